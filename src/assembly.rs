//! Equation numbering, sparse pattern and parallel assembly.
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

use std::collections::BTreeSet;

use rayon::prelude::*;

use crate::elements::{self, BodyGeometry, PointData, TangentMode, Workspace};
use crate::materials::{Material, PointState};
use crate::mesh::Mesh;
use crate::solver::linear::{LinearError, LowerCsc, nested_dissection};
use crate::voigt::Voigt;

/// Marker for a DOF without an equation (constrained).
pub const NO_EQ: usize = usize::MAX;

/// Map from global DOFs (`3 · node + component`) to equations.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Equation of each DOF, or [`NO_EQ`].
    pub eq: Vec<usize>,
    /// Number of equations (free DOFs).
    pub n_eq: usize,
}

/// A body element in the global element list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ElementRef {
    /// Body index.
    pub body: usize,
    /// Body-local element index.
    pub element: usize,
}

/// Pattern, numbering and scatter maps of one model (built once).
#[derive(Debug, Clone)]
pub struct Assembler {
    /// DOF → equation map.
    pub dofs: DofMap,
    /// Lower-triangular pattern in equation numbering.
    pub pattern: LowerCsc,
    elements: Vec<ElementRef>,
    scatter_offsets: Vec<usize>,
    scatter: Vec<u32>,
    colors: Vec<Vec<usize>>,
    /// Elastic element matrices packed like `scatter` (empty until
    /// [`Assembler::cache_elastic`]).
    elastic_cache: Vec<f64>,
    /// Time spent building the node graph and the METIS ordering.
    pub ordering_time: std::time::Duration,
    /// Time spent building the pattern, scatter maps and colours.
    pub pattern_time: std::time::Duration,
}

/// Read-only inputs of an assembly pass.
pub struct Inputs<'a> {
    /// Mesh.
    pub mesh: &'a Mesh,
    /// Geometry caches per body.
    pub geometry: &'a [BodyGeometry],
    /// Materials.
    pub materials: &'a [Material],
    /// Displacements (3 per node).
    pub u: &'a [f64],
    /// Committed Gauss-point states (all bodies).
    pub committed: &'a [PointState],
    /// First Gauss point of each body.
    pub gp_offsets: &'a [usize],
}

/// Outputs of an assembly pass.
pub struct Outputs<'a> {
    /// Internal forces (3 per node), overwritten.
    pub force: &'a mut [f64],
    /// Tangent values in pattern order, overwritten when present.
    pub tangent: Option<&'a mut [f64]>,
    /// Trial Gauss-point states, overwritten.
    pub trial: &'a mut [PointState],
    /// Gauss-point stresses, overwritten.
    pub stress: &'a mut [Voigt],
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
    /// Builds numbering, pattern, scatter maps and colours.
    ///
    /// `constrained[d]` marks DOFs without an equation; `couplings` lists
    /// extra node pairs (contact between bodies) that must be in the pattern.
    pub fn new(mesh: &Mesh, constrained: &[bool], couplings: &[(usize, usize)]) -> Result<Self, LinearError> {
        let t0 = std::time::Instant::now();
        let adjacency = node_adjacency(mesh, couplings);
        let graph: Vec<Vec<usize>> =
            adjacency.iter().enumerate().map(|(n, l)| l.iter().copied().filter(|&m| m != n).collect()).collect();
        let order = nested_dissection(&graph)?;
        let mut eq = vec![NO_EQ; 3 * mesh.n_nodes()];
        let mut n_eq = 0;
        for &node in &order {
            for c in 0..3 {
                if !constrained[3 * node + c] {
                    eq[3 * node + c] = n_eq;
                    n_eq += 1;
                }
            }
        }
        let dofs = DofMap { eq, n_eq };
        let ordering_time = t0.elapsed();
        let t0 = std::time::Instant::now();
        let pattern = lower_pattern(&dofs, &adjacency);
        if pattern.nnz() >= u32::MAX as usize {
            return Err(LinearError::Symbolic(format!(
                "{} stored matrix entries exceed the scatter-map index range (u32)",
                pattern.nnz()
            )));
        }

        let elements: Vec<ElementRef> = mesh
            .bodies
            .iter()
            .enumerate()
            .flat_map(|(b, body)| (0..body.n_elements()).map(move |e| ElementRef { body: b, element: e }))
            .collect();
        let maps: Vec<Vec<u32>> = elements
            .par_iter()
            .map(|r| {
                let mut nodes = Vec::new();
                mesh.bodies[r.body].element_nodes(r.element, &mut nodes);
                let eq = &dofs.eq;
                let eqs: Vec<usize> = nodes.iter().flat_map(|&n| (0..3).map(move |c| eq[3 * n + c])).collect();
                let n = eqs.len();
                let mut map = Vec::with_capacity(n * (n + 1) / 2);
                for p in 0..n {
                    for q in p..n {
                        let (a, b) = (eqs[p], eqs[q]);
                        map.push(if a == NO_EQ || b == NO_EQ {
                            u32::MAX
                        } else {
                            pattern.find(a.max(b), a.min(b)).expect("element entry in pattern") as u32
                        });
                    }
                }
                map
            })
            .collect();
        let mut scatter_offsets = Vec::with_capacity(elements.len() + 1);
        let mut scatter = Vec::with_capacity(maps.iter().map(Vec::len).sum());
        for m in maps {
            scatter_offsets.push(scatter.len());
            scatter.extend(m);
        }
        scatter_offsets.push(scatter.len());
        let colors = colour(mesh, &elements);
        Ok(Self {
            dofs,
            pattern,
            elements,
            scatter_offsets,
            scatter,
            colors,
            elastic_cache: Vec::new(),
            ordering_time,
            pattern_time: t0.elapsed(),
        })
    }

    /// Adds the 3×3 block `k` coupling nodes `a` (rows) and `b` (columns) of
    /// a symmetric matrix stored as its lower triangle. For `a ≠ b` the
    /// caller adds the `(a, b)` block once; its transpose is implied.
    pub fn add_node_block(&self, values: &mut [f64], a: usize, b: usize, k: &[[f64; 3]; 3]) {
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

    /// Computes and keeps the elastic stiffness of every element, packed in
    /// the order of its scatter map. Later assemblies reuse it for elements
    /// whose Gauss points all return the elastic tangent, so an element only
    /// recomputes its nuclei while it is (or is about to be) plastic.
    pub fn cache_elastic(&mut self, input: &Inputs<'_>) {
        let cache: Vec<Vec<f64>> = self
            .elements
            .par_iter()
            .map_init(
                || (Workspace::default(), Vec::new()),
                |(ws, nodes), r| {
                    let body = &input.mesh.bodies[r.body];
                    let geom = &input.geometry[r.body];
                    body.element_nodes(r.element, nodes);
                    let ngp = geom.gp_per_element();
                    let zero = vec![0.0; 3 * nodes.len()];
                    let (mut trial, mut stress) = (vec![PointState::default(); ngp], vec![[0.0; 6]; ngp]);
                    let committed = vec![PointState::default(); ngp];
                    // zero displacement and a virgin state: every point is elastic
                    elements::element_response(
                        geom,
                        r.element,
                        body.section.n_elements(),
                        &zero,
                        &input.materials[body.material],
                        PointData { committed: &committed, trial: &mut trial, stress: &mut stress },
                        TangentMode::Always,
                        ws,
                    );
                    let n = 3 * nodes.len();
                    let mut packed = Vec::with_capacity(n * (n + 1) / 2);
                    for p in 0..n {
                        packed.extend_from_slice(&ws.tangent[p * n + p..(p + 1) * n]);
                    }
                    packed
                },
            )
            .collect();
        self.elastic_cache = cache.concat();
    }

    /// Drops the elastic cache: every element then recomputes its tangent.
    pub fn clear_elastic_cache(&mut self) {
        self.elastic_cache.clear();
    }

    /// Element loop: internal forces (and tangent) of all elements from the
    /// displacements, with trial states and Gauss-point stresses. Returns
    /// the number of plastic Gauss points.
    pub fn assemble(&self, input: &Inputs<'_>, out: Outputs<'_>) -> usize {
        out.force.fill(0.0);
        let with_tangent = out.tangent.is_some();
        let mode = match (with_tangent, self.elastic_cache.is_empty()) {
            (false, _) => TangentMode::None,
            (true, true) => TangentMode::Always,
            (true, false) => TangentMode::UnlessElastic,
        };
        let mut empty: [f64; 0] = [];
        let tangent = out.tangent.unwrap_or(&mut empty);
        tangent.fill(0.0);
        let force = Disjoint::new(out.force);
        let tangent = Disjoint::new(tangent);
        let trial = Disjoint::new(out.trial);
        let stress = Disjoint::new(out.stress);
        let mut plastic = 0;
        for colour in &self.colors {
            plastic += colour
                .par_iter()
                .map_init(
                    || (Vec::new(), Vec::new()),
                    |(nodes, ue), &ge| {
                        let r = self.elements[ge];
                        let body = &input.mesh.bodies[r.body];
                        let geom = &input.geometry[r.body];
                        body.element_nodes(r.element, nodes);
                        ue.clear();
                        ue.extend(nodes.iter().flat_map(|&n| (0..3).map(move |c| input.u[3 * n + c])));
                        let ngp = geom.gp_per_element();
                        let g0 = input.gp_offsets[r.body] + r.element * ngp;
                        // SAFETY: Gauss points of an element belong to it alone.
                        let points = unsafe {
                            PointData {
                                committed: &input.committed[g0..g0 + ngp],
                                trial: trial.range(g0, ngp),
                                stress: stress.range(g0, ngp),
                            }
                        };
                        WORKSPACE.with_borrow_mut(|ws| {
                            let stats = elements::element_response(
                                geom,
                                r.element,
                                body.section.n_elements(),
                                ue,
                                &input.materials[body.material],
                                points,
                                mode,
                                ws,
                            );
                            let range = self.scatter_offsets[ge]..self.scatter_offsets[ge + 1];
                            // SAFETY: elements of one colour share no node, hence
                            // no DOF and no matrix entry.
                            unsafe {
                                for (a, &n) in nodes.iter().enumerate() {
                                    for c in 0..3 {
                                        *force.get(3 * n + c) += ws.force[3 * a + c];
                                    }
                                }
                                let map = &self.scatter[range.clone()];
                                if stats.tangent_computed {
                                    let n = 3 * nodes.len();
                                    let mut k = 0;
                                    for p in 0..n {
                                        for &v in &ws.tangent[p * n + p..(p + 1) * n] {
                                            let pos = map[k];
                                            if pos != u32::MAX {
                                                *tangent.get(pos as usize) += v;
                                            }
                                            k += 1;
                                        }
                                    }
                                } else if with_tangent {
                                    for (&pos, &v) in map.iter().zip(&self.elastic_cache[range]) {
                                        if pos != u32::MAX {
                                            *tangent.get(pos as usize) += v;
                                        }
                                    }
                                }
                            }
                            stats.plastic_points
                        })
                    },
                )
                .sum::<usize>();
        }
        plastic
    }
}

/// Sorted node adjacency (including the node itself) of the whole mesh.
fn node_adjacency(mesh: &Mesh, couplings: &[(usize, usize)]) -> Vec<Vec<usize>> {
    let mut adjacency = Vec::with_capacity(mesh.n_nodes());
    for body in &mesh.bodies {
        let sec = &body.section;
        let mut sec_adj = vec![BTreeSet::new(); sec.n_nodes()];
        for e in 0..sec.n_elements() {
            let el = sec.element(e);
            for &a in el {
                sec_adj[a].extend(el.iter().copied());
            }
        }
        let p = body.axis.kind.order();
        let mut ax_adj = vec![BTreeSet::new(); body.axis.n_nodes()];
        for e in 0..body.axis.n_elements() {
            let first = body.axis.first_node(e);
            for i in first..=first + p {
                ax_adj[i].extend(first..=first + p);
            }
        }
        for ax in &ax_adj {
            for sa in &sec_adj {
                adjacency.push(ax.iter().flat_map(|&j| sa.iter().map(move |&s| body.node(j, s))).collect::<Vec<_>>());
            }
        }
    }
    for &(a, b) in couplings {
        adjacency[a].push(b);
        adjacency[b].push(a);
    }
    for l in &mut adjacency {
        l.sort_unstable();
        l.dedup();
    }
    adjacency
}

/// Lower-triangular pattern in equation numbering.
fn lower_pattern(dofs: &DofMap, adjacency: &[Vec<usize>]) -> LowerCsc {
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); dofs.n_eq];
    for (node, adj) in adjacency.iter().enumerate() {
        for c in 0..3 {
            let col = dofs.eq[3 * node + c];
            if col == NO_EQ {
                continue;
            }
            let rows = &mut columns[col];
            for &m in adj {
                for d in 0..3 {
                    let r = dofs.eq[3 * m + d];
                    if r != NO_EQ && r >= col {
                        rows.push(r);
                    }
                }
            }
            rows.sort_unstable();
        }
    }
    let mut col_ptr = Vec::with_capacity(dofs.n_eq + 1);
    let mut row_idx = Vec::with_capacity(columns.iter().map(Vec::len).sum());
    col_ptr.push(0);
    for c in columns {
        row_idx.extend(c);
        col_ptr.push(row_idx.len());
    }
    LowerCsc { n: dofs.n_eq, col_ptr, row_idx }
}

/// Colours: greedy colouring of section elements × parity of beam elements.
fn colour(mesh: &Mesh, elements: &[ElementRef]) -> Vec<Vec<usize>> {
    let mut section_colours: Vec<Vec<usize>> = Vec::new();
    for body in &mesh.bodies {
        let sec = &body.section;
        let mut node_colours: Vec<Vec<usize>> = vec![Vec::new(); sec.n_nodes()];
        let mut colours = Vec::with_capacity(sec.n_elements());
        for e in 0..sec.n_elements() {
            let el = sec.element(e);
            let c = (0..).find(|c| el.iter().all(|&n| !node_colours[n].contains(c))).unwrap();
            for &n in el {
                node_colours[n].push(c);
            }
            colours.push(c);
        }
        section_colours.push(colours);
    }
    let mut colors: Vec<Vec<usize>> = Vec::new();
    for (ge, r) in elements.iter().enumerate() {
        let body = &mesh.bodies[r.body];
        let (es, eb) = body.split_element(r.element);
        let c = 2 * section_colours[r.body][es] + eb % 2;
        if colors.len() <= c {
            colors.resize(c + 1, Vec::new());
        }
        colors[c].push(ge);
    }
    colors.retain(|c| !c.is_empty());
    colors
}
