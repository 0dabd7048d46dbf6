//! The error estimate of a layered body's static solution (issue 49:
//! "an error estimate for every body, layered and multi-material bodies
//! included"): the recovered-stress estimate (`post::estimate`) with the
//! patch recovery kept to each ply (`post::spr`), against the true error of
//! Pagano's cylindrical bending of a `[0/90/0]` laminate, whose exact 3D
//! elasticity solution is known (N. J. Pagano, J. Composite Materials 3
//! (1969) 398; `tests/common/pagano.rs`, checked on its own in
//! tests/oracles_selfcheck.rs). The model is `examples/pagano_s4.toml`
//! (span/thickness 4, plane strain, sine pressure) on coarser meshes of L9
//! through the plies and B4 along the span: its solution converges to
//! Pagano's with no singular point (the supports hold `u_z` only, as
//! Pagano's), so the true error is the whole laminate's, nothing left out.
//!
//! The true error in the energy norm, `‖e‖² = ∫ (σ − σ_h)ᵀ C⁻¹ (σ − σ_h)`,
//! is integrated at the model's Gauss points with the exact stress and the
//! ply's compliance written here from its engineering constants (not the
//! solver's). The effectivity `η / ‖e‖` is asserted in issue 23's band
//! 0.7–1.5, the band of the homogeneous bodies' estimates
//! (tests/estimator.rs).

#[path = "common/pagano.rs"]
mod pagano;
// only its Gauss points: the rest of the module (isotropic truths) is unused here
#[path = "common/truth.rs"]
#[allow(dead_code)]
mod truth;
use truth::gauss_points;

mod common;

use cufem::adapt::Source;
use cufem::analysis::Silent;
use cufem::setup::AdaptSettings;
use cufem::setup::Model;
use pagano::{Pagano, Ply};

/// Pagano's material with E2 = 1 GPa (the example's plies).
fn ply(thickness: f64, angle_deg: f64) -> Ply {
    Ply::pagano(thickness, angle_deg, 1e9)
}

/// `σᵀ C⁻¹ σ` (Voigt order xx, yy, zz, xy, xz, yz; `src/voigt.rs`) of a
/// ply of [`ply`]'s material whose fibre lies along y (0°) or x (90°).
fn complementary(s: &[f64; 6], angle_deg: f64) -> f64 {
    let e2: f64 = 1e9;
    let (e_fibre, e_trans, e_normal) = (25.0 * e2, e2, e2);
    let nu = 0.25;
    // moduli along x, y, z and shear moduli xy, xz, yz
    let (ex, ey, gxz, gyz) =
        if angle_deg == 0.0 { (e_trans, e_fibre, 0.2 * e2, 0.5 * e2) } else { (e_fibre, e_trans, 0.5 * e2, 0.2 * e2) };
    let (ez, gxy) = (e_normal, 0.5 * e2);
    // ν_ij / E_i = ν_ji / E_j: the major ratio belongs to the fibre (stiffer)
    // direction, 0.25 for every pair of the material's axes
    let sxy = -nu / ex.max(ey);
    let sxz = -nu / ex.max(ez);
    let syz = -nu / ey.max(ez);
    let [xx, yy, zz, xy, xz, yz] = *s;
    xx * xx / ex
        + yy * yy / ey
        + zz * zz / ez
        + 2.0 * (sxy * xx * yy + sxz * xx * zz + syz * yy * zz)
        + xy * xy / gxy
        + xz * xz / gxz
        + yz * yz / gyz
}

/// The example with `through` L9 per ply and `along` B4 over the span.
fn model(through: usize, along: usize) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/pagano_s4.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let plies = "material = \"ply\", angle = 0.0, elements = 4 }";
    assert!(text.contains("element = \"L16\"") && text.contains(plies) && text.contains("elements = 8 }"));
    text.replace("element = \"L16\"", "element = \"L9\"")
        .replace("elements = 4 }", &format!("elements = {through} }}"))
        .replace("to = 0.04, elements = 8 }", &format!("to = 0.04, elements = {along} }}"))
}

/// `(η, ‖e‖)`: the estimate and the true error of the example on
/// `through` L9 per ply × `along` B4.
fn effectivity(through: usize, along: usize) -> (f64, f64) {
    let model = Model::parse(&model(through, along)).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    errors(&model, &solution, 0.04)
}

/// `(η, ‖e‖)` of `solution` on `model` (a mesh of the example), with
/// Galerkin orthogonality, `‖e‖² = ‖σ‖² − ‖σ_h‖²` (a conforming model of
/// linear elasticity), checking the integration of [`parts`] and the
/// compliance written here against the solver's own energy
/// (`estimate.energy`) within 2 %.
fn errors(model: &Model, solution: &cufem::analysis::Solution, span: f64) -> (f64, f64) {
    let (eta, error, orthogonal) = parts(model, solution, span);
    assert!((orthogonal / error - 1.0).abs() < 0.02, "‖e‖ {error:e} against √(E − E_h) {orthogonal:e}");
    (eta, error)
}

/// `(η, ‖e‖, √(‖σ‖² − ‖σ_h‖²))` of `solution` on `model` (a mesh of
/// examples/pagano_s4.toml or pagano_s50.toml: `span` 0.04 or 0.5 m), the
/// true error integrated at the model's Gauss points with Pagano's stress.
fn parts(model: &Model, solution: &cufem::analysis::Solution, span: f64) -> (f64, f64, f64) {
    let h = 0.01;
    let exact = Pagano::new(&[ply(h / 3.0, 0.0), ply(h / 3.0, 90.0), ply(h / 3.0, 0.0)], span, 1e5);
    // ‖e‖² and ‖σ‖² of the exact solution at the same points
    let (mut error2, mut exact2) = (0.0, 0.0);
    for (p, raw) in gauss_points(model).iter().zip(&solution.stresses) {
        let ([x, y, z], w) = (p.position, p.weight);
        assert!(x.abs() <= 0.0025 && z.abs() < h / 2.0);
        let k = exact.ply_at(z);
        let [syy, szz, tyz] = exact.stress_in_ply(k, y, z);
        let sxx = exact.sigma_xx_in_ply(k, y, z);
        let d = [sxx - raw[0], syy - raw[1], szz - raw[2], -raw[3], -raw[4], tyz - raw[5]];
        error2 += w * complementary(&d, if k == 1 { 90.0 } else { 0.0 });
        exact2 += w * complementary(&[sxx, syy, szz, 0.0, 0.0, tyz], if k == 1 { 90.0 } else { 0.0 });
    }
    let estimate = solution.error_estimate.as_ref().expect("a layered body's static solution is estimated");
    (estimate.error, error2.sqrt(), (exact2 - estimate.energy.powi(2)).sqrt())
}

/// One L9 through each ply (the usual laminate mesh) with 2 and 8 B4, and
/// two and four L9 per ply: the effectivity lies in issue 23's band
/// 0.7–1.5 on each (measured 1.14, 1.12, 1.14, 1.10), and the true error
/// falls under refinement. With patches kept to each ply for every
/// component, a ply one element thick is fitted by interpolation through
/// its thickness and the estimate of the one-L9 meshes is `0.003`–`0.26`
/// of the true error, which lies mostly in the transverse stresses
/// (`post::spr` recovers the tractions σ_zz, σ_xz, σ_yz across the plies
/// there); with patches across the plies for every component the jumps of
/// σ_yy count as error.
#[test]
fn the_layered_estimate_is_effective_against_pagano() {
    let mut last = f64::INFINITY;
    for (through, along) in [(1, 2), (1, 8), (2, 4), (4, 8)] {
        let (eta, error) = effectivity(through, along);
        assert!(error < last, "the true error grew under refinement");
        last = error;
        let id = format!("layered_estimate.pagano_s4.{through}L9_{along}B4");
        common::figure(&format!("{id}.effectivity"), eta / error, "", "in [0.7, 1.5] (issue 23's band)");
        common::figure(&format!("{id}.true_error"), error, "J^0.5", "falls under refinement");
        assert!((0.7..=1.5).contains(&(eta / error)), "{through} L9 × {along} B4: η = {eta:e}, ‖e‖ = {error:e}");
    }
}

/// `--adapt` from one L9 per ply and 2 B4 (the estimate `9.9 %`): the error
/// lies through the plies — the fit over the section holds nearly all of
/// it, the fit along the axis little — so the cycles double the plies'
/// elements and leave the axis (`adapt::mark::along_axis`), and only the
/// plies holding most of the section error (`adapt::mark::local`): the
/// middle 90° ply, then the outer ones, then the outer ones again with one
/// axis split (estimates `5.08`, `3.51`, `0.70 %`; 2,457 DOF at 4-2-4 L9 ×
/// 4 B4). The marking without direction — every ply doubled, every marked
/// element's axis interval split — reached `0.68 %` at 4 L9 per ply × 6 B4,
/// 4,275 DOF; the true error (Pagano) of the adapted mesh is within a tenth
/// of that uniform mesh's (measured `+5.6 %`), at 43 % fewer DOF.
/// Known limit (docs/limitations.md): the first cycle's doubling of the
/// middle ply leaves the true error as it was (the estimate halves): on
/// the one-L9 mesh the recovered tractions put the section error in the
/// middle ply while the error that counts sits in the outer ones.
#[test]
fn adapt_refines_a_laminate_through_its_plies() {
    let text = model(1, 2);
    let start = Model::parse(&text).unwrap();
    let source = Source { text: &text, base: std::path::Path::new("."), limits: cufem::setup::Limits::none() };
    let settings = AdaptSettings { tolerance: 0.01, max_cycles: 4, ..Default::default() };
    let mut cycles = Vec::new();
    cufem::adapt::run(start, source, &settings, &Default::default(), &mut Silent, &mut |_, m, s| {
        let section = &m.mesh.bodies[0].section;
        let ply = |k: usize| section.regions.iter().find(|r| r.name == format!("ply{k}")).unwrap().elements.len();
        let relative = s.error_estimate.as_ref().unwrap().relative();
        cycles.push((
            m.n_dofs(),
            relative,
            errors(m, s, 0.04).1,
            [ply(1), ply(2), ply(3)],
            m.mesh.bodies[0].axis.n_elements(),
        ))
    })
    .unwrap();
    common::figure("layered_estimate.adapt.cycles", (cycles.len() - 1) as f64, "", "3: middle ply, outer plies twice");
    let plies: Vec<_> = cycles.iter().map(|c| (c.3, c.4)).collect();
    assert_eq!(plies, [([1, 1, 1], 2), ([1, 2, 1], 2), ([2, 2, 2], 2), ([4, 2, 4], 4)], "{cycles:?}");
    let (dof, estimate, error, ..) = cycles[3];
    assert!(estimate < 0.01, "{cycles:?}");
    // the known limit, from both sides: the first cycle leaves the true error
    let first = cycles[1].2 / cycles[0].2;
    assert!((0.99..=1.01).contains(&first), "the first cycle's true error ratio {first}");
    assert!(cycles[2].2 < 0.5 * cycles[1].2 && error < 0.5 * cycles[2].2, "{cycles:?}");
    // against uniform refinement to the same estimate: 4 L9 per ply × 6 B4
    let uniform = Model::parse(&model(4, 6)).unwrap();
    let solved = cufem::analysis::run(&uniform, &Default::default(), &mut Silent).unwrap();
    let (_, uniform_error) = errors(&uniform, &solved, 0.04);
    common::figure("layered_estimate.adapt.dof_over_uniform", dof as f64 / uniform.n_dofs() as f64, "", "below 1");
    common::figure("layered_estimate.adapt.error_over_uniform", error / uniform_error, "", "at most 1.1");
    assert!(
        dof < uniform.n_dofs() && error <= 1.1 * uniform_error,
        "{dof} {} {error:e} {uniform_error:e}",
        uniform.n_dofs()
    );
}

/// The shipped meshes (examples/pagano_s4.toml and pagano_s50.toml: 4 L16
/// per ply × 8 B4) against Pagano's exact stress: the effectivity within
/// issue 49's `0.5`–`2` (measured 1.50 at S = 4 and 1.00 at S = 50, true
/// relative errors `0.03 %` and `0.13 %`). Galerkin orthogonality checks the
/// integration at S = 4 (within 2 %, as on the coarser meshes above); at
/// S = 50, where ‖σ_h‖² equals ‖σ‖² to 1.7 parts in a million, the
/// difference of the two energies is 3 % above ‖e‖ (the oracle's and the
/// quadrature's last digits, amplified `6·10⁵` times by the cancellation)
/// and is not asserted. Mutation: the section patches across the plies
/// (`post::spr`, every element of one zone: the jumps of σ_yy counted as
/// error) gives 490 at S = 4 and fails.
#[test]
fn the_shipped_pagano_meshes_are_estimated() {
    for (file, span) in [("pagano_s4", 0.04), ("pagano_s50", 0.5)] {
        let path = format!("{}/examples/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let model = Model::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
        let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
        let (eta, error) = if file == "pagano_s4" {
            errors(&model, &solution, span)
        } else {
            let (eta, error, _) = parts(&model, &solution, span);
            (eta, error)
        };
        let energy = solution.error_estimate.as_ref().unwrap().energy;
        let id = format!("layered_estimate.{file}.shipped");
        let relative = error / (error * error + energy * energy).sqrt();
        common::figure(&format!("{id}.true"), 100.0 * relative, "%", "reported: against Pagano's exact stress");
        common::figure(&format!("{id}.effectivity"), eta / error, "", "in [0.5, 2] (issue 49)");
        assert!((0.5..=2.0).contains(&(eta / error)), "{file}: η = {eta:e}, ‖e‖ = {error:e}");
    }
}
