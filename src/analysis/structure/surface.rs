//! Assembly of surface (segment-to-segment, mortar-weighted) contact
//! (`contact::surface`): one constraint per slave node on its weighted gap,
//! the projections of the slave integration points updated after every
//! converged increment.
//!
//! With the weighted gap `g̃_a = gap0_a + G_a·u` (fixed projections), the
//! tributary area `A_a` and penalty `ε_a` of slave node `a`, its normal gap
//! is `ĝ_a = g̃_a / A_a` and its force `P_a = λ_a − ε_a ĝ_a ≥ 0` (N; `λ_a`
//! the augmented-Lagrangian multiplier). The energy `½ ε_a ĝ_a²` gives the
//! nodal contact forces `(P_a / A_a) G_a` and the tangent
//! `(ε_a / A_a²) G_a G_aᵀ` — exact, since `ĝ_a` is linear in `u` within an
//! increment.

use std::time::Instant;

use super::{ContactPoint, Structure};
use crate::contact::{PairContact, surface};

/// Projections and weighted gaps of one surface contact.
#[derive(Debug, Clone, Default)]
pub(super) struct State {
    /// Per slave node.
    gaps: Vec<surface::NodeGap>,
}

/// The contact points (one per slave node) of a surface contact before the
/// first evaluation.
pub(super) fn initial_points(pc: &PairContact) -> impl Iterator<Item = ContactPoint> + '_ {
    pc.surface.iter().flat_map(|s| {
        s.slave_nodes.iter().zip(&s.areas).map(|(&node, &area)| ContactPoint {
            node,
            area,
            gap: f64::NAN,
            ..Default::default()
        })
    })
}

impl Structure<'_> {
    /// Projects every surface-contact point from the committed
    /// displacements (at setup: the reference configuration) and forms the
    /// weighted gaps.
    pub(super) fn update_projections(&mut self) {
        let t = Instant::now();
        let model = self.model;
        for (c, pc) in model.contacts.iter().enumerate() {
            let Some(s) = &pc.surface else { continue };
            let projections: Vec<_> =
                s.points.iter().map(|p| surface::project(s, &model.mesh, p, &self.u_committed)).collect();
            let gaps = s.node_gaps(&projections);
            self.surface_state[c] = State { gaps };
        }
        self.timings.contact += t.elapsed();
    }

    /// Forces and tangent of surface contact `c` (data `s`), whose first
    /// contact point is `k0`; returns the number of slave nodes whose
    /// active status changed.
    pub(super) fn assemble_surface(&mut self, k0: usize, c: usize, s: &surface::SurfaceContact) -> usize {
        let mut changes = 0;
        let state = std::mem::take(&mut self.surface_state[c]);
        for (j, g) in state.gaps.iter().enumerate() {
            let (area, eps) = (s.areas[j], s.penalties[j]);
            let point = &mut self.contact[k0 + j];
            let was = point.active;
            point.force = [0.0; 3];
            point.active = false;
            if g.grad.is_empty() || !(area > 0.0) {
                point.gap = f64::NAN;
                changes += usize::from(was);
                continue;
            }
            let mut gt = g.gap0;
            for (b, v) in &g.grad {
                gt += (0..3).map(|k| v[k] * self.u[3 * b + k]).sum::<f64>();
            }
            let gap = gt / area;
            let m = (g.moment[0].powi(2) + g.moment[1].powi(2) + g.moment[2].powi(2)).sqrt();
            point.gap = gap;
            point.normal = g.moment.map(|v| v / m.max(f64::MIN_POSITIVE));
            // as contact::augmented_response: touching counts, a released
            // multiplier with an open gap does not
            let force = point.multiplier - eps * gap;
            let active = !(force < 0.0 || (point.multiplier == 0.0 && gap > 0.0));
            point.active = active;
            changes += usize::from(active != was);
            if !active {
                continue;
            }
            point.force = g.moment.map(|v| force * v / area);
            for (b, v) in &g.grad {
                for k in 0..3 {
                    self.f_contact[3 * b + k] += force / area * v[k];
                }
            }
            let scale = eps / (area * area);
            for (x, (a, va)) in g.grad.iter().enumerate() {
                for (b, vb) in &g.grad[x..] {
                    let block: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| scale * va[i] * vb[k]));
                    self.assembler.add_node_block(&mut self.tangent, *a, *b, &block);
                }
            }
        }
        self.surface_state[c] = state;
        changes
    }
}
