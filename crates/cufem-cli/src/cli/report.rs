//! Text reports printed by `cufem check` (those of a run are in the
//! library, `cufem::io::report`, shared with the Python package).

use cufem::io::report::thousands;
use cufem::setup::Model;

/// `cufem check`: the model's size and what it contains.
pub fn print_check(model: &Model) {
    println!("{}", model.title);
    if !model.description.is_empty() {
        println!("{}", model.description.trim());
    }
    println!();
    println!("bodies:");
    for b in &model.mesh.bodies {
        // a layered body: its materials in their frames (`t300@90`)
        let names: Vec<&str> = b.materials().into_iter().map(|m| model.materials[m].name.as_str()).collect();
        println!(
            "  {:<12} material {:<12} section {} × {:?} ({} nodes), axis {} × {:?} ({} nodes): {} elements, {} nodes, {} DOF",
            b.name,
            names.join(", "),
            b.section.n_elements(),
            b.section.kind,
            b.section.n_nodes(),
            b.axis.n_elements(),
            b.axis.kind,
            b.axis.n_nodes(),
            thousands(b.n_elements()),
            thousands(b.n_nodes()),
            thousands(3 * b.n_nodes())
        );
    }
    println!(
        "total: {} bodies, {} elements, {} nodes, {} DOF",
        model.mesh.bodies.len(),
        thousands(model.mesh.n_elements()),
        thousands(model.mesh.n_nodes()),
        thousands(model.n_dofs())
    );
    print_sections(model);
    print_materials(model);
    for c in &model.constraints {
        let comps: Vec<String> = c
            .values
            .iter()
            .zip(["x", "y", "z"])
            .filter_map(|(v, n)| v.map(|v| if v == 0.0 { format!("u_{n} = 0") } else { format!("u_{n} = {v:e} m") }))
            .collect();
        println!("constraint {}: {} nodes, {}", c.name, c.nodes.len(), comps.join(", "));
    }
    for l in &model.loads {
        let r = l.resultant();
        println!(
            "load {}: {} nodes, resultant [{:.4e}, {:.4e}, {:.4e}] N",
            l.name,
            l.nodal_forces.len(),
            r[0],
            r[1],
            r[2]
        );
    }
    for i in &model.indenters {
        let area: f64 = i.nodes.iter().map(|n| n.area).sum();
        let motion = indenter_motion(model, i);
        println!(
            "indenter {}: {}, {motion}, {} candidate nodes (surface {:.4e} m²)",
            i.name,
            i.surface,
            i.nodes.len(),
            area
        );
    }
    for c in &model.contacts {
        if let Some(s) = &c.surface {
            println!(
                "contact {} (surface): {} slave nodes, {} slave integration points, {} points without a master face within {:e} m",
                c.name,
                s.slave_nodes.len(),
                s.points.len(),
                s.unpaired,
                s.search_distance
            );
            continue;
        }
        println!(
            "contact {}: {} node pairs, {} slave-surface nodes without a master node",
            c.name,
            c.pairs.len(),
            c.unpaired
        );
    }
    for p in &model.probes {
        println!("probe {}: {:?}", p.name, p.point);
    }
    for l in &model.lines {
        println!("line {}: {:?} → {:?}, {} points", l.name, l.from, l.to, l.points);
    }
    let s = &model.solver;
    println!(
        "solver: Δλ {} (max {}, min {:e}), ≤ {} Newton iterations, tolerances residual {:e}, displacement {:e}",
        s.steps.initial,
        s.steps.max,
        s.steps.min,
        s.newton.max_iterations,
        s.newton.residual_tolerance,
        s.newton.displacement_tolerance
    );
    if let Some(line) = cufem::io::report::time_steps(model) {
        println!("{line}");
    }
}

/// How an indenter moves, for `cufem check`: its displacement, its force or
/// its mass and velocity, with the full structure's force or mass beside
/// the part's share across symmetry planes.
fn indenter_motion(model: &Model, i: &cufem::contact::Indenter) -> String {
    let force = |f: [f64; 3]| match model.symmetry.full(&i.name, f).filter(|full| *full != f) {
        Some(full) => format!("force {f:?} N (its share of the full structure's {full:?} N)"),
        None => format!("force {f:?} N"),
    };
    match (&i.impactor, i.force) {
        (Some(imp), f) => {
            // the part's share of the mass is the velocity's scale to the full structure's
            let speed = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
            let mass = match model.symmetry.full(&i.name, imp.velocity).map(|full| speed(full) / speed(imp.velocity)) {
                Some(copies) if copies > 1.0 => {
                    format!("{} kg (its share of the full structure's {} kg)", imp.mass, imp.mass * copies)
                }
                _ => format!("{} kg", imp.mass),
            };
            let pushed = f.map(|f| format!(", pushed by {}", force(f))).unwrap_or_default();
            format!("impactor of {mass} at {:?} m/s{pushed}", imp.velocity)
        }
        (None, Some(f)) => force(f),
        (None, None) => format!("displacement {:?} m", i.displacement),
    }
}

/// Each body's section properties, integrated over its mesh (`cufem check`).
pub fn print_sections(model: &Model) {
    println!("sections (about the centroid; Ixx = ∫ z̄² dA, Izz = ∫ x̄² dA, Ixz = ∫ x̄ z̄ dA):");
    for b in &model.mesh.bodies {
        let p = b.section.properties();
        println!(
            "  {:<12} A = {:.6e} m², centroid (x, z) = ({:.6e}, {:.6e}) m, Ixx = {:.6e} m⁴, Izz = {:.6e} m⁴, Ixz = {:.6e} m⁴",
            b.name, p.area, p.centroid[0], p.centroid[1], p.ixx, p.izz, p.ixz
        );
        if !b.section.regions.is_empty() {
            let regions: Vec<String> =
                b.section.regions.iter().map(|r| format!("{} ({} elements)", r.name, r.elements.len())).collect();
            println!("  {:<12} regions: {}", "", regions.join(", "));
        }
    }
}

/// Size and memory estimate printed by `cufem check`.
pub fn print_memory(s: &cufem::size::Sizes, limit: Option<u64>) {
    use cufem::size::human_bytes;
    let m = s.memory();
    println!(
        "size: {} equations, nnz(K, lower) {}, nnz(L) {} (symbolic factorization)",
        thousands(s.equations as usize),
        thousands(s.pattern_nnz as usize),
        thousands(s.factor_nnz as usize)
    );
    println!("memory estimate: {} at peak", human_bytes(m.total()));
    for (what, bytes) in &m.parts {
        println!("  {what:<44} {:>12}", human_bytes(*bytes));
    }
    println!("  {:<44} {:>12}", "setup or output transients (larger of)", human_bytes(m.transient));
    if let Some(l) = limit {
        println!("  available: {}", human_bytes(l));
    }
}

/// One line per material an element uses: its constants, or an
/// anisotropic one's moduli along its axes and where they point. A
/// material whose turned copies (`name@angle`, per ply or zone) are used
/// instead is left out (a new-user review: the unturned base was listed
/// as if some element had it); one no element uses is said to be unused.
fn print_materials(model: &Model) {
    let used: std::collections::BTreeSet<usize> = model.mesh.bodies.iter().flat_map(|b| b.materials()).collect();
    for (k, m) in model.materials.iter().enumerate() {
        if !used.contains(&k) {
            let turned = |j: &usize| model.materials[*j].name.strip_prefix(&m.name).is_some_and(|r| r.starts_with('@'));
            if !used.iter().any(turned) {
                println!("material {}: not used by any element", m.name);
            }
            continue;
        }
        let plastic = match &m.hardening {
            None => "elastic".to_string(),
            Some(h) => format!("von Mises, {h}"),
        };
        match &m.anisotropic {
            None => println!("material {}: E = {:.4} GPa, ν = {}, {}", m.name, m.young * 1e-9, m.poisson, plastic),
            Some(c) => {
                // the moduli along the material axes, and where the axes point
                let s = cufem::materials::anisotropic::invert(c).unwrap_or_default();
                let [e1, e2, e3] = [0, 1, 2].map(|i| 1e-9 / s[i][i]);
                let [a1, _, a3] = m.frame.axes;
                println!(
                    "material {}: anisotropic, E1 = {e1:.4}, E2 = {e2:.4}, E3 = {e3:.4} GPa, axis 1 = {a1:.3?}, \
                     axis 3 = {a3:.3?}, elastic{}",
                    m.name,
                    if m.strengths.is_some() { ", with strengths" } else { "" }
                );
            }
        }
    }
}
