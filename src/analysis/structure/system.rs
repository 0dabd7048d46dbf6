//! The linear system of a Newton correction: the tangent in the
//! assembler's lower-triangle pattern, the unsymmetric rest beside it (a
//! model with friction), the right-hand side, and the solver that
//! factorizes and reuses (`solver::reuse`).

use crate::assembly::{Assembler, Tangent};
use crate::solver::linear::{Cholesky, LinearError};
use crate::solver::nonsymmetric::NonSymmetric;
use crate::solver::reuse::{ReuseSettings, ReusingSolver, SolverStats};

/// Tangent, right-hand side and solver.
#[derive(Debug)]
pub(crate) struct LinearSystem {
    /// Numbering, pattern and scatter maps.
    pub(crate) assembler: Assembler,
    /// Tangent values of the last evaluation (pattern order).
    pub tangent: Vec<f64>,
    /// The unsymmetric rest of the tangent (a model with friction).
    pub rest: Option<NonSymmetric>,
    /// Per equation: the residual of the last evaluation; in a correction
    /// the right-hand side, then the solution.
    pub rhs: Vec<f64>,
    /// Per DOF: the residual `Σ` of the parts' forces of the last
    /// evaluation (at a constrained DOF: its reaction).
    pub imbalance: Vec<f64>,
    solver: ReusingSolver,
    /// Forcing term of the next solve (relative residual, capped while
    /// contact has not settled).
    pub forcing: f64,
    /// The last evaluation left the element tangents out
    /// (`structure/evaluation.rs`): `tangent` is not that of the present
    /// state.
    pub(crate) tangent_stale: bool,
    /// A tangent was formed (by an evaluation that wanted it): `tangent`
    /// holds the parts' stiffness of that evaluation.
    pub(crate) tangent_formed: bool,
    /// The last evaluation kept the tangent while the elements left their
    /// elastic stiffness (`structure/evaluation.rs`): `tangent` is theirs
    /// at the state before.
    pub(crate) elastic_onset: bool,
    /// The solver's factor is of `tangent` as it stands: factorized since
    /// the tangent was last formed.
    factor_of_tangent: bool,
    /// The residual's force scale and its history (the floor of the
    /// relative residual, `structure/evaluation.rs`).
    pub(super) force_scale: super::evaluation::ForceScale,
}

impl LinearSystem {
    /// The system of `assembler`'s pattern, factorized by `chol`.
    pub fn new(assembler: Assembler, chol: Cholesky, reuse: ReuseSettings, unsymmetric: bool, n_dofs: usize) -> Self {
        Self {
            tangent: vec![0.0; assembler.pattern.nnz()],
            rhs: vec![0.0; assembler.dofs.n_eq],
            assembler,
            rest: unsymmetric.then(NonSymmetric::default),
            imbalance: vec![0.0; n_dofs],
            solver: ReusingSolver::new(chol, reuse),
            forcing: 1.0,
            tangent_stale: false,
            tangent_formed: false,
            elastic_onset: false,
            factor_of_tangent: false,
            force_scale: Default::default(),
        }
    }

    /// Where the contributions add their stiffness (the rest cleared).
    pub fn tangent(&mut self) -> Tangent<'_> {
        if let Some(rest) = self.rest.as_mut() {
            rest.clear();
        }
        let (values, rest) = (&mut self.tangent, self.rest.as_mut());
        Tangent { assembler: &self.assembler, values, rest, weight: 1.0, wanted: true }
    }

    /// An evaluation formed the tangent anew: the factor is of another.
    pub(crate) fn tangent_changed(&mut self) {
        self.factor_of_tangent = false;
    }

    /// An evaluation kept the tangent formed before
    /// (`structure/evaluation.rs`, a constant tangent): if the factor is of
    /// an older one, the next solve factorizes this one, which the solves
    /// after it will reuse as their exact factor.
    pub(crate) fn keep_tangent(&mut self) {
        if !self.factor_of_tangent {
            self.solver.refactor_next();
        }
    }

    /// Records whether the solver factorized since `before` factorizations.
    fn note_factorizations(&mut self, before: usize) {
        if self.solver.stats().factorizations > before {
            self.factor_of_tangent = true;
        }
    }

    /// Asks the next solve to go on towards the relative residual `eta`
    /// once at its forcing term (`solver::reuse`, a Newton correction
    /// predicted to be the last).
    pub(crate) fn finish_next(&mut self, eta: f64) {
        self.solver.finish_next(eta);
    }

    /// True if the last solve reached the residual [`Self::finish_next`] asked for.
    pub(crate) fn finished(&self) -> bool {
        self.solver.finished()
    }

    /// Solves `K x = rhs` in place (`must_factor`: with the present tangent's
    /// own factor, for further right-hand sides).
    pub fn solve(&mut self, must_factor: bool) -> Result<(), LinearError> {
        let empty = NonSymmetric::default();
        let rest = self.rest.as_ref().unwrap_or(&empty);
        let pattern = &self.assembler.pattern;
        let before = self.solver.stats().factorizations;
        let solved =
            self.solver.solve_unsymmetric(pattern, &self.tangent, rest, &mut self.rhs, self.forcing, must_factor);
        self.note_factorizations(before);
        solved.map(|_| ())
    }

    /// Solves the bordered system `[K B; Bᵀ C] [x; a] = [rhs; rhs_a]`
    /// (`solver::bordered`; `K` symmetric: no unsymmetric rest) in place,
    /// reusing factorizations as [`Self::solve`] does.
    pub(crate) fn solve_bordered(
        &mut self,
        border: &crate::solver::bordered::Border<'_>,
        rhs_a: &mut [f64],
    ) -> Result<(), LinearError> {
        let (pattern, values) = (&self.assembler.pattern, &self.tangent[..]);
        let before = self.solver.stats().factorizations;
        let solved = self.solver.solve_bordered((pattern, values), border, &mut self.rhs, rhs_a, self.forcing);
        self.note_factorizations(before);
        solved.map(|_| ())
    }

    /// After [`Self::solve`] with `must_factor`: solves `K x = b` for a
    /// further right-hand side (`x` holds `b` on entry).
    pub(crate) fn solve_again(&mut self, x: &mut [f64]) -> Result<(), LinearError> {
        let empty = NonSymmetric::default();
        let rest = self.rest.as_ref().unwrap_or(&empty);
        self.solver.solve_again_unsymmetric(&self.assembler.pattern, &self.tangent, rest, x)
    }

    /// Negative pivots of the last factorized tangent.
    pub fn negative_pivots(&self) -> Option<usize> {
        self.solver.negative_pivots()
    }

    /// Factorizes the present (symmetric part of the) tangent and returns
    /// its negative pivots; `None` if the factorization failed.
    pub fn inertia(&mut self) -> Option<usize> {
        self.factor_of_tangent = false;
        self.solver.factorize_now(&self.tangent).ok()?;
        self.factor_of_tangent = true;
        self.solver.negative_pivots()
    }

    /// `K φ = μ B φ` for the lower triangles `k` and `b` on this system's
    /// pattern, with this system's factorization (`ReusingSolver::eigen`).
    pub fn eigen(
        &mut self,
        k: &[f64],
        b: &[f64],
        settings: &crate::solver::eigen::EigenSettings,
    ) -> Result<crate::solver::eigen::EigenSolution, crate::solver::eigen::EigenError> {
        // the eigensolver factorizes `k`, not the tangent
        self.factor_of_tangent = false;
        self.solver.eigen(&self.assembler.pattern, k, b, settings)
    }

    /// The solver's counters.
    pub(crate) fn stats(&self) -> &SolverStats {
        self.solver.stats()
    }

    /// Stored entries of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.solver.factor_nnz()
    }
}
