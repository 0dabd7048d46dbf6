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
    for path in documents() {
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
    assert!(readme.contains(&format!("**{msrv} or newer**")), "README.md must state Rust {msrv}");
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

/// Every `#[ignore]` in tests/ and src/ names the validation step that runs
/// it: `#[ignore = "validate: slow — …"]` (bench/validate's step `slow`,
/// within its hour) or `#[ignore = "validate: references — …"]` (the long
/// CalculiX runs that re-make stored 3D references, `bench/validate
/// --references`). A bare or other reason would leave the test run by
/// nothing.
#[test]
fn every_ignored_test_names_its_validation_step() {
    let mut files = Vec::new();
    let mut stack = vec![root().join("tests"), root().join("src")];
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
