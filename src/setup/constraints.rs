//! The constraint handler: every constraint on the degrees of freedom, in
//! one place, as Ferrite's `ConstraintHandler` or deal.II's
//! `AffineConstraints` hold them. Built once in setup from the model's
//! `[[constraints]]`, the symmetry planes' `u_n = 0` (which
//! `setup::preprocess` appends to them) and the contacts' couplings; the
//! agreement check of overlapping sets ([`ConstraintHandler::checked`]),
//! the numbering, the memory plan, the restraint check, the reactions, the
//! setup's checks of moving supports ([`ConstraintHandler::first_moving`])
//! and fully held bodies (`ConstraintHandler::holds_node`), the modal
//! free mass and the solution's elimination read it instead of deriving
//! the sets again. What still walks `Model::constraints` needs a
//! constraint as the user wrote it: its name and order (the per-set
//! tables and reports), its geometric selection (the CalculiX twin's own
//! mesh) or its load history.
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
//!   elements' own (contact between bodies, the twin nodes of a cohesive
//!   interface).
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

/// Two constraints prescribing different values to one DOF: what
/// [`ConstraintHandler::checked`] refuses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conflict {
    /// The DOF (`3 · node + component`).
    pub dof: usize,
    /// The later constraint (in model order) and the value it gives.
    pub given: Prescribed,
    /// The DOF's owner: the first constraint that gave it a value, and
    /// that value.
    pub owner: Prescribed,
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
    /// geometry, whose node pairs couple the master faces around them) and
    /// of the cohesive `interfaces` (their twin nodes).
    pub fn new(
        mesh: &Mesh,
        constraints: &[Constraint],
        contacts: (&[PairContact], &[crate::interfaces::Interface]),
        current: bool,
    ) -> Self {
        let mut handler = Self::with_couplings(mesh.n_dofs(), constraints, Vec::new());
        handler.couple(mesh, contacts, current);
        handler
    }

    /// The handler of `constraints` on `n_dofs` DOFs with the given couplings.
    pub(crate) fn with_couplings(n_dofs: usize, constraints: &[Constraint], couplings: Vec<(usize, usize)>) -> Self {
        Self { couplings, ..Self::resolve(n_dofs, constraints).0 }
    }

    /// The handler of `constraints` on `n_dofs` DOFs, without couplings
    /// (add them with `Self::couple`), or the first place where two of
    /// them disagree: walking the constraints in model order, node by node
    /// and component by component, the first value that differs from the
    /// one the DOF's owner gives.
    pub fn checked(n_dofs: usize, constraints: &[Constraint]) -> Result<Self, Conflict> {
        match Self::resolve(n_dofs, constraints) {
            (handler, None) => Ok(handler),
            (_, Some(conflict)) => Err(conflict),
        }
    }

    /// Adds the couplings of `contacts` and cohesive `interfaces` on `mesh`
    /// (`current` as in [`Self::new`]).
    pub(crate) fn couple(
        &mut self,
        mesh: &Mesh,
        (contacts, interfaces): (&[PairContact], &[crate::interfaces::Interface]),
        current: bool,
    ) {
        self.couplings.extend(contacts.iter().flat_map(|c| c.couplings(mesh, current)));
        self.couplings.extend(interfaces.iter().flat_map(|i| i.couplings()));
    }

    /// The constrained DOFs of `constraints` (the first constraint giving a
    /// DOF a value owns it) and the first conflict, if any.
    fn resolve(n_dofs: usize, constraints: &[Constraint]) -> (Self, Option<Conflict>) {
        let mut value: std::collections::BTreeMap<usize, Prescribed> = Default::default();
        let mut conflict = None;
        for (ci, c) in constraints.iter().enumerate() {
            for &n in &c.nodes {
                for (k, v) in c.values.iter().enumerate() {
                    let Some(v) = *v else { continue };
                    let given = Prescribed { value: v, constraint: ci };
                    let owner = *value.entry(3 * n + k).or_insert(given);
                    if owner.value != v && conflict.is_none() {
                        conflict = Some(Conflict { dof: 3 * n + k, given, owner });
                    }
                }
            }
        }
        (Self { n_dofs, constrained: value.into_iter().collect(), couplings: Vec::new() }, conflict)
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
    pub(crate) fn constrained(&self) -> impl Iterator<Item = (usize, Prescribed)> + '_ {
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

    /// True if all three components of `node` are constrained.
    pub(crate) fn holds_node(&self, node: usize) -> bool {
        (0..3).all(|k| self.prescribed(3 * node + k).is_some())
    }

    /// The first constraint (index in model order) that prescribes a
    /// non-zero value, `None` if every constrained DOF is fixed. It is the
    /// owner of the DOFs it moves: where constraints overlap they agree
    /// ([`Self::checked`]), so no earlier one gives those DOFs a value.
    pub fn first_moving(&self) -> Option<usize> {
        self.constrained().filter(|(_, p)| p.value != 0.0).map(|(_, p)| p.constraint).min()
    }

    /// The node pairs coupled by contact.
    #[cfg(test)]
    pub(crate) fn couplings(&self) -> &[(usize, usize)] {
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

    /// `checked` walks the constraints in model order and reports the
    /// first value that differs from the DOF's owner, naming the owner
    /// (the first to give the DOF a value), not a later set that agreed
    /// with it; `first_moving` is the smallest constraint index with a
    /// non-zero value, not the one at the lowest DOF; `holds_node` needs
    /// all three components.
    #[test]
    fn conflicts_name_the_owner_and_the_first_mover_is_in_model_order() {
        let agree = [
            constraint(&[2], [None, None, Some(1e-3)]),
            constraint(&[0, 2], [Some(0.0), Some(0.0), Some(1e-3)]),
            constraint(&[0], [Some(0.0), Some(0.0), None]),
        ];
        let h = ConstraintHandler::checked(9, &agree).unwrap();
        assert_eq!(h.first_moving(), Some(0));
        assert_eq!((h.holds_node(0), h.holds_node(1), h.holds_node(2)), (true, false, true));
        let fixed = [constraint(&[0], [Some(0.0), None, Some(0.0)]), constraint(&[0, 1], [None, Some(0.0), None])];
        let h = ConstraintHandler::checked(6, &fixed).unwrap();
        assert_eq!(h.first_moving(), None);
        assert_eq!((h.holds_node(0), h.holds_node(1)), (true, false));
        let mut clash = agree.to_vec();
        clash.push(constraint(&[1, 2], [None, None, Some(2e-3)]));
        clash.push(constraint(&[0], [Some(1e-3), None, None]));
        let conflict = ConstraintHandler::checked(9, &clash).unwrap_err();
        let owner = Prescribed { value: 1e-3, constraint: 0 };
        assert_eq!(conflict, Conflict { dof: 8, given: Prescribed { value: 2e-3, constraint: 3 }, owner });
        // unchecked, the first value stands
        let h = ConstraintHandler::with_couplings(9, &clash, Vec::new());
        assert_eq!(h.prescribed(8), Some(owner));
        assert_eq!(h.prescribed(0), Some(Prescribed { value: 0.0, constraint: 1 }));
    }
}
