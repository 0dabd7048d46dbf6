//! The memory budget of a model, checked body by body before each section
//! is built (see [`crate::size`]): a model too large for the memory allowed
//! is refused before it is meshed.

use super::ModelError;
use crate::shape::{BeamElementKind, SectionElementKind};
use crate::size::{self, Sizes};

/// Sizes of the bodies read so far, checked against the limit before each
/// body's section is built (see [`crate::size`]).
pub(super) struct Budget {
    limit: Option<u64>,
    sizes: Sizes,
}

impl Budget {
    /// Nothing read yet; `limit`: the largest memory allowed (bytes).
    pub(super) fn new(limit: Option<u64>) -> Self {
        Self { limit, sizes: Sizes::default() }
    }

    /// Adds a body of `sec_elements` section elements (with `sec_nodes`
    /// nodes and `sec_pairs` coupled node pairs) swept along `axis_elements`
    /// beam elements; fails if the lower-bound memory exceeds the limit.
    #[allow(clippy::too_many_arguments)] // the counts of a section × axis body
    pub(super) fn add(
        &mut self,
        key: &str,
        section: SectionElementKind,
        beam: BeamElementKind,
        sec_elements: u64,
        sec_nodes: u64,
        sec_pairs: u64,
        axis_elements: u64,
    ) -> Result<(), ModelError> {
        let (p, q) = (section.order() as u64, beam.order() as u64);
        let axis_nodes = q * axis_elements + 1;
        let per_element = (p + 1) * (p + 1) * (q + 1);
        let elements = sec_elements.saturating_mul(axis_elements);
        let nodes = sec_nodes.saturating_mul(axis_nodes);
        let pairs = sec_pairs.saturating_mul(size::coupled_1d(axis_elements, q));
        let n = 3 * per_element;
        let s = &mut self.sizes;
        s.nodes = s.nodes.saturating_add(nodes);
        s.dofs = s.dofs.saturating_add(nodes.saturating_mul(3));
        s.elements = s.elements.saturating_add(elements);
        s.gauss_points = s.gauss_points.saturating_add(elements.saturating_mul(per_element));
        s.element_entries = s.element_entries.saturating_add(elements.saturating_mul(n * (n + 1) / 2));
        s.node_pairs = s.node_pairs.saturating_add(pairs);
        // 9 entries per off-diagonal node pair (each counted twice), 6 per diagonal block
        let nnz = pairs.saturating_sub(nodes).saturating_mul(9) / 2 + nodes.saturating_mul(6);
        s.pattern_nnz = s.pattern_nnz.saturating_add(nnz);
        s.factor_nnz = s.pattern_nnz;
        s.vtu_points = s.vtu_points.saturating_add(elements.saturating_mul(per_element));
        let needed = s.memory().total();
        match self.limit {
            Some(limit) if needed > limit => Err(ModelError::TooLarge {
                needed,
                limit,
                dofs: s.dofs,
                largest: format!("{key}: {sec_elements} section × {axis_elements} beam elements"),
            }),
            _ => Ok(()),
        }
    }
}
