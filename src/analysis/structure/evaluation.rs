//! One evaluation of the structure: every part into the tangent in order,
//! their forces summed into the residual per DOF, and the force scale and
//! settledness that Newton's convergence test reads (`solver::newton`).
//!
//! An evaluation that Newton expects to be the last of its solve skips the
//! element tangents ([`crate::solver::newton::NonlinearProblem::evaluate_residual`]):
//! on the compact bar with nonlinear geometry they are 10.7 of 17.2 ms of an
//! evaluation (`cufem bench … --full`). If the solve goes on after all, the
//! structure evaluates again with them before the correction
//! ([`Structure::form_tangent`]), at the same displacements: the same
//! trial states, forces and contact statuses.
//!
//! **A constant tangent.** Where every part reports its stiffness
//! unchanged since the tangent was last formed
//! ([`crate::assembly::Contribution::tangent_unchanged`]: linear elements,
//! dead loads, no contact or interface, inertia at the same time step) and
//! nothing rewrites the formed tangent (no prescribed non-zero value to
//! eliminate, no bordered indenter or lever), an evaluation that wants the
//! tangent keeps the one formed before: the parts add forces only. On the
//! hammer blow of bench/channel_hammer.toml (linear, 100 equal steps) it
//! spares a copy of the elastic stiffness and a pass adding the mass at
//! every step.
//!
//! A part whose stiffness depends on the state (a plastic body's elements,
//! contacts) answers from its last evaluation: the structure asks before
//! an evaluation, keeping the tangent on the word of the last one, and
//! again after it; if the answer changed (a point yielded, a contact
//! closed), the tangent is formed at once at the same state
//! ([`Structure::form_tangent`]) — except where only the elements changed
//! theirs: Newton's correction from a state where points begin to yield or
//! damage then takes the elastic stiffness kept (the next evaluation forms
//! theirs), as a return-mapping code's elastic predictor does; the
//! eigen-analyses, the path solvers and the finite-difference checks take
//! the exact tangent of `NonlinearProblem::evaluate`, Newton's iterations
//! `evaluate_for_correction`. On the free vibration of
//! examples/tube_drop_weight.toml the first evaluation of a step now and then
//! overshoots into yield at a few elements, and is back inside the surface
//! after that one correction. A kept tangent whose factor is older
//! (made while plasticity or contact still changed it) asks the solver to
//! factorize it at its next solve: the steps after it then solve with
//! their own tangent's factor (a dented tube vibrating freely after its
//! impact, examples/tube_drop_weight.toml).

use std::time::{Duration, Instant};

use super::Structure;
use crate::assembly::{Contribution, NO_EQ, Phase};
use crate::contact::assembly::UNSETTLED_FORCING;
use crate::solver::linear::LinearError;
use crate::solver::newton::Evaluation;

/// Largest forcing term (PCG stop, `solver::reuse`) with nonlinear
/// geometry. A solve stopped at `‖b − K x‖ ≤ η ‖b‖` leaves its error where
/// the residual norm sees least: in the soft modes (a thin wall's bending,
/// an open section's twist), whose stiffness is a small fraction of the
/// membrane stiffness that dominates `‖b‖`. Under large rotations an error
/// `δθ` there stretches the walls by `∝ δθ²` and the next residual jumps.
/// Measured on the channel of bench/channel_twist.toml with 2 L9 along each
/// flange, 4 along the web and 12 uniform B4 (`cufem run … --threads 1`, with the
/// geometric stiffness of the linearized stress, `elements`): its first
/// increment takes 11 corrections with the default cap `0.1`, 7 with
/// `1e-2`, 5 with `1e-3` and 4 with double-precision factors at every
/// correction; the run 101, 95, 92 and 91 corrections, 95, 98, 101 and 110
/// factorizations.
pub(crate) const LARGE_ROTATION_FORCING: f64 = 1e-3;

/// The share of the run's largest force scale below which a state counts
/// as unloaded ("zero flux"): its residual is then measured against that
/// share of the largest force, not against its own vanishing forces.
/// Abaqus's `ε_ℓ = 10⁻⁵` of its time-averaged flux (Abaqus Analysis User's
/// Guide, "Convergence criteria for nonlinear problems", zero flux).
pub(crate) const ZERO_FLUX: f64 = 1e-5;

/// The force scale Newton's relative residual divides by, floored by the
/// history of the run: `max(F, ZERO_FLUX · F_max)` with `F_max` the largest
/// force scale of a converged increment so far. Where every load, reaction
/// and contact force goes to zero (a specimen unloaded to zero opening),
/// `F` vanishes with the residual, and without the floor Newton meets its
/// relative tolerance only once the displacements reach round-off (the
/// double cantilever beam closed to zero opening: 17 corrections, each
/// shrinking the displacements about a billion times; with it one or two,
/// `crates/cufem-cli/tests/delamination.rs`).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ForceScale {
    /// The force scale of the last evaluation (N), before the floor.
    last: f64,
    /// The largest one of a converged increment (N).
    largest: f64,
}

impl ForceScale {
    /// Records the force scale `scale` of an evaluation and returns it floored.
    fn floored(&mut self, scale: f64) -> f64 {
        self.last = scale;
        scale.max(ZERO_FLUX * self.largest)
    }

    /// The last evaluation's state converged: its force scale joins the history.
    pub(super) fn commit(&mut self) {
        self.largest = self.largest.max(self.last);
    }
}

impl Structure<'_> {
    /// Evaluates every part at the present state: the residual, and the
    /// tangent if `wanted` (else the elements leave theirs out).
    pub(super) fn evaluate_parts(&mut self, wanted: bool) -> Result<Evaluation, LinearError> {
        self.report.timings.evaluations += 1;
        self.parts.contacts.move_indenters(self.force.offsets(self.state.lambda));
        let kept = wanted && self.tangent_is_constant();
        // every contribution into the tangent, in order
        let mut changes = 0;
        let mut releasing = true;
        let mut elapsed = [Duration::ZERO; 2];
        {
            let at = self.state.at();
            let mut tangent = self.system.tangent();
            tangent.wanted = wanted && !kept;
            let impulse = &self.parts.impulse;
            let weights = [Phase::Contact, Phase::Interfaces].map(|p| impulse.weight(p));
            for part in self.parts.each_mut() {
                let t = Instant::now();
                tangent.weight = match part.phase() {
                    Phase::Contact => weights[0],
                    Phase::Interfaces => weights[1],
                    Phase::Elements | Phase::Loads => 1.0,
                };
                let changed = part.evaluate(&at, &mut tangent);
                releasing &= changed == 0 || part.releasing();
                changes += changed;
                elapsed[usize::from(part.phase() == Phase::Contact)] += t.elapsed();
            }
        }
        self.report.timings.add_evaluation(elapsed, &self.parts.elements.last);
        self.system.tangent_formed |= wanted;
        let parts = &mut self.parts;
        if let Some(impulse) = parts.impulse.contacts.as_mut() {
            impulse.update(parts.contacts.forces().values);
        }
        if let Some(impulse) = parts.impulse.interfaces.as_mut() {
            impulse.update(parts.interfaces.forces().values);
        }
        // their forces summed into the residual, per DOF
        let imbalance = &mut self.system.imbalance;
        imbalance.fill(0.0);
        let mut scale: f64 = 0.0;
        for part in self.parts.each() {
            let mut f = part.forces();
            f.values = self.parts.impulse.force(part.phase(), f.values);
            let mut size2 = 0.0;
            for (r, &v) in imbalance.iter_mut().zip(f.values) {
                *r += f.sign * v;
                size2 += v * v;
            }
            if f.scale {
                scale = scale.max(size2.sqrt());
            }
            scale = scale.max(f.reference);
        }
        // the levers' pushes, and how far their displacements are from their targets
        let (lever_scale, lever_gap) = self.levers.evaluate(&self.state.u, imbalance, self.state.lambda);
        scale = scale.max(lever_scale);
        let eq = &self.system.assembler.dofs.eq;
        let (mut res2, mut reac2) = (0.0, 0.0);
        for (d, &e) in eq.iter().enumerate() {
            let r = imbalance[d];
            if e == NO_EQ || self.elimination.is_prescribed(e) {
                reac2 += r * r;
            } else {
                res2 += r * r;
            }
            if e != NO_EQ {
                self.system.rhs[e] = r;
            }
        }
        // prescribed values and lever displacements reached (exactly, after the first correction)
        let (off, size) = self.elimination.offset(&self.state.u);
        let (driven_res2, driven_target2) =
            self.force.evaluate(&self.parts.contacts, eq, &self.elimination, self.state.lambda);
        res2 += driven_res2;
        let scale = self.system.force_scale.floored(scale.max(reac2.sqrt()).max(driven_target2.sqrt()));
        let settled = changes == 0 && off <= 1e-12 * size && lever_gap <= 1e-12;
        self.system.elastic_onset = false;
        if kept {
            self.judge_kept_tangent();
        } else if wanted {
            self.system.tangent_changed();
        }
        let r = if scale > 0.0 { res2.sqrt() / scale } else { 1.0 };
        self.system.forcing = if settled { r } else { r.min(UNSETTLED_FORCING) };
        if self.parts.elements.discretisation.kinematics.is_nonlinear() {
            self.system.forcing = self.system.forcing.min(LARGE_ROTATION_FORCING);
        }
        let releasing = releasing && changes > 0;
        Ok(Evaluation { residual_norm: res2.sqrt(), force_scale: scale, settled, releasing })
    }

    /// After an evaluation that kept the tangent on the last one's word
    /// (module docs): kept if every part still says so; formed at once if
    /// a contact or another part changed its stiffness; kept for this one
    /// correction if only the elements left their elastic tangent (points
    /// yielding or damaging at the onset of a step: the elastic stiffness
    /// is the step's first correction, the next evaluation forms theirs).
    fn judge_kept_tangent(&mut self) {
        let at = self.state.at();
        let others = self.parts.each().filter(|p| p.phase() != Phase::Elements).all(|p| p.tangent_unchanged(&at));
        if !others {
            self.system.tangent_stale = true;
        } else if self.parts.elements.tangent_unchanged(&at) {
            self.system.keep_tangent();
        } else {
            self.system.elastic_onset = true;
        }
    }

    /// True if the tangent formed before is that of the present state
    /// (module docs, a constant tangent).
    fn tangent_is_constant(&self) -> bool {
        let at = self.state.at();
        self.system.tangent_formed
            && self.elimination.is_empty()
            && !self.force.is_force_controlled()
            && !self.levers.is_active()
            && self.parts.each().all(|p| p.tangent_unchanged(&at))
    }

    /// Forms the tangent at the present state if the last evaluation left
    /// the element tangents out, keeping that evaluation's forcing term
    /// (the repeated one would see no contact status change and report the
    /// contacts settled).
    pub(super) fn form_tangent(&mut self) -> Result<(), LinearError> {
        if self.system.tangent_stale && self.tangent_is_constant() {
            self.system.tangent_stale = false;
        }
        if self.system.tangent_stale {
            let forcing = self.system.forcing;
            self.evaluate_parts(true)?;
            self.system.forcing = forcing;
            self.system.tangent_stale = false;
            self.report.timings.reevaluations += 1;
        }
        Ok(())
    }
}
