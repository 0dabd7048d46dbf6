//! The unsymmetric tangent of a model with Coulomb friction, solved by
//! sparse LU (`solver::lu`).
//!
//! The tangent is `K = K_sym + K_skew`: `K_sym` is everything the structure
//! assembles into its lower-triangle pattern (elements, normal contact, the
//! symmetric part of every frictional block), `K_skew` the skew parts
//! `(K_c − K_cᵀ)/2` of the sliding points' blocks (`contact::friction`:
//! the coupling `μ ε_N t̂ nᵀ`), kept as a list of `(row, column, value)`
//! entries per evaluation. A model with friction on any contact factorizes
//! `K` on the full pattern `L ∪ Lᵀ` with LU instead of Cholesky (chosen once
//! in `Structure::new`); a frictionless model never comes here.
//!
//! Prescribed displacements are eliminated as in the symmetric path, with
//! `Δ_p = λ ū_p − u_p`: `K_ff δu_f = −R_f − K_fp Δ_p`, the prescribed rows
//! and columns zeroed, their diagonal kept and `δu_p = Δ_p`.

use std::time::Instant;

use super::{NO_EQ, Structure};
use crate::solver::linear::{LinearError, LowerCsc};
use crate::solver::lu::SparseLu;
use crate::solver::newton::Correction;

/// LU factorization and the skew terms of the current evaluation.
pub(super) struct Unsymmetric {
    lu: SparseLu,
    /// `(row, column, value)` in equation numbering.
    skew: Vec<(usize, usize, f64)>,
    /// Full-pattern entries in a prescribed row or column, off the
    /// diagonal: `(position, row, column)`.
    dirichlet: Vec<(usize, usize, usize)>,
    /// Full-pattern position of each diagonal entry.
    diagonal: Vec<usize>,
}

impl Unsymmetric {
    /// The LU path if any contact of `model` has friction, else `None`.
    pub fn for_model(
        model: &crate::model::Model,
        pattern: &LowerCsc,
        is_prescribed: &[bool],
    ) -> Result<Option<Box<Self>>, LinearError> {
        let frictional =
            model.indenters.iter().any(|i| i.friction.is_some()) || model.contacts.iter().any(|c| c.friction.is_some());
        if !frictional {
            return Ok(None);
        }
        let lu = SparseLu::analyze(pattern)?;
        let (col_ptr, row_idx) = lu.structure();
        let mut dirichlet = Vec::new();
        let mut diagonal = vec![0; lu.n()];
        for c in 0..lu.n() {
            for (p, &r) in row_idx.iter().enumerate().take(col_ptr[c + 1]).skip(col_ptr[c]) {
                if r == c {
                    diagonal[c] = p;
                } else if is_prescribed[r] || is_prescribed[c] {
                    dirichlet.push((p, r, c));
                }
            }
        }
        Ok(Some(Box::new(Self { lu, skew: Vec::new(), dirichlet, diagonal })))
    }
}

/// Solves with the LU factorization (a model with friction).
pub(super) fn lu_solve(lu: &mut Option<Box<Unsymmetric>>, x: &mut [f64]) -> Result<(), LinearError> {
    match lu {
        Some(u) => u.lu.solve_in_place(x),
        None => Err(LinearError::Singular),
    }
}

impl Structure<'_> {
    /// Forgets the skew terms of the previous evaluation.
    pub(super) fn clear_skew(&mut self) {
        if let Some(u) = self.lu.as_mut() {
            u.skew.clear();
        }
    }

    /// Adds `sign · block` between the DOFs of nodes `a` (rows) and `b`
    /// (columns) to the skew terms (nothing in a frictionless model, whose
    /// blocks are symmetric).
    pub(super) fn add_skew(&mut self, a: usize, b: usize, block: &[[f64; 3]; 3], sign: f64) {
        let Some(u) = self.lu.as_mut() else { return };
        let eq = &self.assembler.dofs.eq;
        for (i, row) in block.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                let (r, c) = (eq[3 * a + i], eq[3 * b + j]);
                if v != 0.0 && r != NO_EQ && c != NO_EQ {
                    u.skew.push((r, c, sign * v));
                }
            }
        }
    }

    /// True if the structure solves with LU (a model with friction).
    pub fn is_unsymmetric(&self) -> bool {
        self.lu.is_some()
    }

    /// Entry `(row, col)` (equations) of the full tangent of the last
    /// evaluation, before any Dirichlet elimination: the symmetric part
    /// from the lower-triangle values plus the skew terms (for
    /// finite-difference checks of the unsymmetric tangent).
    pub fn tangent_entry(&self, row: usize, col: usize) -> f64 {
        let sym = self.assembler.pattern.find(row.max(col), row.min(col)).map_or(0.0, |p| self.tangent[p]);
        let skew: f64 =
            self.lu.as_ref().map_or(0.0, |u| u.skew.iter().filter(|e| e.0 == row && e.1 == col).map(|e| e.2).sum());
        sym + skew
    }

    /// `correct` for the unsymmetric tangent (module docs).
    pub(super) fn correct_unsymmetric(&mut self) -> Result<Correction, LinearError> {
        let Some(un) = self.lu.as_mut() else { return Err(LinearError::Singular) };
        for r in &mut self.residual {
            *r = -*r;
        }
        for (&(d, e, _, _), now) in self.prescribed.iter().zip(&self.prescribed_now) {
            self.residual[e] = now - self.u[d];
        }
        un.lu.fill_symmetric(&self.tangent);
        for &(r, c, v) in &un.skew {
            if !un.lu.add(r, c, v) {
                return Err(LinearError::Rejected(format!(
                    "internal: friction term ({r}, {c}) outside the tangent's pattern"
                )));
            }
        }
        let values = un.lu.values_mut();
        for &(p, r, c) in &un.dirichlet {
            if !self.is_prescribed[r] {
                self.residual[r] -= values[p] * self.residual[c];
            }
        }
        for &(p, _, _) in &un.dirichlet {
            values[p] = 0.0;
        }
        for &(_, e, _, _) in &self.prescribed {
            self.residual[e] *= values[un.diagonal[e]];
        }
        let t = Instant::now();
        un.lu.factorize()?;
        self.timings.factorization += t.elapsed();
        self.timings.factorizations += 1;
        let t = Instant::now();
        let da2 = self.solve_bordered()?;
        self.timings.solve += t.elapsed();
        Ok(self.apply_correction(da2))
    }
}
