//! The one interface through which the parts of a structure — the elements,
//! the external loads, the contacts (and, next, inertia) — add to its
//! residual and tangent.
//!
//! The structure's residual is the sum of its parts' forces,
//! `R(u) = f_int(u) − λ f_ext − f_c(u) (+ M a …)`, and its tangent the sum of
//! their stiffnesses. A [`Contribution`] evaluates itself at a state
//! ([`At`]), adds its stiffness through a [`Tangent`] (the symmetric,
//! factorized pattern, and the unsymmetric rest beside it) and keeps its
//! nodal forces, which the structure sums in the order of its parts. It
//! owns its own history (Gauss-point states, contact slips) and commits it
//! only when an increment has converged.
//!
//! What is not a contribution: prescribed displacements and force-controlled
//! indenters constrain or border the linear system instead of adding to it
//! (`setup::constraints::Elimination`, `analysis::structure::force`).

use super::Assembler;
use crate::materials::Predictor;
use crate::solver::nonsymmetric::NonSymmetric;

/// The state a contribution is evaluated at.
#[derive(Debug, Clone, Copy)]
pub struct At<'a> {
    /// Displacements (3 per node, `3 · node + component`).
    pub u: &'a [f64],
    /// Displacements of the last converged increment.
    pub u_committed: &'a [f64],
    /// Load factor.
    pub lambda: f64,
    /// Tangent branch at points on their yield surface or Coulomb cone
    /// (elastic/sticking in the cautious retry of a failed increment).
    pub predictor: Predictor,
    /// The Newton iterate `u` was reached from by one linear step (the
    /// last correction, or the secant start of the increment from the
    /// committed state); `None` where `u` was set otherwise. The elements'
    /// geometric stiffness then takes the stress linearized along that step
    /// (`elements`, "The stress of the geometric stiffness").
    pub u_before: Option<&'a [f64]>,
    /// The step of the damage's and the interfaces' viscous regularisation
    /// where it is not the change of the load factor since the committed
    /// state: a path increment's pseudo-time (`analysis::path`), set for
    /// the increment before its iterations, so it does not change sign
    /// with λ.
    pub viscous_step: Option<f64>,
}

/// Where contributions add stiffness: the lower-triangle values of the
/// assembler's pattern, and — in a model with friction — the unsymmetric
/// rest of the tangent beside them.
#[derive(Debug)]
pub struct Tangent<'a> {
    /// Numbering and pattern.
    pub assembler: &'a Assembler,
    /// Lower-triangle values (pattern order).
    pub values: &'a mut [f64],
    /// The unsymmetric rest, `None` in a model whose tangent is symmetric.
    pub rest: Option<&'a mut NonSymmetric>,
    /// The factor on the blocks added through this tangent's methods: 1,
    /// but `1/γ` for the contacts of a transient analysis
    /// (`dynamics::impulse`).
    pub weight: f64,
    /// False when only the forces are asked for (Newton's evaluation that
    /// is expected to be the last of its solve,
    /// [`crate::solver::newton::NonlinearProblem::evaluate_residual`]): a
    /// part may then leave its stiffness out, and the values are not a
    /// tangent until the next evaluation that wants one.
    pub wanted: bool,
}

impl Tangent<'_> {
    /// Adds the symmetric block `k` between the DOFs of nodes `a` (rows) and
    /// `b` (columns) — and its transpose for `a ≠ b`.
    pub(crate) fn add_node_block(&mut self, a: usize, b: usize, k: &[[f64; 3]; 3]) {
        if self.weight == 1.0 {
            self.assembler.add_node_block(self.values, a, b, k);
        } else {
            let w = self.weight;
            self.assembler.add_node_block(self.values, a, b, &k.map(|r| r.map(|v| w * v)));
        }
    }

    /// Adds `sign · block` between nodes `a` (rows) and `b` (columns) to the
    /// unsymmetric rest (nothing where the tangent is symmetric).
    pub(crate) fn add_rest_block(&mut self, a: usize, b: usize, block: &[[f64; 3]; 3], sign: f64) {
        let Some(rest) = self.rest.as_deref_mut() else { return };
        let eq = &self.assembler.dofs.eq;
        for (i, row) in block.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                let (r, c) = (eq[3 * a + i], eq[3 * b + j]);
                if v != 0.0 && r != super::NO_EQ && c != super::NO_EQ {
                    rest.push_entry(r, c, self.weight * sign * v);
                }
            }
        }
    }

    /// Adds the outer product `u vᵀ` of two nodal vectors (`(node, [x, y,
    /// z])`) to the unsymmetric rest (nothing where the tangent is symmetric).
    pub(crate) fn add_rest_outer(&mut self, u: &[(usize, [f64; 3])], v: &[(usize, [f64; 3])]) {
        let Some(rest) = self.rest.as_deref_mut() else { return };
        let eq = &self.assembler.dofs.eq;
        let sparse = |w: &[(usize, [f64; 3])]| -> Vec<(usize, f64)> {
            w.iter()
                .flat_map(|(n, c)| (0..3).map(move |i| (3 * n + i, c[i])))
                .filter_map(|(d, x)| (eq[d] != super::NO_EQ && x != 0.0).then_some((eq[d], x)))
                .collect()
        };
        let w = self.weight;
        rest.push_outer(sparse(u).into_iter().map(|(e, x)| (e, w * x)), sparse(v));
    }
}

/// The timing phase a contribution's evaluation counts in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Element loop and material updates.
    Elements,
    /// Loads and other cheap terms (counted with the elements).
    Loads,
    /// Contact search and penalty terms.
    Contact,
    /// Cohesive interfaces between plies (counted with the elements).
    Interfaces,
}

/// A contribution's nodal forces of the last evaluation.
#[derive(Debug, Clone, Copy)]
pub struct Forces<'a> {
    /// Per DOF (`3 · node + component`).
    pub values: &'a [f64],
    /// Sign in the residual: `+1` for internal forces, `−1` for applied and
    /// contact forces (`R = f_int − λ f_ext − f_c`).
    pub sign: f64,
    /// True if they set the force scale of the convergence test (applied
    /// and contact forces; internal forces balance them).
    pub scale: bool,
    /// A force norm (N) the part sets as a scale beside its own forces (0
    /// for most): inertia's `‖M v_n‖/Δt`, the force that would stop the
    /// motion within the step — a body in free flight has no forces at
    /// all to measure its residual against.
    pub reference: f64,
}

/// A part of the structure's residual and tangent (module docs).
pub trait Contribution {
    /// The timing phase of [`Contribution::evaluate`].
    fn phase(&self) -> Phase;

    /// Evaluates at `at`: its stiffness into `tangent`, its forces kept for
    /// [`Contribution::forces`]. Returns how many of its points changed
    /// status (contact opening or closing, stick–slip): a non-smooth
    /// residual the solver must not trust a loose linear solve with.
    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize;

    /// Its nodal forces of the last evaluation.
    fn forces(&self) -> Forces<'_>;

    /// The increment converged at `at`: its trial history becomes the
    /// committed one.
    fn commit(&mut self, at: &At<'_>);

    /// Back to the committed history (a failed increment).
    fn restore(&mut self);

    /// True if the stiffness it would add at `at` is, to round-off, the
    /// one it added at its last evaluation that formed a tangent: where
    /// every part says so, the structure keeps the tangent it formed then
    /// instead of forming it again (`analysis::structure::evaluation`, a
    /// constant tangent). False unless the part knows.
    fn tangent_unchanged(&self, _at: &At<'_>) -> bool {
        false
    }

    /// True if every status change of its last evaluation was a release
    /// (contact points opening; none closing, none switching between stick
    /// and slip): a run of such evaluations ends, as each releases a point
    /// of a finite set and none takes one back (`solver::newton`, the
    /// releasing iterations). False unless the part knows.
    fn releasing(&self) -> bool {
        false
    }
}
