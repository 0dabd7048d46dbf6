//! How numbers appear in messages: as a user would write them, never as
//! 300 digits (`1e300` prints as 1 followed by 300 zeros with `{}`).

/// Plain between 1e-4 and 1e6, otherwise in exponent notation.
pub fn number(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

/// A computed coordinate, to six significant digits (`0.075`, not
/// `0.07500000000000001`).
pub fn short(v: f64) -> String {
    number(format!("{v:.5e}").parse().unwrap_or(v))
}

/// A row of numbers as a model file writes it: `[0.01, 3.2e8]`.
pub fn list(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|&v| number(v)).collect();
    format!("[{}]", items.join(", "))
}

/// A bound, to four significant digits in exponent notation (`7e8`, `2.5e-3`).
pub fn limit(v: f64) -> String {
    let s = format!("{v:.3e}");
    match s.split_once('e') {
        Some((m, e)) => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
        None => s,
    }
}

/// `12345` → `12,345`.
pub fn thousands(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(number(1e-300), "1e-300");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(-70e9), "-7e10");
        assert_eq!(limit(6.999999999999996e8), "7e8");
        assert_eq!(limit(2.5e-3), "2.5e-3");
        assert_eq!(list(&[0.01, 3.2e8]), "[0.01, 3.2e8]");
        assert_eq!(short(0.07500000000000001), "0.075");
    }
}
