//! Deformable bodies that start inside each other, for both kinds of
//! `[[contacts]]` (node-to-node and surface): refused, or imposed
//! gradually for a deliberate interference fit.

use super::preprocess::model_coords;
use crate::input::schema::ContactFile;
use crate::input::{ModelError, invalid};
use crate::mesh::Mesh;

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
