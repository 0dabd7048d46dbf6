//! The model: reading a TOML model file and validating it into typed,
//! resolved data (materials, meshes, node sets, loads, contacts, outputs).
//!
//! Validation never panics on user input: every error names the model-file
//! key (as a path such as `bodies[1].section.thickness`), the offending
//! value and what is allowed. The file format is documented key by key in
//! `docs/model-format.md`.

pub mod analysis;
mod bodies;
mod bounds;
mod budget;
mod contacts;
mod defaults;
mod indenters;
mod laminate;
mod material;
mod mirror;
mod overlap;
mod path;
mod preprocess;
mod ranges;
mod refine;
mod restraint;
mod schema;
mod sections;
pub mod steps;
mod surface_contact;
mod symmetry;
pub mod transient;
mod validate;
mod zones;

use std::path::Path;

use crate::bc::{Constraint, Load};
use crate::contact::{Indenter, PairContact};
use crate::kinematics::Kinematics;
use crate::materials::Material;
use crate::mesh::{Body, Mesh, MeshError};
use crate::quantity::Quantity;
use crate::solver::newton::NewtonSettings;
use crate::solver::stepping::StepSettings;
use crate::values::{CellValues, ElementError, Location};
pub use analysis::{BucklingSettings, Imperfection, ModalSettings};
use schema::*;

pub use path::{DisplacementStop, PathSettings};
pub use refine::{AdaptSettings, BodyPlan, MAX_BUDGET, MeshPlan, SectionPlan};
pub use schema::json::json_schema;

/// Errors found while reading or validating a model.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// The file could not be read.
    #[error("cannot read model file {path}: {cause}")]
    Io {
        /// File path.
        path: String,
        /// Cause (kept out of the error chain: the message already says it).
        cause: std::io::Error,
    },
    /// The file is larger than a model file can be (or endless).
    #[error(
        "model file {path} holds more than {}: expected a model file of at most {} (model files are a few kB; \
         gmsh meshes are separate files, named by a section's `file` key)",
        crate::size::human_bytes(*.cap), crate::size::human_bytes(*.cap)
    )]
    TooBig {
        /// File path.
        path: String,
        /// The largest size read (bytes).
        cap: u64,
    },
    /// The file is not UTF-8 text.
    #[error("model file {path} is not UTF-8 text: invalid byte at line {line}, column {column} (byte {offset})")]
    NotText {
        /// File path.
        path: String,
        /// 1-based line of the first invalid byte.
        line: usize,
        /// 1-based column (in bytes) of the first invalid byte.
        column: usize,
        /// 0-based byte offset.
        offset: usize,
    },
    /// TOML syntax or type error (the message names the key and line).
    #[error("model file: {0}")]
    Parse(String),
    /// A value that is not allowed.
    #[error("{key} = {value}: expected {allowed}")]
    Invalid {
        /// Model-file key.
        key: String,
        /// The value given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Mesh construction error.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Element geometry error.
    #[error(transparent)]
    Element(#[from] ElementError),
    /// The model cannot fit in the memory allowed.
    #[error(
        "the model needs at least {} of memory ({} DOF; {}) but {} is available; use a coarser mesh, or \
         --max-memory to raise the limit",
        crate::size::human_bytes(*.needed), .dofs, .largest, crate::size::human_bytes(*.limit)
    )]
    TooLarge {
        /// Lower bound of the memory needed (bytes).
        needed: u64,
        /// Memory allowed (bytes).
        limit: u64,
        /// Degrees of freedom.
        dofs: u64,
        /// The body that made it too large, and its size.
        largest: String,
    },
}

/// Limits applied while reading a model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest memory an analysis may need (bytes); `None`: no limit.
    pub max_memory: Option<u64>,
}

impl Limits {
    /// The memory available on this machine (see [`crate::size::available_memory`]).
    pub fn machine() -> Self {
        Self { max_memory: crate::size::available_memory() }
    }

    /// No limit.
    pub fn none() -> Self {
        Self { max_memory: None }
    }
}

/// Cuts the lines of a parser message: the TOML parser quotes the offending
/// source line, which may be huge (a 100,000-deep nested array is one
/// 200 KB line), cut to 200 characters with its `^^^` marker; the message
/// itself, which names what is allowed (`unknown field `x`, expected one
/// of …` lists every key of the table), is kept whole up to 1,000
/// characters (it quotes the value given, which may be huge too).
fn shorten_lines(message: &str) -> String {
    message
        .lines()
        .map(|l| {
            let quoted = l.trim_start().starts_with('|')
                || l.split_once(" | ")
                    .is_some_and(|(n, _)| !n.is_empty() && n.trim().chars().all(|c| c.is_ascii_digit()));
            let max = if quoted { 200 } else { 1000 };
            if l.chars().count() > max {
                format!("{}…", l.chars().take(max).collect::<String>())
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn invalid(key: impl Into<String>, value: impl std::fmt::Display, allowed: impl Into<String>) -> ModelError {
    ModelError::Invalid { key: key.into(), value: shorten_lines(&value.to_string()), allowed: allowed.into() }
}

/// A probe point.
#[derive(Debug, Clone)]
pub struct Probe {
    /// Name.
    pub name: String,
    /// Point (m).
    pub point: [f64; 3],
    /// Body to evaluate in (`None`: the first body containing the point).
    pub body: Option<usize>,
    /// The elements holding the point (several on an element boundary),
    /// located once during preprocessing; for a point in the part a
    /// symmetry plane leaves out, those holding its image.
    pub locations: Vec<Location>,
}

/// A straight line sampled at equally spaced points.
#[derive(Debug, Clone)]
pub struct Line {
    /// Name (also the CSV file stem).
    pub name: String,
    /// Start point (m).
    pub from: [f64; 3],
    /// End point (m).
    pub to: [f64; 3],
    /// Number of samples (≥ 2).
    pub points: usize,
    /// Body (`None`: the first body containing each point).
    pub body: Option<usize>,
    /// Quantities plotted to PNG.
    pub plot: Vec<Quantity>,
}

/// A published value printed beside ours.
#[derive(Debug, Clone)]
pub struct Reference {
    /// Probe name.
    pub probe: String,
    /// Quantity.
    pub quantity: Quantity,
    /// Value in SI units.
    pub value: f64,
    /// Where it comes from.
    pub source: String,
}

/// Solution controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Load stepping.
    pub steps: StepSettings,
    /// Newton iteration.
    pub newton: NewtonSettings,
    /// Worker threads (`None`: all cores).
    pub threads: Option<usize>,
    /// Reuse of a factorization as the preconditioner of later solves.
    pub reuse: crate::solver::reuse::ReuseSettings,
    /// `solver.control = "arc_length"`: path following (`None`: load stepping).
    pub path: Option<PathSettings>,
    /// `solver.inertia`: which tangent's inertia `history.csv` reports
    /// (`None`: every converged one with nonlinear geometry, else the last
    /// factorized one).
    pub inertia: Option<InertiaReport>,
}

/// Which tangent's inertia (negative pivots) each increment reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InertiaReport {
    /// The converged tangent of every increment, factorized in double
    /// precision for it (one factorization per increment).
    EveryIncrement,
    /// The last tangent the solver factorized anyway (free; it may be some
    /// iterations or increments old).
    LastFactorization,
}

/// Output controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputSettings {
    /// Write `result.vtu`.
    pub vtu: bool,
    /// Write PNG plots.
    pub plots: bool,
    /// How stress and peeq are recovered at points.
    pub recovery: Recovery,
    /// Also write `gauss.vtu` with the raw Gauss-point values.
    pub gauss_points: bool,
}

/// How stress and peeq are evaluated at arbitrary points (`output.recovery`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Recovery {
    /// L2 projection of the Gauss-point values onto the CUF basis: a
    /// continuous field ([`crate::post::recovery`]).
    Projection,
    /// Element by element: the expansion's `C ε` in elastic elements, the
    /// limited interpolation of the Gauss-point values in yielded ones
    /// (discontinuous between elements). The default.
    #[default]
    Element,
}

/// A validated model.
#[derive(Debug, Clone)]
pub struct Model {
    /// Title.
    pub title: String,
    /// Description.
    pub description: String,
    /// Materials.
    pub materials: Vec<Material>,
    /// Bodies and node numbering.
    pub mesh: Mesh,
    /// Gauss-point values of every body (built once, used by the analysis
    /// and post-processing).
    pub cells: Vec<CellValues>,
    /// Displacement constraints.
    pub constraints: Vec<Constraint>,
    /// Loads (nodal forces at load factor 1).
    pub loads: Vec<Load>,
    /// Rigid indenters.
    pub indenters: Vec<Indenter>,
    /// Deformable contacts.
    pub contacts: Vec<PairContact>,
    /// Probes.
    pub probes: Vec<Probe>,
    /// Lines.
    pub lines: Vec<Line>,
    /// Published values.
    pub references: Vec<Reference>,
    /// Solver controls.
    pub solver: SolverSettings,
    /// The load history: at least one step ([`steps`]).
    pub steps: Vec<steps::Step>,
    /// Output controls.
    pub output: OutputSettings,
    /// What validation found suspicious but legal.
    pub warnings: Vec<Warning>,
    /// `[adapt]`: refine and solve again (`crate::adapt`); `None` without the table.
    pub adapt: Option<AdaptSettings>,
    /// The divisions adaptive refinement may change ([`MeshPlan`]).
    pub plan: MeshPlan,
    /// `analysis.geometry` and `analysis.strain`: small strain, or total Lagrangian (Green–Lagrange or logarithmic strain).
    pub kinematics: Kinematics,
    /// `analysis.type = "buckling"`: the linear buckling analysis after the
    /// static solution; `None` for a static analysis.
    pub buckling: Option<BucklingSettings>,
    /// `analysis.imperfection`: a scaled buckling mode as the stress-free
    /// initial shape (nonlinear geometry); `None` for the perfect shape.
    pub imperfection: Option<Imperfection>,
    /// `analysis.type = "modal"`: the natural frequencies and modes about
    /// the end of the static analysis; `None` otherwise.
    pub modal: Option<ModalSettings>,
    /// `analysis.type = "transient"`: implicit dynamics over the load
    /// history in time; `None` for a static analysis.
    pub transient: Option<crate::dynamics::TransientSettings>,
    /// Planes of mirror symmetry (`[[symmetry]]`; none in a full model) and
    /// which items lie across them.
    pub symmetry: crate::bc::symmetry::Symmetry,
}

/// Something suspicious but legal in a model (printed by `check` and `run`,
/// stored in `summary.json`).
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// Model-file key concerned.
    pub key: String,
    /// What is suspicious.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.key, self.message)
    }
}

impl Model {
    /// True if any contact has Coulomb friction (its tangent is unsymmetric).
    pub fn has_friction(&self) -> bool {
        self.indenters.iter().any(|i| i.friction.is_some()) || self.contacts.iter().any(|c| c.friction.is_some())
    }

    /// Reads and validates a model file.
    pub fn from_file(path: &Path) -> Result<Self, ModelError> {
        Self::from_file_with(path, Limits::machine())
    }

    /// Reads and validates a model file under explicit limits.
    pub fn from_file_with(path: &Path, limits: Limits) -> Result<Self, ModelError> {
        let (text, base) = Self::read_text(path)?;
        Self::parse_in(&text, limits, &base)
    }

    /// The text of a model file and the folder its relative paths start
    /// at (what [`Model::parse_in`] and [`Model::parse_planned`] take).
    pub fn read_text(path: &Path) -> Result<(String, std::path::PathBuf), ModelError> {
        let cap = crate::size::MAX_MODEL_FILE;
        let bytes = crate::size::read_at_most(path, cap)
            .map_err(|cause| ModelError::Io { path: path.display().to_string(), cause })?
            .ok_or_else(|| ModelError::TooBig { path: path.display().to_string(), cap })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let offset = e.utf8_error().valid_up_to();
            let before = &e.as_bytes()[..offset];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let column = offset - before.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1) + 1;
            ModelError::NotText { path: path.display().to_string(), line, column, offset }
        })?;
        let base = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        Ok((text, base.to_path_buf()))
    }

    /// Parses and validates model-file text, refusing a model that cannot
    /// fit in this machine's available memory.
    pub fn parse(text: &str) -> Result<Self, ModelError> {
        Self::parse_with(text, Limits::machine())
    }

    /// Parses and validates model-file text under explicit limits.
    /// Files named in the model (gmsh sections) are relative to the current folder.
    pub fn parse_with(text: &str, limits: Limits) -> Result<Self, ModelError> {
        Self::parse_in(text, limits, Path::new("."))
    }

    /// Parses and validates model-file text whose relative file paths
    /// (gmsh sections) start at the folder `base`.
    pub fn parse_in(text: &str, limits: Limits, base: &Path) -> Result<Self, ModelError> {
        let file: ModelFile = toml::from_str(text).map_err(|e| ModelError::Parse(shorten_lines(&e.to_string())))?;
        build(file, limits, base)
    }

    /// Parses and validates model-file text with its divisions replaced by
    /// `plan` (a refinement of the plan of the same text, e.g. by `crate::adapt`).
    pub fn parse_planned(text: &str, limits: Limits, base: &Path, plan: &MeshPlan) -> Result<Self, ModelError> {
        let mut file: ModelFile = toml::from_str(text).map_err(|e| ModelError::Parse(shorten_lines(&e.to_string())))?;
        refine::apply(&mut file, plan)?;
        build(file, limits, base)
    }

    /// True if the problem is linear (no body yields, no contact, small strain).
    pub fn is_linear(&self) -> bool {
        is_linear(&self.mesh, &self.materials, &self.indenters, &self.contacts) && !self.kinematics.is_nonlinear()
    }

    /// The quantities of this model's CSV files, VTU and probes: every
    /// [`Quantity`], the failure indices only if a material has strengths.
    pub fn quantities(&self) -> Vec<Quantity> {
        Quantity::all_for(self.materials.iter().any(|m| m.strengths.is_some()))
    }

    /// `analysis.type` as the file writes it: `"static"`, `"buckling"`,
    /// `"modal"` or `"transient"`.
    pub fn analysis_type(&self) -> &'static str {
        analysis::Kind::of(self.buckling.is_some(), self.modal.is_some(), self.transient.is_some()).word()
    }

    /// Number of degrees of freedom (3 per node, constrained ones included).
    pub fn n_dofs(&self) -> usize {
        self.mesh.n_dofs()
    }
}

/// The stiffness scale of a body for its penalties and bounds: the largest
/// Young's modulus of its materials.
pub fn body_young(body: &Body, materials: &[Material]) -> f64 {
    body.materials().iter().map(|&m| materials[m].young).fold(0.0, f64::max)
}

fn is_linear(mesh: &Mesh, materials: &[Material], indenters: &[Indenter], contacts: &[PairContact]) -> bool {
    mesh.bodies.iter().all(|b| b.materials().iter().all(|&m| !materials[m].is_plastic()))
        && indenters.is_empty()
        && contacts.is_empty()
}

fn build(file: ModelFile, limits: Limits, base: &Path) -> Result<Model, ModelError> {
    validate::names(&file)?;
    let mut materials = material::materials(&file.materials)?;
    let planes = symmetry::planes(&file.symmetry)?;
    let mut warnings = Vec::new();
    let bodies = bodies::Input { file: &file.bodies, analysis: &file.analysis, limits, base, planes: &planes };
    let (mesh, cells) = bodies::mesh(&bodies, &mut materials, &mut warnings)?;
    let planes = symmetry::placed(planes, &mesh)?;
    let kinematics = analysis::kinematics(&file.analysis)?;
    let plan = refine::plan(&file)?;
    let adapt = refine::adapt_settings(file.adapt.as_ref())?;
    let (constraints, n_user) = preprocess::constraints(&file.constraints, &mesh, &planes, &mut warnings)?;
    let loads = preprocess::loads(&file.loads, &mesh, &materials, &planes, &mut warnings)?;
    let transient = file.analysis.kind == Some(schema::AnalysisType::Transient);
    let indenters = indenters::indenters(&file.indenters, &mesh, &materials, transient, &planes, &mut warnings)?;
    let contacts = contacts::pair_contacts(&file.contacts, &mesh, &materials, &planes, &mut warnings)?;
    if kinematics.is_nonlinear()
        && let Some((k, c)) = contacts.iter().enumerate().find(|(_, c)| c.surface.is_none() && c.friction.is_some())
    {
        // node pairs in the current configuration are frictionless (contact::nodal_normal)
        return Err(invalid(
            format!("contacts[{k}].friction"),
            c.friction.as_ref().map_or(0.0, |f| f.coefficient),
            "no friction on node-to-node contact with analysis.geometry = \"nonlinear\" (method = \"surface\" \
             takes friction there, with the current normal; docs/contact.md)",
        ));
    }
    // in a transient analysis the mass holds a free body: M/(β Δt²) in the
    // tangent keeps every time step's system positive definite
    if !transient {
        restraint::check(&mesh, &constraints, &indenters, &contacts)?;
    }
    let probes = preprocess::probes(&file.probes, &mesh, &planes)?;
    let lines = preprocess::lines(&file.lines, &mesh, &planes, &mut warnings)?;
    let symmetry = symmetry::resolve(planes, &mesh, (&constraints, n_user), &indenters, &contacts);
    let references = validate::references(&file.references, &probes)?;
    let linear = is_linear(&mesh, &materials, &indenters, &contacts) && !kinematics.is_nonlinear();
    let mut solver = validate::solver_settings(&file.solver, linear)?;
    let loading = path::Loading {
        steps: &file.steps,
        constraints: &constraints,
        loads: &loads,
        indenters: &indenters,
        contacts: &contacts,
        probes: &probes,
    };
    solver.path = path::settings(&file.solver, &solver, &loading)?;
    let output = validate::output(&file.output);
    if output.recovery == Recovery::Projection
        && let Some(b) = mesh.bodies.iter().position(|b| b.is_layered())
    {
        return Err(invalid(
            "output.recovery",
            "\"projection\"",
            format!(
                "\"element\" with a layered body (bodies[{b}] has several materials: a continuous projection \
                 would smooth the stress jumps between its plies and zones)"
            ),
        ));
    }
    if mesh.bodies.iter().any(|b| b.is_layered()) {
        warnings.push(Warning {
            key: "bodies".into(),
            message: "layered bodies: no error estimate (its patch recovery would count the stress jumps between \
                      plies as error)"
                .into(),
        });
    }
    let item_names = steps::ItemNames {
        indenters: indenters.iter().map(|i| i.name.as_str()).collect(),
        constraints: constraints.iter().map(|c| c.name.as_str()).collect(),
        loads: loads.iter().map(|l| l.name.as_str()).collect(),
    };
    let mut steps = steps::steps(&file.steps, &item_names, &solver.steps)?;
    let parts = analysis::Parts {
        mesh: &mesh,
        materials: &materials,
        constraints: &constraints,
        indenters: &indenters,
        contacts: &contacts,
        steps: file.steps.len(),
    };
    let buckling = analysis::buckling(&file.analysis, &parts)?;
    let imperfection = analysis::imperfection(&file.analysis, &parts)?;
    let modal = analysis::modal(&file.analysis, &parts)?;
    let transient = transient::transient(&file, &mut steps, &parts, solver.path.is_some(), &mut warnings)?;
    if let Some(t) = &transient {
        symmetry::check_velocities(&t.initial_velocities, &symmetry.planes, &mesh)?;
    }
    let kind = analysis::Kind::of(buckling.is_some(), modal.is_some(), transient.is_some());
    analysis::combinations(kind, solver.path.is_some(), adapt.is_some())?;
    let modes = buckling.map(|b| b.modes).or(modal.map(|m| m.modes));
    warnings.extend(analysis::eigen_warnings(modes, &mesh, &constraints, !symmetry.planes.is_empty()));
    Ok(Model {
        title: file.title.unwrap_or_else(|| defaults::TITLE.into()),
        description: file.description.unwrap_or_else(|| defaults::DESCRIPTION.into()),
        materials,
        mesh,
        cells,
        constraints,
        loads,
        indenters,
        contacts,
        probes,
        lines,
        references,
        solver,
        steps,
        output,
        warnings,
        adapt,
        plan,
        kinematics,
        buckling,
        imperfection,
        modal,
        transient,
        symmetry,
    })
}
