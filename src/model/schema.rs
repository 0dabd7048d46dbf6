//! The model file as written by the user (TOML), before validation.
//!
//! Every table denies unknown keys and every word-valued key is an enum, so
//! a misspelt key or value is refused by the TOML reader with its line and
//! the keys or values allowed there, instead of being silently ignored.
//! Where one key chooses what the others mean (`hardening`, a section's
//! `shape`, an indenter's `shape`, a contact's `method`) the table is an
//! enum with exactly the keys of each variant ([`tagged`]). The meaning,
//! unit and default of every key are in `docs/model-format.md`; the values
//! are checked in the other files of `model`.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

mod anisotropy;
mod section;
mod stepping;
mod symmetry;
pub(crate) mod tagged;
mod transient;
mod words;

pub use anisotropy::*;
pub use section::*;
pub use stepping::*;
pub use symmetry::*;
use tagged::tagged_table;
pub use transient::*;
pub use words::*;

/// A fixed-length array read from the model file. Unlike serde's `[T; N]`,
/// which silently drops extra elements, it rejects arrays of any length
/// other than `N` (a hardening-table row `[peeq, stress, 7.0]` is an error,
/// not a row of two numbers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact<T, const N: usize>(pub [T; N]);

impl<T, const N: usize> std::ops::Deref for Exact<T, N> {
    type Target = [T; N];
    fn deref(&self) -> &[T; N] {
        &self.0
    }
}

impl<T, const N: usize> From<Exact<T, N>> for [T; N] {
    fn from(e: Exact<T, N>) -> [T; N] {
        e.0
    }
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<T>::deserialize(d)?;
        let n = v.len();
        match <[T; N]>::try_from(v) {
            Ok(a) => Ok(Exact(a)),
            Err(_) => Err(de::Error::invalid_length(n, &format!("an array of length {N}").as_str())),
        }
    }
}

/// Root of a model file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// Title printed in reports.
    #[serde(default)]
    pub title: Option<String>,
    /// Free text.
    #[serde(default)]
    pub description: Option<String>,
    /// The kind of analysis (`[analysis]`).
    #[serde(default)]
    pub analysis: AnalysisFile,
    /// Nonlinear solution controls.
    #[serde(default)]
    pub solver: SolverFile,
    /// Materials.
    #[serde(default)]
    pub materials: Vec<MaterialFile>,
    /// Bodies.
    #[serde(default)]
    pub bodies: Vec<BodyFile>,
    /// Displacement constraints.
    #[serde(default)]
    pub constraints: Vec<ConstraintFile>,
    /// Loads.
    #[serde(default)]
    pub loads: Vec<LoadFile>,
    /// Rigid indenters.
    #[serde(default)]
    pub indenters: Vec<IndenterFile>,
    /// Contacts between deformable bodies.
    #[serde(default)]
    pub contacts: Vec<ContactFile>,
    /// Probe points.
    #[serde(default)]
    pub probes: Vec<ProbeFile>,
    /// Sampled lines.
    #[serde(default)]
    pub lines: Vec<LineFile>,
    /// Load history: an ordered list of steps (default: one step to factor 1).
    #[serde(default)]
    pub steps: Vec<StepFile>,
    /// Output controls.
    #[serde(default)]
    pub output: OutputFile,
    /// Reference values (e.g. from the paper) printed beside the results.
    #[serde(default)]
    pub references: Vec<ReferenceFile>,
    /// Adaptive refinement (`cufem run` refines and solves again).
    #[serde(default)]
    pub adapt: Option<AdaptFile>,
    /// Planes of mirror symmetry.
    #[serde(default)]
    pub symmetry: Vec<SymmetryFile>,
}

/// `[analysis]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisFile {
    /// `geometry = "linear"` (default) or `"nonlinear"` (total Lagrangian).
    pub geometry: Option<Geometry>,
    /// `strain = "green_lagrange"` (default) or `"logarithmic"` (nonlinear geometry).
    pub strain: Option<StrainMeasure>,
    /// `type = "static"` (default), `"buckling"` or `"modal"`.
    #[serde(rename = "type")]
    pub kind: Option<AnalysisType>,
    /// Buckling and modal: the number of modes wanted.
    pub modes: Option<usize>,
    /// Modal and transient: `mass = "consistent"` (default) or `"lumped"`.
    pub mass: Option<MassMatrix>,
    /// Transient: the time (s) of one load step, λ ∈ [k, k + 1].
    pub duration: Option<f64>,
    /// Transient: Newmark's parameters (default the trapezoidal rule).
    pub newmark: Option<NewmarkFile>,
    /// Transient: Rayleigh damping.
    pub damping: Option<DampingFile>,
    /// Transient: uniform initial velocities of bodies.
    pub initial_velocities: Option<Vec<InitialVelocityFile>>,
    /// Transient: the time (s) between the frames of the ParaView series.
    pub output_interval: Option<f64>,
    /// Transient: `contact_forces = "implicit"` (default: the contact
    /// impulse at the end of the step) or `"newmark"`.
    pub contact_forces: Option<ContactForcesFile>,
    /// Transient: `contact_mass = "redistributed"` (default: the contact
    /// nodes carry no mass) or `"kept"`.
    pub contact_mass: Option<ContactMassFile>,
    /// A geometric imperfection from a buckling mode (nonlinear geometry).
    pub imperfection: Option<ImperfectionFile>,
}

/// `analysis.imperfection`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImperfectionFile {
    /// Which buckling mode (1 = the lowest).
    pub mode: usize,
    /// Its largest displacement component (m; the sign flips the shape).
    pub amplitude: f64,
}

/// `[adapt]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptFile {
    pub tolerance: Option<f64>,
    pub max_dof: Option<usize>,
    pub max_cycles: Option<usize>,
    pub fraction: Option<f64>,
}

/// `[solver]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverFile {
    pub increments: Option<usize>,
    pub max_increment: Option<f64>,
    pub min_increment: Option<f64>,
    pub max_iterations: Option<usize>,
    pub residual_tolerance: Option<f64>,
    pub displacement_tolerance: Option<f64>,
    pub cutback_factor: Option<f64>,
    pub growth_factor: Option<f64>,
    pub easy_iterations: Option<usize>,
    /// Newton gives up after this many corrections without a new smallest
    /// residual (`solver::newton::NewtonSettings::stagnation_iterations`).
    pub stagnation_iterations: Option<usize>,
    pub max_increments: Option<usize>,
    pub threads: Option<usize>,
    pub reuse_factorization: Option<bool>,
    pub krylov_tolerance: Option<f64>,
    pub factor_precision: Option<FactorPrecision>,
    /// `"load"` (default) or `"arc_length"` (path following, `model/path.rs`).
    pub control: Option<Control>,
    /// Arc length of the first increment (m), `control = "arc_length"`.
    pub arc_length: Option<f64>,
    /// The path following ends at the first point with λ at least this.
    pub max_load_factor: Option<f64>,
    /// The path following ends once a probe's displacement passes a value.
    pub stop: Option<StopFile>,
    /// Load-step control by an error measure (`schema/stepping.rs`).
    pub step_control: Option<StepControlFile>,
    /// Backtracking along a Newton correction that overshoots.
    pub line_search: Option<bool>,
    /// Which tangent's inertia each increment reports.
    pub inertia: Option<Inertia>,
}

/// `[[materials]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    pub name: String,
    /// Isotropic: E (Pa).
    pub young_modulus: Option<f64>,
    /// Isotropic: ν.
    pub poisson_ratio: Option<f64>,
    /// Orthotropic engineering constants in the material axes.
    pub orthotropic: Option<OrthotropicFile>,
    /// A full 6×6 stiffness in the material axes (Pa; Voigt order xx, yy,
    /// zz, xy, xz, yz with engineering shears).
    pub stiffness: Option<Vec<Exact<f64, 6>>>,
    /// Strengths for the failure indices.
    pub strengths: Option<StrengthsFile>,
    /// Mass density ρ (kg/m³): needed by the mass matrix (`analysis.type = "modal"`).
    pub density: Option<f64>,
    pub plasticity: Option<PlasticityFile>,
}

tagged_table! {
    /// `[materials.plasticity]`.
    pub struct PlasticityFile {
        /// Initial yield stress (Pa); for a table, its first stress.
        yield_stress: Option<f64>,
        /// Armstrong–Frederick back-stresses.
        kinematic: Option<Vec<KinematicFile>>,
    }
    /// The isotropic hardening law and its own keys.
    pub hardening: enum HardeningLaw by "hardening" {
        /// σ_y constant.
        Perfect = "perfect" {}
        /// σ_y + H peeq.
        Linear = "linear" {
            /// H (Pa).
            hardening_modulus: Option<f64>,
        }
        /// Piecewise linear `[[peeq, stress], …]`.
        Table = "table" {
            /// The points.
            table: Option<Vec<Exact<f64, 2>>>,
        }
        /// σ_y + Q (1 − exp(−b peeq)).
        Voce = "voce" {
            /// Q (Pa).
            saturation_stress: Option<f64>,
            /// b.
            saturation_rate: Option<f64>,
        }
    }
    mirror plasticity_file;
}

/// One entry of `plasticity.kinematic`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KinematicFile {
    pub modulus: f64,
    pub recall: f64,
}

/// `[[bodies]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyFile {
    pub name: String,
    /// The body's material (optional where plies or zones cover the section).
    pub material: Option<String>,
    #[serde(deserialize_with = "section::read")]
    pub section: SectionFile,
    pub axis: AxisFile,
    pub formulation: Option<Formulation>,
    /// `[[bodies.zones]]`: materials and material axes of section regions.
    pub zones: Option<Vec<ZoneFile>>,
}

/// An interval division: `{from, to, elements[, ratio]}`, `{lines}` or `{segments}`.
#[derive(Debug, Default, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct DivisionFile {
    pub from: Option<f64>,
    pub to: Option<f64>,
    pub elements: Option<usize>,
    pub ratio: Option<f64>,
    pub lines: Option<Vec<f64>>,
    pub segments: Option<Vec<SegmentFile>>,
}

/// One graded segment.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct SegmentFile {
    pub from: f64,
    pub to: f64,
    pub elements: usize,
    pub ratio: Option<f64>,
}

/// `[bodies.axis]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisFile {
    pub element: BeamElement,
    pub from: Option<f64>,
    pub to: Option<f64>,
    pub elements: Option<usize>,
    pub ratio: Option<f64>,
    pub lines: Option<Vec<f64>>,
    pub segments: Option<Vec<SegmentFile>>,
}

/// A coordinate condition: a number (equality) or `[min, max]`.
#[derive(Debug, Clone, Copy)]
pub enum ConditionFile {
    Value(f64),
    Range([f64; 2]),
}

impl<'de> Deserialize<'de> for ConditionFile {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        const EXPECTED: &str = "a number (the coordinate) or a range [min, max]";
        impl<'de> Visitor<'de> for V {
            type Value = ConditionFile;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<ConditionFile, E> {
                Ok(ConditionFile::Value(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ConditionFile, A::Error> {
                let mut v: Vec<f64> = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                match v[..] {
                    [a, b] => Ok(ConditionFile::Range([a, b])),
                    _ => Err(de::Error::invalid_length(v.len(), &EXPECTED)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// A node selection `{x = …, y = …, z = …, tolerance = …, region = …}`.
#[derive(Debug, Default, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct SelectionFile {
    pub x: Option<ConditionFile>,
    pub y: Option<ConditionFile>,
    pub z: Option<ConditionFile>,
    pub tolerance: Option<f64>,
    /// A named section region (profile wall, gmsh physical group).
    pub region: Option<String>,
    /// Distance from the axis (parallel to y) through `center` (default
    /// the y axis): a cylindrical surface or a ring.
    pub radius: Option<ConditionFile>,
    /// `[x, z]` of the axis of `radius`.
    pub center: Option<Exact<f64, 2>>,
}

/// Per-component prescribed values `{x = …, y = …, z = …}`.
#[derive(Debug, Default, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct ComponentsFile {
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
}

/// `[[constraints]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintFile {
    pub name: String,
    pub body: String,
    #[serde(rename = "where")]
    pub selection: SelectionFile,
    pub fix: Option<Vec<Axis>>,
    pub displacement: Option<ComponentsFile>,
}

/// `[[loads]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadFile {
    pub name: String,
    pub body: String,
    #[serde(rename = "where")]
    pub selection: SelectionFile,
    pub force_per_node: Option<Exact<f64, 3>>,
    pub total_force: Option<Exact<f64, 3>>,
    pub traction: Option<Exact<f64, 3>>,
    pub pressure: Option<f64>,
    /// A variation of `traction` or `pressure` over the faces.
    pub profile: Option<LoadProfileFile>,
}

tagged_table! {
    /// `[[indenters]]`.
    pub struct IndenterFile {
        name: String,
        body: String,
        surface: SelectionFile,
        displacement: Option<Exact<f64, 3>>,
        force: Option<Exact<f64, 3>>,
        penalty: Option<f64>,
        penalty_factor: Option<f64>,
        penetration_tolerance: Option<f64>,
        friction: Option<f64>,
        method: Option<IndenterMethod>,
        mass: Option<f64>,
        velocity: Option<Exact<f64, 3>>,
    }
    /// The indenter's shape and its own keys.
    pub shape: enum IndenterShape by "shape" {
        /// A flat punch.
        Flat = "flat" {
            normal: Option<Normal>,
            position: Option<f64>,
            x: Option<Exact<f64, 2>>,
            y: Option<Exact<f64, 2>>,
            z: Option<Exact<f64, 2>>,
        }
        /// A cylinder (roller).
        Cylinder = "cylinder" {
            axis: Option<Axis>,
            center: Option<Exact<f64, 3>>,
            radius: Option<f64>,
            length: Option<Exact<f64, 2>>,
        }
        /// A sphere (ball).
        Sphere = "sphere" {
            center: Option<Exact<f64, 3>>,
            radius: Option<f64>,
        }
    }
    mirror indenter_file;
}

/// One side of a deformable contact.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSideFile {
    pub body: String,
    #[serde(rename = "where")]
    pub selection: SelectionFile,
}

tagged_table! {
    /// `[[contacts]]`.
    pub struct ContactFile {
        name: String,
        master: ContactSideFile,
        slave: ContactSideFile,
        penalty: Option<f64>,
        penalty_factor: Option<f64>,
        penetration_tolerance: Option<f64>,
        friction: Option<f64>,
        /// A deliberate interference fit: the bodies may start overlapping.
        interference: Option<bool>,
    }
    /// How the surfaces are paired, and its own keys.
    pub method: enum ContactMethod by "method" or "node_to_node" {
        /// Matched node pairs (the paper's method; the default).
        NodeToNode = "node_to_node" {
            tolerance: Option<f64>,
            pairs: Option<Vec<Exact<Exact<f64, 3>, 2>>>,
        }
        /// Segment-to-segment contact on non-matching meshes.
        Surface = "surface" {
            search_distance: Option<f64>,
        }
    }
    mirror contact_file;
}

/// `[[probes]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeFile {
    pub name: String,
    pub point: Exact<f64, 3>,
    pub body: Option<String>,
}

/// `[[lines]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LineFile {
    pub name: String,
    pub from: Exact<f64, 3>,
    pub to: Exact<f64, 3>,
    pub points: Option<usize>,
    pub body: Option<String>,
    pub plot: Option<Vec<QuantityName>>,
}

/// `[output]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    pub vtu: Option<bool>,
    pub plots: Option<bool>,
    pub recovery: Option<super::Recovery>,
    pub gauss_points: Option<bool>,
}

/// `[[references]]`: a published value to print beside ours.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceFile {
    pub probe: String,
    pub quantity: QuantityName,
    pub value: f64,
    pub source: String,
}

/// `[[steps]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepFile {
    pub name: String,
    pub factor: Option<f64>,
    pub factors: Option<std::collections::BTreeMap<String, f64>>,
    pub increments: Option<usize>,
    pub max_increment: Option<f64>,
    pub min_increment: Option<f64>,
    /// Transient: this step's time (s), overriding `analysis.duration`.
    pub duration: Option<f64>,
}
