//! The stored 3D fields of `tests/data` (a `cufem verify` run's
//! `verify/field_points.csv`, gzipped when large) and the report ids of
//! their whole-field rows, shared by crates/cufem-cli/tests/fidelity.rs and
//! crates/cufem-cli/tests/roller_twins.rs.

use std::path::PathBuf;

fn data() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data"))
}

/// The stored 3D fields `tests/data/<name>_field_3d.csv`, or the same
/// gzipped (`.csv.gz`).
pub fn field_3d(name: &str) -> String {
    let plain = data().join(format!("{name}_field_3d.csv"));
    if plain.exists() {
        return std::fs::read_to_string(plain).unwrap();
    }
    let gz = std::fs::File::open(data().join(format!("{name}_field_3d.csv.gz"))).unwrap();
    let mut text = String::new();
    std::io::Read::read_to_string(&mut flate2::read::GzDecoder::new(gz), &mut text).unwrap();
    text
}

/// A whole-field row's region as part of a report id: its spaces and
/// brackets as `_` (`plastic zone tube` → `plastic_zone_tube`).
pub fn region_id(region: &str) -> String {
    let region: String = region.chars().map(|c| if c.is_alphanumeric() { c } else { '_' }).collect();
    region.trim_matches('_').replace("__", "_")
}
