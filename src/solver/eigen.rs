//! The generalized symmetric eigenproblem `K φ = μ B φ` for the eigenvalues
//! of smallest `|μ|`, with `K` symmetric positive definite and `B`
//! symmetric, possibly indefinite: linear buckling (`B = −K_G`, the
//! geometric stiffness of a reference stress state, whose eigenvalues `μ`
//! are the buckling load factors) and free vibration (`B = M`).
//!
//! **Operator.** With the factor `K = L Lᵀ` ([`Cholesky`]) the problem is
//! transformed to `A φ = θ φ`, `A = K⁻¹ B`, `θ = 1/μ`: the wanted smallest
//! `|μ|` are the largest `|θ|`, the extreme and best separated end of `A`'s
//! spectrum, which Krylov methods find first (the *spectral
//! transformation*, Ericsson & Ruhe, *Math. Comp.* 35 (1980) 1251–1268).
//! `A` is not symmetric, but it is self-adjoint in the `K` inner product
//! `⟨x, y⟩_K = xᵀ K y` even when `B` is indefinite:
//! `⟨x, A y⟩_K = xᵀ B y = ⟨A x, y⟩_K`. So Lanczos is run in that inner
//! product — the "buckling mode" of Grimes, Lewis & Simon, *SIAM J. Matrix
//! Anal. Appl.* 15 (1994) 228–272 — which with `B` indefinite is the
//! only choice: there is no `B` inner product, and in the Euclidean one `A`
//! is not symmetric. The vectors `qⱼ` are `K`-orthonormal, and
//!
//! ```text
//! A Q_m = Q_m H_m + β_m q_(m+1) e_mᵀ,   H_m = Q_mᵀ B Q_m  (symmetric),
//! ```
//!
//! tridiagonal for plain Lanczos. Each step costs one product with `B`, one
//! pair of triangular solves with `L`, and two products with `K` (the
//! second Gram–Schmidt pass and the norm; the first pass reads `K w = B qⱼ`
//! for free).
//!
//! **Full reorthogonalization.** Each new vector is orthogonalized against
//! all the basis vectors (and the locked eigenvectors, below) by classical
//! Gram–Schmidt in the `K` inner product, twice ("twice is enough", Parlett,
//! *The Symmetric Eigenvalue Problem*, §6.9). Without it the basis loses
//! orthogonality as soon as a Ritz value converges and copies of it
//! ("ghosts") appear among the results. The coefficients of both passes
//! are kept in `H_m`, which is then symmetric to rounding; its symmetric
//! part is diagonalized by faer's dense self-adjoint eigensolver.
//!
//! **Restarts.** The basis holds at most `m` vectors (`EigenSettings::subspace`,
//! a few dozen, so that memory stays at `m + count + 3` vectors of length
//! `n` for 10⁵–10⁶ unknowns). When it is full and the wanted Ritz pairs have
//! not converged, it is *thick-restarted* (Wu & Simon, *SIAM J. Matrix Anal.
//! Appl.* 22 (2000) 602–616; equivalently Stewart's Krylov–Schur): the best
//! `k = count + (m − count)/2` Ritz vectors `xᵢ = Q_m yᵢ` and the residual
//! vector `q_(m+1)` become the new basis, with
//! `A X_k = X_k Θ_k + q_(m+1) sᵀ`, `sᵢ = β_m e_mᵀ yᵢ`, and Lanczos continues
//! from `q_(m+1)` (the projected matrix is then an arrow followed by a
//! tridiagonal). This was chosen over block subspace iteration (Bathe,
//! *Finite Element Procedures*, §11.6): that needs `min(2p, p + 8)` solves
//! per iteration and converges at the ratio `|θ_(q+1)/θᵢ|`, where Lanczos
//! converges at a rate set by the gaps of the whole spectrum, typically
//! with several times fewer solves.
//!
//! **Convergence** of a Ritz pair `(θ, x = Q_m y)` is read from the
//! relation above: `‖A x − θ x‖_K = |β_m e_mᵀ y| ≤ tol |θ|`. The eigenvalue
//! error is then of the order of the square of that residual over the gap
//! to the rest of the spectrum.
//!
//! **Missed eigenvalues.** A Krylov space holds only one vector of each
//! eigenspace of its start vector (in exact arithmetic), so a multiple
//! eigenvalue — the two equal bending modes of a doubly symmetric section —
//! would appear once; in practice rounding errors, amplified by the
//! reorthogonalized iteration, usually bring in the other copies, but
//! nothing guarantees it, nor that a start vector poor in some mode finds
//! it in time. So when the wanted pairs have converged they are
//! *locked*, and a further run from a new start vector, kept `K`-orthogonal
//! to them, finds the largest remaining `|θ|`; if it ranks among the wanted
//! it is added (and the check repeated), otherwise the result is complete
//! ([`EigenSettings::verify`]). The check costs about half the solves of
//! the first run (1D Laplacian, 3·10⁵ unknowns, 10 pairs: 30 + 30 solves,
//! 1.6 s in all).
//!
//! **Result.** The `μ` sorted by `|μ|` ascending (with
//! `EigenSettings::positive_only`, only `μ > 0`, ascending), each with its
//! eigenvector normalized in the `K` norm, `φᵢᵀ K φⱼ = δᵢⱼ` (so
//! `φᵢᵀ B φⱼ = δᵢⱼ / μᵢ`), its sign chosen so that its entry of largest
//! magnitude is positive.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd;
use faer::{Mat, Par};

use super::linear::{Cholesky, LinearError, LowerCsc};

/// Errors of the eigensolver.
#[derive(Debug, thiserror::Error)]
pub enum EigenError {
    /// `K` is not positive definite (its `LLᵀ` factorization broke down).
    #[error(
        "the stiffness matrix is not positive definite (a free rigid-body motion, or a tangent past a limit \
         point): the eigenproblem K φ = μ B φ needs K positive definite"
    )]
    NotPositiveDefinite,
    /// The wanted Ritz pairs did not reach the tolerance within the restart limit.
    #[error(
        "the eigensolver did not converge: {converged} of the {wanted} wanted eigenpairs reached the tolerance \
         after {restarts} restarts (largest relative residual {worst:.2e}); more restarts, a larger subspace \
         or a looser tolerance (EigenSettings) may converge"
    )]
    NotConverged {
        /// Wanted pairs that had converged.
        converged: usize,
        /// Pairs wanted in the run that failed.
        wanted: usize,
        /// Restarts made.
        restarts: usize,
        /// Largest `‖A x − θ x‖_K / |θ|` among the wanted pairs.
        worst: f64,
    },
    /// The input is inconsistent (the message says how).
    #[error("eigenproblem input: {0}")]
    Input(String),
    /// A solve with the factor failed.
    #[error(transparent)]
    Linear(#[from] LinearError),
    /// faer's dense eigensolver failed on the projected matrix.
    #[error("the dense eigensolver failed on the projected matrix: {0}")]
    Dense(String),
}

/// Controls of the eigensolver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EigenSettings {
    /// Number of eigenpairs wanted.
    pub count: usize,
    /// Only `μ > 0` (buckling load factors under the reference load's sign).
    pub(crate) positive_only: bool,
    /// Relative Ritz residual `‖A x − θ x‖_K / |θ|` of convergence.
    pub tolerance: f64,
    /// Largest basis size `m` (0: `max(2 count + 10, 20)`); capped at the dimension.
    pub(crate) subspace: usize,
    /// Thick restarts allowed in one Lanczos run.
    pub(crate) max_restarts: usize,
    /// After convergence, look for eigenvalues the run missed (multiple ones).
    pub verify: bool,
}

impl Default for EigenSettings {
    fn default() -> Self {
        Self { count: 6, positive_only: false, tolerance: 1e-10, subspace: 0, max_restarts: 100, verify: true }
    }
}

/// Eigenpairs and the work they took.
#[derive(Debug, Clone, PartialEq)]
pub struct EigenSolution {
    /// Eigenvalues `μ`, by `|μ|` ascending (fewer than asked only when the
    /// problem has fewer, e.g. fewer positive ones with `positive_only`).
    pub values: Vec<f64>,
    /// Eigenvectors, `K`-orthonormal, the largest entry of each positive.
    pub vectors: Vec<Vec<f64>>,
    /// Relative Ritz residuals `‖A x − θ x‖_K / |θ|`, `θ = 1/μ`.
    pub residuals: Vec<f64>,
    /// Solves with the factor of `K`.
    pub solves: usize,
    /// Thick restarts, over all runs.
    pub(crate) restarts: usize,
    /// Lanczos runs (the first, plus the checks for missed eigenvalues).
    pub runs: usize,
}

/// The basis size `m` of [`EigenSettings::subspace`] = 0: `max(2 count + 10, 20)`.
pub(crate) fn auto_subspace(count: usize) -> usize {
    (2 * count + 10).max(20)
}

/// Vectors of the equations' size an eigensolution of `count` pairs holds
/// at most: the basis (`m + 1`), the locked pairs and two of scratch (for
/// the memory estimate).
pub fn vectors(count: usize) -> usize {
    auto_subspace(count) + 1 + count + 2
}

/// Solves `K φ = μ B φ` for the eigenvalues of smallest `|μ|`; `k` and `b`
/// are values on `pattern` (lower triangles). Factorizes `K` itself.
pub fn solve(pattern: &LowerCsc, k: &[f64], b: &[f64], settings: &EigenSettings) -> Result<EigenSolution, EigenError> {
    if k.len() != pattern.nnz() {
        return Err(EigenError::Input(format!("{} values of K for {} entries", k.len(), pattern.nnz())));
    }
    let mut chol = Cholesky::analyze(pattern)?;
    match chol.factorize(k) {
        Err(LinearError::Singular) => return Err(EigenError::NotPositiveDefinite),
        other => other?,
    }
    solve_factored(&mut chol, pattern, k, b, settings)
}

/// As [`solve`], with `chol` already holding the double-precision `LLᵀ`
/// factor of `K` (e.g. the last tangent of a nonlinear analysis).
pub(crate) fn solve_factored(
    chol: &mut Cholesky,
    pattern: &LowerCsc,
    k: &[f64],
    b: &[f64],
    settings: &EigenSettings,
) -> Result<EigenSolution, EigenError> {
    if k.len() != pattern.nnz() || b.len() != pattern.nnz() {
        return Err(EigenError::Input(format!(
            "{} values of K and {} of B for {} entries",
            k.len(),
            b.len(),
            pattern.nnz()
        )));
    }
    if !chol.is_llt() {
        return Err(EigenError::NotPositiveDefinite);
    }
    if chol.is_single() {
        return Err(EigenError::Input("the factor of K is single precision (a preconditioner only)".into()));
    }
    let mut op = Operator { chol, pattern, k, b, solves: 0 };
    let mut locked: Vec<Ritz> = Vec::new();
    let (mut restarts, mut runs) = (0, 0);
    let rank = Rank { positive_only: settings.positive_only };
    // a first run, then checks while they find something (each adds a pair)
    let max_runs = if settings.verify { settings.count + 1 } else { 1 };
    while settings.count > 0 && runs < max_runs {
        let first = runs == 0;
        let want = if first { settings.count } else { 1 };
        let vectors: Vec<Vec<f64>> = locked.iter().map(|r| r.vector.clone()).collect();
        let found = lanczos(&mut op, &vectors, want, settings, 0x9E37_79B9 + runs as u64, &mut restarts)?;
        runs += 1;
        // a check's pairs that rank above the last wanted one by more than
        // the tolerance are missed eigenvalues (ties are not: either is right)
        let last = locked.last().map(|r| r.theta);
        let entered: Vec<Ritz> = found
            .into_iter()
            .filter(|r| {
                first
                    || locked.len() < settings.count
                    || last.is_some_and(|t| rank.key(r.theta) > rank.key(t) * (1.0 + 10.0 * settings.tolerance))
            })
            .collect();
        if entered.is_empty() {
            break;
        }
        locked.extend(entered);
        locked.sort_by(|a, b| rank.key(b.theta).total_cmp(&rank.key(a.theta)));
        locked.truncate(settings.count);
    }
    let mut solution = EigenSolution {
        values: Vec::new(),
        vectors: Vec::new(),
        residuals: Vec::new(),
        solves: op.solves,
        restarts,
        runs,
    };
    for mut r in locked {
        let big = r.vector.iter().fold(0.0f64, |m, &v| if v.abs() > m.abs() { v } else { m });
        if big < 0.0 {
            r.vector.iter_mut().for_each(|v| *v = -*v);
        }
        solution.values.push(1.0 / r.theta);
        solution.residuals.push(r.residual / r.theta.abs());
        solution.vectors.push(r.vector);
    }
    Ok(solution)
}

/// A converged Ritz pair of `A`.
struct Ritz {
    theta: f64,
    vector: Vec<f64>,
    /// `‖A x − θ x‖_K`.
    residual: f64,
}

/// Which Ritz values are wanted, and in which order.
#[derive(Clone, Copy)]
struct Rank {
    positive_only: bool,
}

impl Rank {
    /// Larger is more wanted: `|θ|`, or `θ` with `positive_only`.
    fn key(self, theta: f64) -> f64 {
        if self.positive_only { theta } else { theta.abs() }
    }

    /// Indices of the eligible `theta` (not `≈ 0`, i.e. `|μ|` finite against
    /// the largest; positive with `positive_only`), most wanted first.
    fn order(self, theta: &[f64]) -> Vec<usize> {
        let largest = theta.iter().fold(0.0f64, |m, t| m.max(t.abs()));
        let mut idx: Vec<usize> =
            (0..theta.len()).filter(|&i| theta[i].abs() > 1e-12 * largest && self.key(theta[i]) > 0.0).collect();
        idx.sort_by(|&a, &b| self.key(theta[b]).total_cmp(&self.key(theta[a])));
        idx
    }
}

/// `A = K⁻¹ B` and the `K` inner product.
struct Operator<'a> {
    chol: &'a mut Cholesky,
    pattern: &'a LowerCsc,
    k: &'a [f64],
    b: &'a [f64],
    solves: usize,
}

impl Operator<'_> {
    fn n(&self) -> usize {
        self.pattern.n
    }

    /// `bq = B q`, `w = K⁻¹ B q`.
    fn apply(&mut self, q: &[f64], bq: &mut [f64], w: &mut [f64]) -> Result<(), EigenError> {
        self.pattern.mul_symmetric(self.b, q, bq);
        w.copy_from_slice(bq);
        self.chol.solve_in_place(w)?;
        self.solves += 1;
        Ok(())
    }

    /// `out = K x`.
    fn k_mul(&self, x: &[f64], out: &mut [f64]) {
        self.pattern.mul_symmetric(self.k, x, out);
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// One Gram–Schmidt pass: with `kw = K w`, removes from `w` its `K`
/// components along `locked` and `basis`, adding those along `basis` to
/// `coef`.
fn project_out(locked: &[Vec<f64>], basis: &[Vec<f64>], w: &mut [f64], kw: &[f64], coef: &mut [f64]) {
    for v in locked {
        let c = dot(v, kw);
        w.iter_mut().zip(v).for_each(|(x, y)| *x -= c * y);
    }
    for (i, v) in basis.iter().enumerate() {
        let c = dot(v, kw);
        coef[i] += c;
        w.iter_mut().zip(v).for_each(|(x, y)| *x -= c * y);
    }
}

/// A pseudo-random vector in `[−1, 1)ⁿ` (xorshift64, reproducible).
fn random(seed: u64, out: &mut [f64]) {
    let mut s = seed.max(1);
    for x in out {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        *x = (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0;
    }
}

/// The Lanczos basis: `q` (`m + 1` vectors) and the projected matrix
/// `h` (`(m + 1) × m`, column-major), of which the first `len` vectors hold.
struct Basis {
    q: Vec<Vec<f64>>,
    h: Vec<f64>,
    m: usize,
}

impl Basis {
    fn h(&mut self, i: usize, j: usize) -> &mut f64 {
        &mut self.h[i + j * (self.m + 1)]
    }
}

/// Scratch vectors of one Lanczos step.
struct Scratch {
    w: Vec<f64>,
    kw: Vec<f64>,
    coef: Vec<f64>,
}

/// Makes `w` a unit vector `K`-orthogonal to `locked` and `basis` (two
/// passes); false if nothing is left of it (it lay in their span).
fn orthonormalize(op: &Operator, locked: &[Vec<f64>], basis: &[Vec<f64>], s: &mut Scratch) -> bool {
    op.k_mul(&s.w, &mut s.kw);
    let before = dot(&s.w, &s.kw).max(0.0).sqrt();
    for _ in 0..2 {
        op.k_mul(&s.w, &mut s.kw);
        project_out(locked, basis, &mut s.w, &s.kw, &mut s.coef);
    }
    op.k_mul(&s.w, &mut s.kw);
    let after = dot(&s.w, &s.kw).max(0.0).sqrt();
    if !(after > 1e-8 * before) {
        return false;
    }
    s.w.iter_mut().for_each(|x| *x /= after);
    true
}

/// Extends the basis from `from` vectors to `m` by Lanczos steps. Returns
/// the size reached: `m`, or less if `A` has no further direction
/// `K`-orthogonal to `locked` (the space is exhausted; then the Ritz pairs
/// are exact).
fn expand(
    op: &mut Operator,
    locked: &[Vec<f64>],
    basis: &mut Basis,
    from: usize,
    seed: u64,
    s: &mut Scratch,
) -> Result<usize, EigenError> {
    for j in from..basis.m {
        op.apply(&basis.q[j], &mut s.kw, &mut s.w)?;
        let before = dot(&s.w, &s.kw).max(0.0).sqrt();
        s.coef[..=j].fill(0.0);
        // first pass with K w = B q, second with K w recomputed
        project_out(locked, &basis.q[..=j], &mut s.w, &s.kw, &mut s.coef);
        op.k_mul(&s.w, &mut s.kw);
        project_out(locked, &basis.q[..=j], &mut s.w, &s.kw, &mut s.coef);
        op.k_mul(&s.w, &mut s.kw);
        let beta = dot(&s.w, &s.kw).max(0.0).sqrt();
        for i in 0..=j {
            *basis.h(i, j) = s.coef[i];
        }
        if beta > 1e-12 * before {
            *basis.h(j + 1, j) = beta;
            s.w.iter_mut().for_each(|x| *x /= beta);
        } else {
            // an invariant subspace: continue from a new direction (β = 0)
            *basis.h(j + 1, j) = 0.0;
            random(seed.wrapping_add(j as u64 + 1), &mut s.w);
            if !orthonormalize(op, locked, &basis.q[..=j], s) {
                return Ok(j + 1);
            }
        }
        basis.q[j + 1].copy_from_slice(&s.w);
    }
    Ok(basis.m)
}

/// Eigenvalues (ascending) and eigenvectors (`s × s`) of the symmetric part
/// of the leading `s × s` block of `h`.
fn rayleigh_ritz(basis: &Basis, s: usize) -> Result<(Vec<f64>, Mat<f64>), EigenError> {
    let ld = basis.m + 1;
    let t = Mat::<f64>::from_fn(s, s, |i, j| 0.5 * (basis.h[i + j * ld] + basis.h[j + i * ld]));
    let mut y = Mat::<f64>::zeros(s, s);
    let mut theta = faer::Col::<f64>::zeros(s);
    let (par, params) = (Par::Seq, Default::default());
    let mut mem = MemBuffer::new(evd::self_adjoint_evd_scratch::<f64>(s, evd::ComputeEigenvectors::Yes, par, params));
    evd::self_adjoint_evd(t.as_ref(), theta.as_diagonal_mut(), Some(y.as_mut()), par, MemStack::new(&mut mem), params)
        .map_err(|e| EigenError::Dense(format!("{e:?}")))?;
    Ok(((0..s).map(|i| theta[i]).collect(), y))
}

/// Replaces the first `cols.len()` basis vectors by the Ritz vectors
/// `Q_s y_c` (in place, row by row).
fn combine(q: &mut [Vec<f64>], s: usize, y: &Mat<f64>, cols: &[usize]) {
    let n = q.first().map_or(0, Vec::len);
    let (mut row, mut out) = (vec![0.0; s], vec![0.0; cols.len()]);
    for r in 0..n {
        for i in 0..s {
            row[i] = q[i][r];
        }
        for (o, &c) in out.iter_mut().zip(cols) {
            *o = (0..s).map(|i| row[i] * y[(i, c)]).sum();
        }
        for (v, &o) in q.iter_mut().zip(&out) {
            v[r] = o;
        }
    }
}

/// One thick-restarted Lanczos run, `K`-orthogonal to `locked`, for the
/// `want` most wanted pairs of `A`. Returns them converged (fewer if the
/// space holds fewer eligible ones).
fn lanczos(
    op: &mut Operator,
    locked: &[Vec<f64>],
    want: usize,
    settings: &EigenSettings,
    seed: u64,
    restarts: &mut usize,
) -> Result<Vec<Ritz>, EigenError> {
    let n = op.n();
    let auto = auto_subspace(settings.count);
    let m = (if settings.subspace == 0 { auto } else { settings.subspace }).min(n.saturating_sub(locked.len()));
    if m == 0 {
        return Ok(Vec::new());
    }
    let mut basis = Basis { q: vec![vec![0.0; n]; m + 1], h: vec![0.0; (m + 1) * m], m };
    let mut s = Scratch { w: vec![0.0; n], kw: vec![0.0; n], coef: vec![0.0; m + 1] };
    random(seed, &mut s.w);
    if !orthonormalize(op, locked, &[], &mut s) {
        return Ok(Vec::new());
    }
    basis.q[0].copy_from_slice(&s.w);
    let rank = Rank { positive_only: settings.positive_only };
    let mut from = 0;
    for cycle in 0..=settings.max_restarts {
        let size = expand(op, locked, &mut basis, from, seed ^ 0x5DEE_CE66, &mut s)?;
        let (theta, y) = rayleigh_ritz(&basis, size)?;
        let beta = if size == m { *basis.h(m, m - 1) } else { 0.0 };
        let residual: Vec<f64> = (0..size).map(|i| (beta * y[(size - 1, i)]).abs()).collect();
        let order = rank.order(&theta);
        let needed = want.min(order.len());
        let converged = order[..needed].iter().filter(|&&i| residual[i] <= settings.tolerance * theta[i].abs()).count();
        // fewer eligible values than wanted is believed after one restart
        let enough = needed == want || cycle > 0 || size < m;
        if (converged == needed && enough) || size < m {
            let picked = &order[..needed];
            combine(&mut basis.q, size, &y, picked);
            return Ok(picked
                .iter()
                .zip(basis.q.iter_mut())
                .map(|(&i, q)| Ritz { theta: theta[i], vector: std::mem::take(q), residual: residual[i] })
                .collect());
        }
        if cycle == settings.max_restarts {
            let worst = order[..needed].iter().map(|&i| residual[i] / theta[i].abs()).fold(0.0, f64::max);
            return Err(EigenError::NotConverged { converged, wanted: want, restarts: *restarts, worst });
        }
        // thick restart: the best k Ritz vectors and the residual vector
        let k = (needed + (m - needed) / 2).min(order.len()).min(m - 1);
        let kept = &order[..k];
        combine(&mut basis.q, size, &y, kept);
        basis.q.swap(k, m);
        basis.h.fill(0.0);
        for (c, &i) in kept.iter().enumerate() {
            *basis.h(c, c) = theta[i];
            *basis.h(k, c) = beta * y[(size - 1, i)];
        }
        from = k;
        *restarts += 1;
    }
    unreachable!("the last cycle returns")
}

#[cfg(test)]
#[path = "eigen_tests.rs"]
mod tests;
