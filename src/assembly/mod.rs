//! Assembly: equation numbering and pattern ([`Numbering`]), scatter maps
//! and colours ([`ScatterMaps`]), and the parallel element loop (here).
//!
//! * **Numbering.** Nodes are ordered by METIS nested dissection of the node
//!   graph (two nodes are adjacent when they share an element or a contact
//!   pair); the free degrees of freedom are then numbered node by node in
//!   that order, so the matrix handed to the Cholesky factorization is
//!   already fill-reduced. Constrained DOFs get no equation.
//! * **Pattern.** The lower triangle of the tangent in compressed-column
//!   form, built once from the tensor-product structure of CUF bodies: nodes
//!   `(i, τ)` and `(j, s)` are coupled iff beam nodes `i, j` share a beam
//!   element and section nodes `τ, s` share a section element.
//! * **Scatter.** For every element a precomputed map from its local upper
//!   triangle `(p ≤ q)` to positions in the value array; assembly is a plain
//!   scatter of what the element kernel computed.
//! * **Parallelism.** Elements are coloured so that no two elements of a
//!   colour share a node (section colour × beam-element parity); the
//!   elements of a colour are processed in parallel and write to disjoint
//!   entries.

mod contribution;
mod linear;
mod numbering;
mod scatter;
mod skew;

pub use contribution::{At, Contribution, Forces, Phase, Tangent};
pub(crate) use linear::ElasticProduct;
pub(crate) use numbering::node_adjacency;
pub use numbering::{DofMap, NO_EQ, Numbering};
pub use scatter::ScatterMaps;

use rayon::prelude::*;

use crate::elements::DamagePoints;
use crate::elements::{self, PointData, TangentMode, Workspace};
use crate::materials::damage::DamageState;
use crate::materials::{Material, PointState, Predictor};
use crate::mesh::Mesh;
use crate::solver::linear::LowerCsc;
use crate::values::CellValues;
use crate::voigt::Voigt;

/// Pattern, numbering and scatter maps of one model (built once).
#[derive(Debug, Clone)]
pub(crate) struct Assembler {
    /// DOF → equation map.
    pub dofs: DofMap,
    /// Lower-triangular pattern in equation numbering.
    pub pattern: LowerCsc,
    scatter: ScatterMaps,
    /// Their sum, the elastic tangent of the whole model in pattern order
    /// (empty until [`Assembler::cache_elastic`]): an assembly starts from
    /// it and corrects only the elements that are not elastic.
    elastic_global: Vec<f64>,
    /// Time spent building the node graph and the METIS ordering.
    pub ordering_time: std::time::Duration,
    /// Time spent building the pattern, scatter maps and colours.
    pub pattern_time: std::time::Duration,
}

/// The finite-element state of a model: its mesh, geometry and materials,
/// and the displacements and Gauss-point states on them. What an assembly
/// pass ([`Inputs`]) and a field evaluation (`post::FieldView`) both read.
#[derive(Clone, Copy)]
pub struct FeState<'a> {
    /// Mesh.
    pub mesh: &'a Mesh,
    /// Geometry caches per body.
    pub geometry: &'a [CellValues],
    /// Materials.
    pub materials: &'a [Material],
    /// Displacements (3 per node).
    pub u: &'a [f64],
    /// Committed Gauss-point states (all bodies).
    pub states: &'a [PointState],
    /// First Gauss point of each body in `states`.
    pub gp_offsets: &'a [usize],
    /// Strain measure (small strain or total Lagrangian).
    pub kinematics: crate::kinematics::Kinematics,
    /// The committed ply damage and crack bands (empty without damage).
    pub damage: DamageInput<'a>,
}

/// The committed ply-damage states and crack-band lengths of every Gauss
/// point (the layout of [`FeState::states`]); both empty when no material
/// damages.
#[derive(Debug, Clone, Copy, Default)]
pub struct DamageInput<'a> {
    /// Committed damage states.
    pub committed: &'a [DamageState],
    /// Crack-band lengths `[fibre, matrix]` (m).
    pub band: &'a [[f64; 2]],
    /// The change of the load factor since the committed states (the step
    /// of the damage's viscosity).
    pub step: f64,
    /// How a transient run integrates the ply points' forces: Newmark's γ
    /// and whether damaged points take the end-of-step stress
    /// (`analysis.ply_damage_forces = "implicit"`, `dynamics::ply_forces`);
    /// `None` in a static run.
    pub(crate) impulse: Option<crate::materials::damage_impulse::PointForces>,
}

/// Read-only inputs of an assembly pass: the state it starts from, and how.
pub(crate) struct Inputs<'a> {
    /// Displacements, committed states and what they live on.
    pub state: FeState<'a>,
    /// Tangent branch of points on their yield surface.
    pub predictor: Predictor,
    /// Total Lagrangian: a stress-free initial displacement (3 per node; a
    /// geometric imperfection), `None` for the perfect geometry.
    pub initial: Option<&'a [f64]>,
    /// The iterate the displacements were reached from by one linear step
    /// (`At::u_before`), `None` for the stress of the displacements alone.
    pub before: Option<&'a [f64]>,
}

impl<'a> std::ops::Deref for Inputs<'a> {
    type Target = FeState<'a>;

    fn deref(&self) -> &FeState<'a> {
        &self.state
    }
}

/// Outputs of an assembly pass.
pub(crate) struct Outputs<'a> {
    /// Internal forces (3 per node), overwritten.
    pub force: &'a mut [f64],
    /// Tangent values in pattern order, overwritten when present.
    pub tangent: Option<&'a mut [f64]>,
    /// Trial Gauss-point states, overwritten.
    pub trial: &'a mut [PointState],
    /// Gauss-point stresses, overwritten.
    pub stress: &'a mut [Voigt],
    /// Trial ply-damage states, overwritten where a material damages
    /// (empty without damage).
    pub damage: &'a mut [DamageState],
    /// The tangent's unsymmetric rest, where the model keeps one: a
    /// damaging element's loading points add theirs (`skew`).
    pub rest: Option<&'a mut crate::solver::nonsymmetric::NonSymmetric>,
}

thread_local! {
    /// The element kernel's buffers, one set per worker thread, kept across
    /// assemblies (no allocation in the element loop once warmed up).
    static WORKSPACE: std::cell::RefCell<Workspace> = std::cell::RefCell::new(Workspace::default());
}

/// A slice shared between threads that write to disjoint indices.
struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _borrow: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: `Disjoint` hands out access only through the unsafe methods below,
// whose callers guarantee that concurrent accesses touch disjoint indices.
unsafe impl<T: Send> Sync for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    fn new(s: &'a mut [T]) -> Self {
        Self { ptr: s.as_mut_ptr(), len: s.len(), _borrow: std::marker::PhantomData }
    }

    /// # Safety
    /// No other thread may access index `i` concurrently.
    #[allow(clippy::mut_from_ref)] // exclusive access is the caller's contract (see `Disjoint`)
    unsafe fn get(&self, i: usize) -> &mut T {
        assert!(i < self.len);
        // SAFETY: in bounds (checked) and exclusive by the caller's contract.
        unsafe { &mut *self.ptr.add(i) }
    }

    /// # Safety
    /// No other thread may access `start..start+n` concurrently.
    #[allow(clippy::mut_from_ref)] // exclusive access is the caller's contract (see `Disjoint`)
    unsafe fn range(&self, start: usize, n: usize) -> &mut [T] {
        assert!(start + n <= self.len);
        // SAFETY: in bounds (checked) and exclusive by the caller's contract.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(start), n) }
    }
}

impl Assembler {
    /// Builds the scatter maps and colours on a numbering.
    pub fn new(mesh: &Mesh, numbering: Numbering) -> Self {
        let t0 = std::time::Instant::now();
        let Numbering { dofs, pattern, ordering_time, pattern_time, .. } = numbering;
        let scatter = ScatterMaps::new(mesh, &dofs, &pattern);
        Self {
            dofs,
            pattern,
            scatter,
            elastic_global: Vec::new(),
            ordering_time,
            pattern_time: pattern_time + t0.elapsed(),
        }
    }

    /// Adds the 3×3 block `k` coupling nodes `a` (rows) and `b` (columns) of
    /// a symmetric matrix stored as its lower triangle. For `a ≠ b` the
    /// caller adds the `(a, b)` block once; its transpose is implied.
    pub(crate) fn add_node_block(&self, values: &mut [f64], a: usize, b: usize, k: &[[f64; 3]; 3]) {
        for (i, row) in k.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let (r, c) = (self.dofs.eq[3 * a + i], self.dofs.eq[3 * b + j]);
                if r == NO_EQ || c == NO_EQ || (a == b && r < c) {
                    continue;
                }
                if let Some(pos) = self.pattern.find(r.max(c), r.min(c)) {
                    values[pos] += v;
                }
            }
        }
    }

    /// Assembles the elastic stiffness of the whole model once (every
    /// element's matrix at zero displacement from a virgin state, summed in
    /// pattern order). Later assemblies start from it and add, per element,
    /// only the correction `Σ w B̄ᵀ (C − C^el) B̄` of the Gauss points whose
    /// tangent is not elastic (`TangentMode::UnlessElastic`): in localized
    /// plasticity most elements add nothing and a plastic element only its
    /// plastic points.
    ///
    /// `input` holds zero displacements and virgin states (every point
    /// elastic); the element loop itself, without a global elastic tangent
    /// yet, computes and scatters every element's full matrix.
    pub(crate) fn cache_elastic(&mut self, input: &Inputs<'_>) {
        self.elastic_global.clear();
        self.elastic_global = self.elastic_matrix(input);
    }

    /// The tangent of every element at zero displacements and virgin
    /// states (the elastic stiffness `K₀`), in pattern order: what
    /// [`Self::cache_elastic`] keeps, for whoever needs it once (Rayleigh
    /// damping).
    pub(crate) fn elastic_matrix(&self, input: &Inputs<'_>) -> Vec<f64> {
        if !self.elastic_global.is_empty() {
            return self.elastic_global.clone();
        }
        debug_assert!(input.u.iter().all(|&v| v == 0.0), "the elastic tangent is taken at zero displacement");
        let n_gp = input.states.len();
        let (mut force, mut trial, mut stress) =
            (vec![0.0; input.u.len()], vec![PointState::default(); n_gp], vec![[0.0; 6]; n_gp]);
        let mut global = vec![0.0; self.pattern.nnz()];
        // with the cache empty, the element loop forms every element's matrix
        self.assemble(
            input,
            Outputs {
                force: &mut force,
                tangent: Some(&mut global),
                trial: &mut trial,
                stress: &mut stress,
                damage: &mut [],
                rest: None,
            },
        );
        global
    }

    /// Element loop: internal forces (and tangent) of all elements from the
    /// displacements, with trial states and Gauss-point stresses. Returns
    /// the number of plastic Gauss points and the time in the kernel's two
    /// passes.
    pub(crate) fn assemble(&self, input: &Inputs<'_>, out: Outputs<'_>) -> AssemblyStats {
        out.force.fill(0.0);
        let with_tangent = out.tangent.is_some();
        let mode = match (with_tangent, self.elastic_global.is_empty()) {
            (false, _) => TangentMode::None,
            (true, true) => TangentMode::Always,
            (true, false) => TangentMode::UnlessElastic,
        };
        let mut empty: [f64; 0] = [];
        let tangent = out.tangent.unwrap_or(&mut empty);
        if mode == TangentMode::UnlessElastic {
            // the elastic tangent of every element at once; an element that
            // is not elastic adds its tangent minus its elastic matrix below
            tangent.copy_from_slice(&self.elastic_global);
        } else {
            tangent.fill(0.0);
        }
        let force = Disjoint::new(out.force);
        let tangent = Disjoint::new(tangent);
        let trial = Disjoint::new(out.trial);
        let stress = Disjoint::new(out.stress);
        // (the elastic matrix is taken without damage: `out.damage` empty)
        let with_damage = !input.damage.committed.is_empty() && !out.damage.is_empty();
        let damage = Disjoint::new(out.damage);
        let skew = skew::SkewTerms::default();
        let mut stats = AssemblyStats::default();
        for colour in &self.scatter.colours {
            stats += colour
                .par_iter()
                .map_init(
                    || (Vec::new(), Vec::new(), Vec::new(), Vec::new()),
                    |(nodes, ue, ie, de), &ge| {
                        let r = self.scatter.elements[ge];
                        let body = &input.mesh.bodies[r.body];
                        let geom = &input.geometry[r.body];
                        body.element_nodes(r.element, nodes);
                        ue.clear();
                        ue.extend(nodes.iter().flat_map(|&n| (0..3).map(move |c| input.u[3 * n + c])));
                        if let Some(u0) = input.initial {
                            ie.clear();
                            ie.extend(nodes.iter().flat_map(|&n| (0..3).map(move |c| u0[3 * n + c])));
                        }
                        if let Some(before) = input.before {
                            de.clear();
                            de.extend(
                                nodes.iter().flat_map(|&n| (0..3).map(move |c| input.u[3 * n + c] - before[3 * n + c])),
                            );
                        }
                        let ngp = geom.gp_per_element();
                        let g0 = input.gp_offsets[r.body] + r.element * ngp;
                        // SAFETY: Gauss points of an element belong to it alone.
                        let points = unsafe {
                            PointData {
                                committed: &input.states[g0..g0 + ngp],
                                trial: trial.range(g0, ngp),
                                stress: stress.range(g0, ngp),
                                predictor: input.predictor,
                                kinematics: input.kinematics,
                                initial: input.initial.map(|_| &ie[..]),
                                step: input.before.map(|_| &de[..]),
                                damage: with_damage.then(|| DamagePoints {
                                    committed: &input.damage.committed[g0..g0 + ngp],
                                    band: &input.damage.band[g0..g0 + ngp],
                                    step: input.damage.step,
                                    impulse: input.damage.impulse,
                                    trial: damage.range(g0, ngp),
                                }),
                            }
                        };
                        WORKSPACE.with_borrow_mut(|ws| {
                            let stats = elements::element_response(
                                geom,
                                r.element,
                                body.section.n_elements(),
                                ue,
                                &input.materials[body.material_of(body.split_element(r.element).0)],
                                points,
                                mode,
                                ws,
                            );
                            let range = self.scatter.offsets[ge]..self.scatter.offsets[ge + 1];
                            // SAFETY: elements of one colour share no node, hence
                            // no DOF and no matrix entry.
                            unsafe {
                                for (a, &n) in nodes.iter().enumerate() {
                                    for c in 0..3 {
                                        *force.get(3 * n + c) += ws.force[3 * a + c];
                                    }
                                }
                                // the element's tangent (Always) or its
                                // correction to the assembled elastic tangent
                                // (UnlessElastic)
                                if stats.tangent_computed {
                                    scatter_upper(&self.scatter.maps[range], &ws.tangent, 3 * nodes.len(), &tangent);
                                }
                            }
                            skew.add(ge, nodes, &self.dofs, &ws.skew);
                            AssemblyStats {
                                plastic_points: stats.plastic_points,
                                stress_pass: stats.stress_pass,
                                element_tangents: stats.tangent_pass,
                                tangents_formed: usize::from(stats.tangent_computed),
                                inelastic_elements: usize::from(!stats.all_elastic),
                            }
                        })
                    },
                )
                .reduce(AssemblyStats::default, |a, b| a + b);
        }
        if let Some(rest) = out.rest {
            skew.into_rest(rest);
        }
        stats
    }
}

impl Assembler {
    /// The geometric (initial-stress) stiffness `K_σ` of every element from
    /// the Gauss-point stresses `stress` (all bodies, the layout of
    /// `Inputs::committed`), in pattern order (linear buckling).
    pub(crate) fn assemble_geometric(&self, input: &Inputs<'_>, stress: &[Voigt], out: &mut [f64]) {
        self.assemble_matrices(input.mesh, out, |body, element, ws| {
            let geom = &input.geometry[body];
            let ngp = geom.gp_per_element();
            let g0 = input.gp_offsets[body] + element * ngp;
            let n_section = input.mesh.bodies[body].section.n_elements();
            elements::geometric_matrix(geom, element, n_section, &stress[g0..g0 + ngp], ws);
        });
    }

    /// Assembles, in pattern order, a matrix of element contributions
    /// (constrained DOFs dropped): `element(body, element, ws)` writes the
    /// upper triangle of the element's row-major `3 nodes` square matrix
    /// (DOF `3a + c`) into `ws.tangent`; assembly only scatters it.
    pub(crate) fn assemble_matrices<F>(&self, mesh: &Mesh, out: &mut [f64], element: F)
    where
        F: Fn(usize, usize, &mut Workspace) + Sync,
    {
        out.fill(0.0);
        let values = Disjoint::new(out);
        for colour in &self.scatter.colours {
            colour.par_iter().for_each_init(Vec::new, |nodes, &ge| {
                let r = self.scatter.elements[ge];
                mesh.bodies[r.body].element_nodes(r.element, nodes);
                WORKSPACE.with_borrow_mut(|ws| {
                    element(r.body, r.element, ws);
                    let range = self.scatter.offsets[ge]..self.scatter.offsets[ge + 1];
                    // SAFETY: elements of one colour share no matrix entry.
                    unsafe { scatter_upper(&self.scatter.maps[range], &ws.tangent, 3 * nodes.len(), &values) };
                });
            });
        }
    }
}

/// What one element loop did: plastic Gauss points, and the time its
/// kernel spent in each pass, summed over the worker threads (on one
/// thread, the element loop less these two is the scatter and the gather).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct AssemblyStats {
    /// Gauss points whose update was plastic.
    pub plastic_points: usize,
    /// B-bar's projections, strains, material updates and internal forces.
    pub stress_pass: std::time::Duration,
    /// Element tangents (zero where the kernel formed none).
    pub element_tangents: std::time::Duration,
    /// Number of element tangents (or tangent corrections) formed.
    pub tangents_formed: usize,
    /// Elements with a Gauss point off the elastic tangent (a plastic or
    /// damaged one), counted with or without their tangents: none, and the
    /// elements' tangent is the cached elastic stiffness.
    pub inelastic_elements: usize,
}

impl std::ops::Add for AssemblyStats {
    type Output = Self;

    fn add(self, b: Self) -> Self {
        Self {
            plastic_points: self.plastic_points + b.plastic_points,
            stress_pass: self.stress_pass + b.stress_pass,
            element_tangents: self.element_tangents + b.element_tangents,
            tangents_formed: self.tangents_formed + b.tangents_formed,
            inelastic_elements: self.inelastic_elements + b.inelastic_elements,
        }
    }
}

impl std::ops::AddAssign for AssemblyStats {
    fn add_assign(&mut self, b: Self) {
        *self = *self + b;
    }
}

/// Adds the upper triangle of the row-major `n × n` element matrix `k` to
/// the global values through the element's scatter map.
///
/// # Safety
/// No other thread may write the entries of this element's map concurrently.
unsafe fn scatter_upper(map: &[u32], k: &[f64], n: usize, values: &Disjoint<'_, f64>) {
    let mut m = 0;
    for p in 0..n {
        for &v in &k[p * n + p..(p + 1) * n] {
            let pos = map[m];
            if pos != u32::MAX {
                // SAFETY: the caller's contract.
                unsafe { *values.get(pos as usize) += v };
            }
            m += 1;
        }
    }
}

#[cfg(test)]
mod tests;
