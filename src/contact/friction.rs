//! Coulomb friction of a contact point: elastic-slip (penalty)
//! regularisation, a return map onto the Coulomb cone and its consistent,
//! unsymmetric tangent (Wriggers, *Computational Contact Mechanics*, 2nd
//! ed., §5.2 and §6.3; Laursen, *Computational Contact and Impact
//! Mechanics*, §5.4).
//!
//! With the relative displacement `d = u_s − u_m` of a point (slave minus
//! master), its normal `n` (fixed, node-to-node), the tangential projector
//! `P = I − n nᵀ`, the committed slip `s_n` (in the tangent plane) and the
//! normal pressure force `p = λ − ε_N g ≥ 0` (penalty or augmented
//! Lagrangian, `g = g₀ + d·n`):
//!
//! ```text
//! trial      t* = −ε_T (P d − s_n)                     (elastic tangential force)
//! stick      ‖t*‖ ≤ μ p:  t = t*,          s = s_n
//! slip       ‖t*‖ > μ p:  t = μ p t̂,  t̂ = t*/‖t*‖,  s = P d + t/ε_T
//! ```
//!
//! `t` is the tangential force on the slave node (the master gets `−t`); the
//! slip `s` is history, committed with the converged increment like the
//! plastic strain of a Gauss point. The tangent block is `K_T = −∂t/∂d`:
//!
//! ```text
//! stick      K_T = ε_T P
//! slip       K_T = μ ε_N t̂ nᵀ + (ε_T μ p / ‖t*‖) (P − t̂ t̂ᵀ)
//! ```
//!
//! The first slip term (`∂p/∂d = −ε_N nᵀ`: pressing harder raises the
//! friction force) has no transposed partner: the contact tangent of a
//! sliding point is unsymmetric (returned also on its own as
//! [`FrictionResponse::coupling`]), and the structure solves it by GMRES
//! preconditioned with the factor of the rest (`solver::krylov`). The second is the rotation of the
//! friction force with the trial direction (zero along `t̂`: a sliding
//! point offers no resistance to more sliding beyond `μ p`).

/// Coulomb friction of one contact point: the coefficient μ and the
/// tangential penalty ε_T (N/m) of the elastic-slip regularisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Coefficient of friction μ (−).
    pub coefficient: f64,
    /// Tangential penalty ε_T (N/m) per unit of the point's normal penalty.
    pub(crate) penalty_ratio: f64,
}

/// The tangential response of an active contact point (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionResponse {
    /// Tangential force on the slave node (N).
    pub force: [f64; 3],
    /// Slip after this step (m), to be committed on convergence.
    pub slip: [f64; 3],
    /// True on the Coulomb cone (sliding).
    pub sliding: bool,
    /// `K_T = −∂t/∂d`, row = force component, column = displacement
    /// component; unsymmetric while sliding.
    pub block: [[f64; 3]; 3],
    /// The pressure coupling `μ ε_N t̂ nᵀ` included in `block` (zero while
    /// sticking or when the stick tangent is asked for): the term that makes
    /// the block unsymmetric and its symmetric part indefinite. The
    /// structure keeps it out of the factorized (symmetric, positive) part
    /// of the tangent (`analysis::structure::unsymmetric`).
    pub coupling: [[f64; 3]; 3],
}

/// Return map of one point (module docs): `d_t = P d` the tangential
/// relative displacement, `slip` the committed slip, `normal_force` the
/// pressure force `p`, `normal_penalty` ε_N (so `ε_T = penalty_ratio · ε_N`
/// and `∂p/∂d = −ε_N nᵀ`).
pub(crate) fn friction_response(
    d_t: [f64; 3],
    slip: [f64; 3],
    normal: &[f64; 3],
    normal_force: f64,
    normal_penalty: f64,
    friction: &Friction,
) -> FrictionResponse {
    let eps_t = friction.penalty_ratio * normal_penalty;
    let trial: [f64; 3] = std::array::from_fn(|k| -eps_t * (d_t[k] - slip[k]));
    let norm = (trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]).sqrt();
    let limit = friction.coefficient * normal_force.max(0.0);
    let proj: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j)) - normal[i] * normal[j]));
    if norm <= limit || norm == 0.0 {
        return FrictionResponse {
            force: trial,
            slip,
            sliding: false,
            block: stick_block(normal, normal_penalty, friction),
            coupling: [[0.0; 3]; 3],
        };
    }
    let t_hat = trial.map(|v| v / norm);
    let force = t_hat.map(|v| limit * v);
    // slip so that the elastic part carries exactly the Coulomb force
    let new_slip: [f64; 3] = std::array::from_fn(|k| d_t[k] + force[k] / eps_t);
    let scale = eps_t * limit / norm;
    // ∂p/∂d = −ε_N nᵀ only while p > 0 (p is clamped at zero)
    let coupling = if normal_force > 0.0 { friction.coefficient * normal_penalty } else { 0.0 };
    let coupling: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| coupling * t_hat[i] * normal[j]));
    let block =
        std::array::from_fn(|i| std::array::from_fn(|j| coupling[i][j] + scale * (proj[i][j] - t_hat[i] * t_hat[j])));
    FrictionResponse { force, slip: new_slip, sliding: true, block, coupling }
}

/// The stick block `ε_T P` (`P = I − n nᵀ`): the tangent of a sticking
/// point, and the predictor of a sliding one at the start of an increment.
pub(crate) fn stick_block(normal: &[f64; 3], normal_penalty: f64, friction: &Friction) -> [[f64; 3]; 3] {
    let eps_t = friction.penalty_ratio * normal_penalty;
    std::array::from_fn(|i| std::array::from_fn(|j| eps_t * (f64::from(u8::from(i == j)) - normal[i] * normal[j])))
}

/// Coulomb friction of a node on a rigid surface whose normal turns with
/// the node (`indenters[].method = "surface"`): `v = t_c − ε_T Δy` (the
/// committed tangential force less the tangential penalty times the
/// position increment `Δy` relative to the indenter), the trial
/// `t* = P v` in the current tangent plane (`P = I − n nᵀ`), and the
/// return map of `friction_response`. Returns the force `t`, whether it
/// slides, and `∂t/∂y` (row: force component) for the consistent tangent:
///
/// ```text
/// ∂t*/∂y = −ε_T P − (n·v) ∂n/∂y − n (vᵀ ∂n/∂y)
/// stick  ∂t/∂y = ∂t*/∂y
/// slip   ∂t/∂y = −μ ε_N t̂ nᵀ + (μ p/‖t*‖)(I − t̂ t̂ᵀ) ∂t*/∂y
/// ```
///
/// (`∂p/∂y = −ε_N n`). `stick_tangent`: the stick derivative even where it
/// slides (the first iteration of an increment, as for node pairs).
///
/// Returned as a [`FrictionResponse`]: `block = −∂t/∂y`, and `slip` the
/// committed `slip` plus the increment `(t − t*)/ε_T` (zero while sticking).
#[allow(clippy::too_many_arguments)] // the terms of the return map above; bundling them adds nothing
pub fn turning_friction(
    v: [f64; 3],
    slip: [f64; 3],
    normal: &[f64; 3],
    dn: &[[f64; 3]; 3],
    normal_force: f64,
    normal_penalty: f64,
    friction: &Friction,
    stick_tangent: bool,
) -> FrictionResponse {
    let n = normal;
    let eps_t = friction.penalty_ratio * normal_penalty;
    let nv: f64 = (0..3).map(|k| n[k] * v[k]).sum();
    let trial: [f64; 3] = std::array::from_fn(|i| v[i] - n[i] * nv);
    let v_dn: [f64; 3] = std::array::from_fn(|j| (0..3).map(|k| v[k] * dn[k][j]).sum());
    let d_trial: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| -eps_t * (f64::from(u8::from(i == j)) - n[i] * n[j]) - dn[i][j] * nv - n[i] * v_dn[j])
    });
    let norm = (trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]).sqrt();
    let limit = friction.coefficient * normal_force.max(0.0);
    let negated = |m: [[f64; 3]; 3]| m.map(|r| r.map(|x| -x));
    if norm <= limit || norm == 0.0 {
        return FrictionResponse {
            force: trial,
            slip,
            sliding: false,
            block: negated(d_trial),
            coupling: [[0.0; 3]; 3],
        };
    }
    let t_hat = trial.map(|x| x / norm);
    let force = t_hat.map(|x| limit * x);
    let slip = std::array::from_fn(|i| slip[i] + (force[i] - trial[i]) / eps_t);
    if stick_tangent {
        return FrictionResponse { force, slip, sliding: true, block: negated(d_trial), coupling: [[0.0; 3]; 3] };
    }
    let coupling = if normal_force > 0.0 { friction.coefficient * normal_penalty } else { 0.0 };
    let scale = limit / norm;
    let d_force = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let rotate: f64 = (0..3).map(|k| (f64::from(u8::from(i == k)) - t_hat[i] * t_hat[k]) * d_trial[k][j]).sum();
            -coupling * t_hat[i] * n[j] + scale * rotate
        })
    });
    let coupling = std::array::from_fn(|i| std::array::from_fn(|j| coupling * t_hat[i] * n[j]));
    FrictionResponse { force, slip, sliding: true, block: negated(d_force), coupling }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_sticks_inside_the_cone_and_slides_on_it() {
        let n = [0.0, 0.0, 1.0];
        let fr = Friction { coefficient: 0.3, penalty_ratio: 1.0 };
        // small tangential motion: stick, force −ε_T d_t, no new slip
        let r = friction_response([1e-9, 0.0, 0.0], [0.0; 3], &n, 100.0, 1e9, &fr);
        assert!(!r.sliding && (r.force[0] + 1.0).abs() < 1e-12 && r.slip == [0.0; 3]);
        assert!(r.block[0][0] == 1e9 && r.block[2][2] == 0.0 && r.block[0][2] == 0.0);
        // large motion: slide with |f| = μ p_N against the motion, the slip
        // taking up all but the elastic part f/ε_T
        let r = friction_response([1e-6, 0.0, 0.0], [0.0; 3], &n, 100.0, 1e9, &fr);
        assert!(r.sliding && (r.force[0] + 30.0).abs() < 1e-9 && r.force[1] == 0.0);
        assert!((r.slip[0] - (1e-6 - 30.0 / 1e9)).abs() < 1e-18);
        // no stiffness along the sliding direction, ε_T μ p_N/|t| across it,
        // and the coupling μ ε_N t̂ nᵀ (t̂ = −x): row x, column z
        assert!(r.block[0][0].abs() < 1e-6 && (r.block[1][1] - 1e9 * 30.0 / 1000.0).abs() < 1e-3);
        assert!((r.block[0][2] + 0.3 * 1e9).abs() < 1e-3 && r.block[2][0] == 0.0, "{:?}", r.block);
        // the committed slip shifts the elastic reference: the same motion
        // from that slip sticks, with the Coulomb force still carried
        let again = friction_response([1e-6, 0.0, 0.0], r.slip, &n, 100.0, 1e9, &fr);
        assert!(!again.sliding && (again.force[0] + 30.0).abs() < 1e-6, "{again:?}");
        // moving back by less than 2 μ p/ε_T unloads elastically (sticks) ...
        let back = friction_response([1e-6 - 50e-9, 0.0, 0.0], r.slip, &n, 100.0, 1e9, &fr);
        assert!(!back.sliding && (back.force[0] - 20.0).abs() < 1e-6, "{back:?}");
        // ... and by more, slides the other way at +μ p
        let back = friction_response([1e-6 - 70e-9, 0.0, 0.0], r.slip, &n, 100.0, 1e9, &fr);
        assert!(back.sliding && (back.force[0] - 30.0).abs() < 1e-9, "{back:?}");
    }

    /// The total force of a point, normal (penalty) plus tangential, as a
    /// function of the relative displacement `d` alone (the caller's path).
    fn total(d: [f64; 3], n: &[f64; 3], g0: f64, eps: f64, slip: [f64; 3], fr: &Friction) -> [f64; 3] {
        let dn: f64 = (0..3).map(|k| d[k] * n[k]).sum();
        let p = (-eps * (g0 + dn)).max(0.0);
        let d_t: [f64; 3] = std::array::from_fn(|k| d[k] - dn * n[k]);
        let t = friction_response(d_t, slip, n, p, eps, fr).force;
        std::array::from_fn(|k| p * n[k] + t[k])
    }

    /// The block is the derivative of the force: central differences of the
    /// total force against `ε_N n nᵀ + K_T`, at a sticking and at a sliding
    /// point, with an inclined normal and a slip and motion in no special
    /// direction (so every term of the unsymmetric block is exercised).
    /// Expected: agreement to the differencing error (h = 1e-13 m against
    /// motions of 1e-7 m: relative 1e-7 or better).
    #[test]
    fn the_block_is_the_derivative_of_the_force_sticking_and_sliding() {
        let n = [2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0];
        let eps = 1e9;
        let fr = Friction { coefficient: 0.4, penalty_ratio: 1.0 };
        let slip0 = {
            let s = [1e-8, -2e-8, 0.5e-8];
            let sn: f64 = (0..3).map(|k| s[k] * n[k]).sum();
            std::array::from_fn::<f64, 3, _>(|k| s[k] - sn * n[k])
        };
        // d·n = −1e-7 (pressed by 100 N); tangential parts small (stick) or large (slip)
        for (tangential, sliding) in [([1e-9, -1e-9, 0.0], false), ([3e-7, -1e-7, 0.5e-7], true)] {
            let d: [f64; 3] = std::array::from_fn(|k| tangential[k] - 1e-7 * n[k]);
            let dn: f64 = (0..3).map(|k| d[k] * n[k]).sum();
            let p = -eps * dn;
            let d_t: [f64; 3] = std::array::from_fn(|k| d[k] - dn * n[k]);
            let r = friction_response(d_t, slip0, &n, p, eps, &fr);
            assert_eq!(r.sliding, sliding);
            let k_exact: [[f64; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| eps * n[i] * n[j] + r.block[i][j]));
            let h = 1e-13;
            let mut worst: f64 = 0.0;
            for j in 0..3 {
                let mut dp = d;
                dp[j] += h;
                let mut dm = d;
                dm[j] -= h;
                let (fp, fm) = (total(dp, &n, 0.0, eps, slip0, &fr), total(dm, &n, 0.0, eps, slip0, &fr));
                for i in 0..3 {
                    let fd = -(fp[i] - fm[i]) / (2.0 * h);
                    worst = worst.max((fd - k_exact[i][j]).abs() / eps);
                }
            }
            assert!(worst < 1e-6, "sliding {sliding}: block differs from central differences by {worst:e} of ε_N");
            if sliding {
                // unsymmetric: the coupling has no transposed partner
                let skew = (0..3)
                    .flat_map(|i| (0..3).map(move |j| (i, j)))
                    .map(|(i, j)| (k_exact[i][j] - k_exact[j][i]).abs());
                assert!(skew.fold(0.0, f64::max) > 0.1 * eps);
            }
        }
    }
}
