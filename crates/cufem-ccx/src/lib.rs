//! # cufem-ccx — the CalculiX bridge of cufem
//!
//! CalculiX (`ccx`) as the 3D reference: export a model as a solid-element
//! deck ([`deck`], on the hex mesh of [`mesh`]), run `ccx` on it, read its
//! results back ([`results`]) and sample them at the model's probes and
//! lines exactly where cufem samples its own fields. Anisotropic and layered
//! bodies keep their constants in the material axes with an `*ORIENTATION`
//! and a section per body and material ([`material`]), their interface
//! nodes split per material and tied ([`interfaces`]). A modal model
//! (`analysis.type = "modal"`) becomes a `*FREQUENCY` step, whose
//! eigenfrequencies and mode shapes are read back instead of a static state.
//! A transient model (`analysis.type = "transient"`) becomes one `*DYNAMIC`
//! step per load step ([`dynamic`]), whose displacement history is read back.
//! [`verify`] runs a model through both and compares them at the probes, along
//! the lines and over the whole field.

pub mod deck;
pub mod dynamic;
pub mod interfaces;
pub mod material;
pub mod mesh;
mod names;
pub mod results;
pub mod verify;
pub mod volume;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub use mesh::{HexKind, HexMesh};
pub use results::NodalResults;

use cufem::setup::Model;
use cufem::values::Location;

/// A node of the 3D mesh duplicated at a material interface
/// ([`interfaces`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tie {
    /// The body.
    pub body: usize,
    /// The copy (the dependent node of the equations).
    pub copy: usize,
    /// The node it duplicates.
    pub original: usize,
}

/// Errors of the CalculiX cross-check.
#[derive(Debug, thiserror::Error)]
pub enum CcxError {
    /// A file could not be written or read.
    #[error("{path}: {cause}")]
    File {
        /// Path.
        path: String,
        /// Cause.
        cause: std::io::Error,
    },
    /// `ccx` is not installed or not at the given path.
    #[error(
        "CalculiX not found ({program}): install it with `apt-get install calculix-ccx` (Debian/Ubuntu), or give its \
         path with --ccx"
    )]
    Missing {
        /// The program looked for.
        program: String,
    },
    /// `ccx` ran but did not finish the analysis.
    #[error(
        "CalculiX did not finish the analysis (reached step time {reached:.4e}: the load factor of a static step, \
         the time in s of a dynamic one); the end of its log:\n{tail}"
    )]
    Failed {
        /// Step time of the last results written (a dynamic step's total time).
        reached: f64,
        /// Last lines of the log.
        tail: String,
    },
    /// `--ccx-results` points at results of another deck.
    #[error(
        "{from} holds CalculiX results of a different deck than this model exports (model.inp differs): \
         --ccx-results needs an earlier verify of the same mesh, refine and element"
    )]
    OtherDeck {
        /// The folder given.
        from: String,
    },
    /// The model uses a feature the CalculiX twin has no equivalent for.
    #[error(
        "{key}: {what} has no equivalent in the CalculiX deck, which holds one static step, displacement-controlled \
         rigid tools, frictionless contact and isotropic hardening; export-ccx and verify need a model without it"
    )]
    Unsupported {
        /// The model-file key.
        key: String,
        /// What cannot be exported.
        what: String,
    },
    /// A modal model whose modes are about a loaded state.
    #[error(
        "{key}: {value} — a pre-stressed modal analysis cannot be exported to CalculiX yet: the deck's *FREQUENCY \
         step takes the modes about the unloaded, undeformed state, so export-ccx and verify take \
         analysis.type = \"modal\" only without loads, non-zero prescribed displacements, indenters and contacts"
    )]
    PreStressed {
        /// The model-file key.
        key: String,
        /// What it holds.
        value: String,
    },
    /// A transient model with something its `*DYNAMIC` twin cannot reproduce.
    #[error("{key}: {value} — {why}; export-ccx and verify take analysis.type = \"transient\" only with {allowed}")]
    Transient {
        /// The model-file key.
        key: String,
        /// What it holds.
        value: String,
        /// Why the twin cannot hold it.
        why: String,
        /// What is allowed instead.
        allowed: String,
    },
    /// Results could not be read.
    #[error("cannot read CalculiX results {path}: {message}")]
    Results {
        /// Path.
        path: String,
        /// What is wrong.
        message: String,
    },
}

fn file_error(path: &Path) -> impl FnOnce(std::io::Error) -> CcxError + '_ {
    move |cause| CcxError::File { path: path.display().to_string(), cause }
}

/// Writes `dir/model.inp` and returns the mesh it was written on; refuses
/// (before writing anything) a model the deck cannot represent.
pub fn export(model: &Model, kind: HexKind, refine: usize, dir: &Path) -> Result<(HexMesh, PathBuf), CcxError> {
    check_supported(model)?;
    std::fs::create_dir_all(dir).map_err(file_error(dir))?;
    let mut mesh = HexMesh::new(model, kind, refine);
    mesh.ties = interfaces::split(&mut mesh, model);
    let path = dir.join("model.inp");
    let mut text = deck::write(model, &mesh);
    if let Some(t) = &model.transient {
        dynamic::steps(&mut text, model, &mesh, t);
    }
    std::fs::write(&path, text).map_err(file_error(&path))?;
    Ok((mesh, path))
}

/// [`CcxError::Unsupported`] (of a transient model [`CcxError::Transient`])
/// for the first feature of `model` that the CalculiX deck cannot represent (checked before any work by `export` and
/// by `cufem verify` before its analysis).
pub fn check_supported(model: &Model) -> Result<(), CcxError> {
    if let Some(t) = &model.transient {
        // contact first: a transient model with an indenter of any kind is
        // refused as such ([`CcxError::Transient`])
        dynamic::check(model, t)?;
    }
    // the deck's step is static (or a frequency or dynamic one): no
    // *BUCKLE, and its nodes are the perfect geometry
    if model.buckling.is_some() {
        return Err(CcxError::Unsupported {
            key: "analysis.type = \"buckling\"".into(),
            what: "a linear buckling analysis (the deck has no *BUCKLE step)".into(),
        });
    }
    if model.imperfection.is_some() {
        return Err(CcxError::Unsupported {
            key: "analysis.imperfection".into(),
            what: "an imperfection shaped by a buckling mode (the deck's nodes are those of the perfect body)".into(),
        });
    }
    if let Some(i) = model.interfaces.first() {
        return Err(CcxError::Unsupported {
            key: i.key.clone(),
            what: format!("the cohesive interface \"{}\" (the hex deck's plies share their nodes)", i.name),
        });
    }
    if let Some(m) = model.materials.iter().find(|m| m.damage.is_some()) {
        return Err(CcxError::Unsupported {
            key: format!("materials (material {:?}).damage", m.given),
            what: "progressive ply damage (the deck's materials are elastic or von Mises)".into(),
        });
    }
    if let Some(l) = model.levers.first() {
        return Err(CcxError::Unsupported {
            key: "levers[0]".into(),
            what: format!("the lever \"{}\" (the deck has no *EQUATION for it)", l.name),
        });
    }
    if let Some(k) = model.indenters.iter().position(|i| i.force.is_some()) {
        return Err(CcxError::Unsupported {
            key: format!("indenters[{k}].force"),
            what: "a force-controlled indenter".into(),
        });
    }
    // a transient load history is one *DYNAMIC step per load step
    if model.steps.len() > 1 && model.transient.is_none() {
        return Err(CcxError::Unsupported {
            key: "steps".into(),
            what: format!("a load history of {} [[steps]] (one at most)", model.steps.len()),
        });
    }
    if let Some((k, m)) = model.materials.iter().enumerate().find(|(_, m)| !m.kinematic.is_empty()) {
        return Err(CcxError::Unsupported {
            key: format!("materials[{k}].plasticity.kinematic"),
            what: format!("the Armstrong–Frederick kinematic hardening of material \"{}\"", m.name),
        });
    }
    // the deck's contact pairs are frictionless: a frictional model has no twin
    let friction = model
        .indenters
        .iter()
        .position(|i| i.friction.is_some())
        .map(|k| format!("indenters[{k}]"))
        .or_else(|| model.contacts.iter().position(|c| c.friction.is_some()).map(|k| format!("contacts[{k}]")));
    if let Some(key) = friction {
        return Err(CcxError::Unsupported { key: format!("{key}.friction"), what: "Coulomb friction".into() });
    }
    // the deck's loads are uniform over their faces
    if let Some(k) = model.loads.iter().position(|l| l.profile.is_some()) {
        return Err(CcxError::Unsupported {
            key: format!("loads[{k}].profile"),
            what: "a load varying over its faces (the 3D twin's surface loads are uniform)".into(),
        });
    }
    if model.modal.is_some() {
        check_unloaded(model)?;
    }
    Ok(())
}

/// [`CcxError::PreStressed`] for the first thing that loads a modal model:
/// its `*FREQUENCY` step is about the undeformed state only.
fn check_unloaded(model: &Model) -> Result<(), CcxError> {
    let refuse = |key: String, value: String| Err(CcxError::PreStressed { key, value });
    if let Some(l) = model.loads.first() {
        return refuse("loads".into(), format!("load \"{}\"", l.name));
    }
    if let Some(i) = model.constraint_handler.first_moving() {
        let v = model.constraints[i].values.iter().flatten().find(|v| **v != 0.0).copied().unwrap_or_default();
        let value = format!("a prescribed displacement of {} m", cufem::numbers::number(v));
        return refuse(format!("constraints[{i}]"), value);
    }
    if let Some(ind) = model.indenters.first() {
        return refuse("indenters".into(), format!("indenter \"{}\"", ind.name));
    }
    if let Some(c) = model.contacts.first() {
        return refuse("contacts".into(), format!("contact \"{}\"", c.name));
    }
    Ok(())
}

/// What a `ccx` run gave.
#[derive(Debug, Clone)]
pub struct CcxRun {
    /// Nodal results of the last increment.
    pub results: NodalResults,
    /// Force totals per node set (reactions of constraints, tool forces).
    pub totals: std::collections::HashMap<String, ([f64; 3], f64)>,
    /// The same per printed increment: `(step time, force)`.
    pub histories: std::collections::HashMap<String, Vec<(f64, [f64; 3])>>,
    /// The eigenvalue table of a `*FREQUENCY` step (empty for a static deck).
    pub frequencies: Vec<results::Eigenvalue>,
    /// Wall time.
    pub wall_time: Duration,
    /// Peak resident memory of the ccx process (bytes), if known.
    pub peak_memory: Option<u64>,
}

impl CcxRun {
    /// The run's nodal results with the force totals and histories of its
    /// `.dat` text.
    fn new(results: NodalResults, dat: &str, wall_time: Duration, peak_memory: Option<u64>) -> Self {
        Self {
            results,
            totals: results::read_dat(dat),
            histories: results::read_dat_history(dat),
            frequencies: results::read_frequencies(dat),
            wall_time,
            peak_memory,
        }
    }
}

/// Runs `program -i model` in `dir` with `threads` threads; the log goes to
/// `dir/ccx.log`.
pub fn run(program: &str, dir: &Path, threads: usize) -> Result<CcxRun, CcxError> {
    let log_path = dir.join("ccx.log");
    let log = std::fs::File::create(&log_path).map_err(file_error(&log_path))?;
    let err = log.try_clone().map_err(file_error(&log_path))?;
    // a frequency step solves with one factor hundreds of times (ARPACK),
    // which ccx 2.20's SPOOLES does 3–5× slower on 2 threads than on one
    // (1.9 s against 6.3 s for the 960-hex cantilever of crates/cufem-cli/tests/ccx_modal.rs)
    let deck = std::fs::read_to_string(dir.join("model.inp")).unwrap_or_default();
    let frequency = deck.contains("\n*FREQUENCY\n");
    // a dynamic step factorizes twice per increment: on 2 threads ccx 2.20
    // took 27.5 s for the 201 increments of the 50-hex bar of
    // crates/cufem-cli/tests/ccx_dynamic.rs, on one 2.5 s
    let dynamic_end = dynamic::end_time(&deck);
    let solver_threads = if frequency || dynamic_end.is_some() { 1 } else { threads };
    let start = Instant::now();
    let status = std::process::Command::new(program)
        .args(["-i", "model"])
        .current_dir(dir)
        .env("OMP_NUM_THREADS", threads.to_string())
        .env("CCX_NPROC_EQUATION_SOLVER", solver_threads.to_string())
        .env("CCX_NPROC_RESULTS", threads.to_string())
        .stdout(log)
        .stderr(err)
        .status()
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => CcxError::Missing { program: program.to_string() },
            _ => CcxError::File { path: program.to_string(), cause: e },
        })?;
    let wall_time = start.elapsed();
    let peak_memory = children_peak_memory();
    let log_text = std::fs::read_to_string(&log_path).unwrap_or_default();
    let frd_path = dir.join("model.frd");
    let frd = std::fs::read_to_string(&frd_path).unwrap_or_default();
    let results = match read_or_fail(&frd, &frd_path, &log_text) {
        Err(CcxError::Failed { reached, .. }) => return Err(failed(reached, &log_text, program, status)),
        r => r?,
    };
    let dat = std::fs::read_to_string(dir.join("model.dat")).unwrap_or_default();
    // a static step ends at load factor 1, dynamic steps at their total
    // time; a frequency step with every mode it wrote to the .frd file in
    // the .dat file's table
    let finished = if let Some(end) = dynamic_end {
        // a dynamic step's time is the total time, written with 6 digits
        (results.time - end).abs() <= 1e-5 * end
    } else if results.modes.is_empty() {
        (results.time - 1.0).abs() <= 1e-6
    } else {
        results::read_frequencies(&dat).len() == results.modes.len()
    };
    if !status.success() || log_text.contains("*ERROR") || !finished {
        return Err(failed(results.time, &log_text, program, status));
    }
    // kept so that a later `verify --ccx-results` reports the same cost
    let cost = format!("{} {}\n", wall_time.as_secs_f64(), peak_memory.unwrap_or(0));
    let _ = std::fs::write(dir.join("ccx.cost"), cost);
    Ok(CcxRun::new(results, &dat, wall_time, peak_memory))
}

/// Reads the results of an earlier run of the same deck from `from` (a
/// `verify/ccx` folder) and copies them into `dir`, which holds the deck
/// just exported; refuses results of another deck.
pub fn reuse(from: &Path, dir: &Path) -> Result<CcxRun, CcxError> {
    let read = |p: PathBuf| std::fs::read_to_string(&p).map_err(file_error(&p));
    if read(from.join("model.inp"))? != read(dir.join("model.inp"))? {
        return Err(CcxError::OtherDeck { from: from.display().to_string() });
    }
    for name in ["model.frd", "model.dat", "ccx.log", "model.sta", "ccx.cost"] {
        let src = from.join(name);
        if src.exists() {
            std::fs::copy(&src, dir.join(name)).map_err(file_error(&src))?;
        }
    }
    let frd_path = dir.join("model.frd");
    let results = read_or_fail(&read(frd_path.clone())?, &frd_path, &read(dir.join("ccx.log")).unwrap_or_default())?;
    let dat = read(dir.join("model.dat")).unwrap_or_default();
    let cost = read(dir.join("ccx.cost")).unwrap_or_default();
    let mut cost = cost.split_whitespace().map(|v| v.parse::<f64>().ok());
    let wall_time = Duration::from_secs_f64(cost.next().flatten().unwrap_or(f64::NAN).max(0.0));
    let peak_memory = cost.next().flatten().filter(|&b| b > 0.0).map(|b| b as u64);
    Ok(CcxRun::new(results, &dat, wall_time, peak_memory))
}

fn read_or_fail(frd: &str, path: &Path, log: &str) -> Result<NodalResults, CcxError> {
    match results::read_frd(frd, &path.display().to_string()) {
        Ok(r) => Ok(r),
        Err(_) if !frd.contains(" -4") => Err(CcxError::Failed { reached: 0.0, tail: tail(log, 15) }),
        Err(e) => Err(e),
    }
}

/// A run that did not finish, with the end of its log; a program that is
/// not ccx (`--ccx /bin/false`) writes no log, and is told so.
fn failed(reached: f64, log: &str, program: &str, status: std::process::ExitStatus) -> CcxError {
    let mut tail = tail(log, 15);
    if tail.is_empty() {
        tail = format!("(empty: {program} wrote nothing and exited with {status}; is it CalculiX's ccx?)");
    }
    CcxError::Failed { reached, tail }
}

fn tail(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// Peak resident memory of the largest child process waited for (bytes).
fn children_peak_memory() -> Option<u64> {
    // SAFETY: getrusage writes into the zero-initialised struct we own.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let r = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) };
    (r == 0).then(|| usage.ru_maxrss as u64 * 1024)
}

/// The displacement `u` (CalculiX node number → value, one increment of
/// [`NodalResults::history`]) at a point located in the CUF mesh, as
/// [`sample`] interpolates it (mean over the elements holding it).
pub fn sample_displacement(
    model: &Model,
    mesh: &HexMesh,
    u: &std::collections::HashMap<usize, [f64; 3]>,
    locations: &[Location],
) -> Option<[f64; 3]> {
    if locations.is_empty() {
        return None;
    }
    let mut n = [0.0; 20];
    let mut out = [0.0; 3];
    let w = 1.0 / locations.len() as f64;
    for loc in locations {
        let (e, p) = mesh.locate(model, loc);
        mesh::hex_shapes(mesh.kind, p, &mut n);
        for (a, &node) in mesh.elements[e].iter().enumerate() {
            let ua = u.get(&(node + 1)).copied().unwrap_or_default();
            (0..3).for_each(|k| out[k] += w * n[a] * ua[k]);
        }
    }
    Some(out)
}

/// 3D fields at a point located in the CUF mesh (mean over the elements
/// holding it, as cufem reports it): displacement, stress (Voigt) and peeq.
pub fn sample(
    model: &Model,
    mesh: &HexMesh,
    r: &NodalResults,
    locations: &[Location],
) -> Option<([f64; 3], [f64; 6], f64)> {
    if locations.is_empty() {
        return None;
    }
    let mut n = [0.0; 20];
    let (mut u, mut s, mut peeq) = ([0.0; 3], [0.0; 6], 0.0);
    let w = 1.0 / locations.len() as f64;
    for loc in locations {
        let (e, p) = mesh.locate(model, loc);
        mesh::hex_shapes(mesh.kind, p, &mut n);
        for (a, &node) in mesh.elements[e].iter().enumerate() {
            let id = node + 1;
            let ua = r.u.get(&id).copied().unwrap_or_default();
            let sa = r.stress.get(&id).copied().unwrap_or_default();
            for k in 0..3 {
                u[k] += w * n[a] * ua[k];
            }
            for k in 0..6 {
                s[k] += w * n[a] * sa[k];
            }
            peeq += w * n[a] * r.peeq.get(&id).copied().unwrap_or(0.0);
        }
    }
    Some((u, s, peeq.max(0.0)))
}
