//! Free vibration (`analysis.type = "modal"`): the lowest natural
//! frequencies and modes of the structure about the end of its static
//! analysis.
//!
//! Small oscillations `u = u* + φ e^(iωt)` about an equilibrium `u*` obey
//!
//! ```text
//! K_T(u*) φ = ω² M φ,     f = ω / 2π
//! ```
//!
//! with `K_T` the tangent at `u*` — of an unloaded model the elastic
//! stiffness; with loads and `analysis.geometry = "nonlinear"` it carries
//! the geometric (initial-stress) term, so a tensioned member stiffens and
//! a compressed one softens (the pre-stressed modes of CalculiX's
//! `*FREQUENCY` after a `*STATIC, PERTURBATION` base state); contact points
//! in contact add their penalty stiffness, yielded points their
//! elastoplastic tangent — and `M` the mass matrix (`dynamics::mass`).
//! Lanczos in the `K` inner product with the spectral transformation
//! (`solver::eigen`: `θ = 1/ω²`, the lowest frequencies converge first)
//! needs `K_T` positive definite: a structure free to move rigidly, or
//! past a limit point, is refused by the factorization.
//!
//! **Effective masses.** With a rigid translation `r_k` (1 on every free
//! DOF of direction `k`), the participation factor of mode `i` is
//! `Γ_ik = φᵢᵀ M r_k / φᵢᵀ M φᵢ` and its effective mass
//! `m_ik = Γ_ik² φᵢᵀ M φᵢ`; summed over all modes they give `r_kᵀ M r_k`,
//! the mass that moves with the free DOFs (Chopra, *Dynamics of
//! Structures*, §13.2). They tell bending (`x`, `z`), axial (`y`) and
//! torsional (none) modes apart.

use super::{AnalysisError, Structure};
use crate::solver::eigen::EigenSettings;

/// The natural frequencies and their modes.
#[derive(Debug, Clone, PartialEq)]
pub struct Modal {
    /// Natural frequencies f (Hz), ascending.
    pub frequencies: Vec<f64>,
    /// Modes, 3 per node (constrained DOFs zero), largest |component| 1.
    pub modes: Vec<Vec<f64>>,
    /// Effective masses `m_ik` (kg) of each mode in x, y and z.
    pub effective_masses: Vec<[f64; 3]>,
    /// The mass moving with the free DOFs in x, y and z, `r_kᵀ M r_k` (kg).
    pub free_mass: [f64; 3],
    /// Relative Ritz residual of each pair.
    pub residuals: Vec<f64>,
    /// Solves with the factor of `K_T` the eigensolver took.
    pub solves: usize,
}

/// The `settings.modes` lowest natural frequencies of the structure about
/// its present (converged) state.
pub(crate) fn solve(
    structure: &mut Structure<'_>,
    settings: crate::model::ModalSettings,
) -> Result<Modal, AnalysisError> {
    use crate::solver::newton::NonlinearProblem;
    // the tangent at the converged state
    structure.evaluate()?;
    let (k, m) = structure.vibration_matrices(settings.mass)?;
    // 1e-8: the frequency's error is of the order of the residual squared
    let eigen_settings =
        EigenSettings { count: settings.modes, positive_only: true, tolerance: 1e-8, ..Default::default() };
    let sol = structure.eigen(&k, &m, &eigen_settings)?;
    let pattern = structure.pattern();
    // r_k per equation, and M r_k
    let n_eq = pattern.n;
    let mut direction = vec![[0.0; 3]; n_eq];
    let n_dofs = structure.displacements().len();
    for d in 0..n_dofs {
        if let Some(e) = structure.equation(d) {
            direction[e][d % 3] = 1.0;
        }
    }
    let mut mr = [vec![0.0; n_eq], vec![0.0; n_eq], vec![0.0; n_eq]];
    for (k, out) in mr.iter_mut().enumerate() {
        let r: Vec<f64> = direction.iter().map(|d| d[k]).collect();
        pattern.mul_symmetric(&m, &r, out);
    }
    let free_mass: [f64; 3] = std::array::from_fn(|k| mr[k].iter().zip(&direction).map(|(a, d)| a * d[k]).sum::<f64>());
    let mut modes = Vec::with_capacity(sol.vectors.len());
    let mut effective_masses = Vec::with_capacity(sol.vectors.len());
    let mut mphi = vec![0.0; n_eq];
    for v in &sol.vectors {
        pattern.mul_symmetric(&m, v, &mut mphi);
        let modal_mass: f64 = v.iter().zip(&mphi).map(|(a, b)| a * b).sum();
        effective_masses.push(std::array::from_fn(|k| {
            let l: f64 = v.iter().zip(&mr[k]).map(|(a, b)| a * b).sum();
            l * l / modal_mass
        }));
        modes.push(shape(structure, v, n_dofs));
    }
    let frequencies = sol.values.iter().map(|w2| w2.sqrt() / (2.0 * std::f64::consts::PI)).collect();
    Ok(Modal { frequencies, modes, effective_masses, free_mass, residuals: sol.residuals, solves: sol.solves })
}

/// Mode `v` (per equation) per DOF, scaled to a largest component of +1.
pub(super) fn shape(structure: &Structure<'_>, v: &[f64], n_dofs: usize) -> Vec<f64> {
    let mut mode = vec![0.0; n_dofs];
    for (d, m) in mode.iter_mut().enumerate() {
        if let Some(e) = structure.equation(d) {
            *m = v[e];
        }
    }
    let (mut big, mut sign) = (0.0f64, 1.0);
    for m in &mode {
        if m.abs() > big {
            (big, sign) = (m.abs(), m.signum());
        }
    }
    mode.iter_mut().for_each(|m| *m *= sign / big.max(f64::MIN_POSITIVE));
    mode
}
