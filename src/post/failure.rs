//! The failure indices of a solution at its Gauss points: for every
//! criterion of [`crate::materials::failure`] its largest index and where,
//! and the first-ply-failure load factor; and the interlaminar criterion's
//! at the bonded ply interfaces (straight edges between section elements of
//! two plies — two materials, or two layers of one —, whose axis 3 both lie
//! along the edge's normal), where the
//! traction `(σ33, τ13, τ23)` in the material axes is the interface's, from
//! the ply on each side with its own strengths.
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
    /// proportional loading (∞ if it never fails); `None` (null) where the
    /// loading is not a load factor's ([`summary`]).
    pub first_failure_load_factor: Option<f64>,
    /// Where its strength ratio is smallest: `None` (null) with the load
    /// factor (a new-user review found a place of first failure beside a
    /// null load factor of it).
    pub(crate) first_failure_at: Option<Place>,
}

/// The failure indices of a run (`summary.json` `ply_failure`).
#[derive(Debug, Clone, Serialize)]
pub struct FailureSummary {
    /// Per criterion, in the order of [`CRITERIA`].
    pub criteria: Vec<Criterion>,
    /// The smallest first-failure load factor of the criteria (`None`
    /// as theirs).
    pub(crate) first_ply_failure_load_factor: Option<f64>,
    /// The interlaminar criterion (`fi_interlaminar`) over the bonded ply
    /// interfaces; `None` in a model without one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interlaminar: Option<Criterion>,
}

/// A value and where it is.
type Extreme = (f64, Place);

/// The four indices of an [`crate::materials::Indices`], in the order of [`CRITERIA`].
pub fn as_array(i: &crate::materials::Indices) -> [f64; 4] {
    [i.max_stress, i.tsai_wu, i.hashin_fibre, i.hashin_matrix]
}

/// The name of the interlaminar criterion (`summary.json`
/// `ply_failure.interlaminar`; `crate::materials::failure`).
pub(crate) const INTERLAMINAR: &str = "fi_interlaminar";

/// A criterion's extremes so far: (largest index, where), (smallest
/// ratio, where).
type Extremes = Option<(Extreme, Extreme)>;

/// `slot` with the index `value` and strength ratio `ratio` of the point
/// `place` taken in.
fn take(slot: &mut Extremes, (value, ratio): (f64, f64), place: &dyn Fn() -> Place) {
    let Some(((index, at), (smallest, first))) = slot else {
        *slot = Some(((value, place()), (ratio, place())));
        return;
    };
    if value > *index {
        (*index, *at) = (value, place());
    }
    if ratio < *smallest {
        (*smallest, *first) = (ratio, place());
    }
}

/// Per section element of `body`, the natural lines `(coordinate,
/// value)` (`0`: ξ, `1`: η) of its edges that are bonded ply interfaces:
/// straight, shared with an element of another material or layer
/// ([`crate::mesh::Body::layer_of`]: the two middle plies of a `[0/90]s`
/// are two layers of one material), both materials'
/// axis 3 along the edge's normal (plies of a laminate stacked along z, a
/// web's plies stacked along x, any stack of a gmsh section; not a
/// profile's web against its flange; a cohesive interface's twin nodes are
/// not shared: its own onset index is `d_interface`'s).
fn interface_lines(body: &crate::mesh::Body, materials: &[crate::materials::Material]) -> Vec<Vec<(usize, f64)>> {
    // axis 3 of material `m` along the unit (x, z) vector `n`: the stress
    // n ⊗ n is all σ33 in its axes
    let along = |m: usize, n: [f64; 2]| {
        let nn = [n[0] * n[0], 0.0, n[1] * n[1], 0.0, n[0] * n[1], 0.0];
        (materials[m].frame.stress_to_material(&nn)[2] - 1.0).abs() < 1e-9
    };
    let section = &body.section;
    let basis = crate::shape::Lagrange2d::new(section.kind.order());
    let holding = section.elements_at_nodes();
    (0..section.n_elements())
        .map(|es| {
            (0..4)
                .filter_map(|k| {
                    let local = section.edge_local_nodes(k);
                    let nodes: Vec<usize> = local.iter().map(|&l| section.element(es)[l]).collect();
                    let (p, q) = (section.nodes[nodes[0]], section.nodes[nodes[nodes.len() - 1]]);
                    let (dx, dz) = (q[0] - p[0], q[1] - p[1]);
                    let length = dx.hypot(dz);
                    let straight = nodes.iter().all(|&t| {
                        let r = section.nodes[t];
                        ((r[0] - p[0]) * dz - (r[1] - p[1]) * dx).abs() <= 1e-9 * length * length
                    });
                    let normal = [-dz / length, dx / length];
                    let bonded = section.across(&holding, es, &nodes).is_some_and(|f| {
                        let (mf, me) = (body.material_of(f), body.material_of(es));
                        let apart = mf != me || body.layer_of(f) != body.layer_of(es);
                        apart && along(mf, normal) && along(me, normal)
                    });
                    let (a, b) = (basis.node(local[0]), basis.node(local[local.len() - 1]));
                    let d = usize::from(a[0] != b[0]);
                    (straight && bonded).then_some((d, a[d]))
                })
                .collect()
        })
        .collect()
}

/// The failure summary of the fields `view` at load factor `lambda`,
/// `None` if no material has strengths. `lambda` is `None` where the end
/// state says nothing of a first failure under a growing load: a transient
/// run (its end may lie after the rebound: the damaging drop weight's plies
/// had cracked, and `λ_end · min R` said `10.7`; a new-user review) and a
/// model whose plies damage (their stresses are the softened ones); the
/// indices are still given, of the end state.
pub fn summary(view: &FieldView<'_>, lambda: Option<f64>) -> Option<FailureSummary> {
    if view.materials.iter().all(|m| m.strengths.is_none()) {
        return None;
    }
    let mut best: Vec<Extremes> = vec![None; 4];
    let mut interlaminar: Extremes = None;
    for (b, body) in view.mesh.bodies.iter().enumerate() {
        let (ps, pb) = (body.section.kind.order(), body.axis.kind.order());
        let grid = |p: usize| (0..=p).map(move |k| -1.0 + 2.0 * k as f64 / p as f64);
        let lines = interface_lines(body, view.materials);
        for e in 0..body.n_elements() {
            let es = body.split_element(e).0;
            let material = &view.materials[body.material_of(es)];
            if material.strengths.is_none() {
                continue;
            }
            for zeta in grid(pb) {
                for eta in grid(ps) {
                    for xi in grid(ps) {
                        let loc = Location { body: b, element: e, natural: [xi, eta, zeta] };
                        let stress = view.sample(&loc).stress;
                        let Some(ix) = material.failure_indices(&stress) else { continue };
                        let place = || Place {
                            point: PointValues::new(body, &loc).position(body),
                            body: body.name.clone(),
                            material: material.name.clone(),
                        };
                        let values = as_array(&ix);
                        for (k, slot) in best.iter_mut().enumerate() {
                            take(slot, (values[k], ix.ratios[k]), &place);
                        }
                        if lines[es].iter().any(|&(d, v)| [xi, eta][d] == v) {
                            let index = material.interlaminar_index(&stress).expect("a material with strengths");
                            take(&mut interlaminar, index, &place);
                        }
                    }
                }
            }
        }
    }
    let criterion = |(slot, criterion): (Extremes, &'static str)| {
        let ((largest_index, largest_at), (ratio, first_failure_at)) = slot?;
        Some(Criterion {
            criterion,
            largest_index,
            largest_at,
            first_failure_load_factor: lambda.map(|l| l * ratio),
            first_failure_at: lambda.map(|_| first_failure_at),
        })
    };
    let criteria: Vec<Criterion> = best.into_iter().zip(CRITERIA).filter_map(criterion).collect();
    let interlaminar = criterion((interlaminar, INTERLAMINAR));
    let first = lambda.map(|_| criteria.iter().flat_map(|c| c.first_failure_load_factor).fold(f64::INFINITY, f64::min));
    (!criteria.is_empty()).then_some(FailureSummary { criteria, first_ply_failure_load_factor: first, interlaminar })
}
