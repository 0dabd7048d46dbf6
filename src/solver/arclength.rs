//! Arc-length path following of `R(u, λ) = f_int(u) − λ f = 0` through
//! limit points (where `λ` turns back) and snap-backs (where the
//! displacements do), knowing nothing about finite elements.
//!
//! Load control cannot pass a maximum of `λ`, and control of one
//! displacement cannot pass a point where that displacement turns back.
//! Here `λ` is an unknown and each increment is held to a fixed length `Δl`
//! of the path (Riks, *Int. J. Solids Struct.* 15 (1979) 529–551; Crisfield,
//! *Comput. Struct.* 13 (1981) 55–62):
//!
//! ```text
//! Δuᵀ Δu + ψ² Δλ² fᵀf = Δl²,
//! ```
//!
//! with `Δu`, `Δλ` the change since the last converged point. `ψ = 0` (the
//! default, [`ArcLengthSettings::psi`]) is Crisfield's *cylindrical* method:
//! the load term, whose units differ from the displacements' and which
//! matters little once the path turns, is dropped; `ψ = 1` is the spherical
//! constraint of Riks and Wempner. Crisfield's form was chosen over Riks'
//! linearized normal plane because it keeps the iterates on the sphere
//! (cylinder) itself, which with the root choice below follows a sharply
//! turning path (a snap-back) where the normal plane may miss it (Crisfield,
//! *Non-linear Finite Element Analysis of Solids and Structures*, vol. 1,
//! ch. 9).
//!
//! **Predictor.** With the tangent `K` at the converged point,
//! `K δu_F = f` and `Δλ₁ = ±Δl / √(δu_Fᵀ δu_F + ψ² fᵀf)`, `Δu₁ = Δλ₁ δu_F`.
//! The sign continues the previous increment's direction:
//! `sign(Δu_prevᵀ δu_F + ψ² Δλ_prev fᵀf)` (Feng, Perić & Owen, *Comput.
//! Struct.* 58 (1996) 479–485). The sign of `det K` (the
//! parity of the number of negative pivots) is the classical alternative,
//! but it changes at bifurcations, where the path does not reverse, and the
//! previous direction needs no factor inertia; the number of negative pivots,
//! if the problem knows it, is reported with each increment instead (it
//! marks the passage of limit and bifurcation points).
//!
//! **Corrector** (the bordering, or two-solve, approach): at each iterate
//! the tangent is factorized once and solves two right-hand sides,
//! `K δu_R = −R` and `K δu_F = f`; the correction `δu = δu_R + δλ δu_F`
//! satisfies the linearized equilibrium for any `δλ`, which is chosen to
//! keep the constraint exactly:
//!
//! ```text
//! a δλ² + b δλ + c = 0,  a = δu_Fᵀδu_F + ψ² fᵀf,
//! b = 2 [δu_Fᵀ(Δu + δu_R) + ψ² Δλ fᵀf],
//! c = (Δu + δu_R)ᵀ(Δu + δu_R) + ψ² Δλ² fᵀf − Δl².
//! ```
//!
//! Of the two roots the one whose new increment makes the smaller angle
//! with the present one (largest `Δu_oldᵀ Δu_new + ψ² Δλ_old Δλ_new fᵀf`)
//! is taken, so the iteration does not double back along the path
//! (Crisfield 1981). Complex roots (the line `δu_R + δλ δu_F`
//! misses the cylinder, with too long a step) fail the increment.
//! Convergence is `‖R‖ ≤ tol ‖f‖` ([`ArcLengthSettings::residual_tolerance`]):
//! `λ` multiplies `f`, so `‖f‖` is the force unit of the problem.
//!
//! **Step length.** After a converged increment of `I` corrections,
//! `Δl ← Δl · √(I_d / I)` (Crisfield 1981; `I_d` =
//! `ArcLengthSettings::desired_iterations`), the factor limited to
//! `[1/2, max_growth]` and `Δl` to `[min_ratio, max_ratio] · Δl₀`. A failed
//! increment (iteration limit, divergence, complex roots, or a problem
//! error) is rolled back to the last converged state and retried with `Δl/2`;
//! below the minimum the run stops with an error. `Δl₀` comes from the first
//! predictor and `ArcLengthSettings::initial_dlambda`; no `Δl` exceeds
//! `ArcLengthSettings::max_length`.
//!
//! **No jump along the path.** A long arc can converge on a far part of
//! the path — past a limit point and its snap, onto the stable branch
//! beyond — with nothing at its ends to show it (both tangents positive
//! definite). On a smooth path the converged change `Δu` of a short enough
//! increment is nearly parallel to its predictor (the tangent at its start);
//! one that turned by more than `acos(``ArcLengthSettings::min_cosine``)`
//! is rolled back and redone with half the arc length, at most
//! `MAX_TURNS` times per increment (a kink of the path — a contact
//! closing — turns the direction however short the arc, and is then
//! accepted).
//!
//! **Dissipation control** ([`ArcLengthSettings::dissipation`]): once the
//! structure dissipates, each increment is held to the energy it dissipates
//! instead of its length (`src/solver/arclength_dissipation.rs`).
//!
//! **Landing on the end.** An increment that carries `λ` past
//! `ArcLengthSettings::max_lambda` is redone from its start with `λ`
//! prescribed there (Newton at fixed `λ`, the predictor the tangent's), as
//! load stepping ends on its last load factor; if that fails, the arc is
//! shortened in proportion (a cutback) and the path goes on.

use super::Interrupt;

/// A path-following problem: `R(u, λ) = f_int(u) − λ f` with a fixed
/// reference load `f`; the problem holds its state `u` (and any history).
pub trait PathProblem {
    /// Error type of the problem's own operations.
    type Error: std::error::Error + Send + Sync + 'static;
    /// Number of unknowns.
    fn dimension(&self) -> usize;
    /// The reference load `f` (the applied load is `λ f`).
    fn reference_load(&self, f: &mut [f64]);
    /// The residual `R = f_int(u) − λ f` at the current `u` into `r`, and
    /// the tangent `∂f_int/∂u` at `u`, ready for [`Self::solve`].
    fn residual(&mut self, lambda: f64, r: &mut [f64]) -> Result<(), Self::Error>;
    /// Solves `K x = b` in place for each right-hand side, with the tangent
    /// of the last [`Self::residual`] (one factorization for all).
    fn solve(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), Self::Error>;
    /// `u ← u + δu`.
    fn update(&mut self, du: &[f64]) -> Result<(), Self::Error>;
    /// Accepts the current (converged) state as the new start point.
    fn commit(&mut self);
    /// Returns to the last committed state.
    fn restore(&mut self);
    /// The pseudo-time of the increment about to start: its arc length
    /// over the first one's, times the first one's `|Δλ|` — positive and
    /// fixed through the increment's iterations, where `Δλ` changes sign
    /// past a limit point —, for a rate-dependent regularisation of the
    /// problem (a Duvaut–Lions viscosity). The default ignores it.
    fn pseudo_time_step(&mut self, _step: f64) {}
    /// Negative pivots of the last tangent, if the problem knows them.
    fn negative_pivots(&self) -> Option<usize> {
        None
    }
    /// The inner product of displacement vectors in the constraint (the
    /// default: Euclidean; a problem mixing translations and rotations may
    /// weight them).
    fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }
}

/// Controls of the arc-length method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcLengthSettings {
    /// `Δλ` of the first predictor, which sets `Δl₀` (its sign, the direction).
    pub(crate) initial_dlambda: f64,
    /// Weight of the load in the constraint (0: cylindrical, 1: spherical).
    pub psi: f64,
    /// Smallest `Δl / Δl₀` before giving up.
    pub(crate) min_ratio: f64,
    /// Largest `Δl / Δl₀`.
    pub(crate) max_ratio: f64,
    /// Corrections per increment the step length aims at.
    pub(crate) desired_iterations: usize,
    /// Largest growth of `Δl` from one increment to the next.
    pub(crate) max_growth: f64,
    /// Corrections allowed per increment.
    pub max_iterations: usize,
    /// Convergence: `‖R‖ ≤ residual_tolerance · ‖f‖`.
    pub residual_tolerance: f64,
    /// Failure when `‖R‖/‖f‖` exceeds this factor times its first value (or 1).
    pub(crate) divergence_ratio: f64,
    /// Converged increments after which the run ends.
    pub max_increments: usize,
    /// Largest `Δl` of any increment (`f64::INFINITY`: only `max_ratio`).
    pub(crate) max_length: f64,
    /// The end of the path: an increment passing this `λ` is redone to
    /// land on it (`f64::INFINITY`: none).
    pub(crate) max_lambda: f64,
    /// Smallest cosine between an increment's predictor and its converged
    /// `Δu` (module docs, "No jump along the path").
    pub(crate) min_cosine: f64,
    /// Switch to the dissipation constraint (module docs, "Dissipation
    /// control") once the cylinder's predictor would dissipate this share of
    /// the elastic energy `½ λ fᵀu`; `None`: the cylinder throughout.
    pub dissipation: Option<f64>,
    /// Largest `Δτ` of an increment held to its dissipation
    /// (`f64::INFINITY`: only the corrections' adaptation).
    pub(crate) max_dissipation: f64,
}

/// Most rollbacks of one increment for having turned too far from its
/// predictor (the arc is then 1/64 of the first attempt's).
pub(crate) const MAX_TURNS: usize = 6;

impl Default for ArcLengthSettings {
    fn default() -> Self {
        Self {
            initial_dlambda: 0.1,
            psi: 0.0,
            min_ratio: 1e-4,
            max_ratio: 10.0,
            desired_iterations: 5,
            max_growth: 2.0,
            max_iterations: 20,
            residual_tolerance: 1e-8,
            divergence_ratio: 1e6,
            max_increments: 500,
            max_length: f64::INFINITY,
            max_lambda: f64::INFINITY,
            // 11.5°: converged increments of the shipped arch turn by at
            // most 3.7° (20, 5 or 1 increments per unit λ); a jump over its
            // snap-through turned by 23°
            min_cosine: 0.98,
            dissipation: None,
            max_dissipation: f64::INFINITY,
        }
    }
}

/// Follows the path from the problem's committed state at `lambda0` until
/// the observer ends it or `max_increments` converge. Returns the converged
/// increments.
pub fn trace<P: PathProblem>(
    problem: &mut P,
    lambda0: f64,
    settings: &ArcLengthSettings,
    observer: &mut dyn PathObserver<P>,
    interrupt: &Interrupt,
) -> Result<Vec<PathStep>, Box<PathError>> {
    let mut path = Path::start(problem, lambda0, settings)?;
    let arc0 = path.arc;
    let (min, max) = (arc0 * settings.min_ratio, (arc0 * settings.max_ratio).min(settings.max_length));
    let mut history: Vec<PathStep> = Vec::new();
    let mut cutbacks = 0;
    let stop = |reason, path: &Path<P>, n, attempt| {
        Box::new(PathError { reason, last_lambda: path.lambda, increments: n, attempt, message: None })
    };
    while history.len() < settings.max_increments {
        if interrupt.is_requested() {
            return Err(stop(PathStop::Interrupted, &path, history.len(), None));
        }
        let mut step = path.attempt(settings, interrupt, None);
        // a failure halves the arc, a failed landing shortens it in proportion
        let mut shorten = 0.5;
        if step.converged && step.lambda > settings.max_lambda && path.lambda < settings.max_lambda {
            // redo the increment to land on the end (not a cutback)
            let passed = step.lambda;
            path.p.restore();
            path.fresh = false;
            step = path.attempt(settings, interrupt, Some(settings.max_lambda));
            if !step.converged && step.failure.is_some_and(|f| f != PathFailure::Interrupted) {
                // shorten the arc in proportion to the overshoot instead
                shorten = ((settings.max_lambda - path.lambda) / (passed - path.lambda)).clamp(0.05, 0.45);
            }
        }
        step.index = history.len() + 1;
        if step.converged && !path.dissipating && path.turns < MAX_TURNS && path.cosine() < settings.min_cosine {
            step.converged = false;
            step.message = Some(format!(
                "the converged increment turned by {:.1}° from its predictor (at most {:.1}°: a jump along the path, \
                 past a limit point?)",
                path.cosine().clamp(-1.0, 1.0).acos().to_degrees(),
                settings.min_cosine.acos().to_degrees()
            ));
            step.failure = Some(PathFailure::Turned);
            path.turns += 1;
        }
        if step.converged {
            path.p.commit();
            path.fresh = true;
            path.turns = 0;
            let dissipated = path.dissipated(step.dlambda);
            for (t, d) in path.total.iter_mut().zip(&path.du) {
                *t += d;
            }
            path.lambda = step.lambda;
            std::mem::swap(&mut path.prev, &mut path.du);
            path.prev_dlambda = step.dlambda;
            step.cutbacks = cutbacks;
            step.negative_pivots = path.p.negative_pivots();
            cutbacks = 0;
            let go_on = observer.converged(path.p, &step);
            let factor = (settings.desired_iterations as f64 / step.iterations.max(1) as f64).sqrt();
            if path.dissipating {
                // the arc follows the increments' length, for a return to the cylinder
                let length = path.p.dot(&path.prev, &path.prev).sqrt();
                path.arc = length.clamp(min, max);
                path.tau =
                    Some((dissipated.abs() * factor.clamp(0.5, settings.max_growth)).min(settings.max_dissipation));
            } else {
                path.arc = (path.arc * factor.clamp(0.5, settings.max_growth)).clamp(min, max);
            }
            history.push(step);
            if !go_on {
                break;
            }
        } else {
            path.p.restore();
            path.fresh = false;
            if step.failure == Some(PathFailure::Interrupted) {
                return Err(stop(PathStop::Interrupted, &path, history.len(), Some(step)));
            }
            observer.cut_back(&step);
            cutbacks += 1;
            if path.dissipating {
                path.tau = path.tau.map(|t| t * shorten);
            }
            path.arc *= shorten;
            if path.arc < min {
                return Err(stop(PathStop::ArcTooSmall, &path, history.len(), Some(step)));
            }
        }
    }
    Ok(history)
}

/// The state of the path following between increments.
struct Path<'a, P: PathProblem> {
    p: &'a mut P,
    /// Reference load.
    f: Vec<f64>,
    r: Vec<f64>,
    dr: Vec<f64>,
    df: Vec<f64>,
    /// `Δu` of the present increment.
    du: Vec<f64>,
    /// `Δu` of the last converged increment.
    prev: Vec<f64>,
    prev_dlambda: f64,
    /// `ψ² fᵀf`.
    load_weight: f64,
    /// `‖f‖` (Euclidean, the force unit).
    f_norm: f64,
    /// Last converged load factor.
    lambda: f64,
    arc: f64,
    /// True while the problem's tangent is that of the committed state.
    fresh: bool,
    first_sign: f64,
    /// The present increment's predictor `Δu₁`.
    predictor: Vec<f64>,
    /// Rollbacks of the present increment for turning too far.
    turns: usize,
    /// `Δl₀` and the first increment's `|Δλ|`: the pseudo-time's unit.
    clock: (f64, f64),
    /// `u` since the start of the path (`λ₀ = 0`, `u = 0` there), for the
    /// dissipation constraint.
    total: Vec<f64>,
    /// `ArcLengthSettings::dissipation` of a path from `λ = 0`.
    switch: Option<f64>,
    /// The dissipation `Δτ` each increment is held to, once switched
    /// (module docs, "Dissipation control").
    tau: Option<f64>,
    /// The present attempt is held to `tau` (its predictor found the
    /// structure dissipating).
    dissipating: bool,
    /// `ArcLengthSettings::max_dissipation`.
    max_dissipation: f64,
}

impl<'a, P: PathProblem> Path<'a, P> {
    /// Sets up the vectors and `Δl₀` from the tangent at the start.
    fn start(p: &'a mut P, lambda: f64, settings: &ArcLengthSettings) -> Result<Self, Box<PathError>> {
        let n = p.dimension();
        let mut f = vec![0.0; n];
        p.reference_load(&mut f);
        let f_norm = f.iter().map(|x| x * x).sum::<f64>().sqrt();
        let fail = |message: Option<String>| {
            Box::new(PathError { reason: PathStop::Start, last_lambda: lambda, increments: 0, attempt: None, message })
        };
        if !(f_norm > 0.0) {
            return Err(fail(None));
        }
        let mut path = Path {
            load_weight: settings.psi * settings.psi * f_norm * f_norm,
            p,
            r: vec![0.0; n],
            dr: vec![0.0; n],
            df: f.clone(),
            du: vec![0.0; n],
            prev: vec![0.0; n],
            f,
            prev_dlambda: 0.0,
            f_norm,
            lambda,
            arc: 0.0,
            fresh: true,
            first_sign: if settings.initial_dlambda < 0.0 { -1.0 } else { 1.0 },
            predictor: vec![0.0; n],
            turns: 0,
            clock: (0.0, settings.initial_dlambda.abs()),
            total: vec![0.0; n],
            switch: settings.dissipation.filter(|_| lambda == 0.0),
            max_dissipation: settings.max_dissipation,
            tau: None,
            dissipating: false,
        };
        path.p.residual(lambda, &mut path.r).map_err(|e| fail(Some(e.to_string())))?;
        path.p.solve(&mut [&mut path.df[..]]).map_err(|e| fail(Some(e.to_string())))?;
        let scale = (path.p.dot(&path.df, &path.df) + path.load_weight).sqrt();
        path.arc = (settings.initial_dlambda.abs() * scale).min(settings.max_length);
        if !(path.arc > 0.0 && path.arc.is_finite()) {
            return Err(fail(Some(format!("the first predictor has length {:e}", path.arc))));
        }
        path.clock.0 = path.arc;
        Ok(path)
    }

    /// One increment of length `self.arc` from the committed state — or,
    /// with `land`, to the load factor `land` (Newton at fixed `λ`); the
    /// problem is left at its last iterate.
    fn attempt(&mut self, settings: &ArcLengthSettings, interrupt: &Interrupt, land: Option<f64>) -> PathStep {
        let mut step = PathStep {
            index: 0,
            lambda: self.lambda,
            dlambda: 0.0,
            arc_length: self.arc,
            iterations: 0,
            residuals: Vec::new(),
            converged: false,
            failure: None,
            message: None,
            cutbacks: 0,
            negative_pivots: None,
        };
        self.p.pseudo_time_step(self.arc / self.clock.0 * self.clock.1);
        match self.predict(land.map(|l| l - self.lambda)) {
            Ok(dlambda) => step.dlambda = dlambda,
            Err(e) => return failed(step, PathFailure::Problem, Some(e.to_string())),
        }
        loop {
            step.lambda = land.unwrap_or(self.lambda + step.dlambda);
            if let Err(e) = self.p.residual(step.lambda, &mut self.r) {
                return failed(step, PathFailure::Problem, Some(e.to_string()));
            }
            let rho = self.r.iter().map(|x| x * x).sum::<f64>().sqrt() / self.f_norm;
            step.residuals.push(rho);
            if !rho.is_finite() || rho > settings.divergence_ratio * step.residuals[0].max(1.0) {
                return failed(step, PathFailure::Diverged, None);
            }
            if rho <= settings.residual_tolerance {
                step.converged = true;
                return step;
            }
            if step.iterations >= settings.max_iterations {
                return failed(step, PathFailure::MaxIterations, None);
            }
            if interrupt.is_requested() {
                return failed(step, PathFailure::Interrupted, None);
            }
            match self.correct(step.dlambda, land.is_some()) {
                Ok(Some(dl)) => step.dlambda += dl,
                Ok(None) => return failed(step, PathFailure::ComplexRoots, None),
                Err(e) => return failed(step, PathFailure::Problem, Some(e.to_string())),
            }
            step.iterations += 1;
        }
    }

    /// The predictor `Δu = Δλ₁ δu_F` from the committed state, applied to
    /// the problem (`Δλ₁` from the arc length, or `fixed`); returns `Δλ₁`.
    fn predict(&mut self, fixed: Option<f64>) -> Result<f64, P::Error> {
        if !self.fresh {
            self.p.residual(self.lambda, &mut self.r)?;
        }
        self.fresh = false;
        self.df.copy_from_slice(&self.f);
        self.p.solve(&mut [&mut self.df[..]])?;
        let norm = (self.p.dot(&self.df, &self.df) + self.load_weight).sqrt();
        let toward = self.p.dot(&self.prev, &self.df) + self.load_weight * self.prev_dlambda;
        let sign = if self.prev_dlambda == 0.0 && toward == 0.0 {
            self.first_sign
        } else if toward < 0.0 {
            -1.0
        } else {
            1.0
        };
        // the dissipation constraint's Δλ₁ = 2 Δτ / (λ₀ fᵀδu_F − fᵀu₀),
        // while the structure dissipates along the tangent (else the
        // cylinder); its sign is Δλ's: negative on a softening branch
        let rate = self.rate();
        self.switch_to_dissipation(rate, self.arc / norm);
        self.dissipating = fixed.is_none() && self.tau.is_some() && self.dissipates(rate);
        let dlambda = match (fixed, self.tau) {
            (Some(d), _) => d,
            (None, Some(tau)) if self.dissipating => 2.0 * tau / rate,
            _ => sign * self.arc / norm,
        };
        for (d, x) in self.du.iter_mut().zip(&self.df) {
            *d = dlambda * x;
        }
        self.p.update(&self.du)?;
        self.predictor.copy_from_slice(&self.du);
        Ok(dlambda)
    }

    /// One correction at the present iterate (`Δλ = dlambda` so far):
    /// `K δu_R = −R`, `K δu_F = f`, `δλ` from the constraint, `δu` applied
    /// to the problem (with `fixed`, `δλ = 0`: Newton at fixed `λ`).
    /// Returns `δλ`, or `None` if the roots are complex.
    fn correct(&mut self, dlambda: f64, fixed: bool) -> Result<Option<f64>, P::Error> {
        for (d, r) in self.dr.iter_mut().zip(&self.r) {
            *d = -r;
        }
        self.df.copy_from_slice(&self.f);
        self.p.solve(&mut [&mut self.dr[..], &mut self.df[..]])?;
        let p = &*self.p;
        let (uu, ur, rr) = (p.dot(&self.du, &self.du), p.dot(&self.du, &self.dr), p.dot(&self.dr, &self.dr));
        let (fu, fr, ff) = (p.dot(&self.df, &self.du), p.dot(&self.df, &self.dr), p.dot(&self.df, &self.df));
        let w = self.load_weight;
        let a = ff + w;
        let b = 2.0 * (fu + fr + w * dlambda);
        let c = uu + 2.0 * ur + rr + w * dlambda * dlambda - self.arc * self.arc;
        let disc = b * b - 4.0 * a * c;
        if fixed {
            return self.apply(0.0).map(Some);
        }
        if self.dissipating {
            return match self.dissipation_root(dlambda) {
                Some(root) => self.apply(root).map(Some),
                None => Ok(None),
            };
        }
        if !(disc >= 0.0) || !(a > 0.0) {
            return Ok(None);
        }
        // the roots without cancellation (Press et al., Numerical Recipes, §5.6)
        let q = -0.5 * (b + if b < 0.0 { -1.0 } else { 1.0 } * disc.sqrt());
        let roots = if q == 0.0 { [0.0, 0.0] } else { [q / a, c / q] };
        // Δu_oldᵀ Δu_new + ψ² Δλ_old Δλ_new fᵀf, for δλ = x
        let cosine = |x: f64| uu + ur + x * fu + w * dlambda * (dlambda + x);
        let (c0, c1) = (cosine(roots[0]), cosine(roots[1]));
        let pick = if (c0 - c1).abs() <= 1e-12 * (c0.abs() + c1.abs()) {
            // equal angles: the root nearer the linearized one, −c/b
            let linear = if b != 0.0 { -c / b } else { 0.0 };
            if (roots[0] - linear).abs() <= (roots[1] - linear).abs() { roots[0] } else { roots[1] }
        } else if c0 > c1 {
            roots[0]
        } else {
            roots[1]
        };
        self.apply(pick).map(Some)
    }

    /// `δu = δu_R + δλ δu_F` applied to the problem and the increment;
    /// returns `δλ`.
    fn apply(&mut self, dlambda: f64) -> Result<f64, P::Error> {
        for (d, x) in self.dr.iter_mut().zip(&self.df) {
            *d += dlambda * x;
        }
        self.p.update(&self.dr)?;
        for (u, d) in self.du.iter_mut().zip(&self.dr) {
            *u += d;
        }
        Ok(dlambda)
    }

    /// The cosine between the present increment's `Δu` and its predictor
    /// (1 for a zero vector: nothing turned).
    fn cosine(&self) -> f64 {
        let p = &*self.p;
        let (uu, pp) = (p.dot(&self.du, &self.du), p.dot(&self.predictor, &self.predictor));
        if uu > 0.0 && pp > 0.0 { p.dot(&self.du, &self.predictor) / (uu * pp).sqrt() } else { 1.0 }
    }
}

/// `step` marked as failed.
fn failed(mut step: PathStep, failure: PathFailure, message: Option<String>) -> PathStep {
    step.failure = Some(failure);
    step.message = message;
    step
}

#[path = "arclength_dissipation.rs"]
mod dissipation;
#[path = "arclength_outcome.rs"]
mod outcome;
pub use outcome::{PathError, PathFailure, PathObserver, PathStep, PathStop};

#[cfg(test)]
#[path = "arclength_tests.rs"]
mod tests;
