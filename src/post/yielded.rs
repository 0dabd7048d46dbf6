//! The recovery of a yielded body, for the error estimate
//! ([`super::estimate`]): its total strains are recovered, not its
//! stresses, and turned into stresses by the material law.
//!
//! Where a body yields, its stress field has a kink at the elastic–plastic
//! front and is flattened inside the plastic zone (the stress follows the
//! hardening curve, whatever the strain), while its total strain, the
//! displacement's gradient, stays smooth. A polynomial patch fit of the
//! stresses ([`super::spr`]) cannot follow the kink: the recovered stress
//! departs from the raw one by the fit's own error, not the solution's, and
//! the estimate counts that departure at elastic stiffness. On the compact
//! bar's plastic end state (`examples/bending_compact_4L9_quarter.toml`)
//! that made the estimate 2.7–3.8 times the true error, nearly all of it in
//! the elements with yielded points (tests/step_error.rs).
//!
//! So in a body with a yielded point (`ε̄ᵖ > 0`), every point's total strain
//! `ε_h = C⁻¹ σ_h + εᵖ` (the additive split of the material law,
//! [`crate::materials::Material::update`]) is recovered by the same patch
//! fit, `ε*`, and the recovered stress is the one the material law gives
//! for that strain from the point's converged state,
//!
//! ```text
//! σ* = σ(ε*; εᵖ, ε̄ᵖ, back stresses of the converged state)
//! ```
//!
//! — the elastic trial `C (ε* − εᵖ)`, returned to the yield surface if it
//! lies outside it. Like the exact stress, `σ*` is plastically admissible,
//! so a point inside the plastic zone is charged with the change of its
//! stress along the yield surface that the strain error implies, not with
//! that strain error at elastic stiffness (Boroomand & Zienkiewicz, *Int.
//! J. Numer. Methods Eng.* 44, 1999, recover the strains of elastoplastic
//! solutions for the same reason). The linearised map, the loading tangent
//! times `ε* − ε_h`, was tried first: it leaves the stress of a perfectly
//! plastic point free to turn along the surface at elastic stiffness, and
//! on the block under its punch (`examples/block_indentation.toml`) it
//! estimated `84 %` where the mesh is `29 %` off its refinement. A body
//! that never yielded keeps the stress recovery unchanged, to the bit, and
//! so does a body of several materials (its patches are kept to one
//! material, and across an interface its strains jump where its tractions
//! do not). Voigt order and engineering shear as in [`crate::voigt`].

use crate::materials::{Material, PointState, Predictor};
use crate::mesh::Mesh;
use crate::values::CellValues;
use crate::voigt::Voigt;

/// `C⁻¹ σ` for an isotropic material (engineering shear: `γ = τ / G`).
fn elastic_strain(s: &Voigt, m: &Material) -> Voigt {
    let (e, nu) = (m.young, m.poisson);
    let g = e / (2.0 * (1.0 + nu));
    [
        (s[0] - nu * (s[1] + s[2])) / e,
        (s[1] - nu * (s[2] + s[0])) / e,
        (s[2] - nu * (s[0] + s[1])) / e,
        s[3] / g,
        s[4] / g,
        s[5] / g,
    ]
}

/// The Gauss points of body `b` (its first and one past its last, in the
/// global layout of `gp_offsets`) if the body is of one plastic isotropic
/// material and one of its points has yielded.
fn yielded(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    states: &[PointState],
    gp_offsets: &[usize],
    b: usize,
) -> Option<(usize, usize)> {
    let body = &mesh.bodies[b];
    let m = &materials[body.material];
    let homogeneous = body.materials().len() == 1;
    if !homogeneous || !m.is_plastic() || m.anisotropic.is_some() {
        return None;
    }
    let range = (gp_offsets[b], gp_offsets[b] + body.n_elements() * cells[b].gp_per_element());
    let any = states.get(range.0..range.1).is_some_and(|s| s.iter().any(|p| p.peeq > 0.0));
    any.then_some(range)
}

/// Replaces, in every body with a yielded point, the patch recovery of the
/// stresses `recovered` and its first stage `along` (the layout of
/// [`super::spr::recover_stages`]) by the material's stresses at the
/// recovered total strains, from each point's converged state (module
/// docs). Bodies
/// that never yielded, and every body when `states` is empty (a mode shape),
/// are left as they are.
pub(crate) fn replace_recovery(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    (stresses, states): (&[Voigt], &[PointState]),
    gp_offsets: &[usize],
    (recovered, along): (&mut [Voigt], &mut [Voigt]),
) {
    let bodies: Vec<(usize, (usize, usize))> = (0..mesh.bodies.len())
        .filter_map(|b| yielded(mesh, cells, materials, states, gp_offsets, b).map(|r| (b, r)))
        .collect();
    if bodies.is_empty() {
        return;
    }
    // total strains at every point of the yielded bodies (zero elsewhere:
    // each body is recovered on its own)
    let mut strains = vec![[0.0; 6]; stresses.len()];
    for &(b, (first, end)) in &bodies {
        let m = &materials[mesh.bodies[b].material];
        for g in first..end {
            let elastic = elastic_strain(&stresses[g], m);
            strains[g] = std::array::from_fn(|k| elastic[k] + states[g].plastic_strain[k]);
        }
    }
    let (strain_star, strain_along) = super::spr::recover_stages(mesh, cells, &strains, gp_offsets);
    for &(b, (first, end)) in &bodies {
        let m = &materials[mesh.bodies[b].material];
        for g in first..end {
            let stress = |fit: &Voigt| m.update_with(fit, &states[g], Predictor::Loading).stress;
            recovered[g] = stress(&strain_star[g]);
            along[g] = stress(&strain_along[g]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `C⁻¹` is the inverse of the material's elastic stiffness.
    #[test]
    fn elastic_strain_inverts_the_stiffness() {
        let m = Material::new("steel", 200e9, 0.3, None);
        let eps: Voigt = [1e-3, -2e-4, 5e-4, 3e-4, -1e-4, 2e-4];
        let back = elastic_strain(&crate::voigt::mat_vec(m.elastic_stiffness(), &eps), &m);
        for k in 0..6 {
            assert!((back[k] - eps[k]).abs() < 1e-15, "{k}: {} against {}", back[k], eps[k]);
        }
    }
}
