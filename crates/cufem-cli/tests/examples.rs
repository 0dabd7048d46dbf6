//! Every shipped paper example runs through the CLI (issue #4): it must
//! converge, reproduce the paper's DOF count, satisfy global equilibrium,
//! and give probe values comparable with the paper's Tables 2, 5, 6 and 8.
//!
//! Exact agreement with the paper is not expected: its Figs. 3, 7, 13 and 18
//! (mesh grading, bending span and rollers, ring mesh, the cantilever
//! layout) are missing from our copy, so every example assumes them (see
//! each file's header), and the probes sit at stress concentrations (a punch
//! edge, a roller line) where values depend on mesh and recovery. Each
//! tolerance below states its reason.

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;
use std::sync::{Arc, OnceLock};

use serde_json::Value;

#[path = "../../../tests/common/mod.rs"]
mod common;

/// Runs `examples/<name>.toml` and returns its summary.
fn run(name: &str) -> Value {
    // each example runs once per test binary: a regression test that reads
    // an example's files shares the run of the example's own test
    static RUNS: std::sync::LazyLock<std::sync::Mutex<HashMap<String, Arc<OnceLock<Value>>>>> =
        std::sync::LazyLock::new(Default::default);
    let once = RUNS.lock().unwrap().entry(name.to_string()).or_default().clone();
    once.get_or_init(|| run_example(name)).clone()
}

/// Runs `examples/<name>.toml` through the CLI into the test folder and
/// checks what every example must satisfy.
fn run_example(name: &str) -> Value {
    let model = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(format!("{name}.toml"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("example_{name}"));
    let run = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], true, "{name}");
    // the memory estimate made before the analysis against the measured peak
    // resident memory, frictional models included (their GMRES basis is in
    // the estimate). Measured (every shipped example, three runs: two on 2
    // threads, one on 1; docs/performance.md): estimate / peak from 0.978
    // to 1.25, one example varying by 5 % between runs (glibc's per-thread
    // arenas). The band is the issue's −10 % … +30 %: the lower bound is the
    // guard (an estimate below the peak lets a model through that does not
    // fit); the old upper bound of 1.25 failed at 1.253 on a busy machine.
    let estimated = summary["memory"]["estimated_bytes"].as_f64().unwrap();
    let peak = summary["memory"]["peak_bytes"].as_f64().unwrap();
    assert!((0.9..1.3).contains(&(estimated / peak)), "{name}: estimate {estimated:e} B, peak {peak:e} B");
    // no shipped example needs double-precision factors (docs/performance.md:
    // a fallback would keep the answer but lose the speed)
    assert_eq!(summary["timings"]["precision_fallbacks"], 0, "{name}: {}", summary["timings"]);
    summary
}

/// Runs a model given as text (a variant of an example); its summary and
/// output folder.
fn run_text(name: &str, text: &str) -> (Value, std::path::PathBuf) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("examples_{name}"));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet", "--force"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
    let summary = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    (summary, out)
}

fn vec3(v: &Value) -> [f64; 3] {
    [0, 1, 2].map(|k| v[k].as_f64().unwrap())
}

/// Global equilibrium: support reactions, indenter forces and applied loads
/// sum to zero (pair contacts are internal and cancel), to 1e-6 of the
/// largest of them (the Newton tolerance is 1e-6 on the residual norm).
fn assert_equilibrium(name: &str, s: &Value) {
    let mut forces: Vec<[f64; 3]> = s["reactions"].as_array().unwrap().iter().map(|r| vec3(&r["force"])).collect();
    forces
        .extend(s["contact"].as_array().unwrap().iter().filter(|c| c["kind"] == "indenter").map(|c| vec3(&c["force"])));
    forces.push(vec3(&s["applied_load"]));
    let scale = forces.iter().flat_map(|f| f.iter()).fold(0.0f64, |a, b| a.max(b.abs()));
    for k in 0..3 {
        let sum: f64 = forces.iter().map(|f| f[k]).sum();
        assert!(sum.abs() <= 1e-6 * scale, "{name}: force balance {k} off by {sum:e} (scale {scale:e})");
    }
}

/// Probe value (`s_xx`… by Voigt index, or `peeq`).
fn probe(s: &Value, name: &str, quantity: &str) -> f64 {
    let p = s["probes"].as_array().unwrap().iter().find(|p| p["name"] == name).unwrap();
    match quantity {
        "s_yy" => p["stress"][1].as_f64().unwrap(),
        "s_zz" => p["stress"][2].as_f64().unwrap(),
        "peeq" => p["peeq"].as_f64().unwrap(),
        q => panic!("no accessor for {q}"),
    }
}

/// `value` within `relative` of `reference`; the difference in % is the
/// figure `id` of the validation report.
fn assert_within(id: &str, what: &str, value: f64, reference: f64, relative: f64) {
    let err = (value - reference).abs() / reference.abs();
    common::figure(
        id,
        100.0 * (value / reference - 1.0),
        "%",
        &format!("|difference| ≤ {} %: {what}", 100.0 * relative),
    );
    let name = id;
    eprintln!("{name}: {what} = {value:.4e} (reference {reference:.4e}, {:.1} %)", 100.0 * err);
    assert!(
        err <= relative,
        "{name}: {what} = {value:e} is {:.1} % from {reference:e} (allowed {:.0} %)",
        100.0 * err,
        100.0 * relative
    );
}

use common::csv_columns;

/// σ_zz along the top line (`line_top.csv` of a run), as (x, σ_zz, peeq).
fn top_line(out: &Path) -> Vec<[f64; 3]> {
    let c = csv_columns(&out.join("line_top.csv"));
    (0..c["x"].len()).map(|i| [c["x"][i], c["s_zz"][i], c["peeq"][i]]).collect()
}

/// The 7 in roller's force (N, pushing down: positive).
fn roller_7in(s: &Value) -> f64 {
    -vec3(&s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "indenter_7in").unwrap()["force"])[2]
}

/// Normal and tangential resultants (N) of the run's pair contact.
fn interface_forces(s: &Value) -> (f64, f64) {
    let pair = s["contact"].as_array().unwrap().iter().find(|c| c["kind"] == "pair").unwrap();
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (norm(vec3(&pair["normal_force"])), norm(vec3(&pair["tangential_force"])))
}

/// The largest step towards compression of σ_zz between neighbouring
/// stations from x = 0.21 m (just inside the punch edge) to the centre
/// x = 0.25 m: zero for a profile that rises monotonically from the edge to
/// the centre, as the 3D solution does (tests/data/block_calculix_top.csv).
fn largest_reversal(line: &[[f64; 3]]) -> f64 {
    let under: Vec<&[f64; 3]> = line.iter().filter(|p| (0.21 - 1e-9..=0.25 + 1e-9).contains(&p[0])).collect();
    under.windows(2).map(|w| w[0][1] - w[1][1]).fold(0.0, f64::max)
}

/// The 3D solid model of the block: `cufem verify examples/block_indentation.toml
/// --refine 2` (CalculiX 2.20, 10,368 C3D20R, 145,767 DOF): punch force
/// 1.4102 MN, σ_zz peak along the top line 295.4 MPa.
const BLOCK_FORCE_3D: f64 = -1.4102e6;
const BLOCK_SZZ_PEAK_3D: f64 = 295.4e6;

/// §4.1, Tables 1–2, with the example's B-bar element and projected fields
/// (issue 8). Geometry, load and material are all in the paper's text; only
/// the mesh grading is assumed.
#[test]
fn block_indentation() {
    let s = run("block_indentation");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_block_indentation");
    assert_eq!(s["dof"], 5772);
    assert_equilibrium("block", &s);
    // The punch force against the 3D solid model: measured −1.05 %; the
    // issue's tolerance, 2 % (the paper's element: +8.0 %, test below).
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    assert_within(
        "block.punch_force",
        "punch force vs CalculiX (tests/data/references.toml, block)",
        vec3(&punch["force"])[2],
        BLOCK_FORCE_3D,
        0.02,
    );
    // σ_zz rises monotonically from the edge region to the centre, as in 3D:
    // no plateaus and jumps, no oscillation. Measured: largest reversal
    // 2.2 MPa, 0.7 % of the 3D peak; asserted 2 % (the paper's element:
    // 65 MPa, test below).
    let reversal = largest_reversal(&top_line(&out));
    common::figure("block.reversal", reversal / 1e6, "MPa", "< 2 % of the 3D peak (5.9 MPa)");
    assert!(reversal < 0.02 * BLOCK_SZZ_PEAK_3D, "σ_zz reversal under the punch {reversal:e} Pa");
    // The punch edge is a singular point: at the probe (0.2, 0.05, 0.3) the
    // 3D model gives σ_zz −213.7 MPa and peeq 0.194
    // (tests/data/block_calculix_top.csv, x = 0.2) and the paper's models
    // 0.0404–0.0658 (Table 2, growing under refinement); the example gives
    // −134.3 MPa and 0.0755. Known limits, asserted from both sides
    // (docs/limitations.md).
    common::known_limit(
        "block.edge.s_zz",
        probe(&s, "edge", "s_zz") / 1e6,
        "MPa",
        -138.3,
        -130.3,
        "σ_zz at the punch edge",
    );
    common::known_limit("block.edge.peeq", probe(&s, "edge", "peeq"), "", 0.0733, 0.0778, "peeq at the punch edge");
    // Along the top under the punch, x ∈ [0.21, 0.29] m, away from the
    // edge: σ_zz and peeq against the 3D top line, in % of its peak.
    // Measured 14.8 % and 10.5 % (the refined CUF meshes reach 8 % and 6 %:
    // block_refined_fields_match_calculix): known limits.
    let (szz, peeq) = under_the_punch(&top_line(&out));
    common::known_limit("block.top.s_zz", 100.0 * szz, "%", 14.3, 15.3, "σ_zz under the punch against 3D");
    common::known_limit("block.top.peeq", 100.0 * peeq, "%", 10.1, 10.9, "peeq under the punch against 3D");
}

/// The largest differences of σ_zz and peeq along the top under the punch,
/// x ∈ [0.21, 0.29] m, from the 3D top line (CalculiX C3D20R, refine 2,
/// tests/data/block_calculix_top.csv), as fractions of the 3D peak of each.
fn under_the_punch(ours: &[[f64; 3]]) -> (f64, f64) {
    let reference = csv_columns(
        &Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tests/data/block_calculix_top.csv"),
    );
    let mut worst = [0.0f64; 2];
    for (k, q) in [(1, "s_zz"), (2, "peeq")] {
        let peak = reference[q].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, o) in ours.iter().enumerate() {
            assert!((reference["x"][i] - o[0]).abs() < 1e-9, "stations differ");
            if (0.21 - 1e-9..=0.29 + 1e-9).contains(&o[0]) {
                worst[k - 1] = worst[k - 1].max((o[k] - reference[q][i]).abs() / peak);
            }
        }
    }
    (worst[0], worst[1])
}

/// The block's elastic stiffness on the shipped mesh: the force of the
/// first increment (0.05 mm, elastic) against the 3D model of the same
/// elastic increment (CalculiX C3D20R: 263,204.7 N at refine 1,
/// 263,753.4 N at refine 2, 145,767 DOF: `cufem verify` of the example
/// without its plasticity, one increment of 0.05 mm;
/// tests/data/references.toml, block_elastic). Measured +0.57 % against
/// refine 2; 2 %: the 3D force still rises under refinement (+0.2 % from
/// refine 1 to 2) at the singular punch edges, while a 10 % error in the
/// element stiffness or the punch contact fails.
#[test]
fn block_indentation_first_increment_force_against_3d() {
    let _ = run("block_indentation");
    assert_eq!(first_increment("block_indentation", "punch").0, 0.0, "the first increment is elastic");
    let (_, _, force) = first_increment("block_indentation", "punch");
    assert_within(
        "block.first_force",
        "elastic first-increment punch force vs CalculiX (refine 2)",
        force,
        -263_753.4,
        0.02,
    );
}

/// The block with the paper's displacement-based element and element-wise
/// recovery (the example without its two issue-8 lines): volumetric locking
/// in the confined plastic flow under the punch. Measured: punch force
/// +8.0 % above the 3D model (a known limit of that element, asserted from
/// both sides) and a σ_zz reversal of 65 MPa under the punch (plateaus
/// joined by jumps). This is why the example ships B-bar; the test fails if
/// `formulation` or `recovery` stopped being honoured.
#[test]
fn block_indentation_paper_element_locks() {
    let text = std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/block_indentation.toml"),
    )
    .unwrap()
    .replace("formulation = \"bbar\"\n", "")
    .replace("recovery = \"projection\"\n", "");
    assert!(!text.contains("formulation = \"bbar\"\n") && !text.contains("recovery = \"projection\"\n"));
    let (s, out) = run_text("block_standard", &text);
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    let excess = 100.0 * (vec3(&punch["force"])[2] / BLOCK_FORCE_3D - 1.0);
    common::known_limit("block_paper_element.punch_force", excess, "%", 7.8, 8.3, "punch force against 3D (locking)");
    let reversal = largest_reversal(&top_line(&out));
    common::figure("block_paper_element.reversal", reversal / 1e6, "MPa", "> 10 % of the 3D peak (plateaus and jumps)");
    assert!(reversal > 0.1 * BLOCK_SZZ_PEAK_3D, "σ_zz reversal under the punch {reversal:e} Pa");
    common::figure("block_paper_element.edge.s_zz", probe(&s, "edge", "s_zz") / 1e6, "MPa", "reported");
    common::figure("block_paper_element.edge.peeq", probe(&s, "edge", "peeq"), "", "reported");
}

/// The indentation test (issue 10): the block example loaded to 1 mm and
/// unloaded. The punch ends free of force, the dent stays (residual depth
/// between 0 and the 1 mm pushed: measured 0.710 mm at the centre, the
/// springback 0.29 mm), and every step has its results.
#[test]
fn block_indentation_unload() {
    let s = run("block_indentation_unload");
    // the unloading step starts on the elastic branch (docs/load-histories.md)
    assert_eq!(s["cutbacks"], 0, "the unloading step needs no cutback");
    let steps = s["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2);
    let punch = |step: &Value| {
        vec3(&step["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap()["force"])[2]
    };
    // equilibrium of the loaded state (at the end everything is zero)
    let bottom = vec3(&steps[0]["reactions"].as_array().unwrap()[0]["force"])[2];
    assert!((bottom + punch(&steps[0])).abs() < 1e-6 * bottom.abs(), "loaded balance {bottom:e}");
    // loaded: the block example's force (same model and increments)
    assert_within("block_unload.punch_force", "loaded punch force vs CalculiX", punch(&steps[0]), BLOCK_FORCE_3D, 0.02);
    assert_eq!(punch(&steps[1]), 0.0, "the punch has left the block");
    let centre = |step: &Value| {
        step["probes"].as_array().unwrap().iter().find(|p| p["name"] == "centre").unwrap()["u"][2].as_f64().unwrap()
    };
    let residual = -centre(&steps[1]);
    assert!(residual > 0.0 && residual < 1e-3, "residual depth {residual:e} m");
    // the springback is the elastic recovery of the loaded force at the
    // unloading stiffness while the whole punch face is in contact, then the
    // contact opens from the edges. Unloading is elastic with the stiffness
    // of the loaded state (tests/load_history.rs), which is the elastic
    // stiffness of the first loading increment (elastic, the whole face in
    // contact): measured 0.290 mm against F/k = 0.263 mm
    let (plastic, delta, force) = first_increment("block_indentation_unload", "punch");
    assert_eq!(plastic, 0.0, "the first increment is elastic");
    let springback = -centre(&steps[0]) - residual;
    let linear = -punch(&steps[0]) / (force / delta);
    assert!(springback > linear && springback < 1.25 * linear, "springback {springback:e} m, F/k {linear:e} m");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_block_indentation_unload");
    for f in ["result_1_load.vtu", "result_2_unload.vtu", "result.pvd", "history_punch.png"] {
        assert!(out.join(f).exists(), "{f} missing");
    }
}

/// Springback of the tube (issue 10): the force-controlled roller loaded
/// to 1.6 kN and back to 2 %. Unloading starts elastic (no Gauss point
/// yields down to 60 % of the force), so the slope of the first unloading increment is the elastic stiffness
/// of the first loading increment (same contact lines; measured 7.1060e6
/// against 7.1067e6 N/m, asserted 1 %); the roller ends at 32 N; the top
/// fibre, yielded in compression, is left in tension under the roller
/// (measured +12.9 MPa) with a residual dent of 0.43 mm (springback 0.24 mm).
#[test]
fn bending_tube_springback() {
    let s = run("bending_tube_springback");
    assert_eq!(s["cutbacks"], 0, "the unloading step needs no cutback");
    let steps = s["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2);
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_bending_tube_springback");
    let csv = std::fs::read_to_string(out.join("history_load.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let rows: Vec<Vec<f64>> = csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    let (lam, dz, fz, pp) = (col("lambda"), col("d_z"), col("f_z"), col("plastic_points"));
    assert_eq!(rows[0][pp], 0.0, "the first increment is elastic");
    let k_elastic = rows[0][fz] / rows[0][dz];
    let loaded = rows.iter().position(|r| (r[lam] - 1.0).abs() < 1e-9).unwrap();
    assert!(rows[loaded][pp] > 0.0, "the tube yields under the roller");
    let first_unload = &rows[loaded + 1];
    let k_unload = (rows[loaded][fz] - first_unload[fz]) / (rows[loaded][dz] - first_unload[dz]);
    assert_within("tube_springback.unloading_slope", "unloading slope vs elastic stiffness", k_unload, k_elastic, 0.01);
    // elastic down to 60 % of the force; below, 4 Gauss points on the roller
    // line yield again in reverse (measured at 41 % and 22 %)
    for r in rows.iter().filter(|r| r[lam] > 1.0 && r[lam] < 1.5) {
        assert_eq!(r[pp], 0.0, "unloading increment at λ = {} yields", r[lam]);
    }
    let last = rows.last().unwrap();
    assert!((last[fz] + 32.0).abs() < 1e-6 * 1600.0, "final roller force {}", last[fz]);
    let springback = last[dz] - rows[loaded][dz];
    assert!(springback > 0.0 && -last[dz] > 0.0, "springback {springback:e}, residual {:e}", last[dz]);
    let residual = probe(&steps[1], "contact_centre", "s_yy");
    assert!(residual > 0.0, "residual σ_yy at the contact centre {residual:e}");
}

/// §4.2, Tables 3 and 5: compact bar. The span, roller radius and section
/// mesh are assumed (Fig. 7 missing); the probe sits on the loading-roller
/// line, where a node-to-node contact concentrates the load. Against the 3D
/// model of the same bar (CalculiX C3D20R, refine 1 of the 16 L9 mesh;
/// tests/data/references.toml, compact16_quarter): σ_yy −43.6 MPa and peeq
/// 1.08e-3 at the probe. The probe's values are known limits, asserted from
/// both sides (`s_yy` in MPa and `peeq` measured, ±3 %; docs/limitations.md):
/// σ_yy 2–3 % and peeq 9–12 % below 3D on the roller line. The paper's
/// values (Table 5) are reported beside them: its geometry is not ours.
fn compact(name: &str, dof: u64, s_yy: f64, peeq: f64) {
    let s = run(name);
    assert_eq!(s["dof"], dof);
    assert_equilibrium(name, &s);
    let (ours_syy, ours_peeq) = (probe(&s, "contact_centre", "s_yy") / 1e6, probe(&s, "contact_centre", "peeq"));
    let band = |v: f64| if v < 0.0 { (1.03 * v, 0.97 * v) } else { (0.97 * v, 1.03 * v) };
    let (lo, hi) = band(s_yy);
    common::known_limit(&format!("{name}.s_yy"), ours_syy, "MPa", lo, hi, "σ_yy at the contact centre (3D: −43.6 MPa)");
    let (lo, hi) = band(peeq);
    common::known_limit(&format!("{name}.peeq"), ours_peeq, "", lo, hi, "peeq at the contact centre (3D: 1.08e-3)");
    common::figure(
        &format!("{name}.s_yy_vs_paper_abaqus"),
        100.0 * (ours_syy / -43.63 - 1.0),
        "%",
        "reported against paper Table 5, ABAQUS refined",
    );
}

/// `(plastic points, indenter displacement along z, force along z)` of the
/// first converged increment of an example's indenter history.
fn first_increment(name: &str, indenter: &str) -> (f64, f64, f64) {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("example_{name}"));
    let csv = std::fs::read_to_string(out.join(format!("history_{indenter}.csv"))).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |key: &str| -> f64 {
        let at = header.iter().position(|h| *h == key).unwrap_or_else(|| panic!("no column {key} in {header:?}"));
        first[at].parse().unwrap_or_else(|e| panic!("{key} = {:?}: {e}", first[at]))
    };
    (column("plastic_points"), column("d_z"), column("f_z"))
}

/// The roller force of the first (elastic) increment against Timoshenko's
/// three-point bending, δ = P L³/(48 E I) + P L/(4 κ G A) with Cowper's
/// κ = 10(1 + ν)/(12 + 11ν) (Timoshenko & Gere, *Mechanics of Materials*;
/// Cowper, J. Appl. Mech. 33, 1966): span L = 0.2 m between the supports,
/// 10 mm square section, E = 68 GPa, ν = 0.33. Observed 0.15 % above the
/// theory; 2 % allows for the local flexibility of the three roller contacts
/// (node-to-node penalty, α = 100) while a 10 % error in the element
/// stiffness or in the axis derivatives (≥ 10 % in bending) fails.
fn assert_elastic_bending_stiffness(name: &str) {
    let (plastic, delta, force) = first_increment(name, "load");
    let (delta, force) = (-delta, -force);
    assert_eq!(plastic, 0.0, "{name}: the first increment should be elastic");
    let (e, nu, b, l): (f64, f64, f64, f64) = (68e9, 0.33, 0.01, 0.2);
    let (i, a, g) = (b.powi(4) / 12.0, b * b, e / (2.0 * (1.0 + nu)));
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let compliance = l.powi(3) / (48.0 * e * i) + l / (4.0 * kappa * g * a);
    assert_within(
        &format!("{name}.elastic_force"),
        "elastic roller force vs Timoshenko",
        force,
        delta / compliance,
        0.02,
    );
}

#[test]
fn bending_compact_4l9() {
    compact("bending_compact_4L9", 2325, -42.37, 0.951e-3);
    assert_elastic_bending_stiffness("bending_compact_4L9");
}

#[test]
fn bending_compact_16l9() {
    compact("bending_compact_16L9", 7533, -42.93, 0.981e-3);
    assert_elastic_bending_stiffness("bending_compact_16L9");
}

/// §4.2, Tables 4 and 6: thin-walled tube. As for the compact bar, plus the
/// ring mesh (Fig. 13) is assumed. The probe is at mid-width of the top wall
/// under the roller, where the wall bends locally (in our model it lifts off
/// the roller by ~0.02 mm). Against the 3D model of the 28 L9 mesh
/// (CalculiX C3D20R, refine 1; tests/data/references.toml, tube): σ_yy
/// −63.87 MPa and peeq 5.27e-3 at the probe. Known limits, asserted from
/// both sides (the measured values ±3 %; docs/limitations.md): 28 L9 +13 %
/// on σ_yy and peeq within 0.2 %; 20 L9 +1.4 % and +15 %.
fn tube(name: &str, dof: u64, s_yy: f64, peeq: f64) -> Value {
    let s = run(name);
    assert_eq!(s["dof"], dof);
    assert_equilibrium(name, &s);
    let (ours_syy, ours_peeq) = (probe(&s, "contact_centre", "s_yy") / 1e6, probe(&s, "contact_centre", "peeq"));
    common::known_limit(
        &format!("{name}.s_yy"),
        ours_syy,
        "MPa",
        1.03 * s_yy,
        0.97 * s_yy,
        "σ_yy at the contact centre (3D: −63.87 MPa)",
    );
    common::known_limit(
        &format!("{name}.peeq"),
        ours_peeq,
        "",
        0.97 * peeq,
        1.03 * peeq,
        "peeq at the contact centre (3D: 5.27e-3)",
    );
    common::figure(
        &format!("{name}.s_yy_vs_3d"),
        100.0 * (ours_syy / -63.8669 - 1.0),
        "%",
        "reported against 3D (CalculiX C3D20R, refine 1)",
    );
    common::figure(
        &format!("{name}.peeq_vs_3d"),
        100.0 * (ours_peeq / 5.27e-3 - 1.0),
        "%",
        "reported against 3D (CalculiX C3D20R, refine 1)",
    );
    s
}

#[test]
fn bending_tube_20l9() {
    let _ = tube("bending_tube_20L9", 24120, -64.74, 6.05e-3);
}

/// The tube's elastic stiffness on the shipped 20 L9 mesh: the roller force
/// of the example without its plasticity, one increment of 0.05 mm, against
/// the 3D model of the same mesh and increment (CalculiX C3D20R, refine 1,
/// 88,080 DOF: 337.29 N; tests/data/references.toml, tube20_elastic).
/// Measured +5.35 %: one L9 through the 1.5 mm wall and 20 around the ring
/// make the wall too stiff in its local bending under the roller line
/// (cufem's own model with 36 L9 and 44 B4 gives 342.1 N, +1.4 %). A known
/// limit, asserted from both sides (docs/limitations.md); a 10 % error in
/// the thin-wall bending stiffness or the roller contact leaves it.
#[test]
fn bending_tube_20l9_elastic_stiffness_against_3d() {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/bending_tube_20L9.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let (start, end) = (text.find("[materials.plasticity]").unwrap(), text.find("[[bodies]]").unwrap());
    let elastic = format!("{}{}", &text[..start], &text[end..])
        .replace("increments = 15", "increments = 1")
        .replace("displacement = [0.0, 0.0, -0.75e-3]", "displacement = [0.0, 0.0, -0.05e-3]");
    assert!(elastic.contains("-0.05e-3") && elastic.contains("increments = 1\n"));
    let (s, _) = run_text("bending_tube_20L9_elastic", &elastic);
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    let d = 100.0 * (vec3(&load["force"])[2] / -337.2939 - 1.0);
    common::known_limit("bending_tube_20L9.elastic_force", d, "%", 5.19, 5.51, "elastic roller force against 3D");
}

#[test]
fn bending_tube_28l9() {
    let s = tube("bending_tube_28L9", 33768, -72.28, 5.26e-3);
    // 3D reference: `cufem verify examples/bending_tube_28L9.toml --refine 1`
    // (CalculiX 2.20, C3D20R, 123,312 DOF; tests/data/references.toml, tube):
    // loading roller 1,698.2 N. Measured −3.45 %: the axis elements of
    // 11.1 mm cannot follow the web tops crushing under the roller (the
    // graded mesh is within 0.9 %: crates/cufem-cli/tests/fidelity.rs). A known limit.
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    let d = 100.0 * (vec3(&load["force"])[2] / -1698.2 - 1.0);
    common::known_limit("bending_tube_28L9.force_load", d, "%", -3.56, -3.34, "roller force against 3D");
}

/// The graded tube's quarter with two L9 through the wall
/// (`examples/bending_tube_graded_wall2.toml`) against the converged 3D
/// quarter (CalculiX C3D20R of the quarter with 1 mm B4 at the roller,
/// converged along the axis and through the wall:
/// tests/data/references.toml, tube_quarter_1mm — 418.6434 N on the
/// quarter, σ_yy −64.698 MPa and peeq 5.39991e-3 at the contact centre):
/// issue 49's roller force within 2 % (measured −0.18 %) and probes on the
/// roller line within 10 % (σ_yy −1.6 %, peeq −3.1 %), where the shipped
/// meshes with one L9 through the wall are +16 % in σ_yy
/// (crates/cufem-cli/tests/roller_twins.rs). A hardening curve 10 % high
/// puts the force of the same section on the 1 mm axis at +8.7 % (checked
/// by hand), out of the band.
#[test]
fn bending_tube_graded_wall2() {
    let name = "bending_tube_graded_wall2";
    let s = run(name);
    assert_eq!(s["dof"], 31635);
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    let what = "loading roller (quarter) against the converged 3D quarter";
    assert_within(&format!("{name}.force_load"), what, vec3(&load["force"])[2], -418.6434, 0.02);
    let what = "σ_yy at the contact centre against the converged 3D quarter";
    assert_within(&format!("{name}.s_yy"), what, probe(&s, "contact_centre", "s_yy"), -64.6981e6, 0.10);
    let what = "peeq at the contact centre against the converged 3D quarter";
    assert_within(&format!("{name}.peeq"), what, probe(&s, "contact_centre", "peeq"), 5.39991e-3, 0.10);
}

/// §4.3, Tables 7–8. The layout is our choice (no source found for Choi &
/// Chung's dimensions; see the example's header), so the paper's probes are
/// not asserted; the forces are checked against a 3D CalculiX model of the
/// same layout.
#[test]
fn cantilevers_contact() {
    let s = run("cantilevers_contact");
    assert_eq!(s["dof"], 15066);
    assert_equilibrium("cantilevers", &s);
    // the layout's design claim (see the example's header): small plastic
    // strains, far from the crushing of the first layout (0.3–1.5 in 3D)
    let max_peeq = s["max_peeq"].as_f64().unwrap();
    eprintln!("cantilevers: max peeq {max_peeq:.4}");
    assert!(max_peeq > 0.0 && max_peeq < 0.05, "max peeq {max_peeq}");
    // 3D reference: `cufem verify examples/cantilevers_contact.toml --refine 1`
    // (CalculiX 2.20, 5,420 C3D20R, 56,430 DOF, frictionless surface-to-surface
    // contact; tests/data/references.toml, cantilevers). Measured +1.9 %
    // (7 in roller), +2.5 % and +3.6 % (roots); with 20 B4 per beam all
    // three are within 0.6 % (crates/cufem-cli/tests/fidelity.rs): known limits of the
    // paper's axis mesh, asserted from both sides.
    let force = |name: &str| {
        let c = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == name).unwrap();
        vec3(&c["force"])[2]
    };
    let reaction = |name: &str| {
        let r = s["reactions"].as_array().unwrap().iter().find(|r| r["name"] == name).unwrap();
        vec3(&r["force"])[2]
    };
    for (id, value, ccx, low, high) in [
        ("cantilevers.force_7in", force("indenter_7in"), -25_769.0, 1.80, 1.92),
        ("cantilevers.upper_root", reaction("upper_root"), 12_619.0, 2.43, 2.59),
        ("cantilevers.lower_root", reaction("lower_root"), 16_087.0, 3.53, 3.76),
    ] {
        common::known_limit(id, 100.0 * (value / ccx - 1.0), "%", low, high, "against 3D");
    }
    // both rollers bear (the 9 in one lightly: 3.4 kN here, 2.9 kN in 3D)
    assert!(force("indenter_9in") < -1000.0);
    // the pair contact carries the load from one beam to the other
    let pair = s["contact"].as_array().unwrap().iter().find(|c| c["kind"] == "pair").unwrap();
    assert!(vec3(&pair["force"])[2] > 0.0);
}

/// Plane-strain twin of the block (issue 8): a flat punch on a block 10
/// punch widths wide, B-bar, driven to full plastic flow. Prandtl's mean
/// pressure (2 + π) k, k = σ_y/√3 (Hill 1950, §VIII.3), is the limit of the
/// punch pressure and, with a smooth punch, the uniform σ_zz under it.
#[test]
fn punch_plane_strain() {
    let s = run("punch_plane_strain");
    assert_equilibrium("punch_plane_strain", &s);
    let prandtl = -(2.0 + std::f64::consts::PI) * 100e6 / 3f64.sqrt();
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    // measured +2.0 % (+3.0 % on a mesh half as fine: converging from above)
    let pressure = vec3(&punch["force"])[2] / 0.01;
    assert_within("punch_plane_strain.pressure", "mean punch pressure vs Prandtl", pressure, prandtl, 0.03);
    // measured −0.2 %
    assert_within(
        "punch_plane_strain.s_zz_centre",
        "σ_zz at the centre vs Prandtl",
        probe(&s, "centre", "s_zz"),
        prandtl,
        0.03,
    );
    // the profile under the punch, away from the edge elements: flat at
    // Prandtl's pressure within 3 % (measured −294…−301 MPa); no plateaus and
    // jumps, no oscillation between neighbouring stations
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_punch_plane_strain");
    let line = csv_columns(&out.join("line_top.csv"));
    let worst = (0..line["x"].len())
        .filter(|&i| (0.455..=0.545).contains(&line["x"][i]))
        .map(|i| line["s_zz"][i] / prandtl - 1.0)
        .fold(0.0f64, |w, d| if d.abs() > w.abs() { d } else { w });
    common::figure(
        "punch_plane_strain.s_zz_profile",
        100.0 * worst,
        "%",
        "|difference| ≤ 3 % at every station under the punch, against Prandtl",
    );
    assert!(worst.abs() <= 0.03, "σ_zz under the punch {:+.2} % from Prandtl", 100.0 * worst);
}

/// Issue 8's field check. The block example (B-bar, projected fields) on
/// refined CUF meshes — the section twice as fine in both directions
/// (36 × 12 L9, same gradings) with 3 and with 4 B4 along y: 54,750 and
/// 71,175 DOF — against the CalculiX solution of
/// `tests/data/block_calculix_top.csv`: σ_zz and peeq along the top line
/// within 10 % of the 3D peak at every station x ∈ [0.21, 0.29] m, the punch
/// force within 2 %, the σ_zz profile monotone from the edge region to the
/// centre (2 % of the 3D peak), and the two meshes' σ_zz within 3 % of the
/// 3D peak of each other. Measured (3 B4 / 4 B4): σ_zz 8.4 % / 6.8 %, peeq
/// 5.9 % / 5.8 %, force +0.32 % / +0.45 %, no reversal, σ_zz 3 ↔ 4 B4
/// 1.5 %. docs/cross-check.md lists the whole refinement sequence.
#[test]
#[ignore = "validate: slow — the block on two meshes of 55,000 and 71,000 DOF (about 4 min)"]
fn block_refined_fields_match_calculix() {
    let mut lines = Vec::new();
    for (axis, dof) in [(3, 54750), (4, 71175)] {
        let name = format!("block_refined_{axis}B4");
        let text = std::fs::read_to_string(
            Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/block_indentation.toml"),
        )
        .unwrap()
        .replace("elements = 6, ratio", "elements = 12, ratio")
        .replace("{ from = 0.2, to = 0.3, elements = 6 }", "{ from = 0.2, to = 0.3, elements = 12 }")
        .replace("to = 0.1, elements = 1 }", &format!("to = 0.1, elements = {axis} }}"));
        let (s, out) = run_text(&name, &text);
        assert_eq!(s["dof"], dof);
        let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
        assert_within(
            &format!("{name}.punch_force"),
            "punch force vs CalculiX",
            vec3(&punch["force"])[2],
            BLOCK_FORCE_3D,
            0.02,
        );
        let ours = top_line(&out);
        let reversal = largest_reversal(&ours);
        common::figure(&format!("{name}.reversal"), 100.0 * reversal / BLOCK_SZZ_PEAK_3D, "%", "< 2 % of the 3D peak");
        assert!(reversal < 0.02 * BLOCK_SZZ_PEAK_3D, "{name}: σ_zz reversal {reversal:e} Pa");
        let (szz, peeq) = under_the_punch(&ours);
        common::figure(&format!("{name}.s_zz_under"), 100.0 * szz, "%", "< 10 % of the 3D peak under the punch");
        common::figure(&format!("{name}.peeq_under"), 100.0 * peeq, "%", "< 10 % of the 3D peak under the punch");
        assert!(szz < 0.10 && peeq < 0.10, "{name}: σ_zz {szz}, peeq {peeq} of the 3D peaks");
        lines.push(ours);
    }
    for (a, b) in lines[0].iter().zip(&lines[1]) {
        if (0.21 - 1e-9..=0.29 + 1e-9).contains(&a[0]) {
            assert!(
                (a[1] - b[1]).abs() < 0.03 * BLOCK_SZZ_PEAK_3D,
                "σ_zz at x = {}: 3 B4 {:e}, 4 B4 {:e}",
                a[0],
                a[1],
                b[1]
            );
        }
    }
}

/// Timoshenko three-point bending compliance of the I-beam of
/// `examples/ibeam_roller.toml`: δ/P = L³/(48 E I) + L/(4 k G A), span
/// L = 0.6 m, b × h = 40 × 60 mm, t_w = 2 mm, t_f = 3 mm, E = 70 GPa,
/// ν = 0.33, with Cowper's shear coefficient of an I-section (Cowper, J.
/// Appl. Mech. 33, 1966, Table 1; m = 2 b t_f/(h t_w), n = b/h): k = 0.3168.
fn ibeam_compliance() -> f64 {
    let (e, nu, b, h, tw, tf, l): (f64, f64, f64, f64, f64, f64, f64) = (70e9, 0.33, 0.04, 0.06, 0.002, 0.003, 0.6);
    let i = (b * h.powi(3) - (b - tw) * (h - 2.0 * tf).powi(3)) / 12.0;
    let a = 2.0 * b * tf + (h - 2.0 * tf) * tw;
    let (m, n) = (2.0 * b * tf / (h * tw), b / h);
    let k = 10.0 * (1.0 + nu) * (1.0 + 3.0 * m).powi(2)
        / ((12.0 + 72.0 * m + 150.0 * m * m + 90.0 * m.powi(3))
            + nu * (11.0 + 66.0 * m + 135.0 * m * m + 90.0 * m.powi(3))
            + 30.0 * n * n * (m + m * m)
            + 5.0 * nu * n * n * (8.0 * m + 9.0 * m * m));
    assert!((k - 0.3168).abs() < 1e-4, "Cowper k = {k}");
    let g = e / (2.0 * (1.0 + nu));
    l.powi(3) / (48.0 * e * i) + l / (4.0 * k * g * a)
}

/// Issue 11: a thin-walled I-beam (parametric `i_beam` section) pressed by
/// a rigid roller on its top flange in three-point bending.
#[test]
fn ibeam_roller() {
    let name = "ibeam_roller";
    let s = run(name);
    assert_eq!(s["dof"], 19899);
    assert_equilibrium(name, &s);
    // the first increment (0.2 mm) is elastic; its roller force against
    // Timoshenko: measured 2.6 % more compliant, the local indentation of
    // the flanges and web at the three line contacts (beam theory has
    // none); 5 % while a 10 % error in the bending stiffness fails
    let (plastic, delta, force) = first_increment(name, "load");
    assert_eq!(plastic, 0.0, "{name}: the first increment should be elastic");
    assert_within(
        "ibeam_roller.first_force",
        "first-increment roller force vs Timoshenko",
        force / delta,
        1.0 / ibeam_compliance(),
        0.05,
    );
    // at 4 mm the web yields under the roller (local crippling) while the
    // web's mid-height at mid-span and above the support stays elastic
    let peeq =
        |p: &str| s["probes"].as_array().unwrap().iter().find(|q| q["name"] == p).unwrap()["peeq"].as_f64().unwrap();
    assert!(peeq("web_top") > 1e-2, "web under the roller: peeq {}", peeq("web_top"));
    assert_eq!(peeq("web_mid"), 0.0);
    assert_eq!(peeq("web_support"), 0.0);
    // 3D reference: `cufem verify examples/ibeam_roller.toml --refine 1`
    // (CalculiX 2.20, C3D20R, 72,063 DOF, the same half-symmetric model):
    // loading roller 8,554.2 N. Measured +0.97 %; 3 %: node-to-node against
    // surface contact, one L9 through each wall
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    assert_within("ibeam_roller.force_load", "roller force vs CalculiX", vec3(&load["force"])[2], -8554.2, 0.03);
}

/// The same beam elastic (no plasticity, one increment): the deflection of
/// the web's mid-height at mid-span relative to that above a support
/// leaves out the local indentation, and the beam's stiffness matches
/// Timoshenko: measured 0.85 % stiffer. Shear is 15 % of the compliance
/// and Cowper's k is itself approximate for a thin-walled I (the web area
/// h t_w as shear area makes the theory 1.4 % stiffer than with k); 2 %.
#[test]
fn ibeam_roller_elastic_matches_timoshenko() {
    let text = std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/ibeam_roller.toml"),
    )
    .unwrap();
    let start = text.find("[materials.plasticity]").unwrap();
    let end = text.find("[[bodies]]").unwrap();
    let text = format!("{}{}", &text[..start], &text[end..]).replace("increments = 20", "increments = 1");
    let (s, _) = run_text("ibeam_roller_elastic", &text);
    assert_equilibrium("ibeam_roller_elastic", &s);
    let uz =
        |p: &str| s["probes"].as_array().unwrap().iter().find(|q| q["name"] == p).unwrap()["u"][2].as_f64().unwrap();
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    let force = -vec3(&load["force"])[2];
    let deflection = uz("web_support") - uz("web_mid");
    assert_within(
        "ibeam_roller_elastic.stiffness",
        "beam stiffness (web mid-height) vs Timoshenko",
        force / deflection,
        1.0 / ibeam_compliance(),
        0.02,
    );
}

/// Issue 49: `examples/channel_roller.toml`, a channel pressed by a rigid
/// roller on its top flange, off its shear centre (bending plus twist),
/// fork supports, elastic, half model. 3D reference: `cufem verify` of the
/// same model on a finer mesh (4 L9 along each flange, 12 along the web, 2 + 20
/// B4: `python3 bench/channel_roller_study.py model fork "L9 4/12/1 x2"`,
/// CalculiX 2.20, C3D20R, refine 1, 98,487 DOF), which moved the twist by
/// at most 0.1 % and the force by 0.5 % from the twin of the 11 B4 × 12 L9
/// mesh (27,519 DOF; bench/channel_roller_results.txt): roller force
/// 1,363.5 N (full structure) and the web's rotation
/// (u_x(top) − u_x(bottom)) / h at y = 100, 175, 250 and 325 mm. Measured:
/// force +0.09 %, twist +0.26 … +0.36 %; the bounds, 2 % and 3 %.
#[test]
fn channel_roller() {
    let name = "channel_roller";
    let s = run(name);
    assert_eq!(s["dof"], 15075);
    assert_equilibrium(name, &s);
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    assert_within(
        "channel_roller.force_load",
        "roller force (full structure) vs CalculiX",
        vec3(&load["full_structure_force"])[2],
        -1363.5,
        0.02,
    );
    let u = |p: &str| vec3(&s["probes"].as_array().unwrap().iter().find(|q| q["name"] == p).unwrap()["u"]);
    let twist = |y: u32| (u(&format!("wt_{y}"))[0] - u(&format!("wb_{y}"))[0]) / 0.06;
    for (y, reference) in [(100, 0.011006), (175, 0.020681), (250, 0.027627), (325, 0.029977)] {
        assert_within(
            &format!("channel_roller.twist_{y}"),
            &format!("twist at y = {y} mm vs CalculiX"),
            twist(y),
            reference,
            0.03,
        );
    }
    // the fork holds the twist at the support: CalculiX 0.24 % of the mid-span twist
    assert!(twist(25).abs() < 0.01 * twist(325), "twist at the fork {} rad", twist(25));
    // the top flange's tip at mid-span: lateral and vertical displacement (CalculiX
    // 0.9091 and −2.0325 mm; the vertical one is half bending, half twist × width)
    let tip = u("tt_325");
    assert_within("channel_roller.tip_u_x", "top flange tip u_x at mid-span vs CalculiX", tip[0], 0.9091e-3, 0.03);
    assert_within("channel_roller.tip_u_z", "top flange tip u_z at mid-span vs CalculiX", tip[2], -2.0325e-3, 0.03);
}

/// The two cantilevers with Coulomb friction μ = 0.3 between the beams
/// (issue 9, item 5; node-to-node contact, GMRES on the unsymmetric
/// tangent). Coulomb's law bounds the tangential resultant of the interface
/// by μ times its normal resultant; the interface slides wherever it
/// touches here (measured: 5.31 kN against 0.300 × 17.68 kN), so the bound
/// is met with equality to within the elastic-slip regularisation
/// (asserted: between 0.29 and 0.3 (1 + 1e-9) times the normal force).
/// Friction resists the beams' relative sliding, so the structure is
/// stiffer than without it: the 7 in roller force must exceed that of the
/// frictionless example, run by this file (measured +3.6 %).
#[test]
fn cantilevers_contact_friction() {
    let s = run("cantilevers_contact_friction");
    assert_eq!(s["dof"], 15066);
    assert_equilibrium("cantilevers with friction", &s);
    let (normal, tangential) = interface_forces(&s);
    eprintln!("friction cantilevers: interface normal {normal:.1} N, tangential {tangential:.1} N");
    assert!(normal > 0.0 && tangential <= 0.3 * normal * (1.0 + 1e-9), "{tangential} vs μN = {}", 0.3 * normal);
    assert!(tangential >= 0.29 * normal, "interface not sliding: {tangential} vs {normal}");
    let frictionless = roller_7in(&run("cantilevers_contact"));
    let rise = roller_7in(&s) / frictionless - 1.0;
    common::figure("cantilevers_friction.rise_7in", 100.0 * rise, "%", "> 0: friction stiffens the structure");
    assert!(rise > 0.0, "7 in roller {:+.2} % against the frictionless example", 100.0 * rise);
}

/// The two cantilevers on non-matching meshes (surface contact) with
/// Coulomb friction μ = 0.3 (issue 9, item 5). Coulomb bounds the
/// interface's tangential resultant by μ N and it slides wherever it
/// touches (measured 5.03 kN = 0.300 × 16.78 kN; asserted 0.29–0.3 μN as
/// for the matching mesh). Independent check of the friction's effect: the
/// same friction must change the 7 in roller force and the interface
/// normal force on the non-matching mesh (surface contact) as on the
/// matching mesh (node-to-node contact), to within one percentage point;
/// all four examples are run by this file (measured: matching +3.6 % and
/// +6.1 %, non-matching +3.4 % and +6.0 %). Dropping the unsymmetric
/// pressure coupling of the surface-friction tangent makes this model
/// fail to converge in its first increment (measured).
#[test]
fn cantilevers_contact_nonmatching_friction() {
    let s = run("cantilevers_contact_nonmatching_friction");
    assert_eq!(s["dof"], 14694);
    assert_equilibrium("non-matching cantilevers with friction", &s);
    let (normal, tangential) = interface_forces(&s);
    eprintln!("non-matching friction cantilevers: interface normal {normal:.1} N, tangential {tangential:.1} N");
    assert!(tangential <= 0.3 * normal * (1.0 + 1e-9), "{tangential} vs μN = {}", 0.3 * normal);
    assert!(tangential >= 0.29 * normal, "interface not sliding: {tangential} vs {normal}");
    let frictionless = run("cantilevers_contact_nonmatching");
    let rise7 = roller_7in(&s) / roller_7in(&frictionless) - 1.0;
    let rise_n = normal / interface_forces(&frictionless).0 - 1.0;
    let (matching, matching_friction) = (run("cantilevers_contact"), run("cantilevers_contact_friction"));
    let rise7_matching = roller_7in(&matching_friction) / roller_7in(&matching) - 1.0;
    let rise_n_matching = interface_forces(&matching_friction).0 / interface_forces(&matching).0 - 1.0;
    let check = "within 1 point of the same rise on the matching mesh";
    common::figure("cantilevers_nonmatching_friction.rise_7in", 100.0 * rise7, "%", check);
    common::figure("cantilevers_nonmatching_friction.rise_normal", 100.0 * rise_n, "%", check);
    common::figure("cantilevers_friction.rise_normal", 100.0 * rise_n_matching, "%", "reported");
    assert!(
        (rise7 - rise7_matching).abs() < 0.01,
        "7 in roller rises {rise7} with friction (matching mesh: {rise7_matching})"
    );
    assert!(
        (rise_n - rise_n_matching).abs() < 0.01,
        "interface normal force rises {rise_n} (matching mesh: {rise_n_matching})"
    );
    // contact_beams.csv: at every sliding point the tangential traction is
    // μ times the normal pressure (Coulomb), and pressure × area sums to the
    // interface's normal resultant
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_cantilevers_contact_nonmatching_friction");
    let c = csv_columns(&out.join("contact_beams.csv"));
    let (mut total, mut slid) = (0.0, 0);
    for i in 0..c["node"].len() {
        let (area, pressure, traction) = (c["area"][i], c["pressure"][i], c["traction"][i]);
        if area > 0.0 && pressure.is_finite() {
            total += pressure * area;
        }
        if c["sliding"][i] == 1.0 {
            slid += 1;
            assert!(
                (traction - 0.3 * pressure).abs() <= 1e-6 * pressure,
                "point {i}: {traction} Pa against μ × {pressure} Pa"
            );
        }
    }
    assert!(slid >= 5, "{slid} sliding points (measured 9: the upper beam's end line)");
    assert!((total / normal - 1.0).abs() < 1e-6, "Σ pressure × area {total} against the normal resultant {normal}");
}

/// `examples/hertz_ball.toml`: a rigid ball (R = 10 mm) pressed δ = 0.05 mm
/// into a block with `method = "surface"` (exact closest point on the
/// sphere). Hertz (Johnson, *Contact Mechanics*, eqs. 4.22–4.23):
/// P = (4/3) E* √R δ^{3/2}, E* = E/(1 − ν²), on the quarter model P/4 at
/// each of the four increments (δ/4 … δ: the 3/2 power, not a linear
/// spring), and the peak pressure p₀ = 3P/(2πa²), a = √(Rδ), as −σ_zz at
/// the centre of the contact. Measured: force +1.9, +2.4, +1.6, +2.9 %,
/// σ_zz +3.6 % (the clamped 30 mm block is a little stiffer than the
/// half-space). Asserted 4 % and 5 %: a 10 % stiffness error or a wrong
/// radius (P ∝ √R) fails; a gap linearized at the start would not be
/// caught here (the surface hardly slides over the ball):
/// tests/rigid_surface.rs checks the exact gap under sliding.
#[test]
fn hertz_ball() {
    let s = run("hertz_ball");
    assert_eq!(s["dof"], 41013);
    let (e_star, r, delta) = (200e9 / (1.0 - 0.09), 0.01f64, 5e-5f64);
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_hertz_ball");
    let history = csv_columns(&out.join("history_ball.csv"));
    assert_eq!(history["lambda"].len(), 4);
    for (lambda, f_z) in history["lambda"].iter().zip(&history["f_z"]) {
        let d = lambda * delta;
        let hertz = 4.0 / 3.0 * e_star * r.sqrt() * d.powf(1.5) / 4.0;
        assert_within("hertz_ball.force", &format!("ball force at δ = {d:e} m vs Hertz"), -f_z, hertz, 0.04);
    }
    let p = 4.0 / 3.0 * e_star * r.sqrt() * delta.powf(1.5);
    let a2 = r * delta;
    let p0 = 3.0 * p / (2.0 * std::f64::consts::PI * a2);
    let centre = csv_columns(&out.join("line_surface_x.csv"))["s_zz"][0];
    assert_within("hertz_ball.s_zz_centre", "σ_zz at the contact centre vs −p₀", centre, -p0, 0.05);
}
