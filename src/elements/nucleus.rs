//! The total-Lagrangian tangent as 3×3 fundamental nuclei: the material and
//! geometric stiffness summed section by section along the axis.
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
//! Carrera (2018) for the geometrically nonlinear CUF. Only the pairs
//! `c ≤ d` are formed: the pairs `c > d` are the transposes, since
//! `M^(dc) = M^(cd)ᵀ` for symmetric `C = ∂S/∂E` and `S` (the material
//! update symmetrizes its tangent, `update_for_element`, and the logarithmic
//! pull-back forms it symmetric).
//!
//! **Sum factorization.** The node gradients are products,
//! `∇N_(i,τ) = N_i ĝ_(0,τ) + N_i,y ĝ_(1,τ)` with the section's halves
//! `ĝ_(0,τ) = (F_τ,x, 0, F_τ,z)` and `ĝ_(1,τ) = (0, F_τ, 0)`, so that, with
//! `φ_0 = N` and `φ_1 = N_,y` at the axis points `gb`,
//!
//! ```text
//! K_((i,τ)c,(j,s)d) = Σ_gb Σ_αβ φ_α,i φ_β,j S_gb^(cd)[(α,τ),(β,s)],
//! S_gb^(cd)[(α,τ),(β,s)] = Σ_gs ĝ_(α,τ)ᵀ M_(gb,gs)^(cd) ĝ_(β,s)
//! ```
//!
//! The section sums `S` are two GEMMs per axis point over the section
//! points, one for `α = 0` (the `x` and `z` rows of `M`) and one for
//! `α = 1` (its `y` row), which skip the zeros of `ĝ`; the axis functions
//! then enter by contiguous axpys. For an L9 × B4 element that is
//! 4 × 9 × 27 × 108 multiply-adds in the products and 4 × 23,328 in the
//! expansion, against 36 × 108 × 216 for one product over the stacked node
//! gradients.
//!
//! **B-bar at finite strain** (`fbar`) adds the terms of its dilatation
//! row `d = Π g̃ − g̃`. Their `−g̃` halves are local, gradients at the point
//! times 3 × 3 matrices, and join `M_q^(cd)` (`fbar::add_point_terms`, with
//! the dilatation's curvature); the projected halves `Π g̃` span at most
//! four vectors per element and are a rank-8 update after the product
//! (`fbar::add_projected`).

use super::{Workspace, fbar};
use crate::values::{CellValues, PressureSpace};
use crate::voigt::Voigt;

/// The component pairs `(c, d)`, `c ≤ d`, in the order of the column
/// blocks of the section sums and of the pair blocks.
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
    let points = geom.section.n_gp * geom.axis.n_gp;
    let projected = dilatation.map(|ps| {
        ws.proj_z.clear();
        ws.proj_z.resize(3 * ps.n * nodes, 0.0);
        (ps.n, fbar::prepare(ps, points, ws))
    });
    let n_pressure = projected.map_or(0, |(n, _)| n);
    let mut kall = std::mem::take(&mut ws.nuclei);
    kall.clear();
    kall.resize(nodes * PAIRS.len() * nodes, 0.0);
    // built for the CPU's vector width (runtime dispatch)
    pulp::Arch::new().dispatch(Axis { geom, es, eb, n_pressure, ws, kall: &mut kall });
    scatter_pairs(&kall, geom.section.n_fun, nodes, &mut ws.tangent);
    ws.nuclei = kall;
    if let Some((n, a)) = projected {
        fbar::add_projected(n, nodes, &a, ws);
    }
}

/// The geometric (initial-stress) stiffness alone of body element `e`,
/// `K_σ = δ_kl ∫ ∇N_a · σ ∇N_b dV`, from its Gauss-point stresses `stress`
/// (linear buckling, `crate::analysis::buckling`), into the upper triangle
/// of `ws.tangent`: the total-Lagrangian nuclei (above) at `F = I`
/// with no material stiffness, `M^(cd) = w δ_cd σ`.
pub(crate) fn geometric_matrix(
    geom: &CellValues,
    e: usize,
    n_section_elements: usize,
    stress: &[Voigt],
    ws: &mut Workspace,
) {
    let el = super::Element::new(geom, e, n_section_elements);
    ws.resize(el.nodes, el.n_points);
    ws.pk2[..el.n_points].copy_from_slice(&stress[..el.n_points]);
    ws.frames[..el.n_points].fill(crate::kinematics::IDENTITY);
    ws.tangents[..el.n_points].fill([[0.0; 6]; 6]);
    large_tangent(geom, (el.es, el.eb, el.nodes), None, ws);
}

/// The pair blocks `kall` of one element by sum factorization over its
/// axis points (module docs; rows `(i, τ)`, columns `(j, pair, s)`), and
/// with B-bar the projections `Z_l`, as a [`pulp::WithSimd`] so that the
/// loops are compiled for the vector instructions the CPU has (a closure
/// would not be inlined into the dispatched function).
struct Axis<'a> {
    geom: &'a CellValues,
    es: usize,
    eb: usize,
    /// B-bar's pressure functions (0 without B-bar).
    n_pressure: usize,
    ws: &'a mut Workspace,
    kall: &'a mut [f64],
}

impl pulp::WithSimd for Axis<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { geom, es, eb, n_pressure, ws, kall } = self;
        let (sg, ag) = (&geom.section, &geom.axis);
        let (ns, ngs) = (sg.n_fun, sg.n_gp);
        // columns (β, pair, s) of the section rows and sums
        let ewidth = 2 * PAIRS.len() * ns;
        // per axis point: the section values as rows (F_,x and F_,z of each
        // section point, then F of each), the rows of M ĝ in the same
        // order, and the sums S_α (ns × ewidth each)
        let mut gt = std::mem::take(&mut ws.gradients);
        let mut et = std::mem::take(&mut ws.nucleus_rows);
        let mut sums = std::mem::take(&mut ws.section_sums);
        gt.resize(3 * ngs * ns, 0.0);
        et.resize(3 * ngs * ewidth, 0.0);
        sums.resize(2 * ns * ewidth, 0.0);
        ws.section_t.resize(2 * ns * PAIRS.len() * ns * ag.n_fun, 0.0);
        ws.section_z.clear();
        ws.section_z.resize(3 * n_pressure * 2 * ns, 0.0);
        for gb in 0..ag.n_gp {
            let at = ag.point(eb, gb);
            ws.section_z.fill(0.0);
            for gs in 0..ngs {
                let q = gb * ngs + gs;
                let sp = sg.point(es, gs);
                let w = sp.weight * at.weight;
                let mut m = point_nuclei(&ws.frames[q], &ws.tangents[q], &ws.pk2[q], w);
                let gamma = (n_pressure > 0)
                    .then(|| fbar::add_point_terms(&mut m, &PAIRS, &ws.frames[q], ws.coupling[q], w, ws.proj_w[q]));
                gt[2 * gs * ns..(2 * gs + 1) * ns].copy_from_slice(sp.fx);
                gt[(2 * gs + 1) * ns..(2 * gs + 2) * ns].copy_from_slice(sp.fz);
                gt[(2 * ngs + gs) * ns..(2 * ngs + gs + 1) * ns].copy_from_slice(sp.f);
                // row k of M ĝ: k = x, z for α = 0, k = y for α = 1
                for (k, row) in [(0, 2 * gs), (2, 2 * gs + 1), (1, 2 * ngs + gs)] {
                    section_row(&sp, &m, k, &mut et[row * ewidth..(row + 1) * ewidth]);
                }
                if let Some(gamma) = gamma {
                    // ẑ_l[(c, (α, τ))] += c_l(q) γ_c · ĝ_(α,τ)
                    for (l, &cl) in ws.proj_c[4 * q..4 * q + n_pressure].iter().enumerate() {
                        for (c, gc) in gamma.iter().enumerate() {
                            let [x0, x1, x2] = gc.map(|x| cl * x);
                            let z = &mut ws.section_z[(3 * l + c) * 2 * ns..(3 * l + c + 1) * 2 * ns];
                            let (z0, z1) = z.split_at_mut(ns);
                            for (t, (o0, o1)) in z0.iter_mut().zip(z1).enumerate() {
                                *o0 += x0 * sp.fx[t] + x2 * sp.fz[t];
                                *o1 += x1 * sp.f[t];
                            }
                        }
                    }
                }
            }
            // S_α = Ĝ_αᵀ (M ĝ)_α: α = 0 over the 2 ngs rows (x, z), α = 1 over the ngs rows (y)
            let (s0, s1) = sums.split_at_mut(ns * ewidth);
            for (out, first, count) in [(s0, 0, 2 * ngs), (s1, 2 * ngs, ngs)] {
                // as Sᵀ = (M ĝ)ᵀ Ĝ: the long dimension as the product's rows
                faer::linalg::matmul::matmul(
                    faer::MatMut::from_row_major_slice_mut(out, ns, ewidth).transpose_mut(),
                    faer::Accum::Replace,
                    faer::MatRef::from_row_major_slice(&et[first * ewidth..(first + count) * ewidth], count, ewidth)
                        .transpose(),
                    faer::MatRef::from_row_major_slice(&gt[first * ns..(first + count) * ns], count, ns),
                    1.0,
                    faer::Par::Seq,
                );
            }
            expand(&at, ns, &sums, &mut ws.section_t, kall);
            if n_pressure > 0 {
                // Z_l[(c, (i, τ))] += N_i ẑ_l[(c, (0, τ))] + N_i,y ẑ_l[(c, (1, τ))]
                let nodes = ns * at.n.len();
                for (lc, z) in ws.section_z.chunks_exact(2 * ns).enumerate() {
                    let out = &mut ws.proj_z[lc * nodes..(lc + 1) * nodes];
                    for (i, (&n, &ny)) in at.n.iter().zip(at.ny).enumerate() {
                        for (o, (&z0, &z1)) in out[i * ns..(i + 1) * ns].iter_mut().zip(z[..ns].iter().zip(&z[ns..])) {
                            *o += n * z0 + ny * z1;
                        }
                    }
                }
            }
        }
        (ws.gradients, ws.nucleus_rows, ws.section_sums) = (gt, et, sums);
    }
}

/// Row `k` of `M ĝ` at one section point, columns `(β, pair, s)`:
/// `M^pair[k] · ĝ_(β,s)`, i.e. `M[k][x] F_s,x + M[k][z] F_s,z` for `β = 0`
/// and `M[k][y] F_s` for `β = 1`.
#[inline(always)]
fn section_row(sp: &crate::values::SectionAt<'_>, m: &[[[f64; 3]; 3]; 6], k: usize, row: &mut [f64]) {
    let ns = sp.f.len();
    let (r0, r1) = row.split_at_mut(PAIRS.len() * ns);
    for (mp, (o0, o1)) in m.iter().zip(r0.chunks_exact_mut(ns).zip(r1.chunks_exact_mut(ns))) {
        let [mx, my, mz] = mp[k];
        for (((o, &fx), &fz), (p, &f)) in o0.iter_mut().zip(sp.fx).zip(sp.fz).zip(o1.iter_mut().zip(sp.f)) {
            *o = mx * fx + mz * fz;
            *p = my * f;
        }
    }
}

/// One axis point's share of the pair blocks, in two steps:
/// `T[(α, τ), (j, pair, s)] = N_j S_α[τ, (0, pair, s)] + N_j,y S_α[τ, (1, pair, s)]`
/// (into `t`), then `kall[(i, τ), ·] += N_i T[(0, τ), ·] + N_i,y T[(1, τ), ·]`:
/// both contiguous axpys.
#[inline(always)]
fn expand(at: &crate::values::AxisAt<'_>, ns: usize, sums: &[f64], t: &mut [f64], kall: &mut [f64]) {
    let half = PAIRS.len() * ns;
    let width = half * at.n.len();
    for (trow, srow) in t.chunks_exact_mut(width).zip(sums.chunks_exact(2 * half)) {
        let (s0, s1) = srow.split_at(half);
        for ((tj, &nj), &nyj) in trow.chunks_exact_mut(half).zip(at.n).zip(at.ny) {
            for ((o, &a), &b) in tj.iter_mut().zip(s0).zip(s1) {
                *o = nj * a + nyj * b;
            }
        }
    }
    let (t0, t1) = t.split_at(ns * width);
    for (i, (&ni, &nyi)) in at.n.iter().zip(at.ny).enumerate() {
        let rows = kall[i * ns * width..(i + 1) * ns * width].iter_mut();
        for ((o, &a), &b) in rows.zip(t0).zip(t1) {
            *o += ni * a + nyi * b;
        }
    }
}

/// The six nuclei `M^(cd) = w (H_cᵀ C H_d + δ_cd S)` of one point
/// (module docs), in the order of [`PAIRS`]. Column `l` of `H_d` is the
/// strain variation of a unit `u_d` with gradient `e_l`
/// ([`crate::kinematics::strain_variation`], the one statement of the Voigt
/// order and shear convention for `δE`): three non-zeros, so `C H_d` and
/// `H_cᵀ (C H_d)` cost three multiply-adds per entry.
#[inline(always)]
fn point_nuclei(
    f: &crate::kinematics::Tensor,
    c: &crate::voigt::Matrix6,
    pk2: &crate::voigt::Voigt,
    w: f64,
) -> [[[f64; 3]; 3]; 6] {
    // the non-zeros of column l of H_d: (Voigt row, value)
    let column = |d: usize, l: usize| -> [(usize, f64); 3] {
        let r = f[d];
        match l {
            0 => [(0, r[0]), (3, r[1]), (4, r[2])],
            1 => [(1, r[1]), (3, r[0]), (5, r[2])],
            _ => [(2, r[2]), (4, r[0]), (5, r[1])],
        }
    };
    debug_assert!((0..3).all(|d| (0..3).all(|l| {
        let mut e = [0.0; 3];
        e[l] = 1.0;
        let v = crate::kinematics::strain_variation(f, e, d);
        let mut sparse = [0.0; 6];
        for (row, x) in column(d, l) {
            sparse[row] += x;
        }
        v == sparse
    })));
    // w C H_d (per d and l a Voigt column)
    let ch: [[[f64; 6]; 3]; 3] = std::array::from_fn(|d| {
        std::array::from_fn(|l| {
            let [(r0, x0), (r1, x1), (r2, x2)] = column(d, l);
            std::array::from_fn(|r| w * (c[r][r0] * x0 + c[r][r1] * x1 + c[r][r2] * x2))
        })
    });
    let s = crate::voigt::stress_tensor(pk2);
    std::array::from_fn(|pair| {
        let (cc, d) = PAIRS[pair];
        std::array::from_fn(|k| {
            let [(r0, x0), (r1, x1), (r2, x2)] = column(cc, k);
            std::array::from_fn(|l| {
                let v = &ch[d][l];
                let material = x0 * v[r0] + x1 * v[r1] + x2 * v[r2];
                if cc == d { material + w * s[k][l] } else { material }
            })
        })
    })
}

/// Writes the upper triangle of the element tangent (row-major, `3 nodes`
/// square, DOF `3a + c`) from the pair blocks `kall[a, (j, pair, s)] =
/// K_(ac,bd)` with `b = (j, s)` (`ns` section functions): a block with
/// `c < d` holds entries of both triangles (those with `a > b` are the
/// transposed `K_(bd,ac)`).
fn scatter_pairs(kall: &[f64], ns: usize, nodes: usize, tangent: &mut [f64]) {
    let (n, width) = (3 * nodes, PAIRS.len() * nodes);
    for (a, row) in kall.chunks_exact(width).enumerate() {
        for (j, rj) in row.chunks_exact(PAIRS.len() * ns).enumerate() {
            // b = j ns + s ≥ a from s = a − j ns on: (3a + c, 3b + d) is
            // in the upper triangle; below it, with c < d, the transposed
            // entry (3b + d, 3a + c) is
            let split = a.saturating_sub(j * ns).min(ns);
            for (&(c, d), rp) in PAIRS.iter().zip(rj.chunks_exact(ns)) {
                let out = &mut tangent[(3 * a + c) * n + 3 * j * ns + d..];
                for (o, &v) in out.iter_mut().step_by(3).zip(rp).skip(split) {
                    *o = v;
                }
                if c != d {
                    for (s, &v) in rp[..split].iter().enumerate() {
                        tangent[(3 * (j * ns + s) + d) * n + 3 * a + c] = v;
                    }
                }
            }
        }
    }
}
