//! Progressive ply damage in the bodies: the Gauss-point history of the
//! damage law ([`crate::materials::damage`]) of every point whose material
//! damages, its crack-band lengths, and what a run reports of it.
//!
//! * **History.** One [`DamageState`] per Gauss point (the layout of the
//!   plastic states: body `b`'s first point at `gp_offsets[b]`, element `e`'s
//!   at `+ e · points per element`), committed and trial: the element
//!   kernel reads the committed states and writes the trial ones; they are
//!   committed only when an increment converges (a failed increment is
//!   evaluated again from the committed ones, so a cutback restores them).
//!   Empty when no material damages.
//! * **Crack band** (Bažant & Oh 1983). Oliver's projected element size
//!   (1989, IJNME 28:461) at each Gauss point, from the kernel's own 3D
//!   gradients: `L(n) = 2 / Σ_a |∇N_a · n|`, with `n` the crack normal,
//!   material axis 1 for the fibre modes and axis 2 for the matrix modes
//!   (global axes, [`crate::materials::Frame`]). For a bilinear section
//!   element and a linear axis element (L4 × B2) this is the element's
//!   width along `n`; for higher orders it is about the width over the
//!   order.
//! * **Report.** The energy each mode dissipated (`Σ_q w_q g_I`), the
//!   volume where a mode's damage started (`d > 0`) and where it passed ½,
//!   the largest damage, and the points whose strength the law lowered
//!   because their band was longer than `2 E G/X²`.

use serde::Serialize;

use crate::materials::damage::{DamageState, MODES};
use crate::setup::Discretisation;

/// The ply-damage history of every Gauss point of a model (all empty when
/// no material damages).
#[derive(Debug, Clone, Default)]
pub(crate) struct BodyDamage {
    /// Committed states.
    pub committed: Vec<DamageState>,
    /// Trial states of the last evaluation.
    pub trial: Vec<DamageState>,
    /// Crack-band lengths `[fibre, matrix]` per point (m; 0 where the
    /// material does not damage).
    pub band: Vec<[f64; 2]>,
    /// Volume weight of each point (m³; 0 where the material does not
    /// damage).
    pub volume: Vec<f64>,
    /// The load factor of the committed states.
    pub lambda: f64,
}

impl BodyDamage {
    /// Virgin states and the crack bands of `discretisation`'s points
    /// (`n_points` in all, body `b`'s first at `gp_offsets[b]`); empty when
    /// no material damages.
    pub fn new(discretisation: &Discretisation<'_>, gp_offsets: &[usize], n_points: usize) -> Self {
        let d = discretisation;
        if !d.materials.iter().any(|m| m.damage.is_some()) {
            return Self::default();
        }
        let mut band = vec![[0.0; 2]; n_points];
        let mut volume = vec![0.0; n_points];
        let mut grads = Vec::new();
        for (b, (body, geom)) in d.mesh.bodies.iter().zip(d.cells).enumerate() {
            let n_section = body.section.n_elements();
            let per_element = geom.gp_per_element();
            grads.resize(geom.section.n_fun * geom.axis.n_fun, [0.0; 3]);
            for e in 0..body.n_elements() {
                let material = &d.materials[body.material_of(body.split_element(e).0)];
                if material.damage.is_none() {
                    continue;
                }
                for gb in 0..geom.axis.n_gp {
                    for gs in 0..geom.section.n_gp {
                        let w = geom.gradients(e % n_section, e / n_section, gb, gs, &mut grads);
                        let g = gp_offsets[b] + e * per_element + gb * geom.section.n_gp + gs;
                        volume[g] = w;
                        band[g] = [oliver(&grads, material.frame.axes[0]), oliver(&grads, material.frame.axes[1])];
                    }
                }
            }
        }
        let virgin = vec![DamageState::default(); n_points];
        Self { committed: virgin.clone(), trial: virgin, band, volume, lambda: 0.0 }
    }

    /// The committed states and bands as the assembly reads them.
    pub(crate) fn input(&self) -> crate::assembly::DamageInput<'_> {
        crate::assembly::DamageInput { committed: &self.committed, band: &self.band, step: 0.0, impulse: None }
    }

    /// The increment converged at load factor `lambda`: the trial states
    /// become the committed ones. Damage never decreases (checked in debug
    /// builds).
    pub fn commit(&mut self, lambda: f64) {
        self.lambda = lambda;
        debug_assert!(
            self.trial.iter().zip(&self.committed).all(|(t, c)| (0..4)
                .all(|i| t.damage[i] >= c.damage[i] && t.viscous[i] >= c.viscous[i] && t.kappa[i] >= c.kappa[i])),
            "a committed damage or κ decreased"
        );
        self.committed.copy_from_slice(&self.trial);
    }

    /// The energy each mode has released at fixed strain in the trial
    /// states, `Σ_q w_q (Σ_n W(ε_n; d_n) − W(ε_n; d_(n+1)))` (J;
    /// `DamageState::released`): what the energy ledger of a transient run
    /// books per mode.
    pub fn released(&self) -> [f64; 4] {
        per_mode(&self.trial, &self.volume, |s| &s.released)
    }

    /// The energy the end-of-step stress dissipated in the trial states,
    /// `Σ_q w_q B_q` (J; `crate::dynamics::ply_forces`, zero without it).
    pub fn scheme(&self) -> f64 {
        self.trial.iter().zip(&self.volume).map(|(s, w)| w * s.scheme).sum()
    }

    /// The committed damage the stiffness takes (`viscous`) of each mode
    /// at every point, `None` when no material damages: what a frame of a
    /// transient run keeps for its fields `d_ft d_fc d_mt d_mc`
    /// ([`Damage::of_frame`]), 32 bytes a point instead of a whole state.
    pub(crate) fn shown(&self) -> Option<Vec<[f64; 4]>> {
        (!self.committed.is_empty()).then(|| self.committed.iter().map(|s| s.viscous).collect())
    }

    /// The volume of the committed points where each mode's damage (the one
    /// the stiffness takes) passed ½ (m³), `None` when no material damages:
    /// the history's `damaged_volume_*`, as `summary.json`'s
    /// `damaged_volume_m3` at the end ([`Damage::summary`]).
    pub(crate) fn damaged_volume(&self) -> Option<[f64; 4]> {
        (!self.committed.is_empty()).then(|| volume_above(&self.committed, &self.volume, 0.5))
    }

    /// What a run keeps of it: `None` when no material damages.
    pub(crate) fn into_result(self) -> Option<Damage> {
        (!self.committed.is_empty()).then_some(Damage { states: self.committed, volume: self.volume })
    }
}

/// `Σ_q w_q x_I` per mode of the states `states` with volume weights
/// `volume`, `x` a per-mode energy density of a state (J/m³ → J).
fn per_mode(states: &[DamageState], volume: &[f64], x: impl Fn(&DamageState) -> &[f64; 4]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (s, &w) in states.iter().zip(volume) {
        for (o, g) in out.iter_mut().zip(x(s)) {
            *o += w * g;
        }
    }
    out
}

/// `Σ_q w_q` per mode over the states `states` (volume weights `volume`,
/// m³) whose damage the stiffness takes exceeds `level`.
fn volume_above(states: &[DamageState], volume: &[f64], level: f64) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (s, &w) in states.iter().zip(volume) {
        for (o, &d) in out.iter_mut().zip(&s.viscous) {
            if d > level {
                *o += w;
            }
        }
    }
    out
}

/// `2 / Σ_a |∇N_a · n|`: Oliver's projected size of the element along `n`.
fn oliver(grads: &[[f64; 3]], n: [f64; 3]) -> f64 {
    let sum: f64 = grads.iter().map(|g| (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]).abs()).sum();
    if sum > 0.0 { 2.0 / sum } else { 0.0 }
}

/// The ply damage at the end of a run: the committed state and the volume
/// weight of every Gauss point (the layout of `Solution::states`).
#[derive(Debug, Clone)]
pub struct Damage {
    /// Committed states.
    pub states: Vec<DamageState>,
    /// Volume weights (m³; 0 where the material does not damage).
    pub volume: Vec<f64>,
}

/// A value per damage mode, in `summary.json`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct PerMode {
    /// Fibre tension.
    pub fibre_tension: f64,
    /// Fibre compression.
    pub fibre_compression: f64,
    /// Matrix tension.
    pub matrix_tension: f64,
    /// Matrix compression.
    pub matrix_compression: f64,
}

impl PerMode {
    fn from_array(v: [f64; 4]) -> Self {
        Self { fibre_tension: v[0], fibre_compression: v[1], matrix_tension: v[2], matrix_compression: v[3] }
    }

    /// The four values in the order of [`MODES`].
    pub fn to_array(&self) -> [f64; 4] {
        [self.fibre_tension, self.fibre_compression, self.matrix_tension, self.matrix_compression]
    }
}

/// `summary.json` `damage`: the ply damage at the end of a run.
#[derive(Debug, Clone, Serialize)]
pub struct DamageSummary {
    /// The modes, in the order of the fields' names.
    pub modes: [&'static str; 4],
    /// The energy each mode dissipated, `Σ_q w_q g_I` (J).
    pub dissipated_j: PerMode,
    /// Their sum (J).
    pub(crate) dissipated_total_j: f64,
    /// The energy each mode released at fixed strain, increment by
    /// increment, `Σ_q w_q Σ_n W(ε_n; d_n) − W(ε_n; d_(n+1))` (J), at the
    /// strain `ε_n` each increment starts from: never more than the work
    /// of the loads, and the same as `dissipated_j` as the increments
    /// shrink; `dissipated_j` (the law's trapezoidal sums of `Y Δd`) above
    /// it means a damaged point's strain jumped within an increment.
    pub(crate) released_j: PerMode,
    /// Their sum (J).
    pub(crate) released_total_j: f64,
    /// The volume of the points where the mode's damage started, `d > 0` (m³).
    pub(crate) initiated_volume_m3: PerMode,
    /// The volume of the points where the mode's damage passed ½ (m³).
    pub(crate) damaged_volume_m3: PerMode,
    /// The largest damage of each mode.
    pub largest: PerMode,
    /// Gauss points where the law lowered a mode's onset stress because the
    /// crack band was longer than `2 E G/X²` (Bažant & Oh).
    pub(crate) strength_reduced_points: usize,
}

impl Damage {
    /// The damage of a frame ([`BodyDamage::shown`]) with the run's volume
    /// weights: each point's damage of each mode, for the frame's fields
    /// `d_ft d_fc d_mt d_mc` ([`Damage::largest_in`]). It holds no history
    /// (dissipation, onset, branches): its [`Damage::summary`] is not the
    /// frame's, only its fields are.
    pub(crate) fn of_frame(shown: &[[f64; 4]], volume: &[f64]) -> Damage {
        let states = shown.iter().map(|&d| DamageState { damage: d, viscous: d, ..Default::default() }).collect();
        Damage { states, volume: volume.to_vec() }
    }

    /// Its `summary.json` entry.
    pub fn summary(&self) -> DamageSummary {
        let dissipated = per_mode(&self.states, &self.volume, |s| &s.dissipated);
        let released = per_mode(&self.states, &self.volume, |s| &s.released);
        let initiated = volume_above(&self.states, &self.volume, 0.0);
        let damaged = volume_above(&self.states, &self.volume, 0.5);
        let mut largest = [0.0f64; 4];
        let mut reduced = 0;
        for s in &self.states {
            for (l, &d) in largest.iter_mut().zip(&s.viscous) {
                *l = l.max(d);
            }
            reduced += usize::from(s.reduced.iter().any(|&r| r));
        }
        DamageSummary {
            modes: MODES,
            dissipated_j: PerMode::from_array(dissipated),
            dissipated_total_j: dissipated.iter().sum(),
            released_j: PerMode::from_array(released),
            released_total_j: released.iter().sum(),
            initiated_volume_m3: PerMode::from_array(initiated),
            damaged_volume_m3: PerMode::from_array(damaged),
            largest: PerMode::from_array(largest),
            strength_reduced_points: reduced,
        }
    }

    /// Whether the stiffness of point `g` (global Gauss-point index) has
    /// lost anything: some mode's damage `d_v` above zero. Its stress is
    /// then not the elastic stiffness's times its strain
    /// ([`crate::post::FieldView`]).
    pub(crate) fn softened(&self, g: usize) -> bool {
        self.states.get(g).is_some_and(|s| s.viscous.iter().any(|&d| d > 0.0))
    }

    /// The largest damage of each mode over the points `range` (an
    /// element's), for the cell fields `d_ft d_fc d_mt d_mc`.
    pub(crate) fn largest_in(&self, range: std::ops::Range<usize>) -> [f64; 4] {
        let mut out = [0.0f64; 4];
        for s in &self.states[range] {
            for i in 0..4 {
                out[i] = out[i].max(s.viscous[i]);
            }
        }
        out
    }
}
