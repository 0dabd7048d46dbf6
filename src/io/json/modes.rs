//! The eigen-analyses in `summary.json`: vibration modes (`modal`) and
//! buckling modes (`buckling`), each with its estimated errors, and the
//! names of the mode VTUs.

use serde::Serialize;

use crate::analysis::{Solution, tables};
use crate::setup::Model;

/// The modal analysis in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ModalSummary {
    /// Natural frequencies f (Hz), ascending.
    pub frequencies_hz: Vec<f64>,
    /// Effective masses of each mode in x, y and z (kg).
    pub effective_masses: Vec<[f64; 3]>,
    /// The mass moving with the free DOFs in x, y and z (kg): the sums of
    /// all modes' effective masses.
    pub free_mass: [f64; 3],
    /// Whose masses these are: `"model"`, or `"full_structure"` for a
    /// model cut by symmetry planes (the mirror images together; its modes
    /// are the symmetric ones, whose effective mass along a plane's normal
    /// is zero: `crate::analysis::modal`).
    pub effective_masses_of: &'static str,
    /// The estimated relative error of each frequency, `(f_h − f) / f`
    /// (the computed frequencies are upper bounds; `post::mode_error`).
    pub frequency_errors: Vec<f64>,
    /// The estimated relative error of each mode in the energy norm (the
    /// static estimate's measure applied to the mode shape).
    pub mode_errors: Vec<f64>,
    /// The VTU of each mode (`mode_<k>.vtu`), or empty without VTU output.
    pub modes: Vec<String>,
}

/// The buckling analysis in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BucklingSummary {
    /// Critical load factors, ascending: the model's loads times each buckle.
    pub factors: Vec<f64>,
    /// Critical loads: the applied load (N, the sum of the loads at factor 1) times each factor.
    /// In a model cut by symmetry planes, the load on the part modelled.
    pub critical_loads: Vec<[f64; 3]>,
    /// In a model cut by symmetry planes, the full structure's critical loads: its applied
    /// load (the part's and its mirror images', `bc::symmetry::full_structure` across every
    /// plane) times each factor; `None` without planes (the critical loads are the structure's).
    pub full_structure_critical_loads: Option<Vec<[f64; 3]>>,
    /// The estimated relative error of each factor, `(μ_h − μ) / μ_h` (`post::mode_error`).
    pub factor_errors: Vec<f64>,
    /// The estimated relative error of each mode in the energy norm.
    pub mode_errors: Vec<f64>,
    /// The VTU of each mode (`mode_<k>.vtu`), or empty without VTU output.
    pub modes: Vec<String>,
}

/// The modal analysis of `solution` from its table (`analysis::tables::modes`).
pub(super) fn modal_summary(model: &Model, solution: &Solution) -> Option<ModalSummary> {
    let (m, table) = (solution.modal.as_ref()?, tables::modes(solution)?);
    let frequencies_hz = table.real("frequency_hz").unwrap_or_default();
    Some(ModalSummary {
        modes: mode_files(model, frequencies_hz.len()),
        frequencies_hz,
        effective_masses: table.xyz("effective_mass_").unwrap_or_default(),
        free_mass: m.free_mass,
        effective_masses_of: if m.full_structure { "full_structure" } else { "model" },
        frequency_errors: table.real("frequency_error").unwrap_or_default(),
        mode_errors: table.real("mode_error").unwrap_or_default(),
    })
}

/// The buckling analysis of `solution` from its table (`analysis::tables::buckling`).
pub(super) fn buckling_summary(model: &Model, solution: &Solution) -> Option<BucklingSummary> {
    let table = tables::buckling(model, solution)?;
    let factors = table.real("load_factor").unwrap_or_default();
    Some(BucklingSummary {
        modes: mode_files(model, factors.len()),
        factors,
        critical_loads: table.xyz("critical_load_").unwrap_or_default(),
        full_structure_critical_loads: table.xyz("full_critical_load_"),
        factor_errors: table.real("factor_error").unwrap_or_default(),
        mode_errors: table.real("mode_error").unwrap_or_default(),
    })
}

/// The VTU files of `n` modes, none without VTU output.
fn mode_files(model: &Model, n: usize) -> Vec<String> {
    if model.output.vtu { (1..=n).map(mode_vtu_name).collect() } else { Vec::new() }
}

/// The VTU file name of buckling or vibration mode `k` (1-based).
pub(crate) fn mode_vtu_name(k: usize) -> String {
    format!("mode_{k}.vtu")
}
