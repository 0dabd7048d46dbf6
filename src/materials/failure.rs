//! Failure criteria of a ply, evaluated on the stress in its material axes
//! `(11, 22, 33, 12, 13, 23)` (`super::anisotropic::Frame::stress_to_material`).
//!
//! Every criterion is written as modes of the form `f(σ) = a(σ) + b(σ)`
//! with `a` quadratic and `b` linear in the stress, so that under
//! proportional loading `f(Rσ) = a R² + b R` and the **strength ratio** `R`
//! (the load multiplier at which the mode reaches 1) is the positive root of
//! `a R² + b R = 1`. The reported **index** of a criterion is its largest
//! mode's `f(σ)` (1 at failure).
//!
//! * **Maximum stress**: `f = max(σ11/X, σ22/Y, σ33/Z, |τ12|/S12, |τ13|/S13,
//!   |τ23|/S23)` with the tensile or compressive strength by the sign (a
//!   linear mode: `a = 0`).
//! * **Tsai–Wu** (Tsai & Wu 1971), 3D with `F_i = 1/X_t − 1/X_c`,
//!   `F_ii = 1/(X_t X_c)`, `F_66 = 1/S²` and the interaction terms
//!   `F_ij = −½ √(F_ii F_jj)` (Tsai & Hahn 1980).
//! * **Hashin** (Hashin 1980, *J. Appl. Mech.* 47, eqs. 23–26, 3D):
//!   fibre tension (σ11 ≥ 0) `(σ11/X_t)² + (τ12² + τ13²)/S12²`; fibre
//!   compression `(σ11/X_c)²`; matrix tension (σ22 + σ33 ≥ 0)
//!   `((σ22+σ33)/Y_t)² + (τ23² − σ22σ33)/S23² + (τ12² + τ13²)/S12²`; matrix
//!   compression `((Y_c/(2S23))² − 1)(σ22+σ33)/Y_c + (σ22+σ33)²/(4S23²) +
//!   (τ23² − σ22σ33)/S23² + (τ12² + τ13²)/S12²`. The fibre and the matrix
//!   index are reported apart.
//! * **Interlaminar** (the quadratic delamination-onset criterion of
//!   Brewer & Lagace, *J. Compos. Mater.* 22, 1988, eq. 10, with the ply's
//!   own transverse strengths): on a ply interface of normal 3,
//!   `(⟨σ33⟩/Z_t)² + (τ13/S13)² + (τ23/S23)²`, the traction the interface
//!   carries against the strengths of the ply on either side
//!   ([`crate::post::failure`] evaluates it at ply interfaces only).

/// The names of the criteria as fields, in the order of
/// [`Indices::ratios`] (`crate::quantity::Quantity::Failure`, the summary's
/// `ply_failure`).
pub const CRITERIA: [&str; 4] = ["fi_max_stress", "fi_tsai_wu", "fi_hashin_fibre", "fi_hashin_matrix"];

/// Strengths of a ply in its material axes (Pa, all positive; compressive
/// strengths as magnitudes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strengths {
    /// Tensile strengths `X_t, Y_t, Z_t` along 1, 2, 3.
    pub tension: [f64; 3],
    /// Compressive strengths `X_c, Y_c, Z_c` along 1, 2, 3.
    pub compression: [f64; 3],
    /// Shear strengths `S12, S13, S23`.
    pub shear: [f64; 3],
}

/// The failure indices of one stress (each 1 at failure).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Indices {
    /// Maximum stress.
    pub(crate) max_stress: f64,
    /// Tsai–Wu.
    pub(crate) tsai_wu: f64,
    /// Hashin, fibre mode (tension or compression by the sign of σ11).
    pub(crate) hashin_fibre: f64,
    /// Hashin, matrix mode (tension or compression by the sign of σ22 + σ33).
    pub(crate) hashin_matrix: f64,
    /// The strength ratio of each (maximum stress, Tsai–Wu, Hashin fibre,
    /// Hashin matrix): the load multiplier of its failure under
    /// proportional loading (∞ for a mode that never fails).
    pub ratios: [f64; 4],
}

impl Indices {
    /// The smallest of [`Indices::ratios`]: the load multiplier at which
    /// the first criterion fails.
    pub fn strength_ratio(&self) -> f64 {
        self.ratios.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// A mode `a R² + b R` (quadratic and linear parts at the stress itself).
#[derive(Debug, Clone, Copy)]
struct Mode {
    a: f64,
    b: f64,
}

impl Mode {
    fn value(self) -> f64 {
        self.a + self.b
    }

    /// The positive root of `a R² + b R = 1` (∞ if the mode never fails).
    fn ratio(self) -> f64 {
        let (a, b) = (self.a, self.b);
        if a > 0.0 {
            // (−b + √(b² + 4a)) / (2a), written without cancellation for b > 0
            let d = (b * b + 4.0 * a).sqrt();
            if b >= 0.0 { 2.0 / (b + d) } else { (d - b) / (2.0 * a) }
        } else if b > 0.0 {
            1.0 / b
        } else {
            f64::INFINITY
        }
    }
}

impl Strengths {
    fn normal(&self, i: usize, s: f64) -> f64 {
        if s >= 0.0 { s / self.tension[i] } else { -s / self.compression[i] }
    }

    fn max_stress(&self, s: &[f64; 6]) -> Mode {
        let mut b = (0..3).map(|i| self.normal(i, s[i])).fold(0.0, f64::max);
        for k in 0..3 {
            b = b.max(s[3 + k].abs() / self.shear[k]);
        }
        Mode { a: 0.0, b }
    }

    fn tsai_wu(&self, s: &[f64; 6]) -> Mode {
        let f: [f64; 3] = std::array::from_fn(|i| 1.0 / self.tension[i] - 1.0 / self.compression[i]);
        let ff: [f64; 3] = std::array::from_fn(|i| 1.0 / (self.tension[i] * self.compression[i]));
        let mut a = 0.0;
        for i in 0..3 {
            a += ff[i] * s[i] * s[i];
            for j in 0..i {
                a += 2.0 * (-0.5 * (ff[i] * ff[j]).sqrt()) * s[i] * s[j];
            }
            a += (s[3 + i] / self.shear[i]).powi(2);
        }
        Mode { a, b: (0..3).map(|i| f[i] * s[i]).sum() }
    }

    fn hashin(&self, s: &[f64; 6]) -> (Mode, Mode) {
        self.hashin_in(s, [s[0] >= 0.0, s[1] + s[2] >= 0.0], 1.0)
    }

    /// Hashin's fibre and matrix modes of the branches `tension` (`[fibre,
    /// matrix]`, `true`: the tension mode), whatever the stress's signs: a
    /// normal stress of the other sign counts as zero (`⟨σ11⟩`, `⟨σ22 + σ33⟩`
    /// and their negatives), so each mode is continuous across its own
    /// branch's boundary. `fibre_shear` (α) weighs the longitudinal shear in
    /// the fibre-tension mode (Hashin: 1, the failure indices'; the ply
    /// damage law's `fibre_shear` key).
    fn hashin_in(&self, s: &[f64; 6], [fibre_tension, matrix_tension]: [bool; 2], fibre_shear: f64) -> (Mode, Mode) {
        let [xt, yt, _] = self.tension;
        let [xc, yc, _] = self.compression;
        let [s12, _, s23] = self.shear;
        let shear12 = (s[3] * s[3] + s[4] * s[4]) / (s12 * s12);
        let fibre = if fibre_tension {
            Mode { a: (s[0].max(0.0) / xt).powi(2) + fibre_shear * shear12, b: 0.0 }
        } else {
            Mode { a: (s[0].min(0.0) / xc).powi(2), b: 0.0 }
        };
        let transverse = (s[5] * s[5] - s[1] * s[2]) / (s23 * s23);
        let matrix = if matrix_tension {
            let t = (s[1] + s[2]).max(0.0);
            Mode { a: (t / yt).powi(2) + transverse + shear12, b: 0.0 }
        } else {
            let t = (s[1] + s[2]).min(0.0);
            Mode { a: t * t / (4.0 * s23 * s23) + transverse + shear12, b: ((yc / (2.0 * s23)).powi(2) - 1.0) * t / yc }
        };
        (fibre, matrix)
    }

    /// Hashin's strength ratios `[fibre, matrix]` of a stress in the material
    /// axes for the branches `tension` (`Strengths::hashin_in`): the load
    /// multipliers at which the fibre and matrix modes reach 1 (∞ for a mode
    /// that never fails). The onset measure of the ply damage law
    /// ([`super::damage`]).
    pub(crate) fn hashin_ratios(&self, material_stress: &[f64; 6], tension: [bool; 2], fibre_shear: f64) -> [f64; 2] {
        let (fibre, matrix) = self.hashin_in(material_stress, tension, fibre_shear);
        [fibre.ratio(), matrix.ratio()]
    }

    /// The interlaminar index and its strength ratio of a stress in the
    /// material axes at a ply interface of normal 3 (module docs).
    pub(crate) fn interlaminar(&self, material_stress: &[f64; 6]) -> (f64, f64) {
        let s = material_stress;
        let a =
            (s[2].max(0.0) / self.tension[2]).powi(2) + (s[4] / self.shear[1]).powi(2) + (s[5] / self.shear[2]).powi(2);
        let mode = Mode { a, b: 0.0 };
        (mode.value(), mode.ratio())
    }

    /// The indices of a stress given in the material axes (tensor shears).
    pub fn indices(&self, material_stress: &[f64; 6]) -> Indices {
        let s = material_stress;
        let (ms, tw) = (self.max_stress(s), self.tsai_wu(s));
        let (hf, hm) = self.hashin(s);
        Indices {
            max_stress: ms.value(),
            tsai_wu: tw.value(),
            hashin_fibre: hf.value(),
            hashin_matrix: hm.value(),
            ratios: [ms.ratio(), tw.ratio(), hf.ratio(), hm.ratio()],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T300/5208 (Tsai & Hahn 1980, Table 7.1): Xt = Xc = 1500, Yt = 40,
    /// Yc = 246, S = 68 MPa; Z as Y, S23 as S12 for the test.
    fn t300() -> Strengths {
        Strengths { tension: [1500e6, 40e6, 40e6], compression: [1500e6, 246e6, 246e6], shear: [68e6; 3] }
    }

    /// The interlaminar criterion (Brewer & Lagace 1988, eq. 10) reads
    /// the traction on a face of normal 3 against Z_t, S13 and S23, each
    /// at its own index: a tension of Z_t is `1`, a compression of any size
    /// `0` (the Macaulay bracket), τ13 = S13 and τ23 = S23 each `1`, and
    /// the in-plane stresses (σ11, σ22, τ12) nothing; the two shears add
    /// quadratically.
    #[test]
    fn the_interlaminar_index_reads_the_normal_traction() {
        let st =
            Strengths { tension: [1500e6, 40e6, 30e6], compression: [1500e6, 246e6, 200e6], shear: [68e6, 50e6, 80e6] };
        let at = |s: [f64; 6]| st.interlaminar(&s);
        assert!((at([0.0, 0.0, 30e6, 0.0, 0.0, 0.0]).0 - 1.0).abs() < 1e-12);
        assert_eq!(at([0.0, 0.0, -1e9, 0.0, 0.0, 0.0]), (0.0, f64::INFINITY));
        assert!((at([0.0, 0.0, 0.0, 0.0, 50e6, 0.0]).0 - 1.0).abs() < 1e-12);
        assert!((at([0.0, 0.0, 0.0, 0.0, 0.0, 80e6]).0 - 1.0).abs() < 1e-12);
        assert_eq!(at([1e9, 1e9, 0.0, 1e9, 0.0, 0.0]).0, 0.0);
        let (index, ratio) = at([0.0, 0.0, 0.0, 0.0, 25e6, 40e6]);
        assert!((index - 0.5).abs() < 1e-12 && (ratio - 2f64.sqrt()).abs() < 1e-12, "{index} {ratio}");
    }

    #[test]
    fn uniaxial_strengths_are_index_one() {
        // a uniaxial stress equal to a strength is on every criterion's
        // surface for its own mode: the strengths enter each as calibration
        let st = t300();
        for (i, s) in [(0, 1500e6), (0, -1500e6), (1, 40e6), (1, -246e6)] {
            let mut sig = [0.0; 6];
            sig[i] = s;
            let ix = st.indices(&sig);
            assert!((ix.max_stress - 1.0).abs() < 1e-12, "{i} {s}");
            assert!((ix.tsai_wu - 1.0).abs() < 1e-12, "{i} {s}: {}", ix.tsai_wu);
            let h = if i == 0 { ix.hashin_fibre } else { ix.hashin_matrix };
            assert!((h - 1.0).abs() < 1e-12, "{i} {s}: {h}");
            assert!((ix.strength_ratio() - 1.0).abs() < 1e-12);
        }
        let ix = st.indices(&[0.0, 0.0, 0.0, 68e6, 0.0, 0.0]);
        assert!((ix.max_stress - 1.0).abs() < 1e-12 && (ix.tsai_wu - 1.0).abs() < 1e-12);
        assert!((ix.hashin_fibre - 1.0).abs() < 1e-12 && (ix.hashin_matrix - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_strength_ratio_scales_a_stress_onto_the_surface() {
        // a combined stress: at R σ the governing criterion's index is 1
        let st = t300();
        let sig = [400e6, -60e6, 5e6, 20e6, 3e6, -4e6];
        let ix = st.indices(&sig);
        let r = ix.strength_ratio();
        assert!(r > 0.0 && r.is_finite());
        let at = st.indices(&sig.map(|v| v * r));
        let largest = at.max_stress.max(at.tsai_wu).max(at.hashin_fibre).max(at.hashin_matrix);
        assert!((largest - 1.0).abs() < 1e-10, "{largest}");
    }
}
