//! The CalculiX input deck (`.inp`, Abaqus-like) of a model: the same
//! bodies, materials, constraints, loads, rigid tools, contacts and load
//! increments, on the hexahedral mesh of [`super::mesh`].
//!
//! * Materials: `*ELASTIC` (anisotropic: engineering constants or the 21
//!   `ANISO` constants in the material axes, with an `*ORIENTATION`; one
//!   section per body and material: [`super::material`]); `*PLASTIC` rows
//!   `(σ_y, ε̄ᵖ)` from the hardening law (perfect: one row; linear: a second
//!   row at ε̄ᵖ = 10; table: its rows). Small strain (no `NLGEOM`), like cufem, unless the model's
//!   `analysis.geometry = "nonlinear"` (then `*STEP, NLGEOM`).
//! * Constraints: `*BOUNDARY` on every hex node inside the constraint's
//!   geometric selection.
//! * Loads: consistent nodal forces (`*CLOAD`) integrated over the hex faces
//!   of the loaded CUF faces (3 × 3 Gauss points per face, a `loads.profile`
//!   taken at each, though [`super::check_supported`] still refuses such a
//!   load); per-node loads on the hex nodes that coincide with the CUF
//!   nodes.
//! * Indenters: rigid bodies (`*RIGID BODY`) moved through their reference
//!   node; the tool force on the body is the reaction there.
//! * Contacts: frictionless `*CONTACT PAIR`, surface to surface, linear
//!   pressure–overclosure with slope `10 E / h` for tools and `E / h` between
//!   bodies (h: the body's smallest hex
//!   edge); the deformable body is the slave side of a tool contact.
//! * Increments: `*STATIC` with the model's first, smallest and largest Δλ
//!   (the step time is the load factor).
//! * Free vibration (`analysis.type = "modal"`): `*DENSITY` in each material
//!   that has one, and instead of the static step a `*FREQUENCY` step asking
//!   for the model's number of modes, with the same (zero) `*BOUNDARY`: the
//!   elastic modes about the undeformed state, CalculiX's consistent mass.
//!   A pre-stressed modal model (loads, prescribed displacements, tools,
//!   contacts) is refused before the deck is written
//!   ([`super::check_supported`]).
//! * Transient dynamics (`analysis.type = "transient"`): one `*DYNAMIC,
//!   DIRECT` step per load step with the load history as amplitudes in time
//!   ([`super::dynamic`]).

use std::fmt::Write as _;

use super::mesh::{HEX_FACES, HEX_NODES, HexMesh, Part};
pub(super) use super::names::list;
pub use super::names::set_name;
use cufem::bc::{Load, LoadKind, Selection};
use cufem::materials::Hardening;
use cufem::quadrature::GaussRule;
use cufem::setup::Model;

/// An element line: its number and nodes, at most 16 entries per line
/// (CalculiX's limit), continued on the next line.
fn element_line(e: usize, nodes: &[usize]) -> String {
    let mut entries = vec![(e + 1).to_string()];
    entries.extend(nodes.iter().map(|n| (n + 1).to_string()));
    entries.chunks(15).map(|c| c.join(", ")).collect::<Vec<_>>().join(",\n")
}

/// Hex nodes of body `b` inside `selection`.
fn selected_nodes(mesh: &HexMesh, b: usize, selection: &Selection) -> Vec<usize> {
    mesh.body_nodes(b).into_iter().filter(|&n| selection.contains(mesh.nodes[n])).collect()
}

/// Consistent nodal forces of a traction field over hex faces:
/// `∫ N_a t(n, x) dA` with 3 × 3 Gauss points per face.
fn face_forces(
    mesh: &HexMesh,
    faces: &[(usize, usize)],
    traction: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
) -> Vec<(usize, [f64; 3])> {
    let g = GaussRule::new(3);
    let kind = mesh.kind;
    let mut out: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
    let mut n = [0.0; 20];
    let mut dn = [[0.0; 20]; 2];
    for &(e, label) in faces {
        let el = &mesh.elements[e];
        let local = &HEX_FACES[label - 1][..if kind.quadratic() { 8 } else { 4 }];
        // face coordinates (a, b) → hex natural point on the face
        let c: Vec<[f64; 3]> = local.iter().map(|&k| HEX_NODES[k]).collect();
        let fixed_axis = (0..3).find(|&d| c.iter().all(|p| p[d] == c[0][d])).unwrap_or(0);
        let (da, db) = ((fixed_axis + 1) % 3, (fixed_axis + 2) % 3);
        for (qa, wa) in g.points.iter().zip(&g.weights) {
            for (qb, wb) in g.points.iter().zip(&g.weights) {
                let mut p = [0.0; 3];
                p[fixed_axis] = c[0][fixed_axis];
                p[da] = *qa;
                p[db] = *qb;
                super::mesh::hex_shapes(kind, p, &mut n);
                // tangents by central differences of the shape functions (exact for these polynomials up to round-off)
                let h = 1e-6;
                for (s, d) in [da, db].into_iter().enumerate() {
                    let (mut pp, mut pm) = (p, p);
                    pp[d] += h;
                    pm[d] -= h;
                    let (mut np, mut nm) = ([0.0; 20], [0.0; 20]);
                    super::mesh::hex_shapes(kind, pp, &mut np);
                    super::mesh::hex_shapes(kind, pm, &mut nm);
                    for a in 0..kind.nodes() {
                        dn[s][a] = (np[a] - nm[a]) / (2.0 * h);
                    }
                }
                let mut x = [0.0; 3];
                let mut t = [[0.0; 3]; 2];
                for a in 0..kind.nodes() {
                    let xa = mesh.nodes[el[a]];
                    for k in 0..3 {
                        x[k] += n[a] * xa[k];
                        t[0][k] += dn[0][a] * xa[k];
                        t[1][k] += dn[1][a] * xa[k];
                    }
                }
                let cr = [
                    t[0][1] * t[1][2] - t[0][2] * t[1][1],
                    t[0][2] * t[1][0] - t[0][0] * t[1][2],
                    t[0][0] * t[1][1] - t[0][1] * t[1][0],
                ];
                let da_ = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt();
                // outward normal: away from the element's centre
                let mut centre = [0.0; 3];
                for a in 0..8 {
                    for k in 0..3 {
                        centre[k] += mesh.nodes[el[a]][k] / 8.0;
                    }
                }
                let outward = (0..3).map(|k| cr[k] * (x[k] - centre[k])).sum::<f64>() >= 0.0;
                let normal = cr.map(|v| if outward { v / da_ } else { -v / da_ });
                let tr = traction(normal, x);
                let w = wa * wb * da_;
                for &a in local {
                    let f = out.entry(el[a]).or_insert([0.0; 3]);
                    for k in 0..3 {
                        f[k] += w * n[a] * tr[k];
                    }
                }
            }
        }
    }
    out.into_iter().collect()
}

/// Nodal forces of a load on the hex mesh.
pub(super) fn load_forces(model: &Model, mesh: &HexMesh, load: &Load) -> Vec<(usize, [f64; 3])> {
    let factor = |x: [f64; 3]| load.profile.map_or(1.0, |p| p.factor(x));
    match &load.kind {
        LoadKind::PerNode { selection, force } => {
            // the hex nodes at the CUF nodes' positions
            let cuf: Vec<[f64; 3]> = load.nodal_forces.iter().map(|(n, _)| model.mesh.coords(*n)).collect();
            let tol = 1e-9 * model.mesh.bodies[load.body].size();
            // a node split at a material interface takes the load once
            selected_nodes(mesh, load.body, selection)
                .into_iter()
                .filter(|n| !mesh.ties.iter().any(|t| t.copy == *n))
                .filter(|&n| cuf.iter().any(|c| (0..3).all(|k| (c[k] - mesh.nodes[n][k]).abs() <= tol)))
                .map(|n| (n, *force))
                .collect()
        }
        // `loads.profile`: the load times the profile's factor at each Gauss point
        LoadKind::Traction { faces, traction } => {
            let hex = mesh.body_faces(model, load.body, faces);
            let t = *traction;
            face_forces(mesh, &hex, move |_, x| t.map(|v| v * factor(x)))
        }
        LoadKind::Pressure { faces, pressure } => {
            let hex = mesh.body_faces(model, load.body, faces);
            let p = *pressure;
            face_forces(mesh, &hex, move |n, x| n.map(|v| -p * factor(x) * v))
        }
    }
}

/// `*PLASTIC` rows `(σ_y, ε̄ᵖ)`.
fn plastic_rows(h: &Hardening) -> Vec<(f64, f64)> {
    match h {
        Hardening::Perfect { yield_stress } => vec![(*yield_stress, 0.0)],
        Hardening::Linear { yield_stress, modulus } => {
            vec![(*yield_stress, 0.0), (yield_stress + modulus * 10.0, 10.0)]
        }
        Hardening::Table { strains, stresses } => stresses.iter().zip(strains).map(|(s, e)| (*s, *e)).collect(),
        // sampled densely where the curve bends (41 points to ε̄ᵖ = 8/b, then
        // the saturated value at 10): within 0.2 % of Q of the exponential
        Hardening::Voce { rate, .. } => (0..=41)
            .map(|k| if k == 41 { 10.0f64.max(9.0 / rate) } else { (k as f64 / 40.0).powi(2) * 8.0 / rate })
            .map(|p| (h.eval(p).0, p))
            .collect(),
    }
}

/// The deck text; of a transient model its model data only, which
/// [`super::dynamic::steps`] completes with the `*DYNAMIC` steps.
pub fn write(model: &Model, mesh: &HexMesh) -> String {
    let mut d = String::new();
    let _ = writeln!(d, "** CalculiX deck exported by cufem {} from \"{}\"", env!("CARGO_PKG_VERSION"), model.title);
    let _ = writeln!(
        d,
        "** {} hexahedra ({}), refine = {}; SI units (m, N, Pa)",
        mesh.elements.len(),
        mesh.kind.name(),
        mesh.refine
    );
    let _ = writeln!(d, "*HEADING\n{}", model.title.replace('\n', " "));
    let _ = writeln!(d, "*NODE");
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(d, "{}, {:.12e}, {:.12e}, {:.12e}", i + 1, p[0], p[1], p[2]);
    }
    elements(&mut d, model, mesh);
    materials(&mut d, model, mesh);
    node_sets(&mut d, model, mesh);
    super::interfaces::equations(&mut d, model, mesh);
    contact_pairs(&mut d, model, mesh);
    match (model.modal, &model.transient) {
        (Some(modal), _) => frequency_step(&mut d, model, mesh, modal.modes),
        // the model data only: `ccx::export` adds the *DYNAMIC steps
        (None, Some(_)) => return d,
        (None, None) => step(&mut d, model, mesh),
    }
    let _ = writeln!(d, "*END STEP");
    d
}

/// `*ELEMENT` blocks: one set per body, one per rigid tool (with its
/// reference node set).
fn elements(d: &mut String, model: &Model, mesh: &HexMesh) {
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let _ = writeln!(d, "*ELEMENT, TYPE={}, ELSET={}", mesh.kind.name(), set_name("B", &body.name));
        for (e, (el, _)) in mesh.elements.iter().zip(&mesh.parts).enumerate().filter(|(_, (_, p))| **p == Part::Body(b))
        {
            let _ = writeln!(d, "{}", element_line(e, el));
        }
    }
    for tool in &mesh.tools {
        let name = &model.indenters[tool.indenter].name;
        let _ = writeln!(d, "*ELEMENT, TYPE=C3D8, ELSET={}", set_name("T", name));
        for e in tool.elements.clone() {
            let _ = writeln!(d, "{}", element_line(e, &mesh.elements[e]));
        }
        let _ = writeln!(d, "*NSET, NSET={}\n{}", set_name("REF", name), tool.reference + 1);
    }
}

/// `*MATERIAL`s, the rigid tools' stiff elastic material, `*SOLID SECTION`s
/// and `*RIGID BODY`s.
fn materials(d: &mut String, model: &Model, mesh: &HexMesh) {
    // materials
    for (m, name) in model.materials.iter().zip(super::material::material_names(model)) {
        let _ = writeln!(d, "*MATERIAL, NAME={name}\n{}", super::material::elastic(m));
        if let Some(rho) = m.density {
            let _ = writeln!(d, "*DENSITY\n{rho:e}");
        }
        if let Some(h) = &m.hardening {
            let _ = writeln!(d, "*PLASTIC");
            for (s, e) in plastic_rows(h) {
                let _ = writeln!(d, "{s:.12e}, {e:.12e}");
            }
        }
    }
    let stiff = model.materials.iter().map(|m| m.young).fold(0.0, f64::max) * 1e3;
    if !mesh.tools.is_empty() {
        let _ = writeln!(d, "*MATERIAL, NAME=RIGID_TOOL\n*ELASTIC\n{stiff:e}, 0.3");
        // `*DYNAMIC` asks every material for a density: a negligible one
        if model.transient.is_some() {
            let light = model.materials.iter().filter_map(|m| m.density).fold(f64::INFINITY, f64::min);
            let _ = writeln!(d, "*DENSITY\n{:e}", 1e-3 * light);
        }
    }
    super::material::orientations(d, model);
    super::material::sections(d, model, mesh);
    for tool in &mesh.tools {
        let name = &model.indenters[tool.indenter].name;
        // an impactor's mass is its tool's: a material of density m / V
        // (CalculiX leaves a MASS element's kinetic energy out of the energy
        // check of its dynamic contact, and then declares divergence)
        let material = match model.indenters[tool.indenter].impactor {
            Some(imp) if model.transient.is_some() => {
                let material = set_name("RIGID", name);
                let density = imp.mass / super::volume::tool_volume(mesh, tool);
                let _ = writeln!(d, "*MATERIAL, NAME={material}\n*ELASTIC\n{stiff:e}, 0.3\n*DENSITY\n{density:.12e}");
                material
            }
            _ => "RIGID_TOOL".to_string(),
        };
        let _ = writeln!(d, "*SOLID SECTION, ELSET={}, MATERIAL={material}", set_name("T", name));
        let _ = writeln!(
            d,
            "*RIGID BODY, ELSET={}, REF NODE={}, ROT NODE={}",
            set_name("T", name),
            tool.reference + 1,
            tool.rotation + 1
        );
    }
}

/// Node sets of the constraints, probes and lines.
fn node_sets(d: &mut String, model: &Model, mesh: &HexMesh) {
    // node sets of the constraints
    for c in &model.constraints {
        let Some(sel) = &c.selection else { continue };
        let nodes = selected_nodes(mesh, c.body, sel);
        let _ = writeln!(d, "*NSET, NSET={}\n{}", set_name("C", &c.name), list(nodes.into_iter()));
    }
    // node sets of the probes and lines: the nodes of the hexes holding them
    let holding = |d: &mut String, name: String, locations: &[cufem::values::Location]| {
        let mut nodes: Vec<usize> =
            locations.iter().flat_map(|l| mesh.elements[mesh.locate(model, l).0].iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let _ = writeln!(d, "*NSET, NSET={name}\n{}", list(nodes.into_iter()));
    };
    for p in &model.probes {
        holding(d, set_name("P", &p.name), &p.locations);
    }
    for l in &model.lines {
        let locations: Vec<cufem::values::Location> = (0..l.points)
            .flat_map(|i| {
                let t = i as f64 / (l.points - 1) as f64;
                let x = [0, 1, 2].map(|k| l.from[k] + t * (l.to[k] - l.from[k]));
                cufem::values::locate_in_model(&model.mesh, l.body, x)
            })
            .collect();
        if !locations.is_empty() {
            holding(d, set_name("L", &l.name), &locations);
        }
    }
}

/// Contact surfaces and interactions: each indenter against its tool,
/// each deformable pair.
fn contact_pairs(d: &mut String, model: &Model, mesh: &HexMesh) {
    // contact surfaces and interactions
    let surface = |d: &mut String, name: &str, faces: &[(usize, usize)]| {
        let _ = writeln!(d, "*SURFACE, NAME={name}, TYPE=ELEMENT");
        for (e, label) in faces {
            let _ = writeln!(d, "{}, S{label}", e + 1);
        }
    };
    for tool in &mesh.tools {
        let ind = &model.indenters[tool.indenter];
        let slave = mesh.body_faces(model, ind.body, &ind.faces);
        let h = mesh.element_size(ind.body);
        let e = cufem::setup::body_young(&model.mesh.bodies[ind.body], &model.materials);
        surface(d, &set_name("SS", &ind.name), &slave);
        surface(d, &set_name("SM", &ind.name), &tool.faces);
        let _ = writeln!(d, "*SURFACE INTERACTION, NAME={}", set_name("SI", &ind.name));
        let _ = writeln!(d, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{:.6e}", 10.0 * e / h);
        let _ = writeln!(
            d,
            "*CONTACT PAIR, INTERACTION={}, TYPE=SURFACE TO SURFACE\n{}, {}",
            set_name("SI", &ind.name),
            set_name("SS", &ind.name),
            set_name("SM", &ind.name)
        );
    }
    for pc in &model.contacts {
        let slave = mesh.body_faces(model, pc.slave.body, &pc.slave.faces);
        let master = mesh.body_faces(model, pc.master.body, &pc.master.faces);
        let h = mesh.element_size(pc.slave.body).min(mesh.element_size(pc.master.body));
        let e = cufem::setup::body_young(&model.mesh.bodies[pc.slave.body], &model.materials)
            .min(cufem::setup::body_young(&model.mesh.bodies[pc.master.body], &model.materials));
        surface(d, &set_name("SS", &pc.name), &slave);
        surface(d, &set_name("SM", &pc.name), &master);
        let _ = writeln!(d, "*SURFACE INTERACTION, NAME={}", set_name("SI", &pc.name));
        // between two deformable bodies 10·E/h made the contact state flip
        // every iteration in ccx 2.20 on the two-cantilever model; E/h converges
        let _ = writeln!(d, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{:.6e}", e / h);
        let _ = writeln!(
            d,
            "*CONTACT PAIR, INTERACTION={}, TYPE=SURFACE TO SURFACE\n{}, {}",
            set_name("SI", &pc.name),
            set_name("SS", &pc.name),
            set_name("SM", &pc.name)
        );
    }
}

/// `*BOUNDARY` of the constraints on their node sets.
fn boundary(d: &mut String, model: &Model) {
    let _ = writeln!(d, "*BOUNDARY");
    for c in &model.constraints {
        if c.selection.is_none() {
            continue;
        }
        for (k, v) in c.values.iter().enumerate() {
            if let Some(v) = v {
                let _ = writeln!(d, "{}, {}, {}, {v:.12e}", set_name("C", &c.name), k + 1, k + 1);
            }
        }
    }
}

/// The free-vibration step (`*END STEP` is the caller's): the `modes`
/// lowest eigenfrequencies about the undeformed state, each mode's
/// displacement in the `.frd` file, the eigenvalue table in the `.dat` file.
fn frequency_step(d: &mut String, model: &Model, mesh: &HexMesh, modes: usize) {
    debug_assert!(mesh.tools.is_empty(), "a modal deck has no tools (check_supported)");
    let _ = writeln!(d, "*STEP\n*FREQUENCY\n{modes}");
    boundary(d, model);
    let _ = writeln!(d, "*NODE FILE\nU");
}

/// The analysis step: increments, controls, boundary conditions, loads and
/// requested output (`*END STEP` is the caller's).
fn step(d: &mut String, model: &Model, mesh: &HexMesh) {
    // the analysis step
    let s = &model.solver;
    let nonlinear = !model.is_linear();
    // large deformation: CalculiX's NLGEOM (total Lagrangian for C3D20R)
    let nlgeom = if model.kinematics.is_nonlinear() { " NLGEOM," } else { "" };
    let _ = writeln!(d, "*STEP,{nlgeom} INC={}", s.steps.max_increments.max(100) * 10);
    // body–body contact: ccx needs a small first increment (about 10 µm of
    // tool travel on the two-cantilever model) to find the contact state
    let initial = if model.contacts.is_empty() { s.steps.initial } else { s.steps.initial.min(0.004) };
    let _ = writeln!(d, "*STATIC\n{:.9e}, 1.0, {:.9e}, {:.9e}", initial, s.steps.min.min(initial), s.steps.max);
    if !model.indenters.is_empty() || !model.contacts.is_empty() {
        // contact: looser field criteria avoid spurious non-convergence at the
        // first contact increments
        let _ = writeln!(d, "*CONTROLS, PARAMETERS=FIELD\n5e-4, 5e-3");
    } else if nonlinear {
        // plasticity alone: converge as tightly as cufem does
        let r = s.newton.residual_tolerance;
        let _ = writeln!(d, "*CONTROLS, PARAMETERS=FIELD\n{:e}, {:e}", r, 10.0 * r);
    }
    boundary(d, model);
    for tool in &mesh.tools {
        let ind = &model.indenters[tool.indenter];
        for k in 0..3 {
            let _ = writeln!(d, "{}, {}, {}, {:.12e}", tool.reference + 1, k + 1, k + 1, ind.displacement[k]);
            let _ = writeln!(d, "{}, {}, {}, 0.", tool.rotation + 1, k + 1, k + 1);
        }
    }
    let forces: Vec<(usize, [f64; 3])> = model.loads.iter().flat_map(|l| load_forces(model, mesh, l)).collect();
    if !forces.is_empty() {
        let _ = writeln!(d, "*CLOAD");
        for (n, f) in forces {
            for (k, v) in f.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                let _ = writeln!(d, "{}, {}, {v:.12e}", n + 1, k + 1);
            }
        }
    }
    let _ = writeln!(
        d,
        "*NODE FILE\nU\n*EL FILE\nS{}",
        if model.materials.iter().any(|m| m.is_plastic()) { ", PEEQ" } else { "" }
    );
    for c in model.constraints.iter().filter(|c| c.selection.is_some()) {
        let _ = writeln!(d, "*NODE PRINT, NSET={}, TOTALS=ONLY\nRF", set_name("C", &c.name));
    }
    for tool in &mesh.tools {
        let _ = writeln!(d, "*NODE PRINT, NSET={}\nRF, U", set_name("REF", &model.indenters[tool.indenter].name));
    }
}
