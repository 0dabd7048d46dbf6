//! What the structure is built from beside its discretisation
//! ([`crate::setup::Discretisation`]) and constraint handler
//! ([`crate::setup::constraints::ConstraintHandler`]): what loads it and
//! the settings its parts read, each a view of the model's own data.

use crate::bc::{Constraint, Lever, Load};
use crate::contact::{Indenter, PairContact};
use crate::dynamics::TransientSettings;
use crate::input::SolverSettings;
use crate::setup::Model;
use crate::setup::steps::Step;
use crate::size::Sizes;

/// What acts on the structure: loads, constraints (their names and node
/// sets, for the reactions), indenters and contacts, and the load history
/// that scales them.
#[derive(Debug, Clone, Copy)]
pub struct Loading<'m> {
    /// Loads (nodal forces at load factor 1).
    pub loads: &'m [Load],
    /// Rigid levers.
    pub levers: &'m [Lever],
    /// Displacement constraints, in the order of the constraint handler's
    /// sources.
    pub constraints: &'m [Constraint],
    /// Rigid indenters.
    pub indenters: &'m [Indenter],
    /// Deformable contacts.
    pub contacts: &'m [PairContact],
    /// The load history (at least one step).
    pub steps: &'m [Step],
}

impl<'m> Loading<'m> {
    /// The loading of `model`.
    pub fn of(model: &'m Model) -> Self {
        Self {
            loads: &model.loads,
            levers: &model.levers,
            constraints: &model.constraints,
            indenters: &model.indenters,
            contacts: &model.contacts,
            steps: &model.steps,
        }
    }

    /// True if any contact has Coulomb friction (its tangent is unsymmetric).
    pub(crate) fn has_friction(&self) -> bool {
        self.indenters.iter().any(|i| i.friction.is_some()) || self.contacts.iter().any(|c| c.friction.is_some())
    }

    /// True if the structure has indenters or contacts.
    pub(crate) fn has_contacts(&self) -> bool {
        !self.indenters.is_empty() || !self.contacts.is_empty()
    }
}

/// The settings the structure's parts read, and the memory plan it is
/// checked against once its equations are numbered.
#[derive(Debug, Clone)]
pub struct Settings<'m> {
    /// Solver controls.
    pub solver: &'m SolverSettings,
    /// Implicit dynamics (`analysis.type = "transient"`); `None` for a
    /// static analysis.
    pub transient: Option<&'m TransientSettings>,
    /// The sizes the model alone sets (`crate::analysis::model_sizes`),
    /// completed by the structure with its numbering and factor.
    pub sizes: Sizes,
    /// Refuse the structure if its estimated memory exceeds this (bytes).
    pub max_memory: Option<u64>,
}

impl<'m> Settings<'m> {
    /// The settings of `model`, refused above `max_memory` bytes.
    pub fn of(model: &'m Model, max_memory: Option<u64>) -> Self {
        Self {
            solver: &model.solver,
            transient: model.transient.as_ref(),
            sizes: crate::analysis::model_sizes(model),
            max_memory,
        }
    }
}
