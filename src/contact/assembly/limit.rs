//! How far a Newton correction may carry open contact points into the
//! bodies they are about to touch.
//!
//! An open point adds no stiffness to the tangent, so the correction that
//! closes it knows nothing of the contact: it carries the point as deep as
//! the rest of the body goes. With a penalty `ε_N` some hundred times the
//! stiffness of the element layer behind the surface, a few micrometres of
//! such penetration give the point a force a hundred times the largest one
//! at equilibrium. The next correction pushes it out past the surface, the
//! one after that back in: the active set chatters at the edge of the
//! contact zone, and the residual, dominated by those forces, stays at 1
//! relative until Newton runs out of iterations or an element inverts
//! (NaN) and the increment is cut back.
//!
//! The rule here (a step-length control on the contact constraint, cf.
//! the penetration-based line searches of contact codes, Wriggers 2006
//! §8.4): the correction is scaled by the largest `α ≤ 1` with which no
//! point that was open at the last evaluation goes deeper than the deepest
//! point in contact now — so no new point gets a penalty force beyond the
//! largest one carried (for equal penalties). However small that makes
//! `α`: where a whole line of support points sits open by nanometres to
//! micrometres, nothing in the tangent holds the body, and the correction
//! can move it millimetres; scaled down to put those points at the deepest
//! penetration, the correction is nearly void, but the next one has them
//! in contact (a floor of 10⁻³ instead carried them micrometres deep, and
//! the iteration after that was spent pulling them out). The gap after the
//! correction is taken to first order, `g + n · (Δu_slave − Δu_master)`
//! with the normal of the last
//! evaluation; against a convex rigid indenter (flat, cylinder, sphere)
//! that is below the true gap, so the bound holds. Points in contact are
//! not limited (their stiffness is in the tangent), nor are the points of
//! segment-to-segment surface contacts (their gap is a weighted sum over
//! master faces). Where no point is in contact yet, the deepest is zero:
//! open points then stop at the surface, and `α ≥` [`SMALLEST_FRACTION`]
//! so that a point open by round-off cannot stall the iteration.
//!
//! Only with nonlinear geometry and frictionless contact. In small strain
//! no shipped example gained (`cufem run` on every example, one thread:
//! the same or up to 10 more Newton iterations, e.g. the block's unloading
//! 67 → 77), and with friction the scaled corrections stalled the
//! cantilevers' first increment (the stick–slip return of a point depends
//! on how far its correction carries it). Under large deformation a deep
//! penetration inverts elements; the crushed tube
//! (examples/tube_crush.toml), with its line search and the kept contact
//! of a secant start (`rigid`), no longer needs the limit (`cufem run`
//! with `limits_steps` false: 44 increments, 175 iterations, 240
//! evaluations, no cutback, the same curve to 1e-6 of the peak, against
//! 44, 177 and 248 with it).

use super::Contacts;
use crate::contact::dot;

/// The smallest fraction of a correction applied while no point is in
/// contact: a point open by a round-off gap would otherwise stop the
/// iteration where it is.
pub(crate) const SMALLEST_FRACTION: f64 = 1e-3;

impl Contacts<'_> {
    /// The fraction `α ∈ (0, 1]` of the correction (`du(d)`: its value at
    /// DOF `d = 3 · node + component`) to apply: the largest that takes
    /// no point open at the last evaluation (indenters and node pairs)
    /// deeper than the deepest point in contact now (module docs), at
    /// least [`SMALLEST_FRACTION`] while none is; 1 in small strain and
    /// with friction.
    pub(crate) fn step_limit(&self, du: impl Fn(usize) -> f64) -> f64 {
        if !self.limits_steps() {
            return 1.0;
        }
        let limited = self.limited_points();
        let deepest =
            limited.iter().map(|&(k, _, _)| &self.points[k]).filter(|p| p.active).fold(0.0_f64, |d, p| d.max(-p.gap));
        let mut alpha: f64 = 1.0;
        for (k, slave, master) in limited {
            let p = &self.points[k];
            if p.active || !p.gap.is_finite() {
                continue;
            }
            let d: [f64; 3] = std::array::from_fn(|i| du(3 * slave + i) - master.map_or(0.0, |m| du(3 * m + i)));
            let closing = -dot(p.normal, d);
            let reach = p.gap + deepest;
            if closing > reach {
                alpha = alpha.min(reach / closing);
            }
        }
        if deepest > 0.0 { alpha } else { alpha.max(SMALLEST_FRACTION) }
    }

    /// True if [`Self::step_limit`] may scale a correction: nonlinear
    /// geometry and frictionless contact (module docs).
    pub(crate) fn limits_steps(&self) -> bool {
        self.current && !self.frictional && !self.points.is_empty()
    }

    /// `(point, slave node, master node)` of every indenter point and every
    /// node pair, in point order.
    fn limited_points(&self) -> Vec<(usize, usize, Option<usize>)> {
        let mut out = Vec::with_capacity(self.points.len());
        let mut k = 0;
        for ind in self.indenters {
            out.extend(ind.nodes.iter().enumerate().map(|(j, c)| (k + j, c.node, None)));
            k += ind.nodes.len();
        }
        for (pc, range) in self.pairs.iter().zip(&self.ranges[self.indenters.len()..]) {
            out.extend(pc.pairs.iter().enumerate().map(|(j, p)| (range.start + j, p.slave, Some(p.master))));
        }
        out
    }
}
