//! The elimination of prescribed displacements. DOFs fixed at zero have
//! no equation (the numbering leaves them out). DOFs with a non-zero prescribed value keep
//! their equation, and each solve eliminates them symmetrically: with
//! `Δ_p = λ ū_p − u_p`, `K_ff δu_f = −R_f − K_fp Δ_p` and `δu_p = Δ_p`. The
//! first Newton iteration of an increment therefore moves the free DOFs
//! consistently with the prescribed ones (a linearized predictor) instead
//! of jumping the constrained nodes alone, which would strain — and, in
//! plasticity, spuriously yield — the elements next to them. The
//! elimination is the same for the symmetric tangent and for the
//! unsymmetric rest of a model with friction (`solver::nonsymmetric`).

use super::Prescribed;
use crate::assembly::Numbering;
use crate::setup::steps::{self, Item, Step};
use crate::solver::nonsymmetric::NonSymmetric;

/// The non-zero prescribed DOFs on a numbering and the matrix entries they
/// couple.
#[derive(Debug)]
pub struct Elimination {
    /// `(dof, equation, value at factor 1, constraint)`.
    prescribed: Vec<(usize, usize, f64, usize)>,
    /// Their values at the current λ.
    now: Vec<f64>,
    /// Per equation: true for a prescribed DOF.
    is_prescribed: Vec<bool>,
    /// Matrix entries coupling a prescribed equation: `(position, row, col)`.
    entries: Vec<(usize, usize, usize)>,
}

impl Elimination {
    /// The non-zero values of `constrained` (the handler's, by DOF) on
    /// `numbering`'s equations and pattern.
    pub(super) fn new(constrained: impl Iterator<Item = (usize, Prescribed)>, numbering: &Numbering) -> Self {
        let mut prescribed = Vec::new();
        let mut is_prescribed = vec![false; numbering.dofs.n_eq];
        for (d, p) in constrained.filter(|(_, p)| p.value != 0.0) {
            let e = numbering.dofs.eq[d];
            prescribed.push((d, e, p.value, p.constraint));
            is_prescribed[e] = true;
        }
        let pattern = &numbering.pattern;
        let mut entries = Vec::new();
        for c in 0..pattern.n {
            for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                let r = pattern.row_idx[k] as usize;
                if r != c && (is_prescribed[r] || is_prescribed[c]) {
                    entries.push((k, r, c));
                }
            }
        }
        Self { now: vec![0.0; prescribed.len()], prescribed, is_prescribed, entries }
    }

    /// True if no DOF has a non-zero prescribed value (the elimination
    /// leaves the tangent as it is).
    pub(crate) fn is_empty(&self) -> bool {
        self.prescribed.is_empty()
    }

    /// True if equation `e` is prescribed.
    pub(crate) fn is_prescribed(&self, e: usize) -> bool {
        self.is_prescribed[e]
    }

    /// The prescribed values at load factor `lambda` (each constraint times
    /// its factor in the load history).
    pub fn set_load_factor(&mut self, steps: &[Step], lambda: f64) {
        for (&(_, _, v, c), now) in self.prescribed.iter().zip(&mut self.now) {
            *now = steps::factor(steps, Item::Constraint(c), lambda) * v;
        }
    }

    /// How far `u` is from the prescribed values, and their size:
    /// `(max |λ ū − u|, max |ū|)`.
    pub fn offset(&self, u: &[f64]) -> (f64, f64) {
        let (mut off, mut size): (f64, f64) = (0.0, 0.0);
        for (&(d, _, v, _), now) in self.prescribed.iter().zip(&self.now) {
            off = off.max((now - u[d]).abs());
            size = size.max(v.abs());
        }
        (off, size)
    }

    /// For an eigenproblem `K φ = ω² M φ` about the present state: every
    /// entry coupling a prescribed equation zeroed in both matrices (lower
    /// triangles on one pattern), and its mass diagonal too, so that the
    /// prescribed DOFs stay fixed (their `θ = 1/ω²` is zero, never wanted).
    pub(crate) fn fix_for_eigen(&self, diagonal: impl Fn(usize) -> usize, k: &mut [f64], m: &mut [f64]) {
        for &(pos, _, _) in &self.entries {
            k[pos] = 0.0;
            m[pos] = 0.0;
        }
        for &(_, e, _, _) in &self.prescribed {
            m[diagonal(e)] = 0.0;
        }
    }

    /// Symmetric elimination (module docs) of the system `K δu = b` held in
    /// `tangent` (lower-triangle values), `rest` (the unsymmetric part, if
    /// any) and `rhs` (`−R` per equation on entry; on exit with `Δ_p` moved
    /// to the right-hand side and each prescribed row reading
    /// `k_pp δu_p = k_pp Δ_p`).
    pub(crate) fn eliminate(
        &self,
        u: &[f64],
        diagonal: impl Fn(usize) -> usize,
        tangent: &mut [f64],
        rest: Option<&mut NonSymmetric>,
        rhs: &mut [f64],
    ) {
        for (&(d, e, _, _), now) in self.prescribed.iter().zip(&self.now) {
            rhs[e] = now - u[d];
        }
        for &(k, r, c) in &self.entries {
            let kv = tangent[k];
            if !self.is_prescribed[r] {
                rhs[r] -= kv * rhs[c];
            } else if !self.is_prescribed[c] {
                rhs[c] -= kv * rhs[r];
            }
            tangent[k] = 0.0;
        }
        if let Some(rest) = rest {
            rest.eliminate(&self.is_prescribed, rhs);
        }
        for &(_, e, _, _) in &self.prescribed {
            rhs[e] *= tangent[diagonal(e)];
        }
    }
}
