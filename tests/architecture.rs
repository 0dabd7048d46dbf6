//! The house rules of ARCHITECTURE.md that a test can check: no import
//! cycle between the top-level modules of `src/`, nor between the files
//! (submodules) of any module directory, and no source file over 600 lines
//! (a long file is a sign it holds more than one idea).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Top-level module of a source file (`src/model/mod.rs` → `model`).
fn module_of(path: &Path) -> String {
    let rel = path.strip_prefix(src()).unwrap();
    let first = rel.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
    first.trim_end_matches(".rs").to_string()
}

/// `a → b` when a file of module `a` names `crate::b` outside comments.
fn dependencies() -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let mut deps: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files {
        let m = module_of(&f);
        if m == "lib" || m == "main" {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let entry = deps.entry(m.clone()).or_default();
        for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
            let mut rest = line;
            while let Some(i) = rest.find("crate::") {
                rest = &rest[i + 7..];
                let name: String = rest.chars().take_while(|c| c.is_ascii_lowercase() || *c == '_').collect();
                if !name.is_empty() && name != m {
                    entry.insert(name);
                }
            }
        }
    }
    deps
}

#[test]
fn modules_form_no_import_cycle() {
    let deps = dependencies();
    // depth-first search for a back edge
    fn visit(
        m: &str,
        deps: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == m) {
            let mut cycle = path[i..].to_vec();
            cycle.push(m.to_string());
            return Some(cycle);
        }
        if done.contains(m) {
            return None;
        }
        path.push(m.to_string());
        for d in deps.get(m).into_iter().flatten() {
            if let Some(c) = visit(d, deps, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(m.to_string());
        None
    }
    let mut done = BTreeSet::new();
    for m in deps.keys() {
        if let Some(cycle) = visit(m, &deps, &mut Vec::new(), &mut done) {
            panic!("import cycle: {}", cycle.join(" → "));
        }
    }
    // the layering ARCHITECTURE.md describes: the model does not read results
    for (low, high) in [("model", "post"), ("model", "analysis"), ("values", "elements"), ("solver", "analysis")] {
        assert!(!deps[low].contains(high), "{low} depends on {high}");
    }
}

#[test]
fn no_source_file_is_over_600_lines() {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let long: Vec<String> = files
        .iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(f).unwrap().lines().count();
            (n > 600).then(|| format!("{} ({n} lines)", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "split these: {long:?}");
}

/// Source text with comments, string and character literals blanked out
/// (kept as spaces, so that braces and paths in them are not read as code).
fn code_only(text: &str) -> Vec<char> {
    let s: Vec<char> = text.chars().collect();
    let mut out = s.clone();
    let mut i = 0;
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for c in &mut out[from..to.min(s.len())] {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    while i < s.len() {
        let next = |k: usize| s.get(i + k).copied().unwrap_or('\0');
        if s[i] == '/' && next(1) == '/' {
            let end = (i..s.len()).find(|&j| s[j] == '\n').unwrap_or(s.len());
            blank(&mut out, i, end);
            i = end;
        } else if s[i] == '/' && next(1) == '*' {
            let end = (i + 2..s.len()).find(|&j| s[j] == '*' && s.get(j + 1) == Some(&'/')).map_or(s.len(), |j| j + 2);
            blank(&mut out, i, end);
            i = end;
        } else if s[i] == 'r' && (next(1) == '"' || next(1) == '#') && (i == 0 || !is_ident(s[i - 1])) {
            // raw string r"…" or r#"…"#
            let hashes = (1..).take_while(|&k| next(k) == '#').count();
            if next(1 + hashes) != '"' {
                i += 1;
                continue;
            }
            let close: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let start = i + 2 + hashes;
            let end = (start..s.len()).find(|&j| s[j..].starts_with(&close)).map_or(s.len(), |j| j + close.len());
            blank(&mut out, i, end);
            i = end;
        } else if s[i] == '"' {
            let mut j = i + 1;
            while j < s.len() && s[j] != '"' {
                j += if s[j] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, j + 1);
            i = j + 1;
        } else if s[i] == '\'' && (next(1) == '\\' || next(2) == '\'') {
            // a character literal, not a lifetime
            let mut j = i + 1;
            while j < s.len() && s[j] != '\'' {
                j += if s[j] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i, j + 1);
            i = j + 1;
        } else {
            i += 1;
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Removes `#[cfg(test)] mod … { … }` blocks: in them `super` is the file
/// itself, and what a test reads is not a dependency of the code.
fn without_test_modules(code: &mut Vec<char>) {
    let text: String = code.iter().collect();
    let mut cut = Vec::new();
    let mut from = 0;
    while let Some(k) = text[from..].find("#[cfg(test)]") {
        let at = from + k;
        let after = text[at + 12..].trim_start();
        from = at + 12;
        if !after.starts_with("mod ") {
            continue;
        }
        let open_byte = at + 12 + (text[at + 12..].len() - after.len()) + after.find('{').unwrap_or(0);
        let open = text[..open_byte].chars().count();
        let start = text[..at].chars().count();
        let mut depth = 0;
        for (j, &c) in code.iter().enumerate().skip(open) {
            depth += (c == '{') as i32 - (c == '}') as i32;
            if depth == 0 {
                cut.push((start, j + 1));
                break;
            }
        }
    }
    for (a, b) in cut.into_iter().rev() {
        code.drain(a..b.min(code.len()));
    }
}

/// Every path that starts with `crate::`, `super::` or `self::` in `code`,
/// `use` groups (`use super::{a, b::{c, d}}`) expanded, as written.
fn paths_in(code: &[char]) -> Vec<Vec<String>> {
    fn skip_ws(s: &[char], i: &mut usize) {
        while *i < s.len() && s[*i].is_whitespace() {
            *i += 1;
        }
    }
    fn path(s: &[char], i: &mut usize, mut prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
        loop {
            skip_ws(s, i);
            if *i < s.len() && s[*i] == '{' {
                *i += 1;
                loop {
                    path(s, i, prefix.clone(), out);
                    skip_ws(s, i);
                    match s.get(*i) {
                        Some(',') => *i += 1,
                        Some('}') => {
                            *i += 1;
                            return;
                        }
                        _ => return,
                    }
                    skip_ws(s, i);
                    if s.get(*i) == Some(&'}') {
                        *i += 1;
                        return;
                    }
                }
            }
            let start = *i;
            while *i < s.len() && (is_ident(s[*i]) || s[*i] == '*') {
                *i += 1;
            }
            if *i == start {
                out.push(prefix);
                return;
            }
            prefix.push(s[start..*i].iter().collect());
            skip_ws(s, i);
            if s.get(*i) == Some(&':') && s.get(*i + 1) == Some(&':') {
                *i += 2;
            } else {
                out.push(prefix);
                return;
            }
        }
    }
    let mut out = Vec::new();
    let mut i = 0;
    while i < code.len() {
        let starts = ["crate", "super", "self"].iter().any(|w| {
            let w: Vec<char> = w.chars().collect();
            code[i..].starts_with(&w) && (i == 0 || !is_ident(code[i - 1]) && code[i - 1] != ':')
        });
        if starts {
            let before = i;
            path(code, &mut i, Vec::new(), &mut out);
            i = i.max(before + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// The module path of a source file (`src/model/bodies.rs` → `[model,
/// bodies]`, `src/model/mod.rs` → `[model]`, `src/lib.rs` → `[]`).
fn module_path(file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src()).unwrap();
    let mut parts: Vec<String> = rel.iter().map(|c| c.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !(parts.is_empty() && (stem == "lib" || stem == "main")) && stem != "mod" {
        parts.push(stem.to_string());
    }
    parts
}

/// A path as written in the file of module `module`, made absolute
/// (`super::bounds::within` in `model::material` → `[model, bounds, within]`).
fn absolute(module: &[String], written: &[String]) -> Option<Vec<String>> {
    let mut base: Vec<String> = match written.first()?.as_str() {
        "crate" => Vec::new(),
        "self" => module.to_vec(),
        "super" => module[..module.len().checked_sub(1)?].to_vec(),
        _ => return None,
    };
    let mut rest = &written[1..];
    while rest.first().is_some_and(|s| s == "super") {
        base.pop()?;
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The submodules of the module in directory `dir`: its `.rs` files (but
/// `mod.rs`) and its subdirectories.
fn submodules(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            let name = p.file_name()?.to_string_lossy().into_owned();
            if p.is_dir() {
                Some(name)
            } else {
                let stem = name.strip_suffix(".rs")?;
                (stem != "mod" && stem != "lib" && stem != "main").then(|| stem.to_string())
            }
        })
        .collect()
}

/// For every module directory (`src/model`, `src/analysis/structure`, …):
/// `a → b` when a file of submodule `a` names submodule `b` of the same
/// module (`use super::b`, `super::b::f`, `crate::model::b::X`).
fn file_dependencies() -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let mut levels: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for f in files {
        let module = module_path(&f);
        let mut code = code_only(&std::fs::read_to_string(&f).unwrap());
        without_test_modules(&mut code);
        for written in paths_in(&code) {
            let Some(target) = absolute(&module, &written) else { continue };
            // the deepest module holding both the file and the target
            let common = module.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if common >= module.len() || common >= target.len() {
                continue; // the file names itself, one of its own submodules or an ancestor
            }
            let parent = &module[..common];
            let dir = parent.iter().fold(src(), |d, p| d.join(p));
            if !submodules(&dir).contains(&target[common]) {
                continue; // an item of the parent (e.g. `super::ModelError`), not a file
            }
            levels
                .entry(if parent.is_empty() { "crate".into() } else { parent.join("::") })
                .or_default()
                .entry(module[common].clone())
                .or_default()
                .insert(target[common].clone());
        }
    }
    levels
}

/// Every cycle found by a depth-first search (one per back edge).
fn cycles(deps: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    fn visit(
        m: &str,
        deps: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
        found: &mut Vec<Vec<String>>,
    ) {
        if let Some(i) = path.iter().position(|p| p == m) {
            let mut cycle = path[i..].to_vec();
            cycle.push(m.to_string());
            found.push(cycle);
            return;
        }
        if done.contains(m) {
            return;
        }
        path.push(m.to_string());
        for d in deps.get(m).into_iter().flatten() {
            visit(d, deps, path, done, found);
        }
        path.pop();
        done.insert(m.to_string());
    }
    let (mut done, mut found) = (BTreeSet::new(), Vec::new());
    for m in deps.keys() {
        visit(m, deps, &mut Vec::new(), &mut done, &mut found);
    }
    found
}

#[test]
fn files_within_a_module_form_no_import_cycle() {
    let levels = file_dependencies();
    // the check reads what it should: model's files depend on each other
    let model = &levels["model"];
    assert!(model["material"].contains("bounds") && model["bodies"].contains("validate"), "{model:?}");
    let found: Vec<String> = levels
        .iter()
        .flat_map(|(level, deps)| cycles(deps).into_iter().map(move |c| format!("{level}: {}", c.join(" → "))))
        .collect();
    assert!(found.is_empty(), "import cycles between the files of a module:\n{}", found.join("\n"));
}

/// The path reader on the forms the sources use.
#[test]
fn paths_are_read_from_use_groups_and_inline_paths() {
    let code = code_only(
        "use super::{bounds, schema::*, validate::{count, division}};\n// use super::comment\nlet s = \"super::string\";\n\
         let x = super::contacts::overlap(a);\nuse crate::model::{\n    sections::check,\n};\n",
    );
    let got: Vec<String> = paths_in(&code).iter().map(|p| p.join("::")).collect();
    assert_eq!(
        got,
        [
            "super::bounds",
            "super::schema::*",
            "super::validate::count",
            "super::validate::division",
            "super::contacts::overlap",
            "crate::model::sections::check"
        ]
    );
    let module = ["model".to_string(), "bodies".to_string()];
    let abs = |p: &[&str]| absolute(&module, &p.iter().map(|s| s.to_string()).collect::<Vec<_>>()).unwrap();
    assert_eq!(abs(&["super", "sections", "profile"]), ["model", "sections", "profile"]);
    assert_eq!(abs(&["super", "super", "mesh"]), ["mesh"]);
}

/// Every function of `src/` (`fn` items and methods), with its line count
/// from the `fn` line to its closing brace: `(file:line name, lines)`.
fn function_lengths() -> Vec<(String, usize)> {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let mut out = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let code: String = code_only(&text).into_iter().collect();
        let chars: Vec<char> = code.chars().collect();
        let line_at = |i: usize| chars[..i].iter().filter(|&&c| c == '\n').count() + 1;
        let mut i = 0;
        while let Some(k) = code[char_byte(&chars, i)..].find("fn ") {
            let at = chars.len().min(i + code[char_byte(&chars, i)..][..k].chars().count());
            i = at + 3;
            if at > 0 && is_ident(chars[at - 1]) {
                continue;
            }
            let name: String = chars[at + 3..].iter().take_while(|c| is_ident(**c)).collect();
            // the body opens at the first `{` before any `;` (a trait
            // method without a body ends at its `;`)
            let Some(open) = (at..chars.len()).find(|&j| chars[j] == '{' || chars[j] == ';') else { break };
            if chars[open] == ';' || name.is_empty() {
                continue;
            }
            let mut depth = 0i32;
            let close = (open..chars.len()).find(|&j| {
                depth += (chars[j] == '{') as i32 - (chars[j] == '}') as i32;
                depth == 0
            });
            let Some(close) = close else { break };
            let shown = format!("{}:{} {name}", path.strip_prefix(src()).unwrap().display(), line_at(at));
            out.push((shown, line_at(close) - line_at(at) + 1));
        }
    }
    out
}

/// Byte offset of char index `i`.
fn char_byte(chars: &[char], i: usize) -> usize {
    chars[..i].iter().map(|c| c.len_utf8()).sum()
}

/// No function in `src/` is over 120 lines: a longer one does more than one
/// job. (No exception today; one would be listed here with its reason.)
#[test]
fn no_function_is_over_120_lines() {
    let long: Vec<(String, usize)> = function_lengths().into_iter().filter(|(_, n)| *n > 120).collect();
    assert!(long.is_empty(), "split these (or list them with a reason): {long:?}");
    // the measure itself: GMRES (about 100 lines, with nested loops and
    // braces in comments) is found whole
    let all = function_lengths();
    let gmres = all.iter().find(|(f, _)| f.starts_with("solver/krylov.rs:") && f.ends_with(" gmres"));
    assert!(gmres.is_some_and(|(_, n)| (80..=120).contains(n)), "{gmres:?} among {} functions", all.len());
}
