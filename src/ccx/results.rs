//! Reading CalculiX results: nodal fields from the `.frd` file and force
//! totals from the `.dat` file, of the last increment written.
//!
//! `.frd` result blocks start with a `-4  NAME` line, have `-5` component
//! lines and one `-1` line per node: the node number in 10 columns after
//! ` -1`, then the values in 12 columns each. Stress components come as
//! SXX SYY SZZ SXY SYZ SZX and are reordered here to the Voigt order of
//! [`crate::voigt`] (xx, yy, zz, xy, xz, yz).

use std::collections::HashMap;

use super::CcxError;

/// Nodal results of the last increment.
#[derive(Debug, Clone, Default)]
pub struct NodalResults {
    /// Displacement per node (node number → value).
    pub u: HashMap<usize, [f64; 3]>,
    /// Stress per node, Voigt order.
    pub stress: HashMap<usize, [f64; 6]>,
    /// Equivalent plastic strain per node (absent for elastic models).
    pub peeq: HashMap<usize, f64>,
    /// Step time (load factor) of these results.
    pub time: f64,
}

fn parse_values(line: &str) -> Option<(usize, Vec<f64>)> {
    let node: usize = line.get(3..13)?.trim().parse().ok()?;
    let rest = line.get(13..)?;
    let mut values = Vec::new();
    let mut i = 0;
    while i + 12 <= rest.len() {
        values.push(rest[i..i + 12].trim().parse().ok()?);
        i += 12;
    }
    Some((node, values))
}

/// Parses the `.frd` text, keeping the last block of each field.
pub fn read_frd(text: &str, path: &str) -> Result<NodalResults, CcxError> {
    let mut out = NodalResults::default();
    let mut current: Option<String> = None;
    let mut block_time = 0.0;
    for line in text.lines() {
        if line.starts_with("  100C") {
            // "  100CL  101 1.000000000 ..." : the step time in columns 13–25
            block_time = line.get(12..25).and_then(|t| t.trim().parse().ok()).unwrap_or(block_time);
            continue;
        }
        if let Some(rest) = line.strip_prefix(" -4") {
            let name = rest.split_whitespace().next().unwrap_or("").to_string();
            match name.as_str() {
                "DISP" => out.u.clear(),
                "STRESS" => out.stress.clear(),
                "PE" | "PEEQ" => out.peeq.clear(),
                _ => {}
            }
            current = Some(name);
            out.time = block_time;
            continue;
        }
        if line.starts_with(" -3") {
            current = None;
            continue;
        }
        if !line.starts_with(" -1") {
            continue;
        }
        let Some(name) = current.as_deref() else { continue };
        let Some((node, v)) = parse_values(line) else {
            return Err(CcxError::Results { path: path.to_string(), message: format!("unreadable line {line:?}") });
        };
        match name {
            "DISP" if v.len() >= 3 => {
                out.u.insert(node, [v[0], v[1], v[2]]);
            }
            "STRESS" if v.len() >= 6 => {
                out.stress.insert(node, [v[0], v[1], v[2], v[3], v[5], v[4]]);
            }
            "PE" | "PEEQ" if !v.is_empty() => {
                out.peeq.insert(node, v[0]);
            }
            _ => {}
        }
    }
    if out.u.is_empty() {
        return Err(CcxError::Results { path: path.to_string(), message: "no displacement results".into() });
    }
    Ok(out)
}

/// Force histories from the `.dat` file: for each node set, the force
/// (total, or the sum of the listed nodal forces) at every printed
/// increment, as `(step time, force)` in the file's order.
pub fn read_dat_history(text: &str) -> HashMap<String, Vec<(f64, [f64; 3])>> {
    let mut out: HashMap<String, Vec<(f64, [f64; 3])>> = HashMap::new();
    for (set, force, time) in dat_blocks(text) {
        out.entry(set).or_default().push((time, force));
    }
    out
}

/// Force totals from the `.dat` file: for each node set, the last
/// `total force` (sets printed with `TOTALS=ONLY`) or the sum of the last
/// listed nodal forces, with the step time they belong to.
pub fn read_dat(text: &str) -> HashMap<String, ([f64; 3], f64)> {
    dat_blocks(text).into_iter().map(|(set, force, time)| (set, (force, time))).collect()
}

/// Every force block of the `.dat` file, in order: `(set, force, time)`.
fn dat_blocks(text: &str) -> Vec<(String, [f64; 3], f64)> {
    let mut out = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i].trim();
        let header = l.starts_with("total force (fx,fy,fz) for set") || l.starts_with("forces (fx,fy,fz) for set");
        if !header {
            i += 1;
            continue;
        }
        let total = l.starts_with("total");
        let words: Vec<&str> = l.split_whitespace().collect();
        let set = words.iter().position(|w| *w == "set").and_then(|p| words.get(p + 1)).map(|s| s.to_string());
        let time = words.last().and_then(|t| t.parse::<f64>().ok()).unwrap_or(0.0);
        i += 1;
        let mut sum = [0.0; 3];
        while i < lines.len() && lines[i].trim().is_empty() {
            i += 1;
        }
        while i < lines.len() && !lines[i].trim().is_empty() {
            let v: Vec<f64> = lines[i].split_whitespace().filter_map(|w| w.parse().ok()).collect();
            let f = if total { v.get(0..3) } else { v.get(1..4) };
            if let Some(f) = f {
                for k in 0..3 {
                    sum[k] += f[k];
                }
            }
            i += 1;
            if total {
                break;
            }
        }
        if let Some(set) = set {
            out.push((set, sum, time));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_last_blocks_and_reorders_stress() {
        let frd = "\
    1C
  100CL  101 0.500000000          2                     0    1           1
 -4  DISP        4    1
 -1         1 1.00000E-03 2.00000E-03 3.00000E-03
 -3
  100CL  101 1.000000000          2                     0    1           1
 -4  DISP        4    1
 -1         1 2.00000E-03 4.00000E-03 6.00000E-03
 -3
 -4  STRESS      6    1
 -1         1 1.00000E+00 2.00000E+00 3.00000E+00 4.00000E+00 5.00000E+00 6.00000E+00
 -3
";
        let r = read_frd(frd, "x.frd").unwrap();
        assert_eq!(r.u[&1], [2e-3, 4e-3, 6e-3]);
        // SXX SYY SZZ SXY SYZ SZX → xx yy zz xy xz yz
        assert_eq!(r.stress[&1], [1.0, 2.0, 3.0, 4.0, 6.0, 5.0]);
        assert_eq!(r.time, 1.0);
        let dat = "\n total force (fx,fy,fz) for set C_ROOT and time  0.5000000E+00\n\n       1.0  2.0  3.0\n\n total force (fx,fy,fz) for set C_ROOT and time  0.1000000E+01\n\n       -2.5E-10  3.9E-10  1.0E+03\n\n forces (fx,fy,fz) for set REF_P and time  0.1000000E+01\n\n        91 1.0 2.0 -5.0\n";
        let t = read_dat(dat);
        assert_eq!(t["C_ROOT"].0[2], 1e3);
        assert_eq!(t["C_ROOT"].1, 1.0);
        assert_eq!(t["REF_P"].0, [1.0, 2.0, -5.0]);
    }
}
