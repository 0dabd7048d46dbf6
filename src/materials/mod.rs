//! Constitutive models at a material (Gauss) point.
//!
//! The material point is a pure function
//! `(total strain ε_{n+1}, committed state S_n) → (σ_{n+1}, C^cep, S_{n+1})`:
//! it never mutates the committed state; the caller commits `S_{n+1}` only
//! when the load increment has converged (as in Ferrite's plasticity example
//! and deal.II step-42).
//!
//! Models: isotropic linear elasticity, and von Mises (J2) plasticity with
//! isotropic hardening (perfect, linear, tabulated, Voce) and optional
//! nonlinear kinematic hardening (Armstrong–Frederick / Chaboche back-stresses,
//! [`kinematic`]) integrated by the radial-return map with the
//! consistent (algorithmic) tangent — Simo & Hughes, *Computational
//! Inelasticity* (1998), §3.3; de Souza Neto, Perić & Owen, *Computational
//! Methods for Plasticity* (2008), Box 7.3 and eq. (7.120). The paper uses the
//! same model (Nagaraj et al., eq. 5, and its ref. \[21\]).
//!
//! Strains and stresses follow [`crate::voigt`] (engineering shear strains).

pub mod anisotropic;
pub mod cohesive;
pub mod damage;
pub(crate) mod damage_impulse;
pub mod failure;
mod hardening;
pub mod kinematic;
mod ply_point;

pub use anisotropic::{Frame, Orthotropic};
pub use failure::{Indices, Strengths};
pub use hardening::Hardening;
pub use kinematic::BackStress;
pub(crate) use kinematic::MAX_BACKSTRESSES;

use crate::voigt::{self, Matrix6, Voigt};

/// History variables of one material point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointState {
    /// Plastic strain, engineering shear (see [`crate::voigt`]).
    pub plastic_strain: Voigt,
    /// Equivalent plastic strain `ε̄ᵖ = ∫ sqrt(2/3 ε̇ᵖ:ε̇ᵖ) dt` ("PEEQ").
    pub peeq: f64,
    /// Back-stresses `X_i` (stress-like, deviatoric, Pa) of the material's
    /// kinematic hardening terms, in their order; unused entries stay zero.
    pub(crate) back_stress: [Voigt; MAX_BACKSTRESSES],
}

/// Result of a material-point update.
#[derive(Debug, Clone, Copy)]
pub struct Response {
    /// Cauchy stress (small strain), Pa.
    pub stress: Voigt,
    /// Consistent tangent `∂σ/∂ε` (Pa), engineering-strain columns.
    pub tangent: Matrix6,
    /// Updated state (to be committed only on convergence).
    pub state: PointState,
    /// True if the step was plastic (the return map was active).
    pub plastic: bool,
    /// True if `tangent` is the elastic stiffness (lets the element reuse
    /// its cached elastic matrix).
    pub(crate) elastic_tangent: bool,
}

/// The tangent a point returns when it sits on its yield surface (the
/// committed state itself, as at the first iteration of an increment), where
/// loading and unloading tangents differ.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) enum Predictor {
    /// The elastoplastic (loading) branch: the best predictor while the load
    /// keeps growing (fewer iterations).
    #[default]
    Loading,
    /// The elastic branch: the safe predictor when the load reverses (the
    /// loading branch of a perfectly plastic zone is a mechanism).
    Elastic,
}

/// A material: isotropic linear elastic, optionally with J2 plasticity, or
/// anisotropic linear elastic ([`anisotropic`]) in a material frame.
#[derive(Debug, Clone)]
pub struct Material {
    /// Name from the model file (an oriented copy appends its angle).
    pub name: String,
    /// The name as the model file gives it (an oriented copy keeps its
    /// material's: the name messages about the file's keys use).
    pub given: String,
    /// Young's modulus E (Pa); of an anisotropic material the largest of
    /// E1, E2, E3, the scale of its penalties and bounds.
    pub young: f64,
    /// Poisson's ratio ν (−); of an anisotropic material 0 (unused: such a
    /// material has no plasticity and no B-bar by default).
    pub poisson: f64,
    /// Von Mises plasticity, `None` for a purely elastic material.
    pub hardening: Option<Hardening>,
    /// Kinematic hardening terms (at most `MAX_BACKSTRESSES`); empty for
    /// purely isotropic hardening.
    pub kinematic: Vec<BackStress>,
    /// Mass density ρ (kg/m³), `None` where the model gives none (a static
    /// analysis needs none; the mass matrix does, `crate::dynamics`).
    pub density: Option<f64>,
    /// Strengths for the failure indices ([`failure`]), in the material axes.
    pub strengths: Option<Strengths>,
    /// The material axes (global axes unless the material is oriented).
    pub frame: Frame,
    /// The stiffness in the material axes of an anisotropic material
    /// (`None`: isotropic).
    pub anisotropic: Option<Matrix6>,
    /// Progressive ply damage ([`damage`]; `None`: no damage). Its law is
    /// written in the material axes ([`Material::frame`]).
    pub damage: Option<damage::PlyDamage>,
    elastic: Matrix6,
    /// `elastic`'s inverse, `None` if it has none (formed with it: the
    /// error estimate reads it at every Gauss point of every state).
    compliance: Option<Matrix6>,
}

impl Material {
    /// A material from E, ν and an optional hardening law. Inputs are assumed
    /// validated (E > 0, −1 < ν < 0.5, positive yield stress).
    pub fn new(name: impl Into<String>, young: f64, poisson: f64, hardening: Option<Hardening>) -> Self {
        let name = name.into();
        let elastic = voigt::isotropic_stiffness(young, poisson);
        Self {
            given: name.clone(),
            name,
            young,
            poisson,
            hardening,
            kinematic: Vec::new(),
            density: None,
            strengths: None,
            frame: Frame::default(),
            anisotropic: None,
            damage: None,
            compliance: anisotropic::invert(&elastic),
            elastic,
        }
    }

    /// An anisotropic linear-elastic material from its stiffness in the
    /// material axes (validated: symmetric positive definite), in the global
    /// axes until [`Material::oriented`].
    pub fn anisotropic(name: impl Into<String>, stiffness: Matrix6) -> Self {
        let young = anisotropic::invert(&stiffness)
            .map(|s| (0..3).map(|i| 1.0 / s[i][i]).fold(0.0, f64::max))
            .unwrap_or(stiffness[0][0]);
        let mut m = Self::new(name, young, 0.0, None);
        m.anisotropic = Some(stiffness);
        m.set_elastic(stiffness);
        m
    }

    /// The same material with its axes in `frame` (the stiffness turned to
    /// the global axes: `C = Tᵀ C_m T`) and `suffix` appended to its name.
    /// An isotropic material keeps its stiffness; its frame still orients
    /// the stresses of its failure indices.
    pub fn oriented(&self, frame: Frame, suffix: &str) -> Self {
        let mut m = self.clone();
        m.name = format!("{}{suffix}", self.name);
        m.frame = frame;
        if let Some(c) = &self.anisotropic {
            m.set_elastic(frame.stiffness_to_global(c));
        }
        m
    }

    /// The elastic stiffness in the global axes, and its inverse with it.
    fn set_elastic(&mut self, c: Matrix6) {
        self.elastic = c;
        self.compliance = anisotropic::invert(&c);
    }

    /// The same material with strengths for the failure indices.
    pub(crate) fn with_strengths(mut self, strengths: Option<Strengths>) -> Self {
        self.strengths = strengths;
        self
    }

    /// `σᵀ C⁻¹ σ` with this material's elastic compliance (twice the
    /// complementary energy density).
    pub fn complementary(&self, stress: &Voigt) -> f64 {
        let s = self.compliance.as_ref().expect("validated: positive definite");
        (0..6).map(|i| (0..6).map(|j| stress[i] * s[i][j] * stress[j]).sum::<f64>()).sum()
    }

    /// The elastic strain `C⁻¹ σ` of a stress (engineering shear).
    pub(crate) fn elastic_strain(&self, stress: &Voigt) -> Voigt {
        voigt::mat_vec(self.compliance.as_ref().expect("validated: positive definite"), stress)
    }

    /// The failure indices of a global stress, `None` without strengths.
    pub fn failure_indices(&self, stress: &Voigt) -> Option<Indices> {
        self.strengths.as_ref().map(|s| s.indices(&self.frame.stress_to_material(stress)))
    }

    /// The interlaminar index and strength ratio of a global stress at a ply
    /// interface of normal z = material axis 3 ([`failure`]), `None` without strengths.
    pub(crate) fn interlaminar_index(&self, stress: &Voigt) -> Option<(f64, f64)> {
        self.strengths.as_ref().map(|s| s.interlaminar(&self.frame.stress_to_material(stress)))
    }

    /// The same material with progressive ply damage (validated: an
    /// orthotropic material with strengths, no plasticity).
    pub(crate) fn with_damage(mut self, damage: Option<damage::PlyDamage>) -> Self {
        self.damage = damage;
        self
    }

    /// The same material with kinematic hardening terms (validated: at most
    /// [`MAX_BACKSTRESSES`], `C > 0`, `γ ≥ 0`; only with plasticity).
    pub(crate) fn with_kinematic(mut self, kinematic: Vec<BackStress>) -> Self {
        assert!(kinematic.len() <= MAX_BACKSTRESSES);
        self.kinematic = kinematic;
        self
    }

    /// The same material with the mass density ρ (kg/m³, validated: positive).
    pub(crate) fn with_density(mut self, density: Option<f64>) -> Self {
        self.density = density;
        self
    }

    /// Shear modulus G.
    pub(crate) fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// Bulk modulus K.
    pub(crate) fn bulk_modulus(&self) -> f64 {
        self.young / (3.0 * (1.0 - 2.0 * self.poisson))
    }

    /// The elastic stiffness matrix.
    pub(crate) fn elastic_stiffness(&self) -> &Matrix6 {
        &self.elastic
    }

    /// True if the material can yield.
    pub fn is_plastic(&self) -> bool {
        self.hardening.is_some()
    }

    /// The material-point update (a pure function of its arguments), with
    /// the loading branch on the yield surface.
    pub fn update(&self, strain: &Voigt, old: &PointState) -> Response {
        self.update_with(strain, old, Predictor::Loading)
    }

    /// The material-point update as the element kernel uses it: as
    /// [`Material::update_with`], with the tangent made symmetric where the
    /// exact one is not (kinematic hardening: its symmetric part, exact
    /// under proportional loading — `kinematic.rs`), since the structure
    /// factorizes a symmetric tangent.
    pub(crate) fn update_for_element(&self, strain: &Voigt, old: &PointState, predictor: Predictor) -> Response {
        let mut r = self.update_with(strain, old, predictor);
        if !self.kinematic.is_empty() {
            r.tangent = voigt::symmetric_part(&r.tangent);
        }
        r
    }

    /// The material-point update with the chosen tangent branch on the
    /// yield surface (see [`Predictor`]).
    pub(crate) fn update_with(&self, strain: &Voigt, old: &PointState, predictor: Predictor) -> Response {
        let mut elastic_strain = *strain;
        for (e, p) in elastic_strain.iter_mut().zip(&old.plastic_strain) {
            *e -= p;
        }
        let trial = voigt::mat_vec(&self.elastic, &elastic_strain);
        let elastic =
            Response { stress: trial, tangent: self.elastic, state: *old, plastic: false, elastic_tangent: true };
        let Some(hardening) = &self.hardening else {
            return elastic;
        };
        if !self.kinematic.is_empty() || matches!(hardening, Hardening::Voce { .. }) {
            // the general return (nonlinear in Δp): kinematic.rs
            let g = self.shear_modulus();
            return kinematic::update(g, &self.elastic, hardening, &self.kinematic, &trial, old, predictor)
                .unwrap_or(elastic);
        }

        let g = self.shear_modulus();
        let s_trial = voigt::deviator(&trial);
        let norm_s = voigt::norm_stress(&s_trial);
        let q_trial = 1.5f64.sqrt() * norm_s;
        let (sigma_y0, slope0) = hardening.eval(old.peeq);
        let overstress = q_trial - sigma_y0;
        // Relative tolerance so that a point sitting on the yield surface after
        // a converged plastic step is not re-yielded by round-off.
        if overstress <= 1e-12 * sigma_y0 {
            // On the surface (to round-off) the tangent is not unique: elastic
            // for unloading, elastoplastic for continued loading. Taking the
            // loading branch (the Δγ → 0 limit of the consistent tangent) gives
            // the first Newton iteration of an increment a plastic predictor
            // instead of an elastic one.
            if predictor == Predictor::Loading && overstress >= -1e-10 * sigma_y0 && norm_s > 0.0 {
                let n: Voigt = s_trial.map(|v| v / norm_s);
                return Response {
                    tangent: self.elastoplastic_tangent(&n, 0.0, q_trial, slope0),
                    elastic_tangent: false,
                    ..elastic
                };
            }
            return elastic;
        }

        let (dgamma, slope) = return_map(hardening, q_trial, old.peeq, 3.0 * g);

        // σ = p 1 + (1 − 3GΔγ/q_trial) s_trial
        let factor = 1.0 - 3.0 * g * dgamma / q_trial;
        let p = voigt::trace(&trial) / 3.0;
        let mut stress = [0.0; 6];
        for k in 0..6 {
            stress[k] = factor * s_trial[k] + if k < 3 { p } else { 0.0 };
        }
        // Flow direction N̄ = s_trial / |s_trial|; Δεᵖ = Δγ sqrt(3/2) N̄ (tensor),
        // stored with engineering shear.
        let n: Voigt = s_trial.map(|v| v / norm_s);
        let mut state = *old;
        let flow = voigt::stress_like_to_strain_like(&n);
        for k in 0..6 {
            state.plastic_strain[k] += dgamma * 1.5f64.sqrt() * flow[k];
        }
        state.peeq += dgamma;

        Response {
            stress,
            tangent: self.elastoplastic_tangent(&n, dgamma, q_trial, slope),
            state,
            plastic: true,
            elastic_tangent: false,
        }
    }

    /// Consistent tangent of the radial return (de Souza Neto et al., eq. 7.120):
    /// `D = 2G (1 − 3GΔγ/q) I_dev + 6G² (Δγ/q − 1/(3G + H)) N̄⊗N̄ + K 1⊗1`.
    fn elastoplastic_tangent(&self, n: &Voigt, dgamma: f64, q_trial: f64, slope: f64) -> Matrix6 {
        let g = self.shear_modulus();
        let k_bulk = self.bulk_modulus();
        let idev = voigt::deviatoric_projector();
        let a = 2.0 * g * (1.0 - 3.0 * g * dgamma / q_trial);
        let b = 6.0 * g * g * (dgamma / q_trial - 1.0 / (3.0 * g + slope));
        let mut tangent = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let vol = if i < 3 && j < 3 { k_bulk } else { 0.0 };
                tangent[i][j] = a * idev[i][j] + b * n[i] * n[j] + vol;
            }
        }
        tangent
    }
}

/// Solves the scalar consistency condition of the radial return,
/// `q_trial − 3G Δγ − σ_y(ε̄ᵖ_n + Δγ) = 0`, for a (possibly piecewise-linear)
/// hardening curve. Returns `(Δγ, H)` with `H` the hardening slope at the
/// solution (the one entering the consistent tangent).
///
/// On a linear segment the root is closed-form, `Δγ = φ/(3G + H)`. For a
/// table this is Newton's method on the piecewise-linear residual with the
/// step clamped at segment breaks: each step either lands on the root inside
/// the current segment or stops at its end and continues on the next one, so
/// it is exact after at most as many steps as segments are crossed.
///
/// A non-finite trial stress (a diverging Newton iterate) gives a
/// non-finite `Δγ` at once, which the caller's residual reports: the
/// comparison with the segment's end is false for NaN, and the search
/// would otherwise step past the last segment forever (a crushed tube hung
/// there after its Newton iterate diverged).
fn return_map(hardening: &Hardening, q_trial: f64, peeq_old: f64, three_g: f64) -> (f64, f64) {
    let mut k = hardening.segment(peeq_old);
    let mut dgamma = 0.0;
    loop {
        let (sy, h) = hardening.on_segment(k, peeq_old + dgamma);
        let residual = q_trial - three_g * dgamma - sy;
        let step = residual / (three_g + h);
        let end = hardening.segment_end(k) - peeq_old;
        if dgamma + step <= end || !step.is_finite() || end == f64::INFINITY {
            return (dgamma + step, h);
        }
        dgamma = end;
        k += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn linear(e: f64, et: f64, sy: f64) -> Material {
        // Uniaxial tangent modulus E_T relates to the plastic modulus by H = E E_T / (E − E_T).
        Material::new("m", e, 0.3, Some(Hardening::Linear { yield_stress: sy, modulus: e * et / (e - et) }))
    }

    /// Drives a material point along a uniaxial *stress* path: ε_xx is
    /// prescribed, the lateral strains are solved so that σ_yy = σ_zz = 0.
    fn uniaxial(m: &Material, eps_xx: f64, old: &PointState, lateral_guess: f64) -> (Response, f64) {
        let mut lat = lateral_guess;
        for _ in 0..50 {
            let eps = [eps_xx, lat, lat, 0.0, 0.0, 0.0];
            let r = m.update(&eps, old);
            let res = r.stress[1];
            // lateral stress vanishes to round-off relative to the stress scale E·ε
            if res.abs() < 1e-11 * m.young * eps_xx.abs() {
                return (r, lat);
            }
            // d σ_yy / d lat with ε_yy = ε_zz = lat
            let d = r.tangent[1][1] + r.tangent[1][2];
            lat -= res / d;
        }
        panic!("uniaxial driver did not converge: eps_xx={eps_xx} lat={lat}");
    }

    /// A non-finite strain (a diverging Newton iterate) gives a non-finite
    /// stress at once with every hardening law, never a hang.
    #[test]
    fn non_finite_strain_returns_non_finite_stress() {
        let table = Hardening::Table { strains: vec![0.0, 0.01, 0.03], stresses: vec![100e6, 120e6, 130e6] };
        for h in [table, Hardening::Linear { yield_stress: 100e6, modulus: 1e9 }] {
            let m = Material::new("m", 70e9, 0.33, Some(h));
            for bad in [f64::NAN, f64::INFINITY] {
                let r = m.update(&[bad, 0.0, 0.0, 0.0, 0.0, 0.0], &PointState::default());
                assert!(!r.stress.iter().all(|s| s.is_finite()), "{bad}: {:?}", r.stress);
            }
        }
        assert!(
            return_map(&Hardening::Table { strains: vec![0.0, 0.01], stresses: vec![1e8, 2e8] }, f64::NAN, 0.0, 1e11)
                .0
                .is_nan()
        );
    }

    #[test]
    fn uniaxial_linear_hardening_reproduces_the_curve() {
        // E = 100 GPa, E_T = 10 GPa, σ_y = 100 MPa: at ε = 0.01,
        // σ = σ_y + E_T (ε − σ_y/E) = 100 + 10e3·0.009 = 190 MPa (issue #3).
        let m = linear(100e9, 10e9, 100e6);
        let (r, _) = uniaxial(&m, 0.01, &PointState::default(), -0.003);
        assert!((r.stress[0] - 190e6).abs() < 1e-6 * 190e6, "{}", r.stress[0]);
        assert!(r.plastic);
    }

    #[test]
    fn unloading_leaves_the_right_residual_plastic_strain() {
        // Load to ε = 0.01 (σ = 190 MPa), unload elastically to σ = 0:
        // residual plastic strain εᵖ = ε − σ/E = 0.01 − 0.0019 = 0.0081.
        let m = linear(100e9, 10e9, 100e6);
        let (r, lat) = uniaxial(&m, 0.01, &PointState::default(), -0.003);
        let committed = r.state;
        assert!((committed.plastic_strain[0] - 0.0081).abs() < 1e-12);
        // equivalent plastic strain of uniaxial flow equals the axial plastic strain
        assert!((committed.peeq - 0.0081).abs() < 1e-12);
        let (r0, _) = uniaxial(&m, 0.0081, &committed, lat);
        assert!(r0.stress[0].abs() < 1e-3, "{}", r0.stress[0]);
        assert!(!r0.plastic);
        // Reloading is elastic up to the previous maximum stress, then hardens again.
        let (r1, _) = uniaxial(&m, 0.0081 + 0.0019 - 1e-6, &committed, lat);
        assert!(!r1.plastic);
        let (r2, _) = uniaxial(&m, 0.012, &committed, lat);
        assert!(r2.plastic);
        assert!((r2.stress[0] - (190e6 + 10e9 * 0.002)).abs() < 1e-6 * 210e6);
        // Reverse plastic flow in compression: yield again at σ = −190 MPa (isotropic hardening).
        let (r3, _) = uniaxial(&m, 0.0081 - 0.0019 + 1e-6, &committed, lat);
        assert!(!r3.plastic && (r3.stress[0] + 190e6).abs() < 1e6);
        let (r4, _) = uniaxial(&m, 0.0081 - 0.0019 - 1e-4, &committed, lat);
        assert!(r4.plastic && r4.stress[0] < -190e6);
    }

    #[test]
    fn table_return_map_crosses_segment_breaks_exactly() {
        // Uniaxial: with a table, σ(ε) must follow the table where εᵖ = ε − σ/E.
        let strains = vec![0.0, 0.002, 0.005, 0.01, 0.02, 0.05, 0.10, 0.20];
        let stresses: Vec<f64> = [29.0, 44.7, 55.3, 62.5, 71.1, 90.2, 109.9, 126.7].iter().map(|s| s * 1e6).collect();
        let h = Hardening::Table { strains: strains.clone(), stresses: stresses.clone() };
        let m = Material::new("al", 68e9, 0.33, Some(h.clone()));
        for &eps in &[0.001, 0.004, 0.03, 0.12, 0.3] {
            let (r, _) = uniaxial(&m, eps, &PointState::default(), -0.5 * eps);
            let s = r.stress[0];
            let ep = eps - s / 68e9;
            let (expect, _) = h.eval(ep);
            assert!((s - expect).abs() < 1e-9 * expect, "eps={eps}: {s} vs {expect}");
            assert!((r.state.peeq - ep).abs() < 1e-12);
        }
    }

    fn fd_check(m: &Material, strain: &Voigt, old: &PointState) -> f64 {
        let r = m.update(strain, old);
        let mut worst: f64 = 0.0;
        let scale = r.tangent.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
        for j in 0..6 {
            let h = 1e-8;
            let (mut ep, mut em) = (*strain, *strain);
            ep[j] += h;
            em[j] -= h;
            let (sp, sm) = (m.update(&ep, old).stress, m.update(&em, old).stress);
            for i in 0..6 {
                let fd = (sp[i] - sm[i]) / (2.0 * h);
                worst = worst.max((fd - r.tangent[i][j]).abs() / scale);
            }
        }
        worst
    }

    #[test]
    fn consistent_tangent_matches_finite_differences() {
        let table = Hardening::Table {
            strains: vec![0.0, 0.002, 0.005, 0.01, 0.02],
            stresses: vec![29e6, 44.7e6, 55.3e6, 62.5e6, 71.1e6],
        };
        let laws = [
            Hardening::Perfect { yield_stress: 100e6 },
            Hardening::Linear { yield_stress: 100e6, modulus: 5e9 },
            table,
        ];
        let old =
            PointState { plastic_strain: [4e-4, -1e-4, -3e-4, 2e-4, 0.0, -1e-4], peeq: 5e-4, ..PointState::default() };
        // multiaxial strain states well inside segments (FD needs no kink within ±h)
        let strains = [
            [3e-3, -1e-3, 4e-4, 2e-3, -1.5e-3, 8e-4],
            [-2e-3, 1e-3, 1.2e-3, -3e-4, 2e-3, 1e-3],
            [1e-2, -4e-3, -4e-3, 6e-3, 0.0, 0.0],
        ];
        for law in laws {
            let m = Material::new("m", 70e9, 0.3, Some(law.clone()));
            for s in &strains {
                let r = m.update(s, &old);
                assert!(r.plastic, "{law:?} {s:?} should yield");
                let err = fd_check(&m, s, &old);
                assert!(err < 1e-6, "{law:?}: relative tangent error {err}");
            }
        }
        // elastic branch too
        let m = Material::new("m", 70e9, 0.3, Some(Hardening::Perfect { yield_stress: 1e12 }));
        assert!(fd_check(&m, &strains[0], &PointState::default()) < 1e-6);
    }

    #[test]
    fn returned_stress_lies_on_the_yield_surface() {
        let m = Material::new("m", 200e9, 0.3, Some(Hardening::Linear { yield_stress: 242.2e6, modulus: 2e9 }));
        let r = m.update(&[5e-3, -2e-3, 1e-3, 4e-3, -2e-3, 1e-3], &PointState::default());
        let (sy, _) = m.hardening.as_ref().unwrap().eval(r.state.peeq);
        assert!((voigt::von_mises(&r.stress) - sy).abs() < 1e-8 * sy);
        // plastic flow is isochoric
        assert!(voigt::trace(&r.state.plastic_strain).abs() < 1e-15);
    }
}
