//! `[[materials]]`: elastic constants and the plasticity of a material
//! (its anisotropic constants and strengths are in `anisotropy.rs`;
//! `setup/material.rs` checks the values).

use serde::Deserialize;

use super::{Exact, OrthotropicFile, StrengthsFile, tagged_table};
use crate::input::ranges;

/// `[[materials]]`: isotropic (optionally plastic) or anisotropic elastic.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    /// Name, referenced by `bodies[].material`, plies and zones.
    pub name: String,
    /// Isotropic: Young's modulus E (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub young_modulus: Option<f64>,
    /// Isotropic: Poisson's ratio ν.
    #[schemars(transform = ranges::POISSON_RATIO.schema())]
    pub poisson_ratio: Option<f64>,
    /// Orthotropic engineering constants in the material axes.
    pub orthotropic: Option<OrthotropicFile>,
    /// A full 6×6 stiffness in the material axes (Pa; Voigt order xx, yy,
    /// zz, xy, xz, yz with engineering shears).
    pub stiffness: Option<Vec<Exact<f64, 6>>>,
    /// Strengths for the failure indices.
    pub strengths: Option<StrengthsFile>,
    /// Mass density ρ (kg/m³): needed by the mass matrix (`analysis.type = "modal"`).
    #[schemars(transform = ranges::MASS_DENSITY.schema())]
    pub density: Option<f64>,
    /// J2 plasticity (elastic when absent).
    pub plasticity: Option<PlasticityFile>,
    /// An interface material's cohesive law (only with `name`; referenced
    /// by a laminate's `interfaces`, refused as a body material).
    pub cohesive: Option<super::CohesiveFile>,
}

tagged_table! {
    /// `[materials.plasticity]`: von Mises plasticity with isotropic and
    /// kinematic hardening.
    pub struct PlasticityFile {
        /// Initial yield stress (Pa); for a table, its first stress.
        yield_stress: Option<f64> => ranges::POSITIVE.schema(),
        /// Armstrong–Frederick back-stresses.
        kinematic: Option<Vec<KinematicFile>> => max_back_stresses,
    }
    /// The isotropic hardening law and its own keys.
    pub hardening: enum HardeningLaw by "hardening" {
        /// σ_y constant.
        Perfect = "perfect" {}
        /// σ_y + H peeq.
        Linear = "linear" {
            /// The plastic hardening modulus H (Pa).
            hardening_modulus: Option<f64> => ranges::NON_NEGATIVE.schema(),
        }
        /// Piecewise linear `[[peeq, stress], …]`.
        Table = "table" {
            /// The points `[peeq, yield stress (Pa)]`, from peeq = 0.
            table: Option<Vec<Exact<f64, 2>>>,
        }
        /// σ_y + Q (1 − exp(−b peeq)).
        Voce = "voce" {
            /// Q (Pa).
            saturation_stress: Option<f64> => ranges::NON_NEGATIVE.schema(),
            /// b.
            saturation_rate: Option<f64> => ranges::SATURATION_RATE.schema(),
        }
    }
    mirror plasticity_file;
}

/// At most [`crate::materials::MAX_BACKSTRESSES`] back-stresses.
fn max_back_stresses(schema: &mut schemars::Schema) {
    schema.insert("maxItems".into(), crate::materials::MAX_BACKSTRESSES.into());
}

/// One entry of `plasticity.kinematic`: an Armstrong–Frederick back-stress.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct KinematicFile {
    /// C_i (Pa), positive and at most 100 E.
    #[schemars(transform = ranges::POSITIVE.schema())]
    pub modulus: f64,
    /// γ_i (dimensionless); 0 gives linear (Prager) kinematic hardening.
    #[schemars(transform = ranges::KINEMATIC_RECALL.schema())]
    pub recall: f64,
}
