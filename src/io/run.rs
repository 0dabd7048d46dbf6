//! A run into an output folder, the one sequence the CLI (`run`,
//! `verify`) and the Python package share: the folder is prepared (checked,
//! locked) before any computing, the analysis runs, its files are written
//! into the staging folder, and the set is committed — in place of the
//! folder's previous set if the analysis finished, beside a converged one
//! if it stopped early (`output::OutputDir::commit_partial`).

use std::path::{Path, PathBuf};

use super::output::{OutputDir, OutputError};
use super::{IoError, write_results};
use crate::analysis::{self, AnalysisError, Progress, RunOptions, Solution};
use crate::setup::Model;

/// What a run into a folder produced.
#[derive(Debug)]
pub struct RunInto<T> {
    /// The analysis' results.
    pub solution: Solution,
    /// The names of the files written.
    pub files: Vec<String>,
    /// The folder the set went to: the output folder, or `NAME.partial`
    /// beside it when a run that stopped early left a converged set in place.
    pub folder: PathBuf,
    /// True if the output folder held a converged set and still does (the
    /// run stopped early and wrote beside it).
    pub kept_converged: bool,
    /// The process's peak resident memory right after the analysis, before
    /// any output was written (bytes; `None` where it cannot be read).
    pub analysis_peak: Option<u64>,
    /// What `extra` returned (`None`: the analysis stopped early and `extra`
    /// was not called).
    pub extra: Option<T>,
}

/// Errors of a run into a folder.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The analysis could not start or failed outright.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    /// A result file could not be written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The folder could not take the results.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// A finished analysis whose files are written, before they are committed.
#[derive(Debug, Clone, Copy)]
pub struct Finished<'a> {
    /// Its results.
    pub solution: &'a Solution,
    /// The staging folder holding its files.
    pub staging: &'a Path,
    /// The peak resident memory right after the analysis (bytes).
    pub analysis_peak: Option<u64>,
}

/// Runs `model` and writes its results into `folder` (prepared by the
/// caller, before any computing). `extra` may add files to the staging
/// folder of a finished analysis before the set is committed (`verify`'s
/// CalculiX comparison); whatever it returns comes back in
/// [`RunInto::extra`], and the set is committed either way.
pub fn run_into<T>(
    model: &Model,
    folder: OutputDir,
    options: &RunOptions,
    progress: &mut dyn Progress,
    extra: impl FnOnce(Finished<'_>) -> T,
) -> Result<RunInto<T>, RunError> {
    let solution = analysis::run(model, options, progress)?;
    solved_into(model, solution, folder, extra)
}

/// The second half of [`run_into`] for a solution computed otherwise (an
/// adaptive run's last cycle): the peak memory read now, the results
/// written into `folder` and committed.
pub fn solved_into<T>(
    model: &Model,
    solution: Solution,
    folder: OutputDir,
    extra: impl FnOnce(Finished<'_>) -> T,
) -> Result<RunInto<T>, RunError> {
    let analysis_peak = crate::size::peak_memory();
    let written = write_into(model, &solution, folder, |staging| {
        extra(Finished { solution: &solution, staging, analysis_peak })
    })?;
    Ok(RunInto {
        files: written.files,
        folder: written.folder,
        kept_converged: written.kept_converged,
        extra: written.extra,
        analysis_peak,
        solution,
    })
}

/// A result set written into a folder.
#[derive(Debug)]
pub struct Written<T> {
    /// The names of the files written.
    pub files: Vec<String>,
    /// The folder the set went to (module docs).
    pub folder: PathBuf,
    /// True if a converged set was kept in the output folder.
    pub kept_converged: bool,
    /// What `extra` returned (`None` for a solution that stopped early).
    pub extra: Option<T>,
}

/// Writes the results of `solution` into `folder` and commits them: the
/// second half of [`run_into`], also for a solution already in memory
/// (Python's `Results.write`). `extra` sees the staging folder of a
/// finished solution before the commit.
pub fn write_into<T>(
    model: &Model,
    solution: &Solution,
    folder: OutputDir,
    extra: impl FnOnce(&Path) -> T,
) -> Result<Written<T>, RunError> {
    let written = write_results(model, solution, folder.staging())?;
    let files = written.iter().filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned())).collect();
    let kept_converged = solution.failure.is_some() && folder.holds_converged();
    let (extra, folder) = if solution.failure.is_none() {
        let extra = extra(folder.staging());
        let target = folder.target().to_path_buf();
        folder.commit()?;
        (Some(extra), target)
    } else {
        // a converged set in the folder is never replaced by less
        (None, folder.commit_partial()?)
    };
    Ok(Written { files, folder, kept_converged, extra })
}
