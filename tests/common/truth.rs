//! The true error of an estimate, for the estimator's tests
//! (tests/estimator.rs, tests/step_error.rs): a coarse run against a fine
//! reference of the same bodies, in the energy norm (each Gauss point with
//! its own material's compliance: zones and plies included).

use cufem::analysis::Solution;
use cufem::setup::Model;
use cufem::values::locate_in_model;

/// `σᵀ C⁻¹ σ` of an isotropic material (engineering shear), written here
/// apart from the library's compliance so that the true error of an
/// isotropic body does not share a fault of it.
pub fn complementary(s: &[f64; 6], e: f64, nu: f64) -> f64 {
    let normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    (normal + 2.0 * (1.0 + nu) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])) / e
}

/// A Gauss point of a model: its body, global element (the estimate's
/// `element` index), section element, position `[x, y, z]` and weight.
pub struct GaussPoint {
    pub body: usize,
    pub element: usize,
    pub section_element: usize,
    pub position: [f64; 3],
    pub weight: f64,
}

/// Every Gauss point of `model`, in the order of `Solution::stresses`
/// (body by body, element-major, axis point by axis point).
pub fn gauss_points(model: &Model) -> Vec<GaussPoint> {
    let mut out = Vec::new();
    let mut offset = 0;
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let cell = &model.cells[b];
        let (ns, nb) = (cell.section.n_gp, cell.axis.n_gp);
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            for gb in 0..nb {
                for gs in 0..ns {
                    let [x, z] = cell.section.position[es * ns + gs];
                    let y = cell.axis.position[eb * nb + gb];
                    let weight = cell.section.weight[es * ns + gs] * cell.axis.weight[eb * nb + gb];
                    out.push(GaussPoint {
                        body: b,
                        element: offset + e,
                        section_element: es,
                        position: [x, y, z],
                        weight,
                    });
                }
            }
        }
        offset += body.n_elements();
    }
    out
}

/// A plane of mirror symmetry `x_axis = at` of a model of which a fine
/// run holds only the part on one side (`above`: `x_axis ≥ at`).
#[derive(Clone, Copy)]
pub struct Plane {
    pub axis: usize,
    pub at: f64,
    pub above: bool,
}

/// The image of `position` in the part kept by every plane of `planes`
/// (reflected across each plane it lies beyond) and the sign of each
/// stress component (Voigt xx yy zz xy xz yz) there: a reflection across
/// `x_a = at` turns over the two shears with one index `a`.
pub fn image(position: [f64; 3], planes: &[Plane]) -> ([f64; 3], [f64; 6]) {
    let (mut at, mut sign) = (position, [1.0; 6]);
    for p in planes {
        if (at[p.axis] < p.at) == p.above {
            at[p.axis] = 2.0 * p.at - at[p.axis];
            // the shears with index `axis`: xy (3), xz (4), yz (5)
            for (k, pair) in [(3, [0, 1]), (4, [0, 2]), (5, [1, 2])] {
                if pair.contains(&p.axis) {
                    sign[k] = -sign[k];
                }
            }
        }
    }
    (at, sign)
}

/// The stress of `fine` at each of `points` (in the same body of `fine`).
/// With `planes`, `fine` is the part of a symmetric model on the kept side
/// of each plane: a point beyond takes the stress at its [`image`], its
/// shears turned over.
pub fn stresses_at((fm, fs): (&Model, &Solution), points: &[GaussPoint], planes: &[Plane]) -> Vec<[f64; 6]> {
    let view = fs.fields(fm);
    points
        .iter()
        .map(|p| {
            let (at, sign) = image(p.position, planes);
            let located = locate_in_model(&fm.mesh, Some(p.body), at);
            let s = view.sample_at(&located).unwrap_or_else(|| panic!("{at:?} not inside the fine mesh")).stress;
            std::array::from_fn(|i| sign[i] * s[i])
        })
        .collect()
}

/// The error of `coarse` per element (global index) in the energy norm
/// squared, `∫ (σ_ref − σ_h)ᵀ C⁻¹ (σ_ref − σ_h)` with `reference` the
/// stress at each of its Gauss points ([`gauss_points`]' order) (J);
/// each point's material (its section element's): isotropic ones by
/// [`complementary`], orthotropic plies by the library's compliance.
pub fn error_against((cm, cs): (&Model, &Solution), reference: &[[f64; 6]]) -> Vec<f64> {
    let points = gauss_points(cm);
    assert_eq!(points.len(), reference.len(), "a reference stress at every Gauss point");
    let mut out = vec![0.0; cm.mesh.bodies.iter().map(|b| b.n_elements()).sum()];
    for (k, (p, r)) in points.iter().zip(reference).enumerate() {
        let mat = &cm.materials[cm.mesh.bodies[p.body].material_of(p.section_element)];
        let raw = cs.stresses[k];
        let d: [f64; 6] = std::array::from_fn(|i| r[i] - raw[i]);
        // an orthotropic ply's compliance is the library's (its constants
        // inverted and turned to the ply's angle: tests of src/materials)
        let w =
            if mat.anisotropic.is_none() { complementary(&d, mat.young, mat.poisson) } else { mat.complementary(&d) };
        out[p.element] += p.weight * w;
    }
    out
}

/// The true error of `coarse` per element in the energy norm squared,
/// [`error_against`] the stress of `fine` (the same bodies) at each Gauss
/// point of `coarse` (J).
pub fn true_error(coarse: (&Model, &Solution), fine: (&Model, &Solution)) -> Vec<f64> {
    error_against(coarse, &stresses_at(fine, &gauss_points(coarse.0), &[]))
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
    touches_any(model, es, &[[0.2, 0.3], [0.3, 0.3]])
}

/// Whether section element `es` of the first body has a node at one of
/// the section points `points` (`[x, z]`).
pub fn touches_any(model: &Model, es: usize, points: &[[f64; 2]]) -> bool {
    let section = &model.mesh.bodies[0].section;
    section.element(es).iter().any(|&t| {
        let [x, z] = section.nodes[t];
        points.iter().any(|p| (x - p[0]).abs() < 1e-9 && (z - p[1]).abs() < 1e-9)
    })
}
