//! The element tangents' unsymmetric rest gathered from the parallel
//! element loop: a damaging element's loading points hand their vectors
//! `Bᵀs`, `Bᵀg` (`crate::elements::softening`); each becomes the two outer
//! products `½ (Bᵀs)(Bᵀg)ᵀ − ½ (Bᵀg)(Bᵀs)ᵀ` of the structure's rest
//! (`crate::solver::nonsymmetric`), in equation numbering. The workers
//! push under a lock (few elements load at a time); the rest takes the
//! terms sorted by element, so the sum is the same whatever the threads.

use std::sync::{Mutex, PoisonError};

use super::{DofMap, NO_EQ};
use crate::solver::nonsymmetric::NonSymmetric;

/// A sparse vector in equation numbering.
type Sparse = Vec<(usize, f64)>;

/// The terms of the elements of one assembly, by element.
#[derive(Debug, Default)]
pub(super) struct SkewTerms {
    terms: Mutex<Vec<(usize, Sparse, Sparse)>>,
}

impl SkewTerms {
    /// Adds element `ge`'s vectors `skew` (pairs `Bᵀs`, `Bᵀg` of `3 ·
    /// nodes.len()` entries each, element DOF `3a + c` at node `nodes[a]`).
    pub(super) fn add(&self, ge: usize, nodes: &[usize], dofs: &DofMap, skew: &[f64]) {
        if skew.is_empty() {
            return;
        }
        let n = 3 * nodes.len();
        let sparse = |v: &[f64]| -> Sparse {
            v.iter()
                .enumerate()
                .map(|(i, &x)| (dofs.eq[3 * nodes[i / 3] + i % 3], x))
                .filter(|&(e, x)| e != NO_EQ && x != 0.0)
                .collect()
        };
        let own: Vec<_> = skew.chunks_exact(2 * n).map(|p| (ge, sparse(&p[..n]), sparse(&p[n..]))).collect();
        self.terms.lock().unwrap_or_else(PoisonError::into_inner).extend(own);
    }

    /// Adds every term to `rest`, in the order of the elements.
    pub(super) fn into_rest(self, rest: &mut NonSymmetric) {
        let mut terms = self.terms.into_inner().unwrap_or_else(PoisonError::into_inner);
        // stable: an element's terms keep their order
        terms.sort_by_key(|t| t.0);
        for (_, s, g) in terms {
            rest.push_outer(s.iter().map(|&(e, x)| (e, 0.5 * x)), g.iter().copied());
            rest.push_outer(g.iter().map(|&(e, x)| (e, -0.5 * x)), s.iter().copied());
        }
    }
}
