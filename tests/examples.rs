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
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{name}.toml"));
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
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
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

fn assert_within(name: &str, what: &str, value: f64, reference: f64, relative: f64) {
    let err = (value - reference).abs() / reference.abs();
    eprintln!("{name}: {what} = {value:.4e} (reference {reference:.4e}, {:.1} %)", 100.0 * err);
    assert!(
        err <= relative,
        "{name}: {what} = {value:e} is {:.1} % from {reference:e} (allowed {:.0} %)",
        100.0 * err,
        100.0 * relative
    );
}

/// The numeric columns of a CSV file that cufem wrote, by header name.
fn csv_columns(path: &Path) -> std::collections::HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); header.len()];
    for line in lines {
        for (c, v) in columns.iter_mut().zip(line.split(',')) {
            c.push(v.parse().unwrap());
        }
    }
    header.into_iter().map(String::from).zip(columns).collect()
}

/// σ_zz along the top line (`line_top.csv` of a run), as (x, σ_zz, peeq).
fn top_line(out: &Path) -> Vec<[f64; 3]> {
    let c = csv_columns(&out.join("line_top.csv"));
    (0..c["x"].len()).map(|i| [c["x"][i], c["s_zz"][i], c["peeq"][i]]).collect()
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
    assert_within("block", "punch force vs CalculiX", vec3(&punch["force"])[2], BLOCK_FORCE_3D, 0.02);
    // σ_zz rises monotonically from the edge region to the centre, as in 3D:
    // no plateaus and jumps, no oscillation. Measured: largest reversal
    // 2.2 MPa, 0.7 % of the 3D peak; asserted 2 % (the paper's element:
    // 65 MPa, test below).
    let reversal = largest_reversal(&top_line(&out));
    assert!(reversal < 0.02 * BLOCK_SZZ_PEAK_3D, "σ_zz reversal under the punch {reversal:e} Pa");
    // The paper's own models give 0.0404–0.0658 at the punch edge (ABAQUS
    // coarse to fine, CUF): its mesh dependence. We ask for that range ±25 %
    // of its top (a singular point: 3D gives 0.19 there; measured 0.0755).
    let peeq = probe(&s, "edge", "peeq");
    assert!((0.0404 - 0.25 * 0.0658..=0.0658 * 1.25).contains(&peeq), "peeq {peeq}");
}

/// Regression guard, not a validation: the block's elastic stiffness on the
/// shipped mesh against cufem's own refined model (36 × 12 section
/// elements, 2 B4; 38,325 DOF: 266,215 N at the first increment, 0.05 mm;
/// the shipped mesh measured 265,252 N, 0.4 % softer). It guards the
/// element stiffness of the B-bar element and the punch contact against a
/// change of more than 2 %; the independent checks of the same example are
/// the CalculiX force and σ_zz above.
#[test]
fn regression_block_indentation_first_increment_force() {
    let _ = run("block_indentation");
    assert_eq!(first_increment("block_indentation", "punch").0, 0.0, "the first increment is elastic");
    assert_first_force("block_indentation", "punch", -266_215.0, 0.02);
}

/// The block with the paper's displacement-based element and element-wise
/// recovery (the example without its two issue-8 lines): volumetric locking
/// in the confined plastic flow under the punch. Measured: punch force
/// +8.0 % above the 3D model and a σ_zz reversal of 65 MPa under the punch
/// (plateaus joined by jumps). This is why the example ships B-bar; the test
/// fails if `formulation` or `recovery` stopped being honoured.
#[test]
fn block_indentation_paper_element_locks() {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/block_indentation.toml"))
        .unwrap()
        .replace("formulation = \"bbar\"\n", "")
        .replace("recovery = \"projection\"\n", "");
    assert!(!text.contains("formulation = \"bbar\"\n") && !text.contains("recovery = \"projection\"\n"));
    let (s, out) = run_text("block_standard", &text);
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    let excess = vec3(&punch["force"])[2] / BLOCK_FORCE_3D - 1.0;
    assert!((0.05..0.11).contains(&excess), "punch force {:+.1} % vs CalculiX", 100.0 * excess);
    let reversal = largest_reversal(&top_line(&out));
    assert!(reversal > 0.1 * BLOCK_SZZ_PEAK_3D, "σ_zz reversal under the punch {reversal:e} Pa");
}

/// The indentation test (issue 10): the block example loaded to 1 mm and
/// unloaded. The punch ends free of force, the dent stays (residual depth
/// between 0 and the 1 mm pushed: measured 0.710 mm at the centre, the
/// springback 0.29 mm), and every step has its results.
#[test]
fn block_indentation_unload() {
    let s = run("block_indentation_unload");
    let steps = s["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2);
    let punch = |step: &Value| {
        vec3(&step["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap()["force"])[2]
    };
    // equilibrium of the loaded state (at the end everything is zero)
    let bottom = vec3(&steps[0]["reactions"].as_array().unwrap()[0]["force"])[2];
    assert!((bottom + punch(&steps[0])).abs() < 1e-6 * bottom.abs(), "loaded balance {bottom:e}");
    // loaded: the block example's force (same model and increments)
    assert_within("block_indentation_unload", "loaded punch force vs CalculiX", punch(&steps[0]), BLOCK_FORCE_3D, 0.02);
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
    assert_within("bending_tube_springback", "unloading slope vs elastic stiffness", k_unload, k_elastic, 0.01);
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
/// line, where a node-to-node contact concentrates the load.
fn compact(name: &str, dof: u64, paper_syy: f64, paper_peeq: f64) {
    let s = run(name);
    assert_eq!(s["dof"], dof);
    assert_equilibrium(name, &s);
    // σ_yy at the contact centre: bending-dominated; the paper's own models
    // span −38.8 to −49.8 MPa (±12 % around their mean). 20 %.
    assert_within(name, "σ_yy at the contact centre", probe(&s, "contact_centre", "s_yy"), paper_syy, 0.20);
    // peeq there is a local contact quantity, set by the unknown load
    // introduction (span: force ∝ span⁻³ at fixed deflection; roller size):
    // we obtain about half the paper's value. Only the order of magnitude is
    // checked (a factor 2.5), and the gap is reported in the README.
    let peeq = probe(&s, "contact_centre", "peeq");
    eprintln!("{name}: peeq {peeq:.3e} vs paper {paper_peeq:.3e}");
    assert!(peeq > paper_peeq / 2.5 && peeq < paper_peeq * 2.5);
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

/// Regression guard: the indenter force of the first increment (elastic,
/// or with a few plastic points right under a roller) against the same
/// increment of cufem's own refined model (each section and axis division
/// doubled, or the ring refined from 20 to 36 elements). The reference is
/// nearer the converged stiffness but not independent of the code;
/// `tolerance` covers the measured discretization difference with room to
/// spare, while a 10 % error in the element stiffness does not fit in it.
fn assert_first_force(name: &str, indenter: &str, refined: f64, tolerance: f64) {
    let (_, _, force) = first_increment(name, indenter);
    assert_within(name, &format!("first-increment force of {indenter} vs refined CUF"), force, refined, tolerance);
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
    assert_within(name, "elastic roller force vs Timoshenko", force, delta / compliance, 0.02);
}

#[test]
fn bending_compact_4l9() {
    compact("bending_compact_4L9", 2325, -45.30e6, 1.89e-3);
    assert_elastic_bending_stiffness("bending_compact_4L9");
}

#[test]
fn bending_compact_16l9() {
    compact("bending_compact_16L9", 7533, -49.75e6, 1.98e-3);
    assert_elastic_bending_stiffness("bending_compact_16L9");
}

/// §4.2, Tables 4 and 6: thin-walled tube. As for the compact bar, plus the
/// ring mesh (Fig. 13) is assumed. The probe is at mid-width of the top wall
/// under the roller, where the wall bends locally (in our model it lifts off
/// the roller by ~0.02 mm): the paper's models spread from −38.7 to −60.6 MPa
/// (σ_yy) and 2.1e-3 to 8.4e-3 (peeq) at this point. 30 % on σ_yy, a
/// factor 2 on peeq.
fn tube(name: &str, dof: u64, paper_syy: f64, paper_peeq: f64) -> Value {
    let s = run(name);
    assert_eq!(s["dof"], dof);
    assert_equilibrium(name, &s);
    assert_within(name, "σ_yy at the contact centre", probe(&s, "contact_centre", "s_yy"), paper_syy, 0.30);
    let peeq = probe(&s, "contact_centre", "peeq");
    eprintln!("{name}: peeq {peeq:.3e} vs paper {paper_peeq:.3e}");
    assert!(peeq > paper_peeq / 2.0 && peeq < paper_peeq * 2.0);
    s
}

#[test]
fn bending_tube_20l9() {
    let _ = tube("bending_tube_20L9", 24120, -51.50e6, 7.76e-3);
}

/// Regression guard, not a validation: the tube's roller force at the
/// first increment against cufem's own refined model (36 L9 around the
/// ring, 44 B4; 86,184 DOF: 342.1 N at 0.05 mm, 28 Gauss points already
/// yielding under the roller); the 20-element ring is 3.5 % stiffer (the
/// wall bends under the roller), hence 5 %. It guards the thin-wall bending
/// stiffness and the roller contact of the shipped mesh; the independent
/// checks are the paper's σ_yy and peeq in `tube` and the 3D comparison
/// (docs/cross-check.md).
#[test]
fn regression_bending_tube_20l9_first_increment_force() {
    let _ = run("bending_tube_20L9");
    assert_first_force("bending_tube_20L9", "load", -342.12, 0.05);
}

#[test]
fn bending_tube_28l9() {
    let s = tube("bending_tube_28L9", 33768, -60.60e6, 8.38e-3);
    // 3D reference: `cufem verify examples/bending_tube_28L9.toml --refine 1`
    // (CalculiX 2.20, C3D20R, 123,312 DOF, same quarter model): loading
    // roller 1,698.2 N. Measured −3.45 %; 5 %: node-to-node against surface
    // contact on a wall of one L9 through the thickness.
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    assert_within("bending_tube_28L9", "roller force vs CalculiX", vec3(&load["force"])[2], -1698.2, 0.05);
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
    // contact). 5 %: node-to-node against surface contact on a 3.7× coarser
    // model; measured 1.9 % (7 in roller), 2.5 % and 3.6 % (roots).
    let force = |name: &str| {
        let c = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == name).unwrap();
        vec3(&c["force"])[2]
    };
    let reaction = |name: &str| {
        let r = s["reactions"].as_array().unwrap().iter().find(|r| r["name"] == name).unwrap();
        vec3(&r["force"])[2]
    };
    assert_within("cantilevers", "7 in roller force vs CalculiX", force("indenter_7in"), -25_769.0, 0.05);
    assert_within("cantilevers", "upper root reaction vs CalculiX", reaction("upper_root"), 12_619.0, 0.05);
    assert_within("cantilevers", "lower root reaction vs CalculiX", reaction("lower_root"), 16_087.0, 0.05);
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
    assert_within("punch_plane_strain", "mean punch pressure vs Prandtl", pressure, prandtl, 0.03);
    // measured −0.2 %
    assert_within("punch_plane_strain", "σ_zz at the centre vs Prandtl", probe(&s, "centre", "s_zz"), prandtl, 0.03);
    // the profile under the punch, away from the edge elements: flat at
    // Prandtl's pressure within 3 % (measured −294…−301 MPa); no plateaus and
    // jumps, no oscillation between neighbouring stations
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_punch_plane_strain");
    let csv = std::fs::read_to_string(out.join("line_top.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let (ix, izz) = (header.iter().position(|h| *h == "x").unwrap(), header.iter().position(|h| *h == "s_zz").unwrap());
    for line in csv.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        if (0.455..=0.545).contains(&f[ix]) {
            assert_within("punch_plane_strain", &format!("σ_zz at x = {}", f[ix]), f[izz], prandtl, 0.03);
        }
    }
}

/// Issue 8's field check (long: about 5 min; `cargo test --release --test
/// examples -- --ignored`). The block example (B-bar, projected fields) on
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
#[ignore]
fn block_refined_fields_match_calculix() {
    let table = |text: &str| -> Vec<Vec<f64>> {
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with(|c: char| c.is_alphabetic()))
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    let reference = table(include_str!("data/block_calculix_top.csv"));
    let mut lines = Vec::new();
    for (axis, dof) in [(3, 54750), (4, 71175)] {
        let name = format!("block_refined_{axis}B4");
        let text =
            std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/block_indentation.toml"))
                .unwrap()
                .replace("elements = 6, ratio", "elements = 12, ratio")
                .replace("{ from = 0.2, to = 0.3, elements = 6 }", "{ from = 0.2, to = 0.3, elements = 12 }")
                .replace("to = 0.1, elements = 1 }", &format!("to = 0.1, elements = {axis} }}"));
        let (s, out) = run_text(&name, &text);
        assert_eq!(s["dof"], dof);
        let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
        assert_within(&name, "punch force vs CalculiX", vec3(&punch["force"])[2], BLOCK_FORCE_3D, 0.02);
        let ours = top_line(&out);
        assert!(
            largest_reversal(&ours) < 0.02 * BLOCK_SZZ_PEAK_3D,
            "{name}: σ_zz reversal {:e} Pa",
            largest_reversal(&ours)
        );
        for (k, q) in [(1, "s_zz"), (2, "peeq")] {
            let peak = reference.iter().map(|r| r[k].abs()).fold(0.0f64, f64::max);
            for (r, o) in reference.iter().zip(&ours) {
                assert!((r[0] - o[0]).abs() < 1e-9, "stations differ");
                if (0.21 - 1e-9..=0.29 + 1e-9).contains(&r[0]) {
                    let d = (o[k] - r[k]).abs() / peak;
                    assert!(
                        d < 0.10,
                        "{name}: {q} at x = {}: cufem {:e}, 3D {:e} ({:.1} % of the 3D peak)",
                        r[0],
                        o[k],
                        r[k],
                        100.0 * d
                    );
                }
            }
        }
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
    assert_within(name, "first-increment roller force vs Timoshenko", force / delta, 1.0 / ibeam_compliance(), 0.05);
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
    assert_within(name, "roller force vs CalculiX", vec3(&load["force"])[2], -8554.2, 0.03);
}

/// The same beam elastic (no plasticity, one increment): the deflection of
/// the web's mid-height at mid-span relative to that above a support
/// leaves out the local indentation, and the beam's stiffness matches
/// Timoshenko: measured 0.85 % stiffer. Shear is 15 % of the compliance
/// and Cowper's k is itself approximate for a thin-walled I (the web area
/// h t_w as shear area makes the theory 1.4 % stiffer than with k); 2 %.
#[test]
fn ibeam_roller_elastic_matches_timoshenko() {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/ibeam_roller.toml")).unwrap();
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
        "ibeam_roller_elastic",
        "beam stiffness (web mid-height) vs Timoshenko",
        force / deflection,
        1.0 / ibeam_compliance(),
        0.02,
    );
}

/// The two cantilevers with Coulomb friction μ = 0.3 between the beams
/// (issue 9, item 5; node-to-node contact, GMRES on the unsymmetric
/// tangent). Coulomb's law bounds
/// the tangential resultant of the interface by μ times its normal
/// resultant; the interface slides wherever it touches here (measured:
/// 5.31 kN against 0.300 × 17.68 kN), so the bound is met with equality to
/// within the elastic-slip regularisation (asserted: between 0.29 and
/// 0.3 (1 + 1e-9) times the normal force). Friction resists the beams'
/// relative sliding, so the structure is stiffer than without it: the 7 in
/// roller force must exceed the frictionless example's (26.25 kN; measured
/// +3.6 %).
#[test]
fn cantilevers_contact_friction() {
    let s = run("cantilevers_contact_friction");
    assert_eq!(s["dof"], 15066);
    assert_equilibrium("cantilevers with friction", &s);
    let (normal, tangential) = interface_forces(&s);
    eprintln!("friction cantilevers: interface normal {normal:.1} N, tangential {tangential:.1} N");
    assert!(normal > 0.0 && tangential <= 0.3 * normal * (1.0 + 1e-9), "{tangential} vs μN = {}", 0.3 * normal);
    assert!(tangential >= 0.29 * normal, "interface not sliding: {tangential} vs {normal}");
    let roller = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "indenter_7in").unwrap();
    let f7 = -vec3(&roller["force"])[2];
    assert!(f7 > 26_248.0 && f7 < 26_248.0 * 1.10, "7 in roller {f7} N (frictionless 26,248 N)");
}

/// The two cantilevers on non-matching meshes (surface contact) with
/// Coulomb friction μ = 0.3 (issue 9, item 5). Coulomb bounds the
/// interface's tangential resultant by μ N and it slides wherever it
/// touches (measured 5.03 kN = 0.300 × 16.78 kN; asserted 0.29–0.3 μN as
/// for the matching mesh). Independent check of the friction's effect:
/// on the matching mesh with node-to-node contact (examples
/// cantilevers_contact and cantilevers_contact_friction, both run by this
/// file) friction raises the 7 in roller force by 3.6 % and the interface
/// normal force by 6.1 %; on the non-matching mesh the same friction must
/// do the same to within one percentage point, against the frictionless
/// non-matching run (27,866 N and 15,838 N: examples/
/// cantilevers_contact_nonmatching.toml, `cufem run`, and the header of
/// that file). Measured +3.4 % and +6.0 %. Dropping the unsymmetric
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
    let roller = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "indenter_7in").unwrap();
    let f7 = -vec3(&roller["force"])[2];
    let rise7 = f7 / 27_866.0 - 1.0;
    let rise_n = normal / 15_838.0 - 1.0;
    eprintln!(
        "friction effect on the non-matching mesh: 7 in roller {:+.2} %, interface normal {:+.2} %",
        100.0 * rise7,
        100.0 * rise_n
    );
    assert!((rise7 - 0.036).abs() < 0.01, "7 in roller rises {rise7} with friction (matching mesh: +3.6 %)");
    assert!((rise_n - 0.061).abs() < 0.01, "interface normal force rises {rise_n} (matching mesh: +6.1 %)");
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
        assert_within("hertz_ball", &format!("ball force at δ = {d:e} m vs Hertz"), -f_z, hertz, 0.04);
    }
    let p = 4.0 / 3.0 * e_star * r.sqrt() * delta.powf(1.5);
    let a2 = r * delta;
    let p0 = 3.0 * p / (2.0 * std::f64::consts::PI * a2);
    let centre = csv_columns(&out.join("line_surface_x.csv"))["s_zz"][0];
    assert_within("hertz_ball", "σ_zz at the contact centre vs −p₀", centre, -p0, 0.05);
}
