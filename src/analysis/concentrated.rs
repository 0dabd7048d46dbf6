//! Forces that act on points or lines, where the stresses do not converge.
//!
//! A force spread over a surface leaves a bounded stress under it; one
//! carried by a point or a line of nodes does not: in the continuum a line
//! load makes a stress field that grows like `1/r` towards the line
//! (Flamant), a point load like `1/r²` (Boussinesq). Refining the mesh there
//! raises the computed stresses without end, while the forces, the
//! displacements and the stresses a few elements away converge. The
//! node-to-node contact of a roller, a `force_per_node` load on a few nodes
//! and a support on a line are such forces, and so is any contact whose
//! touching nodes form a line.
//!
//! `find` names each: the loads (`force_per_node`), supports (constraints
//! with a reaction) and contacts (indenters and pairs, their nodes touching
//! at the end) whose nodes cover no surface of an element of their body —
//! a boundary face, as surface loads take them (`bc::faces`), or a surface
//! through it (a plane cut through the body) —, the elements that touch those
//! nodes, and the share of the estimated error (`post::estimate`, `Σ η_e²`)
//! those elements hold. `summary.json` lists them (`concentrated`), the VTU
//! marks their elements (`concentrated`, 1 there) and the report says that
//! the stresses there are those of a concentrated force.

use std::collections::HashSet;

use super::Solution;

use crate::mesh::Mesh;
use crate::setup::Model;

/// A force on a point or a line of nodes (as `summary.json` lists it).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Concentrated {
    /// The load, constraint, indenter or contact name.
    pub name: String,
    /// `"load"`, `"support"` or `"contact"`.
    pub kind: &'static str,
    /// Its model-file key (`loads[k]`, `constraints[k]`, `indenters[k]`, `contacts[k]`).
    pub key: String,
    /// The nodes that carry it.
    pub nodes: usize,
    /// The number of elements that touch those nodes.
    pub elements: usize,
    /// Those elements (global indices), ascending.
    #[serde(skip)]
    pub touching: Vec<usize>,
    /// Those elements' share of `Σ η_e²` of the estimate (`None` without one).
    pub error_share: Option<f64>,
}

/// Fraction of the largest force of the model (loads, reactions, contact
/// resultants) below which a support's reaction is taken as zero: a support
/// that only removes a rigid-body motion carries no load.
const NEGLIGIBLE: f64 = 1e-6;

/// Every load, support and contact of the final state that acts on a point
/// or a line of nodes (module docs).
pub(crate) fn find(model: &Model, solution: &Solution) -> Vec<Concentrated> {
    let norm = |f: &[f64; 3]| super::tables::norm(*f);
    let scale = model
        .loads
        .iter()
        .map(|l| norm(&l.resultant()))
        .chain(solution.reactions.iter().map(|r| norm(&r.force)))
        .chain(solution.contacts.iter().map(|c| norm(&c.force)))
        .fold(0.0, f64::max);
    let mut found = Vec::new();
    let mut add = |name: &str, kind, key: String, nodes: Vec<usize>| {
        if let Some(c) = concentrated(model, solution, name, kind, key, nodes) {
            found.push(c);
        }
    };
    for (k, load) in model.loads.iter().enumerate() {
        if let crate::bc::LoadKind::PerNode { force, .. } = load.kind
            && norm(&force) > 0.0
        {
            add(&load.name, "load", format!("loads[{k}]"), load.nodal_forces.iter().map(|(n, _)| *n).collect());
        }
    }
    for (k, c) in model.constraints.iter().enumerate() {
        let carries = solution.reaction(&c.name).is_some_and(|r| norm(&r.force) > NEGLIGIBLE * scale);
        if carries {
            add(&c.name, "support", format!("constraints[{k}]"), c.nodes.clone());
        }
    }
    let n_ind = model.indenters.len();
    for (k, set) in solution.contact_sets.iter().enumerate() {
        let nodes: Vec<usize> = set
            .points
            .iter()
            .filter(|p| p.active && norm(&p.force) > 0.0)
            .flat_map(|p| std::iter::once(p.node).chain(p.master))
            .collect();
        let key = if k < n_ind { format!("indenters[{k}]") } else { format!("contacts[{}]", k - n_ind) };
        add(&set.name, "contact", key, nodes);
    }
    found
}

/// The item if `nodes` (global) cover no surface of an element of any
/// body they lie in (`holds_a_face`), with the elements around them and
/// their share of the error.
fn concentrated(
    model: &Model,
    solution: &Solution,
    name: &str,
    kind: &'static str,
    key: String,
    nodes: Vec<usize>,
) -> Option<Concentrated> {
    let set: HashSet<usize> = nodes.into_iter().collect();
    if set.is_empty() || holds_a_face(&model.mesh, &set) {
        return None;
    }
    let touching = elements_touching(&model.mesh, &set);
    let error_share = solution.error_estimate.as_ref().filter(|e| e.error > 0.0).map(|e| {
        let part: f64 = touching.iter().map(|&i| e.element[i] * e.element[i]).sum();
        part / (e.error * e.error)
    });
    Some(Concentrated {
        name: name.to_string(),
        kind,
        key,
        nodes: set.len(),
        elements: touching.len(),
        touching,
        error_share,
    })
}

/// Whether the nodes in `set` cover a surface of some element of a body:
/// a face on its boundary or a surface through it — the element's section
/// nodes at one of its axis nodes, or one row or column of its section
/// nodes at all of its axis nodes. A support over an interior plane (a
/// symmetry plane cut through a whole model, a mid-span support over a
/// whole cross-section) acts on a surface, as one over a boundary face does.
fn holds_a_face(mesh: &Mesh, set: &HashSet<usize>) -> bool {
    let mut nodes = Vec::new();
    mesh.bodies.iter().any(|body| {
        let range = body.node_offset..body.node_offset + body.n_nodes();
        if !set.iter().any(|n| range.contains(n)) {
            return false;
        }
        let m = body.section.kind.order() + 1;
        (0..body.n_elements()).any(|e| {
            body.element_nodes(e, &mut nodes);
            if !nodes.iter().any(|n| set.contains(n)) {
                return false;
            }
            let (es, eb) = body.split_element(e);
            let section = body.section.element(es);
            let beam = body.axis.first_node(eb)..=body.axis.first_node(eb) + body.axis.kind.order();
            let across = beam.clone().any(|i| section.iter().all(|&t| set.contains(&body.node(i, t))));
            let line = |local: &dyn Fn(usize) -> usize| {
                beam.clone().all(|i| (0..m).all(|k| set.contains(&body.node(i, section[local(k)]))))
            };
            across || (0..m).any(|r| line(&|c| r * m + c) || line(&|c| c * m + r))
        })
    })
}

/// The global elements with a node in `set`, ascending.
fn elements_touching(mesh: &Mesh, set: &HashSet<usize>) -> Vec<usize> {
    let mut out = Vec::new();
    let mut nodes = Vec::new();
    for body in &mesh.bodies {
        let range = body.node_offset..body.node_offset + body.n_nodes();
        if !set.iter().any(|n| range.contains(n)) {
            continue;
        }
        for e in 0..body.n_elements() {
            body.element_nodes(e, &mut nodes);
            if nodes.iter().any(|n| set.contains(n)) {
                out.push(body.element_offset + e);
            }
        }
    }
    out
}
