//! Warnings that only the results can give: an indenter or a contact that
//! never touched, a penalty too soft to hold its contact, an augmented
//! contact left above its tolerance, non-finite forces, a probe in a part
//! the load does not reach, plastic strains beyond what the Green–Lagrange
//! strain measure models, contacts that created energy in a transient run,
//! contacts whose force a transient run's time steps do not resolve.

use super::Solution;
use crate::setup::{Model, Warning};

/// True if the indenter or contact `name` carried a force in some increment
/// (or if no increment converged: nothing to judge).
fn touched(solution: &Solution, name: &str) -> bool {
    solution.history.is_empty()
        || solution
            .history
            .iter()
            .flat_map(|r| r.contact(name))
            .chain(solution.contact(name))
            .any(|c| c.force != [0.0; 3])
}

/// Warnings that only the results can give: an indenter that never touched
/// its body, a probe where the model shows neither stress nor displacement
/// (below 1e-6 of the largest anywhere: a part the load does not reach).
pub(super) fn result_warnings(model: &Model, solution: &Solution) -> Vec<Warning> {
    let mut warnings = Vec::new();
    for (k, ind) in model.indenters.iter().enumerate() {
        if !touched(solution, &ind.name) {
            warnings.push(Warning {
                key: format!("indenters[{k}]"),
                message: format!(
                    "indenter {:?} never touched body {:?}: its contact force stayed zero throughout",
                    ind.name, model.mesh.bodies[ind.body].name
                ),
            });
        }
    }
    contact_warnings(model, solution, &mut warnings);
    if let Some(reduced) = solution.damage.as_ref().map(|d| d.summary().strength_reduced_points).filter(|&n| n > 0) {
        warnings.push(Warning {
            key: "materials.damage".into(),
            message: format!(
                "{reduced} Gauss points had a crack band longer than 2 E G/X² for a damaging mode: their onset \
                 stress was lowered to keep the mode's fracture energy (summary.json damage.strength_reduced_points; \
                 refine the mesh across the crack to keep the strength)"
            ),
        });
    }
    if let Some(w) = solution.damage.as_ref().and_then(|d| unbooked_dissipation(&d.summary(), model)) {
        warnings.push(w);
    }
    viscous_delamination(model, solution, &mut warnings);
    // augmented contacts left above their tolerance (MAX_AUGMENTATIONS reached)
    let tolerances = model
        .indenters
        .iter()
        .map(|i| (&i.name, i.penetration_tolerance, "indenters"))
        .chain(model.contacts.iter().map(|c| (&c.name, c.penetration_tolerance, "contacts")));
    for (k, (name, tol, group)) in tolerances.enumerate() {
        let (Some(tol), Some(c)) = (tol, solution.contacts.get(k)) else { continue };
        if c.max_penetration > tol {
            let index = if group == "indenters" { k } else { k - model.indenters.len() };
            warnings.push(Warning {
                key: format!("{group}[{index}].penetration_tolerance"),
                message: format!(
                    "contact {name:?} ends with a penetration of {:.3e} m, above its tolerance {tol:.3e} m after {} \
                     augmentations: raise the penalty or refine the increments",
                    c.max_penetration,
                    crate::solver::stepping::MAX_AUGMENTATIONS
                ),
            });
        }
    }
    strain_measure_warning(model, solution, &mut warnings);
    super::checks::check(model, solution, &mut warnings);
    contact_energy_warning(model, solution, &mut warnings);
    contact_resolution_warning(model, solution, &mut warnings);
    let finite = |f: &[f64; 3]| f.iter().all(|v| v.is_finite());
    if !(solution.reactions.iter().all(|r| finite(&r.force)) && solution.contacts.iter().all(|c| finite(&c.force))) {
        warnings.push(Warning {
            key: "materials".into(),
            message: "the final state has non-finite reactions or contact forces: a material law or load produces \
                      NaN there"
                .into(),
        });
    }
    let view = solution.fields(model);
    let max_vm = solution.stresses.iter().map(crate::voigt::von_mises).fold(0.0, f64::max);
    let max_u = solution.u.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    if max_vm > 0.0 || max_u > 0.0 {
        for (i, p) in model.probes.iter().enumerate() {
            let Some(v) = view.sample_probe(p) else { continue };
            let u = v.u.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            if v.von_mises <= 1e-6 * max_vm && u <= 1e-6 * max_u {
                warnings.push(Warning {
                    key: format!("probes[{i}]"),
                    message: format!(
                        "probe {:?} shows neither stress nor displacement (below 1e-6 of the largest in the model): \
                         it may lie in a part the load does not reach",
                        p.name
                    ),
                });
            }
        }
    }
    warnings
}

/// Fraction of the motion at the contact that the penetration may reach
/// before the penalty is called too soft: with the default penalty factor
/// the shipped examples stay below 1e-3 of it.
const SOFT_PENALTY: f64 = 0.1;

/// How far the ply damage's dissipation by the law's sums may exceed its
/// release at fixed strain before a run warns: the two agree within a few
/// percent where the increments follow the damage (the notched strips
/// `1.01`, asserted in crates/cufem-cli/tests/ply_damage.rs; the damaging
/// drop weight `1.05`, measured once: `cufem run
/// examples/laminate_drop_weight_damage.toml`, summary.json `damage`).
pub(crate) const DISSIPATION_OVER_RELEASE: f64 = 1.25;

/// A warning when the damage's `dissipated_j` (the law's sums of `Y Δd`
/// along each update's straight strain path) exceeds its `released_j` (at
/// fixed strain, a lower bound) by more than [`DISSIPATION_OVER_RELEASE`]:
/// a damaged point's strain jumped within an increment (a ply crushed
/// under an indenter), so the increments do not follow the damage and
/// both figures rest on a path the points need not have taken (a new
/// user's three-point bend: `0.253` J summed, `0.103` J released, of
/// `0.412` J of work; crates/cufem-cli/tests/ply_damage.rs). The remedy
/// named is the model's own control's: load stepping's damage step
/// control, or path following's bound on an increment's dissipation or
/// its arc length (crates/cufem-cli/tests/snap_back.rs).
fn unbooked_dissipation(d: &crate::damage::DamageSummary, model: &Model) -> Option<Warning> {
    let (sums, released) = (d.dissipated_total_j, d.released_total_j);
    let remedy = match &model.solver.path {
        None => "solver.step_control = { damage = 0.1 }",
        Some(p) if p.arc.dissipation.is_some() => "solver.max_dissipation, e.g. a thousandth of the energy to break",
        Some(_) => "a shorter solver.arc_length",
    };
    (sums > DISSIPATION_OVER_RELEASE * released && sums > 0.0).then(|| Warning {
        key: "materials.damage".into(),
        message: format!(
            "the damage's dissipation summed by its law, {sums:.4e} J (summary.json damage.dissipated_j), is {:.1} \
             times the energy it released at fixed strain, {released:.4e} J (damage.released_j, a lower bound): \
             the strain of damaged points jumped within increments, and both rest on each increment's straight \
             strain path, which the points need not have taken; make the increments follow the damage \
             ({remedy})",
            sums / released.max(f64::MIN_POSITIVE)
        ),
    })
}

/// Largest share of an interface's dissipation that its Duvaut–Lions
/// over-stress may do before the run says so: the shipped double
/// cantilever beam's `0.5 %`, the mixed-mode bend's `1.3 %`; the drop
/// weights' `12 %` and `27 %` are told.
pub(crate) const VISCOUS_SHARE: f64 = 0.1;

/// A warning for each cohesive law whose interfaces' viscous over-stress
/// (summary.json `delamination.viscous_j`) did more than
/// [`VISCOUS_SHARE`] of their dissipation: the answer then depends on the
/// viscosity, which the user chose to pass the softening, not on the
/// toughness alone (a new-user review: `29 %` of a drop weight's
/// delamination energy, unwarned).
fn viscous_delamination(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let Some(d) = &solution.delamination else { return };
    let mut laws: Vec<(&str, f64, f64, f64)> = Vec::new();
    for (interface, s) in model.interfaces.iter().zip(&d.interfaces) {
        match laws.iter_mut().find(|l| l.0 == interface.law_key) {
            Some(l) => (l.1, l.2) = (l.1 + s.dissipated_j, l.2 + s.viscous_j),
            None => laws.push((&interface.law_key, s.dissipated_j, s.viscous_j, interface.law.viscosity)),
        }
    }
    for (key, law, viscous, viscosity) in laws {
        let share = viscous / (law + viscous);
        if share > VISCOUS_SHARE {
            warnings.push(Warning {
                key: format!("{key}.viscosity"),
                message: format!(
                    "the viscous over-stress of viscosity = {viscosity:e} did {:.0} % of its interfaces' \
                     dissipation ({viscous:.4e} J beside the law's {law:.4e} J; summary.json \
                     delamination.viscous_j): the energy absorbed depends on the viscosity as much as on the \
                     toughness; a smaller one (with shorter increments or time steps) brings it nearer the law's",
                    100.0 * share
                ),
            });
        }
    }
}

/// Pair contacts that never closed (as `result_warnings` says of
/// indenters), and contacts whose penetration is a large part of the motion
/// that closed them — the indenter's travel, or the largest displacement of
/// a pair's slave nodes: a penalty so soft that the contact hardly holds.
fn contact_warnings(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let n_ind = model.indenters.len();
    for (k, c) in model.contacts.iter().enumerate() {
        if touched(solution, &c.name) {
            continue;
        }
        let gap = solution
            .contact_points(&c.name)
            .into_iter()
            .flatten()
            .map(|p| p.gap)
            .filter(|g| g.is_finite())
            .fold(f64::INFINITY, f64::min);
        warnings.push(Warning {
            key: format!("contacts[{k}]"),
            message: format!(
                "contact {:?} between bodies {:?} and {:?} never closed: no point touched in any increment (smallest \
                 gap at the end {} m); check the bodies' positions and the `where` selections",
                c.name,
                model.mesh.bodies[c.master.body].name,
                model.mesh.bodies[c.slave.body].name,
                crate::numbers::limit(gap)
            ),
        });
    }
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    for (k, r) in solution.contacts.iter().enumerate() {
        let motion = if k < n_ind {
            norm(r.displacement)
        } else {
            let points = solution.contact_points(&r.name).unwrap_or_default();
            points.iter().map(|p| norm(std::array::from_fn(|i| solution.u[3 * p.node + i]))).fold(0.0, f64::max)
        };
        if motion > 0.0 && r.max_penetration > SOFT_PENALTY * motion {
            let key = if k < n_ind { format!("indenters[{k}]") } else { format!("contacts[{}]", k - n_ind) };
            let what = if k < n_ind { "the indenter's travel" } else { "the largest displacement of its slave nodes" };
            // an indenter driven into held nodes (a roller turned onto a
            // clamp) penetrates whatever its penalty: no penalty moves them
            let points = solution.contact_points(&r.name).unwrap_or_default();
            let deepest = points.iter().filter(|p| p.gap.is_finite()).min_by(|a, b| a.gap.total_cmp(&b.gap));
            if let Some(p) = deepest
                && (0..3).all(|i| model.constraint_handler.prescribed(3 * p.node + i).is_some())
            {
                warnings.push(Warning {
                    key,
                    message: format!(
                        "contact {:?} ends with a penetration of {} m, {:.0} % of {what}, deepest at node {} {:?}, \
                         which the constraints hold in x, y and z: it presses on supported nodes, which no penalty \
                         moves; check its position, axis and surface",
                        r.name,
                        crate::numbers::limit(r.max_penetration),
                        100.0 * r.max_penetration / motion,
                        p.node,
                        model.mesh.coords(p.node)
                    ),
                });
                continue;
            }
            warnings.push(Warning {
                key: format!("{key}.penalty_factor"),
                message: format!(
                    "contact {:?} ends with a penetration of {} m, {:.0} % of {what} ({} m): its penalty is too soft \
                     to hold the contact; raise `penalty_factor` (or `penalty`), or set `penetration_tolerance`",
                    r.name,
                    crate::numbers::limit(r.max_penetration),
                    100.0 * r.max_penetration / motion,
                    crate::numbers::limit(motion)
                ),
            });
        }
    }
}

/// Largest equivalent plastic strain that J2 plasticity on the
/// Green–Lagrange strain is trusted with. Beyond it the model departs from
/// finite-strain plasticity: in uniaxial tension its Cauchy stress is 22 %
/// off the hardening curve at 10 % strain (crates/cufem-cli/tests/large_deformation.rs), and
/// the paper's tube in three-point bending (8.5 % plastic strain under the
/// roller) carries a roller force 2.5 % below the logarithmic strain's.
pub(crate) const GREEN_LAGRANGE_PLASTIC_LIMIT: f64 = 0.02;

/// With nonlinear geometry and the Green–Lagrange strain, a plastic strain
/// beyond [`GREEN_LAGRANGE_PLASTIC_LIMIT`] is reported on `analysis.strain`.
fn strain_measure_warning(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    if model.kinematics != crate::kinematics::Kinematics::TotalLagrangian {
        return;
    }
    let peeq = solution.states.iter().map(|s| s.peeq).fold(0.0, f64::max);
    if peeq > GREEN_LAGRANGE_PLASTIC_LIMIT {
        warnings.push(Warning {
            key: "analysis.strain".into(),
            message: format!(
                "the equivalent plastic strain reaches {:.1} % with the Green–Lagrange strain, whose J2 plasticity \
                 departs from finite-strain plasticity beyond {:.0} % (in uniaxial tension its stress is 22 % off \
                 the hardening curve at 10 % strain): set analysis.strain = \"logarithmic\"",
                100.0 * peeq,
                100.0 * GREEN_LAGRANGE_PLASTIC_LIMIT
            ),
        });
    }
}

/// A transient run whose contacts did net work on the bodies: a
/// frictionless penalty contact is a conservative spring, so once its
/// points have separated again its work is zero; what remains is energy the
/// time integration made at the contact (a penalty too stiff for the time
/// step: the contact spring's period is not resolved, the points chatter,
/// and the trapezoidal rule's end-point forces do spurious work). Warned
/// when, with no contact force left at the end, the contact work exceeds
/// 1 % of the largest energy of the run, in a model whose indenters stand
/// still (the only conservative ones).
fn contact_energy_warning(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    let Some(rows) = &solution.energy else { return };
    // only fixed rigid indenters are conservative: an impactor or a moving
    // or force-driven indenter does work on the bodies by right
    let fixed = model.indenters.iter().all(|i| i.impactor.is_none() && i.force.is_none() && i.displacement == [0.0; 3]);
    if !fixed {
        return;
    }
    let Some(last) = rows.last() else { return };
    let open = solution.contacts.iter().all(|c| c.force == [0.0; 3]);
    let scale = rows.iter().map(|r| r.kinetic.max(r.internal.abs()).max(r.external.abs())).fold(0.0, f64::max);
    if open && scale > 0.0 && last.contact.abs() > 0.01 * scale {
        warnings.push(Warning {
            key: "analysis.type".into(),
            message: format!(
                "the contacts did {:.3e} J of net work ({:.1} % of the largest energy, {:.3e} J) although they \
                 are open at the end: the time integration created or lost energy at the contact — lower the \
                 contacts' penalty_factor (about 1 resolves the contact oscillation with the time step) or \
                 take smaller increments (energy.csv)",
                last.contact,
                100.0 * last.contact.abs() / scale,
                scale
            ),
        });
    }
}

/// Fewest time steps in which a contact of a transient run carries force
/// for its force history to be sampled at all: the rod of
/// examples/rod_impact.toml, in contact for 398 µs, has 2 such steps of
/// 200 µs and 7 of 60 µs (its 600 steps of 1 µs: 398).
const RESOLVED_CONTACT_STEPS: usize = 5;

/// A transient run whose time steps are too long for a contact that
/// closed: it carried force in fewer than [`RESOLVED_CONTACT_STEPS`] steps
/// (one time step of 0.6 ms over the rod's whole impact ended mid-contact
/// without a word; a new-user review).
fn contact_resolution_warning(model: &Model, solution: &Solution, warnings: &mut Vec<Warning>) {
    if model.transient.is_none() {
        return;
    }
    let n_ind = model.indenters.len();
    let names = model.indenters.iter().map(|i| &i.name).chain(model.contacts.iter().map(|c| &c.name));
    for (k, name) in names.enumerate() {
        let active = solution.history.iter().filter(|r| r.contact(name).is_some_and(|c| c.force != [0.0; 3])).count();
        if active == 0 || active >= RESOLVED_CONTACT_STEPS {
            continue;
        }
        let key = if k < n_ind { format!("indenters[{k}]") } else { format!("contacts[{}]", k - n_ind) };
        let open = solution.contact(name).is_none_or(|c| c.force == [0.0; 3]);
        warnings.push(Warning {
            key,
            message: format!(
                "contact {name:?} carried force in only {active} of the run's {} time steps{}: its force history \
                 is not resolved in time (an impact wants tens of steps while it lasts); take more increments \
                 (steps[].increments) or let the error choose them (solver.step_control.time_error)",
                solution.history.len(),
                if open { "" } else { ", and is still closed at the end" }
            ),
        });
    }
}
