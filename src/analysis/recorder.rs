//! The observer of the stepping (`solver::stepping::Observer`): progress,
//! history rows and, for a transient analysis, the frames of its ParaView
//! time series.

use super::{HistoryRow, IncrementLog, Progress, StateReport, StepFields, Structure};
use crate::setup::Model;
use crate::solver::stepping::{Cutback, Increment, Observer};

/// What the stepping reports at every converged increment: the progress
/// shown, the history rows and increments kept, and in a transient analysis
/// with `analysis.output_interval` the frames of the time series.
pub(super) struct Recorder<'a> {
    pub history: Vec<HistoryRow>,
    pub increments: Vec<Increment>,
    pub cutbacks: Vec<Cutback>,
    pub progress: &'a mut dyn Progress,
    /// Frames so far, and the time of the next one (transient analysis).
    pub frames: Vec<Frame>,
    next_frame: f64,
    model: &'a Model,
}

/// The fields of a transient run at one output time.
#[derive(Debug, Clone)]
pub struct Frame {
    /// Time (s).
    pub time: f64,
    /// The increment it was taken at (1-based; its row in the history).
    pub increment: usize,
    /// Displacements, states and stresses then.
    pub fields: StepFields,
    /// The cohesive interfaces then (`None` without interfaces): the
    /// frame's `d_interface`.
    pub delamination: Option<crate::interfaces::Delamination>,
    /// The ply damage then, each mode's per Gauss point (`None` without
    /// `[materials.damage]`): the frame's `d_ft d_fc d_mt d_mc`.
    pub damage: Option<Vec<[f64; 4]>>,
}

impl<'a> Recorder<'a> {
    /// Nothing recorded yet.
    pub fn new(model: &'a Model, progress: &'a mut dyn Progress) -> Self {
        let next_frame = model.transient.as_ref().and_then(|t| t.output_interval).unwrap_or(f64::INFINITY);
        Self {
            history: Vec::new(),
            increments: Vec::new(),
            cutbacks: Vec::new(),
            progress,
            frames: Vec::new(),
            next_frame,
            model,
        }
    }

    /// A frame of the structure's present fields if its time has come.
    fn frame(&mut self, s: &Structure<'_>, inc: &Increment) {
        let Some(tr) = &self.model.transient else { return };
        let Some(interval) = tr.output_interval else { return };
        let t = tr.time(inc.lambda);
        // the first converged time at or past each multiple of the interval
        if t < self.next_frame * (1.0 - 1e-9) {
            return;
        }
        while self.next_frame <= t * (1.0 + 1e-9) {
            self.next_frame += interval;
        }
        self.frames.push(Frame {
            time: t,
            increment: inc.index,
            fields: s.fields(),
            delamination: s.interfaces().delamination(),
            damage: s.elements().damage.shown(),
        });
    }
}

impl Observer<Structure<'_>> for Recorder<'_> {
    fn converged(&mut self, s: &Structure<'_>, inc: &Increment) {
        let StateReport { reactions, contacts, plastic_points, levers, negative_pivots, .. } = s.report();
        let max_penetration = contacts.iter().map(|c| c.max_penetration).fold(0.0, f64::max);
        self.progress.increment(&IncrementLog {
            index: inc.index,
            lambda: inc.lambda,
            dlambda: inc.dlambda,
            iterations: inc.newton.iterations,
            residuals: inc.newton.residuals.clone(),
            plastic_points,
            cutbacks: inc.cutbacks,
            max_penetration,
            negative_pivots,
        });
        self.history.push(HistoryRow {
            increment: inc.index,
            lambda: inc.lambda,
            iterations: inc.newton.iterations,
            reactions,
            contacts,
            plastic_points,
            levers,
            probes: probe_displacements(self.model, s.displacements()),
            negative_pivots,
            delaminated_m2: s.interfaces().delaminated_area(),
            damaged_volume_m3: s.elements().damage.damaged_volume(),
        });
        self.increments.push(inc.clone());
        self.frame(s, inc);
    }

    fn cut_back(&mut self, c: &Cutback) {
        self.progress.cutback(c);
        self.cutbacks.push(c.clone());
    }
}

/// The displacement at each probe of `model` at displacements `u` (mean
/// over the elements holding it; NaN for a probe outside every body).
fn probe_displacements(model: &Model, u: &[f64]) -> Vec<[f64; 3]> {
    model
        .probes
        .iter()
        .map(|p| {
            if p.locations.is_empty() {
                return [f64::NAN; 3];
            }
            // a probe in the part a symmetry plane leaves out: its image's u reflected back
            let reflected = crate::bc::symmetry::image(&model.symmetry.planes, p.point).1;
            let mut sum = [0.0; 3];
            for loc in &p.locations {
                let pv = crate::values::PointValues::new(&model.mesh.bodies[loc.body], loc);
                let at = pv.displacement(u);
                for k in 0..3 {
                    let sign = if reflected[k] { -1.0 } else { 1.0 };
                    sum[k] += sign * at[k] / p.locations.len() as f64;
                }
            }
            sum
        })
        .collect()
}
