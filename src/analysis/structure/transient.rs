//! The transient part of the structure: building its inertia contribution
//! ([`crate::dynamics::Inertia`]) and feeding the energy balance with the
//! other parts' converged forces at every commit.

use super::elements::Elements;
use super::kinematics::Kinematics;
use super::system::LinearSystem;
use crate::assembly::{Assembler, Contribution};
use crate::setup::Model;
use crate::setup::constraints::Elimination;

/// The inertia part of a transient model: the mass matrix, `K₀` if
/// stiffness-proportional damping needs it, the initial velocities on the
/// free DOFs, and the initial row of the energy balance.
pub(super) fn inertia(
    model: &Model,
    settings: &crate::dynamics::TransientSettings,
    assembler: &Assembler,
    elements: &Elements<'_>,
) -> Result<crate::dynamics::Inertia, crate::analysis::AnalysisError> {
    use crate::dynamics::mass;
    let mesh = &model.mesh;
    let densities = mass::densities(mesh, &model.materials)?;
    let contacts = !model.indenters.is_empty() || !model.contacts.is_empty();
    let redistribution =
        (contacts && settings.contact_mass == crate::dynamics::ContactMass::Redistributed).then(|| {
            let nodes = crate::dynamics::redistribution::contact_nodes(mesh, &model.indenters, &model.contacts);
            crate::dynamics::Redistribution::new(mesh, &nodes)
        });
    let m = mass::assemble(assembler, mesh, &model.cells, &densities, settings.mass, redistribution.as_ref())?;
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
    let mut inertia = crate::dynamics::Inertia::new(settings.clone(), m, &k0, v0, assembler.dofs.n_eq);
    let impactors = model
        .indenters
        .iter()
        .filter_map(|i| i.impactor)
        .map(|i| 0.5 * i.mass * i.velocity.iter().map(|v| v * v).sum::<f64>());
    inertia.start(eq, &assembler.pattern, impactors.sum());
    Ok(inertia)
}

/// The contacts' end-of-step impulse of a transient model with contacts
/// (`analysis.contact_forces = "implicit"`, `dynamics::impulse`).
pub(super) fn impulse(model: &Model) -> Option<crate::dynamics::ContactImpulse> {
    let settings = model.transient.as_ref()?;
    let contacts = !model.indenters.is_empty() || !model.contacts.is_empty();
    (contacts && settings.contact_forces == crate::dynamics::ContactForces::Implicit)
        .then(|| crate::dynamics::ContactImpulse::new(settings.gamma, model.mesh.n_dofs()))
}

/// The converged step's work terms into the energy balance: the parts'
/// forces, and the reactions at constrained and prescribed DOFs.
pub(super) fn account_energy(
    inertia: &mut crate::dynamics::Inertia,
    (model, solid): (&Model, &Elements<'_>),
    state: &Kinematics,
    (system, dirichlet): (&LinearSystem, &Elimination),
    parts: [&dyn Contribution; 3],
    (contact, impactors): (Option<&[f64]>, f64),
) {
    let du: Vec<f64> = state.u.iter().zip(&state.u_committed).map(|(a, b)| a - b).collect();
    let eq = &system.assembler.dofs.eq;
    let supports: Vec<f64> = (0..du.len())
        .map(|d| {
            let e = eq[d];
            if e == crate::assembly::NO_EQ || dirichlet.is_prescribed(e) { system.imbalance[d] } else { 0.0 }
        })
        .collect();
    let [elements, loads, contacts] = parts.map(|p| p.forces().values);
    // the contacts' algorithmic force where it replaces theirs
    let contacts = contact.unwrap_or(contacts);
    let elastic = crate::post::estimate::elastic_energy(
        &model.mesh,
        &model.cells,
        &model.materials,
        &solid.stress,
        &solid.gp_offsets,
    );
    inertia.account(
        (state.lambda, elastic, impactors),
        &du,
        [elements, loads, contacts, &supports],
        eq,
        &system.assembler.pattern,
    );
}
