//! The error estimate of every state a run keeps: each step end that kept
//! its fields (a load history of several steps) and each frame of a
//! transient run (`analysis.output_interval`), by the estimate of the final
//! state (`post::estimate::of_state`: the state's own Gauss-point stresses
//! against their patch recovery). A step end that kept no fields (a history
//! of one step, an arc-length path) is the final state when it ended the
//! run: its row is the final estimate.
//!
//! The rows go to summary.json's `error_history`, `error_history.csv`, the
//! run's report and the `error` cell field of each step's and frame's VTU
//! ([`super::Solution::at_step`], [`super::Solution::at_frame`]).

use std::time::{Duration, Instant};

use super::{Frame, HistoryRow, StepEnd};
use crate::post::ErrorEstimate;
use crate::setup::Model;

/// Which kept state a row estimates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// The end of step `k` (0-based, `Solution::steps`).
    Step(usize),
    /// Frame `k` of a transient run (0-based, `Solution::frames`).
    Frame(usize),
}

impl State {
    /// Its name in tables and messages: the step's own name, or the
    /// frame's file stem (`frame_0004`).
    pub fn name(self, steps: &[StepEnd]) -> String {
        match self {
            Self::Step(k) => steps[k].name.clone(),
            Self::Frame(k) => format!("frame_{:04}", k + 1),
        }
    }
}

/// The estimate of one kept state.
#[derive(Debug, Clone, PartialEq)]
pub struct StateError {
    /// The state.
    pub state: State,
    /// Its analysis time λ (a transient run's time in s is
    /// `model.transient.time(λ)`).
    pub lambda: f64,
    /// Its estimate (per element, and its norm against the state's own
    /// energy).
    pub estimate: ErrorEstimate,
}

/// The estimates of the kept states in the order of λ (a frame before the
/// step end at the same λ), and the time they took.
#[derive(Debug, Clone, Default)]
pub struct ErrorHistory {
    /// One per kept state.
    pub rows: Vec<StateError>,
    /// Wall time of the estimates (the final one aside).
    pub elapsed: Duration,
}

impl ErrorHistory {
    /// The estimate of `state`, if kept.
    pub fn of(&self, state: State) -> Option<&ErrorEstimate> {
        self.rows.iter().find(|r| r.state == state).map(|r| &r.estimate)
    }
}

/// Estimates every kept state: the frames (λ of their increment in
/// `history`), then the step ends, by λ; `last` is the estimate of the final
/// state, reached after `increments` increments.
pub(super) fn estimate(
    model: &Model,
    gp_offsets: &[usize],
    (steps, frames, history): (&[StepEnd], &[Frame], &[HistoryRow]),
    (last, increments): (Option<&ErrorEstimate>, usize),
) -> ErrorHistory {
    let start = Instant::now();
    let of = |stresses: &[crate::voigt::Voigt], states: &[crate::materials::PointState], u: &[f64]| {
        crate::post::estimate::of_state(
            &model.mesh,
            &model.cells,
            &model.materials,
            (stresses, states),
            gp_offsets,
            model.kinematics.is_nonlinear().then_some(u),
        )
    };
    let mut rows: Vec<StateError> = frames
        .iter()
        .enumerate()
        .map(|(k, f)| StateError {
            state: State::Frame(k),
            lambda: history[f.increment - 1].lambda,
            estimate: of(&f.fields.stresses, &f.fields.states, &f.fields.u),
        })
        .collect();
    for (k, end) in steps.iter().enumerate() {
        let estimate = match (&end.fields, last) {
            (Some(fields), _) => of(&fields.stresses, &fields.states, &fields.u),
            // the state that ended the run: its estimate is the final one
            (None, Some(last)) if end.increment == increments => last.clone(),
            (None, _) => continue,
        };
        rows.push(StateError { state: State::Step(k), lambda: end.lambda, estimate });
    }
    rows.sort_by(|a, b| a.lambda.total_cmp(&b.lambda));
    ErrorHistory { rows, elapsed: start.elapsed() }
}
