//! Contacts: rigid indenters paired with the nodes of their surface, and
//! node pairs between deformable bodies, with their penalties.

use super::bounds;
use super::preprocess::{body_index, surface_faces};
use super::schema::*;
use super::validate::{axis_index, describe_selection, finite_positive, penalty, reject_unused};
use super::{ModelError, Warning, invalid};
use crate::contact::{self, ContactSurface, Indenter, PairContact, RigidSurface, SurfaceNodes};
use crate::materials::Material;
use crate::mesh::{Body, Mesh};

/// `[[indenters]]`, with a warning for one whose motion cannot reach its surface.
pub(super) fn indenters(
    file: &[IndenterFile],
    mesh: &Mesh,
    materials: &[Material],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<Indenter>, ModelError> {
    let mut indenters = Vec::new();
    for (i, d) in file.iter().enumerate() {
        let key = format!("indenters[{i}]");
        let b = body_index(mesh, format!("{key}.body"), &d.body)?;
        let ind = indenter(&key, d, b, &mesh.bodies[b], materials)?;
        // how far the indenter's own motion brings it towards each node
        let reach = |c: &contact::ContactNode| (0..3).map(|k| ind.displacement[k] * c.normal[k]).sum::<f64>() - c.gap0;
        if ind.force.is_none() && ind.nodes.iter().all(|c| reach(c) < 0.0) {
            warnings.push(Warning {
                key: format!("{key}.displacement"),
                message: format!(
                    "the indenter's motion {:?} m does not close its initial gap (at least {:.3e} m) to any node of \
                     the surface: it touches only if the body moves into it",
                    ind.displacement,
                    ind.nodes.iter().map(|c| c.gap0).fold(f64::INFINITY, f64::min)
                ),
            });
        }
        indenters.push(ind);
    }

    Ok(indenters)
}

/// `[[contacts]]` between two bodies, with a warning for explicit pairs
/// whose nodes do not face each other.
pub(super) fn pair_contacts(
    file: &[ContactFile],
    mesh: &Mesh,
    materials: &[Material],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<PairContact>, ModelError> {
    let mut contacts = Vec::new();
    for (i, c) in file.iter().enumerate() {
        let key = format!("contacts[{i}]");
        let bm = body_index(mesh, format!("{key}.master.body"), &c.master.body)?;
        let bs = body_index(mesh, format!("{key}.slave.body"), &c.slave.body)?;
        if bm == bs {
            return Err(invalid(
                format!("{key}.slave.body"),
                format!("{:?}", c.slave.body),
                "a body other than the master body",
            ));
        }
        let contact = pair_contact(&key, c, mesh, bm, bs, materials)?;
        if c.pairs.is_some() {
            offset_pairs(&key, &contact, mesh, warnings);
        }
        contacts.push(contact);
    }

    Ok(contacts)
}

/// Explicit `pairs` are taken as given; node-to-node contact then acts
/// along the master normal as if the two nodes faced each other. A pair
/// whose nodes lie apart *along* the surface by more than half the slave
/// node's spacing (the square root of its tributary area) does not: warned
/// about, naming the pair, the offset and the spacing.
fn offset_pairs(key: &str, contact: &PairContact, mesh: &Mesh, warnings: &mut Vec<Warning>) {
    for (k, p) in contact.pairs.iter().enumerate() {
        let (xs, xm) = (mesh.coords(p.slave), mesh.coords(p.master));
        let d: [f64; 3] = std::array::from_fn(|i| xs[i] - xm[i]);
        let along = (d.iter().map(|v| v * v).sum::<f64>() - p.gap0 * p.gap0).max(0.0).sqrt();
        let spacing = p.area.sqrt();
        if along > 0.5 * spacing {
            warnings.push(Warning {
                key: format!("{key}.pairs[{k}]"),
                message: format!(
                    "the slave node at {xs:?} and the master node at {xm:?} are {} m apart along the contact surface \
                     (normal gap {} m; node spacing about {} m): node-to-node contact presses them together as if \
                     they faced each other",
                    crate::numbers::limit(along),
                    crate::numbers::limit(p.gap0),
                    crate::numbers::limit(spacing)
                ),
            });
        }
    }
}

pub(super) fn indenter(
    key: &str,
    d: &IndenterFile,
    b: usize,
    body: &Body,
    materials: &[Material],
) -> Result<Indenter, ModelError> {
    let (face_list, faces) = surface_faces(&format!("{key}.surface"), &d.surface, body)?;
    let young = materials[body.material].young;
    let surface = SurfaceNodes::from_faces(&faces, young);
    let pen = penalty(key, d.penalty, d.penalty_factor)?;
    let tol = 1e-9 * body.size();
    let range = |name: &str, r: Option<[f64; 2]>| -> Result<Option<[f64; 2]>, ModelError> {
        match r {
            Some([a, b]) if a.is_finite() && b.is_finite() && a <= b && a.abs().max(b.abs()) <= bounds::MAX_COORD => {
                Ok(Some([a, b]))
            }
            Some(r) => Err(invalid(format!("{key}.{name}"), format!("{r:?}"), "[min, max] with min ≤ max")),
            None => Ok(None),
        }
    };
    let chosen = format!("shape = {:?}", d.shape);
    let flat_keys = [
        ("normal", d.normal.is_some()),
        ("position", d.position.is_some()),
        ("x", d.x.is_some()),
        ("y", d.y.is_some()),
        ("z", d.z.is_some()),
    ];
    let cyl_keys = [
        ("axis", d.axis.is_some()),
        ("center", d.center.is_some()),
        ("radius", d.radius.is_some()),
        ("length", d.length.is_some()),
    ];
    match d.shape.as_str() {
        "flat" => reject_unused(key, &chosen, &cyl_keys)?,
        "cylinder" => reject_unused(key, &chosen, &flat_keys)?,
        "sphere" => {
            reject_unused(key, &chosen, &flat_keys)?;
            reject_unused(key, &chosen, &[cyl_keys[0], cyl_keys[3]])?;
        }
        _ => {}
    }
    let updated = match d.method.as_deref() {
        None | Some("node_to_node") => false,
        Some("surface") => true,
        Some(other) => {
            return Err(invalid(
                format!("{key}.method"),
                format!("{other:?}"),
                "\"node_to_node\" (default: each node paired once with the closest point at the start, the paper's \
                 method) or \"surface\" (the exact closest point of the current configuration)",
            ));
        }
    };

    let shape = match d.shape.as_str() {
        "flat" => {
            let normal = d.normal.as_deref().unwrap_or("");
            let (sign, axis) = match normal {
                "+x" => (1.0, 0),
                "-x" => (-1.0, 0),
                "+y" => (1.0, 1),
                "-y" => (-1.0, 1),
                "+z" => (1.0, 2),
                "-z" => (-1.0, 2),
                _ => {
                    return Err(invalid(
                        format!("{key}.normal"),
                        format!("{normal:?}"),
                        "the direction the punch face looks towards the body: \"+x\", \"-x\", \"+y\", \"-y\", \"+z\" or \"-z\"",
                    ));
                }
            };
            let position = d.position.ok_or_else(|| {
                invalid(
                    format!("{key}.position"),
                    "(missing)",
                    "the coordinate of the punch face along its normal axis (m)",
                )
            })?;
            RigidSurface::Flat {
                axis,
                sign,
                position: bounds::coordinate(&format!("{key}.position"), position)?,
                bounds: [
                    range("x", d.x.map(Into::into))?,
                    range("y", d.y.map(Into::into))?,
                    range("z", d.z.map(Into::into))?,
                ],
            }
        }
        "cylinder" => {
            let axis_name = d.axis.as_deref().unwrap_or("");
            let axis = axis_index(axis_name).ok_or_else(|| {
                invalid(
                    format!("{key}.axis"),
                    format!("{axis_name:?}"),
                    "\"x\", \"y\" or \"z\" (direction of the cylinder axis)",
                )
            })?;
            let (center, radius) = round(key, d, body, "a point [x, y, z] on the cylinder axis")?;
            RigidSurface::Cylinder { axis, center, radius, length: range("length", d.length.map(Into::into))? }
        }
        "sphere" => {
            let (center, radius) = round(key, d, body, "the sphere's centre [x, y, z]")?;
            RigidSurface::Sphere { center, radius }
        }
        other => {
            return Err(invalid(format!("{key}.shape"), format!("{other:?}"), "\"flat\", \"cylinder\" or \"sphere\""));
        }
    };
    // pair each surface node facing the indenter with its closest point
    let nodes: Vec<contact::ContactNode> = surface
        .nodes
        .iter()
        .filter_map(|e| {
            let x0 = body.local_coords(e.0 - body.node_offset);
            shape.reference_gap(x0, tol).map(|(gap0, normal)| contact::ContactNode {
                node: e.0,
                area: e.1,
                penalty: SurfaceNodes::penalty(e, pen),
                gap0,
                normal,
            })
        })
        .collect();
    // a node starting inside the indenter means a wrongly placed or oriented indenter
    if let Some(c) = nodes.iter().find(|c| c.gap0 < -tol) {
        let which = match d.shape.as_str() {
            "flat" => format!("{key}.position / {key}.normal"),
            _ => format!("{key}.center / {key}.radius"),
        };
        return Err(invalid(
            which,
            format!("a surface node at {:?} starts {:.3e} m inside the indenter", model_coords(body, c.node), -c.gap0),
            "an indenter that touches or clears the surface at the start (normal pointing from the indenter to the body)",
        ));
    }
    if nodes.is_empty() {
        return Err(invalid(
            format!("{key}.surface"),
            describe_selection(&d.surface),
            "a surface with nodes facing the indenter (inside a punch's bounds or a cylinder's length)",
        ));
    }
    // The indenter must lie outside the body, facing its surface: at every
    // paired node the direction from the indenter to the node opposes the
    // surface's outward normal. Otherwise the body sits inside a punch, or a
    // roller is buried under the surface, and contact would never engage.
    let outward: std::collections::HashMap<usize, [f64; 3]> = surface.nodes.iter().map(|e| (e.0, e.3)).collect();
    for c in &nodes {
        let m = outward[&c.node];
        let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        let facing = (0..3).map(|k| c.normal[k] * m[k]).sum::<f64>() / len;
        if !(facing < -1e-6) {
            let (which, fix) = match d.shape.as_str() {
                "flat" => (
                    format!("{key}.normal"),
                    "the punch on the outer side of the surface, its normal pointing into the body (e.g. normal = \"-z\" for a punch above a top face)",
                ),
                "sphere" => (format!("{key}.center"), "the sphere's centre on the outer side of the selected surface"),
                _ => (format!("{key}.center"), "the cylinder's axis on the outer side of the selected surface"),
            };
            return Err(invalid(
                which,
                format!(
                    "an indenter on the inner side of the surface at {:?} (outward normal {:?})",
                    model_coords(body, c.node),
                    m.map(|v| (v / len * 1e6).round() / 1e6)
                ),
                fix,
            ));
        }
    }
    let (displacement, force) = match (d.displacement, d.force) {
        (Some(u), None) => {
            let u = bounds::vector(
                &format!("{key}.displacement"),
                u,
                body.size(),
                &format!("a rigid motion in m of at most the size of body {:?}", body.name),
            )?;
            (u, None)
        }
        (None, Some(f)) => {
            let young = materials[body.material].young;
            let f = bounds::vector(
                &format!("{key}.force"),
                f,
                young * body.size().powi(2),
                "a force in N of at most E × (body size)² (a stress of E over the whole body)",
            )?;
            // the force must push the body: along the normals of the nodes it may touch
            let n = nodes.first().map(|c| c.normal).unwrap_or_default();
            if !(f.iter().zip(&n).map(|(a, b)| a * b).sum::<f64>() > 0.0) {
                return Err(invalid(
                    format!("{key}.force"),
                    format!("{f:?}"),
                    format!(
                        "a non-zero force that pushes the body (towards it: along {n:?}); a pull has no contact to act through"
                    ),
                ));
            }
            ([0.0; 3], Some(f))
        }
        (Some(_), Some(_)) => {
            return Err(invalid(
                format!("{key}.force"),
                "(given with displacement)",
                "exactly one of displacement (displacement control) and force (force control)",
            ));
        }
        (None, None) => {
            return Err(invalid(
                format!("{key}.displacement"),
                "(missing)",
                "the indenter's rigid motion [x, y, z] in m, or force = [x, y, z] in N for force control",
            ));
        }
    };
    let penetration_tolerance = tolerance(key, d.penetration_tolerance, body.size())?;
    Ok(Indenter {
        name: d.name.clone(),
        body: b,
        surface: shape,
        displacement,
        force,
        nodes,
        penetration_tolerance,
        friction: friction(key, d.friction)?,
        faces: face_list,
        updated,
    })
}

/// `center` and `radius` of a cylinder or sphere (`center_is`: what the
/// point is, for the message when it is missing).
fn round(key: &str, d: &IndenterFile, body: &Body, center_is: &str) -> Result<([f64; 3], f64), ModelError> {
    let center = d.center.ok_or_else(|| invalid(format!("{key}.center"), "(missing)", center_is))?;
    let radius = d.radius.ok_or_else(|| invalid(format!("{key}.radius"), "(missing)", "the radius in m"))?;
    Ok((
        bounds::point(&format!("{key}.center"), center)?,
        bounds::within(
            &format!("{key}.radius"),
            radius,
            bounds::MIN_RELATIVE_SIZE * body.size(),
            bounds::MAX_COORD,
            "a radius in m, not vanishingly small against the body",
        )?,
    ))
}

pub(super) fn model_coords(body: &Body, node: usize) -> [f64; 3] {
    body.local_coords(node - body.node_offset)
}

pub(super) fn pair_contact(
    key: &str,
    c: &ContactFile,
    mesh: &Mesh,
    bm: usize,
    bs: usize,
    materials: &[Material],
) -> Result<PairContact, ModelError> {
    match c.method.as_deref() {
        None | Some("node_to_node") => {}
        Some("surface") => return super::surface_contact::surface_contact(key, c, mesh, bm, bs, materials),
        Some(other) => {
            return Err(invalid(
                format!("{key}.method"),
                format!("{other:?}"),
                "\"node_to_node\" (default: the paper's matched node pairs) or \"surface\" (segment-to-segment, non-matching meshes)",
            ));
        }
    }
    if c.search_distance.is_some() {
        return Err(invalid(
            format!("{key}.search_distance"),
            "(given)",
            "no `search_distance` key with method = \"node_to_node\" (it belongs to method = \"surface\")",
        ));
    }
    let (master_body, slave_body) = (&mesh.bodies[bm], &mesh.bodies[bs]);
    let (master_faces, mf) = surface_faces(&format!("{key}.master.where"), &c.master.selection, master_body)?;
    let (slave_faces, sf) = surface_faces(&format!("{key}.slave.where"), &c.slave.selection, slave_body)?;
    let (em, es) = (materials[master_body.material].young, materials[slave_body.material].young);
    let master = SurfaceNodes::from_faces(&mf, em);
    // the softer side sets the stiffness scale
    let slave = SurfaceNodes::from_faces(&sf, es.min(em));
    let pen = penalty(key, c.penalty, c.penalty_factor)?;
    let tol = match c.tolerance {
        Some(t) => finite_positive(&format!("{key}.tolerance"), t)?,
        None => 1e-6 * master_body.size().max(slave_body.size()),
    };
    let coords = |n: usize| mesh.coords(n);
    let mut unpaired = 0;
    let pairs = match &c.pairs {
        None => {
            let (pairs, unmatched) =
                contact::match_pairs(&slave, &master, coords, |e| SurfaceNodes::penalty(e, pen), tol);
            unpaired = unmatched.len();
            pairs
        }
        Some(list) => {
            let mut pairs = Vec::new();
            for (k, Exact([ps, pm])) in list.iter().enumerate() {
                let (ps, pm) = (&ps.0, &pm.0);
                let find = |set: &SurfaceNodes, p: [f64; 3], side: &str| {
                    set.nodes
                        .iter()
                        .find(|e| {
                            let x = mesh.coords(e.0);
                            (0..3).all(|d| (x[d] - p[d]).abs() <= tol)
                        })
                        .copied()
                        .ok_or_else(|| {
                            invalid(
                                format!("{key}.pairs[{k}]"),
                                format!("{p:?}"),
                                format!("a node of the {side} surface at this point (tolerance {tol:e} m)"),
                            )
                        })
                };
                let s = find(&slave, *ps, "slave")?;
                let m = find(&master, *pm, "master")?;
                let one = SurfaceNodes { nodes: vec![m] };
                let (mut p, _) = contact::match_pairs(
                    &SurfaceNodes { nodes: vec![s] },
                    &one,
                    coords,
                    |e| SurfaceNodes::penalty(e, pen),
                    f64::INFINITY,
                );
                pairs.append(&mut p);
            }
            pairs
        }
    };
    if pairs.is_empty() {
        return Err(invalid(
            key,
            "no node pair",
            "slave and master surfaces whose nodes face each other along the master normal (check the `where` selections or the matching tolerance)",
        ));
    }
    let penetration_tolerance = tolerance(key, c.penetration_tolerance, mesh.bodies[bs].size())?;
    let gaps: Vec<(usize, f64)> = pairs.iter().map(|p| (p.slave, p.gap0)).collect();
    let initial_overlap = overlap(key, c, mesh, bm, bs, &gaps)?;
    Ok(PairContact {
        name: c.name.clone(),
        pairs,
        penetration_tolerance,
        friction: friction(key, c.friction)?,
        unpaired,
        master: ContactSurface { body: bm, faces: master_faces },
        slave: ContactSurface { body: bs, faces: slave_faces },
        surface: None,
        initial_overlap,
    })
}

/// Deformable bodies that start inside each other: `gaps` holds each
/// contact point's slave node and initial gap (m, negative inside). An
/// overlap deeper than 1e-6 of the bodies' size is refused, naming both
/// bodies, the depth and where, unless the contact asks for an interference
/// fit (`interference = true`); then each point's overlap is returned (for
/// [`PairContact::overlap_relief`]), else an empty list. (Penalty contact
/// would otherwise push the bodies apart with the force of the whole
/// overlap at the first evaluation and report it as a contact force: the
/// overlapping cantilevers of issue 24 converged silently to 14 times the
/// contact force, with the root reaction's sign reversed.)
pub(super) fn overlap(
    key: &str,
    c: &ContactFile,
    mesh: &Mesh,
    bm: usize,
    bs: usize,
    gaps: &[(usize, f64)],
) -> Result<Vec<f64>, ModelError> {
    let (master, slave) = (&mesh.bodies[bm], &mesh.bodies[bs]);
    let tol = 1e-6 * master.size().max(slave.size());
    let inside = gaps.iter().filter(|g| g.1 < -tol).count();
    if c.interference == Some(true) {
        return Ok(gaps.iter().map(|g| (-g.1).max(0.0)).collect());
    }
    let Some(&(node, gap)) = gaps.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else { return Ok(Vec::new()) };
    if inside == 0 {
        return Ok(Vec::new());
    }
    Err(invalid(
        format!("{key}.slave.where"),
        format!(
            "body {:?} starting {} m inside body {:?} at {:?} (the deepest of {inside} overlapping slave nodes)",
            slave.name,
            crate::numbers::limit(-gap),
            master.name,
            model_coords(slave, node).map(|v| (v * 1e9).round() / 1e9),
        ),
        "bodies that touch or stand apart at the start (move one, or check the `where` selections); a deliberate \
         interference (shrink or press) fit needs `interference = true` on this contact: its overlap is then \
         pressed out over the first load step",
    ))
}

/// `penetration_tolerance` (augmented Lagrangian): positive, at most a
/// thousandth of the body's size.
pub(super) fn tolerance(key: &str, t: Option<f64>, size: f64) -> Result<Option<f64>, ModelError> {
    t.map(|t| {
        bounds::within(
            &format!("{key}.penetration_tolerance"),
            t,
            f64::MIN_POSITIVE,
            1e-3 * size,
            "the largest penetration in m that the augmented Lagrangian accepts, positive and at most 1e-3 of the body's size",
        )
    })
    .transpose()
}

/// `friction`: Coulomb's coefficient μ in [0, 10]; the tangential penalty
/// equals the normal one (elastic slip of the order of the penetration).
pub(super) fn friction(key: &str, mu: Option<f64>) -> Result<Option<contact::Friction>, ModelError> {
    mu.map(|m| {
        bounds::within(&format!("{key}.friction"), m, 0.0, 10.0, "Coulomb's coefficient of friction μ")
            .map(|coefficient| contact::Friction { coefficient, penalty_ratio: 1.0 })
    })
    .transpose()
}
