//! The mesh plan of a model — what adaptive refinement may change — and
//! the `[adapt]` table.
//!
//! A [`MeshPlan`] holds, per body, the element boundaries of the beam axis
//! and of a rectangle section's x and z divisions, and for the other
//! sections how often their element counts were doubled. A model is
//! rebuilt on a changed plan from its own model file
//! ([`super::Model::parse_planned`]): the plan replaces the divisions of
//! the file's text (as `lines`, `super::plan_file`) before validation, so constraints, loads,
//! indenters, probes and lines — geometric selections — are resolved anew
//! on the refined mesh and keep their names.
//!
//! What a plan can refine per section shape:
//!
//! * `rectangle`: each x and z interval separately ([`SectionPlan::Grid`]);
//! * `tube`, the parametric profiles, `circular_tube`, `circle`, `laminate`:
//!   in-plane element counts doubled (`around`, `along_*`; for `circle` also
//!   `through`, which sets the O-grid's core; a laminate's plies' `elements`),
//!   all of them or — a profile's walls, a laminate's plies, a tube's
//!   counts along and through its walls — each on its own; the
//!   through-thickness count of a profile's wall stays ([`SectionPlan::Doubled`]);
//! * `quads`, `gmsh`: nothing — the section is kept as given
//!   ([`SectionPlan::Fixed`]).
//!
//! The axis is always refined interval by interval.

use std::collections::BTreeMap;

use crate::input::schema::*;
use crate::input::validate::division;
use crate::input::{ModelError, defaults, invalid, ranges};

/// Default `[adapt] tolerance`: relative error in the energy norm.
pub(crate) const DEFAULT_TOLERANCE: f64 = defaults::ADAPT_TOLERANCE;
/// Default `[adapt] max_dof`.
pub(crate) const DEFAULT_MAX_DOF: usize = defaults::ADAPT_MAX_DOF;
/// Default `[adapt] max_cycles`: refinements after the model's own mesh.
pub(crate) const DEFAULT_MAX_CYCLES: usize = defaults::ADAPT_MAX_CYCLES;
/// Default `[adapt] fraction`: Dörfler's bulk parameter θ.
pub(crate) const DEFAULT_FRACTION: f64 = defaults::ADAPT_FRACTION;
pub use crate::input::ranges::MAX_BUDGET;
pub(crate) use crate::input::ranges::MAX_CYCLES;

/// Validated `[adapt]`: refine and solve again until the estimate is below
/// `tolerance` (`crate::adapt`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptSettings {
    /// Stop when the relative error estimate (energy norm) is below it.
    pub tolerance: f64,
    /// Never solve a mesh with more degrees of freedom.
    pub max_dof: usize,
    /// Largest number of refinements after the model's own mesh.
    pub max_cycles: usize,
    /// Dörfler's θ: the marked elements hold at least this share of `Σ η_e²`.
    pub fraction: f64,
    /// `analysis.type = "modal"`: the lowest this many modes are followed
    /// (`None`: every mode computed); the tolerance is then on the largest
    /// estimated relative frequency error among them (`crate::adapt`).
    pub modes: Option<usize>,
}

impl Default for AdaptSettings {
    fn default() -> Self {
        Self {
            tolerance: DEFAULT_TOLERANCE,
            max_dof: DEFAULT_MAX_DOF,
            max_cycles: DEFAULT_MAX_CYCLES,
            fraction: DEFAULT_FRACTION,
            modes: None,
        }
    }
}

/// `[adapt]`, if the file has one.
pub(super) fn adapt_settings(file: Option<&AdaptFile>) -> Result<Option<AdaptSettings>, ModelError> {
    let Some(a) = file else { return Ok(None) };
    let d = AdaptSettings::default();
    let tolerance = a.tolerance.unwrap_or(d.tolerance);
    if !ranges::ADAPT_TOLERANCE.contains(tolerance) {
        return Err(invalid(
            "adapt.tolerance",
            tolerance,
            "a relative error between 0 and 1 (e.g. 0.05): in the energy norm, or of the frequencies of a modal \
             analysis",
        ));
    }
    let max_dof = a.max_dof.unwrap_or(d.max_dof);
    if !ranges::ADAPT_MAX_DOF.contains_count(max_dof) {
        return Err(invalid("adapt.max_dof", max_dof, format!("an integer from 1 to {}", MAX_BUDGET)));
    }
    let max_cycles = a.max_cycles.unwrap_or(d.max_cycles);
    if !ranges::ADAPT_MAX_CYCLES.contains_count(max_cycles) {
        return Err(invalid(
            "adapt.max_cycles",
            max_cycles,
            format!("an integer from 0 to {MAX_CYCLES} (refinements after the model's own mesh)"),
        ));
    }
    let fraction = a.fraction.unwrap_or(d.fraction);
    if !ranges::FRACTION.contains(fraction) {
        return Err(invalid(
            "adapt.fraction",
            fraction,
            "a share of the squared estimate greater than 0 and at most 1 (Dörfler's θ, e.g. 0.5)",
        ));
    }
    // `modes` against `analysis.modes`: `super::analysis::adapt_combinations`
    Ok(Some(AdaptSettings { tolerance, max_dof, max_cycles, fraction, modes: a.modes }))
}

/// What adaptive refinement may change in a model's meshes (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct MeshPlan {
    /// One entry per body, in model-file order.
    pub bodies: Vec<BodyPlan>,
}

/// The refinable divisions of one body.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyPlan {
    /// Element boundaries along the beam axis (m), increasing.
    pub axis: Vec<f64>,
    /// The section.
    pub section: SectionPlan,
}

/// How a body's section may be refined.
#[derive(Debug, Clone, PartialEq)]
pub enum SectionPlan {
    /// A rectangle: element boundaries along x and z (m), its cells inside
    /// `hole` left out. Section element `s` spans the x and z intervals of
    /// the `s`-th cell in `mesh::grid_cell`'s order (`j · (x.len() − 1) + i`
    /// without a hole; `CrossSection::hollow_rectangle`).
    Grid {
        /// Boundaries along x.
        x: Vec<f64>,
        /// Boundaries along z.
        z: Vec<f64>,
        /// The x and z ranges left out (m), `[[x0, x1], [z0, z1]]`.
        hole: Option<[[f64; 2]; 2]>,
    },
    /// A parametric section: its in-plane element counts doubled relative
    /// to the model file, all of them `times` times and each count named in
    /// `parts` that many times more (local refinement: a profile's
    /// `along_flange`, `along_web`, `along_lip`; a laminate's ply `k` as
    /// `plies[k]`; a tube's `along` and `through`, [`crate::setup`]'s
    /// `plan_file`).
    Doubled {
        /// The section's `shape`.
        shape: &'static str,
        /// How often every count was doubled.
        times: u32,
        /// How often each named count was doubled on top of `times`.
        parts: BTreeMap<String, u32>,
        /// A profile's `junction_element` (m): one more element of this
        /// length at each end of a wall that meets another; `None` as the
        /// file gives it (none for other shapes).
        junction: Option<f64>,
    },
    /// A section that is kept as given (`quads`, `gmsh`).
    Fixed {
        /// The section's `shape`.
        shape: &'static str,
    },
}

/// The plan of the meshes the file describes (divisions already validated).
pub(super) fn plan(file: &ModelFile) -> Result<MeshPlan, ModelError> {
    let mut bodies = Vec::with_capacity(file.bodies.len());
    for (i, b) in file.bodies.iter().enumerate() {
        let a = &b.axis;
        let axis = crate::input::validate::division_parts(
            &format!("bodies[{i}].axis"),
            a.from,
            a.to,
            a.elements,
            a.ratio,
            a.lines.as_ref(),
            a.segments.as_ref(),
        )?;
        let sk = format!("bodies[{i}].section");
        let section = match &b.section {
            SectionFile::Rectangle(r) => match (&r.x, &r.z) {
                (Some(x), Some(z)) => SectionPlan::Grid {
                    x: division(&format!("{sk}.x"), x)?,
                    z: division(&format!("{sk}.z"), z)?,
                    hole: r.hole.map(|h| [h.x, h.z]),
                },
                _ => return Err(invalid(sk, "(no x or z division)", "a rectangle with both `x` and `z`")),
            },
            SectionFile::Quads(_) => SectionPlan::Fixed { shape: "quads" },
            SectionFile::Gmsh(_) => SectionPlan::Fixed { shape: "gmsh" },
            s => SectionPlan::Doubled { shape: s.shape(), times: 0, parts: BTreeMap::new(), junction: None },
        };
        bodies.push(BodyPlan { axis, section });
    }
    Ok(MeshPlan { bodies })
}
