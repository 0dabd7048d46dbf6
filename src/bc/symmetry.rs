//! Planes of mirror symmetry: the model is the part of a symmetric
//! structure on one side of each plane.
//!
//! A plane `x_a = c` (`a` = x, y or z) of a structure whose geometry,
//! materials, supports and loads are mirror images across it carries a
//! mirror-image displacement field: `u_a(R p) = −u_a(p)` and the other two
//! components equal, with `R` the reflection. On the plane itself
//! `u_a = 0` (the only condition the kept part needs); the shear tractions
//! on it vanish by themselves. A quarter model (two planes) of the paper's
//! three-point bending has a quarter of its unknowns and gives the same
//! field where both exist.
//!
//! Fields at a point of the mirrored part are those of its image in the
//! kept part, reflected: a vector component along a mirrored axis changes
//! sign, a tensor component `ij` (Voigt) by the product of the signs of
//! `i` and `j` (so `σ_xy`, `σ_xz` change sign across `x = c`, the normal
//! stresses do not); scalars (von Mises, peeq, failure indices) are equal.
//!
//! A force on an item (a support, a tool) that lies across a plane — its
//! nodes touch the plane, so in the full structure it and its mirror image
//! are one item — is, on the full structure, the sum over the images:
//! the component along the plane's normal cancels, the others double.

use crate::quantity::Sample;

/// Which side of a plane the model keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Coordinates at or above the plane's.
    Above,
    /// Coordinates at or below the plane's.
    Below,
}

/// A plane of symmetry `x_axis = at`, normal to a coordinate axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// Name (its reaction's name).
    pub name: String,
    /// The normal's axis (0: x, 1: y, 2: z).
    pub axis: usize,
    /// The plane's coordinate (m).
    pub at: f64,
    /// The side modelled.
    pub keep: Side,
    /// Distance (m) within which a point lies on the plane.
    pub tolerance: f64,
}

impl Plane {
    /// True if the point lies on the plane (within the tolerance).
    pub fn holds(&self, p: [f64; 3]) -> bool {
        (p[self.axis] - self.at).abs() <= self.tolerance
    }

    /// True if the coordinate lies on the side left out, beyond the tolerance.
    pub fn removes(&self, c: f64) -> bool {
        match self.keep {
            Side::Above => c < self.at - self.tolerance,
            Side::Below => c > self.at + self.tolerance,
        }
    }

    /// The mirror image of a point.
    pub(crate) fn reflect(&self, p: [f64; 3]) -> [f64; 3] {
        let mut q = p;
        q[self.axis] = 2.0 * self.at - p[self.axis];
        q
    }

    /// "x = 0.125" for messages.
    pub(crate) fn describe(&self) -> String {
        format!("{} = {}", ["x", "y", "z"][self.axis], crate::numbers::short(self.at))
    }
}

/// The model's planes of symmetry, and for each named item (constraint,
/// indenter, pair contact) whether it lies across each plane.
#[derive(Debug, Clone, Default)]
pub struct Symmetry {
    /// The planes (none: a full model).
    pub planes: Vec<Plane>,
    /// Per item name, one flag per plane: its nodes touch the plane.
    pub across: Vec<(String, Vec<bool>)>,
    /// The planes' own constraints (`u_n = 0`): their indices among the
    /// model's constraints.
    pub constraints: Vec<usize>,
}

impl Symmetry {
    /// The full structure's resultant of a force on the named item
    /// ([`full_structure`]); `None` in a model without planes or for a name
    /// without an entry (a plane's own reaction).
    pub fn full(&self, name: &str, f: [f64; 3]) -> Option<[f64; 3]> {
        if self.planes.is_empty() {
            return None;
        }
        let (_, across) = self.across.iter().find(|(n, _)| n == name)?;
        Some(full_structure(f, &self.planes, across))
    }

    /// The number of copies of the model in the full structure (2 per plane).
    pub fn copies(&self) -> usize {
        1 << self.planes.len()
    }
}

/// The sign of each Voigt component (xx, yy, zz, xy, xz, yz) under the
/// reflection of `axis`: −1 for a shear with one index along it.
pub(crate) fn voigt_signs(axis: usize) -> [f64; 6] {
    let s = |k: usize| if k == axis { -1.0 } else { 1.0 };
    [1.0, 1.0, 1.0, s(0) * s(1), s(0) * s(2), s(1) * s(2)]
}

/// The mirror image across a plane normal to `axis` of a stiffness in
/// Voigt form: `C'_ij = s_i s_j C_ij` ([`voigt_signs`]). A material is
/// its own mirror image when its couplings between the even and the odd
/// components vanish (orthotropic axes along the plane's normal, or an
/// isotropic material); a ply at θ about z mirrors across x or y to −θ.
pub(crate) fn reflect_stiffness(c: &[[f64; 6]; 6], axis: usize) -> [[f64; 6]; 6] {
    let s = voigt_signs(axis);
    std::array::from_fn(|i| std::array::from_fn(|j| s[i] * s[j] * c[i][j]))
}

/// The image of `p` in the modelled part: reflected across every plane
/// whose left-out side holds it, with the axes it was reflected along
/// (`[false; 3]` for a point of the model itself).
pub fn image(planes: &[Plane], p: [f64; 3]) -> ([f64; 3], [bool; 3]) {
    let mut q = p;
    let mut flips = [false; 3];
    for plane in planes {
        if plane.removes(q[plane.axis]) {
            q = plane.reflect(q);
            flips[plane.axis] = !flips[plane.axis];
        }
    }
    (q, flips)
}

/// The fields at a point `p` of the full structure from an evaluator at
/// points of the model (`at`, given the image of `p`): reflected back from
/// the image, and on a plane averaged with their own mirror image — the
/// full structure's mean over the elements on both sides of the plane
/// (`Sample::mean`), in which the components odd in the plane's normal
/// cancel and von Mises follows the mean stress.
pub fn sample(planes: &[Plane], p: [f64; 3], at: impl FnOnce([f64; 3]) -> Option<Sample>) -> Option<Sample> {
    let (image, flips) = image(planes, p);
    let mut s = at(image)?;
    for plane in planes.iter().filter(|plane| plane.holds(image)) {
        let mut normal = [false; 3];
        normal[plane.axis] = true;
        s = Sample::mean(&[s, reflect_sample(&s, normal)]);
    }
    Some(reflect_sample(&s, flips))
}

/// The fields at a mirror image: `sample` taken at the image of a point
/// reflected along `flips`, turned back to the point (module docs).
pub(crate) fn reflect_sample(sample: &Sample, flips: [bool; 3]) -> Sample {
    let s = flips.map(|f| if f { -1.0 } else { 1.0 });
    // Voigt order xx, yy, zz, xy, xz, yz (crate::voigt)
    let pair = [s[0] * s[0], s[1] * s[1], s[2] * s[2], s[0] * s[1], s[0] * s[2], s[1] * s[2]];
    let mut out = *sample;
    for k in 0..3 {
        out.u[k] *= s[k];
    }
    for k in 0..6 {
        out.strain[k] *= pair[k];
        out.stress[k] *= pair[k];
    }
    out
}

/// The resultant on the full structure of a force `f` on an item that lies
/// across the planes of axes `across`: one image per combination of
/// reflections, so each plane doubles the components along it and cancels
/// the one normal to it.
pub fn full_structure(f: [f64; 3], planes: &[Plane], across: &[bool]) -> [f64; 3] {
    let mut out = f;
    for (plane, _) in planes.iter().zip(across).filter(|(_, a)| **a) {
        for (k, v) in out.iter_mut().enumerate() {
            *v = if k == plane.axis { 0.0 } else { 2.0 * *v };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(axis: usize, at: f64, keep: Side) -> Plane {
        Plane { name: "p".into(), axis, at, keep, tolerance: 1e-9 }
    }

    #[test]
    fn image_reflects_across_the_planes_whose_left_out_side_holds_the_point() {
        let planes = [plane(0, 0.005, Side::Above), plane(1, 0.125, Side::Below)];
        // in the model: unchanged
        assert_eq!(image(&planes, [0.007, 0.1, 0.0]), ([0.007, 0.1, 0.0], [false; 3]));
        // on a plane: unchanged
        assert_eq!(image(&planes, [0.005, 0.125, 0.0]).1, [false; 3]);
        // x below 0.005 and y above 0.125: both reflected
        let (q, f) = image(&planes, [0.001, 0.2, 0.003]);
        assert!((q[0] - 0.009).abs() < 1e-15 && (q[1] - 0.05).abs() < 1e-15 && q[2] == 0.003);
        assert_eq!(f, [true, true, false]);
    }

    #[test]
    fn reflected_fields_flip_the_components_odd_in_the_mirrored_axes() {
        let s = Sample {
            u: [1.0, 2.0, 3.0],
            stress: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            strain: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            von_mises: 7.0,
            peeq: 8.0,
            failure: [0.5; 4],
        };
        // across x: u_x, σ_xy, σ_xz change sign
        let r = reflect_sample(&s, [true, false, false]);
        assert_eq!(r.u, [-1.0, 2.0, 3.0]);
        assert_eq!(r.stress, [1.0, 2.0, 3.0, -4.0, -5.0, 6.0]);
        assert_eq!(r.strain, r.stress);
        assert_eq!((r.von_mises, r.peeq, r.failure), (7.0, 8.0, [0.5; 4]));
        // across x and y: σ_xy keeps its sign, σ_xz and σ_yz change it
        let r = reflect_sample(&s, [true, true, false]);
        assert_eq!(r.u, [-1.0, -2.0, 3.0]);
        assert_eq!(r.stress, [1.0, 2.0, 3.0, 4.0, -5.0, -6.0]);
    }

    #[test]
    fn on_a_plane_the_odd_components_cancel_and_von_mises_follows() {
        let planes = [plane(0, 0.0, Side::Above)];
        let one_side = Sample { stress: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], u: [1.0, 2.0, 3.0], ..Default::default() };
        let s = sample(&planes, [0.0, 0.3, 0.1], |_| Some(one_side)).unwrap();
        assert_eq!(s.stress, [1.0, 2.0, 3.0, 0.0, 0.0, 6.0]);
        assert_eq!(s.u, [0.0, 2.0, 3.0]);
        assert_eq!(s.von_mises, crate::voigt::von_mises(&s.stress));
        // off the plane: the evaluator's own values
        assert_eq!(sample(&planes, [0.1, 0.3, 0.1], |_| Some(one_side)).unwrap().stress, one_side.stress);
    }

    /// A carbon ply's stiffness turned by `deg` about z from the y axis.
    fn ply(deg: f64) -> [[f64; 6]; 6] {
        use crate::materials::anisotropic::{Frame, Orthotropic};
        let o = Orthotropic { young: [140e9, 10e9, 10e9], shear: [5e9, 5e9, 3.5e9], poisson: [0.3, 0.3, 0.4] };
        let frame = Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], deg.to_radians()).unwrap();
        frame.stiffness_to_global(&o.stiffness().unwrap())
    }

    fn close(a: &[[f64; 6]; 6], b: &[[f64; 6]; 6]) -> bool {
        a.iter().flatten().zip(b.iter().flatten()).all(|(x, y)| (x - y).abs() <= 1e-6 * 140e9)
    }

    #[test]
    fn a_ply_at_theta_mirrors_to_minus_theta_across_x_and_y_and_to_itself_across_z() {
        // the reflection x → −x (or y → −y) turns the fibre direction
        // (sin θ, cos θ, 0) into (−sin θ, cos θ, 0) up to its sign: θ → −θ;
        // z → −z leaves an in-plane fibre where it is
        let (c30, c_30) = (ply(30.0), ply(-30.0));
        assert!(close(&reflect_stiffness(&c30, 0), &c_30));
        assert!(close(&reflect_stiffness(&c30, 1), &c_30));
        assert!(close(&reflect_stiffness(&c30, 2), &c30));
        assert!(!close(&reflect_stiffness(&c30, 0), &c30));
        // plies along the axes are their own mirror images across every plane
        for deg in [0.0, 90.0] {
            for axis in 0..3 {
                assert!(close(&reflect_stiffness(&ply(deg), axis), &ply(deg)), "{deg} {axis}");
            }
        }
        assert_eq!(voigt_signs(0), [1.0, 1.0, 1.0, -1.0, -1.0, 1.0]);
        assert_eq!(voigt_signs(2), [1.0, 1.0, 1.0, 1.0, -1.0, -1.0]);
    }

    #[test]
    fn full_structure_force_cancels_normal_components_and_doubles_the_rest() {
        let planes = [plane(0, 0.0, Side::Above), plane(1, 0.0, Side::Above)];
        let f = [1.0, 2.0, 3.0];
        assert_eq!(full_structure(f, &planes, &[true, true]), [0.0, 0.0, 12.0]);
        assert_eq!(full_structure(f, &planes, &[true, false]), [0.0, 4.0, 6.0]);
        assert_eq!(full_structure(f, &planes, &[false, false]), f);
    }
}
