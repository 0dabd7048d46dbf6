//! The unsymmetric tangent of a model with Coulomb friction.
//!
//! The tangent is `K = K_sym + K_skew`: `K_sym` is everything the structure
//! assembles into its lower-triangle pattern (elements, normal contact, the
//! symmetric part of every frictional block), `K_skew` the skew parts
//! `(K_c − K_cᵀ)/2` of the sliding points' blocks (`contact::friction`:
//! the coupling `μ ε_N t̂ nᵀ`), kept as entries and outer products per
//! evaluation (`solver::nonsymmetric`). The solver reuses the factorization of `K_sym`
//! (single precision, reused across iterations like the frictionless
//! path) as the preconditioner of GMRES on `K` (`solver::krylov`,
//! `ReusingSolver::solve_unsymmetric`): no second factorization, no second
//! pattern, and the memory of the frictionless model plus the GMRES basis.
//!
//! Prescribed displacements are eliminated as in the symmetric path
//! (`Structure::correct`): a skew entry in a free row and a prescribed
//! column moves `v Δ_p` to the right-hand side, every skew entry in a
//! prescribed row or column is dropped.

use super::{NO_EQ, Structure};

impl Structure<'_> {
    /// Forgets the skew terms of the previous evaluation.
    pub(super) fn clear_skew(&mut self) {
        if let Some(s) = self.skew.as_mut() {
            s.clear();
        }
    }

    /// Adds `sign · block` between the DOFs of nodes `a` (rows) and `b`
    /// (columns) to the skew terms (nothing in a frictionless model, whose
    /// blocks are symmetric).
    pub(super) fn add_skew(&mut self, a: usize, b: usize, block: &[[f64; 3]; 3], sign: f64) {
        let Some(skew) = self.skew.as_mut() else { return };
        let eq = &self.assembler.dofs.eq;
        for (i, row) in block.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                let (r, c) = (eq[3 * a + i], eq[3 * b + j]);
                if v != 0.0 && r != NO_EQ && c != NO_EQ {
                    skew.push_entry(r, c, sign * v);
                }
            }
        }
    }

    /// Adds the outer product `u vᵀ` of two nodal vectors (`(node, [x, y,
    /// z])`) to the unsymmetric terms (nothing in a frictionless model).
    pub(super) fn add_outer(&mut self, u: &[(usize, [f64; 3])], v: &[(usize, [f64; 3])]) {
        let Some(skew) = self.skew.as_mut() else { return };
        let eq = &self.assembler.dofs.eq;
        let sparse = |w: &[(usize, [f64; 3])]| -> Vec<(usize, f64)> {
            w.iter()
                .flat_map(|(n, c)| (0..3).map(move |i| (3 * n + i, c[i])))
                .filter_map(|(d, x)| (eq[d] != NO_EQ && x != 0.0).then_some((eq[d], x)))
                .collect()
        };
        skew.push_outer(sparse(u), sparse(v));
    }

    /// True if the tangent may be unsymmetric (a model with friction).
    pub fn is_unsymmetric(&self) -> bool {
        self.skew.is_some()
    }

    /// Entry `(row, col)` (equations) of the full tangent of the last
    /// evaluation, before any Dirichlet elimination: the symmetric part
    /// from the lower-triangle values plus the skew terms (for
    /// finite-difference checks of the unsymmetric tangent).
    pub fn tangent_entry(&self, row: usize, col: usize) -> f64 {
        let sym = self.assembler.pattern.find(row.max(col), row.min(col)).map_or(0.0, |p| self.tangent[p]);
        sym + self.skew.as_ref().map_or(0.0, |s| s.entry(row, col))
    }

    /// The Dirichlet elimination of the skew terms (module docs); `residual`
    /// holds `Δ_p` at the prescribed equations.
    pub(super) fn eliminate_skew(&mut self) {
        if let Some(skew) = self.skew.as_mut() {
            skew.eliminate(&self.is_prescribed, &mut self.residual);
        }
    }
}
