//! The values the model file's keys take when they are left out, where the
//! value is a constant: read by the validation (`unwrap_or(…)`) and written
//! into the JSON Schema as the key's `default` (`#[schemars(transform =
//! defaults::schema(…))]`), so an editor shows the value the reader will
//! use. A default that depends on the model (the first increment of a
//! linear model, the number of modes of a buckling or a modal analysis, a
//! tolerance relative to the body's size) is the validation's alone. The
//! words' defaults are their enums' `#[default]` variants.

use schemars::Schema;
use serde::Serialize;

/// The schema transform that writes `value` as the key's `default`.
pub fn schema<T: Serialize>(value: T) -> impl FnMut(&mut Schema) {
    let value = serde_json::to_value(value).unwrap_or_default();
    move |s| {
        s.insert("default".into(), value.clone());
    }
}

// [solver]

/// Converged increments of a load step (a transient one adds its time steps).
pub(crate) const MAX_INCREMENTS: usize = 1000;
/// Newton corrections per attempt.
pub(crate) const MAX_ITERATIONS: usize = 25;
/// An increment converging in at most this many iterations is easy.
pub(crate) const EASY_ITERATIONS: usize = 4;
/// Δλ multiplier after a failed attempt.
pub(crate) const CUTBACK_FACTOR: f64 = 0.5;
/// Δλ multiplier after an easy increment.
pub(crate) const GROWTH_FACTOR: f64 = 1.5;
/// Relative residual of convergence.
pub(crate) const RESIDUAL_TOLERANCE: f64 = 1e-6;
/// Relative correction of convergence.
pub(crate) const DISPLACEMENT_TOLERANCE: f64 = 1e-6;
/// Solve by PCG on the last factorization while it converges.
pub(crate) const REUSE_FACTORIZATION: bool = true;
/// No line search.
pub(crate) const LINE_SEARCH: bool = false;
/// Path following ends at λ = 1.
pub(crate) const MAX_LOAD_FACTOR: f64 = 1.0;

// The top level.

/// The title printed in reports.
pub(crate) const TITLE: &str = "cufem model";
/// No description.
pub(crate) const DESCRIPTION: &str = "";

// [output]

/// Write `result.vtu`.
pub const VTU: bool = true;
/// Write the PNG plots.
pub(crate) const PLOTS: bool = true;
/// No `gauss.vtu`.
pub(crate) const GAUSS_POINTS: bool = false;
/// Write `report.html`.
pub(crate) const REPORT: bool = true;

// [adapt]

/// Stop below this relative error estimate.
pub(crate) const ADAPT_TOLERANCE: f64 = 0.05;
/// No mesh with more DOF is solved.
pub(crate) const ADAPT_MAX_DOF: usize = 50_000;
/// Refinements after the model's own mesh.
pub(crate) const ADAPT_MAX_CYCLES: usize = 5;
/// Dörfler's bulk parameter θ.
pub(crate) const ADAPT_FRACTION: f64 = 0.5;

// [analysis]

/// Newmark's β: with γ = ½, the trapezoidal rule.
pub(crate) const NEWMARK_BETA: f64 = 0.25;
/// Newmark's γ.
pub(crate) const NEWMARK_GAMMA: f64 = 0.5;

/// Bossak's α: Newmark's method.
pub(crate) const BOSSAK_ALPHA: f64 = 0.0;

/// `newmark = { beta, gamma, alpha }` when left out.
#[derive(Serialize)]
pub struct Newmark {
    /// β.
    pub beta: f64,
    /// γ.
    pub gamma: f64,
    /// Bossak's α.
    pub alpha: f64,
}

/// The default Newmark parameters, as the model file writes them.
pub(crate) const NEWMARK: Newmark = Newmark { beta: NEWMARK_BETA, gamma: NEWMARK_GAMMA, alpha: BOSSAK_ALPHA };

// Load history, lines, contacts.

/// A step's factor of every item.
pub(crate) const STEP_FACTOR: f64 = 1.0;
/// Samples along a line.
pub(crate) const LINE_POINTS: usize = 101;
/// No interference fit.
pub(crate) const INTERFERENCE: bool = false;

// Sections.

/// A section's `origin` or `center` `[x, z]` (m).
pub(crate) const ORIGIN: [f64; 2] = [0.0, 0.0];
/// Elements through a wall.
pub(crate) const THROUGH: usize = 1;
/// Elements along each flange part of a profile.
pub(crate) const ALONG_FLANGE: usize = 2;
/// Elements along each web of a profile.
pub(crate) const ALONG_WEB: usize = 4;
/// Elements along each lip of a hat.
pub(crate) const ALONG_LIP: usize = 1;
/// Cells of a box.
pub(crate) const CELLS: usize = 1;
/// Elements around a circle or a circular tube.
pub(crate) const AROUND: usize = 16;
/// Factor on a gmsh file's coordinates.
pub(crate) const GMSH_SCALE: f64 = 1.0;
/// The bottom of a laminate (m).
pub(crate) const Z0: f64 = 0.0;

// Zones and plies.

/// A zone's or a ply's angle (degrees).
pub(crate) const ANGLE: f64 = 0.0;
/// A zone's axis 1 at angle 0: the beam axis.
pub(crate) const FIBRE: [f64; 3] = [0.0, 1.0, 0.0];
/// A zone's axis 3.
pub(crate) const NORMAL: [f64; 3] = [0.0, 0.0, 1.0];
/// A laminate's interfaces: the plies share their nodes (the word of
/// `schema::InterfaceKind::Perfect`).
pub(crate) const INTERFACES: &str = "perfect";
/// The default cohesive penalty is this times E3/t of the thinner ply next
/// to the interface (Turon, Dávila, Camanho & Costa 2007, Eng. Fract. Mech.
/// 74:1665: the laminate loses under 2 % of its stiffness through the
/// thickness).
pub(crate) const PENALTY_PER_STIFFNESS: f64 = 50.0;
/// `materials.cohesive.viscosity`: none.
pub(crate) const COHESIVE_VISCOSITY: f64 = 0.0;
/// `materials.damage.max_damage`: a fully damaged ply point keeps a
/// thousandth of its stiffness (the solve stays definite).
pub(crate) const MAX_DAMAGE: f64 = 0.999;
/// `materials.damage.tangent`: the consistent one (the secant stalls
/// Newton through softening, `examples/notched_strip_coarse.toml`).
pub(crate) const DAMAGE_TANGENT: &str = "consistent";
/// `materials.damage.softening_stress`: the effective stress (Lapczyk &
/// Hurtado's law as Abaqus has it).
pub(crate) const SOFTENING_STRESS: &str = "effective";
/// `materials.damage.viscosity`: none.
pub(crate) const DAMAGE_VISCOSITY: f64 = 0.0;
/// `materials.damage.fibre_shear`: Hashin's fibre-tension criterion, its
/// shear term whole.
pub(crate) const FIBRE_SHEAR: f64 = 1.0;
