//! Coulomb friction on node-to-node contact (issue 9, item 3): a block
//! pressed on a rigid floor and pushed sideways slides when, and with the
//! force that, Coulomb's law says.

mod common;

use cufem::analysis::{self, Structure};
use cufem::setup::Model;
use cufem::solver::newton::{self, NewtonSettings};
use cufem::solver::stepping::Incremental;

/// A 20 × 10 × 10 mm steel block on a rigid floor (z = 0) with friction
/// coefficient μ, pressed by 10 MPa on its top (N = 2,000 N) in step
/// "press", then its face x = 0 pushed 0.1 mm along +x in step "slide".
fn block(mu: f64) -> String {
    block_with(mu, "{ y = 0.0 }", "{ x = 0.0 }", 1e-4, 10, "")
}

/// The block of [`block`] with the selection held in y, the pushed
/// selection, the push amplitude (m), the increments of "slide" and more
/// steps after it.
fn block_with(mu: f64, held: &str, pushed: &str, amplitude: f64, increments: usize, more: &str) -> String {
    format!(
        r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "block"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = 2 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.01, elements = 1 }}

[[constraints]]
name = "symmetry"
body = "block"
where = {held}
fix = ["y"]

[[constraints]]
name = "push"
body = "block"
where = {pushed}
displacement = {{ x = {amplitude:e} }}

[[loads]]
name = "press"
body = "block"
where = {{ z = 0.01 }}
pressure = 10e6

[[indenters]]
name = "floor"
body = "block"
shape = "flat"
surface = {{ z = 0.0 }}
normal = "+z"
position = 0.0
x = [-0.01, 0.03]
y = [-0.01, 0.02]
displacement = [0.0, 0.0, 0.0]
friction = {mu}

[[steps]]
name = "press"
increments = 2
factors = {{ push = 0.0 }}

[[steps]]
name = "slide"
increments = {increments}
{more}"#
    )
}

/// Sliding: once the whole contact slides, the push reaction is μ N
/// (Coulomb; N = 10 MPa × 200 mm² = 2,000 N by vertical equilibrium) to
/// 1e-6, and every point is on the cone; before the push the reaction is
/// below μ N. The normal force is the pressure load.
///
/// Reversal, unloading and the tangent: the tests below.
#[test]
fn a_pushed_block_slides_at_mu_times_the_normal_force() {
    let mut worst: f64 = 0.0;
    for mu in [0.1, 0.3] {
        let sol = common::run(&block(mu));
        let n = sol.contact("floor").unwrap().force[2];
        assert!((n / 2000.0 - 1.0).abs() < 1e-9, "normal force {n}");
        let push = sol.reaction("push").unwrap().force[0];
        worst = worst.max((push.abs() / (mu * 2000.0) - 1.0).abs());
        assert!((push.abs() / (mu * 2000.0) - 1.0).abs() < 1e-6, "push {push} vs μN {}", mu * 2000.0);
        // the floor's resultant split: normal N, tangential μ N
        let floor = sol.contact("floor").unwrap();
        assert!((floor.normal_force[2] / 2000.0 - 1.0).abs() < 1e-9);
        assert!((floor.tangential_force[0].abs() / (mu * 2000.0) - 1.0).abs() < 1e-6, "{:?}", floor.tangential_force);
        let points = sol.contact_points("floor").unwrap();
        assert!(points.iter().filter(|p| p.active).all(|p| p.sliding), "all active points slide");
        // at the end of "press" the held face x = 0 resists the floor's
        // friction against the Poisson expansion (measured 139 N at μ = 0.1),
        // below the sliding force
        let pressed = &sol.steps[0];
        let r = pressed.reactions.iter().find(|r| r.name == "push").unwrap().force[0];
        assert!(r.abs() < mu * 2000.0, "push reaction after pressing {r}");
    }
    common::figure("friction.slide.push", worst, "", "< 1e-6 of μN (Coulomb), μ = 0.1 and 0.3");
}

/// Steps after "slide": back to −amplitude (the press held), then home to 0.
const BACK_AND_HOME: &str = r#"
[[steps]]
name = "back"
factor = -1.0
factors = { press = 1.0 }
increments = 20

[[steps]]
name = "home"
factor = 0.0
factors = { press = 1.0 }
increments = 10
"#;

/// One converged increment of [`drive`].
struct State {
    /// Push displacement (m).
    u: f64,
    /// Push reaction along x (N).
    reaction: f64,
    points: Vec<analysis::ContactPoint>,
    /// Relative residuals of the Newton solve.
    residuals: Vec<f64>,
}

/// Drives the structure through the load factors `lambdas` (analysis time
/// of `[[steps]]`), one Newton solve per value without cutbacks, each of
/// which must converge; `push(λ)` is the push displacement at λ.
fn drive(model: &Model, lambdas: &[f64], push: impl Fn(f64) -> f64) -> Vec<State> {
    let mut s = Structure::of_model(model, None).unwrap();
    let mut out = Vec::new();
    for &l in lambdas {
        s.set_load_factor(l);
        let r = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
        assert!(r.converged(), "λ = {l}: {r:?}");
        s.commit();
        let reaction = s.reactions().iter().find(|r| r.name == "push").unwrap().force[0];
        if std::env::var("DBG").is_ok() {
            eprintln!("λ {l:.3} {:?}", r.residuals.iter().map(|v| format!("{v:.1e}")).collect::<Vec<_>>());
        }
        out.push(State { u: push(l), reaction, points: s.contact_points().to_vec(), residuals: r.residuals });
    }
    out
}

/// λ of "press" (0..1), "slide" (1..2, `n` increments), "back" (2..3, 2n)
/// and "home" (3..4, n).
fn path(n: usize) -> Vec<f64> {
    let mut l = vec![0.5, 1.0];
    l.extend((1..=n).map(|k| 1.0 + k as f64 / n as f64));
    l.extend((1..=2 * n).map(|k| 2.0 + k as f64 / (2 * n) as f64));
    l.extend((1..=n).map(|k| 3.0 + k as f64 / n as f64));
    l
}

/// Push displacement along [`path`] for the amplitude `a`.
fn push_at(a: f64) -> impl Fn(f64) -> f64 {
    move |l: f64| match l {
        l if l <= 1.0 => 0.0,
        l if l <= 2.0 => (l - 1.0) * a,
        l if l <= 3.0 => a - 2.0 * (l - 2.0) * a,
        l => -a + (l - 3.0) * a,
    }
}

/// Loading, unloading and reversal, exactly: every node of the block is
/// moved along x by the push (plane strain, u_y = 0 everywhere), so the
/// block translates as a whole over the floor and each contact point is a
/// Jenkins element (a spring ε_T in series with a Coulomb slider). The
/// pressure 10 MPa gives each point `p_i = P w_i` and the penetration
/// `g = P h/(α E)` at every point (uniform σ_zz, penalty ε_i = α E w_i/h),
/// so all points have the same stick range `r = μ p_i/ε_T,i = μ g`. The
/// slip of every point is then the play operator of the push U with half
/// width r (Jenkins/Prandtl; the stop/play hysteresis of Coulomb's law):
/// from the path 0 → A → −A → 0 with A = 1.1e-8 m ≈ 7.3 r (no increment
/// ends on a stick–slip transition),
/// `s = U − r` sliding forward, `s = U + r` sliding back, constant while
/// sticking; the reaction is `K (U − s)` with `K = Σ ε_T,i`, ±μN on the
/// plateaus. Each increment's slip is checked at every point, with its
/// stick/slip state, the reaction, and the residual slip at the end
/// (−r at every point, held by +μN).
#[test]
fn a_translated_block_follows_the_coulomb_play_operator() {
    let (mu, a, n) = (0.3, 1.1e-8, 10);
    follows_the_play_operator("friction.play", &block_with(mu, "{}", "{}", a, n, BACK_AND_HOME), mu, a, n);
}

/// The same with the normal force from a force-controlled floor: the top
/// face held in z, the floor pushing up with `force = 2,000 N` (the
/// bordered Newton system with the frictional blocks in its border row
/// and column, `structure/force.rs`); N is exact by construction, the
/// stick range and the play operator as above.
#[test]
fn a_translated_block_on_a_force_controlled_floor_follows_the_play_operator() {
    let (mu, a, n) = (0.3, 1.1e-8, 10);
    let text = force_controlled(&block_with(mu, "{}", "{}", a, n, BACK_AND_HOME));
    let model = Model::parse(&text).unwrap();
    assert!(model.indenters[0].force.is_some() && model.loads.is_empty(), "force-controlled floor, no pressure");
    follows_the_play_operator("friction.play_force_controlled", &text, mu, a, n);
}

/// The checks of [`a_translated_block_follows_the_coulomb_play_operator`].
fn follows_the_play_operator(id: &str, text: &str, mu: f64, a: f64, n: usize) {
    let model = Model::parse(text).unwrap();
    let floor = &model.indenters[0];
    let k: f64 = floor.nodes.iter().map(|c| c.penalty).sum();
    let normal = 2000.0;
    let r = mu * normal / k;
    let states = drive(&model, &path(n), push_at(a));
    let mut s: f64 = 0.0; // analytic slip (play operator)
    let mut stuck_below = 0;
    let (mut worst_reaction, mut worst_slip): (f64, f64) = (0.0, 0.0);
    for st in &states {
        let before = s;
        s = s.clamp(st.u - r, st.u + r);
        let sliding = s != before;
        let reaction = k * (st.u - s);
        worst_reaction = worst_reaction.max((st.reaction - reaction).abs() / (mu * normal));
        assert!(
            (st.reaction - reaction).abs() < 1e-9 * mu * normal,
            "U = {:e}: reaction {} vs {reaction}",
            st.u,
            st.reaction
        );
        assert!(st.reaction.abs() <= mu * normal * (1.0 + 1e-12));
        for p in st.points.iter() {
            assert!(p.active);
            worst_slip = worst_slip.max((p.slip[0] - s).abs() / a);
            assert!((p.slip[0] - s).abs() < 1e-9 * a, "U = {:e}: slip {:e} vs {s:e}", st.u, p.slip[0]);
            assert_eq!(p.sliding, sliding, "U = {:e}", st.u);
        }
        stuck_below += usize::from(!sliding && st.reaction.abs() > 0.0 && st.reaction.abs() < mu * normal * 0.999);
    }
    assert!(stuck_below >= 2, "increments that stick below μN: {stuck_below}");
    common::figure(&format!("{id}.reaction"), worst_reaction, "", "< 1e-9 of μN, against the play operator");
    common::figure(
        &format!("{id}.slip"),
        worst_slip,
        "",
        "< 1e-9 of the amplitude at every point, against the play operator",
    );
    let end = states.last().unwrap();
    assert!((end.u).abs() < 1e-20 && (end.reaction / (mu * normal) - 1.0).abs() < 1e-9);
    assert!(end.points.iter().all(|p| (p.slip[0] + r).abs() < 1e-9 * a), "residual slip −r at every point");
}

/// Loading, unloading and reversal of the deformable block (plane strain)
/// pushed on its face x = 0 by A = 2 µm, back to −A and home to 0, one
/// Newton solve per increment without cutbacks: every increment converges
/// (with the unsymmetric tangent and the stick predictor; the symmetric
/// tangent alone chattered at the reversal). Coulomb: the reaction never
/// exceeds μN, stays below it while any point sticks, equals ±μN (1e-6)
/// whenever every point slides. Residual slip: while all points slide one
/// way the state is unique up to a rigid translation, so each point's slip
/// is `U + c_i` with `c_i` the same on every forward plateau — checked
/// between the first forward plateau and the end of "home" (after a
/// reversal and a re-reversal), and per increment (Δs_i = ΔU).
#[test]
fn a_pushed_block_unloads_reverses_and_returns_with_the_right_slip() {
    let (mu, a, n) = (0.3, 2e-6, 20);
    unloads_reverses_and_returns(&block_with(mu, "{}", "{ x = 0.0 }", a, n, BACK_AND_HOME), mu, a, n);
}

/// The same path with the normal force from a force-controlled floor (top
/// face held in z): the bordered system now carries the sliding points'
/// unsymmetric blocks in its border column and row (`structure/force.rs`).
/// Measured: 82 increments, 168 Newton iterations (the bordered solves are
/// made to 1e-12, as exact as a direct solve; the pressure-loaded block, whose
/// solves stop at the forcing term, takes 233 — one more iteration per
/// increment where an exact solve lands on the solution at once, these
/// increments being linear); with the frictionless border (`ε n nᵀ` alone) Newton does not converge
/// in the first press increment (25 iterations, residual growing).
#[test]
fn a_pushed_block_on_a_force_controlled_floor_unloads_and_reverses() {
    let (mu, a, n) = (0.3, 2e-6, 20);
    unloads_reverses_and_returns(
        &force_controlled(&block_with(mu, "{}", "{ x = 0.0 }", a, n, BACK_AND_HOME)),
        mu,
        a,
        n,
    );
}

/// The block with its top held in z and pressed by a force-controlled
/// floor (2,000 N up) instead of the pressure load.
fn force_controlled(text: &str) -> String {
    text.replace("factors = { press = 1.0 }", "factors = { press = 1.0, floor = 1.0 }")
        .replace(
            "[[loads]]\nname = \"press\"\nbody = \"block\"\nwhere = { z = 0.01 }\npressure = 10e6",
            "[[constraints]]\nname = \"press\"\nbody = \"block\"\nwhere = { z = 0.01 }\nfix = [\"z\"]",
        )
        .replace("displacement = [0.0, 0.0, 0.0]", "force = [0.0, 0.0, 2000.0]")
}

/// The checks of [`a_pushed_block_unloads_reverses_and_returns_with_the_right_slip`].
fn unloads_reverses_and_returns(text: &str, mu: f64, a: f64, n: usize) {
    let model = Model::parse(text).unwrap();
    assert!(model.indenters[0].force.is_some() == model.loads.is_empty());
    let states = drive(&model, &path(n), push_at(a));
    let limit = mu * 2000.0;
    let iterations: usize = states.iter().map(|s| s.residuals.len() - 1).sum();
    eprintln!("{} increments, {iterations} Newton iterations", states.len());
    let mut first_forward: Option<&State> = None;
    let mut plateaus = [0, 0];
    // the reaction is μN up to the equilibrium residual Newton leaves:
    // below its tolerance (1e-6) times the force scale (the 2,000 N load).
    // (With the exact LU solves this test was written for, the last step
    // landed at round-off and 1e-9 of μN held; the iterative solves stop at
    // the forcing term: measured 2.7e-9 of μN above it.)
    let slack = NewtonSettings::default().residual_tolerance * 2000.0;
    for (k, st) in states.iter().enumerate() {
        let all = st.points.iter().filter(|p| p.active).all(|p| p.sliding);
        assert!(st.reaction.abs() <= limit + slack, "U = {:e}: {}", st.u, st.reaction);
        if !all {
            assert!(st.reaction.abs() < limit * (1.0 - 1e-6), "sticking points: below μN");
            continue;
        }
        assert!((st.reaction.abs() / limit - 1.0).abs() < 1e-6, "U = {:e}: {} vs μN {limit}", st.u, st.reaction);
        let forward = st.reaction > 0.0;
        plateaus[usize::from(forward)] += 1;
        let prev = &states[k - 1];
        if prev.points.iter().all(|p| !p.active || p.sliding) && (prev.reaction > 0.0) == forward {
            let du = st.u - prev.u;
            for (p, q) in st.points.iter().zip(&prev.points) {
                assert!(
                    ((p.slip[0] - q.slip[0]) - du).abs() < 1e-6 * du.abs(),
                    "Δs {:e} vs ΔU {du:e}",
                    p.slip[0] - q.slip[0]
                );
            }
        }
        if forward && first_forward.is_none() {
            first_forward = Some(st);
        }
    }
    assert!(plateaus[0] >= 5 && plateaus[1] >= 10, "plateau increments back/forward: {plateaus:?}");
    let (first, end) = (first_forward.unwrap(), states.last().unwrap());
    assert!(end.reaction > 0.0 && end.u.abs() < 1e-20);
    for (p, q) in end.points.iter().zip(&first.points) {
        let (c_end, c_first) = (p.slip[0] - end.u, q.slip[0] - first.u);
        assert!((c_end - c_first).abs() < 1e-6 * a, "slip offset {c_end:e} at the end vs {c_first:e}");
    }
}

/// The assembled frictional tangent — with its unsymmetric part — is the
/// derivative of the assembled residual: central differences of `R(u)`
/// against columns of `K` (`Structure::tangent_entry`) at the DOFs of every
/// contact point, in a state of partial slip of the 3D block (held in y on
/// y = 0 only, so the Poisson expansion turns the slip direction out of x):
/// the first push increment, where some points stick and some slide.
/// Expected: agreement to the differencing error (h = 1e-12 m against a
/// stick range μ p/ε_T ≈ 1e-9 m; observed 5.4e-8 of the largest penalty
/// ε_N), asserted below 1e-6; a missing coupling `μ ε_N t̂ nᵀ` would be
/// 0.3 ε_N (the observed asymmetry 0.29 ε_N).
#[test]
fn the_frictional_tangent_matches_finite_differences_sticking_and_sliding() {
    use cufem::solver::newton::NonlinearProblem;
    let model = Model::parse(&block_with(0.3, "{ y = 0.0 }", "{ x = 0.0 }", 2e-6, 20, "")).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    assert!(s.is_unsymmetric(), "a model with friction keeps an unsymmetric part");
    // converged at λ = 1.05 but not committed: a point that slid in this
    // increment is strictly outside the cone of its committed slip (after a
    // commit it would sit on the cone, where the derivative is one-sided)
    for l in [0.5, 1.0, 1.05] {
        s.set_load_factor(l);
        assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
        if l < 1.05 {
            s.commit();
        }
    }
    s.evaluate().unwrap();
    let points = s.contact_points().to_vec();
    let (sliding, sticking) =
        (points.iter().filter(|p| p.sliding).count(), points.iter().filter(|p| !p.sliding).count());
    assert!(sliding > 0 && sticking > 0, "partial slip: {sliding} sliding, {sticking} sticking");
    let columns: Vec<(usize, usize)> = points
        .iter()
        .flat_map(|p| (0..3).map(move |c| 3 * p.node + c))
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    let penalty = model.indenters[0].nodes.iter().map(|c| c.penalty).fold(0.0, f64::max);
    let (worst, skew) = common::tangent_vs_differences(&mut s, &columns, 1e-12, penalty);
    common::figure("friction.tangent.indenter", worst, "ε_N", "< 1e-6 ε_N against central differences");
    common::figure("friction.tangent.indenter_skew", skew, "ε_N", "> 0.1 ε_N (the sliding tangent is unsymmetric)");
    assert!(skew > 0.1, "the sliding points' tangent is unsymmetric (μ = 0.3)");
    assert!(worst < 1e-6, "tangent differs from finite differences by {worst:e} of the largest penalty");
}

/// Quadratic convergence: on the sliding plateau of the 3D block (every
/// point slides, the slip direction turning with the Poisson expansion in
/// y, so the return map is nonlinear) the stick/slip set stays the same in
/// every iteration of an increment, and from the second iteration on (the
/// first uses the stick predictor) the relative residual falls as
/// `r_{k+1} ≤ C r_k²`. Observed with the exact (LU) solves this test was
/// written for: 1.4e-1, 2.0e-2, 3.9e-4, 7.5e-7, 5.4e-12 (ratios
/// r_{k+1}/r_k² = 1.0, 1.0, 4.9, 9.6; the round-off floor is 2e-15); with
/// GMRES solved to the forcing term η = r (`solver::reuse`, inexact Newton
/// keeps the order): 1.4e-1, 1.9e-2, 1.4e-3, 7.5e-6, 1.1e-9, 2.5e-15
/// (ratios 1.0, 3.8, 3.9, 20). C = 100 bounds ½‖∂²R‖‖K⁻¹‖² in these units with room, and still
/// tells quadratic from linear: a linear rate of even 0.1 at r = 7.5e-7
/// would give a ratio of 1.3e5.
#[test]
fn newton_converges_quadratically_on_the_sliding_plateau() {
    use cufem::solver::newton::NonlinearProblem;
    let model = Model::parse(&block_with(0.3, "{ y = 0.0 }", "{ x = 0.0 }", 2e-6, 20, "")).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    for l in [0.5, 1.0, 1.05, 1.1, 1.15, 1.2, 1.25, 1.3, 1.35, 1.4] {
        s.set_load_factor(l);
        assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
        s.commit();
    }
    s.set_load_factor(1.45);
    let mut residuals = Vec::new();
    for _ in 0..8 {
        let ev = s.evaluate().unwrap();
        let all = s.contact_points().iter().all(|p| p.active && p.sliding);
        residuals.push(ev.residual_norm / ev.force_scale);
        if residuals.len() > 1 {
            assert!(all, "every point slides in iteration {}", residuals.len() - 1);
        }
        if *residuals.last().unwrap() < 1e-11 {
            break;
        }
        s.correct().unwrap();
    }
    let r = &residuals;
    assert!(r.last().unwrap() < &1e-11, "converged");
    let constant = (1..r.len() - 1).filter(|&k| r[k + 1] > 1e-13).map(|k| r[k + 1] / (r[k] * r[k])).fold(0.0, f64::max);
    common::figure("friction.newton.constant", constant, "", "r_(k+1)/r_k² ≤ 100 from the second iteration on");
    // below 1e-13 the residual is round-off (floor 2e-15), not Newton's
    // rate: a step from r = 1.1e-9 lands on the floor, not on 100 r² = 1e-16
    for k in (1..r.len() - 1).filter(|&k| r[k + 1] > 1e-13) {
        assert!(r[k + 1] <= 100.0 * r[k] * r[k], "r_{} = {:.2e} > 100 r_{}² ({:.2e})", k + 1, r[k + 1], k, r[k]);
    }
}

/// The same check for friction between two deformable bodies (node pairs):
/// an upper block pressed on a lower one (held at its base) and pushed
/// sideways on its face x = 0, so that the interface partly slides. The
/// columns of the slave and of the master nodes are checked: the skew part
/// of each pair's block enters `[K, −K; −K, K]` with the master's signs.
/// Expected as for the indenter: the differencing error (observed 2.6e-11
/// of the largest penalty), asserted below 1e-6; flipping the sign of one
/// master skew block fails it.
#[test]
fn the_tangent_of_frictional_node_pairs_matches_finite_differences() {
    use cufem::solver::newton::NonlinearProblem;
    let text = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "lower"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.02, elements = 2 }, z = { from = 0.0, to = 0.01, elements = 1 } }
axis = { element = "B3", from = 0.0, to = 0.01, elements = 1 }

[[bodies]]
name = "upper"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.02, elements = 2 }, z = { from = 0.01, to = 0.02, elements = 1 } }
axis = { element = "B3", from = 0.0, to = 0.01, elements = 1 }

[[constraints]]
name = "base"
body = "lower"
where = { z = 0.0 }
fix = ["x", "y", "z"]

[[constraints]]
name = "upper_y"
body = "upper"
where = { y = 0.0 }
fix = ["y"]

[[constraints]]
name = "push"
body = "upper"
where = { x = 0.0 }
displacement = { x = 2e-6 }

[[loads]]
name = "press"
body = "upper"
where = { z = 0.02 }
pressure = 10e6

[[contacts]]
name = "interface"
master = { body = "lower", where = { z = 0.01 } }
slave = { body = "upper", where = { z = 0.01 } }
friction = 0.3

[[steps]]
name = "press"
factors = { push = 0.0 }

[[steps]]
name = "slide"
"#;
    let model = Model::parse(text).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    assert!(s.is_unsymmetric());
    // pressed and committed, then a tenth of the push solved but not
    // committed (points that slide are strictly outside their cone)
    common::solve_path(&mut s, &[(0.5, true), (1.0, true), (1.1, false)]);
    s.evaluate().unwrap();
    let points = s.contact_points().to_vec();
    let sliding = points.iter().filter(|p| p.active && p.sliding).count();
    let sticking = points.iter().filter(|p| p.active && !p.sliding).count();
    assert!(sliding > 0 && sticking > 0, "partial slip: {sliding} sliding, {sticking} sticking");
    let columns: Vec<(usize, usize)> = points
        .iter()
        .flat_map(|p| [p.node, p.master.unwrap()])
        .flat_map(|n| (0..3).map(move |c| 3 * n + c))
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    let penalty = model.contacts[0].pairs.iter().map(|p| p.penalty).fold(0.0, f64::max);
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-12, penalty);
    common::figure("friction.tangent.pairs", worst, "ε_N", "< 1e-6 ε_N against central differences");
    assert!(worst < 1e-6, "tangent differs from finite differences by {worst:e} of the largest penalty");
}

/// examples/cantilevers_contact_friction.toml with 60 B4 per beam along the
/// axis and 2 × 2 L9 per section (27,150 DOF), its rollers pressed the
/// example's first increment (0.125 mm) in one increment. That first
/// attempt fails (the roller's rows and the bonded interface open and
/// close together, the tangent singular), and so does its cautious retry;
/// at half the increment Newton peels the interface open and converges.
/// While the retries gave sliding points the stick tangent at every
/// iteration, the peeled state (20 points touching, 10 sliding, no status
/// change) converged linearly at a rate near one — the relative residual
/// stayed at 0.28 for a dozen corrections — and every cutback repeated
/// that to `solver.min_increment`: the run stopped in its first increment.
#[test]
fn a_fine_frictional_peel_converges_in_its_retry() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilevers_contact_friction.toml"))
            .unwrap()
            .replace("elements = 4 }", "elements = 2 }")
            .replace("elements = 10 }", "elements = 60 }")
            .replace("displacement = [0.0, 0.0, -2.5e-3]", "displacement = [0.0, 0.0, -1.25e-4]")
            .replace("increments = 20", "increments = 1");
    let model = Model::parse(&text).unwrap();
    assert_eq!(model.n_dofs(), 27_150);
    let s = analysis::run(&model, &Default::default(), &mut analysis::Silent).unwrap();
    let corrections: Vec<usize> = s.increments.iter().map(|i| i.newton.iterations).collect();
    eprintln!("corrections per increment {corrections:?}, cutbacks {}", s.cutbacks.len());
    assert!(s.failure.is_none(), "{:?}", s.failure);
    assert!(!s.cutbacks.is_empty(), "the first attempt fails: the retry is what this checks");
    assert!((s.lambda - 1.0).abs() < 1e-12);
}
