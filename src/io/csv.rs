//! CSV files: lines, load histories and contact points.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{IoError, file_error};
use crate::analysis::Solution;
use crate::post::{LineSample, Quantity};
use crate::setup::Model;
use crate::setup::steps::{self, Item};

/// A text field of a CSV row (RFC 4180): quoted, with its quotes doubled,
/// if it holds a comma, a quote or a line break; as it is otherwise. Every
/// text written into a CSV goes through this (names are restricted to
/// letters, digits, `_`, `-` and `.` today, but a reader must never see a
/// row with a column too many).
pub fn field(s: &str) -> std::borrow::Cow<'_, str> {
    if s.contains([',', '"', '\n', '\r']) { format!("\"{}\"", s.replace('"', "\"\"")).into() } else { s.into() }
}

fn write(path: &Path, text: &str) -> Result<(), IoError> {
    std::fs::write(path, text).map_err(|e| file_error(path, e))
}

/// `s,x,y,z,u_x,…,peeq,e_xx,…` — one row per sample; rows outside every
/// body are omitted.
pub fn write_line(path: &Path, samples: &[LineSample], quantities: &[Quantity]) -> Result<(), IoError> {
    let mut text = String::from("s,x,y,z");
    for q in quantities {
        text.push(',');
        text.push_str(&q.name());
    }
    text.push('\n');
    for s in samples {
        let Some(v) = s.sample else { continue };
        let _ = write!(text, "{:e},{:e},{:e},{:e}", s.s, s.point[0], s.point[1], s.point[2]);
        for &q in quantities {
            let _ = write!(text, ",{:e}", v.get(q));
        }
        text.push('\n');
    }
    write(path, &text)
}

/// One CSV per constraint set (reaction against prescribed displacement)
/// and per contact (resultant force against indenter displacement), each
/// matched to its history entries by name. In a model with symmetry planes
/// an item that has a force on the full structure (`bc::symmetry::Symmetry::full`:
/// not a plane's own reaction) gets it in three more columns, `full_r_*`
/// or `full_f_*`, as `summary.json`'s `full_structure_force`.
pub fn write_histories(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut out = Vec::new();
    for (ci, c) in model.constraints.iter().enumerate() {
        let full = |r: [f64; 3]| model.symmetry.full(&c.name, r);
        let mut text = String::from("increment,lambda,iterations,u_x,u_y,u_z,r_x,r_y,r_z");
        text.push_str(if full([0.0; 3]).is_some() { ",full_r_x,full_r_y,full_r_z\n" } else { "\n" });
        for row in &solution.history {
            let a = steps::factor(&model.steps, Item::Constraint(ci), row.lambda);
            let u = c.values.map(|v| v.map_or(String::new(), |v| format!("{:e}", a * v)));
            let r = row.reaction(&c.name).map_or([f64::NAN; 3], |r| r.force);
            // no reaction recorded: NaN in the full columns too, not the
            // plane's cancelled 0 (as Python's Results.history)
            let full_r = if r[0].is_nan() { full(r).map(|_| r) } else { full(r) };
            let _ = write!(
                text,
                "{},{:e},{},{},{},{},{:e},{:e},{:e}",
                row.increment, row.lambda, row.iterations, u[0], u[1], u[2], r[0], r[1], r[2]
            );
            end_row(&mut text, full_r);
        }
        let path = dir.join(format!("history_{}.csv", c.name));
        write(&path, &text)?;
        out.push(path);
    }
    for set in &solution.contact_sets {
        let is_indenter = model.indenters.iter().any(|i| i.name == set.name);
        let full = |f: [f64; 3]| model.symmetry.full(&set.name, f);
        let mut text =
            String::from("increment,lambda,iterations,d_x,d_y,d_z,f_x,f_y,f_z,max_penetration,plastic_points,f_n,f_t");
        text.push_str(if full([0.0; 3]).is_some() { ",full_f_x,full_f_y,full_f_z\n" } else { "\n" });
        for row in &solution.history {
            let Some(c) = row.contact(&set.name) else { continue };
            let d = if is_indenter { c.displacement.map(|v| format!("{v:e}")) } else { Default::default() };
            let f = c.force;
            let _ = write!(
                text,
                "{},{:e},{},{},{},{},{:e},{:e},{:e},{:e},{},{:e},{:e}",
                row.increment,
                row.lambda,
                row.iterations,
                d[0],
                d[1],
                d[2],
                f[0],
                f[1],
                f[2],
                c.max_penetration,
                row.plastic_points,
                norm(c.normal_force),
                norm(c.tangential_force)
            );
            end_row(&mut text, full(f));
        }
        let path = dir.join(format!("history_{}.csv", set.name));
        write(&path, &text)?;
        out.push(path);
    }
    if !model.probes.is_empty() {
        out.push(write_probe_history(model, solution, dir)?);
    }
    if !solution.history.is_empty() {
        out.push(write_increment_history(solution, dir)?);
    }
    Ok(out)
}

/// `history.csv`: one row per converged increment — load factor, Newton
/// iterations, plastic Gauss points and the negative pivots of the last
/// factorized tangent (empty when not known), which count the tangent's
/// negative eigenvalues: a change marks a limit or bifurcation point.
fn write_increment_history(solution: &Solution, dir: &Path) -> Result<PathBuf, IoError> {
    let mut text = String::from("increment,lambda,iterations,plastic_points,negative_pivots\n");
    for row in &solution.history {
        let pivots = row.negative_pivots.map_or(String::new(), |n| n.to_string());
        let _ = writeln!(text, "{},{:e},{},{},{pivots}", row.increment, row.lambda, row.iterations, row.plastic_points);
    }
    let path = dir.join("history.csv");
    write(&path, &text)?;
    Ok(path)
}

/// `history_probes.csv`: the displacement of every probe at every increment
/// (columns `<probe>.u_x`, `<probe>.u_y`, `<probe>.u_z`).
fn write_probe_history(model: &Model, solution: &Solution, dir: &Path) -> Result<PathBuf, IoError> {
    let mut text = String::from("increment,lambda,iterations");
    for p in &model.probes {
        let _ = write!(text, ",{0}.u_x,{0}.u_y,{0}.u_z", p.name);
    }
    text.push('\n');
    for row in &solution.history {
        let _ = write!(text, "{},{:e},{}", row.increment, row.lambda, row.iterations);
        for u in &row.probes {
            let _ = write!(text, ",{:e},{:e},{:e}", u[0], u[1], u[2]);
        }
        text.push('\n');
    }
    let path = dir.join("history_probes.csv");
    write(&path, &text)?;
    Ok(path)
}

/// Final state of each contact point, one CSV per indenter or contact.
pub fn write_contact_points(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut out = Vec::new();
    for set in &solution.contact_sets {
        let mut text = String::from("node,x,y,z,gap,f_x,f_y,f_z,area,pressure,traction,active,slip,sliding\n");
        for p in &set.points {
            let x = model.mesh.coords(p.node);
            let f = p.force;
            // normal and tangential parts of the force, per tributary area
            // (as the contact VTU)
            let f_n: f64 = (0..3).map(|k| f[k] * p.normal[k]).sum();
            let f_t = (0..3).map(|k| (f[k] - f_n * p.normal[k]).powi(2)).sum::<f64>().sqrt();
            let (pressure, traction) = (f_n / p.area, f_t / p.area);
            let slip = (p.slip[0] * p.slip[0] + p.slip[1] * p.slip[1] + p.slip[2] * p.slip[2]).sqrt();
            let _ = writeln!(
                text,
                "{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{}",
                p.node,
                x[0],
                x[1],
                x[2],
                p.gap,
                f[0],
                f[1],
                f[2],
                p.area,
                pressure,
                traction,
                u8::from(p.active),
                slip,
                u8::from(p.sliding)
            );
        }
        let path = dir.join(format!("contact_{}.csv", set.name));
        write(&path, &text)?;
        out.push(path);
    }
    Ok(out)
}

/// Ends a history row, with the full structure's force if there is one.
fn end_row(text: &mut String, full: Option<[f64; 3]>) {
    if let Some(f) = full {
        let _ = write!(text, ",{:e},{:e},{:e}", f[0], f[1], f[2]);
    }
    text.push('\n');
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::field;

    /// RFC 4180: a field with a comma, quote or line break is quoted and its
    /// quotes doubled, so a CSV reader sees one column.
    #[test]
    fn fields_are_quoted_when_needed() {
        assert_eq!(field("tip-1.a"), "tip-1.a");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"hi\"\nnow"), "\"say \"\"hi\"\"\nnow\"");
    }
}
