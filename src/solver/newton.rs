//! Newton–Raphson for `R(x) = 0`, knowing nothing about finite elements.
//!
//! The problem evaluates its residual and tangent at the current iterate,
//! solves `K Δx = −R` and applies the correction. Convergence needs all of
//!
//! * `‖R‖ ≤ tol_R · F`, with `F` the force scale reported by the problem
//!   (applied loads, reactions and contact forces);
//! * `‖Δx‖ ≤ tol_x · ‖x − x_n‖`, the last correction small against the
//!   increment so far (not checked before the first correction, nor when
//!   the residual is already a thousand times below its tolerance, nor when
//!   the next correction, predicted from the contraction of the residual
//!   `‖Δx_k‖ · r_k / r_(k−1)`, is below tolerance);
//! * the problem reports itself *settled* (for contact: the active set did
//!   not change in the last iteration).
//!
//! The iteration stops early when the residual becomes non-finite or grows
//! by more than `divergence_ratio` over its starting value, when it has
//! not fallen below its smallest value so far in `stagnation_iterations`
//! corrections (it is going nowhere: the caller cuts the step back sooner
//! than at `max_iterations`), and before any further correction once an
//! [`Interrupt`] is requested.
//!
//! **The last evaluation.** Once the residual contracts, the next one is
//! predicted as `r_(k+1) ≈ max(r_k³ / r_(k−1)², r_k²)` — quadratic
//! convergence with the constant of the last step, and no faster than the
//! forcing term `η = r_k` of an inexact solve allows. When that prediction
//! and the correction test it implies are within tolerance and the last
//! evaluation was settled, the next evaluation is asked for through
//! [`NonlinearProblem::evaluate_residual`]: a tangent formed there would go
//! unused if it converges. If it does not, the problem forms the tangent
//! before the correction, at the cost of a second evaluation.
//!
//! **The finishing correction.** A correction whose linear solve stops at
//! `η` leaves at least the residual `η r_k`, and after it the next
//! correction, `≈ η` times this one, must pass the correction test: with
//! `η = r_k` a step that is linear or nearly so takes one more correction
//! than its nonlinearity needs (a time step in free vibration:
//! `[1.7e-2 1.2e-6 1.9e-13]`). When the residual the nonlinearity leaves is
//! predicted within half the tolerance — `r_k³ / r_(k−1)²` while the
//! residual contracts, or zero for the first correction of an increment
//! when the load stepping says (`FirstCorrection`) the last increment was about
//! linear — Newton asks the problem to solve this correction to
//! `η = ½ max(min(tol_R / r_k, tol_x / c), 10⁻³ tol_R / r_k)`, with `c` the
//! predicted size of this correction against the increment (1 for the
//! first, `c_k r_k / r_(k−1)` after), through
//! [`NonlinearProblem::finish_within`]; the solve then costs a few more
//! Krylov iterations instead of a correction and its evaluations. The
//! evaluation after a first correction is expected to be the last (above)
//! when the problem reports the request met ([`NonlinearProblem::finished`])
//! and the last increment converged in one (`FirstCorrection::Last`): a
//! laminate whose steps take two corrections from the contact of its
//! delaminated faces would otherwise evaluate its residual alone, find the
//! step unconverged and evaluate again (examples/laminate_drop_weight_damage.toml
//! at a uniform 2.5 µs step with that rule after every two-correction
//! increment: 12,190 evaluations instead of 11,876, the same corrections).
//! An increment that turns out nonlinear after all goes on as before.
//!
//! **An attempt that chatters.** When the problem says that a retry would
//! search along its corrections ([`NonlinearProblem::retry_searches`]: a
//! frictionless contact model, `analysis::structure`), an attempt that has
//! not settled at any evaluation and whose residual has not fallen below
//! half its start after `CHATTER` (6) corrections fails at once (stagnated)
//! instead of running on to `max_iterations`: the contact set of a first
//! touch that cycles keeps the residual at 1 for twenty corrections and
//! more, and the searched retry converges (crates/cufem-cli/tests/retry.rs).
//!
//! **The releasing iterations.** A correction made after an evaluation
//! that reports the discrete state *releasing* ([`Evaluation::releasing`]:
//! contact points only opened since the last one) does not count against
//! `max_iterations`, nor towards the chatter rule above: such a run ends
//! by itself, and its length grows with the mesh, not with the load. Two
//! beams stacked at zero gap start bonded, and Newton peels their
//! interface open a row or two of nodes a correction until only the
//! points that press stay; the first increment of
//! examples/cantilevers_contact.toml takes 18 corrections, of the same
//! beams with 80 B4 along the axis more than 25 at every increment size
//! (the increment is elastic: a cutback scales the solution, not the
//! peeling), and the run failed (tests/contact.rs
//! `stacked_beams_peel_open_past_the_iteration_limit`). At most
//! `RELEASE_ALLOWANCE` times `max_iterations` corrections are made in all.
//!
//! With [`NewtonSettings::line_search`] (or when the problem asks for it,
//! [`NonlinearProblem::searches`]), a correction after which the
//! residual grew *and* the energy still falls along it at its start but
//! rises at its end (`s(η) = Δx·R(x_k + η Δx)`, `s(0) < 0 < s(1)`: the full
//! step overshot the minimum along its direction) is shortened: `η` by
//! regula falsi on `s` (Illinois), at most `LINE_SEARCH_STEPS`
//! evaluations, until `|s(η)| ≤ ½|s(0)|` (Crisfield, *Non-linear Finite
//! Element Analysis of Solids and Structures* 1, §9.3; Matthies & Strang
//! 1979). Corrections after which the residual fell keep their full step,
//! and a problem that cannot search along its correction
//! ([`NonlinearProblem::slopes`] = `None`) is not touched.

use super::Interrupt;

/// What the problem reports after an evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// Euclidean norm of the residual over the unknowns.
    pub residual_norm: f64,
    /// Force scale for the relative residual.
    pub force_scale: f64,
    /// True when discrete state that Newton cannot see (contact status) is stable.
    pub settled: bool,
    /// True when that state changed one way only, as a run of such
    /// evaluations must end (contact points released, none taken back):
    /// the correction after it does not count against
    /// [`NewtonSettings::max_iterations`] (module docs).
    pub releasing: bool,
}

/// What the problem reports after a correction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correction {
    /// `‖Δx‖` of this correction.
    pub norm: f64,
    /// `‖x − x_n‖`, the total change since the start of the increment.
    pub(crate) increment_norm: f64,
}

/// A nonlinear system solved by [`solve`].
pub trait NonlinearProblem {
    /// Error type of the problem's own operations.
    type Error: std::error::Error + Send + Sync + 'static;
    /// Evaluates residual and tangent at the current iterate.
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error>;
    /// Evaluates the residual at the current iterate where [`solve`]
    /// expects it to converge, so that no correction would use the tangent
    /// (module docs). A problem may skip the tangent here, but must then
    /// form it in its next [`Self::correct`]. The default: [`Self::evaluate`].
    fn evaluate_residual(&mut self) -> Result<Evaluation, Self::Error> {
        self.evaluate()
    }
    /// Evaluates residual and tangent at an iterate [`solve`] corrects
    /// from; the tangent may be an approximation the problem trusts for
    /// one correction (the elastic stiffness kept where a few points begin
    /// to yield: `analysis::structure`). The default: [`Self::evaluate`].
    fn evaluate_for_correction(&mut self) -> Result<Evaluation, Self::Error> {
        self.evaluate()
    }
    /// Solves with the current tangent and applies `x ← x + Δx`.
    fn correct(&mut self) -> Result<Correction, Self::Error>;
    /// Asks the next [`Self::correct`] to solve its linear system to the
    /// relative residual `eta` at most: Newton predicts that correction to
    /// be the last (module docs). True if the problem will; the default:
    /// false (its solves are exact, or it does not choose their accuracy).
    fn finish_within(&mut self, _eta: f64) -> bool {
        false
    }
    /// After a [`Self::correct`] asked to finish: true if its solve reached
    /// the residual asked for (a solve may stop short within its budget;
    /// Newton then does not expect the next evaluation to be the last). The
    /// default: true.
    fn finished(&self) -> bool {
        true
    }
    /// For a line search, after an evaluation: `(Δx·R(x_k), Δx·R(x))`, the
    /// last correction `Δx` against the residual at its start `x_k` and at
    /// the present iterate (the slopes of the energy along `Δx`). `None`
    /// (the default): no line search along this correction.
    fn slopes(&self) -> Option<(f64, f64)> {
        None
    }
    /// Moves the iterate to `x_k + η Δx` along the last correction and
    /// reports that correction (called only after [`Self::slopes`] gave
    /// `Some`). The default: nothing moved.
    fn step_to(&mut self, _eta: f64) -> Option<Correction> {
        None
    }
    /// True if the problem asks for the line search whatever
    /// [`NewtonSettings::line_search`] says (a retry of a failed increment
    /// whose contact set cycled: `analysis::structure`). The default: false.
    fn searches(&self) -> bool {
        false
    }
    /// True if a retry of this attempt, after it fails, would search
    /// ([`Self::searches`]): an attempt that has not settled nor halved its
    /// residual in `CHATTER` corrections is then given up (module docs).
    /// The default: false.
    fn retry_searches(&self) -> bool {
        false
    }
}

/// Corrections after which an attempt whose residual has not halved and
/// whose problem never settled fails, when its retry would search
/// ([`NonlinearProblem::retry_searches`]).
const CHATTER: usize = 6;

/// Corrections of one solve, releasing ones included, at most this many
/// times [`NewtonSettings::max_iterations`] (module docs).
pub(crate) const RELEASE_ALLOWANCE: usize = 8;

/// Most evaluations of one line search.
pub(crate) const LINE_SEARCH_STEPS: usize = 4;

/// Smallest step length of a line search.
pub(crate) const SMALLEST_STEP: f64 = 0.1;

/// Newton controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSettings {
    /// Maximum corrections per solve.
    pub max_iterations: usize,
    /// Relative residual tolerance.
    pub residual_tolerance: f64,
    /// Relative correction tolerance.
    pub displacement_tolerance: f64,
    /// Give up when the relative residual exceeds its first value by this factor.
    pub divergence_ratio: f64,
    /// Give up when this many corrections in a row brought no residual
    /// below the smallest one before them (`usize::MAX`, the default:
    /// never). Not a default rule: contact and path-following problems
    /// often converge after such a stretch (the shipped cantilevers failed
    /// their first increment with 4, the elastica took 32 increments
    /// instead of 13); on the crushed tube, whose failed attempts run on to
    /// `max_iterations` after one, 4 saves a fifth of the evaluations
    /// (`solver.stagnation_iterations`, examples/tube_crush.toml).
    pub stagnation_iterations: usize,
    /// Shorten a correction that overshoots (module docs; off by default).
    pub line_search: bool,
}

/// What Newton may assume of an increment's first correction (module docs,
/// the finishing correction), from how the last increment converged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum FirstCorrection {
    /// Nothing: it is solved to its forcing term `η = r₀`.
    #[default]
    Plain,
    /// Solved far enough to be the last (the last increment converged
    /// within two corrections).
    Finishing,
    /// That, and the evaluation after it expected to be the last (the last
    /// increment converged in one).
    Last,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        Self {
            max_iterations: 25,
            residual_tolerance: 1e-6,
            displacement_tolerance: 1e-6,
            divergence_ratio: 1e6,
            stagnation_iterations: usize::MAX,
            line_search: false,
        }
    }
}

/// Why Newton stopped without converging.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Failure {
    /// Iteration limit reached.
    MaxIterations,
    /// Residual grew past the divergence ratio or became non-finite.
    Diverged,
    /// No smaller residual in `stagnation_iterations` corrections.
    Stagnated,
    /// The problem failed (e.g. a singular tangent).
    Problem,
    /// A stop was requested through the [`Interrupt`].
    Interrupted,
    /// The iteration converged, but a check of the converged state
    /// rejected it (the report's message says why; e.g. an arc-length
    /// increment that turned too far from its predictor).
    Rejected,
}

/// History of one Newton solve.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// Corrections made.
    pub iterations: usize,
    /// Relative residual `‖R‖/F` at each evaluation.
    pub residuals: Vec<f64>,
    /// Relative correction `‖Δx‖/‖x − x_n‖` after each correction.
    pub corrections: Vec<f64>,
    /// `None` on convergence.
    pub failure: Option<Failure>,
    /// Message of a problem error, if any.
    pub message: Option<String>,
    /// Corrections shortened by the line search.
    pub(crate) line_searches: usize,
}

impl Report {
    /// True if the solve converged.
    pub fn converged(&self) -> bool {
        self.failure.is_none()
    }
}

/// Runs Newton's method from the problem's current iterate.
pub fn solve<P: NonlinearProblem>(problem: &mut P, settings: &NewtonSettings, interrupt: &Interrupt) -> Report {
    solve_from(problem, settings, FirstCorrection::Plain, interrupt)
}

/// [`solve`], with what the first correction may assume from the last
/// increment (module docs, the finishing correction).
pub(crate) fn solve_from<P: NonlinearProblem>(
    problem: &mut P,
    settings: &NewtonSettings,
    first: FirstCorrection,
    interrupt: &Interrupt,
) -> Report {
    let mut report = Report::default();
    let mut last_correction: Option<f64> = None;
    let mut last_settled = false;
    // the forcing term the first correction was solved to on a trusted
    // finishing request (module docs: read only after that correction)
    let mut finished: Option<f64> = None;
    let mut settled_once = false;
    // corrections made after an evaluation that was not releasing
    let mut counted = 0;
    loop {
        let expected = last_settled && expect_convergence(&report.residuals, last_correction, finished, settings);
        let evaluated = if expected { problem.evaluate_residual() } else { problem.evaluate_for_correction() };
        let mut ev = match evaluated {
            Ok(ev) => ev,
            Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
        };
        let mut r = relative(&ev);
        if (settings.line_search || problem.searches())
            && let Some(&before) = report.residuals.last()
            && r > before
        {
            match line_search(problem) {
                Ok(Some((e, c))) => {
                    (ev, r) = (e, relative(&e));
                    let rel = if c.norm == 0.0 { 0.0 } else { c.norm / c.increment_norm.max(f64::MIN_POSITIVE) };
                    if let Some(last) = report.corrections.last_mut() {
                        *last = rel;
                    }
                    last_correction = Some(rel);
                    report.line_searches += 1;
                }
                Ok(None) => {}
                Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
            }
        }
        report.residuals.push(r);
        last_settled = ev.settled;
        if !r.is_finite() || r > settings.divergence_ratio * report.residuals[0].max(1.0) {
            return fail(report, Failure::Diverged, None);
        }
        // A residual a thousand times below its tolerance needs no further
        // correction check (e.g. a linear problem after its one solve). Nor
        // does one whose *next* correction is predicted below tolerance: the
        // correction is K⁻¹R, so while the residual contracts it shrinks with
        // it, ‖Δx_(k+1)‖ ≈ ‖Δx_k‖ · r_k / r_(k−1) — this saves the iteration
        // that would only confirm convergence.
        let n = report.residuals.len();
        let before = (n >= 2).then(|| report.residuals[n - 2]);
        if ev.settled && converged(r, before, last_correction, settings) {
            return report;
        }
        if counted >= settings.max_iterations
            || report.iterations >= RELEASE_ALLOWANCE.saturating_mul(settings.max_iterations)
        {
            return fail(report, Failure::MaxIterations, None);
        }
        settled_once |= ev.settled;
        // an attempt whose problem never settled and whose residual never
        // halved is handed to a retry that searches (module docs)
        if counted >= CHATTER
            && !settled_once
            && !(settings.line_search || problem.searches())
            && problem.retry_searches()
            && report.residuals[1..].iter().all(|&v| v >= 0.5 * report.residuals[0])
        {
            return fail(report, Failure::Stagnated, None);
        }
        let best =
            report.residuals.iter().enumerate().fold(0, |b, (k, &v)| if v < report.residuals[b] { k } else { b });
        if n - 1 - best >= settings.stagnation_iterations {
            return fail(report, Failure::Stagnated, None);
        }
        if interrupt.is_requested() {
            return fail(report, Failure::Interrupted, None);
        }
        let asked = finishing_forcing(&report.residuals, last_correction, first, settings)
            .filter(|&eta| ev.settled && problem.finish_within(eta));
        match problem.correct() {
            Ok(c) => {
                let rel = if c.norm == 0.0 { 0.0 } else { c.norm / c.increment_norm.max(f64::MIN_POSITIVE) };
                report.corrections.push(rel);
                last_correction = Some(rel);
                // trusted only if the last increment took one correction
                let trusted = report.iterations == 0 && first == FirstCorrection::Last;
                finished = asked.filter(|_| trusted && problem.finished());
            }
            Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
        }
        report.iterations += 1;
        counted += usize::from(!ev.releasing);
    }
}

/// The convergence test on the relative residual `r` (the one before it
/// `before`) and the last relative correction `c` (module docs; the
/// contacts' settledness aside): `r` within tolerance, and the correction
/// test met by `c`, or by the next correction predicted while the residual
/// contracts, `c · r / before`, or waived a thousand times below the
/// residual tolerance.
fn converged(r: f64, before: Option<f64>, c: Option<f64>, settings: &NewtonSettings) -> bool {
    let tol_x = settings.displacement_tolerance;
    let predicted = match (c, before) {
        (Some(c), Some(b)) if r < b => Some(c * r / b),
        _ => None,
    };
    r <= settings.residual_tolerance
        && (c.is_none_or(|c| c <= tol_x)
            || predicted.is_some_and(|c| c <= tol_x)
            || r <= 1e-3 * settings.residual_tolerance)
}

/// True if the next evaluation is predicted to pass [`converged`] (module
/// docs): its residual `max(r_k³ / r_(k−1)², r_k²)` while the residual
/// contracts, after at least one correction — a finishing request does not
/// lower that, as the quadratic term alone underestimates where plasticity
/// switches (examples/tube_crush.toml: 11 evaluations more when it did) —;
/// after the first correction, `η r_0` if it was solved to the forcing
/// term `finished` of a trusted finishing request (`None` after later
/// corrections).
fn expect_convergence(
    residuals: &[f64],
    last_correction: Option<f64>,
    finished: Option<f64>,
    settings: &NewtonSettings,
) -> bool {
    let next = match (last_correction, residuals) {
        (Some(_), [.., before, r]) if r < before => (r * r * r / (before * before)).max(r * r),
        (Some(_), [r]) => match finished {
            Some(eta) => eta * r,
            None => return false,
        },
        _ => return false,
    };
    converged(next, residuals.last().copied(), last_correction, settings)
}

/// The forcing term that lets the next correction be the last (module
/// docs, the finishing correction), if it is predicted to be: `None` when
/// the prediction says more corrections follow anyway, or when `η = r_k`
/// already reaches it.
fn finishing_forcing(
    residuals: &[f64],
    last_correction: Option<f64>,
    first: FirstCorrection,
    settings: &NewtonSettings,
) -> Option<f64> {
    let &r = residuals.last()?;
    if r <= 0.0 {
        return None;
    }
    // the size of the coming correction against the increment, and the
    // residual its nonlinearity leaves
    let (c_next, nonlinear) = match (last_correction, residuals) {
        (None, _) if first != FirstCorrection::Plain => (1.0, 0.0),
        (Some(c), [.., before, _]) if r < *before => (c * r / before, r * r * r / (before * before)),
        _ => return None,
    };
    let tol_r = settings.residual_tolerance;
    if nonlinear > 0.5 * tol_r {
        return None;
    }
    let eta =
        0.5 * (tol_r / r).min(settings.displacement_tolerance / c_next.max(f64::MIN_POSITIVE)).max(1e-3 * tol_r / r);
    (eta < r).then_some(eta)
}

/// The relative residual `‖R‖/F` of an evaluation.
fn relative(ev: &Evaluation) -> f64 {
    if ev.residual_norm == 0.0 { 0.0 } else { ev.residual_norm / ev.force_scale.max(f64::MIN_POSITIVE) }
}

/// Shortens the last correction if it overshot along its direction (module
/// docs): the evaluation and correction of the step length taken, `None`
/// if the full step stays.
fn line_search<P: NonlinearProblem>(problem: &mut P) -> Result<Option<(Evaluation, Correction)>, P::Error> {
    let Some((s0, s1)) = problem.slopes() else { return Ok(None) };
    if !(s0 < 0.0 && s1 > 0.0) {
        return Ok(None);
    }
    // regula falsi on s(η) over the bracket [lo, hi], s(lo) < 0 < s(hi);
    // Illinois: the end kept twice in a row has its value halved
    let (mut lo, mut s_lo, mut hi, mut s_hi) = (0.0, s0, 1.0, s1);
    let mut kept = 0i8;
    let mut taken = None;
    for _ in 0..LINE_SEARCH_STEPS {
        let eta = (lo - s_lo * (hi - lo) / (s_hi - s_lo)).clamp(SMALLEST_STEP, 1.0);
        let Some(c) = problem.step_to(eta) else { return Ok(None) };
        let ev = problem.evaluate()?;
        taken = Some((ev, c));
        let Some((_, s)) = problem.slopes() else { break };
        if s.abs() <= 0.5 * s0.abs() || eta <= SMALLEST_STEP {
            break;
        }
        if s > 0.0 {
            (hi, s_hi) = (eta, s);
            if kept == -1 {
                s_lo *= 0.5;
            }
            kept = -1;
        } else {
            (lo, s_lo) = (eta, s);
            if kept == 1 {
                s_hi *= 0.5;
            }
            kept = 1;
        }
    }
    Ok(taken)
}

fn fail(mut report: Report, failure: Failure, message: Option<String>) -> Report {
    report.failure = Some(failure);
    report.message = message;
    report
}

#[cfg(test)]
#[path = "newton_tests.rs"]
mod tests;
