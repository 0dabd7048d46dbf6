//! `[bodies.section]`: the cross-section of a body, built from the shape the
//! schema read ([`SectionFile`], one variant per `shape` with exactly its
//! own keys): rectangles, thin-walled tubes and listed quads directly, the
//! parametric profiles through [`crate::mesh::profiles`], gmsh files through
//! [`crate::mesh::gmsh`]. Each section is budgeted against the memory limit
//! before it is built.

use std::path::Path;

use super::budget::Budget;
use crate::input::bounds;
use crate::input::schema::*;
use crate::input::validate::{MAX_COUNT, count, division};
use crate::input::{ModelError, defaults, invalid, ranges};
use crate::mesh::blocks::{self, Block};
use crate::mesh::profiles::{self, Counts, Family, Walls};
use crate::mesh::{CrossSection, MeshError, gmsh};
use crate::shape::{BeamElementKind, SectionElementKind};

/// Builds the sections of one body (`key`: `bodies[i]`), swept along
/// `axis_elements` beam elements of kind `beam`.
pub(super) struct Sections<'a> {
    /// `bodies[i]`.
    pub key: &'a str,
    /// The beam element.
    pub beam: BeamElementKind,
    /// Number of beam elements.
    pub axis_elements: u64,
    /// The model's memory budget.
    pub budget: &'a mut Budget,
}

impl Sections<'_> {
    /// The section `s`; files (gmsh) relative to `base`.
    pub(super) fn section(&mut self, s: &SectionFile, base: &Path) -> Result<CrossSection, ModelError> {
        let sk = format!("{}.section", self.key);
        if let SectionFile::Gmsh(g) = s {
            return self.gmsh(&sk, g, base);
        }
        let kind = s
            .element()
            .ok_or_else(|| {
                invalid(format!("{sk}.element"), "(missing)", "\"L4\", \"L9\" or \"L16\" (the section element)")
            })?
            .kind();
        match s {
            SectionFile::Rectangle(r) => self.rectangle(&sk, kind, r),
            SectionFile::Tube(t) => self.tube(&sk, kind, t),
            SectionFile::Quads(q) => self.quads(&sk, kind, q),
            SectionFile::IBeam(p) => self.straight(&sk, kind, Family::I, p, None, None),
            SectionFile::Channel(p) => self.straight(&sk, kind, Family::Channel, p, None, None),
            SectionFile::ZSection(p) => self.straight(&sk, kind, Family::Z, p, None, None),
            SectionFile::Angle(p) => self.straight(&sk, kind, Family::Angle, p, None, None),
            SectionFile::Hat(h) => {
                self.straight(&sk, kind, Family::Hat, &h.profile(), Some((h.lip, h.along_lip)), None)
            }
            SectionFile::Box(b) => self.straight(&sk, kind, Family::Box, &b.profile(), None, b.cells),
            SectionFile::CircularTube(c) => {
                let center = point(format!("{sk}.center"), c.center.map(Into::into))?;
                let n =
                    |name: &str, v: Option<usize>, default: usize| count(&format!("{sk}.{name}"), v.unwrap_or(default));
                let blocks = profiles::circular_tube(
                    center,
                    length(format!("{sk}.radius"), c.radius, "the outer radius")?,
                    length(format!("{sk}.thickness"), c.thickness, "the wall thickness")?,
                    n("around", c.around, defaults::AROUND)?,
                    n("through", c.through, defaults::THROUGH)?,
                );
                self.blocks(&sk, kind, blocks)
            }
            SectionFile::Circle(c) => {
                let center = point(format!("{sk}.center"), c.center.map(Into::into))?;
                let around = count(&format!("{sk}.around"), c.around.unwrap_or(defaults::AROUND))?;
                let radius = length(format!("{sk}.radius"), c.radius, "the radius")?;
                let through = count(&format!("{sk}.through"), c.through.unwrap_or((around / 8).max(1)))?;
                self.blocks(&sk, kind, profiles::circle(center, radius, around, through))
            }
            SectionFile::Gmsh(g) => self.gmsh(&sk, g, base),
            SectionFile::Laminate(l) => {
                let section = super::laminate::section(&sk, kind, l)?;
                let (n, p) = (section.n_elements() as u64, kind.order() as u64);
                self.add(kind, n, section.n_nodes() as u64, n.saturating_mul((p + 1).pow(4)) / 4)?;
                Ok(section)
            }
        }
    }

    fn add(&mut self, kind: SectionElementKind, elements: u64, nodes: u64, pairs: u64) -> Result<(), ModelError> {
        self.budget.add(self.key, kind, self.beam, elements, nodes, pairs, self.axis_elements)
    }

    /// `shape = "rectangle"`.
    fn rectangle(&mut self, sk: &str, kind: SectionElementKind, s: &RectangleFile) -> Result<CrossSection, ModelError> {
        let x = s.x.as_ref().ok_or_else(|| {
            invalid(format!("{sk}.x"), "(missing)", "a division of x, e.g. {from = 0.0, to = 0.5, elements = 18}")
        })?;
        let z = s.z.as_ref().ok_or_else(|| {
            invalid(format!("{sk}.z"), "(missing)", "a division of z, e.g. {from = 0.0, to = 0.3, elements = 6}")
        })?;
        let xl = division(&format!("{sk}.x"), x)?;
        let zl = division(&format!("{sk}.z"), z)?;
        let (nx, nz, p) = ((xl.len() - 1) as u64, (zl.len() - 1) as u64, kind.order() as u64);
        let pairs = crate::size::coupled_1d(nx, p).saturating_mul(crate::size::coupled_1d(nz, p));
        // the full grid's counts: a hole only lowers them
        self.add(kind, nx * nz, (p * nx + 1) * (p * nz + 1), pairs)?;
        match &s.hole {
            None => CrossSection::rectangle(kind, &xl, &zl),
            Some(h) => CrossSection::hollow_rectangle(kind, &xl, &zl, hole_cells(sk, h, &xl, &zl)?),
        }
        .map_err(|e| rekey(e, sk))
    }

    /// `shape = "tube"`: a thin-walled rectangular tube.
    fn tube(&mut self, sk: &str, kind: SectionElementKind, s: &TubeFile) -> Result<CrossSection, ModelError> {
        if s.plies.is_some() {
            return self.layered_tube(sk, kind, s);
        }
        let need = |name: &str, v: Option<f64>| {
            v.ok_or_else(|| invalid(format!("{sk}.{name}"), "(missing)", "a positive length in m"))
                .and_then(|v| ranges::LENGTH.check(&format!("{sk}.{name}"), v, "a positive length in m"))
        };
        let (w, h, t) = (need("width", s.width)?, need("height", s.height)?, need("thickness", s.thickness)?);
        if 2.0 * t >= w.min(h) {
            return Err(invalid(
                format!("{sk}.thickness"),
                t,
                format!("less than half the smaller outer dimension ({})", 0.5 * w.min(h)),
            ));
        }
        let origin: [f64; 2] = s.origin.map_or(defaults::ORIGIN, Into::into);
        if !origin.iter().all(|v| v.is_finite() && v.abs() <= bounds::MAX_COORD) {
            return Err(invalid(
                format!("{sk}.origin"),
                format!("{origin:?}"),
                format!("two finite coordinates [x0, z0] within ±{:e} m", bounds::MAX_COORD),
            ));
        }
        if t < bounds::MIN_RELATIVE_SIZE * w.max(h) {
            return Err(invalid(
                format!("{sk}.thickness"),
                t,
                format!("at least {:e} of the outer size (round-off would swamp the wall)", bounds::MIN_RELATIVE_SIZE),
            ));
        }
        let through = count(&format!("{sk}.through"), s.through.unwrap_or(defaults::THROUGH))?;
        // `around` and `along_x`/`along_z` are two ways of dividing the same
        // tube: which one is given is a value check, not a key of another shape
        let (ax, az) = match (s.around, s.along_x, s.along_z) {
            (Some(n), None, None) => {
                if (w - h).abs() > 1e-12 * w {
                    return Err(invalid(
                        format!("{sk}.around"),
                        n,
                        "`around` only for square tubes; give along_x and along_z for rectangular ones",
                    ));
                }
                if through != 1 || !(8..=MAX_COUNT).contains(&n) || (n - 4) % 4 != 0 {
                    return Err(invalid(
                        format!("{sk}.around"),
                        n,
                        "4 + 4k elements (k ≥ 1: four corner blocks and k per side), with through = 1",
                    ));
                }
                ((n - 4) / 4, (n - 4) / 4)
            }
            (None, Some(a), Some(b)) => (count(&format!("{sk}.along_x"), a)?, count(&format!("{sk}.along_z"), b)?),
            _ => {
                return Err(invalid(
                    sk,
                    "tube division",
                    "either `around` (square tubes) or both `along_x` and `along_z` (≥ 1)",
                ));
            }
        };
        let (t64, ax64, az64, p) = (through as u64, ax as u64, az as u64, kind.order() as u64);
        let (nx, nz) = (2 * t64 + ax64, 2 * t64 + az64);
        let elements = nx * nz - ax64 * az64;
        let nodes = (p * nx + 1) * (p * nz + 1) - (p * ax64 - 1) * (p * az64 - 1);
        // each element's nodes are coupled pairwise: a lower bound
        let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
        self.add(kind, elements, nodes, pairs)?;
        CrossSection::tube(kind, origin[0], origin[1], w, h, t, ax, az, through).map_err(|e| rekey(e, sk))
    }

    /// `shape = "tube"` with plies: the same section as a one-cell `box`
    /// (corner blocks with their flanges), whose walls take the plies.
    fn layered_tube(&mut self, sk: &str, kind: SectionElementKind, s: &TubeFile) -> Result<CrossSection, ModelError> {
        let (Some(along_x), Some(along_z), None) = (s.along_x, s.along_z, s.around) else {
            return Err(invalid(
                format!("{sk}.along_x"),
                "(missing, or around given)",
                "along_x and along_z (not around) with plies: the elements along each wall between the corners",
            ));
        };
        let total: f64 = s.plies.iter().flatten().map(|p| p.thickness).sum();
        if let (Some(w), Some(h)) = (s.width, s.height)
            && total.is_finite()
            && 2.0 * total >= w.min(h)
            && s.thickness.is_none()
        {
            return Err(invalid(
                format!("{sk}.plies"),
                format!("a total thickness of {total} m (every wall's)"),
                format!("plies less than half the smaller outer dimension thick in all ({} m)", 0.5 * w.min(h)),
            ));
        }
        let profile = ProfileFile {
            element: s.element,
            origin: s.origin,
            width: s.width,
            height: s.height,
            web_thickness: s.thickness,
            flange_thickness: s.thickness,
            along_flange: Some(along_x),
            along_web: Some(along_z),
            through: s.through,
            junction_element: None,
            plies: s.plies.clone(),
        };
        self.straight(sk, kind, Family::Box, &profile, None, None).map_err(|e| match e {
            // the box's keys are the tube's
            ModelError::Invalid { key, value, allowed } => ModelError::Invalid {
                key: key
                    .replace("web_thickness", "thickness")
                    .replace("flange_thickness", "thickness")
                    .replace("along_flange", "along_x")
                    .replace("along_web", "along_z"),
                value: value.replace("web_thickness", "thickness").replace("flange_thickness", "thickness"),
                allowed: allowed.replace("web thickness", "wall thickness").replace("the flanges", "the walls"),
            },
            e => e,
        })
    }

    /// `shape = "quads"`: listed corner points and quadrilaterals.
    fn quads(&mut self, sk: &str, kind: SectionElementKind, s: &QuadsFile) -> Result<CrossSection, ModelError> {
        let pts = s
            .points
            .as_ref()
            .ok_or_else(|| invalid(format!("{sk}.points"), "(missing)", "a list of [x, z] corner points"))?;
        let quads = s.quads.as_ref().ok_or_else(|| {
            invalid(format!("{sk}.quads"), "(missing)", "a list of [i, j, k, l] counter-clockwise corner indices")
        })?;
        for (k, p) in pts.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite() && v.abs() <= bounds::MAX_COORD) {
                return Err(invalid(
                    format!("{sk}.points[{k}]"),
                    format!("{:?}", p.0),
                    format!("two finite coordinates within ±{:e} m", bounds::MAX_COORD),
                ));
            }
        }
        let pts: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
        let quads: Vec<[usize; 4]> = quads.iter().map(|q| q.0).collect();
        let p = kind.order() as u64;
        let elements = quads.len() as u64;
        // corners plus edge and interior nodes, shared edges counted once: at least
        let nodes = pts.len() as u64 + elements * (p * p).saturating_sub(1) / 2;
        let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
        self.add(kind, elements, nodes, pairs)?;
        Ok(CrossSection::from_quads(kind, &pts, &quads, sk)?)
    }

    /// The straight-walled profiles (I, channel, Z, angle, hat, box); a hat
    /// has `lip` (its `lip` and `along_lip` keys), a box `cells`.
    fn straight(
        &mut self,
        sk: &str,
        kind: SectionElementKind,
        family: Family,
        s: &ProfileFile,
        lip: Option<(Option<f64>, Option<usize>)>,
        cells: Option<usize>,
    ) -> Result<CrossSection, ModelError> {
        let (walls, counts, origin) = walls(sk, s, lip, cells).map_err(|e| plies_total(sk, s, e))?;
        let blocks = profiles::straight(family, origin, &walls, &counts);
        self.blocks(sk, kind, blocks).map_err(|e| plies_total(sk, s, e))
    }

    /// A section of mapped blocks (the profiles), budgeted first.
    fn blocks(
        &mut self,
        sk: &str,
        kind: SectionElementKind,
        blocks: Result<Vec<Block>, MeshError>,
    ) -> Result<CrossSection, ModelError> {
        let blocks = blocks.map_err(|e| rekey(e, sk))?;
        let p = kind.order() as u64;
        let elements = blocks.iter().fold(0u64, |a, b| a.saturating_add(b.n_elements() as u64));
        // nodes: at least p² per element; pairs: each element's nodes pairwise
        let nodes = elements.saturating_mul(p * p);
        let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
        self.add(kind, elements, nodes, pairs)?;
        blocks::from_blocks(kind, &blocks).map_err(|e| rekey(e, sk))
    }

    /// `shape = "gmsh"`: the mesh of `file` (relative to the model file's folder).
    fn gmsh(&mut self, sk: &str, s: &GmshFile, base: &Path) -> Result<CrossSection, ModelError> {
        let file = s.file.as_ref().ok_or_else(|| {
            invalid(format!("{sk}.file"), "(missing)", "the path of a gmsh .msh file, relative to the model file")
        })?;
        let scale = s.scale.unwrap_or(defaults::GMSH_SCALE);
        ranges::GMSH_SCALE.check(&format!("{sk}.scale"), scale, "a factor, e.g. 1e-3 for a mesh in mm")?;
        let section = gmsh::read(&base.join(file), scale, &format!("{sk}.file"))?;
        if let Some(e) = s.element
            && e.kind() != section.kind
        {
            return Err(invalid(
                format!("{sk}.element"),
                format!("{:?}", format!("{e:?}")),
                format!("{:?} (the elements of {file:?}), or no `element` key", section.kind),
            ));
        }
        let p = section.kind.order() as u64;
        let elements = section.n_elements() as u64;
        let pairs = elements.saturating_mul((p + 1).pow(4)) / 4;
        self.add(section.kind, elements, section.n_nodes() as u64, pairs)?;
        Ok(section)
    }
}

/// The walls, element counts and origin of a straight-walled profile, with
/// the keys as the builders name them.
fn walls(
    sk: &str,
    s: &ProfileFile,
    lip: Option<(Option<f64>, Option<usize>)>,
    cells: Option<usize>,
) -> Result<(Walls, Counts, [f64; 2]), ModelError> {
    let n = |name: &str, v: Option<usize>, default: usize| count(&format!("{sk}.{name}"), v.unwrap_or(default));
    let (web_thickness, flange_thickness, through, plies) = wall_plies(sk, s)?;
    let walls = Walls {
        width: length(format!("{sk}.width"), s.width, "the overall width")?,
        height: length(format!("{sk}.height"), s.height, "the overall height")?,
        web: length(format!("{sk}.web_thickness"), web_thickness, "the web thickness")?,
        flange: length(format!("{sk}.flange_thickness"), flange_thickness, "the flange thickness")?,
        lip: match lip {
            Some((width, _)) => length(format!("{sk}.lip"), width, "the lip width")?,
            None => 0.0,
        },
        cells: cells.unwrap_or(defaults::CELLS),
    };
    let counts = Counts {
        flange: n("along_flange", s.along_flange, defaults::ALONG_FLANGE)?,
        web: n("along_web", s.along_web, defaults::ALONG_WEB)?,
        lip: n("along_lip", lip.and_then(|l| l.1), defaults::ALONG_LIP)?,
        through: n("through", through, defaults::THROUGH)?,
        plies,
        junction: match s.junction_element {
            Some(a) => {
                Some(length(format!("{sk}.junction_element"), Some(a), "the length of the element next to a junction")?)
            }
            None => None,
        },
    };
    let origin = point(format!("{sk}.origin"), s.origin.map(Into::into))?;
    Ok((walls, counts, origin))
}

/// With plies, the wall thicknesses are the plies' total unless the file
/// gives them too: an error on a thickness the file did not write names
/// `plies` and the total.
fn plies_total(sk: &str, s: &ProfileFile, e: ModelError) -> ModelError {
    match e {
        ModelError::Invalid { key, value, allowed } if s.plies.is_some() => {
            let written = |k: &str| match k {
                "web_thickness" => s.web_thickness.is_some(),
                "flange_thickness" => s.flange_thickness.is_some(),
                _ => true,
            };
            match key.strip_prefix(sk).and_then(|k| k.strip_prefix('.')) {
                Some(k) if !written(k) && k.ends_with("thickness") => ModelError::Invalid {
                    key: format!("{sk}.plies"),
                    value: format!("a total thickness of {value} m (the plies' thicknesses summed: every wall's)"),
                    allowed,
                },
                _ => ModelError::Invalid { key, value, allowed },
            }
        }
        e => e,
    }
}

/// A profile's wall thicknesses and elements through them, from its plies
/// when it has some: every wall is the stack (web_thickness and
/// flange_thickness, if given, must equal its thickness; through, its
/// elements), with each ply's share of the thickness and elements.
#[allow(clippy::type_complexity)]
fn wall_plies(
    sk: &str,
    s: &ProfileFile,
) -> Result<(Option<f64>, Option<f64>, Option<usize>, Vec<(f64, usize)>), ModelError> {
    let Some(plies) = s.plies.as_deref() else {
        return Ok((s.web_thickness, s.flange_thickness, s.through, Vec::new()));
    };
    super::laminate::check(sk, plies)?;
    let total: f64 = plies.iter().map(|p| p.thickness).sum();
    let elements: usize = plies.iter().map(|p| p.elements.unwrap_or(defaults::THROUGH)).sum();
    for (name, v) in [("web_thickness", s.web_thickness), ("flange_thickness", s.flange_thickness)] {
        if let Some(v) = v
            && (v - total).abs() > 1e-9 * total
        {
            return Err(invalid(
                format!("{sk}.{name}"),
                v,
                format!("the plies' total thickness {total} m, or no {name} (the plies give every wall's thickness)"),
            ));
        }
    }
    if let Some(t) = s.through
        && t != elements
    {
        return Err(invalid(format!("{sk}.through"), t, format!("the plies' {elements} elements, or no through")));
    }
    let shares = plies.iter().map(|p| (p.thickness / total, p.elements.unwrap_or(defaults::THROUGH))).collect();
    Ok((Some(total), Some(total), Some(elements), shares))
}

fn length(key: String, v: Option<f64>, what: &str) -> Result<f64, ModelError> {
    let v = v.ok_or_else(|| invalid(&key, "(missing)", format!("{what} in m")))?;
    ranges::LENGTH.check(&key, v, &format!("{what} in m, positive"))
}

fn point(key: String, v: Option<[f64; 2]>) -> Result<[f64; 2], ModelError> {
    let p = v.unwrap_or(defaults::ORIGIN);
    if p.iter().all(|c| c.is_finite() && c.abs() <= bounds::MAX_COORD) {
        Ok(p)
    } else {
        Err(invalid(key, format!("{p:?}"), format!("two finite coordinates [x, z] within ±{:e} m", bounds::MAX_COORD)))
    }
}

/// Prefixes the key of a mesh error raised by a builder that does not know its path.
fn rekey(e: MeshError, prefix: &str) -> ModelError {
    match e {
        MeshError::Invalid { key, value, allowed } => {
            let key = match key.strip_prefix("section") {
                Some(rest) => format!("{prefix}{rest}"),
                None => key,
            };
            ModelError::Invalid { key, value, allowed }
        }
    }
}

/// The interval ranges `[[i0, i1], [j0, j1]]` of a rectangle's `hole` on
/// the grid `xl` × `zl`: each edge on an element boundary
/// (`mesh::boundary_at`), strictly inside the grid so that the walls around
/// it are at least one element thick.
fn hole_cells(sk: &str, hole: &HoleFile, xl: &[f64], zl: &[f64]) -> Result<[[usize; 2]; 2], ModelError> {
    let size = crate::mesh::grid_size(xl, zl);
    let range = |axis: &str, lines: &[f64], [a, b]: [f64; 2]| {
        let at = |v: f64| crate::mesh::boundary_at(lines, v, size);
        match (at(a), at(b)) {
            (Some(i), Some(j)) if 0 < i && i < j && j < lines.len() - 1 => Ok([i, j]),
            _ => Err(invalid(
                format!("{sk}.hole.{axis}"),
                format!("[{a}, {b}]"),
                format!(
                    "two element boundaries of {axis} inside the section, the first the smaller (the walls around \
                     the hole at least one element thick): boundaries {:?}",
                    &lines[1..lines.len() - 1]
                ),
            )),
        }
    };
    Ok([range("x", xl, hole.x)?, range("z", zl, hole.z)?])
}
