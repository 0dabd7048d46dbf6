//! The model: reading a TOML model file and validating it into typed,
//! resolved data (materials, meshes, node sets, loads, contacts, outputs).
//!
//! Validation never panics on user input: every error names the model-file
//! key (as a path such as `bodies[1].section.thickness`), the offending
//! value and what is allowed. The file format is documented key by key in
//! `docs/model-format.md`.

mod schema;

use std::path::Path;

use crate::bc::{self, Condition, Constraint, Load, Selection};
use crate::contact::{self, Indenter, PairContact, Penalty, RigidSurface, SurfaceNodes};
use crate::elements::{ElementError, SectionGeometry};
use crate::materials::{Hardening, Material};
use crate::mesh::{BeamAxis, Body, CrossSection, Division, Mesh, MeshError, Segment};
use crate::post::Quantity;
use crate::shape::{BeamElementKind, SectionElementKind};
use crate::solver::newton::NewtonSettings;
use crate::solver::stepping::StepSettings;
use schema::*;

/// Errors found while reading or validating a model.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// The file could not be read.
    #[error("cannot read model file {path}: {source}")]
    Io {
        /// File path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// TOML syntax or type error (the message names the key and line).
    #[error("model file: {0}")]
    Parse(String),
    /// A value that is not allowed.
    #[error("{key} = {value}: expected {allowed}")]
    Invalid {
        /// Model-file key.
        key: String,
        /// The value given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Mesh construction error.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Element geometry error.
    #[error(transparent)]
    Element(#[from] ElementError),
}

fn invalid(key: impl Into<String>, value: impl std::fmt::Display, allowed: impl Into<String>) -> ModelError {
    ModelError::Invalid { key: key.into(), value: value.to_string(), allowed: allowed.into() }
}

/// A probe point.
#[derive(Debug, Clone)]
pub struct Probe {
    /// Name.
    pub name: String,
    /// Point (m).
    pub point: [f64; 3],
    /// Body to evaluate in (`None`: the first body containing the point).
    pub body: Option<usize>,
}

/// A straight line sampled at equally spaced points.
#[derive(Debug, Clone)]
pub struct Line {
    /// Name (also the CSV file stem).
    pub name: String,
    /// Start point (m).
    pub from: [f64; 3],
    /// End point (m).
    pub to: [f64; 3],
    /// Number of samples (≥ 2).
    pub points: usize,
    /// Body (`None`: the first body containing each point).
    pub body: Option<usize>,
    /// Quantities plotted to PNG.
    pub plot: Vec<Quantity>,
}

/// A published value printed beside ours.
#[derive(Debug, Clone)]
pub struct Reference {
    /// Probe name.
    pub probe: String,
    /// Quantity.
    pub quantity: Quantity,
    /// Value in SI units.
    pub value: f64,
    /// Where it comes from.
    pub source: String,
}

/// Solution controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Load stepping.
    pub steps: StepSettings,
    /// Newton iteration.
    pub newton: NewtonSettings,
    /// Worker threads (`None`: all cores).
    pub threads: Option<usize>,
}

/// Output controls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputSettings {
    /// Write `result.vtu`.
    pub vtu: bool,
    /// Write PNG plots.
    pub plots: bool,
}

/// A validated model.
#[derive(Debug, Clone)]
pub struct Model {
    /// Title.
    pub title: String,
    /// Description.
    pub description: String,
    /// Materials.
    pub materials: Vec<Material>,
    /// Bodies and node numbering.
    pub mesh: Mesh,
    /// Displacement constraints.
    pub constraints: Vec<Constraint>,
    /// Loads (nodal forces at load factor 1).
    pub loads: Vec<Load>,
    /// Rigid indenters.
    pub indenters: Vec<Indenter>,
    /// Deformable contacts.
    pub contacts: Vec<PairContact>,
    /// Probes.
    pub probes: Vec<Probe>,
    /// Lines.
    pub lines: Vec<Line>,
    /// Published values.
    pub references: Vec<Reference>,
    /// Solver controls.
    pub solver: SolverSettings,
    /// Output controls.
    pub output: OutputSettings,
}

impl Model {
    /// Reads and validates a model file.
    pub fn from_file(path: &Path) -> Result<Self, ModelError> {
        let text = std::fs::read_to_string(path)
            .map_err(|source| ModelError::Io { path: path.display().to_string(), source })?;
        Self::parse(&text)
    }

    /// Parses and validates model-file text.
    pub fn parse(text: &str) -> Result<Self, ModelError> {
        let file: ModelFile = toml::from_str(text).map_err(|e| ModelError::Parse(e.to_string()))?;
        build(file)
    }

    /// True if the problem is linear (no body yields, no contact).
    pub fn is_linear(&self) -> bool {
        is_linear(&self.mesh, &self.materials, &self.indenters, &self.contacts)
    }

    /// Number of degrees of freedom (3 per node, constrained ones included).
    pub fn n_dofs(&self) -> usize {
        self.mesh.n_dofs()
    }
}

fn is_linear(mesh: &Mesh, materials: &[Material], indenters: &[Indenter], contacts: &[PairContact]) -> bool {
    mesh.bodies.iter().all(|b| !materials[b.material].is_plastic()) && indenters.is_empty() && contacts.is_empty()
}

fn finite_positive(key: &str, v: f64) -> Result<f64, ModelError> {
    if v.is_finite() && v > 0.0 { Ok(v) } else { Err(invalid(key, v, "a positive finite number")) }
}

fn finite(key: &str, v: f64) -> Result<f64, ModelError> {
    if v.is_finite() { Ok(v) } else { Err(invalid(key, v, "a finite number")) }
}

fn finite3(key: &str, v: [f64; 3]) -> Result<[f64; 3], ModelError> {
    if v.iter().all(|x| x.is_finite()) { Ok(v) } else { Err(invalid(key, format!("{v:?}"), "three finite numbers")) }
}

/// Checks that names are non-empty, usable in file names, and unique within
/// `group` (entries given as `(key, name)`).
fn unique_names<'a>(group: impl Iterator<Item = (String, &'a String)>) -> Result<(), ModelError> {
    let mut seen: std::collections::HashMap<&String, String> = Default::default();
    for (key, n) in group {
        if n.is_empty() || !n.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c)) {
            return Err(invalid(
                format!("{key}.name"),
                format!("{n:?}"),
                "a non-empty name of letters, digits, '_', '-' or '.' (it is used in file names)",
            ));
        }
        if let Some(other) = seen.insert(n, key.clone()) {
            return Err(invalid(
                format!("{key}.name"),
                format!("{n:?}"),
                format!("a name not already used by {other}"),
            ));
        }
    }
    Ok(())
}

fn keyed<'a, T>(
    key: &'a str,
    items: &'a [T],
    name: impl Fn(&T) -> &String + 'a,
) -> impl Iterator<Item = (String, &'a String)> + 'a {
    items.iter().enumerate().map(move |(i, t)| (format!("{key}[{i}]"), name(t)))
}

/// Rejects keys that belong to another variant than the one chosen.
fn reject_unused(key: &str, chosen: &str, keys: &[(&str, bool)]) -> Result<(), ModelError> {
    match keys.iter().find(|(_, present)| *present) {
        Some((name, _)) => Err(invalid(format!("{key}.{name}"), "(given)", format!("no `{name}` key with {chosen}"))),
        None => Ok(()),
    }
}

fn build(file: ModelFile) -> Result<Model, ModelError> {
    unique_names(keyed("materials", &file.materials, |m| &m.name))?;
    unique_names(keyed("bodies", &file.bodies, |m| &m.name))?;
    unique_names(keyed("loads", &file.loads, |m| &m.name))?;
    unique_names(keyed("probes", &file.probes, |m| &m.name))?;
    unique_names(keyed("lines", &file.lines, |m| &m.name))?;
    // constraints, indenters and contacts all write history_<name>.csv
    unique_names(
        keyed("constraints", &file.constraints, |m| &m.name)
            .chain(keyed("indenters", &file.indenters, |m| &m.name))
            .chain(keyed("contacts", &file.contacts, |m| &m.name)),
    )?;
    if file.bodies.is_empty() {
        return Err(invalid("bodies", "[]", "at least one [[bodies]] table"));
    }
    let materials = file.materials.iter().enumerate().map(|(i, m)| material(i, m)).collect::<Result<Vec<_>, _>>()?;
    let mut bodies = Vec::new();
    for (i, b) in file.bodies.iter().enumerate() {
        bodies.push(body(i, b, &materials)?);
    }
    let mesh = Mesh::new(bodies);
    let mut sections = Vec::with_capacity(mesh.bodies.len());
    for (i, b) in mesh.bodies.iter().enumerate() {
        sections.push(SectionGeometry::new(&b.section, &b.name).map_err(|e| match e {
            ElementError::Distorted { element, det, .. } => invalid(
                format!("bodies[{i}].section"),
                format!("element {element} with Jacobian determinant {det:e}"),
                "convex quadrilaterals listed counter-clockwise in the x–z plane",
            ),
        })?);
    }

    let body_index = |key: String, name: &str| {
        mesh.body_index(name).ok_or_else(|| {
            let names: Vec<&str> = mesh.bodies.iter().map(|b| b.name.as_str()).collect();
            invalid(key, format!("{name:?}"), format!("one of the bodies {names:?}"))
        })
    };

    let mut constraints = Vec::new();
    for (i, c) in file.constraints.iter().enumerate() {
        let key = format!("constraints[{i}]");
        let b = body_index(format!("{key}.body"), &c.body)?;
        let body = &mesh.bodies[b];
        let sel = selection(&format!("{key}.where"), &c.selection, body)?;
        let nodes: Vec<usize> = sel.nodes(body).into_iter().map(|n| n + body.node_offset).collect();
        if nodes.is_empty() {
            return Err(invalid(
                format!("{key}.where"),
                describe_selection(&c.selection),
                format!("a selection that contains nodes of body {:?}", body.name),
            ));
        }
        let mut values = [None; 3];
        for (k, comp) in c.fix.iter().flatten().enumerate() {
            let axis = axis_index(comp)
                .ok_or_else(|| invalid(format!("{key}.fix[{k}]"), format!("{comp:?}"), "\"x\", \"y\" or \"z\""))?;
            values[axis] = Some(0.0);
        }
        if let Some(d) = &c.displacement {
            for (axis, v) in [d.x, d.y, d.z].into_iter().enumerate() {
                if let Some(v) = v {
                    let k = format!("{key}.displacement.{}", ["x", "y", "z"][axis]);
                    if values[axis].is_some() {
                        return Err(invalid(k, v, "a component not also listed in `fix`"));
                    }
                    values[axis] = Some(finite(&k, v)?);
                }
            }
        }
        if values.iter().all(Option::is_none) {
            return Err(invalid(
                key,
                "no `fix` or `displacement`",
                "at least one constrained component (fix = [\"x\", …] or displacement = {z = …})",
            ));
        }
        constraints.push(Constraint { name: c.name.clone(), body: b, nodes, values });
    }
    // one value per constrained DOF: overlapping sets must agree
    let mut given: std::collections::HashMap<usize, (f64, usize)> = Default::default();
    for (i, c) in constraints.iter().enumerate() {
        for &n in &c.nodes {
            for (k, v) in c.values.iter().enumerate() {
                let Some(v) = *v else { continue };
                if let Some(&(w, j)) = given.get(&(3 * n + k))
                    && w != v
                {
                    return Err(invalid(
                        format!("constraints[{i}]"),
                        format!("u_{} = {v} at {:?}", ["x", "y", "z"][k], mesh.coords(n)),
                        format!(
                            "the value {w} that constraints[{j}] prescribes at the same node (overlapping sets must agree)"
                        ),
                    ));
                }
                given.insert(3 * n + k, (v, i));
            }
        }
    }

    let mut loads = Vec::new();
    for (i, l) in file.loads.iter().enumerate() {
        let key = format!("loads[{i}]");
        let b = body_index(format!("{key}.body"), &l.body)?;
        loads.push(load(&key, l, &mesh.bodies[b], &sections[b])?);
    }

    let mut indenters = Vec::new();
    for (i, d) in file.indenters.iter().enumerate() {
        let key = format!("indenters[{i}]");
        let b = body_index(format!("{key}.body"), &d.body)?;
        indenters.push(indenter(&key, d, b, &mesh.bodies[b], &sections[b], &materials)?);
    }

    let mut contacts = Vec::new();
    for (i, c) in file.contacts.iter().enumerate() {
        let key = format!("contacts[{i}]");
        let bm = body_index(format!("{key}.master.body"), &c.master.body)?;
        let bs = body_index(format!("{key}.slave.body"), &c.slave.body)?;
        if bm == bs {
            return Err(invalid(
                format!("{key}.slave.body"),
                format!("{:?}", c.slave.body),
                "a body other than the master body",
            ));
        }
        contacts.push(pair_contact(&key, c, &mesh, bm, bs, &sections, &materials)?);
    }

    let optional_body = |key: String, name: &Option<String>| name.as_ref().map(|n| body_index(key, n)).transpose();
    let mut probes = Vec::new();
    for (i, p) in file.probes.iter().enumerate() {
        let key = format!("probes[{i}]");
        let point = finite3(&format!("{key}.point"), p.point)?;
        let body = optional_body(format!("{key}.body"), &p.body)?;
        if crate::post::locate_in_model(&mesh, body, point).is_empty() {
            return Err(invalid(
                format!("{key}.point"),
                format!("{point:?}"),
                "a point inside a body (or inside the named body)",
            ));
        }
        probes.push(Probe { name: p.name.clone(), point, body });
    }
    let mut lines = Vec::new();
    for (i, l) in file.lines.iter().enumerate() {
        let key = format!("lines[{i}]");
        let points = l.points.unwrap_or(101);
        if !(2..=MAX_COUNT).contains(&points) {
            return Err(invalid(format!("{key}.points"), points, format!("an integer from 2 to {MAX_COUNT}")));
        }
        let plot = l
            .plot
            .iter()
            .flatten()
            .enumerate()
            .map(|(k, q)| {
                Quantity::parse(q)
                    .ok_or_else(|| invalid(format!("{key}.plot[{k}]"), format!("{q:?}"), quantity_names()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        lines.push(Line {
            name: l.name.clone(),
            from: finite3(&format!("{key}.from"), l.from)?,
            to: finite3(&format!("{key}.to"), l.to)?,
            points,
            body: optional_body(format!("{key}.body"), &l.body)?,
            plot,
        });
    }
    let mut references = Vec::new();
    for (i, r) in file.references.iter().enumerate() {
        let key = format!("references[{i}]");
        if !probes.iter().any(|p| p.name == r.probe) {
            return Err(invalid(format!("{key}.probe"), format!("{:?}", r.probe), "the name of a [[probes]] entry"));
        }
        let quantity = Quantity::parse(&r.quantity)
            .ok_or_else(|| invalid(format!("{key}.quantity"), format!("{:?}", r.quantity), quantity_names()))?;
        references.push(Reference {
            probe: r.probe.clone(),
            quantity,
            value: finite(&format!("{key}.value"), r.value)?,
            source: r.source.clone(),
        });
    }

    let linear =
        mesh.bodies.iter().all(|b| !materials[b.material].is_plastic()) && indenters.is_empty() && contacts.is_empty();
    let solver = solver_settings(&file.solver, linear)?;
    let output = OutputSettings { vtu: file.output.vtu.unwrap_or(true), plots: file.output.plots.unwrap_or(true) };
    Ok(Model {
        title: file.title.unwrap_or_else(|| "cufem model".into()),
        description: file.description.unwrap_or_default(),
        materials,
        mesh,
        constraints,
        loads,
        indenters,
        contacts,
        probes,
        lines,
        references,
        solver,
        output,
    })
}

fn quantity_names() -> String {
    let names: Vec<String> = Quantity::all().into_iter().map(Quantity::name).collect();
    format!("one of {}", names.join(", "))
}

fn axis_index(s: &str) -> Option<usize> {
    match s {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    }
}

fn material(i: usize, m: &MaterialFile) -> Result<Material, ModelError> {
    let key = format!("materials[{i}]");
    let young = finite_positive(&format!("{key}.young_modulus"), m.young_modulus)?;
    let nu = m.poisson_ratio;
    if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
        return Err(invalid(format!("{key}.poisson_ratio"), nu, "a number in (−1, 0.5)"));
    }
    let hardening = match &m.plasticity {
        None => None,
        Some(p) => {
            let pk = format!("{key}.plasticity");
            let sy = p.yield_stress.map(|v| finite_positive(&format!("{pk}.yield_stress"), v)).transpose()?;
            let need_sy = || {
                sy.ok_or_else(|| invalid(format!("{pk}.yield_stress"), "(missing)", "the initial yield stress in Pa"))
            };
            let chosen = format!("hardening = {:?}", p.hardening);
            let unused_modulus = ("hardening_modulus", p.hardening_modulus.is_some());
            let unused_table = ("table", p.table.is_some());
            match p.hardening.as_str() {
                "perfect" => reject_unused(&pk, &chosen, &[unused_modulus, unused_table])?,
                "linear" => reject_unused(&pk, &chosen, &[unused_table])?,
                "table" => reject_unused(&pk, &chosen, &[unused_modulus])?,
                _ => {}
            }
            Some(match p.hardening.as_str() {
                "perfect" => Hardening::Perfect { yield_stress: need_sy()? },
                "linear" => {
                    let h = p.hardening_modulus.ok_or_else(|| {
                        invalid(
                            format!("{pk}.hardening_modulus"),
                            "(missing)",
                            "the plastic hardening modulus H in Pa (≥ 0) for hardening = \"linear\"",
                        )
                    })?;
                    if !(h.is_finite() && h >= 0.0) {
                        return Err(invalid(format!("{pk}.hardening_modulus"), h, "a finite number ≥ 0"));
                    }
                    Hardening::Linear { yield_stress: need_sy()?, modulus: h }
                }
                "table" => {
                    let t = p.table.as_ref().ok_or_else(|| {
                        invalid(format!("{pk}.table"), "(missing)", "[[peeq, yield_stress], …] starting at peeq = 0")
                    })?;
                    if t.is_empty() || t[0][0] != 0.0 {
                        return Err(invalid(
                            format!("{pk}.table"),
                            format!("{t:?}"),
                            "a non-empty table whose first point has peeq = 0",
                        ));
                    }
                    for (k, w) in t.windows(2).enumerate() {
                        if !(w[1][0] > w[0][0]) || !(w[1][1] >= w[0][1]) || !w[1][0].is_finite() || !w[1][1].is_finite()
                        {
                            return Err(invalid(
                                format!("{pk}.table[{}]", k + 1),
                                format!("{:?}", w[1]),
                                "strictly increasing peeq and non-decreasing (no softening), finite yield stress",
                            ));
                        }
                    }
                    if !(t[0][1] > 0.0 && t[0][1].is_finite()) {
                        return Err(invalid(
                            format!("{pk}.table[0]"),
                            format!("{:?}", t[0]),
                            "a positive initial yield stress",
                        ));
                    }
                    if let Some(s) = sy
                        && (s - t[0][1]).abs() > 1e-9 * s
                    {
                        return Err(invalid(
                            format!("{pk}.yield_stress"),
                            s,
                            format!("the table's first stress ({}) or no yield_stress", t[0][1]),
                        ));
                    }
                    Hardening::Table {
                        strains: t.iter().map(|r| r[0]).collect(),
                        stresses: t.iter().map(|r| r[1]).collect(),
                    }
                }
                other => {
                    return Err(invalid(
                        format!("{pk}.hardening"),
                        format!("{other:?}"),
                        "\"perfect\", \"linear\" or \"table\"",
                    ));
                }
            })
        }
    };
    Ok(Material::new(m.name.clone(), young, nu, hardening))
}

fn division(key: &str, d: &DivisionFile) -> Result<Vec<f64>, ModelError> {
    division_parts(key, d.from, d.to, d.elements, d.ratio, d.lines.as_ref(), d.segments.as_ref())
}

/// Largest element count per division and per tube side, and sample count
/// per line: far beyond any useful model, small enough to allocate.
const MAX_COUNT: usize = 100_000;

fn count(key: &str, n: usize) -> Result<usize, ModelError> {
    if (1..=MAX_COUNT).contains(&n) { Ok(n) } else { Err(invalid(key, n, format!("an integer from 1 to {MAX_COUNT}"))) }
}

fn division_parts(
    key: &str,
    from: Option<f64>,
    to: Option<f64>,
    elements: Option<usize>,
    ratio: Option<f64>,
    lines: Option<&Vec<f64>>,
    segments: Option<&Vec<SegmentFile>>,
) -> Result<Vec<f64>, ModelError> {
    let forms = [from.is_some() || to.is_some() || elements.is_some(), lines.is_some(), segments.is_some()];
    if ratio.is_some() && !forms[0] {
        return Err(invalid(
            format!("{key}.ratio"),
            "(given)",
            "`ratio` only with {from, to, elements}; segments carry their own ratio",
        ));
    }
    if forms.iter().filter(|f| **f).count() != 1 {
        return Err(invalid(
            key,
            "(ambiguous or missing division)",
            "exactly one of {from, to, elements[, ratio]}, {lines = […]} or {segments = […]}",
        ));
    }
    for (k, seg) in segments.iter().flat_map(|v| v.iter()).enumerate() {
        count(&format!("{key}.segments[{k}].elements"), seg.elements)?;
    }
    if let Some(l) = lines
        && l.len() > MAX_COUNT + 1
    {
        return Err(invalid(
            format!("{key}.lines"),
            format!("{} values", l.len()),
            format!("at most {} values", MAX_COUNT + 1),
        ));
    }
    let div = if let Some(l) = lines {
        Division::Lines(l.clone())
    } else if let Some(s) = segments {
        Division::Segments(
            s.iter()
                .map(|s| Segment { from: s.from, to: s.to, elements: s.elements, ratio: s.ratio.unwrap_or(1.0) })
                .collect(),
        )
    } else {
        let need = |name: &str| {
            invalid(format!("{key}.{name}"), "(missing)", "a value (uniform division needs from, to and elements)")
        };
        let elements = count(&format!("{key}.elements"), elements.ok_or_else(|| need("elements"))?)?;
        let ratio = ratio.unwrap_or(1.0);
        if !(ratio.is_finite() && ratio > 0.0) {
            return Err(invalid(format!("{key}.ratio"), ratio, "a positive number (last/first element length)"));
        }
        let (from, to) = (from.ok_or_else(|| need("from"))?, to.ok_or_else(|| need("to"))?);
        if !(from.is_finite() && to.is_finite() && to > from) {
            return Err(invalid(format!("{key}.to"), to, format!("a finite number greater than from ({from})")));
        }
        Division::Segments(vec![Segment { from, to, elements, ratio }])
    };
    Ok(div.lines(key)?)
}

fn body(i: usize, b: &BodyFile, materials: &[Material]) -> Result<Body, ModelError> {
    let key = format!("bodies[{i}]");
    let material = materials.iter().position(|m| m.name == b.material).ok_or_else(|| {
        let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        invalid(format!("{key}.material"), format!("{:?}", b.material), format!("one of the materials {names:?}"))
    })?;
    let s = &b.section;
    let sk = format!("{key}.section");
    let kind = SectionElementKind::parse(&s.element)
        .ok_or_else(|| invalid(format!("{sk}.element"), format!("{:?}", s.element), "\"L4\", \"L9\" or \"L16\""))?;
    let chosen = format!("shape = {:?}", s.shape);
    let tube_keys = [
        ("origin", s.origin.is_some()),
        ("width", s.width.is_some()),
        ("height", s.height.is_some()),
        ("thickness", s.thickness.is_some()),
        ("around", s.around.is_some()),
        ("along_x", s.along_x.is_some()),
        ("along_z", s.along_z.is_some()),
        ("through", s.through.is_some()),
    ];
    let rect_keys = [("x", s.x.is_some()), ("z", s.z.is_some())];
    let quad_keys = [("points", s.points.is_some()), ("quads", s.quads.is_some())];
    match s.shape.as_str() {
        "rectangle" => reject_unused(&sk, &chosen, &[&tube_keys[..], &quad_keys[..]].concat())?,
        "tube" => reject_unused(&sk, &chosen, &[&rect_keys[..], &quad_keys[..]].concat())?,
        "quads" => reject_unused(&sk, &chosen, &[&rect_keys[..], &tube_keys[..]].concat())?,
        _ => {}
    }
    let section = match s.shape.as_str() {
        "rectangle" => {
            let x = s.x.as_ref().ok_or_else(|| {
                invalid(format!("{sk}.x"), "(missing)", "a division of x, e.g. {from = 0.0, to = 0.5, elements = 18}")
            })?;
            let z = s.z.as_ref().ok_or_else(|| {
                invalid(format!("{sk}.z"), "(missing)", "a division of z, e.g. {from = 0.0, to = 0.3, elements = 6}")
            })?;
            let xl = division(&format!("{sk}.x"), x)?;
            let zl = division(&format!("{sk}.z"), z)?;
            CrossSection::rectangle(kind, &xl, &zl).map_err(|e| rekey(e, &sk))?
        }
        "tube" => {
            let need = |name: &str, v: Option<f64>| {
                v.ok_or_else(|| invalid(format!("{sk}.{name}"), "(missing)", "a positive length in m"))
                    .and_then(|v| finite_positive(&format!("{sk}.{name}"), v))
            };
            let (w, h, t) = (need("width", s.width)?, need("height", s.height)?, need("thickness", s.thickness)?);
            if 2.0 * t >= w.min(h) {
                return Err(invalid(
                    format!("{sk}.thickness"),
                    t,
                    format!("less than half the smaller outer dimension ({})", 0.5 * w.min(h)),
                ));
            }
            let origin = s.origin.unwrap_or([0.0, 0.0]);
            if !origin.iter().all(|v| v.is_finite()) {
                return Err(invalid(format!("{sk}.origin"), format!("{origin:?}"), "two finite numbers [x0, z0]"));
            }
            let through = count(&format!("{sk}.through"), s.through.unwrap_or(1))?;
            let (ax, az) = match (s.around, s.along_x, s.along_z) {
                (Some(n), None, None) => {
                    if (w - h).abs() > 1e-12 * w {
                        return Err(invalid(
                            format!("{sk}.around"),
                            n,
                            "`around` only for square tubes; give along_x and along_z for rectangular ones",
                        ));
                    }
                    if through != 1 || !(8..=MAX_COUNT).contains(&n) || (n - 4) % 4 != 0 {
                        return Err(invalid(
                            format!("{sk}.around"),
                            n,
                            "4 + 4k elements (k ≥ 1: four corner blocks and k per side), with through = 1",
                        ));
                    }
                    ((n - 4) / 4, (n - 4) / 4)
                }
                (None, Some(a), Some(b)) => (count(&format!("{sk}.along_x"), a)?, count(&format!("{sk}.along_z"), b)?),
                _ => {
                    return Err(invalid(
                        sk.clone(),
                        "tube division",
                        "either `around` (square tubes) or both `along_x` and `along_z` (≥ 1)",
                    ));
                }
            };
            CrossSection::tube(kind, origin[0], origin[1], w, h, t, ax, az, through).map_err(|e| rekey(e, &sk))?
        }
        "quads" => {
            let pts = s
                .points
                .as_ref()
                .ok_or_else(|| invalid(format!("{sk}.points"), "(missing)", "a list of [x, z] corner points"))?;
            let quads = s.quads.as_ref().ok_or_else(|| {
                invalid(format!("{sk}.quads"), "(missing)", "a list of [i, j, k, l] counter-clockwise corner indices")
            })?;
            for (k, p) in pts.iter().enumerate() {
                if !p.iter().all(|v| v.is_finite()) {
                    return Err(invalid(format!("{sk}.points[{k}]"), format!("{p:?}"), "two finite numbers"));
                }
            }
            CrossSection::from_quads(kind, pts, quads, &sk)?
        }
        other => {
            return Err(invalid(format!("{sk}.shape"), format!("{other:?}"), "\"rectangle\", \"tube\" or \"quads\""));
        }
    };
    let a = &b.axis;
    let ak = format!("{key}.axis");
    let beam = BeamElementKind::parse(&a.element)
        .ok_or_else(|| invalid(format!("{ak}.element"), format!("{:?}", a.element), "\"B2\", \"B3\" or \"B4\""))?;
    let lines = division_parts(&ak, a.from, a.to, a.elements, a.ratio, a.lines.as_ref(), a.segments.as_ref())?;
    Ok(Body {
        name: b.name.clone(),
        section,
        axis: BeamAxis::from_lines(beam, &lines),
        material,
        node_offset: 0,
        element_offset: 0,
    })
}

/// Prefixes the key of a mesh error raised by a builder that does not know its path.
fn rekey(e: MeshError, prefix: &str) -> ModelError {
    match e {
        MeshError::Invalid { key, value, allowed } => {
            let key = match key.strip_prefix("section") {
                Some(rest) => format!("{prefix}{rest}"),
                None => key,
            };
            ModelError::Invalid { key, value, allowed }
        }
    }
}

fn describe_selection(s: &SelectionFile) -> String {
    let c = |v: &Option<ConditionFile>| match v {
        None => None,
        Some(ConditionFile::Value(a)) => Some(format!("{a}")),
        Some(ConditionFile::Range([a, b])) => Some(format!("[{a}, {b}]")),
    };
    let parts: Vec<String> = [("x", c(&s.x)), ("y", c(&s.y)), ("z", c(&s.z))]
        .into_iter()
        .filter_map(|(n, v)| v.map(|v| format!("{n} = {v}")))
        .collect();
    format!("{{ {} }}", parts.join(", "))
}

fn selection(key: &str, s: &SelectionFile, body: &Body) -> Result<Selection, ModelError> {
    let tol = match s.tolerance {
        Some(t) => finite_positive(&format!("{key}.tolerance"), t)?,
        None => 1e-6 * body.size(),
    };
    let cond = |name: &str, c: &Option<ConditionFile>| -> Result<Option<Condition>, ModelError> {
        match c {
            None => Ok(None),
            Some(ConditionFile::Value(v)) => Ok(Some(Condition::Equal(finite(&format!("{key}.{name}"), *v)?))),
            Some(ConditionFile::Range([a, b])) => {
                if !(a.is_finite() && b.is_finite() && a <= b) {
                    return Err(invalid(format!("{key}.{name}"), format!("[{a}, {b}]"), "[min, max] with min ≤ max"));
                }
                Ok(Some(Condition::Range(*a, *b)))
            }
        }
    };
    Ok(Selection { conditions: [cond("x", &s.x)?, cond("y", &s.y)?, cond("z", &s.z)?], tolerance: tol })
}

fn surface_faces(
    key: &str,
    s: &SelectionFile,
    body: &Body,
    section: &SectionGeometry,
) -> Result<Vec<bc::FaceIntegral>, ModelError> {
    let sel = selection(key, s, body)?;
    let faces = bc::selected_faces(body, &sel);
    if faces.is_empty() {
        return Err(invalid(
            key,
            describe_selection(s),
            format!("a selection containing whole boundary faces of body {:?}", body.name),
        ));
    }
    Ok(faces.iter().map(|f| bc::integrate_face(body, section, f)).collect())
}

fn load(key: &str, l: &LoadFile, body: &Body, section: &SectionGeometry) -> Result<Load, ModelError> {
    let given = [l.force_per_node.is_some(), l.total_force.is_some(), l.traction.is_some(), l.pressure.is_some()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(invalid(key, "load kind", "exactly one of force_per_node, total_force, traction, pressure"));
    }
    let mut forces: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
    if let Some(f) = l.force_per_node {
        let f = finite3(&format!("{key}.force_per_node"), f)?;
        let sel = selection(&format!("{key}.where"), &l.selection, body)?;
        let nodes = sel.nodes(body);
        if nodes.is_empty() {
            return Err(invalid(
                format!("{key}.where"),
                describe_selection(&l.selection),
                format!("a selection that contains nodes of body {:?}", body.name),
            ));
        }
        for n in nodes {
            forces.insert(n + body.node_offset, f);
        }
    } else {
        let faces = surface_faces(&format!("{key}.where"), &l.selection, body, section)?;
        let area: f64 = faces.iter().map(|f| f.area).sum();
        let traction = |f: &bc::FaceIntegral| -> Result<[f64; 3], ModelError> {
            Ok(if let Some(t) = l.traction {
                finite3(&format!("{key}.traction"), t)?
            } else if let Some(p) = l.pressure {
                let p = finite(&format!("{key}.pressure"), p)?;
                f.normal.map(|n| -p * n)
            } else {
                finite3(&format!("{key}.total_force"), l.total_force.unwrap_or_default())?.map(|v| v / area)
            })
        };
        for f in &faces {
            let t = traction(f)?;
            for (&n, &w) in f.nodes.iter().zip(&f.weights) {
                let e = forces.entry(n).or_insert([0.0; 3]);
                for k in 0..3 {
                    e[k] += w * t[k];
                }
            }
        }
    }
    Ok(Load { name: l.name.clone(), nodal_forces: forces.into_iter().collect() })
}

fn penalty(key: &str, penalty: Option<f64>, factor: Option<f64>) -> Result<Penalty, ModelError> {
    match (penalty, factor) {
        (Some(_), Some(_)) => {
            Err(invalid(format!("{key}.penalty"), "both penalty and penalty_factor", "at most one of them"))
        }
        (Some(p), None) => Ok(Penalty::PerArea(finite_positive(&format!("{key}.penalty"), p)?)),
        (None, Some(a)) => Ok(Penalty::Factor(finite_positive(&format!("{key}.penalty_factor"), a)?)),
        (None, None) => Ok(Penalty::Factor(contact::DEFAULT_PENALTY_FACTOR)),
    }
}

fn indenter(
    key: &str,
    d: &IndenterFile,
    b: usize,
    body: &Body,
    section: &SectionGeometry,
    materials: &[Material],
) -> Result<Indenter, ModelError> {
    let faces = surface_faces(&format!("{key}.surface"), &d.surface, body, section)?;
    let young = materials[body.material].young;
    let surface = SurfaceNodes::from_faces(&faces, young);
    let pen = penalty(key, d.penalty, d.penalty_factor)?;
    let tol = 1e-9 * body.size();
    let range = |name: &str, r: Option<[f64; 2]>| -> Result<Option<[f64; 2]>, ModelError> {
        match r {
            Some([a, b]) if a.is_finite() && b.is_finite() && a <= b => Ok(Some([a, b])),
            Some(r) => Err(invalid(format!("{key}.{name}"), format!("{r:?}"), "[min, max] with min ≤ max")),
            None => Ok(None),
        }
    };
    let chosen = format!("shape = {:?}", d.shape);
    let flat_keys = [
        ("normal", d.normal.is_some()),
        ("position", d.position.is_some()),
        ("x", d.x.is_some()),
        ("y", d.y.is_some()),
        ("z", d.z.is_some()),
    ];
    let cyl_keys = [
        ("axis", d.axis.is_some()),
        ("center", d.center.is_some()),
        ("radius", d.radius.is_some()),
        ("length", d.length.is_some()),
    ];
    match d.shape.as_str() {
        "flat" => reject_unused(key, &chosen, &cyl_keys)?,
        "cylinder" => reject_unused(key, &chosen, &flat_keys)?,
        _ => {}
    }
    let shape = match d.shape.as_str() {
        "flat" => {
            let normal = d.normal.as_deref().unwrap_or("");
            let (sign, axis) = match normal {
                "+x" => (1.0, 0),
                "-x" => (-1.0, 0),
                "+y" => (1.0, 1),
                "-y" => (-1.0, 1),
                "+z" => (1.0, 2),
                "-z" => (-1.0, 2),
                _ => {
                    return Err(invalid(
                        format!("{key}.normal"),
                        format!("{normal:?}"),
                        "the direction the punch face looks towards the body: \"+x\", \"-x\", \"+y\", \"-y\", \"+z\" or \"-z\"",
                    ));
                }
            };
            let position = d.position.ok_or_else(|| {
                invalid(
                    format!("{key}.position"),
                    "(missing)",
                    "the coordinate of the punch face along its normal axis (m)",
                )
            })?;
            RigidSurface::Flat {
                axis,
                sign,
                position: finite(&format!("{key}.position"), position)?,
                bounds: [range("x", d.x)?, range("y", d.y)?, range("z", d.z)?],
            }
        }
        "cylinder" => {
            let axis_name = d.axis.as_deref().unwrap_or("");
            let axis = axis_index(axis_name).ok_or_else(|| {
                invalid(
                    format!("{key}.axis"),
                    format!("{axis_name:?}"),
                    "\"x\", \"y\" or \"z\" (direction of the cylinder axis)",
                )
            })?;
            let center = d.center.ok_or_else(|| {
                invalid(format!("{key}.center"), "(missing)", "a point [x, y, z] on the cylinder axis")
            })?;
            let radius = d.radius.ok_or_else(|| invalid(format!("{key}.radius"), "(missing)", "the radius in m"))?;
            RigidSurface::Cylinder {
                axis,
                center: finite3(&format!("{key}.center"), center)?,
                radius: finite_positive(&format!("{key}.radius"), radius)?,
                length: range("length", d.length)?,
            }
        }
        other => {
            return Err(invalid(format!("{key}.shape"), format!("{other:?}"), "\"flat\" or \"cylinder\""));
        }
    };
    // pair each surface node facing the indenter with its closest point
    let nodes: Vec<contact::ContactNode> = surface
        .nodes
        .iter()
        .filter_map(|e| {
            let x0 = body.local_coords(e.0 - body.node_offset);
            shape.reference_gap(x0, tol).map(|(gap0, normal)| contact::ContactNode {
                node: e.0,
                area: e.1,
                penalty: SurfaceNodes::penalty(e, pen),
                gap0,
                normal,
            })
        })
        .collect();
    // a node starting inside the indenter means a wrongly placed or oriented indenter
    if let Some(c) = nodes.iter().find(|c| c.gap0 < -tol) {
        let which = match d.shape.as_str() {
            "flat" => format!("{key}.position / {key}.normal"),
            _ => format!("{key}.center / {key}.radius"),
        };
        return Err(invalid(
            which,
            format!("a surface node at {:?} starts {:.3e} m inside the indenter", model_coords(body, c.node), -c.gap0),
            "an indenter that touches or clears the surface at the start (normal pointing from the indenter to the body)",
        ));
    }
    if nodes.is_empty() {
        return Err(invalid(
            format!("{key}.surface"),
            describe_selection(&d.surface),
            "a surface with nodes facing the indenter (inside a punch's bounds or a cylinder's length)",
        ));
    }
    Ok(Indenter {
        name: d.name.clone(),
        body: b,
        surface: shape,
        displacement: finite3(&format!("{key}.displacement"), d.displacement)?,
        nodes,
    })
}

fn model_coords(body: &Body, node: usize) -> [f64; 3] {
    body.local_coords(node - body.node_offset)
}

fn pair_contact(
    key: &str,
    c: &ContactFile,
    mesh: &Mesh,
    bm: usize,
    bs: usize,
    sections: &[SectionGeometry],
    materials: &[Material],
) -> Result<PairContact, ModelError> {
    let (master_body, slave_body) = (&mesh.bodies[bm], &mesh.bodies[bs]);
    let mf = surface_faces(&format!("{key}.master.where"), &c.master.selection, master_body, &sections[bm])?;
    let sf = surface_faces(&format!("{key}.slave.where"), &c.slave.selection, slave_body, &sections[bs])?;
    let (em, es) = (materials[master_body.material].young, materials[slave_body.material].young);
    let master = SurfaceNodes::from_faces(&mf, em);
    // the softer side sets the stiffness scale
    let slave = SurfaceNodes::from_faces(&sf, es.min(em));
    let pen = penalty(key, c.penalty, c.penalty_factor)?;
    let tol = match c.tolerance {
        Some(t) => finite_positive(&format!("{key}.tolerance"), t)?,
        None => 1e-6 * master_body.size().max(slave_body.size()),
    };
    let coords = |n: usize| mesh.coords(n);
    let mut unpaired = 0;
    let pairs = match &c.pairs {
        None => {
            let (pairs, unmatched) =
                contact::match_pairs(&slave, &master, coords, |e| SurfaceNodes::penalty(e, pen), tol);
            unpaired = unmatched.len();
            pairs
        }
        Some(list) => {
            let mut pairs = Vec::new();
            for (k, [ps, pm]) in list.iter().enumerate() {
                let find = |set: &SurfaceNodes, p: [f64; 3], side: &str| {
                    set.nodes
                        .iter()
                        .find(|e| {
                            let x = mesh.coords(e.0);
                            (0..3).all(|d| (x[d] - p[d]).abs() <= tol)
                        })
                        .copied()
                        .ok_or_else(|| {
                            invalid(
                                format!("{key}.pairs[{k}]"),
                                format!("{p:?}"),
                                format!("a node of the {side} surface at this point (tolerance {tol:e} m)"),
                            )
                        })
                };
                let s = find(&slave, *ps, "slave")?;
                let m = find(&master, *pm, "master")?;
                let one = SurfaceNodes { nodes: vec![m] };
                let (mut p, _) = contact::match_pairs(
                    &SurfaceNodes { nodes: vec![s] },
                    &one,
                    coords,
                    |e| SurfaceNodes::penalty(e, pen),
                    f64::INFINITY,
                );
                pairs.append(&mut p);
            }
            pairs
        }
    };
    if pairs.is_empty() {
        return Err(invalid(
            key,
            "no node pair",
            "slave and master surfaces whose nodes face each other along the master normal (check the `where` selections or the matching tolerance)",
        ));
    }
    Ok(PairContact { name: c.name.clone(), pairs, unpaired })
}

fn solver_settings(s: &SolverFile, linear: bool) -> Result<SolverSettings, ModelError> {
    let increments = s.increments.unwrap_or(if linear { 1 } else { 10 });
    if increments == 0 {
        return Err(invalid("solver.increments", 0, "an integer ≥ 1"));
    }
    let initial = 1.0 / increments as f64;
    let fraction = |name: &str, v: Option<f64>, default: f64| -> Result<f64, ModelError> {
        match v {
            None => Ok(default),
            Some(v) if v.is_finite() && v > 0.0 && v <= 1.0 => Ok(v),
            Some(v) => Err(invalid(format!("solver.{name}"), v, "a number in (0, 1]")),
        }
    };
    let max = fraction("max_increment", s.max_increment, initial)?;
    let min = fraction("min_increment", s.min_increment, 1e-4 * initial.min(max))?;
    let cutback = fraction("cutback_factor", s.cutback_factor, 0.5)?;
    if cutback >= 1.0 {
        return Err(invalid("solver.cutback_factor", cutback, "a number in (0, 1)"));
    }
    let growth = match s.growth_factor {
        None => 1.5,
        Some(g) if g.is_finite() && g >= 1.0 => g,
        Some(g) => return Err(invalid("solver.growth_factor", g, "a number ≥ 1")),
    };
    let tol = |name: &str, v: Option<f64>, default: f64| -> Result<f64, ModelError> {
        match v {
            None => Ok(default),
            Some(v) if v.is_finite() && v > 0.0 && v < 1.0 => Ok(v),
            Some(v) => Err(invalid(format!("solver.{name}"), v, "a number in (0, 1)")),
        }
    };
    if min > max {
        return Err(invalid("solver.min_increment", min, format!("at most max_increment ({max})")));
    }
    let max_iterations = s.max_iterations.unwrap_or(25);
    if max_iterations == 0 {
        return Err(invalid("solver.max_iterations", 0, "an integer ≥ 1"));
    }
    let max_increments = s.max_increments.unwrap_or(1000);
    if max_increments == 0 {
        return Err(invalid("solver.max_increments", 0, "an integer ≥ 1"));
    }
    if s.threads == Some(0) {
        return Err(invalid("solver.threads", 0, "an integer ≥ 1 (or no key: all cores)"));
    }
    Ok(SolverSettings {
        steps: StepSettings {
            initial: initial.min(max),
            max,
            min: min.min(initial),
            cutback_factor: cutback,
            growth_factor: growth,
            easy_iterations: s.easy_iterations.unwrap_or(4),
            max_increments,
        },
        newton: NewtonSettings {
            max_iterations,
            residual_tolerance: tol("residual_tolerance", s.residual_tolerance, 1e-6)?,
            displacement_tolerance: tol("displacement_tolerance", s.displacement_tolerance, 1e-6)?,
            divergence_ratio: 1e6,
        },
        threads: s.threads,
    })
}
