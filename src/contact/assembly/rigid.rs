//! A node against a rigid indenter with `method = "surface"`: the exact gap
//! and normal of the current configuration (finite sliding over a roller
//! or ball), with the curvature term in the tangent.
//!
//! **The secant's start.** An increment that starts on the secant of the
//! last one (`solver::stepping`: `u_n + (Δλ/Δλ_n) Δu_n`) moves a point in
//! contact along a straight line, while the surface it slides on curves
//! away: sliding `s` over a roller of radius `R` lifts it by `s²/2R`.
//! Without the rule below, the crushed tube's support line
//! (examples/tube_crush.toml), sliding some 0.2 mm per increment, starts
//! every increment open by 2–7 µm; an open point adds nothing to the
//! tangent, so the first correction drops the tube onto the support
//! unresisted, as deep as the step limit (`limit`) allows — the deepest
//! point in contact, a load-roller node line the secant carried 10–30 µm
//! in: support forces of 10⁵ N against a roller force of 750 N, and an
//! iteration spent on them in almost every increment. So at that first
//! evaluation a frictionless point in contact at the committed state keeps
//! its penalty law where the secant opened it (by more than round-off):
//! the force `(λ − ε g) n`, a tension, and the tangent of a point in
//! contact (it counts as a status change, so Newton cannot stop there, and
//! no line search runs along the correction from it, `structure/line.rs`);
//! the first correction then holds it on the surface, and from the next
//! evaluation on, every point's status is its own again. A point that the
//! load truly lifts off (a reversal within a step) is pulled back by that
//! one correction too and opens at the next. Measured with `cufem bench
//! examples/tube_crush.toml --full --threads 1`: docs/performance.md. Not
//! with friction, whose return needs a compressive normal force.

use super::Contacts;
use super::pairs::split;
use crate::assembly::{At, Tangent};
use crate::contact;

impl Contacts<'_> {
    /// A node against a rigid indenter with `method = "surface"`: the exact
    /// gap `g(y)` and normal `n(y)` at the current position `y = X + u − d`
    /// (`d` the indenter's displacement; `RigidSurface::current_gap`), the
    /// force `p n` with `p = λ − ε g ≥ 0`, and its consistent tangent
    /// `K = −∂(p n)/∂u = ε n nᵀ − p ∂n/∂y` — the second (curvature) term
    /// lets the force turn with the normal as the node slides over a
    /// roller or ball. With Coulomb friction, the tangential force of
    /// `contact::turning_friction` from the committed force and position
    /// (its derivative makes the block unsymmetric while sliding: the part
    /// beyond [`split`]'s symmetric one goes to the unsymmetric rest).
    /// Returns true if the point's active status changed.
    pub(super) fn rigid_surface(
        &mut self,
        at: &At<'_>,
        tangent: &mut Tangent<'_>,
        k: usize,
        c: &contact::ContactNode,
        (indenter, offset): (&contact::Indenter, [f64; 3]),
    ) -> bool {
        let (surface, friction) = (&indenter.surface, indenter.friction.as_ref());
        let x0 = self.mesh.coords(c.node);
        let y: [f64; 3] = std::array::from_fn(|i| x0[i] + at.u[3 * c.node + i] - offset[i]);
        let current = surface.current_gap(y, 1e-9 * self.mesh.bodies[self.mesh.body_of(c.node).0].size());
        let point = &mut self.points[k];
        let was = point.active;
        point.force = [0.0; 3];
        point.active = false;
        point.sliding = false;
        point.position = y;
        point.slip = self.committed[k].slip;
        self.blocks[k] = [[0.0; 3]; 3];
        let Some((g, n, dn)) = current else {
            // beyond a punch's edge or a roller's end: out of contact
            point.gap = f64::NAN;
            return was;
        };
        point.gap = g;
        point.normal = n;
        let response = contact::augmented_response(g, &n, c.penalty, point.multiplier);
        point.active = response.is_some();
        // a point in contact lifted off by the secant's start (module docs)
        let kept = response.is_none()
            && self.on_secant
            && friction.is_none()
            && self.committed[k].active
            && g > self.roundoff_gap;
        let response = if kept { Some(contact::penalty_law(g, &n, c.penalty, point.multiplier)) } else { response };
        let Some((mut f, kb)) = response else { return was };
        let p = (0..3).map(|i| f[i] * n[i]).sum::<f64>();
        let mut block: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| kb[i][j] - p * dn[i][j]));
        let mut coupling = [[0.0; 3]; 3];
        if let Some(fr) = friction {
            // from the committed tangential force and position
            let committed = self.committed[k];
            let cn: f64 = (0..3).map(|i| committed.force[i] * committed.normal[i]).sum();
            let eps_t = fr.penalty_ratio * c.penalty;
            let v: [f64; 3] = std::array::from_fn(|i| {
                committed.force[i] - cn * committed.normal[i] - eps_t * (y[i] - committed.position[i])
            });
            let stick_tangent = self.first_evaluation;
            let r = contact::turning_friction(v, committed.slip, &n, &dn, p, c.penalty, fr, stick_tangent);
            let point = &mut self.points[k];
            point.sliding = r.sliding;
            point.slip = r.slip;
            coupling = r.coupling;
            for i in 0..3 {
                f[i] += r.force[i];
                for j in 0..3 {
                    block[i][j] += r.block[i][j];
                }
            }
        }
        self.points[k].force = f;
        for i in 0..3 {
            self.f_contact[3 * c.node + i] += f[i];
        }
        self.blocks[k] = block;
        let (sym, rest) = split(&block, &coupling);
        tangent.add_node_block(c.node, c.node, &sym);
        tangent.add_rest_block(c.node, c.node, &rest, 1.0);
        if kept {
            self.points[k].active = true;
            self.kept += 1;
            return true;
        }
        !was
    }
}
