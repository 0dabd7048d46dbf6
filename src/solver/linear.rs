//! Sparse symmetric direct solver: faer's supernodal Cholesky on a matrix
//! already numbered in a METIS nested-dissection order.
//!
//! The symbolic analysis (elimination tree, supernodes, storage of `L`) is
//! done once per sparsity pattern; each Newton iteration only refactorizes
//! the numbers in place (`factorize_numeric_llt`) and solves. The
//! fill-reducing ordering is applied by the equation numbering itself (see
//! `nested_dissection` and `crate::assembly`), so faer runs with the
//! identity ordering and no permutation copies.
//!
//! If `LLᵀ` breaks down (a tangent that is not positive definite, e.g. a
//! perfectly plastic mechanism or a rigid-body mode left free), the same
//! symbolic structure is refactorized as `LDLᵀ`.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Errors of the linear solver.
#[derive(Debug, thiserror::Error)]
pub enum LinearError {
    /// The symbolic analysis failed (out of memory or invalid pattern).
    #[error("sparse symbolic analysis failed: {0}")]
    Symbolic(String),
    /// The numeric factorization failed: the tangent is singular.
    #[error("the stiffness matrix is singular (a rigid-body motion is not restrained, or the structure has collapsed)")]
    Singular,
    /// METIS failed.
    #[error("METIS nested dissection failed with status {0}")]
    Metis(i32),
    /// The factor could not be allocated (bytes).
    #[error("out of memory: allocating the Cholesky factor ({0} bytes) failed")]
    OutOfMemory(usize),
    /// GMRES (a model with friction) did not converge within this many
    /// iterations with the factor of the present tangent's symmetric part.
    #[error(
        "the unsymmetric (frictional) tangent was not solved within {0} GMRES iterations preconditioned by its \
         symmetric part: the friction coupling dominates the structure's stiffness at the sliding points (a lower \
         contact penalty or friction coefficient, or smaller increments, may help)"
    )]
    KrylovStalled(usize),
    /// The problem rejected the correction (it left the range where the
    /// model means anything); the message says why.
    #[error("{0}")]
    Rejected(String),
}

/// Lower triangle of a symmetric sparse matrix in compressed-column form
/// (rows sorted within each column, diagonal first).
#[derive(Debug, Clone)]
pub struct LowerCsc {
    /// Dimension.
    pub n: usize,
    /// Column pointers (`n + 1`).
    pub(crate) col_ptr: Vec<usize>,
    /// Row indices, `row ≥ col` (32 bits: the product of conjugate gradients
    /// reads them at every iteration, and a quarter less memory traffic is a
    /// quarter less time there; equations are far fewer than 2³²).
    pub(crate) row_idx: Vec<u32>,
}

impl LowerCsc {
    /// The pattern with these sorted row lists per column.
    ///
    /// # Panics
    /// With 2³² equations or more (a model far beyond any memory: the
    /// model's size check refuses it first).
    pub(crate) fn from_columns(n: usize, columns: &[Vec<usize>]) -> Self {
        assert!(u32::try_from(n).is_ok(), "{n} equations: row indices are 32-bit");
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(columns.iter().map(Vec::len).sum());
        col_ptr.push(0);
        for c in columns {
            row_idx.extend(c.iter().map(|&r| r as u32));
            col_ptr.push(row_idx.len());
        }
        Self { n, col_ptr, row_idx }
    }

    /// Position of entry `(row, col)` with `row ≥ col`, if stored.
    pub fn find(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        let row = u32::try_from(row).ok()?;
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    /// Structure of the transpose (the upper triangle): `(col_ptr, row_idx)`.
    pub fn transpose(&self) -> (Vec<usize>, Vec<usize>) {
        let mut count = vec![0usize; self.n + 1];
        for &r in &self.row_idx {
            count[r as usize + 1] += 1;
        }
        for i in 0..self.n {
            count[i + 1] += count[i];
        }
        let col_ptr = count.clone();
        let mut next = count;
        let mut row_idx = vec![0; self.row_idx.len()];
        for c in 0..self.n {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                let r = self.row_idx[k] as usize;
                row_idx[next[r]] = c;
                next[r] += 1;
            }
        }
        (col_ptr, row_idx)
    }

    /// The entries of `values` (on this pattern) that are not zero, as a
    /// matrix on a pattern of its own, with each kept entry's position in
    /// `values`. A consistent mass couples a node's displacement only with
    /// the same component of its neighbours' (`dynamics::mass`): two thirds
    /// of the structure's pattern hold zeros of `M`, which its products and
    /// its additions to the tangent then skip.
    pub(crate) fn compress(&self, values: &[f64]) -> Compressed {
        let mut columns = vec![Vec::new(); self.n];
        let (mut kept, mut at) = (Vec::new(), Vec::new());
        for (c, column) in columns.iter_mut().enumerate() {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                if values[k] != 0.0 {
                    column.push(self.row_idx[k] as usize);
                    kept.push(values[k]);
                    at.push(k);
                }
            }
        }
        Compressed { pattern: Self::from_columns(self.n, &columns), values: kept, at }
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// `y = A x` using the lower triangle as a symmetric matrix.
    pub(crate) fn mul_symmetric(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (c, cols) in self.col_ptr.windows(2).enumerate() {
            let (first, end) = (cols[0], cols[1]);
            // the diagonal, when stored, comes first (rows sorted, row ≥ col)
            let (start, diag) = if first < end && self.row_idx[first] as usize == c {
                (first + 1, values[first])
            } else {
                (first, 0.0)
            };
            let (rows, vals) = (&self.row_idx[start..end], &values[start..end]);
            let xc = x[c];
            // the column's dot product with x below the diagonal in four
            // independent sums: one running sum would wait on the latency
            // of each addition (4 cycles per entry) instead of on memory
            let mut acc = [0.0; 4];
            let (rows4, rows_rest) = rows.split_at(rows.len() - rows.len() % 4);
            let (vals4, vals_rest) = vals.split_at(rows4.len());
            for (r, v) in rows4.chunks_exact(4).zip(vals4.chunks_exact(4)) {
                for k in 0..4 {
                    let r = r[k] as usize;
                    y[r] += v[k] * xc;
                    acc[k] += v[k] * x[r];
                }
            }
            for (&r, &v) in rows_rest.iter().zip(vals_rest) {
                let r = r as usize;
                y[r] += v * xc;
                acc[0] += v * x[r];
            }
            y[c] += diag * xc + (acc[0] + acc[1]) + (acc[2] + acc[3]);
        }
    }
}

/// A symmetric matrix's non-zero entries on a pattern of their own
/// ([`LowerCsc::compress`]).
#[derive(Debug, Clone)]
pub(crate) struct Compressed {
    /// The entries' pattern.
    pub pattern: LowerCsc,
    /// Their values, in the order of `pattern`.
    pub values: Vec<f64>,
    /// Each entry's position on the pattern it was compressed from.
    pub at: Vec<usize>,
}

impl Compressed {
    /// `y = A x`.
    pub(crate) fn mul(&self, x: &[f64], y: &mut [f64]) {
        self.pattern.mul_symmetric(&self.values, x, y);
    }

    /// `target[at] += factor · values`: the matrix scaled, added to one
    /// on the pattern it was compressed from.
    pub(crate) fn add_scaled_to(&self, factor: f64, target: &mut [f64]) {
        for (&k, &v) in self.at.iter().zip(&self.values) {
            target[k] += factor * v;
        }
    }

    /// The diagonal entry of column `c` (zero if not stored).
    pub(crate) fn diagonal(&self, c: usize) -> f64 {
        let first = self.pattern.col_ptr[c];
        if first < self.pattern.col_ptr[c + 1] && self.pattern.row_idx[first] as usize == c {
            self.values[first]
        } else {
            0.0
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Llt,
    /// `LLᵀ` stored in single precision (a preconditioner, not a solver).
    Llt32,
    Ldlt,
}

/// When the factor is stored and computed by supernodes (dense column
/// blocks, BLAS-3) rather than column by column: faer picks supernodal
/// when the factorization's flops per entry of `L` exceed this factor
/// times 40 (faer's `CHOLESKY_SUPERNODAL_RATIO_FACTOR`), so here above 10
/// instead of faer's 40. A CUF stiffness couples every node's 3 DOF with
/// whole sections: its factor is denser per column than the meshes faer
/// tuned its default on, and the supernodal factorization won on every
/// example whose ratio lies between 10 and 40 (one thread, median of 3,
/// ms per factorization simplicial → supernodal: the laminate drop
/// weights' 2,928 DOF at ratio 39.6, 9.2 → 4.0; bending_compact_4L9_quarter
/// 39.7, 2.81 → 0.33; column_buckling 39.5, 4.02 → 0.87;
/// notched_strip_medium 25.3, 1.14 → 0.52; notched_strip_coarse 18.7,
/// 0.20 → 0.10; rod_impact 16.5, 0.78 → 0.43; arch_snap_through 16.4,
/// 1.29 → 0.56; measured when this was set, the commit's message). Below
/// 10 (a chain, a very sparse lattice) the factor stays simplicial.
const SUPERNODAL: SupernodalThreshold = SupernodalThreshold(0.25);

/// A reusable sparse Cholesky factorization for a fixed pattern.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    /// The pattern in faer's form, checked once (not at every factorization).
    pattern: SymbolicSparseColMat<usize>,
    /// The factor's values: `f64`, or in single precision the `f32` factor
    /// in the first half of the same bytes and the rounded matrix in the
    /// second (`nnz(L) ≥ nnz(A)`), so both precisions take the same memory.
    l_values: Vec<f64>,
    /// Right-hand side rounded to `f32` (single-precision solves).
    x_single: Vec<f32>,
    mem: Option<MemBuffer>,
    req: StackReq,
    kind: Option<Kind>,
    par: Par,
}

impl std::fmt::Debug for Cholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cholesky").field("n", &self.pattern.nrows()).field("nnz_l", &self.factor_nnz()).finish()
    }
}

impl Cholesky {
    /// Symbolic analysis of `pattern` (identity ordering: the caller numbers
    /// the equations in a fill-reducing order).
    pub(crate) fn analyze(pattern: &LowerCsc) -> Result<Self, LinearError> {
        // With the identity ordering faer's symbolic analysis reads the upper
        // triangle, so it gets the transposed structure; the numeric
        // factorization then takes our lower triangle directly.
        let upper = pattern.transpose();
        let sym = SymbolicSparseColMatRef::new_checked(pattern.n, pattern.n, &upper.0, None, &upper.1);
        let symbolic = factorize_symbolic_cholesky(
            sym,
            Side::Upper,
            SymmetricOrdering::Identity,
            CholeskySymbolicParams { supernodal_flop_ratio_threshold: SUPERNODAL, ..Default::default() },
        )
        .map_err(|e| LinearError::Symbolic(format!("{e:?}")))?;
        // faer's parallel supernodal factorization lost to the sequential one on
        // the 2-thread CI machine (tube 28 L9: 234 vs 202 ms quiet, 351 vs
        // 226 ms busy, `cufem bench`): parallel only from four threads on
        let par = if rayon::current_num_threads() >= 4 { Par::rayon(0) } else { Par::Seq };
        let req = symbolic
            .factorize_numeric_llt_scratch::<f64>(par, Default::default())
            .or(symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()))
            .or(symbolic.solve_in_place_scratch::<f64>(1, par))
            .or(symbolic.factorize_numeric_llt_scratch::<f32>(par, Default::default()))
            .or(symbolic.solve_in_place_scratch::<f32>(1, par));
        // the factor and the scratch are allocated at the first factorization,
        // after the caller has checked that they fit (see `crate::size`)
        Ok(Self {
            symbolic,
            pattern: SymbolicSparseColMat::new_checked(
                pattern.n,
                pattern.n,
                pattern.col_ptr.clone(),
                None,
                pattern.row_idx.iter().map(|&r| r as usize).collect(),
            ),
            l_values: Vec::new(),
            x_single: Vec::new(),
            mem: None,
            req,
            kind: None,
            par,
        })
    }

    /// True if the present factor is `LLᵀ` (positive definite matrix).
    pub(crate) fn is_llt(&self) -> bool {
        matches!(self.kind, Some(Kind::Llt | Kind::Llt32))
    }

    /// True if the present factor is single precision: its solves are
    /// approximate (relative error about `κ · 6e-8`), a preconditioner.
    pub(crate) fn is_single(&self) -> bool {
        self.kind == Some(Kind::Llt32)
    }

    /// Floating-point operations of one numeric factorization, from the
    /// symbolic structure: per supernode of `w` columns with `h` rows below
    /// its diagonal block, `w³/3 + w² h + w h²` (the dense Cholesky of the
    /// block, the triangular solve below it, the update of the ancestors);
    /// per column of a simplicial factor with `c` entries, `c²`.
    pub(crate) fn factor_flops(&self) -> f64 {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sn) => {
                let (begin, end, ptr) = (sn.supernode_begin(), sn.supernode_end(), sn.col_ptr_for_row_idx());
                (0..sn.n_supernodes())
                    .map(|s| {
                        let w = (end[s] - begin[s]) as f64;
                        let h = (ptr[s + 1] - ptr[s]) as f64;
                        w * w * w / 3.0 + w * w * h + w * h * h
                    })
                    .sum()
            }
            SymbolicCholeskyRaw::Simplicial(sp) => {
                sp.col_ptr().windows(2).map(|c| ((c[1] - c[0]) as f64).powi(2)).sum()
            }
        }
    }

    /// Negative pivots of the present factor: by Sylvester's law of
    /// inertia the number of negative eigenvalues of the factored matrix
    /// (0 for an `LLᵀ` factor; the negative entries of `D` for `LDLᵀ`,
    /// which faer computes without pivoting or regularization here, so
    /// `D` is congruent to the matrix). `None` before the first
    /// factorization.
    pub fn negative_pivots(&self) -> Option<usize> {
        match self.kind? {
            Kind::Llt | Kind::Llt32 => Some(0),
            Kind::Ldlt => Some(self.ldlt_diagonal().iter().filter(|d| **d < 0.0).count()),
        }
    }

    /// The diagonal `D` of an `LDLᵀ` factor, stored where `LLᵀ` keeps its
    /// diagonal: the diagonal of each supernode's dense column block, or
    /// the first entry of each simplicial column.
    fn ldlt_diagonal(&self) -> Vec<f64> {
        let v = &self.l_values;
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sn) => {
                let (begin, end, rows, vals) =
                    (sn.supernode_begin(), sn.supernode_end(), sn.col_ptr_for_row_idx(), sn.col_ptr_for_val());
                (0..sn.n_supernodes())
                    .flat_map(|s| {
                        let w = end[s] - begin[s];
                        let h = w + rows[s + 1] - rows[s];
                        (0..w).map(move |j| v[vals[s] + j * h + j])
                    })
                    .collect()
            }
            SymbolicCholeskyRaw::Simplicial(sp) => sp.col_ptr()[..sp.ncols()].iter().map(|&p| v[p]).collect(),
        }
    }

    /// Number of stored values of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Bytes of the symbolic structure kept with the factor: a simplicial
    /// factor's row index per stored value and column pointers, or a
    /// supernodal factor's row indices per supernode and its pointers (8
    /// bytes each, `usize` indices).
    pub(crate) fn symbolic_bytes(&self) -> usize {
        let words = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sn) => {
                let ptr = sn.col_ptr_for_row_idx();
                ptr[sn.n_supernodes()] + 2 * ptr.len() + sn.col_ptr_for_val().len() + sn.supernode_begin().len()
            }
            SymbolicCholeskyRaw::Simplicial(sp) => sp.col_ptr()[sp.ncols()] + sp.col_ptr().len(),
        };
        8 * words
    }

    /// Bytes of scratch memory the numeric factorization needs.
    pub(crate) fn scratch_bytes(&self) -> usize {
        self.req.unaligned_bytes_required()
    }

    /// Numeric factorization of the matrix with these `values` (in the order
    /// of the pattern's entries). Tries `LLᵀ`, then `LDLᵀ`.
    pub(crate) fn factorize(&mut self, values: &[f64]) -> Result<(), LinearError> {
        self.factorize_with(values, false)
    }

    /// As [`Self::factorize`]; with `single`, first tries `LLᵀ` of the
    /// values rounded to single precision (half the memory traffic of the
    /// factorization and of every solve), and factorizes in double only if
    /// that breaks down.
    pub(crate) fn factorize_with(&mut self, values: &[f64], single: bool) -> Result<(), LinearError> {
        let sym = self.pattern.as_ref();
        self.kind = None;
        let len = self.symbolic.len_val();
        if self.l_values.len() != len {
            self.l_values = zeroed(len)?;
        }
        let req = self.req;
        let mem = self.mem.get_or_insert_with(|| MemBuffer::new(req));
        if single {
            let (l, a) = bytemuck::cast_slice_mut::<f64, f32>(&mut self.l_values).split_at_mut(len);
            for (x, &v) in a.iter_mut().zip(values) {
                *x = v as f32;
            }
            if llt(&self.symbolic, l, SparseColMatRef::new(sym, &a[..values.len()]), self.par, mem) {
                self.kind = Some(Kind::Llt32);
                return Ok(());
            }
        }
        let a = SparseColMatRef::new(sym, values);
        if llt(&self.symbolic, &mut self.l_values, a, self.par, mem) {
            self.kind = Some(Kind::Llt);
            return Ok(());
        }
        let stack = MemStack::new(mem);
        let ldlt = self.symbolic.factorize_numeric_ldlt::<f64>(
            &mut self.l_values,
            a,
            Side::Lower,
            LdltRegularization::default(),
            self.par,
            stack,
            Default::default(),
        );
        if ldlt.is_err() {
            return Err(LinearError::Singular);
        }
        self.kind = Some(Kind::Ldlt);
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds `b` on entry, `x` on exit).
    /// Fails with [`LinearError::Singular`] if the factor produced non-finite values.
    pub(crate) fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let n = self.pattern.nrows();
        let Some(mem) = self.mem.as_mut() else { return Err(LinearError::Singular) };
        let stack = MemStack::new(mem);
        match self.kind {
            Some(Kind::Llt) => {
                let x = MatMut::from_column_major_slice_mut(rhs, n, 1);
                LltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(Conj::No, x, self.par, stack)
            }
            Some(Kind::Ldlt) => {
                let x = MatMut::from_column_major_slice_mut(rhs, n, 1);
                LdltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(Conj::No, x, self.par, stack)
            }
            Some(Kind::Llt32) => {
                self.x_single.clear();
                self.x_single.extend(rhs.iter().map(|&v| v as f32));
                let xs = MatMut::from_column_major_slice_mut(&mut self.x_single, n, 1);
                let l = &bytemuck::cast_slice::<f64, f32>(&self.l_values)[..self.symbolic.len_val()];
                LltRef::new(&self.symbolic, l).solve_in_place_with_conj(Conj::No, xs, self.par, stack);
                for (r, &v) in rhs.iter_mut().zip(&self.x_single) {
                    *r = v as f64;
                }
            }
            None => return Err(LinearError::Singular),
        }
        if rhs.iter().all(|v| v.is_finite()) { Ok(()) } else { Err(LinearError::Singular) }
    }
}

/// Numeric `LLᵀ` of `a` into `l`: true if `a` is positive definite in the
/// precision of `T`.
fn llt<T: faer::traits::ComplexField>(
    symbolic: &SymbolicCholesky<usize>,
    l: &mut [T],
    a: SparseColMatRef<'_, usize, T>,
    par: Par,
    mem: &mut MemBuffer,
) -> bool {
    let stack = MemStack::new(mem);
    symbolic
        .factorize_numeric_llt::<T>(l, a, Side::Lower, LltRegularization::default(), par, stack, Default::default())
        .is_ok()
}

/// A zeroed vector of `n` values, or [`LinearError::OutOfMemory`] rather
/// than an abort (the factor is allocated at the first factorization, after
/// the memory check, which other processes may have made stale).
fn zeroed<T: Clone + Default>(n: usize) -> Result<Vec<T>, LinearError> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| LinearError::OutOfMemory(n.saturating_mul(std::mem::size_of::<T>())))?;
    v.resize(n, T::default());
    Ok(v)
}

/// Held while METIS orders a graph. METIS draws its random numbers from the
/// C library's `rand()` (GKlib's `random.c` without `USE_GKRAND`, as
/// metis-sys builds it), whose state is the process's: each ordering seeds
/// it (`srand(4321)`) and draws from it throughout, so two orderings at once
/// on two threads interleave their draws and number the same graph
/// differently — and the solution then differs in its rounding. One at a
/// time, every ordering of a graph is the same.
static METIS: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// METIS nested-dissection ordering of a graph given by sorted adjacency
/// lists without self loops. Returns `perm` with `perm[k]` = the vertex
/// placed at position `k`: the same for the same graph, whatever else the
/// process orders at the same time (orderings take turns); not if other
/// code of the process calls the C library's `rand()` or `srand()` meanwhile.
pub(crate) fn nested_dissection(adjacency: &[Vec<usize>]) -> Result<Vec<usize>, LinearError> {
    let n = adjacency.len();
    if n == 0 {
        return Ok(Vec::new());
    }
    let edges: usize = adjacency.iter().map(Vec::len).sum();
    if edges == 0 {
        return Ok((0..n).collect());
    }
    let mut xadj: Vec<metis_sys::idx_t> = Vec::with_capacity(n + 1);
    let mut adjncy: Vec<metis_sys::idx_t> = Vec::with_capacity(edges);
    xadj.push(0);
    for list in adjacency {
        adjncy.extend(list.iter().map(|&v| v as metis_sys::idx_t));
        xadj.push(adjncy.len() as metis_sys::idx_t);
    }
    let mut nvtxs = n as metis_sys::idx_t;
    let mut options = [0 as metis_sys::idx_t; metis_sys::METIS_NOPTIONS as usize];
    let mut perm = vec![0 as metis_sys::idx_t; n];
    let mut iperm = vec![0 as metis_sys::idx_t; n];
    // a panic while held cannot leave METIS half done (it is C): the lock
    // only orders the turns, so a poisoned one is still good
    let _turn = METIS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    // SAFETY: all arrays are sized as METIS documents (xadj n+1, adjncy =
    // xadj[n], perm/iperm n, options METIS_NOPTIONS) and outlive the calls;
    // METIS does not retain the pointers.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(LinearError::Metis(status));
    }
    Ok(perm.into_iter().map(|v| v as usize).collect())
}

#[cfg(test)]
#[path = "linear_tests.rs"]
mod tests;
