//! The cells of a rectangular grid of element boundaries with a
//! rectangular hole left out (a `rectangle` section's `hole`, a `tube`):
//! which boundary a hole's edge lies on, and which cell holds element `s`.

/// The index of the boundary among `lines` at `v`, to 1e-9 of `size` (a
/// hole's edge on a grid's element boundaries).
pub(crate) fn boundary_at(lines: &[f64], v: f64, size: f64) -> Option<usize> {
    lines.iter().position(|&l| (l - v).abs() <= 1e-9 * size)
}

/// The larger extent of a grid of boundaries `x_lines` × `z_lines`.
pub(crate) fn grid_size(x_lines: &[f64], z_lines: &[f64]) -> f64 {
    (x_lines[x_lines.len() - 1] - x_lines[0]).max(z_lines[z_lines.len() - 1] - z_lines[0])
}

/// The interval ranges `[[i0, i1], [j0, j1]]` of a hole `[[x0, x1], [z0,
/// z1]]` (m) whose edges lie on the boundaries `x_lines` and `z_lines`
/// ([`boundary_at`]; an edge off them gives an empty range).
pub(crate) fn hole_intervals(x_lines: &[f64], z_lines: &[f64], hole: [[f64; 2]; 2]) -> [[usize; 2]; 2] {
    let size = grid_size(x_lines, z_lines);
    let range = |lines: &[f64], [a, b]: [f64; 2]| match (boundary_at(lines, a, size), boundary_at(lines, b, size)) {
        (Some(i), Some(j)) => [i, j],
        _ => [0, 0],
    };
    [range(x_lines, hole[0]), range(z_lines, hole[1])]
}

/// Whether cell `(i, j)` lies in the hole's interval ranges.
fn in_hole(hole: Option<[[usize; 2]; 2]>, i: usize, j: usize) -> bool {
    hole.is_some_and(|[a, b]| (a[0]..a[1]).contains(&i) && (b[0]..b[1]).contains(&j))
}

/// The cells `(i, j)` of a grid of `nx` × `nz` intervals in element order
/// (z interval by z interval, x fastest), those with `i` in
/// `hole[0][0]..hole[0][1]` and `j` in `hole[1][0]..hole[1][1]` left out
/// (`CrossSection::hollow_rectangle`).
pub(super) fn grid_cells(nx: usize, nz: usize, hole: Option<[[usize; 2]; 2]>) -> impl Iterator<Item = (usize, usize)> {
    (0..nz).flat_map(move |j| (0..nx).map(move |i| (i, j))).filter(move |&(i, j)| !in_hole(hole, i, j))
}

/// The cell `(i, j)` of element `s` in the order of [`grid_cells`], row by
/// row without listing the cells (`None` past the last).
pub(crate) fn grid_cell(nx: usize, nz: usize, hole: Option<[[usize; 2]; 2]>, s: usize) -> Option<(usize, usize)> {
    let mut before = 0;
    for j in 0..nz {
        let gap = match hole {
            Some([a, b]) if (b[0]..b[1]).contains(&j) => a[1].saturating_sub(a[0]).min(nx),
            _ => 0,
        };
        if s < before + nx - gap {
            let k = s - before;
            // the k-th cell of the row, the hole's cells skipped
            let i = match hole {
                Some([a, _]) if gap > 0 && k >= a[0] => k + gap,
                _ => k,
            };
            return Some((i, j));
        }
        before += nx - gap;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Element `s` of a grid is the `s`-th cell of `grid_cells`, with and
    /// without a hole (one touching the last column too), and none past the
    /// last cell.
    #[test]
    fn a_grid_cell_is_found_without_listing_the_cells() {
        for hole in [None, Some([[1, 4], [2, 3]]), Some([[2, 5], [0, 2]])] {
            let cells: Vec<_> = grid_cells(5, 4, hole).collect();
            for (s, cell) in cells.iter().enumerate() {
                assert_eq!(grid_cell(5, 4, hole, s), Some(*cell), "{hole:?}, element {s}");
            }
            assert_eq!(grid_cell(5, 4, hole, cells.len()), None);
        }
    }
}
