//! Tests of `solver::stepping` (a file of their own: the module is near the
//! length limit).

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
            releasing: false,
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

/// A [`Spring`] that records, per increment, whether Newton asked its
/// first correction to finish the increment (`newton`, the finishing
/// correction).
struct Asked {
    s: Spring,
    evaluations: usize,
    first: Vec<bool>,
}

impl NonlinearProblem for Asked {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        self.evaluations += 1;
        self.s.evaluate()
    }
    fn finish_within(&mut self, _eta: f64) -> bool {
        if self.evaluations == 1 {
            *self.first.last_mut().unwrap() = true;
        }
        true
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        self.s.correct()
    }
}

impl Incremental for Asked {
    fn set_load_factor(&mut self, lambda: f64) {
        self.s.set_load_factor(lambda);
        self.evaluations = 0;
        self.first.push(false);
    }
    fn commit(&mut self) {
        self.s.commit();
    }
    fn restore(&mut self) {
        self.s.restore();
    }
}

impl Observer<Asked> for () {
    fn converged(&mut self, _: &Asked, _: &Increment) {}
}

/// A linear spring converges in one correction: every increment after
/// the first has its first correction asked to finish it. The softening
/// spring's increments take three or more: none is asked.
#[test]
fn an_increment_after_an_about_linear_one_asks_its_first_correction_to_finish() {
    let steps = StepSettings { initial: 0.25, max: 0.25, ..Default::default() };
    let mut linear = Asked { s: Spring::new(|u| (2.0 * u, 2.0), 3.0), evaluations: 0, first: Vec::new() };
    run(&mut linear, &steps, &NewtonSettings::default(), &mut (), &Interrupt::new()).unwrap();
    assert_eq!(linear.first, [false, true, true, true]);

    let mut soft = Asked { s: Spring::new(softening, 3.0), evaluations: 0, first: Vec::new() };
    let history = run(&mut soft, &steps, &NewtonSettings::default(), &mut (), &Interrupt::new()).unwrap();
    assert!(history.iter().all(|i| i.newton.iterations >= 3), "{history:?}");
    assert!(soft.first.iter().all(|&f| !f), "{:?}", soft.first);
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
        Ok(Evaluation {
            residual_norm: self.r.abs(),
            force_scale: 3.0 * self.lambda.max(1e-3),
            settled: true,
            releasing: false,
        })
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
