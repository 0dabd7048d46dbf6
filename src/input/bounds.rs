//! Physically motivated bounds on the magnitudes a model file may give.
//!
//! A value can be finite and still make no sense for a small-strain analysis
//! of a structure: `young_modulus = 1e-300` underflows every stress, a load
//! of 1e300 N overflows the residual, a grading ratio of 1e300 makes
//! elements of zero length. Such inputs used to run and end in NaN, a
//! misleading "singular matrix" message or, once, an endless loop in plot
//! tick generation. Every bound below is far outside the range of any real
//! structure, so it rejects nonsense without restricting analyses:
//!
//! | quantity | bound | why |
//! |---|---|---|
//! | Young's modulus | 1e5 ≤ E ≤ 1e13 Pa | soft foams to ten times diamond |
//! | yield stress | ≤ 0.1 E | a yield strain above 10 % is outside small-strain plasticity |
//! | hardening modulus | ≤ 100 E | |
//! | hardening table | peeq ≤ 10, stress ≤ E | |
//! | coordinates | \|x\| ≤ 1e4 m | a 10 km structure |
//! | element size | ≥ 1e-9 × the body's extent | round-off would swamp the element |
//! | grading ratio | 1e-4 … 1e4 | |
//! | tractions, pressures, load/area | ≤ E of the loaded body | a stress of E is a strain of order 1 |
//! | prescribed and indenter displacements | ≤ the body's size | a rigid-body scale motion is not small displacement |
//! | penalty factor α | 1e-3 … 1e8 | |
//! | mass density | 0.1 … 2e5 kg/m³ | aerogels to ten times osmium |
//! | Poisson's ratio (isotropic) | −1 < ν ≤ 0.4999 | rubber's; closer to ½ the bulk modulus exceeds 5000 G and the solves lose the digits Newton needs |
//! | ply elements | ≥ 1e-5 × the stack's thickness | thin-ply prepregs (20 µm) are 2e-4 of a 0.1 m stack |

use super::{ModelError, invalid};
pub use crate::numbers::{limit, list, number};

/// Smallest accepted Young's modulus (Pa).
pub(crate) const MIN_YOUNG: f64 = 1e5;
/// Largest accepted Young's modulus (Pa).
pub(crate) const MAX_YOUNG: f64 = 1e13;
/// Largest yield strain σ_y / E.
pub(crate) const MAX_YIELD_STRAIN: f64 = 0.1;
/// Largest hardening modulus as a multiple of E.
pub(crate) const MAX_HARDENING: f64 = 100.0;
/// Largest equivalent plastic strain in a hardening table.
pub(crate) const MAX_TABLE_PEEQ: f64 = 10.0;
pub(crate) use crate::mesh::{GRADING_RATIO, MAX_COORD, MIN_RELATIVE_SIZE};
/// Accepted range of the mass density (kg/m³).
pub const DENSITY: (f64, f64) = (0.1, 2e5);
/// Largest Poisson's ratio of an isotropic material: natural rubber's
/// (1 − 2ν = 2e-4, bulk modulus 5000 times the shear modulus). Closer to ½
/// the stiffness matrix is too ill-conditioned for double precision:
/// examples/epp_cantilever.toml and bending_compact_4L9.toml converge at
/// ν = 0.49999 and stall at a residual of 1e-5 at 0.499999.
pub(crate) const MAX_POISSON: f64 = 0.4999;
/// Smallest element of a ply (its thickness over its elements) as a share
/// of the stack's thickness; the thinnest plies made (thin-ply prepregs,
/// 20 µm) are 2e-4 of a 0.1 m stack. Thinner, the ply's through-thickness
/// stiffness swamps its neighbours' and the linear solves lose the digits
/// Newton needs: Pagano's S = 4 laminate (examples/pagano_s4.toml) with its
/// middle ply 1e-9 m thick (elements 3.7e-8 of the stack) stalls at a
/// residual of 1e-3 (1e-8 m, 3.7e-7, converges), and an L9 section with an
/// element 1e-6 of its height stalls at 4e-5 (1e-5 converges).
pub(crate) const MIN_PLY_SHARE: f64 = 1e-5;
/// Accepted range of the dimensionless penalty factor.
pub(crate) const PENALTY_FACTOR: (f64, f64) = (1e-3, 1e8);

/// `v` finite and in `[lo, hi]`, else an error naming the range and why.
pub fn within(key: &str, v: f64, lo: f64, hi: f64, why: &str) -> Result<f64, ModelError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(v)
    } else {
        Err(invalid(key, number(v), format!("a number from {} to {} ({why})", limit(lo), limit(hi))))
    }
}

/// A coordinate (m).
pub fn coordinate(key: &str, v: f64) -> Result<f64, ModelError> {
    within(key, v, -MAX_COORD, MAX_COORD, "a coordinate in m; a structure larger than 10 km is not plausible")
}

/// Three coordinates (m).
pub fn point(key: &str, v: impl Into<[f64; 3]>) -> Result<[f64; 3], ModelError> {
    let v = v.into();
    if v.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORD) {
        Ok(v)
    } else {
        Err(invalid(key, format!("{v:?}"), format!("three finite coordinates within ±{MAX_COORD:e} m")))
    }
}

/// A vector whose Euclidean norm is at most `max` (e.g. a displacement or a
/// stress), with `what` saying what the bound is.
pub fn vector(key: &str, v: impl Into<[f64; 3]>, max: f64, what: &str) -> Result<[f64; 3], ModelError> {
    let v = v.into();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if v.iter().all(|x| x.is_finite()) && norm <= max {
        Ok(v)
    } else {
        let shown: Vec<String> = v.iter().map(|x| number(*x)).collect();
        Err(invalid(
            key,
            format!("[{}]", shown.join(", ")),
            format!("three finite numbers of magnitude at most {} ({what})", limit(max)),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_rejects_out_of_range_and_non_finite_values_with_the_reason() {
        assert_eq!(within("k", 2.0, 1.0, 3.0, "why").unwrap(), 2.0);
        for bad in [0.5, 4.0, f64::NAN, f64::INFINITY] {
            let e = within("m.k", bad, 1.0, 3.0, "because").unwrap_err().to_string();
            assert!(e.contains("m.k") && e.contains("from 1e0 to 3e0 (because)"), "{e}");
            assert!(e.len() < 200, "{e}");
        }
        assert!(point("p", [1e5, 0.0, 0.0]).is_err());
        assert!(vector("d", [3.0, 4.0, 0.0], 5.0, "size").is_ok());
        assert!(vector("d", [3.0, 4.0, 0.1], 5.0, "size").unwrap_err().to_string().contains("at most 5e0 (size)"));
    }
}
