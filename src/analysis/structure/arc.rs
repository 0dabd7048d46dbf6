//! What path following (`analysis::path`) needs of the structure beyond
//! the load-stepping traits: λ set without starting an increment, several
//! right-hand sides solved with one factorization of the present tangent,
//! a correction added by equation, and the reference load.

use super::Structure;
use crate::assembly::NO_EQ;
use crate::setup::steps::{self, Item};
use crate::solver::linear::LinearError;

impl Structure<'_> {
    /// Sets λ for the next evaluation (an iterate of the path: the loads,
    /// and any prescribed values, at λ; contact keeps its increment).
    pub(crate) fn set_path_load_factor(&mut self, lambda: f64) {
        self.state.lambda = lambda;
        self.elimination.set_load_factor(self.loading.steps, lambda);
    }

    /// The viscous regularisation's step of the path increments to come
    /// (`At::viscous_step`).
    pub(crate) fn set_path_viscous_step(&mut self, step: f64) {
        self.state.viscous_step = Some(step);
    }

    /// A new increment of the path starts from the committed state.
    pub(crate) fn start_path_increment(&mut self) {
        self.parts.contacts.start_increment();
    }

    /// Solves `K x = b` in place for every right-hand side (by equation)
    /// with the tangent of the last evaluation: one factorization, in
    /// double precision (`LDLᵀ` if the tangent is indefinite, past a limit
    /// point), then triangular solves. The model has no non-zero prescribed
    /// values nor force-controlled indenters (`setup::path`), so no
    /// elimination nor bordering applies.
    pub(crate) fn solve_columns(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), LinearError> {
        let Some((first, rest)) = rhs.split_first_mut() else { return Ok(()) };
        self.system.rhs.copy_from_slice(first);
        let solved = self.system.solve(true);
        first.copy_from_slice(&self.system.rhs);
        let mut solved = solved;
        for x in rest.iter_mut() {
            if solved.is_ok() {
                solved = self.system.solve_again(x);
            }
        }
        self.record_solver();
        solved
    }

    /// `u ← u + δu` with `δu` by equation.
    pub(crate) fn add_by_equation(&mut self, du: &[f64]) {
        self.state.linear_step = false;
        for (d, &e) in self.system.assembler.dofs.eq.iter().enumerate() {
            if e != NO_EQ {
                self.state.u[d] += du[e];
            }
        }
    }

    /// The external load at λ = 1 by equation (each load times its factor
    /// at the end of the history's one step).
    pub(crate) fn reference_load(&self) -> Vec<f64> {
        let eq = &self.system.assembler.dofs.eq;
        let mut f = vec![0.0; self.n_equations()];
        for (i, l) in self.loading.loads.iter().enumerate() {
            let a = steps::factor(self.loading.steps, Item::Load(i), 1.0);
            for (n, force) in &l.nodal_forces {
                for (k, v) in force.iter().enumerate() {
                    let e = eq[3 * n + k];
                    if e != NO_EQ {
                        f[e] += a * v;
                    }
                }
            }
        }
        f
    }
}
