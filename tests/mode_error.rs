//! Error estimates of each vibration mode (`post::mode_error`): the
//! recovered-stress estimate of each mode shape and the frequency error it
//! implies, `(f_h − f) / f ≈ ‖e‖² / (2 λ_h φᵀMφ)`, against the true error of
//! each frequency measured against a refined run of the same model (the
//! mode matched by its MAC on the coarse mesh's nodes).

use cufem::analysis::{Silent, Solution};
use cufem::setup::Model;
use cufem::values::{PointValues, locate_in_model};

mod common;

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    (model, solution)
}

/// The modal assurance criterion between every mode of `coarse` and every
/// mode of `fine`, both sampled at the coarse mesh's nodes: `mac[i][j]`.
fn mac(coarse: &(Model, Solution), fine: &(Model, Solution)) -> Vec<Vec<f64>> {
    let (cm, cs) = coarse;
    let (fm, fs) = fine;
    let (cmodes, fmodes) = (&cs.modal.as_ref().unwrap().modes, &fs.modal.as_ref().unwrap().modes);
    let points: Vec<PointValues> = (0..cm.mesh.n_nodes())
        .map(|n| {
            let loc = locate_in_model(&fm.mesh, Some(0), cm.mesh.coords(n));
            PointValues::new(&fm.mesh.bodies[0], &loc[0])
        })
        .collect();
    let sampled: Vec<Vec<f64>> =
        fmodes.iter().map(|m| points.iter().flat_map(|p| p.displacement(m)).collect()).collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    cmodes.iter().map(|a| sampled.iter().map(|b| dot(a, b).powi(2) / (dot(a, a) * dot(b, b))).collect()).collect()
}

/// Per coarse mode: the fine mode it matches (the largest MAC, if above
/// 0.9), the estimated and the true relative frequency error.
fn compare(coarse: &(Model, Solution), fine: &(Model, Solution)) -> Vec<(Option<usize>, f64, f64)> {
    let (cm, fm) = (coarse.1.modal.as_ref().unwrap(), fine.1.modal.as_ref().unwrap());
    mac(coarse, fine)
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let (j, best) = row.iter().enumerate().fold((0, 0.0), |b, (j, &v)| if v > b.1 { (j, v) } else { b });
            let truth = cm.frequencies[i] / fm.frequencies[j] - 1.0;
            ((best > 0.9).then_some(j), cm.errors[i].frequency(), truth)
        })
        .collect()
}

/// The laminated torsion box of the benchmark (`bench/box_laminated_modes.toml`,
/// [±45]s T300/5208 walls 1 mm, 100 × 50 mm) shortened to 0.4 m, with
/// `flange` × `web` L9 along its walls and `axis` B4, with the paper's
/// element (the benchmark's assumed shear removed: the estimates below are
/// those of the walls' locking modes, the case they were measured on).
fn short_box(flange: usize, web: usize, axis: usize) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/bench/box_laminated_modes.toml")).unwrap();
    let assumed = "formulation = \"assumed_shear\"\n";
    assert!(text.contains("along_flange = 3, along_web = 2") && text.contains("to = 1.0, elements = 8 }"));
    assert!(text.contains(assumed));
    text.replace(assumed, "")
        .replace("along_flange = 3, along_web = 2", &format!("along_flange = {flange}, along_web = {web}"))
        .replace("to = 1.0, elements = 8 }", &format!("to = 0.4, elements = {axis} }}"))
}

/// The laminated box, 3 × 2 L9 along its walls and 4 B4 (18,252 DOF),
/// against the same box with every wall division four times finer and
/// twice the beam elements (12 × 8 L9, 8 B4; 74,880 DOF). The reference is
/// itself converged enough: its first mode went 289.16 → 277.45 → 274.70 Hz
/// over 3 × 2 × 4, 6 × 4 × 8 and 12 × 8 × 8 (`cufem run` on the three
/// files), differences 11.71 and 2.75 Hz, so by Richardson (ratio 4.3) the
/// reference is about 2.75 / 3.3 = 0.8 Hz (0.3 %) above the limit, against
/// 14.5 Hz (5.3 %) for the coarse box.
///
/// Checked: the estimates rank the modes as their true errors do (the two
/// most and the two least converged modes are the same), the global bending
/// mode in x (mode 5, 59 % of the free mass in x; the rest of the eight
/// are wall and z-bending modes) has the smallest estimate, a third of any
/// wall mode's; the effectivity `estimated / true` of every mode matched to
/// the reference by its MAC (> 0.9: modes 1–4; the reference's modes 5–7
/// are mixtures of the x-bending and a wall mode 1 % apart) lies in
/// 0.57–0.95, within the issue's [0.5, 2] (with unweighted section patches,
/// each element counting by its number of points instead of its area in
/// `post::spr`, 1.0–2.2, mode 2 outside).
#[test]
fn the_laminated_box_ranks_its_wall_modes_and_estimates_their_frequency_errors() {
    let coarse = solve(&short_box(3, 2, 4));
    let fine = solve(&short_box(12, 8, 8));
    let m = coarse.1.modal.as_ref().unwrap();
    let rows = compare(&coarse, &fine);
    let (estimated, truth): (Vec<f64>, Vec<f64>) = rows.iter().map(|r| (r.1, r.2)).unzip();
    let order = |v: &[f64]| {
        let mut o: Vec<usize> = (0..v.len()).collect();
        o.sort_by(|&a, &b| v[b].total_cmp(&v[a]));
        o
    };
    let (by_estimate, by_truth) = (order(&estimated), order(&truth));
    let set = |o: &[usize]| {
        let mut s = o.to_vec();
        s.sort_unstable();
        s
    };
    assert_eq!(set(&by_estimate[..2]), set(&by_truth[..2]), "the two least converged modes");
    assert_eq!(set(&by_estimate[6..]), set(&by_truth[6..]), "the two best converged modes");
    // the global bending mode in x: the largest effective mass in x, the smallest estimate
    let bending = (0..8).max_by(|&a, &b| m.effective_masses[a][0].total_cmp(&m.effective_masses[b][0])).unwrap();
    assert!(m.effective_masses[bending][0] > 0.4 * m.free_mass[0], "{:?}", m.effective_masses);
    assert_eq!(by_estimate[7], bending);
    for (i, e) in estimated.iter().enumerate() {
        let wall = m.effective_masses[i].iter().zip(&m.free_mass).all(|(a, f)| *a < 0.05 * f);
        if wall {
            assert!(
                *e > 3.0 * estimated[bending],
                "mode {} {e} against the bending mode's {}",
                i + 1,
                estimated[bending]
            );
        }
    }
    let mut band = (f64::INFINITY, 0.0f64);
    for (i, (matched, est, t)) in rows.iter().enumerate() {
        let id = format!("mode_error.box.mode{}", i + 1);
        common::figure(&format!("{id}.estimate"), 100.0 * est, "%", "reported: estimated (f_h − f) / f");
        common::figure(&format!("{id}.true"), 100.0 * t, "%", "reported: against the 12 × 8 × 8 reference");
        if matched.is_some() {
            common::figure(&format!("{id}.effectivity"), est / t, "", "in the band below");
            band = (band.0.min(est / t), band.1.max(est / t));
        }
    }
    assert!(rows[..4].iter().all(|r| r.0.is_some()), "modes 1-4 match the reference");
    // issue 49: effectivity within 0.5–2
    assert!(band.0 >= 0.5 && band.1 <= 2.0, "effectivity {band:?}");
}

/// A steel cantilever 20 × 10 mm, 0.3 m long, `section` × `section` L9 and `axis` B4.
fn cantilever(section: usize, axis: usize) -> String {
    format!(
        r#"
        [analysis]
        type = "modal"
        modes = 4
        [[materials]]
        name = "steel"
        young_modulus = 200e9
        poisson_ratio = 0.3
        density = 7800.0
        [[bodies]]
        name = "b"
        material = "steel"
        section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = {section} }}, z = {{ from = 0.0, to = 0.01, elements = {section} }} }}
        axis = {{ element = "B4", from = 0.0, to = 0.3, elements = {axis} }}
        [[constraints]]
        name = "root"
        body = "b"
        where = {{ y = 0.0 }}
        fix = ["x", "y", "z"]
    "#
    )
}

/// A homogeneous cantilever's bending modes (the first two in z and in x)
/// on 2, 4 and 8 B4 against 32 B4 (2 × 2 L9 each): effectivity in [0.5, 2]
/// for every mode (measured 0.55–1.27), the estimate falling with the
/// error. The reference's own error, by Richardson through 8, 16 and 32 B4,
/// is checked below a fifth of the finest coarse mesh's error.
#[test]
fn the_cantilever_bending_modes_estimates_are_effective() {
    let fine = solve(&cantilever(2, 32));
    let half = solve(&cantilever(2, 16));
    let mut last = [f64::INFINITY; 4];
    for a in [2, 4, 8] {
        let coarse = solve(&cantilever(2, a));
        let rows = compare(&coarse, &fine);
        for (i, (matched, est, t)) in rows.iter().enumerate() {
            assert!(matched.is_some(), "mode {} of {a} B4 does not match the reference", i + 1);
            let id = format!("mode_error.cantilever.{a}B4.mode{}.effectivity", i + 1);
            common::figure(&id, est / t, "", "in [0.5, 2] against 32 B4");
            assert!((0.5..=2.0).contains(&(est / t)), "{id}: {est} / {t}");
            assert!(*est < last[i], "the estimate of mode {} grew under refinement", i + 1);
            // unloaded, λ_h φᵀMφ = φᵀKφ = ‖σ_h‖² (the Rayleigh quotient), so the
            // frequency error r/2 = ‖e‖² / 2‖σ_h‖² follows from the mode's
            // relative error η = ‖e‖ / √(‖e‖² + ‖σ_h‖²): r = η² / (1 − η²)
            let eta = coarse.1.modal.as_ref().unwrap().errors[i].estimate.relative();
            let r = eta * eta / (1.0 - eta * eta);
            assert!((est - 0.5 * r).abs() < 1e-6 * est, "mode {}: {est} against η {eta}", i + 1);
            last[i] = *est;
            if a == 8 {
                // Richardson through 8, 16, 32 B4: the reference's own error
                let f = |s: &(Model, Solution)| s.1.modal.as_ref().unwrap().frequencies[i];
                let (f8, f16, f32) = (f(&coarse), f(&half), f(&fine));
                let ratio = (f8 - f16) / (f16 - f32);
                let reference = (f16 - f32) / (ratio - 1.0) / f32;
                assert!(ratio > 1.5 && reference < 0.2 * t, "mode {}: ratio {ratio}, reference {reference}", i + 1);
            }
        }
    }
}

/// examples/cantilever_modes.toml (a thin-walled aluminium channel,
/// `4`, `8`, `1` L9 along each flange, along the web and through each wall,
/// `20` B4) with every division `k` times finer.
fn cantilever_modes(k: usize) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilever_modes.toml")).unwrap();
    let (section, axis) = (
        "along_flange = 4, along_web = 8, through = 1 }",
        "axis = { element = \"B4\", from = 0.0, to = 1.0, elements = 20 }",
    );
    assert!(text.contains(section) && text.contains(axis));
    text.replace(section, &format!("along_flange = {}, along_web = {}, through = {k} }}", 4 * k, 8 * k))
        .replace(axis, &format!("axis = {{ element = \"B4\", from = 0.0, to = 1.0, elements = {} }}", 20 * k))
}

/// The stored modes of examples/cantilever_modes.toml refined twice, re-made
/// by `the_shipped_channel_s_twice_refined_modes_are_remade`.
const CHANNEL_MODES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/cantilever_modes_refined_twice.csv");

/// Per shipped mode: the refined run's mode it matches, their MAC and its
/// frequency (Hz).
fn stored_channel_modes() -> Vec<(usize, f64, f64)> {
    let text = std::fs::read_to_string(CHANNEL_MODES).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("mode"))
        .map(|l| {
            let r: Vec<f64> = l.split(',').map(|v| v.trim().parse().unwrap()).collect();
            (r[1] as usize, r[2], r[3])
        })
        .collect()
}

/// The shipped channel's eight modes against its mesh refined twice (every
/// wall division and the axis four times finer, `943,515` DOF, stored:
/// the refined mode matched by its MAC on the shipped nodes, all above
/// `0.9999`): every mode's effectivity within issue 49's `0.5`–`2`
/// (measured `0.63`–`1.81`), and the three least converged modes (6–8,
/// the walls' own) the three largest estimates. The walls are `2` mm with
/// one L9 through and elements `6` thicknesses long; a section patch that
/// reached round the walls' re-entrant corners (`post::spr`) overstated
/// modes 1 and 4–8 up to `6.1` times. The reference's own error: along the
/// axis the frequencies converge at first order (the clamp; with the walls'
/// divisions doubled, 40 → 80 → 160 B4 change mode 1 by `4.2e-4`,
/// `1.9e-4`), across the section modes 6–8 at about `h^1.3` (`2.47` from
/// 1 → 2 → 4 times finer at 40 B4): by Richardson in each, the reference
/// lies up to a fifth of the shipped mesh's true error above the limit,
/// which would lower the effectivities by up to a sixth.
#[test]
fn the_shipped_channel_s_mode_estimates_against_its_twice_refined_modes() {
    let coarse = solve(&cantilever_modes(1));
    let m = coarse.1.modal.as_ref().unwrap();
    let stored = stored_channel_modes();
    assert_eq!(stored.len(), m.frequencies.len());
    let (estimated, truth): (Vec<f64>, Vec<f64>) =
        m.errors.iter().zip(&m.frequencies).zip(&stored).map(|((e, f), s)| (e.frequency(), f / s.2 - 1.0)).unzip();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (i, ((est, t), s)) in estimated.iter().zip(&truth).zip(&stored).enumerate() {
        assert!(s.1 > 0.9999, "mode {}: MAC {} with the refined mode {}", i + 1, s.1, s.0);
        assert!(*t > 5e-4, "mode {}: true error {t}", i + 1);
        let eff = est / t;
        eprintln!("cantilever_modes mode {}: true {t:.3e}, estimated {est:.3e}, effectivity {eff:.2}", i + 1);
        common::figure(&format!("mode_error.channel.mode{}.effectivity", i + 1), eff, "", "in [0.5, 2] (issue 49)");
        assert!((0.5..=2.0).contains(&eff), "mode {}: effectivity {eff}", i + 1);
        (lo, hi) = (lo.min(eff), hi.max(eff));
    }
    common::figure("mode_error.channel.effectivity_min", lo, "", "in [0.5, 2] (issue 49)");
    common::figure("mode_error.channel.effectivity_max", hi, "", "in [0.5, 2] (issue 49)");
    let top = |v: &[f64]| {
        let mut o: Vec<usize> = (0..v.len()).collect();
        o.sort_by(|&a, &b| v[b].total_cmp(&v[a]));
        let mut s = o[..3].to_vec();
        s.sort_unstable();
        s
    };
    assert_eq!(top(&estimated), top(&truth), "the three least converged modes");
}

/// Re-makes the stored modes of `the_shipped_channel_s_mode_estimates_against_its_twice_refined_modes`.
#[test]
#[ignore = "validate: references — examples/cantilever_modes.toml refined twice (943,515 DOF, about 4 min, 15 GiB)"]
fn the_shipped_channel_s_twice_refined_modes_are_remade() {
    let (coarse, fine) = (solve(&cantilever_modes(1)), solve(&cantilever_modes(4)));
    let frequencies = &fine.1.modal.as_ref().unwrap().frequencies;
    let mut out = format!(
        "# examples/cantilever_modes.toml with every division four times finer ({} DOF): for each\n\
         # shipped mode, the refined mode of largest MAC (sampled at the shipped nodes), the MAC and\n\
         # the refined mode's frequency (Hz).\n\
         # Remade by cargo test --release --test suite -- --ignored --exact \
         mode_error::the_shipped_channel_s_twice_refined_modes_are_remade\n\
         mode,refined_mode,mac,refined_frequency_hz\n",
        fine.0.n_dofs()
    );
    for (i, row) in mac(&coarse, &fine).iter().enumerate() {
        let (j, best) = row.iter().enumerate().fold((0, 0.0), |b, (j, &v)| if v > b.1 { (j, v) } else { b });
        out += &format!("{},{},{best:.6},{:.9e}\n", i + 1, j + 1, frequencies[j]);
    }
    std::fs::write(CHANNEL_MODES, out).unwrap();
}
