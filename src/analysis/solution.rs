//! What a [`Solution`] offers beyond its fields: resultants by name, the
//! state at the end of a step or at a frame, and a view for fields at any
//! point.

use super::{AnalysisError, ContactPoint, ContactResultant, Reaction, Solution, StepFields};
use crate::setup::Model;

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
        self.with_fields(model, fields, end.lambda, (&end.reactions, &end.contacts)).map(Some)
    }

    /// The solution as it was at frame `k` of a transient run (its fields,
    /// and the reactions and contact resultants of its increment).
    pub fn at_frame(&self, model: &Model, k: usize) -> Result<Solution, AnalysisError> {
        let frame = &self.frames[k];
        let row = &self.history[frame.increment - 1];
        self.with_fields(model, &frame.fields, row.lambda, (&row.reactions, &row.contacts))
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
            steps: Vec::new(),
            adapt: None,
            buckling: None,
            modal: None,
            energy: None,
            frames: Vec::new(),
            path: self.path.clone(),
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
            mesh: &model.mesh,
            geometry: &model.cells,
            materials: &model.materials,
            u: &self.u,
            states: &self.states,
            stresses: &self.stresses,
            gp_offsets: &self.gp_offsets,
            recovered: self.recovered.as_ref(),
            kinematics: model.kinematics,
            symmetry: &model.symmetry.planes,
        }
    }
}
