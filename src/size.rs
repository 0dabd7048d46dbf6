//! Model size and memory: an estimate made before anything large is
//! allocated, the machine's available memory, and the process's measured
//! peak.
//!
//! The estimate is made twice. While the model file is validated, from
//! element and node counts alone (the section mesh itself is not built yet,
//! so a 1000 × 1000-element section along 1000 beam elements is refused
//! before it takes gigabytes): the sparsity pattern is counted exactly and
//! the factor is taken as large as the pattern — a *lower bound*, so this
//! stage only refuses models that cannot fit whatever the fill. After the
//! equations are ordered and the symbolic factorization is done, the factor
//! size is exact and the estimate is a close one (measured against the peak
//! resident memory of the shipped examples; see docs/performance.md).
//!
//! Bytes per item, from the data structures of `assembly`, `solver::linear`
//! and `analysis`: a stored matrix entry costs 4 (the assembler's row index),
//! 8 (value), 8 (the solver's row index) and 8 (the assembled elastic
//! tangent); an
//! element-matrix entry 4 (scatter index); a
//! factor entry 8 (in both precisions: a single-precision factor shares
//! those bytes with the rounded matrix, see `solver::linear`), and the
//! factor's symbolic structure as `Cholesky::symbolic_bytes` counts it; a Gauss point two states (200 bytes each with three back-stresses) and a stress of 48;
//! a DOF 64 (eight vectors); in a model with friction, the GMRES basis
//! (`solver::krylov::GmresWork::vectors` of 8 bytes per equation); where
//! factors are reused, the conjugate gradients' vectors (5, and 9 more
//! with rigid impactors: `analysis::sizes`); in a buckling or modal analysis
//! the Lanczos basis (`solver::eigen::vectors`) and two value arrays of the pattern (K and B);
//! in a transient analysis the mass (and damping) values on the pattern,
//! the vectors of `dynamics` (8 of the inertia, 5 of the energy ledger's
//! last forces and one more with interfaces, 2 per impulse) and its frames
//! (at most one per time step); every increment's record (the history
//! row, Newton's report twice — the stepping's and the run's — and the
//! energy row: `analysis::sizes`), in vectors whose capacity doubles
//! (`grown`) and blocks of the allocator's size (`chunk`); with ply
//! damage two `DamageState`s, the crack bands and the volume per Gauss
//! point (`damage::BodyDamage`) and 32 bytes per point per snapshot; per
//! cohesive-interface point its states (`interfaces::Interfaces`) and 24
//! bytes per snapshot; the program itself about 11 MiB. Setup transients (node graph, METIS arrays, the
//! transposed pattern) and output transients (VTU arrays) are freed before
//! the factor is allocated, so the larger of them is added, not both.

/// Memory of the program itself (code, libraries, thread stacks, buffers),
/// measured as the peak of the smallest run: a one-element model (one L4
/// section element, one B2 axis element, 24 DOF, elastic, one increment)
/// peaks at 10.9 MiB (`cufem run`, one and two threads), its estimated
/// parts 16 KB; the resident code alone (the binary's text, the report's
/// inlined libraries, libc and libm) is 10.1 MiB of the drop weights' peak.
const BASELINE: u64 = 11 << 20;

/// Counts that set the memory of an analysis.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Sizes {
    /// Nodes.
    pub nodes: u64,
    /// Degrees of freedom (3 per node).
    pub dofs: u64,
    /// Equations (free DOFs; 0 until the numbering is known).
    pub equations: u64,
    /// 3D (CUF) elements.
    pub elements: u64,
    /// Gauss points.
    pub gauss_points: u64,
    /// Entries of the element matrices' upper triangles, summed.
    pub(crate) element_entries: u64,
    /// Node adjacency entries (node pairs sharing an element, both orders, with self).
    pub(crate) node_pairs: u64,
    /// Stored entries of the lower-triangular tangent.
    pub pattern_nnz: u64,
    /// Stored entries of the Cholesky factor (a lower bound until the symbolic analysis).
    pub factor_nnz: u64,
    /// Scratch of the numeric factorization (bytes).
    pub(crate) factor_scratch: u64,
    /// The factor's symbolic structure (bytes; 0 until the symbolic analysis).
    pub(crate) factor_symbolic: u64,
    /// Sample points of the VTU output.
    pub(crate) vtu_points: u64,
    /// Vectors of the equations' size held by GMRES (a model with friction; 0 otherwise).
    pub(crate) krylov_vectors: u64,
    /// Vectors of the equations' size held by the conjugate gradients that
    /// reuse a factor (`solver.reuse_factorization`; 0 without).
    pub(crate) pcg_vectors: u64,
    /// Vectors of the equations' size held by the eigensolver (buckling or
    /// modal analysis; 0 otherwise).
    pub(crate) eigen_vectors: u64,
    /// Matrices on the tangent's pattern a transient analysis keeps: the
    /// mass, and the damping if any (0 otherwise).
    pub(crate) dynamic_matrices: u64,
    /// Field snapshots a run keeps until it writes them: the step ends,
    /// and a transient run's frames (`analysis.output_interval`).
    pub snapshots: u64,
    /// Converged increments the run keeps a record of: the time steps of
    /// a transient analysis (without cutbacks), the planned increments of
    /// a static one.
    pub history_rows: u64,
    /// One increment's record the run keeps (history row, Newton's report,
    /// energy row).
    pub(crate) history_row: RowBytes,
    /// The increments of the longest load step: the stepping keeps its own
    /// record of them (`solver::stepping::run_span`) until the step ends.
    pub(crate) step_rows: u64,
    /// One increment of the stepping's own record.
    pub(crate) step_row: RowBytes,
    /// Gauss points with a ply-damage history (all of them once a material
    /// damages, `damage::BodyDamage`; 0 otherwise).
    pub(crate) damage_points: u64,
    /// Points of the cohesive interfaces (`interfaces::Interfaces`).
    pub(crate) interface_points: u64,
    /// Vectors of the DOFs' size a transient analysis holds beyond the
    /// static ones (`dynamics::Inertia`, the energy ledger, the impulses).
    pub(crate) transient_vectors: u64,
    /// True once `factor_nnz` comes from the symbolic factorization.
    pub exact: bool,
}

/// A memory estimate split by what holds it.
#[derive(Debug, Clone, PartialEq)]
pub struct MemoryEstimate {
    /// `(what, bytes)` for the memory held during the solve.
    pub parts: Vec<(&'static str, u64)>,
    /// The larger transient (setup or output), bytes.
    pub transient: u64,
    /// True if it is a close estimate (after the symbolic factorization),
    /// false for the lower bound of the validation stage.
    pub exact: bool,
}

impl MemoryEstimate {
    /// Estimated peak (bytes).
    pub fn total(&self) -> u64 {
        self.parts.iter().map(|p| p.1).sum::<u64>() + self.transient
    }
}

/// Bytes per Gauss point: committed and trial states and a stress.
const GAUSS_POINT_BYTES: u64 =
    (2 * std::mem::size_of::<crate::materials::PointState>() + std::mem::size_of::<crate::voigt::Voigt>()) as u64;

/// Bytes per Gauss point of a field snapshot: its state and its stress.
const SNAPSHOT_POINT_BYTES: u64 =
    (std::mem::size_of::<crate::materials::PointState>() + std::mem::size_of::<crate::voigt::Voigt>()) as u64;

/// Bytes per Gauss point of the ply-damage history (`damage::BodyDamage`):
/// committed and trial states, the two crack-band lengths and the volume.
const DAMAGE_POINT_BYTES: u64 = (2 * std::mem::size_of::<crate::materials::damage::DamageState>()
    + std::mem::size_of::<[f64; 2]>()
    + std::mem::size_of::<f64>()) as u64;

/// Bytes per Gauss point of a snapshot's ply damage: each mode's damage
/// (`damage::BodyDamage::shown`).
const SNAPSHOT_DAMAGE_BYTES: u64 = std::mem::size_of::<[f64; 4]>() as u64;

/// Bytes per cohesive-interface point (`interfaces::Interfaces`): the
/// committed and trial states, whether it grows, the committed and trial
/// viscous damage and over-stress with separation, the viscous work, the
/// last separation and the booked dissipation.
const INTERFACE_POINT_BYTES: u64 = (2 * std::mem::size_of::<crate::materials::cohesive::CohesiveState>()
    + std::mem::size_of::<bool>()
    + 2 * std::mem::size_of::<f64>()
    + 2 * std::mem::size_of::<[f64; 6]>()
    + std::mem::size_of::<f64>()
    + std::mem::size_of::<[f64; 3]>()
    + std::mem::size_of::<f64>()) as u64;

/// Bytes per cohesive-interface point of a snapshot: its nodes, damage
/// and onset index (`interfaces::PointDamage`).
const SNAPSHOT_INTERFACE_BYTES: u64 = std::mem::size_of::<(usize, usize, f64, f64)>() as u64;

/// Bytes of a record kept for every converged increment.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct RowBytes {
    /// In vectors grown one record at a time (their capacity doubles:
    /// [`grown`]).
    pub(crate) vec: u64,
    /// In the record's own blocks (names, resultants, Newton's residuals),
    /// each as the allocator takes it ([`chunk`]).
    pub(crate) heap: u64,
}

impl RowBytes {
    /// Bytes of `rows` records.
    fn of(&self, rows: u64) -> u64 {
        grown(rows).saturating_mul(self.vec).saturating_add(rows.saturating_mul(self.heap))
    }
}

/// Capacity of a `Vec` after `n` pushes from empty: Rust's `RawVec` starts
/// at 4 (elements up to 1 KiB) and doubles.
pub(crate) fn grown(n: u64) -> u64 {
    if n == 0 { 0 } else { n.checked_next_power_of_two().unwrap_or(n).max(4) }
}

/// Bytes glibc's malloc takes for a block of `n` bytes (64-bit): `n` and
/// an 8-byte header rounded up to 16, at least 32; none for an empty
/// vector, which allocates nothing.
pub(crate) fn chunk(n: u64) -> u64 {
    if n == 0 { 0 } else { n.saturating_add(8 + 15).max(32) & !15 }
}

impl Sizes {
    /// The memory these counts take (see the module docs for the constants).
    pub fn memory(&self) -> MemoryEstimate {
        let s = self;
        let parts = vec![
            ("program and runtime", BASELINE),
            // the assembler's 32-bit row index and value, the solver's row
            // index, and the assembled elastic tangent an assembly starts from
            ("tangent pattern and values", s.pattern_nnz.saturating_mul(28)),
            ("scatter maps", s.element_entries.saturating_mul(4)),
            (
                "Cholesky factor",
                s.factor_nnz.saturating_mul(8).saturating_add(s.factor_scratch).saturating_add(s.factor_symbolic),
            ),
            // committed and trial states, and the stress
            ("Gauss-point states and stresses", s.gauss_points.saturating_mul(GAUSS_POINT_BYTES)),
            ("vectors", s.dofs.saturating_mul(64)),
            ("transient vectors", s.dofs.saturating_mul(8).saturating_mul(s.transient_vectors)),
            ("ply-damage states", s.damage_points.saturating_mul(DAMAGE_POINT_BYTES)),
            ("cohesive-interface states", s.interface_points.saturating_mul(INTERFACE_POINT_BYTES)),
            ("GMRES basis (friction)", s.equations.saturating_mul(8).saturating_mul(s.krylov_vectors)),
            ("conjugate gradients (factor reuse)", s.equations.saturating_mul(8).saturating_mul(s.pcg_vectors)),
            ("mass and damping matrices", s.pattern_nnz.saturating_mul(8).saturating_mul(s.dynamic_matrices)),
            // each: the displacements, a committed state and a stress per
            // Gauss point, the ply damage of the damaging points and the
            // interfaces' damage
            (
                "step ends and frames",
                s.dofs
                    .saturating_mul(8)
                    .saturating_add(s.gauss_points.saturating_mul(SNAPSHOT_POINT_BYTES))
                    .saturating_add(s.damage_points.saturating_mul(SNAPSHOT_DAMAGE_BYTES))
                    .saturating_add(s.interface_points.saturating_mul(SNAPSHOT_INTERFACE_BYTES))
                    .saturating_mul(s.snapshots),
            ),
            ("history of the increments", s.history_row.of(s.history_rows).saturating_add(s.step_row.of(s.step_rows))),
            // the Lanczos basis, and the two matrices K and B (or M) copied
            // out of the tangent's pattern
            (
                "eigensolver (basis, K and B)",
                if s.eigen_vectors > 0 {
                    s.equations.saturating_mul(8).saturating_mul(s.eigen_vectors).saturating_add(s.pattern_nnz * 16)
                } else {
                    0
                },
            ),
        ];
        // node graph (adjacency, its copy, METIS arrays) + transposed pattern
        let setup = s.node_pairs.saturating_mul(20).saturating_add(s.pattern_nnz.saturating_mul(8));
        // VTU: about 30 values per sample point, plus connectivity
        let output = s.vtu_points.saturating_mul(30 * 8 + 8);
        MemoryEstimate { parts, transient: setup.max(output), exact: s.exact }
    }
}

/// Sum over the nodes of a 1D Lagrange mesh (`elements` elements of order
/// `p`) of the number of nodes sharing an element with each node.
pub(crate) fn coupled_1d(elements: u64, p: u64) -> u64 {
    if elements == 0 {
        return 0;
    }
    // interior element nodes see their element; shared end nodes see both
    let interior = elements * (p.saturating_sub(1)) * (p + 1);
    let shared = (elements - 1) * (2 * p + 1);
    interior + shared + 2 * (p + 1)
}

/// Memory the process may use: the smaller of the kernel's `MemAvailable`
/// and a cgroup (container) limit, if they can be read. `None` off Linux
/// (no `/proc/meminfo`): no model is then refused for its size unless a
/// limit is given (`--max-memory`).
pub fn available_memory() -> Option<u64> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        t.lines().find(|l| l.starts_with("MemAvailable:")).and_then(|l| {
            let kb: u64 = l.split_whitespace().nth(1)?.parse().ok()?;
            Some(kb * 1024)
        })
    });
    let cgroup = ["/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"]
        .iter()
        .find_map(|p| std::fs::read_to_string(p).ok().and_then(|t| t.trim().parse::<u64>().ok()));
    match (meminfo, cgroup) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Largest model file read (bytes). Model files are a few kilobytes (gmsh
/// meshes are separate files); without a cap `cufem check /dev/zero`
/// allocated until memory ran out.
pub(crate) const MAX_MODEL_FILE: u64 = 64 << 20;

/// Largest gmsh `.msh` file read (bytes): a 2D section mesh of millions of
/// elements fits; the text and its parse are held in memory at once.
pub(crate) const MAX_MESH_FILE: u64 = 2 << 30;

/// The bytes of `path` if it holds at most `cap` of them, `Ok(None)` if it
/// holds more — also an endless stream such as `/dev/zero`, which is read up
/// to `cap + 1` bytes only (a larger regular file is not read at all).
pub(crate) fn read_at_most(path: &std::path::Path, cap: u64) -> std::io::Result<Option<Vec<u8>>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if meta.is_file() && meta.len() > cap {
        return Ok(None);
    }
    let mut bytes = Vec::with_capacity(if meta.is_file() { meta.len() as usize } else { 0 });
    file.take(cap + 1).read_to_end(&mut bytes)?;
    Ok((bytes.len() as u64 <= cap).then_some(bytes))
}

/// Peak resident memory of this process so far (bytes): on Linux the
/// address space's high-water mark (`VmHWM` of /proc/self/status), elsewhere
/// `getrusage`. Linux's `ru_maxrss` is carried across fork and exec, so a
/// `cufem` started by a large process (a Python session, a test harness)
/// reported the launcher's peak as its own; `VmHWM` starts afresh at exec.
pub fn peak_memory() -> Option<u64> {
    if let Some(bytes) = high_water_mark() {
        return Some(bytes);
    }
    // SAFETY: getrusage writes into the zero-initialised struct we own.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let r = unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) };
    (r == 0).then(|| usage.ru_maxrss as u64 * MAXRSS_UNIT)
}

/// `VmHWM` of /proc/self/status in bytes (Linux; `None` where there is none).
fn high_water_mark() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut words = line.split_whitespace().skip(1);
    let value: u64 = words.next()?.parse().ok()?;
    (words.next() == Some("kB")).then_some(value * 1024)
}

/// Bytes per unit of `ru_maxrss`: kilobytes on Linux and the BSDs, bytes on
/// Apple's systems.
pub(crate) const MAXRSS_UNIT: u64 = if cfg!(target_vendor = "apple") { 1 } else { 1024 };

/// `1234567890` → `1.15 GiB`.
pub fn human_bytes(b: u64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b as f64;
    let mut k = 0;
    while v >= 1024.0 && k + 1 < units.len() {
        v /= 1024.0;
        k += 1;
    }
    if k == 0 { format!("{b} B") } else { format!("{v:.2} {}", units[k]) }
}

/// Parses `--max-memory` values: a byte count with an optional unit
/// (`K`, `M`, `G`, `T`, with or without `iB`/`B`; powers of 1024).
pub fn parse_bytes(text: &str) -> Option<u64> {
    let t = text.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let v: f64 = num.parse().ok()?;
    let scale = match unit.trim().to_ascii_uppercase().trim_end_matches('B').trim_end_matches('I') {
        "" => 1.0,
        "K" => 1024.0,
        "M" => 1024f64.powi(2),
        "G" => 1024f64.powi(3),
        "T" => 1024f64.powi(4),
        _ => return None,
    };
    let bytes = v * scale;
    (1.0..1.8e19).contains(&bytes).then_some(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coupling_counts_of_a_beam_axis() {
        // 2 B2 elements, nodes 0-1-2: node 0 sees 2, node 1 sees 3, node 2 sees 2
        assert_eq!(coupled_1d(2, 1), 7);
        // 1 B4 element: 4 nodes each see 4
        assert_eq!(coupled_1d(1, 3), 16);
        // 2 B3 elements (5 nodes): 3 + 3 + 5 + 3 + 3
        assert_eq!(coupled_1d(2, 2), 17);
    }

    #[test]
    fn memory_probes_answer_in_bytes_where_the_platform_has_them() {
        // a touched 64 MiB block must show in the peak: a wrong ru_maxrss
        // unit would read 64 KiB or 64 GiB
        let block = std::hint::black_box(vec![1u8; 64 << 20]);
        let peak = peak_memory().expect("getrusage");
        assert!((64 << 20..64 << 30).contains(&peak), "peak {peak} B");
        drop(block);
        let available = available_memory();
        if cfg!(target_os = "linux") {
            assert!(available.is_some_and(|b| b >= 1 << 20), "{available:?}");
        } else {
            assert_eq!(available, None);
        }
    }

    #[test]
    fn records_count_as_vectors_grow_and_malloc_allocates() {
        // glibc malloc.c `request2size`: (n + SIZE_SZ + 15) & ~15, at least
        // MINSIZE = 32 on 64-bit; a 12-byte name, a 136-byte contact
        // resultant
        assert_eq!([chunk(0), chunk(12), chunk(24), chunk(25), chunk(136)], [0, 32, 32, 48, 144]);
        // RawVec: 4 first, then doubling (2,400 time steps in 4,096 slots)
        assert_eq!([grown(0), grown(1), grown(5), grown(2400)], [0, 4, 8, 4096]);
        let row = RowBytes { vec: 100, heap: 10 };
        assert_eq!(row.of(2400), 4096 * 100 + 2400 * 10);
    }

    #[test]
    fn byte_sizes_parse_and_print() {
        assert_eq!(parse_bytes("2G"), Some(2 << 30));
        assert_eq!(parse_bytes("512MiB"), Some(512 << 20));
        assert_eq!(parse_bytes("1.5 GB"), Some(3 << 29));
        assert_eq!(parse_bytes("100"), Some(100));
        assert_eq!(parse_bytes("lots"), None);
        assert_eq!(parse_bytes("-1G"), None);
        assert_eq!(human_bytes(3 << 29), "1.50 GiB");
        assert!(peak_memory().is_some_and(|b| b > 0));
    }
}
