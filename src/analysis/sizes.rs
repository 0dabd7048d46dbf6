//! The size of an analysis before it runs: the counts that set its memory
//! (`crate::size`), from the model and its symbolic factorization, and
//! what to change when the estimate does not fit.

use super::{AnalysisError, ContactResultant, HistoryRow, LeverResultant, Reaction};
use crate::assembly::Numbering;
use crate::setup::Model;
use crate::size::{MemoryEstimate, RowBytes, Sizes, chunk, grown, human_bytes};
use crate::solver::linear::Cholesky;
use crate::solver::stepping::Increment;
use std::mem::size_of;

/// What shrinks the largest part of an estimate: the frames of a
/// transient run, its time steps' records, or else the mesh.
pub(crate) fn memory_advice(m: &MemoryEstimate) -> &'static str {
    match m.parts.iter().max_by_key(|p| p.1).map(|p| p.0) {
        Some("step ends and frames") => {
            "raise analysis.output_interval (frames are kept until the run ends, one per time step at most) or use \
             fewer load steps"
        }
        Some("history of the increments") => "use fewer time steps (steps[].increments)",
        _ => "use a coarser mesh",
    }
}

/// `what: size` list of the largest parts of an estimate.
pub(crate) fn describe_memory(m: &MemoryEstimate) -> String {
    let mut parts = m.parts.clone();
    parts.sort_by_key(|p| std::cmp::Reverse(p.1));
    parts.iter().take(3).map(|(w, b)| format!("{w} {}", human_bytes(*b))).collect::<Vec<_>>().join(", ")
}

/// The sizes that set the memory of `model`'s analysis, exact after the
/// symbolic factorization.
pub fn sizes(model: &Model, numbering: &Numbering, solver: &Cholesky) -> Sizes {
    completed(model_sizes(model), numbering, solver)
}

/// `sizes` of the model (from [`model_sizes`]) with the counts of its
/// numbering and symbolic factorization: the exact sizes.
pub(crate) fn completed(mut s: Sizes, numbering: &Numbering, solver: &Cholesky) -> Sizes {
    s.equations = numbering.dofs.n_eq as u64;
    s.node_pairs = numbering.node_pairs as u64;
    s.pattern_nnz = numbering.pattern.nnz() as u64;
    s.factor_nnz = solver.factor_nnz() as u64;
    s.factor_scratch = solver.scratch_bytes() as u64;
    s.factor_symbolic = solver.symbolic_bytes() as u64;
    s.exact = true;
    s
}

/// The sizes that the model alone sets (mesh, settings, outputs), before
/// its equations are numbered (`completed` adds those).
pub(crate) fn model_sizes(model: &Model) -> Sizes {
    let mesh = &model.mesh;
    let mut s = Sizes {
        nodes: mesh.n_nodes() as u64,
        dofs: mesh.n_dofs() as u64,
        elements: mesh.n_elements() as u64,
        krylov_vectors: if model.has_unsymmetric_tangent() {
            crate::solver::krylov::GmresWork::vectors(crate::solver::reuse::GMRES_RESTART) as u64
        } else {
            0
        },
        pcg_vectors: if model.solver.reuse.enabled { pcg_vectors(model) } else { 0 },
        eigen_vectors: model
            .buckling
            .map(|b| b.modes)
            .or(model.modal.map(|m| m.modes))
            .map_or(0, |count| crate::solver::eigen::vectors(count) as u64),
        dynamic_matrices: model.transient.as_ref().map_or(0, |t| {
            let damped = t.damping.0 > 0.0 || t.damping.1 > 0.0;
            1 + u64::from(damped)
        }),
        // the step ends (kept with more than one step), and a frame per
        // output interval: at most one per time step
        snapshots: if model.steps.len() > 1 { model.steps.len() as u64 } else { 0 }
            + model
                .transient
                .as_ref()
                .and_then(|t| {
                    let total: f64 = t.durations.iter().sum();
                    let steps = model.steps.iter().fold(0usize, |n, s| n.saturating_add(s.planned_increments()));
                    t.output_interval.map(|dt| ((total / dt * (1.0 + 1e-9)).floor() as u64).min(steps as u64))
                })
                .unwrap_or(0),
        history_rows: model.steps.iter().fold(0u64, |n, s| n.saturating_add(s.planned_increments() as u64)),
        history_row: history_row(model),
        step_rows: model.steps.iter().map(|s| s.planned_increments() as u64).max().unwrap_or(0),
        step_row: RowBytes { vec: size_of::<Increment>() as u64, heap: newton_blocks(true) },
        interface_points: model.interfaces.iter().map(|i| i.points.len() as u64).sum(),
        transient_vectors: model.transient.as_ref().map_or(0, |t| transient_vectors(model, t)),
        ..Default::default()
    };
    for b in &mesh.bodies {
        let per = (b.section.kind.nodes() * b.axis.kind.nodes()) as u64;
        let n = 3 * per;
        let e = b.n_elements() as u64;
        s.gauss_points += e * per;
        s.element_entries += e * n * (n + 1) / 2;
        s.vtu_points += e * per;
    }
    // `damage::BodyDamage` holds every point's history once a material damages
    if model.materials.iter().any(|m| m.damage.is_some()) {
        s.damage_points = s.gauss_points;
    }
    s
}

/// The blocks of the Newton residuals and corrections of one increment
/// (`solver::newton::Report`), for a solve of three corrections (four
/// residuals; the drop weights of `examples/` average 2.6): as the Newton
/// solve grew them one value at a time (`grown`: the stepping's own
/// record), or as a clone holds them (the run's record).
fn newton_blocks(pushed: bool) -> u64 {
    let f = size_of::<f64>() as u64;
    let held = |n: u64| chunk(f * if pushed { grown(n) } else { n });
    held(4) + held(3)
}

/// The vectors of the equations' size the conjugate gradients with a
/// reused factor hold (`solver::reuse`): the work of `solver::krylov::pcg`
/// (5); with rigid impactors (transient), the bordered system's
/// (`solver::bordered`): its work (5), its stacked right side (2: grown by
/// two extends) and two per impactor (`FactorBorder`'s border and its
/// elimination).
fn pcg_vectors(model: &Model) -> u64 {
    let impactors = model.indenters.iter().filter(|i| i.impactor.is_some()).count() as u64;
    5 + if impactors > 0 { 5 + 2 + 2 * impactors } else { 0 }
}

/// The vectors of the DOFs' size a transient analysis adds (`dynamics`):
/// the inertia's velocities, accelerations, forces and two work vectors
/// (`Inertia::new`: 8), the energy ledger's forces of the last step
/// (`EnergyLedger::record`: internal, damping, external, contact, support,
/// and interface forces where there are interfaces), and two per impulse
/// (`Impulse::new`: the contacts' with `contact_forces = "implicit"`, the
/// interfaces' with an impulse law).
fn transient_vectors(model: &Model, t: &crate::dynamics::TransientSettings) -> u64 {
    let contacts = !(model.indenters.is_empty() && model.contacts.is_empty());
    let interfaces = !model.interfaces.is_empty();
    let impulses = u64::from(contacts && t.contact_forces == crate::dynamics::ContactForces::Implicit)
        + u64::from(interfaces && t.interface_forces.impulse());
    8 + 5 + u64::from(interfaces) + 2 * impulses
}

/// What a converged increment keeps until the results are written, in
/// the run's vectors of records (grown one at a time): its history row,
/// its increment record and, in a transient analysis, its row of the
/// energy balance; in their own blocks: the row's reactions, contact and
/// lever resultants (each with its name) and probe values, and the
/// record's Newton residuals and corrections (cloned from the stepping's).
fn history_row(model: &Model) -> RowBytes {
    let energy = if model.transient.is_some() { size_of::<crate::dynamics::energy::EnergyRow>() } else { 0 };
    let vec = (size_of::<HistoryRow>() + size_of::<Increment>() + energy) as u64;
    let names = |names: &mut dyn Iterator<Item = &String>| names.map(|n| chunk(n.len() as u64)).sum::<u64>();
    let resultants = model.indenters.len() + model.contacts.len();
    let heap = chunk((model.constraints.len() * size_of::<Reaction>()) as u64)
        + names(&mut model.constraints.iter().map(|c| &c.name))
        + chunk((resultants * size_of::<ContactResultant>()) as u64)
        + names(&mut model.indenters.iter().map(|c| &c.name))
        + names(&mut model.contacts.iter().map(|c| &c.name))
        + chunk((model.levers.len() * size_of::<LeverResultant>()) as u64)
        + names(&mut model.levers.iter().map(|l| &l.name))
        + chunk((model.probes.len() * size_of::<[f64; 3]>()) as u64)
        + newton_blocks(false);
    RowBytes { vec, heap }
}

/// Orders the equations and runs the symbolic factorization only (no
/// element matrices, no factor): the exact size of the analysis, for
/// `cufem check`.
pub fn plan(model: &Model) -> Result<Sizes, AnalysisError> {
    let numbering = model.constraint_handler.numbering(&model.mesh)?;
    let solver = Cholesky::analyze(&numbering.pattern)?;
    Ok(sizes(model, &numbering, &solver))
}
