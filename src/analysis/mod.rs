//! The analysis driver: model → structure → load stepping → solution.
//!
//! ```text
//! let structure = Structure::new(model)      // number, order, pattern, symbolic factorization
//! for each increment λ_n → λ_{n+1}:           // solver::stepping (cutbacks, growth)
//!     set λ, prescribe λ ū                     // Incremental::set_load_factor
//!     Newton: evaluate R, K; solve; update     // solver::newton
//!     commit Gauss-point history               // Incremental::commit
//!     record reactions and contact forces      // Recorder
//! ```

pub mod structure;

pub use structure::{ContactPoint, Structure, Timings};

use std::time::{Duration, Instant};

use crate::elements::{BodyGeometry, ElementError};
use crate::materials::PointState;
use crate::model::Model;
use crate::solver::linear::LinearError;
use crate::solver::newton::NonlinearProblem;
use crate::solver::stepping::{self, Cutback, Increment, Observer, SteppingError};
use crate::voigt::Voigt;

/// Errors that stop an analysis before it can start (a non-convergence is
/// not an error: it is reported in [`Solution::failure`]).
#[derive(Debug, thiserror::Error)]
pub enum AnalysisError {
    /// Element geometry.
    #[error(transparent)]
    Element(#[from] ElementError),
    /// Linear algebra.
    #[error(transparent)]
    Linear(#[from] LinearError),
}

/// One row of the load history (after a converged increment).
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryRow {
    /// Increment index (1-based).
    pub increment: usize,
    /// Load factor.
    pub lambda: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// Resultant reaction per constraint set (N).
    pub reactions: Vec<[f64; 3]>,
    /// Per indenter then pair contact: resultant force on the body (N) and largest penetration (m).
    pub contact: Vec<([f64; 3], f64)>,
    /// Plastic Gauss points.
    pub plastic_points: usize,
}

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
}

/// Receives progress while the analysis runs.
pub trait Progress {
    /// Called once the structure is set up.
    fn start(&mut self, _model: &Model, _equations: usize) {}
    /// Called after each converged increment.
    fn increment(&mut self, _log: &IncrementLog) {}
    /// Called after each failed attempt.
    fn cutback(&mut self, _cutback: &Cutback) {}
}

/// A progress sink that ignores everything.
pub struct Silent;
impl Progress for Silent {}

/// The result of an analysis (the last converged state if it stopped early).
#[derive(Debug, Clone)]
pub struct Solution {
    /// Displacements, 3 per node.
    pub u: Vec<f64>,
    /// Committed Gauss-point states.
    pub states: Vec<PointState>,
    /// Gauss-point stresses of the final (converged) state.
    pub stresses: Vec<Voigt>,
    /// Geometry caches per body.
    pub geometry: Vec<BodyGeometry>,
    /// First Gauss point of each body.
    pub gp_offsets: Vec<usize>,
    /// Load factor reached.
    pub lambda: f64,
    /// Reactions per constraint set.
    pub reactions: Vec<[f64; 3]>,
    /// Per indenter then pair contact: force on the body and largest penetration.
    pub contact: Vec<([f64; 3], f64)>,
    /// Final state of every contact point.
    pub contact_points: Vec<ContactPoint>,
    /// Sum of applied nodal loads at the final load factor (N).
    pub applied: [f64; 3],
    /// Load history.
    pub history: Vec<HistoryRow>,
    /// Converged increments.
    pub increments: Vec<Increment>,
    /// Failed attempts.
    pub cutbacks: Vec<Cutback>,
    /// Set when the analysis stopped before λ = 1.
    pub failure: Option<SteppingError>,
    /// Free DOFs.
    pub equations: usize,
    /// Entries of the Cholesky factor.
    pub factor_nnz: usize,
    /// Plastic Gauss points at the end.
    pub plastic_points: usize,
    /// Phase timings.
    pub timings: Timings,
    /// Wall time of the whole analysis.
    pub wall_time: Duration,
}

struct Recorder<'a> {
    history: Vec<HistoryRow>,
    increments: Vec<Increment>,
    cutbacks: Vec<Cutback>,
    progress: &'a mut dyn Progress,
}

impl Observer<Structure<'_>> for Recorder<'_> {
    fn converged(&mut self, s: &Structure<'_>, inc: &Increment) {
        let contact = s.contact_resultants();
        let max_penetration = contact.iter().map(|c| c.1).fold(0.0, f64::max);
        self.progress.increment(&IncrementLog {
            index: inc.index,
            lambda: inc.lambda,
            dlambda: inc.dlambda,
            iterations: inc.newton.iterations,
            residuals: inc.newton.residuals.clone(),
            plastic_points: s.plastic_points,
            cutbacks: inc.cutbacks,
            max_penetration,
        });
        self.history.push(HistoryRow {
            increment: inc.index,
            lambda: inc.lambda,
            iterations: inc.newton.iterations,
            reactions: s.reactions(),
            contact,
            plastic_points: s.plastic_points,
        });
        self.increments.push(inc.clone());
    }

    fn cut_back(&mut self, c: &Cutback) {
        self.progress.cutback(c);
        self.cutbacks.push(c.clone());
    }
}

/// Runs the analysis of `model`.
pub fn run(model: &Model, progress: &mut dyn Progress) -> Result<Solution, AnalysisError> {
    let start = Instant::now();
    let mut structure = Structure::new(model)?;
    progress.start(model, structure.n_equations());
    let mut recorder = Recorder { history: Vec::new(), increments: Vec::new(), cutbacks: Vec::new(), progress };
    let outcome = stepping::run(&mut structure, &model.solver.steps, &model.solver.newton, &mut recorder);
    let failure = outcome.err().map(|e| *e);
    if failure.is_some() {
        // refresh forces at the last converged state for reactions and contact output
        structure.evaluate()?;
    }
    let lambda = structure.lambda;
    let mut applied = [0.0; 3];
    for (d, f) in structure.f_ext.iter().enumerate() {
        applied[d % 3] += lambda * f;
    }
    Ok(Solution {
        reactions: structure.reactions(),
        contact: structure.contact_resultants(),
        contact_points: structure.contact.clone(),
        applied,
        lambda,
        equations: structure.n_equations(),
        factor_nnz: structure.factor_nnz(),
        plastic_points: structure.plastic_points,
        timings: structure.timings,
        u: structure.u,
        states: structure.committed,
        stresses: structure.stress,
        geometry: structure.geometry,
        gp_offsets: structure.gp_offsets,
        history: recorder.history,
        increments: recorder.increments,
        cutbacks: recorder.cutbacks,
        failure,
        wall_time: start.elapsed(),
    })
}

impl Solution {
    /// A view for field evaluation.
    pub fn fields<'a>(&'a self, model: &'a Model) -> crate::post::FieldView<'a> {
        crate::post::FieldView {
            mesh: &model.mesh,
            geometry: &self.geometry,
            materials: &model.materials,
            u: &self.u,
            states: &self.states,
            stresses: &self.stresses,
            gp_offsets: &self.gp_offsets,
        }
    }
}
