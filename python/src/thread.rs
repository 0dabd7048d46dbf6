//! The analysis thread of `Model.run()`: the lines it sends back to the
//! caller's thread, the solve itself (a single run, or the adaptive cycles
//! of a model with an `[adapt]` table), and the kept states a run's
//! `Results` reach (`frame`, `step`, `mode`).

use std::path::Path;
use std::sync::Arc;
use std::sync::mpsc;

use cufem::analysis::{self, AdaptCycle, IncrementLog, Progress, RunOptions, Solution};
use cufem::io::report;
use cufem::setup::Model;
use cufem::solver::stepping::Cutback;

/// Where a line of text goes: as `cufem run` prints it, the header and the
/// final report to stdout, progress and warnings to stderr.
#[derive(Clone, Copy)]
pub(crate) enum Stream {
    /// stdout.
    Out,
    /// stderr.
    Err,
}

/// What the analysis thread tells the caller's thread.
pub(crate) enum Message {
    /// A line of text for a stream.
    Line(Stream, String),
    /// The model solved (an adaptive run's last cycle's) and its solution.
    Done(Box<Result<(Arc<Model>, Solution), String>>),
}

/// Progress lines sent to the caller's thread (printed there through
/// Python's `sys.stderr`, so Jupyter shows them): the CLI's lines, from
/// the same functions (`cufem::io::report`).
pub(crate) struct Channel {
    pub(crate) tx: mpsc::Sender<Message>,
    pub(crate) print: bool,
}

impl Channel {
    fn send(&self, text: String) {
        if self.print {
            let _ = self.tx.send(Message::Line(Stream::Err, text));
        }
    }
}

impl Progress for Channel {
    fn start(&mut self, _model: &Model, setup: &analysis::Setup) {
        self.send(report::start_line(setup));
    }

    fn increment(&mut self, log: &IncrementLog) {
        self.send(report::increment_line(log));
    }

    fn cutback(&mut self, c: &Cutback) {
        self.send(report::cutback_line(c));
    }
}

/// Solves `model`: with its text and folder (`source`) a model with an
/// `[adapt]` table runs its adaptive cycles as the CLI does (a line per
/// cycle; the same file gave other results here than from the CLI: a
/// new-user review), else one analysis. The model solved (the last cycle's)
/// and its solution.
pub(crate) fn solve(
    model: &Arc<Model>,
    source: Option<(&str, &Path)>,
    options: &RunOptions,
    sink: &mut Channel,
) -> Result<(Arc<Model>, Solution), String> {
    match (model.adapt.as_ref(), source) {
        (Some(settings), Some((text, base))) => {
            let source = cufem::adapt::Source { text, base, limits: crate::limits(None) };
            let (tx, print) = (sink.tx.clone(), sink.print);
            let mut line = |c: &AdaptCycle, _: &Model, _: &Solution| {
                let text =
                    format!("adaptive cycle {}: {} DOF, estimated error {:.2} %", c.cycle, c.dof, 100.0 * c.estimate);
                if print {
                    let _ = tx.send(Message::Line(Stream::Err, text));
                }
            };
            cufem::adapt::run((**model).clone(), source, settings, options, sink, &mut line)
                .map(|(m, s)| (Arc::new(m), s))
                .map_err(|e| e.to_string())
        }
        _ => analysis::run(model, options, sink).map(|s| (model.clone(), s)).map_err(|e| e.to_string()),
    }
}

/// Kept state `k` of `kind` (`"frame"`, `"step"`, `"mode"`; counted by the
/// caller) of solution `s`: as `frame_<n>.vtu`, `result_<k+1>_<name>.vtu`
/// or `mode_<k+1>.vtu` hold it; `None` for a step end that kept no fields.
pub(crate) fn kept_state(model: &Model, s: &Solution, kind: &str, k: usize) -> Result<Option<Solution>, String> {
    match kind {
        "frame" => s.at_frame(model, k).map(Some).map_err(|e| e.to_string()),
        "step" => s.at_step(model, k).map_err(|e| e.to_string()),
        _ => {
            // the shape (largest component 1) as the displacement
            let mut shape = s.clone();
            let (shapes, errors) = match (&s.buckling, &s.modal) {
                (Some(b), _) => (&b.modes, &b.errors),
                (None, Some(m)) => (&m.modes, &m.errors),
                (None, None) => return Ok(None),
            };
            shape.u.clone_from(&shapes[k]);
            shape.error_estimate = errors.get(k).map(|e| e.estimate.clone());
            Ok(Some(shape))
        }
    }
}
