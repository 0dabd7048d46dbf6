//! A thin-walled rectangular tube's refinement: which of its axis, the
//! elements along its walls and those through them a marked element asks
//! for ([`tube_sections`]), beside the rules of `super::mark` for grids,
//! profiles and laminates.

use super::mark::{BodyMarks, place};
use crate::mesh::Mesh;
use crate::setup::{MeshPlan, SectionPlan};

/// A plain `tube` (no plies) whose marked elements' error lies across the
/// section (the section fit holding at least half their `Σ η²`, as
/// [`super::mark::across_sections`]) is refined along the sides of its largest marked
/// element (the first of `marked` in the body) that are at least
/// [`LONGEST_SHARE`] of its longest: its axis interval, the elements along
/// the walls (the named part `along`: `around`, or `along_x` and `along_z`)
/// and through them (`through`; a tube given by `around` is then written
/// with `along_x`/`along_z`, `around` allowing one element through the
/// wall only). The estimate says where the error is but not, for a tube
/// under a roller, which of the three to refine: its direction parts
/// (`ErrorEstimate::direction`) put most of the marked elements' error
/// through the wall, yet against the 3D quarter converged along the axis
/// and through the wall (tests/data/references.toml, `tube_quarter_1mm`)
/// what pays is refining the element's longest sides. On the paper's axis
/// (`11` mm B4 at the roller, `4.5` mm L9 along the walls) doubling the
/// section first spoils the whole field (u over the tube `2.18 %` →
/// `3.54 %` with two L9 through the wall, `4.52 %` with twice the elements
/// along it) where splitting the axis keeps it (`2.30 %`); on the axis
/// graded to `2` mm, twice the elements along the walls (`17,649` DOF
/// quarter) take u to `1.21 %` and σ_yy at the contact centre from
/// `+16.2 %` to `+1.1 %` (crates/cufem-cli/tests/roller_twins.rs,
/// `graded_around52`), two through the wall only (measured by hand) to
/// `2.25 %` and `+10.7 %` at `22,770` DOF. Each marked element's axis interval is split
/// when the axis is one of its long sides.
pub(crate) fn tube_sections(
    mesh: &Mesh,
    plan: &MeshPlan,
    marked: &[usize],
    (eta, section): (&[f64], &[f64]),
    marks: &mut [BodyMarks],
) {
    let n = mesh.n_elements();
    if section.len() != n || eta.len() != n {
        return;
    }
    for (b, (m, p)) in marks.iter_mut().zip(&plan.bodies).enumerate() {
        let body = &mesh.bodies[b];
        let SectionPlan::Doubled { shape: "tube", .. } = &p.section else { continue };
        // a ring doubled as a whole by the spread rule (`mark::intervals`) stays so
        if !body.section.regions.is_empty() || m.section {
            continue;
        }
        let mine: Vec<usize> = marked.iter().copied().filter(|&e| mesh.body_of_element(e).0 == b).collect();
        let t2: f64 = mine.iter().map(|&e| eta[e] * eta[e]).sum();
        let s2: f64 = mine.iter().map(|&e| section[e] * section[e]).sum();
        let Some(&top) = mine.first() else { continue };
        if !(t2 > 0.0 && s2 >= 0.5 * t2) {
            continue;
        }
        let t = wall_thickness(&body.section);
        let sides_of = |e: usize| {
            let (_, s, k, _) = place(mesh, plan, e);
            let sides = sides(&body.section, t, s, p.axis[k + 1] - p.axis[k]);
            let longest = sides.iter().copied().fold(0.0, f64::max);
            (k, sides.map(|side| side >= LONGEST_SHARE * longest))
        };
        // each marked element's axis interval is split when it is long
        m.axis.iter_mut().for_each(|v| *v = false);
        for &e in &mine {
            let (k, [axis, _, _]) = sides_of(e);
            m.axis[k] |= axis;
        }
        let (_, [_, along, through]) = sides_of(top);
        for (part, long) in [(crate::setup::TUBE_ALONG, along), (crate::setup::TUBE_THROUGH, through)] {
            if long {
                m.section = true;
                m.parts.insert(part.into());
            }
        }
    }
}

/// A side of a tube's marked element is refined when it is at least this
/// share of its longest ([`tube_sections`]).
pub(crate) const LONGEST_SHARE: f64 = 0.5;

/// The bounding box `[xmin, xmax, zmin, zmax]` of section element `e`.
fn bbox(section: &crate::mesh::CrossSection, e: usize) -> [f64; 4] {
    section.element(e).iter().fold([f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY], |b, &k| {
        let [x, z] = section.nodes[k];
        [b[0].min(x), b[1].max(x), b[2].min(z), b[3].max(z)]
    })
}

/// The wall thickness `t` of a plain tube's section from its area
/// `A = 2t(w + h) − 4t²` (each straight-sided element's area its bounding
/// box's; `w × h` the outer box).
fn wall_thickness(section: &crate::mesh::CrossSection) -> f64 {
    let area: f64 = (0..section.n_elements()).map(|e| bbox(section, e)).map(|b| (b[1] - b[0]) * (b[3] - b[2])).sum();
    let [x0, x1, z0, z1] = section.bounds();
    let (w, h) = (x1 - x0, z1 - z0);
    (2.0 * (w + h) - (4.0 * (w + h).powi(2) - 16.0 * area).max(0.0).sqrt()) / 8.0
}

/// The sides of section element `s` of a plain tube of wall thickness `t`
/// swept over an axis interval `axis` long: `[axis, along the wall,
/// through the wall]` (m). Its bounding box's sides, the shorter through
/// the wall unless the element is a corner block's (its centre within `t`
/// of two sides of the outer box: both sides through a wall).
fn sides(section: &crate::mesh::CrossSection, t: f64, s: usize, axis: f64) -> [f64; 3] {
    let [x0, x1, z0, z1] = section.bounds();
    let b = bbox(section, s);
    let (dx, dz) = (b[1] - b[0], b[3] - b[2]);
    let (cx, cz) = (0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]));
    let corner = (cx < x0 + t || cx > x1 - t) && (cz < z0 + t || cz > z1 - t);
    if corner { [axis, dx.max(dz), dx.max(dz)] } else { [axis, dx.max(dz), dx.min(dz)] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::{Limits, Model};

    /// A tube's marked element whose error lies across the section is
    /// refined along its long sides (`tube_sections`): on the paper's axis
    /// (`11.1` mm B4 under the roller) a top-wall element (`4.5` mm along
    /// the wall, `1.5` mm through it) splits its axis interval only; on the
    /// axis graded to `2` mm the same element doubles the elements along the
    /// walls only, and a corner block's (`1.5 × 1.5` mm) every side. An
    /// element whose error lies along the axis leaves the section.
    #[test]
    fn a_tube_s_marked_element_is_refined_along_its_long_sides() {
        let model = |name: &str| {
            let path = format!("{}/examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
            Model::parse_with(&std::fs::read_to_string(path).unwrap(), Limits::none()).unwrap()
        };
        // the section element whose centre is nearest `at` (x, z), and the
        // axis interval holding y
        let element = |model: &Model, at: [f64; 2], y: f64| {
            let body = &model.mesh.bodies[0];
            let centre = |e: usize| {
                let nodes = body.section.element(e);
                let c = nodes
                    .iter()
                    .fold([0.0; 2], |a, &n| [a[0] + body.section.nodes[n][0], a[1] + body.section.nodes[n][1]]);
                c.map(|v| v / nodes.len() as f64)
            };
            let d = |e: usize| (centre(e)[0] - at[0]).hypot(centre(e)[1] - at[1]);
            let s = (0..body.section.n_elements()).min_by(|&a, &b| d(a).total_cmp(&d(b))).unwrap();
            let axis = &model.plan.bodies[0].axis;
            let k = (0..axis.len() - 1).find(|&k| axis[k] <= y && y < axis[k + 1]).unwrap();
            (k * body.section.n_elements() + s, k)
        };
        let refine = |model: &Model, e: usize, across: bool| {
            let n = model.mesh.n_elements();
            let mut eta = vec![1e-3; n];
            eta[e] = 1.0;
            let section: Vec<f64> = eta.iter().map(|v| if across { *v } else { 0.1 * v }).collect();
            let mut marks = super::super::mark::intervals(&model.mesh, &model.plan, &[e]);
            tube_sections(&model.mesh, &model.plan, &[e], (&eta, &section), &mut marks);
            let m = &marks[0];
            let axis: Vec<usize> = (0..m.axis.len()).filter(|&k| m.axis[k]).collect();
            (axis, m.parts.iter().cloned().collect::<Vec<_>>())
        };
        let (along, through) = (crate::setup::TUBE_ALONG.to_string(), crate::setup::TUBE_THROUGH.to_string());
        // the top wall's middle under the loading roller (y = 0.125 m, just below)
        let paper = model("bending_tube_28L9");
        let (e, k) = element(&paper, [0.015, 0.02925], 0.124);
        assert_eq!(refine(&paper, e, true), (vec![k], vec![]));
        let graded = model("bending_tube_graded_quarter");
        let (e, k) = element(&graded, [0.015, 0.02925], 0.124);
        assert_eq!(refine(&graded, e, true), (vec![], vec![along.clone()]));
        assert_eq!(refine(&graded, e, false), (vec![k], vec![]));
        // the corner block at (x, z) = (0.03, 0.03)
        let (e, k) = element(&graded, [0.02925, 0.02925], 0.124);
        assert_eq!(refine(&graded, e, true), (vec![k], vec![along, through]));
    }
}
