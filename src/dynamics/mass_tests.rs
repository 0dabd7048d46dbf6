//! The mass matrix against closed forms: the mass of the body (a rigid
//! translation) and the kinetic energy of polynomial velocity fields.

use super::*;
use crate::mesh::{BeamAxis, Body, CrossSection, Division};
use crate::shape::{BeamElementKind, SectionElementKind};

/// A straight-edged quadrilateral section (a bilinear map; area by the
/// shoelace formula) swept along y over [0.1, 0.13] m.
const CORNERS: [[f64; 2]; 4] = [[0.0, 0.0], [0.012, 0.001], [0.010, 0.011], [-0.001, 0.009]];
const RHO: f64 = 7850.0;

fn body(section: SectionElementKind, axis: BeamElementKind, elements: usize) -> Body {
    let section = CrossSection::from_quads(section, &CORNERS, &[[0, 1, 2, 3]], "s").unwrap();
    let lines = Division::uniform(0.1, 0.13, elements).lines("y").unwrap();
    Body::new("b", section, BeamAxis::from_lines(axis, &lines), 0)
}

fn shoelace_area() -> f64 {
    let c = &CORNERS;
    0.5 * (0..4).map(|i| c[i][0] * c[(i + 1) % 4][1] - c[(i + 1) % 4][0] * c[i][1]).sum::<f64>()
}

/// `vᵀ M v` summed over the elements for the nodal velocities `v(a)` of
/// local node coordinates (upper triangle doubled off the diagonal).
fn energy(b: &Body, kind: MassKind, v: impl Fn([f64; 3]) -> [f64; 3]) -> f64 {
    let cells = CellValues::new(b).unwrap();
    let mut ws = Workspace::default();
    let mut nodes = Vec::new();
    let mut total = 0.0;
    for e in 0..b.n_elements() {
        element_mass(&cells, e, b.section.n_elements(), RHO, kind, &mut ws);
        b.element_nodes(e, &mut nodes);
        let x: Vec<f64> = nodes.iter().flat_map(|&g| v(b.local_coords(g - b.node_offset))).collect();
        let n = x.len();
        for p in 0..n {
            for q in p..n {
                let k = ws.tangent[p * n + q];
                total += if p == q { k * x[p] * x[q] } else { 2.0 * k * x[p] * x[q] };
            }
        }
    }
    total
}

/// A rigid translation carries the body's mass, `ρ A L` (A by the shoelace
/// formula), to round-off, for every element pair and both matrices.
#[test]
fn a_rigid_translation_carries_the_mass_of_the_body() {
    let mass = RHO * shoelace_area() * 0.03;
    for (s, a) in [
        (SectionElementKind::L4, BeamElementKind::B2),
        (SectionElementKind::L9, BeamElementKind::B3),
        (SectionElementKind::L16, BeamElementKind::B4),
    ] {
        let b = body(s, a, 3);
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            for dir in 0..3 {
                let t = energy(&b, kind, |_| std::array::from_fn(|c| f64::from(u8::from(c == dir))));
                assert!((t - mass).abs() < 1e-12 * mass, "{s:?} {a:?} {kind:?} direction {dir}: {t} against {mass}");
            }
        }
    }
}

/// The consistent matrix integrates the kinetic energy of any velocity the
/// element represents exactly: for `v = ((y − y₀)ᵏ, 0, 0)` over the prism,
/// `∫ ρ (y − y₀)²ᵏ dV = ρ A ℓ^(2k+1) / (2k + 1)`, with `k = 1` on B2 and
/// `k = 2` on B3 and B4. Row-sum lumping is the Newton–Cotes rule of the
/// nodes, exact only to degree 1 (B2) or 3 (B3, B4), so it misses these:
/// a lumped matrix in place of the consistent one, or a wrong weight, fails.
#[test]
fn the_consistent_mass_integrates_the_kinetic_energy_exactly() {
    let length = 0.03f64;
    for (a, k) in [(BeamElementKind::B2, 1), (BeamElementKind::B3, 2), (BeamElementKind::B4, 2)] {
        let exact = RHO * shoelace_area() * length.powi(2 * k + 1) / (2 * k + 1) as f64;
        let b = body(SectionElementKind::L9, a, 2);
        let v = |p: [f64; 3]| [(p[1] - 0.1).powi(k), 0.0, 0.0];
        let t = energy(&b, MassKind::Consistent, v);
        assert!((t - exact).abs() < 1e-12 * exact, "{a:?}: {t} against {exact}");
        let lumped = energy(&b, MassKind::Lumped, v);
        assert!((lumped - exact).abs() > 1e-3 * exact, "{a:?}: lumped {lumped} equals the consistent {exact}");
    }
}

/// Every lumped nodal mass is positive and equals `∫ ρ N_a dV`: on an
/// affine B3 element of length h the end nodes carry ⅙ and the middle
/// node ⅔ of each section node's share (Simpson's weights).
#[test]
fn lumped_masses_are_the_newton_cotes_weights() {
    let b = body(SectionElementKind::L4, BeamElementKind::B3, 1);
    let cells = CellValues::new(&b).unwrap();
    let mut ws = Workspace::default();
    element_mass(&cells, 0, 1, RHO, MassKind::Lumped, &mut ws);
    let n = 3 * b.nodes_per_element();
    let mass = RHO * shoelace_area() * 0.03;
    // nodes a = i · 4 + τ: the axis node i's share of the mass
    let share: Vec<f64> = (0..3)
        .map(|i| (0..4).map(|t| ws.tangent[(3 * (4 * i + t)) * n + 3 * (4 * i + t)]).sum::<f64>() / mass)
        .collect();
    for (got, want) in share.iter().zip([1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]) {
        assert!((got - want).abs() < 1e-12, "{share:?}");
    }
    for p in 0..n {
        assert!(ws.tangent[p * n + p] > 0.0);
    }
}

/// The mass couples a node's displacement component only with the same
/// component of the other nodes (`M = ∫ ρ Nᵀ N` with `N` the same scalar
/// basis for x, y and z): every entry between two different components is
/// zero, for both matrices. The inertia keeps `M`'s non-zero entries only
/// (`LowerCsc::compress`: a third of the structure's pattern), so a
/// coupling term here would be dropped there.
#[test]
fn the_mass_couples_equal_components_only() {
    let b = body(SectionElementKind::L9, BeamElementKind::B3, 2);
    let cells = CellValues::new(&b).unwrap();
    let mut ws = Workspace::default();
    let n = 3 * b.nodes_per_element();
    for kind in [MassKind::Consistent, MassKind::Lumped] {
        element_mass(&cells, 0, b.section.n_elements(), RHO, kind, &mut ws);
        let mut same = 0;
        for p in 0..n {
            for q in 0..n {
                let m = ws.tangent[p * n + q];
                if p % 3 != q % 3 {
                    assert_eq!(m, 0.0, "{kind:?}: entry ({p}, {q})");
                } else if m != 0.0 {
                    same += 1;
                }
            }
        }
        assert!(same >= n, "{kind:?}: {same} non-zero entries");
    }
}
