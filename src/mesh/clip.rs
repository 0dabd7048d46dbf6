//! A part of a cross-section: the elements kept by a symmetry plane
//! (`bc::symmetry`), with their nodes renumbered and the regions cut down.

use super::{CrossSection, EdgeTwin, Region};

impl CrossSection {
    /// The section made of the elements `keep` accepts (in their order),
    /// with only their nodes (in their order) and the regions' kept
    /// elements and the interfaces between two kept elements renumbered.
    pub(crate) fn retain_elements(&self, keep: impl Fn(usize) -> bool) -> CrossSection {
        let kept: Vec<usize> = (0..self.n_elements()).filter(|&e| keep(e)).collect();
        let mut new_node = vec![usize::MAX; self.n_nodes()];
        for &e in &kept {
            for &n in self.element(e) {
                new_node[n] = 0;
            }
        }
        let mut nodes = Vec::new();
        for (n, slot) in new_node.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = nodes.len();
                nodes.push(self.nodes[n]);
            }
        }
        let connectivity = kept.iter().flat_map(|&e| self.element(e).iter().map(|&n| new_node[n])).collect();
        let mut new_element = vec![usize::MAX; self.n_elements()];
        for (i, &e) in kept.iter().enumerate() {
            new_element[e] = i;
        }
        let regions = self
            .regions
            .iter()
            .map(|r| Region {
                name: r.name.clone(),
                elements: r.elements.iter().map(|&e| new_element[e]).filter(|&e| e != usize::MAX).collect(),
                normal: r.normal,
            })
            .collect();
        // an interface stays where both its faces are kept
        let twins = self
            .twins
            .iter()
            .filter(|t| new_element[t.lower.0] != usize::MAX && new_element[t.upper.0] != usize::MAX)
            .map(|t| EdgeTwin {
                lower: (new_element[t.lower.0], t.lower.1),
                upper: (new_element[t.upper.0], t.upper.1),
                interface: t.interface,
            })
            .collect();
        CrossSection { kind: self.kind, nodes, connectivity, regions, twins }
    }
}

#[cfg(test)]
mod tests {
    use crate::shape::SectionElementKind;

    use super::*;

    #[test]
    fn the_right_half_of_a_rectangle_is_a_rectangle() {
        let mut full =
            CrossSection::rectangle(SectionElementKind::L9, &[0.0, 0.5, 1.0, 1.5, 2.0], &[0.0, 1.0]).unwrap();
        full.regions.push(Region { name: "ends".into(), elements: vec![0, 3], normal: None });
        let half = CrossSection::rectangle(SectionElementKind::L9, &[1.0, 1.5, 2.0], &[0.0, 1.0]).unwrap();
        let centre = |s: &CrossSection, e: usize| s.element(e).iter().map(|&n| s.nodes[n][0]).sum::<f64>() / 9.0;
        let kept = full.retain_elements(|e| centre(&full, e) > 1.0);
        assert_eq!((kept.n_nodes(), kept.n_elements()), (half.n_nodes(), half.n_elements()));
        // a region keeps its kept elements, renumbered (old 3 is new 1)
        assert_eq!(kept.regions[0].elements, vec![1]);
        // every kept element has the same corner points as the half's, in order
        for e in 0..2 {
            let a: Vec<[f64; 2]> = kept.element(e).iter().map(|&n| kept.nodes[n]).collect();
            let b: Vec<[f64; 2]> = half.element(e).iter().map(|&n| half.nodes[n]).collect();
            assert_eq!(a, b);
        }
    }
}
