//! Solvers: the sparse direct linear solver, Newton–Raphson, and load
//! stepping with cutbacks.

pub mod linear;
pub mod newton;
pub mod stepping;
