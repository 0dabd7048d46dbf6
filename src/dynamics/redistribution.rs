//! Mass redistribution at the contact nodes (`analysis.contact_mass =
//! "redistributed"`, the default of a transient analysis with contacts).
//!
//! **Why.** A node on a contact surface that carries mass is a particle
//! striking a penalty spring far stiffer than the time step resolves. An
//! implicit step cannot integrate that spring: with Newmark's average of
//! the contact forces the node bounces and creates energy, with the
//! contact impulse at the end of the step (`dynamics::impulse`) it stops
//! dead, loses its kinetic energy and then rings on the surface from step
//! to step. Either way the contact force chatters: the rod of
//! `examples/rod_impact.toml` with its end nodes' mass kept jumps from 0
//! to 7.3 kN and back in its first steps against the wall, about
//! Saint-Venant's plateau of 4.0 kN. The chatter is no error of the time
//! step but of the semi-discrete problem: its contact nodes' inertia makes
//! the dynamic contact problem ill posed (Khenous, Laborde & Renard,
//! *Mass redistribution method for finite element contact problems in
//! elastodynamics*, Eur. J. Mech. A/Solids 27, 2008).
//!
//! **The method** (Khenous, Laborde & Renard 2008): the contact nodes carry
//! no mass; their share goes to the nodes next to them. The contact force
//! is then the force that holds a massless node between the body's
//! stiffness and the penalty, a continuous function of the interior
//! motion: the semi-discrete problem is well posed, the force follows the
//! stress wave that reaches the surface, and an energy-conserving implicit
//! step stays so but for the contact's own (small) losses. Per element the
//! velocity field the mass sees is
//!
//! ```text
//! v_a = Σ_b W_ab v_b,    M'_e = Wᵀ M_e W
//! ```
//!
//! with `W` the identity on the element's other nodes and, for a contact
//! node `a`, equal weights on the nearest of the element's other nodes
//! (in the reference configuration): across the element layer under the
//! surface, along the axis at an end face. The weights of a row sum to
//! one, so a rigid translation keeps its kinetic energy (`M'` carries the
//! body's mass and momentum exactly); `M'` is positive semi-definite with
//! the contact nodes' rows and columns zero. With `mass = "lumped"` the
//! transformed element matrix is lumped again by row sums: the contact
//! node's mass moves to its neighbours.
//!
//! **Energy.** The contact impulse at the end of the step never creates
//! energy whatever the mass matrix (`dynamics::impulse`), and with the
//! contact nodes massless its losses, `½ ε Δg²` of an active point per
//! step, are those of a node that moves with the body behind it rather
//! than one that stops dead: 1.2e-4 of the energy of
//! `examples/rod_impact.toml` against 3.1e-3 with the nodes' mass kept
//! (crates/cufem-cli/tests/dynamics.rs).
//!
//! **Which nodes.** Every candidate node of a rigid indenter (impactors
//! included) and every node of a contact between bodies on either side
//! (its couplings: node pairs' slave and master nodes, a surface
//! contact's slave nodes and the nodes of its candidate master faces).
//! A contact node whose element has no other node — every node of the
//! element on a contact surface, as in one element through a plate
//! pressed on both faces — keeps that element's share of the mass; the
//! model warns by key (`analysis.contact_mass`).

use std::collections::HashMap;

use super::MassKind;
use crate::elements::Workspace;
use crate::mesh::Mesh;

/// How a transient analysis with contacts distributes the mass at the
/// contact nodes (`analysis.contact_mass`, module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactMass {
    /// The contact nodes carry no mass; their share goes to their
    /// neighbours (Khenous, Laborde & Renard 2008).
    #[default]
    Redistributed,
    /// Every node keeps its share of the mass.
    Kept,
}

/// One element's map `W` (module docs): per local node `a`, the local
/// nodes `b` and weights `W_ab` of the velocity the mass sees there.
#[derive(Debug, Clone)]
struct ElementMap {
    rows: Vec<Vec<(usize, f64)>>,
}

/// The transform of the element mass matrices that takes the contact
/// nodes' mass to their neighbours (module docs).
#[derive(Debug, Clone, Default)]
pub(crate) struct Redistribution {
    /// `W` of each (body, element) that holds a contact node.
    elements: HashMap<(usize, usize), ElementMap>,
    /// The contact nodes that carry no mass.
    massless: Vec<bool>,
    /// Contact nodes kept with some mass: in an element of contact nodes only.
    stranded: Vec<usize>,
}

impl Redistribution {
    /// The maps of every element of `mesh` that holds one of `contact`
    /// (global nodes).
    pub fn new(mesh: &Mesh, contact: &[usize]) -> Self {
        let mut is_contact = vec![false; mesh.n_nodes()];
        for &n in contact {
            is_contact[n] = true;
        }
        let mut elements = HashMap::new();
        let mut kept = vec![false; mesh.n_nodes()];
        let mut nodes = Vec::new();
        for (b, body) in mesh.bodies.iter().enumerate() {
            let touched = (body.node_offset..body.node_offset + body.n_nodes()).any(|n| is_contact[n]);
            if !touched {
                continue;
            }
            for e in 0..body.n_elements() {
                body.element_nodes(e, &mut nodes);
                if !nodes.iter().any(|&n| is_contact[n]) {
                    continue;
                }
                let map = element_map(mesh, &nodes, &is_contact);
                for (a, row) in map.rows.iter().enumerate() {
                    if row.iter().any(|&(c, _)| c == a) && is_contact[nodes[a]] {
                        kept[nodes[a]] = true;
                    }
                }
                elements.insert((b, e), map);
            }
        }
        let stranded: Vec<usize> = (0..kept.len()).filter(|&n| kept[n]).collect();
        let massless = is_contact.iter().zip(&kept).map(|(&c, &k)| c && !k).collect();
        Self { elements, massless, stranded }
    }

    /// True if global node `n` carries no mass.
    pub(crate) fn is_massless(&self, n: usize) -> bool {
        self.massless.get(n).copied().unwrap_or(false)
    }

    /// The contact nodes that keep some mass (module docs), sorted.
    pub(crate) fn stranded(&self) -> &[usize] {
        &self.stranded
    }

    /// Replaces the element mass matrix of element `element` of body
    /// `body` in `ws.tangent` (upper triangle, row-major, DOF `3a + c`, as
    /// `mass::element_mass` writes it) by `Wᵀ M_e W`, lumped again by row
    /// sums for `kind = Lumped`; other elements are left as they are.
    pub fn apply(&self, body: usize, element: usize, kind: MassKind, ws: &mut Workspace) {
        let Some(map) = self.elements.get(&(body, element)) else { return };
        let nodes = map.rows.len();
        let n = 3 * nodes;
        // the node-level matrix of one component (all three are equal)
        let m = |a: usize, b: usize| {
            let (p, q) = (3 * a.min(b), 3 * a.max(b));
            ws.tangent[p * n + q]
        };
        // X = m W, then m' = Wᵀ X
        let mut x = vec![0.0; nodes * nodes];
        for (d, row) in map.rows.iter().enumerate() {
            for &(c, w) in row {
                for a in 0..nodes {
                    x[a * nodes + c] += m(a, d) * w;
                }
            }
        }
        let mut out = vec![0.0; nodes * nodes];
        for (a, row) in map.rows.iter().enumerate() {
            for &(b, w) in row {
                for c in 0..nodes {
                    out[b * nodes + c] += w * x[a * nodes + c];
                }
            }
        }
        ws.tangent.fill(0.0);
        super::components::expand(&out, nodes, kind, &mut ws.tangent);
    }
}

/// `W` of one element with global nodes `nodes` (module docs): a contact
/// node's row weighs equally the nearest of the element's other nodes (a
/// relative tie of 1e-9), or is its own if every node is a contact node.
fn element_map(mesh: &Mesh, nodes: &[usize], is_contact: &[bool]) -> ElementMap {
    let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords(n)).collect();
    let distance = |a: usize, b: usize| (0..3).map(|k| (x[a][k] - x[b][k]).powi(2)).sum::<f64>().sqrt();
    let interior: Vec<usize> = (0..nodes.len()).filter(|&b| !is_contact[nodes[b]]).collect();
    let rows = (0..nodes.len())
        .map(|a| {
            if !is_contact[nodes[a]] || interior.is_empty() {
                return vec![(a, 1.0)];
            }
            let nearest = interior.iter().map(|&b| distance(a, b)).fold(f64::INFINITY, f64::min);
            let chosen: Vec<usize> =
                interior.iter().copied().filter(|&b| distance(a, b) <= nearest * (1.0 + 1e-9)).collect();
            let w = 1.0 / chosen.len() as f64;
            chosen.into_iter().map(|b| (b, w)).collect()
        })
        .collect();
    ElementMap { rows }
}

/// The contact nodes of a model (module docs): the candidate nodes of
/// every indenter, and both sides of every contact between bodies.
pub(crate) fn contact_nodes(
    mesh: &Mesh,
    indenters: &[crate::contact::Indenter],
    contacts: &[crate::contact::PairContact],
) -> Vec<usize> {
    let mut set = std::collections::BTreeSet::new();
    for i in indenters {
        set.extend(i.nodes.iter().map(|c| c.node));
    }
    for c in contacts {
        for (a, b) in c.couplings(mesh, false) {
            set.insert(a);
            set.insert(b);
        }
    }
    set.into_iter().collect()
}

#[cfg(test)]
#[path = "redistribution_tests.rs"]
mod tests;
