//! Bodies that start inside each other, interference fits, and contacts
//! that cannot work as modelled (issue 24, item 1). Before: two cantilevers
//! whose lower beam reached 1 or 10 mm into the upper one converged in
//! silence (10 mm: 25.5 kN of contact force against 1.78 kN without the
//! overlap, the upper root reaction with the wrong sign), with either
//! contact method; pairs 1 m apart that never closed, explicit pairs 15 cm
//! apart along the surface and a penalty whose penetration is the whole
//! punch travel drew no warning.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn cufem(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cufem")).args(args).output().unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("interference_{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name))
        .unwrap()
}

fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the model");
    text.replace(from, to)
}

/// The cantilevers with the lower beam's top face (and the contact's master
/// face) moved up by `overlap` into the upper beam, with `method`.
fn overlapping_cantilevers(overlap: f64, method: &str) -> String {
    let top = 0.0254 + overlap;
    let t = replaced(
        &example("cantilevers_contact.toml"),
        "z = { from = 0.0, to = 0.0254, elements = 4 } }\naxis = { element = \"B4\", from = 0.0762",
        &format!("z = {{ from = 0.0, to = {top}, elements = 4 }} }}\naxis = {{ element = \"B4\", from = 0.0762"),
    );
    replaced(
        &t,
        "master = { body = \"lower\", where = { z = 0.0254 } }",
        &format!("master = {{ body = \"lower\", where = {{ z = {top} }} }}\nmethod = \"{method}\""),
    )
}

/// Both methods, 1 mm and 10 mm: exit 1 before any solve, the message naming
/// both bodies, the depth and the key that would allow it.
#[test]
fn bodies_that_start_inside_each_other_are_refused() {
    let dir = scratch("refused");
    for method in ["node_to_node", "surface"] {
        for (overlap, depth) in [(1e-3, "1e-3 m"), (1e-2, "1e-2 m")] {
            let path = dir.join(format!("{method}_{overlap}.toml"));
            std::fs::write(&path, overlapping_cantilevers(overlap, method)).unwrap();
            let out = cufem(&["check", path.to_str().unwrap()]);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{method}, {overlap} m: {err}");
            for needle in ["contacts[0].slave.where", "\"upper\"", "\"lower\"", depth, "interference = true"] {
                assert!(err.contains(needle), "{method}, {overlap} m: {needle:?} missing from {err}");
            }
        }
    }
}

/// Lamé's shrink fit (examples/shrink_fit.toml, whose header derives the
/// numbers): the contact pressure at mid-length and the radial
/// displacements of both surfaces within 1 % of the closed form, with
/// either contact method; without `interference = true` the same model is
/// refused (the shaft starts 0.02 mm inside the hub).
#[test]
fn a_shrink_fit_gives_lames_interference_pressure() {
    let (a, b, c, delta, e, nu) = (0.02, 0.03, 0.045, 2e-5, 200e9, 0.3);
    let bs: f64 = b + delta;
    let lame = |r: f64, x: f64| (x * x + r * r) / (x * x - r * r);
    let p = delta * e / (b * (lame(b, c) + nu) + bs * (lame(a, bs) - nu));
    let (u_hub, u_shaft) = (p * b / e * (lame(b, c) + nu), -p * bs / e * (lame(a, bs) - nu));
    let dir = scratch("lame");
    let text = example("shrink_fit.toml");
    for method in ["node_to_node", "surface"] {
        let model = dir.join(format!("{method}.toml"));
        let variant =
            replaced(&text, "\ninterference = true\n", &format!("\ninterference = true\nmethod = \"{method}\"\n"));
        std::fs::write(&model, variant).unwrap();
        let out = dir.join(method);
        let run = cufem(&["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        // pressure × area summed over the points at y = 50 mm, over their area
        let csv = std::fs::read_to_string(out.join("contact_fit.csv")).unwrap();
        let mut lines = csv.lines();
        let head: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
        let (y, pressure, area) = (col("y"), col("pressure"), col("area"));
        let (mut force, mut total) = (0.0, 0.0);
        for l in lines {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            if (v[y] - 0.05).abs() < 1e-9 {
                force += v[pressure] * v[area];
                total += v[area];
            }
        }
        assert!(total > 0.0, "{method}: no contact point at mid-length");
        let measured = force / total;
        common::within(&format!("interference.{method}.pressure"), measured, p, 0.01, "Lamé's interference pressure");
        let s: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        // the memory estimate's band of every shipped example (crates/cufem-cli/tests/examples.rs; measured 1.14 here)
        let ratio = s["memory"]["estimated_bytes"].as_f64().unwrap() / s["memory"]["peak_bytes"].as_f64().unwrap();
        assert!((0.9..1.3).contains(&ratio), "{method}: memory estimate / peak {ratio}");
        for (probe, expected) in [("hub_bore", u_hub), ("shaft_surface", u_shaft)] {
            let uz =
                s["probes"].as_array().unwrap().iter().find(|x| x["name"] == probe).unwrap()["u"][2].as_f64().unwrap();
            common::within(&format!("interference.{method}.{probe}"), uz, expected, 0.01, "Lamé's radial displacement");
        }
    }
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, replaced(&text, "\ninterference = true\n", "\n")).unwrap();
    let out = cufem(&["check", plain.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("\"shaft\"") && err.contains("\"hub\"") && err.contains("2e-5 m"), "{err}");
}

/// Two clamped blocks 1 m apart, the upper one pushed by a small load:
/// their contact never closes and the run says so (naming the contact and
/// both bodies); explicit pairs 15 cm apart along the surface are warned
/// about before the run.
#[test]
fn contacts_that_cannot_work_are_warned_about() {
    let text = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "low"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.3, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 1 } }
axis = { element = "B4", from = 0.0, to = 0.3, elements = 2 }

[[bodies]]
name = "high"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.3, elements = 2 }, z = { from = 1.1, to = 1.2, elements = 1 } }
axis = { element = "B4", from = 0.0, to = 0.3, elements = 2 }

[[constraints]]
name = "low_base"
body = "low"
where = { z = 0.0 }
fix = ["x", "y", "z"]

[[constraints]]
name = "high_top"
body = "high"
where = { z = 1.2 }
fix = ["x", "y", "z"]

[[loads]]
name = "push"
body = "high"
where = { z = 1.1 }
total_force = [0.0, 0.0, -1000.0]

[[contacts]]
name = "gap"
master = { body = "low", where = { z = 0.1 } }
slave = { body = "high", where = { z = 1.1 } }
"#;
    let dir = scratch("warned");
    let far = dir.join("far.toml");
    std::fs::write(&far, text).unwrap();
    let out = dir.join("far");
    let run = cufem(&["run", far.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(err.contains("contacts[0]") && err.contains("never closed") && err.contains("\"high\""), "{err}");
    // the same upper block 1 mm above, paired by hand with a master node 15 cm away along x
    let near = replaced(
        &replaced(text, "z = { from = 1.1, to = 1.2", "z = { from = 0.101, to = 0.2"),
        "slave = { body = \"high\", where = { z = 1.1 } }",
        "slave = { body = \"high\", where = { z = 0.101 } }\npairs = [[[0.0, 0.0, 0.101], [0.15, 0.0, 0.1]]]",
    );
    let near = near.replace("z = 1.2 }", "z = 0.2 }").replace("where = { z = 1.1 }", "where = { z = 0.101 }");
    let path = dir.join("offset.toml");
    std::fs::write(&path, near).unwrap();
    let check = cufem(&["check", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&check.stderr);
    assert!(check.status.success(), "{err}");
    assert!(err.contains("contacts[0].pairs[0]") && err.contains("1.5e-1 m apart along the contact surface"), "{err}");
}

/// The block indentation with a penalty factor of 1e-3 (the smallest
/// allowed, 1e-5 of the default): the punch sinks into the block instead of pressing it,
/// and the run warns naming the indenter's penalty key and the fraction.
#[test]
fn a_penalty_too_soft_to_hold_the_punch_is_warned_about() {
    let dir = scratch("soft");
    let text = example("block_indentation.toml");
    let soft = replaced(&text, "[[indenters]]\n", "[[indenters]]\npenalty_factor = 1e-3\n");
    let path = dir.join("soft.toml");
    std::fs::write(&path, soft).unwrap();
    let out = dir.join("soft");
    let run = cufem(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(err.contains("indenters[0].penalty_factor") && err.contains("too soft"), "{err}");
    // the shipped example, with its default penalty, draws no such warning
    let out = dir.join("default");
    let path = dir.join("default.toml");
    std::fs::write(&path, &text).unwrap();
    let run = cufem(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(!String::from_utf8_lossy(&run.stderr).contains("too soft"));
}
