//! The redistributed mass matrix against closed forms: the body's mass and
//! momentum kept, the contact nodes massless.

use super::*;
use crate::assembly::Assembler;
use crate::mesh::{BeamAxis, Body, CrossSection, Division};
use crate::shape::{BeamElementKind, SectionElementKind};
use crate::values::CellValues;

/// A 10 × 10 mm rectangle of 2 × 1 L9 along y over [0, 0.1] m, 5 B3.
fn mesh() -> Mesh {
    let section = CrossSection::from_quads(
        SectionElementKind::L9,
        &[[0.0, 0.0], [0.005, 0.0], [0.01, 0.0], [0.0, 0.01], [0.005, 0.01], [0.01, 0.01]],
        &[[0, 1, 4, 3], [1, 2, 5, 4]],
        "s",
    )
    .unwrap();
    let lines = Division::uniform(0.0, 0.1, 5).lines("y").unwrap();
    Mesh::new(vec![Body::new("b", section, BeamAxis::from_lines(BeamElementKind::B3, &lines), 0)])
}

const RHO: f64 = 8000.0;

/// `vᵀ M v` of the assembled lower triangle for per-DOF `v`.
fn quadratic(a: &Assembler, m: &[f64], v: &[f64]) -> f64 {
    let n = a.dofs.n_eq;
    let mut x = vec![0.0; n];
    for (d, &e) in a.dofs.eq.iter().enumerate() {
        if e != crate::assembly::NO_EQ {
            x[e] = v[d];
        }
    }
    let mut y = vec![0.0; n];
    a.pattern.mul_symmetric(m, &x, &mut y);
    x.iter().zip(&y).map(|(p, q)| p * q).sum()
}

/// The nodes of the end face y = 0.1 m and of the face z = 0 (a lateral
/// contact) made contact nodes: with either matrix, a rigid translation
/// still carries the body's mass ρ A L (the weights of a row sum to one),
/// every contact node's velocity is invisible to the matrix (its rows are
/// zero: a velocity of the contact nodes alone has no kinetic energy),
/// and an interior velocity still has some. A map that forgot a node, or
/// weights not summing to one, fails.
#[test]
fn the_contact_nodes_lose_their_mass_and_the_body_keeps_its_own() {
    let mesh = mesh();
    let body = &mesh.bodies[0];
    let cells = vec![CellValues::new(body).unwrap()];
    let a = Assembler::new(&mesh, crate::assembly::Numbering::new(&mesh, &vec![false; mesh.n_dofs()], &[]).unwrap());
    let mass = RHO * 1e-4 * 0.1;
    let end: Vec<usize> = (0..mesh.n_nodes()).filter(|&n| (mesh.coords(n)[1] - 0.1).abs() < 1e-12).collect();
    let bottom: Vec<usize> = (0..mesh.n_nodes()).filter(|&n| mesh.coords(n)[2].abs() < 1e-12).collect();
    assert_eq!((end.len(), bottom.len()), (15, 5 * 11));
    for contact in [&end, &bottom] {
        let r = Redistribution::new(&mesh, contact);
        assert!(r.stranded().is_empty());
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            let m = crate::dynamics::mass::assemble(&a, &mesh, &cells, &[vec![RHO; 2]], kind, Some(&r)).unwrap();
            for dir in 0..3 {
                let v: Vec<f64> = (0..mesh.n_dofs()).map(|d| f64::from(u8::from(d % 3 == dir))).collect();
                let t = quadratic(&a, &m, &v);
                assert!((t - mass).abs() < 1e-12 * mass, "{kind:?} direction {dir}: {t} against {mass}");
            }
            let only = |set: &[usize]| -> Vec<f64> {
                (0..mesh.n_dofs()).map(|d| if set.contains(&(d / 3)) { 1.0 } else { 0.0 }).collect()
            };
            assert!(quadratic(&a, &m, &only(contact)).abs() < 1e-15 * mass, "{kind:?}");
            for &n in contact {
                assert!(r.is_massless(n));
            }
            let interior: Vec<usize> = (0..mesh.n_nodes()).filter(|n| !contact.contains(n)).collect();
            assert!(quadratic(&a, &m, &only(&interior)) > 0.5 * mass, "{kind:?}");
        }
    }
}

/// One element through the height with both faces z = 0 and z = 0.01
/// contact nodes: every node of every element is a contact node, none has
/// a neighbour to take its mass, so all keep it (and are reported).
#[test]
fn an_element_of_contact_nodes_only_keeps_its_mass() {
    let mesh = mesh();
    let faces: Vec<usize> =
        (0..mesh.n_nodes()).filter(|&n| mesh.coords(n)[2].abs() < 1e-12 || mesh.coords(n)[2] > 0.0099).collect();
    let r = Redistribution::new(&mesh, &faces);
    // L9's middle row (z = 0.005) is not on a face: the faces' nodes move there
    assert!(r.stranded().is_empty());
    let all: Vec<usize> = (0..mesh.n_nodes()).collect();
    let r = Redistribution::new(&mesh, &all);
    assert_eq!(r.stranded().len(), mesh.n_nodes());
    assert!(!r.is_massless(0));
}
