//! The cohesive law against its closed forms: the energy of a whole
//! separation is the toughness of its mixity (Benzeggagh–Kenane), onset lies
//! on the quadratic criterion, damage never heals, closed faces never pass
//! through each other, and the tangent is the derivative of the traction.

use super::*;

/// AS4/PEEK interface (Camanho, Dávila & de Moura 2003, *J. Compos. Mater.*
/// 37:1415): N = 80 MPa, S = 100 MPa, G_Ic = 969 J/m², G_IIc = 1719 J/m²,
/// η = 2.284; penalty 1e6 N/mm³ = 1e15 Pa/m (Camanho & Dávila 2002).
fn peek() -> Cohesive {
    Cohesive::new(1e15, 80e6, 100e6, 969.0, 1719.0, 2.284).unwrap()
}

/// Work `∫ t · dδ` per unit area along the straight path `s·direction`,
/// s from 0 to `end`, committing each step; and the state at the end.
fn work_along(law: &Cohesive, direction: [f64; 3], end: f64, steps: usize) -> (f64, CohesiveState) {
    let mut state = CohesiveState::default();
    let mut work = 0.0;
    let mut last = [0.0; 3];
    for i in 1..=steps {
        let s = end * i as f64 / steps as f64;
        let sep = direction.map(|c| c * s);
        let r = law.update(sep, &state);
        let ds = end / steps as f64;
        work += 0.5 * (0..3).map(|c| (last[c] + r.traction[c]) * direction[c] * ds).sum::<f64>();
        last = r.traction;
        state = r.state;
    }
    (work, state)
}

#[test]
fn a_whole_separation_dissipates_the_toughness_of_its_mixity() {
    let law = peek();
    // Pure mode I: the work of opening to full separation is G_Ic (the
    // triangle ½ N δf with δf = 2 G_Ic/N); pure mode II (sliding, faces in
    // touch) G_IIc; at equal sliding and opening (β = 1, G_II/G_T = ½) the
    // Benzeggagh–Kenane toughness 969 + 750·0.5^2.284 = 1122.5 J/m².
    let half = 0.5f64;
    let norm = half.sqrt();
    for (direction, expected) in [
        ([0.0, 0.0, 1.0], 969.0),
        ([1.0, 0.0, 0.0], 1719.0),
        ([0.0, 1.0, 0.0], 1719.0),
        ([norm, 0.0, norm], 969.0 + 750.0 * half.powf(2.284)),
    ] {
        let end = 1.2 * law.envelope(direction).last;
        let (work, state) = work_along(&law, direction, end, 40_000);
        assert!((work / expected - 1.0).abs() < 1e-4, "{direction:?}: work {work} J/m², expected {expected}");
        assert_eq!(state.damage, 1.0, "{direction:?}: fully separated");
        assert!(
            (state.dissipated / expected - 1.0).abs() < 1e-9,
            "{direction:?}: dissipated {} J/m²",
            state.dissipated
        );
    }
}

#[test]
fn onset_lies_on_the_quadratic_criterion() {
    let law = peek();
    // Camanho & Dávila's onset: (t3/N)² + (ts/S)² = 1 at δm = δm⁰ on the
    // linear branch, for every mixity.
    for beta in [0.0, 0.3, 1.0, 3.0, 20.0] {
        let dir = [beta, 0.0, 1.0];
        let len = (1.0f64 + beta * beta).sqrt();
        let onset = law.envelope(dir).onset;
        let sep = dir.map(|c| c / len * onset);
        let t = law.update(sep, &CohesiveState::default()).traction;
        let f = (t[2] / 80e6).powi(2) + (t[0] / 100e6).powi(2);
        assert!((f - 1.0).abs() < 1e-12, "β = {beta}: criterion {f}");
        // Just past onset the point is damaged, just before it is not.
        let after = law.update(sep.map(|c| c * 1.001), &CohesiveState::default());
        let before = law.update(sep.map(|c| c * 0.999), &CohesiveState::default());
        assert!(after.state.damage > 0.0 && before.state.damage == 0.0, "β = {beta}");
    }
}

#[test]
fn damage_never_heals_and_closed_faces_do_not_interpenetrate() {
    let law = peek();
    let e = law.envelope([0.0, 0.0, 1.0]);
    // Open halfway along the softening branch of mode I.
    let peak = 0.5 * (e.onset + e.last);
    let open = law.update([0.0, 0.0, peak], &CohesiveState::default());
    let d = open.state.damage;
    // d = δf(δ − δ0)/(δ(δf − δ0)) (Camanho & Dávila 2002, eq. 27).
    assert!((d - e.last * (peak - e.onset) / (peak * (e.last - e.onset))).abs() < 1e-14);
    // Unloading to half the opening: the secant, damage kept, nothing dissipated.
    let back = law.update([0.0, 0.0, 0.5 * peak], &open.state);
    assert_eq!(back.state, open.state);
    assert!((back.traction[2] - (1.0 - d) * 1e15 * 0.5 * peak).abs() < 1e-6 * back.traction[2]);
    assert!((back.tangent[2][2] - (1.0 - d) * 1e15).abs() < 1e-3);
    // Sliding of the damaged point is softened by the same damage.
    let slide = law.update([1e-7, 0.0, 0.5 * peak], &open.state);
    assert!((slide.traction[0] - (1.0 - d) * 1e15 * 1e-7).abs() < 1e-6 * slide.traction[0]);
    // Closing a fully separated point: the full penalty in compression.
    let broken = CohesiveState { damage: 1.0, dissipated: 969.0 };
    let shut = law.update([2e-7, 0.0, -1e-7], &broken);
    assert_eq!(shut.traction, [0.0, 0.0, -1e15 * 1e-7]);
    assert_eq!(shut.state, broken);
}

/// A fully separated pair at zero opening up to round-off (a specimen
/// unloaded: `δ3 ≈ ±10⁻¹⁷⁰` m) has one stiffness whatever the sign of the
/// round-off, the open one, so that a reopening frees the faces at once;
/// a closure of physical size, a penetration of `10⁻¹²` m (a pressure of
/// 1 kPa on this penalty), carries the full penalty.
#[test]
fn round_off_of_zero_opening_does_not_close_the_faces() {
    let law = peek();
    let broken = CohesiveState { damage: 1.0, dissipated: 969.0 };
    for tiny in [-4e-173, 0.0, 3e-171, -1e-19] {
        let r = law.update([0.0, 0.0, tiny], &broken);
        assert_eq!((r.traction[2], r.tangent[2][2]), (0.0, 0.0), "δ3 = {tiny:e}");
    }
    let shut = law.update([0.0, 0.0, -1e-12], &broken);
    assert_eq!((shut.traction[2], shut.tangent[2][2]), (-1e15 * 1e-12, 1e15));
}

#[test]
fn the_tangent_is_the_derivative_of_the_traction() {
    let law = peek();
    let e1 = law.envelope([0.0, 0.0, 1.0]);
    let e2 = law.envelope([1.0, 0.0, 0.0]);
    let fresh = CohesiveState::default();
    let damaged = law.update([0.0, 0.0, 0.5 * (e1.onset + e1.last)], &fresh).state;
    // Pure modes (where the held mixity is exact), on the elastic branch,
    // while damage grows and while unloading a damaged point, and in closure.
    let cases: [([f64; 3], CohesiveState); 6] = [
        ([0.3 * e1.onset, 0.2 * e1.onset, 0.5 * e1.onset], fresh),
        ([0.0, 0.0, 0.3 * (e1.onset + e1.last)], fresh),
        ([0.4 * (e2.onset + e2.last), 0.0, -1e-8], fresh),
        ([0.0, 0.3 * (e2.onset + e2.last), -1e-8], fresh),
        ([0.0, 0.0, 0.2 * (e1.onset + e1.last)], damaged),
        ([1e-7, 2e-7, -3e-7], damaged),
    ];
    for (sep, state) in cases {
        let r = law.update(sep, &state);
        for j in 0..3 {
            let h = 1e-7 * sep.iter().map(|c| c.abs()).fold(0.0, f64::max);
            let (mut up, mut down) = (sep, sep);
            up[j] += h;
            down[j] -= h;
            let (tu, td) = (law.update(up, &state).traction, law.update(down, &state).traction);
            for i in 0..3 {
                let fd = (tu[i] - td[i]) / (2.0 * h);
                assert!(
                    (fd - r.tangent[i][j]).abs() <= 1e-6 * 1e15,
                    "δ = {sep:?}, ∂t{i}/∂δ{j}: tangent {} against finite difference {fd}",
                    r.tangent[i][j]
                );
            }
        }
    }
}

#[test]
fn constants_that_cannot_work_are_refused_by_key() {
    assert_eq!(
        Cohesive::new(-1.0, 80e6, 100e6, 969.0, 1719.0, 2.0),
        Err(CohesiveError::NotPositive { key: "penalty", value: -1.0 })
    );
    assert!(matches!(
        Cohesive::new(1e15, 80e6, 100e6, 969.0, f64::NAN, 2.0),
        Err(CohesiveError::NotPositive { key: "g_iic", .. })
    ));
    // S²/(2K) = 1e16/2e12 = 5000 J/m² ≥ G_Ic: onset past the toughness.
    let err = Cohesive::new(1e12, 80e6, 100e6, 969.0, 1719.0, 2.0).unwrap_err();
    assert!(matches!(err, CohesiveError::OnsetAboveToughness { strength: "shear_strength", toughness: "g_ic", .. }));
    assert!(err.to_string().contains("`shear_strength`") && err.to_string().contains("`g_ic`"));
}

/// The onset index `(⟨t3⟩/N)² + (t_s/S)²` of the intact traction is 1
/// where the law starts to damage — on the envelope's onset separation of
/// every mixity (Camanho & Dávila's `δ_m⁰`, an independent closed form of
/// the same criterion), in closure at the shear onset — and grows as the
/// separation squared. Mutation: N and S swapped in the index gives
/// `(100/80)²` in pure opening.
#[test]
fn the_onset_index_is_one_on_the_onset_envelope() {
    let law = peek();
    let directions: [[f64; 3]; 6] =
        [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.6, 0.8, 0.0], [1.0, 0.0, 1.0], [0.3, 0.4, 2.0], [1.0, 0.0, -0.5]];
    for dir in directions {
        let norm = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2].max(0.0) * dir[2].max(0.0)).sqrt();
        let onset = law.envelope(dir).onset;
        let at = dir.map(|c| c * onset / norm);
        let index = law.onset_index(at);
        assert!((index - 1.0).abs() < 1e-12, "{dir:?}: {index}");
        assert!((law.onset_index(at.map(|c| 0.5 * c)) - 0.25).abs() < 1e-12, "{dir:?}");
        // the law's damage starts just past it, not before
        assert_eq!(law.update(at.map(|c| 0.999 * c), &CohesiveState::default()).state.damage, 0.0);
        assert!(law.update(at.map(|c| 1.001 * c), &CohesiveState::default()).state.damage > 0.0, "{dir:?}");
    }
}
