//! The validated settings read from the model file without a mesh: solver,
//! path-following and output controls, published reference values.

use crate::quantity::Quantity;
use crate::solver::arclength::ArcLengthSettings;
use crate::solver::newton::NewtonSettings;
use crate::solver::stepping::StepSettings;

/// A published value printed beside ours.
#[derive(Debug, Clone)]
pub struct Reference {
    /// Probe name.
    pub probe: String,
    /// Quantity.
    pub quantity: Quantity,
    /// Value in SI units.
    pub value: f64,
    /// Where it comes from.
    pub source: String,
}

/// Solution controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Load stepping.
    pub steps: StepSettings,
    /// Newton iteration.
    pub newton: NewtonSettings,
    /// Worker threads (`None`: all cores).
    pub threads: Option<usize>,
    /// Reuse of a factorization as the preconditioner of later solves.
    pub reuse: crate::solver::reuse::ReuseSettings,
    /// `solver.control = "arc_length"`: path following (`None`: load stepping).
    pub path: Option<PathSettings>,
    /// `solver.inertia`: which tangent's inertia `history.csv` reports
    /// (`None`: every converged one with nonlinear geometry, else the last
    /// factorized one).
    pub inertia: Option<InertiaReport>,
}

/// Which tangent's inertia (negative pivots) each increment reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InertiaReport {
    /// The converged tangent of every increment, factorized in double
    /// precision for it (one factorization per increment).
    EveryIncrement,
    /// The last tangent the solver factorized anyway (free; it may be some
    /// iterations or increments old).
    LastFactorization,
}

/// Output controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputSettings {
    /// Write `result.vtu`.
    pub vtu: bool,
    /// Write PNG plots.
    pub(crate) plots: bool,
    /// How stress and peeq are recovered at points.
    pub recovery: Recovery,
    /// Also write `gauss.vtu` with the raw Gauss-point values.
    pub gauss_points: bool,
    /// The cells of `result.vtu` and the other field VTUs.
    pub vtu_cells: VtuCells,
    /// Write `report.html` (`io::html`).
    pub report: bool,
}

/// The cells the field VTUs (`result.vtu`, steps, frames, modes) carry
/// (`output.vtu_cells`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum VtuCells {
    /// One VTK Lagrange hexahedron per CUF element, of the element's own
    /// order in each direction: the exact geometry and displacement. The
    /// default.
    #[default]
    Lagrange,
    /// Linear hexahedra between each element's Lagrange nodes, for readers
    /// without Lagrange cells.
    Linear,
}

/// How stress and peeq are evaluated at arbitrary points (`output.recovery`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Recovery {
    /// L2 projection of the Gauss-point values onto the CUF basis: a
    /// continuous field ([`crate::post::recovery`]).
    Projection,
    /// Element by element: the expansion's `C ε` in elastic elements, the
    /// limited interpolation of the Gauss-point values in yielded ones
    /// (discontinuous between elements). The default.
    #[default]
    Element,
}

/// The validated controls of a path following.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSettings {
    /// The arc-length method's controls (`initial_dlambda` = 1/`increments`,
    /// `max_increments`, `max_iterations`, `residual_tolerance` from
    /// `[solver]`, the rest its defaults).
    pub arc: ArcLengthSettings,
    /// `solver.arc_length`: `Δl₀` (m, Euclidean norm of the change of the
    /// free displacements); `None`: from the first predictor of `Δλ =
    /// arc.initial_dlambda`.
    pub arc_length: Option<f64>,
    /// The run ends at the first converged point with `λ ≥` this.
    pub max_load_factor: f64,
    /// The run ends at the first converged point past this displacement.
    pub stop: Option<DisplacementStop>,
}

/// `solver.stop`: a probe's displacement component passing a value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DisplacementStop {
    /// Index of the probe in the model.
    pub probe: usize,
    /// 0, 1, 2 for x, y, z.
    pub component: usize,
    /// The value (m, non-zero): passed when the component is at or beyond
    /// it on its side of zero (`u ≤ beyond` for a negative value).
    pub beyond: f64,
}

impl DisplacementStop {
    /// True if `u` (the probe's displacement) has passed the limit.
    pub fn passed(&self, u: [f64; 3]) -> bool {
        let v = u[self.component];
        if self.beyond < 0.0 { v <= self.beyond } else { v >= self.beyond }
    }
}
