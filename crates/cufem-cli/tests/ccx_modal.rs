//! The CalculiX cross-check of free vibration (issue 27): `cufem verify` on
//! a modal model runs a `*FREQUENCY` step and compares the natural
//! frequencies mode by mode. These tests need `ccx` (Debian package
//! `calculix-ccx`), like crates/cufem-cli/tests/ccx.rs, and fail — never skip — without it.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};

use common::cufem;
use cufem::setup::Model;
use cufem_ccx::{self as ccx, HexKind};

fn scratch(name: &str) -> PathBuf {
    common::scratch_dir("ccx_modal", name)
}

/// A solid steel cantilever, 50 × 100 mm, 1 m, clamped at y = 0:
/// 2 × 4 L9 section, 10 B4, the 6 lowest modes.
const CANTILEVER: &str = r#"
title = "Solid steel cantilever: natural frequencies"

[analysis]
type = "modal"
modes = 6

[[materials]]
name = "steel"
young_modulus = 210e9
poisson_ratio = 0.3
density = 7850.0

[[bodies]]
name = "beam"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.05, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 4 } }
axis = { element = "B4", from = 0.0, to = 1.0, elements = 10 }

[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]
"#;

/// `cufem verify --refine 1` on the cantilever (960 C3D20R, 15 303 DOF;
/// about 2 s, ccx 1.7 s of it): every cufem frequency within 2 % of
/// CalculiX's (issue 27), paired with the 3D mode of the same number and
/// shape (MAC > 0.99). The expected values are CalculiX's own (ccx 2.20,
/// `*FREQUENCY`, consistent mass), from `cufem verify MODEL --refine 1` on
/// the model above; measured +0.13 … +0.28 % (41.956 against 41.895 Hz for
/// the first bending mode, in x; the torsion mode 5, 602.29 against
/// 600.60 Hz, the largest), every MAC above 0.99999. A mass or stiffness
/// off by 4 % (a density read in the wrong unit would be 1000×) moves every
/// frequency by 2 % and fails.
#[test]
fn verify_cross_checks_the_natural_frequencies_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let out = common::verify(&scratch("cantilever"), "cantilever", CANTILEVER, 1);
    // the deck: the density, one frequency step for 6 modes, no static step
    let deck = std::fs::read_to_string(out.join("verify/ccx/model.inp")).unwrap();
    assert!(deck.contains("*DENSITY\n7.85e3\n") && deck.contains("*STEP\n*FREQUENCY\n6\n"), "{deck:.0}");
    assert!(!deck.contains("*STATIC") && !deck.contains("*CLOAD"));
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let modes = table["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 6, "{modes:?}");
    for (k, m) in modes.iter().enumerate() {
        let d = m["difference_percent"].as_f64().unwrap();
        assert!(d.abs() < 2.0, "mode {}: cufem {} Hz, CalculiX {} Hz ({d} %)", k + 1, m["cufem_hz"], m["ccx_hz"]);
        assert_eq!(m["ccx_mode"].as_u64(), Some(k as u64 + 1), "{m}");
        assert!(m["mac"].as_f64().unwrap() > 0.99, "{m}");
    }
    // the first bending frequency against CalculiX's own table (.dat)
    let dat = std::fs::read_to_string(out.join("verify/ccx/model.dat")).unwrap();
    let theirs = ccx::results::read_frequencies(&dat);
    assert_eq!(modes[0]["ccx_hz"].as_f64(), Some(theirs[0].hz));
    // the static rows do not apply and are not written
    for key in ["probes", "lines", "resultants", "fields"] {
        assert!(table[key].as_array().unwrap().is_empty(), "{key}");
    }
    assert!(!out.join("verify/field_difference.vtu").exists());
    let csv = std::fs::read_to_string(out.join("verify/table.csv")).unwrap();
    assert!(csv.lines().any(|l| l.starts_with("mode,1,frequency_hz,")), "{csv}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["verify"]["modes"].as_array().map(Vec::len), Some(6));
}

/// A modal model about a loaded state has no twin yet (the deck's
/// frequency step is about the undeformed state): refused by key, before
/// any file is written, and by `export-ccx` as invalid input (exit 1).
#[test]
fn a_pre_stressed_modal_model_is_refused_by_key() {
    let loaded = format!(
        "{CANTILEVER}\n[[loads]]\nname = \"tip\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\ntotal_force = [0.0, -1e5, 0.0]\n"
    );
    let pulled = format!(
        "{CANTILEVER}\n[[constraints]]\nname = \"pull\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\ndisplacement = {{ y = 1e-4 }}\n"
    );
    for (name, text, key) in [("loads", &loaded, "loads: load \"tip\""), ("pulled", &pulled, "constraints[1]: ")] {
        let model = Model::parse(text).unwrap();
        let dir = scratch(name);
        let e = ccx::export(&model, HexKind::C3D20R, 1, &dir).unwrap_err().to_string();
        assert!(e.starts_with(key) && e.contains("pre-stressed modal analysis cannot be exported"), "{name}: {e}");
        assert!(!dir.join("model.inp").exists(), "{name}: a deck was written");
    }
    let dir = scratch("cli");
    let model = dir.join("loaded.toml");
    std::fs::write(&model, &loaded).unwrap();
    let deck = dir.join("deck");
    let run = cufem().args(["export-ccx", model.to_str().unwrap(), "--out", deck.to_str().unwrap()]).output().unwrap();
    assert_eq!(run.status.code(), Some(1), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(String::from_utf8_lossy(&run.stderr).contains("loads: load \"tip\""));
}

/// How much mode `mode` (per DOF) distorts the cross-section at `y`: the
/// in-plane displacements of the section's nodes there less their best
/// rigid in-plane motion (translation and rotation, least squares), as a
/// fraction of them — near 0 for a beam mode (bending, torsion: the section
/// moves rigidly in its plane), near 1 for a local, plate-like mode.
fn section_distortion(model: &Model, mode: &[f64], y: f64) -> f64 {
    let mesh = &model.mesh;
    let pts: Vec<[f64; 4]> = (0..mesh.n_nodes())
        .map(|n| (mesh.coords(n), n))
        .filter(|(c, _)| (c[1] - y).abs() < 1e-9)
        .map(|(c, n)| [c[0], c[2], mode[3 * n], mode[3 * n + 2]])
        .collect();
    let np = pts.len() as f64;
    let (xc, zc) = (pts.iter().map(|p| p[0]).sum::<f64>() / np, pts.iter().map(|p| p[1]).sum::<f64>() / np);
    // normal equations of u_x = a − θ z', u_z = b + θ x'
    let (mut ata, mut atb) = ([[0.0; 3]; 3], [0.0; 3]);
    for p in &pts {
        let (x, z) = (p[0] - xc, p[1] - zc);
        for (row, value) in [([1.0, 0.0, -z], p[2]), ([0.0, 1.0, x], p[3])] {
            for i in 0..3 {
                atb[i] += row[i] * value;
                for j in 0..3 {
                    ata[i][j] += row[i] * row[j];
                }
            }
        }
    }
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let fit: Vec<f64> = (0..3)
        .map(|c| {
            let mut m = ata;
            (0..3).for_each(|r| m[r][c] = atb[r]);
            det(m) / det(ata)
        })
        .collect();
    let (mut rest, mut all) = (0.0, 0.0);
    for p in &pts {
        let (x, z) = (p[0] - xc, p[1] - zc);
        rest += (p[2] - fit[0] + fit[2] * z).powi(2) + (p[3] - fit[1] - fit[2] * x).powi(2);
        all += p[2] * p[2] + p[3] * p[3];
    }
    (rest / all).sqrt()
}

/// The thin-walled channel of `examples/cantilever_modes.toml`: its first
/// local mode — the first whose section distorts (above 0.9 at y = 0.5 and
/// 0.75 m, where the beam modes before it stay below 0.5; measured mode 6,
/// 303.1 Hz, 0.98 and 1.00, no effective mass), the flanges flapping as
/// plates — within 2 % of CalculiX's `*FREQUENCY` on the same geometry
/// (issue 27; C3D20R, two through each 2 mm wall, 73,599 DOF, ccx about
/// 11 s), paired by its shape (MAC > 0.9). Measured +0.52 % against
/// 301.57 Hz, MAC 1.000 (`cufem verify examples/cantilever_modes.toml
/// --refine 1`; at refine 2, 500,571 DOF, the 3D frequencies move by at
/// most 0.1 %).
#[test]
#[ignore = "validate: slow — the channel's modes against CalculiX's 73,599-DOF *FREQUENCY (about 35 s; CI keeps the frequency cross-check)"]
fn the_channels_first_local_mode_agrees_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let text = std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/cantilever_modes.toml"),
    )
    .unwrap();
    let model = Model::parse(&text).unwrap();
    let sol = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let modal = sol.modal.unwrap();
    let distortion: Vec<f64> = modal
        .modes
        .iter()
        .map(|m| section_distortion(&model, m, 0.5).min(section_distortion(&model, m, 0.75)))
        .collect();
    println!("section distortion per mode: {distortion:.3?}");
    let local = distortion.iter().position(|&d| d > 0.9).expect("a local mode among the first 8");
    assert!(distortion[..local].iter().all(|&d| d < 0.5), "{distortion:?}");
    let out = common::verify(&scratch("channel"), "channel", &text, 1);
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let row = &table["modes"][local];
    let d = row["difference_percent"].as_f64().unwrap();
    println!("local mode {}: {row}", local + 1);
    assert!(d.abs() < 2.0 && row["mac"].as_f64().unwrap() > 0.9, "{row}");
}
