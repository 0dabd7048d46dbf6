//! The discretized structure as a nonlinear problem: residual
//! `R(u) = f_int(u) − λ f_ext − f_c(u)` on the free DOFs and its tangent
//! `K = K_tan + K_p` (paper eq. 18), for the solvers of `solver::newton`
//! and `solver::stepping`.
//!
//! The structure is a composition of parts with one job each, built by
//! [`Structure::new`] from a discretisation
//! ([`crate::setup::Discretisation`]), the model's constraint handler
//! ([`crate::setup::constraints::ConstraintHandler`]), what loads it
//! ([`Loading`]) and its settings ([`Settings`]), never the whole model:
//!
//! * the **contributions** (`structure/parts.rs`, each a
//!   `crate::assembly::Contribution`), evaluated in order into the
//!   tangent, their forces summed into the residual —
//!   `structure/elements.rs` (internal forces, element tangents, the
//!   Gauss-point history; first: it writes the whole tangent),
//!   `structure/loads.rs` (the external loads at λ),
//!   [`crate::contact::Contacts`] (every contact kind) and in a transient
//!   analysis `crate::dynamics::Inertia` (its forces `M a + C v` and
//!   stiffness `M/(βΔt²) + γC/(βΔt)`); a new capability is a new
//!   contribution there;
//! * [`crate::setup::constraints::Elimination`]: the prescribed
//!   displacements of the constraint handler and their elimination from
//!   each linear system (symmetric and unsymmetric alike);
//! * `structure/force.rs`: force-controlled indenters, whose displacement is
//!   an extra unknown bordering the linear system;
//! * `structure/system.rs`: the tangent, the right-hand side and the solver;
//! * `structure/kinematics.rs`: the displacements and λ;
//! * `structure/evaluation.rs`: one evaluation of all parts (with or
//!   without the element tangents), `structure/stepping.rs`: the load
//!   stepping's start, commit and restore of an increment.
//!
//! The structure answers with reports: [`Structure::setup`] (its size),
//! [`Structure::report`] (reactions, contact resultants, plastic points
//! and pivots at the present state), [`Structure::fields`] (the fields a
//! step end or frame keeps).

use std::time::Instant;

mod arc;
pub(crate) mod elements;
mod evaluation;
mod force;
mod inputs;
mod kinematics;
mod levers;
#[cfg(test)]
mod limit_tests;
mod line;
mod loads;
mod parts;
mod resultants;
mod stepping;
mod system;
mod transient;

pub use super::results::{ContactKind, ContactPoint, ContactResultant, ContactSet, Reaction, Timings};
use super::{Setup, StepFields};
use crate::assembly::{Assembler, NO_EQ};
use crate::contact::Contacts;
use crate::setup::constraints::{ConstraintHandler, Elimination};
use crate::setup::{Discretisation, Model};
use crate::solver::linear::{Cholesky, LinearError};
use crate::solver::newton::{Correction, Evaluation, NonlinearProblem};
use elements::Elements;
use force::ForceControl;
pub use inputs::{Loading, Settings};
use kinematics::Kinematics;
pub use levers::LeverResultant;
use levers::Levers;
use loads::Loads;
use parts::{Parts, Report};
use system::LinearSystem;

/// The structure: its parts (module docs), its unknowns and its linear
/// system.
pub struct Structure<'m> {
    /// What loads it.
    loading: Loading<'m>,
    /// The settings its parts read.
    settings: Settings<'m>,
    /// The constrained DOFs (the reactions' sources).
    constraints: &'m ConstraintHandler,
    /// The prescribed DOFs' elimination on this structure's numbering.
    elimination: Elimination,
    /// Displacements and λ.
    state: Kinematics,
    /// The contributions.
    parts: Parts<'m>,
    /// Force-controlled indenters.
    force: ForceControl<'m>,
    /// Rigid levers' forces.
    levers: Levers<'m>,
    /// Tangent, right-hand side and solver.
    system: LinearSystem,
    /// Timings, memory and pivots.
    report: Report,
}

/// The structure's state as the results record it, at the present
/// (usually converged) state.
#[derive(Debug, Clone)]
pub struct StateReport {
    /// Load factor.
    pub lambda: f64,
    /// Reaction of each constraint set ([`Structure::reactions`]).
    pub reactions: Vec<Reaction>,
    /// Per indenter, then per pair contact ([`Structure::contact_resultants`]).
    pub contacts: Vec<ContactResultant>,
    /// Plastic Gauss points in the last evaluation.
    pub plastic_points: usize,
    /// Per lever, its displacement and force ([`LeverResultant`]).
    pub levers: Vec<LeverResultant>,
    /// Negative pivots of the tangent ([`Structure::negative_pivots`]).
    pub negative_pivots: Option<usize>,
}

impl<'m> Structure<'m> {
    /// Builds numbering, pattern, factorization structure and initial state
    /// of `discretisation` under `constraints`, loaded by `loading`.
    ///
    /// With `settings.max_memory`, the memory of the analysis is estimated
    /// after the symbolic factorization (exact factor size) and the
    /// structure is refused with [`super::AnalysisError::TooLarge`] before
    /// the factor, the scatter maps and the element cache are allocated.
    pub fn new(
        discretisation: Discretisation<'m>,
        constraints: &'m ConstraintHandler,
        loading: Loading<'m>,
        settings: Settings<'m>,
    ) -> Result<Self, super::AnalysisError> {
        let t0 = Instant::now();
        let mesh = discretisation.mesh;
        let nonlinear = discretisation.kinematics.is_nonlinear();
        let numbering = constraints.numbering(mesh)?;
        let t_sym = Instant::now();
        let chol = Cholesky::analyze(&numbering.pattern)?;
        let symbolic = t_sym.elapsed();
        let memory = super::sizes::completed(settings.sizes, &numbering, &chol).memory();
        if let Some(limit) = settings.max_memory
            && memory.total() > limit
        {
            return Err(super::AnalysisError::TooLarge { estimate: memory, limit });
        }
        let elimination = constraints.elimination(&numbering);
        let mut assembler = Assembler::new(mesh, numbering);
        let mut elements = Elements::new(discretisation);
        elements.clock = settings.transient;
        let t_cache = Instant::now();
        // the elastic tangent is a constant only in small strain; the
        // total-Lagrangian one depends on u and S everywhere
        if !nonlinear {
            assembler.cache_elastic(&elements.inputs(&vec![0.0; mesh.n_dofs()]));
            elements.use_product_if_linear(&assembler);
        }
        let element_cache = t_cache.elapsed();
        let timings = Timings {
            setup: t0.elapsed(),
            ordering: assembler.ordering_time,
            pattern: assembler.pattern_time,
            symbolic,
            element_cache,
            ..Default::default()
        };
        let n_eq = assembler.dofs.n_eq;
        let inertia = match settings.transient {
            Some(transient) => Some(transient::inertia(&loading, transient, &assembler, &elements)?),
            None => None,
        };
        let massive = inertia.as_ref().map(|i| i.massive());
        let impulse =
            transient::impulse(&loading, !discretisation.interfaces.is_empty(), settings.transient, mesh.n_dofs());
        let parts = Parts {
            elements,
            loads: Loads::new(loading, mesh.n_dofs()),
            contacts: Contacts::new(mesh, loading.indenters, loading.contacts, nonlinear),
            interfaces: crate::interfaces::Interfaces::new(discretisation.interfaces, mesh.n_dofs())
                .in_time(settings.transient),
            inertia,
            impulse,
            time_error: massive.map(crate::dynamics::TimeError::new),
        };
        // friction's tangent and a loading ply's consistent one are unsymmetric
        let softening = discretisation.materials.iter().any(|m| m.damage.as_ref().is_some_and(|d| d.is_consistent()));
        let (reuse, unsymmetric) = (settings.solver.reuse, loading.has_friction() || softening);
        Ok(Self {
            state: Kinematics::new(mesh.n_dofs()),
            force: ForceControl::new(loading, mesh, settings.transient, n_eq),
            levers: Levers::new(loading.levers, loading.steps, &assembler.dofs.eq),
            system: LinearSystem::new(assembler, chol, reuse, unsymmetric, mesh.n_dofs()),
            report: Report { timings, memory, pivots: None },
            loading,
            settings,
            constraints,
            elimination,
            parts,
        })
    }

    /// The structure of `model` (its discretisation, constraint handler,
    /// loading and settings), refused above `max_memory` bytes.
    pub fn of_model(model: &'m Model, max_memory: Option<u64>) -> Result<Self, super::AnalysisError> {
        let settings = Settings::of(model, max_memory);
        Self::new(model.discretisation(), &model.constraint_handler, Loading::of(model), settings)
    }

    /// Equations, factor entries and the memory estimate.
    pub fn setup(&self) -> Setup {
        Setup { equations: self.n_equations(), factor_nnz: self.factor_nnz(), memory: self.report.memory.clone() }
    }

    /// λ, reactions, contact resultants, plastic points and negative pivots
    /// at the present state.
    pub fn report(&self) -> StateReport {
        StateReport {
            lambda: self.state.lambda,
            reactions: self.reactions(),
            contacts: self.contact_resultants(),
            plastic_points: self.plastic_points(),
            levers: self.levers.resultants(&self.state.u),
            negative_pivots: self.negative_pivots(),
        }
    }

    /// A copy of the present displacements, committed Gauss-point states
    /// and stresses.
    pub fn fields(&self) -> StepFields {
        let e = &self.parts.elements;
        StepFields { u: self.state.u.clone(), states: e.committed.clone(), stresses: self.stresses() }
    }

    /// The Gauss-point stresses of the last evaluation (all bodies).
    pub(crate) fn stresses(&self) -> Vec<crate::voigt::Voigt> {
        self.parts.elements.stresses(&self.system.assembler)
    }

    /// What loads the structure.
    pub fn loading(&self) -> &Loading<'m> {
        &self.loading
    }

    /// What the elements are made of.
    pub(crate) fn discretisation(&self) -> Discretisation<'m> {
        self.parts.elements.discretisation
    }

    /// Displacements, 3 per node (`3 · node + component`).
    pub fn displacements(&self) -> &[f64] {
        &self.state.u
    }

    /// Mutable displacements (for finite-difference checks of the tangent;
    /// the next [`NonlinearProblem::evaluate`] sees the change).
    pub fn displacements_mut(&mut self) -> &mut [f64] {
        self.state.linear_step = false;
        &mut self.state.u
    }

    /// Current load factor.
    pub fn load_factor(&self) -> f64 {
        self.state.lambda
    }

    /// Negative pivots of the tangent: the number of its negative
    /// eigenvalues (Sylvester), 0 while it is positive definite; a limit or
    /// bifurcation point is passed where it changes. With
    /// `solver.inertia = "every_increment"` (the default with
    /// `geometry = "nonlinear"`) that of the last committed (converged)
    /// state, factorized at the commit (one factorization per increment,
    /// which the next increment may reuse); otherwise that of the last
    /// factorization made, which may be some iterations or increments old
    /// (PCG reuses factors). `None` before the first or if it failed.
    pub fn negative_pivots(&self) -> Option<usize> {
        if self.inertia_every_increment() { self.report.pivots } else { self.system.negative_pivots() }
    }

    /// True if every converged tangent is factorized for its inertia
    /// (`solver.inertia`; by default with nonlinear geometry, not in a
    /// transient run, whose tangent carries `M / (β Δt²)`).
    fn inertia_every_increment(&self) -> bool {
        let every = match self.settings.solver.inertia {
            Some(report) => report == crate::input::InertiaReport::EveryIncrement,
            None => self.parts.elements.discretisation.kinematics.is_nonlinear(),
        };
        every && self.parts.inertia.is_none()
    }

    /// Plastic Gauss points in the last evaluation.
    pub fn plastic_points(&self) -> usize {
        self.parts.elements.last.plastic_points
    }

    /// Every contact point after the last evaluation (all indenter
    /// candidates, then all node pairs, in model order).
    pub fn contact_points(&self) -> &[ContactPoint] {
        self.parts.contacts.points()
    }

    /// The tangent's lower-triangular pattern (equation numbering).
    pub fn pattern(&self) -> &crate::solver::linear::LowerCsc {
        &self.system.assembler.pattern
    }

    /// Equation of a DOF, `None` if it is fixed.
    pub fn equation(&self, dof: usize) -> Option<usize> {
        let e = self.system.assembler.dofs.eq[dof];
        (e != NO_EQ).then_some(e)
    }

    /// Cumulative phase timings.
    pub fn timings(&self) -> &Timings {
        &self.report.timings
    }

    /// Number of equations (free DOFs).
    pub fn n_equations(&self) -> usize {
        self.system.assembler.dofs.n_eq
    }

    /// Tangent values of the last evaluation, in the order of the pattern
    /// (before any Dirichlet elimination).
    pub fn tangent_values(&self) -> &[f64] {
        &self.system.tangent
    }

    /// True if the tangent may be unsymmetric (a model with friction).
    pub fn is_unsymmetric(&self) -> bool {
        self.system.rest.is_some()
    }

    /// Entry `(row, col)` (equations) of the full tangent of the last
    /// evaluation, before any Dirichlet elimination: the lower-triangle
    /// values plus the unsymmetric rest (for finite-difference checks).
    pub fn tangent_entry(&self, row: usize, col: usize) -> f64 {
        let sym = self.pattern().find(row.max(col), row.min(col)).map_or(0.0, |p| self.system.tangent[p]);
        sym + self.system.rest.as_ref().map_or(0.0, |s| s.entry(row, col))
    }

    /// Residual `f_int − λ f_ext − f_c` per equation, from the last evaluation.
    pub fn residual(&self) -> &[f64] {
        &self.system.rhs
    }

    /// Stored entries of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.system.factor_nnz()
    }

    /// Reaction at every DOF, `f_int − λ f_ext − f_c` (zero up to the
    /// residual at free DOFs).
    pub(crate) fn nodal_imbalance(&self, dof: usize) -> f64 {
        self.system.imbalance[dof]
    }

    /// External loads at the current λ (per DOF).
    pub(crate) fn external_loads(&self) -> &[f64] {
        &self.parts.loads.f_ext
    }

    /// The elements' part: Gauss-point states, stresses and offsets.
    pub(crate) fn elements(&self) -> &Elements<'m> {
        &self.parts.elements
    }

    /// The cohesive interfaces' part: their points' damage.
    pub fn interfaces(&self) -> &crate::interfaces::Interfaces<'m> {
        &self.parts.interfaces
    }

    /// Sets a stress-free initial displacement (a geometric imperfection,
    /// per DOF) for a total-Lagrangian analysis, before the first evaluation.
    pub(crate) fn set_imperfection(&mut self, u0: Vec<f64>) {
        self.parts.elements.initial = Some(u0);
    }

    /// The stress stiffness `K_σ` of the present Gauss-point stresses, in
    /// pattern order (linear buckling).
    pub(crate) fn stress_stiffness(&self) -> Vec<f64> {
        let a = &self.system.assembler;
        let mut kg = vec![0.0; a.pattern.nnz()];
        let u = self.displacements();
        a.assemble_geometric(&self.parts.elements.inputs(u), &self.stresses(), &mut kg);
        kg
    }

    /// The tangent of the last evaluation and the mass matrix of `kind`
    /// (lower triangles on [`Self::pattern`]), with the prescribed DOFs
    /// fixed in both (free vibration, `analysis::modal`).
    pub(crate) fn vibration_matrices(
        &self,
        kind: crate::dynamics::MassKind,
    ) -> Result<(Vec<f64>, Vec<f64>), crate::dynamics::MassError> {
        use crate::dynamics::mass;
        let (d, a) = (self.discretisation(), &self.system.assembler);
        let densities = mass::densities(d.mesh, d.materials)?;
        let mut m = mass::assemble(a, d.mesh, d.cells, &densities, kind, None)?;
        let mut k = self.system.tangent.clone();
        self.elimination.fix_for_eigen(|e| a.pattern.col_ptr[e], &mut k, &mut m);
        Ok((k, m))
    }

    /// `K φ = μ B φ` (lower triangles on [`Self::pattern`]) with the
    /// structure's own factorization (buckling, free vibration).
    pub(crate) fn eigen(
        &mut self,
        k: &[f64],
        b: &[f64],
        settings: &crate::solver::eigen::EigenSettings,
    ) -> Result<crate::solver::eigen::EigenSolution, crate::solver::eigen::EigenError> {
        self.system.eigen(k, b, settings)
    }

    /// The energy balance of a transient analysis, one row per converged
    /// time step (the initial state first); `None` for a static one.
    pub(crate) fn energies(&self) -> Option<Vec<crate::dynamics::energy::EnergyRow>> {
        self.parts.inertia.as_ref().map(|i| i.energies().to_vec())
    }

    /// The parts the solution keeps: displacements, elements, the
    /// stresses of the last evaluation and timings.
    pub(crate) fn into_parts(self) -> (Vec<f64>, Elements<'m>, Vec<crate::voigt::Voigt>, Timings) {
        let stresses = self.stresses();
        (self.state.u, self.parts.elements, stresses, self.report.timings)
    }

    /// Scales the correction in `rhs` by the contacts' step limit
    /// (`contact::assembly::limit`: no open point carried deeper than the
    /// deepest in contact). Not with force-controlled indenters, whose
    /// rigid motion is a further unknown of the same correction.
    fn limit_correction(&mut self) {
        if self.force.is_driven() || self.levers.is_active() || !self.parts.contacts.limits_steps() {
            return;
        }
        // the correction by DOF, read from the equations (no copy)
        let system = &mut self.system;
        let (eq, rhs) = (&system.assembler.dofs.eq, &system.rhs);
        let alpha = self.parts.contacts.step_limit(|d| if eq[d] == NO_EQ { 0.0 } else { rhs[eq[d]] });
        if alpha < 1.0 {
            system.rhs.iter_mut().for_each(|r| *r *= alpha);
        }
    }

    /// Adds the solved correction (in `system.rhs`, by equation) to `u` and
    /// reports its norm (with `da2`, the squared correction of the
    /// force-controlled indenters) and the norm of the increment so far.
    fn apply_correction(&mut self, da2: f64) -> Correction {
        let eq = &self.system.assembler.dofs.eq;
        let mut norm2 = 0.0;
        for (d, &e) in eq.iter().enumerate() {
            if e != NO_EQ {
                let du = self.system.rhs[e];
                self.state.u[d] += du;
                norm2 += du * du;
            }
        }
        let inc2 = self.state.increment2() + self.force.increment2();
        Correction { norm: (norm2 + da2).sqrt(), increment_norm: inc2.sqrt() }
    }

    /// The solver's statistics into the timings.
    fn record_solver(&mut self) {
        self.report.timings.solver = *self.system.stats();
    }
}

impl NonlinearProblem for Structure<'_> {
    type Error = LinearError;

    /// With the tangent of the present state, formed again at once where
    /// one kept on the last evaluation's word turns out changed
    /// (`structure/evaluation.rs`): the modal, buckling and path solvers
    /// and the finite-difference checks read it straight after.
    fn evaluate(&mut self) -> Result<Evaluation, LinearError> {
        let ev = self.evaluate_for_correction()?;
        if self.system.elastic_onset {
            self.system.elastic_onset = false;
            self.system.tangent_stale = true;
            self.form_tangent()?;
        }
        Ok(ev)
    }

    /// As [`Self::evaluate`], but keeping the elastic stiffness for the
    /// next correction where only the elements left it at this state
    /// (`structure/evaluation.rs`).
    fn evaluate_for_correction(&mut self) -> Result<Evaluation, LinearError> {
        self.system.tangent_stale = false;
        let ev = self.evaluate_parts(true)?;
        self.form_tangent()?;
        Ok(ev)
    }

    /// Without the element tangents (the kernel's second pass and its
    /// scatter): [`Self::correct`] evaluates again with them if the solve
    /// goes on. Not when the commit factorizes the converged tangent for
    /// its inertia (`solver.inertia = "every_increment"`): that needs it.
    fn evaluate_residual(&mut self) -> Result<Evaluation, LinearError> {
        if self.inertia_every_increment() {
            return self.evaluate();
        }
        let ev = self.evaluate_parts(false)?;
        self.system.tangent_stale = true;
        self.report.timings.residual_only += 1;
        Ok(ev)
    }

    fn correct(&mut self) -> Result<Correction, LinearError> {
        self.form_tangent()?;
        // a line search only along a correction without a prescribed jump
        let searchable = (self.settings.solver.newton.line_search || self.searches()) && {
            let (off, size) = self.elimination.offset(&self.state.u);
            off <= 1e-12 * size
        };
        let system = &mut self.system;
        for r in &mut system.rhs {
            *r = -*r;
        }
        let col_ptr = &system.assembler.pattern.col_ptr;
        self.elimination.eliminate(
            &self.state.u,
            |e| col_ptr[e],
            &mut system.tangent,
            system.rest.as_mut(),
            &mut system.rhs,
        );
        let da2 = if self.levers.is_active() {
            // setup/levers.rs refuses levers beside force-controlled indenters
            self.levers.solve(system, &self.state.u, self.state.lambda)?;
            0.0
        } else {
            self.force.solve(system, self.state.lambda)?
        };
        self.record_solver();
        self.limit_correction();
        self.remember_correction(searchable);
        self.state.before_correction();
        Ok(self.apply_correction(da2))
    }

    fn finish_within(&mut self, eta: f64) -> bool {
        self.system.finish_next(eta);
        true
    }

    fn finished(&self) -> bool {
        self.system.finished()
    }

    /// The retry of a failed increment (the cautious linearization,
    /// `Incremental::cautious`) of a frictionless contact model searches along
    /// its corrections even with `solver.line_search` off. A contact set
    /// cycling at a first touch is what fails such increments: on a fine
    /// axis mesh under a roller (node lines a third of a millimetre apart),
    /// each correction sends the lines it releases deep into the roller and
    /// the residual stays at 1 until an iterate lifts the supports and the
    /// tangent is singular; shortened where the energy rises along it, the
    /// retry converges at the same Δλ (bench/tube_quarter_axis_1mm.toml
    /// started at 1/15: one cutback instead of five,
    /// crates/cufem-cli/tests/retry.rs). Not in every attempt: the shipped
    /// examples converge without it, and with it some take more Newton
    /// iterations, the large-rotation ones several times as many
    /// (docs/limitations.md).
    fn searches(&self) -> bool {
        self.state.predictor == crate::materials::Predictor::Elastic && self.retry_searches()
    }

    /// A contact model whose corrections can be searched along
    /// (`structure/line.rs`: no friction, force-controlled indenter,
    /// impactor or lever).
    fn retry_searches(&self) -> bool {
        self.parts.contacts.has_points() && self.searchable_model()
    }

    fn slopes(&self) -> Option<(f64, f64)> {
        self.line_slopes()
    }

    fn step_to(&mut self, eta: f64) -> Option<Correction> {
        self.line_step_to(eta)
    }
}
