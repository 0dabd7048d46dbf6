//! The materials of a body's section elements: the body's `material`, the
//! plies of a laminate section or through a profile's walls (each wall's
//! plies turned about that wall's normal) and `[[bodies.zones]]` (a section region's
//! material and material axes), applied in that order. A material placed
//! in a frame it cares about (anisotropic stiffness, or strengths whose
//! indices are taken in its axes) becomes an oriented copy appended to the
//! model's material list ([`Material::oriented`]); one copy per material
//! and frame.

use super::laminate;
use crate::input::schema::{BodyFile, SectionFile, ZoneFile};
use crate::input::{ModelError, invalid, ranges};
use crate::materials::{Frame, Material};
use crate::mesh::CrossSection;

/// One zone as the model file gives it, from a ply or `[[bodies.zones]]`.
struct Zone<'a> {
    key: String,
    region: Option<String>,
    material: Option<&'a str>,
    angle: f64,
    fibre: [f64; 3],
    normal: [f64; 3],
    /// True if the zone states an orientation (angle or axes).
    oriented: bool,
}

/// Index of the material called `name` (key `key` for the message).
fn find(key: &str, name: &str, materials: &[Material]) -> Result<usize, ModelError> {
    materials.iter().position(|m| m.name == name).ok_or_else(|| {
        let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        invalid(key, format!("{name:?}"), format!("one of the materials {names:?}"))
    })
}

fn zones<'a>(key: &str, b: &'a BodyFile, section: &CrossSection) -> Vec<Zone<'a>> {
    let mut out = Vec::new();
    if let Some(plies) = b.section.wall_plies() {
        // `<wall>_ply<k>` regions of a profile (mesh::profiles), with their wall's normal
        for r in &section.regions {
            let Some(n) = r.normal else { continue };
            let Some(k) = r.name.rsplit_once("_ply").and_then(|(_, k)| k.parse::<usize>().ok()) else { continue };
            let Some(p) = k.checked_sub(1).and_then(|k| plies.get(k)) else { continue };
            out.push(Zone {
                key: format!("{key}.section.plies[{}]", k - 1),
                region: Some(r.name.clone()),
                material: Some(&p.material),
                angle: p.angle.unwrap_or(crate::input::defaults::ANGLE),
                fibre: [0.0, 1.0, 0.0],
                normal: [n[0], 0.0, n[1]],
                oriented: true,
            });
        }
    }
    if let SectionFile::Laminate(l) = &b.section {
        for (k, p) in l.plies.as_deref().unwrap_or(&[]).iter().enumerate() {
            out.push(Zone {
                key: format!("{key}.section.plies[{k}]"),
                region: Some(laminate::region_name(k)),
                material: Some(&p.material),
                angle: p.angle.unwrap_or(crate::input::defaults::ANGLE),
                fibre: [0.0, 1.0, 0.0],
                normal: [0.0, 0.0, 1.0],
                oriented: true,
            });
        }
    }
    for (k, z) in b.zones.as_deref().unwrap_or(&[]).iter().enumerate() {
        out.push(zone(format!("{key}.zones[{k}]"), z));
    }
    out
}

fn zone(key: String, z: &ZoneFile) -> Zone<'_> {
    Zone {
        key,
        region: z.region.clone(),
        material: z.material.as_deref(),
        angle: z.angle.unwrap_or(crate::input::defaults::ANGLE),
        fibre: z.fibre.map_or(crate::input::defaults::FIBRE, Into::into),
        normal: z.normal.map_or(crate::input::defaults::NORMAL, Into::into),
        oriented: z.angle.is_some() || z.fibre.is_some() || z.normal.is_some(),
    }
}

/// The body's material and the material of each of its section elements
/// (empty when every element has the body's own, unturned material).
pub(super) fn assign(
    key: &str,
    b: &BodyFile,
    section: &CrossSection,
    materials: &mut Vec<Material>,
) -> Result<(usize, Vec<usize>), ModelError> {
    assign_traced(key, b, section, materials).map(|(base, per_element, _)| (base, per_element))
}

/// The layer of each section element ([`crate::mesh::Body::element_layers`]):
/// the index of the last zone (ply or `[[bodies.zones]]` entry) that
/// covers it, in the order [`assign`] applies them; empty without zones.
/// A zone naming no region of the section covers nothing ([`assign`]
/// refuses it).
pub(super) fn layers(key: &str, b: &BodyFile, section: &CrossSection) -> Vec<usize> {
    let list = zones(key, b, section);
    if list.is_empty() {
        return Vec::new();
    }
    let mut layer = vec![0; section.n_elements()];
    for (k, z) in list.iter().enumerate() {
        let elements: Vec<usize> = match &z.region {
            None => (0..section.n_elements()).collect(),
            Some(r) => section.regions.iter().find(|g| &g.name == r).map_or_else(Vec::new, |g| g.elements.clone()),
        };
        for e in elements {
            layer[e] = k + 1;
        }
    }
    layer
}

/// [`assign`], with what gave each section element its material, as the
/// file says it (`bodies[0].section.plies[1] (material "cfrp", angle 30°)`;
/// empty when every element has the body's own material).
pub(super) fn assign_traced(
    key: &str,
    b: &BodyFile,
    section: &CrossSection,
    materials: &mut Vec<Material>,
) -> Result<(usize, Vec<usize>, Vec<String>), ModelError> {
    let base = b.material.as_deref().map(|name| find(&format!("{key}.material"), name, materials)).transpose()?;
    let list = zones(key, b, section);
    let base_source = format!("{key}.material ({:?})", b.material.as_deref().unwrap_or_default());
    let mut source = vec![base_source; section.n_elements()];
    if list.is_empty() {
        let base = base.ok_or_else(|| {
            invalid(
                format!("{key}.material"),
                "(missing)",
                "the body's material (required unless a laminate's plies or [[bodies.zones]] give every section element one)",
            )
        })?;
        return Ok((base, Vec::new(), Vec::new()));
    }
    let mut per_element: Vec<Option<usize>> = vec![base; section.n_elements()];
    for z in &list {
        let elements: Vec<usize> = match &z.region {
            None => (0..section.n_elements()).collect(),
            Some(r) => section.regions.iter().find(|g| &g.name == r).map(|g| g.elements.clone()).ok_or_else(|| {
                let names: Vec<&str> = section.regions.iter().map(|g| g.name.as_str()).collect();
                invalid(
                    format!("{}.region", z.key),
                    format!("{r:?}"),
                    format!("one of the section's regions {names:?}"),
                )
            })?,
        };
        let m = match z.material {
            Some(name) => find(&format!("{}.material", z.key), name, materials)?,
            None => base.ok_or_else(|| {
                invalid(format!("{}.material", z.key), "(missing)", "a material (the body has none of its own)")
            })?,
        };
        let m = oriented(z, m, materials)?;
        let described = describe(z, &materials[m]);
        for e in elements {
            per_element[e] = Some(m);
            source[e].clone_from(&described);
        }
    }
    if let Some(e) = per_element.iter().position(Option::is_none) {
        let bare = per_element.iter().filter(|m| m.is_none()).count();
        return Err(invalid(
            format!("{key}.material"),
            format!("(missing; {bare} section elements have no material, the first is element {e})"),
            "a material for the body, or plies and zones covering the whole section",
        ));
    }
    let per_element: Vec<usize> = per_element.into_iter().flatten().collect();
    Ok((base.unwrap_or(per_element[0]), per_element, source))
}

/// A zone as the file gives it: its key, material and axes.
fn describe(z: &Zone<'_>, m: &Material) -> String {
    let short = |v: [f64; 3]| v.map(crate::numbers::short).join(", ");
    let mut axes = String::new();
    if z.oriented {
        axes = format!(", angle {}°", crate::numbers::short(z.angle));
        if z.fibre != [0.0, 1.0, 0.0] {
            axes += &format!(", fibre [{}]", short(z.fibre));
        }
        if z.normal != [0.0, 0.0, 1.0] {
            axes += &format!(", normal [{}]", short(z.normal));
        }
    }
    format!("{} (material {:?}{axes})", z.key, m.given)
}

/// The material `m` in the zone's frame: itself when the zone states no
/// orientation (the material keeps its own, global axes) or the frame does
/// not matter to it (isotropic without strengths), else its oriented copy
/// (appended once).
fn oriented(z: &Zone<'_>, m: usize, materials: &mut Vec<Material>) -> Result<usize, ModelError> {
    if !ranges::ANGLE.contains(z.angle) {
        return Err(invalid(format!("{}.angle", z.key), z.angle, format!("an angle in degrees {}", ranges::ANGLE)));
    }
    let frame = Frame::ply(z.fibre, z.normal, z.angle.to_radians()).ok_or_else(|| {
        invalid(
            format!("{}.fibre", z.key),
            format!("{:?} with normal {:?}", z.fibre, z.normal),
            "two non-zero, non-parallel vectors (axis 1 at angle 0, and axis 3)",
        )
    })?;
    let material = &materials[m];
    if !z.oriented || (material.anisotropic.is_none() && material.strengths.is_none()) {
        return Ok(m);
    }
    // `cfrp@90`, with the axes when they are not the laminate's: `cfrp@0 n(1,0,0)`
    let short = |v: [f64; 3]| v.map(crate::numbers::short).join(",");
    let mut suffix = format!("@{}", crate::numbers::short(z.angle));
    if z.normal != [0.0, 0.0, 1.0] {
        suffix += &format!(" n({})", short(z.normal));
    }
    if z.fibre != [0.0, 1.0, 0.0] {
        suffix += &format!(" f({})", short(z.fibre));
    }
    let copy = material.oriented(frame, &suffix);
    if let Some(k) = materials.iter().position(|x| x.name == copy.name) {
        return Ok(k);
    }
    materials.push(copy);
    Ok(materials.len() - 1)
}

/// Ply and zone angles that read as radians: within `10⁻³` of a multiple
/// of π/4 up to 2π (`1.5708` for 90°), which as degrees no one lays a ply
/// at (a new user's review: `angle = 1.5708` was taken as 1.57° in
/// silence).
pub(super) fn radian_warnings(bodies: &[BodyFile], warnings: &mut Vec<super::Warning>) {
    for (i, b) in bodies.iter().enumerate() {
        let plies = b.section.wall_plies().or(match &b.section {
            SectionFile::Laminate(l) => l.plies.as_deref(),
            _ => None,
        });
        let plies = plies.unwrap_or(&[]).iter().enumerate().map(|(k, p)| (format!("section.plies[{k}]"), p.angle));
        let zones = b.zones.as_deref().unwrap_or(&[]).iter().enumerate().map(|(k, z)| (format!("zones[{k}]"), z.angle));
        for (key, angle) in plies.chain(zones) {
            let Some(a) = angle else { continue };
            let quarters = a / std::f64::consts::FRAC_PI_4;
            let k = quarters.round();
            if k != 0.0 && k.abs() <= 8.0 && (a - k * std::f64::consts::FRAC_PI_4).abs() <= 1e-3 {
                let sign = if k < 0.0 { "−" } else { "" };
                let pi = ["π/4", "π/2", "3π/4", "π", "5π/4", "3π/2", "7π/4", "2π"][k.abs() as usize - 1];
                let a = crate::numbers::short(a);
                warnings.push(super::Warning {
                    key: format!("bodies[{i}].{key}.angle"),
                    message: format!(
                        "{a} reads as {sign}{pi} in radians, but angles are in degrees ({a}° here): write {} for {}°",
                        45.0 * k,
                        45.0 * k
                    ),
                });
            }
        }
    }
}
