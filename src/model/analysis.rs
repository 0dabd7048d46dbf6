//! `[analysis]`: the kind of analysis and its geometry — what the driver
//! does with the model, checked against what the model holds.

use super::schema::{AnalysisFile, AnalysisType, Geometry};
use super::{ModelError, invalid};
use crate::bc::Constraint;
use crate::contact::{Indenter, PairContact};
use crate::kinematics::Kinematics;
use crate::materials::Material;
use crate::mesh::Mesh;

/// Largest number of buckling modes one run may ask for.
pub const MAX_MODES: usize = 50;

/// `analysis.type = "buckling"`: the linear buckling analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BucklingSettings {
    /// Modes wanted (`analysis.modes`, default 4).
    pub modes: usize,
}

/// The kinematics of `analysis.geometry`.
pub(super) fn kinematics(file: &AnalysisFile) -> Kinematics {
    match file.geometry.unwrap_or_default() {
        Geometry::Linear => Kinematics::Linear,
        Geometry::Nonlinear => Kinematics::TotalLagrangian,
    }
}

/// What the model holds that a buckling analysis must check.
pub(super) struct Parts<'a> {
    pub mesh: &'a Mesh,
    pub materials: &'a [Material],
    pub constraints: &'a [Constraint],
    pub indenters: &'a [Indenter],
    pub contacts: &'a [PairContact],
    pub steps: usize,
}

/// `analysis.type` and `analysis.modes`: `None` for a static analysis. A
/// linear buckling analysis (the eigenvalues of `K₀ + μ K_σ` about the
/// linear elastic state at load factor 1) needs an elastic, small-strain
/// model with loads and fixed supports only; anything else is refused by
/// its key.
pub(super) fn buckling(file: &AnalysisFile, parts: &Parts<'_>) -> Result<Option<BucklingSettings>, ModelError> {
    if file.kind.unwrap_or_default() != AnalysisType::Buckling {
        if let Some(m) = file.modes {
            return Err(invalid("analysis.modes", m, "only with analysis.type = \"buckling\""));
        }
        return Ok(None);
    }
    let modes = file.modes.unwrap_or(4);
    if modes == 0 || modes > MAX_MODES {
        return Err(invalid("analysis.modes", modes, format!("an integer in 1..={MAX_MODES}")));
    }
    let refuse = |key: String, value: &str, why: &str| Err(invalid(key, value, why.to_string()));
    if file.geometry == Some(Geometry::Nonlinear) {
        return refuse(
            "analysis.geometry".into(),
            "\"nonlinear\"",
            "\"linear\" with analysis.type = \"buckling\" (a linear eigenvalue analysis about the small-strain state)",
        );
    }
    if !parts.indenters.is_empty() || !parts.contacts.is_empty() {
        let key = if parts.indenters.is_empty() { "contacts" } else { "indenters" };
        return refuse(key.into(), "present", "none with analysis.type = \"buckling\" (loads and supports only)");
    }
    if parts.steps > 1 {
        return refuse("steps".into(), &format!("{} steps", parts.steps), "one step with analysis.type = \"buckling\"");
    }
    for (i, c) in parts.constraints.iter().enumerate() {
        if c.values.iter().flatten().any(|&v| v != 0.0) {
            return refuse(
                format!("constraints[{i}]"),
                "a non-zero prescribed displacement",
                "fixed components only with analysis.type = \"buckling\" (prescribe loads instead)",
            );
        }
    }
    for b in &parts.mesh.bodies {
        let m = &parts.materials[b.material];
        if m.is_plastic() {
            return refuse(
                format!("materials \"{}\".plasticity", m.name),
                "present",
                "elastic materials with analysis.type = \"buckling\" (the stress state is the linear elastic one)",
            );
        }
    }
    Ok(Some(BucklingSettings { modes }))
}
