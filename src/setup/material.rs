//! Validation of `[[materials]]`: elastic constants (isotropic, orthotropic
//! or a full stiffness), strengths, the isotropic hardening
//! law (perfect, linear, table, Voce) and the kinematic back-stresses, each
//! bounded to physically sensible magnitudes.

use crate::input::bounds;
use crate::input::schema::*;
use crate::input::{ModelError, invalid};
use crate::input::{defaults, ranges};
use crate::materials::anisotropic::{self, positive_definite};
use crate::materials::damage::PlyDamage;
use crate::materials::{BackStress, Hardening, MAX_BACKSTRESSES, Material, Orthotropic, Strengths};
use crate::voigt::Matrix6;

/// `[[materials]]`, but the interface materials (with `cohesive`:
/// `setup/interfaces.rs`).
pub(super) fn materials(file: &[MaterialFile]) -> Result<Vec<Material>, ModelError> {
    if let Some(i) = file.iter().position(|m| m.cohesive.is_some() && m.damage.is_some()) {
        return Err(invalid(
            format!("materials[{i}].damage"),
            "given with cohesive",
            "ply damage on a body material (orthotropic with strengths); an interface material has only cohesive",
        ));
    }
    file.iter().enumerate().filter(|(_, m)| m.cohesive.is_none()).map(|(i, m)| material(i, m)).collect()
}

/// Elastic wave speeds of solids (m/s): an elastomer's tens to diamond's
/// `18,000`. A material whose constants and density give a speed outside
/// is likely in other units.
const WAVE_SPEEDS: (f64, f64) = (10.0, 25_000.0);

/// Warns about each material whose density and elastic constants give a
/// wave speed `√(max C_ii / ρ)` (the normal stiffnesses) outside
/// [`WAVE_SPEEDS`]: a density in g/cm³ (aluminium's `2.7` gave modes
/// `√1000` times too high without a word), or moduli in MPa.
pub(super) fn density_warnings(file: &[MaterialFile], materials: &[Material], warnings: &mut Vec<super::Warning>) {
    for m in materials {
        let Some(rho) = m.density else { continue };
        let c = m.elastic_stiffness();
        let speed = ((0..3).map(|i| c[i][i]).fold(0.0, f64::max) / rho).sqrt();
        if (WAVE_SPEEDS.0..=WAVE_SPEEDS.1).contains(&speed) {
            continue;
        }
        let i = file.iter().position(|f| f.name == m.name).unwrap_or_default();
        warnings.push(super::Warning {
            key: format!("materials[{i}].density"),
            message: format!(
                "density = {rho} kg/m³ with the material's elastic constants gives an elastic wave speed of {speed:.3e} \
                 m/s, where solids lie between {:.0} and {:.0} m/s: the density in kg/m³ (g/cm³ × 1000) and the \
                 moduli in Pa?",
                WAVE_SPEEDS.0, WAVE_SPEEDS.1
            ),
        });
    }
}

/// Smallest strength over the largest normal stiffness of any engineering
/// material: a ply's transverse tensile strength over its fibre modulus is
/// about `2e-4` (T300/5208: `40 MPa / 181 GPa`), concrete's `1e-4`, a foam's
/// `1e-2`; a strength typed in MPa against moduli in Pa gives `1e-8` or less.
const MIN_STRENGTH_OVER_MODULUS: f64 = 1e-6;

/// Warns about each material whose smallest strength is below
/// [`MIN_STRENGTH_OVER_MODULUS`] times its largest normal stiffness `max
/// C_ii`: strengths in MPa (a new user's `xt = 1500` was taken as 1500 Pa,
/// and every failure index read in the millions).
pub(super) fn strength_warnings(file: &[MaterialFile], materials: &[Material], warnings: &mut Vec<super::Warning>) {
    const NAMES: [[&str; 3]; 3] = [["xt", "yt", "zt"], ["xc", "yc", "zc"], ["s12", "s13", "s23"]];
    for m in materials {
        let Some(s) = &m.strengths else { continue };
        let c = m.elastic_stiffness();
        let modulus = (0..3).map(|i| c[i][i]).fold(0.0, f64::max);
        let values = [s.tension, s.compression, s.shear];
        let (name, value) = NAMES
            .iter()
            .flatten()
            .zip(values.iter().flatten())
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("nine strengths");
        if *value >= MIN_STRENGTH_OVER_MODULUS * modulus {
            continue;
        }
        let i = file.iter().position(|f| f.name == m.name).unwrap_or_default();
        warnings.push(super::Warning {
            key: format!("materials[{i}].strengths.{name}"),
            message: format!(
                "{name} = {value} Pa is {:.1e} of the material's largest modulus ({modulus:.4e} Pa), where the \
                 strengths of engineering materials lie above {MIN_STRENGTH_OVER_MODULUS:e} of it (a ply's \
                 transverse strength about 2e-4): the strengths in Pa (MPa × 1e6)?",
                value / modulus
            ),
        });
    }
}

pub(super) fn material(i: usize, m: &MaterialFile) -> Result<Material, ModelError> {
    let key = format!("materials[{i}]");
    let density = m
        .density
        .map(|rho| {
            bounds::within(
                &format!("{key}.density"),
                rho,
                bounds::DENSITY.0,
                bounds::DENSITY.1,
                "the mass density in kg/m³, from aerogels to ten times osmium",
            )
        })
        .transpose()?;
    let base = match (m.orthotropic.as_ref(), m.stiffness.as_ref()) {
        (None, None) => isotropic(&key, m)?,
        (Some(o), None) => anisotropic(&key, m, "orthotropic", orthotropic(&key, o)?.1)?,
        (None, Some(c)) => anisotropic(&key, m, "stiffness", full_stiffness(&key, c)?)?,
        (Some(_), Some(_)) => {
            return Err(invalid(
                format!("{key}.stiffness"),
                "given with orthotropic",
                "one of young_modulus/poisson_ratio, orthotropic or stiffness",
            ));
        }
    };
    let strengths = m.strengths.as_ref().map(|s| strengths(&key, s)).transpose()?;
    let damage = m.damage.as_ref().map(|d| damage(&key, m, d, strengths)).transpose()?;
    Ok(base.with_density(density).with_strengths(strengths).with_damage(damage))
}

/// `[materials.damage]` (key `key.damage`): fracture energies and the
/// largest damage, on an orthotropic material with strengths (the law needs
/// the engineering constants and Hashin's strengths; plasticity is refused
/// with `orthotropic` already).
fn damage(key: &str, m: &MaterialFile, d: &DamageFile, strengths: Option<Strengths>) -> Result<PlyDamage, ModelError> {
    let dk = format!("{key}.damage");
    let needs = "ply damage needs orthotropic = {…} (its engineering constants) and strengths = {…} (Hashin's onset)";
    if m.stiffness.is_some() {
        return Err(invalid(&dk, "given with stiffness", needs));
    }
    let Some(o) = m.orthotropic.as_ref() else {
        let what = if m.plasticity.is_some() { "given with plasticity" } else { "given with isotropic constants" };
        return Err(invalid(&dk, what, needs));
    };
    let Some(strengths) = strengths else {
        return Err(invalid(&dk, "given without strengths", needs));
    };
    let energy = |name: &str, v: f64| {
        ranges::FRACTURE_ENERGY.check(&format!("{dk}.{name}"), v, "the mode's fracture energy in J/m²")
    };
    let toughness = [
        energy("fibre_tension", d.fibre_tension)?,
        energy("fibre_compression", d.fibre_compression)?,
        energy("matrix_tension", d.matrix_tension)?,
        energy("matrix_compression", d.matrix_compression)?,
    ];
    let max_damage = match d.max_damage {
        Some(v) => ranges::MAX_DAMAGE.check(
            &format!("{dk}.max_damage"),
            v,
            "the largest damage of a mode (its point keeps 1 − max_damage of its stiffness)",
        )?,
        None => defaults::MAX_DAMAGE,
    };
    let (constants, _) = orthotropic(key, o)?;
    let viscosity = match d.viscosity {
        Some(v) => ranges::DAMAGE_VISCOSITY.check(&format!("{dk}.viscosity"), v, "a viscosity in load-factor units")?,
        None => defaults::DAMAGE_VISCOSITY,
    };
    let consistent = d.tangent.unwrap_or_default() == DamageTangent::Consistent;
    let alpha = "the weight of the longitudinal shear in fibre tension (0: none, 1: Hashin's)";
    let fibre_shear = d.fibre_shear.map(|v| ranges::FIBRE_SHEAR.check(&format!("{dk}.fibre_shear"), v, alpha));
    let fibre_shear = fibre_shear.transpose()?.unwrap_or(defaults::FIBRE_SHEAR);
    let uniaxial = d.softening_stress.unwrap_or_default() == SofteningStress::Uniaxial;
    let law =
        PlyDamage::new(constants, strengths, toughness, max_damage).map(|law| law.with_uniaxial_softening(uniaxial));
    law.map(|law| law.with_consistent_tangent(consistent).with_viscosity(viscosity).with_fibre_shear(fibre_shear))
        .map_err(|e| invalid(&dk, "refused", e.to_string()))
}

/// The isotropic elastic constants and the plasticity of `m`.
fn isotropic(key: &str, m: &MaterialFile) -> Result<Material, ModelError> {
    let young = m.young_modulus.ok_or_else(|| {
        invalid(
            format!("{key}.young_modulus"),
            "(missing)",
            "Young's modulus in Pa (or, for an anisotropic material, orthotropic = {…} or stiffness = [[…], …])",
        )
    })?;
    let young = bounds::within(
        &format!("{key}.young_modulus"),
        young,
        bounds::MIN_YOUNG,
        bounds::MAX_YOUNG,
        "Young's modulus in Pa, from soft foams to ten times diamond",
    )?;
    let nu = m.poisson_ratio.ok_or_else(|| {
        invalid(format!("{key}.poisson_ratio"), "(missing)", "Poisson's ratio, a number in (−1, 0.4999]")
    })?;
    if !ranges::POISSON_RATIO.contains(nu) {
        return Err(invalid(
            format!("{key}.poisson_ratio"),
            nu,
            format!(
                "a number in (−1, {}] (rubber's; nearer to 0.5 the stiffness matrix is too ill-conditioned to solve \
                 in double precision)",
                bounds::MAX_POISSON
            ),
        ));
    }
    let (hardening, kinematic) = match &m.plasticity {
        None => (None, Vec::new()),
        Some(p) => {
            let pk = format!("{key}.plasticity");
            (Some(hardening(&pk, p, young)?), kinematic(&pk, p.kinematic.as_deref().unwrap_or(&[]), young)?)
        }
    };
    Ok(Material::new(m.name.clone(), young, nu, hardening).with_kinematic(kinematic))
}

/// An anisotropic elastic material (its constants given by `which`): no
/// isotropic constants, no plasticity.
fn anisotropic(key: &str, m: &MaterialFile, which: &str, stiffness: Matrix6) -> Result<Material, ModelError> {
    for (name, given) in [("young_modulus", m.young_modulus), ("poisson_ratio", m.poisson_ratio)] {
        if let Some(v) = given {
            return Err(invalid(
                format!("{key}.{name}"),
                crate::numbers::number(v),
                format!("no isotropic constants with {which}"),
            ));
        }
    }
    if m.plasticity.is_some() {
        return Err(invalid(
            format!("{key}.plasticity"),
            "given",
            format!("no plasticity with {which}: anisotropic materials are elastic (J2 plasticity is isotropic)"),
        ));
    }
    Ok(Material::anisotropic(m.name.clone(), stiffness))
}

/// `orthotropic = {…}`: moduli bounded like `young_modulus`, the stiffness
/// positive definite (Jones, Mechanics of Composite Materials, §2.4).
fn orthotropic(key: &str, o: &OrthotropicFile) -> Result<(Orthotropic, Matrix6), ModelError> {
    let ok = format!("{key}.orthotropic");
    let modulus = |name: &str, v: f64| {
        bounds::within(
            &format!("{ok}.{name}"),
            v,
            bounds::MIN_YOUNG,
            bounds::MAX_YOUNG,
            "a modulus in Pa, from soft foams to ten times diamond",
        )
    };
    let ratio = |name: &str, v: f64| {
        if ranges::ORTHOTROPIC_POISSON.contains(v) {
            Ok(v)
        } else {
            Err(invalid(format!("{ok}.{name}"), v, "a finite Poisson's ratio (|ν| < 10; admissible with the moduli)"))
        }
    };
    let c = Orthotropic {
        young: [modulus("e1", o.e1)?, modulus("e2", o.e2)?, modulus("e3", o.e3)?],
        shear: [modulus("g12", o.g12)?, modulus("g13", o.g13)?, modulus("g23", o.g23)?],
        poisson: [ratio("nu12", o.nu12)?, ratio("nu13", o.nu13)?, ratio("nu23", o.nu23)?],
    };
    let stiffness = c.stiffness().ok_or_else(|| {
        invalid(
            &ok,
            format!("ν12 = {}, ν13 = {}, ν23 = {}", o.nu12, o.nu13, o.nu23),
            "Poisson's ratios with a positive definite compliance: ν_ij² < E_i/E_j and \
             1 − ν12ν21 − ν23ν32 − ν13ν31 − 2ν21ν32ν13 > 0 (Jones §2.4.1)",
        )
    })?;
    Ok((c, stiffness))
}

/// `stiffness = [[…] × 6]`: symmetric, positive definite, entries bounded.
fn full_stiffness(key: &str, rows: &[Exact<f64, 6>]) -> Result<Matrix6, ModelError> {
    let sk = format!("{key}.stiffness");
    if rows.len() != 6 {
        return Err(invalid(&sk, format!("{} rows", rows.len()), "6 rows of 6 numbers (Pa)"));
    }
    let c: Matrix6 = std::array::from_fn(|i| rows[i].0);
    for (i, row) in c.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            if !(v.is_finite() && v.abs() <= 10.0 * bounds::MAX_YOUNG) {
                return Err(invalid(format!("{sk}[{i}][{j}]"), v, "a finite stiffness in Pa"));
            }
        }
    }
    if !positive_definite(&c) {
        return Err(invalid(
            &sk,
            "not symmetric positive definite",
            "a symmetric, positive definite 6×6 matrix in the order xx, yy, zz, xy, xz, yz (engineering shears)",
        ));
    }
    let young = anisotropic::invert(&c).map(|s| (0..3).map(|i| 1.0 / s[i][i]).fold(0.0, f64::max)).unwrap_or(0.0);
    bounds::within(
        &sk,
        young,
        bounds::MIN_YOUNG,
        bounds::MAX_YOUNG,
        "moduli 1/S_ii from soft foams to ten times diamond",
    )?;
    Ok(c)
}

/// `strengths = {…}`: positive stresses below the largest modulus.
fn strengths(key: &str, s: &StrengthsFile) -> Result<Strengths, ModelError> {
    let sk = format!("{key}.strengths");
    let v = |name: &str, v: f64| {
        ranges::STRENGTH.check(
            &format!("{sk}.{name}"),
            v,
            "a strength in Pa, positive (compressive ones as magnitudes)",
        )
    };
    let (yt, yc, s12) = (v("yt", s.yt)?, v("yc", s.yc)?, v("s12", s.s12)?);
    Ok(Strengths {
        tension: [v("xt", s.xt)?, yt, v("zt", s.zt.unwrap_or(yt))?],
        compression: [v("xc", s.xc)?, yc, v("zc", s.zc.unwrap_or(yc))?],
        shear: [s12, v("s13", s.s13.unwrap_or(s12))?, v("s23", s.s23)?],
    })
}

/// What `yield_stress` may be, for the messages.
const YIELD_WHY: &str =
    "the yield stress in Pa, positive and at most 0.1 E: a larger yield strain is outside small-strain plasticity";

/// The isotropic hardening law of `plasticity` (key `pk`). Which keys each
/// law has is the schema's ([`HardeningLaw`]); the values are checked here.
/// A required key is an `Option` there so that its absence is reported
/// here with the key's path, unit and meaning (serde would say only
/// `missing field`).
fn hardening(pk: &str, p: &PlasticityFile, young: f64) -> Result<Hardening, ModelError> {
    let max_sy = bounds::MAX_YIELD_STRAIN * young;
    let sy = p
        .yield_stress
        .map(|v| bounds::within(&format!("{pk}.yield_stress"), v, f64::MIN_POSITIVE, max_sy, YIELD_WHY))
        .transpose()?;
    let need_sy =
        || sy.ok_or_else(|| invalid(format!("{pk}.yield_stress"), "(missing)", "the initial yield stress in Pa"));
    let required = |name: &str, v: Option<f64>, what: &str| {
        v.ok_or_else(|| invalid(format!("{pk}.{name}"), "(missing)", what.to_string()))
    };
    Ok(match &p.hardening {
        HardeningLaw::Perfect {} => Hardening::Perfect { yield_stress: need_sy()? },
        HardeningLaw::Linear { hardening_modulus } => {
            let h = required(
                "hardening_modulus",
                *hardening_modulus,
                "the plastic hardening modulus H in Pa (≥ 0) for hardening = \"linear\"",
            )?;
            bounds::within(
                &format!("{pk}.hardening_modulus"),
                h,
                0.0,
                bounds::MAX_HARDENING * young,
                "the plastic hardening modulus H in Pa, from 0 to 100 E",
            )?;
            Hardening::Linear { yield_stress: need_sy()?, modulus: h }
        }
        HardeningLaw::Voce { saturation_stress, saturation_rate } => {
            let q = required(
                "saturation_stress",
                *saturation_stress,
                "the Voce saturation stress Q in Pa (≥ 0) for hardening = \"voce\"",
            )?;
            bounds::within(
                &format!("{pk}.saturation_stress"),
                q,
                0.0,
                young,
                "the Voce saturation stress Q in Pa, from 0 to E",
            )?;
            let b = required(
                "saturation_rate",
                *saturation_rate,
                "the Voce saturation rate b (dimensionless, > 0) for hardening = \"voce\"",
            )?;
            let rate = format!("{pk}.saturation_rate");
            ranges::SATURATION_RATE.check(&rate, b, "the Voce saturation rate b (dimensionless)")?;
            // the initial slope Q b is a hardening modulus: the same bound
            let max_rate = bounds::MAX_HARDENING * young / q.max(f64::MIN_POSITIVE);
            bounds::within(&rate, b, 0.0, max_rate, "a rate whose initial slope Q b is at most 100 E")?;
            Hardening::Voce { yield_stress: need_sy()?, saturation: q, rate: b }
        }
        HardeningLaw::Table { table } => {
            let t = table.as_ref().ok_or_else(|| {
                invalid(format!("{pk}.table"), "(missing)", "[[peeq, yield_stress], …] starting at peeq = 0")
            })?;
            let t: Vec<[f64; 2]> = t.iter().map(|r| r.0).collect();
            table_law(pk, &t, sy, young)?
        }
    })
}

/// `hardening = "table"`: points of increasing peeq from 0, no softening,
/// each segment's slope bounded like a hardening modulus; `sy` (if given)
/// must be the first stress.
fn table_law(pk: &str, t: &[[f64; 2]], sy: Option<f64>, young: f64) -> Result<Hardening, ModelError> {
    if t.is_empty() {
        return Err(invalid(format!("{pk}.table"), "[]", "a non-empty table whose first point has peeq = 0"));
    }
    if t[0][0] != 0.0 {
        return Err(invalid(
            format!("{pk}.table[0]"),
            bounds::list(&t[0][..]),
            "a first point [0.0, initial yield stress]: the table starts at peeq = 0",
        ));
    }
    for (k, w) in t.windows(2).enumerate() {
        if !(w[1][0] > w[0][0]) || !(w[1][1] >= w[0][1]) || !w[1][0].is_finite() || !w[1][1].is_finite() {
            return Err(invalid(
                format!("{pk}.table[{}]", k + 1),
                bounds::list(&w[1][..]),
                "strictly increasing peeq and non-decreasing (no softening), finite yield stress",
            ));
        }
        // the segment's slope is a hardening modulus: the same bound as
        // `hardening_modulus` (a near-vertical segment overflows it)
        let slope = (w[1][1] - w[0][1]) / (w[1][0] - w[0][0]);
        if !(slope <= bounds::MAX_HARDENING * young) {
            return Err(invalid(
                format!("{pk}.table[{}]", k + 1),
                bounds::list(&w[1][..]),
                format!(
                    "a segment slope of at most 100 E = {} Pa (this one rises {} Pa over a peeq of {})",
                    bounds::limit(bounds::MAX_HARDENING * young),
                    bounds::number(w[1][1] - w[0][1]),
                    bounds::number(w[1][0] - w[0][0])
                ),
            ));
        }
    }
    if !(t[0][1] > 0.0 && t[0][1].is_finite()) {
        return Err(invalid(format!("{pk}.table[0]"), bounds::list(&t[0][..]), "a positive initial yield stress"));
    }
    let max_sy = bounds::MAX_YIELD_STRAIN * young;
    bounds::within(&format!("{pk}.table[0][1]"), t[0][1], 0.0, max_sy, YIELD_WHY)?;
    let last = t.len() - 1;
    bounds::within(
        &format!("{pk}.table[{last}][0]"),
        t[last][0],
        0.0,
        bounds::MAX_TABLE_PEEQ,
        "an equivalent plastic strain of at most 10",
    )?;
    bounds::within(&format!("{pk}.table[{last}][1]"), t[last][1], 0.0, young, "a yield stress of at most E")?;
    if let Some(s) = sy
        && (s - t[0][1]).abs() > 1e-9 * s
    {
        return Err(invalid(
            format!("{pk}.yield_stress"),
            bounds::number(s),
            format!("the table's first stress ({}) or no yield_stress", bounds::number(t[0][1])),
        ));
    }
    Ok(Hardening::Table { strains: t.iter().map(|r| r[0]).collect(), stresses: t.iter().map(|r| r[1]).collect() })
}

/// `plasticity.kinematic`: at most [`MAX_BACKSTRESSES`] back-stresses.
fn kinematic(pk: &str, list: &[KinematicFile], young: f64) -> Result<Vec<BackStress>, ModelError> {
    let kk = format!("{pk}.kinematic");
    if list.len() > MAX_BACKSTRESSES {
        return Err(invalid(kk, list.len(), format!("at most {MAX_BACKSTRESSES} back-stresses")));
    }
    let mut kinematic = Vec::new();
    for (i, k) in list.iter().enumerate() {
        bounds::within(
            &format!("{kk}[{i}].modulus"),
            k.modulus,
            f64::MIN_POSITIVE,
            bounds::MAX_HARDENING * young,
            "the kinematic hardening modulus C in Pa, positive and at most 100 E",
        )?;
        ranges::KINEMATIC_RECALL.check(
            &format!("{kk}[{i}].recall"),
            k.recall,
            "the recall rate γ (dimensionless), from 0 (linear kinematic hardening)",
        )?;
        kinematic.push(BackStress { modulus: k.modulus, recall: k.recall });
    }
    Ok(kinematic)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material_file(toml_text: &str) -> MaterialFile {
        toml::from_str(toml_text).unwrap()
    }

    fn err(r: Result<impl std::fmt::Debug, ModelError>) -> String {
        format!("{}", r.unwrap_err())
    }

    #[test]
    fn materials_are_bounded_and_tables_checked() {
        let ok = material(0, &material_file("name = \"s\"\nyoung_modulus = 200e9\npoisson_ratio = 0.3")).unwrap();
        assert_eq!((ok.young, ok.poisson), (200e9, 0.3));
        let e = err(material(2, &material_file("name = \"s\"\nyoung_modulus = 1e3\npoisson_ratio = 0.3")));
        assert!(e.starts_with("materials[2].young_modulus = 1000: expected a number from 1e5 to 1e13"), "{e}");
        let e = err(material(0, &material_file("name = \"s\"\nyoung_modulus = 200e9\npoisson_ratio = 0.5")));
        assert!(e.contains("poisson_ratio = 0.5"), "{e}");
        // a yield strain above 10 %
        let e = err(material(
            0,
            &material_file(
                "name = \"s\"\nyoung_modulus = 1e9\npoisson_ratio = 0.3\nplasticity = { yield_stress = 2e8, hardening = \"perfect\" }",
            ),
        ));
        assert!(e.contains("plasticity.yield_stress = 2e8") && e.contains("0.1 E"), "{e}");
        // softening and unsorted tables
        let e = err(material(
            0,
            &material_file(
                "name = \"s\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\nplasticity = { hardening = \"table\", table = [[0.0, 1e8], [0.01, 9e7]] }",
            ),
        ));
        assert!(e.contains("table[1]") && e.contains("no softening"), "{e}");
        let table = material(
            0,
            &material_file("name = \"s\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\nplasticity = { hardening = \"table\", table = [[0.0, 1e8], [0.01, 1.2e8]] }"),
        )
        .unwrap();
        assert_eq!(table.hardening.unwrap().eval(0.005), (1.1e8, 2e9));
    }

    /// Hardening-table errors once printed Rust debug text
    /// (`table[2] = Exact([0.02, 310000000.0])`): every value must read as
    /// the model file writes it.
    #[test]
    fn table_errors_print_the_values_as_written() {
        let base = "name = \"s\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\nplasticity = { hardening = \"table\"";
        let cases = [
            (
                ", table = [[0.0, 2.5e8], [0.01, 3.2e8], [0.02, 3.1e8]] }",
                "plasticity.table[2] = [0.02, 3.1e8]: expected",
            ),
            (", table = [[0.01, 2.5e8], [0.02, 3.2e8]] }", "plasticity.table[0] = [0.01, 2.5e8]: expected"),
            (", table = [] }", "plasticity.table = []: expected"),
            (", table = [[0.0, -1e8]] }", "plasticity.table[0] = [0, -1e8]: expected"),
            (
                ", yield_stress = 2e8, table = [[0.0, 2.5e8], [0.02, 3.2e8]] }",
                "plasticity.yield_stress = 2e8: expected the table's first stress (2.5e8)",
            ),
        ];
        for (table, expect) in cases {
            let e = err(material(0, &material_file(&format!("{base}{table}"))));
            assert!(e.contains(expect) && !e.contains("Exact") && !e.contains("00000"), "{table}: {e}");
        }
    }

    #[test]
    fn voce_and_kinematic_hardening_are_checked() {
        let base = "name = \"s\"\nyoung_modulus = 200e9\npoisson_ratio = 0.3\n";
        let m = material(
            0,
            &material_file(&format!(
                "{base}plasticity = {{ yield_stress = 2e8, hardening = \"voce\", saturation_stress = 5e7, saturation_rate = 20.0, \
                 kinematic = [{{ modulus = 6e10, recall = 600.0 }}, {{ modulus = 5e9, recall = 0.0 }}] }}"
            )),
        )
        .unwrap();
        assert_eq!(
            m.kinematic,
            vec![BackStress { modulus: 6e10, recall: 600.0 }, BackStress { modulus: 5e9, recall: 0.0 }]
        );
        let (sy, h) = m.hardening.unwrap().eval(0.0);
        assert_eq!((sy, h), (2e8, 5e7 * 20.0));
        // a missing Voce parameter, a negative recall rate, too many
        // back-stresses: each names its key
        let cases = [
            ("hardening = \"voce\", saturation_stress = 5e7", "plasticity.saturation_rate = (missing)"),
            ("hardening = \"perfect\", kinematic = [{ modulus = 6e10, recall = -1.0 }]", "kinematic[0].recall = -1"),
            ("hardening = \"perfect\", kinematic = [{ modulus = 0.0, recall = 1.0 }]", "kinematic[0].modulus = 0"),
            (
                "hardening = \"perfect\", kinematic = [{ modulus = 1e9, recall = 1.0 }, { modulus = 1e9, recall = 1.0 }, \
                 { modulus = 1e9, recall = 1.0 }, { modulus = 1e9, recall = 1.0 }]",
                "at most 3 back-stresses",
            ),
        ];
        for (p, expect) in cases {
            let e = err(material(3, &material_file(&format!("{base}plasticity = {{ yield_stress = 2e8, {p} }}"))));
            assert!(e.contains(expect) && e.starts_with("materials[3].plasticity"), "{p}: {e}");
        }
        // a Voce key with another law is refused by the reader, which lists
        // the keys of the law given
        let text =
            format!("{base}plasticity = {{ yield_stress = 2e8, hardening = \"perfect\", saturation_rate = 5.0 }}");
        let e = toml::from_str::<MaterialFile>(&text).unwrap_err().to_string();
        assert!(
            e.contains("line 4")
                && e.contains("unknown field `saturation_rate`, expected `yield_stress` or `kinematic`"),
            "{e}"
        );
    }
}
