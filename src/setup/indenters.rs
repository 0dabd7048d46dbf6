//! `[[indenters]]`: rigid flat punches, cylinders and spheres paired with the
//! nodes of the body surface they face, with their penalties and motion
//! (displacement or force control).

use super::preprocess::{body_index, model_coords, surface_faces};
use super::{Warning, symmetry};
use crate::bc::symmetry::Plane;
use crate::contact::{self, Indenter, RigidSurface, SurfaceNodes};
use crate::input::bounds;
use crate::input::schema::*;
use crate::input::validate::{describe_selection, friction, penalty, tolerance};
use crate::input::{ModelError, invalid, ranges};
use crate::materials::Material;
use crate::mesh::{Body, Mesh};
use crate::numbers::limit;

/// `[[indenters]]`, with a warning for one whose motion cannot reach its
/// surface (not in a transient analysis, where bodies may fly into it).
pub(super) fn indenters(
    file: &[IndenterFile],
    mesh: &Mesh,
    materials: &[Material],
    transient: bool,
    planes: &[Plane],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<Indenter>, ModelError> {
    let mut indenters = Vec::new();
    for (i, d) in file.iter().enumerate() {
        let key = format!("indenters[{i}]");
        if let Some(p) = symmetry::left_out(planes, &d.surface) {
            warnings.push(symmetry::note(key, &d.name, p));
            continue;
        }
        let b = body_index(mesh, format!("{key}.body"), &d.body)?;
        if !planes.is_empty() {
            // a surface lying in a symmetry plane is a cut, held by the plane's u_n = 0
            let (faces, _) = surface_faces(&format!("{key}.surface"), &d.surface, &mesh.bodies[b])?;
            symmetry::faces_off_planes(&format!("{key}.surface"), &mesh.bodies[b], &faces, planes)?;
        }
        let mut ind = indenter(&key, d, b, &mesh.bodies[b], materials)?;
        ind.impactor = impactor(&key, d, transient)?;
        symmetry::check_indenter_shape(&key, &ind, planes, mesh)?;
        // the force and an impactor's mass are the full structure's: the part kept carries its share
        let shared = symmetry::check_indenter(&key, &ind, planes, mesh)?;
        let share = 1.0 / f64::from(1u32 << shared);
        ind.force = ind.force.map(|f| f.map(|v| v * share));
        if let Some(imp) = &mut ind.impactor {
            imp.mass *= share;
            // the share against the body kept, as the whole mass against the whole body
            lightest_impactor(&key, (imp.mass, share), &mesh.bodies[b], materials)?;
        }
        // how far the indenter's own motion brings it towards each node
        let reach = |c: &contact::ContactNode| (0..3).map(|k| ind.displacement[k] * c.normal[k]).sum::<f64>() - c.gap0;
        if !transient && ind.force.is_none() && ind.nodes.iter().all(|c| reach(c) < 0.0) {
            let gap = ind.nodes.iter().map(|c| c.gap0).fold(f64::INFINITY, f64::min);
            // a gap of zero (printed "-0.000e0" before): it starts touching and moves away
            let start = if gap > 1e-9 * mesh.bodies[b].size() {
                format!("does not close its initial gap (at least {} m) to any node of the surface", limit(gap))
            } else {
                "moves it away from the surface it touches at the start".to_string()
            };
            warnings.push(Warning {
                key: format!("{key}.displacement"),
                message: format!(
                    "the indenter's motion {:?} m {start}: it touches only if the body moves into it",
                    ind.displacement
                ),
            });
        }
        indenters.push(ind);
    }

    Ok(indenters)
}

pub(super) fn indenter(
    key: &str,
    d: &IndenterFile,
    b: usize,
    body: &Body,
    materials: &[Material],
) -> Result<Indenter, ModelError> {
    let (face_list, faces) = surface_faces(&format!("{key}.surface"), &d.surface, body)?;
    let young = super::body_young(body, materials);
    let surface = SurfaceNodes::from_faces(&faces, young);
    let pen = penalty(key, d.penalty, d.penalty_factor)?;
    let tol = 1e-9 * body.size();
    let shape = rigid_surface(key, &d.shape, body)?;
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
        let which = match d.shape {
            IndenterShape::Flat { .. } => format!("{key}.position / {key}.normal"),
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
    facing(key, d, body, &surface, &nodes)?;
    // an impactor (mass, velocity) moves by its inertia: checked by `impactor`
    let (displacement, force) = if d.mass.is_some() || d.velocity.is_some() {
        ([0.0; 3], d.force.map(<[f64; 3]>::from))
    } else {
        motion(key, d, body, young, &nodes)?
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
        updated: d.method.unwrap_or_default() == IndenterMethod::Surface,
        impactor: None,
    })
}

/// `mass` and `velocity`: a rigid impactor, only in a transient analysis,
/// without `displacement` (its motion is its own), with a `force` (say its
/// weight) along its velocity if any.
fn impactor(key: &str, d: &IndenterFile, transient: bool) -> Result<Option<contact::Impactor>, ModelError> {
    let (mass, velocity) = match (d.mass, d.velocity) {
        (None, None) => return Ok(None),
        (None, Some(_)) => {
            return Err(invalid(format!("{key}.mass"), "(missing)", "the impactor's mass in kg (with velocity)"));
        }
        (Some(_), None) => {
            return Err(invalid(
                format!("{key}.velocity"),
                "(missing)",
                "the impactor's initial velocity [x, y, z] in m/s (with mass)",
            ));
        }
        (Some(m), Some(v)) => (m, <[f64; 3]>::from(v)),
    };
    if !transient {
        return Err(invalid(format!("{key}.mass"), bounds::number(mass), "only with analysis.type = \"transient\""));
    }
    ranges::IMPACTOR_MASS.check(&format!("{key}.mass"), mass, "the impactor's mass in kg, positive")?;
    let speed = velocity.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !(speed > 0.0 && speed <= super::transient::MAX_SPEED) {
        return Err(invalid(
            format!("{key}.velocity"),
            format!("{velocity:?}"),
            "a non-zero velocity in m/s of at most 1e4 (the impactor moves along it)",
        ));
    }
    if d.displacement.is_some() {
        return Err(invalid(
            format!("{key}.displacement"),
            "(given with mass)",
            "no displacement for an impactor: its motion follows from its mass, velocity and contact force",
        ));
    }
    if let Some(f) = d.force {
        let f = <[f64; 3]>::from(f);
        let along: f64 = f.iter().zip(&velocity).map(|(a, b)| a * b).sum::<f64>() / speed;
        let norm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm.is_finite() && (norm - along.abs()) <= 1e-9 * norm) {
            return Err(invalid(
                format!("{key}.force"),
                format!("{f:?}"),
                "a force along the impactor's velocity (it moves along one direction)",
            ));
        }
    }
    Ok(Some(contact::Impactor { mass, velocity }))
}

/// Smallest impactor mass as a fraction of the body it strikes: a lighter
/// one's inertia is lost in the round-off of the body's forces (a 1e-15 kg
/// impactor on the 0.8 kg rod of `examples/rod_impact.toml` stops Newton
/// at first contact, a 1e-12 kg one converges; tests/dynamics.rs).
pub(crate) const MIN_IMPACTOR_FRACTION: f64 = 1e-9;

/// An impactor's mass against the mass of the body it strikes (its
/// section's area × its length × the lightest of its densities; not
/// checked without densities, which a transient analysis then refuses):
/// `(mass, share)` the mass the part kept carries and its share of the
/// file's `mass` across symmetry planes (1 without), weighed against the
/// body kept, which is what the round-off sees.
fn lightest_impactor(
    key: &str,
    (mass, share): (f64, f64),
    body: &Body,
    materials: &[Material],
) -> Result<(), ModelError> {
    let Some(rho) =
        body.materials().iter().map(|&m| materials[m].density).try_fold(f64::INFINITY, |a, d| d.map(|d| a.min(d)))
    else {
        return Ok(());
    };
    let length = body.axis.nodes.last().unwrap_or(&0.0) - body.axis.nodes.first().unwrap_or(&0.0);
    let body_mass = rho * body.section.properties().area * length;
    let lightest = MIN_IMPACTOR_FRACTION * body_mass;
    if mass < lightest {
        let kept = if share < 1.0 {
            format!(" (the part kept carries {:.2e} kg of it against the body's {body_mass:.2e} kg kept)", mass)
        } else {
            String::new()
        };
        return Err(invalid(
            format!("{key}.mass"),
            format!("{}{kept}", bounds::number(mass / share)),
            format!(
                "at least {:.2e} kg, a billionth of the {:.2e} kg of body {:?} it strikes (a lighter impactor's \
                 inertia is lost in the round-off of the body's forces)",
                lightest / share,
                body_mass / share,
                body.name
            ),
        ));
    }
    Ok(())
}

/// The indenter's rigid surface from its shape's own keys.
fn rigid_surface(key: &str, shape: &IndenterShape, body: &Body) -> Result<RigidSurface, ModelError> {
    let range = |name: &str, r: Option<Exact<f64, 2>>| -> Result<Option<[f64; 2]>, ModelError> {
        match r.map(<[f64; 2]>::from) {
            Some([a, b]) if a.is_finite() && b.is_finite() && a <= b && a.abs().max(b.abs()) <= bounds::MAX_COORD => {
                Ok(Some([a, b]))
            }
            Some(r) => Err(invalid(format!("{key}.{name}"), format!("{r:?}"), "[min, max] with min ≤ max")),
            None => Ok(None),
        }
    };
    Ok(match shape {
        IndenterShape::Flat { normal, position, x, y, z } => {
            // required keys are `Option`s in the schema so that a missing
            // one is reported here with what it means
            let (sign, axis) = normal
                .ok_or_else(|| {
                    invalid(
                        format!("{key}.normal"),
                        "(missing)",
                        "the direction the punch face looks towards the body: \"+x\", \"-x\", \"+y\", \"-y\", \"+z\" or \"-z\"",
                    )
                })?
                .sign_and_axis();
            let position = position.ok_or_else(|| {
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
                bounds: [range("x", *x)?, range("y", *y)?, range("z", *z)?],
            }
        }
        IndenterShape::Cylinder { axis, center, radius, length } => {
            let axis = axis.ok_or_else(|| {
                invalid(format!("{key}.axis"), "(missing)", "\"x\", \"y\" or \"z\" (direction of the cylinder axis)")
            })?;
            let (center, radius) = round(key, *center, *radius, body, "a point [x, y, z] on the cylinder axis")?;
            RigidSurface::Cylinder { axis: axis.index(), center, radius, length: range("length", *length)? }
        }
        IndenterShape::Sphere { center, radius } => {
            let (center, radius) = round(key, *center, *radius, body, "the sphere's centre [x, y, z]")?;
            RigidSurface::Sphere { center, radius }
        }
    })
}

/// The indenter must lie outside the body, facing its surface: at every
/// paired node the direction from the indenter to the node opposes the
/// surface's outward normal. Otherwise the body sits inside a punch, or a
/// roller is buried under the surface, and contact would never engage.
fn facing(
    key: &str,
    d: &IndenterFile,
    body: &Body,
    surface: &SurfaceNodes,
    nodes: &[contact::ContactNode],
) -> Result<(), ModelError> {
    let outward: std::collections::HashMap<usize, [f64; 3]> = surface.nodes.iter().map(|e| (e.0, e.3)).collect();
    for c in nodes {
        let m = outward[&c.node];
        let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        let facing = (0..3).map(|k| c.normal[k] * m[k]).sum::<f64>() / len;
        if !(facing < -1e-6) {
            let (which, fix) = match d.shape {
                IndenterShape::Flat { .. } => (
                    format!("{key}.normal"),
                    "the punch on the outer side of the surface, its normal pointing into the body (e.g. normal = \"-z\" for a punch above a top face)",
                ),
                IndenterShape::Sphere { .. } => {
                    (format!("{key}.center"), "the sphere's centre on the outer side of the selected surface")
                }
                IndenterShape::Cylinder { .. } => {
                    (format!("{key}.center"), "the cylinder's axis on the outer side of the selected surface")
                }
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
    Ok(())
}

/// Displacement control (`displacement`: the rigid motion at factor 1) or
/// force control (`force`, which must push the body), exactly one of them.
/// Both are keys of every shape: which one is given is a value check.
fn motion(
    key: &str,
    d: &IndenterFile,
    body: &Body,
    young: f64,
    nodes: &[contact::ContactNode],
) -> Result<([f64; 3], Option<[f64; 3]>), ModelError> {
    match (d.displacement, d.force) {
        (Some(u), None) => {
            let u = bounds::vector(
                &format!("{key}.displacement"),
                u,
                body.size(),
                &format!("a rigid motion in m of at most the size of body {:?}", body.name),
            )?;
            Ok((u, None))
        }
        (None, Some(f)) => {
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
            Ok(([0.0; 3], Some(f)))
        }
        (Some(_), Some(_)) => Err(invalid(
            format!("{key}.force"),
            "(given with displacement)",
            "exactly one of displacement (displacement control) and force (force control)",
        )),
        (None, None) => Err(invalid(
            format!("{key}.displacement"),
            "(missing)",
            "the indenter's rigid motion [x, y, z] in m, or force = [x, y, z] in N for force control",
        )),
    }
}

/// `center` and `radius` of a cylinder or sphere (`center_is`: what the
/// point is, for the message when it is missing).
fn round(
    key: &str,
    center: Option<Exact<f64, 3>>,
    radius: Option<f64>,
    body: &Body,
    center_is: &str,
) -> Result<([f64; 3], f64), ModelError> {
    let center = center.ok_or_else(|| invalid(format!("{key}.center"), "(missing)", center_is))?;
    let radius = radius.ok_or_else(|| invalid(format!("{key}.radius"), "(missing)", "the radius in m"))?;
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
