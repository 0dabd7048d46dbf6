//! Lagrange shape functions: 1D along the beam axis (B2, B3, B4) and 2D over
//! the cross-section (L4, L9, L16).
//!
//! In CUF the displacement field is `u(x,y,z) = F_τ(x,z) N_i(y) u_τi`
//! (paper eq. 6): `F_τ` are the cross-section expansion functions and `N_i`
//! the beam shape functions. With Lagrange expansions both families are
//! nodal Lagrange polynomials on equispaced nodes, so every unknown is a
//! displacement.
//!
//! Node ordering conventions (used throughout the crate):
//! * 1D, order `p`: nodes at `ξ_k = -1 + 2k/p`, `k = 0..=p`, in increasing ξ.
//! * 2D, order `p`: tensor product, local node `j (p+1) + i` sits at
//!   `(ξ_i, η_j)`, i.e. ξ varies fastest (lexicographic, not corner-first).

mod lagrange;

pub(crate) use lagrange::Lagrange1d;
pub use lagrange::Lagrange2d;

use serde::{Deserialize, Serialize};

/// Beam (axis) element types: Lagrange elements with 2, 3 or 4 nodes along y.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BeamElementKind {
    /// Linear, 2 nodes.
    B2,
    /// Quadratic, 3 nodes.
    B3,
    /// Cubic, 4 nodes.
    B4,
}

impl BeamElementKind {
    /// Polynomial order `p` (nodes = `p + 1`).
    pub fn order(self) -> usize {
        match self {
            Self::B2 => 1,
            Self::B3 => 2,
            Self::B4 => 3,
        }
    }

    /// Number of nodes of the element.
    pub fn nodes(self) -> usize {
        self.order() + 1
    }

    /// Parses `"B2"`, `"B3"` or `"B4"`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "B2" => Some(Self::B2),
            "B3" => Some(Self::B3),
            "B4" => Some(Self::B4),
            _ => None,
        }
    }
}

/// Cross-section element types: Lagrange quadrilaterals with 4, 9 or 16 nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SectionElementKind {
    /// Bilinear, 4 nodes.
    L4,
    /// Biquadratic, 9 nodes.
    L9,
    /// Bicubic, 16 nodes.
    L16,
}

impl SectionElementKind {
    /// Polynomial order `p` per direction (nodes = `(p + 1)²`).
    pub fn order(self) -> usize {
        match self {
            Self::L4 => 1,
            Self::L9 => 2,
            Self::L16 => 3,
        }
    }

    /// Number of nodes of the element.
    pub fn nodes(self) -> usize {
        (self.order() + 1).pow(2)
    }

    /// Parses `"L4"`, `"L9"` or `"L16"`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "L4" => Some(Self::L4),
            "L9" => Some(Self::L9),
            "L16" => Some(Self::L16),
            _ => None,
        }
    }
}
