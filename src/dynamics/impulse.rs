//! Contact forces at the end of the time step: the impulse of a contact
//! over a Newmark step is `Δt f_c(u_(n+1))`, not Newmark's average of its
//! forces at both ends (`analysis.contact_forces = "implicit"`, the default
//! of a transient analysis).
//!
//! **Why.** Newmark's trapezoidal rule conserves the energy of a smooth
//! potential only to the accuracy of its quadrature, `½ (f_n + f_(n+1)) ·
//! Δu` for the work of a force over the step. A penalty contact's force is
//! not smooth: it switches on and off inside a step, and its spring is
//! far stiffer than the step resolves. At every switch the trapezoidal
//! work is wrong — too little on closing, too much on opening — so a node
//! that chatters on a rigid wall gains energy at every bounce: a steel rod
//! hitting a wall at the default penalty factor, its end nodes' mass kept
//! (`analysis.contact_mass = "kept"`), leaves with 8.41 times its kinetic
//! energy (crates/cufem-cli/tests/dynamics.rs). The contact nodes' chatter itself is what
//! `dynamics::redistribution` removes.
//!
//! **The scheme.** The contact's impulse over the step is taken fully at
//! its end, as the contact-stabilized Newmark method treats the contact
//! forces (Deuflhard, Krause & Ertel, *A contact-stabilized Newmark method
//! for dynamical contact problems*, IJNME 73, 2008; Kane, Repetto, Ortiz &
//! Marsden, *Finite element analysis of nonsmooth contact*, CMAME 180,
//! 1999, whose implicit contact impulse is the same). Newmark's velocity
//! update weighs the forces of both ends, `Δt ((1 − γ) f_n + γ f_(n+1))`;
//! the contact's algorithmic force
//!
//! ```text
//! f'_(n+1) = (f_c(u_(n+1)) − (1 − γ) f'_n) / γ,     ∂f'/∂u = K_c / γ
//! ```
//!
//! makes that weighted sum `Δt f_c(u_(n+1))`. With the trapezoidal rule
//! (`β = ¼, γ = ½`) the displacement update carries the same impulse
//! (`Δt²/4 (f'_n + f'_(n+1)) = Δt²/2 f_c(u_(n+1))`), and the step's
//! energy balance reads `ΔT + ΔU_int = W_ext + f_c(u_(n+1)) · Δu`. A
//! frictionless penalty contact has the convex potential `Φ = ½ ε ⟨−g⟩²`
//! of a gap linear in the displacements (node to node, a flat rigid
//! surface, a rigid impactor's motion), so `f_c(u_(n+1)) · Δu ≤ Φ(u_n) −
//! Φ(u_(n+1))`: **the contact cannot create energy**. It dissipates the
//! Bregman distance `Φ(u_n) − Φ(u_(n+1)) − ∇Φ(u_(n+1)) · (u_n − u_(n+1))
//! = ½ ε Δg²` of an active point per step — a share of the penalty
//! spring's own energy, which vanishes as the penalty stiffens. (A curved
//! rigid surface's gap is not linear; its curvature adds a term of the
//! order of the penetration over the radius.)
//!
//! **Bossak.** With Bossak's α the residual weighs the accelerations as
//! `M ((1 − α) a_(n+1) + α a_n)`, so the force that enters the velocity
//! update is `g` with `f'_(n+1) = (1 − α) g_(n+1) + α g_n` (`crate::newmark::Recursion`):
//! `g_(n+1) = (f_c(u_(n+1)) − (1 − γ) g_n) / γ` keeps the step's impulse
//! `Δt f_c(u_(n+1))`, and `∂f'/∂u = (1 − α) K_c / γ`; with α = 0, `g = f'`.
//! The energy statements below are the trapezoidal rule's; under Bossak's
//! method the balance carries the scheme's own dissipation as well.
//!
//! `f'` is the force the residual and the energy balance use; the contact
//! points keep the physical `f_c` for output. `f'` stays where a contact
//! opened, alternating in sign with the trapezoidal rule (decaying by
//! `(γ − 1)/γ` per step with `γ > ½`): the part of the last closed step's
//! impulse Newmark's average still owes. `analysis.contact_forces =
//! "newmark"` averages the contact forces like every other force.
//!
//! **Cohesive interfaces** (`analysis.interface_forces = "implicit"`, the
//! default of a transient analysis with interfaces) take the same impulse.
//! At a fixed damage `d` a point's law has the potential (`crate::materials::cohesive`,
//! `δ3` the opening, `δ_s` the slip)
//!
//! ```text
//! ψ(δ, d) = ½ K ⟨−δ3⟩² + ½ (1 − d) K (⟨δ3⟩² + |δ_s|²),    t = ∂ψ/∂δ,
//! ```
//!
//! convex in `δ` (a closing interface carries the full penalty at any
//! damage) and non-increasing in `d`, which never decreases. The
//! interface's work over a step with the impulse at its end is then
//!
//! ```text
//! t(δ_(n+1), d_(n+1)) · Δδ ≥ ψ(δ_(n+1), d_(n+1)) − ψ(δ_n, d_(n+1))
//!                          ≥ ψ(δ_(n+1), d_(n+1)) − ψ(δ_n, d_n)
//! ```
//!
//! (convexity, then `d_(n+1) ≥ d_n`): **the interfaces cannot create
//! energy**, and the energy ledger's `delamination` — their work less the
//! energy they hold, `ψ` — never decreases (`dynamics::energy`, which
//! takes their work with `f'`). With Newmark's average a separated
//! interface that closes within a step engages its full compression
//! penalty, far stiffer than the step resolves, and its trapezoidal work
//! falls short of the energy it stores, then gives more back: separated
//! plies that close again create energy (`"newmark"`, kept to show it,
//! tests/delamination_energy.rs). The price is the Bregman distance
//! `ψ(δ_n) − ψ(δ_(n+1)) − t_(n+1) · (δ_n − δ_(n+1))` per point and step,
//! `½ K |Δδ|²` on a branch, counted as dissipation by the ledger: first
//! order in the step for the interface's own vibration. The Duvaut–Lions
//! viscosity keeps this: the traction is the secant of the viscous damage
//! `d_v`, which never decreases either.
//!
//! **Discrete gradient** (`analysis.interface_forces =
//! "discrete_gradient"`; Gonzalez, *J. Nonlinear Sci.* 6, 1996; Armero &
//! Romero, CMAME 190, 2001, for dissipative laws). The end-of-step
//! traction books as dissipated, of a point that passes its whole
//! softening branch within a step, only the energy the point held. The
//! discrete gradient
//!
//! ```text
//! t* = t_(n+1) + (ψ_(n+1) − ψ_n + ΔD − t_(n+1)·Δδ) / |Δδ|² Δδ      (t* = t_(n+1) where |Δδ| < 1e-9 N/K)
//! ```
//!
//! with `ΔD` the law's own dissipation over the step (`CohesiveState::
//! dissipated`) does work `t*·Δδ = Δψ + ΔD` exactly, so the ledger's
//! `delamination` is the law's dissipation after every step; the same
//! impulse recursion carries it (`f*` in place of `f(u_(n+1))`). With a
//! viscosity `ΔD` is the carried damage's, `½ (ψ(δ, d_v,n) − ψ(δ, d_v,n+1))`
//! summed over both ends of the step (the law's would leave a residual at
//! `Δδ = 0` while `d_v` relaxes, and `t*` unbounded); its excess over the
//! law's is the summary's `viscous_j`. The tangent is the symmetric part of
//! `∂t*/∂δ` by central differences (`interfaces::Interfaces`). A closed or
//! elastic interface then conserves its energy (the midpoint traction of a
//! quadratic `ψ`), so the unresolved ringing of its stiff penalty is not
//! damped: on an impact it needs Newmark's `γ > ½` (docs/limitations.md).

use crate::assembly::Phase;
pub(crate) use crate::newmark::Recursion;

/// How a transient analysis integrates its contact forces (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactForces {
    /// The contact impulse at the end of the step (cannot create energy).
    #[default]
    Implicit,
    /// Newmark's average of the forces at both ends of the step.
    Newmark,
}

/// How a transient analysis integrates the forces of its cohesive
/// interfaces (`analysis.interface_forces`, module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InterfaceForces {
    /// The interfaces' impulse at the end of the step (cannot create
    /// energy).
    #[default]
    Implicit,
    /// Newmark's average of the forces at both ends of the step.
    Newmark,
    /// The impulse of each point's discrete-gradient traction
    /// (`interfaces::Interfaces`): its work over a step is the change of
    /// the energy it holds plus the law's dissipation, exactly.
    DiscreteGradient,
}

impl InterfaceForces {
    /// True if the interfaces' force is replaced by an impulse
    /// ([`Impulse`]): the end-of-step traction's or the discrete gradient's.
    pub(crate) fn impulse(self) -> bool {
        matches!(self, Self::Implicit | Self::DiscreteGradient)
    }
}

/// The algorithmic force `f'` of one kind of non-smooth force (the
/// contacts', or the interfaces') in the present step, and the velocity
/// update's `g` in it and in the last converged one (module docs).
#[derive(Debug, Clone)]
pub(crate) struct Impulse {
    recursion: Recursion,
    committed: Vec<f64>,
    trial: Vec<f64>,
    force: Vec<f64>,
}

impl Impulse {
    /// No force yet, with the weights `recursion`, `n` DOFs.
    pub fn new(recursion: Recursion, n: usize) -> Self {
        Self { recursion, committed: vec![0.0; n], trial: vec![0.0; n], force: vec![0.0; n] }
    }

    /// The factor `(1 − α)/γ` on the stiffness of the forces.
    pub fn weight(&self) -> f64 {
        self.recursion.weight()
    }

    /// `f'` from the physical force `f` at the end of the step.
    pub fn update(&mut self, physical: &[f64]) {
        for (((f, g), &p), &c) in self.force.iter_mut().zip(&mut self.trial).zip(physical).zip(&self.committed) {
            (*g, *f) = self.recursion.step(p, c);
        }
    }

    /// `f'` of the last [`Impulse::update`].
    pub fn force(&self) -> &[f64] {
        &self.force
    }

    /// The step converged: its `g` is the committed one.
    pub fn commit(&mut self) {
        self.committed.clone_from(&self.trial);
    }
}

/// The end-of-step impulses of a transient analysis: of its contacts
/// (`analysis.contact_forces = "implicit"`, with contacts) and of its
/// cohesive interfaces (`analysis.interface_forces = "implicit"`, with
/// interfaces); neither in a static one. Not a contribution: each replaces
/// the force of the contributions of its [`Phase`] and weights their
/// stiffness by `1/γ`.
#[derive(Debug, Clone, Default)]
pub(crate) struct Impulses {
    /// The contacts' ([`Phase::Contact`]).
    pub contacts: Option<Impulse>,
    /// The interfaces' ([`Phase::Interfaces`]).
    pub interfaces: Option<Impulse>,
}

impl Impulses {
    /// The impulse that replaces the forces of the contributions of `phase`.
    pub fn of(&self, phase: Phase) -> Option<&Impulse> {
        match phase {
            Phase::Contact => self.contacts.as_ref(),
            Phase::Interfaces => self.interfaces.as_ref(),
            Phase::Elements | Phase::Loads => None,
        }
    }

    /// The factor on the stiffness of the contributions of `phase`:
    /// `(1 − α)/γ` under an impulse, else 1.
    pub fn weight(&self, phase: Phase) -> f64 {
        self.of(phase).map_or(1.0, Impulse::weight)
    }

    /// The force the residual and the energy balance take for a
    /// contribution of `phase` whose physical force is `physical`.
    pub fn force<'a>(&'a self, phase: Phase, physical: &'a [f64]) -> &'a [f64] {
        self.of(phase).map_or(physical, Impulse::force)
    }

    /// The step converged: every `f'` is committed.
    pub fn commit(&mut self) {
        self.contacts.iter_mut().chain(self.interfaces.iter_mut()).for_each(Impulse::commit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What Bossak's integrator sees: the residual takes `f'`, so the
    /// acceleration share is `g_(n+1) = (f'_(n+1) − α g_n) / (1 − α)` and
    /// the velocity update's impulse `Δt ((1 − γ) g_n + γ g_(n+1))`. Over a
    /// force that switches on, varies and off, [`Impulse`] must make each
    /// step's impulse `Δt f(u_(n+1))` exactly, for Newmark's method and for
    /// Bossak's α = −0.1 (γ = 0.6); g recovered from the emitted `f'`
    /// alone, independently of what the impulse keeps (committing `f'`
    /// instead of `g` fails it for α ≠ 0).
    #[test]
    fn the_emitted_force_carries_the_end_of_step_impulse() {
        for (gamma, alpha) in [(0.5, 0.0), (0.6, -0.1)] {
            let mut impulse = Impulse::new(Recursion { gamma, alpha }, 1);
            let forces = [0.0, 3.0, 5.0, -1.0, 4.0, 0.0, 0.0, 2.0, 0.0, 0.0];
            let mut g_n = 0.0;
            for &f in &forces {
                impulse.update(&[f + 7.0]); // a Newton iterate first
                impulse.update(&[f]);
                let g = (impulse.force()[0] - alpha * g_n) / (1.0 - alpha);
                let share = (1.0 - gamma) * g_n + gamma * g;
                assert!((share - f).abs() < 1e-12, "γ {gamma}, α {alpha}: impulse {share} for {f}");
                impulse.commit();
                g_n = g;
            }
        }
    }

    /// One mass on a penalty spring that it strikes, closes and leaves —
    /// the trapezoidal rule with the end-of-step impulse never gains
    /// energy, and gives back all but the spring's Bregman losses; with
    /// Newmark's average (the same recursion with `f'` replaced by the
    /// physical force) it gains energy. An independent integration of
    /// `m ü = −k ⟨u⟩` (u > 0 closed) by the two schemes.
    fn bounce(implicit: bool, k: f64, dt: f64) -> f64 {
        let (m, gamma) = (1.0, 0.5);
        let (mut u, mut v, mut a) = (-0.3 * dt, 1.0, 0.0);
        let mut f_n = 0.0;
        for _ in 0..2000 {
            // solve the step's equation for u_(n+1) by bisection on the
            // monotone residual m a(u) + f'(u)
            let force = |x: f64| k * x.max(0.0);
            let acc = |x: f64| 4.0 / (dt * dt) * (x - u - dt * v) - a;
            let step = Recursion { gamma, alpha: 0.0 };
            let fa = |x: f64| if implicit { step.step(force(x), f_n).1 } else { force(x) };
            let (mut lo, mut hi) = (u - 10.0 * dt, u + 10.0 * dt);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if m * acc(mid) + fa(mid) > 0.0 { hi = mid } else { lo = mid }
            }
            let x = 0.5 * (lo + hi);
            let a1 = acc(x);
            v += 0.5 * dt * (a + a1);
            (u, a, f_n) = (x, a1, fa(x));
            if u < -dt && v < 0.0 {
                break;
            }
        }
        0.5 * m * v * v + 0.5 * k * u.max(0.0).powi(2)
    }

    #[test]
    fn the_end_of_step_impulse_cannot_create_energy() {
        // a spring far stiffer than the step (ω Δt = 10): the implicit
        // impulse stops the mass like an inelastic impact, Newmark's average
        // throws it back with more than it had
        let (implicit, newmark) = (bounce(true, 1e4, 0.1), bounce(false, 1e4, 0.1));
        println!("ω Δt = 10: implicit {implicit}, newmark {newmark} of 0.5");
        assert!(implicit <= 0.5 && newmark > 0.5 * 1.5, "{implicit} {newmark}");
        // a resolved spring (ω Δt = 0.1): the Bregman losses ½ k (v Δt)²
        // per step over the half period π/ω with v = v₀ cos ω t sum to
        // (π/2) ω Δt of the energy (first order in Δt, as backward Euler
        // on the spring); Newmark's average keeps the energy but for the
        // two switches
        let (implicit, newmark) = (bounce(true, 1e2, 0.01), bounce(false, 1e2, 0.01));
        let (loss, expected) = (1.0 - implicit / 0.5, std::f64::consts::FRAC_PI_2 * 0.1);
        println!("ω Δt = 0.1: implicit loses {loss} (estimate {expected}), newmark {newmark} of 0.5");
        assert!(loss > 0.0 && (loss / expected - 1.0).abs() < 0.2, "{loss}");
        assert!((newmark / 0.5 - 1.0).abs() < 1e-2, "{newmark}");
    }
}
