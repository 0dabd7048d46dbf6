//! Force histories, both ways: each indenter's force on the body at every
//! increment CalculiX printed (its reference node's `RF`, `*NODE PRINT`)
//! against cufem's history at the same load factor — the
//! force–displacement curve of a crushing or bending test, up to and past
//! its peak, not only its end point.
//!
//! CalculiX's step time is the load factor (the deck's step runs from 0 to
//! 1 with the loads ramped), so cufem's force is interpolated linearly in λ
//! between its converged increments (from 0 at λ = 0). The curve of a
//! moving indenter is its force along its motion, `F = f·d̂` (`d̂` the unit
//! direction of its displacement; positive when it pushes), against its
//! displacement — the force–displacement curve of a test machine; that of
//! a support (no motion) is `F = ‖f‖` against the load factor. The
//! difference is in % of the 3D peak,
//!
//! ```text
//! max_t |F_cufem(t) − F_3D(t)| / max_t F_3D(t) ,
//! ```
//!
//! and the two peaks are reported with where they occur.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::{CcxRun, deck::set_name};
use cufem::analysis::Solution;
use cufem::io::{IoError, Plot, Series};
use cufem::setup::Model;

/// One indenter's force history, both ways.
#[derive(Debug, Clone, Serialize)]
pub struct ForceHistoryRow {
    /// Indenter name.
    pub name: String,
    /// CalculiX increments compared.
    pub points: usize,
    /// Largest `F` of cufem's curve (N) and the indenter's displacement
    /// along its motion there (m; the load factor for a support).
    pub cufem_peak: (f64, f64),
    /// The same of the 3D curve.
    pub ccx_peak: (f64, f64),
    /// `100 (F_peak,cufem − F_peak,3D) / F_peak,3D`.
    pub peak_difference_percent: f64,
    /// Largest `|F_cufem − F_3D|` over the increments, in % of the 3D peak.
    pub max_difference_percent: f64,
    /// Displacement along the motion (m; the load factor for a support)
    /// where it occurs.
    pub at: f64,
    /// The indenter moves (`at` in m) or is a support (`at` is λ).
    pub moving: bool,
}

/// A point of a force curve: `(λ, x, cufem force (N), 3D force (N))`.
pub type CurvePoint = (f64, f64, [f64; 3], [f64; 3]);

/// One indenter's curve, per CalculiX increment.
#[derive(Debug, Clone)]
pub struct ForceCurve {
    /// Indenter name.
    pub name: String,
    /// The indenter moves: `x` is its displacement along the motion (m);
    /// otherwise the load factor.
    pub moving: bool,
    /// Unit direction of the motion (zero for a support).
    pub direction: [f64; 3],
    /// The points, in the 3D increments' order.
    pub points: Vec<CurvePoint>,
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// cufem's force of contact set `name` at load factor `lambda`, linear
/// between converged increments (0 at λ = 0); `None` beyond its last.
fn cufem_force(solution: &Solution, name: &str, lambda: f64) -> Option<[f64; 3]> {
    let mut last = (0.0, [0.0; 3]);
    for row in &solution.history {
        let f = row.contact(name)?.force;
        if row.lambda >= lambda - 1e-12 {
            let w = if row.lambda > last.0 { (lambda - last.0) / (row.lambda - last.0) } else { 1.0 };
            return Some(std::array::from_fn(|k| last.1[k] + w * (f[k] - last.1[k])));
        }
        last = (row.lambda, f);
    }
    None
}

/// The force histories of the model's indenters with more than one
/// CalculiX increment (none for a linear model solved in one).
pub fn compare_histories(model: &Model, solution: &Solution, run: &CcxRun) -> (Vec<ForceHistoryRow>, Vec<ForceCurve>) {
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    for ind in &model.indenters {
        let Some(theirs) = run.histories.get(&set_name("REF", &ind.name)) else { continue };
        let length = norm(ind.displacement);
        let moving = length > 0.0;
        // a support's curve is drawn against the load factor
        let along = |lambda: f64| if moving { lambda * length } else { lambda };
        let measure = |f: [f64; 3]| {
            if moving { (0..3).map(|k| f[k] * ind.displacement[k]).sum::<f64>() / length } else { norm(f) }
        };
        let curve: Vec<CurvePoint> = theirs
            .iter()
            .filter(|(t, _)| *t > 0.0)
            .filter_map(|&(t, f)| Some((t, along(t), cufem_force(solution, &ind.name, t)?, f)))
            .collect();
        if curve.len() < 2 {
            continue;
        }
        let peak = |pick: fn(&CurvePoint) -> [f64; 3]| {
            curve.iter().map(|c| (measure(pick(c)), c.1)).fold((0.0, 0.0), |m, p| if p.0 > m.0 { p } else { m })
        };
        let (ours, reference) = (peak(|c| c.2), peak(|c| c.3));
        if reference.0 <= 0.0 {
            continue;
        }
        let (at, max) = curve
            .iter()
            .map(|c| (c.1, 100.0 * (measure(c.2) - measure(c.3)).abs() / reference.0))
            .fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
        rows.push(ForceHistoryRow {
            name: ind.name.clone(),
            points: curve.len(),
            cufem_peak: ours,
            ccx_peak: reference,
            peak_difference_percent: 100.0 * (ours.0 - reference.0) / reference.0,
            max_difference_percent: max,
            at,
            moving,
        });
        curves.push(ForceCurve {
            name: ind.name.clone(),
            moving,
            direction: ind.displacement.map(|v| v / length.max(f64::MIN_POSITIVE)),
            points: curve,
        });
    }
    (rows, curves)
}

/// The rows of the verification table.
pub fn table(rows: &[ForceHistoryRow], t: &mut String) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        t,
        "\n{:<20} {:>6} {:>14} {:>14} {:>9} {:>9}  at [mm or λ]",
        "force history", "points", "cufem peak [N]", "3D peak [N]", "peak diff", "max diff"
    );
    for r in rows {
        let _ = writeln!(
            t,
            "{:<20} {:>6} {:>14.2} {:>14.2} {:>8.2}% {:>8.2}%  {:.3}",
            r.name,
            r.points,
            r.cufem_peak.0,
            r.ccx_peak.0,
            r.peak_difference_percent,
            r.max_difference_percent,
            if r.moving { r.at * 1e3 } else { r.at }
        );
    }
    let _ = writeln!(
        t,
        "(force along the motion against the displacement, ‖f‖ against λ for a support; \
         max diff: largest |F_cufem − F_3D| over the 3D increments, % of the 3D peak)"
    );
}

/// Writes `history_<indenter>.csv` (`lambda,d,f_x,f_y,f_z,ccx_f_x,ccx_f_y,ccx_f_z`:
/// load factor, displacement along the motion in m (0 for a support),
/// forces on the body in N) and `history_<indenter>.png` (the force along
/// the motion against the displacement, or ‖f‖ against the load factor for
/// a support, both curves) into `dir`.
pub fn write(dir: &Path, curves: &[ForceCurve]) -> Result<Vec<PathBuf>, IoError> {
    let mut written = Vec::new();
    for (ForceCurve { name, moving, points: curve, .. }, plot) in curves.iter().zip(plots(curves)) {
        let mut csv = String::from("lambda,d,f_x,f_y,f_z,ccx_f_x,ccx_f_y,ccx_f_z\n");
        for (l, d, a, b) in curve {
            let d = if *moving { *d } else { 0.0 };
            let _ = writeln!(csv, "{l:e},{d:e},{:e},{:e},{:e},{:e},{:e},{:e}", a[0], a[1], a[2], b[0], b[1], b[2]);
        }
        let p = dir.join(format!("history_{name}.csv"));
        std::fs::write(&p, csv).map_err(|e| cufem::io::file_error(&p, e))?;
        written.push(p);
        written.push(plot.write_png(dir)?);
    }
    Ok(written)
}

/// The plot of each curve (`history_<indenter>`): the force along the
/// motion against the displacement (mm), or ‖f‖ against the load factor
/// for a support, both ways, from 0.
pub fn plots(curves: &[ForceCurve]) -> Vec<Plot> {
    curves
        .iter()
        .map(|ForceCurve { name, moving, direction, points: curve }| {
            let measure = |f: [f64; 3]| if *moving { (0..3).map(|k| f[k] * direction[k]).sum() } else { norm(f) };
            let scale = if *moving { 1e3 } else { 1.0 };
            let series = |label: &str, pick: fn(&CurvePoint) -> [f64; 3], dashed| Series {
                name: label.to_string(),
                points: std::iter::once((0.0, 0.0))
                    .chain(curve.iter().map(|c| (c.1 * scale, measure(pick(c)))))
                    .collect(),
                dashed,
            };
            Plot {
                name: format!("history_{name}"),
                title: format!("{name}: force against {}", if *moving { "displacement" } else { "load factor" }),
                x: if *moving { "displacement [mm]" } else { "load factor" }.into(),
                y: "force [N]".into(),
                series: vec![series("cufem", |c| c.2, false), series("CalculiX 3D", |c| c.3, true)],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::results::read_dat_history;

    /// Every printed increment of a set is kept, in order, with its time.
    #[test]
    fn reads_every_increment_of_a_set() {
        let dat = " forces (fx,fy,fz) for set REF_LOAD and time  0.5000000E+00\n\n     \
                   7  1.0E+00  2.0E+00 -3.0E+00\n\n \
                   forces (fx,fy,fz) for set REF_LOAD and time  0.1000000E+01\n\n     \
                   7  2.0E+00  4.0E+00 -6.0E+00\n";
        let h = read_dat_history(dat);
        assert_eq!(h["REF_LOAD"], vec![(0.5, [1.0, 2.0, -3.0]), (1.0, [2.0, 4.0, -6.0])]);
    }
}
