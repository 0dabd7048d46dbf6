//! Sections added to a written `report.html` after the run: `cufem
//! verify`'s comparison with CalculiX (its table as printed, its rows as
//! tables and its overlay plots as charts). The page's data gains a
//! `sections` entry; the page draws it after the warnings.

use std::path::Path;

use serde_json::{Value, json};

use crate::analysis::tables::Column;
use crate::analysis::{Adaptivity, ModeQuantity};
use crate::io::png::Series;
use crate::io::{IoError, file_error};

/// A plot of curves sampled at their own abscissae (the PNG
/// `io::png::line_plot` draws, and the page's chart of it).
#[derive(Debug, Clone)]
pub struct Plot {
    /// Its name: the PNG's file name without `.png`.
    pub name: String,
    /// Title.
    pub title: String,
    /// Label of the x axis (with its display unit).
    pub x: String,
    /// Label of the y axis (with its display unit).
    pub y: String,
    /// The curves.
    pub series: Vec<Series>,
}

impl Plot {
    /// Draws it as `<dir>/<name>.png`; returns the path.
    pub fn write_png(&self, dir: &Path) -> Result<std::path::PathBuf, IoError> {
        let p = dir.join(format!("{}.png", self.name));
        crate::io::png::line_plot(&p, &self.title, &self.x, &self.y, &self.series)?;
        Ok(p)
    }
}

/// A table of a section: named columns, rows of numbers (shown to 4
/// significant digits) or text (`null`: no value).
#[derive(Debug, Clone)]
pub struct SectionTable {
    /// Title.
    pub title: String,
    /// Column headers (with their units).
    pub columns: Vec<String>,
    /// Rows, one value per column.
    pub rows: Vec<Vec<Value>>,
}

/// A section of the page.
#[derive(Debug, Clone)]
pub struct Section {
    /// Its heading.
    pub title: String,
    /// Preformatted text (a table as the CLI prints it).
    pub text: String,
    /// Its tables.
    pub tables: Vec<SectionTable>,
    /// Its charts.
    pub plots: Vec<Plot>,
}

impl Section {
    /// The section as the page's data holds it.
    pub(crate) fn data(&self) -> Value {
        let plots: Vec<Value> = self
            .plots
            .iter()
            .map(|p| {
                let series: Vec<Value> = p
                    .series
                    .iter()
                    .map(|s| {
                        let (x, y): (Vec<f64>, Vec<f64>) = s.points.iter().copied().unzip();
                        json!({"label": s.name, "dashed": s.dashed, "x": x, "y": y})
                    })
                    .collect();
                json!({"name": p.name, "title": p.title, "x": p.x, "y": p.y, "series": series})
            })
            .collect();
        let tables: Vec<Value> =
            self.tables.iter().map(|t| json!({"title": t.title, "columns": t.columns, "rows": t.rows})).collect();
        json!({"title": self.title, "text": self.text, "tables": tables, "plots": plots})
    }
}

/// The section of an adaptive run (`cufem run --adapt`): every cycle's
/// DOF, estimate, time and refinement, its probes' values (a table per
/// probe, a row per cycle), and the estimate against the DOF.
pub(crate) fn adapt(a: &Adaptivity) -> Section {
    let cycles = SectionTable {
        title: "cycles".into(),
        columns: ["cycle", "DOF", "estimate [%]", "time [s]", "refined"].map(String::from).to_vec(),
        rows: a
            .cycles
            .iter()
            .map(|c| {
                // as the console prints them
                let (estimate, time) = ((1e4 * c.estimate).round() / 100.0, (10.0 * c.time_s).round() / 10.0);
                vec![json!(c.cycle), json!(c.dof), json!(estimate), json!(time), json!(c.refined)]
            })
            .collect(),
    };
    let mut tables = vec![cycles];
    // a modal (buckling) run's: each followed mode's frequency (critical
    // load factor) and estimated error per cycle
    let first = a.cycles.first().and_then(|c| c.modes.as_ref()).filter(|m| !m.errors.is_empty());
    if let Some(first) = first {
        let (followed, what) = (first.errors.len(), first.quantity.name());
        let (symbol, unit) = match first.quantity {
            ModeQuantity::LoadFactor => ("μ", ""),
            ModeQuantity::Frequency => ("f", " [Hz]"),
        };
        let columns =
            (1..=followed).flat_map(|k| [format!("{symbol}{k}{unit}"), format!("{symbol}{k} est. error [%]")]);
        tables.push(SectionTable {
            title: format!("modes followed: {what} and its estimated error, cycle by cycle"),
            columns: ["cycle", "DOF"].into_iter().map(String::from).chain(columns).collect(),
            rows: a
                .cycles
                .iter()
                .map(|c| {
                    let m = c.modes.as_ref();
                    let modes = (0..followed).flat_map(|k| {
                        let value = m.and_then(|m| m.values.get(k));
                        [json!(value), json!(m.and_then(|m| m.errors.get(k)).map(|e| 100.0 * e))]
                    });
                    [json!(c.cycle), json!(c.dof)].into_iter().chain(modes).collect()
                })
                .collect(),
        });
    }
    let first = a.cycles.first().map(|c| &c.probes);
    for (p, name) in first.and_then(|t| t.text("probe")).unwrap_or_default().iter().enumerate() {
        let columns: Vec<&Column> = first.map_or(Vec::new(), |t| t.columns.iter().skip(4).collect());
        let columns = without_round_off(columns, &a.cycles, p);
        tables.push(SectionTable {
            title: format!("probe {name}: its values cycle by cycle (SI units)"),
            columns: ["cycle", "DOF"]
                .into_iter()
                .map(String::from)
                .chain(columns.iter().map(|c| c.name.clone()))
                .collect(),
            rows: a
                .cycles
                .iter()
                .map(|c| {
                    let values = columns
                        .iter()
                        .map(|col| c.probes.column(&col.name).map_or(Value::Null, |v| json!(v.values.get(p))));
                    [json!(c.cycle), json!(c.dof)].into_iter().chain(values).collect()
                })
                .collect(),
        });
    }
    let estimate = Series {
        name: "estimate [%]".into(),
        points: a.cycles.iter().map(|c| (c.dof as f64, 100.0 * c.estimate)).collect(),
        dashed: false,
    };
    Section {
        title: format!("Adaptive refinement: {} cycles", a.cycles.len()),
        text: format!(
            "until the estimate is below {:.2} %, at most {} DOF; stopped: {}. The last cycle's mesh is written \
             beside these results as a model file, adapted.toml.",
            100.0 * a.tolerance,
            crate::numbers::thousands(a.max_dof),
            a.stop
        ),
        tables,
        plots: vec![Plot {
            name: "adapt".into(),
            title: estimate_title(a),
            x: "DOF".into(),
            y: "estimate [%]".into(),
            series: vec![estimate],
        }],
    }
}

/// The title of an adaptive run's estimate chart, by what the estimate
/// measures: the energy norm, or of a
/// modal (buckling) run the largest relative error of the followed modes'
/// frequencies (critical load factors; model-format.md, `[adapt]`).
fn estimate_title(a: &Adaptivity) -> String {
    match a.cycles.first().and_then(|c| c.modes.as_ref()) {
        Some(m) => format!("largest estimated {} error of the followed modes against DOF", m.quantity.name()),
        None => "estimated error (energy norm) against DOF".into(),
    }
}

/// The marker of the page's data.
const DATA: &str = "id=\"cufem-data\">";

/// The probe columns of `p` that are not round-off in every cycle: a
/// column whose values stay below `1e-9` of the largest of its unit (u_y of
/// a beam bent in x–z, `1.7e-19` m beside `5.7e-4` m) filled the table
/// past the page (a new-user review).
fn without_round_off<'a>(
    columns: Vec<&'a Column>,
    cycles: &[crate::analysis::AdaptCycle],
    p: usize,
) -> Vec<&'a Column> {
    let largest = |c: &Column| {
        cycles
            .iter()
            .filter_map(|cy| cy.probes.column(&c.name).map(|v| v.values.get(p).abs()))
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max)
    };
    let size: Vec<f64> = columns.iter().map(|c| largest(c)).collect();
    let of_unit = |u: &str| columns.iter().zip(&size).filter(|(c, _)| c.unit == u).map(|(_, &s)| s).fold(0.0, f64::max);
    columns.iter().zip(&size).filter(|(c, s)| **s > 1e-9 * of_unit(c.unit)).map(|(c, _)| *c).collect()
}

/// Adds `section` to the report.html at `path` (written by the run), in
/// place: its data gains the section, the rest of the page is unchanged.
pub fn add_section(path: &Path, section: &Section) -> Result<(), IoError> {
    let bad = |what: &str| file_error(path, std::io::Error::new(std::io::ErrorKind::InvalidData, what.to_string()));
    let html = std::fs::read_to_string(path).map_err(|e| file_error(path, e))?;
    let start = html.find(DATA).ok_or_else(|| bad("not a cufem report.html: no data"))? + DATA.len();
    let end = start + html[start..].find("</script>").ok_or_else(|| bad("not a cufem report.html: data not closed"))?;
    let mut data: Value = serde_json::from_str(&html[start..end]).map_err(|e| bad(&e.to_string()))?;
    let entry = section.data();
    match data.get_mut("sections").and_then(Value::as_array_mut) {
        Some(list) => list.push(entry),
        None => data["sections"] = json!([entry]),
    }
    // `<` escaped so that no text in the data can close the script element
    let text = data.to_string().replace('<', "\\u003c");
    let page = format!("{}{text}{}", &html[..start], &html[end..]);
    std::fs::write(path, page).map_err(|e| file_error(path, e))
}
