//! The load history (`[[steps]]`): an ordered list of steps, each ramping
//! every loading item — rigid indenter displacement, prescribed constraint
//! values, loads — linearly from its factor at the end of the previous step
//! to its factor at the end of this one, like piecewise-linear amplitudes of
//! Abaqus/CalculiX steps. State (displacements, plastic history, contact) is
//! carried from step to step.
//!
//! Analysis time: step `k` (0-based) spans `λ ∈ [k, k + 1]`; the factor of an
//! item at `λ` is `a_{k−1} + (λ − k)(a_k − a_{k−1})`, `a_{−1} = 0`. Without
//! `[[steps]]` there is one step, every factor 1: the classic ramp
//! `λ ∈ [0, 1]`.

use std::collections::BTreeMap;

use super::Warning;
use crate::bc::Constraint;
use crate::input::schema::StepFile;
use crate::input::validate::count;
use crate::input::{ModelError, invalid, ranges};
use crate::solver::stepping::StepSettings;

/// A loading item a step can scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Item {
    /// `indenters[i]`: its rigid displacement.
    Indenter(usize),
    /// `constraints[i]`: its non-zero prescribed values.
    Constraint(usize),
    /// `loads[i]`: its forces.
    Load(usize),
    /// `levers[i]`: its prescribed displacement.
    Lever(usize),
}

/// One step of the load history.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Name (used in output file names and `summary.json`).
    pub name: String,
    /// Increment controls, in λ units (a step has length 1).
    pub settings: StepSettings,
    /// Factor of each indenter at the end of the step.
    pub indenters: Vec<f64>,
    /// Factor of each constraint at the end of the step.
    pub constraints: Vec<f64>,
    /// Factor of each load at the end of the step.
    pub loads: Vec<f64>,
    /// Factor of each lever at the end of the step.
    pub levers: Vec<f64>,
}

impl Step {
    /// The fewest increments that cover the step, `⌈1 / max_increment⌉`:
    /// a transient step's time steps without cutbacks.
    pub fn planned_increments(&self) -> usize {
        (1.0 / self.settings.max * (1.0 - 1e-9)).ceil().max(1.0) as usize
    }

    /// The item's factor at the end of the step; 1 for an item added to the
    /// model after validation (code that builds constraints or loads itself).
    fn target(&self, item: Item) -> f64 {
        let list = match item {
            Item::Indenter(_) => &self.indenters,
            Item::Constraint(_) => &self.constraints,
            Item::Load(_) => &self.loads,
            Item::Lever(_) => &self.levers,
        };
        let (Item::Indenter(i) | Item::Constraint(i) | Item::Load(i) | Item::Lever(i)) = item;
        list.get(i).copied().unwrap_or(1.0)
    }
}

/// The factor of `item` at analysis time `lambda` (see the module docs).
/// Outside `[0, n]` the first and last steps are extended linearly: load
/// stepping never goes there, path following (`solver.control =
/// "arc_length"`, one step) may pass λ = 1 or turn back below 0.
pub fn factor(steps: &[Step], item: Item, lambda: f64) -> f64 {
    if steps.is_empty() {
        return lambda;
    }
    let t = lambda.clamp(0.0, steps.len() as f64);
    let k = (t.ceil() as usize).clamp(1, steps.len()) - 1;
    let before = if k == 0 { 0.0 } else { steps[k - 1].target(item) };
    before + (lambda - k as f64) * (steps[k].target(item) - before)
}

/// The factors of `item` at the start and the end of step `k` (from 0).
fn ramp(steps: &[Step], k: usize, item: Item) -> (f64, f64) {
    let before = k.checked_sub(1).and_then(|j| steps.get(j)).map_or(0.0, |s| s.target(item));
    (before, steps.get(k).map_or(before, |s| s.target(item)))
}

/// True if the item's factor first moves towards zero over step `k`: the
/// step takes that load back (`1 → 0.5`, `−1 → −0.5`, a reversal `1 → −1`).
pub(crate) fn takes_back(steps: &[Step], k: usize, item: Item) -> bool {
    let (x, y) = ramp(steps, k, item);
    x != 0.0 && (y - x) * x < 0.0
}

/// Every item of step `k`, for [`unloads`] and [`loads_more`].
fn items(steps: &[Step], k: usize) -> impl Iterator<Item = Item> + '_ {
    let step = steps.get(k);
    let n = |list: fn(&Step) -> &Vec<f64>| step.map_or(0, |s| list(s).len());
    (0..n(|s| &s.indenters))
        .map(Item::Indenter)
        .chain((0..n(|s| &s.constraints)).map(Item::Constraint))
        .chain((0..n(|s| &s.loads)).map(Item::Load))
        .chain((0..n(|s| &s.levers)).map(Item::Lever))
}

/// True if step `k` (from 0) takes some load back ([`takes_back`]).
pub(crate) fn unloads(steps: &[Step], k: usize) -> bool {
    items(steps, k).any(|item| takes_back(steps, k, item))
}

/// True if step `k` moves some item's factor away from zero (more load),
/// other than `except`.
pub(crate) fn loads_more(steps: &[Step], k: usize, except: Item) -> bool {
    items(steps, k).filter(|&item| item != except).any(|item| {
        let (x, y) = ramp(steps, k, item);
        (x == 0.0 && y != 0.0) || (y - x) * x > 0.0
    })
}

/// The step (from 0) that analysis time `lambda` lies in.
pub(crate) fn step_at(steps: &[Step], lambda: f64) -> usize {
    (lambda.ceil().max(1.0) as usize).min(steps.len().max(1)) - 1
}

/// Names of the items a step may scale, in model order.
pub(crate) struct ItemNames<'a> {
    /// Indenter names.
    pub indenters: Vec<&'a str>,
    /// Constraint names.
    pub constraints: Vec<&'a str>,
    /// Load names.
    pub loads: Vec<&'a str>,
    /// Lever names.
    pub levers: Vec<&'a str>,
    /// Which indenters are force-controlled (their force must push).
    pub pushing: Vec<bool>,
}

/// Validates `[[steps]]` against the model's item names; `base` holds the
/// `[solver]` increment controls that a step does not override.
pub(super) fn steps(file: &[StepFile], names: &ItemNames, base: &StepSettings) -> Result<Vec<Step>, ModelError> {
    let ones = |n: usize| vec![1.0; n];
    if file.is_empty() {
        return Ok(vec![Step {
            name: "load".into(),
            settings: *base,
            indenters: ones(names.indenters.len()),
            constraints: ones(names.constraints.len()),
            loads: ones(names.loads.len()),
            levers: ones(names.levers.len()),
        }]);
    }
    let mut out: Vec<Step> = Vec::new();
    for (k, s) in file.iter().enumerate() {
        let key = format!("steps[{k}]");
        if s.name.is_empty() || !s.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
            return Err(invalid(
                format!("{key}.name"),
                format!("{:?}", s.name),
                "a non-empty name of letters, digits, _ and -",
            ));
        }
        if let Some(j) = out.iter().position(|o| o.name == s.name) {
            return Err(invalid(
                format!("{key}.name"),
                format!("{:?}", s.name),
                format!("a name not used by steps[{j}]"),
            ));
        }
        let default = s.factor.unwrap_or(crate::input::defaults::STEP_FACTOR);
        check_factor(&format!("{key}.factor"), default)?;
        let mut step = Step {
            name: s.name.clone(),
            settings: settings(&key, s, base)?,
            indenters: vec![default; names.indenters.len()],
            constraints: vec![default; names.constraints.len()],
            loads: vec![default; names.loads.len()],
            levers: vec![default; names.levers.len()],
        };
        for (name, &v) in s.factors.as_ref().unwrap_or(&BTreeMap::new()) {
            let fk = format!("{key}.factors.{name}");
            check_factor(&fk, v)?;
            let slot = if let Some(i) = names.indenters.iter().position(|n| n == name) {
                &mut step.indenters[i]
            } else if let Some(i) = names.constraints.iter().position(|n| n == name) {
                &mut step.constraints[i]
            } else if let Some(i) = names.loads.iter().position(|n| n == name) {
                &mut step.loads[i]
            } else if let Some(i) = names.levers.iter().position(|n| n == name) {
                &mut step.levers[i]
            } else {
                let all: Vec<&str> = names
                    .indenters
                    .iter()
                    .chain(&names.constraints)
                    .chain(&names.loads)
                    .chain(&names.levers)
                    .copied()
                    .collect();
                return Err(invalid(
                    fk,
                    v,
                    format!("the name of an indenter, constraint, load or lever: one of {all:?}"),
                ));
            };
            *slot = v;
        }
        pulled(&key, s, &step, names)?;
        out.push(step);
    }
    Ok(out)
}

/// A force-controlled indenter's force must push the body
/// (`setup/indenters.rs`): a negative factor would turn it into a pull,
/// which a contact cannot carry (the run stalled at the factor's first
/// increment with a bare "Newton did not converge"; a new-user review).
fn pulled(key: &str, s: &StepFile, step: &Step, names: &ItemNames<'_>) -> Result<(), ModelError> {
    let Some(i) = (0..step.indenters.len()).find(|&i| names.pushing[i] && step.indenters[i] < 0.0) else {
        return Ok(());
    };
    let name = names.indenters[i];
    let own = s.factors.as_ref().is_some_and(|f| f.contains_key(name));
    let fk = if own { format!("{key}.factors.{name}") } else { format!("{key}.factor") };
    Err(invalid(
        fk,
        step.indenters[i],
        format!(
            "a factor of at least 0 for indenter {name:?}: its force pushes the body, which a negative factor \
             would turn into a pull that a contact cannot carry (0 releases it)"
        ),
    ))
}

/// A step's own factor for a constraint that only fixes components at 0
/// (`fix`) changes nothing: `0 × factor` stays 0, so such a support cannot
/// be released by a step (a new-user review wrote `factors = { root = 0.0 }`
/// to let go of a clamp, and it held in silence). Warned by the key; the
/// step-wide `factor` is not, as it scales every item alike.
pub(super) fn idle_constraint_factors(file: &[StepFile], constraints: &[Constraint], warnings: &mut Vec<Warning>) {
    for (k, s) in file.iter().enumerate() {
        for (name, &v) in s.factors.as_ref().unwrap_or(&BTreeMap::new()) {
            let fixing = constraints
                .iter()
                .find(|c| &c.name == name)
                .is_some_and(|c| c.values.iter().flatten().all(|&x| x == 0.0));
            if fixing && v != 1.0 {
                warnings.push(Warning {
                    key: format!("steps[{k}].factors.{name}"),
                    message: format!(
                        "{} leaves constraint {name:?} as it is: it only fixes components at 0 (`fix`), which a \
                         factor does not change, so it holds in this step as in every other (a step cannot \
                         release a support; to move it, give it a non-zero `displacement`)",
                        crate::numbers::short(v)
                    ),
                });
            }
        }
    }
}

fn check_factor(key: &str, v: f64) -> Result<(), ModelError> {
    ranges::STEP_FACTOR.check(key, v, "a factor of the item's value given in the model; 0 releases it").map(|_| ())
}

/// The step's increment controls: `increments`, `max_increment` and
/// `min_increment` as fractions of the step, the rest from `[solver]`.
fn settings(key: &str, s: &StepFile, base: &StepSettings) -> Result<StepSettings, ModelError> {
    let mut out = *base;
    if let Some(n) = s.increments {
        let n = count(&format!("{key}.increments"), n)?;
        out.initial = 1.0 / n as f64;
        // with a step control the step's increments grow as its measures allow
        if out.control.is_none() {
            out.max = out.initial;
        }
        out.min = out.min.min(1e-4 * out.initial);
    }
    for (name, value, slot) in
        [("max_increment", s.max_increment, &mut out.max), ("min_increment", s.min_increment, &mut out.min)]
    {
        if let Some(v) = value {
            if !ranges::FRACTION.contains(v) {
                return Err(invalid(
                    format!("{key}.{name}"),
                    v,
                    format!("a fraction of the step {}", ranges::FRACTION),
                ));
            }
            *slot = v;
        }
    }
    out.initial = out.initial.min(out.max);
    if out.min > out.initial {
        return Err(invalid(
            format!("{key}.min_increment"),
            out.min,
            format!("at most the first increment ({})", out.initial),
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(name: &str, toml_text: &str) -> StepFile {
        toml::from_str(&format!("name = \"{name}\"\n{toml_text}")).unwrap()
    }

    #[test]
    fn factors_ramp_hold_and_release_piecewise_linearly() {
        let names = ItemNames {
            indenters: vec!["punch"],
            constraints: vec!["root"],
            loads: vec!["tip"],
            levers: vec![],
            pushing: vec![false],
        };
        let base = StepSettings::default();
        let file = [
            step("load", "increments = 4"),
            step("hold", ""),
            step("unload", "factor = 0.0\nfactors = { root = 1.0 }"),
        ];
        let s = steps(&file, &names, &base).unwrap();
        assert_eq!(s.len(), 3);
        assert_eq!(s[0].settings.initial, 0.25);
        let punch = Item::Indenter(0);
        assert_eq!(factor(&s, punch, 0.0), 0.0);
        assert_eq!(factor(&s, punch, 0.5), 0.5);
        assert_eq!(factor(&s, punch, 1.5), 1.0); // hold
        assert_eq!(factor(&s, punch, 2.25), 0.75); // unload
        assert_eq!(factor(&s, punch, 3.0), 0.0);
        assert_eq!(factor(&s, Item::Constraint(0), 2.5), 1.0); // kept by name
        assert_eq!(factor(&s, Item::Load(0), 2.5), 0.5);
        // no [[steps]]: one ramp to 1
        let one = steps(&[], &names, &base).unwrap();
        assert_eq!(factor(&one, Item::Load(0), 0.3), 0.3);
        // beyond the history (path following): the end steps extended
        assert_eq!(factor(&one, Item::Load(0), 1.5), 1.5);
        assert_eq!(factor(&one, Item::Load(0), -0.25), -0.25);
        assert_eq!(factor(&s, punch, 3.5), -0.5);
    }

    /// Which steps take load back, and which add some: a hold, a ramp
    /// towards zero of either sign, a reversal through zero, a step that
    /// starts from zero, and a step that takes one item back while it
    /// pushes another further.
    #[test]
    fn unloading_steps_are_told_from_loading_ones() {
        let names = ItemNames {
            indenters: vec!["punch"],
            constraints: vec![],
            loads: vec!["tip"],
            levers: vec![],
            pushing: vec![false],
        };
        let base = StepSettings::default();
        let file = [
            step("pull", "factor = -1.0"),
            step("ease", "factor = -0.5"),
            step("hold", "factor = -0.5"),
            step("reverse", "factor = 1.0"),
            step("swap", "factors = { punch = 0.0, tip = 2.0 }"),
            step("restart", "factors = { punch = 1.0, tip = 2.0 }"),
        ];
        let s = steps(&file, &names, &base).unwrap();
        let (punch, tip) = (Item::Indenter(0), Item::Load(0));
        assert_eq!((0..6).map(|k| unloads(&s, k)).collect::<Vec<_>>(), [false, true, false, true, true, false]);
        assert!(takes_back(&s, 4, punch) && !takes_back(&s, 4, tip));
        assert!(loads_more(&s, 4, punch) && !loads_more(&s, 1, punch) && !loads_more(&s, 2, punch));
        assert!(loads_more(&s, 5, tip), "0 → 1 adds load");
        assert_eq!([0.5, 1.0, 1.5, 6.0, 7.0].map(|l| step_at(&s, l)), [0, 0, 1, 5, 5]);
    }

    #[test]
    fn bad_steps_name_the_key() {
        let names = ItemNames {
            indenters: vec!["punch"],
            constraints: vec![],
            loads: vec![],
            levers: vec![],
            pushing: vec![false],
        };
        let base = StepSettings::default();
        let cases = [
            (
                vec![step("a", "factors = { pnuch = 0.0 }")],
                "steps[0].factors.pnuch = 0: expected the name of an indenter",
            ),
            (vec![step("a", ""), step("a", "")], "steps[1].name = \"a\""),
            (vec![step("a b", "")], "steps[0].name"),
            (vec![step("a", "factor = 1e9")], "steps[0].factor = 1e9"),
            (vec![step("a", "increments = 0")], "steps[0].increments = 0"),
            (vec![step("a", "max_increment = 2.0")], "steps[0].max_increment = 2"),
        ];
        for (file, expect) in cases {
            let e = steps(&file, &names, &base).unwrap_err().to_string();
            assert!(e.starts_with(expect), "{e}");
        }
    }

    /// A force-controlled indenter reversed by a step's factor stalled the
    /// run (a new-user review): refused by the key that reverses it; a
    /// displacement-controlled one may go back, and 0 releases either.
    #[test]
    fn a_pushing_indenter_is_not_reversed() {
        let names = |pushing| ItemNames {
            indenters: vec!["punch"],
            constraints: vec![],
            loads: vec![],
            levers: vec![],
            pushing: vec![pushing],
        };
        let base = StepSettings::default();
        let back = [step("load", ""), step("back", "factor = -1.0")];
        let own = [step("load", ""), step("back", "factors = { punch = -0.5 }")];
        let release = [step("load", ""), step("off", "factor = 0.0")];
        for (file, expect) in [(&back, "steps[1].factor = -1: "), (&own, "steps[1].factors.punch = -0.5: ")] {
            let e = steps(file, &names(true), &base).unwrap_err().to_string();
            assert!(e.starts_with(expect) && e.contains("at least 0 for indenter \"punch\""), "{e}");
            steps(file, &names(false), &base).unwrap();
        }
        steps(&release, &names(true), &base).unwrap();
    }
}
