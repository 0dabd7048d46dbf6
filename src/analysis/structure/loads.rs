//! The external loads' part of the residual: each load's consistent nodal
//! forces times its factor in the load history at λ (no stiffness: the
//! loads do not follow the deformation).

use super::inputs::Loading;
use crate::assembly::{At, Contribution, Forces, Phase, Tangent};
use crate::setup::steps::{self, Item};

/// `λ`-scaled external loads.
#[derive(Debug)]
pub(crate) struct Loads<'m> {
    loading: Loading<'m>,
    /// External loads at the λ of the last evaluation (per DOF).
    pub(crate) f_ext: Vec<f64>,
}

impl<'m> Loads<'m> {
    /// No load yet (λ = 0) on `n_dofs` DOFs.
    pub fn new(loading: Loading<'m>, n_dofs: usize) -> Self {
        Self { loading, f_ext: vec![0.0; n_dofs] }
    }
}

impl Contribution for Loads<'_> {
    fn phase(&self) -> Phase {
        Phase::Loads
    }

    fn evaluate(&mut self, at: &At<'_>, _tangent: &mut Tangent<'_>) -> usize {
        let loading = self.loading;
        self.f_ext.fill(0.0);
        for (i, l) in loading.loads.iter().enumerate() {
            let a = steps::factor(loading.steps, Item::Load(i), at.lambda);
            for (n, f) in &l.nodal_forces {
                for k in 0..3 {
                    self.f_ext[3 * n + k] += a * f[k];
                }
            }
        }
        0
    }

    fn forces(&self) -> Forces<'_> {
        Forces { values: &self.f_ext, sign: -1.0, scale: true, reference: 0.0 }
    }

    fn commit(&mut self, _at: &At<'_>) {}

    fn restore(&mut self) {}

    /// Dead loads add no stiffness.
    fn tangent_unchanged(&self, _at: &At<'_>) -> bool {
        true
    }
}
