//! Names and number lists as the CalculiX deck writes them.

/// A name usable in a CalculiX set (letters, digits, `_`).
pub fn set_name(prefix: &str, name: &str) -> String {
    let clean: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_uppercase() } else { '_' }).collect();
    format!("{prefix}_{clean}")
}

/// Node or element numbers (1-based), twelve per line.
pub fn list(ids: impl Iterator<Item = usize>) -> String {
    let v: Vec<String> = ids.map(|i| (i + 1).to_string()).collect();
    v.chunks(12).map(|c| c.join(", ")).collect::<Vec<_>>().join(",\n")
}
