//! Error estimates of each eigenpair (`analysis.type = "modal"` and
//! `"buckling"`): the recovered-stress estimate ([`super::estimate`],
//! [`super::spr`]) of each mode shape, and the error of its eigenvalue that
//! it implies.
//!
//! **The estimate of a mode.** A mode `φ_h` (per DOF) has the stresses
//! `σ_h = C ε(φ_h)` at the Gauss points (`C` each point's elastic
//! stiffness, `ε` the small-strain measure); their patch recovery `σ*`
//! gives `η_e² = ∫_e (σ* − σ_h)ᵀ C⁻¹ (σ* − σ_h)` per element and
//! `‖e‖_E² ≈ Σ η_e²`, the error of the mode in the energy norm — the
//! estimator of a static solution applied to the shape (Wiberg, Bausys &
//! Hager, "Adaptive h-version eigenfrequency analysis", *Computers &
//! Structures* 71, 1999, who apply the same recovery to each mode).
//!
//! **The eigenvalue error it implies.** For a conforming Galerkin
//! approximation of `K φ = λ M φ` with `φᵀ M φ = φ_hᵀ M φ_h = 1` (the
//! exact mode of the continuum and its approximation),
//!
//! ```text
//! λ_h − λ = ‖φ − φ_h‖_K² − λ ‖φ − φ_h‖_M²
//! ```
//!
//! (expand `a(φ − φ_h, φ − φ_h)` with `a(φ, v) = λ m(φ, v)` and
//! `a(φ_h, φ_h) = λ_h`; Strang & Fix, *An Analysis of the Finite Element
//! Method*, ch. 6; Babuška & Osborn, "Eigenvalue problems", in *Handbook
//! of Numerical Analysis* II, 1991). The mass term is of
//! higher order (the error in L2 converges one order faster than in
//! energy), so `λ_h − λ ≈ ‖e‖_K²` and, with `λ_h = φ_hᵀ K φ_h / φ_hᵀ M φ_h`
//! for any scaling of the shape,
//!
//! ```text
//! (λ_h − λ) / λ_h ≈ ‖e‖_E² / (λ_h φ_hᵀ M φ_h) =: r,      (f_h − f) / f ≈ r / 2
//! ```
//!
//! (`λ = ω²`, `f = ω / 2π`; the computed frequencies are upper bounds,
//! so the estimated error is the amount `f_h` exceeds `f` by). The error
//! of an eigenvalue is the square of that of its mode: a mode 10 % off in
//! energy is 1 % off in `λ` and ½ % in `f`. `r` is not `η²` of the static
//! estimate's relative norm `η = ‖e‖ / √(‖e‖² + ‖σ_h‖²)`; both agree to
//! leading order, `r` is the one that follows from the identity.
//!
//! **Buckling.** The same identity holds for `K₀ φ = μ G φ` (`G = −K_σ`,
//! the stress stiffness of the loads at factor 1, `analysis::buckling`)
//! with `φᵀ G φ = φ_hᵀ G φ_h = 1`, positive for a positive `μ`:
//! `μ_h − μ = ‖e‖_K₀² − μ ‖e‖_G²`, the `G` term a first-derivative form of
//! higher order again, so `(μ_h − μ) / μ_h ≈ ‖e‖_E² / φ_hᵀ K₀ φ_h` — the
//! same `r` with the shape's stiffness for `λ_h φ_hᵀ M φ_h`, the computed
//! critical factors being upper bounds of those of the discrete prebuckling
//! stress. The error of that stress itself (`σ₀` of the static solution
//! `K_σ` is formed from) is not in `r`: exact for a column under an end
//! load, it is not where the prebuckling stress varies steeply.
//!
//! **What it covers.** `C ε` is the elastic material stiffness: of an
//! unloaded model `λ_h φ_hᵀ M φ_h = φ_hᵀ K φ_h = ‖σ_h‖²`. About a loaded
//! state with `analysis.geometry = "nonlinear"` the tangent also carries
//! the geometric (initial-stress) term; the denominator `λ_h φ_hᵀ M φ_h`
//! is then the whole stiffness the eigenvalue measures, while `‖e‖_E²`
//! estimates the error of the material part only (the stress stiffness is
//! a first-derivative form, of lower order than the material energy for
//! the short-wave error). Contact penalties, cohesive interfaces and the
//! B-bar projection of the volumetric strain are not in `σ_h` either (the
//! assumed in-section shear is: `σ_h = C ε̄`, the kernel's strain); at
//! yielded points the elastic stiffness stands in for the tangent (the
//! static estimate's convention).
//!
//! **Layered bodies.** The patches of the recovery keep to the section
//! elements of one material ([`super::spr`]), so the stress jumps between
//! plies and material zones are not counted as error.

use super::estimate::{ErrorEstimate, of_state};
use crate::setup::Discretisation;
use crate::voigt::Voigt;

/// The estimate of one eigenpair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModeError {
    /// The recovered-stress estimate of the mode shape (per element, and
    /// its norm against the shape's own energy).
    pub estimate: ErrorEstimate,
    /// `r`, the estimated relative error of the eigenvalue `(λ_h − λ) / λ_h`
    /// (module docs).
    pub eigenvalue: f64,
}

impl ModeError {
    /// The estimated relative error of the natural frequency, `(f_h − f) / f ≈ r / 2`.
    pub fn frequency(&self) -> f64 {
        0.5 * self.eigenvalue
    }
}

/// `σ_h = C ε(u)` at every Gauss point (each body from the returned offset,
/// element-major, axis point outer, section point inner), `u` 3 per node.
pub(crate) fn stresses(d: &Discretisation<'_>, u: &[f64]) -> (Vec<Voigt>, Vec<usize>) {
    let mut out = Vec::new();
    let mut offsets = Vec::with_capacity(d.mesh.bodies.len());
    let (mut nodes, mut grads, mut local) = (Vec::new(), Vec::new(), Vec::new());
    // the assumed shear's axis-contracted displacements v_τ, v'_τ (the kernel's)
    let (mut v, mut vy) = (Vec::new(), Vec::new());
    for (b, body) in d.mesh.bodies.iter().enumerate() {
        offsets.push(out.len());
        let cell = &d.cells[b];
        v.resize(cell.section.n_fun, [0.0; 3]);
        vy.resize(cell.section.n_fun, [0.0; 3]);
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            let c = d.materials[body.material_of(es)].elastic_stiffness();
            body.element_nodes(e, &mut nodes);
            local.clear();
            local.extend(nodes.iter().flat_map(|&n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]));
            grads.resize(nodes.len(), [0.0; 3]);
            for gb in 0..cell.axis.n_gp {
                if cell.shear.is_some() {
                    crate::elements::contract_axis(&cell.axis.point(eb, gb), &local, &mut v, &mut vy);
                }
                for gs in 0..cell.section.n_gp {
                    cell.gradients(es, eb, gb, gs, &mut grads);
                    let mut eps = crate::values::strain(&grads, &local);
                    if let Some(sh) = &cell.shear {
                        // the kernel's strain: the assumed shear's change
                        sh.add_strain(es, gs, &v, &mut eps);
                    }
                    out.push(crate::voigt::mat_vec(c, &eps));
                }
            }
        }
    }
    (out, offsets)
}

/// The estimate of an eigenpair: `shape` per DOF (any scaling),
/// `stiffness` its `φ_hᵀ K φ_h` in the same scaling (`λ_h φ_hᵀ M φ_h` of a
/// vibration mode, `μ_h φ_hᵀ G φ_h` of a buckling mode).
pub(crate) fn mode_error(d: &Discretisation<'_>, shape: &[f64], stiffness: f64) -> ModeError {
    let (sigma, offsets) = stresses(d, shape);
    // with the section stage's part: where `--adapt` on modes refines
    // (across the section or along the axis), as for the static estimate
    let estimate = of_state(d.mesh, d.cells, d.materials, (&sigma, &[]), &offsets, None);
    let eigenvalue = if stiffness > 0.0 { estimate.error * estimate.error / stiffness } else { 0.0 };
    ModeError { estimate, eigenvalue }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A [0/90/0] laminate of three plies, two L9 through each and two across.
    const LAMINATE: &str = r#"
        [analysis]
        type = "modal"
        [[materials]]
        name = "ply"
        orthotropic = { e1 = 181e9, e2 = 10.3e9, e3 = 10.3e9, g12 = 7.17e9, g13 = 7.17e9, g23 = 3.6786e9, nu12 = 0.28, nu13 = 0.28, nu23 = 0.4 }
        density = 1600.0
        [[bodies]]
        name = "plate"
        section = { shape = "laminate", element = "L9", x = { from = 0.0, to = 0.01, elements = 2 }, plies = [
          { thickness = 0.001, material = "ply", angle = 0.0, elements = 2 },
          { thickness = 0.001, material = "ply", angle = 90.0, elements = 2 },
          { thickness = 0.001, material = "ply", angle = 0.0, elements = 2 } ] }
        axis = { element = "B4", from = 0.0, to = 0.1, elements = 3 }
        [[constraints]]
        name = "root"
        body = "plate"
        where = { y = 0.0 }
        fix = ["x", "y", "z"]
    "#;

    /// The patch test of a layered body: a uniform in-plane strain
    /// (ε_xx, ε_yy, γ_xy) with each ply's own ε_zz leaving σ_zz = 0 (a
    /// laminate stretched and sheared in its plane: the traction between
    /// the plies is zero, as equilibrium asks) gives in-plane stresses
    /// constant in each ply and jumping between them (the plies' stiffness
    /// along y differs 17.6-fold); the recovery per ply reproduces them and
    /// the traction components recovered across the plies are zero, so the
    /// estimate is zero. A recovery whose patches cross the plies for every
    /// component would count the jumps as error.
    #[test]
    fn a_uniform_strain_of_a_laminate_has_no_estimated_error() {
        let model = crate::setup::Model::parse(LAMINATE).unwrap();
        assert!(model.mesh.bodies[0].is_layered());
        let body = &model.mesh.bodies[0];
        let (a, b, c) = (1e-4, 2e-4, 4e-5);
        // ply k ∈ [0.001 k, 0.001 (k + 1)]: its stiffness, from a section
        // element whose centre lies in it
        let ply = |z: f64| ((z / 0.001).floor() as usize).min(2);
        let stiffness = |k: usize| {
            let es = (0..body.section.n_elements())
                .find(|&es| {
                    let nodes = body.section.element(es);
                    let zc = nodes.iter().map(|&t| body.section.nodes[t][1]).sum::<f64>() / nodes.len() as f64;
                    ply(zc) == k
                })
                .unwrap();
            *model.materials[body.material_of(es)].elastic_stiffness()
        };
        // σ_zz = C_zx a + C_zy b + C_zz ε_zz = 0 in each ply (0° and 90°
        // plies: no coupling of the normal stresses with the shears)
        let ezz: Vec<f64> = (0..3)
            .map(|k| {
                let m = stiffness(k);
                -(m[2][0] * a + m[2][1] * b) / m[2][2]
            })
            .collect();
        let uz = |z: f64| (0..3).map(|k| ezz[k] * (z - 0.001 * k as f64).clamp(0.0, 0.001)).sum::<f64>();
        let u: Vec<f64> = (0..model.mesh.n_nodes())
            .flat_map(|n| {
                let [x, y, z] = model.mesh.coords(n);
                [a * x + c * y, b * y, uz(z)]
            })
            .collect();
        let d = model.discretisation();
        let (sigma, _) = stresses(&d, &u);
        let syy: Vec<f64> = sigma.iter().map(|s| s[1]).collect();
        let (lo, hi) = syy.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &s| (a.min(s), b.max(s)));
        assert!(hi > 5.0 * lo && lo > 0.0, "the stress jumps between the plies: {lo} {hi}");
        let szz = sigma.iter().fold(0.0f64, |m, s| m.max(s[2].abs()));
        assert!(szz < 1e-9 * hi, "no traction between the plies: {szz}");
        let out = mode_error(&d, &u, 1.0);
        assert!(out.estimate.relative() < 1e-8, "{}", out.estimate.relative());
    }
}
