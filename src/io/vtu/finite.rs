//! The finite-strain measures of `gauss.vtu` beside the analysis's own.

use super::Array;
use crate::post::{FieldView, Location};
use crate::setup::Model;

/// At every Gauss point (the order of [`super::write_gauss_vtu`]), from the
/// deformation gradient `F = I + ∇u` of the displacement and the Cauchy
/// stress σ of the run's field `view`: the second Piola–Kirchhoff stress
/// `S = J F⁻¹ σ F⁻ᵀ`
/// (`pk2_xx`…`pk2_yz`, Pa), the Green–Lagrange strain (`gl_xx`…`gl_yz`) and
/// the logarithmic strain `½ ln C` (`log_xx`…`log_yz`), shears as
/// engineering strains (`crate::voigt`) — each measure beside the one the
/// analysis used, whichever `analysis.strain` is.
pub(super) fn finite_strain_data(model: &Model, view: &FieldView<'_>) -> Vec<(String, usize, Array)> {
    let mut columns: [Vec<f64>; 18] = Default::default();
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let cell = &model.cells[b];
        let ngp = cell.gp_per_element();
        for e in 0..body.n_elements() {
            for gb in 0..cell.axis.n_gp {
                for gs in 0..cell.section.n_gp {
                    let [xi, eta] = cell.section.natural[gs];
                    let natural = [xi, eta, cell.axis.natural[gb]];
                    let pv = crate::values::PointValues::new(body, &Location { body: b, element: e, natural });
                    let h = pv.gradient(view.u);
                    let f = crate::kinematics::deformation_gradient(&h);
                    let sigma = view.stresses[view.gp_offsets[b] + e * ngp + gb * cell.section.n_gp + gs];
                    let measures = [
                        crate::kinematics::second_piola(&f, &sigma),
                        crate::kinematics::green_lagrange(&h),
                        crate::kinematics::hencky::log_strain(&h),
                    ];
                    for (m, values) in measures.iter().enumerate() {
                        for k in 0..6 {
                            columns[6 * m + k].push(values[k]);
                        }
                    }
                }
            }
        }
    }
    let components = ["xx", "yy", "zz", "xy", "xz", "yz"];
    columns
        .into_iter()
        .enumerate()
        .map(|(c, v)| (format!("{}_{}", ["pk2", "gl", "log"][c / 6], components[c % 6]), 1, Array::F64(v)))
        .collect()
}
