//! The discretized structure as a nonlinear problem: residual
//! `R(u) = f_int(u) − λ f_ext − f_c(u)` on the free DOFs and its tangent
//! `K = K_tan + K_p` (paper eq. 18), for the solvers of `solver::newton`
//! and `solver::stepping`.
//!
//! The structure is a composition of parts with one job each:
//!
//! * the **contributions** ([`crate::assembly::Contribution`]), evaluated
//!   in order into the tangent, their forces summed into the residual —
//!   `structure/elements.rs` (internal forces, element tangents, the
//!   Gauss-point history; first: it writes the whole tangent),
//!   `structure/loads.rs` (the external loads at λ) and
//!   [`crate::contact::Contacts`] (every contact kind);
//! * `structure/dirichlet.rs`: prescribed displacements and their
//!   elimination from each linear system (symmetric and unsymmetric alike);
//! * `structure/force.rs`: force-controlled indenters, whose displacement is
//!   an extra unknown bordering the linear system;
//! * `structure/system.rs`: the tangent, the right-hand side and the solver;
//! * `structure/kinematics.rs`: the displacements and λ;
//! * `structure/evaluation.rs`: one evaluation of all parts (with or
//!   without the element tangents), `structure/stepping.rs`: the load
//!   stepping's start, commit and restore of an increment.
//!
//! A new capability is a new part: inertia is a contribution
//! ([`crate::dynamics::Inertia`]: its forces `M a + C v` and stiffness
//! `M/(βΔt²) + γC/(βΔt)`), a new contact kind a file of `contact::assembly`.

use std::time::Instant;

mod arc;
mod dirichlet;
pub(crate) mod elements;
mod evaluation;
mod force;
mod kinematics;
#[cfg(test)]
mod limit_tests;
mod line;
mod loads;
mod resultants;
mod stepping;
mod system;
mod transient;

pub use super::results::{ContactKind, ContactPoint, ContactResultant, ContactSet, Reaction, Timings};
use crate::assembly::{Assembler, Contribution, NO_EQ, Numbering};
use crate::contact::Contacts;
use crate::setup::Model;
use crate::size::MemoryEstimate;
use crate::solver::linear::{Cholesky, LinearError};
use crate::solver::newton::{Correction, Evaluation, NonlinearProblem};
use dirichlet::Dirichlet;
use elements::Elements;
use force::ForceControl;
use kinematics::Kinematics;
use loads::Loads;
use system::LinearSystem;

/// The structure: the model's parts (module docs), its unknowns and its
/// linear system.
pub struct Structure<'m> {
    model: &'m Model,
    state: Kinematics,
    elements: Elements<'m>,
    loads: Loads<'m>,
    contacts: Contacts<'m>,
    dirichlet: Dirichlet,
    force: ForceControl<'m>,
    system: LinearSystem,
    timings: Timings,
    memory: MemoryEstimate,
    /// Negative pivots of the last committed tangent (nonlinear geometry).
    pivots: Option<usize>,
    /// Inertia and damping (`analysis.type = "transient"`), a contribution.
    dynamics: Option<crate::dynamics::Inertia>,
    /// The contacts' end-of-step impulse (a transient analysis with
    /// contacts and `analysis.contact_forces = "implicit"`).
    impulse: Option<crate::dynamics::ContactImpulse>,
    /// The last evaluation left the element tangents out
    /// (`structure/evaluation.rs`).
    tangent_stale: bool,
}

impl<'m> Structure<'m> {
    /// Builds numbering, pattern, factorization structure and initial state.
    ///
    /// With `max_memory`, the memory of the analysis is estimated after the
    /// symbolic factorization (exact factor size) and the structure is
    /// refused with [`super::AnalysisError::TooLarge`] before the factor, the
    /// scatter maps and the element cache are allocated.
    pub fn new(model: &'m Model, max_memory: Option<u64>) -> Result<Self, super::AnalysisError> {
        let t0 = Instant::now();
        let mesh = &model.mesh;
        let (value, source) = dirichlet::prescribed_values(model);
        let fixed: Vec<bool> = value.iter().map(|v| *v == Some(0.0)).collect();
        let couplings: Vec<(usize, usize)> =
            model.contacts.iter().flat_map(|c| c.couplings(mesh, model.kinematics.is_nonlinear())).collect();
        let numbering = Numbering::new(mesh, &fixed, &couplings)?;
        let t_sym = Instant::now();
        let chol = Cholesky::analyze(&numbering.pattern)?;
        let symbolic = t_sym.elapsed();
        let memory = super::sizes(model, &numbering, &chol).memory();
        if let Some(limit) = max_memory
            && memory.total() > limit
        {
            return Err(super::AnalysisError::TooLarge { estimate: memory, limit });
        }
        let mut assembler = Assembler::new(mesh, numbering);
        let dirichlet = Dirichlet::new(&value, &source, &assembler);
        let elements = Elements::new(model);
        let t_cache = Instant::now();
        // the elastic tangent is a constant only in small strain; the
        // total-Lagrangian one depends on u and S everywhere
        if !model.kinematics.is_nonlinear() {
            assembler.cache_elastic(&elements.inputs(&vec![0.0; mesh.n_dofs()]));
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
        let dynamics = match &model.transient {
            Some(settings) => Some(transient::inertia(model, settings, &assembler, &elements)?),
            None => None,
        };
        Ok(Self {
            model,
            state: Kinematics::new(mesh.n_dofs()),
            elements,
            loads: Loads::new(model),
            contacts: Contacts::new(mesh, &model.indenters, &model.contacts, model.kinematics.is_nonlinear()),
            dirichlet,
            force: ForceControl::new(model, n_eq),
            system: LinearSystem::new(assembler, chol, model.solver.reuse, model.has_friction(), mesh.n_dofs()),
            timings,
            memory,
            pivots: None,
            dynamics,
            impulse: transient::impulse(model),
            tangent_stale: false,
        })
    }

    /// The contributions in the order they are evaluated and summed (the
    /// elements first: they write the whole tangent).
    fn contributions(&mut self) -> impl Iterator<Item = &mut dyn Contribution> {
        let parts: [&mut dyn Contribution; 3] = [&mut self.elements, &mut self.loads, &mut self.contacts];
        parts.into_iter().chain(self.dynamics.iter_mut().map(|i| i as &mut dyn Contribution))
    }

    /// Displacements, 3 per node (`3 · node + component`).
    pub fn displacements(&self) -> &[f64] {
        &self.state.u
    }

    /// Mutable displacements (for finite-difference checks of the tangent;
    /// the next [`NonlinearProblem::evaluate`] sees the change).
    pub fn displacements_mut(&mut self) -> &mut [f64] {
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
        if self.inertia_every_increment() { self.pivots } else { self.system.negative_pivots() }
    }

    /// True if every converged tangent is factorized for its inertia
    /// (`solver.inertia`; by default with nonlinear geometry, not in a
    /// transient run, whose tangent carries `M / (β Δt²)`).
    fn inertia_every_increment(&self) -> bool {
        let every = match self.model.solver.inertia {
            Some(report) => report == crate::input::InertiaReport::EveryIncrement,
            None => self.model.kinematics.is_nonlinear(),
        };
        every && self.dynamics.is_none()
    }

    /// Plastic Gauss points in the last evaluation.
    pub fn plastic_points(&self) -> usize {
        self.elements.last.plastic_points
    }

    /// The displacement at each probe of the model (mean over the elements
    /// holding it; NaN for a probe outside every body).
    pub fn probe_displacements(&self) -> Vec<[f64; 3]> {
        self.model
            .probes
            .iter()
            .map(|p| {
                if p.locations.is_empty() {
                    return [f64::NAN; 3];
                }
                // a probe in the part a symmetry plane leaves out: its image's u reflected back
                let reflected = crate::bc::symmetry::image(&self.model.symmetry.planes, p.point).1;
                let mut sum = [0.0; 3];
                for loc in &p.locations {
                    let pv = crate::values::PointValues::new(&self.model.mesh.bodies[loc.body], loc);
                    let u = pv.displacement(&self.state.u);
                    for k in 0..3 {
                        let sign = if reflected[k] { -1.0 } else { 1.0 };
                        sum[k] += sign * u[k] / p.locations.len() as f64;
                    }
                }
                sum
            })
            .collect()
    }

    /// Every contact point after the last evaluation (all indenter
    /// candidates, then all node pairs, in model order).
    pub fn contact_points(&self) -> &[ContactPoint] {
        self.contacts.points()
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
        &self.timings
    }

    /// Memory estimate made after the symbolic factorization.
    pub fn memory(&self) -> &MemoryEstimate {
        &self.memory
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
    pub fn nodal_imbalance(&self, dof: usize) -> f64 {
        self.system.imbalance[dof]
    }

    /// External loads at the current λ (per DOF).
    pub fn external_loads(&self) -> &[f64] {
        &self.loads.f_ext
    }

    /// The model the structure discretizes.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// The elements' part: Gauss-point states, stresses and offsets.
    pub(crate) fn elements(&self) -> &Elements<'m> {
        &self.elements
    }

    /// Sets a stress-free initial displacement (a geometric imperfection,
    /// per DOF) for a total-Lagrangian analysis, before the first evaluation.
    pub(crate) fn set_imperfection(&mut self, u0: Vec<f64>) {
        self.elements.initial = Some(u0);
    }

    /// The stress stiffness `K_σ` of the present Gauss-point stresses, in
    /// pattern order (linear buckling).
    pub(crate) fn stress_stiffness(&self) -> Vec<f64> {
        let a = &self.system.assembler;
        let mut kg = vec![0.0; a.pattern.nnz()];
        let u = self.displacements();
        a.assemble_geometric(&self.elements.inputs(u), &self.elements.stress, &mut kg);
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
        let (model, a) = (self.model, &self.system.assembler);
        let densities = mass::densities(&model.mesh, &model.materials)?;
        let mut m = mass::assemble(a, &model.mesh, &model.cells, &densities, kind, None)?;
        let mut k = self.system.tangent.clone();
        self.dirichlet.fix_for_eigen(|e| a.pattern.col_ptr[e], &mut k, &mut m);
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
        self.dynamics.as_ref().map(|i| i.energies().to_vec())
    }

    /// The parts the solution keeps: displacements, elements, timings, memory.
    pub(crate) fn into_parts(self) -> (Vec<f64>, Elements<'m>, Timings, MemoryEstimate) {
        (self.state.u, self.elements, self.timings, self.memory)
    }

    /// Scales the correction in `rhs` by the contacts' step limit
    /// (`contact::assembly::limit`: no open point carried deeper than the
    /// deepest in contact). Not with force-controlled indenters, whose
    /// rigid motion is a further unknown of the same correction.
    fn limit_correction(&mut self) {
        if self.force.is_driven() || !self.contacts.limits_steps() {
            return;
        }
        // the correction by DOF, read from the equations (no copy)
        let system = &mut self.system;
        let (eq, rhs) = (&system.assembler.dofs.eq, &system.rhs);
        let alpha = self.contacts.step_limit(|d| if eq[d] == NO_EQ { 0.0 } else { rhs[eq[d]] });
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
        self.timings.solver = *self.system.stats();
    }
}

impl NonlinearProblem for Structure<'_> {
    type Error = LinearError;

    fn evaluate(&mut self) -> Result<Evaluation, LinearError> {
        self.tangent_stale = false;
        self.evaluate_parts(true)
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
        self.tangent_stale = true;
        self.timings.residual_only += 1;
        Ok(ev)
    }

    fn correct(&mut self) -> Result<Correction, LinearError> {
        self.form_tangent()?;
        // a line search only along a correction without a prescribed jump
        let searchable = self.model.solver.newton.line_search && {
            let (off, size) = self.dirichlet.offset(&self.state.u);
            off <= 1e-12 * size
        };
        let system = &mut self.system;
        for r in &mut system.rhs {
            *r = -*r;
        }
        let col_ptr = &system.assembler.pattern.col_ptr;
        self.dirichlet.eliminate(
            &self.state.u,
            |e| col_ptr[e],
            &mut system.tangent,
            system.rest.as_mut(),
            &mut system.rhs,
        );
        let da2 = self.force.solve(system, self.state.lambda)?;
        self.record_solver();
        self.limit_correction();
        self.remember_correction(searchable);
        Ok(self.apply_correction(da2))
    }

    fn slopes(&self) -> Option<(f64, f64)> {
        self.line_slopes()
    }

    fn step_to(&mut self, eta: f64) -> Option<Correction> {
        self.line_step_to(eta)
    }
}
