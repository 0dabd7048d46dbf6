//! The CalculiX twin of anisotropic and layered models (issue 28): the
//! exported elastic constants and material axes against a uniform stress
//! state, and the sandwich beam indented by a rigid cylinder
//! (examples/sandwich_indentation.toml) against its 3D model. These tests
//! need `ccx` (Debian package `calculix-ccx`) and fail — never skip — when
//! it cannot be found.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::collections::HashMap;
use std::path::Path;

use cufem::analysis::{self, Silent};
use cufem::materials::{Frame, Orthotropic};
use cufem::setup::Model;
use cufem_ccx::{self as ccx, HexKind};

/// A carbon/epoxy ply with three different moduli and Poisson's ratios.
fn ply() -> Orthotropic {
    Orthotropic { young: [140e9, 10e9, 9e9], shear: [5e9, 4.5e9, 3.5e9], poisson: [0.3, 0.28, 0.45] }
}

/// The uniform stress (Pa, Voigt xx, yy, zz, xy, xz, yz) of the block tests.
const STRESS: [f64; 6] = [20e6, -10e6, 15e6, 8e6, -6e6, 5e6];

/// A 10 × 12 × 8 mm block (one L9 × B3 element, 2 × 2 × 2 C3D20R at
/// refine 1) of `material` (a `[[materials]]` table named "ply") turned by a zone
/// (30° about a tilted normal from a tilted fibre: every coupling of the
/// global stiffness non-zero), loaded by the tractions `σ n` of [`STRESS`]
/// on its six faces and held by six support components that leave the
/// deformation free (origin: x, y, z; (a, 0, 0): y, z; (0, 0, c): y). The
/// uniform stress then is the exact solution of both models.
fn block(material: &str) -> String {
    let [sxx, syy, szz, sxy, sxz, syz] = STRESS;
    let faces = [
        ("x0", "x = 0.0", [-sxx, -sxy, -sxz]),
        ("x1", "x = 0.01", [sxx, sxy, sxz]),
        ("y0", "y = 0.0", [-sxy, -syy, -syz]),
        ("y1", "y = 0.012", [sxy, syy, syz]),
        ("z0", "z = 0.0", [-sxz, -syz, -szz]),
        ("z1", "z = 0.008", [sxz, syz, szz]),
    ];
    let mut loads = String::new();
    for (name, at, t) in faces {
        loads += &format!(
            "[[loads]]\nname = \"{name}\"\nbody = \"block\"\nwhere = {{ {at} }}\ntraction = [{:e}, {:e}, {:e}]\n",
            t[0], t[1], t[2]
        );
    }
    format!(
        r#"title = "Oriented anisotropic block under a uniform stress"
{material}
[[bodies]]
name = "block"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.008, elements = 1 }} }}
axis = {{ element = "B3", from = 0.0, to = 0.012, elements = 1 }}
[[bodies.zones]]
material = "ply"
angle = 30.0
fibre = [0.2, 1.0, 0.1]
normal = [0.3, -0.2, 1.0]
[[constraints]]
name = "origin"
body = "block"
where = {{ x = 0.0, y = 0.0, z = 0.0 }}
fix = ["x", "y", "z"]
[[constraints]]
name = "xend"
body = "block"
where = {{ x = 0.01, y = 0.0, z = 0.0 }}
fix = ["y", "z"]
[[constraints]]
name = "zend"
body = "block"
where = {{ x = 0.0, y = 0.0, z = 0.008 }}
fix = ["y"]
{loads}
[[probes]]
name = "far"
point = [0.01, 0.012, 0.008]
[[probes]]
name = "side"
point = [0.01, 0.0, 0.008]
[[probes]]
name = "centre"
point = [0.005, 0.006, 0.004]
"#
    )
}

/// The node displacements of the last `displacements … for set NAME` block
/// of a `.dat` file (7 significant digits, against 6 in the `.frd` file).
fn dat_displacements(dat: &str, set: &str) -> HashMap<usize, [f64; 3]> {
    let title = format!("displacements (vx,vy,vz) for set {set} and time");
    let start = dat.rfind(&title).unwrap_or_else(|| panic!("no {title} in the .dat file"));
    dat[start..]
        .lines()
        .skip(1)
        .skip_while(|l| l.trim().is_empty())
        .take_while(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|v| v.parse().unwrap()).collect();
            (v[0] as usize, [v[1], v[2], v[3]])
        })
        .collect()
}

/// Exports `text`, runs CalculiX and compares the displacement at the
/// probes "far" and "side" (to 2e-6 of the largest component: the `.dat`
/// file's 7 digits) and the stress at "centre" with cufem's and with the
/// applied uniform stress; returns the deck. CalculiX's `.frd` stresses are
/// in the global axes (its `.dat` prints them in the material axes); they
/// come out 4e-5 low in every component, isotropic material too: its
/// extrapolation of C3D20R's integration-point stresses (exact there) to
/// the nodes. Hence 1e-4 for them, 1e-9 for cufem's.
fn uniform_stress_agrees(name: &str, text: &str) -> String {
    let dir = common::scratch_dir("ccx_laminate", name);
    let model = Model::parse(text).unwrap();
    let (mesh, path) = ccx::export(&model, HexKind::C3D20R, 1, &dir).unwrap();
    let deck = std::fs::read_to_string(&path).unwrap();
    let print = "*NODE PRINT, NSET=P_FAR\nU\n*NODE PRINT, NSET=P_SIDE\nU\n*END STEP";
    std::fs::write(&path, deck.replace("*END STEP", print)).unwrap();
    let run = ccx::run("ccx", &dir, 1).expect("ccx must be installed (apt-get install calculix-ccx)");
    let dat = std::fs::read_to_string(dir.join("model.dat")).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let fields = sol.fields(&model);
    let mut scale = 0.0f64;
    let mut pairs = Vec::new();
    for (probe, set) in [(&model.probes[0], "P_FAR"), (&model.probes[1], "P_SIDE")] {
        let ours = fields.sample_probe(probe).unwrap().u;
        let theirs = ccx::sample_displacement(&model, &mesh, &dat_displacements(&dat, set), &probe.locations).unwrap();
        eprintln!("{name} {}: u cufem {ours:?}, CalculiX {theirs:?}", probe.name);
        scale = scale.max(theirs.iter().fold(0.0, |m, v| m.max(v.abs())));
        pairs.push((ours, theirs));
    }
    for (ours, theirs) in pairs {
        for k in 0..3 {
            assert!((ours[k] - theirs[k]).abs() <= 2e-6 * scale, "{name}: u {ours:?} against {theirs:?}");
        }
    }
    let ours = fields.sample_probe(&model.probes[2]).unwrap().stress;
    let theirs = ccx::sample(&model, &mesh, &run.results, &model.probes[2].locations).unwrap().1;
    eprintln!("{name} centre: σ cufem {ours:?}, CalculiX {theirs:?}");
    let big = STRESS.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for k in 0..6 {
        assert!((ours[k] - STRESS[k]).abs() <= 1e-9 * big, "{name}: cufem σ {ours:?}");
        assert!((theirs[k] - STRESS[k]).abs() <= 1e-4 * big, "{name}: CalculiX σ {theirs:?}");
    }
    std::fs::read_to_string(&path).unwrap()
}

/// An orthotropic ply in a tilted frame, exported as engineering constants
/// with an `*ORIENTATION`: CalculiX's displacements match cufem's to 2e-6
/// under a uniform stress (observed: within the 7 printed digits). A wrong
/// constant, a swapped ν_ij, or axes 1 and 2 exchanged move them by
/// percents.
#[test]
fn an_oriented_orthotropic_block_agrees_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let p = ply();
    let material = format!(
        "[[materials]]\nname = \"ply\"\northotropic = {{ e1 = {:e}, e2 = {:e}, e3 = {:e}, g12 = {:e}, g13 = {:e}, g23 = {:e}, nu12 = {}, nu13 = {}, nu23 = {} }}",
        p.young[0],
        p.young[1],
        p.young[2],
        p.shear[0],
        p.shear[1],
        p.shear[2],
        p.poisson[0],
        p.poisson[1],
        p.poisson[2]
    );
    let deck = uniform_stress_agrees("orthotropic", &block(&material));
    assert!(deck.contains("*ELASTIC, TYPE=ENGINEERING CONSTANTS\n1.400000000000e11, 1.000000000000e10"), "{deck}");
    assert!(deck.contains("*ORIENTATION, NAME=OM_PLY_30") && deck.contains(", ORIENTATION=OM_PLY_30"));
}

/// A fully anisotropic stiffness (the ply turned 40° about a skew axis, given
/// as `stiffness = [[…]]`: every coupling non-zero in its own axes), in the
/// same tilted frame: exported as the 21 `*ELASTIC, TYPE=ANISO` constants,
/// whose order and shear convention this checks.
#[test]
fn a_fully_anisotropic_block_agrees_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let c = Frame::ply([0.0, 1.0, 0.3], [0.5, 0.2, 1.0], 40f64.to_radians())
        .unwrap()
        .stiffness_to_global(&ply().stiffness().unwrap());
    let rows: Vec<String> =
        c.iter().map(|r| format!("[{}]", r.iter().map(|v| format!("{v:e}")).collect::<Vec<_>>().join(", "))).collect();
    let material = format!("[[materials]]\nname = \"ply\"\nstiffness = [{}]", rows.join(", "));
    let deck = uniform_stress_agrees("aniso", &block(&material));
    assert!(deck.contains("*ELASTIC, TYPE=ANISO\n"), "{deck}");
}

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name))
        .unwrap()
}

/// The CalculiX twin of examples/sandwich_indentation.toml at refine 1
/// (C3D20R from `ccx::mesh`, one per Lagrange interval: 2 × 2 per L9
/// element, 3 per B4 element): the skins as engineering constants in their
/// axes (`*ORIENTATION`), one element set per material, the skin–core
/// interface nodes tied by equations (`ccx::interfaces`). The 3D run
/// itself is `the_sandwich_indentation_agrees_with_calculix` (validation).
const SANDWICH_CARDS: [&str; 5] = [
    "*ELASTIC, TYPE=ENGINEERING CONSTANTS\n1.400000000000e11, 1.000000000000e10, 1.000000000000e10",
    "*ORIENTATION, NAME=OM_SKIN_0, SYSTEM=RECTANGULAR\n0.000000000000e0, 1.000000000000e0, 0.000000000000e0, -1.000000000000e0",
    "*SOLID SECTION, ELSET=BM_BEAM_1, MATERIAL=M_FOAM\n",
    "*SOLID SECTION, ELSET=BM_BEAM_2, MATERIAL=M_SKIN_0, ORIENTATION=OM_SKIN_0\n",
    "*EQUATION\n2\n",
];

#[test]
fn the_sandwich_deck_holds_orientations_materials_and_ties() {
    let dir = common::scratch_dir("ccx_laminate", "sandwich_deck");
    let model = dir.join("sandwich.toml");
    std::fs::write(&model, example("sandwich_indentation.toml")).unwrap();
    let deck = dir.join("deck");
    let run = common::cufem()
        .args(["export-ccx", model.to_str().unwrap(), "--out", deck.to_str().unwrap(), "--refine", "1"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let deck = std::fs::read_to_string(deck.join("model.inp")).unwrap();
    for card in SANDWICH_CARDS {
        assert!(deck.contains(card), "no {card:?} in the deck");
    }
}

/// `cufem verify` on examples/sandwich_indentation.toml (3 × 6 L9 × 14 B4,
/// 11,739 DOF) against its 3D twin at refine 1 (3,024 C3D20R, 49,221 DOF;
/// the deck: `the_sandwich_deck_holds_orientations_materials_and_ties`).
/// The issue asks for the indenter's contact force and the core's σ_zz
/// under the indenter within 5 %; measured: force +0.15 %, σ_zz +1.9 %
/// (−0.3649 against −0.3721 MPa). At refine 2 CalculiX had not settled the
/// contact of the first increment after 25 iterations (an hour); on a
/// one-element-wide variant refine 1 and 2 give −0.376 and −0.373 MPa.
/// CalculiX takes 1.5–4 minutes here, so the comparison runs in the
/// validation (its figures are the `verify.sandwich.*` rows of the same
/// run in `bench/validate --steps verify`).
#[test]
#[ignore = "validate: slow — CalculiX on 49,221 DOF with contact (about 2 min)"]
fn the_sandwich_indentation_agrees_with_calculix() {
    if common::ccx_missing() {
        return;
    }
    let dir = common::scratch_dir("ccx_laminate", "sandwich");
    let out = common::verify(&dir, "sandwich", &example("sandwich_indentation.toml"), 1);
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let force = table["resultants"].as_array().unwrap().iter().find(|r| r["name"] == "cylinder").unwrap();
    let df = force["difference_percent"].as_f64().unwrap();
    let probe = table["probes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["probe"] == "core_under_indenter" && r["quantity"] == "s_zz")
        .unwrap();
    let ds = probe["difference_percent"].as_f64().unwrap();
    eprintln!(
        "contact force {force}
core σ_zz {probe}"
    );
    assert!(df.abs() < 5.0, "contact force differs by {df} %");
    assert!(ds.abs() < 5.0, "core σ_zz under the indenter differs by {ds} %");
    let deck = std::fs::read_to_string(out.join("verify/ccx/model.inp")).unwrap();
    for card in SANDWICH_CARDS {
        assert!(deck.contains(card), "no {card:?} in the deck");
    }
}
