//! The elements' part of the residual and tangent: internal forces and the
//! element tangents of every body (`assembly::Assembler`, the kernel of
//! `elements`, the material point of `materials`), and the Gauss-point
//! history, committed only after an increment converges.
//!
//! **Linear elements.** In small strain with materials that neither yield
//! nor damage, the internal force is the product of the elastic stiffness
//! with the displacements (`assembly::ElasticProduct`), the tangent that
//! stiffness, and the Gauss loop runs only when the stresses are read
//! ([`Elements::stresses`]: output frames, step ends, the end of the run),
//! from the displacements of the last evaluation. The strain energy of a
//! transient run's ledger is then `½ uᵀ f` ([`Elements::elastic_energy`]).
//!
//! **Elastic elements of a nonlinear material.** In small strain a Gauss
//! point on its elastic tangent (a plastic point unloading or inside its
//! yield surface, an intact ply) has the stiffness of the cached elastic
//! tangent, whatever its history. Where every point was so at the
//! evaluation that formed the tangent and again at the last one, the
//! elements report their tangent unchanged
//! ([`Contribution::tangent_unchanged`]) and the structure keeps the one
//! formed (`analysis::structure::evaluation`): the free vibration of a
//! dented tube after its impact costs force evaluations and solves only.

use std::sync::{Mutex, PoisonError};

use crate::assembly::{
    Assembler, AssemblyStats, At, Contribution, ElasticProduct, Forces, Inputs, Outputs, Phase, Tangent,
};
use crate::materials::PointState;
use crate::setup::Discretisation;
use crate::voigt::Voigt;

/// Internal forces, Gauss-point states and stresses of all bodies.
#[derive(Debug)]
pub(crate) struct Elements<'m> {
    /// The meshes, Gauss-point values, materials and kinematics.
    pub(crate) discretisation: Discretisation<'m>,
    /// First Gauss point of each body.
    pub(crate) gp_offsets: Vec<usize>,
    /// Committed Gauss-point states.
    pub committed: Vec<PointState>,
    trial: Vec<PointState>,
    /// Gauss-point stresses of the last evaluation ([`Self::stresses`]).
    stress: Mutex<Stresses>,
    /// Internal forces of the last evaluation (per DOF).
    f_int: Vec<f64>,
    /// The last evaluation's element loop: its plastic Gauss points and
    /// the time in the kernel's passes.
    pub last: AssemblyStats,
    /// A stress-free initial displacement (geometric imperfection), per DOF.
    pub initial: Option<Vec<f64>>,
    /// The ply damage of the Gauss points (`crate::damage`; empty without
    /// damage), committed with the states.
    pub damage: crate::damage::BodyDamage,
    /// The clock of a transient run (`None` in a static one): the damage
    /// viscosity's step is the time step in seconds there, the change of
    /// the load factor in a static run.
    pub clock: Option<&'m crate::dynamics::TransientSettings>,
    /// The internal force as a product with the elastic stiffness, where
    /// the elements are linear (module docs; `None` otherwise).
    product: Option<ElasticProduct>,
    /// The last evaluation that formed a tangent found every Gauss point on
    /// the elastic tangent in small strain: the elements' part of that
    /// tangent is the cached elastic stiffness (module docs).
    formed_elastic: bool,
}

/// The Gauss-point stresses of the last evaluation, formed when read after
/// a linear one.
#[derive(Debug, Default)]
struct Stresses {
    values: Vec<Voigt>,
    /// The displacements of a linear evaluation whose stresses are not
    /// formed yet.
    pending: Option<Vec<f64>>,
}

impl<'m> Elements<'m> {
    /// Virgin states for every Gauss point of `discretisation`.
    pub fn new(discretisation: Discretisation<'m>) -> Self {
        let d = discretisation;
        let mut gp_offsets = Vec::with_capacity(d.cells.len());
        let mut n_gp = 0;
        for (b, g) in d.mesh.bodies.iter().zip(d.cells) {
            gp_offsets.push(n_gp);
            n_gp += b.n_elements() * g.gp_per_element();
        }
        let damage = crate::damage::BodyDamage::new(&d, &gp_offsets, n_gp);
        Self {
            discretisation,
            gp_offsets,
            committed: vec![PointState::default(); n_gp],
            trial: vec![PointState::default(); n_gp],
            stress: Mutex::new(Stresses { values: vec![[0.0; 6]; n_gp], pending: None }),
            f_int: vec![0.0; d.mesh.n_dofs()],
            last: AssemblyStats::default(),
            initial: None,
            damage,
            clock: None,
            product: None,
            formed_elastic: false,
        }
    }

    /// Evaluates the internal force as a product with the elastic
    /// stiffness cached in `assembler` from now on, if the elements are
    /// linear: small strain, no material that yields or damages, no initial
    /// displacement (else nothing changes).
    pub(crate) fn use_product_if_linear(&mut self, assembler: &Assembler) {
        let d = &self.discretisation;
        let linear = !d.kinematics.is_nonlinear()
            && self.initial.is_none()
            && d.materials.iter().all(|m| m.hardening.is_none() && m.damage.is_none());
        // a model whose every DOF is held has no equation, and no stiffness to cache
        if linear && assembler.dofs.n_eq > 0 {
            let zeros = vec![0.0; d.mesh.n_dofs()];
            self.product = Some(ElasticProduct::new(assembler, &self.inputs(&zeros)));
        }
    }

    /// The Gauss-point stresses of the last evaluation (formed now by the
    /// element loop of `assembler` if that evaluation was linear).
    pub(crate) fn stresses(&self, assembler: &Assembler) -> Vec<Voigt> {
        self.with_stresses(assembler, <[Voigt]>::to_vec)
    }

    /// `read` of the Gauss-point stresses of the last evaluation, without
    /// a copy ([`Self::stresses`]).
    fn with_stresses<R>(&self, assembler: &Assembler, read: impl FnOnce(&[Voigt]) -> R) -> R {
        let mut s = self.stress.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(u) = s.pending.take() {
            let n_gp = self.committed.len();
            assembler.assemble(
                &self.inputs(&u),
                Outputs {
                    force: &mut vec![0.0; u.len()],
                    tangent: None,
                    trial: &mut vec![PointState::default(); n_gp],
                    stress: &mut s.values,
                    damage: &mut [],
                    rest: None,
                },
            );
        }
        read(&s.values)
    }

    /// The strain energy of the last evaluation (J): `½ uᵀ f_int` at its
    /// displacements `u` for linear elements, else the sum over the Gauss
    /// points (`post::estimate::elastic_energy`, with the damaged points'
    /// stored energy).
    pub(crate) fn elastic_energy(&self, u: &[f64], assembler: &Assembler) -> f64 {
        if self.product.is_some() && self.initial.is_none() {
            return 0.5 * u.iter().zip(&self.f_int).map(|(a, b)| a * b).sum::<f64>();
        }
        let d = self.discretisation;
        self.with_stresses(assembler, |stress| {
            crate::post::estimate::elastic_energy(
                d.mesh,
                d.cells,
                d.materials,
                (stress, &self.damage.trial),
                &self.gp_offsets,
            )
        })
    }

    /// The assembly inputs at displacements `u` from the committed states
    /// (for the elastic tangent cached at setup).
    pub fn inputs<'a>(&'a self, u: &'a [f64]) -> Inputs<'a> {
        Inputs {
            state: self.discretisation.fe_state(u, &self.committed, &self.gp_offsets, self.damage.input()),
            predictor: Default::default(),
            initial: self.initial.as_deref(),
            before: None,
        }
    }
}

impl Elements<'_> {
    /// The largest increment of the equivalent plastic strain at any Gauss
    /// point, from the committed states to those of the last evaluation
    /// (the step control's measure of plastic flow).
    pub(crate) fn largest_peeq_increment(&self) -> f64 {
        self.trial.iter().zip(&self.committed).map(|(t, c)| t.peeq - c.peeq).fold(0.0, f64::max)
    }

    /// The largest increment of a ply damage mode at any point since the
    /// committed state (of the damage the stiffness takes; 0 without ply
    /// damage).
    pub(crate) fn largest_damage_increment(&self) -> f64 {
        let d = &self.damage;
        d.trial
            .iter()
            .zip(&d.committed)
            .flat_map(|(t, c)| t.viscous.iter().zip(&c.viscous).map(|(a, b)| a - b))
            .fold(0.0, f64::max)
    }
}

impl Contribution for Elements<'_> {
    fn phase(&self) -> Phase {
        Phase::Elements
    }

    /// Overwrites the whole tangent (the assembler starts from the elastic
    /// tangent and corrects the non-elastic elements): the elements are
    /// evaluated first. When the tangent is not wanted, the kernel's second
    /// pass (the element tangents and their scatter) is skipped. Linear
    /// elements take the product instead of the kernel (module docs).
    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize {
        let stress = self.stress.get_mut().unwrap_or_else(PoisonError::into_inner);
        if let Some(product) = self.product.as_mut().filter(|_| self.initial.is_none()) {
            product.force(tangent.assembler, at.u, &mut self.f_int);
            if tangent.wanted {
                tangent.assembler.elastic_tangent_into(tangent.values);
            }
            let pending = stress.pending.get_or_insert_with(Vec::new);
            pending.clear();
            pending.extend_from_slice(at.u);
            self.last = AssemblyStats::default();
            return 0;
        }
        stress.pending = None;
        let crate::damage::BodyDamage { committed, band, trial: damage_trial, lambda, .. } = &mut self.damage;
        let step = match self.clock {
            Some(clock) => (clock.time(at.lambda) - clock.time(*lambda)).abs(),
            None => at.viscous_step.unwrap_or((at.lambda - *lambda).abs()),
        };
        // the end-of-step stress of damaged points (`dynamics::ply_forces`)
        let impulse = self.clock.map(|c| crate::materials::damage_impulse::PointForces {
            recursion: c.recursion(),
            end_of_step: c.ply_damage_forces == crate::dynamics::PlyDamageForces::Implicit,
        });
        let damage_in = crate::assembly::DamageInput { committed, band, step, impulse };
        let inputs = Inputs {
            state: self.discretisation.fe_state(at.u, &self.committed, &self.gp_offsets, damage_in),
            predictor: at.predictor,
            initial: self.initial.as_deref(),
            before: at.u_before,
        };
        self.last = tangent.assembler.assemble(
            &inputs,
            Outputs {
                force: &mut self.f_int,
                tangent: if tangent.wanted { Some(&mut *tangent.values) } else { None },
                trial: &mut self.trial,
                stress: &mut stress.values,
                damage: damage_trial,
                rest: if tangent.wanted { tangent.rest.as_deref_mut() } else { None },
            },
        );
        if tangent.wanted {
            self.formed_elastic = !self.discretisation.kinematics.is_nonlinear() && self.last.inelastic_elements == 0;
        }
        0
    }

    fn forces(&self) -> Forces<'_> {
        Forces { values: &self.f_int, sign: 1.0, scale: false, reference: 0.0 }
    }

    fn commit(&mut self, at: &At<'_>) {
        self.committed.copy_from_slice(&self.trial);
        self.damage.commit(at.lambda);
    }

    fn restore(&mut self) {}

    /// Linear elements' tangent is the elastic stiffness, always; other
    /// elements' in small strain while every Gauss point stays on its elastic
    /// tangent, at the last evaluation as at the one that formed the tangent
    /// (a plastic body unloading, a ply short of damage: module docs).
    fn tangent_unchanged(&self, _at: &At<'_>) -> bool {
        (self.product.is_some() && self.initial.is_none()) || (self.formed_elastic && self.last.inelastic_elements == 0)
    }
}
