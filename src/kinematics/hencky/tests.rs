//! Tests of the logarithmic strain and its pull-back.

use super::*;
use crate::kinematics::tests::{mul, rotation};
use crate::kinematics::{cauchy, determinant};
use crate::voigt;

fn transpose(a: &Tensor) -> Tensor {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// `F = R Q diag(λ) Qᵀ`: principal stretches `λ` along the columns of `Q`,
/// then the rigid rotation `R`. Returns `F` and `ln U = Q diag(ln λ) Qᵀ`.
fn stretch(lam: [f64; 3], q: &Tensor, r: &Tensor) -> (Tensor, Tensor) {
    let u: Tensor = std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| q[i][k] * lam[k] * q[j][k]).sum()));
    let ln_u: Tensor =
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| q[i][k] * lam[k].ln() * q[j][k]).sum()));
    (mul(r, &u), ln_u)
}

fn gradient(f: &Tensor) -> Tensor {
    let mut h = *f;
    for (i, row) in h.iter_mut().enumerate() {
        row[i] -= 1.0;
    }
    h
}

/// The principal stretches the tests run through: distinct; two equal
/// (uniaxial tension); two equal to round-off and two 1e-7 apart; all
/// three equal (dilatation); none (the undeformed state); large.
const STRETCHES: [[f64; 3]; 7] = [
    [1.3, 0.8, 1.1],
    [1.6487212707001282, 0.78, 0.78],
    [1.2, 0.9, 0.9 * (1.0 + 1e-15)],
    [1.2, 0.9, 0.9 * (1.0 + 1e-7)],
    [1.1, 1.1, 1.1],
    [1.0, 1.0, 1.0],
    [2.5, 0.6, 0.7],
];

/// `½ ln(Fᵀ F) = ln U` for stretches along rotated principal axes, under a
/// rigid rotation (which it ignores), also for repeated stretches.
#[test]
fn log_strain_is_ln_u() {
    let q = rotation([0.2, -1.0, 0.7], 0.8);
    let r = rotation([1.0, 0.4, -0.3], 2.1);
    for lam in STRETCHES {
        let (f, ln_u) = stretch(lam, &q, &r);
        let e = LogStrain::new(&gradient(&f)).strain();
        let expected = [ln_u[0][0], ln_u[1][1], ln_u[2][2], 2.0 * ln_u[0][1], 2.0 * ln_u[0][2], 2.0 * ln_u[1][2]];
        for k in 0..6 {
            assert!((e[k] - expected[k]).abs() < 1e-14, "{lam:?} {k}: {e:?} {expected:?}");
        }
    }
    // small strain: ½ ln(1 + 2e) = e − e² + …, to round-off of e
    let e = LogStrain::from_green_lagrange(&[1e-8, 0.0, 0.0, 0.0, 0.0, 0.0]).strain();
    assert!((e[0] - (1e-8 - 1e-16)).abs() < 1e-22, "{e:?}");
}

/// The material law used by the pull-back tests: `T = C (E_log − E_p)`,
/// isotropic, with a fixed "plastic" strain `E_p` that is not coaxial with
/// `C` (as after non-proportional plastic flow), or zero.
fn material_stress(e_log: &Voigt, ep: &Voigt, c: &Matrix6) -> Voigt {
    let el: Voigt = std::array::from_fn(|k| e_log[k] - ep[k]);
    voigt::mat_vec(c, &el)
}

/// `∂S/∂E` against central differences of `S(E) = T(E_log(E)) : L(E)` in
/// every engineering component of `E`, with and without a non-coaxial
/// `T`, at every state of [`STRETCHES`] (distinct, equal and nearly equal
/// stretches): within 1e-6 of the largest entry. Dropping the second
/// derivative `T : ∂²E_log/∂E²` fails it (checked: also asserted below),
/// and so does a wrong confluent limit (`f[a, a]` or `f[a, a, b]`) at the
/// repeated stretches.
#[test]
fn pull_back_tangent_matches_finite_differences() {
    let c = voigt::isotropic_stiffness(200e9, 0.3);
    let q = rotation([0.2, -1.0, 0.7], 0.8);
    let r = rotation([1.0, 0.4, -0.3], 2.1);
    let plastic = [0.0; 6];
    let skew_plastic = [0.02, -0.03, 0.01, 0.04, -0.02, 0.03];
    let axis_aligned = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for ep in [plastic, skew_plastic] {
        for lam in STRETCHES {
            for frame in [&q, &axis_aligned] {
                let (f, _) = stretch(lam, frame, &r);
                let e = green_lagrange(&gradient(&f));
                let s_of = |e: &Voigt| {
                    let log = LogStrain::from_green_lagrange(e);
                    log.pull_back(&material_stress(&log.strain(), &ep, &c), &c)
                };
                let (_, k) = s_of(&e);
                let scale = k.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
                let h = 1e-6;
                let mut worst = 0.0f64;
                for j in 0..6 {
                    let (mut ep_, mut em_) = (e, e);
                    ep_[j] += h;
                    em_[j] -= h;
                    let (sp, sm) = (s_of(&ep_).0, s_of(&em_).0);
                    for i in 0..6 {
                        worst = worst.max(((sp[i] - sm[i]) / (2.0 * h) - k[i][j]).abs() / scale);
                    }
                }
                assert!(worst < 1e-6, "{lam:?} E_p {ep:?}: relative tangent error {worst:e}");
            }
        }
    }
    // the second-derivative term matters: without it (Lᵀ D L alone) the
    // tangent at a stretched, stressed state is off by far more than 1e-6
    let (f, _) = stretch(STRETCHES[1], &q, &r);
    let log = LogStrain::new(&gradient(&f));
    let t = material_stress(&log.strain(), &skew_plastic, &c);
    let (_, full) = log.pull_back(&t, &c);
    let (_, without) = log.pull_back(&[0.0; 6], &c);
    let scale = full.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    let gap = full.iter().flatten().zip(without.iter().flatten()).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(gap > 1e-3 * scale, "the geometric part of ∂S/∂E: {gap:e} of {scale:e}");
}

/// With `T` coaxial with `C` (an isotropic elastic law, or proportional
/// plastic flow) the Cauchy stress `J⁻¹ F S Fᵀ` of the pulled-back `S` is
/// the rotated Kirchhoff stress `J⁻¹ R T Rᵀ` (Miehe et al. 2002, eq. 2.23
/// with `τ = R T Rᵀ` for isotropy), 1e-12 relative, for every state of
/// [`STRETCHES`].
#[test]
fn cauchy_is_the_rotated_kirchhoff_stress() {
    let c = voigt::isotropic_stiffness(200e9, 0.3);
    let q = rotation([0.2, -1.0, 0.7], 0.8);
    let r = rotation([1.0, 0.4, -0.3], 2.1);
    for lam in STRETCHES {
        let (f, _) = stretch(lam, &q, &r);
        let log = LogStrain::new(&gradient(&f));
        let t = material_stress(&log.strain(), &[0.0; 6], &c);
        let (s, _) = log.pull_back(&t, &c);
        let sigma = voigt::stress_tensor(&cauchy(&f, &s));
        let j = determinant(&f);
        let tau = mul(&mul(&r, &voigt::stress_tensor(&t)), &transpose(&r));
        let scale = tau.iter().flatten().fold(1.0f64, |a, b| a.max(b.abs()));
        for a in 0..3 {
            for b in 0..3 {
                assert!((sigma[a][b] - tau[a][b] / j).abs() < 1e-12 * scale, "{lam:?} {a}{b}");
            }
        }
    }
}

/// At small strain the logarithmic model is the Green–Lagrange one to
/// second order: `S_log − C E = O(|E|²)` (the difference falls 100× when
/// the strain falls 10×) and the tangents agree to O(|E|).
#[test]
fn small_strain_agrees_with_green_lagrange_to_second_order() {
    let c = voigt::isotropic_stiffness(200e9, 0.3);
    let shape = [1.0, -0.3, 0.2, 0.5, -0.4, 0.25];
    let gap = |size: f64| {
        let e = shape.map(|v| v * size);
        let log = LogStrain::from_green_lagrange(&e);
        let (s, k) = log.pull_back(&voigt::mat_vec(&c, &log.strain()), &c);
        let se = voigt::mat_vec(&c, &e);
        let ds = s.iter().zip(&se).fold(0.0f64, |a, (x, y)| a.max((x - y).abs())) / (200e9 * size);
        let dk = k.iter().flatten().zip(c.iter().flatten()).fold(0.0f64, |a, (x, y)| a.max((x - y).abs())) / 200e9;
        (ds, dk)
    };
    let ((s1, k1), (s2, k2)) = (gap(1e-3), gap(1e-4));
    assert!(s1 < 1e-2 && k1 < 1e-2, "{s1:e} {k1:e}");
    assert!((s1 / s2 - 10.0).abs() < 0.5, "relative stress gap {s1:e} → {s2:e}: first order in |E|");
    assert!((k1 / k2 - 10.0).abs() < 0.5, "tangent gap {k1:e} → {k2:e}");
}

/// The divided differences against their definitions where those are
/// well conditioned, and their confluent limits.
#[test]
fn divided_differences_and_their_limits() {
    let f = |x: f64| 0.5 * x.ln_1p();
    // f[a, b, c] from the first differences of the three, as the pull-back makes it
    let second_divided = |a: f64, b: f64, c: f64| {
        let x = [a, b, c];
        let f1 = std::array::from_fn(|i| std::array::from_fn(|j| first_divided(x[i], x[j])));
        super::second_divided(x, &f1, [0, 1, 2])
    };
    let (a, b, c) = (0.3, -0.2, 0.7);
    assert!((first_divided(a, b) - (f(a) - f(b)) / (a - b)).abs() < 1e-15);
    let dd = ((f(a) - f(b)) / (a - b) - (f(b) - f(c)) / (b - c)) / (a - c);
    assert!((second_divided(a, b, c) - dd).abs() < 1e-14);
    // f'(c) = 1/(2c), f''(c)/2 = −1/(4c²), f[a, a, b] = (f'(a) − f[a, b])/(a − b)
    assert!((first_divided(a, a) - 0.5 / (1.0 + a)).abs() < 1e-15);
    assert!((second_divided(a, a, a) + 0.25 / (1.3 * 1.3)).abs() < 1e-15);
    let aab = (0.5 / (1.0 + a) - (f(a) - f(c)) / (a - c)) / (a - c);
    assert!((second_divided(a, a, c) - aab).abs() < 1e-15);
    // continuous across the switches between formulas and series
    for d in [1e-2, 2.1e-3, 1.9e-3, 1e-3, 1e-5, 1e-9] {
        let near = second_divided(a, a + d, a - 0.5 * d);
        let exact = -0.25 / (1.3 * 1.3);
        assert!((near - exact).abs() < 2.0 * d * exact.abs(), "{d}: {near} {exact}");
        let n1 = first_divided(a, a + d);
        assert!((n1 - (f(a + d) - f(a)) / d).abs() < 1e-15_f64.max(1e-16 / d), "{d}");
    }
}

/// Jacobi: orthonormal eigenvectors, `A Q = Q Λ`, also with a repeated eigenvalue.
#[test]
fn symmetric_eigen_decomposes() {
    let q = rotation([0.3, 0.1, -1.0], 1.1);
    for lam in [[3.0, -1.0, 0.5], [2.0, 2.0, -1.0], [1e-6, 1e-6, 1e-6], [0.0, 0.0, 0.0]] {
        let a: Tensor =
            std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| q[i][k] * lam[k] * q[j][k]).sum()));
        let (x, v) = symmetric_eigen(a);
        let av = mul(&a, &v);
        let vtv = mul(&transpose(&v), &v);
        for i in 0..3 {
            for j in 0..3 {
                assert!((av[i][j] - v[i][j] * x[j]).abs() < 1e-14, "{lam:?}");
                assert!((vtv[i][j] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        let mut got = x;
        got.sort_by(f64::total_cmp);
        let mut want = lam;
        want.sort_by(f64::total_cmp);
        assert!(got.iter().zip(&want).all(|(g, w)| (g - w).abs() < 1e-14), "{got:?} {want:?}");
    }
}

/// The recurrence for `h_n` against its definition, the sum of all
/// monomials of degree `n` (`Σ_(i+j+k=n) d_0^i d_1^j d_2^k`).
#[test]
fn complete_homogeneous_polynomials_match_their_definition() {
    for d in [[0.3, -0.2, 0.1], [1e-3, 2e-3, -3e-3], [0.0, 0.0, 0.7]] {
        let h = complete_homogeneous(d);
        for (n, hn) in h.iter().enumerate() {
            let mut direct = 0.0;
            for i in 0..=n {
                for j in 0..=n - i {
                    direct += d[0].powi(i as i32) * d[1].powi(j as i32) * d[2].powi((n - i - j) as i32);
                }
            }
            assert!((hn - direct).abs() <= 1e-15 * direct.abs().max(1.0), "n {n}: {hn} against {direct}");
        }
    }
}
