//! The model file's keys of anisotropic materials and material zones:
//! `materials.orthotropic`, `materials.strengths`, `[[bodies.zones]]`, and
//! the variation of a load along a coordinate (`loads.profile`, as for
//! Pagano's sine load).

use serde::Deserialize;

use super::{Axis, Exact, ProfileShape};
use crate::input::{defaults, ranges};

/// `materials.orthotropic`: engineering constants (Pa and −).
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct OrthotropicFile {
    /// E_1 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub e1: f64,
    /// E_2 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub e2: f64,
    /// E_3 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub e3: f64,
    /// G_12 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub g12: f64,
    /// G_13 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub g13: f64,
    /// G_23 (Pa).
    #[schemars(transform = ranges::YOUNG_MODULUS.schema())]
    pub g23: f64,
    /// ν_12: contraction along 2 under stress along 1.
    #[schemars(transform = ranges::ORTHOTROPIC_POISSON.schema())]
    pub nu12: f64,
    /// ν_13.
    #[schemars(transform = ranges::ORTHOTROPIC_POISSON.schema())]
    pub nu13: f64,
    /// ν_23.
    #[schemars(transform = ranges::ORTHOTROPIC_POISSON.schema())]
    pub nu23: f64,
}

/// `materials.strengths` (Pa, magnitudes): `zt`, `zc` default to `yt`,
/// `yc` and `s13` to `s12` (transverse isotropy).
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct StrengthsFile {
    /// Tensile strength along 1 (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub xt: f64,
    /// Compressive strength along 1 (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub xc: f64,
    /// Tensile strength along 2 (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub yt: f64,
    /// Compressive strength along 2 (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub yc: f64,
    /// Tensile strength along 3 (Pa; default `yt`).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub(crate) zt: Option<f64>,
    /// Compressive strength along 3 (Pa; default `yc`).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub zc: Option<f64>,
    /// Shear strength in the 1–2 plane (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub s12: f64,
    /// Shear strength in the 1–3 plane (Pa; default `s12`).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub(crate) s13: Option<f64>,
    /// Shear strength in the 2–3 plane (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub s23: f64,
}

/// One `[[bodies.zones]]`: a section region's material and its axes.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ZoneFile {
    /// A named section region (every element when absent).
    pub region: Option<String>,
    /// The material (the body's when absent).
    pub material: Option<String>,
    /// The angle (degrees) of the material's axis 1 from `fibre`, about `normal`.
    #[schemars(transform = ranges::ANGLE.with_default(defaults::ANGLE))]
    pub angle: Option<f64>,
    /// Axis 1 at angle 0 (default the beam axis).
    #[schemars(transform = defaults::schema(defaults::FIBRE))]
    pub fibre: Option<Exact<f64, 3>>,
    /// Axis 3.
    #[schemars(transform = defaults::schema(defaults::NORMAL))]
    pub normal: Option<Exact<f64, 3>>,
}

/// `loads.profile = { shape = "sine", along = "y", from = …, to = … }`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LoadProfileFile {
    /// `"sine"`: a half sine wave over [from, to].
    pub shape: ProfileShape,
    /// The coordinate it varies along.
    pub along: Axis,
    /// Start of the wave (m).
    #[schemars(transform = ranges::COORDINATE.schema())]
    pub from: f64,
    /// End of the wave (m), above `from`.
    #[schemars(transform = ranges::COORDINATE.schema())]
    pub to: f64,
}
