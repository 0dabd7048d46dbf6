//! What an analysis reports: reactions and contact resultants by name, the
//! contact points, and the phase timings with the solver statistics.

use std::time::Duration;

use crate::solver::reuse::SolverStats;

/// Cumulative wall time per phase.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Setup: numbering, ordering, pattern, scatter maps, symbolic analysis.
    pub setup: Duration,
    /// Part of `setup`: node graph and METIS nested dissection.
    pub ordering: Duration,
    /// Part of `setup`: sparse pattern, scatter maps, colours.
    pub pattern: Duration,
    /// Part of `setup`: symbolic Cholesky analysis.
    pub symbolic: Duration,
    /// Part of `setup`: elastic element matrices computed once for reuse.
    pub element_cache: Duration,
    /// Element loop with material updates and scatter.
    pub assembly: Duration,
    /// Part of `assembly`, summed over the worker threads: the kernel's
    /// first pass (B-bar's projections, strains, material updates,
    /// internal forces).
    pub stress_pass: Duration,
    /// Part of `assembly`, summed over the worker threads: forming the
    /// element tangents. On one thread `assembly` less both is the gather
    /// of element displacements and the scatter of forces and matrices.
    pub element_tangents: Duration,
    /// Contact search and penalty terms.
    pub contact: Duration,
    /// A modal or buckling analysis's eigenproblem about the static state
    /// (its factorizations and solves included; zero otherwise).
    pub eigen: Duration,
    /// Number of residual/tangent evaluations.
    pub evaluations: usize,
    /// Element tangents (or their corrections to the cached elastic
    /// tangent) formed by the kernel, over all evaluations.
    pub element_tangents_formed: usize,
    /// Of them: evaluations without the element tangents (Newton expected
    /// them to be the last of their solve).
    pub residual_only: usize,
    /// Of them: evaluations repeated with the element tangents after a
    /// residual-only one that did not converge.
    pub reevaluations: usize,
    /// The linear solver's counters and times: factorizations, reuses,
    /// PCG iterations, fallbacks, and the time in factorizations and solves.
    pub solver: SolverStats,
}

impl Timings {
    /// Adds one evaluation: the element loop's and the contacts' wall times
    /// (`[elements, contact]`) and the kernel's passes.
    pub(crate) fn add_evaluation(&mut self, elapsed: [Duration; 2], kernel: &crate::assembly::AssemblyStats) {
        self.assembly += elapsed[0];
        self.contact += elapsed[1];
        self.stress_pass += kernel.stress_pass;
        self.element_tangents += kernel.element_tangents;
        self.element_tangents_formed += kernel.tangents_formed;
    }
}

/// The resultant reaction of a named constraint set (N): the force of the
/// support on the body.
#[derive(Debug, Clone, PartialEq)]
pub struct Reaction {
    /// Constraint name.
    pub name: String,
    /// Force (N).
    pub force: [f64; 3],
}

/// What kind of contact a resultant belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactKind {
    /// A rigid indenter: the force it applies to its body.
    Indenter,
    /// Node pairs between two bodies: the force on the slave body (the
    /// master body gets its opposite).
    Pair,
}

impl ContactKind {
    /// `"indenter"` or `"pair"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Indenter => "indenter",
            Self::Pair => "pair",
        }
    }
}

/// The resultant of a named contact.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactResultant {
    /// Indenter or contact name.
    pub name: String,
    /// Indenter or pair contact.
    pub kind: ContactKind,
    /// Force on the body (on the slave body for pairs), N.
    pub force: [f64; 3],
    /// Its part along the contact normals (Σ (f·n) n over the points), N.
    pub normal_force: [f64; 3],
    /// Its tangential (friction) part, `force − normal_force`, N.
    pub tangential_force: [f64; 3],
    /// Largest penetration of its active points (m).
    pub max_penetration: f64,
    /// Rigid displacement of an indenter (m; prescribed, or solved for
    /// under force control); zero for pair contacts.
    pub displacement: [f64; 3],
}

/// The points of one named contact after the last evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSet {
    /// Indenter or contact name.
    pub name: String,
    /// Indenter or pair contact.
    pub kind: ContactKind,
    /// Its points (for pairs the slave node is `node`).
    pub points: Vec<ContactPoint>,
}

pub use crate::contact::ContactPoint;

/// One cycle of an adaptive run (`crate::adapt`): a mesh solved from the
/// start of the load history.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptCycle {
    /// Cycle number, 0 for the model's own mesh.
    pub cycle: usize,
    /// Degrees of freedom of its mesh.
    pub dof: usize,
    /// Relative error estimate of its solution: in the energy norm, or of a
    /// modal (buckling) analysis the largest estimated relative frequency
    /// (critical load factor) error of the modes followed
    /// (`crate::adapt::measure`).
    pub estimate: f64,
    /// Modal and buckling: the modes followed, with their estimated
    /// errors; `None` otherwise.
    pub modes: Option<FollowedModes>,
    /// Transient: the kept state whose estimate is `estimate` (the worst
    /// of the frames and the end: `frame_0004`, or `end`); `None` otherwise.
    pub state: Option<String>,
    /// Wall time of the cycle: building the refined model and solving it (s).
    pub time_s: f64,
    /// What its mesh refined in the previous one (empty for cycle 0).
    pub refined: String,
    /// Its probes' values ([`super::tables::probes`]: a row per probe).
    pub probes: super::tables::Table,
}

/// What the modes an adaptive cycle follows are measured by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeQuantity {
    /// A modal analysis's natural frequencies (Hz).
    Frequency,
    /// A buckling analysis's critical load factors.
    LoadFactor,
}

impl ModeQuantity {
    /// Its name in messages and tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::Frequency => "frequency",
            Self::LoadFactor => "critical load factor",
        }
    }
}

/// The modes an adaptive cycle of a modal or buckling analysis follows
/// (`crate::adapt::measure`), lowest first.
#[derive(Debug, Clone, PartialEq)]
pub struct FollowedModes {
    /// Frequencies or critical load factors.
    pub quantity: ModeQuantity,
    /// Their values (Hz, or load factors).
    pub values: Vec<f64>,
    /// Their estimated relative errors: `(f_h − f) / f` of a frequency,
    /// `(μ_h − μ) / μ_h` of a load factor.
    pub errors: Vec<f64>,
}

/// How an adaptive run went: every cycle and why it stopped. The solution
/// carrying it is the last cycle's.
#[derive(Debug, Clone, PartialEq)]
pub struct Adaptivity {
    /// The cycles, in order.
    pub cycles: Vec<AdaptCycle>,
    /// Why no further cycle was run.
    pub stop: String,
    /// The tolerance on the relative estimate.
    pub tolerance: f64,
    /// The DOF budget.
    pub max_dof: usize,
    /// How the run ended; the solution is that of the last cycle in
    /// [`Adaptivity::cycles`] (the last finished one) unless `Done` came
    /// with a cycle whose own analysis stopped early (cycle 0).
    pub end: AdaptEnd,
    /// The model file of the mesh the results are on: the run's model file
    /// with that mesh's divisions written in (`setup::plan_file`);
    /// written beside the results as `adapted.toml`, to keep, verify or ship.
    pub model_file: String,
}

impl Adaptivity {
    /// Wall time of all its cycles (s): the run's, where a solution's own
    /// `wall_time` is its last cycle's.
    pub fn time_s(&self) -> f64 {
        self.cycles.iter().map(|c| c.time_s).sum()
    }
}

/// How an adaptive run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdaptEnd {
    /// As asked: the tolerance, the DOF budget, the memory limit,
    /// `max_cycles`, nothing left to refine — or cycle 0 itself stopped
    /// early (its `Solution::failure` says why, as for a single run).
    Done,
    /// A later cycle's analysis stopped early, failed, or its refined model
    /// could not be built: the results are the last finished cycle's.
    Stopped,
    /// A stop was requested (Ctrl-C, SIGTERM) during or between later
    /// cycles: the results are the last finished cycle's.
    Interrupted,
}
