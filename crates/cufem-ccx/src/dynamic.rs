//! The CalculiX twin of a transient model (`analysis.type = "transient"`):
//! one `*DYNAMIC, DIRECT` step per load step, so that the 3D model is
//! integrated in time with the same load history, the time histories of
//! [`crate::verify`] then compared at the probes.
//!
//! * Time: load step `k` (λ ∈ [k, k + 1]) lasts its duration `T_k`
//!   ([`cufem::dynamics::TransientSettings::time`]); its fixed time
//!   increment is `T_k` times the step's first increment fraction
//!   (`steps[k].increments`, else `[solver]`), `DIRECT` so that CalculiX does
//!   not adapt it (cufem's increments then coincide with CalculiX's where
//!   cufem does not cut back or grow its increments).
//! * Integrator: CalculiX's `*DYNAMIC` is the HHT-α method; `ALPHA=0` makes
//!   it Newmark's trapezoidal rule (β = ¼, γ = ½), cufem's default. Other
//!   Newmark parameters and Rayleigh damping have no exact CalculiX
//!   equivalent and are refused ([`check`]); the 3D mass is CalculiX's
//!   consistent one whatever `analysis.mass` says.
//! * Load history: a load's or prescribed displacement's factor is
//!   piecewise linear in λ ([`cufem::setup::steps::factor`]), hence in time:
//!   one `*AMPLITUDE, TIME=TOTAL TIME` per loaded item through
//!   `(t_k, factor(k))` at the step ends, referenced by its `*CLOAD` or
//!   `*BOUNDARY` in every step.
//! * Initial velocities: `*INITIAL CONDITIONS, TYPE=VELOCITY` on every node
//!   of the body.
//! * Output: the displacement `U` at every increment (`*NODE FILE`), of the
//!   nodes of the hexahedra holding the probes (all nodes in a model
//!   without probes), which is what verify compares.
//!
//! * Rigid tools (indenters) and contact pairs as in the static deck
//!   ([`super::deck`]); a displacement-controlled tool's reference node
//!   follows its prescribed motion through an amplitude. A rigid
//!   **impactor** (`[[indenters]] mass, velocity`) is free along its
//!   velocity, which must be a coordinate axis (its other translations and
//!   its rotation node are held). Its mass is its tool's: the tool's
//!   material has the density `m / V` (CalculiX leaves a `MASS` element's
//!   kinetic energy out of the energy check of its dynamic contact and
//!   then declares divergence); the other tools' material has a negligible
//!   one (a thousandth of the lightest body's). Its initial velocity is
//!   given to every node of the tool. Its displacement (`*NODE PRINT,
//!   NSET=REF_…`, `U, V`) and the contact's total surface force on the
//!   body (`*CONTACT PRINT, SLAVE=…, MASTER=…`, `CF`) are printed at every
//!   increment ([`crate::verify::impact`] compares them). With a rigid tool
//!   the step has `NLGEOM` (ccx 2.20 ends in a segmentation fault
//!   without). CalculiX integrates its contact forces like every other
//!   force (its penalty with the static deck's slope); cufem takes their
//!   impulse at the end of each step ([`cufem::dynamics::impulse`]).
//!   Plasticity with contact is refused ([`check`]: ccx 2.20 cannot
//!   integrate it in a `*DYNAMIC` step). CalculiX's dynamic contact needs
//!   small fixed increments: on a steel block struck by a plate, 2e-7 s
//!   converged where 1e-6 s stopped at separation (`DIRECT` allows no
//!   cutback).

use std::fmt::Write as _;

use super::CcxError;
use super::deck::{list, load_forces, set_name};
use super::mesh::HexMesh;
use cufem::dynamics::TransientSettings;
use cufem::setup::Model;
use cufem::setup::steps::{Item, factor};

/// The node set whose displacements are written at every increment.
pub const OUTPUT_SET: &str = "U_HISTORY";

/// [`CcxError::Transient`] for the first thing of a transient model that
/// the `*DYNAMIC` twin cannot reproduce exactly: an impactor moving off a
/// coordinate axis, Newmark parameters other than the trapezoidal rule,
/// Rayleigh damping.
pub fn check(model: &Model, t: &TransientSettings) -> Result<(), CcxError> {
    let refuse = |key: &str, value: String, why: &str, allowed: &str| {
        Err(CcxError::Transient { key: key.into(), value, why: why.into(), allowed: allowed.into() })
    };
    for (k, ind) in model.indenters.iter().enumerate() {
        if let Some(imp) = ind.impactor
            && axis(imp.velocity).is_none()
        {
            let v = imp.velocity.map(cufem::numbers::number);
            return refuse(
                &format!("indenters[{k}].velocity"),
                format!("[{}, {}, {}]", v[0], v[1], v[2]),
                "the CalculiX twin holds an impactor's reference node in the directions across its velocity, \
                 which it can only along coordinate axes",
                "a velocity along x, y or z",
            );
        }
    }
    let contact = !model.indenters.is_empty() || !model.contacts.is_empty();
    if let Some(k) = model.materials.iter().position(|m| m.is_plastic()).filter(|_| contact) {
        return refuse(
            &format!("materials[{k}].plasticity"),
            format!("material \"{}\"", model.materials[k].name),
            "CalculiX 2.20 cannot integrate plasticity in a *DYNAMIC step with contact pairs: its return map \
             fails at the first iteration (`no convergence in incplas`, residuals of 1e48) even before any \
             contact, and node-to-surface contact stops at the first contact increment",
            "elastic materials in a transient model with indenters or contacts",
        );
    }
    if t.beta != 0.25 || t.gamma != 0.5 || t.alpha != 0.0 {
        return refuse(
            "analysis.newmark",
            format!(
                "beta = {}, gamma = {}, alpha = {}",
                cufem::numbers::number(t.beta),
                cufem::numbers::number(t.gamma),
                cufem::numbers::number(t.alpha)
            ),
            "CalculiX's *DYNAMIC integrates by the HHT-α method, which is Newmark's method only as the \
             trapezoidal rule (α = 0)",
            "the default beta = 0.25, gamma = 0.5 (leave analysis.newmark out)",
        );
    }
    if t.damping != (0.0, 0.0) {
        return refuse(
            "analysis.damping",
            format!(
                "mass = {}, stiffness = {}",
                cufem::numbers::number(t.damping.0),
                cufem::numbers::number(t.damping.1)
            ),
            "the CalculiX twin's *DYNAMIC step has no Rayleigh damping",
            "no damping (leave analysis.damping out)",
        );
    }
    Ok(())
}

/// The coordinate axis (0, 1, 2) a velocity is along, `None` off the axes.
fn axis(v: [f64; 3]) -> Option<usize> {
    let nonzero: Vec<usize> = (0..3).filter(|&k| v[k] != 0.0).collect();
    (nonzero.len() == 1).then(|| nonzero[0])
}

/// Step end times `t_k` (s): `[0, T_0, T_0 + T_1, …]`.
fn step_ends(t: &TransientSettings) -> Vec<f64> {
    std::iter::once(0.0)
        .chain(t.durations.iter().scan(0.0, |s, d| {
            *s += d;
            Some(*s)
        }))
        .collect()
}

/// Each step's fixed time increment (s) and number of increments.
pub fn increments(model: &Model, t: &TransientSettings) -> Vec<(f64, usize)> {
    model
        .steps
        .iter()
        .zip(&t.durations)
        .map(|(s, d)| {
            let fraction = s.settings.initial.clamp(f64::MIN_POSITIVE, 1.0);
            let n = (1.0 / fraction - 1e-9).ceil().max(1.0) as usize;
            (d * fraction, n)
        })
        .collect()
}

/// An `*AMPLITUDE` through the item's factor at every step end.
fn amplitude(d: &mut String, model: &Model, name: &str, item: Item, ends: &[f64]) {
    let _ = writeln!(d, "*AMPLITUDE, NAME={name}, TIME=TOTAL TIME");
    let points: Vec<String> = ends
        .iter()
        .enumerate()
        .map(|(k, t)| format!("{t:.12e}, {:.12e}", factor(&model.steps, item, k as f64)))
        .collect();
    // at most four pairs per line
    for chunk in points.chunks(4) {
        let _ = writeln!(d, "{}", chunk.join(", "));
    }
}

/// The amplitudes, the initial velocities and the output node set (model
/// data, before the first step).
fn model_data(d: &mut String, model: &Model, mesh: &HexMesh, t: &TransientSettings) {
    let ends = step_ends(t);
    for (i, load) in model.loads.iter().enumerate() {
        amplitude(d, model, &set_name("A_L", &load.name), Item::Load(i), &ends);
    }
    for (i, c) in model.constraints.iter().enumerate() {
        if c.selection.is_some() && c.values.iter().flatten().any(|v| *v != 0.0) {
            amplitude(d, model, &set_name("A_C", &c.name), Item::Constraint(i), &ends);
        }
    }
    for (k, ind) in model.indenters.iter().enumerate() {
        if ind.impactor.is_none() && ind.displacement.iter().any(|v| *v != 0.0) {
            amplitude(d, model, &set_name("A_I", &ind.name), Item::Indenter(k), &ends);
        }
    }
    impactors(d, model, mesh);
    for &(b, v) in &t.initial_velocities {
        let set = set_name("V", &model.mesh.bodies[b].name);
        let _ = writeln!(d, "*NSET, NSET={set}\n{}", list(mesh.body_nodes(b).into_iter()));
        let _ = writeln!(d, "*INITIAL CONDITIONS, TYPE=VELOCITY");
        for (k, c) in v.iter().enumerate().filter(|(_, c)| **c != 0.0) {
            let _ = writeln!(d, "{set}, {}, {c:.12e}", k + 1);
        }
    }
    let mut nodes: Vec<usize> = model
        .probes
        .iter()
        .flat_map(|p| &p.locations)
        .flat_map(|l| mesh.elements[mesh.locate(model, l).0].iter().copied())
        .collect();
    if nodes.is_empty() {
        nodes = (0..model.mesh.bodies.len()).flat_map(|b| mesh.body_nodes(b)).collect();
    }
    nodes.sort_unstable();
    nodes.dedup();
    let _ = writeln!(d, "*NSET, NSET={OUTPUT_SET}\n{}", list(nodes.into_iter()));
}

/// Each impactor's initial velocity on every node of its rigid body (on
/// the reference node alone CalculiX's velocities alternate between v₀ and
/// 0 from one increment to the next).
fn impactors(d: &mut String, model: &Model, mesh: &HexMesh) {
    for tool in &mesh.tools {
        let ind = &model.indenters[tool.indenter];
        let Some(imp) = ind.impactor else { continue };
        let mut nodes: Vec<usize> = mesh.elements[tool.elements.clone()].iter().flatten().copied().collect();
        nodes.extend([tool.reference, tool.rotation]);
        nodes.sort_unstable();
        nodes.dedup();
        let _ = writeln!(d, "*NSET, NSET={}\n{}", set_name("V", &ind.name), list(nodes.into_iter()));
        let _ = writeln!(d, "*INITIAL CONDITIONS, TYPE=VELOCITY");
        for (c, v) in imp.velocity.iter().enumerate().filter(|(_, v)| **v != 0.0) {
            let _ = writeln!(d, "{}, {}, {v:.12e}", set_name("V", &ind.name), c + 1);
        }
    }
}

/// The rigid tools' reference and rotation nodes: a displacement-controlled
/// tool moves through its amplitude, an impactor is free along its
/// velocity's axis.
fn tools(d: &mut String, model: &Model, mesh: &HexMesh) {
    for tool in &mesh.tools {
        let ind = &model.indenters[tool.indenter];
        let (reference, rotation) = (tool.reference + 1, tool.rotation + 1);
        let _ = writeln!(d, "*BOUNDARY\n{rotation}, 1, 3, 0.");
        let free = ind.impactor.and_then(|imp| axis(imp.velocity));
        let moved = ind.impactor.is_none() && ind.displacement.iter().any(|v| *v != 0.0);
        for k in (0..3).filter(|&k| Some(k) != free && !(moved && ind.displacement[k] != 0.0)) {
            let _ = writeln!(d, "{reference}, {}, {}, 0.", k + 1, k + 1);
        }
        if moved {
            let _ = writeln!(d, "*BOUNDARY, AMPLITUDE={}", set_name("A_I", &ind.name));
            for (k, v) in ind.displacement.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                let _ = writeln!(d, "{reference}, {}, {}, {v:.12e}", k + 1, k + 1);
            }
        }
    }
}

/// The boundary conditions and loads of a step, each non-zero one through
/// its amplitude.
fn conditions(d: &mut String, model: &Model, mesh: &HexMesh) {
    for c in model.constraints.iter().filter(|c| c.selection.is_some()) {
        let set = set_name("C", &c.name);
        let fixed: Vec<usize> = (0..3).filter(|&k| c.values[k] == Some(0.0)).collect();
        if !fixed.is_empty() {
            let _ = writeln!(d, "*BOUNDARY");
            for k in fixed {
                let _ = writeln!(d, "{set}, {}, {}, 0.", k + 1, k + 1);
            }
        }
        let moved: Vec<(usize, f64)> =
            (0..3).filter_map(|k| c.values[k].filter(|v| *v != 0.0).map(|v| (k, v))).collect();
        if !moved.is_empty() {
            let _ = writeln!(d, "*BOUNDARY, AMPLITUDE={}", set_name("A_C", &c.name));
            for (k, v) in moved {
                let _ = writeln!(d, "{set}, {}, {}, {v:.12e}", k + 1, k + 1);
            }
        }
    }
    for load in &model.loads {
        let forces = load_forces(model, mesh, load);
        if forces.iter().all(|(_, f)| f.iter().all(|v| *v == 0.0)) {
            continue;
        }
        let _ = writeln!(d, "*CLOAD, AMPLITUDE={}", set_name("A_L", &load.name));
        for (n, f) in forces {
            for (k, v) in f.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                let _ = writeln!(d, "{}, {}, {v:.12e}", n + 1, k + 1);
            }
        }
    }
}

/// The model data of `model_data` and one `*DYNAMIC, DIRECT` step per
/// load step, each with its `*END STEP`.
pub fn steps(d: &mut String, model: &Model, mesh: &HexMesh, t: &TransientSettings) {
    model_data(d, model, mesh, t);
    // a rigid body in a *DYNAMIC step: ccx 2.20 ends in a segmentation
    // fault without NLGEOM (the displacements of an impact are small: the
    // same small-strain answer)
    let nlgeom = if model.kinematics.is_nonlinear() || !mesh.tools.is_empty() { " NLGEOM," } else { "" };
    let plastic = model.materials.iter().any(|m| m.is_plastic());
    for (k, ((dt, n), duration)) in increments(model, t).into_iter().zip(&t.durations).enumerate() {
        let _ = writeln!(d, "** load step {} \"{}\": {n} increments of {dt:.6e} s", k, model.steps[k].name);
        let _ = writeln!(d, "*STEP,{nlgeom} INC={}", (2 * n).max(100));
        let _ = writeln!(d, "*DYNAMIC, DIRECT, ALPHA=0.\n{dt:.12e}, {duration:.12e}");
        if plastic {
            // plasticity: converge as tightly as cufem does
            let r = model.solver.newton.residual_tolerance;
            let _ = writeln!(d, "*CONTROLS, PARAMETERS=FIELD\n{:e}, {:e}", r, 10.0 * r);
        }
        conditions(d, model, mesh);
        tools(d, model, mesh);
        let _ = writeln!(d, "*NODE FILE, NSET={OUTPUT_SET}\nU");
        for tool in &mesh.tools {
            let name = &model.indenters[tool.indenter].name;
            let _ = writeln!(d, "*NODE PRINT, NSET={}\nU, V", set_name("REF", name));
            let (slave, master) = (set_name("SS", name), set_name("SM", name));
            let _ = writeln!(d, "*CONTACT PRINT, SLAVE={slave}, MASTER={master}\nCF");
        }
        let _ = writeln!(d, "*END STEP");
    }
}

/// The end time (s) of a deck's `*DYNAMIC` steps (the sum of their time
/// periods), `None` for a deck without one.
pub fn end_time(deck: &str) -> Option<f64> {
    let mut lines = deck.lines();
    let mut end = None;
    while let Some(line) = lines.next() {
        if line.trim_start().to_ascii_uppercase().starts_with("*DYNAMIC") {
            let data = lines.next().unwrap_or_default();
            let period = data.split(',').nth(1).and_then(|v| v.trim().parse::<f64>().ok()).unwrap_or(0.0);
            end = Some(end.unwrap_or(0.0) + period);
        }
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_ends_accumulate_the_durations() {
        let t = TransientSettings {
            durations: vec![1e-9, 8e-4],
            beta: 0.25,
            gamma: 0.5,
            alpha: 0.0,
            damping: (0.0, 0.0),
            mass: cufem::dynamics::MassKind::Consistent,
            initial_velocities: Vec::new(),
            output_interval: None,
            contact_forces: Default::default(),
            contact_mass: Default::default(),
            interface_forces: Default::default(),
            ply_damage_forces: Default::default(),
        };
        assert_eq!(step_ends(&t), vec![0.0, 1e-9, 1e-9 + 8e-4]);
        let deck = "*STEP, INC=100\n*DYNAMIC, DIRECT, ALPHA=0.\n1e-9, 1e-9\n*END STEP\n*STEP\n*DYNAMIC, DIRECT, ALPHA=0.\n4e-6, 8e-4\n";
        assert_eq!(end_time(deck), Some(1e-9 + 8e-4));
        assert_eq!(end_time("*STEP\n*STATIC\n0.1, 1.0\n"), None);
    }
}
