//! The energy ledger of a transient run with cohesive interfaces (issue 48,
//! `dynamics::energy`): a double cantilever beam opened slowly, in time,
//! past its peak load, so that the crack grows.
//!
//! Two independent measures of what the interface dissipates are compared:
//! the ledger's `delamination` (the trapezoidal work of the interface forces
//! over the displacement increments, less the energy the interfaces hold,
//! `Σ A ½ t·δ`) and the cohesive law's own dissipation at its points
//! (`Σ A g`, `summary.json` `delamination.dissipated_j`); and the latter
//! against the toughness times the area the crack grew, `G_Ic ΔA` (Griffith:
//! a crack growing under mode I dissipates G_Ic per unit area; the process
//! zone ahead of it, partly damaged, adds at most G_Ic times its area). A ledger that drops
//! the interfaces' forces misses the whole dissipation (0.2 J here) in its
//! balance.

use cufem::{Model, RunOptions, Silent};

/// examples/dcb.toml (AS4/PEEK, G_Ic = 969 J/m², 25.4 mm wide, precrack
/// 32.8 mm) in time: ρ = 1600 kg/m³, each arm opened by 3 mm over 30 ms
/// (0.1 m/s: the arms' first bending period, about 0.5 ms, is 60 times
/// shorter, so the opening is slow), 120 time steps, the crack zone meshed
/// with 24 B4 elements over 16 mm (0.22 mm node spacing); the example's
/// viscosity kept (without it Newton cuts the time step back twice as often);
/// the interface forces averaged as every force (`interface_forces =
/// "newmark"`: the ledger's trapezoidal work is what is compared with the
/// law here; with the end-of-step impulse, the default, the crack grew
/// 6.33 mm against 4.99 mm, the ledger's delamination measured 0.1615 J
/// against the law's 0.1626 J, and the viscous over-stress's work
/// `viscous_j` grew to 0.025 J: a known limit in docs/limitations.md).
fn transient_dcb(forces: &str) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/dcb.toml")).unwrap();
    let edits = [
        ("orthotropic = {", "density = 1600.0\northotropic = {"),
        ("displacement = { z = 0.005 }", "displacement = { z = 0.003 }"),
        ("displacement = { z = -0.005 }", "displacement = { z = -0.003 }"),
        (
            "{ from = 0.032, to = 0.056, elements = 64 },\n  { from = 0.056, to = 0.1, elements = 10 },",
            "{ from = 0.032, to = 0.048, elements = 24 },\n  { from = 0.048, to = 0.1, elements = 8 },",
        ),
        (
            "[solver]\nincrements = 200",
            "[analysis]\ntype = \"transient\"\nduration = 0.03\ninterface_forces = \"FORCES\"\n\n[solver]\nincrements = 120",
        ),
    ];
    edits
        .iter()
        .fold(text, |t, (from, to)| {
            assert!(t.contains(from), "examples/dcb.toml no longer holds {from:?}");
            t.replacen(from, to, 1)
        })
        .replace("FORCES", forces)
}

#[test]
#[ignore = "validate: slow — a transient DCB opened past its peak (about 2 min)"]
fn the_ledger_counts_the_energy_delamination_dissipates() {
    let model = Model::parse(&transient_dcb("newmark")).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows = solution.energy.as_ref().expect("a transient run keeps its energy balance");
    let end = rows.last().unwrap();
    let delamination = solution.delamination.as_ref().unwrap().summary();
    let (width, a0, gic) = (0.0254, 0.0328, 969.0);
    let grown = delamination.area_m2 - width * a0;
    println!(
        "work of the supports {:.4} J, interfaces' work {:.4} J, ledger's delamination {:.4} J, law's {:.4} J, \
         G_Ic ΔA {:.4} J (Δa = {:.2} mm), kinetic {:.2e} J, balance {:.2e} J",
        end.supports,
        end.interfaces,
        end.delamination,
        delamination.dissipated_j,
        gic * grown,
        grown / width * 1e3,
        end.kinetic,
        end.balance
    );
    // the crack grew: the opening is past the peak (CBT: 4.19 mm in all)
    assert!(grown > 0.002 * width, "the crack grew by {:.2} mm only", grown / width * 1e3);
    // the balance closes (Newmark's trapezoidal rule: to Newton's tolerance)
    let work = end.supports;
    for r in rows {
        assert!(r.balance.abs() < 1e-3 * work, "balance {} J at t = {} s", r.balance, r.time);
    }
    // the ledger's path integral and the law's point sums agree (the ledger
    // also holds the work of the viscous over-stress, about 1 % here)
    let law = delamination.dissipated_j + delamination.viscous_j;
    let ledger_vs_law = (end.delamination - law).abs() / law;
    assert!(ledger_vs_law < 0.01, "ledger and law differ by {:.2} %", 100.0 * ledger_vs_law);
    // Griffith: at least G_Ic times the area delaminated, at most G_Ic
    // times that and the process zone (its points partly damaged)
    let zone = delamination.interfaces.iter().map(|i| i.process_zone_m2).sum::<f64>();
    let (low, high) = (gic * grown, gic * (grown + zone));
    assert!(
        (low..high).contains(&delamination.dissipated_j),
        "dissipated {} J outside G_Ic ΔA = {low} J .. G_Ic (ΔA + A_zone) = {high} J",
        delamination.dissipated_j
    );
    // no step creates energy: the ledger's dissipation never decreases
    for w in rows.windows(2) {
        let step = w[1].delamination - w[0].delamination;
        assert!(step > -1e-3 * work, "the dissipation fell by {step} J at t = {} s", w[1].time);
    }
}

/// The transient DCB above with the discrete-gradient traction
/// (`interface_forces = "discrete_gradient"`): the ledger's delamination is
/// the law's dissipation plus the viscosity's (`dissipated_j + viscous_j`)
/// to round-off, but the crack grows less than with `"newmark"` and than
/// corrected beam theory's quasi-static 4.19 mm: measured 3.12 mm (newmark
/// 4.99, the end-of-step traction 6.33), the viscosity's share
/// `viscous_j` 0.0208 J against the law's 0.0851 J — with viscosity the
/// discrete gradient carries the step's mean damage, which lags the law's.
/// A known shortfall (docs/limitations.md), held from both sides.
#[test]
#[ignore = "validate: slow — a transient DCB opened past its peak"]
fn the_discrete_gradient_dcb_grows_a_shorter_crack() {
    let model = Model::parse(&transient_dcb("discrete_gradient")).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let end = *solution.energy.as_ref().unwrap().last().unwrap();
    let delamination = solution.delamination.as_ref().unwrap().summary();
    let grown = (delamination.area_m2 - 0.0254 * 0.0328) / 0.0254;
    let law = delamination.dissipated_j + delamination.viscous_j;
    println!(
        "discrete gradient: crack grew {:.2} mm; ledger's delamination {:.4} J, law's {:.4} J + viscous {:.4} J; \
         kinetic {:.2e} J",
        grown * 1e3,
        end.delamination,
        delamination.dissipated_j,
        delamination.viscous_j,
        end.kinetic
    );
    assert!((end.delamination / law - 1.0).abs() < 1e-6, "ledger {} J, law and viscosity {law} J", end.delamination);
    assert!((0.0029..0.0034).contains(&grown), "the crack grew {grown} m");
}

/// Two plies (E = 1 GPa, ν = 0: no slide at the interface) of 1 mm over
/// 4 mm × 20 mm, glued by a cohesive interface (N = 10 MPa, G_Ic = 100 J/m²,
/// K = 5e13 Pa/m: δ0 = 0.2 µm, δf = 20 µm), the bottom face held and the top
/// face lifted by 50 µm in 1 ms (40 steps): the whole interface opens at
/// once, so every point fails and the interface dissipates exactly
/// G_Ic × its area, 8 mJ. The plies hold ½ F²/k = 4 mJ each at the peak, as
/// much as the interface can dissipate: statically a snap-back, in time the
/// plies spring back and the kinetic energy takes the difference.
const PULLED_STACK: &str = r#"
[[materials]]
name = "ply"
young_modulus = 1e9
poisson_ratio = 0.0
density = 1500.0

[[materials]]
name = "glue"
cohesive = { gic = 100.0, giic = 200.0, bk_exponent = 2.0, normal_strength = 10e6 }

[[bodies]]
name = "stack"
section = { shape = "laminate", element = "L4", x = { from = 0.0, to = 0.004, elements = 2 }, plies = [
  { thickness = 0.001, material = "ply" }, { thickness = 0.001, material = "ply" } ], interfaces = "cohesive", interface_material = "glue" }
axis = { element = "B2", from = 0.0, to = 0.02, elements = 3 }

[[constraints]]
name = "bottom"
body = "stack"
where = { z = 0.0 }
fix = ["x", "y", "z"]

[[constraints]]
name = "top"
body = "stack"
where = { z = 0.002 }
fix = ["x", "y"]
displacement = { z = 5e-5 }

[analysis]
type = "transient"
duration = 1e-3

[solver]
increments = 40
"#;

/// The pulled stack in `steps` time steps, its interface forces integrated
/// by `forces` (`analysis.interface_forces`): (the law's dissipation, the
/// ledger's, the largest |balance| over the run, the work of the supports).
fn pulled_stack(steps: usize, forces: &str) -> (f64, f64, f64, f64) {
    let text = PULLED_STACK
        .replace("increments = 40", &format!("increments = {steps}"))
        .replace("duration = 1e-3", &format!("duration = 1e-3\ninterface_forces = \"{forces}\""));
    let model = Model::parse(&text).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows = solution.energy.as_ref().unwrap();
    let end = rows.last().unwrap();
    let delamination = solution.delamination.as_ref().unwrap().summary();
    // every point failed
    assert!((delamination.area_m2 / (0.004 * 0.02) - 1.0).abs() < 1e-9, "delaminated {} m²", delamination.area_m2);
    let balance = rows.iter().map(|r| r.balance.abs()).fold(0.0, f64::max);
    println!(
        "{steps} steps: supports {:.4e} J, ledger's delamination {:.4e} J, law's {:.4e} J, kinetic {:.3e} J, \
         |balance| ≤ {balance:.2e} J",
        end.supports, end.delamination, delamination.dissipated_j, end.kinetic
    );
    (delamination.dissipated_j, end.delamination, balance, end.supports)
}

/// The law's dissipation is G_Ic A to round-off; with Newmark's average of
/// the interface forces (`interface_forces = "newmark"`) the ledger's path
/// integral of them (the trapezoidal rule, as every work term)
/// overestimates it where a step jumps over the softening branch (the whole
/// interface fails within one step here): the gap shrinks with the step.
#[test]
fn a_fully_opened_interface_dissipates_its_toughness_times_its_area() {
    let ga = 100.0 * 0.004 * 0.02;
    let (law, coarse, balance, work) = pulled_stack(40, "newmark");
    assert!((law / ga - 1.0).abs() < 1e-6, "law's dissipation {law} J, G_Ic A = {ga} J");
    assert!(balance < 1e-6 * work, "the balance is off by {balance} J");
    let (law_fine, fine, _, _) = pulled_stack(80, "newmark");
    assert!((law_fine / ga - 1.0).abs() < 1e-6, "law's dissipation {law_fine} J, G_Ic A = {ga} J");
    let (gap_coarse, gap_fine) = (coarse / ga - 1.0, fine / ga - 1.0);
    println!("ledger − G_Ic A: {:.2} % (40 steps), {:.2} % (80 steps)", 100.0 * gap_coarse, 100.0 * gap_fine);
    assert!(gap_coarse.abs() < 0.05, "the ledger's delamination is {:.2} % off G_Ic A", 100.0 * gap_coarse);
    assert!(gap_fine.abs() < 0.7 * gap_coarse.abs(), "halving the step took the gap from {gap_coarse} to {gap_fine}");
}

/// With the interfaces' impulse at the end of the step (the default,
/// `dynamics::impulse`) a point that passes its whole softening branch
/// within one step does the work of its traction at the step's end, zero:
/// the forces remove only the energy it held, and the plies keep as motion
/// what the law books as dissipated. The pulled stack fails within one
/// step at either step size (its plies' through-thickness period, about
/// 4 µs, is shorter than either step), so the ledger's delamination stays
/// at the same share of G_Ic A (measured 0.372 with 40 steps, 0.374 with
/// 80): a known limit (docs/limitations.md), held from both sides.
#[test]
fn the_end_of_step_impulse_misses_the_toughness_of_a_point_that_fails_within_a_step() {
    let ga = 100.0 * 0.004 * 0.02;
    for steps in [40, 80] {
        let (law, ledger, balance, work) = pulled_stack(steps, "implicit");
        println!("{steps} steps, implicit: ledger's delamination {:.3} G_Ic A", ledger / ga);
        assert!((law / ga - 1.0).abs() < 1e-6, "law's dissipation {law} J, G_Ic A = {ga} J");
        assert!(balance < 1e-6 * work, "the balance is off by {balance} J");
        assert!((0.3..0.45).contains(&(ledger / ga)), "the ledger's delamination is {} G_Ic A", ledger / ga);
    }
}

/// The pulled stack lifted (40 steps of 25 µs: every point fails), brought
/// back to the start in as long (the separated plies, ringing, strike each
/// other again and again) and held there as long: (each converged step's
/// energies, the law's dissipation, the Newton iterations of the hold).
fn closed_stack(forces: &str) -> (Vec<cufem::dynamics::energy::EnergyRow>, f64, usize) {
    let steps = "\n[[steps]]\nname = \"lift\"\nfactor = 1.0\n\n[[steps]]\nname = \"close\"\nfactor = 0.0\n\n\
                 [[steps]]\nname = \"hold\"\nfactor = 0.0\n";
    let text = format!("{PULLED_STACK}{steps}")
        .replace("duration = 1e-3", &format!("duration = 1e-3\ninterface_forces = \"{forces}\""));
    let model = Model::parse(&text).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let law = solution.delamination.as_ref().unwrap().summary().dissipated_j;
    let hold = solution.history.iter().filter(|h| h.lambda > 2.0).map(|h| h.iterations).sum();
    (solution.energy.unwrap(), law, hold)
}

/// The energy the plies and the interface hold, `T + U + Σ A ψ`.
fn mechanical(r: &cufem::dynamics::energy::EnergyRow) -> f64 {
    r.kinetic + r.elastic + (r.interfaces - r.delamination)
}

/// No step of the closed stack's run creates energy: the ledger's
/// delamination never falls, the balance closes (`1e-6` of the supports'
/// `work`), and in the hold (t > 2 ms) the plies' energy grows by at most
/// `growth` of `work` a step.
fn never_creates(rows: &[cufem::dynamics::energy::EnergyRow], work: f64, growth: f64) {
    for w in rows.windows(2) {
        let step = w[1].delamination - w[0].delamination;
        assert!(step >= -1e-12 * work, "the delamination fell by {step} J at t = {} s", w[1].time);
        assert!(w[1].balance.abs() < 1e-6 * work, "balance {} J at t = {} s", w[1].balance, w[1].time);
        if w[0].time > 2.0e-3 * (1.0 + 1e-9) {
            let grown = mechanical(&w[1]) - mechanical(&w[0]);
            assert!(grown <= growth * work, "the plies' energy grew by {grown} J at t = {} s in the hold", w[1].time);
        }
    }
}

/// Issue 48 (a): separated plies that close again. With Newmark's average
/// of the interface forces the full compression penalty, engaging and
/// letting go within a step (ω Δt ≈ 200), does more work on opening than
/// on closing: in the hold, where the supports do no work, the plies'
/// energy grows (measured 30-fold over its smallest value) and the
/// ledger's delamination falls (by 1.8 % of G_Ic A at worst). With the
/// impulse at the end of the step (`dynamics::impulse`: the law's energy
/// at fixed damage is convex in δ) no step creates energy: the ledger's
/// delamination never falls and the plies' energy never grows in the hold.
/// The ledger then holds the law's G_Ic A and the motion the plies lost in
/// their (inelastic, under the unresolved penalty) impacts, at most the
/// supports' work: measured 1.083 G_Ic A.
#[test]
fn separated_plies_that_close_again_create_no_energy_with_the_end_of_step_impulse() {
    let ga = 100.0 * 0.004 * 0.02;
    // Newmark's average: energy created (the old behaviour)
    let (rows, _, _) = closed_stack("newmark");
    let fall = rows.windows(2).map(|w| w[1].delamination - w[0].delamination).fold(0.0, f64::min);
    let hold: Vec<f64> = rows.iter().filter(|r| r.time > 2.0e-3 * (1.0 + 1e-9)).map(mechanical).collect();
    let (low, high) = hold.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &e| (l.min(e), h.max(e)));
    println!(
        "newmark: delamination falls by {:.4} G_Ic A at worst; in the hold the plies' energy grows {:.1}-fold",
        -fall / ga,
        high / low
    );
    assert!(fall < -0.01 * ga, "the delamination fell by {fall} J at worst");
    assert!(high > 10.0 * low, "the plies' energy in the hold stays within {low} .. {high} J");
    // the impulse at the end of the step: none
    let (rows, law, iterations) = closed_stack("implicit");
    let work = rows.last().unwrap().supports;
    let steps = rows.iter().filter(|r| r.time > 2.0e-3 * (1.0 + 1e-9)).count();
    never_creates(&rows, work, 1e-12);
    let ledger = rows.last().unwrap().delamination;
    println!(
        "implicit: ledger's delamination {:.4} G_Ic A, law's {:.4}, supports' work {:.4}; {:.2} Newton iterations \
         per step in the hold",
        ledger / ga,
        law / ga,
        work / ga,
        iterations as f64 / steps as f64
    );
    assert!((law / ga - 1.0).abs() < 1e-6, "law's dissipation {law} J");
    assert!((1.0..1.15).contains(&(ledger / law)), "ledger {ledger} J against the law's {law} J");
    // the tangent is the algorithmic force's (the interfaces' stiffness
    // over γ): Newton converges in the hold in measured 2.73 iterations per
    // step (points opening and closing between iterations); without the
    // 1/γ it does not converge at all
    assert!(iterations <= 3 * steps, "{iterations} Newton iterations over {steps} steps in the hold");
}

/// In a transient run the interfaces' viscosity is in seconds, as the ply
/// damage's: the pulled stack (40 steps of Δt = 25 µs) with η = Δt relaxes
/// its damage over a whole step, and the over-stress does work of the order
/// of the toughness's (measured 2.69 G_Ic A); read in load-factor units
/// (Δλ = 1/40) the same η would be a thousandth of a step (measured 0.062
/// G_Ic A with the clock withheld). The ledger still closes.
#[test]
fn the_interfaces_viscosity_is_in_seconds_in_time() {
    let ga = 100.0 * 0.004 * 0.02;
    let text = PULLED_STACK.replace("normal_strength = 10e6 }", "normal_strength = 10e6, viscosity = 2.5e-5 }");
    let model = Model::parse(&text).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let viscous = solution.delamination.as_ref().unwrap().summary().viscous_j;
    println!("η = Δt: viscous work {:.3e} J = {:.3} G_Ic A", viscous, viscous / ga);
    assert!(viscous > 0.5 * ga, "viscous work {viscous} J against G_Ic A = {ga} J");
    let rows = solution.energy.as_ref().unwrap();
    let work = rows.last().unwrap().supports;
    let balance = rows.iter().map(|r| r.balance.abs()).fold(0.0, f64::max);
    assert!(balance < 1e-6 * work, "the balance is off by {balance} J of {work} J");
}

/// `analysis.interface_forces` is refused outside a transient analysis and
/// for a word it does not know, by key (src/input/validate.rs style).
#[test]
fn interface_forces_is_refused_by_key() {
    let transient = PULLED_STACK.replace("duration = 1e-3", "duration = 1e-3\ninterface_forces = \"newmark\"");
    assert!(Model::parse(&transient).is_ok());
    let fixed = transient.replace("type = \"transient\"\nduration = 1e-3\n", "");
    let err = Model::parse(&fixed).unwrap_err().to_string();
    println!("{err}");
    assert!(err.contains("analysis.interface_forces") && err.contains("transient"), "{err}");
    let wrong = PULLED_STACK.replace("duration = 1e-3", "duration = 1e-3\ninterface_forces = \"average\"");
    let err = Model::parse(&wrong).unwrap_err().to_string();
    println!("{err}");
    assert!(err.contains("interface_forces") && err.contains("implicit") && err.contains("newmark"), "{err}");
}

/// With the discrete-gradient traction (`interface_forces =
/// "discrete_gradient"`, `dynamics::impulse`) a point's work over a step is
/// the change of the energy it holds plus the law's dissipation over the
/// step, so the ledger's delamination is the law's own sum, G_Ic A, at
/// either step size, where the end-of-step traction left 0.37 G_Ic A (the
/// test above): the pulled stack still fails within one step.
#[test]
fn the_discrete_gradient_books_the_toughness_of_a_point_that_fails_within_a_step() {
    let ga = 100.0 * 0.004 * 0.02;
    for steps in [40, 80] {
        let (law, ledger, balance, work) = pulled_stack(steps, "discrete_gradient");
        println!("{steps} steps, discrete gradient: ledger's delamination {:.9} G_Ic A", ledger / ga);
        assert!((law / ga - 1.0).abs() < 1e-6, "law's dissipation {law} J, G_Ic A = {ga} J");
        assert!(balance < 1e-6 * work, "the balance is off by {balance} J");
        assert!((ledger / law - 1.0).abs() < 1e-6, "the ledger's delamination is {} of the law's", ledger / law);
    }
}

/// The pulled stack closed and held (as above) under the discrete
/// gradient: the ledger's delamination is the law's dissipation after
/// every step (the work of the interface's forces is its stored energy's
/// change plus the law's dissipation, exactly), so it never falls; once
/// the supports stop, the closed interface is an elastic penalty whose
/// discrete gradient conserves energy (the midpoint traction of a
/// quadratic ψ): the plies' energy stays constant to Newton's tolerance
/// (the balance's, 1e-6 of the supports' work) — neither grows nor decays,
/// where the end-of-step impulse dissipates `½ K |Δδ|²` per point and step.
#[test]
fn separated_plies_that_close_again_create_no_energy_with_the_discrete_gradient() {
    let (rows, law, iterations) = closed_stack("discrete_gradient");
    let work = rows.last().unwrap().supports;
    let steps = rows.iter().filter(|r| r.time > 2.0e-3 * (1.0 + 1e-9)).count();
    never_creates(&rows, work, 1e-6);
    let hold: Vec<f64> = rows.iter().filter(|r| r.time > 2.0e-3 * (1.0 + 1e-9)).map(mechanical).collect();
    let (low, high) = hold.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &e| (l.min(e), h.max(e)));
    println!("discrete gradient: the plies' energy in the hold {low:.6e} .. {high:.6e} J");
    let ledger = rows.last().unwrap().delamination;
    println!(
        "discrete gradient: ledger's delamination {:.9} of the law's; supports' work {:.4e} J; {:.2} Newton \
         iterations per step in the hold",
        ledger / law,
        work,
        iterations as f64 / steps as f64
    );
    assert!((ledger / law - 1.0).abs() < 1e-6, "ledger {ledger} J against the law's {law} J");
    // the plies keep ringing in the hold (nothing dissipates it), opening
    // and closing the interface between iterations: measured 6.92 Newton
    // iterations per step (the end-of-step impulse, whose plies come to
    // rest, 2.73)
    assert!(iterations <= 8 * steps, "{iterations} Newton iterations over {steps} steps in the hold");
}

/// The history records the delaminated area of every converged time step
/// (`HistoryRow::delaminated_m2`, `history.csv` `delaminated_area`) and a
/// transient run plots it against time (`delamination.png`): on the pulled
/// stack it starts at zero, never falls, and ends at the whole interface,
/// `0.004 × 0.02` m², the summary's area (every point fails, above).
#[test]
fn the_history_holds_the_delaminated_area_and_its_plot_is_written() {
    let model = Model::parse(PULLED_STACK).unwrap();
    let solution = cufem::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let area: Vec<f64> = solution.history.iter().map(|r| r.delaminated_m2.expect("an interface's area")).collect();
    assert_eq!(area[0], 0.0, "the first step's area");
    assert!(area.windows(2).all(|w| w[1] >= w[0]), "the area fell: {area:?}");
    let whole = 0.004 * 0.02;
    let end = solution.delamination.as_ref().unwrap().summary().area_m2;
    assert!((area[area.len() - 1] / whole - 1.0).abs() < 1e-9, "last area {} m²", area[area.len() - 1]);
    assert_eq!(area[area.len() - 1], end, "the summary's area");
    assert!(solution.history.iter().all(|r| r.damaged_volume_m3.is_none()), "no ply damages here");
    let dir = std::env::temp_dir().join(format!("cufem_delamination_plot_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let written = cufem::write_results(&model, &solution, &dir).unwrap();
    assert!(written.iter().any(|f| f.ends_with("delamination.png")), "files {written:?}");
    let header = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    assert!(header.lines().next().unwrap().split(',').any(|c| c == "delaminated_area"), "history.csv's header");
    std::fs::remove_dir_all(&dir).unwrap();
}
