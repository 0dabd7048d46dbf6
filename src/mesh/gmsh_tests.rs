//! Tests of the gmsh reader on tiny hand-written files.

use super::*;

/// The nodes block of a 4.1 file: tags 1.. of the given `(x, y)` points, one surface entity.
fn nodes41(points: &[[f64; 2]]) -> String {
    let n = points.len();
    let mut s = format!("$Nodes\n1 {n} 1 {n}\n2 1 0 {n}\n");
    for k in 1..=n {
        s += &format!("{k}\n");
    }
    for p in points {
        s += &format!("{} {} 0\n", p[0], p[1]);
    }
    s + "$EndNodes\n"
}

const HEAD41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 7 \"plate\"\n$EndPhysicalNames\n\
                      $Entities\n0 0 1 0\n1 0 0 0 2 1 0 1 7 0\n$EndEntities\n";

/// `[0, 2] × [0, 1]` as two quad4: nodes 1–3 along y = 0, 4–6 along y = 1.
fn quad4_file(elements: &str) -> String {
    let pts = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]];
    format!("{HEAD41}{}$Elements\n1 2 1 2\n{elements}$EndElements\n", nodes41(&pts))
}

const QUAD4: &str = "2 1 3 2\n1 1 2 5 4\n2 2 3 6 5\n";

/// Node coordinates (to 1e-9) of every element in local order, elements sorted: two
/// sections with equal keys are the same mesh up to node numbering.
fn key(s: &CrossSection) -> Vec<Vec<[i64; 2]>> {
    let mut k: Vec<Vec<[i64; 2]>> = (0..s.n_elements())
        .map(|e| s.element(e).iter().map(|&n| s.nodes[n].map(|c| (c * 1e9).round() as i64)).collect())
        .collect();
    k.sort();
    k
}

fn rectangle(kind: SectionElementKind) -> CrossSection {
    CrossSection::rectangle(kind, &[0.0, 1.0, 2.0], &[0.0, 1.0]).unwrap()
}

#[test]
fn quad4_file_is_the_parametric_rectangle() {
    let s = parse(&quad4_file(QUAD4), "plate.msh", 1.0, "section.file").unwrap();
    assert_eq!(s.kind, SectionElementKind::L4);
    assert_eq!(s.n_nodes(), 6);
    assert_eq!(key(&s), key(&rectangle(SectionElementKind::L4)));
    assert_eq!(s.regions, vec![Region { name: "plate".into(), elements: vec![0, 1], normal: None }]);
    // scaled from mm
    let mm = parse(&quad4_file(QUAD4), "plate.msh", 1e-3, "section.file").unwrap();
    assert!((mm.properties().area - 2e-6).abs() < 1e-20);
}

#[test]
fn quad9_file_is_the_parametric_rectangle() {
    // node tag j·5 + i + 1 at (i/2, j/2); gmsh order: corners, edge nodes, centre
    let pts: Vec<[f64; 2]> = (0..15).map(|t| [(t % 5) as f64 * 0.5, (t / 5) as f64 * 0.5]).collect();
    let elements = "2 1 10 2\n1 1 3 13 11 2 8 12 6 7\n2 3 5 15 13 4 10 14 8 9\n";
    let text = format!("{HEAD41}{}$Elements\n1 2 1 2\n{elements}$EndElements\n", nodes41(&pts));
    let s = parse(&text, "plate9.msh", 1.0, "section.file").unwrap();
    assert_eq!(s.kind, SectionElementKind::L9);
    assert_eq!(s.n_nodes(), 15);
    assert_eq!(key(&s), key(&rectangle(SectionElementKind::L9)));
}

#[test]
fn gmsh_quad16_file_is_the_parametric_rectangle() {
    // written by gmsh 4.15 from tests/data/rect_quad16.geo: the node order
    // table of the 16-node quadrilateral checked against gmsh itself
    let text = include_str!("../../tests/data/rect_quad16.msh");
    let s = parse(text, "rect_quad16.msh", 1.0, "section.file").unwrap();
    assert_eq!(s.kind, SectionElementKind::L16);
    assert_eq!(s.n_nodes(), 7 * 4);
    assert_eq!(key(&s), key(&rectangle(SectionElementKind::L16)));
}

#[test]
fn format_22_reads_the_same_mesh() {
    let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n\
                6 2 1 0\n$EndNodes\n$Elements\n3\n1 1 2 7 1 1 2\n2 3 2 7 1 1 2 5 4\n3 3 2 7 1 2 3 6 5\n$EndElements\n";
    let s = parse(text, "plate22.msh", 1.0, "section.file").unwrap();
    assert_eq!(key(&s), key(&rectangle(SectionElementKind::L4)));
    assert_eq!(s.regions[0].name, "physical_7");
}

fn error(text: &str) -> String {
    parse(text, "bad.msh", 1.0, "bodies[0].section.file").unwrap_err().to_string()
}

#[test]
fn triangles_are_refused_with_their_line() {
    let text = quad4_file("2 1 2 1\n1 1 2 5\n");
    let e = error(&text);
    assert!(
        e.contains("bodies[0].section.file") && e.contains("\"bad.msh\" line 31") && e.contains("a triangle"),
        "{e}"
    );
    assert!(e.contains("type 36 → L16"), "{e}");
}

/// A duplicated element, one covering another, and a node tag listed twice
/// were read without a word (the area counted twice, or the later node
/// silently replacing the first: the tip of a cantilever 35 % off; a
/// new-user review), as `shape = "quads"` refuses its overlapping quads.
#[test]
fn duplicated_and_overlapping_elements_and_nodes_are_refused() {
    let e = error(&quad4_file("2 1 3 3\n1 1 2 5 4\n2 2 3 6 5\n3 1 2 5 4\n"));
    assert!(e.contains("line 33") && e.contains("element 2 covers 100.000 % of element 0 (line 31)"), "{e}");
    // the second element [0, 2] × [0, 1] covers the first, [0, 1] × [0, 1]
    let e = error(&quad4_file("2 1 3 2\n1 1 2 5 4\n2 1 3 6 4\n"));
    assert!(e.contains("line 32") && e.contains("element 1 covers 100.000 % of element 0"), "{e}");
    // neighbours sharing an edge do not overlap
    assert!(parse(&quad4_file(QUAD4), "plate.msh", 1.0, "section.file").is_ok());
    let twice = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n\
                 6 2 1 0\n6 2 2 0\n$EndNodes\n$Elements\n2\n2 3 2 7 1 1 2 5 4\n3 3 2 7 1 2 3 6 5\n$EndElements\n";
    let e = error(twice);
    assert!(e.contains("line 12") && e.contains("node 6 is listed twice (first on line 11)"), "{e}");
}

#[test]
fn inverted_and_mixed_elements_are_refused() {
    let e = error(&quad4_file("2 1 3 2\n1 1 4 5 2\n2 2 3 6 5\n"));
    assert!(e.contains("line 31") && e.contains("inverted"), "{e}");
    let mixed = quad4_file("2 1 3 1\n1 1 2 5 4\n2 1 10 1\n2 2 3 6 5 1 2 3 4 5\n")
        .replace("$Elements\n1 2 1 2", "$Elements\n2 2 1 2");
    let e = error(&mixed);
    assert!(e.contains("mixed orders"), "{e}");
}

#[test]
fn unsupported_versions_and_broken_files_are_refused() {
    let e = error("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
    assert!(e.contains("line 2") && e.contains("version \"3.0 0 8\" is not supported"), "{e}");
    let e = error("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n");
    assert!(e.contains("binary"), "{e}");
    let e = error("hello");
    assert!(e.contains("line 1"), "{e}");
    let e = error(&quad4_file(QUAD4)[..200]);
    assert!(e.contains("bad.msh"), "{e}");
    let e = error(&quad4_file("2 1 3 2\n1 1 2 5 99\n2 2 3 6 5\n"));
    assert!(e.contains("node 99 is not in $Nodes"), "{e}");
    let e = read(Path::new("/nonexistent/x.msh"), 1.0, "bodies[0].section.file").unwrap_err().to_string();
    assert!(e.contains("bodies[0].section.file = \"/nonexistent/x.msh\"") && e.contains("readable"), "{e}");
    // no panic on any prefix of a valid file
    let full = quad4_file(QUAD4);
    for cut in 0..full.len() {
        if full.is_char_boundary(cut) {
            let _ = parse(&full[..cut], "cut.msh", 1.0, "k");
        }
    }
}
