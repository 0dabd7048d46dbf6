//! Superconvergent patch recovery of the Gauss-point stresses, for the error
//! estimate ([`super::estimate`]).
//!
//! Zienkiewicz & Zhu (*Int. J. Numer. Methods Eng.* 33, 1992, "The
//! superconvergent patch recovery and a posteriori error estimates", part 1):
//! each stress component is fitted, by least squares over the Gauss points
//! of a patch of elements, with a polynomial of the element's own degree
//! `p`, one degree above the stress it fits; the fit filters the
//! element-periodic part of the stress error, which no continuous field of
//! the element's own basis removes when `p` is even (the derivative error of
//! a degree-`p` Lagrange element is, to leading order, `∝ P_p(ξ)` in each
//! element, equal at both ends of it, so a global L2 projection onto the
//! continuous basis reproduces it).
//!
//! In CUF a body is a tensor product, section mesh (x–z) × beam axis (y),
//! and so are its Gauss points. The patch of element `(s, b)` is the
//! product of the section elements sharing a node with `s` and the beam
//! elements `b − 1 ..= b + 1`; the fitted polynomial is the tensor product
//! `Q_{p_s}(x, z) ⊗ P_{p_a}(y)` (Legendre polynomials of coordinates scaled
//! to the patch). On a product of point sets with a product basis the
//! least-squares operator factorizes, `(A_s ⊗ A_a)⁺ = A_s⁺ ⊗ A_a⁺`, so the
//! fit is one small section operator per section element and one axis
//! operator per beam element, applied one after the other:
//!
//! ```text
//! σ*(s, g_s, b, g_a) = Σ_{s' g_s'} R_s[g_s, (s' g_s')] Σ_{b' g_a'} R_b[g_a, (b' g_a')] σ_h(s', g_s', b', g_a')
//! R = V A⁺ :  A = basis at the patch's Gauss points, V = basis at the element's own
//! ```
//!
//! Along the axis each element has up to three candidate patches: itself
//! with both neighbours, with the one before, with the one after; for each
//! section point and stress component the fit with the smallest mean
//! squared residual per redundant point is used, fits within `1e-6` of
//! the data of the first counting as ties that go to it (`TIE`) (the
//! choice of the smoothest stencil of ENO schemes, Harten, Engquist, Osher & Chakravarthy,
//! *J. Comput. Phys.* 71, 1987). A centred patch beside a singular element
//! (the clamped root of a cantilever, a roller's contact line) fits that
//! element's steep raw stresses and overestimated the error of its
//! neighbour 2.6–3.0 times (cantilever, beyond the root element) and 1.8
//! times (compact bar, away from the roller lines); the one-sided patch is
//! smooth there and brings both to 0.75–1.04. In the smooth interior the
//! candidates fit equally well. Over the section the patch is the full ring
//! (one-sided section patches would interpolate in the direction across a
//! boundary and hide the error there) of the section elements of the
//! element's own material: in a layered body (plies, material zones) the
//! stress jumps between materials, and a patch across the interface would
//! smooth the jump and count it as error; kept to one material, a ply's
//! piecewise-constant stress under a uniform in-plane strain is reproduced
//! exactly (`post::mode_error`'s laminate patch test). A ply one element
//! thick would then be a patch one element thick, through which the fit
//! interpolates and sees no error — yet there the error of a laminate lies,
//! in its transverse stresses. Equilibrium makes the traction of an
//! interface continuous: across an interface of normal z the components
//! σ_zz, σ_xz, σ_yz, across one of normal x σ_xx, σ_xy, σ_xz. Where an
//! element is the only one of its zone through a direction (no element of
//! its zone beside it along z, or x), those components are fitted over the
//! patch with the elements across the interface added (beside it along that
//! direction, and at its corners in their zones); the other components keep
//! to the zone. On Pagano's cross-ply laminate with one L9 per ply this
//! takes the effectivity from `0.003`–`0.26` to `1.12`–`1.14`
//! (tests/layered_estimate.rs). An interface that is neither along x nor
//! along z (a curved wall's plies) keeps the per-zone patch.
//!
//! Each element of a section patch weighs by its area: the rows of its
//! Gauss points are scaled by `√(A_f / A_max)`, a weighted least-squares
//! fit close to the L2 projection of `σ_h` over the patch onto `Q_p`, the
//! local projection of which the patch recovery is the discrete version
//! (Li & Zhang, *Numer. Methods Partial Differ. Equ.* 15, 1999). On a
//! patch of equal elements this is the paper's plain fit. Where a patch
//! joins elements of very different sizes — a thin-walled profile's
//! junction squares, a wall's or a ply's thickness on a side, beside wall
//! elements tens of times longer — the plain fit gives the small element's
//! points as much say as the large one's, and the polynomial bends over
//! the whole patch towards the junction's own stress state. On the
//! laminated torsion box (`bench/box_laminated_modes.toml`, 3 × 2 L9 along
//! the walls, 0.25 mm ply elements at the corners) the plain fit put the
//! wall modes' frequency errors at `4.1`–`12.2 %`, `3.0`–`9.9` times their
//! true errors against 24 × 16 L9 × 16 B4 with graded walls; weighted,
//! every one of the eight modes lies at `0.71`–`1.73` times its true error
//! (tests/mode_error.rs and tests/modal_adapt.rs check the effectivity of
//! two such boxes). The cost: a small element's steep stresses no longer
//! tell its large neighbour about a feature the neighbour leaves
//! unresolved, and a static profile's estimate is then held by its
//! re-entrant corners (docs/limitations.md, the I-beam of
//! crates/cufem-cli/tests/adapt.rs).
//!
//! A section patch does not reach round a re-entrant corner
//! (`CrossSection::reentrant_corners`: the inner corner where two walls of
//! a profile meet, a hole's corner): an element touching the element only
//! at such a corner is left out. There a wall element's ring held the other
//! wall's element, of the same area and with its stresses turned by `90°`
//! (a flange's bending stress is the web's stress across its thickness);
//! fitted together, the polynomial bent over the whole wall element, and the
//! estimate charged every wall element at a junction with an error its
//! elements do not have. On the shipped channel's vibration modes
//! (examples/cantilever_modes.toml against every division four times
//! finer) that took the effectivity from `0.66`–`6.1` to `0.63`–`1.81`
//! (tests/mode_error.rs).
//!
//! A section patch is fitted in its element's natural coordinates, the
//! element's isoparametric map continued over the patch, each point's
//! stress turned into the frame that turns with the map
//! (`post::patch_map`): on a curved wall (a circular tube) the stress
//! turns with the wall, which a polynomial in x and z over three elements
//! misses (the shrink fit's estimate fell from `7.6` to `1.05` times its
//! true error against Lamé, tests/step_error.rs). On a grid of
//! axis-aligned rectangles the continued map is affine and the fit the
//! Cartesian one.
//!
//! Every fit is evaluated only on the element the patch belongs to
//! (element patches rather than the node patches of the paper: every
//! element, also at a boundary, has a patch around it, and no boundary node
//! needs the patch of another). `σ*` is therefore discontinuous between
//! elements; it is only compared with `σ_h` inside each element. A field the
//! polynomial holds (a constant or linear stress, pure bending) is
//! reproduced exactly, so the patch test gives `σ* = σ_h`. Where a patch
//! has a single element in a direction (a single beam element, a section
//! element whose faces along that direction are both straight boundaries
//! of the section: a one-element section, a wall one element thick) the
//! fit interpolates its Gauss points in that direction and sees no error
//! there; so the shear tractions of such an element's faces are held at
//! zero in its section fit (`post::free_faces`: the elastica's one L9 is
//! estimated at `0.73`–`0.81` times its true error, at `0.12`–`0.45` with
//! the element interpolated; tests/step_error.rs), for stresses in the
//! body's own axes only: not a strain
//! (`post::yielded`), and nonlinear geometry's Cauchy stresses are turned
//! into second Piola–Kirchhoff ones first
//! (`post::estimate::of_state`). `A⁺` is the pseudo-inverse through the
//! eigenvalues of `AᵀA`, those below `1e-12` of the largest dropped
//! (degenerate patches).

use super::free_faces::{SHEAR_X, SHEAR_Z};
use super::least_squares::{fit_operator, residual_operator};
use crate::mesh::{BeamAxis, CrossSection, Mesh};
use crate::shape::Lagrange2d;
use crate::values::{AxisValues, CellValues, SectionValues};
use crate::voigt::Voigt;

/// A patch operator: the element's own points from the patch's points.
struct Patch {
    /// Elements of the patch (the element itself among them).
    elements: Vec<usize>,
    /// `R[g, k]`, `g` the element's points, `k` the patch's points (element-major), row-major.
    weights: Vec<f64>,
    /// `I − A A⁺` over the patch's points (row-major): the fit's residual.
    residual: Vec<f64>,
    /// A curved section patch's frames (module docs): `[cos δ, sin δ]` of
    /// the turn of each patch point's frame, then of each of the element's
    /// own points; empty where every frame is the element's (a straight
    /// patch, an axis patch).
    turn: Vec<[f64; 2]>,
}

/// Legendre polynomials `P_0 … P_n` at `x`.
fn legendre(n: usize, x: f64, out: &mut [f64]) {
    out[0] = 1.0;
    if n >= 1 {
        out[1] = x;
    }
    for k in 2..=n {
        out[k] = ((2 * k - 1) as f64 * x * out[k - 1] - (k - 1) as f64 * out[k - 2]) / k as f64;
    }
}

/// The `Q_p(x, z)` basis at `(x, z)` scaled by centre and half-widths.
fn section_basis(p: usize, at: [f64; 2], centre: [f64; 2], half: [f64; 2], out: &mut Vec<f64>) {
    let (mut lx, mut lz) = (vec![0.0; p + 1], vec![0.0; p + 1]);
    legendre(p, (at[0] - centre[0]) / half[0], &mut lx);
    legendre(p, (at[1] - centre[1]) / half[1], &mut lz);
    for a in &lx {
        for b in &lz {
            out.push(a * b);
        }
    }
}

/// Centre and half-widths of a point set (a zero width becomes 1).
fn frame(points: impl Iterator<Item = [f64; 2]>) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in points {
        for d in 0..2 {
            lo[d] = lo[d].min(q[d]);
            hi[d] = hi[d].max(q[d]);
        }
    }
    let half = std::array::from_fn(|d| if hi[d] > lo[d] { 0.5 * (hi[d] - lo[d]) } else { 1.0 });
    (std::array::from_fn(|d| 0.5 * (lo[d] + hi[d])), half)
}

/// The stress components a material interface of normal z (in the
/// section plane) passes on continuously: the traction `σ·e_z` = (σ_zz,
/// σ_xz, σ_yz) (Voigt indices, `crate::voigt`).
const ACROSS_Z: [usize; 3] = [2, 4, 5];
/// The same for an interface of normal x: `σ·e_x` = (σ_xx, σ_xy, σ_xz).
const ACROSS_X: [usize; 3] = [0, 3, 4];

/// The section patches of one element: their operators and, per stress
/// component, the one that fits it.
struct SectionPatches {
    patches: Vec<Patch>,
    of_component: [usize; 6],
}

/// The elements sharing a node with section element `e` (`holding`: the
/// elements at each node), without those that touch it only at a
/// re-entrant corner (module docs).
fn ring(section: &CrossSection, holding: &[Vec<usize>], reentrant: &[bool], e: usize) -> Vec<usize> {
    let nodes = section.element(e);
    let shared = |f: usize| nodes.iter().copied().filter(move |t| section.element(f).contains(t));
    nodes
        .iter()
        .flat_map(|&t| holding[t].iter().copied())
        .filter(|&f| {
            let mut common = shared(f);
            !matches!((common.next(), common.next()), (Some(t), None) if reentrant[t])
        })
        .collect()
}

/// What every section patch of one section is fitted with: its elements'
/// Gauss points, basis and areas.
struct SectionFit<'a> {
    section: &'a CrossSection,
    values: &'a SectionValues,
    basis: Lagrange2d,
    area: Vec<f64>,
}

impl<'a> SectionFit<'a> {
    fn new(section: &'a CrossSection, values: &'a SectionValues) -> Self {
        let ng = values.n_gp;
        let area = (0..section.n_elements()).map(|f| values.weight[f * ng..(f + 1) * ng].iter().sum()).collect();
        SectionFit { section, values, basis: Lagrange2d::new(section.kind.order()), area }
    }

    /// The operator of element `e`'s patch of `elements`, the shear
    /// tractions held at zero at the points `free` of its faces (module
    /// docs; none where `free` is empty).
    fn patch(&self, e: usize, mut elements: Vec<usize>, free: &[[f64; 2]]) -> Patch {
        let (section, values, area) = (self.section, self.values, &self.area);
        let (p, ng) = (section.kind.order(), values.n_gp);
        elements.sort_unstable();
        elements.dedup();
        let points = |list: &[usize]| -> Vec<[f64; 2]> {
            list.iter().flat_map(|&f| values.position[f * ng..(f + 1) * ng].iter().copied()).collect()
        };
        // in the coordinates and frames of the element's own map (module
        // docs); the points of the traction-free faces after the element's own
        let mut own_points = points(&[e]);
        own_points.extend_from_slice(free);
        let super::patch_map::PatchCoordinates { patch: patch_points, mut own, mut turn } =
            super::patch_map::coordinates(section, &self.basis, e, points(&elements), own_points);
        let held = own.split_off(ng);
        turn.truncate(patch_points.len() + ng);
        let (centre, half) = frame(patch_points.iter().copied());
        let (mut a, mut v) = (Vec::new(), Vec::new());
        for &q in &patch_points {
            section_basis(p, q, centre, half, &mut a);
        }
        for &q in &own {
            section_basis(p, q, centre, half, &mut v);
        }
        // each element weighs by its area: √(A_f / A_max) on its rows
        let largest = elements.iter().map(|&f| area[f]).fold(0.0f64, f64::max);
        let scale: Vec<f64> =
            elements.iter().flat_map(|&f| std::iter::repeat_n((area[f] / largest).sqrt(), ng)).collect();
        let n = (p + 1) * (p + 1);
        for (row, s) in a.chunks_mut(n).zip(&scale) {
            row.iter_mut().for_each(|x| *x *= s);
        }
        // a straight patch's held faces: among the polynomials vanishing there
        let basis = |q: [f64; 2], out: &mut Vec<f64>| section_basis(p, q, centre, half, out);
        let held = if turn.is_empty() { super::free_faces::fit(&held, basis, (&a, &v), n) } else { None };
        let mut weights = held.unwrap_or_else(|| fit_operator(&a, &v, n));
        let m = scale.len();
        for row in weights.chunks_mut(m) {
            row.iter_mut().zip(&scale).for_each(|(x, s)| *x *= s);
        }
        Patch { weights, residual: Vec::new(), elements, turn }
    }
}

/// The patches of every section element (module docs): the elements
/// sharing a node with it and lying in its zone (`zone`: the material of
/// each section element), and for the traction components of an interface
/// of normal z or x between zones also the elements across it.
fn section_patches(
    section: &CrossSection,
    values: &SectionValues,
    zone: &dyn Fn(usize) -> usize,
    free_faces: bool,
) -> Vec<SectionPatches> {
    let holding = section.elements_at_nodes();
    // each element's box [x_min, x_max, z_min, z_max]
    let boxes: Vec<[f64; 4]> = (0..section.n_elements())
        .map(|e| {
            section.element(e).iter().fold(
                [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY],
                |b, &t| {
                    let [x, z] = section.nodes[t];
                    [b[0].min(x), b[1].max(x), b[2].min(z), b[3].max(z)]
                },
            )
        })
        .collect();
    let reentrant = section.reentrant_corners();
    let [x0, x1, z0, z1] = section.bounds();
    let tol = 1e-9 * (x1 - x0).max(z1 - z0);
    // whether b lies beside a along the coordinate (0: x, 2: z), sharing no interior
    let apart = |a: &[f64; 4], b: &[f64; 4], d: usize| b[d] >= a[d + 1] - tol || b[d + 1] <= a[d] + tol;
    let fit = SectionFit::new(section, values);
    let operator = |e: usize, elements: Vec<usize>, free: &[[f64; 2]]| fit.patch(e, elements, free);
    // each element's faces through z and through x, where it is alone
    // through the section there (`post::free_faces`)
    let faces: Vec<[Vec<[f64; 2]>; 2]> = (0..section.n_elements())
        .map(|e| match free_faces {
            true => [2, 0].map(|d| super::free_faces::through(section, (&holding, &boxes), e, d, tol)),
            false => [Vec::new(), Vec::new()],
        })
        .collect();
    (0..section.n_elements())
        .map(|e| {
            let ring = ring(section, &holding, &reentrant, e);
            let own: Vec<usize> = ring.iter().copied().filter(|&f| zone(f) == zone(e)).collect();
            // elements of other zones across an interface of normal z (d = 2)
            // or x (d = 0): those beside e along d and overlapping it
            // along the other coordinate, and those at its corners in the
            // zones of the former
            let across = |d: usize| -> Vec<usize> {
                let other = 2 - d;
                let (ea, eb) = (&boxes[e], |f: usize| &boxes[f]);
                // a zone two elements deep along d has its own patch there
                if own.iter().any(|&f| f != e && apart(ea, eb(f), d) && !apart(ea, eb(f), other)) {
                    return Vec::new();
                }
                let others: Vec<usize> = ring.iter().copied().filter(|&f| zone(f) != zone(e)).collect();
                let faces: Vec<usize> =
                    others.iter().copied().filter(|&f| apart(ea, eb(f), d) && !apart(ea, eb(f), other)).collect();
                let zones: Vec<usize> = faces.iter().map(|&f| zone(f)).collect();
                let corners = others
                    .iter()
                    .copied()
                    .filter(|&f| apart(ea, eb(f), d) && apart(ea, eb(f), other) && zones.contains(&zone(f)));
                faces.iter().copied().chain(corners).collect()
            };
            let (z, x) = (across(2), across(0));
            // the faces of an element alone through z or x (module docs)
            // held only where every element of the ring on the faces' lines
            // (not beside it along d) has them free too: a junction's line
            // is interior there
            let held = |k: usize, d: usize| match ring
                .iter()
                .all(|&f| apart(&boxes[e], &boxes[f], d) || !faces[f][k].is_empty())
            {
                true => faces[e][k].clone(),
                false => Vec::new(),
            };
            let (free_z, free_x) = (held(0, 2), held(1, 0));
            let mut patches = vec![operator(e, own.clone(), &[])];
            let mut frees = vec![Vec::new()];
            let mut of_component = [0; 6];
            for (c, slot) in of_component.iter_mut().enumerate() {
                // the elements across an interface for its traction, the
                // held faces' points for the shear tractions (module docs)
                let some = |on: bool, list: &[usize]| if on { list.to_vec() } else { Vec::new() };
                let mut elements = own.clone();
                elements.extend(some(ACROSS_Z.contains(&c), &z).into_iter().chain(some(ACROSS_X.contains(&c), &x)));
                elements.sort_unstable();
                elements.dedup();
                let held = |on: bool, points: &[[f64; 2]]| if on { points.to_vec() } else { Vec::new() };
                let mut free = held(SHEAR_Z.contains(&c), &free_z);
                free.extend(held(SHEAR_X.contains(&c), &free_x));
                *slot = match (0..patches.len()).find(|&k| patches[k].elements == elements && frees[k] == free) {
                    Some(k) => k,
                    None => {
                        patches.push(operator(e, elements, &free));
                        frees.push(free);
                        patches.len() - 1
                    }
                };
            }
            SectionPatches { patches, of_component }
        })
        .collect()
}

/// The candidate patches of every beam element: itself with both
/// neighbours, with the one before, with the one after (those that exist).
///
/// A body with one element along its axis has no neighbour to fit with,
/// and a fit of degree `p` through its `p + 1` Gauss points interpolates
/// them: the error along the axis goes unseen (a cantilever of one B2,
/// its tip 97 % short of the beam's, was estimated at `0.15 %` and
/// `--adapt` stopped at once). A lone element fits one degree less: a B2
/// a constant, so the estimate holds the stress's linear part along the
/// element, which a slice whose fields are constant along it (plane
/// strain, generalized plane stress: the shipped one-B2 examples) does not
/// have; the paper's block (one B4, its plastic squeeze-out along the axis
/// under the punch) is estimated at `30.4 %` instead of `28.5 %`.
fn axis_patches(axis: &BeamAxis, values: &AxisValues) -> Vec<Vec<Patch>> {
    let (p, ng, ne) = (axis.kind.order(), values.n_gp, axis.n_elements());
    let patch = |e: usize, elements: Vec<usize>| {
        let p = if elements.len() == 1 { p - 1 } else { p };
        let ys: Vec<f64> =
            elements.iter().flat_map(|&f| values.position[f * ng..(f + 1) * ng].iter().copied()).collect();
        let (centre, half) = frame(ys.iter().map(|&y| [y, 0.0]));
        let basis = |y: f64, out: &mut Vec<f64>| {
            let mut l = vec![0.0; p + 1];
            legendre(p, (y - centre[0]) / half[0], &mut l);
            out.extend(l);
        };
        let (mut a, mut v) = (Vec::new(), Vec::new());
        ys.iter().for_each(|&y| basis(y, &mut a));
        values.position[e * ng..(e + 1) * ng].iter().for_each(|&y| basis(y, &mut v));
        Patch {
            weights: fit_operator(&a, &v, p + 1),
            residual: residual_operator(&a, p + 1),
            elements,
            turn: Vec::new(),
        }
    };
    (0..ne)
        .map(|e| {
            let mut list = Vec::new();
            if e > 0 && e + 1 < ne {
                list.push(vec![e - 1, e, e + 1]);
            }
            if e > 0 {
                list.push(vec![e - 1, e]);
            }
            if e + 1 < ne {
                list.push(vec![e, e + 1]);
            }
            if list.is_empty() {
                list.push(vec![e]);
            }
            list.into_iter().map(|elements| patch(e, elements)).collect()
        })
        .collect()
}

/// Residuals within this fraction of the data are a tie: a later
/// candidate replaces the first only if its mean squared residual is below
/// the first's by more than `(TIE · max |f|)²` and by `TIE` of it. The
/// data are known to Newton's tolerance, not to round-off; with a strict
/// minimum, fits equal to round-off (a stress about uniform along the
/// axis) were chosen by the solver's last digits, and the recovery moved
/// with them: `examples/block_indentation_graded.toml` was estimated at
/// `22.08` and `22.21 %`, one element's error at `2.2e-2` and `0.9e-2`,
/// with and without a change of the factor reuse that left its stresses,
/// strains and plastic strains equal to `1e-9` (`21.97 %` both ways with
/// `TIE`: tests/estimator.rs `the_block_estimate_does_not_follow_the_solver_path`).
const TIE: f64 = 1e-6;

/// The candidate whose fit of `f` (values at each candidate's points) leaves
/// the smallest mean squared residual per redundant point, ties
/// ([`TIE`]) going to the first (`values`: a buffer reused between calls).
fn smoothest(
    candidates: &[Patch],
    per_element: usize,
    n_terms: usize,
    f: &dyn Fn(&Patch, usize) -> f64,
    values: &mut Vec<f64>,
) -> usize {
    let mut best = (0, f64::INFINITY);
    for (i, patch) in candidates.iter().enumerate() {
        let m = patch.elements.len() * per_element;
        if m <= n_terms {
            continue;
        }
        values.clear();
        values.extend((0..m).map(|k| f(patch, k)));
        let r2: f64 =
            (0..m).map(|i| (0..m).map(|j| patch.residual[i * m + j] * values[j]).sum::<f64>().powi(2)).sum::<f64>()
                / (m - n_terms) as f64;
        let floor = (TIE * values.iter().fold(0.0f64, |a, v| a.max(v.abs()))).powi(2);
        if r2 < best.1 * (1.0 - TIE) - floor {
            best = (i, r2);
        }
    }
    best.0
}

/// The recovered stress `σ*` at every Gauss point of every body (the layout
/// of `stresses`: body `b` from `gp_offsets[b]`, element-major, axis point
/// outer, section point inner) and its first stage, the fit along the axis alone
/// (the same layout): `σ* − σ_along` is what the fit over the section
/// adds, the error the estimate finds across the section. `shear`: the
/// ratio of the stored shears to the tensor's (1 for stresses, 2 for
/// engineering strains), for the frames of curved patches. `free_faces`:
/// the fields are stresses in the section's own axes, whose shear
/// tractions vanish on a free face (module docs) — not a strain (plastic
/// shear strains, anisotropic couplings), nor the Cauchy stress of a body
/// that turned with nonlinear geometry.
pub(crate) fn recover_stages(
    mesh: &Mesh,
    cells: &[CellValues],
    (stresses, shear): (&[Voigt], f64),
    gp_offsets: &[usize],
    free_faces: bool,
) -> (Vec<Voigt>, Vec<Voigt>) {
    let mut out = vec![[0.0; 6]; stresses.len()];
    let mut first = vec![[0.0; 6]; stresses.len()];
    for (b, body) in mesh.bodies.iter().enumerate() {
        let cell = &cells[b];
        let (gs, ga) = (cell.section.n_gp, cell.axis.n_gp);
        let (ns, na) = (body.section.n_elements(), body.axis.n_elements());
        let ngp = gs * ga;
        let raw = &stresses[gp_offsets[b]..gp_offsets[b] + ns * na * ngp];
        let index = |s: usize, eb: usize, qs: usize, qa: usize| (eb * ns + s) * ngp + qa * gs + qs;
        // along the axis first, at every section point
        let mut along = vec![[0.0; 6]; raw.len()];
        let n_terms = body.axis.kind.order() + 1;
        let mut values = Vec::new();
        for (eb, candidates) in axis_patches(&body.axis, &cell.axis).iter().enumerate() {
            for s in 0..ns {
                for qs in 0..gs {
                    for c in 0..6 {
                        let at = |patch: &Patch, k: usize| raw[index(s, patch.elements[k / ga], qs, k % ga)][c];
                        let patch = &candidates[smoothest(candidates, ga, n_terms, &at, &mut values)];
                        let m = patch.elements.len() * ga;
                        for qa in 0..ga {
                            let row = &patch.weights[qa * m..(qa + 1) * m];
                            along[index(s, eb, qs, qa)][c] =
                                row.iter().enumerate().map(|(k, &w)| w * at(patch, k)).sum();
                        }
                    }
                }
            }
        }
        first[gp_offsets[b]..gp_offsets[b] + raw.len()].copy_from_slice(&along);
        // then over the section
        let target = &mut out[gp_offsets[b]..gp_offsets[b] + raw.len()];
        let zone = |es: usize| body.material_of(es);
        for (s, own) in section_patches(&body.section, &cell.section, &zone, free_faces).iter().enumerate() {
            for (k, patch) in own.patches.iter().enumerate() {
                let components: Vec<usize> = (0..6).filter(|&c| own.of_component[c] == k).collect();
                let m = patch.elements.len() * gs;
                for eb in 0..na {
                    for qa in 0..ga {
                        for qs in 0..gs {
                            let row = &patch.weights[qs * m..(qs + 1) * m];
                            let mut acc = [0.0; 6];
                            for (j, &w) in row.iter().enumerate() {
                                let mut f = along[index(patch.elements[j / gs], eb, j % gs, qa)];
                                if let Some(&t) = patch.turn.get(j) {
                                    f = super::patch_map::turned(&f, t, shear);
                                }
                                (0..6).for_each(|c| acc[c] += w * f[c]);
                            }
                            if let Some(&[c, t]) = patch.turn.get(m + qs) {
                                acc = super::patch_map::turned(&acc, [c, -t], shear);
                            }
                            let at = &mut target[index(s, eb, qs, qa)];
                            components.iter().for_each(|&c| at[c] = acc[c]);
                        }
                    }
                }
            }
        }
    }
    (out, first)
}

#[cfg(test)]
#[path = "spr_tests.rs"]
mod tests;
