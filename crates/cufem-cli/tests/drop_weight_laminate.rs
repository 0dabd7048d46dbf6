//! A drop weight on a laminate that delaminates (issue 48):
//! examples/laminate_drop_weight.toml through the CLI. A rigid cylinder of
//! 0.1 kg at 4 m/s (0.8 J) strikes a simply supported [0/90]s carbon/epoxy
//! beam (50 mm span, 4 × 0.5 mm, 10 mm wide) with cohesive interfaces
//! between all its plies; the mid-plane interface fails in shear over most
//! of the span, the force drops, and the striker rebounds with what the
//! beam gives back.
//!
//! References: the impact energy `½ m v²` (the ledger's balance and the
//! dissipated energy are fractions of it); the onset load of laminated beam
//! theory, where the mid-plane shear `V Q/(D b)` of the three-point bend
//! reaches the interface's shear strength S: `P = 2 b S D/Q` = 501.6 N
//! (per unit width D = Σ E_k ∫z² dz = 91.76 N m over the thickness and
//! Q = Σ E_k ∫z dz = 59,636 N over its upper half; E1 = 156, E2 = 9.09
//! GPa, S = 16.3 MPa); and the refined runs of the convergence study
//! (`python3 bench/drop/study.py`, table in bench/drop/results.txt).

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

/// Impact energy ½ m v² of the example's striker (J).
const IMPACT_ENERGY: f64 = 0.5 * 0.1 * 4.0 * 4.0;

/// The window of the averaged contact force (s): what a load cell of about
/// 10 kHz shows (the raw contact force rings at the beam's modes under the
/// rigid striker and is not a converged quantity; bench/drop/results.txt).
const WINDOW: f64 = 1.0e-4;

/// The study's refined runs (bench/drop/results.txt): the averaged peak
/// force (N) and the energy dissipated (J) of the example's beam with the
/// axis refined again (120 B2, same step: `imp_a120_p1_n2400`) and with the
/// step halved (60 B2, 4,800 steps: `imp_a60_p1_n4800`).
const REFINED_AXIS: (f64, f64) = (519.605, 0.500357);
const REFINED_STEP: (f64, f64) = (517.582, 0.507341);

/// The time between the frames the test asks for (s): ten steps.
const FRAMES: f64 = 2.5e-5;

/// The example as shipped, with frames every `FRAMES` (output only: the
/// solution is the example's).
fn run_example() -> (PathBuf, Value) {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/laminate_drop_weight.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let framed = text.replacen(
        "interface_forces = \"implicit\"\n",
        &format!("interface_forces = \"implicit\"\noutput_interval = {FRAMES:e}\n"),
        1,
    );
    assert_ne!(framed, text, "the example's [analysis] changed: ask for its frames another way");
    common::run_text("drop_weight_laminate", "example", &framed)
}

/// One frame's failure picture: where (y, z in m) a Hashin index of the
/// plies is at least 1, and per point of the interfaces (y, z, d).
struct Onset {
    time: f64,
    ply: Vec<(f64, f64)>,
    interface: Vec<(f64, f64, f64)>,
}

/// The frames of a run until `until` (s), from `frames.pvd`.
fn onsets(out: &Path, until: f64) -> Vec<Onset> {
    let pvd = std::fs::read_to_string(out.join("frames.pvd")).unwrap();
    let mut frames = Vec::new();
    for line in pvd.lines().filter(|l| l.contains("<DataSet")) {
        let attr =
            |name: &str| line.split(&format!("{name}=\"")).nth(1).unwrap().split('"').next().unwrap().to_string();
        let time: f64 = attr("timestep").parse().unwrap();
        if time > until {
            break;
        }
        let file = out.join(attr("file"));
        let points = common::vtu_array(&file, None);
        let fibre = common::vtu_array(&file, Some("fi_hashin_fibre"));
        let matrix = common::vtu_array(&file, Some("fi_hashin_matrix"));
        let damage = common::vtu_array(&file, Some("d_interface"));
        let at = |i: usize| (points[3 * i + 1], points[3 * i + 2]);
        let ply = (0..fibre.len()).filter(|&i| fibre[i].max(matrix[i]) >= 1.0).map(at).collect();
        // the interface planes z = 0.5, 1, 1.5 mm (d_interface is 0 elsewhere)
        let on_interface = |z: f64| (1..4).any(|k| (z - 5e-4 * k as f64).abs() < 1e-9);
        let interface =
            (0..damage.len()).filter(|&i| on_interface(at(i).1)).map(|i| (at(i).0, at(i).1, damage[i])).collect();
        frames.push(Onset { time, ply, interface });
    }
    frames
}

/// The contact force averaged over `WINDOW`: the striker's impulse over the
/// window divided by it (`f_n` at a step's end is that step's impulse / Δt).
fn averaged_force(time: &[f64], force: &[f64]) -> Vec<(f64, f64)> {
    let mut impulse = vec![0.0];
    for k in 0..force.len() {
        impulse.push(impulse[k] + force[k] * (time[k + 1] - time[k]));
    }
    let mut out = Vec::new();
    let mut j = 0;
    for i in 0..time.len() {
        while time[i] - time[j] > WINDOW * (1.0 + 1e-9) {
            j += 1;
        }
        if time[i] - time[j] >= WINDOW * (1.0 - 1e-9) {
            out.push((time[i], (impulse[i] - impulse[j]) / (time[i] - time[j])));
        }
    }
    out
}

/// The energy ledger of a drop-weight run in `out` (`energy.csv`), checked
/// as every such run must hold it: the striker starts with the impact
/// energy; the balance stays within 1 % of it at every step (figure
/// `<id>.balance`); no step creates energy (nothing does work on the beam
/// and striker but the fixed supports, so their mechanical energy —
/// kinetic, elastic, the striker's, what the interfaces hold — never
/// grows); and no dissipation column of `booked` ever falls (damage is
/// never undone). Returns the columns and the mechanical energy per step.
fn checked_ledger(out: &Path, id: &str, booked: &[&str]) -> (std::collections::HashMap<String, Vec<f64>>, Vec<f64>) {
    let c = common::csv_columns(&out.join("energy.csv"));
    let col = |name: &str| c.get(name).unwrap_or_else(|| panic!("energy.csv has no {name}"));
    let (time, kinetic, elastic, striker) = (col("time_s"), col("kinetic_J"), col("elastic_J"), col("impactors_J"));
    let (interfaces, delamination, balance) = (col("interfaces_J"), col("delamination_J"), col("balance_J"));
    assert!((striker[0] / IMPACT_ENERGY - 1.0).abs() < 1e-12, "impact energy {} J", striker[0]);
    let n = time.len();
    let worst = balance.iter().fold(0.0_f64, |m, b| m.max(b.abs()));
    let check = "≤ 0.01 of the impact energy at every step";
    common::figure(&format!("{id}.balance"), worst / IMPACT_ENERGY, "", check);
    assert!(worst <= 0.01 * IMPACT_ENERGY, "balance {worst} J");
    let mechanical: Vec<f64> =
        (0..n).map(|k| kinetic[k] + elastic[k] + striker[k] + interfaces[k] - delamination[k]).collect();
    let booked: Vec<&Vec<f64>> = booked.iter().map(|b| col(b)).collect();
    for k in 1..n {
        let grown = mechanical[k] - mechanical[k - 1];
        assert!(grown <= 1e-9 * IMPACT_ENERGY, "the mechanical energy grew by {grown} J at t = {} s", time[k]);
        for b in &booked {
            let fell = b[k] - b[k - 1];
            assert!(fell >= -1e-12 * IMPACT_ENERGY, "a dissipation fell by {fell} J at t = {} s", time[k]);
        }
    }
    (c, mechanical)
}

/// The ledger closes within 1 % of the impact energy at every step
/// (measured below 1e-6 of it: the trapezoidal rule with the interfaces'
/// and the contact's end-of-step impulse), no step creates energy (nothing
/// does work on the beam and striker but the fixed supports, so their
/// mechanical energy — kinetic, elastic, the striker's, what the interfaces
/// hold — never grows; and the ledger's delamination never falls), the
/// beam delaminates (d = 1 over an area), and its averaged force drops
/// after the peak.
#[test]
#[ignore = "validate: slow — examples/laminate_drop_weight.toml, 2,400 time steps (about 40 s)"]
fn a_drop_weight_delaminates_a_laminate_and_the_ledger_closes() {
    let (out, summary) = run_example();
    let (c, mechanical) = checked_ledger(&out, "drop_weight_laminate", &["delamination_J"]);
    let (time, n) = (&c["time_s"], mechanical.len());
    // delaminated: the mid-plane interface (interface2) over most of the span
    let area = summary["delamination"]["area_m2"].as_f64().unwrap();
    common::figure("drop_weight_laminate.delaminated_area", area, "m²", "> 0");
    assert!(area > 0.5 * 0.05 * 0.01, "delaminated area {area} m²");
    let per_interface: Vec<f64> = summary["delamination"]["interfaces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["delaminated_m2"].as_f64().unwrap())
        .collect();
    assert!(per_interface[1] == area, "only the mid-plane separates: {per_interface:?}");
    // a transient run's end may lie after the rebound: no first-failure
    // load factor from it (one was printed; a new-user review)
    assert!(summary["ply_failure"]["first_ply_failure_load_factor"].is_null());
    // the load drop: after its peak the averaged force falls below half of it
    let h = common::csv_columns(&out.join("history_striker.csv"));
    let avg = averaged_force(time, &h["f_n"]);
    let (ip, &(t_peak, peak)) = avg.iter().enumerate().max_by(|a, b| a.1.1.total_cmp(&b.1.1)).unwrap();
    let lowest_after = avg[ip..].iter().take_while(|(t, _)| *t < t_peak + 0.5e-3).fold(f64::MAX, |m, a| m.min(a.1));
    common::figure("drop_weight_laminate.drop", lowest_after / peak, "", "< 0.5: the load drop at delamination");
    assert!(lowest_after < 0.5 * peak, "peak {peak} N at {t_peak} s, then {lowest_after} N");
    // the onset against laminated beam theory (the averaged peak lies above
    // it by the striker's inertia share; static run: 512 N)
    common::within("drop_weight_laminate.onset", peak, 501.6, 0.10, "laminated beam theory's onset 2 b S D/Q");
    // converged: against the study's refined runs. The energy the beam
    // absorbed less what it still holds at the end (vibration, and on the
    // finer meshes the striker still touching it at 6 ms): the energy
    // dissipated, by delamination and by the contact, final once the
    // interface stops failing (about 1.5 ms)
    let dissipated = IMPACT_ENERGY - mechanical[n - 1];
    common::within(
        "drop_weight_laminate.peak_axis",
        peak,
        REFINED_AXIS.0,
        0.03,
        "the axis refined, bench/drop/results.txt",
    );
    common::within(
        "drop_weight_laminate.dissipated_axis",
        dissipated,
        REFINED_AXIS.1,
        0.03,
        "the axis refined, bench/drop/results.txt",
    );
    common::within(
        "drop_weight_laminate.peak_step",
        peak,
        REFINED_STEP.0,
        0.03,
        "the step halved, bench/drop/results.txt",
    );
    common::within(
        "drop_weight_laminate.dissipated_step",
        dissipated,
        REFINED_STEP.1,
        0.03,
        "the step halved, bench/drop/results.txt",
    );
    where_failure_starts(&out, &avg, (t_peak, peak));
}

/// Where and when failure starts, from the frames (every `FRAMES`), against
/// the delamination and the load drop. The interfaces' law damages a point
/// only once its quadratic onset criterion `(⟨t3⟩/N)² + (t_s/S)² ≥ 1` is
/// met (`materials::cohesive`), so `d_interface > 0` is where that index
/// reached 1. Measured (docs/composites.md, "Where failure starts"):
/// * at the line supports (y = 0, 50 mm) both indices pass 1 in the first
///   frame — the stress wave meeting the supports' lines, a singular
///   support, two points of each lower interface, which stay there;
/// * away from the supports the interfaces' onset spreads over the span from
///   0.25 ms, on all three interfaces; the mid-plane reaches d = 1 over most
///   of the span between the frames at 0.500 and 0.525 ms, the averaged
///   force peaks at 0.500 ms and falls after: delamination and the load
///   drop appear together, where the interface's index passed 1;
/// * the plies' Hashin matrix index first passes 1 (away from the
///   supports) at 0.375 ms under the striker, at the lower 0/90 ply face
///   (z = 0.5 mm: the 90° ply's transverse tension) — not on the mid-plane
///   that delaminates. A finding, asserted from both sides
///   (docs/limitations.md): the ply indices say where the plies crack,
///   not which interface separates.
fn where_failure_starts(out: &Path, avg: &[(f64, f64)], (t_peak, peak): (f64, f64)) {
    const SPAN: f64 = 0.05;
    const MID_PLANE: f64 = 1e-3;
    let frames = onsets(out, 1.0e-3);
    let interior = |y: f64| y > 0.05 * SPAN && y < 0.95 * SPAN;
    // the first frame: the supports only
    let first = &frames[0];
    let inside = |ps: &[(f64, f64)]| ps.iter().filter(|p| interior(p.0)).count();
    assert!(
        inside(&first.ply) == 0 && !first.ply.is_empty(),
        "first frame: ply index ≥ 1 at {} points",
        first.ply.len()
    );
    let started: Vec<(f64, f64)> = first.interface.iter().filter(|p| p.2 > 0.0).map(|p| (p.0, p.1)).collect();
    assert!(inside(&started) == 0 && !started.is_empty(), "first frame: onset at {} points", started.len());
    // delamination: the first frame with d = 1, on the mid-plane only
    let k_delam = frames.iter().position(|f| f.interface.iter().any(|p| p.2 >= 1.0)).expect("no frame with d = 1");
    let t_delam = frames[k_delam].time;
    let separated: Vec<&(f64, f64, f64)> = frames[k_delam].interface.iter().filter(|p| p.2 >= 1.0).collect();
    assert!(separated.iter().all(|p| (p.1 - MID_PLANE).abs() < 1e-9), "separated off the mid-plane");
    common::figure("drop_weight_laminate.delamination_time", t_delam, "s", "first frame with d = 1 (every 25 µs)");
    // its onset came first, where it separates: every separated point had
    // d > 0 in an earlier frame, and the mid-plane's onset spread over
    // most of its span (interior) before
    let had_onset = |k: usize, y: f64, z: f64| {
        frames[k].interface.iter().any(|p| (p.0 - y).abs() < 1e-9 && (p.1 - z).abs() < 1e-9 && p.2 > 0.0)
    };
    assert!(k_delam >= 2 && separated.iter().all(|p| had_onset(k_delam - 1, p.0, p.1)), "onset before d = 1");
    let k_onset = frames
        .iter()
        .position(|f| {
            let mid: Vec<_> = f.interface.iter().filter(|p| (p.1 - MID_PLANE).abs() < 1e-9 && interior(p.0)).collect();
            2 * mid.iter().filter(|p| p.2 > 0.0).count() > mid.len()
        })
        .unwrap();
    common::figure("drop_weight_laminate.onset_time", frames[k_onset].time, "s", "mid-plane onset over half its span");
    assert!(k_onset < k_delam, "onset at {} s, d = 1 at {t_delam} s", frames[k_onset].time);
    // the load drop with it: the averaged force peaks no later than the
    // first frame with d = 1 and falls below 90 % of its peak after the
    // last frame without it, within two frames of the separation
    let t_drop = avg.iter().find(|&&(t, f)| t > t_peak && f < 0.9 * peak).unwrap().0;
    common::figure("drop_weight_laminate.drop_time", t_drop, "s", "averaged force below 90 % of its peak");
    assert!(
        t_peak <= t_delam && t_drop > frames[k_delam - 1].time,
        "peak {t_peak} s, drop {t_drop} s, d = 1 {t_delam} s"
    );
    assert!(t_drop <= t_delam + 2.0 * FRAMES, "drop {t_drop} s long after d = 1 at {t_delam} s");
    // the plies: their first index ≥ 1 away from the supports, before the
    // separation, within the delaminated span, but not on the mid-plane
    let k_ply = frames.iter().position(|f| f.ply.iter().any(|p| interior(p.0))).expect("no ply index ≥ 1");
    let ply: Vec<(f64, f64)> = frames[k_ply].ply.iter().copied().filter(|p| interior(p.0)).collect();
    common::known_limit(
        "drop_weight_laminate.ply_onset_time",
        frames[k_ply].time,
        "s",
        3.5e-4,
        4.0e-4,
        "the plies' first Hashin index ≥ 1 (frames every 25 µs)",
    );
    assert!(frames[k_ply].time < t_delam);
    let (low, high) = separated.iter().fold((SPAN, 0.0_f64), |(l, h), p| (l.min(p.0), h.max(p.0)));
    assert!(ply.iter().all(|&(y, _)| (low..=high).contains(&y)), "ply onset outside the separated {low}..{high} m");
    let depth = ply.iter().fold(f64::NAN, |_, p| p.1);
    common::known_limit(
        "drop_weight_laminate.ply_onset_z",
        depth,
        "m",
        4.9e-4,
        5.1e-4,
        "the plies' first index ≥ 1, z",
    );
    assert!(ply.iter().all(|p| (p.1 - depth).abs() < 1e-9), "ply onset at several depths");
}

/// The study's refined runs of examples/laminate_drop_weight_damage.toml
/// (`python3 bench/drop/damage_study.py roll_a120_g1600_800
/// roll_a60_g3200_1600`, bench/drop/damage_results.csv): the averaged peak
/// force (N) and the energy dissipated (J) with the axis refined again
/// (120 B2, the same graded steps) and with both time steps halved (60 B2,
/// 0.625 µs over the first 2 ms, then 2.5 µs).
const DAMAGE_REFINED_AXIS: (f64, f64) = (512.310, 0.446161);
const DAMAGE_REFINED_STEP: (f64, f64) = (515.427, 0.452905);

/// A cell of a VTU file: its centre (y, z in m), the largest Hashin
/// matrix index of its points and its matrix-tension damage `d_mt`.
type Cell = (f64, f64, f64, f64);

/// The cells of a VTU file.
fn cell_indices(file: &Path) -> Vec<Cell> {
    let points = common::vtu_array(file, None);
    let connectivity = common::vtu_array(file, Some("connectivity"));
    let offsets = common::vtu_array(file, Some("offsets"));
    let matrix = common::vtu_array(file, Some("fi_hashin_matrix"));
    let d_mt = common::vtu_array(file, Some("d_mt"));
    let mut start = 0;
    let mut cells = Vec::new();
    for (&end, &d) in offsets.iter().zip(&d_mt) {
        let ids: Vec<usize> = connectivity[start..end as usize].iter().map(|&i| i as usize).collect();
        start = end as usize;
        let mean = |c: usize| ids.iter().map(|&i| points[3 * i + c]).sum::<f64>() / ids.len() as f64;
        cells.push((mean(1), mean(2), ids.iter().map(|&i| matrix[i]).fold(0.0, f64::max), d));
    }
    cells
}

/// The frames of a run (time, cells of `cell_indices`).
fn cell_frames(out: &Path) -> Vec<(f64, Vec<Cell>)> {
    let pvd = std::fs::read_to_string(out.join("frames.pvd")).unwrap();
    let mut frames = Vec::new();
    for line in pvd.lines().filter(|l| l.contains("<DataSet")) {
        let attr =
            |name: &str| line.split(&format!("{name}=\"")).nth(1).unwrap().split('"').next().unwrap().to_string();
        frames.push((attr("timestep").parse().unwrap(), cell_indices(&out.join(attr("file")))));
    }
    frames
}

/// The damaging example as shipped, with frames every `FRAMES`.
fn run_damage_example() -> (PathBuf, Value) {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/laminate_drop_weight_damage.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let framed = text.replacen(
        "ply_damage_forces = \"implicit\"\n",
        &format!("ply_damage_forces = \"implicit\"\noutput_interval = {FRAMES:e}\n"),
        1,
    );
    assert_ne!(framed, text, "the example's [analysis] changed: ask for its frames another way");
    common::run_text("drop_weight_laminate", "damage", &framed)
}

/// examples/laminate_drop_weight_damage.toml: the same drop weight with
/// ply damage. The ledger closes within 1 % of the impact energy at every
/// step; no step creates energy (the mechanical energy never grows) and no
/// damage is undone (the ledger's delamination, every mode's damage and
/// the scheme's column never fall); the plies crack in the matrix and
/// their fibres barely damage (the beam is not punched through); it
/// delaminates and the averaged force drops; the onset against laminated
/// beam theory (501.6 N, as the elastic plies'); the averaged peak force
/// and the energy dissipated converged against the study's refined runs
/// (issue 48: within 3 % of each); and the matrix damage starts where the
/// Hashin matrix index reached 1.
#[test]
#[ignore = "validate: slow — examples/laminate_drop_weight_damage.toml, 2,400 time steps (under a minute)"]
fn a_drop_weight_cracks_and_delaminates_a_damaging_laminate_and_the_ledger_closes() {
    let (out, summary) = run_damage_example();
    let booked = [
        "delamination_J",
        "damage_fibre_tension_J",
        "damage_fibre_compression_J",
        "damage_matrix_tension_J",
        "damage_matrix_compression_J",
        "damage_scheme_J",
    ];
    let (c, mechanical) = checked_ledger(&out, "drop_weight_damage", &booked);
    let (time, n) = (&c["time_s"], mechanical.len());
    // the damage: matrix cracks, the fibres (nearly) whole: not punched
    // through. A few points at a multiaxial onset have their strength
    // lowered at the point (`materials::damage`, the rollers' and the
    // striker's contact), a known limit (docs/limitations.md)
    let damage = &summary["damage"];
    let reduced = damage["strength_reduced_points"].as_u64().unwrap() as f64;
    common::known_limit("drop_weight_damage.reduced_points", reduced, "", 1.0, 30.0, "points with a lowered strength");
    let dissipated_by = |mode: &str| damage["dissipated_j"][mode].as_f64().unwrap();
    common::figure("drop_weight_damage.matrix_tension", dissipated_by("matrix_tension"), "J", "> 0: matrix cracks");
    assert!(dissipated_by("matrix_tension") > 1e-2 * IMPACT_ENERGY);
    let fibres = dissipated_by("fibre_tension") + dissipated_by("fibre_compression");
    // the fibres: damaged little, not broken. Their tension onset is
    // borderline under the striker (the bottom 0° ply's Hashin fibre
    // index near 1), so what they dissipate follows Δt, the mesh and the
    // factor's round-off: bench/drop/damage_results.csv at 60 B2 gives
    // 0.27 % (2.5 µs), 0.04 % (1.25 µs) and 0.52 % (0.625 µs) of the
    // impact energy (0.03 %, 0.31 %, 0.48 % with the simplicial factor),
    // 0 at 120 B2; the bound is 1 %, a tenth of what the matrix dissipates
    common::figure("drop_weight_damage.fibres", fibres / IMPACT_ENERGY, "", "< 0.01 of the impact energy");
    assert!(fibres < 1e-2 * IMPACT_ENERGY, "the fibres broke: {fibres} J");
    let area = summary["delamination"]["area_m2"].as_f64().unwrap();
    common::figure("drop_weight_damage.delaminated_area", area, "m²", "> half the beam's plan");
    assert!(area > 0.5 * 0.05 * 0.01, "delaminated area {area} m²");
    // the load drop and the onset, as the elastic plies' example
    let h = common::csv_columns(&out.join("history_striker.csv"));
    let avg = averaged_force(time, &h["f_n"]);
    let (ip, &(t_peak, peak)) = avg.iter().enumerate().max_by(|a, b| a.1.1.total_cmp(&b.1.1)).unwrap();
    let lowest_after = avg[ip..].iter().take_while(|(t, _)| *t < t_peak + 0.5e-3).fold(f64::MAX, |m, a| m.min(a.1));
    common::figure("drop_weight_damage.drop", lowest_after / peak, "", "< 0.5: the load drop");
    assert!(lowest_after < 0.5 * peak, "peak {peak} N at {t_peak} s, then {lowest_after} N");
    common::within("drop_weight_damage.onset", peak, 501.6, 0.10, "laminated beam theory's onset 2 b S D/Q");
    let dissipated = IMPACT_ENERGY - mechanical[n - 1];
    common::figure("drop_weight_damage.dissipated", dissipated, "J", "");
    // converged: the averaged peak force and the energy dissipated within
    // 3 % of the refined runs' (at a uniform 2.5 µs step the energy follows
    // the factor's round-off, 8 %; from 1.25 µs on, while the laminate
    // damages, it converges: docs/limitations.md)
    for (what, refined) in [("axis", DAMAGE_REFINED_AXIS), ("step", DAMAGE_REFINED_STEP)] {
        let source = format!("the {what} refined, bench/drop/damage_results.csv");
        common::within(&format!("drop_weight_damage.peak_{what}"), peak, refined.0, 0.03, &source);
        common::within(&format!("drop_weight_damage.dissipated_{what}"), dissipated, refined.1, 0.03, &source);
    }
    // where the matrix cracks: every cell away from the supports with
    // d_mt > 0 at the end (result.vtu) had its Hashin matrix index at 1 or
    // more in some frame (every 25 µs) by the one it first shows damage
    // in, or its crack grew in along its ply from a next cell of its row
    // that had cracked by then, back to one whose index did: the law's
    // onset is that index at 1 where no band lowers it, and once a point
    // softens its stress (the fields') falls back inside the surface, so a
    // crack running along a ply (9 mm within the 25 µs before 0.525 ms)
    // passes cells between two frames whose index never shows 1 (measured
    // 0.79–0.99). (The fields took the intact stiffness times a softened
    // point's strain, an index of hundreds, and showed every cracked cell
    // at 1 or more.)
    const SPAN: f64 = 0.05;
    let interior = |y: f64| y > 0.15 * SPAN && y < 0.85 * SPAN;
    let frames = cell_frames(&out);
    let d_mt = common::vtu_array(&out.join("result.vtu"), Some("d_mt"));
    let cracked: Vec<usize> = (0..d_mt.len()).filter(|&i| d_mt[i] > 0.0 && interior(frames[0].1[i].0)).collect();
    assert!(!cracked.is_empty(), "no matrix crack between the rollers");
    let cell = |i: usize| frames[0].1[i];
    // the frame each cell first shows damage in
    let cracked_at: Vec<Option<usize>> = (0..d_mt.len()).map(|i| frames.iter().position(|f| f.1[i].3 > 0.0)).collect();
    // the cells' pitch along y
    let pitch = cracked
        .iter()
        .flat_map(|&a| cracked.iter().map(move |&b| (a, b)))
        .filter(|&(a, b)| a != b && (cell(a).1 - cell(b).1).abs() < 1e-9)
        .map(|(a, b)| (cell(a).0 - cell(b).0).abs())
        .fold(f64::MAX, f64::min);
    let mut explained: Vec<bool> =
        (0..d_mt.len()).map(|i| cracked_at[i].is_some_and(|k| frames[..=k].iter().any(|f| f.1[i].2 >= 1.0))).collect();
    let origins = cracked.iter().filter(|&&i| explained[i]).count();
    loop {
        let grown: Vec<usize> = (0..d_mt.len())
            .filter(|&i| !explained[i] && cracked_at[i].is_some())
            .filter(|&i| {
                (0..d_mt.len()).any(|j| {
                    explained[j]
                        && cracked_at[j] <= cracked_at[i]
                        && (cell(j).1 - cell(i).1).abs() < 1e-9
                        && (cell(j).0 - cell(i).0).abs() < 1.5 * pitch
                })
            })
            .collect();
        if grown.is_empty() {
            break;
        }
        for i in grown {
            explained[i] = true;
        }
    }
    for &i in &cracked {
        let (y, z, _, _) = cell(i);
        let k = cracked_at[i].unwrap_or_else(|| panic!("d_mt > 0 at y {y} z {z} at the end, in no frame"));
        println!("d_mt {} at y {y} z {z}: cracked at {} s, explained {}", d_mt[i], frames[k].0, explained[i]);
        assert!(explained[i], "d_mt > 0 at y {y} z {z} from {} s, where no index of its crack reached 1", frames[k].0);
    }
    common::figure("drop_weight_damage.crack_origins", origins as f64, "", "cracked cells whose own index reached 1");
    // most cracks start where their own index shows 1 (measured 44 of 56
    // cells; the others lie on the cracks running along the 90° plies)
    assert!(2 * origins >= cracked.len(), "{origins} of {} cracked cells showed their index at 1", cracked.len());
    let k = frames.iter().position(|f| f.1.iter().any(|c| interior(c.0) && c.2 >= 1.0)).unwrap();
    common::figure("drop_weight_damage.matrix_onset_time", frames[k].0, "s", "first frame with a matrix index >= 1");
    println!("averaged peak {peak} N at {t_peak} s; dissipated {dissipated} J");
}

/// The energy dissipated by examples/laminate_drop_weight_damage.toml as
/// shipped, the default linear solves (`python3 bench/drop/damage_study.py
/// roll_a60_g1600_800`, bench/drop/damage_results.csv).
const DAMAGE_DEFAULT_DISSIPATED: f64 = 0.448792;

/// The damaging drop weight's answer is not unique across linear solves
/// (docs/limitations.md): with a new double factor at every correction
/// (`solver.reuse_factorization = false`) the averaged peak is the same but
/// the mid-plane's crack arrests further out — measured 471 mm² against
/// 350 and 1.226 times the energy dissipated (0.5503 J;
/// `damage_study.py roll_a60_g1600_800_noreuse`). A known limit, asserted
/// from both sides: a change that makes the run independent of its solves
/// shows up here.
#[test]
#[ignore = "validate: slow — examples/laminate_drop_weight_damage.toml without the factor reuse, 2,400 time steps (under a minute)"]
fn the_damaging_drop_weights_crack_arrest_follows_the_linear_solves() {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/laminate_drop_weight_damage.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let changed =
        text.replacen("max_increments = 200000\n", "max_increments = 200000\nreuse_factorization = false\n", 1);
    assert_ne!(changed, text, "the example's [solver] changed: set reuse_factorization another way");
    let (out, summary) = common::run_text("drop_weight_laminate", "damage_noreuse", &changed);
    let (_, mechanical) = checked_ledger(&out, "drop_weight_damage_noreuse", &[]);
    let dissipated = IMPACT_ENERGY - mechanical[mechanical.len() - 1];
    let area = summary["delamination"]["area_m2"].as_f64().unwrap();
    println!("without the reuse: dissipated {dissipated} J, delaminated {area} m²");
    common::known_limit(
        "drop_weight_damage.noreuse_dissipated_ratio",
        dissipated / DAMAGE_DEFAULT_DISSIPATED,
        "",
        1.15,
        1.30,
        "the energy dissipated without the factor reuse over the default's",
    );
    common::known_limit(
        "drop_weight_damage.noreuse_area",
        area * 1e6,
        "mm²",
        440.0,
        500.0,
        "delaminated (350 mm² by default)",
    );
}

/// The example's first `0.8` ms (`320` steps of `2.5` µs: through the
/// mid-plane's separation), at its own viscosity and at a tenth of it, run
/// by the CLI: the console's result lines and summary.json.
fn run_short(viscosity: &str) -> (String, Value) {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/laminate_drop_weight.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let short = [("duration = 0.006\n", "duration = 0.0008\n"), ("increments = 2400\n", "increments = 320\n")]
        .iter()
        .chain([("viscosity = 1e-06 }", viscosity)].iter())
        .fold(text, |t, (from, to)| {
            assert_eq!(t.matches(from).count(), 1, "the example changed: {from}");
            t.replace(from, to)
        });
    let dir = common::scratch_dir("drop_weight_laminate", &format!("short_{viscosity}"));
    let (model, out) = (dir.join("short.toml"), dir.join("out"));
    std::fs::write(&model, short).unwrap();
    let run = common::cufem().args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap()]).output().unwrap();
    let console = String::from_utf8_lossy(&run.stdout).into_owned() + &String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{console}");
    // the impactor's force against time (it had no plot; a new-user review)
    assert!(out.join("history_striker.png").is_file(), "{console}");
    (console, serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap())
}

/// A new user's review: the console gave the delamination's energy by its
/// law and its viscosity (0.489 J) while energy.csv's `delamination_J`
/// said 0.455 J, without a word; and the viscous over-stress did 29 % of
/// that energy, unwarned. Now the console splits the law's and the viscous
/// part, prints the ledger's end row beside them (its delamination the
/// interfaces' work less what they hold, told as such), and warns, naming
/// `materials[1].cohesive.viscosity`, when the viscous part exceeds a tenth
/// of the interfaces' dissipation: at the example's `1e-6` s through the
/// separation (`29 %`), not at `1e-7` s (`6.5 %`). The percentages are
/// checked against summary.json's `delamination` (an independent
/// reckoning of the same sums), the ledger's figures against energy.csv's
/// last row.
#[test]
fn the_console_tells_the_delamination_energy_apart_and_warns_of_viscosity() {
    let (console, summary) = run_short("viscosity = 1e-06 }");
    let d = &summary["delamination"];
    let (law, viscous) = (d["dissipated_j"].as_f64().unwrap(), d["viscous_j"].as_f64().unwrap());
    let share = viscous / (law + viscous);
    assert!((0.2..0.4).contains(&share), "{share}");
    assert!(
        console.contains(&format!("J dissipated: the law's {law:.5e} J and its viscous over-stress's {viscous:.5e} J")),
        "{console}"
    );
    let warning = format!(
        "warning: materials[1].cohesive.viscosity: the viscous over-stress of viscosity = 1e-6 did {:.0} % of its \
         interfaces' dissipation",
        100.0 * share
    );
    assert!(console.contains(&warning), "{console}");
    let ledger = summary["energy"]["delamination"].as_f64().unwrap();
    assert!(console.contains(&format!("delamination {ledger:.5e}; balance")), "{console}");
    assert!(console.contains("delamination: the interfaces' work less the energy they hold"), "{console}");
    assert!(console.contains("energy [J]         at the start 8.00000e-1;"), "{console}");

    let (console, summary) = run_short("viscosity = 1e-07 }");
    let d = &summary["delamination"];
    let share =
        d["viscous_j"].as_f64().unwrap() / (d["dissipated_j"].as_f64().unwrap() + d["viscous_j"].as_f64().unwrap());
    assert!((0.02..0.1).contains(&share), "{share}");
    assert!(!console.contains("cohesive.viscosity"), "{console}");
}
