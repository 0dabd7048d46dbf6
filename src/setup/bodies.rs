//! Bodies: cross-sections and beam axes from the model file, budgeted
//! against the memory limit before each section is built, and their
//! Gauss-point values (computed once, for validation and the analysis).

use std::path::Path;

use super::budget::Budget;
use super::sections::Sections;
use super::{Limits, Warning};
use crate::bc::symmetry::Plane;
use crate::elements::ElementError;
use crate::input::schema::*;
use crate::input::validate::division_parts;
use crate::input::{ModelError, invalid};
use crate::materials::Material;
use crate::mesh::{BeamAxis, Body, CrossSection, Mesh};
use crate::values::CellValues;

/// `[[bodies]]`: the mesh and the Gauss-point values of every body (a
/// distorted section element is rejected here).
/// Files named by a section (gmsh) are relative to `base`.
pub(super) fn mesh(
    input: &Input<'_>,
    materials: &mut Vec<Material>,
    warnings: &mut Vec<Warning>,
) -> Result<(Mesh, Vec<CellValues>), ModelError> {
    let (file, analysis, base, planes) = (input.file, input.analysis, input.base, input.planes);
    let mut bodies = Vec::new();
    let mut budget = Budget::new(input.limits.max_memory);
    for (i, b) in file.iter().enumerate() {
        bodies.push(body(i, b, materials, &mut budget, base, planes, warnings)?);
    }
    let mesh = Mesh::new(bodies);
    let cells = mesh
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let cell = CellValues::new(b).map_err(|e| match e {
                ElementError::Distorted { element, det, .. } => invalid(
                    format!("bodies[{i}].section"),
                    format!("element {element} with Jacobian determinant {det:e}"),
                    "convex quadrilaterals listed counter-clockwise in the x–z plane",
                ),
            })?;
            // B-bar by default where the displacement-based element locks in
            // elasticity (ν ≥ 0.45: tests/locking.rs); for plastic flow the
            // choice stays the user's (docs/cross-check.md, docs/limitations.md)
            let bbar = match file[i].formulation {
                None => b.materials().iter().any(|&m| materials[m].anisotropic.is_none() && materials[m].poisson >= 0.45),
                Some(Formulation::Standard | Formulation::AssumedShear) => false,
                Some(Formulation::Bbar) => true,
            };
            if file[i].formulation == Some(Formulation::AssumedShear) {
                // the tying interpolation (crate::values::AssumedShear) needs p ≥ 2 to pass
                // the patch test; at finite strain it ties the Green–Lagrange strain
                if b.section.kind.order() < 2 {
                    return Err(invalid(
                        format!("bodies[{i}].formulation"),
                        "\"assumed_shear\" with L4 section elements",
                        "\"assumed_shear\" with L9 or L16 section elements, or \"standard\"/\"bbar\"",
                    ));
                }
                if analysis.geometry == Some(Geometry::Nonlinear) {
                    if analysis.strain == Some(StrainMeasure::Logarithmic) {
                        return Err(invalid(
                            format!("bodies[{i}].formulation"),
                            "\"assumed_shear\" with analysis.strain = \"logarithmic\"",
                            "\"standard\" or \"bbar\", or the Green–Lagrange strain (the assumed shear ties E_ξη)",
                        ));
                    }
                    if analysis.imperfection.is_some() {
                        return Err(invalid(
                            format!("bodies[{i}].formulation"),
                            "\"assumed_shear\" with analysis.imperfection",
                            "\"standard\" (a stress-free imperfection is not tied)",
                        ));
                    }
                }
                return Ok(cell.with_assumed_shear(b));
            }
            if bbar && analysis.geometry == Some(Geometry::Nonlinear) {
                // at finite strain B-bar projects the logarithmic dilatation
                // ln J (crate::elements's fbar), which only the logarithmic
                // strain has as its trace; a stress-free imperfection would
                // need its own projected dilatation
                let why =
                    if file[i].formulation.is_some() { "\"bbar\"" } else { "unset (B-bar by default for ν ≥ 0.45)" };
                if analysis.strain != Some(StrainMeasure::Logarithmic) {
                    return Err(invalid(
                        format!("bodies[{i}].formulation"),
                        why,
                        "\"standard\" with the Green–Lagrange strain (B-bar at finite strain needs analysis.strain = \"logarithmic\")",
                    ));
                }
                if analysis.imperfection.is_some() {
                    return Err(invalid(
                        format!("bodies[{i}].formulation"),
                        why,
                        "\"standard\" with analysis.imperfection (B-bar of an imperfect shape is not implemented)",
                    ));
                }
            }
            Ok(if bbar { cell.with_bbar(b) } else { cell })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    Ok((mesh, cells))
}

/// What the bodies are built from.
pub(super) struct Input<'a> {
    /// `[[bodies]]`.
    pub file: &'a [BodyFile],
    /// `[analysis]` (the default formulation depends on it).
    pub analysis: &'a AnalysisFile,
    /// The memory limit.
    pub limits: Limits,
    /// The folder of relative file names.
    pub base: &'a Path,
    /// The symmetry planes (which cut the bodies).
    pub planes: &'a [Plane],
}

pub(super) fn body(
    i: usize,
    b: &BodyFile,
    materials: &mut Vec<Material>,
    budget: &mut Budget,
    base: &Path,
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<Body, ModelError> {
    let key = format!("bodies[{i}]");
    // the axis first: its size is needed to budget the body before the
    // section mesh is built
    let a = &b.axis;
    let ak = format!("{key}.axis");
    let beam = a.element.kind();
    let axis_lines = division_parts(&ak, a.from, a.to, a.elements, a.ratio, a.lines.as_ref(), a.segments.as_ref())?;
    let axis_elements = (axis_lines.len() - 1) as u64;
    let section = Sections { key: &key, beam, axis_elements, budget }.section(&b.section, base)?;
    if let crate::input::schema::SectionFile::Gmsh(g) = &b.section
        && g.scale.is_none()
    {
        let length = axis_lines.last().zip(axis_lines.first()).map_or(0.0, |(end, start)| (end - start).abs());
        unit_mismatch(&key, &section, length, warnings);
    }
    // symmetry planes cut the body to the side kept; each must be a plane
    // of symmetry of the body as written
    let written = (!planes.is_empty()).then(|| (section.clone(), axis_lines.clone()));
    let (section, axis_lines) = super::symmetry::cut(&key, &b.name, planes, section, axis_lines)?;
    if let Some((whole, lines)) = &written {
        let whole = super::mirror::Whole { key: &key, file: b, section: whole, lines, beam };
        super::mirror::check(&whole, planes, materials, warnings)?;
    }
    connected(&format!("{key}.section"), &section)?;
    let (material, element_materials) = super::zones::assign(&key, b, &section, materials)?;
    let element_layers = super::zones::layers(&key, b, &section);
    Ok(Body {
        name: b.name.clone(),
        section,
        axis: BeamAxis::from_lines(beam, &axis_lines),
        material,
        element_materials,
        element_layers,
        node_offset: 0,
        element_offset: 0,
        whole_size: written.as_ref().map(|(section, lines)| super::symmetry::whole_size(section, lines, planes)),
    })
}

/// A gmsh section drawn in mm and read without `scale = 1e-3` is a
/// thousand times too large: a 100 mm profile on a 1 m axis became 100 m
/// across and ran without a word (a new-user review). Without a `scale`, a
/// section at least 20 m across (no beam's) or a hundred times wider than
/// its body is long (a plane-strain slice is ten to forty) is warned
/// about, naming the key that fixes it if it was drawn in mm.
fn unit_mismatch(key: &str, section: &CrossSection, length: f64, warnings: &mut Vec<Warning>) {
    let [x0, x1, z0, z1] = section.bounds();
    let width = (x1 - x0).max(z1 - z0);
    if width >= 20.0 || width > 100.0 * length {
        let short = crate::numbers::short;
        warnings.push(Warning {
            key: format!("{key}.section.scale"),
            message: format!(
                "not given (1): the section spans {} m across, {:.0} times the body's length of {} m along y; if it \
                 was drawn in mm, give `scale = 1e-3` (the axis is read in m)",
                short(width),
                width / length,
                short(length)
            ),
        });
    }
}

/// A section must be one region connected through shared element edges: a
/// part touching the rest at a corner only (a hinge line once swept along
/// the axis) or not at all is free to move against it, and the analysis
/// used to fail at λ = 0 after its iterations.
fn connected(sk: &str, section: &CrossSection) -> Result<(), ModelError> {
    let parts = section.parts();
    if parts.len() <= 1 {
        return Ok(());
    }
    const SHOWN: usize = 4;
    let mut list: Vec<String> = parts
        .iter()
        .take(SHOWN)
        .map(|part| {
            // a point of the part: the centre of its first element's nodes
            let el = section.element(part[0]);
            let mut c = [0.0; 2];
            for &n in el {
                c[0] += section.nodes[n][0] / el.len() as f64;
                c[1] += section.nodes[n][1] / el.len() as f64;
            }
            let plural = if part.len() == 1 { "" } else { "s" };
            format!(
                "{} element{plural} (first: element {} at x = {}, z = {})",
                part.len(),
                part[0],
                crate::numbers::short(c[0]),
                crate::numbers::short(c[1])
            )
        })
        .collect();
    if parts.len() > SHOWN {
        list.push(format!("and {} more", parts.len() - SHOWN));
    }
    Err(invalid(
        sk,
        format!("{} separate parts: {}", parts.len(), list.join("; ")),
        "one region whose elements are connected through shared edges (elements touching only at a corner form a \
         hinge, and a separate piece is free to move); model separate pieces as separate bodies",
    ))
}
