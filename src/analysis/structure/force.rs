//! Force-controlled rigid indenters: the indenter's rigid displacement
//! `a d̂` along its force direction `d̂` is an unknown, and one equation per
//! indenter asks that the contact force it applies along `d̂` equal its
//! target `F(λ)` (the indenter's `force` times its step factor).
//!
//! With penalty contact the gap of a candidate node is
//! `g = g₀ + (u_s − a d̂)·n`; the force on the body `f = −ε g n` when
//! `g ≤ 0`. The extra residual is `r = Σ f·d̂ − F`, and the Newton system
//! borders the structural tangent:
//!
//! ```text
//! [ K   B ] [Δu]     [R]      B_s = ∂R/∂a = −ε (d̂·n) n   (each active node s)
//! [ Bᵀ  C ] [Δa] = − [r],     C   = ∂r/∂a =  ε Σ (d̂·n)²
//! ```
//!
//! the Hessian of the potential `Π(u, a) − F a` (symmetric, positive
//! definite while the indenter touches). With Coulomb friction each active
//! point's block `K` (normal penalty plus the friction block, possibly
//! unsymmetric: `contact::friction`) replaces `ε n nᵀ`: column
//! `B_s = −K d̂`, row `∂r/∂u_s = −Kᵀ d̂`, corner `C = Σ d̂ᵀ K d̂`, and the
//! bordered system uses the row where `Bᵀ` stood. It is solved by bordering with the
//! one factorization of `K`: `K x₁ = −R`, `K X₂ = B`, then the small system
//! `(C − Bᵀ X₂) Δa = −r − Bᵀ x₁` and `Δu = x₁ − X₂ Δa` (Keller's bordering
//! algorithm, as in arc-length methods). While an indenter touches nothing,
//! the Jacobian of its nearest candidate node stands in, so that Newton
//! moves it into contact.
//!
//! A rigid **impactor** (`mass`, `velocity`; transient analysis) is driven
//! the same way along its velocity `d̂`: its equation gains its inertia,
//! `r = Σ f·d̂ − F + m ä` with Newmark's `ä` of its displacement `a`
//! (`dynamics::inertia`, the model's β and γ) and `C += m/(β Δt²)`; its
//! mass keeps the bordered system regular while it flies, so no contact
//! stands in, and its force scale is `m |v_n| / Δt`.

use super::inputs::Loading;
use super::system::LinearSystem;
use crate::assembly::NO_EQ;
use crate::contact::Contacts;
use crate::dynamics::TransientSettings;
use crate::mesh::Mesh;
use crate::setup::constraints::Elimination;
use crate::setup::steps::{self, Item};
use crate::solver::bordered::{Border, eliminate};
use crate::solver::linear::LinearError;

/// One force-controlled indenter.
#[derive(Debug, Clone)]
struct Driven {
    /// Index in `model.indenters`.
    indenter: usize,
    /// Unit direction of its force.
    dir: [f64; 3],
    /// Force magnitude at factor 1 (N).
    magnitude: f64,
    /// Current and committed displacement along `dir` (m).
    a: f64,
    a_committed: f64,
    /// Its change over the last converged increment.
    a_step: f64,
    /// The largest force (N, magnitude) a converged increment carried.
    held: f64,
    /// Border column `B = ∂R/∂a` (equation space) and corner `C` of the last evaluation.
    b: Vec<f64>,
    /// Border row `∂r/∂u` (equals `B` without friction).
    b_row: Vec<f64>,
    c: f64,
    /// Residual `r` of the last evaluation (N).
    r: f64,
    /// Its push on the body as the residual takes it — the algorithmic `f'`
    /// of a transient analysis's end-of-step contact impulse
    /// (`dynamics::impulse`), else the push itself — and the velocity
    /// update's `g`, trial and committed (N).
    pushed: (f64, f64, f64),
    /// A rigid impactor's inertia (transient analysis), `None` under force
    /// control.
    inertia: Option<Inertia>,
}

/// The Newmark state of an impactor along its direction (module docs).
#[derive(Debug, Clone)]
struct Inertia {
    mass: f64,
    /// Committed velocity and acceleration along `dir`, and λ.
    v_n: f64,
    acc_n: f64,
    lambda_n: f64,
    /// Trial velocity and acceleration.
    v: f64,
    acc: f64,
}

/// The force-controlled indenters of a model.
#[derive(Debug)]
pub(crate) struct ForceControl<'m> {
    loading: Loading<'m>,
    /// The bodies (their sizes bound a collapse).
    mesh: &'m Mesh,
    transient: Option<&'m TransientSettings>,
    driven: Vec<Driven>,
}

impl<'m> ForceControl<'m> {
    /// The force-controlled indenters of `loading` on `mesh` (`n_eq`
    /// equations; `transient`: the implicit dynamics, if any).
    pub fn new(loading: Loading<'m>, mesh: &'m Mesh, transient: Option<&'m TransientSettings>, n_eq: usize) -> Self {
        let driven = loading
            .indenters
            .iter()
            .enumerate()
            .filter_map(|(i, ind)| {
                let norm = |f: [f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
                // an impactor moves along its velocity, pushed by its force
                // (if any, validated parallel); under force control along the force
                let (dir, magnitude, inertia) = match (ind.impactor, ind.force) {
                    (Some(imp), f) => {
                        let speed = norm(imp.velocity);
                        let dir = imp.velocity.map(|v| v / speed);
                        let along = f.map_or(0.0, |f| f.iter().zip(&dir).map(|(a, b)| a * b).sum());
                        let inertia =
                            Inertia { mass: imp.mass, v_n: speed, acc_n: 0.0, lambda_n: 0.0, v: speed, acc: 0.0 };
                        (dir, along, Some(inertia))
                    }
                    (None, Some(f)) => (f.map(|v| v / norm(f)), norm(f), None),
                    (None, None) => return None,
                };
                Some(Driven {
                    indenter: i,
                    dir,
                    magnitude,
                    inertia,
                    a: 0.0,
                    a_committed: 0.0,
                    held: 0.0,
                    a_step: 0.0,
                    b: vec![0.0; n_eq],
                    b_row: vec![0.0; n_eq],
                    c: 0.0,
                    r: 0.0,
                    pushed: (0.0, 0.0, 0.0),
                })
            })
            .collect();
        Self { loading, mesh, transient, driven }
    }

    /// True if some indenter is force-controlled (its motion an unknown).
    pub(crate) fn is_driven(&self) -> bool {
        !self.driven.is_empty()
    }

    /// True if some indenter is under force control proper (not an
    /// impactor): its stand-in contact couples it while it touches nothing.
    /// An impactor couples only through its active contact points, which
    /// the contacts' part reports.
    pub(crate) fn is_force_controlled(&self) -> bool {
        self.driven.iter().any(|d| d.inertia.is_none())
    }

    /// Rigid displacement of every indenter at load factor `lambda`: the
    /// prescribed motion times its factor, or the solved one.
    pub fn offsets(&self, lambda: f64) -> impl Iterator<Item = [f64; 3]> + '_ {
        self.loading.indenters.iter().enumerate().map(move |(k, ind)| {
            if let Some(d) = self.driven.iter().find(|d| d.indenter == k) {
                return d.dir.map(|v| d.a * v);
            }
            let a = steps::factor(self.loading.steps, Item::Indenter(k), lambda);
            ind.displacement.map(|d| a * d)
        })
    }

    /// After the contact evaluation: the force residual, border column and
    /// corner of every force-controlled indenter. Returns `(Σ r², Σ F²)`.
    pub fn evaluate(
        &mut self,
        contacts: &Contacts<'_>,
        eq: &[usize],
        elimination: &Elimination,
        lambda: f64,
    ) -> (f64, f64) {
        let loading = self.loading;
        let (points, blocks) = (contacts.points(), contacts.blocks());
        let (mut res2, mut target2) = (0.0, 0.0);
        // the contacts' end-of-step impulse: f' and its derivatives (1 − α)/γ
        let recursion = self
            .transient
            .filter(|t| t.contact_forces == crate::dynamics::ContactForces::Implicit)
            .map(crate::dynamics::TransientSettings::recursion);
        let weight = recursion.map_or(1.0, crate::newmark::Recursion::weight);
        for drv in &mut self.driven {
            let k = drv.indenter;
            let ind = &loading.indenters[k];
            let range = contacts.ranges()[k].clone();
            let d = drv.dir;
            let target = steps::factor(loading.steps, Item::Indenter(k), lambda) * drv.magnitude;
            let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let mut pushed = 0.0;
            let mut any = false;
            let mut nearest = (f64::INFINITY, 0);
            for (j, p) in points[range.clone()].iter().enumerate() {
                pushed += dot(&p.force, &d);
                any |= p.active;
                if p.gap < nearest.0 {
                    nearest = (p.gap, j);
                }
            }
            drv.b.fill(0.0);
            drv.b_row.fill(0.0);
            drv.c = 0.0;
            // an impactor's mass regularizes its equation: no stand-in contact
            let stand_in = !any && drv.inertia.is_none();
            for (j, (p, c)) in points[range.clone()].iter().zip(&ind.nodes).enumerate() {
                if !(p.active || (stand_in && j == nearest.1)) {
                    continue;
                }
                // the point's assembled block K (ε n nᵀ, plus friction);
                // while nothing touches, the nearest point's ε n nᵀ
                let kb = if p.active {
                    blocks[range.start + j]
                } else {
                    c.normal.map(|a| c.normal.map(|b| c.penalty * a * b))
                };
                let col: [f64; 3] = std::array::from_fn(|m| weight * dot(&kb[m], &d));
                let row: [f64; 3] = std::array::from_fn(|m| weight * (0..3).map(|i| kb[i][m] * d[i]).sum::<f64>());
                drv.c += dot(&d, &col);
                for m in 0..3 {
                    let e = eq[3 * c.node + m];
                    if e != NO_EQ && !elimination.is_prescribed(e) {
                        drv.b[e] -= col[m];
                        drv.b_row[e] -= row[m];
                    }
                }
            }
            (drv.pushed.1, drv.pushed.0) = recursion.map_or((pushed, pushed), |r| r.step(pushed, drv.pushed.2));
            drv.r = drv.pushed.0 - target;
            let mut scale = target.abs();
            if let (Some(inertia), Some(tr)) = (drv.inertia.as_mut(), self.transient) {
                // m ä + (its push on the body) = its force: Newmark in a,
                // the inertia force Bossak's m ((1 − α) ä + α ä_n)
                let dt = tr.time(lambda) - tr.time(inertia.lambda_n);
                let mut acc = inertia.acc_n;
                if dt > 0.0 {
                    let c0 = 1.0 / (tr.beta * dt * dt);
                    inertia.acc = c0 * (drv.a - drv.a_committed - dt * inertia.v_n)
                        - (1.0 / (2.0 * tr.beta) - 1.0) * inertia.acc_n;
                    inertia.v = inertia.v_n + dt * ((1.0 - tr.gamma) * inertia.acc_n + tr.gamma * inertia.acc);
                    drv.c += (1.0 - tr.alpha) * inertia.mass * c0;
                    acc = (1.0 - tr.alpha) * inertia.acc + tr.alpha * inertia.acc_n;
                    // the force that would stop it within the step
                    scale = scale.max(inertia.mass * inertia.v_n.abs() / dt);
                }
                drv.r += inertia.mass * acc;
            }
            res2 += drv.r * drv.r;
            target2 += scale * scale;
        }
        (res2, target2)
    }

    /// Bordered solve (module docs): `system.rhs` holds `−R` (after the
    /// Dirichlet elimination); on return it holds `Δu`. Updates each
    /// indenter's `a` and returns `Σ Δa²`.
    pub fn solve(&mut self, system: &mut LinearSystem, lambda: f64) -> Result<f64, LinearError> {
        let m = self.driven.len();
        let coupled = |d: &Driven| d.b.iter().chain(&d.b_row).any(|v| *v != 0.0);
        // impactors in contact without friction: their bordered system is
        // symmetric positive definite (their mass holds it), solved by PCG
        // with the reuse of factorizations (`solver::bordered`). Measured on
        // examples/tube_drop_weight.toml: 240 factorizations against 430
        // with the elimination below, the probes equal within 1e-5. Force
        // control keeps Keller's elimination with the present tangent's own
        // factor (a stand-in border while nothing touches is no Hessian),
        // and so does an impactor in flight (no border couples: its motion
        // is then solved exactly, Newmark's rule exact for it).
        let symmetric = system.rest.as_ref().is_none_or(|r| r.is_empty())
            && self.driven.iter().all(|d| d.inertia.is_some() && d.b == d.b_row);
        if symmetric && self.driven.iter().any(coupled) {
            let cols: Vec<&[f64]> = self.driven.iter().map(|d| &d.b[..]).collect();
            let corner: Vec<f64> = self.driven.iter().map(|d| d.c).collect();
            let mut da: Vec<f64> = self.driven.iter().map(|d| -d.r).collect();
            let border = Border { cols: &cols, corner: &corner };
            match system.solve_bordered(&border, &mut da) {
                Ok(()) => return self.advance(&da, lambda),
                // not positive definite after all: Keller's elimination below
                Err(LinearError::KrylovStalled(_)) => {}
                Err(e) => return Err(e),
            }
        }
        let coupled = |d: &Driven| d.b.iter().chain(&d.b_row).any(|v| *v != 0.0);
        system.solve(self.driven.iter().any(coupled))?;
        if m == 0 {
            return Ok(0.0);
        }
        let mut x2 = Vec::with_capacity(m);
        for d in &self.driven {
            let mut x = d.b.clone();
            if coupled(d) {
                system.solve_again(&mut x)?;
            }
            x2.push(x);
        }
        // S = C − Bᵀ X₂ (C diagonal: each contact point belongs to one indenter)
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let row = |i: usize, v: &[f64]| dot(&self.driven[i].b_row, v);
        let corner: Vec<f64> = self.driven.iter().map(|d| d.c).collect();
        let r_a: Vec<f64> = self.driven.iter().map(|d| -d.r).collect();
        let da = eliminate(&mut system.rhs, &x2, row, &corner, &r_a)?;
        self.advance(&da, lambda)
    }

    /// Moves each indenter by its correction `da`; returns `Σ Δa²`.
    fn advance(&mut self, da: &[f64], lambda: f64) -> Result<f64, LinearError> {
        let mut sum = 0.0;
        for (d, v) in self.driven.iter_mut().zip(da) {
            d.a += v;
            sum += v * v;
        }
        self.check_collapse(lambda)?;
        Ok(sum)
    }

    /// A target force beyond the limit load: under perfect plasticity the
    /// solution runs away (small strains allow any displacement), so a
    /// motion beyond a tenth of the body is a collapse, not an answer —
    /// unless the step takes this force back, adds no other load, and the
    /// model already carried it (a correction that diverged: a cutback, not
    /// a collapse). Not for an
    /// impactor: its travel is its flight, which its inertia bounds.
    fn check_collapse(&self, lambda: f64) -> Result<(), LinearError> {
        for d in self.driven.iter().filter(|d| d.inertia.is_none()) {
            let ind = &self.loading.indenters[d.indenter];
            let body = &self.mesh.bodies[ind.body];
            if !(d.a.abs() <= 0.1 * body.size()) {
                let item = Item::Indenter(d.indenter);
                let target = steps::factor(self.loading.steps, item, lambda) * d.magnitude;
                let k = steps::step_at(self.loading.steps, lambda);
                let back =
                    steps::takes_back(self.loading.steps, k, item) && !steps::loads_more(self.loading.steps, k, item);
                if back && target.abs() <= d.held * (1.0 + 1e-9) {
                    return Err(LinearError::Rejected(format!(
                        "a correction moved force-controlled indenter {:?} {:.3e} m, more than a tenth of the size \
                         of body {:?} ({:.3e} m), towards {:.4e} N, no more than the {:.4e} N a converged increment \
                         carried: the correction diverged (not a collapse)",
                        ind.name,
                        d.a.abs(),
                        body.name,
                        body.size(),
                        target,
                        d.held
                    )));
                }
                return Err(LinearError::Rejected(format!(
                    "force-controlled indenter {:?} would have to move {:.3e} m, more than a tenth of the size of \
                     body {:?} ({:.3e} m), to carry {:.4e} N: the body collapses before this force (the last \
                     converged increment holds the largest force reached)",
                    ind.name,
                    d.a.abs(),
                    body.name,
                    body.size(),
                    target
                )));
            }
        }
        Ok(())
    }

    /// Starts the next solve on the secant of the last increment.
    pub fn extrapolate(&mut self, ratio: f64) {
        for d in &mut self.driven {
            d.a = d.a_committed + ratio * d.a_step;
        }
    }

    /// The increment converged (at λ = `lambda`).
    pub fn commit(&mut self, lambda: f64) {
        for d in &mut self.driven {
            let force = steps::factor(self.loading.steps, Item::Indenter(d.indenter), lambda) * d.magnitude;
            d.held = d.held.max(force.abs());
            d.a_step = d.a - d.a_committed;
            d.a_committed = d.a;
            d.pushed.2 = d.pushed.1;
            if let Some(i) = d.inertia.as_mut() {
                (i.v_n, i.acc_n, i.lambda_n) = (i.v, i.acc, lambda);
            }
        }
    }

    /// Back to the committed displacements.
    pub fn restore(&mut self) {
        for d in &mut self.driven {
            d.a = d.a_committed;
        }
    }

    /// `½ m v²` of the impactors at the last evaluation.
    pub(crate) fn impactor_energy(&self) -> f64 {
        self.driven.iter().filter_map(|d| d.inertia.as_ref()).map(|i| 0.5 * i.mass * i.v * i.v).sum()
    }

    /// Squared norm of the change since the committed state.
    pub(crate) fn increment2(&self) -> f64 {
        self.driven.iter().map(|d| (d.a - d.a_committed).powi(2)).sum()
    }
}
