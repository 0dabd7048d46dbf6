//! Material interfaces of the 3D twin: the nodes where hexahedra of
//! different materials of one body meet are duplicated, one node per
//! material, and the copies tied to the original by `*EQUATION`s.
//!
//! Why: CalculiX's nodal stresses (the `.frd` file that
//! [`super::sample`] interpolates) are averages over every element at a
//! node. At a ply or skin–core interface the in-plane stresses jump by the
//! stiffness ratio (≈ 100 MPa in a carbon skin over ≈ 0.1 MPa in a foam
//! core), and the average made a core probe next to the skin read skin
//! stresses. With a node per material each side is averaged on its own, as
//! cufem's fields are evaluated in the element holding a point; the
//! displacement stays continuous through the equations (the meshes match
//! node for node, so the tied model is the shared-node one). A body of one
//! material, and so every isotropic single-material deck, is unchanged.
//!
//! The original node keeps the material first in the body's list
//! ([`super::material::body_element_sets`]); each copy is the dependent
//! term of its equations (`u_copy − u_original = 0`), except in directions
//! a constraint prescribes at that position, which constrains both nodes
//! alike (CalculiX refuses a dependent degree of freedom that is also
//! prescribed). A per-node load goes on the original only
//! (`super::deck::load_forces`).

use std::collections::HashMap;
use std::fmt::Write as _;

use super::Tie;
use super::mesh::HexMesh;
use cufem::setup::Model;

/// Duplicates the interface nodes of every body of several materials;
/// returns the ties. The copies are appended to `mesh.nodes`.
pub(super) fn split(mesh: &mut HexMesh, model: &Model) -> Vec<Tie> {
    let mut ties = Vec::new();
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        if body.materials().len() < 2 {
            continue;
        }
        let mut owner: HashMap<usize, usize> = HashMap::new();
        let mut copies: HashMap<(usize, usize), usize> = HashMap::new();
        for (m, hexes) in super::material::body_element_sets(model, mesh, b) {
            for e in hexes {
                for slot in 0..mesh.elements[e].len() {
                    let n = mesh.elements[e][slot];
                    let first = *owner.entry(n).or_insert(m);
                    if first == m {
                        continue;
                    }
                    let copy = *copies.entry((n, m)).or_insert_with(|| {
                        mesh.nodes.push(mesh.nodes[n]);
                        ties.push(Tie { body: b, copy: mesh.nodes.len() - 1, original: n });
                        mesh.nodes.len() - 1
                    });
                    mesh.elements[e][slot] = copy;
                }
            }
        }
    }
    ties
}

/// The `*EQUATION`s tying each copy to its original, direction by
/// direction, except where a constraint of the body prescribes the
/// direction at that position (both nodes are then in its node set).
pub(super) fn equations(d: &mut String, model: &Model, mesh: &HexMesh) {
    if mesh.ties.is_empty() {
        return;
    }
    let _ = writeln!(d, "*EQUATION");
    for t in &mesh.ties {
        let p = mesh.nodes[t.original];
        for k in 0..3 {
            let prescribed = model.constraints.iter().any(|c| {
                c.body == t.body && c.values[k].is_some() && c.selection.as_ref().is_some_and(|s| s.contains(p))
            });
            if !prescribed {
                let _ = writeln!(d, "2\n{}, {}, 1., {}, {}, -1.", t.copy + 1, k + 1, t.original + 1, k + 1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::HexKind;

    /// Two plies of different materials, one L4 × B2 element each (one
    /// C3D8I each at refine 1), held at y = 0.
    fn two_plies() -> Model {
        Model::parse(
            r#"
[[materials]]
name = "stiff"
orthotropic = { e1 = 140e9, e2 = 10e9, e3 = 10e9, g12 = 5e9, g13 = 5e9, g23 = 3.5e9, nu12 = 0.3, nu13 = 0.3, nu23 = 0.45 }
[[materials]]
name = "soft"
young_modulus = 1e8
poisson_ratio = 0.3
[[bodies]]
name = "b"
section = { shape = "laminate", element = "L4", x = { from = 0.0, to = 0.01, elements = 1 }, plies = [
  { thickness = 0.001, material = "soft" }, { thickness = 0.001, material = "stiff", angle = 45.0 } ] }
axis = { element = "B2", from = 0.0, to = 0.01, elements = 1 }
[[constraints]]
name = "root"
body = "b"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "b"
where = { y = 0.01 }
force_per_node = [0.0, 0.0, 1.0]
"#,
        )
        .unwrap()
    }

    #[test]
    fn interface_nodes_are_split_and_tied_where_free() {
        let model = two_plies();
        let mut mesh = HexMesh::new(&model, HexKind::C3D8I, 1);
        mesh.ties = split(&mut mesh, &model);
        // 12 grid nodes, the 4 of the interface once more
        assert_eq!((mesh.nodes.len(), mesh.ties.len()), (16, 4));
        let shared: Vec<usize> = mesh.elements[0].iter().filter(|n| mesh.elements[1].contains(n)).copied().collect();
        assert!(shared.is_empty(), "{:?}", mesh.elements);
        for t in &mesh.ties {
            assert_eq!(mesh.nodes[t.copy], mesh.nodes[t.original]);
        }
        let mut d = String::new();
        equations(&mut d, &model, &mesh);
        // two tied nodes are held at y = 0 in every direction: 2 × 3 equations
        assert_eq!(d.matches("\n2\n").count(), 6, "{d}");
        // the tip load goes on the 6 CUF nodes of the tip once, not on the copies
        let forces = crate::deck::load_forces(&model, &mesh, &model.loads[0]);
        assert_eq!(forces.len(), 6);
        let deck = crate::deck::write(&model, &mesh);
        assert!(deck.contains("*ELSET, ELSET=BM_B_1\n") && deck.contains("*ELSET, ELSET=BM_B_2\n"), "{deck}");
        assert!(deck.contains("*SOLID SECTION, ELSET=BM_B_2, MATERIAL=M_STIFF_45, ORIENTATION=OM_STIFF_45\n"));
    }
}
