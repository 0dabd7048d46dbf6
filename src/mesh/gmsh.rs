//! Section meshes read from gmsh `.msh` files: ASCII format 4.1 or 2.2,
//! quadrilaterals of order 1–3 (gmsh types 3, 10, 36 → L4, L9, L16).
//!
//! gmsh's `(x, y)` becomes the section's `(x, z)` (the beam axis is y);
//! gmsh's z must be 0. Node order is converted from gmsh's (corners
//! counter-clockwise, then edge nodes edge by edge, then the interior
//! recursively) to the lexicographic order of [`crate::shape`]. Every
//! element's Jacobian is checked at its nodes: a clockwise (inverted)
//! element is refused rather than flipped. Line and point elements
//! (boundaries) are ignored; physical surface groups become
//! [`Region`]s.
//!
//! Every error names the model-file key, the file, its line and what is
//! allowed; nothing in a file can make the reader panic.

use std::collections::HashMap;
use std::path::Path;

use super::MeshError;
use super::section::{CrossSection, Region};
use crate::shape::{Lagrange2d, SectionElementKind};

/// gmsh node `k` of a quadrilateral of order `p` sits at grid position
/// `(i, j)` (lexicographic index `j (p + 1) + i`).
fn gmsh_grid(p: usize) -> &'static [(usize, usize)] {
    match p {
        1 => &[(0, 0), (1, 0), (1, 1), (0, 1)],
        2 => &[(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)],
        _ => &[
            (0, 0),
            (3, 0),
            (3, 3),
            (0, 3),
            (1, 0),
            (2, 0),
            (3, 1),
            (3, 2),
            (2, 3),
            (1, 3),
            (0, 2),
            (0, 1),
            (1, 1),
            (2, 1),
            (2, 2),
            (1, 2),
        ],
    }
}

/// What a gmsh element type is, for the messages.
fn type_name(t: u32) -> &'static str {
    match t {
        2 | 9 | 20 | 21 | 22 | 23 | 24 | 25 => "a triangle",
        16 => "an 8-node serendipity quadrilateral",
        1 | 8 | 26 | 27 | 28 => "a line",
        15 => "a point",
        4 | 5 | 6 | 7 | 11 | 12 | 13 | 14 | 17 | 18 | 19 | 29 | 30 | 31 | 92 | 93 => "a 3D element",
        _ => "an unsupported element",
    }
}

const ALLOWED: &str = "a planar gmsh mesh (ASCII format 4.1 or 2.2) of quadrilaterals of one order: 4-node \
                       (type 3 → L4), 9-node (type 10 → L9) or 16-node (type 36 → L16) in the z = 0 plane, \
                       counter-clockwise";

/// Reads a section from the `.msh` file at `path`, coordinates multiplied by
/// `scale` (e.g. 1e-3 for a mesh drawn in mm). `key` is the model-file key
/// naming the file.
pub fn read(path: &Path, scale: f64, key: &str) -> Result<CrossSection, MeshError> {
    let name = path.display().to_string();
    let cap = crate::size::MAX_MESH_FILE;
    let bytes = crate::size::read_at_most(path, cap)
        .map_err(|e| MeshError::invalid(key, format!("{name:?} ({e})"), "the path of a readable gmsh .msh file"))?
        .ok_or_else(|| {
            MeshError::invalid(
                key,
                format!("{name:?} (more than {})", crate::size::human_bytes(cap)),
                format!("a gmsh .msh file of at most {}", crate::size::human_bytes(cap)),
            )
        })?;
    let text = String::from_utf8(bytes).map_err(|_| {
        MeshError::invalid(key, format!("{name:?} (not text: binary .msh?)"), format!("{ALLOWED}; save as ASCII"))
    })?;
    parse(&text, &name, scale, key)
}

/// A raw element: gmsh type, node tags, line in the file, physical tags.
struct RawElement {
    kind: u32,
    nodes: Vec<u64>,
    line: usize,
    physical: Vec<i64>,
}

/// Line-by-line reader that knows where it is.
struct Reader<'a> {
    lines: Vec<(usize, &'a str)>,
    at: usize,
    file: &'a str,
    key: &'a str,
}

impl<'a> Reader<'a> {
    fn error(&self, line: usize, problem: impl std::fmt::Display) -> MeshError {
        MeshError::invalid(self.key, format!("{:?} line {line}: {problem}", self.file), ALLOWED)
    }

    fn next(&mut self) -> Result<(usize, &'a str), MeshError> {
        let last = self.lines.last().map_or(0, |l| l.0);
        let l = self.lines.get(self.at).copied().ok_or_else(|| self.error(last, "unexpected end of file"))?;
        self.at += 1;
        Ok(l)
    }

    /// The next line's whitespace-separated numbers of type `T`.
    fn numbers<T: std::str::FromStr>(&mut self, what: &str) -> Result<(usize, Vec<T>), MeshError> {
        let (n, l) = self.next()?;
        let v: Result<Vec<T>, _> = l.split_whitespace().map(str::parse).collect();
        v.map(|v| (n, v)).map_err(|_| self.error(n, format!("expected {what}, found {:?}", shorten(l))))
    }

    fn expect(&mut self, tag: &str) -> Result<(), MeshError> {
        let (n, l) = self.next()?;
        if l.trim() == tag { Ok(()) } else { Err(self.error(n, format!("expected {tag}, found {:?}", shorten(l)))) }
    }
}

fn shorten(l: &str) -> String {
    l.chars().take(60).collect()
}

fn get<T: Copy>(r: &Reader, line: usize, v: &[T], i: usize, what: &str) -> Result<T, MeshError> {
    v.get(i).copied().ok_or_else(|| r.error(line, format!("missing {what}")))
}

/// Parses `.msh` text (`file` names it in messages).
pub fn parse(text: &str, file: &str, scale: f64, key: &str) -> Result<CrossSection, MeshError> {
    let lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty()).collect();
    let mut r = Reader { lines, at: 0, file, key };
    let mut version = None;
    let mut names: HashMap<i64, String> = HashMap::new();
    let mut surface_physicals: HashMap<i64, Vec<i64>> = HashMap::new();
    let mut nodes: HashMap<u64, ([f64; 3], usize)> = HashMap::new();
    let mut elements: Vec<RawElement> = Vec::new();
    while r.at < r.lines.len() {
        let (n, l) = r.next()?;
        match l {
            "$MeshFormat" => {
                let (n, head) = r.next()?;
                let t: Vec<&str> = head.split_whitespace().collect();
                match (t.first().copied(), t.get(1).copied()) {
                    (Some("4.1"), Some("0")) => version = Some(4),
                    (Some("2.2"), Some("0")) => version = Some(2),
                    (Some(v @ ("4.1" | "2.2")), Some(_)) => {
                        return Err(r.error(n, format!("format {v} binary; only ASCII files are read")));
                    }
                    _ => return Err(r.error(n, format!("format version {:?} is not supported", shorten(head)))),
                }
                r.expect("$EndMeshFormat")?;
            }
            "$PhysicalNames" => {
                let (_, c) = r.numbers::<usize>("the number of physical names")?;
                for _ in 0..get(&r, n, &c, 0, "count")? {
                    let (m, l) = r.next()?;
                    let t: Vec<&str> = l.splitn(3, char::is_whitespace).collect();
                    let (dim, tag) =
                        (t.first().and_then(|s| s.parse::<u8>().ok()), t.get(1).and_then(|s| s.parse().ok()));
                    match (dim, tag, t.get(2)) {
                        (Some(2), Some(tag), Some(name)) => {
                            names.insert(tag, name.trim().trim_matches('"').to_string());
                        }
                        (Some(_), Some(_), Some(_)) => {}
                        _ => return Err(r.error(m, "expected `dimension tag \"name\"`")),
                    }
                }
                r.expect("$EndPhysicalNames")?;
            }
            "$Entities" if version == Some(4) => entities(&mut r, &mut surface_physicals)?,
            "$Nodes" | "$Elements" if version.is_none() => {
                return Err(r.error(n, format!("{l} before $MeshFormat")));
            }
            "$Nodes" if version == Some(4) => nodes_v4(&mut r, &mut nodes)?,
            "$Nodes" => {
                let (m, c) = r.numbers::<usize>("the number of nodes")?;
                for _ in 0..get(&r, m, &c, 0, "node count")? {
                    let (t, v) = r.numbers::<f64>("`tag x y z`")?;
                    if v.len() < 4 || !v.iter().all(|c| c.is_finite()) || v[0] < 0.0 {
                        return Err(r.error(t, "expected `tag x y z` with finite coordinates"));
                    }
                    insert_node(&r, &mut nodes, v[0] as u64, ([v[1], v[2], v[3]], t))?;
                }
                r.expect("$EndNodes")?;
            }
            "$Elements" if version == Some(4) => elements_v4(&mut r, &surface_physicals, &mut elements)?,
            "$Elements" => elements_v2(&mut r, &mut elements)?,
            other if other.starts_with("$End") => return Err(r.error(n, format!("unexpected {other}"))),
            other if other.starts_with('$') => {
                // a section we do not need ($Periodic, $NodeData, …): skip it
                let end = format!("$End{}", &other[1..]);
                while r.next()?.1 != end {}
            }
            other => return Err(r.error(n, format!("expected a $Section header, found {:?}", shorten(other)))),
        }
    }
    if version.is_none() {
        return Err(r.error(1, "no $MeshFormat section: not a gmsh .msh file"));
    }
    build(&r, &nodes, &elements, &names, scale)
}

/// `$Entities` (4.1): the physical tags of every surface.
fn entities(r: &mut Reader, surface_physicals: &mut HashMap<i64, Vec<i64>>) -> Result<(), MeshError> {
    let (m, c) = r.numbers::<usize>("four entity counts")?;
    let skip = get(r, m, &c, 0, "point count")? + get(r, m, &c, 1, "curve count")?;
    for _ in 0..skip {
        r.next()?;
    }
    for _ in 0..get(r, m, &c, 2, "surface count")? {
        let (s, v) = r.numbers::<f64>("a surface entity")?;
        let np = get(r, s, &v, 7, "number of physical tags")? as usize;
        let tags: Vec<i64> = v.iter().skip(8).take(np).map(|&t| t as i64).collect();
        surface_physicals.insert(get(r, s, &v, 0, "surface tag")? as i64, tags);
    }
    for _ in 0..get(r, m, &c, 3, "volume count")? {
        r.next()?;
    }
    r.expect("$EndEntities")?;
    Ok(())
}

/// `$Nodes` (4.1): blocks of tags, then their coordinates.
fn nodes_v4(r: &mut Reader, nodes: &mut HashMap<u64, ([f64; 3], usize)>) -> Result<(), MeshError> {
    let (m, c) = r.numbers::<u64>("`blocks nodes minTag maxTag`")?;
    for _ in 0..get(r, m, &c, 0, "block count")? {
        let (b, h) = r.numbers::<u64>("`dimension entity parametric count`")?;
        let count = get(r, b, &h, 3, "node count")? as usize;
        let mut tags = Vec::with_capacity(count.min(1 << 20));
        for _ in 0..count {
            let (t, v) = r.numbers::<u64>("a node tag")?;
            tags.push((get(r, t, &v, 0, "node tag")?, t));
        }
        for (tag, _) in tags {
            let (t, v) = r.numbers::<f64>("node coordinates x y z")?;
            let x = [0, 1, 2].map(|k| v.get(k).copied().unwrap_or(f64::NAN));
            if !x.iter().all(|c| c.is_finite()) {
                return Err(r.error(t, "expected three finite coordinates x y z"));
            }
            insert_node(r, nodes, tag, (x, t))?;
        }
    }
    r.expect("$EndNodes")?;
    Ok(())
}

/// Records node `tag` (its coordinates and line); a tag listed twice is
/// refused, naming both lines (the later one silently replaced the first).
fn insert_node(
    r: &Reader,
    nodes: &mut HashMap<u64, ([f64; 3], usize)>,
    tag: u64,
    node: ([f64; 3], usize),
) -> Result<(), MeshError> {
    match nodes.insert(tag, node) {
        Some((_, first)) => Err(r.error(node.1, format!("node {tag} is listed twice (first on line {first})"))),
        None => Ok(()),
    }
}

/// `$Elements` (4.1): blocks per entity; surfaces' elements kept with
/// their entity's physical tags, volumes refused.
fn elements_v4(
    r: &mut Reader,
    surface_physicals: &HashMap<i64, Vec<i64>>,
    elements: &mut Vec<RawElement>,
) -> Result<(), MeshError> {
    let (m, c) = r.numbers::<u64>("`blocks elements minTag maxTag`")?;
    for _ in 0..get(r, m, &c, 0, "block count")? {
        let (b, h) = r.numbers::<i64>("`dimension entity type count`")?;
        let (dim, entity) = (get(r, b, &h, 0, "dimension")?, get(r, b, &h, 1, "entity tag")?);
        let (kind, count) = (get(r, b, &h, 2, "element type")?, get(r, b, &h, 3, "element count")?);
        for _ in 0..count {
            let (t, v) = r.numbers::<u64>("`tag node node …`")?;
            if dim == 2 {
                let physical = surface_physicals.get(&entity).cloned().unwrap_or_default();
                let nodes = v.get(1..).unwrap_or_default().to_vec();
                elements.push(RawElement { kind: kind as u32, nodes, line: t, physical });
            } else if dim == 3 {
                return Err(r.error(t, format!("{} (type {kind}) in a section mesh", type_name(kind as u32))));
            }
        }
    }
    r.expect("$EndElements")?;
    Ok(())
}

/// `$Elements` (2.2): one line per element; points and lines skipped.
fn elements_v2(r: &mut Reader, elements: &mut Vec<RawElement>) -> Result<(), MeshError> {
    let (m, c) = r.numbers::<usize>("the number of elements")?;
    for _ in 0..get(r, m, &c, 0, "element count")? {
        let (t, v) = r.numbers::<i64>("`tag type ntags tags… nodes…`")?;
        let kind = get(r, t, &v, 1, "element type")? as u32;
        let ntags = get(r, t, &v, 2, "number of tags")?.max(0) as usize;
        let physical = v.get(3).copied().filter(|_| ntags > 0).into_iter().filter(|&p| p != 0).collect();
        let nodes = v.get(3 + ntags..).unwrap_or_default().iter().map(|&n| n.max(0) as u64).collect();
        match kind {
            1 | 8 | 26 | 27 | 28 | 15 => {}
            _ => elements.push(RawElement { kind, nodes, line: t, physical }),
        }
    }
    r.expect("$EndElements")?;
    Ok(())
}

fn build(
    r: &Reader,
    nodes: &HashMap<u64, ([f64; 3], usize)>,
    elements: &[RawElement],
    names: &HashMap<i64, String>,
    scale: f64,
) -> Result<CrossSection, MeshError> {
    let first = elements.first().ok_or_else(|| r.error(r.lines.last().map_or(0, |l| l.0), "no 2D elements"))?;
    let order = |e: &RawElement| match e.kind {
        3 => Ok(1),
        10 => Ok(2),
        36 => Ok(3),
        k => Err(r.error(e.line, format!("{} (gmsh type {k})", type_name(k)))),
    };
    let p = order(first)?;
    let kind = [SectionElementKind::L4, SectionElementKind::L9, SectionElementKind::L16][p - 1];
    let grid = gmsh_grid(p);
    let m = p + 1;
    let basis = Lagrange2d::new(p);
    let (mut f, mut dxi, mut deta) = (vec![0.0; m * m], vec![0.0; m * m], vec![0.0; m * m]);
    let mut index: HashMap<u64, usize> = HashMap::new();
    let mut coords: Vec<[f64; 2]> = Vec::new();
    let mut connectivity = Vec::with_capacity(elements.len() * m * m);
    let mut regions: Vec<Region> = Vec::new();
    for (e, el) in elements.iter().enumerate() {
        let q = order(el)?;
        if q != p {
            return Err(r.error(
                el.line,
                format!("a {}-node quadrilateral among {}-node ones (mixed orders)", (q + 1).pow(2), m * m),
            ));
        }
        if el.nodes.len() != m * m {
            return Err(r.error(el.line, format!("{} node tags for a {}-node quadrilateral", el.nodes.len(), m * m)));
        }
        let mut local = vec![0; m * m];
        for (k, &tag) in el.nodes.iter().enumerate() {
            let (x, _) = nodes.get(&tag).ok_or_else(|| r.error(el.line, format!("node {tag} is not in $Nodes")))?;
            if x[2].abs() > 1e-9 * (1.0 + x[0].abs().max(x[1].abs())) {
                return Err(r.error(el.line, format!("node {tag} has z = {} (off the z = 0 plane)", x[2])));
            }
            let id = *index.entry(tag).or_insert_with(|| {
                coords.push([x[0] * scale, x[1] * scale]);
                coords.len() - 1
            });
            let (i, j) = grid[k];
            local[j * m + i] = id;
        }
        // the Jacobian at every node: all positive for a valid counter-clockwise element
        let mut dets = Vec::with_capacity(m * m);
        for k in 0..m * m {
            let [xi, eta] = basis.node(k);
            basis.eval(xi, eta, &mut f, &mut dxi, &mut deta);
            let mut jac = [[0.0; 2]; 2];
            for (a, &n) in local.iter().enumerate() {
                for d in 0..2 {
                    jac[0][d] += dxi[a] * coords[n][d];
                    jac[1][d] += deta[a] * coords[n][d];
                }
            }
            dets.push(jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0]);
        }
        if dets.iter().all(|&d| d < 0.0) {
            return Err(r.error(
                el.line,
                format!("element {e} is inverted (clockwise in x–y; reverse the surface's orientation in gmsh)"),
            ));
        }
        if !dets.iter().all(|&d| d > 0.0) {
            return Err(r.error(el.line, format!("element {e} is distorted (its Jacobian changes sign)")));
        }
        connectivity.extend_from_slice(&local);
        for &tag in &el.physical {
            let name = names.get(&tag).cloned().unwrap_or_else(|| format!("physical_{tag}"));
            match regions.iter_mut().find(|g| g.name == name) {
                Some(g) => g.elements.push(e),
                None => regions.push(Region { name, elements: vec![e], normal: None }),
            }
        }
    }
    // duplicated or overlapping elements would count their area twice
    let corners: Vec<[usize; 4]> =
        connectivity.chunks(m * m).map(|c| [c[0], c[m - 1], c[m * m - 1], c[(m - 1) * m]]).collect();
    if let Some((a, b, share)) = super::overlaps::first_overlap(&coords, &corners) {
        return Err(r.error(
            elements[b].line,
            format!(
                "element {b} covers {:.3} % of element {a} (line {}): a duplicated or overlapping element would \
                 count that area twice",
                100.0 * share,
                elements[a].line
            ),
        ));
    }
    Ok(CrossSection { kind, nodes: coords, connectivity, regions, twins: Vec::new() })
}

#[cfg(test)]
#[path = "gmsh_tests.rs"]
mod tests;
