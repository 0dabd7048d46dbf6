//! Progressive damage of a ply (intralaminar): Hashin onset, linear
//! softening per mode regularised by the crack band, and the damaged
//! orthotropic stiffness (Lapczyk & Hurtado 2007, *Compos. A* 38:2333, as
//! Abaqus's Hashin damage, in 3D; Matzenmiller, Lubliner & Taylor 1995,
//! *Mech. Mater.* 20:125; Bažant & Oh 1983, *Mater. Struct.* 16:155).
//!
//! A pure point function in the ply's material axes (1 fibre, 2 in-plane
//! transverse, 3 normal; [`crate::voigt`] order and engineering shears):
//! `(strain ε_m, crack-band lengths, committed state) → (stress, secant
//! stiffness, new state)`. The caller rotates the strain in and the stress
//! out ([`super::anisotropic::Frame`]) and commits the state only after an
//! increment has converged.
//!
//! * **Modes** `I ∈ {FT, FC, MT, MC}` (fibre tension and compression,
//!   matrix tension and compression). Onset when Hashin's strength ratio of
//!   the undamaged ("effective") stress `σ̃ = C⁰ ε_m` of the active fibre or
//!   matrix mode falls to 1 (`Strengths::hashin_ratios`); the
//!   onset measure `φ = 1/R` is homogeneous of degree one in the strain.
//! * **Equivalent displacement and stress** of a mode, from the strain
//!   components that drive it: FT `e = √(⟨ε11⟩² + α (γ12² + γ13²))` (α the
//!   `fibre_shear` key, 1 by default, which also weighs the shear term of
//!   Hashin's FT criterion), FC
//!   `e = ⟨−ε11⟩`, MT `e = √(⟨ε22⟩² + ⟨ε33⟩² + γ12² + γ13² + γ23²)`, MC the
//!   same with `⟨−ε22⟩, ⟨−ε33⟩`; `s` the matching work conjugate `σ̃·ε/e`;
//!   `δ = L e` with `L` the crack-band length (fibre modes `band[0]`,
//!   matrix modes `band[1]`). At the first onset the state records
//!   `δ0 = δ/φ`, `σ0 = s/φ` (where the path crossed the surface) and
//!   `δf = 2 G_I/σ0`.
//! * **Damage** `d_I = δf (κ − δ0)/(κ (δf − δ0))`, `κ` the largest `δ`
//!   reached after onset (never smaller: damage does not heal), at most
//!   `max_damage`. The energy dissipated per unit volume by a complete
//!   softening is `G_I/L`: per unit crack area `G_I`, whatever the mesh.
//! * **Branches of growth**: the fibre mode that grows is FT where
//!   `σ̃11 ≥ 0`, else FC; the matrix mode MT where `σ̃22 + σ̃33 ≥ 0`, else
//!   MC — signs taken from the committed state's strain (the last converged
//!   increment's; a point's own strain at its first update), so that within
//!   an increment a point keeps them. Taken from the trial strain, a point
//!   whose `σ̃11` sits at zero while shear drives Hashin's fibre-tension
//!   criterion (which has a shear term where fibre compression has none)
//!   grows and stops growing from one Newton iteration to the next, and
//!   Newton cycles without converging. A normal stress of the other sign
//!   counts as zero in the criterion (`⟨σ̃11⟩`; `Strengths::hashin_in`). A
//!   point whose stress changes sign within an increment grows in the new
//!   mode one increment late: the lag vanishes as the step shrinks.
//! * **Stiffness**: the compliance's normal diagonal `1/E_k` divided by
//!   `1 − d` of the tension mode of its direction (FT for `k = 1`, MT for
//!   `k = 2, 3`) where the damaged stress `σ_k ≥ 0`, of the compression
//!   mode (FC, MC) where `σ_k < 0`; the shear moduli by `1 − d_s`,
//!   `d_s = 1 − Π_I (1 − d_I)`; the Poisson terms kept. An entry `1/E_k`
//!   multiplies `σ_k` only, so the strain is a continuous function of the
//!   stress across a closing crack (and the stress of the strain, solved for
//!   the signs, `PlyDamage::closed_or_open`): a closed crack carries
//!   compression again, without a jump that would make Newton cycle (Maimí
//!   et al. 2007, *Mech. Mater.* 39:897, take the signs of the stress the
//!   same way). The tangent returned is the consistent one (`damage_tangent`:
//!   unsymmetric where a mode loads), or the secant `C_d = S(d)⁻¹`
//!   (symmetric, positive definite).
//! * **Snap-back inside a point**: the law needs `δf > δ0`, i.e.
//!   `L < 2 E G_I/X²` (`PlyDamage::longest_band`). A longer band lowers the
//!   mode's strength by `√(L_max/L)` (Bažant & Oh), so that the band's
//!   elastic energy at onset stays below `G_I`, and marks the mode in
//!   [`DamageState::reduced`].
//! * **Dissipation** per mode, from the energy release rates of the
//!   stiffness variables: `Y_I = Σ_k ½ σ_k²/((1 − d_I)² E_k)` over the
//!   normal stresses whose compliance mode `I` holds,
//!   `Y_s = ½ Σ τ²/((1 − d_s)² G)`: each update adds
//!   `(Ȳ_I + Ȳ_s ∂d_s/∂d_I) Δd_I` with the trapezoidal means `Ȳ` over
//!   steps of its straight strain path that grow no mode by more than
//!   `0.02` (`damage_dissipation`), so the work of any closed strain cycle
//!   equals the dissipated energy to the rule's second order, and a point
//!   that softens through within one update books its `G_I/L`.

use thiserror::Error;

use super::anisotropic::Orthotropic;
use super::failure::Strengths;
use crate::voigt::{Matrix6, Voigt, mat_vec};

/// The four damage modes, in the order of every `[_; 4]` of this module.
pub const MODES: [&str; 4] = ["fibre_tension", "fibre_compression", "matrix_tension", "matrix_compression"];

/// Fibre tension, fibre compression, matrix tension, matrix compression.
const FT: usize = 0;
const FC: usize = 1;
const MT: usize = 2;
const MC: usize = 3;

/// A ply damage law: elastic constants, strengths and the fracture energy of
/// each mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlyDamage {
    elastic: Orthotropic,
    stiffness: Matrix6,
    /// `elastic.compliance()`, which every damaged stiffness starts from.
    compliance: Matrix6,
    /// The damaged stiffness at zero damage, as [`PlyDamage::damaged_stiffness`]
    /// computes it (bitwise: the stress of an intact point is the one a
    /// damaged stiffness of zero damage gives, not `stiffness`'s).
    intact: Matrix6,
    strengths: Strengths,
    toughness: [f64; 4],
    max_damage: f64,
    consistent: bool,
    viscosity: f64,
    /// α: the weight of the longitudinal shear in fibre tension's onset
    /// criterion and equivalent strain (1: Hashin's; [`PlyDamage::with_fibre_shear`]).
    fibre_shear: f64,
    /// Each mode's softening line drawn for `E_k ε_k` in the normal
    /// components instead of the effective stress
    /// ([`PlyDamage::with_uniaxial_softening`]).
    uniaxial_softening: bool,
}

/// A damage law that cannot be used, by the key of its constant.
#[derive(Debug, Error, PartialEq)]
pub enum DamageError {
    /// A fracture energy that is not a positive finite number.
    #[error("damage `{key}` = {value}: must be a positive finite fracture energy (J/m²)")]
    Toughness {
        /// The key of the mode's fracture energy.
        key: &'static str,
        /// Its value.
        value: f64,
    },
    /// A largest damage outside (0, 1): a fully damaged point would have no
    /// stiffness left.
    #[error("damage `max_damage` = {0}: must be in (0, 1)")]
    MaxDamage(f64),
    /// Elastic constants whose compliance is not positive definite.
    #[error("damage needs admissible orthotropic constants (compliance positive definite)")]
    Elastic,
}

/// The history of one ply point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DamageState {
    /// Damage of each mode ([`MODES`]).
    pub damage: [f64; 4],
    /// Largest equivalent displacement after onset (m); 0 before onset.
    pub kappa: [f64; 4],
    /// Equivalent displacement at onset `δ0` (m); 0 before onset.
    pub onset: [f64; 4],
    /// Equivalent displacement at full damage `δf` (m).
    pub last: [f64; 4],
    /// Energy dissipated per unit volume by each mode (J/m³).
    pub dissipated: [f64; 4],
    /// Energy released per unit volume by each mode at the strain of the
    /// committed state (J/m³): the sum over updates of
    /// `W(ε_n; d_n) − W(ε_n; d_(n+1))`, the modes' growths taken one after
    /// the other in [`MODES`] order (`PlyDamage::release_at`). The energy
    /// ledger of a transient run books it (`crate::dynamics::ply_forces`).
    pub(crate) released: [f64; 4],
    /// The regularised damage `d_v` of each mode, the one the stiffness
    /// takes (Duvaut–Lions; equal to `damage` without viscosity).
    pub viscous: [f64; 4],
    /// Energy release rates of this state (J/m³): of each mode's own
    /// compliance terms ([`MODES`] order; zero for a mode that holds no
    /// normal stress) and `Y_s` of the shear moduli.
    pub release: [f64; 5],
    /// The elastic strain energy density the point holds, `½ σ·ε`
    /// (J/m³): `½ σᵀ S(d) σ`, the stress being the damaged secant's.
    pub stored: f64,
    /// Modes whose onset stress was lowered because the band is longer
    /// than `PlyDamage::longest_band`.
    pub reduced: [bool; 4],
    /// The branches `[fibre, matrix]` (`true`: tension) of this state's
    /// strain, which the next increment's updates take (module docs);
    /// `None` before a point's first update.
    pub tension: Option<[bool; 2]>,
    /// The strain of this state (material axes), from which the next
    /// step's end-of-step stress measures its work
    /// (`super::damage_impulse`).
    pub strain: Voigt,
    /// Hashin's onset measure `φ = 1/R` of this strain's effective stress,
    /// the larger of the fibre and matrix modes' (1 at onset).
    pub index: f64,
    /// The stress the internal force takes (global axes): the physical one,
    /// or under `analysis.ply_damage_forces = "implicit"` the algorithmic
    /// stress of the end-of-step impulse (`crate::dynamics::ply_forces`).
    pub(crate) force_stress: Voigt,
    /// The stress the velocity update weighs, `g` of the impulse recursion
    /// (`crate::newmark::Recursion`; `force_stress` itself
    /// without Bossak's α).
    pub(crate) velocity_stress: Voigt,
    /// The point takes the end-of-step stress from the next step on.
    pub implicit: bool,
    /// The energy per unit volume the end-of-step stress dissipated beyond
    /// the law's (J/m³; `crate::dynamics::ply_forces`).
    pub scheme: f64,
}

/// The answer of [`PlyDamage::update`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DamageResponse {
    /// Stress in the material axes (Pa).
    pub stress: Voigt,
    /// The secant stiffness `C_d` in the material axes (Pa).
    pub tangent: Matrix6,
    /// The trial state.
    pub state: DamageState,
}

impl PlyDamage {
    /// A law from the ply's constants, strengths, the fracture energies of
    /// [`MODES`] (J/m²) and the largest damage.
    pub fn new(
        elastic: Orthotropic,
        strengths: Strengths,
        toughness: [f64; 4],
        max_damage: f64,
    ) -> Result<Self, DamageError> {
        for (i, &value) in toughness.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(DamageError::Toughness { key: MODES[i], value });
            }
        }
        if !(max_damage > 0.0 && max_damage < 1.0) {
            return Err(DamageError::MaxDamage(max_damage));
        }
        let stiffness = elastic.stiffness().ok_or(DamageError::Elastic)?;
        let compliance = elastic.compliance();
        let mut law = Self {
            elastic,
            stiffness,
            compliance,
            intact: [[0.0; 6]; 6],
            strengths,
            toughness,
            max_damage,
            consistent: true,
            viscosity: 0.0,
            fibre_shear: 1.0,
            uniaxial_softening: false,
        };
        law.intact = law.damaged_stiffness([0.0; 3], 0.0);
        Ok(law)
    }

    /// The same law returning the secant stiffness `C_d` as its tangent
    /// (`consistent = false`) or the consistent one
    /// ([`PlyDamage::consistent_tangent`], the default).
    pub(crate) fn with_consistent_tangent(mut self, consistent: bool) -> Self {
        self.consistent = consistent;
        self
    }

    /// The same law with Duvaut–Lions viscosity `eta` (in the units of the
    /// steps given to [`PlyDamage::update_over`]; 0: rate independent).
    pub(crate) fn with_viscosity(mut self, eta: f64) -> Self {
        self.viscosity = eta;
        self
    }

    /// The same law with the longitudinal shear weighed by `alpha` ∈ [0, 1]
    /// in fibre tension: in Hashin's criterion `(σ11/Xt)² + α (τ12² + τ13²)/S12²`
    /// and in the equivalent strain `e = √(ε11² + α (γ12² + γ13²))` (Abaqus's
    /// α; 1 by default, Hashin's own criterion). With `α = 0` a point's
    /// fibre-tension softening does not depend on the shear it carried at
    /// onset (docs/limitations.md, "Ply damage").
    pub(crate) fn with_fibre_shear(mut self, alpha: f64) -> Self {
        self.fibre_shear = alpha;
        self
    }

    /// The same law with each mode's softening line drawn for `E_k ε_k`
    /// in the normal components (`uniaxial`) instead of the effective
    /// stress `C⁰ε`: the onset stress `σ0` and so `δf = 2 G/σ0` follow the
    /// stress the damaged compliance leaves as `d → 1` (`1/E_k` divided by
    /// `1 − d`, the Poisson terms kept), so that a band held laterally
    /// dissipates `G/L` as one free does (docs/limitations.md). A point in
    /// uniaxial stress softens the same either way.
    pub(crate) fn with_uniaxial_softening(mut self, uniaxial: bool) -> Self {
        self.uniaxial_softening = uniaxial;
        self
    }

    /// True if its tangent is the consistent one, unsymmetric where a mode
    /// loads (`damage_tangent`).
    pub(crate) fn is_consistent(&self) -> bool {
        self.consistent
    }

    /// Its Duvaut–Lions viscosity.
    pub fn viscosity(&self) -> f64 {
        self.viscosity
    }

    /// The longest crack band (m) for which mode `mode` ([`MODES`] index)
    /// softens without lowering its strength: `2 E G/X²`.
    pub(crate) fn longest_band(&self, mode: usize) -> f64 {
        let [e1, e2, _] = self.elastic.young;
        let (young, strength) = match mode {
            FT => (e1, self.strengths.tension[0]),
            FC => (e1, self.strengths.compression[0]),
            MT => (e2, self.strengths.tension[1]),
            _ => (e2, self.strengths.compression[1]),
        };
        2.0 * young * self.toughness[mode] / (strength * strength)
    }

    /// Stress, tangent and trial state at the strain `strain` (material
    /// axes) with the crack-band lengths `band = [fibre, matrix]` (m) from
    /// the committed state `old`, rate independent (as
    /// `PlyDamage::update_over` over an infinite step).
    pub fn update(&self, strain: &Voigt, band: [f64; 2], old: &DamageState) -> DamageResponse {
        self.update_over(strain, band, f64::INFINITY, old)
    }

    /// As [`PlyDamage::update`] over a step `step` (the change of the load
    /// factor or time since `old`): with viscosity η the damage the
    /// stiffness takes relaxes towards the law's, implicitly,
    /// `d_v = (η d_v,n + Δ d)/(η + Δ)` (Duvaut–Lions; Lapczyk & Hurtado).
    pub(crate) fn update_over(&self, strain: &Voigt, band: [f64; 2], step: f64, old: &DamageState) -> DamageResponse {
        let mut state = DamageState::default();
        let (stress, tangent, _) = self.update_into(strain, band, (step, true), old, &mut state);
        DamageResponse { stress, tangent, state }
    }

    /// As [`PlyDamage::update_over`], the trial state written into `state`
    /// (the caller's slot: a point's state is not copied on its way there)
    /// and the stress, the tangent and the consistent tangent's rank-one
    /// terms returned (`damage_tangent`; none with the secant). A point on
    /// its damage surface (its strain the committed one's, as at an
    /// increment's first iteration) takes the softening branch's tangent if
    /// `loading` (the next increment goes on cracking), else the secant.
    pub(crate) fn update_into(
        &self,
        strain: &Voigt,
        band: [f64; 2],
        (step, loading): (f64, bool),
        old: &DamageState,
        state: &mut DamageState,
    ) -> (Voigt, Matrix6, Softening) {
        let effective = mat_vec(&self.stiffness, strain);
        // the branches of the committed state (module docs), this strain's
        // at a point's first update; this strain's for the next increment
        let own = [effective[0] >= 0.0, effective[1] + effective[2] >= 0.0];
        let tension = old.tension.unwrap_or(own);
        let [fibre_ratio, matrix_ratio] = self.strengths.hashin_ratios(&effective, tension, self.fibre_shear);
        let fibre = if tension[0] { FT } else { FC };
        let matrix = if tension[1] { MT } else { MC };
        *state = *old;
        state.tension = Some(own);
        state.strain = *strain;
        state.index = (1.0 / fibre_ratio).max(1.0 / matrix_ratio);
        for (mode, ratio, length) in [(fibre, fibre_ratio, band[0]), (matrix, matrix_ratio, band[1])] {
            self.soften(mode, 1.0 / ratio, length, strain, &effective, state);
        }
        let share = self.share(step);
        for i in 0..4 {
            state.viscous[i] = (1.0 - share) * old.viscous[i] + share * state.damage[i];
        }
        let d = state.viscous;
        let ds = 1.0 - d.iter().map(|x| 1.0 - x).product::<f64>();
        let (normal, tangent, stress) = self.closed_or_open(&d, ds, strain, &effective);
        state.stored = 0.5 * stress.iter().zip(strain).map(|(s, e)| s * e).sum::<f64>();
        state.release = self.release_rates(&d, ds, normal, &stress);
        self.book_dissipation((strain, band, step), ([fibre, matrix], tension), old, state);
        self.release_at(old, state);
        if !self.consistent {
            return (stress, tangent, Softening::default());
        }
        let (tangent, terms) = self.consistent_tangent(
            strain,
            &effective,
            band,
            ([fibre, matrix], normal),
            (old, share, loading),
            state,
            &tangent,
        );
        (stress, tangent, terms)
    }

    /// The share `Δ/(η + Δ)` of the law's damage in the regularised one
    /// over a step `step` (1 without viscosity).
    fn share(&self, step: f64) -> f64 {
        if self.viscosity > 0.0 && step.is_finite() { step / (self.viscosity + step) } else { 1.0 }
    }

    /// Adds to `state.released` what each mode's growth from `old` releases
    /// at the committed strain `old.strain` (J/m³): `W(ε_n; d) − W(ε_n; d')`
    /// with `d` the damage before and `d'` after the mode's growth, the
    /// modes taken in [`MODES`] order, so that the sum over the modes is
    /// `W(ε_n; d_n) − W(ε_n; d_(n+1))` exactly. Each is ≥ 0: at fixed strain
    /// the stored energy falls as a compliance grows (the conjugate of a
    /// complementary energy that rises).
    fn release_at(&self, old: &DamageState, state: &mut DamageState) {
        if (0..4).all(|i| state.viscous[i] <= old.viscous[i]) {
            return;
        }
        let mut d = old.viscous;
        let mut before = self.stored(&d, &old.strain);
        for mode in 0..4 {
            if state.viscous[mode] > old.viscous[mode] {
                d[mode] = state.viscous[mode];
                let after = self.stored(&d, &old.strain);
                state.released[mode] += before - after;
                before = after;
            }
        }
    }

    /// The stress (material axes) at the strain `strain` with the damage
    /// the stiffness takes `d` (the branches solved as in
    /// [`PlyDamage::update`]).
    pub(crate) fn stress(&self, d: &[f64; 4], strain: &Voigt) -> Voigt {
        let ds = 1.0 - d.iter().map(|x| 1.0 - x).product::<f64>();
        let effective = mat_vec(&self.stiffness, strain);
        self.closed_or_open(d, ds, strain, &effective).2
    }

    /// The elastic strain energy density `½ σ·ε` (J/m³) held at the strain
    /// `strain` (material axes) with the damage the stiffness takes `d`
    /// (the stress's branches solved as in [`PlyDamage::update`]).
    pub(crate) fn stored(&self, d: &[f64; 4], strain: &Voigt) -> f64 {
        0.5 * self.stress(d, strain).iter().zip(strain).map(|(s, e)| s * e).sum::<f64>()
    }

    /// The stress whose work conjugate draws a mode's softening line: the
    /// effective stress, or with `uniaxial` its normal components
    /// `ε_k / S⁰_kk` (what the damaged compliance's own entry carries).
    fn softening_stress(&self, strain: &Voigt, effective: &Voigt) -> Voigt {
        let mut s = *effective;
        if self.uniaxial_softening {
            for k in 0..3 {
                s[k] = strain[k] / self.compliance[k][k];
            }
        }
        s
    }

    /// Onset and damage of one active mode at the onset measure `phi`.
    fn soften(&self, mode: usize, phi: f64, length: f64, strain: &Voigt, effective: &Voigt, state: &mut DamageState) {
        let (e, s) = equivalent(mode, strain, &self.softening_stress(strain, effective), self.fibre_shear);
        if !(e > 0.0) {
            return;
        }
        let delta = length * e;
        if state.onset[mode] == 0.0 {
            // Bažant & Oh: a band longer than the law allows lowers the
            // strength (the onset threshold of φ) so that the elastic energy
            // of the band at onset stays below G_I.
            let threshold = (self.longest_band(mode) * (1.0 - 1e-3) / length).sqrt().min(1.0);
            if !(phi >= threshold) {
                return;
            }
            let (mut onset, mut strength) = (delta / phi * threshold, s / phi * threshold);
            let g = self.toughness[mode];
            state.reduced[mode] = threshold < 1.0;
            if onset * strength >= 2.0 * g {
                // A multiaxial onset past the uniaxial estimate: lowered at
                // the point itself (the stress drops at once here).
                let scale = (2.0 * g * (1.0 - 1e-3) / (onset * strength)).sqrt();
                onset *= scale;
                strength *= scale;
                state.reduced[mode] = true;
            }
            state.onset[mode] = onset;
            state.last[mode] = 2.0 * g / strength;
        }
        let (onset, last) = (state.onset[mode], state.last[mode]);
        state.kappa[mode] = state.kappa[mode].max(delta);
        let kappa = state.kappa[mode];
        let reached = if kappa > onset { last * (kappa - onset) / (kappa * (last - onset)) } else { 0.0 };
        state.damage[mode] = state.damage[mode].max(reached.min(self.max_damage));
    }

    /// The modes of the three normal stresses (module docs: the tension
    /// mode where the damaged stress `σ_k ≥ 0`, else the compression mode),
    /// the damaged stiffness and the stress: the signs guessed from the
    /// effective stress, then taken from the stress until they agree (the
    /// map is continuous, so where two choices disagree by a sign flip of a
    /// stress at zero either is right; eight tries at most).
    fn closed_or_open(&self, d: &[f64; 4], ds: f64, strain: &Voigt, effective: &Voigt) -> ([usize; 3], Matrix6, Voigt) {
        let modes = |s: [bool; 3]| [if s[0] { FT } else { FC }, if s[1] { MT } else { MC }, if s[2] { MT } else { MC }];
        if d.iter().all(|&x| x == 0.0) {
            // intact (d_s = 0 too): every choice of modes is the same stiffness, so the
            // loop below would end on the signs of this stress
            let stress = mat_vec(&self.intact, strain);
            return (modes([stress[0] >= 0.0, stress[1] >= 0.0, stress[2] >= 0.0]), self.intact, stress);
        }
        let mut signs = [effective[0] >= 0.0, effective[1] >= 0.0, effective[2] >= 0.0];
        let mut tries = 0;
        loop {
            let normal = modes(signs);
            let c = self.damaged_stiffness(normal.map(|m| d[m]), ds);
            let stress = mat_vec(&c, strain);
            let found = [stress[0] >= 0.0, stress[1] >= 0.0, stress[2] >= 0.0];
            tries += 1;
            if found == signs || tries == 8 {
                return (normal, c, stress);
            }
            signs = found;
        }
    }

    /// `C_d = S(d)⁻¹`: the normal 3×3 block inverted by cofactors (it is
    /// the admissible block with its diagonal enlarged, so its determinant
    /// is positive), the shear moduli scaled. Not `anisotropic::invert`: its
    /// Cholesky refuses pivots below 1e-12 of the largest diagonal entry,
    /// which a compliance divided by `1 − d` near `max_damage` reaches.
    fn damaged_stiffness(&self, normal: [f64; 3], ds: f64) -> Matrix6 {
        let full = &self.compliance;
        let mut a = [[0.0; 3]; 3];
        for (i, row) in a.iter_mut().enumerate() {
            row.copy_from_slice(&full[i][..3]);
        }
        for (k, d) in normal.iter().enumerate() {
            a[k][k] /= 1.0 - d;
        }
        let cof = |i: usize, j: usize| {
            let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
            let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
            a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
        };
        let det = (0..3).map(|j| a[0][j] * cof(0, j)).sum::<f64>();
        let mut c = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = cof(j, i) / det;
            }
        }
        for (k, g) in self.elastic.shear.iter().enumerate() {
            c[3 + k][3 + k] = (1.0 - ds) * g;
        }
        c
    }
}

/// `e ∂e/∂ε` of a mode: each driving component of the strain times the
/// sign with which it enters (the brackets `⟨±ε⟩` where they are open).
fn equivalent_gradient(mode: usize, strain: &Voigt, fibre_shear: f64) -> Voigt {
    let pos = |x: f64| x.max(0.0);
    let mut g = [0.0; 6];
    match mode {
        FT => {
            g[0] = pos(strain[0]);
            g[3] = fibre_shear * strain[3];
            g[4] = fibre_shear * strain[4];
        }
        FC => g[0] = -pos(-strain[0]),
        MT => {
            g[1] = pos(strain[1]);
            g[2] = pos(strain[2]);
            g[3..].copy_from_slice(&strain[3..]);
        }
        _ => {
            g[1] = -pos(-strain[1]);
            g[2] = -pos(-strain[2]);
            g[3..].copy_from_slice(&strain[3..]);
        }
    }
    g
}

/// The equivalent strain `e` and stress `s` of a mode (`fibre_shear`: α
/// of fibre tension, [`PlyDamage::with_fibre_shear`]).
fn equivalent(mode: usize, strain: &Voigt, effective: &Voigt, fibre_shear: f64) -> (f64, f64) {
    let pos = |x: f64| x.max(0.0);
    let shear = |k: usize| (strain[k], effective[k]);
    let root = fibre_shear.sqrt();
    let weighed = |k: usize| (root * strain[k], root * effective[k]);
    // (strain, stress) pairs that drive the mode; unused entries zero
    let pairs: [(f64, f64); 5] = match mode {
        FT => [(pos(strain[0]), pos(effective[0])), weighed(3), weighed(4), (0.0, 0.0), (0.0, 0.0)],
        FC => [(pos(-strain[0]), pos(-effective[0])), (0.0, 0.0), (0.0, 0.0), (0.0, 0.0), (0.0, 0.0)],
        MT => [(pos(strain[1]), pos(effective[1])), (pos(strain[2]), pos(effective[2])), shear(3), shear(4), shear(5)],
        _ => {
            [(pos(-strain[1]), pos(-effective[1])), (pos(-strain[2]), pos(-effective[2])), shear(3), shear(4), shear(5)]
        }
    };
    let e = pairs.iter().map(|(x, _)| x * x).sum::<f64>().sqrt();
    let s = if e > 0.0 { pairs.iter().map(|(x, y)| x * y).sum::<f64>() / e } else { 0.0 };
    (e, s)
}

#[cfg(test)]
#[path = "damage_tests.rs"]
mod tests;

#[path = "damage_dissipation.rs"]
mod dissipation;

#[path = "damage_tangent.rs"]
mod tangent;
pub(crate) use tangent::Softening;
