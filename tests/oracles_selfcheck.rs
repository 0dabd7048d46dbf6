//! Self-checks of the analytical oracles in `tests/common/pagano.rs`
//! (Pagano's exact cylindrical bending), `tests/common/clt.rs`
//! (classical laminate theory and first-ply failure) and `tests/common/cbt.rs`
//! (corrected beam theory of the DCB, ENF and MMB delamination specimens).
//! Pure arithmetic, no solver: the whole file runs in well under a second.

#[path = "common/cbt.rs"]
mod cbt;
#[path = "common/clt.rs"]
mod clt;
#[path = "common/pagano.rs"]
mod pagano;

use std::f64::consts::PI;

use pagano::{Pagano, Ply};

/// [0/90/0], equal plies, thickness h.
fn three_ply(h: f64, e2: f64) -> Vec<Ply> {
    vec![Ply::pagano(h / 3.0, 0.0, e2), Ply::pagano(h / 3.0, 90.0, e2), Ply::pagano(h / 3.0, 0.0, e2)]
}

/// Normalized results of Pagano (1969):
/// `(σ̄_yy(L/2, +h/2), σ̄_yy(L/2, −h/2), τ̄_yz(0, 0), w̄(L/2, 0))` with
/// σ̄ = σ/(q0 S²), τ̄ = τ/(q0 S), w̄ = 100 E_T w/(q0 h S⁴), S = L/h.
fn normalized(sol: &Pagano, e2: f64) -> [f64; 4] {
    let (l, h, q0) = (sol.span(), sol.thickness(), sol.load());
    let s = l / h;
    [
        sol.stress(l / 2.0, h / 2.0)[0] / (q0 * s * s),
        sol.stress(l / 2.0, -h / 2.0)[0] / (q0 * s * s),
        sol.stress(0.0, 0.0)[2] / (q0 * s),
        100.0 * e2 * sol.displacement(l / 2.0, 0.0)[1] / (q0 * h * s.powi(4)),
    ]
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// (a) [0/90/0], equal plies, Pagano's material, normalized as in
/// [`normalized`]. Pagano's own table (1969) and Reddy's reprint of it could
/// not be retrieved, so nothing here is compared with a published number:
/// the pinned values are this oracle's own (its correctness rests on the
/// field-equation, thin-limit and isotropic checks below), kept as a
/// regression guard. w̄(S = 4) = 2.887 coincides with the value usually quoted
/// for this case; that quote is unverified. Sign: the pressure pushes toward
/// −z, so the top fibre is in compression and w < 0.
#[test]
fn pagano_three_ply_normalized_values() {
    let e2 = 6.9e9; // any modulus: the normalized values do not depend on it
    let pinned = [
        (4.0, [-1.1755, 1.1315, -0.3579, -2.8872]),
        (10.0, [-0.7367, 0.7363, -0.4239, -0.9316]),
        (50.0, [-0.6348, 0.6349, -0.4415, -0.5270]),
        (100.0, [-0.6315, 0.6315, -0.4421, -0.5140]),
    ];
    for (s, want) in pinned {
        let h = 0.01;
        let got = normalized(&Pagano::new(&three_ply(h, e2), s * h, 1.0e5), e2);
        for i in 0..4 {
            assert!((got[i] - want[i]).abs() < 1e-4, "S = {s}: {got:?} against {want:?}");
        }
    }
}

/// Sample points (y, z, ply) inside every ply and on its faces.
fn samples(sol: &Pagano) -> Vec<(f64, f64, usize)> {
    let zs = sol.interfaces();
    let mut out = Vec::new();
    for k in 0..zs.len() - 1 {
        for f in [0.0, 0.13, 0.5, 0.87, 1.0] {
            for y in [0.1, 0.37, 0.5, 0.81] {
                out.push((y * sol.span(), zs[k] + f * (zs[k + 1] - zs[k]), k));
            }
        }
    }
    out
}

/// (b) Continuity, face conditions, equilibrium and the constitutive law by
/// central differences: together these fix the elasticity solution uniquely.
#[test]
fn pagano_field_equations() {
    let e2 = 1.0e10;
    let h = 0.02;
    let layups: Vec<Vec<Ply>> = vec![
        three_ply(h, e2),
        vec![Ply::pagano(0.5 * h, 0.0, e2), Ply::pagano(0.5 * h, 90.0, e2)],
        vec![Ply::pagano(0.1 * h, 90.0, e2), Ply::pagano(0.3 * h, 0.0, e2), Ply::pagano(0.6 * h, 90.0, e2)],
    ];
    for plies in &layups {
        for s in [2.0, 4.0, 10.0, 100.0] {
            let q0 = 1.0e5;
            let sol = Pagano::new(plies, s * h, q0);
            let zs = sol.interfaces();
            let n = zs.len() - 1;
            // Interfaces: U, W, T, N continuous (relative to the largest amplitude).
            let scale: Vec<f64> = (0..5)
                .map(|i| zs.iter().map(|&z| sol.amplitudes_in_ply(sol.ply_at(z), z)[i].abs()).fold(0.0, f64::max))
                .collect();
            for k in 1..n {
                let (a, b) = (sol.amplitudes_in_ply(k - 1, zs[k]), sol.amplitudes_in_ply(k, zs[k]));
                for i in 0..4 {
                    assert!((a[i] - b[i]).abs() <= 1e-10 * scale[i], "S = {s}, interface {k}, amplitude {i}");
                }
            }
            // Faces: T = N = 0 at the bottom, T = 0 and N = −q0 at the top.
            let bot = sol.amplitudes_in_ply(0, zs[0]);
            let top = sol.amplitudes_in_ply(n - 1, zs[n]);
            for v in [bot[2], bot[3], top[2], top[3] + q0] {
                assert!(v.abs() < 1e-9 * q0, "S = {s}: face residual {v}");
            }
            let l = sol.span();
            // Ends: u_z = 0 and σ_yy = 0 through the thickness.
            for &(_, z, k) in &samples(&sol) {
                for y in [0.0, l] {
                    assert!(sol.displacement_in_ply(k, y, z)[1].abs() < 1e-12 * scale[1]);
                    assert!(sol.stress_in_ply(k, y, z)[0].abs() < 1e-12 * q0 * s * s);
                }
            }
            // Interior: equilibrium and constitutive law by fourth-order central
            // differences, each equilibrium residual relative to the largest term
            // of its equation (p max|Σ| and p max|T|: ∂σ_yy/∂y and ∂τ_yz/∂y at
            // their peaks), each strain relative to the largest strain there.
            let p = PI / l;
            let (dy, dz) = (1e-3 * l, 1e-3 * h);
            let d1 = |f: &dyn Fn(f64) -> f64, x: f64, d: f64| {
                (8.0 * (f(x + d) - f(x - d)) - (f(x + 2.0 * d) - f(x - 2.0 * d))) / (12.0 * d)
            };
            for &(y, z, k) in &samples(&sol) {
                let (z0, z1) = (zs[k], zs[k + 1]);
                let zc = z.clamp(z0 + 2.0 * dz, z1 - 2.0 * dz);
                let dsy = |i: usize| d1(&|y| sol.stress_in_ply(k, y, zc)[i], y, dy);
                let dsz = |i: usize| d1(&|z| sol.stress_in_ply(k, y, z)[i], zc, dz);
                let (a1, b1) = (dsy(0), dsz(2));
                let (a2, b2) = (dsy(2), dsz(1));
                let r1 = (a1 + b1).abs() / (p * scale[4]);
                let r2 = (a2 + b2).abs() / (p * scale[2]);
                assert!(r1 < 1e-6 && r2 < 1e-6, "S = {s}, ply {k}, ({y}, {zc}): equilibrium {r1:e} {r2:e}");
                let duy = |i: usize| d1(&|y| sol.displacement_in_ply(k, y, zc)[i], y, dy);
                let duz = |i: usize| d1(&|z| sol.displacement_in_ply(k, y, z)[i], zc, dz);
                let fd = [duy(0), duz(1), duz(0) + duy(1)];
                let law = sol.strain_in_ply(k, y, zc);
                let emax = law.iter().map(|e| e.abs()).fold(0.0, f64::max);
                for i in 0..3 {
                    assert!((fd[i] - law[i]).abs() < 1e-6 * emax, "S = {s}, ply {k}: strain {i} {fd:?} {law:?}");
                }
            }
        }
    }
}

/// (c) Thin limit: the mid-span deflection tends to the CLT one,
/// w = q0 L⁴/(π⁴ D_yy) with D_yy from the plane-stress reduced stiffnesses
/// with ε_xx = 0 (`clt::abd`, `D[1][1]`). For this very shear-flexible
/// material (E_L/G_LT = 50, G_TT = 0.2 E_T) the gap at S = 100 is 0.85 % (not 0.5 %), and it
/// falls like 1/S² (shear deformation), as the constant (ratio − 1)·S² shows.
#[test]
fn pagano_thin_limit_is_clt() {
    let e2 = 1.0e10;
    let h = 0.01;
    let lam = clt::Lamina { e1: 25.0 * e2, e2, nu12: 0.25, g12: 0.5 * e2 };
    let cplies: Vec<clt::Ply> =
        [0.0, 90.0, 0.0].iter().map(|&a| clt::Ply { thickness: h / 3.0, angle_deg: a, material: lam }).collect();
    let d = clt::abd(&cplies).d[1][1];
    // Hand value: D_yy = (h³/12)(Q11·26/27 + Q22/27).
    let den = 1.0 - 0.25 * 0.25 / 25.0;
    let hand = h.powi(3) / 12.0 * (25.0 * e2 / den * 26.0 / 27.0 + e2 / den / 27.0);
    assert!(rel(d, hand) < 1e-12);
    let mut gaps = Vec::new();
    for s in [100.0, 200.0, 1000.0] {
        let (l, q0) = (s * h, 1.0e4);
        let w = -Pagano::new(&three_ply(h, e2), l, q0).displacement(l / 2.0, 0.0)[1];
        let w_clt = q0 * l.powi(4) / (PI.powi(4) * d);
        gaps.push((w / w_clt - 1.0, s));
    }
    println!("thin limit: (w/w_CLT − 1, S) = {gaps:?}");
    assert!(gaps[0].0 > 0.0 && gaps[0].0 < 0.01);
    assert!(gaps[2].0 < 5e-4);
    let c: Vec<f64> = gaps.iter().map(|(g, s)| g * s * s).collect();
    assert!(rel(c[1], c[0]) < 0.01 && rel(c[2], c[0]) < 0.01, "{c:?}");
}

/// The exact plane-strain solution of an isotropic strip under
/// σ_zz(top) = −q0 sin py by the Airy function φ = f(z) sin py,
/// f = (A + Bz) cosh pz + (C + Dz) sinh pz (Timoshenko & Goodier, Theory of
/// Elasticity, §24): returns `[u_y, u_z, σ_yy, σ_zz, τ_yz]` at (y, z).
fn airy_strip(e: f64, nu: f64, h: f64, l: f64, q0: f64, y: f64, z: f64) -> [f64; 5] {
    let p = PI / l;
    // f and its derivatives as rows of coefficients of (A, B, C, D).
    let basis = |z: f64| {
        let (ch, sh) = ((p * z).cosh(), (p * z).sinh());
        [
            [ch, z * ch, sh, z * sh],
            [p * sh, ch + p * z * sh, p * ch, sh + p * z * ch],
            [p * p * ch, 2.0 * p * sh + p * p * z * ch, p * p * sh, 2.0 * p * ch + p * p * z * sh],
            [
                p.powi(3) * sh,
                3.0 * p * p * ch + p.powi(3) * z * sh,
                p.powi(3) * ch,
                3.0 * p * p * sh + p.powi(3) * z * ch,
            ],
        ]
    };
    let (bt, bb) = (basis(h / 2.0), basis(-h / 2.0));
    let coef = pagano::gauss_solve(
        vec![bt[0].to_vec(), bt[1].to_vec(), bb[0].to_vec(), bb[1].to_vec()],
        vec![q0 / (p * p), 0.0, 0.0, 0.0],
    );
    let f: Vec<f64> = basis(z).iter().map(|r| (0..4).map(|j| r[j] * coef[j]).sum()).collect();
    let (ep, nup, g) = (e / (1.0 - nu * nu), nu / (1.0 - nu), e / (2.0 * (1.0 + nu)));
    let u = -(f[2] + nup * p * p * f[0]) / (ep * p);
    let w = -f[1] / g + (f[3] + nup * p * p * f[1]) / (ep * p * p);
    let (sn, cs) = (p * y).sin_cos();
    [u * cs, w * sn, f[2] * sn, -p * p * f[0] * sn, -p * f[1] * cs]
}

/// (d) Homogeneous isotropic layer (one ply, and the same split into three
/// plies) against the Airy solution at S = 2, 4, 10, everywhere, and against
/// the Kirchhoff plate w = q0 L⁴/(π⁴ D), D = E h³/(12(1 − ν²)), at S = 100.
#[test]
fn pagano_isotropic_layer() {
    let (e, nu, h, q0) = (70e9, 0.3, 0.05, 1.0e6);
    for s in [2.0, 4.0, 10.0] {
        let l = s * h;
        let one = Pagano::new(&[Ply::isotropic(h, e, nu)], l, q0);
        let three = Pagano::new(
            &[Ply::isotropic(0.2 * h, e, nu), Ply::isotropic(0.5 * h, e, nu), Ply::isotropic(0.3 * h, e, nu)],
            l,
            q0,
        );
        let (wref, sref) = (airy_strip(e, nu, h, l, q0, l / 2.0, 0.0)[1].abs(), q0 * s * s);
        for sol in [&one, &three] {
            for &(y, z, _) in &samples(sol) {
                let r = airy_strip(e, nu, h, l, q0, y, z);
                let (u, st) = (sol.displacement(y, z), sol.stress(y, z));
                for i in 0..2 {
                    assert!((u[i] - r[i]).abs() < 1e-9 * wref, "S = {s}: u {u:?} against {r:?}");
                }
                for i in 0..3 {
                    assert!((st[i] - r[2 + i]).abs() < 1e-9 * sref, "S = {s}: σ {st:?} against {r:?}");
                }
                // Plane strain: σ_xx = ν (σ_yy + σ_zz).
                assert!((sol.sigma_xx(y, z) - nu * (st[0] + st[1])).abs() < 1e-9 * sref);
            }
        }
    }
    let l = 100.0 * h;
    let w = -Pagano::new(&[Ply::isotropic(h, e, nu)], l, q0).displacement(l / 2.0, 0.0)[1];
    let w_plate = q0 * l.powi(4) / (PI.powi(4) * e * h.powi(3) / (12.0 * (1.0 - nu * nu)));
    assert!(rel(w, w_plate) < 5e-3, "{w} against {w_plate}");
}

// ---------------------------------------------------------------- CLT

fn t300() -> (clt::Lamina, clt::Strengths) {
    (
        clt::Lamina { e1: 181e9, e2: 10.3e9, nu12: 0.28, g12: 7.17e9 },
        clt::Strengths { xt: 1500e6, xc: 1500e6, yt: 40e6, yc: 246e6, s12: 68e6, s23: 123e6 },
    )
}

fn cross_ply(t: f64) -> Vec<clt::Ply> {
    let (m, _) = t300();
    [0.0, 90.0, 90.0, 0.0].iter().map(|&a| clt::Ply { thickness: t, angle_deg: a, material: m }).collect()
}

/// Q̄ against Jones's closed forms (angle measured from y, so Q̄_yy plays
/// Jones's Q̄11 and Q̄_xx his Q̄22), and [0/90]s A, B, D against hand sums.
#[test]
fn clt_stiffness() {
    let (m, _) = t300();
    let q = clt::q_material(&m);
    let nu21 = m.nu12 * m.e2 / m.e1;
    assert!(rel(q[0][0], m.e1 / (1.0 - m.nu12 * nu21)) < 1e-14);
    for th in [0.0f64, 30.0, 45.0, 60.0, 90.0, -20.0] {
        let qb = clt::q_bar(&m, th);
        let (s, c) = th.to_radians().sin_cos();
        let (q11, q22, q12, q66) = (q[0][0], q[1][1], q[0][1], q[2][2]);
        let yy = q11 * c.powi(4) + 2.0 * (q12 + 2.0 * q66) * s * s * c * c + q22 * s.powi(4);
        let xx = q11 * s.powi(4) + 2.0 * (q12 + 2.0 * q66) * s * s * c * c + q22 * c.powi(4);
        let xy = (q11 + q22 - 4.0 * q66) * s * s * c * c + q12 * (s.powi(4) + c.powi(4));
        let ss = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * s * s * c * c + q66 * (s.powi(4) + c.powi(4));
        let scale = q11;
        for (got, want) in [(qb[1][1], yy), (qb[0][0], xx), (qb[0][1], xy), (qb[2][2], ss)] {
            assert!((got - want).abs() < 1e-12 * scale, "θ = {th}: {got} against {want}");
        }
        for i in 0..3 {
            for j in 0..3 {
                assert!((qb[i][j] - qb[j][i]).abs() < 1e-12 * scale);
            }
        }
    }
    let t = 0.125e-3;
    let plies = cross_ply(t);
    let abd = clt::abd(&plies);
    // z = −2t, −t, 0, t, 2t: outer 0° plies Σ(z³) = 2·7t³, inner 90° plies 2·t³.
    let d_yy = (q[0][0] * 14.0 + q[1][1] * 2.0) * t.powi(3) / 3.0;
    let d_xx = (q[1][1] * 14.0 + q[0][0] * 2.0) * t.powi(3) / 3.0;
    let d_xy = q[0][1] * 16.0 * t.powi(3) / 3.0;
    let d_ss = q[2][2] * 16.0 * t.powi(3) / 3.0;
    assert!(rel(abd.d[1][1], d_yy) < 1e-12 && rel(abd.d[0][0], d_xx) < 1e-12);
    assert!(rel(abd.d[0][1], d_xy) < 1e-12 && rel(abd.d[2][2], d_ss) < 1e-12);
    assert!(abd.d[0][2].abs() < 1e-12 * d_yy && abd.d[1][2].abs() < 1e-12 * d_yy);
    assert!(rel(abd.a[1][1], (q[0][0] + q[1][1]) * 2.0 * t) < 1e-12);
    for i in 0..3 {
        for j in 0..3 {
            assert!(abd.b[i][j].abs() < 1e-12 * abd.a[1][1] * t, "symmetric laminate: B = 0");
        }
    }
    // An unsymmetric [0/90] has B_yy = (Q22 − Q11) t²/2 ≠ 0.
    let b = clt::abd(&[plies[0], plies[1]]).b;
    assert!(b[1][1].abs() > 1e-3 * q[0][0] * t * t);
}

/// Narrow-beam ply stresses: the resultants they integrate to, the hand
/// stresses of the outer 0° ply, and the plate (cylindrical bending) variant.
#[test]
fn clt_beam_bending_stresses() {
    let (m, _) = t300();
    let q = clt::q_material(&m);
    let t = 0.125e-3;
    let plies = cross_ply(t);
    let (width, moment) = (0.02, 1.5);
    let pts = clt::beam_bending_stresses(&plies, width, moment);
    assert_eq!(pts.len(), 8);
    // σ_yy, σ_xx in laminate axes: 0° ply (σ11, σ22), 90° ply (σ22, σ11); linear
    // through each ply, so ∫σ dz and ∫σ z dz are exact from the end values.
    let (mut n_yy, mut m_yy, mut m_xx) = (0.0, 0.0, 0.0);
    for k in 0..4 {
        let ((za, sa), (zb, sb)) = (pts[2 * k], pts[2 * k + 1]);
        let zero = plies[k].angle_deg == 0.0;
        let (yy, xx) = if zero { ((sa[0], sb[0]), (sa[1], sb[1])) } else { ((sa[1], sb[1]), (sa[0], sb[0])) };
        let mom = |a: f64, b: f64| (zb - za) * (a * (2.0 * za + zb) + b * (za + 2.0 * zb)) / 6.0;
        n_yy += (zb - za) * (yy.0 + yy.1) / 2.0;
        m_yy += mom(yy.0, yy.1);
        m_xx += mom(xx.0, xx.1);
    }
    let mw = moment / width;
    assert!(n_yy.abs() < 1e-10 * mw / t && rel(m_yy, mw) < 1e-12 && m_xx.abs() < 1e-10 * mw, "{n_yy} {m_yy} {m_xx}");
    // Hand: D⁻¹ of the (xx, yy) block (D16 = D26 = 0), ε = z κ, 0° ply on top.
    let d = clt::abd(&plies).d;
    let det = d[0][0] * d[1][1] - d[0][1] * d[0][1];
    let (k_xx, k_yy) = (-d[0][1] * mw / det, d[0][0] * mw / det);
    let z = 2.0 * t;
    let s11 = q[0][0] * z * k_yy + q[0][1] * z * k_xx;
    let s22 = q[0][1] * z * k_yy + q[1][1] * z * k_xx;
    assert!(rel(pts[7].1[0], s11) < 1e-12 && rel(pts[7].1[1], s22) < 1e-12 && pts[7].1[2].abs() < 1e-6 * s11);
    assert!(pts[7].1[0] > 0.0, "positive M: top in tension");
    assert!(rel(clt::beam_bending_stiffness(&plies, width), width * det / d[0][0]) < 1e-12);
    // Plate: κ_xx = 0, so σ11(top) = Q11 z M/D_yy.
    let plate = clt::plate_cylindrical_bending_stresses(&plies, mw);
    assert!(rel(plate[7].1[0], q[0][0] * z * mw / d[1][1]) < 1e-12);
}

/// Failure criteria: the uniaxial and shear strengths give R = 1; for the
/// [0/90]s beam the index at R·σ equals 1 at the critical point and stays
/// ≤ 1 elsewhere; max stress by hand (90° ply transverse tension).
#[test]
fn clt_failure() {
    use clt::Criterion::*;
    let (_, st) = t300();
    for c in [MaxStress, TsaiWu, Hashin] {
        for (s, r) in
            [([st.xt, 0.0, 0.0], 1.0), ([-st.xc, 0.0, 0.0], 1.0), ([0.0, st.yt, 0.0], 1.0), ([0.0, 0.0, -st.s12], 1.0)]
        {
            assert!((clt::strength_ratio(&s, &st, c) - r).abs() < 1e-12, "{c:?} {s:?}");
        }
    }
    // Transverse compression: max stress and Hashin reach Yc; Tsai–Wu too (uniaxial).
    for c in [MaxStress, TsaiWu, Hashin] {
        assert!((clt::strength_ratio(&[0.0, -st.yc, 0.0], &st, c) - 1.0).abs() < 1e-12, "{c:?}");
    }
    let t = 0.125e-3;
    let plies = cross_ply(t);
    let pts = clt::beam_bending_stresses(&plies, 0.02, 1.0);
    let mut rs = Vec::new();
    for c in [MaxStress, TsaiWu, Hashin] {
        let (r, i) = clt::first_ply_failure_factor(&pts, &st, c);
        assert!(r.is_finite() && r > 0.0);
        let at = |k: usize| pts[k].1.map(|v| v * r);
        assert!((clt::failure_index(&at(i), &st, c) - 1.0).abs() < 1e-10, "{c:?}");
        for k in 0..pts.len() {
            assert!(clt::failure_index(&at(k), &st, c) <= 1.0 + 1e-10, "{c:?} point {k}");
        }
        rs.push((c, r, i));
    }
    // Max stress by hand: the smallest of the fibre and transverse ratios.
    let hand = pts
        .iter()
        .map(|(_, s)| {
            let f1 = if s[0] > 0.0 { st.xt / s[0] } else { st.xc / -s[0] };
            let f2 = if s[1] > 0.0 { st.yt / s[1] } else { st.yc / -s[1] };
            f1.min(f2)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(rel(rs[0].1, hand) < 1e-12);
    // It is the 90° ply's top (z = +t, transverse tension) that fails first.
    assert_eq!(rs[0].2, 5);
    println!("first-ply failure moments for a 20 mm wide [0/90]s, t = 0.125 mm: {rs:?} (N·m)");
}

// ---------------------------------------------------------------------------
// Corrected beam theory (tests/common/cbt.rs). The pinned numbers were
// recomputed independently in python3 (no closed forms for C, G or c): the
// compliances by Simpson integration of the complementary energy M²/(2EI) of
// the Euler–Bernoulli arms and beams, G by a central difference of that
// compliance (G = P²/(2B) dC/da), the MMB lever by bisection on the mode ratio
// of the superposed DCB and ENF energies, the branches by bisection. They
// agree with design48 §3's DCB, ENF onset and MMB numbers.

use cbt::{Dcb, Enf, Material, Mmb, Specimen};

/// AS4/PEEK specimens of design48 §3: B = 25.4 mm, arms h = 1.56 mm,
/// half-span L = 51 mm; DCB 100 mm long from the load line.
const B: f64 = 25.4e-3;
const H: f64 = 1.56e-3;
const L: f64 = 51e-3;
const A0_DCB: f64 = 32.9e-3;
const A0_ENF: f64 = 39.3e-3;
const A0_MMB: f64 = 33.7e-3;

fn dcb(material: Material) -> Dcb {
    Dcb { material, width: B, arm: H, length: 0.1 }
}

fn enf(material: Material) -> Enf {
    Enf { material, width: B, arm: H, half_span: L }
}

fn mmb(material: Material, ratio: f64) -> Mmb {
    Mmb::for_ratio(material, B, H, L, A0_MMB, ratio)
}

/// dC/da by central differences (step 1 µm: C is a cubic in a).
fn dc_da<S: Specimen>(s: &S, a: f64) -> f64 {
    let e = 1e-6;
    (s.compliance(a + e) - s.compliance(a - e)) / (2.0 * e)
}

/// χ, Γ and the two offsets for AS4/PEEK (python: Γ = 7.552701, χ = 1.709142).
#[test]
fn cbt_crack_length_correction() {
    let m = Material::as4_peek();
    assert!(rel(m.gamma(), 7.552701) < 1e-6, "Γ = {}", m.gamma());
    assert!(rel(m.chi(), 1.709142) < 1e-6, "χ = {}", m.chi());
    assert!(rel(cbt::mode_i_offset(&m, H), 1.709142 * H) < 1e-6);
    assert!(rel(cbt::mode_ii_offset(&m, H), 0.42 * 1.709142 * H) < 1e-6);
    // Isotropic limit: E22 = E11 = E, G13 = E/2.6: Γ = 3.068, χ² = (2.6/11)(3 − 2(Γ/(1+Γ))²).
    let iso = Material { e11: 1.0, e22: 1.0, g13: 1.0 / 2.6, ..m };
    let g: f64 = 1.18 * 2.6;
    assert!(rel(iso.chi(), (2.6 / 11.0 * (3.0 - 2.0 * (g / (1.0 + g)).powi(2))).sqrt()) < 1e-14);
}

/// G = P²/(2B) dC/da for every specimen (both sides of the ENF load point),
/// and the MMB's release rates and compliance equal its DCB and ENF parts
/// under the split loads P_I, P_II.
#[test]
fn cbt_release_rate_is_compliance_derivative() {
    let m = Material::as4_peek();
    let p = 100.0;
    let check = |name: &str, s: &dyn Fn(f64) -> (f64, f64), a: f64| {
        let (g, dg) = s(a);
        assert!(rel(g, dg) < 1e-7, "{name} at a = {a}: G = {g}, P²/(2B) dC/da = {dg}");
    };
    let d = dcb(m);
    let e = enf(m);
    let mm = mmb(m, 0.5);
    for a in [20e-3, 32.9e-3, 45e-3, 60e-3] {
        check("DCB", &|a| (d.release_rate(p, a), p * p / (2.0 * B) * dc_da(&d, a)), a);
    }
    // ENF: before the load (A < L) and past it (A > L).
    for a in [20e-3, 39.3e-3, 49e-3, 51e-3, 60e-3, 90e-3] {
        check("ENF", &|a| (e.release_rate(p, a), p * p / (2.0 * B) * dc_da(&e, a)), a);
    }
    for a in [20e-3, 33.7e-3, 45e-3, 49e-3] {
        check("MMB", &|a| (mm.release_rate(p, a), p * p / (2.0 * B) * dc_da(&mm, a)), a);
        let (pi, pii) = mm.split(p);
        let (gi, gii) = mm.release_rates(p, a);
        assert!(rel(gi, d.release_rate(pi, a)) < 1e-12, "MMB G_I against the DCB under P_I");
        assert!(rel(gii, e.release_rate(pii, a)) < 1e-12, "MMB G_II against the ENF under P_II");
        // δ = ∂U/∂P with U = ½(P_I² C_DCB + P_II² C_ENF).
        let c = (pi / p).powi(2) * d.compliance(a) + (pii / p).powi(2) * e.compliance(a);
        assert!(rel(mm.compliance(a), c) < 1e-12, "MMB compliance against its parts");
    }
    // The split balances the lever: P_h = Pc/L at the hinge, P_s = P(c + L)/L at the saddle.
    let (pi, pii) = mm.split(p);
    let (ph, ps) = (p * mm.lever / L, p * (mm.lever + L) / L);
    assert!(rel(pi, (ph - (ps / 2.0 - ph)) / 2.0) < 1e-12 && rel(pii, ps) < 1e-12);
}

/// DCB: onset at G = G_Ic, the closed-form branch equals the generic
/// bisection, and design48's numbers (python: C = 3.041953e-5, 5.251601e-5,
/// 9.877235e-5 m/N at a = 32.9, 40, 50 mm; P_c = 138.5083 N at 4.21336 mm;
/// 127.1467 N at 5 mm with a = 36.0781 mm, 89.9063 N at 10 mm, a = 52.1266 mm).
#[test]
fn cbt_dcb() {
    let m = Material::as4_peek();
    let d = dcb(m);
    for a0 in [25e-3, A0_DCB, 50e-3] {
        let (dc, pc) = d.onset(a0);
        assert!(rel(d.release_rate(pc, a0), m.gic) < 1e-12);
        assert!(rel(pc, d.onset_load(a0)) < 1e-12);
        assert!(rel(dc, pc * d.compliance(a0)) < 1e-12);
        for k in [1.01, 1.5, 2.0, 3.0] {
            let delta = k * dc;
            let a = d.branch_crack(a0, delta);
            assert!(rel(a, d.branch_crack_closed(delta)) < 1e-9, "a0 = {a0}, δ = {delta}");
            assert!(rel(d.branch_load(a0, delta), d.branch_load_closed(delta)) < 1e-9);
            assert!(rel(d.release_rate(d.branch_load_closed(delta), a), m.gic) < 1e-9);
        }
    }
    for (a, c) in [(32.9e-3, 3.041953e-5), (40e-3, 5.251601e-5), (50e-3, 9.877235e-5)] {
        assert!(rel(d.compliance(a), c) < 1e-6, "C({a}) = {}", d.compliance(a));
    }
    let (dc, pc) = d.onset(A0_DCB);
    assert!(rel(pc, 138.5083) < 1e-6 && rel(dc, 4.21336e-3) < 1e-5, "P_c = {pc}, δ_c = {dc}");
    for (delta, p, a) in [(5e-3, 127.1467, 36.0781e-3), (10e-3, 89.9063, 52.1266e-3)] {
        assert!(rel(d.load(A0_DCB, delta), p) < 1e-6 && rel(d.branch_crack(A0_DCB, delta), a) < 1e-5);
    }
}

/// ENF: continuity of C and G where the effective tip passes the load
/// (A = L), the stability limit A0 = 3^(−1/3) L where dδ/da on the branch
/// changes sign, and the numbers (python: P_c = 749.7649 N at 3.67071 mm;
/// branch (a, P, δ) = (42, 702.8174, 3.75577), (45, 657.1006, 3.88478),
/// (48, 616.9681, 4.04672), (51, 607.5635, 4.42185), (55, 660.5330, 5.38363)
/// in mm, N, mm).
#[test]
fn cbt_enf() {
    let m = Material::as4_peek();
    let e = enf(m);
    let at = e.crack_at_load();
    assert!((e.effective(at) - L).abs() < 1e-15);
    let eps = 1e-10;
    let (cl, cr) = (e.compliance(at - eps), e.compliance(at + eps));
    let (gl, gr) = (e.release_rate(1.0, at - eps), e.release_rate(1.0, at + eps));
    assert!(rel(cl, cr) < 1e-8 && rel(gl, gr) < 1e-8, "C {cl} | {cr}, G {gl} | {gr}");
    // Both sides equal 5L³/(8E11Bh³) and 9L²/(16E11B²h³) at A = L.
    assert!(rel(cl, 5.0 * L.powi(3) / (8.0 * m.e11 * B * H.powi(3))) < 1e-8);
    assert!(rel(gl, 9.0 * L * L / (16.0 * m.e11 * B * B * H.powi(3))) < 1e-8);
    // Stability: δ(a) on the branch falls before A = 0.693 L and rises after.
    let s = e.stable_crack();
    assert!(rel(e.effective(s) / L, 3f64.powf(-1.0 / 3.0)) < 1e-12);
    let slope = |a: f64| (e.branch_point(a + 1e-7).0 - e.branch_point(a - 1e-7).0) / 2e-7;
    assert!(slope(s - 0.2e-3) < 0.0 && slope(s + 0.2e-3) > 0.0);
    assert!(slope(s).abs() < 1e-4 * slope(s + 5e-3), "dδ/da at the limit: {}", slope(s));
    assert!(e.stable_from(s + 0.5e-3) && !e.stable_from(s - 0.5e-3));
    assert!(e.stable_from(A0_ENF));
    // Onset and branch.
    let (dc, pc) = e.onset(A0_ENF);
    assert!(rel(pc, e.onset_load(A0_ENF)) < 1e-12 && rel(e.release_rate(pc, A0_ENF), m.giic) < 1e-12);
    assert!(rel(pc, 749.7649) < 1e-6 && rel(dc, 3.67071e-3) < 1e-5, "P_c = {pc}, δ_c = {dc}");
    for (a, p, delta) in [
        (42.0, 702.8174, 3.75577),
        (45.0, 657.1006, 3.88478),
        (48.0, 616.9681, 4.04672),
        (51.0, 607.5635, 4.42185),
        (55.0, 660.5330, 5.38363),
    ] {
        let (dg, pg) = e.branch_point(a * 1e-3);
        assert!(rel(pg, p) < 1e-6 && rel(dg, delta * 1e-3) < 1e-5, "a = {a} mm: P = {pg}, δ = {dg}");
        assert!(rel(e.branch_crack(A0_ENF, delta * 1e-3), a * 1e-3) < 1e-5);
    }
}

/// MMB: the lever reproduces its mode ratio at a0 for every ratio, and the
/// numbers (python: c = 101.05695, 42.97452, 27.90460 mm for G_II/G = 0.2,
/// 0.5, 0.8 at a0 = 33.7 mm; P_c = 98.9717, 269.9536, 457.2349 N at
/// δ = 8.56095, 5.07626, 4.91440 mm; at ratio 0.5 the ratio drifts to
/// 0.506768 at a = 49.8 mm).
#[test]
fn cbt_mmb() {
    let m = Material::as4_peek();
    for a0 in [20e-3, A0_MMB, 45e-3] {
        for r in [0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95, 1.0] {
            let s = Mmb::for_ratio(m, B, H, L, a0, r);
            assert!((s.mode_ratio(a0) - r).abs() < 1e-12, "a0 = {a0}, ratio {r}: {}", s.mode_ratio(a0));
            assert!(s.lever >= L / 3.0 * (1.0 - 1e-12));
        }
        // The least ratio, 1/(1 + 12β²), is the limit of an endless lever.
        let beta = (a0 + cbt::mode_i_offset(&m, H)) / (a0 + cbt::mode_ii_offset(&m, H));
        let far = Mmb { material: m, width: B, arm: H, half_span: L, lever: 1e6 * L };
        assert!((far.mode_ratio(a0) - 1.0 / (1.0 + 12.0 * beta * beta)).abs() < 1e-6);
    }
    // Pure mode II at c = L/3 (P_I = 0).
    let pure = Mmb { material: m, width: B, arm: H, half_span: L, lever: L / 3.0 };
    assert!((pure.mode_ratio(A0_MMB) - 1.0).abs() < 1e-15);
    for (r, c, p, delta) in
        [(0.2, 101.05695, 98.9717, 8.56095), (0.5, 42.97452, 269.9536, 5.07626), (0.8, 27.90460, 457.2349, 4.91440)]
    {
        let s = mmb(m, r);
        let (dc, pc) = s.onset(A0_MMB);
        assert!(rel(s.lever, c * 1e-3) < 1e-6, "ratio {r}: c = {}", s.lever);
        assert!(rel(pc, p) < 1e-6 && rel(dc, delta * 1e-3) < 1e-5, "ratio {r}: P_c = {pc}, δ_c = {dc}");
        assert!(rel(s.release_rate(pc, A0_MMB), m.bk_toughness(r)) < 1e-12);
        assert!(s.stable_from(A0_MMB), "ratio {r}");
    }
    assert!((mmb(m, 0.5).mode_ratio(49.8e-3) - 0.506768).abs() < 2e-6);
    assert!(rel(m.bk_toughness(0.5), 969.0 + 750.0 * 0.5f64.powf(2.284)) < 1e-15);
}

/// Every point of each whole curve past onset lies on G = G_c(a) (for MMB at
/// the drifting ratio), the curve is continuous at onset, and the error of
/// the curve against itself is zero.
#[test]
fn cbt_whole_curves_hold_toughness() {
    let m = Material::as4_peek();
    check_curve("DCB", &dcb(m), A0_DCB, 12e-3);
    check_curve("ENF", &enf(m), A0_ENF, 6e-3);
    for r in [0.2, 0.5, 0.8] {
        let s = mmb(m, r);
        let top = s.branch_point(s.crack_limit()).0;
        check_curve("MMB", &s, A0_MMB, 0.99 * top);
    }
}

fn check_curve<S: Specimen>(name: &str, s: &S, a0: f64, delta_max: f64) {
    let (dc, pc) = s.onset(a0);
    assert!(delta_max > 1.1 * dc, "{name}: the sample must reach the branch");
    let pts = s.sample(a0, delta_max, 300);
    for &(d, p) in &pts {
        if d <= dc {
            assert!(rel(p, d / s.compliance(a0)) < 1e-12 || d == 0.0);
            assert!(s.release_rate(p, a0) <= s.toughness(a0) * (1.0 + 1e-12));
        } else {
            let a = s.branch_crack(a0, d);
            assert!(a > a0 && rel(s.release_rate(p, a), s.toughness(a)) < 1e-9, "{name}: δ = {d}");
            assert!(rel(p * s.compliance(a), d) < 1e-9, "{name}: δ = {d}");
        }
    }
    let below = s.load(a0, dc * (1.0 - 1e-12));
    let above = s.load(a0, dc * (1.0 + 1e-9));
    assert!(rel(below, pc) < 1e-9 && rel(above, pc) < 1e-6, "{name}: {below} | {pc} | {above}");
    assert_eq!(cbt::curve_error(&pts, s, a0), 0.0);
    // A curve 2 % above the reference everywhere is 2 % of its largest load off.
    let up: Vec<(f64, f64)> = pts.iter().map(|&(d, p)| (d, 1.02 * p)).collect();
    let pmax = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    assert!(rel(cbt::curve_error(&up, s, a0), 0.02 * pmax / pc) < 1e-9, "{name}");
    let down: Vec<(f64, f64)> = pts.iter().map(|&(d, p)| (d, 0.98 * p)).collect();
    assert!(rel(cbt::curve_error(&down, s, a0), 0.02 * pmax / pc) < 1e-9, "{name}");
}

/// design48 §3.4 again: a toughness 10 % off moves the peak and the whole
/// curve by this much (`max |P' − P_CBT(δ)| / P_c` over 201 points from 0 to
/// δ_max: DCB 2δ_c, ENF 3.9 mm, MMB 6.1 mm at the ratio 0.5 and 5.8 mm at 0.8,
/// where the branch of G_IIc − 10 % reaches the saddle at 5.83 mm). The ranges are python's
/// independent values (±0.05 % points): DCB −5.13/+4.88 % at the peak and
/// 7.60/7.23 % over the curve; ENF −5.13/+4.88 %, 15.95/15.26 %; MMB 0.5 with
/// G_Ic −3.49/+3.37 %, 9.17/9.07 %; MMB 0.5 with G_IIc −1.58/+1.56 %,
/// 4.43/4.42 %; MMB 0.8 with G_IIc −3.71/+3.57 %, 15.03/14.65 %. So the 3 %
/// (DCB, ENF) and 5 % (MMB) tolerances catch every ±10 % change on the whole
/// curve except G_IIc at the MMB ratio 0.5, which stays under 5 %.
#[test]
fn cbt_toughness_sensitivity() {
    let m = Material::as4_peek();
    let (gi, gii) = (m.gic, m.giic);
    let dc = dcb(m).onset(A0_DCB).0;
    let mut rows = Vec::new();
    for (k, f) in [(0usize, 0.9), (1, 1.1)] {
        let lo = m.with_toughness(f * gi, gii);
        let lo2 = m.with_toughness(gi, f * gii);
        let c5 = mmb(m, 0.5);
        let c8 = mmb(m, 0.8);
        rows.push(("DCB G_Ic", k, sensitivity(&dcb(m), &dcb(lo), A0_DCB, 2.0 * dc), 3.0));
        rows.push(("ENF G_IIc", k, sensitivity(&enf(m), &enf(lo2), A0_ENF, 3.9e-3), 3.0));
        rows.push(("MMB 0.5 G_Ic", k, sensitivity(&c5, &Mmb { material: lo, ..c5 }, A0_MMB, 6.1e-3), 5.0));
        rows.push(("MMB 0.5 G_IIc", k, sensitivity(&c5, &Mmb { material: lo2, ..c5 }, A0_MMB, 6.1e-3), 5.0));
        rows.push(("MMB 0.8 G_IIc", k, sensitivity(&c8, &Mmb { material: lo2, ..c8 }, A0_MMB, 5.8e-3), 5.0));
    }
    let python = [
        ("DCB G_Ic", [(-5.13, 7.60), (4.88, 7.23)]),
        ("ENF G_IIc", [(-5.13, 15.95), (4.88, 15.26)]),
        ("MMB 0.5 G_Ic", [(-3.49, 9.17), (3.37, 9.07)]),
        ("MMB 0.5 G_IIc", [(-1.58, 4.43), (1.56, 4.42)]),
        ("MMB 0.8 G_IIc", [(-3.71, 15.03), (3.57, 14.65)]),
    ];
    println!("| case | toughness | peak P_c | whole curve | tolerance | caught |");
    for (name, k, (peak, curve), tol) in rows {
        let want = python.iter().find(|p| p.0 == name).unwrap().1[k];
        println!(
            "| {name} | {} | {peak:+.2} % | {curve:.2} % | {tol} % | {} |",
            ["-10 %", "+10 %"][k],
            if curve > tol { "yes" } else { "no" }
        );
        assert!((peak - want.0).abs() < 0.05 && (curve - want.1).abs() < 0.05, "{name} {k}: {peak} {curve}");
        assert_eq!(curve > tol, name != "MMB 0.5 G_IIc", "{name}");
    }
}

/// (peak change, whole-curve error), both in % of the nominal peak.
fn sensitivity<S: Specimen>(nominal: &S, mutated: &S, a0: f64, delta_max: f64) -> (f64, f64) {
    let pc = nominal.onset(a0).1;
    let curve = mutated.sample(a0, delta_max, 200);
    (100.0 * (mutated.onset(a0).1 / pc - 1.0), 100.0 * cbt::curve_error(&curve, nominal, a0))
}
