//! Linear buckling (`analysis.type = "buckling"`): the critical load
//! factors of the model's loads and the buckling modes.
//!
//! With `K₀` the elastic stiffness and `σ₀` the linear elastic stress
//! under the loads at load factor 1, the stress stiffness of `μ σ₀` is
//! `μ K_σ` (`K_σ = δ_kl ∫ ∇N_a · σ₀ ∇N_b dV`, the geometric term of the
//! total-Lagrangian tangent, `elements::geometric_matrix`), and the
//! structure loses stability where `K₀ + μ K_σ` becomes singular:
//!
//! ```text
//! K₀ φ = μ (−K_σ) φ,     μ > 0 the critical load factors
//! ```
//!
//! (Bathe, *Finite Element Procedures*, §6.8.2; CalculiX `*BUCKLE`.)
//! `K₀` is positive definite on the free DOFs; `−K_σ` is indefinite, so the
//! eigenvalues come from Lanczos in the `K₀` inner product
//! (`solver::eigen`), the smallest positive ones first. The modes are
//! returned per DOF, scaled to a largest displacement component of 1
//! (a shape; its sign is arbitrary).

use super::{AnalysisError, Structure};
use crate::solver::eigen::EigenSettings;

/// The critical load factors and their modes.
#[derive(Debug, Clone, PartialEq)]
pub struct Buckling {
    /// Critical load factors μ, ascending (the loads times μ buckle).
    pub factors: Vec<f64>,
    /// Modes, 3 per node (constrained DOFs zero), largest |component| 1.
    pub modes: Vec<Vec<f64>>,
    /// Relative Ritz residual of each pair.
    pub residuals: Vec<f64>,
    /// Solves with the factor of `K₀` the eigensolver took.
    pub solves: usize,
}

/// The buckling analysis about the structure's present (converged, linear
/// elastic) state: `modes` critical load factors of the loads at factor 1.
pub(crate) fn solve(structure: &mut Structure<'_>, modes: usize) -> Result<Buckling, AnalysisError> {
    use crate::solver::newton::NonlinearProblem;
    // K₀ at the converged state (elastic, small strain: the same everywhere)
    structure.evaluate()?;
    let lambda = structure.load_factor();
    let k0 = structure.tangent_values().to_vec();
    let kg = structure.stress_stiffness();
    // the stress state of the loads at factor 1 (linear: σ scales with λ)
    let b: Vec<f64> = kg.iter().map(|v| -v / lambda).collect();
    // 1e-8: a load factor's error is of the order of the residual squared
    // (a Rayleigh quotient); 1e-10 is out of reach of the round-off of
    // slender models' K₀ (a 4 m deep-web cantilever stalled at 5e-9)
    let settings = EigenSettings { count: modes, positive_only: true, tolerance: 1e-8, ..Default::default() };
    let sol = structure.eigen(&k0, &b, &settings)?;
    let n_dofs = structure.displacements().len();
    let modes = sol.vectors.iter().map(|v| super::modal::shape(structure, v, n_dofs)).collect();
    Ok(Buckling { factors: sol.values, modes, residuals: sol.residuals, solves: sol.solves })
}

/// `analysis.imperfection`: the buckling analysis of the same model — small
/// strain, its materials taken elastic — and its mode `imp.mode` scaled to
/// a largest component of `imp.amplitude`, the stress-free initial
/// displacement `u₀` of the nonlinear analysis (`elements::PointData::initial`).
/// Returns `u₀` (per DOF) and the buckling analysis it came from.
pub(crate) fn imperfection(
    model: &crate::model::Model,
    imp: crate::model::Imperfection,
) -> Result<(Vec<f64>, Buckling), AnalysisError> {
    let mut linear = model.clone();
    linear.kinematics = crate::kinematics::Kinematics::Linear;
    linear.imperfection = None;
    // by load control: the linear static state at the loads of the first step
    linear.solver.path = None;
    linear.buckling = Some(crate::model::BucklingSettings { modes: imp.mode });
    // the buckling of the loads' static state, whatever the analysis that
    // follows (a transient one integrates from the imperfect shape)
    linear.transient = None;
    linear.modal = None;
    for m in &mut linear.materials {
        let density = m.density;
        *m = crate::materials::Material::new(m.name.clone(), m.young, m.poisson, None);
        m.density = density;
    }
    // a single static increment (the model is now linear)
    linear.solver.steps.initial = 1.0;
    linear.solver.steps.max = 1.0;
    for s in &mut linear.steps {
        s.settings.initial = 1.0;
        s.settings.max = 1.0;
    }
    let sol = super::run(&linear, &Default::default(), &mut super::Silent)?;
    let b = sol.buckling.ok_or(AnalysisError::Imperfection(imp.mode, 0))?;
    let mode = b.modes.get(imp.mode - 1).ok_or(AnalysisError::Imperfection(imp.mode, b.modes.len()))?;
    Ok((mode.iter().map(|m| m * imp.amplitude).collect(), b))
}
