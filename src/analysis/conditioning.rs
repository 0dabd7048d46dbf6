//! Why Newton may stall on a sound model: an ill-conditioned stiffness
//! matrix, whose linear solves lose the digits the iteration needs. A
//! linear model converges in one iteration unless its solves are
//! inaccurate, so when it stops — or when any model stops and one of its
//! scales is extreme — the stop message names the scales that make the
//! matrix ill-conditioned, each with its key (issue 46): the smallest
//! element against its section or axis, a Poisson's ratio near ½, the
//! contrast of the materials' stiffnesses. A model whose plies damage
//! without viscosity is told what lets Newton past a damage peak
//! ([`softening`]).

use crate::numbers::limit;
use crate::setup::Model;

/// An element thinner than this share of its section (or axis) is named.
/// An L9 section whose middle element is 1e-6 of its height stalls at a
/// relative residual of 4e-5; at 1e-5 it converges (in 4 iterations, a
/// linear model that needs 1).
const THIN: f64 = 1e-5;
/// A Poisson's ratio above this is named (bulk modulus above 500 G).
const NEAR_HALF: f64 = 0.499;
/// A ratio of the stiffest to the softest modulus above this is named.
const CONTRAST: f64 = 1e6;

/// One scale of the model: its key, what it is, and how extreme (a share,
/// smaller is worse).
struct Scale {
    key: String,
    what: String,
    share: f64,
}

/// The smallest element of each body against its section's or axis's
/// extent.
fn thinnest(model: &Model) -> Option<Scale> {
    let mut worst: Option<Scale> = None;
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let bounds = body.section.bounds();
        let extent = (bounds[1] - bounds[0]).max(bounds[3] - bounds[2]);
        for es in 0..body.section.n_elements() {
            let points: Vec<[f64; 2]> = body.section.element(es).iter().map(|&n| body.section.nodes[n]).collect();
            let span = |k: usize| {
                let (lo, hi) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[k]), hi.max(p[k])));
                hi - lo
            };
            let size = span(0).min(span(1));
            if extent > 0.0 && worst.as_ref().is_none_or(|w| size / extent < w.share) {
                worst = Some(Scale {
                    key: format!("bodies[{b}].section"),
                    what: format!(
                        "section element {es} of body {:?} is {} m thin, {} of the section's {} m",
                        body.name,
                        limit(size),
                        limit(size / extent),
                        limit(extent)
                    ),
                    share: size / extent,
                });
            }
        }
        let nodes = &body.axis.nodes;
        let length = nodes[nodes.len() - 1] - nodes[0];
        for e in 0..body.axis.n_elements() {
            let (a, c) = body.axis.element_span(e);
            if length > 0.0 && worst.as_ref().is_none_or(|w| (c - a) / length < w.share) {
                worst = Some(Scale {
                    key: format!("bodies[{b}].axis"),
                    what: format!(
                        "axis element {e} of body {:?} is {} m long, {} of the axis's {} m",
                        body.name,
                        limit(c - a),
                        limit((c - a) / length),
                        limit(length)
                    ),
                    share: (c - a) / length,
                });
            }
        }
    }
    worst
}

/// The diagnosis to append to the stop of a Newton iteration that did not
/// converge: the extreme scales of the model, or for a linear model (which
/// must converge at once) its smallest element at least. `None` if there
/// is nothing to say.
pub(super) fn diagnose(model: &Model) -> Option<String> {
    let mut scales = Vec::new();
    let linear = model.is_linear();
    if let Some(t) = thinnest(model).filter(|t| linear || t.share < THIN) {
        scales.push(t);
    }
    let used = used(model);
    for &k in &used {
        let m = &model.materials[k];
        if m.anisotropic.is_none() && m.poisson > NEAR_HALF {
            scales.push(Scale {
                key: format!("materials[{}].poisson_ratio", super::checks::file_material(model, k)),
                what: format!(
                    "material {:?} has ν = {} (its bulk modulus is {} times its shear modulus)",
                    m.name,
                    m.poisson,
                    limit(m.bulk_modulus() / m.shear_modulus())
                ),
                share: 1.0 - 2.0 * m.poisson,
            });
        }
    }
    let young = |k: &usize| model.materials[*k].young;
    let (soft, stiff) = (
        used.iter().min_by(|a, b| young(a).total_cmp(&young(b))),
        used.iter().max_by(|a, b| young(a).total_cmp(&young(b))),
    );
    if let (Some(&soft), Some(&stiff)) = (soft, stiff)
        && young(&stiff) > CONTRAST * young(&soft)
    {
        scales.push(Scale {
            key: format!("materials[{}].young_modulus", super::checks::file_material(model, soft)),
            what: format!(
                "the materials' Young's moduli range from {} Pa ({:?}) to {} Pa ({:?})",
                limit(young(&soft)),
                model.materials[soft].name,
                limit(young(&stiff)),
                model.materials[stiff].name
            ),
            share: young(&soft) / young(&stiff),
        });
    }
    if scales.is_empty() {
        return None;
    }
    let list: Vec<String> = scales.iter().map(|s| format!("{} ({})", s.what, s.key)).collect();
    let lead = if linear {
        "the model is linear, so Newton stalls only when its linear solves are inaccurate: the stiffness matrix is too \
         ill-conditioned for double precision"
    } else {
        "the stiffness matrix may be too ill-conditioned for the linear solves to give Newton the digits it needs"
    };
    Some(format!(
        "{lead}; the model's scales: {}; make the extreme scale less extreme (thicker elements, fewer and thicker \
         plies, a Poisson's ratio further from 0.5)",
        list.join("; ")
    ))
}

/// Why a model whose plies damage may stop past a peak: a damaging
/// material without Duvaut–Lions viscosity, whose points switch between
/// their softening and unloading branches from one Newton iteration to the
/// next (docs/composites.md; a new user's beam stopped at λ = 0.33 with
/// residuals cycling, and no word of the viscosity); `None` if every
/// damaging material has one.
pub(super) fn softening(model: &Model) -> Option<String> {
    let mut keys: Vec<usize> = used(model)
        .into_iter()
        .filter(|&k| model.materials[k].damage.as_ref().is_some_and(|d| d.viscosity() == 0.0))
        .map(|k| super::checks::file_material(model, k))
        .collect();
    keys.dedup();
    let k = *keys.first()?;
    Some(format!(
        "materials[{k}].damage has no viscosity: past a damage peak Newton cycles between the points' softening \
         and unloading branches; a Duvaut–Lions viscosity (materials[{k}].damage.viscosity, e.g. 1e-3 in \
         load-factor units) lets it pass (docs/composites.md)"
    ))
}

/// The materials (indices into `model.materials`) some element uses, each once.
fn used(model: &Model) -> Vec<usize> {
    let mut m: Vec<usize> = model.mesh.bodies.iter().flat_map(|b| b.materials()).collect();
    m.sort_unstable();
    m.dedup();
    m
}
