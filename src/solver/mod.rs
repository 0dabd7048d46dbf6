//! Solvers: the sparse direct linear solver (and its reuse as a
//! preconditioner), Newton–Raphson, and load stepping with cutbacks.
//! For large deformations: the generalized eigenproblem `K φ = μ B φ`
//! (linear buckling, modes; [`eigen`]) and arc-length path following
//! through limit points and snap-backs ([`arclength`]).

pub mod arclength;
pub(crate) mod bordered;
pub mod eigen;
pub mod krylov;
pub mod linear;
pub mod newton;
pub(crate) mod nonsymmetric;
pub mod reuse;
pub mod step_control;
pub mod stepping;
pub mod stop;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A request to stop the analysis at the next safe point, shared between
/// whoever may ask (a Ctrl-C handler, a deadline, a Python caller) and the
/// solver, which checks it between Newton iterations. The state the solver
/// then leaves is the last converged increment.
#[derive(Debug, Clone, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// A fresh, unrequested interrupt.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the solver to stop.
    pub fn request(&self) {
        self.0.store(true, Ordering::SeqCst);
    }

    /// True once a stop was requested.
    pub fn is_requested(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }

    /// The shared flag (for signal handlers that set it directly).
    pub fn flag(&self) -> Arc<AtomicBool> {
        self.0.clone()
    }
}
