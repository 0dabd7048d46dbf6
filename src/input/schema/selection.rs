//! Node selections (`where`) and what is applied on them: `[[constraints]]`
//! and `[[loads]]` (`setup/preprocess.rs` resolves and checks them).

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

use super::{Axis, Exact, LoadProfileFile};
use crate::input::{defaults, ranges};

/// A coordinate condition: a number (equality) or `[min, max]`.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ConditionFile {
    /// Equal to the value, within the tolerance.
    Value(f64),
    /// In `[min, max]`, widened by the tolerance.
    Range([f64; 2]),
}

impl<'de> Deserialize<'de> for ConditionFile {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        const EXPECTED: &str = "a number (the coordinate) or a range [min, max]";
        impl<'de> Visitor<'de> for V {
            type Value = ConditionFile;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ConditionFile, A::Error> {
                let mut v: Vec<f64> = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                match v[..] {
                    [a, b] => Ok(ConditionFile::Range([a, b])),
                    _ => Err(de::Error::invalid_length(v.len(), &EXPECTED)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// A number or a pair `[min, max]`, as [`ConditionFile`] reads them.
impl schemars::JsonSchema for ConditionFile {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Condition".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "A coordinate (m): a number (equal within the tolerance) or a range [min, max].",
            "anyOf": [
                { "type": "number" },
                { "type": "array", "items": { "type": "number" }, "minItems": 2, "maxItems": 2 }
            ]
        })
    }
}

/// A node selection `{x = …, y = …, z = …, tolerance = …, region = …}`.
#[derive(Debug, Default, Deserialize, Clone, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct SelectionFile {
    /// x: a coordinate or `[min, max]` (m).
    pub x: Option<ConditionFile>,
    /// y: a coordinate or `[min, max]` (m).
    pub y: Option<ConditionFile>,
    /// z: a coordinate or `[min, max]` (m).
    pub z: Option<ConditionFile>,
    /// Absolute tolerance (m; default 1e-6 of the body's size).
    #[schemars(transform = ranges::POSITIVE.schema())]
    pub tolerance: Option<f64>,
    /// A named section region (profile wall, gmsh physical group).
    pub region: Option<String>,
    /// Distance from the axis (parallel to y) through `center` (default
    /// the y axis): a cylindrical surface or a ring.
    pub radius: Option<ConditionFile>,
    /// `[x, z]` of the axis of `radius`.
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub center: Option<Exact<f64, 2>>,
}

/// Per-component prescribed values `{x = …, y = …, z = …}`.
#[derive(Debug, Default, Deserialize, Clone, Copy, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ComponentsFile {
    /// u_x (m).
    pub x: Option<f64>,
    /// u_y (m).
    pub y: Option<f64>,
    /// u_z (m).
    pub z: Option<f64>,
}

/// `[[constraints]]`: fixed or prescribed displacements on selected nodes.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ConstraintFile {
    /// Names the reaction output (`history_<name>.csv`).
    pub name: String,
    /// Body name.
    pub body: String,
    /// The nodes.
    #[serde(rename = "where")]
    pub selection: SelectionFile,
    /// Components fixed at 0.
    pub fix: Option<Vec<Axis>>,
    /// Prescribed displacement per component at λ = 1 (m).
    pub displacement: Option<ComponentsFile>,
}

/// `[[loads]]`: one of four load kinds on selected nodes or faces.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LoadFile {
    /// Load name.
    pub name: String,
    /// Body name.
    pub body: String,
    /// Nodes (`force_per_node`) or faces (the other kinds).
    #[serde(rename = "where")]
    pub selection: SelectionFile,
    /// `[fx, fy, fz]` (N) on every selected node.
    pub force_per_node: Option<Exact<f64, 3>>,
    /// `[fx, fy, fz]` (N), spread uniformly over the selected faces.
    pub total_force: Option<Exact<f64, 3>>,
    /// `[tx, ty, tz]` (Pa) on the selected faces.
    pub traction: Option<Exact<f64, 3>>,
    /// Pressure (Pa) along each face's inward normal.
    pub pressure: Option<f64>,
    /// A variation of `traction` or `pressure` over the faces.
    pub profile: Option<LoadProfileFile>,
}

/// `[[levers]]`: a rigid lever, a linear multi-point constraint whose
/// value is prescribed: `Σ_k coefficient_k · ū_k = value(λ)`, `ū_k` the
/// mean displacement component `component_k` of the nodes of point `k`'s
/// selection (`setup/levers.rs`). The lever's force `P` (its Lagrange
/// multiplier, N) acts on each point as `P · coefficient_k` along its
/// component, spread equally over its nodes.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LeverFile {
    /// Names the history output (`history_<name>.csv`) and a step's `factors` key.
    pub name: String,
    /// The lever's displacement `Σ_k coefficient_k · ū_k` at λ = 1 (m),
    /// times the step factor.
    pub value: f64,
    /// The points it ties (at least one).
    pub points: Vec<LeverPointFile>,
}

/// One point of a `[[levers]]` entry: a node selection, the component it
/// moves along and its coefficient.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LeverPointFile {
    /// Body name.
    pub body: String,
    /// The nodes (their mean displacement is the point's).
    #[serde(rename = "where")]
    pub selection: SelectionFile,
    /// The displacement component the lever reads and pushes along.
    pub component: Axis,
    /// The point's coefficient in the lever's displacement (non-zero, finite).
    pub coefficient: f64,
}
