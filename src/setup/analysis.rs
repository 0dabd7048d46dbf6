//! `[analysis]`: the kind of analysis and its geometry — what the driver
//! does with the model, checked against what the model holds.

use super::constraints::ConstraintHandler;
use crate::contact::{Indenter, PairContact};
use crate::input::schema::{AnalysisFile, AnalysisType, Geometry, MassMatrix, StrainMeasure};
use crate::input::{ModelError, invalid};
use crate::kinematics::Kinematics;
use crate::materials::Material;
use crate::mesh::Mesh;

pub(crate) use crate::input::ranges::MAX_MODES;

/// `analysis.type = "buckling"`: the linear buckling analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BucklingSettings {
    /// Modes wanted (`analysis.modes`, default 4).
    pub modes: usize,
}

/// `analysis.type = "modal"`: free vibration about the end of the static
/// analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModalSettings {
    /// Modes wanted (`analysis.modes`, default 6).
    pub modes: usize,
    /// `analysis.mass`.
    pub mass: crate::dynamics::MassKind,
}

/// The kinematics of `analysis.geometry` and `analysis.strain` (a strain
/// measure only with nonlinear geometry).
pub(super) fn kinematics(file: &AnalysisFile) -> Result<Kinematics, ModelError> {
    match (file.geometry.unwrap_or_default(), file.strain) {
        (Geometry::Linear, None) => Ok(Kinematics::Linear),
        (Geometry::Linear, Some(s)) => Err(invalid(
            "analysis.strain",
            match s {
                StrainMeasure::GreenLagrange => "\"green_lagrange\"",
                StrainMeasure::Logarithmic => "\"logarithmic\"",
            },
            "only with analysis.geometry = \"nonlinear\" (a small-strain analysis has one strain, sym ∇u)",
        )),
        (Geometry::Nonlinear, None | Some(StrainMeasure::GreenLagrange)) => Ok(Kinematics::TotalLagrangian),
        (Geometry::Nonlinear, Some(StrainMeasure::Logarithmic)) => Ok(Kinematics::TotalLagrangianLog),
    }
}

/// `analysis.imperfection`: the shape of a buckling mode, scaled, taken as
/// the stress-free initial shape of a nonlinear-geometry analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Imperfection {
    /// Buckling mode (1-based).
    pub mode: usize,
    /// Largest displacement component of the imperfection (m).
    pub amplitude: f64,
}

/// `analysis.imperfection`: with nonlinear geometry, and on a model whose
/// buckling analysis can be made (loads and fixed supports only, one step;
/// plastic materials are taken elastic for it).
pub(super) fn imperfection(file: &AnalysisFile, parts: &Parts<'_>) -> Result<Option<Imperfection>, ModelError> {
    let Some(imp) = &file.imperfection else { return Ok(None) };
    if file.geometry != Some(Geometry::Nonlinear) {
        return Err(invalid(
            "analysis.imperfection",
            "given",
            "only with analysis.geometry = \"nonlinear\" (a small-strain analysis does not see it)",
        ));
    }
    if imp.mode == 0 || imp.mode > MAX_MODES {
        return Err(invalid("analysis.imperfection.mode", imp.mode, format!("an integer in 1..={MAX_MODES}")));
    }
    let size = parts.mesh.bodies.iter().map(|b| b.size()).fold(0.0, f64::max);
    if !imp.amplitude.is_finite() || imp.amplitude == 0.0 || imp.amplitude.abs() > 0.1 * size {
        return Err(invalid(
            "analysis.imperfection.amplitude",
            crate::numbers::number(imp.amplitude),
            format!(
                "a non-zero length (m) of at most a tenth of the body's size, {}",
                crate::numbers::number(0.1 * size)
            ),
        ));
    }
    loads_and_supports_only(parts, "analysis.imperfection")?;
    Ok(Some(Imperfection { mode: imp.mode, amplitude: imp.amplitude }))
}

/// Loads and fixed supports only, in one step: what a buckling analysis
/// (and so an imperfection from one) can take.
fn loads_and_supports_only(parts: &Parts<'_>, what: &str) -> Result<(), ModelError> {
    let refuse = |key: String, value: &str, why: String| Err(invalid(key, value, why));
    let first = parts
        .indenters
        .first()
        .map(|i| ("indenters", &i.name))
        .or(parts.contacts.first().map(|c| ("contacts", &c.name)));
    if let Some((group, name)) = first {
        return refuse(
            format!("{group}[0]"),
            &format!("{name:?}"),
            format!("none with {what} (loads and supports only)"),
        );
    }
    if parts.steps > 1 {
        return refuse("steps".into(), &format!("{} steps", parts.steps), format!("one step with {what}"));
    }
    if let Some(i) = parts.constraints.first_moving() {
        return refuse(
            format!("constraints[{i}]"),
            "a non-zero prescribed displacement",
            format!("fixed components only with {what} (prescribe loads instead)"),
        );
    }
    Ok(())
}

/// What the model holds that a buckling analysis must check.
pub(super) struct Parts<'a> {
    pub mesh: &'a Mesh,
    pub materials: &'a [Material],
    pub constraints: &'a ConstraintHandler,
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
        if let (Some(m), false) = (file.modes, file.kind == Some(AnalysisType::Modal)) {
            return Err(invalid("analysis.modes", m, "only with analysis.type = \"buckling\" or \"modal\""));
        }
        return Ok(None);
    }
    let modes = file.modes.unwrap_or(4);
    if modes == 0 || modes > MAX_MODES {
        return Err(invalid("analysis.modes", modes, format!("an integer in 1..={MAX_MODES}")));
    }
    if file.geometry == Some(Geometry::Nonlinear) {
        return Err(invalid(
            "analysis.geometry",
            "\"nonlinear\"",
            "\"linear\" with analysis.type = \"buckling\" (a linear eigenvalue analysis about the small-strain state)",
        ));
    }
    loads_and_supports_only(parts, "analysis.type = \"buckling\"")?;
    for m in parts.mesh.bodies.iter().flat_map(|b| b.materials()) {
        let m = &parts.materials[m];
        if m.is_plastic() {
            return Err(invalid(
                format!("{}.plasticity", material_key(parts.materials, m)),
                format!("given for material {:?}", m.given),
                "elastic materials with analysis.type = \"buckling\" (the stress state is the linear elastic one)",
            ));
        }
    }
    Ok(Some(BucklingSettings { modes }))
}

/// `analysis.type = "modal"`, `analysis.modes` and `analysis.mass`: `None`
/// for another analysis. The frequencies are those of the tangent at the
/// end of the static analysis (of an unloaded model: the elastic
/// stiffness), so the static part may hold anything a static analysis may,
/// except friction (its tangent is unsymmetric); every body's material
/// needs a density.
pub(super) fn modal(file: &AnalysisFile, parts: &Parts<'_>) -> Result<Option<ModalSettings>, ModelError> {
    if file.kind != Some(AnalysisType::Modal) {
        if let (Some(m), false) = (file.mass, file.kind == Some(AnalysisType::Transient)) {
            return Err(invalid("analysis.mass", mass_word(m), "only with analysis.type = \"modal\" or \"transient\""));
        }
        return Ok(None);
    }
    let modes = file.modes.unwrap_or(6);
    if modes == 0 || modes > MAX_MODES {
        return Err(invalid("analysis.modes", modes, format!("an integer in 1..={MAX_MODES}")));
    }
    if file.imperfection.is_some() {
        return Err(invalid("analysis.imperfection", "given", "not with analysis.type = \"modal\""));
    }
    densities_given(parts, "modal")?;
    let frictional = (parts.indenters.iter().map(|i| i.friction).enumerate().map(|(k, f)| ("indenters", k, f)))
        .chain(parts.contacts.iter().map(|c| c.friction).enumerate().map(|(k, f)| ("contacts", k, f)))
        .find_map(|(group, k, f)| f.map(|f| (group, k, f.coefficient)));
    if let Some((group, k, mu)) = frictional {
        return Err(invalid(
            format!("{group}[{k}].friction"),
            crate::numbers::number(mu),
            "frictionless contact with analysis.type = \"modal\" (the tangent with friction is unsymmetric)",
        ));
    }
    Ok(Some(ModalSettings { modes, mass: mass_kind(file) }))
}

/// `analysis.mass` as the mass matrix's kind.
pub(super) fn mass_kind(file: &AnalysisFile) -> crate::dynamics::MassKind {
    match file.mass.unwrap_or_default() {
        MassMatrix::Consistent => crate::dynamics::MassKind::Consistent,
        MassMatrix::Lumped => crate::dynamics::MassKind::Lumped,
    }
}

/// Every body's material has a density (`kind`: the analysis type that needs it).
pub(super) fn densities_given(parts: &Parts<'_>, kind: &str) -> Result<(), ModelError> {
    for b in &parts.mesh.bodies {
        let Some(m) = b.materials().into_iter().map(|m| &parts.materials[m]).find(|m| m.density.is_none()) else {
            continue;
        };
        {
            return Err(invalid(
                format!("{}.density", material_key(parts.materials, m)),
                "(missing)",
                format!(
                    "the mass density in kg/m³ of material {:?} with analysis.type = \"{kind}\" (body {:?} is made of it)",
                    m.given, b.name
                ),
            ));
        }
    }
    Ok(())
}

fn mass_word(m: MassMatrix) -> &'static str {
    match m {
        MassMatrix::Consistent => "\"consistent\"",
        MassMatrix::Lumped => "\"lumped\"",
    }
}

/// `materials[i]`, the model file's entry of material `m` (of an oriented
/// copy, the entry it was copied from: the file's materials come first).
pub(super) fn material_key(materials: &[Material], m: &Material) -> String {
    match materials.iter().position(|x| x.name == m.given) {
        Some(i) => format!("materials[{i}]"),
        None => format!("materials (material {:?})", m.given),
    }
}

/// Ply damage only in a static or transient small-strain analysis: an
/// eigenvalue analysis is about an elastic state, and the law is written
/// for small strains. Checked before what an eigenvalue analysis asks of
/// the model (a modal strip was refused for its density, then, once
/// given, for the damage; a new-user review).
pub(super) fn damage_combinations(
    kind: Kind,
    kinematics: crate::kinematics::Kinematics,
    materials: &[Material],
    arc_length: bool,
) -> Result<(), ModelError> {
    if let Some((m, law)) =
        materials.iter().find_map(|m| m.damage.as_ref().filter(|d| d.viscosity() > 0.0).map(|d| (m, d)))
        && arc_length
    {
        return Err(invalid(
            format!("{}.damage.viscosity", material_key(materials, m)),
            law.viscosity(),
            "0 with solver.control = \"arc_length\" (the viscosity's time is the increment of the load factor, an \
             unknown of either sign there)",
        ));
    }
    let Some(m) = materials.iter().find(|m| m.damage.is_some()) else { return Ok(()) };
    let key = format!("{}.damage", material_key(materials, m));
    if !matches!(kind, Kind::Static | Kind::Transient) {
        return Err(invalid(
            key,
            format!("given with analysis.type = \"{}\"", kind.word()),
            "analysis.type = \"static\" or \"transient\" with ply damage (an eigenvalue analysis is about an \
             elastic state)",
        ));
    }
    if kinematics.is_nonlinear() {
        return Err(invalid(
            key,
            "given with analysis.geometry = \"nonlinear\"",
            "analysis.geometry = \"linear\" with ply damage (the law is written for small strains)",
        ));
    }
    Ok(())
}

/// The kind of analysis (`analysis.type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Static,
    Buckling,
    Modal,
    Transient,
}

impl Kind {
    /// The kind from which analysis the model holds.
    /// The kind `analysis.type` asks for.
    pub(super) fn asked(file: &AnalysisFile) -> Self {
        let asked = |k| file.kind == Some(k);
        Self::of(asked(AnalysisType::Buckling), asked(AnalysisType::Modal), asked(AnalysisType::Transient))
    }

    pub(super) fn of(buckling: bool, modal: bool, transient: bool) -> Self {
        match (buckling, modal, transient) {
            (true, _, _) => Self::Buckling,
            (_, true, _) => Self::Modal,
            (_, _, true) => Self::Transient,
            _ => Self::Static,
        }
    }

    /// The word of `analysis.type`.
    pub(super) fn word(self) -> &'static str {
        match self {
            Self::Static => "static",
            Self::Buckling => "buckling",
            Self::Modal => "modal",
            Self::Transient => "transient",
        }
    }
}

/// The combinations of `analysis.type` with other tables that are not
/// supported, refused by key: path following with a buckling analysis (its
/// eigenvalues are those of the linear state at load factor 1, a path ends
/// at another λ: a 500 N load was reported with a 625 N reaction).
pub(super) fn combinations(kind: Kind, arc_length: bool) -> Result<(), ModelError> {
    if arc_length && kind == Kind::Buckling {
        return Err(invalid(
            "solver.control",
            "\"arc_length\"",
            "load control (no solver.control) with analysis.type = \"buckling\": the critical load factors are \
             those of the linear elastic state at load factor 1, while a path following ends at another load factor \
             (for the path past the critical load, use analysis.type = \"static\" with analysis.imperfection)",
        ));
    }
    Ok(())
}

/// Adaptive refinement is driven by the static estimate (of a transient
/// analysis: its worst kept time) or, in a modal or buckling analysis, by
/// the modes' estimates (`crate::adapt`). `adapt.modes` (modal and buckling
/// only) is at most the `modes` computed.
pub(super) fn adapt_combinations(adapt: Option<&super::AdaptSettings>, modes: Option<usize>) -> Result<(), ModelError> {
    let Some(adapt) = adapt else { return Ok(()) };
    match (adapt.modes, modes) {
        (Some(m), None) => Err(invalid("adapt.modes", m, "only with analysis.type = \"modal\" or \"buckling\"")),
        (Some(m), Some(n)) if m == 0 || m > n => Err(invalid(
            "adapt.modes",
            m,
            format!("an integer in 1..={n} (the lowest modes followed, at most analysis.modes = {n})"),
        )),
        _ => Ok(()),
    }
}

/// The warnings of an eigenvalue analysis asking for `modes` (`None`:
/// another analysis): more modes than equations ([`warn_modes`]), and
/// with symmetry planes only the symmetric modes.
pub(super) fn eigen_warnings(
    modes: Option<usize>,
    mesh: &Mesh,
    constraints: &ConstraintHandler,
    planes: bool,
) -> Vec<super::Warning> {
    let Some(modes) = modes else { return Vec::new() };
    let mut out: Vec<super::Warning> = warn_modes(modes, mesh, constraints).into_iter().collect();
    if planes {
        out.push(super::Warning {
            key: "symmetry".into(),
            message: "with symmetry planes only the modes symmetric about them are found: an antisymmetric buckling \
                      or vibration mode, and a lower eigenvalue it may have, needs the full structure"
                .into(),
        });
    }
    out
}

/// A warning when `analysis.modes` asks for more modes than the model has
/// free equations (3 per node less the constrained components): the
/// eigenvalue problem has no more, and the run reports those.
fn warn_modes(modes: usize, mesh: &Mesh, constraints: &ConstraintHandler) -> Option<super::Warning> {
    let constrained = constraints.constrained().count();
    let free = mesh.n_dofs().saturating_sub(constrained);
    (modes > free).then(|| super::Warning {
        key: "analysis.modes".into(),
        message: format!(
            "analysis.modes = {modes} but the model has {free} free equations ({} nodes × 3 less {} constrained \
             components): at most {free} modes exist, and the run reports those (refine the mesh for more)",
            mesh.n_nodes(),
            constrained
        ),
    })
}
