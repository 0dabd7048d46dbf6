//! The documentation states current facts a newcomer can read: README.md
//! stays short (at most 300 lines, the rest in docs/), names the two set-up
//! commands that CI runs, and neither it nor docs/ cites commit hashes
//! (history belongs in commit messages); relative links resolve.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every docs/*.md.
fn documents() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
}

/// Words (maximal runs of letters, digits and `_`, as a regex `\b` sees
/// them) of 7–40 characters that are lowercase hex digits with at least
/// one digit and one letter a–f: abbreviated or full git commit hashes.
/// Ordinary words ("deadbeef", "facade") have no digit; numbers have no
/// letter or are shorter.
fn commit_hashes(text: &str) -> Vec<String> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| {
            (7..=40).contains(&w.len())
                && w.chars().all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c))
                && w.chars().any(|c| c.is_ascii_digit())
                && w.chars().any(|c| c.is_ascii_alphabetic())
        })
        .map(String::from)
        .collect()
}

#[test]
fn commit_hashes_are_recognised_and_ordinary_words_and_numbers_are_not() {
    let text = "the binary of 9e87594 (bd4a1cf, commit a2b63d9e1f0c); \
                10d4578c2b7f6a9e0d3c1b2a4f5e6d7c8b9a0f1e";
    assert_eq!(commit_hashes(text), ["9e87594", "bd4a1cf", "a2b63d9e1f0c", "10d4578c2b7f6a9e0d3c1b2a4f5e6d7c8b9a0f1e"]);
    let ordinary = "deadbeef facade 1234567 5.305e9 1.6e-6 abc1234x x_abc1234 σ_zz 0.0254 e9 3d4e5f";
    assert!(commit_hashes(ordinary).is_empty(), "{:?}", commit_hashes(ordinary));
}

#[test]
fn readme_is_at_most_300_lines() {
    let lines = std::fs::read_to_string(root().join("README.md")).unwrap().lines().count();
    assert!(lines <= 300, "README.md has {lines} lines: move details into docs/ (at most 300)");
}

#[test]
fn no_commit_hash_in_readme_or_docs() {
    let mut found = Vec::new();
    // the generated validation report names the commit it ran on
    for path in documents().into_iter().filter(|p| !p.ends_with("validation.md")) {
        let text = std::fs::read_to_string(&path).unwrap();
        for (n, line) in text.lines().enumerate() {
            for hash in commit_hashes(line) {
                found.push(format!("{}:{}: {hash}", path.strip_prefix(root()).unwrap().display(), n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "commit hashes in the documentation (history belongs in commit messages):\n{}",
        found.join("\n")
    );
}

/// The README's two set-up commands are the ones CI runs and uses.
#[test]
fn readme_names_the_set_up_commands_ci_runs() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    let run = "cargo run --release -- run examples/block_indentation.toml";
    assert!(readme.contains(run) && root().join("examples/block_indentation.toml").exists());
    assert!(readme.contains("\ncargo test --release "), "README.md: the test command");
    assert!(ci.lines().any(|l| l.trim() == "cargo test --release"), ".ci/run runs another test command");
    let msrv = std::fs::read_to_string(root().join("Cargo.toml"))
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("rust-version = ").map(|v| v.trim_matches('"').to_string()))
        .expect("rust-version in Cargo.toml");
    assert!(readme.contains(&format!("**`{msrv}` or newer**")), "README.md must state Rust {msrv}");
}

/// GitHub's anchor of a heading: lowercase, only letters, digits, spaces,
/// `-` and `_` kept, spaces as `-`.
fn slug(heading: &str) -> String {
    heading
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// Anchors of a Markdown file's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(slug(line.trim_start_matches('#').trim()));
        }
    }
    out
}

/// Every relative link `](target)` of README.md and docs/*.md names a file
/// that exists, and its `#anchor`, if any, a heading of that file.
#[test]
fn relative_links_resolve() {
    let mut broken = Vec::new();
    for path in documents() {
        let text = std::fs::read_to_string(&path).unwrap();
        for (_, rest) in text.match_indices("](").map(|(i, _)| text.split_at(i + 2)) {
            let Some(end) = rest.find(')') else { continue };
            let target = &rest[..end];
            if target.starts_with("http") || target.contains(' ') {
                continue;
            }
            let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
            let file = if file.is_empty() { path.clone() } else { path.parent().unwrap().join(file) };
            let shown = format!("{}: {target}", path.strip_prefix(root()).unwrap().display());
            match std::fs::read_to_string(&file) {
                Err(_) if !file.exists() => broken.push(format!("{shown} (no such file)")),
                Ok(t) if !anchor.is_empty() && !anchors(&t).iter().any(|a| a == anchor) => {
                    broken.push(format!("{shown} (no such heading)"))
                }
                _ => {}
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Every `#[ignore]` in tests/, src/ and crates/ (the other crates' src/ and
/// tests/) names the validation step that runs
/// it: `#[ignore = "validate: slow — …"]` (bench/validate's step `slow`,
/// within its hour) or `#[ignore = "validate: references — …"]` (the long
/// CalculiX runs that re-make stored 3D references, `bench/validate
/// --references`). A bare or other reason would leave the test run by
/// nothing.
#[test]
fn every_ignored_test_names_its_validation_step() {
    let mut files = Vec::new();
    let mut stack = vec![root().join("tests"), root().join("src"), root().join("crates")];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                files.push(p);
            }
        }
    }
    let validate = std::fs::read_to_string(root().join("bench/validate")).unwrap();
    assert!(validate.contains("\"validate: slow\"") && validate.contains("\"validate: references\""));
    let mut bad = Vec::new();
    for f in files {
        for (n, line) in std::fs::read_to_string(&f).unwrap().lines().enumerate() {
            let t = line.trim_start();
            if t.starts_with("#[ignore")
                && !(t.starts_with("#[ignore = \"validate: slow — ")
                    || t.starts_with("#[ignore = \"validate: references — "))
            {
                bad.push(format!("{}:{}: {t}", f.strip_prefix(root()).unwrap().display(), n + 1));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "ignored tests that no validation step runs (give them `validate: slow — …` or `validate: references — …`):\n{}",
        bad.join("\n")
    );
}

/// A figure of README.md or docs/: a number outside code that states a
/// measured, computed or published value, with the tag naming its row of
/// docs/validation.md.
#[derive(Debug, PartialEq)]
struct Figure {
    /// Line number (1-based).
    line: usize,
    /// The number as written (sign, digits, separators, exponent).
    text: String,
    /// `<!--v:ID-->` (the figure is row ID's value) or `<!--b:ID-->` (it is
    /// the bound row ID's test asserts) right after it, if any.
    tag: Option<Tag>,
}

/// A figure's source: a row of docs/validation.md, as its value or its
/// asserted bound.
#[derive(Debug, PartialEq)]
enum Tag {
    Value(String),
    Bound(String),
}

/// Units (after one optional space) that make a number a figure.
const UNITS: [&str; 34] = [
    "%", "×", "s", "ms", "µs", "min", "h", "minutes", "seconds", "hours", "N", "kN", "MN", "MPa", "GPa", "kPa", "Pa",
    "mm", "µm", "nm", "m", "Hz", "kHz", "MiB", "GiB", "KiB", "MB", "GB", "kB", "J", "kg", "DOF", "m/s", "K",
];

/// The line with its inline code, link targets, URLs and HTML comments
/// (other than figure tags) blanked out: code spans hold model-file input
/// (`young_modulus = 70e9`), versions and commands, not figures.
fn prose(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix('`') {
            let end = r.find('`').map_or(r.len(), |e| e + 1);
            out.push(' ');
            rest = &r[end.min(r.len())..];
        } else if rest.starts_with("](") {
            let end = rest.find(')').map_or(rest.len(), |e| e + 1);
            out.push(']');
            rest = &rest[end..];
        } else if rest.starts_with("http://") || rest.starts_with("https://") {
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            out.push(' ');
            rest = &rest[end..];
        } else if rest.starts_with("<!--") && !rest.starts_with("<!--v:") && !rest.starts_with("<!--b:") {
            let end = rest.find("-->").map_or(rest.len(), |e| e + 3);
            out.push(' ');
            rest = &rest[end..];
        } else {
            let c = rest.chars().next().unwrap();
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// Every figure of a Markdown text (outside fenced code). A number is a
/// figure if it has a decimal point, an exponent or thousands separators,
/// or a unit or `%` after it, or `×` before it; numbers inside names (B4,
/// L9), section, table, figure, equation and issue numbers, and dates are
/// not.
fn figures(text: &str) -> Vec<Figure> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (n, raw) in text.lines().enumerate() {
        if raw.starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let line = prose(raw);
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            let before = if i > 0 { chars[i - 1] } else { ' ' };
            if !c.is_ascii_digit() || before.is_alphanumeric() || matches!(before, '_' | '.' | '§' | '/' | '#' | '@') {
                i += 1;
                continue;
            }
            let start = if matches!(before, '−' | '-' | '+')
                && (i < 2 || !(chars[i - 2].is_alphanumeric() || chars[i - 2] == '_'))
            {
                i - 1
            } else {
                i
            };
            let mut j = i;
            let (mut point, mut comma, mut exponent) = (false, false, false);
            while j < chars.len() {
                let d = chars[j];
                let next_digits =
                    |k: usize, count: usize| (1..=count).all(|m| chars.get(k + m).is_some_and(char::is_ascii_digit));
                if d.is_ascii_digit() {
                    j += 1;
                } else if d == ',' && !point && next_digits(j, 3) && !chars.get(j + 4).is_some_and(char::is_ascii_digit)
                {
                    comma = true;
                    j += 1;
                } else if d == '.' && !point && !exponent && next_digits(j, 1) {
                    point = true;
                    j += 1;
                } else if d == 'e'
                    && !exponent
                    && (next_digits(j, 1) || (matches!(chars.get(j + 1), Some('-' | '−')) && next_digits(j + 1, 1)))
                {
                    exponent = true;
                    j += if next_digits(j, 1) { 1 } else { 2 };
                } else {
                    break;
                }
            }
            let text: String = chars[start..j].iter().collect();
            let after: String = chars[j..].iter().collect();
            let tagged = |prefix: &str| after.strip_prefix(prefix).and_then(|r| r.split_once("-->"));
            let (tag, after) = match (tagged("<!--v:"), tagged("<!--b:")) {
                (Some((id, rest)), _) => (Some(Tag::Value(id.to_string())), rest.to_string()),
                (_, Some((id, rest))) => (Some(Tag::Bound(id.to_string())), rest.to_string()),
                _ => (None, after),
            };
            let trimmed = after.strip_prefix(' ').unwrap_or(&after);
            // `4 × 4` is a product of counts, `266×` a ratio
            let product = |r: &str| r.trim_start().starts_with(|c: char| c.is_ascii_digit());
            let unit = UNITS.iter().any(|u| {
                trimmed.strip_prefix(u).is_some_and(|r| {
                    !(r.starts_with(|c: char| c.is_alphanumeric() || c == '_') || (*u == "×" && product(r)))
                })
            }) || after.starts_with('%');
            let head: String = chars[..start].iter().collect();
            let head = head.trim_end_matches(['(', ' ']);
            let numbered =
                ["§", "Table", "Tables", "Fig.", "Figs.", "issue", "issues", "Issue", "Eq.", "eq.", "step", "Step"]
                    .iter()
                    .any(|w| head.ends_with(w));
            let date = chars.get(j) == Some(&'-') && j - start == 4 && !point;
            let times = start > 0 && chars[start - 1] == '×';
            // a tag makes a bare count a figure (README's test count was
            // left a run behind its row: a docs audit)
            if !numbered && !date && (point || comma || exponent || unit || times || tag.is_some()) {
                out.push(Figure { line: n + 1, text, tag });
            }
            i = j.max(i + 1);
        }
    }
    out
}

#[test]
fn figures_are_recognised_and_names_numbers_and_code_are_not() {
    let text = "σ_zz −134.3<!--v:block.s_zz--> MPa at 5,772 DOF, 0.61 s, +8.0 % and ×266, 2e-6 (test 2<!--b:x--> %);\n\
                4 × 4 L9, 3 × 1, 20×;\n\
                10 B4 × 108 L9, §4.1, Table 2, issue 23, 2026-11-25, `E = 70e9`, [a](docs/x-1.2.md), 3 cores\n\
                ```\n1.5 s\n```\n";
    let all = figures(text);
    let found: Vec<(usize, &str, Option<&Tag>)> =
        all.iter().map(|f| (f.line, f.text.as_str(), f.tag.as_ref())).collect();
    let (v, b) = (Tag::Value("block.s_zz".into()), Tag::Bound("x".into()));
    assert_eq!(
        found,
        [
            (1, "−134.3", Some(&v)),
            (1, "5,772", None),
            (1, "0.61", None),
            (1, "+8.0", None),
            (1, "266", None),
            (1, "2e-6", None),
            (1, "2", Some(&b)),
            (2, "20", None)
        ]
    );
}

/// The mark of a document whose figures are all sourced (checked by
/// [`every_figure_in_the_docs_has_a_source`]).
const SOURCED: &str = "<!-- every figure is a row of docs/validation.md -->";

/// The rows of the validation report: id → (value, what its test checks)
/// (docs/validation.md, written by `bench/validate`).
fn report_rows() -> std::collections::HashMap<String, (f64, String)> {
    let text = std::fs::read_to_string(root().join("docs/validation.md")).unwrap();
    let mut rows = std::collections::HashMap::new();
    let mut in_figures = false;
    for line in text.lines() {
        if line.starts_with("## ") {
            in_figures = line == "## Figures";
            continue;
        }
        let cells: Vec<&str> = line.trim().trim_matches('|').split(" | ").map(str::trim).collect();
        if in_figures
            && cells.len() == 7
            && !cells[0].starts_with("id")
            && !cells[0].starts_with("--")
            && let Ok(v) = cells[1].parse::<f64>()
        {
            rows.insert(cells[0].to_string(), (v, cells[3].to_string()));
        }
    }
    rows
}

/// The value of a figure as written, and half a unit of its last digit
/// (the rounding a correct figure may carry).
fn value_and_resolution(text: &str) -> (f64, f64) {
    let t = text.replace('−', "-").replace(',', "");
    let (mantissa, exponent) = match t.split_once('e') {
        Some((m, e)) => (m.to_string(), e.parse::<i32>().unwrap()),
        None => (t.clone(), 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    let value: f64 = t.parse().unwrap();
    (value, 0.5 * 10f64.powi(exponent - decimals))
}

#[test]
fn a_figure_matches_its_row_at_the_precision_written() {
    assert_eq!(value_and_resolution("−134.3"), (-134.3, 0.05));
    assert_eq!(value_and_resolution("1,576"), (1576.0, 0.5));
    let (v, r) = value_and_resolution("0.95e-3");
    assert!((v - 0.95e-3).abs() < 1e-18 && (r - 0.5e-5).abs() < 1e-18);
}

/// Every document (README.md and docs/*.md but the report itself) holds the
/// line `SOURCED`, and every figure in it carries a tag naming a row of
/// docs/validation.md, and shows that row's value at
/// the precision written (an unsigned figure may show its magnitude; a tag
/// `<!--v:ID*1e-6-->` scales the row into the unit written). A
/// figure added without a source, or left behind when the report moved,
/// fails here; `bench/validate --update-docs` rewrites the tagged figures
/// from the report.
#[test]
fn every_figure_in_the_docs_has_a_source() {
    let rows = report_rows();
    let mut bad = Vec::new();
    for path in documents().into_iter().filter(|p| !p.ends_with("validation.md")) {
        let shown = path.strip_prefix(root()).unwrap().display().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        if !text.contains(SOURCED) {
            bad.push(format!("{shown}: no line {SOURCED} (every document's figures are checked)"));
            continue;
        }
        for f in figures(&text) {
            let at = format!("{shown}:{}: {}", f.line, f.text);
            let (id, bound) = match &f.tag {
                None => {
                    bad.push(format!("{at}: no source (tag it <!--v:ID--> with a row of docs/validation.md)"));
                    continue;
                }
                Some(Tag::Value(id)) => (id, false),
                Some(Tag::Bound(id)) => (id, true),
            };
            // a value tag may scale the row into the unit written: `ID*1e-6` (N → MN)
            let (id, scale) = match id.split_once('*') {
                Some((id, factor)) if !bound => (id, factor.parse::<f64>().unwrap_or(f64::NAN)),
                _ => (id.as_str(), 1.0),
            };
            let Some((row, check)) = rows.get(id) else {
                bad.push(format!("{at}: tag {id} is not a row of docs/validation.md"));
                continue;
            };
            if bound {
                let number = f.text.trim_start_matches(['+', '−', '-']);
                if !check
                    .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                    .any(|w| w == number)
                {
                    bad.push(format!("{at}: the check of {id} is \"{check}\", which has no bound {number}"));
                }
                continue;
            }
            let row = row * scale;
            let (value, resolution) = value_and_resolution(&f.text);
            let signed = f.text.starts_with(['−', '-', '+']);
            let shown_row = if signed { row } else { row.abs() };
            if (value - shown_row).abs() > resolution * (1.0 + 1e-9) + 1e-12 * row.abs() {
                bad.push(format!("{at}: the report gives {id} = {row}"));
            }
        }
    }
    assert!(bad.is_empty(), "{} figures without a matching source:\n{}", bad.len(), bad.join("\n"));
}
