//! The faces of a section element that is the only one of its section
//! through z or x, whose shear tractions the patch recovery holds at zero
//! ([`super::spr`], module docs).
//!
//! Such an element — a one-element section, a wall one element thick —
//! is its own patch in that direction, and a fit of degree `p` through it
//! interpolates its Gauss points: the error across it goes unseen. Yet a
//! beam's or a wall's shear across its depth vanishes on its free faces
//! (a cantilever's `τ = 1.5 V/A (1 − 4ζ²)`, Timoshenko & Goodier §124),
//! where the element's is about constant. Fitted among the polynomials of
//! `Q_p` that vanish at `p + 1` points of each of its two faces (the null
//! space of the basis there), σ_xz and σ_yz across z, σ_xy and σ_xz across
//! x, the recovered shear has that shape (Wiberg, Abdulwahab & Ziukas,
//! *Int. J. Numer. Methods Eng.* 37, 1994: patch recovery with boundary
//! conditions). A free face, a frictionless contact's, a pressure's and a
//! symmetry plane carry no shear traction; a face that does (friction, a
//! tangential load, a face held fixed) is charged with it as error
//! (docs/limitations.md). Not held: a face on a cohesive interface (twin
//! nodes, shared with no element, carrying the interface's traction), and
//! an element whose face line runs on through an element of its ring that
//! is not alone there (a wall beside a profile's junction, where that line
//! is interior: [`super::spr`]'s `section_patches`). An L4 has no bilinear
//! polynomial that vanishes on two opposite faces but zero: it keeps the
//! plain fit.

use crate::mesh::CrossSection;

/// The shear tractions of a face of normal z, (σ_xz, σ_yz) (Voigt indices,
/// `crate::voigt`).
pub(super) const SHEAR_Z: [usize; 2] = [4, 5];
/// The same for a face of normal x: (σ_xy, σ_xz).
pub(super) const SHEAR_X: [usize; 2] = [3, 4];

/// A basis of the polynomials that vanish at the constraint points: the
/// columns (`n × k`, row-major) of the null space of `B` (`b`, rows of
/// `n`: the basis at each point), from the eigenvectors of `BᵀB` whose
/// eigenvalues lie below `1e-10` of the largest.
fn null_space(b: &[f64], n: usize) -> (Vec<f64>, usize) {
    let Some((q, lambda)) = super::least_squares::gram_eigen(b, n) else { return (Vec::new(), 0) };
    let largest = lambda.iter().copied().fold(0.0f64, f64::max);
    let kept: Vec<usize> = (0..n).filter(|&l| lambda[l] <= 1e-10 * largest).collect();
    let mut out = vec![0.0; n * kept.len()];
    for i in 0..n {
        for (c, &l) in kept.iter().enumerate() {
            out[i * kept.len() + c] = q[(i, l)];
        }
    }
    (out, kept.len())
}

/// `X N` for `x` (rows of `n`) and `N` (`n × k`, row-major).
fn times(x: &[f64], n: usize, null: &[f64], k: usize) -> Vec<f64> {
    x.chunks(n).flat_map(|row| (0..k).map(move |c| (0..n).map(|j| row[j] * null[j * k + c]).sum::<f64>())).collect()
}

/// The operator `V N (A N)⁺` of the fit among the polynomials of `basis`
/// that vanish at the points `held`, for the basis at the patch's points
/// (`a`, rows of `n`) and at the element's own (`v`); `None` without held
/// points or without such polynomials (an L4's).
pub(super) fn fit(
    held: &[[f64; 2]],
    basis: impl Fn([f64; 2], &mut Vec<f64>),
    (a, v): (&[f64], &[f64]),
    n: usize,
) -> Option<Vec<f64>> {
    if held.is_empty() {
        return None;
    }
    let mut b = Vec::new();
    held.iter().for_each(|&q| basis(q, &mut b));
    let (null, k) = null_space(&b, n);
    (k > 0).then(|| super::least_squares::fit_operator(&times(a, n, &null, k), &times(v, n, &null, k), k))
}

/// The points (`p + 1` along each) of section element `e`'s two faces
/// along `d` (0: x, 2: z) when both are straight section boundaries (no
/// other element holds a face's nodes: the element is the only one of
/// the section through `d`) and neither is a cohesive interface's (an
/// element with a twin edge), else none. `holding`: the elements at each
/// node; `boxes`: each element's `[x_min, x_max, z_min, z_max]`.
pub(super) fn through(
    section: &CrossSection,
    (holding, boxes): (&[Vec<usize>], &[[f64; 4]]),
    e: usize,
    d: usize,
    tol: f64,
) -> Vec<[f64; 2]> {
    let (p, b, other) = (section.kind.order(), &boxes[e], 2 - d);
    // a cohesive interface's face has twin nodes, shared with no element,
    // yet carries the interface's traction
    if section.twins.iter().any(|t| t.lower.0 == e || t.upper.0 == e) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for at in [b[d], b[d + 1]] {
        let on: Vec<usize> =
            section.element(e).iter().copied().filter(|&t| (section.nodes[t][d / 2] - at).abs() <= tol).collect();
        if on.len() != p + 1 || section.across(holding, e, &on).is_some() {
            return Vec::new();
        }
        for k in 0..=p {
            let s = b[other] + (b[other + 1] - b[other]) * k as f64 / p as f64;
            out.push(if d == 0 { [at, s] } else { [s, at] });
        }
    }
    out
}
