//! `[[bodies]]`: a section mesh swept along a beam-axis mesh, and the
//! divisions of an interval that both use (`setup/bodies.rs` and
//! `setup/sections.rs` check them).

use serde::Deserialize;

use super::{BeamElement, Formulation, SectionFile, ZoneFile};
use crate::input::ranges;

/// `[[bodies]]`: a refined 1D (CUF) body.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodyFile {
    /// Name, referenced by constraints, loads, indenters, contacts, probes, lines.
    pub name: String,
    /// The body's material (optional where plies or zones cover the section).
    pub material: Option<String>,
    /// The cross-section mesh in the x–z plane.
    #[serde(deserialize_with = "super::section::read")]
    pub section: SectionFile,
    /// The beam-axis mesh along y.
    pub axis: AxisFile,
    /// `"standard"`, `"bbar"` or `"assumed_shear"` (default from the material's ν).
    pub formulation: Option<Formulation>,
    /// `[[bodies.zones]]`: materials and material axes of section regions.
    pub zones: Option<Vec<ZoneFile>>,
}

/// An interval division: `{from, to, elements[, ratio]}`, `{lines}` or `{segments}`.
#[derive(Debug, Default, Deserialize, Clone, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct DivisionFile {
    /// Start of the interval (m).
    pub from: Option<f64>,
    /// End of the interval (m), above `from`.
    pub to: Option<f64>,
    /// Elements over [from, to].
    #[schemars(transform = ranges::COUNT.schema())]
    pub elements: Option<usize>,
    /// Last over first element length (geometric grading).
    #[schemars(transform = ranges::RATIO.schema())]
    pub ratio: Option<f64>,
    /// Element boundaries (m), strictly increasing.
    pub lines: Option<Vec<f64>>,
    /// Consecutive graded segments.
    pub segments: Option<Vec<SegmentFile>>,
}

/// One graded segment of a division.
#[derive(Debug, Deserialize, Clone, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct SegmentFile {
    /// Start (m): the previous segment's end.
    pub from: f64,
    /// End (m).
    pub to: f64,
    /// Elements of the segment.
    #[schemars(transform = ranges::COUNT.schema())]
    pub elements: usize,
    /// Last over first element length (default 1).
    #[schemars(transform = ranges::RATIO.schema())]
    pub ratio: Option<f64>,
}

/// `[bodies.axis]`: the beam element and the division of y, as flat keys.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct AxisFile {
    /// `"B2"`, `"B3"` or `"B4"`.
    pub element: BeamElement,
    /// Start of the axis (m).
    pub from: Option<f64>,
    /// End of the axis (m).
    pub to: Option<f64>,
    /// Elements over [from, to].
    #[schemars(transform = ranges::COUNT.schema())]
    pub elements: Option<usize>,
    /// Last over first element length.
    #[schemars(transform = ranges::RATIO.schema())]
    pub ratio: Option<f64>,
    /// Element boundaries (m), strictly increasing.
    pub lines: Option<Vec<f64>>,
    /// Consecutive graded segments.
    pub segments: Option<Vec<SegmentFile>>,
}
