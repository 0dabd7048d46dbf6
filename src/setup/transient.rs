//! `analysis.type = "transient"`: the keys of implicit dynamics — the time
//! of a load step, Newmark's parameters, Rayleigh damping, the mass matrix
//! and initial velocities — checked here (`crate::dynamics::inertia` uses
//! them).

use super::analysis::{Parts, densities_given, mass_kind};
use crate::dynamics::TransientSettings;
use crate::input::schema::{AnalysisFile, AnalysisType};
use crate::input::{ModelError, bounds, invalid, ranges};

pub(crate) use crate::input::ranges::MAX_SPEED;
/// Largest accepted Newmark β: above ¼ (γ + ½)² = 0.5625 of the most
/// dissipative γ = 1, so every γ in [½, 1] has its unconditionally stable
/// range (a larger β only lengthens the periods).
pub(crate) const MAX_BETA: f64 = 1.0;

/// `analysis.newmark`: `(β, γ, α)`. Bossak's α (default 0) sets the
/// defaults of the others, `γ = ½ − α` and `β = ¼ (1 − α)²`: second order
/// and unconditionally stable, damping the highest frequencies for α < 0
/// (Wood, Bossak & Zienkiewicz, IJNME 15, 1980); with α = 0 the
/// trapezoidal rule.
fn newmark(file: &AnalysisFile) -> Result<(f64, f64, f64), ModelError> {
    let n = file.newmark.as_ref();
    let alpha = n.and_then(|n| n.alpha).unwrap_or(crate::input::defaults::BOSSAK_ALPHA);
    ranges::BOSSAK_ALPHA.check("analysis.newmark.alpha", alpha, "Bossak's α, from -1/3 to 0 (0: Newmark's method)")?;
    let gamma = n.and_then(|n| n.gamma).unwrap_or(0.5 - alpha);
    let beta = n.and_then(|n| n.beta).unwrap_or(0.25 * (1.0 - alpha).powi(2));
    Ok((beta, gamma, alpha))
}

/// The keys that only a transient analysis takes, for the refusal of a
/// static one.
fn transient_key(file: &AnalysisFile) -> Option<(&'static str, String)> {
    use crate::numbers::number;
    // a word as the model file spells it: "newmark"
    fn word<T: serde::Serialize>(v: &T) -> String {
        serde_json::to_string(v).unwrap_or_default()
    }
    let table = || "a table".to_string();
    if let Some(d) = file.duration {
        Some(("analysis.duration", number(d)))
    } else if file.newmark.is_some() {
        Some(("analysis.newmark", table()))
    } else if file.damping.is_some() {
        Some(("analysis.damping", table()))
    } else if file.initial_velocities.is_some() {
        Some(("analysis.initial_velocities", "a list".into()))
    } else if let Some(d) = file.output_interval {
        Some(("analysis.output_interval", number(d)))
    } else if let Some(v) = &file.contact_forces {
        Some(("analysis.contact_forces", word(v)))
    } else if let Some(v) = &file.contact_mass {
        Some(("analysis.contact_mass", word(v)))
    } else if let Some(v) = &file.interface_forces {
        Some(("analysis.interface_forces", word(v)))
    } else {
        file.ply_damage_forces.as_ref().map(|v| ("analysis.ply_damage_forces", word(v)))
    }
}

/// `analysis.type = "transient"` and its keys; `None` for another analysis
/// (whose file may not hold them). Its load steps' increment limits follow
/// their time steps ([`time_steps`]), and the contacts' mass is checked
/// ([`contact_mass_warnings`]).
pub(super) fn transient(
    file: &crate::input::schema::ModelFile,
    steps: &mut [super::steps::Step],
    parts: &Parts<'_>,
    arc_length: bool,
    warnings: &mut Vec<super::Warning>,
) -> Result<Option<TransientSettings>, ModelError> {
    let settings = settings(&file.analysis, &file.steps, parts, arc_length)?;
    if let Some(e) = file.solver.step_control.and_then(|c| c.time_error).filter(|_| settings.is_none()) {
        return Err(invalid(
            "solver.step_control.time_error",
            crate::numbers::number(e),
            "only with analysis.type = \"transient\" (it bounds the error of a time step)",
        ));
    }
    if let Some(t) = &settings {
        time_steps(steps, file.solver.max_increments)?;
        contact_mass_warnings(&file.analysis, t, parts, warnings);
        // each step's own duration wins: the analysis' one is then unused
        if let Some(d) = file.analysis.duration
            && !file.steps.is_empty()
            && file.steps.iter().all(|s| s.duration.is_some())
        {
            warnings.push(super::Warning {
                key: "analysis.duration".into(),
                message: format!(
                    "duration = {d} s is not used: every [[steps]] entry gives its own duration (the analysis' one \
                     stands for the steps without)"
                ),
            });
        }
    }
    Ok(settings)
}

/// Another analysis than a transient one: its keys refused, with their values.
fn not_transient(file: &AnalysisFile, steps: &[crate::input::schema::StepFile]) -> Result<(), ModelError> {
    if let Some((i, d)) = steps.iter().enumerate().find_map(|(i, s)| s.duration.map(|d| (i, d))) {
        return Err(invalid(
            format!("steps[{i}].duration"),
            crate::numbers::number(d),
            "only with analysis.type = \"transient\"",
        ));
    }
    match transient_key(file) {
        Some((key, value)) => Err(invalid(key, value, "only with analysis.type = \"transient\"")),
        None => Ok(()),
    }
}

/// The transient settings of `[analysis]` (module docs).
fn settings(
    file: &AnalysisFile,
    steps: &[crate::input::schema::StepFile],
    parts: &Parts<'_>,
    arc_length: bool,
) -> Result<Option<TransientSettings>, ModelError> {
    if file.kind != Some(AnalysisType::Transient) {
        return not_transient(file, steps).map(|()| None);
    }
    let duration = |key: &str, d: Option<f64>| -> Result<f64, ModelError> {
        let d = d.ok_or_else(|| {
            invalid(
                "analysis.duration",
                "(missing)",
                format!("the time of one load step in s with analysis.type = \"transient\" ({key} gives none)"),
            )
        })?;
        ranges::DURATION.check(key, d, "the time of a load step in s, positive")
    };
    let base = file.duration.map(|d| duration("analysis.duration", Some(d))).transpose()?;
    let durations = if steps.is_empty() {
        vec![duration("analysis.duration", base)?]
    } else {
        steps
            .iter()
            .enumerate()
            .map(|(i, s)| duration(&format!("steps[{i}].duration"), s.duration.or(base)))
            .collect::<Result<Vec<f64>, ModelError>>()?
    };
    let (beta, gamma, alpha) = newmark(file)?;
    // unconditional stability of the implicit Newmark family on linear
    // problems: γ ≥ ½ and β ≥ ¼ (γ + ½)² (Hughes, *The Finite Element
    // Method*, §9.1.2); γ > ½ damps the highest modes
    if !ranges::NEWMARK_GAMMA.contains(gamma) {
        return Err(invalid(
            "analysis.newmark.gamma",
            bounds::number(gamma),
            format!("a number {} (γ ≥ ½ for stability)", ranges::NEWMARK_GAMMA),
        ));
    }
    let min_beta = 0.25 * (gamma + 0.5).powi(2);
    if !(beta.is_finite() && beta >= min_beta - 1e-12 && beta <= MAX_BETA) {
        return Err(invalid(
            "analysis.newmark.beta",
            bounds::number(beta),
            format!(
                "with analysis.newmark.gamma = {}, a number from ¼ (γ + ½)² = {} (unconditional stability; an \
                 explicit β is not supported) to {MAX_BETA}",
                bounds::number(gamma),
                bounds::number(min_beta)
            ),
        ));
    }
    let damping = file.damping.as_ref().map_or(Ok::<_, ModelError>((0.0, 0.0)), |d| {
        let a = d.mass.unwrap_or(0.0);
        let b = d.stiffness.unwrap_or(0.0);
        ranges::DAMPING_MASS.check("analysis.damping.mass", a, "α_M in 1/s, ≥ 0")?;
        ranges::DAMPING_STIFFNESS.check("analysis.damping.stiffness", b, "β_K in s, ≥ 0")?;
        Ok((a, b))
    })?;
    if arc_length {
        return Err(invalid(
            "solver.control",
            "\"arc_length\"",
            "load control with analysis.type = \"transient\" (time cannot run backwards)",
        ));
    }
    densities_given(parts, "transient")?;
    let initial_velocities = initial_velocities(file, parts)?;
    let total: f64 = durations.iter().sum();
    let output_interval = file
        .output_interval
        .map(|dt| {
            bounds::within(
                "analysis.output_interval",
                dt,
                total * 1e-6,
                total,
                &format!(
                    "the time between frames in s, at most the analysis's {} s and a millionth of it at least",
                    bounds::number(total)
                ),
            )
        })
        .transpose()?;
    Ok(Some(TransientSettings {
        durations,
        beta,
        gamma,
        alpha,
        damping,
        mass: mass_kind(file),
        initial_velocities,
        output_interval,
        contact_forces: match file.contact_forces.unwrap_or_default() {
            crate::input::schema::ContactForcesFile::Newmark => crate::dynamics::ContactForces::Newmark,
            crate::input::schema::ContactForcesFile::Implicit => crate::dynamics::ContactForces::Implicit,
        },
        contact_mass: match file.contact_mass.unwrap_or_default() {
            crate::input::schema::ContactMassFile::Kept => crate::dynamics::ContactMass::Kept,
            crate::input::schema::ContactMassFile::Redistributed => crate::dynamics::ContactMass::Redistributed,
        },
        interface_forces: match file.interface_forces.unwrap_or_default() {
            crate::input::schema::InterfaceForcesFile::Newmark => crate::dynamics::InterfaceForces::Newmark,
            crate::input::schema::InterfaceForcesFile::Implicit => crate::dynamics::InterfaceForces::Implicit,
            crate::input::schema::InterfaceForcesFile::DiscreteGradient => {
                crate::dynamics::InterfaceForces::DiscreteGradient
            }
        },
        ply_damage_forces: ply_damage_forces(file.ply_damage_forces.unwrap_or_default()),
    }))
}

/// `analysis.ply_damage_forces` as the dynamics take it.
fn ply_damage_forces(file: crate::input::schema::PlyDamageForcesFile) -> crate::dynamics::PlyDamageForces {
    match file {
        crate::input::schema::PlyDamageForcesFile::Newmark => crate::dynamics::PlyDamageForces::Newmark,
        crate::input::schema::PlyDamageForcesFile::Implicit => crate::dynamics::PlyDamageForces::Implicit,
    }
}

/// Increments a transient step may take beyond its time steps when none is
/// given (`solver.max_increments`): room for cutbacks, the default limit of
/// a static run.
pub(crate) const CUTBACK_ALLOWANCE: usize = 1000;

/// The time steps of a transient analysis against `solver.max_increments`
/// (`given`, the limit of each load step): refused by key if the limit is
/// below a step's time steps (the run would stop part way); without the
/// key, each step may take its time steps and [`CUTBACK_ALLOWANCE`] more.
fn time_steps(steps: &mut [super::steps::Step], given: Option<usize>) -> Result<(), ModelError> {
    for (k, step) in steps.iter_mut().enumerate() {
        let needed = step.planned_increments();
        match given {
            Some(limit) if limit < needed => {
                return Err(invalid(
                    "solver.max_increments",
                    limit,
                    format!(
                        "at least the {needed} time steps of steps[{k}] (\"{}\"; the limit applies to each load \
                         step, and cutbacks need more), or no key: each step's time steps and {CUTBACK_ALLOWANCE} more",
                        step.name
                    ),
                ));
            }
            Some(_) => {}
            None => {
                step.settings.max_increments =
                    step.settings.max_increments.max(needed.saturating_add(CUTBACK_ALLOWANCE));
            }
        }
    }
    Ok(())
}

/// Warnings of the contacts' mass (`analysis.contact_mass`): the key given
/// without contacts, and contact nodes that keep mass because every node of
/// an element is on a contact surface (`dynamics::redistribution`).
fn contact_mass_warnings(
    file: &AnalysisFile,
    settings: &TransientSettings,
    parts: &Parts<'_>,
    warnings: &mut Vec<super::Warning>,
) {
    let contacts = !parts.indenters.is_empty() || !parts.contacts.is_empty();
    if !contacts {
        if file.contact_mass.is_some() {
            warnings.push(super::Warning {
                key: "analysis.contact_mass".into(),
                message: "the model has no indenters or contacts: every node keeps its mass".into(),
            });
        }
        return;
    }
    if settings.contact_mass != crate::dynamics::ContactMass::Redistributed {
        return;
    }
    let nodes = crate::dynamics::redistribution::contact_nodes(parts.mesh, parts.indenters, parts.contacts);
    let stranded = crate::dynamics::Redistribution::new(parts.mesh, &nodes).stranded().len();
    if stranded > 0 {
        warnings.push(super::Warning {
            key: "analysis.contact_mass".into(),
            message: format!(
                "\"redistributed\": {stranded} of the {} contact nodes keep part of their mass (every node of an \
                 element of theirs is on a contact surface, so the element has no other node to take it): the \
                 contact force may chatter there; refine the mesh under the contact surfaces",
                nodes.len()
            ),
        });
    }
}

/// `analysis.initial_velocities`: one entry per body, each speed bounded.
fn initial_velocities(file: &AnalysisFile, parts: &Parts<'_>) -> Result<Vec<(usize, [f64; 3])>, ModelError> {
    let mut initial_velocities: Vec<(usize, [f64; 3])> = Vec::new();
    for (i, v) in file.initial_velocities.iter().flatten().enumerate() {
        let key = format!("analysis.initial_velocities[{i}]");
        let body = parts.mesh.body_index(&v.body).ok_or_else(|| {
            let names: Vec<&str> = parts.mesh.bodies.iter().map(|b| b.name.as_str()).collect();
            invalid(format!("{key}.body"), format!("{:?}", v.body), format!("one of the bodies {names:?}"))
        })?;
        // one velocity per body: a second entry would silently replace the first
        if let Some(j) = initial_velocities.iter().position(|&(b, _)| b == body) {
            return Err(invalid(
                format!("{key}.body"),
                format!("{:?}", v.body),
                format!(
                    "a body without an earlier entry (analysis.initial_velocities[{j}] already gives body {:?} its \
                     velocity; one entry per body, its velocity the whole body's)",
                    v.body
                ),
            ));
        }
        for (k, c) in v.velocity.iter().enumerate() {
            ranges::SPEED.check(&format!("{key}.velocity[{k}]"), *c, "a speed in m/s")?;
        }
        initial_velocities.push((body, *v.velocity));
    }
    Ok(initial_velocities)
}
