//! Meshes: the beam axis, cross-sections, bodies and global node numbering.
//!
//! A body is the tensor product of a cross-section mesh over x–z and a beam
//! axis mesh along y (paper Fig. 1 and eq. 6). Its 3D nodes are the pairs
//! (beam node `i`, section node `τ`) and its elements the pairs (beam element,
//! section element). Global node numbers run body by body:
//!
//! `node = body.node_offset + i · n_section_nodes + τ`
//!
//! Degrees of freedom are `3 · node + c` with `c = 0, 1, 2` for `u_x, u_y, u_z`
//! (the equation numbering for the solver is in `crate::assembly`).

pub mod blocks;
mod clip;
mod division;
pub mod gmsh;
mod grid;
mod overlaps;
pub(crate) mod profiles;
mod properties;
mod section;
pub mod twins;

pub(crate) use division::{Division, Segment};
pub(crate) use grid::{boundary_at, grid_cell, grid_size, hole_intervals};
pub use properties::SectionProperties;
pub use section::{CrossSection, Region};
pub use twins::EdgeTwin;

use crate::shape::BeamElementKind;

/// Largest absolute coordinate of a mesh (m): a 10 km structure.
pub(crate) const MAX_COORD: f64 = 1e4;
/// Smallest element length of a division relative to the divided span:
/// below it round-off swamps the element's own size.
pub(crate) const MIN_RELATIVE_SIZE: f64 = 1e-9;
/// Accepted range of a grading ratio (last / first element length).
pub(crate) const GRADING_RATIO: (f64, f64) = (1e-4, 1e4);

/// Errors raised while building meshes. Every message names the model-file
/// key, the offending value and what is allowed.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
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
}

impl MeshError {
    /// Shorthand for [`MeshError::Invalid`].
    pub fn invalid(key: impl Into<String>, value: impl Into<String>, allowed: impl Into<String>) -> Self {
        Self::Invalid { key: key.into(), value: value.into(), allowed: allowed.into() }
    }
}

/// The beam axis: Lagrange elements along y, nodes equispaced inside each element.
#[derive(Debug, Clone)]
pub struct BeamAxis {
    /// Element type.
    pub kind: BeamElementKind,
    /// Node coordinates y (m), increasing. Element `e` owns nodes `e·p ..= e·p + p`.
    pub nodes: Vec<f64>,
}

impl BeamAxis {
    /// Axis with elements between consecutive `lines` (element boundaries).
    pub(crate) fn from_lines(kind: BeamElementKind, lines: &[f64]) -> Self {
        let p = kind.order();
        let mut nodes = vec![lines[0]];
        for w in lines.windows(2) {
            for k in 1..=p {
                nodes.push(if k == p { w[1] } else { w[0] + (w[1] - w[0]) * k as f64 / p as f64 });
            }
        }
        Self { kind, nodes }
    }

    /// Number of beam elements.
    pub fn n_elements(&self) -> usize {
        (self.nodes.len() - 1) / self.kind.order()
    }

    /// Number of beam nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// First node index of element `e` (its nodes are `first ..= first + p`).
    pub fn first_node(&self, e: usize) -> usize {
        e * self.kind.order()
    }

    /// End coordinates `(y0, y1)` of element `e`.
    pub fn element_span(&self, e: usize) -> (f64, f64) {
        let p = self.kind.order();
        (self.nodes[e * p], self.nodes[e * p + p])
    }

    /// Elements containing `y` (within `tol`), with the natural coordinate ζ.
    pub fn locate(&self, y: f64, tol: f64) -> Vec<(usize, f64)> {
        (0..self.n_elements())
            .filter_map(|e| {
                let (a, b) = self.element_span(e);
                (y >= a - tol && y <= b + tol).then(|| (e, (2.0 * (y - a) / (b - a) - 1.0).clamp(-1.0, 1.0)))
            })
            .collect()
    }
}

/// One deformable body: a cross-section swept along a beam axis.
#[derive(Debug, Clone)]
pub struct Body {
    /// Name from the model file.
    pub name: String,
    /// Cross-section mesh (x–z).
    pub section: CrossSection,
    /// Beam-axis mesh (y).
    pub axis: BeamAxis,
    /// Index of the body's material in the model's material list.
    pub material: usize,
    /// The material of each section element where they differ (plies,
    /// zones; indices into the model's list, oriented copies included);
    /// empty: [`Body::material`] everywhere.
    pub element_materials: Vec<usize>,
    /// The layer of each section element where the section has layers
    /// (the ply or `[[bodies.zones]]` entry that gave it its material, in
    /// the order `setup::zones` applies them); empty: one layer. Two plies
    /// of one material and orientation are two layers, bonded at their
    /// boundary (`post::failure`'s interlaminar criterion).
    pub(crate) element_layers: Vec<usize>,
    /// Global number of the body's first node.
    pub node_offset: usize,
    /// Global number of the body's first element.
    pub(crate) element_offset: usize,
    /// [`Body::size`] of the whole structure's body when `[[symmetry]]`
    /// planes cut it (`None`: not cut): a quarter model's tolerances and
    /// bounds are then those of the whole structure.
    pub(crate) whole_size: Option<f64>,
}

impl Body {
    /// A body of one material (`material`, an index into the model's
    /// list); its node and element offsets are set by [`Mesh::new`].
    pub fn new(name: impl Into<String>, section: CrossSection, axis: BeamAxis, material: usize) -> Self {
        Self {
            name: name.into(),
            section,
            axis,
            material,
            element_materials: Vec::new(),
            element_layers: Vec::new(),
            node_offset: 0,
            element_offset: 0,
            whole_size: None,
        }
    }

    /// The material of section element `es` (of every body element over it).
    pub fn material_of(&self, es: usize) -> usize {
        self.element_materials.get(es).copied().unwrap_or(self.material)
    }

    /// The layer of section element `es` ([`Body::element_layers`]; `0`
    /// where the section has one).
    pub(crate) fn layer_of(&self, es: usize) -> usize {
        self.element_layers.get(es).copied().unwrap_or(0)
    }

    /// Every material the body uses, without repeats, in increasing order.
    pub fn materials(&self) -> Vec<usize> {
        if self.element_materials.is_empty() {
            return vec![self.material];
        }
        let mut m = self.element_materials.clone();
        m.sort_unstable();
        m.dedup();
        m
    }

    /// True if the body has more than one material (plies, zones): its
    /// stresses jump between them.
    pub(crate) fn is_layered(&self) -> bool {
        self.materials().len() > 1
    }

    /// Number of 3D nodes.
    pub fn n_nodes(&self) -> usize {
        self.section.n_nodes() * self.axis.n_nodes()
    }

    /// Number of 3D (CUF) elements.
    pub fn n_elements(&self) -> usize {
        self.section.n_elements() * self.axis.n_elements()
    }

    /// Nodes per 3D element.
    pub fn nodes_per_element(&self) -> usize {
        self.section.kind.nodes() * self.axis.kind.nodes()
    }

    /// Global node of beam node `i` and section node `tau`.
    pub fn node(&self, i: usize, tau: usize) -> usize {
        self.node_offset + i * self.section.n_nodes() + tau
    }

    /// Splits a body element index into (section element, beam element).
    pub fn split_element(&self, e: usize) -> (usize, usize) {
        let ns = self.section.n_elements();
        (e % ns, e / ns)
    }

    /// Global nodes of body element `e`, beam node outer, section node inner
    /// (local node `a = i · n_sec + τ`), written into `out`.
    pub fn element_nodes(&self, e: usize, out: &mut Vec<usize>) {
        let (es, eb) = self.split_element(e);
        out.clear();
        let first = self.axis.first_node(eb);
        for i in first..=first + self.axis.kind.order() {
            for &tau in self.section.element(es) {
                out.push(self.node(i, tau));
            }
        }
    }

    /// Coordinates of a body-local node index `n = i · n_sec + τ`.
    pub fn local_coords(&self, n: usize) -> [f64; 3] {
        let ns = self.section.n_nodes();
        let (i, tau) = (n / ns, n % ns);
        let [x, z] = self.section.nodes[tau];
        [x, self.axis.nodes[i], z]
    }

    /// A length scale of the body: the diagonal of its bounding box, of the
    /// whole structure's body if symmetry planes cut it (its tolerances and
    /// bounds are the whole structure's).
    pub fn size(&self) -> f64 {
        self.whole_size.unwrap_or_else(|| diagonal(&self.section, &self.axis.nodes))
    }
}

/// The diagonal of the bounding box of a section swept along the axis
/// nodes (or lines) `axis`.
pub(crate) fn diagonal(section: &CrossSection, axis: &[f64]) -> f64 {
    let b = section.bounds();
    let ly = axis.last().unwrap_or(&0.0) - axis.first().unwrap_or(&0.0);
    ((b[1] - b[0]).powi(2) + (b[3] - b[2]).powi(2) + ly * ly).sqrt()
}

/// All bodies of a model with their global node numbering.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Bodies in model-file order.
    pub bodies: Vec<Body>,
}

impl Mesh {
    /// Assigns node and element offsets to the bodies.
    pub fn new(mut bodies: Vec<Body>) -> Self {
        let (mut n, mut e) = (0, 0);
        for b in &mut bodies {
            b.node_offset = n;
            b.element_offset = e;
            n += b.n_nodes();
            e += b.n_elements();
        }
        Self { bodies }
    }

    /// Total number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.bodies.iter().map(Body::n_nodes).sum()
    }

    /// Total number of degrees of freedom (3 per node).
    pub fn n_dofs(&self) -> usize {
        3 * self.n_nodes()
    }

    /// Total number of 3D elements.
    pub fn n_elements(&self) -> usize {
        self.bodies.iter().map(Body::n_elements).sum()
    }

    /// Body owning a global node, and the node's body-local index.
    pub fn body_of(&self, node: usize) -> (usize, usize) {
        let b = self.bodies.iter().rposition(|b| b.node_offset <= node).unwrap_or(0);
        (b, node - self.bodies[b].node_offset)
    }

    /// Body owning a global element, and the element's body-local index.
    pub(crate) fn body_of_element(&self, e: usize) -> (usize, usize) {
        let b = self.bodies.iter().rposition(|b| b.element_offset <= e).unwrap_or(0);
        (b, e - self.bodies[b].element_offset)
    }

    /// Reference coordinates of a global node.
    pub fn coords(&self, node: usize) -> [f64; 3] {
        let (b, local) = self.body_of(node);
        self.bodies[b].local_coords(local)
    }

    /// Index of the body with this name.
    pub(crate) fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::SectionElementKind;

    fn body(kind: SectionElementKind, nx: usize, nz: usize, beam: BeamElementKind, ny: usize) -> Body {
        let xl = Division::uniform(0.0, 0.01, nx).lines("x").unwrap();
        let zl = Division::uniform(0.0, 0.01, nz).lines("z").unwrap();
        let yl = Division::uniform(0.0, 0.25, ny).lines("y").unwrap();
        Body::new("b", CrossSection::rectangle(kind, &xl, &zl).unwrap(), BeamAxis::from_lines(beam, &yl), 0)
    }

    /// DOF counts of the paper's discretizations (Nagaraj et al., Tables 1, 3, 4, 7).
    #[test]
    fn paper_dof_counts() {
        use BeamElementKind::B4;
        use SectionElementKind::L9;
        let block = Mesh::new(vec![body(L9, 18, 6, B4, 1)]);
        assert_eq!(block.n_dofs(), 5772);
        assert_eq!(Mesh::new(vec![body(L9, 2, 2, B4, 10)]).n_dofs(), 2325);
        assert_eq!(Mesh::new(vec![body(L9, 4, 4, B4, 10)]).n_dofs(), 7533);
        assert_eq!(Mesh::new(vec![body(L9, 4, 4, B4, 10), body(L9, 4, 4, B4, 10)]).n_dofs(), 15066);
        for (along, dofs) in [(4, 24120), (6, 33768)] {
            let mut b = body(L9, 1, 1, B4, 22);
            b.section = CrossSection::tube(L9, 0.0, 0.0, 0.03, 0.03, 0.0015, along, along, 1).unwrap();
            assert_eq!(Mesh::new(vec![b]).n_dofs(), dofs);
        }
    }

    #[test]
    fn element_nodes_are_beam_outer_section_inner() {
        let m = Mesh::new(vec![body(SectionElementKind::L4, 2, 1, BeamElementKind::B3, 2)]);
        let b = &m.bodies[0];
        let mut nodes = Vec::new();
        b.element_nodes(3, &mut nodes); // section element 1, beam element 1
        assert_eq!(nodes.len(), 12);
        // beam element 1 starts at beam node 2; section element 1 has corner nodes 1,2,4,5
        assert_eq!(&nodes[..4], &[2 * 6 + 1, 2 * 6 + 2, 2 * 6 + 4, 2 * 6 + 5]);
        let c = m.coords(nodes[0]);
        assert!((c[1] - 0.125).abs() < 1e-15 && (c[0] - 0.005).abs() < 1e-15);
    }
}
