//! The materials of the CalculiX deck: `*MATERIAL` cards, the material axes
//! of oriented anisotropic materials (`*ORIENTATION`) and the bodies'
//! `*SOLID SECTION`s, one per (body, material).
//!
//! * Isotropic: `*ELASTIC` with E and ν (and `*PLASTIC`, [`super::deck`]).
//! * Anisotropic ([`cufem::materials::anisotropic`]): the stiffness in the
//!   material axes, `C_m`. When it is orthotropic (no coupling between
//!   normal and shear components nor among the shears, to 1e-12 of its
//!   largest entry) as `*ELASTIC, TYPE=ENGINEERING CONSTANTS` — `E1, E2,
//!   E3, ν12, ν13, ν23, G12, G13, G23` from the compliance `S = C_m⁻¹`
//!   (`E_i = 1/S_ii`, `ν_ij = −S_ij E_i`, `G_ij = 1/S_kk` of the shear
//!   rows), the inverse of how cufem built `C_m` from them; otherwise as
//!   `*ELASTIC, TYPE=ANISO` with the 21 constants `D1111, D1122, D2222,
//!   D1133, D2233, D3333, D1112, D2212, D3312, D1212, D1113, …, D2323`:
//!   the upper triangle of `C_m` column by column. CalculiX's stress is
//!   `σ_ij = D_ijkl ε_kl` with tensor strains; a shear column of cufem's
//!   Voigt matrix multiplies the engineering strain `γ_kl = ε_kl + ε_lk`,
//!   so `D_ijkl` is the Voigt entry itself, without factors of 2 (Voigt
//!   order 11, 22, 33, 12, 13, 23, [`cufem::voigt`]).
//! * Material axes: a material whose frame is not the global one gets
//!   `*ORIENTATION, SYSTEM=RECTANGULAR` with `a = e1`, `b = e2` (its axes in
//!   global coordinates; `e3 = e1 × e2` for cufem's right-handed frames),
//!   named on the `*SOLID SECTION` of its elements. CalculiX writes the
//!   stresses in the global axes (checked by crates/cufem-cli/tests/ccx_laminate.rs).
//! * Sections: a body of one material keeps the one section on its element
//!   set `B_<BODY>`; a body of several (plies, zones) gets an element set
//!   `BM_<BODY>_<k>` per material `k` (index into the model's materials,
//!   oriented copies included) holding the hexahedra of the CUF elements
//!   whose section element has that material.
//!
//! Deck names are the material names made CalculiX-safe
//! ([`super::names::set_name`]); an oriented copy's name (`ply@30`, or with
//! its vectors) stays readable, cut to CalculiX's 80 characters and made
//! unique by the material's index where needed.

use std::fmt::Write as _;

use super::mesh::HexMesh;
use super::names::{list, set_name};
use cufem::materials::{Frame, Material};
use cufem::setup::Model;
use cufem::voigt::Matrix6;

/// Longest name written (CalculiX allows 80; `O` is prefixed to a material
/// name for its orientation).
const MAX_NAME: usize = 78;

/// The deck name of each material of the model (`M_<NAME>`), unique.
pub fn material_names(model: &Model) -> Vec<String> {
    unique_names(model.materials.iter().map(|m| m.name.as_str()))
}

/// `M_<NAME>` of each name, cut to [`MAX_NAME`] and made unique by the
/// name's index where needed.
fn unique_names<'a>(names: impl Iterator<Item = &'a str>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for (k, n) in names.enumerate() {
        let mut name = set_name("M", n);
        if name.len() > MAX_NAME {
            name.truncate(MAX_NAME - 8);
            let _ = write!(name, "_{k}");
        }
        while out.contains(&name) {
            let _ = write!(name, "_{k}");
        }
        out.push(name);
    }
    out
}

/// The orientation of material `m` named `O<deck name>`, `None` when its
/// stiffness needs none (isotropic, or in the global axes).
fn orientation(m: &Material, deck_name: &str) -> Option<String> {
    (m.anisotropic.is_some() && m.frame != Frame::default()).then(|| format!("O{deck_name}"))
}

/// `E1, E2, E3, ν12, ν13, ν23, G12, G13, G23` of an orthotropic stiffness
/// (material axes), `None` if it couples normal and shear components or
/// the shears among themselves.
pub fn engineering_constants(c: &Matrix6) -> Option<[f64; 9]> {
    let big = c.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let coupled = (0..6).any(|i| (3..6).any(|j| i != j && c[i][j].abs() > 1e-12 * big));
    if coupled {
        return None;
    }
    let s = cufem::materials::anisotropic::invert(c)?;
    let e = [1.0 / s[0][0], 1.0 / s[1][1], 1.0 / s[2][2]];
    let nu = [-s[0][1] * e[0], -s[0][2] * e[0], -s[1][2] * e[1]];
    Some([e[0], e[1], e[2], nu[0], nu[1], nu[2], 1.0 / s[3][3], 1.0 / s[4][4], 1.0 / s[5][5]])
}

/// The 21 `*ELASTIC, TYPE=ANISO` constants of a stiffness (material axes):
/// the upper triangle column by column (`D1111; D1122, D2222; D1133, …`).
pub fn aniso_constants(c: &Matrix6) -> [f64; 21] {
    let mut d = [0.0; 21];
    let mut k = 0;
    for j in 0..6 {
        for row in c.iter().take(j + 1) {
            d[k] = row[j];
            k += 1;
        }
    }
    d
}

/// Data lines of at most eight values each (CalculiX's `*ELASTIC` layout).
fn rows(values: &[f64]) -> String {
    let v: Vec<String> = values.iter().map(|x| format!("{x:.12e}")).collect();
    v.chunks(8).map(|c| c.join(", ")).collect::<Vec<_>>().join("\n")
}

/// The `*ELASTIC` card of a material (with its data lines).
pub fn elastic(m: &Material) -> String {
    match &m.anisotropic {
        None => format!("*ELASTIC\n{:e}, {}", m.young, m.poisson),
        Some(c) => match engineering_constants(c) {
            Some(k) => format!("*ELASTIC, TYPE=ENGINEERING CONSTANTS\n{}", rows(&k)),
            None => format!("*ELASTIC, TYPE=ANISO\n{}", rows(&aniso_constants(c))),
        },
    }
}

/// `*ORIENTATION`s of the oriented anisotropic materials the bodies use.
pub(super) fn orientations(d: &mut String, model: &Model) {
    let names = material_names(model);
    for k in used(model) {
        let m = &model.materials[k];
        if let Some(name) = orientation(m, &names[k]) {
            let [a, b, _] = m.frame.axes;
            let _ = writeln!(d, "*ORIENTATION, NAME={name}, SYSTEM=RECTANGULAR");
            let _ = writeln!(d, "{}", rows(&[a[0], a[1], a[2], b[0], b[1], b[2]]));
        }
    }
}

/// Every material some body uses, in increasing order.
fn used(model: &Model) -> Vec<usize> {
    let mut all: Vec<usize> = model.mesh.bodies.iter().flat_map(|b| b.materials()).collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// The hexahedra of body `b` per material: `(material, elements)`.
pub fn body_element_sets(model: &Model, mesh: &HexMesh, b: usize) -> Vec<(usize, Vec<usize>)> {
    let body = &model.mesh.bodies[b];
    let bh = &mesh.bodies[b];
    let per: usize = bh.sub.iter().product();
    body.materials()
        .into_iter()
        .map(|m| {
            let hexes = (0..body.n_elements())
                .filter(|&e| body.material_of(body.split_element(e).0) == m)
                .flat_map(|e| bh.first_element + e * per..bh.first_element + (e + 1) * per)
                .collect();
            (m, hexes)
        })
        .collect()
}

/// The bodies' `*SOLID SECTION`s (after the orientations they name): one
/// on `B_<BODY>` for a body of one material, else one per material on its
/// element set `BM_<BODY>_<k>`.
pub(super) fn sections(d: &mut String, model: &Model, mesh: &HexMesh) {
    let names = material_names(model);
    let section = |d: &mut String, elset: &str, k: usize| {
        let m = &model.materials[k];
        let _ = write!(d, "*SOLID SECTION, ELSET={elset}, MATERIAL={}", names[k]);
        match orientation(m, &names[k]) {
            Some(o) => {
                let _ = writeln!(d, ", ORIENTATION={o}");
            }
            None => d.push('\n'),
        }
    };
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let materials = body.materials();
        if let [k] = materials[..] {
            section(d, &set_name("B", &body.name), k);
            continue;
        }
        for (k, hexes) in body_element_sets(model, mesh, b) {
            let elset = format!("{}_{k}", set_name("BM", &body.name));
            let _ = writeln!(d, "*ELSET, ELSET={elset}\n{}", list(hexes.into_iter()));
            section(d, &elset, k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cufem::materials::Orthotropic;

    fn ply() -> Orthotropic {
        Orthotropic { young: [140e9, 10e9, 9e9], shear: [5e9, 4.5e9, 3.5e9], poisson: [0.3, 0.28, 0.45] }
    }

    #[test]
    fn engineering_constants_invert_the_orthotropic_stiffness() {
        let p = ply();
        let k = engineering_constants(&p.stiffness().unwrap()).unwrap();
        let given = [p.young, p.poisson, p.shear].concat();
        for (a, b) in k.iter().zip(&given) {
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{k:?} against {given:?}");
        }
    }

    #[test]
    fn a_coupled_stiffness_is_written_as_aniso_in_ccx_order() {
        // the ply turned by 30° about z in its own axes: normal–shear coupling
        let c = Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 30f64.to_radians())
            .unwrap()
            .stiffness_to_global(&ply().stiffness().unwrap());
        assert!(engineering_constants(&c).is_none());
        let m = Material::anisotropic("p", c);
        let text = elastic(&m);
        assert!(text.starts_with("*ELASTIC, TYPE=ANISO\n"), "{text}");
        let values: Vec<f64> = text.lines().skip(1).flat_map(|l| l.split(", ")).map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), 21);
        assert_eq!(text.lines().skip(1).map(|l| l.split(", ").count()).collect::<Vec<_>>(), [8, 8, 5]);
        // D1112 = C_xx,xy (7th), D1212 (10th), D1323 (20th)
        for (i, (r, s)) in [(6, (0, 3)), (9, (3, 3)), (19, (4, 5)), (20, (5, 5))] {
            assert!((values[i] - c[r][s]).abs() <= 1e-11 * c[r][s].abs().max(1e6), "{i}");
        }
    }

    #[test]
    fn names_are_unique_and_short() {
        let long = "x".repeat(100);
        let names = unique_names(["steel", "Steel", &long, "ply@30"].into_iter());
        assert_eq!(names[..2], ["M_STEEL".to_string(), "M_STEEL_1".to_string()]);
        assert!(names[2].len() <= MAX_NAME && names[2].ends_with("_2"), "{}", names[2]);
        assert_eq!(names[3], "M_PLY_30");
    }
}
