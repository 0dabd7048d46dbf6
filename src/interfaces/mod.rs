//! Cohesive interfaces between the plies of a laminate: delamination.
//!
//! Where a laminate's interface is cohesive its two plies do not share
//! nodes: the section holds twin edges ([`crate::mesh::EdgeTwin`]) and each
//! pair of twin nodes at each beam node is one **interface point**, a
//! spring of the cohesive law ([`crate::materials::cohesive`]) between the
//! node below and the node above, carrying the traction over its area.
//!
//! **Nodal integration.** The area of point `(i, τ)` is `A = w_τ · w_i`,
//! `w_τ = Σ_edges ∫F_τ ds` along the section edges and `w_i = Σ_elements
//! ∫N_i dy` along the axis: the closed Newton–Cotes weights of the
//! equispaced Lagrange nodes, positive for every order cufem has. A uniform
//! traction is carried exactly (the weights are ∫N), and Newton–Cotes
//! integration of a stiff interface has none of the traction oscillations
//! of Gauss integration (Schellekens & de Borst 1993, IJNME 36:43). Onset
//! is sampled at the nodes, so the process zone needs nodes along the axis.
//!
//! **Frame.** A laminate's interface is normal to z: the separation is
//! `δ = u_upper − u_lower` in global axes, `δ3` the opening (mode I), `δ2`
//! the slip along the beam axis and `δ1` across the width (modes II/III).
//!
//! The points' forces and stiffness enter the structure as a
//! `crate::assembly::Contribution` ([`Interfaces`], `assembly.rs`); each
//! point's damage is history, committed only when an increment converges.

mod assembly;

pub use assembly::{Delamination, DelaminationSummary, Interfaces};

use crate::materials::cohesive::Cohesive;
use crate::mesh::Body;

/// One cohesive interface of a body, as the model defines it.
#[derive(Debug, Clone)]
pub struct Interface {
    /// Its name, `interface<k>` for the interface above ply k (1-based).
    pub name: String,
    /// The model-file key that asks for it (errors, the CalculiX refusal).
    pub key: String,
    /// The body's index.
    pub body: usize,
    /// The body's name (`bodies[i].name`), for summary.json.
    pub body_name: String,
    /// The traction–separation law.
    pub law: Cohesive,
    /// The model-file key of the law (`materials[j].cohesive`), for
    /// warnings about it.
    pub law_key: String,
    /// Its points.
    pub points: Vec<InterfacePoint>,
}

/// A twin-node pair of an interface at one beam node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfacePoint {
    /// The global node below.
    pub lower: usize,
    /// The global node above.
    pub upper: usize,
    /// Its area (m²).
    pub area: f64,
    /// Where it is `(x, y, z)` (m).
    pub position: [f64; 3],
    /// True inside a precrack: delaminated from the start (d = 1).
    pub cracked: bool,
}

impl Interface {
    /// The node pairs the points couple, for the tangent's pattern.
    pub fn couplings(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.points.iter().map(|p| (p.lower, p.upper))
    }

    /// Its area (m²).
    pub fn area(&self) -> f64 {
        self.points.iter().map(|p| p.area).sum()
    }
}

/// The points of interface `interface` (the 0-based ply below it) of
/// `body`: one per twin-node pair and beam node, with its nodal area;
/// those with `y` inside `crack` (`[from, to]`, m) start delaminated.
pub fn points(body: &Body, interface: usize, crack: Option<[f64; 2]>) -> Vec<InterfacePoint> {
    let axis = &body.axis;
    let p = axis.kind.order();
    let weights = crate::mesh::twins::edge_weights(p);
    let mut along = vec![0.0; axis.n_nodes()];
    for e in 0..axis.n_elements() {
        let (a, b) = axis.element_span(e);
        for (k, w) in weights.iter().enumerate() {
            along[axis.first_node(e) + k] += w * (b - a);
        }
    }
    let pairs = body.section.twin_nodes(interface);
    let mut out = Vec::with_capacity(pairs.len() * along.len());
    for (i, &wy) in along.iter().enumerate() {
        let y = axis.nodes[i];
        for &(lower, upper, wx) in &pairs {
            let [x, z] = body.section.nodes[lower];
            let cracked = crack.is_some_and(|[from, to]| y >= from && y <= to);
            out.push(InterfacePoint {
                lower: body.node(i, lower),
                upper: body.node(i, upper),
                area: wx * wy,
                position: [x, y, z],
                cracked,
            });
        }
    }
    out
}
