//! `cufem verify`: a model's results against a 3D solid model of the same
//! problem in CalculiX, at the same points.
//!
//! Probes and line stations are located once in the CUF mesh; cufem samples
//! its fields there ([`cufem::post`]) and the 3D fields are interpolated at
//! the same points inside the hexahedra that subdivide the CUF elements
//! ([`crate::sample`]). Differences are given in % of the 3D value; a
//! value below 1e-3 of its scale (the largest displacement or von Mises
//! stress of the 3D model) has no meaningful relative difference and is
//! reported as such. Along lines the difference is in % of the line's 3D
//! peak. Resultants compare the reactions of every constraint and the force
//! of every indenter. Over the whole field ([`field`]): relative L2 and
//! largest differences of the displacement, von Mises stress and peeq over
//! each body, its plastic zone and its contact surfaces, singular places
//! left out by a stated neighbourhood, and a VTU of the point-wise
//! differences. Over the load path ([`history`]): each indenter's force at
//! every CalculiX increment (up to and past a peak), and with nonlinear
//! geometry each probe's displacement at every cufem increment
//! ([`transient`]). A modal model
//! ([`modal`]) compares its natural frequencies mode by mode instead, since
//! its static state is the unloaded one; a transient model ([`transient`])
//! the displacement history at its probes, since its state changes in time.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::{CcxRun, HexMesh, deck::set_name};
use cufem::analysis::Solution;
use cufem::io::IoError;
use cufem::io::csv_field as csv_text;
use cufem::quantity::{Quantity, Sample};
use cufem::setup::Model;

pub mod field;
pub mod history;
pub mod impact;
pub mod modal;
mod page;
pub mod transient;

pub use field::{FieldComparison, FieldRow, SingularZone, StoredError, compare_stored, compare_stored_on};
pub use history::{ForceCurve, ForceHistoryRow};
pub use modal::ModeRow;
pub use transient::{ProbeCurve, ProbeHistoryRow};

/// One probe value, both ways.
#[derive(Debug, Clone, Serialize)]
pub struct ProbeRow {
    /// Probe name.
    pub probe: String,
    /// Quantity name (`u_z`, `s_yy`, …).
    pub quantity: String,
    /// cufem (SI).
    pub cufem: f64,
    /// CalculiX (SI).
    pub ccx: f64,
    /// `100 (cufem − 3D) / 3D`, `None` where the 3D value is ≈ 0.
    pub difference_percent: Option<f64>,
}

/// One line and quantity.
#[derive(Debug, Clone, Serialize)]
pub struct LineRow {
    /// Line name.
    pub line: String,
    /// Quantity name.
    pub quantity: String,
    /// Largest `|cufem − 3D|` in % of the line's 3D peak.
    pub max_difference_percent: f64,
    /// Distance along the line where it occurs (m).
    pub at: f64,
    /// The 3D peak `max |value|` (SI).
    pub peak: f64,
    /// Mean `|cufem − 3D|` in % of the peak.
    pub mean_difference_percent: f64,
}

/// A resultant force, both ways.
#[derive(Debug, Clone, Serialize)]
pub struct ResultantRow {
    /// Constraint or indenter name.
    pub name: String,
    /// `"reaction"` or `"indenter"`.
    pub kind: &'static str,
    /// cufem (N).
    pub cufem: [f64; 3],
    /// CalculiX (N).
    pub ccx: [f64; 3],
    /// `100 |cufem − 3D| / |3D|` (vector norms), `None` if the 3D force is ≈ 0.
    pub difference_percent: Option<f64>,
}

/// The cost of both analyses.
#[derive(Debug, Clone, Serialize)]
pub struct Cost {
    /// cufem degrees of freedom.
    pub cufem_dof: usize,
    /// 3D degrees of freedom (3 per body node).
    pub ccx_dof: usize,
    /// cufem wall time (s).
    pub cufem_time_s: f64,
    /// ccx wall time (s).
    pub ccx_time_s: f64,
    /// cufem peak memory (bytes).
    pub cufem_peak_bytes: Option<u64>,
    /// ccx peak memory (bytes).
    pub ccx_peak_bytes: Option<u64>,
}

/// The whole comparison.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Model title.
    pub title: String,
    /// Solid element and refinement of the 3D model.
    pub solid: String,
    /// Probe values.
    pub probes: Vec<ProbeRow>,
    /// Lines.
    pub lines: Vec<LineRow>,
    /// Resultants.
    pub resultants: Vec<ResultantRow>,
    /// Whole-field norms per body, plastic zone and contact surface.
    pub fields: Vec<FieldRow>,
    /// The neighbourhoods of singular places left out of `fields`.
    pub excluded: Vec<SingularZone>,
    /// Indenter force histories over the CalculiX increments.
    pub force_histories: Vec<ForceHistoryRow>,
    /// Their curves (written by [`Self::write`]).
    #[serde(skip)]
    pub force_curves: Vec<ForceCurve>,
    /// Natural frequencies mode by mode (a modal model; it has no static rows).
    pub modes: Vec<ModeRow>,
    /// Displacement histories at the probes: in time (a transient model;
    /// it has no static rows) or along the load factor (a static model
    /// with nonlinear geometry, beside its static rows).
    pub probe_histories: Vec<ProbeHistoryRow>,
    /// Their curves (written by [`Self::write`]).
    #[serde(skip)]
    pub probe_curves: Vec<ProbeCurve>,
    /// Rigid impactors' motion, force and energy left (a transient model).
    pub impacts: Vec<impact::ImpactRow>,
    /// Their curves (written by [`Self::write`]).
    #[serde(skip)]
    pub impact_curves: Vec<impact::ImpactCurve>,
    /// DOF, time and memory of both.
    pub cost: Cost,
}

/// One line overlay: line name, quantity and `(s, cufem, ccx)` samples.
pub type Curve = (String, Quantity, Vec<(f64, f64, f64)>);

fn quantities(model: &Model) -> Vec<Quantity> {
    let plastic = model.materials.iter().any(|m| m.is_plastic());
    Quantity::all()
        .into_iter()
        .filter(|q| !matches!(q, Quantity::Strain(_)) && (plastic || *q != Quantity::Peeq))
        .collect()
}

use cufem::bc::symmetry;

/// The reactions and indenter forces against CalculiX's.
fn resultant_rows(model: &Model, solution: &Solution, run: &CcxRun) -> Vec<ResultantRow> {
    let mut resultants = Vec::new();
    // a resultant below 1e-6 of the largest one is round-off (a symmetry plane's reaction)
    let force_scale = run.totals.values().map(|t| norm(t.0)).fold(0.0f64, f64::max);
    let mut push = |name: &str, kind: &'static str, ours: [f64; 3], set: String| {
        if let Some((theirs, _)) = run.totals.get(&set) {
            let d = [ours[0] - theirs[0], ours[1] - theirs[1], ours[2] - theirs[2]];
            let big = norm(*theirs);
            resultants.push(ResultantRow {
                name: name.to_string(),
                kind,
                cufem: ours,
                ccx: *theirs,
                difference_percent: (big > 1e-6 * force_scale).then(|| 100.0 * norm(d) / big),
            });
        }
    };
    // a symmetry plane's reaction is internal to the full structure (and
    // CalculiX's RF at its nodes holds their contact forces): not compared
    let sym = &model.symmetry;
    for r in solution.reactions.iter().filter(|r| sym.planes.is_empty() || sym.across.iter().any(|(n, _)| n == &r.name))
    {
        push(&r.name, "reaction", r.force, set_name("C", &r.name));
    }
    for c in solution.contacts.iter().filter(|c| c.kind == cufem::analysis::ContactKind::Indenter) {
        push(&c.name, "indenter", c.force, set_name("REF", &c.name));
    }
    resultants
}

fn ccx_sample(model: &Model, mesh: &HexMesh, run: &CcxRun, locations: &[cufem::values::Location]) -> Option<Sample> {
    let (u, stress, peeq) = crate::sample(model, mesh, &run.results, locations)?;
    Some(Sample { u, stress, von_mises: cufem::voigt::von_mises(&stress), peeq, ..Default::default() })
}

/// Length of a vector.
fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn percent(ours: f64, reference: f64, scale: f64) -> Option<f64> {
    (reference.abs() > 1e-3 * scale).then(|| 100.0 * (ours - reference) / reference.abs())
}

/// A transient model's rows: the probes' and the impactors' histories.
fn transient_comparison(
    model: &Model,
    solution: &Solution,
    mesh: &HexMesh,
    run: &CcxRun,
    empty: Comparison,
) -> Comparison {
    let (probe_histories, probe_curves) = transient::compare_probe_histories(model, solution, mesh, run);
    let (impacts, impact_curves) = impact::compare_impacts(model, solution, run);
    Comparison { probe_histories, probe_curves, impacts, impact_curves, ..empty }
}

/// Compares `solution` with the CalculiX run on `mesh`: the table, the
/// line overlays and the sample points of the whole-field comparison.
pub fn compare(
    model: &Model,
    solution: &Solution,
    mesh: &HexMesh,
    run: &CcxRun,
    cufem_peak: Option<u64>,
) -> (Comparison, Vec<Curve>, FieldComparison) {
    let solid = format!("{} × refine {}", mesh.kind.name(), mesh.refine);
    let cost = cost(model, solution, mesh, run, cufem_peak);
    if model.modal.is_some() {
        let modes = modal::compare_modes(model, solution, mesh, run);
        return (Comparison { modes, ..Comparison::empty(model, solid, cost) }, Vec::new(), FieldComparison::default());
    }
    if model.transient.is_some() {
        let comparison = transient_comparison(model, solution, mesh, run, Comparison::empty(model, solid, cost));
        return (comparison, Vec::new(), FieldComparison::default());
    }
    let view = solution.fields(model);
    let u_scale = run.results.u.values().flat_map(|u| u.iter()).fold(0.0f64, |a, b| a.max(b.abs()));
    let s_scale = run.results.stress.values().map(cufem::voigt::von_mises).fold(0.0f64, f64::max);
    let scale = |q: Quantity| match q {
        Quantity::Displacement(_) => u_scale,
        Quantity::Peeq => run.results.peeq.values().fold(0.0f64, |a, b| a.max(*b)),
        _ => s_scale,
    };
    let qs = quantities(model);
    let planes = &model.symmetry.planes;
    let mut probes = Vec::new();
    for p in &model.probes {
        let theirs = symmetry::sample(planes, p.point, |_| ccx_sample(model, mesh, run, &p.locations));
        let (Some(ours), Some(theirs)) = (view.sample_probe(p), theirs) else {
            continue;
        };
        for &q in &qs {
            let (a, b) = (ours.get(q), theirs.get(q));
            probes.push(ProbeRow {
                probe: p.name.clone(),
                quantity: q.name(),
                cufem: a,
                ccx: b,
                difference_percent: percent(a, b, scale(q)),
            });
        }
    }
    let mut lines = Vec::new();
    let mut curves = Vec::new();
    for l in &model.lines {
        let len = (0..3).map(|k| (l.to[k] - l.from[k]).powi(2)).sum::<f64>().sqrt();
        let stations: Vec<(f64, Sample, Sample)> = (0..l.points)
            .filter_map(|i| {
                let t = i as f64 / (l.points - 1) as f64;
                let x = [0, 1, 2].map(|k| l.from[k] + t * (l.to[k] - l.from[k]));
                // beyond a symmetry plane or on it: both sides as bc::symmetry::sample
                let locs = cufem::values::locate_in_model(&model.mesh, l.body, symmetry::image(planes, x).0);
                let ours = symmetry::sample(planes, x, |_| view.sample_at(&locs))?;
                Some((t * len, ours, symmetry::sample(planes, x, |_| ccx_sample(model, mesh, run, &locs))?))
            })
            .collect();
        let wanted: Vec<Quantity> = if l.plot.is_empty() { qs.clone() } else { l.plot.clone() };
        // the 3D twin has no failure indices: a plotted one is not compared
        for q in wanted.into_iter().filter(|q| !matches!(q, Quantity::Failure(_))) {
            let peak = stations.iter().map(|s| s.2.get(q).abs()).fold(0.0f64, f64::max);
            if stations.is_empty() {
                continue;
            }
            let diffs: Vec<f64> = stations
                .iter()
                .map(|s| if peak > 0.0 { 100.0 * (s.1.get(q) - s.2.get(q)).abs() / peak } else { 0.0 })
                .collect();
            let (k, max) = diffs.iter().enumerate().fold((0, 0.0f64), |m, (k, d)| if *d > m.1 { (k, *d) } else { m });
            lines.push(LineRow {
                line: l.name.clone(),
                quantity: q.name(),
                max_difference_percent: max,
                at: stations[k].0,
                peak,
                mean_difference_percent: diffs.iter().sum::<f64>() / diffs.len() as f64,
            });
            curves.push((l.name.clone(), q, stations.iter().map(|s| (s.0, s.1.get(q), s.2.get(q))).collect()));
        }
    }
    let resultants = resultant_rows(model, solution, run);
    let whole = field::compare_fields(model, &view, mesh, run);
    let (force_histories, force_curves) = history::compare_histories(model, solution, run);
    // with nonlinear geometry, the probes along the load path too
    let (probe_histories, probe_curves) = transient::compare_probe_histories(model, solution, mesh, run);
    let comparison = Comparison {
        probe_histories,
        probe_curves,
        probes,
        lines,
        resultants,
        fields: whole.rows.clone(),
        excluded: whole.zones.clone(),
        force_histories,
        force_curves,
        ..Comparison::empty(model, solid, cost)
    };
    (comparison, curves, whole)
}

/// DOF, wall time and peak memory of both analyses.
fn cost(model: &Model, solution: &Solution, mesh: &HexMesh, run: &CcxRun, cufem_peak: Option<u64>) -> Cost {
    let body_nodes: usize = (0..model.mesh.bodies.len()).map(|b| mesh.body_nodes(b).len()).sum();
    Cost {
        cufem_dof: model.n_dofs(),
        ccx_dof: 3 * body_nodes,
        cufem_time_s: solution.wall_time.as_secs_f64(),
        ccx_time_s: run.wall_time.as_secs_f64(),
        cufem_peak_bytes: cufem_peak,
        ccx_peak_bytes: run.peak_memory,
    }
}

fn show(v: Option<f64>) -> String {
    v.map_or_else(|| "(≈ 0)".to_string(), |d| format!("{d:+.2} %"))
}

impl Comparison {
    /// A comparison without rows, for a modal model (its frequencies only,
    /// since its static state is the unloaded one) or a transient one (its
    /// probe histories only): nothing to compare at one state's probes,
    /// lines, resultants or over its field; a static comparison fills in
    /// its own.
    fn empty(model: &Model, solid: String, cost: Cost) -> Self {
        Self {
            title: model.title.clone(),
            solid,
            probes: Vec::new(),
            lines: Vec::new(),
            resultants: Vec::new(),
            fields: Vec::new(),
            excluded: Vec::new(),
            force_histories: Vec::new(),
            force_curves: Vec::new(),
            modes: Vec::new(),
            probe_histories: Vec::new(),
            probe_curves: Vec::new(),
            impacts: Vec::new(),
            impact_curves: Vec::new(),
            cost,
        }
    }

    /// The table as text.
    pub fn table(&self) -> String {
        let mut t = String::new();
        let c = &self.cost;
        let _ = writeln!(t, "{} — cufem against CalculiX ({})", self.title, self.solid);
        // a reused 3D run without its recorded cost (`--ccx-results`) has no time
        let ccx_time = if c.ccx_time_s > 0.0 {
            format!("{:.2} s (×{:.1})", c.ccx_time_s, c.ccx_time_s / c.cufem_time_s.max(1e-9))
        } else {
            "? s".to_string()
        };
        let _ = writeln!(
            t,
            "DOF {} vs {} ({:.1} %), wall time {:.2} s vs {}, peak memory {} vs {}",
            c.cufem_dof,
            c.ccx_dof,
            100.0 * c.cufem_dof as f64 / c.ccx_dof.max(1) as f64,
            c.cufem_time_s,
            ccx_time,
            c.cufem_peak_bytes.map_or("?".into(), cufem::size::human_bytes),
            c.ccx_peak_bytes.map_or("?".into(), cufem::size::human_bytes),
        );
        if !self.resultants.is_empty() {
            let _ =
                writeln!(t, "\n{:<18} {:<9} {:>38} {:>38} {:>10}", "resultant", "kind", "cufem [N]", "3D [N]", "diff");
            for r in &self.resultants {
                let f = |v: [f64; 3]| format!("[{:.4e}, {:.4e}, {:.4e}]", v[0], v[1], v[2]);
                let _ = writeln!(
                    t,
                    "{:<18} {:<9} {:>38} {:>38} {:>10}",
                    r.name,
                    r.kind,
                    f(r.cufem),
                    f(r.ccx),
                    show(r.difference_percent)
                );
            }
        }
        if !self.probes.is_empty() {
            let _ = writeln!(t, "\n{:<16} {:<10} {:>14} {:>14} {:>10}", "probe", "quantity", "cufem", "3D", "diff");
            for p in &self.probes {
                let q = Quantity::parse(&p.quantity).unwrap_or(Quantity::VonMises);
                let s = q.display_scale();
                let _ = writeln!(
                    t,
                    "{:<16} {:<10} {:>14.5} {:>14.5} {:>10}",
                    p.probe,
                    q.label(),
                    p.cufem * s,
                    p.ccx * s,
                    show(p.difference_percent)
                );
            }
        }
        if !self.lines.is_empty() {
            let _ = writeln!(
                t,
                "\n{:<16} {:<10} {:>14} {:>12} {:>14} {:>14}",
                "line", "quantity", "3D peak", "max diff", "at [mm]", "mean diff"
            );
            for l in &self.lines {
                let q = Quantity::parse(&l.quantity).unwrap_or(Quantity::VonMises);
                let _ = writeln!(
                    t,
                    "{:<16} {:<10} {:>14.5} {:>11.2}% {:>14.2} {:>13.2}%",
                    l.line,
                    l.quantity,
                    l.peak * q.display_scale(),
                    l.max_difference_percent,
                    l.at * 1e3,
                    l.mean_difference_percent
                );
            }
        }
        self.field_table(&mut t);
        history::table(&self.force_histories, &mut t);
        modal::table(&self.modes, &mut t);
        transient::table(&self.probe_histories, &mut t);
        impact::table(&self.impacts, &mut t);
        t
    }

    /// The whole-field rows of [`Comparison::table`].
    fn field_table(&self, t: &mut String) {
        if self.fields.is_empty() {
            return;
        }
        let _ = writeln!(
            t,
            "\n{:<32} {:<10} {:>8} {:>9} {:>9} {:>10}  max at [mm]",
            "whole field", "quantity", "points", "excluded", "L2 diff", "max diff"
        );
        for r in &self.fields {
            let _ = writeln!(
                t,
                "{:<32} {:<10} {:>8} {:>9} {:>8.2}% {:>9.2}%  ({:.2}, {:.2}, {:.2})",
                r.region,
                r.quantity,
                r.points,
                r.excluded,
                r.l2_percent,
                r.max_percent,
                r.at[0] * 1e3,
                r.at[1] * 1e3,
                r.at[2] * 1e3
            );
        }
        for z in &self.excluded {
            let _ = writeln!(
                t,
                "excluded: {} points within {:.2} mm (one 3D element) of {} ({})",
                z.points,
                z.distance * 1e3,
                z.place,
                z.indenter
            );
        }
        let _ = writeln!(
            t,
            "(max diff: % of the body's largest 3D value; plastic zone: peeq above {} of the largest 3D peeq)",
            field::PLASTIC_ZONE
        );
    }

    /// Writes `table.txt`, `table.csv`, `table.json`, the whole-field
    /// differences (`field_difference.vtu`, [`FieldComparison::write_vtu`]) and, per line and
    /// quantity, the overlay plot and its numbers (`line_<name>_<q>.csv`:
    /// distance along the line in m, cufem and CalculiX values in SI units)
    /// into `dir`; returns the files written.
    pub fn write(&self, dir: &Path, curves: &[Curve], whole: &FieldComparison) -> Result<Vec<PathBuf>, IoError> {
        let file = |p: &Path, text: &str| std::fs::write(p, text).map_err(|e| cufem::io::file_error(p, e));
        std::fs::create_dir_all(dir).map_err(|e| cufem::io::file_error(dir, e))?;
        let mut written = Vec::new();
        let p = dir.join("table.txt");
        file(&p, &self.table())?;
        written.push(p);
        let mut csv = String::from("kind,name,quantity,cufem,ccx,difference_percent\n");
        for r in &self.resultants {
            for k in 0..3 {
                let _ = writeln!(
                    csv,
                    "{},{},f_{},{:e},{:e},{}",
                    csv_text(r.kind),
                    csv_text(&r.name),
                    ["x", "y", "z"][k],
                    r.cufem[k],
                    r.ccx[k],
                    r.difference_percent.map_or(String::new(), |d| format!("{d:e}"))
                );
            }
        }
        for p in &self.probes {
            let _ = writeln!(
                csv,
                "probe,{},{},{:e},{:e},{}",
                csv_text(&p.probe),
                csv_text(&p.quantity),
                p.cufem,
                p.ccx,
                p.difference_percent.map_or(String::new(), |d| format!("{d:e}"))
            );
        }
        for l in &self.lines {
            let _ =
                writeln!(csv, "line,{},{},,,{:e}", csv_text(&l.line), csv_text(&l.quantity), l.max_difference_percent);
        }
        for r in &self.fields {
            let _ = writeln!(csv, "field_l2,{},{},,,{:e}", csv_text(&r.region), csv_text(&r.quantity), r.l2_percent);
            let _ = writeln!(csv, "field_max,{},{},,,{:e}", csv_text(&r.region), csv_text(&r.quantity), r.max_percent);
        }
        modal::csv(&self.modes, &mut csv);
        transient::csv(&self.probe_histories, &mut csv);
        impact::csv(&self.impacts, &mut csv);
        let p = dir.join("table.csv");
        file(&p, &csv)?;
        written.push(p);
        let p = dir.join("table.json");
        file(&p, &serde_json::to_string_pretty(self).unwrap_or_default())?;
        written.push(p);
        // a modal model compares no static field
        if !whole.points.is_empty() {
            let p = dir.join("field_difference.vtu");
            whole.write_vtu(&p, &self.title)?;
            written.push(p);
            let p = dir.join("field_points.csv");
            file(&p, &whole.points_csv())?;
            written.push(p);
        }
        for ((line, q, points), plot) in curves.iter().zip(page::line_plots(&self.solid, curves)) {
            written.push(plot.write_png(dir)?);
            // the numbers behind the plot, for any other comparison
            let p = dir.join(format!("line_{line}_{}.csv", q.name()));
            let mut csv = format!("s,cufem_{0},ccx_{0}\n", q.name());
            for (s, a, b) in points {
                let _ = writeln!(csv, "{s:e},{a:e},{b:e}");
            }
            file(&p, &csv)?;
            written.push(p);
        }
        written.extend(history::write(dir, &self.force_curves)?);
        written.extend(transient::write(dir, &self.probe_histories, &self.probe_curves)?);
        written.extend(impact::write(dir, &self.impact_curves)?);
        Ok(written)
    }
}
