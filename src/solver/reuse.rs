//! A factorization reused across Newton iterations as the preconditioner of
//! conjugate gradients, refactored only when it stops paying.
//!
//! Plasticity and contact change the tangent `K` of these problems in a small
//! region, so the factor `L Lᵀ = K₀` of an earlier tangent is close to the
//! present one: `K₀⁻¹ K = I + E` with `E` of low rank or small norm, and
//! preconditioned conjugate gradients (PCG, Saad, *Iterative methods for
//! sparse linear systems*, 2nd ed., Alg. 9.1) solve `K x = b` in a few
//! iterations, each costing one product with `K` and one pair of triangular
//! solves with `L` — a small fraction of a numeric factorization.
//!
//! **Policy.** Every solve first tries PCG with the last factor, stopping at
//! `‖b − K x‖ ≤ η ‖b‖`. The forcing term `η` follows the caller's relative
//! Newton residual `r`: `η = min(r, η_max)` ([`ReuseSettings::tolerance`]
//! is `η_max`). A linear residual of the order of the nonlinear one keeps
//! Newton's convergence quadratic (Dembo, Eisenstat & Steihaug, *SIAM J.
//! Numer. Anal.* 19 (1982) 400–408, Cor. 3.5) while early iterations, far from
//! the solution, are not oversolved. `η_max = 0.1` (the cap matters only
//! while `r > η_max`, i.e. in the first iteration of an increment): against
//! `10⁻²` the paper examples need the same Newton iterations within one and
//! 4–5 fewer factorizations on the tubes (tube 28 L9, `cufem run` with
//! `krylov_tolerance` set in the example's `[solver]`, one run each: 21 → 17
//! factorizations, 5.29 → 4.82 s; probes equal within 2e-8 by
//! `bench/compare_summaries.py`), because a PCG solve
//! that stops earlier marks its factor worn less often. (The structure caps
//! the forcing term at `10⁻²` while contact has not settled:
//! `analysis::structure`.) PCG may take at most as many iterations
//! as would cost one factorization, estimated from counts so that a run is
//! reproducible to the last digit: the factorization's flops (from the
//! symbolic structure, [`Cholesky::factor_flops`]) over [`FLOP_RATE_RATIO`]
//! times the flops of one PCG iteration (`4 nnz(L) + 4 nnz(K)`), clamped to
//! `[ReuseSettings::min_iterations, ReuseSettings::max_iterations]`. If PCG does not converge within them,
//! or breaks down (`pᵀ K p ≤ 0`: the tangent is not positive definite), the
//! present tangent is factorized and solved directly (the *fallback*). A solve
//! that needed more than half its allowance marks the factor as worn, and a
//! fallback marks the tangent as changing fast: in both cases the next solve
//! refactors at once instead of trying. An `LDLᵀ` factor
//! (indefinite tangent) is never reused.
//!
//! **Mixed precision.** With [`ReuseSettings::single_precision`] (model key
//! `solver.factor_precision = "single"`, the default) a factorization rounds
//! the tangent to `f32` and factorizes that: half the bytes of the factor and
//! of every triangular solve, and about two thirds of the factorization time
//! (tube 28 L9: 144 → 98 ms, `cufem bench --full`). The factor
//! `L̃ L̃ᵀ = K + δK`, `‖δK‖ ≈ 6·10⁻⁸ ‖K‖`, is then only a preconditioner:
//! even its own tangent is solved by PCG, with the residual and the product
//! with `K` in `f64`, which reaches `η` in one or two iterations while
//! `κ(K) · 6·10⁻⁸` is small — iterative refinement in mixed precision with a
//! Krylov method in place of the plain correction (Higham, *Accuracy and
//! Stability of Numerical Algorithms*, 2nd ed., ch. 12; Carson & Higham,
//! *SIAM J. Sci. Comput.* 40 (2018) A817). If that PCG does not converge
//! within the allowance (a tangent too ill-conditioned for `f32`), the
//! tangent is factorized in `f64` and solved directly, and the solver stays
//! in `f64` for the rest of the run (a *precision fallback*); if `LLᵀ`
//! breaks down in `f32`, the `f64` factorization follows at once. A solve
//! whose factor serves further right-hand sides (`must_factor`) factorizes
//! in `f64`, and so does a linear model (the model's settings turn single
//! precision off there: its one factorization then solves it to round-off,
//! not to Newton's tolerance). A tangent that is not positive definite but
//! whose `f32` factorization happens to succeed makes PCG break down: that
//! too is a precision fallback.
//!
//! The converged Newton solution does not depend on the path: each
//! correction solves the same tangent system to `η` (relative), so Newton
//! converges to the same state within its own tolerance.

use std::time::{Duration, Instant};

use super::linear::{Cholesky, LinearError, LowerCsc};

/// How many times faster (in flops per second) the dense kernels of a
/// supernodal factorization run than the memory-bound triangular solves and
/// sparse products of a PCG iteration. Measured with the paper examples on
/// the 2-core CI machine, 1 thread (factorization time / PCG iteration time
/// against their flop ratio): tube 28 L9 11.6, cantilevers 13, block 8.3,
/// compact bar 4 L9 2–4 (small supernodes run slower).
pub const FLOP_RATE_RATIO: f64 = 10.0;

/// Controls of the reuse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReuseSettings {
    /// False: factorize at every solve (the classic full Newton path).
    pub enabled: bool,
    /// Largest relative residual `η_max` at which PCG stops (the forcing
    /// term is the Newton residual, capped here).
    pub tolerance: f64,
    /// Bounds on the PCG iterations per solve; between them, the estimated
    /// cost of one factorization decides (module docs).
    pub min_iterations: usize,
    /// See `min_iterations`.
    pub max_iterations: usize,
    /// Factorize in single precision and refine by PCG in double (module
    /// docs); only with `enabled`.
    pub single_precision: bool,
}

impl Default for ReuseSettings {
    fn default() -> Self {
        Self { enabled: true, tolerance: 0.1, min_iterations: 2, max_iterations: 50, single_precision: true }
    }
}

/// Counters of the solves made.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReuseStats {
    /// Numeric factorizations.
    pub factorizations: usize,
    /// Solves that reused an earlier factor (PCG converged).
    pub reused: usize,
    /// PCG iterations in all solves (also those that fell back).
    pub krylov_iterations: usize,
    /// Solves where PCG was tried and did not converge.
    pub fallbacks: usize,
    /// Factorizations stored in single precision.
    pub single_factorizations: usize,
    /// Single-precision factors that did not precondition their own matrix
    /// (the solver factorizes in double from then on).
    pub precision_fallbacks: usize,
    /// Time in numeric factorizations.
    pub factorization_time: Duration,
    /// Time in triangular solves and PCG.
    pub solve_time: Duration,
}

/// How one solve was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolveKind {
    /// Factorized the present matrix and solved directly.
    Factorized,
    /// PCG with the earlier factor converged in this many iterations.
    Reused(usize),
    /// PCG did not converge in this many iterations; then factorized.
    FellBack(usize),
}

/// A sparse Cholesky factorization with the reuse policy of the module docs.
#[derive(Debug)]
pub struct ReusingSolver {
    chol: Cholesky,
    settings: ReuseSettings,
    stats: ReuseStats,
    has_factor: bool,
    worn: bool,
    /// Set by a fallback: the next solve factorizes without trying PCG.
    skip: bool,
    /// PCG iterations allowed per solve (fixed by the pattern: computed once).
    allowed: Option<usize>,
    work: [Vec<f64>; 5],
    /// Factorize in single precision (until a single factor fails to precondition).
    single: bool,
}

impl ReusingSolver {
    /// Wraps an analysed Cholesky factorization.
    pub fn new(chol: Cholesky, settings: ReuseSettings) -> Self {
        Self {
            chol,
            settings,
            stats: ReuseStats::default(),
            has_factor: false,
            worn: false,
            skip: false,
            allowed: None,
            work: Default::default(),
            single: settings.enabled && settings.single_precision,
        }
    }

    /// Number of stored values of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.chol.factor_nnz()
    }

    /// Counters so far.
    pub fn stats(&self) -> &ReuseStats {
        &self.stats
    }

    /// Solves `A x = b` for the symmetric matrix with lower-triangle
    /// `values` on `pattern`; `rhs` holds `b` on entry and `x` on exit.
    /// `forcing` is the relative residual of the nonlinear iteration this
    /// solve serves (`η = min(forcing, η_max)`, at least 1e-12). With
    /// `must_factor`, the present matrix is factorized whatever the policy
    /// says (e.g. when the caller solves further right-hand sides with the
    /// factor).
    pub fn solve(
        &mut self,
        pattern: &LowerCsc,
        values: &[f64],
        rhs: &mut [f64],
        forcing: f64,
        must_factor: bool,
    ) -> Result<SolveKind, LinearError> {
        let try_pcg =
            self.settings.enabled && self.has_factor && !self.worn && !self.skip && !must_factor && self.chol.is_llt();
        self.skip = false;
        let mut kind = SolveKind::Factorized;
        if try_pcg {
            let allowed = self.allowed_iterations(pattern);
            let t = Instant::now();
            let eta = self.stop(forcing);
            let outcome = pcg(pattern, values, &mut self.chol, rhs, eta, allowed, &mut self.work)?;
            let elapsed = t.elapsed();
            self.stats.solve_time += elapsed;
            let its = match outcome {
                Pcg::Converged(k) | Pcg::NotConverged(k) => k,
            };
            self.stats.krylov_iterations += its;
            match outcome {
                Pcg::Converged(k) => {
                    self.stats.reused += 1;
                    self.worn = 2 * k > allowed;
                    return Ok(SolveKind::Reused(k));
                }
                Pcg::NotConverged(k) => {
                    self.stats.fallbacks += 1;
                    kind = SolveKind::FellBack(k);
                }
            }
        }
        // a factor one iteration old did not precondition: the tangent is
        // changing fast (contact status, spreading plastic zone), so the
        // next solve factorizes directly rather than risk another fallback
        self.skip = matches!(kind, SolveKind::FellBack(_));
        // further right-hand sides (`solve_again`) need an exact factor
        self.factorize(values, self.single && !must_factor)?;
        if self.chol.is_single() {
            // the single-precision factor of the present tangent is a
            // preconditioner: PCG refines its solution to η in f64
            let allowed = self.allowed_iterations(pattern);
            let t = Instant::now();
            let eta = self.stop(forcing);
            let outcome = pcg(pattern, values, &mut self.chol, rhs, eta, allowed, &mut self.work)?;
            self.stats.solve_time += t.elapsed();
            match outcome {
                Pcg::Converged(k) => {
                    self.stats.krylov_iterations += k;
                    self.worn = 2 * k > allowed;
                    return Ok(kind);
                }
                Pcg::NotConverged(k) => {
                    // too ill-conditioned for single precision: double from now on
                    self.stats.krylov_iterations += k;
                    self.stats.precision_fallbacks += 1;
                    self.single = false;
                    self.factorize(values, false)?;
                }
            }
        }
        let t = Instant::now();
        self.chol.solve_in_place(rhs)?;
        self.stats.solve_time += t.elapsed();
        Ok(kind)
    }

    /// The PCG stop `η = min(forcing, η_max)`, at least 1e-12 (module docs).
    fn stop(&self, forcing: f64) -> f64 {
        forcing.min(self.settings.tolerance).max(1e-12)
    }

    /// Numeric factorization of the present matrix (single precision if
    /// asked and `LLᵀ` succeeds in it), with the counters.
    fn factorize(&mut self, values: &[f64], single: bool) -> Result<(), LinearError> {
        let t = Instant::now();
        self.has_factor = false;
        self.chol.factorize_with(values, single)?;
        self.stats.factorization_time += t.elapsed();
        self.stats.factorizations += 1;
        self.stats.single_factorizations += usize::from(self.chol.is_single());
        self.has_factor = true;
        self.worn = false;
        Ok(())
    }

    /// Solves with the factor of the last [`Self::solve`] that factorized
    /// (call it after `solve(.., must_factor = true)` for further
    /// right-hand sides of the same matrix).
    pub fn solve_again(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let t = Instant::now();
        self.chol.solve_in_place(rhs)?;
        self.stats.solve_time += t.elapsed();
        Ok(())
    }

    /// PCG iterations that cost about one factorization (module docs).
    fn allowed_iterations(&mut self, pattern: &LowerCsc) -> usize {
        *self.allowed.get_or_insert_with(|| {
            let (lo, hi) = (self.settings.min_iterations.max(1), self.settings.max_iterations);
            let iteration = 4.0 * (self.chol.factor_nnz() + pattern.nnz()) as f64;
            let ratio = self.chol.factor_flops() / (FLOP_RATE_RATIO * iteration);
            (ratio as usize).clamp(lo, hi.max(lo))
        })
    }
}

/// Result of [`pcg`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pcg {
    /// Converged after this many iterations (`rhs` holds the solution).
    Converged(usize),
    /// Stopped after this many iterations (`rhs` holds `b` again).
    NotConverged(usize),
}

/// Preconditioned conjugate gradients for the symmetric matrix (`pattern`,
/// lower-triangle `values`) with the factor in `precond`, from `x₀ = 0`, to
/// `‖b − A x‖ ≤ tol ‖b‖` within `max_iterations`. `rhs` holds `b` on entry;
/// on convergence it holds `x`, otherwise `b` unchanged. Stops early on a
/// breakdown (`pᵀ A p ≤ 0`).
pub fn pcg(
    pattern: &LowerCsc,
    values: &[f64],
    precond: &mut Cholesky,
    rhs: &mut [f64],
    tol: f64,
    max_iterations: usize,
    work: &mut [Vec<f64>; 5],
) -> Result<Pcg, LinearError> {
    let n = rhs.len();
    for w in work.iter_mut() {
        w.resize(n, 0.0);
    }
    let [x, r, z, p, q] = work;
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>();
    let b_norm = dot(rhs, rhs).sqrt();
    if b_norm == 0.0 {
        return Ok(Pcg::Converged(0));
    }
    x.fill(0.0);
    r.copy_from_slice(rhs);
    z.copy_from_slice(r);
    precond.solve_in_place(z)?;
    p.copy_from_slice(z);
    let mut rz = dot(r, z);
    for k in 1..=max_iterations {
        pattern.mul_symmetric(values, p, q);
        let pq = dot(p, q);
        if !(pq > 0.0) || !(rz > 0.0) {
            return Ok(Pcg::NotConverged(k - 1));
        }
        let alpha = rz / pq;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
        }
        if dot(r, r).sqrt() <= tol * b_norm {
            rhs.copy_from_slice(x);
            return Ok(Pcg::Converged(k));
        }
        if k == max_iterations {
            return Ok(Pcg::NotConverged(k));
        }
        z.copy_from_slice(r);
        precond.solve_in_place(z)?;
        let rz_new = dot(r, z);
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    Ok(Pcg::NotConverged(max_iterations))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lower pattern of a 1D Laplacian-like tridiagonal SPD matrix of size n
    /// with diagonal `d[i]` and off-diagonal −1.
    fn tridiagonal(d: &[f64]) -> (LowerCsc, Vec<f64>) {
        let n = d.len();
        let columns: Vec<Vec<usize>> = (0..n).map(|c| (c..(c + 2).min(n)).collect()).collect();
        let values: Vec<f64> =
            columns.iter().zip(d).flat_map(|(rows, &dc)| [dc, -1.0].into_iter().take(rows.len())).collect();
        (LowerCsc::from_columns(n, &columns), values)
    }

    fn residual(p: &LowerCsc, v: &[f64], x: &[f64], b: &[f64]) -> f64 {
        let mut y = vec![0.0; b.len()];
        p.mul_symmetric(v, x, &mut y);
        y.iter().zip(b).map(|(a, c)| (a - c) * (a - c)).sum::<f64>().sqrt()
    }

    /// A local change of the matrix (a "plastic zone" of 3 rows of 200) is
    /// solved by PCG with the old factor in a few iterations (at most one per
    /// changed row plus one, in exact arithmetic) to the requested tolerance.
    #[test]
    fn local_change_is_solved_by_the_old_factor_in_a_few_iterations() {
        let n = 200;
        let d0 = vec![2.5; n];
        let (pattern, v0) = tridiagonal(&d0);
        // a tridiagonal factorization costs less than two PCG iterations, so
        // the cost rule alone would allow only the minimum: raise it
        let settings = ReuseSettings { min_iterations: 10, ..Default::default() };
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
        let mut x = b.clone();
        assert_eq!(solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap(), SolveKind::Factorized);
        // soften three rows (as plastic flow would)
        let mut d1 = d0.clone();
        for d in &mut d1[100..103] {
            *d = 2.1;
        }
        let (_, v1) = tridiagonal(&d1);
        let mut x = b.clone();
        let kind = solver.solve(&pattern, &v1, &mut x, 1e-8, false).unwrap();
        let SolveKind::Reused(k) = kind else { panic!("expected reuse, got {kind:?}") };
        assert!(k <= 4, "{k} iterations");
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(residual(&pattern, &v1, &x, &b) <= 1e-8 * bn);
        assert_eq!(solver.stats().factorizations, 1);
    }

    /// A matrix far from the factored one (every diagonal changed by a
    /// factor 50: no low-rank structure) defeats PCG within its allowance:
    /// the solver must fall back to a factorization and still solve exactly.
    #[test]
    fn a_factor_that_no_longer_preconditions_is_replaced() {
        let n = 400;
        let (pattern, v0) = tridiagonal(&vec![2.0001; n]);
        // double precision: the factorization after the fallback solves exactly
        let settings =
            ReuseSettings { min_iterations: 5, max_iterations: 5, single_precision: false, ..Default::default() };
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        let b: Vec<f64> = (0..n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let mut x = b.clone();
        solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap();
        let d1: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 100.0 } else { 2.0001 }).collect();
        let (_, v1) = tridiagonal(&d1);
        let mut x = b.clone();
        let kind = solver.solve(&pattern, &v1, &mut x, 1e-8, false).unwrap();
        assert_eq!(kind, SolveKind::FellBack(5));
        assert_eq!(solver.stats().factorizations, 2);
        assert_eq!(solver.stats().fallbacks, 1);
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(residual(&pattern, &v1, &x, &b) <= 1e-12 * bn);
    }

    /// 2×2 blocks `[[1 + δ, −1], [−1, 1 + δ]]` (eigenvalues `δ` and `2 + δ`):
    /// lower pattern and values.
    fn pairs(deltas: &[f64]) -> (LowerCsc, Vec<f64>) {
        let columns: Vec<Vec<usize>> =
            (0..deltas.len()).flat_map(|i| [vec![2 * i, 2 * i + 1], vec![2 * i + 1]]).collect();
        let values: Vec<f64> = deltas.iter().flat_map(|d| [1.0 + d, -1.0, 1.0 + d]).collect();
        (LowerCsc::from_columns(2 * deltas.len(), &columns), values)
    }

    /// Mixed precision: the `f32` factor of the present matrix alone solves
    /// it with a relative error of about `κ · 6e-8` only (κ = 4e4 here:
    /// measured residual 3.0e-4 of ‖b‖, printed by the assertion message if
    /// it ever reaches 1e-9); the PCG refinement in `f64` must bring the
    /// residual to `η`.
    #[test]
    fn a_single_precision_factor_is_refined_to_the_requested_tolerance() {
        let n = 200;
        let (pattern, v) = tridiagonal(&vec![2.0001; n]);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut alone = Cholesky::analyze(&pattern).unwrap();
        alone.factorize_with(&v, true).unwrap();
        assert!(alone.is_single());
        let mut y = b.clone();
        alone.solve_in_place(&mut y).unwrap();
        let unrefined = residual(&pattern, &v, &y, &b) / bn;
        assert!(unrefined > 1e-9, "the f32 solve alone reached {unrefined:e}: the test proves nothing");

        let settings = ReuseSettings { min_iterations: 10, ..Default::default() };
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        let mut x = b.clone();
        assert_eq!(solver.solve(&pattern, &v, &mut x, 1e-11, false).unwrap(), SolveKind::Factorized);
        assert!(residual(&pattern, &v, &x, &b) <= 1e-11 * bn, "{unrefined:e}");
        let st = solver.stats();
        assert_eq!((st.factorizations, st.single_factorizations, st.precision_fallbacks), (1, 1, 0));
        assert!(st.krylov_iterations >= 1);
    }

    /// A matrix too ill-conditioned for `f32`: 2×2 blocks whose small
    /// eigenvalues `δ ∈ [3e-7, 1e-6]` are of the size of the rounding of
    /// `1 + δ` (1.2e-7), so the `f32` factor (which still exists) gets each
    /// of them wrong by up to ~20 %, differently per block; PCG needs more
    /// than the 5 iterations allowed. The solver must fall back to an `f64`
    /// factor, solve exactly, and stay in `f64`.
    #[test]
    fn a_single_precision_factor_that_does_not_precondition_falls_back_to_double() {
        let deltas: Vec<f64> = (0..100).map(|i| 3e-7 + 7e-7 * ((i * 37) % 100) as f64 / 100.0).collect();
        let (pattern, v) = pairs(&deltas);
        let settings = ReuseSettings { min_iterations: 5, max_iterations: 5, ..Default::default() };
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        let b: Vec<f64> = (0..pattern.n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut x = b.clone();
        assert_eq!(solver.solve(&pattern, &v, &mut x, 1e-10, false).unwrap(), SolveKind::Factorized);
        let st = *solver.stats();
        assert_eq!((st.factorizations, st.single_factorizations, st.precision_fallbacks), (2, 1, 1), "{st:?}");
        // a backward-stable f64 solve leaves ε ‖A‖ ‖x‖ ≈ 1e-16 · 2 · ‖b‖ / 3e-7
        // ≈ 7e-10 ‖b‖ (measured 2.2e-10; the f32 factor alone leaves 0.12)
        let r = residual(&pattern, &v, &x, &b) / bn;
        let mut alone = Cholesky::analyze(&pattern).unwrap();
        alone.factorize_with(&v, true).unwrap();
        let mut y = b.clone();
        alone.solve_in_place(&mut y).unwrap();
        eprintln!("residual {r:e}, f32 alone {:e}", residual(&pattern, &v, &y, &b) / bn);
        assert!(r <= 1e-8, "{r:e}");
        // the next factorization is in f64 (a matrix changed everywhere)
        let (_, v2) = pairs(&deltas.iter().map(|d| 2.0 * d).collect::<Vec<_>>());
        let mut x = b.clone();
        solver.solve(&pattern, &v2, &mut x, 1e-10, false).unwrap();
        assert_eq!(solver.stats().single_factorizations, 1);
        assert!(residual(&pattern, &v2, &x, &b) <= 1e-8 * bn);
    }

    /// Disabled reuse factorizes every time.
    #[test]
    fn disabled_reuse_factorizes_every_solve() {
        let (pattern, v0) = tridiagonal(&[3.0; 10]);
        let settings = ReuseSettings { enabled: false, ..Default::default() };
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        for _ in 0..3 {
            let mut x = vec![1.0; 10];
            assert_eq!(solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap(), SolveKind::Factorized);
        }
        assert_eq!((solver.stats().factorizations, solver.stats().reused), (3, 0));
    }
}
