//! A posteriori error estimate of the Zienkiewicz–Zhu type: the distance,
//! in the energy norm, between the raw Gauss-point stresses and their
//! superconvergent patch recovery.
//!
//! With `σ_h` the stresses at the Gauss points and `σ*` their patch
//! recovery at the same points ([`super::spr`]), each element gets
//!
//! ```text
//! η_e² = Σ_gp w |J| (σ* − σ_h)ᵀ C⁻¹ (σ* − σ_h)
//! ```
//!
//! (`C⁻¹` the elastic compliance of the body's material; for plastic points
//! this measures the stress jump with the elastic energy, as an indicator),
//! and the global estimate is the relative error in the energy norm
//! `η = √(Σ η_e² / (Σ η_e² + ‖σ_h‖²))`, `‖σ_h‖² = Σ w |J| σ_hᵀ C⁻¹ σ_h`
//! (Zienkiewicz & Zhu, *Int. J. Numer. Methods Eng.* 24, 1987, eq. 9–13;
//! the recovery of their 1992 paper). A field the patch polynomials hold (a
//! patch test's constant stress) gives `η = 0`. Voigt order and engineering
//! shear as in [`crate::voigt`].
//!
//! Why not the L2 projection onto the body's continuous basis
//! ([`super::recovery`], the first version): for elements of even order the
//! leading stress error is equal at both ends of every element, so the
//! continuous projection reproduces it and `σ* ≈ σ_h`. On the Timoshenko
//! cantilever its effectivity index was 0.18–0.19 against the exact error;
//! with the patch recovery 0.81–0.89 (`tests/estimator.rs`).

use crate::materials::Material;
use crate::mesh::Mesh;
use crate::values::CellValues;
use crate::voigt::Voigt;

/// The estimate of one solution.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ErrorEstimate {
    /// `η_e` per element (global element index), √J.
    pub element: Vec<f64>,
    /// `√(Σ η_e²)`, √J.
    pub error: f64,
    /// `‖σ_h‖` in the energy norm, √J.
    pub energy: f64,
    /// Per element, the part of the recovery the fit over the section
    /// made (`‖σ* − σ_along‖_e`, `post::spr::recover_stages`), √J: where
    /// it holds most of `η_e` the error lies across the section rather than
    /// along the axis (the direction `--adapt` refines). Empty when not
    /// computed.
    pub section: Vec<f64>,
}

impl ErrorEstimate {
    /// The relative error in the energy norm (module docs).
    pub fn relative(&self) -> f64 {
        let total = self.error * self.error + self.energy * self.energy;
        if total > 0.0 { (self.error * self.error / total).sqrt() } else { 0.0 }
    }

    /// An element's part of the relative error: `η_e / √(Σ η² + ‖σ_h‖²)`
    /// (they add up in quadrature to [`ErrorEstimate::relative`]).
    pub(crate) fn relative_element(&self, e: usize) -> f64 {
        let total = (self.error * self.error + self.energy * self.energy).sqrt();
        if total > 0.0 { self.element[e] / total } else { 0.0 }
    }

    /// The `k` elements with the largest `η_e`, with their share of `Σ η²`.
    pub fn largest(&self, k: usize) -> Vec<(usize, f64)> {
        let mut order: Vec<usize> = (0..self.element.len()).collect();
        order.sort_by(|&a, &b| self.element[b].total_cmp(&self.element[a]));
        let total = self.error * self.error;
        order
            .into_iter()
            .take(k)
            .map(|e| (e, if total > 0.0 { self.element[e].powi(2) / total } else { 0.0 }))
            .collect()
    }
}

/// `σᵀ C⁻¹ σ` for an isotropic material (engineering shear: `γ = τ / G`).
fn complementary(s: &Voigt, young: f64, poisson: f64) -> f64 {
    let normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 2.0 * poisson * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    let shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
    normal / young + 2.0 * (1.0 + poisson) * shear / young
}

/// `σᵀ C⁻¹ σ` of the material (its own compliance when anisotropic).
fn energy(s: &Voigt, m: &Material) -> f64 {
    match &m.anisotropic {
        None => complementary(s, m.young, m.poisson),
        Some(_) => m.complementary(s),
    }
}

/// Calls `visit(global element, Gauss point, volume weight, material)` for
/// every Gauss point of the mesh (first of each body at `gp_offsets`, the
/// kernel's order `g = g_axis · n_section + g_section` within an element).
fn each_point(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    gp_offsets: &[usize],
    mut visit: impl FnMut(usize, usize, f64, &Material),
) {
    for (b, body) in mesh.bodies.iter().enumerate() {
        let cell = &cells[b];
        let ngp = cell.gp_per_element();
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            let m = &materials[body.material_of(es)];
            for gb in 0..cell.axis.n_gp {
                for gs in 0..cell.section.n_gp {
                    let w =
                        cell.section.weight[es * cell.section.n_gp + gs] * cell.axis.weight[eb * cell.axis.n_gp + gb];
                    let g = gp_offsets[b] + e * ngp + gb * cell.section.n_gp + gs;
                    visit(body.element_offset + e, g, w, m);
                }
            }
        }
    }
}

/// The elastic strain energy `½ ∫ σᵀ C⁻¹ σ dV` of the Gauss-point
/// stresses `stresses` (first of each body at `gp_offsets`), with each
/// body's elastic compliance: the recoverable part of the internal work
/// (the energy ledger of a transient run; with nonlinear geometry, of the
/// stresses as stored, an approximation for large strains). At the points
/// of a damaging material the compliance is the damaged one: the energy
/// their states `damage` hold ([`crate::materials::damage::DamageState`]
/// `stored`; `damage` is empty when no material damages).
pub(crate) fn elastic_energy(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    (stresses, damage): (&[Voigt], &[crate::materials::damage::DamageState]),
    gp_offsets: &[usize],
) -> f64 {
    let mut total = 0.0;
    each_point(mesh, cells, materials, gp_offsets, |_, g, w, m| {
        total += match (&m.damage, damage.get(g)) {
            (Some(_), Some(state)) => w * state.stored,
            _ => 0.5 * w * energy(&stresses[g], m),
        };
    });
    total
}

/// Estimates the error of the stresses `stresses` (Gauss points, first of
/// each body at `gp_offsets`) against their recovery `recovered` (the same
/// layout, `super::spr::recover_stages`).
pub fn estimate(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    stresses: &[Voigt],
    gp_offsets: &[usize],
    recovered: &[Voigt],
) -> ErrorEstimate {
    let mut out = ErrorEstimate { element: vec![0.0; mesh.n_elements()], ..Default::default() };
    let mut energy2 = 0.0;
    // η_e² per element, then its square root
    each_point(mesh, cells, materials, gp_offsets, |e, g, w, m| {
        let (raw, star) = (stresses[g], recovered[g]);
        let d: Voigt = std::array::from_fn(|k| star[k] - raw[k]);
        out.element[e] += w * energy(&d, m);
        energy2 += w * energy(&raw, m);
    });
    let mut error2 = 0.0;
    for eta in &mut out.element {
        error2 += eta.max(0.0);
        *eta = eta.max(0.0).sqrt();
    }
    out.error = error2.sqrt();
    out.energy = energy2.max(0.0).sqrt();
    out
}

/// The estimate of one state: the stresses `stresses` (Gauss points, first
/// of each body at `gp_offsets`) against their patch recovery
/// (`super::spr::recover_stages`), with the section stage's part of each
/// element ([`ErrorEstimate::section`]). What every run, step end, frame
/// and mode shape is estimated with.
pub(crate) fn of_state(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    stresses: &[Voigt],
    gp_offsets: &[usize],
) -> ErrorEstimate {
    let (recovered, along) = super::spr::recover_stages(mesh, cells, stresses, gp_offsets);
    let mut out = estimate(mesh, cells, materials, stresses, gp_offsets, &recovered);
    out.section = section_parts(mesh, cells, materials, gp_offsets, (&recovered, &along));
    out
}

/// `‖σ* − σ_along‖_e` per element (global element index), √J: the
/// section stage's part of the recovery ([`ErrorEstimate::section`]).
fn section_parts(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    gp_offsets: &[usize],
    (recovered, along): (&[Voigt], &[Voigt]),
) -> Vec<f64> {
    let mut out = vec![0.0; mesh.n_elements()];
    each_point(mesh, cells, materials, gp_offsets, |e, g, w, m| {
        let d: Voigt = std::array::from_fn(|k| recovered[g][k] - along[g][k]);
        out[e] += w * energy(&d, m);
    });
    out.iter().map(|v| v.max(0.0).sqrt()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complementary_energy_is_the_compliance_form() {
        // uniaxial σ: σ²/E; pure shear τ: τ²/G
        let (e, nu) = (200e9, 0.3);
        assert!((complementary(&[1e8, 0.0, 0.0, 0.0, 0.0, 0.0], e, nu) - 1e16 / e).abs() < 1e-12 * 1e16 / e);
        let g = e / (2.0 * (1.0 + nu));
        assert!((complementary(&[0.0, 0.0, 0.0, 0.0, 5e7, 0.0], e, nu) - 25e14 / g).abs() < 1e-12 * 25e14 / g);
        // hydrostatic p: 3 p² (1 − 2ν) / E
        let p = 1e8;
        let hydro = complementary(&[p, p, p, 0.0, 0.0, 0.0], e, nu);
        assert!((hydro - 3.0 * p * p * (1.0 - 2.0 * nu) / e).abs() < 1e-12 * hydro);
    }

    #[test]
    fn relative_and_largest() {
        let est = ErrorEstimate { element: vec![3.0, 4.0, 0.0], error: 5.0, energy: 12.0, section: Vec::new() };
        assert!((est.relative() - 5.0 / 13.0).abs() < 1e-15);
        assert!((est.relative_element(1) - 4.0 / 13.0).abs() < 1e-15);
        assert_eq!(est.largest(2), vec![(1, 16.0 / 25.0), (0, 9.0 / 25.0)]);
    }
}
