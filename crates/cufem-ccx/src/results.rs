//! Reading CalculiX results: nodal fields from the `.frd` file and force
//! totals from the `.dat` file, of the last increment written; of a
//! `*FREQUENCY` step every mode shape (`.frd`) and the eigenvalue table
//! (`.dat`).
//!
//! `.frd` result blocks start with a `-4  NAME` line, have `-5` component
//! lines and one `-1` line per node: the node number in 10 columns after
//! ` -1`, then the values in 12 columns each. Stress components come as
//! SXX SYY SZZ SXY SYZ SZX and are reordered here to the Voigt order of
//! [`cufem::voigt`] (xx, yy, zz, xy, xz, yz). A mode's block has `MODAL` in
//! its `100C` header line, whose value is the frequency (cycles/time). A
//! dynamic step's blocks have the type 1 (a time step; columns 57–58 of the
//! header, after the value and the node count) and the total time as their
//! value, a static step's the step time (the load factor): each one's
//! displacements are kept ([`NodalResults::history`]).

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
    /// Of a `*FREQUENCY` step: each mode's frequency (Hz, as its block
    /// header gives it) and displacement per node, in the file's order.
    pub modes: Vec<(f64, HashMap<usize, [f64; 3]>)>,
    /// Every increment's displacement per node, in the file's order, with
    /// its total time (s) in `*DYNAMIC` steps or its step time (the load
    /// factor) in a static step; empty for a `*FREQUENCY` step.
    pub history: Vec<(f64, HashMap<usize, [f64; 3]>)>,
}

/// One row of CalculiX's eigenvalue table.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Eigenvalue {
    /// Mode number (1-based).
    pub mode: usize,
    /// Eigenvalue ω² (rad²/s²).
    pub eigenvalue: f64,
    /// ω (rad/s).
    pub radians_per_second: f64,
    /// f = ω / 2π (Hz).
    pub hz: f64,
}

/// The last `E I G E N V A L U E   O U T P U T` table of a `.dat` text
/// (rows `MODE NO, EIGENVALUE, ω (rad/time), f (cycles/time), imaginary
/// part`); empty if there is none.
pub fn read_frequencies(text: &str) -> Vec<Eigenvalue> {
    let mut out = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if !line.contains("E I G E N V A L U E   O U T P U T") {
            continue;
        }
        out.clear();
        // header lines, then one row per mode up to the next blank line
        for row in lines.by_ref().skip_while(|l| parse_eigen_row(l).is_none()) {
            match parse_eigen_row(row) {
                Some(e) => out.push(e),
                None => break,
            }
        }
    }
    out
}

fn parse_eigen_row(line: &str) -> Option<Eigenvalue> {
    let w: Vec<&str> = line.split_whitespace().collect();
    if w.len() < 4 {
        return None;
    }
    let mode = w[0].parse().ok()?;
    let v: Vec<f64> = w[1..4].iter().map(|t| t.parse().ok()).collect::<Option<_>>()?;
    Some(Eigenvalue { mode, eigenvalue: v[0], radians_per_second: v[1], hz: v[2] })
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
    let mut modal = false;
    for line in text.lines() {
        if line.starts_with("  100C") {
            // "  100CL  101 1.000000000 ..." : the step time in columns 13–25
            block_time = line.get(12..25).and_then(|t| t.trim().parse().ok()).unwrap_or(block_time);
            modal = line.contains("MODAL");
            continue;
        }
        if let Some(rest) = line.strip_prefix(" -4") {
            let name = rest.split_whitespace().next().unwrap_or("").to_string();
            if modal && name == "DISP" {
                out.modes.push((block_time, HashMap::new()));
            }
            if !modal && name == "DISP" {
                out.history.push((block_time, HashMap::new()));
            }
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
                if modal && let Some((_, mode)) = out.modes.last_mut() {
                    mode.insert(node, [v[0], v[1], v[2]]);
                }
                if !modal && let Some((_, increment)) = out.history.last_mut() {
                    increment.insert(node, [v[0], v[1], v[2]]);
                }
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
/// Nodal displacement and velocity blocks come as the sums over their
/// sets' nodes under `U:set` and `V:set`, a contact's total surface force
/// (`*CONTACT PRINT`, `CF`) under `CF:slave set`.
fn dat_blocks(text: &str) -> Vec<(String, [f64; 3], f64)> {
    let mut out = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i].trim();
        let prefix = if l.starts_with("displacements (vx,vy,vz) for set") {
            "U:"
        } else if l.starts_with("velocities (vx,vy,vz) for set") {
            "V:"
        } else {
            ""
        };
        if l.starts_with("statistics for slave set") {
            // its first row of numbers: the total surface force, then the moment
            let words: Vec<&str> = l.split_whitespace().collect();
            let set = words.get(4).map(|s| format!("CF:{}", s.trim_end_matches(',')));
            let time = words.last().and_then(|t| t.parse::<f64>().ok()).unwrap_or(0.0);
            let values = lines[i + 1..].iter().take(6).find_map(|line| {
                let v: Vec<f64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
                (v.len() >= 3).then(|| [v[0], v[1], v[2]])
            });
            if let (Some(set), Some(f)) = (set, values) {
                out.push((set, f, time));
            }
            i += 1;
            continue;
        }
        let header = l.starts_with("total force (fx,fy,fz) for set")
            || l.starts_with("forces (fx,fy,fz) for set")
            || !prefix.is_empty();
        if !header {
            i += 1;
            continue;
        }
        let total = l.starts_with("total");
        let words: Vec<&str> = l.split_whitespace().collect();
        let set = words.iter().position(|w| *w == "set").and_then(|p| words.get(p + 1)).map(|s| format!("{prefix}{s}"));
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

    /// The eigenvalue table and two mode blocks as ccx 2.20 wrote them for
    /// a solid steel cantilever (50 × 100 mm, 1 m, 960 C3D20R, `*FREQUENCY`
    /// 6; the deck of `cufem export-ccx` on crates/cufem-cli/tests/ccx_modal.rs's model,
    /// `ccx -i model`), mode lines cut to the clamped node 1 and the tip
    /// node 5101.
    #[test]
    fn reads_the_eigenvalue_table_and_the_mode_shapes() {
        let dat = "
     E I G E N V A L U E   O U T P U T

 MODE NO    EIGENVALUE                       FREQUENCY   
                                     REAL PART            IMAGINARY PART
                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)

      1   0.6929342E+05   0.2632364E+03   0.4189538E+02   0.0000000E+00
      2   0.2730604E+06   0.5225518E+03   0.8316670E+02   0.0000000E+00
      3   0.2659536E+07   0.1630808E+04   0.2595512E+03   0.0000000E+00
      4   0.9824251E+07   0.3134366E+04   0.4988499E+03   0.0000000E+00
      5   0.1424082E+08   0.3773701E+04   0.6006032E+03   0.0000000E+00
      6   0.2013363E+08   0.4487052E+04   0.7141365E+03   0.0000000E+00

     P A R T I C I P A T I O N   F A C T O R S

MODE NO.   X-COMPONENT     Y-COMPONENT     Z-COMPONENT     X-ROTATION      Y-ROTATION      Z-ROTATION

      1   0.4900181E+01  -0.2249294E-13  -0.2176608E-10  -0.1600867E-10   0.2450091E+00  -0.3564036E+01
";
        let f = read_frequencies(dat);
        assert_eq!(f.len(), 6, "{f:?}");
        assert_eq!(
            f[0],
            Eigenvalue { mode: 1, eigenvalue: 0.6929342e5, radians_per_second: 0.2632364e3, hz: 0.4189538e2 }
        );
        assert_eq!((f[5].mode, f[5].hz), (6, 0.7141365e3));
        // ω² and f agree to the table's 7 digits
        for e in &f {
            assert!((e.eigenvalue.sqrt() / (2.0 * std::f64::consts::PI) / e.hz - 1.0).abs() < 1e-6, "{e:?}");
        }
        assert!(read_frequencies(" total force (fx,fy,fz) for set C_ROOT and time  0.1000000E+01\n").is_empty());
        // two modes in CalculiX's fixed columns: node 1 held, node 5101 moving
        let mode = |k: usize, hz: &str, u: &str| {
            format!(
                "    1PMODE                         {k}                                  \n  100CL  10{k} {hz}        5101                     2    {k}MODAL      1\n -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n -1      5101{u}\n -3\n"
            )
        };
        let frd = [
            mode(1, "41.89537836", " 3.19233E-01-1.09886E-02 5.49092E-07"),
            mode(2, "83.16669999", "-3.12701E-01 6.06000E-02-1.38330E-04"),
        ]
        .concat()
            + " 9999\n";
        let r = read_frd(&frd, "x.frd").unwrap();
        assert_eq!(r.modes.len(), 2);
        assert_eq!(r.modes[0].0, 41.89537836);
        assert_eq!(r.modes[0].1[&5101], [3.19233e-1, -1.09886e-2, 5.49092e-7]);
        assert_eq!(r.modes[1].1[&5101], [-3.12701e-1, 6.06e-2, -1.3833e-4]);
        assert_eq!(r.modes[1].1[&1], [0.0; 3]);
        // a frequency step has no history; a static .frd has no modes and
        // one history entry per increment, at its step time
        assert!(r.history.is_empty());
        // the header as ccx 2.20 writes a static increment's: the step time, then the node count
        let block = |t: &str, u: &str| {
            format!(
                "  100CL  101 {t}           1                     0    1           1\n -4  DISP        4    1\n -1         1{u}\n -3\n"
            )
        };
        let s = read_frd(
            &(block("0.500000000", " 1.00000E-03 2.00000E-03 3.00000E-03")
                + &block("1.000000000", " 2.00000E-03 4.00000E-03 6.00000E-03")),
            "s.frd",
        )
        .unwrap();
        assert!(s.modes.is_empty());
        assert_eq!(s.history.len(), 2);
        assert_eq!((s.history[0].0, s.history[0].1[&1]), (0.5, [1e-3, 2e-3, 3e-3]));
        assert_eq!((s.history[1].0, s.history[1].1[&1]), (1.0, [2e-3, 4e-3, 6e-3]));
        assert_eq!(s.u[&1], [2e-3, 4e-3, 6e-3]);
    }

    /// Two increments of a `*DYNAMIC` step as ccx 2.20 wrote them for the
    /// step-loaded bar of crates/cufem-cli/tests/ccx_dynamic.rs (`cufem export-ccx`, then
    /// `ccx -i model`), cut to two nodes: each increment is kept with its
    /// total time, the last one is also the final state.
    #[test]
    fn reads_displacement_velocity_and_contact_force_histories() {
        // ccx 2.20's .dat blocks of *NODE PRINT U, V and *CONTACT PRINT CF
        let dat = "\n displacements (vx,vy,vz) for set REF_W and time  0.1000000E-05\n\n     20001  0.000000E+00  0.000000E+00 -1.000000E-06\n\n velocities (vx,vy,vz) for set REF_W and time  0.1000000E-05\n\n     20001  0.000000E+00  0.000000E+00 -1.000000E+00\n\n statistics for slave set SS_W, master set SM_W and time  0.2000000E-05\n\n   total surface force (fx,fy,fz) and moment about the origin (mx,my,mz)\n\n    0.000000E+00 -1.533896E-27 -5.165458E+01 -2.644729E-12  2.569421E-12 -1.274413E-29\n\n   center of gravity and mean normal\n";
        let h = read_dat_history(dat);
        assert_eq!(h["U:REF_W"], vec![(1e-6, [0.0, 0.0, -1e-6])]);
        assert_eq!(h["V:REF_W"], vec![(1e-6, [0.0, 0.0, -1.0])]);
        assert_eq!(h["CF:SS_W"], vec![(2e-6, [0.0, -1.533896e-27, -51.65458])]);
    }

    #[test]
    fn reads_every_increment_of_a_dynamic_step() {
        let frd = "\
    1PSTEP                         1           1           1          
  100CL  101 1.00000E-09          52                     1    1           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -1       289 0.00000E+00 1.65253E-33 0.00000E+00
 -1       601 0.00000E+00 3.10000E-13 0.00000E+00
 -3
    1PSTEP                         2           1           2          
  100CL  102 4.00100E-06          52                     1    2           1
 -4  DISP        4    1
 -5  D1          1    2    1    0
 -1       289 0.00000E+00 0.00000E+00 0.00000E+00
 -1       601 0.00000E+00 2.50000E-06 0.00000E+00
 -3
 9999
";
        let r = read_frd(frd, "d.frd").unwrap();
        assert_eq!(r.history.len(), 2);
        assert_eq!(r.history[0].0, 1e-9);
        assert_eq!(r.history[1].0, 4.001e-6);
        assert_eq!(r.history[0].1[&601], [0.0, 3.1e-13, 0.0]);
        assert_eq!(r.history[1].1[&601], [0.0, 2.5e-6, 0.0]);
        assert_eq!((r.time, r.u[&601]), (4.001e-6, [0.0, 2.5e-6, 0.0]));
        assert!(r.modes.is_empty());
    }
}
