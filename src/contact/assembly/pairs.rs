//! Node-to-node contact (the paper's eqs. 13–20): a node against a rigid
//! indenter's surface (gap and normal fixed in the reference
//! configuration) or against a master node of another body, penalty or
//! augmented Lagrangian along the normal, Coulomb friction in the tangent
//! plane.

use super::Contacts;
use crate::assembly::{At, Tangent};
use crate::contact;

/// A contact block `K` split into `S = sym(K − C)`, which goes into the
/// lower-triangle (factorized) tangent, and the rest `K − S`, which goes
/// into the unsymmetric terms: `C` is a sliding point's pressure coupling
/// `μ ε_N t̂ nᵀ` (`FrictionResponse::coupling`), whose symmetric part
/// would make the factorized matrix indefinite; without it the rest is the
/// skew part `(K − Kᵀ)/2` (zero in a frictionless model).
pub(super) fn split(k: &[[f64; 3]; 3], coupling: &[[f64; 3]; 3]) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let d: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] - coupling[i][j]));
    let sym: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (d[i][j] + d[j][i])));
    (sym, std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] - sym[i][j])))
}

/// One contact point's terms: slave node, master node (pairs), the master's
/// displacement (a body node's or the rigid indenter's), initial gap, normal
/// and penalty.
pub(super) type PairTerms = (usize, Option<usize>, [f64; 3], f64, [f64; 3], f64);

impl Contacts<'_> {
    /// One node pair of eq. (13): gap from the slave displacement and the
    /// master's (`u_master`: a body node's, or a rigid indenter's), force
    /// `−ε g n` on the slave and its opposite on the master node if any,
    /// blocks `±ε n nᵀ` into the tangent. Records the point's state in
    /// `self.points[k]` and returns true if its active status changed.
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
    /// consistent one in the first evaluation of an increment, the cautious
    /// retry of a failed one included (`Incremental::cautious`). At the
    /// start of an increment a point that slid sits on the cone to
    /// round-off, so its branch there is arbitrary; the stick tangent
    /// predicts an elastic unloading, which is exact when the sliding
    /// reverses (the consistent slip tangent, without stiffness along the
    /// sliding direction, sends every point across its tiny stick range —
    /// `μ p / ε_T` — and Newton chatters between forward and reverse slip).
    /// From the second iteration on the tangent is consistent, and from the
    /// first when the increment starts on the secant of the last one
    /// (`Incremental::extrapolate`: the point is then past the cone). The
    /// stick tangent kept at every iteration converges only linearly, at a
    /// rate near one where many points slide under a stiff penalty: the
    /// cantilevers' peel on 60 B4 stalled at a relative residual of 0.28
    /// (tests/friction.rs `a_fine_frictional_peel_converges_in_its_retry`).
    pub(super) fn pair(
        &mut self,
        at: &At<'_>,
        tangent: &mut Tangent<'_>,
        k: usize,
        pair: PairTerms,
        friction: Option<&contact::Friction>,
    ) -> bool {
        let (slave, master, u_master, gap0, normal, penalty) = pair;
        let normal = &normal;
        let us = [0, 1, 2].map(|i| at.u[3 * slave + i]);
        let g = contact::gap(gap0, normal, us, u_master);
        let mut response = contact::augmented_response(g, normal, penalty, self.points[k].multiplier);
        let committed_slip = self.committed[k].slip;
        let point = &mut self.points[k];
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
            if fr.sliding && self.first_evaluation {
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
        self.blocks[k] = response.map_or([[0.0; 3]; 3], |r| r.1);
        if let Some((f, kb)) = response {
            point.force = f;
            for i in 0..3 {
                self.f_contact[3 * slave + i] += f[i];
            }
            // the symmetric part into the lower-triangle tangent, the rest
            // (sliding friction) into the unsymmetric terms
            let (sym, rest) = split(&kb, &coupling);
            tangent.add_node_block(slave, slave, &sym);
            tangent.add_rest_block(slave, slave, &rest, 1.0);
            if let Some(m) = master {
                for i in 0..3 {
                    self.f_contact[3 * m + i] -= f[i];
                }
                tangent.add_node_block(m, m, &sym);
                tangent.add_node_block(slave, m, &sym.map(|r| r.map(|v| -v)));
                tangent.add_rest_block(m, m, &rest, 1.0);
                tangent.add_rest_block(slave, m, &rest, -1.0);
                tangent.add_rest_block(m, slave, &rest, -1.0);
            }
        }
        changed
    }
}

impl Contacts<'_> {
    /// Node pair `j` of pair contact `c` in the current configuration
    /// (`contact::nodal_normal`): the gap between the current positions
    /// along the master surface's current normal, force `p ∇g`
    /// (`p = λ − ε g ≥ 0`) on the slave node, the master node and the
    /// master faces' nodes that turn the normal, tangent
    /// `ε ∇g ∇gᵀ − p ∂²g`. Frictionless (friction is refused with it).
    /// Returns true if the point's active status changed.
    pub(super) fn pair_current(
        &mut self,
        at: &At<'_>,
        tangent: &mut Tangent<'_>,
        k: usize,
        (c, j): (usize, usize),
    ) -> bool {
        let pc = &self.pairs[c];
        let p = &pc.pairs[j];
        let normal = &self.nodal_normals[c][j];
        let cp = normal.pair(self.mesh, p.slave, p.master, at.u, pc.overlap_relief(j, at.lambda));
        // a master surface crushed to no normal (|ñ| = 0) gives no contact,
        // not NaN forces (augmented_response takes a NaN gap as touching)
        let response = if cp.gap.is_finite() {
            contact::augmented_response(cp.gap, &cp.normal, p.penalty, self.points[k].multiplier)
        } else {
            None
        };
        let point = &mut self.points[k];
        let changed = response.is_some() != point.active;
        point.active = response.is_some();
        point.gap = cp.gap;
        point.normal = cp.normal;
        point.force = [0.0; 3];
        point.sliding = false;
        self.blocks[k] = response.map_or([[0.0; 3]; 3], |r| r.1);
        let Some((f, _)) = response else { return changed };
        point.force = f;
        let pressure: f64 = (0..3).map(|i| f[i] * cp.normal[i]).sum();
        for (b, g) in &cp.gradient {
            for i in 0..3 {
                self.f_contact[3 * b + i] += pressure * g[i];
            }
        }
        for (x, (a, ga)) in cp.gradient.iter().enumerate() {
            for (b, gb) in &cp.gradient[x..] {
                let block: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|s| p.penalty * ga[r] * gb[s]));
                tangent.add_node_block(*a, *b, &block);
            }
        }
        normal.add_second_variation(&cp, -pressure, p.master, |a, b, block| tangent.add_node_block(a, b, block));
        changed
    }
}
