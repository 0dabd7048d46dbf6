//! The element loop's tests (`super`).

use super::*;
use crate::assembly::numbering::tests::two_body_mesh;
use crate::materials::Hardening;

struct Setup {
    mesh: Mesh,
    geometry: Vec<CellValues>,
    gp_offsets: Vec<usize>,
    materials: Vec<Material>,
    u: Vec<f64>,
    committed: Vec<PointState>,
    assembler: Assembler,
    /// The same assembler before its elastic cache was built.
    uncached: Assembler,
}

/// The two-body mesh, elastoplastic, with `u_y = 0.2 y²` (so ε_yy =
/// 0.4 y): elements near y = 0 stay elastic, the others yield.
fn setup() -> Setup {
    let mesh = two_body_mesh();
    let geometry: Vec<CellValues> = mesh.bodies.iter().map(|b| CellValues::new(b).unwrap()).collect();
    let mut gp_offsets = Vec::new();
    let mut n_gp = 0;
    for (b, g) in mesh.bodies.iter().zip(&geometry) {
        gp_offsets.push(n_gp);
        n_gp += b.n_elements() * g.gp_per_element();
    }
    let materials = vec![Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 1e9 }))];
    let mut u = vec![0.0; mesh.n_dofs()];
    for node in 0..mesh.n_nodes() {
        let [x, y, z] = mesh.coords(node);
        u[3 * node] = 1e-4 * z;
        u[3 * node + 1] = 0.2 * y * y;
        u[3 * node + 2] = -3e-4 * x * y;
    }
    let constrained: Vec<bool> = (0..mesh.n_dofs()).map(|d| d < 9).collect();
    let mut assembler = Assembler::new(&mesh, Numbering::new(&mesh, &constrained, &[]).unwrap());
    let uncached = assembler.clone();
    let committed = vec![PointState::default(); n_gp];
    let zero = vec![0.0; mesh.n_dofs()];
    let state = FeState {
        mesh: &mesh,
        geometry: &geometry,
        materials: &materials,
        u: &zero,
        states: &committed,
        gp_offsets: &gp_offsets,
        kinematics: Default::default(),
        damage: Default::default(),
    };
    let inputs = Inputs { state, predictor: Default::default(), initial: None, before: None };
    assembler.cache_elastic(&inputs);
    Setup { mesh, geometry, gp_offsets, materials, u, committed, assembler, uncached }
}

/// Internal forces, tangent values and plastic points, on `threads` threads.
fn assemble(s: &Setup, a: &Assembler, threads: usize) -> (Vec<f64>, Vec<f64>, usize) {
    let n_gp = s.committed.len();
    let state = FeState {
        mesh: &s.mesh,
        geometry: &s.geometry,
        materials: &s.materials,
        u: &s.u,
        states: &s.committed,
        gp_offsets: &s.gp_offsets,
        kinematics: Default::default(),
        damage: Default::default(),
    };
    let inputs = Inputs { state, predictor: Default::default(), initial: None, before: None };
    let mut force = vec![0.0; s.mesh.n_dofs()];
    let mut tangent = vec![0.0; a.pattern.nnz()];
    let (mut trial, mut stress) = (vec![PointState::default(); n_gp], vec![[0.0; 6]; n_gp]);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let plastic = pool.install(|| {
        a.assemble(
            &inputs,
            Outputs {
                force: &mut force,
                tangent: Some(&mut tangent),
                trial: &mut trial,
                stress: &mut stress,
                damage: &mut [],
                rest: None,
            },
        )
        .plastic_points
    });
    (force, tangent, plastic)
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// The coloured parallel loop gives the serial result to round-off
/// (only the order of additions into an entry may differ).
#[test]
fn parallel_assembly_equals_serial() {
    let s = setup();
    let (f1, k1, p1) = assemble(&s, &s.assembler, 1);
    let (f4, k4, p4) = assemble(&s, &s.assembler, 4);
    assert!(p1 > 0 && p1 == p4);
    assert!(largest_difference(&f1, &f4) < 1e-13);
    assert!(largest_difference(&k1, &k4) < 1e-13);
}

/// The elastic element matrices cached at setup give the same global
/// tangent as recomputing every element, in a state where some
/// elements are plastic and others elastic.
#[test]
fn cached_elastic_matrices_give_the_same_tangent() {
    let s = setup();
    let (f_cached, k_cached, plastic) = assemble(&s, &s.assembler, 2);
    let total: usize = s.committed.len();
    assert!(plastic > 0 && plastic < total, "{plastic} of {total} points plastic: want a mixed state");
    assert!(s.uncached.elastic_global.is_empty() && !s.assembler.elastic_global.is_empty());
    let (f_full, k_full, _) = assemble(&s, &s.uncached, 2);
    assert!(largest_difference(&k_full, &k_cached) < 1e-12);
    assert_eq!(f_full, f_cached);
}
