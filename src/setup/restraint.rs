//! Rigid-body restraint: every body must be held against all six rigid
//! motions, or the stiffness matrix is singular and Newton fails with
//! nothing but cutbacks.
//!
//! Each body has six rigid modes: translations `e_k` and small rotations
//! `θ × (x − c)` about the centroid `c` of its restrained nodes, scaled by
//! the body's size. A *restraint row* is a linear form on the
//! displacement that the model holds: a constrained component (fixed or
//! prescribed), the normal `n·u_s` of a node touching a rigid indenter at the
//! start, or `n·(u_s − u_m)` of a node pair or surface-contact point touching
//! at the start (contacts
//! that only close later cannot hold the first iterations). With `R` the
//! rows evaluated on the `6B` modes of all `B` bodies, the model is
//! restrained iff `G = Rᵀ R` is positive definite. `G` is judged with unit
//! diagonal (each mode measured against its own restraint), so a thin body
//! held over its 5 mm thickness is as restrained as a thick one; a mode
//! whose diagonal is at the round-off of the coordinates is held by nothing.
//! A null vector of `G` is a free motion; it is named in the error (which
//! body, which translation or rotation).

use faer::Mat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd;

use super::constraints::ConstraintHandler;
use crate::contact::{Indenter, PairContact};
use crate::input::{ModelError, invalid};
use crate::mesh::Mesh;

/// A restraint row `Σ w · u_node`, as (node, weight vector) terms.
type Row = Vec<(usize, [f64; 3])>;

/// Checks that no body (or group of bodies joined by contact) can move as a
/// rigid body.
pub fn check(
    mesh: &Mesh,
    constraints: &ConstraintHandler,
    indenters: &[Indenter],
    contacts: &[PairContact],
) -> Result<(), ModelError> {
    let size: Vec<f64> = mesh.bodies.iter().map(|b| b.size()).collect();
    let rows = restraint_rows(mesh, constraints, indenters, contacts, &size);
    let (centre, reach) = centres(mesh, &rows);
    let (mut g, rows_of) = gram(mesh, &rows, &centre, &size);
    let scale = unit_diagonal(&mut g, &rows_of, &reach, &size);
    free_motions(mesh, &g, &scale)
}

/// Every displacement form the model holds (module docs).
fn restraint_rows(
    mesh: &Mesh,
    constraints: &ConstraintHandler,
    indenters: &[Indenter],
    contacts: &[PairContact],
    size: &[f64],
) -> Vec<Row> {
    let mut rows: Vec<Row> = Vec::new();
    for (dof, _) in constraints.constrained() {
        let mut w = [0.0; 3];
        w[dof % 3] = 1.0;
        rows.push(vec![(dof / 3, w)]);
    }
    let touching = |gap0: f64, node: usize| gap0 <= 1e-9 * size[mesh.body_of(node).0];
    for ind in indenters {
        for c in ind.nodes.iter().filter(|c| touching(c.gap0, c.node)) {
            rows.push(vec![(c.node, c.normal)]);
        }
    }
    for pc in contacts {
        for p in pc.pairs.iter().filter(|p| touching(p.gap0, p.slave)) {
            rows.push(vec![(p.slave, p.normal), (p.master, p.normal.map(|v| -v))]);
        }
    }
    // surface contacts: n·(u_s − u_m) at the slave points touching at the start
    let zero = vec![0.0; mesh.n_dofs()];
    for s in contacts.iter().filter_map(|pc| pc.surface.as_ref()) {
        for p in &s.points {
            let Some(proj) = crate::contact::surface::project(s, mesh, p, &zero) else { continue };
            if proj.gap0 > 1e-9 * size[s.master_body] {
                continue;
            }
            let mut row = Vec::new();
            let sides = [(&p.nodes, &p.shapes, 1.0), (&proj.nodes, &proj.shapes, -1.0)];
            for (nodes, shapes, sign) in sides {
                for (&node, &sh) in nodes.iter().zip(shapes.iter()) {
                    row.push((node, proj.normal.map(|v| sign * sh * v)));
                }
            }
            rows.push(row);
        }
    }
    rows
}

/// The centre of each body's rotations and the magnitude of its restrained
/// nodes' coordinates.
fn centres(mesh: &Mesh, rows: &[Row]) -> (Vec<[f64; 3]>, Vec<f64>) {
    let nb = mesh.bodies.len();
    // Rotations about the centroid of each body's restrained nodes (the body's
    // centre if none): about any other centre a rotation moves the restrained
    // nodes nearly like a translation, and a body restrained over a thin
    // face (a 100 m × 5 mm section clamped at its root) looked free.
    let mut centre: Vec<[f64; 3]> = mesh
        .bodies
        .iter()
        .map(|b| {
            let s = b.section.bounds();
            let (y0, y1) = (b.axis.nodes[0], b.axis.nodes[b.axis.nodes.len() - 1]);
            [0.5 * (s[0] + s[1]), 0.5 * (y0 + y1), 0.5 * (s[2] + s[3])]
        })
        .collect();
    let mut sum = vec![([0.0; 3], 0usize); nb];
    // the coordinates' magnitude per body: their round-off bounds what a
    // restraint's lever arm can resolve
    let mut reach = vec![0.0f64; nb];
    for &(node, _) in rows.iter().flatten() {
        let b = mesh.body_of(node).0;
        let x = mesh.coords(node);
        for k in 0..3 {
            sum[b].0[k] += x[k];
            reach[b] = reach[b].max(x[k].abs());
        }
        sum[b].1 += 1;
    }
    for (b, (s, count)) in sum.iter().enumerate() {
        if *count > 0 {
            centre[b] = s.map(|v| v / *count as f64);
        }
    }
    (centre, reach)
}

/// `G = Rᵀ R` over the six rigid modes of every body, and how many row
/// terms fall on each body.
fn gram(mesh: &Mesh, rows: &[Row], centre: &[[f64; 3]], size: &[f64]) -> (Mat<f64>, Vec<usize>) {
    let nb = mesh.bodies.len();
    // mode values of a node: modes[j][k] = component k of mode j
    let modes = |node: usize| -> (usize, [[f64; 3]; 6]) {
        let (b, _) = mesh.body_of(node);
        let x = mesh.coords(node);
        let r = [0, 1, 2].map(|k| (x[k] - centre[b][k]) / size[b]);
        let mut m = [[0.0; 3]; 6];
        for k in 0..3 {
            m[k][k] = 1.0;
        }
        // θ e_x × r, θ e_y × r, θ e_z × r
        m[3] = [0.0, -r[2], r[1]];
        m[4] = [r[2], 0.0, -r[0]];
        m[5] = [-r[1], r[0], 0.0];
        (b, m)
    };
    let n = 6 * nb;
    let mut g = Mat::<f64>::zeros(n, n);
    let mut rows_of = vec![0usize; nb];
    let mut entries: Vec<(usize, f64)> = Vec::new();
    for row in rows {
        entries.clear();
        for &(node, w) in row {
            let (b, m) = modes(node);
            rows_of[b] += 1;
            entries.extend((0..6).map(|j| (6 * b + j, (0..3).map(|k| w[k] * m[j][k]).sum::<f64>())));
        }
        for &(i, a) in &entries {
            for &(j, b) in &entries {
                g[(i, j)] += a * b;
            }
        }
    }
    (g, rows_of)
}

/// Scales `g` to a unit diagonal; returns the scale of every mode (0 for a
/// mode held by nothing).
fn unit_diagonal(g: &mut Mat<f64>, rows_of: &[usize], reach: &[f64], size: &[f64]) -> Vec<f64> {
    let (n, nb) = (g.nrows(), rows_of.len());
    // Each mode scaled to a unit diagonal, so a mode held only over a short
    // lever arm (a thin face) counts as much as one held over a long one; a
    // mode whose diagonal is at the round-off of the coordinates is held by
    // nothing (its row and column zeroed: a zero eigenvalue).
    let mut scale = vec![0.0; n];
    for b in 0..nb {
        let noise = 1e-12 * (1.0 + reach[b] / size[b]);
        let floor = rows_of[b] as f64 * noise * noise;
        for j in 6 * b..6 * b + 6 {
            if g[(j, j)] > floor {
                scale[j] = 1.0 / g[(j, j)].sqrt();
            }
        }
    }
    for i in 0..n {
        for j in 0..n {
            g[(i, j)] *= scale[i] * scale[j];
        }
    }
    scale
}

/// `Ok` if `g` is positive definite; else the free motions, named by body
/// and mode.
fn free_motions(mesh: &Mesh, g: &Mat<f64>, scale: &[f64]) -> Result<(), ModelError> {
    let (n, nb) = (g.nrows(), mesh.bodies.len());
    // sequential: validation must not start the global thread pool, which
    // the CLI sizes afterwards from the model's `solver.threads`
    let mut u = Mat::<f64>::zeros(n, n);
    let mut eigenvalues = faer::Col::<f64>::zeros(n);
    let par = faer::Par::Seq;
    let params = Default::default();
    let mut mem = MemBuffer::new(evd::self_adjoint_evd_scratch::<f64>(n, evd::ComputeEigenvectors::Yes, par, params));
    let stack = MemStack::new(&mut mem);
    if evd::self_adjoint_evd(g.as_ref(), eigenvalues.as_diagonal_mut(), Some(u.as_mut()), par, stack, params).is_err() {
        return Ok(()); // no verdict: leave it to the solver
    }
    let s = &eigenvalues;
    let largest = (0..n).map(|i| s[i]).fold(0.0f64, f64::max);
    // eigenvalues come sorted; the smallest tells whether a motion is free
    if s[0] > 1e-9 * largest.max(1.0) {
        return Ok(());
    }
    // every free motion (eigenvalue below the threshold), named by its
    // dominant body and modes
    const NAMES: [&str; 6] = [
        "translation along x",
        "translation along y",
        "translation along z",
        "rotation about x",
        "rotation about y",
        "rotation about z",
    ];
    let threshold = 1e-9 * largest.max(1.0);
    let mut free: Vec<(usize, Vec<&str>)> = Vec::new();
    for k in (0..n).take_while(|&k| s[k] <= threshold) {
        // back to unit-size modes (a mode held by nothing keeps its value)
        let v: Vec<f64> = (0..n).map(|i| if scale[i] > 0.0 { u[(i, k)] * scale[i] } else { u[(i, k)] }).collect();
        let b = (0..nb)
            .max_by(|&a, &c| {
                let na: f64 = (0..6).map(|j| v[6 * a + j].powi(2)).sum();
                let nc: f64 = (0..6).map(|j| v[6 * c + j].powi(2)).sum();
                na.total_cmp(&nc)
            })
            .unwrap_or(0);
        let big = (0..6).map(|j| v[6 * b + j].abs()).fold(0.0f64, f64::max);
        let motion: Vec<&str> = (0..6).filter(|&j| v[6 * b + j].abs() > 0.3 * big).map(|j| NAMES[j]).collect();
        free.push((b, motion));
    }
    let b = free[0].0;
    let motions: Vec<String> = free.iter().filter(|f| f.0 == b).map(|f| f.1.join(" with ")).collect();
    Err(invalid(
        format!("bodies[{b}]"),
        format!("{:?}, free to move as a rigid body ({})", mesh.bodies[b].name, motions.join("; ")),
        "every body held against rigid motion by [[constraints]], or by indenters and contacts touching it at \
         the start (frictionless contact only holds along its normal)",
    ))
}
