//! The VTU files of points rather than elements: the raw Gauss-point
//! values, the points of a contact, and any cloud of points (one VTK vertex
//! each, `super::write_vertices`).

use std::path::Path;

use super::{Array, FieldArray, body_element_data, finite, write_vertices};
use crate::analysis::Solution;
use crate::io::IoError;
use crate::setup::Model;

/// Writes the raw Gauss-point values (`output.gauss_points = true`): one
/// VTK vertex per integration point at its physical position, with the
/// stress of the return map (`s_xx`…`s_yz`, `von_mises`) and `peeq` as
/// point data and `body`, `element` as cell data — the values every
/// recovered field is built from, unsmoothed. With
/// `analysis.geometry = "nonlinear"` the stress is the Cauchy stress and
/// `finite::finite_strain_data` adds the reference-configuration measures.
pub(crate) fn write_gauss_vtu(path: &Path, model: &Model, solution: &Solution) -> Result<(), IoError> {
    let view = solution.fields(model);
    let mut points: Vec<f64> = Vec::new();
    let mut stress: [Vec<f64>; 6] = Default::default();
    let (mut von_mises, mut peeq) = (Vec::new(), Vec::new());
    let (mut cell_body, mut cell_element) = (Vec::new(), Vec::new());
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let cell = &model.cells[b];
        let ngp = cell.gp_per_element();
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            for gb in 0..cell.axis.n_gp {
                for gs in 0..cell.section.n_gp {
                    let [x, z] = cell.section.position[es * cell.section.n_gp + gs];
                    let y = cell.axis.position[eb * cell.axis.n_gp + gb];
                    points.extend([x, y, z]);
                    let g = view.gp_offsets[b] + e * ngp + gb * cell.section.n_gp + gs;
                    let s = view.stresses[g];
                    for k in 0..6 {
                        stress[k].push(s[k]);
                    }
                    von_mises.push(crate::voigt::von_mises(&s));
                    peeq.push(view.states[g].peeq);
                    cell_body.push(b as i32);
                    cell_element.push((body.element_offset + e) as i32);
                }
            }
        }
    }
    let names = ["s_xx", "s_yy", "s_zz", "s_xy", "s_xz", "s_yz"];
    let mut point_data: Vec<(String, usize, Array)> =
        names.iter().zip(stress).map(|(n, v)| (n.to_string(), 1, Array::F64(v))).collect();
    point_data.push(("von_mises".into(), 1, Array::F64(von_mises)));
    point_data.push(("peeq".into(), 1, Array::F64(peeq)));
    if model.kinematics.is_nonlinear() {
        point_data.extend(finite::finite_strain_data(model, &view));
    }
    let cell_data = body_element_data(cell_body, cell_element);
    write_vertices(path, &model.title, &points, &point_data, &cell_data)
}

/// Writes the points of one contact (`solution.contact_sets[set]`) as a
/// point cloud of VTK vertices at the reference positions of their nodes
/// (the slave node of a pair or surface contact, the body node under an
/// indenter): `u` (displacement, m, to warp by),
/// `force` (on the slave body or the body under the indenter, N), `normal`,
/// `pressure` (normal force / tributary area, Pa), `traction` (tangential
/// force / area, Pa), `gap` (m, negative = penetration; NaN for a
/// surface-contact node without a master face under it), `slip` (|slip|,
/// m) and `status` (0 open, 1 in contact and sticking or frictionless,
/// 2 sliding).
pub fn write_contact_vtu(path: &Path, model: &Model, solution: &Solution, set: usize) -> Result<(), IoError> {
    let contact = &solution.contact_sets[set];
    // position, gap, pressure, traction and slip as in `contact_<name>.csv`
    let table = crate::analysis::tables::contact_points(model, contact);
    let column = |name: &str| table.real(name).unwrap_or_default();
    let (x, y, z) = (column("x"), column("y"), column("z"));
    let points: Vec<f64> = (0..x.len()).flat_map(|i| [x[i], y[i], z[i]]).collect();
    let (mut u, mut force, mut normal, mut status) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for p in &contact.points {
        u.extend((0..3).map(|k| solution.u[3 * p.node + k]));
        force.extend(p.force);
        normal.extend(p.normal);
        status.push(if !p.active {
            0
        } else if p.sliding {
            2
        } else {
            1
        });
    }
    let (pressure, traction, gap, slip) = (column("pressure"), column("traction"), column("gap"), column("slip"));
    let point_data: Vec<(String, usize, Array)> = vec![
        ("u".into(), 3, Array::F64(u)),
        ("force".into(), 3, Array::F64(force)),
        ("normal".into(), 3, Array::F64(normal)),
        ("pressure".into(), 1, Array::F64(pressure)),
        ("traction".into(), 1, Array::F64(traction)),
        ("gap".into(), 1, Array::F64(gap)),
        ("slip".into(), 1, Array::F64(slip)),
        ("status".into(), 1, Array::I32(status)),
    ];
    write_vertices(path, &model.title, &points, &point_data, &[])
}

/// Writes a cloud of points (one VTK vertex each) with point data: `points`
/// holds 3 coordinates per point (m).
pub fn write_point_cloud(path: &Path, title: &str, points: &[f64], data: Vec<FieldArray>) -> Result<(), IoError> {
    let point_data: Vec<(String, usize, Array)> =
        data.into_iter().map(|a| (a.name, a.components, Array::F64(a.values))).collect();
    write_vertices(path, title, points, &point_data, &[])
}
