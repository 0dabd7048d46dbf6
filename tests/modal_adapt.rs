//! `--adapt` on a modal analysis (`cufem::adapt`, `adapt::measure`): the
//! cycles are measured by the largest estimated relative frequency error of
//! the modes followed and refined where those modes hold their estimates;
//! and the effectivity of the modes' estimates with the assumed in-section
//! shear (`formulation = "assumed_shear"`), against refined runs of the
//! same model.

use cufem::adapt::Source;
use cufem::analysis::{Silent, Solution};
use cufem::setup::{AdaptSettings, Model};
use cufem::values::{PointValues, locate_in_model};

mod common;

/// A thin steel box 100 × 50 mm, walls 1 mm (one L9 through), 0.4 m long,
/// clamped at y = 0, eight modes, the assumed in-section shear: the lowest
/// mode bends it in z, the next ones are the walls' own (local) modes.
fn steel_box(flange: usize, web: usize, axis: usize) -> String {
    format!(
        r#"
        [analysis]
        type = "modal"
        modes = 8
        [[materials]]
        name = "steel"
        young_modulus = 200e9
        poisson_ratio = 0.3
        density = 7800.0
        [[bodies]]
        name = "box"
        material = "steel"
        formulation = "assumed_shear"
        section = {{ shape = "box", element = "L9", width = 0.1, height = 0.05, web_thickness = 0.001, flange_thickness = 0.001, along_flange = {flange}, along_web = {web} }}
        axis = {{ element = "B4", from = 0.0, to = 0.4, elements = {axis} }}
        [[constraints]]
        name = "root"
        body = "box"
        where = {{ y = 0.0 }}
        fix = ["x", "y", "z"]
    "#
    )
}

fn solve(model: &Model) -> Solution {
    cufem::analysis::run(model, &Default::default(), &mut Silent).unwrap()
}

/// Per mode of `coarse`: the mode of `fine` it matches (the largest MAC on
/// the coarse mesh's nodes, if above 0.9) and the true relative frequency
/// error `f_coarse / f_fine − 1`.
fn truth(coarse: (&Model, &Solution), fine: (&Model, &Solution)) -> Vec<(Option<usize>, f64)> {
    let (cm, fm) = (coarse.1.modal.as_ref().unwrap(), fine.1.modal.as_ref().unwrap());
    let points: Vec<PointValues> = (0..coarse.0.mesh.n_nodes())
        .map(|n| {
            let loc = locate_in_model(&fine.0.mesh, Some(0), coarse.0.mesh.coords(n));
            PointValues::new(&fine.0.mesh.bodies[0], &loc[0])
        })
        .collect();
    let sampled: Vec<Vec<f64>> =
        fm.modes.iter().map(|m| points.iter().flat_map(|p| p.displacement(m)).collect()).collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    cm.modes
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let macs = sampled.iter().map(|b| dot(a, b).powi(2) / (dot(a, a) * dot(b, b)));
            let (j, best) = macs.enumerate().fold((0, 0.0), |b, (j, v)| if v > b.1 { (j, v) } else { b });
            ((best > 0.9).then_some(j), cm.frequencies[i] / fm.frequencies[j] - 1.0)
        })
        .collect()
}

/// The estimates of the assumed shear's modes against the true errors of
/// the thin box (3 × 2 L9 along the walls, 4 B4; 3,276 DOF) measured
/// against the same box with 24 × 16 L9 and 8 B4 (37,800 DOF; its lowest
/// frequency went 303.3 → 302.6 → 301.7 → 301.5 Hz over 3 × 2 × 4,
/// 6 × 4 × 4, 12 × 8 × 8 and 24 × 16 × 8, so it is within about 0.1 % of
/// the limit against the coarse box's 0.6 %).
///
/// Measured: every mode matches the reference (MAC > 0.9) and the estimate
/// is above the true error (effectivity `1.04`–`2.33`), within issue 49's
/// `0.5`–`2` but for mode 8 (`2.33`, held from both sides as a known limit,
/// docs/limitations.md). Before the section patches stopped reaching round
/// the walls' re-entrant corners (`post::spr`) the estimates were `10`–`27`
/// times the true errors.
#[test]
fn the_assumed_shears_mode_estimates_are_pessimistic_upper_bounds() {
    let coarse = Model::parse(&steel_box(3, 2, 4)).unwrap();
    let fine = Model::parse(&steel_box(24, 16, 8)).unwrap();
    let (cs, fs) = (solve(&coarse), solve(&fine));
    let rows = truth((&coarse, &cs), (&fine, &fs));
    let estimates: Vec<f64> = cs.modal.as_ref().unwrap().errors.iter().map(|e| e.frequency()).collect();
    let mut band = (f64::INFINITY, 0.0f64);
    for (i, ((matched, t), est)) in rows.iter().zip(&estimates).enumerate() {
        assert!(matched.is_some(), "mode {} does not match the reference", i + 1);
        assert!(*t > 0.0, "mode {}: the coarse frequency is an upper bound ({t})", i + 1);
        let id = format!("modal_adapt.assumed_shear.mode{}", i + 1);
        common::figure(&format!("{id}.estimate"), 100.0 * est, "%", "reported: estimated (f_h − f) / f");
        common::figure(&format!("{id}.true"), 100.0 * t, "%", "reported: against 24 × 16 L9 × 8 B4");
        band = (band.0.min(est / t), band.1.max(est / t));
    }
    // an upper bound of every mode's error, within the band but for mode 8
    common::figure("modal_adapt.assumed_shear.effectivity_min", band.0, "", "in [1, 2]");
    assert!((1.0..=2.0).contains(&band.0), "{band:?}");
    let what = "the largest effectivity of the assumed shear's mode estimates on the thin box";
    common::known_limit("modal_adapt.assumed_shear.effectivity_max", band.1, "", 2.1, 2.6, what);
}

/// The thin box with webs three times thicker (3 mm): its flanges carry
/// the local modes.
fn stiff_webs(flange: usize, web: usize, axis: usize) -> String {
    let text = steel_box(flange, web, axis);
    assert!(text.contains("web_thickness = 0.001"));
    text.replace("web_thickness = 0.001", "web_thickness = 0.003")
}

/// `--adapt` on the modes of the thin box with stiff webs (3 × 2 L9 along
/// its walls, 4 B4): one cycle, following the lowest five modes (bending,
/// and the flanges' own modes above it). Their estimates hold most of
/// theirs in the wall elements next to the junctions (the walls'
/// transverse-shear boundary layer, `python3 bench/junction_layer_study.py`),
/// so the cycle grades the walls towards the junctions — one more element
/// of the junction's smallest side, 1 mm, at each wall end — instead of
/// doubling a count. Checked: the cycle's estimate is the largest of the
/// five modes' estimated frequency errors; the refinement and the model
/// file written; every one of the five modes' true errors against a
/// graded reference falls; the graded mesh has fewer DOF than the section
/// doubled as a whole; and the estimates, 1.49–2.11× the true errors on
/// the uniform walls, come within 1.25–1.66× of them on the graded ones
/// (the issue's 0.5–2).
///
/// The reference: 24 × 16 L9 with 0.25 mm elements at the junctions,
/// 8 B4 (41,400 DOF). Its modes 3–5 lie 0.06 % above the same box with
/// 48 × 32 L9 and 0.1 mm (77,400 DOF), against the graded cycle's
/// 1.2–1.3 %; the ungraded 24 × 16 L9 lies 0.4 % above it
/// (`cufem run` of the three, out/jl in the session that measured them).
#[test]
fn adapt_on_modes_grades_the_walls_towards_their_junctions() {
    let text = stiff_webs(3, 2, 4) + "[adapt]\nmodes = 5\n";
    let start = Model::parse(&text).unwrap();
    let settings = start.adapt.unwrap();
    assert_eq!(settings.modes, Some(5));
    let settings = AdaptSettings { tolerance: 0.001, max_cycles: 1, ..settings };
    let source = Source { text: &text, base: std::path::Path::new("."), limits: cufem::setup::Limits::none() };
    let mut cycles: Vec<(Model, Solution, f64, Vec<f64>)> = Vec::new();
    let (_, last) = cufem::adapt::run(start, source, &settings, &Default::default(), &mut Silent, &mut |c, m, s| {
        cycles.push((m.clone(), s.clone(), c.estimate, c.modes.as_ref().map(|m| m.errors.clone()).unwrap_or_default()))
    })
    .unwrap();
    assert_eq!(cycles.len(), 2);
    let adapt = last.adapt.as_ref().unwrap();
    assert!(adapt.stop.contains("max_cycles = 1"), "{}", adapt.stop);
    assert_eq!(adapt.cycles[1].refined, "box: walls graded to a 0.001 m element at each junction");
    // the model file written: the counts as given, the junction element set
    assert!(adapt.model_file.contains("along_flange = 3, along_web = 2"), "{}", adapt.model_file);
    assert!(adapt.model_file.contains("junction_element = 0.001"), "{}", adapt.model_file);
    for (model, solution, estimate, errors) in &cycles {
        let modal = solution.modal.as_ref().unwrap();
        assert_eq!(errors.len(), 5);
        let largest = modal.errors[..5].iter().map(|e| e.frequency()).fold(0.0, f64::max);
        assert_eq!(*estimate, largest);
        assert!(model.n_dofs() > 0);
    }
    let fine = Model::parse(
        &stiff_webs(24, 16, 8).replace("along_web = 16 }", "along_web = 16, junction_element = 0.00025 }"),
    )
    .unwrap();
    assert_eq!(fine.n_dofs(), 41_400);
    let fs = solve(&fine);
    let before = truth((&cycles[0].0, &cycles[0].1), (&fine, &fs));
    let after = truth((&cycles[1].0, &cycles[1].1), (&fine, &fs));
    let mut effectivity = (f64::INFINITY, 0.0f64);
    for i in 0..5 {
        let (b, a) = (before[i].1, after[i].1);
        common::figure(&format!("modal_adapt.steel_box.mode{}.true_before", i + 1), 100.0 * b, "%", "reported");
        common::figure(&format!("modal_adapt.steel_box.mode{}.true_after", i + 1), 100.0 * a, "%", "below before");
        assert!(before[i].0.is_some() && after[i].0.is_some(), "mode {} matched", i + 1);
        assert!(a < b, "mode {}: the true error {b} → {a}", i + 1);
        let eff = cycles[1].3[i] / a;
        effectivity = (effectivity.0.min(eff), effectivity.1.max(eff));
        common::figure(
            &format!("modal_adapt.steel_box.mode{}.effectivity_before", i + 1),
            cycles[0].3[i] / b,
            "",
            "reported",
        );
    }
    // issue 49: effectivity within 0.5–2 of the true frequency error
    common::figure("modal_adapt.steel_box.graded_effectivity_min", effectivity.0, "", "at least 0.5");
    common::figure("modal_adapt.steel_box.graded_effectivity_max", effectivity.1, "", "at most 2");
    assert!(effectivity.0 >= 0.5 && effectivity.1 <= 2.0, "{effectivity:?}");
    let doubled = Model::parse(&stiff_webs(6, 4, 4)).unwrap();
    common::figure("modal_adapt.steel_box.dof", cycles[1].0.n_dofs() as f64, "", "below the whole section doubled");
    assert!(cycles[1].0.n_dofs() < doubled.n_dofs(), "{} {}", cycles[1].0.n_dofs(), doubled.n_dofs());
}

/// The laminated torsion box of the benchmark (`bench/box_laminated_modes.toml`,
/// its assumed-shear base mesh, 35,100 DOF) adapted on its eight modes to
/// the frequency tolerance 2 %, against the CalculiX frequencies of
/// docs/validation.md (`verify.box_modes.mode.<k>.ccx_hz`, C3D20R two
/// through each ply; `bench/validate --steps verify-newer --models
/// box_modes`), and against uniform section doubling (every wall count
/// doubled once: 6 × 4 L9, and twice: 12 × 8 L9; the axis as given).
///
/// Measured: the base mesh's eight modes are estimated at `0.50`–`2.11 %`
/// (`0.71`–`1.73` times their true errors against 24 × 16 L9 × 16 B4 with
/// 0.25 mm junction elements; `python3 bench/box_mode_estimates.py`), so
/// one cycle suffices: it doubles the flanges and adds an axis element
/// (48,384 DOF, every frequency within 1.41 % of CalculiX) and the
/// estimate falls below 2 %. Uniform doubling once (48,600 DOF) leaves
/// mode 6 at `2.15 %`; twice (75,600 DOF) brings every mode within
/// `1.86 %`. The issue's check: the adaptive run stops within 2 % of
/// CalculiX at fewer DOF than the uniform doubling that gets there. With
/// unweighted section patches (each element counting by its number of
/// points instead of its area, `post::spr`) the estimates of the wall
/// modes were 3–10 times their true errors and the run stopped late, at
/// 118,800 DOF.
#[test]
#[ignore = "validate: slow — the laminated box adapted on its modes and doubled twice (about 5 min)"]
fn the_laminated_box_adapted_on_its_modes_against_calculix_and_uniform_doubling() {
    // docs/validation.md, verify.box_modes.mode.<k>.ccx_hz
    let ccx = [48.68194, 82.09348, 254.1779, 273.785, 331.0014, 380.2711, 395.7732, 408.1163];
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/bench/box_laminated_modes.toml")).unwrap();
    assert!(text.contains("along_flange = 3, along_web = 2") && text.contains("formulation = \"assumed_shear\""));
    let worst = |s: &Solution| {
        let f = &s.modal.as_ref().unwrap().frequencies;
        f.iter().zip(ccx).map(|(a, b)| (a / b - 1.0).abs()).fold(0.0, f64::max)
    };
    let start = Model::parse(&text).unwrap();
    let settings = AdaptSettings { tolerance: 0.02, max_dof: 120_000, max_cycles: 5, ..Default::default() };
    let source = Source { text: &text, base: std::path::Path::new("."), limits: cufem::setup::Limits::none() };
    let mut cycles = Vec::new();
    let (model, solution) =
        cufem::adapt::run(start, source, &settings, &Default::default(), &mut Silent, &mut |c, _, s| {
            cycles.push((c.dof, c.estimate, worst(s), c.refined.clone()))
        })
        .unwrap();
    for (k, (dof, estimate, diff, refined)) in cycles.iter().enumerate() {
        eprintln!(
            "cycle {k}: {dof} DOF, estimate {:.2} %, largest |f − f_ccx| {:.2} % ({refined})",
            100.0 * estimate,
            100.0 * diff
        );
        common::figure(&format!("modal_adapt.box.cycle{k}.dof"), *dof as f64, "", "reported");
        common::figure(&format!("modal_adapt.box.cycle{k}.estimate"), 100.0 * estimate, "%", "reported");
        common::figure(&format!("modal_adapt.box.cycle{k}.ccx_max"), 100.0 * diff, "%", "reported");
    }
    let adapted = worst(&solution);
    common::figure("modal_adapt.box.adapted.ccx_max", 100.0 * adapted, "%", "within 2 % of CalculiX");
    assert!(adapted <= 0.02, "the adapted box: {adapted}");
    assert!(solution.adapt.as_ref().unwrap().stop.contains("below the tolerance"));
    let mut uniform = Vec::new();
    for (flange, web) in [(6, 4), (12, 8)] {
        let m = Model::parse(
            &text.replace("along_flange = 3, along_web = 2", &format!("along_flange = {flange}, along_web = {web}")),
        )
        .unwrap();
        let s = solve(&m);
        let id = format!("modal_adapt.box.uniform_{flange}x{web}");
        common::figure(&format!("{id}.dof"), m.n_dofs() as f64, "", "reported");
        common::figure(&format!("{id}.ccx_max"), 100.0 * worst(&s), "%", "reported");
        uniform.push((m.n_dofs(), worst(&s)));
    }
    // doubled once: not within 2 %; doubled twice: within
    assert!(uniform[0].1 > 0.02 && uniform[1].1 <= 0.02, "{uniform:?}");
    let ratio = model.n_dofs() as f64 / uniform[1].0 as f64;
    common::figure("modal_adapt.box.dof_over_uniform", ratio, "", "below 1 (issue 49)");
    assert!(ratio < 1.0, "adapted {} DOF against {}", model.n_dofs(), uniform[1].0);
}
