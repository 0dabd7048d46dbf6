//! Penalty-independent contact enforcement (issue 9, item 2): with an
//! augmented Lagrangian the penalty changes the cost, not the answer.

mod common;

use std::path::Path;

use cufem::analysis::{self, Silent, Solution};
use cufem::setup::Model;

/// The block of `examples/block_indentation.toml` made elastic, its punch
/// pushed 0.1 mm, with the given extra indenter keys.
fn punch(keys: &str) -> (Model, Solution) {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/block_indentation.toml"))
        .unwrap()
        .replace("plasticity = { yield_stress = 100e6, hardening = \"perfect\" }\n", "")
        .replace("increments = 20", "increments = 2")
        .replace("displacement = [0.0, 0.0, -1.0e-3]", &format!("displacement = [0.0, 0.0, -0.1e-3]\n{keys}"));
    assert!(!text.contains("plasticity = ") && text.contains("-0.1e-3"));
    let model = Model::parse(&text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    // the pure penalty at a factor of 1 lets the punch sink 23 % of its
    // 0.1 mm travel into the block (16.7 % low in force): the one case the
    // soft-penalty warning must name
    let soft = keys == "penalty_factor = 1.0";
    let named = sol.warnings.iter().map(|w| w.key.as_str()).collect::<Vec<_>>();
    let expected: &[&str] = if soft { &["indenters[0].penalty_factor"] } else { &[] };
    assert!(sol.failure.is_none() && named == expected, "{keys}: {:?} {:?}", sol.failure, sol.warnings);
    (model, sol)
}

/// Pure penalty: the punch force depends on the penalty (measured, two
/// increments: 4.4306e5 N at penalty_factor 1, 5.3050e5 N at 100, i.e.
/// −16.7 % and −0.22 % of the augmented answer). Augmented Lagrangian with
/// a penetration tolerance of 1e-10 m: 5.31680691e5 and 5.31680707e5 N (3e-8
/// apart; asserted 1e-6) and 5.31680711e5 N at 1000 (three decades),
/// penetration 9.1e-11, 4.0e-11 and 2.3e-11 m, the
/// pure-penalty forces approaching it from below. Cost: 60, 6 and 4 Newton
/// iterations against 2 (the soft penalty needs ~30 augmentations per
/// increment): the penalty now sets the cost, not the answer.
#[test]
fn augmented_lagrangian_makes_the_answer_independent_of_the_penalty() {
    let force = |s: &Solution| -s.contact("punch").unwrap().force[2];
    let pen = |s: &Solution| s.contact("punch").unwrap().max_penetration;
    let (_, soft) = punch("penalty_factor = 1.0");
    let (_, stiff) = punch("penalty_factor = 100.0");
    let (_, soft_al) = punch("penalty_factor = 1.0\npenetration_tolerance = 1e-10");
    let (_, stiff_al) = punch("penalty_factor = 100.0\npenetration_tolerance = 1e-10");
    // three decades: also a penalty ten times the default
    let (_, stiffest_al) = punch("penalty_factor = 1000.0\npenetration_tolerance = 1e-10");
    // the penalty moves the pure-penalty answer
    let check = "|difference| > 0.1 % (pure penalty depends on ε)";
    common::figure("augmented.pure_penalty_1_vs_100", 100.0 * (force(&soft) / force(&stiff) - 1.0), "%", check);
    assert!((force(&soft) / force(&stiff) - 1.0).abs() > 1e-3, "pure penalty did not depend on ε");
    // and not the augmented one
    let check = "< 1e-6 (the augmented answer does not depend on ε)";
    let apart = |a: &Solution, b: &Solution| (force(a) / force(b) - 1.0).abs();
    common::figure("augmented.penalty_1_vs_100", apart(&soft_al, &stiff_al), "", check);
    common::figure("augmented.penalty_1_vs_1000", apart(&soft_al, &stiffest_al), "", check);
    assert!(apart(&soft_al, &stiff_al) < 1e-6);
    assert!(apart(&soft_al, &stiffest_al) < 1e-6);
    let iterations = |s: &Solution| s.increments.iter().map(|i| i.newton.iterations).sum::<usize>() as f64;
    for (id, s) in
        [("penalty_1", &soft), ("penalty_100", &stiff), ("augmented_1", &soft_al), ("augmented_100", &stiff_al)]
    {
        common::figure(&format!("augmented.iterations.{id}"), iterations(s), "", "reported");
    }
    assert!(pen(&soft_al) <= 1e-10 && pen(&stiff_al) <= 1e-10 && pen(&stiffest_al) <= 1e-10);
    // penalty forces approach the augmented (rigid-contact) one from below
    let check = "below the augmented force (the penalty forces approach it from below)";
    common::figure(
        "augmented.pure_penalty_1_vs_augmented",
        100.0 * (force(&soft) / force(&stiff_al) - 1.0),
        "%",
        check,
    );
    assert!(force(&soft) < force(&stiff) && force(&stiff) < force(&stiff_al) * (1.0 + 1e-9));
}
