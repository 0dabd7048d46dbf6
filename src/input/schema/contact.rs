//! `[[indenters]]` (rigid surfaces) and `[[contacts]]` (between deformable
//! bodies): tables whose `shape` or `method` chooses their other keys
//! (`setup/indenters.rs` and `setup/contacts.rs` check them).

use serde::Deserialize;

use super::{Axis, Exact, IndenterMethod, Normal, SelectionFile, tagged_table};
use crate::input::{defaults, ranges};

tagged_table! {
    /// `[[indenters]]`: a rigid indenter in penalty contact with one body.
    pub(crate) struct IndenterFile {
        /// Unique among indenters, constraints and contacts.
        name: String,
        /// The body pressed.
        body: String,
        /// Candidate contact faces.
        surface: SelectionFile,
        /// Rigid displacement `[dx, dy, dz]` (m) at factor 1.
        displacement: Option<Exact<f64, 3>>,
        /// Force control: `[fx, fy, fz]` (N) at factor 1, instead of `displacement`.
        force: Option<Exact<f64, 3>>,
        /// ε_N per unit tributary area (Pa/m).
        penalty: Option<f64> => ranges::PENALTY.schema(),
        /// α in ε_i = α Σ_f E w_f / h_f.
        penalty_factor: Option<f64> => ranges::PENALTY_FACTOR_RANGE.with_default(crate::contact::DEFAULT_PENALTY_FACTOR),
        /// Augmented Lagrangian: the largest penetration accepted (m).
        penetration_tolerance: Option<f64> => ranges::POSITIVE.schema(),
        /// Coulomb's coefficient of friction μ.
        friction: Option<f64> => ranges::FRICTION.schema(),
        /// `"node_to_node"` (default) or `"surface"`.
        method: Option<IndenterMethod> => defaults::schema(IndenterMethod::default()),
        /// Transient: an impactor's mass (kg).
        mass: Option<f64> => ranges::IMPACTOR_MASS.schema(),
        /// Transient: an impactor's initial velocity `[vx, vy, vz]` (m/s).
        velocity: Option<Exact<f64, 3>>,
    }
    /// The indenter's shape and its own keys.
    pub shape: enum IndenterShape by "shape" {
        /// A flat punch.
        Flat = "flat" {
            /// Direction the punch face looks towards the body.
            normal: Option<Normal>,
            /// Coordinate of the face plane along the normal's axis (m).
            position: Option<f64> => ranges::COORDINATE.schema(),
            /// Extent `[min, max]` of the face along x (m).
            x: Option<Exact<f64, 2>> => ranges::COORDINATE.items(),
            /// Extent `[min, max]` of the face along y (m).
            y: Option<Exact<f64, 2>> => ranges::COORDINATE.items(),
            /// Extent `[min, max]` of the face along z (m).
            z: Option<Exact<f64, 2>> => ranges::COORDINATE.items(),
        }
        /// A cylinder (roller).
        Cylinder = "cylinder" {
            /// Direction of the cylinder's axis.
            axis: Option<Axis>,
            /// Any point `[x, y, z]` on the axis (m).
            center: Option<Exact<f64, 3>> => ranges::COORDINATE.items(),
            /// Radius (m).
            radius: Option<f64> => ranges::LENGTH.schema(),
            /// Extent `[min, max]` along the axis (m).
            length: Option<Exact<f64, 2>> => ranges::COORDINATE.items(),
        }
        /// A sphere (ball).
        Sphere = "sphere" {
            /// Centre `[x, y, z]` (m).
            center: Option<Exact<f64, 3>> => ranges::COORDINATE.items(),
            /// Radius (m).
            radius: Option<f64> => ranges::LENGTH.schema(),
        }
    }
    mirror indenter_file;
}

/// One side of a deformable contact.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct ContactSideFile {
    /// Body name.
    pub body: String,
    /// The surface faces.
    #[serde(rename = "where")]
    pub selection: SelectionFile,
}

tagged_table! {
    /// `[[contacts]]`: contact between two deformable bodies.
    pub(crate) struct ContactFile {
        /// Unique among indenters, constraints and contacts.
        name: String,
        /// Master body and faces (their normal is the contact direction).
        master: ContactSideFile,
        /// Slave body and faces.
        slave: ContactSideFile,
        /// ε_N per unit slave tributary area (Pa/m).
        penalty: Option<f64> => ranges::PENALTY.schema(),
        /// α as for indenters.
        penalty_factor: Option<f64> => ranges::PENALTY_FACTOR_RANGE.with_default(crate::contact::DEFAULT_PENALTY_FACTOR),
        /// Augmented Lagrangian: the largest penetration accepted (m).
        penetration_tolerance: Option<f64> => ranges::POSITIVE.schema(),
        /// Coulomb's coefficient of friction μ.
        friction: Option<f64> => ranges::FRICTION.schema(),
        /// A deliberate interference fit: the bodies may start overlapping.
        interference: Option<bool> => defaults::schema(defaults::INTERFERENCE),
    }
    /// How the surfaces are paired, and its own keys.
    pub method: enum ContactMethod by "method" or "node_to_node" {
        /// Matched node pairs (the paper's method; the default).
        NodeToNode = "node_to_node" {
            /// Matching tolerance (m).
            tolerance: Option<f64> => ranges::POSITIVE.schema(),
            /// Explicit pairs `[[xs, ys, zs], [xm, ym, zm]]` (m).
            pairs: Option<Vec<Exact<Exact<f64, 3>, 2>>>,
        }
        /// Segment-to-segment contact on non-matching meshes.
        Surface = "surface" {
            /// How far (m) a slave point may be from the master faces it can use.
            search_distance: Option<f64> => ranges::POSITIVE.schema(),
        }
    }
    mirror contact_file;
}
