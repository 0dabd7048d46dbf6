//! Adaptive time steps (`solver.step_control.time_error`,
//! `dynamics::time_error`): the error estimate against the true local
//! error of an oscillator with a closed form, the global error and the
//! step count against the tolerance, and step ends and output frames hit
//! exactly.

#[path = "common/mod.rs"]
mod common;

const E: f64 = 200e9;
const RHO: f64 = 8000.0;
const V0: f64 = 1.0;

/// One B2 element of a steel bar (ν = 0), fixed at its root, flying off at
/// `V0` along its axis: the free end's four nodes move together, a single
/// degree of freedom of stiffness `EA/L` and consistent mass `ρAL/3` (the
/// B2 mass's free-node row with the root at rest), so
/// `u = (V0/ω) sin ωt`, `ω = √(3E/ρ)/L` (8,660 rad/s, a period of
/// 0.726 ms). Two periods, first step a hundredth of the step; `extra`
/// joins `[analysis]`, `control` is `solver.step_control`.
fn oscillator(control: &str, extra: &str, steps: &str) -> String {
    format!(
        r#"title = "Axial oscillator"

[analysis]
type = "transient"
initial_velocities = [{{ body = "bar", velocity = [0.0, {V0:?}, 0.0] }}]
{extra}

[solver]
{control}

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0

[[bodies]]
name = "bar"
material = "steel"
section = {{ shape = "rectangle", element = "L4", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B2", from = 0.0, to = 1.0, elements = 1 }}

[[constraints]]
name = "root"
body = "bar"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[constraints]]
name = "lateral"
body = "bar"
where = {{ y = [0.0, 1.0] }}
fix = ["x", "z"]

{steps}

[[probes]]
name = "tip"
point = [0.005, 1.0, 0.005]
"#
    )
}

fn omega() -> f64 {
    (3.0 * E / RHO).sqrt()
}

/// Two periods in one step of 100 increments (the first Δt with a step control).
fn two_periods() -> String {
    let period = 2.0 * std::f64::consts::PI / omega();
    format!("[[steps]]\nname = \"swing\"\nfactor = 1.0\nduration = {:?}\nincrements = 100\n", 2.0 * period)
}

/// The closed form's displacement, velocity and acceleration at `t`.
fn exact(t: f64) -> (f64, f64, f64) {
    let w = omega();
    ((V0 / w) * (w * t).sin(), V0 * (w * t).cos(), -V0 * w * (w * t).sin())
}

struct Run {
    sol: cufem::analysis::Solution,
    duration: f64,
}

fn run(tol: f64) -> Run {
    let text = oscillator(&format!("step_control = {{ time_error = {tol:e} }}"), "", &two_periods());
    let model = cufem::setup::Model::parse(&text).unwrap();
    let duration = model.transient.as_ref().unwrap().durations[0];
    Run { sol: common::run(&text), duration }
}

/// Per accepted step: the estimate the control measured, the true local
/// error of the same step from the exact state (one average-acceleration
/// step of the oscillator from the closed form's state at `t_n`, against
/// the closed form at `t_(n+1)`), both over the displacement scale (the
/// largest |u| so far, the step's end included), and `|cos ω t|` at the
/// step's middle (the leading error term's phase: `ȧ ∝ cos ωt`).
fn effectivities(r: &Run) -> Vec<(f64, f64, f64)> {
    let w = omega();
    let (mut scale, mut out) = (0.0f64, Vec::new());
    for (inc, row) in r.sol.increments.iter().zip(&r.sol.history) {
        let (t1, dt) = (inc.lambda * r.duration, inc.dlambda * r.duration);
        let (u, v, a) = exact(t1 - dt);
        let beta = 0.25;
        let u1 = (u + dt * v + dt * dt * (0.5 - beta) * a) / (1.0 + beta * dt * dt * w * w);
        scale = scale.max(row.probes[0][1].abs());
        let truth = (u1 - exact(t1).0).abs() / scale;
        out.push((inc.measure.time_error, truth, (w * (t1 - 0.5 * dt)).cos().abs()));
    }
    out
}

/// The estimate's effectivity (estimate over the true local error from the
/// exact state): both are `(β − 1/6) Δt³ ȧ` to leading order
/// (`dynamics::time_error`), the next term is `O(ωΔt tan ωt)` of it, so
/// the ratio is within [0.85, 1.15] on every step where `|cos ωt|` ≥ ½
/// (measured 0.888 … 1.129 at 1e-4, 0.951 … 1.057 at 1e-5; near the zeros
/// of `ȧ` the ratio is one of higher-order terms, down to 0.31 and up to
/// 1.24), and the sum of the estimates within 10 % of the sum of the true
/// errors over all steps (measured 0.962 and 0.978), at tolerances 1e-4
/// and 1e-5. The tolerance then bounds the local
/// error: no accepted step's estimate above twice it (the reject rule;
/// but for a step already redone once),
/// and the steps at the target: their median within [0.4, 1.0] of it (the
/// control aims at 0.8).
#[test]
fn the_estimate_follows_the_true_local_error_of_an_oscillator() {
    for tol in [1e-4, 1e-5] {
        let r = run(tol);
        let pairs = effectivities(&r);
        let ratios: Vec<f64> = pairs.iter().filter(|p| p.2 >= 0.5).map(|p| p.0 / p.1).collect();
        let (lo, hi) = ratios.iter().fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        let sum = pairs.iter().map(|p| p.0).sum::<f64>() / pairs.iter().map(|p| p.1).sum::<f64>();
        println!(
            "tol {tol:e}: {} steps, effectivity {lo:.3} … {hi:.3} over {} steps, of the sums {sum:.3}",
            pairs.len(),
            ratios.len()
        );
        assert!(ratios.len() > pairs.len() / 3 && lo > 0.85 && hi < 1.15, "{ratios:?}");
        assert!((sum - 1.0).abs() < 0.1, "{sum}");
        // a step redone once is accepted whatever its estimate (the first, from rest)
        let redone = |k: usize| r.sol.increments[k].cutbacks > 0;
        assert!(pairs.iter().enumerate().all(|(k, p)| p.0 <= 2.0 * tol || redone(k)), "{pairs:?}");
        let mut eta: Vec<f64> = pairs.iter().map(|p| p.0 / tol).collect();
        eta.sort_by(f64::total_cmp);
        let median = eta[eta.len() / 2];
        assert!((0.4..=1.0).contains(&median), "{median}");
    }
}

/// With a tolerance ten times smaller, the local error per step `∝ Δt³`
/// gives `10^(1/3)` = 2.15 times the steps, and the global (phase) error of
/// the trapezoidal rule, `∝ Δt²` over the same time, `10^(2/3)` = 4.64
/// times less (error per step control: the end error scales with
/// `tol^(2/3)`, not `tol`). Measured on the oscillator at 1e-4 and 1e-5
/// over two periods (measured 112 → 237 steps, ×2.116; end error
/// 1.637e-2 → 3.872e-3 of the amplitude, ÷4.228); both ratios within 15 %
/// of theory (the first step's cutback, the last step's landing on the end
/// and the phase error's higher-order terms are not in the asymptote).
#[test]
fn steps_and_error_follow_the_tolerance_as_theory_says() {
    let end_error = |r: &Run| {
        let u = r.sol.history.last().unwrap().probes[0][1];
        (u - exact(r.duration).0).abs() / (V0 / omega())
    };
    let (coarse, fine) = (run(1e-4), run(1e-5));
    let steps = fine.sol.increments.len() as f64 / coarse.sol.increments.len() as f64;
    let error = end_error(&coarse) / end_error(&fine);
    println!(
        "steps {} → {} (×{steps:.3}, theory 2.154), end error {:.3e} → {:.3e} (÷{error:.3}, theory 4.642)",
        coarse.sol.increments.len(),
        fine.sol.increments.len(),
        end_error(&coarse),
        end_error(&fine)
    );
    assert!((steps / 10f64.powf(1.0 / 3.0) - 1.0).abs() < 0.15, "{steps}");
    assert!((error / 10f64.powf(2.0 / 3.0) - 1.0).abs() < 0.15, "{error}");
}

/// Two load steps of different lengths and frames every 0.13 ms (not a
/// multiple of any step): the adaptive steps land on every frame time and
/// on both step ends (to round-off), and still vary in length.
#[test]
fn adaptive_steps_land_on_step_ends_and_frames() {
    let steps = "[[steps]]\nname = \"a\"\nfactor = 1.0\nduration = 5e-4\nincrements = 20\n\n\
                 [[steps]]\nname = \"b\"\nfactor = 1.0\nduration = 7e-4\nincrements = 20\n";
    let text = oscillator("step_control = { time_error = 1e-4 }", "output_interval = 1.3e-4", steps);
    let model = cufem::setup::Model::parse(&text).unwrap();
    let sol = common::run(&text);
    let times: Vec<f64> = sol.frames.iter().map(|f| f.time).collect();
    assert_eq!(times.len(), 9, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        assert!((t - 1.3e-4 * (k + 1) as f64).abs() < 1e-12 * 1.2e-3, "frame {k} at {t} s");
    }
    assert_eq!(sol.steps.iter().map(|s| s.lambda).collect::<Vec<_>>(), vec![1.0, 2.0]);
    let tr = model.transient.as_ref().unwrap();
    assert!(sol.history.iter().any(|r| (tr.time(r.lambda) - 5e-4).abs() < 1e-15));
    assert!((tr.time(sol.history.last().unwrap().lambda) - 1.2e-3).abs() < 1e-15);
    let dt: Vec<f64> = sol.increments.iter().map(|i| i.dlambda).collect();
    let (lo, hi) = dt.iter().fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi > 2.0 * lo, "{dt:?}");
}

/// A rigid hammer (0.8 kg = ρAL, 1 m/s, `[[indenters]] mass, velocity`,
/// penalty factor 1) flies 100 µm onto the free end of a 1 m steel rod
/// (200 B2) fixed at the other, for 0.5 ms after a 1 µs start: in contact
/// the hammer follows Saint-Venant's `d = gap + v₀ τ (1 − e^(−(t − t₀)/τ))`,
/// `τ = M/(ρAc)` = L/c, until the reflected wave returns at `2L/c`
/// (Timoshenko & Goodier, *Theory of Elasticity*, §151; tests/dynamics.rs
/// checks the fixed-step run). Returns the hammer's largest difference from
/// it over 10 % to 95 % of `2L/c` after the touch (relative), the time
/// steps and the energy balance's largest magnitude over the largest
/// kinetic energy.
fn hammer_on_rod(step_control: &str, increments: usize) -> (f64, usize, f64) {
    let hold = 5e-4;
    let text = common::step_loaded_bar(200, 0.0, hold, increments, "")
        .replace(
            "[[loads]]\nname = \"end\"\nbody = \"bar\"\nwhere = { y = 1.0 }\ntotal_force = [0.0, 0.0, 0.0]\n",
            "[[indenters]]\nname = \"hammer\"\nbody = \"bar\"\nshape = \"flat\"\nsurface = { y = 1.0 }\nnormal = \"-y\"\n\
             position = 1.0001\nmass = 0.8\nvelocity = [0.0, -1.0, 0.0]\npenalty_factor = 1.0\n",
        )
        .replace("name = \"rise\"\nfactor = 1.0\nduration = 1e-9", "name = \"rise\"\nfactor = 1.0\nduration = 1e-6")
        .replace("max_increments = 5000", &format!("max_increments = 5000\n{step_control}"));
    assert!(text.contains("hammer") && !text.contains("total_force"), "{text}");
    let sol = common::run(&text);
    let (c, area, v0, mass, gap) = ((E / RHO).sqrt(), 1e-4, 1.0, 0.8, 1e-4);
    let tau = mass / (RHO * area * c);
    let t0 = gap / v0;
    let time_of = |lambda: f64| if lambda <= 1.0 { lambda * 1e-6 } else { 1e-6 + (lambda - 1.0) * hold };
    let travel = |t: f64| if t < t0 { v0 * t } else { gap + v0 * tau * (1.0 - (-(t - t0) / tau).exp()) };
    let span = 2.0 / c;
    let mut worst: f64 = 0.0;
    for r in &sol.history {
        let (t, d) = (time_of(r.lambda), -r.contact("hammer").unwrap().displacement[1]);
        if t > t0 + 0.1 * span && t < t0 + 0.95 * span {
            worst = worst.max((d - travel(t)).abs() / travel(t));
        }
    }
    let rows = sol.energy.as_ref().unwrap();
    let scale = rows.iter().map(|e| e.kinetic.max(e.impactors)).fold(0.0, f64::max);
    let balance = rows.iter().map(|e| e.balance.abs()).fold(0.0, f64::max) / scale;
    (worst, sol.increments.len(), balance)
}

/// The impact check of issue 50 is not met on this model, a known limit
/// asserted from both sides (docs/limitations.md): the hammer's history is
/// at its discretisation's floor (1.72e-3 to 1.74e-3 of Saint-Venant's from
/// 500 fixed steps of 1 µs down to 60 of 8.3 µs: the rod's 200 B2 and the
/// penalty contact, not Δt, set it), and the error estimate, driven by the
/// rod's wave front, asks for more steps than that: 166 with
/// `time_error = 1e-3` for the same 1.74e-3 (60 fixed steps: 1.726e-3).
/// The energy ledger closes with adaptive steps as with fixed ones: its
/// balance within 1e-6 of the largest kinetic energy (the tolerance of
/// tests/dynamics.rs's trapezoidal-rule check; measured 4.0e-7 adaptive,
/// 1.7e-7 fixed), and the adaptive run is as accurate as the fixed ones
/// (hammer within 2e-3 of the closed form).
#[test]
fn adaptive_steps_on_a_hammer_striking_a_rod_against_fixed_ones() {
    let (fixed, fixed_steps, fixed_balance) = hammer_on_rod("", 60);
    let (adaptive, steps, balance) = hammer_on_rod("step_control = { time_error = 1e-3 }", 50);
    println!(
        "fixed: {fixed_steps} steps, hammer {fixed:.4e}, balance {fixed_balance:.2e}; adaptive: {steps} steps, \
         hammer {adaptive:.4e}, balance {balance:.2e}"
    );
    assert!(fixed < 2e-3 && adaptive < 2e-3, "{fixed} {adaptive}");
    assert!(balance < 1e-6 && fixed_balance < 1e-6, "{balance} {fixed_balance}");
    let what = "time steps of the adaptive run (time_error = 1e-3) over the fixed run's 61 of the same accuracy";
    common::known_limit("adaptive_time.hammer.step_ratio", steps as f64 / fixed_steps as f64, "", 2.3, 3.2, what);
}
