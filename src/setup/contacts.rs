//! `[[contacts]]` between deformable bodies: each by its `method`,
//! node-to-node pairs here (the paper's method) and segment-to-segment in
//! `surface_contact`.

use super::overlap::overlap;
use super::preprocess::{body_index, surface_faces};
use super::surface_contact::surface_contact;
use super::{Warning, symmetry};
use crate::bc::symmetry::Plane;
use crate::contact::{self, ContactSurface, PairContact, SurfaceNodes};
use crate::input::schema::*;
use crate::input::validate::{finite_positive, friction, penalty, tolerance};
use crate::input::{ModelError, invalid};
use crate::materials::Material;
use crate::mesh::Mesh;

/// `[[contacts]]` between two bodies, with a warning for explicit pairs
/// whose nodes do not face each other.
pub(super) fn pair_contacts(
    file: &[ContactFile],
    mesh: &Mesh,
    materials: &[Material],
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<PairContact>, ModelError> {
    let mut contacts = Vec::new();
    for (i, c) in file.iter().enumerate() {
        let key = format!("contacts[{i}]");
        if let Some(p) = symmetry::left_out(planes, &c.slave.selection) {
            warnings.push(symmetry::note(key, &c.name, p));
            continue;
        }
        let bm = body_index(mesh, format!("{key}.master.body"), &c.master.body)?;
        let bs = body_index(mesh, format!("{key}.slave.body"), &c.slave.body)?;
        if bm == bs {
            return Err(invalid(
                format!("{key}.slave.body"),
                format!("{:?}", c.slave.body),
                "a body other than the master body",
            ));
        }
        // a surface lying in a symmetry plane is a cut, held by the plane's u_n = 0
        for (side, selection, b) in [("master", &c.master.selection, bm), ("slave", &c.slave.selection, bs)] {
            if !planes.is_empty() {
                let where_ = format!("{key}.{side}.where");
                let (faces, _) = surface_faces(&where_, selection, &mesh.bodies[b])?;
                symmetry::faces_off_planes(&where_, &mesh.bodies[b], &faces, planes)?;
            }
        }
        let contact = match &c.method {
            ContactMethod::NodeToNode { tolerance, pairs } => {
                let contact = pair_contact(&key, c, *tolerance, pairs.as_deref(), mesh, (bm, bs), materials)?;
                if pairs.is_some() {
                    offset_pairs(&key, &contact, mesh, warnings);
                }
                contact
            }
            ContactMethod::Surface { search_distance } => {
                surface_contact(&key, c, *search_distance, mesh, bm, bs, materials)?
            }
        };
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

/// `method = "node_to_node"`: slave nodes matched with master nodes within
/// `tolerance`, or the explicit `pairs` of points.
/// `(bm, bs)`: the master and slave bodies.
fn pair_contact(
    key: &str,
    c: &ContactFile,
    tolerance_key: Option<f64>,
    explicit: Option<&[Exact<Exact<f64, 3>, 2>]>,
    mesh: &Mesh,
    (bm, bs): (usize, usize),
    materials: &[Material],
) -> Result<PairContact, ModelError> {
    let (master_body, slave_body) = (&mesh.bodies[bm], &mesh.bodies[bs]);
    let (master_faces, mf) = surface_faces(&format!("{key}.master.where"), &c.master.selection, master_body)?;
    let (slave_faces, sf) = surface_faces(&format!("{key}.slave.where"), &c.slave.selection, slave_body)?;
    let (em, es) = (super::body_young(master_body, materials), super::body_young(slave_body, materials));
    let master = SurfaceNodes::from_faces(&mf, em);
    // the softer side sets the stiffness scale
    let slave = SurfaceNodes::from_faces(&sf, es.min(em));
    let pen = penalty(key, c.penalty, c.penalty_factor)?;
    let tol = match tolerance_key {
        Some(t) => finite_positive(&format!("{key}.tolerance"), t)?,
        None => 1e-6 * master_body.size().max(slave_body.size()),
    };
    let coords = |n: usize| mesh.coords(n);
    let mut unpaired = 0;
    let pairs = match explicit {
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
