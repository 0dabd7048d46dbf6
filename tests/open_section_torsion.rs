//! Open-section torsion with restrained warping (issue 11): an I-beam
//! cantilever built from the parametric `i_beam` section, clamped at the
//! root (warping restrained there, free at the tip), twisted by an end
//! torque, against Vlasov's closed form.

use cufem::analysis::{self, Silent};
use cufem::setup::Model;

/// I-section b = 100 mm, h = 200 mm, t_w = 3 mm, t_f = 4 mm, centred on
/// x = 0 and z = 0; 2 m long, 20 B4; the section mesh is stated in the test.
fn cantilever(along_flange: usize, along_web: usize) -> String {
    format!(
        r#"
[[materials]]
name = "steel"
young_modulus = 210e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "i_beam", element = "L9", origin = [-0.05, -0.1], width = 0.1, height = 0.2, web_thickness = 0.003, flange_thickness = 0.004, along_flange = {along_flange}, along_web = {along_web}, through = 1 }}
axis = {{ element = "B4", from = 0.0, to = 2.0, elements = 20 }}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = {{ y = 2.0 }}
total_force = [0.0, 0.0, -1.0]
"#
    )
}

/// Twist of the tip under the end torque `torque` (replacing the model's
/// tip load): the in-plane traction τ ∝ (−z, x) about the centroid (the
/// shear centre of the doubly symmetric I), lumped on the tip face's nodes
/// (`∫ N_a dA` times the traction at the node) and scaled so that its moment
/// is exactly `torque`. The twist is the relative lateral displacement of
/// the two flanges' mid-points over the distance between them.
fn tip_twist(text: &str, torque: f64, h0: f64) -> f64 {
    let mut model = Model::parse(text).unwrap();
    let body = &model.mesh.bodies[0];
    let mut forces = std::collections::BTreeMap::<usize, [f64; 3]>::new();
    for face in cufem::bc::boundary_faces(body) {
        if face.side != cufem::bc::FaceSide::End(true) {
            continue;
        }
        let fi = cufem::bc::integrate_face(body, &face);
        for (&n, &w) in fi.nodes.iter().zip(&fi.weights) {
            let x = model.mesh.coords(n);
            let f = forces.entry(n).or_default();
            f[0] -= w * x[2];
            f[2] += w * x[0];
        }
    }
    let moment: f64 =
        forces.iter().map(|(&n, f)| model.mesh.coords(n)[0] * f[2] - model.mesh.coords(n)[2] * f[0]).sum();
    model.loads[0].nodal_forces = forces.into_iter().map(|(n, f)| (n, f.map(|v| v * torque / moment))).collect();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let view = sol.fields(&model);
    let ux = |z: f64| view.sample_point(None, [0.0, 2.0, z]).unwrap().u[0];
    (ux(-h0 / 2.0) - ux(h0 / 2.0)) / h0
}

/// Vlasov (Timoshenko & Gere, *Theory of Elastic Stability*, §5.2; a
/// cantilever with warping restrained at the root and free at the tip):
/// θ(L) = T/(G J) · [L − tanh(k L)/k], k = √(G J/(E Γ)), with the
/// thin-walled warping constant of a doubly symmetric I, Γ = t_f b³ h₀²/24
/// (h₀ = h − t_f between the flanges' mid-planes), and J = 2 · b t_f³/3 ·
/// (1 − 0.63 t_f/b) + (h − 2 t_f) t_w³/3 (Roark, Table 10.7: the flanges as
/// thin rectangles with their end correction). Issue 11 asks for 5 %; the
/// mesh: 4 L9 along each flange outstand, 8 along the web, one through each
/// wall (26 L9), 20 B4 over 2 m. Measured 1.21 % above Vlasov (0.12849
/// against 0.12695 rad). With k L = 1.19 the tip twists 70 % less than
/// under Saint-Venant torsion alone, T L/(G J) = 0.4206 rad: asserted
/// below half of it.
#[test]
fn i_beam_cantilever_twist_matches_vlasov() {
    let (e, nu, b, h, tw, tf, l, torque): (f64, f64, f64, f64, f64, f64, f64, f64) =
        (210e9, 0.3, 0.1, 0.2, 0.003, 0.004, 2.0, 100.0);
    let g = e / (2.0 * (1.0 + nu));
    let h0 = h - tf;
    let j = 2.0 * b * tf.powi(3) / 3.0 * (1.0 - 0.63 * tf / b) + (h - 2.0 * tf) * tw.powi(3) / 3.0;
    let gamma = tf * b.powi(3) * h0 * h0 / 24.0;
    let k = (g * j / (e * gamma)).sqrt();
    let vlasov = torque / (g * j) * (l - (k * l).tanh() / k);
    let saint_venant = torque * l / (g * j);
    let theta = tip_twist(&cantilever(4, 8), torque, h0);
    let err = (theta - vlasov).abs() / vlasov;
    eprintln!(
        "I-beam tip twist {theta:.5e} rad; Vlasov {vlasov:.5e} rad (k L = {:.3}, error {:.2} %); Saint-Venant alone \
         {saint_venant:.5e} rad",
        k * l,
        100.0 * err
    );
    assert!(err < 0.05, "twist {theta:e} vs Vlasov {vlasov:e}: {:.1} %", 100.0 * err);
    assert!(theta < 0.5 * saint_venant, "the restrained warping should stiffen the beam");
}
