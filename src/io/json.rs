//! `summary.json`: the numbers a script or a test reads back.

use std::path::Path;

use serde::Serialize;

use super::{IoError, file_error};
use crate::analysis::Solution;
use crate::model::Model;

/// A probe in the summary.
#[derive(Debug, Clone, Serialize)]
pub struct ProbeSummary {
    /// Probe name.
    pub name: String,
    /// Point (m).
    pub point: [f64; 3],
    /// Displacement (m).
    pub u: [f64; 3],
    /// Stress `[sxx, syy, szz, sxy, sxz, syz]` (Pa).
    pub stress: [f64; 6],
    /// Von Mises stress (Pa).
    pub von_mises: f64,
    /// Equivalent plastic strain (0 while elastic).
    pub peeq: f64,
}

/// A resultant force of a constraint set or contact.
#[derive(Debug, Clone, Serialize)]
pub struct ForceSummary {
    /// Name.
    pub name: String,
    /// `"indenter"` or `"pair"` for contacts (a pair's force is internal:
    /// the force on the slave body, balanced by the opposite one on the
    /// master); absent for reactions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<&'static str>,
    /// Force on the body (N).
    pub force: [f64; 3],
    /// Largest penetration (contacts only, m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_penetration: Option<f64>,
}

/// Phase timings in seconds.
#[derive(Debug, Clone, Serialize)]
pub struct TimingSummary {
    /// Numbering, ordering, pattern and symbolic factorization.
    pub setup_s: f64,
    /// Element loops (with material updates).
    pub assembly_s: f64,
    /// Contact terms.
    pub contact_s: f64,
    /// Numeric factorizations.
    pub factorization_s: f64,
    /// Triangular solves.
    pub solve_s: f64,
}

/// The summary file.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Model title.
    pub title: String,
    /// Degrees of freedom (3 per node).
    pub dof: usize,
    /// Free DOFs (equations solved).
    pub equations: usize,
    /// Analysis wall time (s).
    pub wall_time_s: f64,
    /// True if λ = 1 was reached.
    pub converged: bool,
    /// Load factor reached.
    pub load_factor: f64,
    /// Converged increments.
    pub increments: usize,
    /// Newton iterations in converged increments.
    pub newton_iterations: usize,
    /// Failed attempts.
    pub cutbacks: usize,
    /// Plastic Gauss points at the end.
    pub plastic_points: usize,
    /// Why the analysis stopped early, if it did.
    pub failure: Option<String>,
    /// Probe values.
    pub probes: Vec<ProbeSummary>,
    /// Reactions per constraint set.
    pub reactions: Vec<ForceSummary>,
    /// Resultants per indenter / contact pair (force on the body; on the slave body for pairs).
    pub contact: Vec<ForceSummary>,
    /// Sum of applied loads (N).
    pub applied_load: [f64; 3],
    /// Phase timings.
    pub timings: TimingSummary,
}

/// Builds the summary of a solution.
pub fn summary(model: &Model, solution: &Solution) -> Summary {
    let view = solution.fields(model);
    let probes = model
        .probes
        .iter()
        .map(|p| {
            let s = view.sample_point(p.body, p.point).unwrap_or_default();
            ProbeSummary {
                name: p.name.clone(),
                point: p.point,
                u: s.u,
                stress: s.stress,
                von_mises: s.von_mises,
                peeq: s.peeq,
            }
        })
        .collect();
    let reactions = model
        .constraints
        .iter()
        .zip(&solution.reactions)
        .map(|(c, r)| ForceSummary { name: c.name.clone(), kind: None, force: *r, max_penetration: None })
        .collect();
    let names = model
        .indenters
        .iter()
        .map(|i| (i.name.clone(), "indenter"))
        .chain(model.contacts.iter().map(|c| (c.name.clone(), "pair")));
    let contact = names
        .zip(&solution.contact)
        .map(|((name, kind), (f, pen))| ForceSummary { name, kind: Some(kind), force: *f, max_penetration: Some(*pen) })
        .collect();
    let t = &solution.timings;
    Summary {
        title: model.title.clone(),
        dof: model.n_dofs(),
        equations: solution.equations,
        wall_time_s: solution.wall_time.as_secs_f64(),
        converged: solution.failure.is_none(),
        load_factor: solution.lambda,
        increments: solution.increments.len(),
        newton_iterations: solution.increments.iter().map(|i| i.newton.iterations).sum(),
        cutbacks: solution.cutbacks.len(),
        plastic_points: solution.plastic_points,
        failure: solution.failure.as_ref().map(|f| f.to_string()),
        probes,
        reactions,
        contact,
        applied_load: solution.applied,
        timings: TimingSummary {
            setup_s: t.setup.as_secs_f64(),
            assembly_s: t.assembly.as_secs_f64(),
            contact_s: t.contact.as_secs_f64(),
            factorization_s: t.factorization.as_secs_f64(),
            solve_s: t.solve.as_secs_f64(),
        },
    }
}

/// Writes a summary as pretty JSON.
pub fn write(path: &Path, s: &Summary) -> Result<(), IoError> {
    let text = serde_json::to_string_pretty(s).expect("summary serializes");
    std::fs::write(path, text).map_err(|e| file_error(path, e))
}
