//! Linear elements take their internal force as a product with the elastic
//! stiffness assembled at setup and form their stresses only when read
//! (`analysis::structure::elements`, `assembly::ElasticProduct`). Each
//! model here runs twice: with a purely elastic material (the product) and
//! with the same material given a yield stress it never reaches (the Gauss
//! loop of every evaluation). The same physics both ways, so everything a
//! run reports must agree within Newton's tolerances: displacements, reactions at the
//! fixed DOFs (the product's rows of `K₀` there), stresses at every frame
//! and at the end, the transient energy ledger's strain energy (`½ uᵀ f`
//! against the Gauss sum `½ ∫ σᵀ C⁻¹ σ`) and each step end of a static
//! history. (The stresses a buckling analysis forms its geometric stiffness
//! from are read the same way; examples/column_buckling.toml's test holds
//! its critical load to Euler's.)

use cufem::analysis::Solution;

mod common;

/// `model` with its material `name = "m"` as written (elastic), and the
/// same with a yield stress of 1 GPa (never reached in these models: asserted).
fn both_ways(model: &str) -> (Solution, Solution) {
    let yielding = model.replace(
        "poisson_ratio = 0.3\n",
        "poisson_ratio = 0.3\nplasticity = { yield_stress = 1e9, hardening = \"perfect\" }\n",
    );
    assert_ne!(yielding, model, "the material block is found");
    let (product, gauss) = (common::run(model), common::run(&yielding));
    assert!(gauss.history.iter().all(|r| r.plastic_points == 0), "the yield stress is never reached");
    (product, gauss)
}

/// Largest difference of `a` and `b` relative to the largest `|a|`.
fn relative(a: impl IntoIterator<Item = f64> + Clone, b: impl IntoIterator<Item = f64>) -> f64 {
    let scale = a.clone().into_iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0, "compared values are not all zero");
    a.into_iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

fn flat(stresses: &[[f64; 6]]) -> impl Iterator<Item = f64> + Clone + '_ {
    stresses.iter().flatten().copied()
}

/// Newton's tolerances of the models here, a hundred times below the
/// default: the two runs stop at different iterates within them, so the
/// comparison is as strict as they are (at 1e-9 the thin channel's residual
/// meets its round-off floor, ~3e-10, and the unloading step stalls).
const TIGHT: &str = "[solver]\nresidual_tolerance = 1e-8\ndisplacement_tolerance = 1e-8\n\n";

/// The largest relative difference allowed: a hundred times the
/// tolerances (measured: at most 3.4e-9 over the transient run, 1.6e-7 at
/// the static history's second step end; a dropped term or stale stresses
/// differ by order one).
const AGREE: f64 = 1e-6;

const CHANNEL: &str = r#"
[analysis]
type = "transient"
output_interval = 2e-4

[[materials]]
name = "m"
young_modulus = 70e9
poisson_ratio = 0.3
density = 2700.0

[[bodies]]
name = "channel"
material = "m"
section = { shape = "channel", element = "L9", origin = [0.0, -0.05], width = 0.05, height = 0.1, web_thickness = 0.002, flange_thickness = 0.002, along_flange = 1, along_web = 2, through = 1 }
axis = { element = "B4", from = 0.0, to = 1.0, elements = 4 }

[[constraints]]
name = "root"
body = "channel"
where = { y = 0.0 }
fix = ["x", "y", "z"]

[[loads]]
name = "blow"
body = "channel"
where = { y = 1.0, region = "top_flange" }
total_force = [0.0, 0.0, -1e3]

[[steps]]
name = "rise"
factor = 1.0
duration = 5e-4
increments = 5

[[steps]]
name = "free"
factor = 0.0
duration = 1e-3
increments = 8

[[probes]]
name = "tip"
point = [0.05, 1.0, 0.049]
"#;

/// An elastic channel struck at its tip (a small bench/channel_hammer.toml):
/// the same corrections, history, reactions, frames, end stresses and
/// energy ledger with the product (and its constant tangent) as with the
/// Gauss loop.
#[test]
fn a_linear_transient_run_agrees_with_the_gauss_loop() {
    let (product, gauss) = both_ways(&format!("{TIGHT}{CHANNEL}"));
    assert_eq!(product.history.len(), gauss.history.len());
    // no more corrections at any step: the product's run keeps its
    // tangent while the time step stays (analysis::structure::evaluation,
    // a constant tangent) and forms it again where the step changes (100 µs
    // while the force rises, 125 µs in free vibration); one kept across
    // that change would cost corrections there. (The run of the material
    // that may yield takes four at its first step, its residual falling
    // about fiftyfold a correction, where the elastic one takes one.)
    let iterations = |s: &Solution| s.history.iter().map(|r| r.iterations).collect::<Vec<_>>();
    let (p, g) = (iterations(&product), iterations(&gauss));
    assert!(p.iter().zip(&g).all(|(a, b)| a <= b), "corrections per step: {p:?} against {g:?}");
    let tip = |s: &Solution| s.history.iter().map(|r| r.probes[0][2]).collect::<Vec<_>>();
    assert!(relative(tip(&product), tip(&gauss)) < AGREE, "tip u_z history");
    // the root's reaction at every step: the fixed DOFs' rows of K₀
    let root = |s: &Solution| s.history.iter().flat_map(|r| r.reactions[0].force).collect::<Vec<_>>();
    assert!(relative(root(&product), root(&gauss)) < AGREE, "root reactions");
    assert!(relative(product.u.iter().copied(), gauss.u.iter().copied()) < AGREE);
    assert!(relative(flat(&gauss.stresses), flat(&product.stresses)) < AGREE, "end stresses");
    assert_eq!(product.frames.len(), gauss.frames.len());
    assert!(product.frames.len() >= 5, "{} frames", product.frames.len());
    for (p, g) in product.frames.iter().zip(&gauss.frames) {
        assert!(relative(flat(&g.fields.stresses), flat(&p.fields.stresses)) < AGREE, "frame at {} s", g.time);
    }
    let (pe, ge) = (product.energy.unwrap(), gauss.energy.unwrap());
    assert_eq!(pe.len(), ge.len());
    let elastic = |rows: &[cufem::dynamics::energy::EnergyRow]| rows.iter().map(|r| r.elastic).collect::<Vec<_>>();
    assert!(relative(elastic(&ge), elastic(&pe)) < AGREE, "strain energy of the ledger");
    let internal = |rows: &[cufem::dynamics::energy::EnergyRow]| rows.iter().map(|r| r.internal).collect::<Vec<_>>();
    assert!(relative(internal(&ge), internal(&pe)) < AGREE, "internal work of the ledger");
}

/// The channel loaded statically at its tip, then unloaded by half, over
/// a history of two steps: the same displacements, reactions and stresses
/// at each step end.
#[test]
fn a_linear_static_history_agrees_with_the_gauss_loop() {
    let start = CHANNEL.find("[[materials]]").unwrap();
    let end = CHANNEL.find("[[steps]]").unwrap();
    let model = format!(
        "[analysis]\ntype = \"static\"\n{TIGHT}{}{}",
        &CHANNEL[start..end],
        "[[steps]]\nname = \"load\"\nfactor = 1.0\nincrements = 2\n\n[[steps]]\nname = \"half\"\nfactor = 0.5\nincrements = 1\n"
    );
    let (product, gauss) = both_ways(&model);
    assert_eq!(product.steps.len(), 2);
    for (p, g) in product.steps.iter().zip(&gauss.steps) {
        let (pf, gf) = (p.fields.as_ref().unwrap(), g.fields.as_ref().unwrap());
        assert!(relative(gf.u.iter().copied(), pf.u.iter().copied()) < AGREE, "u at {}", g.name);
        assert!(relative(flat(&gf.stresses), flat(&pf.stresses)) < AGREE, "stresses at {}", g.name);
        assert!(relative(g.reactions[0].force, p.reactions[0].force) < AGREE, "reaction at {}", g.name);
    }
}
