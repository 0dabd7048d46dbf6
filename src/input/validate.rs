//! Validation of the model file's values that needs no mesh: names,
//! materials, divisions, penalties, solver controls, references. Pure
//! functions of the schema, each error naming key, value and what is
//! allowed.

use super::bounds::{self, number};
use super::defaults;
use super::ranges::{self, AT_LEAST_ONE, FRACTION, TOLERANCE};
use super::schema::*;
use super::{ModelError, OutputSettings, Reference, SolverSettings, invalid};
use crate::contact::{self, Penalty};
use crate::mesh::{Division, Segment};
use crate::solver::newton::NewtonSettings;
use crate::solver::reuse::ReuseSettings;
use crate::solver::stepping::{StepControl, StepSettings};

/// Names are unique per table; constraints, indenters and contacts share
/// one name space with levers (they all write `history_<name>.csv`), in
/// which `probes` is taken by the probes' history (`history_probes.csv`).
pub(crate) fn names(file: &ModelFile) -> Result<(), ModelError> {
    unique_names(keyed("materials", &file.materials, |m| &m.name))?;
    unique_names(keyed("bodies", &file.bodies, |m| &m.name))?;
    unique_names(keyed("loads", &file.loads, |m| &m.name))?;
    unique_names(keyed("probes", &file.probes, |m| &m.name))?;
    unique_names(keyed("lines", &file.lines, |m| &m.name))?;
    let histories = || {
        keyed("constraints", &file.constraints, |m| &m.name)
            .chain(keyed("indenters", &file.indenters, |m| &m.name))
            .chain(keyed("contacts", &file.contacts, |m| &m.name))
            .chain(keyed("symmetry", &file.symmetry, |m| &m.name))
            .chain(keyed("levers", &file.levers, |m| &m.name))
    };
    unique_names(histories())?;
    if let Some((key, name)) = histories().find(|(_, n)| n.as_str() == "probes") {
        return Err(invalid(
            format!("{key}.name"),
            format!("{name:?}"),
            "another name: history_probes.csv is the probes' history",
        ));
    }
    if file.bodies.is_empty() {
        return Err(invalid("bodies", "[]", "at least one [[bodies]] table"));
    }
    Ok(())
}

/// `[output]`.
pub(crate) fn output(o: &OutputFile) -> OutputSettings {
    // element-wise recovery stays the default until the projection is
    // validated against 3D under punches (issue 8)
    let recovery = o.recovery.unwrap_or_default();
    OutputSettings {
        vtu: o.vtu.unwrap_or(defaults::VTU),
        plots: o.plots.unwrap_or(defaults::PLOTS),
        recovery,
        gauss_points: o.gauss_points.unwrap_or(defaults::GAUSS_POINTS),
        vtu_cells: o.vtu_cells.unwrap_or_default(),
        report: o.report.unwrap_or(defaults::REPORT),
    }
}

/// `[[references]]`: published values beside named probes.
pub(crate) fn references(file: &[ReferenceFile], probes: &[ProbeFile]) -> Result<Vec<Reference>, ModelError> {
    let mut references = Vec::new();
    for (i, r) in file.iter().enumerate() {
        let key = format!("references[{i}]");
        if !probes.iter().any(|p| p.name == r.probe) {
            return Err(invalid(format!("{key}.probe"), format!("{:?}", r.probe), "the name of a [[probes]] entry"));
        }
        references.push(Reference {
            probe: r.probe.clone(),
            quantity: r.quantity.0,
            value: finite(&format!("{key}.value"), r.value)?,
            source: r.source.clone(),
        });
    }

    Ok(references)
}

pub(crate) fn finite_positive(key: &str, v: f64) -> Result<f64, ModelError> {
    if v.is_finite() && v > 0.0 { Ok(v) } else { Err(invalid(key, v, "a positive finite number")) }
}

pub(crate) fn finite(key: &str, v: f64) -> Result<f64, ModelError> {
    if v.is_finite() { Ok(v) } else { Err(invalid(key, v, "a finite number")) }
}

/// Checks that names are non-empty, usable in file names, and unique within
/// `group` (entries given as `(key, name)`).
pub(crate) fn unique_names<'a>(group: impl Iterator<Item = (String, &'a String)>) -> Result<(), ModelError> {
    let mut seen: std::collections::HashMap<&String, String> = Default::default();
    for (key, n) in group {
        if n.is_empty() || !n.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c)) {
            return Err(invalid(
                format!("{key}.name"),
                format!("{n:?}"),
                "a non-empty name of letters, digits, '_', '-' or '.' (it is used in file names)",
            ));
        }
        if let Some(other) = seen.insert(n, key.clone()) {
            return Err(invalid(
                format!("{key}.name"),
                format!("{n:?}"),
                format!("a name not already used by {other}"),
            ));
        }
    }
    Ok(())
}

pub(crate) fn keyed<'a, T>(
    key: &'a str,
    items: &'a [T],
    name: impl Fn(&T) -> &String + 'a,
) -> impl Iterator<Item = (String, &'a String)> + 'a {
    items.iter().enumerate().map(move |(i, t)| (format!("{key}[{i}]"), name(t)))
}

pub(crate) fn division(key: &str, d: &DivisionFile) -> Result<Vec<f64>, ModelError> {
    division_parts(key, d.from, d.to, d.elements, d.ratio, d.lines.as_ref(), d.segments.as_ref())
}

pub(crate) use super::ranges::MAX_COUNT;

pub(crate) fn count(key: &str, n: usize) -> Result<usize, ModelError> {
    if (1..=MAX_COUNT).contains(&n) { Ok(n) } else { Err(invalid(key, n, format!("an integer from 1 to {MAX_COUNT}"))) }
}

/// An interval division in one of its three forms. Which form is meant is
/// checked here, not by serde: an untagged enum of the three would answer a
/// mistake with "data did not match any variant", naming neither the key
/// nor the forms.
pub(crate) fn division_parts(
    key: &str,
    from: Option<f64>,
    to: Option<f64>,
    elements: Option<usize>,
    ratio: Option<f64>,
    lines: Option<&Vec<f64>>,
    segments: Option<&Vec<SegmentFile>>,
) -> Result<Vec<f64>, ModelError> {
    let forms = [from.is_some() || to.is_some() || elements.is_some(), lines.is_some(), segments.is_some()];
    if ratio.is_some() && !forms[0] {
        return Err(invalid(
            format!("{key}.ratio"),
            "(given)",
            "`ratio` only with {from, to, elements}; segments carry their own ratio",
        ));
    }
    if forms.iter().filter(|f| **f).count() != 1 {
        return Err(invalid(
            key,
            "(ambiguous or missing division)",
            "exactly one of {from, to, elements[, ratio]}, {lines = […]} or {segments = […]}",
        ));
    }
    for (k, seg) in segments.iter().flat_map(|v| v.iter()).enumerate() {
        count(&format!("{key}.segments[{k}].elements"), seg.elements)?;
    }
    if let Some(l) = lines
        && l.len() > MAX_COUNT + 1
    {
        return Err(invalid(
            format!("{key}.lines"),
            format!("{} values", l.len()),
            format!("at most {} values", MAX_COUNT + 1),
        ));
    }
    let div = if let Some(l) = lines {
        Division::Lines(l.clone())
    } else if let Some(s) = segments {
        Division::Segments(
            s.iter()
                .map(|s| Segment { from: s.from, to: s.to, elements: s.elements, ratio: s.ratio.unwrap_or(1.0) })
                .collect(),
        )
    } else {
        let need = |name: &str| {
            invalid(format!("{key}.{name}"), "(missing)", "a value (uniform division needs from, to and elements)")
        };
        let elements = count(&format!("{key}.elements"), elements.ok_or_else(|| need("elements"))?)?;
        let ratio = ratio.unwrap_or(1.0);
        let (lo, hi) = bounds::GRADING_RATIO;
        bounds::within(&format!("{key}.ratio"), ratio, lo, hi, "last/first element length")?;
        let (from, to) = (from.ok_or_else(|| need("from"))?, to.ok_or_else(|| need("to"))?);
        if !(from.is_finite() && to.is_finite() && to > from) {
            return Err(invalid(format!("{key}.to"), to, format!("a finite number greater than from ({from})")));
        }
        Division::Segments(vec![Segment { from, to, elements, ratio }])
    };
    Ok(div.lines(key)?)
}

pub(crate) fn penalty(key: &str, penalty: Option<f64>, factor: Option<f64>) -> Result<Penalty, ModelError> {
    match (penalty, factor) {
        (Some(_), Some(_)) => {
            Err(invalid(format!("{key}.penalty"), "both penalty and penalty_factor", "at most one of them"))
        }
        (Some(p), None) => Ok(Penalty::PerArea(ranges::PENALTY.check(
            &format!("{key}.penalty"),
            p,
            "a positive penalty per area in Pa/m",
        )?)),
        (None, Some(a)) => {
            let (lo, hi) = bounds::PENALTY_FACTOR;
            Ok(Penalty::Factor(bounds::within(
                &format!("{key}.penalty_factor"),
                a,
                lo,
                hi,
                "dimensionless: ε_N = α E A / h",
            )?))
        }
        (None, None) => Ok(Penalty::Factor(contact::DEFAULT_PENALTY_FACTOR)),
    }
}

/// `penetration_tolerance` (augmented Lagrangian): positive, at most a
/// thousandth of the body's size.
pub(crate) fn tolerance(key: &str, t: Option<f64>, size: f64) -> Result<Option<f64>, ModelError> {
    t.map(|t| {
        bounds::within(
            &format!("{key}.penetration_tolerance"),
            t,
            f64::MIN_POSITIVE,
            1e-3 * size,
            "the largest penetration in m that the augmented Lagrangian accepts, positive and at most 1e-3 of the body's size",
        )
    })
    .transpose()
}

/// `friction`: Coulomb's coefficient μ in [0, 10]; the tangential penalty
/// equals the normal one (elastic slip of the order of the penetration).
pub(crate) fn friction(key: &str, mu: Option<f64>) -> Result<Option<contact::Friction>, ModelError> {
    mu.map(|m| {
        ranges::FRICTION
            .check(&format!("{key}.friction"), m, "Coulomb's coefficient of friction μ")
            .map(|coefficient| contact::Friction { coefficient, penalty_ratio: 1.0 })
    })
    .transpose()
}

pub(crate) fn solver_settings(s: &SolverFile, linear: bool) -> Result<SolverSettings, ModelError> {
    let increments = s.increments.unwrap_or(if linear { 1 } else { 10 });
    if !AT_LEAST_ONE.contains_count(increments) {
        return Err(invalid("solver.increments", increments, format!("an integer {AT_LEAST_ONE}")));
    }
    let initial = 1.0 / increments as f64;
    let fraction = |name: &str, v: Option<f64>, default: f64| -> Result<f64, ModelError> {
        match v {
            None => Ok(default),
            Some(v) if FRACTION.contains(v) => Ok(v),
            Some(v) => Err(invalid(format!("solver.{name}"), number(v), format!("a number {FRACTION}"))),
        }
    };
    let control = step_control(s.step_control.as_ref())?;
    // the step control grows the increment as far as its measures allow
    let max = fraction("max_increment", s.max_increment, if control.is_some() { 1.0 } else { initial })?;
    let min = fraction("min_increment", s.min_increment, 1e-4 * initial.min(max))?;
    // open at both ends: 0 would stop at the first cutback, 1 would retry the
    // same increment forever
    let cutback = match s.cutback_factor {
        None => defaults::CUTBACK_FACTOR,
        Some(c) if ranges::CUTBACK_FACTOR.contains(c) => c,
        Some(c) => {
            return Err(invalid(
                "solver.cutback_factor",
                number(c),
                format!(
                    "a number {}, both ends excluded: the failed increment Δλ is retried as Δλ × cutback_factor, \
                     so 1 would retry the same increment",
                    ranges::CUTBACK_FACTOR
                ),
            ));
        }
    };
    let growth = match s.growth_factor {
        None => defaults::GROWTH_FACTOR,
        Some(g) if ranges::GROWTH_FACTOR.contains(g) => g,
        Some(g) => return Err(invalid("solver.growth_factor", g, format!("a number {}", ranges::GROWTH_FACTOR))),
    };
    let tol = |name: &str, v: Option<f64>, default: f64| -> Result<f64, ModelError> {
        match v {
            None => Ok(default),
            Some(v) if TOLERANCE.contains(v) => Ok(v),
            Some(v) => Err(invalid(format!("solver.{name}"), number(v), format!("a number {TOLERANCE}"))),
        }
    };
    if min > max {
        return Err(invalid("solver.min_increment", min, format!("at most max_increment ({max})")));
    }
    let stagnation = match s.stagnation_iterations {
        Some(n) if !AT_LEAST_ONE.contains_count(n) => {
            return Err(invalid("solver.stagnation_iterations", n, format!("an integer {AT_LEAST_ONE}")));
        }
        Some(n) => n,
        None => usize::MAX,
    };
    let max_iterations = s.max_iterations.unwrap_or(defaults::MAX_ITERATIONS);
    if !AT_LEAST_ONE.contains_count(max_iterations) {
        return Err(invalid("solver.max_iterations", max_iterations, format!("an integer {AT_LEAST_ONE}")));
    }
    let max_increments = s.max_increments.unwrap_or(defaults::MAX_INCREMENTS);
    if !AT_LEAST_ONE.contains_count(max_increments) {
        return Err(invalid("solver.max_increments", max_increments, format!("an integer {AT_LEAST_ONE}")));
    }
    let single_precision = s.factor_precision.unwrap_or_default() == FactorPrecision::Single;
    if let Some(n) = s.threads.filter(|n| !AT_LEAST_ONE.contains_count(*n)) {
        return Err(invalid("solver.threads", n, format!("an integer {AT_LEAST_ONE} (or no key: all cores)")));
    }
    Ok(SolverSettings {
        steps: StepSettings {
            initial: initial.min(max),
            max,
            min: min.min(initial),
            cutback_factor: cutback,
            growth_factor: growth,
            easy_iterations: s.easy_iterations.unwrap_or(defaults::EASY_ITERATIONS),
            max_increments,
            control,
        },
        newton: NewtonSettings {
            max_iterations,
            residual_tolerance: tol("residual_tolerance", s.residual_tolerance, defaults::RESIDUAL_TOLERANCE)?,
            displacement_tolerance: tol(
                "displacement_tolerance",
                s.displacement_tolerance,
                defaults::DISPLACEMENT_TOLERANCE,
            )?,
            divergence_ratio: 1e6,
            stagnation_iterations: stagnation,
            line_search: s.line_search.unwrap_or(defaults::LINE_SEARCH),
        },
        threads: s.threads,
        reuse: ReuseSettings {
            enabled: s.reuse_factorization.unwrap_or(defaults::REUSE_FACTORIZATION),
            tolerance: tol("krylov_tolerance", s.krylov_tolerance, ReuseSettings::default().tolerance)?,
            // a linear model factorizes once: in double, solved to round-off
            // rather than to Newton's tolerance (solver::reuse, mixed precision)
            single_precision: single_precision && !linear,
            ..ReuseSettings::default()
        },
        path: None,
        inertia: s.inertia.map(|i| match i {
            Inertia::EveryIncrement => super::InertiaReport::EveryIncrement,
            Inertia::LastFactorization => super::InertiaReport::LastFactorization,
        }),
    })
}

/// `solver.step_control`: at least one target; a plastic strain in
/// (0, 0.1], a fraction of the contact set in (0, 1], a time error in
/// (0, 0.1] (a transient analysis only: `setup::transient`), a damage
/// increment in (0, 1] (a model that damages only: `setup`).
fn step_control(c: Option<&StepControlFile>) -> Result<Option<StepControl>, ModelError> {
    let Some(c) = c else { return Ok(None) };
    let key = "solver.step_control";
    let check = |name: &str, v: Option<f64>, range: ranges::Range, what: &str| match v {
        Some(v) if !range.contains(v) => {
            Err(invalid(format!("{key}.{name}"), number(v), format!("a number {range}: {what}")))
        }
        _ => Ok(v),
    };
    let plastic_strain = check(
        "plastic_strain",
        c.plastic_strain,
        ranges::PLASTIC_STRAIN_STEP,
        "the largest increment of the equivalent plastic strain at any Gauss point per load increment, e.g. 2e-3",
    )?;
    let contact_set = check(
        "contact_set",
        c.contact_set,
        FRACTION,
        "the largest fraction of the active contact points that open or close in one increment, e.g. 0.2",
    )?;
    let time_error = check(
        "time_error",
        c.time_error,
        ranges::TIME_ERROR,
        "the largest local error of a time step relative to the largest displacement so far (analysis.type = \
         \"transient\"), e.g. 1e-3",
    )?;
    let damage = check(
        "damage",
        c.damage,
        FRACTION,
        "the largest increment of a damage variable (a ply damage mode's, a cohesive interface's) at any point per \
         increment, e.g. 0.1",
    )?;
    if plastic_strain.is_none() && contact_set.is_none() && time_error.is_none() && damage.is_none() {
        return Err(invalid(key, "{}", "at least one of plastic_strain, contact_set, time_error, damage"));
    }
    Ok(Some(StepControl { plastic_strain, contact_set, time_error, damage }))
}

pub(crate) fn describe_selection(s: &SelectionFile) -> String {
    let c = |v: &Option<ConditionFile>| match v {
        None => None,
        Some(ConditionFile::Value(a)) => Some(format!("{a}")),
        Some(ConditionFile::Range([a, b])) => Some(format!("[{a}, {b}]")),
    };
    let parts: Vec<String> = [
        ("x", c(&s.x)),
        ("y", c(&s.y)),
        ("z", c(&s.z)),
        ("radius", c(&s.radius)),
        ("center", s.center.map(|Exact(v)| format!("{v:?}"))),
        ("region", s.region.as_ref().map(|r| format!("{r:?}"))),
    ]
    .into_iter()
    .filter_map(|(n, v)| v.map(|v| format!("{n} = {v}")))
    .collect();
    format!("{{ {} }}", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(r: Result<impl std::fmt::Debug, ModelError>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn divisions_take_exactly_one_form() {
        assert_eq!(division_parts("d", Some(0.0), Some(1.0), Some(2), None, None, None).unwrap(), vec![0.0, 0.5, 1.0]);
        let lines = vec![0.0, 0.2, 1.0];
        assert_eq!(division_parts("d", None, None, None, None, Some(&lines), None).unwrap(), lines);
        let e = err(division_parts("d", Some(0.0), Some(1.0), Some(2), None, Some(&lines), None));
        assert!(e.contains("exactly one of"), "{e}");
        let e = err(division_parts("d", None, None, None, Some(2.0), Some(&lines), None));
        assert!(e.contains("d.ratio") && e.contains("only with"), "{e}");
        let e = err(division_parts("d", Some(0.0), Some(1.0), Some(0), None, None, None));
        assert!(e.contains("d.elements = 0"), "{e}");
        let e = err(division_parts("d", Some(1.0), Some(0.0), Some(2), None, None, None));
        assert!(e.contains("d.to = 0"), "{e}");
    }

    #[test]
    fn solver_settings_defaults_and_limits() {
        let s = solver_settings(&SolverFile::default(), false).unwrap();
        assert_eq!((s.steps.initial, s.newton.max_iterations, s.steps.max_increments), (0.1, 25, 1000));
        assert_eq!(solver_settings(&SolverFile::default(), true).unwrap().steps.initial, 1.0);
        // cutback_factor: the message states the range the check applies
        // (0 and 1.5 were told "(0, 1]" while 1 was refused as outside "(0, 1)")
        for c in [0.0, 1.0, 1.5, f64::NAN] {
            let e = err(solver_settings(&SolverFile { cutback_factor: Some(c), ..Default::default() }, false));
            assert!(
                e.contains(&format!(
                    "solver.cutback_factor = {}: expected a number in (0, 1), both ends excluded",
                    number(c)
                )),
                "{c}: {e}"
            );
        }
        let ok = solver_settings(&SolverFile { cutback_factor: Some(0.999), ..Default::default() }, false).unwrap();
        assert_eq!(ok.steps.cutback_factor, 0.999);
        let e = err(solver_settings(
            &SolverFile { min_increment: Some(0.5), max_increment: Some(0.1), ..Default::default() },
            false,
        ));
        assert!(e.contains("solver.min_increment"), "{e}");
        // stagnation: off unless asked, and at least one correction
        assert_eq!(s.newton.stagnation_iterations, usize::MAX);
        let given = SolverFile { stagnation_iterations: Some(4), ..Default::default() };
        assert_eq!(solver_settings(&given, false).unwrap().newton.stagnation_iterations, 4);
        let e = err(solver_settings(&SolverFile { stagnation_iterations: Some(0), ..Default::default() }, false));
        assert!(e.contains("solver.stagnation_iterations = 0"), "{e}");
        // reuse of factorizations: on by default, PCG stop at most 0.1
        // (docs/model-format.md)
        assert!(s.reuse.enabled && s.reuse.tolerance == 0.1);
        let off = SolverFile { reuse_factorization: Some(false), krylov_tolerance: Some(1e-6), ..Default::default() };
        let off = solver_settings(&off, false).unwrap();
        assert!(!off.reuse.enabled && off.reuse.tolerance == 1e-6);
        let e = err(solver_settings(&SolverFile { krylov_tolerance: Some(1.5), ..Default::default() }, false));
        assert!(e.contains("solver.krylov_tolerance = 1.5") && e.contains("(0, 1)"), "{e}");
        // mixed precision: single by default (in a nonlinear model), "double"
        // turns it off, other words are named
        assert!(s.reuse.single_precision);
        assert!(!solver_settings(&SolverFile::default(), true).unwrap().reuse.single_precision);
        let double = SolverFile { factor_precision: Some(FactorPrecision::Double), ..Default::default() };
        assert!(!solver_settings(&double, false).unwrap().reuse.single_precision);
        // another word is refused by the reader, with its line and the two allowed
        let e = toml::from_str::<SolverFile>("factor_precision = \"half\"").unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("unknown variant `half`, expected `single` or `double`"), "{e}");
    }

    #[test]
    fn step_control_and_line_search_keys() {
        // off by default: the fixed count, no line search
        let s = solver_settings(&SolverFile::default(), false).unwrap();
        assert_eq!((s.steps.control, s.steps.max, s.newton.line_search), (None, 0.1, false));
        let file = |t: &str| toml::from_str::<SolverFile>(t).unwrap();
        let s = solver_settings(&file("step_control = { plastic_strain = 2e-3 }\nline_search = true"), false).unwrap();
        let c = s.steps.control.unwrap();
        assert_eq!((c.plastic_strain, c.contact_set, s.newton.line_search), (Some(2e-3), None, true));
        // the control lets Δλ grow to the whole step unless max_increment caps it
        assert_eq!((s.steps.initial, s.steps.max), (0.1, 1.0));
        let s = solver_settings(&file("max_increment = 0.2\nstep_control = { contact_set = 0.3 }"), false).unwrap();
        assert_eq!((s.steps.max, s.steps.control.unwrap().contact_set), (0.2, Some(0.3)));
        for (text, says) in [
            (
                "step_control = { plastic_strain = 0.0 }",
                "solver.step_control.plastic_strain = 0: expected a number in (0, 0.1]",
            ),
            (
                "step_control = { plastic_strain = 0.5 }",
                "solver.step_control.plastic_strain = 0.5: expected a number in (0, 0.1]",
            ),
            (
                "step_control = { contact_set = 1.5 }",
                "solver.step_control.contact_set = 1.5: expected a number in (0, 1]",
            ),
            (
                "step_control = { contact_set = nan }",
                "solver.step_control.contact_set = NaN: expected a number in (0, 1]",
            ),
            (
                "step_control = {}",
                "solver.step_control = {}: expected at least one of plastic_strain, contact_set, time_error, damage",
            ),
            (
                "step_control = { time_error = 0.2 }",
                "solver.step_control.time_error = 0.2: expected a number in (0, 0.1]",
            ),
            ("step_control = { damage = 0.0 }", "solver.step_control.damage = 0: expected a number in (0, 1]"),
            ("step_control = { damage = 1.5 }", "solver.step_control.damage = 1.5: expected a number in (0, 1]"),
        ] {
            let e = err(solver_settings(&file(text), false));
            assert!(e.contains(says), "{text}: {e}");
        }
        // an unknown key is refused by the reader with the allowed ones
        let e = toml::from_str::<SolverFile>("step_control = { plastic = 1e-3 }").unwrap_err().to_string();
        assert!(
            e.contains("unknown field `plastic`, expected one of `plastic_strain`, `contact_set`, `time_error`"),
            "{e}"
        );
    }

    #[test]
    fn names_must_be_unique_and_usable_in_file_names() {
        let names = [String::from("a"), String::from("b"), String::from("a")];
        let e = err(unique_names(keyed("probes", &names, |n| n)));
        assert!(e.contains("probes[2].name = \"a\"") && e.contains("already used by probes[0]"), "{e}");
        let bad = [String::from("a/b")];
        assert!(err(unique_names(keyed("lines", &bad, |n| n))).contains("file names"));
        // a constraint named "probes" wrote its history over the probes'
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilever_timoshenko.toml"))
            .unwrap()
            .replace("name = \"root\"", "name = \"probes\"");
        let e = crate::setup::Model::parse(&text).map(|_| ()).unwrap_err().to_string();
        assert!(e.starts_with("constraints[0].name = \"probes\"") && e.contains("history_probes.csv"), "{e}");
    }

    #[test]
    fn penalties_are_one_of_two_forms() {
        assert_eq!(penalty("c", None, None).unwrap(), Penalty::Factor(contact::DEFAULT_PENALTY_FACTOR));
        assert_eq!(penalty("c", None, Some(1e3)).unwrap(), Penalty::Factor(1e3));
        assert!(err(penalty("c", Some(1e12), Some(1e3))).contains("at most one of them"));
        assert!(err(penalty("c", None, Some(1e12))).contains("c.penalty_factor"));
    }
}
