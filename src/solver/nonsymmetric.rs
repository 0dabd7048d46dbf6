//! The part of an unsymmetric tangent kept outside its symmetric,
//! factorized part: `K = A + S`, `A` on the lower-triangle pattern
//! ([`super::linear::LowerCsc`]), `S` here, as sparse entries and as outer
//! products `u vᵀ`.
//!
//! Coulomb friction makes `S` (`contact::friction`): a node pair's pressure
//! coupling `μ ε_N t̂ nᵀ` is a few entries, but a surface contact's slave node
//! couples every node `b` of its faces to every node `c` of its faces and
//! master faces through `μ ε (T_b t̂) G_cᵀ / A²` — one outer product, whose
//! entries would number the square of those nodes (tens of thousands per
//! slave node); stored as its two vectors it costs their length.

/// `S = Σ entries + Σ u vᵀ`, in equation numbering.
#[derive(Debug, Clone, Default)]
pub struct NonSymmetric {
    /// `(row, column, value)`.
    entries: Vec<(usize, usize, f64)>,
    /// Outer products: the ranges of `u` and `v` in `pool`.
    outer: Vec<(std::ops::Range<usize>, std::ops::Range<usize>)>,
    /// `(index, value)` of the outer products' vectors.
    pool: Vec<(usize, f64)>,
}

impl NonSymmetric {
    /// Nothing stored.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty() && self.outer.is_empty()
    }

    /// Forgets every term (keeps the storage).
    pub fn clear(&mut self) {
        self.entries.clear();
        self.outer.clear();
        self.pool.clear();
    }

    /// Adds `value` at `(row, column)`.
    pub(crate) fn push_entry(&mut self, row: usize, column: usize, value: f64) {
        self.entries.push((row, column, value));
    }

    /// Adds the outer product `u vᵀ` of two sparse vectors (`(index, value)`;
    /// an index may repeat, its values add).
    pub(crate) fn push_outer(
        &mut self,
        u: impl IntoIterator<Item = (usize, f64)>,
        v: impl IntoIterator<Item = (usize, f64)>,
    ) {
        let a = self.pool.len();
        self.pool.extend(u);
        let b = self.pool.len();
        self.pool.extend(v);
        self.outer.push((a..b, b..self.pool.len()));
    }

    /// `y += S x`.
    pub(crate) fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        for &(r, c, v) in &self.entries {
            y[r] += v * x[c];
        }
        for (u, v) in &self.outer {
            let s: f64 = self.pool[v.clone()].iter().map(|&(c, w)| w * x[c]).sum();
            for &(r, w) in &self.pool[u.clone()] {
                y[r] += w * s;
            }
        }
    }

    /// Entry `(row, column)` of `S` (a search: for tests).
    pub fn entry(&self, row: usize, column: usize) -> f64 {
        let direct: f64 = self.entries.iter().filter(|e| e.0 == row && e.1 == column).map(|e| e.2).sum();
        let sum = |r: &std::ops::Range<usize>, i: usize| -> f64 {
            self.pool[r.clone()].iter().filter(|e| e.0 == i).map(|e| e.1).sum()
        };
        direct + self.outer.iter().map(|(u, v)| sum(u, row) * sum(v, column)).sum::<f64>()
    }

    /// Symmetric elimination of prescribed equations: with `delta` holding
    /// the prescribed change `Δ_p` at every prescribed equation (and the
    /// right-hand side elsewhere), moves `S_fp Δ_p` to the right-hand side
    /// of the free rows and drops every term in a prescribed row or column.
    pub(crate) fn eliminate(&mut self, prescribed: &[bool], delta: &mut [f64]) {
        self.entries.retain(|&(r, c, v)| {
            if prescribed[c] && !prescribed[r] {
                delta[r] -= v * delta[c];
            }
            !prescribed[r] && !prescribed[c]
        });
        let mut pool = Vec::with_capacity(self.pool.len());
        let mut outer = Vec::with_capacity(self.outer.len());
        for (u, v) in &self.outer {
            let s: f64 = self.pool[v.clone()].iter().filter(|e| prescribed[e.0]).map(|&(c, w)| w * delta[c]).sum();
            if s != 0.0 {
                for &(r, w) in &self.pool[u.clone()] {
                    if !prescribed[r] {
                        delta[r] -= w * s;
                    }
                }
            }
            let a = pool.len();
            pool.extend(self.pool[u.clone()].iter().filter(|e| !prescribed[e.0]));
            let b = pool.len();
            pool.extend(self.pool[v.clone()].iter().filter(|e| !prescribed[e.0]));
            if a < b && b < pool.len() {
                outer.push((a..b, b..pool.len()));
            } else {
                pool.truncate(a);
            }
        }
        self.pool = pool;
        self.outer = outer;
    }

    /// Bytes held (for the memory estimate's check).
    pub fn bytes(&self) -> usize {
        self.entries.capacity() * std::mem::size_of::<(usize, usize, f64)>()
            + self.outer.capacity() * std::mem::size_of::<(std::ops::Range<usize>, std::ops::Range<usize>)>()
            + self.pool.capacity() * std::mem::size_of::<(usize, f64)>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Product, entries and elimination against the dense matrix of the
    /// same terms (an entry, an outer product with a repeated index): a sign
    /// or index slip in any of them changes a dense entry.
    #[test]
    fn products_entries_and_elimination_match_the_dense_matrix() {
        let n = 5;
        let mut s = NonSymmetric::default();
        s.push_entry(0, 3, 2.0);
        s.push_outer([(1, 1.5), (4, -0.5), (1, 0.5)], [(0, 3.0), (2, -1.0)]);
        let mut dense = [[0.0; 5]; 5];
        dense[0][3] += 2.0;
        for (r, a) in [(1, 2.0), (4, -0.5)] {
            for (c, b) in [(0, 3.0), (2, -1.0)] {
                dense[r][c] += a * b;
            }
        }
        for r in 0..n {
            for c in 0..n {
                assert_eq!(s.entry(r, c), dense[r][c], "({r}, {c})");
            }
        }
        let x = [1.0, -2.0, 0.5, 3.0, 4.0];
        let mut y = [0.0; 5];
        s.mul_add(&x, &mut y);
        for r in 0..n {
            let d: f64 = (0..n).map(|c| dense[r][c] * x[c]).sum();
            assert!((y[r] - d).abs() < 1e-14, "row {r}: {} vs {d}", y[r]);
        }
        // prescribe equation 2 (Δ = 0.5) and 3 (Δ = 3): the free rows get
        // −S_fp Δ_p, and no term touches a prescribed row or column afterwards
        let prescribed = [false, false, true, true, false];
        let mut delta = [0.0, 0.0, 0.5, 3.0, 0.0];
        s.eliminate(&prescribed, &mut delta);
        for r in [0, 1, 4] {
            let expected = -(dense[r][2] * 0.5 + dense[r][3] * 3.0);
            assert!((delta[r] - expected).abs() < 1e-14, "row {r}: {} vs {expected}", delta[r]);
            for c in [0, 1, 4] {
                assert_eq!(s.entry(r, c), dense[r][c]);
            }
        }
        for p in [2, 3] {
            assert!((0..n).all(|i| s.entry(p, i) == 0.0 && s.entry(i, p) == 0.0));
        }
    }
}
