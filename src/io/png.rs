//! PNG line plots (plotters, bitmap backend, embedded DejaVu Sans font).

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::IoError;
use crate::analysis::tables::Table;
use crate::setup::Line;
use crate::setup::Model;

/// One curve of a plot.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// `(x, y)` points in display units.
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed (e.g. a reference solution beside ours).
    pub dashed: bool,
}

static FONT: Once = Once::new();

pub(super) fn register_font() {
    FONT.call_once(|| {
        // The font is compiled in, so registration cannot fail on user input.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            include_bytes!("../../assets/fonts/DejaVuSans.ttf"),
        );
    });
}

pub(super) fn plot_error(path: &Path, e: impl std::fmt::Display) -> IoError {
    IoError::Plot { path: path.display().to_string(), message: e.to_string() }
}

/// Largest magnitude drawn on an axis: beyond it the padded range or the
/// tick spacing can overflow (a range of ±∞ once made the tick generator
/// loop forever).
const MAX_AXIS: f64 = 1e200;

/// Padded axis range of the finite values of magnitude ≤ [`MAX_AXIS`]:
/// 5 % of the data span on each side, at least a relative 1e-9 of the
/// values (a constant curve), and `[0, 1]` without data. Values smaller
/// than 1e-200 in magnitude are treated as zero so the span never falls
/// into subnormal numbers.
fn axis_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && v.abs() <= MAX_AXIS) {
        let v = if v.abs() < 1.0 / MAX_AXIS { 0.0 } else { v };
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    let scale = lo.abs().max(hi.abs());
    let pad = (0.05 * (hi - lo)).max(1e-9 * scale).max(if scale == 0.0 { 1.0 } else { 0.0 });
    (lo - pad, hi + pad)
}

/// Text as drawn on a plot: control characters (which a font has no glyph
/// for, a line break included: captions are one line) as visible `\u{7}`.
pub(super) fn printable(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if c.is_control() {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    out
}

/// Draws `series` as lines with markers into a 1000×640 PNG.
pub(crate) fn line_plot(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), IoError> {
    register_font();
    let (title, x_label, y_label) = (printable(title), printable(x_label), printable(y_label));
    let (x0, x1) = axis_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let (y0, y1) = axis_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    // points that cannot be drawn are left out rather than derailing the axes
    let drawable = |p: &(f64, f64)| (x0..=x1).contains(&p.0) && (y0..=y1).contains(&p.1);

    let root = BitMapBackend::new(path, (1000, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(&title, ("sans-serif", 22))
        .margin(18)
        .x_label_area_size(50)
        .y_label_area_size(100)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .x_desc(&x_label)
        .y_desc(&y_label)
        .label_style(("sans-serif", 16))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    for (k, s) in series.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let points = s.points.iter().copied().filter(drawable);
        let drawn = if s.dashed {
            chart.draw_series(DashedLineSeries::new(points, 8, 5, colour.stroke_width(2)))
        } else {
            chart.draw_series(LineSeries::new(points, colour.stroke_width(2)))
        };
        drawn
            .map_err(|e| plot_error(path, e))?
            .label(printable(&s.name))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        if s.points.len() <= 60 && !s.dashed {
            chart
                .draw_series(s.points.iter().copied().filter(drawable).map(|p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| plot_error(path, e))?;
        }
    }
    draw_legend(&mut chart, path)?;
    root.present().map_err(|e| plot_error(path, e))?;
    Ok(())
}

/// The legend of every labelled series, in the plots' one style.
pub(super) fn draw_legend<'a, 'b: 'a>(
    chart: &mut ChartContext<
        'a,
        BitMapBackend<'b>,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    path: &Path,
) -> Result<(), IoError> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()
        .map_err(|e| plot_error(path, e))
}

/// `line_<name>_<quantity>.png`: the quantities listed in a line's `plot`
/// along it, from its table ([`tables::line`]).
pub(crate) fn line_plots(line: &Line, table: &Table, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut out = Vec::new();
    let s = table.real("s").unwrap_or_default();
    for &q in &line.plot {
        let values = table.real(&q.name()).unwrap_or_default();
        let points = s.iter().zip(&values).map(|(s, v)| (s * 1e3, v * q.display_scale())).collect();
        let path = dir.join(format!("line_{}_{}.png", line.name, q.name()));
        let title = format!(
            "{} along {} ({:?} → {:?} m)",
            q.label().split(" [").next().unwrap_or_default(),
            line.name,
            line.from,
            line.to
        );
        let series = [Series { name: "cufem".into(), points, dashed: false }];
        line_plot(&path, &title, "distance along the line [mm]", &q.label(), &series)?;
        out.push(path);
    }
    Ok(out)
}

/// Force–displacement curve of every indenter: the force the indenter
/// applies along its direction of motion against its displacement, from
/// its history table ([`tables::contact_history`]); in a model cut by
/// symmetry planes the force on the full structure (as summary.json's
/// `full_structure_force`), the one to compare.
pub(crate) fn history_plots(model: &Model, histories: &[Table], dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut out = Vec::new();
    for ind in &model.indenters {
        // the direction of motion: the prescribed displacement, the force,
        // or an impactor's velocity (whose force is drawn against time: an
        // impactor had no plot; a new-user review)
        let impactor = ind.impactor.filter(|_| ind.force.is_none() && ind.displacement == [0.0; 3]);
        let d = impactor.map_or(ind.force.unwrap_or(ind.displacement), |i| i.velocity);
        let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if norm == 0.0 {
            continue;
        }
        let dir_unit = d.map(|v| v / norm);
        let along = |v: [f64; 3]| v[0] * dir_unit[0] + v[1] * dir_unit[1] + v[2] * dir_unit[2];
        let table = histories.iter().find(|t| t.name == format!("history_{}", ind.name));
        let full = model.symmetry.full(&ind.name, [0.0; 3]).is_some();
        let force = if full { "full_f_" } else { "f_" };
        let vectors = |prefix: &str| -> Vec<[f64; 3]> {
            let Some(t) = table else { return Vec::new() };
            let [x, y, z] = ["x", "y", "z"].map(|a| t.real(&format!("{prefix}{a}")).unwrap_or_default());
            (0..x.len()).map(|i| [x[i], y[i], z[i]]).collect()
        };
        let mut points = vec![(0.0, 0.0)];
        let abscissa: Vec<f64> = match (impactor, table) {
            (Some(_), Some(t)) => t.real("time").unwrap_or_default().iter().map(|t| t * 1e3).collect(),
            _ => vectors("d_").into_iter().map(|d| along(d) * 1e3).collect(),
        };
        points.extend(abscissa.into_iter().zip(vectors(force)).map(|(x, f)| (x, along(f))));
        // short tick labels keep the axis label clear of them
        let largest = points.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let (unit, scale) = match largest {
            f if f >= 1e6 => ("MN", 1e-6),
            f if f >= 1e3 => ("kN", 1e-3),
            _ => ("N", 1.0),
        };
        for p in &mut points {
            p.1 *= scale;
        }
        let path = dir.join(format!("history_{}.png", ind.name));
        let (title, abscissa) = match impactor {
            Some(_) => (format!("Impactor {}: contact force against time", ind.name), "time [ms]"),
            None => (format!("Indenter {}: force against displacement", ind.name), "indenter displacement [mm]"),
        };
        line_plot(
            &path,
            &title,
            abscissa,
            &format!("force along the motion{} [{unit}]", if full { ", full structure" } else { "" }),
            &[Series { name: "cufem".into(), points, dashed: false }],
        )?;
        out.push(path);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 13, reproduction 1: values that overflow the padded range (and
    /// subnormal or constant ones) are drawn in bounded time.
    #[test]
    fn extreme_values_plot_in_bounded_time() {
        let dir = std::env::temp_dir().join(format!("cufem_png_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let cases: Vec<Vec<(f64, f64)>> = vec![
            vec![(0.0, -1e308), (1.0, 1e308)],
            vec![(0.0, 1e-310), (1.0, 2e-310)],
            vec![(0.0, f64::NAN), (1.0, f64::INFINITY)],
            vec![(0.0, 5.0), (1.0, 5.0)],
            vec![(1e300, 1.0), (1e300, 1.0)],
            vec![],
        ];
        for (k, points) in cases.into_iter().enumerate() {
            let path = dir.join(format!("p{k}.png"));
            let t = std::time::Instant::now();
            line_plot(&path, "t", "x", "y", &[Series { name: "s".into(), points, dashed: false }]).unwrap();
            assert!(t.elapsed().as_secs_f64() < 5.0, "case {k} took {:?}", t.elapsed());
            assert!(std::fs::metadata(&path).unwrap().len() > 0);
        }
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(axis_range([1e-310, 2e-310].into_iter()), (-1.0, 1.0));
        let (a, b) = axis_range([5.0, 5.0].into_iter());
        assert!(a < 5.0 && b > 5.0 && b - a < 1e-6);
    }

    /// Titles, labels and legends with control characters, markup and
    /// non-ASCII text are drawn (shown as `\u{7}`), never a failure or a panic.
    #[test]
    fn any_text_is_drawn() {
        let dir = std::env::temp_dir().join(format!("cufem_png_text_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.png");
        let text = "bell \u{7} nul \u{0} esc \u{1b}\nnew line \r\t <&> \"'--> ü 日本 \u{FFFF} \u{202E}";
        let points = vec![(0.0, 1.0), (1.0, 2.0)];
        line_plot(&path, text, text, text, &[Series { name: text.into(), points, dashed: false }]).unwrap();
        assert_eq!(&std::fs::read(&path).unwrap()[1..4], b"PNG");
        assert_eq!(printable("a\u{7}b\nc ü"), "a\\u{7}b\\u{a}c ü");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
