//! `summary.json`: the numbers a script or a test reads back.

use std::path::Path;

use serde::Serialize;

use super::{IoError, file_error};
use crate::analysis::{ModeQuantity, Solution, tables};
use crate::post::Quantity;
use crate::setup::Model;

mod modes;
pub(crate) use modes::mode_vtu_name;
pub use modes::{BucklingSummary, ModalSummary};
use modes::{buckling_summary, modal_summary};

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
    /// Failure indices by name (`fi_max_stress`, …), where a material has strengths.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure_indices: Option<std::collections::BTreeMap<&'static str, f64>>,
}

/// A lever's state (`[[levers]]`).
#[derive(Debug, Clone, Serialize)]
pub struct LeverSummary {
    /// Name.
    pub name: String,
    /// Its displacement `Σ a_d u_d` (m).
    pub displacement: f64,
    /// Its force on the body (N).
    pub force: f64,
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
    /// Normal and tangential (friction) parts of `force` (contacts only, N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal_force: Option<[f64; 3]>,
    /// See `normal_force`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential_force: Option<[f64; 3]>,
    /// In a model with symmetry planes, the force on the full structure
    /// (`bc::symmetry::full_structure`: doubled per plane the item lies
    /// across, its component normal to the plane cancelled); absent in a
    /// full model and for a plane's own reaction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub full_structure_force: Option<[f64; 3]>,
}

/// Phase timings in seconds.
#[derive(Debug, Clone, Serialize)]
pub struct TimingSummary {
    /// Numbering, ordering, pattern and symbolic factorization.
    pub(crate) setup_s: f64,
    /// Element loops (with material updates).
    pub(crate) assembly_s: f64,
    /// Contact terms.
    pub(crate) contact_s: f64,
    /// Numeric factorizations.
    pub(crate) factorization_s: f64,
    /// Triangular solves and preconditioned conjugate gradients.
    pub(crate) solve_s: f64,
    /// A modal or buckling analysis's eigenproblem, its own
    /// factorizations and solves included (0 otherwise).
    pub(crate) eigen_s: f64,
    /// Residual and tangent evaluations.
    pub evaluations: usize,
    /// Numeric factorizations.
    pub factorizations: usize,
    /// Linear solves that reused an earlier factorization (PCG converged).
    pub(crate) reused_factorizations: usize,
    /// PCG iterations over all solves.
    pub krylov_iterations: usize,
    /// Solves where PCG did not converge and the tangent was factorized.
    pub fallbacks: usize,
    /// Writing the run's files, `summary.json` aside (`io::write_results`;
    /// 0 where no files are written).
    pub output_s: f64,
    /// Of `output_s`, what `report.html` alone costs: its 3D view's data
    /// (the fields on the outer surface of each frame) and the page.
    pub report_s: f64,
    /// Estimating the error of every kept step end and frame
    /// (`error_history`; part of the analysis's wall time).
    pub(crate) error_history_s: f64,
    /// Factorizations stored in single precision (`solver.factor_precision`).
    pub single_factorizations: usize,
    /// Single-precision factors that did not precondition their own tangent
    /// (the run went on in double precision).
    pub precision_fallbacks: usize,
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
    /// `"converged"`, `"not_converged"` (stopped by the load stepping) or
    /// `"interrupted"` (Ctrl-C): in the last two cases the results are those
    /// of the last converged increment.
    pub status: &'static str,
    /// Load factor reached.
    pub load_factor: f64,
    /// Converged increments.
    pub increments: usize,
    /// Newton iterations in converged increments.
    pub newton_iterations: usize,
    /// Failed attempts (and increments rejected by `solver.step_control`).
    pub cutbacks: usize,
    /// Of those, converged increments rejected by `solver.step_control`.
    pub(crate) rejected_increments: usize,
    /// Newton corrections shortened by `solver.line_search` (converged increments).
    pub(crate) line_searches: usize,
    /// Plastic Gauss points at the end.
    pub plastic_points: usize,
    /// Largest equivalent plastic strain over all Gauss points.
    pub max_peeq: f64,
    /// Why the analysis stopped early, if it did.
    pub failure: Option<String>,
    /// Probe values.
    pub probes: Vec<ProbeSummary>,
    /// Reactions per constraint set.
    pub reactions: Vec<ForceSummary>,
    /// Resultants per indenter / contact pair (force on the body; on the slave body for pairs).
    pub contact: Vec<ForceSummary>,
    /// Per lever, its displacement and force at the end (absent without levers).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub levers: Vec<LeverSummary>,
    /// Sum of applied loads (N).
    pub applied_load: [f64; 3],
    /// Phase timings.
    pub timings: TimingSummary,
    /// Memory: estimate before the analysis and measured peak.
    pub memory: MemorySummary,
    /// Warnings of the model and of the results.
    pub warnings: Vec<String>,
    /// The end of every completed step of the load history.
    pub steps: Vec<StepSummary>,
    /// The estimated discretization error (`post::estimate`), if computed.
    pub error_estimate: Option<EstimateSummary>,
    /// The estimated error of every step end and frame the run kept
    /// (`analysis::state_errors`), in the order of λ; absent without one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub error_history: Vec<super::error_history::StateErrorSummary>,
    /// The loads, supports and contacts that act on points or lines
    /// (`analysis::concentrated`): the stresses of the elements around them do
    /// not converge under refinement. Absent when there are none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub concentrated: Vec<crate::analysis::concentrated::Concentrated>,
    /// The failure indices' largest values and the first-ply-failure load
    /// factor (`post::failure`), where a material has strengths.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ply_failure: Option<crate::post::failure::FailureSummary>,
    /// The cycles of an adaptive run (`cufem run --adapt`), absent otherwise;
    /// the rest of the summary is the last cycle's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapt: Option<Vec<CycleSummary>>,
    /// Why the adaptive run stopped, absent for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapt_stop: Option<String>,
    /// The cycle whose results the files hold (the last finished one),
    /// absent for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapt_cycle: Option<usize>,
    /// How the adaptive run ended: `"done"` (tolerance, budget, memory,
    /// max_cycles), `"stopped"` (a cycle failed or stopped early) or
    /// `"interrupted"`; absent for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapt_end: Option<&'static str>,
    /// Wall time of all the cycles of an adaptive run (s; `wall_time_s`
    /// is the last cycle's), absent for a single run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapt_time_s: Option<f64>,
    /// `analysis.type = "buckling"`: the critical load factors and their
    /// mode files, absent for a static analysis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub buckling: Option<BucklingSummary>,
    /// `analysis.type = "modal"`: the natural frequencies, effective masses
    /// and mode files, absent for another analysis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modal: Option<ModalSummary>,
    /// `analysis.type = "transient"`: the last row of `energy.csv` by column
    /// name (`time` in s, `kinetic` … in J), absent for another analysis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<tables::Row>,
    /// In a transient model cut by symmetry planes, the full structure's energy balance at the
    /// end: `energy` (and `energy.csv`, the part modelled) times the number of mirror images.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub full_structure_energy: Option<tables::Row>,
    /// `solver.control = "arc_length"`: how the path following ended and
    /// the limit points it passed, absent under load control.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path: Option<PathSummary>,
    /// Cohesive interfaces: each one's delaminated area and dissipated
    /// energy, and their sums.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub delamination: Option<crate::interfaces::DelaminationSummary>,
    /// Progressive ply damage: the energy each mode dissipated, the
    /// volumes where each mode started and passed ½, the largest damage,
    /// the points whose strength the crack band lowered.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damage: Option<crate::damage::DamageSummary>,
    /// The other files of this result set (summary.json is written last and
    /// lists them, so a complete set can be recognised).
    pub files: Vec<String>,
}

/// A path following in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct PathSummary {
    /// The stop criterion met: `"load_factor"` (λ reached
    /// `solver.max_load_factor`), `"displacement"` (the probe of
    /// `solver.stop` passed its value) or `"none"` (stopped early:
    /// `failure` says why).
    pub end: &'static str,
    /// The limit points passed, in order: `[increment, λ]` of the converged
    /// point where λ turned (a maximum, then a minimum after a snap).
    pub limit_points: Vec<(usize, f64)>,
    /// The first arc length (m).
    pub(crate) first_arc_length: f64,
}

/// One cycle of an adaptive run.
#[derive(Debug, Clone, Serialize)]
pub struct CycleSummary {
    /// Cycle number, 0 for the model's own mesh.
    pub cycle: usize,
    /// Degrees of freedom.
    pub dof: usize,
    /// Relative error estimate (energy norm, 0–1; modal, buckling: the
    /// largest estimated relative frequency or critical load factor error
    /// of the modes followed).
    pub estimate: f64,
    /// Modal: the frequencies of the modes followed (Hz); absent otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub frequencies: Vec<f64>,
    /// Modal: their estimated relative errors (0–1); absent otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub frequency_errors: Vec<f64>,
    /// Buckling: the critical load factors of the modes followed; absent
    /// otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub factors: Vec<f64>,
    /// Buckling: their estimated relative errors (0–1); absent otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub factor_errors: Vec<f64>,
    /// Transient: the kept state the estimate is of, the worst of the
    /// frames and the end (`frame_0004`, `end`); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state: Option<String>,
    /// Wall time of the cycle: building its model and solving it (s).
    pub time_s: f64,
    /// What its mesh refined in the previous cycle's.
    pub refined: String,
}

/// The estimated discretization error of a run.
#[derive(Debug, Clone, Serialize)]
pub struct EstimateSummary {
    /// How it is estimated.
    pub method: &'static str,
    /// Estimated relative error in the energy norm (0–1).
    pub relative_energy_norm: f64,
    /// The elements holding most of it: body, element within the body, and
    /// share of the squared error.
    pub largest: Vec<ElementShare>,
}

/// An element's share of the estimated error.
#[derive(Debug, Clone, Serialize)]
pub struct ElementShare {
    /// Body name.
    pub body: String,
    /// Element index within the body (section element + section elements ×
    /// beam element).
    pub element: usize,
    /// Share of `Σ η_e²`.
    pub share: f64,
}

/// The estimate of `solution`, with its five largest elements.
pub(crate) fn estimate_summary(model: &Model, solution: &Solution) -> Option<EstimateSummary> {
    let est = solution.error_estimate.as_ref()?;
    let largest = est
        .largest(5)
        .into_iter()
        .map(|(e, share)| {
            let (b, element) = model.mesh.body_of_element(e);
            ElementShare { body: model.mesh.bodies[b].name.clone(), element, share }
        })
        .collect();
    Some(EstimateSummary {
        method: "Zienkiewicz-Zhu: raw Gauss-point stresses against their superconvergent patch recovery, energy norm",
        relative_energy_norm: est.relative(),
        largest,
    })
}

/// The results at the end of one step.
#[derive(Debug, Clone, Serialize)]
pub struct StepSummary {
    /// Step name.
    pub name: String,
    /// Analysis time λ at its end (step k ends at λ = k + 1).
    pub load_factor: f64,
    /// Index of its last increment.
    pub increment: usize,
    /// Largest equivalent plastic strain at its end.
    pub max_peeq: f64,
    /// Probe values at its end.
    pub probes: Vec<ProbeSummary>,
    /// Reactions at its end.
    pub reactions: Vec<ForceSummary>,
    /// Contact resultants at its end.
    pub contact: Vec<ForceSummary>,
    /// Its VTU file, when the history has several steps.
    pub vtu: Option<String>,
}

/// Memory of the run.
#[derive(Debug, Clone, Serialize)]
pub struct MemorySummary {
    /// Estimate made after the symbolic factorization (bytes).
    pub estimated_bytes: u64,
    /// Peak resident memory of the process when the summary was written (bytes).
    pub peak_bytes: Option<u64>,
}

/// Probe values of a solution, from its table (`analysis::tables::probes`).
fn probes(model: &Model, solution: &Solution) -> Vec<ProbeSummary> {
    let (t, criteria) = (&tables::probes(model, &solution.fields(model)), crate::post::failure::CRITERIA);
    let names = t.text("probe").unwrap_or_default();
    let each = |q: fn(usize) -> Quantity, i| move |k| t.at(&q(k).name(), i);
    (names.iter().enumerate())
        .map(|(i, name)| ProbeSummary {
            name: name.clone(),
            point: ["x", "y", "z"].map(|axis| t.at(axis, i)),
            u: std::array::from_fn(each(Quantity::Displacement, i)),
            stress: std::array::from_fn(each(Quantity::Stress, i)),
            von_mises: t.at(&Quantity::VonMises.name(), i),
            peeq: t.at(&Quantity::Peeq.name(), i),
            failure_indices: t.column(criteria[0]).map(|_| criteria.iter().map(|&c| (c, t.at(c, i))).collect()),
        })
        .collect()
}

use crate::bc::symmetry::Symmetry;

fn reactions(list: &[crate::analysis::Reaction], symmetry: &Symmetry) -> Vec<ForceSummary> {
    list.iter()
        .map(|r| ForceSummary {
            name: r.name.clone(),
            kind: None,
            force: r.force,
            max_penetration: None,
            normal_force: None,
            tangential_force: None,
            full_structure_force: symmetry.full(&r.name, r.force),
        })
        .collect()
}

fn contacts(list: &[crate::analysis::ContactResultant], symmetry: &Symmetry) -> Vec<ForceSummary> {
    list.iter()
        .map(|c| ForceSummary {
            name: c.name.clone(),
            kind: Some(c.kind.name()),
            force: c.force,
            max_penetration: Some(c.max_penetration),
            normal_force: Some(c.normal_force),
            tangential_force: Some(c.tangential_force),
            full_structure_force: symmetry.full(&c.name, c.force),
        })
        .collect()
}

/// The summary of step `k` of `solution`, its probes and peak peeq from
/// `at_end` (the solution as it was at the end of that step).
pub(crate) fn step_summary(
    model: &Model,
    solution: &Solution,
    k: usize,
    at_end: &Solution,
    vtu: Option<String>,
) -> StepSummary {
    let end = &solution.steps[k];
    StepSummary {
        name: end.name.clone(),
        load_factor: end.lambda,
        increment: end.increment,
        max_peeq: at_end.states.iter().map(|s| s.peeq).fold(0.0, f64::max),
        probes: probes(model, at_end),
        reactions: reactions(&end.reactions, &model.symmetry),
        contact: contacts(&end.contacts, &model.symmetry),
        vtu,
    }
}

/// Builds the summary of a solution (per-step entries from the final state
/// for the last step only; `io::write_results` fills the others).
pub fn summary(model: &Model, solution: &Solution) -> Summary {
    let probes = probes(model, solution);
    let reactions = reactions(&solution.reactions, &model.symmetry);
    let contact = contacts(&solution.contacts, &model.symmetry);
    let t = &solution.timings;
    Summary {
        title: model.title.clone(),
        dof: model.n_dofs(),
        equations: solution.equations,
        wall_time_s: solution.wall_time.as_secs_f64(),
        converged: solution.failure.is_none(),
        status: match &solution.failure {
            None => "converged",
            Some(f) if f.reason == crate::solver::stepping::StopReason::Interrupted => "interrupted",
            Some(_) => "not_converged",
        },
        load_factor: solution.lambda,
        increments: solution.increments.len(),
        newton_iterations: solution.increments.iter().map(|i| i.newton.iterations).sum(),
        cutbacks: solution.cutbacks.len(),
        rejected_increments: solution.cutbacks.iter().filter(|c| c.rejected.is_some()).count(),
        line_searches: solution.increments.iter().map(|i| i.newton.line_searches).sum(),
        plastic_points: solution.plastic_points,
        max_peeq: solution.states.iter().map(|s| s.peeq).fold(0.0, f64::max),
        failure: solution.failure.as_ref().map(|f| f.to_string()),
        probes,
        reactions,
        contact,
        levers: solution
            .levers
            .iter()
            .map(|l| LeverSummary { name: l.name.clone(), displacement: l.displacement, force: l.force })
            .collect(),
        applied_load: solution.applied,
        timings: TimingSummary {
            setup_s: t.setup.as_secs_f64(),
            assembly_s: t.assembly.as_secs_f64(),
            contact_s: t.contact.as_secs_f64(),
            factorization_s: t.solver.factorization_time.as_secs_f64(),
            solve_s: t.solver.solve_time.as_secs_f64(),
            eigen_s: t.eigen.as_secs_f64(),
            evaluations: t.evaluations,
            factorizations: t.solver.factorizations,
            reused_factorizations: t.solver.reused,
            krylov_iterations: t.solver.krylov_iterations,
            fallbacks: t.solver.fallbacks,
            error_history_s: solution.error_history.elapsed.as_secs_f64(),
            single_factorizations: t.solver.single_factorizations,
            precision_fallbacks: t.solver.precision_fallbacks,
            output_s: 0.0,
            report_s: 0.0,
        },
        memory: MemorySummary { estimated_bytes: solution.memory.total(), peak_bytes: crate::size::peak_memory() },
        warnings: model.warnings.iter().chain(&solution.warnings).map(|w| w.to_string()).collect(),
        steps: Vec::new(),
        error_estimate: estimate_summary(model, solution),
        error_history: super::error_history::rows(model, solution),
        concentrated: crate::analysis::concentrated::find(model, solution),
        ply_failure: crate::post::failure::summary(
            &solution.fields(model),
            (model.transient.is_none() && solution.damage.is_none()).then_some(solution.lambda),
        ),
        adapt: solution.adapt.as_ref().map(|a| {
            a.cycles
                .iter()
                .map(|c| {
                    // summary.json keeps a key pair per quantity
                    let of = |q: ModeQuantity| {
                        let m = c.modes.as_ref().filter(|m| m.quantity == q);
                        m.map_or((Vec::new(), Vec::new()), |m| (m.values.clone(), m.errors.clone()))
                    };
                    let (frequencies, frequency_errors) = of(ModeQuantity::Frequency);
                    let (factors, factor_errors) = of(ModeQuantity::LoadFactor);
                    CycleSummary {
                        cycle: c.cycle,
                        dof: c.dof,
                        estimate: c.estimate,
                        frequencies,
                        frequency_errors,
                        factors,
                        factor_errors,
                        state: c.state.clone(),
                        time_s: c.time_s,
                        refined: c.refined.clone(),
                    }
                })
                .collect()
        }),
        adapt_stop: solution.adapt.as_ref().map(|a| a.stop.clone()),
        adapt_cycle: solution.adapt.as_ref().and_then(|a| a.cycles.last()).map(|c| c.cycle),
        adapt_end: adapt_end(solution),
        adapt_time_s: solution.adapt.as_ref().map(|a| a.time_s()),
        buckling: buckling_summary(model, solution),
        modal: modal_summary(model, solution),
        energy: energy_at_end(solution, 1.0),
        full_structure_energy: energy_at_end(solution, model.symmetry.copies() as f64)
            .filter(|_| !model.symmetry.planes.is_empty()),
        path: solution.path.as_ref().map(|p| PathSummary {
            end: match p.end {
                Some(crate::analysis::PathEnd::LoadFactor(_)) => "load_factor",
                Some(crate::analysis::PathEnd::Displacement { .. }) => "displacement",
                None => "none",
            },
            limit_points: p.limit_points.clone(),
            first_arc_length: p.first_arc_length,
        }),
        delamination: solution.delamination.as_ref().map(|d| d.summary()),
        damage: solution.damage.as_ref().map(|d| d.summary()),
        files: Vec::new(),
    }
}

/// How an adaptive run ended (summary.json `adapt_end`): `"done"` as asked,
/// `"stopped"` or `"interrupted"` otherwise; `None` for a single run.
fn adapt_end(solution: &Solution) -> Option<&'static str> {
    solution.adapt.as_ref().map(|a| match a.end {
        // a first cycle that stopped early ended as a single run that
        // stops does (exit 2, or 130 when interrupted): not as asked
        crate::analysis::AdaptEnd::Done => match solution.failure.as_ref().map(|f| f.reason) {
            None => "done",
            Some(crate::solver::stepping::StopReason::Interrupted) => "interrupted",
            Some(_) => "stopped",
        },
        crate::analysis::AdaptEnd::Stopped => "stopped",
        crate::analysis::AdaptEnd::Interrupted => "interrupted",
    })
}

/// The last row of the energy table (`analysis::tables::energy`), its
/// energies (J) times `copies` (mirror images of a model cut by symmetry planes).
fn energy_at_end(solution: &Solution, copies: f64) -> Option<tables::Row> {
    let t = tables::energy(solution)?;
    Some(t.row_scaled(t.rows().checked_sub(1)?, |c| if c.unit == "J" { copies } else { 1.0 }))
}

/// Writes a summary as pretty JSON.
pub fn write(path: &Path, s: &Summary) -> Result<(), IoError> {
    // plain data (strings, numbers, NaN-free options): serialization cannot fail
    let text = serde_json::to_string_pretty(s).unwrap_or_default();
    std::fs::write(path, text).map_err(|e| file_error(path, e))
}
