//! Linear buckling (issue 26, item 3): critical load factors and modes of
//! `K₀ φ = μ (−K_σ) φ` against the closed forms of Euler and of
//! lateral–torsional and flexural–torsional buckling, and the model-file
//! checks.

use std::path::Path;
use std::process::Command;

use cufem::analysis::{self, Silent};
use cufem::setup::Model;

#[path = "../../../tests/common/mod.rs"]
mod common;

const COLUMN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/column_buckling.toml");

/// `examples/column_buckling.toml` through the CLI: the clamped–free
/// column's first two factors (the two bending planes) within 1 % of
/// Euler's π² E I/(4 L²) = 6,579.7 N, the next two within 1 % of 9 times
/// it (measured +0.37 % and +0.15 %: the 3D clamp's restrained Poisson
/// contraction; shear would lower them). A 10 % error in E, or in K_σ,
/// moves them by 10 %.
#[test]
fn clamped_free_column_buckles_at_euler_load() {
    let out = std::env::temp_dir().join(format!("cufem_column_{}", std::process::id()));
    let status =
        Command::new(env!("CARGO_BIN_EXE_cufem")).args(["run", COLUMN, "--quiet", "--out"]).arg(&out).status().unwrap();
    assert!(status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let b = &summary["buckling"];
    let factors: Vec<f64> = b["factors"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let euler = std::f64::consts::PI.powi(2) * 200e9 * 0.02f64.powi(4) / 12.0 / 4.0;
    eprintln!("factors {factors:?}, Euler {euler}");
    assert_eq!(factors.len(), 4);
    for (f, n) in factors.iter().zip([1.0, 1.0, 9.0, 9.0]) {
        assert!((f - n * euler).abs() < 0.01 * n * euler, "{f} against {}", n * euler);
    }
    // the unit load times the factor, along −y
    let p = b["critical_loads"][0].as_array().unwrap()[1].as_f64().unwrap();
    assert!((p + factors[0]).abs() < 1e-9 * factors[0]);
    for k in 1..=4 {
        assert!(out.join(format!("mode_{k}.vtu")).exists());
        assert_eq!(b["modes"][k - 1], format!("mode_{k}.vtu"));
    }
    // mode_1.vtu holds the shape's strains and stresses at its scale
    // (docs/model-format.md): its largest bending stress over its largest
    // bending strain is E, up to the clamp's restrained contraction
    // (E/(1 − ν²) = 1.10 E to E (1 − ν)/((1 + ν)(1 − 2ν)) = 1.35 E; measured
    // 1.18 E), not the static state's stress (2.9 kPa) over the shape's strain
    let largest = |file: &str, name: &str| {
        common::vtu_array(&out.join(file), Some(name)).iter().fold(0.0f64, |m, v| m.max(v.abs()))
    };
    let modulus = largest("mode_1.vtu", "s_yy") / largest("mode_1.vtu", "e_yy");
    assert!((1.0..1.35).contains(&(modulus / 200e9)), "σ/ε = {modulus:e} Pa");
    assert!(largest("result.vtu", "s_yy") < 1e4, "the static state under its unit load");
    // buckling.csv: the same table, a row per mode, the load along −y
    let csv = common::csv_columns(&out.join("buckling.csv"));
    assert_eq!(csv["mode"], [1.0, 2.0, 3.0, 4.0]);
    for (k, f) in factors.iter().enumerate() {
        assert!((csv["load_factor"][k] - f).abs() < 1e-6 * f, "{csv:?}");
        assert!((csv["critical_load_y"][k] + f).abs() < 1e-6 * f, "{csv:?}");
        assert_eq!([csv["critical_load_x"][k], csv["critical_load_z"][k]], [0.0, 0.0]);
    }
    assert!(!csv.contains_key("full_critical_load_y"), "no symmetry planes: no full structure");
    // each factor's estimated error (tests/buckling_error.rs), the same in
    // both files: the computed first factor lies 0.37 % above Euler's, of
    // which the mesh's share is a fraction (tests/buckling_error.rs's 20 B4
    // reference is 0.18 % above it), so positive and below that
    let errors: Vec<f64> = b["factor_errors"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(errors, csv["factor_error"]);
    assert!(errors[0] > 0.0 && errors[0] < factors[0] / euler - 1.0, "{errors:?}");
    std::fs::remove_dir_all(&out).ok();
}

/// The first mode's shape: the lateral deflection of the column's axis
/// follows the Euler mode 1 − cos(π y/(2L)), scaled to the tip, within 1 %
/// of the tip value at every axis node.
#[test]
fn the_first_mode_is_eulers_shape() {
    let model = Model::from_file(Path::new(COLUMN)).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let b = sol.buckling.as_ref().unwrap();
    let mode = &b.modes[0];
    let axis: Vec<(f64, [f64; 3])> = (0..model.mesh.n_nodes())
        .filter_map(|n| {
            let [x, y, z] = model.mesh.coords(n);
            (x.abs() < 1e-12 && z.abs() < 1e-12).then(|| (y, [mode[3 * n], mode[3 * n + 1], mode[3 * n + 2]]))
        })
        .collect();
    assert_eq!(axis.len(), 31);
    // the lateral direction of this mode (the pair's two planes mix)
    let tip = axis.iter().find(|(y, _)| (y - 1.0).abs() < 1e-12).unwrap().1;
    let scale = (tip[0] * tip[0] + tip[2] * tip[2]).sqrt();
    for (y, u) in &axis {
        let lateral = (u[0] * tip[0] + u[2] * tip[2]) / scale;
        let euler = scale * (1.0 - (std::f64::consts::FRAC_PI_2 * y).cos());
        assert!((lateral - euler).abs() < 0.01 * scale, "y = {y}: {lateral} against {euler}");
    }
}

/// Lateral–torsional buckling of a narrow rectangular cantilever (depth
/// h = 0.1 m, thickness t = 0.01 m, L = 2 m) under a tip load through the
/// centroid, against Timoshenko & Gere (*Theory of Elastic Stability*,
/// 2nd ed., §6.4): P_cr = 4.013 √(E I_z G J)/L², with
/// J = h t³ (1/3 − 0.21 (t/h)(1 − t⁴/(12 h⁴))) (Roark) — within 3 %
/// (measured +2.3 %). ν = 0, so that the plate-like lateral bending of the
/// deep web has the beam's E I_z (with ν = 0.3 it is up to E I_z/(1 − ν²)).
/// The theory leaves out the root's warping restraint and the section's
/// depth: the difference falls with slenderness (+4.0 % at L = 1 m, +1.5 %
/// at L = 4 m on the same section mesh).
#[test]
fn narrow_cantilever_buckles_laterally_at_the_closed_form() {
    let l: f64 = 2.0;
    let text = format!(
        r#"
[analysis]
type = "buckling"
modes = 1
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.0
[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = -0.005, to = 0.005, elements = 2 }}, z = {{ from = -0.05, to = 0.05, elements = 12 }} }}
axis = {{ element = "B4", from = 0.0, to = {l}, elements = 20 }}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = {{ y = {l} }}
total_force = [0.0, 0.0, -1.0]
"#
    );
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let p = sol.buckling.as_ref().unwrap().factors[0];
    let (e, h, t): (f64, f64, f64) = (200e9, 0.1, 0.01);
    let g = e / 2.0;
    let iz = h * t * t * t / 12.0;
    let j = h * t.powi(3) * (1.0 / 3.0 - 0.21 * (t / h) * (1.0 - t.powi(4) / (12.0 * h.powi(4))));
    let closed = 4.013 * (e * iz * g * j).sqrt() / (l * l);
    eprintln!("P_cr {p:.1} N against {closed:.1} N ({:+.2} %)", 100.0 * (p / closed - 1.0));
    assert!((p - closed).abs() < 0.03 * closed);
}

/// Flexural–torsional buckling of a thin-walled channel column (web 0.1 m,
/// flanges 0.06 m, walls 3 mm, L = 2 m) under uniform compression, ends
/// held in x and z over the whole section (pinned, no twist, free to warp),
/// against Vlasov's thin-walled theory (Timoshenko & Gere, *Theory of
/// Elastic Stability*, 2nd ed., §5.4, eqs. 5-25 and 5-30): the channel's
/// symmetry axis is x, so bending along x stays apart at
/// P_x = π² E I_zz/L², and bending across it couples with the twist about
/// the shear centre (offset x₀ from the centroid):
/// (P_z − P)(P_φ − P) r₀² − P² x₀² = 0, with P_φ = (G J + π² E C_w/L²)/r₀².
/// Section properties of the wall centre lines: e = 3 b² t/(6 b t + h t),
/// J = (2 b + h) t³/3, C_w = t b³ h²/12 · (3 b + 2 h)/(6 b + h). ν = 0, as
/// in the closed form: with ν = 0.3 the ends' restrained Poisson expansion
/// lowers the load by 0.9 % on this axis mesh and the axis must be refined
/// for it. Measured: P_FT +0.38 %, P_x −0.49 % (the walls' shear); asserted
/// within 2 % (the centre-line J and C_w differ from the solid walls' by
/// about 1 %). The first mode is a rotation about a point beyond the shear
/// centre: x₀ P_z/(P_z − P) from the centroid — within 5 % (a shear centre
/// at the centroid, or an uncoupled torsion, fails).
#[test]
fn channel_column_buckles_flexural_torsionally_at_vlasovs_load() {
    let (e, h_out, w_out, t, l): (f64, f64, f64, f64, f64) = (200e9, 0.1, 0.06, 0.003, 2.0);
    let text = format!(
        r#"
[analysis]
type = "buckling"
modes = 2
[[materials]]
name = "steel"
young_modulus = {e}
poisson_ratio = 0.0
[[bodies]]
name = "column"
material = "steel"
section = {{ shape = "channel", element = "L9", width = {w_out}, height = {h_out}, web_thickness = {t}, flange_thickness = {t}, along_flange = 4, along_web = 8 }}
axis = {{ element = "B4", from = 0.0, to = {l}, elements = 10 }}
[[constraints]]
name = "end_a"
body = "column"
where = {{ y = 0.0 }}
fix = ["x", "z"]
[[constraints]]
name = "end_b"
body = "column"
where = {{ y = {l} }}
fix = ["x", "z"]
[[constraints]]
name = "middle"
body = "column"
where = {{ y = {half} }}
fix = ["y"]
[[loads]]
name = "end_a"
body = "column"
where = {{ y = 0.0 }}
total_force = [0.0, 1.0, 0.0]
[[loads]]
name = "end_b"
body = "column"
where = {{ y = {l} }}
total_force = [0.0, -1.0, 0.0]
"#,
        half = l / 2.0
    );
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let buckling = sol.buckling.as_ref().unwrap();
    // Vlasov's channel, centre-line dimensions
    let pi2 = std::f64::consts::PI.powi(2);
    let (b, h) = (w_out - t / 2.0, h_out - t);
    let g = e / 2.0;
    let a = h * t + 2.0 * b * t;
    let xc = b * b * t / a; // centroid from the web's centre line
    let i_sym = t * h.powi(3) / 12.0 + 2.0 * (b * t.powi(3) / 12.0 + b * t * (h / 2.0).powi(2));
    let i_zz = h * t * xc * xc + 2.0 * (t * b.powi(3) / 12.0 + b * t * (b / 2.0 - xc).powi(2));
    let x0 = 3.0 * b * b * t / (6.0 * b * t + h * t) + xc; // shear centre to centroid
    let j = (2.0 * b + h) * t.powi(3) / 3.0;
    let cw = t * b.powi(3) * h * h / 12.0 * (3.0 * b + 2.0 * h) / (6.0 * b + h);
    let r02 = (i_sym + i_zz) / a + x0 * x0;
    let (p_x, p_z) = (pi2 * e * i_zz / (l * l), pi2 * e * i_sym / (l * l));
    let p_phi = (g * j + pi2 * e * cw / (l * l)) / r02;
    let k = 1.0 - x0 * x0 / r02;
    let p_ft = ((p_z + p_phi) - ((p_z + p_phi).powi(2) - 4.0 * k * p_z * p_phi).sqrt()) / (2.0 * k);
    let [ft, flexural] = [buckling.factors[0], buckling.factors[1]];
    eprintln!(
        "P_FT {ft:.0} N against {p_ft:.0} N ({:+.2} %); P_x {flexural:.0} N against {p_x:.0} N ({:+.2} %)",
        100.0 * (ft / p_ft - 1.0),
        100.0 * (flexural / p_x - 1.0)
    );
    assert!((ft - p_ft).abs() < 0.02 * p_ft);
    assert!((flexural - p_x).abs() < 0.02 * p_x);
    // the first mode's centre of rotation at mid-length: least squares of
    // the section's rigid in-plane motion u_x = a − φ (z − h/2), u_z = c + φ x
    let mode = &buckling.modes[0];
    let (mut n, mut sx, mut sxx, mut sz, mut szz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut sux, mut suz, mut sxuz, mut szux) = (0.0, 0.0, 0.0, 0.0);
    for node in 0..model.mesh.n_nodes() {
        let [x, y, z] = model.mesh.coords(node);
        if (y - l / 2.0).abs() > 1e-9 {
            continue;
        }
        let z = z - h_out / 2.0;
        let (ux, uz) = (mode[3 * node], mode[3 * node + 2]);
        n += 1.0;
        (sx, sxx, sz, szz) = (sx + x, sxx + x * x, sz + z, szz + z * z);
        (sux, suz, sxuz, szux) = (sux + ux, suz + uz, sxuz + x * uz, szux + z * ux);
    }
    // normal equations of the 3 unknowns (a, c, φ); Σz = 0 by symmetry
    assert!(sz.abs() < 1e-9 * n);
    let phi = (sxuz - sx * suz / n - szux) / (sxx - sx * sx / n + szz);
    let c = (suz - phi * sx) / n;
    let centre = -c / phi;
    let centroid = t / 2.0 + xc;
    let expected = centroid - x0 * p_z / (p_z - p_ft);
    eprintln!("centre of rotation x = {centre:.5} m against {expected:.5} m (centroid {centroid:.5} m)");
    assert!((centre - expected).abs() < 0.05 * (expected - centroid).abs());
}

/// What a linear buckling analysis cannot take is refused by its key.
#[test]
fn buckling_refuses_what_it_cannot_analyse() {
    let text = std::fs::read_to_string(COLUMN).unwrap();
    let cases = [
        (text.replace("modes = 4", "modes = 0"), "analysis.modes = 0"),
        (text.replace("type = \"buckling\"\n", ""), "analysis.modes = 4"),
        (text.replace("modes = 4", "modes = 4\ngeometry = \"nonlinear\""), "analysis.geometry"),
        (
            text.replace(
                "poisson_ratio = 0.3",
                "poisson_ratio = 0.3\nplasticity = { yield_stress = 250e6, hardening = \"perfect\" }",
            ),
            "materials[0].plasticity",
        ),
        (
            text.replace("fix = [\"x\", \"y\", \"z\"]", "fix = [\"x\", \"z\"]\ndisplacement = { y = 1e-3 }"),
            "constraints[0]",
        ),
        (text.clone() + "[[steps]]\nname = \"a\"\nfactor = 0.5\n[[steps]]\nname = \"b\"\nfactor = 1.0\n", "steps"),
    ];
    for (model, key) in cases {
        match Model::parse(&model) {
            Err(e) => assert!(e.to_string().contains(key), "{key}: {e}"),
            Ok(_) => panic!("{key}: accepted"),
        }
    }
}

/// The inertia of the tangent on the perfect column's straight path
/// (`geometry = "nonlinear"`, a rectangular 0.02 × 0.01 m section so that
/// the two bending planes buckle apart): `history.csv` counts one negative
/// pivot per Euler load passed — 0 below P₁ = π² E I_weak/(4 L²) =
/// 822.5 N, 1 up to P₂ = 4 P₁ (the stiff plane), 2 up to 9 P₁ — checked
/// at every increment of 100 N outside ±1 % of each critical load (the
/// CUF loads are 0.2–0.4 % above Euler, test above). A count that lags by
/// an increment (a factor reused from an earlier state) fails here.
#[test]
fn negative_pivots_count_the_euler_loads_passed() {
    let (history, _) = perfect_column("exact", "");
    let p1 = std::f64::consts::PI.powi(2) * 200e9 * (0.02 * 0.01f64.powi(3) / 12.0) / 4.0;
    let (mut checked, mut seen) = (0, [false; 3]);
    for line in history.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        let p = 4000.0 * v[1].parse::<f64>().unwrap();
        let pivots: usize = v[4].parse().unwrap();
        if [1.0, 4.0, 9.0].iter().any(|n| (p - n * p1).abs() < 0.01 * n * p1) {
            continue;
        }
        let expected = [1.0, 4.0, 9.0].iter().filter(|n| p > *n * p1).count();
        assert_eq!(pivots, expected, "P = {p:.1} N");
        seen[expected] = true;
        checked += 1;
    }
    assert!(checked >= 35 && seen == [true; 3], "{checked} increments checked, counts seen {seen:?}");
}

/// `history.csv` and `summary.json` of the perfect column of the test
/// above, under 4 kN in 40 increments, with `solver` keys `extra`.
fn perfect_column(name: &str, extra: &str) -> (String, serde_json::Value) {
    let text = std::fs::read_to_string(COLUMN)
        .unwrap()
        .replace(
            "type = \"buckling\"\nmodes = 4",
            &format!("geometry = \"nonlinear\"\n\n[solver]\nincrements = 40\n{extra}"),
        )
        .replace("z = { from = -0.01, to = 0.01", "z = { from = -0.005, to = 0.005")
        .replace("total_force = [0.0, -1.0, 0.0]", "total_force = [0.0, -4000.0, 0.0]");
    let (out, summary) = common::run_text("inertia", name, &text);
    (std::fs::read_to_string(out.join("history.csv")).unwrap(), summary)
}

/// `solver.inertia = "last_factorization"` reports the inertia of the last
/// factor the solver made anyway: the same increments and load factors, no
/// factorization per increment (fewer in all), and a count that lags the
/// converged tangent's (one negative pivot from P₁ on) but never leads it
/// — a report that is the converged one's, or that counts anything but
/// factors, fails.
#[test]
fn inertia_of_the_last_factorization_is_free_and_lags() {
    let (exact, exact_summary) = perfect_column("every", "");
    let (lagged, lagged_summary) = perfect_column("last", "inertia = \"last_factorization\"");
    let factorizations = |summary: &serde_json::Value| summary["timings"]["factorizations"].as_u64().unwrap();
    let (every, last) = (factorizations(&exact_summary), factorizations(&lagged_summary));
    assert!(last + 35 <= every, "{last} factorizations with the last one's inertia, {every} with every increment's");
    let mut lags = 0;
    for (e, l) in exact.lines().zip(lagged.lines()).skip(1) {
        let (e, l): (Vec<&str>, Vec<&str>) = (e.split(',').collect(), l.split(',').collect());
        assert_eq!(e[..2], l[..2], "the same increments and load factors");
        let (e, l): (usize, usize) = (e[4].parse().unwrap(), l[4].parse().unwrap());
        assert!(l <= e, "the last factor's count leads the converged tangent's: {l} > {e}");
        lags += usize::from(l < e);
    }
    assert!(lags > 0, "the last factorization's count never lagged: it is the converged tangent's");
}

/// `cufem run --adapt` on the shipped column (`adapt::measure`: buckling
/// cycles measured by the largest estimated critical load factor error of
/// the modes followed; the library's test is tests/buckling_error.rs): each
/// cycle's factors and their estimates in summary.json (`adapt[k].factors`,
/// `factor_errors`, the estimate their largest), the report's table of the
/// modes followed, and the adapted model file, which solves to the last
/// cycle's factors.
#[test]
fn adapt_on_buckling_writes_each_cycles_factors_and_estimates() {
    let dir = std::env::temp_dir().join(format!("cufem_column_adapt_{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", COLUMN, "--adapt", "0.001", "--quiet", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let read = |p: &Path| -> serde_json::Value { serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap() };
    let s = read(&dir.join("out/summary.json"));
    let cycles = s["adapt"].as_array().unwrap();
    assert!(cycles.len() >= 2, "{cycles:?}");
    let floats =
        |v: &serde_json::Value| -> Vec<f64> { v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect() };
    for c in cycles {
        let (factors, errors) = (floats(&c["factors"]), floats(&c["factor_errors"]));
        assert_eq!((factors.len(), errors.len()), (4, 4), "every mode followed: {c}");
        assert_eq!(c["estimate"].as_f64().unwrap(), errors.iter().copied().fold(0.0, f64::max));
        assert!(c.get("frequencies").is_none());
    }
    let (first, last) = (&cycles[0], cycles.last().unwrap());
    assert!(first["estimate"].as_f64().unwrap() > 0.001 && last["estimate"].as_f64().unwrap() < 0.001, "{cycles:?}");
    assert_eq!(floats(&last["factors"]), floats(&s["buckling"]["factors"]), "the results are the last cycle's");
    assert!(s["adapt_stop"].as_str().unwrap().contains("critical load factor error"), "{}", s["adapt_stop"]);
    let html = std::fs::read_to_string(dir.join("out/report.html")).unwrap();
    assert!(html.contains("critical load factor and its estimated error"));
    // a value and an estimate column per mode followed, the fourth the last
    assert!(html.contains("μ4 est. error [%]") && !html.contains("μ5"), "the report's table of the four modes");
    // the estimate charted and printed is the factors', not an energy norm (a new user's review)
    let chart = "largest estimated critical load factor error of the followed modes against DOF";
    assert!(html.contains(chart) && !html.contains("(energy norm) against DOF"), "the chart's title");
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(printed.contains("load factor   factor err.[%]"), "{printed}");
    let again = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", dir.join("out/adapted.toml").to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("again"))
        .output()
        .unwrap();
    assert!(again.status.success(), "{}", String::from_utf8_lossy(&again.stderr));
    let a = read(&dir.join("again/summary.json"));
    assert_eq!(a["dof"], s["dof"]);
    for (x, y) in floats(&a["buckling"]["factors"]).iter().zip(floats(&s["buckling"]["factors"])) {
        assert!((x / y - 1.0).abs() < 1e-9, "{x} against {y}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
