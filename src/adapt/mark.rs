//! Marking (Dörfler's bulk criterion) and the refined mesh plan: which
//! division intervals hold marked elements, each split in half for its
//! whole row, column or axis slice, so the refined meshes stay
//! tensor products without hanging nodes.

use crate::mesh::Mesh;
use crate::model::{MeshPlan, SectionPlan};

/// A parametric section (not a grid) is refined — uniformly — when the
/// marked elements lie in at least this share of its section elements:
/// the error is then spread over the section, and the only refinement it
/// has, doubling every count, is the one that reaches it.
pub const SECTION_SPREAD: f64 = 0.5;

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

/// The intervals of one body that hold marked elements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BodyMarks {
    /// Per axis interval (beam element).
    pub axis: Vec<bool>,
    /// Per x interval of a grid section (empty otherwise).
    pub x: Vec<bool>,
    /// Per z interval of a grid section (empty otherwise).
    pub z: Vec<bool>,
    /// Section elements holding marked elements.
    pub section: Vec<bool>,
}

impl BodyMarks {
    /// True if anything is to be split.
    pub fn any(&self) -> bool {
        self.axis.iter().chain(&self.x).chain(&self.z).any(|m| *m)
    }
}

/// The intervals holding the marked (global) elements, per body of `mesh`
/// built from `plan`.
pub fn intervals(mesh: &Mesh, plan: &MeshPlan, marked: &[usize]) -> Vec<BodyMarks> {
    let mut marks: Vec<BodyMarks> = mesh
        .bodies
        .iter()
        .zip(&plan.bodies)
        .map(|(b, p)| {
            let (nx, nz) = match &p.section {
                SectionPlan::Grid { x, z } => (x.len() - 1, z.len() - 1),
                _ => (0, 0),
            };
            BodyMarks {
                axis: vec![false; b.axis.n_elements()],
                x: vec![false; nx],
                z: vec![false; nz],
                section: vec![false; b.section.n_elements()],
            }
        })
        .collect();
    for &e in marked {
        let (b, local) = mesh.body_of_element(e);
        let (s, k) = mesh.bodies[b].split_element(local);
        let m = &mut marks[b];
        m.axis[k] = true;
        m.section[s] = true;
        if !m.x.is_empty() {
            let nx = m.x.len();
            m.x[s % nx] = true;
            m.z[s / nx] = true;
        }
    }
    marks
}

/// The plan refined at `marks`: marked axis and grid intervals halved; a
/// parametric section doubled when its marked elements are spread over it
/// ([`SECTION_SPREAD`]); a fixed section kept.
pub fn refine(plan: &MeshPlan, marks: &[BodyMarks]) -> MeshPlan {
    let bodies = plan
        .bodies
        .iter()
        .zip(marks)
        .map(|(p, m)| {
            let mut p = p.clone();
            p.axis = split(&p.axis, &m.axis);
            match &mut p.section {
                SectionPlan::Grid { x, z } => {
                    *x = split(x, &m.x);
                    *z = split(z, &m.z);
                }
                SectionPlan::Doubled { times, .. } => {
                    let share = m.section.iter().filter(|s| **s).count() as f64 / m.section.len().max(1) as f64;
                    if share >= SECTION_SPREAD {
                        *times += 1;
                    }
                }
                SectionPlan::Fixed { .. } => {}
            }
            p
        })
        .collect();
    MeshPlan { bodies }
}

/// What a refinement changed, for the cycle report: per body, intervals
/// split along x, z and the axis, and whether the section was doubled.
pub fn describe(mesh: &Mesh, before: &MeshPlan, after: &MeshPlan) -> String {
    let mut parts = Vec::new();
    for ((b, p), q) in mesh.bodies.iter().zip(&before.bodies).zip(&after.bodies) {
        let mut what = Vec::new();
        if let (SectionPlan::Grid { x, z }, SectionPlan::Grid { x: x2, z: z2 }) = (&p.section, &q.section) {
            what.push(format!("x {} → {}", x.len() - 1, x2.len() - 1));
            what.push(format!("z {} → {}", z.len() - 1, z2.len() - 1));
        }
        if let (SectionPlan::Doubled { times, .. }, SectionPlan::Doubled { times: t2, .. }) = (&p.section, &q.section)
            && t2 > times
        {
            what.push("section counts doubled".into());
        }
        what.push(format!("axis {} → {}", p.axis.len() - 1, q.axis.len() - 1));
        parts.push(format!("{}: {}", b.name, what.join(", ")));
    }
    parts.join("; ")
}
