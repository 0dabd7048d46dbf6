//! The result of an analysis: the [`Solution`] (fields, resultants,
//! histories, statistics), the end of each step, the rows of the load
//! history, and what a solution offers beyond its fields (resultants by
//! name, the state at the end of a step or at a frame, a view for fields at
//! any point).

use std::time::Duration;

use super::{Adaptivity, Timings, buckling, modal};
use super::{AnalysisError, ContactPoint, ContactResultant, ContactSet, Frame, LeverResultant, PathOutcome, Reaction};
use crate::materials::PointState;
use crate::setup::{Model, Warning};
use crate::size::MemoryEstimate;
use crate::solver::stepping::{Cutback, Increment, SteppingError};
use crate::voigt::Voigt;

/// The result of an analysis (the last converged state if it stopped early).
#[derive(Debug, Clone)]
pub struct Solution {
    /// Displacements, 3 per node.
    pub u: Vec<f64>,
    /// Committed Gauss-point states.
    pub states: Vec<PointState>,
    /// Gauss-point stresses of the final (converged) state.
    pub stresses: Vec<Voigt>,
    /// First Gauss point of each body.
    pub(crate) gp_offsets: Vec<usize>,
    /// Load factor reached.
    pub lambda: f64,
    /// Reactions per constraint set.
    pub reactions: Vec<Reaction>,
    /// Per indenter then pair contact: force on the body and largest penetration.
    pub contacts: Vec<ContactResultant>,
    /// Per lever: its displacement and force.
    pub levers: Vec<LeverResultant>,
    /// Final state of every contact point.
    pub contact_sets: Vec<ContactSet>,
    /// Sum of applied nodal loads at the final load factor (N).
    pub applied: [f64; 3],
    /// Load history.
    pub history: Vec<HistoryRow>,
    /// Converged increments.
    pub increments: Vec<Increment>,
    /// Failed attempts.
    pub cutbacks: Vec<Cutback>,
    /// Set when the analysis stopped before λ = 1.
    pub failure: Option<SteppingError>,
    /// Free DOFs.
    pub equations: usize,
    /// Entries of the Cholesky factor.
    pub factor_nnz: usize,
    /// Plastic Gauss points at the end.
    pub plastic_points: usize,
    /// Phase timings.
    pub timings: Timings,
    /// Wall time of the whole analysis.
    pub wall_time: Duration,
    /// Memory estimate made before the analysis (after the symbolic factorization).
    pub memory: MemoryEstimate,
    /// What the results show to be suspicious (an indenter that never
    /// touched, a probe in a region that carries no load).
    pub warnings: Vec<Warning>,
    /// Recovered (projected) nodal stress and peeq, when the model asks for them.
    pub recovered: Option<crate::post::Recovered>,
    /// The estimated discretization error of the final state
    /// ([`crate::post::estimate`]); for the states of [`Solution::at_step`]
    /// and [`Solution::at_frame`], that state's own.
    pub error_estimate: Option<crate::post::ErrorEstimate>,
    /// The estimate of every step end and frame the run kept
    /// ([`super::state_errors`]); empty for the states of
    /// [`Solution::at_step`] and [`Solution::at_frame`].
    pub error_history: super::state_errors::ErrorHistory,
    /// The end of every completed step of the load history, in order.
    pub steps: Vec<StepEnd>,
    /// The cycles of an adaptive run that ended with this solution
    /// (`crate::adapt`); `None` for a single run.
    pub adapt: Option<Adaptivity>,
    /// `analysis.type = "buckling"`: critical load factors and modes about
    /// the final state; `None` otherwise.
    pub buckling: Option<buckling::Buckling>,
    /// `analysis.type = "modal"`: natural frequencies and modes about the
    /// final state; `None` otherwise.
    pub modal: Option<modal::Modal>,
    /// `analysis.type = "transient"`: the energy balance per converged
    /// time step (the initial state first); `None` otherwise.
    pub energy: Option<Vec<crate::dynamics::energy::EnergyRow>>,
    /// `analysis.output_interval`: the fields at every output time of a
    /// transient run (empty otherwise).
    pub frames: Vec<Frame>,
    /// How the path following went (`solver.control = "arc_length"`).
    pub path: Option<PathOutcome>,
    /// The cohesive interfaces at the end, or at the frame of
    /// [`Solution::at_frame`] (`None` without interfaces and for the states
    /// of [`Solution::at_step`]).
    pub delamination: Option<crate::interfaces::Delamination>,
    /// The ply damage at the end (`None` without a damaging material and
    /// for the states of [`Solution::at_step`]).
    pub damage: Option<crate::damage::Damage>,
}

/// The state at the end of one step of the load history.
#[derive(Debug, Clone)]
pub struct StepEnd {
    /// Step name.
    pub name: String,
    /// Analysis time λ at the end of the step.
    pub lambda: f64,
    /// Index of the step's last increment (0 if it had none).
    pub increment: usize,
    /// Reactions per constraint set.
    pub reactions: Vec<Reaction>,
    /// Per indenter then pair contact: force and largest penetration.
    pub contacts: Vec<ContactResultant>,
    /// Displacements, Gauss-point states and stresses (kept when the model
    /// has more than one step, for per-step output).
    pub fields: Option<StepFields>,
    /// The ply damage then, each mode's per Gauss point (kept with the
    /// fields; `None` without `[materials.damage]`): the step end's
    /// `d_ft d_fc d_mt d_mc`.
    pub damage: Option<Vec<[f64; 4]>>,
    /// The cohesive interfaces then (kept with the fields; `None` without
    /// cohesive interfaces): the step end's `d_interface` and delaminated area.
    pub delamination: Option<crate::interfaces::Delamination>,
}

/// The fields of a [`StepEnd`].
#[derive(Debug, Clone)]
pub struct StepFields {
    /// Displacements, 3 per node.
    pub u: Vec<f64>,
    /// Committed Gauss-point states.
    pub states: Vec<PointState>,
    /// Gauss-point stresses.
    pub stresses: Vec<Voigt>,
}

/// One row of the load history (after a converged increment).
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryRow {
    /// Increment index (1-based).
    pub increment: usize,
    /// Load factor.
    pub lambda: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// Resultant reaction of each constraint set.
    pub reactions: Vec<Reaction>,
    /// Resultant of each indenter, then of each pair contact.
    pub contacts: Vec<ContactResultant>,
    /// Plastic Gauss points.
    pub plastic_points: usize,
    /// Per lever: its displacement and force.
    pub levers: Vec<LeverResultant>,
    /// Displacement at each probe, in the model's order.
    pub probes: Vec<[f64; 3]>,
    /// Negative pivots of the last factorized tangent
    /// (`Structure::negative_pivots`).
    pub negative_pivots: Option<usize>,
    /// The delaminated area of every cohesive interface together (m²; the
    /// points with d = 1), `None` in a model without interfaces.
    pub delaminated_m2: Option<f64>,
    /// The volume of the ply points where each mode's damage passed ½
    /// (m³, in [`crate::materials::damage::MODES`] order), `None` in a model
    /// whose materials do not damage.
    pub damaged_volume_m3: Option<[f64; 4]>,
}

impl HistoryRow {
    /// The reaction of the constraint set `name`.
    pub fn reaction(&self, name: &str) -> Option<&Reaction> {
        self.reactions.iter().find(|r| r.name == name)
    }

    /// The resultant of the indenter or contact `name`.
    pub fn contact(&self, name: &str) -> Option<&ContactResultant> {
        self.contacts.iter().find(|c| c.name == name)
    }
}

impl Solution {
    /// The reaction of the constraint set `name`.
    pub fn reaction(&self, name: &str) -> Option<&Reaction> {
        self.reactions.iter().find(|r| r.name == name)
    }

    /// The resultant of the indenter or contact `name`.
    pub fn contact(&self, name: &str) -> Option<&ContactResultant> {
        self.contacts.iter().find(|c| c.name == name)
    }

    /// The points of the indenter or contact `name`.
    pub fn contact_points(&self, name: &str) -> Option<&[ContactPoint]> {
        self.contact_sets.iter().find(|c| c.name == name).map(|c| c.points.as_slice())
    }

    /// The solution as it was at the end of step `k` (fields, reactions and
    /// contact resultants of that moment; histories and timings of the whole
    /// run), or `None` if the step did not complete or kept no fields.
    pub fn at_step(&self, model: &Model, k: usize) -> Result<Option<Solution>, AnalysisError> {
        let Some(end) = self.steps.get(k) else { return Ok(None) };
        let Some(fields) = &end.fields else { return Ok(None) };
        let mut s = self.with_fields(model, fields, end.lambda, (&end.reactions, &end.contacts))?;
        s.damage = self.damage_then(end.damage.as_deref());
        s.delamination = end.delamination.clone();
        s.error_estimate = self.error_history.of(super::state_errors::State::Step(k)).cloned();
        Ok(Some(s))
    }

    /// The solution as it was at frame `k` of a transient run (its fields,
    /// and the reactions and contact resultants of its increment).
    pub fn at_frame(&self, model: &Model, k: usize) -> Result<Solution, AnalysisError> {
        let frame = &self.frames[k];
        let row = &self.history[frame.increment - 1];
        let mut s = self.with_fields(model, &frame.fields, row.lambda, (&row.reactions, &row.contacts))?;
        s.delamination = frame.delamination.clone();
        s.damage = self.damage_then(frame.damage.as_deref());
        s.error_estimate = self.error_history.of(super::state_errors::State::Frame(k)).cloned();
        Ok(s)
    }

    /// The ply damage of a step end or frame that kept `shown`
    /// ([`crate::damage::BodyDamage::shown`]), with the run's volume
    /// weights: its fields only (`None` if it kept none).
    fn damage_then(&self, shown: Option<&[[f64; 4]]>) -> Option<crate::damage::Damage> {
        match (shown, &self.damage) {
            (Some(shown), Some(end)) => Some(crate::damage::Damage::of_frame(shown, &end.volume)),
            _ => None,
        }
    }

    /// This solution with the fields, λ and resultants of another moment
    /// (histories and timings of the whole run).
    fn with_fields(
        &self,
        model: &Model,
        fields: &StepFields,
        lambda: f64,
        (reactions, contacts): (&[Reaction], &[ContactResultant]),
    ) -> Result<Solution, AnalysisError> {
        // field by field: `..self.clone()` would copy every step's fields
        // (and the final ones) only to drop them
        let mut s = Solution {
            u: fields.u.clone(),
            states: fields.states.clone(),
            stresses: fields.stresses.clone(),
            gp_offsets: self.gp_offsets.clone(),
            lambda,
            reactions: reactions.to_vec(),
            contacts: contacts.to_vec(),
            // the levers of the increment that ended at λ (none recorded: none)
            levers: self
                .history
                .iter()
                .rev()
                .find(|r| (r.lambda - lambda).abs() <= 1e-12 * lambda.abs().max(1.0))
                .map_or_else(Vec::new, |r| r.levers.clone()),
            contact_sets: self.contact_sets.clone(),
            applied: self.applied,
            history: self.history.clone(),
            increments: self.increments.clone(),
            cutbacks: self.cutbacks.clone(),
            failure: self.failure.clone(),
            equations: self.equations,
            factor_nnz: self.factor_nnz,
            plastic_points: self.plastic_points,
            timings: self.timings,
            wall_time: self.wall_time,
            memory: self.memory.clone(),
            warnings: self.warnings.clone(),
            recovered: None,
            error_estimate: None,
            error_history: Default::default(),
            steps: Vec::new(),
            adapt: None,
            buckling: None,
            modal: None,
            energy: None,
            frames: Vec::new(),
            path: self.path.clone(),
            delamination: None,
            damage: None,
        };
        if model.output.recovery == crate::input::Recovery::Projection {
            s.recovered =
                Some(crate::post::recovery::project(&model.mesh, &model.cells, &s.stresses, &s.states, &s.gp_offsets)?);
        }
        Ok(s)
    }

    /// A view for field evaluation.
    pub fn fields<'a>(&'a self, model: &'a Model) -> crate::post::FieldView<'a> {
        crate::post::FieldView {
            state: model.discretisation().fe_state(&self.u, &self.states, &self.gp_offsets, Default::default()),
            stresses: &self.stresses,
            recovered: self.recovered.as_ref(),
            symmetry: &model.symmetry.planes,
            damage: self.damage.as_ref(),
        }
    }
}
