//! The paper's small-strain examples with large deformation switched on
//! (issue 26: "the small-strain paper examples change by less than their
//! own 3D–cufem difference with the switch on"): each example run as
//! shipped and with `analysis.geometry = "nonlinear"`, `strain =
//! "logarithmic"` added (the block both with the paper's element and, as
//! shipped, with B-bar, which at finite strain projects ln J). The compact
//! bar and the block run in CI (seconds); the tube and the cantilevers are
//! run by `bench/validate` (step `slow`, about a minute and a half).
//!
//! The 3D–cufem differences are the README's (small strain, `cufem verify
//! examples/FILE.toml --refine N`); the 3D values with NLGEOM are from
//! `cufem verify` of the switched-on files (CalculiX 2.20, C3D20R,
//! `--refine 1`), stored here.

mod common;

use cufem::analysis::{self, Silent, Solution};
use cufem::setup::Model;

/// The example `name` with the paper's element (B-bar removed) as shipped
/// (`nonlinear = false`) or switched on.
fn example(name: &str, nonlinear: bool) -> (Model, Solution) {
    example_with(name, nonlinear, false)
}

/// [`example`], keeping the file's B-bar when `bbar`.
fn example_with(name: &str, nonlinear: bool, bbar: bool) -> (Model, Solution) {
    let path = format!("{}/examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut text = std::fs::read_to_string(&path).unwrap();
    if !bbar {
        text = text.replace("formulation = \"bbar\"\n", "");
    }
    if nonlinear {
        assert!(text.contains("\n[solver]"), "{name}: no [solver] table to put [analysis] before");
        text = text.replacen(
            "\n[solver]",
            "\n[analysis]\ngeometry = \"nonlinear\"\nstrain = \"logarithmic\"\n\n[solver]",
            1,
        );
    }
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none(), "{name}: {:?}", sol.failure);
    (model, sol)
}

/// The largest force component of indenter or contact `name`.
fn force((_, sol): &(Model, Solution), name: &str) -> f64 {
    sol.contact(name).unwrap().force.iter().copied().fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a })
}

/// Stress component `k` at probe `name`.
fn probe_stress((model, sol): &(Model, Solution), name: &str, k: usize) -> f64 {
    let probe = model.probes.iter().find(|p| p.name == name).unwrap();
    sol.fields(model).sample_probe(probe).unwrap().stress[k]
}

fn change(a: f64, b: f64) -> f64 {
    (b / a - 1.0).abs()
}

/// Compact bar (16 L9): σ_yy at the contact centre within 1.7 % of 3D in
/// small strain; the switch moves it by 0.03 % (measured) and the roller
/// force by 0.08 %; against CalculiX with NLGEOM (172.20 N) the switched-on
/// roller force is +0.03 %.
#[test]
fn compact_bar_changes_less_than_its_3d_difference() {
    let (small, large) = (example("bending_compact_16L9", false), example("bending_compact_16L9", true));
    let s = change(probe_stress(&small, "contact_centre", 1), probe_stress(&large, "contact_centre", 1));
    let f = force(&large, "load");
    common::figure("switch_on.compact.s_yy_change", 100.0 * s, "%", "< 1.7 % (the small-strain difference from 3D)");
    assert!(s < 0.017, "{s}");
    common::within("switch_on.compact.force_vs_nlgeom", f, -172.20, 0.005, "CalculiX NLGEOM, refine 1 (172.20 N)");
}

/// Thin-walled tube (28 L9): roller force −3.45 % and σ_yy +13 % from 3D in
/// small strain; the switch moves them by −1.68 % and +3.7 % (measured).
/// Against CalculiX with NLGEOM (1,677.8 N) the switched-on roller force is
/// −3.9 % (and −6.3 % with the Green–Lagrange strain, whose run warns).
#[test]
#[ignore = "validate: slow — the tube with and without nonlinear geometry (about a minute)"]
fn tube_changes_less_than_its_3d_difference() {
    let (small, large) = (example("bending_tube_28L9", false), example("bending_tube_28L9", true));
    let f = change(force(&small, "load"), force(&large, "load"));
    let s = change(probe_stress(&small, "contact_centre", 1), probe_stress(&large, "contact_centre", 1));
    common::figure("switch_on.tube.force_change", 100.0 * f, "%", "< 3.45 % (the small-strain difference from 3D)");
    common::figure("switch_on.tube.s_yy_change", 100.0 * s, "%", "< 13 % (the small-strain difference from 3D)");
    assert!(f < 0.0345 && s < 0.13, "{f} {s}");
    let d = 100.0 * (force(&large, "load") / -1677.8 - 1.0);
    common::known_limit("switch_on.tube.force_vs_nlgeom", d, "%", -4.1, -3.7, "roller force against CalculiX NLGEOM");
}

/// Two cantilevers (our layout): σ_yy at the roller-line probes +29 % and
/// +15 % from 3D, the 7 in roller +1.9 % in small strain; the switch moves
/// them by 0.5 %, 0.4 % and 0.4 % (measured), the 9 in roller and the
/// beams' contact force by 0.3 % and 0.6 %.
#[test]
#[ignore = "validate: slow — the cantilevers with and without nonlinear geometry (about half a minute)"]
fn cantilevers_change_less_than_their_3d_difference() {
    let (small, large) = (example("cantilevers_contact", false), example("cantilevers_contact", true));
    let p1 = change(probe_stress(&small, "y_177.8mm", 1), probe_stress(&large, "y_177.8mm", 1));
    let p2 = change(probe_stress(&small, "y_228.6mm", 1), probe_stress(&large, "y_228.6mm", 1));
    let r = change(force(&small, "indenter_7in"), force(&large, "indenter_7in"));
    common::figure(
        "switch_on.cantilevers.probe1_change",
        100.0 * p1,
        "%",
        "< 29 % (the small-strain difference from 3D)",
    );
    common::figure(
        "switch_on.cantilevers.probe2_change",
        100.0 * p2,
        "%",
        "< 15 % (the small-strain difference from 3D)",
    );
    common::figure(
        "switch_on.cantilevers.force_change",
        100.0 * r,
        "%",
        "< 1.9 % (the small-strain difference from 3D)",
    );
    assert!(p1 < 0.29 && p2 < 0.15 && r < 0.019, "{p1} {p2} {r}");
}

/// Block with the paper's element (no B-bar: small-strain only): punch
/// force +8.0 % from 3D in small strain; the switch moves it by +1.0 %
/// (measured; −4.1 % with the Green–Lagrange strain, 5.5 % plastic strain
/// at the punch edge).
#[test]
fn block_changes_less_than_its_3d_difference() {
    let (small, large) = (example("block_indentation", false), example("block_indentation", true));
    let f = change(force(&small, "punch"), force(&large, "punch"));
    common::figure("switch_on.block.force_change", 100.0 * f, "%", "< 8 % (the small-strain difference from 3D)");
    assert!(f < 0.08, "{f}");
}

/// Block as shipped (B-bar, projected fields): punch force −1.05 % from 3D
/// in small strain (1.3954 against 1.4102 MN). Switched on, B-bar projects
/// the logarithmic dilatation; against CalculiX with NLGEOM (1.4238 MN,
/// `--refine 2`, docs/cross-check.md) the punch force is −0.59 % (measured
/// 1.4154 MN), where the paper's element is +8.0 %. The switch itself moves
/// it by +1.4 %, as it moves the 3D force by +1.0 %.
#[test]
fn block_with_bbar_matches_3d_with_nlgeom() {
    let large = example_with("block_indentation", true, true);
    let source = "CalculiX NLGEOM, refine 2 (1.4238 MN); less than the small-strain difference, 1.05 %";
    common::within("switch_on.block_bbar.force_vs_nlgeom", force(&large, "punch"), -1.4238e6, 0.0105, source);
}
