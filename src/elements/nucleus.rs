//! The total-Lagrangian tangent as 3×3 fundamental nuclei: the material and
//! geometric stiffness in one product over the displacement gradients.
//!
//! With `F = I + ∇u` the Green–Lagrange variation of a unit displacement
//! `δu_c` of node `a` (reference gradient `g = ∇N_a`) is
//! `δE = H_c g` ([`crate::kinematics::strain_variation`]), where `H_c` is
//! the 6 × 3 matrix of row `c` of `F` in Voigt order (engineering shear):
//!
//! ```text
//!        | F_cx  0     0    |   xx
//!        | 0     F_cy  0    |   yy
//!  H_c = | 0     0     F_cz |   zz
//!        | F_cy  F_cx  0    |   xy
//!        | F_cz  0     F_cx |   xz
//!        | 0     F_cz  F_cy |   yz
//! ```
//!
//! The tangent block between `(a, c)` and `(b, d)` is then, material and
//! geometric term together,
//!
//! ```text
//! K_(ac,bd) = Σ_q ∇N_aᵀ M_q^(cd) ∇N_b,   M_q^(cd) = w_q (H_cᵀ C_q H_d + δ_cd S_q)
//! ```
//!
//! a 3 × 3 matrix per point and component pair — the nucleus of Pagani &
//! Carrera (2018) for the geometrically nonlinear CUF. With the gradients of
//! all nodes at all points stacked, `G` (nodes × 3Q), and `E^(cd) =
//! G (blockdiag_q M_q^(cd))ᵀ` likewise, the six pairs `c ≤ d` are one GEMM
//! `G [E^(00) … E^(22)]ᵀ` (nodes × 6 nodes; the pairs `c > d` are the
//! transposes, since `M^(dc) = M^(cd)ᵀ` for symmetric `C = ∂S/∂E` and `S`:
//! the material update symmetrizes its tangent, `update_for_element`, and
//! the logarithmic pull-back forms it symmetric). That is 36 × 108 × 216
//! for an L9 × B4 element against 108 × 216 × 108 (half of it, the upper
//! triangle) for `Bᵀ (C B)` with `B` the stacked 6 × 108 operators, plus
//! the latter's `C B` products and separate geometric GEMM; the operator
//! `B` is never formed.
//!
//! **B-bar at finite strain** (`fbar`) adds the terms of its dilatation
//! row `d = Π g̃ − g̃`. Their `−g̃` halves are local, gradients at the point
//! times 3 × 3 matrices, and join `M_q^(cd)` (`fbar::add_point_terms`, with
//! the dilatation's curvature); the projected halves `Π g̃` span at most
//! four vectors per element and are a rank-8 update after the product
//! (`fbar::add_projected`).

use super::{Workspace, fbar};
use crate::values::{CellValues, PressureSpace};

/// The component pairs `(c, d)`, `c ≤ d`, in the order of the product's
/// column blocks.
const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// Writes the total-Lagrangian tangent (material and geometric; with a
/// pressure space `dilatation`, B-bar's terms too) of element `(es, eb)`
/// with `nodes` nodes into the upper triangle of `ws.tangent`, from the
/// first pass's `F` (`ws.frames`), `S` (`ws.pk2`) and `∂S/∂E`
/// (`ws.tangents`), and with B-bar its projection and coupling
/// (`fbar::dilatation_projection`, `ws.coupling`, `ws.pressure`).
pub(super) fn large_tangent(
    geom: &CellValues,
    (es, eb, nodes): (usize, usize, usize),
    dilatation: Option<&PressureSpace>,
    ws: &mut Workspace,
) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let points = sg.n_gp * ag.n_gp;
    let rows = 3 * points;
    let width = PAIRS.len() * nodes;
    let projected = dilatation.map(|ps| {
        ws.proj_z.clear();
        ws.proj_z.resize(3 * ps.n * nodes, 0.0);
        (ps.n, fbar::prepare(ps, points, ws))
    });
    // Gᵀ (3Q × nodes) and Eᵀ (3Q × 6 nodes), row-major: the rows of a point
    // are contiguous, so E's rows are axpys over contiguous node gradients
    let mut gt = std::mem::take(&mut ws.gradients);
    let mut et = std::mem::take(&mut ws.nucleus_rows);
    gt.resize(rows * nodes, 0.0);
    et.resize(rows * width, 0.0);
    // built for the CPU's vector width (runtime dispatch): the rows of E are
    // 54 multiply-adds per node and point, as many as the product below
    // has per output entry and point
    let n_pressure = projected.map_or(0, |(n, _)| n);
    pulp::Arch::new().dispatch(Rows { geom, es, eb, nodes, n_pressure, ws, gt: &mut gt, et: &mut et });
    let mut kall = std::mem::take(&mut ws.nuclei);
    kall.resize(nodes * width, 0.0);
    faer::linalg::matmul::matmul(
        faer::MatMut::from_row_major_slice_mut(&mut kall, nodes, width),
        faer::Accum::Replace,
        faer::MatRef::from_row_major_slice(&gt, rows, nodes).transpose(),
        faer::MatRef::from_row_major_slice(&et, rows, width),
        1.0,
        faer::Par::Seq,
    );
    scatter_pairs(&kall, nodes, &mut ws.tangent);
    (ws.nuclei, ws.gradients, ws.nucleus_rows) = (kall, gt, et);
    if let Some((n, a)) = projected {
        fbar::add_projected(n, nodes, &a, ws);
    }
}

/// The rows of `Gᵀ` and `Eᵀ` of all points of one element (and with B-bar
/// the projections `Z_l`), as a [`pulp::WithSimd`] so that the loops are
/// compiled for the vector instructions the CPU has (a closure would not be
/// inlined into the dispatched function).
struct Rows<'a> {
    geom: &'a CellValues,
    es: usize,
    eb: usize,
    nodes: usize,
    /// B-bar's pressure functions (0 without B-bar).
    n_pressure: usize,
    ws: &'a mut Workspace,
    gt: &'a mut [f64],
    et: &'a mut [f64],
}

impl pulp::WithSimd for Rows<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { geom, es, eb, nodes, n_pressure, ws, gt, et } = self;
        let (sg, ag) = (&geom.section, &geom.axis);
        let width = PAIRS.len() * nodes;
        for gb in 0..ag.n_gp {
            for gp in 0..sg.n_gp {
                let q = gb * sg.n_gp + gp;
                let w = geom.gradients(es, eb, gb, gp, &mut ws.grads[..nodes]);
                let mut m = point_nuclei(&ws.frames[q], &ws.tangents[q], &ws.pk2[q], w);
                let gamma = (n_pressure > 0)
                    .then(|| fbar::add_point_terms(&mut m, &PAIRS, &ws.frames[q], ws.coupling[q], w, ws.proj_w[q]));
                let g = &mut gt[3 * q * nodes..3 * (q + 1) * nodes];
                point_rows(&ws.grads[..nodes], &m, g, &mut et[3 * q * width..3 * (q + 1) * width]);
                if let Some(gamma) = gamma {
                    // Z_l[(c, ·)] += c_l(q) Σ_k γ_ck ∂_k N
                    let (g0, rest) = g.split_at(nodes);
                    let (g1, g2) = rest.split_at(nodes);
                    for (l, &cl) in ws.proj_c[4 * q..4 * q + n_pressure].iter().enumerate() {
                        for (c, gc) in gamma.iter().enumerate() {
                            let [x0, x1, x2] = gc.map(|x| cl * x);
                            let z = &mut ws.proj_z[(3 * l + c) * nodes..(3 * l + c + 1) * nodes];
                            for (((o, &a), &b), &d) in z.iter_mut().zip(g0).zip(g1).zip(g2) {
                                *o += x0 * a + x1 * b + x2 * d;
                            }
                        }
                    }
                }
            }
        }
    }
}

/// One point's rows of `Gᵀ` (3 × nodes, from the gradients `grads`) and of
/// `Eᵀ` (3 × 6 nodes): `E^(cd)[b, k] = Σ_l M^(cd)[k][l] ∂_l N_b`.
#[inline(always)]
fn point_rows(grads: &[[f64; 3]], m: &[[[f64; 3]; 3]; 6], g: &mut [f64], e: &mut [f64]) {
    let nodes = grads.len();
    for (a, ga) in grads.iter().enumerate() {
        for l in 0..3 {
            g[l * nodes + a] = ga[l];
        }
    }
    let (g0, rest) = g.split_at(nodes);
    let (g1, g2) = rest.split_at(nodes);
    for (k, row) in e.chunks_exact_mut(PAIRS.len() * nodes).enumerate() {
        for (mp, out) in m.iter().zip(row.chunks_exact_mut(nodes)) {
            let [m0, m1, m2] = mp[k];
            for (((o, &x), &y), &z) in out.iter_mut().zip(g0).zip(g1).zip(g2) {
                *o = m0 * x + m1 * y + m2 * z;
            }
        }
    }
}

/// The six nuclei `M^(cd) = w (H_cᵀ C H_d + δ_cd S)` of one point
/// (module docs), in the order of [`PAIRS`].
#[inline(always)]
fn point_nuclei(
    f: &crate::kinematics::Tensor,
    c: &crate::voigt::Matrix6,
    pk2: &crate::voigt::Voigt,
    w: f64,
) -> [[[f64; 3]; 3]; 6] {
    // H_c as 6 × 3: column l is δE of a unit u_c with gradient e_l
    // (kinematics::strain_variation, the one statement of the Voigt order
    // and shear convention for δE)
    let cols: [[crate::voigt::Voigt; 3]; 3] = std::array::from_fn(|cc| {
        std::array::from_fn(|l| {
            let mut e = [0.0; 3];
            e[l] = 1.0;
            crate::kinematics::strain_variation(f, e, cc)
        })
    });
    let h: [[[f64; 3]; 6]; 3] =
        std::array::from_fn(|cc| std::array::from_fn(|r| std::array::from_fn(|l| cols[cc][l][r])));
    // w C H_d (6 × 3)
    let ch: [[[f64; 3]; 6]; 3] = std::array::from_fn(|d| {
        std::array::from_fn(|r| std::array::from_fn(|l| w * (0..6).map(|s| c[r][s] * h[d][s][l]).sum::<f64>()))
    });
    let s = crate::voigt::stress_tensor(pk2);
    std::array::from_fn(|pair| {
        let (cc, d) = PAIRS[pair];
        std::array::from_fn(|k| {
            std::array::from_fn(|l| {
                let material: f64 = (0..6).map(|r| h[cc][r][k] * ch[d][r][l]).sum();
                if cc == d { material + w * s[k][l] } else { material }
            })
        })
    })
}

/// Writes the upper triangle of the element tangent (row-major, `3 nodes`
/// square, DOF `3a + c`) from the pair blocks `kall[a, pair · nodes + b] =
/// K_(ac,bd)`: a block with `c < d` holds entries of both triangles (those
/// with `a > b` are the transposed `K_(bd,ac)`).
fn scatter_pairs(kall: &[f64], nodes: usize, tangent: &mut [f64]) {
    let (n, width) = (3 * nodes, PAIRS.len() * nodes);
    for (pair, &(c, d)) in PAIRS.iter().enumerate() {
        for a in 0..nodes {
            let row = &kall[a * width + pair * nodes..a * width + (pair + 1) * nodes];
            for (b, &v) in row.iter().enumerate() {
                let (p, q) = (3 * a + c, 3 * b + d);
                if p <= q {
                    tangent[p * n + q] = v;
                } else if c != d {
                    tangent[q * n + p] = v;
                }
            }
        }
    }
}
