//! `[bodies.section]`: one variant per `shape`, each with exactly its own
//! keys (a key of another shape is refused by the reader, which lists the
//! keys of the shape given). Which values are allowed is checked in
//! `model/sections.rs`.

use serde::{Deserialize, Deserializer};

use super::{DivisionFile, Exact, SectionElement};

/// `[bodies.section]`, chosen by `shape`.
#[derive(Debug, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case")]
pub enum SectionFile {
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
    pub fn wall_plies(&self) -> Option<&[PlyFile]> {
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
    super::tagged::read_tagged(d, "shape", None, None)
}

/// `shape = "rectangle"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectangleFile {
    pub element: Option<SectionElement>,
    pub x: Option<DivisionFile>,
    pub z: Option<DivisionFile>,
}

/// `shape = "laminate"`: plies stacked along z from `z0`, bottom first,
/// over the width divided by `x`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaminateFile {
    pub element: Option<SectionElement>,
    pub x: Option<DivisionFile>,
    pub z0: Option<f64>,
    pub plies: Option<Vec<PlyFile>>,
}

/// One ply of a laminate.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlyFile {
    pub thickness: f64,
    pub material: String,
    /// Degrees about z from the beam axis y (right-handed: +90 along −x).
    pub angle: Option<f64>,
    /// Elements through the ply (default 1).
    pub elements: Option<usize>,
}

/// `shape = "tube"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TubeFile {
    pub element: Option<SectionElement>,
    pub origin: Option<Exact<f64, 2>>,
    pub width: Option<f64>,
    pub height: Option<f64>,
    pub thickness: Option<f64>,
    pub around: Option<usize>,
    pub along_x: Option<usize>,
    pub along_z: Option<usize>,
    pub through: Option<usize>,
    /// Plies through every wall (the tube is then built as a one-cell box).
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "quads"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadsFile {
    pub element: Option<SectionElement>,
    pub points: Option<Vec<Exact<f64, 2>>>,
    pub quads: Option<Vec<Exact<usize, 4>>>,
}

/// `shape = "i_beam"`, `"channel"`, `"z_section"` or `"angle"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileFile {
    pub element: Option<SectionElement>,
    pub origin: Option<Exact<f64, 2>>,
    pub width: Option<f64>,
    pub height: Option<f64>,
    pub web_thickness: Option<f64>,
    pub flange_thickness: Option<f64>,
    pub along_flange: Option<usize>,
    pub along_web: Option<usize>,
    pub through: Option<usize>,
    /// Plies through every wall (thickness, material, angle, elements),
    /// from the wall's lower x (webs) or lower z (flanges).
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "hat"`: a profile with lips.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HatFile {
    pub element: Option<SectionElement>,
    pub origin: Option<Exact<f64, 2>>,
    pub width: Option<f64>,
    pub height: Option<f64>,
    pub web_thickness: Option<f64>,
    pub flange_thickness: Option<f64>,
    pub lip: Option<f64>,
    pub along_flange: Option<usize>,
    pub along_web: Option<usize>,
    pub along_lip: Option<usize>,
    pub through: Option<usize>,
    /// Plies through every wall.
    pub plies: Option<Vec<PlyFile>>,
}

/// `shape = "box"`: a profile of one or more cells.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxFile {
    pub element: Option<SectionElement>,
    pub origin: Option<Exact<f64, 2>>,
    pub width: Option<f64>,
    pub height: Option<f64>,
    pub web_thickness: Option<f64>,
    pub flange_thickness: Option<f64>,
    pub cells: Option<usize>,
    pub along_flange: Option<usize>,
    pub along_web: Option<usize>,
    pub through: Option<usize>,
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
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircularTubeFile {
    pub element: Option<SectionElement>,
    pub center: Option<Exact<f64, 2>>,
    pub radius: Option<f64>,
    pub thickness: Option<f64>,
    pub around: Option<usize>,
    pub through: Option<usize>,
}

/// `shape = "circle"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleFile {
    pub element: Option<SectionElement>,
    pub center: Option<Exact<f64, 2>>,
    pub radius: Option<f64>,
    pub around: Option<usize>,
    pub through: Option<usize>,
}

/// `shape = "gmsh"`: the element comes from the file (`element`, if
/// given, must agree).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GmshFile {
    pub element: Option<SectionElement>,
    pub file: Option<String>,
    pub scale: Option<f64>,
}
