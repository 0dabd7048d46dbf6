//! Helpers shared by the integration tests of every crate (each test binary
//! uses a part): the core's include this file as `mod common;`, the other
//! crates' as `#[path = "../../../tests/common/mod.rs"] mod common;`. It is
//! compiled into each test rather than built as a crate of its own because it
//! reads what Cargo gives a test target only (`CARGO_TARGET_TMPDIR`, the
//! binary's path).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

use cufem::analysis::Structure;
use cufem::solver::newton::NonlinearProblem;

/// Central differences of the residual against the assembled tangent
/// (`Structure::tangent_entry`: the symmetric part plus the skew terms of
/// the GMRES path) in the given `(dof, equation)` columns, over every row:
/// the largest `|ΔR/2h − K|` and the largest asymmetry `|K_re − K_er|`,
/// both divided by `scale`. The structure is left evaluated at the
/// displacements it had.
pub fn tangent_vs_differences(s: &mut Structure, columns: &[(usize, usize)], h: f64, scale: f64) -> (f64, f64) {
    let n_eq = s.n_equations();
    let (mut worst, mut skew): (f64, f64) = (0.0, 0.0);
    for &(d, e) in columns {
        s.displacements_mut()[d] += h;
        s.evaluate().unwrap();
        let rp = s.residual().to_vec();
        s.displacements_mut()[d] -= 2.0 * h;
        s.evaluate().unwrap();
        let rm = s.residual().to_vec();
        s.displacements_mut()[d] += h;
        s.evaluate().unwrap();
        for r in 0..n_eq {
            let k = s.tangent_entry(r, e);
            worst = worst.max(((rp[r] - rm[r]) / (2.0 * h) - k).abs() / scale);
            skew = skew.max((k - s.tangent_entry(e, r)).abs() / scale);
        }
    }
    (worst, skew)
}

/// Parses and runs a model given as text; the run must converge.
pub fn run(text: &str) -> cufem::analysis::Solution {
    let model = cufem::setup::Model::parse(text).unwrap();
    let sol = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    sol
}

/// Newton at each load factor of `path` in turn, committing the converged
/// state where the flag says so (the last one is usually left uncommitted,
/// so that sliding points sit strictly outside their cone).
pub fn solve_path(s: &mut Structure, path: &[(f64, bool)]) {
    use cufem::solver::stepping::Incremental;
    for &(l, commit) in path {
        s.set_load_factor(l);
        let r = cufem::solver::newton::solve(s, &Default::default(), &Default::default());
        assert!(r.converged(), "λ = {l}: {r:?}");
        if commit {
            s.commit();
        }
    }
}

/// The values of a VTK XML file's `DataArray` named `name` (binary,
/// `header_type="UInt64"`, the format cufem writes; `Float64`, or `Int64`
/// as numbers), or of the `Points` array with `name = None`.
pub fn vtu_array(path: &std::path::Path, name: Option<&str>) -> Vec<f64> {
    use base64::Engine as _;
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let a = doc
        .descendants()
        .find(|n| {
            n.has_tag_name("DataArray")
                && match name {
                    Some(name) => n.attribute("Name") == Some(name),
                    None => n.parent().is_some_and(|p| p.has_tag_name("Points")),
                }
        })
        .unwrap_or_else(|| panic!("no array {name:?} in {}", path.display()));
    let raw = base64::engine::general_purpose::STANDARD.decode(a.text().unwrap_or("").trim()).unwrap();
    let n = u64::from_le_bytes(raw[..8].try_into().unwrap()) as usize;
    match a.attribute("type").unwrap() {
        "Float64" => raw[8..8 + n].chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect(),
        // connectivity and offsets, as numbers (exact below 2^53)
        "Int64" => raw[8..8 + n].chunks_exact(8).map(|b| i64::from_le_bytes(b.try_into().unwrap()) as f64).collect(),
        t => panic!("type {t}"),
    }
}

/// The centroids `(x, z)` (m, the mean of each cell's nodes) of a
/// `result.vtu`'s cells whose cell field `field` exceeds ½: where a ply
/// damage mode has passed half (`d_ft`, ...).
pub fn cells_past_half(result: &Path, field: &str) -> Vec<(f64, f64)> {
    let (d, points) = (vtu_array(result, Some(field)), vtu_array(result, None));
    let (connectivity, offsets) = (vtu_array(result, Some("connectivity")), vtu_array(result, Some("offsets")));
    let mut start = 0;
    let mut cells = Vec::new();
    for (c, &end) in offsets.iter().enumerate() {
        let nodes = &connectivity[start..end as usize];
        start = end as usize;
        if d[c] > 0.5 {
            let mean = |k: usize| nodes.iter().map(|&i| points[3 * i as usize + k]).sum::<f64>() / nodes.len() as f64;
            cells.push((mean(0), mean(2)));
        }
    }
    cells
}

/// A CSV file's columns by header name (comment lines `#` skipped; an
/// empty field, such as a free component's prescribed displacement in a
/// constraint's history, is NaN).
pub fn csv_columns(path: &std::path::Path) -> std::collections::HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let names: Vec<String> = lines.next().unwrap().split(',').map(str::to_string).collect();
    let mut cols: std::collections::HashMap<String, Vec<f64>> = names.iter().map(|n| (n.clone(), vec![])).collect();
    for l in lines {
        for (n, v) in names.iter().zip(l.split(',')) {
            cols.get_mut(n).unwrap().push(if v.is_empty() { f64::NAN } else { v.parse().unwrap() });
        }
    }
    cols
}

/// The `cufem` binary of this build. Cargo names it only to the tests of
/// the package that builds it (crates/cufem-cli); the core's tests, which
/// share this file, cannot run it.
pub fn cufem() -> Command {
    let Some(exe) = option_env!("CARGO_BIN_EXE_cufem") else {
        panic!("the cufem binary runs from crates/cufem-cli/tests only")
    };
    Command::new(exe)
}

/// Writes `text` as `<prefix>_<name>/<name>.toml` in the test scratch
/// directory and runs `cufem run --quiet` on it into `out` beside it; the
/// run must succeed and converge. The output folder and its summary.json.
pub fn run_text(prefix: &str, name: &str, text: &str) -> (PathBuf, serde_json::Value) {
    let dir = scratch_dir(prefix, name);
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let run =
        cufem().args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]).output().unwrap();
    assert!(run.status.success(), "{name}: {}", String::from_utf8_lossy(&run.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], true, "{name}");
    (out, summary)
}

/// An empty folder `<prefix>_<name>` in the test scratch directory.
pub fn scratch_dir(prefix: &str, name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{prefix}_{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` as `<dir>/<name>.toml` and runs `cufem verify` on it at
/// `--refine refine` into `<dir>/out`, which it returns; the run must
/// succeed (its report is printed).
pub fn verify(dir: &Path, name: &str, text: &str, refine: u32) -> PathBuf {
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let refine = refine.to_string();
    let run = cufem()
        .args(["verify", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--refine", &refine, "--quiet"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&run.stderr));
    eprintln!("{stdout}");
    out
}

/// A 1 m steel bar (10 × 10 mm, ν = 0 so that it is the 1D rod of
/// d'Alembert's solution, held laterally everywhere; E = 200 GPa,
/// ρ = 8,000 kg/m³, c = 5,000 m/s) of `elements` B2, fixed at y = 0 and
/// pulled at y = 1 m by `force` (N) applied within 1 ns and held for `hold`
/// s in `steps` time steps, with the analysis keys `analysis`; probes at
/// the end and the middle (crates/cufem-cli/tests/dynamics.rs, crates/cufem-cli/tests/ccx_dynamic.rs).
pub fn step_loaded_bar(elements: usize, force: f64, hold: f64, steps: usize, analysis: &str) -> String {
    format!(
        r#"title = "Step-loaded bar"

[analysis]
type = "transient"
{analysis}

[solver]
max_increments = 5000

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0

[[bodies]]
name = "bar"
material = "steel"
section = {{ shape = "rectangle", element = "L4", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B2", from = 0.0, to = 1.0, elements = {elements} }}

[[constraints]]
name = "root"
body = "bar"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[constraints]]
name = "lateral"
body = "bar"
where = {{ y = [0.0, 1.0] }}
fix = ["x", "z"]

[[loads]]
name = "end"
body = "bar"
where = {{ y = 1.0 }}
total_force = [0.0, {force:?}, 0.0]

[[steps]]
name = "rise"
factor = 1.0
duration = 1e-9
increments = 1

[[steps]]
name = "hold"
factor = 1.0
duration = {hold:?}
increments = {steps}

[[probes]]
name = "end"
point = [0.005, 1.0, 0.005]

[[probes]]
name = "middle"
point = [0.005, 0.5, 0.005]
"#
    )
}

/// The test's name: the test harness names each test's thread after it.
fn test_name() -> String {
    std::thread::current().name().unwrap_or("?").to_string()
}

/// Reports one figure to the validation report: `bench/validate` runs the
/// tests with `--nocapture` and keeps every `FIGURE` line as a row of
/// docs/validation.md (README.md and docs/ tag their figures with `id`).
/// `check` says what the test asserts about it and against which reference.
pub fn figure(id: &str, value: f64, unit: &str, check: &str) {
    // one write of the whole line: `eprintln!` writes its pieces one by one
    // to the unbuffered stderr, and the harness's `test … ok` lines of other
    // threads landed between them (a row lost its `FIGURE` prefix)
    let line = format!("FIGURE\t{}\t{id}\t{value:.9e}\t{unit}\t{check}\n", test_name());
    std::io::Write::write_all(&mut std::io::stderr().lock(), line.as_bytes()).unwrap();
}

/// A known limit, asserted from both sides: the measured `value` must stay
/// within `[low, high]`, the range docs/limitations.md states. A value
/// below `low` is an improvement (tighten the range and the docs), above
/// `high` a regression; both fail.
pub fn known_limit(id: &str, value: f64, unit: &str, low: f64, high: f64, what: &str) {
    figure(id, value, unit, &format!("known limit, asserted in [{low}, {high}] {unit} (docs/limitations.md)"));
    assert!(
        (low..=high).contains(&value),
        "{what}: {value} {unit} left its known range [{low}, {high}] {unit}: update the range and \
         docs/limitations.md (below it: an improvement; above it: a regression)"
    );
}

/// `value` within `relative` of `reference` (source named by the caller),
/// reported as the figure `id` (the relative difference in %).
pub fn within(id: &str, value: f64, reference: f64, relative: f64, source: &str) {
    let d = 100.0 * (value / reference - 1.0);
    figure(id, d, "%", &format!("|difference| ≤ {} % against {source}", 100.0 * relative));
    assert!(
        d.abs() <= 100.0 * relative,
        "{id}: {value:e} is {d:+.2} % from {reference:e} ({source}; allowed {} %)",
        100.0 * relative
    );
}

/// True when CalculiX (`ccx`) is not on the PATH: the calling test should
/// return at once (`if common::ccx_missing() { return; }`), and this prints
/// its one-line reason, `<test>: skipped: CalculiX (ccx) not on the PATH; …`.
/// With `CUFEM_REQUIRE_CCX` set (`.ci/run` sets it: CI has ccx) a missing
/// ccx fails the test instead, so that CI never passes by skipping.
pub fn ccx_missing() -> bool {
    let on_path = std::env::var_os("PATH").is_some_and(|path| {
        use std::os::unix::fs::PermissionsExt;
        std::env::split_paths(&path).any(|dir| {
            std::fs::metadata(dir.join("ccx")).is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        })
    });
    if on_path {
        return false;
    }
    // libtest runs each test in a thread named after it
    let test = std::thread::current().name().unwrap_or("a CalculiX test").to_string();
    let reason = "CalculiX (ccx) not on the PATH; apt-get install calculix-ccx";
    if std::env::var_os("CUFEM_REQUIRE_CCX").is_some_and(|v| !v.is_empty()) {
        panic!("{test}: {reason} (CUFEM_REQUIRE_CCX is set: the CalculiX tests must run here)");
    }
    // to stderr past the test harness's capture, so that the skip shows in
    // `cargo test`'s output; in one write, so that other tests' lines do not
    // cut it
    use std::io::Write;
    let _ = std::io::stderr().write_all(format!("{test}: skipped: {reason}\n").as_bytes());
    true
}

/// A column 1 m along y, section x ∈ [−half[0], half[0]] in `nx` L9
/// elements by z ∈ [−half[1], half[1]] in one, axis in `ny` B4 elements, of
/// `material` (a `[[materials]]` table named `steel`): clamped at y = 0
/// (constraint `root`), loaded at y = 1 m by the load `tip` with `load` (its
/// force key, e.g. `total_force = [0.0, -1.0, 0.0]`); `head` before the
/// material, `extra` after the load.
pub fn clamped_column(
    head: &str,
    material: &str,
    half: [f64; 2],
    nx: usize,
    ny: usize,
    load: &str,
    extra: &str,
) -> String {
    let [a, b] = half;
    format!(
        r#"
{head}
{material}
[[bodies]]
name = "column"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = -{a}, to = {a}, elements = {nx} }}, z = {{ from = -{b}, to = {b}, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 1.0, elements = {ny} }}

[[constraints]]
name = "root"
body = "column"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "tip"
body = "column"
where = {{ y = 1.0 }}
{load}
{extra}
"#
    )
}

/// The block's top line (examples/block_indentation*.toml, `top`: 201
/// stations x ∈ [0, 0.5] m at y = 0.05, z = 0.3 m): the largest relative
/// u_z difference `|u_z / u_z_3d − 1|` over the stations with x in `[a, b]`
/// and their mirror images about the punch centre x = 0.25 m (the 3D top
/// line, tests/data/block_calculix_top_u_z.csv, is negative at every
/// station, so the ratio is defined everywhere).
pub fn block_u_z_error(x: &[f64], u_z: &[f64], u_z_3d: &[f64], a: f64, b: f64) -> f64 {
    assert!(x.len() == u_z.len() && x.len() == u_z_3d.len());
    (0..x.len())
        .filter(|&i| {
            let x = x[i].min(0.5 - x[i]);
            (a - 1e-9..=b + 1e-9).contains(&x)
        })
        .map(|i| (u_z[i] / u_z_3d[i] - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The quarter of examples/bending_tube_springback.toml (`text`): its two
/// constraints on the planes x = 15 mm and y = 125 mm (the whole tube's
/// planes of mirror symmetry) turned into `[[symmetry]]` planes, which cut
/// the tube to x ≥ 15 mm, y ≤ 125 mm; the force-controlled roller crosses
/// both and the quarter carries a quarter of its force.
pub fn springback_quarter(text: &str) -> String {
    tube_quarter(text)
}

/// The quarter of a whole §4.2 tube (`text`, its axis 0–250 mm, its section
/// 0–30 mm) held on its planes of mirror symmetry by two constraints named
/// `symmetry_x`, `symmetry_y`: they become `[[symmetry]]` planes, which cut
/// it to x ≥ 15 mm, y ≤ 125 mm (the drop weight's twins,
/// crates/cufem-cli/tests/symmetry.rs; [`springback_quarter`]).
pub fn tube_quarter(text: &str) -> String {
    let plane = |axis: &str, at: &str, keep: &str| {
        let constraint = format!(
            "[[constraints]]\nname = \"symmetry_{axis}\"\nbody = \"tube\"\nwhere = {{ {axis} = {at} }}\nfix = [\"{axis}\"]\n"
        );
        let symmetry =
            format!("[[symmetry]]\nname = \"symmetry_{axis}\"\nplane = {{ {axis} = {at} }}\nkeep = \"{keep}\"\n");
        (constraint, symmetry)
    };
    let mut out = text.to_string();
    for (constraint, symmetry) in [plane("y", "0.125", "below"), plane("x", "0.015", "above")] {
        assert_eq!(out.matches(&constraint).count(), 1, "{constraint}");
        out = out.replace(&constraint, &symmetry);
    }
    out
}

/// The smaller twin of `examples/tube_drop_weight.toml` (`text`): 8 L9
/// around instead of 20 and 10 B4 along the axis instead of 22 (4,464 DOF
/// against 24,120); crates/cufem-cli/tests/dynamics.rs and symmetry.rs.
pub fn coarse_drop_weight(text: &str) -> String {
    let mut twin = text.replace("around = 20", "around = 8");
    for (from, to) in [
        ("to = 0.025, elements = 2", "to = 0.025, elements = 1"),
        ("to = 0.125, elements = 9", "to = 0.125, elements = 4"),
        ("to = 0.225, elements = 9", "to = 0.225, elements = 4"),
        ("to = 0.25, elements = 2", "to = 0.25, elements = 1"),
    ] {
        assert!(twin.contains(from), "{from}");
        twin = twin.replace(from, to);
    }
    twin
}

/// Every column of `whole`'s energy.csv against `copies` times the same
/// column of `part`'s (a model cut by symmetry planes; `time_s` once), at
/// every row (`every_row`) or at the last, within `tolerance` (J).
pub fn assert_energies_scaled(whole: &Path, part: &Path, copies: f64, tolerance: f64, every_row: bool) {
    let (ew, ep) = (csv_columns(&whole.join("energy.csv")), csv_columns(&part.join("energy.csv")));
    for (name, column) in &ew {
        let factor = if name == "time_s" { 1.0 } else { copies };
        let skip = if every_row { 0 } else { column.len() - 1 };
        for (k, (w, p)) in column.iter().zip(&ep[name]).enumerate().skip(skip) {
            assert!((w - factor * p).abs() < tolerance, "{name} at row {k}: {p} × {factor} against {w}");
        }
    }
}

/// What `cufem check` prints for the model `text` (written as
/// `<scratch>/<name>.toml`).
pub fn check_output(prefix: &str, name: &str, text: &str) -> String {
    let model = scratch_dir(prefix, name).join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = cufem().args(["check", model.to_str().unwrap()]).output().unwrap();
    String::from_utf8_lossy(&out.stdout).into_owned()
}
