//! Delamination through cohesive interfaces (issue 48): the double
//! cantilever beam of `examples/dcb.toml` and the end-notched flexure of
//! `examples/enf.toml` against corrected beam theory with the same
//! constants (`tests/common/cbt.rs`: Williams 1989's crack correction χh,
//! Wang & Williams 1992's 0.42χh; self-checked in
//! tests/oracles_selfcheck.rs) — the compliance of a held crack, the
//! load–displacement curves through onset, and that they move with G_Ic and
//! G_IIc.

#[path = "../../../tests/common/cbt.rs"]
mod cbt;
#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};

use cbt::Specimen;
use serde_json::Value;

/// The text of `examples/<name>.toml`.
fn read_example(name: &str) -> String {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(format!("examples/{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

/// The example `name`'s text without its `propagation` step (the last
/// before `[solver]`): its elastic step alone, to onset.
fn before_propagation(name: &str) -> String {
    let text = read_example(name);
    let cut = text.find("[[steps]]\nname = \"propagation\"").unwrap();
    let end = text[cut..].find("[solver]").unwrap();
    format!("{}{}", &text[..cut], &text[cut + end..])
}

/// The DCB example's text.
fn example() -> String {
    read_example("dcb")
}

/// Runs a model text through the CLI: the output folder and the summary;
/// the run must reach its end if `complete`.
fn run_cli(name: &str, text: &str, complete: bool) -> (PathBuf, Value) {
    let dir = common::scratch_dir("delamination", name);
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let run = common::cufem()
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success() || !complete, "{name}: {}", String::from_utf8_lossy(&run.stderr));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(summary["converged"] == true || !complete, "{name}");
    (out, summary)
}

/// The example's specimen: B = 25.4 mm, h = 1.56 mm, 100 mm long, G_Ic
/// `gic`.
fn specimen(gic: f64) -> cbt::Dcb {
    let material = cbt::Material::as4_peek();
    cbt::Dcb { material: material.with_toughness(gic, material.giic), width: 0.0254, arm: 0.00156, length: 0.1 }
}

/// The precrack's tip: midway between the last cracked interface nodes
/// (y = 32.75 mm) and the first intact ones (32.875 mm) (examples/dcb.toml).
const A0: f64 = 0.0328125;

/// The load–opening points `(δ, P)` of a run of the example: P the
/// reaction of the upper arm's face, δ the difference of the arm-end
/// probes.
fn curve(out: &Path) -> Vec<(f64, f64)> {
    let c = common::csv_columns(&out.join("history_probes.csv"));
    let r = common::csv_columns(&out.join("history_upper_arm.csv"));
    let (up, down) = (&c["upper_end.u_z"], &c["lower_end.u_z"]);
    up.iter().zip(down).zip(&r["r_z"]).map(|((u, d), p)| (u - d, *p)).collect()
}

/// The example with G_Ic scaled by `factor`.
fn with_toughness(factor: f64) -> String {
    let text = example();
    assert!(text.contains("gic = 969.0"));
    text.replace("gic = 969.0", &format!("gic = {}", 969.0 * factor))
}

/// The held-crack compliance δ/P at an opening of 0.25 mm (far below onset: no point
/// damages) with the precrack to `to` (m), against CBT's
/// `C = 8 (a + χh)³/(E11 B h³)` at `a`, the midpoint between the last
/// cracked and the first intact nodes. Measured: −0.44 % at a = 32.8 mm,
/// −0.45 % at 39.9 mm; asserted 1 % (design48 §3.1). The interface's
/// onset index (summary and node field) below 1, ×4 at twice the opening.
#[test]
fn held_crack_compliance_matches_corrected_beam_theory() {
    for (name, to, a) in [("held_a33", 0.0328, A0), ("held_a40", 0.0399, 0.0399375)] {
        // an opening of 0.25 mm: below onset (4.19 mm)
        let text = example()
            .replace("to = 0.0328 }", &format!("to = {to} }}"))
            .replace("z = 0.005 }", "z = 0.000125 }")
            .replace("z = -0.005 }", "z = -0.000125 }");
        let solver = text.find("[solver]").unwrap();
        let text = format!("{}[solver]\nincrements = 1\n", &text[..solver]);
        let (out, summary) = run_cli(name, &text, true);
        let (d, p) = *curve(&out).last().unwrap();
        let c = d / p;
        let exact = specimen(969.0).compliance(a);
        eprintln!("{name}: C = {c:.5e} m/N, CBT {exact:.5e} ({:+.3} %)", 100.0 * (c / exact - 1.0));
        assert!((c / exact - 1.0).abs() < 0.01, "{name}: C = {c:e} against {exact:e}");
        // nothing grew: the delaminated area is the precrack's
        let area = summary["delamination"]["area_m2"].as_f64().unwrap();
        assert_eq!(summary["delamination"]["interfaces"][0]["process_zone_m2"].as_f64().unwrap(), 0.0);
        assert!((area / 0.0254 - a).abs() < 0.2e-3, "{name}: delaminated {area} m²");
        // and the interface's onset index says how far it is from damaging:
        // below 1, and four times as large at twice the opening (elastic)
        let index = |s: &Value| s["delamination"]["interfaces"][0]["largest_onset_index"].as_f64().unwrap();
        let (_, doubled) = run_cli(
            &format!("{name}_doubled"),
            &text.replace("z = 0.000125 }", "z = 0.00025 }").replace("z = -0.000125 }", "z = -0.00025 }"),
            true,
        );
        eprintln!("{name}: largest onset index {:.4e}, at twice the opening {:.4e}", index(&summary), index(&doubled));
        assert!(index(&summary) > 0.0 && index(&doubled) < 1.0, "{} {}", index(&summary), index(&doubled));
        assert!((index(&doubled) / index(&summary) - 4.0).abs() < 1e-6, "{} {}", index(&summary), index(&doubled));
        // the node field `onset_interface` holds the index where it sits:
        // its largest is the summary's, and it is 0 on the precrack (d = 1)
        let onset = common::vtu_array(&out.join("result.vtu"), Some("onset_interface"));
        let damage = common::vtu_array(&out.join("result.vtu"), Some("d_interface"));
        let largest = onset.iter().copied().fold(0.0, f64::max);
        assert!((largest / index(&summary) - 1.0).abs() < 1e-9, "field {largest}, summary {}", index(&summary));
        let cracked = damage.iter().zip(&onset).filter(|(d, _)| **d >= 1.0);
        assert!(cracked.clone().count() > 0 && cracked.clone().all(|(_, i)| *i == 0.0), "{name}: precrack");
    }
}

/// The whole computed curve within 3 % of P_c of CBT (issue 48): up to
/// onset and along the propagation branch to an opening of 10 mm, where
/// CBT's crack is 52.1 mm. Measured: 2.55 % at worst, at the CBT curve's
/// cusp (the cohesive zone rounds the peak: 135.2 N against 138.7 N at
/// δ = 4.2 mm), 0.4 % at 10 mm (90.2 N against 89.9 N); the crack grew to
/// 51.5 mm.
#[test]
fn dcb_curve_follows_corrected_beam_theory() {
    let (out, summary) = run_cli("dcb", &example(), true);
    let points = curve(&out);
    let dcb = specimen(969.0);
    let (dc, pc) = dcb.onset(A0);
    let error = cbt::curve_error(&points, &dcb, A0);
    let last = *points.last().unwrap();
    eprintln!(
        "DCB: P_c = {pc:.2} N at {:.3} mm; {} points to δ = {:.3} mm; curve error {:.2} % of P_c",
        1e3 * dc,
        points.len(),
        1e3 * last.0,
        100.0 * error
    );
    assert!((last.0 - 0.01).abs() < 1e-9, "the curve stops at δ = {} m", last.0);
    assert!(points.iter().filter(|p| p.0 > dc).count() >= 100, "too few points on the branch");
    assert!(error < 0.03, "curve error {error}");
    // the crack: CBT's at the last opening, a + χh = K/P
    let d = &summary["delamination"];
    // each interface names its body (its index was all a new user saw)
    assert_eq!(d["interfaces"][0]["body_name"], "dcb");
    assert_eq!(d["interfaces"][0]["body"], 0);
    // the first onset: the increment after which a point first damaged.
    // Elastic before it, the onset index grows as δ² (the held crack's
    // test: 0.035535 at δ = 0.25 mm, ×4 at twice the opening), so it
    // reaches 1 at δ = 0.25 mm/√0.035535 = 1.326 mm, λ = 0.1326 of the 10 mm:
    // the first increment at or past it, before the load peaks; a static
    // run gives no time
    let lambda = common::csv_columns(&out.join("history_probes.csv"))["lambda"].clone();
    let peak = (0..points.len()).max_by(|&i, &j| points[i].1.total_cmp(&points[j].1)).unwrap();
    let onset = d["interfaces"][0]["first_onset_load_factor"].as_f64().unwrap();
    let expected = 0.25e-3 / 0.035535f64.sqrt() / 0.01;
    let at = lambda.iter().position(|&l| l >= expected).unwrap();
    eprintln!(
        "DCB: first onset at λ = {onset:.4} (index 1 at {expected:.4}), the peak load at λ = {:.4}",
        lambda[peak]
    );
    assert!(
        onset == lambda[at] && onset < lambda[peak],
        "onset {onset}, expected {}, peak {}",
        lambda[at],
        lambda[peak]
    );
    assert!(d["interfaces"][0]["first_onset_time_s"].is_null());
    // and the run's table (console, report.html) says how much let go
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    let area = format!("delamination       {:.5e} m² of", d["area_m2"].as_f64().unwrap());
    assert!(page.contains(&area), "report.html has no {area:?}");
    let a = d["area_m2"].as_f64().unwrap() / 0.0254;
    let exact = dcb.branch_crack_closed(last.0);
    let dissipated = d["dissipated_j"].as_f64().unwrap();
    eprintln!("DCB: crack {:.3} mm (CBT {:.3} mm), dissipated {dissipated:.4} J", 1e3 * a, 1e3 * exact);
    assert!((a - exact).abs() < 1e-3, "crack {a} m against CBT's {exact} m");
    // the law's dissipation is G_Ic times the new crack's area (the points
    // of the process zone hold part of theirs: within 5 %)
    let grown = 969.0 * 0.0254 * (a - A0);
    assert!((dissipated / grown - 1.0).abs() < 0.05, "dissipated {dissipated} J against G_Ic ΔA = {grown} J");
    // the ledger: the work of the arm loads ∫P dδ (trapezoidal over the
    // increments) is the elastic energy left, ½ P δ (every point on its
    // secant: the unloading is linear to the origin, as
    // `dcb_reloads_on_the_reduced_stiffness` shows), plus the law's
    // dissipation plus the work of the viscous over-stress
    let viscous = d["viscous_j"].as_f64().unwrap();
    let work: f64 = std::iter::once((0.0, 0.0))
        .chain(points.iter().copied())
        .collect::<Vec<_>>()
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum();
    let elastic = 0.5 * last.0 * last.1;
    let gap = work - elastic - dissipated - viscous;
    eprintln!(
        "DCB: work {work:.5} J = elastic {elastic:.5} + dissipated {dissipated:.5} + viscous {viscous:.5} J {:+.3e} J \
         ({:+.3} % of the work)",
        gap,
        100.0 * gap / work
    );
    common::figure("dcb.ledger_gap", 100.0 * gap / work, "%", "|gap| ≤ 0.1 % of the work of the arm loads");
    common::figure("dcb.viscous_work", viscous, "J", "positive; closes the ledger with dissipated_j");
    assert!(viscous > 0.0, "viscous work {viscous} J");
    assert!(gap.abs() < 1e-3 * work, "the ledger does not close: {gap} J of {work} J");
}

/// G_Ic changed by ±10 % moves the curve out of the 3 % band around the
/// original closed form, and keeps it within 3 % of the closed form of the
/// changed toughness (design48 §3.4). Each run stops after 120 converged
/// increments (of 100 to an opening of 5 mm: the changed toughness makes
/// the crack front cut back about once per increment, so the whole branch
/// would cost minutes), past both peaks (4.40 and 3.98 mm), where the
/// curves part most. Measured: +10 %: 8.27 % against the original, 2.87 %
/// against its own; −10 %: 4.47 % and 2.40 % (7.37 % against the original
/// when run on to 4.44 mm). Both run in the validation (+10 % here, −10 %
/// in `dcb_curve_moves_with_a_lower_toughness`); CI keeps the original curve.
#[test]
#[ignore = "validate: slow — the DCB with G_Ic raised by 10 % (about 20 s; CI keeps the original curve)"]
fn dcb_curve_moves_with_the_toughness() {
    dcb_moves("gic_up", 1.1);
}

/// `dcb_curve_moves_with_the_toughness` with G_Ic lowered by 10 % (the
/// closer of the two to the original curve: 4.47 % against 3 %).
#[test]
#[ignore = "validate: slow — the DCB to 120 increments with G_Ic lowered by 10 % (about a minute)"]
fn dcb_curve_moves_with_a_lower_toughness() {
    dcb_moves("gic_down", 0.9);
}

/// The DCB with G_Ic times `factor`, 120 increments: outside the 3 % band
/// of the original closed form, inside that of its own.
fn dcb_moves(name: &str, factor: f64) {
    let text = with_toughness(factor)
        .replace("z = 0.005 }", "z = 0.0025 }")
        .replace("z = -0.005 }", "z = -0.0025 }")
        .replace("increments = 200", "increments = 100\nmax_increments = 120");
    let (out, _) = run_cli(name, &text, false);
    let points = curve(&out);
    let original = cbt::curve_error(&points, &specimen(969.0), A0);
    let own = cbt::curve_error(&points, &specimen(969.0 * factor), A0);
    eprintln!("{name}: error against the original CBT {:.2} %, against its own {:.2} %", 100.0 * original, 100.0 * own);
    assert!(original > 0.03, "{name}: within 3 % of the original curve ({original})");
    assert!(own < 0.03, "{name}: not within 3 % of its own curve ({own})");
}

/// The DCB opened to 4.5 mm (past its peak: the crack has started to run),
/// then to 6 mm, in two `[[steps]]` of 0.05 mm increments, closed to 0 in
/// 10 and opened again to 5.5 mm in 10: one run for
/// `dcb_reloads_on_the_reduced_stiffness` and
/// `dcb_step_ends_carry_the_interface_damage_as_it_grows` (whichever test
/// comes first runs it, the other waits); its output folder.
fn loaded_unloaded_reloaded() -> &'static Path {
    static RUN: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    RUN.get_or_init(|| {
        let text = example().replace("[solver]\nincrements = 200", "");
        assert!(!text.contains("[solver]"));
        let text = format!(
            "{text}[[steps]]\nname = \"onset\"\nfactor = 0.45\nincrements = 90\n\n\
             [[steps]]\nname = \"load\"\nfactor = 0.6\nincrements = 30\n\n\
             [[steps]]\nname = \"unload\"\nfactor = 0.0\nincrements = 10\n\n\
             [[steps]]\nname = \"reload\"\nfactor = 0.55\nincrements = 10\n"
        );
        run_cli("reload", &text, true).0
    })
}

/// A damaged interface is never healed (design48 §3.6b): the DCB opened to
/// 6 mm (CBT's crack 39.8 mm, from 32.8), closed to 0 and opened again to
/// 5.5 mm ([`loaded_unloaded_reloaded`]). Unloading is linear to the origin and
/// reloading retraces it: every point of both has the secant δ/P of the
/// turn-around within 0.5 %, and that secant is CBT's compliance at the
/// crack CBT reaches at 6 mm within 2 % (measured: see the output), far
/// from the intact precrack's. A law that let d fall as the
/// separation falls would unload on a stiffer path and reload on the
/// precrack's compliance.
#[test]
fn dcb_reloads_on_the_reduced_stiffness() {
    let out = loaded_unloaded_reloaded();
    let points = curve(out);
    let lambda = &common::csv_columns(&out.join("history_probes.csv"))["lambda"];
    // the turn-around: the end of the second step (λ = 2)
    let turn = lambda.iter().rposition(|&l| l <= 2.0 + 1e-9).unwrap();
    let (dm, pm) = points[turn];
    let secant = dm / pm;
    let dcb = specimen(969.0);
    let a = dcb.branch_crack_closed(dm);
    let exact = dcb.compliance(a);
    let initial = points[0].0 / points[0].1;
    eprintln!(
        "reload: turned at δ = {:.3} mm, P = {pm:.2} N; secant {secant:.5e} m/N, CBT {exact:.5e} at a = {:.3} mm \
         ({:+.2} %); the precrack's {initial:.5e}",
        1e3 * dm,
        1e3 * a,
        100.0 * (secant / exact - 1.0)
    );
    assert!((dm - 0.006).abs() < 1e-9, "turned at {dm} m");
    common::figure("dcb.reload_secant", 100.0 * (secant / exact - 1.0), "%", "|difference| ≤ 2 % against CBT's C(a)");
    assert!((secant / exact - 1.0).abs() < 0.02, "secant {secant:e} against CBT's {exact:e}");
    assert!(secant > 1.5 * initial, "secant {secant:e}, precrack {initial:e}");
    let after = &points[turn + 1..];
    assert_eq!(after.len(), 20, "unload and reload increments");
    let mut worst: f64 = 0.0;
    for &(d, p) in after.iter().filter(|p| p.0 > 0.05 * dm) {
        worst = worst.max((d / p / secant - 1.0).abs());
    }
    eprintln!("reload: unloading and reloading secants within {:.3} % of the turn-around's", 100.0 * worst);
    assert!(worst < 0.005, "off the secant by {worst}");
    let origin = after[9];
    assert!(origin.0.abs() < 1e-12 && origin.1.abs() < 1e-6 * pm, "unloaded to {origin:?}");
    // At zero opening the precrack's faces sit at round-off of zero: the
    // first reopening increment frees them at once (with the sign of the
    // round-off choosing each face's stiffness: 18 corrections, about one
    // node row each, as a beam lifting off a rigid foundation). Closing to
    // zero opening, every load and reaction goes to zero with the residual:
    // measured against its own vanishing forces that increment took 17
    // corrections (each shrinking the displacements a billion times); the
    // force scale's floor from the run's history (`ZERO_FLUX`,
    // src/analysis/structure/evaluation.rs) ends it in one or two.
    let history = common::csv_columns(&out.join("history.csv"));
    assert!(!history.contains_key("time"), "a static run's history has no time");
    let iterations = &history["iterations"];
    assert_eq!(iterations.len(), lambda.len());
    let (closing, reopening) = (iterations[turn + 10], iterations[turn + 11]);
    eprintln!(
        "reload: corrections of the increment closing to zero opening {closing}, of the first reopening one {reopening}"
    );
    assert!(reopening <= 2.0, "the first reopening increment took {reopening} corrections");
    common::figure("dcb.closing_corrections", closing, "", "at most 2: the increment closing to zero opening");
    assert!(closing <= 2.0, "the increment closing to zero opening took {closing} corrections");
}

/// The step ends of a run of several steps carry the interface damage then
/// ([`loaded_unloaded_reloaded`]): each step's `result_<k>_<name>.vtu`
/// holds `d_interface`; no node's damage falls from the first step end to
/// the second and it grows at some (a step end showing the damage of the
/// run's end, or the precrack's alone, fails); unloading and reloading
/// below the turn-around leave it as it was, and the last step end is the
/// run's end (`result.vtu`).
#[test]
fn dcb_step_ends_carry_the_interface_damage_as_it_grows() {
    let out = loaded_unloaded_reloaded();
    let [first, second, fourth, end] = ["result_1_onset.vtu", "result_2_load.vtu", "result_4_reload.vtu", "result.vtu"]
        .map(|f| common::vtu_array(&out.join(f), Some("d_interface")));
    assert!(first.iter().zip(&second).all(|(a, b)| b >= a), "a node's d_interface fell over the second step");
    let grew = first.iter().zip(&second).filter(|(a, b)| *b > *a).count();
    let cracked = |d: &[f64]| d.iter().filter(|&&v| v >= 1.0).count();
    eprintln!(
        "step ends: nodes at d = 1: {} then {}; {grew} nodes' damage grew over the second step",
        cracked(&first),
        cracked(&second)
    );
    assert!(grew > 0, "the first step end shows the damage of a later moment");
    assert!(cracked(&second) > cracked(&first), "the crack did not run over the second step");
    // unloaded and reloaded below the turn-around: the damage stays
    assert_eq!(second, fourth, "the damage moved while unloading and reloading");
    assert_eq!(fourth, end, "the last step end is the run's end");
}

/// The MMB example's specimen at G_II/G = `ratio` with toughnesses
/// `(gic, giic)`: the lever is the one of the original toughness (the
/// lever of the example), B = 25.4 mm, h = 1.56 mm, L = 51 mm.
fn mmb_specimen(ratio: f64, gic: f64, giic: f64) -> cbt::Mmb {
    let m = cbt::Material::as4_peek();
    let mut mmb = cbt::Mmb::for_ratio(m, 0.0254, 0.00156, 0.051, MMB_A0, ratio);
    mmb.material = m.with_toughness(gic, giic);
    mmb
}

/// The MMB precrack's tip: midway between the last cracked interface nodes
/// (y = 42.0 mm) and the first intact ones (42.125 mm) (examples/mmb.toml).
const MMB_A0: f64 = 0.0420625;

/// The MMB example's mode ratio G_II/G at a0 (examples/mmb.toml's lever).
const MMB_RATIO: f64 = 0.65;

/// The largest gap between the CBT curves of `a` and `b` up to the
/// opening `delta_max`, over `a`'s P_c (400 samples).
fn cbt_gap(a: &cbt::Mmb, b: &cbt::Mmb, delta_max: f64) -> f64 {
    let (_, pc) = a.onset(MMB_A0);
    (1..=400)
        .map(|i| {
            let d = delta_max * f64::from(i) / 400.0;
            (a.load(MMB_A0, d) - b.load(MMB_A0, d)).abs() / pc
        })
        .fold(0.0, f64::max)
}

/// Which MMB ratio can catch a ±10 % toughness at the 5 %
/// (design48 §3.4), from the closed form alone, with the example's
/// precrack (a0 = 42.1 mm): the largest gap between the curves up to the
/// crack limit (where the mode-II tip reaches the saddle). At G_II/G = 0.5
/// a ±10 % G_IIc moves the curve by at most 3.1 % of P_c, and at 0.8 a
/// ±10 % G_Ic by 3.5 %: no test at 5 % catches them. At the example's
/// 0.65 each of the four moves it by 5.3–5.8 %: all can be caught, on the
/// propagation branch (the peak moves by less than 5 %).
#[test]
fn mmb_ratio_that_can_catch_the_toughnesses() {
    let (gic, giic) = (969.0, 1719.0);
    for (ratio, gi, gii, low, high) in [
        (0.5, gic, 1.1 * giic, 0.0, 0.05),
        (0.5, gic, 0.9 * giic, 0.0, 0.05),
        (0.8, 1.1 * gic, giic, 0.0, 0.05),
        (0.8, 0.9 * gic, giic, 0.0, 0.05),
        (MMB_RATIO, gic, 1.1 * giic, 0.05, 1.0),
        (MMB_RATIO, gic, 0.9 * giic, 0.05, 1.0),
        (MMB_RATIO, 1.1 * gic, giic, 0.05, 1.0),
        (MMB_RATIO, 0.9 * gic, giic, 0.05, 1.0),
    ] {
        let original = mmb_specimen(ratio, gic, giic);
        let changed = mmb_specimen(ratio, gi, gii);
        let end = |m: &cbt::Mmb| m.branch_point(m.crack_limit() - 1e-4).0;
        let gap = cbt_gap(&original, &changed, end(&original).min(end(&changed)));
        let peak = changed.onset(MMB_A0).1 / original.onset(MMB_A0).1 - 1.0;
        eprintln!(
            "MMB {ratio}: G_Ic {gi:.1}, G_IIc {gii:.1}: curves {:.2} % of P_c apart, peak {:+.2} %",
            100.0 * gap,
            100.0 * peak
        );
        assert!(gap > low && gap < high, "MMB {ratio} ({gi}, {gii}): {gap}");
        assert!(peak.abs() < 0.05, "the peak alone catches it: {peak}");
    }
}

/// The lever's curve `(δ, P)` of an MMB run: its displacement and force
/// per increment (`history_lever.csv`).
fn mmb_curve(out: &Path) -> Vec<(f64, f64)> {
    let c = common::csv_columns(&out.join("history_lever.csv"));
    c["displacement"].iter().zip(&c["force"]).map(|(d, p)| (*d, *p)).collect()
}

/// The MMB example with G_Ic and G_IIc scaled by `gi` and `gii`.
fn mmb_with_toughness(gi: f64, gii: f64) -> String {
    let text = read_example("mmb");
    assert!(text.contains("gic = 969.0, giic = 1719.0"));
    text.replace("gic = 969.0, giic = 1719.0", &format!("gic = {}, giic = {}", 969.0 * gi, 1719.0 * gii))
}

/// The error of the MMB's propagation branch past 1.1 δ_c of `reference`:
/// `max |P − P_CBT(δ)| / P_c` (the first `10 %` of δ past the peak left
/// out, where the crack jumps: `mmb_curve_follows_corrected_beam_theory`).
fn mmb_branch_error(points: &[(f64, f64)], reference: &cbt::Mmb) -> f64 {
    let (dc, _) = reference.onset(MMB_A0);
    // the closed form ends where its crack reaches its limit (the saddle): a
    // run with a lower toughness passes that δ in its last increments
    let top = reference.branch_point(reference.crack_limit()).0;
    let branch: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 >= 1.1 * dc && p.0 <= top).collect();
    assert!(branch.len() >= 20, "{} points on the branch", branch.len());
    cbt::curve_error(&branch, reference, MMB_A0)
}

/// The MMB lever before onset (`examples/mmb.toml`'s first step alone, to
/// δ = 5.1 mm), against statics and CBT: the lever pushes the end up by
/// P c/L and the saddle down by P (c + L)/L, so the pin carries
/// P (c + L)/(2L) and the roller P (L − c)/(2L) (moments about the
/// supports; to round-off); the lever's displacement is
/// (c/L) u_end − ((c + L)/L) u_saddle of the mid-width probes (within
/// `1 %`: the lever reads the mean over the width's four nodes; measured
/// `0.5 %`); and the compliance δ/P at the first increment is CBT's
/// (Reeder & Crews) within `1 %` (measured `+0.23 %`; the ENF's `+0.69 %`:
/// its beams' and interface's shear). Swapping the lever's two coefficients or dropping one
/// moves the pin's share by far more.
#[test]
fn mmb_lever_before_onset_matches_statics_and_corrected_beam_theory() {
    let text = before_propagation("mmb");
    let (out, _) = run_cli("mmb_elastic", &text, true);
    let mmb = mmb_specimen(MMB_RATIO, 969.0, 1719.0);
    let (c, l) = (mmb.lever, mmb.half_span);
    let lever = common::csv_columns(&out.join("history_lever.csv"));
    let probes = common::csv_columns(&out.join("history_probes.csv"));
    let (pin, roller) =
        (common::csv_columns(&out.join("history_pin.csv")), common::csv_columns(&out.join("history_roller.csv")));
    assert_eq!(lever["force"].len(), 10);
    for i in 0..10 {
        let (d, p) = (lever["displacement"][i], lever["force"][i]);
        assert!((d / lever["target"][i] - 1.0).abs() < 1e-9, "the lever at {d} m, not at its target");
        let pin_share = pin["r_z"][i] / (p * (c + l) / (2.0 * l));
        let roller_share = roller["r_z"][i] / (p * (l - c) / (2.0 * l));
        assert!((pin_share - 1.0).abs() < 1e-6 && (roller_share - 1.0).abs() < 1e-6, "{pin_share} {roller_share}");
        let from_probes = c / l * probes["end.u_z"][i] - (c + l) / l * probes["saddle.u_z"][i];
        assert!((from_probes / d - 1.0).abs() < 0.01, "probes' lever {from_probes} m against {d} m");
    }
    let compliance = lever["displacement"][0] / lever["force"][0];
    let reference = mmb.compliance(MMB_A0);
    eprintln!("MMB: C = {compliance:.5e} m/N, CBT {reference:.5e} ({:+.2} %)", 100.0 * (compliance / reference - 1.0));
    assert!((compliance / reference - 1.0).abs() < 0.01, "compliance {compliance:e}");
}

/// The MMB at G_II/G = 0.65 under the lever's displacement control
/// (`examples/mmb.toml`, viscosity 3e-4) through onset (δ_c = 5.48 mm) and
/// propagation to δ = 6.3 mm, near CBT's crack limit (6.39 mm). The issue
/// asks for the whole curve within 5 % of P_c (measured 3.74 %, at δ_c:
/// the process zone rounds the peak, 3.19 % below P_c); the branch past
/// 1.1 δ_c is within it too (1.56 %), and CBT's crack at the last δ lies in
/// the computed process zone.
#[test]
#[ignore = "validate: slow — examples/mmb.toml through onset and propagation, about 300 increments, about 2 min"]
fn mmb_curve_follows_corrected_beam_theory() {
    let (out, summary) = run_cli("mmb", &read_example("mmb"), true);
    let points = mmb_curve(&out);
    let mmb = mmb_specimen(MMB_RATIO, 969.0, 1719.0);
    let (dc, pc) = mmb.onset(MMB_A0);
    let last = *points.last().unwrap();
    assert!((last.0 - 0.0063).abs() < 1e-9, "the curve stops at δ = {} m", last.0);
    // summary.json's lever is the history's last row
    let lever = &summary["levers"][0];
    let (d, p) = (lever["displacement"].as_f64().unwrap(), lever["force"].as_f64().unwrap());
    assert!((d / last.0 - 1.0).abs() < 1e-12 && (p / last.1 - 1.0).abs() < 1e-12, "summary's lever ({d}, {p})");
    let whole = cbt::curve_error(&points, &mmb, MMB_A0);
    let branch = mmb_branch_error(&points, &mmb);
    let peak = points.iter().map(|p| p.1).fold(0.0, f64::max);
    eprintln!(
        "MMB: P_c = {pc:.2} N at {:.3} mm; peak {peak:.2} N ({:+.2} %); {} points; whole-curve error {:.2} %, branch \
         past 1.1 δ_c {:.2} % of P_c",
        1e3 * dc,
        100.0 * (peak / pc - 1.0),
        points.len(),
        100.0 * whole,
        100.0 * branch
    );
    common::figure(
        "mmb.whole_curve_error",
        100.0 * whole,
        "%",
        "≤ 5 % of P_c over the whole curve (corrected beam theory)",
    );
    assert!(whole < 0.05, "whole-curve error {whole}");
    common::figure("mmb.branch_error", 100.0 * branch, "%", "≤ 5 % of P_c past 1.1 δ_c (corrected beam theory)");
    assert!(branch < 0.05, "branch error {branch}");
    common::figure("mmb.peak_below_pc", 100.0 * (1.0 - peak / pc), "%", "the process zone rounds the peak");
    let i = &summary["delamination"]["interfaces"][0];
    let cracked = i["delaminated_m2"].as_f64().unwrap() / 0.0254;
    let damaged = cracked + i["process_zone_m2"].as_f64().unwrap() / 0.0254;
    let exact = mmb.branch_crack(MMB_A0, last.0);
    eprintln!(
        "MMB: d = 1 to {:.3} mm, d > 0 to {:.3} mm, CBT crack {:.3} mm",
        1e3 * cracked,
        1e3 * damaged,
        1e3 * exact
    );
    assert!(cracked < exact && exact < damaged, "CBT's crack {exact} m outside [{cracked}, {damaged}] m");
}

/// G_Ic or G_IIc changed by ±10 %: each run's whole curve is more than
/// 5 % of P_c from the original closed form (the check fails),
/// while it stays within 5 % of its own closed form. Measured against the
/// original CBT (whole curve): G_Ic ×1.1 6.74 %, ×0.9 5.62 %; G_IIc ×1.1
/// 6.35 %, ×0.9 5.65 %; against their own 3.36–4.03 %
/// (`mmb_curve_follows_corrected_beam_theory`'s run: 3.74 %).
#[test]
#[ignore = "validate: slow — four runs of examples/mmb.toml, about 2 min each"]
fn mmb_curve_moves_with_the_toughness() {
    for (name, gi, gii) in
        [("mmb_gic_up", 1.1, 1.0), ("mmb_gic_down", 0.9, 1.0), ("mmb_giic_up", 1.0, 1.1), ("mmb_giic_down", 1.0, 0.9)]
    {
        let (out, _) = run_cli(name, &mmb_with_toughness(gi, gii), true);
        let points = mmb_curve(&out);
        let original = mmb_specimen(MMB_RATIO, 969.0, 1719.0);
        let whole = cbt::curve_error(&points, &original, MMB_A0);
        // the closed form of a lower toughness reaches its crack limit
        // before the run's last δ: its curve ends there
        let changed = mmb_specimen(MMB_RATIO, 969.0 * gi, 1719.0 * gii);
        let top = changed.branch_point(changed.crack_limit()).0;
        let within: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 <= top).collect();
        let own = cbt::curve_error(&within, &changed, MMB_A0);
        eprintln!(
            "{name}: whole curve {:.2} % of P_c from the original CBT, {:.2} % from its own",
            100.0 * whole,
            100.0 * own
        );
        common::figure(&format!("{name}.whole_gap"), 100.0 * whole, "%", "> 5 % of P_c (the issue's check fails)");
        assert!(whole > 0.05, "{name}: the whole curve within 5 % of the original CBT ({whole})");
        common::figure(&format!("{name}.own_gap"), 100.0 * own, "%", "≤ 5 % of its own P_c");
        assert!(own < 0.05, "{name}: not within 5 % of its own CBT ({own})");
    }
}

/// The ENF example's specimen: B = 25.4 mm, h = 1.56 mm, half-span
/// L = 51 mm, G_IIc `giic`.
fn enf_specimen(giic: f64) -> cbt::Enf {
    let material = cbt::Material::as4_peek();
    cbt::Enf { material: material.with_toughness(material.gic, giic), width: 0.0254, arm: 0.00156, half_span: 0.051 }
}

/// The ENF precrack's tip: midway between the last cracked interface nodes
/// (y = 44.0 mm) and the first intact ones (44.125 mm) (examples/enf.toml).
const ENF_A0: f64 = 0.0440625;

/// The load–deflection points `(δ, P)` of an ENF run: P the reaction of the
/// load line (downward positive), δ its downward displacement.
fn enf_curve(out: &Path) -> Vec<(f64, f64)> {
    let c = common::csv_columns(&out.join("history_probes.csv"));
    let r = common::csv_columns(&out.join("history_load.csv"));
    c["load_line.u_z"].iter().zip(&r["r_z"]).map(|(u, p)| (-u, -p)).collect()
}

/// The error of the propagation branch alone: `max |P − P_CBT(δ)| / P_c`
/// over the points past 1.05 δ_c of `reference` (the peak and the first
/// 3 mm of growth left out: there the process zone rounds CBT's cusp).
fn enf_branch_error(points: &[(f64, f64)], reference: &cbt::Enf) -> f64 {
    let (dc, _) = reference.onset(ENF_A0);
    let branch: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 >= 1.05 * dc).collect();
    assert!(branch.len() >= 20, "{} points on the branch", branch.len());
    cbt::curve_error(&branch, reference, ENF_A0)
}

/// The ENF before onset (`examples/enf.toml`'s first step alone, 10
/// increments to δ = 3.6 mm; the whole curve is the slow
/// `enf_curve_follows_corrected_beam_theory`): the compliance of the
/// precracked beam δ/P is CBT's (Wang & Williams' corrected beam theory,
/// `tests/common/cbt.rs`) within `1 %` at every point up to a quarter of
/// CBT's onset deflection (measured `+0.69 %` at both: the beams' and the
/// interface's shear compliance, which CBT leaves out), so a `10 %` error in the plies' stiffness or an
/// interface that does not carry the bonded part's shear fails it; the
/// crack does not grow; and the precracked arms, pressed together by the
/// load, do not pass through each other (the law's compression penalty:
/// δ3 ≥ −0.1 µm).
#[test]
fn enf_before_onset_matches_corrected_beam_theory() {
    let text = before_propagation("enf");
    let (out, summary) = run_cli("enf_elastic", &text, true);
    let points = enf_curve(&out);
    assert_eq!(points.len(), 10);
    let enf = enf_specimen(1719.0);
    let (dc, _) = enf.onset(ENF_A0);
    let reference = enf.compliance(ENF_A0);
    let mut checked = 0;
    eprintln!("ENF before onset: CBT's δ_c = {:.3} mm", 1e3 * dc);
    for &(d, p) in points.iter().filter(|p| p.0 <= 0.25 * dc) {
        let c = d / p;
        eprintln!(
            "ENF before onset: δ = {:.3} mm, C = {c:.5e} m/N ({:+.2} % of CBT)",
            1e3 * d,
            100.0 * (c / reference - 1.0)
        );
        assert!((c / reference - 1.0).abs() < 0.01, "compliance {c:e} m/N at δ = {d} m against CBT {reference:e}");
        checked += 1;
    }
    assert!(checked >= 2, "{checked} points below a quarter of δ_c = {dc} m");
    // no crack growth before onset: the delaminated points (d = 1) are the
    // precrack's, within one node spacing (0.125 mm) of a0
    let cracked = summary["delamination"]["area_m2"].as_f64().unwrap() / 0.0254;
    assert!((cracked - ENF_A0).abs() < 1.25e-4, "delaminated to {cracked} m before onset (a0 = {ENF_A0} m)");
    let c = common::csv_columns(&out.join("history_probes.csv"));
    for y in [5, 20, 35] {
        let gap = c[&format!("above_{y}.u_z")].iter().zip(&c[&format!("below_{y}.u_z")]).map(|(a, b)| a - b);
        let least = gap.fold(f64::INFINITY, f64::min);
        assert!(least > -1e-7, "the arms pass through each other at y = {y} mm by {least} m");
    }
}

/// The ENF in three-point bending (design48 §3.2), a0 = 44.06 mm (A0 =
/// 0.886 L: stable, the closed form falling gently past its peak),
/// deflected to 4.15 mm, where CBT's crack is 49.7 mm. The issue asks for
/// the whole curve within 3 % of P_c: measured 2.78 %, past the peak,
/// where the branch rides above CBT's (CBT leaves out the beams' shear
/// compliance and the interface's, about 1.5 % of P_c each way); the
/// peak, rounded by the mode-II process zone, 1.0 % below P_c. The
/// interface that gets there (examples/enf.toml's header): the DCB's
/// toughnesses with a shorter process zone (normal_strength = 140e6) and
/// a third of the default penalty; the DCB's precrack and interface
/// (a0 = 39.3 mm) were 5.0 % off at CBT's cusp, and neither the precrack,
/// the strength, the viscosity nor the increments alone reached 3 %
/// (python3 bench/enf_strength_study.py, bench/enf_strength_results.txt).
/// Before the peak the compliance is within 1 % of CBT (measured 0.69 %
/// more compliant at δ = 0.36 mm). The crack: CBT's at the last
/// deflection lies past the delaminated points and 0.34 mm past the
/// process zone's front (the computed load higher at that deflection, its
/// crack shorter), a known limit asserted from both sides. The precracked
/// arms slide without passing through each other (the law's compression
/// penalty).
#[test]
#[ignore = "validate: slow — examples/enf.toml through onset and propagation, about 830 increments, about 100 s (CI: the compliance before onset)"]
fn enf_curve_follows_corrected_beam_theory() {
    let (out, summary) = run_cli("enf", &read_example("enf"), true);
    let points = enf_curve(&out);
    let enf = enf_specimen(1719.0);
    let (dc, pc) = enf.onset(ENF_A0);
    let last = *points.last().unwrap();
    assert!((last.0 - 0.00415).abs() < 1e-9, "the curve stops at δ = {} m", last.0);
    // before onset: the compliance of the precracked beam
    let (d0, p0) = points[0];
    let c0 = d0 / p0;
    eprintln!("ENF: C = {c0:.5e} m/N at δ = {:.3} mm, CBT {:.5e}", 1e3 * d0, enf.compliance(ENF_A0));
    assert!(d0 < 0.1 * dc);
    assert!((c0 / enf.compliance(ENF_A0) - 1.0).abs() < 0.01, "compliance {c0:e}");
    let whole = cbt::curve_error(&points, &enf, ENF_A0);
    let branch = enf_branch_error(&points, &enf);
    let peak = points.iter().map(|p| p.1).fold(0.0, f64::max);
    eprintln!(
        "ENF: P_c = {pc:.2} N at {:.3} mm; peak {peak:.2} N ({:+.2} %); {} points; whole-curve error {:.2} %, branch \
         past 1.05 δ_c {:.2} % of P_c",
        1e3 * dc,
        100.0 * (peak / pc - 1.0),
        points.len(),
        100.0 * whole,
        100.0 * branch
    );
    assert!(points.iter().filter(|p| p.0 > 1.05 * dc).count() >= 50, "too few points on the branch");
    common::figure("enf.branch_error", 100.0 * branch, "%", "≤ 3 % of P_c past 1.05 δ_c (corrected beam theory)");
    assert!(branch < 0.03, "branch error {branch}");
    common::figure(
        "enf.whole_curve_error",
        100.0 * whole,
        "%",
        "≤ 3 % of P_c over the whole curve (corrected beam theory)",
    );
    common::figure("enf.peak_below_pc", 100.0 * (1.0 - peak / pc), "%", "reported: the process zone rounds CBT's cusp");
    assert!(whole < 0.03, "whole-curve error {whole}");
    // CBT's crack at the last deflection lies just past the process zone's
    // front (the last damaged point): the computed branch rides above
    // CBT's (the load higher at the same deflection, so the crack shorter)
    let i = &summary["delamination"]["interfaces"][0];
    let cracked = i["delaminated_m2"].as_f64().unwrap() / 0.0254;
    let damaged = cracked + i["process_zone_m2"].as_f64().unwrap() / 0.0254;
    let exact = enf.branch_crack(ENF_A0, last.0);
    eprintln!(
        "ENF: d = 1 to {:.3} mm, d > 0 to {:.3} mm, CBT crack {:.3} mm",
        1e3 * cracked,
        1e3 * damaged,
        1e3 * exact
    );
    assert!(cracked < exact, "CBT's crack {exact} m behind the delaminated points ({cracked} m)");
    common::known_limit(
        "enf.crack_past_process_zone",
        1e3 * (exact - damaged),
        "mm",
        0.2,
        0.5,
        "CBT's crack at the last deflection past the last damaged interface point",
    );
    // the dissipation lies between G_IIc times the delaminated and the
    // damaged growth (a process-zone point has dissipated less than G_IIc)
    let dissipated = i["dissipated_j"].as_f64().unwrap();
    let (low, high) = (1719.0 * 0.0254 * (cracked - ENF_A0), 1719.0 * 0.0254 * (damaged - ENF_A0));
    eprintln!("ENF: dissipated {dissipated:.4} J, G_IIc ΔA from {low:.4} to {high:.4} J");
    assert!(low < dissipated && dissipated < high, "dissipated {dissipated} J");
    // no interpenetration behind the crack: the opening just below and
    // above the interface, δ3 ≥ −0.1 µm (the penalty lets the compressed
    // faces overlap by p/K, p/(1.08e14 Pa/m))
    let c = common::csv_columns(&out.join("history_probes.csv"));
    for y in [5, 20, 35] {
        let gap = c[&format!("above_{y}.u_z")].iter().zip(&c[&format!("below_{y}.u_z")]).map(|(a, b)| a - b);
        let least = gap.fold(f64::INFINITY, f64::min);
        eprintln!("ENF: least opening at y = {y} mm: {least:.3e} m");
        assert!(least > -1e-7, "the arms pass through each other at y = {y} mm by {least} m");
    }
}

/// G_IIc changed by ±10 % moves the ENF curve out of the 3 % band around
/// the original closed form, and keeps it within 3 % of the closed form of
/// the changed toughness (design48 §3.4; the whole-curve error as in
/// `enf_curve_follows_corrected_beam_theory`; measured −10 %: 10.9 % and
/// 2.76 %, +10 %: 13.9 % and 2.78 %). Both run in the validation
/// (−10 % here, +10 % in `enf_curve_moves_with_a_higher_toughness`); CI
/// keeps the original curve.
#[test]
#[ignore = "validate: slow — the ENF with G_IIc lowered by 10 % (about 2 min; CI keeps the original curve)"]
fn enf_curve_moves_with_the_toughness() {
    enf_moves("giic_down", 0.9);
}

/// `enf_curve_moves_with_the_toughness` with G_IIc raised by 10 %.
#[test]
#[ignore = "validate: slow — the ENF curve with G_IIc raised by 10 % (about 1 min)"]
fn enf_curve_moves_with_a_higher_toughness() {
    enf_moves("giic_up", 1.1);
}

/// The ENF with G_IIc times `factor`, the whole curve outside the 3 % band
/// of the original closed form, inside that of its own (the whole-curve
/// error of `enf_curve_follows_corrected_beam_theory`; with +10 % the
/// onset moves to 4.03 mm, and the curve, which stops at 4.15 mm, has no
/// point past 1.05 δ_c for a branch error).
fn enf_moves(name: &str, factor: f64) {
    let text = read_example("enf");
    assert!(text.contains("giic = 1719.0"));
    let text = text.replace("giic = 1719.0", &format!("giic = {}", 1719.0 * factor));
    let (out, _) = run_cli(name, &text, true);
    let points = enf_curve(&out);
    let original = cbt::curve_error(&points, &enf_specimen(1719.0), ENF_A0);
    let own = cbt::curve_error(&points, &enf_specimen(1719.0 * factor), ENF_A0);
    eprintln!(
        "{name}: whole-curve error against the original CBT {:.2} %, against its own {:.2} %",
        100.0 * original,
        100.0 * own
    );
    common::figure(&format!("enf_{name}.whole_original"), 100.0 * original, "%", "> 3 %: outside the original band");
    common::figure(&format!("enf_{name}.whole_own"), 100.0 * own, "%", "< 3 %: within its own closed form's band");
    assert!(original > 0.03, "{name}: within 3 % of the original curve ({original})");
    assert!(own < 0.03, "{name}: not within 3 % of its own curve ({own})");
}

/// CalculiX's deck has no twin of a cohesive interface (its plies share
/// their nodes): `export-ccx` and `verify` refuse the model by the key that
/// asks for one, before writing anything.
#[test]
fn calculix_export_refuses_cohesive_interfaces_by_key() {
    let dir = common::scratch_dir("delamination", "ccx");
    let model = dir.join("dcb.toml");
    std::fs::write(&model, example()).unwrap();
    for command in ["export-ccx", "verify"] {
        let out = dir.join(command);
        let run =
            common::cufem().args([command, model.to_str().unwrap(), "--out", out.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{command} ran");
        assert!(
            err.contains("bodies[0].section.interfaces[0]") && err.contains("cohesive interface"),
            "{command}: {err}"
        );
        assert!(!out.join("model.inp").exists(), "{command} wrote a deck");
    }
}

/// examples/dcb_arm_forces.toml (the DCB loaded by forces on its arms,
/// `±200` N at λ = 1 on each arm's end face, traced by path following held
/// to its dissipation per increment once it dissipates,
/// `solver.constraint = "dissipation"`, to an opening of 10 mm), its
/// interface's law closed by `viscosity` (`" }"`: the example's, none): the
/// points `(δ, P)` and the summary.
fn dcb_by_dissipation(name: &str, viscosity: &str) -> (Vec<(f64, f64)>, Value) {
    let text = read_example("dcb_arm_forces");
    let law = "normal_strength = 80e6 }";
    assert_eq!(text.matches(law).count(), 1, "the example's law changed");
    let text = text.replace(law, &format!("normal_strength = 80e6{viscosity}"));
    let (out, summary) = run_cli(name, &text, true);
    // 12 nodes on each arm's face
    let total = 12.0 * 16.666666666666668;
    let c = common::csv_columns(&out.join("history_probes.csv"));
    let points = c["upper_end.u_z"]
        .iter()
        .zip(&c["lower_end.u_z"])
        .zip(&c["lambda"])
        .map(|((u, d), l)| (u - d, l * total))
        .collect();
    (points, summary)
}

/// The DCB under arm forces (`dcb_by_dissipation`), as shipped (without
/// viscosity) and with examples/dcb.toml's `1e-5` (over the path's
/// pseudo-time): through
/// the peak, where λ turns back, to an opening of 10 mm. Under load
/// control a point past the peak carries less than the peak's load, which
/// only a path following that lets λ fall can reach. Both curves within
/// the example's `3 %` of P_c of corrected beam theory (Williams 1989,
/// tests/common/cbt.rs), the law's dissipation G_Ic times the new crack
/// (within 5 %, as the example). Measured: `2.1 %` each, `35`–`36` points,
/// no cutback; with G_Ic `+10 %` in the model the peak is λ `0.719`
/// instead of `0.686`, `143.8` N: `3.6 %` of P_c above the closed form's,
/// and fails. The same model held by the
/// cylinder stalls just past the peak ("the arc-length constraint has no
/// real root": the displacements' change turns as the crack grows), and
/// without viscosity Newton cycles at the crack front before it.
#[test]
fn dcb_under_arm_forces_is_traced_past_its_peak_by_its_dissipation() {
    let dcb = specimen(969.0);
    let (dc, pc) = dcb.onset(A0);
    for (name, viscosity) in [("dcb_dissipation", " }"), ("dcb_dissipation_viscous", ", viscosity = 1e-5 }")] {
        let (points, summary) = dcb_by_dissipation(name, viscosity);
        let error = cbt::curve_error(&points, &dcb, A0);
        let last = *points.last().unwrap();
        let past = points.iter().filter(|p| p.0 > dc).count();
        eprintln!(
            "{name}: P_c = {pc:.2} N at {:.3} mm; {} points, {past} past onset, to δ = {:.3} mm; curve error {:.2} % of P_c",
            1e3 * dc,
            points.len(),
            1e3 * last.0,
            100.0 * error
        );
        common::figure(&format!("{name}.curve_error"), 100.0 * error, "%", "within 3 % of P_c (issue 48)");
        assert!(last.0 >= 0.01, "{name}: the path stopped at δ = {} m", last.0);
        assert!(past >= 15, "{name}: {past} points past onset");
        assert!(error < 0.03, "{name}: curve error {error}");
        // λ turned back: the peak, and loads well below it on the branch
        let peak = points.iter().map(|p| p.1).fold(0.0, f64::max);
        assert!(last.1 < 0.8 * peak, "{name}: the last load {} N against the peak {peak} N", last.1);
        let d = &summary["delamination"];
        let a = d["area_m2"].as_f64().unwrap() / 0.0254;
        let grown = 969.0 * 0.0254 * (a - A0);
        let dissipated = d["dissipated_j"].as_f64().unwrap();
        assert!(
            (dissipated / grown - 1.0).abs() < 0.05,
            "{name}: dissipated {dissipated} J against G_Ic ΔA = {grown} J"
        );
        // the viscosity's work over the pseudo-time: some, and small
        let viscous = d["viscous_j"].as_f64().unwrap();
        assert!(
            if viscosity == " }" { viscous == 0.0 } else { viscous > 0.0 && viscous < 0.05 * dissipated },
            "{viscous}"
        );
    }
}
