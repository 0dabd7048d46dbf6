//! CSV files: every result table (`analysis::tables`) as text.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{IoError, file_error};
use crate::analysis::tables::{Table, Values};

/// A text field of a CSV row (RFC 4180): quoted, with its quotes doubled,
/// if it holds a comma, a quote or a line break; as it is otherwise. Every
/// text written into a CSV goes through this (names are restricted to
/// letters, digits, `_`, `-` and `.` today, but a reader must never see a
/// row with a column too many).
pub fn field(s: &str) -> std::borrow::Cow<'_, str> {
    if s.contains([',', '"', '\n', '\r']) { format!("\"{}\"", s.replace('"', "\"\"")).into() } else { s.into() }
}

fn write(path: &Path, text: &str) -> Result<(), IoError> {
    std::fs::write(path, text).map_err(|e| file_error(path, e))
}

/// A table as CSV text: a header of its column names, then one line per
/// row — real numbers in `{:e}` (NaN as `NaN`), counts as integers, an
/// absent value as an empty field.
pub(crate) fn table_text(table: &Table) -> String {
    let names: Vec<_> = table.columns.iter().map(|c| field(&c.name)).collect();
    let mut text = names.join(",");
    text.push('\n');
    for i in 0..table.rows() {
        for (k, c) in table.columns.iter().enumerate() {
            if k > 0 {
                text.push(',');
            }
            let _ = match &c.values {
                Values::Real(v) => write!(text, "{:e}", v[i]),
                Values::Optional(v) => v[i].map_or(Ok(()), |v| write!(text, "{v:e}")),
                Values::Count(v) => write!(text, "{}", v[i]),
                Values::OptionalCount(v) => v[i].map_or(Ok(()), |v| write!(text, "{v}")),
            };
        }
        text.push('\n');
    }
    text
}

/// Writes `table` as `<dir>/<table.name>.csv`; returns the path.
pub(crate) fn write_table(table: &Table, dir: &Path) -> Result<PathBuf, IoError> {
    let path = dir.join(format!("{}.csv", table.name));
    write(&path, &table_text(table))?;
    Ok(path)
}

/// Writes every table; returns the paths.
pub(crate) fn write_tables(tables: &[Table], dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    tables.iter().map(|t| write_table(t, dir)).collect()
}

#[cfg(test)]
mod tests {
    use super::{field, table_text};
    use crate::analysis::tables::{Column, Table, Values};

    /// The CSV form of each kind of column, as the writer's contract states
    /// it: reals in `{:e}` with a NaN (a value not recorded) as `NaN`, counts
    /// as integers, an absent value as an empty field (which the Python
    /// package reads as NaN) — a writer that wrote `NaN` for an absent
    /// component, or `0`, would fail.
    #[test]
    fn tables_write_each_kind_of_column() {
        let col = |name: &str, values| Column { name: name.into(), unit: "", values };
        let t = Table {
            name: "t".into(),
            columns: vec![
                col("increment", Values::Count(vec![1, 2])),
                col("r_x", Values::Real(vec![1.5, f64::NAN])),
                col("u_x", Values::Optional(vec![None, Some(-2.0e-3)])),
                col("negative_pivots", Values::OptionalCount(vec![Some(0), None])),
            ],
        };
        assert_eq!(table_text(&t), "increment,r_x,u_x,negative_pivots\n1,1.5e0,,0\n2,NaN,-2e-3,\n");
        assert!(t.columns[2].values.get(0).is_nan() && t.columns[3].values.get(1).is_nan());
        assert_eq!(t.columns[2].values.to_f64()[1], -2.0e-3);
    }

    /// RFC 4180: a field with a comma, quote or line break is quoted and its
    /// quotes doubled, so a CSV reader sees one column.
    #[test]
    fn fields_are_quoted_when_needed() {
        assert_eq!(field("tip-1.a"), "tip-1.a");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"hi\"\nnow"), "\"say \"\"hi\"\"\nnow\"");
    }
}
