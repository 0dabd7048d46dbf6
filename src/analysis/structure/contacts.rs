//! Contact assembly: every indenter point and node pair, penalty or
//! augmented Lagrangian in the normal direction, Coulomb friction in the
//! tangent plane (`contact::friction_response`).

use std::time::Instant;

use super::Structure;
use crate::contact;
use crate::materials::Predictor;

/// Largest forcing term (PCG stop, `solver::reuse`) of a correction made
/// while the contact status or the prescribed values have not settled.
/// Inexact Newton's theory needs a smooth residual; while points open and
/// close, a step solved only to `krylov_tolerance` (0.1) can flip the wrong
/// points and the active set then cycles: `examples/hertz_ball.toml` cycled
/// in its last increment (two cutbacks, 12.1 s) where solves to 1e-2 converge
/// in 4 increments (5.0 s). Once settled, the looser stop applies (the tubes
/// need 4–5 fewer factorizations with it). tests/examples.rs `hertz_ball`
/// asserts the 4 increments. With friction, points switching between stick
/// and slip count as unsettled too.
pub(super) const UNSETTLED_FORCING: f64 = 1e-2;

impl Structure<'_> {
    /// Penalty contact: forces into `f_contact`, stiffness into the tangent.
    /// Returns the number of points whose active status changed.
    pub(super) fn assemble_contact(&mut self) -> usize {
        let t = Instant::now();
        self.f_contact.fill(0.0);
        self.clear_skew();
        let model = self.model;
        let mut changes = 0;
        // with friction a point switching between stick and slip is a change
        // of the active set too (the forcing cap above)
        let was_sliding: Vec<bool> =
            if model.has_friction() { self.contact.iter().map(|p| p.sliding).collect() } else { Vec::new() };
        let mut k = 0;
        for (k_ind, ind) in model.indenters.iter().enumerate() {
            // the rigid surface's displacement plays the master's part
            let offset = self.indenter_offset(k_ind);
            if ind.updated {
                for c in &ind.nodes {
                    changes +=
                        usize::from(self.contact_rigid_surface(k, c, &ind.surface, offset, ind.friction.as_ref()));
                    k += 1;
                }
                continue;
            }
            for c in &ind.nodes {
                let pair = (c.node, None, offset, c.gap0, c.normal, c.penalty);
                changes += usize::from(self.contact_pair(k, pair, ind.friction.as_ref()));
                k += 1;
            }
        }
        for (c, pc) in model.contacts.iter().enumerate() {
            for (j, p) in pc.pairs.iter().enumerate() {
                let um = [0, 1, 2].map(|i| self.u[3 * p.master + i]);
                // an interference fit's overlap is imposed over the first step
                let gap0 = p.gap0 + pc.overlap_relief(j, self.lambda);
                let pair = (p.slave, Some(p.master), um, gap0, p.normal, p.penalty);
                changes += usize::from(self.contact_pair(k, pair, pc.friction.as_ref()));
                k += 1;
            }
            if let Some(s) = &pc.surface {
                changes += self.assemble_surface(k, c, s, pc.friction.as_ref());
                k += s.slave_nodes.len();
            }
        }
        changes += was_sliding.iter().zip(&self.contact).filter(|(w, p)| **w != p.sliding).count();
        self.first_evaluation = false;
        self.timings.contact += t.elapsed();
        changes
    }
}

impl Structure<'_> {
    /// A node against a rigid indenter with `method = "surface"`: the exact
    /// gap `g(y)` and normal `n(y)` at the current position `y = X + u − d`
    /// (`d` the indenter's displacement; `RigidSurface::current_gap`), the
    /// force `p n` with `p = λ − ε g ≥ 0`, and its consistent tangent
    /// `K = −∂(p n)/∂u = ε n nᵀ − p ∂n/∂y` — the second (curvature) term
    /// lets the force turn with the normal as the node slides over a
    /// roller or ball. With Coulomb friction, the tangential force of
    /// `contact::turning_friction` from the committed force and position
    /// (its derivative makes the block unsymmetric while sliding: the part
    /// beyond [`split`]'s symmetric one goes to the unsymmetric terms). Returns true if the point's active status
    /// changed.
    fn contact_rigid_surface(
        &mut self,
        k: usize,
        c: &contact::ContactNode,
        surface: &contact::RigidSurface,
        offset: [f64; 3],
        friction: Option<&contact::Friction>,
    ) -> bool {
        let x0 = self.model.mesh.coords(c.node);
        let y: [f64; 3] = std::array::from_fn(|i| x0[i] + self.u[3 * c.node + i] - offset[i]);
        let current = surface.current_gap(y, 1e-9 * self.model.mesh.bodies[self.model.mesh.body_of(c.node).0].size());
        let point = &mut self.contact[k];
        let was = point.active;
        point.force = [0.0; 3];
        point.active = false;
        point.sliding = false;
        point.position = y;
        point.slip = self.contact_committed[k].slip;
        self.contact_blocks[k] = [[0.0; 3]; 3];
        let Some((g, n, dn)) = current else {
            // beyond a punch's edge or a roller's end: out of contact
            point.gap = f64::NAN;
            return was;
        };
        point.gap = g;
        point.normal = n;
        let response = contact::augmented_response(g, &n, c.penalty, point.multiplier);
        point.active = response.is_some();
        let Some((mut f, kb)) = response else { return was };
        let p = (0..3).map(|i| f[i] * n[i]).sum::<f64>();
        let mut block: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| kb[i][j] - p * dn[i][j]));
        let mut coupling = [[0.0; 3]; 3];
        if let Some(fr) = friction {
            // from the committed tangential force and position
            let committed = self.contact_committed[k];
            let cn: f64 = (0..3).map(|i| committed.force[i] * committed.normal[i]).sum();
            let eps_t = fr.penalty_ratio * c.penalty;
            let v: [f64; 3] = std::array::from_fn(|i| {
                committed.force[i] - cn * committed.normal[i] - eps_t * (y[i] - committed.position[i])
            });
            let stick_tangent = self.first_evaluation || self.predictor == Predictor::Elastic;
            let r = contact::turning_friction(v, committed.slip, &n, &dn, p, c.penalty, fr, stick_tangent);
            let point = &mut self.contact[k];
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
        self.contact[k].force = f;
        for i in 0..3 {
            self.f_contact[3 * c.node + i] += f[i];
        }
        self.contact_blocks[k] = block;
        let (sym, rest) = split(&block, &coupling);
        self.assembler.add_node_block(&mut self.tangent, c.node, c.node, &sym);
        self.add_skew(c.node, c.node, &rest, 1.0);
        !was
    }
}

/// A contact block `K` split into `S = sym(K − C)`, which goes into the
/// lower-triangle (factorized) tangent, and the rest `K − S`, which goes
/// into the unsymmetric terms: `C` is a sliding point's pressure coupling
/// `μ ε_N t̂ nᵀ` (`FrictionResponse::coupling`), whose symmetric part
/// would make the factorized matrix indefinite; without it the rest is the
/// skew part `(K − Kᵀ)/2` (zero in a frictionless model).
fn split(k: &[[f64; 3]; 3], coupling: &[[f64; 3]; 3]) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let d: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] - coupling[i][j]));
    let sym: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (d[i][j] + d[j][i])));
    (sym, std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] - sym[i][j])))
}

/// One contact point's terms: slave node, master node (pairs), the master's
/// displacement (a body node's or the rigid indenter's), initial gap, normal
/// and penalty.
type PairTerms = (usize, Option<usize>, [f64; 3], f64, [f64; 3], f64);

impl Structure<'_> {
    /// One node pair of eq. (13): gap from the slave displacement and the
    /// master's (`u_master`: a body node's, or a rigid indenter's), force
    /// `−ε g n` on the slave and its opposite on the master node if any,
    /// blocks `±ε n nᵀ` into the tangent. Records the point's state in
    /// `self.contact[k]` and returns true if its active status changed.
    ///
    /// With Coulomb friction an active point adds its tangential force and
    /// block (`contact::friction_response`, from the committed slip). The
    /// point's block `K = ε n nᵀ + K_T` may be unsymmetric (sliding): its
    /// symmetric part goes into the lower-triangle tangent as
    /// `[K_ss, K_sm; K_ms, K_mm] = [K, −K; −K, K]`, the rest (the
    /// pressure coupling, [`split`]) with the same signs into the
    /// unsymmetric terms (`structure/unsymmetric.rs`).
    ///
    /// A sliding point gets the stick tangent `ε_T P` instead of its
    /// consistent one in the first evaluation of an increment and in the
    /// cautious retry of a failed one (`Incremental::cautious`). At the
    /// start of an increment a point that slid sits on the cone to
    /// round-off, so its branch there is arbitrary; the stick tangent
    /// predicts an elastic unloading, which is exact when the sliding
    /// reverses (the consistent slip tangent, without stiffness along the
    /// sliding direction, sends every point across its tiny stick range —
    /// `μ p / ε_T` — and Newton chatters between forward and reverse slip).
    /// From the second iteration on the tangent is consistent, and from the
    /// first when the increment starts on the secant of the last one
    /// (`Incremental::extrapolate`: the point is then past the cone).
    fn contact_pair(&mut self, k: usize, pair: PairTerms, friction: Option<&contact::Friction>) -> bool {
        let (slave, master, u_master, gap0, normal, penalty) = pair;
        let normal = &normal;
        let us = [0, 1, 2].map(|i| self.u[3 * slave + i]);
        let g = contact::gap(gap0, normal, us, u_master);
        let mut response = contact::augmented_response(g, normal, penalty, self.contact[k].multiplier);
        let committed_slip = self.contact_committed[k].slip;
        let point = &mut self.contact[k];
        let changed = response.is_some() != point.active;
        point.active = response.is_some();
        point.gap = g;
        point.normal = *normal;
        point.force = [0.0; 3];
        point.sliding = false;
        point.slip = committed_slip;
        let mut coupling = [[0.0; 3]; 3];
        if let (Some((f, kb)), Some(friction_law)) = (response.as_mut(), friction) {
            let rel: [f64; 3] = std::array::from_fn(|i| us[i] - u_master[i]);
            let dn: f64 = (0..3).map(|i| rel[i] * normal[i]).sum();
            let d_t: [f64; 3] = std::array::from_fn(|i| rel[i] - dn * normal[i]);
            let p_n: f64 = (0..3).map(|i| f[i] * normal[i]).sum();
            let mut fr = contact::friction_response(d_t, committed_slip, normal, p_n, penalty, friction_law);
            if fr.sliding && (self.first_evaluation || self.predictor == Predictor::Elastic) {
                fr.block = contact::stick_block(normal, penalty, friction_law);
                fr.coupling = [[0.0; 3]; 3];
            }
            coupling = fr.coupling;
            point.slip = fr.slip;
            point.sliding = fr.sliding;
            for i in 0..3 {
                f[i] += fr.force[i];
                for j in 0..3 {
                    kb[i][j] += fr.block[i][j];
                }
            }
        }
        self.contact_blocks[k] = response.map_or([[0.0; 3]; 3], |r| r.1);
        if let Some((f, kb)) = response {
            point.force = f;
            for i in 0..3 {
                self.f_contact[3 * slave + i] += f[i];
            }
            // the symmetric part into the lower-triangle tangent, the rest
            // (sliding friction) into the unsymmetric terms
            let (sym, rest) = split(&kb, &coupling);
            self.assembler.add_node_block(&mut self.tangent, slave, slave, &sym);
            self.add_skew(slave, slave, &rest, 1.0);
            if let Some(m) = master {
                for i in 0..3 {
                    self.f_contact[3 * m + i] -= f[i];
                }
                self.assembler.add_node_block(&mut self.tangent, m, m, &sym);
                self.assembler.add_node_block(&mut self.tangent, slave, m, &sym.map(|r| r.map(|v| -v)));
                self.add_skew(m, m, &rest, 1.0);
                self.add_skew(slave, m, &rest, -1.0);
                self.add_skew(m, slave, &rest, -1.0);
            }
        }
        changed
    }
}
