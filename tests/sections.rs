//! Parametric sections and gmsh sections (issue 11): properties against
//! closed forms, the exact arcs of curved walls, and a circular tube
//! cantilever against Timoshenko and Saint-Venant torsion.

use std::f64::consts::PI;

use cufem::analysis::{self, Silent};
use cufem::mesh::SectionProperties;
use cufem::setup::Model;

/// The model text of one elastic body with the given section table and a
/// root clamp and tip load (used for the properties tests too).
fn model(section: &str, length: f64, beam_elements: usize) -> String {
    format!(
        r#"
[[materials]]
name = "al"
young_modulus = 70e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "al"
section = {{ {section} }}
axis = {{ element = "B4", from = 0.0, to = {length}, elements = {beam_elements} }}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = {{ y = {length} }}
total_force = [0.0, 0.0, -100.0]
"#
    )
}

fn properties(section: &str) -> SectionProperties {
    let m = Model::parse(&model(section, 1.0, 2)).unwrap_or_else(|e| panic!("{section}: {e}"));
    m.mesh.bodies[0].section.properties()
}

/// Closed form of a union of disjoint rectangles `[x0, x1] × [z0, z1]`:
/// area, centroid and second moments by the parallel-axis theorem
/// (b h³/12 + A d² per rectangle; Gere & Timoshenko, Mechanics of
/// Materials, ch. 12).
fn rectangles(r: &[[f64; 4]]) -> SectionProperties {
    let a: f64 = r.iter().map(|q| (q[1] - q[0]) * (q[3] - q[2])).sum();
    let xc = r.iter().map(|q| (q[1] - q[0]) * (q[3] - q[2]) * 0.5 * (q[0] + q[1])).sum::<f64>() / a;
    let zc = r.iter().map(|q| (q[1] - q[0]) * (q[3] - q[2]) * 0.5 * (q[2] + q[3])).sum::<f64>() / a;
    let (mut ixx, mut izz, mut ixz) = (0.0, 0.0, 0.0);
    for q in r {
        let (b, h) = (q[1] - q[0], q[3] - q[2]);
        let (dx, dz) = (0.5 * (q[0] + q[1]) - xc, 0.5 * (q[2] + q[3]) - zc);
        ixx += b * h.powi(3) / 12.0 + b * h * dz * dz;
        izz += h * b.powi(3) / 12.0 + b * h * dx * dx;
        ixz += b * h * dx * dz;
    }
    SectionProperties { area: a, centroid: [xc, zc], ixx, izz, ixz, min_det: 0.0 }
}

fn assert_exact(what: &str, got: SectionProperties, exact: SectionProperties) {
    let scale = exact.ixx.max(exact.izz);
    let checks = [
        ("area", got.area, exact.area, exact.area),
        ("x_c", got.centroid[0], exact.centroid[0], exact.area.sqrt()),
        ("z_c", got.centroid[1], exact.centroid[1], exact.area.sqrt()),
        ("Ixx", got.ixx, exact.ixx, exact.ixx),
        ("Izz", got.izz, exact.izz, exact.izz),
        ("Ixz", got.ixz, exact.ixz, scale),
    ];
    for (name, g, e, s) in checks {
        assert!((g - e).abs() <= 1e-10 * s, "{what}: {name} = {g:e}, closed form {e:e}");
    }
    assert!(got.min_det > 0.0, "{what}: an element is inverted");
}

/// I, channel, Z, angle, hat and two-cell box against the rectangles they
/// are made of, for every element kind: exact to 1e-10 (observed ≤ 1e-14).
#[test]
fn straight_walled_profiles_match_closed_forms() {
    let (b, h, tw, tf) = (0.1, 0.2, 0.006, 0.01);
    let dims = "width = 0.1, height = 0.2, web_thickness = 0.006, flange_thickness = 0.01, origin = [0.01, -0.02]";
    let o = [0.01, -0.02];
    let r = |x0: f64, x1: f64, z0: f64, z1: f64| [o[0] + x0, o[0] + x1, o[1] + z0, o[1] + z1];
    let cases: Vec<(&str, String, Vec<[f64; 4]>)> = vec![
        (
            "i_beam",
            dims.into(),
            vec![r(0.0, b, 0.0, tf), r((b - tw) / 2.0, (b + tw) / 2.0, tf, h - tf), r(0.0, b, h - tf, h)],
        ),
        ("channel", dims.into(), vec![r(0.0, b, 0.0, tf), r(0.0, tw, tf, h - tf), r(0.0, b, h - tf, h)]),
        (
            "z_section",
            dims.into(),
            vec![r(b - tw, 2.0 * b - tw, 0.0, tf), r(b - tw, b, tf, h - tf), r(0.0, b, h - tf, h)],
        ),
        ("angle", dims.into(), vec![r(0.0, b, 0.0, tf), r(0.0, tw, tf, h)]),
        (
            "hat",
            format!("{dims}, lip = 0.03"),
            vec![
                r(0.0, 0.03 + tw, 0.0, tf),
                r(0.03 + b - tw, 0.06 + b, 0.0, tf),
                r(0.03, 0.03 + tw, tf, h - tf),
                r(0.03 + b - tw, 0.03 + b, tf, h - tf),
                r(0.03, 0.03 + b, h - tf, h),
            ],
        ),
        (
            "box",
            format!("{dims}, cells = 2"),
            vec![
                r(0.0, b, 0.0, tf),
                r(0.0, b, h - tf, h),
                r(0.0, tw, tf, h - tf),
                r((b - tw) / 2.0, (b + tw) / 2.0, tf, h - tf),
                r(b - tw, b, tf, h - tf),
            ],
        ),
    ];
    for (shape, dims, rects) in &cases {
        for element in ["L4", "L9", "L16"] {
            let section = format!("shape = \"{shape}\", element = \"{element}\", {dims}, through = 2");
            assert_exact(&format!("{shape} {element}"), properties(&section), rectangles(rects));
        }
    }
    // the single-cell box is the rectangular tube of different walls:
    // (B H³ − b h³)/12 with b = B − 2 t_w, h = H − 2 t_f
    let p = properties(&format!("shape = \"box\", element = \"L9\", {dims}"));
    let (bi, hi) = (b - 2.0 * tw, h - 2.0 * tf);
    assert!((p.area / (b * h - bi * hi) - 1.0).abs() < 1e-10);
    assert!((p.ixx / ((b * h.powi(3) - bi * hi.powi(3)) / 12.0) - 1.0).abs() < 1e-10);
    assert!((p.izz / ((h * b.powi(3) - hi * bi.powi(3)) / 12.0) - 1.0).abs() < 1e-10);
}

/// `junction_element`: every straight-walled profile graded towards its
/// junctions keeps its exact geometry (the closed-form properties of the
/// previous test), gains one element row or column of that length at each
/// wall end that meets another wall — `through` elements each — and none
/// at a free edge (I: 4 outstand ends + 2 web ends; channel, Z: 2 + 2;
/// angle: 1 + 1; hat: 2 lip + 2 top-flange + 4 web ends; a two-cell box:
/// 8 flange + 6 web ends), with the wall's element next to the junction
/// exactly that long; a length not shorter than the wall's other elements
/// is refused by its key.
#[test]
fn profiles_graded_towards_their_junctions() {
    let dims = "width = 0.1, height = 0.2, web_thickness = 0.006, flange_thickness = 0.01, through = 2";
    let cases = [("i_beam", "", 6), ("channel", "", 4), ("z_section", "", 4), ("angle", "", 2)];
    let more = [("hat", ", lip = 0.03", 8), ("box", ", cells = 2", 14)];
    for (shape, extra, ends) in cases.into_iter().chain(more) {
        let plain = format!("shape = \"{shape}\", element = \"L9\", {dims}{extra}");
        let graded = format!("{plain}, junction_element = 0.002");
        let section = |s: &str| {
            let m = Model::parse(&model(s, 1.0, 2)).unwrap_or_else(|e| panic!("{s}: {e}"));
            m.mesh.bodies[0].section.clone()
        };
        let (a, b) = (section(&plain), section(&graded));
        assert_exact(shape, b.properties(), a.properties());
        assert_eq!(b.n_elements(), a.n_elements() + 2 * ends, "{shape}");
        // the graded elements: one side 2 mm, the other a wall's thickness
        // or a ply of it (through = 2: 3 or 5 mm)
        let sides = |e: usize| {
            let p: Vec<[f64; 2]> = b.element(e).iter().map(|&n| b.nodes[n]).collect();
            let span = |k: usize| {
                p.iter().map(|q| q[k]).fold(f64::MIN, f64::max) - p.iter().map(|q| q[k]).fold(f64::MAX, f64::min)
            };
            let (x, z) = (span(0), span(1));
            (x.min(z), x.max(z))
        };
        let layer = (0..b.n_elements()).filter(|&e| (sides(e).0 - 0.002).abs() < 1e-12).count();
        assert_eq!(layer, 2 * ends, "{shape}: elements 2 mm long");
    }
    let err = Model::parse(&model(
        &format!("shape = \"i_beam\", element = \"L9\", {dims}, along_flange = 2, junction_element = 0.02"),
        1.0,
        2,
    ))
    .unwrap_err()
    .to_string();
    assert!(err.contains("junction_element") && err.contains("0.02") && err.contains("shorter than"), "{err}");
}

/// Relative errors of area and second moment of a curved section.
fn curved_errors(section: &str, area: f64, inertia: f64) -> (f64, f64) {
    let p = properties(section);
    assert!(p.min_det > 0.0);
    assert!(p.centroid[0].abs() < 1e-12 && p.centroid[1].abs() < 1e-12, "{section}: centroid {:?}", p.centroid);
    assert!((p.ixx - p.izz).abs() < 1e-9 * inertia && p.ixz.abs() < 1e-9 * inertia, "{section}: not isotropic");
    ((p.area / area - 1.0).abs(), (p.ixx / inertia - 1.0).abs())
}

/// Circular tube and solid circle: the nodes lie on the arcs and the
/// isoparametric map interpolates them, so the errors are those of
/// polynomial arcs: measured O(h²) for L4 (a polygon), O(h⁴) for L9 (the
/// quadratic arc's area error superconverges) and L16 (with a constant ~7
/// times smaller). Relative errors of A and I with 16 elements around: L9
/// 4.9e-5 and 9.9e-5, L16 7.3e-6 and 1.5e-5 (L4: 2.6e-2 and 5.0e-2). Bounds:
/// the measured values rounded up.
#[test]
fn curved_sections_converge_to_the_exact_circle() {
    let (ro, t) = (0.02f64, 0.002f64);
    let ri = ro - t;
    let (a_tube, i_tube) = (PI * (ro * ro - ri * ri), PI * (ro.powi(4) - ri.powi(4)) / 4.0);
    let (a_disc, i_disc) = (PI * ro * ro, PI * ro.powi(4) / 4.0);
    for (element, rate) in [("L4", 1.9), ("L9", 3.9), ("L16", 3.9)] {
        let mut previous: Option<(f64, f64)> = None;
        for around in [8, 16, 32] {
            let tube = format!(
                "shape = \"circular_tube\", element = \"{element}\", radius = {ro}, thickness = {t}, around = {around}"
            );
            let disc = format!("shape = \"circle\", element = \"{element}\", radius = {ro}, around = {around}");
            let (ea, ei) = curved_errors(&tube, a_tube, i_tube);
            let (da, di) = curved_errors(&disc, a_disc, i_disc);
            eprintln!("{element} around {around}: tube area {ea:.2e}, I {ei:.2e}; circle area {da:.2e}, I {di:.2e}");
            if let Some((pe, pd)) = previous {
                // halving the element angle divides the error by 2^rate at least
                assert!(pe / ei > 2f64.powf(rate), "{element} tube: {pe:e} → {ei:e}");
                assert!(pd / di > 2f64.powf(rate), "{element} circle: {pd:e} → {di:e}");
            }
            previous = Some((ei, di));
            if element == "L9" && around == 16 {
                // measured 4.93e-5 (area) and 9.86e-5 (I), tube and circle alike
                assert!(ea < 6e-5 && ei < 1.2e-4 && da < 6e-5 && di < 1.2e-4, "L9, 16 around");
            }
            if element == "L16" && around == 16 {
                // measured 7.26e-6 (area) and 1.45e-5 (I)
                assert!(ea < 1e-5 && ei < 2e-5 && da < 1e-5 && di < 2e-5, "L16, 16 around");
            }
        }
    }
}

/// A point inside a curved element but outside the box of its nodes is in
/// the body: the L16 circle with 4 elements around has its rim nodes every
/// 30° from 45°, so the box of the bottom rim element's nodes stops at
/// z = −r sin 75° = −0.966 r while the element's cubic edge reaches
/// −0.998 r (its shape functions at ξ = 0, −1/16, 9/16, 9/16, −1/16, on
/// the nodes' sin 135°, 105°, 75°, 45°). Probes there were refused as
/// outside every body. Just outside the arc stays outside.
#[test]
fn points_between_the_nodes_of_a_curved_edge_are_located() {
    let r = 0.02;
    let section = format!("shape = \"circle\", element = \"L16\", radius = {r}, around = 4");
    let probe =
        |x: f64, z: f64| format!("{}\n[[probes]]\nname = \"p\"\npoint = [{x}, 0.5, {z}]\n", model(&section, 1.0, 2));
    for (x, z) in [(0.0, -0.997 * r), (0.0, 0.997 * r), (0.997 * r, 0.0), (0.2 * r, -0.975 * r)] {
        Model::parse(&probe(x, z)).unwrap_or_else(|e| panic!("({x}, {z}): {e}"));
    }
    let e = Model::parse(&probe(0.0, -1.001 * r)).unwrap_err().to_string();
    assert!(e.contains("probes[0].point") && e.contains("inside a body"), "{e}");
}

/// Circular tube r_o = 20 mm, t = 2 mm, L = 1 m (25 diameters), 10 B4 ×
/// 16 L9 (16 around, 1 through), root clamped, E = 70 GPa, ν = 0.3.
fn tube_cantilever() -> (Model, f64, f64) {
    let (ro, t) = (0.02f64, 0.002f64);
    let section = format!("shape = \"circular_tube\", element = \"L9\", radius = {ro}, thickness = {t}, around = 16");
    (Model::parse(&model(&section, 1.0, 10)).unwrap(), ro, ro - t)
}

/// Mean of `f(u, angle)` at the mid-wall points of the tip section, every 30°.
fn tip_mean(model: &Model, sol: &analysis::Solution, r: f64, f: impl Fn([f64; 3], f64) -> f64) -> f64 {
    let view = sol.fields(model);
    let angles: Vec<f64> = (0..12).map(|k| k as f64 * PI / 6.0).collect();
    let sum: f64 =
        angles.iter().map(|&a| f(view.sample_point(None, [r * a.cos(), 1.0, r * a.sin()]).unwrap().u, a)).sum();
    sum / angles.len() as f64
}

/// Tip deflection under a 100 N end load against Timoshenko,
/// δ = P L³/(3 E I) + P L/(k G A), with the exact I and A of the tube and
/// Cowper's coefficient for a hollow circle (Cowper, J. Appl. Mech. 33,
/// 1966, Table 1): k = 6(1+ν)(1+m²)² / [(7+6ν)(1+m²)² + (20+12ν)m²],
/// m = r_i/r_o. Issue 11 asks for 1 %; measured 0.59 % stiffer (1.0983e-2
/// against 1.1048e-2 m, k = 0.533): the clamped root also restrains the
/// Poisson contraction there.
#[test]
fn circular_tube_cantilever_matches_timoshenko() {
    let (model, ro, ri) = tube_cantilever();
    let (e, nu, p, l) = (70e9, 0.3f64, 100.0, 1.0f64);
    let (area, inertia) = (PI * (ro * ro - ri * ri), PI * (ro.powi(4) - ri.powi(4)) / 4.0);
    let m2 = (ri / ro).powi(2);
    let k = 6.0 * (1.0 + nu) * (1.0 + m2).powi(2) / ((7.0 + 6.0 * nu) * (1.0 + m2).powi(2) + (20.0 + 12.0 * nu) * m2);
    let g = e / (2.0 * (1.0 + nu));
    let exact = p * l.powi(3) / (3.0 * e * inertia) + p * l / (k * g * area);
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let uz = tip_mean(&model, &sol, 0.5 * (ro + ri), |u, _| u[2]);
    let err = (-uz - exact).abs() / exact;
    eprintln!("circular tube tip deflection {:.6e} m, Timoshenko {exact:.6e} m (k = {k:.4}), error {err:.4e}", -uz);
    assert!(err < 0.01, "tip deflection {uz:e} vs {exact:e}: error {err}");
}

/// End torque on the same tube: twist θ = T L/(G J) with the exact
/// J = π(r_o⁴ − r_i⁴)/2 (Saint-Venant; a circular tube does not warp).
/// The torque is the tangential traction τ = T r/J lumped on the tip
/// face's nodes (`∫ N_a dA` times the traction at the node); T is the
/// moment those forces actually apply. The twist is the mean tangential
/// displacement over the mid-wall radius at the tip. Issue 11 asks for 1 %;
/// measured 0.010 % (2.14879e-2 against 2.14858e-2 rad).
#[test]
fn circular_tube_twist_matches_saint_venant() {
    let (mut model, ro, ri) = tube_cantilever();
    let j = PI * (ro.powi(4) - ri.powi(4)) / 2.0;
    let (e, nu, l, torque) = (70e9, 0.3f64, 1.0, 50.0);
    let body = &model.mesh.bodies[0];
    let mut forces = std::collections::BTreeMap::<usize, [f64; 3]>::new();
    for face in cufem::bc::boundary_faces(body) {
        if face.side != cufem::bc::FaceSide::End(true) {
            continue;
        }
        let fi = cufem::bc::integrate_face(body, &face);
        for (&n, &w) in fi.nodes.iter().zip(&fi.weights) {
            let x = model.mesh.coords(n);
            let f = forces.entry(n).or_default();
            f[0] -= w * torque / j * x[2];
            f[2] += w * torque / j * x[0];
        }
    }
    let applied: f64 =
        forces.iter().map(|(&n, f)| model.mesh.coords(n)[0] * f[2] - model.mesh.coords(n)[2] * f[0]).sum();
    model.loads[0].nodal_forces = forces.into_iter().collect();
    let g = e / (2.0 * (1.0 + nu));
    let exact = applied * l / (g * j);
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let rm = 0.5 * (ro + ri);
    // tangential displacement e_θ · u = −sin a u_x + cos a u_z over r
    let twist = tip_mean(&model, &sol, rm, |u, a| (-a.sin() * u[0] + a.cos() * u[2]) / rm);
    let err = (twist - exact).abs() / exact;
    eprintln!(
        "circular tube twist {twist:.6e} rad under T = {applied:.4} N m, T L/(G J) = {exact:.6e} rad, error {err:.4e}"
    );
    assert!((applied / torque - 1.0).abs() < 0.01, "lumped torque {applied}");
    assert!(err < 0.01, "twist {twist:e} vs {exact:e}: error {err}");
}

fn sections_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join("sections")
}

/// Nodes as a sorted list, and elements as sorted lists of their node
/// coordinates: equal for two meshes that differ only in numbering (and in
/// which corner an element starts from).
fn mesh_key(s: &cufem::mesh::CrossSection) -> (Vec<[i64; 2]>, Vec<Vec<[i64; 2]>>) {
    let q = |p: [f64; 2]| p.map(|c| (c * 1e12).round() as i64);
    let mut nodes: Vec<[i64; 2]> = s.nodes.iter().map(|&p| q(p)).collect();
    nodes.sort();
    let mut elements: Vec<Vec<[i64; 2]>> = (0..s.n_elements())
        .map(|e| {
            let mut v: Vec<[i64; 2]> = s.element(e).iter().map(|&n| q(s.nodes[n])).collect();
            v.sort();
            v
        })
        .collect();
    elements.sort();
    (nodes, elements)
}

/// The I-beam built parametrically and the same layout drawn in gmsh
/// (examples/sections/i_beam_twin.geo, seven transfinite rectangles):
/// identical nodes and elements up to numbering, identical properties, and
/// the same cantilever tip deflection to round-off (another node numbering
/// reorders the factorization). The round-off of this solve is about 2e-9
/// relative: the *same* parametric model gives tip deflections 1.8e-9 apart
/// when only the element kernel's order of summation changes (the per-point
/// loop of 9e87594 against the GEMM of the next kernel, measured); the twins
/// differ by 1.0e-9 (5e-10 with the old kernel). Bound 1e-8; a wrong node or
/// element mapping moves the deflection by far more than 1e-6.
#[test]
fn gmsh_twin_of_the_parametric_i_beam_is_identical() {
    let parametric = "shape = \"i_beam\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 0.006, \
                      flange_thickness = 0.01, along_flange = 2, along_web = 4, through = 1";
    let imported = "shape = \"gmsh\", file = \"i_beam_twin.msh\"";
    let limits = cufem::setup::Limits::none();
    let a = Model::parse_in(&model(parametric, 2.0, 4), limits, &sections_dir()).unwrap();
    let b = Model::parse_in(&model(imported, 2.0, 4), limits, &sections_dir()).unwrap();
    let (sa, sb) = (&a.mesh.bodies[0].section, &b.mesh.bodies[0].section);
    assert_eq!(sb.kind, sa.kind);
    assert_eq!(mesh_key(sa), mesh_key(sb));
    let names: Vec<&str> = sb.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["flanges", "web"]);
    let (pa, pb) = (sa.properties(), sb.properties());
    assert!((pa.ixx / pb.ixx - 1.0).abs() < 1e-12 && (pa.area / pb.area - 1.0).abs() < 1e-12);
    let tip = |m: &Model| {
        let sol = analysis::run(m, &Default::default(), &mut Silent).unwrap();
        sol.fields(m).sample_point(None, [0.05, 2.0, 0.1]).unwrap().u[2]
    };
    let (ua, ub) = (tip(&a), tip(&b));
    eprintln!("I-beam cantilever tip u_z: parametric {ua:.9e} m, gmsh {ub:.9e} m");
    assert!((ua / ub - 1.0).abs() < 1e-8, "{ua:e} vs {ub:e}");
}

/// IPE 100 with root fillets from gmsh (examples/sections/ipe100.geo, 178
/// quad9, in mm scaled by 1e-3): the area against the closed form
/// 2 b t_f + (h − 2 t_f) t_w + (4 − π) r² = 1032.3 mm², and the second
/// moments against the tabulated I_y = 171.0 cm⁴ and I_z = 15.92 cm⁴
/// (EN 10365 / ArcelorMittal sales programme, rounded to 4 digits: 0.1 %).
#[test]
fn gmsh_ipe100_matches_the_tables() {
    let section = "shape = \"gmsh\", file = \"ipe100.msh\", scale = 1e-3";
    let m = Model::parse_in(&model(section, 1.0, 1), cufem::setup::Limits::none(), &sections_dir()).unwrap();
    let s = &m.mesh.bodies[0].section;
    let p = s.properties();
    let (h, b, tw, tf, r) = (100e-3f64, 55e-3, 4.1e-3, 5.7e-3, 7e-3);
    let area = 2.0 * b * tf + (h - 2.0 * tf) * tw + (4.0 - PI) * r * r;
    eprintln!(
        "IPE 100: {} L9, A = {:.6e} m² (closed form {area:.6e}), Ixx = {:.5e} m⁴, Izz = {:.5e} m⁴, centroid {:?}",
        s.n_elements(),
        p.area,
        p.ixx,
        p.izz,
        p.centroid
    );
    // measured 7.3e-6: the quadratic (L9) interpolation of the fillet arcs
    assert!((p.area / area - 1.0).abs() < 2e-5, "area {}", p.area);
    assert!((p.ixx / 171.0e-8 - 1.0).abs() < 1e-3, "Ixx {}", p.ixx);
    assert!((p.izz / 15.92e-8 - 1.0).abs() < 1e-3, "Izz {}", p.izz);
    assert!((p.centroid[1] - 0.05).abs() < 1e-12 && p.centroid[0].abs() < 1e-12);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    // the same file without its scale is 100 m across on a 1 m axis: ran
    // without a word (a new-user review); warned by the key that fixes it
    let mm = "shape = \"gmsh\", file = \"ipe100.msh\"";
    let m = Model::parse_in(&model(mm, 1.0, 1), cufem::setup::Limits::none(), &sections_dir()).unwrap();
    let w: Vec<String> = m.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        w.len() == 1
            && w[0].starts_with("bodies[0].section.scale: not given (1): the section spans 100 m across")
            && w[0].contains("if it was drawn in mm, give `scale = 1e-3`"),
        "{w:?}"
    );
}

/// Every mistake in a section table is refused with the key, the value and
/// what is allowed (never a panic).
#[test]
fn section_errors_name_key_value_and_allowed() {
    let dims = "width = 0.1, height = 0.2, web_thickness = 0.006, flange_thickness = 0.01";
    let cases: Vec<(String, &[&str])> = vec![
        // a misspelt shape and a key of another shape are refused by the
        // reader, with the line and the shapes, or the keys of this shape
        (
            "shape = \"octagon\", element = \"L9\"".into(),
            &["line 9", "unknown variant `octagon`, expected one of `rectangle`, `tube`, `quads`, `i_beam`"],
        ),
        (
            format!("shape = \"i_beam\", element = \"L9\", {dims}, radius = 0.1"),
            &["line 9", "unknown field `radius`, expected one of `element`, `origin`, `width`", "`web_thickness`"],
        ),
        (
            "shape = \"channel\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 0.006".into(),
            &["bodies[0].section.flange_thickness = (missing)", "the flange thickness in m"],
        ),
        (
            "shape = \"i_beam\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 0.006, flange_thickness = 0.1"
                .into(),
            &["bodies[0].section.flange_thickness = 0.1", "less than 1/2 of the height"],
        ),
        (
            "shape = \"i_beam\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 0.2, flange_thickness = 0.01"
                .into(),
            &["bodies[0].section.web_thickness = 0.2", "positive clear width"],
        ),
        (format!("shape = \"hat\", element = \"L9\", {dims}"), &["bodies[0].section.lip = (missing)"]),
        (
            "shape = \"box\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 1e-9, flange_thickness = 0.01"
                .into(),
            &["bodies[0].section.web_thickness = 0.000000001", "at least 1e-6 of the profile's size"],
        ),
        (
            "shape = \"circular_tube\", element = \"L9\", radius = 0.02, thickness = 1e-10".into(),
            &["bodies[0].section.thickness = 0.0000000001", "at least 1e-6"],
        ),
        (format!("shape = \"box\", element = \"L9\", {dims}, cells = 0"), &["bodies[0].section.cells = 0", "1 to 1000"]),
        (
            format!("shape = \"box\", element = \"L9\", {dims}, along_web = 0"),
            &["bodies[0].section.along_web = 0", "an integer from 1"],
        ),
        (
            "shape = \"circular_tube\", element = \"L9\", radius = 0.02, thickness = 0.03".into(),
            &["bodies[0].section.thickness = 0.03", "less than the outer radius"],
        ),
        (
            "shape = \"circle\", element = \"L9\", radius = 0.02, around = 10".into(),
            &["bodies[0].section.around = 10", "a multiple of 4"],
        ),
        (
            "shape = \"circle\", element = \"L9\", radius = -0.02".into(),
            &["bodies[0].section.radius = -0.02", "positive"],
        ),
        ("shape = \"circle\", radius = 0.02".into(), &["bodies[0].section.element = (missing)", "\"L16\""]),
        (
            "shape = \"gmsh\", file = \"no_such.msh\"".into(),
            &["bodies[0].section.file = ", "no_such.msh", "the path of a readable gmsh .msh file"],
        ),
        (
            "shape = \"gmsh\", file = \"ipe100.msh\", element = \"L16\"".into(),
            &["bodies[0].section.element = \"L16\"", "L9 (the elements of \"ipe100.msh\")"],
        ),
        (
            "shape = \"gmsh\", file = \"ipe100.msh\", scale = 0.0".into(),
            &["bodies[0].section.scale = 0", "e.g. 1e-3 for a mesh in mm"],
        ),
        ("shape = \"gmsh\"".into(), &["bodies[0].section.file = (missing)"]),
        // a rectangle's hole: its edges on element boundaries, strictly inside
        (
            "shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.03, elements = 3 }, \
             z = { from = 0.0, to = 0.03, elements = 3 }, hole = { x = [0.01, 0.015], z = [0.01, 0.02] }"
                .into(),
            &["bodies[0].section.hole.x = [0.01, 0.015]", "element boundaries of x inside the section", "[0.01, 0.02]"],
        ),
        (
            "shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.03, elements = 3 }, \
             z = { from = 0.0, to = 0.03, elements = 3 }, hole = { x = [0.01, 0.02], z = [0.0, 0.02] }"
                .into(),
            &["bodies[0].section.hole.z = [0, 0.02]", "the walls around the hole at least one element thick"],
        ),
        (
            "shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.03, elements = 3 }, \
             z = { from = 0.0, to = 0.03, elements = 3 }, hole = { x = [0.02, 0.01], z = [0.01, 0.02] }"
                .into(),
            &["bodies[0].section.hole.x = [0.02, 0.01]", "the first the smaller"],
        ),
        ("shape = \"gmsh\", file = \"ipe100.geo\"".into(), &["bodies[0].section.file", "ipe100.geo\" line 1"]),
    ];
    for (section, expected) in &cases {
        let e = Model::parse_in(&model(section, 1.0, 2), cufem::setup::Limits::none(), &sections_dir())
            .err()
            .unwrap_or_else(|| panic!("accepted: {section}"))
            .to_string();
        for x in *expected {
            assert!(e.contains(x), "{section}:\n{e}\nshould contain {x:?}");
        }
    }
}

/// A `rectangle` with a `hole` (a hollow rectangle graded wall by wall):
/// its properties are the outer rectangle's less the hole's, exact to
/// 1e-10 for every element kind (Gere & Timoshenko: the four walls as
/// disjoint rectangles), with walls of unequal thickness and a hole off
/// centre; and the paper's tube written as the rectangle with its inside as
/// the hole is the `tube` section node for node, element for element.
/// A hole one cell too wide or placed on the wrong cells fails the
/// properties (the walls would be 2 mm, not 3, or move the centroid).
#[test]
fn a_rectangle_with_a_hole_is_the_hollow_section() {
    for element in ["L4", "L9", "L16"] {
        // walls 3 mm (left), 6 mm (right), 3 mm (bottom), 9 mm (top), the outside 50 × 60 mm
        let section = format!(
            "shape = \"rectangle\", element = \"{element}\", x = {{ lines = [0.0, 0.003, 0.02, 0.044, 0.05] }}, \
             z = {{ lines = [0.0, 0.001, 0.003, 0.03, 0.051, 0.06] }}, hole = {{ x = [0.003, 0.044], z = [0.003, 0.051] }}"
        );
        let walls = [
            [0.0, 0.05, 0.0, 0.003],
            [0.0, 0.05, 0.051, 0.06],
            [0.0, 0.003, 0.003, 0.051],
            [0.044, 0.05, 0.003, 0.051],
        ];
        assert_exact(&format!("hollow rectangle {element}"), properties(&section), rectangles(&walls));
    }
    // the paper's tube (examples/bending_tube_28L9.toml): 30 × 30 mm, wall 1.5 mm, 28 L9
    let tube = "shape = \"tube\", element = \"L9\", width = 0.03, height = 0.03, thickness = 0.0015, around = 28";
    let lines = "[0.0, 0.0015, 0.006, 0.0105, 0.015, 0.0195, 0.024, 0.0285, 0.03]";
    let rectangle = format!(
        "shape = \"rectangle\", element = \"L9\", x = {{ lines = {lines} }}, z = {{ lines = {lines} }}, \
         hole = {{ x = [0.0015, 0.0285], z = [0.0015, 0.0285] }}"
    );
    let mesh = |s: &str| Model::parse(&model(s, 1.0, 2)).unwrap_or_else(|e| panic!("{s}: {e}")).mesh;
    let (a, b) = (mesh(tube), mesh(&rectangle));
    assert_eq!(b.bodies[0].section.n_elements(), 28);
    assert_eq!(mesh_key(&a.bodies[0].section), mesh_key(&b.bodies[0].section));
}

/// Regions select nodes: `where = { y = …, region = "web" }` takes the
/// nodes of the web's elements only (the web of the parametric I excludes
/// the junction blocks, which belong to the flanges: 4 L9 along the web,
/// one through it, are 3 × 9 = 27 section nodes), the same for the
/// parametric I and its gmsh twin (physical group "web").
#[test]
fn regions_select_nodes() {
    let parametric = "shape = \"i_beam\", element = \"L9\", width = 0.1, height = 0.2, web_thickness = 0.006, \
                      flange_thickness = 0.01, along_flange = 2, along_web = 4, through = 1";
    let imported = "shape = \"gmsh\", file = \"i_beam_twin.msh\"";
    for section in [parametric, imported] {
        let text = model(section, 2.0, 4)
            .replace("where = { y = 2 }\ntotal_force", "where = { y = 2, region = \"web\" }\ntotal_force");
        assert!(text.contains("region"));
        let m = Model::parse_in(&text, cufem::setup::Limits::none(), &sections_dir()).unwrap();
        let nodes: std::collections::BTreeSet<usize> = m.loads[0].nodal_forces.iter().map(|(n, _)| *n).collect();
        assert_eq!(nodes.len(), 27, "{section}");
        for &n in &nodes {
            let [x, y, z] = m.mesh.coords(n);
            assert!((x - 0.05).abs() <= 0.003 + 1e-12 && (0.01 - 1e-12..=0.19 + 1e-12).contains(&z) && y == 2.0);
        }
        let r = m.loads[0].resultant();
        assert!((r[2] + 100.0).abs() < 1e-9, "{r:?}");
    }
    // an unknown region names the ones there are
    let text = model(parametric, 2.0, 4).replace("where = { y = 0.0 }", "where = { y = 0.0, region = \"flange\" }");
    let e = Model::parse_in(&text, cufem::setup::Limits::none(), &sections_dir()).unwrap_err().to_string();
    assert!(
        e.contains("constraints[0].where.region = \"flange\"")
            && e.contains("[\"bottom_flange\", \"web\", \"top_flange\"]"),
        "{e}"
    );
}
