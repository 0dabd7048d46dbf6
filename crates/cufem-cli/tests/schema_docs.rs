//! docs/model-format.md against the model file's JSON Schema (`cufem
//! schema`, derived from the reader's types): every key in the document's
//! key tables is a key the reader accepts at that place, every key the
//! reader accepts is documented, and every range and default a table
//! states is the range and default the schema (and so the reader,
//! `src/input/ranges.rs`, `src/input/defaults.rs`) has.
//!
//! How the document is read: each key table (a Markdown table with a `key`
//! or `keys` column) follows a comment `<!-- keys: PATH … -->` naming where
//! its keys live: `.` for the top level, dotted table names otherwise
//! (arrays of tables are transparent: `bodies.section`), and
//! `name(tag=a|b)` for the variants of a table whose `tag` key chooses its
//! other keys (`bodies.section(shape=tube)`). In a row, every back-quoted
//! name of the key cell is a key (`step_control.plastic_strain` one level
//! down), and the names in braces in the key or type cell (`{ beta, gamma
//! }`, `segments = [{from, to, …}]`) are the keys of that key's table. A key
//! is documented when a row names it or when a table of its own is marked
//! with its path.

use std::path::Path;

use serde_json::Value;

/// A level of a key's path: a table name, and the variant (tag, value) a
/// table of variants takes there.
#[derive(Debug, Clone, PartialEq)]
struct Level {
    name: String,
    variant: Option<(String, String)>,
}

/// A key the schema accepts: where, its name, its schema (`$ref`
/// followed) and its `default`.
#[derive(Debug)]
struct SchemaKey {
    path: Vec<Level>,
    key: String,
    schema: Value,
    default: Option<Value>,
}

/// A level of a path as the document writes it: the variants it covers
/// (`None`: any).
#[derive(Debug, Clone)]
struct DocLevel {
    name: String,
    variants: Option<(String, Vec<String>)>,
}

/// A key a table documents: where, its name, the table row's line, type
/// and default cells, and whether the row names it alone.
#[derive(Debug)]
struct DocKey {
    path: Vec<DocLevel>,
    key: String,
    line: usize,
    type_cell: String,
    default_cell: String,
    alone: bool,
}

fn schema() -> Value {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cufem")).arg("schema").output().unwrap();
    assert!(out.status.success());
    serde_json::from_slice(&out.stdout).unwrap()
}

/// `node` with its `$ref` followed (`#/definitions/…`).
fn resolve<'a>(root: &'a Value, node: &'a Value) -> &'a Value {
    match node.get("$ref").and_then(Value::as_str) {
        Some(r) => resolve(root, root.pointer(r.trim_start_matches('#')).expect("a $ref into the schema")),
        None => node,
    }
}

/// Every key of `node` and below, at `path`.
fn walk(root: &Value, node: &Value, path: &[Level], out: &mut Vec<SchemaKey>) {
    let node = resolve(root, node);
    for list in ["allOf", "anyOf"] {
        for sub in node.get(list).and_then(Value::as_array).into_iter().flatten() {
            walk(root, sub, path, out);
        }
    }
    if let Some(branches) = node.get("oneOf").and_then(Value::as_array) {
        let tag_of = |b: &Value, tag: &str| {
            resolve(root, b).pointer(&format!("/properties/{tag}/const")).and_then(Value::as_str).map(String::from)
        };
        let first = resolve(root, &branches[0]);
        let tag = first
            .get("properties")
            .and_then(Value::as_object)
            .and_then(|p| p.keys().find(|t| branches.iter().all(|b| tag_of(b, t).is_some())).cloned());
        for b in branches {
            let mut at = path.to_vec();
            if let (Some(tag), Some(last)) = (&tag, at.last_mut()) {
                last.variant = Some((tag.clone(), tag_of(b, tag).unwrap()));
            }
            walk(root, b, &at, out);
        }
    }
    if let Some(properties) = node.get("properties").and_then(Value::as_object) {
        for (key, sub) in properties {
            out.push(SchemaKey {
                path: path.to_vec(),
                key: key.clone(),
                schema: resolve(root, sub).clone(),
                default: sub.get("default").cloned(),
            });
            let mut below = path.to_vec();
            below.push(Level { name: key.clone(), variant: None });
            walk(root, sub, &below, out);
        }
    }
    if let Some(items) = node.get("items") {
        walk(root, items, path, out);
    }
}

fn schema_keys() -> Vec<SchemaKey> {
    let root = schema();
    let mut out = Vec::new();
    walk(&root, &root, &[], &mut out);
    out
}

/// `bodies.section(shape=tube|box)` as levels (`.`: the top level).
fn doc_path(text: &str) -> Vec<DocLevel> {
    if text == "." {
        return Vec::new();
    }
    text.split('.')
        .map(|level| match level.split_once('(') {
            Some((name, rest)) => {
                let (tag, values) = rest.trim_end_matches(')').split_once('=').expect("name(tag=a|b)");
                DocLevel {
                    name: name.to_string(),
                    variants: Some((tag.to_string(), values.split('|').map(String::from).collect())),
                }
            }
            None => DocLevel { name: level.to_string(), variants: None },
        })
        .collect()
}

/// The back-quoted spans of a cell.
fn quoted(cell: &str) -> Vec<&str> {
    cell.split('`').skip(1).step_by(2).collect()
}

/// The leading name of a span (`lines = [c0, …]` → `lines`), if it is one.
fn name_of(span: &str) -> Option<&str> {
    let end = span.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.')).unwrap_or(span.len());
    let name = &span[..end];
    (!name.is_empty() && name.starts_with(|c: char| c.is_ascii_lowercase())).then_some(name)
}

/// The names in the braces of `text` (`{ probe = NAME, component = "x", beyond = u }`
/// → probe, component, beyond), split at the commas outside brackets.
fn brace_names(text: &str) -> Vec<String> {
    // depth 0: outside the braces; 1: in them; more: in brackets within
    let (mut depth, mut part, mut names) = (0, String::new(), Vec::new());
    for c in text.chars() {
        match c {
            '{' | '[' if depth > 0 || c == '{' => depth += 1,
            '}' | ']' if depth > 1 => depth -= 1,
            '}' if depth == 1 => depth = 0,
            _ => {}
        }
        if depth == 1 && (c == ',' || c == '{') || depth == 0 && c == '}' {
            if let Some(n) = name_of(part.trim()) {
                names.push(n.to_string());
            }
            part.clear();
        } else if depth >= 1 {
            part.push(c);
        }
    }
    names
}

/// The keys of docs/model-format.md's key tables, and the paths of its tables.
fn doc_keys(text: &str) -> (Vec<DocKey>, Vec<Vec<DocLevel>>, Vec<String>) {
    let (mut keys, mut tables, mut unmarked) = (Vec::new(), Vec::new(), Vec::new());
    let mut marker: Option<Vec<Vec<DocLevel>>> = None;
    let mut columns: Option<(usize, Option<usize>, Option<usize>)> = None;
    let mut paths = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if let Some(m) = line.strip_prefix("<!-- keys: ").and_then(|m| m.strip_suffix(" -->")) {
            marker = Some(m.split_whitespace().map(doc_path).collect());
            continue;
        }
        let cells: Vec<&str> = line.trim().trim_matches('|').split(" | ").map(str::trim).collect();
        if !line.starts_with('|') {
            columns = None;
            continue;
        }
        if columns.is_none() {
            // a header row
            let Some(k) = cells.iter().position(|c| *c == "key" || *c == "keys") else { continue };
            match marker.take() {
                Some(m) => paths = m,
                None => {
                    unmarked.push(format!("line {}: a key table without <!-- keys: … -->", n + 1));
                    paths = Vec::new();
                }
            }
            tables.extend(paths.iter().cloned());
            let column = |name: &str| cells.iter().position(|c| *c == name);
            columns = Some((k, column("type"), column("default")));
            continue;
        }
        let (k, t, dc) = columns.unwrap();
        if cells[0].starts_with("--") {
            continue;
        }
        let type_cell = t.and_then(|t| cells.get(t)).map_or("", |c| c);
        let default_cell = dc.and_then(|d| cells.get(d)).map_or("", |c| c);
        let spans = quoted(cells[k]);
        let names: Vec<&str> = spans.iter().filter_map(|s| name_of(s)).collect();
        for path in &paths {
            for span in &spans {
                let Some(name) = name_of(span) else { continue };
                let mut at = path.clone();
                let mut parts: Vec<&str> = name.split('.').collect();
                let key = parts.pop().unwrap().to_string();
                at.extend(parts.iter().map(|p| DocLevel { name: p.to_string(), variants: None }));
                let alone = names.len() == 1;
                keys.push(DocKey {
                    path: at.clone(),
                    key: key.clone(),
                    line: n + 1,
                    type_cell: type_cell.into(),
                    default_cell: default_cell.into(),
                    alone,
                });
                // the keys of its table, in braces in the span or (a lone key) the type cell
                let braces = if span.contains('{') {
                    brace_names(span)
                } else if alone {
                    brace_names(type_cell)
                } else {
                    Vec::new()
                };
                at.push(DocLevel { name: key, variants: None });
                for sub in braces {
                    let (line, type_cell, default_cell) = (n + 1, String::new(), String::new());
                    keys.push(DocKey { path: at.clone(), key: sub, line, type_cell, default_cell, alone: false });
                }
            }
        }
    }
    (keys, tables, unmarked)
}

fn level_matches(doc: &DocLevel, schema: &Level) -> bool {
    doc.name == schema.name
        && match (&doc.variants, &schema.variant) {
            (None, _) => true,
            (Some((tag, values)), Some((t, v))) => tag == t && values.contains(v),
            (Some(_), None) => false,
        }
}

fn path_matches(doc: &[DocLevel], schema: &[Level]) -> bool {
    doc.len() == schema.len() && doc.iter().zip(schema).all(|(d, s)| level_matches(d, s))
}

fn show(path: &[Level], key: &str) -> String {
    let mut parts: Vec<String> = path
        .iter()
        .map(|l| match &l.variant {
            Some((t, v)) => format!("{}({t}={v})", l.name),
            None => l.name.clone(),
        })
        .collect();
    parts.push(key.to_string());
    parts.join(".")
}

fn document() -> String {
    std::fs::read_to_string(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("docs/model-format.md"))
        .unwrap()
}

#[test]
fn every_documented_key_is_read_and_every_key_read_is_documented() {
    let schema = schema_keys();
    let (doc, tables, unmarked) = doc_keys(&document());
    assert!(unmarked.is_empty(), "{}", unmarked.join("\n"));
    assert!(doc.len() > 150 && schema.len() > 150, "{} documented keys, {} schema keys", doc.len(), schema.len());
    let mut bad = Vec::new();
    for d in &doc {
        if !schema.iter().any(|s| s.key == d.key && path_matches(&d.path, &s.path)) {
            let at: Vec<String> = d.path.iter().map(|l| l.name.clone()).collect();
            bad.push(format!("line {}: `{}` is not a key the reader accepts in `{}`", d.line, d.key, at.join(".")));
        }
    }
    for s in &schema {
        let below: Vec<Level> = s.path.iter().cloned().chain([Level { name: s.key.clone(), variant: None }]).collect();
        let documented = doc.iter().any(|d| d.key == s.key && path_matches(&d.path, &s.path))
            || tables.iter().any(|t| path_matches(t, &below));
        if !documented {
            bad.push(format!("`{}` is read but documented nowhere", show(&s.path, &s.key)));
        }
    }
    assert!(bad.is_empty(), "{} disagreements:\n{}", bad.len(), bad.join("\n"));
}

/// A range as the document's type cells write it (`real > 0`, `real in
/// (0, 1]`, `integer 1–50`, `real, ±360`), followed by nothing or by a
/// comma: `(min, min open, max, max open)`.
fn doc_range(cell: &str) -> Option<(f64, bool, f64, bool)> {
    let t = cell.replace('`', "").replace('−', "-");
    let t = t.trim();
    let rest = ["real", "number", "integers", "integer"].iter().find_map(|w| t.strip_prefix(w))?;
    let number = |s: &str| s.trim().parse::<f64>().ok();
    let done = |rest: &str| rest.trim().is_empty() || rest.trim_start().starts_with(',');
    let rest = rest.trim_start();
    if let Some(r) = rest.strip_prefix(',').map(str::trim).and_then(|r| r.strip_prefix('±')) {
        let end = r.find(',').unwrap_or(r.len());
        let v = number(&r[..end])?;
        return done(&r[end..]).then_some((-v, false, v, false));
    }
    for (sign, open) in [(">", true), ("≥", false)] {
        if let Some(r) = rest.strip_prefix(sign) {
            let end = r.find(',').unwrap_or(r.len());
            return number(&r[..end]).filter(|_| done(&r[end..])).map(|v| (v, open, f64::INFINITY, false));
        }
    }
    if let Some(r) = rest.strip_prefix("in ") {
        let r = r.trim_start();
        let min_open = r.starts_with('(');
        let close = r.find([']', ')'])?;
        let (a, b) = r[1..close].split_once(',')?;
        return Some((number(a)?, min_open, number(b)?, r[close..].starts_with(')'))).filter(|_| done(&r[close + 1..]));
    }
    let (a, b) = rest.split_once('–')?;
    let end = b.find(',').unwrap_or(b.len());
    Some((number(a)?, false, number(&b[..end])?, false)).filter(|_| done(&b[end..]))
}

/// The range of a number's schema, as [`doc_range`] gives it.
fn schema_range(s: &Value) -> (f64, bool, f64, bool) {
    let get = |k: &str| s.get(k).and_then(Value::as_f64);
    let (min, min_open) = match (get("minimum"), get("exclusiveMinimum")) {
        (_, Some(v)) => (v, true),
        (Some(v), None) => (v, false),
        _ => (f64::NEG_INFINITY, false),
    };
    let (max, max_open) = match (get("maximum"), get("exclusiveMaximum")) {
        (_, Some(v)) => (v, true),
        (Some(v), None) => (v, false),
        _ => (f64::INFINITY, false),
    };
    (min, min_open, max, max_open)
}

#[test]
fn the_ranges_the_tables_state_are_the_readers() {
    let schema = schema_keys();
    let (doc, _, _) = doc_keys(&document());
    let close = |a: f64, b: f64| a == b || (a - b).abs() <= 1e-3 * a.abs().max(b.abs());
    let mut checked = 0;
    let mut bad = Vec::new();
    for d in doc.iter().filter(|d| d.alone) {
        let Some(want) = doc_range(&d.type_cell) else { continue };
        for s in schema.iter().filter(|s| s.key == d.key && path_matches(&d.path, &s.path)) {
            checked += 1;
            let got = schema_range(&s.schema);
            if !(close(want.0, got.0) && want.1 == got.1 && close(want.2, got.2) && want.3 == got.3) {
                bad.push(format!(
                    "line {}: `{}` is documented as \"{}\" {want:?}; the reader's range is {got:?}",
                    d.line,
                    show(&s.path, &s.key),
                    d.type_cell
                ));
            }
        }
    }
    assert!(checked > 60, "only {checked} ranges checked");
    assert!(bad.is_empty(), "{} ranges disagree:\n{}", bad.len(), bad.join("\n"));
}

/// A default cell's value as TOML reads it, and whether it is the whole
/// cell (`1.5`, `"single"`, `[0.0, 0.0]`, `{ beta = 0.25, gamma = 0.5 }`)
/// or a value with a remark (`100 (if penalty absent)`, `1000; transient: …`).
fn doc_default(cell: &str) -> Option<(Value, bool)> {
    let t = cell.replace('`', "");
    let t = t.trim();
    let parse = |s: &str| {
        let table: toml::Table = toml::from_str(&format!("v = {s}")).ok()?;
        serde_json::to_value(&table["v"]).ok()
    };
    if let Some(v) = parse(t) {
        return Some((v, true));
    }
    let end = [t.find(" ("), t.find(';')].into_iter().flatten().min()?;
    parse(&t[..end]).map(|v| (v, false))
}

/// Equal JSON values, numbers as reals (`1` is `1.0`).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => x.as_f64() == y.as_f64(),
        (Value::Array(x), Value::Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b)),
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

#[test]
fn the_defaults_the_tables_state_are_the_readers() {
    let schema = schema_keys();
    let (doc, _, _) = doc_keys(&document());
    let empty = |v: &Value| v.as_array().is_some_and(Vec::is_empty) || v.as_object().is_some_and(|o| o.is_empty());
    let mut bad = Vec::new();
    // a value the table gives as the default is the schema's
    for d in doc.iter().filter(|d| d.alone) {
        let Some((want, true)) = doc_default(&d.default_cell) else { continue };
        if empty(&want) {
            continue;
        }
        let found: Vec<&SchemaKey> =
            schema.iter().filter(|s| s.key == d.key && path_matches(&d.path, &s.path)).collect();
        if !found.iter().any(|s| s.default.as_ref().is_some_and(|got| same(got, &want))) {
            let got: Vec<Option<&Value>> = found.iter().map(|s| s.default.as_ref()).collect();
            bad.push(format!("line {}: `{}` defaults to {want} in the table; the reader's: {got:?}", d.line, d.key));
        }
    }
    // the schema's default of a key a row names alone is the row's
    let mut checked = 0;
    for s in schema.iter().filter(|s| s.default.is_some()) {
        let rows: Vec<&DocKey> =
            doc.iter().filter(|d| d.alone && d.key == s.key && path_matches(&d.path, &s.path)).collect();
        if rows.is_empty() {
            continue;
        }
        checked += 1;
        let got = s.default.as_ref().unwrap();
        if !rows.iter().any(|d| doc_default(&d.default_cell).is_some_and(|(want, _)| same(&want, got))) {
            let cells: Vec<String> = rows.iter().map(|d| format!("line {}: {:?}", d.line, d.default_cell)).collect();
            bad.push(format!("`{}` defaults to {got} in the reader; the tables say {cells:?}", show(&s.path, &s.key)));
        }
    }
    assert!(checked > 40, "only {checked} defaults checked");
    assert!(bad.is_empty(), "{} defaults disagree:\n{}", bad.len(), bad.join("\n"));
}

/// The quantity names the reader accepts (`lines.plot`, `references.quantity`)
/// are the document's table of them.
#[test]
fn the_quantity_names_are_the_documents() {
    let root = schema();
    let read: Vec<&str> =
        root["definitions"]["QuantityName"]["enum"].as_array().unwrap().iter().filter_map(Value::as_str).collect();
    let text = document();
    let table = text.split("**Quantity names**").nth(1).unwrap().split("\n\n").nth(1).unwrap();
    let documented: Vec<&str> =
        table.lines().skip(2).flat_map(|row| quoted(row.split(" | ").next().unwrap())).collect();
    let mut sorted_read = read.clone();
    let mut sorted_documented = documented.clone();
    sorted_read.sort();
    sorted_documented.sort();
    assert!(read.len() >= 21, "{read:?}");
    assert_eq!(sorted_read, sorted_documented);
}

#[test]
fn the_range_and_brace_readers_read_the_documents_forms() {
    assert_eq!(doc_default("`0.5`"), Some((serde_json::json!(0.5), true)));
    assert_eq!(doc_default("100 (if `penalty` absent)"), Some((serde_json::json!(100), false)));
    assert_eq!(
        doc_default("`{ beta = 0.25, gamma = 0.5 }`"),
        Some((serde_json::json!({ "beta": 0.25, "gamma": 0.5 }), true))
    );
    assert_eq!(doc_default("1 if linear, 10 otherwise"), None);
    assert_eq!(doc_default("`1e-4` × first Δλ"), None);
    assert!(same(&serde_json::json!([0, 1, 0]), &serde_json::json!([0.0, 1.0, 0.0])));
    assert_eq!(doc_range("real > 0"), Some((0.0, true, f64::INFINITY, false)));
    assert_eq!(doc_range("integer ≥ 1"), Some((1.0, false, f64::INFINITY, false)));
    assert_eq!(doc_range("real in (0, 1), both ends excluded"), Some((0.0, true, 1.0, true)));
    assert_eq!(doc_range("real in (−1, `0.4999`]"), Some((-1.0, true, 0.4999, false)));
    assert_eq!(doc_range("integer 1–50"), Some((1.0, false, 50.0, false)));
    assert_eq!(doc_range("real, ±360"), Some((-360.0, false, 360.0, false)));
    assert_eq!(doc_range("real in [`1e-9`, 1] × larger body size"), None);
    assert_eq!(doc_range("real in [0, E]"), None);
    assert_eq!(doc_range("integer 4 + 4k, k ≥ 1"), None);
    assert_eq!(
        brace_names("`{ probe = NAME, component = \"x\", \"y\" or \"z\", beyond = u }`"),
        ["probe", "component", "beyond"]
    );
    assert_eq!(brace_names("array of `{ body, velocity = [vx, vy, vz] }`"), ["body", "velocity"]);
    assert_eq!(name_of("segments = [{from, to}]"), Some("segments"));
    assert_eq!(name_of("\"x\""), None);
}
