//! Displacement histories at the probes against CalculiX's `*DYNAMIC`
//! steps ([`crate::dynamic`]): the time history of a transient model,
//! not one state; and the load path of a static model with nonlinear
//! geometry (its probes' displacements against the load factor λ, the
//! step time of its single NLGEOM step), whose static comparisons at the
//! end state stay.
//!
//! cufem's history is its converged increments (`Solution::history`: each
//! probe's displacement at analysis time λ, at time `t(λ)` of
//! [`cufem::dynamics::TransientSettings::time`]); CalculiX's is every
//! increment of its `.frd` file, sampled at the same probe points as the
//! static comparison samples them ([`crate::sample_displacement`]).
//! They are compared at cufem's times, CalculiX's history interpolated
//! linearly in time between its increments (from rest, `u = 0`, at
//! `t = 0`). Per probe and component the difference is
//!
//! ```text
//! max_t |u_cufem(t) − u_3D(t)| / max_t |u_3D(t)| ,
//! ```
//!
//! in %; a component whose 3D peak is below 1e-3 of the probe's largest 3D
//! displacement (a restrained direction) has no meaningful relative
//! difference and is reported as such. The other static comparisons
//! (probes, lines, resultants, whole field at the end) are left out.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::{CcxRun, HexMesh};
use cufem::analysis::Solution;
use cufem::io::{IoError, Plot, Series};
use cufem::quantity::Quantity;
use cufem::setup::Model;

/// One probe and displacement component over the whole history.
#[derive(Debug, Clone, Serialize)]
pub struct ProbeHistoryRow {
    /// Probe name.
    pub probe: String,
    /// Quantity name (`u_x`, `u_y`, `u_z`).
    pub quantity: String,
    /// cufem increments compared.
    pub points: usize,
    /// `max_t |u_cufem|` (m).
    pub cufem_peak: f64,
    /// `max_t |u_3D|` (m).
    pub ccx_peak: f64,
    /// `100 max_t |u_cufem − u_3D| / max_t |u_3D|`, `None` where the 3D
    /// component stays ≈ 0 (below 1e-3 of the probe's largest 3D value).
    pub max_difference_percent: Option<f64>,
    /// Time (s) of the largest difference, or its load factor on a load
    /// path (`load_path`).
    pub at: f64,
    /// `true` when compared along the load factor λ of a static step (the
    /// load path of a model with nonlinear geometry), `false` in time.
    pub load_path: bool,
}

/// A point of a probe's history: `(λ, t (s), cufem u (m), 3D u (m))`.
pub type HistoryPoint = (f64, f64, [f64; 3], [f64; 3]);

/// One probe's history, both ways, at cufem's increments.
#[derive(Debug, Clone)]
pub struct ProbeCurve {
    /// Probe name.
    pub probe: String,
    /// The points, in time order.
    pub points: Vec<HistoryPoint>,
}

/// CalculiX's displacement at `t`, linear between its increments;
/// `None` past its last increment (beyond the 6 digits of its times).
fn at_time(history: &[(f64, [f64; 3])], t: f64) -> Option<[f64; 3]> {
    let last = history.last()?;
    if t > last.0 * (1.0 + 1e-5) {
        return None;
    }
    let k = history.partition_point(|h| h.0 < t);
    if k == 0 {
        return Some(history[0].1);
    }
    let Some(&(t1, u1)) = history.get(k) else { return Some(last.1) };
    let (t0, u0) = history[k - 1];
    let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 1.0 };
    Some(std::array::from_fn(|c| u0[c] + w * (u1[c] - u0[c])))
}

/// The probes' displacement histories: in time for a transient model,
/// along the load factor for a static one with nonlinear geometry (empty
/// for any other model or a run without an increment history).
pub fn compare_probe_histories(
    model: &Model,
    solution: &Solution,
    mesh: &HexMesh,
    run: &CcxRun,
) -> (Vec<ProbeHistoryRow>, Vec<ProbeCurve>) {
    let load_path = model.transient.is_none();
    if load_path && (model.modal.is_some() || !model.kinematics.is_nonlinear()) {
        return Default::default();
    }
    // CalculiX's time: the transient total time, or the static step time λ
    let time = |lambda: f64| model.transient.as_ref().map_or(lambda, |t| t.time(lambda));
    let (mut rows, mut curves) = (Vec::new(), Vec::new());
    for (i, probe) in model.probes.iter().enumerate() {
        // CalculiX's history at the probe, from rest at t = 0
        let theirs: Vec<(f64, [f64; 3])> = std::iter::once(Some((0.0, [0.0; 3])))
            .chain(
                run.results
                    .history
                    .iter()
                    .map(|(t, u)| crate::sample_displacement(model, mesh, u, &probe.locations).map(|v| (*t, v))),
            )
            .collect::<Option<_>>()
            .unwrap_or_default();
        if theirs.len() < 2 {
            continue;
        }
        let points: Vec<HistoryPoint> = solution
            .history
            .iter()
            .filter_map(|row| {
                let t = time(row.lambda);
                Some((row.lambda, t, *row.probes.get(i)?, at_time(&theirs, t)?))
            })
            .collect();
        if points.is_empty() {
            continue;
        }
        let scale = points.iter().flat_map(|p| p.3).fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..3 {
            let peak = |pick: fn(&HistoryPoint) -> [f64; 3]| points.iter().fold(0.0f64, |m, p| m.max(pick(p)[k].abs()));
            let (ours, reference) = (peak(|p| p.2), peak(|p| p.3));
            let (at, max) = points
                .iter()
                .map(|p| (p.1, (p.2[k] - p.3[k]).abs()))
                .fold((0.0, 0.0), |m, d| if d.1 > m.1 { d } else { m });
            rows.push(ProbeHistoryRow {
                probe: probe.name.clone(),
                quantity: Quantity::Displacement(k).name(),
                points: points.len(),
                cufem_peak: ours,
                ccx_peak: reference,
                max_difference_percent: (scale > 0.0 && reference > 1e-3 * scale).then(|| 100.0 * max / reference),
                at,
                load_path,
            });
        }
        curves.push(ProbeCurve { probe: probe.name.clone(), points });
    }
    (rows, curves)
}

/// The rows of the verification table.
pub fn table(rows: &[ProbeHistoryRow], t: &mut String) {
    let Some(first) = rows.first() else { return };
    let (title, at, scale) =
        if first.load_path { ("load path", "at λ", 1.0) } else { ("probe history", "at [ms]", 1e3) };
    let _ = writeln!(
        t,
        "\n{:<16} {:<10} {:>6} {:>16} {:>14} {:>10} {:>9}",
        title, "quantity", "points", "cufem peak [mm]", "3D peak [mm]", "max diff", at
    );
    for r in rows {
        let _ = writeln!(
            t,
            "{:<16} {:<10} {:>6} {:>16.6} {:>14.6} {:>10} {:>9.4}",
            r.probe,
            r.quantity,
            r.points,
            r.cufem_peak * 1e3,
            r.ccx_peak * 1e3,
            r.max_difference_percent.map_or_else(|| "(≈ 0)".to_string(), |d| format!("{d:.2} %")),
            r.at * scale
        );
    }
    let _ = if first.load_path {
        writeln!(
            t,
            "(max diff: largest |u_cufem − u_3D| over cufem's increments, CalculiX interpolated linearly in the \
             load factor, % of the 3D peak of that component)"
        )
    } else {
        writeln!(
            t,
            "(max diff: largest |u_cufem − u_3D| over cufem's increments, CalculiX interpolated linearly in time, \
             % of the 3D peak of that component; the static comparisons are left out)"
        )
    };
}

/// The rows of `table.csv` (`kind,name,quantity,cufem,ccx,difference_percent`):
/// per probe and component both peaks and the largest difference.
pub fn csv(rows: &[ProbeHistoryRow], csv: &mut String) {
    for r in rows {
        let _ = writeln!(
            csv,
            "probe_history,{},{},{:e},{:e},{}",
            cufem::io::csv_field(&r.probe),
            r.quantity,
            r.cufem_peak,
            r.ccx_peak,
            r.max_difference_percent.map_or(String::new(), |d| format!("{d:e}"))
        );
    }
}

/// Writes `probe_history_<probe>.csv` (`lambda,t,u_x,u_y,u_z,ccx_u_x,ccx_u_y,ccx_u_z`:
/// analysis time, time in s, displacements in m) and
/// `probe_history_<probe>.png` (the components compared, both ways, against
/// time) into `dir`.
pub fn write(dir: &Path, rows: &[ProbeHistoryRow], curves: &[ProbeCurve]) -> Result<Vec<PathBuf>, IoError> {
    let mut written = Vec::new();
    for (ProbeCurve { probe, points }, plot) in curves.iter().zip(plots(rows, curves)) {
        let mut csv = String::from("lambda,t,u_x,u_y,u_z,ccx_u_x,ccx_u_y,ccx_u_z\n");
        for (l, t, a, b) in points {
            let _ = writeln!(csv, "{l:e},{t:e},{:e},{:e},{:e},{:e},{:e},{:e}", a[0], a[1], a[2], b[0], b[1], b[2]);
        }
        let p = dir.join(format!("probe_history_{probe}.csv"));
        std::fs::write(&p, csv).map_err(|e| cufem::io::file_error(&p, e))?;
        written.push(p);
        written.push(plot.write_png(dir)?);
    }
    Ok(written)
}

/// The plot of each probe's history (`probe_history_<probe>`): the
/// components that move in 3D (all three if none does), both ways,
/// against time (ms) or, on a load path, the load factor.
pub fn plots(rows: &[ProbeHistoryRow], curves: &[ProbeCurve]) -> Vec<Plot> {
    let load_path = rows.first().is_some_and(|r| r.load_path);
    let (x, against, scale) = if load_path { ("load factor", "load factor", 1.0) } else { ("time [ms]", "time", 1e3) };
    let mut out = Vec::new();
    for ProbeCurve { probe, points } in curves {
        let moving: Vec<usize> = (0..3)
            .filter(|&k| {
                rows.iter().any(|r| {
                    &r.probe == probe
                        && r.quantity == Quantity::Displacement(k).name()
                        && r.max_difference_percent.is_some()
                })
            })
            .collect();
        let moving = if moving.is_empty() { vec![0, 1, 2] } else { moving };
        let mut series = Vec::new();
        for k in moving {
            let name = Quantity::Displacement(k).name();
            let curve = |pick: fn(&HistoryPoint) -> [f64; 3]| {
                std::iter::once((0.0, 0.0)).chain(points.iter().map(|p| (p.1 * scale, pick(p)[k] * 1e3))).collect()
            };
            series.push(Series { name: format!("cufem {name}"), points: curve(|p| p.2), dashed: false });
            series.push(Series { name: format!("CalculiX 3D {name}"), points: curve(|p| p.3), dashed: true });
        }
        out.push(Plot {
            name: format!("probe_history_{probe}"),
            title: format!("{probe}: displacement against {against}"),
            x: x.into(),
            y: "displacement [mm]".into(),
            series,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_linearly_in_time_and_stops_at_the_last_increment() {
        let h = [(0.0, [0.0; 3]), (1.0, [0.0, 2.0, 0.0]), (3.0, [0.0, 6.0, 0.0])];
        assert_eq!(at_time(&h, 0.5), Some([0.0, 1.0, 0.0]));
        assert_eq!(at_time(&h, 2.0), Some([0.0, 4.0, 0.0]));
        assert_eq!(at_time(&h, 3.0), Some([0.0, 6.0, 0.0]));
        // within the 6 digits of the .frd times: the last increment
        assert_eq!(at_time(&h, 3.00001), Some([0.0, 6.0, 0.0]));
        assert_eq!(at_time(&h, 3.1), None);
        assert_eq!(at_time(&[], 1.0), None);
    }
}
