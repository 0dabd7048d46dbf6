//! The stress of the geometric stiffness after a linear step (total
//! Lagrangian, Green–Lagrange strain).
//!
//! The residual takes `S(E(u))`. The geometric term of the tangent takes, after a linear step `δ` of the displacements (a Newton correction,
//! or the secant start of an increment), the stress *linearized* along it,
//! `S̃ = S(E(u − δ)) + C : B(u − δ) δ = S(E(u)) − C : ½ sym(∇δᵀ ∇δ)` (exact for
//! an elastic point, the Green–Lagrange strain being quadratic in `∇u`; `C`
//! the point's tangent otherwise). This is Newton's method on the mixed
//! problem whose stresses at the Gauss points are unknowns of their own,
//! condensed point by point: the *mixed integration point* strategy of
//! Magisano, Leonetti & Garcea (*Comput. Methods Appl. Mech. Engrg.* 313
//! (2017) 986–1005). A linear step that rotates a thin wall stretches it by
//! `∝ θ²`, a membrane stress far larger than the wall's bending and torsion
//! stresses: taken into the geometric stiffness it spoils the next
//! correction, and Newton on the displacements alone oscillates under large
//! rotations whatever the increment (the channel of bench/channel_twist.toml
//! with 2 L9 along each flange, 4 along the web and 12 uniform B4: the same
//! 6–7 corrections per increment with 80 increments as with 20). `S̃` leaves
//! that spurious stress out. The residual, hence the converged state, is
//! unchanged, and `S̃ → S` as the corrections vanish: the convergence stays
//! quadratic. Not with the logarithmic strain (not quadratic in `∇u`), nor
//! where no step is given ([`super::PointData::step`]: the tangent of a state, e.g.
//! for the buckling and modal analyses and the finite-difference tests).
//! The structure gives the step (`analysis::structure::kinematics`:
//! the iterate before the last correction, while `u` was reached by one).

use crate::kinematics::Tensor;
use crate::voigt::{Matrix6, Voigt};

/// The stress `S − C : ½ sym(∇δᵀ ∇δ)` linearized along the last step `δ`
/// (gradient `gd`) for the geometric stiffness: `½ ∇δᵀ∇δ` is the
/// part of the Green–Lagrange strain of the step that its linearization
/// leaves out (engineering shear, `crate::voigt`'s order).
///
/// With the assumed in-section shear (`crate::values::AssumedShear`) the
/// step's quadratic strain gains its change `Δ m` along the direction `m`:
/// `extra = (Δ, m)`.
pub(super) fn stress(stress: &Voigt, tangent: &Matrix6, gd: &Tensor, extra: Option<(f64, &Voigt)>) -> Voigt {
    let mut quadratic = crate::kinematics::quadratic_strain(gd);
    if let Some((change, m)) = extra {
        for (e, mi) in quadratic.iter_mut().zip(m) {
            *e += change * mi;
        }
    }
    let c_q = crate::voigt::mat_vec(tangent, &quadratic);
    std::array::from_fn(|i| stress[i] - c_q[i])
}
