//! Boundary faces of a body and their integrals.
//!
//! A body element (section element × beam element) has four *lateral* faces
//! (a section edge swept along the beam element) and two *end* faces (the
//! section element at either end of the beam element). A face is on the
//! boundary if its section edge is on the section boundary (lateral) or if it
//! is at the first or last beam node (end).
//!
//! Sections have straight edges and the axis is straight, so every face is
//! planar: its normal is constant and `∫_face N_a dA` factorizes into a
//! section part and a beam part, integrated exactly by Gauss rules.

use super::Selection;
use crate::elements::SectionGeometry;
use crate::mesh::Body;
use crate::quadrature::GaussRule;
use crate::shape::Lagrange1d;

/// Which face of a body element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceSide {
    /// Section edge `k` (see [`crate::mesh::EDGES`]) swept along the beam element.
    Lateral(usize),
    /// The section element at the start (`false`) or end (`true`) of the beam axis.
    End(bool),
}

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
fn face_nodes(body: &Body, face: &Face) -> Vec<usize> {
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
pub fn selected_faces(body: &Body, selection: &Selection) -> Vec<Face> {
    boundary_faces(body)
        .into_iter()
        .filter(|f| face_nodes(body, f).iter().all(|&n| selection.contains(body.local_coords(n - body.node_offset))))
        .collect()
}

/// Integrates the shape functions over a face.
pub fn integrate_face(body: &Body, section: &SectionGeometry, face: &Face) -> FaceIntegral {
    let el = body.section.element(face.section_element);
    let (y0, y1) = body.axis.element_span(face.beam_element);
    let p_beam = body.axis.kind.order();
    let first = body.axis.first_node(face.beam_element);
    let es = face.section_element;
    // section-element area, for the depth of lateral faces
    let gp = section.n_gp;
    let el_area: f64 = section.weight[es * gp..(es + 1) * gp].iter().sum();
    let centroid = {
        let mut c = [0.0; 2];
        for q in 0..gp {
            let w = section.weight[es * gp + q];
            c[0] += w * section.position[es * gp + q][0] / el_area;
            c[1] += w * section.position[es * gp + q][1] / el_area;
        }
        c
    };
    match face.side {
        FaceSide::Lateral(k) => {
            let edge = body.section.edge_local_nodes(k);
            let a = body.section.nodes[el[edge[0]]];
            let b = body.section.nodes[el[*edge.last().unwrap()]];
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            let mut n2 = [(b[1] - a[1]) / len, -(b[0] - a[0]) / len];
            let mid = [0.5 * (a[0] + b[0]) - centroid[0], 0.5 * (a[1] + b[1]) - centroid[1]];
            if n2[0] * mid[0] + n2[1] * mid[1] < 0.0 {
                n2 = [-n2[0], -n2[1]];
            }
            let we = line_weights(body.section.kind.order(), len);
            let wb = line_weights(p_beam, y1 - y0);
            let mut nodes = Vec::new();
            let mut weights = Vec::new();
            for (i, wy) in wb.iter().enumerate() {
                for (t, wx) in edge.iter().zip(&we) {
                    nodes.push(body.node(first + i, el[*t]));
                    weights.push(wx * wy);
                }
            }
            FaceIntegral { nodes, weights, normal: [n2[0], 0.0, n2[1]], area: len * (y1 - y0), depth: el_area / len }
        }
        FaceSide::End(end) => {
            let n_fun = section.n_fun;
            let mut weights = vec![0.0; n_fun];
            for q in 0..gp {
                let w = section.weight[es * gp + q];
                for (t, wt) in weights.iter_mut().enumerate() {
                    *wt += w * section.f[(es * gp + q) * n_fun + t];
                }
            }
            let i = if end { first + p_beam } else { first };
            FaceIntegral {
                nodes: el.iter().map(|&t| body.node(i, t)).collect(),
                weights,
                normal: [0.0, if end { 1.0 } else { -1.0 }, 0.0],
                area: el_area,
                depth: y1 - y0,
            }
        }
    }
}

/// `∫ l_k ds` of the 1D Lagrange functions of order `p` over a straight
/// segment of length `len` with equispaced nodes.
fn line_weights(p: usize, len: f64) -> Vec<f64> {
    let basis = Lagrange1d::new(p);
    let rule = GaussRule::new(p + 1);
    let (mut n, mut dn) = (vec![0.0; p + 1], vec![0.0; p + 1]);
    let mut w = vec![0.0; p + 1];
    for (x, wq) in rule.points.iter().zip(&rule.weights) {
        basis.eval(*x, &mut n, &mut dn);
        for k in 0..=p {
            w[k] += wq * n[k] * 0.5 * len;
        }
    }
    w
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
            node_offset: 0,
            element_offset: 0,
        }
    }

    #[test]
    fn face_weights_sum_to_areas_and_normals_point_out() {
        let b = block();
        let sg = SectionGeometry::new(&b.section, "b").unwrap();
        let faces = boundary_faces(&b);
        // 2·(3+2) edges × 2 beam elements + 2·6 end faces
        assert_eq!(faces.len(), 10 * 2 + 12);
        let mut total = 0.0;
        for f in &faces {
            let fi = integrate_face(&b, &sg, f);
            let s: f64 = fi.weights.iter().sum();
            assert!((s - fi.area).abs() < 1e-14);
            assert!(fi.weights.iter().all(|&w| w > 0.0));
            total += fi.area;
        }
        let exact = 2.0 * (0.5 * 0.3 + 0.5 * 0.1 + 0.3 * 0.1);
        assert!((total - exact).abs() < 1e-12);
        // the top face z = 0.3 has normal +z
        let top = Selection { conditions: [None, None, Some(Condition::Equal(0.3))], tolerance: 1e-9 };
        let sel = selected_faces(&b, &top);
        assert_eq!(sel.len(), 3 * 2);
        for f in &sel {
            let fi = integrate_face(&b, &sg, f);
            assert_eq!(fi.normal, [0.0, 0.0, 1.0]);
            assert!((fi.depth - 0.15).abs() < 1e-12);
        }
    }
}
