//! The structure's named resultants: constraint reactions and contact
//! forces, from the imbalance and the contact points of the last evaluation.

use super::{ContactKind, ContactPoint, ContactResultant, Reaction, Structure};

impl Structure<'_> {
    /// Resultant reaction of each constraint set (force of the support on
    /// the body): the imbalance at the DOFs the constraint handler gives
    /// it. A DOF prescribed by several sets (an edge shared by two faces)
    /// counts once, for its owner (the first in the model file), so that
    /// the reactions sum to the support force.
    pub fn reactions(&self) -> Vec<Reaction> {
        let mut force = vec![[0.0; 3]; self.loading.constraints.len()];
        for (dof, p) in self.constraints.constrained() {
            if let Some(f) = force.get_mut(p.constraint) {
                f[dof % 3] += self.nodal_imbalance(dof);
            }
        }
        let names = self.loading.constraints.iter().map(|c| c.name.clone());
        names.zip(force).map(|(name, force)| Reaction { name, force }).collect()
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

#[cfg(test)]
mod tests {
    use crate::setup::{Limits, Model};

    /// A cantilever clamped at its root by two overlapping sets: "edge"
    /// (the root's bottom edge, z fixed) is given first, "root" (the whole
    /// root face) second, and a prescribed tip displacement as a third set
    /// on the same tip nodes as a z-fix ("tip_guard", overlapping it).
    const MODEL: &str = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "beam"
material = "steel"
section = { shape = "rectangle", element = "L4", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.0, to = 0.04, elements = 2 } }
axis = { element = "B3", from = 0.0, to = 0.5, elements = 4 }

[[constraints]]
name = "edge"
body = "beam"
where = { y = 0.0, z = 0.0 }
fix = ["z"]

[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]

[[constraints]]
name = "tip"
body = "beam"
where = { y = 0.5 }
displacement = { z = -1e-3 }

[[constraints]]
name = "tip_guard"
body = "beam"
where = { y = 0.5, z = 0.0 }
displacement = { z = -1e-3 }

[[loads]]
name = "side"
body = "beam"
where = { y = 0.5 }
total_force = [250.0, 0.0, 0.0]
"#;

    /// Each constrained DOF is counted for the one set that owns it (the
    /// first in the file), so the reactions balance the applied load and the
    /// prescribed motion's support force to round-off (static equilibrium of
    /// the free body: Σ reactions + Σ loads = 0), and a set that owns no DOF
    /// of its own ("tip_guard", all its nodes already in "tip") reports zero.
    #[test]
    fn reactions_count_a_shared_dof_once_and_balance_the_loads() {
        let model = Model::parse_with(MODEL, Limits::none()).unwrap();
        let sol = crate::analysis::run(&model, &Default::default(), &mut crate::analysis::Silent).unwrap();
        assert!(sol.failure.is_none());
        let by_name = |n: &str| sol.reactions.iter().find(|r| r.name == n).unwrap().force;
        assert_eq!(by_name("tip_guard"), [0.0; 3]);
        // the edge owns its z components: it carries part of the root's force
        assert!(by_name("edge")[2].abs() > 0.0);
        let scale = by_name("tip")[2].abs().max(250.0);
        for k in 0..3 {
            let sum: f64 = sol.reactions.iter().map(|r| r.force[k]).sum::<f64>() + sol.applied[k];
            assert!(sum.abs() <= 1e-9 * scale, "component {k}: Σ reactions + loads = {sum:e} (scale {scale:e})");
        }
    }
}
