//! `energy.csv` and `energy.png`: the energy balance of a transient
//! analysis per converged time step (`dynamics::energy`).

use std::path::{Path, PathBuf};

use super::IoError;
use super::png::{Series, line_plot};
use crate::analysis::Solution;
use crate::setup::Model;

/// Writes the energy balance of a transient run (nothing for another).
pub fn write_energy(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let Some(rows) = &solution.energy else { return Ok(Vec::new()) };
    let mut text = String::from(
        "time_s,kinetic_J,internal_J,elastic_J,plastic_J,damping_J,external_J,contact_J,supports_J,balance_J,impactors_J\n",
    );
    for r in rows {
        let values = [
            r.time,
            r.kinetic,
            r.internal,
            r.elastic,
            r.plastic,
            r.damping,
            r.external,
            r.contact,
            r.supports,
            r.balance,
            r.impactors,
        ];
        let line: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
        text.push_str(&line.join(","));
        text.push('\n');
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
                series("elastic strain energy", |r| r.elastic),
                series("plastic dissipation", |r| r.plastic),
                series("work of loads, contacts and supports", |r| r.external + r.contact + r.supports),
                series("damping", |r| r.damping),
                series("balance", |r| r.balance),
            ],
        )?;
        written.push(path);
    }
    Ok(written)
}
