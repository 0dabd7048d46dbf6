//! `[solver] control = "arc_length"`: the keys of path following
//! (`analysis::path`, `solver::arclength`) and what a model must be to use
//! it. Arc length scales one reference load by an unknown λ (proportional
//! loading), so a model whose loading is anything else — non-zero
//! prescribed displacements, moving or force-controlled indenters, several
//! load steps, augmented-Lagrangian contact (its multiplier updates need
//! load stepping's re-solves) — is refused by key.

use super::Probe;
use super::constraints::ConstraintHandler;
use crate::bc::{Constraint, Load};
use crate::contact::{Indenter, PairContact};
use crate::input::schema::{Control, PathConstraint, SolverFile, StepFile};
use crate::input::validate::finite_positive;
use crate::input::{DisplacementStop, ModelError, PathSettings, SolverSettings, invalid, ranges};
use crate::solver::arclength::ArcLengthSettings;

/// What the path following reads from the rest of the model.
pub(super) struct Loading<'a> {
    pub steps: &'a [StepFile],
    pub constraints: &'a [Constraint],
    pub handler: &'a ConstraintHandler,
    pub loads: &'a [Load],
    pub indenters: &'a [Indenter],
    pub contacts: &'a [PairContact],
    pub probes: &'a [Probe],
    /// The model has cohesive interfaces or ply damage, and no material
    /// yields: a structure that damages and unloads on its secant, what
    /// the dissipation constraint is made for.
    pub(super) secant_unloading: bool,
}

/// The share of the elastic energy `½ λ fᵀu` one increment must dissipate
/// before `constraint = "dissipation"` holds the increments to their
/// dissipation (smaller shares are the process zone's first points, whose
/// dissipation rate along the tangent is still round-off).
const DISSIPATION_SWITCH: f64 = 1e-3;

const ARC: &str = "solver.control = \"arc_length\"";

/// A model that damages (cohesive interfaces or ply damage) and does not
/// yield: one that unloads on its secant, as the dissipation constraint
/// assumes ([`Loading::secant_unloading`]).
pub(super) fn unloads_on_its_secant(materials: &[crate::materials::Material], cohesive: bool) -> bool {
    (cohesive || materials.iter().any(|m| m.damage.is_some())) && !materials.iter().any(|m| m.is_plastic())
}

/// `None` for load control (refusing the path-following keys there),
/// else the path settings, the model checked for proportional loading.
pub(super) fn settings(
    s: &SolverFile,
    solver: &SolverSettings,
    model: &Loading,
) -> Result<Option<PathSettings>, ModelError> {
    if s.control.unwrap_or_default() != Control::ArcLength {
        let given = [
            ("arc_length", s.arc_length.is_some()),
            ("max_load_factor", s.max_load_factor.is_some()),
            ("stop", s.stop.is_some()),
            ("constraint", s.constraint.is_some()),
            ("max_dissipation", s.max_dissipation.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|g| g.1) {
            return Err(invalid(format!("solver.{key}"), "(given)", format!("no value without {ARC}")));
        }
        return Ok(None);
    }
    let load_only = [
        ("max_increment", s.max_increment.is_some()),
        ("min_increment", s.min_increment.is_some()),
        ("cutback_factor", s.cutback_factor.is_some()),
        ("growth_factor", s.growth_factor.is_some()),
        ("easy_iterations", s.easy_iterations.is_some()),
        ("stagnation_iterations", s.stagnation_iterations.is_some()),
        ("displacement_tolerance", s.displacement_tolerance.is_some()),
        ("step_control", s.step_control.is_some()),
        ("line_search", s.line_search.is_some()),
    ];
    if let Some((key, _)) = load_only.iter().find(|g| g.1) {
        return Err(invalid(
            format!("solver.{key}"),
            "(given)",
            format!("no value with {ARC} (a load-stepping control; the arc length adapts itself)"),
        ));
    }
    if let (Some(_), Some(n)) = (s.arc_length, s.increments) {
        return Err(invalid(
            "solver.increments",
            n,
            "no value beside solver.arc_length: the first increment is either the arc length or 1/increments of the load",
        ));
    }
    proportional(model)?;
    let arc_length = s.arc_length.map(|a| finite_positive("solver.arc_length", a)).transpose()?;
    let max_load_factor = match s.max_load_factor {
        None => crate::input::defaults::MAX_LOAD_FACTOR,
        Some(m) if ranges::MAX_LOAD_FACTOR.contains(m) => m,
        Some(m) => {
            return Err(invalid("solver.max_load_factor", m, format!("a number {}", ranges::MAX_LOAD_FACTOR)));
        }
    };
    let stop = s.stop.as_ref().map(|st| stop(st, model.probes)).transpose()?;
    let dissipation = s.constraint == Some(PathConstraint::Dissipation);
    if dissipation && !model.secant_unloading {
        return Err(invalid(
            "solver.constraint",
            "\"dissipation\"",
            "\"cylinder\" in a model without cohesive interfaces or ply damage, or with plasticity: the \
             dissipation of an increment, ½ (λ fᵀΔu − Δλ fᵀu), is that of a structure that damages and \
             unloads on its secant",
        ));
    }
    let max_dissipation = match s.max_dissipation {
        Some(m) if !dissipation => {
            return Err(invalid("solver.max_dissipation", m, "no value without solver.constraint = \"dissipation\""));
        }
        Some(m) => finite_positive("solver.max_dissipation", m)?,
        None => f64::INFINITY,
    };
    let arc = ArcLengthSettings {
        initial_dlambda: solver.steps.initial,
        max_increments: solver.steps.max_increments,
        max_iterations: solver.newton.max_iterations,
        residual_tolerance: solver.newton.residual_tolerance,
        dissipation: dissipation.then_some(DISSIPATION_SWITCH),
        max_dissipation,
        ..ArcLengthSettings::default()
    };
    Ok(Some(PathSettings { arc, arc_length, max_load_factor, stop }))
}

fn stop(st: &crate::input::schema::StopFile, probes: &[Probe]) -> Result<DisplacementStop, ModelError> {
    let Some(probe) = probes.iter().position(|p| p.name == st.probe) else {
        let names: Vec<&str> = probes.iter().map(|p| p.name.as_str()).collect();
        return Err(invalid(
            "solver.stop.probe",
            format!("{:?}", st.probe),
            format!("the name of a [[probes]] entry: one of {names:?}"),
        ));
    };
    if !(st.beyond.is_finite() && st.beyond != 0.0) {
        return Err(invalid(
            "solver.stop.beyond",
            st.beyond,
            "a finite non-zero displacement in m (its sign says which way)",
        ));
    }
    Ok(DisplacementStop { probe, component: st.component.index(), beyond: st.beyond })
}

/// Refuses whatever arc length cannot scale with the load.
fn proportional(m: &Loading) -> Result<(), ModelError> {
    let why = format!("nothing with {ARC}: it scales the loads alone (proportional loading)");
    if m.steps.len() > 1 {
        return Err(invalid("steps", format!("{} steps", m.steps.len()), format!("at most one step with {ARC}")));
    }
    if m.loads.is_empty() {
        return Err(invalid("loads", "[]", format!("at least one [[loads]] entry with {ARC} (the load it scales)")));
    }
    if let Some(i) = m.handler.first_moving() {
        let v: Vec<String> =
            m.constraints[i].values.iter().map(|v| v.map_or("free".into(), |v| format!("{v}"))).collect();
        return Err(invalid(
            format!("constraints[{i}].displacement"),
            format!("[{}]", v.join(", ")),
            format!("zero values only with {ARC} (prescribe a displacement by load control, or load the point)"),
        ));
    }
    for (i, ind) in m.indenters.iter().enumerate() {
        if ind.force.is_some() {
            return Err(invalid(format!("indenters[{i}].force"), format!("{:?}", ind.force.unwrap_or_default()), &why));
        }
        if ind.displacement.iter().any(|&d| d != 0.0) {
            return Err(invalid(format!("indenters[{i}].displacement"), format!("{:?}", ind.displacement), &why));
        }
        if let Some(t) = ind.penetration_tolerance {
            return Err(invalid(format!("indenters[{i}].penetration_tolerance"), t, &why));
        }
    }
    for (i, c) in m.contacts.iter().enumerate() {
        if let Some(t) = c.penetration_tolerance {
            return Err(invalid(format!("contacts[{i}].penetration_tolerance"), t, &why));
        }
    }
    Ok(())
}
