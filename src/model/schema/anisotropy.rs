//! The model file's keys of anisotropic materials and material zones:
//! `materials.orthotropic`, `materials.strengths`, `[[bodies.zones]]`, and
//! the variation of a load along a coordinate (`loads.profile`, as for
//! Pagano's sine load).

use serde::Deserialize;

use super::{Axis, Exact, ProfileShape};

/// `materials.orthotropic`: engineering constants (Pa and −).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrthotropicFile {
    pub e1: f64,
    pub e2: f64,
    pub e3: f64,
    pub g12: f64,
    pub g13: f64,
    pub g23: f64,
    pub nu12: f64,
    pub nu13: f64,
    pub nu23: f64,
}

/// `materials.strengths` (Pa, magnitudes): `zt`, `zc` default to `yt`,
/// `yc` and `s13` to `s12` (transverse isotropy).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthsFile {
    pub xt: f64,
    pub xc: f64,
    pub yt: f64,
    pub yc: f64,
    pub zt: Option<f64>,
    pub zc: Option<f64>,
    pub s12: f64,
    pub s13: Option<f64>,
    pub s23: f64,
}

/// One `[[bodies.zones]]`: a section region's material and its axes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZoneFile {
    /// A named section region (every element when absent).
    pub region: Option<String>,
    /// The material (the body's when absent).
    pub material: Option<String>,
    /// The angle (degrees) of the material's axis 1 from `fibre`, about `normal`.
    pub angle: Option<f64>,
    /// Axis 1 at angle 0 (default the beam axis `[0, 1, 0]`).
    pub fibre: Option<Exact<f64, 3>>,
    /// Axis 3 (default `[0, 0, 1]`).
    pub normal: Option<Exact<f64, 3>>,
}

/// `loads.profile = { shape = "sine", along = "y", from = …, to = … }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadProfileFile {
    pub shape: ProfileShape,
    pub along: Axis,
    pub from: f64,
    pub to: f64,
}
