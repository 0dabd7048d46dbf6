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
//!
//! **What is not buckling.** A positive μ is a load at which `K₀ + μ K_σ`
//! is singular; it is a buckling load only if the structure reaches it
//! elastically with small strain, the premise of the linear prebuckling
//! state. Under tension, shear and the supports' restrained Poisson
//! contraction leave `K_σ` slightly indefinite, and the eigenproblem finds
//! factors whose states strain the material by tens of percent (a tensioned
//! B2 column: μ = 4.0e6 for 1 N, 5.4 % strain). A factor whose critical
//! state strains some point by more than `CRITICAL_STRAIN` (`μ` times the
//! largest elastic strain of the loads at factor 1, `σᵀ C⁻¹ σ / |σ|` at
//! each Gauss point) is therefore set apart (`Buckling::beyond`), not
//! reported as a buckling load, and not used as an imperfection. Loads that
//! are absent, zero or so small that their strain is below
//! `MIN_UNIT_STRAIN` are refused by key.

use super::{AnalysisError, Structure};
use crate::solver::eigen::EigenSettings;

/// The critical load factors and their modes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Buckling {
    /// Critical load factors μ, ascending (the loads times μ buckle).
    pub factors: Vec<f64>,
    /// Modes, 3 per node (constrained DOFs zero), largest |component| 1.
    pub modes: Vec<Vec<f64>>,
    /// Relative Ritz residual of each pair.
    pub residuals: Vec<f64>,
    /// The error estimate of each pair (`post::mode_error`): of the mode
    /// shape, and the relative error of its factor `(μ_h − μ) / μ_h` it
    /// implies ([`ModeError::eigenvalue`](crate::post::mode_error::ModeError::eigenvalue)).
    pub errors: Vec<crate::post::mode_error::ModeError>,
    /// Solves with the factor of `K₀` the eigensolver took.
    pub solves: usize,
    /// Factors the eigenproblem found whose critical states strain the
    /// structure beyond `CRITICAL_STRAIN`: not buckling loads (module docs).
    pub beyond: Vec<f64>,
    /// The largest elastic strain of the loads at factor 1 (μ times it is a
    /// factor's critical strain).
    pub(crate) unit_strain: f64,
}

/// Largest elastic strain at a critical state for its factor to count as a
/// buckling load: at 2 % the Green–Lagrange strain differs from the linear
/// one by 1 %, and no metal or fibre composite stays elastic beyond it
/// (metals yield at 0.1–0.7 %, carbon fibre plies fail at 1–1.8 %). The
/// shipped column buckles at 8.6e-5, a tensioned column's spurious factors
/// lie at 5.4 % and beyond.
pub(crate) const CRITICAL_STRAIN: f64 = 0.02;

/// Smallest largest strain of the loads at factor 1 a buckling analysis
/// takes: below it a critical factor would exceed 1e28 (loads 28 orders of
/// magnitude below the critical load are a unit mistake, and near 1e-300 N
/// the static solution leaves the double-precision range).
pub(crate) const MIN_UNIT_STRAIN: f64 = 1e-30;

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
    let unit_strain = unit_strain(structure) / lambda;
    loaded(structure, unit_strain)?;
    let sol = structure.eigen(&k0, &b, &settings)?;
    let n_dofs = structure.displacements().len();
    let mut out = Buckling { unit_strain, ..Default::default() };
    out.solves = sol.solves;
    let mut k0v = vec![0.0; structure.pattern().n];
    for ((mu, v), r) in sol.values.iter().zip(&sol.vectors).zip(&sol.residuals) {
        if mu * unit_strain > CRITICAL_STRAIN {
            out.beyond.push(*mu);
        } else {
            out.factors.push(*mu);
            out.modes.push(super::modal::shape(structure, v, n_dofs));
            out.residuals.push(*r);
            // the shape's stiffness φᵀ K₀ φ, the estimate's denominator
            structure.pattern().mul_symmetric(&k0, v, &mut k0v);
            let stiffness: f64 = v.iter().zip(&k0v).map(|(a, b)| a * b).sum();
            let per_dof = super::modal::unscaled(structure, v, n_dofs);
            out.errors.push(crate::post::mode_error::mode_error(&structure.discretisation(), &per_dof, stiffness));
        }
    }
    Ok(out)
}

/// The largest elastic strain of the present Gauss-point stresses, the
/// Rayleigh quotient `σᵀ C⁻¹ σ / |σ|` at each point (the strain itself for
/// uniaxial stress, the engineering shear strain for pure shear; at most
/// the strain's norm).
fn unit_strain(structure: &Structure<'_>) -> f64 {
    let d = structure.discretisation();
    let elements = structure.elements();
    let stresses = structure.stresses();
    let compliances: Vec<Option<crate::voigt::Matrix6>> =
        d.materials.iter().map(|m| crate::materials::anisotropic::invert(m.elastic_stiffness())).collect();
    let mut largest = 0.0f64;
    for (b, body) in d.mesh.bodies.iter().enumerate() {
        let ngp = d.cells[b].gp_per_element();
        for e in 0..body.n_elements() {
            let Some(c) = &compliances[body.material_of(body.split_element(e).0)] else { continue };
            for sigma in &stresses[elements.gp_offsets[b] + e * ngp..][..ngp] {
                let norm = sigma.iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm > 0.0 {
                    let energy: f64 = (0..6).map(|i| (0..6).map(|j| sigma[i] * c[i][j] * sigma[j]).sum::<f64>()).sum();
                    largest = largest.max(energy / norm);
                }
            }
        }
    }
    largest
}

/// Refuses a buckling analysis without loads, or with loads too small to
/// scale (`unit_strain` below [`MIN_UNIT_STRAIN`]), by key.
fn loaded(structure: &Structure<'_>, unit_strain: f64) -> Result<(), AnalysisError> {
    let loads = structure.loading().loads;
    let largest = structure.external_loads().iter().fold(0.0f64, |m, f| m.max(f.abs()));
    if unit_strain >= MIN_UNIT_STRAIN && largest > 0.0 {
        return Ok(());
    }
    let (key, value) = if loads.is_empty() {
        ("loads".to_string(), "[]".to_string())
    } else {
        let entries = if loads.len() == 1 { "1 entry".to_string() } else { format!("{} entries", loads.len()) };
        ("loads".to_string(), format!("{entries}, nodal forces up to {} N", crate::numbers::limit(largest)))
    };
    Err(crate::setup::ModelError::Invalid {
        key,
        value,
        allowed: format!(
            "loads that strain the structure by at least {MIN_UNIT_STRAIN:e} with analysis.type = \"buckling\" \
             (these reach {}): the critical factors multiply the loads, so give them of the order of the \
             expected critical load (1 N makes the factors the critical loads in N)",
            crate::numbers::limit(unit_strain)
        ),
    }
    .into())
}

/// `analysis.imperfection`: the buckling analysis of the same model — small
/// strain, its materials taken elastic — and its mode `imp.mode` scaled to
/// a largest component of `imp.amplitude`, the stress-free initial
/// displacement `u₀` of the nonlinear analysis (`elements::PointData::initial`).
/// Returns `u₀` (per DOF) and the buckling analysis it came from.
pub(crate) fn imperfection(
    model: &crate::setup::Model,
    imp: crate::setup::Imperfection,
) -> Result<(Vec<f64>, Buckling), AnalysisError> {
    let mut linear = model.clone();
    linear.kinematics = crate::kinematics::Kinematics::Linear;
    linear.resolve_constraints();
    linear.imperfection = None;
    // by load control: the linear static state at the loads of the first step
    linear.solver.path = None;
    linear.buckling = Some(crate::setup::BucklingSettings { modes: imp.mode });
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
    if let Some(f) = sol.failure {
        return Err(AnalysisError::Imperfection { mode: imp.mode, found: 0, beyond: Vec::new(), why: f.to_string() });
    }
    let b = sol.buckling.unwrap_or_default();
    let Some(mode) = b.modes.get(imp.mode - 1) else {
        let why = if b.beyond.is_empty() {
            String::new()
        } else {
            format!(
                "; the factors {} it found strain the structure beyond {} % and are not buckling loads (the loads \
                 put little or nothing in compression)",
                factors(&b.beyond),
                100.0 * CRITICAL_STRAIN
            )
        };
        return Err(AnalysisError::Imperfection { mode: imp.mode, found: b.factors.len(), beyond: b.beyond, why });
    };
    Ok((mode.iter().map(|m| m * imp.amplitude).collect(), b))
}

/// Factors as a short list: `[4.049e6, 5.505e8]`.
pub(super) fn factors(values: &[f64]) -> String {
    format!("[{}]", values.iter().map(|v| crate::numbers::limit(*v)).collect::<Vec<_>>().join(", "))
}
