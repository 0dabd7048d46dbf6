//! A symmetry plane is valid only if the body is its own mirror image
//! across it — its extent and its material layout (plies, zones, material
//! frames). Checked on the section and axis as the file writes them, before
//! the cut (`symmetry::cut`): each section element's points are reflected
//! and located in the full section, and the material found there must be
//! the mirror image of the element's own (`bc::symmetry::reflect_stiffness`:
//! a ply at θ about z mirrors to −θ across a plane normal to x or y; a plane
//! normal to z maps each ply onto the one opposite it). A plane normal to
//! y maps every section element onto itself.
//!
//! A body written on one side of a plane only (the file gives the part kept)
//! declares its mirror image to be the rest: nothing can be compared, and a
//! material that is not its own mirror image there (the full structure then
//! holds −θ plies beside θ ones) is warned about.

use super::Warning;
use crate::bc::symmetry::{Plane, Side, reflect_stiffness};
use crate::input::schema::BodyFile;
use crate::input::{ModelError, invalid};
use crate::materials::Material;
use crate::mesh::{BeamAxis, Body, CrossSection};
use crate::shape::BeamElementKind;

/// The body as the file writes it (before the cut).
pub(super) struct Whole<'a> {
    /// `bodies[i]`.
    pub key: &'a str,
    /// Its entry.
    pub file: &'a BodyFile,
    /// The whole section.
    pub section: &'a CrossSection,
    /// The whole axis's element boundaries.
    pub lines: &'a [f64],
    /// The beam element.
    pub beam: BeamElementKind,
}

/// Refuses a plane across which the body's extent or material layout is not
/// its own mirror image; warns about a body on one side of a plane whose
/// material is not its own mirror image.
pub(super) fn check(
    whole: &Whole<'_>,
    planes: &[Plane],
    materials: &[Material],
    warnings: &mut Vec<Warning>,
) -> Result<(), ModelError> {
    if planes.is_empty() {
        return Ok(());
    }
    let (key, section) = (whole.key, whole.section);
    let mut scratch = materials.to_vec();
    let (base, mut per_element, mut source) = super::zones::assign_traced(key, whole.file, section, &mut scratch)?;
    if per_element.is_empty() {
        per_element = vec![base; section.n_elements()];
        source = vec![format!("{key}.material ({:?})", scratch[base].given); section.n_elements()];
    }
    let layout = Layout { materials: &scratch, per_element: &per_element, source: &source };
    let b = section.bounds();
    let (y0, y1) = (whole.lines[0], whole.lines[whole.lines.len() - 1]);
    let size = ((b[1] - b[0]).powi(2) + (b[3] - b[2]).powi(2) + (y1 - y0).powi(2)).sqrt();
    for (k, p) in planes.iter().enumerate() {
        let plane = Plane { tolerance: 1e-6 * size, ..p.clone() };
        let found = if plane.axis == 1 {
            along_axis(whole, (k, &plane), &layout)?
        } else {
            across_section(whole, (k, &plane), &layout, size)?
        };
        if let Some(e) = found {
            warnings.push(Warning {
                key: format!("symmetry[{k}]"),
                message: format!(
                    "body {:?} lies on one side of symmetry plane {:?} ({}): the full structure the model solves holds \
                     its mirror image on the other side, where {} is turned to its mirror image (a ply at θ about z \
                     becomes one at −θ across a plane normal to x or y); if the structure has the same plies on both \
                     sides, write the whole section or axis (the plane cuts it and checks its layout) or model the \
                     full structure",
                    whole.file.name,
                    p.name,
                    p.describe(),
                    layout.source[e]
                ),
            });
        }
    }
    Ok(())
}

/// Each section element's material and what gave it.
struct Layout<'a> {
    materials: &'a [Material],
    per_element: &'a [usize],
    source: &'a [String],
}

impl Layout<'_> {
    fn material(&self, e: usize) -> &Material {
        &self.materials[self.per_element[e]]
    }

    /// The first element whose material is not its own mirror image.
    fn first_unmirrored(&self, axis: usize) -> Option<usize> {
        (0..self.per_element.len()).find(|&e| !mirror_images(self.material(e), self.material(e), axis))
    }
}

/// A plane normal to y: the axis's ends are mirror images, and every
/// section element's material is its own mirror image. `Some(element)`:
/// the axis lies on one side of the plane only and that element's
/// material is not its own mirror image (a warning).
fn along_axis(whole: &Whole<'_>, (k, p): (usize, &Plane), layout: &Layout<'_>) -> Result<Option<usize>, ModelError> {
    let (y0, y1) = (whole.lines[0], whole.lines[whole.lines.len() - 1]);
    if !p.removes(y0) && !p.removes(y1) {
        // written on the kept side only
        let touches = p.holds([0.0, y0, 0.0]) || p.holds([0.0, y1, 0.0]);
        return Ok(layout.first_unmirrored(1).filter(|_| touches));
    }
    if (y0 + y1 - 2.0 * p.at).abs() > p.tolerance {
        let n = |v: f64| crate::numbers::short(v);
        return Err(invalid(
            format!("{}.axis", whole.key),
            format!("from y = {} to y = {}", n(y0), n(y1)),
            format!(
                "an axis whose ends are mirror images across symmetry plane {:?} ({}): the model would solve the \
                 structure from y = {} to y = {} (write the whole axis centred on the plane, or only the side kept)",
                p.name,
                p.describe(),
                n(if p.keep == Side::Above { 2.0 * p.at - y1 } else { y0 }),
                n(if p.keep == Side::Above { y1 } else { 2.0 * p.at - y0 })
            ),
        ));
    }
    match layout.first_unmirrored(1) {
        None => Ok(None),
        Some(e) => Err(unmirrored(whole, (k, p), layout, e, None)),
    }
}

/// A plane normal to x or z: every sample point of every section element
/// has its image in the section, in a material that is the mirror image
/// of its own. `Some(element)`: as in [`along_axis`].
fn across_section(
    whole: &Whole<'_>,
    (k, p): (usize, &Plane),
    layout: &Layout<'_>,
    size: f64,
) -> Result<Option<usize>, ModelError> {
    let section = whole.section;
    let d = if p.axis == 0 { 0 } else { 1 };
    let at3 = |q: [f64; 2]| [q[0], 0.0, q[1]];
    let samples: Vec<Vec<[f64; 2]>> = (0..section.n_elements()).map(|e| sample_points(section, e)).collect();
    let removed = samples.iter().any(|s| p.removes(at3(s[0])[p.axis]));
    if !removed {
        let touches = section.nodes.iter().any(|&q| p.holds(at3(q)));
        return Ok(layout.first_unmirrored(p.axis).filter(|_| touches));
    }
    let probe = Body::new(String::new(), section.clone(), BeamAxis::from_lines(whole.beam, &[0.0, size]), 0);
    let n_section = section.n_elements();
    for (e, points) in samples.iter().enumerate() {
        for &q in points {
            let mut image = q;
            image[d] = 2.0 * p.at - q[d];
            let found = crate::values::locate(0, &probe, [image[0], 0.5 * size, image[1]]);
            let Some(l) = found.first() else {
                let n = |v: [f64; 2]| format!("({}, {})", crate::numbers::short(v[0]), crate::numbers::short(v[1]));
                return Err(invalid(
                    format!("{}.section", whole.key),
                    format!("the point (x, z) = {} of section element {e}", n(q)),
                    format!(
                        "a section that is its own mirror image across symmetry plane {:?} ({}): the image {} of \
                         this point lies outside it, so the model would solve another structure (write the whole \
                         section, symmetric about the plane, or only the side kept)",
                        p.name,
                        p.describe(),
                        n(image)
                    ),
                ));
            };
            let mirror = l.element % n_section;
            if !mirror_images(layout.material(e), layout.material(mirror), p.axis) {
                return Err(unmirrored(whole, (k, p), layout, e, Some((q, image, mirror))));
            }
        }
    }
    Ok(None)
}

/// The error of an element `e` whose material's mirror image is not the
/// material at its image (`image`: the point, its image and the element
/// holding it; `None` across y, where the image is the element itself).
fn unmirrored(
    whole: &Whole<'_>,
    (k, p): (usize, &Plane),
    layout: &Layout<'_>,
    e: usize,
    image: Option<([f64; 2], [f64; 2], usize)>,
) -> ModelError {
    let n = |v: [f64; 2]| format!("({}, {})", crate::numbers::short(v[0]), crate::numbers::short(v[1]));
    let what = match image {
        None => format!(
            "{} (section element {e}) is not its own mirror image: the part left out would hold it turned (a ply \
             at θ about z becomes one at −θ)",
            layout.source[e]
        ),
        Some((q, i, m)) => format!(
            "{} at (x, z) = {} faces, at its image {}, {}, which is not its mirror image (a ply at θ about z mirrors \
             to −θ across a plane normal to x; across z each ply must face the same ply turned likewise)",
            layout.source[e],
            n(q),
            n(i),
            layout.source[m]
        ),
    };
    invalid(
        format!("symmetry[{k}].plane"),
        format!("{} across body {:?}", p.describe(), whole.file.name),
        format!(
            "a plane about which the body's material layout is its own mirror image: {what}; model the full \
             structure (the plane {:?} would impose a symmetry the structure does not have)",
            p.name
        ),
    )
}

/// The centroid of section element `e` and, on small sections, the points
/// halfway from it to each of its nodes.
fn sample_points(section: &CrossSection, e: usize) -> Vec<[f64; 2]> {
    let el = section.element(e);
    let mut c = [0.0; 2];
    for &n in el {
        c[0] += section.nodes[n][0] / el.len() as f64;
        c[1] += section.nodes[n][1] / el.len() as f64;
    }
    let mut out = vec![c];
    if section.n_elements() <= 500 {
        out.extend(el.iter().map(|&n| [0.5 * (c[0] + section.nodes[n][0]), 0.5 * (c[1] + section.nodes[n][1])]));
    }
    out
}

/// True if `b` is the mirror image of `a` across a plane normal to `axis`:
/// the same constants, the stiffness reflected (`reflect_stiffness`) and,
/// where strengths make the axes matter, the axes reflected (each up to its
/// sign, which no failure index sees).
pub(super) fn mirror_images(a: &Material, b: &Material, axis: usize) -> bool {
    let same = a.young == b.young
        && a.poisson == b.poisson
        && a.hardening == b.hardening
        && a.kinematic == b.kinematic
        && a.density == b.density
        && a.strengths == b.strengths
        && a.anisotropic == b.anisotropic;
    if !same {
        return false;
    }
    let (ca, cb) = (reflect_stiffness(a.elastic_stiffness(), axis), b.elastic_stiffness());
    let scale = ca.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if ca.iter().flatten().zip(cb.iter().flatten()).any(|(x, y)| (x - y).abs() > 1e-9 * scale) {
        return false;
    }
    a.strengths.is_none()
        || (0..3).all(|i| {
            let mut r = a.frame.axes[i];
            r[axis] = -r[axis];
            let dot: f64 = (0..3).map(|k| r[k] * b.frame.axes[i][k]).sum();
            dot.abs() >= 1.0 - 1e-9
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::anisotropic::{Frame, Orthotropic};

    fn ply(deg: f64) -> Material {
        let o = Orthotropic { young: [140e9, 10e9, 10e9], shear: [5e9, 5e9, 3.5e9], poisson: [0.3, 0.3, 0.4] };
        let frame = Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], deg.to_radians()).unwrap();
        Material::anisotropic("cfrp", o.stiffness().unwrap()).oriented(frame, &format!("@{deg}"))
    }

    #[test]
    fn mirror_images_compare_the_reflected_stiffness_and_the_constants() {
        assert!(mirror_images(&ply(30.0), &ply(-30.0), 0));
        assert!(!mirror_images(&ply(30.0), &ply(30.0), 0));
        assert!(mirror_images(&ply(30.0), &ply(30.0), 2));
        assert!(!mirror_images(&ply(0.0), &ply(90.0), 2));
        let steel = Material::new("steel", 200e9, 0.3, None);
        assert!((0..3).all(|a| mirror_images(&steel, &steel, a)));
        // the same stiffness with another density is not the same material
        assert!(!mirror_images(&steel, &steel.clone().with_density(Some(7800.0)), 0));
    }

    #[test]
    fn with_strengths_the_axes_must_mirror_too() {
        use crate::materials::failure::Strengths;
        let s = Strengths { tension: [1e9, 5e7, 5e7], compression: [8e8, 2e8, 2e8], shear: [7e7, 7e7, 5e7] };
        // an isotropic material with strengths in turned axes: the same
        // stiffness, but its indices are taken along 30° or −30°
        let iso = Material::new("glass", 70e9, 0.2, None).with_strengths(Some(s));
        let turned =
            |deg: f64| iso.oriented(Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], deg.to_radians()).unwrap(), "");
        assert!(mirror_images(&turned(30.0), &turned(-30.0), 0));
        assert!(!mirror_images(&turned(30.0), &turned(30.0), 0));
    }
}
