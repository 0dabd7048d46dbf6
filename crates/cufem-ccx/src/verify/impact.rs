//! Rigid impactors against CalculiX's `*DYNAMIC` twin
//! ([`crate::dynamic`]): each impactor's motion, its contact force
//! over time and the energy it leaves in the bodies.
//!
//! cufem's history is its converged increments (the impactor's rigid
//! displacement `a` along its velocity `d̂`, and its contact force on the
//! body `F = f · d̂`, positive when it pushes); CalculiX's is its reference
//! node's displacement (`*NODE PRINT`, `U`) and the contact's total
//! surface force on the slave body (`*CONTACT PRINT`, `CF`) at every
//! increment. Compared:
//!
//! * the displacement history, `max_t |a_cufem − a_3D| / max_t |a_3D|`
//!   (CalculiX interpolated linearly in time at cufem's times);
//! * the force history: the peaks, and the impulse `∫ F dt` (each by the
//!   trapezoidal rule over its own increments) — the force itself rings at
//!   the contact nodes' frequencies, which differ between the two meshes,
//!   and the impulse is what the motion integrates;
//! * the energy the impactor left in the bodies, `½ m (v₀² − v_end²)`, with
//!   `v_end` both ways the mean velocity over the last tenth of the
//!   analysis (from the displacements: the same estimator for both).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::{CcxRun, deck::set_name};
use cufem::analysis::Solution;
use cufem::io::{IoError, Plot, Series};
use cufem::setup::Model;

/// One impactor, both ways.
#[derive(Debug, Clone, Serialize)]
pub struct ImpactRow {
    /// Indenter name.
    pub name: String,
    /// cufem increments compared.
    pub points: usize,
    /// Largest displacement along the velocity (m), cufem and 3D.
    pub displacement_peaks: (f64, f64),
    /// `100 max_t |a_cufem − a_3D| / max_t |a_3D|`.
    pub displacement_difference_percent: f64,
    /// Largest contact force (N), cufem and 3D.
    pub force_peaks: (f64, f64),
    /// `100 (F_peak,cufem − F_peak,3D) / F_peak,3D`.
    pub peak_difference_percent: f64,
    /// `∫ F dt` (N s), cufem and 3D.
    pub impulses: (f64, f64),
    /// `100 (I_cufem − I_3D) / I_3D`.
    pub impulse_difference_percent: f64,
    /// `½ m (v₀² − v_end²)` (J), cufem and 3D.
    pub absorbed: (f64, f64),
    /// `100 (E_cufem − E_3D) / E_3D`.
    pub absorbed_difference_percent: f64,
    /// `100 (E_cufem − E_3D) / (½ m v₀²)`: the same difference in % of
    /// the impact energy (what it is small against in an elastic impact).
    pub absorbed_difference_of_impact_percent: f64,
}

/// One impactor's histories: `(t (s), a cufem, a 3D (m), F cufem (N))` at
/// cufem's increments, and `(t, F 3D)` at CalculiX's.
#[derive(Debug, Clone)]
pub struct ImpactCurve {
    /// Indenter name.
    pub name: String,
    /// At cufem's increments.
    pub points: Vec<(f64, f64, f64, f64)>,
    /// CalculiX's force at its increments.
    pub ccx_force: Vec<(f64, f64)>,
}

/// `½ m (v₀² − v²)` with `v` the mean velocity over the last tenth of the
/// history `(t, a)`.
fn absorbed(mass: f64, speed: f64, history: &[(f64, f64)]) -> f64 {
    let Some(&(t1, a1)) = history.last() else { return 0.0 };
    let k = history.partition_point(|h| h.0 < 0.9 * t1);
    let (t0, a0) = history[k.min(history.len() - 1)];
    let v = if t1 > t0 { (a1 - a0) / (t1 - t0) } else { speed };
    0.5 * mass * (speed * speed - v * v)
}

/// The largest magnitude of `values` (0 for none).
fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m, x| m.max(x.abs()))
}

/// `∫ F dt` by the trapezoidal rule from `(0, 0)`.
fn impulse(history: &[(f64, f64)]) -> f64 {
    let mut last = (0.0, 0.0);
    let mut sum = 0.0;
    for &(t, f) in history {
        sum += 0.5 * (f + last.1) * (t - last.0);
        last = (t, f);
    }
    sum
}

/// Linear interpolation in a time history; `None` past its end.
fn at_time(history: &[(f64, f64)], t: f64) -> Option<f64> {
    let last = history.last()?;
    if t > last.0 * (1.0 + 1e-5) {
        return None;
    }
    let k = history.partition_point(|h| h.0 < t);
    let Some(&(t1, v1)) = history.get(k) else { return Some(last.1) };
    let (t0, v0) = if k == 0 { (0.0, 0.0) } else { history[k - 1] };
    let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 1.0 };
    Some(v0 + w * (v1 - v0))
}

/// The impactors of a transient model against the CalculiX run (none
/// without impactors, or when CalculiX printed no history of theirs).
pub fn compare_impacts(model: &Model, solution: &Solution, run: &CcxRun) -> (Vec<ImpactRow>, Vec<ImpactCurve>) {
    let Some(settings) = &model.transient else { return Default::default() };
    let (mut rows, mut curves) = (Vec::new(), Vec::new());
    for ind in &model.indenters {
        let Some(imp) = ind.impactor else { continue };
        let speed = imp.velocity.iter().map(|v| v * v).sum::<f64>().sqrt();
        let dir = imp.velocity.map(|v| v / speed);
        let along = |v: [f64; 3]| v.iter().zip(&dir).map(|(a, b)| a * b).sum::<f64>();
        let (Some(u), Some(cf)) = (
            run.histories.get(&format!("U:{}", set_name("REF", &ind.name))),
            run.histories.get(&format!("CF:{}", set_name("SS", &ind.name))),
        ) else {
            continue;
        };
        let theirs_a: Vec<(f64, f64)> = u.iter().map(|(t, v)| (*t, along(*v))).collect();
        let theirs_f: Vec<(f64, f64)> = cf.iter().map(|(t, f)| (*t, along(*f))).collect();
        let ours: Vec<(f64, f64, f64)> = solution
            .history
            .iter()
            .filter_map(|row| {
                let c = row.contact(&ind.name)?;
                Some((settings.time(row.lambda), along(c.displacement), along(c.force)))
            })
            .collect();
        let points: Vec<(f64, f64, f64, f64)> =
            ours.iter().filter_map(|&(t, a, f)| Some((t, a, at_time(&theirs_a, t)?, f))).collect();
        if points.len() < 2 || theirs_f.is_empty() {
            continue;
        }
        let displacement_peaks = (largest(points.iter().map(|p| p.1)), largest(points.iter().map(|p| p.2)));
        let diff = largest(points.iter().map(|p| p.1 - p.2));
        let force_peaks =
            (points.iter().fold(0.0f64, |m, p| m.max(p.3)), theirs_f.iter().fold(0.0f64, |m, p| m.max(p.1)));
        let ours_f: Vec<(f64, f64)> = ours.iter().map(|p| (p.0, p.2)).collect();
        let ours_a: Vec<(f64, f64)> = ours.iter().map(|p| (p.0, p.1)).collect();
        let impulses = (impulse(&ours_f), impulse(&theirs_f));
        let energies = (absorbed(imp.mass, speed, &ours_a), absorbed(imp.mass, speed, &theirs_a));
        let relative = |a: f64, b: f64| if b != 0.0 { 100.0 * (a - b) / b.abs() } else { f64::NAN };
        rows.push(ImpactRow {
            name: ind.name.clone(),
            points: points.len(),
            displacement_peaks,
            displacement_difference_percent: 100.0 * diff / displacement_peaks.1,
            force_peaks,
            peak_difference_percent: relative(force_peaks.0, force_peaks.1),
            impulses,
            impulse_difference_percent: relative(impulses.0, impulses.1),
            absorbed: energies,
            absorbed_difference_percent: relative(energies.0, energies.1),
            absorbed_difference_of_impact_percent: 100.0 * (energies.0 - energies.1) / (0.5 * imp.mass * speed * speed),
        });
        curves.push(ImpactCurve { name: ind.name.clone(), points, ccx_force: theirs_f });
    }
    (rows, curves)
}

/// The rows of the verification table.
pub fn table(rows: &[ImpactRow], t: &mut String) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        t,
        "\n{:<16} {:>16} {:>32} {:>32} {:>32} {:>12}",
        "impactor", "motion max diff", "peak force [N]", "impulse [N s]", "energy left [J]", "of impact"
    );
    for r in rows {
        let pair = |(a, b): (f64, f64), d: f64| format!("{a:.4e} / {b:.4e} ({d:+.1} %)");
        let _ = writeln!(
            t,
            "{:<16} {:>14.2} % {:>32} {:>32} {:>32} {:>+10.2} %",
            r.name,
            r.displacement_difference_percent,
            pair(r.force_peaks, r.peak_difference_percent),
            pair(r.impulses, r.impulse_difference_percent),
            pair(r.absorbed, r.absorbed_difference_percent),
            r.absorbed_difference_of_impact_percent
        );
    }
    let _ = writeln!(
        t,
        "(cufem / CalculiX 3D; motion: largest |a_cufem − a_3D| along the velocity, % of the 3D peak; energy left: \
         ½ m (v₀² − v_end²), v_end the mean velocity over the last tenth of the analysis; of impact: its \
         difference in % of ½ m v₀²)"
    );
}

/// The rows of `table.csv` (`kind,name,quantity,cufem,ccx,difference_percent`).
pub fn csv(rows: &[ImpactRow], csv: &mut String) {
    for r in rows {
        let name = cufem::io::csv_field(&r.name);
        let d = r.displacement_difference_percent;
        let _ =
            writeln!(csv, "impact,{name},displacement,{:e},{:e},{d:e}", r.displacement_peaks.0, r.displacement_peaks.1);
        for (q, (a, b), d) in [
            ("peak_force", r.force_peaks, r.peak_difference_percent),
            ("impulse", r.impulses, r.impulse_difference_percent),
            ("energy_left", r.absorbed, r.absorbed_difference_percent),
        ] {
            let _ = writeln!(csv, "impact,{name},{q},{a:e},{b:e},{d:e}");
        }
    }
}

/// Writes `impact_<name>.csv` (`t,a,ccx_a,force`: cufem's increments, s, m,
/// N), `impact_<name>_ccx.csv` (`t,force`) and `impact_<name>.png` (the
/// contact force against time, both ways) into `dir`.
pub fn write(dir: &Path, curves: &[ImpactCurve]) -> Result<Vec<PathBuf>, IoError> {
    let mut written = Vec::new();
    for (c, plot) in curves.iter().zip(plots(curves)) {
        let mut ours = String::from("t,a,ccx_a,force\n");
        for (t, a, b, f) in &c.points {
            let _ = writeln!(ours, "{t:e},{a:e},{b:e},{f:e}");
        }
        let mut theirs = String::from("t,force\n");
        for (t, f) in &c.ccx_force {
            let _ = writeln!(theirs, "{t:e},{f:e}");
        }
        for (file, text) in [(format!("impact_{}.csv", c.name), ours), (format!("impact_{}_ccx.csv", c.name), theirs)] {
            let p = dir.join(file);
            std::fs::write(&p, text).map_err(|e| cufem::io::file_error(&p, e))?;
            written.push(p);
        }
        written.push(plot.write_png(dir)?);
    }
    Ok(written)
}

/// The plot of each impactor (`impact_<name>`): the contact force against
/// time (ms), cufem's at its increments and CalculiX's at its own.
pub fn plots(curves: &[ImpactCurve]) -> Vec<Plot> {
    curves
        .iter()
        .map(|c| Plot {
            name: format!("impact_{}", c.name),
            title: format!("{}: contact force against time", c.name),
            x: "time [ms]".into(),
            y: "force [N]".into(),
            series: vec![
                Series {
                    name: "cufem".into(),
                    points: c.points.iter().map(|p| (p.0 * 1e3, p.3)).collect(),
                    dashed: false,
                },
                Series {
                    name: "CalculiX 3D".into(),
                    points: c.ccx_force.iter().map(|p| (p.0 * 1e3, p.1)).collect(),
                    dashed: true,
                },
            ],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_impulse_and_the_energy_left_of_known_histories() {
        // a half-sine pulse of 1 N over 1 s: impulse 2/π
        let pulse: Vec<(f64, f64)> =
            (1..=1000).map(|k| (k as f64 / 1000.0, (std::f64::consts::PI * k as f64 / 1000.0).sin())).collect();
        assert!((impulse(&pulse) - 2.0 / std::f64::consts::PI).abs() < 1e-6);
        // 2 kg from 1 m/s to a rebound at 0.5 m/s: 0.75 J left
        let motion: Vec<(f64, f64)> = (0..=100).map(|k| (k as f64 / 100.0, 1.0 - 0.5 * k as f64 / 100.0)).collect();
        assert!((absorbed(2.0, 1.0, &motion) - 0.75).abs() < 1e-12);
        assert!((at_time(&motion, 0.005).unwrap() - 0.9975).abs() < 1e-12);
        assert_eq!(at_time(&motion, 2.0), None);
    }
}
