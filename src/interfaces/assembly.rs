//! The interfaces as a part of the structure's residual and tangent: at
//! each point the separation `δ = u_upper − u_lower`, the cohesive law's
//! traction `t` and tangent `D`, the forces `±A t` (internal: the point
//! resists the separation) and the blocks `A D` on the two nodes and `−A D`
//! between them. The points' damage is trial history until the increment
//! converges.
//!
//! **Viscous work.** With Duvaut–Lions viscosity the traction is the
//! secant's of the viscous damage `d_v ≤ d`, above the law's by the
//! over-stress `σ_v = (d − d_v) K δ̂`. Its work `∫ σ_v · dδ` (trapezoidal
//! over the converged increments) is energy the law's dissipation
//! (`dissipated_j`) does not hold: the work done on an interface is its
//! elastic energy plus `dissipated_j` plus `viscous_j`.

use super::Interface;
use crate::assembly::{At, Contribution, Forces, Phase, Tangent};
use crate::materials::Predictor;
use crate::materials::cohesive::{Cohesive, CohesiveState};

/// Every cohesive interface of a model, with its points' history.
#[derive(Debug)]
pub struct Interfaces<'m> {
    interfaces: &'m [Interface],
    /// The points' committed states, interface by interface.
    committed: Vec<Vec<CohesiveState>>,
    /// Their states at the last evaluation.
    trial: Vec<Vec<CohesiveState>>,
    /// Whether each point's damage grew in the last evaluation (its branch
    /// of the law: softening, or elastic on its secant).
    growing: Vec<Vec<bool>>,
    /// Internal forces of the last evaluation, per DOF.
    forces: Vec<f64>,
    /// The viscous damage `d_v` that carries the traction (the law's
    /// damage where the law has no viscosity), committed and trial.
    viscous: [Vec<Vec<f64>>; 2],
    /// The load factor of the last converged increment.
    lambda: f64,
    /// The clock of a transient run (`None` in a static one): the
    /// viscosity's step is then in seconds, as the ply damage's.
    clock: Option<&'m crate::dynamics::TransientSettings>,
    /// Each point's viscous over-stress and separation `[σ_v, δ]`,
    /// committed and trial (`[0; 6]` at the start).
    over: [Vec<Vec<[f64; 6]>>; 2],
    /// Each point's work of the viscous over-stress so far (J/m²).
    viscous_work: Vec<Vec<f64>>,
    /// Each point's separation at the last converged increment, `δ_n`.
    separation: Vec<Vec<[f64; 3]>>,
    /// Each interface's first onset: the load factor (a transient run's
    /// time) of the first converged increment after which a point that
    /// was not precracked had damaged.
    onset: Vec<Option<f64>>,
    /// Each point's dissipation over the present step under the discrete
    /// gradient (`analysis.interface_forces = "discrete_gradient"`),
    /// `t*·Δδ − Δψ` (J/m², trial).
    booked: Vec<Vec<f64>>,
}

/// What an interface has become: its delaminated area and the energy it
/// dissipated (`summary.json` `delamination.interfaces`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct InterfaceSummary {
    /// The interface's name.
    pub name: String,
    /// The body's index (0-based, in the order of `[[bodies]]`).
    pub body: usize,
    /// The body's name.
    pub body_name: String,
    /// Its whole area (m²).
    pub area_m2: f64,
    /// Area of the points with d = 1 (m²).
    pub delaminated_m2: f64,
    /// Area of the points with 0 < d < 1: the process zone (m²).
    pub process_zone_m2: f64,
    /// Energy dissipated by the law, `Σ A g` (J).
    pub dissipated_j: f64,
    /// Work of the Duvaut–Lions over-stress (J; 0 without viscosity):
    /// dissipated beyond `dissipated_j`.
    pub viscous_j: f64,
    /// The largest onset index `(⟨t3⟩/N)² + (t_s/S)²` of the intact
    /// traction `K δ` over its points not yet separated (d < 1) at the end
    /// (`Cohesive::onset_index`): below 1 where no point has started to
    /// damage, how close the interface is to delaminating (the
    /// interlaminar index of a cohesive interface); 0 where every point
    /// has separated.
    pub largest_onset_index: f64,
    /// The load factor of the first converged increment after which a
    /// point (not precracked) had damaged: where the onset index first
    /// reached 1 (`None`: none has, or a transient run).
    pub first_onset_load_factor: Option<f64>,
    /// The same time in a transient run (s).
    pub first_onset_time_s: Option<f64>,
}

/// The interfaces at the end of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Delamination {
    /// Each interface's summary.
    pub interfaces: Vec<InterfaceSummary>,
    /// Each interface's name and its points' damage.
    pub damage: Vec<(String, Vec<PointDamage>)>,
}

/// The damage of an interface point: `(lower node, upper node, d, onset
/// index)`, the index `(⟨t3⟩/N)² + (t_s/S)²` of the intact traction at its
/// committed separation (`Cohesive::onset_index`; 0 once separated, d = 1).
pub type PointDamage = (usize, usize, f64, f64);

/// `summary.json` `delamination`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DelaminationSummary {
    /// Every interface.
    pub interfaces: Vec<InterfaceSummary>,
    /// The delaminated area (d = 1) of all of them (m²).
    pub area_m2: f64,
    /// The energy their law dissipated (J).
    pub dissipated_j: f64,
    /// The work of their viscous over-stress (J).
    pub viscous_j: f64,
}

impl Delamination {
    /// Its `summary.json` entry.
    pub fn summary(&self) -> DelaminationSummary {
        DelaminationSummary {
            interfaces: self.interfaces.clone(),
            area_m2: self.interfaces.iter().map(|i| i.delaminated_m2).sum(),
            dissipated_j: self.interfaces.iter().map(|i| i.dissipated_j).sum(),
            viscous_j: self.interfaces.iter().map(|i| i.viscous_j).sum(),
        }
    }

    /// The damage and the onset index at each interface node (both twins
    /// of a point), for the `d_interface` and `onset_interface` fields.
    pub fn node_damage(&self) -> std::collections::HashMap<usize, (f64, f64)> {
        let mut out = std::collections::HashMap::new();
        for (_, points) in &self.damage {
            for &(l, u, d, onset) in points {
                out.insert(l, (d, onset));
                out.insert(u, (d, onset));
            }
        }
        out
    }
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
        let growing = committed.iter().map(|c| vec![false; c.len()]).collect();
        let viscous: Vec<Vec<f64>> = committed.iter().map(|c| c.iter().map(|s| s.damage).collect()).collect();
        let over: Vec<Vec<[f64; 6]>> = committed.iter().map(|c| vec![[0.0; 6]; c.len()]).collect();
        let viscous_work: Vec<Vec<f64>> = committed.iter().map(|c| vec![0.0; c.len()]).collect();
        let separation = committed.iter().map(|c| vec![[0.0; 3]; c.len()]).collect();
        Self {
            interfaces,
            trial: committed.clone(),
            committed,
            growing,
            forces,
            viscous: [viscous.clone(), viscous],
            lambda: 0.0,
            clock: None,
            over: [over.clone(), over],
            booked: viscous_work.clone(),
            viscous_work,
            separation,
            onset: vec![None; interfaces.len()],
        }
    }

    /// The same interfaces in a transient run: their viscosity in seconds
    /// of `clock`'s time (in load-factor units without it).
    pub fn in_time(mut self, clock: Option<&'m crate::dynamics::TransientSettings>) -> Self {
        self.clock = clock;
        self
    }

    /// The largest increment of the carried damage `d_v` at any point
    /// since the committed state (the law's damage without viscosity; 0
    /// without interfaces): the step control's `damage` measure.
    pub fn largest_damage_increment(&self) -> f64 {
        let [committed, trial] = &self.viscous;
        committed.iter().zip(trial).flat_map(|(c, t)| c.iter().zip(t).map(|(a, b)| b - a)).fold(0.0, f64::max)
    }

    /// True if the model has cohesive interfaces.
    pub fn is_active(&self) -> bool {
        !self.interfaces.is_empty()
    }

    /// The committed damage of every point, interface by interface.
    pub fn damage(&self) -> impl Iterator<Item = (&'m Interface, Vec<f64>)> + '_ {
        self.interfaces.iter().zip(&self.committed).map(|(i, s)| (i, s.iter().map(|s| s.damage).collect()))
    }

    /// The committed state of every interface: its summary and its
    /// points' damage.
    pub fn delamination(&self) -> Option<Delamination> {
        self.is_active().then(|| Delamination {
            interfaces: self.summaries(),
            damage: self
                .interfaces
                .iter()
                .zip(self.committed.iter().zip(&self.separation))
                .map(|(i, (states, separations))| {
                    let points = i.points.iter().zip(states.iter().zip(separations));
                    let point = points.map(|(p, (st, d))| (p.lower, p.upper, st.damage, onset_index(&i.law, st, *d)));
                    (i.name.clone(), point.collect())
                })
                .collect(),
        })
    }

    /// The energy the interfaces hold at displacements `u` with the damage
    /// of the last evaluation (the converged state's, before it is
    /// committed), `Σ A ½ t·δ` (J): the law unloads to the origin on its
    /// secant, so this is what they give back; the rest of their work is
    /// dissipated (the energy ledger's `delamination`).
    pub fn stored_energy(&self, u: &[f64]) -> f64 {
        let carried = self.interfaces.iter().zip(&self.viscous[1]);
        let mut stored = 0.0;
        for (interface, dv) in carried {
            for (p, &d) in interface.points.iter().zip(dv) {
                let delta: [f64; 3] = std::array::from_fn(|k| u[3 * p.upper + k] - u[3 * p.lower + k]);
                let k = secant(&interface.law, &CohesiveState { damage: d, dissipated: 0.0 }, delta);
                stored += p.area * 0.5 * (0..3).map(|i| k[i][i] * delta[i] * delta[i]).sum::<f64>();
            }
        }
        stored
    }

    /// The committed delaminated area of every interface together (m²; the
    /// points with d = 1), `None` without interfaces.
    pub fn delaminated_area(&self) -> Option<f64> {
        self.delamination().map(|d| d.summary().area_m2)
    }

    /// Each interface's delaminated area and dissipated energy (committed).
    pub fn summaries(&self) -> Vec<InterfaceSummary> {
        self.interfaces
            .iter()
            .zip(self.committed.iter().zip(&self.viscous_work).zip(&self.separation))
            .zip(&self.onset)
            .map(|((i, ((states, work), separations)), &onset)| {
                let mut s = InterfaceSummary {
                    name: i.name.clone(),
                    body: i.body,
                    body_name: i.body_name.clone(),
                    area_m2: i.area(),
                    delaminated_m2: 0.0,
                    process_zone_m2: 0.0,
                    dissipated_j: 0.0,
                    viscous_j: i.points.iter().zip(work).map(|(p, w)| p.area * w).sum(),
                    largest_onset_index: separations
                        .iter()
                        .zip(states)
                        .map(|(&d, st)| onset_index(&i.law, st, d))
                        .fold(0.0, f64::max),
                    first_onset_load_factor: onset.filter(|_| self.clock.is_none()),
                    first_onset_time_s: onset.filter(|_| self.clock.is_some()),
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

/// The secant of the law at `state` and separation `delta`: `(1 − d) K`,
/// and `K` across a closing interface. Newton takes it in the cautious
/// retry of a failed increment ([`Predictor::Elastic`]): a point cycling
/// between its softening and its unloading tangent from one iteration to
/// the next (measured on examples/dcb.toml) converges on its secant.
/// A point's onset index at its committed separation `d`
/// (`Cohesive::onset_index`), 0 once it has separated (d = 1).
fn onset_index(law: &Cohesive, state: &CohesiveState, d: [f64; 3]) -> f64 {
    if state.damage < 1.0 { law.onset_index(d) } else { 0.0 }
}

fn secant(law: &Cohesive, state: &CohesiveState, delta: [f64; 3]) -> [[f64; 3]; 3] {
    let soft = (1.0 - state.damage) * law.penalty;
    let closing = if law.is_closed(delta[2]) { law.penalty } else { soft };
    [[soft, 0.0, 0.0], [0.0, soft, 0.0], [0.0, 0.0, closing]]
}

/// Duvaut–Lions regularisation of a point's response `r` (design48 §2.3,
/// §2.4): the damage that carries the traction relaxes towards the law's
/// `d` over the viscosity `eta` (load-factor units, or seconds in a transient run), implicitly,
/// `d_v = (η d_v,n + Δλ d)/(η + Δλ)` (into `dv`), so `d_v ≤ d` and it never
/// decreases; the traction is the secant's of `d_v` and the tangent's
/// softening part is scaled by `Δλ/(η + Δλ)`. The over-stress above the
/// law's traction does work the law's dissipation does not count (the
/// module's `viscous_j`).
fn regularise(
    law: &Cohesive,
    r: &mut crate::materials::cohesive::CohesiveResponse,
    delta: [f64; 3],
    (dv_n, dv): (f64, &mut f64),
    eta: f64,
    dt: f64,
) {
    let d = r.state.damage;
    *dv = (eta * dv_n + dt * d) / (eta + dt);
    let w = dt / (eta + dt);
    let viscous = secant(law, &CohesiveState { damage: *dv, dissipated: 0.0 }, delta);
    let plain = secant(law, &r.state, delta);
    for k in 0..3 {
        r.traction[k] = viscous[k][k] * delta[k];
        for l in 0..3 {
            r.tangent[k][l] = viscous[k][l] + w * (r.tangent[k][l] - plain[k][l]);
        }
    }
}

/// The law's response at separation `delta` from the committed state
/// `old`, regularised over the step `dt` where the law has a viscosity
/// (`dv_n` the committed viscous damage), with the damage that carries the
/// traction.
fn respond(
    law: &Cohesive,
    delta: [f64; 3],
    old: &CohesiveState,
    dv_n: f64,
    dt: f64,
) -> (crate::materials::cohesive::CohesiveResponse, f64) {
    let mut r = law.update(delta, old);
    let mut dv = r.state.damage;
    if law.viscosity > 0.0 {
        regularise(law, &mut r, delta, (dv_n, &mut dv), law.viscosity, dt);
    }
    (r, dv)
}

/// The energy a point holds at separation `delta` under the carried damage
/// `d`, `ψ = ½ K ⟨−δ3⟩² + ½ (1 − d) K (⟨δ3⟩² + |δ_s|²)` (J/m²).
fn held(law: &Cohesive, d: f64, delta: [f64; 3]) -> f64 {
    let k = secant(law, &CohesiveState { damage: d, dissipated: 0.0 }, delta);
    0.5 * (0..3).map(|i| k[i][i] * delta[i] * delta[i]).sum::<f64>()
}

/// The discrete-gradient traction of a point over the step from
/// `(δ_n, d_v,n)` (`start`) to `delta` (module docs of
/// `crate::dynamics::impulse`): `t* = t + (Δψ + ΔD − t·Δδ)/|Δδ|² Δδ`, with
/// `t` the end-of-step traction and `ΔD` the law's dissipation over the
/// step (without viscosity) or the carried damage's, `½ K |δ̂|² Δd_v`
/// averaged over both ends (with it). Returns `t*` and the dissipation its
/// work books, `t*·Δδ − Δψ` (`ΔD`, or the end-of-step traction's where the
/// step is too short to carry a correction).
fn discrete_gradient(
    law: &Cohesive,
    delta: [f64; 3],
    old: &CohesiveState,
    start: ([f64; 3], f64),
    dt: f64,
) -> ([f64; 3], f64) {
    let (delta_n, dv_n) = start;
    let (r, dv) = respond(law, delta, old, dv_n, dt);
    let stored = held(law, dv, delta) - held(law, dv_n, delta_n);
    let dissipated = if law.viscosity > 0.0 {
        0.5 * (held(law, dv_n, delta_n) - held(law, dv, delta_n) + held(law, dv_n, delta) - held(law, dv, delta))
    } else {
        r.state.dissipated - old.dissipated
    };
    let step: [f64; 3] = std::array::from_fn(|k| delta[k] - delta_n[k]);
    let length2: f64 = step.iter().map(|s| s * s).sum();
    let work: f64 = (0..3).map(|k| r.traction[k] * step[k]).sum();
    let tiny = 1e-9 * law.normal_strength / law.penalty;
    if length2 <= tiny * tiny {
        return (r.traction, work - stored);
    }
    let c = (stored + dissipated - work) / length2;
    (std::array::from_fn(|k| r.traction[k] + c * step[k]), dissipated)
}

/// The symmetric part of `∂t*/∂δ` of [`discrete_gradient`] by central
/// differences (three components, six evaluations of the law).
fn discrete_tangent(
    law: &Cohesive,
    delta: [f64; 3],
    old: &CohesiveState,
    start: ([f64; 3], f64),
    dt: f64,
) -> [[f64; 3]; 3] {
    let size = delta.iter().chain(&start.0).fold(law.normal_strength / law.penalty, |m, x| m.max(x.abs()));
    let h = 1e-6 * size;
    let mut d = [[0.0; 3]; 3];
    for j in 0..3 {
        let at = |s: f64| {
            let mut x = delta;
            x[j] += s;
            discrete_gradient(law, x, old, start, dt).0
        };
        let (plus, minus) = (at(h), at(-h));
        for i in 0..3 {
            d[i][j] = (plus[i] - minus[i]) / (2.0 * h);
        }
    }
    std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (d[i][j] + d[j][i])))
}

impl Contribution for Interfaces<'_> {
    fn phase(&self) -> Phase {
        Phase::Interfaces
    }

    /// In the cautious retry of a failed increment each point takes its
    /// secant ([`secant`]). Returns the points whose branch (damage growing or not) differs
    /// from the last evaluation's: the residual is not smooth there, as
    /// where a contact opens or closes.
    fn evaluate(&mut self, at: &At<'_>, tangent: &mut Tangent<'_>) -> usize {
        if self.interfaces.is_empty() {
            return 0;
        }
        self.forces.fill(0.0);
        let mut changes = 0;
        let dt = match self.clock {
            Some(clock) => (clock.time(at.lambda) - clock.time(self.lambda)).abs(),
            None => at.viscous_step.unwrap_or((at.lambda - self.lambda).abs()),
        };
        let gradient =
            self.clock.is_some_and(|c| c.interface_forces == crate::dynamics::InterfaceForces::DiscreteGradient);
        for (i, interface) in self.interfaces.iter().enumerate() {
            let law = &interface.law;
            for (j, p) in interface.points.iter().enumerate() {
                let delta: [f64; 3] = std::array::from_fn(|k| at.u[3 * p.upper + k] - at.u[3 * p.lower + k]);
                let old = &self.committed[i][j];
                let dv_n = self.viscous[0][i][j];
                let (r, dv) = respond(law, delta, old, dv_n, dt);
                self.viscous[1][i][j] = dv;
                if law.viscosity > 0.0 {
                    let plain = law.update(delta, old).traction;
                    self.over[1][i][j] =
                        std::array::from_fn(|k| if k < 3 { r.traction[k] - plain[k] } else { delta[k - 3] });
                }
                let start = (self.separation[i][j], dv_n);
                let traction = if gradient {
                    let (t, booked) = discrete_gradient(law, delta, old, start, dt);
                    self.booked[i][j] = booked;
                    t
                } else {
                    r.traction
                };
                let now = r.state.damage > old.damage;
                changes += usize::from(now != self.growing[i][j]);
                self.growing[i][j] = now;
                self.trial[i][j] = r.state;
                for k in 0..3 {
                    self.forces[3 * p.upper + k] += p.area * traction[k];
                    self.forces[3 * p.lower + k] -= p.area * traction[k];
                }
                if tangent.wanted {
                    let d = if at.predictor == Predictor::Elastic {
                        secant(law, &r.state, delta)
                    } else if gradient {
                        discrete_tangent(law, delta, old, start, dt)
                    } else {
                        r.tangent
                    };
                    let block = d.map(|row| row.map(|v| p.area * v));
                    tangent.add_node_block(p.upper, p.upper, &block);
                    tangent.add_node_block(p.lower, p.lower, &block);
                    tangent.add_node_block(p.upper, p.lower, &block.map(|row| row.map(|v| -v)));
                }
            }
        }
        changes
    }

    fn forces(&self) -> Forces<'_> {
        Forces { values: &self.forces, sign: 1.0, scale: false, reference: 0.0 }
    }

    /// Keeps the trial state: damage (the law's and the viscous one) never
    /// decreases (a debug assertion: a damaged point is never healed), and
    /// the over-stress's work of the increment is added (trapezoidal in δ).
    fn commit(&mut self, at: &At<'_>) {
        let gradient =
            self.clock.is_some_and(|c| c.interface_forces == crate::dynamics::InterfaceForces::DiscreteGradient);
        let [before, after] = &mut self.over;
        for (i, interface) in self.interfaces.iter().enumerate() {
            for (j, p) in interface.points.iter().enumerate() {
                let (c, t) = (&self.committed[i][j], &self.trial[i][j]);
                debug_assert!(t.damage >= c.damage, "interface damage decreased");
                debug_assert!(self.viscous[1][i][j] >= self.viscous[0][i][j], "viscous interface damage decreased");
                let w = &mut self.viscous_work[i][j];
                if gradient {
                    // the discrete gradient's dissipation beyond the law's
                    *w += self.booked[i][j] - (t.dissipated - c.dissipated);
                } else {
                    let (b, a) = (&before[i][j], &after[i][j]);
                    *w += (0..3).map(|k| 0.5 * (b[k] + a[k]) * (a[k + 3] - b[k + 3])).sum::<f64>();
                }
                before[i][j] = after[i][j];
                self.committed[i][j] = *t;
                self.viscous[0][i][j] = self.viscous[1][i][j];
                self.separation[i][j] = std::array::from_fn(|k| at.u[3 * p.upper + k] - at.u[3 * p.lower + k]);
            }
        }
        let now = self.clock.map_or(at.lambda, |c| c.time(at.lambda));
        for ((interface, states), onset) in self.interfaces.iter().zip(&self.committed).zip(&mut self.onset) {
            if onset.is_none() && interface.points.iter().zip(states).any(|(p, st)| !p.cracked && st.damage > 0.0) {
                *onset = Some(now);
            }
        }
        self.lambda = at.lambda;
        self.growing.iter_mut().for_each(|g| g.fill(false));
    }

    fn restore(&mut self) {
        for (c, t) in self.committed.iter().zip(&mut self.trial) {
            t.copy_from_slice(c);
        }
        self.growing.iter_mut().for_each(|g| g.fill(false));
    }

    /// Without interfaces it adds nothing.
    fn tangent_unchanged(&self, _at: &At<'_>) -> bool {
        self.interfaces.is_empty()
    }
}
