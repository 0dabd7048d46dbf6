//! Composite and layered structures (issue 28): the layer-wise laminate
//! against independent oracles — Pagano's exact 3D elasticity solution of
//! cylindrical bending (tests/common/pagano.rs, a state-space transfer
//! matrix per ply, checked in tests/oracles_selfcheck.rs) and classical
//! laminate theory for first-ply failure (tests/common/clt.rs).

#[path = "../../../tests/common/clt.rs"]
mod clt;
#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "../../../tests/common/pagano.rs"]
mod pagano;

use std::path::{Path, PathBuf};

use serde_json::Value;

/// Runs `examples/<name>.toml` (or a variant's text) through the CLI; the
/// output folder and the summary.
fn run_cli(name: &str, text: Option<&str>) -> (PathBuf, Value) {
    let dir = common::scratch_dir("composites", name);
    let model = match text {
        Some(t) => {
            let p = dir.join(format!("{name}.toml"));
            std::fs::write(&p, t).unwrap();
            p
        }
        None => Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(format!("{name}.toml")),
    };
    let out = dir.join("out");
    let run = common::cufem()
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], true, "{name}");
    (out, summary)
}

/// Pagano's material (E1/E2 = 25, G12 = G13 = 0.5 E2, G23 = 0.2 E2, ν = 0.25,
/// E2 = 1 GPa), one ply of `t` at `angle` (0: fibre along the span y).
fn pagano_ply(t: f64, angle: f64) -> pagano::Ply {
    pagano::Ply::pagano(t, angle, 1e9)
}

/// The largest difference between a through-thickness line of cufem's
/// `column` and the exact `exact(z)`, relative to the exact's largest
/// magnitude on the line; with the exact's largest magnitude.
fn line_difference(out: &Path, line: &str, column: &str, exact: impl Fn(f64) -> f64) -> (f64, f64) {
    let cols = common::csv_columns(&out.join(format!("line_{line}.csv")));
    let (z, v) = (&cols["z"], &cols[column]);
    let peak = z.iter().map(|&z| exact(z).abs()).fold(0.0, f64::max);
    let worst = z.iter().zip(v).map(|(&z, &v)| (v - exact(z)).abs()).fold(0.0, f64::max);
    (worst / peak, peak)
}

/// Pagano's [0/90/0] at S = L/h (h = 10 mm, q0 = 100 kPa): mid-span
/// deflection, σ_yy through the thickness at mid-span and τ_yz at the
/// support, each within 1 % of the exact solution (issue 28).
fn pagano_case(name: &str, s: f64) {
    let (h, q0) = (0.01, 1e5);
    let span = s * h;
    let t = h / 3.0;
    let exact = pagano::Pagano::new(&[pagano_ply(t, 0.0), pagano_ply(t, 90.0), pagano_ply(t, 0.0)], span, q0);
    let (out, summary) = run_cli(name, None);
    let probe = summary["probes"].as_array().unwrap().iter().find(|p| p["name"] == "mid_span_centre").unwrap();
    let w = probe["u"][2].as_f64().unwrap();
    let w_exact = exact.displacement(0.5 * span, 0.0)[1];
    let dw = (w - w_exact) / w_exact;
    // the normalized deflection 100 E2 w / (q0 h S⁴) for the record
    eprintln!(
        "{name}: w̄ = {:.4} (exact {:.4}), difference {:+.3} %",
        -100.0 * 1e9 * w / (q0 * h * s.powi(4)),
        -100.0 * 1e9 * w_exact / (q0 * h * s.powi(4)),
        100.0 * dw
    );
    assert!(dw.abs() < 0.01, "{name}: w {w:e} against {w_exact:e}");
    let (d_syy, peak) = line_difference(&out, "through_mid_span", "s_yy", |z| exact.stress(0.5 * span, z)[0]);
    eprintln!("{name}: σ_yy at mid-span within {:.3} % of its peak {peak:e} Pa", 100.0 * d_syy);
    assert!(d_syy < 0.01, "{name}: σ_yy {d_syy}");
    let (d_tau, peak) = line_difference(&out, "through_support", "s_yz", |z| exact.stress(0.0, z)[2]);
    eprintln!("{name}: τ_yz at the support within {:.3} % of its peak {peak:e} Pa", 100.0 * d_tau);
    assert!(d_tau < 0.01, "{name}: τ_yz {d_tau}");
}

#[test]
fn pagano_cylindrical_bending_thick() {
    pagano_case("pagano_s4", 4.0);
}

#[test]
fn pagano_cylindrical_bending_thin() {
    pagano_case("pagano_s50", 50.0);
}

/// The interlaminar criterion (`post::failure`, Brewer & Lagace's
/// quadratic delamination onset) on Pagano's [0/90/0] at S = 4
/// (examples/pagano_s4.toml with strengths): the pressure leaves the
/// interfaces in compression or unloaded, so its largest index is
/// `(τ_yz / S)²` at a support, on a 0/90 interface, with `τ_yz = τ13` and
/// S13 from the 0° ply's side, `τ_yz = τ23` and S23 from the 90° ply's —
/// each side with its own strengths (the 0° plies' S13 = 1 MPa, S23 =
/// 3 MPa; the 90° ply's S13 = 2 MPa, S23 = 2.5 MPa: the 0° side governs).
/// Against Pagano's exact τ_yz at the supports' interfaces: the index within
/// 2 % and at an interface, the first-failure load factor `1/√index`
/// within 1 %. The same laminate with every ply at 0° (one material and
/// orientation) is bonded at its ply boundaries too: its index there
/// within 2 % of Pagano's [0/0/0]. Measured `+0.07 %`. Mutations: S13 and S23 swapped in the criterion gives the
/// 90° side's `(τ/2 MPa)²`, `−75 %`; the criterion at every grid point,
/// not only the interfaces', `+18.6 %` off an interface (the outer plies'
/// shear against S13).
#[test]
fn the_interlaminar_index_follows_pagano_at_the_interfaces() {
    let (h, span, q0) = (0.01, 0.04, 1e5);
    let t = h / 3.0;
    let exact = pagano::Pagano::new(&[pagano_ply(t, 0.0), pagano_ply(t, 90.0), pagano_ply(t, 0.0)], span, q0);
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/pagano_s4.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let elastic = "orthotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }";
    let middle = "material = \"ply\", angle = 90.0,";
    assert!(text.contains(elastic) && text.contains(middle));
    let strong = "xt = 1e9, xc = 1e9, yt = 1e8, yc = 1e8";
    let with = text.replace(
        elastic,
        &format!(
            "{elastic}\nstrengths = {{ {strong}, s12 = 1e6, s23 = 3e6 }}\n\n[[materials]]\nname = \"core\"\n{elastic}\nstrengths = {{ {strong}, s12 = 2e6, s13 = 2e6, s23 = 2.5e6 }}"
        ),
    );
    let (_, summary) =
        run_cli("interlaminar_pagano", Some(&with.replace(middle, "material = \"core\", angle = 90.0,")));
    let entry = &summary["ply_failure"]["interlaminar"];
    let index = entry["largest_index"].as_f64().unwrap();
    let at: Vec<f64> = entry["largest_at"]["point"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    // the exact: τ_yz at y = 0 on each interface, against the 0° side's S13
    let z_i = [-h / 6.0, h / 6.0];
    let (z_max, tau) =
        z_i.iter().map(|&z| (z, exact.stress(0.0, z)[2].abs())).fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    let expected = (tau / 1e6).powi(2);
    eprintln!(
        "interlaminar: largest index {index:.5e} at [{:.4e}, {:.4e}, {:.4e}] m, Pagano's {expected:.5e} at z = {z_max:.4e} m: {:+.2} %",
        at[0],
        at[1],
        at[2],
        100.0 * (index / expected - 1.0)
    );
    let d = 100.0 * (index / expected - 1.0);
    common::figure(
        "composites.interlaminar_pagano",
        d,
        "%",
        "within 2 % of Pagano's (τ_yz/S13)² at the supports' 0/90 interface",
    );
    assert!(d.abs() < 2.0, "index {index:e} against {expected:e}");
    assert!(z_i.iter().any(|z| (at[2] - z).abs() < 1e-9), "at z = {} m, not on an interface", at[2]);
    assert!(at[1].min(span - at[1]) < 1e-9, "at y = {} m, not at a support", at[1]);
    let factor = entry["first_failure_load_factor"].as_f64().unwrap();
    assert!((factor * expected.sqrt() - 1.0).abs() < 0.01, "first failure at λ = {factor}");
    // an elastic static run's first failure has its place (null only with its factor)
    assert_eq!(entry["first_failure_at"]["point"], entry["largest_at"]["point"]);
    // one material and orientation throughout: three plies still, bonded
    // at their two boundaries (as a [0/90]s's middle 90° plies; the index
    // was evaluated between two materials only and gave no entry), their
    // index Pagano's [0/0/0] (τ_yz/S13)² there
    let (_, single) = run_cli("interlaminar_single", Some(&with.replace(middle, "material = \"ply\", angle = 0.0,")));
    let entry = &single["ply_failure"]["interlaminar"];
    let index = entry["largest_index"].as_f64().unwrap_or_else(|| panic!("no interlaminar entry: {single}"));
    let same = pagano::Pagano::new(&[pagano_ply(t, 0.0), pagano_ply(t, 0.0), pagano_ply(t, 0.0)], span, q0);
    let tau = z_i.iter().map(|&z| same.stress(0.0, z)[2].abs()).fold(0.0, f64::max);
    let expected = (tau / 1e6).powi(2);
    let d = 100.0 * (index / expected - 1.0);
    eprintln!("interlaminar, one ply kind: largest index {index:.5e}, Pagano's [0/0/0] {expected:.5e}: {d:+.2} %");
    common::figure(
        "composites.interlaminar_pagano_one_kind",
        d,
        "%",
        "within 2 % of Pagano's [0/0/0] (τ_yz/S13)² at the supports' ply boundaries",
    );
    assert!(d.abs() < 2.0, "index {index:e} against {expected:e}");
    let at = &entry["largest_at"]["point"];
    assert!(z_i.iter().any(|z| (at[2].as_f64().unwrap() - z).abs() < 1e-9), "at {at}, not on a ply boundary");
}

/// A gmsh 2.2 file of L16 quadrilaterals (gmsh type 36) over the
/// rectangle `x0..x1` × `z0..z1` (gmsh's x, y: the section's x, z): `cuts`
/// are the x of the boundaries between physical groups `ply1`, `ply2`, …,
/// `per` elements across each group, one element along z; the whole turned
/// by `turn` radians about the beam axis (x towards z).
fn stacked_along_x(cuts: &[f64], per: usize, z: [f64; 2], turn: f64) -> String {
    let n_el = per * (cuts.len() - 1);
    let (ni, nj) = (3 * n_el + 1, 4);
    let xs: Vec<f64> = (0..ni)
        .map(|i| {
            let (e, k) = ((i / 3).min(n_el - 1), i - 3 * (i / 3).min(n_el - 1));
            let (g, m) = (e / per, e % per);
            let w = (cuts[g + 1] - cuts[g]) / per as f64;
            cuts[g] + w * (m as f64 + k as f64 / 3.0)
        })
        .collect();
    let id = |i: usize, j: usize| j * ni + i + 1;
    let mut text = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    text += &format!("{}\n", cuts.len() - 1);
    for g in 1..cuts.len() {
        text += &format!("2 {g} \"ply{g}\"\n");
    }
    text += &format!("$EndPhysicalNames\n$Nodes\n{}\n", ni * nj);
    for j in 0..nj {
        for (i, x) in xs.iter().enumerate() {
            let zj = z[0] + (z[1] - z[0]) * j as f64 / 3.0;
            let (c, s) = (turn.cos(), turn.sin());
            text += &format!("{} {:e} {:e} 0\n", id(i, j), x * c - zj * s, x * s + zj * c);
        }
    }
    // gmsh's quad16: corners, edge nodes edge by edge, the inner four
    let order = [
        (0, 0),
        (3, 0),
        (3, 3),
        (0, 3),
        (1, 0),
        (2, 0),
        (3, 1),
        (3, 2),
        (2, 3),
        (1, 3),
        (0, 2),
        (0, 1),
        (1, 1),
        (2, 1),
        (2, 2),
        (1, 2),
    ];
    text += &format!("$EndNodes\n$Elements\n{n_el}\n");
    for e in 0..n_el {
        let nodes: Vec<String> = order.iter().map(|&(a, b)| id(3 * e + a, b).to_string()).collect();
        text += &format!("{} 36 2 {g} {g} {}\n", e + 1, nodes.join(" "), g = e / per + 1);
    }
    text + "$EndElements\n"
}

/// The interlaminar index reads any stack, not only plies stacked along z:
/// Pagano's `[0/90/0]` of the test above turned 90° about the beam axis
/// (section x' = z, z' = −x: plies stacked along x, axis 3 along x, as in a
/// web of `box_beam_laminated`; the same L16 lattice from a gmsh file, the
/// load on the face x' = h/2) is the same elastic problem, so its largest
/// index and first-failure factor are the laminate's to round-off, at the
/// turned place. With the plies' axis 3 left along z (zones without the
/// normal) the interfaces of constant x bond no plies: no index.
#[test]
fn the_interlaminar_index_reads_plies_stacked_along_x() {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/pagano_s4.toml"));
    let text = std::fs::read_to_string(path).unwrap();
    let elastic = "orthotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }";
    let strong = "xt = 1e9, xc = 1e9, yt = 1e8, yc = 1e8";
    let materials = format!(
        "[[materials]]\nname = \"ply\"\n{elastic}\nstrengths = {{ {strong}, s12 = 1e6, s23 = 3e6 }}\n\n[[materials]]\nname = \"core\"\n{elastic}\nstrengths = {{ {strong}, s12 = 2e6, s13 = 2e6, s23 = 2.5e6 }}\n"
    );
    let middle = "material = \"ply\", angle = 90.0,";
    let (start, end) = (text.find("[[materials]]").unwrap(), text.find("[[bodies]]").unwrap());
    let laminate = format!("{}{materials}\n{}", &text[..start], &text[end..])
        .replace(middle, "material = \"core\", angle = 90.0,");
    let (_, flat) = run_cli("interlaminar_along_z", Some(&laminate));
    let h = 0.01;
    let zones = |normal: &str| {
        [("ply1", "ply", 0.0), ("ply2", "core", 90.0), ("ply3", "ply", 0.0)]
            .iter()
            .map(|(r, m, a)| {
                format!("[[bodies.zones]]\nregion = \"{r}\"\nmaterial = \"{m}\"\nangle = {a:.1}\n{normal}\n")
            })
            .collect::<String>()
    };
    let cuts = [-h / 2.0, -h / 6.0, h / 6.0, h / 2.0];
    let mesh = common::scratch_dir("composites", "interlaminar_x_mesh").join("along_x.msh");
    std::fs::write(&mesh, stacked_along_x(&cuts, 4, [-0.0025, 0.0025], 0.0)).unwrap();
    let turned = |normal: &str| {
        format!(
            r#"title = "Pagano [0/90/0], S = 4, stacked along x"
{materials}
[[bodies]]
name = "laminate"
material = "ply"
section = {{ shape = "gmsh", file = "{}" }}
axis = {{ element = "B4", from = 0.0, to = 0.04, elements = 8 }}
{}
[[constraints]]
name = "plane_strain"
body = "laminate"
where = {{}}
fix = ["z"]

[[constraints]]
name = "left_support"
body = "laminate"
where = {{ y = 0.0 }}
fix = ["x"]

[[constraints]]
name = "right_support"
body = "laminate"
where = {{ y = 0.04 }}
fix = ["x"]

[[constraints]]
name = "mid_span"
body = "laminate"
where = {{ y = 0.02 }}
fix = ["y"]

[[loads]]
name = "sine_pressure"
body = "laminate"
where = {{ x = 0.005 }}
pressure = 1e5
profile = {{ shape = "sine", along = "y", from = 0.0, to = 0.04 }}
"#,
            mesh.display(),
            zones(normal)
        )
    };
    let run = |name: &str, normal: &str| run_cli(name, Some(&turned(normal))).1;
    let along_x = run("interlaminar_x", "normal = [1.0, 0.0, 0.0]");
    let (a, b) = (&flat["ply_failure"]["interlaminar"], &along_x["ply_failure"]["interlaminar"]);
    let value = |e: &Value, k: &str| e[k].as_f64().unwrap_or_else(|| panic!("{k} in {e}"));
    for k in ["largest_index", "first_failure_load_factor"] {
        let (za, xb) = (value(a, k), value(b, k));
        eprintln!("{k}: stacked along z {za:.8e}, along x {xb:.8e}");
        assert!((xb / za - 1.0).abs() < 1e-6, "{k}: {xb:e} against {za:e}");
    }
    let point = |e: &Value| -> Vec<f64> {
        e["largest_at"]["point"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
    };
    let (pa, pb) = (point(a), point(b));
    assert!(
        (pb[0] - pa[2]).abs() < 1e-9 && [-h / 6.0, h / 6.0].iter().any(|x| (pb[0] - x).abs() < 1e-9),
        "{pb:?} against {pa:?}"
    );
    assert!(pb[1].min(0.04 - pb[1]) < 1e-9, "at y = {}, not at a support", pb[1]);
    // axis 3 along z, across the stack: the constant-x edges bond no plies
    let across = run("interlaminar_x_across", "");
    assert!(across["ply_failure"]["criteria"].is_array() && across["ply_failure"].get("interlaminar").is_none());
}

/// A stack at any inclination: Pagano's `[0/90/0]` plies (the strengths of
/// the test above) as a cantilever, clamped at y = 0 and sheared at its tip
/// along the stack's normal, stacked along x and the same stack turned 30°
/// about the beam axis (gmsh sections, zones with the turned normal): the
/// same problem turned, so the same largest interlaminar index and
/// first-failure factor to `1e-6`, the index found on the turned
/// interfaces. Plies whose axis 3 is not the interface's normal bond
/// nothing there: with the middle ply's axis 3 along z (its neighbours' along
/// x) the index has no interface.
#[test]
fn the_interlaminar_index_reads_an_inclined_stack() {
    let elastic = "orthotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }";
    let strong = "xt = 1e9, xc = 1e9, yt = 1e8, yc = 1e8";
    let h = 0.01;
    let dir = common::scratch_dir("composites", "interlaminar_inclined_meshes");
    let run = |name: &str, turn: f64, middle_normal: Option<[f64; 3]>| {
        let (c, s) = (turn.cos(), turn.sin());
        let normal = [c, 0.0, s];
        let zones: String = [
            ("ply1", "ply", 0.0, normal),
            ("ply2", "core", 90.0, middle_normal.unwrap_or(normal)),
            ("ply3", "ply", 0.0, normal),
        ]
        .iter()
        .map(|(r, m, a, n)| {
            format!(
                "[[bodies.zones]]\nregion = \"{r}\"\nmaterial = \"{m}\"\nangle = {a:.1}\nnormal = [{:e}, {:e}, {:e}]\n",
                n[0], n[1], n[2]
            )
        })
        .collect();
        let cuts = [-h / 2.0, -h / 6.0, h / 6.0, h / 2.0];
        let mesh = dir.join(format!("{name}.msh"));
        std::fs::write(&mesh, stacked_along_x(&cuts, 4, [-0.0025, 0.0025], turn)).unwrap();
        let text = format!(
            r#"title = "Pagano's plies as a cantilever, stacked at {turn} rad"
[[materials]]
name = "ply"
{elastic}
strengths = {{ {strong}, s12 = 1e6, s23 = 3e6 }}

[[materials]]
name = "core"
{elastic}
strengths = {{ {strong}, s12 = 2e6, s13 = 2e6, s23 = 2.5e6 }}

[[bodies]]
name = "laminate"
material = "ply"
section = {{ shape = "gmsh", file = "{}" }}
axis = {{ element = "B4", from = 0.0, to = 0.04, elements = 8 }}
{zones}
[[constraints]]
name = "clamp"
body = "laminate"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "tip_shear"
body = "laminate"
where = {{ y = 0.04 }}
traction = [{:e}, 0.0, {:e}]
"#,
            mesh.display(),
            2e5 * c,
            2e5 * s
        );
        run_cli(name, Some(&text)).1["ply_failure"]["interlaminar"].clone()
    };
    let turn = 30f64.to_radians();
    let (a, b) = (run("inclined_x", 0.0, None), run("inclined_turned", turn, None));
    for k in ["largest_index", "first_failure_load_factor"] {
        let (x, t) = (a[k].as_f64().unwrap(), b[k].as_f64().unwrap());
        eprintln!("{k}: stacked along x {x:.8e}, turned 30° {t:.8e}");
        assert!(x > 0.0 && (t / x - 1.0).abs() < 1e-6, "{k}: {t:e} against {x:e}");
    }
    // on an interface: its distance from the section's centre along the turned normal is h/6
    let p: Vec<f64> = b["largest_at"]["point"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let along = p[0] * turn.cos() + p[2] * turn.sin();
    assert!((along.abs() - h / 6.0).abs() < 1e-9, "at {p:?}: {along} m along the normal");
    // the middle ply's axis 3 across its interfaces: nothing bonded
    let mixed = run("inclined_mixed", 0.0, Some([0.0, 0.0, 1.0]));
    assert!(mixed.is_null(), "{mixed}");
}

/// T300/5208 carbon/epoxy (Tsai & Hahn, Introduction to Composite
/// Materials, 1980, Table 7.1): E1 = 181, E2 = 10.3, G12 = 7.17 GPa,
/// ν12 = 0.28; Xt = Xc = 1500, Yt = 40, Yc = 246, S12 = 68 MPa. Not in the
/// table (chosen): E3 = E2, G13 = G12, ν13 = ν12, ν23 = 0.4 (G23 = E2/2.8),
/// S23 = Yc/2.
const T300: &str = r#"
[[materials]]
name = "t300"
orthotropic = { e1 = 181e9, e2 = 10.3e9, e3 = 10.3e9, g12 = 7.17e9, g13 = 7.17e9, g23 = 3.6786e9, nu12 = 0.28, nu13 = 0.28, nu23 = 0.4 }
strengths = { xt = 1500e6, xc = 1500e6, yt = 40e6, yc = 246e6, s12 = 68e6, s23 = 123e6 }
"#;

/// First-ply failure of a [0/90]s laminate in cylindrical bending (plies
/// 0.25 mm, h = 1 mm, span 40 mm, sine pressure q0 = 10 kPa, simply
/// supported as Pagano's) against classical laminate theory's plate in
/// cylindrical bending (tests/common/clt.rs) under the mid-span moment
/// per width `q0 L²/π²` (statics of the sine load): each criterion's
/// first-failure load factor within 2 % (issue 28).
#[test]
fn first_ply_failure_of_a_cross_ply_in_bending_matches_laminate_theory() {
    let (span, q0, t) = (0.04, 1e4, 0.25e-3);
    let ply = |angle: f64| format!("{{ thickness = {t:e}, material = \"t300\", angle = {angle:.1}, elements = 2 }}");
    let text = format!(
        r#"title = "[0/90]s in cylindrical bending"
{T300}
[[bodies]]
name = "laminate"
section = {{ shape = "laminate", element = "L9", x = {{ from = -0.0005, to = 0.0005, elements = 1 }}, z0 = -0.0005, plies = [{}, {}, {}, {}] }}
axis = {{ element = "B4", from = 0.0, to = {span}, elements = 8 }}

[[constraints]]
name = "plane_strain"
body = "laminate"
where = {{}}
fix = ["x"]

[[constraints]]
name = "supports"
body = "laminate"
where = {{ y = [0.0, 0.0] }}
fix = ["z"]

[[constraints]]
name = "support_right"
body = "laminate"
where = {{ y = {span} }}
fix = ["z"]

[[constraints]]
name = "mid_span"
body = "laminate"
where = {{ y = {mid} }}
fix = ["y"]

[[loads]]
name = "sine"
body = "laminate"
where = {{ z = 0.0005 }}
pressure = {q0}
profile = {{ shape = "sine", along = "y", from = 0.0, to = {span} }}
"#,
        ply(0.0),
        ply(90.0),
        ply(90.0),
        ply(0.0),
        mid = 0.5 * span,
    );
    let (_, summary) = run_cli("fpf_cross_ply", Some(&text));
    let factor = |name: &str| {
        summary["ply_failure"]["criteria"].as_array().unwrap().iter().find(|c| c["criterion"] == name).unwrap()
            ["first_failure_load_factor"]
            .as_f64()
            .unwrap()
    };
    let lamina = clt::Lamina { e1: 181e9, e2: 10.3e9, nu12: 0.28, g12: 7.17e9 };
    let plies: Vec<clt::Ply> =
        [0.0, 90.0, 90.0, 0.0].iter().map(|&a| clt::Ply { thickness: t, angle_deg: a, material: lamina }).collect();
    let st = clt::Strengths { xt: 1500e6, xc: 1500e6, yt: 40e6, yc: 246e6, s12: 68e6, s23: 123e6 };
    // sagging: the top in compression, a negative M_yy in clt's convention
    let moment = -q0 * span * span / (std::f64::consts::PI * std::f64::consts::PI);
    let points = clt::plate_cylindrical_bending_stresses(&plies, moment);
    let hashin = factor("fi_hashin_fibre").min(factor("fi_hashin_matrix"));
    for (name, ours, c) in [
        ("maximum stress", factor("fi_max_stress"), clt::Criterion::MaxStress),
        ("Tsai–Wu", factor("fi_tsai_wu"), clt::Criterion::TsaiWu),
        ("Hashin", hashin, clt::Criterion::Hashin),
    ] {
        let (r, at) = clt::first_ply_failure_factor(&points, &st, c);
        let d = ours / r - 1.0;
        eprintln!(
            "{name}: first-ply failure at λ = {ours:.4} against {r:.4} (CLT, z = {:.3e} m): {:+.2} %",
            points[at].0,
            100.0 * d
        );
        assert!(d.abs() < 0.02, "{name}: {ours} against {r}");
    }
}

/// A 100 mm cantilever, square section 10 × 10 mm centred on the axis
/// (2 × 2 L9, 4 B4), clamped at y = 0, with a tip force `force` (N) on the
/// end face; the material block `material` and the body's extra keys `zones`.
fn cantilever(material: &str, zones: &str, force: [f64; 3]) -> String {
    format!(
        r#"{material}
[[bodies]]
name = "beam"
section = {{ shape = "rectangle", element = "L9", x = {{ from = -0.005, to = 0.005, elements = 2 }}, z = {{ from = -0.005, to = 0.005, elements = 2 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.1, elements = 4 }}
{zones}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "tip"
body = "beam"
where = {{ y = 0.1 }}
total_force = [{}, {}, {}]
"#,
        force[0], force[1], force[2]
    )
}

/// Points spread through the cantilever (corners, faces, inside).
fn sample_points() -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for &x in &[-0.005, -0.002, 0.0, 0.004] {
        for &y in &[0.01, 0.05, 0.1] {
            for &z in &[-0.005, 0.001, 0.005] {
                v.push([x, y, z]);
            }
        }
    }
    v
}

/// An orthotropic material whose constants are isotropic (E, ν, G =
/// E/(2(1 + ν)) in every direction), as a 0° ply and turned by 30°, gives
/// the isotropic model's displacements to round-off. The issue asks 1e-12:
/// that holds for the stiffness itself (the inverted compliance against the
/// Lamé form, 1e-12 E in `materials::anisotropic`'s unit test), but a
/// stiffness that differs in its last bits moves this cantilever's solution
/// by its condition number times the rounding: measured 8.9e-12 (0°) and
/// 1.2e-11 (30°) of the largest displacement, hence 1e-10 here. A 10 %
/// error in any modulus moves it by 1e-1.
#[test]
fn isotropic_constants_given_as_orthotropic_reproduce_the_isotropic_model() {
    let (e, nu) = (70e9, 0.3);
    let g = e / (2.0 * (1.0 + nu));
    let iso = format!("[[materials]]\nname = \"m\"\nyoung_modulus = {e:e}\npoisson_ratio = {nu}\n");
    let ortho = format!(
        "[[materials]]\nname = \"m\"\northotropic = {{ e1 = {e:e}, e2 = {e:e}, e3 = {e:e}, g12 = {g:e}, \
         g13 = {g:e}, g23 = {g:e}, nu12 = {nu}, nu13 = {nu}, nu23 = {nu} }}\n"
    );
    let force = [300.0, -200.0, 1000.0];
    let with_material = |t: String| t.replace("name = \"beam\"\n", "name = \"beam\"\nmaterial = \"m\"\n");
    let a = common::run(&with_material(cantilever(&iso, "", force)));
    let scale = a.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (angle, tolerance) in [(0.0, 1e-10), (30.0, 1e-10)] {
        let zones = format!("[[bodies.zones]]\nmaterial = \"m\"\nangle = {angle:.1}\n");
        let b = common::run(&with_material(cantilever(&ortho, &zones, force)));
        let du = a.u.iter().zip(&b.u).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale;
        eprintln!("{angle}°: displacements differ by {du:e} of the largest");
        assert!(du < tolerance, "{angle}°: displacements differ by {du:e}");
    }
}

/// Turning the plies and the load together leaves the answer turned: a
/// cantilever of Pagano's ply (E1/E2 = 25) at 30° about the normal z, under
/// a tip force, against the same with the normal along x and the force
/// turned by the same 90° about the beam axis (the square section maps
/// onto itself): `u₂(R p) = R u₁(p)` at points through the beam, 1e-10 of
/// the largest displacement (issue 28). A frame that ignores the given
/// normal breaks it at O(1) (tried by hand); a wrong shear factor in `T`,
/// applied alike to both, does not — the Pagano tests catch that one.
#[test]
fn turning_plies_and_load_together_turns_the_answer() {
    let ply = "[[materials]]\nname = \"ply\"\northotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, \
               g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }\n";
    // R: (x, y, z) → (z, y, −x), 90° about y
    let rot = |v: [f64; 3]| [v[2], v[1], -v[0]];
    let f1 = [200.0, 0.0, 1000.0];
    let zone = |normal: [f64; 3]| {
        format!(
            "[[bodies.zones]]\nmaterial = \"ply\"\nangle = 30.0\nfibre = [0.0, 1.0, 0.0]\nnormal = [{:.1}, {:.1}, {:.1}]\n",
            normal[0], normal[1], normal[2]
        )
    };
    let text1 = cantilever(ply, &zone([0.0, 0.0, 1.0]), f1);
    let text2 = cantilever(ply, &zone(rot([0.0, 0.0, 1.0])), rot(f1));
    let (m1, m2) = (cufem::setup::Model::parse(&text1).unwrap(), cufem::setup::Model::parse(&text2).unwrap());
    let (s1, s2) = (common::run(&text1), common::run(&text2));
    let (v1, v2) = (s1.fields(&m1), s2.fields(&m2));
    let scale = s1.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst: f64 = 0.0;
    for p in sample_points() {
        let a = v1.sample_point(None, p).unwrap().u;
        let b = v2.sample_point(None, rot(p)).unwrap().u;
        let ra = rot(a);
        for k in 0..3 {
            worst = worst.max((b[k] - ra[k]).abs() / scale);
        }
    }
    eprintln!("turned answer within {worst:e} of the largest displacement");
    assert!(worst < 1e-10, "{worst:e}");
    // and the turn is not trivial: the answers differ from the unturned ply's
    let text0 = cantilever(ply, &zone([0.0, 0.0, 1.0]).replace("angle = 30.0", "angle = 0.0"), f1);
    let s0 = common::run(&text0);
    let d0 = s0.u.iter().zip(&s1.u).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale;
    assert!(d0 > 0.1, "30° against 0°: {d0}");
}

/// The laminated box beam example: its mid-span deflection per unit
/// roller force against Timoshenko's beam whose stiffnesses come from the
/// walls' laminates (classical laminate theory, tests/common/clt.rs):
/// `w/F = a³/(48 EI) + a/(4 G A_w)` over the rollers' span a = 525 mm, with
/// EI summed ply by ply (each ply's modulus under the wall's uniaxial
/// membrane state, `Q̄_yy + Q̄_yx ε_xx/ε_yy`) and the webs' shear area `2 h t`
/// at G12. Measured +0.8 % (rollers' local deformation and shear lag are
/// outside the beam theory); a 10 % error in E1 moves it by 6.6 %, in G12
/// by 3.3 %.
#[test]
fn laminated_box_beam_bends_like_laminated_timoshenko_beam() {
    let (out, s) = run_cli("box_beam_laminated", None);
    let force =
        -s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap()["force"][2].as_f64().unwrap();
    let probe = s["probes"].as_array().unwrap().iter().find(|p| p["name"] == "bottom_flange_mid_span").unwrap();
    let w = -probe["u"][2].as_f64().unwrap();
    assert!(probe["failure_indices"]["fi_tsai_wu"].as_f64().unwrap() > 0.0, "{probe}");
    // the VTU's failure fields are the summary's: its largest Tsai–Wu index
    // is the one summary.json reports (both over every element's Lagrange
    // grid, faces included)
    let vtu = common::vtu_array(&out.join("result.vtu"), Some("fi_tsai_wu"));
    let largest = vtu.iter().fold(0.0f64, |m, v| m.max(*v));
    let reported = s["ply_failure"]["criteria"][1]["largest_index"].as_f64().unwrap();
    assert!((largest / reported - 1.0).abs() < 1e-9, "VTU {largest} against summary {reported}");
    let lamina = clt::Lamina { e1: 181e9, e2: 10.3e9, nu12: 0.28, g12: 7.17e9 };
    let (t, layup) = (0.5e-3, [0.0, 90.0, 90.0, 0.0]);
    let plies: Vec<clt::Ply> =
        layup.iter().map(|&a| clt::Ply { thickness: t, angle_deg: a, material: lamina }).collect();
    let abd = clt::abd(&plies);
    // the wall's membrane compliance a = A⁻¹ (order xx, yy, xy): under N_yy
    // alone ε_xx/ε_yy = a_xy/a_yy
    let (a11, a12, a22) = (abd.a[0][0], abd.a[0][1], abd.a[1][1]);
    let det = a11 * a22 - a12 * a12;
    let ratio = (-a12 / det) / (a11 / det);
    let modulus = |angle: f64| {
        let q = clt::q_bar(&lamina, angle);
        q[1][1] + q[1][0] * ratio
    };
    let (b, h, web_clear, z_na): (f64, f64, f64, f64) = (0.04, 0.06, 0.056, 0.03);
    let mut ei = 0.0;
    for (k, &angle) in layup.iter().enumerate() {
        let e = modulus(angle);
        for zc in [(k as f64 + 0.5) * t, h - 4.0 * t + (k as f64 + 0.5) * t] {
            ei += e * t * b * ((zc - z_na).powi(2) + t * t / 12.0);
        }
        ei += 2.0 * e * t * web_clear.powi(3) / 12.0;
    }
    let a: f64 = 0.525;
    let compliance = a.powi(3) / (48.0 * ei) + a / (4.0 * 7.17e9 * 2.0 * web_clear * 4.0 * t);
    let d = (w / force) / compliance - 1.0;
    eprintln!(
        "box beam: w/F = {:.5e} m/N against {compliance:.5e} (Timoshenko, CLT walls): {:+.2} %",
        w / force,
        100.0 * d
    );
    assert!(d.abs() < 0.025, "{d}");
}

/// Plies through a profile's walls: every wall of the box gets the stack,
/// each ply turned about its own wall's normal (webs: x; flanges and
/// their junctions: z), ply k counted from the wall's lower x or z; a wall
/// thickness that contradicts the plies, or plies too thick for the
/// profile, are refused by key.
#[test]
fn plies_follow_each_wall_of_a_profile() {
    let text = std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/box_beam_laminated.toml"),
    )
    .unwrap();
    let model = cufem::setup::Model::parse(&text).unwrap();
    let body = &model.mesh.bodies[0];
    let section = &body.section;
    let mut seen = 0;
    for region in &section.regions {
        let (wall, k) = region.name.rsplit_once("_ply").unwrap();
        let k: usize = k.parse().unwrap();
        let normal = if wall == "webs" { [1.0, 0.0, 0.0] } else { [0.0, 0.0, 1.0] };
        let angle = [0.0, 90.0, 90.0, 0.0][k - 1];
        for &e in &region.elements {
            let m = &model.materials[body.material_of(e)];
            assert_eq!(m.frame.axes[2], normal, "{} element {e}", region.name);
            // the fibre: along y at 0°, across the wall in its plane at 90°
            let fibre = m.frame.axes[0];
            let along_y = if angle == 0.0 { 1.0 } else { 0.0 };
            assert!((fibre[1].abs() - along_y).abs() < 1e-12, "{} {fibre:?}", region.name);
            // ply k lies in the k-th quarter of the wall's thickness
            let nodes = section.element(e);
            let c: f64 = nodes.iter().map(|&n| section.nodes[n][if wall == "webs" { 0 } else { 1 }]).sum::<f64>()
                / nodes.len() as f64;
            let offset = if wall == "top_flange" {
                0.058
            } else if wall == "webs" && c > 0.02 {
                0.038
            } else {
                0.0
            };
            let layer = ((c - offset) / 0.5e-3).floor() as usize;
            assert_eq!(layer + 1, k, "{} element {e} at {c}", region.name);
            seen += 1;
        }
    }
    assert_eq!(seen, section.n_elements());
    let bad = text.replace("height = 0.06,", "height = 0.06, web_thickness = 0.003,");
    let e = cufem::setup::Model::parse(&bad).unwrap_err().to_string();
    assert!(e.contains("bodies[0].section.web_thickness") && e.contains("total thickness"), "{e}");
    // a wall the plies make too thick for the profile is refused on `plies`
    // (the file writes no wall thickness), with the plies' total
    let narrow = text.replace("width = 0.04,", "width = 0.003,");
    let e = cufem::setup::Model::parse(&narrow).unwrap_err().to_string();
    assert!(e.contains("bodies[0].section.plies = a total thickness of 0.002"), "{e}");
}

/// Bad anisotropic input is refused by key with what is allowed: Poisson's
/// ratios without a positive definite compliance, a stiffness that is not
/// symmetric, plasticity on an anisotropic material, an unknown zone region,
/// a fibre along the normal.
#[test]
fn bad_anisotropic_input_is_refused_by_key() {
    let ply = "[[materials]]\nname = \"ply\"\northotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, \
               g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }\n";
    let zone = "[[bodies.zones]]\nmaterial = \"ply\"\nangle = 30.0\n";
    let good = cantilever(ply, zone, [0.0, 0.0, 1.0]);
    assert_eq!(cufem::setup::Model::parse(&good).unwrap().materials.len(), 2, "ply and ply@30");
    // a zone that states no orientation keeps the material's own axes: no copy
    let plain =
        cufem::setup::Model::parse(&cantilever(ply, "[[bodies.zones]]\nmaterial = \"ply\"\n", [0.0; 3])).unwrap();
    assert_eq!(plain.materials.len(), 1);
    assert_eq!(plain.mesh.bodies[0].materials(), vec![0]);
    let cases: [(String, &str, &str); 5] = [
        (good.replace("nu12 = 0.25", "nu12 = 6.0"), "materials[0].orthotropic", "positive definite"),
        (
            good.replace(
                "orthotropic = { e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }",
                "stiffness = [[1e9, 2e8, 0, 0, 0, 0], [0, 1e9, 0, 0, 0, 0], [0, 0, 1e9, 0, 0, 0], [0, 0, 0, 1e9, 0, 0], [0, 0, 0, 0, 1e9, 0], [0, 0, 0, 0, 0, 1e9]]",
            ),
            "materials[0].stiffness",
            "symmetric",
        ),
        (
            good.replace("nu23 = 0.25 }\n", "nu23 = 0.25 }\nplasticity = { hardening = \"perfect\", yield_stress = 1e8 }\n"),
            "materials[0].plasticity",
            "anisotropic materials are elastic",
        ),
        (good.replace("angle = 30.0\n", "angle = 30.0\nregion = \"web\"\n"), "bodies[0].zones[0].region", "regions"),
        (good.replace("angle = 30.0\n", "angle = 30.0\nfibre = [0.0, 0.0, 2.0]\n"), "bodies[0].zones[0].fibre", "non-parallel"),
    ];
    for (text, key, allowed) in cases {
        let e = cufem::setup::Model::parse(&text).unwrap_err().to_string();
        assert!(e.contains(key) && e.contains(allowed), "expected {key} … {allowed}, got: {e}");
    }
}

/// An isotropic elastoplastic layer beside an elastic anisotropic one (a
/// metal liner on a carbon ply): a cantilever loaded past the liner's yield
/// converges, the liner yields, the ply stays elastic, and the liner's
/// Gauss points stay on or inside their yield surface (perfect plasticity:
/// von Mises ≤ σ_y to 1e-9).
#[test]
fn an_elastoplastic_liner_yields_beside_an_elastic_ply() {
    let materials = "[[materials]]\nname = \"ply\"\northotropic = { e1 = 181e9, e2 = 10.3e9, e3 = 10.3e9, g12 = 7.17e9, \
                     g13 = 7.17e9, g23 = 3.68e9, nu12 = 0.28, nu13 = 0.28, nu23 = 0.4 }\n\n[[materials]]\nname = \"liner\"\n\
                     young_modulus = 70e9\npoisson_ratio = 0.33\nplasticity = { hardening = \"perfect\", yield_stress = 1e8 }\n";
    let text = format!(
        r#"{materials}
[solver]
increments = 8

[[bodies]]
name = "beam"
section = {{ shape = "laminate", element = "L9", x = {{ from = -0.005, to = 0.005, elements = 2 }}, z0 = -0.005, plies = [
  {{ thickness = 0.005, material = "liner", elements = 2 }},
  {{ thickness = 0.005, material = "ply", angle = 0.0, elements = 2 }} ] }}
axis = {{ element = "B4", from = 0.0, to = 0.1, elements = 4 }}

[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "tip"
body = "beam"
where = {{ y = 0.1 }}
total_force = [0.0, 0.0, -3000.0]
"#
    );
    let model = cufem::setup::Model::parse(&text).unwrap();
    let sol = common::run(&text);
    let body = &model.mesh.bodies[0];
    let cell = &model.cells[0];
    let ngp = cell.gp_per_element();
    let (mut liner_yielded, mut ply_yielded) = (0, 0);
    for e in 0..body.n_elements() {
        let es = body.split_element(e).0;
        let m = &model.materials[body.material_of(es)];
        // the liner is the first ply, below z = 0
        let nodes = body.section.element(es);
        let zc = nodes.iter().map(|&n| body.section.nodes[n][1]).sum::<f64>() / nodes.len() as f64;
        assert_eq!(m.is_plastic(), zc < 0.0, "element {es} at z = {zc}");
        for g in e * ngp..(e + 1) * ngp {
            let peeq = sol.states[g].peeq;
            if m.is_plastic() {
                liner_yielded += usize::from(peeq > 0.0);
                let vm = cufem::voigt::von_mises(&sol.stresses[g]);
                assert!(vm <= 1e8 * (1.0 + 1e-9), "liner point {g}: von Mises {vm:e}");
            } else {
                ply_yielded += usize::from(peeq > 0.0);
            }
        }
    }
    eprintln!("liner: {liner_yielded} plastic Gauss points; ply: {ply_yielded}");
    assert!(liner_yielded > 0 && ply_yielded == 0);
}

/// `shape = "tube"` with plies is the one-cell box with the same plies:
/// the same section (nodes, elements, ply regions and their materials), so
/// the same answer; without along_x/along_z it is refused by key.
#[test]
fn a_tube_with_plies_is_the_layered_box() {
    let text = std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/box_beam_laminated.toml"),
    )
    .unwrap();
    let tube = text.replace(
        "shape = \"box\", element = \"L9\", origin = [0.0, 0.0], width = 0.04, height = 0.06, along_flange = 4, along_web = 6,",
        "shape = \"tube\", element = \"L9\", origin = [0.0, 0.0], width = 0.04, height = 0.06, along_x = 4, along_z = 6,",
    );
    assert_ne!(tube, text);
    let (a, b) = (cufem::setup::Model::parse(&text).unwrap(), cufem::setup::Model::parse(&tube).unwrap());
    let (sa, sb) = (&a.mesh.bodies[0].section, &b.mesh.bodies[0].section);
    assert_eq!(sa.nodes, sb.nodes);
    assert_eq!(sa.connectivity, sb.connectivity);
    assert_eq!(sa.regions, sb.regions);
    assert_eq!(a.mesh.bodies[0].element_materials, b.mesh.bodies[0].element_materials);
    let bad = tube.replace("along_x = 4, along_z = 6,", "around = 8,");
    let e = cufem::setup::Model::parse(&bad).unwrap_err().to_string();
    assert!(e.contains("bodies[0].section.along_x") && e.contains("plies"), "{e}");
}

/// Pagano's S = 4 (examples/pagano_s4.toml) with its two ply interfaces
/// cohesive (`interfaces = "cohesive"`, default penalty K = 50 E3/t =
/// 1.5e13 Pa/m of Turon et al. 2007, far below onset: undamaged) against the
/// shared-node run: the penalty adds 2/K = 1.3e-13 m³/N to the stack's
/// through-thickness compliance h/E3 = 1e-11, so the deflection and σ_yy may
/// move by a fraction of that (design48 §4.1 step 2: within 0.5 %).
/// Measured: w +0.36 %, σ_yy within 0.2 % of its peak.
#[test]
fn pagano_with_cohesive_interfaces_matches_shared_nodes() {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/pagano_s4.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let cohesive =
        text.replacen("plies = [", "interfaces = \"cohesive\", interface_material = \"resin\", plies = [", 1)
            + "\n[[materials]]\nname = \"resin\"\ncohesive = { gic = 969.0, giic = 1719.0, bk_exponent = 2.284, \
           normal_strength = 80e6 }\n";
    assert!(cohesive.contains("interfaces = \"cohesive\""), "the example's section has no plies list to add to");
    let (shared_out, shared) = run_cli("pagano_shared", Some(&text));
    let (out, summary) = run_cli("pagano_cohesive", Some(&cohesive));
    let w = |s: &Value| s["probes"][0]["u"][2].as_f64().unwrap();
    let dw = w(&summary) / w(&shared) - 1.0;
    // undamaged: no delaminated area, nothing dissipated
    assert_eq!(summary["delamination"]["area_m2"].as_f64(), Some(0.0));
    assert_eq!(summary["delamination"]["dissipated_j"].as_f64(), Some(0.0));
    let line = |o: &Path| common::csv_columns(&o.join("line_through_mid_span.csv"))["s_yy"].clone();
    let (a, b) = (line(&out), line(&shared_out));
    let peak = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let d_syy = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / peak;
    eprintln!("cohesive interfaces: w {:+.3} %, σ_yy within {:.3} % of its peak", 100.0 * dw, 100.0 * d_syy);
    assert!(dw.abs() < 0.005, "w moved by {dw}");
    assert!(d_syy < 0.005, "σ_yy moved by {d_syy} of its peak");
}
