//! The unknowns and the load factor: displacements (current, committed,
//! and the last converged increment's change, for the extrapolated start
//! of the next), λ, and the tangent branch the increment is solved with.

use crate::assembly::At;
use crate::materials::Predictor;

/// Displacements and load factor.
#[derive(Debug)]
pub(crate) struct Kinematics {
    /// Displacements (3 per node).
    pub u: Vec<f64>,
    /// Those of the last converged increment.
    pub(crate) u_committed: Vec<f64>,
    /// Displacement change of the last converged increment.
    pub(crate) u_step: Vec<f64>,
    /// Current load factor.
    pub lambda: f64,
    /// That of the last converged increment.
    pub(crate) lambda_committed: f64,
    /// Tangent branch of points on their yield surface or Coulomb cone
    /// (elastic/sticking after a failed attempt: `Incremental::cautious`).
    pub predictor: Predictor,
    /// The present solve started on the secant of the last increment, not
    /// at the committed state.
    pub(crate) on_secant: bool,
    /// The last correction, for a line search (`solver.line_search`).
    pub line: Option<Line>,
    /// The iterate `u` was reached from by one linear step (the last
    /// Newton correction, or the committed state for the secant start),
    /// valid while `linear_step`: the elements' geometric stiffness takes
    /// the stress linearized along that step (`At::u_before`).
    pub(crate) u_before: Vec<f64>,
    /// `u` was reached from `u_before` by one linear step.
    pub(crate) linear_step: bool,
    /// The viscous regularisation's step of a path increment (`At::viscous_step`).
    pub(crate) viscous_step: Option<f64>,
}

impl Kinematics {
    /// Zero displacements at λ = 0.
    pub fn new(n_dofs: usize) -> Self {
        Self {
            u: vec![0.0; n_dofs],
            u_committed: vec![0.0; n_dofs],
            u_step: vec![0.0; n_dofs],
            lambda: 0.0,
            lambda_committed: 0.0,
            predictor: Predictor::Loading,
            on_secant: false,
            line: None,
            u_before: vec![0.0; n_dofs],
            linear_step: false,
            viscous_step: None,
        }
    }

    /// The state the contributions are evaluated at.
    pub fn at(&self) -> At<'_> {
        At {
            u: &self.u,
            u_committed: &self.u_committed,
            lambda: self.lambda,
            predictor: self.predictor,
            u_before: self.linear_step.then_some(&self.u_before[..]),
            viscous_step: self.viscous_step,
        }
    }

    /// Starts the next solve at `u_committed + ratio · u_step`; true if that
    /// moved anything (a secant start rather than the committed state).
    pub fn extrapolate(&mut self, ratio: f64) -> bool {
        for ((u, c), s) in self.u.iter_mut().zip(&self.u_committed).zip(&self.u_step) {
            *u = c + ratio * s;
        }
        self.on_secant = ratio > 0.0 && self.u_step.iter().any(|&s| s != 0.0);
        self.u_before.copy_from_slice(&self.u_committed);
        self.linear_step = true;
        self.on_secant
    }

    /// A Newton correction is about to move `u`: the present iterate is
    /// the one the next is reached from.
    pub(crate) fn before_correction(&mut self) {
        self.u_before.copy_from_slice(&self.u);
        self.linear_step = true;
    }

    /// The increment converged: its state becomes the committed one.
    pub fn commit(&mut self) {
        for ((s, u), c) in self.u_step.iter_mut().zip(&self.u).zip(&self.u_committed) {
            *s = u - c;
        }
        self.u_committed.copy_from_slice(&self.u);
        self.lambda_committed = self.lambda;
        self.linear_step = false;
    }

    /// Back to the committed state.
    pub fn restore(&mut self) {
        self.u.copy_from_slice(&self.u_committed);
        self.lambda = self.lambda_committed;
        self.linear_step = false;
    }

    /// Squared norm of the change since the committed state.
    pub(crate) fn increment2(&self) -> f64 {
        self.u.iter().zip(&self.u_committed).map(|(a, b)| (a - b) * (a - b)).sum()
    }
}

/// The last correction, for a line search along it (`structure/line.rs`).
#[derive(Debug)]
pub(crate) struct Line {
    /// The full correction by DOF (0 at fixed and prescribed DOFs).
    pub du: Vec<f64>,
    /// `Δu·R` at its start.
    pub start: f64,
    /// The fraction of it applied now.
    pub eta: f64,
}
