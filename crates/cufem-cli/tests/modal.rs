//! Free vibration (`analysis.type = "modal"`) against beam theory: a solid
//! rectangular cantilever's bending, torsional and axial frequencies, and
//! the softening of a compressed column by its pre-stress.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::f64::consts::PI;

const E: f64 = 210e9;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;

/// A steel cantilever `b × h × L` (x × z × y), clamped at y = 0: 20 B4
/// along the axis, 2 × 4 L9 over the section.
fn cantilever(b: f64, h: f64, length: f64, modes: usize) -> String {
    format!(
        r#"
        [analysis]
        type = "modal"
        modes = {modes}

        [[materials]]
        name = "steel"
        young_modulus = {E}
        poisson_ratio = {NU}
        density = {RHO}

        [[bodies]]
        name = "beam"
        material = "steel"
        section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = {b}, elements = 2 }}, z = {{ from = 0.0, to = {h}, elements = 4 }} }}
        axis = {{ element = "B4", from = 0.0, to = {length}, elements = 20 }}

        [[constraints]]
        name = "root"
        body = "beam"
        where = {{ y = 0.0 }}
        fix = ["x", "y", "z"]
        "#
    )
}

/// The natural frequencies (Hz) of a clamped–free Timoshenko beam bending
/// with thickness `t` in the plane of bending and width `w`: the
/// frequency equation found by shooting. The state `(v, v', ψ, ψ')` of
///
/// ```text
/// κ G A (v'' − ψ') + ρ A ω² v = 0,   E I ψ'' + κ G A (v' − ψ) + ρ I ω² ψ = 0
/// ```
///
/// is integrated from the clamped end (`v = ψ = 0`) with RK4 for the two
/// free initial slopes, and `ω` is a root of the 2 × 2 determinant of the
/// free-end conditions (moment `ψ' = 0`, shear `v' − ψ = 0`), bracketed by
/// a scan and bisected. Shear coefficient of Cowper (1966) for a
/// rectangle, `κ = 10 (1 + ν) / (12 + 11 ν)`.
fn timoshenko(t: f64, w: f64, length: f64, count: usize) -> Vec<f64> {
    let (g, area, inertia) = (E / (2.0 * (1.0 + NU)), t * w, w * t.powi(3) / 12.0);
    let kappa = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU);
    let det = |om: f64| {
        let rhs = |y: [f64; 4]| {
            let [v, vp, p, pp] = y;
            let vpp = pp - RHO * om * om * v / (kappa * g);
            let ppp = -(kappa * g * area * (vp - p) + RHO * inertia * om * om * p) / (E * inertia);
            [vp, vpp, pp, ppp]
        };
        let shoot = |mut y: [f64; 4]| {
            let n = 4000;
            let dx = length / n as f64;
            let add = |y: [f64; 4], k: [f64; 4], s: f64| std::array::from_fn::<f64, 4, _>(|i| y[i] + s * k[i]);
            for _ in 0..n {
                let k1 = rhs(y);
                let k2 = rhs(add(y, k1, dx / 2.0));
                let k3 = rhs(add(y, k2, dx / 2.0));
                let k4 = rhs(add(y, k3, dx));
                y = std::array::from_fn(|i| y[i] + dx / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
            }
            [y[3], y[1] - y[2]]
        };
        let (a, b) = (shoot([0.0, 1.0, 0.0, 0.0]), shoot([0.0, 0.0, 0.0, 1.0]));
        a[0] * b[1] - a[1] * b[0]
    };
    let euler = (E * inertia / (RHO * area)).sqrt() / (length * length);
    let (mut roots, mut om, step) = (Vec::new(), 0.5 * euler, 0.05 * euler);
    let mut d0 = det(om);
    while roots.len() < count {
        let d1 = det(om + step);
        if d0 * d1 < 0.0 {
            let (mut lo, mut hi, mut dlo) = (om, om + step, d0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let dm = det(mid);
                if dm * dlo < 0.0 {
                    hi = mid;
                } else {
                    (lo, dlo) = (mid, dm);
                }
            }
            roots.push(0.5 * (lo + hi) / (2.0 * PI));
        }
        (om, d0) = (om + step, d1);
    }
    roots
}

fn close(got: f64, want: f64, tol: f64, what: &str) {
    let rel = (got - want) / want;
    println!("{what}: {got:.4} Hz against {want:.4} Hz ({:+.3} %)", 100.0 * rel);
    assert!(rel.abs() < tol, "{what}: {got} Hz against {want} Hz ({:+.3} %)", 100.0 * rel);
}

/// A 2 m steel cantilever of 50 × 100 mm (L/h = 20). Bending in x and in
/// z: the first three frequencies of each against Timoshenko beam theory
/// (above); torsion against Saint-Venant's `f = (1/4L) √(G J / ρ I_p)`
/// with `J` of the rectangle from its series (Timoshenko & Goodier,
/// *Theory of Elasticity*, §109) and `I_p = (b h³ + h b³)/12`; axial
/// against the rod's `f = √(E/ρ) / 4L`. Issue 27 asks for 1 %; measured
/// +0.23 … +0.34 % in bending, +0.80 % in torsion (the clamp restrains
/// warping, which Saint-Venant's theory leaves free) and +0.14 % axially.
/// Modes are told apart by their effective masses: bending in x or z
/// moves mass in x or z, the axial mode in y, torsion in none.
#[test]
fn a_solid_cantilever_vibrates_at_the_frequencies_of_beam_theory() {
    let (b, h, length) = (0.05, 0.1, 2.0);
    let sol = common::run(&cantilever(b, h, length, 12));
    let modal = sol.modal.as_ref().unwrap();
    let share = |i: usize, k: usize| modal.effective_masses[i][k] / modal.free_mass[k];
    let family = |k: usize| -> Vec<f64> {
        (0..modal.frequencies.len()).filter(|&i| share(i, k) > 0.01).map(|i| modal.frequencies[i]).collect()
    };
    let (bend_x, axial, bend_z) = (family(0), family(1), family(2));
    // effective masses: the first bending mode of a uniform cantilever
    // moves 61.3 % of its mass (Euler–Bernoulli, Chopra §16.6; measured
    // 61.75 %), the axial one 8/π² = 81.1 % (measured 81.6 %); and no
    // direction's sum over the modes exceeds the free mass
    let first_share = share(0, 0);
    assert!((first_share - 0.613).abs() < 0.01, "first bending mode moves {first_share} of the mass");
    let axial_mode = (0..modal.frequencies.len()).find(|&i| share(i, 1) > 0.5).unwrap();
    assert!((share(axial_mode, 1) - 8.0 / (PI * PI)).abs() < 0.01, "axial mode moves {}", share(axial_mode, 1));
    for k in 0..3 {
        let sum: f64 = (0..modal.frequencies.len()).map(|i| share(i, k)).sum();
        assert!(sum <= 1.0 + 1e-9, "direction {k}: {sum}");
    }
    for (i, (got, want)) in bend_x.iter().zip(timoshenko(b, h, length, 3)).enumerate() {
        close(*got, want, 0.01, &format!("bending in x, mode {}", i + 1));
    }
    for (i, (got, want)) in bend_z.iter().zip(timoshenko(h, b, length, 3)).enumerate() {
        close(*got, want, 0.01, &format!("bending in z, mode {}", i + 1));
    }
    assert!(bend_x.len() >= 3 && bend_z.len() >= 3, "{bend_x:?} {bend_z:?}");
    close(axial[0], (E / RHO).sqrt() / (4.0 * length), 0.01, "axial");
    let torsion = (0..modal.frequencies.len())
        .find(|&i| (0..3).all(|k| share(i, k) < 1e-6))
        .map(|i| modal.frequencies[i])
        .expect("a mode that moves no mass: torsion");
    let g = E / (2.0 * (1.0 + NU));
    let series: f64 =
        (0..100).map(|k| 2 * k + 1).map(|n| (n as f64 * PI * h / (2.0 * b)).tanh() / (n as f64).powi(5)).sum();
    let j = h * b.powi(3) / 3.0 * (1.0 - 192.0 / PI.powi(5) * (b / h) * series);
    let ip = (b * h.powi(3) + h * b.powi(3)) / 12.0;
    close(torsion, (g * j / (RHO * ip)).sqrt() / (4.0 * length), 0.01, "torsion");
}

/// A pinned steel column, 1 m, 20 × 40 mm (pins: u_x = u_z = 0 over both
/// end faces, u_y = 0 on the line x = 0 of the base), compressed by `load`
/// (N) at its top, with the analysis block `analysis`.
fn pinned_column(analysis: &str, load: f64) -> String {
    format!(
        r#"
        [analysis]
        {analysis}

        [[materials]]
        name = "steel"
        young_modulus = 200e9
        poisson_ratio = 0.3
        density = {RHO}

        [[bodies]]
        name = "column"
        material = "steel"
        section = {{ shape = "rectangle", element = "L9", x = {{ from = -0.01, to = 0.01, elements = 1 }}, z = {{ from = -0.02, to = 0.02, elements = 2 }} }}
        axis = {{ element = "B4", from = 0.0, to = 1.0, elements = 10 }}

        [[constraints]]
        name = "base"
        body = "column"
        where = {{ y = 0.0 }}
        fix = ["x", "z"]

        [[constraints]]
        name = "top"
        body = "column"
        where = {{ y = 1.0 }}
        fix = ["x", "z"]

        [[constraints]]
        name = "axial"
        body = "column"
        where = {{ y = 0.0, x = 0.0 }}
        fix = ["y"]

        [[loads]]
        name = "top"
        body = "column"
        where = {{ y = 1.0 }}
        total_force = [0.0, {}, 0.0]
        "#,
        -load
    )
}

/// Pre-stress: a pinned column's buckling mode is its first vibration mode
/// (a half sine in beam theory), so under a compressive force `P` its
/// frequency falls as `f(P)² = f(0)² (1 − P/P_cr)` (Timoshenko, Young &
/// Weaver, *Vibration Problems in Engineering*, 4th ed., §5.13). `P_cr`
/// from the linear buckling analysis of the same model; at `P = P_cr / 2`
/// the modal analysis about the static state with nonlinear geometry gives
/// `f/f₀ = √½` (measured within 4e-5). Without the geometric term — small
/// strain — the load leaves the frequency unchanged.
#[test]
fn compression_lowers_the_frequency_as_it_approaches_buckling() {
    let buckling = common::run(&pinned_column("type = \"buckling\"\nmodes = 1", 1.0));
    let p_cr = buckling.buckling.unwrap().factors[0];
    // beam theory: π² E I / L² less a little shear flexibility
    let euler = PI * PI * 200e9 * (0.04 * 0.02f64.powi(3) / 12.0);
    assert!((p_cr / euler - 0.99).abs() < 0.01, "P_cr {p_cr} N against Euler's {euler} N");
    let first = |analysis: &str, load: f64| {
        let sol = common::run(&pinned_column(analysis, load));
        let m = sol.modal.unwrap();
        // the first bending mode in x
        assert!(m.effective_masses[0][0] > 0.5 * m.free_mass[0], "{:?}", m.effective_masses);
        m.frequencies[0]
    };
    let f0 = first("type = \"modal\"\nmodes = 2", 0.0);
    let f = first("type = \"modal\"\nmodes = 2\ngeometry = \"nonlinear\"", 0.5 * p_cr);
    println!("f0 = {f0} Hz, f(P_cr/2) = {f} Hz, ratio {} against {}", f / f0, 0.5f64.sqrt());
    assert!((f / f0 - 0.5f64.sqrt()).abs() < 1e-3, "f/f0 = {} against √½", f / f0);
    let linear = first("type = \"modal\"\nmodes = 2", 0.5 * p_cr);
    assert!((linear / f0 - 1.0).abs() < 1e-9, "small strain: {linear} Hz against {f0} Hz");
}

/// `examples/cantilever_modes.toml` through the CLI: the channel's bending
/// mode in its plane of symmetry (the first mode moving mass in x) against
/// Euler–Bernoulli, `f = (1.8751² / 2π L²) √(E I / ρ A)` with the
/// channel's `A` and `I` about the centroidal z axis summed from its three
/// rectangles (web 2 × 100 mm at x ∈ [0, 2] mm, flanges 48 × 2 mm at
/// x ∈ [2, 50] mm): 45.07 Hz; measured 44.93 Hz (−0.3 %: shear
/// flexibility); and every mode written as a VTU named in summary.json.
#[test]
fn the_channel_example_bends_in_its_plane_of_symmetry_as_a_beam() {
    let model =
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/cantilever_modes.toml");
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("example_cantilever_modes");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    let modal = &summary["modal"];
    let freq: Vec<f64> = modal["frequencies_hz"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let eff: Vec<f64> = modal["effective_masses"].as_array().unwrap().iter().map(|v| v[0].as_f64().unwrap()).collect();
    let free_x = modal["free_mass"][0].as_f64().unwrap();
    let first_x = (0..freq.len()).find(|&i| eff[i] > 0.3 * free_x).unwrap();
    // the rectangles (x from, x to, z extent)
    let rects = [(0.0, 0.002, 0.1), (0.002, 0.05, 0.002), (0.002, 0.05, 0.002)];
    let area: f64 = rects.iter().map(|(a, b, h)| (b - a) * h).sum();
    let xc = rects.iter().map(|(a, b, h)| (b - a) * h * 0.5 * (a + b)).sum::<f64>() / area;
    let inertia: f64 =
        rects.iter().map(|(a, b, h)| h * (b - a).powi(3) / 12.0 + (b - a) * h * (0.5 * (a + b) - xc).powi(2)).sum();
    let euler = 1.875_104_068_7f64.powi(2) / (2.0 * PI) * (70e9 * inertia / (2700.0 * area)).sqrt();
    close(freq[first_x], euler, 0.01, "channel, bending in its plane of symmetry");
    for name in modal["modes"].as_array().unwrap() {
        assert!(out.join(name.as_str().unwrap()).exists(), "{name}");
    }
    assert_eq!(modal["modes"].as_array().unwrap().len(), 8);
    // the unloaded structure has no static error to estimate (0 / 0): the run
    // says so instead of printing "estimated error 0.00 %" (a new user's review)
    let printed = String::from_utf8_lossy(&run.stdout);
    assert!(printed.contains("estimated error of the end state not given: it carries no stress"), "{printed}");
    assert!(!printed.contains("estimated error 0.00 %") && printed.contains("freq. err. [%]"), "{printed}");
    // modes.csv: the same table, a row per mode, columns in x, y, z order
    let csv = common::csv_columns(&out.join("modes.csv"));
    assert_eq!(csv["mode"], (1..=8).map(f64::from).collect::<Vec<_>>());
    for (k, f) in freq.iter().enumerate() {
        assert!((csv["frequency_hz"][k] - f).abs() < 1e-6 * f, "{csv:?}");
        for (axis, i) in [("x", 0), ("y", 1), ("z", 2)] {
            let e = modal["effective_masses"][k][i].as_f64().unwrap();
            assert!((csv[&format!("effective_mass_{axis}")][k] - e).abs() <= 1e-6 * e, "{axis}: {csv:?}");
        }
        // each mode's estimated errors (src/post/mode_error.rs), the same in both
        for (json, column) in [("frequency_errors", "frequency_error"), ("mode_errors", "mode_error")] {
            let e = modal[json][k].as_f64().unwrap();
            assert!(e > 0.0 && (csv[column][k] - e).abs() <= 1e-6 * e, "{json}: {e}, {csv:?}");
        }
    }
    // the memory estimate, eigensolver included, against the measured peak:
    // the band of every example (crates/cufem-cli/tests/examples.rs); measured 1.19
    let estimated = summary["memory"]["estimated_bytes"].as_f64().unwrap();
    let peak = summary["memory"]["peak_bytes"].as_f64().unwrap();
    assert!((0.9..1.3).contains(&(estimated / peak)), "estimate {estimated:e} B, peak {peak:e} B");
}

/// What a modal analysis cannot take is refused by its key.
#[test]
fn modal_refuses_what_it_cannot_analyse() {
    let text = std::fs::read_to_string(
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/cantilever_modes.toml"),
    )
    .unwrap();
    let cases = [
        (text.replace("density = 2700.0\n", ""), "materials[0].density = (missing)"),
        (text.replace("density = 2700.0", "density = -1.0"), "materials[0].density = -1"),
        (text.replace("modes = 8", "modes = 0"), "analysis.modes = 0"),
        (text.replace("modes = 8", "modes = 8\nmass = \"diagonal\""), "diagonal"),
        (text.replace("type = \"modal\"\nmodes = 8", "mass = \"lumped\""), "analysis.mass"),
    ];
    for (model, key) in cases {
        match cufem::setup::Model::parse(&model) {
            Err(e) => assert!(e.to_string().contains(key), "{key}: {e}"),
            Ok(_) => panic!("{key}: accepted"),
        }
    }
}

/// The lumped mass converges to the frequencies of the consistent one:
/// on 20 B4 the first four agree within 1e-4 (measured 3e-7), on 2 B4 they
/// differ (the third by 1.5 %), so the key takes effect; the lumped mass is
/// accepted (positive) on these L9 × B4 elements.
#[test]
fn the_lumped_mass_converges_to_the_frequencies_of_the_consistent_one() {
    let pair = |text: String| {
        let consistent = common::run(&text).modal.unwrap().frequencies;
        let lumped = common::run(&text.replace("modes = 4", "modes = 4\nmass = \"lumped\"")).modal.unwrap().frequencies;
        consistent.iter().zip(&lumped).map(|(a, b)| b / a - 1.0).collect::<Vec<f64>>()
    };
    let fine = pair(cantilever(0.05, 0.1, 2.0, 4));
    let coarse = pair(cantilever(0.05, 0.1, 2.0, 4).replace("elements = 20", "elements = 2"));
    println!("lumped against consistent: 20 B4 {fine:?}, 2 B4 {coarse:?}");
    assert!(fine.iter().all(|d| d.abs() < 1e-4), "{fine:?}");
    assert!(coarse[2].abs() > 5e-3, "{coarse:?}");
}

/// Tension stiffens: the same column pulled by a prescribed displacement
/// of the line x = 0 of its top face, to an axial force `N` (its
/// reaction), vibrates at
/// `f = f₀ √(1 + N/P_cr)` (the relation above with `P = −N`). The
/// prescribed DOFs stay fixed in the vibration (no mass, no coupling):
/// left free in the eigenproblem they would add modes and shift this one.
#[test]
fn tension_from_a_prescribed_displacement_raises_the_frequency() {
    let p_cr = common::run(&pinned_column("type = \"buckling\"\nmodes = 1", 1.0)).buckling.unwrap().factors[0];
    let first = |text: String| common::run(&text).modal.unwrap().frequencies[0];
    let f0 = first(pinned_column("type = \"modal\"\nmodes = 2", 0.0));
    // N ≈ P_cr / 2 for E A = 1.6e8 N
    let delta = 0.5 * p_cr / 1.6e8;
    // pulled on the line x = 0 of the top face (as the base is held), so
    // that the end stays free to rotate: the buckling model's supports; the
    // top face's u_x prescribed too (1 nm of sway), so that the pin itself
    // is a prescribed DOF of the vibration
    let text = pinned_column("type = \"modal\"\nmodes = 2\ngeometry = \"nonlinear\"", 0.0).replacen(
        "where = { y = 1.0 }\n        fix = [\"x\", \"z\"]",
        "where = { y = 1.0 }\n        fix = [\"z\"]\n        displacement = { x = 1e-9 }",
        1,
    ) + &format!(
        "[[constraints]]\nname = \"pull\"\nbody = \"column\"\nwhere = {{ y = 1.0, x = 0.0 }}\nfix = []\n\
             displacement = {{ y = {delta} }}\n"
    );
    let sol = common::run(&text);
    let n = sol.reaction("pull").unwrap().force[1];
    let f = sol.modal.unwrap().frequencies[0];
    let want = f0 * (1.0 + n / p_cr).sqrt();
    println!("N = {n} N (P_cr {p_cr} N): f = {f} Hz against {want} Hz");
    assert!(n > 0.4 * p_cr && n < 0.6 * p_cr, "N = {n}");
    assert!((f / want - 1.0).abs() < 1e-3, "f = {f} Hz against {want} Hz");
}
