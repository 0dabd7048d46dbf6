//! Implicit transient dynamics (`analysis.type = "transient"`): waves
//! against d'Alembert, the trapezoidal rule's energy conservation, Newmark
//! dissipation and Rayleigh damping against their closed forms.

#[path = "../../../tests/common/mod.rs"]
mod common;

const E: f64 = 200e9;
const RHO: f64 = 8000.0;

/// The step-loaded bar of `common::step_loaded_bar` on 200 B2.
fn bar(force: f64, hold: f64, steps: usize, analysis: &str) -> String {
    common::step_loaded_bar(200, force, hold, steps, analysis)
}

/// Time (s) of analysis time λ in the bar's history (1 ns, then `hold`).
fn time(lambda: f64, hold: f64) -> f64 {
    if lambda <= 1.0 { lambda * 1e-9 } else { 1e-9 + (lambda - 1.0) * hold }
}

/// A step end load `F` on a fixed–free rod: the end moves as d'Alembert's
/// triangle wave, `u(L, t) = F c t / (E A)` up to `2L/c`, back to zero at
/// `4L/c` (Graff, *Wave Motion in Elastic Solids*, §1.4), with
/// `c = √(E/ρ)` = 5,000 m/s; the middle of the rod stays at rest until the
/// front arrives at `L/2c`. 200 B2 and Δt = 1 µs (a Courant number of 1):
/// the end within 2 % of the peak `2FL/(EA)` over the whole period
/// (measured 0.6 %, issue 27 asks 2 %), the middle below 1 % of it before
/// `0.95 L/2c` and moving after `1.05 L/2c`.
#[test]
fn a_step_load_travels_along_a_bar_as_dalembert_says() {
    let (force, area, length) = (1000.0, 1e-4, 1.0);
    let c = (E / RHO).sqrt();
    let period = 4.0 * length / c;
    let sol = common::run(&bar(force, period, 800, ""));
    let peak = 2.0 * force * length / (E * area);
    let exact = |t: f64| {
        let t = t % period;
        if t <= 2.0 * length / c { peak * t / (2.0 * length / c) } else { peak * (2.0 - t / (2.0 * length / c)) }
    };
    let mut worst: f64 = 0.0;
    for row in &sol.history {
        let t = time(row.lambda, period);
        let end = row.probes[0][1];
        worst = worst.max((end - exact(t)).abs() / peak);
        let middle = row.probes[1][1].abs();
        if t < 0.95 * length / (2.0 * c) {
            assert!(middle < 0.01 * peak, "the middle moves at t = {t} s before the front: {middle} m");
        }
        if t > 1.05 * length / (2.0 * c) && t < 1.5 * length / c {
            assert!(middle > 0.01 * peak, "the middle is still at rest at t = {t} s: {middle} m");
        }
    }
    println!("largest difference from d'Alembert: {:.3} % of the peak", 100.0 * worst);
    assert!(worst < 0.02, "{worst}");
}

/// The trapezoidal rule (β = ¼, γ = ½, the default) conserves the energy of
/// an undamped linear elastic body exactly: the bar under its held load,
/// 1,000 steps over more than a period, keeps `W_ext − T − W_int` within
/// 1e-6 of the largest energy (issue 27; measured at round-off, 1e-12).
/// Newmark with γ = 0.6, β = 0.3025 dissipates: over the same steps its
/// balance grows to more than 1 % of the energy — the numerical damping
/// the test shows for contrast.
#[test]
fn the_trapezoidal_rule_conserves_energy_and_a_dissipative_newmark_does_not() {
    let c = (E / RHO).sqrt();
    let hold = 1.25 * 4.0 / c;
    let balance = |analysis: &str| {
        let sol = common::run(&bar(1000.0, hold, 1000, analysis));
        let rows = sol.energy.unwrap();
        assert_eq!(rows.len(), 1002, "the initial state and every step");
        let scale = rows.iter().map(|r| r.external.abs().max(r.kinetic)).fold(0.0, f64::max);
        rows.iter().map(|r| r.balance.abs()).fold(0.0, f64::max) / scale
    };
    let trapezoidal = balance("");
    // an elastic body's internal work is its elastic strain energy: the
    // trapezoidal work of the nodal forces against ½ ∫ σᵀ C⁻¹ σ dV of the
    // Gauss-point stresses, the same quadrature as K (round-off apart)
    let sol = common::run(&bar(1000.0, hold, 100, ""));
    let last = *sol.energy.unwrap().last().unwrap();
    println!("internal work {:e} J, elastic strain energy {:e} J", last.internal, last.elastic);
    assert!(last.plastic.abs() < 1e-9 * last.internal, "{last:?}");
    let dissipative = balance("newmark = { beta = 0.3025, gamma = 0.6 }");
    println!("largest energy imbalance: trapezoidal {trapezoidal:.2e}, γ = 0.6 {dissipative:.2e} of the energy");
    assert!(trapezoidal < 1e-6, "{trapezoidal}");
    assert!(dissipative > 1e-2, "{dissipative}");
}

/// A bar of 4 B2 pulled at its end by a load that rises over 0.2 ms and is
/// then held for 1 ms (its first period is 0.8 ms): `n` steps over the
/// rise, `5 n` over the hold. Returns the end's displacement at the last
/// step (m) and the energy balance there (J).
fn ramped_bar(n: usize, newmark: &str) -> (f64, f64) {
    let text = common::step_loaded_bar(4, 1000.0, 1e-3, 5 * n, newmark)
        .replace("duration = 1e-9\nincrements = 1", &format!("duration = 2e-4\nincrements = {n}"));
    assert!(text.contains("duration = 2e-4"));
    let sol = common::run(&text);
    let end = sol.history.last().unwrap().probes[0][1];
    (end, sol.energy.unwrap().last().unwrap().balance)
}

/// Bossak's method (`newmark = { alpha }`, `γ = ½ − α`, `β = ¼ (1 − α)²`;
/// Wood, Bossak & Zienkiewicz, IJNME 15, 1980) is second-order accurate
/// where Newmark's method with the same `γ > ½` is first order (Hughes,
/// *The Finite Element Method*, §9.3): on the ramped bar ([`ramped_bar`])
/// halving the step from 40 to 80 steps over the rise divides the error of
/// the end's final displacement (against 640 trapezoidal steps) by 4.45 for
/// α = −0.1 and by 1.98 for Newmark's γ = 0.6, β = 0.3025 (measured: the
/// observed orders 2.15 and 0.99, asserted within 0.3 of 2 and 0.2 of 1);
/// and its energy balance, the scheme's dissipation, is two orders of
/// magnitude smaller (measured `3.8e-6` against `6.4e-4` J at 40 steps).
/// Dropping the `α M a_n` term of the inertia force (then γ = 0.6 Newmark
/// with a 10 % lighter mass) fails it: the error no longer falls (ratio
/// 1.00, tried by hand).
#[test]
fn bossak_is_second_order_where_a_dissipative_newmark_is_first_order() {
    let (reference, _) = ramped_bar(640, "");
    let order = |newmark: &str| {
        let [(u40, balance), (u80, _)] = [40, 80].map(|n| ramped_bar(n, newmark));
        ((u40 - reference).abs() / (u80 - reference).abs(), balance)
    };
    let (bossak, bossak_balance) = order("newmark = { alpha = -0.1 }");
    let (newmark, newmark_balance) = order("newmark = { beta = 0.3025, gamma = 0.6 }");
    println!("error ratio under halving Δt: Bossak {bossak:.2}, Newmark γ = 0.6 {newmark:.2}");
    println!("balance at 40 steps: Bossak {bossak_balance:e} J, Newmark {newmark_balance:e} J");
    // the observed orders log₂(ratio): 2 and 1 in theory
    let (bossak, newmark) = (bossak.log2(), newmark.log2());
    common::figure(
        "dynamics.bossak.order",
        bossak,
        "",
        "observed order under halving Δt within 1.7–2.3 (second order)",
    );
    assert!((1.7..2.3).contains(&bossak), "{bossak}");
    assert!((0.8..1.2).contains(&newmark), "{newmark}");
    assert!(bossak_balance > 0.0 && bossak_balance < 0.02 * newmark_balance, "{bossak_balance} {newmark_balance}");
}

/// Mass-proportional Rayleigh damping `C = α M` damps every mode at the
/// same rate, its amplitude as `e^(−α t/2)` (modal damping ratio
/// `ζ_n = α / 2ω_n`, Chopra, *Dynamics of Structures*, §11.4): the bar's
/// end oscillates about its static stretch `u_s = FL/(EA)`, the deviation
/// starting at `−u_s` and, undamped, back at `−u_s` after one period
/// `4L/c`. With α = 2,000 /s, after one period it is `−u_s e^(−α·2L/c)`
/// (= 0.449 u_s) within 5 % (the damped frequencies differ from the
/// undamped ones by at most 0.8 %); and with the dissipated energy in the
/// ledger the balance still closes (1e-6 of the work of the load).
#[test]
fn mass_proportional_damping_decays_every_mode_at_its_rate() {
    let (force, area, length, alpha) = (1000.0, 1e-4, 1.0, 2000.0);
    let c = (E / RHO).sqrt();
    let period = 4.0 * length / c;
    let sol = common::run(&bar(force, 1.5 * period, 1200, &format!("damping = {{ mass = {alpha} }}")));
    let u_s = force * length / (E * area);
    // the deviation at the end of the first period (its extreme there)
    let at_period = sol
        .history
        .iter()
        .filter(|r| (time(r.lambda, 1.5 * period) - period).abs() < 0.05 * period)
        .map(|r| r.probes[0][1] - u_s)
        .fold(0.0, |m: f64, d| if d.abs() > m.abs() { d } else { m });
    let want = -u_s * (-alpha * period / 2.0).exp();
    println!("deviation after one period {at_period:e} m against {want:e} m");
    assert!((at_period / want - 1.0).abs() < 0.05, "{at_period} against {want}");
    let rows = sol.energy.unwrap();
    let last = rows.last().unwrap();
    assert!(last.damping > 0.1 * last.external, "{last:?}");
    assert!((last.balance / last.external).abs() < 1e-6, "{last:?}");
}

/// What a transient analysis cannot take is refused by its key.
#[test]
fn transient_refuses_what_it_cannot_integrate() {
    let text = bar(1000.0, 1e-3, 10, "");
    let cases = [
        (text.replace("duration = 0.001\n", "").replace("duration = 1e-9\n", ""), "analysis.duration"),
        (text.replace("duration = 1e-9", "duration = -1.0"), "steps[0].duration = -1"),
        (
            text.replace("type = \"transient\"", "type = \"transient\"\nnewmark = { beta = 0.1, gamma = 0.5 }"),
            "analysis.newmark.beta",
        ),
        (
            text.replace("type = \"transient\"", "type = \"transient\"\nnewmark = { beta = 0.25, gamma = 0.4 }"),
            "analysis.newmark.gamma",
        ),
        // Bossak's α outside [−⅓, 0]; and a γ given without its β, whose
        // default ¼ (1 − α)² = ¼ is below the stable ¼ (γ + ½)²
        (
            text.replace("type = \"transient\"", "type = \"transient\"\nnewmark = { alpha = 0.1 }"),
            "analysis.newmark.alpha = 0.1",
        ),
        (
            text.replace("type = \"transient\"", "type = \"transient\"\nnewmark = { gamma = 0.6 }"),
            "analysis.newmark.beta = 0.25",
        ),
        (
            text.replace("type = \"transient\"", "type = \"transient\"\ndamping = { mass = -1.0 }"),
            "analysis.damping.mass",
        ),
        (
            text.replace(
                "type = \"transient\"",
                "type = \"transient\"\ninitial_velocities = [{ body = \"rod\", velocity = [0.0, 1.0, 0.0] }]",
            ),
            "analysis.initial_velocities[0].body",
        ),
        (text.replace("density = 8000", "# no density"), "materials[0].density = (missing)"),
        (text.replace("type = \"transient\"", "type = \"static\""), "steps[0].duration"),
        (text.replace("type = \"transient\"", "type = \"transient\"\nmodes = 3"), "analysis.modes"),
    ];
    for (model, key) in cases {
        match cufem::setup::Model::parse(&model) {
            Err(e) => assert!(e.to_string().contains(key), "{key}: {e}"),
            Ok(_) => panic!("{key}: accepted"),
        }
    }
}

/// Runs a model file through the CLI into the test folder; its output folder.
fn run_cli(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("dynamics_{name}"));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet", "--force"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
    out
}

/// The columns of a CSV file by header name.
fn columns(path: &std::path::Path) -> std::collections::HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    let mut cols: std::collections::HashMap<String, Vec<f64>> = names.iter().map(|n| (n.clone(), Vec::new())).collect();
    for line in lines {
        for (n, v) in names.iter().zip(line.split(',')) {
            cols.get_mut(n).unwrap().push(v.parse().unwrap_or(f64::NAN));
        }
    }
    cols
}

/// The energy `T + W_int` at the end over `T₀` and the contacts' net work
/// over `T₀` of a run's energy.csv.
fn energy_ratio(out: &std::path::Path) -> (f64, f64) {
    let e = columns(&out.join("energy.csv"));
    let n = e["time_s"].len() - 1;
    let t0 = e["kinetic_J"][0];
    ((e["kinetic_J"][n] + e["internal_J"][n]) / t0, e["contact_J"][n] / t0)
}

/// `examples/rod_impact.toml` with `line` added to its `[analysis]`.
fn rod_impact(line: &str) -> String {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/rod_impact.toml");
    let text = std::fs::read_to_string(path).unwrap();
    text.replace("type = \"transient\"\n", &format!("type = \"transient\"\n{line}\n"))
}

/// The wall's contact force of a rod_impact run: (time in s, force in N
/// pushing the rod back) per time step.
fn wall_force(out: &std::path::Path) -> Vec<(f64, f64)> {
    let wall = columns(&out.join("history_wall.csv"));
    wall["lambda"].iter().zip(&wall["f_y"]).map(|(l, f)| (l * 6e-4, -f)).collect()
}

/// `examples/rod_impact.toml` through the CLI: an elastic rod at v₀ = 1 m/s
/// against a rigid wall stays in contact for `2L/c` = 0.4 ms and leaves
/// with `−v₀` and its kinetic energy (the 1D wave solution, Graff §1.4):
/// duration within 2 %, the free end's mean velocity after separation
/// within 2 % of −v₀, the energy `T + W_int` at the end within 1 % of `T₀`
/// — the checks — at the default penalty factor (100), whose
/// contact spring the 1 µs step does not resolve, with the defaults of a
/// transient contact: the contact impulse at the end of each step
/// (`dynamics::impulse`) and the contact nodes massless
/// (`dynamics::redistribution`): the contact's net work is a loss (it
/// cannot create energy) below 1 % of `T₀` (measured 1.2e-4). For
/// contrast the plain penalty — Newmark's average of the contact forces
/// with the contact nodes' mass kept — creates energy: the rod leaves with
/// 5.16 times its energy, asserted from both sides (3 to 12: the
/// chatter's gain depends on every bounce, so on round-off — the same
/// model gave 8.41 with faer's simplicial factor of the stiffness and 5.16
/// with its supernodal one, `solver::linear::SUPERNODAL`), and the run warns
/// (summary.json).
#[test]
fn a_rod_rebounds_from_a_rigid_wall_after_two_transit_times() {
    let text = rod_impact("");
    let (c, length, v0) = ((200e9f64 / 8000.0).sqrt(), 1.0, 1.0);
    let out = run_cli("rod_impact", &text);
    let force = wall_force(&out);
    let touching: Vec<f64> = force.iter().filter(|(_, f)| f.abs() > 0.0).map(|(t, _)| *t).collect();
    let duration = touching.last().unwrap() - touching[0];
    println!(
        "contact {:e} s to {:e} s: {duration:e} s against 2L/c = {:e} s",
        touching[0],
        touching.last().unwrap(),
        2.0 * length / c
    );
    assert!((duration / (2.0 * length / c) - 1.0).abs() < 0.02, "{duration}");
    let time: Vec<f64> = force.iter().map(|r| r.0).collect();
    let probes = columns(&out.join("history_probes.csv"));
    let tail = &probes["tail.u_y"];
    let (i1, i2) = (time.iter().position(|&t| t >= 4.5e-4).unwrap(), time.len() - 1);
    let rebound = (tail[i2] - tail[i1]) / (time[i2] - time[i1]);
    println!("rebound velocity {rebound} m/s");
    assert!((rebound / -v0 - 1.0).abs() < 0.02, "{rebound}");
    let (energy, contact_work) = energy_ratio(&out);
    println!("energy at the end {energy} of T0, the contact's net work {contact_work} of T0");
    assert!((energy - 1.0).abs() < 0.01 && (-0.01..=0.0).contains(&contact_work), "{energy} {contact_work}");
    // the plain penalty: Newmark's average of the contact forces, the
    // contact nodes' mass kept: energy created
    let plain = run_cli("rod_impact_plain", &rod_impact("contact_forces = \"newmark\"\ncontact_mass = \"kept\""));
    let (energy, _) = energy_ratio(&plain);
    let what = "energy after the impact with Newmark's average of the contact forces, the nodes' mass kept";
    common::known_limit("dynamics.newmark_average.energy_ratio", energy, "", 3.0, 12.0, what);
    let summary = std::fs::read_to_string(plain.join("summary.json")).unwrap();
    assert!(summary.contains("net work"), "no warning in {summary}");
    // the ParaView time series: a frame every 50 µs of the 600 µs, each
    // counted by the memory estimate
    let pvd = std::fs::read_to_string(out.join("frames.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 12, "{pvd}");
    let model = cufem::setup::Model::parse(&text).unwrap();
    assert_eq!(cufem::analysis::plan(&model).unwrap().snapshots, 12);
    assert!(out.join("frame_0012.vtu").exists());
}

/// The middle 80 % of a contact: the force samples after the first tenth
/// and before the last tenth of the time from first touch to the last step
/// with a force, and whether the contact opened in between.
fn plateau(force: &[(f64, f64)]) -> (Vec<f64>, usize, f64) {
    let first = force.iter().position(|r| r.1 > 0.0).unwrap();
    let last = force.iter().rposition(|r| r.1 > 0.0).unwrap();
    let (t0, t1) = (force[first].0, force[last].0);
    let span = t1 - t0;
    let middle = force.iter().filter(|r| r.0 >= t0 + 0.1 * span && r.0 <= t1 - 0.1 * span).map(|r| r.1).collect();
    let opened = force[first..=last].iter().filter(|r| r.1 <= 0.0).count();
    (middle, opened, span)
}

/// Saint-Venant's impact force (Graff, *Wave Motion in Elastic Solids*,
/// §1.4): the rod of `examples/rod_impact.toml` pushes on the wall with
/// `ρ c v₀ A` = 8000 · 5000 · 1 · 1e-4 = 4.0 kN from first touch until
/// the wave's return at `2L/c` = 400 µs. With the contact nodes massless
/// (`analysis.contact_mass = "redistributed"`, the default) and the
/// contact impulse at the end of the step (the default): the wall's force
/// within 5 % of 4.0 kN over the middle 80 % of the contact (issue 46;
/// measured 0.71 %: the mesh's dispersion, largest as the unloading wave
/// returns), no step of the contact without force, the contact time
/// within 2 % of 2L/c (measured −0.5 %), and the energy `T + U` (kinetic
/// and elastic strain energy) above `T₀` at no step beyond round-off
/// (1e-9 of it; measured 1.1e-12, in free flight). With the contact
/// nodes' mass kept (`"kept"`) the force chatters: the end node stops
/// dead, opens in the contact's second step and rings (a peak of 7.3 kN,
/// asserted above 6 kN). A 10 % error in the density (the mass matrix)
/// fails the plateau (7.7 %) and the contact time (+4.3 %), tried by hand.
#[test]
fn the_wall_force_follows_saint_venants_plateau() {
    let (rho, c, v0, area, length) = (8000.0, (200e9f64 / 8000.0).sqrt(), 1.0, 1e-4, 1.0);
    let plateau_force = rho * c * v0 * area;
    let out = run_cli("rod_impact_plateau", &rod_impact(""));
    let force = wall_force(&out);
    let (middle, opened, span) = plateau(&force);
    let worst = middle.iter().map(|f| (f / plateau_force - 1.0).abs()).fold(0.0, f64::max);
    println!(
        "{} steps in the middle 80 %: largest deviation {:.2} % of {plateau_force} N; {opened} open steps; contact \
         {span:e} s",
        middle.len(),
        100.0 * worst
    );
    assert!(middle.len() > 300 && worst < 0.05, "{worst}");
    assert_eq!(opened, 0, "the contact opened {opened} times");
    assert!((span / (2.0 * length / c) - 1.0).abs() < 0.02, "{span}");
    let e = columns(&out.join("energy.csv"));
    let t0 = e["kinetic_J"][0];
    let most = e["kinetic_J"].iter().zip(&e["elastic_J"]).map(|(t, u)| (t + u) / t0).fold(0.0, f64::max);
    println!("largest T + U: {most} of T0");
    assert!(most <= 1.0 + 1e-9, "{most}");
    // the contact nodes' mass kept: the end chatters on the wall
    let kept = run_cli("rod_impact_kept", &rod_impact("contact_mass = \"kept\""));
    let force = wall_force(&kept);
    let (_, opened, _) = plateau(&force);
    let peak = force.iter().map(|r| r.1).fold(0.0, f64::max);
    println!("the contact nodes' mass kept: {opened} open steps, peak {peak} N");
    assert!(opened > 0 && peak > 1.5 * plateau_force, "{opened} {peak}");
}

/// Two identical rods colliding at ±1 m/s (node-to-node contact between
/// bodies, `[[contacts]]`): the interface stays at rest and each rod
/// carries Saint-Venant's stress `ρ c v₀` until its wave returns at `2L/c`
/// (Graff §1.4), a contact force of 4.0 kN. With both sides' contact nodes
/// massless (the default) the force is within 5 % of it over the middle
/// 80 % of the contact (measured 0.71 %) and never zero inside it, and the
/// energy never above the initial beyond round-off (measured 1.5e-12);
/// with their mass kept the ends chatter (measured 9.6 %, an open step).
#[test]
fn two_colliding_rods_push_with_saint_venants_force() {
    let rod = |name: &str, from: f64| {
        format!(
            "[[bodies]]\nname = \"{name}\"\nmaterial = \"steel\"\nsection = {{ shape = \"rectangle\", element = \"L4\", \
             x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}\n\
             axis = {{ element = \"B2\", from = {from:?}, to = {:?}, elements = 100 }}\n\n",
            from + 1.0
        )
    };
    let text = format!(
        "[analysis]\ntype = \"transient\"\ninitial_velocities = [{{ body = \"left\", velocity = [0.0, 1.0, 0.0] }}, \
         {{ body = \"right\", velocity = [0.0, -1.0, 0.0] }}]\n\n[[materials]]\nname = \"steel\"\n\
         young_modulus = 200e9\npoisson_ratio = 0.0\ndensity = 8000.0\n\n{}{}[[contacts]]\nname = \"ends\"\n\
         master = {{ body = \"right\", where = {{ y = 1.00002 }} }}\nslave = {{ body = \"left\", where = {{ y = 1.0 }} }}\n\n\
         [[steps]]\nname = \"flight\"\nfactor = 1.0\nduration = 6e-4\nincrements = 600\n",
        rod("left", 0.0),
        rod("right", 1.00002)
    );
    let run = |text: &str| {
        let sol = common::run(text);
        let force: Vec<(f64, f64)> =
            sol.history.iter().map(|r| (r.lambda * 6e-4, r.contact("ends").unwrap().force[1].abs())).collect();
        let energy = sol.energy.unwrap();
        let t0 = energy[0].kinetic;
        (force, energy.iter().map(|r| (r.kinetic + r.elastic) / t0).fold(0.0, f64::max))
    };
    let (force, most) = run(&text);
    let (middle, opened, _) = plateau(&force);
    let worst = middle.iter().map(|f| (f / 4000.0 - 1.0).abs()).fold(0.0, f64::max);
    println!("largest deviation {:.2} %, {opened} open steps, largest T + U {most} of T0", 100.0 * worst);
    assert!(middle.len() > 300 && worst < 0.05 && opened == 0, "{worst} {opened}");
    assert!(most <= 1.0 + 1e-9, "{most}");
    let (force, _) = run(&text.replace("type = \"transient\"\n", "type = \"transient\"\ncontact_mass = \"kept\"\n"));
    let (middle, opened, _) = plateau(&force);
    let worst = middle.iter().map(|f| (f / 4000.0 - 1.0).abs()).fold(0.0, f64::max);
    println!("the contact nodes' mass kept: largest deviation {:.2} %, {opened} open steps", 100.0 * worst);
    assert!(worst > 0.05 && opened > 0, "{worst} {opened}");
}

/// A frame (`analysis.output_interval`) holds the state of the increment it
/// was taken at: the tip displacement sampled from the frame's fields
/// equals the probe history's at that increment, and the frames come at
/// the first converged time at or past each multiple of the interval.
#[test]
fn frames_hold_the_fields_of_their_time() {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/rod_impact.toml");
    let text = std::fs::read_to_string(path).unwrap().replace("output_interval = 5e-5", "output_interval = 1.5e-4");
    let model = cufem::setup::Model::parse(&text).unwrap();
    let sol = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let times: Vec<f64> = sol.frames.iter().map(|f| f.time).collect();
    assert_eq!(times.len(), 4, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        assert!((t - 1.5e-4 * (k + 1) as f64).abs() < 1e-6 * 6e-4, "frame {k} at {t} s");
        let snapshot = sol.at_frame(&model, k).unwrap();
        let tip = snapshot.fields(&model).sample_probe(&model.probes[0]).unwrap().u;
        let row = &sol.history[sol.frames[k].increment - 1];
        assert!((tip[1] - row.probes[0][1]).abs() <= 1e-12 * row.probes[0][1].abs().max(1e-9), "{tip:?} {row:?}");
    }
}

/// A rigid mass striking the free end of a rod fixed at the other end
/// (`[[indenters]] mass, velocity`): until the reflected wave returns at
/// `2L/c` the end moves with the mass and radiates a wave of stress
/// `ρ c v`, so `M v̇ = −A ρ c v`, `v = v₀ e^(−t/τ)`, `τ = M/(ρ A c)`, and
/// the mass has travelled `v₀ τ (1 − e^(−t/τ))` (Saint-Venant; Timoshenko
/// & Goodier, *Theory of Elasticity*, §151). M = ρ A L (τ = L/c),
/// v₀ = 1 m/s, a 10 µm gap, penalty factor 1: the mass's displacement
/// within 1 % of that over the contact (measured 0.36 %, its end nodes massless), and its mean
/// force over each quarter of `2L/c` within 5 % of the closed form's (the
/// contact spring rings about it; measured within 2.4 %).
#[test]
fn a_mass_striking_a_rod_follows_saint_venants_solution() {
    let text = bar(0.0, 4e-4, 400, "")
        .replace(
            "[[loads]]\nname = \"end\"\nbody = \"bar\"\nwhere = { y = 1.0 }\ntotal_force = [0.0, 0.0, 0.0]\n",
            "[[indenters]]\nname = \"hammer\"\nbody = \"bar\"\nshape = \"flat\"\nsurface = { y = 1.0 }\nnormal = \"-y\"\n\
             position = 1.00001\nmass = 0.8\nvelocity = [0.0, -1.0, 0.0]\npenalty_factor = 1.0\n",
        )
        .replace("name = \"rise\"\nfactor = 1.0\nduration = 1e-9", "name = \"rise\"\nfactor = 1.0\nduration = 1e-6");
    assert!(text.contains("hammer") && !text.contains("total_force"), "{text}");
    let sol = common::run(&text);
    let (rho, c, area, v0, mass, gap) = (RHO, (E / RHO).sqrt(), 1e-4, 1.0, 0.8, 1e-5);
    let tau = mass / (rho * area * c);
    let t0 = gap / v0;
    let time_of = |lambda: f64| if lambda <= 1.0 { lambda * 1e-6 } else { 1e-6 + (lambda - 1.0) * 4e-4 };
    let rows: Vec<(f64, f64, f64)> = sol
        .history
        .iter()
        .map(|r| {
            let h = r.contact("hammer").unwrap();
            (time_of(r.lambda), -h.displacement[1], -h.force[1])
        })
        .collect();
    let travel = |t: f64| if t < t0 { v0 * t } else { gap + v0 * tau * (1.0 - (-(t - t0) / tau).exp()) };
    let span = 2.0 / c;
    let mut worst: f64 = 0.0;
    for &(t, d, _) in rows.iter().filter(|r| r.0 > t0 + 0.1 * span && r.0 < t0 + 0.95 * span) {
        worst = worst.max((d - travel(t)).abs() / travel(t));
    }
    println!("mass displacement within {:.3} % of Saint-Venant's", 100.0 * worst);
    assert!(worst < 0.01, "{worst}");
    for q in 0..4 {
        let (a, b) = (t0 + 0.25 * q as f64 * span, t0 + 0.25 * (q + 1) as f64 * span);
        let window: Vec<f64> = rows.iter().filter(|r| r.0 > a && r.0 <= b).map(|r| r.2).collect();
        let mean = window.iter().sum::<f64>() / window.len() as f64;
        // the closed form's mean force over [a, b]: M (v(a) − v(b)) / (b − a)
        let exact = mass * v0 * ((-(a - t0) / tau).exp() - (-(b - t0) / tau).exp()) / (b - a);
        println!("quarter {q}: mean force {mean:.1} N against {exact:.1} N");
        assert!((mean / exact - 1.0).abs() < 0.05, "quarter {q}: {mean} against {exact}");
    }
}

/// An impactor flies freely for as long as it touches nothing, however far:
/// a hammer launched away from the step-loaded rod at 100 m/s for 2 ms
/// travels 0.2 m, twice the tenth of the rod past which a force-controlled
/// indenter is taken for a collapse (the rod's waves make Newton solve at
/// every step). Newmark's rule is exact for a constant velocity, so the
/// hammer's displacement is `v t` at every step (to round-off).
#[test]
fn an_impactor_in_free_flight_travels_v_t_however_far() {
    let (v, hold) = (100.0, 2e-3);
    let text = bar(1e3, hold, 20, "").replace(
        "[[loads]]",
        "[[indenters]]\nname = \"hammer\"\nbody = \"bar\"\nshape = \"flat\"\nsurface = { y = 1.0 }\nnormal = \"-y\"\n\
         position = 1.00001\nmass = 0.8\nvelocity = [0.0, 100.0, 0.0]\n\n[[loads]]",
    );
    assert!(text.contains("hammer") && text.contains("total_force"), "{text}");
    let sol = common::run(&text);
    let last = sol.history.last().unwrap();
    assert!((time(last.lambda, hold) / (1e-9 + hold) - 1.0).abs() < 1e-12, "the run reached its end");
    assert!(sol.history.iter().all(|r| r.iterations > 0), "Newton solves at every step");
    for r in &sol.history {
        let (t, d) = (time(r.lambda, hold), r.contact("hammer").unwrap().displacement[1]);
        assert!((d - v * t).abs() <= 1e-9 * v * t, "t = {t}: {d} m against {} m", v * t);
    }
    assert!(v * time(last.lambda, hold) > 0.15);
}

/// A smaller twin of `examples/tube_drop_weight.toml` through the CLI: the
/// same tube, supports, alloy and 2 kg weight at 1 m/s, its section 8 L9
/// around instead of 20 and its axis 10 B4 instead of 22 (4,464 DOF
/// against 24,120), the same 300 steps of 20 µs. The weight's loss of
/// kinetic energy `½ m (v₀² − v²)` (its final velocity from its
/// displacement over the last ten steps) equals the contact work on the
/// tube in the energy ledger within 1 % (measured 0.79 J and −0.24 %; the
/// example itself gives 0.805 J and −0.005 %) once it has left the tube:
/// two independent integrations — the impactor's Newmark in its own
/// unknown, the ledger's trapezoidal work on the tube's nodes — of the
/// same exchange, which differ by what the contact dissipates (with 150
/// steps of 40 µs −1.5 %, tried by hand). The tube dents plastically and
/// the weight rebounds.
#[test]
fn a_drop_weight_hands_its_energy_to_the_tube() {
    drop_weight("tube_drop_weight_twin", &drop_weight_twin(), 1.0);
}

/// The smaller twin of `examples/tube_drop_weight.toml`
/// ([`a_drop_weight_hands_its_energy_to_the_tube`]): 8 L9 around, 10 B4.
fn drop_weight_twin() -> String {
    common::coarse_drop_weight(&drop_weight_example())
}

/// The tangent of a time step while a drop weight dents a tube: the twin
/// of [`a_drop_weight_hands_its_energy_to_the_tube`] after 40 steps of
/// 20 µs (the weight pressing the top wall, about 700 Gauss points
/// yielding under it), in the middle of the 41st, every column of the top
/// wall's nodes within 15 mm of the contact centre against central
/// differences of the residual: within 1e-6 of the largest entry
/// (measured 1.4e-9). The inertia, the elastoplastic consistent tangent
/// and the contact impulse together, where the other transient checks
/// hold one at a time on elastic models; the impactor stays at its
/// position (its bordered unknown's column is not differenced, only the
/// tube's DOFs are).
/// The step is h = 1e-11 m: the contact-centre node sits about 6e-11 m inside
/// the weight there (the dented wall just touching it), and h = 1e-10 m
/// crosses its contact switch (a difference of 0.2 in that one column,
/// every other column within 1e-6). The plastic term of the consistent
/// tangent 10 % low (`b` in `Material::elastoplastic_tangent`) puts the
/// difference at 3.4e-4 (tried by hand). So the drop weight's Newton,
/// falling linearly over its first corrections while the weight presses
/// (residuals `[7e-2 4e-3 3e-4 6e-6 1e-9]` on the example), has the exact
/// tangent: its rate is set by the yielded set moving — on the example,
/// hundreds of points leave or enter the yield surface between the first
/// evaluations of a step (docs/limitations.md).
#[test]
fn the_tangent_of_a_yielding_drop_weight_step_matches_finite_differences() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    use cufem::solver::stepping::{Increment, Observer, StepSettings};
    struct Quiet;
    impl<'a> Observer<cufem::analysis::Structure<'a>> for Quiet {
        fn converged(&mut self, _: &cufem::analysis::Structure<'a>, _: &Increment) {}
    }
    let model = cufem::setup::Model::parse(&drop_weight_twin()).unwrap();
    let mut s = cufem::analysis::Structure::of_model(&model, None).unwrap();
    // 40 steps of 1/300 of the load step, cut back where Newton fails (the
    // first touch), as the CLI's stepping does
    let full = 1.0 / 300.0;
    let mut steps = StepSettings::default();
    (steps.initial, steps.max) = (full, full);
    cufem::solver::stepping::run_span(
        &mut s,
        (0.0, 40.0 * full),
        1,
        &steps,
        &NewtonSettings::default(),
        &mut Quiet,
        &Default::default(),
    )
    .unwrap();
    s.set_load_factor(40.5 * full);
    let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
    assert!(report.converged(), "{report:?}");
    s.evaluate().unwrap();
    assert!(s.plastic_points() > 0, "the wall does not yield");
    assert!(
        s.contact_points().iter().any(|p| p.active && model.mesh.coords(p.node)[2] > 0.028),
        "the weight does not touch the tube"
    );
    let k = s.tangent_values().to_vec();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let columns: Vec<(usize, usize)> = (0..model.mesh.n_nodes())
        .filter(|&n| {
            let [_, y, z] = model.mesh.coords(n);
            z > 0.028 && (y - 0.125).abs() <= 0.015
        })
        .flat_map(|n| 3 * n..3 * n + 3)
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    assert!(columns.len() >= 30, "{} columns", columns.len());
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-11, scale);
    println!("{} columns, {} plastic points: largest relative difference {worst:e}", columns.len(), s.plastic_points());
    assert!(worst < 1e-6, "{worst:e}");
}

/// The checks of [`a_drop_weight_hands_its_energy_to_the_tube`] on
/// `examples/tube_drop_weight.toml` itself (measured: the weight lost
/// 0.80492 J, the contacts did 0.80488 J on the tube, −0.005 %; 0.786 J
/// plastic dissipation of 0.802 J internal work).
#[test]
#[ignore = "validate: slow — examples/tube_drop_weight.toml through the CLI, 24,120 DOF and 300 time steps, about 60 s"]
fn the_drop_weight_example_hands_its_energy_to_the_tube() {
    drop_weight("tube_drop_weight", &drop_weight_example(), 1.0);
}

/// The checks of [`a_drop_weight_hands_its_energy_to_the_tube`] on
/// `examples/tube_drop_weight_quarter.toml`, the whole example's quarter
/// across its two planes of symmetry, whose weight carries a quarter of
/// the mass and of every energy.
#[test]
fn the_quarter_drop_weight_example_hands_its_energy_to_the_tube() {
    drop_weight("tube_drop_weight_quarter", &example_text("tube_drop_weight_quarter"), 0.25);
}

/// `examples/tube_drop_weight_quarter.toml` against the whole tube of
/// `examples/tube_drop_weight.toml`, the same problem: the quarter's
/// energy.csv times four equal to the whole's at the end within `1e-6` of
/// the impact energy, the weight's motion at every step within `1e-4` of
/// its largest, the contact centre's u_z and peeq within `1e-3`. Measured:
/// energies within `5e-8` J, the motion within `7e-8`, u_z `5e-5` (a
/// small residual dent, `29` µm), peeq `5e-7` (the two take the same one
/// cutback). Mutation: the quarter's weight with the whole mass fails.
#[test]
#[ignore = "validate: slow — examples/tube_drop_weight.toml and its quarter through the CLI, about 60 s"]
fn the_quarter_drop_weight_follows_the_whole_tube() {
    let whole = run_cli("tube_drop_weight_whole", &drop_weight_example());
    let quarter = run_cli("tube_drop_weight_quarter_twin", &example_text("tube_drop_weight_quarter"));
    common::assert_energies_scaled(&whole, &quarter, 4.0, 1e-6, false);
    let (hw, hq) = (columns(&whole.join("history_load.csv")), columns(&quarter.join("history_load.csv")));
    assert_eq!(hw["d_z"].len(), hq["d_z"].len(), "the same steps");
    let peak = hw["d_z"].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = hw["d_z"].iter().zip(&hq["d_z"]).map(|(a, b)| (a - b).abs() / peak).fold(0.0, f64::max);
    println!("the weight's motion within {worst:.1e} of its largest, {peak:.4e} m");
    assert!(worst < 1e-4, "{worst:e}");
    let probe = |out: &std::path::Path| {
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        (s["probes"][0]["u"][2].as_f64().unwrap(), s["probes"][0]["peeq"].as_f64().unwrap())
    };
    let ((uw, pw), (uq, pq)) = (probe(&whole), probe(&quarter));
    println!("contact centre: u_z {uw:.6e} / {uq:.6e} m, peeq {pw:.6e} / {pq:.6e}");
    assert!((uq / uw - 1.0).abs() < 1e-3 && (pq / pw - 1.0).abs() < 1e-3);
}

fn drop_weight_example() -> String {
    example_text("tube_drop_weight")
}

/// The text of `examples/<name>.toml`.
fn example_text(name: &str) -> String {
    let path =
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(format!("examples/{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

/// Runs a drop-weight model through the CLI and checks its energy exchange
/// ([`a_drop_weight_hands_its_energy_to_the_tube`]); `share` of the 2 kg
/// weight is in the model (a quarter across two symmetry planes).
fn drop_weight(name: &str, text: &str, share: f64) {
    let out = run_cli(name, text);
    let hammer = columns(&out.join("history_load.csv"));
    let n = hammer["lambda"].len() - 1;
    let t = |k: usize| hammer["lambda"][k] * 6e-3;
    let v_end = (hammer["d_z"][n] - hammer["d_z"][n - 10]) / (t(n) - t(n - 10));
    assert_eq!(hammer["f_z"][n], 0.0, "the weight is still in contact at the end");
    assert!(v_end > 0.0, "the weight does not rebound: {v_end} m/s");
    let lost = 0.5 * 2.0 * share * (1.0 - v_end * v_end);
    let energy = columns(&out.join("energy.csv"));
    let work = *energy["contact_J"].last().unwrap();
    println!("the weight lost {lost} J, the contacts did {work} J on the tube");
    assert!((work / lost - 1.0).abs() < 0.01, "{work} against {lost}");
    // the ledger's impactor column: 1 J (its share) at the start, and the contacts
    // took from the weight at least what they gave the tube (the
    // end-of-step impulse cannot create energy)
    let kinetic = &energy["impactors_J"];
    let ledger_lost = kinetic[0] - kinetic.last().unwrap();
    println!("the ledger: the weight lost {ledger_lost} J");
    assert!((kinetic[0] - share).abs() < 1e-12 && (ledger_lost / lost - 1.0).abs() < 0.01, "{kinetic:?}");
    assert!(ledger_lost >= work * (1.0 - 1e-9), "{ledger_lost} < {work}");
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let peeq = summary["probes"][0]["peeq"].as_f64().unwrap_or(0.0);
    assert!(peeq > 1e-3, "no plastic dent: peeq {peeq}");
    // most of what the tube took is dissipated plastically
    let (plastic, internal) = (*energy["plastic_J"].last().unwrap(), *energy["internal_J"].last().unwrap());
    println!("plastic dissipation {plastic} J of the internal work {internal} J");
    assert!(plastic > 0.5 * internal && plastic <= internal, "{plastic} of {internal}");
}

/// The transient tangent `K + (1 − α) M/(βΔt²) + γC/(βΔt)` against central
/// differences of the residual (inertia and Rayleigh damping with both
/// terms, `C = α_M M + β_K K₀`), on the bar after 20 time steps, in the
/// middle of a step, with Newmark's method and with Bossak's α = −0.2:
/// within 1e-6 of the largest entry (measured 7e-15: the problem is
/// linear). The mass and damping terms dominate the tangent at
/// this Δt: with γ/(βΔt) written 1/(βΔt), or the mass term 10 % off, the
/// difference is 7e-2 (both tried by hand).
#[test]
fn the_transient_tangent_matches_finite_differences() {
    for newmark in ["", "newmark = { alpha = -0.2 }"] {
        transient_tangent(&bar(
            1000.0,
            8e-4,
            800,
            &format!("damping = {{ mass = 500.0, stiffness = 1e-7 }}\n{newmark}"),
        ));
    }
}

/// The check of `the_transient_tangent_matches_finite_differences` on the
/// bar `text`.
fn transient_tangent(text: &str) {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let model = cufem::setup::Model::parse(text).unwrap();
    let mut s = cufem::analysis::Structure::of_model(&model, None).unwrap();
    // the rise (λ 0 → 1), then 20 steps of 1 µs
    for l in std::iter::once(1.0).chain((1..=20).map(|k| 1.0 + k as f64 / 800.0)) {
        s.set_load_factor(l);
        let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
        assert!(report.converged(), "{report:?}");
        s.commit();
    }
    s.set_load_factor(1.0 + 20.5 / 800.0);
    s.evaluate().unwrap();
    let k = s.tangent_values().to_vec();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let eq: Vec<usize> = (0..s.displacements().len()).map(|d| s.equation(d).unwrap_or(usize::MAX)).collect();
    let n_nodes = s.displacements().len() / 3;
    let columns: Vec<(usize, usize)> = (1..8)
        .map(|i| i * n_nodes / 8)
        .flat_map(|n| [3 * n + 1])
        .filter(|&d| eq[d] != usize::MAX)
        .map(|d| (d, eq[d]))
        .collect();
    assert!(!columns.is_empty());
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-10, scale);
    println!("{} columns, largest relative difference {worst:e}", columns.len());
    assert!(worst < 1e-6, "{worst:e}");
}

/// The end-of-step contact impulse (`dynamics::impulse`) in the tangent:
/// `examples/rod_impact.toml` 20 µs into its contact with the wall, in the
/// middle of a step, the columns of the rod's end nodes (in contact, the
/// contact stiffness `K_c / γ = 2 K_c` far above the mass term) against
/// central differences of the residual: within 1e-6 of the largest entry.
/// Without the factor 1/γ on the contact blocks Newton does not converge in
/// the first steps of the contact (tried by hand). The same with Bossak's
/// α = −0.2, whose factor is `(1 − α)/γ` (`dynamics::impulse::Recursion`).
#[test]
fn the_contact_impulse_tangent_matches_finite_differences() {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/rod_impact.toml");
    let text = std::fs::read_to_string(path).unwrap();
    contact_impulse_tangent(&text);
    // Bossak's weight (1 − α)/γ on the contact blocks
    let bossak = text.replace("type = \"transient\"", "type = \"transient\"\nnewmark = { alpha = -0.2 }");
    assert_ne!(bossak, text);
    contact_impulse_tangent(&bossak);
}

/// The check of `the_contact_impulse_tangent_matches_finite_differences`
/// on the rod impact `text`.
fn contact_impulse_tangent(text: &str) {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let model = cufem::setup::Model::parse(text).unwrap();
    let mut s = cufem::analysis::Structure::of_model(&model, None).unwrap();
    // steps of 1 µs (600 over the 600 µs); the wall is reached at 10 µs
    for k in 1..=30 {
        s.set_load_factor(k as f64 / 600.0);
        let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
        assert!(report.converged(), "{report:?}");
        s.commit();
    }
    s.set_load_factor(30.5 / 600.0);
    s.evaluate().unwrap();
    let k = s.tangent_values().to_vec();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let n_nodes = s.displacements().len() / 3;
    let columns: Vec<(usize, usize)> =
        (n_nodes - 4..n_nodes).map(|n| 3 * n + 1).filter_map(|d| s.equation(d).map(|e| (d, e))).collect();
    assert_eq!(columns.len(), 4);
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-10, scale);
    println!("largest relative difference {worst:e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// Hertz's impact theory (Johnson, *Contact Mechanics*, §11.4): a rigid
/// ball of mass m at v₀ on an elastic half-space indents it by
/// `δ_max = (15 m v₀² / (16 E* √R))^(2/5)`, with the peak force
/// `(4/3) E* √R δ_max^(3/2)`, and leaves after `2.94 δ_max / v₀`. The
/// quarter model of `examples/hertz_ball.toml` (the same block, clamped,
/// 30 mm: a wave crosses it in 6 µs, quasi-static against the impact),
/// coarsened to 5 elements per direction (ratio 60, the example 10) for a
/// fast twin, with its ball made an impactor (a quarter of 1 kg at 1 m/s,
/// 1 µm above the block, `method = "surface"`, default penalty), 40 steps
/// of 6.5 µs: δ_max 71.1 µm, 4,394 N on the quarter and 209.1 µs in
/// theory; measured −0.67 %, +3.1 % (the static example is +2.9 %: the
/// finite clamped block is stiffer than the half-space) and −1.1 %; the
/// ball rebounds at 0.998 v₀ (test 2 %). Issue 27 asks 5 %. The example's
/// own mesh (10 elements per direction, 40 s) gives −1.3 %, +1.7 % and
/// −1.2 % (the validation test below); with 4 elements per direction
/// −3.0 % on the force. A 10 % heavier ball (+5.9 % on the peak force in
/// theory) fails, tried by hand.
#[test]
fn a_ball_bounces_off_a_block_as_hertz_impact_theory_says() {
    hertz_impact(5);
}

/// [`a_ball_bounces_off_a_block_as_hertz_impact_theory_says`] on the mesh
/// of `examples/hertz_ball.toml` itself (10 elements per direction,
/// 41,013 DOF; measured −1.3 %, +1.7 %, −1.2 %, rebound 0.998 v₀).
#[test]
#[ignore = "validate: slow — the Hertz impact on examples/hertz_ball.toml's mesh, 41,013 DOF and 40 time steps, about 40 s"]
fn a_ball_bounces_off_the_examples_block_as_hertz_impact_theory_says() {
    hertz_impact(10);
}

/// The Hertz impact on the block of `examples/hertz_ball.toml` with
/// `elements` per direction (module docs of the tests above).
fn hertz_impact(elements: usize) {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/hertz_ball.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let lines = text.find("[[lines]]").unwrap();
    let text = text[..lines]
        .replace("[solver]\nincrements = 4", "[analysis]\ntype = \"transient\"\n\n[solver]\nmax_increments = 5000")
        .replacen("poisson_ratio = 0.3\n", "poisson_ratio = 0.3\ndensity = 7850.0\n", 1)
        .replace("center = [0.0, 0.0, 0.01]", "center = [0.0, 0.0, 0.010001]")
        .replace("displacement = [0.0, 0.0, -5e-5]", "mass = 0.25\nvelocity = [0.0, 0.0, -1.0]")
        .replace("elements = 10,", &format!("elements = {elements},"))
        + "[[steps]]\nname = \"impact\"\nfactor = 1.0\nduration = 2.6e-4\nincrements = 40\n";
    assert!(text.contains("mass = 0.25") && text.contains("transient"), "{text}");
    assert_eq!(text.matches(&format!("elements = {elements},")).count(), 3, "{text}");
    let sol = common::run(&text);
    let (mass, v0, radius, gap) = (1.0f64, 1.0, 0.01f64, 1e-6);
    let e_star = 200e9 / (1.0 - 0.3f64 * 0.3);
    let delta = (15.0 * mass * v0 * v0 / (16.0 * e_star * radius.sqrt())).powf(0.4);
    let peak = 4.0 / 3.0 * e_star * radius.sqrt() * delta.powf(1.5) / 4.0;
    let duration = 2.94 * delta / v0;
    // the ball's travel beyond the gap (its indentation) and force in time
    let rows: Vec<(f64, f64, f64)> = sol
        .history
        .iter()
        .map(|r| {
            let b = r.contact("ball").unwrap();
            (r.lambda * 2.6e-4, -b.displacement[2] - gap, -b.force[2])
        })
        .collect();
    let max_indent = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    let max_force = rows.iter().map(|r| r.2).fold(0.0, f64::max);
    // separation: where the indentation returns to zero (linear between steps)
    let k = rows.iter().rposition(|r| r.1 > 0.0).unwrap();
    let (a, b) = (rows[k], rows[k + 1]);
    let end = a.0 + (b.0 - a.0) * a.1 / (a.1 - b.1);
    let contact = end - gap / v0;
    let n = rows.len() - 1;
    let rebound = (rows[n - 5].1 - rows[n].1) / (rows[n].0 - rows[n - 5].0);
    println!(
        "indentation {max_indent:e} m against {delta:e} m, force {max_force:.1} N against {peak:.1} N, \
         contact {contact:e} s against {duration:e} s, rebound {rebound} m/s"
    );
    for (got, want, what) in
        [(max_indent, delta, "indentation"), (max_force, peak, "force"), (contact, duration, "duration")]
    {
        assert!((got / want - 1.0).abs() < 0.05, "{what}: {got} against {want}");
    }
    assert!((rebound / v0 - 1.0).abs() < 0.02, "rebound {rebound}");
}
