//! `shape = "laminate"`: a stack of plies over a rectangle, bottom first
//! from `z0`, each ply `elements` section elements thick (layer-wise: every
//! ply has its own elements, so the displacement field is continuous and
//! its gradient free to jump at the interfaces). Each ply is the section
//! region `ply1`, `ply2`, … and gets its material turned by its angle about
//! z from the beam axis (applied by `zones`).

use crate::input::schema::{LaminateFile, PlyFile};
use crate::input::validate::{MAX_COUNT, division};
use crate::input::{ModelError, bounds, invalid, ranges};
use crate::mesh::{CrossSection, Region};
use crate::shape::SectionElementKind;

/// The section region of ply `k` (0-based): `ply{k+1}`.
pub(super) fn region_name(k: usize) -> String {
    format!("ply{}", k + 1)
}

/// The ply (0-based) whose region is `name` ([`region_name`]'s inverse).
pub(super) fn ply_of_region(name: &str) -> Option<usize> {
    name.strip_prefix("ply")?.parse::<usize>().ok()?.checked_sub(1)
}

/// The plies of `s` (key `sk`), checked: at least one, positive thickness,
/// 1..=MAX_COUNT elements, a finite angle.
fn plies<'a>(sk: &str, s: &'a LaminateFile) -> Result<&'a [PlyFile], ModelError> {
    let plies = s.plies.as_deref().ok_or_else(|| invalid(format!("{sk}.plies"), "(missing)", PLIES))?;
    check(sk, plies)?;
    Ok(plies)
}

/// What `plies` takes.
const PLIES: &str = "a list of at least one ply, bottom first: [{thickness = …, material = \"…\", angle = 0, \
                     elements = 1}, …]";

/// Checks a list of plies (key `sk`.plies): at least one, positive
/// thickness, 1..=MAX_COUNT elements, a finite angle.
pub(super) fn check(sk: &str, plies: &[PlyFile]) -> Result<(), ModelError> {
    if plies.is_empty() {
        return Err(invalid(format!("{sk}.plies"), "[] (an empty list: no ply)", PLIES));
    }
    for (k, p) in plies.iter().enumerate() {
        let pk = format!("{sk}.plies[{k}]");
        ranges::LENGTH.check(&format!("{pk}.thickness"), p.thickness, "the ply thickness in m, positive")?;
        let n = p.elements.unwrap_or(crate::input::defaults::THROUGH);
        if !(1..=MAX_COUNT).contains(&n) {
            return Err(invalid(format!("{pk}.elements"), n, format!("an integer in 1..={MAX_COUNT}")));
        }
        let stack: f64 = plies.iter().map(|q| q.thickness).sum();
        if p.thickness / (n as f64) < bounds::MIN_PLY_SHARE * stack {
            return Err(invalid(
                format!("{pk}.thickness"),
                crate::numbers::number(p.thickness),
                format!(
                    "at least {} m with {n} element(s): each element at least {:e} of the stack's {} m (thinner, \
                     the ply's stiffness through its thickness swamps its neighbours' and the solves lose the digits \
                     Newton needs)",
                    crate::numbers::limit(bounds::MIN_PLY_SHARE * stack * n as f64),
                    bounds::MIN_PLY_SHARE,
                    crate::numbers::limit(stack)
                ),
            ));
        }
        if let Some(a) = p.angle
            && !ranges::ANGLE.contains(a)
        {
            return Err(invalid(format!("{pk}.angle"), a, format!("an angle in degrees {}", ranges::ANGLE)));
        }
    }
    Ok(())
}

/// The z lines of the stack (element boundaries) and each ply's element
/// rows `(first, count)`.
fn z_lines(z0: f64, plies: &[PlyFile]) -> (Vec<f64>, Vec<(usize, usize)>) {
    let mut lines = vec![z0];
    let mut rows = Vec::new();
    let mut bottom = z0;
    for p in plies {
        let n = p.elements.unwrap_or(crate::input::defaults::THROUGH);
        rows.push((lines.len() - 1, n));
        for k in 1..=n {
            lines.push(if k == n { bottom + p.thickness } else { bottom + p.thickness * k as f64 / n as f64 });
        }
        bottom += p.thickness;
    }
    (lines, rows)
}

/// A cohesive interface a laminate asks for.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Request {
    /// The key of its entry (`….interfaces[j]`, or `….interfaces`).
    pub key: String,
    /// The ply below it (0-based).
    pub ply: usize,
    /// Its material, `None` for `interface_material`.
    pub material: Option<String>,
    /// Its precrack `[from, to]` along y (m).
    pub crack: Option<[f64; 2]>,
}

/// The cohesive interfaces of `s` (key `sk`) with `n` plies, checked: each
/// above a ply below the top one, once; a crack with `from < to`.
pub(super) fn requests(sk: &str, s: &LaminateFile, n: usize) -> Result<Vec<Request>, ModelError> {
    use crate::input::schema::{InterfaceKind, InterfacesFile};
    let key = format!("{sk}.interfaces");
    let out: Vec<Request> = match &s.interfaces {
        None | Some(InterfacesFile::Every(InterfaceKind::Perfect)) => {
            if s.interface_material.is_some() {
                return Err(invalid(
                    format!("{sk}.interface_material"),
                    "given with perfect interfaces",
                    format!("only with {key} = \"cohesive\" or a list"),
                ));
            }
            Vec::new()
        }
        Some(InterfacesFile::Every(InterfaceKind::Cohesive)) => {
            if n < 2 {
                // accepted in silence before (a new-user review)
                return Err(invalid(
                    key,
                    "\"cohesive\"",
                    "\"perfect\" with a single ply: a laminate of one ply has no interface",
                ));
            }
            (0..n - 1).map(|ply| Request { key: key.clone(), ply, material: None, crack: None }).collect()
        }
        Some(InterfacesFile::Listed(list)) => {
            let mut out: Vec<Request> = Vec::new();
            for (j, f) in list.iter().enumerate() {
                let ik = format!("{key}[{j}]");
                if !(1..n).contains(&f.ply) {
                    let allowed = if n > 1 {
                        format!("a ply below the top one, 1..={} (the interface above it)", n - 1)
                    } else {
                        "no interface: the laminate has one ply".to_string()
                    };
                    return Err(invalid(format!("{ik}.ply"), f.ply, allowed));
                }
                if let Some(o) = out.iter().find(|r| r.ply == f.ply - 1) {
                    return Err(invalid(
                        format!("{ik}.ply"),
                        f.ply,
                        format!("an interface not listed before ({})", o.key),
                    ));
                }
                let crack = match f.crack {
                    None => None,
                    Some(c) => {
                        let from = ranges::COORDINATE.check(&format!("{ik}.crack.from"), c.from, "y in m")?;
                        if !(c.to.is_finite() && c.to > from) {
                            return Err(invalid(
                                format!("{ik}.crack.to"),
                                c.to,
                                format!("a y in m above from ({from})"),
                            ));
                        }
                        Some([from, c.to])
                    }
                };
                out.push(Request { key: ik, ply: f.ply - 1, material: f.material.clone(), crack });
            }
            out
        }
    };
    if out.iter().any(|r| r.material.is_none()) && s.interface_material.is_none() {
        return Err(invalid(
            format!("{sk}.interface_material"),
            "(missing)",
            format!("the name of a material with cohesive = {{…}}, for the interfaces of {key} that name none"),
        ));
    }
    Ok(out)
}

/// The section of `shape = "laminate"`, with one region per ply.
pub(super) fn section(sk: &str, kind: SectionElementKind, s: &LaminateFile) -> Result<CrossSection, ModelError> {
    let x = s.x.as_ref().ok_or_else(|| {
        invalid(
            format!("{sk}.x"),
            "(missing)",
            "a division of the width along x, e.g. {from = 0.0, to = 0.01, elements = 2}",
        )
    })?;
    let xl = division(&format!("{sk}.x"), x)?;
    let z0 = bounds::within(
        &format!("{sk}.z0"),
        s.z0.unwrap_or(crate::input::defaults::Z0),
        -bounds::MAX_COORD,
        bounds::MAX_COORD,
        "the bottom of the stack in m",
    )?;
    let plies = plies(sk, s)?;
    let (zl, rows) = z_lines(z0, plies);
    let mut split = vec![false; plies.len() - 1];
    for r in requests(sk, s, plies.len())? {
        split[r.ply] = true;
    }
    let ply_lines: Vec<Vec<f64>> = rows.iter().map(|&(first, n)| zl[first..=first + n].to_vec()).collect();
    let mut section = CrossSection::stack(kind, &xl, &ply_lines, &split).map_err(|e| match e {
        crate::mesh::MeshError::Invalid { value, allowed, .. } => invalid(format!("{sk}.plies"), value, allowed),
    })?;
    let nx = xl.len() - 1;
    section.regions = rows
        .iter()
        .enumerate()
        .map(|(k, &(first, n))| Region {
            name: region_name(k),
            elements: (first * nx..(first + n) * nx).collect(),
            normal: None,
        })
        .collect();
    Ok(section)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plies_stack_from_z0_with_their_rows() {
        let ply = |t: f64, n: usize| PlyFile { thickness: t, material: "m".into(), angle: None, elements: Some(n) };
        let (lines, rows) = z_lines(-0.5, &[ply(0.25, 1), ply(0.5, 2), ply(0.25, 1)]);
        let expect = [-0.5, -0.25, 0.0, 0.25, 0.5];
        assert_eq!(lines.len(), expect.len());
        for (a, b) in lines.iter().zip(expect) {
            assert!((a - b).abs() < 1e-15);
        }
        assert_eq!(rows, vec![(0, 1), (1, 2), (3, 1)]);
    }
}
