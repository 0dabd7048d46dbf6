//! The CalculiX cross-check of transient dynamics (issue 27): `cufem
//! verify` on a transient model runs one `*DYNAMIC` step per load step and
//! compares the displacement history at the probes. These tests need `ccx`
//! (Debian package `calculix-ccx`), like crates/cufem-cli/tests/ccx.rs, and fail — never
//! skip — without it.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::PathBuf;

use common::cufem;
use cufem::setup::Model;
use cufem_ccx::{self as ccx, HexKind};

fn scratch(name: &str) -> PathBuf {
    common::scratch_dir("ccx_dynamic", name)
}

/// The step-loaded bar of crates/cufem-cli/tests/dynamics.rs, coarsened: a 1 m steel rod,
/// 10 × 10 mm, ν = 0, fixed at y = 0 and held laterally everywhere, 50 B2;
/// 1 kN at its end risen in 1 ns, then held for one period 4L/c = 0.8 ms
/// in 200 time steps (c = √(E/ρ) = 5,000 m/s; Courant number 1).
fn bar() -> String {
    common::step_loaded_bar(50, 1000.0, 8e-4, 200, "")
}

/// `cufem verify --refine 1` on the bar (50 C3D20R, 1,824 DOF against
/// cufem's 612; about 2 s in all, ccx 1.8 s of it): the end's u_y history
/// within 2 % of the peak of CalculiX's (issue 27). The expected values are
/// CalculiX's own (ccx 2.20, `*DYNAMIC, DIRECT, ALPHA=0`, its consistent
/// mass), from `cufem verify MODEL --refine 1` on the model above:
/// measured end 0.88 %, middle 1.31 % (both just behind a corner of the
/// triangle wave, where the two meshes' dispersion differs most); CalculiX's
/// own peaks within 1.5 % of d'Alembert's `2FL/(EA)` = 0.1 mm at the end and
/// half of it in the middle (measured 0.098698 and 0.050612 mm). At refine 2
/// (9,063 DOF, ccx 10.4 s) the differences are 0.87 % and 1.17 %.
#[test]
fn verify_cross_checks_the_step_loaded_bar_history_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let out = common::verify(&scratch("bar"), "bar", &bar(), 1);
    // the deck: the density, two dynamic steps (1 ns in one increment, then
    // 200 of 4 µs), the trapezoidal rule, the load through its amplitude
    let deck = std::fs::read_to_string(out.join("verify/ccx/model.inp")).unwrap();
    assert!(deck.contains("*DENSITY\n8e3\n"), "{deck:.0}");
    assert_eq!(deck.matches("*DYNAMIC, DIRECT, ALPHA=0.\n").count(), 2);
    assert!(deck.contains("ALPHA=0.\n1.000000000000e-9, 1.000000000000e-9\n"));
    assert!(deck.contains("ALPHA=0.\n4.000000000000e-6, 8.000000000000e-4\n"));
    assert!(deck.contains("*AMPLITUDE, NAME=A_L_END, TIME=TOTAL TIME\n0.000000000000e0, 0.000000000000e0, 1.000000000000e-9, 1.000000000000e0, 8.000010000000e-4, 1.000000000000e0\n"));
    assert_eq!(deck.matches("*CLOAD, AMPLITUDE=A_L_END\n").count(), 2);
    assert!(!deck.contains("*STATIC") && !deck.contains("*FREQUENCY"));
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let rows = table["probe_histories"].as_array().unwrap();
    assert_eq!(rows.len(), 6, "{rows:?}");
    let row = |probe: &str, q: &str| rows.iter().find(|r| r["probe"] == probe && r["quantity"] == q).unwrap();
    // every increment of cufem's compared, CalculiX's at the same times
    let end = row("end", "u_y");
    assert_eq!(end["points"].as_u64(), Some(201), "{end}");
    let d = end["max_difference_percent"].as_f64().unwrap();
    assert!(d < 2.0, "end u_y: {d} % of CalculiX's peak {}", end["ccx_peak"]);
    // the 3D reference itself: d'Alembert's peak 2FL/(EA) = 0.1 mm
    for r in [end, row("middle", "u_y")] {
        let peak = r["ccx_peak"].as_f64().unwrap();
        let expected = if r["probe"] == "end" { 1e-4 } else { 0.5e-4 };
        assert!((peak / expected - 1.0).abs() < 0.015, "{r}");
    }
    // the restrained directions have no relative difference
    assert!(row("end", "u_x")["max_difference_percent"].is_null());
    // the static rows do not apply and are not written
    for key in ["probes", "lines", "resultants", "fields", "modes"] {
        assert!(table[key].as_array().unwrap().is_empty(), "{key}");
    }
    assert!(!out.join("verify/field_difference.vtu").exists());
    for f in ["probe_history_end.csv", "probe_history_end.png", "probe_history_middle.png", "table.txt"] {
        assert!(out.join("verify").join(f).exists(), "{f}");
    }
    let csv = std::fs::read_to_string(out.join("verify/probe_history_end.csv")).unwrap();
    assert!(csv.starts_with("lambda,t,u_x,u_y,u_z,ccx_u_x,ccx_u_y,ccx_u_z\n") && csv.lines().count() == 202);
    let table_csv = std::fs::read_to_string(out.join("verify/table.csv")).unwrap();
    assert!(table_csv.lines().any(|l| l.starts_with("probe_history,end,u_y,")), "{table_csv}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["verify"]["probe_histories"].as_array().map(Vec::len), Some(6));
}

/// Initial velocities and a load history of several steps become the deck:
/// `*INITIAL CONDITIONS` on the body's nodes, one amplitude through every
/// step end, each step's own increment (no ccx run).
#[test]
fn initial_velocities_and_the_load_history_become_the_deck() {
    let text = bar().replace(
        "type = \"transient\"",
        "type = \"transient\"\ninitial_velocities = [{ body = \"bar\", velocity = [0.0, -0.5, 0.0] }]",
    ) + "\n[[steps]]\nname = \"release\"\nfactor = 0.5\nduration = 2e-4\nincrements = 40\n";
    let model = Model::parse(&text).unwrap();
    let dir = scratch("deck");
    let (mesh, path) = ccx::export(&model, HexKind::C3D20R, 1, &dir).unwrap();
    let deck = std::fs::read_to_string(path).unwrap();
    let body_nodes = mesh.body_nodes(0).len();
    assert!(deck.contains("*INITIAL CONDITIONS, TYPE=VELOCITY\nV_BAR, 2, -5.000000000000e-1\n"), "{deck:.0}");
    let set = deck.split("*NSET, NSET=V_BAR\n").nth(1).unwrap().split('*').next().unwrap();
    assert_eq!(set.split(',').filter(|v| !v.trim().is_empty()).count(), body_nodes);
    assert!(deck.contains(
        "*AMPLITUDE, NAME=A_L_END, TIME=TOTAL TIME\n0.000000000000e0, 0.000000000000e0, 1.000000000000e-9, \
         1.000000000000e0, 8.000010000000e-4, 1.000000000000e0, 1.000001000000e-3, 5.000000000000e-1\n"
    ));
    assert!(deck.contains("*DYNAMIC, DIRECT, ALPHA=0.\n5.000000000000e-6, 2.000000000000e-4\n"));
    assert_eq!(deck.matches("*END STEP").count(), 3);
}

/// A transient model with an impactor moving off the axes, plasticity
/// with contact, another Newmark rule or damping has no exact twin:
/// refused by key before any file is written, and by `export-ccx` and
/// `verify` as invalid input (exit 1) before any analysis.
#[test]
fn a_transient_model_without_an_exact_twin_is_refused_by_key() {
    let wall = format!(
        "{}\n[[indenters]]\nname = \"wall\"\nbody = \"bar\"\nshape = \"flat\"\nsurface = {{ y = 1.0 }}\n\
         normal = \"-y\"\nposition = 1.00001\nmass = 1.0\nvelocity = [0.0, -1.0, 0.1]\n",
        bar()
    );
    let plastic = wall.replace("velocity = [0.0, -1.0, 0.1]", "velocity = [0.0, -1.0, 0.0]").replace(
        "density = 8000.0\n",
        "density = 8000.0\n[materials.plasticity]\nhardening = \"perfect\"\nyield_stress = 250e6\n",
    );
    let newmark =
        bar().replace("type = \"transient\"", "type = \"transient\"\nnewmark = { beta = 0.3025, gamma = 0.6 }");
    let damped = bar().replace("type = \"transient\"", "type = \"transient\"\ndamping = { mass = 10.0 }");
    let cases = [
        ("wall", &wall, "indenters[0].velocity: [0, -1, 0.1]", "a velocity along x, y or z"),
        ("plastic", &plastic, "materials[0].plasticity: material \"steel\"", "elastic materials"),
        ("newmark", &newmark, "analysis.newmark: beta = 0.3025, gamma = 0.6", "the default beta = 0.25, gamma = 0.5"),
        ("damped", &damped, "analysis.damping: mass = 10, stiffness = 0", "no damping"),
    ];
    for (name, text, key, allowed) in cases {
        let model = Model::parse(text).unwrap();
        let dir = scratch(name);
        let e = ccx::export(&model, HexKind::C3D20R, 1, &dir).unwrap_err().to_string();
        assert!(e.starts_with(key) && e.contains(allowed), "{name}: {e}");
        assert!(!dir.join("model.inp").exists(), "{name}: a deck was written");
    }
    let dir = scratch("cli");
    let model = dir.join("wall.toml");
    std::fs::write(&model, &wall).unwrap();
    for command in ["export-ccx", "verify"] {
        let out = dir.join(command);
        let run = cufem().args([command, model.to_str().unwrap(), "--out", out.to_str().unwrap()]).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{command}: {stderr}");
        assert!(stderr.contains("indenters[0].velocity") && stderr.contains("along x, y or z"), "{command}: {stderr}");
        assert!(!out.join("result.vtu").exists(), "{command}: analysed");
    }
}

/// A steel block (10 × 10 × 5 mm, 2 × 1 L9 × 2 B4, clamped at its base)
/// struck by a rigid flat plate of 0.1 kg at 1 m/s, 1 µm above it, 300 steps
/// of 0.2 µs (CalculiX's dynamic contact needs the small step:
/// `ccx::dynamic`), through `cufem verify --refine 1` (315 against 1,047
/// DOF; ccx about 20 s). The expected values are CalculiX's own (ccx 2.20,
/// `*DYNAMIC, DIRECT, ALPHA=0`, the plate's mass in its density):
/// measured the plate's motion within 0.91 % of the 3D peak (test 2 %), the
/// contact's impulse +0.11 % (test 2 %), the peak force −4.8 % (test 10 %:
/// the force rings at the contact nodes' frequencies, which differ between
/// the meshes).
///
/// The energy the plate leaves in the block, `½ m (v₀² − v²)` (CalculiX
/// 1.121 mJ, 2.2 % of the impact energy), is not matched: cufem's is
/// −19.6 % of it with the contact nodes massless (the default,
/// `dynamics::redistribution`: with one element through the block's
/// height the top row's share of the mass moves to mid-height, and the
/// block's vibration changes), +12.3 % with their mass kept (the same
/// CalculiX results, `--ccx-results`; the end-of-step contact impulse then
/// dissipates 0.38 mJ, the nodes stopping dead on the plate). Both are
/// asserted from both sides (docs/limitations.md), and so is the largest
/// difference of the top probe's u_z history under the ringing contact:
/// 25.4 % of the 3D peak (21.1 % with the nodes' mass kept). With Newmark's average
/// of the contact forces and the nodes' mass kept (`contact_forces =
/// "newmark"`, `contact_mass = "kept"`, tried by hand) the plate leaves
/// with 20 times its energy: motion 350 %, impulse +173 %.
#[test]
#[ignore = "validate: slow — an impact against CalculiX *DYNAMIC (about 40 s; CI keeps the step-loaded bar's history)"]
fn verify_cross_checks_an_impact_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let text = r#"title = "Steel block struck by a rigid plate"

[analysis]
type = "transient"

[solver]
max_increments = 5000

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
density = 7800.0

[[bodies]]
name = "block"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.01, elements = 2 }, z = { from = 0.0, to = 0.005, elements = 1 } }
axis = { element = "B4", from = 0.0, to = 0.01, elements = 2 }

[[constraints]]
name = "base"
body = "block"
where = { z = 0.0 }
fix = ["x", "y", "z"]

[[indenters]]
name = "plate"
body = "block"
shape = "flat"
surface = { z = 0.005 }
normal = "-z"
position = 0.005001
mass = 0.1
velocity = [0.0, 0.0, -1.0]

[[probes]]
name = "top"
point = [0.005, 0.005, 0.005]

[[steps]]
name = "impact"
factor = 1.0
duration = 6e-5
increments = 300
"#;
    let out = common::verify(&scratch("impact"), "impact", text, 1);
    // the deck: the plate's mass in its tool's density, its velocity on
    // every node of the tool, free along z only, its motion and contact
    // force printed
    let deck = std::fs::read_to_string(out.join("verify/ccx/model.inp")).unwrap();
    assert!(deck.contains("*MATERIAL, NAME=RIGID_PLATE\n") && deck.contains("*STEP, NLGEOM,"), "{deck:.0}");
    assert!(deck.contains("*INITIAL CONDITIONS, TYPE=VELOCITY\nV_PLATE, 3, -1.000000000000e0\n"));
    assert!(deck.contains("*CONTACT PRINT, SLAVE=SS_PLATE, MASTER=SM_PLATE\nCF\n"));
    assert!(!deck.contains("TYPE=MASS"));
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let rows = table["impacts"].as_array().unwrap();
    assert_eq!(rows.len(), 1, "{rows:?}");
    let r = &rows[0];
    let get = |k: &str| r[k].as_f64().unwrap();
    assert_eq!(r["points"].as_u64(), Some(300), "{r}");
    assert!(get("displacement_difference_percent") < 2.0, "{r}");
    assert!(get("impulse_difference_percent").abs() < 2.0, "{r}");
    assert!(get("peak_difference_percent").abs() < 10.0, "{r}");
    // the energy left in the block against CalculiX's, relative to itself:
    // the contact nodes massless (the default), then their mass kept, on
    // the same CalculiX results
    let absorbed = get("absorbed_difference_percent");
    println!("absorbed energy: {} against CalculiX's {} J, {absorbed:.2} %", r["absorbed"][0], r["absorbed"][1]);
    let what = "energy left in the block against CalculiX's";
    common::known_limit("ccx_dynamic.absorbed.redistributed", absorbed, "%", -22.0, -17.0, what);
    // the top probe's u_z, under the ringing contact: 25.4 % of the 3D peak
    // (21.1 % with the contact nodes' mass kept), asserted from both sides
    let top = |table: &serde_json::Value| {
        let rows = table["probe_histories"].as_array().unwrap();
        let r = rows.iter().find(|r| r["probe"] == "top" && r["quantity"] == "u_z").unwrap();
        r["max_difference_percent"].as_f64().unwrap()
    };
    let probe = top(&table);
    let what = "the top probe's u_z history against CalculiX's, % of its peak";
    common::known_limit("ccx_dynamic.probe_history.redistributed", probe, "%", 23.0, 28.0, what);
    let kept = text.replace("type = \"transient\"\n", "type = \"transient\"\ncontact_mass = \"kept\"\n");
    let dir = scratch("impact_kept");
    std::fs::write(dir.join("kept.toml"), &kept).unwrap();
    let (model, ccx_dir, out_kept) = (dir.join("kept.toml"), out.join("verify/ccx"), dir.join("out"));
    let run = cufem()
        .args(["verify", model.to_str().unwrap(), "--out", out_kept.to_str().unwrap(), "--refine", "1", "--quiet"])
        .args(["--ccx-results", ccx_dir.to_str().unwrap(), "--force"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_kept.join("verify/table.json")).unwrap()).unwrap();
    let kept = &table["impacts"][0];
    let absorbed = kept["absorbed_difference_percent"].as_f64().unwrap();
    println!("the contact nodes' mass kept: absorbed {} J, {absorbed:.2} %", kept["absorbed"][0]);
    let what = "energy left in the block against CalculiX's, the contact nodes' mass kept";
    common::known_limit("ccx_dynamic.absorbed.kept", absorbed, "%", 10.0, 15.0, what);
    let probe = top(&table);
    let what = "the top probe's u_z history, the contact nodes' mass kept";
    common::known_limit("ccx_dynamic.probe_history.kept", probe, "%", 18.5, 23.5, what);
    // the 3D reference itself: the plate's impulse is m (v0 − v_end), with
    // the rebound close to v0 (an elastic block keeps 2.2 % of the energy in CalculiX)
    let impulse = r["impulses"][1].as_f64().unwrap();
    assert!((impulse / 0.2 - 1.0).abs() < 0.02, "{r}");
    for f in ["impact_plate.csv", "impact_plate_ccx.csv", "impact_plate.png"] {
        assert!(out.join("verify").join(f).exists(), "{f}");
    }
}
