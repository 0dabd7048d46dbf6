//! The structure's parts: its contributions, in the order they are
//! evaluated into the tangent and summed into the residual, and what it
//! measured of itself.

use super::Timings;
use super::elements::Elements;
use super::loads::Loads;
use crate::assembly::Contribution;
use crate::contact::Contacts;
use crate::dynamics::{Impulses, Inertia, TimeError};
use crate::interfaces::Interfaces;
use crate::size::MemoryEstimate;

/// Every contribution ([`crate::assembly::Contribution`]). A new one is a
/// field here and its line in [`Parts::each`] and [`Parts::each_mut`].
pub(crate) struct Parts<'m> {
    /// Internal forces, element tangents and the Gauss-point history
    /// (first: they write the whole tangent).
    pub elements: Elements<'m>,
    /// External loads at λ.
    pub loads: Loads<'m>,
    /// Every contact kind.
    pub contacts: Contacts<'m>,
    /// Cohesive interfaces between plies.
    pub interfaces: Interfaces<'m>,
    /// Inertia and damping (`analysis.type = "transient"`).
    pub inertia: Option<Inertia>,
    /// The end-of-step impulses of the contacts and the interfaces (a
    /// transient analysis with them and `analysis.contact_forces`,
    /// `analysis.interface_forces = "implicit"`): not a contribution, each
    /// replaces its contributions' force and weights their stiffness.
    pub impulse: Impulses,
    /// The time steps' error estimate (a transient analysis): not a
    /// contribution, it measures the converged step for the step control
    /// (`solver.step_control.time_error`).
    pub time_error: Option<TimeError>,
}

impl Parts<'_> {
    /// The contributions in order (the elements first).
    pub(crate) fn each_mut(&mut self) -> impl Iterator<Item = &mut dyn Contribution> {
        let parts: [&mut dyn Contribution; 4] =
            [&mut self.elements, &mut self.loads, &mut self.contacts, &mut self.interfaces];
        parts.into_iter().chain(self.inertia.iter_mut().map(|i| i as &mut dyn Contribution))
    }

    /// The contributions in order, read only.
    pub fn each(&self) -> impl Iterator<Item = &dyn Contribution> {
        let parts: [&dyn Contribution; 4] = [&self.elements, &self.loads, &self.contacts, &self.interfaces];
        parts.into_iter().chain(self.inertia.iter().map(|i| i as &dyn Contribution))
    }
}

/// What the structure measured of itself.
#[derive(Debug)]
pub(crate) struct Report {
    /// Cumulative phase timings and the solver's statistics.
    pub timings: Timings,
    /// Memory estimate made after the symbolic factorization.
    pub memory: MemoryEstimate,
    /// Negative pivots of the last committed tangent (nonlinear geometry).
    pub pivots: Option<usize>,
}
