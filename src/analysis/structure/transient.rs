//! The transient part of the structure: building its inertia contribution
//! ([`crate::dynamics::Inertia`]) and feeding the energy balance with the
//! other parts' converged forces at every commit.

use super::elements::Elements;
use super::inputs::Loading;
use super::kinematics::Kinematics;
use super::parts::Parts;
use super::system::LinearSystem;
use crate::assembly::{Assembler, Contribution};
use crate::setup::constraints::Elimination;

/// The inertia part of a transient model: the mass matrix, `K₀` if
/// stiffness-proportional damping needs it, the initial velocities on the
/// free DOFs, and the initial row of the energy balance.
pub(super) fn inertia(
    loading: &Loading<'_>,
    settings: &crate::dynamics::TransientSettings,
    assembler: &Assembler,
    elements: &Elements<'_>,
) -> Result<crate::dynamics::Inertia, crate::analysis::AnalysisError> {
    use crate::dynamics::mass;
    let d = elements.discretisation;
    let mesh = d.mesh;
    let densities = mass::densities(mesh, d.materials)?;
    let redistribution =
        (loading.has_contacts() && settings.contact_mass == crate::dynamics::ContactMass::Redistributed).then(|| {
            let nodes = crate::dynamics::redistribution::contact_nodes(mesh, loading.indenters, loading.contacts);
            crate::dynamics::Redistribution::new(mesh, &nodes)
        });
    let m = mass::assemble(assembler, mesh, d.cells, &densities, settings.mass, redistribution.as_ref())?;
    let k0 = if settings.damping.1 > 0.0 {
        assembler.elastic_matrix(&elements.inputs(&vec![0.0; mesh.n_dofs()]))
    } else {
        Vec::new()
    };
    let eq = &assembler.dofs.eq;
    let mut v0 = vec![0.0; mesh.n_dofs()];
    for &(b, v) in &settings.initial_velocities {
        let body = &mesh.bodies[b];
        for n in body.node_offset..body.node_offset + body.n_nodes() {
            for k in 0..3 {
                if eq[3 * n + k] != crate::assembly::NO_EQ {
                    v0[3 * n + k] = v[k];
                }
            }
        }
    }
    let mut inertia = crate::dynamics::Inertia::new(settings.clone(), (&assembler.pattern, m), &k0, v0);
    let impactors = loading
        .indenters
        .iter()
        .filter_map(|i| i.impactor)
        .map(|i| 0.5 * i.mass * i.velocity.iter().map(|v| v * v).sum::<f64>());
    inertia.start(eq, impactors.sum());
    Ok(inertia)
}

/// The end-of-step impulses of a transient model (`dynamics::impulse`): of
/// its contacts (`analysis.contact_forces = "implicit"`) and of its
/// cohesive interfaces (`analysis.interface_forces = "implicit"`), where it
/// has them; none in a static model.
pub(super) fn impulse(
    loading: &Loading<'_>,
    interfaces: bool,
    settings: Option<&crate::dynamics::TransientSettings>,
    n_dofs: usize,
) -> crate::dynamics::Impulses {
    use crate::dynamics::impulse::Impulse;
    let Some(settings) = settings else { return Default::default() };
    crate::dynamics::Impulses {
        contacts: (loading.has_contacts() && settings.contact_forces == crate::dynamics::ContactForces::Implicit)
            .then(|| Impulse::new(settings.recursion(), n_dofs)),
        interfaces: (interfaces && settings.interface_forces.impulse())
            .then(|| Impulse::new(settings.recursion(), n_dofs)),
    }
}

/// The converged step's work terms into the energy balance of a
/// transient analysis (none in a static one): the parts' forces (the
/// contacts' and interfaces' algorithmic force where an impulse replaces
/// theirs, and
/// `impactors`, the impactors' kinetic energy), and the reactions at
/// constrained and prescribed DOFs.
pub(super) fn account_energy(
    parts: &mut Parts<'_>,
    state: &Kinematics,
    (system, elimination): (&LinearSystem, &Elimination),
    impactors: f64,
) {
    let Parts { elements, loads, contacts, interfaces, inertia, impulse, .. } = parts;
    let Some(inertia) = inertia.as_mut() else { return };
    let du: Vec<f64> = state.u.iter().zip(&state.u_committed).map(|(a, b)| a - b).collect();
    let eq = &system.assembler.dofs.eq;
    let supports: Vec<f64> = (0..du.len())
        .map(|d| {
            let e = eq[d];
            if e == crate::assembly::NO_EQ || elimination.is_prescribed(e) { system.imbalance[d] } else { 0.0 }
        })
        .collect();
    use crate::assembly::Phase;
    let contact = impulse.force(Phase::Contact, contacts.forces().values);
    let interface = impulse.force(Phase::Interfaces, interfaces.forces().values);
    let held = crate::dynamics::energy::Held {
        elastic: elements.elastic_energy(&state.u, &system.assembler),
        interfaces: interfaces.stored_energy(&state.u),
        damage: elements.damage.released(),
        damage_scheme: elements.damage.scheme(),
    };
    inertia.account(
        (state.lambda, held, impactors),
        &du,
        [elements.forces().values, loads.forces().values, contact, &supports, interface],
        eq,
    );
}

/// The time step's error estimate relative to the displacement scale
/// (`dynamics::time_error`; 0 in a static analysis).
pub(super) fn time_error(
    parts: &Parts<'_>,
    state: &Kinematics,
    system: &LinearSystem,
    elimination: &Elimination,
) -> f64 {
    let (Some(inertia), Some(estimate)) = (&parts.inertia, &parts.time_error) else { return 0.0 };
    let eq = &system.assembler.dofs.eq;
    let free =
        |d: usize| eq[d] != crate::assembly::NO_EQ && !elimination.is_prescribed(eq[d]) && estimate.massive[eq[d]];
    estimate.measure((&state.u, &state.u_committed), &inertia.committed(), inertia.step_length(state.lambda), free)
}

/// The committed displacements into the time error's scale.
pub(super) fn commit_time_error(
    parts: &mut Parts<'_>,
    state: &Kinematics,
    system: &LinearSystem,
    elimination: &Elimination,
) {
    let Some(estimate) = parts.time_error.as_mut() else { return };
    let eq = &system.assembler.dofs.eq;
    estimate.commit(&state.u, |d| eq[d] != crate::assembly::NO_EQ && !elimination.is_prescribed(eq[d]));
}

/// The first λ after `lambda` at an output time of the frames
/// (`analysis.output_interval`) inside the present load step; `None`
/// without frames, or when the step ends first.
pub(super) fn next_output(parts: &Parts<'_>, lambda: f64) -> Option<f64> {
    let settings = parts.inertia.as_ref()?.settings();
    let interval = settings.output_interval?;
    let n = settings.durations.len();
    let k = (lambda.max(0.0).floor() as usize).min(n - 1);
    let start = settings.time(k as f64);
    let t = settings.time(lambda);
    // the next multiple of the interval past t (a time reached to
    // round-off counts as reached)
    let next = ((t / interval) * (1.0 + 1e-9)).floor() + 1.0;
    let at = k as f64 + (next * interval - start) / settings.durations[k];
    (at < (k + 1) as f64).then_some(at)
}
