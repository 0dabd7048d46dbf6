//! A damaging ply point as the element kernel sees it ([`super::damage`]):
//! the global strain turned to the material axes, the law's stress and
//! tangent turned back, the end-of-step stress of a transient run
//! ([`super::damage_impulse`]), and the consistent tangent split into its
//! symmetric part and the rank-one terms of the rest
//! ([`super::damage::Softening`]).

use super::damage::{self, Softening};
use super::{Material, PointState, Response, damage_impulse};
use crate::voigt::{self, Voigt};

impl Material {
    /// The material-point update of a damaging ply: the global strain
    /// turned to the material axes, the law's stress and tangent turned
    /// back (`σ = Tᵀ σ_m`, `C = Tᵀ C_T T`), with the crack-band lengths
    /// `band` (m) over the step `step` (the viscosity's) from the committed
    /// state `old`, the trial state written into `state`, on its damage
    /// surface the loading branch's tangent if `loading`. The response's
    /// tangent is the symmetric part of the law's; the rank-one terms of the
    /// consistent tangent come apart, in the global axes (with the same
    /// impulse factor). The tangent is reported elastic while no mode has
    /// damaged (the cached elastic matrices stay valid); `plastic` is never
    /// set.
    pub(crate) fn update_damaged(
        &self,
        law: &damage::PlyDamage,
        strain: &Voigt,
        (band, step, impulse, loading): ([f64; 2], f64, Option<damage_impulse::PointForces>, bool),
        (old, state): (&damage::DamageState, &mut damage::DamageState),
    ) -> (Response, Softening) {
        let t = self.frame.strain_rotation();
        let local = voigt::mat_vec(&t, strain);
        let (local_stress, tangent, terms) = law.update_into(&local, band, (step, loading), old, state);
        let stress: Voigt = std::array::from_fn(|i| (0..6).map(|k| t[k][i] * local_stress[k]).sum());
        // the end-of-step stress of a damaged point in a transient run
        // (`damage_impulse`): its force stress, and 1/γ on its tangent
        let factor = impulse
            .map_or(1.0, |forces| damage_impulse::end_of_step(forces, law, old, state, (&stress, &local_stress)));
        let intact = state.damage.iter().all(|&d| d == 0.0) && factor == 1.0;
        if intact {
            let response = Response {
                stress,
                tangent: self.elastic,
                state: PointState::default(),
                plastic: false,
                elastic_tangent: true,
            };
            return (response, Softening::default());
        }
        // the consistent tangent is unsymmetric: its symmetric part here,
        // the rest from the terms (`damage::Softening`)
        let mut symmetric = voigt::symmetric_part(&tangent);
        damage_impulse::scale(&mut symmetric, factor);
        let tangent = self.frame.stiffness_to_global(&symmetric);
        let response =
            Response { stress, tangent, state: PointState::default(), plastic: false, elastic_tangent: false };
        (response, terms.in_global_axes(&t, factor))
    }
}
