//! Verification of the elastoplastic solver (issue #3): plastic-hinge
//! theory, quadratic convergence of Newton, and cutbacks.

use std::path::Path;
use std::process::Command;

use cufem::analysis::{self, Silent};
use cufem::model::Model;

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

/// The example through the CLI: its load–deflection history against the
/// plastic-hinge theory and its collapse load against P_c = M_p/L = 1.5 P_y.
#[test]
fn epp_cantilever_follows_the_plastic_hinge_theory() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("epp_cantilever");
    let run = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", EXAMPLE, "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let (py, dy) = first_yield();
    let csv = std::fs::read_to_string(out.join("history_tip.csv")).unwrap();
    let mut header = csv.lines().next().unwrap().split(',');
    let col = |name: &str, h: &mut std::str::Split<'_, char>| h.position(|c| c == name).unwrap();
    let (iu, ir) = (col("u_z", &mut header.clone()), col("r_z", &mut header));
    let mut checked = 0;
    let mut p_max: f64 = 0.0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let delta = -f[iu].parse::<f64>().unwrap();
        let p = -f[ir].parse::<f64>().unwrap() / py;
        p_max = p_max.max(p);
        if p <= 1.4 {
            let err = (delta / dy - hinge_theory(p)) / hinge_theory(p);
            // issue #3 asks for 3 %; observed ≤ 0.6 % on this mesh
            assert!(err.abs() < 0.03, "δ/δ_y = {} at p = {p}: theory {} (error {err})", delta / dy, hinge_theory(p));
            checked += usize::from(p > 1.0);
        }
    }
    assert!(checked >= 2, "too few points between first yield and p = 1.4");
    // collapse plateau (δ = 6 δ_y) against the plastic-hinge load 1.5 P_y
    eprintln!("collapse load {:.4} P_y (plastic hinge: 1.5 P_y)", p_max);
    assert!((p_max / 1.5 - 1.0).abs() < 0.03, "collapse at p = {p_max}");
}

/// Quadratic convergence: once the relative residual is below 1e-2, each
/// Newton step squares it (r_{k+1} ≤ C r_k² with a modest C), in every
/// plastic increment; a linearly converging iteration would break this.
/// Residuals at the round-off floor (< 1e-9) are not informative and skipped.
#[test]
fn newton_converges_quadratically_in_the_plastic_range() {
    let model = Model::from_file(Path::new(EXAMPLE)).unwrap();
    let sol = analysis::run(&model, &mut Silent).unwrap();
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
            if w[0] <= 1e-2 && w[1] >= 1e-9 {
                worst = worst.max(w[1] / (w[0] * w[0]));
                pairs += 1;
            }
        }
    }
    eprintln!("{pairs} residual pairs, largest r_(k+1)/r_k² = {worst:.3}");
    assert!(pairs >= 20, "only {pairs} pairs in the asymptotic range");
    // observed ≤ 2.6; a linearly converging step at rate ρ gives ρ/r_k ≥ 100
    // for r_k ≤ 1e-2 and ρ ≥ 1
    assert!(worst < 10.0, "r_(k+1)/r_k² reached {worst}");
}

/// A deliberately large first increment (the whole load in one step, with
/// few Newton iterations allowed) is cut back, and the run still finishes
/// at the same collapse load.
#[test]
fn an_increment_that_cannot_converge_is_cut_back_and_the_run_finishes() {
    let text =
        std::fs::read_to_string(EXAMPLE).unwrap().replace("increments = 30", "increments = 1\nmax_iterations = 6");
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &mut Silent).unwrap();
    assert!(!sol.cutbacks.is_empty(), "the first increment should have failed");
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    assert!((sol.lambda - 1.0).abs() < 1e-12);
    let (py, _) = first_yield();
    let p = sol.reactions[2][2].abs() / py;
    // same plateau as the 30-increment run (path independence under monotonic loading)
    let reference = Model::from_file(Path::new(EXAMPLE)).unwrap();
    let ref_sol = analysis::run(&reference, &mut Silent).unwrap();
    let p_ref = ref_sol.reactions[2][2].abs() / py;
    assert!((p - p_ref).abs() < 0.01 * p_ref, "{p} vs {p_ref}");
}

/// The elastic element matrices cached at setup give the same global
/// tangent as recomputing every element, in a state where some elements
/// are plastic and others elastic.
#[test]
fn cached_elastic_matrices_give_the_same_tangent() {
    use cufem::assembly::{Assembler, Inputs, Outputs};
    use cufem::materials::PointState;
    use cufem::solver::stepping::Incremental;

    let model = Model::from_file(Path::new(EXAMPLE)).unwrap();
    let mut s = analysis::Structure::new(&model).unwrap();
    // advance to a partly plastic state
    s.set_load_factor(0.5);
    for _ in 0..6 {
        cufem::solver::newton::NonlinearProblem::evaluate(&mut s).unwrap();
        cufem::solver::newton::NonlinearProblem::correct(&mut s).unwrap();
    }
    let n_gp = s.committed.len();
    let inputs = Inputs {
        mesh: &model.mesh,
        geometry: &s.geometry,
        materials: &model.materials,
        u: &s.u,
        committed: &s.committed,
        gp_offsets: &s.gp_offsets,
    };
    let assemble = |a: &Assembler| {
        let mut force = vec![0.0; model.mesh.n_dofs()];
        let mut tangent = vec![0.0; a.pattern.nnz()];
        let (mut trial, mut stress) = (vec![PointState::default(); n_gp], vec![[0.0; 6]; n_gp]);
        let plastic = a.assemble(
            &inputs,
            Outputs { force: &mut force, tangent: Some(&mut tangent), trial: &mut trial, stress: &mut stress },
        );
        (tangent, plastic)
    };
    let (cached, plastic) = assemble(&s.assembler);
    assert!(plastic > 0, "the state should be partly plastic");
    let mut uncached = s.assembler.clone();
    uncached.clear_elastic_cache();
    let (full, _) = assemble(&uncached);
    let scale = full.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let diff = cached.iter().zip(&full).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(diff <= 1e-12 * scale, "largest difference {diff:e} (scale {scale:e})");
}
