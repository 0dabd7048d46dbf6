//! The discretized structure as a nonlinear problem: residual
//! `R(u) = f_int(u) − λ f_ext − f_c(u)` on the free DOFs, its tangent
//! `K = K_tan + K_p` (paper eq. 18), prescribed displacements `λ ū`, and the
//! committed/trial split of the Gauss-point history.
//!
//! **Prescribed displacements.** DOFs fixed at zero have no equation. DOFs
//! with a non-zero prescribed value keep their equation, and each solve
//! eliminates them symmetrically: with `Δ_p = λ ū_p − u_p`,
//! `K_ff δu_f = −R_f − K_fp Δ_p` and `δu_p = Δ_p`. The first Newton
//! iteration of an increment therefore moves the free DOFs consistently
//! with the prescribed ones (a linearized predictor) instead of jumping the
//! constrained nodes alone, which would strain — and, in plasticity,
//! spuriously yield — the elements next to them.

use std::time::Instant;

mod augment;
mod contacts;
mod force;
mod resultants;
mod surface;
mod unsymmetric;

pub use super::results::{ContactKind, ContactPoint, ContactResultant, ContactSet, Reaction, Timings};
use crate::assembly::{Assembler, Inputs, NO_EQ, Numbering, Outputs};
use crate::materials::{PointState, Predictor};
use crate::model::Model;
use crate::model::steps::{self, Item};
use crate::size::MemoryEstimate;
use crate::solver::linear::{Cholesky, LinearError};
use crate::solver::newton::{Correction, Evaluation, NonlinearProblem};
use crate::solver::nonsymmetric::NonSymmetric;
use crate::solver::reuse::ReusingSolver;
use crate::solver::stepping::Incremental;
use crate::voigt::Voigt;

/// The structure: model, discretization, state and linear algebra.
pub struct Structure<'m> {
    /// The model.
    pub(super) model: &'m Model,
    /// First Gauss point of each body.
    pub(super) gp_offsets: Vec<usize>,
    /// Numbering, pattern and scatter.
    pub(super) assembler: Assembler,
    solver: ReusingSolver,
    /// A model with friction: the unsymmetric rest of the tangent of the
    /// last evaluation (`structure/unsymmetric.rs`).
    skew: Option<NonSymmetric>,
    /// Displacements (3 per node).
    pub(super) u: Vec<f64>,
    u_committed: Vec<f64>,
    /// Displacement change of the last converged increment (for the
    /// extrapolated start of the next: [`Incremental::extrapolate`]).
    u_step: Vec<f64>,
    /// Committed Gauss-point states.
    pub(super) committed: Vec<PointState>,
    trial: Vec<PointState>,
    /// Gauss-point stresses of the last evaluation.
    pub(super) stress: Vec<Voigt>,
    /// Internal forces of the last evaluation.
    pub(super) f_int: Vec<f64>,
    /// External loads at the current λ (each load times its factor).
    pub(super) f_ext: Vec<f64>,
    /// Contact forces of the last evaluation.
    pub(super) f_contact: Vec<f64>,
    tangent: Vec<f64>,
    residual: Vec<f64>,
    /// Non-zero prescribed DOFs: `(dof, equation, value at factor 1, constraint)`.
    prescribed: Vec<(usize, usize, f64, usize)>,
    /// Their values at the current λ.
    prescribed_now: Vec<f64>,
    /// Per equation: true for a prescribed DOF.
    is_prescribed: Vec<bool>,
    /// Matrix entries coupling a prescribed equation: `(position, row, col)`.
    dirichlet_entries: Vec<(usize, usize, usize)>,
    /// Current load factor.
    pub(super) lambda: f64,
    lambda_committed: f64,
    /// Contact points: all indenter candidates, then all pairs, in model order.
    pub(super) contact: Vec<ContactPoint>,
    contact_committed: Vec<ContactPoint>,
    contact_ranges: Vec<std::ops::Range<usize>>,
    /// Each contact point's assembled block of the last evaluation.
    contact_blocks: Vec<[[f64; 3]; 3]>,
    /// Per pair contact: the projections and weighted gaps of a surface contact.
    surface_state: Vec<surface::State>,
    /// `‖R‖ / F` of the last evaluation, at most `contacts::UNSETTLED_FORCING` while
    /// not settled: the forcing term of the next PCG solve.
    relative_residual: f64,
    /// Plastic Gauss points in the last evaluation.
    pub(super) plastic_points: usize,
    /// Force-controlled indenters (their displacement is an unknown).
    driven: Vec<force::Driven>,
    /// Tangent branch of Gauss points on their yield surface (elastic after
    /// a failed attempt: [`Incremental::cautious`]).
    predictor: Predictor,
    /// The next evaluation is the first of an increment (frictional points
    /// then get the stick tangent: `structure/contacts.rs`).
    first_evaluation: bool,
    /// Phase timings.
    pub(super) timings: Timings,
    /// Memory estimate made after the symbolic factorization.
    pub(super) memory: MemoryEstimate,
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
        // Gauss-point values come from the model's preprocessing
        let geometry = &model.cells;
        let mut gp_offsets = Vec::with_capacity(geometry.len());
        let mut n_gp = 0;
        for (b, g) in mesh.bodies.iter().zip(geometry) {
            gp_offsets.push(n_gp);
            n_gp += b.n_elements() * g.gp_per_element();
        }
        let n_dofs = mesh.n_dofs();
        // value prescribed at each constrained DOF (validation rejects conflicts)
        let mut value: Vec<Option<f64>> = vec![None; n_dofs];
        let mut source = vec![0; n_dofs];
        for (ci, c) in model.constraints.iter().enumerate() {
            for &n in &c.nodes {
                for (k, v) in c.values.iter().enumerate() {
                    if v.is_some() && value[3 * n + k].is_none() {
                        value[3 * n + k] = *v;
                        source[3 * n + k] = ci;
                    }
                }
            }
        }
        let fixed: Vec<bool> = value.iter().map(|v| *v == Some(0.0)).collect();
        let couplings: Vec<(usize, usize)> = model.contacts.iter().flat_map(|c| c.couplings(mesh)).collect();
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
        let n_eq = assembler.dofs.n_eq;
        let mut prescribed = Vec::new();
        let mut is_prescribed = vec![false; n_eq];
        for (d, v) in value.iter().enumerate() {
            if let Some(v) = *v
                && v != 0.0
            {
                let e = assembler.dofs.eq[d];
                prescribed.push((d, e, v, source[d]));
                is_prescribed[e] = true;
            }
        }
        let pattern = &assembler.pattern;
        let mut dirichlet_entries = Vec::new();
        for c in 0..pattern.n {
            for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                let r = pattern.row_idx[k] as usize;
                if r != c && (is_prescribed[r] || is_prescribed[c]) {
                    dirichlet_entries.push((k, r, c));
                }
            }
        }
        let frictional = model.has_friction();
        let t_cache = Instant::now();
        let states = vec![PointState::default(); n_gp];
        let zero = vec![0.0; n_dofs];
        assembler.cache_elastic(&Inputs {
            mesh,
            geometry,
            materials: &model.materials,
            u: &zero,
            committed: &states,
            gp_offsets: &gp_offsets,
            predictor: Default::default(),
        });
        let element_cache = t_cache.elapsed();

        let f_ext = vec![0.0; n_dofs];
        let mut contact = Vec::new();
        let mut contact_ranges = Vec::new();
        for ind in &model.indenters {
            let start = contact.len();
            contact.extend(ind.nodes.iter().map(|c| ContactPoint {
                node: c.node,
                area: c.area,
                position: mesh.coords(c.node),
                ..Default::default()
            }));
            contact_ranges.push(start..contact.len());
        }
        for pc in &model.contacts {
            let start = contact.len();
            contact.extend(pc.pairs.iter().map(|p| ContactPoint {
                node: p.slave,
                master: Some(p.master),
                area: p.area,
                gap: p.gap0,
                ..Default::default()
            }));
            contact.extend(surface::initial_points(pc));
            contact_ranges.push(start..contact.len());
        }
        let nnz = assembler.pattern.nnz();
        let timings = Timings {
            setup: t0.elapsed(),
            ordering: assembler.ordering_time,
            pattern: assembler.pattern_time,
            symbolic,
            element_cache,
            ..Default::default()
        };
        let mut structure = Self {
            model,
            gp_offsets,
            assembler,
            solver: ReusingSolver::new(chol, model.solver.reuse),
            skew: frictional.then(NonSymmetric::default),
            u: vec![0.0; n_dofs],
            u_committed: vec![0.0; n_dofs],
            u_step: vec![0.0; n_dofs],
            committed: vec![PointState::default(); n_gp],
            trial: vec![PointState::default(); n_gp],
            stress: vec![[0.0; 6]; n_gp],
            f_int: vec![0.0; n_dofs],
            f_ext,
            f_contact: vec![0.0; n_dofs],
            tangent: vec![0.0; nnz],
            residual: vec![0.0; n_eq],
            prescribed_now: vec![0.0; prescribed.len()],
            prescribed,
            is_prescribed,
            dirichlet_entries,
            lambda: 0.0,
            lambda_committed: 0.0,
            contact_blocks: vec![[[0.0; 3]; 3]; contact.len()],
            contact_committed: contact.clone(),
            surface_state: vec![Default::default(); model.contacts.len()],
            contact,
            contact_ranges,
            plastic_points: 0,
            relative_residual: 1.0,
            driven: force::Driven::of(model, n_eq),
            predictor: Predictor::Loading,
            first_evaluation: false,
            timings,
            memory,
        };
        structure.update_projections();
        Ok(structure)
    }

    /// Displacements, 3 per node (`3 · node + component`).
    pub fn displacements(&self) -> &[f64] {
        &self.u
    }

    /// Mutable displacements (for finite-difference checks of the tangent;
    /// the next [`NonlinearProblem::evaluate`] sees the change).
    pub fn displacements_mut(&mut self) -> &mut [f64] {
        &mut self.u
    }

    /// Current load factor.
    pub fn load_factor(&self) -> f64 {
        self.lambda
    }

    /// Plastic Gauss points in the last evaluation.
    pub fn plastic_points(&self) -> usize {
        self.plastic_points
    }

    /// Every contact point after the last evaluation (all indenter
    /// candidates, then all node pairs, in model order).
    pub fn contact_points(&self) -> &[ContactPoint] {
        &self.contact
    }

    /// The tangent's lower-triangular pattern (equation numbering).
    pub fn pattern(&self) -> &crate::solver::linear::LowerCsc {
        &self.assembler.pattern
    }

    /// Equation of a DOF, `None` if it is fixed.
    pub fn equation(&self, dof: usize) -> Option<usize> {
        let e = self.assembler.dofs.eq[dof];
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
        self.assembler.dofs.n_eq
    }

    /// Tangent values of the last evaluation, in the order of
    /// `assembler.pattern` (before any Dirichlet elimination).
    pub fn tangent_values(&self) -> &[f64] {
        &self.tangent
    }

    /// Residual `f_int − λ f_ext − f_c` per equation, from the last evaluation.
    pub fn residual(&self) -> &[f64] {
        &self.residual
    }

    /// Stored entries of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.solver.factor_nnz()
    }

    /// Reaction at every DOF, `f_int − λ f_ext − f_c` (zero up to the
    /// residual at free DOFs).
    pub fn nodal_imbalance(&self, dof: usize) -> f64 {
        self.f_int[dof] - self.f_ext[dof] - self.f_contact[dof]
    }

    fn assemble_elements(&mut self) {
        let t = Instant::now();
        let model = self.model;
        let inputs = Inputs {
            mesh: &model.mesh,
            geometry: &model.cells,
            materials: &model.materials,
            u: &self.u,
            committed: &self.committed,
            gp_offsets: &self.gp_offsets,
            predictor: self.predictor,
        };
        self.plastic_points = self.assembler.assemble(
            &inputs,
            Outputs {
                force: &mut self.f_int,
                tangent: Some(&mut self.tangent),
                trial: &mut self.trial,
                stress: &mut self.stress,
            },
        );
        self.timings.assembly += t.elapsed();
    }
}

impl NonlinearProblem for Structure<'_> {
    type Error = LinearError;

    fn evaluate(&mut self) -> Result<Evaluation, LinearError> {
        self.timings.evaluations += 1;
        self.assemble_elements();
        let changes = self.assemble_contact();
        let eq = &self.assembler.dofs.eq;
        let (mut res2, mut ext2, mut con2, mut reac2) = (0.0, 0.0, 0.0, 0.0);
        for (d, &e) in eq.iter().enumerate() {
            let ext = self.f_ext[d];
            let r = self.f_int[d] - ext - self.f_contact[d];
            ext2 += ext * ext;
            con2 += self.f_contact[d] * self.f_contact[d];
            if e == NO_EQ || self.is_prescribed[e] {
                reac2 += r * r;
            } else {
                res2 += r * r;
            }
            if e != NO_EQ {
                self.residual[e] = r;
            }
        }
        // prescribed values reached (exactly, after the first correction)
        let mut off: f64 = 0.0;
        let mut size: f64 = 0.0;
        for (&(d, _, v, _), now) in self.prescribed.iter().zip(&self.prescribed_now) {
            off = off.max((now - self.u[d]).abs());
            size = size.max(v.abs());
        }
        let (driven_res2, driven_target2) = self.evaluate_driven();
        res2 += driven_res2;
        let scale = ext2.sqrt().max(con2.sqrt()).max(reac2.sqrt()).max(driven_target2.sqrt());
        let settled = changes == 0 && off <= 1e-12 * size;
        let r = if scale > 0.0 { res2.sqrt() / scale } else { 1.0 };
        self.relative_residual = if settled { r } else { r.min(contacts::UNSETTLED_FORCING) };
        Ok(Evaluation { residual_norm: res2.sqrt(), force_scale: scale, settled })
    }

    fn correct(&mut self) -> Result<Correction, LinearError> {
        for r in &mut self.residual {
            *r = -*r;
        }
        // symmetric elimination of the prescribed equations (see module docs)
        for (&(d, e, _, _), now) in self.prescribed.iter().zip(&self.prescribed_now) {
            self.residual[e] = now - self.u[d];
        }
        for &(k, r, c) in &self.dirichlet_entries {
            let kv = self.tangent[k];
            if !self.is_prescribed[r] {
                self.residual[r] -= kv * self.residual[c];
            } else if !self.is_prescribed[c] {
                self.residual[c] -= kv * self.residual[r];
            }
            self.tangent[k] = 0.0;
        }
        self.eliminate_skew();
        for &(_, e, _, _) in &self.prescribed {
            let diag = self.assembler.pattern.col_ptr[e];
            self.residual[e] *= self.tangent[diag];
        }
        let da2 = self.solve_bordered()?;
        let stats = *self.solver.stats();
        self.timings.factorization = stats.factorization_time;
        self.timings.factorizations = stats.factorizations;
        self.timings.solve = stats.solve_time;
        self.timings.reused = stats.reused;
        self.timings.krylov_iterations = stats.krylov_iterations;
        self.timings.fallbacks = stats.fallbacks;
        self.timings.single_factorizations = stats.single_factorizations;
        self.timings.precision_fallbacks = stats.precision_fallbacks;
        Ok(self.apply_correction(da2))
    }
}

impl Incremental for Structure<'_> {
    fn set_load_factor(&mut self, lambda: f64) {
        // prescribed values are reached by the next correction (see module docs)
        self.lambda = lambda;
        self.first_evaluation = true;
        self.apply_factors();
    }

    fn augment(&mut self) -> bool {
        self.augment_contacts()
    }

    fn cautious(&mut self, on: bool) -> bool {
        let wanted = if on { Predictor::Elastic } else { Predictor::Loading };
        let changed = self.predictor != wanted;
        self.predictor = wanted;
        changed
    }

    fn extrapolate(&mut self, ratio: f64) {
        for ((u, c), s) in self.u.iter_mut().zip(&self.u_committed).zip(&self.u_step) {
            *u = c + ratio * s;
        }
        // Started on the secant of the last increment, a point that slid is
        // beyond its cone in the direction it slid, not on it to round-off:
        // its consistent tangent applies from the first iteration, and the
        // stick predictor (`structure/contacts.rs`) is kept for increments
        // that start at the committed state (the first of a load step, where
        // the loading may reverse). Measured on
        // examples/cantilevers_contact_friction.toml: the same Newton
        // iterations (66 against 67), 21 factorizations against 52 (the
        // predictor's tangent differs from the sliding one at every sliding
        // point, so no factor served both).
        if ratio > 0.0 && self.u_step.iter().any(|&s| s != 0.0) {
            self.first_evaluation = false;
        }
        for d in &mut self.driven {
            d.a = d.a_committed + ratio * d.a_step;
        }
    }

    fn commit(&mut self) {
        for ((s, u), c) in self.u_step.iter_mut().zip(&self.u).zip(&self.u_committed) {
            *s = u - c;
        }
        self.u_committed.copy_from_slice(&self.u);
        self.committed.copy_from_slice(&self.trial);
        self.lambda_committed = self.lambda;
        self.contact_committed.copy_from_slice(&self.contact);
        for d in &mut self.driven {
            d.a_step = d.a - d.a_committed;
            d.a_committed = d.a;
        }
        self.update_projections();
    }

    fn restore(&mut self) {
        self.u.copy_from_slice(&self.u_committed);
        self.contact.copy_from_slice(&self.contact_committed);
        self.lambda = self.lambda_committed;
        for d in &mut self.driven {
            d.a = d.a_committed;
        }
        self.apply_factors();
    }
}

impl Structure<'_> {
    /// Adds the solved correction (in `residual`, by equation) to `u` and
    /// reports its norm (with `da2`, the squared correction of the
    /// force-controlled indenters) and the norm of the increment so far.
    pub(super) fn apply_correction(&mut self, da2: f64) -> Correction {
        let eq = &self.assembler.dofs.eq;
        let mut norm2 = 0.0;
        for (d, &e) in eq.iter().enumerate() {
            if e != NO_EQ {
                let du = self.residual[e];
                self.u[d] += du;
                norm2 += du * du;
            }
        }
        let mut inc2: f64 = self.u.iter().zip(&self.u_committed).map(|(a, b)| (a - b) * (a - b)).sum();
        inc2 += self.driven.iter().map(|d| (d.a - d.a_committed).powi(2)).sum::<f64>();
        Correction { norm: (norm2 + da2).sqrt(), increment_norm: inc2.sqrt() }
    }

    /// Loads and prescribed values at the current λ: each item times its
    /// factor in the load history (`model::steps`).
    fn apply_factors(&mut self) {
        let model = self.model;
        self.f_ext.fill(0.0);
        for (i, l) in model.loads.iter().enumerate() {
            let a = steps::factor(&model.steps, Item::Load(i), self.lambda);
            for (n, f) in &l.nodal_forces {
                for k in 0..3 {
                    self.f_ext[3 * n + k] += a * f[k];
                }
            }
        }
        for (&(_, _, v, c), now) in self.prescribed.iter().zip(&mut self.prescribed_now) {
            *now = steps::factor(&model.steps, Item::Constraint(c), self.lambda) * v;
        }
    }
}
