//! Load histories (issue 10): steps that load, hold, unload and reload;
//! elastic unloading and springback against beam theory; the unloading of
//! the indentation example.

use std::path::Path;

use cufem::analysis::{self, Silent, Solution};
use cufem::setup::Model;

mod common;

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).unwrap()
}

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    (model, sol)
}

/// The fields at a point of the solution as it was at the end of step `k`.
fn probe_at(model: &Model, sol: &Solution, k: usize, point: [f64; 3]) -> cufem::post::Sample {
    let s = sol.at_step(model, k).unwrap().unwrap();
    s.fields(model).sample_point(None, point).unwrap()
}

/// The elastic–perfectly-plastic cantilever of `examples/epp_cantilever.toml`
/// (b = h = 20 mm, L = 0.8 m, σ_y = 250 MPa: P_y = 416.67 N, δ_y = 26.67 mm)
/// under a tip *force* 1.4 P_y, then unloaded to zero. Eight L9 through the
/// height and projected stresses (the outer fibre lies outside the Gauss
/// points). The root face keeps its symmetry-plane supports; a line
/// u_x = 0 on the mid-plane holds the twist that the tip displacement of the
/// example held.
fn epp_force_history() -> String {
    let text = example("epp_cantilever.toml")
        .replace("z = { from = 0.0, to = 0.02, elements = 2 }", "z = { from = 0.0, to = 0.02, elements = 8 }")
        .replace(
            "[[constraints]]\nname = \"tip\"\nbody = \"beam\"\nwhere = { y = 0.8 }\ndisplacement = { z = -0.16 }",
            "[[constraints]]\nname = \"root_mid\"\nbody = \"beam\"\nwhere = { y = 0.0, x = 0.01 }\nfix = [\"x\"]\n\n\
             [[loads]]\nname = \"tip\"\nbody = \"beam\"\nwhere = { y = 0.8 }\ntotal_force = [0.0, 0.0, -583.3333333333334]\n\n\
             [[steps]]\nname = \"load\"\nincrements = 14\n\n[[steps]]\nname = \"unload\"\nfactor = 0.0\nincrements = 4\n\n\
             [output]\nrecovery = \"projection\"",
        );
    assert!(text.contains("[[steps]]") && text.contains("elements = 8 }"));
    text
}

/// Unloading is elastic: the residual tip deflection is δ(p) − p δ_y with
/// the model's own elastic compliance (2 %), and δ(p) − p δ_y of the
/// plastic-hinge theory within 4 %; the residual bending stress at the
/// root's outer fibre is the loaded stress minus the elastic p σ_y (3 %)
/// and the beam-theory closed form σ_y − p σ_y = −100 MPa within 8 %.
///
/// Why not the 2 % and 3 % against beam theory: the residual is a
/// small difference (0.147 δ_y of 1.547 δ_y loaded), and the 3D model
/// differs from uniaxial beam theory by a few per cent (collapse at
/// 1.53 P_y, see the example's header; the loaded outer fibre carries
/// σ_yy = 257 MPa at von Mises 250 MPa, with transverse stresses of 15 MPa
/// from isochoric plastic flow against the compressible elastic core).
/// Measured (8 L9 through the height): residual deflection 3.818 mm against
/// 3.922 mm (−2.6 %), outer-fibre residual −94.7 MPa (−5.3 %; −93.9 MPa
/// with 8 L16 × 16 B4, so converged).
#[test]
fn epp_cantilever_unloads_elastically_to_its_residual_state() {
    let (model, sol) = solve(&epp_force_history());
    assert_eq!(sol.steps.len(), 2);
    // p = P/P_y; δ_y = P_y L³/(3EI) = 26.67 mm (the example's header)
    let (p, dy) = (1.4f64, 0.02666666666666667);
    let tip = [0.01, 0.8, 0.01];
    let loaded = probe_at(&model, &sol, 0, tip).u[2];
    let residual = probe_at(&model, &sol, 1, tip).u[2];
    // the model's elastic compliance: the same beam loaded to p = 0.7
    // (elastic), scaled to the full load: p δ_y of the model
    let u_elastic = {
        let (m1, s1) = solve(&epp_force_history().replace("increments = 14", "increments = 14\nfactor = 0.5"));
        assert!(s1.states.iter().all(|s| s.peeq == 0.0), "p = 0.7 is elastic");
        probe_at(&m1, &s1, 0, tip).u[2] / 0.5
    };
    let delta_y_model = -u_elastic / p;
    let expect_model = -loaded - p * delta_y_model;
    assert!(
        (-residual - expect_model).abs() < 0.02 * expect_model,
        "residual deflection {:.5e} m vs δ(p) − p δ_y = {expect_model:.5e} m (model compliance)",
        -residual
    );
    let hinge = (5.0 - (3.0 + p) * (3.0 - 2.0 * p).sqrt()) / (p * p) * dy - p * dy;
    eprintln!(
        "residual tip deflection {:.4} mm; plastic-hinge theory {:.4} mm ({:+.1} %); δ_y model {:.4} mm, theory {:.4} mm",
        -residual * 1e3,
        hinge * 1e3,
        100.0 * (-residual / hinge - 1.0),
        delta_y_model * 1e3,
        dy * 1e3
    );
    assert!((-residual / hinge - 1.0).abs() < 0.04, "residual deflection {} vs hinge theory {hinge}", -residual);

    // residual stress at the root's outer fibre (top, in tension when loaded)
    let root_top = [0.01, 0.0, 0.02];
    let s_loaded = probe_at(&model, &sol, 0, root_top).stress[1];
    let s_res = probe_at(&model, &sol, 1, root_top).stress[1];
    let elastic_change = p * 250e6; // M c / I = p σ_y at the root
    eprintln!("root outer fibre: loaded {:.1} MPa, residual {:.1} MPa", s_loaded * 1e-6, s_res * 1e-6);
    assert!(
        (s_res - (s_loaded - elastic_change)).abs() < 0.03 * (s_loaded - elastic_change).abs(),
        "residual {s_res:e} vs loaded − p σ_y {:e}",
        s_loaded - elastic_change
    );
    let closed = 250e6 * (1.0 - p);
    assert!((s_res / closed - 1.0).abs() < 0.08, "residual {s_res:e} vs beam theory {closed:e}");
    // the unloading increments are elastic: no Gauss point returns plastically
    for row in sol.history.iter().filter(|r| r.lambda > 1.0) {
        assert_eq!(row.plastic_points, 0, "increment {} at λ = {}", row.increment, row.lambda);
    }
}

/// A step that holds every factor changes nothing: the state at its end is
/// the state at its start to round-off.
#[test]
fn a_hold_step_changes_nothing() {
    let text = epp_force_history().replace(
        "[[steps]]\nname = \"unload\"\nfactor = 0.0\nincrements = 4",
        "[[steps]]\nname = \"hold\"\nincrements = 3",
    );
    let (model, sol) = solve(&text);
    let a = sol.at_step(&model, 0).unwrap().unwrap();
    let b = sol.at_step(&model, 1).unwrap().unwrap();
    let umax = a.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let du = a.u.iter().zip(&b.u).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(du <= 1e-9 * umax, "hold moved the displacements by {du:e} (max {umax:e})");
    let dp = a.states.iter().zip(&b.states).fold(0.0f64, |m, (x, y)| m.max((x.peeq - y.peeq).abs()));
    assert!(dp <= 1e-12, "hold changed peeq by {dp:e}");
    assert!(a.states.iter().any(|s| s.peeq > 0.0), "the held state is plastic");
}

/// In a purely elastic model, load → unload → reload to the same target
/// gives the state of one load to that target (1e-10 relative).
#[test]
fn elastic_load_unload_reload_equals_one_load() {
    let base = example("cantilever_timoshenko.toml");
    let (_, once) = solve(&base);
    let cycled = format!(
        "{base}\n[[steps]]\nname = \"load\"\n\n[[steps]]\nname = \"unload\"\nfactor = 0.0\n\n[[steps]]\nname = \"reload\"\nincrements = 3\n"
    );
    let (_, again) = solve(&cycled);
    assert_eq!(again.steps.len(), 3);
    let umax = once.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let du = once.u.iter().zip(&again.u).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(du <= 1e-10 * umax, "difference {du:e} (max {umax:e})");
    // and in the middle the structure was back at rest
    let mid = again.steps[1].fields.as_ref().unwrap().u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(mid <= 1e-10 * umax, "unloaded state {mid:e}");
}

/// The indentation test of `examples/block_indentation_unload.toml` with its
/// unloading step replaced by one increment back to `factor`.
fn block_unloaded_to(factor: f64) -> (Model, Solution) {
    let text = example("block_indentation_unload.toml").replace(
        "name = \"unload\"\nfactor = 0.0\nincrements = 20",
        &format!("name = \"unload\"\nfactor = {factor}\nincrements = 1"),
    );
    assert!(text.contains(&format!("factor = {factor}\n")));
    solve(&text)
}

/// Unloading of the indentation test starts elastically: in the first
/// unloading increment (0.05 mm of the 1 mm depth) the plastic strain of
/// the block stays as it was, and the unloading slope equals the stiffness
/// of the loaded state probed by a 0.001 mm elastic perturbation (2 %; the
/// issue's check). Measured: slopes 5.3050e9 and 5.3050e9 N/m. "Elastic"
/// to 1e-4 of the peak peeq rather than exactly: 4 of the 676 plastic
/// Gauss points (at the punch edges, where the stress is singular) change
/// their peeq, by at most 4.4e-6 (peak 5.5e-2).
#[test]
fn indentation_unloading_starts_elastically_with_the_loaded_stiffness() {
    let force = |s: &Solution, k: usize| s.steps[k].contacts.iter().find(|c| c.name == "punch").unwrap().force[2];
    let (model, first) = block_unloaded_to(0.95);
    let (_, probe) = block_unloaded_to(0.999);
    let slope = (force(&first, 1) - force(&first, 0)) / (0.05e-3);
    let stiffness = (force(&probe, 1) - force(&probe, 0)) / (0.001e-3);
    eprintln!("unloading slope {slope:.5e} N/m, perturbation {stiffness:.5e} N/m");
    assert!((slope / stiffness - 1.0).abs() < 0.02, "slope {slope:e} vs {stiffness:e}");
    let a = first.at_step(&model, 0).unwrap().unwrap();
    let b = first.at_step(&model, 1).unwrap().unwrap();
    let peak = a.states.iter().map(|s| s.peeq).fold(0.0, f64::max);
    let changes: Vec<f64> =
        a.states.iter().zip(&b.states).map(|(x, y)| y.peeq - x.peeq).filter(|d| *d != 0.0).collect();
    let largest = changes.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    eprintln!(
        "first unloading increment: {} points change peeq, largest {largest:.3e} (peak peeq {peak:.3e})",
        changes.len()
    );
    assert!(largest <= 1e-4 * peak, "peeq changes by {largest:e} on unloading");
}

/// The block example made elastic, its punch either pushed `depth` down
/// (displacement control) or loaded by `force` (force control).
fn elastic_block(control: &str) -> String {
    let text = example("block_indentation.toml")
        .replace("plasticity = { yield_stress = 100e6, hardening = \"perfect\" }\n", "")
        .replace("displacement = [0.0, 0.0, -1.0e-3]", control);
    assert!(!text.contains("plasticity = ") && text.contains(control));
    text
}

/// Force control (issue 10): an elastic punch loaded to the force F that a
/// prescribed depth produced gives the same state as that prescribed depth
/// (1e-8), its solved displacement is that depth, and a load history that
/// loads and unloads by force ends where it started.
#[test]
fn force_control_reproduces_displacement_control() {
    let (model_d, by_depth) = solve(&elastic_block("displacement = [0.0, 0.0, -0.1e-3]"));
    let punch = |s: &Solution| s.contact("punch").unwrap().clone();
    let f = punch(&by_depth).force;
    assert!(f[2] < -1e5, "{f:?}");
    let (_, by_force) = solve(&elastic_block(&format!("force = [0.0, 0.0, {:e}]", f[2])));
    let umax = by_depth.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let du = by_depth.u.iter().zip(&by_force.u).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!(
        "force control: largest difference {du:e} m (max {umax:e} m); punch at {:?}",
        punch(&by_force).displacement
    );
    assert!(du <= 1e-8 * umax, "states differ by {du:e}");
    assert!((punch(&by_force).displacement[2] + 0.1e-3).abs() <= 1e-8 * 0.1e-3);
    assert!((punch(&by_force).force[2] / f[2] - 1.0).abs() < 1e-8);
    assert_eq!(model_d.indenters[0].force, None);
}

/// A target force above the limit load is refused with a clear reason, and
/// the last converged increment is kept: the block's punch (limit ≈ 1.41 MN,
/// the plateau of the displacement-controlled example) asked for 2 MN.
#[test]
fn force_above_the_limit_load_stops_with_a_collapse_message() {
    let text =
        example("block_indentation.toml").replace("displacement = [0.0, 0.0, -1.0e-3]", "force = [0.0, 0.0, -2.0e6]");
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let failure = sol.failure.as_ref().expect("2 MN cannot be carried");
    let message = failure.to_string();
    assert!(message.contains("\"punch\"") && message.contains("collapses before this force"), "{message}");
    let reached = -sol.contact("punch").unwrap().force[2];
    eprintln!("largest force reached {reached:.4e} N");
    assert!((1.3e6..1.45e6).contains(&reached), "{reached:e}");
}

/// A diverging correction of an unloading step is not a collapse: the
/// springback tube's quarter (tests/common `springback_quarter`, its roller
/// loaded to 1.6 kN by force, then unloaded), its unload's first increment
/// solved on the loading branch at points on their yield surface (as the
/// stepping did before it started unloading steps cautiously): the first
/// corrections would move the roller by centimetres, and Newton stops
/// saying the correction diverged, not that the tube collapses before a
/// force it has already carried. The run itself starts that increment with
/// the elastic branch and has no cutback.
#[test]
fn an_unloading_divergence_is_not_called_a_collapse() {
    use cufem::solver::stepping::Incremental;
    let model = Model::parse(&common::springback_quarter(&example("bending_tube_springback.toml"))).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    let path: Vec<(f64, bool)> = (1..=15).map(|k| (k as f64 / 15.0, true)).collect();
    common::solve_path(&mut s, &path);
    s.set_load_factor(1.2);
    let r = cufem::solver::newton::solve(&mut s, &Default::default(), &Default::default());
    let message = r.message.clone().unwrap_or_default();
    assert!(!r.converged() && message.contains("the correction diverged (not a collapse)"), "{r:?}");
    let run = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(run.failure.is_none() && run.cutbacks.is_empty(), "{:?}, {} cutbacks", run.failure, run.cutbacks.len());
}
