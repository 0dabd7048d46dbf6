//! The structure driven by the load stepping (`solver::stepping`): the
//! load factor, the start of each increment, the commit of a converged one
//! and the return to the last committed state.

use super::{Structure, transient};
use crate::materials::Predictor;
use crate::solver::stepping::{Incremental, StepMeasure};

impl Incremental for Structure<'_> {
    fn set_load_factor(&mut self, lambda: f64) {
        // prescribed values are reached by the next correction (setup::constraints::Elimination)
        self.state.lambda = lambda;
        self.state.on_secant = false;
        self.parts.contacts.start_increment();
        self.elimination.set_load_factor(self.loading.steps, lambda);
    }

    fn augment(&mut self) -> bool {
        self.parts.contacts.augment()
    }

    fn cautious(&mut self, on: bool) -> bool {
        // The elastic predictor decides only at points on their yield
        // surface with no strain increment: at the committed state. A failed
        // attempt started on the secant of the last increment would be
        // repeated to the last digit (measured on examples/tube_crush.toml:
        // every retry's residuals equal its failed attempt's), unless
        // cohesive interfaces take their secant (interfaces::assembly).
        // Sliding frictional points take the stick tangent at the first
        // evaluation of an increment started at the committed state only,
        // cautious or not (contact::assembly): the stick tangent at every
        // evaluation converges linearly, at a rate near one where many
        // points slide under a stiff penalty (a fine mesh's peel stalled at
        // a residual of 0.28 for twenty corrections).
        if on && self.state.on_secant && !self.parts.interfaces.is_active() {
            return false;
        }
        let wanted = if on { Predictor::Elastic } else { Predictor::Loading };
        let changed = self.state.predictor != wanted;
        self.state.predictor = wanted;
        changed
    }

    fn unloads(&self, lambda: f64) -> bool {
        // only points on their yield surface need the elastic branch (the
        // cautious retry also searches along a frictionless contact's
        // corrections); a transient step's first time step follows from its motion
        self.parts.inertia.is_none()
            && self.parts.elements.discretisation.materials.iter().any(|m| m.is_plastic())
            && crate::setup::steps::unloads(self.loading.steps, lambda.round() as usize)
    }

    fn extrapolate(&mut self, ratio: f64) {
        if self.starts_committed() {
            return;
        }
        // Started on the secant of the last increment, a point that slid is
        // beyond its cone in the direction it slid, not on it to round-off:
        // its consistent tangent applies from the first iteration, and the
        // stick predictor (`contact::assembly`) is kept for increments that
        // start at the committed state (the first of a load step, where the
        // loading may reverse). Measured on
        // examples/cantilevers_contact_friction.toml: the same Newton
        // iterations (66 against 67), 21 factorizations against 52 (the
        // predictor's tangent differs from the sliding one at every sliding
        // point, so no factor served both).
        if self.state.extrapolate(ratio) {
            self.parts.contacts.start_extrapolated();
        }
        self.force.extrapolate(ratio);
        self.levers.extrapolate(ratio);
    }

    fn measure(&self) -> StepMeasure {
        let (changed, before, after) = self.parts.contacts.status_changes();
        StepMeasure {
            plastic_strain: self.parts.elements.largest_peeq_increment(),
            contact_set: (before > 0).then(|| changed as f64 / before.max(after) as f64),
            time_error: transient::time_error(&self.parts, &self.state, &self.system, &self.elimination),
            damage: self
                .parts
                .elements
                .largest_damage_increment()
                .max(self.parts.interfaces.largest_damage_increment()),
        }
    }

    fn landing(&self, lambda: f64) -> Option<f64> {
        transient::next_output(&self.parts, lambda)
    }

    fn commit(&mut self) {
        let impactors = self.force.impactor_energy();
        transient::account_energy(&mut self.parts, &self.state, (&self.system, &self.elimination), impactors);
        self.parts.impulse.commit();
        if self.inertia_every_increment() {
            // the tangent of the last evaluation is that of the converged
            // state: its inertia (on the free DOFs, as it is solved; the
            // right-hand side is rewritten by the next evaluation) marks
            // limit and bifurcation points
            let formed = self.form_tangent().is_ok();
            let system = &mut self.system;
            let col_ptr = &system.assembler.pattern.col_ptr;
            let (tangent, rest, rhs) = (&mut system.tangent, system.rest.as_mut(), &mut system.rhs);
            self.elimination.eliminate(&self.state.u, |e| col_ptr[e], tangent, rest, rhs);
            self.report.pivots = if formed { system.inertia() } else { None };
        }
        transient::commit_time_error(&mut self.parts, &self.state, &self.system, &self.elimination);
        self.state.commit();
        let at = self.state.at();
        for part in self.parts.each_mut() {
            part.commit(&at);
        }
        self.force.commit(self.state.lambda);
        self.levers.commit();
        self.system.force_scale.commit();
    }

    fn restore(&mut self) {
        self.state.restore();
        for part in self.parts.each_mut() {
            part.restore();
        }
        self.force.restore();
        self.levers.restore();
        self.elimination.set_load_factor(self.loading.steps, self.state.lambda);
    }
}

impl Structure<'_> {
    /// True if each increment starts at the committed state, its first
    /// correction the tangent step, rather than on the secant of the last
    /// increment: with nonlinear geometry and nothing path-dependent (no
    /// contact, plasticity, damage, interface, force control, lever or
    /// inertia). Under large rotation the secant of the displacements
    /// leaves the path by a stretch `∝ Δθ²` of the walls, and the soft
    /// modes then take a correction more, after which the residual rises
    /// before it falls. Measured (`cufem run FILE --threads 1`, corrections
    /// with a secant start → at the committed state): the channel of
    /// bench/channel_twist.toml with 2 L9 along each flange, 4 along the web
    /// and 12 uniform B4, 92 → 81 (every increment 4, and 5 for the first,
    /// quadratic in its last three), examples/elastica.toml 59 → 50, examples/column_postbuckling.toml
    /// 134 → 141 (140 → 120 factorizations). Path-dependent models keep the
    /// secant: examples/tube_crush.toml takes 177 corrections with it and
    /// 1,944 and 25 cutbacks without.
    fn starts_committed(&self) -> bool {
        let d = &self.parts.elements.discretisation;
        d.kinematics.is_nonlinear()
            && d.interfaces.is_empty()
            && d.materials.iter().all(|m| !m.is_plastic() && m.damage.is_none())
            && self.parts.contacts.points().is_empty()
            && self.parts.inertia.is_none()
            && !self.force.is_driven()
            && !self.levers.is_active()
    }
}
