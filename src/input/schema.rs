//! The model file as written by the user (TOML), before validation.
//!
//! Every table denies unknown keys and every word-valued key is an enum, so
//! a misspelt key or value is refused by the TOML reader with its line and
//! the keys or values allowed there, instead of being silently ignored.
//! Where one key chooses what the others mean (`hardening`, a section's
//! `shape`, an indenter's `shape`, a contact's `method`) the table is an
//! enum with exactly the keys of each variant ([`tagged`]). The meaning,
//! unit and default of every key are in `docs/model-format.md`; the values
//! are checked in the other files of `model`.
//!
//! The same types give the model file's JSON Schema (`cufem schema`,
//! [`json`]): `JsonSchema` is derived beside `Deserialize`, the doc comments
//! of the keys are its descriptions, and the plain ranges the validation
//! checks come from one table ([`super::ranges`]), attached to their keys
//! by `#[schemars(transform = …)]`.

use serde::Deserialize;
use serde::de::{self, Deserializer};

use super::defaults;
use super::ranges::{self, AT_LEAST_ONE, FRACTION, TOLERANCE};
use crate::solver::reuse::ReuseSettings;

mod anisotropy;
mod bodies;
mod contact;
mod interfaces;
pub mod json;
mod materials;
mod section;
mod selection;
mod stepping;
mod symmetry;
pub(crate) mod tagged;
mod transient;
mod words;

pub(crate) use anisotropy::*;
pub(crate) use bodies::*;
pub(crate) use contact::*;
pub(crate) use interfaces::*;
pub use materials::*;
pub(crate) use section::*;
pub(crate) use selection::*;
pub(crate) use stepping::*;
pub(crate) use symmetry::*;
use tagged::tagged_table;
pub(crate) use transient::*;
pub use words::*;

/// A fixed-length array read from the model file. Unlike serde's `[T; N]`,
/// which silently drops extra elements, it rejects arrays of any length
/// other than `N` (a hardening-table row `[peeq, stress, 7.0]` is an error,
/// not a row of two numbers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact<T, const N: usize>(pub [T; N]);

impl<T, const N: usize> std::ops::Deref for Exact<T, N> {
    type Target = [T; N];
    fn deref(&self) -> &[T; N] {
        &self.0
    }
}

impl<T, const N: usize> From<Exact<T, N>> for [T; N] {
    fn from(e: Exact<T, N>) -> [T; N] {
        e.0
    }
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<T>::deserialize(d)?;
        let n = v.len();
        match <[T; N]>::try_from(v) {
            Ok(a) => Ok(Exact(a)),
            Err(_) => Err(de::Error::invalid_length(n, &format!("an array of length {N}").as_str())),
        }
    }
}

/// The model file (`cufem run MODEL.toml`): materials, bodies, their
/// supports and loads, contacts, the load history, the analysis and its
/// outputs. Every key is in docs/model-format.md.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ModelFile {
    /// Title printed in reports.
    #[schemars(transform = defaults::schema(defaults::TITLE))]
    pub title: Option<String>,
    /// Free text.
    #[schemars(transform = defaults::schema(defaults::DESCRIPTION))]
    pub description: Option<String>,
    /// The kind of analysis (`[analysis]`).
    #[serde(default)]
    pub analysis: AnalysisFile,
    /// Nonlinear solution controls.
    #[serde(default)]
    pub solver: SolverFile,
    /// Materials.
    #[serde(default)]
    pub materials: Vec<MaterialFile>,
    /// Bodies.
    #[serde(default)]
    pub bodies: Vec<BodyFile>,
    /// Displacement constraints.
    #[serde(default)]
    pub constraints: Vec<ConstraintFile>,
    /// Loads.
    #[serde(default)]
    pub loads: Vec<LoadFile>,
    /// Rigid levers: linear multi-point constraints with a prescribed value.
    #[serde(default)]
    pub levers: Vec<LeverFile>,
    /// Rigid indenters.
    #[serde(default)]
    pub indenters: Vec<IndenterFile>,
    /// Contacts between deformable bodies.
    #[serde(default)]
    pub contacts: Vec<ContactFile>,
    /// Probe points.
    #[serde(default)]
    pub probes: Vec<ProbeFile>,
    /// Sampled lines.
    #[serde(default)]
    pub lines: Vec<LineFile>,
    /// Load history: an ordered list of steps (default: one step to factor 1).
    #[serde(default)]
    pub steps: Vec<StepFile>,
    /// Output controls.
    #[serde(default)]
    pub output: OutputFile,
    /// Reference values (e.g. from the paper) printed beside the results.
    #[serde(default)]
    pub references: Vec<ReferenceFile>,
    /// Adaptive refinement (`cufem run` refines and solves again).
    #[serde(default)]
    pub adapt: Option<AdaptFile>,
    /// Planes of mirror symmetry.
    #[serde(default)]
    pub symmetry: Vec<SymmetryFile>,
}

/// `[analysis]`: the kind of analysis and its settings.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct AnalysisFile {
    /// `geometry = "linear"` (default) or `"nonlinear"` (total Lagrangian).
    #[schemars(transform = defaults::schema(Geometry::default()))]
    pub geometry: Option<Geometry>,
    /// `strain = "green_lagrange"` (default) or `"logarithmic"` (nonlinear geometry).
    #[schemars(transform = defaults::schema(StrainMeasure::default()))]
    pub strain: Option<StrainMeasure>,
    /// `type = "static"` (default), `"buckling"`, `"modal"` or `"transient"`.
    #[serde(rename = "type")]
    #[schemars(transform = defaults::schema(AnalysisType::default()))]
    pub kind: Option<AnalysisType>,
    /// Buckling and modal: the number of modes wanted.
    #[schemars(transform = ranges::MODES.schema())]
    pub modes: Option<usize>,
    /// Modal and transient: `mass = "consistent"` (default) or `"lumped"`.
    #[schemars(transform = defaults::schema(MassMatrix::default()))]
    pub mass: Option<MassMatrix>,
    /// Transient: the time (s) of one load step, λ ∈ [k, k + 1].
    #[schemars(transform = ranges::DURATION.schema())]
    pub duration: Option<f64>,
    /// Transient: Newmark's parameters (default the trapezoidal rule).
    #[schemars(transform = defaults::schema(defaults::NEWMARK))]
    pub newmark: Option<NewmarkFile>,
    /// Transient: Rayleigh damping.
    pub damping: Option<DampingFile>,
    /// Transient: uniform initial velocities of bodies.
    pub initial_velocities: Option<Vec<InitialVelocityFile>>,
    /// Transient: the time (s) between the frames of the ParaView series.
    pub output_interval: Option<f64>,
    /// Transient: `contact_forces = "implicit"` (default: the contact
    /// impulse at the end of the step) or `"newmark"`.
    #[schemars(transform = defaults::schema(ContactForcesFile::default()))]
    pub contact_forces: Option<ContactForcesFile>,
    /// Transient: `contact_mass = "redistributed"` (default: the contact
    /// nodes carry no mass) or `"kept"`.
    #[schemars(transform = defaults::schema(ContactMassFile::default()))]
    pub contact_mass: Option<ContactMassFile>,
    /// Transient: `interface_forces = "implicit"` (default: the cohesive
    /// interfaces' impulse at the end of the step) or `"newmark"`.
    #[schemars(transform = defaults::schema(InterfaceForcesFile::default()))]
    pub interface_forces: Option<InterfaceForcesFile>,
    /// Transient: `ply_damage_forces = "newmark"` (default: Newmark's
    /// average of the stresses) or `"implicit"` (the end-of-step stress at
    /// damaged ply points, `dynamics::ply_forces`).
    #[schemars(transform = defaults::schema(PlyDamageForcesFile::default()))]
    pub ply_damage_forces: Option<PlyDamageForcesFile>,
    /// A geometric imperfection from a buckling mode (nonlinear geometry).
    pub imperfection: Option<ImperfectionFile>,
}

/// `analysis.imperfection`: a buckling mode added to the geometry.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ImperfectionFile {
    /// Which buckling mode (1 = the lowest).
    #[schemars(transform = ranges::MODES.schema())]
    pub mode: usize,
    /// Its largest displacement component (m; the sign flips the shape).
    pub amplitude: f64,
}

/// `[adapt]`: adaptive refinement by the error estimate.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct AdaptFile {
    /// Stop below this relative error estimate in the energy norm (modal:
    /// the largest estimated relative frequency error of the modes followed).
    #[schemars(transform = ranges::ADAPT_TOLERANCE.with_default(defaults::ADAPT_TOLERANCE))]
    pub tolerance: Option<f64>,
    /// Modal: the lowest this many modes are followed (default: all of `analysis.modes`).
    #[schemars(transform = ranges::MODES.schema())]
    pub modes: Option<usize>,
    /// No mesh with more DOF is solved.
    #[schemars(transform = ranges::ADAPT_MAX_DOF.with_default(defaults::ADAPT_MAX_DOF))]
    pub max_dof: Option<usize>,
    /// Most refinements after the model's own mesh.
    #[schemars(transform = ranges::ADAPT_MAX_CYCLES.with_default(defaults::ADAPT_MAX_CYCLES))]
    pub max_cycles: Option<usize>,
    /// Dörfler's θ: the share of the squared estimate the marked elements hold.
    #[schemars(transform = FRACTION.with_default(defaults::ADAPT_FRACTION))]
    pub fraction: Option<f64>,
}

/// `[solver]`: load stepping and Newton controls.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolverFile {
    /// First Δλ = 1/increments (default 1 for a linear model, else 10).
    #[schemars(transform = AT_LEAST_ONE.schema())]
    pub increments: Option<usize>,
    /// Largest Δλ.
    #[schemars(transform = FRACTION.schema())]
    pub(crate) max_increment: Option<f64>,
    /// Smallest Δλ before giving up.
    #[schemars(transform = FRACTION.schema())]
    pub min_increment: Option<f64>,
    /// Newton corrections per attempt.
    #[schemars(transform = AT_LEAST_ONE.with_default(defaults::MAX_ITERATIONS))]
    pub max_iterations: Option<usize>,
    /// Converged when ‖R‖ ≤ this × the largest force norm.
    #[schemars(transform = TOLERANCE.with_default(defaults::RESIDUAL_TOLERANCE))]
    pub residual_tolerance: Option<f64>,
    /// …and ‖Δu‖ ≤ this × the increment's displacement.
    #[schemars(transform = TOLERANCE.with_default(defaults::DISPLACEMENT_TOLERANCE))]
    pub displacement_tolerance: Option<f64>,
    /// Δλ multiplier after a failed attempt.
    #[schemars(transform = ranges::CUTBACK_FACTOR.with_default(defaults::CUTBACK_FACTOR))]
    pub cutback_factor: Option<f64>,
    /// Δλ multiplier after an easy increment.
    #[schemars(transform = ranges::GROWTH_FACTOR.with_default(defaults::GROWTH_FACTOR))]
    pub(crate) growth_factor: Option<f64>,
    /// An increment converging in at most this many iterations is easy.
    #[schemars(transform = defaults::schema(defaults::EASY_ITERATIONS))]
    pub(crate) easy_iterations: Option<usize>,
    /// Newton gives up after this many corrections without a new smallest
    /// residual (`solver::newton::NewtonSettings::stagnation_iterations`).
    #[schemars(transform = AT_LEAST_ONE.schema())]
    pub(crate) stagnation_iterations: Option<usize>,
    /// Most converged increments of a load step (a transient one adds its time steps).
    #[schemars(transform = AT_LEAST_ONE.with_default(defaults::MAX_INCREMENTS))]
    pub max_increments: Option<usize>,
    /// Worker threads (default all cores; `--threads` takes precedence).
    #[schemars(transform = AT_LEAST_ONE.schema())]
    pub threads: Option<usize>,
    /// Solve with PCG preconditioned by the last factorization while it converges.
    #[schemars(transform = defaults::schema(defaults::REUSE_FACTORIZATION))]
    pub reuse_factorization: Option<bool>,
    /// Largest relative residual at which such a PCG solve stops.
    #[schemars(transform = TOLERANCE.with_default(ReuseSettings::default().tolerance))]
    pub(crate) krylov_tolerance: Option<f64>,
    /// `"single"` (default) or `"double"` precision factors.
    #[schemars(transform = defaults::schema(FactorPrecision::default()))]
    pub factor_precision: Option<FactorPrecision>,
    /// `"load"` (default) or `"arc_length"` (path following, `setup/path.rs`).
    #[schemars(transform = defaults::schema(Control::default()))]
    pub control: Option<Control>,
    /// Arc length of the first increment (m), `control = "arc_length"`.
    #[schemars(transform = ranges::POSITIVE.schema())]
    pub arc_length: Option<f64>,
    /// `"cylinder"` (default) or `"dissipation"`: what holds a path increment.
    #[schemars(transform = defaults::schema(PathConstraint::default()))]
    pub constraint: Option<PathConstraint>,
    /// Largest dissipation of one increment (J), `constraint = "dissipation"`.
    #[schemars(transform = ranges::POSITIVE.schema())]
    pub max_dissipation: Option<f64>,
    /// The path following ends at the first point with λ at least this.
    #[schemars(transform = ranges::MAX_LOAD_FACTOR.with_default(defaults::MAX_LOAD_FACTOR))]
    pub max_load_factor: Option<f64>,
    /// The path following ends once a probe's displacement passes a value.
    pub stop: Option<StopFile>,
    /// Load-step control by an error measure (`schema/stepping.rs`).
    pub step_control: Option<StepControlFile>,
    /// Backtracking along a Newton correction that overshoots.
    #[schemars(transform = defaults::schema(defaults::LINE_SEARCH))]
    pub(crate) line_search: Option<bool>,
    /// Which tangent's inertia each increment reports.
    pub inertia: Option<Inertia>,
}

/// `[[probes]]`: a point where the results are reported.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ProbeFile {
    /// Probe name.
    pub name: String,
    /// `[x, y, z]` (m), inside a body.
    #[schemars(transform = ranges::COORDINATE.items())]
    pub point: Exact<f64, 3>,
    /// The body to evaluate in (default the first containing the point).
    pub body: Option<String>,
}

/// `[[lines]]`: fields sampled along a segment (`line_<name>.csv`).
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LineFile {
    /// File stem: `line_<name>.csv`.
    pub name: String,
    /// Start point `[x, y, z]` (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    pub from: Exact<f64, 3>,
    /// End point `[x, y, z]` (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    pub to: Exact<f64, 3>,
    /// Equally spaced samples, both ends included.
    #[schemars(transform = ranges::LINE_POINTS.with_default(defaults::LINE_POINTS))]
    pub points: Option<usize>,
    /// The body to evaluate in (default the first containing each point).
    pub body: Option<String>,
    /// Quantities plotted as PNG.
    pub plot: Option<Vec<QuantityName>>,
}

/// `[output]`: which result files are written.
#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct OutputFile {
    /// Write `result.vtu`.
    #[schemars(transform = defaults::schema(defaults::VTU))]
    pub vtu: Option<bool>,
    /// Write the PNG plots.
    #[schemars(transform = defaults::schema(defaults::PLOTS))]
    pub(crate) plots: Option<bool>,
    /// How stress and peeq at points are recovered from the Gauss points.
    #[schemars(transform = defaults::schema(super::Recovery::default()))]
    pub recovery: Option<super::Recovery>,
    /// Also write `gauss.vtu` with the raw Gauss-point values.
    #[schemars(transform = defaults::schema(defaults::GAUSS_POINTS))]
    pub gauss_points: Option<bool>,
    /// The cells of the field VTUs: `"lagrange"` (one VTK Lagrange
    /// hexahedron per element) or `"linear"` (linear sub-cells).
    #[schemars(transform = defaults::schema(super::VtuCells::default()))]
    pub vtu_cells: Option<super::VtuCells>,
    /// Write `report.html`, the run's self-contained page.
    #[schemars(transform = defaults::schema(defaults::REPORT))]
    pub(crate) report: Option<bool>,
}

/// `[[references]]`: a published value to print beside ours.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ReferenceFile {
    /// Name of a `[[probes]]` entry.
    pub probe: String,
    /// A quantity name.
    pub quantity: QuantityName,
    /// The reference value (SI).
    pub value: f64,
    /// Where it comes from.
    pub source: String,
}

/// `[[steps]]`: one step of the load history.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct StepFile {
    /// Step name (its VTU file and `summary.json` entry).
    pub name: String,
    /// Factor of every item at the end of the step.
    #[schemars(transform = ranges::STEP_FACTOR.with_default(defaults::STEP_FACTOR))]
    pub factor: Option<f64>,
    /// Per-item factors (by indenter, constraint or load name) overriding `factor`.
    #[schemars(transform = ranges::STEP_FACTOR.values())]
    pub factors: Option<std::collections::BTreeMap<String, f64>>,
    /// Increments of the step.
    #[schemars(transform = ranges::COUNT.schema())]
    pub increments: Option<usize>,
    /// Largest Δλ, as a fraction of the step.
    #[schemars(transform = FRACTION.schema())]
    pub(crate) max_increment: Option<f64>,
    /// Smallest Δλ, as a fraction of the step.
    #[schemars(transform = FRACTION.schema())]
    pub min_increment: Option<f64>,
    /// Transient: this step's time (s), overriding `analysis.duration`.
    #[schemars(transform = ranges::DURATION.schema())]
    pub duration: Option<f64>,
}
