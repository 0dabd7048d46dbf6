//! The model file's keys of cohesive interfaces between plies: a laminate
//! section's `interfaces` and `interface_material`, and the interface
//! material `[materials.cohesive]` (`setup/interfaces.rs` checks the
//! values; `crate::interfaces` is the part they build).

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer};

use crate::input::{defaults, ranges};

/// `interfaces` of a laminate: one word for every interface, or a list of
/// the cohesive ones.
#[derive(Debug, Clone, PartialEq, schemars::JsonSchema)]
#[schemars(untagged)]
pub(crate) enum InterfacesFile {
    /// `"perfect"` (shared nodes) or `"cohesive"` (every interface, with
    /// `interface_material`).
    Every(InterfaceKind),
    /// The cohesive interfaces, each above its ply.
    Listed(Vec<InterfaceFile>),
}

/// What every interface of a laminate is.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub(crate) enum InterfaceKind {
    /// The plies share their nodes.
    #[default]
    Perfect,
    /// A cohesive law between every two plies.
    Cohesive,
}

/// One cohesive interface: the one above ply `ply`.
#[derive(Debug, Clone, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct InterfaceFile {
    /// The ply below the interface (1-based, below the top ply).
    #[schemars(transform = ranges::COUNT.schema())]
    pub ply: usize,
    /// A material with `cohesive` (default the laminate's
    /// `interface_material`).
    pub material: Option<String>,
    /// A delamination from the start: `{from, to}` along the beam axis y (m).
    pub crack: Option<CrackFile>,
}

/// `crack = { from, to }`: where an interface starts delaminated (y, m).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct CrackFile {
    /// Start along y (m).
    #[schemars(transform = ranges::COORDINATE.schema())]
    pub from: f64,
    /// End along y (m), above `from`.
    #[schemars(transform = ranges::COORDINATE.schema())]
    pub to: f64,
}

/// `[materials.cohesive]`: the bilinear traction–separation law of an
/// interface material (Camanho & Dávila 2002 with Benzeggagh–Kenane).
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct CohesiveFile {
    /// Mode I toughness G_Ic (J/m²).
    #[schemars(transform = ranges::TOUGHNESS.schema())]
    pub gic: f64,
    /// Mode II toughness G_IIc (J/m²).
    #[schemars(transform = ranges::TOUGHNESS.schema())]
    pub giic: f64,
    /// Benzeggagh–Kenane exponent η.
    #[schemars(transform = ranges::BK_EXPONENT.schema())]
    pub bk_exponent: f64,
    /// Onset traction in pure opening N (Pa).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub normal_strength: f64,
    /// Onset traction in pure shear S (Pa; default N √(G_IIc/G_Ic)).
    #[schemars(transform = ranges::STRENGTH.schema())]
    pub(crate) shear_strength: Option<f64>,
    /// Penalty stiffness K (Pa/m; default 50 E3/t of the thinner adjacent ply).
    #[schemars(transform = ranges::COHESIVE_PENALTY.schema())]
    pub penalty: Option<f64>,
    /// Duvaut–Lions viscosity η in units of the load factor (default 0:
    /// none); not with `solver.control = "arc_length"`.
    #[schemars(transform = ranges::COHESIVE_VISCOSITY.with_default(defaults::COHESIVE_VISCOSITY))]
    pub viscosity: Option<f64>,
}

/// Reads a word or a list, naming both forms when it is neither (an
/// untagged enum would say "data did not match any variant").
impl<'de> Deserialize<'de> for InterfacesFile {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> de::Visitor<'de> for Either {
            type Value = InterfacesFile;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"perfect\", \"cohesive\" or a list of { ply, material, crack }")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Self::Value, E> {
                InterfaceKind::deserialize(de::value::StrDeserializer::<E>::new(s)).map(InterfacesFile::Every)
            }
            fn visit_seq<A: de::SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
                Vec::<InterfaceFile>::deserialize(de::value::SeqAccessDeserializer::new(seq))
                    .map(InterfacesFile::Listed)
            }
        }
        d.deserialize_any(Either)
    }
}
