//! `[[contacts]]` with `method = "surface"`: segment-to-segment contact on
//! non-matching meshes (`contact::surface`).

use super::overlap::overlap;
use super::preprocess::surface_faces;
use crate::contact::{ContactSurface, PairContact, Penalty, SurfaceNodes, surface};
use crate::input::schema::ContactFile;
use crate::input::validate::{friction, penalty, tolerance};
use crate::input::{ModelError, bounds, invalid};
use crate::materials::Material;
use crate::mesh::Mesh;

/// Builds a surface contact: slave integration points on the slave faces,
/// candidate master faces within `search_distance` (default: a quarter of
/// the largest master face's bounding-box diagonal — sliding of a fraction
/// of an element, the small-displacement setting).
pub(super) fn surface_contact(
    key: &str,
    c: &ContactFile,
    search_distance: Option<f64>,
    mesh: &Mesh,
    bm: usize,
    bs: usize,
    materials: &[Material],
) -> Result<PairContact, ModelError> {
    let (master_body, slave_body) = (&mesh.bodies[bm], &mesh.bodies[bs]);
    let (master_faces, mf) = surface_faces(&format!("{key}.master.where"), &c.master.selection, master_body)?;
    let (slave_faces, sf) = surface_faces(&format!("{key}.slave.where"), &c.slave.selection, slave_body)?;
    let young = super::body_young(master_body, materials).min(super::body_young(slave_body, materials));
    let pen = penalty(key, c.penalty, c.penalty_factor)?;
    let largest_face = master_faces
        .iter()
        .map(|f| {
            let fp = surface::face_point(master_body, f, 0.0, 0.0);
            let xs: Vec<[f64; 3]> = fp.nodes.iter().map(|&n| mesh.coords(n)).collect();
            let ext = |k: usize| {
                let (lo, hi) =
                    xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x[k]), b.max(x[k])));
                hi - lo
            };
            (ext(0).powi(2) + ext(1).powi(2) + ext(2).powi(2)).sqrt()
        })
        .fold(0.0, f64::max);
    let size = master_body.size().max(slave_body.size());
    let search_distance = match search_distance {
        Some(d) => bounds::within(
            &format!("{key}.search_distance"),
            d,
            bounds::MIN_RELATIVE_SIZE * size,
            size,
            "a distance in m (how far a slave point may slide or start from the master faces it can touch), at most the bodies' size",
        )?,
        None => 0.25 * largest_face,
    };
    let depths: Vec<f64> = sf.iter().map(|f| f.depth).collect();
    let contact = surface::build(
        surface::SlaveSide { body: slave_body, faces: &slave_faces, depths: &depths },
        bm,
        master_body,
        master_faces.clone(),
        search_distance,
        |h| match pen {
            Penalty::Factor(a) => a * young / h,
            Penalty::PerArea(p) => p,
        },
    );
    if contact.points.is_empty() {
        // slave faces deep inside the master body find no master face either:
        // say that, from the nearest master node along its outward normal
        let master_nodes = SurfaceNodes::from_faces(&mf, young);
        let slave_nodes = SurfaceNodes::from_faces(&sf, young);
        let gaps: Vec<(usize, f64)> = slave_nodes
            .nodes
            .iter()
            .filter_map(|s| {
                let xs = mesh.coords(s.0);
                let dist = |m: &&(usize, f64, f64, [f64; 3])| {
                    let xm = mesh.coords(m.0);
                    (0..3).map(|k| (xs[k] - xm[k]).powi(2)).sum::<f64>()
                };
                let m = master_nodes.nodes.iter().min_by(|a, b| dist(a).total_cmp(&dist(b)))?;
                let (xm, n) = (mesh.coords(m.0), m.3);
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                let d: [f64; 3] = std::array::from_fn(|k| xs[k] - xm[k]);
                let normal = (0..3).map(|k| d[k] * n[k]).sum::<f64>() / len;
                // facing the master node: off its normal by less than its spacing
                let off = (dist(&m) - normal * normal).max(0.0).sqrt();
                (off <= m.1.sqrt()).then_some((s.0, normal))
            })
            .collect();
        if !c.interference.unwrap_or(crate::input::defaults::INTERFERENCE) {
            overlap(key, c, mesh, bm, bs, &gaps)?;
        }
        return Err(invalid(
            format!("{key}.search_distance"),
            format!("{search_distance:e} m"),
            "a distance within which the slave faces find master faces (no slave point has a master face this close)",
        ));
    }
    // the weighted gap of each slave node at the start (projections of the
    // undeformed bodies), for the overlap check
    let zero = vec![0.0; mesh.n_dofs()];
    let projections: Vec<_> = contact.points.iter().map(|p| surface::project(&contact, mesh, p, &zero)).collect();
    let gaps: Vec<(usize, f64)> = contact
        .node_gaps(&projections)
        .iter()
        .zip(&contact.slave_nodes)
        .zip(&contact.areas)
        .map(|((g, &n), &a)| (n, if g.grad.is_empty() || !(a > 0.0) { 0.0 } else { g.gap0 / a }))
        .collect();
    let initial_overlap = overlap(key, c, mesh, bm, bs, &gaps)?;
    Ok(PairContact {
        initial_overlap,
        name: c.name.clone(),
        pairs: Vec::new(),
        penetration_tolerance: tolerance(key, c.penetration_tolerance, slave_body.size())?,
        friction: friction(key, c.friction)?,
        unpaired: contact.unpaired,
        master: ContactSurface { body: bm, faces: master_faces },
        slave: ContactSurface { body: bs, faces: slave_faces },
        surface: Some(contact),
    })
}
