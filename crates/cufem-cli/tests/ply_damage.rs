//! Progressive ply damage in a body (issue 48): the notched strip of
//! `examples/notched_strip_{coarse,medium,fine}.toml` (a crack from a notch
//! across a 4.8 mm ligament of a 1 mm deep IM7/8552-like strip in fibre tension,
//! written by `examples/sections/notched_strip.py`) against the crack band's
//! promise (Bažant & Oh 1983): the energy dissipated is `G_FT` times the
//! cracked area whatever the element size; the energy balance of the run;
//! a damaged strip unloaded and reloaded follows its damaged secant; and the
//! model file's refusals.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

/// The example `name`'s text.
fn example(name: &str) -> String {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(format!("examples/{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

/// Runs a model text through the CLI: the output folder and the summary;
/// the run must reach its end.
fn run_cli(name: &str, text: &str) -> (PathBuf, Value) {
    common::run_text("ply_damage", name, text)
}

/// The energy each mode dissipated (J), in the order of `damage.modes`.
fn dissipated(summary: &Value) -> [f64; 4] {
    let d = &summary["damage"]["dissipated_j"];
    ["fibre_tension", "fibre_compression", "matrix_tension", "matrix_compression"].map(|m| d[m].as_f64().unwrap())
}

/// The pull's history: `(u_x, r_x)` per converged increment, from the
/// unloaded start.
fn pull(out: &Path) -> Vec<(f64, f64)> {
    let c = common::csv_columns(&out.join("history_pull.csv"));
    std::iter::once((0.0, 0.0)).chain(c["u_x"].iter().copied().zip(c["r_x"].iter().copied())).collect()
}

/// `∫ F du` of a force–displacement path by the trapezoidal rule (J).
fn work(path: &[(f64, f64)]) -> f64 {
    path.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum()
}

/// The nose's path of the three-point bend in `out`: `(−d_z, −f_z)` per
/// converged increment, from the unloaded start.
fn nose(out: &Path) -> Vec<(f64, f64)> {
    let c = common::csv_columns(&out.join("history_nose.csv"));
    std::iter::once((0.0, 0.0)).chain(c["d_z"].iter().zip(&c["f_z"]).map(|(&u, &f)| (-u, -f))).collect()
}

/// `(the law's sums, the release at fixed strain)` of a summary's damage (J).
fn sums_and_release(summary: &Value) -> (f64, f64) {
    let d = &summary["damage"];
    (d["dissipated_total_j"].as_f64().unwrap(), d["released_total_j"].as_f64().unwrap())
}

/// `G_FT × ligament × depth` = 133.3e3 J/m² × 4.8 mm × 1 mm (the examples'
/// constants).
const CRACK_ENERGY: f64 = 133.3e3 * 4.8e-3 * 1.0e-3;

/// A known limit (docs/limitations.md "Ply damage"): the fibre crack starts
/// at the notch root in the notch's column, but does not cross the
/// ligament there — it turns into the wider columns towards the pulled end
/// (held flat, so the eccentric ligament bends the strip) and crosses to
/// the far edge in another one. Measured (cells past half damage, `d_ft`):
/// coarse 2 rows in the notch column, across at x = 4.2 mm; medium 5 rows,
/// across at 3.9 mm; fine 9 rows, across at 3.5 mm. The band's energy
/// counts each column the crack steps through.
fn crack_leaves_the_notch_column(result: &Path, mesh: &str) {
    let h = match mesh {
        "coarse" => 0.8e-3,
        "medium" => 0.4e-3,
        _ => 0.2e-3,
    };
    let (column, notch, width) = ((2.0e-3, 2.0e-3 + h), 1.6e-3, 6.4e-3);
    let cells = common::cells_past_half(result, "d_ft");
    let inside: Vec<f64> = cells.iter().filter(|c| c.0 > column.0 && c.0 < column.1).map(|c| c.1).collect();
    assert!(inside.iter().any(|&z| z < notch + h), "{mesh}: the crack starts at the notch root: {cells:?}");
    assert!(inside.iter().all(|&z| z < width - h), "{mesh}: it does not cross in the notch's column: {cells:?}");
    assert!(cells.iter().any(|c| c.0 > column.1 && c.1 > width - h), "{mesh}: it crosses elsewhere: {cells:?}");
}

/// One mesh of the notched strip: the energy it dissipates in fibre
/// tension over `G_FT` × the ligament (returned), the other modes under
/// `1 %` of the total, and the balance `∫ P du = D + E_el` within `1 %`, with
/// `E_el = ½ P u` at the end (the damaged body is secant-linear through the
/// origin: Clapeyron; measured within 0.02 %).
fn strip_energy_ratio(mesh: &str) -> f64 {
    let name = format!("notched_strip_{mesh}");
    let (out, summary) = run_cli(&name, &example(&name));
    let d = dissipated(&summary);
    let total: f64 = d.iter().sum();
    let ratio = d[0] / CRACK_ENERGY;
    // a damaging run's end stresses are the softened ones: no first-failure
    // load factor from them (one was printed; a new-user review), the end
    // state's indices kept
    for c in summary["ply_failure"]["criteria"].as_array().unwrap() {
        // nor a place of that first failure (it was given beside the null)
        assert!(c["first_failure_load_factor"].is_null() && c["first_failure_at"].is_null(), "{c}");
        assert!(c["largest_index"].as_f64().unwrap() > 0.0 && c["largest_at"]["point"].is_array(), "{c}");
        // and no point holds a stress the law would not let it hold: the
        // law keeps each point on or inside its Hashin onset surface (index
        // 1), the viscosity's lag a little outside. The fields took the
        // intact stiffness times the strain of the softened band and gave
        // indices of hundreds at the crack (coarse: 17, 537, 292 for max
        // stress, Tsai–Wu, Hashin fibre); measured 0.74–1.05 over the
        // three meshes since they take the Gauss points' stresses there
        let largest = c["largest_index"].as_f64().unwrap();
        assert!(largest < 1.5, "{mesh}: {} {largest} at {}", c["criterion"], c["largest_at"]["point"]);
    }
    println!("{mesh}: D = {d:?} J, D_FT/(G A) = {ratio:.4}");
    // only fibre tension cracks the ligament: the others under 1 % of D
    assert!(d[1..].iter().all(|&x| x < 0.01 * total), "{mesh}: {d:?}");
    // the energy balance: the work of the pull is what the damage
    // dissipated plus what the strip stores at the end
    let curve = pull(&out);
    let work = work(&curve);
    let (u, p) = *curve.last().unwrap();
    let stored = 0.5 * p * u;
    let balance = (work - total - stored) / work;
    println!("{mesh}: work {work:.5} J, stored {stored:.5} J, balance {balance:.2e}");
    assert!(balance.abs() < 0.01, "{mesh}: work {work} J, dissipated {total} J, stored {stored} J");
    // its increments follow the damage: the release at fixed strain within
    // 2 % of the law's sums (measured 0.990 coarse, 0.990 medium), no warning
    let released = summary["damage"]["released_total_j"].as_f64().unwrap();
    assert!((0.98..=1.0).contains(&(released / total)), "{mesh}: released {released} J of {total} J");
    assert!(!summary["warnings"].to_string().contains("released at fixed strain"), "{}", summary["warnings"]);
    crack_leaves_the_notch_column(&out.join("result.vtu"), mesh);
    // G_FT × area and a known excess of 6–7 % (measured 1.065, 1.061, 1.071
    // on the three meshes; 1.068 on the coarse one without viscosity, 1.056
    // with fibre_shear = 0: mostly the crack's steps through the columns
    // above, a little the law's onset mixity; docs/limitations.md "Ply
    // damage"), asserted from both sides
    assert!((1.04..1.09).contains(&ratio), "{mesh}: D_FT/(G_FT A) = {ratio}");
    ratio
}

/// A new user's three-point bend of a `[0/90]s` beam with ply damage and
/// cohesive interfaces, pressed `2 mm` by a cylinder in `20` increments
/// (a new-user review): the plies under the nose crush in matrix
/// compression. Increments that coarse do not follow the crushing: the
/// path is the one of finer steps only until the first load drop. At
/// `Δλ = 2.5e-3` (400 increments) the nose's force peaks at `336` N
/// (λ = 0.3), holds about `230` N and falls to `26` N at λ ≈ 0.64, with
/// the secant or the consistent tangent alike (the law's sums `0.2321`
/// and `0.2312` J); there the balance closes: the law's sums plus the end
/// state's `½ P u` (Clapeyron: the damaged beam is secant-linear) are
/// `1.004` of the nose's `0.270` J of work. With 20 increments the crushed
/// points jump far within an increment: the law's sums of `Y Δd` follow
/// each update's straight strain path (`materials::damage_dissipation`),
/// `0.434` J of `0.489` J of work, the balance `0.948`; one trapezoid per
/// update booked past the work (the review). The release at fixed
/// strain, `released_j`, a lower bound, is `0.227` J, and the run warns
/// that the increments do not follow the damage. Steered by it
/// (`solver.step_control = { damage = 0.1 }`) the two agree within `10 %`
/// (`0.142` and `0.130` J), but that run stops at λ = `0.68`, Newton
/// cycling there with steps of `1e-5` (exit 2).
/// The figures of docs/limitations.md "Ply damage", each held within 3 %.
#[test]
fn a_crushed_ply_s_dissipation_is_not_booked_past_the_work() {
    let near = |x: f64, measured: f64| (x / measured - 1.0).abs() < 0.03;
    let (out, summary) = run_cli("tpb_crushed", TPB);
    let done = work(&nose(&out));
    let (sums, released) = sums_and_release(&summary);
    println!("work {done:.4} J, the law's sums {sums:.4} J, released at fixed strain {released:.4} J");
    assert!(released > 0.0 && released < done, "released {released} J, work {done} J");
    // measured 0.4342 J and 0.2265 J (1.9 times) of 0.4892 J of work
    assert!(sums < done, "the law's sums {sums} J past the work {done} J");
    assert!(near(done, 0.4892) && near(1e3 * sums, 434.2) && near(released, 0.2265), "{done} {sums} {released}");
    // the balance: the work is what the damage dissipated plus what the
    // beam holds at the end, ½ P u of the nose; measured 0.948 of the work
    let (u, p) = *nose(&out).last().unwrap();
    let balance = (sums + 0.5 * p * u) / done;
    println!("(D + ½ P u) / W = {balance:.4}");
    assert!(near(balance, 0.948), "{balance}");
    // the fine steps' path, where the balance closes within 1 %
    assert!(TPB.contains("increments = 20\n"));
    let fine = TPB.replace("increments = 20\n", "increments = 400\nmax_increment = 0.0025\n");
    let (fine_out, fine_summary) =
        run_cli("tpb_crushed_fine", &fine.replace("max_increments = 400\n", "max_increments = 4000\n"));
    let fine_work = work(&nose(&fine_out));
    let (fine_sums, _) = sums_and_release(&fine_summary);
    let (u, p) = *nose(&fine_out).last().unwrap();
    let fine_balance = (fine_sums + 0.5 * p * u) / fine_work;
    println!("fine steps: work {fine_work:.4} J, the law's sums {fine_sums:.4} J, (D + ½ P u) / W = {fine_balance:.4}");
    assert!((fine_balance - 1.0).abs() < 0.01, "{fine_balance}");
    assert!(near(fine_work, 0.2698) && near(fine_sums, 0.2312), "{fine_work} {fine_sums}");
    // the failure indices of its fields: the crushed plies' softened
    // stresses, not the intact stiffness times their strain, which showed
    // a Tsai–Wu index of 95,887 at the support line (the review's "1e4–1e5
    // at line supports"); measured at most 0.27 since
    for c in summary["ply_failure"]["criteria"].as_array().unwrap() {
        let largest = c["largest_index"].as_f64().unwrap();
        assert!(largest < 1.5, "{} {largest} at {}", c["criterion"], c["largest_at"]["point"]);
    }
    let warnings = summary["warnings"].to_string();
    assert!(warnings.contains("is 1.9 times the energy it released at fixed strain"), "{warnings}");
    assert!(warnings.contains("solver.step_control = { damage = 0.1 }"), "{warnings}");
    // steered by the damage: the two within 10 %, the run stopping early
    assert!(TPB.contains("max_increments = 400\n"));
    let steered = TPB.replace("max_increments = 400\n", "max_increments = 4000\nstep_control = { damage = 0.1 }\n");
    let dir = common::scratch_dir("ply_damage", "tpb_steered");
    std::fs::write(dir.join("m.toml"), steered).unwrap();
    let run = common::cufem()
        .args(["run", dir.join("m.toml").to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2), "{}", String::from_utf8_lossy(&run.stderr));
    let s: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap();
    let (sums, released) = sums_and_release(&s);
    let lambda = s["load_factor"].as_f64().unwrap();
    println!("steered: the law's sums {sums:.4} J, released {released:.4} J, stopped at λ = {lambda:.4}");
    let steered_work = work(&nose(&dir.join("out")));
    assert!(sums / released < 1.1 && sums < steered_work, "{sums} / {released}, work {steered_work}");
    assert!(near(sums, 0.1423) && near(released, 0.1301) && near(lambda, 0.6815), "{sums} {released} {lambda}");
}

/// The same beam without the damage's viscosity stops past its peak, its
/// residuals cycling; the stop message names the viscosity that lets
/// Newton pass (a new-user review: it said only that Newton did not
/// converge).
#[test]
fn a_damage_stop_without_viscosity_names_the_viscosity() {
    assert!(TPB.contains("matrix_compression = 800.0, viscosity = 1e-3 }"));
    let text = TPB.replace("matrix_compression = 800.0, viscosity = 1e-3 }", "matrix_compression = 800.0 }");
    let dir = common::scratch_dir("ply_damage", "tpb_no_viscosity");
    let model = dir.join("m.toml");
    std::fs::write(&model, text).unwrap();
    let run = common::cufem()
        .args(["run", model.to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("materials[0].damage has no viscosity: past a damage peak Newton cycles"), "{stderr}");
}

/// The model of [`a_crushed_ply_s_dissipation_is_not_booked_past_the_work`].
const TPB: &str = r#"title = "My [0/90]s three-point bend with ply damage and cohesive interfaces"

[solver]
increments = 20
max_increments = 400

[[materials]]
name = "cfrp"
orthotropic = { e1 = 140e9, e2 = 9e9, e3 = 9e9, g12 = 5e9, g13 = 5e9, g23 = 3.2e9, nu12 = 0.3, nu13 = 0.3, nu23 = 0.4 }
strengths = { xt = 1500e6, xc = 1200e6, yt = 50e6, yc = 200e6, s12 = 80e6, s23 = 60e6 }
damage = { fibre_tension = 80e3, fibre_compression = 60e3, matrix_tension = 300.0, matrix_compression = 800.0, viscosity = 1e-3 }

[[materials]]
name = "coh"
cohesive = { gic = 300.0, giic = 800.0, bk_exponent = 2.0, normal_strength = 30e6, shear_strength = 49e6, viscosity = 1e-4 }

[[bodies]]
name = "beam"
section = { shape = "laminate", element = "L4", x = { from = 0.0, to = 0.01, elements = 1 }, plies = [
  { thickness = 0.0005, material = "cfrp", angle = 0 },
  { thickness = 0.0005, material = "cfrp", angle = 90 },
  { thickness = 0.0005, material = "cfrp", angle = 90 },
  { thickness = 0.0005, material = "cfrp", angle = 0 } ], interfaces = "cohesive", interface_material = "coh" }
axis = { element = "B2", segments = [{ from = 0.0, to = 0.04, elements = 40 }] }

[[constraints]]
name = "left"
body = "beam"
where = { y = 0.0, z = 0.0 }
fix = ["z"]

[[constraints]]
name = "right"
body = "beam"
where = { y = 0.04, z = 0.0 }
fix = ["z"]

[[constraints]]
name = "hold"
body = "beam"
where = { y = 0.02, z = 0.0 }
fix = ["x", "y"]

[[indenters]]
name = "nose"
body = "beam"
shape = "cylinder"
surface = { z = 0.002, y = [0.012, 0.028] }
axis = "x"
center = [0.005, 0.02, 0.00701]
radius = 0.005
displacement = [0.0, 0.0, -2.0e-3]
"#;

/// The coarse strip (h = 0.8 mm across the crack path) in CI: the crack
/// band's energy, the other modes and the balance of `strip_energy_ratio`
/// (a lost band scaling or a dropped damage mode moves the energy far
/// outside its band). The three meshes together are the slow
/// `the_notched_strip_dissipates_the_fracture_energy_of_its_ligament`.
#[test]
fn the_coarse_notched_strip_dissipates_the_fracture_energy_of_its_ligament() {
    strip_energy_ratio("coarse");
}

/// The three meshes (h = 0.8, 0.4, 0.2 mm across the crack path, L4 × B2),
/// each as `strip_energy_ratio`, and the crack band's promise: the meshes'
/// fibre-tension energies within 5 % of each other (measured 1.0 %:
/// D_FT/(G_FT A) = 1.065, 1.061, 1.071, `cufem run examples/notched_strip_*.toml`).
#[test]
#[ignore = "validate: slow — the three notched strips, about a minute (CI: the coarse strip)"]
fn the_notched_strip_dissipates_the_fracture_energy_of_its_ligament() {
    let fibre: Vec<f64> = ["coarse", "medium", "fine"].iter().map(|m| strip_energy_ratio(m)).collect();
    let (lo, hi) = fibre.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
    assert!(hi / lo - 1.0 < 0.05, "D_FT/(G_FT A) = {fibre:?}");
}

/// A damaged strip unloaded to zero and reloaded (three `[[steps]]` on the
/// coarse example): the unloading and the reloading follow one straight
/// line through the origin, its slope the damaged secant (below the intact
/// stiffness), and the reload resumes damaging only at the old end (the
/// damage is not undone, and not redone short of where it stopped).
#[test]
fn a_damaged_strip_reloads_along_its_damaged_secant() {
    let base = example("notched_strip_coarse");
    // past the peak (the crack part-way across the ligament)
    let peak = 0.55;
    let once = format!("{base}\n[[steps]]\nname = \"load\"\nfactor = {peak}\n");
    let (_, s_once) = run_cli("load_once", &once);
    let cycle = format!(
        "{base}\n[[steps]]\nname = \"load\"\nfactor = {peak}\n\n[[steps]]\nname = \"unload\"\nfactor = 0.0\n\
         increments = 10\n\n[[steps]]\nname = \"reload\"\nfactor = {peak}\nincrements = 10\n"
    );
    let (out, s_cycle) = run_cli("load_unload_reload", &cycle);
    let c = common::csv_columns(&out.join("history_pull.csv"));
    let (lambda, u, r) = (&c["lambda"], &c["u_x"], &c["r_x"]);
    let intact = r[0] / u[0];
    let end_of_load = lambda.iter().position(|&l| (l - 1.0).abs() < 1e-9).unwrap();
    // the secant after the first unloading increment (over which the
    // viscous damage catches up with the law's: Δλ = 0.1 ≫ η = 1e-3)
    let secant = r[end_of_load + 1] / u[end_of_load + 1];
    let at_load = r[end_of_load] / u[end_of_load];
    println!("intact {intact:.4e} N/m, at the end of the load {at_load:.4e} N/m, damaged secant {secant:.4e} N/m");
    assert!(secant < 0.8 * intact, "the strip is damaged: {secant} against {intact}");
    assert!((at_load / secant - 1.0).abs() < 0.02, "{at_load} against {secant}");
    // every later unloading and reloading point short of the old end on
    // the secant through the origin (measured within 3.3e-5 of it)
    let end = u[end_of_load];
    for i in end_of_load + 2..lambda.len() {
        if u[i].abs() > 1e-3 * end && u[i] < 0.99 * end {
            let k = r[i] / u[i];
            assert!((k / secant - 1.0).abs() < 1e-4, "λ = {}: P/u = {k} against {secant}", lambda[i]);
        }
    }
    // Back at the old end the damage resumes a little: over the unloading the
    // viscous damage caught up with the law's, so the crack front's
    // neighbours reach their onset just before the old end (a known effect
    // of the viscosity, docs/limitations.md "Ply damage"). Never stiffer
    // than the secant (the damage is not undone); measured −0.34 % and
    // 0.94 % more dissipation, asserted from both sides.
    let k_end = r[lambda.len() - 1] / u[lambda.len() - 1];
    assert!((-0.01..0.0).contains(&(k_end / secant - 1.0)), "{k_end} against {secant}");
    let (d_once, d_cycle) = (dissipated(&s_once)[0], dissipated(&s_cycle)[0]);
    println!("dissipated: load {d_once:.5} J, load-unload-reload {d_cycle:.5} J");
    assert!(d_once > 0.05 * CRACK_ENERGY, "{d_once}");
    assert!((1.0..1.02).contains(&(d_cycle / d_once)), "{d_cycle} against {d_once}");
}

/// The step ends of a damaging static run of two steps carry the ply
/// damage (`d_ft d_fc d_mt d_mc`, each mode's largest over an element's
/// Gauss points, as `result.vtu`): the coarse strip pulled to 0.45 of its
/// end displacement, then to 0.55 (past the peak, the crack part-way
/// across the ligament). The crack grows over the second step, so no
/// cell's fibre-tension damage falls from the first step end to the second
/// and some rises; the second step end is the end of the run
/// (`result.vtu`). Step ends that carried no damage (no field), or the
/// end's damage, fail here.
#[test]
fn the_step_ends_of_a_damaging_run_carry_its_damage_as_it_grows() {
    let base = example("notched_strip_coarse");
    let text =
        format!("{base}\n[[steps]]\nname = \"first\"\nfactor = 0.45\n\n[[steps]]\nname = \"second\"\nfactor = 0.55\n");
    let (out, _) = run_cli("two_steps", &text);
    let first = common::vtu_array(&out.join("result_1_first.vtu"), Some("d_ft"));
    let second = common::vtu_array(&out.join("result_2_second.vtu"), Some("d_ft"));
    let end = common::vtu_array(&out.join("result.vtu"), Some("d_ft"));
    assert!(first.iter().zip(&second).all(|(a, b)| b >= a), "a cell's damage fell over the second step");
    assert_eq!(second, end, "the second step end is the end of the run");
    assert!(first.iter().any(|&d| d > 0.0), "the strip has started to crack at the first step end");
    let grew = first.iter().zip(&second).filter(|(a, b)| *b > *a).count();
    println!("cells whose damage grew over the second step: {grew} of {}", end.len());
    assert!(grew > 0, "the first step end shows the end's damage");
}

/// The memory estimate counts the ply-damage history (`src/size.rs`: two
/// `DamageState`s, the crack bands and the volume per Gauss point, held
/// from the start whether or not a point damages): the coarse strip swept
/// along 200 axis elements (60,800 Gauss points, 32,562 DOF) and pulled
/// elastically in one increment. Measured (`cufem run`, one thread, the
/// machine shared): estimate 214.6 MB against a peak of 212.0 MB (1.01),
/// the history 46.9 MiB of it; without it the estimate would be 0.78 of
/// the peak. The band is `examples.rs`'s, [0.9, 1.3].
#[test]
fn the_memory_estimate_counts_the_ply_damage_history() {
    let base = example("notched_strip_coarse");
    let from = "axis = { element = \"B2\", from = 0.0, to = 0.001, elements = 1 }";
    assert!(base.contains(from), "examples/notched_strip_coarse.toml no longer holds {from:?}");
    let long = base.replace(from, &from.replace("elements = 1 }", "elements = 200 }"));
    let text = format!("{long}\n[[steps]]\nname = \"pull\"\nfactor = 0.1\nincrements = 1\n");
    let (_, summary) = run_cli("memory", &text);
    assert_eq!(summary["dof"], 32_562);
    let estimated = summary["memory"]["estimated_bytes"].as_f64().unwrap();
    let peak = summary["memory"]["peak_bytes"].as_f64().unwrap();
    println!("estimate {estimated:e} B, peak {peak:e} B: {:.3}", estimated / peak);
    assert!((0.9..1.3).contains(&(estimated / peak)), "estimate {estimated:e} B, peak {peak:e} B");
}

/// Each misuse of `[materials.damage]` is refused by `cufem check` naming
/// the key, the value and what is allowed.
#[test]
fn damage_keys_are_refused_where_the_law_cannot_work() {
    let base = example("notched_strip_coarse");
    let damage_line = base.lines().find(|l| l.starts_with("damage = ")).unwrap().to_string();
    let cases: [(&str, String, &str); 6] = [
        (
            "no_strengths",
            base.lines().filter(|l| !l.starts_with("strengths = ")).collect::<Vec<_>>().join("\n"),
            "materials[0].damage = given without strengths",
        ),
        (
            "isotropic",
            base.replace(
                base.lines().find(|l| l.starts_with("orthotropic = ")).unwrap(),
                "young_modulus = 70e9\npoisson_ratio = 0.3",
            ),
            "materials[0].damage = given with isotropic constants",
        ),
        (
            "toughness",
            base.replace(&damage_line, &damage_line.replace("fibre_tension = 133.3e3", "fibre_tension = -1.0")),
            "materials[0].damage.fibre_tension = -1",
        ),
        (
            "modal",
            format!("{base}\n[analysis]\ntype = \"modal\"\n")
                .replace("name = \"im7_8552\"", "name = \"im7_8552\"\ndensity = 1580.0"),
            "materials[0].damage = given with analysis.type = \"modal\"",
        ),
        (
            "max_damage",
            base.replace(&damage_line, &damage_line.replace("viscosity = 1e-3", "viscosity = 1e-3, max_damage = 1.0")),
            "materials[0].damage.max_damage = 1: expected",
        ),
        (
            "step_control_without_damage",
            base.replace(&damage_line, "")
                .replace("max_increments = 5000\n", "max_increments = 5000\nstep_control = { damage = 0.05 }\n"),
            "solver.step_control.damage = 0.05: expected only in a model that damages",
        ),
    ];
    for (name, text, expect) in cases {
        let dir = common::scratch_dir("ply_damage_refused", name);
        let model = dir.join("model.toml");
        std::fs::write(&model, text).unwrap();
        let check = common::cufem().args(["check", model.to_str().unwrap()]).output().unwrap();
        let stderr = String::from_utf8_lossy(&check.stderr);
        assert!(!check.status.success() && stderr.contains(expect), "{name}: {stderr}");
    }
}

/// `solver.step_control.damage` steers the increments by the largest
/// increment of a damage variable (`solver::step_control`): on the coarse
/// strip (its cap on the step lifted to `0.01`), halving the target from
/// `0.02` to `0.01` per increment takes more increments, at least 1.3 times
/// as many (measured 303 → 583; the increments before onset are not
/// steered, so not twice), and the crack band's energy stays in its band.
/// A damage measure that is not wired to the stepping leaves both runs at
/// the uncontrolled count (106).
#[test]
fn the_damage_increment_steers_the_load_steps() {
    // the example's own cap on the step lifted, so that the damage steers
    let base = example("notched_strip_coarse");
    assert!(base.contains("max_increment = 0.001\n"));
    let base = base.replace("max_increment = 0.001\n", "max_increment = 0.01\n");
    let anchor = "max_increments = 5000\n";
    assert!(base.contains(anchor));
    let run = |target: f64| {
        let text = base.replace(anchor, &format!("{anchor}step_control = {{ damage = {target} }}\n"));
        let (_, s) = run_cli(&format!("step_control_damage_{target}"), &text);
        let ratio = dissipated(&s)[0] / CRACK_ENERGY;
        let increments = s["increments"].as_u64().unwrap();
        println!("damage target {target}: {increments} increments, D_FT/(G_FT A) = {ratio:.4}");
        // the known band of `strip_energy_ratio` (the crack's steps)
        assert!((1.04..1.09).contains(&ratio), "target {target}: D_FT/(G_FT A) = {ratio}");
        increments as f64
    };
    let (coarse, fine) = (run(0.02), run(0.01));
    assert!(fine / coarse > 1.3, "{coarse} → {fine} increments");
}

/// A strip that had broken printed its failure indices only, as if intact
/// (a new-user review): the run's table (console and report.html) names
/// each mode's largest damage, the energy it dissipated and the volume past
/// half damage, as summary.json has them.
#[test]
fn the_runs_table_says_what_broke() {
    let dir = common::scratch_dir("ply_damage", "table");
    let model = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/notched_strip_coarse.toml");
    let out = dir.join("out");
    let run = common::cufem()
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success());
    let stdout = String::from_utf8_lossy(&run.stdout);
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let line = stdout.lines().find(|l| l.trim_start().starts_with("fibre_tension")).expect("a fibre-tension row");
    let cells: Vec<f64> = line.split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
    let d = &summary["damage"];
    let expected =
        [&d["largest"], &d["dissipated_j"], &d["damaged_volume_m3"]].map(|v| v["fibre_tension"].as_f64().unwrap());
    println!("{line}");
    // the strip breaks: its fibres fail (d → 1) and dissipate G_FT × the crack
    assert!(expected[0] > 0.99 && expected[1] > 0.1, "{expected:?}");
    for (got, want) in cells.iter().zip(expected) {
        assert!((got / want - 1.0).abs() < 1e-3, "{line}: against summary.json's {expected:?}");
    }
    let all = stdout.lines().find(|l| l.trim_start().starts_with("all modes")).expect("the total");
    let total: f64 = all.split_whitespace().last().unwrap().parse().unwrap();
    assert!((total / d["dissipated_total_j"].as_f64().unwrap() - 1.0).abs() < 1e-4, "{all}");
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(page.contains("ply damage") && page.contains("all modes"), "the report's table");
}

/// The coarse strip without its viscosity: the consistent tangent, its
/// unsymmetric rest included, takes Newton through the peak and the whole
/// softening under displacement control (the symmetric part alone did not:
/// it converged linearly and the run stopped at the peak). Measured
/// D_FT/(G_FT A) = 1.068 (1.065 with it: the excess is not the
/// viscosity's, docs/limitations.md "Ply damage"); held within 3 %.
#[test]
fn the_coarse_strip_passes_its_peak_without_viscosity() {
    let text = example("notched_strip_coarse");
    assert!(text.contains(", viscosity = 1e-3 }"));
    let (_, summary) = run_cli("strip_no_viscosity", &text.replace(", viscosity = 1e-3 }", " }"));
    assert_eq!(summary["load_factor"].as_f64(), Some(1.0), "{}", summary["load_factor"]);
    let ratio = dissipated(&summary)[0] / CRACK_ENERGY;
    let iterations = summary["newton_iterations"].as_f64().unwrap() / summary["increments"].as_f64().unwrap();
    println!("without viscosity: D_FT/(G_FT A) = {ratio:.4}, {iterations:.2} Newton iterations per increment");
    assert!((ratio / 1.068 - 1.0).abs() < 0.03, "D_FT/(G_FT A) = {ratio}");
}
