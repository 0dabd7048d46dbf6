//! The contacts' part of the structure's residual and tangent
//! (`crate::assembly::Contribution`): every rigid indenter and every pair
//! contact of a model, with the state of each contact point (gap, force,
//! slip, multiplier) committed only after an increment converges.
//!
//! One file per contact kind: `pairs` (node-to-node, against a rigid
//! surface fixed in the reference configuration or a master node), `rigid`
//! (the exact gap of a rigid surface in the current configuration,
//! `method = "surface"` on an indenter), `surface` (segment-to-segment
//! between deformable bodies, `method = "surface"` on a contact);
//! `augment` holds the Uzawa updates of the augmented Lagrangian, `limit`
//! the step-length control that keeps a correction from carrying open
//! points deep into contact. A new
//! contact kind is a new file here and a branch in `Contacts::evaluate`.
//!
//! Forces go to the contact's own nodal force vector `f_c` (the residual is
//! `R = f_int − λ f_ext − f_c`); each point's block `K` (normal penalty plus
//! friction) is split by `split` into the symmetric part
//! the structure factorizes and the unsymmetric rest (a sliding point's
//! pressure coupling), which goes beside it (`Tangent::add_rest_block`).

mod augment;
mod limit;
#[cfg(test)]
pub(crate) use limit::SMALLEST_FRACTION;
mod pairs;
mod rigid;
mod surface;

use std::ops::Range;

use super::{Indenter, PairContact};
use crate::assembly::{At, Contribution, Forces, Phase, Tangent};
use crate::mesh::Mesh;

/// Largest forcing term (PCG stop, `solver::reuse`) of a correction made
/// while the contact status or the prescribed values have not settled.
/// Inexact Newton's theory needs a smooth residual; while points open and
/// close, a step solved only to `krylov_tolerance` (0.1) can flip the wrong
/// points and the active set then cycles: `examples/hertz_ball.toml` cycled
/// in its last increment (two cutbacks, 12.1 s) where solves to 1e-2 converge
/// in 4 increments (5.0 s). Once settled, the looser stop applies (the tubes
/// need 4–5 fewer factorizations with it). crates/cufem-cli/tests/examples.rs `hertz_ball`
/// asserts the 4 increments. With friction, points switching between stick
/// and slip count as unsettled too.
pub(crate) const UNSETTLED_FORCING: f64 = 1e-2;

/// A gap below this fraction of the largest body is round-off (the
/// status of a point there does not unsettle Newton).
pub(crate) const ROUNDOFF_GAP: f64 = 1e-12;

/// State of one contact point after an evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPoint {
    /// Global node (the slave node for pairs).
    pub node: usize,
    /// Master node for pairs.
    pub master: Option<usize>,
    /// Normal gap (m), negative = penetration.
    pub gap: f64,
    /// Force on the (slave) node (N).
    pub force: [f64; 3],
    /// Tributary area (m²).
    pub area: f64,
    /// True if active.
    pub active: bool,
    /// Augmented-Lagrangian multiplier (N): the contact force carried over
    /// from the last augmentation (0 for pure penalty).
    pub multiplier: f64,
    /// Accumulated tangential slip (m, slave relative to master) of a
    /// frictional point, committed with the increment.
    pub slip: [f64; 3],
    /// True if the frictional point slides (on the Coulomb cone).
    pub sliding: bool,
    /// Contact normal (pointing to the slave body or body under an indenter).
    pub normal: [f64; 3],
    /// Position relative to a rigid indenter, `X + u − d` (m), at the last
    /// evaluation of an indenter with `method = "surface"` (its friction
    /// measures the slip increment from the committed one); zero otherwise.
    pub position: [f64; 3],
}

/// Every contact of a model and the state of its points.
#[derive(Debug)]
pub struct Contacts<'m> {
    mesh: &'m Mesh,
    indenters: &'m [Indenter],
    pairs: &'m [PairContact],
    frictional: bool,
    /// All indenter candidates, then all pairs, in model order.
    points: Vec<ContactPoint>,
    committed: Vec<ContactPoint>,
    /// Each indenter's, then each pair contact's points.
    ranges: Vec<Range<usize>>,
    /// Each point's assembled block of the last evaluation.
    blocks: Vec<[[f64; 3]; 3]>,
    /// Per pair contact: the projections and weighted gaps of a surface contact.
    surface: Vec<surface::State>,
    /// Contact forces of the last evaluation (per DOF).
    f_contact: Vec<f64>,
    /// The rigid displacement of each indenter at this evaluation.
    offsets: Vec<[f64; 3]>,
    /// The next evaluation is the first of an increment that starts at the
    /// committed state (frictional points then get the stick tangent).
    first_evaluation: bool,
    /// The next evaluation is the first of an increment started on the
    /// secant of the last one: frictionless rigid-surface points in contact
    /// at the committed state keep their penalty law there (`rigid`).
    on_secant: bool,
    /// Points that kept their contact so at the last evaluation.
    kept: usize,
    /// Every status change of the last evaluation was a release
    /// (`Contribution::releasing`).
    released_only: bool,
    /// No point was active at the last evaluation that formed a tangent:
    /// the contacts added no stiffness to it.
    formed_open: bool,
    /// Surface contacts between deformable bodies are evaluated in the
    /// current configuration (`crate::contact::current`: nonlinear
    /// geometry); otherwise their projections are fixed within an increment.
    current: bool,
    /// With `current`: the current master normal of every node pair, per
    /// pair contact (empty for surface contacts).
    nodal_normals: Vec<Vec<crate::contact::nodal_normal::NodalNormal>>,
    /// [`ROUNDOFF_GAP`] times the largest body's size (m).
    roundoff_gap: f64,
}

impl<'m> Contacts<'m> {
    /// The contact points of `indenters` and `pairs` on `mesh`, the surface
    /// contacts projected in the reference configuration; with `current`
    /// (nonlinear geometry) surface contacts between deformable bodies are
    /// evaluated in the current configuration.
    pub fn new(mesh: &'m Mesh, indenters: &'m [Indenter], pairs: &'m [PairContact], current: bool) -> Self {
        let mut points = Vec::new();
        let mut ranges = Vec::new();
        for ind in indenters {
            let start = points.len();
            points.extend(ind.nodes.iter().map(|c| ContactPoint {
                node: c.node,
                area: c.area,
                position: mesh.coords(c.node),
                ..Default::default()
            }));
            ranges.push(start..points.len());
        }
        for pc in pairs {
            let start = points.len();
            points.extend(pc.pairs.iter().map(|p| ContactPoint {
                node: p.slave,
                master: Some(p.master),
                area: p.area,
                gap: p.gap0,
                ..Default::default()
            }));
            points.extend(surface::initial_points(pc));
            ranges.push(start..points.len());
        }
        let frictional = indenters.iter().any(|i| i.friction.is_some()) || pairs.iter().any(|c| c.friction.is_some());
        let mut contacts = Self {
            mesh,
            indenters,
            pairs,
            frictional,
            blocks: vec![[[0.0; 3]; 3]; points.len()],
            committed: points.clone(),
            points,
            ranges,
            surface: vec![Default::default(); pairs.len()],
            f_contact: vec![0.0; mesh.n_dofs()],
            offsets: vec![[0.0; 3]; indenters.len()],
            first_evaluation: false,
            on_secant: false,
            kept: 0,
            released_only: false,
            formed_open: false,
            current,
            roundoff_gap: ROUNDOFF_GAP * mesh.bodies.iter().map(|b| b.size()).fold(0.0, f64::max),
            nodal_normals: if current {
                pairs
                    .iter()
                    .map(|pc| {
                        let masters: Vec<usize> = pc.pairs.iter().map(|p| p.master).collect();
                        crate::contact::nodal_normal::NodalNormal::for_nodes(mesh, &pc.master, &masters)
                    })
                    .collect()
            } else {
                Vec::new()
            },
        };
        contacts.update_projections(&vec![0.0; mesh.n_dofs()]);
        contacts
    }

    /// Every contact point after the last evaluation (all indenter
    /// candidates, then all pairs, in model order).
    pub fn points(&self) -> &[ContactPoint] {
        &self.points
    }

    /// The points, to be set by hand in tests.
    #[cfg(test)]
    pub(crate) fn points_mut(&mut self) -> &mut [ContactPoint] {
        &mut self.points
    }

    /// The points of each indenter, then of each pair contact, in model order.
    pub fn ranges(&self) -> &[Range<usize>] {
        &self.ranges
    }

    /// True if the model has contact points (indenters or contacts).
    pub(crate) fn has_points(&self) -> bool {
        !self.points.is_empty()
    }

    /// True if some indenter or contact has friction.
    pub(crate) fn is_frictional(&self) -> bool {
        self.frictional
    }

    /// Each point's assembled block `K = −∂f/∂u_slave` of the last evaluation.
    pub fn blocks(&self) -> &[[[f64; 3]; 3]] {
        &self.blocks
    }

    /// Sets the rigid displacement of every indenter for the next
    /// evaluations (prescribed by its motion, or solved for under force
    /// control).
    pub(crate) fn move_indenters(&mut self, offsets: impl IntoIterator<Item = [f64; 3]>) {
        for (o, v) in self.offsets.iter_mut().zip(offsets) {
            *o = v;
        }
    }

    /// A new increment starts at the committed state: its first evaluation
    /// gives sliding points the stick tangent (`pairs`).
    pub(crate) fn start_increment(&mut self) {
        self.first_evaluation = true;
        self.on_secant = false;
    }

    /// Points that opened or closed since the committed state, and the
    /// points active there and now: the step control's measure of the
    /// contact set (`solver::step_control`).
    pub(crate) fn status_changes(&self) -> (usize, usize, usize) {
        let changed = self.points.iter().zip(&self.committed).filter(|(p, c)| p.active != c.active).count();
        let active = |v: &[ContactPoint]| v.iter().filter(|p| p.active).count();
        (changed, active(&self.committed), active(&self.points))
    }

    /// The increment starts on the secant of the last one instead: a point
    /// that slid is past its cone, and its consistent tangent applies at
    /// once; a frictionless point of a rigid surface that the secant lifted
    /// off keeps the contact it had (`rigid`, module docs).
    pub(crate) fn start_extrapolated(&mut self) {
        self.first_evaluation = false;
        self.on_secant = true;
    }

    /// The points that kept their contact at the last evaluation, the first
    /// of an increment started on the secant (`rigid`, module docs): its
    /// residual holds their tensions, which no later evaluation has.
    pub(crate) fn kept_points(&self) -> usize {
        self.kept
    }
}

impl Contribution for Contacts<'_> {
    fn phase(&self) -> Phase {
        Phase::Contact
    }

    /// Penalty contact: forces into `f_contact`, stiffness into the tangent.
    /// Returns the number of points whose active (or, with friction,
    /// stick–slip) status changed.
    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize {
        self.f_contact.fill(0.0);
        let mut changes = 0;
        // with friction a point switching between stick and slip is a change
        // of the active set too (UNSETTLED_FORCING)
        let was_sliding: Vec<bool> =
            if self.frictional { self.points.iter().map(|p| p.sliding).collect() } else { Vec::new() };
        let was_active: Vec<bool> = self.points.iter().map(|p| p.active).collect();
        self.kept = 0;
        let (indenters, pairs) = (self.indenters, self.pairs);
        let mut k = 0;
        for (k_ind, ind) in indenters.iter().enumerate() {
            // the rigid surface's displacement plays the master's part
            let offset = self.offsets[k_ind];
            if ind.updated {
                for c in &ind.nodes {
                    changes += usize::from(self.rigid_surface(at, tangent, k, c, (ind, offset)));
                    k += 1;
                }
                continue;
            }
            for c in &ind.nodes {
                let pair = (c.node, None, offset, c.gap0, c.normal, c.penalty);
                changes += usize::from(self.pair(at, tangent, k, pair, ind.friction.as_ref()));
                k += 1;
            }
        }
        for (c, pc) in pairs.iter().enumerate() {
            for (j, p) in pc.pairs.iter().enumerate() {
                if self.current {
                    changes += usize::from(self.pair_current(at, tangent, k, (c, j)));
                    k += 1;
                    continue;
                }
                let um = [0, 1, 2].map(|i| at.u[3 * p.master + i]);
                // an interference fit's overlap is imposed over the first step
                let gap0 = p.gap0 + pc.overlap_relief(j, at.lambda);
                let pair = (p.slave, Some(p.master), um, gap0, p.normal, p.penalty);
                changes += usize::from(self.pair(at, tangent, k, pair, pc.friction.as_ref()));
                k += 1;
            }
            if let Some(s) = &pc.surface {
                changes += self.assemble_surface(at, tangent, k, c, s, pc.friction.as_ref());
                k += s.slave_nodes.len();
            }
        }
        changes += was_sliding.iter().zip(&self.points).filter(|(w, p)| **w != p.sliding).count();
        // A point that opens or closes at a gap of round-off carries no
        // force either way: its flip leaves the residual as it is and must
        // not keep Newton from settling. Implicit dynamics brings nodes to
        // rest on a surface (an inelastic impact, `dynamics::impulse`), and
        // bodies resting on rigid supports at zero gap start there.
        let roundoff = self.roundoff_gap;
        let grazing = was_active.iter().zip(&self.points).filter(|(w, p)| **w != p.active && p.gap.abs() <= roundoff);
        changes = changes.saturating_sub(grazing.count());
        self.released_only = self.only_released(&was_active, &was_sliding);
        self.first_evaluation = false;
        self.on_secant = false;
        if tangent.wanted {
            self.formed_open = self.points.iter().all(|p| !p.active);
        }
        changes
    }

    fn forces(&self) -> Forces<'_> {
        Forces { values: &self.f_contact, sign: -1.0, scale: true, reference: 0.0 }
    }

    /// Commits the points and projects the surface contacts anew from the
    /// converged displacements.
    fn commit(&mut self, at: &At<'_>) {
        self.committed.copy_from_slice(&self.points);
        self.update_projections(at.u);
    }

    fn restore(&mut self) {
        self.points.copy_from_slice(&self.committed);
    }

    /// Without indenters and pair contacts it adds nothing, and nothing
    /// either while no point touches: none at the last evaluation, nor at
    /// the one that formed the tangent (an inactive point adds no block).
    fn tangent_unchanged(&self, _at: &At<'_>) -> bool {
        (self.indenters.is_empty() && self.pairs.is_empty())
            || (self.formed_open && self.points.iter().all(|p| !p.active))
    }

    fn releasing(&self) -> bool {
        self.released_only
    }
}

impl Contacts<'_> {
    /// True if the last evaluation opened a point (beyond a gap of
    /// round-off) and neither closed one nor switched a point that stayed
    /// in contact between stick and slip (`was_sliding` empty without
    /// friction): what two stacked beams do while Newton peels their
    /// interface open from the bonded start of zero gaps, a row or two of
    /// nodes a correction (`solver::newton`, the releasing iterations).
    pub(crate) fn only_released(&self, was_active: &[bool], was_sliding: &[bool]) -> bool {
        let roundoff = self.roundoff_gap;
        let (mut opened, mut other) = (false, false);
        for (k, (p, &w)) in self.points.iter().zip(was_active).enumerate() {
            let switched = w && p.active && was_sliding.get(k).is_some_and(|&s| s != p.sliding);
            if w != p.active && p.gap.abs() <= roundoff {
                continue;
            }
            opened |= w && !p.active;
            other |= (!w && p.active) || switched;
        }
        opened && !other
    }
}
