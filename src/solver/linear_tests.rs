//! Tests of `solver::linear` (a file of their own: the module is near the
//! length limit).

use super::*;

/// 1D Laplacian with a Dirichlet end: tridiagonal SPD, exact solution known.
#[test]
fn solves_a_tridiagonal_system() {
    let n = 50;
    let columns: Vec<Vec<usize>> = (0..n).map(|c| (c..(c + 2).min(n)).collect()).collect();
    let vals: Vec<f64> = columns.iter().flat_map(|rows| [2.0, -1.0].into_iter().take(rows.len())).collect();
    let pat = LowerCsc::from_columns(n, &columns);
    let mut chol = Cholesky::analyze(&pat).unwrap();
    chol.factorize(&vals).unwrap();
    let x_exact: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut b = vec![0.0; n];
    pat.mul_symmetric(&vals, &x_exact, &mut b);
    chol.solve_in_place(&mut b).unwrap();
    for (a, e) in b.iter().zip(&x_exact) {
        assert!((a - e).abs() < 1e-12);
    }
    // an indefinite matrix falls back to LDLᵀ and still solves
    let mut ind = vals.clone();
    ind[0] = -2.0;
    chol.factorize(&ind).unwrap();
    // one negative eigenvalue: the diagonal -2 couples to the rest by -1
    // only, so the matrix is congruent to diag(-2, positive definite)
    assert_eq!(chol.negative_pivots(), Some(1));
    pat.mul_symmetric(&ind, &x_exact, &mut b);
    chol.solve_in_place(&mut b).unwrap();
    for (a, e) in b.iter().zip(&x_exact) {
        assert!((a - e).abs() < 1e-9);
    }
}

/// Inertia: the 5-point Laplacian on an m × m grid shifted by −σ has
/// as many negative pivots as Laplacian eigenvalues
/// `4 − 2 cos(iπ/(m+1)) − 2 cos(jπ/(m+1))` below σ (Sylvester's law;
/// the eigenvalues in closed form). The banded fill makes faer's
/// factor supernodal at m = 100 and simplicial at m = 8: both storage
/// kinds are read.
#[test]
fn negative_pivots_count_the_eigenvalues_below_the_shift() {
    for (m, supernodal) in [(8, false), (100, true)] {
        let n = m * m;
        let columns: Vec<Vec<usize>> = (0..n)
            .map(|c| [c, c + 1, c + m].into_iter().filter(|&r| r < n && (r != c + 1 || r % m != 0)).collect())
            .collect();
        let pat = LowerCsc::from_columns(n, &columns);
        let mut chol = Cholesky::analyze(&pat).unwrap();
        assert_eq!(matches!(chol.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)), supernodal);
        let h = std::f64::consts::PI / (m + 1) as f64;
        for sigma in [0.0, 0.5, 1.3, 2.9] {
            let vals: Vec<f64> = columns
                .iter()
                .flat_map(|rows| rows.iter().map(|&r| if r == rows[0] { 4.0 - sigma } else { -1.0 }))
                .collect();
            chol.factorize(&vals).unwrap();
            let below = (1..=m)
                .flat_map(|i| (1..=m).map(move |j| 4.0 - 2.0 * (i as f64 * h).cos() - 2.0 * (j as f64 * h).cos()))
                .filter(|&l| l < sigma)
                .count();
            assert_eq!(chol.negative_pivots(), Some(below), "m {m}, shift {sigma}");
        }
    }
}

/// The symmetric product against a dense one, on columns with 0 to 12
/// entries below the diagonal (the four-way split and its remainder
/// of 0–3 entries all occur) and one column without its diagonal.
#[test]
fn symmetric_product_equals_the_dense_product() {
    let n = 13;
    let entry = |r: usize, c: usize| 1.0 + (r * 7 + c * 3) as f64 / 10.0;
    // column c holds the diagonal (not column 6) and every row r > c with
    // (r + c) % 3 != 1, and every row of the first four (12, 11, 10 and 9
    // entries below)
    let keep = |r: usize, c: usize| if r == c { c != 6 } else { c < 4 || (r + c) % 3 != 1 };
    let columns: Vec<Vec<usize>> = (0..n).map(|c| (c..n).filter(|&r| keep(r, c)).collect()).collect();
    let pat = LowerCsc::from_columns(n, &columns);
    let values: Vec<f64> =
        columns.iter().enumerate().flat_map(|(c, rows)| rows.iter().map(move |&r| entry(r, c))).collect();
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() + 0.5).collect();
    let mut y = vec![f64::NAN; n];
    pat.mul_symmetric(&values, &x, &mut y);
    for (i, yi) in y.iter().enumerate() {
        let dense: f64 = (0..n).filter(|&j| keep(i.max(j), i.min(j))).map(|j| entry(i.max(j), i.min(j)) * x[j]).sum();
        assert!((yi - dense).abs() <= 1e-13 * dense.abs().max(1.0), "row {i}: {yi} against {dense}");
    }
    let below: Vec<usize> =
        columns.iter().enumerate().map(|(c, rows)| rows.iter().filter(|&&r| r > c).count()).collect();
    assert!((0..4).all(|m| below.iter().any(|&b| b >= 4 && b % 4 == m)), "{below:?}");
}

/// The 5-point graph of an `m × m` grid (sorted adjacency, no self loops).
fn grid(m: usize) -> Vec<Vec<usize>> {
    (0..m * m)
        .map(|v| {
            let (i, j) = (v % m, v / m);
            let mut l = Vec::new();
            if j > 0 {
                l.push(v - m);
            }
            if i > 0 {
                l.push(v - 1);
            }
            if i + 1 < m {
                l.push(v + 1);
            }
            if j + 1 < m {
                l.push(v + m);
            }
            l
        })
        .collect()
}

#[test]
fn nested_dissection_is_a_permutation() {
    let m = 10;
    let mut p = nested_dissection(&grid(m)).unwrap();
    p.sort_unstable();
    assert_eq!(p, (0..m * m).collect::<Vec<_>>());
}

/// METIS's random draws come from the C library's `rand()`, whose state
/// belongs to the whole process (GKlib's `random.c` without `USE_GKRAND`,
/// as metis-sys builds it: `srand(4321)` when an ordering starts, then
/// `rand()` throughout): two orderings on two threads at once would
/// interleave their draws and number the same graph differently, and a
/// solution then differs in its rounding — its Newton history in its
/// last digits (`nested_dissection` serializes them). Orderings made
/// on two threads at once equal the one made alone.
#[test]
fn orderings_made_at_once_on_two_threads_equal_the_one_made_alone() {
    let adj = grid(40);
    let alone = nested_dissection(&adj).unwrap();
    let start = std::sync::Barrier::new(2);
    let differing: usize = std::thread::scope(|s| {
        let workers: Vec<_> = (0..2)
            .map(|_| {
                s.spawn(|| {
                    start.wait();
                    (0..40).filter(|_| nested_dissection(&adj).unwrap() != alone).count()
                })
            })
            .collect();
        workers.into_iter().map(|w| w.join().unwrap()).sum()
    });
    assert_eq!(differing, 0, "{differing} of 80 concurrent orderings differ from the one made alone");
}

/// `LowerCsc::compress` keeps the non-zero entries only, and its product,
/// its scaled addition and its diagonal are those of the full matrix (a
/// dropped or misplaced entry changes the product; an entry kept at the
/// wrong position changes the addition).
#[test]
fn a_compressed_matrix_acts_as_the_full_one() {
    let n = 7;
    let columns: Vec<Vec<usize>> = (0..n).map(|c| (c..n).collect()).collect();
    let pat = LowerCsc::from_columns(n, &columns);
    // zeros wherever row and column differ in parity (as the mass couples
    // only equal components), and one zero diagonal
    let mut values = Vec::new();
    for (c, rows) in columns.iter().enumerate() {
        for &r in rows {
            let v = if (r + c) % 2 == 1 || (r == 3 && c == 3) { 0.0 } else { 1.0 + (r * n + c) as f64 * 0.1 };
            values.push(v);
        }
    }
    let m = pat.compress(&values);
    assert_eq!(m.values.len(), values.iter().filter(|&&v| v != 0.0).count());
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
    let (mut full, mut compact) = (vec![0.0; n], vec![0.0; n]);
    pat.mul_symmetric(&values, &x, &mut full);
    m.mul(&x, &mut compact);
    for (a, b) in full.iter().zip(&compact) {
        assert!((a - b).abs() < 1e-14 * a.abs().max(1.0), "{full:?} against {compact:?}");
    }
    let mut target: Vec<f64> = (0..values.len()).map(|k| k as f64).collect();
    m.add_scaled_to(2.5, &mut target);
    for (k, (t, v)) in target.iter().zip(&values).enumerate() {
        assert_eq!(*t, k as f64 + 2.5 * v);
    }
    for c in 0..n {
        assert_eq!(m.diagonal(c), values[pat.find(c, c).unwrap()]);
    }
}
