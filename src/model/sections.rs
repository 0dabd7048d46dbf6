//! `[bodies.section]` beyond the rectangle, tube and listed quads: the
//! parametric profiles of [`crate::mesh::profiles`] and gmsh files
//! ([`crate::mesh::gmsh`]). Which keys belong to which shape is stated once
//! here ([`SHAPES`]), and a key of another shape is an error.

use std::path::Path;

use super::bodies::{Budget, rekey};
use super::bounds;
use super::schema::SectionFile;
use super::validate::count;
use super::{ModelError, invalid};
use crate::mesh::blocks::{self, Block};
use crate::mesh::profiles::{self, Counts, Family, Walls};
use crate::mesh::{CrossSection, gmsh};
use crate::shape::{BeamElementKind, SectionElementKind};

const STRAIGHT: &[&str] =
    &["origin", "width", "height", "web_thickness", "flange_thickness", "along_flange", "along_web", "through"];

/// Every shape with the keys it reads (besides `shape` and `element`).
pub(super) const SHAPES: &[(&str, &[&str])] = &[
    ("rectangle", &["x", "z"]),
    ("tube", &["origin", "width", "height", "thickness", "around", "along_x", "along_z", "through"]),
    ("quads", &["points", "quads"]),
    ("i_beam", STRAIGHT),
    ("channel", STRAIGHT),
    ("z_section", STRAIGHT),
    ("angle", STRAIGHT),
    (
        "hat",
        &[
            "origin",
            "width",
            "height",
            "web_thickness",
            "flange_thickness",
            "lip",
            "along_flange",
            "along_web",
            "along_lip",
            "through",
        ],
    ),
    (
        "box",
        &[
            "origin",
            "width",
            "height",
            "web_thickness",
            "flange_thickness",
            "cells",
            "along_flange",
            "along_web",
            "through",
        ],
    ),
    ("circular_tube", &["center", "radius", "thickness", "around", "through"]),
    ("circle", &["center", "radius", "around", "through"]),
    ("gmsh", &["file", "scale"]),
];

/// The optional keys of a section table and whether each is given.
fn given(s: &SectionFile) -> [(&'static str, bool); 23] {
    [
        ("x", s.x.is_some()),
        ("z", s.z.is_some()),
        ("origin", s.origin.is_some()),
        ("width", s.width.is_some()),
        ("height", s.height.is_some()),
        ("thickness", s.thickness.is_some()),
        ("around", s.around.is_some()),
        ("along_x", s.along_x.is_some()),
        ("along_z", s.along_z.is_some()),
        ("through", s.through.is_some()),
        ("points", s.points.is_some()),
        ("quads", s.quads.is_some()),
        ("web_thickness", s.web_thickness.is_some()),
        ("flange_thickness", s.flange_thickness.is_some()),
        ("lip", s.lip.is_some()),
        ("cells", s.cells.is_some()),
        ("along_flange", s.along_flange.is_some()),
        ("along_web", s.along_web.is_some()),
        ("along_lip", s.along_lip.is_some()),
        ("center", s.center.is_some()),
        ("radius", s.radius.is_some()),
        ("file", s.file.is_some()),
        ("scale", s.scale.is_some()),
    ]
}

/// Checks the shape's name and that no key of another shape is given.
pub(super) fn check_keys(sk: &str, s: &SectionFile) -> Result<(), ModelError> {
    let names: Vec<&str> = SHAPES.iter().map(|(n, _)| *n).collect();
    let Some((_, keys)) = SHAPES.iter().find(|(n, _)| *n == s.shape) else {
        return Err(invalid(format!("{sk}.shape"), format!("{:?}", s.shape), format!("one of {names:?}")));
    };
    for (name, present) in given(s) {
        if present && !keys.contains(&name) {
            return Err(invalid(
                format!("{sk}.{name}"),
                "(given)",
                format!("no `{name}` key with shape = {:?} (its keys: {})", s.shape, keys.join(", ")),
            ));
        }
    }
    Ok(())
}

fn length(key: String, v: Option<f64>, what: &str) -> Result<f64, ModelError> {
    let v = v.ok_or_else(|| invalid(&key, "(missing)", format!("{what} in m")))?;
    bounds::within(&key, v, f64::MIN_POSITIVE, bounds::MAX_COORD, &format!("{what} in m, positive"))
}

fn point(key: String, v: Option<[f64; 2]>) -> Result<[f64; 2], ModelError> {
    let p = v.unwrap_or([0.0, 0.0]);
    if p.iter().all(|c| c.is_finite() && c.abs() <= bounds::MAX_COORD) {
        Ok(p)
    } else {
        Err(invalid(key, format!("{p:?}"), format!("two finite coordinates [x, z] within ±{:e} m", bounds::MAX_COORD)))
    }
}

/// Builds a parametric profile (`None` for the shapes handled elsewhere).
pub(super) fn profile(
    key: &str,
    s: &SectionFile,
    kind: SectionElementKind,
    beam: BeamElementKind,
    axis_elements: u64,
    budget: &mut Budget,
) -> Result<Option<CrossSection>, ModelError> {
    let sk = format!("{key}.section");
    let n = |name: &str, v: Option<usize>, default: usize| count(&format!("{sk}.{name}"), v.unwrap_or(default));
    let family = match s.shape.as_str() {
        "i_beam" => Some(Family::I),
        "channel" => Some(Family::Channel),
        "z_section" => Some(Family::Z),
        "angle" => Some(Family::Angle),
        "hat" => Some(Family::Hat),
        "box" => Some(Family::Box),
        _ => None,
    };
    let blocks: Vec<Block> = if let Some(family) = family {
        let walls = Walls {
            width: length(format!("{sk}.width"), s.width, "the overall width")?,
            height: length(format!("{sk}.height"), s.height, "the overall height")?,
            web: length(format!("{sk}.web_thickness"), s.web_thickness, "the web thickness")?,
            flange: length(format!("{sk}.flange_thickness"), s.flange_thickness, "the flange thickness")?,
            lip: if family == Family::Hat { length(format!("{sk}.lip"), s.lip, "the lip width")? } else { 0.0 },
            cells: s.cells.unwrap_or(1),
        };
        let counts = Counts {
            flange: n("along_flange", s.along_flange, 2)?,
            web: n("along_web", s.along_web, 4)?,
            lip: n("along_lip", s.along_lip, 1)?,
            through: n("through", s.through, 1)?,
        };
        let origin = point(format!("{sk}.origin"), s.origin.map(Into::into))?;
        profiles::straight(family, origin, &walls, &counts).map_err(|e| rekey(e, &sk))?
    } else {
        let center = point(format!("{sk}.center"), s.center.map(Into::into))?;
        match s.shape.as_str() {
            "circular_tube" => profiles::circular_tube(
                center,
                length(format!("{sk}.radius"), s.radius, "the outer radius")?,
                length(format!("{sk}.thickness"), s.thickness, "the wall thickness")?,
                n("around", s.around, 16)?,
                n("through", s.through, 1)?,
            ),
            "circle" => {
                let around = n("around", s.around, 16)?;
                profiles::circle(
                    center,
                    length(format!("{sk}.radius"), s.radius, "the radius")?,
                    around,
                    n("through", s.through, (around / 8).max(1))?,
                )
            }
            _ => return Ok(None),
        }
        .map_err(|e| rekey(e, &sk))?
    };
    let p = kind.order() as u64;
    let elements = blocks.iter().fold(0u64, |a, b| a.saturating_add(b.n_elements() as u64));
    // nodes: at least p² per element; pairs: each element's nodes pairwise
    let nodes = elements.saturating_mul(p * p);
    let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
    budget.add(key, kind, beam, elements, nodes, pairs, axis_elements)?;
    let section = blocks::from_blocks(kind, &blocks).map_err(|e| rekey(e, &sk))?;
    Ok(Some(section))
}

/// `shape = "gmsh"`: the mesh of `file` (relative to the model file's folder).
pub(super) fn gmsh_section(
    key: &str,
    s: &SectionFile,
    base: &Path,
    beam: BeamElementKind,
    axis_elements: u64,
    budget: &mut Budget,
) -> Result<CrossSection, ModelError> {
    let sk = format!("{key}.section");
    let file = s.file.as_ref().ok_or_else(|| {
        invalid(format!("{sk}.file"), "(missing)", "the path of a gmsh .msh file, relative to the model file")
    })?;
    let scale = s.scale.unwrap_or(1.0);
    if !(scale.is_finite() && scale > 0.0 && (1e-9..=1e9).contains(&scale)) {
        return Err(invalid(format!("{sk}.scale"), scale, "a factor from 1e-9 to 1e9 (e.g. 1e-3 for a mesh in mm)"));
    }
    let section = gmsh::read(&base.join(file), scale, &format!("{sk}.file"))?;
    if let Some(e) = &s.element
        && SectionElementKind::parse(e) != Some(section.kind)
    {
        return Err(invalid(
            format!("{sk}.element"),
            format!("{e:?}"),
            format!("{:?} (the elements of {file:?}), or no `element` key", section.kind),
        ));
    }
    let p = section.kind.order() as u64;
    let elements = section.n_elements() as u64;
    let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
    budget.add(key, section.kind, beam, elements, section.n_nodes() as u64, pairs, axis_elements)?;
    Ok(section)
}
