//! The interfaces as a part of the structure's residual and tangent: at
//! each point the separation `δ = u_upper − u_lower`, the cohesive law's
//! traction `t` and tangent `D`, the forces `±A t` (internal: the point
//! resists the separation) and the blocks `A D` on the two nodes and `−A D`
//! between them. The points' damage is trial history until the increment
//! converges.

use super::Interface;
use crate::assembly::{At, Contribution, Forces, Phase, Tangent};
use crate::materials::cohesive::CohesiveState;

/// Every cohesive interface of a model, with its points' history.
#[derive(Debug)]
pub struct Interfaces<'m> {
    interfaces: &'m [Interface],
    /// The points' committed states, interface by interface.
    committed: Vec<Vec<CohesiveState>>,
    /// Their states at the last evaluation.
    trial: Vec<Vec<CohesiveState>>,
    /// Internal forces of the last evaluation, per DOF.
    forces: Vec<f64>,
}

/// What an interface has become: its delaminated area and the energy it
/// dissipated.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceSummary {
    /// The interface's name.
    pub name: String,
    /// The body's index.
    pub body: usize,
    /// Its whole area (m²).
    pub area_m2: f64,
    /// Area of the points with d = 1 (m²).
    pub delaminated_m2: f64,
    /// Area of the points with 0 < d < 1: the process zone (m²).
    pub process_zone_m2: f64,
    /// Energy dissipated, `Σ A g` (J).
    pub dissipated_j: f64,
}

impl<'m> Interfaces<'m> {
    /// The interfaces of a model with `n_dofs` DOFs, intact but for their
    /// precracks.
    pub fn new(interfaces: &'m [Interface], n_dofs: usize) -> Self {
        let committed: Vec<Vec<CohesiveState>> = interfaces
            .iter()
            .map(|i| {
                i.points
                    .iter()
                    .map(|p| CohesiveState { damage: if p.cracked { 1.0 } else { 0.0 }, dissipated: 0.0 })
                    .collect()
            })
            .collect();
        let forces = if interfaces.is_empty() { Vec::new() } else { vec![0.0; n_dofs] };
        Self { interfaces, trial: committed.clone(), committed, forces }
    }

    /// The committed damage of every point, interface by interface.
    pub fn damage(&self) -> impl Iterator<Item = (&'m Interface, Vec<f64>)> + '_ {
        self.interfaces.iter().zip(&self.committed).map(|(i, s)| (i, s.iter().map(|s| s.damage).collect()))
    }

    /// Each interface's delaminated area and dissipated energy (committed).
    pub fn summaries(&self) -> Vec<InterfaceSummary> {
        self.interfaces
            .iter()
            .zip(&self.committed)
            .map(|(i, states)| {
                let mut s = InterfaceSummary {
                    name: i.name.clone(),
                    body: i.body,
                    area_m2: i.area(),
                    delaminated_m2: 0.0,
                    process_zone_m2: 0.0,
                    dissipated_j: 0.0,
                };
                for (p, st) in i.points.iter().zip(states) {
                    if st.damage >= 1.0 {
                        s.delaminated_m2 += p.area;
                    } else if st.damage > 0.0 {
                        s.process_zone_m2 += p.area;
                    }
                    s.dissipated_j += p.area * st.dissipated;
                }
                s
            })
            .collect()
    }
}

impl Contribution for Interfaces<'_> {
    fn phase(&self) -> Phase {
        Phase::Elements
    }

    /// Returns the points whose damage started in this increment: the
    /// law's branch changed there, as a contact's status does.
    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize {
        if self.interfaces.is_empty() {
            return 0;
        }
        self.forces.fill(0.0);
        let mut onsets = 0;
        for ((interface, committed), trial) in self.interfaces.iter().zip(&self.committed).zip(&mut self.trial) {
            for ((p, old), new) in interface.points.iter().zip(committed).zip(trial.iter_mut()) {
                let delta: [f64; 3] = std::array::from_fn(|k| at.u[3 * p.upper + k] - at.u[3 * p.lower + k]);
                let r = interface.law.update(delta, old);
                onsets += usize::from(old.damage == 0.0 && r.state.damage > 0.0);
                *new = r.state;
                for k in 0..3 {
                    self.forces[3 * p.upper + k] += p.area * r.traction[k];
                    self.forces[3 * p.lower + k] -= p.area * r.traction[k];
                }
                if tangent.wanted {
                    let block = r.tangent.map(|row| row.map(|v| p.area * v));
                    tangent.add_node_block(p.upper, p.upper, &block);
                    tangent.add_node_block(p.lower, p.lower, &block);
                    tangent.add_node_block(p.upper, p.lower, &block.map(|row| row.map(|v| -v)));
                }
            }
        }
        onsets
    }

    fn forces(&self) -> Forces<'_> {
        Forces { values: &self.forces, sign: 1.0, scale: false, reference: 0.0 }
    }

    fn commit(&mut self, _at: &At<'_>) {
        for (c, t) in self.committed.iter_mut().zip(&self.trial) {
            debug_assert!(c.iter().zip(t).all(|(c, t)| t.damage >= c.damage), "interface damage decreased");
            c.copy_from_slice(t);
        }
    }

    fn restore(&mut self) {
        for (c, t) in self.committed.iter().zip(&mut self.trial) {
            t.copy_from_slice(c);
        }
    }
}
