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

/// A table as CSV text: a header of its column names (with their units
/// where the table says so: [`Table::header`]), then one line per row —
/// real numbers in `{:e}` (NaN as `NaN`), counts as integers, an absent
/// value as an empty field, text as a [`field`].
pub(crate) fn table_text(table: &Table) -> String {
    let names: Vec<_> = table.columns.iter().map(|c| field(&table.header(c)).into_owned()).collect();
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
                Values::Text(v) => write!(text, "{}", field(&v[i])),
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
            units_in_header: false,
        };
        assert_eq!(table_text(&t), "increment,r_x,u_x,negative_pivots\n1,1.5e0,,0\n2,NaN,-2e-3,\n");
        assert!(t.columns[2].values.get(0).is_nan() && t.columns[3].values.get(1).is_nan());
        assert_eq!(t.columns[2].values.to_f64()[1], -2.0e-3);
    }

    /// A text column (a probe's name) is a field, quoted when it must be,
    /// and NaN as a number (it is left out of a row); a table with units in
    /// its header names each column `<name>_<unit>` (energy.csv's
    /// `kinetic_J`), a unitless one by its name alone.
    #[test]
    fn text_columns_and_headers_with_units() {
        let col = |name: &str, unit, values| Column { name: name.into(), unit, values };
        let mut t = Table {
            name: "t".into(),
            columns: vec![
                col("probe", "", Values::Text(vec!["tip".into(), "a,b".into()])),
                col("kinetic", "J", Values::Real(vec![0.5, 2.0])),
                col("step", "", Values::Count(vec![3, 4])),
            ],
            units_in_header: false,
        };
        assert_eq!(table_text(&t), "probe,kinetic,step\ntip,5e-1,3\n\"a,b\",2e0,4\n");
        t.units_in_header = true;
        assert_eq!(table_text(&t), "probe,kinetic_J,step\ntip,5e-1,3\n\"a,b\",2e0,4\n");
        assert!(t.columns[0].values.get(1).is_nan());
        let row = t.row(1);
        assert_eq!(row.0, vec![("kinetic".to_string(), 2.0), ("step".to_string(), 4.0)]);
        assert_eq!(serde_json::to_string(&row).unwrap(), r#"{"kinetic":2.0,"step":4.0}"#);
        assert_eq!(t.text("probe").unwrap()[1], "a,b");
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
