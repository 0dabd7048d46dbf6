//! Rigid levers (`[[levers]]`, `bc::Lever`): linear multi-point
//! constraints with a prescribed value, each held by one extra unknown, the
//! lever's force `P` (a Lagrange multiplier). Lever `j` pushes the body by
//! `P_j a_j` (its coefficients `a_j` per DOF) and asks `a_jᵀ u = δ_j(λ)`,
//! its `value` times its step factor. With `R = f_int − λ f_ext − Σ P_j a_j`
//! and `g_j = a_jᵀ u − δ_j` the Newton system borders the structural
//! tangent:
//!
//! ```text
//! [ K    −A ] [Δu]     [R]
//! [ −Aᵀ   0 ] [ΔP] = − [g]      A = [a_1 … a_m]  (free equations only)
//! ```
//!
//! the Hessian of `Π(u) − Σ P_j (a_jᵀ u − δ_j)` (symmetric, indefinite
//! by its zero corner). It is solved by bordering with the one
//! factorization of `K`, as the force-controlled indenters
//! (`structure/force.rs`): `K x₁ = −R`, `K X₂ = A`, then the small system
//! `(Aᵀ X₂) ΔP = −g − Aᵀ x₁` and `Δu = x₁ + X₂ ΔP`.
//! `K` need not be positive definite: past the limit point of the
//! structure under the levers' forces (the MMB past its peak) it is not,
//! while the bordered system, the structure under the levers'
//! displacements, is regular; the factorization falls back to `LDLᵀ`
//! (`solver::linear`).
//!
//! The levers' DOFs are free equations (`setup/levers.rs` refuses a
//! constrained one), so the Dirichlet elimination leaves their rows alone.

use super::system::LinearSystem;
use crate::assembly::NO_EQ;
use crate::bc::Lever;
use crate::setup::steps::{self, Item, Step};
use crate::solver::linear::LinearError;

/// One lever's unknown and border.
#[derive(Debug, Clone)]
struct Held {
    /// `(equation, a)` of its DOFs.
    border: Vec<(usize, f64)>,
    /// Its force `P` (N), current and committed, and the change over the
    /// last converged increment.
    force: f64,
    force_committed: f64,
    force_step: f64,
}

/// The model's levers: their forces, unknowns of the bordered solve.
#[derive(Debug)]
pub(crate) struct Levers<'m> {
    levers: &'m [Lever],
    steps: &'m [Step],
    held: Vec<Held>,
}

/// A lever's state as the results record it.
#[derive(Debug, Clone, PartialEq)]
pub struct LeverResultant {
    /// The lever's name.
    pub name: String,
    /// Its displacement `Σ a_d u_d` (m).
    pub displacement: f64,
    /// Its force `P` on the body (N): `P a_d` at DOF `d`.
    pub force: f64,
}

impl<'m> Levers<'m> {
    /// The levers of a model scaled by `steps`, on the numbering `eq` (per DOF).
    pub fn new(levers: &'m [Lever], steps: &'m [Step], eq: &[usize]) -> Self {
        let held = levers
            .iter()
            .map(|l| Held {
                border: l.terms.iter().filter(|(d, _)| eq[*d] != NO_EQ).map(|&(d, a)| (eq[d], a)).collect(),
                force: 0.0,
                force_committed: 0.0,
                force_step: 0.0,
            })
            .collect();
        Self { levers, steps, held }
    }

    /// True if the model has levers.
    pub(crate) fn is_active(&self) -> bool {
        !self.held.is_empty()
    }

    /// Each lever's prescribed displacement at `lambda` (m).
    fn target(&self, j: usize, lambda: f64) -> f64 {
        steps::factor(self.steps, Item::Lever(j), lambda) * self.levers[j].value
    }

    /// Adds the levers' pushes to the imbalance `f_int − λ f_ext − …` (per
    /// DOF). Returns the norm of those pushes (a force scale, N) and the
    /// largest relative gap `|g_j| / max(|δ_j|, Σ|a u|)` between a lever's
    /// displacement and its target (0 once a correction reached it).
    pub fn evaluate(&self, u: &[f64], imbalance: &mut [f64], lambda: f64) -> (f64, f64) {
        let (mut scale2, mut gap) = (0.0_f64, 0.0_f64);
        for (j, (lever, held)) in self.levers.iter().zip(&self.held).enumerate() {
            for &(d, a) in &lever.terms {
                imbalance[d] -= held.force * a;
                scale2 += (held.force * a).powi(2);
            }
            let target = self.target(j, lambda);
            let size = lever.terms.iter().map(|&(d, a)| (a * u[d]).abs()).sum::<f64>().max(target.abs());
            let g = lever.displacement(u) - target;
            if size > 0.0 {
                gap = gap.max(g.abs() / size);
            }
        }
        (scale2.sqrt(), gap)
    }

    /// Bordered solve (module docs): `system.rhs` holds `−R` (after the
    /// Dirichlet elimination); on return it holds `Δu`. `u` are the present
    /// displacements (per DOF), from which the gaps are taken. Updates
    /// each lever's force.
    pub fn solve(&mut self, system: &mut LinearSystem, u: &[f64], lambda: f64) -> Result<(), LinearError> {
        system.solve(true)?;
        let m = self.held.len();
        // a lever's force P enters the residual as −P a: the border column
        // is −a, its row −aᵀ Δu = g (the linearised gap to the lever's
        // target), the corner zero
        let mut cols = Vec::with_capacity(m);
        for held in &self.held {
            let mut x = vec![0.0; system.rhs.len()];
            for &(e, a) in &held.border {
                x[e] -= a;
            }
            system.solve_again(&mut x)?;
            cols.push(x);
        }
        let row = |i: usize, x: &[f64]| -self.held[i].border.iter().map(|&(e, a)| a * x[e]).sum::<f64>();
        let gaps: Vec<f64> = (0..m).map(|i| self.levers[i].displacement(u) - self.target(i, lambda)).collect();
        let dp = crate::solver::bordered::eliminate(&mut system.rhs, &cols, row, &vec![0.0; m], &gaps)?;
        for (held, d) in self.held.iter_mut().zip(&dp) {
            held.force += d;
        }
        Ok(())
    }

    /// Each lever's name, displacement and force at displacements `u`.
    pub fn resultants(&self, u: &[f64]) -> Vec<LeverResultant> {
        let each = self.levers.iter().zip(&self.held);
        each.map(|(l, h)| LeverResultant { name: l.name.clone(), displacement: l.displacement(u), force: h.force })
            .collect()
    }

    /// Starts the next solve on the secant of the last increment.
    pub fn extrapolate(&mut self, ratio: f64) {
        for h in &mut self.held {
            h.force = h.force_committed + ratio * h.force_step;
        }
    }

    /// The increment converged.
    pub fn commit(&mut self) {
        for h in &mut self.held {
            h.force_step = h.force - h.force_committed;
            h.force_committed = h.force;
        }
    }

    /// Back to the committed forces.
    pub fn restore(&mut self) {
        for h in &mut self.held {
            h.force = h.force_committed;
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::setup::{Limits, Model};

    /// A steel cantilever, 0.5 m × 0.02 m × 0.04 m, clamped at y = 0; `more`
    /// appended (a lever or loads on the tip face y = 0.5 and the section
    /// y = 0.25).
    fn cantilever(more: &str) -> Model {
        let text = format!(
            r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = 1 }}, z = {{ from = 0.0, to = 0.04, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.5, elements = 8 }}

[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
{more}
"#
        );
        Model::parse_with(&text, Limits::none()).unwrap()
    }

    /// The lever's coefficients: the tip (y = L) and mid-span (y = a = L/2)
    /// sections, as an MMB lever's c/L and −(c + L)/L with c = 0.3 L.
    const C_TIP: f64 = 0.3;
    const C_MID: f64 = -1.3;

    /// The mean u_z over the nodes of section `y` of a solution.
    fn mean_uz(model: &Model, u: &[f64], y: f64) -> f64 {
        let body = &model.mesh.bodies[0];
        let nodes: Vec<usize> = (0..body.n_nodes()).filter(|&n| (body.local_coords(n)[1] - y).abs() < 1e-9).collect();
        nodes.iter().map(|&n| u[3 * (n + body.node_offset) + 2]).sum::<f64>() / nodes.len() as f64
    }

    /// A lever tying the tip and mid-span of a cantilever, moved to
    /// δ = 1 mm, against two independent calculations: (1) the same model
    /// under the lever's two loads at P = 1 N (each section's load spread
    /// equally over its 9 nodes), which is linear: the lever's force must
    /// be δ/δ₁ and the displacements P times those of the loads, to
    /// round-off; (2) beam theory's superposition of the loads `P c₁` at L
    /// and `P c₂` at a: Euler–Bernoulli's
    /// `δ/P = [c₁² L³/3 + c₁c₂ a²(3L − a)/3 + c₂² a³/3]/(E I)` below it,
    /// Timoshenko's (plus `[c₁² L + 2c₁c₂ a + c₂² a]/(κ G A)`) above it
    /// (measured: `+2.2 %` and `−2.4 %`, the clamped root's warping
    /// restrained). Dropping a point's coefficient or swapping the two
    /// breaks (1) by far more than its tolerance, a `10 %` stiffness error (2).
    #[test]
    fn lever_holds_its_displacement_with_the_force_of_the_equivalent_loads() {
        let delta = 1e-3;
        let lever = cantilever(&format!(
            r#"
[[levers]]
name = "lever"
value = {delta}
points = [
  {{ body = "beam", where = {{ y = 0.5 }}, component = "z", coefficient = {C_TIP} }},
  {{ body = "beam", where = {{ y = 0.25 }}, component = "z", coefficient = {C_MID} }},
]
"#
        ));
        let loads = cantilever(&format!(
            r#"
[[loads]]
name = "tip"
body = "beam"
where = {{ y = 0.5 }}
force_per_node = [0.0, 0.0, {}]

[[loads]]
name = "mid"
body = "beam"
where = {{ y = 0.25 }}
force_per_node = [0.0, 0.0, {}]
"#,
            C_TIP / 9.0,
            C_MID / 9.0
        ));
        let run = |m: &Model| crate::analysis::run(m, &Default::default(), &mut crate::analysis::Silent).unwrap();
        let (with_lever, with_loads) = (run(&lever), run(&loads));
        assert!(with_lever.failure.is_none());
        let delta_1 = C_TIP * mean_uz(&loads, &with_loads.u, 0.5) + C_MID * mean_uz(&loads, &with_loads.u, 0.25);
        let p = delta / delta_1;
        let l = &with_lever.levers[0];
        eprintln!("lever: P = {:.6e} N at δ = {:.6e} m; the loads' δ/P = {delta_1:.6e} m/N", l.force, l.displacement);
        assert!((l.displacement / delta - 1.0).abs() < 1e-10, "lever displacement {}", l.displacement);
        assert!((l.force / p - 1.0).abs() < 1e-8, "lever force {} against {p}", l.force);
        let scale = with_lever.u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in with_lever.u.iter().zip(&with_loads.u) {
            assert!((a - p * b).abs() <= 1e-8 * scale, "u {a} against {}", p * b);
        }
        // the support carries the lever's two pushes, P (c₁ + c₂)
        let root = with_lever.reaction("root").unwrap().force[2];
        assert!((root + p * (C_TIP + C_MID)).abs() < 1e-8 * p, "root reaction {root}");
        // beam theory brackets it: Euler–Bernoulli (no shear) below,
        // Timoshenko (shear κ = 5/6, the root's section free to warp) above
        let (e, nu, b, h, length, a): (f64, f64, f64, f64, f64, f64) = (200e9, 0.3, 0.02, 0.04, 0.5, 0.25);
        let i = b * h.powi(3) / 12.0;
        let bending = (C_TIP * C_TIP * length.powi(3) / 3.0
            + C_TIP * C_MID * a * a * (3.0 * length - a) / 3.0
            + C_MID * C_MID * a.powi(3) / 3.0)
            / (e * i);
        let shear = (C_TIP * C_TIP * length + 2.0 * C_TIP * C_MID * a + C_MID * C_MID * a)
            / (5.0 / 6.0 * e / (2.0 * (1.0 + nu)) * b * h);
        eprintln!(
            "lever: δ/P = {delta_1:.6e} m/N; Euler–Bernoulli {bending:.6e} ({:+.3} %), Timoshenko {:.6e} ({:+.3} %)",
            100.0 * (delta_1 / bending - 1.0),
            bending + shear,
            100.0 * (delta_1 / (bending + shear) - 1.0)
        );
        assert!(bending < delta_1 && delta_1 < bending + shear, "δ/P {delta_1} outside beam theory's bracket");
        // the history records the lever's force and displacement per increment
        let last = with_lever.history.last().unwrap();
        assert_eq!(last.levers[0], *l);
    }
}
