//! Error estimates of each buckling mode (`post::mode_error`, issue 49):
//! the recovered-stress estimate of each mode shape and the error of the
//! critical load factor it implies, `(μ_h − μ) / μ_h ≈ ‖e‖² / φᵀ K₀ φ`,
//! against the true error of each factor measured against a refined run of
//! the same model (the modes in the same order: their factors are apart).

use cufem::analysis::Solution;
use cufem::setup::Model;
use cufem::values::{PointValues, locate_in_model};

mod common;

fn solve(text: &str) -> (Model, Solution) {
    (Model::parse(text).unwrap(), common::run(text))
}

/// A steel channel column (`100 × 50 mm`, walls `2 mm`, `0.5 m`), clamped at
/// its foot and pressed at its head: its first modes are the flanges'
/// local buckling, a few half-waves along the column, which a coarse
/// section and axis resolve poorly. `flange` × `web` L9 along its walls,
/// `axis` B4.
fn channel(flange: usize, web: usize, axis: usize) -> String {
    format!(
        r#"
[analysis]
type = "buckling"
modes = 4

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "column"
material = "steel"
section = {{ shape = "channel", element = "L9", origin = [0.0, -0.05], width = 0.05, height = 0.1, web_thickness = 0.002, flange_thickness = 0.002, along_flange = {flange}, along_web = {web}, through = 1 }}
axis = {{ element = "B4", from = 0.0, to = 0.5, elements = {axis} }}

[[constraints]]
name = "foot"
body = "column"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "head"
body = "column"
where = {{ y = 0.5 }}
total_force = [0.0, -1.0, 0.0]
"#
    )
}

/// Per mode of `coarse`: the mode of `fine` it matches (the largest
/// modal assurance criterion, both sampled at the coarse mesh's nodes, if
/// above 0.9), the estimated relative error of its factor and the true one,
/// `(μ_h − μ) / μ_h` with `μ` the matched factor of `fine`.
fn compare(coarse: &(Model, Solution), fine: &(Model, Solution)) -> Vec<(Option<usize>, f64, f64)> {
    let ((cm, cs), (fm, fs)) = (coarse, fine);
    let (c, f) = (cs.buckling.as_ref().unwrap(), fs.buckling.as_ref().unwrap());
    let points: Vec<PointValues> = (0..cm.mesh.n_nodes())
        .map(|n| PointValues::new(&fm.mesh.bodies[0], &locate_in_model(&fm.mesh, Some(0), cm.mesh.coords(n))[0]))
        .collect();
    let sampled: Vec<Vec<f64>> =
        f.modes.iter().map(|m| points.iter().flat_map(|p| p.displacement(m)).collect()).collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    c.modes
        .iter()
        .zip(&c.factors)
        .zip(&c.errors)
        .map(|((a, mu_h), e)| {
            let macs = sampled.iter().map(|b| dot(a, b).powi(2) / (dot(a, a) * dot(b, b)));
            let (j, best) = macs.enumerate().fold((0, 0.0), |b, (j, v)| if v > b.1 { (j, v) } else { b });
            ((best > 0.9).then_some(j), e.eigenvalue, 1.0 - f.factors[j] / mu_h)
        })
        .collect()
}

/// examples/column_buckling.toml (a clamped–free steel column, `20 × 20 mm`,
/// `1 m`) with `n` beam elements of kind `axis` and `sec` × `sec` L9.
fn column(axis: &str, n: usize, sec: usize) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/column_buckling.toml")).unwrap();
    let (old_axis, old_sec) = (
        "axis = { element = \"B4\", from = 0.0, to = 1.0, elements = 10 }",
        "elements = 1 }, z = { from = -0.01, to = 0.01, elements = 1 }",
    );
    assert!(text.contains(old_axis) && text.contains(old_sec));
    text.replace(old_axis, &format!("axis = {{ element = \"{axis}\", from = 0.0, to = 1.0, elements = {n} }}"))
        .replace(old_sec, &format!("elements = {sec} }}, z = {{ from = -0.01, to = 0.01, elements = {sec} }}"))
}

/// The column's factors and their estimates on coarse axes against 20 B4 ×
/// 2 × 2 L9, mode by mode in order (each comes as a pair of equal factors,
/// the two bending planes of the square section, so a MAC would pair them
/// arbitrarily). Issue 49 asks for an effectivity (estimated over true
/// error) in 0.5–2; measured `0.55`–`0.83` over the first two pairs on B3 × 2,
/// B3 × 4 and B4 × 2. A column of B2, which locks in shear (the first factor
/// 16 times the reference on 8 B2), is estimated above 70 % (true 94 %).
#[test]
fn a_columns_buckling_estimates_follow_the_true_factor_errors() {
    let (_, fine) = solve(&column("B4", 20, 2));
    let reference = &fine.buckling.as_ref().unwrap().factors;
    // the reference against Euler, π² E I / (4 L²) = 6,580 N (I = b⁴/12):
    // within 0.2 % (the true errors below are 2 % and more)
    let euler = std::f64::consts::PI.powi(2) * 200e9 * 0.02f64.powi(4) / 12.0 / 4.0;
    assert!((reference[0] / euler - 1.0).abs() < 2e-3, "{} against {euler}", reference[0]);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (kind, n) in [("B3", 2), ("B3", 4), ("B4", 2)] {
        let (_, coarse) = solve(&column(kind, n, 1));
        let b = coarse.buckling.as_ref().unwrap();
        assert_eq!(b.factors.len(), 4);
        for (k, (mu_h, e)) in b.factors.iter().zip(&b.errors).enumerate() {
            let truth = 1.0 - reference[k] / mu_h;
            let effectivity = e.eigenvalue / truth;
            assert!(truth > 0.02, "{kind} × {n}, mode {}: a coarse mesh (true {truth})", k + 1);
            assert!((0.5..=2.0).contains(&effectivity), "{kind} × {n}, mode {}: effectivity {effectivity}", k + 1);
            (lo, hi) = (lo.min(effectivity), hi.max(effectivity));
        }
    }
    let check = "estimated over true factor error, every mode of B3 × 2, B3 × 4 and B4 × 2: within 0.5–2";
    common::figure("buckling_error.column.effectivity_min", lo, "", check);
    common::figure("buckling_error.column.effectivity_max", hi, "", check);
    let (_, locked) = solve(&column("B2", 8, 1));
    let b = locked.buckling.as_ref().unwrap();
    assert!(b.factors[0] > 10.0 * reference[0], "B2 locks: {}", b.factors[0]);
    assert!(b.errors[0].eigenvalue > 0.7, "and is estimated so: {}", b.errors[0].eigenvalue);
    // two B2 × one L4, locked harder (the factor 134 times Euler's): the
    // recovery sees the locked stresses, and the factor is estimated
    // `12.5 %` off against a true `99.3 %` (a new-user review) — a known
    // limit, asserted from both sides (docs/limitations.md)
    let text = column("B2", 2, 1).replacen("element = \"L9\"", "element = \"L4\"", 1);
    let (_, locked) = solve(&text);
    let b = locked.buckling.as_ref().unwrap();
    let truth = 1.0 - reference[0] / b.factors[0];
    assert!(truth > 0.99, "two B2 × one L4 lock: {}", b.factors[0]);
    let effectivity = b.errors[0].eigenvalue / truth;
    common::known_limit("buckling_error.column.locked_2b2_effectivity", effectivity, "", 0.1, 0.2, "a locked column");
}

/// The shipped column (examples/column_buckling.toml, 10 B4 × 1 L9) against
/// its mesh refined twice (40 B4 × 4 × 4 L9, 29,403 DOF), mode by mode in
/// order (pairs of equal factors, as above). Its true factor errors are
/// the section's (`0.27`–`0.31 %`: one L9 across a solid section, the
/// axis converged), which a patch of one section element sees in part,
/// through its faces' shear tractions held at zero (`post::spr`):
/// measured effectivity `0.65`–`0.68` (`0.57`–`0.61` with the element
/// interpolated), in issue 49's `0.5`–`2`.
/// (The reference's own error: its first factor moved `12.8` N from 1 to 2
/// and `5.2` N from 2 to 4 L9 across, so by Richardson it lies about `3.5` N,
/// `0.05 %`, above the limit, a sixth of the shipped mesh's error.)
#[test]
fn the_shipped_columns_buckling_estimates_follow_the_true_factor_errors() {
    let (_, coarse) = solve(&column("B4", 10, 1));
    let (_, fine) = solve(&column("B4", 40, 4));
    let (b, reference) = (coarse.buckling.as_ref().unwrap(), &fine.buckling.as_ref().unwrap().factors);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (k, (mu_h, e)) in b.factors.iter().zip(&b.errors).enumerate() {
        let truth = 1.0 - reference[k] / mu_h;
        let effectivity = e.eigenvalue / truth;
        eprintln!(
            "column_buckling mode {}: true {truth:.3e}, estimated {:.3e}, effectivity {effectivity:.3}",
            k + 1,
            e.eigenvalue
        );
        assert!(truth > 1e-3, "mode {}: true error {truth}", k + 1);
        assert!((0.5..=2.0).contains(&effectivity), "mode {}: effectivity {effectivity}", k + 1);
        (lo, hi) = (lo.min(effectivity), hi.max(effectivity));
    }
    let check =
        "estimated over true factor error, examples/column_buckling.toml against 40 B4 × 4 × 4 L9: within 0.5–2";
    common::figure("buckling_error.shipped_column.effectivity_min", lo, "", check);
    common::figure("buckling_error.shipped_column.effectivity_max", hi, "", check);
}

/// The channel column's local modes on `2 × 4` L9 and 8 B4 against
/// `16 × 32` L9 and 32 B4 (116,109 DOF; modes matched by their MAC), whose
/// own factors lie `0.2`–`0.4 %` below those of `8 × 16` L9 and 32 B4
/// (`the_channel_columns_reference_is_converged`),
/// against the coarse mesh's true errors of `1.7`–`6.6 %`: the estimates
/// lie at `0.83`–`1.64` times their true errors, and with the walls graded
/// to a `2` mm element at each junction (`junction_element`, what `--adapt`
/// sets) at `0.88`–`0.98` times, both within issue 49's `0.5`–`2`. With
/// section patches reaching round the walls' re-entrant corners
/// (`post::spr`) the uniform walls' estimates were `2.4`–`6.9` times the
/// true errors.
#[test]
fn a_channel_columns_buckling_estimates_follow_its_local_modes_errors() {
    let fine = solve(&channel(16, 32, 32));
    let effectivity = |coarse: &(Model, Solution)| {
        let rows = compare(coarse, &fine);
        assert_eq!(rows.len(), 4);
        rows.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &(j, est, truth)| {
            assert!(j.is_some() && truth > 0.005, "a matched, unconverged mode ({truth})");
            (lo.min(est / truth), hi.max(est / truth))
        })
    };
    let (lo, hi) = effectivity(&solve(&channel(2, 4, 8)));
    common::figure("buckling_error.channel.effectivity_min", lo, "", "at least 0.5");
    common::figure("buckling_error.channel.effectivity_max", hi, "", "at most 2");
    assert!(lo >= 0.5 && hi <= 2.0, "uniform walls: {lo} – {hi}");
    let graded = channel(2, 4, 8).replace("through = 1 }", "through = 1, junction_element = 0.002 }");
    assert!(graded.contains("junction_element"));
    let (lo, hi) = effectivity(&solve(&graded));
    common::figure("buckling_error.channel.graded_effectivity_min", lo, "", "at least 0.5");
    common::figure("buckling_error.channel.graded_effectivity_max", hi, "", "at most 2");
    assert!(lo >= 0.5 && hi <= 2.0, "graded walls: {lo} – {hi}");
}

/// The reference of `a_channel_columns_buckling_estimates_follow_its_local_modes_errors`
/// (`16 × 32` L9, 32 B4) against the same column on half its section
/// divisions (`8 × 16` L9, 32 B4) and on half its axis elements (`16 × 32`
/// L9, 16 B4), mode by mode (matched by their MAC): each halving moves its
/// four local factors by less than `0.5 %` (measured: section
/// `0.20`–`0.41 %`, axis `0.03`–`0.45 %`), a fraction of the coarse mesh's
/// true errors (`1.7`–`6.6 %`) that the estimates are measured against. With
/// eigenvalue errors falling as h⁴ (L9) and h⁶ (B4), the reference's own
/// error is then about a fifteenth of those moves.
#[test]
#[ignore = "validate: slow — the channel column's reference and its two halvings, about 25 s"]
fn the_channel_columns_reference_is_converged() {
    let fine = solve(&channel(16, 32, 32));
    for (name, coarse) in [("section", channel(8, 16, 32)), ("axis", channel(16, 32, 16))] {
        let rows = compare(&solve(&coarse), &fine);
        assert_eq!(rows.len(), 4);
        let largest = rows.iter().fold(0.0f64, |m, &(j, _, truth)| {
            assert!(j.is_some(), "{name}: a mode without its match in the reference");
            m.max(truth.abs())
        });
        eprintln!("channel reference, {name} halved: factors {:?}", rows.iter().map(|r| r.2).collect::<Vec<_>>());
        common::figure(
            &format!("buckling_error.channel.reference_{name}_halved"),
            100.0 * largest,
            "%",
            "below 0.5 %: the reference is converged",
        );
        assert!(largest < 0.005, "{name} halved moves a factor by {largest}");
    }
}

/// `--adapt` on a buckling analysis (`adapt::measure`: a cycle is measured
/// by the largest estimated critical load factor error of the modes
/// followed, and refined where those modes hold their estimates): the
/// column from 2 B3 × 1 L9, following its lowest pair (`adapt.modes = 2`)
/// to `0.5 %`, against the reference of
/// [`a_columns_buckling_estimates_follow_the_true_factor_errors`].
///
/// Measured: the estimate falls `5.07 → 1.98 → 1.21 → 0.58 → 0.34 %` over
/// four cycles (`1,425` DOF: 2 × 2 L9, 9 B3 graded towards the clamp), the
/// last factor `0.46 %` above the reference (effectivity `0.73`), and the
/// written model file gives the same factor. The first cycle doubles the
/// section, where the clamp's three-dimensional stresses hold much of the
/// estimate but little of the factor's error: uniform axis refinement of the
/// given section reaches the tolerance in fewer DOF (16 B3 × 1 L9, `891`
/// DOF, true `0.30 %`) — a known limit (docs/limitations.md).
#[test]
fn adapt_on_buckling_brings_the_columns_critical_load_within_its_tolerance() {
    use cufem::adapt::Source;
    let text = column("B3", 2, 1) + "[adapt]\nmodes = 2\ntolerance = 0.005\n";
    let start = Model::parse(&text).unwrap();
    let settings = start.adapt.unwrap();
    let source = Source { text: &text, base: std::path::Path::new("."), limits: cufem::setup::Limits::none() };
    let mut estimates = Vec::new();
    let (model, last) = cufem::adapt::run(
        start,
        source,
        &settings,
        &Default::default(),
        &mut cufem::analysis::Silent,
        &mut |c, _, s| {
            let b = s.buckling.as_ref().unwrap();
            // the cycle's measure: the largest estimate of the two modes followed
            let followed = c.modes.as_ref().unwrap();
            assert_eq!(followed.quantity, cufem::analysis::ModeQuantity::LoadFactor);
            assert_eq!(followed.values, b.factors[..2]);
            assert_eq!(c.estimate, b.errors[..2].iter().map(|e| e.eigenvalue).fold(0.0, f64::max));
            estimates.push(c.estimate)
        },
    )
    .unwrap();
    let adapt = last.adapt.as_ref().unwrap();
    assert!(adapt.stop.contains("below the tolerance 0.50 %"), "{}", adapt.stop);
    assert!(estimates[0] > 0.05 && estimates.len() >= 3, "{estimates:?}");
    assert!(*estimates.last().unwrap() < 0.005, "{estimates:?}");
    // the true error of the adapted factor, against the reference
    let (_, fine) = solve(&column("B4", 20, 2));
    let reference = fine.buckling.as_ref().unwrap().factors[0];
    let mu_h = last.buckling.as_ref().unwrap().factors[0];
    let truth = 1.0 - reference / mu_h;
    common::figure("buckling_error.adapt.true_error", 100.0 * truth, "%", "adapted to 0.5 %: within 1 %");
    assert!(truth > 0.0 && truth < 0.01, "{mu_h} against {reference}");
    let effectivity = estimates.last().unwrap() / truth;
    assert!((0.5..=2.0).contains(&effectivity), "{effectivity}");
    // the model file written gives the adapted factor again
    let rerun = common::run(&adapt.model_file);
    assert_eq!(Model::parse(&adapt.model_file).unwrap().n_dofs(), model.n_dofs());
    assert!((rerun.buckling.as_ref().unwrap().factors[0] / mu_h - 1.0).abs() < 1e-9);
    // against uniform refinement of the axis alone: a known limit
    let (uniform, u) = solve(&column("B3", 16, 1));
    assert!(1.0 - reference / u.buckling.as_ref().unwrap().factors[0] < 0.005);
    let ratio = model.n_dofs() as f64 / uniform.n_dofs() as f64;
    let what = "adapted DOF over those of 16 B3 × 1 L9 (uniform axis refinement within the same tolerance)";
    common::known_limit("buckling_error.adapt.dof_over_uniform_axis", ratio, "", 1.4, 1.8, what);
}
