//! Large deformation (issue 26): the total-Lagrangian CUF against the
//! exact elastica, Newton's convergence with the geometric stiffness, and
//! the model-file switch.

use std::path::Path;
use std::process::Command;

use cufem::analysis;
use cufem::setup::Model;

#[path = "../../../tests/common/mod.rs"]
mod common;

const ELASTICA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/elastica.toml");

/// The inextensible, shear-rigid elastica of a cantilever under a dead tip
/// load `α = P L²/(E I)` perpendicular to its undeformed axis, by shooting:
/// with `s ∈ [0, 1]` the arc length over `L` and `θ` the rotation,
/// `θ'' = −α cos θ`, `θ(0) = 0` (clamped), `θ'(1) = 0` (no tip moment).
/// The root curvature `θ'(0) ∈ (0, α]` is found by bisection on `θ'(1)`,
/// each trial integrated by classical Runge–Kutta (4,000 steps), and the
/// tip follows from `x = ∫ cos θ ds`, `v = ∫ sin θ ds` (Simpson, on the
/// same steps). Returns `(v/L, (L − x)/L)`: deflection and shortening.
fn elastica(alpha: f64) -> (f64, f64) {
    const N: usize = 4000;
    let h = 1.0 / N as f64;
    // integrates (θ, θ') and returns θ at every step and θ'(1)
    let shoot = |k0: f64| -> (Vec<f64>, f64) {
        let f = |th: f64, om: f64| (om, -alpha * th.cos());
        let (mut th, mut om) = (0.0, k0);
        let mut path = Vec::with_capacity(N + 1);
        path.push(th);
        for _ in 0..N {
            let (a1, b1) = f(th, om);
            let (a2, b2) = f(th + 0.5 * h * a1, om + 0.5 * h * b1);
            let (a3, b3) = f(th + 0.5 * h * a2, om + 0.5 * h * b2);
            let (a4, b4) = f(th + h * a3, om + h * b3);
            th += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
            om += h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
            path.push(th);
        }
        (path, om)
    };
    // θ'(1) < 0 when the root curvature is too small (the beam bends back
    // too little to relieve the moment), > 0 when too large
    let (mut lo, mut hi) = (0.0, alpha);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid).1 < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (path, _) = shoot(0.5 * (lo + hi));
    let simpson = |g: &dyn Fn(f64) -> f64| -> f64 {
        let mut s = g(path[0]) + g(path[N]);
        for (i, &t) in path.iter().enumerate().take(N).skip(1) {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * g(t);
        }
        s * h / 3.0
    };
    (simpson(&|t| t.sin()), 1.0 - simpson(&|t| t.cos()))
}

/// The oracle against the published table (Mattiasson 1981, Table 1, tip
/// deflection and shortening of the elastica, five digits): the shooting
/// above must reproduce it to its last digit.
#[test]
fn the_shooting_oracle_reproduces_mattiasson() {
    for (alpha, v, u) in
        [(1.0, 0.30172, 0.05643), (2.0, 0.49346, 0.16064), (5.0, 0.71379, 0.38763), (10.0, 0.81061, 0.55500)]
    {
        let (ev, eu) = elastica(alpha);
        assert!((ev - v).abs() < 1e-5 && (eu - u).abs() < 1e-5, "α = {alpha}: {ev:.6} {eu:.6}");
    }
}

/// `examples/elastica.toml` through the CLI: the tip of the 20 B4 × 1 L9
/// cantilever at the ends of its four steps, P L²/(E I) = 1, 2, 5, 10,
/// both components within 0.5 % of the elastica (issue 26; measured:
/// within 0.02 %). A small-strain run of the same file deflects the tip
/// 10/3 L at α = 10 and could not pass; a missing geometric stiffness
/// stops Newton; a 10 % error in E moves the α = 1 deflection by ~9 %.
#[test]
fn elastica_tip_within_half_a_percent_through_the_cli() {
    let out = std::env::temp_dir().join(format!("cufem_elastica_{}", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", ELASTICA, "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let steps = summary["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 4);
    for (step, alpha) in steps.iter().zip([1.0, 2.0, 5.0, 10.0]) {
        let u = &step["probes"][0]["u"];
        // L = 1 m: displacements are fractions of L
        let (v, s) = (-u[2].as_f64().unwrap(), -u[1].as_f64().unwrap());
        let (ev, es) = elastica(alpha);
        eprintln!("α = {alpha}: v/L {v:.5} ({ev:.5}), shortening {s:.5} ({es:.5})");
        assert!((v - ev).abs() < 5e-3 * ev, "α = {alpha}: deflection {v} against {ev}");
        assert!((s - es).abs() < 5e-3 * es, "α = {alpha}: shortening {s} against {es}");
    }
    let history = std::fs::read_to_string(out.join("history_probes.csv")).unwrap();
    assert!(history.starts_with("increment,lambda,iterations,tip.u_x,tip.u_y,tip.u_z\n"));
    assert_eq!(history.lines().count(), 1 + summary["increments"].as_u64().unwrap() as usize);
    std::fs::remove_dir_all(&out).ok();
}

/// Newton converges quadratically with the geometric stiffness: from the
/// converged state at P L²/(E I) = 2 (tip rotation ≈ 50°, solved to
/// round-off) perturbed by 1 % of itself, the relative error
/// e_k = ‖u_k − u*‖/‖u*‖ of successive full-Newton iterates obeys
/// e_(k+1) ≤ C e_k² and reaches round-off in four iterations (measured:
/// 1e-2, 7.4e-3, 1.4e-5, 3.2e-7, 2.3e-14, i.e. C = 0.26, 1,540, 0.23 — large
/// in the Euclidean norm of a thin beam, whose membrane stiffness is
/// (L/h)² times its bending stiffness). A linearly converging iteration at
/// rate ρ gives e_(k+1)/e_k² = ρ/e_k, 3e6 ρ at the last pair.
#[test]
fn newton_converges_quadratically_with_the_geometric_stiffness() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let mut model = Model::from_file(Path::new(ELASTICA)).unwrap();
    model.solver.reuse.enabled = false;
    model.solver.reuse.single_precision = false;
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    for l in [0.05, 0.1, 0.15, 0.2] {
        s.set_load_factor(l);
        assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
        s.commit();
    }
    // the reference to round-off, not to the run's tolerance
    let tight = NewtonSettings { residual_tolerance: 1e-14, displacement_tolerance: 1e-15, ..Default::default() };
    newton::solve(&mut s, &tight, &Default::default());
    let exact = s.displacements().to_vec();
    let norm = exact.iter().map(|v| v * v).sum::<f64>().sqrt();
    for v in s.displacements_mut() {
        *v *= 1.01;
    }
    let mut errors = Vec::new();
    for _ in 0..6 {
        let e = s.displacements().iter().zip(&exact).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt() / norm;
        errors.push(e);
        if e < 1e-12 {
            break;
        }
        s.evaluate().unwrap();
        s.correct().unwrap();
    }
    eprintln!("relative errors {errors:?}");
    let mut pairs = 0;
    for w in errors.windows(2).filter(|w| w[1] > 1e-13) {
        assert!(w[1] < 1e4 * w[0] * w[0], "e_(k+1)/e_k² = {:.3e} in {errors:?}", w[1] / (w[0] * w[0]));
        pairs += 1;
    }
    assert!(pairs >= 3 && *errors.last().unwrap() < 1e-12, "{errors:?}");
}

/// At finite strain B-bar projects the logarithmic dilatation ln J: with
/// the Green–Lagrange strain it is refused, by its key, whether asked for
/// or the default (ν ≥ 0.45); with the logarithmic strain it is accepted,
/// but not with an imperfection.
#[test]
fn bbar_at_finite_strain_needs_the_logarithmic_strain() {
    let text = std::fs::read_to_string(ELASTICA).unwrap();
    let asked = text.replacen("material = \"steel\"\n", "material = \"steel\"\nformulation = \"bbar\"\n", 1);
    let e = Model::parse(&asked).unwrap_err().to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("analysis.strain = \"logarithmic\""), "{e}");
    let log = asked.replace("geometry = \"nonlinear\"\n", "geometry = \"nonlinear\"\nstrain = \"logarithmic\"\n");
    assert!(Model::parse(&log).is_ok());
    let default = text.replace("poisson_ratio = 0.0", "poisson_ratio = 0.49");
    let e = Model::parse(&default).unwrap_err().to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("ν ≥ 0.45"), "{e}");
    let imperfect =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/column_postbuckling.toml"))
            .unwrap();
    let bbar_imperfect = imperfect
        .replace("geometry = \"nonlinear\"\n", "geometry = \"nonlinear\"\nstrain = \"logarithmic\"\n")
        .replacen("[[bodies]]\n", "[[bodies]]\nformulation = \"bbar\"\n", 1);
    let e = Model::parse(&bbar_imperfect).unwrap_err().to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("analysis.imperfection"), "{e}");
    // an imperfection needs nonlinear geometry and a length
    let imperfect =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/column_postbuckling.toml"))
            .unwrap();
    let e = Model::parse(&imperfect.replace("geometry = \"nonlinear\"\n", "")).unwrap_err().to_string();
    assert!(e.contains("analysis.imperfection") && e.contains("nonlinear"), "{e}");
    let e = Model::parse(&imperfect.replace("amplitude = 1e-3", "amplitude = 0.0")).unwrap_err().to_string();
    assert!(e.contains("analysis.imperfection.amplitude = 0"), "{e}");
    let standard = default.replacen("material = \"steel\"\n", "material = \"steel\"\nformulation = \"standard\"\n", 1);
    assert!(Model::parse(&standard).is_ok());
}

/// The assembled tangent of the deformed elastica (material and geometric
/// parts, Dirichlet elimination) against central differences of the
/// residual in every component of a few nodes along the beam, at the
/// converged state P L²/(E I) = 2 (tip rotation ≈ 50°).
#[test]
fn assembled_tangent_matches_finite_differences_at_large_rotation() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let model = Model::from_file(Path::new(ELASTICA)).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    for l in [0.05, 0.1, 0.15, 0.2] {
        s.set_load_factor(l);
        let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
        assert!(report.converged(), "{report:?}");
        s.commit();
    }
    s.evaluate().unwrap();
    let k = s.tangent_values().to_vec();
    let eq: Vec<usize> = (0..s.displacements().len()).map(|d| s.equation(d).unwrap_or(usize::MAX)).collect();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let n_nodes = s.displacements().len() / 3;
    let columns: Vec<(usize, usize)> = (1..6)
        .map(|i| i * n_nodes / 6)
        .flat_map(|n| [3 * n, 3 * n + 1, 3 * n + 2])
        .filter(|&d| eq[d] != usize::MAX)
        .map(|d| (d, eq[d]))
        .collect();
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-9, scale);
    eprintln!("{} columns, largest relative difference {worst:e}", columns.len());
    assert!(worst < 1e-6, "tangent differs from finite differences by {worst:e} of its largest entry");
}

/// Against CalculiX with NLGEOM through `cufem verify` (issue 26): the
/// elastica at P L²/(E I) = 10 in one step (verify needs a single-step
/// model; 20 increments) against 240 C3D20R (5,463 DOF). Tip displacement
/// within 1 % (measured 0.003 %), whole-field displacement L2 within 1 %
/// (measured 0.004 %), von Mises over the beam within 3 % (measured 0.83 %:
/// both report Cauchy stress). A small-strain CalculiX deck (no NLGEOM)
/// would bend the tip by 3.3 m and fail all three.
#[test]
fn elastica_agrees_with_calculix_nlgeom() {
    if common::ccx_missing() {
        return;
    }
    let text = std::fs::read_to_string(ELASTICA).unwrap();
    let one_step = text
        .split("[[steps]]")
        .next()
        .unwrap()
        .to_string()
        .replace("[analysis]", "[solver]\nincrements = 20\n\n[analysis]")
        + &text[text.find("[[probes]]").unwrap()..];
    let dir = std::env::temp_dir().join(format!("cufem_elastica_ccx_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("elastica_one_step.toml");
    std::fs::write(&model, one_step).unwrap();
    let out = dir.join("out");
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["verify", "--quiet", "--refine", "1", "--out"])
        .arg(&out)
        .arg(&model)
        .status()
        .unwrap();
    assert!(status.success());
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let deck = std::fs::read_to_string(out.join("verify/ccx/model.inp")).unwrap();
    assert!(deck.contains("*STEP, NLGEOM,"), "the deck is a large-deformation one");
    for p in table["probes"].as_array().unwrap() {
        if p["quantity"] == "u_y" || p["quantity"] == "u_z" {
            let d = p["difference_percent"].as_f64().unwrap();
            assert!(d.abs() < 1.0, "tip {}: {d} %", p["quantity"]);
        }
    }
    let field = |q: &str| {
        table["fields"].as_array().unwrap().iter().find(|f| f["quantity"] == q).unwrap()["l2_percent"].as_f64().unwrap()
    };
    assert!(field("u") < 1.0, "whole-field u: {} %", field("u"));
    assert!(field("von_mises") < 3.0, "von Mises: {} %", field("von_mises"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Post-buckling of the imperfect column (`examples/column_postbuckling.toml`,
/// the first buckling mode at L/1000 as imperfection) through the CLI: the
/// load against the tip rotation α follows the perfect column's elastica
/// branch P/P_cr = (2 K(k)/π)², k = sin(α/2) (Timoshenko & Gere §2.7; K by
/// the arithmetic–geometric mean), within 1 % at every increment with
/// α ≥ 20° up to α ≥ 90° (measured: within 0.43 %, 0.25 % from 35°).
/// P_cr is the run's own buckling factor (within 1 % of Euler's; +0.2 %).
/// Below 20° the imperfect column leaves the perfect branch, as it must
/// (−2.4 % at 3.7°); without the imperfection it would not buckle at all.
#[test]
fn imperfect_column_follows_the_elastica_branch() {
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/column_postbuckling.toml");
    let out = std::env::temp_dir().join(format!("cufem_postbuckling_{}", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", example, "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let (load, b): (f64, f64) = (11500.0, 0.02);
    let p_cr = summary["buckling"]["factors"][0].as_f64().unwrap() * load;
    let euler = std::f64::consts::PI.powi(2) * 200e9 * 0.025 * b.powi(3) / 12.0 / 4.0;
    assert!((p_cr - euler).abs() < 0.01 * euler, "P_cr {p_cr} against Euler {euler}");
    let elliptic_k = |k: f64| {
        let (mut a, mut g) = (1.0f64, (1.0 - k * k).sqrt());
        for _ in 0..40 {
            (a, g) = (0.5 * (a + g), (a * g).sqrt());
        }
        std::f64::consts::FRAC_PI_2 / a
    };
    let history = std::fs::read_to_string(out.join("history_probes.csv")).unwrap();
    let (mut checked, mut largest) = (0, 0.0f64);
    for line in history.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        // columns: increment, λ, iterations, tip_plus u, tip_minus u
        let (du_x, du_y) = (v[3] - v[6], v[4] - v[7]);
        let alpha = du_y.abs().atan2(b + du_x);
        let p = v[1] * load / p_cr;
        let branch = (2.0 * elliptic_k((alpha / 2.0).sin()) / std::f64::consts::PI).powi(2);
        largest = largest.max(alpha.to_degrees());
        if alpha.to_degrees() >= 20.0 {
            assert!(
                (p - branch).abs() < 0.01 * branch,
                "α = {:.1}°: P/P_cr {p:.4} against {branch:.4}",
                alpha.to_degrees()
            );
            checked += 1;
        } else if p < 0.9 {
            // well below the critical load the imperfect column barely turns
            assert!(alpha.to_degrees() < 2.0, "P/P_cr {p:.3}: α = {:.2}°", alpha.to_degrees());
        }
    }
    assert!(checked >= 10 && largest >= 90.0, "{checked} points, largest rotation {largest:.1}°");
    std::fs::remove_dir_all(&out).ok();
}

/// The bar of the logarithmic-strain tests: 10 × 10 mm section (1 L9),
/// 50 mm long (2 B4) along y, E = 200 GPa, ν = 0.3, linear hardening
/// σ_y = 250 MPa + 1 GPa ε̄ᵖ; symmetry planes x = 0 and z = 0 and the end
/// y = 0 carry one component each, so the lateral faces are free and the
/// deformation is homogeneous; the end y = 0.05 is pulled to a stretch of
/// λ = e^0.5 (50 % logarithmic strain) over five steps ending at
/// ln λ = 0.1, …, 0.5.
fn log_bar(strain: &str) -> String {
    let length = 0.05f64;
    let pull = length * (0.5f64.exp() - 1.0);
    let steps: String = (1..=5)
        .map(|k| {
            let factor = ((0.1 * k as f64).exp() - 1.0) / (0.5f64.exp() - 1.0);
            format!("[[steps]]\nname = \"s{k}\"\nfactor = {factor:.17}\nincrements = 4\n\n")
        })
        .collect();
    format!(
        r#"title = "bar pulled to a logarithmic strain of 0.5"

[analysis]
geometry = "nonlinear"
{strain}

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
plasticity = {{ hardening = "linear", yield_stress = 250e6, hardening_modulus = 1e9 }}

[[bodies]]
name = "bar"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = {length}, elements = 2 }}

[[constraints]]
name = "end"
body = "bar"
where = {{ y = 0.0 }}
fix = ["y"]

[[constraints]]
name = "symmetry_x"
body = "bar"
where = {{ x = 0.0 }}
fix = ["x"]

[[constraints]]
name = "symmetry_z"
body = "bar"
where = {{ z = 0.0 }}
fix = ["z"]

[[constraints]]
name = "pull"
body = "bar"
where = {{ y = {length} }}
displacement = {{ y = {pull:.17} }}

{steps}[[probes]]
name = "end"
point = [0.005, {length}, 0.005]
"#
    )
}

/// Uniaxial tension to 50 % logarithmic strain with
/// `analysis.strain = "logarithmic"`: at the end of each of the five steps
/// (ln λ = 0.1 … 0.5) the Cauchy stress σ_yy at every Gauss point follows
/// the hardening curve, σ = σ_y(ε̄ᵖ) with ε̄ᵖ = ln λ − σ/E, within 0.5 %
/// (the brief's bound; source of the expectation: Miehe, Apel & Lambrecht
/// 2002 — the small-strain J2 model on E_log gives the Kirchhoff stress
/// τ = J σ on the uniaxial curve τ = σ_y(ln λ − τ/E), which holds here to
/// Newton's tolerance, 1e-6, the peeq to 1e-7); the section shrinks so that the volume changes only
/// elastically, J = λ μ² = exp((1 − 2ν) τ/E) to 1e-6 (plastic flow is
/// isochoric in E_log) to 1e-8, J − 1 < 0.2 %; the pulling force is σ times the
/// current section μ² A₀. The Green–Lagrange model of the same file is
/// more than 10 % off the curve at ln λ = 0.5 (S = C E with E = (λ² − 1)/2;
/// measured 22 % at ln λ = 0.1), and its run warns on `analysis.strain`.
#[test]
fn log_strain_bar_follows_the_hardening_curve_to_fifty_percent() {
    let (e, nu, sy0, h) = (200e9, 0.3, 250e6, 1e9);
    let curve = |peeq: f64| sy0 + h * peeq;
    for (strain, logarithmic) in [("strain = \"logarithmic\"", true), ("", false)] {
        let model = Model::parse(&log_bar(strain)).unwrap();
        let sol = analysis::run(&model, &Default::default(), &mut analysis::Silent).unwrap();
        assert!(sol.failure.is_none(), "{:?}", sol.failure);
        assert_eq!(sol.steps.len(), 5);
        // the Green–Lagrange run is told of its plastic strain, by key
        let told = sol.warnings.iter().any(|w| w.key == "analysis.strain" && w.message.contains("logarithmic"));
        assert_eq!(told, !logarithmic, "{:?}", sol.warnings);
        for (k, step) in sol.steps.iter().enumerate() {
            let ln_lambda = 0.1 * (k + 1) as f64;
            let fields = step.fields.as_ref().unwrap();
            // the corner node (0.01, L, 0.01): the lateral stretch μ from its u_x
            let bar = &model.mesh.bodies[0];
            let near = |x: [f64; 3]| (x[0] - 0.01).abs() + (x[1] - 0.05).abs() + (x[2] - 0.01).abs() < 1e-12;
            let corner = (0..bar.n_nodes()).find(|&n| near(bar.local_coords(n))).unwrap();
            let mu = 1.0 + fields.u[3 * corner] / 0.01;
            let jac = ln_lambda.exp() * mu * mu;
            let sigma = fields.stresses[0][1];
            let off_curve = (sigma - curve(ln_lambda - sigma / e)).abs() / sigma;
            eprintln!(
                "{strain:>24} ln λ = {ln_lambda:.1}: σ_yy {:.3} MPa, off the curve {off_curve:.2e}, J − 1 = {:.2e}",
                sigma / 1e6,
                jac - 1.0
            );
            if !logarithmic {
                if k == 4 {
                    assert!(off_curve > 0.1, "Green–Lagrange: {off_curve}");
                }
                continue;
            }
            assert!(off_curve < 5e-3, "ln λ = {ln_lambda}: σ {sigma:e} off the curve by {off_curve:e}");
            let tau = jac * sigma;
            let peeq = ln_lambda - tau / e;
            assert!((tau - curve(peeq)).abs() < 1e-6 * tau, "Kirchhoff {tau:e} against {:e}", curve(peeq));
            for (s, p) in fields.stresses.iter().zip(&fields.states) {
                assert!((s[1] - sigma).abs() < 1e-6 * sigma && s[0].abs() < 1e-6 * sigma && s[2].abs() < 1e-6 * sigma);
                assert!((p.peeq - peeq).abs() < 1e-7, "peeq {} against {peeq}", p.peeq);
            }
            assert!((jac - ((1.0 - 2.0 * nu) * tau / e).exp()).abs() < 1e-6 && jac - 1.0 < 2e-3, "J = {jac}");
            let force = step.reactions.iter().find(|r| r.name == "pull").unwrap().force[1];
            assert!(
                (force - sigma * mu * mu * 1e-4).abs() < 1e-5 * force,
                "force {force} against {}",
                sigma * mu * mu * 1e-4
            );
        }
    }
}

/// Newton converges quadratically with the logarithmic strain on the bar
/// in its plastic range: from the state converged at ln λ = 0.4
/// (committed), one full-Newton increment to ln λ = 0.5 (double factors,
/// no reuse) — 10 % more plastic strain in one go. The relative residuals
/// r_k of its iterations must obey r_(k+1) ≤ C r_k² with C ≤ 10 at every
/// pair above round-off, two pairs or more, down to 1e-12 (measured:
/// 0.63, 2.0e-4, 1.9e-11, 1.2e-13, i.e. C = 5e-4 twice). A linearly converging iteration at rate ρ gives
/// r_(k+1)/r_k² = ρ/r_k, beyond 10 once r_k < ρ/10; a tangent without
/// the second-derivative term `T : ∂²E_log/∂E²` or the geometric term
/// converges linearly.
#[test]
fn newton_converges_quadratically_with_the_log_strain() {
    use cufem::solver::newton::{self, NewtonSettings};
    use cufem::solver::stepping::Incremental;
    let text = log_bar("strain = \"logarithmic\"");
    let mut model = Model::parse(&text).unwrap();
    model.solver.reuse.enabled = false;
    model.solver.reuse.single_precision = false;
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    let factor = |l: f64| (l.exp() - 1.0) / (0.5f64.exp() - 1.0);
    for k in 1..=8 {
        s.set_load_factor(factor(0.05 * k as f64));
        assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
        s.commit();
    }
    s.set_load_factor(1.0);
    let tight = NewtonSettings { residual_tolerance: 1e-12, displacement_tolerance: 1e-15, ..Default::default() };
    let report = newton::solve(&mut s, &tight, &Default::default());
    let r = &report.residuals;
    eprintln!("relative residuals {r:?}");
    let mut pairs = 0;
    // the first entry is the residual before the increment's prescribed
    // displacement is applied; below 1e-12 is round-off
    for w in r.windows(2).filter(|w| w[0] > 1e-12 && w[1] > 1e-12) {
        assert!(w[1] < 10.0 * w[0] * w[0], "r_(k+1)/r_k² = {:.3e} in {r:?}", w[1] / (w[0] * w[0]));
        pairs += 1;
    }
    assert!(pairs >= 2 && *r.last().unwrap() < 1e-12, "{r:?}");
}

/// `analysis.strain` is refused with small-strain geometry, by its key and
/// value with the allowed setting; an unknown measure by the reader with
/// the allowed words; `"green_lagrange"` is the default, to the bit.
#[test]
fn strain_measure_is_refused_without_nonlinear_geometry() {
    const SECTION: &str = "[analysis]\ngeometry = \"nonlinear\"\n";
    let text = std::fs::read_to_string(ELASTICA).unwrap();
    assert!(text.contains(SECTION));
    for value in ["logarithmic", "green_lagrange"] {
        let linear = text.replace(SECTION, &format!("[analysis]\nstrain = \"{value}\"\n"));
        let e = Model::parse(&linear).unwrap_err().to_string();
        assert!(e.contains("analysis.strain") && e.contains(value) && e.contains("geometry = \"nonlinear\""), "{e}");
    }
    let e = Model::parse(&text.replace(SECTION, "[analysis]\ngeometry = \"nonlinear\"\nstrain = \"hencky\"\n"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("green_lagrange") && e.contains("logarithmic"), "{e}");
    let explicit =
        Model::parse(&text.replace(SECTION, "[analysis]\ngeometry = \"nonlinear\"\nstrain = \"green_lagrange\"\n"))
            .unwrap();
    let default = Model::parse(&text).unwrap();
    assert_eq!(explicit.kinematics, default.kinematics);
    assert_eq!(default.kinematics, cufem::setup::Kinematics::TotalLagrangian);
}

/// At small strain the logarithmic model is the Green–Lagrange one to
/// O(ε²): the compact bar of the paper's §4.2 (`examples/bending_compact_4L9.toml`,
/// strains ≈ 0.1 %) with `geometry = "nonlinear"` and `strain =
/// "logarithmic"` against the same with the Green–Lagrange strain and
/// against the small-strain run. σ_yy and peeq at the probe and the
/// loading roller's force move by less than 0.5 % (measured: σ_yy +0.05 %
/// from small strain, +0.38 % from Green–Lagrange; peeq −0.15 %, −0.06 %;
/// roller force −0.07 %, 5e-6), far below the 3D–cufem differences the
/// README states for this example (von Mises 1.87 % over the plastic zone,
/// σ_yy 3 % from CalculiX).
#[test]
fn log_strain_is_green_lagrange_at_small_strain_on_the_compact_bar() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/bending_compact_4L9.toml"))
        .unwrap();
    let run = |analysis: &str| {
        let model = Model::parse(&text.replacen("[solver]", &format!("{analysis}\n[solver]"), 1)).unwrap();
        let sol = analysis::run(&model, &Default::default(), &mut analysis::Silent).unwrap();
        assert!(sol.failure.is_none());
        let view = sol.fields(&model);
        let probe = view.sample_probe(&model.probes[0]).unwrap();
        let load = sol.contacts.iter().find(|c| c.name == "load").unwrap().force[2];
        [probe.stress[1], probe.peeq, load]
    };
    let small = run("");
    let gl = run("[analysis]\ngeometry = \"nonlinear\"\n");
    let log = run("[analysis]\ngeometry = \"nonlinear\"\nstrain = \"logarithmic\"\n");
    for (name, other) in [("small strain", small), ("Green–Lagrange", gl)] {
        for (k, q) in ["σ_yy", "peeq", "roller force"].iter().enumerate() {
            let change = (log[k] - other[k]) / other[k];
            eprintln!("{q}: logarithmic {:.6e} against {name} {:.6e}: {:+.3} %", log[k], other[k], 100.0 * change);
            assert!(change.abs() < 5e-3, "{q} against {name}: {change:e}");
        }
    }
}

/// `gauss.vtu` of a large-deformation run gives the reference measures
/// beside the Cauchy stress: on the elastica at P L²/EI = 10 (the beam's
/// axis turned by up to 80°, ν = 0), at every Gauss point of the middle
/// half of the span, where the stress is the bending fibre stress along
/// the turned axis t: the second Piola–Kirchhoff `pk2_yy` equals tr σ =
/// σ_tt (the only non-zero Cauchy component of a slender beam, here
/// rotated away from s_yy) within 2 % of the peak, the Green–Lagrange
/// strain `gl_yy` is pk2_yy/E (Saint Venant–Kirchhoff, uniaxial) to 1e-6
/// of the peak strain — while s_yy itself, the Cauchy component along the
/// reference axis, is less than half of pk2_yy where the axis has turned
/// by more than 45°. A wrong pull-back (a transposed F⁻¹: R σ Rᵀ for Rᵀ σ R)
/// or F taken at another Gauss point than σ fails. (`log_yy` is written
/// beside them; at these strains of 1e-3 it differs from gl_yy by 1e-6,
/// below what this test could tell apart — `kinematics::hencky`'s tests
/// check the measure.)
#[test]
fn gauss_points_give_pk2_and_both_strains_beside_cauchy() {
    let out = std::env::temp_dir().join(format!("cufem_elastica_gauss_{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let model = out.join("elastica.toml");
    let text = std::fs::read_to_string(ELASTICA).unwrap();
    std::fs::write(&model, format!("{text}\n[output]\ngauss_points = true\n")).unwrap();
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", "--quiet", "--force", "--out"])
        .arg(out.join("run"))
        .arg(&model)
        .status()
        .unwrap();
    assert!(status.success());
    let vtu = out.join("run/gauss.vtu");
    let get = |n: &str| common::vtu_array(&vtu, Some(n));
    let points = common::vtu_array(&vtu, None);
    let (sxx, syy, szz, pk2, gl) = (get("s_xx"), get("s_yy"), get("s_zz"), get("pk2_yy"), get("gl_yy"));
    assert_eq!(get("log_yy").len(), pk2.len());
    let peak = pk2.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let strain_peak = gl.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (mut checked, mut turned) = (0, 0);
    for (i, p) in points.chunks(3).enumerate() {
        if !(0.25..=0.75).contains(&p[1]) {
            continue;
        }
        let trace = sxx[i] + syy[i] + szz[i];
        assert!((pk2[i] - trace).abs() < 0.02 * peak, "y = {}: S_yy {} against tr σ {trace}", p[1], pk2[i]);
        assert!((gl[i] - pk2[i] / 200e9).abs() < 1e-6 * strain_peak, "y = {}: E_yy {}", p[1], gl[i]);
        if pk2[i].abs() > 0.2 * peak && syy[i].abs() < 0.5 * pk2[i].abs() {
            turned += 1;
        }
        checked += 1;
    }
    assert!(checked > 100 && turned > 10, "{checked} points checked, {turned} turned past 45°");
    std::fs::remove_dir_all(&out).ok();
}

/// A failed increment is retried once with the elastic predictor before it
/// is cut back (`Incremental::cautious`). That predictor decides only at
/// points on their yield surface with no strain increment, i.e. at the
/// committed state: an attempt started on the secant of the last increment
/// would be repeated to the last digit (every such retry of
/// examples/tube_crush.toml did), so the structure declines it there,
/// with friction as without: a sliding point takes the stick tangent only
/// at the first evaluation of an increment started at the committed state,
/// cautious or not (`contact::assembly`). (An elastic model with nonlinear
/// geometry and no contact starts at the committed state:
/// `Structure::starts_committed`.)
#[test]
fn the_cautious_retry_is_declined_where_it_would_repeat_the_failed_attempt() {
    use cufem::solver::stepping::Incremental;
    let example = |name: &str| {
        let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name);
        Model::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
    };
    for name in ["cantilevers_contact.toml", "cantilevers_contact_friction.toml"] {
        let model = example(name);
        let mut s = analysis::Structure::of_model(&model, None).unwrap();
        common::solve_path(&mut s, &[(0.02, true)]);
        s.set_load_factor(0.04);
        assert!(s.cautious(true), "{name}: at the committed state the retry differs");
        s.cautious(false);
        s.set_load_factor(0.04);
        s.extrapolate(1.0);
        assert!(!s.cautious(true), "{name}: on the secant the retry would repeat the attempt");
    }
}

/// The kernel forms element tangents only where they change
/// (`analysis::Timings::element_tangents_formed`): with nonlinear geometry
/// every element at every evaluation that wants the tangent (all but
/// Newton's expected last ones), while the same cantilever in small strain
/// reuses its cached elastic matrices and forms none; on one thread the
/// kernel's two timed passes lie within the loop's wall time (a tangent
/// formed twice, skipped where needed or timed outside the loop fails it).
#[test]
fn the_element_loop_forms_tangents_only_where_they_change() {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let run = |model: &Model| {
        pool.install(|| analysis::run(model, &Default::default(), &mut analysis::Silent).unwrap()).timings
    };
    let mut model = Model::from_file(Path::new(ELASTICA)).unwrap();
    let elements = model.mesh.bodies.iter().map(|b| b.n_elements()).sum::<usize>();
    let t = run(&model);
    assert!(t.evaluations > 0);
    assert_eq!(t.element_tangents_formed, elements * (t.evaluations - t.residual_only), "{t:?}");
    assert!(t.stress_pass + t.element_tangents <= t.assembly, "{t:?}");
    model.kinematics = cufem::setup::Kinematics::Linear;
    let t = run(&model);
    assert!(t.evaluations > 0);
    assert_eq!(t.element_tangents_formed, 0, "{t:?}");
}

/// Newton's last evaluation of a solve leaves the element tangents out
/// (`Structure::evaluate_residual`, `solver::newton`'s module docs): if a
/// correction follows after all, the structure forms them again first. The
/// elastica loaded to PL²/EI ≈ 2 from its committed state at ≈ 1.6 (one
/// thread; `solver.inertia = "last_factorization"`, with which the commit
/// needs no converged tangent and the structure accepts the skip): the correction after `evaluate_residual` equals the one after
/// `evaluate` to the bit. Without the second evaluation the correction
/// solves with the tangent the residual-only evaluation left — the first
/// correction's, its supports eliminated — and differs (checked).
#[test]
fn a_correction_after_a_residual_only_evaluation_uses_the_present_tangent() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let mut model = Model::from_file(Path::new(ELASTICA)).unwrap();
    model.solver.inertia = Some(cufem::input::InertiaReport::LastFactorization);
    let correction = |residual_only: bool| {
        pool.install(|| {
            let mut s = analysis::Structure::of_model(&model, None).unwrap();
            s.set_load_factor(0.16);
            assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
            s.commit();
            s.set_load_factor(0.2);
            // two corrections in: the tangent of the first is in the system
            s.evaluate().unwrap();
            s.correct().unwrap();
            if residual_only {
                s.evaluate_residual().unwrap();
            } else {
                s.evaluate().unwrap();
            }
            let before = s.displacements().to_vec();
            s.correct().unwrap();
            s.displacements().iter().zip(&before).map(|(a, b)| a - b).collect::<Vec<f64>>()
        })
    };
    let (full, lazy) = (correction(false), correction(true));
    assert!(full.iter().any(|&v| v != 0.0));
    assert_eq!(full, lazy);
}

/// bench/channel_twist.toml made coarser (one L9 along each flange, two
/// along the web, 6 uniform B4 along the axis: 2,223 DOF; the paper's
/// element): the channel cantilever that an eccentric dead tip load twists
/// past 90°.
fn coarse_channel() -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../bench/channel_twist.toml")).unwrap();
    let coarse = text
        .replace("formulation = \"assumed_shear\"\n", "")
        .replace("along_flange = 3, along_web = 6", "along_flange = 1, along_web = 2")
        .replace(
            "axis = { element = \"B4\", from = 0.0, to = 1.0, elements = 12, ratio = 10.0 }",
            "axis = { element = \"B4\", from = 0.0, to = 1.0, elements = 6 }",
        );
    for (kept, what) in [("\"L9\", origin", "L9"), ("along_flange = 1,", "section"), ("elements = 6 }", "axis")] {
        assert!(!coarse.contains("formulation"), "bench/channel_twist.toml: the coarse channel's formulation was kept");
        assert!(coarse.contains(kept), "bench/channel_twist.toml: the coarse channel's {what} was not set");
    }
    coarse
}

/// Issue 50, check 1: every increment of an open-section cantilever twisted
/// past 90° converges in at most 6 corrections, and its last three
/// residuals fall, at least quadratically: `r_(k+1) ≤ C r_k²` with
/// `C = 1e3` (measured ≤ `1.1e2`, with the run's solves — single-precision
/// factors refined by PCG to the forcing term — and with exact ones; the
/// last residual often sits at the round-off floor `≈ 1.5e-10`, which
/// bounds the ratio from below). The flanges' rotation is read from the two
/// tip probes (their chord, `0.097` m along z unloaded): past 90°
/// (`111°`). 75 corrections in all. The same holds with the assumed
/// in-section shear of the bench file (its tangent's own terms,
/// `elements::assumed_large`).
///
/// Each of the three choices that make it so fails it when undone
/// (measured): the geometric stiffness of the stress of the displacements
/// instead of the stress linearized along the last step (`elements`, "The
/// stress of the geometric stiffness"): 139 corrections, 7 in the first
/// increment, its residual rising after good iterates; solves stopped at the
/// default forcing term `0.1` instead of `1e-3` (`evaluation.rs`,
/// `LARGE_ROTATION_FORCING`): 5 cutbacks; increments started on the secant
/// of the last instead of the committed state (`structure/stepping.rs`): 93
/// corrections, 5 an increment, the residual rising in the middle. With
/// none of the three (the code before issue 50's fix): 125.
#[test]
fn a_channel_twisted_past_ninety_degrees_converges_quadratically() {
    const C: f64 = 1e3;
    let text = coarse_channel();
    let exact = text.replacen("[solver]\n", "[solver]\nreuse_factorization = false\n", 1);
    let assumed = text.replacen("\nsection = ", "\nformulation = \"assumed_shear\"\nsection = ", 1);
    assert!(assumed.contains("assumed_shear"));
    for (text, name) in [(&text, "run's solves"), (&exact, "exact solves"), (&assumed, "assumed shear")] {
        let model = Model::parse(text).unwrap();
        let sol = analysis::run(&model, &Default::default(), &mut cufem::Silent).unwrap();
        assert!(
            sol.failure.is_none() && sol.cutbacks.is_empty(),
            "{name}: {:?}, {} cutbacks",
            sol.failure,
            sol.cutbacks.len()
        );
        let total: usize = sol.increments.iter().map(|i| i.newton.iterations).sum();
        eprintln!("{name}: {} increments, {total} corrections", sol.increments.len());
        let mut worst: f64 = 0.0;
        for inc in &sol.increments {
            let r = &inc.newton.residuals;
            eprintln!("{name}: increment {} residuals {}", inc.index, show(r));
            assert!(inc.newton.iterations <= 6, "{name}: increment {}: {}", inc.index, show(r));
            let [a, b, last] = r[r.len() - 3..] else { unreachable!() };
            assert!(last < b && b < a, "{name}: increment {}: the last three do not fall: {}", inc.index, show(r));
            worst = worst.max(b / (a * a)).max(last / (b * b));
            assert!(
                b <= C * a * a && last <= C * b * b,
                "{name}: increment {}: slower than quadratic: {}",
                inc.index,
                show(r)
            );
        }
        eprintln!("{name}: largest r_(k+1)/r_k² of the last three: {worst:.2e}");
        assert!(total <= 100, "{name}: {total} corrections");
        // the flanges' chord, top tip less bottom tip, turned past 90° about the axis
        let probe = |n: &str| model.probes.iter().position(|p| p.name == n).unwrap();
        let (top, bottom) = (probe("top_flange_tip"), probe("bottom_flange_tip"));
        let end = &sol.history.last().unwrap().probes;
        let dx = end[top][0] - end[bottom][0];
        let dz = 0.097 + end[top][2] - end[bottom][2];
        let twist = (-dx).atan2(dz).abs().to_degrees();
        eprintln!("{name}: twist {twist:.1}°");
        assert!(twist > 100.0, "{name}: twisted {twist:.1}°");
    }
}

/// Residuals as `1.0e-3` each.
fn show(r: &[f64]) -> String {
    r.iter().map(|v| format!("{v:.1e}")).collect::<Vec<_>>().join(" ")
}
