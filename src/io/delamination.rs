//! `delamination.png`: the delaminated area of a transient run's cohesive
//! interfaces against time (the history's `delaminated_area`,
//! [`crate::analysis::HistoryRow::delaminated_m2`]).

use std::path::{Path, PathBuf};

use super::IoError;
use super::png::{Series, line_plot};
use crate::analysis::Solution;
use crate::setup::Model;

/// Writes the plot for a transient run with interfaces and plots on
/// (nothing for another): the area in mm² against the time in ms, one
/// point per converged time step.
pub(crate) fn write_delamination_plot(
    model: &Model,
    solution: &Solution,
    dir: &Path,
) -> Result<Option<PathBuf>, IoError> {
    let Some(clock) = model.transient.as_ref().filter(|_| model.output.plots) else { return Ok(None) };
    let points: Vec<(f64, f64)> = solution
        .history
        .iter()
        .filter_map(|r| r.delaminated_m2.map(|a| (1e3 * clock.time(r.lambda), 1e6 * a)))
        .collect();
    if points.is_empty() {
        return Ok(None);
    }
    let path = dir.join("delamination.png");
    let series = [Series { name: "delaminated area (d = 1)".into(), points, dashed: false }];
    line_plot(&path, "delaminated area", "time [ms]", "area [mm²]", &series)?;
    Ok(Some(path))
}
