//! Tests of the surface-contact geometry: face points and segmentation.

use super::*;
use crate::mesh::{BeamAxis, CrossSection, Division};
use crate::shape::{BeamElementKind, SectionElementKind};

fn block(kind: SectionElementKind, nx: usize, z: [f64; 2], offset: usize) -> Body {
    let xl = Division::uniform(0.0, 0.3, nx).lines("x").unwrap();
    let zl = Division::uniform(z[0], z[1], 2).lines("z").unwrap();
    let yl = Division::uniform(0.0, 0.2, 3).lines("y").unwrap();
    Body {
        name: "b".into(),
        section: CrossSection::rectangle(kind, &xl, &zl).unwrap(),
        axis: BeamAxis::from_lines(BeamElementKind::B3, &yl),
        material: 0,
        element_materials: Vec::new(),
        element_layers: Vec::new(),
        node_offset: offset,
        element_offset: 0,
        whole_size: None,
    }
}

/// A face point reproduces the face's geometry: position on the top
/// face z = 0.1, outward normal +z, shape values summing to one
/// (partition of unity) and interpolating the node coordinates.
#[test]
fn face_points_follow_the_expansion() {
    let b = block(SectionElementKind::L9, 3, [0.0, 0.1], 0);
    let top = crate::bc::boundary_faces(&b)
        .into_iter()
        .find(|f| matches!(f.side, FaceSide::Lateral(_)) && face_box(&b, f).0[2] > 0.099)
        .unwrap();
    let fp = face_point(&b, &top, 0.3, -0.5);
    assert!((fp.position[2] - 0.1).abs() < 1e-15 && fp.normal == [0.0, 0.0, 1.0], "{fp:?}");
    assert!((fp.shapes.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    for k in 0..3 {
        let x: f64 = fp.nodes.iter().zip(&fp.shapes).map(|(&n, s)| s * b.local_coords(n)[k]).sum();
        assert!((x - fp.position[k]).abs() < 1e-14);
    }
}

/// Segmentation against a master section cut at x = 0.1, 0.2 (three
/// elements) of a slave edge spanning [0, 0.15] (two elements): the
/// first slave edge is cut at a = 1/3 (x = 0.1 on [0, 0.15]).
#[test]
fn slave_edges_are_cut_at_master_edge_ends() {
    let slave = block(SectionElementKind::L9, 2, [0.1, 0.2], 0);
    let master = block(SectionElementKind::L9, 3, [0.0, 0.1], 1000);
    let bottom = |b: &Body, z: f64| {
        crate::bc::boundary_faces(b)
            .into_iter()
            .filter(|f| matches!(f.side, FaceSide::Lateral(_)) && (face_box(b, f).1[2] - z).abs() < 1e-12)
            .filter(|f| (face_box(b, f).0[2] - z).abs() < 1e-12)
            .collect::<Vec<_>>()
    };
    let sf = bottom(&slave, 0.1);
    let mf = bottom(&master, 0.1);
    let first = sf.iter().find(|f| face_box(&slave, f).0[0] < 1e-12 && f.beam_element == 0).unwrap();
    let [a, b] = breakpoints(&slave, first, &master, &mf, 1e-3);
    assert_eq!(b, vec![-1.0, 1.0], "same axis mesh: no cut along y");
    assert_eq!(a.len(), 3, "{a:?}");
    assert!((a[1] - (2.0 * 0.1 / 0.15 - 1.0)).abs() < 1e-12, "{a:?}");
}
