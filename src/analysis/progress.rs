//! What the analysis tells while it runs: the size once it is set up, a
//! log line per converged increment and every failed attempt, to a
//! [`Progress`] sink (the CLI's and the Python package's progress lines).

use crate::setup::Model;
use crate::size::MemoryEstimate;
use crate::solver::stepping::Cutback;

/// A log line per converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct IncrementLog {
    /// Increment index.
    pub index: usize,
    /// Load factor reached.
    pub lambda: f64,
    /// Its increment.
    pub dlambda: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// Relative residuals at each evaluation.
    pub residuals: Vec<f64>,
    /// Plastic Gauss points.
    pub plastic_points: usize,
    /// Cutbacks before convergence.
    pub cutbacks: usize,
    /// Largest contact penetration (m).
    pub max_penetration: f64,
    /// Negative pivots of the last factorized tangent.
    pub negative_pivots: Option<usize>,
}

/// The size of an analysis once it is set up.
#[derive(Debug, Clone)]
pub struct Setup {
    /// Equations (free DOFs).
    pub equations: usize,
    /// Stored entries of the Cholesky factor.
    pub factor_nnz: usize,
    /// Memory estimate.
    pub memory: MemoryEstimate,
}

/// Receives progress while the analysis runs.
pub trait Progress {
    /// Called once the structure is set up (equations ordered, symbolic
    /// factorization done).
    fn start(&mut self, _model: &Model, _setup: &Setup) {}
    /// Called after each converged increment.
    fn increment(&mut self, _log: &IncrementLog) {}
    /// Called after each failed attempt.
    fn cutback(&mut self, _cutback: &Cutback) {}
}

/// A progress sink that ignores everything.
pub struct Silent;
impl Progress for Silent {}
