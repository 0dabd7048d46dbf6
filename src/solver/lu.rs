//! Sparse unsymmetric direct solver: faer's sparse LU with partial pivoting,
//! for tangents that are not symmetric (Coulomb friction: the sliding
//! points couple their tangential force to the normal gap, `μ ε_N t̂ nᵀ`,
//! with no transposed counterpart).
//!
//! The structure assembles its tangent into the lower triangle of a
//! symmetric pattern ([`LowerCsc`]); the unsymmetric matrix lives on the
//! *full* pattern `P = L ∪ Lᵀ` (every stored `(r, c)` and its mirror
//! `(c, r)`), so that a symmetric part is copied from the lower values
//! ([`SparseLu::fill_symmetric`]) and the unsymmetric terms are then added
//! entry by entry ([`SparseLu::add`]) — they only ever fall on positions of
//! `P`, because every unsymmetric term couples DOFs that a symmetric term
//! already couples.
//!
//! The symbolic analysis (COLAMD column ordering, supernodal structure) is
//! done once for `P`; each Newton iteration refactorizes the numbers
//! (`factorize_numeric_lu`, row pivoting chosen anew) and solves. faer's LU
//! always orders the columns itself (COLAMD), so the structure's METIS
//! numbering only serves the symmetric solver.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{LuRef, LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

use super::linear::{LinearError, LowerCsc};

/// A reusable sparse LU factorization of matrices on the full pattern of a
/// symmetric [`LowerCsc`] pattern.
pub struct SparseLu {
    n: usize,
    /// Full pattern: column pointers and sorted row indices.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// For each entry of the lower pattern: its position in the full
    /// pattern and the position of its mirror (equal on the diagonal).
    mirror: Vec<(usize, usize)>,
    /// Values on the full pattern.
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factored: bool,
    mem: Option<MemBuffer>,
    req: StackReq,
    par: Par,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLu").field("n", &self.n).field("nnz", &self.row_idx.len()).finish()
    }
}

impl SparseLu {
    /// Builds the full pattern of `lower` and its symbolic LU analysis.
    pub fn analyze(lower: &LowerCsc) -> Result<Self, LinearError> {
        let n = lower.n;
        let (up_ptr, up_idx) = lower.transpose();
        // column c of the full pattern: the upper rows (r < c, from the
        // transpose, which stores for column c the rows r with (c, r) lower),
        // then the lower rows (r ≥ c); both sorted, so their concatenation is
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(2 * lower.nnz());
        col_ptr.push(0);
        for c in 0..n {
            row_idx.extend(up_idx[up_ptr[c]..up_ptr[c + 1]].iter().copied().filter(|&r| r != c));
            row_idx.extend(lower.row_idx[lower.col_ptr[c]..lower.col_ptr[c + 1]].iter().map(|&r| r as usize));
            col_ptr.push(row_idx.len());
        }
        let find = |r: usize, c: usize| -> Option<usize> {
            let (a, b) = (col_ptr[c], col_ptr[c + 1]);
            row_idx[a..b].binary_search(&r).ok().map(|k| a + k)
        };
        let mut mirror = Vec::with_capacity(lower.nnz());
        for c in 0..n {
            for k in lower.col_ptr[c]..lower.col_ptr[c + 1] {
                let r = lower.row_idx[k] as usize;
                let (Some(p), Some(q)) = (find(r, c), find(c, r)) else {
                    return Err(LinearError::Symbolic(format!("entry ({r}, {c}) missing from the full pattern")));
                };
                mirror.push((p, q));
            }
        }
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_lu(sym, LuSymbolicParams::default())
            .map_err(|e| LinearError::Symbolic(format!("{e:?}")))?;
        let par = if rayon::current_num_threads() > 1 { Par::rayon(0) } else { Par::Seq };
        let req = symbolic
            .factorize_numeric_lu_scratch::<f64>(par, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, par));
        let values = vec![0.0; row_idx.len()];
        Ok(Self {
            n,
            col_ptr,
            row_idx,
            mirror,
            values,
            symbolic,
            numeric: NumericLu::new(),
            factored: false,
            mem: None,
            req,
            par,
        })
    }

    /// Dimension.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Stored entries of the full pattern.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry `(row, col)` in the full pattern, if stored.
    pub fn find(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    /// Sets the values to the symmetric matrix whose lower triangle is
    /// `lower` (in the order of the lower pattern's entries).
    pub fn fill_symmetric(&mut self, lower: &[f64]) {
        for (&(p, q), &v) in self.mirror.iter().zip(lower) {
            self.values[p] = v;
            self.values[q] = v;
        }
    }

    /// Adds `v` to entry `(row, col)`; false (and nothing added) if the
    /// entry is not in the pattern.
    pub fn add(&mut self, row: usize, col: usize, v: f64) -> bool {
        match self.find(row, col) {
            Some(p) => {
                self.values[p] += v;
                true
            }
            None => false,
        }
    }

    /// Current values on the full pattern (column-major, rows sorted).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Mutable values on the full pattern.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Column pointers and row indices of the full pattern.
    pub fn structure(&self) -> (&[usize], &[usize]) {
        (&self.col_ptr, &self.row_idx)
    }

    /// `y = A x` with the current values.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for c in 0..self.n {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * x[c];
            }
        }
    }

    /// Numeric LU factorization of the current values.
    pub fn factorize(&mut self) -> Result<(), LinearError> {
        let sym = SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx);
        let a = SparseColMatRef::new(sym, &self.values);
        self.factored = false;
        let req = self.req;
        let mem = self.mem.get_or_insert_with(|| MemBuffer::new(req));
        let stack = MemStack::new(mem);
        self.symbolic
            .factorize_numeric_lu(&mut self.numeric, a, self.par, stack, Default::default())
            .map_err(|_| LinearError::Singular)?;
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds `b` on entry, `x` on exit).
    /// Fails with [`LinearError::Singular`] if nothing is factored or the
    /// solution is not finite (a zero pivot).
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let (true, Some(mem)) = (self.factored, self.mem.as_mut()) else { return Err(LinearError::Singular) };
        let stack = MemStack::new(mem);
        let x = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
        LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(Conj::No, x, self.par, stack);
        if rhs.iter().all(|v| v.is_finite()) { Ok(()) } else { Err(LinearError::Singular) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tridiagonal lower pattern with an extra far entry (row 7, col 2).
    fn pattern(n: usize) -> LowerCsc {
        let columns: Vec<Vec<usize>> = (0..n)
            .map(|c| {
                let mut rows: Vec<usize> = (c..(c + 2).min(n)).collect();
                if c == 2 && n > 7 {
                    rows.push(7);
                }
                rows
            })
            .collect();
        LowerCsc::from_columns(n, &columns)
    }

    /// An unsymmetric matrix (convection–diffusion-like: −1.5 below, −0.5
    /// above the diagonal, and an entry at (2, 7) only) is solved to round-off:
    /// the exact solution is chosen and its right-hand side computed by
    /// [`SparseLu::mul`], which is checked against a dense product.
    #[test]
    fn solves_an_unsymmetric_system() {
        let n = 12;
        let pat = pattern(n);
        let mut lu = SparseLu::analyze(&pat).unwrap();
        // the full pattern holds each off-diagonal entry twice
        assert_eq!(lu.nnz(), 2 * pat.nnz() - n);
        lu.fill_symmetric(&vec![0.0; pat.nnz()]);
        let mut dense = vec![vec![0.0; n]; n];
        let mut set = |lu: &mut SparseLu, r: usize, c: usize, v: f64| {
            assert!(lu.add(r, c, v), "({r}, {c}) in the pattern");
            dense[r][c] += v;
        };
        for i in 0..n {
            set(&mut lu, i, i, 3.0);
            if i + 1 < n {
                set(&mut lu, i + 1, i, -1.5);
                set(&mut lu, i, i + 1, -0.5);
            }
        }
        set(&mut lu, 2, 7, 0.75);
        assert!(!lu.add(3, 9, 1.0), "(3, 9) is not in the pattern");
        let x_exact: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
        let mut b = vec![0.0; n];
        lu.mul(&x_exact, &mut b);
        for i in 0..n {
            let d: f64 = (0..n).map(|j| dense[i][j] * x_exact[j]).sum();
            assert!((d - b[i]).abs() < 1e-14, "row {i}: {d} vs {}", b[i]);
        }
        lu.factorize().unwrap();
        lu.solve_in_place(&mut b).unwrap();
        for (a, e) in b.iter().zip(&x_exact) {
            assert!((a - e).abs() < 1e-13, "{a} vs {e}");
        }
    }

    /// `fill_symmetric` mirrors every lower entry.
    #[test]
    fn fills_both_triangles() {
        let pat = pattern(9);
        let mut lu = SparseLu::analyze(&pat).unwrap();
        let lower: Vec<f64> = (0..pat.nnz()).map(|k| k as f64 + 1.0).collect();
        lu.fill_symmetric(&lower);
        for c in 0..pat.n {
            for k in pat.col_ptr[c]..pat.col_ptr[c + 1] {
                let r = pat.row_idx[k] as usize;
                assert_eq!(lu.values()[lu.find(r, c).unwrap()], lower[k]);
                assert_eq!(lu.values()[lu.find(c, r).unwrap()], lower[k]);
            }
        }
    }

    /// A singular matrix (a zero column) is reported, not solved.
    #[test]
    fn a_singular_matrix_is_an_error() {
        let pat = pattern(5);
        let mut lu = SparseLu::analyze(&pat).unwrap();
        let lower: Vec<f64> = pat.row_idx.iter().map(|_| 0.0).collect();
        lu.fill_symmetric(&lower);
        for i in 0..4 {
            lu.add(i, i, 1.0);
        }
        let mut b = vec![1.0; 5];
        let r = lu.factorize().and_then(|()| lu.solve_in_place(&mut b));
        assert!(matches!(r, Err(LinearError::Singular)), "{r:?}");
    }
}
