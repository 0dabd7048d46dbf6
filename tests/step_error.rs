//! The effectivity of the estimate of every kept state
//! (`analysis::state_errors`) on shipped examples: each step end or frame of
//! the example's own mesh, and of its mesh refined once (every section and
//! axis division doubled), against the true error measured against the
//! mesh refined twice (every division four times finer) at the same state,
//! as `tests/estimator.rs` measures it: `‖e‖² = Σ_gp w (σ_ref − σ_h)ᵀ C⁻¹
//! (σ_ref − σ_h)` with `σ_ref` the finest run's stress at each Gauss point
//! of the coarser one. Issue 49 asks for an effectivity `η / ‖e‖` in
//! 0.5–2 at every step; where a state lies outside, the measured value is
//! held from both sides and listed in docs/limitations.md.

use cufem::analysis::state_errors::State;
use cufem::analysis::{IncrementLog, Progress, Silent, Solution};
use cufem::setup::Model;
use cufem::solver::stepping::Cutback;

mod common;
#[path = "common/truth.rs"]
mod truth;
use truth::{
    Plane, block_refined, error_against, gauss_points, image, stresses_at, touches_any, touches_punch_edge, true_error,
};

fn example(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).unwrap()
}

fn solve(text: &str) -> (Model, Solution) {
    solve_with(text, &mut Silent)
}

fn solve_with(text: &str, progress: &mut dyn Progress) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), progress).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    (model, solution)
}

/// A line on stderr per converged increment and per cutback: the
/// references' remakes run for up to hours (`--nocapture` shows them).
struct Log(std::time::Instant);

impl Progress for Log {
    fn increment(&mut self, log: &IncrementLog) {
        let s = self.0.elapsed().as_secs();
        eprintln!("[{s} s] increment {} λ = {:.4}: {} corrections", log.index, log.lambda, log.iterations);
    }
    fn cutback(&mut self, c: &Cutback) {
        let s = self.0.elapsed().as_secs();
        let (n, why) = (c.newton.iterations, &c.newton.failure);
        eprintln!("[{s} s] cutback at increment {} (Δλ = {:.2e}): {n} corrections, {why:?}", c.index, c.dlambda);
    }
}

/// Every kept state of a run in the order of its `error_history`: the
/// state's fields (the run itself for a step end that kept none: the final
/// state) and its estimate.
fn states(model: &Model, s: &Solution) -> Vec<(String, Solution)> {
    s.error_history
        .rows
        .iter()
        .map(|r| match r.state {
            State::Step(k) => {
                let at = s.at_step(model, k).unwrap().unwrap_or_else(|| s.clone());
                (s.steps[k].name.clone(), at)
            }
            State::Frame(k) => (format!("frame_{:04}", k + 1), s.at_frame(model, k).unwrap()),
        })
        .collect()
}

/// One row per kept state: its name, the estimate `η` (√J), the true error
/// `‖e‖` (√J) and the estimated and true relative errors, of `coarse`
/// against `fine` (the same states, in the same order); `keep` picks the
/// (section, beam) elements summed.
type Row = (String, f64, f64, f64, f64);

/// Picks elements by body, section element and beam element.
type Pick<'a> = &'a dyn Fn(&Model, usize, usize, usize) -> bool;

fn effectivities(coarse: &(Model, Solution), fine: &(Model, Solution), keep: Pick<'_>) -> Vec<Row> {
    let (c, f) = (states(&coarse.0, &coarse.1), states(&fine.0, &fine.1));
    assert_eq!(c.len(), f.len(), "the same states");
    c.iter()
        .zip(&f)
        .map(|((name, cs), (_, fs))| {
            assert!((cs.lambda - fs.lambda).abs() < 1e-9 * cs.lambda.abs().max(1.0));
            row(name, (&coarse.0, cs), &true_error((&coarse.0, cs), (&fine.0, fs)), keep)
        })
        .collect()
}

/// The [`Row`] of one state `s` of `model` whose true error per element
/// (global index) is `truth` (J), summed over the elements `keep` picks
/// (by body, section element and beam element).
fn row(name: &str, (model, s): (&Model, &Solution), truth: &[f64], keep: Pick<'_>) -> Row {
    let est = s.error_estimate.as_ref().unwrap();
    let (mut eta, mut error, mut e) = (0.0, 0.0, 0);
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        for local in 0..body.n_elements() {
            let (es, eb) = body.split_element(local);
            if keep(model, b, es, eb) {
                eta += est.element[e].powi(2);
                error += truth[e];
            }
            e += 1;
        }
    }
    assert_eq!(e, truth.len());
    let energy = est.energy.powi(2);
    let rel = |x: f64| (x / (x + energy)).sqrt();
    (name.to_string(), eta.sqrt(), error.sqrt(), rel(eta), rel(error))
}

/// Prints each row as FIGURE lines `<id>.<mesh>.<state>.{estimate,true,effectivity}`
/// and returns the effectivities.
fn report(id: &str, mesh: &str, rows: &[Row], check: &str) -> Vec<f64> {
    rows.iter()
        .map(|(name, eta, error, rel_eta, rel_error)| {
            let at = format!("{id}.{mesh}.{name}");
            common::figure(&format!("{at}.estimate"), 100.0 * rel_eta, "%", "reported");
            common::figure(
                &format!("{at}.true"),
                100.0 * rel_error,
                "%",
                "reported: against the refined reference its test names",
            );
            common::figure(&format!("{at}.effectivity"), eta / error, "", check);
            eta / error
        })
        .collect()
}

/// `text` with every division count `elements = n` of the listed keys
/// (`x = {…}`, `z = {…}`, `axis = {…}`) times `k`.
fn refined(text: &str, k: usize, counts: &[(&str, usize)]) -> String {
    let mut out = text.to_string();
    for &(pattern, n) in counts {
        let from = format!("{pattern}elements = {n} }}");
        assert!(out.contains(&from), "{from}");
        out = out.replace(&from, &format!("{pattern}elements = {} }}", n * k));
    }
    out
}

/// The elastica (`elastica.toml`: nonlinear geometry, four steps rolling
/// the tip up to 0.81 m, elastic), 1 L9 × 20 B4 and 2 × 2 × 40, against
/// 4 × 4 × 80: the effectivity at every step end, in the band on both
/// meshes. On the example's one L9 across the section the error lies in
/// the shear across it (about constant where the beam's is the parabola
/// that vanishes on the free faces), which the section fit sees only
/// through the faces' vanishing shear tractions (`post::spr`). Mutation:
/// without them (the fit interpolating the one element) the shipped mesh
/// is at `0.12`–`0.45` and fails.
#[test]
#[ignore = "validate: slow — the elastica's four steps on three meshes, the finest 58,563 DOF (about 2 min)"]
fn the_elastica_steps_are_estimated() {
    let text = example("elastica.toml");
    let counts = [("to = 0.01, ", 1), ("to = 1.0, ", 20)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    // 2 × 2 L9 × 40 B4: in the band at every step (measured 0.77–0.84)
    let rows = effectivities(&runs[1], &runs[2], &|_, _, _, _| true);
    for eff in report("step_error.elastica", "2x2L9_40B4", &rows, "in [0.5, 2] (issue 49)") {
        assert!((0.5..=2.0).contains(&eff), "2 × 2 L9: effectivity {eff}");
    }
    // the example's one L9 across the section (measured 0.81, 0.77, 0.73,
    // 0.74)
    let rows = effectivities(&runs[0], &runs[2], &|_, _, _, _| true);
    for eff in report("step_error.elastica", "1L9_20B4", &rows, "in [0.5, 2] (issue 49)") {
        assert!((0.5..=2.0).contains(&eff), "1 L9: effectivity {eff}");
    }
}

/// `text` with each quadrilateral of its first body's `quads` section split
/// into `k × k` by the quadrilateral's bilinear map (straight-edged
/// elements: the section's polygon unchanged).
fn quads_refined(text: &str, k: usize) -> String {
    let mut doc: toml::Table = text.parse().unwrap();
    let section = doc["bodies"].as_array_mut().unwrap()[0].get_mut("section").unwrap().as_table_mut().unwrap();
    let pair = |v: &toml::Value| -> [f64; 2] {
        let a = v.as_array().unwrap();
        std::array::from_fn(|i| a[i].as_float().unwrap_or_else(|| a[i].as_integer().unwrap() as f64))
    };
    let points: Vec<[f64; 2]> = section["points"].as_array().unwrap().iter().map(pair).collect();
    let quads: Vec<[usize; 4]> = section["quads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|q| std::array::from_fn(|i| q.as_array().unwrap()[i].as_integer().unwrap() as usize))
        .collect();
    let (mut new_points, mut index) = (Vec::<[f64; 2]>::new(), std::collections::HashMap::new());
    let mut new_quads = Vec::new();
    for q in &quads {
        let c = q.map(|i| points[i]);
        let mut at = |s: f64, t: f64| {
            let w = [(1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t];
            let p: [f64; 2] = std::array::from_fn(|d| (0..4).map(|n| w[n] * c[n][d]).sum());
            let key = p.map(|x| (x * 1e12).round() as i64);
            *index.entry(key).or_insert_with(|| {
                new_points.push(p);
                new_points.len() - 1
            })
        };
        let grid: Vec<Vec<usize>> =
            (0..=k).map(|i| (0..=k).map(|j| at(i as f64 / k as f64, j as f64 / k as f64)).collect()).collect();
        for i in 0..k {
            for j in 0..k {
                new_quads.push([grid[i][j], grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1]]);
            }
        }
    }
    let value = |rows: Vec<Vec<toml::Value>>| toml::Value::Array(rows.into_iter().map(toml::Value::Array).collect());
    section.insert("points".into(), value(new_points.iter().map(|p| p.map(toml::Value::Float).to_vec()).collect()));
    section.insert(
        "quads".into(),
        value(new_quads.iter().map(|q| q.map(|i| toml::Value::Integer(i as i64)).to_vec()).collect()),
    );
    toml::to_string(&doc).unwrap()
}

/// The shallow arch snapping through (`arch_snap_through.toml`: nonlinear
/// geometry, arc length through both limit points to λ = 1 past the snap,
/// elastic, plane strain), its 40 L9 quadrilaterals along the span and one
/// through the thickness, and each split into 2 × 2, against each split
/// into 4 × 4 (17,334 DOF; the one B2 along y kept: the fields are
/// constant along it), at the run's end, λ = 1 on the inverted arch.
#[test]
fn the_arch_s_snapped_state_is_estimated() {
    let text = example("arch_snap_through.toml");
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&quads_refined(&text, k))).collect();
    for (m, mesh) in [(0, "40L9"), (1, "160L9")] {
        let rows = effectivities(&runs[m], &runs[2], &|_, _, _, _| true);
        for eff in report("step_error.arch", mesh, &rows, "in [0.5, 2] (issue 49)") {
            assert!((0.5..=2.0).contains(&eff), "{mesh}: effectivity {eff}");
        }
    }
}

/// The compact bar's quarter (`bending_compact_4L9_quarter.toml`: one
/// step, the roller pushed 0.75 mm, plastic under the roller), 1 × 2 L9 ×
/// 5 B4 and 2 × 4 × 10, against 4 × 8 × 20: the effectivity of its one
/// step end, over the whole quarter and without the beam elements touching
/// a roller line (where the true error has no limit, `tests/estimator.rs`):
/// within issue 49's `0.5`–`2` on both meshes (measured 1.10 and 0.89 on
/// the shipped mesh, 1.02 and 1.35 on the refined one); and the whole
/// shipped bar (`bending_compact_4L9.toml`, 2 × 2 L9 × 10 B4) against the
/// finest quarter mirrored, without its three roller lines (1.13 and
/// 0.90). Mutation: the yielded body's stresses recovered instead of its
/// strains (`post::yielded::replace_recovery` returning at once) gives
/// 3.65, 2.99, 2.74 and 3.76 and fails.
#[test]
fn the_compact_bar_step_is_estimated() {
    let text = example("bending_compact_4L9_quarter.toml");
    let counts = [("to = 0.01, ", 2), ("to = 0.25, ", 10)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    let away = |m: &Model, _: usize, _: usize, eb: usize| {
        let (a, b) = m.mesh.bodies[0].axis.element_span(eb);
        ![0.025, 0.125].iter().any(|&y| y > a - 1e-9 && y < b + 1e-9)
    };
    // plastic under the roller: the yielded body's strains are recovered
    // (`post::yielded`); recovering its stresses instead, the estimate was
    // 3.65 and 2.74 times the true error over the whole quarter, 2.99 and
    // 3.76 without the roller lines
    for (m, mesh) in [(0, "1x2L9_5B4"), (1, "2x4L9_10B4")] {
        let whole = effectivities(&runs[m], &runs[2], &|_, _, _, _| true);
        let whole = report("step_error.bar", &format!("{mesh}.whole"), &whole, "reported (the whole quarter)");
        let rows = effectivities(&runs[m], &runs[2], &away);
        let away = report("step_error.bar", mesh, &rows, "reported, without the roller lines");
        for (id, eff) in [("whole", whole[0]), ("away", away[0])] {
            assert!((0.5..=2.0).contains(&eff), "{mesh} {id}: effectivity {eff}");
        }
    }
    // the whole bar (`bending_compact_4L9.toml`, 2 × 2 L9 × 10 B4, the
    // quarter's mirror images) against the quarter refined twice, mirrored
    // across both planes (`stresses_at`): measured 1.13 whole, 0.90 away
    let whole = solve(&example("bending_compact_4L9.toml"));
    let reference = stresses_at((&runs[2].0, &runs[2].1), &gauss_points(&whole.0), &COMPACT_QUARTER);
    let truth = error_against((&whole.0, &whole.1), &reference);
    in_band(("step_error.bar_whole", "2x2L9_10B4"), &whole, &truth, (&off_lines(0, WHOLE_ROLLERS), "the roller lines"));
}

/// The rod against the wall (`rod_impact.toml`, transient, frames every
/// 50 µs), 1 L4 × 100 B2 and 2 × 2 × 200, against 4 × 4 × 400, the same
/// time step: the effectivity at every frame.
#[test]
#[ignore = "validate: slow — the rod's 600 time steps on three meshes, the finest 30,075 DOF (about 2 min)"]
fn the_rod_frames_are_estimated() {
    let text = example("rod_impact.toml");
    let counts = [("to = 0.01, ", 1), ("to = 1.0, ", 100)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    for (m, mesh) in [(0, "1L4_100B2"), (1, "2x2L4_200B2")] {
        let rows = effectivities(&runs[m], &runs[2], &|_, _, _, _| true);
        let eff = report("step_error.rod", mesh, &rows, "reported; the range below");
        let (lo, hi) = eff.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &e| (a.min(e), b.max(e)));
        // the wave's phase error: a known limit (measured 0.084–0.22 and 0.090–0.25)
        let what = "the rod's frames: the estimate does not see the wave's phase error";
        common::known_limit(&format!("step_error.rod.{mesh}.effectivity_min"), lo, "", 0.07, 0.5, what);
        common::known_limit(&format!("step_error.rod.{mesh}.effectivity_max"), hi, "", 0.07, 0.5, what);
    }
}

/// The elastic–perfectly-plastic cantilever (`epp_cantilever.toml`: one
/// step, the tip pushed to 6 δ_y, past its collapse load, a plastic hinge
/// at the root), 1 × 2 L9 × (8 + 4) B4 and 2 × 4 × (16 + 8), against
/// 4 × 8 × (32 + 16): the effectivity of its one step end over the whole
/// beam and without the root's first `37.5 mm` (the shipped mesh's first
/// element), where the root's `u_x = u_z = 0` holds one point of the
/// section (the symmetry plane of a beam under a central point load; the
/// elastic stress has no limit there: with the tip at `δ_y / 2` the first
/// element's effectivity is 0.32 and 1.76). Within issue 49's `0.5`–`2`
/// (measured 1.24 whole and 0.81 away on the shipped mesh, 1.54 and 1.13 on
/// the refined one). Mutation: the yielding points' fitted strains returned
/// from their converged state (`post::yielded`, the elastic trial from the
/// end state) charges every fit below the point's own strain at elastic
/// stiffness: 3.75 and 4.69 over the whole beam, the first element five to
/// six times its error; fails.
#[test]
#[ignore = "validate: slow — the plastic cantilever's 30 increments on three meshes, the finest 66,555 DOF (about 1 min)"]
fn the_plastic_cantilever_step_is_estimated() {
    let text = example("epp_cantilever.toml");
    let counts = [("to = 0.02, ", 1), ("to = 0.02, ", 2), ("to = 0.3, ", 8), ("to = 0.8, ", 4)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    let away = |m: &Model, _: usize, _: usize, eb: usize| m.mesh.bodies[0].axis.element_span(eb).0 >= 0.0375 - 1e-9;
    for (m, mesh) in [(0, "1x2L9_12B4"), (1, "2x4L9_24B4")] {
        let rows = effectivities(&runs[m], &runs[2], &|_, _, _, _| true);
        let whole = report("step_error.epp", &format!("{mesh}.whole"), &rows, "in [0.5, 2] (issue 49)")[0];
        let rows = effectivities(&runs[m], &runs[2], &away);
        let away = report("step_error.epp", mesh, &rows, "in [0.5, 2] (issue 49), without the root's first 37.5 mm")[0];
        for (id, eff) in [("whole", whole), ("away", away)] {
            assert!((0.5..=2.0).contains(&eff), "{mesh} {id}: effectivity {eff}");
        }
    }
}

/// The imperfect column past its Euler load (`column_postbuckling.toml`:
/// nonlinear geometry, one step of 40 increments turning the tip by about
/// 91°, elastic), 1 L9 × 20 B4 and 2 × 2 × 40, against 4 × 4 × 80: the
/// effectivity of its step end: in issue 49's band on both meshes (measured
/// 0.70 and 1.17), even with one L9 across the section, unlike the elastica
/// (the column's error lies along its axis).
#[test]
#[ignore = "validate: slow — the column's 40 increments on three meshes, the finest 58,563 DOF (about 40 s)"]
fn the_postbuckled_column_step_is_estimated() {
    let text = example("column_postbuckling.toml");
    let counts = [("to = 0.01, ", 1), ("to = 0.0125, ", 1), ("to = 1.0, ", 20)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    for (m, mesh) in [(0, "1L9_20B4"), (1, "2x2L9_40B4")] {
        let rows = effectivities(&runs[m], &runs[2], &|_, _, _, _| true);
        let eff = report("step_error.column", mesh, &rows, "in [0.5, 2] (issue 49)")[0];
        assert!((0.5..=2.0).contains(&eff), "{mesh}: effectivity {eff}");
    }
}

/// The block's indentation test (`block_indentation_unload.toml`: the
/// punch pushed 1 mm, perfectly plastic, then pulled back until it leaves
/// the dent), the shipped mesh against every section division twice finer
/// and 3 B4 (as `estimator::the_block_s_plastic_end_state_is_estimated`,
/// element recovery): the effectivity of both step ends, without the
/// section elements touching a punch edge line (singular) and over the
/// whole block. After unloading every yielded point lies inside its yield
/// surface and keeps its stress fit (`post::yielded`): within issue 49's
/// `0.5`–`2` (measured 1.09 and 0.99 loaded, 1.28 and 1.12 unloaded).
/// Mutation: the unloaded points' total strains fitted and returned from
/// their converged state (their frozen plastic strain's roughness charged
/// as stress error) gives 2.32 and 2.18 unloaded and fails.
#[test]
#[ignore = "validate: slow — the block loaded and unloaded on two meshes, the finer 3 B4 (about 1 min)"]
fn the_block_s_indentation_test_steps_are_estimated() {
    let mesh = |k: usize, m: usize| block_refined(&example("block_indentation_unload.toml"), k, m);
    let (coarse, fine) = (solve(&mesh(1, 1)), solve(&mesh(2, 3)));
    let away = |m: &Model, _: usize, es: usize, _: usize| !touches_punch_edge(m, es);
    let check = "in [0.5, 2] (issue 49)";
    let rows = effectivities(&coarse, &fine, &away);
    let away = report("step_error.block_unload", "18x6L9_1B4", &rows, &format!("{check}, without the punch edges"));
    let rows = effectivities(&coarse, &fine, &|_, _, _, _| true);
    let whole = report("step_error.block_unload", "18x6L9_1B4.whole", &rows, check);
    assert_eq!(away.len(), 2, "the load and unload step ends");
    for (k, eff) in away.iter().chain(&whole).enumerate() {
        assert!((0.5..=2.0).contains(eff), "state {k}: effectivity {eff}");
    }
}

/// A tube's quarter (`bending_tube_20L9_quarter.toml` or the paper's
/// `bending_tube_28L9_quarter.toml`: the §4.2 tube, `around = 4 + 4 side`
/// L9 × 11 B4, elastoplastic, one step of 15 increments pressing the roller
/// 0.75 mm) with every division `k` times finer: `through = k` elements
/// through the wall and `side k` along each side (`around` is `through =
/// 1`, `along_x = along_z = side`), every axis segment's count times `k`.
fn tube_refined(text: &str, side: usize, k: usize) -> String {
    let around = format!("around = {} }}", 4 + 4 * side);
    let section = format!("through = {k}, along_x = {}, along_z = {} }}", side * k, side * k);
    assert!(text.contains(&format!("thickness = 0.0015, {around}")));
    let counts = [("to = 0.025, ", 2), ("to = 0.125, ", 9), ("to = 0.225, ", 9), ("to = 0.25, ", 2)];
    refined(&text.replace(&around, &section), k, &counts)
}

/// A shipped example whose mesh refined twice (every division four times
/// finer) is too long a run for CI: that run's stress at each Gauss point
/// of the shipped mesh, at the end of its analysis, is stored in
/// tests/data, re-made by a `validate: references` test.
struct Reference {
    /// The example (examples/).
    example: &'static str,
    /// The stored stresses.
    file: &'static str,
    /// The example's text refined twice: the whole model, or its part on
    /// the kept side of the planes `mirror` (sampled at the mirror images
    /// beyond them, [`stresses_at`]).
    refined: fn(&str) -> String,
    mirror: &'static [Plane],
    /// How `refined` makes the model, for the file's header.
    what: &'static str,
    /// The test that re-makes the file.
    remade_by: &'static str,
}

impl Reference {
    fn path(&self) -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(self.file)
    }

    /// The stored rows: global element, Gauss point `[x, y, z]` and stress.
    fn rows(&self) -> Vec<(usize, [f64; 3], [f64; 6])> {
        stored_rows(&self.path())
    }

    /// The stored reference stress at each Gauss point of `model`, its
    /// points checked against the model's.
    fn stresses(&self, model: &Model) -> Vec<[f64; 6]> {
        let (points, rows, name) = (gauss_points(model), self.rows(), self.file);
        assert_eq!(rows.len(), points.len(), "{name}: a stored stress at each Gauss point of the shipped mesh");
        rows.iter()
            .zip(&points)
            .map(|(&(element, position, stress), p)| {
                assert_eq!(element, p.element);
                assert!(
                    (0..3).all(|i| (position[i] - p.position[i]).abs() < 1e-9),
                    "{name}: not the shipped mesh's points"
                );
                stress
            })
            .collect()
    }

    /// The shipped example's step end against the stored stress, over the
    /// whole model and without `body`'s elements touching the roller lines
    /// `y ∈ rollers` ([`in_band`], reported as `<id>.<mesh>.…`).
    fn estimated(&self, id: &str, mesh: &str, (body, rollers): (usize, &'static [f64])) {
        self.estimated_whole(self.example, &[], (id, mesh), (&off_lines(body, rollers), "the roller lines"));
    }

    /// The model `example` (of which this reference's example is the part
    /// on the kept side of `planes`, none: the example itself) against the
    /// stored stress at the images of its Gauss points ([`mirrored`]), over
    /// the whole model and over the elements `away` picks ([`in_band`]).
    fn estimated_whole(&self, example: &str, planes: &[Plane], (id, mesh): (&str, &str), away: (Pick<'_>, &str)) {
        let coarse = solve(&self::example(example));
        let reference =
            if planes.is_empty() { self.stresses(&coarse.0) } else { mirrored(self.rows(), &coarse.0, planes) };
        let truth = error_against((&coarse.0, &coarse.1), &reference);
        in_band((id, mesh), &coarse, &truth, away);
    }

    /// Runs the refined model and writes the file.
    fn remake(&self) {
        let text = example(self.example);
        let log = &mut Log(std::time::Instant::now());
        let (model, fine) = (Model::parse(&text).unwrap(), solve_with(&(self.refined)(&text), log));
        let points = gauss_points(&model);
        let stresses = stresses_at((&fine.0, &fine.1), &points, self.mirror);
        let header = format!(
            "# The stress (Pa, Voigt order xx yy zz xy xz yz) of examples/{} {} ({} DOF) at the end of\n\
             # its analysis, at each Gauss point of the shipped mesh (global element, x, y, z in m).\n\
             # Remade by cargo test --release --test suite -- --ignored --exact step_error::{}\n",
            self.example,
            self.what,
            fine.0.n_dofs(),
            self.remade_by
        );
        store_rows(&self.path(), header, &points, &stresses);
    }
}

/// A stored reference file of tests/data.
fn data(file: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(file)
}

/// The rows of a stored reference: global element, Gauss point `[x, y, z]`
/// and stress.
fn stored_rows(path: &std::path::Path) -> Vec<(usize, [f64; 3], [f64; 6])> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("element"))
        .map(|l| {
            let r: Vec<f64> = l.split(',').map(|v| v.trim().parse().unwrap()).collect();
            (r[0] as usize, std::array::from_fn(|i| r[1 + i]), std::array::from_fn(|i| r[4 + i]))
        })
        .collect()
}

/// Writes a stored reference: `header` (comment lines), then a row per
/// Gauss point of `points` with its stress.
fn store_rows(path: &std::path::Path, header: String, points: &[truth::GaussPoint], stresses: &[[f64; 6]]) {
    let mut out = header + "element,x,y,z,s_xx,s_yy,s_zz,s_xy,s_xz,s_yz\n";
    for (p, s) in points.iter().zip(stresses) {
        let v: Vec<String> = p.position.iter().chain(s).map(|x| format!("{x:.9e}")).collect();
        out += &format!("{},{}\n", p.element, v.join(","));
    }
    std::fs::write(path, out).unwrap();
}

/// The stress at each Gauss point of `whole` from `rows` (global element,
/// Gauss point, stress) given at the Gauss points of its part on the kept
/// side of `planes` (`whole`'s mesh that part's mirror images): each point
/// takes the stress of the row at its [`image`], which must be there, its
/// shears turned over.
fn mirrored(mut rows: Vec<(usize, [f64; 3], [f64; 6])>, whole: &Model, planes: &[Plane]) -> Vec<[f64; 6]> {
    rows.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]));
    gauss_points(whole)
        .iter()
        .map(|p| {
            let (at, sign) = image(p.position, planes);
            let from = rows.partition_point(|r| r.1[0] < at[0] - 1e-9);
            let r = rows[from..]
                .iter()
                .take_while(|r| r.1[0] < at[0] + 1e-9)
                .find(|r| (0..3).all(|i| (r.1[i] - at[i]).abs() < 1e-9))
                .unwrap_or_else(|| panic!("no point of the part at {at:?}, the image of {:?}", p.position));
            std::array::from_fn(|i| sign[i] * r.2[i])
        })
        .collect()
}

/// Picks the elements of every body but `body`, and those of `body` whose
/// axis span does not touch any of the lines `y ∈ ys` (roller lines).
fn off_lines(body: usize, ys: &'static [f64]) -> impl Fn(&Model, usize, usize, usize) -> bool {
    move |m: &Model, b: usize, _: usize, eb: usize| {
        let (a, c) = m.mesh.bodies[b].axis.element_span(eb);
        b != body || !ys.iter().any(|&y| y > a - 1e-9 && y < c + 1e-9)
    }
}

/// The one step end of `coarse` whose true error per element is `truth`,
/// over the whole model and over the elements `away` picks (away from the
/// lines `lines` names, its roller lines by default): reported as
/// `<id>.<mesh>.whole.load.*` and `<id>.<mesh>.load.*`, both effectivities
/// asserted in issue 49's band.
fn in_band((id, mesh): (&str, &str), coarse: &(Model, Solution), truth: &[f64], away: (Pick<'_>, &str)) {
    in_band_at("load", (id, mesh), (&coarse.0, &coarse.1), truth, away);
}

/// [`in_band`] of the state `state` (`s`, of `model`), reported as
/// `<id>.<mesh>.whole.<state>.*` and `<id>.<mesh>.<state>.*`.
fn in_band_at(
    state: &str,
    (id, mesh): (&str, &str),
    (model, s): (&Model, &Solution),
    truth: &[f64],
    (away, lines): (Pick<'_>, &str),
) {
    let check = "in [0.5, 2] (issue 49)";
    let whole = row(state, (model, s), truth, &|_, _, _, _| true);
    let whole = report(id, &format!("{mesh}.whole"), &[whole], check)[0];
    let away = row(state, (model, s), truth, away);
    let away = report(id, mesh, &[away], &format!("{check}, without {lines}"))[0];
    for (part, eff) in [("whole", whole), ("away", away)] {
        assert!((0.5..=2.0).contains(&eff), "{id} {state} {part}: effectivity {eff}");
    }
}

/// The two cantilevers in contact (`cantilevers_contact.toml`: 4 × 4 L9 ×
/// 10 B4 per beam, perfectly plastic, node-to-node contact between them,
/// two rollers pressed 2.5 mm, 20 increments) with every division `k`
/// times finer, cut by their plane of mirror symmetry x = 12.7 mm (the
/// beams, the rollers and the contact are their own mirror images across
/// it; `bench/cantilevers_half_20B4.toml` is that half with the axis
/// doubled): the half `x ≥ 12.7` mm.
fn cantilevers_refined_half(text: &str, k: usize) -> String {
    let counts = [("to = 0.0254, ", 4), ("to = 0.0508, ", 4), ("to = 0.254, ", 10), ("to = 0.3302, ", 10)];
    refined(text, k, &counts) + CANTILEVERS_PLANE
}

/// The cantilevers' plane of mirror symmetry, the half x ≥ 12.7 mm kept.
const CANTILEVERS_PLANE: &str = "\n[[symmetry]]\nname = \"symmetry_x\"\nplane = { x = 0.0127 }\nkeep = \"above\"\n";

/// The mirrored half of the stored reference checked where it is exact:
/// the cantilevers' half at the shipped divisions (`k = 1`), sampled at
/// the Gauss points of the whole shipped model (those below x = 12.7 mm at
/// their mirror images, σ_xy and σ_xz turned over), is the whole model's
/// own stress there: its "true error" is nil (measured `1e-17` of the
/// energy). Mutation: σ_xy and σ_xz not turned over gives `3.5e-2` and
/// fails.
#[test]
fn the_mirrored_half_reproduces_the_whole_cantilevers() {
    let text = example(CANTILEVERS.example);
    let (whole, half) = (solve(&text), solve(&cantilevers_refined_half(&text, 1)));
    let points = gauss_points(&whole.0);
    let error: f64 =
        error_against((&whole.0, &whole.1), &stresses_at((&half.0, &half.1), &points, CANTILEVERS.mirror)).iter().sum();
    let energy = whole.1.error_estimate.as_ref().unwrap().energy.powi(2);
    eprintln!("mirrored half against the whole: {:.3e} of the energy", error / energy);
    assert!(error < 1e-8 * energy, "{} of the energy", error / energy);
}

/// The paper's compact bar on its 16 L9 (`bending_compact_16L9_quarter.toml`:
/// the quarter, 2 × 4 L9 × 5 B4, elastoplastic, the roller pressed
/// 0.75 mm in 15 increments) with every division `k` times finer.
fn compact16_refined(text: &str, k: usize) -> String {
    refined(text, k, &[("to = 0.01, ", 4), ("to = 0.25, ", 10)])
}

const TUBE: Reference = Reference {
    example: "bending_tube_20L9_quarter.toml",
    file: "bending_tube_20L9_quarter_refined_twice.csv",
    refined: |text| tube_refined(text, 4, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `tube_refined(…, 4, 4)`)",
    remade_by: "the_tube_s_twice_refined_stresses_are_remade",
};

/// The shipped tube quarter's step end against the stress of its mesh
/// refined twice (160 L9 × 44 B4, 290,871 DOF, about 20 min: stored), over
/// the whole quarter and without the beam elements touching a roller line
/// (the support at y = 25 mm and the load at the symmetry plane y = 125 mm:
/// node lines pressed by rigid cylinders, where the true error has no
/// limit, as on the compact bar): within issue 49's `0.5`–`2` (measured
/// 0.96 whole and 1.12 away, the estimate 29.3 % against a true 30.5 % over
/// the quarter). Mutation: the yielding points' fitted strains returned
/// from their converged state (`post::yielded`, no monotonic base) gives
/// 1.63 and 1.92, inside the band: not caught here (the graded tube's test
/// catches it, 2.14, and the punch's); the yielded body's stresses recovered instead
/// of its strains (`post::yielded::replace_recovery` returning at once:
/// 0.81, 1.10) stay in the band, the tube's plastic zone being a few wall
/// elements under the roller.
#[test]
fn the_tube_step_is_estimated() {
    TUBE.estimated("step_error.tube", "10L9_11B4", (0, &[0.025, 0.125]));
}

#[test]
#[ignore = "validate: references — the tube's quarter refined twice (290,871 DOF, about 20 min)"]
fn the_tube_s_twice_refined_stresses_are_remade() {
    TUBE.remake();
}

const CANTILEVERS: Reference = Reference {
    example: "cantilevers_contact.toml",
    file: "cantilevers_contact_refined_twice.csv",
    refined: |text| cantilevers_refined_half(text, 4),
    mirror: &[Plane { axis: 0, at: 0.0127, above: true }],
    what: "refined twice, its half x ≥ 12.7 mm (tests/step_error.rs `cantilevers_refined_half(…, 4)`), mirrored below x = 12.7 mm",
    remade_by: "the_cantilevers_twice_refined_stresses_are_remade",
};

/// The shipped cantilevers' step end against the stress of their model
/// refined twice (16 × 16 L9 × 40 B4 per beam; its half, 407,286 DOF,
/// about 30 min: stored), over both beams and without the upper beam's
/// elements touching a roller line (y = 177.8 and 228.6 mm: node lines
/// pressed by rigid cylinders): within issue 49's `0.5`–`2` (measured 0.71
/// both ways, the estimate 20.5 % against a true 28.2 % over both beams).
/// Mutation: the yielding points' fitted strains returned from their
/// converged state (`post::yielded`, no monotonic base) gives 1.94 and
/// 2.16 and fails; the yielded bodies' stresses recovered instead of their
/// strains (0.79, 0.81) stay in the band.
#[test]
fn the_cantilevers_step_is_estimated() {
    CANTILEVERS.estimated("step_error.cantilevers", "4x4L9_10B4", (0, &[0.1778, 0.2286]));
}

#[test]
#[ignore = "validate: references — the cantilevers' half refined twice (407,286 DOF, about 30 min)"]
fn the_cantilevers_twice_refined_stresses_are_remade() {
    CANTILEVERS.remake();
}

const CANTILEVERS_FINE: Reference = Reference {
    example: "cantilevers_contact_fine.toml",
    file: "cantilevers_contact_fine_refined.csv",
    refined: cantilevers_fine_refined,
    mirror: &[Plane { axis: 0, at: 0.0127, above: true }],
    what: "with its section refined twice and its axis once, its half x ≥ 12.7 mm: the shipped cantilevers refined \
           twice (tests/step_error.rs `cantilevers_fine_refined`), mirrored below x = 12.7 mm",
    remade_by: "the_fine_cantilevers_refined_stresses_are_remade",
};

/// The cantilevers on their fine axis (`cantilevers_contact_fine.toml`: 4 ×
/// 4 L9 × 20 B4 per beam) with every section division four times finer
/// and the axis twice: the half of the shipped cantilevers refined twice
/// (`cantilevers_refined_half(…, 4)`, 407,286 DOF), the model behind
/// [`CANTILEVERS`]'s stored stresses.
fn cantilevers_fine_refined(text: &str) -> String {
    let axis = "elements = 20 }";
    assert_eq!(text.matches(axis).count(), 2, "{axis}");
    let shipped = example("cantilevers_contact.toml");
    let fine = cantilevers_refined_half(&text.replace(axis, "elements = 10 }"), 4);
    assert_eq!(model_lines(&fine), model_lines(&cantilevers_refined_half(&shipped, 4)));
    fine
}

/// A model file's lines but for its title and comments: two files with
/// the same are the same model.
fn model_lines(text: &str) -> Vec<&str> {
    text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("title")).collect()
}

/// The cantilevers on their fine axis against their half with the section
/// refined twice and the axis once (16 × 16 L9 × 40 B4 per beam, the
/// shipped cantilevers' twice-refined model: stored at this mesh's Gauss
/// points), over both beams and without the upper beam's elements touching
/// a roller line: within issue 49's `0.5`–`2`. Refined once only along the
/// axis, the reference leaves part of the true error out (`1 − 2^(−p)` of
/// it with the error falling as `h^p`): the effectivity reads up to
/// `1/(1 − 2^(−p))` high.
#[test]
fn the_fine_cantilevers_step_is_estimated() {
    CANTILEVERS_FINE.estimated("step_error.cantilevers_fine", "4x4L9_20B4", (0, &[0.1778, 0.2286]));
}

#[test]
#[ignore = "validate: references — the cantilevers' half refined twice, at the Gauss points of the fine axis mesh (407,286 DOF, about 30 min)"]
fn the_fine_cantilevers_refined_stresses_are_remade() {
    CANTILEVERS_FINE.remake();
}

/// The frictional twin (`cantilevers_contact_friction.toml`: the same
/// model with Coulomb friction μ = 0.3 between the beams), its reference
/// made the same way (the friction is its own mirror image across
/// x = 12.7 mm as well).
const CANTILEVERS_FRICTION: Reference = Reference {
    example: "cantilevers_contact_friction.toml",
    file: "cantilevers_contact_friction_refined_twice.csv",
    remade_by: "the_frictional_cantilevers_twice_refined_stresses_are_remade",
    ..CANTILEVERS
};

/// The shipped frictional cantilevers' step end against the stress of
/// their model refined twice (the half, 407,286 DOF, about 30 min:
/// stored), as [`the_cantilevers_step_is_estimated`]: within issue 49's
/// `0.5`–`2` (measured 0.70 whole and 0.72 without the roller lines, the
/// estimate 20.7 % against a true 29.0 % over both beams). That reference
/// could be made only once a sliding point's stick tangent was kept to the
/// first evaluation of a retry (tests/friction.rs
/// `a_fine_frictional_peel_converges_in_its_retry`).
#[test]
fn the_frictional_cantilevers_step_is_estimated() {
    CANTILEVERS_FRICTION.estimated("step_error.cantilevers_friction", "4x4L9_10B4", (0, &[0.1778, 0.2286]));
}

#[test]
#[ignore = "validate: references — the frictional cantilevers' half refined twice (407,286 DOF, hours)"]
fn the_frictional_cantilevers_twice_refined_stresses_are_remade() {
    CANTILEVERS_FRICTION.remake();
}

/// The frictional cantilevers on non-matching meshes
/// (`cantilevers_contact_nonmatching_friction.toml`: the upper beam 4 × 4
/// L9, the lower 5 × 3 L9, each × 10 B4, surface-to-surface contact with
/// μ = 0.3) with every division `k` times finer, cut by their plane of
/// mirror symmetry x = 12.7 mm as [`cantilevers_refined_half`] (an element
/// boundary once `k` is even).
fn nonmatching_refined_half(text: &str, k: usize) -> String {
    let counts = [
        ("x = { from = 0.0, to = 0.0254, ", 4),
        ("z = { from = 0.0254, to = 0.0508, ", 4),
        ("x = { from = 0.0, to = 0.0254, ", 5),
        ("z = { from = 0.0, to = 0.0254, ", 3),
        ("from = 0.0, to = 0.254, ", 10),
        ("from = 0.0762, to = 0.3302, ", 10),
    ];
    refined(text, k, &counts) + CANTILEVERS_PLANE
}

const NONMATCHING_FRICTION: Reference = Reference {
    example: "cantilevers_contact_nonmatching_friction.toml",
    file: "cantilevers_contact_nonmatching_friction_refined_twice.csv",
    refined: |text| nonmatching_refined_half(text, 4),
    mirror: &[Plane { axis: 0, at: 0.0127, above: true }],
    what: "refined twice, its half x ≥ 12.7 mm (tests/step_error.rs `nonmatching_refined_half(…, 4)`), mirrored below x = 12.7 mm",
    remade_by: "the_nonmatching_frictional_cantilevers_twice_refined_stresses_are_remade",
};

/// The shipped non-matching frictional cantilevers' step end against the
/// stress of their model refined twice (the half, 394,218 DOF, 41 min:
/// stored), over both beams and without the upper beam's elements touching
/// a roller line: within issue 49's `0.5`–`2` (measured 0.69 whole and
/// 0.71 away, the estimate 20.2 % against a true 28.5 % over both beams).
#[test]
fn the_nonmatching_frictional_cantilevers_step_is_estimated() {
    NONMATCHING_FRICTION.estimated("step_error.nonmatching_friction", "4x4L9_5x3L9_10B4", (0, &[0.1778, 0.2286]));
}

#[test]
#[ignore = "validate: references — the non-matching frictional cantilevers' half refined twice (394,218 DOF)"]
fn the_nonmatching_frictional_cantilevers_twice_refined_stresses_are_remade() {
    NONMATCHING_FRICTION.remake();
}

/// The frictionless non-matching cantilevers
/// (`cantilevers_contact_nonmatching.toml`: the frictional twin's model
/// without friction), their reference made the same way.
const NONMATCHING: Reference = Reference {
    example: "cantilevers_contact_nonmatching.toml",
    file: "cantilevers_contact_nonmatching_refined_twice.csv",
    remade_by: "the_nonmatching_cantilevers_twice_refined_stresses_are_remade",
    ..NONMATCHING_FRICTION
};

/// The shipped non-matching cantilevers' step end against the stress of
/// their model refined twice (the half, 394,218 DOF: stored), as
/// [`the_nonmatching_frictional_cantilevers_step_is_estimated`]: within
/// issue 49's `0.5`–`2` (measured 0.72 whole and 0.72 away, the estimate
/// 20.0 % against a true 27.5 % over both beams; the reference took 47 min
/// and 6.7 GB, 40 of them in its first increment: three failed attempts
/// peeling the stacked beams open, docs/limitations.md).
#[test]
fn the_nonmatching_cantilevers_step_is_estimated() {
    NONMATCHING.estimated("step_error.nonmatching", "4x4L9_5x3L9_10B4", (0, &[0.1778, 0.2286]));
}

#[test]
#[ignore = "validate: references — the non-matching cantilevers' half refined twice (394,218 DOF)"]
fn the_nonmatching_cantilevers_twice_refined_stresses_are_remade() {
    NONMATCHING.remake();
}

/// A profile under rollers (`channel_roller.toml`, `ibeam_roller.toml`: 2
/// L9 along each flange (outstand), 6 along the web, 1 through each wall;
/// along the axis `ends` B4 over each 25 mm beyond a support and `graded`
/// over each half span, graded towards the loading roller) with every
/// division `k` times finer, each graded segment keeping its ratio.
fn profile_refined(text: &str, k: usize, (ends, graded): (usize, usize)) -> String {
    let section = "along_flange = 2, along_web = 6, through = 1 }";
    assert!(text.contains(section), "{section}");
    let text = text.replace(section, &format!("along_flange = {}, along_web = {}, through = {k} }}", 2 * k, 6 * k));
    let mut out = refined(&text, k, &[("from = 0.0, to = 0.025, ", ends), ("from = 0.625, to = 0.65, ", ends)]);
    for to in ["0.325", "0.625"] {
        let from = format!("to = {to}, elements = {graded}, ratio");
        assert!(out.contains(&from), "{from}");
        out = out.replace(&from, &format!("to = {to}, elements = {}, ratio", graded * k));
    }
    out
}

/// The channel pressed on one flange (`channel_roller.toml`: its half
/// y ≤ 0.325 m, 2 + 20 B4, elastic, a rigid roller pressed 1 mm off the
/// shear centre) with every division `k` times finer.
fn channel_refined(text: &str, k: usize) -> String {
    profile_refined(text, k, (2, 20))
}

const CHANNEL: Reference = Reference {
    example: "channel_roller.toml",
    file: "channel_roller_refined_twice.csv",
    refined: |text| channel_refined(text, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `channel_refined(…, 4)`)",
    remade_by: "the_channel_s_twice_refined_stresses_are_remade",
};

/// The channel pressed on one flange against the stress of its mesh
/// refined twice (8 L9 along each flange, 24 along the web, 4 through each
/// wall × 88 B4, 694,035 DOF: stored), over the half and without the beam
/// elements touching a roller line (the support at y = 25 mm, the loading
/// roller at 325 mm): within issue 49's `0.5`–`2` (measured 1.53 whole and
/// 1.33 away, the estimate 15.9 % against a true 10.5 % over the half; the
/// reference took 8 min and 9.3 GB, its one increment converging in its
/// retry). Mutation: the section patches unweighted by element area
/// (`post::spr`) gives 1.93 and 1.81, inside the band: not caught here.
#[test]
fn the_channel_step_is_estimated() {
    CHANNEL.estimated("step_error.channel", "12L9_22B4", (0, &[0.025, 0.325]));
}

#[test]
#[ignore = "validate: references — the channel refined twice (694,035 DOF)"]
fn the_channel_s_twice_refined_stresses_are_remade() {
    CHANNEL.remake();
}

/// The I-beam under its roller (`ibeam_roller.toml`: 1 + 10 + 10 + 1 B4,
/// elastoplastic, three rigid rollers, 20 increments) with every division
/// `k` times finer ([`profile_refined`]), cut by its two planes of mirror symmetry
/// ([`IBEAM_QUARTER`]: the web's mid-plane x = 0, an element boundary once
/// `k` is even, and mid-span y = 0.325 m): the quarter x ≥ 0, y ≤ 0.325 m.
fn ibeam_refined_quarter(text: &str, k: usize) -> String {
    profile_refined(text, k, (1, 10))
        + "\n[[symmetry]]\nname = \"mid_web\"\nplane = { x = 0.0 }\nkeep = \"above\"\n\n\
           [[symmetry]]\nname = \"mid_span\"\nplane = { y = 0.325 }\nkeep = \"below\"\n"
}

/// The I-beam's planes of mirror symmetry: the web's mid-plane x = 0 and
/// mid-span y = 0.325 m (the loading roller's line).
const IBEAM_QUARTER: [Plane; 2] = [Plane { axis: 0, at: 0.0, above: true }, Plane { axis: 1, at: 0.325, above: false }];

const IBEAM: Reference = Reference {
    example: "ibeam_roller.toml",
    file: "ibeam_roller_refined_twice.csv",
    refined: |text| ibeam_refined_quarter(text, 4),
    mirror: &IBEAM_QUARTER,
    what: "refined twice, its quarter x ≥ 0, y ≤ 0.325 m (tests/step_error.rs `ibeam_refined_quarter(…, 4)`), mirrored",
    remade_by: "the_ibeam_s_twice_refined_stresses_are_remade",
};

/// The I-beam under its roller against the stress of its mesh refined
/// twice (its quarter, 244,587 DOF: stored), over the whole beam and
/// without the beam elements touching a roller line (y = 25, 325 and
/// 625 mm): within issue 49's `0.5`–`2` (measured 1.03 whole and 1.12
/// away, the estimate 14.2 % against a true 13.8 % over the beam; the
/// reference took 6 min and 2.3 GB). The whole model already holds u_x = 0
/// on the web's mid-plane and u_y = 0 at mid-span (its constraints
/// `symmetry_x`, `symmetry_y`) and its rollers are their own mirror images,
/// so the quarter is the whole model's own half of a half. Mutations: the
/// yielded body's stresses recovered instead of its strains
/// (`post::yielded::replace_recovery` returning at once) gives 0.88 and
/// 1.11, and the section patches unweighted by area 1.13 and 1.36, inside
/// the band: not caught here.
#[test]
fn the_ibeam_step_is_estimated() {
    IBEAM.estimated("step_error.ibeam", "16L9_22B4", (0, &[0.025, 0.325, 0.625]));
}

#[test]
#[ignore = "validate: references — the I-beam's quarter refined twice (244,587 DOF)"]
fn the_ibeam_s_twice_refined_stresses_are_remade() {
    IBEAM.remake();
}

const COMPACT16: Reference = Reference {
    example: "bending_compact_16L9_quarter.toml",
    file: "bending_compact_16L9_quarter_refined_twice.csv",
    refined: |text| compact16_refined(text, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `compact16_refined(…, 4)`)",
    remade_by: "the_compact_bar_s_twice_refined_stresses_are_remade",
};

/// The shipped compact bar's 16 L9 quarter's step end against the stress
/// of its mesh refined twice (8 × 16 L9 × 20 B4, 102,663 DOF: stored), over
/// the whole quarter and without the beam elements touching a roller line:
/// within issue 49's `0.5`–`2` (measured 1.01 and 0.86, the estimate 3.63 %
/// against a true 3.60 % over the quarter). Mutation: the yielded body's
/// stresses recovered instead of its strains
/// (`post::yielded::replace_recovery` returning at once) gives 2.38 and
/// 2.01 and fails; the yielding points' fits returned from their converged
/// state (1.30, 0.87) stay in the band.
#[test]
fn the_compact_bar_s_16l9_step_is_estimated() {
    COMPACT16.estimated("step_error.compact16", "2x4L9_5B4", (0, &[0.025, 0.125]));
}

#[test]
#[ignore = "validate: references — the compact bar's 16 L9 quarter refined twice (102,663 DOF, about 30 s)"]
fn the_compact_bar_s_twice_refined_stresses_are_remade() {
    COMPACT16.remake();
}

const TUBE28: Reference = Reference {
    example: "bending_tube_28L9_quarter.toml",
    file: "bending_tube_28L9_quarter_refined_twice.csv",
    refined: |text| tube_refined(text, 6, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `tube_refined(…, 6, 4)`)",
    remade_by: "the_paper_s_tube_s_twice_refined_stresses_are_remade",
};

/// The paper's tube (its shipped quarter on 28 L9) against the stress of
/// its quarter refined twice (224 L9 × 44 B4, 405,783 DOF, about 35 min:
/// stored), over the whole quarter and without the beam elements touching a
/// roller line, as the 20 L9 tube: within issue 49's `0.5`–`2` (measured
/// 0.94 and 1.08, the estimate 27.4 % against a true 29.0 % over the
/// quarter). Mutation: the yielding points' fits returned from their
/// converged state (`post::yielded`, no monotonic base) gives 1.63 and
/// 1.73, inside the band: not caught here (the graded tube's test catches
/// it, 2.14).
#[test]
fn the_paper_s_tube_step_is_estimated() {
    TUBE28.estimated("step_error.tube28", "14L9_11B4", (0, &[0.025, 0.125]));
}

#[test]
#[ignore = "validate: references — the paper's tube quarter refined twice (405,783 DOF, about 35 min)"]
fn the_paper_s_tube_s_twice_refined_stresses_are_remade() {
    TUBE28.remake();
}

const GRADED: Reference = Reference {
    example: "bending_tube_graded_quarter.toml",
    file: "bending_tube_graded_quarter_refined_twice.csv",
    refined: |text| graded_refined(text, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `graded_refined(…, 4)`)",
    remade_by: "the_graded_tube_s_twice_refined_stresses_are_remade",
};

/// The graded tube's quarter (`bending_tube_graded_quarter.toml`: 14 L9 ×
/// 12 B4, the axis graded towards the loading roller) with every division
/// `k` times finer (`tube_refined` for the section, every axis segment's
/// count times `k`).
fn graded_refined(text: &str, k: usize) -> String {
    let around = "around = 28 }";
    let section = format!("through = {k}, along_x = {}, along_z = {} }}", 6 * k, 6 * k);
    assert!(text.contains(&format!("thickness = 0.0015, {around}")));
    let counts = [
        ("to = 0.025, ", 2),
        ("to = 0.115, ", 6),
        ("to = 0.121, ", 2),
        ("to = 0.125, ", 2),
        ("to = 0.129, ", 2),
        ("to = 0.135, ", 2),
        ("to = 0.225, ", 6),
        ("to = 0.25, ", 2),
    ];
    refined(&text.replace(around, &section), k, &counts)
}

/// The shipped graded tube quarter against the stress of its mesh refined
/// twice (224 L9 × 48 B4: stored), over the whole quarter and without the
/// beam elements touching a roller line: within issue 49's `0.5`–`2`
/// (measured 0.85 whole and 0.95 away, the estimate 22.3 % against a true
/// 25.9 % over the quarter; the reference run took 11 min on one thread).
/// Mutation: the yielding points' fits returned from their converged state
/// (`post::yielded`, no monotonic base) gives 1.46 and 2.14 and fails.
#[test]
fn the_graded_tube_step_is_estimated() {
    GRADED.estimated("step_error.graded", "14L9_12B4", (0, &[0.025, 0.125]));
}

/// The whole graded tube (`bending_tube_graded.toml`, 28 L9 × 24 B4)
/// against the graded quarter's stored reference mirrored: within
/// `0.5`–`2` (measured 0.86 and 0.95).
#[test]
fn the_whole_graded_tube_step_is_estimated() {
    GRADED.estimated_whole(
        "bending_tube_graded.toml",
        &TUBE_QUARTER,
        ("step_error.graded_whole", "28L9_24B4"),
        (&off_lines(0, WHOLE_ROLLERS), "the roller lines"),
    );
}

#[test]
#[ignore = "validate: references — the graded tube's quarter refined twice (442,395 DOF, about 15 min)"]
fn the_graded_tube_s_twice_refined_stresses_are_remade() {
    GRADED.remake();
}

const GRADED_WALL2: Reference = Reference {
    example: "bending_tube_graded_wall2.toml",
    file: "bending_tube_graded_wall2_refined.csv",
    refined: graded_wall2_refined,
    mirror: &[],
    what: "with its section refined once and its axis twice, the graded quarter refined twice \
           (tests/step_error.rs `graded_wall2_refined`)",
    remade_by: "the_graded_tube_with_two_l9_through_the_wall_refined_stresses_are_remade",
};

/// The graded tube's quarter with two L9 through the wall
/// (`bending_tube_graded_wall2.toml`: the graded quarter's section refined
/// once, 2 L9 through the wall and 12 along each side, on its axis) with
/// its section refined once more (4 through the wall, 24 along each side) and every axis division
/// four times finer: the graded quarter refined twice (`graded_refined(…,
/// 4)`, 442,395 DOF), the model behind [`GRADED`]'s stored stresses.
fn graded_wall2_refined(text: &str) -> String {
    let section = "through = 2, along_x = 12, along_z = 12 }";
    assert!(text.contains(section), "{section}");
    let quarter = example("bending_tube_graded_quarter.toml");
    let axis_only = |t: &str| graded_refined(&t.replace(section, "around = 28 }"), 4);
    let fine = axis_only(text);
    assert_eq!(model_lines(&fine), model_lines(&graded_refined(&quarter, 4)));
    fine
}

/// The shipped graded quarter with two L9 through the wall against its
/// mesh with the section refined once and the axis twice (224 L9 × 48 B4,
/// the graded quarter's twice-refined model, 442,395 DOF: stored at this
/// mesh's Gauss points), over the whole quarter and without the beam
/// elements touching a roller line: within issue 49's `0.5`–`2`. Refined
/// once only across the section, the reference leaves part of the true
/// error out: with the error falling as `h^p` it is `1 − 2^(−p)` of it
/// (`0.75` for `p = 2`), so the effectivity reads up to `1/0.75` high.
#[test]
fn the_graded_tube_with_two_l9_through_the_wall_is_estimated() {
    GRADED_WALL2.estimated("step_error.graded_wall2", "wall2_12B4", (0, &[0.025, 0.125]));
}

#[test]
#[ignore = "validate: references — the graded tube's quarter refined twice, at the Gauss points of its two-through-the-wall mesh (442,395 DOF, about 15 min)"]
fn the_graded_tube_with_two_l9_through_the_wall_refined_stresses_are_remade() {
    GRADED_WALL2.remake();
}

/// The graded block (`block_indentation_graded.toml`: 16 × 6 L9 × 3 B3,
/// graded towards the punch's edges, plastic) with every division `k`
/// times finer, each graded segment keeping its ratio, its stresses
/// recovered element by element (the true error samples them).
fn block_graded_refined(text: &str, k: usize) -> String {
    let counts = [("elements = 3 }", 3), ("elements = 2 }", 2), ("elements = 3, ratio", 3), ("elements = 6, ratio", 6)];
    let out = counts.iter().fold(text.to_string(), |out, &(from, n)| {
        assert!(out.contains(from), "{from}");
        out.replace(from, &from.replace(&n.to_string(), &(n * k).to_string()))
    });
    assert!(out.contains("recovery = \"projection\""));
    out.replace("recovery = \"projection\"", "recovery = \"element\"")
}

const BLOCK_GRADED: Reference = Reference {
    example: "block_indentation_graded.toml",
    file: "block_indentation_graded_refined_twice.csv",
    refined: |text| block_graded_refined(text, 4),
    mirror: &[],
    what: "refined twice (tests/step_error.rs `block_graded_refined(…, 4)`)",
    remade_by: "the_graded_block_s_twice_refined_stresses_are_remade",
};

/// The shipped graded block against the stress of its mesh refined twice
/// (64 × 24 L9 × 12 B3, 474,075 DOF: stored), over the whole block and
/// without the section elements touching a punch edge line (where the
/// stress is singular): within issue 49's `0.5`–`2` (measured 1.66 whole
/// and 1.73 without the edges, the estimate 22.1 % against a true 13.5 %:
/// the upper half of the band, as the uniform block's refined meshes; the
/// reference run took 9 min on one thread).
#[test]
fn the_graded_block_step_is_estimated() {
    let edges = |m: &Model, _: usize, es: usize, _: usize| !touches_punch_edge(m, es);
    let id = ("step_error.block_graded", "16x6L9_3B3");
    BLOCK_GRADED.estimated_whole(BLOCK_GRADED.example, &[], id, (&edges, "the punch edges"));
}

#[test]
#[ignore = "validate: references — the graded block refined twice (474,075 DOF, about 10 min)"]
fn the_graded_block_s_twice_refined_stresses_are_remade() {
    BLOCK_GRADED.remake();
}

/// The sandwich beam's planes of mirror symmetry: the beam's mid-width
/// x = 0 and its mid-span y = 0.1 m (the cylinder's line).
const SANDWICH_QUARTER: [Plane; 2] =
    [Plane { axis: 0, at: 0.0, above: true }, Plane { axis: 1, at: 0.1, above: false }];

/// The indented sandwich beam (`sandwich_indentation.toml`: 3 L9 across
/// the width, one per skin and four through the foam core, 3 + 8 + 3 B4,
/// elastic, a rigid cylinder pressed 0.5 mm at mid-span) with every
/// division `k` times finer (each graded axis segment keeping its ratio),
/// cut by its two planes of mirror symmetry ([`SANDWICH_QUARTER`]): the
/// quarter `x ≥ 0`, `y ≤ 0.1` m.
fn sandwich_refined_quarter(text: &str, k: usize) -> String {
    let mut out = text.to_string();
    for (from, to) in [
        ("to = 0.08, elements = 3, ratio", format!("to = 0.08, elements = {}, ratio", 3 * k)),
        ("to = 0.12, elements = 8 }", format!("to = 0.12, elements = {} }}", 8 * k)),
        ("to = 0.2, elements = 3, ratio", format!("to = 0.2, elements = {}, ratio", 3 * k)),
        ("to = 0.01, elements = 3 }", format!("to = 0.01, elements = {} }}", 3 * k)),
        ("angle = 0.0, elements = 1 }", format!("angle = 0.0, elements = {k} }}")),
        ("material = \"foam\", elements = 4 }", format!("material = \"foam\", elements = {} }}", 4 * k)),
    ] {
        assert!(out.contains(from), "{from}");
        out = out.replace(from, &to);
    }
    out + "\n[[symmetry]]\nname = \"mid_width\"\nplane = { x = 0.0 }\nkeep = \"above\"\n\n\
           [[symmetry]]\nname = \"mid_span\"\nplane = { y = 0.1 }\nkeep = \"below\"\n"
}

const SANDWICH: Reference = Reference {
    example: "sandwich_indentation.toml",
    file: "sandwich_indentation_refined_twice.csv",
    refined: |text| sandwich_refined_quarter(text, 4),
    mirror: &SANDWICH_QUARTER,
    what: "refined twice, its quarter x ≥ 0, y ≤ 0.1 m (tests/step_error.rs `sandwich_refined_quarter(…, 4)`)",
    remade_by: "the_sandwich_s_twice_refined_stresses_are_remade",
};

/// The indented sandwich beam against its mesh refined twice (its quarter,
/// `162,435` DOF, 20 s; stored), over the whole beam and without the beam
/// elements touching the cylinder's line y = 0.1 m: a layered body (skins
/// and foam core of stiffnesses a thousand times apart, the recovery ply by
/// ply, the true error with each point's own material) within issue 49's
/// `0.5`–`2` (measured 0.72 whole, 0.84 away).
#[test]
fn the_sandwich_step_is_estimated() {
    let away = off_lines(0, &[0.1]);
    SANDWICH.estimated_whole(
        SANDWICH.example,
        &[],
        ("step_error.sandwich", "3x6L9_14B4"),
        (&away, "the cylinder's line"),
    );
}

#[test]
#[ignore = "validate: references — the sandwich beam's quarter refined twice (162,435 DOF, about 20 s)"]
fn the_sandwich_s_twice_refined_stresses_are_remade() {
    SANDWICH.remake();
}

/// The planes of the quarter models of the §4.2 bars (x = 5 mm, kept
/// above; y = 125 mm, kept below) and tubes (x = 15 mm; y = 125 mm).
const COMPACT_QUARTER: [Plane; 2] =
    [Plane { axis: 0, at: 0.005, above: true }, Plane { axis: 1, at: 0.125, above: false }];
const TUBE_QUARTER: [Plane; 2] =
    [Plane { axis: 0, at: 0.015, above: true }, Plane { axis: 1, at: 0.125, above: false }];

/// The roller lines of the whole §4.2 bars and tubes: the supports at
/// y = 25 and 225 mm, the load at 125 mm.
const WHOLE_ROLLERS: &[f64] = &[0.025, 0.125, 0.225];

/// The whole shipped models against their quarters' stored references
/// checked where it is exact: the 16 L9 bar's shipped quarter, its stress
/// at its own Gauss points mirrored across both planes, is the whole
/// shipped bar's own stress there (its "true error" measured `1.5e-18` of
/// the energy; the quarter holds the whole to `1e-6` in tests/symmetry.rs).
/// Mutation: the shears not turned over (`image` keeping the signs) gives
/// `1.8e-2` and fails.
#[test]
fn the_mirrored_quarter_reproduces_the_whole_bar() {
    let (quarter, whole) = (solve(&example(COMPACT16.example)), solve(&example("bending_compact_16L9.toml")));
    let rows =
        gauss_points(&quarter.0).iter().zip(&quarter.1.stresses).map(|(p, s)| (p.element, p.position, *s)).collect();
    let error: f64 = error_against((&whole.0, &whole.1), &mirrored(rows, &whole.0, &COMPACT_QUARTER)).iter().sum();
    let energy = whole.1.error_estimate.as_ref().unwrap().energy.powi(2);
    eprintln!("mirrored quarter against the whole: {:.3e} of the energy", error / energy);
    assert!(error < 1e-8 * energy, "{} of the energy", error / energy);
}

/// The whole shipped 20 L9 tube (`bending_tube_20L9.toml`, 20 L9 × 22 B4,
/// the quarter's mirror images) against the 20 L9 quarter's stored
/// reference mirrored across both planes, over the whole tube and without
/// the beam elements touching its three roller lines: within issue 49's
/// `0.5`–`2` (measured 0.96 whole and 1.12 away, as the quarter: the true
/// error is four times the quarter's, the estimate differs only by the
/// patches that now straddle the planes). Mutation: no monotonic base in
/// `post::yielded` gives 1.63 and 1.92, inside the band (the whole graded
/// tube's test catches it, 2.14).
#[test]
fn the_whole_tube_step_is_estimated() {
    TUBE.estimated_whole(
        "bending_tube_20L9.toml",
        &TUBE_QUARTER,
        ("step_error.tube_whole", "20L9_22B4"),
        (&off_lines(0, WHOLE_ROLLERS), "the roller lines"),
    );
}

/// The whole paper's tube (`bending_tube_28L9.toml`, 28 L9 × 22 B4) against
/// the 28 L9 quarter's stored reference mirrored, as the 20 L9 tube:
/// within `0.5`–`2` (measured 0.95 and 1.08).
#[test]
fn the_whole_paper_s_tube_step_is_estimated() {
    TUBE28.estimated_whole(
        "bending_tube_28L9.toml",
        &TUBE_QUARTER,
        ("step_error.tube28_whole", "28L9_22B4"),
        (&off_lines(0, WHOLE_ROLLERS), "the roller lines"),
    );
}

/// The springback tube's stored references: the step ends of its quarter
/// (`common::springback_quarter`) with every division four times finer
/// (`tube_refined(…, 4, 4)`, 160 L9 × 44 B4, 290,871 DOF), at the Gauss
/// points of the quarter at the shipped divisions.
const SPRINGBACK: [(&str, &str); 2] = [
    ("load", "bending_tube_springback_load_refined_twice.csv"),
    ("unload", "bending_tube_springback_unload_refined_twice.csv"),
];

/// The springback tube (`bending_tube_springback.toml`: the whole 20 L9
/// tube, 20 L9 × 22 B4, its roller pushed with 1.6 kN, then unloaded to 2 %
/// of it) at both step ends against its quarter's stored references
/// mirrored across both planes, over the whole tube and without the beam
/// elements touching its three roller lines: within issue 49's `0.5`–`2`
/// at both (measured loaded 0.97 whole and 1.10 away, unloaded 0.90 and
/// 1.24; the unloaded tube's residual stresses estimated at 23.0 % of their
/// energy away from the rollers against a true 18.7 %). Mutation: the
/// points that yielded and unloaded recovered from their converged state
/// instead of keeping their stress fit (`post::yielded`) gives 1.73 and
/// 2.39 unloaded and fails. The roller's travel loaded (+0.63 %), the
/// residual dent (+3.06 %) and the springback between them (−3.51 %)
/// within `5 %` of the refined quarter's (stored with its stresses); the
/// springback is elastic, so a 10 % stiffness error fails it.
#[test]
fn the_springback_steps_are_estimated() {
    let coarse = solve(&example("bending_tube_springback.toml"));
    let kept = states(&coarse.0, &coarse.1);
    assert_eq!(kept.len(), SPRINGBACK.len());
    for ((name, state), (step, file)) in kept.iter().zip(SPRINGBACK) {
        assert_eq!(name, step);
        let reference = mirrored(stored_rows(&data(file)), &coarse.0, &TUBE_QUARTER);
        let truth = error_against((&coarse.0, state), &reference);
        in_band_at(
            name,
            ("step_error.springback", "20L9_22B4"),
            (&coarse.0, state),
            &truth,
            (&off_lines(0, WHOLE_ROLLERS), "the roller lines"),
        );
    }
    // the roller's motion at both step ends, and the springback between
    // them, against the refined quarter's
    let text = std::fs::read_to_string(data(SPRINGBACK_ROLLER)).unwrap();
    let stored: Vec<f64> = text
        .lines()
        .filter(|l| l.starts_with("load,") || l.starts_with("unload,"))
        .map(|l| l[l.find(',').unwrap() + 1..].parse().unwrap())
        .collect();
    let ours: Vec<f64> = kept.iter().map(|(_, s)| s.contact("load").unwrap().displacement[2]).collect();
    let source = "the quarter refined twice";
    common::within("step_error.springback.roller.load.u_z", ours[0], stored[0], 0.05, source);
    common::within("step_error.springback.roller.unload.u_z", ours[1], stored[1], 0.05, source);
    common::within("step_error.springback.roller.springback", ours[0] - ours[1], stored[0] - stored[1], 0.05, source);
}

#[test]
#[ignore = "validate: references — the springback tube's quarter refined twice, loaded and unloaded (290,871 DOF, about 40 min)"]
fn the_springback_s_twice_refined_stresses_are_remade() {
    let text = common::springback_quarter(&example("bending_tube_springback.toml"));
    let log = &mut Log(std::time::Instant::now());
    let (model, fine) = (Model::parse(&text).unwrap(), solve_with(&tube_refined(&text, 4, 4), log));
    let points = gauss_points(&model);
    let kept = states(&fine.0, &fine.1);
    assert_eq!(kept.len(), SPRINGBACK.len());
    for ((name, state), (step, file)) in kept.iter().zip(SPRINGBACK) {
        assert_eq!(name, step);
        let header = format!(
            "# The stress (Pa, Voigt order xx yy zz xy xz yz) of the quarter of examples/bending_tube_springback.toml\n\
             # (tests/common `springback_quarter`) refined twice (tests/step_error.rs `tube_refined(…, 4, 4)`,\n\
             # {} DOF) at the end of its step {step:?}, at each Gauss point of that quarter at the shipped\n\
             # divisions (global element, x, y, z in m). Remade by cargo test --release --test suite --\n\
             # --ignored --exact step_error::the_springback_s_twice_refined_stresses_are_remade\n",
            fine.0.n_dofs()
        );
        store_rows(&data(file), header, &points, &stresses_at((&fine.0, state), &points, &[]));
    }
    // the roller's motion at each step end (the springback is their difference)
    let mut out = format!(
        "# The roller's displacement u_z (m) at each step end of the quarter of\n\
         # examples/bending_tube_springback.toml refined twice ({} DOF). Remade by cargo test --release\n\
         # --test suite -- --ignored --exact step_error::the_springback_s_twice_refined_stresses_are_remade\n\
         step,u_z\n",
        fine.0.n_dofs()
    );
    for (name, state) in &kept {
        out += &format!("{name},{:.9e}\n", state.contact("load").unwrap().displacement[2]);
    }
    std::fs::write(data(SPRINGBACK_ROLLER), out).unwrap();
}

/// The stored roller motion of the springback's refined quarter.
const SPRINGBACK_ROLLER: &str = "bending_tube_springback_roller_refined_twice.csv";

/// The whole paper's bar (`bending_compact_16L9.toml`, 4 × 4 L9 × 10 B4)
/// against its quarter's stored reference mirrored: within `0.5`–`2`
/// (measured 1.02 and 0.86).
#[test]
fn the_whole_compact_bar_s_16l9_step_is_estimated() {
    COMPACT16.estimated_whole(
        "bending_compact_16L9.toml",
        &COMPACT_QUARTER,
        ("step_error.compact16_whole", "4x4L9_10B4"),
        (&off_lines(0, WHOLE_ROLLERS), "the roller lines"),
    );
}

/// The Timoshenko cantilever (`cantilever_timoshenko.toml`: elastic, a tip
/// shear of 1 kN spread over the tip face, clamped root), 2 × 2 L9 × 5 B4
/// and 4 × 4 × 10, against 8 × 8 × 20: the effectivity of its one step,
/// over the whole beam and without the beam elements at the clamped root
/// and the loaded tip (where the 3D stress is singular: the clamp holds
/// the Poisson contraction, the load sits on the face's nodes): within
/// issue 49's `0.5`–`2` on both meshes.
#[test]
fn the_timoshenko_cantilever_step_is_estimated() {
    let text = example("cantilever_timoshenko.toml");
    let counts = [("to = 0.1, ", 2), ("to = 1.0, ", 5)];
    let runs: Vec<_> = [1, 2, 4].iter().map(|&k| solve(&refined(&text, k, &counts))).collect();
    for (m, mesh) in [(0, "2x2L9_5B4"), (1, "4x4L9_10B4")] {
        let truth = true_error((&runs[m].0, &runs[m].1), (&runs[2].0, &runs[2].1));
        in_band(
            ("step_error.timoshenko", mesh),
            &runs[m],
            &truth,
            (&off_lines(0, &[0.0, 1.0]), "the root and the tip"),
        );
    }
}

/// The plane-strain punch (`punch_plane_strain.toml`: 40 × 16 L9 × 1 B2,
/// u_y = 0 on both end faces, perfectly plastic, pressed 8 mm to full
/// plastic flow) with every section division `k` times finer; its one B2
/// along y is kept (every node held in y, the field is the same in every
/// section: a finer axis gives the same solution), each graded segment
/// keeping its ratio of last to first element.
fn punch_refined(text: &str, k: usize) -> String {
    let counts = [
        ("to = 0.45, ", 12, ", ratio"),
        ("to = 0.55, ", 16, " }"),
        ("to = 1.0, ", 12, ", ratio"),
        ("to = 0.5, ", 16, ", ratio"),
    ];
    counts.iter().fold(text.to_string(), |out, &(pattern, n, end)| {
        let from = format!("{pattern}elements = {n}{end}");
        assert!(out.contains(&from), "{from}");
        out.replace(&from, &format!("{pattern}elements = {}{end}", n * k))
    })
}

const PUNCH: Reference = Reference {
    example: "punch_plane_strain.toml",
    file: "punch_plane_strain_refined_twice.csv",
    refined: |text| punch_refined(text, 4),
    mirror: &[],
    what: "its section refined twice (tests/step_error.rs `punch_refined(…, 4)`)",
    remade_by: "the_punch_s_twice_refined_stresses_are_remade",
};

/// The shipped plane-strain punch at full plastic flow against the
/// stress of its section refined twice (160 × 64 L9, 248,454 DOF: stored),
/// over the whole block and without the section elements at the punch's
/// edges (x = 0.45 and 0.55 m on the top face, where the stress is
/// singular): within issue 49's `0.5`–`2` (measured 1.44 whole and 1.45
/// without the edges, the estimate 7.9 % against a true 5.5 %). Mutation:
/// the yielding points' fits returned from their converged state
/// (`post::yielded`, no monotonic base) gives 5.6 and 5.7 and fails; the
/// stresses recovered instead of the strains (`replace_recovery`
/// returning at once: 0.78, 0.76) stay in the band.
#[test]
fn the_punch_step_is_estimated() {
    let edges = |m: &Model, _: usize, es: usize, _: usize| !touches_any(m, es, &[[0.45, 0.5], [0.55, 0.5]]);
    PUNCH.estimated_whole(PUNCH.example, &[], ("step_error.punch", "40x16L9_1B2"), (&edges, "the punch edges"));
}

#[test]
#[ignore = "validate: references — the plane-strain punch's section refined twice (248,454 DOF, about 3 min)"]
fn the_punch_s_twice_refined_stresses_are_remade() {
    PUNCH.remake();
}

/// Lamé's stress at `(x, z)` of a tube `a ≤ r ≤ c` with pressures `pa`
/// inside and `pc` outside (plane stress, Voigt xx yy zz xy xz yz; the
/// tube's axis along y): `σ_rr = A − B/r²`, `σ_θθ = A + B/r²`.
fn lame([x, z]: [f64; 2], (a, c): (f64, f64), (pa, pc): (f64, f64)) -> [f64; 6] {
    let (a2, c2) = (a * a, c * c);
    let (big_a, big_b) = ((pa * a2 - pc * c2) / (c2 - a2), (pa - pc) * a2 * c2 / (c2 - a2));
    let r2 = x * x + z * z;
    let (rr, tt) = (big_a - big_b / r2, big_a + big_b / r2);
    let (cos2, sin2, sc) = (x * x / r2, z * z / r2, x * z / r2);
    [rr * cos2 + tt * sin2, 0.0, rr * sin2 + tt * cos2, 0.0, (rr - tt) * sc, 0.0]
}

/// The shrink fit (`shrink_fit.toml`: a shaft 20–30.02 mm pressed into a
/// hub 30–45 mm, elastic, 16 × 2 L9 × 4 B4 each, node-to-node contact)
/// and its section refined (32 × 4 L9) against Lamé's exact stress with
/// free ends (plane stress, exact in 3D: `σ_rr + σ_θθ` is uniform in each
/// tube, so is `ε_yy`), the pressure `p = 25.65 MPa` of the example's
/// header: the estimate over both tubes within issue 49's `0.5`–`2`
/// (measured 1.05 on both; 0.97 on 48 × 6 L9). The error is the section's:
/// quadratic arcs around a circle. Mutation: the section patches fitted in
/// x, z and the global frame (`post::spr::own_map` returning `None`) gives
/// 7.6 and 3.9 and fails: a quadratic in x, z over three elements of a
/// ring misses the stress's turn with the wall by more than the element's
/// own error.
#[test]
fn the_shrink_fit_step_is_estimated() {
    let (a, b, c, delta): (f64, f64, f64, f64) = (0.02, 0.03, 0.045, 2e-5);
    let (young, nu): (f64, f64) = (200e9, 0.3);
    let bd = b + delta;
    let hub = b * ((c * c + b * b) / (c * c - b * b) + nu);
    let shaft = bd * ((bd * bd + a * a) / (bd * bd - a * a) - nu);
    let p = delta * young / (hub + shaft);
    assert!((p / 25.65e6 - 1.0).abs() < 1e-3, "the header's pressure: {p}");
    for k in [1, 2] {
        let ring = format!("around = {}, through = {}", 16 * k, 2 * k);
        let (model, s) = solve(&example("shrink_fit.toml").replace("around = 16, through = 2", &ring));
        let exact: Vec<_> = gauss_points(&model)
            .iter()
            .map(|g| {
                let at = [g.position[0], g.position[2]];
                if g.body == 0 { lame(at, (b, c), (p, 0.0)) } else { lame(at, (a, bd), (0.0, p)) }
            })
            .collect();
        let truth = error_against((&model, &s), &exact);
        let (_, eta, error, rel_eta, rel_error) = row("load", (&model, &s), &truth, &|_, _, _, _| true);
        let at = format!("step_error.shrink_fit.{}x{}L9_4B4.load", 16 * k, 2 * k);
        common::figure(&format!("{at}.estimate"), 100.0 * rel_eta, "%", "reported");
        common::figure(&format!("{at}.true"), 100.0 * rel_error, "%", "reported: against Lamé's stress");
        common::figure(&format!("{at}.effectivity"), eta / error, "", "in [0.5, 2] (issue 49)");
        assert!((0.5..=2.0).contains(&(eta / error)), "{at}: effectivity {}", eta / error);
    }
}
