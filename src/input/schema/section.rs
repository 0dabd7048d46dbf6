//! `[bodies.section]`: one variant per `shape`, each with exactly its own
//! keys (a key of another shape is refused by the reader, which lists the
//! keys of the shape given). Which values are allowed is checked in
//! `setup/sections.rs`.

use serde::{Deserialize, Deserializer};

use super::{DivisionFile, Exact, SectionElement};
use crate::input::{defaults, ranges};

/// `[bodies.section]`, chosen by `shape`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(tag = "shape", rename_all = "snake_case")]
pub(crate) enum SectionFile {
    /// A rectangle divided along x and z.
    Rectangle(RectangleFile),
    /// A thin-walled rectangular tube.
    Tube(TubeFile),
    /// Listed corner points and quadrilaterals.
    Quads(QuadsFile),
    /// An I (H) profile.
    IBeam(ProfileFile),
    /// A channel (C, U).
    Channel(ProfileFile),
    /// A Z profile.
    ZSection(ProfileFile),
    /// An angle (L).
    Angle(ProfileFile),
    /// A hat (omega) profile.
    Hat(HatFile),
    /// A rectangular box of one or more cells.
    Box(BoxFile),
    /// A circular tube.
    CircularTube(CircularTubeFile),
    /// A solid circle (O-grid).
    Circle(CircleFile),
    /// A gmsh `.msh` file.
    Gmsh(GmshFile),
    /// A stack of plies over a rectangle.
    Laminate(LaminateFile),
}

impl SectionFile {
    /// The `shape` word, as the model file spells it.
    pub fn shape(&self) -> &'static str {
        match self {
            Self::Rectangle(_) => "rectangle",
            Self::Tube(_) => "tube",
            Self::Quads(_) => "quads",
            Self::IBeam(_) => "i_beam",
            Self::Channel(_) => "channel",
            Self::ZSection(_) => "z_section",
            Self::Angle(_) => "angle",
            Self::Hat(_) => "hat",
            Self::Box(_) => "box",
            Self::CircularTube(_) => "circular_tube",
            Self::Circle(_) => "circle",
            Self::Gmsh(_) => "gmsh",
            Self::Laminate(_) => "laminate",
        }
    }

    /// The plies through the walls of a straight-walled profile, if given.
    pub(crate) fn wall_plies(&self) -> Option<&[PlyFile]> {
        match self {
            Self::IBeam(s) | Self::Channel(s) | Self::ZSection(s) | Self::Angle(s) => s.plies.as_deref(),
            Self::Hat(s) => s.plies.as_deref(),
            Self::Box(s) => s.plies.as_deref(),
            Self::Tube(s) => s.plies.as_deref(),
            _ => None,
        }
    }

    /// The `element` key (required except for `shape = "gmsh"`).
    pub fn element(&self) -> Option<SectionElement> {
        match self {
            Self::Rectangle(s) => s.element,
            Self::Tube(s) => s.element,
            Self::Quads(s) => s.element,
            Self::IBeam(s) | Self::Channel(s) | Self::ZSection(s) | Self::Angle(s) => s.element,
            Self::Hat(s) => s.element,
            Self::Box(s) => s.element,
            Self::CircularTube(s) => s.element,
            Self::Circle(s) => s.element,
            Self::Gmsh(s) => s.element,
            Self::Laminate(s) => s.element,
        }
    }
}

/// Reads `[bodies.section]` naming the key of a bad value
/// ([`super::tagged::read_tagged`]).
pub(super) fn read<'de, D: Deserializer<'de>>(d: D) -> Result<SectionFile, D::Error> {
    super::tagged::read_tagged(d, ("shape", SHAPES), None, None)
}

/// The values of `shape`, in the order of [`SectionFile`]'s variants.
const SHAPES: &[&str] = &[
    "rectangle",
    "tube",
    "quads",
    "i_beam",
    "channel",
    "z_section",
    "angle",
    "hat",
    "box",
    "circular_tube",
    "circle",
    "gmsh",
    "laminate",
];

/// `shape = "rectangle"`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct RectangleFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The division along x (m).
    pub x: Option<DivisionFile>,
    /// The division along z (m).
    pub z: Option<DivisionFile>,
    /// A rectangular hole `{ x = [x0, x1], z = [z0, z1] }` (m): the grid's
    /// cells inside it are left out (a hollow rectangle, e.g. a tube graded
    /// wall by wall). Its edges lie on element boundaries, inside the grid.
    pub hole: Option<HoleFile>,
}

/// `hole` of a `rectangle` section: the x and z ranges left out (m).
#[derive(Debug, Clone, Copy, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct HoleFile {
    /// `[x0, x1]`, x0 < x1.
    pub x: [f64; 2],
    /// `[z0, z1]`, z0 < z1.
    pub z: [f64; 2],
}

/// `shape = "laminate"`: plies stacked along z from `z0`, bottom first,
/// over the width divided by `x`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct LaminateFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The division along x (m).
    pub x: Option<DivisionFile>,
    /// The bottom of the stack (m).
    #[schemars(transform = ranges::COORDINATE.with_default(defaults::Z0))]
    pub z0: Option<f64>,
    /// The plies, bottom first.
    pub plies: Option<Vec<PlyFile>>,
    /// The interfaces between plies: `"perfect"` (shared nodes),
    /// `"cohesive"` (every one, with `interface_material`) or a list of the
    /// cohesive ones `[{ply, material, crack}]`.
    #[schemars(transform = defaults::schema(defaults::INTERFACES))]
    pub interfaces: Option<super::InterfacesFile>,
    /// The material (with `cohesive`) of the cohesive interfaces that name none.
    pub interface_material: Option<String>,
}

/// One ply of a laminate.
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlyFile {
    /// Thickness (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub thickness: f64,
    /// Name of a `[[materials]]` entry.
    pub material: String,
    /// Degrees about z from the beam axis y (right-handed: +90 along −x).
    #[schemars(transform = ranges::ANGLE.with_default(defaults::ANGLE))]
    pub angle: Option<f64>,
    /// Elements through the ply.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub elements: Option<usize>,
}

/// `shape = "tube"`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct TubeFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The corner `[x, z]` with the smallest x and z (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub origin: Option<Exact<f64, 2>>,
    /// Outer size along x (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub width: Option<f64>,
    /// Outer size along z (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub height: Option<f64>,
    /// Wall thickness (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub thickness: Option<f64>,
    /// Elements around a square tube (4 + 4k), instead of `along_x` and `along_z`.
    #[schemars(transform = ranges::COUNT.schema())]
    pub around: Option<usize>,
    /// Elements along each straight part of the walls along x.
    #[schemars(transform = ranges::COUNT.schema())]
    pub along_x: Option<usize>,
    /// Elements along each straight part of the walls along z.
    #[schemars(transform = ranges::COUNT.schema())]
    pub along_z: Option<usize>,
    /// Elements through the wall.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub through: Option<usize>,
    /// Plies through every wall (the tube is then built as a one-cell box).
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "quads"`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct QuadsFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// Corner points `[x, z]` (m), numbered from 0.
    #[schemars(transform = ranges::COORDINATE.items())]
    pub points: Option<Vec<Exact<f64, 2>>>,
    /// Quadrilaterals: four point indices, counter-clockwise in the x–z plane.
    pub quads: Option<Vec<Exact<usize, 4>>>,
}

/// `shape = "i_beam"`, `"channel"`, `"z_section"` or `"angle"`.
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ProfileFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The corner `[x, z]` with the smallest x and z (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub origin: Option<Exact<f64, 2>>,
    /// Outer size along x (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub width: Option<f64>,
    /// Outer size along z (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub height: Option<f64>,
    /// Thickness of the walls along z, t_w (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub web_thickness: Option<f64>,
    /// Thickness of the walls along x, t_f (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub flange_thickness: Option<f64>,
    /// Elements along each flange part.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_FLANGE))]
    pub along_flange: Option<usize>,
    /// Elements along each web between the flanges.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_WEB))]
    pub along_web: Option<usize>,
    /// Elements through the wall.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub through: Option<usize>,
    /// Length of one more element at each end of a wall that meets another
    /// wall, next to the junction (m); none: a wall's elements are equal.
    #[schemars(transform = ranges::LENGTH.schema())]
    pub junction_element: Option<f64>,
    /// Plies through every wall (thickness, material, angle, elements),
    /// from the wall's lower x (webs) or lower z (flanges).
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "hat"`: a profile with lips.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct HatFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The corner `[x, z]` with the smallest x and z (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub origin: Option<Exact<f64, 2>>,
    /// Outer size along x (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub width: Option<f64>,
    /// Outer size along z (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub height: Option<f64>,
    /// Thickness of the walls along z, t_w (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub web_thickness: Option<f64>,
    /// Thickness of the walls along x, t_f (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub flange_thickness: Option<f64>,
    /// Width of each lip (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub lip: Option<f64>,
    /// Elements along each flange part.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_FLANGE))]
    pub along_flange: Option<usize>,
    /// Elements along each web between the flanges.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_WEB))]
    pub along_web: Option<usize>,
    /// Elements along each lip.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_LIP))]
    pub(crate) along_lip: Option<usize>,
    /// Elements through the wall.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub through: Option<usize>,
    /// Length of one more element at each end of a wall that meets another
    /// wall, next to the junction (m); none: a wall's elements are equal.
    #[schemars(transform = ranges::LENGTH.schema())]
    pub junction_element: Option<f64>,
    /// Plies through every wall.
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "box"`: a profile of one or more cells.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoxFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// The corner `[x, z]` with the smallest x and z (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub origin: Option<Exact<f64, 2>>,
    /// Outer size along x (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub width: Option<f64>,
    /// Outer size along z (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub height: Option<f64>,
    /// Thickness of the walls along z, t_w (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub web_thickness: Option<f64>,
    /// Thickness of the walls along x, t_f (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub flange_thickness: Option<f64>,
    /// Cells side by side.
    #[schemars(transform = ranges::CELLS.with_default(defaults::CELLS))]
    pub cells: Option<usize>,
    /// Elements along each flange part.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_FLANGE))]
    pub along_flange: Option<usize>,
    /// Elements along each web between the flanges.
    #[schemars(transform = ranges::COUNT.with_default(defaults::ALONG_WEB))]
    pub along_web: Option<usize>,
    /// Elements through the wall.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub through: Option<usize>,
    /// Length of one more element at each end of a wall that meets another
    /// wall, next to the junction (m); none: a wall's elements are equal.
    #[schemars(transform = ranges::LENGTH.schema())]
    pub junction_element: Option<f64>,
    /// Plies through every wall (thickness, material, angle, elements),
    /// from the wall's lower x (webs) or lower z (flanges).
    pub plies: Option<Vec<PlyFile>>,
}

/// The keys a hat or a box shares with the other profiles.
macro_rules! shared_profile {
    ($s:expr) => {
        ProfileFile {
            element: $s.element,
            origin: $s.origin,
            width: $s.width,
            height: $s.height,
            web_thickness: $s.web_thickness,
            flange_thickness: $s.flange_thickness,
            along_flange: $s.along_flange,
            along_web: $s.along_web,
            through: $s.through,
            junction_element: $s.junction_element,
            plies: $s.plies.clone(),
        }
    };
}

impl HatFile {
    /// The keys it shares with the other profiles.
    pub fn profile(&self) -> ProfileFile {
        shared_profile!(self)
    }
}

impl BoxFile {
    /// The keys it shares with the other profiles.
    pub fn profile(&self) -> ProfileFile {
        shared_profile!(self)
    }
}

/// `shape = "circular_tube"`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct CircularTubeFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// Centre `[x, z]` (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub center: Option<Exact<f64, 2>>,
    /// Outer radius (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub radius: Option<f64>,
    /// Wall thickness (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub thickness: Option<f64>,
    /// Elements around.
    #[schemars(transform = ranges::COUNT.with_default(defaults::AROUND))]
    pub around: Option<usize>,
    /// Elements through the wall.
    #[schemars(transform = ranges::COUNT.with_default(defaults::THROUGH))]
    pub through: Option<usize>,
}

/// `shape = "circle"`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct CircleFile {
    /// The section element: `"L4"`, `"L9"` or `"L16"`.
    pub element: Option<SectionElement>,
    /// Centre `[x, z]` (m).
    #[schemars(transform = ranges::COORDINATE.items())]
    #[schemars(transform = defaults::schema(defaults::ORIGIN))]
    pub center: Option<Exact<f64, 2>>,
    /// Outer radius (m).
    #[schemars(transform = ranges::LENGTH.schema())]
    pub radius: Option<f64>,
    /// Elements around.
    #[schemars(transform = ranges::COUNT.with_default(defaults::AROUND))]
    pub around: Option<usize>,
    /// Elements radially in each rim block (default max(1, around/8)).
    #[schemars(transform = ranges::COUNT.schema())]
    pub through: Option<usize>,
}

/// `shape = "gmsh"`: the element comes from the file (`element`, if
/// given, must agree).
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct GmshFile {
    /// Optional: if given, the file's elements (`"L4"`, `"L9"` or `"L16"`).
    pub element: Option<SectionElement>,
    /// Path of the `.msh` file, relative to the model file's folder.
    pub file: Option<String>,
    /// Factor applied to the file's coordinates (`1e-3` for a mesh in mm).
    #[schemars(transform = ranges::GMSH_SCALE.with_default(defaults::GMSH_SCALE))]
    pub scale: Option<f64>,
}
