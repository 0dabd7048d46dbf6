//! Overlapping quadrilaterals of a section (a duplicated quad, a square
//! listed with its own half): refused, since their area would count twice.

use super::MeshError;

/// Signed area of a polygon (shoelace; positive counter-clockwise).
fn polygon_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    0.5 * (0..n).map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1]).sum::<f64>()
}

/// Intersection of a polygon with a convex counter-clockwise polygon
/// (Sutherland–Hodgman clipping against each edge of `clip`).
fn clip_convex(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = subject.to_vec();
    for k in 0..clip.len() {
        if out.is_empty() {
            break;
        }
        let (a, b) = (clip[k], clip[(k + 1) % clip.len()]);
        // > 0 on the inner (left) side of the edge a → b
        let side = |p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        let input = std::mem::take(&mut out);
        for i in 0..input.len() {
            let (p, q) = (input[i], input[(i + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
    }
    out
}

/// Rejects quads that overlap (a duplicated quad, a square listed with its
/// own half): the section's area would be counted twice and its stiffness
/// silently doubled there. Every pair of quads whose bounding boxes overlap
/// is clipped (the quads are convex, checked before); an intersection area
/// above 1e-9 of the smaller quad is an error. Neighbours that only share an
/// edge or a corner intersect in a set of zero area.
pub(super) fn check_overlaps(corners: &[[f64; 2]], quads: &[[usize; 4]], key: &str) -> Result<(), MeshError> {
    match first_overlap(corners, quads) {
        Some((a, b, share)) => Err(MeshError::invalid(
            format!("{key}.quads[{b}]"),
            format!("{:?}", quads[b]),
            format!(
                "quads that do not overlap: it covers {:.3} % of quads[{a}] = {:?} (a duplicated or overlapping \
                 quad would count that area twice)",
                100.0 * share,
                quads[a]
            ),
        )),
        None => Ok(()),
    }
}

/// The first pair of quads (`a < b`, corner indices into `corners`,
/// counter-clockwise and convex) that overlap ([`check_overlaps`]), with
/// the share of quad `a`'s area that `b` covers.
pub(super) fn first_overlap(corners: &[[f64; 2]], quads: &[[usize; 4]]) -> Option<(usize, usize, f64)> {
    let polys: Vec<[[f64; 2]; 4]> = quads.iter().map(|q| q.map(|i| corners[i])).collect();
    let boxes: Vec<[f64; 4]> = polys
        .iter()
        .map(|p| {
            let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
            for c in p {
                b = [b[0].min(c[0]), b[1].max(c[0]), b[2].min(c[1]), b[3].max(c[1])];
            }
            b
        })
        .collect();
    // sweep along x: candidates are quads whose x-intervals overlap
    let mut order: Vec<usize> = (0..quads.len()).collect();
    order.sort_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        active.retain(|&j| boxes[j][1] > boxes[i][0]);
        for &j in &active {
            if boxes[j][3] <= boxes[i][2] || boxes[i][3] <= boxes[j][2] {
                continue;
            }
            let shared = polygon_area(&clip_convex(&polys[i], &polys[j]));
            let smaller = polygon_area(&polys[i]).min(polygon_area(&polys[j]));
            if shared > 1e-9 * smaller {
                let (a, b) = (i.min(j), i.max(j));
                return Some((a, b, shared / polygon_area(&polys[a])));
            }
        }
        active.push(i);
    }
    None
}
