//! The text a run prints, shared by `cufem run` and the Python package
//! (`Model.run`): the header, a line when the analysis is set up, one per
//! converged increment and per failed attempt, the final report (a table
//! like the paper's, probes, references, resultants, error estimate, ply
//! failure, path, modes) and the closing lines. Every function returns the
//! text; the caller decides where it goes (the CLI: header and report to
//! stdout, progress to stderr; Python: `sys.stdout` and `sys.stderr`).

use std::fmt::Write;
use std::path::Path;

use crate::analysis::{IncrementLog, Setup, Solution, tables};
use crate::setup::Model;
use crate::solver::newton::Failure;
use crate::solver::stepping::Cutback;

/// Appends a line to a `String` (writing to a `String` cannot fail).
macro_rules! out {
    ($s:expr) => {
        $s.push('\n')
    };
    ($s:expr, $($arg:tt)*) => {{
        let _ = writeln!($s, $($arg)*);
    }};
}

pub use crate::numbers::thousands;

/// Each body's discretization: `block 1B4 - 108L9, punch …`.
fn discretization(model: &Model) -> String {
    let parts: Vec<String> = model
        .mesh
        .bodies
        .iter()
        .map(|b| {
            format!(
                "{} {}{:?} - {}{:?}",
                b.name,
                b.axis.n_elements(),
                b.axis.kind,
                b.section.n_elements(),
                b.section.kind
            )
        })
        .collect();
    parts.join(", ")
}

/// The header of a run: the title, then the discretization and the DOF (two
/// lines), and a transient analysis's time steps ([`time_steps`]).
pub fn header(model: &Model) -> String {
    let mut text = format!("{}\n{} — {} DOF\n", model.title, discretization(model), thousands(model.n_dofs()));
    if let Some(line) = time_steps(model) {
        text.push_str(&line);
        text.push('\n');
    }
    text
}

/// A transient analysis's time steps, said before it starts: how many,
/// over how long, and each load step's Δt (without cutbacks).
pub fn time_steps(model: &Model) -> Option<String> {
    let t = model.transient.as_ref()?;
    let per: Vec<(usize, f64)> = model
        .steps
        .iter()
        .zip(&t.durations)
        .map(|(s, d)| (s.planned_increments(), d / s.planned_increments() as f64))
        .collect();
    let total = per.iter().fold(0usize, |n, p| n.saturating_add(p.0));
    let mut steps: Vec<String> = model
        .steps
        .iter()
        .zip(&per)
        .take(3)
        .map(|(s, (n, dt))| format!("{}: {} × {dt:.3e} s", s.name, thousands(*n)))
        .collect();
    if model.steps.len() > 3 {
        steps.push(format!("and {} more load steps", model.steps.len() - 3));
    }
    Some(format!(
        "transient: {} time steps over {:.4e} s ({}); each load step may take up to solver.max_increments = {}",
        thousands(total),
        t.durations.iter().sum::<f64>(),
        steps.join(", "),
        thousands(model.steps.iter().map(|s| s.settings.max_increments).max().unwrap_or(0))
    ))
}

/// The line once the analysis is set up: equations, factor size, memory.
pub fn start_line(setup: &Setup) -> String {
    format!(
        "solving {} equations, nnz(L) = {}, memory estimate {} (Ctrl-C stops at the next safe point and keeps the \
         results)",
        setup.equations,
        setup.factor_nnz,
        crate::size::human_bytes(setup.memory.total())
    )
}

/// One log line per converged increment.
pub fn increment_line(log: &IncrementLog) -> String {
    let res: Vec<String> = log.residuals.iter().map(|r| format!("{r:.1e}")).collect();
    let mut line = format!(
        "increment {:>3}  λ = {:.4} (Δλ {:.3e})  {} iterations  residuals [{}]  plastic points {}",
        log.index,
        log.lambda,
        log.dlambda,
        log.iterations,
        res.join(" "),
        log.plastic_points
    );
    if log.max_penetration > 0.0 {
        line.push_str(&format!("  max penetration {:.2e} m", log.max_penetration));
    }
    if let Some(n) = log.negative_pivots.filter(|n| *n > 0) {
        // an indefinite tangent: past a limit or bifurcation point
        line.push_str(&format!("  negative pivots {n}"));
    }
    if log.cutbacks > 0 {
        line.push_str(&format!("  (after {} cutbacks)", log.cutbacks));
    }
    line
}

/// One log line per failed attempt: Newton's failure and residuals, or the
/// step control's rejection of a converged increment.
pub fn cutback_line(c: &Cutback) -> String {
    if let Some(q) = c.rejected {
        return format!(
            "  rejected: increment {} (λ = {:.4}, Δλ = {:.3e}) converged in {} iterations but changed {:.1} times \
             what solver.step_control allows; redone smaller",
            c.index, c.lambda, c.dlambda, c.newton.iterations, q
        );
    }
    let res: Vec<String> = c.newton.residuals.iter().map(|r| format!("{r:.1e}")).collect();
    format!(
        "  cutback: increment {} (λ = {:.4}, Δλ = {:.3e}) failed after {} iterations ({}), residuals [{}]{}",
        c.index,
        c.lambda,
        c.dlambda,
        c.newton.iterations,
        match c.newton.failure {
            Some(Failure::Diverged) => "diverged",
            Some(Failure::Problem) => "linear solve failed",
            Some(Failure::Stagnated) => "stagnated",
            Some(Failure::Rejected) => "converged, rejected",
            _ => "not converged",
        },
        res.join(" "),
        c.newton.message.as_ref().map(|m| format!(": {m}")).unwrap_or_default()
    )
}

/// The closing line of a run that wrote its files.
pub fn wrote_line(files: usize, folder: &Path) -> String {
    format!("\nwrote {files} files to {}", folder.display())
}

/// The lines of a run that stopped before the full load (`None` if it did
/// not): why, and where the last converged increment's results are
/// (`folder`; `None`: kept in memory only); `kept`: the output folder whose
/// converged results the run left in place (it wrote beside them).
pub fn stopped_early(model: &Model, solution: &Solution, folder: Option<&Path>, kept: Option<&Path>) -> Option<String> {
    let f = solution.failure.as_ref()?;
    let place = folder.map_or_else(|| "returned (nothing written)".to_string(), |d| format!("in {}", d.display()));
    // a transient run's λ is time: the stop is said in seconds
    let at = match &model.transient {
        Some(t) => format!("time step (t = {:.6e} s)", t.time(solution.lambda)),
        None => format!("increment (load factor {:.4})", solution.lambda),
    };
    let mut text = format!("\nthe analysis stopped early: {f}\nresults of the last converged {at} are {place}");
    if let Some(kept) = kept {
        let _ = write!(text, "\nthe converged results already in {} were kept as they were", kept.display());
    }
    Some(text)
}

/// The final report: a table like the paper's and the probe values, then
/// the references, resultants, error estimate, ply failure, path and modes
/// the model has (starts with an empty line).
pub fn results(model: &Model, solution: &Solution) -> String {
    let mut s = String::new();
    let iterations: usize = solution.increments.iter().map(|i| i.newton.iterations).sum();
    out!(s);
    out!(s, "{:<40} {:>10} {:>12} {:>11} {:>10}", "Model", "DOF", "Time (s)", "Increments", "Newton it.");
    out!(
        s,
        "{:<40} {:>10} {:>12.2} {:>11} {:>10}",
        format!("cufem 1D ({})", discretization(model)),
        thousands(model.n_dofs()),
        solution.wall_time.as_secs_f64(),
        solution.increments.len(),
        iterations
    );
    if let Some(a) = &solution.adapt {
        out!(s);
        out!(s, "{:<8} {:>10} {:>12} {:>10}  refined", "cycle", "DOF", "estimate [%]", "time (s)");
        for c in &a.cycles {
            out!(
                s,
                "{:<8} {:>10} {:>12.2} {:>10.1}  {}",
                c.cycle,
                thousands(c.dof),
                100.0 * c.estimate,
                c.time_s,
                c.refined
            );
        }
        let n = a.cycles.len();
        out!(s, "cycles: {n}, {:.1} s in all (the Model row above: the last cycle's)", a.time_s());
        out!(s, "adaptive run stopped: {}", a.stop);
    }
    let summary = super::summary(model, solution);
    if !summary.probes.is_empty() {
        out!(s);
        out!(
            s,
            "{:<14} {:<26} {:>12} {:>12} {:>12} {:>12}",
            "probe",
            "point [m]",
            "u_z [mm]",
            "s_yy [MPa]",
            "s_zz [MPa]",
            "peeq [-]"
        );
        for p in &summary.probes {
            out!(
                s,
                "{:<14} {:<26} {:>12.5} {:>12.3} {:>12.3} {:>12.4e}",
                p.name,
                format!("{:?}", p.point),
                p.u[2] * 1e3,
                p.stress[1] * 1e-6,
                p.stress[2] * 1e-6,
                p.peeq
            );
        }
    }
    references(&mut s, model, solution);
    resultants(&mut s, model, &summary);
    let unloaded = unloaded_end(&summary);
    if let Some((end, largest)) = unloaded {
        out!(
            s,
            "estimated error of the end state not given: it is unloaded (its stresses' energy norm {end:.3e} √J, \
             against {largest:.3e} √J in the run), so its relative error measures round-off; the kept states' \
             estimates follow"
        );
    } else if solution.error_estimate.as_ref().is_some_and(|e| e.energy == 0.0 && e.error == 0.0) {
        // no stress at all (a modal analysis of the unloaded structure): a
        // relative error of 0 / 0, which read as "0.00 %, converged"
        let modes = if solution.modal.is_some() { "; the modes' estimates are in their table" } else { "" };
        out!(s, "estimated error of the end state not given: it carries no stress{modes}");
    } else if let Some(e) = &summary.error_estimate {
        let largest: Vec<String> =
            e.largest.iter().take(3).map(|l| format!("{} #{} ({:.0} %)", l.body, l.element, 100.0 * l.share)).collect();
        out!(
            s,
            "estimated error {:.2} % (energy norm, raw against recovered stresses); largest in {}",
            100.0 * e.relative_energy_norm,
            largest.join(", ")
        );
    }
    error_history(&mut s, &summary);
    // an unloaded end's "concentrated" forces are round-off
    for c in summary.concentrated.iter().filter(|_| unloaded.is_none()) {
        let share = c.error_share.map_or(String::new(), |v| format!("; {:.0} % of the estimated error", 100.0 * v));
        out!(
            s,
            "{} {:?} ({}) acts on a point or a line ({} nodes): the stresses of its {} elements are a concentrated \
             force's and do not converge under refinement{share}",
            c.kind,
            c.name,
            c.key,
            c.nodes,
            c.elements
        );
    }
    ply_failure(&mut s, &summary);
    damage(&mut s, &summary);
    energy(&mut s, solution);
    if let Some(p) = &summary.path {
        let points: Vec<String> = p.limit_points.iter().map(|(i, l)| format!("increment {i} (λ = {l:.5})")).collect();
        let points = if points.is_empty() { "none".to_string() } else { points.join(", ") };
        out!(s, "arc length: limit points {points}; ended by {}", p.end);
    }
    modes(&mut s, model, solution);
    s
}

/// An end state whose stresses' energy norm is below [`UNLOADED`] of the
/// largest of the run's kept states (a load history that returns to zero
/// on an elastic body): `(its energy norm, the largest)`. Its relative
/// estimate divides round-off by round-off (`56 %` on a roller pressed and
/// withdrawn; a new-user review).
fn unloaded_end(summary: &super::Summary) -> Option<(f64, f64)> {
    let end = summary.error_history.last()?.energy;
    let largest = summary.error_history.iter().map(|r| r.energy).fold(0.0, f64::max);
    (largest > 0.0 && end < UNLOADED * largest).then_some((end, largest))
}

/// The energy norm below which an end state counts as unloaded, as a
/// fraction of the run's largest (Newton's tolerance leaves about `1e-8`
/// of the load; an elastic body pressed and released: `1e-13`).
const UNLOADED: f64 = 1e-6;

/// The estimated error of every kept step end and frame (summary.json's
/// `error_history`), when the run kept more than its final state.
fn error_history(s: &mut String, summary: &super::Summary) {
    let rows = &summary.error_history;
    if rows.len() < 2 {
        return;
    }
    let transient = rows.iter().any(|r| r.time_s.is_some());
    let at = if transient { "time [s]" } else { "λ" };
    out!(
        s,
        "error  state  {:<16} {:>10} {:>12}  {:>14}  {:>12}",
        "name",
        "increment",
        at,
        "est. error [%]",
        "energy [√J]"
    );
    for r in rows {
        out!(
            s,
            "       {:<5}  {:<16} {:>10} {:>12.5e}  {:>14.3}  {:>12.4e}",
            r.state,
            r.name,
            r.increment,
            r.time_s.unwrap_or(r.load_factor),
            100.0 * r.relative_energy_norm,
            r.energy
        );
    }
    if transient {
        out!(
            s,
            "       each time's estimate is the error of its own stresses: it does not see an error that waves \
             carried from earlier times (a travelling wave's phase), which can be several times larger \
             (docs/limitations.md)"
        );
    }
}

/// The model's reference values beside cufem's at their probes.
fn references(s: &mut String, model: &Model, solution: &Solution) {
    if model.references.is_empty() {
        return;
    }
    out!(s);
    out!(s, "{:<14} {:<16} {:>12} {:>12}  source", "probe", "quantity", "cufem", "reference");
    let view = solution.fields(model);
    for r in &model.references {
        let ours = model
            .probes
            .iter()
            .find(|p| p.name == r.probe)
            .and_then(|p| view.sample_probe(p))
            .map_or(f64::NAN, |v| v.get(r.quantity));
        let scale = r.quantity.display_scale();
        let unit = r.quantity.label();
        let unit = unit.split('[').nth(1).map(|u| format!("[{u}")).unwrap_or_default();
        out!(
            s,
            "{:<14} {:<16} {:>12.4} {:>12.4}  {}",
            r.probe,
            format!("{} {unit}", r.quantity.name()),
            ours * scale,
            r.value * scale,
            r.source
        );
    }
}

/// Reactions and contact forces, with the full structure's beside in a
/// model with symmetry planes.
fn resultants(s: &mut String, model: &Model, summary: &super::Summary) {
    // in a model with symmetry planes, the force on the full structure beside
    let full = |f: &super::ForceSummary| {
        f.full_structure_force
            .map_or(String::new(), |g| format!(" (full structure [{:.5e}, {:.5e}, {:.5e}] N)", g[0], g[1], g[2]))
    };
    for (c, f) in model.constraints.iter().zip(&summary.reactions) {
        out!(s, "reaction {:<12} [{:.5e}, {:.5e}, {:.5e}] N{}", c.name, f.force[0], f.force[1], f.force[2], full(f));
    }
    for c in &summary.contact {
        out!(
            s,
            "contact  {:<12} force on body [{:.5e}, {:.5e}, {:.5e}] N, max penetration {:.3e} m{}",
            c.name,
            c.force[0],
            c.force[1],
            c.force[2],
            c.max_penetration.unwrap_or(0.0),
            full(c)
        );
    }
    // a lever's force may be the model's only load (it was in summary.json
    // alone; a new-user review)
    for l in &summary.levers {
        out!(s, "lever    {:<12} force {:.5e} N at displacement {:.5e} m", l.name, l.force, l.displacement);
    }
}

/// Each failure criterion's largest index and first-failure load factor,
/// the interlaminar one's at the bonded ply interfaces last.
fn ply_failure(s: &mut String, summary: &super::Summary) {
    let Some(f) = &summary.ply_failure else { return };
    for c in f.criteria.iter().chain(&f.interlaminar) {
        let (when, w) = match (c.first_failure_load_factor, &c.first_failure_at) {
            (Some(factor), Some(at)) => (format!("; first failure at load factor {factor:.4}"), at),
            _ => (" at the end,".to_string(), &c.largest_at),
        };
        let why = if c.first_failure_load_factor.is_none() {
            " (no first-failure load factor: the loading of a transient or damaging run is not proportional)"
        } else {
            ""
        };
        let [x, y, z] = w.point;
        out!(
            s,
            "{:<18} largest index {:.4}{when} in {} at [{x:.4e}, {y:.4e}, {z:.4e}] m{why}",
            c.criterion,
            c.largest_index,
            w.material
        );
    }
}

/// What broke: the ply damage of each mode and the delaminated area, with
/// the energy they dissipated (summary.json `damage`, `delamination`). A
/// strip that had failed printed only its failure indices, as if intact
/// (a new-user review).
fn damage(s: &mut String, summary: &super::Summary) {
    if let Some(d) = &summary.damage {
        let [largest, dissipated, past_half] =
            [&d.largest, &d.dissipated_j, &d.damaged_volume_m3].map(crate::damage::PerMode::to_array);
        out!(s, "ply damage         {:<20} {:>8} {:>14} {:>18}", "mode", "largest", "dissipated [J]", "past ½ [m³]");
        for (k, mode) in d.modes.iter().enumerate() {
            out!(
                s,
                "                   {mode:<20} {:>8.4} {:>14.5e} {:>18.5e}",
                largest[k],
                dissipated[k],
                past_half[k]
            );
        }
        out!(s, "                   {:<20} {:>8} {:>14.5e}", "all modes", "", d.dissipated_total_j);
    }
    if let Some(d) = &summary.delamination {
        let whole: f64 = d.interfaces.iter().map(|i| i.area_m2).sum();
        let viscous = if d.viscous_j > 0.0 {
            format!(": the law's {:.5e} J and its viscous over-stress's {:.5e} J", d.dissipated_j, d.viscous_j)
        } else {
            String::new()
        };
        out!(
            s,
            "delamination       {:.5e} m² of {:.5e} m² of interface delaminated (d = 1), {:.5e} J dissipated{viscous}",
            d.area_m2,
            whole,
            d.dissipated_j + d.viscous_j
        );
    }
}

/// Terms of the energy ledger below this share of its largest are round-off.
const ROUND_OFF: f64 = 1e-9;

/// A transient run's energy ledger at its end (`energy.csv`'s last row):
/// the terms that are not zero, the energy at the start (the bodies' and
/// the impactors' kinetic energy) and the balance as a share of it. The
/// console gave the delamination's dissipation by its law, and the
/// ledger's `delamination_J` (the interfaces' work less the energy they
/// hold) another number, without a word (a new-user review).
fn energy(s: &mut String, solution: &Solution) {
    let Some(rows) = solution.energy.as_ref().filter(|r| !r.is_empty()) else { return };
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    let start = first.kinetic + first.impactors;
    let terms = [
        ("kinetic", last.kinetic),
        ("elastic", last.elastic),
        ("impactors' kinetic", last.impactors),
        ("loads' work", last.external),
        ("contacts' work", last.contact),
        ("supports' work", last.supports),
        ("plastic", last.plastic),
        ("damage", last.damage.iter().sum()),
        ("damage scheme", last.damage_scheme),
        ("damping", last.damping),
        ("delamination", last.delamination),
    ];
    // a term within round-off of the largest (a body without plasticity's
    // `plastic`, 1e-13 of the impact's) is left out
    let scale = terms.iter().map(|(_, v)| v.abs()).fold(start, f64::max);
    let listed: Vec<String> =
        terms.iter().filter(|(_, v)| v.abs() > ROUND_OFF * scale).map(|(name, v)| format!("{name} {v:.5e}")).collect();
    let share = if start > 0.0 { format!(" ({:.1e} of the start)", last.balance.abs() / start) } else { String::new() };
    out!(
        s,
        "energy [J]         at the start {start:.5e}; at t = {:.5e} s: {}; balance {:.3e}{share} (energy.csv)",
        last.time,
        listed.join(", "),
        last.balance
    );
    if last.interfaces != 0.0 {
        out!(
            s,
            "                   delamination: the interfaces' work less the energy they hold; it differs from the \
             law's and the viscous sums above where a point fails within a time step (docs/model-format.md, \
             analysis.interface_forces)"
        );
    }
}

/// Vibration frequencies with their effective masses, buckling factors with
/// their critical loads: the tables `modes` and `buckling`
/// (`analysis::tables`), as `modes.csv` and `buckling.csv` hold them.
fn modes(s: &mut String, model: &Model, solution: &Solution) {
    if let (Some(m), Some(t)) = (&solution.modal, tables::modes(solution)) {
        let share = |k: usize, v: f64| if m.free_mass[k] > 0.0 { 100.0 * v / m.free_mass[k] } else { 0.0 };
        let of = if m.full_structure { " of the full structure" } else { "" };
        out!(s, "modal  mode  frequency [Hz]   freq. err. [%]   effective mass [% of the free mass{of}]  x / y / z");
        let (f, e) = (t.real("frequency_hz").unwrap_or_default(), t.xyz("effective_mass_").unwrap_or_default());
        let error = t.real("frequency_error").unwrap_or_default();
        for (k, (f, e)) in f.iter().zip(&e).enumerate() {
            out!(
                s,
                "       {:>4}  {f:>14.6e}   {:>14.3}   {:>6.2} / {:>6.2} / {:>6.2}",
                k + 1,
                100.0 * error.get(k).copied().unwrap_or(f64::NAN),
                share(0, e[0]),
                share(1, e[1]),
                share(2, e[2])
            );
        }
    }
    if let Some(t) = tables::buckling(model, solution) {
        // a cut model's loads are the part's: its table gives the full structure's
        let (loads, of) = match t.xyz("full_critical_load_") {
            Some(full) => (full, "critical load of the full structure [N]"),
            None => (t.xyz("critical_load_").unwrap_or_default(), "critical load [N]"),
        };
        out!(s, "buckling  mode  load factor   factor err.[%]   {of}");
        let error = t.real("factor_error").unwrap_or_default();
        for (k, (f, p)) in t.real("load_factor").unwrap_or_default().iter().zip(&loads).enumerate() {
            let e = 100.0 * error.get(k).copied().unwrap_or(f64::NAN);
            out!(s, "          {:>4}  {f:>11.5e}   {e:>14.3}   [{:.5e}, {:.5e}, {:.5e}]", k + 1, p[0], p[1], p[2]);
        }
    }
}
