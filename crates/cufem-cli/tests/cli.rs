//! The `cufem` binary: a shipped example through `run`, its outputs read
//! back (JSON, CSV, and the VTU decoded from the VTK format spec), and clear errors on bad input.

use std::path::{Path, PathBuf};
use std::process::Command;

fn cufem() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cufem"))
}

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli_{name}"));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn example(name: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name)
}

/// Signed volume of a linear hexahedron by splitting it into 6 tetrahedra.
/// Values of a VTK XML `binary` DataArray with `header_type="UInt64"`:
/// base64 of an 8-byte little-endian byte count followed by the raw data.
fn decode(ty: &str, text: &str) -> Vec<f64> {
    use base64::Engine as _;
    let raw = base64::engine::general_purpose::STANDARD.decode(text.trim()).unwrap();
    let n = u64::from_le_bytes(raw[..8].try_into().unwrap()) as usize;
    let data = &raw[8..8 + n];
    let width = match ty {
        "Float64" | "Int64" | "UInt64" => 8,
        "Float32" | "Int32" | "UInt32" => 4,
        "UInt8" | "Int8" => 1,
        t => panic!("type {t}"),
    };
    data.chunks_exact(width)
        .map(|b| match ty {
            "Float64" => f64::from_le_bytes(b.try_into().unwrap()),
            "Int64" => i64::from_le_bytes(b.try_into().unwrap()) as f64,
            "UInt64" => u64::from_le_bytes(b.try_into().unwrap()) as f64,
            "Float32" => f32::from_le_bytes(b.try_into().unwrap()) as f64,
            "Int32" => i32::from_le_bytes(b.try_into().unwrap()) as f64,
            "UInt32" => u32::from_le_bytes(b.try_into().unwrap()) as f64,
            _ => b[0] as f64,
        })
        .collect()
}

fn hex_volume(p: &[[f64; 3]; 8]) -> f64 {
    let tet = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| {
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
        (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]))
            / 6.0
    };
    // standard decomposition along the 0–6 diagonal
    [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]]
        .iter()
        .map(|t| tet(p[t[0]], p[t[1]], p[t[2]], p[t[3]]))
        .sum()
}

#[test]
fn cantilever_example_runs_and_its_outputs_read_back() {
    let out = out_dir("cantilever_cli");
    let started = std::time::Instant::now();
    let status = cufem()
        .args([
            "run",
            example("cantilever_timoshenko.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .status()
        .unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(status.success());

    // summary.json contract
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["dof"], 1200);
    // the run's own wall time, in seconds: positive and within the time the
    // process took as seen from here (milliseconds or a clock read twice
    // from the wrong start would fail one or the other)
    let wall = summary["wall_time_s"].as_f64().unwrap();
    assert!(wall > 0.0 && wall <= elapsed, "wall_time_s {wall} s, process {elapsed} s");
    let probe = &summary["probes"][0];
    assert_eq!(probe["name"], "tip");
    let uz = probe["u"][2].as_f64().unwrap();
    // Timoshenko 5.759e-4 m (see the example's header); 2 % for 5 B4 × 2×2 L9
    assert!((uz + 5.759e-4).abs() < 0.02 * 5.759e-4, "{uz}");
    assert_eq!(probe["stress"].as_array().unwrap().len(), 6);
    assert_eq!(probe["peeq"].as_f64().unwrap(), 0.0);
    let r = &summary["reactions"][0];
    assert_eq!(r["name"], "root");
    assert!((r["force"][2].as_f64().unwrap() - 1000.0).abs() < 1e-9 * 1000.0);

    // line CSV header contract
    let csv = std::fs::read_to_string(out.join("line_top.csv")).unwrap();
    assert!(csv.starts_with("s,x,y,z,u_x,u_y,u_z,s_xx,s_yy,s_zz,s_xy,s_xz,s_yz,von_mises,peeq"));
    assert_eq!(csv.lines().count(), 102);
    assert!(out.join("line_top_s_yy.png").exists());

    // the VTU, read back by an XML parser and a decoder written from the VTK
    // file-format spec (header_type, byte order, base64 `binary` arrays)
    let text = std::fs::read_to_string(out.join("result.vtu")).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let file = doc.root_element();
    assert_eq!(file.attribute("type"), Some("UnstructuredGrid"));
    assert_eq!(file.attribute("byte_order"), Some("LittleEndian"));
    // VTK >= 9.1 renumbers the Lagrange hexahedra of files older than 2.1
    // from VTK 8's order, which the file holds; meshio reads 0.1 and 1.0
    assert_eq!(file.attribute("version"), Some("1.0"));
    let piece = file.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
    // 20 elements (5 B4 × 4 L9), 36 points each, one VTK Lagrange
    // hexahedron each (`output.vtu_cells = "lagrange"`)
    assert_eq!(piece.attribute("NumberOfPoints"), Some("720"));
    assert_eq!(piece.attribute("NumberOfCells"), Some("20"));
    let array = |parent: &str, name: Option<&str>| -> Vec<f64> {
        let p = piece.descendants().find(|n| n.has_tag_name(parent)).unwrap();
        let a = p
            .descendants()
            .find(|n| n.has_tag_name("DataArray") && (name.is_none() || n.attribute("Name") == name))
            .unwrap_or_else(|| panic!("missing array {name:?} in {parent}"));
        decode(a.attribute("type").unwrap(), a.text().unwrap_or(""))
    };
    let points = array("Points", None);
    assert_eq!(points.len(), 3 * 720);
    let connectivity = array("Cells", Some("connectivity"));
    let offsets = array("Cells", Some("offsets"));
    assert_eq!(offsets, (1..=20).map(|c| 36.0 * c as f64).collect::<Vec<_>>());
    assert_eq!(array("Cells", Some("types")), vec![72.0; 20]);
    // orders along (x, y, z): L9 quadratic in the section, B4 cubic along y
    assert_eq!(array("CellData", Some("HigherOrderDegrees")), [2.0, 3.0, 2.0].repeat(20));
    // a Lagrange hexahedron lists its 8 corners first, as a linear one: the
    // straight-edged elements' volumes
    let mut volume = 0.0;
    for c in 0..offsets.len() {
        let ids = &connectivity[36 * c..36 * c + 8];
        let mut p = [[0.0; 3]; 8];
        for (k, &id) in ids.iter().enumerate() {
            let id = id as usize;
            p[k] = [points[3 * id], points[3 * id + 1], points[3 * id + 2]];
        }
        let v = hex_volume(&p);
        assert!(v > 0.0, "cell {c} has volume {v}");
        volume += v;
    }
    assert!((volume - 0.01).abs() < 1e-12, "total volume {volume}");
    let point_data = piece.descendants().find(|n| n.has_tag_name("PointData")).unwrap();
    let names: Vec<&str> = point_data.children().filter_map(|n| n.attribute("Name")).collect();
    for n in ["displacement", "s_yy", "von_mises", "peeq", "contact_pressure", "contact_gap", "contact_force"] {
        assert!(names.contains(&n), "missing array {n} in {names:?}");
    }
    // the largest downward displacement in the file is the tip deflection
    let disp = array("PointData", Some("displacement"));
    let min_uz = disp.iter().skip(2).step_by(3).fold(f64::INFINITY, |a, &b| a.min(b));
    assert!((min_uz - uz).abs() < 0.01 * uz.abs(), "{min_uz} vs {uz}");
}

#[test]
fn check_prints_the_model_size() {
    let out = cufem().args(["check", example("cantilever_timoshenko.toml").to_str().unwrap()]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("1,200 DOF") && text.contains("20 elements") && text.contains("400 nodes"), "{text}");
    // each indenter with its motion: prescribed, or an impactor's mass and velocity
    let out = cufem().args(["check", example("tube_drop_weight.toml").to_str().unwrap()]).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("indenter support_left: ") && text.contains("displacement [0.0, 0.0, 0.0] m"), "{text}");
    assert!(text.contains("impactor of 2 kg at [0.0, 0.0, -1.0] m/s"), "{text}");
    // the materials the elements use: a laminate's turned plies, not the
    // unturned base material no element has (a new-user review); a material
    // nothing uses is said to be unused
    let laminate = std::fs::read_to_string(example("laminate_drop_weight.toml")).unwrap();
    let spare = laminate.replacen(
        "[[materials]]",
        "[[materials]]\nname = \"spare\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\n\n[[materials]]",
        1,
    );
    let dir = out_dir("check_materials");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("spare.toml");
    std::fs::write(&path, spare).unwrap();
    let out = cufem().args(["check", path.to_str().unwrap()]).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let materials: Vec<&str> =
        text.lines().filter(|l| l.starts_with("material ")).map(|l| &l[..l.find(':').unwrap()]).collect();
    assert_eq!(materials, ["material spare", "material cfrp@0", "material cfrp@90"], "{text}");
    assert!(text.contains("material spare: not used by any element"), "{text}");
}

/// Bad input: exit code 1 and a message naming the key, the value and what is allowed.
#[test]
fn bad_input_is_reported_with_key_value_and_allowed_values() {
    let base = std::fs::read_to_string(example("cantilever_timoshenko.toml")).unwrap();
    let dir = out_dir("bad_inputs");
    std::fs::create_dir_all(&dir).unwrap();
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            base.replace("poisson_ratio = 0.3", "poisson_ratio = 0.7"),
            vec!["materials[0].poisson_ratio", "0.7", "(−1, 0.4999]"],
        ),
        (
            base.replace("element = \"L9\"", "element = \"L8\""),
            // a word outside the list: refused by the reader, with the line and the allowed words
            vec!["line 20", "unknown variant `L8`, expected one of `L4`, `L9`, `L16`"],
        ),
        (
            base.replace("element = \"B4\"", "element = \"B5\""),
            vec!["line 21", "unknown variant `B5`, expected one of `B2`, `B3`, `B4`"],
        ),
        (
            format!("{base}\n[output]\nvtu_cells = \"quadratic\"\n"),
            vec!["vtu_cells = \"quadratic\"", "unknown variant `quadratic`, expected `lagrange` or `linear`"],
        ),
        (
            base.replace("material = \"aluminium\"", "material = \"steel\""),
            vec!["bodies[0].material", "steel", "aluminium"],
        ),
        (base.replace("where = { y = 0.0 }", "where = { y = -1.0 }"), vec!["constraints[0].where", "y = -1", "nodes"]),
        (
            base.replace("fix = [\"x\", \"y\", \"z\"]", "fix = [\"x\", \"w\"]"),
            vec!["TOML parse error at line", "unknown variant `w`, expected one of `x`, `y`, `z`"],
        ),
        (
            // (density is a key since free vibration; a material key that does not exist)
            base.replace("young_modulus = 70e9", "young_modulus = 70e9\nthermal_expansion = 2.3e-5"),
            vec!["thermal_expansion", "unknown field"],
        ),
        (
            base.replace("elements = 5", "elements = 0"),
            vec!["bodies[0].axis.elements = 0", "an integer from 1 to 100000"],
        ),
        (
            base.replace("point = [0.05, 1.0, 0.05]", "point = [0.05, 2.0, 0.05]"),
            vec!["probes[0].point", "inside a body"],
        ),
        (
            base.replace("plot = [\"u_z\"]", "plot = [\"uz\"]"),
            vec![
                "TOML parse error at line",
                "lines[0].plot: invalid value: text \"uz\", expected one of u_x, u_y, u_z",
            ],
        ),
        (
            base.replace(
                "z = { from = 0.0, to = 0.1, elements = 2 } }",
                "z = { from = 0.0, to = 0.1, elements = 2 }, thickness = 0.01 }",
            ),
            // a key of another shape: refused by the reader, which lists the keys of this one
            vec!["line 20", "unknown field `thickness`, expected one of `element`, `x`, `z`"],
        ),
        (
            format!(
                "{base}\n[[constraints]]\nname = \"root\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\nfix = [\"x\"]\n"
            ),
            vec!["constraints[1].name", "\"root\"", "already used by constraints[0]"],
        ),
        (
            format!(
                "{base}\n[[constraints]]\nname = \"a\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\ndisplacement = {{ z = 0.001 }}\n\
                 [[constraints]]\nname = \"b\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\ndisplacement = {{ z = 0.002 }}\n"
            ),
            vec!["constraints[2]", "u_z = 0.002", "constraints[1]"],
        ),
        (base.replace("name = \"tip\"\nbody", "name = \"tip/1\"\nbody"), vec!["loads[0].name", "tip/1", "file names"]),
        (
            base.replace("elements = 5", "elements = 9000000000000000000"),
            vec!["bodies[0].axis.elements", "an integer from 1 to 100000"],
        ),
        (base.replace("points = 51", "points = 9000000000000000000"), vec!["lines[0].points", "from 2 to 100000"]),
        // a line of zero length sampled one point 51 times (a new-user review)
        (
            base.replace("to = [0.05, 1.0, 0.05]", "to = [0.05, 0.0, 0.05]"),
            vec!["lines[0].to = [0.05, 0.0, 0.05]", "a point other than `from`"],
        ),
    ];
    for (k, (text, needles)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{k}.toml"));
        std::fs::write(&path, text).unwrap();
        let out = cufem().args(["check", path.to_str().unwrap()]).output().unwrap();
        assert_eq!(out.status.code(), Some(1), "case {k} should fail");
        let err = String::from_utf8(out.stderr).unwrap();
        for n in needles {
            assert!(err.contains(n), "case {k}: {n:?} not in {err:?}");
        }
        assert!(!err.contains("panicked"), "case {k} panicked: {err}");
    }
    let out = cufem().args(["run", "/nonexistent/model.toml"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8(out.stderr).unwrap().contains("/nonexistent/model.toml"));
}

/// `output.gauss_points = true` writes the raw Gauss-point values: one
/// vertex per integration point (L9 × B4: 9 × 4 per element) at its physical
/// position, with the stress of the kernel. On the Timoshenko cantilever the
/// bending stress there is beam theory's P (L − y)(z − h/2)/I away from the
/// clamp and the load (within 3 % of the section's peak; ν = 0.3 adds a
/// little shear-lag and Poisson stress, the rest is discretization).
#[test]
fn gauss_point_vtu_holds_the_kernel_stresses() {
    let text = std::fs::read_to_string(example("cantilever_timoshenko.toml")).unwrap();
    let dir = out_dir("gauss_vtu");
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.toml");
    std::fs::write(&model, format!("{text}\n[output]\ngauss_points = true\n")).unwrap();
    let out = dir.join("out");
    let run =
        cufem().args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let text = std::fs::read_to_string(out.join("gauss.vtu")).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let piece = doc.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
    assert_eq!(piece.attribute("NumberOfPoints"), Some("720"));
    let array = |parent: &str, name: Option<&str>| -> Vec<f64> {
        let p = piece.descendants().find(|n| n.has_tag_name(parent)).unwrap();
        let a = p
            .descendants()
            .find(|n| n.has_tag_name("DataArray") && (name.is_none() || n.attribute("Name") == name))
            .unwrap();
        decode(a.attribute("type").unwrap(), a.text().unwrap_or(""))
    };
    let points = array("Points", None);
    let syy = array("PointData", Some("s_yy"));
    let types = array("Cells", Some("types"));
    assert!(types.iter().all(|&t| t == 1.0), "VTK_VERTEX cells");
    let i = 0.1f64.powi(4) / 12.0;
    let peak = 1000.0 * 1.0 * 0.05 / i;
    let mut checked = 0;
    for (p, s) in points.chunks(3).zip(&syy) {
        assert!((0.0..=0.1).contains(&p[0]) && (0.0..=1.0).contains(&p[1]) && (0.0..=0.1).contains(&p[2]));
        if (0.3..=0.7).contains(&p[1]) {
            let beam = 1000.0 * (1.0 - p[1]) * (p[2] - 0.05) / i;
            assert!((s - beam).abs() < 0.03 * peak, "σ_yy {s} vs {beam} at {p:?}");
            checked += 1;
        }
    }
    assert!(checked > 100);
}

/// `cufem check` prints each section's integrated properties; `--plot`
/// draws every section mesh to a PNG in `--out`.
#[test]
fn check_prints_section_properties_and_plots_them() {
    let out = out_dir("check_plot");
    let run = cufem()
        .args(["check", example("ibeam_roller.toml").to_str().unwrap(), "--plot", "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let text = String::from_utf8_lossy(&run.stdout);
    // 40 × 60 mm I, web 2 mm, flanges 3 mm: A = 2·40·3 + 54·2 = 348 mm²,
    // Ixx = (40·60³ − 38·54³)/12 = 221,364 mm⁴, centroid at mid-height
    assert!(text.contains("A = 3.480000e-4 m²"), "{text}");
    assert!(text.contains("Ixx = 2.213640e-7 m⁴"), "{text}");
    assert!(text.contains("regions: bottom_flange (5 elements), web (6 elements), top_flange (5 elements)"), "{text}");
    let png = out.join("ibeam_roller_section_beam.png");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG", "{}", png.display());
}

/// A section in two parts — touching at a corner only (a hinge line along
/// the axis) or not at all, listed as quads or read from a gmsh file — was
/// accepted and the run failed at λ = 0 after 25 iterations. It is refused
/// at validation, naming the section, the number of parts and a point of
/// each, and what is allowed.
#[test]
fn sections_in_separate_parts_are_refused() {
    let base = std::fs::read_to_string(example("cantilever_timoshenko.toml")).unwrap();
    let base =
        base.split("[[lines]]").next().unwrap().replace("point = [0.05, 1.0, 0.05]", "point = [0.025, 1.0, 0.025]");
    let rectangle = "section = { shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 } }";
    assert!(base.contains(rectangle));
    let dir = out_dir("separate_parts");
    std::fs::create_dir_all(&dir).unwrap();
    // two 5 cm squares 1 cm apart, as a gmsh 2.2 file of two quad4
    let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n1 0 0 0\n2 0.05 0 0\n3 0.05 0.05 0\n4 0 0.05 0\n\
               5 0.06 0 0\n6 0.1 0 0\n7 0.1 0.05 0\n8 0.06 0.05 0\n$EndNodes\n$Elements\n2\n\
               1 3 2 1 1 1 2 3 4\n2 3 2 1 1 5 6 7 8\n$EndElements\n";
    std::fs::write(dir.join("apart.msh"), msh).unwrap();
    let cases = [
        (
            "corner",
            "section = { shape = \"quads\", element = \"L9\", points = [[0.0, 0.0], [0.05, 0.0], [0.05, 0.05], [0.0, 0.05], \
             [0.1, 0.05], [0.1, 0.1], [0.05, 0.1]], quads = [[0, 1, 2, 3], [2, 4, 5, 6]] }",
            "element 1 at x = 0.075, z = 0.075",
        ),
        (
            "apart",
            "section = { shape = \"quads\", element = \"L4\", points = [[0.0, 0.0], [0.05, 0.0], [0.05, 0.05], [0.0, 0.05], \
             [0.06, 0.0], [0.1, 0.0], [0.1, 0.05], [0.06, 0.05]], quads = [[0, 1, 2, 3], [4, 5, 6, 7]] }",
            "element 1 at x = 0.08, z = 0.025",
        ),
        ("gmsh", "section = { shape = \"gmsh\", file = \"apart.msh\" }", "element 1 at x = 0.08, z = 0.025"),
    ];
    for (name, section, point) in cases {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, base.replace(rectangle, section)).unwrap();
        let out = cufem().args(["check", path.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        for needle in
            ["bodies[0].section = 2 separate parts", "1 element (first: element 0 at x = 0.025, z = 0.025)", point]
        {
            assert!(err.contains(needle), "{name}: {needle:?} not in {err}");
        }
        assert!(err.contains("connected through shared edges") && err.contains("separate bodies"), "{name}: {err}");
    }
}

/// `export-ccx` refusals of what the CalculiX deck cannot hold (load steps,
/// friction, force control) exited 3 (file error); they are invalid input
/// for the command: exit 1, naming the key, before any folder is created.
/// `verify` refuses them before its analysis. A real file error stays 3.
#[test]
fn export_ccx_refusals_are_input_errors() {
    let dir = out_dir("ccx_refusals");
    let block = std::fs::read_to_string(example("block_indentation.toml")).unwrap();
    std::fs::create_dir_all(&dir).unwrap();
    let force = dir.join("force.toml");
    std::fs::write(&force, block.replace("displacement = [0.0, 0.0, -1.0e-3]", "force = [0.0, 0.0, -1.0e6]")).unwrap();
    let cases = [
        (example("cantilevers_contact_friction.toml"), "contacts[0].friction: Coulomb friction"),
        (example("block_indentation_unload.toml"), "steps: a load history of 2 [[steps]]"),
        (force, "indenters[0].force: a force-controlled indenter"),
    ];
    for (k, (model, key)) in cases.iter().enumerate() {
        let out = dir.join(format!("out{k}"));
        let r = cufem()
            .args(["export-ccx", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--refine", "1"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{key}: {err}");
        assert!(err.contains(key) && err.contains("export-ccx and verify need a model without it"), "{err}");
        assert!(!out.exists(), "{key}: the refusal created {}", out.display());
    }
    let r = cufem()
        .args(["verify", cases[0].0.to_str().unwrap(), "--out", dir.join("v").to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert_eq!(r.status.code(), Some(1), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(!dir.join("v").exists(), "verify ran the analysis before refusing");
    // an unwritable folder is still a file error
    let r = cufem()
        .args(["export-ccx", example("cantilever_timoshenko.toml").to_str().unwrap(), "--out", "/dev/null/ccx"])
        .output()
        .unwrap();
    assert_eq!(r.status.code(), Some(3), "{}", String::from_utf8_lossy(&r.stderr));
    // an --out that is a file is named as `cufem run` names it (export-ccx
    // and check --plot gave the OS error with the path alone)
    let file = dir.join("a_file");
    std::fs::write(&file, "").unwrap();
    let cant = example("cantilever_timoshenko.toml");
    for args in [["export-ccx", cant.to_str().unwrap()], ["check", cant.to_str().unwrap()]] {
        let plot: &[&str] = if args[0] == "check" { &["--plot"] } else { &[] };
        let r = cufem().args(args).args(plot).args(["--out", file.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(&format!("--out {}: expected a folder", file.display())), "{args:?}: {err}");
    }
}

/// Option values: negative numbers got clap's "unexpected argument '-1'",
/// `bench --repeat 0` silently ran once, `--threads 100000` was refused
/// although the help says it is capped at the logical cores, and with
/// --force-threads the refusal stated "1..<cores>" instead of the 1024 it
/// applies. Each bad value: exit 1 naming the option, the value and the range.
#[test]
fn option_values_are_checked_by_name() {
    let cant = example("cantilever_timoshenko.toml");
    let m = cant.to_str().unwrap();
    let cases: [(&[&str], &[&str]); 7] = [
        (&["bench", m, "--repeat", "0"], &["'0' for '--repeat", "an integer from 1 to 1000"]),
        (&["bench", m, "--repeat", "-1"], &["'-1' for '--repeat", "an integer from 1 to 1000"]),
        (&["bench", m, "--threads", "-1"], &["'-1' for '--threads", "an integer ≥ 1"]),
        (&["bench", m, "--threads", "0"], &["'0' for '--threads", "an integer ≥ 1"]),
        (&["export-ccx", m, "--refine", "-1"], &["'-1' for '--refine", "an integer from 1 to 8"]),
        (&["bench", m, "--max-memory", "-1"], &["'-1' for '--max-memory", "a positive size such as 8G"]),
        (
            &["bench", m, "--repeat", "1", "--threads", "5000", "--force-threads"],
            &["--threads = 5000", "with --force-threads: expected an integer from 1 to 1024"],
        ),
    ];
    for (args, needles) in cases {
        let r = cufem().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{args:?}: {n:?} not in {err}");
        }
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    // more threads than cores: capped with a warning, whatever the number
    let r = cufem().args(["bench", m, "--repeat", "1", "--threads", "100000"]).output().unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    let cores = std::thread::available_parallelism().unwrap().get();
    assert!(err.contains(&format!("100000 threads requested but this machine has {cores} logical cores")), "{err}");
}

/// `cufem check /dev/zero` allocated until memory ran out: a model file is
/// read up to 64 MiB, and a larger or endless one refused (exit 1) with the
/// file, the cap and what is allowed. A gmsh mesh has its own cap (2 GiB).
#[test]
fn endless_and_huge_model_files_are_refused() {
    let dir = out_dir("huge_files");
    std::fs::create_dir_all(&dir).unwrap();
    let big = dir.join("big.toml");
    std::fs::File::create(&big).unwrap().set_len(100 << 20).unwrap();
    for path in [Path::new("/dev/zero"), big.as_path()] {
        let start = std::time::Instant::now();
        let r = cufem().args(["check", path.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{err}");
        assert!(
            err.contains(&format!("model file {} holds more than 64.00 MiB", path.display()))
                && err.contains("expected a model file of at most 64.00 MiB"),
            "{err}"
        );
        assert!(start.elapsed().as_secs() < 30, "{}", path.display());
    }
    let big_mesh = dir.join("big.msh");
    std::fs::File::create(&big_mesh).unwrap().set_len(3 << 30).unwrap();
    let model = dir.join("gmsh.toml");
    let text = std::fs::read_to_string(example("cantilever_timoshenko.toml")).unwrap();
    let rectangle = "section = { shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 } }";
    std::fs::write(&model, text.replace(rectangle, "section = { shape = \"gmsh\", file = \"big.msh\" }")).unwrap();
    let r = cufem().args(["check", model.to_str().unwrap()]).output().unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("bodies[0].section.file") && err.contains("a gmsh .msh file of at most 2.00 GiB"), "{err}");
    let _ = std::fs::remove_file(&big_mesh);
}

/// A title with control characters (`title = "bell \u0007 only"` gave a
/// result.vtu that expat, VTK and ParaView reject), markup, `-->` and
/// non-ASCII text is accepted and escaped: the VTU parses as XML and
/// summary.json as JSON, with the title intact there. Names may use only
/// letters, digits, `_`, `-` and `.` (they become file names): a control
/// character or a `/` in a name is refused with its key.
#[test]
fn any_title_gives_outputs_their_readers_accept() {
    let dir = out_dir("hostile_title");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(example("cantilever_timoshenko.toml")).unwrap();
    let title = "bell \u{7} nul \u{0} esc \u{1b} \u{c} quote \" apos ' <tag> & --> --- end- \u{ffff} ü 日本";
    let toml_title =
        "\"bell \\u0007 nul \\u0000 esc \\u001b \\f quote \\\" apos ' <tag> & --> --- end- \\uFFFF ü 日本\"";
    let start = text.find("title = ").unwrap();
    let end = start + text[start..].find('\n').unwrap();
    let model = text[..start].to_string() + "title = " + toml_title + &text[end..];
    let model = model
        .replace("name = \"tip\"\nbody", "name = \"tip-1.a\"\nbody")
        .replace("name = \"top\"", "name = \"top_2.x\"");
    let path = dir.join("model.toml");
    std::fs::write(&path, &model).unwrap();
    let out = dir.join("out");
    let r = cufem().args(["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]).output().unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let vtu = std::fs::read_to_string(out.join("result.vtu")).unwrap();
    if let Err(e) = roxmltree::Document::parse(&vtu) {
        panic!("result.vtu is not XML: {e}\n{}", &vtu[..300.min(vtu.len())]);
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["title"], title);
    assert!(out.join("line_top_2.x.csv").exists());
    for bad in ["tip\\u0007", "tip/1", "tip\\\\1"] {
        let p = dir.join("bad.toml");
        std::fs::write(&p, model.replace("name = \"tip-1.a\"", &format!("name = \"{bad}\""))).unwrap();
        let r = cufem().args(["check", p.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{bad}: {err}");
        assert!(err.contains("loads[0].name") && err.contains("letters, digits"), "{bad}: {err}");
    }
}

/// A reader that stops early (`cufem check … | head -0`) closes the pipe
/// before cufem writes: cufem ends on SIGPIPE like other Unix tools, not
/// with println!'s panic on EPIPE (exit code 101 and a backtrace).
#[test]
fn a_closed_output_pipe_ends_cufem_quietly() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    let mut child = cufem()
        .arg("check")
        .arg(example("bending_compact_16L9.toml"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?} {stderr}", out.status);
}

#[test]
fn the_peak_memory_is_the_runs_own_not_its_launchers() {
    // Linux's ru_maxrss survives fork and exec: a cufem started by a process
    // holding 1 GiB (a Python session, this test harness) reported that GiB
    // as its own peak. The compact bar's run needs about 40 MiB
    // (summary.json memory.estimated_bytes: 21 MB); its launcher here holds
    // 1 GiB, touched page by page so that it is resident.
    let mut held = vec![0u8; 1 << 30];
    for page in held.chunks_mut(4096) {
        page[0] = 1;
    }
    let out = out_dir("peak_memory");
    let run = cufem()
        .args(["run", example("bending_compact_4L9.toml").to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    std::hint::black_box(&held);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let peak = summary["memory"]["peak_bytes"].as_f64().unwrap();
    let estimated = summary["memory"]["estimated_bytes"].as_f64().unwrap();
    // the examples' band of estimate / peak (crates/cufem-cli/tests/examples.rs)
    assert!((0.9..1.3).contains(&(estimated / peak)), "peak {peak:e} B, estimate {estimated:e} B");
}
