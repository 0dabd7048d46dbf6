//! Krylov methods preconditioned by a sparse factorization: conjugate
//! gradients for the symmetric tangent, GMRES for the unsymmetric tangent
//! of a model with Coulomb friction.
//!
//! **PCG** (Saad, *Iterative methods for sparse linear systems*, 2nd ed.,
//! Alg. 9.1): the factor `L Lᵀ = K₀` of an earlier (or the present,
//! single-precision) tangent preconditions `K`; each iteration costs one
//! product with `K` and one pair of triangular solves.
//!
//! **GMRES** with right preconditioning (Saad, Alg. 9.5, restarted; modified
//! Gram–Schmidt, Givens rotations): solves `K x = b` for
//! `K = K_sym + K_skew`, where `K_sym` is everything the structure assembles
//! into its symmetric pattern and `K_skew` the skew parts of the sliding
//! points' friction blocks (`contact::friction`: `μ ε_N t̂ nᵀ` has no
//! transposed partner). Preconditioned by the factor `M` of `K_sym`, the
//! operator is `K M⁻¹ = I + K_skew M⁻¹`, similar to
//! `I + M^{-1/2} K_skew M^{-1/2}` — the identity plus a skew-symmetric
//! matrix while `M` is positive definite: its eigenvalues `1 ± iσ` lie on a
//! segment of the line `Re z = 1`, away from 0, and GMRES converges at a
//! rate set by the largest `σ` (about `μ/2 · √(ε_N / k_t)`, `k_t` the
//! structure's own tangential stiffness at a sliding point), independent of
//! how many points slide. With right preconditioning the residual GMRES
//! minimizes is the true one, `‖b − K x‖`, which is what the Newton forcing
//! term bounds.

use super::linear::{Cholesky, LinearError, LowerCsc};
use super::nonsymmetric::NonSymmetric;

/// Outcome of a Krylov solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Krylov {
    /// Converged after this many iterations (`rhs` holds the solution).
    Converged(usize),
    /// Stopped after this many iterations (`rhs` holds `b` again).
    NotConverged(usize),
}

impl Krylov {
    /// Iterations made.
    pub fn iterations(self) -> usize {
        match self {
            Krylov::Converged(k) | Krylov::NotConverged(k) => k,
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>()
}

/// Where conjugate gradients stop: at `‖b − A x‖ ≤ tol ‖b‖`, or, once
/// there, on towards `finish ≤ tol` while they have made fewer than
/// `finish_within` iterations in all (a Newton correction predicted to be
/// the last, `solver::newton`: the few iterations more spare a
/// correction). Reaching `tol` is what convergence means.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stop {
    /// The relative residual the solve must reach.
    pub tol: f64,
    /// The relative residual it goes on towards, if within its iterations.
    pub finish: f64,
    /// Most iterations in all while going on towards `finish`.
    pub finish_within: usize,
}

impl Stop {
    /// Stop at `tol`.
    pub(crate) fn at(tol: f64) -> Self {
        Self { tol, finish: tol, finish_within: 0 }
    }
}

/// Preconditioned conjugate gradients for the symmetric matrix (`pattern`,
/// lower-triangle `values`) with the factor in `precond`, from `x₀ = 0`, to
/// `‖b − A x‖ ≤ tol ‖b‖` within `max_iterations` ([`Stop`]). `rhs` holds `b` on entry;
/// on convergence it holds `x`, otherwise `b` unchanged. Stops early on a
/// breakdown (`pᵀ A p ≤ 0`).
pub(crate) fn pcg(
    pattern: &LowerCsc,
    values: &[f64],
    precond: &mut Cholesky,
    rhs: &mut [f64],
    stop: Stop,
    max_iterations: usize,
    work: &mut [Vec<f64>; 5],
) -> Result<Krylov, LinearError> {
    let operator = |p: &[f64], q: &mut [f64]| pattern.mul_symmetric(values, p, q);
    pcg_with(operator, |z| precond.solve_in_place(z), rhs, stop, max_iterations, work)
}

/// Preconditioned conjugate gradients (Saad, Alg. 9.1) for the symmetric
/// operator `q = A p` (`operator(p, q)`) with the preconditioner `z ← M⁻¹ z`
/// (`precond(z)`), from `x₀ = 0`, to `‖b − A x‖ ≤ tol ‖b‖` within
/// `max_iterations` ([`Stop`]: on towards its `finish` once there). `rhs` holds `b` on entry; on convergence it holds `x`,
/// otherwise `b` unchanged. Stops early on a breakdown (`pᵀ A p ≤ 0`). The
/// loop of [`pcg`] and of the bordered systems (`solver::bordered`).
pub(crate) fn pcg_with(
    mut operator: impl FnMut(&[f64], &mut [f64]),
    mut precond: impl FnMut(&mut [f64]) -> Result<(), LinearError>,
    rhs: &mut [f64],
    stop: Stop,
    max_iterations: usize,
    work: &mut [Vec<f64>; 5],
) -> Result<Krylov, LinearError> {
    let n = rhs.len();
    for w in work.iter_mut() {
        w.resize(n, 0.0);
    }
    let [x, r, z, p, q] = work;
    let b_norm = dot(rhs, rhs).sqrt();
    if b_norm == 0.0 {
        return Ok(Krylov::Converged(0));
    }
    x.fill(0.0);
    r.copy_from_slice(rhs);
    z.copy_from_slice(r);
    precond(z)?;
    p.copy_from_slice(z);
    let mut rz = dot(r, z);
    let mut reached = false;
    for k in 1..=max_iterations {
        operator(p, q);
        let pq = dot(p, q);
        if !(pq > 0.0) || !(rz > 0.0) {
            if reached {
                rhs.copy_from_slice(x);
                return Ok(Krylov::Converged(k - 1));
            }
            return Ok(Krylov::NotConverged(k - 1));
        }
        let alpha = rz / pq;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
        }
        // once at `tol`, on towards `finish` (the error in the energy norm
        // falls at every iteration, the residual need not)
        let res = dot(r, r).sqrt();
        reached |= res <= stop.tol * b_norm;
        if reached && (res <= stop.finish * b_norm || k >= stop.finish_within || k == max_iterations) {
            rhs.copy_from_slice(x);
            return Ok(Krylov::Converged(k));
        }
        if k == max_iterations {
            return Ok(Krylov::NotConverged(k));
        }
        z.copy_from_slice(r);
        precond(z)?;
        let rz_new = dot(r, z);
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    Ok(Krylov::NotConverged(max_iterations))
}

/// `y = (A + S) x` for the symmetric `A` (lower triangle `values` on
/// `pattern`) and the unsymmetric rest `skew`.
pub(crate) fn mul_unsymmetric(pattern: &LowerCsc, values: &[f64], skew: &NonSymmetric, x: &[f64], y: &mut [f64]) {
    pattern.mul_symmetric(values, x, y);
    skew.mul_add(x, y);
}

/// Storage of [`gmres`], kept between solves (no allocation per solve once
/// grown): the Krylov basis, the preconditioned basis and the small
/// least-squares problem.
#[derive(Debug, Default)]
pub struct GmresWork {
    /// Orthonormal basis `v_j`.
    basis: Vec<Vec<f64>>,
    /// Preconditioned vectors `z_j = M⁻¹ v_j`.
    z: Vec<Vec<f64>>,
    x: Vec<f64>,
    /// Hessenberg columns `h[j][i]`, `i ≤ j + 1`.
    h: Vec<Vec<f64>>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
}

impl GmresWork {
    /// Vectors of the unknowns' size held for `restart` (for the memory
    /// estimate): `restart + 1` basis vectors, `restart` preconditioned
    /// ones, the iterate.
    pub fn vectors(restart: usize) -> usize {
        2 * restart + 2
    }
}

/// Right-preconditioned restarted GMRES (module docs) for
/// `(A + S) x = b` (`A` symmetric: `pattern`, `values`; `S`: `skew`), with
/// the factor in `precond` applied as `M⁻¹`, from `x₀ = 0`, to
/// `‖b − (A + S) x‖ ≤ tol ‖b‖` within `max_iterations` (restarted every
/// `restart`). `rhs` holds `b` on entry; on convergence it holds `x`,
/// otherwise `b` unchanged.
///
/// The preconditioned vectors `z_j` are kept (the flexible variant, Saad
/// Alg. 9.6), so the iterate is `x₀ + Z y` without a further solve with the
/// factor, and the Arnoldi relation `(A + S) Z = V H̄` holds for the `z_j`
/// actually computed — also when the factor is a single-precision one,
/// whose solve rounds — so the least-squares residual `|g_k|` is the true
/// residual up to round-off, and it is what the stop tests.
#[allow(clippy::too_many_arguments)]
pub fn gmres(
    pattern: &LowerCsc,
    values: &[f64],
    skew: &NonSymmetric,
    precond: &mut Cholesky,
    rhs: &mut [f64],
    tol: f64,
    max_iterations: usize,
    restart: usize,
    work: &mut GmresWork,
) -> Result<Krylov, LinearError> {
    let n = rhs.len();
    let b_norm = dot(rhs, rhs).sqrt();
    if b_norm == 0.0 {
        return Ok(Krylov::Converged(0));
    }
    let m = restart.max(1);
    work.size(n, m);
    let GmresWork { basis, z, x, h, cs, sn, g } = work;
    // r₀ = b (x₀ = 0)
    basis[0].copy_from_slice(rhs);
    let mut beta = b_norm;
    let mut total = 0;
    loop {
        for v in basis[0].iter_mut() {
            *v /= beta;
        }
        g.fill(0.0);
        g[0] = beta;
        let mut k = 0;
        let mut converged = false;
        while k < m && total < max_iterations {
            // z_k = M⁻¹ v_k, v_{k+1} = (A + S) z_k orthogonalized
            z[k].copy_from_slice(&basis[k]);
            precond.solve_in_place(&mut z[k])?;
            let (head, tail) = basis.split_at_mut(k + 1);
            let next = &mut tail[0];
            mul_unsymmetric(pattern, values, skew, &z[k], next);
            // modified Gram–Schmidt
            for (i, v) in head.iter().enumerate() {
                let hij = dot(next, v);
                h[k][i] = hij;
                for (a, b) in next.iter_mut().zip(v) {
                    *a -= hij * b;
                }
            }
            let norm = dot(next, next).sqrt();
            h[k][k + 1] = norm;
            // previous rotations on the new column, then its own
            for i in 0..k {
                let (a, b) = (h[k][i], h[k][i + 1]);
                h[k][i] = cs[i] * a + sn[i] * b;
                h[k][i + 1] = -sn[i] * a + cs[i] * b;
            }
            let (a, b) = (h[k][k], h[k][k + 1]);
            let r = a.hypot(b);
            if !(r > 0.0) || !r.is_finite() {
                // breakdown without progress: (A + S) M⁻¹ is singular here
                break;
            }
            cs[k] = a / r;
            sn[k] = b / r;
            h[k][k] = r;
            h[k][k + 1] = 0.0;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            k += 1;
            total += 1;
            if g[k].abs() <= tol * b_norm || norm == 0.0 {
                converged = true;
                break;
            }
            for v in next.iter_mut() {
                *v /= norm;
            }
        }
        if k == 0 {
            return Ok(Krylov::NotConverged(total));
        }
        add_correction(&h[..k], &g[..k], z, x);
        if !x.iter().all(|v| v.is_finite()) {
            return Ok(Krylov::NotConverged(total));
        }
        if converged {
            rhs.copy_from_slice(x);
            return Ok(Krylov::Converged(total));
        }
        if total >= max_iterations || k < m {
            // out of iterations, or a breakdown without convergence
            return Ok(Krylov::NotConverged(total));
        }
        // restart from the true residual
        let r0 = &mut basis[0];
        mul_unsymmetric(pattern, values, skew, x, r0);
        for (a, b) in r0.iter_mut().zip(rhs.iter()) {
            *a = b - *a;
        }
        beta = dot(r0, r0).sqrt();
        if beta <= tol * b_norm {
            rhs.copy_from_slice(x);
            return Ok(Krylov::Converged(total));
        }
    }
}

impl GmresWork {
    /// Sizes the buffers for `n` unknowns and restart length `m`; `x = 0`.
    fn size(&mut self, n: usize, m: usize) {
        let GmresWork { basis, z, x, h, cs, sn, g } = self;
        for (vs, count) in [(&mut *basis, m + 1), (&mut *z, m)] {
            vs.resize_with(count, Vec::new);
            for v in vs.iter_mut() {
                v.resize(n, 0.0);
            }
        }
        h.resize_with(m, Vec::new);
        for (j, col) in h.iter_mut().enumerate() {
            col.resize(j + 2, 0.0);
        }
        cs.resize(m, 0.0);
        sn.resize(m, 0.0);
        g.resize(m + 1, 0.0);
        x.resize(n, 0.0);
        x.fill(0.0);
    }
}

/// `x += Z y` with `y = H⁻¹ g`, `H` the rotated (upper triangular)
/// Hessenberg columns of the cycle.
fn add_correction(h: &[Vec<f64>], g: &[f64], z: &[Vec<f64>], x: &mut [f64]) {
    let k = h.len();
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|j| h[j][i] * y[j]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    for (yi, zi) in y.iter().zip(z.iter()) {
        for (a, b) in x.iter_mut().zip(zi) {
            *a += yi * b;
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Lower pattern and values of a tridiagonal SPD matrix (diagonal `d`,
    /// off-diagonal −1).
    pub(crate) fn tridiagonal(d: &[f64]) -> (LowerCsc, Vec<f64>) {
        let n = d.len();
        let columns: Vec<Vec<usize>> = (0..n).map(|c| (c..(c + 2).min(n)).collect()).collect();
        let values: Vec<f64> =
            columns.iter().zip(d).flat_map(|(rows, &dc)| [dc, -1.0].into_iter().take(rows.len())).collect();
        (LowerCsc::from_columns(n, &columns), values)
    }

    /// `‖(A + S) x − b‖` for the symmetric `A` (lower `v` on `p`) and `S`.
    pub(crate) fn residual(p: &LowerCsc, v: &[f64], s: &NonSymmetric, x: &[f64], b: &[f64]) -> f64 {
        let mut y = vec![0.0; b.len()];
        mul_unsymmetric(p, v, s, x, &mut y);
        y.iter().zip(b).map(|(a, c)| (a - c) * (a - c)).sum::<f64>().sqrt()
    }

    /// The skew part of friction blocks at `points` pairs of neighbouring
    /// unknowns: `±σ` between `2i` and `2i + 1` (as `(t nᵀ − n tᵀ)/2`).
    fn skew_pairs(points: &[usize], sigma: f64) -> NonSymmetric {
        let mut s = NonSymmetric::default();
        for &i in points {
            s.push_entry(i, i + 1, sigma);
            s.push_entry(i + 1, i, -sigma);
        }
        s
    }

    /// PCG without a preconditioner on a tridiagonal SPD matrix: to `1e-2`
    /// it stops at the first iteration below it; asked to go on towards
    /// `1e-10` it goes on and reaches it (an independent product checks the
    /// residual), and within a budget of two more iterations it stops after
    /// exactly those, still converged. A stop that ignores `finish`, or
    /// that gives up the `tol` already reached, fails.
    #[test]
    fn pcg_goes_on_towards_its_finish_only_within_its_budget() {
        let n = 200;
        let d: Vec<f64> = (0..n).map(|i| 2.1 + (i % 7) as f64).collect();
        let (pattern, values) = tridiagonal(&d);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let none = NonSymmetric::default();
        let run = |stop: Stop| {
            let mut x = b.clone();
            let mut work: [Vec<f64>; 5] = Default::default();
            let op = |p: &[f64], q: &mut [f64]| pattern.mul_symmetric(&values, p, q);
            let out = pcg_with(op, |_| Ok(()), &mut x, stop, 500, &mut work).unwrap();
            (out, residual(&pattern, &values, &none, &x, &b) / bn)
        };
        let (plain, r_plain) = run(Stop::at(1e-2));
        let Krylov::Converged(k) = plain else { panic!("{plain:?}") };
        assert!(r_plain <= 1e-2 && k >= 3, "{k} {r_plain:e}");
        let (far, r_far) = run(Stop { tol: 1e-2, finish: 1e-10, finish_within: 500 });
        assert!(matches!(far, Krylov::Converged(m) if m > k + 2), "{far:?}");
        assert!(r_far <= 1e-10, "{r_far:e}");
        let (short, r_short) = run(Stop { tol: 1e-2, finish: 1e-10, finish_within: k + 2 });
        assert_eq!(short, Krylov::Converged(k + 2));
        assert!(r_short <= 1e-2 && r_short > 1e-10, "{r_short:e}");
    }

    /// The symmetric part's own factor preconditions `A + S` with `S` of
    /// rank 2k: GMRES must converge in at most 2k + 1 iterations (exact
    /// arithmetic: the Krylov space of `I + S M⁻¹` has dimension ≤ rank + 1)
    /// and the solution must satisfy the unsymmetric system, checked by an
    /// independent product. A wrong sign of the skew product (the method
    /// solving `A − S` or `A` alone) leaves a residual of order ‖S x‖.
    #[test]
    fn gmres_with_the_symmetric_factor_solves_a_low_rank_skew_system() {
        let n = 300;
        let (pattern, values) = tridiagonal(&vec![2.5; n]);
        let skew = skew_pairs(&[10, 50, 51, 120, 200, 290], 0.8);
        let mut chol = Cholesky::analyze(&pattern).unwrap();
        chol.factorize(&values).unwrap();
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin() + 0.5).collect();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut x = b.clone();
        let mut work = GmresWork::default();
        let out = gmres(&pattern, &values, &skew, &mut chol, &mut x, 1e-12, 100, 50, &mut work).unwrap();
        let Krylov::Converged(k) = out else { panic!("{out:?}") };
        assert!(k <= 2 * 6 + 1, "{k} iterations for a rank-12 perturbation");
        let r = residual(&pattern, &values, &skew, &x, &b);
        assert!(r <= 1e-11 * bn, "residual {r:e}");
        // the same x does not solve the symmetric system: the skew part mattered
        let r_sym = residual(&pattern, &values, &NonSymmetric::default(), &x, &b);
        assert!(r_sym > 1e-3 * bn, "{r_sym:e}");
    }

    /// Restarts: with a restart length below the iterations needed, GMRES
    /// must still reach the tolerance (restarted from the true residual),
    /// and give `b` back unchanged when it cannot within the limit.
    #[test]
    fn restarted_gmres_converges_and_a_failure_leaves_b() {
        let n = 200;
        let (pattern, values) = tridiagonal(&vec![2.2; n]);
        // an old factor (of another matrix): many iterations needed
        let (_, v0) = tridiagonal(&vec![3.5; n]);
        let mut chol = Cholesky::analyze(&pattern).unwrap();
        chol.factorize(&v0).unwrap();
        let skew = skew_pairs(&(0..40).map(|i| 4 * i).collect::<Vec<_>>(), 0.3);
        let b: Vec<f64> = (0..n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut work = GmresWork::default();
        let mut x = b.clone();
        let out = gmres(&pattern, &values, &skew, &mut chol, &mut x, 1e-10, 400, 5, &mut work).unwrap();
        assert!(matches!(out, Krylov::Converged(k) if k > 5), "{out:?}");
        assert!(residual(&pattern, &values, &skew, &x, &b) <= 1e-10 * bn);
        let mut y = b.clone();
        let out = gmres(&pattern, &values, &skew, &mut chol, &mut y, 1e-14, 3, 5, &mut work).unwrap();
        assert_eq!(out, Krylov::NotConverged(3));
        assert_eq!(y, b);
    }
}
