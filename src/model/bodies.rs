//! Bodies: cross-sections and beam axes from the model file, budgeted
//! against the memory limit before each section is built, and their
//! Gauss-point values (computed once, for validation and the analysis).

use std::path::Path;

use super::bounds;
use super::schema::*;
use super::sections;
use super::validate::{MAX_COUNT, count, division, division_parts};
use super::{Limits, ModelError, invalid};
use crate::elements::ElementError;
use crate::materials::Material;
use crate::mesh::{BeamAxis, Body, CrossSection, Mesh, MeshError};
use crate::shape::{BeamElementKind, SectionElementKind};
use crate::size::{self, Sizes};
use crate::values::CellValues;

/// `[[bodies]]`: the mesh and the Gauss-point values of every body (a
/// distorted section element is rejected here).
/// Files named by a section (gmsh) are relative to `base`.
pub(super) fn mesh(
    file: &[BodyFile],
    materials: &[Material],
    limits: Limits,
    base: &Path,
) -> Result<(Mesh, Vec<CellValues>), ModelError> {
    let mut bodies = Vec::new();
    let mut budget = Budget { limit: limits.max_memory, sizes: Sizes::default() };
    for (i, b) in file.iter().enumerate() {
        bodies.push(body(i, b, materials, &mut budget, base)?);
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
            let bbar = match file[i].formulation.as_deref() {
                None => materials[b.material].poisson >= 0.45,
                Some("standard") => false,
                Some("bbar") => true,
                Some(other) => {
                    return Err(invalid(
                        format!("bodies[{i}].formulation"),
                        format!("{other:?}"),
                        "\"standard\" (displacement-based, fully integrated; the default for ν < 0.45) or \"bbar\" \
                         (volumetric strain projected per element; the default for ν ≥ 0.45)",
                    ));
                }
            };
            Ok(if bbar { cell.with_bbar(b) } else { cell })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    Ok((mesh, cells))
}

/// Sizes of the bodies read so far, checked against the limit before each
/// body's section is built (see [`crate::size`]).
pub(super) struct Budget {
    limit: Option<u64>,
    sizes: Sizes,
}

impl Budget {
    /// Adds a body of `sec_elements` section elements (with `sec_nodes`
    /// nodes and `sec_pairs` coupled node pairs) swept along `axis_elements`
    /// beam elements; fails if the lower-bound memory exceeds the limit.
    #[allow(clippy::too_many_arguments)] // the counts of a section × axis body
    pub(super) fn add(
        &mut self,
        key: &str,
        section: SectionElementKind,
        beam: BeamElementKind,
        sec_elements: u64,
        sec_nodes: u64,
        sec_pairs: u64,
        axis_elements: u64,
    ) -> Result<(), ModelError> {
        let (p, q) = (section.order() as u64, beam.order() as u64);
        let axis_nodes = q * axis_elements + 1;
        let per_element = (p + 1) * (p + 1) * (q + 1);
        let elements = sec_elements.saturating_mul(axis_elements);
        let nodes = sec_nodes.saturating_mul(axis_nodes);
        let pairs = sec_pairs.saturating_mul(size::coupled_1d(axis_elements, q));
        let n = 3 * per_element;
        let s = &mut self.sizes;
        s.nodes = s.nodes.saturating_add(nodes);
        s.dofs = s.dofs.saturating_add(nodes.saturating_mul(3));
        s.elements = s.elements.saturating_add(elements);
        s.gauss_points = s.gauss_points.saturating_add(elements.saturating_mul(per_element));
        s.element_entries = s.element_entries.saturating_add(elements.saturating_mul(n * (n + 1) / 2));
        s.node_pairs = s.node_pairs.saturating_add(pairs);
        // 9 entries per off-diagonal node pair (each counted twice), 6 per diagonal block
        let nnz = pairs.saturating_sub(nodes).saturating_mul(9) / 2 + nodes.saturating_mul(6);
        s.pattern_nnz = s.pattern_nnz.saturating_add(nnz);
        s.factor_nnz = s.pattern_nnz;
        s.vtu_points = s.vtu_points.saturating_add(elements.saturating_mul(per_element));
        let needed = s.memory().total();
        match self.limit {
            Some(limit) if needed > limit => Err(ModelError::TooLarge {
                needed,
                limit,
                dofs: s.dofs,
                largest: format!("{key}: {sec_elements} section × {axis_elements} beam elements"),
            }),
            _ => Ok(()),
        }
    }
}

pub(super) fn body(
    i: usize,
    b: &BodyFile,
    materials: &[Material],
    budget: &mut Budget,
    base: &Path,
) -> Result<Body, ModelError> {
    let key = format!("bodies[{i}]");
    // the axis first: its size is needed to budget the body before the
    // section mesh is built
    let a = &b.axis;
    let ak = format!("{key}.axis");
    let beam = BeamElementKind::parse(&a.element)
        .ok_or_else(|| invalid(format!("{ak}.element"), format!("{:?}", a.element), "\"B2\", \"B3\" or \"B4\""))?;
    let axis_lines = division_parts(&ak, a.from, a.to, a.elements, a.ratio, a.lines.as_ref(), a.segments.as_ref())?;
    let axis_elements = (axis_lines.len() - 1) as u64;
    let material = materials.iter().position(|m| m.name == b.material).ok_or_else(|| {
        let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        invalid(format!("{key}.material"), format!("{:?}", b.material), format!("one of the materials {names:?}"))
    })?;
    let s = &b.section;
    let sk = format!("{key}.section");
    sections::check_keys(&sk, s)?;
    let axis = |section: CrossSection| -> Result<Body, ModelError> {
        connected(&sk, &section)?;
        Ok(Body {
            name: b.name.clone(),
            section,
            axis: BeamAxis::from_lines(beam, &axis_lines),
            material,
            node_offset: 0,
            element_offset: 0,
        })
    };
    if s.shape == "gmsh" {
        return axis(sections::gmsh_section(&key, s, base, beam, axis_elements, budget)?);
    }
    let element = s.element.as_deref().ok_or_else(|| {
        invalid(format!("{sk}.element"), "(missing)", "\"L4\", \"L9\" or \"L16\" (the section element)")
    })?;
    let kind = SectionElementKind::parse(element)
        .ok_or_else(|| invalid(format!("{sk}.element"), format!("{element:?}"), "\"L4\", \"L9\" or \"L16\""))?;
    let section = match s.shape.as_str() {
        "rectangle" => {
            let x = s.x.as_ref().ok_or_else(|| {
                invalid(format!("{sk}.x"), "(missing)", "a division of x, e.g. {from = 0.0, to = 0.5, elements = 18}")
            })?;
            let z = s.z.as_ref().ok_or_else(|| {
                invalid(format!("{sk}.z"), "(missing)", "a division of z, e.g. {from = 0.0, to = 0.3, elements = 6}")
            })?;
            let xl = division(&format!("{sk}.x"), x)?;
            let zl = division(&format!("{sk}.z"), z)?;
            let (nx, nz, p) = ((xl.len() - 1) as u64, (zl.len() - 1) as u64, kind.order() as u64);
            let pairs = size::coupled_1d(nx, p).saturating_mul(size::coupled_1d(nz, p));
            budget.add(&key, kind, beam, nx * nz, (p * nx + 1) * (p * nz + 1), pairs, axis_elements)?;
            CrossSection::rectangle(kind, &xl, &zl).map_err(|e| rekey(e, &sk))?
        }
        "tube" => {
            let need = |name: &str, v: Option<f64>| {
                v.ok_or_else(|| invalid(format!("{sk}.{name}"), "(missing)", "a positive length in m")).and_then(|v| {
                    bounds::within(
                        &format!("{sk}.{name}"),
                        v,
                        f64::MIN_POSITIVE,
                        bounds::MAX_COORD,
                        "a positive length in m",
                    )
                })
            };
            let (w, h, t) = (need("width", s.width)?, need("height", s.height)?, need("thickness", s.thickness)?);
            if 2.0 * t >= w.min(h) {
                return Err(invalid(
                    format!("{sk}.thickness"),
                    t,
                    format!("less than half the smaller outer dimension ({})", 0.5 * w.min(h)),
                ));
            }
            let origin: [f64; 2] = s.origin.map_or([0.0, 0.0], Into::into);
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
                    format!(
                        "at least {:e} of the outer size (round-off would swamp the wall)",
                        bounds::MIN_RELATIVE_SIZE
                    ),
                ));
            }
            let through = count(&format!("{sk}.through"), s.through.unwrap_or(1))?;
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
                        sk.clone(),
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
            budget.add(&key, kind, beam, elements, nodes, pairs, axis_elements)?;
            CrossSection::tube(kind, origin[0], origin[1], w, h, t, ax, az, through).map_err(|e| rekey(e, &sk))?
        }
        "quads" => {
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
            budget.add(&key, kind, beam, elements, nodes, pairs, axis_elements)?;
            CrossSection::from_quads(kind, &pts, &quads, &sk)?
        }
        _ => match sections::profile(&key, s, kind, beam, axis_elements, budget)? {
            Some(section) => section,
            None => return Err(invalid(format!("{sk}.shape"), format!("{:?}", s.shape), "a known shape")),
        },
    };
    axis(section)
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

/// Prefixes the key of a mesh error raised by a builder that does not know its path.
pub(super) fn rekey(e: MeshError, prefix: &str) -> ModelError {
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
