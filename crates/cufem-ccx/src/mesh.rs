//! Hexahedral meshes of the CUF bodies and of the rigid tools, for the
//! CalculiX deck.
//!
//! **Bodies.** Every CUF element (section element × beam element) becomes a
//! block of `n_ξ × n_y × n_η` hexahedra with `n_ξ = n_η = N p_s` and
//! `n_y = N p_b` (`N` = `refine`, `p` the Lagrange orders): with `N = 1` the
//! hex corners are the CUF element's own Lagrange nodes. Hex nodes are
//! placed through the CUF element's isoparametric map, so gradings, thin
//! walls and curved sections are the same geometry. A section point shared by
//! two elements is identified topologically (a corner by its section node,
//! an edge point by its edge and position), never by comparing coordinates,
//! and a 3D node is a (section point, axis point) pair — the tensor
//! structure of the CUF body.
//!
//! **Hex convention.** Local coordinates `(r, s, t)` of a hex follow
//! `(ξ, y, η)` — right-handed in `(x, y, z)` since sections are
//! counter-clockwise in the x–z plane — with the Abaqus/CalculiX node order
//! (corners 1–8, then mid-edge nodes 9–20 for C3D20R) and faces S1 (t = −1)
//! … S6 (r = −1).
//!
//! **Tools.** A flat punch is a block of hexes under its face; a roller is a
//! cylinder sector covering the angles of the nodes it may touch. Both are
//! rigid bodies driven by a reference node.

use std::collections::HashMap;

use cufem::bc::Face;
use cufem::contact::{Indenter, RigidSurface};
use cufem::mesh::Body;
use cufem::setup::Model;
use cufem::shape::Lagrange2d;
use cufem::values::{FaceSide, Location, section_point};

/// The hexahedron used for the bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HexKind {
    /// 8 nodes with incompatible modes (good in bending).
    C3D8I,
    /// 20 nodes, reduced integration.
    C3D20R,
}

impl HexKind {
    /// CalculiX element type name.
    pub fn name(self) -> &'static str {
        match self {
            Self::C3D8I => "C3D8I",
            Self::C3D20R => "C3D20R",
        }
    }

    /// Parses `C3D8I` or `C3D20R`.
    pub fn parse(s: &str) -> Option<Self> {
        match s.to_ascii_uppercase().as_str() {
            "C3D8I" => Some(Self::C3D8I),
            "C3D20R" => Some(Self::C3D20R),
            _ => None,
        }
    }

    /// True for the 20-node element.
    pub fn quadratic(self) -> bool {
        self == Self::C3D20R
    }

    /// Nodes per element.
    pub fn nodes(self) -> usize {
        if self.quadratic() { 20 } else { 8 }
    }
}

/// Natural coordinates of the 20 nodes of a hexahedron in CalculiX order.
pub const HEX_NODES: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// Local node indices of the six faces (corners, then mid-edge nodes), in
/// the order of CalculiX's face labels S1…S6.
pub const HEX_FACES: [[usize; 8]; 6] = [
    [0, 1, 2, 3, 8, 9, 10, 11],
    [4, 7, 6, 5, 15, 14, 13, 12],
    [0, 4, 5, 1, 16, 12, 17, 8],
    [1, 5, 6, 2, 17, 13, 18, 9],
    [2, 6, 7, 3, 18, 14, 19, 10],
    [3, 7, 4, 0, 19, 15, 16, 11],
];

/// Shape functions of the 8- or 20-node hexahedron at `(r, s, t)`.
pub fn hex_shapes(kind: HexKind, p: [f64; 3], out: &mut [f64]) {
    let [r, s, t] = p;
    for (a, c) in HEX_NODES.iter().take(kind.nodes()).enumerate() {
        let (ri, si, ti) = (c[0], c[1], c[2]);
        out[a] = if !kind.quadratic() {
            0.125 * (1.0 + r * ri) * (1.0 + s * si) * (1.0 + t * ti)
        } else if a < 8 {
            0.125 * (1.0 + r * ri) * (1.0 + s * si) * (1.0 + t * ti) * (r * ri + s * si + t * ti - 2.0)
        } else if ri == 0.0 {
            0.25 * (1.0 - r * r) * (1.0 + s * si) * (1.0 + t * ti)
        } else if si == 0.0 {
            0.25 * (1.0 + r * ri) * (1.0 - s * s) * (1.0 + t * ti)
        } else {
            0.25 * (1.0 + r * ri) * (1.0 + s * si) * (1.0 - t * t)
        };
    }
}

/// Which part of the deck an element belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// A CUF body.
    Body(usize),
    /// The rigid tool of an indenter.
    Tool(usize),
}

/// The hexes of one CUF body.
#[derive(Debug, Clone)]
pub struct BodyHexes {
    /// Index of the body's first element in [`HexMesh::elements`].
    pub first_element: usize,
    /// Hexes per CUF element along ξ, η and the axis.
    pub sub: [usize; 3],
}

/// A rigid tool: its elements, the face it presses with and its reference node.
#[derive(Debug, Clone)]
pub struct Tool {
    /// Indenter index.
    pub indenter: usize,
    /// Elements of the tool.
    pub elements: std::ops::Range<usize>,
    /// Reference node (drives the tool) and rotation node.
    pub reference: usize,
    /// Rotation node of the rigid body.
    pub rotation: usize,
    /// `(element, face label 1–6)` of the pressing surface.
    pub faces: Vec<(usize, usize)>,
}

/// The whole 3D mesh: bodies, then tools.
#[derive(Debug, Clone)]
pub struct HexMesh {
    /// Element kind of the bodies (tools use C3D8).
    pub kind: HexKind,
    /// Subdivision per Lagrange interval.
    pub refine: usize,
    /// Node coordinates.
    pub nodes: Vec<[f64; 3]>,
    /// Element connectivity (node indices, CalculiX order).
    pub elements: Vec<Vec<usize>>,
    /// Owner of each element.
    pub parts: Vec<Part>,
    /// Per body.
    pub bodies: Vec<BodyHexes>,
    /// Per indenter.
    pub tools: Vec<Tool>,
    /// Nodes duplicated at material interfaces (filled by
    /// [`super::interfaces`] when exported).
    pub ties: Vec<super::Tie>,
}

/// Topological identity of a point of a section element's grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum SectionKey {
    Corner(usize),
    Edge(usize, usize, usize),
    Interior(usize, usize, usize),
}

impl HexMesh {
    /// Meshes every body of `model` (and its tools) with `refine` hexes per
    /// Lagrange interval.
    pub fn new(model: &Model, kind: HexKind, refine: usize) -> Self {
        let mut mesh = Self {
            kind,
            refine,
            nodes: Vec::new(),
            elements: Vec::new(),
            parts: Vec::new(),
            bodies: Vec::new(),
            tools: Vec::new(),
            ties: Vec::new(),
        };
        for (b, body) in model.mesh.bodies.iter().enumerate() {
            mesh.add_body(b, body);
        }
        mesh.compact();
        for (i, ind) in model.indenters.iter().enumerate() {
            let body = &model.mesh.bodies[ind.body];
            mesh.add_tool(i, ind, body, model);
        }
        mesh
    }

    /// Grid points per CUF element edge (`m · n + 1`) and the hexes per element `n`.
    fn grid(&self, order: usize) -> (usize, usize) {
        let m = if self.kind.quadratic() { 2 } else { 1 };
        let n = self.refine * order;
        (m * n + 1, n)
    }

    fn add_body(&mut self, b: usize, body: &Body) {
        let section = &body.section;
        let (ps, pb) = (section.kind.order(), body.axis.kind.order());
        let (gs, ns) = self.grid(ps);
        let (ga, na) = self.grid(pb);
        let basis = Lagrange2d::new(ps);
        let n_fun = basis.len();
        let (mut f, mut dxi, mut deta) = (vec![0.0; n_fun], vec![0.0; n_fun], vec![0.0; n_fun]);
        // section points, identified topologically
        let mut ids: HashMap<SectionKey, usize> = HashMap::new();
        let mut positions: Vec<[f64; 2]> = Vec::new();
        let mut element_points: Vec<Vec<usize>> = Vec::with_capacity(section.n_elements());
        for es in 0..section.n_elements() {
            let el = section.element(es);
            let c = [el[0], el[ps], el[(ps + 1) * (ps + 1) - 1], el[ps * (ps + 1)]];
            let last = gs - 1;
            let mut pts = Vec::with_capacity(gs * gs);
            for bi in 0..gs {
                for ai in 0..gs {
                    let edge = |u: usize, v: usize, k: usize| {
                        if u < v { SectionKey::Edge(u, v, k) } else { SectionKey::Edge(v, u, last - k) }
                    };
                    let key = match (ai, bi) {
                        (0, 0) => SectionKey::Corner(c[0]),
                        (a, 0) if a == last => SectionKey::Corner(c[1]),
                        (a, b) if a == last && b == last => SectionKey::Corner(c[2]),
                        (0, b) if b == last => SectionKey::Corner(c[3]),
                        (a, 0) => edge(c[0], c[1], a),
                        (a, b) if a == last => edge(c[1], c[2], b),
                        (a, b) if b == last => edge(c[3], c[2], a),
                        (0, b) => edge(c[0], c[3], b),
                        (a, b) => SectionKey::Interior(es, a, b),
                    };
                    let id = *ids.entry(key).or_insert_with(|| {
                        let xi = -1.0 + 2.0 * ai as f64 / last as f64;
                        let eta = -1.0 + 2.0 * bi as f64 / last as f64;
                        let sp = section_point(section, &basis, es, xi, eta, &mut f, &mut dxi, &mut deta);
                        positions.push(sp.position);
                        positions.len() - 1
                    });
                    pts.push(id);
                }
            }
            element_points.push(pts);
        }
        // axis points: shared element ends by construction
        let n_axis = (ga - 1) * body.axis.n_elements() + 1;
        let mut ys = Vec::with_capacity(n_axis);
        for eb in 0..body.axis.n_elements() {
            let (y0, y1) = body.axis.element_span(eb);
            for k in 0..ga - usize::from(eb + 1 < body.axis.n_elements()) {
                ys.push(y0 + (y1 - y0) * k as f64 / (ga - 1) as f64);
            }
        }
        let offset = self.nodes.len();
        let n_sec = positions.len();
        for &y in &ys {
            for p in &positions {
                self.nodes.push([p[0], y, p[1]]);
            }
        }
        let node = |axis_pt: usize, sec_pt: usize| offset + axis_pt * n_sec + sec_pt;
        let first_element = self.elements.len();
        let m = (gs - 1) / ns;
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            let pts = &element_points[es];
            for k in 0..na {
                for j in 0..ns {
                    for i in 0..ns {
                        let hex: Vec<usize> = HEX_NODES
                            .iter()
                            .take(self.kind.nodes())
                            .map(|c| {
                                let a = m * i + ((c[0] + 1.0) * 0.5 * m as f64) as usize;
                                let bb = m * j + ((c[2] + 1.0) * 0.5 * m as f64) as usize;
                                let ax = eb * (ga - 1) + m * k + ((c[1] + 1.0) * 0.5 * m as f64) as usize;
                                node(ax, pts[bb * gs + a])
                            })
                            .collect();
                        self.elements.push(hex);
                        self.parts.push(Part::Body(b));
                    }
                }
            }
        }
        self.bodies.push(BodyHexes { first_element, sub: [ns, ns, na] });
    }

    /// Drops the grid points no element uses (face and cell centres of the
    /// 20-node grid) and renumbers.
    fn compact(&mut self) {
        let mut new_id = vec![usize::MAX; self.nodes.len()];
        for e in &self.elements {
            for &n in e {
                new_id[n] = 0;
            }
        }
        let mut nodes = Vec::new();
        for (old, id) in new_id.iter_mut().enumerate() {
            if *id == 0 {
                *id = nodes.len();
                nodes.push(self.nodes[old]);
            }
        }
        for e in &mut self.elements {
            for n in e.iter_mut() {
                *n = new_id[*n];
            }
        }
        self.nodes = nodes;
    }

    /// The hex of a CUF location and the local coordinates `(r, s, t)` of the point in it.
    pub fn locate(&self, model: &Model, loc: &Location) -> (usize, [f64; 3]) {
        let body = &model.mesh.bodies[loc.body];
        let bh = &self.bodies[loc.body];
        let [nx, ny_, na] = bh.sub;
        let cell = |u: f64, n: usize| {
            let x = (u + 1.0) * 0.5 * n as f64;
            let i = (x.floor() as usize).min(n - 1);
            (i, 2.0 * (x - i as f64) - 1.0)
        };
        let (i, r) = cell(loc.natural[0], nx);
        let (j, t) = cell(loc.natural[1], ny_);
        let (k, s) = cell(loc.natural[2], na);
        let per = nx * ny_ * na;
        let _ = body;
        (bh.first_element + loc.element * per + (k * ny_ + j) * nx + i, [r, s, t])
    }

    /// `(element, face label 1–6)` of the hex faces that make up CUF faces.
    pub fn body_faces(&self, model: &Model, b: usize, faces: &[Face]) -> Vec<(usize, usize)> {
        let body = &model.mesh.bodies[b];
        let bh = &self.bodies[b];
        let [nx, nh, na] = bh.sub;
        let mut out = Vec::new();
        for f in faces {
            let e = f.beam_element * body.section.n_elements() + f.section_element;
            let first = bh.first_element + e * nx * nh * na;
            let hex = |i: usize, j: usize, k: usize| first + (k * nh + j) * nx + i;
            match f.side {
                FaceSide::Lateral(0) => (0..na).for_each(|k| (0..nx).for_each(|i| out.push((hex(i, 0, k), 1)))),
                FaceSide::Lateral(1) => (0..na).for_each(|k| (0..nh).for_each(|j| out.push((hex(nx - 1, j, k), 4)))),
                FaceSide::Lateral(2) => (0..na).for_each(|k| (0..nx).for_each(|i| out.push((hex(i, nh - 1, k), 2)))),
                FaceSide::Lateral(_) => (0..na).for_each(|k| (0..nh).for_each(|j| out.push((hex(0, j, k), 6)))),
                FaceSide::End(false) => (0..nh).for_each(|j| (0..nx).for_each(|i| out.push((hex(i, j, 0), 3)))),
                FaceSide::End(true) => (0..nh).for_each(|j| (0..nx).for_each(|i| out.push((hex(i, j, na - 1), 5)))),
            }
        }
        out
    }

    /// Nodes of the body elements of body `b`.
    pub fn body_nodes(&self, b: usize) -> Vec<usize> {
        let mut nodes: Vec<usize> = self
            .elements
            .iter()
            .zip(&self.parts)
            .filter(|(_, p)| **p == Part::Body(b))
            .flat_map(|(e, _)| e.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// A typical hex size near the surface of body `b` (m): its smallest edge length.
    pub fn element_size(&self, b: usize) -> f64 {
        let mut h = f64::INFINITY;
        for (e, p) in self.elements.iter().zip(&self.parts) {
            if *p != Part::Body(b) {
                continue;
            }
            for (u, v) in [(0, 1), (0, 3), (0, 4)] {
                let (a, c) = (self.nodes[e[u]], self.nodes[e[v]]);
                h = h.min(((a[0] - c[0]).powi(2) + (a[1] - c[1]).powi(2) + (a[2] - c[2]).powi(2)).sqrt());
            }
        }
        h
    }

    /// Adds a structured block of C3D8 hexes `map(u, v, w)` with `u, v, w ∈ [0, 1]`,
    /// `n[0] × n[1] × 1` cells, oriented to a positive volume; returns the
    /// element range and the elements' local face label at `w = 1`.
    fn add_block(
        &mut self,
        n: [usize; 2],
        map: impl Fn(f64, f64, f64) -> [f64; 3],
        part: Part,
    ) -> (std::ops::Range<usize>, usize) {
        let first_node = self.nodes.len();
        for w in 0..2 {
            for v in 0..=n[1] {
                for u in 0..=n[0] {
                    self.nodes.push(map(u as f64 / n[0] as f64, v as f64 / n[1] as f64, w as f64));
                }
            }
        }
        let id = |u: usize, v: usize, w: usize| first_node + (w * (n[1] + 1) + v) * (n[0] + 1) + u;
        let first = self.elements.len();
        // (r, s, t) = (u, v, w) unless that is left-handed, then (v, u, w)
        // local orientation at the first cell (a whole curved sector's chords could mislead)
        let (du, dv) = (1.0 / n[0] as f64, 1.0 / n[1] as f64);
        let probe = [map(0.0, 0.0, 0.0), map(du, 0.0, 0.0), map(0.0, dv, 0.0), map(0.0, 0.0, 1.0)];
        let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let (a, b, c) = (d(probe[0], probe[1]), d(probe[0], probe[2]), d(probe[0], probe[3]));
        let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
        for v in 0..n[1] {
            for u in 0..n[0] {
                let hex = if det > 0.0 {
                    vec![
                        id(u, v, 0),
                        id(u + 1, v, 0),
                        id(u + 1, v + 1, 0),
                        id(u, v + 1, 0),
                        id(u, v, 1),
                        id(u + 1, v, 1),
                        id(u + 1, v + 1, 1),
                        id(u, v + 1, 1),
                    ]
                } else {
                    vec![
                        id(u, v, 0),
                        id(u, v + 1, 0),
                        id(u + 1, v + 1, 0),
                        id(u + 1, v, 0),
                        id(u, v, 1),
                        id(u, v + 1, 1),
                        id(u + 1, v + 1, 1),
                        id(u + 1, v, 1),
                    ]
                };
                self.elements.push(hex);
                self.parts.push(part);
            }
        }
        // w = 1 is the face of nodes 5–8: S2
        (first..self.elements.len(), 2)
    }

    fn add_tool(&mut self, i: usize, ind: &Indenter, body: &Body, model: &Model) {
        let h = self.element_size(ind.body).max(1e-12);
        let b = body.section.bounds();
        let (y0, y1) = (body.axis.nodes[0], body.axis.nodes[body.axis.n_nodes() - 1]);
        let body_box = [[b[0], b[1]], [y0, y1], [b[2], b[3]]];
        let coords: Vec<[f64; 3]> = ind.nodes.iter().map(|c| model.mesh.coords(c.node)).collect();
        let part = Part::Tool(i);
        let count = |len: f64| ((len / (2.0 * h)).ceil() as usize).clamp(2, 60);
        let (range, face, centre) = match &ind.surface {
            RigidSurface::Flat { axis, sign, position, bounds } => {
                let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
                let extent = |k: usize| bounds[k].unwrap_or(body_box[k]);
                let (eu, ev) = (extent(ua), extent(va));
                let thick = 0.2 * (eu[1] - eu[0]).max(ev[1] - ev[0]);
                let (axis, sign, position) = (*axis, *sign, *position);
                let map = move |u: f64, v: f64, w: f64| {
                    let mut p = [0.0; 3];
                    p[ua] = eu[0] + u * (eu[1] - eu[0]);
                    p[va] = ev[0] + v * (ev[1] - ev[0]);
                    // w = 1 on the punch face, the tool behind it
                    p[axis] = position - sign * thick * (1.0 - w);
                    p
                };
                let n = [count(eu[1] - eu[0]), count(ev[1] - ev[0])];
                let (r, f) = self.add_block(n, map, part);
                (r, f, map(0.5, 0.5, 0.5))
            }
            RigidSurface::Cylinder { axis, center, radius, length } => {
                let (axis, center, radius) = (*axis, *center, *radius);
                let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
                // angles of the nodes it may touch, with a margin
                let angles: Vec<f64> = coords.iter().map(|p| (p[va] - center[va]).atan2(p[ua] - center[ua])).collect();
                let mid =
                    angles.iter().map(|a| a.sin()).sum::<f64>().atan2(angles.iter().map(|a| a.cos()).sum::<f64>());
                let spread = angles
                    .iter()
                    .map(|a| {
                        let d = (a - mid).rem_euclid(2.0 * std::f64::consts::PI);
                        if d > std::f64::consts::PI { 2.0 * std::f64::consts::PI - d } else { d }
                    })
                    .fold(0.0f64, f64::max);
                let half = (spread + 15f64.to_radians()).min(std::f64::consts::FRAC_PI_2);
                let along = length.unwrap_or_else(|| {
                    let (lo, hi) = coords
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p[axis]), h.max(p[axis])));
                    [lo, hi]
                });
                let margin = 0.05 * (along[1] - along[0]).max(radius);
                let (a0, a1) = (along[0] - margin, along[1] + margin);
                let map = move |u: f64, v: f64, w: f64| {
                    let phi = mid - half + 2.0 * half * u;
                    let r = radius * (0.8 + 0.2 * w);
                    let mut p = center;
                    p[ua] += r * phi.cos();
                    p[va] += r * phi.sin();
                    p[axis] = a0 + v * (a1 - a0);
                    p
                };
                // facets of 0.02 rad: the sag R (1 − cos 0.01) is 5e-5 R, far below the hexes
                let n = [((2.0 * half / 0.02).ceil() as usize).clamp(8, 400), count(a1 - a0)];
                let (r, f) = self.add_block(n, map, part);
                (r, f, center)
            }
            RigidSurface::Sphere { center, radius } => {
                let (center, radius) = (*center, *radius);
                let unit = |v: [f64; 3]| {
                    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                    v.map(|x| x / l)
                };
                // a cap around the mean direction to the nodes it may touch
                let dirs: Vec<[f64; 3]> =
                    coords.iter().map(|p| unit(std::array::from_fn(|k| p[k] - center[k]))).collect();
                let pole = unit(dirs.iter().fold([0.0; 3], |a, d| std::array::from_fn(|k| a[k] + d[k])));
                let spread = dirs
                    .iter()
                    .map(|d| (d[0] * pole[0] + d[1] * pole[1] + d[2] * pole[2]).clamp(-1.0, 1.0).acos())
                    .fold(0.0f64, f64::max);
                let half = (spread + 15f64.to_radians()).min(75f64.to_radians());
                // two directions across the pole
                let k = (0..3).min_by(|&a, &b| pole[a].abs().total_cmp(&pole[b].abs())).unwrap_or(0);
                let mut e = [0.0; 3];
                e[k] = 1.0;
                let dot = e[0] * pole[0] + e[1] * pole[1] + e[2] * pole[2];
                let e1 = unit(std::array::from_fn(|i| e[i] - dot * pole[i]));
                let e2 = [
                    pole[1] * e1[2] - pole[2] * e1[1],
                    pole[2] * e1[0] - pole[0] * e1[2],
                    pole[0] * e1[1] - pole[1] * e1[0],
                ];
                let span = half.tan();
                let map = move |u: f64, v: f64, w: f64| {
                    let (a, b) = (span * (2.0 * u - 1.0), span * (2.0 * v - 1.0));
                    let d = unit(std::array::from_fn(|i| pole[i] + a * e1[i] + b * e2[i]));
                    let r = radius * (0.8 + 0.2 * w);
                    std::array::from_fn(|i| center[i] + r * d[i])
                };
                // facets of about 0.02 rad, as for the cylinder
                let m = ((2.0 * half / 0.02).ceil() as usize).clamp(8, 150);
                let (r, f) = self.add_block([m, m], map, part);
                (r, f, center)
            }
        };
        let faces = range.clone().map(|e| (e, face)).collect();
        self.nodes.push(centre);
        let reference = self.nodes.len() - 1;
        self.nodes.push(centre);
        let rotation = self.nodes.len() - 1;
        self.tools.push(Tool { indenter: i, elements: range, reference, rotation, faces });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serendipity_shapes_are_a_partition_of_unity_and_kronecker() {
        for kind in [HexKind::C3D8I, HexKind::C3D20R] {
            let mut n = vec![0.0; 20];
            hex_shapes(kind, [0.3, -0.7, 0.1], &mut n);
            assert!((n[..kind.nodes()].iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for (a, c) in HEX_NODES.iter().take(kind.nodes()).enumerate() {
                hex_shapes(kind, *c, &mut n);
                for b in 0..kind.nodes() {
                    assert!((n[b] - f64::from(u8::from(a == b))).abs() < 1e-14, "{kind:?} {a} {b}");
                }
            }
        }
    }
}
