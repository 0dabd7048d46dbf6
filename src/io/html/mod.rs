//! `report.html`: one self-contained page per run, openable offline — the
//! model's description, the text the run printed ([`super::report`]: the
//! header, one line per converged increment, the tables), the warnings, a
//! zoomable chart of every history, line, energy and mode table the run
//! writes as CSV, and a 3D view of the deformed outer surface coloured by
//! any field of `result.vtu`, with a deformation scale and a slider over
//! the step ends or the frames of a transient run.
//!
//! The page inlines its scripts and data: the charts are drawn by uPlot and
//! the 3D view by three.js, both vendored at a pinned version with their
//! licences in `assets/vendor` (see its README for why these two), and the
//! page's own script and style are `assets/report/`. The data is one JSON
//! object (`<script type="application/json" id="cufem-data">`); the 3D
//! arrays in it are base64: vertex positions and displacements as
//! little-endian `f32`, each field quantized to 16 bits between its
//! minimum and maximum in the frame (65535: no value). Its size is bounded:
//! at most [`surface::MAX_VERTICES`] surface vertices (a larger surface is
//! decimated), [`MAX_FRAMES`] frames and about [`FRAME_BUDGET`] bytes of
//! frame data; the page states what it shows of how much.

mod section;
mod surface;

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use base64::Engine as _;
use serde_json::{Value, json};

use super::{FieldGrid, GridElement, IoError, Summary, file_error, report};
use crate::analysis::tables::{Table, Values};
use crate::analysis::{IncrementLog, Solution};
use crate::setup::Model;
pub use section::{Plot, Section, SectionTable, add_section};
use surface::Surface;

/// uPlot 1.6.32 (MIT): the charts.
const UPLOT_JS: &str = include_str!("../../../assets/vendor/uPlot-1.6.32.iife.min.js");
/// uPlot's style sheet.
const UPLOT_CSS: &str = include_str!("../../../assets/vendor/uPlot-1.6.32.min.css");
/// three.js r147 (MIT), its classic-script build: the 3D view.
const THREE_JS: &str = include_str!("../../../assets/vendor/three-0.147.0.min.js");
/// three.js r147's OrbitControls (classic script, `THREE.OrbitControls`).
const ORBIT_JS: &str = include_str!("../../../assets/vendor/three-0.147.0-OrbitControls.js");
/// The page's own script.
const SCRIPT: &str = include_str!("../../../assets/report/report.js");
/// The page's own style.
const STYLE: &str = include_str!("../../../assets/report/report.css");

/// The most frames the 3D view's slider carries; more are sampled evenly.
pub(crate) const MAX_FRAMES: usize = 60;
/// About the most bytes of 3D frame data (base64) a page carries: frames
/// beyond it are left out (the last state is always shown).
pub(crate) const FRAME_BUDGET: usize = 12 << 20;

/// Columns that count rather than measure, charted only in `history`.
const COUNTS: [&str; 3] = ["iterations", "plastic_points", "negative_pivots"];

/// The 3D view's data, gathered frame by frame while the run's files are
/// written (each frame's fields computed once, for its VTU and here).
#[derive(Debug, Default)]
pub(crate) struct View {
    surface: Option<Surface>,
    frames: Vec<Value>,
    /// The mode shapes of a modal or buckling run (displacement only).
    modes: Vec<Value>,
    /// The cell fields that no frame changes (`body`, `element`).
    cells: Vec<Value>,
    bytes: usize,
    skipped: usize,
    /// The time spent gathering the view's data.
    pub(crate) spent: std::time::Duration,
}

impl View {
    /// True if frame `k` of `n` is one the slider carries (evenly sampled
    /// down to [`MAX_FRAMES`]).
    pub(crate) fn wants(k: usize, n: usize) -> bool {
        k.is_multiple_of(n.div_ceil(MAX_FRAMES).max(1))
    }

    /// True if a state at `lambda` would be added (the frame budget not
    /// spent, or `last`: the run's end, always added unless already shown).
    pub(crate) fn takes(&self, lambda: f64, last: bool) -> bool {
        if last {
            // the run's end, already shown as the last step's end or frame
            return !self.frames.last().is_some_and(|f| f["lambda"] == json!(lambda));
        }
        let per_frame = self.frames.first().map_or(0, |_| self.bytes / self.frames.len());
        self.bytes + 2 * per_frame <= FRAME_BUDGET
    }

    /// Counts a state left out because [`View::takes`] refused it (the
    /// run's end, already shown, is not counted).
    pub(crate) fn skip(&mut self, last: bool) {
        self.skipped += usize::from(!last);
    }

    /// Adds the state `at` whose field grid is `grid` (one that
    /// [`View::takes`]): its point fields and its ply damage, the cell data
    /// `d_ft … d_mc` of its VTU on the points of each element.
    pub(crate) fn add_grid(&mut self, label: String, model: &Model, at: &Solution, grid: &FieldGrid) {
        let start = std::time::Instant::now();
        let surface = self.surface.get_or_insert_with(|| Surface::of(grid, surface::MAX_VERTICES));
        if self.cells.is_empty() {
            let of_element = |pick: fn(&GridElement) -> usize| per_point(grid, |_, e| pick(e) as f64);
            for (name, values) in [("body", of_element(|e| e.body)), ("element", of_element(|e| e.element))] {
                self.cells.push(scalar(surface, name, &values));
            }
        }
        let mut fields = Vec::new();
        let mut displacement = String::new();
        for a in &grid.point_data {
            if a.name == "displacement" {
                displacement = encode_f32(&surface.gather(&a.values, 3));
            } else if a.components == 1 {
                fields.push(scalar(surface, &a.name, &a.values));
            }
        }
        for (name, values) in damage_fields(model, at, grid) {
            fields.push(scalar(surface, name, &values));
        }
        self.bytes += displacement.len() + fields.iter().map(|f| f["data"].as_str().map_or(0, str::len)).sum::<usize>();
        self.frames.push(json!({"label": label, "lambda": at.lambda, "displacement": displacement, "fields": fields}));
        self.spent += start.elapsed();
    }

    /// True if a mode shape would be added (fewer than [`MAX_FRAMES`]
    /// shown and the frame budget not spent).
    pub(crate) fn takes_mode(&self) -> bool {
        let per_mode = self.modes.first().map_or(0, |m| m["displacement"].as_str().map_or(0, str::len));
        self.modes.len() < MAX_FRAMES && self.bytes + 2 * per_mode <= FRAME_BUDGET
    }

    /// Adds a mode shape (its displacement, as `mode_<k>.vtu` holds it),
    /// after the states (one that [`View::takes_mode`]).
    pub(crate) fn add_mode(&mut self, label: String, grid: &FieldGrid) {
        let start = std::time::Instant::now();
        let surface = self.surface.get_or_insert_with(|| Surface::of(grid, surface::MAX_VERTICES));
        if let Some(a) = grid.point_data.iter().find(|a| a.name == "displacement") {
            let displacement = encode_f32(&surface.gather(&a.values, 3));
            self.bytes += displacement.len();
            self.modes.push(json!({"label": label, "displacement": displacement, "fields": []}));
        }
        self.spent += start.elapsed();
    }

    /// The view as the page's data (`None` without frames).
    fn data(self) -> Option<Value> {
        let s = self.surface?;
        let note = format!(
            "outer surface of {} vertices{}; {} frame{}{}{}; field colours in 16-bit steps of each frame's range",
            s.vertices(),
            if s.full_vertices > s.vertices() {
                format!(
                    " (decimated from {} by vertex clustering: the 3D view carries at most {})",
                    s.full_vertices,
                    surface::MAX_VERTICES
                )
            } else {
                String::new()
            },
            self.frames.len(),
            if self.frames.len() == 1 { "" } else { "s" },
            if self.skipped > 0 {
                format!(" ({} more left out to bound the page's size)", self.skipped)
            } else {
                String::new()
            },
            match self.modes.len() {
                0 => String::new(),
                n => format!("; {n} mode shape{} (largest component 1)", if n == 1 { "" } else { "s" }),
            }
        );
        Some(json!({
            "bbox": s.bbox,
            "vertices": s.vertices(),
            "positions": encode_f32(&s.positions),
            "triangles": base64_le(s.triangles.iter().map(|t| t.to_le_bytes())),
            "note": note,
            "frames": self.frames,
            "modes": self.modes,
            "cells": self.cells,
        }))
    }
}

/// A scalar field at the surface's vertices, quantized, as the page holds it.
fn scalar(surface: &Surface, name: &str, values: &[f64]) -> Value {
    let (data, min, max) = quantize(&surface.gather(values, 1));
    json!({"name": name, "min": min, "max": max, "data": data})
}

/// A value per element of `grid` (from its index and itself) on each of
/// its points.
fn per_point(grid: &FieldGrid, value: impl Fn(usize, &GridElement) -> f64) -> Vec<f64> {
    let n = grid.points.len() / 3;
    let mut out = Vec::with_capacity(n);
    for (k, e) in grid.elements.iter().enumerate() {
        let end = grid.elements.get(k + 1).map_or(n, |next| next.first);
        out.resize(end, value(k, e));
    }
    out
}

/// The ply damage of `at` on the points of `grid` (none without it): for
/// each mode `d_ft d_fc d_mt d_mc`, its largest over the Gauss points of
/// the point's element, the cell data of the state's VTU.
fn damage_fields(model: &Model, at: &Solution, grid: &FieldGrid) -> Vec<(&'static str, Vec<f64>)> {
    let Some(damage) = &at.damage else {
        return Vec::new();
    };
    let largest: Vec<[f64; 4]> = grid
        .elements
        .iter()
        .map(|e| {
            let ngp = model.cells[e.body].gp_per_element();
            let first = at.gp_offsets[e.body] + (e.element - model.mesh.bodies[e.body].element_offset) * ngp;
            damage.largest_in(first..first + ngp)
        })
        .collect();
    ["d_ft", "d_fc", "d_mt", "d_mc"]
        .into_iter()
        .enumerate()
        .map(|(m, name)| (name, per_point(grid, |k, _| largest[k][m])))
        .collect()
}

/// Little-endian `f32`s in base64.
fn encode_f32(values: &[f32]) -> String {
    base64_le(values.iter().map(|v| v.to_le_bytes()))
}

/// Numbers given as their little-endian bytes, in base64 (the page's
/// typed arrays).
fn base64_le<const N: usize>(numbers: impl Iterator<Item = [u8; N]>) -> String {
    base64::engine::general_purpose::STANDARD.encode(numbers.flatten().collect::<Vec<u8>>())
}

/// Values as 16-bit steps between their finite minimum and maximum
/// (65535: NaN or infinite), in base64, with the minimum and maximum.
fn quantize(values: &[f32]) -> (String, f64, f64) {
    let finite = || values.iter().filter(|v| v.is_finite()).map(|&v| v as f64);
    let (min, max) = (finite().fold(f64::INFINITY, f64::min), finite().fold(f64::NEG_INFINITY, f64::max));
    let span = if max > min { max - min } else { 1.0 };
    let data = base64_le(values.iter().map(|&v| {
        let q = if v.is_finite() { ((v as f64 - min) / span * 65534.0).round() as u16 } else { u16::MAX };
        q.to_le_bytes()
    }));
    let (min, max) = if min <= max { (min, max) } else { (0.0, 0.0) };
    (data, min, max)
}

/// A table as a chart: `x` against every other numeric column but the
/// increment, λ when drawn against time (and the counts, but in `history`);
/// `None` without rows or without the column `x`.
fn chart(table: &Table, x: &str, title: &str) -> Option<Value> {
    let xc = table.column(x).filter(|_| table.rows() > 0)?;
    let mut series = Vec::new();
    // each column's SI unit (`Column::unit`), the abscissa's first: the page labels curves and axes with them
    let mut units = vec![xc.unit];
    let mut data = vec![xc.values.to_f64()];
    for c in &table.columns {
        let skip = c.name == x
            || c.name == "increment"
            || (x == "time" && c.name == "lambda")
            || matches!(c.values, Values::Text(_))
            || (table.name != "history" && COUNTS.contains(&c.name.as_str()));
        if !skip {
            series.push(table.header(c));
            units.push(c.unit);
            data.push(c.values.to_f64());
        }
    }
    Some(
        json!({"name": table.name, "title": title, "x": table.header(xc), "series": series, "units": units, "data": data}),
    )
}

/// The charts of a run's tables: histories against λ, lines along their
/// distance, the energy balance against time, modes by number.
fn charts(tables: &[&Table]) -> Vec<Value> {
    tables
        .iter()
        .filter_map(|t| {
            let n = t.name.as_str();
            match n {
                "energy" => chart(t, "time", "energy balance"),
                "modes" | "buckling" => chart(t, "mode", n),
                _ if n.starts_with("line_") => chart(t, "s", &format!("line {}", &n[5..])),
                // a transient run's histories against time (s), a static one's against λ
                _ if n.starts_with("history") || n == "error_history" => {
                    chart(t, if t.column("time").is_some() { "time" } else { "lambda" }, n)
                }
                _ => None,
            }
        })
        .collect()
}

/// The console line of every converged increment, as the run printed them
/// ([`report::increment_line`]), rebuilt from the solution's records.
fn increment_log(solution: &Solution) -> String {
    let mut text = String::new();
    for (inc, row) in solution.increments.iter().zip(&solution.history) {
        let log = IncrementLog {
            index: inc.index,
            lambda: inc.lambda,
            dlambda: inc.dlambda,
            iterations: inc.newton.iterations,
            residuals: inc.newton.residuals.clone(),
            plastic_points: row.plastic_points,
            cutbacks: inc.cutbacks,
            max_penetration: row.contacts.iter().map(|c| c.max_penetration).fold(0.0, f64::max),
            negative_pivots: row.negative_pivots,
        };
        let _ = writeln!(text, "{}", report::increment_line(&log));
    }
    text
}

/// The tables a page charts: the histories, the lines, and the energy,
/// mode and buckling tables a run has.
pub(crate) struct Tables<'a> {
    /// `history*` tables.
    pub histories: &'a [Table],
    /// `line_*` tables.
    pub lines: &'a [Table],
    /// The energy, modes and buckling tables (those the run has).
    pub others: &'a [Table],
}

/// Writes `<dir>/report.html` for `solution`; returns its path.
pub(crate) fn write(
    model: &Model,
    solution: &Solution,
    dir: &Path,
    summary: &Summary,
    tables: Tables<'_>,
    view: View,
) -> Result<PathBuf, IoError> {
    let all: Vec<&Table> = tables.histories.iter().chain(tables.lines).chain(tables.others).collect();
    let data = json!({
        "title": model.title,
        "description": model.description,
        "header": report::header(model),
        "log": increment_log(solution),
        "results": report::results(model, solution),
        "status": summary.status,
        "failure": summary.failure,
        "warnings": summary.warnings,
        "charts": charts(&all),
        "view": view.data(),
        "sections": solution.adapt.iter().map(|a| section::adapt(a).data()).collect::<Vec<_>>(),
    });
    // `<` escaped so that no text in the data can close the script element
    let data = data.to_string().replace('<', "\\u003c");
    let path = dir.join("report.html");
    let file = std::fs::File::create(&path).map_err(|e| file_error(&path, e))?;
    let mut w = std::io::BufWriter::new(file);
    let parts = [
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>cufem report</title>\n<style>\n",
        UPLOT_CSS,
        "\n",
        STYLE,
        "\n</style>\n</head>\n<body>\n<script>\n",
        UPLOT_JS,
        "\n</script>\n<script>\n",
        THREE_JS,
        "\n</script>\n<script>\n",
        ORBIT_JS,
        "\n</script>\n<script type=\"application/json\" id=\"cufem-data\">",
        &data,
        "</script>\n<script>\n",
        SCRIPT,
        "\n</script>\n</body>\n</html>\n",
    ];
    for part in parts {
        w.write_all(part.as_bytes()).map_err(|e| file_error(&path, e))?;
    }
    w.flush().map_err(|e| file_error(&path, e))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::tables::Column;

    /// 16-bit steps span the finite range: the minimum is 0, the maximum
    /// 65534, a NaN 65535; a constant field is all 0.
    #[test]
    fn fields_are_quantized_over_their_range() {
        let decode = |s: &str| -> Vec<u16> {
            let b = base64::engine::general_purpose::STANDARD.decode(s).unwrap();
            b.chunks(2).map(|c| u16::from_le_bytes([c[0], c[1]])).collect()
        };
        let (d, min, max) = quantize(&[2.0, f32::NAN, 4.0, 3.0]);
        assert_eq!((min, max), (2.0, 4.0));
        assert_eq!(decode(&d), vec![0, 65535, 65534, 32767]);
        let (d, min, max) = quantize(&[5.0, 5.0]);
        assert_eq!((decode(&d), min, max), (vec![0, 0], 5.0, 5.0));
    }

    /// A history is charted against λ with one series per measured column
    /// (the increment and the counts left out), `history` with its counts.
    #[test]
    fn charts_take_the_measured_columns() {
        let col = |name: &str, values| Column { name: name.into(), unit: "", values };
        let t = |name: &str| Table {
            name: name.into(),
            columns: vec![
                col("increment", Values::Count(vec![1, 2])),
                col("lambda", Values::Real(vec![0.5, 1.0])),
                col("iterations", Values::Count(vec![3, 4])),
                col("r_x", Values::Optional(vec![None, Some(2.0)])),
            ],
            units_in_header: false,
        };
        let (a, b) = (t("history_top"), t("history"));
        let c = charts(&[&a, &b]);
        assert_eq!(c[0]["series"], json!(["r_x"]));
        assert_eq!(c[0]["data"], json!([[0.5, 1.0], [null, 2.0]]));
        assert_eq!(c[1]["series"], json!(["iterations", "r_x"]));
    }
}
