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
//!
//! # Using the library
//!
//! A [`Model`] is read from TOML text or a file (the format of
//! `docs/model-format.md`), solved by [`run`], and its [`Solution`] read by
//! name or written by [`write_results`]; these nouns sit at the crate's root:
//!
//! ```
//! use cufem::{Model, RunOptions, Silent};
//!
//! // a 1 m steel cantilever, 0.1 m square, 1 kN down at the tip
//! let model = Model::parse(r#"
//!     [[materials]]
//!     name = "steel"
//!     young_modulus = 200e9
//!     poisson_ratio = 0.3
//!
//!     [[bodies]]
//!     name = "beam"
//!     material = "steel"
//!     section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.1, elements = 1 }, z = { from = 0.0, to = 0.1, elements = 1 } }
//!     axis = { element = "B4", from = 0.0, to = 1.0, elements = 4 }
//!
//!     [[constraints]]
//!     name = "root"
//!     body = "beam"
//!     where = { y = 0.0 }
//!     fix = ["x", "y", "z"]
//!
//!     [[loads]]
//!     name = "tip"
//!     body = "beam"
//!     where = { y = 1.0 }
//!     total_force = [0.0, 0.0, -1000.0]
//!
//!     [[probes]]
//!     name = "tip"
//!     point = [0.05, 1.0, 0.05]
//! "#)?;
//! let solution = cufem::run(&model, &RunOptions::default(), &mut Silent)?;
//! assert!(solution.failure.is_none());
//!
//! // the support carries the load
//! let root = solution.reaction("root").unwrap();
//! assert!((root.force[2] - 1000.0).abs() < 1e-6);
//!
//! // fields at a probe: P L³/(3 E I) = 2.0e-4 m of bending, plus shear
//! let tip = solution.fields(&model).sample_probe(&model.probes[0]).unwrap();
//! assert!((tip.u[2] + 2.0e-4).abs() < 0.03 * 2.0e-4);
//!
//! // and everything the CLI writes (summary.json, VTU, CSV, PNG)
//! let dir = std::env::temp_dir().join("cufem_doc_example");
//! cufem::write_results(&model, &solution, &dir)?;
//! assert!(dir.join("summary.json").exists());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod adapt;
pub mod analysis;
pub(crate) mod assembly;
pub mod bc;
pub mod contact;
pub mod damage;
pub mod dynamics;
pub(crate) mod elements;
pub mod input;
pub(crate) mod interfaces;
pub mod io;
pub(crate) mod kinematics;
pub mod materials;
pub mod mesh;
pub(crate) mod newmark;
pub mod numbers;
pub mod post;
pub mod quadrature;
pub mod quantity;
pub mod setup;
pub mod shape;
pub mod size;
pub mod solver;
pub mod values;
pub mod voigt;

// The nouns a user of the library needs, at the crate's root: a model read
// from its file, the run and its options, its solution, and the files the CLI
// writes. The modules above stay public for the other crates of the
// workspace (ARCHITECTURE.md lists what each names).
pub use analysis::{Progress, RunOptions, Silent, Solution, run};
pub use io::write_results;
pub use setup::Model;
