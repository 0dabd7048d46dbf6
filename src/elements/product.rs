//! The small-strain tangent as one product (module docs of
//! [`crate::elements`]): `B̄` and `w C B̄` gathered point by point, then
//! `K = Σ_j B̄_jᵀ (w C B̄_j)` by one dense GEMM.

use super::{Element, Workspace};
use crate::materials::Material;
use crate::values::CellValues;

/// Second pass (small strain): for every contributing Gauss point `j`
/// (all, or with `correction` only those whose tangent is not the elastic
/// one, with `C − C^el` — the nucleus is linear in `C`), the operator `B̄_j`
/// (its six rows as columns of `ws.bt`, one row per element DOF) and
/// `w C B̄_j` likewise in `ws.cbt`. Returns the number of points gathered.
pub(super) fn gather_operators(
    geom: &CellValues,
    el: &Element,
    material: &Material,
    correction: bool,
    ws: &mut Workspace,
) -> usize {
    let (sg, ag) = (&geom.section, &geom.axis);
    let (nodes, ndof, stride) = (el.nodes, 3 * el.nodes, 6 * el.n_points);
    let bbar = geom.volumetric.is_some();
    let elastic = material.elastic_stiffness();
    ws.bt.resize(ndof * stride, 0.0);
    ws.cbt.resize(ndof * stride, 0.0);
    let mut contributing = 0;
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            if correction {
                let t = &mut ws.tangents[q];
                if t == elastic {
                    continue;
                }
                for (row, er) in t.iter_mut().zip(elastic) {
                    for (v, e) in row.iter_mut().zip(er) {
                        *v -= e;
                    }
                }
            }
            let w = geom.gradients(el.es, el.eb, gb, gs, &mut ws.grads[..nodes]);
            let c = &ws.tangents[q];
            let dbar = if bbar { Some(&ws.bbar[q * nodes..(q + 1) * nodes]) } else { None };
            let shear = geom.shear.as_ref().map(|sh| (sh.at(el.es, gs), geom.axis.point(el.eb, gb).n));
            let col0 = 6 * contributing;
            for (b, &g) in ws.grads[..nodes].iter().enumerate() {
                // column k of B̄_b: the strain of a unit displacement u_k of
                // node b (crate::voigt's order and shear convention) plus the
                // B-bar term m d_b[k] / 3 on the normal rows, plus the
                // assumed shear's N_i m d_τ[k] on the in-plane columns
                let d = dbar.map_or([0.0; 3], |d| d[b]);
                for k in 0..3 {
                    let mut col = [d[k] / 3.0, d[k] / 3.0, d[k] / 3.0, 0.0, 0.0, 0.0];
                    let mut unit = [0.0; 3];
                    unit[k] = 1.0;
                    crate::voigt::add_nodal_strain(&mut col, g, unit);
                    if let Some(((m, dt), n)) = shear.filter(|_| k != 1) {
                        let (i, t) = (b / dt.len(), b % dt.len());
                        let s = n[i] * dt[t][k / 2];
                        for (cv, mv) in col.iter_mut().zip(m) {
                            *cv += s * mv;
                        }
                    }
                    let p = (3 * b + k) * stride + col0;
                    ws.bt[p..p + 6].copy_from_slice(&col);
                }
            }
            // w C B̄_j for all element DOFs at once: (DOF × 6) · (w C)ᵀ, a
            // small GEMM (the column-by-column 6 × 6 products ran scalar)
            let lhs = faer::MatRef::from_row_major_slice_with_stride(&ws.bt[col0..], ndof, 6, stride);
            let flat: [f64; 36] = std::array::from_fn(|i| c[i / 6][i % 6]);
            let cmat = faer::MatRef::from_row_major_slice(&flat, 6, 6);
            // (faer 0.24's `from_row_major_slice_with_stride_mut` lays the
            // data out column-major: the transposed column-major view instead)
            let dst = faer::MatMut::from_column_major_slice_with_stride_mut(&mut ws.cbt[col0..], 6, ndof, stride)
                .transpose_mut();
            faer::linalg::matmul::matmul(dst, faer::Accum::Replace, lhs, cmat.transpose(), w, faer::Par::Seq);
            contributing += 1;
        }
    }
    contributing
}

/// `K = Σ_j B̄_jᵀ (w C B̄_j) = bt · cbtᵀ` over the `contributing` points, one
/// dense product (faer GEMM, upper triangle only, sequential: the element
/// loop is the parallel one) into `ws.tangent`.
pub(super) fn tangent_product(el: &Element, contributing: usize, ws: &mut Workspace) {
    use faer::linalg::matmul::triangular::{BlockStructure, matmul};
    let (ndof, stride) = (3 * el.nodes, 6 * el.n_points);
    let k = 6 * contributing;
    let lhs = faer::MatRef::from_row_major_slice_with_stride(&ws.bt[..], ndof, k, stride);
    let rhs = faer::MatRef::from_row_major_slice_with_stride(&ws.cbt[..], ndof, k, stride);
    let dst = faer::MatMut::from_row_major_slice_mut(&mut ws.tangent[..ndof * ndof], ndof, ndof);
    matmul(
        dst,
        BlockStructure::TriangularUpper,
        faer::Accum::Replace,
        lhs,
        BlockStructure::Rectangular,
        rhs.transpose(),
        BlockStructure::Rectangular,
        1.0,
        faer::Par::Seq,
    );
}
