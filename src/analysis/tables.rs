//! The result tables: every table of numbers a run writes (a CSV file, the
//! PNG plots drawn from it, the Python package's columns) built once from
//! the [`Solution`] as a typed [`Table`] of named columns with their units.
//! The writers only serialise them (`io::csv`, `io::png`, `io::energy`,
//! the Python package), so a column is named, ordered and computed in one
//! place.
//!
//! | table | file | rows |
//! |-------|------|------|
//! | [`line()`] | `line_<name>.csv` | a sample along a `[[lines]]` entry (outside every body left out) |
//! | [`constraint_history`] | `history_<constraint>.csv` | a converged increment |
//! | [`contact_history`] | `history_<contact>.csv` | a converged increment with that contact |
//! | `lever_history` | `history_<lever>.csv` | a converged increment |
//! | [`probe_history`] | `history_probes.csv` | a converged increment |
//! | `increment_history` | `history.csv` | a converged increment |
//! | [`contact_points`] | `contact_<name>.csv` | a point of a contact, final state |
//! | [`probes`] | summary.json's `probes`, the printed table, Python's `probe` | a probe, final state |
//! | [`energy`] | `energy.csv`, summary.json's `energy` (its last row) | a converged time step of a transient run |
//! | [`modes`] | `modes.csv` | a vibration mode: frequency, effective masses, estimated errors |
//! | [`buckling`] | `buckling.csv` | a buckling mode: load factor, critical load |
//! | [`error_history`] | `error_history.csv`, summary.json's `error_history` | a kept step end or frame: its estimated error |

use super::{ContactSet, LeverResultant, Solution};
use crate::post::{FieldView, LineSample, Quantity, Sample};
use crate::setup::Model;
use crate::setup::steps::{self, Item};

/// The values of a column.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Real numbers (a NaN is a value not recorded, e.g. a reaction missing
    /// from an increment).
    Real(Vec<f64>),
    /// Real numbers that do not exist in some rows (a component of a
    /// constraint that is not prescribed, the displacement of a pair
    /// contact): an empty CSV field, NaN in Python.
    Optional(Vec<Option<f64>>),
    /// Counts, indices and flags (0 or 1).
    Count(Vec<usize>),
    /// Counts not known in some rows (an empty CSV field, NaN in Python).
    OptionalCount(Vec<Option<usize>>),
    /// Text (a probe's name): a CSV field quoted when it must be, NaN as a
    /// number.
    Text(Vec<String>),
}

impl Values {
    /// Number of rows.
    pub fn len(&self) -> usize {
        match self {
            Self::Real(v) => v.len(),
            Self::Optional(v) => v.len(),
            Self::Count(v) => v.len(),
            Self::OptionalCount(v) => v.len(),
            Self::Text(v) => v.len(),
        }
    }

    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i` as a real number, NaN where absent or text.
    pub fn get(&self, i: usize) -> f64 {
        match self {
            Self::Real(v) => v[i],
            Self::Optional(v) => v[i].unwrap_or(f64::NAN),
            Self::Count(v) => v[i] as f64,
            Self::OptionalCount(v) => v[i].map_or(f64::NAN, |n| n as f64),
            Self::Text(_) => f64::NAN,
        }
    }

    /// Every row as a real number, NaN where absent (the Python package's
    /// columns).
    pub fn to_f64(&self) -> Vec<f64> {
        (0..self.len()).map(|i| self.get(i)).collect()
    }
}

/// A named column.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Name (the CSV header, the Python column name).
    pub name: String,
    /// SI unit of its values (`"m"`, `"N"`, `"J"`, `"s"`, `"Pa"`), `""`
    /// for counts and dimensionless values.
    pub unit: &'static str,
    /// Its values, one per row.
    pub values: Values,
}

/// A table of results: columns of equal length.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Its name: the stem of its CSV file (`history_clamp`, `energy`).
    pub name: String,
    /// The columns, in order.
    pub columns: Vec<Column>,
    /// Whether its CSV header names each column with its unit
    /// (`kinetic_J`: [`Table::header`]); the columns' own names are bare.
    pub(crate) units_in_header: bool,
}

impl Table {
    fn new(name: impl Into<String>) -> Self {
        Self { name: name.into(), columns: Vec::new(), units_in_header: false }
    }

    /// The CSV header of column `c`: its name, followed by `_<unit>` in a
    /// table with `Table::units_in_header` (`time` in s: `time_s`).
    pub fn header(&self, c: &Column) -> String {
        if self.units_in_header && !c.unit.is_empty() { format!("{}_{}", c.name, c.unit) } else { c.name.clone() }
    }

    fn push(&mut self, name: impl Into<String>, unit: &'static str, values: Values) {
        self.columns.push(Column { name: name.into(), unit, values });
    }

    /// Three columns `<prefix>x`, `<prefix>y`, `<prefix>z` of a vector per row.
    fn push_xyz(&mut self, prefix: &str, unit: &'static str, rows: &[[f64; 3]]) {
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            self.push(format!("{prefix}{axis}"), unit, Values::Real(rows.iter().map(|v| v[k]).collect()));
        }
    }

    /// Rows (0 without columns).
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.values.len())
    }

    /// The column `name`.
    pub fn column(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|c| c.name == name)
    }

    /// The values of column `name` as real numbers (NaN where absent), or
    /// `None` without such a column.
    pub fn real(&self, name: &str) -> Option<Vec<f64>> {
        self.column(name).map(|c| c.values.to_f64())
    }

    /// The values of text column `name`, or `None` without such a text
    /// column.
    pub fn text(&self, name: &str) -> Option<&[String]> {
        match &self.column(name)?.values {
            Values::Text(v) => Some(v),
            _ => None,
        }
    }

    /// Row `i` of column `name` as a real number, NaN without the column.
    pub fn at(&self, name: &str, i: usize) -> f64 {
        self.column(name).map_or(f64::NAN, |c| c.values.get(i))
    }

    /// Row `i`: every column but the text ones, as a real number.
    pub fn row(&self, i: usize) -> Row {
        self.row_scaled(i, |_| 1.0)
    }

    /// Row `i` as [`Table::row`], each column's value times `scale` of it
    /// (the energies of a model's mirror images).
    pub(crate) fn row_scaled(&self, i: usize, scale: impl Fn(&Column) -> f64) -> Row {
        let numbers = self.columns.iter().filter(|c| !matches!(c.values, Values::Text(_)));
        Row(numbers.map(|c| (c.name.clone(), scale(c) * c.values.get(i))).collect())
    }

    /// The columns `<prefix>x`, `<prefix>y`, `<prefix>z` together, a vector
    /// per row, or `None` without them.
    pub(crate) fn xyz(&self, prefix: &str) -> Option<Vec<[f64; 3]>> {
        let [x, y, z] = ["x", "y", "z"].map(|axis| self.real(&format!("{prefix}{axis}")));
        let (x, y, z) = (x?, y?, z?);
        Some((0..x.len()).map(|i| [x[i], y[i], z[i]]).collect())
    }
}

/// One row of a table: its name and value per column, in column order (a
/// row of [`probes`] in Python, the last row of [`energy`] in
/// summary.json, where it is an object of those keys).
#[derive(Debug, Clone, PartialEq)]
pub struct Row(pub Vec<(String, f64)>);

impl Row {
    /// The value of column `name`, or `None` without it.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.0.iter().find(|(n, _)| n == name).map(|&(_, v)| v)
    }
}

impl serde::Serialize for Row {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// `x, y, z` of each point and every quantity of the model there.
fn push_points(t: &mut Table, model: &Model, points: &[[f64; 3]], samples: &[Sample]) {
    t.push_xyz("", "m", points);
    for q in model.quantities() {
        t.push(q.name(), si_unit(q), Values::Real(samples.iter().map(|v| v.get(q)).collect()));
    }
}

/// `s, x, y, z` and every quantity of the model along a line, one row per
/// sample inside a body.
pub fn line(model: &Model, samples: &[LineSample]) -> Table {
    let inside: Vec<_> = samples.iter().filter_map(|s| s.sample.map(|v| (s, v))).collect();
    let mut t = Table::new("");
    t.push("s", "m", Values::Real(inside.iter().map(|(s, _)| s.s).collect()));
    let points: Vec<[f64; 3]> = inside.iter().map(|(s, _)| s.point).collect();
    let values: Vec<Sample> = inside.iter().map(|&(_, v)| v).collect();
    push_points(&mut t, model, &points, &values);
    t
}

/// `probes`: one row per probe of the model, sampled in `view` — its name
/// (`probe`), its point `x, y, z` and every quantity of the model there (0
/// where it cannot be sampled).
pub fn probes(model: &Model, view: &FieldView<'_>) -> Table {
    let mut t = Table::new("probes");
    t.push("probe", "", Values::Text(model.probes.iter().map(|p| p.name.clone()).collect()));
    let points: Vec<[f64; 3]> = model.probes.iter().map(|p| p.point).collect();
    let values: Vec<Sample> = model.probes.iter().map(|p| view.sample_probe(p).unwrap_or_default()).collect();
    push_points(&mut t, model, &points, &values);
    t
}

/// The table of line `k` of the model (`line_<name>`), sampled in `view`.
pub fn sampled_line(model: &Model, view: &FieldView<'_>, k: usize) -> Table {
    let l = &model.lines[k];
    let mut t = line(model, &crate::post::sample_line(view, l));
    t.name = format!("line_{}", l.name);
    t
}

/// `increment, lambda, iterations` of the rows kept, and in a transient
/// run of `model` the time of each (`time`, s, after `lambda`: what the
/// report's charts of a transient run are drawn against).
fn increments(model: &Model, rows: &[&super::HistoryRow], name: String) -> Table {
    let mut t = Table::new(name);
    t.push("increment", "", Values::Count(rows.iter().map(|r| r.increment).collect()));
    t.push("lambda", "", Values::Real(rows.iter().map(|r| r.lambda).collect()));
    if let Some(clock) = &model.transient {
        t.push("time", "s", Values::Real(rows.iter().map(|r| clock.time(r.lambda)).collect()));
    }
    t.push("iterations", "", Values::Count(rows.iter().map(|r| r.iterations).collect()));
    t
}

/// `history_<name>` of constraint set `ci`: its prescribed displacement
/// (absent for a free component) and its reaction (NaN where not recorded);
/// in a model with symmetry planes, when the set has a force on the full
/// structure (`bc::symmetry::Symmetry::full`), that force too (`full_r_*`).
pub fn constraint_history(model: &Model, solution: &Solution, ci: usize) -> Table {
    let c = &model.constraints[ci];
    let rows: Vec<_> = solution.history.iter().collect();
    let mut t = increments(model, &rows, format!("history_{}", c.name));
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let u = rows
            .iter()
            .map(|r| c.values[k].map(|v| steps::factor(&model.steps, Item::Constraint(ci), r.lambda) * v))
            .collect();
        t.push(format!("u_{axis}"), "m", Values::Optional(u));
    }
    let r: Vec<[f64; 3]> = rows.iter().map(|r| r.reaction(&c.name).map_or([f64::NAN; 3], |r| r.force)).collect();
    t.push_xyz("r_", "N", &r);
    if model.symmetry.full(&c.name, [0.0; 3]).is_some() {
        // no reaction recorded: NaN, not the plane's cancelled 0
        let full: Vec<[f64; 3]> = r
            .iter()
            .map(|&r| if r[0].is_nan() { r } else { model.symmetry.full(&c.name, r).unwrap_or([f64::NAN; 3]) })
            .collect();
        t.push_xyz("full_r_", "N", &full);
    }
    t
}

/// `history_<name>` of a contact: per increment with it, the indenter's
/// displacement (absent for a pair contact), the force, the largest
/// penetration, the plastic points, the magnitudes of the force's normal
/// and tangential parts, and in a model with symmetry planes the force on
/// the full structure (`full_f_*`).
pub fn contact_history(model: &Model, solution: &Solution, set: &ContactSet) -> Table {
    let name = &set.name;
    let is_indenter = model.indenters.iter().any(|i| &i.name == name);
    let (rows, contacts): (Vec<_>, Vec<_>) =
        solution.history.iter().filter_map(|r| r.contact(name).map(|c| (r, c))).unzip();
    let mut t = increments(model, &rows, format!("history_{name}"));
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let d = contacts.iter().map(|c| is_indenter.then_some(c.displacement[k])).collect();
        t.push(format!("d_{axis}"), "m", Values::Optional(d));
    }
    let f: Vec<[f64; 3]> = contacts.iter().map(|c| c.force).collect();
    t.push_xyz("f_", "N", &f);
    t.push("max_penetration", "m", Values::Real(contacts.iter().map(|c| c.max_penetration).collect()));
    t.push("plastic_points", "", Values::Count(rows.iter().map(|r| r.plastic_points).collect()));
    t.push("f_n", "N", Values::Real(contacts.iter().map(|c| norm(c.normal_force)).collect()));
    t.push("f_t", "N", Values::Real(contacts.iter().map(|c| norm(c.tangential_force)).collect()));
    if model.symmetry.full(name, [0.0; 3]).is_some() {
        let full: Vec<[f64; 3]> = f.iter().map(|&f| model.symmetry.full(name, f).unwrap_or([f64::NAN; 3])).collect();
        t.push_xyz("full_f_", "N", &full);
    }
    t
}

/// `history_<name>` of lever `li`: per increment its prescribed
/// displacement (`target`), its displacement `Σ a_d u_d` (`displacement`,
/// equal to the target once converged) and its force `P` (`force`).
pub(crate) fn lever_history(model: &Model, solution: &Solution, li: usize) -> Table {
    let lever = &model.levers[li];
    let rows: Vec<_> = solution.history.iter().collect();
    let mut t = increments(model, &rows, format!("history_{}", lever.name));
    let at = |r: &super::HistoryRow| -> Option<LeverResultant> { r.levers.get(li).cloned() };
    let target = rows.iter().map(|r| steps::factor(&model.steps, Item::Lever(li), r.lambda) * lever.value).collect();
    t.push("target", "m", Values::Real(target));
    t.push(
        "displacement",
        "m",
        Values::Real(rows.iter().map(|r| at(r).map_or(f64::NAN, |l| l.displacement)).collect()),
    );
    t.push("force", "N", Values::Real(rows.iter().map(|r| at(r).map_or(f64::NAN, |l| l.force)).collect()));
    t
}

/// `history_probes`: the displacement of every probe at every increment
/// (columns `<probe>.u_x`, `<probe>.u_y`, `<probe>.u_z`).
pub fn probe_history(model: &Model, solution: &Solution) -> Table {
    let rows: Vec<_> = solution.history.iter().collect();
    let mut t = increments(model, &rows, "history_probes".into());
    for (p, probe) in model.probes.iter().enumerate() {
        let u: Vec<[f64; 3]> = rows.iter().map(|r| r.probes[p]).collect();
        t.push_xyz(&format!("{}.u_", probe.name), "m", &u);
    }
    t
}

/// `history`: per converged increment, the load factor, Newton iterations,
/// plastic Gauss points and the negative pivots of the last factorized
/// tangent (absent when not known), which count the tangent's negative
/// eigenvalues: a change marks a limit or bifurcation point.
pub(crate) fn increment_history(model: &Model, solution: &Solution) -> Table {
    let rows: Vec<_> = solution.history.iter().collect();
    let mut t = increments(model, &rows, "history".into());
    t.push("plastic_points", "", Values::Count(rows.iter().map(|r| r.plastic_points).collect()));
    t.push("negative_pivots", "", Values::OptionalCount(rows.iter().map(|r| r.negative_pivots).collect()));
    // the extent of delamination and ply damage, in a model that has them
    if rows.iter().any(|r| r.delaminated_m2.is_some()) {
        t.push("delaminated_area", "m²", Values::Optional(rows.iter().map(|r| r.delaminated_m2).collect()));
    }
    if rows.iter().any(|r| r.damaged_volume_m3.is_some()) {
        for (k, mode) in crate::materials::damage::MODES.iter().enumerate() {
            let v = rows.iter().map(|r| r.damaged_volume_m3.map(|v| v[k])).collect();
            t.push(format!("damaged_volume_{mode}"), "m³", Values::Optional(v));
        }
    }
    t
}

/// Every history table of a solution, in the order of their files: each
/// constraint set, each contact, each lever, the probes (if any), the increments (if
/// any).
pub fn histories(model: &Model, solution: &Solution) -> Vec<Table> {
    let mut out: Vec<Table> = (0..model.constraints.len()).map(|ci| constraint_history(model, solution, ci)).collect();
    out.extend(solution.contact_sets.iter().map(|set| contact_history(model, solution, set)));
    out.extend((0..model.levers.len()).map(|li| lever_history(model, solution, li)));
    if !model.probes.is_empty() {
        out.push(probe_history(model, solution));
    }
    if !solution.history.is_empty() {
        out.push(increment_history(model, solution));
    }
    out
}

/// `contact_<name>`: the final state of every point of a contact — its
/// position, gap, force, tributary area, the normal and tangential parts of
/// the force per area (as the contact VTU), whether it is active, its slip
/// and whether it slides.
pub fn contact_points(model: &Model, set: &ContactSet) -> Table {
    let p = &set.points;
    let mut t = Table::new(format!("contact_{}", set.name));
    t.push("node", "", Values::Count(p.iter().map(|p| p.node).collect()));
    let x: Vec<[f64; 3]> = p.iter().map(|p| model.mesh.coords(p.node)).collect();
    t.push_xyz("", "m", &x);
    t.push("gap", "m", Values::Real(p.iter().map(|p| p.gap).collect()));
    let f: Vec<[f64; 3]> = p.iter().map(|p| p.force).collect();
    t.push_xyz("f_", "N", &f);
    t.push("area", "m^2", Values::Real(p.iter().map(|p| p.area).collect()));
    let f_n: Vec<f64> = p.iter().map(|p| (0..3).map(|k| p.force[k] * p.normal[k]).sum()).collect();
    let f_t: Vec<f64> = p
        .iter()
        .zip(&f_n)
        .map(|(p, f_n)| (0..3).map(|k| (p.force[k] - f_n * p.normal[k]).powi(2)).sum::<f64>().sqrt())
        .collect();
    t.push("pressure", "Pa", Values::Real(p.iter().zip(&f_n).map(|(p, f)| f / p.area).collect()));
    t.push("traction", "Pa", Values::Real(p.iter().zip(&f_t).map(|(p, f)| f / p.area).collect()));
    t.push("active", "", Values::Count(p.iter().map(|p| usize::from(p.active)).collect()));
    t.push("slip", "m", Values::Real(p.iter().map(|p| norm(p.slip)).collect()));
    t.push("sliding", "", Values::Count(p.iter().map(|p| usize::from(p.sliding)).collect()));
    t
}

/// `energy`: the energy balance of a transient run per converged time step
/// (`dynamics::energy`): `time` (s) and the energies (J), each CSV header
/// with its unit (`kinetic_J`); `None` for another analysis.
pub fn energy(solution: &Solution) -> Option<Table> {
    use crate::dynamics::energy::EnergyRow;
    let rows = solution.energy.as_ref()?;
    let mut t = Table::new("energy");
    t.units_in_header = true;
    // name, unit, value of a row
    type EnergyColumn = (&'static str, &'static str, fn(&EnergyRow) -> f64);
    let columns: [EnergyColumn; 11] = [
        ("time", "s", |r| r.time),
        ("kinetic", "J", |r| r.kinetic),
        ("internal", "J", |r| r.internal),
        ("elastic", "J", |r| r.elastic),
        ("plastic", "J", |r| r.plastic),
        ("damping", "J", |r| r.damping),
        ("external", "J", |r| r.external),
        ("contact", "J", |r| r.contact),
        ("supports", "J", |r| r.supports),
        ("balance", "J", |r| r.balance),
        ("impactors", "J", |r| r.impactors),
    ];
    // the interfaces' columns only in a model that has them
    let cohesive: [EnergyColumn; 2] =
        [("interfaces", "J", |r| r.interfaces), ("delamination", "J", |r| r.delamination)];
    let cohesive = if solution.delamination.is_some() { &cohesive[..] } else { &[] };
    // the energy ply damage dissipated per mode, only in a model that damages
    // and what the end-of-step stress of damaged points dissipated (`dynamics::ply_forces`)
    let damage: [EnergyColumn; 5] = [
        ("damage_fibre_tension", "J", |r| r.damage[0]),
        ("damage_fibre_compression", "J", |r| r.damage[1]),
        ("damage_matrix_tension", "J", |r| r.damage[2]),
        ("damage_matrix_compression", "J", |r| r.damage[3]),
        ("damage_scheme", "J", |r| r.damage_scheme),
    ];
    let damage = if solution.damage.is_some() { &damage[..] } else { &[] };
    for &(name, unit, f) in columns.iter().chain(cohesive).chain(damage) {
        t.push(name, unit, Values::Real(rows.iter().map(f).collect()));
    }
    Some(t)
}

/// `modes`: one row per mode of a modal analysis (`mode`, numbered from
/// 1): its natural frequency `frequency_hz` (Hz) and effective masses
/// `effective_mass_x`, `_y`, `_z` (kg; of the full structure in a model cut
/// by symmetry planes, `analysis::modal`), the estimated relative error of
/// the frequency `frequency_error` (`(f_h − f) / f`) and the mode's
/// relative error in the energy norm `mode_error` (`post::mode_error`);
/// `None` without one.
pub fn modes(solution: &Solution) -> Option<Table> {
    let m = solution.modal.as_ref()?;
    let mut t = Table::new("modes");
    t.push("mode", "", Values::Count((1..=m.frequencies.len()).collect()));
    t.push("frequency_hz", "Hz", Values::Real(m.frequencies.clone()));
    t.push_xyz("effective_mass_", "kg", &m.effective_masses);
    t.push("frequency_error", "", Values::Real(m.errors.iter().map(|e| e.frequency()).collect()));
    t.push("mode_error", "", Values::Real(m.errors.iter().map(|e| e.estimate.relative()).collect()));
    Some(t)
}

/// `error_history`: one row per state the run kept and estimated
/// (`analysis::state_errors`: each step end with its fields, each frame of
/// a transient run, in the order of λ): `state` (`step` or `frame`),
/// `name` (the step's name, or `frame_<k>` numbered from 1 as its VTU),
/// its `increment`, `lambda`, a transient run's `time` (s), the estimated
/// relative error in the energy norm `estimate` (0–1), the estimated error
/// `error` and the stresses' own energy norm `energy` (√J); `None` without
/// a row.
pub fn error_history(model: &Model, solution: &Solution) -> Option<Table> {
    use super::state_errors::State;
    let rows = &solution.error_history.rows;
    if rows.is_empty() {
        return None;
    }
    let (state, name, increment): (Vec<_>, Vec<_>, Vec<_>) = rows
        .iter()
        .map(|r| match r.state {
            State::Step(k) => ("step".to_string(), r.state.name(&solution.steps), solution.steps[k].increment),
            State::Frame(k) => ("frame".to_string(), r.state.name(&solution.steps), solution.frames[k].increment),
        })
        .fold((Vec::new(), Vec::new(), Vec::new()), |(mut a, mut b, mut c), (x, y, z)| {
            a.push(x);
            b.push(y);
            c.push(z);
            (a, b, c)
        });
    let mut t = Table::new("error_history");
    t.push("state", "", Values::Text(state));
    t.push("name", "", Values::Text(name));
    t.push("increment", "", Values::Count(increment));
    t.push("lambda", "", Values::Real(rows.iter().map(|r| r.lambda).collect()));
    if let Some(tr) = &model.transient {
        t.push("time", "s", Values::Real(rows.iter().map(|r| tr.time(r.lambda)).collect()));
    }
    t.push("estimate", "", Values::Real(rows.iter().map(|r| r.estimate.relative()).collect()));
    t.push("error", "J^0.5", Values::Real(rows.iter().map(|r| r.estimate.error).collect()));
    t.push("energy", "J^0.5", Values::Real(rows.iter().map(|r| r.estimate.energy).collect()));
    Some(t)
}

/// `buckling`: one row per buckling mode (`mode`, numbered from 1) — its
/// critical `load_factor` and critical load `critical_load_x`, `_y`, `_z`
/// (N: the applied load at factor 1 times the factor, on the part
/// modelled) and, in a model cut by symmetry planes, the full structure's
/// `full_critical_load_*` (its applied load across every plane,
/// `bc::symmetry::full_structure`, times the factor); `None` without a
/// buckling analysis (or `analysis.imperfection`).
pub fn buckling(model: &Model, solution: &Solution) -> Option<Table> {
    let b = solution.buckling.as_ref()?;
    let mut t = Table::new("buckling");
    t.push("mode", "", Values::Count((1..=b.factors.len()).collect()));
    t.push("load_factor", "", Values::Real(b.factors.clone()));
    // the applied load at factor 1: the loads at the end over their factor
    let loads = |applied: [f64; 3]| -> Vec<[f64; 3]> {
        b.factors.iter().map(|f| applied.map(|a| a * f / solution.lambda)).collect()
    };
    t.push_xyz("critical_load_", "N", &loads(solution.applied));
    if !model.symmetry.planes.is_empty() {
        let every = vec![true; model.symmetry.planes.len()];
        let full = crate::bc::symmetry::full_structure(solution.applied, &model.symmetry.planes, &every);
        t.push_xyz("full_critical_load_", "N", &loads(full));
    }
    t.push("factor_error", "", Values::Real(b.errors.iter().map(|e| e.eigenvalue).collect()));
    t.push("mode_error", "", Values::Real(b.errors.iter().map(|e| e.estimate.relative()).collect()));
    Some(t)
}

/// The SI unit of a quantity's values.
fn si_unit(q: Quantity) -> &'static str {
    match q {
        Quantity::Displacement(_) => "m",
        Quantity::Stress(_) | Quantity::VonMises => "Pa",
        Quantity::Strain(_) | Quantity::Peeq | Quantity::Failure(_) => "",
    }
}

pub(super) fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
