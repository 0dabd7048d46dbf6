//! VTU (VTK XML unstructured grid) output for ParaView.
//!
//! Each CUF element is split into linear hexahedra whose corners are the
//! element's own Lagrange nodes (an L9 × B4 element gives 2 × 2 × 3 hexes).
//! Points are duplicated per element so that fields recovered from each
//! element's expansion (stress, strain, peeq) keep their inter-element
//! jumps; the displacement is continuous by construction. Stress and strain
//! components are written as separate scalar arrays named as in the CSV
//! files (`s_xx`, …) to avoid any ambiguity about tensor component order.
//! Contact results per node: `contact_force` (force on the body, N),
//! `contact_pressure` (|force| / tributary area, Pa) and `contact_gap`
//! (smallest gap over the node's contact points, m; NaN for nodes that are
//! in no contact).

use std::path::Path;

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

use super::IoError;
use crate::analysis::Solution;
use crate::model::Model;
use crate::post::{Location, Quantity};
use crate::shape::Lagrange2d;

/// Writes the whole 3D field of every body.
pub fn write_vtu(path: &Path, model: &Model, solution: &Solution) -> Result<(), IoError> {
    let view = solution.fields(model);
    let mut points: Vec<f64> = Vec::new();
    let mut connectivity: Vec<u64> = Vec::new();
    let mut offsets: Vec<u64> = Vec::new();
    let mut cell_body: Vec<i32> = Vec::new();
    let mut cell_element: Vec<i32> = Vec::new();
    let scalars: Vec<Quantity> =
        Quantity::all().into_iter().filter(|q| !matches!(q, Quantity::Displacement(_))).collect();
    let mut scalar_data: Vec<Vec<f64>> = vec![Vec::new(); scalars.len()];
    let mut displacement: Vec<f64> = Vec::new();
    let mut contact_force: Vec<f64> = Vec::new();
    let mut contact_pressure: Vec<f64> = Vec::new();
    let mut contact_gap: Vec<f64> = Vec::new();

    // smallest contact gap per node (NaN where a node is in no contact)
    let mut node_gap: std::collections::HashMap<usize, f64> = Default::default();
    for p in &solution.contact_points {
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
    for p in &solution.contact_points {
        add(&mut node_contact, p.node, p.force, p.area);
        if let Some(m) = p.master {
            add(&mut node_contact, m, p.force.map(|v| -v), p.area);
        }
    }

    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let ps = body.section.kind.order();
        let m = ps + 1;
        let ns = m * m;
        let pb = body.axis.kind.order();
        let basis = Lagrange2d::new(ps);
        let mut nodes = Vec::new();
        for e in 0..body.n_elements() {
            let base = (points.len() / 3) as u64;
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
                }
            }
            // (ξ, η, ζ) is left-handed in (x, y, z): list each bottom face
            // η-first so that VTK sees positive volumes.
            for k in 0..pb {
                for iz in 0..ps {
                    for ix in 0..ps {
                        let id =
                            |dk: usize, dz: usize, dx: usize| base + ((k + dk) * ns + (iz + dz) * m + ix + dx) as u64;
                        connectivity.extend([
                            id(0, 0, 0),
                            id(0, 1, 0),
                            id(0, 1, 1),
                            id(0, 0, 1),
                            id(1, 0, 0),
                            id(1, 1, 0),
                            id(1, 1, 1),
                            id(1, 0, 1),
                        ]);
                        offsets.push(connectivity.len() as u64);
                        cell_body.push(b as i32);
                        cell_element.push((body.element_offset + e) as i32);
                    }
                }
            }
        }
    }
    let n_cells = offsets.len();
    let mut point_data = vec![
        Attribute::vectors("displacement").with_data(displacement),
        Attribute::vectors("contact_force").with_data(contact_force),
        Attribute::scalars("contact_pressure", 1).with_data(contact_pressure),
        Attribute::scalars("contact_gap", 1).with_data(contact_gap),
    ];
    for (data, q) in scalar_data.into_iter().zip(&scalars) {
        point_data.push(Attribute::scalars(q.name(), 1).with_data(data));
    }
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: model.title.clone(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML { connectivity, offsets },
                types: vec![CellType::Hexahedron; n_cells],
            },
            data: Attributes {
                point: point_data,
                cell: vec![
                    Attribute::scalars("body", 1).with_data(cell_body),
                    Attribute::scalars("element", 1).with_data(cell_element),
                ],
            },
        }),
    };
    vtk.export(path).map_err(|e| IoError::Vtk { path: path.display().to_string(), message: e.to_string() })
}
