//! Assembly of segment-to-segment contact (`contact::surface`): each slave
//! integration point against its projection on the master surface, the
//! projection updated after every converged increment.

use std::time::Instant;

use super::{ContactPoint, Structure};
use crate::contact::{self, PairContact, surface};

/// The contact points of a surface contact before the first evaluation.
pub(super) fn initial_points(pc: &PairContact) -> impl Iterator<Item = ContactPoint> + '_ {
    pc.surface.iter().flat_map(|s| {
        s.points.iter().map(|p| ContactPoint {
            node: p.nearest_node,
            area: p.weight,
            gap: f64::NAN,
            position: Some(p.position),
            ..Default::default()
        })
    })
}

impl Structure<'_> {
    /// Projects every surface-contact point from the committed
    /// displacements (at setup: the reference configuration).
    pub(super) fn update_projections(&mut self) {
        let t = Instant::now();
        let model = self.model;
        let ni = model.indenters.len();
        for (c, pc) in model.contacts.iter().enumerate() {
            let Some(s) = &pc.surface else { continue };
            let start = self.contact_ranges[ni + c].start;
            for (j, p) in s.points.iter().enumerate() {
                self.projections[start + j] = surface::project(s, &model.mesh, p, &self.u_committed);
            }
        }
        self.timings.contact += t.elapsed();
    }

    /// Forces and tangent of the points of surface contact `s`, whose
    /// first point is contact point `k0`; returns the number of points
    /// whose active status changed.
    pub(super) fn assemble_surface(&mut self, k0: usize, s: &surface::SurfaceContact) -> usize {
        let mut changes = 0;
        let mut coeff: Vec<(usize, f64)> = Vec::new();
        for (j, p) in s.points.iter().enumerate() {
            let k = k0 + j;
            let Some(proj) = &self.projections[k] else {
                let point = &mut self.contact[k];
                changes += usize::from(point.active);
                point.active = false;
                point.gap = f64::NAN;
                point.force = [0.0; 3];
                continue;
            };
            let g = surface::gap(p, proj, &self.u);
            let n = proj.normal;
            let response = contact::augmented_response(g, &n, p.penalty, self.contact[k].multiplier);
            let point = &mut self.contact[k];
            changes += usize::from(response.is_some() != point.active);
            point.active = response.is_some();
            point.gap = g;
            point.normal = n;
            point.force = [0.0; 3];
            let Some((f, kb)) = response else { continue };
            point.force = f;
            // c = (N_s, −N_m): force c_a f on node a, block c_a c_b k
            coeff.clear();
            coeff.extend(p.nodes.iter().copied().zip(p.shapes.iter().copied()));
            coeff.extend(proj.nodes.iter().copied().zip(proj.shapes.iter().map(|v| -v)));
            coeff.retain(|&(_, c)| c != 0.0);
            for &(a, ca) in &coeff {
                for i in 0..3 {
                    self.f_contact[3 * a + i] += ca * f[i];
                }
            }
            for (x, &(a, ca)) in coeff.iter().enumerate() {
                for &(b, cb) in &coeff[x..] {
                    let block = kb.map(|r| r.map(|v| ca * cb * v));
                    self.assembler.add_node_block(&mut self.tangent, a, b, &block);
                }
            }
        }
        changes
    }
}
