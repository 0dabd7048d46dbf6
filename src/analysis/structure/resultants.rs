//! The structure's named resultants: constraint reactions and contact
//! forces, from the imbalance and the contact points of the last evaluation.

use super::{ContactKind, ContactPoint, ContactResultant, Reaction, Structure};

impl Structure<'_> {
    /// Resultant reaction of each constraint set (force of the support on
    /// the body): the imbalance at the components the set prescribes. A DOF
    /// prescribed by several sets (an edge shared by two faces) counts once,
    /// for the set the constraint handler gives it (the first in the model
    /// file), so that the reactions sum to the support force.
    pub fn reactions(&self) -> Vec<Reaction> {
        self.loading
            .constraints
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let mut force = [0.0; 3];
                for &n in &c.nodes {
                    for (k, f) in force.iter_mut().enumerate() {
                        let dof = 3 * n + k;
                        if self.constraints.prescribed(dof).is_some_and(|p| p.constraint == i) {
                            *f += self.nodal_imbalance(dof);
                        }
                    }
                }
                Reaction { name: c.name.clone(), force }
            })
            .collect()
    }

    /// Per indenter, then per pair contact: resultant force on the body (on
    /// the slave body for pairs) and largest penetration.
    pub fn contact_resultants(&self) -> Vec<ContactResultant> {
        let offsets: Vec<[f64; 3]> = self.force.offsets(self.state.lambda).collect();
        self.contact_sets()
            .enumerate()
            .map(|(k, (name, kind, points))| {
                let mut force = [0.0; 3];
                let mut normal_force = [0.0; 3];
                let mut max_penetration: f64 = 0.0;
                for p in points {
                    let n = p.normal;
                    let fn_ = p.force[0] * n[0] + p.force[1] * n[1] + p.force[2] * n[2];
                    for c in 0..3 {
                        force[c] += p.force[c];
                        normal_force[c] += fn_ * n[c];
                    }
                    if p.active {
                        max_penetration = max_penetration.max(-p.gap);
                    }
                }
                let tangential_force = std::array::from_fn(|c| force[c] - normal_force[c]);
                let displacement = if kind == ContactKind::Indenter { offsets[k] } else { [0.0; 3] };
                ContactResultant {
                    name: name.to_string(),
                    kind,
                    force,
                    normal_force,
                    tangential_force,
                    max_penetration,
                    displacement,
                }
            })
            .collect()
    }

    /// The contact points of each indenter, then of each pair contact, by name.
    pub fn contact_sets(&self) -> impl Iterator<Item = (&str, ContactKind, &[ContactPoint])> {
        let names = self
            .loading
            .indenters
            .iter()
            .map(|i| (i.name.as_str(), ContactKind::Indenter))
            .chain(self.loading.contacts.iter().map(|c| (c.name.as_str(), ContactKind::Pair)));
        let points = self.parts.contacts.points();
        names.zip(self.parts.contacts.ranges()).map(move |((name, kind), r)| (name, kind, &points[r.clone()]))
    }
}
