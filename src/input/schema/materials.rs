//! `[[materials]]`: elastic constants and the plasticity of a material
//! (its anisotropic constants and strengths are in `anisotropy.rs`;
//! `setup/material.rs` checks the values).

use serde::Deserialize;

use super::{Exact, OrthotropicFile, StrengthsFile, tagged_table};
use crate::input::{defaults, ranges};

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
    /// Progressive ply damage (only with `orthotropic` and `strengths`).
    pub damage: Option<DamageFile>,
}

/// `[materials.damage]`: progressive ply damage (Hashin onset, linear
/// softening per mode regularised by the crack band;
/// `crate::materials::damage`).
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct DamageFile {
    /// Fracture energy of fibre tension G_FT (J/m²).
    #[schemars(transform = ranges::FRACTURE_ENERGY.schema())]
    pub fibre_tension: f64,
    /// Fracture energy of fibre compression G_FC (J/m²).
    #[schemars(transform = ranges::FRACTURE_ENERGY.schema())]
    pub fibre_compression: f64,
    /// Fracture energy of matrix tension G_MT (J/m²).
    #[schemars(transform = ranges::FRACTURE_ENERGY.schema())]
    pub matrix_tension: f64,
    /// Fracture energy of matrix compression G_MC (J/m²).
    #[schemars(transform = ranges::FRACTURE_ENERGY.schema())]
    pub matrix_compression: f64,
    /// The largest damage of a mode (a fully damaged point keeps
    /// `1 − max_damage` of its stiffness).
    #[schemars(transform = ranges::MAX_DAMAGE.with_default(defaults::MAX_DAMAGE))]
    pub max_damage: Option<f64>,
    /// Duvaut–Lions viscosity η in units of the load factor (default 0:
    /// none); not with `solver.control = "arc_length"`.
    #[schemars(transform = ranges::DAMAGE_VISCOSITY.with_default(defaults::DAMAGE_VISCOSITY))]
    pub viscosity: Option<f64>,
    /// The tangent the points hand to Newton: `"consistent"` or `"secant"`.
    #[schemars(transform = defaults::schema(defaults::DAMAGE_TANGENT))]
    pub tangent: Option<DamageTangent>,
    /// α: the weight of the longitudinal shear in fibre tension's onset
    /// criterion and equivalent strain (1: Hashin's; Abaqus's α).
    #[schemars(transform = ranges::FIBRE_SHEAR.with_default(defaults::FIBRE_SHEAR))]
    pub fibre_shear: Option<f64>,
    /// The stress whose work conjugate draws each mode's softening line:
    /// `"effective"` (`C⁰ε`) or `"uniaxial"` (`E_k ε_k` in the normal
    /// components).
    #[schemars(transform = defaults::schema(defaults::SOFTENING_STRESS))]
    pub softening_stress: Option<SofteningStress>,
}

/// The stress of a mode's softening line (`materials.damage.softening_stress`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum SofteningStress {
    /// The undamaged stress `C⁰ε` (Lapczyk & Hurtado's, Abaqus's): a band
    /// held laterally dissipates less than `G/L`, by the Poisson terms the
    /// damaged compliance keeps.
    #[default]
    Effective,
    /// `E_k ε_k` in the normal components (the stress the damaged
    /// compliance's own entry leaves as the damage grows): a band held
    /// laterally dissipates `G/L` as one free.
    Uniaxial,
}

/// The tangent of a damaging point (`materials.damage.tangent`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum DamageTangent {
    /// The derivative of the stress, unsymmetric where a point softens
    /// (its symmetric part factorized, the rest by GMRES): Newton converges
    /// quadratically through softening; indefinite there.
    #[default]
    Consistent,
    /// The secant stiffness `C_d`: positive definite, Newton converges
    /// linearly (slowly) while points soften.
    Secant,
}

tagged_table! {
    /// `[materials.plasticity]`: von Mises plasticity with isotropic and
    /// kinematic hardening.
    pub(crate) struct PlasticityFile {
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
