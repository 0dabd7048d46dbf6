//! Parametric profiles: the thin-walled sections of real structures (I/H,
//! channel, Z, angle, hat, rectangular tubes with one or several cells,
//! circular tubes, solid circles) as lists of mapped [`Block`]s.
//!
//! Straight-walled profiles are unions of axis-aligned rectangles on a grid:
//! a wall's junction with another wall is its own block of `through ×
//! through` elements, so every wall is meshed conformingly with its
//! neighbours. Curved profiles are mapped exactly: a circular tube is the
//! polar map `(r, θ)` of a rectangle; a solid circle is an O-grid (a
//! central square and four blocks blending its sides into quarter arcs).
//!
//! Keys in errors are relative to `section` (the model layer prefixes the
//! body's path).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use super::MeshError;
use super::blocks::Block;

/// Dimensions of a straight-walled profile (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Walls {
    /// Overall width along x (see each family for what it spans).
    pub width: f64,
    /// Overall height along z.
    pub height: f64,
    /// Thickness of the vertical walls (webs), along x.
    pub web: f64,
    /// Thickness of the horizontal walls (flanges, lips), along z.
    pub flange: f64,
    /// Width of a hat's lips (brims), along x.
    pub lip: f64,
    /// Cells of a box (webs = cells + 1).
    pub cells: usize,
}

/// Element counts of a straight-walled profile.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Counts {
    /// Along each flange part between webs (an outstand, or a box cell's flange).
    pub flange: usize,
    /// Along each web between the flanges.
    pub web: usize,
    /// Along each lip of a hat.
    pub lip: usize,
    /// Through each wall thickness (with `plies`: their sum).
    pub through: usize,
    /// Plies through every wall, first at the wall's lower x (webs) or
    /// lower z (flanges): (share of the wall thickness, elements); empty for
    /// a homogeneous wall. Ply `k`'s elements form the region
    /// `<wall>_ply<k+1>` with the wall's normal.
    pub plies: Vec<(f64, usize)>,
    /// Length (m) of one more element at each end of a wall that meets
    /// another wall, next to the junction, where a thin wall's
    /// transverse-shear boundary layer sits; `None`: the wall's elements
    /// are equal.
    pub junction: Option<f64>,
}

/// The families of straight-walled profiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Family {
    /// I or H: two flanges of `width`, a central web; `height` overall.
    I,
    /// Channel (U): a web at x = x0, flanges of `width` (web included) towards +x.
    Channel,
    /// Z: bottom flange towards +x, top flange towards −x, each `width` wide (web included).
    Z,
    /// Angle (L): a vertical leg of `height` (thickness `web`) and a horizontal leg of `width` (thickness `flange`).
    Angle,
    /// Hat (top-hat): a top flange of `width` on two webs, lips of `lip` outwards at the bottom.
    Hat,
    /// Rectangular tube with `cells` cells side by side (cells + 1 equally spaced webs).
    Box,
}

/// Smallest wall thickness relative to the profile's size: thinner walls
/// would fall below the node-merging tolerance of [`super::blocks`].
pub(crate) const MIN_RELATIVE_THICKNESS: f64 = 1e-6;

/// Most cells of a `box` section side by side (the model file's range of
/// `cells` reads it).
pub(crate) const MAX_CELLS: usize = 1000;

fn thick_enough(key: &str, t: f64, size: f64) -> Result<(), MeshError> {
    if t >= MIN_RELATIVE_THICKNESS * size {
        Ok(())
    } else {
        Err(MeshError::invalid(
            key,
            t.to_string(),
            format!("at least {MIN_RELATIVE_THICKNESS:e} of the profile's size ({size} m)"),
        ))
    }
}

fn positive(key: &str, v: f64, allowed: &str) -> Result<f64, MeshError> {
    if v.is_finite() && v > 0.0 { Ok(v) } else { Err(MeshError::invalid(key, v.to_string(), allowed)) }
}

/// A clear length between walls that must stay positive.
fn clear(key: &str, value: f64, clear: f64, what: &str) -> Result<f64, MeshError> {
    if clear > 1e-9 * value.abs().max(clear.abs()) {
        Ok(clear)
    } else {
        Err(MeshError::invalid(key, value.to_string(), what))
    }
}

/// One column or row of a profile's grid: its length, its elements, and
/// whether it is a wall's thickness (split into the plies, if any).
type Part = (f64, usize, bool);

/// The sub-parts of a part: the plies of a wall's thickness, or itself.
fn split(part: Part, plies: &[(f64, usize)]) -> Vec<(f64, usize)> {
    if part.2 && !plies.is_empty() {
        plies.iter().map(|&(share, n)| (share * part.0, n)).collect()
    } else {
        vec![(part.0, part.1)]
    }
}

/// Whether a length part of a grid meets a wall at its lower and upper
/// ends: the neighbouring part is a thickness and some filled cell of this
/// part has a filled neighbour across that end. `filled(a, b)` says whether
/// the cell at part `a` (this direction) and `b` (the other) is filled.
fn junction_ends(parts: &[Part], i: usize, others: usize, filled: impl Fn(usize, usize) -> bool) -> [bool; 2] {
    let meets = |k: Option<usize>| {
        k.filter(|&k| k < parts.len() && parts[k].2).is_some_and(|k| (0..others).any(|b| filled(i, b) && filled(k, b)))
    };
    if parts[i].2 { [false, false] } else { [meets(i.checked_sub(1)), meets(Some(i + 1))] }
}

/// Element boundaries of a part of `len` from `start`: `n` equal elements,
/// with one more of `layer` at each end in `ends` (a junction). `None` if
/// the layer would not be shorter than the part's other elements.
fn stations(start: f64, len: f64, n: usize, ends: [bool; 2], layer: Option<f64>) -> Option<Vec<f64>> {
    let (a, ends) = match layer {
        Some(a) => (a, ends),
        None => (0.0, [false, false]),
    };
    let layers = ends.iter().filter(|&&e| e).count();
    let h = (len - layers as f64 * a) / n as f64;
    if layers > 0 && a >= h {
        return None;
    }
    let first = if ends[0] { start + a } else { start };
    let mut s = if ends[0] { vec![start] } else { Vec::new() };
    s.extend((0..=n).map(|k| first + k as f64 * h));
    if ends[1] {
        s.push(start + len);
    }
    Some(s)
}

/// The point at `u` in [0, 1] of the piecewise-linear map through the
/// element boundaries `b` (element `k` spans `u` in `[k, k + 1] / (b.len() − 1)`).
fn piecewise(b: &[f64], u: f64) -> f64 {
    let n = b.len() - 1;
    let t = u * n as f64;
    let k = (t.floor() as usize).min(n - 1);
    b[k] + (t - k as f64) * (b[k + 1] - b[k])
}

/// Blocks of a grid whose columns are `xs` from `x0`, rows `zs` from `z0`;
/// `cells` lists the filled `(column, row, region)`. With `plies`, each
/// wall thickness is split into its plies: a cell on a thickness row
/// (flanges, and the junctions, which belong to them) is layered along z,
/// a cell on a thickness column only (webs) along x. With `junction`, a
/// wall's length gets one more element of that length at each end that
/// meets another wall.
fn grid(
    origin: [f64; 2],
    xs: &[Part],
    zs: &[Part],
    cells: &[(usize, usize, &str)],
    n: &Counts,
) -> Result<Vec<Block>, MeshError> {
    let plies = &n.plies[..];
    let lines = |start: f64, parts: &[Part]| {
        let mut l = vec![start];
        for (len, _, _) in parts {
            l.push(l.last().unwrap() + len);
        }
        l
    };
    let (xl, zl) = (lines(origin[0], xs), lines(origin[1], zs));
    let filled = |i: usize, j: usize| cells.iter().any(|&(a, b, _)| a == i && b == j);
    let mut blocks = Vec::new();
    for &(i, j, region) in cells {
        let (cols, rows) = (split(xs[i], plies), split(zs[j], plies));
        let along_z = zs[j].2;
        let ends_x = junction_ends(xs, i, zs.len(), filled);
        let ends_z = junction_ends(zs, j, xs.len(), |b, a| filled(a, b));
        let mut z0 = zl[j];
        for (b, &(hz, nz)) in rows.iter().enumerate() {
            let mut x0 = xl[i];
            for (a, &(hx, nx)) in cols.iter().enumerate() {
                let too_long = |len: f64, count: usize| {
                    MeshError::invalid(
                        "section.junction_element",
                        n.junction.unwrap_or_default().to_string(),
                        format!(
                            "a length shorter than the other elements of each wall it grades (the {region}: {count} elements over {len} m)"
                        ),
                    )
                };
                let bx = stations(x0, hx, nx, ends_x, n.junction).ok_or_else(|| too_long(hx, nx))?;
                let bz = stations(z0, hz, nz, ends_z, n.junction).ok_or_else(|| too_long(hz, nz))?;
                let mut block = if bx.len() == nx + 1 && bz.len() == nz + 1 {
                    Block::rectangle([x0, x0 + hx], [z0, z0 + hz], nx, nz, region)
                } else {
                    let counts = [bx.len() - 1, bz.len() - 1];
                    Block {
                        counts,
                        map: Box::new(move |u, v| [piecewise(&bx, u), piecewise(&bz, v)]),
                        region: region.to_string(),
                        normal: None,
                    }
                };
                if !plies.is_empty() && (along_z || xs[i].2) {
                    let (k, normal) = if along_z { (b, [0.0, 1.0]) } else { (a, [1.0, 0.0]) };
                    block.region = format!("{region}_ply{}", k + 1);
                    block.normal = Some(normal);
                }
                blocks.push(block);
                x0 += hx;
            }
            z0 += hz;
        }
    }
    Ok(blocks)
}

/// The count key of the model file that sets how many elements a wall of
/// region `region` has along its length (`along_flange`, `along_web`,
/// `along_lip`; a ply's region `<wall>_ply<k>` is its wall's), for local
/// refinement by `crate::adapt`; `None` for a name no straight-walled
/// profile gives. A junction of two walls belongs to a flange (leg_x) and
/// has only `through` elements: doubling that flange's count leaves it.
pub(crate) fn along_key(region: &str) -> Option<&'static str> {
    let wall = match region.rfind("_ply") {
        Some(i) if region[i + 4..].bytes().all(|b| b.is_ascii_digit()) && i + 4 < region.len() => &region[..i],
        _ => region,
    };
    match wall {
        "bottom_flange" | "top_flange" | "leg_x" => Some("along_flange"),
        "web" | "webs" | "leg_z" => Some("along_web"),
        "lips" => Some("along_lip"),
        _ => None,
    }
}

/// The blocks of a straight-walled profile with its bottom-left bounding-box
/// corner at `origin`.
pub fn straight(family: Family, origin: [f64; 2], d: &Walls, n: &Counts) -> Result<Vec<Block>, MeshError> {
    let width = positive("section.width", d.width, "a positive width in m")?;
    let height = positive("section.height", d.height, "a positive height in m")?;
    let tw = positive("section.web_thickness", d.web, "a positive web thickness in m")?;
    let tf = positive("section.flange_thickness", d.flange, "a positive flange thickness in m")?;
    for (key, v) in [("section.web_thickness", tw), ("section.flange_thickness", tf)] {
        thick_enough(key, v, width.max(height))?;
    }
    let t = n.through;
    let web_clear = |flanges: f64| {
        clear(
            "section.flange_thickness",
            tf,
            height - flanges * tf,
            &format!("less than 1/{flanges} of the height ({height} m): the web needs a positive clear height"),
        )
    };
    let flange_clear = |webs: f64, extra: f64| {
        clear(
            "section.web_thickness",
            tw,
            width - webs * tw - extra,
            &format!("a web thickness leaving the flanges a positive clear width (width {width} m)"),
        )
    };
    let (bf, bw, bt) = ("bottom_flange", "web", "top_flange");
    Ok(match family {
        Family::I => {
            let out = flange_clear(1.0, 0.0)? / 2.0;
            let h = web_clear(2.0)?;
            let xs = [(out, n.flange, false), (tw, t, true), (out, n.flange, false)];
            let zs = [(tf, t, true), (h, n.web, false), (tf, t, true)];
            let cells = [(0, 0, bf), (1, 0, bf), (2, 0, bf), (1, 1, bw), (0, 2, bt), (1, 2, bt), (2, 2, bt)];
            grid(origin, &xs, &zs, &cells, n)?
        }
        Family::Channel => {
            let out = flange_clear(1.0, 0.0)?;
            let h = web_clear(2.0)?;
            let xs = [(tw, t, true), (out, n.flange, false)];
            let zs = [(tf, t, true), (h, n.web, false), (tf, t, true)];
            grid(origin, &xs, &zs, &[(0, 0, bf), (1, 0, bf), (0, 1, bw), (0, 2, bt), (1, 2, bt)], n)?
        }
        Family::Z => {
            let out = flange_clear(1.0, 0.0)?;
            let h = web_clear(2.0)?;
            let xs = [(out, n.flange, false), (tw, t, true), (out, n.flange, false)];
            let zs = [(tf, t, true), (h, n.web, false), (tf, t, true)];
            grid(origin, &xs, &zs, &[(1, 0, bf), (2, 0, bf), (1, 1, bw), (0, 2, bt), (1, 2, bt)], n)?
        }
        Family::Angle => {
            let out = flange_clear(1.0, 0.0)?;
            let h = web_clear(1.0)?;
            let xs = [(tw, t, true), (out, n.flange, false)];
            let zs = [(tf, t, true), (h, n.web, false)];
            grid(origin, &xs, &zs, &[(0, 0, "leg_x"), (1, 0, "leg_x"), (0, 1, "leg_z")], n)?
        }
        Family::Hat => {
            let lip = positive("section.lip", d.lip, "a positive lip width in m")?;
            let top = flange_clear(2.0, 0.0)?;
            let h = web_clear(2.0)?;
            let xs = [(lip, n.lip, false), (tw, t, true), (top, n.flange, false), (tw, t, true), (lip, n.lip, false)];
            let zs = [(tf, t, true), (h, n.web, false), (tf, t, true)];
            let cells = [
                (0, 0, "lips"),
                (1, 0, "lips"),
                (3, 0, "lips"),
                (4, 0, "lips"),
                (1, 1, "webs"),
                (3, 1, "webs"),
                (1, 2, bt),
                (2, 2, bt),
                (3, 2, bt),
            ];
            grid(origin, &xs, &zs, &cells, n)?
        }
        Family::Box => {
            let cells = d.cells;
            if !(1..=MAX_CELLS).contains(&cells) {
                return Err(MeshError::invalid(
                    "section.cells",
                    cells.to_string(),
                    format!("1 to {MAX_CELLS} cells side by side"),
                ));
            }
            let cell = flange_clear(cells as f64 + 1.0, 0.0)? / cells as f64;
            let h = web_clear(2.0)?;
            let mut xs = vec![(tw, t, true)];
            for _ in 0..cells {
                xs.extend([(cell, n.flange, false), (tw, t, true)]);
            }
            let zs = [(tf, t, true), (h, n.web, false), (tf, t, true)];
            let mut filled = Vec::new();
            for i in 0..xs.len() {
                filled.extend([(i, 0, bf), (i, 2, bt)]);
                if i % 2 == 0 {
                    filled.push((i, 1, "webs"));
                }
            }
            grid(origin, &xs, &zs, &filled, n)?
        }
    })
}

/// A circular tube about `center`: outer `radius`, wall `thickness`,
/// `around` elements around and `through` through the wall, every node on
/// its circle (polar map; ξ radial, η counter-clockwise from +x).
pub fn circular_tube(
    center: [f64; 2],
    radius: f64,
    thickness: f64,
    around: usize,
    through: usize,
) -> Result<Vec<Block>, MeshError> {
    let ro = positive("section.radius", radius, "a positive outer radius in m")?;
    let t = positive("section.thickness", thickness, "a positive wall thickness in m")?;
    if t >= ro {
        return Err(MeshError::invalid(
            "section.thickness",
            t.to_string(),
            format!("less than the outer radius ({ro} m)"),
        ));
    }
    if around < 3 {
        return Err(MeshError::invalid("section.around", around.to_string(), "at least 3 elements around the tube"));
    }
    thick_enough("section.thickness", t, ro)?;
    let ri = ro - t;
    Ok(vec![Block {
        counts: [through, around],
        map: Box::new(move |u, v| {
            let (r, th) = (ri + u * (ro - ri), TAU * v);
            [center[0] + r * th.cos(), center[1] + r * th.sin()]
        }),
        region: "wall".into(),
        normal: None,
    }])
}

/// Half-width of the O-grid's central square relative to the radius.
pub(crate) const OGRID_SQUARE: f64 = 0.5;

/// A solid circle about `center`: an O-grid of a central square
/// (`around/4 × around/4` elements, half-width `OGRID_SQUARE` · radius)
/// and four blocks of `around/4 × through` elements blending its sides
/// linearly into quarter arcs (transfinite: their other sides are straight
/// radial segments). Every node of the outer edge lies on the circle.
pub fn circle(center: [f64; 2], radius: f64, around: usize, through: usize) -> Result<Vec<Block>, MeshError> {
    let r = positive("section.radius", radius, "a positive radius in m")?;
    if around < 4 || !around.is_multiple_of(4) {
        return Err(MeshError::invalid(
            "section.around",
            around.to_string(),
            "a multiple of 4 (elements around the circle; around/4 per side of the central square)",
        ));
    }
    let n = around / 4;
    let a = OGRID_SQUARE * r;
    let mut blocks = vec![Block {
        counts: [n, n],
        map: Box::new(move |u, v| [center[0] - a + 2.0 * a * u, center[1] - a + 2.0 * a * v]),
        region: "core".into(),
        normal: None,
    }];
    for k in 0..4 {
        let rot = k as f64 * FRAC_PI_2;
        let (c, s) = (rot.cos(), rot.sin());
        blocks.push(Block {
            counts: [through, n],
            map: Box::new(move |u, v| {
                // the block on the +x side, rotated by k quarter turns
                let inner = [a, a * (2.0 * v - 1.0)];
                let phi = -FRAC_PI_4 + v * FRAC_PI_2;
                let outer = [r * phi.cos(), r * phi.sin()];
                let p = [(1.0 - u) * inner[0] + u * outer[0], (1.0 - u) * inner[1] + u * outer[1]];
                [center[0] + c * p[0] - s * p[1], center[1] + s * p[0] + c * p[1]]
            }),
            region: "rim".into(),
            normal: None,
        });
    }
    Ok(blocks)
}

/// The elements of a straight-walled profile's section next to a junction
/// of two walls (sharing a node with it, not in it), the smallest side of
/// a junction's elements and the shortest length along its wall of an
/// element next to a junction (m; `None` without junctions). A junction's
/// elements lie in a flange's or lip's region ([`along_key`] other than
/// `along_web`) over the x-interval of a web element: the cell where a
/// web's column crosses a flange's row. For a section of another shape
/// (no such regions) none.
pub(crate) fn next_to_junctions(section: &super::CrossSection) -> (Vec<bool>, Option<(f64, f64)>) {
    let n = section.n_elements();
    let mut key = vec![None; n];
    for r in &section.regions {
        for &e in &r.elements {
            if let Some(k) = key.get_mut(e).filter(|k| k.is_none()) {
                *k = along_key(&r.name);
            }
        }
    }
    let bbox: Vec<[f64; 4]> = (0..n)
        .map(|e| {
            section.element(e).iter().fold([f64::MAX, f64::MIN, f64::MAX, f64::MIN], |b, &p| {
                let [x, z] = section.nodes[p];
                [b[0].min(x), b[1].max(x), b[2].min(z), b[3].max(z)]
            })
        })
        .collect();
    let [x0, x1, z0, z1] = section.bounds();
    let tol = 1e-9 * (x1 - x0).max(z1 - z0);
    let webs: Vec<[f64; 2]> =
        (0..n).filter(|&e| key[e] == Some("along_web")).map(|e| [bbox[e][0], bbox[e][1]]).collect();
    let junction: Vec<bool> = (0..n)
        .map(|e| {
            key[e].is_some_and(|k| k != "along_web")
                && webs.iter().any(|w| (w[0] - bbox[e][0]).abs() <= tol && (w[1] - bbox[e][1]).abs() <= tol)
        })
        .collect();
    let mut touches = vec![false; section.n_nodes()];
    for e in (0..n).filter(|&e| junction[e]) {
        for &p in section.element(e) {
            touches[p] = true;
        }
    }
    let side = (0..n)
        .filter(|&e| junction[e])
        .map(|e| (bbox[e][1] - bbox[e][0]).min(bbox[e][3] - bbox[e][2]))
        .reduce(f64::min);
    let next: Vec<bool> = (0..n).map(|e| !junction[e] && section.element(e).iter().any(|&p| touches[p])).collect();
    // an element's length along its wall: x along a flange or lip, z along a web
    let layer = (0..n)
        .filter(|&e| next[e] && key[e].is_some())
        .map(|e| if key[e] == Some("along_web") { bbox[e][3] - bbox[e][2] } else { bbox[e][1] - bbox[e][0] })
        .reduce(f64::min);
    (next, side.zip(layer))
}
