//! Preprocessing: what needs the meshes — node selections, constraints,
//! face integrals of loads, probe and line locations. Runs once, after the
//! bodies are built; the analysis consumes its results.

use super::constraints::{Conflict, ConstraintHandler};
use super::{Line, Probe, Warning, symmetry};
use crate::bc::symmetry::Plane;
use crate::bc::{self, Condition, Constraint, Load, LoadKind, Selection};
use crate::input::bounds;
use crate::input::schema::*;
use crate::input::validate::{MAX_COUNT, describe_selection};
use crate::input::{ModelError, invalid};
use crate::mesh::{Body, Mesh};
use crate::values::locate_in_model;

/// Index of the body named `name`, or an error listing the bodies.
pub(super) fn body_index(mesh: &Mesh, key: String, name: &str) -> Result<usize, ModelError> {
    mesh.body_index(name).ok_or_else(|| {
        let names: Vec<&str> = mesh.bodies.iter().map(|b| b.name.as_str()).collect();
        invalid(key, format!("{name:?}"), format!("one of the bodies {names:?}"))
    })
}

/// The coordinates of global node `node` of `body`.
pub(super) fn model_coords(body: &Body, node: usize) -> [f64; 3] {
    body.local_coords(node - body.node_offset)
}

pub(super) fn optional_body(mesh: &Mesh, key: String, name: &Option<String>) -> Result<Option<usize>, ModelError> {
    name.as_ref().map(|n| body_index(mesh, key, n)).transpose()
}

/// `[[constraints]]`: node sets and their values; overlapping sets must agree.
/// A constraint whose selection holds every node of its body although its
/// `where` asks for a part of it (a `tolerance` as large as the body, or
/// ranges around all of it), and a body every node of which is fixed in all
/// three directions, are warned about: such a body cannot deform, the
/// analysis runs and shows nothing (the probe warning needs some motion).
/// The symmetry planes' constraints follow the file's (whose number is
/// returned beside them); a constraint wholly on a plane's left-out side
/// is left out with a note. The constraint handler of them all is returned
/// with them, without couplings (`ConstraintHandler::couple` adds those).
pub(super) fn constraints(
    file: &[ConstraintFile],
    mesh: &Mesh,
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<(Vec<Constraint>, usize, ConstraintHandler), ModelError> {
    let mut constraints = Vec::new();
    // bodies already warned about a selection holding all their nodes
    let mut whole = vec![false; mesh.bodies.len()];
    for (i, c) in file.iter().enumerate() {
        let key = format!("constraints[{i}]");
        if let Some(p) = symmetry::left_out(planes, &c.selection) {
            warnings.push(symmetry::note(key, &c.name, p));
            continue;
        }
        let b = body_index(mesh, format!("{key}.body"), &c.body)?;
        let body = &mesh.bodies[b];
        let sel = selection(&format!("{key}.where"), &c.selection, body)?;
        let nodes: Vec<usize> = sel.nodes(body).into_iter().map(|n| n + body.node_offset).collect();
        if nodes.is_empty() {
            return Err(invalid(
                format!("{key}.where"),
                describe_selection(&c.selection),
                format!("a selection that contains nodes of body {:?}", body.name),
            ));
        }
        let mut values = [None; 3];
        for axis in c.fix.iter().flatten() {
            values[axis.index()] = Some(0.0);
        }
        if let Some(d) = &c.displacement {
            for (axis, v) in [d.x, d.y, d.z].into_iter().enumerate() {
                if let Some(v) = v {
                    let k = format!("{key}.displacement.{}", ["x", "y", "z"][axis]);
                    if values[axis].is_some() {
                        return Err(invalid(k, v, "a component not also listed in `fix`"));
                    }
                    let why = format!("a displacement in m of at most the size of body {:?}", body.name);
                    values[axis] = Some(bounds::within(&k, v, -body.size(), body.size(), &why)?);
                }
            }
        }
        if values.iter().all(Option::is_none) {
            return Err(invalid(
                key,
                "no `fix` or `displacement`",
                "at least one constrained component (fix = [\"x\", …] or displacement = {z = …})",
            ));
        }
        let s = &c.selection;
        let asks_for_part = s.x.is_some() || s.y.is_some() || s.z.is_some() || s.region.is_some();
        if asks_for_part && nodes.len() == body.n_nodes() {
            whole[b] = true;
            let (k, message) = match s.tolerance {
                Some(t) => (
                    format!("{key}.where.tolerance"),
                    format!(
                        "tolerance = {} m selects every node of body {:?} ({} nodes), not only those at where = {}: \
                         the constraint holds the whole body; give a tolerance well below the element size (the \
                         default is 1e-6 of the body's size)",
                        bounds::number(t),
                        body.name,
                        nodes.len(),
                        describe_selection(s)
                    ),
                ),
                None => (
                    format!("{key}.where"),
                    format!(
                        "where = {} selects every node of body {:?} ({} nodes): the constraint holds the whole body; \
                         give coordinates or a region that select only the supports",
                        describe_selection(s),
                        body.name,
                        nodes.len()
                    ),
                ),
            };
            warnings.push(Warning { key: k, message });
        }
        constraints.push(Constraint { name: c.name.clone(), body: b, nodes, values, selection: Some(sel) });
    }
    let user = constraints.len();
    let own = symmetry::constraints(planes, mesh);
    let owners: Vec<usize> = own.iter().map(|(p, _)| *p).collect();
    constraints.extend(own.into_iter().map(|(_, c)| c));
    let handler = ConstraintHandler::checked(mesh.n_dofs(), &constraints).map_err(|conflict| {
        disagreement(&constraints, mesh, conflict, |i| {
            let k = i.checked_sub(user).map(|k| (owners[k], &planes[owners[k]]));
            k.map_or_else(|| Owner::File(format!("constraints[{i}]")), |(k, p)| Owner::Plane(k, p))
        })
    })?;
    warn_fully_fixed(&constraints, mesh, &handler, &whole, warnings);
    Ok((constraints, user, handler))
}

/// Warns about a body fixed in x, y and z at every node (by one or several
/// constraints; not again for a body already warned about in `whole`). The
/// warning's key is the body's last constraint in the file's order.
fn warn_fully_fixed(
    constraints: &[Constraint],
    mesh: &Mesh,
    handler: &ConstraintHandler,
    whole: &[bool],
    warnings: &mut Vec<Warning>,
) {
    for (b, body) in mesh.bodies.iter().enumerate() {
        let last = constraints.iter().rposition(|c| c.body == b);
        if let Some(i) = last
            && !whole[b]
            && (body.node_offset..body.node_offset + body.n_nodes()).all(|n| handler.holds_node(n))
        {
            warnings.push(Warning {
                key: format!("constraints[{i}]"),
                message: format!(
                    "every node of body {:?} is fixed or prescribed in x, y and z (by this and earlier constraints): \
                     the body cannot deform and shows no stress; constrain only the supports",
                    body.name
                ),
            });
        }
    }
}

/// Who prescribes a constraint: the file's `constraints[i]`, or symmetry
/// plane `k` (`symmetry[k]`).
enum Owner<'a> {
    File(String),
    Plane(usize, &'a Plane),
}

/// The error of two constraints prescribing different values to one DOF
/// (the handler's [`Conflict`]: the later constraint against the DOF's
/// owner). A constraint is named by its key and name (`owner` gives the
/// key); a conflict with a symmetry plane's `u_n = 0` names the file's
/// constraint and the plane.
fn disagreement<'a>(
    constraints: &[Constraint],
    mesh: &Mesh,
    conflict: Conflict,
    owner: impl Fn(usize) -> Owner<'a>,
) -> ModelError {
    let (i, v) = (conflict.given.constraint, conflict.given.value);
    let (j, w) = (conflict.owner.constraint, conflict.owner.value);
    let at = mesh.coords(conflict.dof / 3);
    let c = ["x", "y", "z"][conflict.dof % 3];
    match (owner(i), owner(j)) {
        (Owner::Plane(p, plane), Owner::File(key)) | (Owner::File(key), Owner::Plane(p, plane)) => {
            let (file, value) = if matches!(owner(i), Owner::File(_)) { (i, v) } else { (j, w) };
            invalid(
                format!("{key}.displacement.{c}"),
                format!("{value} at a node of symmetry plane {:?} ({}), e.g. at {at:?}", plane.name, plane.describe()),
                format!(
                    "0 on the plane (symmetry[{p}] {:?} holds u_{c} = 0 there; constraint {:?}); prescribe the normal \
                     displacement off the plane, or model the full structure",
                    plane.name, constraints[file].name
                ),
            )
        }
        (Owner::File(key), Owner::File(earlier)) => invalid(
            key,
            format!("u_{c} = {v} at {at:?} (constraint {:?})", constraints[i].name),
            format!(
                "the value {w} that {earlier} (constraint {:?}) prescribes at the same node (overlapping sets must \
                 agree)",
                constraints[j].name
            ),
        ),
        (Owner::Plane(p, plane), Owner::Plane(..)) => invalid(
            format!("symmetry[{p}].plane"),
            plane.describe(),
            format!("a plane whose u_{c} = 0 no other plane contradicts (at {at:?})"),
        ),
    }
}

/// `[[loads]]`: nodal forces at load factor 1.
pub(super) fn loads(
    file: &[LoadFile],
    mesh: &Mesh,
    materials: &[crate::materials::Material],
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<Load>, ModelError> {
    let mut loads = Vec::new();
    for (i, l) in file.iter().enumerate() {
        let key = format!("loads[{i}]");
        if let Some(p) = symmetry::left_out(planes, &l.selection) {
            warnings.push(symmetry::note(key, &l.name, p));
            continue;
        }
        let b = body_index(mesh, format!("{key}.body"), &l.body)?;
        let young = super::body_young(&mesh.bodies[b], materials);
        let load = load(&key, l, b, &mesh.bodies[b], young)?;
        symmetry::check_load(&key, &load, l, planes, mesh)?;
        loads.push(load);
    }

    Ok(loads)
}

/// Warnings for loads that cannot act: every nodal force zero (a zero
/// `total_force` or pressure), or every non-zero component on a DOF the
/// constraints hold (a load on a clamped face, carried by the reaction
/// alone). `held(dof)` tells a held DOF (`3 node + component`).
pub(super) fn idle_loads(loads: &[Load], held: impl Fn(usize) -> bool, warnings: &mut Vec<Warning>) {
    for (i, load) in loads.iter().enumerate() {
        let acting: Vec<(usize, usize)> = load
            .nodal_forces
            .iter()
            .flat_map(|&(n, f)| (0..3).filter(move |&c| f[c] != 0.0).map(move |c| (n, c)))
            .collect();
        let message = if acting.is_empty() {
            format!("every nodal force of load {:?} is zero: it loads nothing", load.name)
        } else if acting.iter().all(|&(n, c)| held(3 * n + c)) {
            format!(
                "load {:?} acts only on components the constraints hold: the reactions carry it and nothing moves \
                 under it; load a face that is free to move",
                load.name
            )
        } else {
            continue;
        };
        warnings.push(Warning { key: format!("loads[{i}]"), message });
    }
}

/// `[[probes]]`, located once.
/// A probe in the part a symmetry plane leaves out is located at its
/// image (`bc::symmetry::image`) and its fields reflected back.
pub(super) fn probes(file: &[ProbeFile], mesh: &Mesh, planes: &[Plane]) -> Result<Vec<Probe>, ModelError> {
    let mut probes = Vec::new();
    for (i, p) in file.iter().enumerate() {
        let key = format!("probes[{i}]");
        let point = bounds::point(&format!("{key}.point"), p.point)?;
        let body = optional_body(mesh, format!("{key}.body"), &p.body)?;
        let locations = locate_in_model(mesh, body, crate::bc::symmetry::image(planes, point).0);
        if locations.is_empty() {
            return Err(invalid(
                format!("{key}.point"),
                format!("{point:?}"),
                "a point inside a body (or inside the named body)",
            ));
        }
        probes.push(Probe { name: p.name.clone(), point, body, locations });
    }
    Ok(probes)
}

/// `[[lines]]`; a line outside every body is an error, partly outside a warning.
pub(super) fn lines(
    file: &[LineFile],
    mesh: &Mesh,
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<Line>, ModelError> {
    let mut lines = Vec::new();
    for (i, l) in file.iter().enumerate() {
        let key = format!("lines[{i}]");
        let points = l.points.unwrap_or(crate::input::defaults::LINE_POINTS);
        if !(2..=MAX_COUNT).contains(&points) {
            return Err(invalid(format!("{key}.points"), points, format!("an integer from 2 to {MAX_COUNT}")));
        }
        let plot = l.plot.iter().flatten().map(|q| q.0).collect();
        let line = Line {
            name: l.name.clone(),
            from: bounds::point(&format!("{key}.from"), l.from)?,
            to: bounds::point(&format!("{key}.to"), l.to)?,
            points,
            body: optional_body(mesh, format!("{key}.body"), &l.body)?,
            plot,
        };
        // a line of zero length samples one point `points` times
        if line.from == line.to {
            return Err(invalid(format!("{key}.to"), format!("{:?}", line.to), "a point other than `from`"));
        }
        // a line outside every body would give an empty CSV and plot
        let checked = points.min(1001);
        let outside = (0..checked)
            .filter(|&k| {
                let t = k as f64 / (checked - 1) as f64;
                let p = [0, 1, 2].map(|d| line.from[d] + t * (line.to[d] - line.from[d]));
                locate_in_model(mesh, line.body, crate::bc::symmetry::image(planes, p).0).is_empty()
            })
            .count();
        if outside == checked {
            return Err(invalid(
                key,
                format!("from {:?} to {:?}", line.from, line.to),
                "a line that passes through a body (or through the named body)",
            ));
        }
        if outside > 0 {
            warnings.push(Warning {
                key: key.clone(),
                message: format!(
                    "about {:.0} % of the line lies outside every body; those samples are left out of its CSV and plots",
                    100.0 * outside as f64 / checked as f64
                ),
            });
        }
        lines.push(line);
    }
    Ok(lines)
}

pub(super) fn selection(key: &str, s: &SelectionFile, body: &Body) -> Result<Selection, ModelError> {
    let tol = match s.tolerance {
        Some(t) => bounds::within(
            &format!("{key}.tolerance"),
            t,
            f64::MIN_POSITIVE,
            body.size(),
            "a positive distance in m, at most the body's size",
        )?,
        None => 1e-6 * body.size(),
    };
    let cond = |name: &str, c: &Option<ConditionFile>| -> Result<Option<Condition>, ModelError> {
        match c {
            None => Ok(None),
            Some(ConditionFile::Value(v)) => {
                Ok(Some(Condition::Equal(bounds::coordinate(&format!("{key}.{name}"), *v)?)))
            }
            Some(ConditionFile::Range([a, b])) => {
                if !(a.is_finite() && b.is_finite() && a <= b && a.abs().max(b.abs()) <= bounds::MAX_COORD) {
                    return Err(invalid(format!("{key}.{name}"), format!("[{a}, {b}]"), "[min, max] with min ≤ max"));
                }
                Ok(Some(Condition::Range(*a, *b)))
            }
        }
    };
    let region = match &s.region {
        None => None,
        Some(name) => {
            let r = body.section.regions.iter().find(|r| &r.name == name).ok_or_else(|| {
                let names: Vec<&str> = body.section.regions.iter().map(|r| r.name.as_str()).collect();
                let allowed = if names.is_empty() {
                    format!("no `region` key: the section of body {:?} has no named regions", body.name)
                } else {
                    format!("one of the regions of body {:?}: {names:?}", body.name)
                };
                invalid(format!("{key}.region"), format!("{name:?}"), allowed)
            })?;
            Some(bc::RegionFilter {
                name: name.clone(),
                section: std::sync::Arc::new(body.section.clone()),
                elements: r.elements.clone(),
            })
        }
    };
    let radial = match (&s.radius, s.center) {
        (None, None) => None,
        (None, Some(_)) => {
            return Err(invalid(
                format!("{key}.center"),
                "(given without radius)",
                "`center` only with `radius` (the axis the distance is measured from)",
            ));
        }
        (Some(r), center) => {
            let center = match center {
                Some(Exact(c)) => {
                    let name = format!("{key}.center");
                    [bounds::coordinate(&name, c[0])?, bounds::coordinate(&name, c[1])?]
                }
                None => crate::input::defaults::ORIGIN,
            };
            let c = cond("radius", &Some(*r))?.filter(|c| match *c {
                Condition::Equal(v) => v >= 0.0,
                Condition::Range(a, _) => a >= 0.0,
            });
            let c = c.ok_or_else(|| {
                invalid(
                    format!("{key}.radius"),
                    describe_selection(s),
                    "a distance ≥ 0 in m from the axis parallel to y through `center` (a number or [min, max])",
                )
            })?;
            Some((c, center))
        }
    };
    Ok(Selection { conditions: [cond("x", &s.x)?, cond("y", &s.y)?, cond("z", &s.z)?], tolerance: tol, region, radial })
}

/// The selected boundary faces of `body` and their integrals.
pub(super) fn surface_faces(
    key: &str,
    s: &SelectionFile,
    body: &Body,
) -> Result<(Vec<bc::Face>, Vec<bc::FaceIntegral>), ModelError> {
    let sel = selection(key, s, body)?;
    let faces = bc::selected_faces(body, &sel);
    if faces.is_empty() {
        return Err(invalid(
            key,
            describe_selection(s),
            format!("a selection containing whole boundary faces of body {:?}", body.name),
        ));
    }
    let integrals = faces.iter().map(|f| bc::integrate_face(body, f)).collect();
    Ok((faces, integrals))
}

pub(super) fn load(key: &str, l: &LoadFile, b: usize, body: &Body, young: f64) -> Result<Load, ModelError> {
    // a stress of E is a strain of order one: far outside small-strain theory
    let stress_why = format!("at most Young's modulus of body {:?} ({young:e} Pa) as a stress", body.name);
    let given = [l.force_per_node.is_some(), l.total_force.is_some(), l.traction.is_some(), l.pressure.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(invalid(key, "load kind", "exactly one of force_per_node, total_force, traction, pressure"));
    }
    let profile = l.profile.as_ref().map(|p| load_profile(key, l, p, body)).transpose()?;
    let mut forces: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
    let kind;
    if let Some(f) = l.force_per_node {
        let f = bounds::vector(&format!("{key}.force_per_node"), f, young * body.size().powi(2), &stress_why)?;
        let sel = selection(&format!("{key}.where"), &l.selection, body)?;
        let nodes = sel.nodes(body);
        if nodes.is_empty() {
            return Err(invalid(
                format!("{key}.where"),
                describe_selection(&l.selection),
                format!("a selection that contains nodes of body {:?}", body.name),
            ));
        }
        for n in nodes {
            forces.insert(n + body.node_offset, f);
        }
        kind = LoadKind::PerNode { selection: sel, force: f };
    } else {
        let (face_list, mut faces) = surface_faces(&format!("{key}.where"), &l.selection, body)?;
        let area: f64 = faces.iter().map(|f| f.area).sum();
        if let Some(p) = profile {
            profile_span(key, &p, &faces, body)?;
            // ∫ N_a f dA with the uniform traction's normal and area kept
            for (fi, face) in faces.iter_mut().zip(&face_list) {
                let weighted = bc::integrate_face_with(body, face, |x| p.factor(x));
                (fi.nodes, fi.weights) = (weighted.nodes, weighted.weights);
            }
        }
        let traction = |f: &bc::FaceIntegral| -> Result<[f64; 3], ModelError> {
            Ok(if let Some(t) = l.traction {
                bounds::vector(&format!("{key}.traction"), t, young, &stress_why)?
            } else if let Some(p) = l.pressure {
                let p = bounds::within(&format!("{key}.pressure"), p, -young, young, &stress_why)?;
                f.normal.map(|n| -p * n)
            } else {
                let total = l.total_force.map_or([0.0; 3], Into::into);
                bounds::vector(
                    &format!("{key}.total_force"),
                    total,
                    young * area,
                    &format!("{stress_why} over the loaded area {area:e} m²"),
                )?
                .map(|v| v / area)
            })
        };
        for f in &faces {
            let t = traction(f)?;
            for (&n, &w) in f.nodes.iter().zip(&f.weights) {
                let e = forces.entry(n).or_insert([0.0; 3]);
                for k in 0..3 {
                    e[k] += w * t[k];
                }
            }
        }
        kind = match (l.pressure, l.traction) {
            (Some(p), _) => LoadKind::Pressure { faces: face_list, pressure: p },
            (None, Some(t)) => LoadKind::Traction { faces: face_list, traction: t.into() },
            (None, None) => {
                let total: [f64; 3] = l.total_force.map_or([0.0; 3], Into::into);
                LoadKind::Traction { faces: face_list, traction: total.map(|v| v / area) }
            }
        };
    }
    Ok(Load { name: l.name.clone(), nodal_forces: forces.into_iter().collect(), body: b, kind, profile })
}

/// `loads.profile` against the loaded faces: they must extend along its
/// axis (else the half sine is one constant factor) and lie within
/// `[from, to]` (outside it the sine turns negative and reverses the load).
fn profile_span(key: &str, p: &bc::Profile, faces: &[bc::FaceIntegral], body: &Body) -> Result<(), ModelError> {
    let axis = ["x", "y", "z"][p.along];
    let (lo, hi) = faces
        .iter()
        .flat_map(|f| &f.nodes)
        .map(|&n| body.local_coords(n - body.node_offset)[p.along])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c), hi.max(c)));
    let tol = 1e-6 * body.size();
    let short = crate::numbers::short;
    if hi - lo <= tol {
        return Err(invalid(
            format!("{key}.profile.along"),
            format!("{axis:?}"),
            format!(
                "an axis the loaded faces extend along: they all lie at {axis} = {} m, where the sine is one factor",
                short(lo)
            ),
        ));
    }
    let reverses = format!(
        "the loaded faces span {axis} from {} to {} m; the half sine turns negative outside [from, to] and would \
         reverse the load there",
        short(lo),
        short(hi)
    );
    if lo < p.from - tol {
        return Err(invalid(format!("{key}.profile.from"), p.from, format!("at most {} m: {reverses}", short(lo))));
    }
    if hi > p.to + tol {
        return Err(invalid(format!("{key}.profile.to"), p.to, format!("at least {} m: {reverses}", short(hi))));
    }
    Ok(())
}

/// `loads.profile`: only on a traction or a pressure, over an interval of
/// positive length within the body's extent.
fn load_profile(key: &str, l: &LoadFile, p: &LoadProfileFile, body: &Body) -> Result<bc::Profile, ModelError> {
    let pk = format!("{key}.profile");
    if l.traction.is_none() && l.pressure.is_none() {
        return Err(invalid(
            &pk,
            "given",
            "a profile only with traction or pressure (a total_force or force_per_node is not distributed)",
        ));
    }
    let ProfileShape::Sine = p.shape;
    let size = body.size();
    for (name, v) in [("from", p.from), ("to", p.to)] {
        bounds::within(&format!("{pk}.{name}"), v, -bounds::MAX_COORD, bounds::MAX_COORD, "a coordinate in m")?;
    }
    if !(p.to - p.from > 1e-9 * size) {
        return Err(invalid(format!("{pk}.to"), p.to, format!("a coordinate above from = {}", p.from)));
    }
    Ok(bc::Profile { along: p.along.index(), from: p.from, to: p.to })
}
