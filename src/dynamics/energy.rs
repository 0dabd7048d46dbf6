//! The energy balance of a transient analysis, per converged time step.
//!
//! Every work term is accumulated by the trapezoidal rule over the step's
//! displacement increment `Δu`, `W += ½ (f_n + f_(n+1)) · Δu`: the
//! internal work `W_int` (strain energy plus plastic dissipation), the
//! damping dissipation `D` (`C v`), the work of the loads `W_ext`, of the
//! contacts `W_c` and of the supports `W_s` (reactions on prescribed
//! motion), and the work of the cohesive interfaces' tractions `W_i`
//! (the contacts' and interfaces' with the algorithmic force `f'` the
//! residual takes under their end-of-step impulse, `dynamics::impulse`:
//! with the trapezoidal rule their work per step is then `f(u_(n+1)) · Δu`,
//! and an interface's work never falls short of the energy it holds). The
//! kinetic energy is `T = ½ vᵀ M v`; the internal work splits into the
//! elastic strain energy held, `½ ∫ σᵀ C⁻¹ σ dV` (with the damaged
//! compliance at ply-damage points), the energy ply damage released per
//! Hashin mode at fixed strain (`Σ_q w_q Σ_n W(ε_n; d_n) − W(ε_n; d_(n+1))`,
//! `crate::materials::damage::DamageState::released`), what the damaging
//! points' forces did beyond their stored energy and that release,
//! `damage_scheme` (the Bregman losses of the end-of-step stress, the
//! trapezoidal excess under Newmark's average; `dynamics::ply_forces`), and
//! the rest, the plastic dissipation (in a body that only damages, the
//! trapezoidal work of cracks that open or shut without growing against
//! their stored energy); the interfaces' work into the energy they hold,
//! `Σ A ½ t·δ`, and the rest, dissipated by delamination. Their balance
//!
//! ```text
//! B = W_ext + W_c + W_s − (T − T₀) − W_int − W_i − D
//! ```
//!
//! is zero to Newton's tolerance for the trapezoidal rule (`β = ¼, γ = ½`:
//! the inertia forces' trapezoidal work is exactly `ΔT`), and for `γ > ½`
//! or Bossak's `α < 0` the energy the scheme dissipates (Hughes, *The Finite Element Method*,
//! §9.3): what a run prints as the balance is an error budget, not a
//! physical term.

/// One converged time step's energies (J) at time `time` (s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnergyRow {
    /// Time (s).
    pub time: f64,
    /// `T`.
    pub kinetic: f64,
    /// `W_int`.
    pub internal: f64,
    /// The elastic strain energy `½ ∫ σᵀ C⁻¹ σ dV` held now.
    pub elastic: f64,
    /// `W_int` less the elastic strain energy, the energy ply damage
    /// dissipated and the end-of-step stress's dissipation: plastic
    /// dissipation.
    pub plastic: f64,
    /// The energy ply damage released per mode at fixed strain (fibre
    /// tension and compression, matrix tension and compression; zero
    /// without damage).
    pub damage: [f64; 4],
    /// What the forces of damaging ply points did beyond the change of
    /// their stored energy and the release (`dynamics::ply_forces`; zero
    /// without damage).
    pub damage_scheme: f64,
    /// `D`.
    pub damping: f64,
    /// `W_ext`.
    pub external: f64,
    /// `W_i`: the work of the cohesive interfaces' tractions (zero without
    /// interfaces).
    pub interfaces: f64,
    /// `W_i` less the energy the interfaces hold: dissipated by
    /// delamination.
    pub delamination: f64,
    /// `W_c`: the contacts' work on the bodies.
    pub contact: f64,
    /// `½ m v²` of the rigid impactors, beside the balance (which is the
    /// bodies'): what they lose is the contacts' work on the bodies plus
    /// what the contacts dissipate (`dynamics::impulse`).
    pub impactors: f64,
    /// `W_s`.
    pub supports: f64,
    /// `B` (above).
    pub balance: f64,
}

/// The running sums and the forces of the last converged step.
#[derive(Debug, Default)]
pub(crate) struct EnergyLedger {
    /// Rows so far (the initial state first).
    pub rows: Vec<EnergyRow>,
    previous: Option<[Vec<f64>; 6]>,
}

/// The converged step's forces per DOF: internal, damping, loads, contact,
/// supports (reactions at constrained DOFs, zero elsewhere), interfaces.
pub(crate) struct StepForces<'a> {
    /// `f_int`.
    pub internal: &'a [f64],
    /// `C v`.
    pub damping: &'a [f64],
    /// `f_ext`.
    pub external: &'a [f64],
    /// `f_c`.
    pub contact: &'a [f64],
    /// Reactions.
    pub supports: &'a [f64],
    /// The cohesive interfaces' internal forces.
    pub interfaces: &'a [f64],
}

/// The energies held at the end of a converged step (J): the elastic strain
/// energy of the bodies and the energy the cohesive interfaces hold; and
/// what ply damage has dissipated so far, per mode.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Held {
    /// `½ ∫ σᵀ C⁻¹ σ dV`.
    pub elastic: f64,
    /// `Σ A ½ t·δ`.
    pub interfaces: f64,
    /// The release at fixed strain per damage mode.
    pub damage: [f64; 4],
    /// What the damaging ply points' forces did beyond it.
    pub damage_scheme: f64,
}

impl EnergyLedger {
    /// Records the step to `time` over `du` with the converged `forces`,
    /// kinetic energy `kinetic` and the energies `held`; the first call
    /// records the initial state (then `du` is ignored).
    pub fn record(&mut self, time: f64, du: &[f64], forces: &StepForces<'_>, kinetic: f64, held: Held) {
        let f = forces;
        let now = [f.internal, f.damping, f.external, f.contact, f.supports, f.interfaces];
        let mut row = self.rows.last().copied().unwrap_or_default();
        row.time = time;
        row.kinetic = kinetic;
        if let Some(prev) = &self.previous {
            let work = |k: usize| -> f64 {
                let f = now[k];
                let total: f64 = prev[k].iter().zip(f).zip(du).map(|((a, b), d)| 0.5 * (a + b) * d).sum();
                total
            };
            row.internal += work(0);
            row.damping += work(1);
            row.external += work(2);
            row.contact += work(3);
            row.supports += work(4);
            row.interfaces += work(5);
        }
        row.elastic = held.elastic;
        row.damage = held.damage;
        row.damage_scheme = held.damage_scheme;
        row.plastic = row.internal - held.elastic - held.damage.iter().sum::<f64>() - held.damage_scheme;
        row.delamination = row.interfaces - held.interfaces;
        let t0 = self.rows.first().map_or(kinetic, |r| r.kinetic);
        row.balance = row.external + row.contact + row.supports
            - (row.kinetic - t0)
            - row.internal
            - row.interfaces
            - row.damping;
        self.rows.push(row);
        self.previous = Some(now.map(<[f64]>::to_vec));
    }
}
