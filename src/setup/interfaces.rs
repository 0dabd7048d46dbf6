//! Cohesive interfaces of laminates: the interface materials
//! (`[[materials]]` with `cohesive`), the laws of the interfaces a laminate
//! asks for (`interfaces`, `interface_material`; `laminate::requests`) with
//! their default penalty and shear strength, and their points on the mesh
//! (`crate::interfaces`).

use super::Warning;
use super::laminate;
use crate::input::schema::{BodyFile, CohesiveFile, MaterialFile, ModelFile, SectionFile};
use crate::input::{ModelError, defaults, invalid, ranges};
use crate::interfaces::Interface;
use crate::materials::Material;
use crate::materials::cohesive::{Cohesive, CohesiveError};
use crate::mesh::Mesh;

/// The interface materials of `file` and where they are used: checked
/// before the bodies are built.
pub(super) fn check(file: &ModelFile) -> Result<(), ModelError> {
    check_materials(&file.materials)?;
    refuse_as_body_material(&file.bodies, &file.materials)
}

/// An interface material has its `name` and `cohesive` only.
fn check_materials(file: &[MaterialFile]) -> Result<(), ModelError> {
    for (i, m) in file.iter().enumerate().filter(|(_, m)| m.cohesive.is_some()) {
        let given = [
            ("young_modulus", m.young_modulus.is_some()),
            ("poisson_ratio", m.poisson_ratio.is_some()),
            ("orthotropic", m.orthotropic.is_some()),
            ("stiffness", m.stiffness.is_some()),
            ("strengths", m.strengths.is_some()),
            ("density", m.density.is_some()),
            ("plasticity", m.plasticity.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|g| g.1) {
            return Err(invalid(
                format!("materials[{i}].{key}"),
                "given with cohesive",
                "an interface material has only name and cohesive = {…}",
            ));
        }
    }
    Ok(())
}

/// Refuses an interface material where a body material is expected: a
/// body's `material`, a ply's, a zone's.
fn refuse_as_body_material(bodies: &[BodyFile], materials: &[MaterialFile]) -> Result<(), ModelError> {
    let cohesive = |name: &str| materials.iter().any(|m| m.cohesive.is_some() && m.name == name);
    for (i, b) in bodies.iter().enumerate() {
        let key = format!("bodies[{i}]");
        let mut uses: Vec<(String, &str)> = Vec::new();
        if let Some(m) = &b.material {
            uses.push((format!("{key}.material"), m));
        }
        let plies = match &b.section {
            SectionFile::Laminate(l) => l.plies.as_deref(),
            s => s.wall_plies(),
        };
        for (k, p) in plies.unwrap_or(&[]).iter().enumerate() {
            uses.push((format!("{key}.section.plies[{k}].material"), &p.material));
        }
        for (k, z) in b.zones.iter().flatten().enumerate() {
            if let Some(m) = &z.material {
                uses.push((format!("{key}.zones[{k}].material"), m));
            }
        }
        if let Some((k, m)) = uses.into_iter().find(|(_, m)| cohesive(m)) {
            return Err(invalid(
                k,
                format!("{m:?}"),
                "a body material (an interface material, with cohesive, is for a laminate's interfaces only)",
            ));
        }
    }
    Ok(())
}

/// The cohesive interfaces of every laminate body of `model`, with their
/// laws and points on `mesh` (`materials` the model's).
pub(super) fn interfaces(
    model: &ModelFile,
    mesh: &Mesh,
    materials: &[Material],
    warnings: &mut Vec<Warning>,
) -> Result<Vec<Interface>, ModelError> {
    let (bodies, file) = (&model.bodies, &model.materials);
    let mut out: Vec<Interface> = Vec::new();
    // the first material with a viscosity, for the arc-length refusal
    for (i, b) in bodies.iter().enumerate() {
        let SectionFile::Laminate(l) = &b.section else { continue };
        let sk = format!("bodies[{i}].section");
        let plies = l.plies.as_deref().unwrap_or(&[]);
        for r in laminate::requests(&sk, l, plies.len())? {
            let (mkey, name) = match &r.material {
                Some(m) => (format!("{}.material", r.key), m),
                None => (format!("{sk}.interface_material"), l.interface_material.as_ref().expect("checked")),
            };
            let (j, c) = find(file, &mkey, name)?;
            // the thinner of the two plies sets the default penalty
            let below = &plies[r.ply];
            let above = &plies[r.ply + 1];
            let thin = if below.thickness <= above.thickness { below } else { above };
            let e3 = materials.iter().find(|m| m.name == thin.material).map_or(f64::NAN, through_thickness_modulus);
            let law_key = format!("materials[{j}].cohesive");
            let law = law(&law_key, c, defaults::PENALTY_PER_STIFFNESS * e3 / thin.thickness, warnings)?;
            let points = crate::interfaces::points(&mesh.bodies[i], r.ply, r.crack);
            if points.is_empty() {
                return Err(invalid(
                    r.key,
                    format!("the interface above ply {}", r.ply + 1),
                    "an interface inside the body as its symmetry planes cut it (a plane through the stack leaves \
                     one side of it out)",
                ));
            }
            // a plane normal to y cuts the axis: a crack across it runs past the part modelled
            let cut = model.symmetry.iter().any(|s| s.plane.y.is_some());
            let axis = &mesh.bodies[i].axis;
            let (y0, y1) = (axis.nodes[0], *axis.nodes.last().expect("an axis has nodes"));
            let past = |[from, to]: [f64; 2]| !cut && (from < y0 - 1e-9 * (y1 - y0) || to > y1 + 1e-9 * (y1 - y0));
            if let Some([from, to]) = r.crack.filter(|&c| !points.iter().any(|p| p.cracked) || past(c)) {
                // a precrack in mm, or off the beam's end, ran as an uncracked
                // beam without a word, one running past an end as a crack to
                // it (new-user reviews)
                let short = crate::numbers::short;
                return Err(invalid(
                    format!("{}.crack", r.key),
                    format!("{{ from = {}, to = {} }}", short(from), short(to)),
                    format!(
                        "an interval along y within the body that holds nodes of the interface: the body runs \
                         from y = {} to {} m",
                        short(y0),
                        short(y1)
                    ),
                ));
            }
            let body_name = mesh.bodies[i].name.clone();
            out.push(Interface {
                name: format!("interface{}", r.ply + 1),
                key: r.key,
                body: i,
                body_name,
                law,
                law_key,
                points,
            });
        }
    }
    Ok(out)
}

/// The material called `name` (for key `key`), which must be an interface
/// material: its index and law.
fn find<'a>(file: &'a [MaterialFile], key: &str, name: &str) -> Result<(usize, &'a CohesiveFile), ModelError> {
    let found = file.iter().enumerate().find(|(_, m)| m.name == name);
    match found.and_then(|(j, m)| m.cohesive.as_ref().map(|c| (j, c))) {
        Some(found) => Ok(found),
        None => {
            let names: Vec<&str> = file.iter().filter(|m| m.cohesive.is_some()).map(|m| m.name.as_str()).collect();
            Err(invalid(key, format!("{name:?}"), format!("one of the materials with cohesive = {{…}}: {names:?}")))
        }
    }
}

/// E3 of a ply's material: `1/S33` of its compliance (its Young's modulus
/// if isotropic).
fn through_thickness_modulus(m: &Material) -> f64 {
    match crate::materials::anisotropic::invert(m.elastic_stiffness()) {
        Some(s) => 1.0 / s[2][2],
        None => m.young,
    }
}

/// Largest final opening `2 G_c / strength` (m) of a plausible cohesive
/// law: a tough structural adhesive (`G_Ic ≈ 5` kJ/m², `N ≈ 10` MPa) opens
/// `1` mm; a strength typed in MPa opens metres.
const MAX_FINAL_OPENING: f64 = 0.01;

/// The law of `[materials.cohesive]` (key `ck`), with `penalty` the
/// default penalty of its interface. The shear strength defaults to
/// `N √(G_IIc/G_Ic)`, the one value for which the Camanho–Dávila law with
/// one penalty is thermodynamically consistent under a changing mixity
/// (Turon, Camanho, Costa & Renart 2010, Compos. Struct. 92:1857); another
/// one more than 10 % away is warned about.
fn law(ck: &str, c: &CohesiveFile, penalty: f64, warnings: &mut Vec<Warning>) -> Result<Cohesive, ModelError> {
    ranges::TOUGHNESS.check(&format!("{ck}.gic"), c.gic, "the mode I toughness in J/m²")?;
    ranges::TOUGHNESS.check(&format!("{ck}.giic"), c.giic, "the mode II toughness in J/m²")?;
    ranges::BK_EXPONENT.check(&format!("{ck}.bk_exponent"), c.bk_exponent, "the Benzeggagh–Kenane exponent")?;
    ranges::STRENGTH.check(&format!("{ck}.normal_strength"), c.normal_strength, "the onset traction in Pa")?;
    let consistent = c.normal_strength * (c.giic / c.gic).sqrt();
    let shear = match c.shear_strength {
        None => consistent,
        Some(s) => {
            ranges::STRENGTH.check(&format!("{ck}.shear_strength"), s, "the onset shear traction in Pa")?;
            if (s / consistent - 1.0).abs() > 0.1 {
                warnings.push(Warning {
                    key: format!("{ck}.shear_strength"),
                    message: format!(
                        "{s:e} Pa is more than 10 % from normal_strength·√(giic/gic) = {consistent:e} Pa: with one \
                         penalty the mixed-mode law dissipates more or less than the Benzeggagh–Kenane toughness \
                         when the mixity changes (Turon et al. 2010)"
                    ),
                });
            }
            s
        }
    };
    for (key, strength, toughness, g) in
        [("normal_strength", c.normal_strength, c.gic, "gic"), ("shear_strength", shear, c.giic, "giic")]
    {
        let opening = 2.0 * toughness / strength;
        if opening > MAX_FINAL_OPENING && (key == "normal_strength" || c.shear_strength.is_some()) {
            warnings.push(Warning {
                key: format!("{ck}.{key}"),
                message: format!(
                    "{key} = {strength} Pa with {g} = {toughness} J/m² lets the interface open {opening:.3e} m \
                     before it fails (2 {g}/{key}), where a tough adhesive fails within about a millimetre: the \
                     strength in Pa (MPa × 1e6)?"
                ),
            });
        }
    }
    let penalty = match c.penalty {
        Some(k) => ranges::COHESIVE_PENALTY.check(&format!("{ck}.penalty"), k, "the penalty stiffness in Pa/m")?,
        None => penalty,
    };
    let viscosity = match c.viscosity {
        Some(v) => {
            ranges::COHESIVE_VISCOSITY.check(&format!("{ck}.viscosity"), v, "a viscosity in load-factor units")?
        }
        None => defaults::COHESIVE_VISCOSITY,
    };
    Cohesive::new(penalty, c.normal_strength, shear, c.gic, c.giic, c.bk_exponent)
        .map(|law| Cohesive { viscosity, ..law })
        .map_err(|e| match e {
        CohesiveError::NotPositive { key, value } => {
            let key = match key {
                "g_ic" => "gic",
                "g_iic" => "giic",
                k => k,
            };
            invalid(format!("{ck}.{key}"), value, "a positive finite number")
        }
        CohesiveError::OnsetAboveToughness { strength, toughness, onset_energy, value } => {
            // a defaulted shear strength follows the normal one
            let (key, v) = match (strength, c.shear_strength) {
                ("shear_strength", Some(s)) => ("shear_strength", s),
                _ => ("normal_strength", c.normal_strength),
            };
            let toughness = if toughness == "g_ic" { "gic" } else { "giic" };
            invalid(
                format!("{ck}.{key}"),
                v,
                format!(
                    "a strength whose elastic energy at onset, {strength}²/(2 penalty) = {onset_energy:.4e} J/m², is \
                     below {toughness} = {value:.4e} J/m² (else the softening would snap back inside the point): a \
                     lower strength or a higher penalty"
                ),
            )
        }
    })
}
