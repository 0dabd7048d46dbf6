//! The coordinates and frames of a curved section patch for the patch
//! recovery ([`super::spr`]): a section element's own isoparametric map
//! continued over the elements around it.
//!
//! A polynomial in x and z fits a stress that turns with a curved wall
//! badly: on a ring of sixteen quadratic arcs (Lamé's thick tube) the
//! Cartesian components vary as `cos 2θ / r²` and a `Q_2(x, z)` fit over
//! three elements around misses them by about 5 % of the peak, several
//! times the element's own error, and the estimate was 7.6 times the true
//! error (tests/step_error.rs, the shrink fit). In the element's natural
//! coordinates `(ξ, η)`, continued over the patch, and with each point's
//! stress turned into the frame that turns with the map's `ξ` direction
//! (the element's own frame at its centre), the same stress is a function
//! of `η` alone, which `Q_2(ξ, η)` fits to `0.3 %`. On a patch of
//! axis-aligned rectangles the continued map is affine and the frame does
//! not turn: the fit is the Cartesian one.

use crate::mesh::CrossSection;
use crate::shape::Lagrange2d;
use crate::values::{natural_of, section_point};
use crate::voigt::Voigt;

/// A section patch's points in the coordinates its fit is made in.
pub(super) struct PatchCoordinates {
    /// The patch's points.
    pub patch: Vec<[f64; 2]>,
    /// The element's own points.
    pub own: Vec<[f64; 2]>,
    /// `[cos δ, sin δ]` of the turn of each point's frame, the patch's
    /// points first ([`own_map`]): empty where no frame turns.
    pub turn: Vec<[f64; 2]>,
}

/// The patch points `patch` and the element's own points `own` (physical
/// `(x, z)`) in section element `e`'s continued natural coordinates, with
/// their frames' turns; where the continued map does not reach a point,
/// the physical coordinates and no turn.
pub(super) fn coordinates(
    section: &CrossSection,
    basis: &Lagrange2d,
    e: usize,
    patch: Vec<[f64; 2]>,
    own: Vec<[f64; 2]>,
) -> PatchCoordinates {
    match own_map(section, basis, e, patch.iter().chain(&own)) {
        Some(mapped) => {
            let (mut coords, turns): (Vec<[f64; 2]>, Vec<[f64; 2]>) = mapped.into_iter().unzip();
            let own = coords.split_off(patch.len());
            let turn = if turns.iter().any(|t| t[1].abs() > 1e-12) { turns } else { Vec::new() };
            PatchCoordinates { patch: coords, own, turn }
        }
        None => PatchCoordinates { patch, own, turn: Vec::new() },
    }
}

/// The natural coordinates `(ξ, η)` of each of `points` under section
/// element `e`'s isoparametric map, continued beyond the element
/// ([`crate::values::natural_of`]), and the turn `[cos δ, sin δ]` of the map's
/// `ξ` direction there from its direction at the centre; `None` where the
/// continued map does not reach a point (a fold, no convergence).
pub(super) fn own_map<'a>(
    section: &CrossSection,
    basis: &Lagrange2d,
    e: usize,
    points: impl Iterator<Item = &'a [f64; 2]>,
) -> Option<Vec<([f64; 2], [f64; 2])>> {
    let m = basis.len();
    let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let unit = |t: [f64; 2]| {
        let n = t[0].hypot(t[1]);
        [t[0] / n, t[1] / n]
    };
    let centre = section_point(section, basis, e, 0.0, 0.0, &mut f, &mut dxi, &mut deta);
    let t0 = unit(centre.tangents[0]);
    points
        .map(|&target| {
            let [xi, eta] = natural_of(section, basis, e, target, (&mut f, &mut dxi, &mut deta))?;
            let t = unit(section_point(section, basis, e, xi, eta, &mut f, &mut dxi, &mut deta).tangents[0]);
            Some(([xi, eta], [t0[0] * t[0] + t0[1] * t[1], t0[0] * t[1] - t0[1] * t[0]]))
        })
        .collect()
}

/// `s` turned into the frame of the x–z plane turned by `δ` about y (`t =
/// [cos δ, sin δ]`; `δ → −δ` turns it back); its shears are `shear` times
/// the tensor's (1 for stresses, 2 for engineering strains, `crate::voigt`).
pub(super) fn turned(s: &Voigt, [c, t]: [f64; 2], shear: f64) -> Voigt {
    let (xx, zz, xz) = (s[0], s[2], s[4] / shear);
    [
        c * c * xx + 2.0 * c * t * xz + t * t * zz,
        s[1],
        t * t * xx - 2.0 * c * t * xz + c * c * zz,
        c * s[3] + t * s[5],
        shear * ((c * c - t * t) * xz + c * t * (zz - xx)),
        c * s[5] - t * s[3],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CrossSection;

    /// The frame turned by `δ` and back is the identity, and a stress whose
    /// principal axes are the turned frame's is diagonal in it; engineering
    /// shears (`shear = 2`) turn as the tensor's doubled.
    #[test]
    fn a_stress_turns_with_its_frame() {
        let d = 0.3f64;
        let t = [d.cos(), d.sin()];
        let s: Voigt = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let back = turned(&turned(&s, t, 1.0), [t[0], -t[1]], 1.0);
        assert!((0..6).all(|k| (back[k] - s[k]).abs() < 1e-12), "{back:?}");
        // σ = a n⊗n with n = (cos δ, sin δ) in x–z: in the turned frame σ_x'x' = a, the rest 0
        let a = 2.5;
        let n = t;
        let along: Voigt = [a * n[0] * n[0], 0.0, a * n[1] * n[1], 0.0, a * n[0] * n[1], 0.0];
        let local = turned(&along, t, 1.0);
        assert!((local[0] - a).abs() < 1e-12 && local[2].abs() < 1e-12 && local[4].abs() < 1e-12, "{local:?}");
        let strain: Voigt = [along[0], 0.0, along[2], 0.0, 2.0 * along[4], 0.0];
        let local = turned(&strain, t, 2.0);
        assert!((local[0] - a).abs() < 1e-12 && local[4].abs() < 1e-12, "{local:?}");
        // out-of-plane shears turn as a vector (σ_xy, σ_zy)
        let local = turned(&[0.0, 0.0, 0.0, n[0], 0.0, n[1]], t, 1.0);
        assert!((local[3] - 1.0).abs() < 1e-12 && local[5].abs() < 1e-12, "{local:?}");
    }

    /// On a grid of rectangles the continued map of an element is affine:
    /// its neighbours' points come out at natural coordinates beyond ±1,
    /// spaced as in physical space, and no frame turns. On a ring the
    /// frame turns by the angle between the points (module docs).
    #[test]
    fn the_continued_map_is_affine_on_rectangles_and_turns_on_a_ring() {
        use crate::mesh::{blocks, profiles};
        use crate::shape::SectionElementKind;
        let grid = CrossSection::rectangle(SectionElementKind::L9, &[0.0, 1.0, 2.0], &[0.0, 1.0]).unwrap();
        let basis = Lagrange2d::new(2);
        // element 0 spans x ∈ [0, 1]: x = 1.5 is ξ = 2, z = 0.5 is η = 0
        let PatchCoordinates { patch, own, turn } =
            coordinates(&grid, &basis, 0, vec![[1.5, 0.5], [0.25, 0.75]], vec![[0.5, 0.5]]);
        assert!((patch[0][0] - 2.0).abs() < 1e-12 && patch[0][1].abs() < 1e-12, "{patch:?}");
        assert!((patch[1][0] + 0.5).abs() < 1e-12 && (patch[1][1] - 0.5).abs() < 1e-12, "{patch:?}");
        assert!(own[0][0].abs() < 1e-12 && turn.is_empty());
        // a ring of 16 (element 0: 0 to 22.5°): a point a sixteenth of a
        // turn on from its centre, at the same radius, has a frame turned by
        // that sixteenth
        let ring =
            blocks::from_blocks(SectionElementKind::L9, &profiles::circular_tube([0.0, 0.0], 1.0, 0.2, 16, 1).unwrap())
                .unwrap();
        let centre = ring.map_point(0, 0.0, 0.0);
        let (r, theta) = (centre[0].hypot(centre[1]), centre[1].atan2(centre[0]));
        let step = std::f64::consts::TAU / 16.0;
        let q = [r * (theta + step).cos(), r * (theta + step).sin()];
        let mapped = own_map(&ring, &basis, 0, [centre, q].iter()).expect("reached");
        let turned_by = mapped[1].1[1].atan2(mapped[1].1[0]);
        assert!((turned_by - step).abs() < 0.02 * step, "turned by {turned_by}, a sixteenth is {step}");
        assert!(mapped[0].1[1].abs() < 1e-12, "the centre's frame is the element's");
        // the same point in the physical frame is two elements' worth of η away
        assert!((mapped[1].0[1].abs() - 2.0).abs() < 0.05, "{:?}", mapped[1].0);
    }
}
