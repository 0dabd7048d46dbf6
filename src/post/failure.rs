//! The failure indices of a solution at its Gauss points: for every
//! criterion of [`crate::materials::failure`] its largest index and where,
//! and the first-ply-failure load factor.
//!
//! The stresses are those of the fields people look at (`post::FieldView`,
//! as in the VTU): at every node of every element's Lagrange grid, faces
//! included, so the largest values at ply surfaces and interfaces are seen
//! from the ply on each side; each is turned into its material's axes. Under proportional loading a
//! point's stress is `λ σ/λ_end`, so the load factor at which the first
//! point fails is `λ_end · min R` over the points, `R` the strength ratio
//! of [`crate::materials::Indices`]: exact for a linear elastic model, an
//! estimate from the final state otherwise (contact, plasticity or large
//! displacements make the stress path non-proportional).

use serde::Serialize;

use super::FieldView;
use crate::values::{Location, PointValues};

pub use crate::materials::failure::CRITERIA;

/// A place in the model and the material there.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Place {
    /// The point (m).
    pub point: [f64; 3],
    /// The body.
    pub body: String,
    /// The material there (an oriented copy's name carries its angle).
    pub material: String,
}

/// One criterion's largest index, its first-ply failure, and where.
#[derive(Debug, Clone, Serialize)]
pub struct Criterion {
    /// The criterion (`fi_max_stress`, …).
    pub criterion: &'static str,
    /// Its largest index over the model (1 at failure).
    pub largest_index: f64,
    /// Where the index is largest.
    pub(crate) largest_at: Place,
    /// `λ_end · min R`: the load factor of its first failure under
    /// proportional loading (∞ if it never fails).
    pub first_failure_load_factor: f64,
    /// Where its strength ratio is smallest.
    pub(crate) first_failure_at: Place,
}

/// The failure indices of a run (`summary.json` `ply_failure`).
#[derive(Debug, Clone, Serialize)]
pub struct FailureSummary {
    /// Per criterion, in the order of [`CRITERIA`].
    pub criteria: Vec<Criterion>,
    /// The smallest first-failure load factor of the criteria.
    pub(crate) first_ply_failure_load_factor: f64,
}

/// A value and where it is.
type Extreme = (f64, Place);

/// The four indices of an [`crate::materials::Indices`], in the order of [`CRITERIA`].
pub fn as_array(i: &crate::materials::Indices) -> [f64; 4] {
    [i.max_stress, i.tsai_wu, i.hashin_fibre, i.hashin_matrix]
}

/// The failure summary of the fields `view` at load factor `lambda`,
/// `None` if no material has strengths.
pub fn summary(view: &FieldView<'_>, lambda: f64) -> Option<FailureSummary> {
    if view.materials.iter().all(|m| m.strengths.is_none()) {
        return None;
    }
    // per criterion: (largest index, where), (smallest ratio, where)
    let mut best: Vec<Option<(Extreme, Extreme)>> = vec![None; 4];
    for (b, body) in view.mesh.bodies.iter().enumerate() {
        let (ps, pb) = (body.section.kind.order(), body.axis.kind.order());
        let grid = |p: usize| (0..=p).map(move |k| -1.0 + 2.0 * k as f64 / p as f64);
        for e in 0..body.n_elements() {
            let material = &view.materials[body.material_of(body.split_element(e).0)];
            if material.strengths.is_none() {
                continue;
            }
            for zeta in grid(pb) {
                for eta in grid(ps) {
                    for xi in grid(ps) {
                        let loc = Location { body: b, element: e, natural: [xi, eta, zeta] };
                        let Some(ix) = material.failure_indices(&view.sample(&loc).stress) else { continue };
                        let place = || Place {
                            point: PointValues::new(body, &loc).position(body),
                            body: body.name.clone(),
                            material: material.name.clone(),
                        };
                        let values = as_array(&ix);
                        for (k, slot) in best.iter_mut().enumerate() {
                            let Some(((index, at), (ratio, first))) = slot else {
                                *slot = Some(((values[k], place()), (ix.ratios[k], place())));
                                continue;
                            };
                            if values[k] > *index {
                                (*index, *at) = (values[k], place());
                            }
                            if ix.ratios[k] < *ratio {
                                (*ratio, *first) = (ix.ratios[k], place());
                            }
                        }
                    }
                }
            }
        }
    }
    let criteria: Vec<Criterion> = best
        .into_iter()
        .zip(CRITERIA)
        .filter_map(|(slot, criterion)| {
            let ((largest_index, largest_at), (ratio, first_failure_at)) = slot?;
            Some(Criterion {
                criterion,
                largest_index,
                largest_at,
                first_failure_load_factor: lambda * ratio,
                first_failure_at,
            })
        })
        .collect();
    let first = criteria.iter().map(|c| c.first_failure_load_factor).fold(f64::INFINITY, f64::min);
    (!criteria.is_empty()).then_some(FailureSummary { criteria, first_ply_failure_load_factor: first })
}
