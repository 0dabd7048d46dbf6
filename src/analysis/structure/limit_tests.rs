//! The contacts' step limit (`contact::assembly::limit`) and their
//! releasing evaluations (`Contacts::only_released`) on the contacts of a
//! model: points set open or in contact by hand, corrections made up.
//! Here and not beside the limit because the contact module must not
//! import the model reader (tests/architecture.rs).

use crate::contact::Contacts;
use crate::contact::assembly::SMALLEST_FRACTION;
use crate::setup::Model;

/// Two stacked blocks (a node pair contact between them, normal +z on
/// the upper one) under a flat rigid punch on the upper one's top.
const MODEL: &str = r#"
[analysis]
geometry = "nonlinear"

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "lower"
material = "steel"
section = { shape = "rectangle", element = "L4", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.0, to = 0.01, elements = 1 } }
axis = { element = "B2", from = 0.0, to = 0.03, elements = 1 }

[[bodies]]
name = "upper"
material = "steel"
section = { shape = "rectangle", element = "L4", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.01, to = 0.02, elements = 1 } }
axis = { element = "B2", from = 0.0, to = 0.03, elements = 1 }

[[constraints]]
name = "base"
body = "lower"
where = { z = 0.0 }
fix = ["x", "y", "z"]

[[constraints]]
name = "sides"
body = "upper"
where = { x = 0.0 }
fix = ["x", "y"]

[[indenters]]
name = "punch"
body = "upper"
shape = "flat"
normal = "-z"
position = 0.02
surface = { z = 0.02 }
displacement = [0.0, 0.0, -1e-5]

[[contacts]]
name = "interface"
master = { body = "lower", where = { z = 0.01 } }
slave = { body = "upper", where = { z = 0.01 } }
"#;

/// Sets every point's gap, activity and normal (the punch's points
/// face −z into the upper body, the pairs' +z).
fn contacts_with<'m>(model: &'m Model, gaps: &[f64]) -> Contacts<'m> {
    let mut c = Contacts::new(&model.mesh, &model.indenters, &model.contacts, true);
    let n_punch = model.indenters[0].nodes.len();
    for (k, (p, &g)) in c.points_mut().iter_mut().zip(gaps).enumerate() {
        p.gap = g;
        p.active = g <= 0.0;
        p.normal = if k < n_punch { [0.0, 0.0, -1.0] } else { [0.0, 0.0, 1.0] };
    }
    c
}

#[test]
fn an_open_point_stops_at_the_depth_of_the_deepest_in_contact() {
    let model = Model::parse(MODEL).unwrap();
    let punch: Vec<usize> = model.indenters[0].nodes.iter().map(|c| c.node).collect();
    let pairs = &model.contacts[0].pairs;
    assert_eq!((punch.len(), pairs.len()), (4, 4));
    let n = model.mesh.n_dofs();
    // punch point 0 in contact 1 µm deep, point 1 open by 2 µm and moved
    // 10 µm up into the punch: stops 1 µm deep, α = 3/10
    let mut gaps = vec![5e-6; 8];
    gaps[0] = -1e-6;
    gaps[1] = 2e-6;
    let c = contacts_with(&model, &gaps);
    let mut du = vec![0.0; n];
    du[3 * punch[1] + 2] = 1e-5;
    let alpha = c.step_limit(|d| du[d]);
    assert!((alpha - 0.3).abs() < 1e-12, "{alpha}");
    // not in small strain (the same points, evaluated in the reference
    // configuration)
    let mut small = Contacts::new(&model.mesh, &model.indenters, &model.contacts, false);
    small.points_mut().clone_from_slice(c.points());
    assert_eq!(small.step_limit(|d| du[d]), 1.0);
    // nor with friction (the same points, the punch frictional)
    let text = MODEL.replace("displacement = [0.0, 0.0, -1e-5]", "displacement = [0.0, 0.0, -1e-5]\nfriction = 0.3");
    let frictional = Model::parse(&text).unwrap();
    let mut rough = Contacts::new(&frictional.mesh, &frictional.indenters, &frictional.contacts, true);
    rough.points_mut().clone_from_slice(c.points());
    assert_eq!(rough.step_limit(|d| du[d]), 1.0);
    // the point in contact is not limited, however deep it goes
    du[3 * punch[1] + 2] = 0.0;
    du[3 * punch[0] + 2] = 1e-3;
    assert_eq!(c.step_limit(|d| du[d]), 1.0);
    // moving away from the punch: no limit
    du[3 * punch[0] + 2] = 0.0;
    du[3 * punch[1] + 2] = -1e-3;
    assert_eq!(c.step_limit(|d| du[d]), 1.0);
    // a pair closes by the relative motion only: slave down 4 µm onto a
    // master that rises 4 µm, open by 5 µm, stops 1 µm deep (α = 6/8);
    // both moving down together leaves it open
    du.fill(0.0);
    let (slave, master) = (pairs[0].slave, pairs[0].master);
    du[3 * slave + 2] = -4e-6;
    du[3 * master + 2] = 4e-6;
    let alpha = c.step_limit(|d| du[d]);
    assert!((alpha - 0.75).abs() < 1e-12, "{alpha}");
    du[3 * master + 2] = -4e-6;
    assert_eq!(c.step_limit(|d| du[d]), 1.0);
}

#[test]
fn with_nothing_in_contact_open_points_stop_at_the_surface_and_round_off_does_not_stall() {
    let model = Model::parse(MODEL).unwrap();
    let punch: Vec<usize> = model.indenters[0].nodes.iter().map(|c| c.node).collect();
    let mut gaps = vec![5e-6; 8];
    gaps[2] = 4e-6;
    let c = contacts_with(&model, &gaps);
    let mut du = vec![0.0; model.mesh.n_dofs()];
    du[3 * punch[2] + 2] = 1e-5;
    let alpha = c.step_limit(|d| du[d]);
    assert!((alpha - 0.4).abs() < 1e-12, "{alpha}");
    // open by round-off while nothing is in contact: the smallest
    // fraction, not zero
    gaps[2] = 1e-18;
    let c = contacts_with(&model, &gaps);
    assert_eq!(c.step_limit(|d| du[d]), SMALLEST_FRACTION);
    // with a point in contact 1 nm deep, one open by 1 nm and closing by
    // 1 mm (a body held by nothing else in the tangent) stops 1 nm deep,
    // however small that makes α
    gaps[0] = -1e-9;
    gaps[2] = 1e-9;
    let c = contacts_with(&model, &gaps);
    du[3 * punch[2] + 2] = 1e-3;
    let alpha = c.step_limit(|d| du[d]);
    assert!((alpha / 2e-6 - 1.0).abs() < 1e-9, "{alpha}");
}

/// Which status changes make an evaluation releasing (`solver::newton`,
/// the releasing iterations): opens alone; not a close, not a point that
/// stays in contact and switches between stick and slip, not a flip at a
/// gap of round-off.
#[test]
fn only_points_opening_make_an_evaluation_releasing() {
    let model = Model::parse(MODEL).unwrap();
    // punch points 0–3, pair points 4–7; all in contact before
    let mut gaps = vec![-1e-6; 8];
    let before = vec![true; 8];
    gaps[5] = 2e-6;
    let c = contacts_with(&model, &gaps);
    assert!(c.only_released(&before, &[]));
    // nothing changed: not releasing
    assert!(!c.only_released(&c.points().iter().map(|p| p.active).collect::<Vec<_>>(), &[]));
    // point 2 closes while 5 opens
    let mut was = before.clone();
    was[2] = false;
    assert!(!c.only_released(&was, &[]));
    // a point opening at a gap of round-off alone is no release
    gaps[5] = 1e-20;
    assert!(!contacts_with(&model, &gaps).only_released(&before, &[]));
    // with friction: point 1 stays in contact and starts sliding
    gaps[5] = 2e-6;
    let mut c = contacts_with(&model, &gaps);
    c.points_mut()[1].sliding = true;
    assert!(!c.only_released(&before, &[false; 8]));
    assert!(c.only_released(&before, &[false, true, false, false, false, false, false, false]));
    // the opening point 5 was sliding: its switch does not count
    assert!(c.only_released(&before, &[false, true, false, false, false, true, false, false]));
}
