//! The model: reading a TOML model file and validating it into typed,
//! resolved data (materials, meshes, node sets, loads, contacts, outputs).
//!
//! Validation never panics on user input: every error names the model-file
//! key (as a path such as `bodies[1].section.thickness`), the offending
//! value and what is allowed. The file format is documented key by key in
//! `docs/model-format.md`.

pub mod analysis;
mod bodies;
mod budget;
pub mod constraints;
mod contacts;
mod indenters;
mod interfaces;
mod laminate;
mod levers;
mod material;
mod mirror;
mod overlap;
mod path;
mod plan_file;
mod preprocess;
mod refine;
mod restraint;
mod sections;
pub mod steps;
mod surface_contact;
mod symmetry;
pub mod transient;
mod zones;

use std::path::Path;

use crate::bc::{Constraint, Lever, Load};
use crate::contact::{Indenter, PairContact};
pub use crate::input::ModelError;
use crate::input::schema::{self, *};
use crate::input::{OutputSettings, Recovery, Reference, SolverSettings, defaults, invalid};
pub use crate::kinematics::Kinematics;
use crate::materials::Material;
use crate::mesh::{Body, Mesh};
use crate::quantity::Quantity;
use crate::values::{CellValues, Location};
pub use analysis::{BucklingSettings, Imperfection, ModalSettings};

pub(crate) use plan_file::adapted_text;
pub(crate) use plan_file::{TUBE_ALONG, TUBE_THROUGH, count_keys};
pub use refine::{AdaptSettings, BodyPlan, MAX_BUDGET, MeshPlan, SectionPlan};

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
    /// Displacement constraints: the file's, then the symmetry planes'.
    pub constraints: Vec<Constraint>,
    /// Every constrained DOF and contact coupling, resolved once
    /// ([`constraints::ConstraintHandler`]).
    pub constraint_handler: constraints::ConstraintHandler,
    /// Loads (nodal forces at load factor 1).
    pub loads: Vec<Load>,
    /// Rigid levers (`[[levers]]`).
    pub levers: Vec<Lever>,
    /// Rigid indenters.
    pub indenters: Vec<Indenter>,
    /// Deformable contacts.
    pub contacts: Vec<PairContact>,
    /// Cohesive interfaces between the plies of laminates.
    pub interfaces: Vec<crate::interfaces::Interface>,
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

/// What the elements of a model are made of: the meshes, their
/// Gauss-point values, the materials and the strain measure (a view of a
/// [`Model`], `Model::discretisation`).
#[derive(Debug, Clone, Copy)]
pub struct Discretisation<'m> {
    /// Bodies and node numbering.
    pub mesh: &'m Mesh,
    /// Gauss-point values of every body.
    pub cells: &'m [CellValues],
    /// Materials.
    pub materials: &'m [Material],
    /// Small strain or total Lagrangian.
    pub kinematics: Kinematics,
    /// Cohesive interfaces between plies.
    pub interfaces: &'m [crate::interfaces::Interface],
}

impl<'m> Discretisation<'m> {
    /// The finite-element state at displacements `u` with Gauss-point
    /// `states` (the first of body `b` at `gp_offsets[b]`) and ply `damage`.
    pub(crate) fn fe_state<'a>(
        &self,
        u: &'a [f64],
        states: &'a [crate::materials::PointState],
        gp_offsets: &'a [usize],
        damage: crate::assembly::DamageInput<'a>,
    ) -> crate::assembly::FeState<'a>
    where
        'm: 'a,
    {
        crate::assembly::FeState {
            mesh: self.mesh,
            geometry: self.cells,
            materials: self.materials,
            u,
            states,
            gp_offsets,
            kinematics: self.kinematics,
            damage,
        }
    }
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
    /// Refuses an adaptive run of this model asked for outside its file
    /// (the command line's `--adapt`) where the file's `[adapt]` would be
    /// refused: with `[[levers]]`.
    pub fn check_adaptive(&self) -> Result<(), ModelError> {
        if self.levers.is_empty() { Ok(()) } else { Err(levers::with_adapt("--adapt")) }
    }

    /// True if any contact has Coulomb friction (its tangent is unsymmetric).
    pub(crate) fn has_friction(&self) -> bool {
        self.indenters.iter().any(|i| i.friction.is_some()) || self.contacts.iter().any(|c| c.friction.is_some())
    }

    /// True if the tangent has an unsymmetric rest (solved by GMRES):
    /// Coulomb friction, or ply damage with its consistent tangent.
    pub(crate) fn has_unsymmetric_tangent(&self) -> bool {
        self.has_friction() || self.materials.iter().any(|m| m.damage.as_ref().is_some_and(|d| d.is_consistent()))
    }

    /// Reads and validates a model file.
    pub fn from_file(path: &Path) -> Result<Self, ModelError> {
        Self::from_file_with(path, Limits::machine())
    }

    /// Reads and validates a model file under explicit limits.
    pub fn from_file_with(path: &Path, limits: Limits) -> Result<Self, ModelError> {
        let (text, base) = crate::input::read_text(path)?;
        Self::parse_in(&text, limits, &base)
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
        let file = crate::input::parse(text)?;
        build(file, limits, base)
    }

    /// Parses and validates model-file text with its divisions replaced by
    /// `plan` (a refinement of the plan of the same text, e.g. by `crate::adapt`).
    pub fn parse_planned(text: &str, limits: Limits, base: &Path, plan: &MeshPlan) -> Result<Self, ModelError> {
        let text = plan_file::planned_text(text, plan)?;
        let file = crate::input::parse(&text)?;
        // the plan itself, not the refined file's: a doubled parametric
        // section counts its doublings from the original file's counts
        let mut model = build(file, limits, base)?;
        model.plan = plan.clone();
        Ok(model)
    }

    /// True if the problem is linear (no body yields, no contact, no
    /// cohesive interface, small strain).
    pub fn is_linear(&self) -> bool {
        is_linear(&self.mesh, &self.materials, &self.indenters, &self.contacts, &self.interfaces)
            && !self.kinematics.is_nonlinear()
    }

    /// The quantities of this model's CSV files, VTU and probes: every
    /// [`Quantity`], the failure indices only if a material has strengths.
    pub fn quantities(&self) -> Vec<Quantity> {
        Quantity::all_for(self.materials.iter().any(|m| m.strengths.is_some()))
    }

    /// The meshes, Gauss-point values, materials, kinematics and
    /// interfaces.
    pub(crate) fn discretisation(&self) -> Discretisation<'_> {
        Discretisation {
            mesh: &self.mesh,
            cells: &self.cells,
            materials: &self.materials,
            kinematics: self.kinematics,
            interfaces: &self.interfaces,
        }
    }

    /// Replaces the constraints and resolves the constraint handler again
    /// (a model changed in code: a patch test's boundary values).
    pub fn set_constraints(&mut self, constraints: Vec<Constraint>) {
        self.constraints = constraints;
        self.resolve_constraints();
    }

    /// Resolves the constraint handler from the present constraints,
    /// contacts and kinematics (after any of them changed in code).
    pub(crate) fn resolve_constraints(&mut self) {
        let current = self.kinematics.is_nonlinear();
        self.constraint_handler = constraints::ConstraintHandler::new(
            &self.mesh,
            &self.constraints,
            (&self.contacts, &self.interfaces),
            current,
        );
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

fn is_linear(
    mesh: &Mesh,
    materials: &[Material],
    indenters: &[Indenter],
    contacts: &[PairContact],
    interfaces: &[crate::interfaces::Interface],
) -> bool {
    mesh.bodies
        .iter()
        .all(|b| b.materials().iter().all(|&m| !materials[m].is_plastic() && materials[m].damage.is_none()))
        && indenters.is_empty()
        && contacts.is_empty()
        && interfaces.is_empty()
}

/// The constraint handler with the contacts' and interfaces' couplings
/// added, every body's restraint checked against it — not in a transient
/// analysis, whose mass holds a free body (`M/(β Δt²)` in the tangent
/// keeps every time step's system positive definite).
fn restrained(
    mesh: &Mesh,
    mut handler: constraints::ConstraintHandler,
    (indenters, contacts, interfaces): (&[Indenter], &[PairContact], &[crate::interfaces::Interface]),
    kinematics: Kinematics,
    kind: Option<schema::AnalysisType>,
) -> Result<constraints::ConstraintHandler, ModelError> {
    use schema::AnalysisType::{Modal, Transient};
    handler.couple(mesh, (contacts, interfaces), kinematics.is_nonlinear());
    if kind != Some(Transient) {
        restraint::check(mesh, &handler, indenters, contacts).map_err(|e| match e {
            // free–free modes were refused without a word on why (a new-user review)
            ModelError::Invalid { key, value, allowed } if kind == Some(Modal) => ModelError::Invalid {
                key,
                value,
                allowed: format!(
                    "{allowed}; a modal analysis too: its modes are those about a static state, which a free body \
                     does not have (free–free modes are not computed: docs/limitations.md)"
                ),
            },
            e => e,
        })?;
    }
    Ok(handler)
}

/// `solver.step_control.damage` only in a model that damages (a material
/// with ply damage, or cohesive interfaces): elsewhere it would control
/// nothing.
fn damage_step_control(
    file: &ModelFile,
    materials: &[Material],
    interfaces: &[crate::interfaces::Interface],
) -> Result<(), ModelError> {
    if let Some(d) = file.solver.step_control.and_then(|c| c.damage)
        && interfaces.is_empty()
        && !materials.iter().any(|m| m.damage.is_some())
    {
        return Err(invalid(
            "solver.step_control.damage",
            crate::numbers::number(d),
            "only in a model that damages: a material with [materials.damage] or cohesive interfaces",
        ));
    }
    Ok(())
}

/// The solver's settings (`solver`), and the reuse of worn factors for
/// loose solves off in a model whose materials damage: their loose solves
/// steer a softening path onto another branch (examples/laminate_drop_weight_damage.toml
/// with them breaks fibres at 1.98 ms that it does not break without, 4 → 42
/// cutbacks, 27.3 → 32.4 s on one thread; 30 cutbacks each at
/// `krylov_tolerance` 0.09 and 0.11, against 4 without them), where the
/// tube's drop weight saves 36 of 242 factorizations (`solver::reuse`).
fn solver_settings(file: &ModelFile, materials: &[Material], linear: bool) -> Result<SolverSettings, ModelError> {
    let mut solver = crate::input::validate::solver_settings(&file.solver, linear)?;
    solver.reuse.worn_for_loose = !materials.iter().any(|m| m.damage.is_some());
    Ok(solver)
}

fn build(file: ModelFile, limits: Limits, base: &Path) -> Result<Model, ModelError> {
    crate::input::validate::names(&file)?;
    interfaces::check(&file)?;
    levers::combinations(&file)?;
    let mut materials = material::materials(&file.materials)?;
    let planes = symmetry::planes(&file.symmetry)?;
    let mut warnings = Vec::new();
    material::density_warnings(&file.materials, &materials, &mut warnings);
    material::strength_warnings(&file.materials, &materials, &mut warnings);
    zones::radian_warnings(&file.bodies, &mut warnings);
    let bodies = bodies::Input { file: &file.bodies, analysis: &file.analysis, limits, base, planes: &planes };
    let (mesh, cells) = bodies::mesh(&bodies, &mut materials, &mut warnings)?;
    let planes = symmetry::placed(planes, &mesh)?;
    let interfaces = interfaces::interfaces(&file, &mesh, &materials, &mut warnings)?;
    let kinematics = analysis::kinematics(&file.analysis)?;
    let plan = refine::plan(&file)?;
    let adapt = refine::adapt_settings(file.adapt.as_ref())?;
    let (constraints, n_user, handler) = preprocess::constraints(&file.constraints, &mesh, &planes, &mut warnings)?;
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
    let constraint_handler =
        restrained(&mesh, handler, (&indenters, &contacts, &interfaces), kinematics, file.analysis.kind)?;
    preprocess::idle_loads(&loads, |d| constraint_handler.prescribed(d).is_some(), &mut warnings);
    let levers = levers::levers(&file.levers, &mesh, &constraint_handler, &indenters)?;
    let probes = preprocess::probes(&file.probes, &mesh, &planes)?;
    let lines = preprocess::lines(&file.lines, &mesh, &planes, &mut warnings)?;
    let symmetry = symmetry::resolve(planes, &mesh, (&constraints, n_user), &indenters, &contacts);
    let references = crate::input::validate::references(&file.references, &file.probes)?;
    let linear = is_linear(&mesh, &materials, &indenters, &contacts, &interfaces) && !kinematics.is_nonlinear();
    damage_step_control(&file, &materials, &interfaces)?;
    let mut solver = solver_settings(&file, &materials, linear)?;
    let loading = path::Loading {
        steps: &file.steps,
        constraints: &constraints,
        handler: &constraint_handler,
        loads: &loads,
        indenters: &indenters,
        contacts: &contacts,
        probes: &probes,
        secant_unloading: path::unloads_on_its_secant(&materials, !interfaces.is_empty()),
    };
    solver.path = path::settings(&file.solver, &solver, &loading)?;
    let output = output_settings(&file.output, &mesh)?;
    let item_names = steps::ItemNames {
        indenters: indenters.iter().map(|i| i.name.as_str()).collect(),
        constraints: constraints.iter().map(|c| c.name.as_str()).collect(),
        loads: loads.iter().map(|l| l.name.as_str()).collect(),
        levers: levers.iter().map(|l| l.name.as_str()).collect(),
        pushing: indenters.iter().map(|i| i.force.is_some()).collect(),
    };
    let mut steps = steps::steps(&file.steps, &item_names, &solver.steps)?;
    steps::idle_constraint_factors(&file.steps, &constraints[..n_user], &mut warnings);
    let parts = analysis::Parts {
        mesh: &mesh,
        materials: &materials,
        constraints: &constraint_handler,
        indenters: &indenters,
        contacts: &contacts,
        steps: file.steps.len(),
    };
    let kind = analysis::Kind::asked(&file.analysis);
    analysis::damage_combinations(kind, kinematics, &materials, solver.path.is_some())?;
    let buckling = analysis::buckling(&file.analysis, &parts)?;
    let imperfection = analysis::imperfection(&file.analysis, &parts)?;
    let modal = analysis::modal(&file.analysis, &parts)?;
    let transient = transient::transient(&file, &mut steps, &parts, solver.path.is_some(), &mut warnings)?;
    if let Some(t) = &transient {
        symmetry::check_velocities(&t.initial_velocities, &symmetry.planes, &mesh)?;
    }
    analysis::combinations(kind, solver.path.is_some())?;
    let modes = buckling.map(|b| b.modes).or(modal.map(|m| m.modes));
    analysis::adapt_combinations(adapt.as_ref(), modes)?;
    warnings.extend(analysis::eigen_warnings(modes, &mesh, &constraint_handler, !symmetry.planes.is_empty()));
    // a material's warning is found once per use (a cohesive law per
    // interface: printed three times, a new-user review): each once
    let mut seen = std::collections::HashSet::new();
    warnings.retain(|w| seen.insert((w.key.clone(), w.message.clone())));
    Ok(Model {
        title: file.title.unwrap_or_else(|| defaults::TITLE.into()),
        description: file.description.unwrap_or_else(|| defaults::DESCRIPTION.into()),
        materials,
        mesh,
        cells,
        constraints,
        constraint_handler,
        loads,
        levers,
        indenters,
        contacts,
        interfaces,
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

/// `[output]`, its recovery checked against the bodies: a continuous
/// projection is refused with a layered body.
fn output_settings(file: &schema::OutputFile, mesh: &Mesh) -> Result<OutputSettings, ModelError> {
    let output = crate::input::validate::output(file);
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
    Ok(output)
}

#[cfg(test)]
mod tests {
    use super::Model;

    /// The worn-factor reuse is off where plies damage, on elsewhere
    /// ([`solver_settings`]): the damaging laminate drop weight and the
    /// same laminate with cohesive interfaces only.
    #[test]
    fn worn_factors_serve_loose_solves_unless_a_material_damages() {
        let damaging = Model::parse(include_str!("../../examples/laminate_drop_weight_damage.toml")).unwrap();
        let cohesive = Model::parse(include_str!("../../examples/laminate_drop_weight.toml")).unwrap();
        assert!(!damaging.solver.reuse.worn_for_loose);
        assert!(cohesive.solver.reuse.worn_for_loose);
    }
}
