//! The constraint handler: every constraint on the degrees of freedom, in
//! one place, as Ferrite's `ConstraintHandler` or deal.II's
//! `AffineConstraints` hold them. Built once in setup from the model's
//! `[[constraints]]`, the symmetry planes' `u_n = 0` (which
//! `setup::preprocess` appends to them) and the contacts' couplings; the
//! numbering, the memory plan, the restraint check, the reactions and the
//! solution's elimination read it instead of deriving the sets again.
//!
//! * A DOF is **constrained** when some constraint gives it a value (the
//!   first in the model's order; validation rejects a second, different
//!   value): `u_d = a(λ) ū_d`, with `a` the constraint's factor in the load
//!   history.
//! * A DOF constrained to zero is **fixed**: it gets no equation
//!   ([`ConstraintHandler::numbering`]).
//! * A DOF with a non-zero value keeps its equation and is eliminated
//!   symmetrically from each linear system ([`Elimination`], built on a
//!   numbering by [`ConstraintHandler::elimination`]).
//! * A **coupling** is a node pair the matrix pattern must hold beyond the
//!   elements' own (contact between bodies).
//!
//! The elimination lives here beside the data it applies, not in
//! `assembly`: it needs the load history (`setup::steps`) for `a(λ)`, and
//! `setup` may read `assembly` and `solver` (neither reads `setup`), so
//! the handler and its application stay one module without a cycle.

mod elimination;

pub use elimination::Elimination;

use crate::assembly::Numbering;
use crate::bc::Constraint;
use crate::contact::PairContact;
use crate::mesh::Mesh;
use crate::solver::linear::LinearError;

/// The value a constraint prescribes at one DOF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prescribed {
    /// The total value at load factor 1 (m); 0 for a fixed DOF.
    pub value: f64,
    /// Index of the constraint that prescribes it (in `Model::constraints`).
    pub constraint: usize,
}

/// Every constrained DOF and every extra coupling of a model (module docs).
#[derive(Debug, Clone, Default)]
pub struct ConstraintHandler {
    /// Number of DOFs (3 per node).
    n_dofs: usize,
    /// The constrained DOFs in increasing order, each with its value.
    constrained: Vec<(usize, Prescribed)>,
    /// Node pairs coupled by contact.
    couplings: Vec<(usize, usize)>,
}

impl ConstraintHandler {
    /// The handler of `constraints` (the file's and the symmetry planes')
    /// on `mesh`, with the couplings of `contacts` (`current`: nonlinear
    /// geometry, whose node pairs couple the master faces around them).
    pub fn new(mesh: &Mesh, constraints: &[Constraint], contacts: &[PairContact], current: bool) -> Self {
        let couplings = contacts.iter().flat_map(|c| c.couplings(mesh, current)).collect();
        Self::with_couplings(mesh.n_dofs(), constraints, couplings)
    }

    /// The handler of `constraints` on `n_dofs` DOFs with the given couplings.
    pub fn with_couplings(n_dofs: usize, constraints: &[Constraint], couplings: Vec<(usize, usize)>) -> Self {
        let mut value: std::collections::BTreeMap<usize, Prescribed> = Default::default();
        for (ci, c) in constraints.iter().enumerate() {
            for &n in &c.nodes {
                for (k, v) in c.values.iter().enumerate() {
                    if let Some(v) = *v {
                        value.entry(3 * n + k).or_insert(Prescribed { value: v, constraint: ci });
                    }
                }
            }
        }
        Self { n_dofs, constrained: value.into_iter().collect(), couplings }
    }

    /// Number of DOFs (constrained ones included).
    pub fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    /// The value prescribed at `dof`, `None` if it is free.
    pub fn prescribed(&self, dof: usize) -> Option<Prescribed> {
        self.constrained.binary_search_by_key(&dof, |c| c.0).ok().map(|i| self.constrained[i].1)
    }

    /// Every constrained DOF in increasing order, with its value.
    pub fn constrained(&self) -> impl Iterator<Item = (usize, Prescribed)> + '_ {
        self.constrained.iter().copied()
    }

    /// Per DOF: true if it is fixed (constrained to zero: no equation).
    pub fn fixed(&self) -> Vec<bool> {
        let mut fixed = vec![false; self.n_dofs];
        for (d, p) in self.constrained() {
            fixed[d] = p.value == 0.0;
        }
        fixed
    }

    /// The node pairs coupled by contact.
    pub fn couplings(&self) -> &[(usize, usize)] {
        &self.couplings
    }

    /// The equation numbering and pattern of `mesh` under these
    /// constraints: fixed DOFs left out, couplings added.
    pub fn numbering(&self, mesh: &Mesh) -> Result<Numbering, LinearError> {
        Numbering::new(mesh, &self.fixed(), &self.couplings)
    }

    /// The elimination of the non-zero prescribed DOFs on `numbering`
    /// (built by [`Self::numbering`]).
    pub fn elimination(&self, numbering: &Numbering) -> Elimination {
        Elimination::new(self.constrained(), numbering)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constraint(nodes: &[usize], values: [Option<f64>; 3]) -> Constraint {
        Constraint { name: "c".into(), body: 0, nodes: nodes.to_vec(), values, selection: None }
    }

    /// Overlapping sets: the first constraint in model order owns a DOF
    /// (as the reactions count it), zero values are fixed, non-zero ones
    /// keep their equation, free components stay free.
    #[test]
    fn the_first_constraint_owns_a_shared_dof() {
        let cs = [constraint(&[0, 1], [Some(0.0), None, None]), constraint(&[1, 2], [Some(0.0), Some(2e-3), None])];
        let h = ConstraintHandler::with_couplings(9, &cs, vec![(0, 2)]);
        let got: Vec<(usize, f64, usize)> = h.constrained().map(|(d, p)| (d, p.value, p.constraint)).collect();
        assert_eq!(got, [(0, 0.0, 0), (3, 0.0, 0), (4, 2e-3, 1), (6, 0.0, 1), (7, 2e-3, 1)]);
        assert_eq!(h.fixed(), [true, false, false, true, false, false, true, false, false]);
        assert_eq!(h.prescribed(4), Some(Prescribed { value: 2e-3, constraint: 1 }));
        assert_eq!(h.prescribed(5), None);
        assert_eq!(h.couplings(), [(0, 2)]);
    }
}
