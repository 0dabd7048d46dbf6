//! PNG line plots (plotters, bitmap backend, embedded DejaVu Sans font).

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::IoError;
use crate::analysis::Solution;
use crate::model::Model;

/// One curve of a plot.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// `(x, y)` points in display units.
    pub points: Vec<(f64, f64)>,
}

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        // The font is compiled in, so registration cannot fail on user input.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            include_bytes!("../../assets/fonts/DejaVuSans.ttf"),
        );
    });
}

fn plot_error(path: &Path, e: impl std::fmt::Display) -> IoError {
    IoError::Plot { path: path.display().to_string(), message: e.to_string() }
}

/// Draws `series` as lines with markers into a 1000×640 PNG.
pub fn line_plot(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<(), IoError> {
    register_font();
    let all = series.iter().flat_map(|s| s.points.iter()).filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 <= 0.0 {
        x1 = x0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0).abs().max(1e-12 * y1.abs().max(1.0));
    let (y0, y1) = (y0 - pad, y1 + pad);

    let root = BitMapBackend::new(path, (1000, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(18)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 16))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (k, s) in series.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(s.points.iter().copied(), colour.stroke_width(2)))
            .map_err(|e| plot_error(path, e))?
            .label(s.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        if s.points.len() <= 60 {
            chart
                .draw_series(s.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| plot_error(path, e))?;
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    root.present().map_err(|e| plot_error(path, e))?;
    Ok(())
}

/// Force–displacement curve of every indenter: the force the indenter
/// applies along its direction of motion against its displacement.
pub fn history_plots(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut out = Vec::new();
    for (k, ind) in model.indenters.iter().enumerate() {
        let d = ind.displacement;
        let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if norm == 0.0 {
            continue;
        }
        let dir_unit = d.map(|v| v / norm);
        let mut points = vec![(0.0, 0.0)];
        points.extend(solution.history.iter().map(|row| {
            let f = row.contact[k].0;
            (row.lambda * norm * 1e3, f[0] * dir_unit[0] + f[1] * dir_unit[1] + f[2] * dir_unit[2])
        }));
        let path = dir.join(format!("history_{}.png", ind.name));
        line_plot(
            &path,
            &format!("Indenter {}: force against displacement", ind.name),
            "indenter displacement [mm]",
            "force along the motion [N]",
            &[Series { name: "cufem".into(), points }],
        )?;
        out.push(path);
    }
    Ok(out)
}
