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
    /// Per element, the parts of `σ* − σ_h` that vary along x, z and the
    /// axis (`directions`), √J each: where one holds most of the variation,
    /// the element's error is that of too long an element in that
    /// direction (`--adapt` splits a grid's intervals by it). Empty when
    /// not computed.
    pub direction: Vec<[f64; 3]>,
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
/// (`super::spr::recover_stages`; in a body with a yielded point, of its
/// strains through the material points' `states`, `super::yielded`; an
/// empty `states` for a mode shape), with the section stage's part of each
/// element ([`ErrorEstimate::section`]). `turned`: the displacements of a
/// state of nonlinear geometry, whose stresses are Cauchy stresses in axes
/// the body has turned away from: they are recovered as second
/// Piola–Kirchhoff stresses, in the body's own axes, where a free face's
/// shear tractions vanish (`super::spr::recover_stages`), and turned back.
/// What every run, step end, frame and mode shape is estimated with.
pub(crate) fn of_state(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    (stresses, states): (&[Voigt], &[crate::materials::PointState]),
    gp_offsets: &[usize],
    turned: Option<&[f64]>,
) -> ErrorEstimate {
    let (mut recovered, mut along) = match turned {
        None => super::spr::recover_stages(mesh, cells, (stresses, 1.0), gp_offsets, true),
        Some(u) => {
            let f = deformation_gradients(mesh, cells, u, gp_offsets, stresses.len());
            let material: Vec<Voigt> =
                stresses.iter().zip(&f).map(|(s, f)| crate::kinematics::second_piola(f, s)).collect();
            let (star, along) = super::spr::recover_stages(mesh, cells, (&material, 1.0), gp_offsets, true);
            let spatial = |s: Vec<Voigt>| -> Vec<Voigt> {
                s.iter().zip(&f).map(|(s, f)| crate::kinematics::cauchy(f, s)).collect()
            };
            (spatial(star), spatial(along))
        }
    };
    // a yielded body's strains are recovered instead (`super::yielded`)
    super::yielded::replace_recovery(
        mesh,
        cells,
        materials,
        (stresses, states),
        gp_offsets,
        (&mut recovered, &mut along),
    );
    let mut out = estimate(mesh, cells, materials, stresses, gp_offsets, &recovered);
    out.section = section_parts(mesh, cells, materials, gp_offsets, (&recovered, &along));
    out.direction = directions(mesh, cells, materials, (stresses, &recovered), gp_offsets);
    out
}

/// The deformation gradient `F = I + ∂u/∂X` at every Gauss point (the
/// layout of the stresses, `n` of them) of the displacements `u`.
fn deformation_gradients(
    mesh: &Mesh,
    cells: &[CellValues],
    u: &[f64],
    gp_offsets: &[usize],
    n: usize,
) -> Vec<crate::kinematics::Tensor> {
    let mut out = vec![crate::kinematics::deformation_gradient(&[[0.0; 3]; 3]); n];
    let (mut nodes, mut grads) = (Vec::new(), Vec::new());
    for (b, body) in mesh.bodies.iter().enumerate() {
        let cell = &cells[b];
        let (gs, ga) = (cell.section.n_gp, cell.axis.n_gp);
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            body.element_nodes(e, &mut nodes);
            grads.resize(nodes.len(), [0.0; 3]);
            for qa in 0..ga {
                for qs in 0..gs {
                    cell.gradients(es, eb, qa, qs, &mut grads);
                    let mut h = [[0.0; 3]; 3];
                    for (g, &node) in grads.iter().zip(&nodes) {
                        for (k, row) in h.iter_mut().enumerate() {
                            (0..3).for_each(|d| row[d] += u[3 * node + k] * g[d]);
                        }
                    }
                    out[gp_offsets[b] + e * gs * ga + qa * gs + qs] = crate::kinematics::deformation_gradient(&h);
                }
            }
        }
    }
    out
}

/// Per element, `‖e − ē_d‖_e` for each direction `d` (x, z, the axis), √J:
/// `e = σ* − σ_h` at the element's Gauss points and `ē_d` its weighted mean
/// over the points that differ only in `d` (the tensor rule's lines along
/// `d`). The leading stress error of an element of degree `p` along a
/// direction is `∝ h_d^p P_p(ξ_d)` (`super::spr`, module docs): it varies
/// along that direction only, so each part measures what halving the
/// element in its direction removes; a part the element's own recovery
/// cannot see (a constant offset of `e`) is in none of them. The section's
/// natural directions are mapped to x or z by the larger of their physical
/// components (a grid's rectangles: exactly). A section element whose rule
/// is not a square tensor rule has no section parts.
fn directions(
    mesh: &Mesh,
    cells: &[CellValues],
    materials: &[Material],
    (stresses, recovered): (&[Voigt], &[Voigt]),
    gp_offsets: &[usize],
) -> Vec<[f64; 3]> {
    let mut out = vec![[0.0; 3]; mesh.n_elements()];
    let (mut d, mut w) = (Vec::new(), Vec::new());
    for (b, body) in mesh.bodies.iter().enumerate() {
        let cell = &cells[b];
        let (gs, ga) = (cell.section.n_gp, cell.axis.n_gp);
        let n = (gs as f64).sqrt().round() as usize;
        let square = n * n == gs && n > 1;
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            let m = &materials[body.material_of(es)];
            let first = gp_offsets[b] + e * gs * ga;
            d.clear();
            w.clear();
            for qa in 0..ga {
                for qs in 0..gs {
                    let g = first + qa * gs + qs;
                    d.push(std::array::from_fn::<f64, 6, _>(|k| recovered[g][k] - stresses[g][k]));
                    w.push(cell.section.weight[es * gs + qs] * cell.axis.weight[eb * ga + qa]);
                }
            }
            // every line along a direction is the points `start + k · stride`,
            // `k < len` (point `qa · gs + j · n + i`: ξ index i, ζ index j)
            let part = |starts: &mut dyn Iterator<Item = usize>, stride: usize, len: usize| {
                let mut sum = 0.0;
                for start in starts {
                    let line = (0..len).map(|k| start + k * stride);
                    let total: f64 = line.clone().map(|p| w[p]).sum();
                    if !(total > 0.0) {
                        continue;
                    }
                    let mean: Voigt =
                        std::array::from_fn(|c| line.clone().map(|p| w[p] * d[p][c]).sum::<f64>() / total);
                    for p in line {
                        let v: Voigt = std::array::from_fn(|c| d[p][c] - mean[c]);
                        sum += w[p] * energy(&v, m);
                    }
                }
                sum.max(0.0).sqrt()
            };
            let axis = part(&mut (0..gs), gs, ga);
            let (xi, zeta) = if square {
                let rows = |qa: usize| (0..n).map(move |j| qa * gs + j * n);
                let columns = |qa: usize| (0..n).map(move |i| qa * gs + i);
                (part(&mut (0..ga).flat_map(rows), 1, n), part(&mut (0..ga).flat_map(columns), n, n))
            } else {
                (0.0, 0.0)
            };
            // does ξ run along x or along z?
            let pos = &cell.section.position;
            let step = |k: usize| {
                let (a, c) = (pos[es * gs], pos[es * gs + k]);
                [(c[0] - a[0]).abs(), (c[1] - a[1]).abs()]
            };
            let xi_along_x = !square || step(1)[0] >= step(1)[1];
            out[body.element_offset + e] = if xi_along_x { [xi, zeta, axis] } else { [zeta, xi, axis] };
        }
    }
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
        let est = ErrorEstimate { element: vec![3.0, 4.0, 0.0], error: 5.0, energy: 12.0, ..Default::default() };
        assert!((est.relative() - 5.0 / 13.0).abs() < 1e-15);
        assert!((est.relative_element(1) - 4.0 / 13.0).abs() < 1e-15);
        assert_eq!(est.largest(2), vec![(1, 16.0 / 25.0), (0, 9.0 / 25.0)]);
    }

    /// Each direction part holds only what varies along its own direction:
    /// on the Timoshenko cantilever's grid (2 × 2 L9, B4), a field of x alone
    /// at the Gauss points is all in the x part, of z alone in the z part,
    /// of y alone in the axis part, and a constant offset in none.
    #[test]
    fn each_direction_part_holds_the_variation_along_it() {
        use crate::setup::{Limits, Model};
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilever_timoshenko.toml");
        let model = Model::parse_with(&std::fs::read_to_string(path).unwrap(), Limits::none()).unwrap();
        let (body, cell) = (&model.mesh.bodies[0], &model.cells[0]);
        let (gs, ga) = (cell.section.n_gp, cell.axis.n_gp);
        let n = body.n_elements() * gs * ga;
        let raw = vec![[0.0; 6]; n];
        // a field f(x, z, y) at every Gauss point, in σ_xx
        let field = |f: &dyn Fn(f64, f64, f64) -> f64| {
            let mut out = vec![[0.0; 6]; n];
            for e in 0..body.n_elements() {
                let (es, eb) = body.split_element(e);
                for qa in 0..ga {
                    for qs in 0..gs {
                        let [x, z] = cell.section.position[es * gs + qs];
                        out[e * gs * ga + qa * gs + qs][0] = f(x, z, cell.axis.position[eb * ga + qa]);
                    }
                }
            }
            out
        };
        let parts = |f: &dyn Fn(f64, f64, f64) -> f64| {
            directions(&model.mesh, &model.cells, &model.materials, (&raw, &field(f)), &[0])
        };
        for (d, f) in [
            (0, &(|x: f64, _: f64, _: f64| 1e8 * (x / 0.05 - 1.0).powi(2)) as &dyn Fn(f64, f64, f64) -> f64),
            (1, &|_, z: f64, _| 1e8 * (z / 0.05 - 1.0).powi(2)),
            (2, &|_, _, y: f64| 1e8 * y * y),
        ] {
            for (e, p) in parts(f).iter().enumerate() {
                assert!(p[d] > 0.0, "direction {d}, element {e}: {p:?}");
                (0..3)
                    .filter(|&o| o != d)
                    .for_each(|o| assert!(p[o] < 1e-12 * p[d], "direction {d}, element {e}: {p:?}"));
            }
        }
        assert!(parts(&|_, _, _| 1e8).iter().flatten().all(|p| p.abs() < 1e-9), "a constant offset varies nowhere");
    }
}
