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
//! symbolic structure, `Cholesky::factor_flops`) over `FLOP_RATE_RATIO`
//! times the flops of one PCG iteration (`4 nnz(L) + 4 nnz(K)`), clamped to
//! `[ReuseSettings::min_iterations, ReuseSettings::max_iterations]`. If PCG does not converge within them,
//! or breaks down (`pᵀ K p ≤ 0`: the tangent is not positive definite), the
//! present tangent is factorized and solved directly (the *fallback*). A solve
//! that needed more than half its allowance marks the factor as worn, and a
//! fallback marks the tangent as changing fast: in both cases the next solve
//! refactors at once instead of trying — but a worn factor is still tried
//! for a solve whose target (its forcing term, or the finishing target
//! below when Newton asks for one) the worn solve's contraction per
//! iteration (`ln η_worn / k`) reaches within half the allowance: the loose
//! first correction of a time step in contact after the tight last one of
//! the step before (examples/tube_drop_weight.toml: 206 factorizations for
//! 632 corrections, `cufem run … --threads 1`). Judged by its finishing
//! target, a step Newton expects to end in one correction is still solved
//! directly: a linear step ends at round-off, not at Newton's tolerance,
//! which the energy ledger of an elastic impact sums over its steps
//! (tests/adaptive_time.rs's hammer). Not in a model whose plies damage:
//! there the loose solves steer the iterates onto another branch of the
//! softening path (`setup`). An `LDLᵀ` factor
//! (indefinite tangent) is never reused.
//!
//! A correction that Newton predicts to be the last of its increment
//! (`solver::newton`, the finishing correction) asks, through
//! `ReusingSolver::finish_next`, for a residual below `η`: PCG then goes
//! on past `η` towards it, but only within half the allowance, the
//! iterations after which a solve marks its factor worn — so the policy
//! counts, worn factors and fallbacks are those of a solve to `η`.
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

use super::bordered::{Border, BorderedWork, FactorBorder, pcg_bordered};
use super::krylov::{GmresWork, Krylov, Stop, pcg};
use super::linear::{Cholesky, LinearError, LowerCsc};

/// How many times faster (in flops per second) the dense kernels of a
/// supernodal factorization run than the memory-bound triangular solves and
/// sparse products of a PCG iteration. Measured with the paper examples on
/// the 2-core CI machine, 1 thread (factorization time / PCG iteration time
/// against their flop ratio): tube 28 L9 11.6, cantilevers 13, block 8.3,
/// compact bar 4 L9 2–4 (small supernodes run slower).
pub(crate) const FLOP_RATE_RATIO: f64 = 10.0;

pub(crate) use unsymmetric::GMRES_RESTART;

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
    pub(crate) min_iterations: usize,
    /// See `min_iterations`.
    pub max_iterations: usize,
    /// Factorize in single precision and refine by PCG in double (module
    /// docs); only with `enabled`.
    pub single_precision: bool,
    /// Try a worn factor for a looser solve its contraction reaches (module
    /// docs); false in a model whose materials soften (`setup`).
    pub(crate) worn_for_loose: bool,
}

impl Default for ReuseSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            tolerance: 0.1,
            min_iterations: 2,
            max_iterations: 50,
            single_precision: true,
            worn_for_loose: true,
        }
    }
}

/// Counters of the solves made.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverStats {
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
    /// Single-precision `LLᵀ` attempts that broke down (the matrix rounded
    /// to `f32` not positive definite; the factor was then made in double).
    pub(crate) single_breakdowns: usize,
    /// Time in numeric factorizations.
    pub factorization_time: Duration,
    /// Time in triangular solves and PCG.
    pub solve_time: Duration,
}

/// How one solve was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SolveKind {
    /// Factorized the present matrix and solved directly.
    Factorized,
    /// PCG with the earlier factor converged in this many iterations.
    Reused(usize),
    /// PCG did not converge in this many iterations; then factorized.
    FellBack(usize),
}

/// A sparse Cholesky factorization with the reuse policy of the module docs.
#[derive(Debug)]
pub(crate) struct ReusingSolver {
    chol: Cholesky,
    settings: ReuseSettings,
    stats: SolverStats,
    has_factor: bool,
    worn: bool,
    /// `ln η / k` of the last converged PCG solve with the present factor
    /// (`η` its forcing term, `k` its iterations): what a worn factor is
    /// expected to do for a looser forcing term (module docs); `None` until
    /// a PCG solve with it converged.
    contraction: Option<f64>,
    /// Set by a fallback: the next solve factorizes without trying PCG.
    skip: bool,
    /// PCG iterations allowed per solve (fixed by the pattern: computed once).
    allowed: Option<usize>,
    work: [Vec<f64>; 5],
    /// GMRES storage (a model with friction).
    gmres: GmresWork,
    /// GMRES iterations of the last solve with a fresh factor: what the
    /// skew part alone costs (the reuse allowance comes on top).
    fresh_iterations: usize,
    /// Factorize in single precision (until a single factor fails to precondition).
    single: bool,
    /// Breakdowns of the single-precision `LLᵀ` since its last success.
    breakdowns: usize,
    /// Factorizations left to make in double before single precision is
    /// tried again (`2^breakdowns − 1` after a breakdown, at most 63).
    backoff: usize,
    /// The border eliminated with the present factor (`solver::bordered`),
    /// if it was made for a bordered solve.
    border: Option<FactorBorder>,
    bordered_work: BorderedWork,
    /// The relative residual the next solve goes on towards once at its
    /// forcing term ([`Self::finish_next`]).
    finish: Option<f64>,
    /// The last solve reached the residual it was asked to go on towards
    /// (or was solved by a direct factor).
    finished: bool,
}

impl ReusingSolver {
    /// Wraps an analysed Cholesky factorization.
    pub fn new(chol: Cholesky, settings: ReuseSettings) -> Self {
        Self {
            chol,
            settings,
            stats: SolverStats::default(),
            has_factor: false,
            worn: false,
            contraction: None,
            skip: false,
            allowed: None,
            work: Default::default(),
            gmres: GmresWork::default(),
            fresh_iterations: 0,
            single: settings.enabled && settings.single_precision,
            breakdowns: 0,
            backoff: 0,
            border: None,
            bordered_work: BorderedWork::default(),
            finish: None,
            finished: false,
        }
    }

    /// True if the last solve reached the relative residual of
    /// [`Self::finish_next`] (a direct solve always does).
    pub(crate) fn finished(&self) -> bool {
        self.finished
    }

    /// Whether a PCG solve that stopped with `outcome` reached its stop's
    /// `finish`: before its `finish_within` (conservatively: one that
    /// reached it at the last allowed iteration counts as not).
    fn reached_finish(stop: Stop, outcome: Krylov) -> bool {
        matches!(outcome, Krylov::Converged(k) if stop.finish >= stop.tol || k < stop.finish_within)
    }

    /// Asks the next solve to go on from its forcing term `η` towards the
    /// relative residual `eta` (a Newton correction predicted to be the
    /// last, `solver::newton`), as far as PCG gets within the iterations
    /// that leave its factor unworn (half the allowance): the reuse policy
    /// reads the same counts as without the request. A solve by a direct
    /// factor is exact anyway; GMRES (friction) does not go on.
    pub(crate) fn finish_next(&mut self, eta: f64) {
        self.finish = Some(eta);
    }

    /// The stop of a PCG solve to `eta` with `allowed` iterations, going on
    /// towards `finish` within half of them.
    fn pcg_stop(eta: f64, finish: Option<f64>, allowed: usize) -> Stop {
        match finish {
            Some(f) if f < eta => Stop { tol: eta, finish: f.max(1e-14), finish_within: allowed / 2 },
            _ => Stop::at(eta),
        }
    }

    /// Makes the next solve factorize its matrix instead of trying PCG with
    /// the present factor (as a worn factor does): the caller knows the
    /// matrix will stay as it is for the solves after it.
    pub(crate) fn refactor_next(&mut self) {
        self.worn = true;
        self.contraction = None;
    }

    /// Number of stored values of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.chol.factor_nnz()
    }

    /// Factorizes `values` now in double precision, whatever the policy
    /// says (the next solves may reuse the factor): for the inertia of a
    /// converged tangent. Not in single precision: near a critical point
    /// the negative eigenvalue is far below the largest times 6e-8, and a
    /// single-precision `LLᵀ` of the rounded matrix may then succeed.
    pub(crate) fn factorize_now(&mut self, values: &[f64]) -> Result<(), LinearError> {
        self.factorize(values, false)
    }

    /// Factorizes `values` in double precision and solves the eigenproblem
    /// `K φ = μ B φ` with that factor (`K` = `values`, `b` on the same
    /// pattern): the structure's own factorization serves the eigensolver,
    /// so a buckling or modal analysis adds no second symbolic analysis or
    /// factor. Not positive definite: [`EigenError::NotPositiveDefinite`].
    pub fn eigen(
        &mut self,
        pattern: &LowerCsc,
        values: &[f64],
        b: &[f64],
        settings: &super::eigen::EigenSettings,
    ) -> Result<super::eigen::EigenSolution, super::eigen::EigenError> {
        match self.factorize(values, false) {
            Err(LinearError::Singular) => return Err(super::eigen::EigenError::NotPositiveDefinite),
            other => other?,
        }
        super::eigen::solve_factored(&mut self.chol, pattern, values, b, settings)
    }

    /// Negative pivots of the present factor (the inertia of the last
    /// factorized matrix: [`Cholesky::negative_pivots`]); `None` before
    /// the first factorization.
    pub fn negative_pivots(&self) -> Option<usize> {
        self.chol.negative_pivots()
    }

    /// Counters so far.
    pub(crate) fn stats(&self) -> &SolverStats {
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
        let allowed = self.allowed_iterations(pattern);
        let try_pcg = self.settings.enabled
            && self.has_factor
            && self.serves(self.stop(forcing), allowed)
            && !self.skip
            && !must_factor
            && self.chol.is_llt();
        self.skip = false;
        let finish = self.finish.take();
        let mut kind = SolveKind::Factorized;
        if try_pcg {
            let t = Instant::now();
            let stop = Self::pcg_stop(self.stop(forcing), finish, allowed);
            let outcome = pcg(pattern, values, &mut self.chol, rhs, stop, allowed, &mut self.work)?;
            self.stats.solve_time += t.elapsed();
            self.stats.krylov_iterations += outcome.iterations();
            self.record(stop, outcome);
            kind = self.reused(outcome, allowed / 2);
            if let SolveKind::Reused(_) = kind {
                return Ok(kind);
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
            let t = Instant::now();
            let stop = Self::pcg_stop(self.stop(forcing), finish, allowed);
            let outcome = pcg(pattern, values, &mut self.chol, rhs, stop, allowed, &mut self.work)?;
            self.stats.solve_time += t.elapsed();
            self.record(stop, outcome);
            match outcome {
                Krylov::Converged(k) => {
                    self.stats.krylov_iterations += k;
                    self.worn = 2 * k > allowed;
                    return Ok(kind);
                }
                Krylov::NotConverged(k) => {
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
        self.finished = true;
        Ok(kind)
    }

    /// Solves the bordered system `[K B; Bᵀ C] [x_u; x_a] = [b_u; b_a]`
    /// (`solver::bordered`) for the symmetric `K` (lower-triangle `values`
    /// on `pattern`) to `η = min(forcing, η_max)`, with the reuse policy of
    /// [`Self::solve`]: PCG preconditioned by the bordered factorization of
    /// an earlier tangent (with as many border columns), else the present
    /// tangent factorized (in single precision if the policy says so) and
    /// its border eliminated with it. `rhs_u`, `rhs_a` hold `b` on entry and
    /// `x` on exit. [`LinearError::KrylovStalled`] if even the present
    /// tangent's double-precision factor does not solve it (the system is
    /// not positive definite): `rhs_u` and `rhs_a` then still hold `b`.
    pub(crate) fn solve_bordered(
        &mut self,
        (pattern, values): (&LowerCsc, &[f64]),
        border: &Border<'_>,
        rhs_u: &mut [f64],
        rhs_a: &mut [f64],
        forcing: f64,
    ) -> Result<SolveKind, LinearError> {
        let fits = self.border.as_ref().is_some_and(|b| b.len() == border.cols.len());
        let allowed = self.allowed_iterations(pattern);
        let try_pcg = self.settings.enabled
            && self.has_factor
            && fits
            && self.serves(self.stop(forcing), allowed)
            && !self.skip
            && self.chol.is_llt();
        self.skip = false;
        let mut kind = SolveKind::Factorized;
        let stop = Self::pcg_stop(self.stop(forcing), self.finish.take(), allowed);
        if try_pcg {
            let outcome = self.bordered((pattern, values), border, rhs_u, rhs_a, stop, allowed)?;
            self.record(stop, outcome);
            kind = self.reused(outcome, allowed / 2);
            if let SolveKind::Reused(_) = kind {
                return Ok(kind);
            }
        }
        self.skip = matches!(kind, SolveKind::FellBack(_));
        let mut single = self.settings.enabled && self.single;
        loop {
            self.factorize(values, single)?;
            self.border = Some(FactorBorder::new(&mut self.chol, border)?);
            // its own factor and border: one iteration in double precision,
            // a few in single
            let outcome = self.bordered((pattern, values), border, rhs_u, rhs_a, stop, allowed)?;
            self.record(stop, outcome);
            match outcome {
                Krylov::Converged(k) => {
                    self.worn = 2 * k > allowed;
                    return Ok(kind);
                }
                Krylov::NotConverged(_) if self.chol.is_single() => {
                    self.stats.precision_fallbacks += 1;
                    self.single = false;
                    single = false;
                }
                Krylov::NotConverged(k) => return Err(LinearError::KrylovStalled(k)),
            }
        }
    }

    /// One bordered PCG solve with the present factor, counted and timed.
    fn bordered(
        &mut self,
        (pattern, values): (&LowerCsc, &[f64]),
        border: &Border<'_>,
        rhs_u: &mut [f64],
        rhs_a: &mut [f64],
        stop: Stop,
        max_iterations: usize,
    ) -> Result<Krylov, LinearError> {
        let factor = self.border.as_ref().ok_or(LinearError::Singular)?;
        let t = Instant::now();
        let outcome = pcg_bordered(
            (pattern, values),
            border,
            (&mut self.chol, factor),
            rhs_u,
            rhs_a,
            stop,
            max_iterations,
            &mut self.bordered_work,
        )?;
        self.stats.solve_time += t.elapsed();
        self.stats.krylov_iterations += outcome.iterations();
        Ok(outcome)
    }

    /// The PCG stop `η = min(forcing, η_max)`, at least 1e-12 (module docs).
    fn stop(&self, forcing: f64) -> f64 {
        forcing.min(self.settings.tolerance).max(1e-12)
    }

    /// Numeric factorization of the present matrix (single precision if
    /// asked and `LLᵀ` succeeds in it), with the counters.
    fn factorize(&mut self, values: &[f64], single: bool) -> Result<(), LinearError> {
        // after LLᵀ broke down in single precision (the matrix rounded to
        // f32 not positive definite; the factor was then made again in
        // double), single precision is tried again only after 1, 3, 7, …
        // factorizations in double: a breakdown can pass (a contact set
        // flipping in a failing attempt: the graded tube breaks down and
        // then factors 79 times in single), while a tangent too
        // ill-conditioned for f32 (the 1M I-beam, all 68 factorizations)
        // would pay a failed attempt before every factorization
        let try_single = single && self.backoff == 0;
        if single && !try_single {
            self.backoff -= 1;
        }
        let t = Instant::now();
        self.has_factor = false;
        self.border = None;
        self.chol.factorize_with(values, try_single)?;
        if try_single {
            if self.chol.is_single() {
                self.breakdowns = 0;
            } else {
                self.breakdowns += 1;
                self.stats.single_breakdowns += 1;
                self.backoff = (1 << self.breakdowns.min(6)) - 1;
            }
        }
        self.stats.factorization_time += t.elapsed();
        self.stats.factorizations += 1;
        self.stats.single_factorizations += usize::from(self.chol.is_single());
        self.has_factor = true;
        self.worn = false;
        self.contraction = None;
        Ok(())
    }

    /// True if the present factor is to be tried for a solve to `eta`: it
    /// is not worn, or (unless `worn_for_loose` is off) the contraction of
    /// the solve that wore it reaches `eta`, or the finishing target if one
    /// is asked, within half the allowance (module docs).
    fn serves(&self, eta: f64, allowed: usize) -> bool {
        // a correction asked to finish is judged by the residual it is to reach
        let eta = self.finish.map_or(eta, |f| f.min(eta));
        !self.worn
            || self.settings.worn_for_loose && self.contraction.is_some_and(|c| eta.ln() / c <= (allowed / 2) as f64)
    }

    /// After a PCG solve that stopped with `outcome`: whether it reached
    /// its `finish`, and the contraction per iteration it showed.
    fn record(&mut self, stop: Stop, outcome: Krylov) {
        self.finished = Self::reached_finish(stop, outcome);
        if let Krylov::Converged(k @ 1..) = outcome {
            self.contraction = Some(stop.tol.ln() / k as f64);
        }
    }

    /// Counts a Krylov solve with an earlier factor: `Reused` — the solve
    /// is done, the factor marked worn if it took more than `worn_after`
    /// iterations — or `FellBack`: the caller factorizes.
    fn reused(&mut self, outcome: Krylov, worn_after: usize) -> SolveKind {
        match outcome {
            Krylov::Converged(k) => {
                self.stats.reused += 1;
                self.worn = k > worn_after;
                SolveKind::Reused(k)
            }
            Krylov::NotConverged(k) => {
                self.stats.fallbacks += 1;
                SolveKind::FellBack(k)
            }
        }
    }

    /// Solves with the factor of the last [`Self::solve`] that factorized
    /// (call it after `solve(.., must_factor = true)` for further
    /// right-hand sides of the same matrix).
    pub(crate) fn solve_again(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
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

#[path = "reuse_unsymmetric.rs"]
mod unsymmetric;

#[cfg(test)]
#[path = "reuse_tests.rs"]
mod tests;
