//! Tests of `solver::arclength` on the von Mises truss, whose equilibrium
//! path is known in closed form.
//!
//! Two bars of half-span `a`, rise `h` and axial stiffness `EA` meet at the
//! apex, loaded downwards by `λ P`; `w` is the apex's downward displacement.
//! With the Green–Lagrange strain `E = (L² − L₀²)/(2 L₀²)`,
//! `L² = a² + (h − w)²`, `L₀² = a² + h²`, and a constant `EA` (a
//! Saint-Venant–Kirchhoff bar), the strain energy of the two bars is
//! `U = 2 · EA L₀ E²/2` and `E = (w² − 2hw)/(2L₀²)`, so equilibrium
//! `dU/dw = λ P` reads
//!
//! ```text
//! F(w) = k_t w (h − w)(2h − w) = λ P,   k_t = EA / L₀³
//! ```
//!
//! (the same cubic as Crisfield's shallow truss, *Non-linear Finite Element
//! Analysis of Solids and Structures*, vol. 1, ch. 1, here exact for any
//! depth). `F' = k_t (3w² − 6hw + 2h²)` vanishes at the limit points
//! `w = h(1 ∓ 1/√3)`, where `F = ±2 k_t h³/(3√3)`; with `P` equal to that
//! value the path runs up to `λ = 1`, down through `λ = 0` at `w = h` to
//! `λ = −1`, and up the stable branch through `λ = 0` at `w = 2h` to
//! `λ = 1` again at `w = h(1 + 2/√3)`.

use super::*;

const H: f64 = 1.0;

/// `k_t = EA / L₀³` with `a = 10`, `h = 1`, `EA = 10⁶`.
fn kt() -> f64 {
    1e6 / (100.0 + H * H).powf(1.5)
}

/// The reference load: `λ = ±1` at the limit points.
fn p_ref() -> f64 {
    kt() * 2.0 * H.powi(3) / (3.0 * 3f64.sqrt())
}

/// `(F(w), F'(w))`.
fn truss(w: f64) -> (f64, f64) {
    let k = kt();
    (k * w * (H - w) * (2.0 * H - w), k * (3.0 * w * w - 6.0 * H * w + 2.0 * H * H))
}

/// The truss alone (`u = [w]`), or with a spring of stiffness `k_s`
/// between the apex and the loaded point (`u = [v, w]`: apex and load-point
/// displacements): `f_int = [F(v) + k_s (v − w), k_s (w − v)]`, `f = [0, P]`.
struct Truss {
    spring: Option<f64>,
    u: Vec<f64>,
    committed: Vec<f64>,
    k: [[f64; 2]; 2],
}

impl Truss {
    fn new(spring: Option<f64>) -> Self {
        let n = if spring.is_some() { 2 } else { 1 };
        Self { spring, u: vec![0.0; n], committed: vec![0.0; n], k: [[0.0; 2]; 2] }
    }
}

impl PathProblem for Truss {
    type Error = std::io::Error;
    fn dimension(&self) -> usize {
        self.u.len()
    }
    fn reference_load(&self, f: &mut [f64]) {
        f.fill(0.0);
        f[f.len() - 1] = p_ref();
    }
    fn residual(&mut self, lambda: f64, r: &mut [f64]) -> Result<(), Self::Error> {
        let (force, stiffness) = truss(self.u[0]);
        match self.spring {
            None => {
                r[0] = force - lambda * p_ref();
                self.k[0][0] = stiffness;
            }
            Some(ks) => {
                let stretch = self.u[1] - self.u[0];
                r[0] = force - ks * stretch;
                r[1] = ks * stretch - lambda * p_ref();
                self.k = [[stiffness + ks, -ks], [-ks, ks]];
            }
        }
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), Self::Error> {
        solve_small(&self.k, self.u.len(), rhs)
    }
    fn update(&mut self, du: &[f64]) -> Result<(), Self::Error> {
        self.u.iter_mut().zip(du).for_each(|(u, d)| *u += d);
        Ok(())
    }
    fn commit(&mut self) {
        self.committed.clone_from(&self.u);
    }
    fn restore(&mut self) {
        self.u.clone_from(&self.committed);
    }
}

/// Solves `k x = b` in place for each right-hand side, `k` the leading
/// `n × n` (1 or 2) block, by Cramer's rule.
fn solve_small(k: &[[f64; 2]; 2], n: usize, rhs: &mut [&mut [f64]]) -> Result<(), std::io::Error> {
    let det = if n == 1 { k[0][0] } else { k[0][0] * k[1][1] - k[0][1] * k[1][0] };
    if det == 0.0 {
        return Err(std::io::Error::other("singular tangent"));
    }
    for b in rhs.iter_mut() {
        if n == 1 {
            b[0] /= k[0][0];
        } else {
            let (x, y) = (b[0], b[1]);
            b[0] = (k[1][1] * x - k[0][1] * y) / det;
            b[1] = (k[0][0] * y - k[1][0] * x) / det;
        }
    }
    Ok(())
}

/// The converged points `(λ, u)` and steps; stops once `λ` has gone below
/// −1/2 and come back up to 1 (the stable branch regained).
#[derive(Default)]
struct Record {
    points: Vec<(f64, Vec<f64>)>,
    steps: Vec<PathStep>,
    cutbacks: usize,
    dipped: bool,
}

impl PathObserver<Truss> for Record {
    fn converged(&mut self, problem: &Truss, step: &PathStep) -> bool {
        self.points.push((step.lambda, problem.u.clone()));
        self.steps.push(step.clone());
        self.dipped |= step.lambda < -0.5;
        !(self.dipped && step.lambda >= 1.0)
    }
    fn cut_back(&mut self, _: &PathStep) {
        self.cutbacks += 1;
    }
}

/// Number of sign changes of the successive differences of `x`.
fn reversals(x: &[f64]) -> usize {
    let d: Vec<f64> = x.windows(2).map(|p| p[1] - p[0]).collect();
    d.windows(2).filter(|p| p[0] * p[1] < 0.0).count()
}

fn settings() -> ArcLengthSettings {
    ArcLengthSettings { initial_dlambda: 0.1, residual_tolerance: 1e-11, max_increments: 300, ..Default::default() }
}

fn run(spring: Option<f64>, settings: &ArcLengthSettings) -> (Truss, Record) {
    let mut truss = Truss::new(spring);
    let mut record = Record::default();
    let history = trace(&mut truss, 0.0, settings, &mut record, &Interrupt::new()).map_err(|e| e.to_string()).unwrap();
    assert_eq!(history, record.steps);
    (truss, record)
}

/// Past the limit point `λ = 1`, down to `λ = −1` and back up the stable
/// branch to `λ = 1`, without a cutback, every converged point on
/// `λ = F(w)/P` (module comment) to 1e-8: with the cylinder (ψ = 0, where
/// one unknown makes `Δw = ±Δl` and the path's direction rests on the
/// predictor's sign), and with the sphere `Δw² + (h Δλ)² = Δl²`
/// (`ψ = h/P`), which each converged point satisfies.
#[test]
fn von_mises_truss_snaps_through_on_the_exact_path() {
    for psi in [0.0, H / p_ref()] {
        let (_, rec) = run(None, &ArcLengthSettings { psi, ..settings() });
        assert_eq!(rec.cutbacks, 0);
        assert!(rec.steps.iter().all(|s| s.cutbacks == 0 && s.converged));
        for (lambda, u) in &rec.points {
            let exact = truss(u[0]).0 / p_ref();
            assert!((lambda - exact).abs() < 1e-8, "ψ = {psi}, w = {}: λ = {lambda}, exact {exact}", u[0]);
        }
        let w: Vec<f64> = rec.points.iter().map(|p| p.1[0]).collect();
        let lambda: Vec<f64> = rec.points.iter().map(|p| p.0).collect();
        let (mut w0, mut l0) = (0.0, 0.0);
        for (s, (&w, &l)) in rec.steps.iter().zip(w.iter().zip(&lambda)) {
            let length = ((w - w0).powi(2) + (psi * p_ref() * (l - l0)).powi(2)).sqrt();
            assert!((length - s.arc_length).abs() < 1e-10 * s.arc_length, "{length} against {}", s.arc_length);
            (w0, l0) = (w, l);
        }
        // the apex moves down all the way (the predictor kept its direction
        // where the tangent stiffness changed sign)
        assert!(w.windows(2).all(|p| p[1] > p[0]), "{w:?}");
        // both limit points, w = h(1 ∓ 1/√3), passed: λ rose, fell and rose again
        assert_eq!(reversals(&lambda), 2, "{lambda:?}");
        assert!(w[0] < H * (1.0 - 1.0 / 3f64.sqrt()) && H * (1.0 + 1.0 / 3f64.sqrt()) < w[w.len() - 1]);
        let last = rec.points.last().unwrap();
        assert!(last.0 >= 1.0 && last.1[0] > 2.0 * H, "{last:?}");
    }
}

/// With a spring `k_s = k_t/2` in series, the load point's displacement is
/// `w = v + F(v)/k_s` and `λ = F(v)/P` along the path (`v` the apex's). As
/// `min F' = F'(h) = −k_t < −k_s`, `dw/dv = 1 + F'/k_s` is negative for
/// `|v − h| < h/√6`: the path snaps back. Load control stops at the maxima
/// of `λ`, and control of `w` at those of `w`; the path is traced through
/// both pairs of turning points, every point on the exact path.
#[test]
fn snap_back_with_a_spring_in_series() {
    let ks = 0.5 * kt();
    let (_, rec) = run(Some(ks), &settings());
    for (lambda, u) in &rec.points {
        let (v, w) = (u[0], u[1]);
        let force = truss(v).0;
        assert!((lambda - force / p_ref()).abs() < 1e-8, "v = {v}: λ = {lambda}");
        assert!((w - (v + force / ks)).abs() < 1e-8 * H, "v = {v}: w = {w}");
    }
    let v: Vec<f64> = rec.points.iter().map(|p| p.1[0]).collect();
    let w: Vec<f64> = rec.points.iter().map(|p| p.1[1]).collect();
    let lambda: Vec<f64> = rec.points.iter().map(|p| p.0).collect();
    assert!(v.windows(2).all(|p| p[1] > p[0]), "{v:?}");
    assert_eq!(reversals(&lambda), 2, "{lambda:?}");
    assert_eq!(reversals(&w), 2, "{w:?}");
    // w went back by most of the exact snap-back: w(h − h/√6) − w(h + h/√6)
    let w_at = |v: f64| v + truss(v).0 / ks;
    let back = w_at(H - H / 6f64.sqrt()) - w_at(H + H / 6f64.sqrt());
    let traced = w.iter().cloned().fold(f64::MIN, f64::max) - w.iter().cloned().fold(f64::MAX, f64::min);
    assert!(back > 0.0 && traced > back, "{back} {traced}");
}

/// The corrector is Newton's method with the exact tangent: near the
/// solution the residual falls quadratically, `ρ_(k+1) ≈ C ρ_k²`, so the
/// observed order `log(ρ_(k+1)/ρ_k) / log(ρ_k/ρ_(k−1))` tends to 2 (it would
/// be 1 with a tangent kept from the predictor). Each converged point lies
/// on the cylinder `‖Δu‖ = Δl` (ψ = 0).
#[test]
fn corrector_converges_quadratically_on_the_cylinder() {
    let tight = ArcLengthSettings { residual_tolerance: 1e-13, ..settings() };
    let (_, rec) = run(Some(0.5 * kt()), &tight);
    let mut orders = Vec::new();
    for s in &rec.steps {
        for r in s.residuals.windows(3) {
            // the asymptotic range, above rounding (‖R‖ ≈ 1e-16 · k_t h³)
            if r[0] < 1e-2 && r[2] > 1e-13 {
                orders.push((r[2] / r[1]).ln() / (r[1] / r[0]).ln());
            }
        }
    }
    assert!(orders.len() >= 5, "{orders:?}");
    assert!(orders.iter().all(|&p| p > 1.8), "{orders:?}");
    let mut last = vec![0.0; 2];
    for ((_, u), s) in rec.points.iter().zip(&rec.steps) {
        let du = ((u[0] - last[0]).powi(2) + (u[1] - last[1]).powi(2)).sqrt();
        assert!((du - s.arc_length).abs() < 1e-10 * s.arc_length, "{du} against {}", s.arc_length);
        last.clone_from(u);
    }
}

/// A problem whose tangent cannot be solved after the start: each attempt
/// fails, the arc length halves down to its minimum, and the error says so
/// with the problem's message; the state is the committed one.
#[test]
fn repeated_failure_stops_at_the_minimum_arc_length() {
    struct Broken(Truss, usize);
    impl PathProblem for Broken {
        type Error = std::io::Error;
        fn dimension(&self) -> usize {
            1
        }
        fn reference_load(&self, f: &mut [f64]) {
            self.0.reference_load(f)
        }
        fn residual(&mut self, lambda: f64, r: &mut [f64]) -> Result<(), Self::Error> {
            self.0.residual(lambda, r)
        }
        fn solve(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), Self::Error> {
            self.1 += 1;
            if self.1 > 1 { Err(std::io::Error::other("factor broke down")) } else { self.0.solve(rhs) }
        }
        fn update(&mut self, du: &[f64]) -> Result<(), Self::Error> {
            self.0.update(du)
        }
        fn commit(&mut self) {
            self.0.commit()
        }
        fn restore(&mut self) {
            self.0.restore()
        }
    }
    struct Count(usize);
    impl PathObserver<Broken> for Count {
        fn converged(&mut self, _: &Broken, _: &PathStep) -> bool {
            true
        }
        fn cut_back(&mut self, _: &PathStep) {
            self.0 += 1;
        }
    }
    let mut p = Broken(Truss::new(None), 0);
    let mut count = Count(0);
    let s = ArcLengthSettings { min_ratio: 0.01, ..settings() };
    let e = trace(&mut p, 0.0, &s, &mut count, &Interrupt::new()).unwrap_err();
    assert_eq!(e.reason, PathStop::ArcTooSmall);
    // Δl₀ · (1, 1/2, …, 1/64) tried and failed; 1/128 < 0.01 ends the run
    assert_eq!(count.0, 7);
    assert!(e.to_string().contains("factor broke down"), "{e}");
    assert_eq!(p.0.u, [0.0]);
}

/// Records the converged points until `λ` reaches `end`.
struct Until(f64, Vec<(f64, Vec<f64>)>, usize);

impl PathObserver<Truss> for Until {
    fn converged(&mut self, problem: &Truss, step: &PathStep) -> bool {
        self.1.push((step.lambda, problem.u.clone()));
        step.lambda < self.0
    }
    fn cut_back(&mut self, _: &PathStep) {
        self.2 += 1;
    }
}

/// A first arc three and five times the linear path to the limit load
/// (`Δλ₁ = 3`, `5`) on the truss with a spring in series: unchecked, it
/// converges on the stable branch far beyond both limit points (λ = 0.14
/// then 3.2, 6.7, …: λ never turns); with the check each jump turns the
/// increment by more than 11.5° from its predictor, is redone shorter, and
/// the path passes both limit points (λ turns twice), every point on the
/// exact path. (A first arc of 10 jumps without turning: what
/// [`ArcLengthSettings::max_length`] is for.)
#[test]
fn a_long_arc_does_not_jump_over_the_limit_points() {
    for first in [3.0, 5.0] {
        let traced = |min_cosine: f64| {
            let s = ArcLengthSettings { initial_dlambda: first, min_cosine, max_increments: 60, ..settings() };
            let (mut problem, mut record) = (Truss::new(Some(0.5 * kt())), Record::default());
            let _ = trace(&mut problem, 0.0, &s, &mut record, &Interrupt::new());
            record
        };
        let unchecked = traced(-1.0);
        let lambda: Vec<f64> = unchecked.points.iter().map(|p| p.0).collect();
        assert_eq!(reversals(&lambda), 0, "the premise: an unchecked arc of {first} jumps, {lambda:?}");
        let checked = traced(ArcLengthSettings::default().min_cosine);
        let lambda: Vec<f64> = checked.points.iter().map(|p| p.0).collect();
        assert!(checked.cutbacks > 0, "no increment redone");
        // down below −1/2 and back up to 1 (the observer's end), λ turning twice
        assert!(checked.dipped && *lambda.last().unwrap() >= 1.0, "{lambda:?}");
        assert_eq!(reversals(&lambda), 2, "{lambda:?}");
        for (lambda, u) in &checked.points {
            assert!((lambda - truss(u[0]).0 / p_ref()).abs() < 1e-8, "v = {}: λ = {lambda}", u[0]);
        }
    }
}

/// With `max_lambda = 0.5` the increment that passes it is redone at
/// λ = 0.5: the last point is there exactly, on the exact path's rising
/// branch (`F(w) = P/2`, `w < h(1 − 1/√3)`), and no cutback was counted.
#[test]
fn the_path_lands_on_its_end() {
    let s = ArcLengthSettings { max_lambda: 0.5, initial_dlambda: 0.15, ..settings() };
    let mut record = Until(0.5, Vec::new(), 0);
    let mut problem = Truss::new(None);
    let steps = trace(&mut problem, 0.0, &s, &mut record, &Interrupt::new()).unwrap();
    let (lambda, u) = record.1.last().unwrap();
    assert_eq!(*lambda, 0.5);
    assert!((truss(u[0]).0 / p_ref() - 0.5).abs() < 1e-9, "w = {}", u[0]);
    assert!(u[0] < H * (1.0 - 1.0 / 3f64.sqrt()));
    assert!(record.1[..record.1.len() - 1].iter().all(|p| p.0 < 0.5));
    assert_eq!((record.2, steps.last().unwrap().cutbacks), (0, 0));
}

/// A bar that damages (elastic `k0` to its strength `s` at `v0 = s/k0`,
/// then exponential softening `σ = s exp(−(κ − v0)/ℓ)`, unloading on its
/// secant) in series with an elastic spring `ks`, pulled by `λ P` at the
/// spring's free end: `u = [v, w]`, the bar's end and the load point. With
/// `ks < s/ℓ` the load point snaps back as the bar starts to soften
/// (`w = v + λP/ks`, `dw/dv < 0`), the path the dissipation constraint is
/// made for; the curved branch makes each increment take corrections.
struct Softening {
    u: [f64; 2],
    committed: [f64; 2],
    /// Largest `v` so far (committed).
    kappa: f64,
    k: [[f64; 2]; 2],
}

const K0: f64 = 100.0;
const STRENGTH: f64 = 1.0;
const ELL: f64 = 0.05;
const KS: f64 = 2.0;

impl Softening {
    /// The envelope's stress at `kappa` past the peak.
    fn envelope(kappa: f64) -> f64 {
        STRENGTH * (-(kappa - STRENGTH / K0) / ELL).exp()
    }

    /// The bar's force and its tangent at `v`, from the committed `kappa`.
    fn bar(&self, v: f64) -> (f64, f64) {
        let v0 = STRENGTH / K0;
        let kappa = self.kappa.max(v0);
        if v >= kappa && v > v0 * (1.0 - 1e-12) {
            // loading from the largest so far: the envelope (at the peak
            // itself too: its tangent points where the path goes)
            (Self::envelope(v), -Self::envelope(v) / ELL)
        } else {
            // on the secant of the largest so far
            let secant = Self::envelope(kappa) / kappa;
            (secant * v, secant)
        }
    }

    /// The energy the bar has dissipated at `kappa`: the work along its
    /// envelope less what it holds on its secant.
    fn dissipated(kappa: f64) -> f64 {
        let v0 = STRENGTH / K0;
        if kappa <= v0 {
            return 0.0;
        }
        let work = 0.5 * STRENGTH * v0 + STRENGTH * ELL * (1.0 - (-(kappa - v0) / ELL).exp());
        work - 0.5 * kappa * Self::envelope(kappa)
    }
}

impl PathProblem for Softening {
    type Error = std::io::Error;
    fn dimension(&self) -> usize {
        2
    }
    fn reference_load(&self, f: &mut [f64]) {
        f.copy_from_slice(&[0.0, STRENGTH]);
    }
    fn residual(&mut self, lambda: f64, r: &mut [f64]) -> Result<(), Self::Error> {
        let (force, tangent) = self.bar(self.u[0]);
        let stretch = self.u[1] - self.u[0];
        r[0] = force - KS * stretch;
        r[1] = KS * stretch - lambda * STRENGTH;
        self.k = [[tangent + KS, -KS], [-KS, KS]];
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), Self::Error> {
        solve_small(&self.k, 2, rhs)
    }
    fn update(&mut self, du: &[f64]) -> Result<(), Self::Error> {
        self.u.iter_mut().zip(du).for_each(|(u, d)| *u += d);
        Ok(())
    }
    fn commit(&mut self) {
        self.committed = self.u;
        self.kappa = self.kappa.max(self.u[0]);
    }
    fn restore(&mut self) {
        self.u = self.committed;
    }
}

/// The converged points `(λ, v, w)` until the bar holds 1 % of its strength.
#[derive(Default)]
struct SofteningRecord(Vec<(f64, f64, f64)>, usize);

impl PathObserver<Softening> for SofteningRecord {
    fn converged(&mut self, problem: &Softening, step: &PathStep) -> bool {
        self.0.push((step.lambda, problem.u[0], problem.u[1]));
        self.1 += step.iterations;
        step.lambda > 0.01 || problem.u[0] < STRENGTH / K0
    }
}

/// The dissipation constraint traces the softening bar through its
/// snap-back until it holds 1 % of its strength: the bar's end `v` never
/// goes back once it softens (no point of the path unloads: the constraint
/// asks each increment to dissipate), the load point `w` turns back (the
/// snap-back: `w` falls from `v0 + s/ks = 0.51` to below half of it), each
/// point on the exact envelope `λ P = s exp(−(v − v0)/ℓ)` (to 1e-8), and
/// the energy the increments were held to, `Σ ½ (λ₀ fᵀΔu − Δλ fᵀu₀)`,
/// sums to the bar's dissipation `D(v)` of its law within 1 % (a first-order
/// rule along a curved path). Mutation: the corrector's `Δλ fᵀu₀` with
/// the wrong sign fails it.
#[test]
fn the_dissipation_constraint_follows_a_softening_bar_through_its_snap_back() {
    let settings = ArcLengthSettings {
        initial_dlambda: 0.05,
        residual_tolerance: 1e-11,
        max_increments: 2000,
        // each increment's dissipation at most that of the one before
        max_growth: 1.0,
        dissipation: Some(1e-3),
        ..Default::default()
    };
    let mut bar = Softening { u: [0.0; 2], committed: [0.0; 2], kappa: 0.0, k: [[0.0; 2]; 2] };
    let mut record = SofteningRecord::default();
    trace(&mut bar, 0.0, &settings, &mut record, &Interrupt::new()).map_err(|e| e.to_string()).unwrap();
    let points = &record.0;
    let v0 = STRENGTH / K0;
    let (lambda, v, _) = *points.last().unwrap();
    assert!(lambda <= 0.01, "ended at λ = {lambda}, v = {v}");
    let softening: Vec<_> = points.iter().filter(|p| p.1 > v0 * (1.0 + 1e-9)).collect();
    for p in &softening {
        let exact = Softening::envelope(p.1) / STRENGTH;
        assert!((p.0 - exact).abs() < 1e-8, "λ = {} at v = {}: the envelope's {exact}", p.0, p.1);
    }
    assert!(softening.windows(2).all(|p| p[1].1 > p[0].1), "v went back");
    let w_peak = v0 + STRENGTH / KS;
    let w_min = points.iter().map(|p| p.2).fold(f64::INFINITY, f64::min);
    assert!(w_min < 0.5 * w_peak, "the load point's least {w_min}, its peak {w_peak}");
    // the increments' dissipation, as the constraint reckons it, against the law's
    let reckoned: f64 = std::iter::once((0.0, 0.0, 0.0))
        .chain(points.iter().copied())
        .collect::<Vec<_>>()
        .windows(2)
        .map(|p| 0.5 * STRENGTH * (p[0].0 * (p[1].2 - p[0].2) - (p[1].0 - p[0].0) * p[0].2))
        .sum();
    let exact = Softening::dissipated(v);
    eprintln!(
        "{} points, {} past the peak, {} corrections; w least {w_min:.4}; dissipation reckoned {reckoned:.6}, the law's {exact:.6}",
        points.len(),
        softening.len(),
        record.1
    );
    assert!(softening.len() >= 10 && record.1 > softening.len(), "{} points past the peak", softening.len());
    assert!((reckoned / exact - 1.0).abs() < 0.01, "reckoned {reckoned} against the law's {exact}");
}
