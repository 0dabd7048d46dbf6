//! # cufem — refined 1D CUF finite elements for elastoplastic contact
//!
//! `cufem` solves small-strain elastoplastic contact problems of compact and
//! thin-walled metallic structures with refined one-dimensional models of the
//! Carrera Unified Formulation (CUF), following Nagaraj, Kaleel, Carrera &
//! Petrolo, *Nonlinear analysis of compact and thin-walled metallic structures
//! including localized plasticity under contact conditions*.
//!
//! The displacement field of a body whose axis is `y` is
//! `u(x, y, z) = F_τ(x, z) N_i(y) u_τi` with Lagrange cross-section functions
//! `F_τ` (L4/L9/L16) and Lagrange beam functions `N_i` (B2/B3/B4), so every
//! unknown is a displacement. See `ARCHITECTURE.md` for the module map and the
//! data flow model file → mesh → assembly → Newton → output.

pub mod analysis;
pub mod assembly;
pub mod bc;
pub mod contact;
pub mod elements;
pub mod io;
pub mod materials;
pub mod mesh;
pub mod model;
pub mod post;
pub mod quadrature;
pub mod shape;
pub mod solver;
pub mod voigt;
