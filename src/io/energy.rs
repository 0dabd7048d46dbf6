//! `energy.csv` and `energy.png`: the energy balance of a transient
//! analysis per converged time step (`dynamics::energy`).

use std::path::{Path, PathBuf};

use super::IoError;
use super::png::{Series, line_plot};
use crate::analysis::{Solution, tables};
use crate::setup::Model;

/// Writes the energy balance of a transient run (nothing for another):
/// its table ([`tables::energy`]) and, with plots, their curves.
pub(crate) fn write_energy(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let Some(table) = tables::energy(solution) else { return Ok(Vec::new()) };
    let mut written = vec![super::csv::write_table(&table, dir)?];
    if model.output.plots {
        let time = table.real("time").unwrap_or_default();
        let column = |name: &str| table.real(name).unwrap_or_default();
        let series = |name: &str, values: Vec<f64>| Series {
            name: name.into(),
            points: time.iter().zip(values).map(|(t, v)| (t * 1e3, v)).collect(),
            dashed: false,
        };
        let (external, contact, supports) = (column("external"), column("contact"), column("supports"));
        let work = (0..time.len()).map(|i| external[i] + contact[i] + supports[i]).collect();
        let path = dir.join("energy.png");
        let mut curves = vec![
            series("kinetic T", column("kinetic")),
            series("internal work", column("internal")),
            series("elastic strain energy", column("elastic")),
            series("plastic dissipation", column("plastic")),
            series("work of loads, contacts and supports", work),
            series("damping", column("damping")),
            series("balance", column("balance")),
        ];
        if let Some(delamination) = table.real("delamination") {
            curves.push(series("delamination", delamination));
        }
        let modes = crate::materials::damage::MODES.map(|m| table.real(&format!("damage_{m}")));
        if modes.iter().all(Option::is_some) {
            let damage = (0..time.len()).map(|i| modes.iter().flatten().map(|c| c[i]).sum()).collect();
            curves.push(series("ply damage (all modes)", damage));
        }
        line_plot(&path, "energy balance", "time [ms]", "energy [J]", &curves)?;
        written.push(path);
    }
    Ok(written)
}
