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
//! `(ε_a / A_a²) G_a G_aᵀ` — exact in small strain, where `ĝ_a` is linear
//! in `u` within an increment. With nonlinear geometry
//! (`Contacts::current`) the projections are made on the deformed master
//! at every evaluation (`contact::current`), the weighted gaps linearized
//! there, and the gaps' second variation `−(P_a/A_a) Σ_q w_q N_a ∂²g_q`
//! completes the tangent.

use super::{ContactPoint, Contacts};
use crate::assembly::{At, Tangent};
use crate::contact::{self, PairContact, current, surface};

/// Projections and weighted gaps of one surface contact.
#[derive(Debug, Clone, Default)]
pub(super) struct State {
    /// Per slave node.
    gaps: Vec<surface::NodeGap>,
    /// In the current configuration (`Contacts::current`): each slave
    /// point's projection onto the deformed master surface, from which the
    /// gaps were linearized; empty otherwise.
    current: Vec<Option<current::CurrentProjection>>,
}

impl State {
    /// Every point projected onto the master surface deformed by `u`, and
    /// the weighted gaps linearized there.
    fn current(s: &surface::SurfaceContact, mesh: &crate::mesh::Mesh, u: &[f64]) -> Self {
        let master = &mesh.bodies[s.master_body];
        let current: Vec<_> = s.points.iter().map(|p| current::project(s, master, p, u)).collect();
        let projections: Vec<_> = current.iter().map(|c| c.as_ref().map(|c| c.projection.clone())).collect();
        Self { gaps: s.node_gaps(&projections), current }
    }
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

impl Contacts<'_> {
    /// Projects every surface-contact point from the committed
    /// displacements (at setup: the reference configuration) and forms the
    /// weighted gaps.
    pub(super) fn update_projections(&mut self, u_committed: &[f64]) {
        for (c, pc) in self.pairs.iter().enumerate() {
            let Some(s) = &pc.surface else { continue };
            self.surface[c] = if self.current {
                State::current(s, self.mesh, u_committed)
            } else {
                let projections: Vec<_> =
                    s.points.iter().map(|p| surface::project(s, self.mesh, p, u_committed)).collect();
                State { gaps: s.node_gaps(&projections), current: Vec::new() }
            };
        }
    }

    /// Forces and tangent of surface contact `c` (data `s`), whose first
    /// contact point is `k0`; returns the number of slave nodes whose
    /// active status changed.
    pub(super) fn assemble_surface(
        &mut self,
        at: &At<'_>,
        tangent: &mut Tangent<'_>,
        k0: usize,
        c: usize,
        s: &surface::SurfaceContact,
        friction: Option<&contact::Friction>,
    ) -> usize {
        let mut changes = 0;
        let state = if self.current {
            // the deformed master surface of this very state
            State::current(s, self.mesh, at.u)
        } else {
            std::mem::take(&mut self.surface[c])
        };
        // P_a / A_a of each active slave node, for the gaps' second variation
        // (current configuration only: in the reference one the gap is linear)
        let mut pressures = vec![0.0; if self.current { state.gaps.len() } else { 0 }];
        for (j, g) in state.gaps.iter().enumerate() {
            let (area, eps) = (s.areas[j], s.penalties[j]);
            let point = &mut self.points[k0 + j];
            let was = point.active;
            point.force = [0.0; 3];
            point.active = false;
            point.sliding = false;
            point.slip = self.committed[k0 + j].slip;
            if g.grad.is_empty() || !(area > 0.0) {
                point.gap = f64::NAN;
                changes += usize::from(was);
                continue;
            }
            let mut gt = g.gap0;
            for (b, v) in &g.grad {
                gt += (0..3).map(|k| v[k] * at.u[3 * b + k]).sum::<f64>();
            }
            // an interference fit's overlap is imposed over the first step
            let gap = gt / area + self.pairs[c].overlap_relief(j, at.lambda);
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
            if let Some(p) = pressures.get_mut(j) {
                *p = force / area;
            }
            for (b, v) in &g.grad {
                for k in 0..3 {
                    self.f_contact[3 * b + k] += force / area * v[k];
                }
            }
            let scale = eps / (area * area);
            for (x, (a, va)) in g.grad.iter().enumerate() {
                for (b, vb) in &g.grad[x..] {
                    let block: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| scale * va[i] * vb[k]));
                    tangent.add_node_block(*a, *b, &block);
                }
            }
            if let Some(fr) = friction {
                self.surface_friction(at, tangent, k0 + j, (g, area, eps, force), fr);
            }
        }
        // in the current configuration the gap is not linear in u: the force
        // P_a on g̃_a/A_a adds −(P_a/A_a) Σ_q w_q N_a(q) ∂²g_q
        for (p, cp) in s.points.iter().zip(&state.current) {
            let Some(cp) = cp else { continue };
            let coefficient: f64 = p
                .nodes
                .iter()
                .zip(&p.shapes)
                .map(|(a, na)| pressures[s.slave_nodes.binary_search(a).expect("slave node listed")] * p.weight * na)
                .sum();
            if coefficient != 0.0 {
                cp.add_second_variation(p, -coefficient, |a, b, block| tangent.add_node_block(a, b, block));
            }
        }
        self.surface[c] = state;
        changes
    }
}

impl Contacts<'_> {
    /// Coulomb friction of slave-node point `k` (weighted gap `g`, area,
    /// normal penalty and force), incremental from the committed state: the
    /// weighted tangential relative displacement of the increment
    /// `d_t = Σ_b T_b (u_b − u_b,n) / A` and the committed tangential force
    /// `t_n` give the trial `t_n − ε_T d_t`, returned onto the Coulomb cone
    /// by `contact::friction_response`. Nodal forces `T_b t / A` (`T_b`
    /// symmetric); the accumulated slip grows by `d_t + (t − t_n)/ε_T`. The
    /// consistent tangent `(T_b K_tt T_c + μ ε (T_b t̂) G_cᵀ) / A²` (`K_tt`
    /// the return map's tangential block; the second term, from
    /// `∂P/∂u_c = −ε G_c / A` while sliding, is unsymmetric and goes to
    /// the unsymmetric terms). A sliding point's first iteration of an
    /// increment uses the stick block, as node-to-node friction does.
    fn surface_friction(
        &mut self,
        at: &At<'_>,
        tangent: &mut Tangent<'_>,
        k: usize,
        (g, area, eps, normal_force): (&surface::NodeGap, f64, f64, f64),
        fr: &contact::Friction,
    ) {
        let eps_t = fr.penalty_ratio * eps;
        let n = self.points[k].normal;
        let committed = self.committed[k];
        let fcn: f64 = (0..3).map(|i| committed.force[i] * n[i]).sum();
        let t_n: [f64; 3] = std::array::from_fn(|i| committed.force[i] - fcn * n[i]);
        let mut d_t = [0.0; 3];
        for ((b, _), t) in g.grad.iter().zip(&g.tangential) {
            for i in 0..3 {
                for l in 0..3 {
                    d_t[i] += t[i][l] * (at.u[3 * b + l] - at.u_committed[3 * b + l]) / area;
                }
            }
        }
        let mut r = contact::friction_response(d_t, t_n.map(|v| v / eps_t), &n, normal_force, eps, fr);
        let predicted = r.sliding && self.first_evaluation;
        if predicted {
            // as node-to-node friction (structure/contacts.rs): the stick
            // tangent predicts the first iteration of an increment
            r.block = contact::stick_block(&n, eps, fr);
        }
        let (ft, sliding) = (r.force, r.sliding);
        // r.block = K_tt + μ ε_N t̂ nᵀ (while sliding and pressed): the
        // second term is the pressure coupling of a node pair, whose ∂p/∂d
        // is −ε nᵀ; here ∂P/∂u_c = −ε G_c / A, so it is rebuilt below with G_c.
        let f_norm = (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]).sqrt();
        let coupling =
            if sliding && !predicted && normal_force > 0.0 && f_norm > 0.0 { fr.coefficient * eps } else { 0.0 };
        let t_hat = ft.map(|v| v / f_norm.max(f64::MIN_POSITIVE));
        let kt: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|l| r.block[i][l] - coupling * t_hat[i] * n[l]));
        let point = &mut self.points[k];
        point.sliding = sliding;
        point.slip = std::array::from_fn(|i| committed.slip[i] + d_t[i] + (ft[i] - t_n[i]) / eps_t);
        for i in 0..3 {
            point.force[i] += ft[i];
        }
        for ((b, _), t) in g.grad.iter().zip(&g.tangential) {
            for i in 0..3 {
                self.f_contact[3 * b + i] += (0..3).map(|l| t[i][l] * ft[l]).sum::<f64>() / area;
            }
        }
        // M_bc = −∂F_b/∂u_c = (T_b K_tt T_c + μ ε (T_b t̂) G_cᵀ) / A²: the
        // symmetric first term into the lower-triangle (factorized) tangent,
        // the pressure coupling — one outer product over the point's nodes —
        // into the unsymmetric terms
        let scale = 1.0 / (area * area);
        let tb_kt: Vec<[[f64; 3]; 3]> = g
            .tangential
            .iter()
            .map(|tb| std::array::from_fn(|i| std::array::from_fn(|l| (0..3).map(|m| tb[i][m] * kt[m][l]).sum())))
            .collect();
        for (x, (a, _)) in g.grad.iter().enumerate() {
            for ((b, _), tc) in g.grad.iter().zip(&g.tangential).skip(x) {
                let sym: [[f64; 3]; 3] = std::array::from_fn(|i| {
                    std::array::from_fn(|l| scale * (0..3).map(|m| tb_kt[x][i][m] * tc[m][l]).sum::<f64>())
                });
                tangent.add_node_block(*a, *b, &sym);
            }
        }
        if coupling != 0.0 {
            let u: Vec<(usize, [f64; 3])> = g
                .grad
                .iter()
                .zip(&g.tangential)
                .map(|((b, _), tb)| {
                    (*b, std::array::from_fn(|i| scale * coupling * (0..3).map(|m| tb[i][m] * t_hat[m]).sum::<f64>()))
                })
                .collect();
            let v: Vec<(usize, [f64; 3])> = g.grad.iter().map(|(c, gc)| (*c, *gc)).collect();
            tangent.add_rest_outer(&u, &v);
        }
    }
}
