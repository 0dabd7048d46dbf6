//! The true error of an estimate, for the estimator's tests
//! (tests/estimator.rs, tests/step_error.rs): a coarse run against a fine
//! reference of the same isotropic body, in the energy norm.

use cufem::analysis::Solution;
use cufem::setup::Model;
use cufem::values::locate_in_model;

/// `σᵀ C⁻¹ σ` (isotropic, engineering shear).
pub fn complementary(s: &[f64; 6], e: f64, nu: f64) -> f64 {
    let normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    (normal + 2.0 * (1.0 + nu) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])) / e
}

/// The true error of `coarse` per element in the energy norm squared,
/// `∫ (σ_ref − σ_h)ᵀ C⁻¹ (σ_ref − σ_h)` with `σ_ref` the stress of `fine`
/// at each Gauss point of `coarse` (J); one isotropic body.
pub fn true_error((cm, cs): (&Model, &Solution), (fm, fs): (&Model, &Solution)) -> Vec<f64> {
    assert_eq!(cm.mesh.bodies.len(), 1);
    let view = fs.fields(fm);
    let body = &cm.mesh.bodies[0];
    let (cell, mat) = (&cm.cells[0], &cm.materials[body.material]);
    assert!(mat.anisotropic.is_none());
    let ngp = cell.gp_per_element();
    let mut out = vec![0.0; body.n_elements()];
    for (e, o) in out.iter_mut().enumerate() {
        let (es, eb) = body.split_element(e);
        for gb in 0..cell.axis.n_gp {
            for gs in 0..cell.section.n_gp {
                let [x, z] = cell.section.position[es * cell.section.n_gp + gs];
                let y = cell.axis.position[eb * cell.axis.n_gp + gb];
                let w = cell.section.weight[es * cell.section.n_gp + gs] * cell.axis.weight[eb * cell.axis.n_gp + gb];
                let at = locate_in_model(&fm.mesh, Some(0), [x, y, z]);
                let reference = view.sample_at(&at).expect("inside the fine mesh").stress;
                let raw = cs.stresses[e * ngp + gb * cell.section.n_gp + gs];
                *o += w * complementary(&std::array::from_fn(|k| reference[k] - raw[k]), mat.young, mat.poisson);
            }
        }
    }
    out
}

/// The paper's block (`text`: examples/block_indentation.toml or its
/// indentation test) with every section division `k` times finer and `m`
/// B4 along its axis, its stresses recovered element by element (the true
/// error samples the reference at the coarse Gauss points).
pub fn block_refined(text: &str, k: usize, m: usize) -> String {
    assert!(text.matches("elements = 6").count() == 4 && text.contains("to = 0.1, elements = 1 }"));
    text.replace("elements = 6", &format!("elements = {}", 6 * k))
        .replace("to = 0.1, elements = 1 }", &format!("to = 0.1, elements = {m} }}"))
        .replace("recovery = \"projection\"", "recovery = \"element\"")
}

/// Whether section element `es` of the block touches a punch edge line
/// (x = 0.2 or 0.3 m on the top face z = 0.3 m), where the stress is
/// singular.
pub fn touches_punch_edge(model: &Model, es: usize) -> bool {
    let section = &model.mesh.bodies[0].section;
    section.element(es).iter().any(|&t| {
        let [x, z] = section.nodes[t];
        ((x - 0.2).abs() < 1e-9 || (x - 0.3).abs() < 1e-9) && (z - 0.3).abs() < 1e-9
    })
}
