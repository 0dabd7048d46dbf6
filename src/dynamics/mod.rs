//! Inertia: the mass matrix of CUF bodies (`mass`) and the free-vibration
//! analysis built on it (`crate::analysis::modal`).
//!
//! With `u(x, y, z, t) = F_τ(x, z) N_i(y) u_τi(t)` the kinetic energy
//! `T = ½ ∫ ρ u̇ · u̇ dV` gives the mass matrix whose 3 × 3 fundamental
//! nucleus is diagonal,
//!
//! ```text
//! M^(τi,sj) = δ_kl ∫ ρ F_τ N_i F_s N_j dV,   k, l ∈ {x, y, z}
//! ```
//!
//! (Carrera, Cinefra, Petrolo & Zappino, *Finite Element Analysis of
//! Structures through Unified Formulation*, Wiley 2014, ch. 10): the same
//! node pairs as the stiffness, so it fits the stiffness's pattern and
//! scatter maps.

mod components;
pub mod energy;
pub mod impulse;
pub mod inertia;
pub mod mass;
pub mod ply_forces;
pub mod redistribution;
pub mod settings;
pub(crate) mod time_error;

pub(crate) use impulse::Impulses;
pub use impulse::{ContactForces, InterfaceForces};
pub(crate) use inertia::Inertia;

pub use mass::{MassError, MassKind};
pub use ply_forces::PlyDamageForces;
pub use redistribution::ContactMass;
pub(crate) use redistribution::Redistribution;
pub use settings::TransientSettings;
pub(crate) use time_error::TimeError;
