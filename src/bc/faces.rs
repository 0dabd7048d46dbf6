//! Boundary faces of a body and their integrals.
//!
//! A body element (section element × beam element) has four *lateral* faces
//! (a section edge swept along the beam element) and two *end* faces (the
//! section element at either end of the beam element). A face is on the
//! boundary if its section edge is on the section boundary (lateral) or if it
//! is at the first or last beam node (end). The integrals use
//! [`crate::values::FacetValues`], the same shape values as the element
//! kernel, with Gauss rules of `p + 1` points per direction (exact for the
//! straight edges of the current sections).

use super::Selection;
use crate::mesh::Body;
pub use crate::values::FaceSide;
use crate::values::FacetValues;

/// A boundary face of a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Face {
    /// Section element.
    pub section_element: usize,
    /// Beam element.
    pub beam_element: usize,
    /// Which face.
    pub side: FaceSide,
}

/// Integrals over one face.
#[derive(Debug, Clone)]
pub struct FaceIntegral {
    /// Global nodes of the face with a non-zero weight.
    pub nodes: Vec<usize>,
    /// `∫_face N_a dA` for each node (m²), all positive for Lagrange faces.
    pub weights: Vec<f64>,
    /// Outward unit normal.
    pub normal: [f64; 3],
    /// Face area (m²).
    pub area: f64,
    /// Thickness of the element behind the face, measured along the normal (m).
    pub depth: f64,
}

/// All boundary faces of a body.
pub fn boundary_faces(body: &Body) -> Vec<Face> {
    let mut faces = Vec::new();
    let nb = body.axis.n_elements();
    for (es, k) in body.section.boundary_edges() {
        for eb in 0..nb {
            faces.push(Face { section_element: es, beam_element: eb, side: FaceSide::Lateral(k) });
        }
    }
    for es in 0..body.section.n_elements() {
        faces.push(Face { section_element: es, beam_element: 0, side: FaceSide::End(false) });
        faces.push(Face { section_element: es, beam_element: nb - 1, side: FaceSide::End(true) });
    }
    faces
}

/// Global nodes of a face (all of them, in no particular order).
pub(crate) fn face_nodes(body: &Body, face: &Face) -> Vec<usize> {
    let el = body.section.element(face.section_element);
    let first = body.axis.first_node(face.beam_element);
    let p = body.axis.kind.order();
    match face.side {
        FaceSide::Lateral(k) => {
            let edge = body.section.edge_local_nodes(k);
            (first..=first + p).flat_map(|i| edge.iter().map(move |&t| body.node(i, el[t]))).collect()
        }
        FaceSide::End(end) => {
            let i = if end { first + p } else { first };
            el.iter().map(|&t| body.node(i, t)).collect()
        }
    }
}

/// Boundary faces of `body` all of whose nodes are selected.
pub(crate) fn selected_faces(body: &Body, selection: &Selection) -> Vec<Face> {
    boundary_faces(body)
        .into_iter()
        .filter(|f| face_nodes(body, f).iter().all(|&n| selection.contains(body.local_coords(n - body.node_offset))))
        .collect()
}

/// Integrates the shape functions over a face: `∫ N_a dA` per node (nodes
/// whose integral vanishes are left out), the mean outward normal, the area
/// and the depth of the element behind the face.
pub fn integrate_face(body: &Body, face: &Face) -> FaceIntegral {
    integrate_face_with(body, face, |_| 1.0)
}

/// As [`integrate_face`], with the shape functions weighted by `f` at each
/// point of the face: `∫ N_a f dA` per node.
pub(crate) fn integrate_face_with(body: &Body, face: &Face, f: impl Fn([f64; 3]) -> f64) -> FaceIntegral {
    let fv = FacetValues::new(body, face.section_element, face.beam_element, face.side);
    let n = fv.nodes.len();
    let per_node = fv.integrate(|q| {
        let mut x = [0.0; 3];
        for (s, &node) in fv.shapes[q * n..(q + 1) * n].iter().zip(&fv.nodes) {
            let c = body.local_coords(node - body.node_offset);
            for k in 0..3 {
                x[k] += s * c[k];
            }
        }
        f(x)
    });
    let area: f64 = fv.weights.iter().sum();
    let mut normal = [0.0; 3];
    for (n, w) in fv.normals.iter().zip(&fv.weights) {
        for k in 0..3 {
            normal[k] += w * n[k] / area;
        }
    }
    let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
    let scale = per_node.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (nodes, weights) =
        fv.nodes.iter().zip(&per_node).filter(|(_, w)| w.abs() > 1e-12 * scale).map(|(&n, &w)| (n, w)).unzip();
    FaceIntegral { nodes, weights, normal: normal.map(|v| v / len), area, depth: fv.depth }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bc::Condition;
    use crate::mesh::{BeamAxis, CrossSection, Division};
    use crate::shape::{BeamElementKind, SectionElementKind};

    fn block() -> Body {
        let xl = Division::uniform(0.0, 0.5, 3).lines("x").unwrap();
        let zl = Division::uniform(0.0, 0.3, 2).lines("z").unwrap();
        let yl = Division::uniform(0.0, 0.1, 2).lines("y").unwrap();
        Body {
            name: "b".into(),
            section: CrossSection::rectangle(SectionElementKind::L9, &xl, &zl).unwrap(),
            axis: BeamAxis::from_lines(BeamElementKind::B4, &yl),
            material: 0,
            element_materials: Vec::new(),
            element_layers: Vec::new(),
            node_offset: 0,
            element_offset: 0,
            whole_size: None,
        }
    }

    #[test]
    fn face_weights_sum_to_areas_and_normals_point_out() {
        let b = block();
        let faces = boundary_faces(&b);
        // 2·(3+2) edges × 2 beam elements + 2·6 end faces
        assert_eq!(faces.len(), 10 * 2 + 12);
        let mut total = 0.0;
        for f in &faces {
            let fi = integrate_face(&b, f);
            let s: f64 = fi.weights.iter().sum();
            assert!((s - fi.area).abs() < 1e-14);
            assert!(fi.weights.iter().all(|&w| w > 0.0));
            total += fi.area;
        }
        let exact = 2.0 * (0.5 * 0.3 + 0.5 * 0.1 + 0.3 * 0.1);
        assert!((total - exact).abs() < 1e-12);
        // the top face z = 0.3 has normal +z
        let top = Selection {
            conditions: [None, None, Some(Condition::Equal(0.3))],
            tolerance: 1e-9,
            region: None,
            radial: None,
        };
        let sel = selected_faces(&b, &top);
        assert_eq!(sel.len(), 3 * 2);
        for f in &sel {
            let fi = integrate_face(&b, f);
            // from the map's tangents: exact up to round-off
            assert!((fi.normal[2] - 1.0).abs() < 1e-15 && fi.normal[0].abs() < 1e-15 && fi.normal[1] == 0.0);
            assert!((fi.depth - 0.15).abs() < 1e-12);
        }
    }
}
