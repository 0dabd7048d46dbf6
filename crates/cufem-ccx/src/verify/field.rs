//! Whole-field comparison: both solutions sampled at common points over
//! every body, not only at the probes and lines the model names.
//!
//! **Points.** The volume is sampled at the Gauss points of every CUF
//! element (`values::CellValues`: position and weight `w |J|`, a volume),
//! the contact surfaces at the quadrature points of their faces
//! (`values::FacetValues`: weight an area). cufem's fields there are the
//! ones its output shows (`post::FieldView::sample`: recovered stress and
//! peeq); the 3D fields are CalculiX's nodal fields interpolated in the
//! hexahedron holding the point (`ccx::sample`).
//!
//! **Norms.** For a region `Ω` and a quantity `q` (the displacement vector,
//! von Mises stress, peeq): the relative L2 difference
//! `‖q_cufem − q_3D‖_Ω / ‖q_3D‖_Ω` with `‖q‖²_Ω = Σ w |q|²`, and the largest
//! point-wise difference `max |q_cufem − q_3D|` in % of the largest 3D
//! value over the body (for a surface too: "of the largest |u|"), with the
//! point where it occurs. Regions: each body; each contact surface; the
//! plastic zone of each body, the points where either model's peeq exceeds
//! [`PLASTIC_ZONE`] of the body's largest 3D peeq.
//!
//! **Singular places.** A punch's edges, a roller's or a ball's contact line
//! or point carry stress singularities (or near-singularities) that no two
//! discretizations agree at. Points within one 3D element of them — `h =
//! (V / n)^{1/3}`, the body's volume over its number of hexahedra — are left
//! out of every norm and counted in the table, which names each zone and
//! its `h`. Contacts between deformable bodies have no such zone (their
//! contact edge is not known beforehand): nothing is left out there.

use serde::Serialize;

use crate::mesh::Part;
use crate::{CcxRun, HexMesh};
use cufem::contact::RigidSurface;
use cufem::post::FieldView;
use cufem::quantity::Sample;
use cufem::setup::Model;
use cufem::values::{FacetValues, Location, PointValues};

/// Share of a body's largest 3D peeq above which a point is in the plastic
/// zone.
pub const PLASTIC_ZONE: f64 = 1e-3;

/// One region and quantity compared over the whole field.
#[derive(Debug, Clone, Serialize)]
pub struct FieldRow {
    /// `body NAME`, `plastic zone NAME` or `surface CONTACT (side)`.
    pub region: String,
    /// `u` (the displacement vector), `von_mises` or `peeq`.
    pub quantity: String,
    /// Points compared.
    pub points: usize,
    /// Points left out as near a singular place.
    pub excluded: usize,
    /// `100 ‖q_cufem − q_3D‖ / ‖q_3D‖` over the region (weighted L2).
    pub l2_percent: f64,
    /// `100 max |q_cufem − q_3D|` over the region, in % of `scale`.
    pub max_percent: f64,
    /// Where the largest difference is (m).
    pub at: [f64; 3],
    /// The largest 3D value over the body (SI): the scale of `max_percent`.
    pub scale: f64,
}

/// A neighbourhood left out of the norms.
#[derive(Debug, Clone, Serialize)]
pub struct SingularZone {
    /// The indenter.
    pub indenter: String,
    /// What is singular there.
    pub place: String,
    /// Its half-width: one 3D element of the body (m).
    pub distance: f64,
    /// Sample points inside it.
    pub points: usize,
}

/// One sample point, both ways.
#[derive(Debug, Clone)]
pub struct FieldPoint {
    /// Where it is in the CUF mesh.
    pub location: Location,
    /// Position (m).
    pub x: [f64; 3],
    /// Volume or area weight.
    pub weight: f64,
    /// Body.
    pub body: usize,
    /// `None`: a volume point; `Some(k)`: a point of surface `k`.
    pub surface: Option<usize>,
    /// Inside a singular zone.
    pub excluded: bool,
    /// cufem's fields.
    pub ours: Sample,
    /// The 3D fields.
    pub theirs: Sample,
}

/// The whole-field comparison.
#[derive(Debug, Clone, Default)]
pub struct FieldComparison {
    /// Norms per region and quantity.
    pub rows: Vec<FieldRow>,
    /// The zones left out.
    pub zones: Vec<SingularZone>,
    /// Every sample point (for the difference VTU).
    pub points: Vec<FieldPoint>,
    /// The surfaces' names, as `FieldPoint::surface` indexes them.
    pub surfaces: Vec<String>,
}

/// Samples both solutions over every body and its contact surfaces and
/// compares them (module docs).
pub fn compare_fields(model: &Model, view: &FieldView<'_>, mesh: &HexMesh, run: &CcxRun) -> FieldComparison {
    let h = element_sizes(model, mesh);
    let zones = singular_zones(model, &h);
    let mut points = Vec::new();
    let mut push = |loc: Location, weight: f64, surface: Option<usize>| {
        let x = position(model, &loc);
        if let Some(t) = super::ccx_sample(model, mesh, run, std::slice::from_ref(&loc)) {
            let excluded = zones.iter().any(|z| z.body == loc.body && z.contains(x));
            points.push(FieldPoint {
                location: loc,
                x,
                weight,
                body: loc.body,
                surface,
                excluded,
                ours: view.sample(&loc),
                theirs: t,
            });
        }
    };
    for b in 0..model.mesh.bodies.len() {
        volume_points(model, b, &mut push);
    }
    let surfaces = contact_surfaces(model);
    for (k, (_, body, faces)) in surfaces.iter().enumerate() {
        for f in faces {
            face_points(model, *body, f, &mut |loc, w| push(loc, w, Some(k)));
        }
    }
    let rows = norms(model, &points, &surfaces);
    let zones = zones
        .iter()
        .map(|z| SingularZone {
            indenter: z.indenter.clone(),
            place: z.place.clone(),
            distance: z.distance,
            points: points.iter().filter(|p| p.body == z.body && z.contains(p.x)).count(),
        })
        .collect();
    FieldComparison { rows, zones, points, surfaces: surfaces.into_iter().map(|s| s.0).collect() }
}

impl FieldComparison {
    /// Writes the sample points with both models' fields and their
    /// differences (cufem − 3D): `u_cufem`, `u_3d`, `u_difference` (3
    /// components), `von_mises_*`, `peeq_*`, `excluded` (1 inside a singular
    /// zone) and `surface` (−1 for volume points, else the index of the
    /// contact surface in the table's order).
    pub fn write_vtu(&self, path: &std::path::Path, title: &str) -> Result<(), cufem::io::IoError> {
        use cufem::io::FieldArray;
        let pts = &self.points;
        let array = |name: &str, components: usize, f: &dyn Fn(&FieldPoint) -> Vec<f64>| FieldArray {
            name: name.to_string(),
            components,
            values: pts.iter().flat_map(f).collect(),
        };
        let coords: Vec<f64> = pts.iter().flat_map(|p| p.x).collect();
        let data = vec![
            array("u_cufem", 3, &|p| p.ours.u.to_vec()),
            array("u_3d", 3, &|p| p.theirs.u.to_vec()),
            array("u_difference", 3, &|p| (0..3).map(|k| p.ours.u[k] - p.theirs.u[k]).collect()),
            array("von_mises_cufem", 1, &|p| vec![p.ours.von_mises]),
            array("von_mises_3d", 1, &|p| vec![p.theirs.von_mises]),
            array("von_mises_difference", 1, &|p| vec![p.ours.von_mises - p.theirs.von_mises]),
            array("peeq_cufem", 1, &|p| vec![p.ours.peeq]),
            array("peeq_3d", 1, &|p| vec![p.theirs.peeq]),
            array("peeq_difference", 1, &|p| vec![p.ours.peeq - p.theirs.peeq]),
            array("excluded", 1, &|p| vec![f64::from(u8::from(p.excluded))]),
            array("surface", 1, &|p| vec![p.surface.map_or(-1.0, |k| k as f64)]),
        ];
        cufem::io::write_point_cloud(path, title, &coords, data)
    }
}

impl FieldComparison {
    /// The 3D side of every sample point as CSV (`field_points.csv`), enough
    /// to compare another cufem run of the same mesh without CalculiX
    /// ([`compare_stored`]): `body, element, xi, eta, zeta` (the CUF
    /// location), `weight` (m³, or m² on a surface), `surface` (−1: volume,
    /// else the contact surface's index), `excluded` (0/1), then the 3D
    /// `u_x, u_y, u_z` (m), `von_mises` (Pa) and `peeq`.
    pub fn points_csv(&self) -> String {
        use std::fmt::Write as _;
        let mut csv = String::from("body,element,xi,eta,zeta,weight,surface,excluded,u_x,u_y,u_z,von_mises,peeq\n");
        for p in &self.points {
            let l = &p.location;
            let t = &p.theirs;
            let _ = write!(csv, "{},{}", l.body, l.element);
            // 8 significant digits: far below the 3D model's own error
            for v in [l.natural[0], l.natural[1], l.natural[2], p.weight] {
                let _ = write!(csv, ",{v:.7e}");
            }
            let _ = write!(csv, ",{},{}", p.surface.map_or(-1, |k| k as i64), u8::from(p.excluded));
            for v in [t.u[0], t.u[1], t.u[2], t.von_mises, t.peeq] {
                let _ = write!(csv, ",{v:.7e}");
            }
            csv.push('\n');
        }
        csv
    }
}

/// Errors of a stored comparison.
#[derive(Debug, thiserror::Error)]
pub enum StoredError {
    /// A line of the CSV could not be read.
    #[error("field points line {line}: {reason}")]
    Line {
        /// 1-based line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
}

/// Compares `view` (a cufem solution of the mesh the CSV was made on) with
/// the 3D fields stored by [`FieldComparison::points_csv`] (lines starting
/// with `#` before the column names are a comment); the rows are those of
/// `cufem verify`.
pub fn compare_stored(model: &Model, view: &FieldView<'_>, csv: &str) -> Result<Vec<FieldRow>, StoredError> {
    compare_stored_on(model, model, view, csv)
}

/// As [`compare_stored`] for a solution `view` of `model`, another mesh of
/// the same bodies (a refinement, another element): the points are placed
/// by `stored_on`, the model the CSV was made on, and located in `model`'s
/// mesh by their position; the norms keep `stored_on`'s weights.
pub fn compare_stored_on(
    stored_on: &Model,
    model: &Model,
    view: &FieldView<'_>,
    csv: &str,
) -> Result<Vec<FieldRow>, StoredError> {
    let same = std::ptr::eq(stored_on, model);
    let mut points = Vec::new();
    // `#` lines (a provenance header) and the column names are skipped
    let rows = csv.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#')).skip(1);
    for (i, line) in rows {
        let bad = |reason: String| StoredError::Line { line: i + 1, reason };
        let v: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| bad(e.to_string()))?;
        if v.len() != 13 {
            return Err(bad(format!("{} columns, expected 13", v.len())));
        }
        let (body, element) = (v[0] as usize, v[1] as usize);
        if body >= stored_on.mesh.bodies.len() || element >= stored_on.mesh.bodies[body].n_elements() {
            return Err(bad(format!("body {body}, element {element}: not in this model's mesh")));
        }
        let location = Location { body, element, natural: [v[2], v[3], v[4]] };
        let x = position(stored_on, &location);
        let ours = if same {
            view.sample(&location)
        } else {
            let at = cufem::values::locate_in_model(&model.mesh, Some(body), x);
            view.sample_at(&at).ok_or_else(|| bad(format!("the point {x:?} is not in the other mesh")))?
        };
        let theirs = Sample { u: [v[8], v[9], v[10]], von_mises: v[11], peeq: v[12], ..Default::default() };
        points.push(FieldPoint {
            location,
            x,
            weight: v[5],
            body,
            surface: (v[6] >= 0.0).then_some(v[6] as usize),
            excluded: v[7] != 0.0,
            ours,
            theirs,
        });
    }
    Ok(norms(stored_on, &points, &contact_surfaces(stored_on)))
}

/// One 3D element per body: `(V / n)^{1/3}`.
fn element_sizes(model: &Model, mesh: &HexMesh) -> Vec<f64> {
    (0..model.mesh.bodies.len())
        .map(|b| {
            let cell = &model.cells[b];
            let sec: f64 = cell.section.weight.iter().sum();
            let len: f64 = cell.axis.weight.iter().sum();
            // Σ over elements of area × length = Σ_es A_es · Σ_eb L_eb
            let volume = sec * len;
            let n = mesh.parts.iter().filter(|p| **p == Part::Body(b)).count().max(1);
            (volume / n as f64).cbrt()
        })
        .collect()
}

/// Physical position of a located point.
fn position(model: &Model, loc: &Location) -> [f64; 3] {
    let pv = PointValues::new(&model.mesh.bodies[loc.body], loc);
    let mut x = [0.0; 3];
    for (&n, &node) in pv.shapes.iter().zip(&pv.nodes) {
        let c = model.mesh.coords(node);
        for k in 0..3 {
            x[k] += n * c[k];
        }
    }
    x
}

/// The Gauss points of body `b` with their volume weights.
fn volume_points(model: &Model, b: usize, push: &mut impl FnMut(Location, f64, Option<usize>)) {
    let body = &model.mesh.bodies[b];
    let cell = &model.cells[b];
    let (sec, axis) = (&cell.section, &cell.axis);
    for e in 0..body.n_elements() {
        let (es, eb) = body.split_element(e);
        for gb in 0..axis.n_gp {
            for gs in 0..sec.n_gp {
                let [xi, eta] = sec.natural[gs];
                let w = sec.weight[es * sec.n_gp + gs] * axis.weight[eb * axis.n_gp + gb];
                push(Location { body: b, element: e, natural: [xi, eta, axis.natural[gb]] }, w, None);
            }
        }
    }
}

/// The quadrature points of one face with their area weights.
fn face_points(model: &Model, b: usize, f: &cufem::bc::Face, push: &mut impl FnMut(Location, f64)) {
    let body = &model.mesh.bodies[b];
    let fv = FacetValues::new(body, f.section_element, f.beam_element, f.side);
    let element = f.beam_element * body.section.n_elements() + f.section_element;
    for (&natural, &w) in fv.natural.iter().zip(&fv.weights) {
        push(Location { body: b, element, natural }, w);
    }
}

/// Every contact surface: `(name, body, faces)`.
fn contact_surfaces(model: &Model) -> Vec<(String, usize, Vec<cufem::bc::Face>)> {
    let mut out: Vec<(String, usize, Vec<cufem::bc::Face>)> =
        model.indenters.iter().map(|i| (i.name.clone(), i.body, i.faces.clone())).collect();
    for c in &model.contacts {
        out.push((format!("{} (master)", c.name), c.master.body, c.master.faces.clone()));
        out.push((format!("{} (slave)", c.name), c.slave.body, c.slave.faces.clone()));
    }
    out
}

/// A neighbourhood of a singular place of an indenter (module docs).
struct Zone {
    indenter: String,
    place: String,
    body: usize,
    distance: f64,
    surface: RigidSurface,
}

impl Zone {
    /// Whether `x` (reference configuration) is within `distance` of the
    /// singular place.
    fn contains(&self, x: [f64; 3]) -> bool {
        let d = self.distance;
        match &self.surface {
            RigidSurface::Flat { axis, position, bounds, .. } => {
                if (x[*axis] - position).abs() > d {
                    return false;
                }
                let inside = |k: usize| bounds[k].is_none_or(|[lo, hi]| x[k] >= lo - d && x[k] <= hi + d);
                let at_edge =
                    |k: usize| bounds[k].is_some_and(|[lo, hi]| (x[k] - lo).abs() <= d || (x[k] - hi).abs() <= d);
                let plane: Vec<usize> = (0..3).filter(|k| k != axis).collect();
                plane.iter().all(|&k| inside(k)) && plane.iter().any(|&k| at_edge(k))
            }
            RigidSurface::Cylinder { axis, center, radius, length } => {
                let r2: f64 = (0..3).filter(|k| k != axis).map(|k| (x[k] - center[k]).powi(2)).sum();
                let along = length.is_none_or(|[lo, hi]| x[*axis] >= lo - d && x[*axis] <= hi + d);
                along && r2.sqrt() <= radius + d
            }
            RigidSurface::Sphere { center, radius } => {
                let r2: f64 = (0..3).map(|k| (x[k] - center[k]).powi(2)).sum();
                r2.sqrt() <= radius + d
            }
        }
    }
}

/// The singular places of every indenter: a flat punch's edges, a
/// roller's contact line, a ball's contact point.
fn singular_zones(model: &Model, h: &[f64]) -> Vec<Zone> {
    model
        .indenters
        .iter()
        .map(|i| Zone {
            indenter: i.name.clone(),
            place: match i.surface {
                RigidSurface::Flat { .. } => "the punch's edges",
                RigidSurface::Cylinder { .. } => "the roller's contact line",
                RigidSurface::Sphere { .. } => "the ball's contact point",
            }
            .to_string(),
            body: i.body,
            distance: h[i.body],
            surface: i.surface.clone(),
        })
        .collect()
}

/// Accumulated weighted sums of one region and quantity.
#[derive(Default)]
struct Norm {
    diff2: f64,
    ref2: f64,
    max: f64,
    at: [f64; 3],
    points: usize,
    excluded: usize,
}

impl Norm {
    fn add(&mut self, p: &FieldPoint, ours: &[f64], theirs: &[f64]) {
        if p.excluded {
            self.excluded += 1;
            return;
        }
        let d2: f64 = ours.iter().zip(theirs).map(|(a, b)| (a - b).powi(2)).sum();
        self.diff2 += p.weight * d2;
        self.ref2 += p.weight * theirs.iter().map(|v| v * v).sum::<f64>();
        if d2.sqrt() > self.max {
            self.max = d2.sqrt();
            self.at = p.x;
        }
        self.points += 1;
    }

    fn row(&self, region: String, quantity: &str, scale: f64) -> FieldRow {
        let ratio = |a: f64, b: f64| if b > 0.0 { 100.0 * a / b } else { 0.0 };
        FieldRow {
            region,
            quantity: quantity.to_string(),
            points: self.points,
            excluded: self.excluded,
            l2_percent: ratio(self.diff2.sqrt(), self.ref2.sqrt()),
            max_percent: ratio(self.max, scale),
            at: self.at,
            scale,
        }
    }
}

/// The norms of every region (module docs).
fn norms(model: &Model, points: &[FieldPoint], surfaces: &[(String, usize, Vec<cufem::bc::Face>)]) -> Vec<FieldRow> {
    let mut rows = Vec::new();
    let plastic = model.materials.iter().any(|m| m.is_plastic());
    for (b, body) in model.mesh.bodies.iter().enumerate() {
        let volume: Vec<&FieldPoint> = points.iter().filter(|p| p.body == b && p.surface.is_none()).collect();
        let largest = |f: &dyn Fn(&Sample) -> f64| volume.iter().map(|p| f(&p.theirs)).fold(0.0f64, f64::max);
        let u_scale = largest(&|s| super::norm(s.u));
        let vm_scale = largest(&|s| s.von_mises);
        let peeq_scale = largest(&|s| s.peeq);
        let (mut u, mut vm) = (Norm::default(), Norm::default());
        for p in &volume {
            u.add(p, &p.ours.u, &p.theirs.u);
            vm.add(p, &[p.ours.von_mises], &[p.theirs.von_mises]);
        }
        rows.push(u.row(format!("body {}", body.name), "u", u_scale));
        rows.push(vm.row(format!("body {}", body.name), "von_mises", vm_scale));
        if plastic && peeq_scale > 0.0 {
            let (mut vm, mut peeq) = (Norm::default(), Norm::default());
            let threshold = PLASTIC_ZONE * peeq_scale;
            for p in volume.iter().filter(|p| p.ours.peeq > threshold || p.theirs.peeq > threshold) {
                vm.add(p, &[p.ours.von_mises], &[p.theirs.von_mises]);
                peeq.add(p, &[p.ours.peeq], &[p.theirs.peeq]);
            }
            rows.push(vm.row(format!("plastic zone {}", body.name), "von_mises", vm_scale));
            rows.push(peeq.row(format!("plastic zone {}", body.name), "peeq", peeq_scale));
        }
        for (k, (name, _, _)) in surfaces.iter().enumerate().filter(|(_, s)| s.1 == b) {
            let mut u = Norm::default();
            for p in points.iter().filter(|p| p.surface == Some(k)) {
                u.add(p, &p.ours.u, &p.theirs.u);
            }
            rows.push(u.row(format!("surface {name}"), "u", u_scale));
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(weight: f64, ours: [f64; 3], theirs: [f64; 3], excluded: bool) -> FieldPoint {
        FieldPoint {
            location: Location { body: 0, element: 0, natural: [0.0; 3] },
            x: [weight, 0.0, 0.0],
            weight,
            body: 0,
            surface: None,
            excluded,
            ours: Sample { u: ours, ..Default::default() },
            theirs: Sample { u: theirs, ..Default::default() },
        }
    }

    #[test]
    fn norms_are_weighted_relative_l2_and_scaled_max() {
        // two points: weights 1 and 3; differences 0.1 and 0.2 (along x);
        // references 1 and 2: L2 = sqrt(1·0.01 + 3·0.04) / sqrt(1·1 + 3·4)
        let mut n = Norm::default();
        for p in [
            point(1.0, [1.1, 0.0, 0.0], [1.0, 0.0, 0.0], false),
            point(3.0, [2.0, 0.2, 0.0], [2.0, 0.0, 0.0], false),
            point(5.0, [9.0, 0.0, 0.0], [0.0, 0.0, 0.0], true),
        ] {
            n.add(&p, &p.ours.u, &p.theirs.u);
        }
        let row = n.row("body b".into(), "u", 4.0);
        let l2 = 100.0 * (0.01f64 + 3.0 * 0.04).sqrt() / 13.0f64.sqrt();
        assert!((row.l2_percent - l2).abs() < 1e-12, "{} vs {l2}", row.l2_percent);
        assert!((row.max_percent - 5.0).abs() < 1e-12, "{}", row.max_percent);
        assert_eq!(row.at, [3.0, 0.0, 0.0]);
        assert_eq!((row.points, row.excluded), (2, 1));
    }

    #[test]
    fn zones_hold_a_punch_edge_a_roller_line_and_a_ball() {
        let zone = |surface| Zone { indenter: "i".into(), place: String::new(), body: 0, distance: 0.01, surface };
        // a punch on z = 0.3 over x ∈ [0.2, 0.3], unbounded in y
        let punch =
            zone(RigidSurface::Flat { axis: 2, sign: -1.0, position: 0.3, bounds: [Some([0.2, 0.3]), None, None] });
        assert!(punch.contains([0.205, 5.0, 0.295]) && punch.contains([0.3, 0.0, 0.3]));
        assert!(!punch.contains([0.25, 0.0, 0.3]), "the middle of the face is not an edge");
        assert!(!punch.contains([0.2, 0.0, 0.2]), "away from the face plane");
        assert!(!punch.contains([0.1, 0.0, 0.3]), "outside the face");
        let roller = zone(RigidSurface::Cylinder { axis: 0, center: [0.0, 0.1, 0.015], radius: 0.005, length: None });
        assert!(roller.contains([7.0, 0.1, 0.01]) && !roller.contains([0.0, 0.08, 0.01]));
        let ball = zone(RigidSurface::Sphere { center: [0.0; 3], radius: 0.01 });
        assert!(ball.contains([0.0, 0.0, 0.019]) && !ball.contains([0.0, 0.0, 0.021]));
    }
}
