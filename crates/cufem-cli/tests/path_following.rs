//! Path following through the finite-element driver (issue 26, item 3):
//! the snap-through of examples/arch_snap_through.toml traced by arc length,
//! checked point by point against the same arch under displacement control
//! of its crown (which, unlike load control, passes a snap-through), the
//! limit load against that path's peak, Newton's order on the path, and the
//! model keys.
//!
//! No published or closed-form limit load is used: the clamped shallow
//! arch under a central load has none in closed form that this plane-strain
//! continuum model (polygonal centreline, thickness along z) would match to
//! better than the shallow-arch approximations themselves; the limit load is
//! checked against the displacement-controlled path and against CalculiX
//! with NLGEOM under the same displacement control.

#[path = "../../../tests/common/mod.rs"]
mod common;

use cufem::analysis::{self, PathEnd, Silent, Solution};
use cufem::setup::Model;

const ARCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/arch_snap_through.toml");
/// The reference load: 2 × 500 N on the crown line.
const P: f64 = 1000.0;

fn text() -> String {
    std::fs::read_to_string(ARCH).unwrap()
}

fn run(text: &str) -> Solution {
    let model = Model::parse(text).unwrap();
    analysis::run(&model, &Default::default(), &mut Silent).unwrap()
}

/// The TOML table starting at `header` (to the next blank line) replaced.
fn replace_table(text: &str, header: &str, with: &str) -> String {
    let start = 1 + text.find(&format!("\n{header}\n")).unwrap_or_else(|| panic!("no {header}"));
    let end = start + text[start..].find("\n\n").unwrap();
    format!("{}{}{}", &text[..start], with, &text[end..])
}

/// The arch with its load replaced by a prescribed crown deflection of
/// `depth` (m), ramped by λ over `increments` equal increments.
fn displacement_controlled(depth: f64, increments: usize) -> String {
    let t = replace_table(&text(), "[solver]", &format!("[solver]\nincrements = {increments}"));
    let crown = format!(
        "[[constraints]]\nname = \"crown\"\nbody = \"arch\"\nwhere = {{ x = 0.5, z = 0.035 }}\n\
         displacement = {{ z = {depth} }}"
    );
    replace_table(&t, "[[loads]]", &crown)
}

/// `(crown u_z, applied load)` at each converged point.
fn arc_path(sol: &Solution) -> Vec<(f64, f64)> {
    sol.history.iter().map(|r| (r.probes[0][2], r.lambda * P)).collect()
}

/// `(crown u_z, load on the crown)` at each increment of displacement
/// control: the crown's reaction is the force the support puts on the
/// arch, `−λ P` in equilibrium.
fn dc_path(sol: &Solution) -> Vec<(f64, f64)> {
    let mut path = vec![(0.0, 0.0)];
    path.extend(sol.history.iter().map(|r| (r.probes[0][2], -r.reaction("crown").unwrap().force[2])));
    path
}

/// Cubic Lagrange interpolation of `path` (sorted by decreasing u) at `u`.
fn interpolate(path: &[(f64, f64)], u: f64) -> f64 {
    let i = path.iter().position(|p| p.0 < u).expect("u beyond the displacement-controlled path");
    let lo = i.saturating_sub(2).min(path.len() - 4);
    let pts = &path[lo..lo + 4];
    let mut sum = 0.0;
    for (j, pj) in pts.iter().enumerate() {
        let mut w = 1.0;
        for (k, pk) in pts.iter().enumerate() {
            if k != j {
                w *= (u - pk.0) / (pj.0 - pk.0);
            }
        }
        sum += w * pj.1;
    }
    sum
}

/// The vertex of the parabola through the first local maximum of `path`
/// and its neighbours: the limit point between samples.
fn peak(path: &[(f64, f64)]) -> (f64, f64) {
    let i = (1..path.len() - 1).find(|&i| path[i].1 >= path[i - 1].1 && path[i].1 > path[i + 1].1).unwrap();
    let [(x0, y0), (x1, y1), (x2, y2)] = [path[i - 1], path[i], path[i + 1]];
    // Newton's divided differences
    let d1 = (y1 - y0) / (x1 - x0);
    let d2 = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
    let xv = 0.5 * (x0 + x1) - d1 / (2.0 * d2);
    (xv, y0 + d1 * (xv - x0) + d2 * (xv - x0) * (xv - x1))
}

/// (a) The example passes its limit point, falls through the snap and
/// rises again to λ = 1 with no failed increment. A predictor of the wrong
/// sign turns back at the first increment (λ < 0), one that does not follow
/// the previous direction turns back at the limit point, and a poor tangent
/// shows as cutbacks.
#[test]
fn the_arch_is_traced_through_its_limit_point_without_cutbacks() {
    let sol = run(&text());
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    assert!(sol.cutbacks.is_empty(), "{} cutbacks", sol.cutbacks.len());
    let path = arc_path(&sol);
    let lambdas: Vec<f64> = sol.history.iter().map(|r| r.lambda).collect();
    eprintln!("λ: {lambdas:.4?}");
    let outcome = sol.path.as_ref().unwrap();
    // the increment that passed λ = 1 was redone to land on it
    assert!(matches!(outcome.end, Some(PathEnd::LoadFactor(l)) if l == 1.0), "{:?}", outcome.end);
    // two limit points: the peak, then the valley of the snap a third lower
    let [(at, top), (low_at, valley)] = outcome.limit_points[..] else { panic!("{:?}", outcome.limit_points) };
    assert!((0.95..1.0).contains(&top) && at > 2 && lambdas[at - 1] == top, "peak λ = {top} at {at}");
    assert!(low_at > at && valley < 0.65 * top && low_at < lambdas.len(), "valley {valley} at {low_at}");
    assert!(*lambdas.last().unwrap() == 1.0 && sol.lambda == 1.0);
    // the crown moves down monotonically, through the inverted position
    assert!(path.windows(2).all(|w| w[1].0 < w[0].0), "{path:?}");
    assert!(path.last().unwrap().0 < -0.04);
    // every point on the path: its last residual below the tolerance
    for inc in &sol.increments {
        assert!(*inc.newton.residuals.last().unwrap() <= 1e-6, "{:?}", inc.newton.residuals);
    }
    // the summary reports the end criterion as converged, at the last λ
    assert_eq!(sol.steps.len(), 1);
    assert_eq!(sol.steps[0].lambda, sol.lambda);
}

/// (b) and (c): every converged point lies on the path obtained
/// independently by displacement control of the crown (Newton with the
/// crown deflection prescribed, 150 increments of 0.5 mm, its reaction
/// interpolated by cubics at the arc-length point's deflection), within
/// 1e-3 of the load; the limit load (parabola through the largest point
/// and its neighbours, on both paths) within 1e-3: the oracle for the
/// points themselves (a history row recorded off the converged iterate, or
/// a residual at another λ than the one recorded, fails it).
#[test]
fn every_point_lies_on_the_displacement_controlled_path() {
    let arc = run(&text());
    assert!(arc.failure.is_none(), "{:?}", arc.failure);
    let dc = run(&displacement_controlled(-0.075, 150));
    assert!(dc.failure.is_none(), "{:?}", dc.failure);
    let reference = dc_path(&dc);
    let mut worst: f64 = 0.0;
    for (u, load) in arc_path(&arc) {
        let other = interpolate(&reference, u);
        worst = worst.max((load - other).abs() / other.abs());
    }
    eprintln!("largest relative difference of the load at equal crown deflection: {worst:.2e}");
    assert!(worst < 1e-3, "{worst}");
    let (u_a, p_a) = peak(&arc_path(&arc));
    let (u_d, p_d) = peak(&reference);
    eprintln!("limit load: arc length {p_a:.3} N at u = {u_a:.5} m, displacement control {p_d:.3} N at {u_d:.5} m");
    assert!((p_a - p_d).abs() < 1e-3 * p_d, "{p_a} vs {p_d}");
    // the limit load against CalculiX with NLGEOM under the same
    // displacement control of the crown (`cufem verify` of the arch with the
    // load replaced by a prescribed crown deflection of 30 mm in 60
    // increments, --refine 1; tests/data/references.toml, arch): 975.56 N at
    // 12.87 mm (the parabola through the three largest increments). 1 %: the
    // 3D model's own discretization and increments; a 10 % error in the
    // stiffness moves the limit load by about as much.
    common::within("arch.limit_load_vs_nlgeom", p_d, 975.56, 0.01, "CalculiX NLGEOM, displacement control");
}

/// (d) Newton on the path converges quadratically: with the tolerance at
/// 1e-9, every pair of successive residuals in the asymptotic range
/// satisfies `r_(k+1) ≤ C r_k²` with `C < 1` (measured 0.07; three
/// successive residuals above the round-off floor, for an observed order,
/// do not occur: from 1e-3 Newton is at the floor in two steps). A tangent without the geometric stiffness
/// (or the structure's load in place of the reference one) converges
/// linearly and fails it.
#[test]
fn newton_on_the_path_is_quadratic() {
    let t = text().replace("increments = 20", "increments = 20\nresidual_tolerance = 1e-9");
    let sol = run(&t);
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    let (mut pairs, mut worst) = (0, 0.0f64);
    for inc in &sol.increments {
        let r = &inc.newton.residuals;
        // above 1e-9: clear of the round-off floor of R (1e-11 to 1.5e-10
        // of ‖f‖ along this path, from the arch's thrust of 3e4 N)
        for w in r.windows(2) {
            if w[0] <= 1e-1 && w[1] >= 1e-9 {
                worst = worst.max(w[1] / (w[0] * w[0]));
                pairs += 1;
            }
        }
    }
    eprintln!("{pairs} pairs, largest r_(k+1)/r_k² = {worst:.3}");
    assert!(pairs >= 20, "{pairs}");
    // linear convergence at a rate ρ gives r_(k+1)/r_k² = ρ/r_k: 1e2–1e5 here
    assert!(worst < 1.0, "{worst}");
}

/// `control = "load"` (the default) is load stepping, to the last bit; the
/// path-following keys are refused with load control, load-stepping keys
/// with arc length, and any loading arc length cannot scale is refused by
/// key.
#[test]
fn the_keys_are_checked_and_load_control_is_unchanged() {
    let dc = displacement_controlled(-0.01, 4);
    let a = run(&dc);
    let b = run(&dc.replace("\n[solver]", "\n[solver]\ncontrol = \"load\""));
    assert_eq!(a.u, b.u);
    assert!(a.path.is_none());
    let err = |t: &str| Model::parse(t).unwrap_err().to_string();
    let cases = [
        (dc.replace("\n[solver]", "\n[solver]\nmax_load_factor = 2.0"), "solver.max_load_factor"),
        (text().replace("increments = 20", "increments = 20\ncutback_factor = 0.5"), "solver.cutback_factor"),
        (text().replace("increments = 20", "arc_length = 0.01"), ""),
        (text().replace("increments = 20", "increments = 20\narc_length = 0.01"), "solver.increments = 20"),
        (text().replace("increments = 20", "arc_length = -1.0"), "solver.arc_length = -1"),
        (text().replace("max_load_factor = 1.0", "max_load_factor = 0.0"), "solver.max_load_factor = 0"),
        (text().replace("probe = \"crown\"", "probe = \"crwon\""), "solver.stop.probe = \"crwon\""),
        (text().replace("beyond = -0.07", "beyond = 0.0"), "solver.stop.beyond = 0"),
        (
            format!(
                "{}\n[[constraints]]\nname = \"crown\"\nbody = \"arch\"\nwhere = {{ x = 0.5, z = 0.035 }}\n\
                 displacement = {{ z = -0.01 }}\n",
                text()
            ),
            "constraints[4].displacement = [free, free, -0.01]",
        ),
        (dc.replace("increments = 4", "control = \"arc_length\""), "loads = []: expected at least one [[loads]]"),
        // the dissipation constraint: with arc length, in a model that damages (the arch does not)
        (
            dc.replace("\n[solver]", "\n[solver]\nconstraint = \"dissipation\""),
            "solver.constraint = (given): expected no value without",
        ),
        (
            text().replace("increments = 20", "increments = 20\nconstraint = \"dissipation\""),
            "solver.constraint = \"dissipation\": expected \"cylinder\" in a model without cohesive interfaces",
        ),
        (text().replace("increments = 20", "increments = 20\nconstraint = \"cylinder\""), ""),
        (
            format!("{}\n[[steps]]\nname = \"a\"\n\n[[steps]]\nname = \"b\"\n", text()),
            "steps = 2 steps: expected at most one step",
        ),
    ];
    for (t, expect) in cases {
        if expect.is_empty() {
            Model::parse(&t).unwrap();
        } else {
            let e = err(&t);
            assert!(e.contains(expect), "{expect}: {e}");
        }
    }
    let e = err(&text().replace("control = \"arc_length\"", "control = \"arclength\""));
    assert!(e.contains("unknown variant `arclength`, expected `load` or `arc_length`"), "{e}");
}

/// The inertia of the tangent along the arch's path: no negative pivot on
/// the rising branch, exactly one between the two limit points (a limit
/// point turns one eigenvalue negative; the path is symmetric, so it is
/// not a bifurcation), none after the valley. The limit points' own rows
/// lie within an increment of the turn and are not checked.
#[test]
fn one_negative_pivot_between_the_limit_points() {
    let sol = run(&text());
    let outcome = sol.path.as_ref().unwrap();
    let [(top, _), (valley, _)] = outcome.limit_points[..] else { panic!("{:?}", outcome.limit_points) };
    for row in &sol.history {
        let expected = if row.increment < top || row.increment > valley {
            0
        } else if row.increment > top && row.increment < valley {
            1
        } else {
            continue;
        };
        assert_eq!(row.negative_pivots, Some(expected), "increment {} (λ = {})", row.increment, row.lambda);
    }
}

/// `summary.json` and the run's table report the path: its end criterion
/// and the two limit points, as the library's outcome has them.
#[test]
fn the_summary_reports_the_limit_points() {
    let out = std::env::temp_dir().join(format!("cufem_arch_{}", std::process::id()));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", ARCH, "--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let outcome = run_text_outcome();
    assert_eq!(summary["path"]["end"], "load_factor");
    let points = summary["path"]["limit_points"].as_array().unwrap();
    assert_eq!(points.len(), outcome.len());
    for (p, (i, l)) in points.iter().zip(&outcome) {
        assert_eq!(p[0].as_u64().unwrap() as usize, *i);
        assert!((p[1].as_f64().unwrap() - l).abs() < 1e-12 * l);
    }
    let table = String::from_utf8_lossy(&run.stdout);
    assert!(table.contains("arc length: limit points increment"), "{table}");
    std::fs::remove_dir_all(&out).ok();
}

/// The limit points of the example run through the library.
fn run_text_outcome() -> Vec<(usize, f64)> {
    run(&text()).path.unwrap().limit_points
}
