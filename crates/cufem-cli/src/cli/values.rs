//! The values of the command line's options, parsed so that a bad one is
//! refused with the option, the value and what is allowed (clap prefixes
//! the option and the value).

use cufem::size;

use super::MAX_THREADS;

/// An integer option from `lo` to `hi` (`None`: no upper limit). Negative
/// values reach this parser (`allow_negative_numbers`) so that the message
/// names what is allowed instead of clap's "unexpected argument '-1'"; clap
/// prefixes it with the option and the value.
pub(super) fn integer_in(s: &str, lo: usize, hi: Option<usize>, what: &str) -> Result<usize, String> {
    let range = match hi {
        Some(hi) => format!("an integer from {lo} to {hi}"),
        None => format!("an integer ≥ {lo}"),
    };
    match s.trim().parse::<i128>() {
        Ok(v) if v >= lo as i128 && hi.is_none_or(|hi| v <= hi as i128) => {
            usize::try_from(v).map_err(|_| format!("expected {range} ({what})"))
        }
        _ => Err(format!("expected {range} ({what})")),
    }
}

pub(super) fn parse_threads(s: &str) -> Result<usize, String> {
    integer_in(
        s,
        1,
        None,
        &format!(
            "worker threads; more than the logical cores are capped at them unless --force-threads, which allows up \
             to {MAX_THREADS}"
        ),
    )
}

pub(super) fn parse_refine(s: &str) -> Result<usize, String> {
    integer_in(s, 1, Some(8), "hexahedra per Lagrange interval")
}

pub(super) fn parse_repeat(s: &str) -> Result<usize, String> {
    integer_in(s, 1, Some(1000), "timed repetitions")
}

pub(super) fn parse_memory(s: &str) -> Result<u64, String> {
    const ALLOWED: &str = "a positive size such as 8G, 512MiB or 1000000000 (bytes; K, M, G, T are powers of 1024)";
    if s.trim().starts_with('-') {
        return Err(format!("{s:?} is negative: expected {ALLOWED}"));
    }
    size::parse_bytes(s).ok_or_else(|| format!("{s:?}: expected {ALLOWED}"))
}
