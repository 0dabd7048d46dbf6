//! The model file as the user wrote it: its typed schema (`schema`), the
//! ranges and defaults of its keys (`ranges`, `defaults`, `bounds`),
//! the JSON Schema printed from it ([`json_schema`]) and the checks of its
//! values that need no mesh (`validate`). Pure: nothing here meshes,
//! locates a point or reads the set-up model (`crate::setup` reads this
//! layer, never the reverse; tests/architecture.rs checks it).
//!
//! Validation never panics on user input: every error names the model-file
//! key (as a path such as `bodies[1].section.thickness`), the offending
//! value and what is allowed. The file format is documented key by key in
//! `docs/model-format.md`.

pub(crate) mod bounds;
pub(crate) mod defaults;
mod parse_error;
pub(crate) mod ranges;
pub(crate) mod schema;
mod settings;
pub(crate) mod validate;

use std::path::{Path, PathBuf};

use crate::mesh::MeshError;
use crate::values::ElementError;
pub use schema::json::json_schema;
pub use settings::*;

/// Errors found while reading or validating a model.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// The file could not be read.
    #[error("cannot read model file {path}: {cause}")]
    Io {
        /// File path.
        path: String,
        /// Cause (kept out of the error chain: the message already says it).
        cause: std::io::Error,
    },
    /// The file is larger than a model file can be (or endless).
    #[error(
        "model file {path} holds more than {}: expected a model file of at most {} (model files are a few kB; \
         gmsh meshes are separate files, named by a section's `file` key)",
        crate::size::human_bytes(*.cap), crate::size::human_bytes(*.cap)
    )]
    TooBig {
        /// File path.
        path: String,
        /// The largest size read (bytes).
        cap: u64,
    },
    /// The file is not UTF-8 text.
    #[error("model file {path} is not UTF-8 text: invalid byte at line {line}, column {column} (byte {offset})")]
    NotText {
        /// File path.
        path: String,
        /// 1-based line of the first invalid byte.
        line: usize,
        /// 1-based column (in bytes) of the first invalid byte.
        column: usize,
        /// 0-based byte offset.
        offset: usize,
    },
    /// TOML syntax or type error (the message names the key and line).
    #[error("model file: {0}")]
    Parse(String),
    /// A value that is not allowed.
    #[error("{key} = {value}: expected {allowed}")]
    Invalid {
        /// Model-file key.
        key: String,
        /// The value given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Mesh construction error.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Element geometry error.
    #[error(transparent)]
    Element(#[from] ElementError),
    /// The model cannot fit in the memory allowed.
    #[error(
        "the model needs at least {} of memory ({} DOF; {}) but {} is available; use a coarser mesh, or \
         --max-memory to raise the limit",
        crate::size::human_bytes(*.needed), .dofs, .largest, crate::size::human_bytes(*.limit)
    )]
    TooLarge {
        /// Lower bound of the memory needed (bytes).
        needed: u64,
        /// Memory allowed (bytes).
        limit: u64,
        /// Degrees of freedom.
        dofs: u64,
        /// The body that made it too large, and its size.
        largest: String,
    },
}

/// Cuts the lines of a parser message: the TOML parser quotes the offending
/// source line, which may be huge (a 100,000-deep nested array is one
/// 200 KB line), cut to 200 characters with its `^^^` marker; the message
/// itself, which names what is allowed (`unknown field `x`, expected one
/// of …` lists every key of the table), is kept whole up to 1,000
/// characters (it quotes the value given, which may be huge too).
pub(crate) fn shorten_lines(message: &str) -> String {
    message
        .lines()
        .map(|l| {
            let quoted = l.trim_start().starts_with('|')
                || l.split_once(" | ")
                    .is_some_and(|(n, _)| !n.is_empty() && n.trim().chars().all(|c| c.is_ascii_digit()));
            let max = if quoted { 200 } else { 1000 };
            if l.chars().count() > max {
                format!("{}…", l.chars().take(max).collect::<String>())
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The error of a value that is not allowed: `key = value: expected allowed`
/// (the value's quoted lines cut as a parser message's are).
pub(crate) fn invalid(key: impl Into<String>, value: impl std::fmt::Display, allowed: impl Into<String>) -> ModelError {
    ModelError::Invalid { key: key.into(), value: shorten_lines(&value.to_string()), allowed: allowed.into() }
}

/// The text of a model file and the folder its relative paths start at.
pub fn read_text(path: &Path) -> Result<(String, PathBuf), ModelError> {
    let cap = crate::size::MAX_MODEL_FILE;
    let bytes = crate::size::read_at_most(path, cap)
        .map_err(|cause| ModelError::Io { path: path.display().to_string(), cause })?
        .ok_or_else(|| ModelError::TooBig { path: path.display().to_string(), cap })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let before = &e.as_bytes()[..offset];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let column = offset - before.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1) + 1;
        ModelError::NotText { path: path.display().to_string(), line, column, offset }
    })?;
    let base = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    Ok((text, base.to_path_buf()))
}

/// Reads model-file text into its typed schema (TOML syntax, unknown keys,
/// types and word values; the values themselves are checked later).
pub(crate) fn parse(text: &str) -> Result<schema::ModelFile, ModelError> {
    toml::from_str(text).map_err(|e| ModelError::Parse(shorten_lines(&parse_error::explain(text, &e))))
}
