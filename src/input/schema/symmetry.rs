//! `[[symmetry]]`: planes of mirror symmetry (`bc::symmetry`).

use serde::Deserialize;

/// `[[symmetry]]`: the model is the part of a symmetric structure on one
/// side of this plane.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct SymmetryFile {
    /// Name (the plane's reaction).
    pub name: String,
    /// `{ x = c }`, `{ y = c }` or `{ z = c }`.
    pub plane: PlaneFile,
    /// The side modelled: `"above"` (coordinates ≥ c) or `"below"`.
    pub keep: Option<KeepSide>,
}

/// `symmetry.plane`: exactly one coordinate.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlaneFile {
    /// The plane x = c (m).
    pub x: Option<f64>,
    /// The plane y = c (m).
    pub y: Option<f64>,
    /// The plane z = c (m).
    pub z: Option<f64>,
}

/// `symmetry.keep`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum KeepSide {
    /// Coordinates at or above the plane's.
    Above,
    /// Coordinates at or below the plane's.
    Below,
}
