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
//! With [`NewtonSettings::line_search`], a correction after which the
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
    /// Solves with the current tangent and applies `x ← x + Δx`.
    fn correct(&mut self) -> Result<Correction, Self::Error>;
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
}

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
    let mut report = Report::default();
    let mut last_correction: Option<f64> = None;
    let mut last_settled = false;
    loop {
        let expected = last_settled && expect_convergence(&report.residuals, last_correction, settings);
        let evaluated = if expected { problem.evaluate_residual() } else { problem.evaluate() };
        let mut ev = match evaluated {
            Ok(ev) => ev,
            Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
        };
        let mut r = relative(&ev);
        if settings.line_search
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
        if report.iterations >= settings.max_iterations {
            return fail(report, Failure::MaxIterations, None);
        }
        let best =
            report.residuals.iter().enumerate().fold(0, |b, (k, &v)| if v < report.residuals[b] { k } else { b });
        if n - 1 - best >= settings.stagnation_iterations {
            return fail(report, Failure::Stagnated, None);
        }
        if interrupt.is_requested() {
            return fail(report, Failure::Interrupted, None);
        }
        match problem.correct() {
            Ok(c) => {
                let rel = if c.norm == 0.0 { 0.0 } else { c.norm / c.increment_norm.max(f64::MIN_POSITIVE) };
                report.corrections.push(rel);
                last_correction = Some(rel);
            }
            Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
        }
        report.iterations += 1;
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
/// contracts, after at least one correction.
fn expect_convergence(residuals: &[f64], last_correction: Option<f64>, settings: &NewtonSettings) -> bool {
    let (Some(_), [.., before, r]) = (last_correction, residuals) else { return false };
    if r >= before {
        return false;
    }
    let next = (r * r * r / (before * before)).max(r * r);
    converged(next, Some(*r), last_correction, settings)
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
mod tests {
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
            Ok(Evaluation { residual_norm: self.r.abs(), force_scale: 8.0, settled: true })
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
            Ok(Evaluation { residual_norm: 1e3 * (self.x - 2.0).abs(), force_scale: 1.0, settled: true })
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
            Ok(Evaluation { residual_norm: self.residual().abs(), force_scale: scale, settled: true })
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
            Ok(Evaluation { residual_norm: [1.0, 2.0, 1.5, 1.0][self.k % 4], force_scale: 1.0, settled: true })
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
        let rep = solve(
            &mut Bouncing { k: 0 },
            &NewtonSettings { max_iterations: 20, ..Default::default() },
            &Interrupt::new(),
        );
        assert_eq!((rep.failure, rep.iterations), (Some(Failure::MaxIterations), 20));
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
            Ok(Evaluation { residual_norm: self.x.atan().abs(), force_scale: 1.0, settled: true })
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
}
