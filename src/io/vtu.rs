//! VTU (VTK XML unstructured grid) output for ParaView.
//!
//! Each CUF element is one VTK Lagrange hexahedron of the element's own
//! orders over its Lagrange nodes (`output.vtu_cells = "lagrange"`), or is
//! split into linear hexahedra between them (`"linear"`; an L9 × B4
//! element gives 2 × 2 × 3 hexes), src/io/vtu/cells.rs.
//! Points are duplicated per element so that fields recovered from each
//! element's expansion (stress, strain, peeq) keep their inter-element
//! jumps; the displacement is continuous by construction. Stress and strain
//! components are written as separate scalar arrays named as in the CSV
//! files (`s_xx`, …) to avoid any ambiguity about tensor component order.
//! Contact results per node: `contact_force` (force on the body, N),
//! `contact_pressure` (|force| / tributary area, Pa) and `contact_gap`
//! (smallest gap over the node's contact points, m; NaN for nodes that are
//! in no contact).
//!
//! The file is VTK XML (`UnstructuredGrid`, version 1.0) with every data
//! array in the `binary` format: a little-endian UInt64 byte count followed
//! by the raw values, base64-encoded — about a third of the size of ASCII
//! and loaded without parsing numbers. The model title is in an XML comment
//! at the top. Written through one buffered stream; every I/O error (a full
//! disk, say) is reported with the file's path.

use std::io::Write;
use std::path::Path;

use base64::write::EncoderWriter;

use super::{IoError, file_error};
use crate::analysis::Solution;
use crate::post::{Location, Quantity};
use crate::setup::Model;
use crate::shape::Lagrange2d;

mod cells;
mod finite;
mod points;

use cells::VTK_LAGRANGE_HEXAHEDRON;
pub use cells::{Cells, GridElement};
pub(crate) use points::write_gauss_vtu;
pub use points::{write_contact_vtu, write_point_cloud};

/// The whole 3D field of every body as `result.vtu` holds it: each
/// element's own nodes, points duplicated per element, and the cells over
/// them ([`FieldGrid::cells`]).
#[derive(Debug, Clone)]
pub struct FieldGrid {
    /// Point coordinates, 3 per point (m).
    pub points: Vec<f64>,
    /// Every CUF element: its body, global index, first point and orders.
    pub elements: Vec<GridElement>,
    /// Point data: `displacement`, `contact_force` (3 components each),
    /// `contact_pressure`, `contact_gap`, `error` (the element's part of the
    /// estimated relative error, `post::ErrorEstimate::relative_element`,
    /// constant over the element), then every scalar of
    /// [`Quantity::all`] but the displacement (1 component).
    pub point_data: Vec<FieldArray>,
}

/// A named point-data array of a [`FieldGrid`].
#[derive(Debug, Clone)]
pub struct FieldArray {
    /// The name, as in the CSV files (`s_xx`, `peeq`, …).
    pub name: String,
    /// Components per point.
    pub components: usize,
    /// The values, `components` per point.
    pub values: Vec<f64>,
}

/// Writes the whole 3D field of every body ([`field_grid`]).
pub fn write_vtu(path: &Path, model: &Model, solution: &Solution) -> Result<(), IoError> {
    write_grid_vtu(path, model, solution, field_grid(model, solution))
}

/// Writes the field grid `g` of `solution` ([`write_vtu`], the grid
/// computed by the caller).
pub(crate) fn write_grid_vtu(path: &Path, model: &Model, solution: &Solution, g: FieldGrid) -> Result<(), IoError> {
    let c = g.cells(model.output.vtu_cells);
    let point_data: Vec<(String, usize, Array)> =
        g.point_data.into_iter().map(|a| (a.name, a.components, Array::F64(a.values))).collect();
    let damage = damage_cells(model, solution, &c.body, &c.element);
    let mut cell_data = body_element_data(c.body, c.element);
    cell_data.extend(damage.into_iter().map(|(n, v)| (n, 1, Array::F64(v))));
    if !c.degrees.is_empty() {
        cell_data.push((HIGHER_ORDER_DEGREES.to_string(), 3, Array::I32(c.degrees)));
    }
    let grid = Grid {
        title: &model.title,
        points: &g.points,
        connectivity: &c.connectivity,
        offsets: &c.offsets,
        n_cells: c.offsets.len(),
        point_data: &point_data,
        cell_data: &cell_data,
        cell_type: c.cell_type,
    };
    write_file(path, &grid)
}

/// The ply damage as cell data `d_ft d_fc d_mt d_mc` (none without
/// `[materials.damage]`): each mode's largest damage over the Gauss points
/// of the cell's element, for the cells of `cell_body` and `cell_element`
/// ([`FieldGrid::cells`]; also the Python package's cell data).
pub fn damage_cells(
    model: &Model,
    solution: &Solution,
    cell_body: &[i32],
    cell_element: &[i32],
) -> Vec<(String, Vec<f64>)> {
    let Some(damage) = solution.damage.as_ref() else {
        return Vec::new();
    };
    let mut modes: [Vec<f64>; 4] = Default::default();
    for (&b, &global) in cell_body.iter().zip(cell_element) {
        let b = b as usize;
        let e = global as usize - model.mesh.bodies[b].element_offset;
        let ngp = model.cells[b].gp_per_element();
        let first = solution.gp_offsets[b] + e * ngp;
        for (values, d) in modes.iter_mut().zip(damage.largest_in(first..first + ngp)) {
            values.push(d);
        }
    }
    ["d_ft", "d_fc", "d_mt", "d_mc"].iter().zip(modes).map(|(n, v)| (n.to_string(), v)).collect()
}

/// The whole 3D field of every body, as [`write_vtu`] writes it.
pub fn field_grid(model: &Model, solution: &Solution) -> FieldGrid {
    let view = solution.fields(model);
    let mut points: Vec<f64> = Vec::new();
    let mut elements: Vec<GridElement> = Vec::new();
    let scalars: Vec<Quantity> =
        model.quantities().into_iter().filter(|q| !matches!(q, Quantity::Displacement(_))).collect();
    let mut scalar_data: Vec<Vec<f64>> = vec![Vec::new(); scalars.len()];
    let mut displacement: Vec<f64> = Vec::new();
    let mut contact_force: Vec<f64> = Vec::new();
    let mut contact_pressure: Vec<f64> = Vec::new();
    let mut contact_gap: Vec<f64> = Vec::new();
    let mut error: Vec<f64> = Vec::new();
    // the elements around forces on points or lines (`analysis::concentrated`)
    let marked: std::collections::HashSet<usize> =
        crate::analysis::concentrated::find(model, solution).into_iter().flat_map(|c| c.touching).collect();
    let mut concentrated: Vec<f64> = Vec::new();

    // smallest contact gap per node (NaN where a node is in no contact)
    let mut node_gap: std::collections::HashMap<usize, f64> = Default::default();
    let contact_points = || solution.contact_sets.iter().flat_map(|c| &c.points);
    // (a surface-contact node without a master face under it has no gap)
    for p in contact_points().filter(|p| !p.gap.is_nan()) {
        for n in std::iter::once(p.node).chain(p.master) {
            let g = node_gap.entry(n).or_insert(f64::INFINITY);
            *g = g.min(p.gap);
        }
    }
    // contact force and pressure per node (summed over contacts)
    let mut node_contact: std::collections::HashMap<usize, ([f64; 3], f64)> = Default::default();
    let add = |map: &mut std::collections::HashMap<usize, ([f64; 3], f64)>, n: usize, f: [f64; 3], area: f64| {
        let e = map.entry(n).or_insert(([0.0; 3], 0.0));
        for k in 0..3 {
            e.0[k] += f[k];
        }
        e.1 += (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt() / area;
    };
    for p in contact_points() {
        add(&mut node_contact, p.node, p.force, p.area);
        if let Some(m) = p.master {
            add(&mut node_contact, m, p.force.map(|v| -v), p.area);
        }
    }

    // the damage and onset index of the interface points on their nodes
    // (`d_interface`, `onset_interface`)
    let interface_damage = solution.delamination.as_ref().map(|d| d.node_damage());
    let (mut d_interface, mut onset_interface) = (Vec::new(), Vec::new());
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let ps = body.section.kind.order();
        let m = ps + 1;
        let ns = m * m;
        let pb = body.axis.kind.order();
        let basis = Lagrange2d::new(ps);
        let mut nodes = Vec::new();
        for e in 0..body.n_elements() {
            let first = points.len() / 3;
            elements.push(GridElement {
                body: b,
                element: body.element_offset + e,
                first,
                section_order: ps,
                axis_order: pb,
            });
            body.element_nodes(e, &mut nodes);
            for i in 0..=pb {
                let zeta = -1.0 + 2.0 * i as f64 / pb as f64;
                for t in 0..ns {
                    let [xi, eta] = basis.node(t);
                    let node = nodes[i * ns + t];
                    points.extend(model.mesh.coords(node));
                    let s = view.sample(&Location { body: b, element: e, natural: [xi, eta, zeta] });
                    displacement.extend(s.u);
                    for (data, &q) in scalar_data.iter_mut().zip(&scalars) {
                        data.push(s.get(q));
                    }
                    let (f, p) = node_contact.get(&node).copied().unwrap_or_default();
                    contact_force.extend(f);
                    contact_pressure.push(p);
                    contact_gap.push(node_gap.get(&node).copied().unwrap_or(f64::NAN));
                    if let Some(map) = &interface_damage {
                        let (d, onset) = map.get(&node).copied().unwrap_or_default();
                        d_interface.push(d);
                        onset_interface.push(onset);
                    }
                    if !marked.is_empty() {
                        concentrated.push(if marked.contains(&(body.element_offset + e)) { 1.0 } else { 0.0 });
                    }
                    error.push(
                        solution
                            .error_estimate
                            .as_ref()
                            .map_or(f64::NAN, |x| x.relative_element(body.element_offset + e)),
                    );
                }
            }
        }
    }
    let mut point_data = vec![
        FieldArray { name: "displacement".into(), components: 3, values: displacement },
        FieldArray { name: "contact_force".into(), components: 3, values: contact_force },
        FieldArray { name: "contact_pressure".into(), components: 1, values: contact_pressure },
        FieldArray { name: "contact_gap".into(), components: 1, values: contact_gap },
        FieldArray { name: "error".into(), components: 1, values: error },
    ];
    for (values, q) in scalar_data.into_iter().zip(&scalars) {
        point_data.push(FieldArray { name: q.name(), components: 1, values });
    }
    if interface_damage.is_some() {
        point_data.push(FieldArray { name: "d_interface".into(), components: 1, values: d_interface });
        point_data.push(FieldArray { name: "onset_interface".into(), components: 1, values: onset_interface });
    }
    if !marked.is_empty() {
        point_data.push(FieldArray { name: "concentrated".into(), components: 1, values: concentrated });
    }
    FieldGrid { points, elements, point_data }
}

/// Writes `points` (3 coordinates each) as one VTK vertex per point, with
/// their point and cell data.
fn write_vertices(
    path: &Path,
    title: &str,
    points: &[f64],
    point_data: &[(String, usize, Array)],
    cell_data: &[(String, usize, Array)],
) -> Result<(), IoError> {
    let n = points.len() / 3;
    let connectivity: Vec<u64> = (0..n as u64).collect();
    let offsets: Vec<u64> = (1..=n as u64).collect();
    let grid = Grid {
        title,
        points,
        connectivity: &connectivity,
        offsets: &offsets,
        n_cells: n,
        point_data,
        cell_data,
        cell_type: VTK_VERTEX,
    };
    write_file(path, &grid)
}

/// Writes `grid` to `path` through one buffered stream; errors name the file.
fn write_file(path: &Path, grid: &Grid<'_>) -> Result<(), IoError> {
    let file = std::fs::File::create(path).map_err(|e| file_error(path, e))?;
    let mut out = std::io::BufWriter::with_capacity(1 << 20, file);
    write_grid(&mut out, grid).and_then(|()| out.flush()).map_err(|e| file_error(path, e))
}

/// Cell data of both files: body and global element of every cell.
fn body_element_data(cell_body: Vec<i32>, cell_element: Vec<i32>) -> Vec<(String, usize, Array)> {
    vec![("body".to_string(), 1, Array::I32(cell_body)), ("element".to_string(), 1, Array::I32(cell_element))]
}

/// A data array of one of the types the file uses.
enum Array {
    F64(Vec<f64>),
    I32(Vec<i32>),
}

/// Everything written to the file.
struct Grid<'a> {
    title: &'a str,
    points: &'a [f64],
    connectivity: &'a [u64],
    offsets: &'a [u64],
    n_cells: usize,
    point_data: &'a [(String, usize, Array)],
    cell_data: &'a [(String, usize, Array)],
    /// VTK cell type of every cell.
    cell_type: u8,
}

/// The cell-data array VTK reads a Lagrange cell's orders from (named
/// by the `CellData` element's attribute of the same name).
const HIGHER_ORDER_DEGREES: &str = "HigherOrderDegrees";
/// VTK cell type of a single point.
const VTK_VERTEX: u8 = 1;

fn write_grid(w: &mut impl Write, g: &Grid<'_>) -> std::io::Result<()> {
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(w, "<!-- {} -->", xml_comment(g.title))?;
    // version 1.0 for both kinds of cells: the Lagrange hexahedra are in
    // VTK 8's point order, which VTK ≥ 9.1 renumbers on reading (cells.rs)
    let lagrange = g.cell_type == VTK_LAGRANGE_HEXAHEDRON;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(w, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">", g.points.len() / 3, g.n_cells)?;
    writeln!(w, "      <PointData>")?;
    for (name, comps, data) in g.point_data {
        data_array(w, Some(name), *comps, data)?;
    }
    writeln!(w, "      </PointData>")?;
    let degrees = if lagrange { format!(" {HIGHER_ORDER_DEGREES}=\"{HIGHER_ORDER_DEGREES}\"") } else { String::new() };
    writeln!(w, "      <CellData{degrees}>")?;
    for (name, comps, data) in g.cell_data {
        data_array(w, Some(name), *comps, data)?;
    }
    writeln!(w, "      </CellData>")?;
    writeln!(w, "      <Points>")?;
    binary_array(w, "Float64", None, 3, g.points.len(), g.points.iter().flat_map(|v| v.to_le_bytes()))?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    let conn = g.connectivity;
    binary_array(w, "Int64", Some("connectivity"), 1, conn.len(), conn.iter().flat_map(|&v| (v as i64).to_le_bytes()))?;
    let offs = g.offsets;
    binary_array(w, "Int64", Some("offsets"), 1, offs.len(), offs.iter().flat_map(|&v| (v as i64).to_le_bytes()))?;
    binary_array(w, "UInt8", Some("types"), 1, g.n_cells, std::iter::repeat_n(g.cell_type, g.n_cells))?;
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}

fn data_array(w: &mut impl Write, name: Option<&str>, comps: usize, data: &Array) -> std::io::Result<()> {
    match data {
        Array::F64(v) => binary_array(w, "Float64", name, comps, v.len(), v.iter().flat_map(|x| x.to_le_bytes())),
        Array::I32(v) => binary_array(w, "Int32", name, comps, v.len(), v.iter().flat_map(|x| x.to_le_bytes())),
    }
}

/// One `DataArray` in VTK's `binary` format: base64 of a UInt64 byte count
/// followed by the little-endian values.
fn binary_array(
    w: &mut impl Write,
    ty: &str,
    name: Option<&str>,
    comps: usize,
    len: usize,
    bytes: impl Iterator<Item = u8>,
) -> std::io::Result<()> {
    let name = name.map(|n| format!(" Name=\"{}\"", xml_text(n))).unwrap_or_default();
    write!(w, "        <DataArray type=\"{ty}\"{name} NumberOfComponents=\"{comps}\" format=\"binary\">")?;
    let size = (len * type_size(ty)) as u64;
    {
        let mut enc = EncoderWriter::new(&mut *w, &base64::engine::general_purpose::STANDARD);
        enc.write_all(&size.to_le_bytes())?;
        let mut buf = Vec::with_capacity(1 << 16);
        for b in bytes {
            buf.push(b);
            if buf.len() == buf.capacity() {
                enc.write_all(&buf)?;
                buf.clear();
            }
        }
        enc.write_all(&buf)?;
        enc.finish()?;
    }
    writeln!(w, "</DataArray>")
}

fn type_size(ty: &str) -> usize {
    match ty {
        "Float64" | "Int64" => 8,
        "Int32" => 4,
        _ => 1,
    }
}

/// Escapes text for an XML attribute or comment: the five markup
/// characters as entities, and the characters XML 1.0 forbids even as
/// character references (controls other than tab, newline and carriage
/// return; U+FFFE, U+FFFF) as visible `\u{7}` text. A bell in the title made
/// expat, and so VTK and ParaView, reject the file.
fn xml_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if c < ' ' || c == '\u{FFFE}' || c == '\u{FFFF}' => out.extend(c.escape_unicode()),
            c => out.push(c),
        }
    }
    out
}

/// Text for an XML comment: escaped as [`xml_text`], with every `--` (not
/// allowed inside a comment, `---` included) broken by a space.
fn xml_comment(s: &str) -> String {
    let mut out = xml_text(s);
    while out.contains("--") {
        out = out.replace("--", "- -");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::cells::VTK_HEXAHEDRON;
    use super::*;
    use base64::Engine as _;

    /// A writer that fails like a full disk after `room` bytes.
    struct Full {
        room: usize,
    }

    impl Write for Full {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.room == 0 {
                return Err(std::io::Error::from_raw_os_error(28)); // ENOSPC
            }
            let n = buf.len().min(self.room);
            self.room -= n;
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn grid_bytes(w: &mut impl Write) -> std::io::Result<()> {
        let data = vec![("p".to_string(), 1, Array::F64((0..8).map(f64::from).collect()))];
        let grid = Grid {
            title: "a <title> -- with dashes",
            points: &[
                0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0,
                1.0, 0.0, 1.0, 1.0,
            ],
            connectivity: &[0, 1, 2, 3, 4, 5, 6, 7],
            offsets: &[8],
            n_cells: 1,
            point_data: &data,
            cell_data: &[],
            cell_type: VTK_HEXAHEDRON,
        };
        write_grid(w, &grid)
    }

    /// Every string written into the VTU must stay well-formed XML: control
    /// characters (a bell in the title), markup characters and `---` in a
    /// comment once gave a file expat rejects.
    #[test]
    fn text_is_escaped_for_xml() {
        assert_eq!(xml_text("a\u{7}b\u{0}<&>\"'\t\u{FFFF}ü"), "a\\u{7}b\\u{0}&lt;&amp;&gt;&quot;&apos;\t\\u{ffff}ü");
        // written as `<!-- {c} -->`: a trailing `-` is kept apart by the space
        for title in ["a --- b", "--> end -", "----"] {
            let c = xml_comment(title);
            assert!(!c.contains("--"), "{title:?} → {c:?}");
        }
        let mut out = Vec::new();
        let data = vec![("p\u{7}<\"".to_string(), 1, Array::F64(vec![0.0]))];
        let grid = Grid {
            title: "bell \u{7} -->---<!-- & \"'",
            points: &[0.0, 0.0, 0.0],
            connectivity: &[0],
            offsets: &[1],
            n_cells: 1,
            point_data: &data,
            cell_data: &[],
            cell_type: VTK_VERTEX,
        };
        write_grid(&mut out, &grid).unwrap();
        let text = String::from_utf8(out).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let a = doc.descendants().find(|n| n.has_tag_name("DataArray")).unwrap();
        assert_eq!(a.attribute("Name"), Some("p\\u{7}<\""));
    }

    #[test]
    fn binary_arrays_carry_their_byte_count_and_values() {
        let mut out = Vec::new();
        grid_bytes(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("<!-- a &lt;title&gt; - - with dashes -->"), "{text}");
        let start = text.find("Name=\"p\" NumberOfComponents=\"1\" format=\"binary\">").unwrap();
        let body = &text[start..];
        let b64 = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
        let raw = base64::engine::general_purpose::STANDARD.decode(b64).unwrap();
        assert_eq!(u64::from_le_bytes(raw[..8].try_into().unwrap()), 64);
        let values: Vec<f64> = raw[8..].chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
        assert_eq!(values, (0..8).map(f64::from).collect::<Vec<_>>());
    }

    /// Issue 13, reproduction 5: a full disk is reported as the OS error,
    /// not as an XML error.
    #[test]
    fn a_full_disk_is_an_io_error() {
        let err = grid_bytes(&mut Full { room: 300 }).unwrap_err();
        assert_eq!(err.raw_os_error(), Some(28));
        let e = file_error(Path::new("out/result.vtu"), err).to_string();
        assert!(e.contains("out/result.vtu") && e.contains("No space left on device"), "{e}");
    }
}
