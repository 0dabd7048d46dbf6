//! Marking and the refined mesh plan: which division intervals are split,
//! each in half for its whole row, column or axis slice, so the refined
//! meshes stay tensor products without hanging nodes: the elements holding
//! the bulk of the estimate are marked ([`dorfler`]) and every interval
//! through a marked element is split ([`intervals`], [`refine`]).
//!
//! In a `rectangle` grid a marked element is split along the directions in
//! which its error varies (`by_direction`: the parts of `σ* − σ_h` along
//! x, z and the axis, `crate::post::ErrorEstimate::direction`): `η_e` alone
//! says how much error an element holds, not whether it is along x, z or
//! the axis, and splitting every direction of the top elements beside the
//! paper's punch edges (whose error varies along x) asked for 234,825 DOF
//! where halving their x intervals took 59,475. Choosing intervals by
//! error per added DOF instead (the cheap section intervals first, an axis
//! interval only when its error paid for a whole section of nodes) was
//! tried and failed: on the Timoshenko cantilever (1 × 1 L9, 2 B4; its
//! error is along the axis) it split x and z intervals for eight cycles,
//! 189 to 5,733 DOF, while the estimate stayed at 1.8 %. A parametric
//! section (profile, laminate) is
//! refined by the two stages of the patch recovery instead: the fit over
//! the section says how much of an element's error lies across it
//! (`across_sections`, `local`: which walls or plies), the rest lies
//! along the axis (`along_axis`).

use std::collections::BTreeSet;

use crate::mesh::Mesh;
use crate::setup::{MeshPlan, SectionPlan};

/// A parametric section (not a grid) is doubled — its only refinement —
/// when the marked elements lie in at least this share of its section
/// elements (the error is spread over the section); with the error in a
/// few of its elements only the axis is refined.
pub(crate) const SECTION_SPREAD: f64 = 0.5;

/// Dörfler marking: the fewest elements, largest `η_e` first, whose `η_e²`
/// add up to at least `theta` of `Σ η_e²` (all of them for `theta ≥ 1`,
/// none when every `η_e` is zero). Returned largest first.
pub fn dorfler(eta: &[f64], theta: f64) -> Vec<usize> {
    let total: f64 = eta.iter().map(|e| e * e).sum();
    if !(total > 0.0) {
        return Vec::new();
    }
    let mut order: Vec<usize> = (0..eta.len()).collect();
    order.sort_by(|&a, &b| eta[b].total_cmp(&eta[a]).then(a.cmp(&b)));
    let mut sum = 0.0;
    let mut marked = Vec::new();
    for e in order {
        if sum >= theta * total {
            break;
        }
        sum += eta[e] * eta[e];
        marked.push(e);
    }
    marked
}

/// Element boundaries with every interval `k` for which `split[k]` holds
/// cut in half.
pub fn split(lines: &[f64], split: &[bool]) -> Vec<f64> {
    let mut out = Vec::with_capacity(lines.len() + split.iter().filter(|s| **s).count());
    for (k, w) in lines.windows(2).enumerate() {
        out.push(w[0]);
        if split.get(k).copied().unwrap_or(false) {
            out.push(0.5 * (w[0] + w[1]));
        }
    }
    out.extend(lines.last());
    out
}

/// The intervals of one body to split.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BodyMarks {
    /// Per axis interval (beam element).
    pub axis: Vec<bool>,
    /// Per x interval of a grid section (empty otherwise).
    pub x: Vec<bool>,
    /// Per z interval of a grid section (empty otherwise).
    pub z: Vec<bool>,
    /// A parametric section to be refined: as a whole, or only the counts
    /// in `parts`.
    pub section: bool,
    /// The named counts of a parametric section to double instead of the
    /// whole section (local refinement, `local`); empty: all of them.
    pub parts: BTreeSet<String>,
    /// A profile's walls graded towards their junctions instead (`local`):
    /// the length of the element added next to each junction (m).
    pub junction: Option<f64>,
}

impl BodyMarks {
    fn empty(axis: usize, plan: &SectionPlan) -> Self {
        let (nx, nz) = match plan {
            SectionPlan::Grid { x, z, .. } => (x.len() - 1, z.len() - 1),
            _ => (0, 0),
        };
        Self {
            axis: vec![false; axis],
            x: vec![false; nx],
            z: vec![false; nz],
            section: false,
            parts: BTreeSet::new(),
            junction: None,
        }
    }
}

/// Where an element lies: its body, section element and axis interval,
/// and in a grid section its x and z intervals.
pub(super) fn place(mesh: &Mesh, plan: &MeshPlan, e: usize) -> (usize, usize, usize, Option<(usize, usize)>) {
    let (b, local) = mesh.body_of_element(e);
    let (s, k) = mesh.bodies[b].split_element(local);
    (b, s, k, grid_cell(&plan.bodies[b].section, s))
}

/// The x and z intervals of section element `s` of a grid (`None` for
/// other sections; [`SectionPlan::Grid`]).
fn grid_cell(section: &SectionPlan, s: usize) -> Option<(usize, usize)> {
    let SectionPlan::Grid { x, z, hole } = section else { return None };
    let hole = hole.map(|h| crate::mesh::hole_intervals(x, z, h));
    crate::mesh::grid_cell(x.len() - 1, z.len() - 1, hole, s)
}

/// Every interval holding one of the `marked` elements, in every
/// direction: isotropic refinement of the marked elements (a grid's then
/// narrowed to its error's directions by `by_direction`). A parametric
/// section (not a grid) is doubled when marked elements lie in at least
/// `SECTION_SPREAD` of its section elements, else only its axis
/// intervals are split.
pub fn intervals(mesh: &Mesh, plan: &MeshPlan, marked: &[usize]) -> Vec<BodyMarks> {
    let mut marks: Vec<BodyMarks> =
        mesh.bodies.iter().zip(&plan.bodies).map(|(b, p)| BodyMarks::empty(b.axis.n_elements(), &p.section)).collect();
    let mut section: Vec<Vec<bool>> = mesh.bodies.iter().map(|b| vec![false; b.section.n_elements()]).collect();
    for &e in marked {
        let (b, s, k, grid) = place(mesh, plan, e);
        let m = &mut marks[b];
        m.axis[k] = true;
        match grid {
            Some((i, j)) => (m.x[i], m.z[j]) = (true, true),
            None => section[b][s] = true,
        }
    }
    for ((m, p), s) in marks.iter_mut().zip(&plan.bodies).zip(&section) {
        let share = s.iter().filter(|x| **x).count() as f64 / s.len().max(1) as f64;
        m.section = matches!(p.section, SectionPlan::Doubled { .. }) && share >= SECTION_SPREAD;
    }
    marks
}

/// A grid's marked element is split in a direction only when its error's
/// variation along that direction (`ErrorEstimate::direction`) is at least
/// this share of its largest direction's, squared (`by_direction`).
pub(crate) const DIRECTION_SHARE: f64 = 0.25;

/// The intervals of `rectangle` grids to split, by the direction of each
/// marked element's error: the x, z or axis interval of a marked element is
/// split only when the variation of `σ* − σ_h` along that direction holds
/// at least [`DIRECTION_SHARE`] of the largest direction's (squared;
/// `direction`, per element; every direction where none varies). An
/// element as long as a steep gradient along one direction (a punch
/// edge's surface beside it) is split in that direction only, instead of
/// adding a whole row of section nodes and a section of axis nodes along
/// every other. Leaves the marks as they are without direction parts and
/// for bodies that are not grids.
pub(crate) fn by_direction(
    mesh: &Mesh,
    plan: &MeshPlan,
    marked: &[usize],
    direction: &[[f64; 3]],
    marks: &mut [BodyMarks],
) {
    if direction.len() != mesh.n_elements() {
        return;
    }
    for (m, p) in marks.iter_mut().zip(&plan.bodies) {
        if matches!(p.section, SectionPlan::Grid { .. }) {
            m.x.iter_mut().chain(m.z.iter_mut()).chain(m.axis.iter_mut()).for_each(|v| *v = false);
        }
    }
    for &e in marked {
        let (b, _, k, Some((i, j))) = place(mesh, plan, e) else { continue };
        let v = direction[e].map(|d| d * d);
        let most = v.iter().copied().fold(0.0, f64::max);
        let split = |d: usize| !(most > 0.0) || v[d] >= DIRECTION_SHARE * most;
        let m = &mut marks[b];
        m.x[i] |= split(0);
        m.z[j] |= split(1);
        m.axis[k] |= split(2);
    }
}

/// A parametric section with named counts (a profile's walls, a
/// laminate's plies: [`local`] then doubles only the counts holding the
/// error) is also doubled when the fit over the section holds most of its
/// marked elements' estimate (`Σ ‖σ* − σ_along‖² ≥ ½ Σ η²` over them,
/// [`crate::post::ErrorEstimate::section`]): the error lies across the
/// section wherever the marked elements are (a laminate's plies one element
/// thick, the walls of a profile), which refining the axis alone leaves.
/// A section without named counts (`circular_tube`, `circle`) is doubled
/// only as a whole, along the whole axis, so it keeps the spread rule of
/// [`intervals`]; a plain `tube` is refined by [`super::tube::tube_sections`] instead:
/// on the paper's uniform tube under its roller the section fit holds over
/// half of the marked elements' estimate, and doubling the whole ring for
/// it on the paper's axis (`33,768` → `68,328` DOF) left the roller force
/// further from 3D and the next cycle over the `140,000`-DOF budget.
pub(crate) fn across_sections(
    mesh: &Mesh,
    plan: &MeshPlan,
    marked: &[usize],
    (eta, section): (&[f64], &[f64]),
    marks: &mut [BodyMarks],
) {
    if section.len() != eta.len() {
        return;
    }
    let mut sums = vec![(0.0, 0.0); marks.len()];
    for &e in marked {
        let (b, _) = mesh.body_of_element(e);
        sums[b].0 += section[e] * section[e];
        sums[b].1 += eta[e] * eta[e];
    }
    for (b, ((m, p), (s2, t2))) in marks.iter_mut().zip(&plan.bodies).zip(sums).enumerate() {
        let SectionPlan::Doubled { shape, .. } = &p.section else { continue };
        let named = crate::setup::count_keys(shape, &mesh.bodies[b].section).iter().any(Option::is_some);
        if named && t2 > 0.0 && s2 >= 0.5 * t2 {
            m.section = true;
        }
    }
}

/// A marked element's axis interval is split only when the fit along the
/// axis holds at least this share of its squared estimate (`η_e² − ‖σ* −
/// σ_along‖²`, [`along_axis`]).
pub(crate) const AXIS_SHARE: f64 = 0.25;

/// The axis intervals to split, by the direction of each marked element's
/// error: the interval of a marked element is split when the first stage
/// of the patch recovery, along the axis, holds at least [`AXIS_SHARE`]
/// of `η_e²` (`η_e² − s_e²`, `s_e` the section stage's part,
/// [`crate::post::ErrorEstimate::section`]); an element whose error lies
/// across its section leaves its axis interval — the section is refined
/// instead ([`across_sections`]) — and only in a body whose section this
/// cycle refines: a section that is not refined (a tube whose marked
/// elements lie under a roller, [`across_sections`]) keeps every marked
/// axis interval, else nothing of it would be refined (the paper's tube
/// stopped after two cycles, `nothing left to refine`, at `0.4 %` above
/// 3D's roller force). Only for parametric sections (profiles,
/// tubes, laminates), which are refined as a whole or count by count:
/// `quads` and `gmsh` sections, which cannot be refined, keep every marked
/// interval, and so do `rectangle` grids here, whose intervals
/// `by_direction` chooses by the direction of each element's error — on
/// the graded block under its punch, dropping the axis split of every
/// element whose error lies across the section (by this rule) left σ_zz at
/// the surface `5.2 %` of the 3D peak off after one cycle, against `3.5 %`
/// with it (crates/cufem-cli/tests/adapt.rs, `block_adapts_…`). Nothing
/// changes without the section parts.
pub(crate) fn along_axis(
    mesh: &Mesh,
    plan: &MeshPlan,
    marked: &[usize],
    (eta, section): (&[f64], &[f64]),
    marks: &mut [BodyMarks],
) {
    if section.len() != eta.len() {
        return;
    }
    let mut axis: Vec<Vec<bool>> = marks.iter().map(|m| vec![false; m.axis.len()]).collect();
    for &e in marked {
        let (b, _, k, _) = place(mesh, plan, e);
        let (t2, s2) = (eta[e] * eta[e], section[e] * section[e]);
        if t2 - s2 >= AXIS_SHARE * t2 {
            axis[b][k] = true;
        }
    }
    for ((m, p), a) in marks.iter_mut().zip(&plan.bodies).zip(axis) {
        if matches!(p.section, SectionPlan::Doubled { .. }) && m.section {
            m.axis = a;
        }
    }
}

/// A named count of a parametric section is doubled when its elements
/// hold at least this share of the largest count's squared section error
/// ([`local`]).
pub(crate) const LOCAL_SHARE: f64 = 0.5;

/// Local refinement of the parametric sections marked for refinement:
/// each section element belongs to one named count (a profile's wall:
/// `along_flange`, `along_web`, `along_lip`; a laminate's ply:
/// `plies[k]`; [`crate::setup::SectionPlan::Doubled`]), and only the counts
/// holding at least [`LOCAL_SHARE`] of the largest count's share of the
/// body's squared section error are doubled (`weights` per element: the
/// section stage's part of the estimate, or `η_e` where that is not
/// computed; over the whole body, as a count is doubled along the whole
/// axis): the one wall or ply where the error sits, every count where it
/// is spread. A section whose elements have no named count (a tube,
/// a circle), or where such elements are among those chosen, is doubled
/// as a whole.
pub(crate) fn local(mesh: &Mesh, plan: &MeshPlan, weights: &[f64], marks: &mut [BodyMarks]) {
    for (b, (m, p)) in marks.iter_mut().zip(&plan.bodies).enumerate() {
        let SectionPlan::Doubled { shape, .. } = &p.section else { continue };
        if !m.section {
            continue;
        }
        let keys = crate::setup::count_keys(shape, &mesh.bodies[b].section);
        let mut sums: Vec<(Option<&str>, f64)> = Vec::new();
        for e in 0..weights.len().min(mesh.n_elements()) {
            let (eb, local) = mesh.body_of_element(e);
            if eb != b {
                continue;
            }
            let (s, _) = mesh.bodies[b].split_element(local);
            let key = keys.get(s).and_then(|k| k.as_deref());
            let w = weights.get(e).copied().unwrap_or(0.0);
            match sums.iter_mut().find(|(k, _)| *k == key) {
                Some((_, sum)) => *sum += w * w,
                None => sums.push((key, w * w)),
            }
        }
        let total: f64 = sums.iter().map(|(_, w)| w).sum();
        if !(total > 0.0) {
            m.parts.clear();
            continue;
        }
        let most = sums.iter().map(|(_, w)| *w).fold(0.0, f64::max);
        let chosen: Option<BTreeSet<String>> =
            sums.iter().filter(|(_, w)| *w >= LOCAL_SHARE * most).map(|(k, _)| k.map(String::from)).collect();
        m.parts = chosen.unwrap_or_default();
        m.junction = junctions(mesh, b, weights, total);
    }
}

/// A profile's walls are graded towards their junctions
/// ([`crate::mesh::profiles::next_to_junctions`]) instead of doubling a
/// count when the elements next to the junctions hold at least this share
/// of the body's squared section error ([`local`]), in static runs as in
/// modal and buckling ones. Measured against references converged in the
/// section and along the axis (`python3 bench/profile_true_error.py`,
/// bench/profile_true_error_results.txt): the I-beam under a pressure on
/// its top flange (crates/cufem-cli/tests/adapt.rs) adapts to a true
/// relative error of `12.0 %` at `19,323` DOF, where the section doubled
/// four times is `22.6 %` off at `38,025` DOF; the channel with the
/// pressure on its web to `6.5 %` at `13,725` DOF (uniform `32 × 32` L9:
/// `18.9 %` at `23,049` DOF). The estimate right after grading understates
/// the error (the channel: `18.7 %` estimated, `36.8 %` true); the next
/// cycles' doubling of the wall counts brings them together.
pub(crate) const JUNCTION_SHARE: f64 = 0.5;

/// The length of the element next to each junction of body `b`'s profile
/// — the smallest side of a junction's elements — when its elements next
/// to the junctions hold at least [`JUNCTION_SHARE`] of `total` (`Σ
/// weights²` over the body) and are longer than twice that (a wall not yet
/// graded): a thin wall's transverse-shear boundary layer at a junction, a
/// wall thickness wide, that an element many thicknesses long leaves
/// unresolved and whose error halves only with each doubling of the
/// wall's count (`python3 bench/junction_layer_study.py`). Once graded the
/// walls are not graded further: halving the graded element on the thin
/// box with 3 mm webs (tests/modal_adapt.rs) left the wall modes'
/// estimates as they were (`3.31` → `3.33 %`, measured before the section
/// patches of `post::spr` were weighted by element area).
fn junctions(mesh: &Mesh, b: usize, weights: &[f64], total: f64) -> Option<f64> {
    let (next, sizes) = crate::mesh::profiles::next_to_junctions(&mesh.bodies[b].section);
    let mut near = 0.0;
    for (e, w) in weights.iter().enumerate().take(mesh.n_elements()) {
        let (eb, local) = mesh.body_of_element(e);
        if eb == b && next[mesh.bodies[b].split_element(local).0] {
            near += w * w;
        }
    }
    let (side, layer) = sizes.filter(|_| near >= JUNCTION_SHARE * total)?;
    if layer <= 2.0 * side {
        return None;
    }
    Some(four_digits(side))
}

/// A length rounded to four significant digits: it is written to the
/// model file.
fn four_digits(a: f64) -> f64 {
    let scale = 10f64.powi(a.log10().floor() as i32 - 3);
    (a / scale).round() * scale
}

/// The plan refined at `marks`: marked axis and grid intervals halved, a
/// marked parametric section doubled, a fixed section kept.
pub fn refine(plan: &MeshPlan, marks: &[BodyMarks]) -> MeshPlan {
    let bodies = plan
        .bodies
        .iter()
        .zip(marks)
        .map(|(p, m)| {
            let mut p = p.clone();
            p.axis = split(&p.axis, &m.axis);
            match &mut p.section {
                SectionPlan::Grid { x, z, .. } => {
                    *x = split(x, &m.x);
                    *z = split(z, &m.z);
                }
                SectionPlan::Doubled { times, parts, junction, .. } if m.section => {
                    if let Some(a) = m.junction {
                        *junction = Some(a);
                    } else {
                        if m.parts.is_empty() {
                            *times += 1;
                        }
                        for k in &m.parts {
                            *parts.entry(k.clone()).or_default() += 1;
                        }
                        // walls graded by an earlier cycle: their element next
                        // to each junction halves with the counts, so that it
                        // stays shorter than the walls' halved elements (the
                        // model file refuses one that is not)
                        if let Some(a) = junction {
                            *a = four_digits(*a / 2.0);
                        }
                    }
                }
                SectionPlan::Doubled { .. } => {}
                SectionPlan::Fixed { .. } => {}
            }
            p
        })
        .collect();
    MeshPlan { bodies }
}

/// What a refinement changed, for the cycle report: per body, intervals
/// split along x, z and the axis, and whether the section was doubled.
pub(crate) fn describe(mesh: &Mesh, before: &MeshPlan, after: &MeshPlan) -> String {
    let mut parts = Vec::new();
    for ((b, p), q) in mesh.bodies.iter().zip(&before.bodies).zip(&after.bodies) {
        let mut what = Vec::new();
        // the counts that changed only (a new user read `x 1 → 1` as a refinement)
        let mut changed = |name: &str, a: usize, b: usize| {
            if a != b {
                what.push(format!("{name} {a} → {b}"));
            }
        };
        if let (SectionPlan::Grid { x, z, .. }, SectionPlan::Grid { x: x2, z: z2, .. }) = (&p.section, &q.section) {
            changed("x", x.len() - 1, x2.len() - 1);
            changed("z", z.len() - 1, z2.len() - 1);
        }
        if let (
            SectionPlan::Doubled { times, parts, junction, .. },
            SectionPlan::Doubled { times: t2, parts: p2, junction: j2, .. },
        ) = (&p.section, &q.section)
        {
            match (junction, j2) {
                (None, Some(a)) => what.push(format!("walls graded to a {a} m element at each junction")),
                (Some(_), Some(a)) if j2 != junction => what.push(format!("element at each junction halved to {a} m")),
                _ => {}
            }
            if t2 > times {
                what.push("section counts doubled".into());
            }
            for (k, n) in p2 {
                if parts.get(k).is_none_or(|m| m < n) {
                    what.push(format!("{k} doubled"));
                }
            }
        }
        if p.axis.len() != q.axis.len() {
            what.push(format!("axis {} → {}", p.axis.len() - 1, q.axis.len() - 1));
        }
        if !what.is_empty() {
            parts.push(format!("{}: {}", b.name, what.join(", ")));
        }
    }
    parts.join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::{Limits, Model};

    /// A tube's section has no named counts: marked elements whose error
    /// lies across the section (the section fit holding all of it) double
    /// it only when they cover half its ring ([`intervals`]), not by
    /// [`across_sections`], which would double the whole ring along the
    /// whole axis for a few elements under a roller.
    #[test]
    fn a_tube_is_not_doubled_for_a_few_elements_error_across_it() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/bending_tube_20L9.toml");
        let text = std::fs::read_to_string(path).unwrap();
        let model = Model::parse_with(&text, Limits::none()).unwrap();
        let ns = model.mesh.bodies[0].section.n_elements();
        let n = model.mesh.n_elements();
        // three section elements of beam element 5, all their error across the section
        let marked: Vec<usize> = (0..3).map(|s| 5 * ns + s).collect();
        let mut eta = vec![1e-3; n];
        marked.iter().for_each(|&e| eta[e] = 1.0);
        let section = eta.clone();
        let mut marks = intervals(&model.mesh, &model.plan, &marked);
        assert!(!marks[0].section, "three of {ns} section elements: not spread");
        across_sections(&model.mesh, &model.plan, &marked, (&eta, &section), &mut marks);
        assert!(!marks[0].section, "a tube is doubled as a whole only by the spread rule");
        along_axis(&model.mesh, &model.plan, &marked, (&eta, &section), &mut marks);
        // the section is not refined, so the marked elements' axis interval
        // is split although their error lies across the section
        let split: Vec<usize> = (0..marks[0].axis.len()).filter(|&k| marks[0].axis[k]).collect();
        assert_eq!(split, vec![5]);
    }

    /// A grid's marked element is split along the directions its error
    /// varies in: x alone when z and the axis hold less than a quarter of
    /// x's squared part, x and z when z holds more, every direction when
    /// the parts are not known or all zero.
    #[test]
    fn a_grid_element_is_split_along_its_error_s_directions() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilever_timoshenko.toml");
        let model = Model::parse_with(&std::fs::read_to_string(path).unwrap(), Limits::none()).unwrap();
        let (mesh, plan) = (&model.mesh, &model.plan);
        assert!(matches!(plan.bodies[0].section, SectionPlan::Grid { .. }));
        let (ns, n) = (mesh.bodies[0].section.n_elements(), mesh.n_elements());
        // section element 1 (x interval 1, z interval 0) of beam element 2
        let hot = 2 * ns + 1;
        let split = |parts: [f64; 3]| {
            let mut direction = vec![[0.0; 3]; n];
            direction[hot] = parts;
            let mut marks = intervals(mesh, plan, &[hot]);
            by_direction(mesh, plan, &[hot], &direction, &mut marks);
            let m = &marks[0];
            let which = |v: &[bool]| (0..v.len()).filter(|&k| v[k]).collect::<Vec<_>>();
            (which(&m.x), which(&m.z), which(&m.axis))
        };
        let none = Vec::<usize>::new();
        assert_eq!(split([1.0, 0.4, 0.1]), (vec![1], none.clone(), none.clone()));
        assert_eq!(split([1.0, 0.6, 0.0]), (vec![1], vec![0], none.clone()));
        assert_eq!(split([0.1, 0.0, 1.0]), (none.clone(), none.clone(), vec![2]));
        assert_eq!(split([0.0; 3]), (vec![1], vec![0], vec![2]));
        // without direction parts the marks are every direction's
        let mut marks = intervals(mesh, plan, &[hot]);
        let all = marks.clone();
        by_direction(mesh, plan, &[hot], &[], &mut marks);
        assert_eq!(marks, all);
    }

    /// A `rectangle` with a `hole`: each section element is placed in the
    /// cell that holds it (its centre inside the cell's x and z intervals),
    /// and a top-wall element whose error varies through the wall splits
    /// only the top wall's z interval, the hole kept: the refined model has
    /// one more row of cells across the top and the same hole.
    #[test]
    fn a_hollow_rectangle_s_wall_is_refined_alone() {
        let text = "[[materials]]\nname = \"al\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\n[[bodies]]\n\
            name = \"tube\"\nmaterial = \"al\"\nsection = { shape = \"rectangle\", element = \"L9\", \
            x = { lines = [0.0, 0.002, 0.01, 0.02, 0.028, 0.03] }, z = { lines = [0.0, 0.002, 0.02, 0.038, 0.04] }, \
            hole = { x = [0.002, 0.028], z = [0.002, 0.038] } }\n\
            axis = { element = \"B4\", from = 0.0, to = 0.3, elements = 2 }\n\
            [[constraints]]\nname = \"root\"\nbody = \"tube\"\nwhere = { y = 0.0 }\nfix = [\"x\", \"y\", \"z\"]\n";
        let placed = |model: &Model| {
            let (section, plan) = (&model.mesh.bodies[0].section, &model.plan.bodies[0].section);
            let SectionPlan::Grid { x, z, .. } = plan else { panic!("a grid") };
            for s in 0..section.n_elements() {
                let nodes = section.element(s);
                let c = nodes.iter().fold([0.0; 2], |a, &n| [a[0] + section.nodes[n][0], a[1] + section.nodes[n][1]]);
                let c = c.map(|v| v / nodes.len() as f64);
                let (i, j) = grid_cell(plan, s).unwrap();
                assert!(x[i] < c[0] && c[0] < x[i + 1] && z[j] < c[1] && c[1] < z[j + 1], "element {s} at {c:?}");
            }
            section.n_elements()
        };
        let model = Model::parse_with(text, Limits::none()).unwrap();
        // 5 × 4 cells less the hole's 3 × 2
        assert_eq!(placed(&model), 14);
        let (mesh, plan) = (&model.mesh, &model.plan);
        // the top wall's middle element (x interval 2, z interval 3) of beam element 1
        let hot = mesh.bodies[0].section.n_elements()
            + (0..14).find(|&s| grid_cell(&plan.bodies[0].section, s) == Some((2, 3))).unwrap();
        let mut direction = vec![[0.0; 3]; mesh.n_elements()];
        direction[hot] = [0.1, 1.0, 0.1];
        let mut marks = intervals(mesh, plan, &[hot]);
        by_direction(mesh, plan, &[hot], &direction, &mut marks);
        let refined = refine(plan, &marks);
        let SectionPlan::Grid { x, z, hole } = &refined.bodies[0].section else { panic!("a grid") };
        assert_eq!((x.len(), z.len(), *hole), (6, 6, Some([[0.002, 0.028], [0.002, 0.038]])));
        let next = Model::parse_planned(text, Limits::none(), std::path::Path::new("."), &refined).unwrap();
        assert_eq!(placed(&next), 19, "one more row of five cells across the top");
    }
}
