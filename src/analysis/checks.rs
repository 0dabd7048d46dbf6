//! Checks of a finished solution against the assumptions of its analysis
//! (issue 46): a converged state whose tangent is indefinite (an unstable
//! equilibrium, past a bifurcation or limit point), and magnitudes that
//! break the analysis — a small-strain run whose displacement gradients
//! (strains and rotations) are far from small or whose displacements exceed
//! the body, stresses far beyond what any elastic strain of the material
//! could carry. Each becomes a [`Warning`] naming the key to change.

use super::Solution;
use crate::setup::{Model, Warning};

/// Largest root-mean-square displacement gradient `√(∫ ∂u_i/∂X_j ∂u_i/∂X_j
/// dV / V)` of a body that a small-strain analysis is not warned about: at
/// a rotation θ the linearized strain gains a spurious stretch θ²/2, 12.5 %
/// at 0.5 rad — more than any elastic strain, so the stresses are no longer
/// those of the structure. Over a body, not at a point: a punch's corner or
/// a plastic hinge concentrates the gradient at points of a sound analysis
/// (shipped small-strain examples: largest single components 2.99 at the corner
/// of examples/punch_plane_strain.toml and 0.23 in the plastic hinge of
/// examples/epp_cantilever.toml; body RMS values at most 0.29, on that
/// cantilever collapsing to 20 % of its length, and 0.20 on Pagano's S = 50
/// laminate, both verifications of small-strain theory at its own word).
pub(crate) const SMALL_GRADIENT: f64 = 0.5;

/// Largest elastic strain (stress over the material's largest directional
/// Young's modulus) a result is trusted with: no metal or fibre composite
/// carries 10 % elastically.
pub(crate) const PLAUSIBLE_STRAIN: f64 = 0.1;

/// The checks of this module, appended to `warnings`.
pub(super) fn check(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    unstable_state(model, solution, warnings);
    buckling(model, solution, warnings);
    if solution.history.is_empty() {
        return;
    }
    if !model.kinematics.is_nonlinear() {
        small_strain(model, solution, warnings);
    }
    stresses(model, solution, warnings);
}

/// A static state whose tangent has negative pivots is an unstable
/// equilibrium: under load control a perfect structure stays on its
/// straight (fundamental) path past a bifurcation, and Newton converges on
/// it; it is no answer to the loads.
/// Not with cohesive interfaces: a softening process zone makes the
/// tangent indefinite on a stable path (a DCB under opening control).
fn unstable_state(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    if solution.energy.is_some() || !model.interfaces.is_empty() {
        return;
    }
    let Some(last) = solution.history.last() else { return };
    let Some(n) = last.negative_pivots.filter(|&n| n > 0) else { return };
    let first = solution.history.iter().find(|r| r.negative_pivots.is_some_and(|p| p > 0)).unwrap_or(last);
    let lagging = model.solver.inertia == Some(crate::input::InertiaReport::LastFactorization);
    let counted = if lagging {
        " (solver.inertia = \"last_factorization\": the count of the last factorization, which may lag)"
    } else {
        ""
    };
    let (key, advice) = if model.solver.path.is_some() {
        (
            "solver.control",
            "the path ends on an unstable branch; trace it further (solver.max_load_factor, solver.stop) to a \
             stable state, or give analysis.imperfection to follow the branch a real structure takes"
                .to_string(),
        )
    } else {
        (
            "analysis.imperfection",
            format!(
                "a perfect structure pressed past a bifurcation stays on its unstable fundamental path under load \
                 control; give analysis.imperfection (a buckling mode as the initial shape{}), trace the path with \
                 solver.control = \"arc_length\", or find the critical loads with analysis.type = \"buckling\"",
                if model.kinematics.is_nonlinear() { "" } else { ", with analysis.geometry = \"nonlinear\"" }
            ),
        )
    };
    warnings.push(Warning {
        key: key.into(),
        message: format!(
            "the converged state at load factor {:.6} is unstable: its tangent has {n} negative pivot{}{counted} \
             (first at increment {}, load factor {:.6}), so {n} critical load{} of the structure {} been passed: {advice}",
            last.lambda,
            if n == 1 { "" } else { "s" },
            first.increment,
            first.lambda,
            if n == 1 { "" } else { "s" },
            if n == 1 { "has" } else { "have" },
        ),
    });
}

/// A buckling analysis that found no buckling load, or factors that are
/// not buckling loads (`analysis::buckling`, "What is not buckling").
fn buckling(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let (Some(settings), Some(b)) = (model.buckling, &solution.buckling) else { return };
    if model.imperfection.is_some() {
        return;
    }
    let bound = 100.0 * super::buckling::CRITICAL_STRAIN;
    let beyond = if b.beyond.is_empty() {
        String::new()
    } else {
        format!(
            "; the factors {} it found are not buckling loads: at them the structure would strain by {} (beyond \
             {bound} %, where no structural material is still elastic and the linear prebuckling state no longer \
             holds), the instability of a tensioned or sheared continuum, not of the structure",
            super::buckling::factors(&b.beyond),
            b.beyond.iter().map(|mu| format!("{:.1} %", 100.0 * mu * b.unit_strain)).collect::<Vec<_>>().join(", ")
        )
    };
    if b.factors.is_empty() {
        warnings.push(Warning {
            key: "analysis.type".into(),
            message: format!(
                "the buckling analysis found no buckling load among the lowest {} critical factors: no positive \
                 factor brings the structure to instability within {bound} % strain{beyond}; the loads put (almost) \
                 nothing in compression that could buckle it: a structure in tension does not buckle",
                settings.modes
            ),
        });
    } else if !b.beyond.is_empty() {
        warnings.push(Warning {
            key: "analysis.modes".into(),
            message: format!(
                "{} buckling load factor(s) reported{beyond}; they are left out of the table and the modes",
                b.factors.len()
            ),
        });
    }
}

/// The largest displacement gradient of each body and its displacement
/// against its size, in a small-strain analysis.
fn small_strain(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let u = &solution.u;
    let (mut nodes, mut grads) = (Vec::new(), Vec::new());
    let mut worst: Option<(usize, f64, f64)> = None;
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let cell = &model.cells[b];
        let (mut largest, mut sum2, mut vol) = (0.0f64, 0.0f64, 0.0f64);
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            body.element_nodes(e, &mut nodes);
            grads.resize(nodes.len(), [0.0; 3]);
            for gb in 0..cell.axis.n_gp {
                for gs in 0..cell.section.n_gp {
                    let w = cell.gradients(es, eb, gb, gs, &mut grads);
                    let mut h = [[0.0f64; 3]; 3];
                    for (g, &node) in grads.iter().zip(&nodes) {
                        for (i, row) in h.iter_mut().enumerate() {
                            for (j, v) in row.iter_mut().enumerate() {
                                *v += u[3 * node + i] * g[j];
                            }
                        }
                    }
                    let norm2 = h.iter().flatten().map(|v| v * v).sum::<f64>();
                    largest = largest.max(norm2.sqrt());
                    sum2 += w * norm2;
                    vol += w;
                }
            }
        }
        let rms = if vol > 0.0 { (sum2 / vol).sqrt() } else { 0.0 };
        if rms > SMALL_GRADIENT && worst.is_none_or(|w| rms > w.1) {
            worst = Some((b, rms, largest));
        }
        let moved = (0..body.n_nodes())
            .map(|n| {
                let d = 3 * (body.node_offset + n);
                (u[d] * u[d] + u[d + 1] * u[d + 1] + u[d + 2] * u[d + 2]).sqrt()
            })
            .fold(0.0, f64::max);
        if solution.energy.is_none() && moved > body.size() {
            warnings.push(Warning {
                key: "analysis.geometry".into(),
                message: format!(
                    "body {:?} moves by up to {} m, more than its own size ({} m), in a small-strain analysis, \
                     which assumes small displacements: its results do not describe the structure; check the loads' \
                     and the materials' units, or set analysis.geometry = \"nonlinear\"",
                    body.name,
                    crate::numbers::limit(moved),
                    crate::numbers::limit(body.size())
                ),
            });
        }
    }
    if let Some((b, rms, largest)) = worst {
        warnings.push(Warning {
            key: "analysis.geometry".into(),
            message: format!(
                "the displacement gradients (strains and rotations) of body {:?} are {} on average (root mean \
                 square; up to {} at a point), far beyond small strain, which a small-strain analysis assumes (a \
                 rotation θ adds a spurious strain θ²/2: 12.5 % at {SMALL_GRADIENT}): set analysis.geometry = \
                 \"nonlinear\", or check the loads' and the materials' units",
                model.mesh.bodies[b].name,
                crate::numbers::limit(rms),
                crate::numbers::limit(largest)
            ),
        });
    }
}

/// The index in the model file's list of material `k` of the model
/// (oriented copies of plies and zones, `name@angle`, are appended after
/// the file's materials).
pub(super) fn file_material(model: &Model, k: usize) -> usize {
    let name = &model.materials[k].name;
    let file_name = name.split('@').next().unwrap_or(name);
    model.materials.iter().position(|m| m.name == file_name).unwrap_or(k)
}

/// The largest directional Young's modulus `max 1/S_ii` of a material
/// (its Young's modulus if isotropic).
fn stiffest(m: &crate::materials::Material) -> f64 {
    match crate::materials::anisotropic::invert(m.elastic_stiffness()) {
        Some(s) => (0..3).map(|i| 1.0 / s[i][i]).fold(0.0, f64::max),
        None => m.young,
    }
}

/// A Gauss-point stress whose von Mises value exceeds [`PLAUSIBLE_STRAIN`]
/// times its material's stiffest modulus: beyond any elastic strain a
/// structural material carries (and, with plasticity, far above any
/// hardening curve the bounds accept).
fn stresses(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let moduli: Vec<f64> = model.materials.iter().map(stiffest).collect();
    let mut worst: Option<(usize, usize, f64, f64)> = None;
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let ngp = model.cells[b].gp_per_element();
        for e in 0..body.n_elements() {
            let material = body.material_of(body.split_element(e).0);
            for g in 0..ngp {
                let vm = crate::voigt::von_mises(&solution.stresses[solution.gp_offsets[b] + e * ngp + g]);
                let ratio = vm / moduli[material];
                if ratio > PLAUSIBLE_STRAIN && worst.is_none_or(|w| ratio > w.3) {
                    worst = Some((b, material, vm, ratio));
                }
            }
        }
    }
    let Some((b, material, vm, ratio)) = worst else { return };
    // oriented copies (plies, zones) are appended after the file's materials
    let base = file_material(model, material);
    warnings.push(Warning {
        key: format!("materials[{base}]"),
        message: format!(
            "the von Mises stress reaches {} Pa in body {:?}, {:.0} % of material {:?}'s stiffest modulus ({} Pa): \
             an elastic strain of that size is beyond every metal and fibre composite (at most {:.0} % is \
             plausible), so the result breaks the analysis' assumptions; check the loads' and the materials' units{}",
            crate::numbers::limit(vm),
            model.mesh.bodies[b].name,
            100.0 * ratio,
            model.materials[base].name,
            crate::numbers::limit(moduli[material]),
            100.0 * PLAUSIBLE_STRAIN,
            if model.kinematics.is_nonlinear() { "" } else { ", or set analysis.geometry = \"nonlinear\"" }
        ),
    });
}
