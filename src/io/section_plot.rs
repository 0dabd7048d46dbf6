//! PNG drawings of section meshes (`cufem check --plot`): elements through
//! their isoparametric map (curved edges as they are integrated), nodes,
//! and the section's regions in colour.

use std::path::Path;

use plotters::prelude::*;

use super::IoError;
use super::png::{plot_error, register_font};
use crate::mesh::CrossSection;

/// Draws `section` into a 1000 × 1000 PNG at `path` with equal scales on x
/// and z (mm); `title` is the caption.
pub fn section_plot(path: &Path, title: &str, section: &CrossSection) -> Result<(), IoError> {
    register_font();
    let mm = |p: [f64; 2]| (p[0] * 1e3, p[1] * 1e3);
    let b = section.bounds();
    let (cx, cz) = (0.5 * (b[0] + b[1]) * 1e3, 0.5 * (b[2] + b[3]) * 1e3);
    let half = 0.55 * ((b[1] - b[0]).max(b[3] - b[2]) * 1e3).max(1e-9);
    let root = BitMapBackend::new(path, (1000, 1000)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(super::png::printable(title), ("sans-serif", 20))
        .margin(18)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(cx - half..cx + half, cz - half..cz + half)
        .map_err(|e| plot_error(path, e))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x [mm]")
        .y_desc("z [mm]")
        .label_style(("sans-serif", 16))
        .draw()
        .map_err(|e| plot_error(path, e))?;
    let per_edge = 2 * section.kind.order() + 2;
    // regions filled (one colour each), then every element's outline
    let mut region_of = vec![None; section.n_elements()];
    for (r, region) in section.regions.iter().enumerate() {
        for &e in &region.elements {
            region_of[e] = Some(r);
        }
    }
    for e in 0..section.n_elements() {
        let outline: Vec<(f64, f64)> = section.outline(e, per_edge).into_iter().map(mm).collect();
        let fill = region_of[e].map_or(RGBColor(220, 220, 220).mix(1.0), |r| Palette99::pick(r).mix(0.25));
        chart.draw_series(std::iter::once(Polygon::new(outline.clone(), fill))).map_err(|e| plot_error(path, e))?;
        let mut closed = outline;
        closed.push(closed[0]);
        chart.draw_series(std::iter::once(PathElement::new(closed, BLACK))).map_err(|e| plot_error(path, e))?;
    }
    // corner nodes larger than the high-order nodes
    let p = section.kind.order();
    let mut corner = vec![false; section.n_nodes()];
    for e in 0..section.n_elements() {
        let el = section.element(e);
        for k in [0, p, p * (p + 1), (p + 1) * (p + 1) - 1] {
            corner[el[k]] = true;
        }
    }
    let nodes = section
        .nodes
        .iter()
        .zip(&corner)
        .map(|(&n, &c)| if c { Circle::new(mm(n), 3, BLUE.filled()) } else { Circle::new(mm(n), 2, RED.filled()) });
    chart.draw_series(nodes).map_err(|e| plot_error(path, e))?;
    for (r, region) in section.regions.iter().enumerate() {
        let colour = Palette99::pick(r).mix(0.6);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(|e| plot_error(path, e))?
            .label(format!("{} ({} elements)", region.name, region.elements.len()))
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 16, y + 6)], colour.filled()));
    }
    if !section.regions.is_empty() {
        super::png::draw_legend(&mut chart, path)?;
    }
    root.present().map_err(|e| plot_error(path, e))?;
    Ok(())
}
