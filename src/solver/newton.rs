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
    pub increment_norm: f64,
}

/// A nonlinear system solved by [`solve`].
pub trait NonlinearProblem {
    /// Error type of the problem's own operations.
    type Error: std::error::Error + Send + Sync + 'static;
    /// Evaluates residual and tangent at the current iterate.
    fn evaluate(&mut self) -> Result<Evaluation, Self::Error>;
    /// Solves with the current tangent and applies `x ← x + Δx`.
    fn correct(&mut self) -> Result<Correction, Self::Error>;
}

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
}

impl Default for NewtonSettings {
    fn default() -> Self {
        Self {
            max_iterations: 25,
            residual_tolerance: 1e-6,
            displacement_tolerance: 1e-6,
            divergence_ratio: 1e6,
            stagnation_iterations: usize::MAX,
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
    loop {
        let ev = match problem.evaluate() {
            Ok(ev) => ev,
            Err(e) => return fail(report, Failure::Problem, Some(e.to_string())),
        };
        let r = ev.residual_norm / ev.force_scale.max(f64::MIN_POSITIVE);
        let r = if ev.residual_norm == 0.0 { 0.0 } else { r };
        report.residuals.push(r);
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
        let predicted = match (last_correction, n >= 2) {
            (Some(c), true) if r < report.residuals[n - 2] => Some(c * r / report.residuals[n - 2]),
            _ => None,
        };
        let small_correction = last_correction.is_none_or(|c| c <= settings.displacement_tolerance)
            || predicted.is_some_and(|c| c <= settings.displacement_tolerance)
            || r <= 1e-3 * settings.residual_tolerance;
        if ev.settled && r <= settings.residual_tolerance && small_correction {
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
