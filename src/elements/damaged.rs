//! The ply-damage points of an element (`crate::materials::damage`): their
//! history, and the update the kernel calls at each of them.

use super::PointData;
use super::softening::Term;
use crate::materials::damage::{DamageState, PlyDamage, Softening};
use crate::materials::{Material, Predictor, Response};
use crate::voigt::Voigt;

/// The ply-damage history of one element's Gauss points
/// ([`crate::materials::damage`]): read from the committed states, written
/// to the trial ones.
pub struct DamagePoints<'a> {
    /// Committed states (read).
    pub committed: &'a [DamageState],
    /// Crack-band lengths `[fibre, matrix]` per point (m).
    pub band: &'a [[f64; 2]],
    /// The change of the load factor since the committed states.
    pub step: f64,
    /// How a transient run integrates the points' forces (Newmark's γ and
    /// whether damaged points take the end-of-step stress,
    /// `crate::dynamics::ply_forces`); `None` in a static run.
    pub(crate) impulse: Option<crate::materials::damage_impulse::PointForces>,
    /// Trial states (written).
    pub trial: &'a mut [DamageState],
}

/// The update of ply point `q` of `dp` at the strain `eps`: the response
/// whose stress the force takes (the end-of-step stress where
/// `dp.impulse` asks for it, `crate::materials::damage_impulse`), then
/// the physical stress apart and the consistent tangent's rank-one terms
/// (`softening`); on its damage surface the loading branch's tangent if
/// `loading` (`Predictor::Loading`).
fn damaged_point(
    material: &Material,
    law: &PlyDamage,
    eps: &Voigt,
    (dp, q, loading): (&mut DamagePoints<'_>, usize, bool),
) -> (Response, Option<Voigt>, Softening) {
    let (band, step, old) = (dp.band[q], dp.step, &dp.committed[q]);
    let (mut r, terms) = material.update_damaged(law, eps, (band, step, dp.impulse, loading), (old, &mut dp.trial[q]));
    let physical = dp.impulse.map(|_| std::mem::replace(&mut r.stress, dp.trial[q].force_stress));
    (r, physical, terms)
}

/// The material update of point `q` (weight `w`) at the strain `eps`: a
/// damaging ply's (its rank-one tangent terms added to `softening`), or
/// the material's own; with the physical stress apart where the force
/// takes another (a damaged ply point's end-of-step stress).
pub(super) fn update_point(
    material: &Material,
    points: &mut PointData<'_>,
    eps: &Voigt,
    (q, w): (usize, f64),
    softening: &mut Vec<Term>,
) -> (Response, Option<Voigt>) {
    let loading = points.predictor == Predictor::Loading;
    match (&material.damage, points.damage.as_mut()) {
        (Some(law), Some(dp)) => {
            let (r, physical, terms) = damaged_point(material, law, eps, (dp, q, loading));
            softening.extend(terms.terms().iter().map(|&(s, g)| (q, w, s, g)));
            (r, physical)
        }
        _ => (material.update_for_element(eps, &points.committed[q], points.predictor), None),
    }
}
