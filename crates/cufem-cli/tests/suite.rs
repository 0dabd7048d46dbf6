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
#[path = "adapt.rs"]
mod adapt;
#[path = "buckling.rs"]
mod buckling;
#[path = "ccx.rs"]
mod ccx;
#[path = "ccx_dynamic.rs"]
mod ccx_dynamic;
#[path = "ccx_laminate.rs"]
mod ccx_laminate;
#[path = "ccx_modal.rs"]
mod ccx_modal;
#[path = "cli.rs"]
mod cli;
#[path = "composites.rs"]
mod composites;
#[path = "concentrated.rs"]
mod concentrated;
#[path = "delamination.rs"]
mod delamination;
#[path = "drop_weight_laminate.rs"]
mod drop_weight_laminate;
#[path = "dynamics.rs"]
mod dynamics;
#[path = "examples.rs"]
mod examples;
#[path = "fidelity.rs"]
mod fidelity;
#[path = "interference.rs"]
mod interference;
#[path = "interrupt.rs"]
mod interrupt;
#[path = "json_schema.rs"]
mod json_schema;
#[path = "large_deformation.rs"]
mod large_deformation;
#[path = "modal.rs"]
mod modal;
#[path = "path_following.rs"]
mod path_following;
#[path = "ply_damage.rs"]
mod ply_damage;
#[path = "ply_damage_transient.rs"]
mod ply_damage_transient;
#[path = "reliability.rs"]
mod reliability;
#[path = "report_html.rs"]
mod report_html;
#[path = "retry.rs"]
mod retry;
#[path = "roller_twins.rs"]
mod roller_twins;
#[path = "schema_docs.rs"]
mod schema_docs;
#[path = "silent_answers.rs"]
mod silent_answers;
#[path = "silent_solves.rs"]
mod silent_solves;
#[path = "snap_back.rs"]
mod snap_back;
#[path = "step_control.rs"]
mod step_control;
#[path = "symmetry.rs"]
mod symmetry;
#[path = "transient_checks.rs"]
mod transient_checks;
#[path = "tube_crush.rs"]
mod tube_crush;
