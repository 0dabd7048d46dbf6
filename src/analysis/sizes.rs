//! The size of an analysis before it runs: the counts that set its memory
//! (`crate::size`), from the model and its symbolic factorization, and
//! what to change when the estimate does not fit.

use super::{AnalysisError, ContactResultant, HistoryRow, Reaction};
use crate::assembly::Numbering;
use crate::setup::Model;
use crate::size::{MemoryEstimate, Sizes, human_bytes};
use crate::solver::linear::Cholesky;
use crate::solver::stepping::Increment;

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
        krylov_vectors: if model.has_friction() {
            crate::solver::krylov::GmresWork::vectors(crate::solver::reuse::GMRES_RESTART) as u64
        } else {
            0
        },
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
        history_row_bytes: history_row_bytes(model),
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
    s
}

/// Bytes a converged increment keeps until the results are written: its
/// history row (reactions, contact resultants, probes), its increment
/// record (Newton's residuals, about 8 of them), and in a transient
/// analysis its row of the energy balance.
fn history_row_bytes(model: &Model) -> u64 {
    use std::mem::size_of;
    let row = size_of::<HistoryRow>()
        + model.constraints.len() * size_of::<Reaction>()
        + (model.indenters.len() + model.contacts.len()) * size_of::<ContactResultant>()
        + model.probes.len() * size_of::<[f64; 3]>();
    let increment = size_of::<Increment>() + 8 * size_of::<f64>();
    let energy = if model.transient.is_some() { size_of::<crate::dynamics::energy::EnergyRow>() } else { 0 };
    (row + increment + energy) as u64
}

/// Orders the equations and runs the symbolic factorization only (no
/// element matrices, no factor): the exact size of the analysis, for
/// `cufem check`.
pub fn plan(model: &Model) -> Result<Sizes, AnalysisError> {
    let numbering = model.constraint_handler.numbering(&model.mesh)?;
    let solver = Cholesky::analyze(&numbering.pattern)?;
    Ok(sizes(model, &numbering, &solver))
}
