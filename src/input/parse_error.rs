//! The message of a model file the TOML reader refused: the key it stands
//! at, as a path (`bodies[0].axis.elements`), and what was wrong in plain
//! words instead of the reader's Rust types (`expected usize` becomes
//! `expected a whole number, 0 or more`).
//!
//! The reader's own message names the value and where it stands (line,
//! column and the quoted line with a `^^^` marker), but not the key of a
//! value nested in inline tables (`axis = { …, elements = 2.5 }`), and its
//! words are those of serde's data model (`f64`, `usize`, `sequence`,
//! `map`): a new user's review found them opaque. The key is that of the
//! innermost key or value of the document (parsed again with its spans,
//! `toml_edit`) whose span holds the error's; a table written `[[adapt]]`
//! where one `[adapt]` belongs (or `[materials]` where the array
//! `[[materials]]` does) is told so.

use toml_edit::{Document, Item, TableLike, Value};

/// The reader's error `e` of `text`, its message naming the key and in
/// plain words (module docs); the quoted line is kept.
pub(crate) fn explain(text: &str, e: &toml::de::Error) -> String {
    let whole = e.to_string();
    let message = e.message().trim_end();
    let found = e
        .span()
        .and_then(|span| located(text, span.start))
        .map(|(path, kind, keys)| (unknown_key_path(&path, message, &keys).unwrap_or(path), kind));
    let explained = match &found {
        Some((path, kind)) => with_key(path, *kind, message),
        None => plain(message),
    };
    match whole.rfind(message) {
        Some(at) => format!("{}{}{}", &whole[..at], explained, &whole[at + message.len()..]),
        None => format!("{whole}\n{explained}"),
    }
}

/// What the error's span lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A value or a key.
    Value,
    /// A table's `[name]` header.
    Table,
    /// An array of tables' `[[name]]` header.
    ArrayOfTables,
}

/// The message of `path` for the reader's `message`.
fn with_key(path: &str, kind: Kind, message: &str) -> String {
    let name = path.rsplit('.').next().unwrap_or(path);
    let name = name.split('[').next().unwrap_or(name);
    let wrong_type = message.starts_with("invalid type") || message.starts_with("invalid length");
    match kind {
        // `[[adapt]]`: serde reads the array as the table's fields in order
        // ("invalid type: map, expected f64"), which says nothing useful
        Kind::ArrayOfTables if wrong_type => {
            let path = path.strip_suffix("[0]").unwrap_or(path);
            format!("{path}: `[[{name}]]` makes `{name}` an array of tables, but it is one table: write `[{name}]`")
        }
        Kind::Table if message.contains("expected a sequence") => format!(
            "{path}: `[{name}]` makes `{name}` one table, but it is an array of tables: write `[[{name}]]` \
             before each of its entries"
        ),
        _ => {
            // a buffered table's error names its key already (`tagged`)
            let (path, message) = match message.strip_prefix('`').and_then(|m| m.split_once("`: ")) {
                Some((key, rest)) => (format!("{path}.{key}"), rest),
                None => (path.to_string(), message),
            };
            format!("{path}: {}", plain(message))
        }
    }
}

/// `message` with serde's type names in plain words.
fn plain(message: &str) -> String {
    const WORDS: [(&str, &str); 8] = [
        ("invalid type: floating point `", "invalid type: number `"),
        ("invalid value: floating point `", "invalid value: number `"),
        ("invalid type: integer `", "invalid type: whole number `"),
        ("invalid value: integer `", "invalid value: whole number `"),
        ("invalid type: map,", "invalid type: a table,"),
        ("invalid type: sequence,", "invalid type: an array,"),
        ("invalid type: string ", "invalid type: text "),
        ("invalid value: string ", "invalid value: text "),
    ];
    let mut out = message.to_string();
    for (from, to) in WORDS {
        out = out.replace(from, to);
    }
    // the expected type: the word after "expected "
    let Some(at) = out.find("expected ") else { return out };
    let start = at + "expected ".len();
    let end = out[start..].find([',', ';', ')', '\n']).map_or(out.len(), |e| start + e);
    let said = match out[start..end].trim_end() {
        "f64" | "f32" => "a number",
        "usize" | "u64" | "u32" | "u16" | "u8" => "a whole number, 0 or more",
        "i64" | "i32" | "i16" | "i8" | "isize" => "a whole number",
        "a sequence" => "an array",
        "a map" => "a table",
        "a string" => "text in quotes",
        "a boolean" => "true or false",
        s if s.starts_with("struct ") => "a table",
        _ => return out,
    };
    format!("{}{said}{}", &out[..start], &out[end..])
}

/// The path of an unknown key the reader reports at the table `path` it
/// was reading (`unknown field `k``, at a header or an inline section):
/// the one key `k` under that table, or `path.k` if there are several.
fn unknown_key_path(path: &str, message: &str, keys: &[String]) -> Option<String> {
    let key = message.strip_prefix("unknown field `")?.split('`').next()?;
    if path.rsplit('.').next() == Some(key) {
        return None;
    }
    let mut under = keys.iter().filter(|k| {
        k.strip_prefix(path).is_some_and(|rest| rest.starts_with(['.', '[']) && rest.ends_with(&format!(".{key}")))
    });
    match (under.next(), under.next()) {
        (Some(one), None) => Some(one.clone()),
        _ => Some(format!("{path}.{key}")),
    }
}

/// Where an error stands: the path of the innermost key or value of a
/// document whose span holds it, and what that is.
struct Walk {
    at: usize,
    best: Option<(usize, String, Kind)>,
    /// The path of every key of the document.
    keys: Vec<String>,
}

/// The path of the innermost key or value of `text` whose span holds the
/// byte `at`, what it is, and the paths of every key; `None` if the text
/// does not parse.
fn located(text: &str, at: usize) -> Option<(String, Kind, Vec<String>)> {
    let doc = Document::parse(text).ok()?;
    let mut walk = Walk { at, best: None, keys: Vec::new() };
    walk.table(doc.as_item().as_table_like()?, "");
    walk.best.map(|(_, path, kind)| (path, kind, walk.keys))
}

impl Walk {
    /// Keeps `(path, kind)` if `span` holds the error and is the shortest so far.
    fn consider(&mut self, span: Option<std::ops::Range<usize>>, path: &str, kind: Kind) {
        if let Some(s) = span
            && s.contains(&self.at)
            && self.best.as_ref().is_none_or(|(len, _, _)| s.len() < *len)
        {
            self.best = Some((s.len(), path.to_string(), kind));
        }
    }

    fn table(&mut self, table: &dyn TableLike, path: &str) {
        for (key, item) in table.iter() {
            let here = if path.is_empty() { key.to_string() } else { format!("{path}.{key}") };
            if let Some((k, _)) = table.get_key_value(key) {
                self.consider(k.span(), &here, Kind::Value);
            }
            self.keys.push(here.clone());
            self.item(item, &here);
        }
    }

    fn item(&mut self, item: &Item, path: &str) {
        match item {
            Item::None => {}
            Item::Value(v) => self.value(v, path),
            Item::Table(t) => {
                self.consider(t.span(), path, Kind::Table);
                self.table(t, path);
            }
            Item::ArrayOfTables(a) => {
                for (i, t) in a.iter().enumerate() {
                    let here = format!("{path}[{i}]");
                    self.consider(t.span(), &here, Kind::ArrayOfTables);
                    self.table(t, &here);
                }
            }
        }
    }

    fn value(&mut self, value: &Value, path: &str) {
        self.consider(value.span(), path, Kind::Value);
        match value {
            Value::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    self.value(v, &format!("{path}[{i}]"));
                }
            }
            Value::InlineTable(t) => self.table(t, path),
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of `text` read as a model file.
    fn refused(text: &str) -> String {
        let e = toml::from_str::<crate::input::schema::ModelFile>(text).unwrap_err();
        explain(text, &e)
    }

    const BEAM: &str = "[[materials]]\nname = \"a\"\nyoung_modulus = 7e10\npoisson_ratio = 0.3\n\n[[bodies]]\n\
        name = \"b\"\nmaterial = \"a\"\nsection = { shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.1, \
        elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 } }\naxis = { element = \"B4\", from = 0.0, to = 1.0, \
        elements = 5 }\n";

    #[test]
    fn a_value_in_an_inline_table_is_named_by_its_path_in_plain_words() {
        let e = refused(&BEAM.replace("elements = 5 }", "elements = 2.5 }"));
        assert!(
            e.contains("bodies[0].axis.elements: invalid type: number `2.5`, expected a whole number, 0 or more"),
            "{e}"
        );
        // the quoted line stays
        assert!(e.contains("axis = { element = \"B4\""), "{e}");
        let e = refused(&BEAM.replace("elements = 5 }", "elements = -1 }"));
        assert!(
            e.contains("bodies[0].axis.elements: invalid value: whole number `-1`, expected a whole number, 0 or more"),
            "{e}"
        );
        let e = refused(&BEAM.replace("young_modulus = 7e10", "young_modulus = \"abc\""));
        assert!(e.contains("materials[0].young_modulus: invalid type: text \"abc\", expected a number"), "{e}");
        // an element of an array: its index
        let e = refused(&BEAM.replace("from = 0.0, to = 1.0", "from = 0.0, to = [1.0]"));
        assert!(e.contains("bodies[0].axis.to: invalid type: an array, expected a number"), "{e}");
    }

    #[test]
    fn a_table_written_as_an_array_of_tables_is_told_so() {
        let e = refused(&format!("[[adapt]]\ntolerance = 0.1\n\n{BEAM}"));
        assert!(
            e.contains("adapt: `[[adapt]]` makes `adapt` an array of tables, but it is one table: write `[adapt]`"),
            "{e}"
        );
        let e = refused(&BEAM.replacen("[[materials]]", "[materials]", 1));
        assert!(
            e.contains("materials: `[materials]` makes `materials` one table, but it is an array of tables"),
            "{e}"
        );
    }

    #[test]
    fn an_unknown_key_reported_at_its_table_is_named_under_it() {
        let e = refused(&format!("{BEAM}\n[materials.plasticity]\nhardening = \"perfect\"\nyield_strength = 1e8\n"));
        assert!(e.contains("materials[0].plasticity.yield_strength: unknown field `yield_strength`"), "{e}");
        let e = refused(&BEAM.replace(
            "x = { from = 0.0, to = 0.1, elements = 2 }",
            "x = { from = 0.0, to = 0.1, elements = 2, ratios = 2.0 }",
        ));
        assert!(e.contains("bodies[0].section.x.ratios: unknown field `ratios`"), "{e}");
    }

    #[test]
    fn serde_type_names_become_words() {
        assert_eq!(
            plain("invalid type: string \"x\", expected a sequence"),
            "invalid type: text \"x\", expected an array"
        );
        assert_eq!(plain("invalid type: map, expected f64"), "invalid type: a table, expected a number");
        assert_eq!(
            plain("invalid type: boolean `true`, expected i64"),
            "invalid type: boolean `true`, expected a whole number"
        );
        assert_eq!(
            plain("invalid length 2, expected an array of length 3"),
            "invalid length 2, expected an array of length 3"
        );
        assert_eq!(plain("unknown field `x`, expected one of `a`, `b`"), "unknown field `x`, expected one of `a`, `b`");
        assert_eq!(
            plain("invalid type: integer `3`, expected a string"),
            "invalid type: whole number `3`, expected text in quotes"
        );
    }
}
