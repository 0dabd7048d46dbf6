//! The consistent and the lumped mass matrix.
//!
//! **Consistent.** `m_ab = Σ_q w_q ρ N_a(q) N_b(q)` with the section × axis
//! Gauss rule of the stiffness (`values::CellValues`): `p + 1` points per
//! direction integrate the degree-`2p` products exactly on an affine
//! element. `M_(ac,bd) = δ_cd m_ab`.
//!
//! **Lumped** (row sum): `m_a = Σ_b m_ab = ∫ ρ N_a dV`, since `Σ_b N_b = 1`.
//! On the Lagrange elements of this code (L4, L9, L16 × B2, B3, B4) these
//! are tensor products of the 1D weights `∫ N_i` on equispaced nodes —
//! the Newton–Cotes weights ½ ½, ⅙ ⅔ ⅙ and ⅛ ⅜ ⅜ ⅛, all positive — so the
//! lumped mass is positive on affine elements; a strongly distorted
//! element could make a node's share non-positive, which
//! `assemble` refuses. Both conserve the mass: for a rigid translation
//! `r`, `rᵀ M r = ∫ ρ dV`.

use crate::assembly::Assembler;
use crate::elements::Workspace;
use crate::mesh::Mesh;
use crate::values::{CellValues, shape_values};

/// How the mass is distributed over the nodes (`analysis.mass`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MassKind {
    /// `∫ ρ N_a N_b dV`: the variationally consistent matrix.
    #[default]
    Consistent,
    /// Row sums on the diagonal.
    Lumped,
}

/// Errors of the mass matrix.
#[derive(Debug, thiserror::Error)]
pub enum MassError {
    /// A body's material has no density.
    #[error(
        "materials \"{material}\".density = (missing): the mass density in kg/m³ of body \"{body}\" (the mass matrix needs it)"
    )]
    NoDensity {
        /// The material.
        material: String,
        /// A body made of it.
        body: String,
    },
    /// A lumped nodal mass is not positive (a distorted element).
    #[error(
        "analysis.mass = \"lumped\": the lumped mass of equation {equation} is {value:e} kg, not positive \
         (a strongly distorted element); use analysis.mass = \"consistent\""
    )]
    NotPositive {
        /// The equation.
        equation: usize,
        /// Its lumped mass.
        value: f64,
    },
}

/// The element mass of element `e` (section element `e % n_section`,
/// beam element `e / n_section`) with density `density`, into the upper
/// triangle of `ws.tangent` (row-major, `3 nodes` square, DOF `3a + c`).
pub(crate) fn element_mass(
    geom: &CellValues,
    e: usize,
    n_section: usize,
    density: f64,
    kind: MassKind,
    ws: &mut Workspace,
) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let (es, eb) = (e % n_section, e / n_section);
    let nodes = sg.n_fun * ag.n_fun;
    let n = 3 * nodes;
    ws.tangent.clear();
    ws.tangent.resize(n * n, 0.0);
    let mut shapes = vec![0.0; nodes];
    let mut m = vec![0.0; nodes * nodes];
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let (s, a) = (sg.point(es, gs), ag.point(eb, gb));
            let w = density * s.weight * a.weight;
            shape_values(s, a, &mut shapes);
            for (row, &na) in m.chunks_exact_mut(nodes).zip(&shapes) {
                let wa = w * na;
                for (o, &nb) in row.iter_mut().zip(&shapes) {
                    *o += wa * nb;
                }
            }
        }
    }
    super::components::expand(&m, nodes, kind, &mut ws.tangent);
}

/// The mass matrix of the model in `assembler`'s pattern (free equations;
/// lower triangle in pattern order), each body with its material's
/// density per section element (`densities[body][section element]`),
/// with the contact nodes' mass moved to their neighbours by
/// `redistribution` if given (`dynamics::redistribution`).
pub(crate) fn assemble(
    assembler: &Assembler,
    mesh: &Mesh,
    cells: &[CellValues],
    densities: &[Vec<f64>],
    kind: MassKind,
    redistribution: Option<&super::redistribution::Redistribution>,
) -> Result<Vec<f64>, MassError> {
    let mut out = vec![0.0; assembler.pattern.nnz()];
    assembler.assemble_matrices(mesh, &mut out, |body, element, ws| {
        let n_section = mesh.bodies[body].section.n_elements();
        let rho = densities[body][element % n_section];
        element_mass(&cells[body], element, n_section, rho, kind, ws);
        if let Some(r) = redistribution {
            r.apply(body, element, kind, ws);
        }
    });
    if kind == MassKind::Lumped {
        let p = &assembler.pattern;
        // the equation's node: a massless contact node's zero is expected
        let mut node = vec![usize::MAX; p.n];
        for (d, &e) in assembler.dofs.eq.iter().enumerate() {
            if e != crate::assembly::NO_EQ {
                node[e] = d / 3;
            }
        }
        for e in 0..p.n {
            let value = out[p.col_ptr[e]];
            let massless = redistribution.is_some_and(|r| r.is_massless(node[e]));
            if !(value > 0.0 || massless) {
                return Err(MassError::NotPositive { equation: e, value });
            }
        }
    }
    Ok(out)
}

/// The density of every section element of every body of `mesh` from its
/// material (plies and zones have their own), or the error naming the first
/// material without one.
pub fn densities(mesh: &Mesh, materials: &[crate::materials::Material]) -> Result<Vec<Vec<f64>>, MassError> {
    mesh.bodies
        .iter()
        .map(|b| {
            (0..b.section.n_elements())
                .map(|es| {
                    let m = &materials[b.material_of(es)];
                    m.density.ok_or_else(|| MassError::NoDensity { material: m.name.clone(), body: b.name.clone() })
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
#[path = "mass_tests.rs"]
mod tests;
