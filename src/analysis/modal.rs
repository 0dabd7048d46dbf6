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
//!
//! **A model cut by symmetry planes** is `2^p` mirror images of itself
//! (`p` planes), and its modes are the full structure's modes symmetric
//! about every plane (`u_n` odd across it). The effective masses reported
//! are the full structure's: a symmetric mode `Φ` (the mode and its mirror
//! images) has `Φᵀ M_full Φ = 2^p φᵀ M φ` and, for a direction `k` along
//! every plane, `Φᵀ M_full r_k = 2^p φᵀ M r_k`, so `m_ik` is `2^p` times the
//! model's; along a plane's normal the rigid translation is antisymmetric
//! about it and a symmetric mode's effective mass is zero (the
//! antisymmetric modes that carry it are not computed). The free mass is
//! the full structure's too: `2^p` times the model's `r_kᵀ M r_k` with
//! `r_k` on every node the file's constraints leave free in direction `k`
//! — a node held only by a plane's `u_n = 0` is free in the full
//! structure (`full_free_mass`).

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
    /// True if the effective and free masses are those of the full
    /// structure of a model cut by symmetry planes (module docs), false if
    /// they are the model's own (a model without planes).
    pub full_structure: bool,
    /// Relative Ritz residual of each pair.
    pub residuals: Vec<f64>,
    /// Solves with the factor of `K_T` the eigensolver took.
    pub solves: usize,
    /// The error estimate of each mode and of its frequency
    /// (`post::mode_error`).
    pub errors: Vec<crate::post::mode_error::ModeError>,
}

/// The `settings.modes` lowest natural frequencies of the structure about
/// its present (converged) state.
pub(crate) fn solve(
    structure: &mut Structure<'_>,
    model: &crate::setup::Model,
    settings: crate::setup::ModalSettings,
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
    let mut errors = Vec::with_capacity(sol.vectors.len());
    for (v, w2) in sol.vectors.iter().zip(&sol.values) {
        pattern.mul_symmetric(&m, v, &mut mphi);
        let modal_mass: f64 = v.iter().zip(&mphi).map(|(a, b)| a * b).sum();
        let per_dof = unscaled(structure, v, n_dofs);
        errors.push(crate::post::mode_error::mode_error(&structure.discretisation(), &per_dof, w2 * modal_mass));
        effective_masses.push(std::array::from_fn(|k| {
            let l: f64 = v.iter().zip(&mr[k]).map(|(a, b)| a * b).sum();
            l * l / modal_mass
        }));
        modes.push(shape(structure, v, n_dofs));
    }
    let frequencies = sol.values.iter().map(|w2| w2.sqrt() / (2.0 * std::f64::consts::PI)).collect();
    let mut modal = Modal {
        frequencies,
        modes,
        effective_masses,
        free_mass,
        full_structure: false,
        residuals: sol.residuals,
        solves: sol.solves,
        errors,
    };
    if !model.symmetry.planes.is_empty() {
        let full = full_free_mass(model, settings.mass).map_err(AnalysisError::from)?;
        to_full_structure(&mut modal, &model.symmetry, full);
    }
    Ok(modal)
}

/// The model's effective and free masses turned into the full structure's
/// (module docs), given the full structure's free mass `full`.
fn to_full_structure(modal: &mut Modal, symmetry: &crate::bc::symmetry::Symmetry, full: [f64; 3]) {
    let copies = symmetry.copies() as f64;
    let normal: [bool; 3] = std::array::from_fn(|k| symmetry.planes.iter().any(|p| p.axis == k));
    for m in &mut modal.effective_masses {
        for k in 0..3 {
            m[k] = if normal[k] { 0.0 } else { copies * m[k] };
        }
    }
    modal.free_mass = full;
    modal.full_structure = true;
}

/// The full structure's free mass of a model cut by symmetry planes:
/// `2^p r_kᵀ M r_k` with `r_k` = 1 on every node the file's constraints
/// (not the planes') leave free in direction `k`, integrated element by
/// element with the mass matrix's own rule: `∫ ρ (Σ_a r_a N_a)²`
/// (consistent) or `∫ ρ Σ_a r_a N_a` (lumped, the row sums).
pub(crate) fn full_free_mass(
    model: &crate::setup::Model,
    kind: crate::dynamics::MassKind,
) -> Result<[f64; 3], crate::dynamics::MassError> {
    let densities = crate::dynamics::mass::densities(&model.mesh, &model.materials)?;
    // a DOF the file constrains is owned by a file's constraint (they come
    // before the planes' in the handler's order): free unless so owned
    let free: Vec<[bool; 3]> = (0..model.mesh.n_nodes())
        .map(|n| {
            std::array::from_fn(|k| {
                let owner = model.constraint_handler.prescribed(3 * n + k).map(|p| p.constraint);
                owner.is_none_or(|c| model.symmetry.constraints.contains(&c))
            })
        })
        .collect();
    let mut total = [0.0; 3];
    let (mut nodes, mut shapes) = (Vec::new(), Vec::new());
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let cell = &model.cells[b];
        let (sg, ag) = (&cell.section, &cell.axis);
        let n_section = body.section.n_elements();
        for e in 0..body.n_elements() {
            let (es, eb) = (e % n_section, e / n_section);
            body.element_nodes(e, &mut nodes);
            shapes.resize(nodes.len(), 0.0);
            for gb in 0..ag.n_gp {
                for gs in 0..sg.n_gp {
                    let (s, a) = (sg.point(es, gs), ag.point(eb, gb));
                    let w = densities[b][es] * s.weight * a.weight;
                    crate::values::shape_values(s, a, &mut shapes);
                    for (k, t) in total.iter_mut().enumerate() {
                        let r: f64 = nodes.iter().zip(&shapes).filter(|(n, _)| free[**n][k]).map(|(_, v)| v).sum();
                        *t += match kind {
                            crate::dynamics::MassKind::Consistent => w * r * r,
                            crate::dynamics::MassKind::Lumped => w * r,
                        };
                    }
                }
            }
        }
    }
    let copies = model.symmetry.copies() as f64;
    Ok(total.map(|t| copies * t))
}

/// Mode `v` (per equation) per DOF, as it is (constrained DOFs zero).
pub(super) fn unscaled(structure: &Structure<'_>, v: &[f64], n_dofs: usize) -> Vec<f64> {
    let mut mode = vec![0.0; n_dofs];
    for (d, m) in mode.iter_mut().enumerate() {
        if let Some(e) = structure.equation(d) {
            *m = v[e];
        }
    }
    mode
}

/// Mode `v` (per equation) per DOF, scaled to a largest component of +1.
pub(super) fn shape(structure: &Structure<'_>, v: &[f64], n_dofs: usize) -> Vec<f64> {
    let mut mode = unscaled(structure, v, n_dofs);
    let (mut big, mut sign) = (0.0f64, 1.0);
    for m in &mode {
        if m.abs() > big {
            (big, sign) = (m.abs(), m.signum());
        }
    }
    mode.iter_mut().for_each(|m| *m *= sign / big.max(f64::MIN_POSITIVE));
    mode
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::MassKind;

    /// A cantilever with a prescribed end: its free DOFs differ per direction.
    const MODEL: &str = r#"
        [analysis]
        type = "modal"
        modes = 2
        mass = "MASS"
        [[materials]]
        name = "steel"
        young_modulus = 200e9
        poisson_ratio = 0.3
        density = 7800.0
        [[bodies]]
        name = "b"
        material = "steel"
        section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.02, elements = 2 }, z = { from = 0.0, to = 0.01, elements = 1 } }
        axis = { element = "B3", from = 0.0, to = 0.2, elements = 3 }
        [[constraints]]
        name = "root"
        body = "b"
        where = { y = 0.0 }
        fix = ["x", "y", "z"]
        [[constraints]]
        name = "edge"
        body = "b"
        where = { y = 0.2, z = 0.0 }
        fix = ["z"]
    "#;

    #[test]
    fn the_integrated_free_mass_is_the_mass_matrixs_without_planes() {
        // two independent computations of r_kᵀ M r_k: the assembled matrix on
        // the free equations (`solve`) and the element integral of
        // `full_free_mass` (one copy, no plane)
        for (word, kind) in [("consistent", MassKind::Consistent), ("lumped", MassKind::Lumped)] {
            let model = crate::setup::Model::parse(&MODEL.replace("MASS", word)).unwrap();
            let sol = crate::analysis::run(&model, &Default::default(), &mut crate::analysis::Silent).unwrap();
            let modal = sol.modal.unwrap();
            let integrated = full_free_mass(&model, kind).unwrap();
            for k in 0..3 {
                assert!((integrated[k] - modal.free_mass[k]).abs() < 1e-12 * modal.free_mass[k], "{word} {k}");
            }
            // with the end's z fixed, less mass moves along z than along x
            assert!(modal.free_mass[2] < modal.free_mass[0]);
            assert!(!modal.full_structure);
        }
    }
}
