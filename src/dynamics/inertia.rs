//! Inertia and Rayleigh damping as a contribution to the residual:
//! Newmark's method (`analysis.type = "transient"`).
//!
//! The semi-discrete equations `M ü + C u̇ + f_int(u) = f_ext(t) + f_c(u)`
//! are integrated from `t_n` to `t_(n+1) = t_n + Δt` with Newmark's
//! approximations (Newmark 1959; Hughes, *The Finite Element Method*,
//! §9.1):
//!
//! ```text
//! a = (u − u_n − Δt v_n) / (β Δt²) − (1/(2β) − 1) a_n
//! v = v_n + Δt ((1 − γ) a_n + γ a)
//! ```
//!
//! so that at the end of the step the residual gains `M a + C v` and the
//! tangent `M / (β Δt²) + γ C / (β Δt)`; with Bossak's α
//! (`analysis.newmark.alpha`; Wood, Bossak & Zienkiewicz, *An alpha
//! modification of Newmark's method*, IJNME 15, 1980) the inertia force is
//! `M ((1 − α) a + α a_n)` and its tangent `(1 − α) M / (β Δt²)`. The unknown stays the
//! displacement and the existing Newton solves each step. The load history
//! is the time history: analysis time λ maps to `t` through the steps'
//! durations (`TransientSettings::time`), so the
//! stepping's increments are time steps and its cutbacks halve Δt.
//! `β = ¼, γ = ½` (the default, the trapezoidal rule) conserves the energy
//! of a linear undamped system exactly and is second-order accurate;
//! `γ > ½` with `β = ¼ (γ + ½)²` damps the highest frequencies (first
//! order). Bossak's `α ∈ [−⅓, 0)` with `γ = ½ − α`, `β = ¼ (1 − α)²` (the
//! defaults it sets) damps them too (spectral radius `(1 + α)/(1 − α)` at
//! infinite frequency) and stays second order: on a ramped bar it
//! dissipates two orders of magnitude less than Newmark's `γ = 0.6`
//! (crates/cufem-cli/tests/dynamics.rs). `C = α_M M + β_K K₀` with `K₀` the
//! elastic stiffness at u = 0.
//!
//! `M` is kept as its non-zero entries only (`LowerCsc::compress`): it
//! couples each displacement component with the same component of the
//! neighbouring nodes, a third of the structure's pattern, so the product
//! `M a` of every evaluation and the addition of `M / (β Δt²)` to the tangent
//! pass over a third of the entries (the steps of an impact in contact
//! are dominated by the solves: the drop weight's time is within the
//! spread of its runs either way).
//!
//! The structure starts at rest with the initial velocities of the model
//! (`a₀ = 0`: no load at t = 0, as every load history starts from zero).
//! Constrained DOFs have no equation and carry no inertia force (so with a
//! consistent mass a support's reaction leaves out the inertia of its
//! neighbours' coupling terms; with the lumped mass it is exact).

use super::TransientSettings;
use super::energy::{Held, StepForces};
use crate::assembly::{At, Contribution, Forces, NO_EQ, Phase, Tangent};
use crate::solver::linear::{Compressed, LowerCsc};

/// Newmark's inertia and damping forces.
#[derive(Debug)]
pub(crate) struct Inertia {
    settings: TransientSettings,
    /// `M`'s non-zero entries (lower triangle; `LowerCsc::compress`).
    mass: Compressed,
    /// `C`, `None` without damping.
    damping: Option<Vec<f64>>,
    /// Committed velocity and acceleration (per DOF), and λ.
    v_n: Vec<f64>,
    a_n: Vec<f64>,
    lambda_n: f64,
    /// Trial velocity and acceleration (per DOF).
    v: Vec<f64>,
    a: Vec<f64>,
    /// `M a + C v` per DOF, and its damping part `C v`.
    force: Vec<f64>,
    /// `‖M v_n‖ / Δt` of the last evaluation (the force scale it sets).
    reference: f64,
    /// `‖M v_n‖` of the committed state, once computed.
    momentum: Option<f64>,
    /// `‖M v‖` of the converged step's velocity, from its kinetic energy
    /// ([`Self::account`]): the next step's `‖M v_n‖` once it is committed.
    momentum_of_step: Option<f64>,
    /// The step `Δt` of the last evaluation that added the stiffness.
    tangent_step: Option<f64>,
    damping_force: Vec<f64>,
    /// Scratch per equation.
    x: Vec<f64>,
    y: Vec<f64>,
    /// The energy balance per converged step.
    ledger: super::energy::EnergyLedger,
}

impl Inertia {
    /// At rest but for the initial velocities `v0` (per DOF; constrained
    /// DOFs are left at zero), with the mass `mass` and the elastic
    /// stiffness `k0` (both lower triangles on the structure's `pattern`;
    /// `k0` is read only for stiffness-proportional damping).
    pub fn new(settings: TransientSettings, (pattern, mass): (&LowerCsc, Vec<f64>), k0: &[f64], v0: Vec<f64>) -> Self {
        let (alpha, beta) = settings.damping;
        // K₀ is given only when β_K > 0 (empty otherwise)
        let damping = (alpha > 0.0 || beta > 0.0).then(|| {
            let k = |i: usize| k0.get(i).copied().unwrap_or(0.0);
            mass.iter().enumerate().map(|(i, m)| alpha * m + beta * k(i)).collect::<Vec<f64>>()
        });
        let n = v0.len();
        let n_eq = pattern.n;
        Self {
            settings,
            mass: pattern.compress(&mass),
            damping,
            v: v0.clone(),
            v_n: v0,
            a_n: vec![0.0; n],
            a: vec![0.0; n],
            lambda_n: 0.0,
            force: vec![0.0; n],
            reference: 0.0,
            momentum: None,
            momentum_of_step: None,
            tangent_step: None,
            damping_force: vec![0.0; n],
            x: vec![0.0; n_eq],
            y: vec![0.0; n_eq],
            ledger: Default::default(),
        }
    }

    /// Records the initial state (at rest but for the initial velocities,
    /// unloaded) as the first row of the energy balance.
    pub fn start(&mut self, eq: &[usize], impactors: f64) {
        let v0 = self.v_n.clone();
        let kinetic = self.kinetic_energy(&v0, eq);
        let zero = vec![0.0; v0.len()];
        let forces = StepForces {
            internal: &zero,
            damping: &zero,
            external: &zero,
            contact: &zero,
            supports: &zero,
            interfaces: &zero,
        };
        self.ledger.record(self.time(0.0), &zero, &forces, kinetic, Held::default());
        self.set_impactors(impactors);
    }

    /// The impactors' kinetic energy in the last row.
    fn set_impactors(&mut self, energy: f64) {
        if let Some(row) = self.ledger.rows.last_mut() {
            row.impactors = energy;
        }
    }

    /// Adds the converged step at λ to the energy balance: `du` the step's
    /// displacement increment, `forces` the other parts' converged forces
    /// (the damping forces are this part's own), `held` the energies held,
    /// `impactors` the rigid impactors' kinetic energy.
    pub(crate) fn account(
        &mut self,
        (lambda, held, impactors): (f64, Held, f64),
        du: &[f64],
        forces: [&[f64]; 5],
        eq: &[usize],
    ) {
        let v = std::mem::take(&mut self.v);
        let kinetic = self.kinetic_energy(&v, eq);
        self.v = v;
        self.momentum_of_step = Some(self.y.iter().map(|v| v * v).sum::<f64>().sqrt());
        let [internal, external, contact, supports, interfaces] = forces;
        let step = StepForces { internal, damping: &self.damping_force, external, contact, supports, interfaces };
        let time = self.time(lambda);
        self.ledger.record(time, du, &step, kinetic, held);
        self.set_impactors(impactors);
    }

    /// The energy balance, one row per converged step (the initial state first).
    pub fn energies(&self) -> &[super::energy::EnergyRow] {
        &self.ledger.rows
    }

    /// Time (s) at analysis time λ.
    pub fn time(&self, lambda: f64) -> f64 {
        self.settings.time(lambda)
    }

    /// The committed velocity and acceleration and Newmark's β, for the
    /// time step's error estimate (`dynamics::time_error`).
    pub(crate) fn committed(&self) -> super::time_error::Committed<'_> {
        super::time_error::Committed { v: &self.v_n, a: &self.a_n, beta: self.settings.beta }
    }

    /// Per equation: whether it carries mass (a positive diagonal of `M`;
    /// the contact nodes whose mass `dynamics::redistribution` moved away
    /// carry none, and their Newmark acceleration is no motion's).
    pub(crate) fn massive(&self) -> Vec<bool> {
        (0..self.mass.pattern.n).map(|c| self.mass.diagonal(c) > 0.0).collect()
    }

    /// The length (s) of the step from the committed state to λ.
    pub(crate) fn step_length(&self, lambda: f64) -> f64 {
        self.time(lambda) - self.time(self.lambda_n)
    }

    /// The settings of the analysis.
    pub(crate) fn settings(&self) -> &TransientSettings {
        &self.settings
    }

    /// `½ vᵀ M v` of per-DOF velocities `v` on the equations `eq`.
    fn kinetic_energy(&mut self, v: &[f64], eq: &[usize]) -> f64 {
        gather(v, eq, &mut self.x);
        self.mass.mul(&self.x, &mut self.y);
        0.5 * self.x.iter().zip(&self.y).map(|(a, b)| a * b).sum::<f64>()
    }
}

/// `out[e] = v[d]` for every DOF `d` with an equation `e`.
fn gather(v: &[f64], eq: &[usize], out: &mut [f64]) {
    for (d, &e) in eq.iter().enumerate() {
        if e != NO_EQ {
            out[e] = v[d];
        }
    }
}

impl Contribution for Inertia {
    fn phase(&self) -> Phase {
        Phase::Loads
    }

    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize {
        let dt = self.time(at.lambda) - self.time(self.lambda_n);
        let (beta, gamma) = (self.settings.beta, self.settings.gamma);
        if dt > 0.0 {
            let c0 = 1.0 / (beta * dt * dt);
            let c2 = 1.0 / (2.0 * beta) - 1.0;
            for d in 0..self.a.len() {
                let a = c0 * (at.u[d] - at.u_committed[d] - dt * self.v_n[d]) - c2 * self.a_n[d];
                self.a[d] = a;
                self.v[d] = self.v_n[d] + dt * ((1.0 - gamma) * self.a_n[d] + gamma * a);
            }
            let c1 = gamma / (beta * dt);
            // Bossak's inertia force M ((1 − α) a + α a_n); a residual-only
            // evaluation leaves the tangent out, as the elements do (a pass
            // over every non-zero entry of M)
            let m0 = (1.0 - self.settings.alpha) * c0;
            if tangent.wanted {
                self.tangent_step = Some(dt);
                self.mass.add_scaled_to(m0, tangent.values);
                if let Some(c) = &self.damping {
                    for (t, ck) in tangent.values.iter_mut().zip(c) {
                        *t += c1 * ck;
                    }
                }
            }
        } else {
            // at the committed time (the state before the first increment,
            // or evaluated again after convergence): its own a and v, and
            // no stiffness (a tangent formed now has no mass to keep)
            self.a.clone_from(&self.a_n);
            self.v.clone_from(&self.v_n);
            if tangent.wanted {
                self.tangent_step = None;
            }
        }
        let eq = &tangent.assembler.dofs.eq;
        let pattern = &tangent.assembler.pattern;
        // the scale of the step's residual: the force that would stop the
        // committed motion within the step
        self.reference = 0.0;
        if dt > 0.0 {
            let momentum = match self.momentum {
                Some(p) => p,
                None => {
                    gather(&self.v_n, eq, &mut self.x);
                    self.mass.mul(&self.x, &mut self.y);
                    *self.momentum.insert(self.y.iter().map(|v| v * v).sum::<f64>().sqrt())
                }
            };
            self.reference = momentum / dt;
        }
        self.force.fill(0.0);
        self.damping_force.fill(0.0);
        let alpha = self.settings.alpha;
        for (d, &e) in eq.iter().enumerate() {
            if e != NO_EQ {
                self.x[e] = (1.0 - alpha) * self.a[d] + alpha * self.a_n[d];
            }
        }
        self.mass.mul(&self.x, &mut self.y);
        for (d, &e) in eq.iter().enumerate() {
            if e != NO_EQ {
                self.force[d] = self.y[e];
            }
        }
        if let Some(c) = &self.damping {
            gather(&self.v, eq, &mut self.x);
            pattern.mul_symmetric(c, &self.x, &mut self.y);
            for (d, &e) in eq.iter().enumerate() {
                if e != NO_EQ {
                    self.damping_force[d] = self.y[e];
                    self.force[d] += self.y[e];
                }
            }
        }
        0
    }

    fn forces(&self) -> Forces<'_> {
        // the inertia force balances the internal one in free motion, so
        // it sets the force scale of the convergence test with the loads
        Forces { values: &self.force, sign: 1.0, scale: true, reference: self.reference }
    }

    fn commit(&mut self, at: &At<'_>) {
        self.v_n.clone_from(&self.v);
        self.a_n.clone_from(&self.a);
        self.lambda_n = at.lambda;
        // the converged step's ‖M v‖ if its energy was accounted (the same
        // product the next evaluation would form again)
        self.momentum = self.momentum_of_step.take();
    }

    fn restore(&mut self) {}

    /// `(1 − α) M / (β Δt²) + γ C / (β Δt)` depends on the step alone: the
    /// same as formed last if the step is (within `1e-12` of it, the
    /// round-off of a step length computed from load factors).
    fn tangent_unchanged(&self, at: &At<'_>) -> bool {
        let dt = self.time(at.lambda) - self.time(self.lambda_n);
        self.tangent_step.is_some_and(|s| dt > 0.0 && (dt - s).abs() <= 1e-12 * s)
    }
}
