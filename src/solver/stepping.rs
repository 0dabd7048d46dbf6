//! Incremental load stepping with automatic cutbacks, above Newton.
//!
//! The load factor λ goes from 0 to 1. Each increment sets λ, runs Newton
//! from the last converged state and, on success, commits the state (so
//! path-dependent material history only advances on converged increments).
//! A failed increment is rolled back and retried with `Δλ · cutback_factor`;
//! an increment that converged in at most `easy_iterations` iterations lets
//! the next one grow by `growth_factor` (up to `max_increment`). Before the
//! first cutback of an increment, the same `Δλ` is retried once with the
//! problem's cautious linearization ([`Incremental::cautious`]). When `Δλ`
//! would fall below `min_increment`, the analysis stops with a report and the
//! problem is left at its last converged increment.
//!
//! With a [`StepControl`] (`solver.step_control`) the size of the next
//! increment follows instead what the last one changed, as the problem
//! measures it ([`Incremental::measure`]; rules in `solver::step_control`),
//! and an increment that changed far too much is redone smaller. With its
//! `time_error` (adaptive time steps) the increments also land on the
//! problem's landing points ([`Incremental::landing`], a transient
//! analysis's output times): an increment that would pass one is shortened
//! to end on it, and the next takes up the size it was cut from.

use super::Interrupt;
use super::newton::{self, NewtonSettings, NonlinearProblem, Report};
use super::step_control::Verdict;
pub use super::step_control::{StepControl, StepMeasure};

/// A problem that can be driven incrementally.
pub trait Incremental: NonlinearProblem {
    /// Sets the load factor for the next solve (applying prescribed values).
    fn set_load_factor(&mut self, lambda: f64);
    /// Accepts the current (converged) state as the new start point.
    fn commit(&mut self);
    /// Returns to the last committed state.
    fn restore(&mut self);
    /// After a converged solve: updates the problem's constraint
    /// multipliers (augmented Lagrangian); true if it changed them and the
    /// increment must be solved again (the default: nothing to update).
    fn augment(&mut self) -> bool {
        false
    }
    /// Switches to (or back from) a more cautious linearization for a retry
    /// of a failed increment — e.g. elastic tangents at points on their
    /// yield surface when the load reverses. Returns true if that changed
    /// anything (the default: nothing to switch).
    fn cautious(&mut self, _on: bool) -> bool {
        false
    }
    /// Moves the start of the next solve from the committed state along the
    /// last converged increment, scaled by `ratio` = Δλ_next / Δλ_last (a
    /// linear extrapolation of the path; the default: start at the
    /// committed state). Called only within one step of a load history.
    fn extrapolate(&mut self, _ratio: f64) {}
    /// After a converged solve, before it is committed: what the increment
    /// changed, for the step control (the default: nothing measured).
    fn measure(&self) -> StepMeasure {
        StepMeasure::default()
    }
    /// The first λ after `lambda` that an adaptive increment must land on
    /// (the default: none; the end of the span always is one). Read only
    /// with a step control's `time_error`.
    fn landing(&self, _lambda: f64) -> Option<f64> {
        None
    }
}

/// Controls of the load stepping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepSettings {
    /// First increment of λ.
    pub initial: f64,
    /// Largest increment.
    pub max: f64,
    /// Smallest increment before giving up.
    pub min: f64,
    /// Factor applied to Δλ after a failure (0 < f < 1).
    pub cutback_factor: f64,
    /// Factor applied to Δλ after an easy increment (≥ 1).
    pub(crate) growth_factor: f64,
    /// An increment converging within this many iterations is "easy".
    pub(crate) easy_iterations: usize,
    /// Largest number of converged increments before the analysis is stopped.
    pub max_increments: usize,
    /// Step control by an error measure (`None`: the growth after easy
    /// increments alone).
    pub control: Option<StepControl>,
}

impl Default for StepSettings {
    fn default() -> Self {
        Self {
            initial: 0.1,
            max: 0.1,
            min: 1e-5,
            cutback_factor: 0.5,
            growth_factor: 1.5,
            easy_iterations: 4,
            max_increments: 1000,
            control: None,
        }
    }
}

/// One converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct Increment {
    /// 1-based index.
    pub index: usize,
    /// Load factor reached.
    pub lambda: f64,
    /// Its increment.
    pub dlambda: f64,
    /// Newton history of the converged attempt.
    pub newton: Report,
    /// Failed attempts (cutbacks) before it converged.
    pub cutbacks: usize,
    /// What it changed, as the step control measured it (nothing measured
    /// without a step control).
    pub measure: StepMeasure,
}

/// A failed attempt, for logs.
#[derive(Debug, Clone, PartialEq)]
pub struct Cutback {
    /// Index of the increment being attempted.
    pub index: usize,
    /// λ that was attempted.
    pub lambda: f64,
    /// Δλ that failed.
    pub dlambda: f64,
    /// The failed Newton history (converged if the step control rejected it).
    pub newton: Report,
    /// `Some(q)`: the attempt converged, but the step control rejected it,
    /// its measure `q` times the target.
    pub rejected: Option<f64>,
}

/// Callbacks of the stepping loop.
pub trait Observer<P> {
    /// Called after each converged and committed increment.
    fn converged(&mut self, problem: &P, increment: &Increment);
    /// Called after each failed attempt (before the retry).
    fn cut_back(&mut self, _cutback: &Cutback) {}
}

pub use super::stop::{SteppingError, StopReason};

/// Most multiplier updates per increment (augmented Lagrangian); the
/// contact's penetration check then reports what is left.
pub(crate) const MAX_AUGMENTATIONS: usize = 50;

/// Drives `problem` from λ = 0 to 1. Returns the converged increments.
pub fn run<P: Incremental>(
    problem: &mut P,
    steps: &StepSettings,
    newton_settings: &NewtonSettings,
    observer: &mut dyn Observer<P>,
    interrupt: &Interrupt,
) -> Result<Vec<Increment>, Box<SteppingError>> {
    run_span(problem, (0.0, 1.0), 1, steps, newton_settings, observer, interrupt)
}

/// Drives `problem` from λ = `span.0` to `span.1` (one step of a load
/// history; the problem starts from its committed state at `span.0`), the
/// increments numbered from `first_index`. The increment controls are
/// lengths in λ. Returns the converged increments.
pub fn run_span<P: Incremental>(
    problem: &mut P,
    span: (f64, f64),
    first_index: usize,
    steps: &StepSettings,
    newton_settings: &NewtonSettings,
    observer: &mut dyn Observer<P>,
    interrupt: &Interrupt,
) -> Result<Vec<Increment>, Box<SteppingError>> {
    let (mut lambda, end) = span;
    let mut history: Vec<Increment> = Vec::new();
    let mut dlambda = steps.initial.min(steps.max);
    let mut cutbacks = 0;
    // the present increment was already rejected once by the step control
    let mut rejected = false;
    let lands = steps.control.is_some_and(|c| c.time_error.is_some());
    while lambda < end - 1e-12 * end.abs().max(1.0) {
        if history.len() >= steps.max_increments {
            return Err(stop_before(StopReason::TooManyIncrements, first_index + history.len(), lambda, dlambda));
        }
        if interrupt.is_requested() {
            return Err(stop_before(StopReason::Interrupted, first_index + history.len(), lambda, dlambda));
        }
        dlambda = dlambda.min(end - lambda);
        let mut target = if dlambda >= end - lambda { end } else { lambda + dlambda };
        let planned = if lands { land(problem, lambda, &mut dlambda, &mut target) } else { None };
        problem.set_load_factor(target);
        if let Some(last) = history.last() {
            // within a step the loads are linear in λ: start Newton on the
            // secant of the last increment instead of the committed state
            problem.extrapolate((target - lambda) / last.dlambda);
        }
        let report = solve_increment(problem, newton_settings, interrupt);
        if report.failure == Some(newton::Failure::Interrupted) {
            problem.restore();
            problem.set_load_factor(lambda);
            return Err(Box::new(SteppingError {
                reason: StopReason::Interrupted,
                increment: first_index + history.len(),
                lambda: target,
                dlambda,
                last_converged: lambda,
                newton: report,
                seconds: None,
            }));
        }
        if report.converged() {
            let easy = report.iterations <= steps.easy_iterations;
            let mut next = None;
            let mut measure = StepMeasure::default();
            if let Some(control) = &steps.control {
                let growth = if easy { steps.growth_factor } else { 1.0 };
                measure = problem.measure();
                match control.verdict(&measure, dlambda, growth, steps.min, rejected) {
                    Verdict::Reject { factor, q } => {
                        problem.restore();
                        let index = first_index + history.len();
                        let rejection = Cutback { index, lambda: target, dlambda, newton: report, rejected: Some(q) };
                        observer.cut_back(&rejection);
                        (cutbacks, rejected, dlambda) = (cutbacks + 1, true, dlambda * factor);
                        continue;
                    }
                    Verdict::Accept(factor) => next = Some(factor),
                }
            }
            problem.cautious(false);
            problem.commit();
            lambda = target;
            let inc =
                Increment { index: first_index + history.len(), lambda, dlambda, newton: report, cutbacks, measure };
            observer.converged(problem, &inc);
            history.push(inc);
            cutbacks = 0;
            rejected = false;
            if let Some(factor) = next {
                dlambda = (dlambda * factor).clamp(steps.min, steps.max);
                if let Some(planned) = planned.filter(|_| factor >= 1.0) {
                    dlambda = dlambda.max(planned);
                }
            } else if easy {
                dlambda = (dlambda * steps.growth_factor).min(steps.max);
            }
        } else {
            problem.restore();
            let index = first_index + history.len();
            observer.cut_back(&Cutback { index, lambda: target, dlambda, newton: report.clone(), rejected: None });
            cutbacks += 1;
            if problem.cautious(true) {
                // retry the same Δλ with the cautious linearization first
                continue;
            }
            let next = dlambda * steps.cutback_factor;
            if next < steps.min {
                problem.set_load_factor(lambda);
                return Err(Box::new(SteppingError {
                    reason: StopReason::IncrementTooSmall,
                    increment: index,
                    lambda: target,
                    dlambda,
                    last_converged: lambda,
                    newton: report,
                    seconds: None,
                }));
            }
            dlambda = next;
        }
    }
    Ok(history)
}

/// The stop before an increment is attempted (the problem at its last
/// converged state, λ).
fn stop_before(reason: StopReason, increment: usize, lambda: f64, dlambda: f64) -> Box<SteppingError> {
    Box::new(SteppingError {
        reason,
        increment,
        lambda,
        dlambda,
        last_converged: lambda,
        newton: Report::default(),
        seconds: None,
    })
}

/// An adaptive time step lands on the problem's next landing point: the
/// increment from `lambda` to `target` is cut short to end on it, and the
/// size it was cut from is returned (for the next increment).
fn land<P: Incremental>(problem: &P, lambda: f64, dlambda: &mut f64, target: &mut f64) -> Option<f64> {
    let stop = problem.landing(lambda)?;
    if stop > lambda + 1e-9 * *dlambda && stop < *target - 1e-9 * *dlambda {
        let planned = *dlambda;
        (*dlambda, *target) = (stop - lambda, stop);
        return Some(planned);
    }
    None
}

/// Newton on the present increment, solved again after each multiplier
/// update of an augmented Lagrangian until the problem is satisfied (or
/// Newton fails); the reports joined.
fn solve_increment<P: Incremental>(problem: &mut P, newton_settings: &NewtonSettings, interrupt: &Interrupt) -> Report {
    let mut report = newton::solve(problem, newton_settings, interrupt);
    let mut augmentations = 0;
    while report.converged() && augmentations < MAX_AUGMENTATIONS && problem.augment() {
        augmentations += 1;
        let again = newton::solve(problem, newton_settings, interrupt);
        report.iterations += again.iterations;
        report.residuals.extend(again.residuals);
        report.corrections.extend(again.corrections);
        report.line_searches += again.line_searches;
        report.failure = again.failure;
        report.message = again.message;
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::newton::{Correction, Evaluation};

    /// A one-DOF spring with internal force `law(u) = (f, ∂f/∂u)` under the
    /// load `λ · load`.
    struct Spring {
        lambda: f64,
        u: f64,
        u_committed: f64,
        r: f64,
        k: f64,
        law: fn(f64) -> (f64, f64),
        load: f64,
    }

    /// The Newton correction `u −= r/k` of a one-unknown problem.
    fn scalar_correction(u: &mut f64, u_committed: f64, r: f64, k: f64) -> Correction {
        let du = -r / k;
        *u += du;
        Correction { norm: du.abs(), increment_norm: (*u - u_committed).abs() }
    }

    impl Spring {
        fn new(law: fn(f64) -> (f64, f64), load: f64) -> Self {
            Self { lambda: 0.0, u: 0.0, u_committed: 0.0, r: 0.0, k: 0.0, law, load }
        }
    }

    impl NonlinearProblem for Spring {
        type Error = std::io::Error;
        fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
            let (f, k) = (self.law)(self.u);
            self.r = f - self.load * self.lambda;
            self.k = k;
            Ok(Evaluation {
                residual_norm: self.r.abs(),
                force_scale: self.load * self.lambda.max(1e-3),
                settled: true,
            })
        }
        fn correct(&mut self) -> Result<Correction, Self::Error> {
            Ok(scalar_correction(&mut self.u, self.u_committed, self.r, self.k))
        }
    }

    impl Incremental for Spring {
        fn set_load_factor(&mut self, lambda: f64) {
            self.lambda = lambda;
        }
        fn commit(&mut self) {
            self.u_committed = self.u;
        }
        fn restore(&mut self) {
            self.u = self.u_committed;
        }
    }

    /// Softening: u + 0.45 sin(4u) = 3 λ.
    fn softening(u: f64) -> (f64, f64) {
        (u + 0.45 * (4.0 * u).sin(), 1.0 + 1.8 * (4.0 * u).cos())
    }

    /// Requests a stop after the first converged increment.
    struct StopAfterFirst(Interrupt);
    impl Observer<Spring> for StopAfterFirst {
        fn converged(&mut self, _: &Spring, _: &Increment) {
            self.0.request();
        }
    }

    #[test]
    fn an_interrupt_leaves_the_last_converged_increment() {
        let mut s = Spring::new(softening, 3.0);
        let stop = Interrupt::new();
        let steps = StepSettings { initial: 0.1, max: 0.1, ..Default::default() };
        let e = run(&mut s, &steps, &NewtonSettings::default(), &mut StopAfterFirst(stop.clone()), &stop).unwrap_err();
        assert_eq!(e.reason, StopReason::Interrupted);
        assert!((e.last_converged - 0.1).abs() < 1e-15 && (s.lambda - 0.1).abs() < 1e-15);
        assert_eq!(s.u, s.u_committed);
        assert!(e.to_string().contains("interrupted at load factor 0.100000"));
    }

    /// Stiffening spring u³ + u = 30 λ (no limit point, root u = 3 at λ = 1):
    /// Newton from u = 0 with Δλ = 1 needs 10 iterations (30, 20, 13.3, …,
    /// residual 3e-2 after 8), so with at most 8 the first increment fails
    /// and is cut back; the smaller increments converge and the run reaches
    /// λ = 1 on the exact root.
    fn stiffening(u: f64) -> (f64, f64) {
        (u.powi(3) + u, 3.0 * u * u + 1.0)
    }

    #[test]
    fn a_too_large_first_increment_is_cut_back_and_the_run_finishes() {
        struct Cuts(usize);
        impl Observer<Spring> for Cuts {
            fn converged(&mut self, _: &Spring, _: &Increment) {}
            fn cut_back(&mut self, _: &Cutback) {
                self.0 += 1;
            }
        }
        let mut s = Spring::new(stiffening, 30.0);
        let steps = StepSettings { initial: 1.0, max: 1.0, ..Default::default() };
        let newton = NewtonSettings { max_iterations: 8, ..Default::default() };
        let mut obs = Cuts(0);
        let hist = run(&mut s, &steps, &newton, &mut obs, &Interrupt::new()).map_err(|e| e.to_string()).unwrap();
        assert!(obs.0 >= 1, "expected at least one cutback");
        assert!(hist[0].dlambda < 1.0);
        assert!((hist.last().unwrap().lambda - 1.0).abs() < 1e-12);
        assert!((s.u - 3.0).abs() < 1e-5, "{}", s.u);
    }

    /// A 1-DOF elastoplastic spring (k = 1, yield force 1, hardening
    /// H = 0.1) under 3 λ: elastic to λ = 1/3, then the plastic
    /// displacement grows by dp/dλ = 3/H = 30; at λ = 1, p = 20 and u = 23
    /// (backward Euler is exact on this monotonic 1-D path, whatever the
    /// increments).
    struct Hardening {
        lambda: f64,
        u: f64,
        u_committed: f64,
        p: f64,
        p_committed: f64,
        r: f64,
        k: f64,
    }

    impl Hardening {
        fn new() -> Self {
            Self { lambda: 0.0, u: 0.0, u_committed: 0.0, p: 0.0, p_committed: 0.0, r: 0.0, k: 1.0 }
        }
    }

    impl NonlinearProblem for Hardening {
        type Error = std::io::Error;
        fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
            let h = 0.1;
            let trial = self.u - self.p_committed;
            let over = trial.abs() - (1.0 + h * self.p_committed);
            (self.p, self.k) = if over > 0.0 {
                (self.p_committed + trial.signum() * over / (1.0 + h), h / (1.0 + h))
            } else {
                (self.p_committed, 1.0)
            };
            self.r = self.u - self.p - 3.0 * self.lambda;
            Ok(Evaluation { residual_norm: self.r.abs(), force_scale: 3.0 * self.lambda.max(1e-3), settled: true })
        }
        fn correct(&mut self) -> Result<Correction, Self::Error> {
            Ok(scalar_correction(&mut self.u, self.u_committed, self.r, self.k))
        }
    }

    impl Incremental for Hardening {
        fn set_load_factor(&mut self, lambda: f64) {
            self.lambda = lambda;
        }
        fn commit(&mut self) {
            (self.u_committed, self.p_committed) = (self.u, self.p);
        }
        fn restore(&mut self) {
            (self.u, self.p) = (self.u_committed, self.p_committed);
        }
        fn measure(&self) -> StepMeasure {
            StepMeasure { plastic_strain: (self.p - self.p_committed).abs(), ..Default::default() }
        }
    }

    /// Records the plastic increment of every converged increment and the
    /// rejections.
    #[derive(Default)]
    struct PlasticLog {
        dp: Vec<f64>,
        p: f64,
        rejected: usize,
    }
    impl Observer<Hardening> for PlasticLog {
        fn converged(&mut self, s: &Hardening, _: &Increment) {
            self.dp.push(s.p_committed - self.p);
            self.p = s.p_committed;
        }
        fn cut_back(&mut self, c: &Cutback) {
            self.rejected += usize::from(c.rejected.is_some());
        }
    }

    fn plastic_run(steps: &StepSettings) -> (Vec<Increment>, PlasticLog, Hardening) {
        let mut s = Hardening::new();
        let mut log = PlasticLog::default();
        let hist = run(&mut s, steps, &NewtonSettings::default(), &mut log, &Interrupt::new()).unwrap();
        assert!((s.u - 23.0).abs() < 1e-5 && (hist.last().unwrap().lambda - 1.0).abs() < 1e-12, "{}", s.u);
        (hist, log, s)
    }

    #[test]
    fn without_a_step_control_the_count_is_fixed() {
        let (hist, log, _) = plastic_run(&StepSettings { initial: 0.1, max: 0.1, ..Default::default() });
        assert_eq!((hist.len(), log.rejected), (10, 0));
        assert!(hist.iter().all(|i| (i.dlambda - 0.1).abs() < 1e-12));
    }

    /// With `plastic_strain = 5` the elastic start grows (0.1, 0.2, 0.4),
    /// the increment into the plastic range (to λ = 0.7) changes p by
    /// 11 > 2 × 5 and is redone smaller, and the plastic increments then
    /// follow Δλ ≈ 0.8 · 5 / 30: fewer increments than the fixed 10, each
    /// accepted one within twice the target, the same exact end.
    #[test]
    fn the_step_control_grows_elastic_increments_and_bounds_plastic_ones() {
        let control = StepControl { plastic_strain: Some(5.0), ..Default::default() };
        let steps =
            StepSettings { initial: 0.1, max: 1.0, growth_factor: 2.0, control: Some(control), ..Default::default() };
        let (hist, log, _) = plastic_run(&steps);
        assert!(hist.len() < 10, "{} increments", hist.len());
        assert!(hist[1].dlambda > hist[0].dlambda, "the elastic increments grow");
        assert!(log.rejected >= 1, "the jump into the plastic range is redone");
        assert!(log.dp.iter().all(|&dp| dp <= 2.0 * 5.0 * (1.0 + 1e-9)), "{:?}", log.dp);
        // the plastic increments (3.36 across the yield point, 5.19, 4, 4,
        // and the rest to λ = 1) aim at 0.8 of the target: once p grows
        // linearly in λ, they hit it
        let plastic: Vec<f64> = log.dp.iter().copied().filter(|&dp| dp > 0.0).collect();
        assert_eq!(hist.len(), 7, "{plastic:?}");
        assert!(plastic[2..plastic.len() - 1].iter().all(|&dp| (dp - 4.0).abs() < 1e-9), "{plastic:?}");
    }

    /// A too large first increment is rejected once, not repeatedly: with
    /// Δλ = 1 the first attempt changes p by 20 (4 × the target).
    #[test]
    fn a_rejected_increment_is_redone_once() {
        let control = StepControl { plastic_strain: Some(5.0), ..Default::default() };
        let steps = StepSettings { initial: 1.0, max: 1.0, control: Some(control), ..Default::default() };
        let (hist, log, _) = plastic_run(&steps);
        assert_eq!(hist[0].cutbacks, 1);
        // 0.8 / 4 = 0.2, bounded below by a quarter
        assert!((hist[0].dlambda - 0.25).abs() < 1e-12, "{}", hist[0].dlambda);
        assert!(log.rejected >= 1);
    }
}
