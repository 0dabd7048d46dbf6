//! Nearly incompressible elasticity (ν = 0.4999): the B-bar formulation
//! (`formulation = "bbar"`) is free of volumetric locking, the
//! displacement-based element is not (issue 8).
//!
//! The beam is the Timoshenko check of `examples/cantilever_timoshenko.toml`
//! (1 m, 0.1 × 0.1 m, E = 70 GPa, 2 × 2 L9 × 5 B4, clamped at y = 0). The
//! closed forms are Timoshenko beam theory with the shear coefficient of a
//! rectangle κ = 10(1 + ν)/(12 + 11ν) (Cowper, J. Appl. Mech. 33, 1966):
//! tip load P: δ = PL³/3EI + PL/κGA; uniform load q per length:
//! δ = qL⁴/8EI + qL²/2κGA. The 3D clamp (all three components fixed, which
//! also stops the lateral contraction) stiffens the 3D answer by about 1 %
//! at this slenderness, inside the 2 % tolerance.

use cufem::analysis::{self, Silent};
use cufem::setup::Model;

mod common;

const E: f64 = 70e9;
const NU: f64 = 0.4999;
const L: f64 = 1.0;
const B: f64 = 0.1;

fn beam(formulation: &str, load: &str) -> String {
    format!(
        r#"
[[materials]]
name = "rubber_like"
young_modulus = 70e9
poisson_ratio = 0.4999

[[bodies]]
name = "beam"
material = "rubber_like"
{formulation}
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.1, elements = 2 }}, z = {{ from = 0.0, to = 0.1, elements = 2 }} }}
axis = {{ element = "B4", from = 0.0, to = 1.0, elements = 5 }}

[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "load"
body = "beam"
{load}
"#
    )
}

fn timoshenko_terms() -> (f64, f64) {
    let g = E / (2.0 * (1.0 + NU));
    let i = B * B * B * B / 12.0;
    let kappa = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU);
    (E * i, kappa * g * B * B)
}

/// Tip deflection (centre of the end section) and the solved model.
fn tip(formulation: &str, load: &str) -> (f64, Model, analysis::Solution) {
    let key = if formulation.is_empty() { String::new() } else { format!("formulation = \"{formulation}\"") };
    let model = Model::parse(&beam(&key, load)).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let uz = sol.fields(&model).sample_point(None, [0.05, L, 0.05]).unwrap().u[2];
    (uz, model, sol)
}

fn relative(value: f64, reference: f64) -> f64 {
    (value - reference).abs() / reference.abs()
}

/// B-bar within 2 % of Timoshenko and the displacement-based element more
/// than 2 % off (it locks), reported as `locking.<case>.bbar` and
/// `locking.<case>.standard`.
fn bbar_and_standard(case: &str, bbar: f64, standard: f64, exact: f64) {
    common::within(&format!("locking.{case}.bbar"), bbar, exact, 0.02, "Timoshenko with Cowper's κ");
    let check = "|difference| > 2 % against Timoshenko (the element locks)";
    common::figure(&format!("locking.{case}.standard"), 100.0 * (standard / exact - 1.0), "%", check);
    assert!(relative(standard, exact) > 0.02, "standard {standard} vs {exact}: no locking shown");
}

#[test]
fn tip_load_bbar_matches_timoshenko_and_the_standard_element_locks() {
    let p = 1000.0;
    let (ei, kga) = timoshenko_terms();
    let exact = -(p * L.powi(3) / (3.0 * ei) + p * L / kga);
    let load = "where = { y = 1.0 }\ntotal_force = [0.0, 0.0, -1000.0]";
    let (bbar, ..) = tip("bbar", load);
    let (standard, ..) = tip("standard", load);
    bbar_and_standard("tip", bbar, standard, exact);
}

/// The same with nonlinear geometry and the logarithmic strain (at this
/// load the deflection is 1e-5 of the length, so beam theory holds): B-bar
/// at finite strain (the projected ln J, `crate::elements`'s fbar) is free
/// of locking as the small-strain B-bar is, the displacement-based element
/// locks as in small strain.
#[test]
fn tip_load_at_finite_strain_bbar_matches_timoshenko_and_the_standard_element_locks() {
    let (ei, kga) = timoshenko_terms();
    let exact = -(1000.0 * L.powi(3) / (3.0 * ei) + 1000.0 * L / kga);
    let load = "where = { y = 1.0 }\ntotal_force = [0.0, 0.0, -1000.0]";
    let finite = |formulation: &str| {
        let text =
            format!("[analysis]\ngeometry = \"nonlinear\"\nstrain = \"logarithmic\"\n{}", beam(formulation, load));
        let model = Model::parse(&text).unwrap();
        let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
        assert!(sol.failure.is_none(), "{:?}", sol.failure);
        sol.fields(&model).sample_point(None, [0.05, L, 0.05]).unwrap().u[2]
    };
    let (bbar, standard) = (finite("formulation = \"bbar\""), finite("formulation = \"standard\""));
    let (small, ..) = tip("bbar", load);
    bbar_and_standard("finite_strain", bbar, standard, exact);
    assert!(relative(bbar, small) < 1e-3, "bbar at finite strain {bbar} vs small strain {small}");
}

#[test]
fn uniform_pressure_bbar_matches_timoshenko_and_the_standard_element_locks() {
    let pressure = 1e4;
    let q = pressure * B;
    let (ei, kga) = timoshenko_terms();
    let exact = -(q * L.powi(4) / (8.0 * ei) + q * L * L / (2.0 * kga));
    let load = "where = { z = 0.1 }\npressure = 1e4";
    let (bbar, ..) = tip("bbar", load);
    let (standard, ..) = tip("standard", load);
    bbar_and_standard("pressure", bbar, standard, exact);
}

/// Checkerboard measure: on the top surface away from the clamp and the tip
/// (y ∈ [0.2, 0.8] m, 61 stations), the largest difference between the
/// pressure `p = −tr σ / 3` and beam theory's `−σ_yy / 3 = −M(y) c / 3I`,
/// in % of the largest beam-theory pressure there. Pressure modes that
/// alternate between elements (or Gauss points) show up as a large value.
#[test]
fn bbar_pressure_has_no_checkerboard() {
    let measure = |formulation: &str| {
        let (_, model, sol) = tip(formulation, "where = { y = 1.0 }\ntotal_force = [0.0, 0.0, -1000.0]");
        let view = sol.fields(&model);
        let i = B.powi(4) / 12.0;
        let (mut worst, mut peak) = (0.0f64, 0.0f64);
        for k in 0..=60 {
            let y = 0.2 + 0.6 * k as f64 / 60.0;
            let s = view.sample_point(None, [0.05, y, B]).unwrap().stress;
            let p = -(s[0] + s[1] + s[2]) / 3.0;
            let beam = -(1000.0 * (L - y) * (B / 2.0) / i) / 3.0;
            worst = worst.max((p - beam).abs());
            peak = peak.max(beam.abs());
        }
        worst / peak
    };
    let (bbar, standard) = (measure("bbar"), measure("standard"));
    let check = "< 5 % of the peak, against beam theory's −M c/3I";
    common::figure("locking.checkerboard.bbar", 100.0 * bbar, "%", check);
    let check = "> 50 % of the peak (the pressure oscillates)";
    common::figure("locking.checkerboard.standard", 100.0 * standard, "%", check);
    assert!(bbar < 0.05, "bbar pressure error {bbar}");
    assert!(standard > 0.5, "standard pressure error {standard}: no oscillation shown");
}

/// Without a `formulation` key a body with ν ≥ 0.45 gets B-bar.
#[test]
fn bbar_is_the_default_for_nearly_incompressible_materials() {
    let load = "where = { y = 1.0 }\ntotal_force = [0.0, 0.0, -1000.0]";
    let (default, ..) = tip("", load);
    let (bbar, ..) = tip("bbar", load);
    // equal up to the round-off of the parallel assembly order (the standard
    // element is 7.8 % off)
    assert!((default - bbar).abs() < 1e-9 * bbar.abs(), "{default} vs {bbar}");
}
