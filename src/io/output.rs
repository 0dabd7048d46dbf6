//! The output folder, written so that a result is never lost or mixed.
//!
//! * **Checked before the solve.** [`OutputDir::prepare`] creates the parent
//!   folder, takes the folder's lock and creates a staging folder beside it,
//!   so a `--out` that is a file, not writable or below a file fails before
//!   any computing is done.
//! * **One run at a time.** The lock is an advisory `flock` on
//!   `.NAME.cufem-lock` beside the folder; a second run into the same folder
//!   fails at once, naming the folder. The kernel releases the lock when a
//!   process dies, however it dies.
//! * **All or nothing.** Results are written into the staging folder
//!   `.NAME.cufem-staging-PID` (summary.json last) and then swapped with the
//!   output folder in one atomic `renameat2(RENAME_EXCHANGE)`; the old set is
//!   deleted afterwards. A run killed at any moment leaves the folder holding
//!   either the previous complete result set or the new one, never a mix or
//!   a truncated file (stale staging folders are removed by the next run).
//!   Where the file system cannot exchange (or off Linux) the old folder is
//!   renamed aside, the new one renamed in, the old one deleted: the window
//!   without a folder is two renames wide, and the old set survives under
//!   its temporary name.
//! * **A converged set is never replaced by less.** A run that stopped
//!   early (not converged, interrupted) commits with
//!   `OutputDir::commit_partial`: if the folder holds a converged result
//!   set (its summary.json says `"converged": true`), that set is kept byte
//!   for byte and the partial one goes beside it, into `NAME.partial`
//!   (replaced as a whole like the folder itself); the caller says where.
//! * **Nothing left behind.** A second Ctrl-C exits at once, without
//!   unwinding: [`remove_unfinished`], called by the signal handler first,
//!   removes the staging folders and lock files of every prepared folder.
//! * **No stale files, no foreign files touched.** A folder that holds only
//!   an earlier cufem result (the files named in its summary.json) is
//!   replaced as a whole, so nothing of the earlier run remains. A folder
//!   holding anything else is refused, unless `force`: then the new files
//!   are renamed into it one by one (summary.json last), the earlier run's
//!   files that the new run does not write are deleted and every other file
//!   is left alone — not atomic as a set, which is why it must be asked for.

use std::fs::File;
use std::path::{Path, PathBuf};

/// Errors of the output folder.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A file-system operation failed.
    #[error("{what} {path}: {cause}")]
    Fs {
        /// What was attempted.
        what: &'static str,
        /// Path concerned.
        path: String,
        /// OS error.
        cause: std::io::Error,
    },
    /// The output path exists and is not a folder.
    #[error("--out {0}: expected a folder (or a path to create), found a file")]
    NotAFolder(String),
    /// A parent of the output path is a file.
    #[error("--out {out}: {file} is a file, not a folder")]
    BelowAFile {
        /// The output path.
        out: String,
        /// The parent that is a file.
        file: String,
    },
    /// The output path has no usable name (`/`, `..`).
    #[error("--out {0}: expected a folder with a name (not a root or `..`)")]
    NoName(String),
    /// Another run writes into the same folder.
    #[error(
        "--out {dir}: another cufem run{pid} is writing to this folder (lock {lock}); wait for it or choose another folder"
    )]
    Locked {
        /// The folder.
        dir: String,
        /// The lock file.
        lock: String,
        /// " (pid N)" if known.
        pid: String,
    },
    /// The folder holds files cufem did not write.
    #[error(
        "--out {dir}: the folder holds {entry:?}, which is not part of a cufem result set; choose an empty or new \
         folder, or add --force to write into it (files of an earlier run are replaced, other files left alone)"
    )]
    Foreign {
        /// The folder.
        dir: String,
        /// One foreign entry.
        entry: String,
    },
}

fn fs_error<'a>(what: &'static str, path: &'a Path) -> impl FnOnce(std::io::Error) -> OutputError + 'a {
    move |cause| OutputError::Fs { what, path: path.display().to_string(), cause }
}

/// How the staged files reach the output folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Swap the whole staging folder with the output folder.
    Exchange,
    /// Rename file by file into a folder holding foreign files (`force`).
    InPlace,
}

/// A prepared output folder: locked, checked, with a staging folder to
/// write into. Dropping it without [`OutputDir::commit`] removes the
/// staging folder and leaves the output folder as it was.
#[derive(Debug)]
pub struct OutputDir {
    target: PathBuf,
    staging: PathBuf,
    lock_path: PathBuf,
    _lock: File,
    mode: Mode,
    /// Files of the earlier result set (from its summary.json).
    previous: Vec<String>,
    /// The folder holds a converged result set.
    holds_converged: bool,
    committed: bool,
}

/// Staging folders and lock files of the prepared, uncommitted output
/// folders of this process (for [`remove_unfinished`]).
static UNFINISHED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn track(paths: &[&Path]) {
    if let Ok(mut u) = UNFINISHED.lock() {
        u.extend(paths.iter().map(|p| p.to_path_buf()));
    }
}

fn untrack(paths: &[&Path]) {
    if let Ok(mut u) = UNFINISHED.lock() {
        u.retain(|p| !paths.contains(&p.as_path()));
    }
}

/// Removes the staging folder and lock file of every output folder this
/// process has prepared and not yet committed or dropped: for a process
/// about to exit without unwinding (a second Ctrl-C). The output folders
/// themselves are left as they are (each holds its previous set, or — if
/// the exchange already happened — the new one).
pub fn remove_unfinished() {
    // a poisoned or busy lock only means the main thread is inside a
    // commit; never block a process that was asked to exit
    let Ok(paths) = UNFINISHED.try_lock() else { return };
    for p in paths.iter() {
        if p.is_dir() {
            let _ = std::fs::remove_dir_all(p);
        } else {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// True if `dir/summary.json` records a converged run.
fn holds_converged(dir: &Path) -> bool {
    std::fs::read_to_string(dir.join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .is_some_and(|v| v.get("converged").and_then(serde_json::Value::as_bool) == Some(true))
}

/// The files of the cufem result set in `dir`: those listed in its
/// summary.json's `files` entry, or — for a summary written before that
/// entry existed — every file named like a cufem output.
fn manifest(dir: &Path) -> Option<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("summary.json")).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    let mut names: Vec<String> = match v.get("files").and_then(|f| f.as_array()) {
        Some(files) => files.iter().filter_map(|f| f.as_str().map(str::to_string)).collect(),
        None => std::fs::read_dir(dir)
            .ok()?
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| {
                n == "result.vtu"
                    || n == "verify"
                    || (["line_", "history_", "contact_"].iter().any(|p| n.starts_with(p))
                        && (n.ends_with(".csv") || n.ends_with(".png")))
            })
            .collect(),
    };
    names.push("summary.json".into());
    Some(names)
}

impl OutputDir {
    /// Checks and locks `target` and creates the staging folder. `force`
    /// allows writing into a folder that holds foreign files.
    pub fn prepare(target: &Path, force: bool) -> Result<Self, OutputError> {
        let shown = target.display().to_string();
        if target.exists() && !target.is_dir() {
            return Err(OutputError::NotAFolder(shown));
        }
        // a file where a parent folder should be
        if let Some(file) = target.ancestors().skip(1).find(|a| a.is_file()) {
            return Err(OutputError::BelowAFile { out: shown, file: file.display().to_string() });
        }
        // resolve `.`, `..` and symlinks of existing parts so the folder has a real parent and name
        let absolute = if target.exists() {
            target.canonicalize().map_err(fs_error("cannot resolve", target))?
        } else {
            std::env::current_dir().map_err(fs_error("cannot resolve", target))?.join(target)
        };
        let (Some(parent), Some(name)) = (absolute.parent(), absolute.file_name()) else {
            return Err(OutputError::NoName(shown));
        };
        if name == ".." {
            return Err(OutputError::NoName(shown));
        }
        std::fs::create_dir_all(parent).map_err(fs_error("cannot create the folder", parent))?;
        let name = name.to_string_lossy().into_owned();
        let lock_path = parent.join(format!(".{name}.cufem-lock"));
        let lock = acquire(&lock_path, &shown)?;

        let mut previous = Vec::new();
        let mut mode = Mode::Exchange;
        if absolute.is_dir() {
            let listed = manifest(&absolute);
            let entries = std::fs::read_dir(&absolute).map_err(fs_error("cannot read the folder", &absolute))?;
            for entry in entries {
                let entry = entry.map_err(fs_error("cannot read the folder", &absolute))?;
                let n = entry.file_name().to_string_lossy().into_owned();
                if n.starts_with(".cufem-staging-") {
                    continue;
                }
                // `verify/` (the comparison of `cufem verify`) belongs to the set
                if !listed.as_ref().is_some_and(|l| l.contains(&n) || n == "verify") {
                    if !force {
                        return Err(OutputError::Foreign { dir: shown, entry: n });
                    }
                    mode = Mode::InPlace;
                }
            }
            previous = listed.unwrap_or_default();
        }
        // staging folders of runs that died (we hold the lock, so none is in use)
        let prefix = format!(".{name}.cufem-staging-");
        if let Ok(entries) = std::fs::read_dir(parent) {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().starts_with(&prefix) {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
        let _ = std::fs::remove_dir_all(absolute.join(format!(".cufem-staging-{}", std::process::id())));
        let staging = match mode {
            Mode::Exchange => parent.join(format!("{prefix}{}", std::process::id())),
            Mode::InPlace => absolute.join(format!(".cufem-staging-{}", std::process::id())),
        };
        std::fs::create_dir(&staging).map_err(fs_error("cannot create a folder in", &staging))?;
        track(&[&staging, &lock_path]);
        let holds_converged = holds_converged(&absolute);
        Ok(Self {
            target: absolute,
            staging,
            lock_path,
            _lock: lock,
            mode,
            previous,
            holds_converged,
            committed: false,
        })
    }

    /// The folder to write the results into.
    pub fn staging(&self) -> &Path {
        &self.staging
    }

    /// The output folder (absolute).
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Moves the staged result set into the output folder (see the module
    /// docs), then releases the lock.
    pub fn commit(mut self) -> Result<(), OutputError> {
        match self.mode {
            Mode::Exchange => replace(&self.staging, &self.target)?,
            Mode::InPlace => self.in_place()?,
        }
        self.committed = true;
        Ok(())
    }

    /// Commits the result set of a run that stopped early: into the output
    /// folder like [`Self::commit`], unless that folder holds a converged
    /// result set, which is then kept as it is while the staged set goes
    /// beside it into `NAME.partial` (module docs). Returns the folder the
    /// set went to.
    pub(crate) fn commit_partial(mut self) -> Result<PathBuf, OutputError> {
        if !self.holds_converged {
            let target = self.target.clone();
            self.commit()?;
            return Ok(target);
        }
        let beside = partial_path(&self.target);
        if beside.exists() && !(beside.is_dir() && manifest(&beside).is_some()) {
            // something that is not a cufem result set: never replaced
            return Err(OutputError::Foreign {
                dir: beside.display().to_string(),
                entry: "(not a cufem result set)".into(),
            });
        }
        replace(&self.staging, &beside)?;
        self.committed = true;
        Ok(beside)
    }

    /// True if the output folder held a converged result set when it was
    /// prepared.
    pub(crate) fn holds_converged(&self) -> bool {
        self.holds_converged
    }

    fn in_place(&self) -> Result<(), OutputError> {
        let mut names: Vec<String> = std::fs::read_dir(&self.staging)
            .map_err(fs_error("cannot read", &self.staging))?
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        // summary.json last: its presence marks a complete set
        names.sort_by_key(|n| n == "summary.json");
        for n in &names {
            let to = self.target.join(n);
            std::fs::rename(self.staging.join(n), &to).map_err(fs_error("cannot move results into", &to))?;
        }
        for old in self.previous.iter().filter(|o| !names.contains(o)) {
            let _ = std::fs::remove_file(self.target.join(old));
        }
        let _ = std::fs::remove_dir_all(&self.staging);
        Ok(())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        // removed while still locked: a waiting run re-checks the file it locked
        let _ = std::fs::remove_file(&self.lock_path);
        untrack(&[&self.staging, &self.lock_path]);
    }
}

/// `NAME.partial` beside the folder `NAME`.
pub(crate) fn partial_path(target: &Path) -> PathBuf {
    let mut name = target.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(".partial");
    target.with_file_name(name)
}

/// Puts the folder `staged` in place of `dest` (module docs: one atomic
/// exchange where the file system offers it) and deletes what `dest` held.
fn replace(staged: &Path, dest: &Path) -> Result<(), OutputError> {
    if !dest.exists() {
        return std::fs::rename(staged, dest).map_err(fs_error("cannot move results into", dest));
    }
    if exchange_paths(staged, dest).is_err() {
        // no atomic exchange here: old aside, new in, old out
        let aside = staged.with_extension("old");
        std::fs::rename(dest, &aside).map_err(fs_error("cannot move aside", dest))?;
        std::fs::rename(staged, dest).map_err(fs_error("cannot move results into", dest))?;
        let _ = std::fs::remove_dir_all(&aside);
        return Ok(());
    }
    // the staged path now holds the previous result set
    let _ = std::fs::remove_dir_all(staged);
    Ok(())
}

// The lock's identity check below (device and inode), the CLI's Ctrl-C
// handling (signal-hook's iterator) and the memory probes (`getrusage`) are
// POSIX: other targets are refused with this message rather than with
// unresolved imports.
#[cfg(not(unix))]
compile_error!(
    "cufem builds on Unix only (tested on Linux x86_64; macOS and the BSDs are expected to work): \
     the output folder's lock is checked by device and inode, and Ctrl-C handling and the memory \
     probes use POSIX calls. On Windows, build and run it in WSL."
);

/// Takes the advisory lock on `path`, making sure the locked file is still
/// the one at `path` (a run that finishes deletes its lock file).
fn acquire(path: &Path, shown: &str) -> Result<File, OutputError> {
    use std::os::unix::fs::MetadataExt;
    for _ in 0..10 {
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(fs_error("cannot create the lock file", path))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                let pid =
                    std::fs::read_to_string(path).ok().map(|p| format!(" (pid {})", p.trim())).unwrap_or_default();
                return Err(OutputError::Locked { dir: shown.to_string(), lock: path.display().to_string(), pid });
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(fs_error("cannot lock", path)(e)),
        }
        let same = match (file.metadata(), std::fs::metadata(path)) {
            (Ok(a), Ok(b)) => a.ino() == b.ino() && a.dev() == b.dev(),
            _ => false,
        };
        if same {
            use std::os::unix::fs::FileExt;
            // the holder's pid, for the message another run prints
            let _ = file.set_len(0);
            let _ = file.write_all_at(std::process::id().to_string().as_bytes(), 0);
            return Ok(file);
        }
    }
    Err(OutputError::Locked { dir: shown.to_string(), lock: path.display().to_string(), pid: String::new() })
}

/// Atomically swaps two paths (Linux `renameat2` with `RENAME_EXCHANGE`;
/// elsewhere `Unsupported`, and [`replace`] renames twice instead).
#[cfg(target_os = "linux")]
fn exchange_paths(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let ca = CString::new(a.as_os_str().as_bytes()).map_err(std::io::Error::other)?;
    let cb = CString::new(b.as_os_str().as_bytes()).map_err(std::io::Error::other)?;
    // SAFETY: both arguments are valid NUL-terminated paths that outlive the
    // call; renameat2 does not retain them.
    let r = unsafe { libc::renameat2(libc::AT_FDCWD, ca.as_ptr(), libc::AT_FDCWD, cb.as_ptr(), libc::RENAME_EXCHANGE) };
    if r == 0 { Ok(()) } else { Err(std::io::Error::last_os_error()) }
}

#[cfg(not(target_os = "linux"))]
fn exchange_paths(_a: &Path, _b: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("cufem_out_{}_{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn write_set(dir: &Path, files: &[(&str, &str)]) {
        let names: Vec<&str> = files.iter().map(|f| f.0).collect();
        for (n, c) in files {
            std::fs::write(dir.join(n), c).unwrap();
        }
        std::fs::write(dir.join("summary.json"), serde_json::json!({ "files": names }).to_string()).unwrap();
    }

    #[test]
    fn a_new_set_replaces_the_old_one_as_a_whole() {
        let root = scratch("replace");
        let out = root.join("res");
        let o = OutputDir::prepare(&out, false).unwrap();
        write_set(o.staging(), &[("a.csv", "1"), ("b.csv", "2")]);
        o.commit().unwrap();
        let o = OutputDir::prepare(&out, false).unwrap();
        write_set(o.staging(), &[("a.csv", "3")]);
        o.commit().unwrap();
        let mut names: Vec<String> =
            std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        assert_eq!(names, ["a.csv", "summary.json"]);
        assert_eq!(std::fs::read_to_string(out.join("a.csv")).unwrap(), "3");
        // nothing left beside the folder
        let siblings: Vec<_> = std::fs::read_dir(&root).unwrap().collect();
        assert_eq!(siblings.len(), 1);
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn foreign_files_are_refused_unless_forced_and_then_kept() {
        let root = scratch("foreign");
        let out = root.join("res");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        let e = OutputDir::prepare(&out, false).unwrap_err().to_string();
        assert!(e.contains("notes.txt") && e.contains("--force"), "{e}");
        let o = OutputDir::prepare(&out, true).unwrap();
        write_set(o.staging(), &[("a.csv", "1")]);
        o.commit().unwrap();
        assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
        assert!(out.join("a.csv").exists() && out.join("summary.json").exists());
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn a_second_run_into_a_locked_folder_fails_and_a_file_is_not_a_folder() {
        let root = scratch("lock");
        let out = root.join("res");
        let first = OutputDir::prepare(&out, false).unwrap();
        let e = OutputDir::prepare(&out, false).unwrap_err().to_string();
        assert!(e.contains("another cufem run") && e.contains(&format!("pid {}", std::process::id())), "{e}");
        drop(first);
        // dropped without commit: nothing written, the lock is free again
        assert!(!out.exists());
        OutputDir::prepare(&out, false).unwrap();
        let file = root.join("file");
        std::fs::write(&file, "x").unwrap();
        assert!(matches!(OutputDir::prepare(&file, false), Err(OutputError::NotAFolder(_))));
        assert!(matches!(OutputDir::prepare(&file.join("below"), false), Err(OutputError::BelowAFile { .. })));
        let _ = std::fs::remove_dir_all(&root);
    }
}
