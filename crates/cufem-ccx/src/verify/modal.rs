//! Natural frequencies against CalculiX's `*FREQUENCY` step, mode by mode.
//!
//! A modal model's static state is the unloaded one, so the probes, lines,
//! resultants and whole field of [`super::compare`] would compare zeros;
//! what both analyses compute are the frequencies and their modes.
//!
//! **Pairing.** Modes are paired by the modal assurance criterion, not by
//! their order, so that two modes whose order differs between the models
//! (close frequencies, or a 3D mode — a section's own deformation — that
//! the beam model has higher up) are still compared with each other. Both
//! mode shapes are sampled at the same points — the 27 points
//! `(ξ, η, ζ) ∈ {−1, 0, 1}³` of every CUF element: cufem's by its own shape
//! functions (`values::PointValues`), CalculiX's in the hexahedron holding
//! the point (`ccx::mesh::hex_shapes`) — and
//! `MAC(a, b) = (aᵀb)² / (aᵀa · bᵀb)` over all of them; the pairs are taken
//! greedily from the largest MAC down, each mode in at most one pair. A MAC
//! near 1 says the pair is the same mode; within a set of repeated
//! frequencies (a square section's two bending modes) the shapes are any
//! basis of the same space and the MAC of a pair may be low while its
//! frequencies agree. Without mode shapes in the `.frd` file the modes are
//! paired by order.

use serde::Serialize;

use crate::{CcxRun, HexMesh, mesh::hex_shapes};
use cufem::analysis::Solution;
use cufem::setup::Model;
use cufem::values::{Location, PointValues};

/// One cufem mode and the CalculiX mode paired with it.
#[derive(Debug, Clone, Serialize)]
pub struct ModeRow {
    /// cufem's mode number (1-based, ascending frequency).
    pub mode: usize,
    /// cufem's natural frequency (Hz).
    pub cufem_hz: f64,
    /// CalculiX's mode paired with it (1-based), `None` if CalculiX has no
    /// mode left for it.
    pub ccx_mode: Option<usize>,
    /// CalculiX's frequency of that mode (Hz).
    pub ccx_hz: Option<f64>,
    /// `100 (f_cufem − f_3D) / f_3D`.
    pub difference_percent: Option<f64>,
    /// The modal assurance criterion of the pair (0 … 1), `None` when
    /// paired by order.
    pub mac: Option<f64>,
}

/// A sample point in both meshes: the CUF point's functions, and the nodes
/// (CalculiX numbers) and shape values of the hexahedron holding it.
struct Point {
    cuf: PointValues,
    hex: Vec<(usize, f64)>,
}

fn points(model: &Model, mesh: &HexMesh) -> Vec<Point> {
    let grid = [-1.0, 0.0, 1.0];
    let mut n = [0.0; 20];
    let mut out = Vec::new();
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        for element in 0..body.n_elements() {
            for xi in grid {
                for eta in grid {
                    for zeta in grid {
                        let loc = Location { body: b, element, natural: [xi, eta, zeta] };
                        let (e, p) = mesh.locate(model, &loc);
                        hex_shapes(mesh.kind, p, &mut n);
                        let hex = mesh.elements[e].iter().zip(&n).map(|(&node, &w)| (node + 1, w)).collect();
                        out.push(Point { cuf: PointValues::new(body, &loc), hex });
                    }
                }
            }
        }
    }
    out
}

/// The modal assurance criterion of two sampled shapes.
fn mac(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let dot = |x: &[[f64; 3]], y: &[[f64; 3]]| -> f64 {
        x.iter().zip(y).map(|(p, q)| p[0] * q[0] + p[1] * q[1] + p[2] * q[2]).sum()
    };
    let (ab, aa, bb) = (dot(a, b), dot(a, a), dot(b, b));
    if aa > 0.0 && bb > 0.0 { ab * ab / (aa * bb) } else { 0.0 }
}

/// Pairs of `(cufem mode, CalculiX mode, MAC)` from the largest MAC down,
/// each mode in at most one pair.
fn pair(macs: &[Vec<f64>]) -> Vec<(usize, usize, f64)> {
    let mut all: Vec<(usize, usize, f64)> =
        macs.iter().enumerate().flat_map(|(i, row)| row.iter().enumerate().map(move |(j, &m)| (i, j, m))).collect();
    all.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)).then(a.1.cmp(&b.1)));
    let (mut ours, mut theirs) = (vec![false; macs.len()], vec![false; macs.first().map_or(0, Vec::len)]);
    let mut out = Vec::new();
    for (i, j, m) in all {
        if !ours[i] && !theirs[j] {
            (ours[i], theirs[j]) = (true, true);
            out.push((i, j, m));
        }
    }
    out
}

/// cufem's natural frequencies against CalculiX's, one row per cufem mode
/// (empty if either analysis has none).
pub fn compare_modes(model: &Model, solution: &Solution, mesh: &HexMesh, run: &CcxRun) -> Vec<ModeRow> {
    let Some(modal) = &solution.modal else { return Vec::new() };
    let theirs: Vec<f64> = run.frequencies.iter().map(|e| e.hz).collect();
    let mut rows: Vec<ModeRow> = modal
        .frequencies
        .iter()
        .enumerate()
        .map(|(i, &f)| ModeRow {
            mode: i + 1,
            cufem_hz: f,
            ccx_mode: None,
            ccx_hz: None,
            difference_percent: None,
            mac: None,
        })
        .collect();
    let set = |row: &mut ModeRow, j: usize, mac: Option<f64>| {
        row.ccx_mode = Some(j + 1);
        row.ccx_hz = Some(theirs[j]);
        row.difference_percent = Some(100.0 * (row.cufem_hz - theirs[j]) / theirs[j]);
        row.mac = mac;
    };
    let shapes = &run.results.modes;
    if shapes.len() != theirs.len() {
        // no shapes to pair by: by order
        for (j, row) in rows.iter_mut().enumerate().take(theirs.len()) {
            set(row, j, None);
        }
        return rows;
    }
    let pts = points(model, mesh);
    let ours: Vec<Vec<[f64; 3]>> =
        modal.modes.iter().map(|m| pts.iter().map(|p| p.cuf.displacement(m)).collect()).collect();
    let sampled: Vec<Vec<[f64; 3]>> = shapes
        .iter()
        .map(|(_, u)| {
            pts.iter()
                .map(|p| {
                    let mut v = [0.0; 3];
                    for &(node, w) in &p.hex {
                        let un = u.get(&node).copied().unwrap_or_default();
                        (0..3).for_each(|k| v[k] += w * un[k]);
                    }
                    v
                })
                .collect()
        })
        .collect();
    let macs: Vec<Vec<f64>> = ours.iter().map(|a| sampled.iter().map(|b| mac(a, b)).collect()).collect();
    for (i, j, m) in pair(&macs) {
        set(&mut rows[i], j, Some(m));
    }
    rows
}

/// The rows of the text table.
pub fn table(rows: &[ModeRow], t: &mut String) {
    use std::fmt::Write as _;
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        t,
        "\n{:>4} {:>14} {:>7} {:>14} {:>10} {:>7}",
        "mode", "cufem [Hz]", "3D mode", "3D [Hz]", "diff", "MAC"
    );
    for r in rows {
        let opt = |v: Option<String>| v.unwrap_or_else(|| "—".into());
        let _ = writeln!(
            t,
            "{:>4} {:>14.6} {:>7} {:>14} {:>10} {:>7}",
            r.mode,
            r.cufem_hz,
            opt(r.ccx_mode.map(|j| j.to_string())),
            opt(r.ccx_hz.map(|f| format!("{f:.6}"))),
            opt(r.difference_percent.map(|d| format!("{d:+.2} %"))),
            opt(r.mac.map(|m| format!("{m:.4}")))
        );
    }
    let _ = writeln!(
        t,
        "(modes paired by the MAC of their displacements at 27 points per CUF element; the static \
         comparisons are left out: the modal model's static state is the unloaded one)"
    );
}

/// The frequencies mode by mode (`modes`), cufem's and those of the
/// CalculiX modes paired with them; `None` without modes.
pub fn plot(rows: &[ModeRow]) -> Option<cufem::io::Plot> {
    let series = |name: &str, f: fn(&ModeRow) -> Option<f64>, dashed| cufem::io::Series {
        name: name.into(),
        points: rows.iter().filter_map(|r| f(r).map(|hz| (r.mode as f64, hz))).collect(),
        dashed,
    };
    (!rows.is_empty()).then(|| cufem::io::Plot {
        name: "modes".into(),
        title: "natural frequencies, mode by mode".into(),
        x: "cufem mode".into(),
        y: "frequency [Hz]".into(),
        series: vec![series("cufem", |r| Some(r.cufem_hz), false), series("CalculiX 3D (paired)", |r| r.ccx_hz, true)],
    })
}

/// The rows of `table.csv` (`kind,name,quantity,cufem,ccx,difference_percent`):
/// per cufem mode its frequency, the CalculiX mode paired with it and the
/// pair's MAC.
pub fn csv(rows: &[ModeRow], csv: &mut String) {
    use std::fmt::Write as _;
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for r in rows {
        let name = r.mode;
        let _ =
            writeln!(csv, "mode,{name},frequency_hz,{:e},{},{}", r.cufem_hz, opt(r.ccx_hz), opt(r.difference_percent));
        let _ = writeln!(csv, "mode,{name},ccx_mode,,{},", r.ccx_mode.map_or(String::new(), |j| j.to_string()));
        let _ = writeln!(csv, "mode,{name},mac,,{},", opt(r.mac));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_by_the_largest_mac_each_mode_once() {
        // cufem's modes 2 and 3 are CalculiX's 3 and 2; mode 1 is 1
        let macs = vec![vec![0.99, 0.01, 0.0], vec![0.0, 0.2, 0.97], vec![0.02, 0.95, 0.3]];
        let mut p = pair(&macs);
        p.sort_by_key(|x| x.0);
        assert_eq!(p.iter().map(|x| (x.0, x.1)).collect::<Vec<_>>(), [(0, 0), (1, 2), (2, 1)]);
        // the MAC of a shape with itself, and with an orthogonal one
        let a = [[1.0, 0.0, 0.0], [0.5, 0.0, 0.0]];
        let b = [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!((mac(&a, &a.map(|v| v.map(|c| -3.0 * c))) - 1.0).abs() < 1e-15);
        assert_eq!(mac(&a, &b), 0.0);
    }
}
