//! The model file's small string-valued settings as serde enums: a value
//! outside the list is refused by the reader with its line and the allowed
//! values (`unknown variant `L8`, expected one of `L4`, `L9`, `L16``).

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer};

use crate::quantity::Quantity;
use crate::shape::{BeamElementKind, SectionElementKind};

/// A section element (`bodies.section.element`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
pub(crate) enum SectionElement {
    /// Bilinear, 4 nodes.
    L4,
    /// Biquadratic, 9 nodes.
    L9,
    /// Bicubic, 16 nodes.
    L16,
}

impl SectionElement {
    /// The element kind.
    pub fn kind(self) -> SectionElementKind {
        match self {
            Self::L4 => SectionElementKind::L4,
            Self::L9 => SectionElementKind::L9,
            Self::L16 => SectionElementKind::L16,
        }
    }
}

/// A beam element (`bodies.axis.element`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
pub(crate) enum BeamElement {
    /// Linear, 2 nodes.
    B2,
    /// Quadratic, 3 nodes.
    B3,
    /// Cubic, 4 nodes.
    B4,
}

impl BeamElement {
    /// The element kind.
    pub fn kind(self) -> BeamElementKind {
        match self {
            Self::B2 => BeamElementKind::B2,
            Self::B3 => BeamElementKind::B3,
            Self::B4 => BeamElementKind::B4,
        }
    }
}

/// The shape of a load's variation (`loads.profile.shape`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum ProfileShape {
    /// A half sine wave over `[from, to]`.
    Sine,
}

/// A coordinate axis (`constraints.fix`, a cylinder's `axis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Axis {
    /// x.
    X,
    /// y, the beam axis.
    Y,
    /// z.
    Z,
}

impl Axis {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// The direction a flat punch's face looks towards the body (`normal`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
pub enum Normal {
    /// +x.
    #[serde(rename = "+x")]
    PlusX,
    /// −x.
    #[serde(rename = "-x")]
    MinusX,
    /// +y.
    #[serde(rename = "+y")]
    PlusY,
    /// −y.
    #[serde(rename = "-y")]
    MinusY,
    /// +z.
    #[serde(rename = "+z")]
    PlusZ,
    /// −z.
    #[serde(rename = "-z")]
    MinusZ,
}

impl Normal {
    /// The sign (±1) and the axis (0, 1, 2).
    pub(crate) fn sign_and_axis(self) -> (f64, usize) {
        match self {
            Self::PlusX => (1.0, 0),
            Self::MinusX => (-1.0, 0),
            Self::PlusY => (1.0, 1),
            Self::MinusY => (-1.0, 1),
            Self::PlusZ => (1.0, 2),
            Self::MinusZ => (-1.0, 2),
        }
    }
}

/// `solver.factor_precision`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum FactorPrecision {
    /// Factors stored in f32, refined by PCG in f64 (the default).
    #[default]
    Single,
    /// Factors in f64.
    Double,
}

/// `solver.inertia`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum Inertia {
    /// The converged tangent of every increment (the default with
    /// nonlinear geometry).
    EveryIncrement,
    /// The last factorized tangent (the default otherwise).
    LastFactorization,
}

/// `analysis.geometry`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Geometry {
    /// Small strain and small displacement (the default; the paper's).
    #[default]
    Linear,
    /// Total Lagrangian: large displacements and rotations
    /// (`crate::kinematics`).
    Nonlinear,
}

/// `analysis.strain`: the strain measure of nonlinear geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum StrainMeasure {
    /// Green–Lagrange strain (the default with nonlinear geometry).
    #[default]
    GreenLagrange,
    /// Logarithmic (Hencky) strain `½ ln C` (`crate::kinematics::hencky`).
    Logarithmic,
}

/// `analysis.type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum AnalysisType {
    /// Incremental static analysis (the default).
    #[default]
    Static,
    /// Linear buckling: the static solution at load factor 1, then the
    /// critical load factors of its stress state (`crate::analysis::buckling`).
    Buckling,
    /// Free vibration: the static solution, then the lowest natural
    /// frequencies and modes about it (`crate::analysis::modal`).
    Modal,
    /// Implicit transient dynamics: the load history in time, with inertia
    /// (`crate::dynamics::inertia`).
    Transient,
}

/// `analysis.mass`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum MassMatrix {
    /// `∫ ρ N_a N_b dV` (the default).
    #[default]
    Consistent,
    /// Row sums on the diagonal.
    Lumped,
}

/// `bodies.formulation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Formulation {
    /// Displacement-based, fully integrated (the default for ν < 0.45).
    Standard,
    /// Volumetric strain projected per element (the default for ν ≥ 0.45).
    Bbar,
    /// The in-section covariant shear strain interpolated from the reduced
    /// Gauss points (crate::values::AssumedShear; small strain, L9/L16).
    #[serde(rename = "assumed_shear")]
    AssumedShear,
}

/// An indenter's `method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum IndenterMethod {
    /// Each node paired once with the closest point at the start (the
    /// paper's method; the default).
    #[default]
    NodeToNode,
    /// The exact closest point of the current configuration.
    Surface,
}

/// A result quantity by name (`lines.plot`, `references.quantity`): one of
/// [`Quantity::all_for`], the failure indices included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuantityName(pub Quantity);

/// One of the names of [`Quantity::all_for`] (failure indices included).
impl schemars::JsonSchema for QuantityName {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "QuantityName".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names: Vec<String> = Quantity::all_for(true).into_iter().map(Quantity::name).collect();
        schemars::json_schema!({
            "description": "A result quantity (also the CSV and VTU name).",
            "type": "string",
            "enum": names,
        })
    }
}

impl<'de> Deserialize<'de> for QuantityName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// The names, for the message (the list lives in [`Quantity::all_for`]).
        struct Names;
        impl de::Expected for Names {
            fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
                let names: Vec<String> = Quantity::all_for(true).into_iter().map(Quantity::name).collect();
                write!(f, "one of {}", names.join(", "))
            }
        }
        let s = String::deserialize(d)?;
        Quantity::parse(&s).map(QuantityName).ok_or_else(|| de::Error::invalid_value(de::Unexpected::Str(&s), &Names))
    }
}
