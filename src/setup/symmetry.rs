//! `[[symmetry]]`: the planes read and checked, each body cut to the side
//! kept, the planes' constraints (`u_n = 0` on the plane), the items that
//! lie wholly in the mirrored part (left out), and the items that lie
//! across a plane (whose forces on the full structure are reported).
//! The mechanics is in `bc::symmetry`.

use super::Warning;
use crate::bc::symmetry::{Plane, Side, Symmetry};
use crate::bc::{Condition, Constraint, Load, Selection};
use crate::contact::{Indenter, PairContact, RigidSurface};
use crate::input::schema::{ConditionFile, KeepSide, LoadFile, SelectionFile, SymmetryFile};
use crate::input::{ModelError, bounds, invalid};
use crate::mesh::{CrossSection, Mesh};

/// The planes as the file gives them (tolerance 0 until the bodies are known).
pub(super) fn planes(file: &[SymmetryFile]) -> Result<Vec<Plane>, ModelError> {
    let mut planes: Vec<Plane> = Vec::new();
    for (i, s) in file.iter().enumerate() {
        let key = format!("symmetry[{i}]");
        let given: Vec<(usize, f64)> =
            [s.plane.x, s.plane.y, s.plane.z].into_iter().enumerate().filter_map(|(a, v)| Some((a, v?))).collect();
        let &[(axis, at)] = given.as_slice() else {
            return Err(invalid(
                format!("{key}.plane"),
                format!("{} coordinates", given.len()),
                "exactly one coordinate: { x = … }, { y = … } or { z = … } (a plane normal to that axis)",
            ));
        };
        let at = bounds::coordinate(&format!("{key}.plane.{}", ["x", "y", "z"][axis]), at)?;
        let keep = match s.keep {
            Some(KeepSide::Above) => Side::Above,
            Some(KeepSide::Below) => Side::Below,
            None => {
                return Err(invalid(
                    format!("{key}.keep"),
                    "missing",
                    "\"above\" or \"below\": the side of the plane the model keeps (coordinates ≥ or ≤ the plane's)",
                ));
            }
        };
        if let Some(j) = planes.iter().position(|p| p.axis == axis) {
            return Err(invalid(
                format!("{key}.plane"),
                format!("{} = {at}", ["x", "y", "z"][axis]),
                format!(
                    "a plane normal to another axis than symmetry[{j}]'s (two parallel planes make a periodic cell)"
                ),
            ));
        }
        planes.push(Plane { name: s.name.clone(), axis, at, keep, tolerance: 0.0 });
    }
    Ok(planes)
}

/// Cuts a body's section and axis element boundaries (`lines`) to the sides
/// kept: an element on the left-out side goes, one across a plane is an error.
pub(super) fn cut(
    key: &str,
    body: &str,
    planes: &[Plane],
    mut section: CrossSection,
    mut lines: Vec<f64>,
) -> Result<(CrossSection, Vec<f64>), ModelError> {
    if planes.is_empty() {
        return Ok((section, lines));
    }
    let size = crate::mesh::diagonal(&section, &lines);
    for (i, p) in planes.iter().enumerate() {
        let plane = Plane { tolerance: 1e-6 * size, ..p.clone() };
        let pk = format!("symmetry[{i}].plane");
        // each element's extent along the plane's normal
        let spans: Vec<(f64, f64)> = if plane.axis == 1 {
            lines.windows(2).map(|w| (w[0], w[1])).collect()
        } else {
            let c = if plane.axis == 0 { 0 } else { 1 };
            (0..section.n_elements())
                .map(|e| {
                    let v = section.element(e).iter().map(|&n| section.nodes[n][c]);
                    (v.clone().fold(f64::INFINITY, f64::min), v.fold(f64::NEG_INFINITY, f64::max))
                })
                .collect()
        };
        let mut kept = Vec::with_capacity(spans.len());
        for (e, &(lo, hi)) in spans.iter().enumerate() {
            let (above, below) = (lo >= plane.at - plane.tolerance, hi <= plane.at + plane.tolerance);
            let stays = if plane.keep == Side::Above { above } else { below };
            if !above && !below {
                let what = if plane.axis == 1 { "axis element" } else { "section element" };
                let c = ["x", "y", "z"][plane.axis];
                return Err(invalid(
                    pk,
                    plane.describe(),
                    format!(
                        "a plane along element boundaries: {what} {e} of body {body:?} spans {c} from {} to {} \
                         (place an element boundary on the plane)",
                        crate::numbers::short(lo),
                        crate::numbers::short(hi)
                    ),
                ));
            }
            kept.push(stays);
        }
        if !kept.iter().any(|&k| k) {
            return Err(invalid(
                pk,
                plane.describe(),
                format!("a plane with part of body {body:?} on the side kept ({key} lies wholly on the side left out)"),
            ));
        }
        if plane.axis == 1 {
            let first = kept.iter().position(|&k| k).unwrap_or(0);
            let last = kept.iter().rposition(|&k| k).unwrap_or(0);
            lines = lines[first..=last + 1].to_vec();
        } else {
            section = section.retain_elements(|e| kept[e]);
        }
    }
    Ok((section, lines))
}

/// The size (bounding-box diagonal) of the whole structure's body of which
/// `section` swept along `lines` is written: the box joined with its
/// mirror image across every plane it touches, so that a body written
/// whole and one written on the kept side only (which declares its mirror
/// image to be the rest, `setup::mirror`) get the same size.
pub(super) fn whole_size(section: &CrossSection, lines: &[f64], planes: &[Plane]) -> f64 {
    let b = section.bounds();
    let mut boxed = [[b[0], b[1]], [lines[0], lines[lines.len() - 1]], [b[2], b[3]]];
    let tolerance = 1e-6 * crate::mesh::diagonal(section, lines);
    for p in planes {
        let [lo, hi] = boxed[p.axis];
        if p.at >= lo - tolerance && p.at <= hi + tolerance {
            boxed[p.axis] = [lo.min(2.0 * p.at - hi), hi.max(2.0 * p.at - lo)];
        }
    }
    boxed.iter().map(|[lo, hi]| (hi - lo).powi(2)).sum::<f64>().sqrt()
}

/// The planes with their tolerance (1e-6 of the largest body) and a check
/// that each touches a body.
pub(super) fn placed(planes: Vec<Plane>, mesh: &Mesh) -> Result<Vec<Plane>, ModelError> {
    let size = mesh.bodies.iter().map(|b| b.size()).fold(0.0, f64::max);
    let planes: Vec<Plane> = planes.into_iter().map(|p| Plane { tolerance: 1e-6 * size, ..p }).collect();
    for (i, p) in planes.iter().enumerate() {
        if !(0..mesh.n_nodes()).any(|n| p.holds(mesh.coords(n))) {
            return Err(invalid(
                format!("symmetry[{i}].plane"),
                p.describe(),
                "a plane through nodes of a body (the model's side of it must touch the plane)",
            ));
        }
    }
    Ok(planes)
}

/// One constraint per plane and body it touches: the normal component zero
/// on the plane (named after the plane; `plane_body` with several bodies),
/// each with the index of its plane.
pub(super) fn constraints(planes: &[Plane], mesh: &Mesh) -> Vec<(usize, Constraint)> {
    let mut out = Vec::new();
    for (i, p) in planes.iter().enumerate() {
        let touched: Vec<usize> = (0..mesh.bodies.len())
            .filter(|&b| (0..mesh.bodies[b].n_nodes()).any(|n| p.holds(mesh.bodies[b].local_coords(n))))
            .collect();
        for &b in &touched {
            let body = &mesh.bodies[b];
            let mut conditions = [None; 3];
            conditions[p.axis] = Some(Condition::Equal(p.at));
            let selection = Selection { conditions, tolerance: p.tolerance, region: None, radial: None };
            let nodes = selection.nodes(body).into_iter().map(|n| n + body.node_offset).collect();
            let mut values = [None; 3];
            values[p.axis] = Some(0.0);
            let name = if touched.len() == 1 { p.name.clone() } else { format!("{}_{}", p.name, body.name) };
            out.push((i, Constraint { name, body: b, nodes, values, selection: Some(selection) }));
        }
    }
    out
}

/// The plane whose left-out side holds the whole selection (its condition
/// along the plane's normal lies there), if any: the item is the mirror
/// image of one in the model, and is left out.
pub(super) fn left_out<'a>(planes: &'a [Plane], s: &SelectionFile) -> Option<&'a Plane> {
    planes.iter().find(|p| match [&s.x, &s.y, &s.z][p.axis] {
        Some(ConditionFile::Value(v)) => p.removes(*v),
        Some(ConditionFile::Range([a, b])) => p.removes(*a) && p.removes(*b),
        None => false,
    })
}

/// The note for an item left out.
pub(super) fn note(key: String, name: &str, plane: &Plane) -> Warning {
    Warning {
        key,
        message: format!(
            "{name:?} lies wholly on the side of symmetry plane {:?} ({}) that the model leaves out: it is the \
             mirror image of an item kept, and is left out with it",
            plane.name,
            plane.describe()
        ),
    }
}

/// For each plane, whether any of the nodes lies on it.
pub(super) fn across(planes: &[Plane], mesh: &Mesh, nodes: impl Iterator<Item = usize> + Clone) -> Vec<bool> {
    planes.iter().map(|p| nodes.clone().any(|n| p.holds(mesh.coords(n)))).collect()
}

/// The model's [`Symmetry`]: which constraints (the first `user` of
/// `constraints`, not the planes' own, which follow), indenters and pair
/// contacts lie across each plane.
pub(super) fn resolve(
    planes: Vec<Plane>,
    mesh: &Mesh,
    (constraints, user): (&[Constraint], usize),
    indenters: &[Indenter],
    contacts: &[PairContact],
) -> Symmetry {
    let mut items: Vec<(String, Vec<bool>)> = Vec::new();
    for c in &constraints[..user] {
        items.push((c.name.clone(), across(&planes, mesh, c.nodes.iter().copied())));
    }
    for i in indenters {
        items.push((i.name.clone(), across(&planes, mesh, i.nodes.iter().map(|n| n.node))));
    }
    for c in contacts {
        let surface = c.surface.iter().flat_map(|s| s.slave_nodes.iter().copied());
        let slave = c.pairs.iter().map(|p| p.slave).chain(surface);
        items.push((c.name.clone(), across(&planes, mesh, slave)));
    }
    Symmetry { planes, across: items, constraints: (user..constraints.len()).collect() }
}

/// A load on a symmetric model: on nodes, it touches no plane
/// (`nodal_load`); on faces, it is its own mirror image (`faces_load`).
pub(super) fn check_load(
    key: &str,
    load: &Load,
    l: &LoadFile,
    planes: &[Plane],
    mesh: &Mesh,
) -> Result<(), ModelError> {
    nodal_load(key, load, l, planes, mesh)?;
    faces_load(key, load, l, planes, mesh)
}

/// A force per node or a total force on nodes of a plane is refused: which
/// share of it the part kept carries is not said (a traction or pressure
/// is integrated over the faces kept, which is that share).
fn nodal_load(key: &str, load: &Load, l: &LoadFile, planes: &[Plane], mesh: &Mesh) -> Result<(), ModelError> {
    let kind = if l.force_per_node.is_some() {
        "force_per_node"
    } else if l.total_force.is_some() {
        "total_force"
    } else {
        return Ok(());
    };
    match planes.iter().find(|p| load.nodal_forces.iter().any(|(n, _)| p.holds(mesh.coords(*n)))) {
        None => Ok(()),
        Some(p) => Err(invalid(
            format!("{key}.{kind}"),
            format!("a load on nodes of symmetry plane {:?} ({})", p.name, p.describe()),
            "a `traction` or `pressure` there (integrated over the faces kept, it is the kept part's share; a force \
             per node or a total force does not say which share the part kept carries)",
        )),
    }
}

/// A force-controlled indenter or an impactor touching a plane must cross
/// it as its own mirror image ([`check_indenter_shape`], which runs first),
/// and one crossing it must reach it: the tool and its images are one tool,
/// pushed by the full structure's force (an impactor: of the full
/// structure's mass), of which the part kept carries `1/2` per plane
/// crossed. Returns that number of planes (0 for a displacement-controlled
/// indenter, or one clear of every plane).
pub(super) fn check_indenter(key: &str, indenter: &Indenter, planes: &[Plane], mesh: &Mesh) -> Result<u32, ModelError> {
    if indenter.impactor.is_none() && indenter.force.is_none() {
        return Ok(0);
    }
    let (driven, by) = match indenter.impactor {
        Some(_) => ("an impactor", "mass"),
        None => ("a force-controlled indenter", "force"),
    };
    let mut shared = 0;
    let touching = across(planes, mesh, indenter.nodes.iter().map(|n| n.node));
    for (p, &touches) in planes.iter().zip(&touching) {
        let crosses = crossing(indenter, p).0;
        let (what, found, allowed) = match (touches, crosses) {
            (false, false) => continue,
            (true, true) => {
                shared += 1;
                continue;
            }
            (true, false) => (
                by,
                "touching",
                format!(
                    "{driven} that crosses the plane as its own mirror image (the part kept then carries half its \
                     {by} per plane), or one clear of the plane"
                ),
            ),
            (false, true) => (
                "surface",
                "crossing",
                format!(
                    "a surface that reaches the plane (the tool shares its {by} with its mirror image through the \
                     nodes on the plane), or a displacement-controlled indenter"
                ),
            ),
        };
        return Err(invalid(
            format!("{key}.{what}"),
            format!("{driven} {found} symmetry plane {:?} ({})", p.name, p.describe()),
            allowed,
        ));
    }
    Ok(shared)
}

/// Whether `indenter` crosses the plane `p` (a sphere or a cylinder lying
/// along the plane closer to it than its radius, a punch or a cylinder
/// across it whose extent along the normal spans it or is unbounded),
/// whether it is then its own mirror image (centred on the plane), and the
/// key that places it along the normal.
fn crossing(indenter: &Indenter, p: &Plane) -> (bool, bool, String) {
    let (a, c) = (p.axis, ["x", "y", "z"][p.axis]);
    let on = |v: f64| (v - p.at).abs() <= p.tolerance;
    let extent = |r: Option<[f64; 2]>, k: &str| match r {
        None => (true, true, k.to_string()),
        Some([lo, hi]) => (lo < p.at - p.tolerance && hi > p.at + p.tolerance, on(0.5 * (lo + hi)), k.to_string()),
    };
    let round = |center: [f64; 3], radius: f64| ((center[a] - p.at).abs() < radius, on(center[a]), "center".into());
    match &indenter.surface {
        RigidSurface::Flat { axis, .. } if *axis == a => (false, true, String::new()),
        RigidSurface::Flat { bounds, .. } => extent(bounds[a], c),
        RigidSurface::Cylinder { axis, length, .. } if *axis == a => extent(*length, "length"),
        RigidSurface::Cylinder { center, radius, .. } | RigidSurface::Sphere { center, radius } => {
            round(*center, *radius)
        }
    }
}

/// An indenter that crosses a plane ([`crossing`]) is one tool with its
/// mirror image: its shape must be its own mirror image (centred on the
/// plane) and its motion (displacement or force) have no component along
/// the plane's normal. A tool clear of the plane has a separate mirror
/// image, moving mirrored. No indenter's surface may lie in a plane.
pub(super) fn check_indenter_shape(
    key: &str,
    indenter: &Indenter,
    planes: &[Plane],
    mesh: &Mesh,
) -> Result<(), ModelError> {
    faces_off_planes(&format!("{key}.surface"), &mesh.bodies[indenter.body], &indenter.faces, planes)?;
    for p in planes {
        let (a, c) = (p.axis, ["x", "y", "z"][p.axis]);
        let (crosses, mirrored, k) = crossing(indenter, p);
        if !crosses {
            continue;
        }
        let plane = format!("symmetry plane {:?} ({})", p.name, p.describe());
        if !mirrored {
            return Err(invalid(
                format!("{key}.{k}"),
                format!("{} (the indenter crosses {plane})", indenter.surface),
                format!(
                    "a tool that is its own mirror image across the plane: its centre, or the middle of its extent \
                     along {c}, at {c} = {} (the part left out would hold its mirror image, overlapping it); model \
                     the full structure for a tool off the plane",
                    crate::numbers::short(p.at)
                ),
            ));
        }
        let (what, motion, unit) = match (&indenter.impactor, indenter.force) {
            (Some(imp), _) => ("velocity", imp.velocity, "m/s"),
            (None, Some(f)) => ("force", f, "N"),
            (None, None) => ("displacement", indenter.displacement, "m"),
        };
        // a round-off component is none (as `check_velocities` allows)
        if motion[a].abs() > 1e-12 * motion.iter().map(|v| v * v).sum::<f64>().sqrt() {
            return Err(invalid(
                format!("{key}.{what}"),
                format!("{motion:?} {unit} for an indenter crossing {plane}"),
                format!(
                    "{what}[{a}] = 0 (no {c} component): the indenter and its mirror image are one tool, which \
                     cannot move both ways along {c}; model the full structure"
                ),
            ));
        }
    }
    Ok(())
}

/// `analysis.initial_velocities`: a body touching a plane (cut by it, or
/// lying against it) is one body with its mirror image, which moves with
/// the mirrored velocity; a component along the plane's normal would make
/// the two halves fly apart (and the plane holds `u_n = 0`): refused.
pub(super) fn check_velocities(
    velocities: &[(usize, [f64; 3])],
    planes: &[Plane],
    mesh: &Mesh,
) -> Result<(), ModelError> {
    for (i, &(b, v)) in velocities.iter().enumerate() {
        let body = &mesh.bodies[b];
        let nodes = (0..body.n_nodes()).map(|n| n + body.node_offset);
        let speed = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        for p in planes.iter().filter(|p| nodes.clone().any(|n| p.holds(mesh.coords(n)))) {
            let a = p.axis;
            if v[a].abs() > 1e-12 * speed {
                let c = ["x", "y", "z"][a];
                return Err(invalid(
                    format!("analysis.initial_velocities[{i}].velocity"),
                    format!("{v:?} m/s for body {:?}", body.name),
                    format!(
                        "velocity[{a}] = 0 (no {c} component): body {:?} touches symmetry plane {:?} ({}), so in the \
                         full structure it is one body with its mirror image, which would move at −{} m/s along {c} \
                         while the plane holds u_{c} = 0; model the full structure for a motion across the plane",
                        body.name,
                        p.name,
                        p.describe(),
                        crate::numbers::short(v[a])
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// A traction or pressure on faces of `load` is mirror-symmetric about
/// every plane it touches: no face lies in a plane (it is inside the full
/// structure), a traction has no component along the normal of a plane
/// its faces touch (its mirror image would pull the other way), and a sine
/// profile along a plane's normal that spans the plane is centred on it.
fn faces_load(key: &str, load: &Load, l: &LoadFile, planes: &[Plane], mesh: &Mesh) -> Result<(), ModelError> {
    let faces = match &load.kind {
        crate::bc::LoadKind::Traction { faces, .. } | crate::bc::LoadKind::Pressure { faces, .. } => faces,
        crate::bc::LoadKind::PerNode { .. } => return Ok(()),
    };
    let body = &mesh.bodies[load.body];
    faces_off_planes(&format!("{key}.where"), body, faces, planes)?;
    for p in planes.iter().filter(|q| load.nodal_forces.iter().any(|(n, _)| q.holds(mesh.coords(*n)))) {
        let a = p.axis;
        let c = ["x", "y", "z"][a];
        // (a total force on nodes of a plane is refused by `nodal_load`)
        if let Some(t) = l.traction.map(<[f64; 3]>::from)
            && t[a] != 0.0
        {
            return Err(invalid(
                format!("{key}.traction"),
                format!("{t:?} on faces touching symmetry plane {:?} ({})", p.name, p.describe()),
                format!(
                    "no {c} component there: the load's mirror image across the plane acts with the opposite {c} \
                     component, so the full structure would not carry this load (and the plane's u_{c} = 0 takes the \
                     share at the plane); load faces off the plane, or model the full structure"
                ),
            ));
        }
        if let Some(pr) = &load.profile
            && pr.along == a
            && pr.from < p.at - p.tolerance
            && pr.to > p.at + p.tolerance
            && (pr.from + pr.to - 2.0 * p.at).abs() > p.tolerance
        {
            return Err(invalid(
                format!("{key}.profile"),
                format!("from = {}, to = {}", crate::numbers::short(pr.from), crate::numbers::short(pr.to)),
                format!(
                    "a profile symmetric about symmetry plane {:?} ({}): (from + to)/2 = {} (the part left out \
                     carries the mirror image of the part kept, not this profile), or model the full structure",
                    p.name,
                    p.describe(),
                    crate::numbers::short(p.at)
                ),
            ));
        }
    }
    Ok(())
}

/// No face lies in a plane: a face there is a cut through the full
/// structure, not a surface of it.
pub(super) fn faces_off_planes(
    key: &str,
    body: &crate::mesh::Body,
    faces: &[crate::bc::Face],
    planes: &[Plane],
) -> Result<(), ModelError> {
    for p in planes {
        let inside = faces.iter().any(|f| {
            let integral = crate::bc::integrate_face(body, f);
            integral.nodes.iter().all(|&n| p.holds(body.local_coords(n - body.node_offset)))
        });
        if inside {
            return Err(invalid(
                key,
                format!("faces of body {:?} lying in symmetry plane {:?} ({})", body.name, p.name, p.describe()),
                "faces off the plane: a face in a symmetry plane is a cut through the full structure (its two sides \
                 are joined there), not one of its surfaces",
            ));
        }
    }
    Ok(())
}
