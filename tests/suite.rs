//! Every integration test file of this folder as one test binary (Cargo.toml:
//! `autotests = false`, the target `suite`): one link of the library instead
//! of one per file, and the files' tests share the harness's threads. Each
//! file stays a module named after it (`cargo test --release --test suite
//! -- estimator::`) and a target of its own that plain `cargo test` does not
//! build (`cargo test --release --test estimator` still runs it alone).
//!
//! A file that stands alone declares its own `mod common;`, so the shared
//! helpers (tests/common) are loaded once per module here: deliberate.
#![allow(clippy::duplicate_mod)]
#[path = "adaptive_time.rs"]
mod adaptive_time;
#[path = "architecture.rs"]
mod architecture;
#[path = "assumed_shear.rs"]
mod assumed_shear;
#[path = "augmented.rs"]
mod augmented;
#[path = "buckling_error.rs"]
mod buckling_error;
#[path = "cattaneo_mindlin.rs"]
mod cattaneo_mindlin;
#[path = "contact.rs"]
mod contact;
#[path = "convergence.rs"]
mod convergence;
#[path = "current_contact.rs"]
mod current_contact;
#[path = "delamination_energy.rs"]
mod delamination_energy;
#[path = "docs.rs"]
mod docs;
#[path = "estimator.rs"]
mod estimator;
#[path = "friction.rs"]
mod friction;
#[path = "hostile_inputs.rs"]
mod hostile_inputs;
#[path = "infsup.rs"]
mod infsup;
#[path = "interfaces.rs"]
mod interfaces;
#[path = "kept_tangent.rs"]
mod kept_tangent;
#[path = "layered_estimate.rs"]
mod layered_estimate;
#[path = "linear_elements.rs"]
mod linear_elements;
#[path = "linear_verification.rs"]
mod linear_verification;
#[path = "load_history.rs"]
mod load_history;
#[path = "locking.rs"]
mod locking;
#[path = "modal_adapt.rs"]
mod modal_adapt;
#[path = "mode_error.rs"]
mod mode_error;
#[path = "open_section_torsion.rs"]
mod open_section_torsion;
#[path = "oracles_selfcheck.rs"]
mod oracles_selfcheck;
#[path = "plasticity.rs"]
mod plasticity;
#[path = "ply_damage_state.rs"]
mod ply_damage_state;
#[path = "recovery.rs"]
mod recovery;
#[path = "result_tables.rs"]
mod result_tables;
#[path = "reuse.rs"]
mod reuse;
#[path = "rigid_surface.rs"]
mod rigid_surface;
#[path = "schema.rs"]
mod schema;
#[path = "sections.rs"]
mod sections;
#[path = "state_errors.rs"]
mod state_errors;
#[path = "step_error.rs"]
mod step_error;
#[path = "surface_contact.rs"]
mod surface_contact;
#[path = "switch_on.rs"]
mod switch_on;
#[path = "user_mistakes.rs"]
mod user_mistakes;
