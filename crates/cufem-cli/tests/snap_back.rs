//! Path following through a ply crack's snap-back (issue 48):
//! `examples/notched_strip_snap_back.toml`, a double-edge notched ply strip
//! whose long arms store more elastic energy at the peak than the crack
//! dissipates, pulled by an end force whose factor λ is an unknown held by
//! the dissipation constraint. Checked against displacement control of the
//! same strip (the peak), against the energy the arms must give back (the
//! snap-back), and the path's dissipation against the damage law's.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::Path;

/// The example's text.
fn example() -> String {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/notched_strip_snap_back.toml");
    std::fs::read_to_string(path).unwrap()
}

/// The example's reference load (N): `total_force` at λ = 1.
const FORCE: f64 = 10.0e3;

/// `G_FT × ligament × depth` = 133.3e3 J/m² × 3.2 mm × 1 mm (the crack
/// band's promise for a crack through the ligament, Bažant & Oh 1983).
const CRACK_ENERGY: f64 = 133.3e3 * 3.2e-3 * 1e-3;

/// The strip pulled through its peak by the end's displacement (load
/// control of a prescribed 0.293 mm, increments of 1e-3): the largest
/// reaction (N) and whether it came before the last increment.
fn displacement_controlled_peak() -> (f64, bool) {
    let text = example();
    let solver = text.find("[solver]").unwrap();
    let materials = text.find("[[materials]]").unwrap();
    let load = text.find("[[loads]]").unwrap();
    let probes = text.find("[[probes]]").unwrap();
    let length = text[load..probes].split("x = ").nth(1).unwrap().split(' ').next().unwrap().to_string();
    let text = format!(
        "{}[solver]\nincrements = 1000\nmax_increment = 0.001\nmax_increments = 2000\n\n{}[[constraints]]\nname = \
         \"pull\"\nbody = \"strip\"\nwhere = {{ x = {length} }}\ndisplacement = {{ x = 2.93e-4 }}\n\n{}",
        &text[..solver],
        &text[materials..load],
        &text[probes..]
    );
    let (out, _) = common::run_text("snap_back", "displacement", &text);
    let r = common::csv_columns(&out.join("history_pull.csv"))["r_x"].clone();
    let k = peak(&r);
    (r[k], k + 1 < r.len())
}

/// The path's dissipation `Σ ½ (λ₀ fᵀΔu − Δλ fᵀu₀)` from the load factors
/// and the end's displacements (`fᵀu = P u`: a uniform traction on an end
/// that stays flat), and the largest of one increment (J).
fn path_dissipation(lambda: &[f64], u: &[f64]) -> (f64, f64) {
    let (mut path, mut largest) = (0.0, 0.0f64);
    let (mut l0, mut u0) = (0.0, 0.0);
    for (&l, &x) in lambda.iter().zip(u) {
        let step = 0.5 * FORCE * (l0 * (x - u0) - (l - l0) * u0);
        (path, largest) = (path + step, largest.max(step));
        (l0, u0) = (l, x);
    }
    (path, largest)
}

/// The index of a history's largest value.
fn peak(values: &[f64]) -> usize {
    (0..values.len()).fold(0, |m, i| if values[i] > values[m] { i } else { m })
}

#[test]
fn the_strip_is_followed_through_its_snap_back_by_its_dissipation() {
    let (out, summary) = common::run_text("snap_back", "example", &example());
    assert_eq!(summary["path"]["end"], "displacement", "the run ends on its stop (the crack through)");
    let c = common::csv_columns(&out.join("history_probes.csv"));
    let (lambda, u) = (&c["lambda"], &c["end.u_x"]);
    let k = peak(lambda);

    // the peak: displacement control reaches the same one (the arms are
    // 20 mm long, so how the end is pulled does not reach the ligament);
    // measured 0.538 both, 0.09 % apart (with a first Δλ of 1e-2 the path's
    // peak is 2 % low: the pre-peak increments set the notch roots' damage)
    let (peak, before_end) = displacement_controlled_peak();
    assert!(before_end, "displacement control passed its peak");
    let p = lambda[k] * FORCE;
    assert!((p - peak).abs() < 5e-3 * peak, "peak {p} N by the path, {peak} N by displacement control");

    // the snap-back: the arms store ½ P u at the peak, more than the crack
    // can dissipate, so past it the end's displacement falls with the force
    let stored = 0.5 * p * u[k];
    assert!(stored > 1.5 * CRACK_ENERGY, "stored {stored} J at the peak");
    let low = (k..lambda.len()).find(|&i| lambda[i] < 0.1 * lambda[k]).expect("the force falls below a tenth");
    assert!(u[low] < 0.7 * u[k], "end at {} m with λ {}, {} m at the peak", u[low], lambda[low], u[k]);
    assert!((k..low).all(|i| lambda[i + 1] <= lambda[i] + 1e-9), "λ falls monotonically past the peak");

    // the path's dissipation, ½ (λ₀ fᵀΔu − Δλ fᵀu₀) summed from the end's
    // displacement (fᵀu = P u: a uniform traction on an end that stays flat),
    // against the damage law's sums over its points: two independent
    // bookkeepings of the same energy (measured 0.45 % apart)
    let (path, largest) = path_dissipation(lambda, u);
    // and no increment dissipated more than max_dissipation = 1 mJ (to the
    // probe's reading of fᵀu: measured 1.0007e-3; without the key one took
    // 0.17 J, two fifths of the crack's energy)
    assert!(largest < 1.02e-3, "an increment dissipated {largest} J");
    let law = summary["damage"]["dissipated_total_j"].as_f64().unwrap();
    assert!((path - law).abs() < 0.02 * law, "path {path} J, law {law} J");
    // a known limit (docs/limitations.md): the double-edge notched band
    // dissipates 1.31 G_FT A, where the single-edge notched strips under
    // displacement control dissipate 1.06-1.07 G_FT A
    let ratio = law / CRACK_ENERGY;
    assert!((1.25..1.37).contains(&ratio), "dissipated {law} J = {ratio} G_FT A");
    // the crack crosses the ligament in the notches' column, every row of it
    // (where the single-edge strips' turns away: ply_damage.rs): the cells
    // past half fibre-tension damage are the column's four
    let cells = common::cells_past_half(&out.join("result.vtu"), "d_ft");
    assert_eq!(cells.len(), 4, "{cells:?}");
    assert!(cells.iter().all(|c| (c.0 - 20.4e-3).abs() < 0.4e-3 && (c.1 - 3.2e-3).abs() < 1.6e-3), "{cells:?}");
    // increments that follow the damage: no warning that they do not
    assert!(!summary["warnings"].to_string().contains("released at fixed strain"), "{}", summary["warnings"]);
}

/// Without `max_dissipation` the increments grow with Newton's fast
/// convergence until points jump through their softening within one
/// (measured: 82 increments, the law's sums 1.5 times the release at fixed
/// strain): the run says so and names the key that bounds them, not load
/// stepping's step control, which path following refuses.
#[test]
fn an_unbounded_dissipation_per_increment_is_told() {
    let text = example();
    assert!(text.contains("max_dissipation = 0.001\n"));
    let (_, summary) = common::run_text("snap_back", "unbounded", &text.replace("max_dissipation = 0.001\n", ""));
    let warnings = summary["warnings"].to_string();
    assert!(
        warnings.contains("released at fixed strain") && warnings.contains("(solver.max_dissipation"),
        "{warnings}"
    );
}

#[test]
fn the_largest_dissipation_of_an_increment_is_checked_by_key() {
    let text = example();
    let key = "max_dissipation = 0.001";
    let cases = [
        (text.replace(key, "max_dissipation = -0.001"), "solver.max_dissipation = -0.001"),
        (
            text.replace("matrix_compression = 1e7 }", "matrix_compression = 1e7, fibre_shear = 1.5 }"),
            "materials[0].damage.fibre_shear = 1.5",
        ),
        (
            text.replace("matrix_compression = 1e7 }", "matrix_compression = 1e7, softening_stress = \"plastic\" }"),
            "materials[0].damage.softening_stress: unknown variant `plastic`, expected `effective` or `uniaxial`",
        ),
        (
            text.replace("constraint = \"dissipation\"", "constraint = \"cylinder\""),
            "solver.max_dissipation = 0.001: expected no value without solver.constraint = \"dissipation\"",
        ),
        (
            // load control, the path's other keys gone
            text.replace("control = \"arc_length\"", "control = \"load\"")
                .replace("constraint = \"dissipation\"\n", "")
                .replace("stop = { probe = \"crack_right\", component = \"x\", beyond = 3e-4 }\n", ""),
            "solver.max_dissipation = (given): expected no value without solver.control = \"arc_length\"",
        ),
    ];
    for (t, expect) in cases {
        let e = cufem::Model::parse(&t).unwrap_err().to_string();
        assert!(e.contains(expect), "{expect}: {e}");
    }
    cufem::Model::parse(&text).unwrap();
}

/// The crack-band strips (`examples/notched_strip_band_{mesh}.toml`: the
/// snap-back strip with `fibre_shear = 0`, `softening_stress = "uniaxial"`
/// and `max_damage = 0.9999`, h = 0.8, 0.4, 0.2 mm across the crack path),
/// run as shipped or with the softening line of the effective stress
/// (`uniaxial` false: the key removed): the energy the damage law
/// dissipated over `G_FT A` (returned), after checking that the crack is
/// the notches' column and nothing else, that only fibre tension
/// dissipates, and the path's own dissipation against the law's (`test`
/// names the scratch folders).
fn band_ratio(test: &str, mesh: &str, uniaxial: bool) -> f64 {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join(format!("examples/notched_strip_band_{mesh}.toml"));
    let mut text = std::fs::read_to_string(path).unwrap();
    let key = " softening_stress = \"uniaxial\",";
    assert_eq!(text.matches(key).count(), 1);
    if !uniaxial {
        text = text.replace(key, "");
    }
    let (out, summary) = common::run_text(test, &format!("band_{mesh}_{uniaxial}"), &text);
    assert_eq!(summary["path"]["end"], "displacement", "{mesh}: the run ends on its stop");
    assert_eq!(summary["warnings"].as_array().map_or(0, Vec::len), 0, "{mesh}: {}", summary["warnings"]);
    // the crack: every cell of the notches' column past half damage, no
    // other (3.2 mm / h cells, centred at x = 20 mm + h/2)
    let h: f64 = match mesh {
        "coarse" => 0.8e-3,
        "medium" => 0.4e-3,
        _ => 0.2e-3,
    };
    let cells = common::cells_past_half(&out.join("result.vtu"), "d_ft");
    assert_eq!(cells.len(), (3.2e-3 / h).round() as usize, "{mesh}: {cells:?}");
    assert!(cells.iter().all(|c| (c.0 - 20e-3 - h / 2.0).abs() < 0.1 * h), "{mesh}: {cells:?}");
    // only fibre tension dissipates (the others under 0.1 % of it)
    let modes = &summary["damage"]["dissipated_j"];
    let ft = modes["fibre_tension"].as_f64().unwrap();
    let total = summary["damage"]["dissipated_total_j"].as_f64().unwrap();
    assert!(total - ft < 1e-3 * ft, "{mesh}: {modes}");
    // the path's dissipation against the law's sums (as in the snap-back
    // test above; measured within 0.6 %)
    let c = common::csv_columns(&out.join("history_probes.csv"));
    let (path, _) = path_dissipation(&c["lambda"], &c["end.u_x"]);
    assert!((path - total).abs() < 0.02 * total, "{mesh}: path {path} J, law {total} J");
    let ratio = ft / CRACK_ENERGY;
    println!("{mesh} (uniaxial {uniaxial}): D_FT/(G_FT A) = {ratio:.4}");
    ratio
}

/// The crack band (Bažant & Oh 1983), coarse strip as shipped: `G_FT A`
/// within 2 % (issue 48 asks 5 %; measured 1.015); with the effective
/// stress's softening line (the default) `0.984`, a known limit asserted
/// from both sides (docs/limitations.md; the three meshes are
/// `the_band_strips_dissipate_their_crack_energy_on_three_meshes`).
#[test]
fn the_coarse_band_strip_dissipates_its_crack_energy() {
    let ratio = band_ratio("snap_back_coarse", "coarse", true);
    assert!((ratio - 1.0).abs() < 0.02, "D_FT/(G_FT A) = {ratio}");
    let effective = band_ratio("snap_back_coarse", "coarse", false);
    assert!((0.975..0.995).contains(&effective), "with the effective stress D_FT/(G_FT A) = {effective}");
}

/// The crack band's promise on three meshes (h = 0.8, 0.4, 0.2 mm, each
/// halving the last): as shipped each within 2 % of `G_FT A` and within
/// 5 % of each other (issue 48; measured 1.015, 1.010, 1.004: 1.1 %
/// apart, nearing `G_FT A` as the band narrows). With the effective
/// stress's softening line (the default) a known limit, asserted from both
/// sides: below `G_FT A` and falling as the band narrows (measured 0.984,
/// 0.969, 0.954), the fine strip 3–5 % short.
#[test]
#[ignore = "validate: slow — the three crack-band strips twice, about a minute (CI: the coarse strip)"]
fn the_band_strips_dissipate_their_crack_energy_on_three_meshes() {
    let meshes = ["coarse", "medium", "fine"];
    let shipped: Vec<f64> = meshes.iter().map(|m| band_ratio("snap_back_three", m, true)).collect();
    assert!(shipped.iter().all(|r| (r - 1.0).abs() < 0.02), "D_FT/(G_FT A) = {shipped:?}");
    let (lo, hi) = shipped.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
    assert!(hi / lo - 1.0 < 0.05, "D_FT/(G_FT A) = {shipped:?}");
    let effective: Vec<f64> = meshes.iter().map(|m| band_ratio("snap_back_three", m, false)).collect();
    let w = &effective;
    assert!(w[0] < 1.0 && w[1] < w[0] && w[2] < w[1] && w[2] > 0.95 && w[2] < 0.97, "effective: {w:?}");
}
