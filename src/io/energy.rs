//! `energy.csv` and `energy.png`: the energy balance of a transient
//! analysis per converged time step (`dynamics::energy`).

use std::path::{Path, PathBuf};

use super::IoError;
use super::png::{Series, line_plot};
use crate::analysis::Solution;
use crate::model::Model;

/// Writes the energy balance of a transient run (nothing for another).
pub fn write_energy(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let Some(rows) = &solution.energy else { return Ok(Vec::new()) };
    let mut text = String::from("time_s,kinetic_J,internal_J,damping_J,external_J,contact_J,supports_J,balance_J\n");
    for r in rows {
        text.push_str(&format!(
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            r.time, r.kinetic, r.internal, r.damping, r.external, r.contact, r.supports, r.balance
        ));
    }
    let path = dir.join("energy.csv");
    std::fs::write(&path, text).map_err(|e| super::file_error(&path, e))?;
    let mut written = vec![path];
    if model.output.plots {
        let series = |name: &str, f: fn(&crate::dynamics::energy::EnergyRow) -> f64| Series {
            name: name.into(),
            points: rows.iter().map(|r| (r.time * 1e3, f(r))).collect(),
            dashed: false,
        };
        let path = dir.join("energy.png");
        line_plot(
            &path,
            "energy balance",
            "time [ms]",
            "energy [J]",
            &[
                series("kinetic T", |r| r.kinetic),
                series("internal work", |r| r.internal),
                series("work of loads, contacts and supports", |r| r.external + r.contact + r.supports),
                series("damping", |r| r.damping),
                series("balance", |r| r.balance),
            ],
        )?;
        written.push(path);
    }
    Ok(written)
}
