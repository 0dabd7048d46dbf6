//! Tests of `solver::newton` (a file of their own: the module is near the
//! length limit).

use super::*;

/// x³ − 8 = 0 from x = 3: Newton converges quadratically to 2.
struct Cubic {
    x: f64,
    x0: f64,
    r: f64,
    k: f64,
}

impl NonlinearProblem for Cubic {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        self.r = self.x.powi(3) - 8.0;
        self.k = 3.0 * self.x * self.x;
        Ok(Evaluation { residual_norm: self.r.abs(), force_scale: 8.0, settled: true, releasing: false })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        let dx = -self.r / self.k;
        self.x += dx;
        Ok(Correction { norm: dx.abs(), increment_norm: (self.x - self.x0).abs() })
    }
}

#[test]
fn converges_quadratically_on_a_scalar_equation() {
    let mut p = Cubic { x: 3.0, x0: 3.0, r: 0.0, k: 0.0 };
    let rep = solve(&mut p, &NewtonSettings { residual_tolerance: 1e-14, ..Default::default() }, &Interrupt::new());
    assert!(rep.converged());
    assert!((p.x - 2.0).abs() < 1e-14);
    // r_{k+1} / r_k² bounded (quadratic) once close: check the last ratios
    let r = &rep.residuals;
    let n = r.len();
    assert!(r[n - 2] / (r[n - 3] * r[n - 3]) < 10.0, "{r:?}");
}

/// Linear contraction by one half per iteration (a stale tangent): the
/// correction halves with the residual.
struct Halving {
    x: f64,
}

impl NonlinearProblem for Halving {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        Ok(Evaluation { residual_norm: 1e3 * (self.x - 2.0).abs(), force_scale: 1.0, settled: true, releasing: false })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        let dx = -0.5 * (self.x - 2.0);
        self.x += dx;
        Ok(Correction { norm: dx.abs(), increment_norm: (self.x - 3.0).abs() })
    }
}

/// From x₀ = 3 the k-th correction is 2⁻ᵏ of an increment ≈ 1: the plain
/// rule stops after the 20th (2⁻²⁰ ≤ 10⁻⁶); the predicted next
/// correction 2⁻ᵏ · r_k/r_(k−1) = 2⁻ᵏ⁻¹ is below 10⁻⁶ one iteration
/// earlier, and the 20th correction, not made, is indeed below it. The
/// residual tolerance (0.5, i.e. 1e-3 · 0.5 reached only at k = 21) does
/// not decide here.
#[test]
fn stops_when_the_predicted_next_correction_is_below_tolerance() {
    let mut p = Halving { x: 3.0 };
    let settings = NewtonSettings {
        max_iterations: 100,
        residual_tolerance: 0.5,
        displacement_tolerance: 1e-6,
        ..Default::default()
    };
    let rep = solve(&mut p, &settings, &Interrupt::new());
    assert!(rep.converged());
    assert_eq!(rep.iterations, 19);
    assert!(0.5 * (p.x - 2.0).abs() <= 1e-6 * (p.x - 3.0).abs() * 1.000_01);
}

/// `Halving` or `Cubic` that forms its "tangent" (the correction's
/// factor) only in `evaluate` and drops it in `evaluate_residual`: a
/// correction after a residual-only evaluation must form it again.
struct Lazy {
    x: f64,
    cubic: bool,
    tangent: Option<f64>,
    residual_only: usize,
    reformed: usize,
}

impl Lazy {
    fn residual(&self) -> f64 {
        if self.cubic { self.x.powi(3) - 8.0 } else { 1e3 * (self.x - 2.0) }
    }
}

impl NonlinearProblem for Lazy {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        self.tangent = Some(if self.cubic { 3.0 * self.x * self.x } else { 2e3 });
        let scale = if self.cubic { 8.0 } else { 1.0 };
        Ok(Evaluation { residual_norm: self.residual().abs(), force_scale: scale, settled: true, releasing: false })
    }
    fn evaluate_residual(&mut self) -> Result<Evaluation, Self::Error> {
        let ev = self.evaluate()?;
        self.tangent = None;
        self.residual_only += 1;
        Ok(ev)
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        if self.tangent.is_none() {
            self.evaluate()?;
            self.reformed += 1;
        }
        let dx = -self.residual() / self.tangent.unwrap();
        self.x += dx;
        Ok(Correction { norm: dx.abs(), increment_norm: (self.x - 3.0).abs() })
    }
}

/// Quadratic convergence (x³ = 8): the prediction `max(r³/r_prev², r²)`
/// is above the true `r²/3` (module docs), so the last evaluation, and
/// only it, leaves the tangent out, and the iterates are those of the
/// plain problem to the bit.
#[test]
fn the_last_evaluation_of_a_quadratic_solve_skips_the_tangent() {
    let settings = NewtonSettings { residual_tolerance: 1e-12, ..Default::default() };
    let mut plain = Cubic { x: 3.0, x0: 3.0, r: 0.0, k: 0.0 };
    let expected = solve(&mut plain, &settings, &Interrupt::new());
    let mut p = Lazy { x: 3.0, cubic: true, tangent: None, residual_only: 0, reformed: 0 };
    let rep = solve(&mut p, &settings, &Interrupt::new());
    assert!(rep.converged());
    assert_eq!(rep.residuals, expected.residuals);
    assert_eq!(p.x, plain.x);
    assert_eq!((p.residual_only, p.reformed), (1, 0));
}

/// Linear convergence by one half where the prediction expects a
/// quarter: residual-only evaluations that do not converge are followed
/// by corrections that form the tangent again, and the iterates are
/// those of `Halving` (19 corrections, the test above).
#[test]
fn a_wrongly_expected_convergence_forms_the_tangent_before_correcting() {
    let settings = NewtonSettings {
        max_iterations: 100,
        residual_tolerance: 0.5,
        displacement_tolerance: 1e-6,
        ..Default::default()
    };
    let mut p = Lazy { x: 3.0, cubic: false, tangent: None, residual_only: 0, reformed: 0 };
    let rep = solve(&mut p, &settings, &Interrupt::new());
    assert!(rep.converged());
    assert_eq!(rep.iterations, 19);
    assert!(p.reformed >= 1, "{} {}", p.residual_only, p.reformed);
    assert_eq!(p.residual_only, p.reformed + 1);
    let mut plain = Halving { x: 3.0 };
    solve(&mut plain, &settings, &Interrupt::new());
    assert_eq!(p.x, plain.x);
}

/// `R(x) = x³ − 8` (or `1000 (x − 2)`, linear) solved inexactly as the
/// structure does: each correction leaves `η R` with the forcing term
/// `η = min(r, 0.1)`, tightened by [`NonlinearProblem::finish_within`]
/// when `honour` (else the request is declined).
struct Inexact {
    x: f64,
    x0: f64,
    cubic: bool,
    honour: bool,
    eta: f64,
    asked: Vec<f64>,
    residual_only: usize,
}

impl Inexact {
    fn new(x: f64, cubic: bool, honour: bool) -> Self {
        Self { x, x0: x, cubic, honour, eta: 0.1, asked: Vec::new(), residual_only: 0 }
    }
    fn residual(&self) -> f64 {
        if self.cubic { self.x.powi(3) - 8.0 } else { 1e3 * (self.x - 2.0) }
    }
}

impl NonlinearProblem for Inexact {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        let (r, scale) = (self.residual(), if self.cubic { 8.0 } else { 1.0 });
        self.eta = (r.abs() / scale).min(0.1);
        Ok(Evaluation { residual_norm: r.abs(), force_scale: scale, settled: true, releasing: false })
    }
    fn evaluate_residual(&mut self) -> Result<Evaluation, Self::Error> {
        self.residual_only += 1;
        self.evaluate()
    }
    fn finish_within(&mut self, eta: f64) -> bool {
        self.asked.push(eta);
        if self.honour {
            self.eta = self.eta.min(eta);
        }
        self.honour
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        let k = if self.cubic { 3.0 * self.x * self.x } else { 1e3 };
        // the exact Newton step, short by the linear solve's relative residual
        let dx = -(1.0 - self.eta) * self.residual() / k;
        self.x += dx;
        Ok(Correction { norm: dx.abs(), increment_norm: (self.x - self.x0).abs() })
    }
}

/// A linear increment from `r = 1.7e-2` (a time step in free vibration,
/// module docs). With `η = r` it takes three corrections
/// (`[1.7e-2, 2.9e-4, 8.4e-8, 0]`: after the second the next correction
/// is predicted at 0.017 · 2.9e-4 of the increment, above `tol_x`). When
/// the problem honours the finishing forcing, the second correction is
/// solved to `½ tol_x / c = 2.9e-5` (`c = r₁/r₀`) and is the last; when
/// the stepping also says the last increment was about linear, the
/// first is solved to `½ tol_x = 5e-7` (`c = 1`; `tol_R / r` is the
/// looser bound) and is the last, its residual `1.7e-2 · 5e-7`.
#[test]
fn a_linear_increment_finishes_in_its_first_correction_when_asked() {
    let start = 2.0 + 1.7e-5;
    let settings = NewtonSettings::default();
    let declined = solve(&mut Inexact::new(start, false, false), &settings, &Interrupt::new());
    assert!(declined.converged());
    assert_eq!(declined.iterations, 3, "{:?}", declined.residuals);

    let mut p = Inexact::new(start, false, true);
    let rep = solve(&mut p, &settings, &Interrupt::new());
    assert!(rep.converged());
    assert_eq!(rep.iterations, 2, "{:?}", rep.residuals);
    assert_eq!(p.asked.len(), 1);
    let c = rep.residuals[1] / rep.residuals[0];
    assert!((p.asked[0] - 0.5e-6 / c).abs() < 1e-9 * p.asked[0], "{:?} {c}", p.asked);

    let first = FirstCorrection::Finishing;
    let mut p = Inexact::new(start, false, true);
    let rep = solve_from(&mut p, &settings, first, &Interrupt::new());
    assert!(rep.converged());
    assert_eq!(rep.iterations, 1, "{:?}", rep.residuals);
    assert!((p.asked[0] - 5e-7).abs() < 1e-18, "{:?}", p.asked);
    assert!((rep.residuals[1] - 1.7e-2 * 5e-7).abs() < 1e-12, "{:?}", rep.residuals);
    // the evaluation after it is expected to be the last only when the
    // last increment took one correction
    assert_eq!(p.residual_only, 0);
    let mut p = Inexact::new(start, false, true);
    let rep = solve_from(&mut p, &settings, FirstCorrection::Last, &Interrupt::new());
    assert_eq!((rep.iterations, p.residual_only), (1, 1));

    // a problem that declines is solved as without the request
    let again = solve_from(&mut Inexact::new(start, false, false), &settings, first, &Interrupt::new());
    assert_eq!(again.residuals, declined.residuals);
}

/// x³ = 8 from x = 3 with inexact solves: the nonlinearity and the
/// forcing term `η = r` leave residuals of one order, so the correction
/// that the quadratic prediction calls the last (from 4.0e-4 after
/// 1.75e-2: 2.1e-7) already meets its finishing forcing with `η = r`:
/// nothing is asked, and the iterates are those of a problem that
/// declines.
#[test]
fn a_quadratic_solve_needs_no_finishing_request() {
    let settings = NewtonSettings::default();
    let plain = solve(&mut Inexact::new(3.0, true, false), &settings, &Interrupt::new());
    let mut p = Inexact::new(3.0, true, true);
    let rep = solve(&mut p, &settings, &Interrupt::new());
    assert!(plain.converged() && rep.converged());
    assert_eq!(rep.residuals, plain.residuals);
    assert!(p.asked.is_empty(), "{:?}", p.asked);
}

/// A residual that bounces between 1 and 2 (a cycle): with
/// `stagnation_iterations = 3` the attempt fails after the 3rd
/// correction that brought no residual below the first; without, it
/// runs on to `max_iterations`.
struct Bouncing {
    k: usize,
}

impl NonlinearProblem for Bouncing {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        Ok(Evaluation {
            residual_norm: [1.0, 2.0, 1.5, 1.0][self.k % 4],
            force_scale: 1.0,
            settled: true,
            releasing: false,
        })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        self.k += 1;
        Ok(Correction { norm: 1.0, increment_norm: 1.0 })
    }
}

#[test]
fn gives_up_when_the_residual_stops_reaching_new_lows() {
    let settings = NewtonSettings { max_iterations: 20, stagnation_iterations: 3, ..Default::default() };
    let rep = solve(&mut Bouncing { k: 0 }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::Stagnated), 3), "{rep:?}");
    let rep =
        solve(&mut Bouncing { k: 0 }, &NewtonSettings { max_iterations: 20, ..Default::default() }, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::MaxIterations), 20));
}

/// A residual at 1 whose problem never settles (a contact set that
/// cycles), and whose retry would search or not.
struct Chattering {
    retry_searches: bool,
}

impl NonlinearProblem for Chattering {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        Ok(Evaluation { residual_norm: 1.0, force_scale: 1.0, settled: false, releasing: false })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        Ok(Correction { norm: 1.0, increment_norm: 1.0 })
    }
    fn retry_searches(&self) -> bool {
        self.retry_searches
    }
}

#[test]
fn an_attempt_that_chatters_is_handed_to_a_searching_retry_after_six_corrections() {
    let settings = NewtonSettings { max_iterations: 20, ..Default::default() };
    let rep = solve(&mut Chattering { retry_searches: true }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::Stagnated), CHATTER), "{rep:?}");
    let rep = solve(&mut Chattering { retry_searches: false }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::MaxIterations), 20));
}

/// A contact interface peeled open from a bonded start: each evaluation
/// until `open` reports points released (`releasing`, the residual at 0.3),
/// then the set is settled and the residual gone; with `closes_too` every
/// other evaluation also takes a point back (not releasing).
struct Peeling {
    evaluations: usize,
    open: usize,
    closes_too: bool,
}

impl NonlinearProblem for Peeling {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        self.evaluations += 1;
        let peeling = self.evaluations <= self.open;
        let releasing = peeling && !(self.closes_too && self.evaluations.is_multiple_of(2));
        let residual_norm = if peeling { 0.3 } else { 0.0 };
        Ok(Evaluation { residual_norm, force_scale: 1.0, settled: !peeling, releasing })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        Ok(Correction { norm: 1.0, increment_norm: 1.0 })
    }
    fn retry_searches(&self) -> bool {
        true
    }
}

#[test]
fn corrections_that_only_release_points_do_not_count_against_the_limit() {
    let settings = NewtonSettings { max_iterations: 25, ..Default::default() };
    // forty releasing evaluations, then one settled: forty corrections, more
    // than max_iterations, and no chatter verdict after six
    let rep = solve(&mut Peeling { evaluations: 0, open: 40, closes_too: false }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (None, 40), "{rep:?}");
    // every other one also closing a point: those count, and the attempt
    // is given up as chattering after the sixth of them
    let rep = solve(&mut Peeling { evaluations: 0, open: 60, closes_too: true }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::Stagnated), 2 * CHATTER), "{rep:?}");
    // releasing without end: stopped at RELEASE_ALLOWANCE times the limit
    let rep = solve(&mut Peeling { evaluations: 0, open: usize::MAX, closes_too: false }, &settings, &Interrupt::new());
    assert_eq!((rep.failure, rep.iterations), (Some(Failure::MaxIterations), RELEASE_ALLOWANCE * 25), "{rep:?}");
}

/// A softening spring `atan(x) = 0` from x₀ = 2: Newton's first step
/// lands at −3.5, where the residual is larger, and every further one
/// overshoots more (plain Newton on atan diverges from |x₀| > 1.39).
struct Atan {
    x: f64,
    start: f64,
    dx: f64,
    x0: f64,
}

impl NonlinearProblem for Atan {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        Ok(Evaluation { residual_norm: self.x.atan().abs(), force_scale: 1.0, settled: true, releasing: false })
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        (self.start, self.dx) = (self.x, -self.x.atan() * (1.0 + self.x * self.x));
        self.x += self.dx;
        Ok(Correction { norm: self.dx.abs(), increment_norm: (self.x - self.x0).abs() })
    }
    fn slopes(&self) -> Option<(f64, f64)> {
        Some((self.dx * self.start.atan(), self.dx * self.x.atan()))
    }
    fn step_to(&mut self, eta: f64) -> Option<Correction> {
        self.x = self.start + eta * self.dx;
        Some(Correction { norm: (eta * self.dx).abs(), increment_norm: (self.x - self.x0).abs() })
    }
}

#[test]
fn the_line_search_shortens_an_overshooting_correction() {
    let plain = NewtonSettings::default();
    let rep = solve(&mut Atan { x: 2.0, start: 2.0, dx: 0.0, x0: 2.0 }, &plain, &Interrupt::new());
    assert!(!rep.converged(), "plain Newton should diverge: {rep:?}");
    let searching = NewtonSettings { line_search: true, ..plain };
    let mut p = Atan { x: 2.0, start: 2.0, dx: 0.0, x0: 2.0 };
    let rep = solve(&mut p, &searching, &Interrupt::new());
    assert!(rep.converged() && p.x.abs() < 1e-6, "{rep:?} at x = {}", p.x);
    assert!(rep.line_searches >= 1, "{rep:?}");
    // every recorded residual after the first search is below its start
    assert!(rep.residuals.iter().skip(1).all(|&r| r < rep.residuals[0]), "{:?}", rep.residuals);
}

/// [`Atan`] asking for the search itself (`NonlinearProblem::searches`: a
/// retry of a failed contact increment, `analysis::structure`).
struct Asking(Atan);

impl NonlinearProblem for Asking {
    type Error = std::io::Error;
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error> {
        self.0.evaluate()
    }
    fn correct(&mut self) -> Result<Correction, Self::Error> {
        self.0.correct()
    }
    fn slopes(&self) -> Option<(f64, f64)> {
        self.0.slopes()
    }
    fn step_to(&mut self, eta: f64) -> Option<Correction> {
        self.0.step_to(eta)
    }
    fn searches(&self) -> bool {
        true
    }
}

#[test]
fn a_problem_that_asks_for_the_line_search_gets_it_with_the_setting_off() {
    let mut p = Asking(Atan { x: 2.0, start: 2.0, dx: 0.0, x0: 2.0 });
    let rep = solve(&mut p, &NewtonSettings::default(), &Interrupt::new());
    assert!(rep.converged() && p.0.x.abs() < 1e-6 && rep.line_searches >= 1, "{rep:?} at x = {}", p.0.x);
}

/// From x₀ = 1 Newton on atan converges, its residual falling at every
/// correction (0.79, 0.52, 0.12, …): the line search leaves every
/// iterate as it is, to the last bit.
#[test]
fn the_line_search_leaves_a_contracting_newton_alone() {
    let exact = NewtonSettings { residual_tolerance: 1e-14, ..Default::default() };
    let mut a = Atan { x: 1.0, start: 1.0, dx: 0.0, x0: 1.0 };
    let plain = solve(&mut a, &exact, &Interrupt::new());
    let mut b = Atan { x: 1.0, start: 1.0, dx: 0.0, x0: 1.0 };
    let searched = solve(&mut b, &NewtonSettings { line_search: true, ..exact }, &Interrupt::new());
    assert!(plain.converged() && plain.iterations >= 4, "{plain:?}");
    assert_eq!((&plain, a.x.to_bits()), (&searched, b.x.to_bits()));
}

#[test]
fn reports_non_convergence() {
    let mut p = Cubic { x: 3.0, x0: 3.0, r: 0.0, k: 0.0 };
    let rep = solve(&mut p, &NewtonSettings { max_iterations: 1, ..Default::default() }, &Interrupt::new());
    assert_eq!(rep.failure, Some(Failure::MaxIterations));
    assert_eq!(rep.residuals.len(), 2);
}

#[test]
fn stops_before_correcting_once_interrupted() {
    let mut p = Cubic { x: 3.0, x0: 3.0, r: 0.0, k: 0.0 };
    let stop = Interrupt::new();
    stop.request();
    let rep = solve(&mut p, &NewtonSettings::default(), &stop);
    assert_eq!(rep.failure, Some(Failure::Interrupted));
    assert_eq!((rep.iterations, p.x), (0, 3.0));
}
