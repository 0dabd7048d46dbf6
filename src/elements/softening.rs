//! The unsymmetric rest of a damaging element's consistent tangent
//! (`crate::materials::damage::Softening`): a loading ply point's tangent
//! is `C_sym + ½ Σ (s gᵀ − g sᵀ)`, whose rest adds to the element
//! `½ w [(Bᵀs)(Bᵀg)ᵀ − (Bᵀg)(Bᵀs)ᵀ]` — two outer products per term of
//! vectors the internal force's own operator gives (`Bᵀv` is the force of
//! the "stress" `v` at the point, with the assumed shear's and B-bar's
//! rows, `super::stresses_and_forces`). The kernel keeps the terms in its
//! first pass; this forms the vectors after the tangent, and the assembly
//! scatters them into the structure's unsymmetric rest
//! (`crate::assembly::skew`). Small strain only (ply damage is).

use super::{Element, Workspace, add_point_force, expand_force};
use crate::values::CellValues;
use crate::voigt::{Voigt, stress_tensor};

/// One rank-one term of a Gauss point: `(point, weight, s, g)`.
pub(crate) type Term = (usize, f64, Voigt, Voigt);

/// Forms `Bᵀs` and `Bᵀg` of every term of `ws.softening` into `ws.skew`
/// (term `k`: `Bᵀs` at `2k · n`, `Bᵀg` at `(2k + 1) · n`, `n` the element's
/// DOF), `Bᵀs` with the point's weight.
pub(super) fn operators(geom: &CellValues, el: &Element, ws: &mut Workspace) {
    let n = 3 * el.nodes;
    let ns = geom.section.n_fun;
    let Workspace { softening, skew, skew_h: h, bbar, .. } = ws;
    skew.clear();
    skew.resize(2 * n * softening.len(), 0.0);
    h.resize(2 * ns, [0.0; 3]);
    for (k, &(q, w, s, g)) in softening.iter().enumerate() {
        let (gb, gs) = (q / geom.section.n_gp, q % geom.section.n_gp);
        let (at, sp) = (geom.axis.point(el.eb, gb), geom.section.point(el.es, gs));
        // the point's weight once, on `Bᵀs`
        for (j, (v, w)) in [(s, w), (g, 1.0)].iter().copied().enumerate() {
            let (hx, hy) = h.split_at_mut(ns);
            hx.fill([0.0; 3]);
            hy.fill([0.0; 3]);
            add_point_force(&sp, w, &stress_tensor(&v), hx, hy);
            if let Some(sh) = &geom.shear {
                sh.add_force(el.es, gs, w, &v, hx);
            }
            let out = &mut skew[(2 * k + j) * n..(2 * k + j + 1) * n];
            expand_force(&at, hx, hy, out);
            if geom.volumetric.is_some() {
                // f_a += w d_a tr(v)/3, as the force's pressure row
                let tr = (v[0] + v[1] + v[2]) / 3.0;
                for a in 0..el.nodes {
                    let da = bbar[q * el.nodes + a];
                    for c in 0..3 {
                        out[3 * a + c] += w * tr * da[c];
                    }
                }
            }
        }
    }
}

/// The element tangent's rest `Σ ½ [(Bᵀs)(Bᵀg)ᵀ − (Bᵀg)(Bᵀs)ᵀ]` as a
/// dense row-major `n × n` matrix (for tests: the assembly keeps the
/// vectors).
#[cfg(test)]
pub(super) fn dense_rest(ws: &Workspace, n: usize) -> Vec<f64> {
    let mut m = vec![0.0; n * n];
    for pair in ws.skew.chunks_exact(2 * n) {
        let (bs, bg) = pair.split_at(n);
        for i in 0..n {
            for j in 0..n {
                m[i * n + j] += 0.5 * (bs[i] * bg[j] - bg[i] * bs[j]);
            }
        }
    }
    m
}
