//! Scatter maps and element colours.
//!
//! For every element a precomputed map from its local upper triangle
//! `(p ≤ q)` to positions in the value array, so assembly is a plain
//! scatter of what the element kernel computed. Elements are coloured so
//! that no two elements of a colour share a node (greedy colouring of the
//! section elements × parity of the beam elements); the elements of a
//! colour are processed in parallel and write to disjoint entries.

use rayon::prelude::*;

use super::{DofMap, NO_EQ};
use crate::mesh::Mesh;
use crate::solver::linear::LowerCsc;

/// A body element in the global element list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ElementRef {
    /// Body index.
    pub body: usize,
    /// Body-local element index.
    pub element: usize,
}

/// Scatter maps of every element, packed.
#[derive(Debug, Clone)]
pub struct ScatterMaps {
    /// Global element list (body by body).
    pub elements: Vec<ElementRef>,
    /// Start of each element's map in `maps` (`elements.len() + 1` entries).
    pub offsets: Vec<usize>,
    /// Position in the pattern's value array of each upper-triangle entry
    /// `(p ≤ q)` of each element matrix, `u32::MAX` for a constrained DOF.
    pub maps: Vec<u32>,
    /// Elements of each colour.
    pub colours: Vec<Vec<usize>>,
}

impl ScatterMaps {
    /// Builds the maps and colours of every element of `mesh`.
    pub fn new(mesh: &Mesh, dofs: &DofMap, pattern: &LowerCsc) -> Self {
        let elements: Vec<ElementRef> = mesh
            .bodies
            .iter()
            .enumerate()
            .flat_map(|(b, body)| (0..body.n_elements()).map(move |e| ElementRef { body: b, element: e }))
            .collect();
        let per_element: Vec<Vec<u32>> = elements
            .par_iter()
            .map(|r| {
                let mut nodes = Vec::new();
                mesh.bodies[r.body].element_nodes(r.element, &mut nodes);
                let eq = &dofs.eq;
                let eqs: Vec<usize> = nodes.iter().flat_map(|&n| (0..3).map(move |c| eq[3 * n + c])).collect();
                element_map(&eqs, pattern)
            })
            .collect();
        let mut offsets = Vec::with_capacity(elements.len() + 1);
        let mut maps = Vec::with_capacity(per_element.iter().map(Vec::len).sum());
        for m in per_element {
            offsets.push(maps.len());
            maps.extend(m);
        }
        offsets.push(maps.len());
        let colours = colour(mesh, &elements);
        Self { elements, offsets, maps, colours }
    }

    /// The map of global element `ge` (read by the tests of the maps).
    #[cfg(test)]
    pub fn map(&self, ge: usize) -> &[u32] {
        &self.maps[self.offsets[ge]..self.offsets[ge + 1]]
    }
}

/// The scatter map of one element with equations `eqs` (`NO_EQ` for a
/// constrained DOF): for each local pair `p ≤ q`, row by row, the position
/// of entry `(max, min)` of their equations in the pattern, `u32::MAX` for
/// a constrained DOF. The element's equations are visited in increasing
/// order, so each global column is walked once, merged with the element's
/// rows below it (instead of a binary search per entry).
fn element_map(eqs: &[usize], pattern: &LowerCsc) -> Vec<u32> {
    let n = eqs.len();
    // upper-triangle packing, row by row: (p, q ≥ p) ↦ p n − p(p−1)/2 + q − p
    let packed = |p: usize, q: usize| p * n - p * p.saturating_sub(1) / 2 + q - p;
    let mut map = vec![u32::MAX; n * (n + 1) / 2];
    let mut order: Vec<usize> = (0..n).filter(|&p| eqs[p] != NO_EQ).collect();
    order.sort_unstable_by_key(|&p| eqs[p]);
    for (i, &a) in order.iter().enumerate() {
        let col = eqs[a];
        let (start, end) = (pattern.col_ptr[col], pattern.col_ptr[col + 1]);
        let rows = &pattern.row_idx[start..end];
        let mut k = 0;
        for &b in &order[i..] {
            let row = eqs[b] as u32;
            // the pattern holds every element coupling by construction (tested)
            while rows[k] < row {
                k += 1;
            }
            debug_assert_eq!(rows[k], row, "element entry ({row}, {col}) in pattern");
            map[packed(a.min(b), a.max(b))] = (start + k) as u32;
        }
    }
    map
}

/// Colours: greedy colouring of section elements × parity of beam elements.
pub(crate) fn colour(mesh: &Mesh, elements: &[ElementRef]) -> Vec<Vec<usize>> {
    let mut section_colours: Vec<Vec<usize>> = Vec::new();
    for body in &mesh.bodies {
        let sec = &body.section;
        let mut node_colours: Vec<Vec<usize>> = vec![Vec::new(); sec.n_nodes()];
        let mut colours = Vec::with_capacity(sec.n_elements());
        for e in 0..sec.n_elements() {
            let el = sec.element(e);
            let c = (0..).find(|c| el.iter().all(|&n| !node_colours[n].contains(c))).unwrap();
            for &n in el {
                node_colours[n].push(c);
            }
            colours.push(c);
        }
        section_colours.push(colours);
    }
    let mut colors: Vec<Vec<usize>> = Vec::new();
    for (ge, r) in elements.iter().enumerate() {
        let body = &mesh.bodies[r.body];
        let (es, eb) = body.split_element(r.element);
        let c = 2 * section_colours[r.body][es] + eb % 2;
        if colors.len() <= c {
            colors.resize(c + 1, Vec::new());
        }
        colors[c].push(ge);
    }
    colors.retain(|c| !c.is_empty());
    colors
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::numbering::tests::two_body_mesh;

    /// Elements of one colour share no node (the parallel scatter writes
    /// disjoint entries), every element has exactly one colour, and every
    /// map entry points at the entry of its own DOF pair (found by binary
    /// search here, by a merge walk in `element_map`), or is `u32::MAX` for
    /// a constrained DOF.
    #[test]
    fn colours_never_share_a_node_and_maps_point_at_their_entries() {
        let mesh = two_body_mesh();
        // every seventh DOF constrained: the maps mark those entries
        let constrained: Vec<bool> = (0..mesh.n_dofs()).map(|d| d % 7 == 3).collect();
        let num = crate::assembly::Numbering::new(&mesh, &constrained, &[]).unwrap();
        let s = ScatterMaps::new(&mesh, &num.dofs, &num.pattern);
        let mut coloured = vec![0; s.elements.len()];
        let mut nodes = Vec::new();
        for colour in &s.colours {
            let mut used = std::collections::HashSet::new();
            for &ge in colour {
                coloured[ge] += 1;
                let r = s.elements[ge];
                mesh.bodies[r.body].element_nodes(r.element, &mut nodes);
                for &n in &nodes {
                    assert!(used.insert(n), "node {n} in two elements of one colour");
                }
            }
        }
        assert!(coloured.iter().all(|&c| c == 1));
        for (ge, r) in s.elements.iter().enumerate() {
            mesh.bodies[r.body].element_nodes(r.element, &mut nodes);
            let eq = &num.dofs.eq;
            let eqs: Vec<usize> = nodes.iter().flat_map(|&n| (0..3).map(move |c| eq[3 * n + c])).collect();
            let mut k = 0;
            for p in 0..eqs.len() {
                for q in p..eqs.len() {
                    let (a, b) = (eqs[p].max(eqs[q]), eqs[p].min(eqs[q]));
                    if eqs[p] == NO_EQ || eqs[q] == NO_EQ {
                        assert_eq!(s.map(ge)[k], u32::MAX);
                    } else {
                        assert_eq!(s.map(ge)[k] as usize, num.pattern.find(a, b).unwrap());
                    }
                    k += 1;
                }
            }
        }
    }
}
