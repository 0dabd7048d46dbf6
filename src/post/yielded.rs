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
//! fit, `ε*`, and turned into a recovered stress by the material law:
//!
//! ```text
//! yielding point (on its yield surface):   σ* = σ_h + σ_m(ε*) − σ_m(ε_h)
//! never-yielded point (elastic):           σ* = σ(ε*; converged state)
//! unloaded point (ε̄ᵖ > 0, inside):         σ* = the patch fit of the stresses
//! ```
//!
//! with `σ_m` the monotonic response, the law's one-step return from the
//! virgin state (deformation theory). A yielding point's neighbours in a
//! finer run went on yielding too, so a fitted strain below the point's own
//! is charged, like one above it, along the loading curve (at the hardening
//! slope along the flow direction, at elastic stiffness across it), and
//! `σ* = σ_h` where the fit is exact; an elastic point's trial is elastic
//! unless the fit crosses its yield surface. An unloaded point's stress is
//! `C (ε − εᵖ)` with its plastic strain frozen, as rough as the plastic
//! front left it: fitting its total strain and subtracting its own `εᵖ`
//! would charge that roughness as stress error, so its elastic strain —
//! its stress — is what is fitted (the block's residual stresses after
//! unloading, `examples/block_indentation_unload.toml`: effectivity `2.32`
//! with the total strain fitted, `1.28` with the stress, tests/step_error.rs).
//! Like the exact stress, `σ*` is then (near) plastically admissible, and a point inside the plastic zone
//! is charged with the change of its stress along the yield surface that
//! the strain error implies, not with that strain error at elastic
//! stiffness (Boroomand & Zienkiewicz, *Int. J. Numer. Methods Eng.* 44,
//! 1999, recover the strains of elastoplastic solutions for the same
//! reason). Tried and measured (tests/step_error.rs, tests/estimator.rs):
//! the yielding points' fitted strains returned from their converged state
//! (the elastic trial `σ_h + C (ε* − ε_h)`) charge every fit below the
//! point's own strain at elastic stiffness: the perfectly plastic
//! cantilever's hinge (`examples/epp_cantilever.toml`) was estimated at
//! five to six times its error, the whole beam at `3.75`. The linearised
//! map, the loading tangent times `ε* − ε_h`, leaves the stress of a
//! perfectly plastic point free to turn along the surface at elastic
//! stiffness, and on the block under its punch
//! (`examples/block_indentation.toml`) it estimated `84 %` where the mesh
//! is `29 %` off its refinement. A body that never yielded keeps the stress
//! recovery unchanged, to the bit, and so does a body of several materials
//! (its patches are kept to one material, and across an interface its
//! strains jump where its tractions do not). Voigt order and engineering
//! shear as in [`crate::voigt`].

use crate::materials::{Material, PointState, Predictor};
use crate::mesh::Mesh;
use crate::values::CellValues;
use crate::voigt::Voigt;

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

/// The recovered stress at the fitted strain `fit` of a yielding point, its
/// converged stress `σ_h` plus the change of the monotonic response `σ_m`
/// from its own strain (`base = σ_m(ε_h)`), or of a never-yielded point
/// (`base` none), the return from its converged state (module docs).
fn stress_at(m: &Material, (stress, state): (&Voigt, &PointState), base: Option<&Voigt>, fit: &Voigt) -> Voigt {
    match base {
        Some(base) => {
            let at = m.update_with(fit, &PointState::default(), Predictor::Loading).stress;
            std::array::from_fn(|k| stress[k] + at[k] - base[k])
        }
        None => m.update_with(fit, state, Predictor::Loading).stress,
    }
}

/// `σ_m(ε)`, the law's one-step return from the virgin state.
fn monotonic(m: &Material, strain: &Voigt) -> Voigt {
    m.update_with(strain, &PointState::default(), Predictor::Loading).stress
}

/// Replaces, in every body with a yielded point, the patch recovery of the
/// stresses `recovered` and its first stage `along` (the layout of
/// [`super::spr::recover_stages`]) by the material's stresses at the
/// recovered total strains: along the monotonic response at a yielding
/// point, from the converged state at a never-yielded one; an unloaded
/// point keeps its stress fit (module docs). Bodies
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
            let elastic = m.elastic_strain(&stresses[g]);
            strains[g] = std::array::from_fn(|k| elastic[k] + states[g].plastic_strain[k]);
        }
    }
    let (strain_star, strain_along) = super::spr::recover_stages(mesh, cells, (&strains, 2.0), gp_offsets, false);
    for &(b, (first, end)) in &bodies {
        let m = &materials[mesh.bodies[b].material];
        for g in first..end {
            let (stress, state) = (&stresses[g], &states[g]);
            let yielding = !m.update_with(&strains[g], state, Predictor::Loading).elastic_tangent;
            if state.peeq > 0.0 && !yielding {
                // unloaded: its stress fit is kept (module docs)
                continue;
            }
            let base = yielding.then(|| monotonic(m, &strains[g]));
            let stress = |fit: &Voigt| stress_at(m, (stress, state), base.as_ref(), fit);
            recovered[g] = stress(&strain_star[g]);
            along[g] = stress(&strain_along[g]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point yielding in uniaxial tension (perfectly plastic, strained to
    /// twice its yield strain): a fitted strain a little below its own and
    /// one a little above change its axial stress alike, at the
    /// monotonic response's slope (zero), where the return from the
    /// converged state would unload the lower one at elastic stiffness; an
    /// exact fit gives the point's own stress back.
    #[test]
    fn a_yielding_point_is_charged_alike_on_both_sides() {
        let m = Material::new("steel", 200e9, 0.3, Some(crate::materials::Hardening::Perfect { yield_stress: 250e6 }));
        // uniaxial σ_xx = σ_y: elastic strain σ_y/E axially, −ν σ_y/E laterally, plus
        // the plastic strain 1.25e-3 axially, −0.625e-3 laterally (incompressible)
        let (e_el, p) = (250e6 / 200e9, 1.25e-3);
        let own: Voigt = [e_el + p, -0.3 * e_el - 0.5 * p, -0.3 * e_el - 0.5 * p, 0.0, 0.0, 0.0];
        let state =
            PointState { plastic_strain: [p, -0.5 * p, -0.5 * p, 0.0, 0.0, 0.0], peeq: p, ..Default::default() };
        let stress: Voigt = [250e6, 0.0, 0.0, 0.0, 0.0, 0.0];
        // the converged state reproduces the stress and lies on the surface
        let back = m.update_with(&own, &state, Predictor::Loading);
        assert!((back.stress[0] - 250e6).abs() < 1.0 && !back.elastic_tangent);
        let exact = stress_at(&m, (&stress, &state), Some(&monotonic(&m, &own)), &own);
        assert!(exact.iter().zip(&stress).all(|(a, b)| (a - b).abs() < 1e-6), "{exact:?}");
        for delta in [-1e-4, 1e-4] {
            let fit: Voigt = std::array::from_fn(|k| own[k] + [delta, -0.5 * delta, -0.5 * delta, 0.0, 0.0, 0.0][k]);
            let s = stress_at(&m, (&stress, &state), Some(&monotonic(&m, &own)), &fit);
            // along the loading curve: the axial stress stays at σ_y (to the
            // return's round-off), whichever side the fit lies on
            assert!((s[0] - 250e6).abs() < 1e3, "δ = {delta}: σ_xx {}", s[0]);
        }
        // the converged state's return unloads the lower fit elastically
        let fit: Voigt = std::array::from_fn(|k| own[k] + [-1e-4, 0.5e-4, 0.5e-4, 0.0, 0.0, 0.0][k]);
        let unloaded = m.update_with(&fit, &state, Predictor::Loading).stress[0];
        assert!(unloaded < 250e6 - 1e7, "σ_xx {unloaded}");
    }

    /// `C⁻¹` is the inverse of the material's elastic stiffness.
    #[test]
    fn elastic_strain_inverts_the_stiffness() {
        let m = Material::new("steel", 200e9, 0.3, None);
        let eps: Voigt = [1e-3, -2e-4, 5e-4, 3e-4, -1e-4, 2e-4];
        let back = m.elastic_strain(&crate::voigt::mat_vec(m.elastic_stiffness(), &eps));
        for k in 0..6 {
            assert!((back[k] - eps[k]).abs() < 1e-15, "{k}: {} against {}", back[k], eps[k]);
        }
    }
}
