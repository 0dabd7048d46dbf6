//! Tests of the kinematic/combined return map (issue 10): finite-difference
//! tangent, uniaxial cyclic closed form, Voce.

use super::*;
use crate::materials::Material;

const E: f64 = 200e9;
const SY: f64 = 200e6;

/// Two Armstrong–Frederick back-stresses (Chaboche-style: a fast one that
/// saturates early and a slow, nearly linear one) with a constant yield
/// stress, or with Voce isotropic hardening.
fn chaboche(voce: bool) -> Material {
    let iso = if voce {
        Hardening::Voce { yield_stress: SY, saturation: 80e6, rate: 15.0 }
    } else {
        Hardening::Perfect { yield_stress: SY }
    };
    Material::new("steel", E, 0.3, Some(iso))
        .with_kinematic(vec![BackStress { modulus: 60e9, recall: 600.0 }, BackStress { modulus: 5e9, recall: 20.0 }])
}

/// Uniaxial stress path: ε_xx prescribed, the lateral strains solved so that
/// σ_yy = σ_zz = 0 (Newton on the lateral strain with the material tangent).
fn uniaxial(m: &Material, eps: f64, old: &PointState, lateral: &mut f64) -> Response {
    for _ in 0..60 {
        let r = m.update(&[eps, *lateral, *lateral, 0.0, 0.0, 0.0], old);
        if r.stress[1].abs() < 1e-9 * SY {
            return r;
        }
        *lateral -= r.stress[1] / (r.tangent[1][1] + r.tangent[1][2]);
    }
    panic!("uniaxial driver did not converge at ε = {eps}");
}

/// Largest relative difference between the tangent and central differences
/// of the stress (step 1e-8 on each engineering-strain component).
fn fd_error(m: &Material, strain: &Voigt, old: &PointState) -> f64 {
    let r = m.update(strain, old);
    let scale = r.tangent.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut worst = 0.0f64;
    for j in 0..6 {
        let h = 1e-9;
        let (mut ep, mut em) = (*strain, *strain);
        ep[j] += h;
        em[j] -= h;
        let (sp, sm) = (m.update(&ep, old).stress, m.update(&em, old).stress);
        for i in 0..6 {
            worst = worst.max(((sp[i] - sm[i]) / (2.0 * h) - r.tangent[i][j]).abs() / scale);
        }
    }
    worst
}

#[test]
fn consistent_tangent_matches_finite_differences_loading_and_reverse_loading() {
    // A committed state with back-stresses NOT parallel to the new flow
    // (non-proportional: the exact tangent is unsymmetric) and a plastic
    // history, then strain increments forward, reversed and sideways.
    for voce in [false, true] {
        let m = chaboche(voce);
        let mut old = PointState { peeq: 3e-3, ..PointState::default() };
        old.plastic_strain = [2e-3, -1e-3, -1e-3, 1e-3, 0.0, 0.0];
        old.back_stress[0] = [60e6, -30e6, -30e6, 20e6, 0.0, 5e6];
        old.back_stress[1] = [10e6, -4e6, -6e6, 0.0, 3e6, 0.0];
        let loads = [
            [5e-3, -1.5e-3, -1.5e-3, 2e-3, 0.0, 0.0],   // forward
            [-3e-3, 1.2e-3, 1.0e-3, -1e-3, 1e-3, 0.0],  // reversed
            [2e-3, -1e-3, 0.5e-3, 4e-3, -2e-3, 1.5e-3], // sideways
            [1e-2, -5e-3, -5e-3, 0.0, 0.0, 0.0],        // large
        ];
        for eps in &loads {
            let r = m.update(eps, &old);
            assert!(r.plastic, "voce {voce}: {eps:?} should yield");
            let err = fd_error(&m, eps, &old);
            assert!(err < 1e-6, "voce {voce}, {eps:?}: relative tangent error {err:e}");
        }
        // the non-proportional case really is unsymmetric (so the test
        // exercises the (P a) ⊗ b term)
        let t = m.update(&loads[2], &old).tangent;
        let asym = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .map(|(i, j)| (t[i][j] - t[j][i]).abs())
            .fold(0.0, f64::max);
        assert!(asym > 1e-4 * E, "tangent unexpectedly symmetric: {asym:e}");
    }
}

#[test]
fn returned_state_lies_on_the_shifted_yield_surface_and_flow_is_isochoric() {
    let m = chaboche(true);
    let r = m.update(&[8e-3, -2e-3, -1e-3, 3e-3, -1e-3, 2e-3], &PointState::default());
    let x: Voigt = std::array::from_fn(|c| r.state.back_stress[0][c] + r.state.back_stress[1][c]);
    let rel: Voigt = std::array::from_fn(|c| voigt::deviator(&r.stress)[c] - x[c]);
    let sy = m.hardening.as_ref().unwrap().eval(r.state.peeq).0;
    assert!((1.5f64.sqrt() * voigt::norm_stress(&rel) - sy).abs() < 1e-9 * sy);
    assert!(voigt::trace(&r.state.plastic_strain).abs() < 1e-15);
    assert!(voigt::trace(&x).abs() < 1e-6, "back-stress deviatoric");
}

/// Uniaxial back-stress of one term on a plastic branch (issue 10):
/// `X = ±C/γ + (X₀ ∓ C/γ) e^{∓γ(εp − εp₀)}`, upper signs in forward flow.
fn closed_form(bs: &BackStress, sign: f64, x0: f64, ep: f64, ep0: f64) -> f64 {
    sign * bs.modulus / bs.recall + (x0 - sign * bs.modulus / bs.recall) * (-sign * bs.recall * (ep - ep0)).exp()
}

#[test]
fn uniaxial_cyclic_loop_follows_the_closed_form_branch_by_branch() {
    for voce in [false, true] {
        let m = chaboche(voce);
        // strain-controlled loop 0 → +1 % → −1 % → +1 % in steps of 1e-4
        // (steps of 2.5e-4 on the first branch: the exponential integration
        // is exact for any step along a fixed direction)
        let mut path = Vec::new();
        path.extend((1..=40).map(|k| 2.5e-4 * k as f64));
        path.extend((1..=200).map(|k| 0.01 - 1e-4 * k as f64));
        path.extend((1..=200).map(|k| -0.01 + 1e-4 * k as f64));
        let mut state = PointState::default();
        let mut lateral = 0.0;
        let (mut sign, mut x0, mut ep0) = (1.0, [0.0; 2], 0.0);
        let mut prev = 0.0;
        let mut branches = 0;
        let mut checked = 0;
        for &eps in &path {
            let direction = if eps > prev { 1.0 } else { -1.0 };
            prev = eps;
            let r = uniaxial(&m, eps, &state, &mut lateral);
            if r.plastic {
                if direction != sign || branches == 0 {
                    // a new plastic branch starts from the committed state
                    sign = direction;
                    x0 = [0, 1].map(|i| 1.5 * state.back_stress[i][0]);
                    ep0 = state.plastic_strain[0];
                    branches += 1;
                }
                let ep = r.state.plastic_strain[0];
                let x: f64 = (0..2).map(|i| closed_form(&m.kinematic[i], sign, x0[i], ep, ep0)).sum();
                let sy = m.hardening.as_ref().unwrap().eval(r.state.peeq).0;
                let expected = sign * sy + x;
                assert!(
                    (r.stress[0] - expected).abs() < 1e-6 * SY,
                    "voce {voce}, ε = {eps}: σ = {:e}, closed form {expected:e}",
                    r.stress[0]
                );
                for i in 0..2 {
                    let xi = closed_form(&m.kinematic[i], sign, x0[i], ep, ep0);
                    assert!((1.5 * r.state.back_stress[i][0] - xi).abs() < 1e-6 * SY);
                }
                checked += 1;
            }
            state = r.state;
        }
        assert_eq!(branches, 3, "voce {voce}: three plastic branches");
        assert!(checked > 300, "{checked}");
    }
}

#[test]
fn voce_saturates_and_its_return_is_exact() {
    // uniaxial monotonic: σ = σ_y0 + Q (1 − e^{−b εp}) with εp = ε − σ/E
    let m =
        Material::new("al", 70e9, 0.33, Some(Hardening::Voce { yield_stress: 100e6, saturation: 50e6, rate: 30.0 }));
    let mut lateral = 0.0;
    for &eps in &[0.002, 0.01, 0.05, 0.3] {
        let r = uniaxial(&m, eps, &PointState::default(), &mut lateral);
        let ep = r.state.plastic_strain[0];
        let expected = 100e6 + 50e6 * (1.0 - (-30.0 * ep).exp());
        assert!((r.stress[0] - expected).abs() < 1e-9 * expected, "ε = {eps}: {} vs {expected}", r.stress[0]);
        assert!((ep - (eps - r.stress[0] / 70e9)).abs() < 1e-12);
    }
}

#[test]
fn without_back_stresses_the_general_return_equals_the_radial_return() {
    // the same linear-hardening law through both paths (a zero-modulus-like
    // back-stress is not allowed, so compare Voce with b → linear limit
    // against the closed-form radial return of a linear law instead)
    let lin = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
    let general = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }))
        .with_kinematic(vec![BackStress { modulus: 1e-300, recall: 0.0 }]);
    let eps = [3e-3, -1e-3, 4e-4, 2e-3, -1.5e-3, 8e-4];
    let (a, b) = (lin.update(&eps, &PointState::default()), general.update(&eps, &PointState::default()));
    for c in 0..6 {
        assert!((a.stress[c] - b.stress[c]).abs() < 1e-9 * 100e6);
        for d in 0..6 {
            assert!((a.tangent[c][d] - b.tangent[c][d]).abs() < 1e-9 * 70e9);
        }
    }
    assert!((a.state.peeq - b.state.peeq).abs() < 1e-15);
}
