//! Text reports printed by the CLI.

use cufem::analysis::{IncrementLog, Solution};
use cufem::model::Model;

/// `12345` → `12,345`.
pub(super) fn thousands(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn discretization(model: &Model) -> String {
    let parts: Vec<String> = model
        .mesh
        .bodies
        .iter()
        .map(|b| {
            format!(
                "{} {}{:?} - {}{:?}",
                b.name,
                b.axis.n_elements(),
                b.axis.kind,
                b.section.n_elements(),
                b.section.kind
            )
        })
        .collect();
    parts.join(", ")
}

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
        println!(
            "indenter {}: {}, displacement {:?} m, {} candidate nodes (surface {:.4e} m²)",
            i.name,
            i.surface,
            i.displacement,
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

/// Header of `cufem run`.
pub fn print_header(model: &Model) {
    println!("{}", model.title);
    println!("{} — {} DOF", discretization(model), thousands(model.n_dofs()));
}

/// One log line per converged increment.
pub fn increment_line(log: &IncrementLog) -> String {
    let res: Vec<String> = log.residuals.iter().map(|r| format!("{r:.1e}")).collect();
    let mut line = format!(
        "increment {:>3}  λ = {:.4} (Δλ {:.3e})  {} iterations  residuals [{}]  plastic points {}",
        log.index,
        log.lambda,
        log.dlambda,
        log.iterations,
        res.join(" "),
        log.plastic_points
    );
    if log.max_penetration > 0.0 {
        line.push_str(&format!("  max penetration {:.2e} m", log.max_penetration));
    }
    if let Some(n) = log.negative_pivots.filter(|n| *n > 0) {
        // an indefinite tangent: past a limit or bifurcation point
        line.push_str(&format!("  negative pivots {n}"));
    }
    if log.cutbacks > 0 {
        line.push_str(&format!("  (after {} cutbacks)", log.cutbacks));
    }
    line
}

/// Final report: a table like the paper's and the probe values.
pub fn print_results(model: &Model, solution: &Solution) {
    let iterations: usize = solution.increments.iter().map(|i| i.newton.iterations).sum();
    println!();
    println!("{:<40} {:>10} {:>12} {:>11} {:>10}", "Model", "DOF", "Time (s)", "Increments", "Newton it.");
    println!(
        "{:<40} {:>10} {:>12.2} {:>11} {:>10}",
        format!("cufem 1D ({})", discretization(model)),
        thousands(model.n_dofs()),
        solution.wall_time.as_secs_f64(),
        solution.increments.len(),
        iterations
    );
    if let Some(a) = &solution.adapt {
        println!();
        println!("{:<8} {:>10} {:>12} {:>10}  refined", "cycle", "DOF", "estimate [%]", "time (s)");
        for c in &a.cycles {
            println!(
                "{:<8} {:>10} {:>12.2} {:>10.1}  {}",
                c.cycle,
                thousands(c.dof),
                100.0 * c.estimate,
                c.time_s,
                c.refined
            );
        }
        println!("adaptive run stopped: {}", a.stop);
    }
    let summary = cufem::io::summary(model, solution);
    if !summary.probes.is_empty() {
        println!();
        println!(
            "{:<14} {:<26} {:>12} {:>12} {:>12} {:>12}",
            "probe", "point [m]", "u_z [mm]", "s_yy [MPa]", "s_zz [MPa]", "peeq [-]"
        );
        for p in &summary.probes {
            println!(
                "{:<14} {:<26} {:>12.5} {:>12.3} {:>12.3} {:>12.4e}",
                p.name,
                format!("{:?}", p.point),
                p.u[2] * 1e3,
                p.stress[1] * 1e-6,
                p.stress[2] * 1e-6,
                p.peeq
            );
        }
    }
    if !model.references.is_empty() {
        println!();
        println!("{:<14} {:<16} {:>12} {:>12}  source", "probe", "quantity", "cufem", "reference");
        for r in &model.references {
            let view = solution.fields(model);
            let ours = model
                .probes
                .iter()
                .find(|p| p.name == r.probe)
                .and_then(|p| view.sample_probe(p))
                .map_or(f64::NAN, |s| s.get(r.quantity));
            let scale = r.quantity.display_scale();
            let unit = r.quantity.label();
            let unit = unit.split('[').nth(1).map(|u| format!("[{u}")).unwrap_or_default();
            println!(
                "{:<14} {:<16} {:>12.4} {:>12.4}  {}",
                r.probe,
                format!("{} {unit}", r.quantity.name()),
                ours * scale,
                r.value * scale,
                r.source
            );
        }
    }
    print_resultants(model, &summary);
    if let Some(e) = &summary.error_estimate {
        let largest: Vec<String> =
            e.largest.iter().take(3).map(|l| format!("{} #{} ({:.0} %)", l.body, l.element, 100.0 * l.share)).collect();
        println!(
            "estimated error {:.2} % (energy norm, raw against recovered stresses); largest in {}",
            100.0 * e.relative_energy_norm,
            largest.join(", ")
        );
    }
    print_ply_failure(&summary);
    if let Some(p) = &summary.path {
        let points: Vec<String> = p.limit_points.iter().map(|(i, l)| format!("increment {i} (λ = {l:.5})")).collect();
        let points = if points.is_empty() { "none".to_string() } else { points.join(", ") };
        println!("arc length: limit points {points}; ended by {}", p.end);
    }
    if let Some(m) = &summary.modal {
        let share = |k: usize, v: f64| if m.free_mass[k] > 0.0 { 100.0 * v / m.free_mass[k] } else { 0.0 };
        let of = if m.effective_masses_of == "full_structure" { " of the full structure" } else { "" };
        println!("modal  mode  frequency [Hz]   effective mass [% of the free mass{of}]  x / y / z");
        for (k, (f, e)) in m.frequencies_hz.iter().zip(&m.effective_masses).enumerate() {
            println!(
                "       {:>4}  {f:>14.6e}   {:>6.2} / {:>6.2} / {:>6.2}",
                k + 1,
                share(0, e[0]),
                share(1, e[1]),
                share(2, e[2])
            );
        }
    }
    if let Some(b) = &summary.buckling {
        println!("buckling  mode  load factor   critical load [N]");
        for (k, (f, p)) in b.factors.iter().zip(&b.critical_loads).enumerate() {
            println!("          {:>4}  {f:>11.5e}   [{:.5e}, {:.5e}, {:.5e}]", k + 1, p[0], p[1], p[2]);
        }
    }
}

/// Each failure criterion's largest index and first-failure load factor.
/// Reactions and contact forces, with the full structure's beside in a
/// model with symmetry planes.
fn print_resultants(model: &Model, summary: &cufem::io::Summary) {
    // in a model with symmetry planes, the force on the full structure beside
    let full = |f: &cufem::io::ForceSummary| {
        f.full_structure_force
            .map_or(String::new(), |g| format!(" (full structure [{:.5e}, {:.5e}, {:.5e}] N)", g[0], g[1], g[2]))
    };
    for (c, f) in model.constraints.iter().zip(&summary.reactions) {
        println!("reaction {:<12} [{:.5e}, {:.5e}, {:.5e}] N{}", c.name, f.force[0], f.force[1], f.force[2], full(f));
    }
    for c in &summary.contact {
        println!(
            "contact  {:<12} force on body [{:.5e}, {:.5e}, {:.5e}] N, max penetration {:.3e} m{}",
            c.name,
            c.force[0],
            c.force[1],
            c.force[2],
            c.max_penetration.unwrap_or(0.0),
            full(c)
        );
    }
}

fn print_ply_failure(summary: &cufem::io::Summary) {
    let Some(f) = &summary.ply_failure else { return };
    for c in &f.criteria {
        let w = &c.first_failure_at;
        println!(
            "{:<18} largest index {:.4}; first failure at load factor {:.4} in {} at [{:.4e}, {:.4e}, {:.4e}] m",
            c.criterion, c.largest_index, c.first_failure_load_factor, w.material, w.point[0], w.point[1], w.point[2]
        );
    }
}

/// One line per material: its constants, or an anisotropic one's moduli along its axes and where they point.
fn print_materials(model: &Model) {
    for m in &model.materials {
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
