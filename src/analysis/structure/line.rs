//! The structure's side of Newton's line search (`solver::newton`,
//! `solver.line_search`, and the retry of a failed increment of a
//! frictionless contact model: `Structure::searches`): the last correction
//! kept by DOF, the slopes `Δu·R` of the energy along it, and moves along it.
//!
//! Only a correction that makes no jump of the prescribed values and moves
//! no force-controlled indenter nor lever force is searched along: a shortened prescribed
//! jump would be a different load, and an indenter's displacement and a
//! lever's force are further unknowns outside `u`. Nor in a model with friction: its tangent
//! is no energy's Hessian, so `Δu·R` is no slope (measured: both frictional
//! cantilevers failed their first increment with a search, stick and slip
//! flipping with every trial step). Nor a correction from an evaluation
//! in which contact points kept their contact at a secant start
//! (`contact::assembly::rigid`): its residual holds their tensions, the
//! residuals along the correction do not.

use super::Structure;
use super::kinematics::Line;
use crate::assembly::NO_EQ;
use crate::solver::newton::Correction;

impl Structure<'_> {
    /// Keeps the solved correction (in `system.rhs`, by equation) before it
    /// is applied, with its slope at the start; `searchable` false forgets
    /// the last one instead.
    pub(super) fn remember_correction(&mut self, searchable: bool) {
        // nor from an evaluation whose residual holds kept contact tensions
        // (`contact::assembly::rigid`): the slope at its end, without them,
        // would be another function's
        if !searchable || !self.searchable_model() || self.parts.contacts.kept_points() > 0 {
            self.state.line = None;
            return;
        }
        let eq = &self.system.assembler.dofs.eq;
        let du: Vec<f64> = eq
            .iter()
            .map(|&e| if e == NO_EQ || self.elimination.is_prescribed(e) { 0.0 } else { self.system.rhs[e] })
            .collect();
        let start = dot(&du, &self.system.imbalance);
        self.state.line = Some(Line { du, start, eta: 1.0 });
    }

    /// True if the model's corrections can be searched along at all: no
    /// force-controlled indenter or impactor, no lever, no friction (module
    /// docs).
    pub(super) fn searchable_model(&self) -> bool {
        !self.force.is_driven() && !self.levers.is_active() && !self.parts.contacts.is_frictional()
    }

    /// `(Δu·R(u_k), Δu·R(u))` at the last evaluation.
    pub(super) fn line_slopes(&self) -> Option<(f64, f64)> {
        let line = self.state.line.as_ref()?;
        Some((line.start, dot(&line.du, &self.system.imbalance)))
    }

    /// Moves `u` to `u_k + η Δu`.
    pub(super) fn line_step_to(&mut self, eta: f64) -> Option<Correction> {
        let line = self.state.line.as_mut()?;
        let change = eta - line.eta;
        let mut norm2 = 0.0;
        for (u, d) in self.state.u.iter_mut().zip(&line.du) {
            *u += change * d;
            norm2 += d * d;
        }
        line.eta = eta;
        Some(Correction { norm: eta * norm2.sqrt(), increment_norm: self.state.increment2().sqrt() })
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
