//! The error estimate (`post::estimate`, Zienkiewicz–Zhu with
//! superconvergent patch recovery, `post::spr`): zero where the basis holds
//! the exact stress, decreasing under refinement, and close to the true
//! error — its effectivity index `η / ‖e‖` within issue 23's band 0.7–1.5 on
//! the Timoshenko cantilever (true error from the exact energy), the compact
//! bar and the block (true error against a much finer cufem solution of the
//! same model, singular contact neighbourhoods left out).

use cufem::analysis::{Silent, Solution};
use cufem::setup::Model;

mod common;
#[path = "common/truth.rs"]
mod truth;
use truth::{block_refined, touches_punch_edge, true_error};

/// The check of every effectivity index asserted here.
const BAND: &str = "in [0.7, 1.5] (issue 23)";

fn example(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).unwrap()
}

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    (model, solution)
}

/// The Timoshenko cantilever with `n` × `n` L9 over the section and `m` B4
/// along the axis.
fn cantilever(n: usize, m: usize) -> String {
    let text = example("cantilever_timoshenko.toml");
    let section = "x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }";
    assert!(text.contains(section) && text.contains("elements = 5 }"));
    text.replace(
        section,
        &format!("x = {{ from = 0.0, to = 0.1, elements = {n} }}, z = {{ from = 0.0, to = 0.1, elements = {n} }}"),
    )
    .replace("to = 1.0, elements = 5 }", &format!("to = 1.0, elements = {m} }}"))
}

/// The compact bar (`bending_compact_4L9.toml`) with `n` × `n` L9 and `m`
/// B4, over its first increment only: the roller pushed 0.05 mm (1/15 of
/// the example's 0.75 mm) in one increment, which stays elastic (no
/// plastic point, checked), so the energy norm is the error norm.
fn bar(n: usize, m: usize) -> String {
    let text = example("bending_compact_4L9.toml");
    let section = "x = { from = 0.0, to = 0.01, elements = 2 }, z = { from = 0.0, to = 0.01, elements = 2 }";
    assert!(text.contains(section) && text.contains("to = 0.25, elements = 10 }"));
    assert!(text.contains("[0.0, 0.0, -0.75e-3]") && text.contains("increments = 15"));
    text.replace(
        section,
        &format!("x = {{ from = 0.0, to = 0.01, elements = {n} }}, z = {{ from = 0.0, to = 0.01, elements = {n} }}"),
    )
    .replace("to = 0.25, elements = 10 }", &format!("to = 0.25, elements = {m} }}"))
    .replace("[0.0, 0.0, -0.75e-3]", "[0.0, 0.0, -0.05e-3]")
    .replace("increments = 15", "increments = 1")
}

/// The block (`block_indentation.toml`) with every section division `k`
/// times finer and `m` B4, over its first increment (the punch down 0.05 mm
/// of the example's 1 mm, elastic: no plastic point, checked), the element
/// stress recovery (the reference's fields are then its own elements').
fn block(k: usize, m: usize) -> String {
    let text = example("block_indentation.toml");
    assert!(text.matches("elements = 6").count() == 4 && text.contains("to = 0.1, elements = 1 }"));
    assert!(text.contains("[0.0, 0.0, -1.0e-3]") && text.contains("increments = 20"));
    text.replace("elements = 6", &format!("elements = {}", 6 * k))
        .replace("to = 0.1, elements = 1 }", &format!("to = 0.1, elements = {m} }}"))
        .replace("[0.0, 0.0, -1.0e-3]", "[0.0, 0.0, -0.05e-3]")
        .replace("increments = 20", "increments = 1")
        .replace("recovery = \"projection\"", "recovery = \"element\"")
}

/// `(η, ‖e‖)` over the elements `keep` accepts (section element, beam element).
fn over(coarse: &(Model, Solution), truth: &[f64], keep: &dyn Fn(usize, usize) -> bool) -> (f64, f64) {
    let body = &coarse.0.mesh.bodies[0];
    let est = coarse.1.error_estimate.as_ref().unwrap();
    let (mut eta, mut error) = (0.0, 0.0);
    for (e, t) in truth.iter().enumerate() {
        let (es, eb) = body.split_element(e);
        if keep(es, eb) {
            eta += est.element[e].powi(2);
            error += t;
        }
    }
    (eta.sqrt(), error.sqrt())
}

/// A bar in uniform tension: the stress is constant, the projection
/// reproduces it, and the estimate is zero (to round-off) — the patch test
/// of the estimator.
#[test]
fn a_uniform_stress_has_no_estimated_error() {
    let text = cantilever(2, 3).replace("total_force = [0.0, 0.0, -1000.0]", "total_force = [0.0, 1000.0, 0.0]").replace(
        "fix = [\"x\", \"y\", \"z\"]",
        "fix = [\"y\"]\n\n[[constraints]]\nname = \"pin\"\nbody = \"beam\"\nwhere = { x = 0.0, y = 0.0, z = 0.0 }\nfix = [\"x\", \"z\"]\n\n[[constraints]]\nname = \"roll\"\nbody = \"beam\"\nwhere = { x = 0.1, y = 0.0, z = 0.0 }\nfix = [\"z\"]",
    );
    let (_, s) = solve(&text);
    let est = s.error_estimate.as_ref().unwrap();
    common::figure("estimator.uniform_tension", est.relative(), "", "< 1e-6 of the energy norm (the exact stress)");
    assert!(est.relative() < 1e-6, "{}", est.relative());
}

/// `‖σ‖²` (twice the strain energy, J) of the exact solution of the
/// Timoshenko cantilever model (the 3D elasticity problem the CUF meshes
/// converge to): Richardson extrapolation `E_n = E − C n^−β` through the
/// 8×8 × 20, 10×10 × 25 and 12×12 × 30 meshes (β = 1.59: the clamped
/// root's corners are singular, ‖e‖ ~ h^0.8); the 6/8/10 triple gives
/// 5.71998e-1. Recomputed by `the_exact_energy_of_the_cantilever` (ignored).
const CANTILEVER_ENERGY: f64 = 5.72004e-1;

/// The Timoshenko cantilever on three meshes: the effectivity index against
/// the true error `‖e‖² = E − E_h` (Galerkin orthogonality: for a conforming
/// displacement model of linear elasticity `a(u − u_h, u − u_h) = a(u, u) −
/// a(u_h, u_h)`, exact, and `E_h = ‖σ_h‖²` is the estimate's own
/// `energy²`) lies in issue 23's band 0.7–1.5 (measured 0.81, 0.87, 0.89);
/// the estimate decreases under refinement; its largest element lies at the
/// clamped root, whose section corners are singular (the clamp holds the
/// Poisson contraction) and hold 98 % of the true error of the 2 × 2 × 5
/// mesh.
#[test]
fn the_cantilever_estimate_is_effective_and_points_at_the_root() {
    let mut last = f64::INFINITY;
    for (n, m) in [(2, 5), (4, 10), (6, 15)] {
        let coarse = solve(&cantilever(n, m));
        let est = coarse.1.error_estimate.as_ref().unwrap();
        let truth = (CANTILEVER_ENERGY - est.energy.powi(2)).sqrt();
        let effectivity = est.error / truth;
        let id = format!("estimator.cantilever.{n}x{n}_{m}B4");
        common::figure(&format!("{id}.estimate"), 100.0 * est.relative(), "%", "falls under refinement");
        let check = format!("{BAND}, against the exact error √(E − E_h)");
        common::figure(&format!("{id}.effectivity"), effectivity, "", &check);
        assert!((0.7..=1.5).contains(&effectivity), "effectivity {effectivity}");
        assert!(est.relative() < last, "the estimate grew under refinement");
        last = est.relative();
        let body = &coarse.0.mesh.bodies[0];
        let (top, _) = est.largest(1)[0];
        assert_eq!(body.split_element(top).1, 0, "the largest estimate is not at the root");
    }
}

/// Recomputes [`CANTILEVER_ENERGY`] (about 40 s).
#[test]
#[ignore = "validate: slow — the cantilever on its three finest meshes (about 40 s)"]
fn the_exact_energy_of_the_cantilever() {
    let e: Vec<f64> = [(8, 20), (10, 25), (12, 30)]
        .iter()
        .map(|&(n, m)| solve(&cantilever(n, m)).1.error_estimate.unwrap().energy.powi(2))
        .collect();
    // E_n = E − C n^−β through n = 8, 10, 12: bisection on β
    let ratio = (e[1] - e[0]) / (e[2] - e[1]);
    let f = |b: f64| (8f64.powf(-b) - 10f64.powf(-b)) / (10f64.powf(-b) - 12f64.powf(-b)) - ratio;
    let (mut lo, mut hi) = (0.1, 6.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(lo) * f(mid) <= 0.0 { hi = mid } else { lo = mid }
    }
    let c = (e[1] - e[0]) / (8f64.powf(-lo) - 10f64.powf(-lo));
    let exact = e[0] + c * 8f64.powf(-lo);
    let check = "within 2e-6 of the constant the CI test uses (5.72004e-1 J)";
    common::figure("estimator.cantilever.exact_energy", exact, "J", check);
    common::figure("estimator.cantilever.energy_rate", lo, "", "reported (β of E_n = E − C n^−β)");
    assert!((exact - CANTILEVER_ENERGY).abs() < 2e-6 * CANTILEVER_ENERGY);
}

/// The compact bar's first (elastic) increment, 2×2 L9 × 10 B4 (the
/// example's mesh) and 4×4 × 20, against 8×8 × 40. The rollers load the bar
/// along three lines (y = 0.025, 0.125, 0.225 m) narrower than any element:
/// there the stress is singular and the true error has no limit (it grows
/// with the reference's refinement), so the effectivity is asserted over the
/// bar without the beam elements touching a roller line, and printed over
/// the whole bar. Measured 0.89 and 1.04 (whole bar 1.01 and 1.32).
#[test]
fn the_compact_bar_estimate_is_effective_away_from_the_rollers() {
    let fine = solve(&bar(8, 40));
    assert_eq!(fine.1.plastic_points, 0);
    for (n, m) in [(2, 10), (4, 20)] {
        let coarse = solve(&bar(n, m));
        assert_eq!(coarse.1.plastic_points, 0);
        let truth = true_error((&coarse.0, &coarse.1), (&fine.0, &fine.1));
        let touches_roller = |eb: usize| {
            let (a, b) = coarse.0.mesh.bodies[0].axis.element_span(eb);
            [0.025, 0.125, 0.225].iter().any(|&y| y > a - 1e-9 && y < b + 1e-9)
        };
        let (eta, error) = over(&coarse, &truth, &|_, eb| !touches_roller(eb));
        let (eta_all, error_all) = over(&coarse, &truth, &|_, _| true);
        let effectivity = eta / error;
        let id = format!("estimator.bar.{n}x{n}_{m}B4");
        let check = format!("{BAND}, against 8×8 L9 × 40 B4, without the roller lines' elements");
        common::figure(&format!("{id}.effectivity"), effectivity, "", &check);
        common::figure(&format!("{id}.effectivity_whole"), eta_all / error_all, "", "reported (the whole bar)");
        assert!((0.7..=1.5).contains(&effectivity), "effectivity {effectivity}");
    }
}

/// The block's first (elastic) increment, the example's 18×6 L9 × 1 B4,
/// against every section division twice finer and 3 B4. The punch edges
/// (x = 0.2 and 0.3 m on the top face) are singular (`r^−1/2` under a flat
/// punch), so the effectivity is asserted over the block without the
/// section elements touching an edge line (one element around each, as
/// `verify`'s whole-field comparison leaves out), and printed over the
/// whole block. Measured 0.96 (whole block 1.08).
#[test]
fn the_block_estimate_is_effective_away_from_the_punch_edges() {
    let fine = solve(&block(2, 3));
    let coarse = solve(&block(1, 1));
    assert_eq!((coarse.1.plastic_points, fine.1.plastic_points), (0, 0));
    let truth = true_error((&coarse.0, &coarse.1), (&fine.0, &fine.1));
    let at_edge = |es: usize| touches_punch_edge(&coarse.0, es);
    let (eta, error) = over(&coarse, &truth, &|es, _| !at_edge(es));
    let (eta_all, error_all) = over(&coarse, &truth, &|_, _| true);
    let effectivity = eta / error;
    let check = format!("{BAND}, against the divisions twice finer and 3 B4, without the punch edges' elements");
    common::figure("estimator.block.effectivity", effectivity, "", &check);
    common::figure("estimator.block.effectivity_whole", eta_all / error_all, "", "reported (the whole block)");
    assert!((0.7..=1.5).contains(&effectivity), "effectivity {effectivity}");
}

/// The block's plastic end state (`block_indentation.toml` pressed the full
/// 1 mm in 20 increments: 676 of its Gauss points yielded, perfectly
/// plastic, B-bar) against every section division twice finer and 3 B4,
/// without the section elements touching a punch edge line: the estimate
/// of the yielded body, its strains fitted and turned into stresses by the
/// material law (`post::yielded`), within issue 49's `0.5`–`2` (measured
/// 1.09, 0.99 over the whole block; measured once with the reference's
/// divisions three times finer: 1.11 and 1.03). Mutations: the stresses fitted instead
/// (`post::yielded::replace_recovery` returning at once) gives 0.51; the
/// yielding points' fitted strains returned from their converged state
/// instead of along the monotonic response, 1.94 (within the band: the
/// plastic cantilever of tests/step_error.rs is the test that catches it);
/// the linearised map (the loading tangent times the strain's departure)
/// 84 % estimated instead of 51 %, above 2.
#[test]
fn the_block_s_plastic_end_state_is_estimated() {
    let full = |k: usize, m: usize| block_refined(&example("block_indentation.toml"), k, m);
    let fine = solve(&full(2, 3));
    let coarse = solve(&full(1, 1));
    assert_eq!(coarse.1.plastic_points, 676);
    let truth = true_error((&coarse.0, &coarse.1), (&fine.0, &fine.1));
    let at_edge = |es: usize| touches_punch_edge(&coarse.0, es);
    let (eta, error) = over(&coarse, &truth, &|es, _| !at_edge(es));
    let (eta_all, error_all) = over(&coarse, &truth, &|_, _| true);
    let effectivity = eta / error;
    let check = "0.5–2 (issue 49), against the divisions twice finer and 3 B4, without the punch edges' elements";
    common::figure("estimator.block_plastic.effectivity", effectivity, "", check);
    common::figure("estimator.block_plastic.effectivity_whole", eta_all / error_all, "", "reported (the whole block)");
    assert!((0.5..=2.0).contains(&effectivity), "effectivity {effectivity}");
}

/// The estimate is a function of the solution, not of the solver's path:
/// the graded block solved with and without the factor reuse (the
/// converged states equal within Newton's tolerance, the probes to `1e-8`)
/// is estimated alike to `1e-6`, element by element to `1e-6` of the
/// largest. The axis recovery chose among fits equal to round-off by the
/// last digits (`post::spr`, `TIE`): the two runs were estimated at `22.08`
/// and `22.21 %`.
#[test]
fn the_block_estimate_does_not_follow_the_solver_path() {
    let text = example("block_indentation_graded.toml");
    assert!(text.contains("[solver]\n"));
    let plain = text.replace("[solver]\n", "[solver]\nreuse_factorization = false\n");
    let (a, b) = (common::run(&text), common::run(&plain));
    let (ea, eb) = (a.error_estimate.as_ref().unwrap(), b.error_estimate.as_ref().unwrap());
    let (ra, rb) = (ea.relative(), eb.relative());
    assert!((ra - rb).abs() <= 1e-6 * ra, "{ra} against {rb}");
    let largest = ea.element.iter().fold(0.0f64, |m, &v| m.max(v));
    let worst = ea.element.iter().zip(&eb.element).map(|(x, y)| (x - y).abs()).fold(0.0f64, f64::max);
    assert!(worst <= 1e-6 * largest, "an element's estimate moved by {worst:e} of {largest:e}");
}

/// A body with one element along its axis has no axis neighbour, and the
/// axis fit of degree `p` through its `p + 1` Gauss points interpolated
/// them: the Timoshenko cantilever on one B2 (its tip at `0.0145` mm
/// against the beam's `0.576` mm, shear-locked) was estimated at `0.15 %`
/// and `--adapt` stopped at once (a new-user review). A lone B2 now fits a
/// constant along the axis (`post::spr` `axis_patches`): estimated at
/// `65 %` (asserted above half). The estimate cannot see the locking
/// itself — the recovered stresses are the locked ones' — so it still
/// falls short of the true error (`‖e‖ = √(E − E_h)` against
/// [`CANTILEVER_ENERGY`]: effectivity about `0.14`, asserted from both
/// sides as a known limit). A plane-strain slice (the punch of
/// `punch_plane_strain.toml`, elastic, one increment), whose stress is
/// constant along its one B2, is estimated alike on one and on two B2.
#[test]
fn a_lone_b2_along_the_axis_is_estimated() {
    let text =
        cantilever(2, 1).replace("element = \"B4\", from = 0.0, to = 1.0", "element = \"B2\", from = 0.0, to = 1.0");
    assert!(text.contains("element = \"B2\", from = 0.0, to = 1.0, elements = 1 }"));
    let (_, s) = solve(&text);
    let est = s.error_estimate.as_ref().unwrap();
    common::figure("estimator.lone_b2.relative", 100.0 * est.relative(), "%", "≥ 50 % (the tip 97 % short)");
    assert!(est.relative() >= 0.5, "{}", est.relative());
    let truth = (CANTILEVER_ENERGY - est.energy.powi(2)).sqrt();
    let effectivity = est.error / truth;
    common::known_limit("estimator.lone_b2.effectivity", effectivity, "", 0.10, 0.20, "a shear-locked lone B2");
    let punch = example("punch_plane_strain.toml")
        .replace("plasticity = { yield_stress = 100e6, hardening = \"perfect\" }\n", "")
        .replace("increments = 32", "increments = 1");
    let slices: Vec<f64> = [1, 2]
        .iter()
        .map(|&n| {
            let t = punch.replace("to = 0.1, elements = 1 }", &format!("to = 0.1, elements = {n} }}"));
            let (_, s) = solve(&t);
            s.error_estimate.unwrap().relative()
        })
        .collect();
    common::figure("estimator.lone_b2.slice", 100.0 * slices[0], "%", "equal on one and two B2 (plane strain)");
    assert!((slices[0] - slices[1]).abs() <= 1e-6 * slices[1] && slices[0] > 1e-3, "{slices:?}");
}

/// A lone B3 or B4 along the axis fitted its Gauss points with the
/// polynomial through them, so the error along the axis went unseen, as
/// a lone B2's did (above); it now fits one degree less (`post::spr`
/// `axis_patches`). The Timoshenko cantilever on 2 × 2 L9 and one B4
/// (its energy-norm error `22.8 %`): the effectivity against the true error
/// `√(E − E_h)` in issue 49's band 0.5–2 (measured `0.70`; the
/// interpolating fit: `0.047`). On one B3 (`49.8 %` off, its shear partly
/// locked) the recovery sees the locked stresses, as on one B2: `0.40`
/// (the interpolating fit: `0.020`), asserted from both sides as a known
/// limit (docs/limitations.md).
#[test]
fn a_lone_b3_or_b4_along_the_axis_is_estimated() {
    for kind in ["B3", "B4"] {
        let text = cantilever(2, 1)
            .replace("element = \"B4\", from = 0.0, to = 1.0", &format!("element = \"{kind}\", from = 0.0, to = 1.0"));
        assert!(text.contains(&format!("element = \"{kind}\", from = 0.0, to = 1.0, elements = 1 }}")));
        let (_, s) = solve(&text);
        let est = s.error_estimate.as_ref().unwrap();
        let truth = (CANTILEVER_ENERGY - est.energy.powi(2)).sqrt();
        let effectivity = est.error / truth;
        let id = format!("estimator.lone_{}", kind.to_lowercase());
        common::figure(&format!("{id}.relative"), 100.0 * est.relative(), "%", "reported");
        common::figure(&format!("{id}.true"), 100.0 * truth / CANTILEVER_ENERGY.sqrt(), "%", "reported");
        if kind == "B4" {
            common::figure(&format!("{id}.effectivity"), effectivity, "", "in [0.5, 2] (issue 49)");
            assert!((0.5..=2.0).contains(&effectivity), "{kind}: effectivity {effectivity}");
        } else {
            common::known_limit(&format!("{id}.effectivity"), effectivity, "", 0.3, 0.5, "a partly locked lone B3");
        }
    }
}
