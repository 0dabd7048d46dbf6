//! The ranges of the model file's numbers that are plain intervals, in one
//! table read twice: by the validation, which refuses a value outside one
//! (naming the key, the value and the range), and by the JSON Schema of the
//! model file (`cufem schema`, `schema/json.rs`), which states it as
//! `minimum`/`maximum` (`exclusiveMinimum`/`exclusiveMaximum` for an open
//! end) so that an editor flags the value as it is typed. A bound that
//! depends on another value (a yield stress at most a tenth of E, a
//! displacement at most the body's size) is the validation's alone; the
//! table holds what can be said of the key by itself.

use std::fmt;

use schemars::Schema;
use serde_json::{Map, Value};

use super::bounds::{self, DENSITY, GRADING_RATIO, MAX_COORD, MAX_POISSON, MAX_YOUNG, MIN_YOUNG, PENALTY_FACTOR};
use super::{ModelError, invalid};
use crate::numbers::number;

/// An interval of accepted values; an infinite end is unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower end.
    pub min: f64,
    /// Upper end.
    pub max: f64,
    /// Whether `min` itself is refused.
    pub min_open: bool,
    /// Whether `max` itself is refused.
    pub max_open: bool,
}

impl Range {
    /// `[min, max]`.
    pub const fn closed(min: f64, max: f64) -> Self {
        Range { min, max, min_open: false, max_open: false }
    }

    /// `(min, max)`.
    pub const fn open(min: f64, max: f64) -> Self {
        Range { min, max, min_open: true, max_open: true }
    }

    /// `(min, max]`.
    pub(crate) const fn above_up_to(min: f64, max: f64) -> Self {
        Range { min, max, min_open: true, max_open: false }
    }

    /// `[min, ∞)`.
    pub(crate) const fn at_least(min: f64) -> Self {
        Range::closed(min, f64::INFINITY)
    }

    /// `(min, ∞)`.
    pub const fn above(min: f64) -> Self {
        Range::open(min, f64::INFINITY)
    }

    /// `v` is finite and in the range.
    pub fn contains(&self, v: f64) -> bool {
        let above = if self.min_open { v > self.min } else { v >= self.min };
        let below = if self.max_open { v < self.max } else { v <= self.max };
        v.is_finite() && above && below
    }

    /// `n` is in the range.
    pub(crate) fn contains_count(&self, n: usize) -> bool {
        self.contains(n as f64)
    }

    /// `v` if it is in the range, else an error naming `key`, `v`, the
    /// range and `why` (a closed range reads as [`bounds::within`] says it).
    pub fn check(&self, key: &str, v: f64, why: &str) -> Result<f64, ModelError> {
        if !(self.min_open || self.max_open) && self.min.is_finite() && self.max.is_finite() {
            return bounds::within(key, v, self.min, self.max, why);
        }
        if self.contains(v) { Ok(v) } else { Err(invalid(key, number(v), format!("a number {self} ({why})"))) }
    }

    /// The schema transform that writes the range on a number's schema (a
    /// field attribute `#[schemars(transform = RANGE.schema())]`).
    pub fn schema(self) -> impl FnMut(&mut Schema) {
        move |s| self.write(s.ensure_object())
    }

    /// [`Range::schema`] and the key's `default` ([`super::defaults`]).
    pub(crate) fn with_default<T: serde::Serialize>(self, value: T) -> impl FnMut(&mut Schema) {
        let mut default = super::defaults::schema(value);
        move |s| {
            self.write(s.ensure_object());
            default(s);
        }
    }

    /// The schema transform that writes the range on the innermost items
    /// of an array (of arrays) of numbers: a point's coordinates.
    pub fn items(self) -> impl FnMut(&mut Schema) {
        move |s| {
            let mut at = s.as_object_mut();
            while let Some(Value::Object(items)) = at.and_then(|o| o.get_mut("items")) {
                if items.contains_key("items") {
                    at = Some(items);
                } else {
                    self.write(items);
                    return;
                }
            }
        }
    }

    /// The schema transform that writes the range on the values of a table
    /// whose keys are names (`steps.factors`).
    pub fn values(self) -> impl FnMut(&mut Schema) {
        move |s| {
            if let Some(Value::Object(v)) = s.ensure_object().get_mut("additionalProperties") {
                self.write(v);
            }
        }
    }

    fn write(&self, s: &mut Map<String, Value>) {
        let json = |v: f64| {
            if v.fract() == 0.0 && v.abs() < 1e15 { Value::from(v as i64) } else { Value::from(v) }
        };
        for (value, open, closed_key, open_key) in [
            (self.min, self.min_open, "minimum", "exclusiveMinimum"),
            (self.max, self.max_open, "maximum", "exclusiveMaximum"),
        ] {
            s.remove(closed_key);
            s.remove(open_key);
            if value.is_finite() {
                s.insert(if open { open_key } else { closed_key }.to_string(), json(value));
            }
        }
    }
}

/// As the model-format document writes it: `in (0, 1]`, `≥ 1`, `> 0`.
impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let show = number;
        match (self.min.is_finite(), self.max.is_finite()) {
            (true, false) => write!(f, "{} {}", if self.min_open { ">" } else { "≥" }, show(self.min)),
            (false, true) => write!(f, "{} {}", if self.max_open { "<" } else { "≤" }, show(self.max)),
            _ => write!(
                f,
                "in {}{}, {}{}",
                if self.min_open { '(' } else { '[' },
                show(self.min),
                show(self.max),
                if self.max_open { ')' } else { ']' }
            ),
        }
    }
}

/// Largest element count per division and per tube side, and sample count
/// per line: far beyond any useful model, small enough to allocate.
pub(crate) const MAX_COUNT: usize = 100_000;
/// Largest number of buckling modes one run may ask for.
pub(crate) const MAX_MODES: usize = 50;
/// Longest accepted step duration (s).
pub(crate) const MAX_DURATION: f64 = 1e6;
/// Largest accepted initial speed (m/s).
pub(crate) const MAX_SPEED: f64 = 1e4;
/// Largest `max_cycles`: each refinement at least adds an interval, and
/// twenty are more than any budget allows.
pub(crate) const MAX_CYCLES: usize = 20;
/// Largest `max_dof` accepted (a budget, not a promise: memory is checked
/// for every mesh as for any model).
pub const MAX_BUDGET: usize = 100_000_000;

// Counts.

/// A count of at least one (increments, iterations, threads).
pub(crate) const AT_LEAST_ONE: Range = Range::at_least(1.0);
/// Elements per division, wall or ply, and increments of a step.
pub(crate) const COUNT: Range = Range::closed(1.0, MAX_COUNT as f64);
/// Samples along a line, both ends included.
pub(crate) const LINE_POINTS: Range = Range::closed(2.0, MAX_COUNT as f64);
/// Buckling or vibration modes (`analysis.modes`, `analysis.imperfection.mode`).
pub(crate) const MODES: Range = Range::closed(1.0, MAX_MODES as f64);
/// Cells of a `box` section side by side.
pub(crate) const CELLS: Range = Range::closed(1.0, crate::mesh::profiles::MAX_CELLS as f64);

// Lengths and positions (m).

/// A coordinate (m): a structure larger than 10 km is not plausible.
pub(crate) const COORDINATE: Range = Range::closed(-MAX_COORD, MAX_COORD);
/// A length (m): positive, at most the largest coordinate.
pub(crate) const LENGTH: Range = Range::above_up_to(0.0, MAX_COORD);
/// Any positive number (a tolerance in m, a penetration, an arc length).
pub(crate) const POSITIVE: Range = Range::above(0.0);
/// Any number ≥ 0 (a hardening modulus, a back-stress recall).
pub(crate) const NON_NEGATIVE: Range = Range::at_least(0.0);

// Materials.

/// Young's modulus and the orthotropic moduli (Pa).
pub(crate) const YOUNG_MODULUS: Range = Range::closed(MIN_YOUNG, MAX_YOUNG);
/// Poisson's ratio of an isotropic material.
pub(crate) const POISSON_RATIO: Range = Range::above_up_to(-1.0, MAX_POISSON);
/// An orthotropic Poisson's ratio ν_ij (admissible with the moduli).
pub(crate) const ORTHOTROPIC_POISSON: Range = Range::open(-10.0, 10.0);
/// A strength (Pa, compressive ones as magnitudes).
pub(crate) const STRENGTH: Range = Range::above_up_to(0.0, MAX_YOUNG);
/// Mass density (kg/m³), from aerogels to ten times osmium.
pub(crate) const MASS_DENSITY: Range = Range::closed(DENSITY.0, DENSITY.1);
/// Voce's saturation rate b.
pub(crate) const SATURATION_RATE: Range = Range::closed(1e-6, 1e6);
/// The recall rate γ of a back-stress (0: linear kinematic hardening).
pub(crate) const KINEMATIC_RECALL: Range = Range::closed(0.0, 1e6);
/// A ply's or a zone's angle (degrees).
pub(crate) const ANGLE: Range = Range::closed(-360.0, 360.0);

// Meshes.

/// Last over first element length of a graded division.
pub(crate) const RATIO: Range = Range::closed(GRADING_RATIO.0, GRADING_RATIO.1);
/// Factor applied to a gmsh file's coordinates.
pub(crate) const GMSH_SCALE: Range = Range::closed(1e-9, 1e9);

// Contact.

/// Penalty per area (Pa/m).
pub(crate) const PENALTY: Range = Range::above_up_to(0.0, 1.3407807929942596e154);
/// The dimensionless penalty factor α.
pub(crate) const PENALTY_FACTOR_RANGE: Range = Range::closed(PENALTY_FACTOR.0, PENALTY_FACTOR.1);
/// Coulomb's coefficient of friction μ.
pub(crate) const FRICTION: Range = Range::closed(0.0, 10.0);

// Cohesive interfaces.

/// A cohesive toughness `gic`, `giic` (J/m²): from brittle resins to far
/// beyond any laminate.
pub(crate) const TOUGHNESS: Range = Range::above_up_to(0.0, 1e6);
/// The Benzeggagh–Kenane exponent η (measured values lie between 1 and 3).
pub(crate) const BK_EXPONENT: Range = Range::closed(0.5, 10.0);
/// A cohesive penalty (Pa/m): Turon et al.'s 50 E3/t spans about 1e13 to
/// 1e16 for plies of 0.1–10 mm.
pub(crate) const COHESIVE_PENALTY: Range = Range::closed(1e10, 1e18);
/// A cohesive Duvaut–Lions viscosity in load-factor units: 0 (none) up to
/// the whole load step.
pub(crate) const COHESIVE_VISCOSITY: Range = Range::closed(0.0, 1.0);

// Ply damage.

/// A ply's fracture energy per mode (J/m²): from brittle resins to far
/// beyond the fibre tension of any laminate.
pub(crate) const FRACTURE_ENERGY: Range = Range::above_up_to(0.0, 1e7);
/// The largest damage of a ply mode: at least 0.9 (a softening that stops
/// earlier is not a crack), below 1 by at least 1e-5 (the damaged
/// stiffness stays definite).
pub(crate) const MAX_DAMAGE: Range = Range::closed(0.9, 0.99999);
/// A ply damage's Duvaut–Lions viscosity in load-factor units: 0 (none) up
/// to the whole load step.
pub(crate) const DAMAGE_VISCOSITY: Range = Range::closed(0.0, 1.0);
/// The weight α of the longitudinal shear in fibre tension (Abaqus's α):
/// none to Hashin's whole term.
pub(crate) const FIBRE_SHEAR: Range = Range::closed(0.0, 1.0);
/// An impactor's mass (kg; at least a billionth of the body's, checked apart).
pub(crate) const IMPACTOR_MASS: Range = Range::above_up_to(0.0, 1e9);

// Increments, tolerances and the load history.

/// A share of the load step: an increment Δλ.
pub(crate) const FRACTION: Range = Range::above_up_to(0.0, 1.0);
/// A relative tolerance.
pub(crate) const TOLERANCE: Range = Range::open(0.0, 1.0);
/// Δλ multiplier after a failed attempt (1 would retry the same increment).
pub(crate) const CUTBACK_FACTOR: Range = Range::open(0.0, 1.0);
/// Δλ multiplier after an easy increment.
pub(crate) const GROWTH_FACTOR: Range = Range::at_least(1.0);
/// Target increment of the equivalent plastic strain per load increment.
pub(crate) const PLASTIC_STRAIN_STEP: Range = Range::above_up_to(0.0, 0.1);
/// Target of a time step's local error relative to the displacement scale
/// (`dynamics::time_error`).
pub(crate) const TIME_ERROR: Range = Range::above_up_to(0.0, 0.1);
/// The load factor at which path following ends.
pub(crate) const MAX_LOAD_FACTOR: Range = Range::above_up_to(0.0, 1000.0);
/// A step's factor of the items' values.
pub(crate) const STEP_FACTOR: Range = Range::closed(-1e3, 1e3);
/// The time of a load step (s).
pub(crate) const DURATION: Range = Range::above_up_to(0.0, MAX_DURATION);
/// Newmark's γ (γ ≥ ½ for stability).
pub(crate) const NEWMARK_GAMMA: Range = Range::closed(0.5, 1.0);
/// Bossak's α (Wood, Bossak & Zienkiewicz 1980): 0 is Newmark's method,
/// −⅓ the most dissipative of the usual range.
pub(crate) const BOSSAK_ALPHA: Range = Range::closed(-1.0 / 3.0, 0.0);
/// Rayleigh's α_M (1/s).
pub(crate) const DAMPING_MASS: Range = Range::closed(0.0, 1e9);
/// Rayleigh's β_K (s).
pub(crate) const DAMPING_STIFFNESS: Range = Range::closed(0.0, 1e3);
/// A component of an initial velocity (m/s).
pub(crate) const SPEED: Range = Range::closed(-MAX_SPEED, MAX_SPEED);

// Adaptive refinement.

/// The relative error in the energy norm at which refinement stops.
pub(crate) const ADAPT_TOLERANCE: Range = Range::open(0.0, 1.0);
/// The most DOF of a refined mesh.
pub(crate) const ADAPT_MAX_DOF: Range = Range::closed(1.0, MAX_BUDGET as f64);
/// The most refinements after the model's own mesh.
pub(crate) const ADAPT_MAX_CYCLES: Range = Range::closed(0.0, MAX_CYCLES as f64);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_are_kept_or_refused_as_written() {
        assert!(FRACTION.contains(1.0) && !FRACTION.contains(0.0) && !FRACTION.contains(f64::NAN));
        assert!(CUTBACK_FACTOR.contains(0.5) && !CUTBACK_FACTOR.contains(1.0));
        assert!(GROWTH_FACTOR.contains(1.0) && GROWTH_FACTOR.contains(1e300) && !GROWTH_FACTOR.contains(f64::INFINITY));
        assert_eq!(FRACTION.to_string(), "in (0, 1]");
        assert_eq!(AT_LEAST_ONE.to_string(), "≥ 1");
        assert_eq!(POSITIVE.to_string(), "> 0");
        assert_eq!(FRICTION.to_string(), "in [0, 10]");
        assert_eq!(PLASTIC_STRAIN_STEP.to_string(), "in (0, 0.1]");
        let e = CUTBACK_FACTOR.check("k", 1.0, "why").unwrap_err().to_string();
        assert!(e.contains("k = 1: expected a number in (0, 1) (why)"), "{e}");
    }

    #[test]
    fn the_schema_gets_the_same_ends() {
        let mut s = schemars::json_schema!({ "type": "number" });
        FRACTION.schema()(&mut s);
        assert_eq!(s.as_value(), &serde_json::json!({ "type": "number", "exclusiveMinimum": 0, "maximum": 1 }));
        let mut s = schemars::json_schema!({ "type": "integer", "minimum": 0 });
        AT_LEAST_ONE.schema()(&mut s);
        assert_eq!(s.as_value(), &serde_json::json!({ "type": "integer", "minimum": 1 }));
        let mut s =
            schemars::json_schema!({ "type": "array", "items": { "type": "array", "items": { "type": "number" } } });
        COORDINATE.items()(&mut s);
        assert_eq!(s.pointer("/items/items/maximum"), Some(&serde_json::json!(10000)));
    }
}
