//! Verification of the elastoplastic solver (issue #3): plastic-hinge
//! theory, quadratic convergence of Newton, and cutbacks.

use std::path::Path;

use cufem::analysis::{self, Silent};
use cufem::setup::Model;

mod common;

const EXAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/epp_cantilever.toml");

/// Beam theory of the example (see its header): P_y and δ_y.
fn first_yield() -> (f64, f64) {
    let (b, h, l, e, sy) = (0.02f64, 0.02f64, 0.8f64, 200e9, 250e6);
    let py = sy * b * h * h / (6.0 * l);
    let i = b * h.powi(3) / 12.0;
    (py, py * l.powi(3) / (3.0 * e * i))
}

/// δ/δ_y of an elastic–perfectly-plastic rectangular cantilever at p = P/P_y.
fn hinge_theory(p: f64) -> f64 {
    if p <= 1.0 { p } else { (5.0 - (3.0 + p) * (3.0 - 2.0 * p).sqrt()) / (p * p) }
}

/// The example's load–deflection history against the plastic-hinge theory
/// (at least five points between first yield and p = 1.4, each within the
/// 1 % of docs/verification.md) and its collapse load against P_c = M_p/L = 1.5 P_y. The
/// example takes 30 increments of 0.2 δ_y; here 60, so that five converged
/// points fall in the plastic range before p = 1.4.
#[test]
fn epp_cantilever_follows_the_plastic_hinge_theory() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap().replace("increments = 30", "increments = 60");
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none());
    let (py, dy) = first_yield();
    let tip = model.constraints.iter().find(|c| c.name == "tip").unwrap().values[2].unwrap();
    let mut plastic_points = 0;
    let mut p_max: f64 = 0.0;
    let mut worst: f64 = 0.0;
    for row in &sol.history {
        let delta = -row.lambda * tip;
        let p = -row.reaction("tip").unwrap().force[2] / py;
        p_max = p_max.max(p);
        if p <= 1.4 {
            let err = (delta / dy - hinge_theory(p)) / hinge_theory(p);
            worst = worst.max(err.abs());
            // docs/verification.md: "within 1 % for p ≤ 1.4"; observed ≤ 0.6 %
            assert!(err.abs() < 0.01, "δ/δ_y = {} at p = {p}: theory {} (error {err})", delta / dy, hinge_theory(p));
            plastic_points += usize::from(p > 1.0);
        }
    }
    let check = "< 1 % at every point with p ≤ 1.4 against the plastic-hinge theory";
    common::figure("plasticity.epp.hinge_error", 100.0 * worst, "%", check);
    common::figure("plasticity.epp.plastic_points", plastic_points as f64, "", "≥ 5 between p = 1 and 1.4");
    assert!(plastic_points >= 5, "only {plastic_points} points between first yield and p = 1.4");
    // collapse plateau (δ = 6 δ_y) against the plastic-hinge load 1.5 P_y:
    // above it by a 3D effect of the moment gradient that stays under
    // refinement (see the example's header); 3 % leaves half of that margin
    // for the mesh
    common::figure("plasticity.epp.collapse_load", p_max, "P_y", "reported (plastic hinge: 1.5 P_y)");
    common::within("plasticity.epp.collapse", p_max, 1.5, 0.03, "the plastic-hinge load M_p/L = 1.5 P_y");
}

/// Quadratic convergence: once the relative residual is below 1e-2, each
/// Newton step squares it (r_{k+1} ≤ C r_k² with a modest C), in every
/// plastic increment; a linearly converging iteration would break this.
/// Residuals at the round-off floor (< 1e-9) are not informative and skipped.
#[test]
fn newton_converges_quadratically_in_the_plastic_range() {
    let model = Model::from_file(Path::new(EXAMPLE)).unwrap();
    // observed ≤ 2.6 (docs/verification.md); a linearly converging step at rate ρ gives
    // ρ/r_k ≥ 100 for r_k ≤ 1e-2 and ρ ≥ 1, so 4 separates the two clearly
    // at least 10 pairs: 12 measured since each increment starts on the
    // secant of the last (issue 14: 3 iterations per increment instead of
    // more before, so fewer pairs reach the asymptotic range)
    assert_quadratic("standard", &model, 1e-2, 4.0, 10);
}

/// The same with the B-bar formulation (issue 8): its consistent tangent
/// keeps Newton quadratic, with a larger constant while the plastic zone
/// grows (r_(k+1)/r_k² up to 13 at r_k ≈ 5e-3, e.g. 2.6e-2, 5.4e-3, 3.8e-4,
/// 1.1e-6, 2.8e-11 in one increment). Checked deeper in the asymptotic
/// range: for r_k ≤ 2e-3 the observed constant is ≤ 7.6, while a linear
/// rate ρ ≥ 0.05 would give ρ/r_k ≥ 25.
#[test]
fn newton_converges_quadratically_with_bbar() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let text = text.replacen("material = \"steel\"\n", "material = \"steel\"\nformulation = \"bbar\"\n", 1);
    assert!(text.contains("formulation = \"bbar\""));
    // at least 6 pairs (8 measured with the extrapolated increment start)
    assert_quadratic("bbar", &Model::parse(&text).unwrap(), 2e-3, 10.0, 6);
}

/// The same with combined hardening (issue 10): Voce isotropic plus two
/// Armstrong–Frederick back-stresses. The solver uses the symmetric part of
/// the kinematic tangent, exact where a point loads proportionally; near the
/// clamp, where bending and shear stresses turn the flow direction, it is
/// not, and the constant grows: measured r_(k+1)/r_k² ≤ 26.6 for r_k ≤ 1e-2
/// and ≤ 20.9 for r_k ≤ 2e-3 (e.g. 3.6e-3, 3.5e-4, 2.3e-8 in one increment),
/// against 2.6 for the isotropic law. Asserted as for B-bar: for r_k ≤ 2e-3
/// the constant stays < 25, while a linear rate ρ ≥ 0.05 would give
/// ρ/r_k ≥ 25.
#[test]
fn newton_converges_quadratically_with_kinematic_hardening() {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    let old = "plasticity = { yield_stress = 250e6, hardening = \"perfect\" }";
    assert!(text.contains(old));
    let text = text.replace(
        old,
        "plasticity = { yield_stress = 250e6, hardening = \"voce\", saturation_stress = 50e6, saturation_rate = 20.0, \
         kinematic = [{ modulus = 60e9, recall = 600.0 }, { modulus = 5e9, recall = 20.0 }] }",
    );
    assert_quadratic("kinematic", &Model::parse(&text).unwrap(), 2e-3, 25.0, 10);
}

/// Over every plastic increment, `r_(k+1)/r_k² < limit` for all residual
/// pairs with `r_k ≤ below` (and `r_(k+1)` above the round-off floor), with
/// at least `min_pairs` such pairs.
///
/// The tangent is what is tested, so every correction is a direct solve
/// with it (`reuse_factorization = false`: PCG with an older factor solves
/// only to the forcing term, see `solver::reuse`).
fn assert_quadratic(name: &str, model: &Model, below: f64, limit: f64, min_pairs: usize) {
    let mut model = model.clone();
    model.solver.reuse.enabled = false;
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none());
    let mut pairs = 0;
    let mut worst: f64 = 0.0;
    for (inc, row) in sol.increments.iter().zip(&sol.history) {
        if row.plastic_points == 0 {
            continue;
        }
        // residuals[0] is evaluated before the increment's prescribed
        // displacement is applied (by the first correction), so it is the
        // previous equilibrium, not part of this increment's iteration.
        for w in inc.newton.residuals[1..].windows(2) {
            if w[0] <= below && w[1] >= 1e-9 {
                worst = worst.max(w[1] / (w[0] * w[0]));
                pairs += 1;
            }
        }
    }
    let check = format!("< {limit} over every pair with r_k ≤ {below}, at least {min_pairs} pairs");
    common::figure(&format!("plasticity.newton.{name}.constant"), worst, "", &check);
    common::figure(&format!("plasticity.newton.{name}.pairs"), pairs as f64, "", &format!("≥ {min_pairs}"));
    assert!(pairs >= min_pairs, "{name}: only {pairs} pairs in the asymptotic range");
    assert!(worst < limit, "{name}: r_(k+1)/r_k² reached {worst}");
}

/// A deliberately large first increment (the whole load in one step, with
/// few Newton iterations allowed) is cut back, and the run still finishes
/// at the same collapse load.
#[test]
fn an_increment_that_cannot_converge_is_cut_back_and_the_run_finishes() {
    let text =
        std::fs::read_to_string(EXAMPLE).unwrap().replace("increments = 30", "increments = 1\nmax_iterations = 6");
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(!sol.cutbacks.is_empty(), "the first increment should have failed");
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    assert!((sol.lambda - 1.0).abs() < 1e-12);
    let (py, _) = first_yield();
    let p = sol.reaction("tip").unwrap().force[2].abs() / py;
    // same plateau as the 30-increment run (path independence under monotonic loading)
    let reference = Model::from_file(Path::new(EXAMPLE)).unwrap();
    let ref_sol = analysis::run(&reference, &Default::default(), &mut Silent).unwrap();
    let p_ref = ref_sol.reaction("tip").unwrap().force[2].abs() / py;
    assert!((p - p_ref).abs() < 0.01 * p_ref, "{p} vs {p_ref}");
}
