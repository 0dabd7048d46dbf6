//! The comparison as a section of the run's `report.html`
//! ([`cufem::io::add_section`]): the table as printed, its rows as tables
//! and every overlay the verify folder plots as a chart, from the same
//! numbers (the line, force, probe and impact curves, the frequencies).

use serde_json::{Value, json};

use super::{Comparison, Curve, history, impact, modal, transient};
use cufem::io::{Plot, Section, SectionTable, Series};
use cufem::quantity::Quantity;

/// The overlay of each line and quantity (`line_<name>_<q>`): both
/// values along the line (mm), in display units.
pub(super) fn line_plots(solid: &str, curves: &[Curve]) -> Vec<Plot> {
    curves
        .iter()
        .map(|(line, q, points)| {
            let along = |pick: fn(&(f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
                points.iter().map(|p| (p.0 * 1e3, pick(p) * q.display_scale())).collect()
            };
            Plot {
                name: format!("line_{line}_{}", q.name()),
                title: format!("{} along {line}: cufem and 3D", q.label().split(" [").next().unwrap_or_default()),
                x: "distance along the line [mm]".into(),
                y: q.label(),
                series: vec![
                    Series { name: "cufem (CUF 1D)".into(), points: along(|p| p.1), dashed: false },
                    Series { name: format!("CalculiX ({solid})"), points: along(|p| p.2), dashed: true },
                ],
            }
        })
        .collect()
}

/// `v`, or `null` for none.
fn opt(v: Option<f64>) -> Value {
    v.map_or(Value::Null, |v| json!(v))
}

impl Comparison {
    /// The comparison as a section of the run's page.
    pub fn section(&self, curves: &[Curve]) -> Section {
        let mut tables = Vec::new();
        let mut push = |title: &str, columns: &[&str], rows: Vec<Vec<Value>>| {
            if !rows.is_empty() {
                let columns = columns.iter().map(|c| c.to_string()).collect();
                tables.push(SectionTable { title: title.into(), columns, rows });
            }
        };
        push(
            "whole field: cufem against CalculiX at every sample point (max diff: % of the body's largest 3D value)",
            &["region", "quantity", "points", "excluded", "L2 diff [%]", "max diff [%]", "max at x, y, z [mm]"],
            self.fields
                .iter()
                .map(|r| {
                    let at = r.at.map(|c| format!("{:.2}", c * 1e3)).join(", ");
                    let (points, excluded) = (json!(r.points), json!(r.excluded));
                    let (l2, max) = (json!(r.l2_percent), json!(r.max_percent));
                    vec![json!(r.region), json!(r.quantity), points, excluded, l2, max, json!(at)]
                })
                .collect(),
        );
        let display = |q: &str| Quantity::parse(q).map_or((q.to_string(), 1.0), |q| (q.label(), q.display_scale()));
        push(
            "probes",
            &["probe", "quantity", "cufem", "CalculiX", "diff [%]"],
            self.probes
                .iter()
                .map(|p| {
                    let (label, s) = display(&p.quantity);
                    vec![json!(p.probe), json!(label), json!(p.cufem * s), json!(p.ccx * s), opt(p.difference_percent)]
                })
                .collect(),
        );
        push(
            "lines (differences in % of the line's 3D peak)",
            &["line", "quantity", "3D peak", "max diff [%]", "at [mm]", "mean diff [%]"],
            self.lines
                .iter()
                .map(|l| {
                    let (_, s) = display(&l.quantity);
                    vec![
                        json!(l.line),
                        json!(l.quantity),
                        json!(l.peak * s),
                        json!(l.max_difference_percent),
                        json!(l.at * 1e3),
                        json!(l.mean_difference_percent),
                    ]
                })
                .collect(),
        );
        push(
            "resultants [N]",
            &["name", "kind", "cufem", "CalculiX", "diff [%]"],
            self.resultants
                .iter()
                .map(|r| {
                    let v = |f: [f64; 3]| format!("[{:.4e}, {:.4e}, {:.4e}]", f[0], f[1], f[2]);
                    vec![json!(r.name), json!(r.kind), json!(v(r.cufem)), json!(v(r.ccx)), opt(r.difference_percent)]
                })
                .collect(),
        );
        push(
            "natural frequencies (modes paired by their MAC)",
            &["mode", "cufem [Hz]", "3D mode", "3D [Hz]", "diff [%]", "MAC"],
            self.modes
                .iter()
                .map(|r| {
                    let m = r.ccx_mode.map_or(Value::Null, |m| json!(m));
                    vec![json!(r.mode), json!(r.cufem_hz), m, opt(r.ccx_hz), opt(r.difference_percent), opt(r.mac)]
                })
                .collect(),
        );
        let mut plots = line_plots(&self.solid, curves);
        plots.extend(history::plots(&self.force_curves));
        plots.extend(transient::plots(&self.probe_histories, &self.probe_curves));
        plots.extend(impact::plots(&self.impact_curves));
        plots.extend(modal::plot(&self.modes));
        Section { title: format!("Verification against CalculiX ({})", self.solid), text: self.table(), tables, plots }
    }
}
