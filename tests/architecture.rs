//! The house rules of ARCHITECTURE.md that a test can check, read from the
//! syntax tree (`syn`), not from the characters of the source:
//!
//! * **The crates are layers**: the workspace's packages (the root's
//!   `Cargo.toml`) are ordered in [`CRATE_LAYERS`], the core library first; a
//!   package depends (normal, build or dev dependency) only on packages
//!   before it: the CalculiX bridge and the CLI on the core, never the
//!   reverse.
//! * **The module tree** of every crate (each package's `src/lib.rs` and
//!   `src/main.rs`) is followed through their `mod` items (`#[path]`
//!   honoured); every `.rs` file under a package's `src/` must be in it, so
//!   no check misses a file. Files are named by their path under `src/` for
//!   the core (the root package), from the repository root for the others.
//! * **No import cycle** between the top-level modules of a crate, nor
//!   between the files (submodules) of any module directory. `a → b` when
//!   the code of `a` (outside `#[cfg(test)]` items: what a test reads is not
//!   a dependency of the code) names `b`: in a `use` item, in any path of
//!   the syntax tree (types, expressions, patterns, attributes), or in a
//!   path inside a macro call's tokens; a name a `use` item brought in is
//!   followed to what it names. The layers ([`LAYERS`]): `input` (the
//!   model file's schema and checks) never reads `setup`, `analysis` or
//!   `post`; `setup` reads `input` and never `post` or `analysis`; `values`
//!   never `elements`, `solver` never `analysis`.
//! * **No function over 120 lines**: every `fn` item, method, associated
//!   function and default trait method, nested ones and tests included,
//!   from its `fn` keyword to its closing brace. (Functions written inside
//!   a `macro_rules!` body are tokens, not items, and are not counted.)
//! * **Long files are reviewed, not capped**: a file over 600 lines must be
//!   listed in [`LONG_FILES`] with a one-line reason why it is one idea; a
//!   listed file that is no longer over 600 lines (or no longer exists)
//!   fails the test too, so the list is always the current set of reviewed
//!   outliers. A hard cap bent the code: files were cut where the counter
//!   said, not where the concepts part.
//!
//! * **The structure holds parts**: `struct Structure` (the nonlinear
//!   problem of `analysis::structure`) has at most [`MAX_STRUCTURE_FIELDS`]
//!   named fields; a new capability is a part inside one of them (a
//!   contribution in its parts list), not a field of its own.
//! * **The public surface is what others name**: a plain-`pub` item (or
//!   field, or re-export) of a public module of the core is named by the
//!   code outside it (the other crates and their tests, `tests/`, the
//!   Python package, the doc examples), or exposed by the public face of
//!   one that is, or listed in [`PUBLIC_BY_REVIEW`] (the same check as
//!   `python3 bench/public_surface.py --check`).
//!
//! Each check is shown to fail on a small source written for it (the
//! `*_is_caught` tests below).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use syn::visit::{self, Visit};

/// The longest a function may be, in lines.
const MAX_FN_LINES: usize = 120;

/// Above this many lines a file must be in [`LONG_FILES`].
const LONG_FILE_LINES: usize = 600;

/// Files over [`LONG_FILE_LINES`] lines, reviewed: `(path as in
/// [`Source::file`], why it stays one file)`.
const LONG_FILES: &[(&str, &str)] = &[];

/// The workspace's packages from the lowest layer up: each may depend only
/// on the ones before it.
/// The Python package sits on the core alone, a member beside the CLI (last:
/// nothing depends on it).
const CRATE_LAYERS: &[&str] = &["cufem", "cufem-ccx", "cufem-cli", "cufem-python"];

/// The repository root: the workspace's and the core package's directory.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A manifest (`Cargo.toml`) as a TOML table.
fn manifest(dir: &Path) -> toml::Table {
    let path = dir.join("Cargo.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.parse().unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The workspace's packages: `(name, directory relative to the root)`.
fn members() -> Vec<(String, String)> {
    let members = manifest(root())["workspace"]["members"].as_array().unwrap().clone();
    members
        .iter()
        .map(|m| {
            let dir = m.as_str().unwrap().to_string();
            let name = manifest(&root().join(&dir))["package"]["name"].as_str().unwrap().to_string();
            (name, dir)
        })
        .collect()
}

/// The `src/` folder of the package in `dir` and the prefix its files are
/// named with (none for the core).
fn src_of(dir: &str) -> (PathBuf, String) {
    let prefix = if dir == "." { String::new() } else { format!("{dir}/src/") };
    (root().join(dir).join("src"), prefix)
}

/// One source file of a crate.
struct Source {
    /// Path under `src/` for the core (`setup/bodies.rs`), from the
    /// repository root for the other packages (`crates/cufem-ccx/src/deck.rs`).
    file: String,
    /// Module path in its crate (`[setup, bodies]`; `[]` for the root).
    module: Vec<String>,
    /// Reached through a `#[cfg(test)] mod`: test code only.
    test: bool,
    /// Line count of the file.
    lines: usize,
    ast: syn::File,
}

fn parse(file: &str, text: &str) -> syn::File {
    syn::parse_file(text).unwrap_or_else(|e| {
        let at = e.span().start();
        panic!("{file}:{}:{}: {e}", at.line, at.column + 1)
    })
}

/// `#[cfg(test)]` among `attrs`.
fn is_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| match &a.meta {
        syn::Meta::List(l) => l.path.is_ident("cfg") && l.tokens.to_string() == "test",
        _ => false,
    })
}

/// The value of a `#[path = "…"]` attribute.
fn path_attribute(attrs: &[syn::Attribute]) -> Option<String> {
    attrs.iter().find_map(|a| match &a.meta {
        syn::Meta::NameValue(nv) if nv.path.is_ident("path") => match &nv.value {
            syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) => Some(s.value()),
            _ => None,
        },
        _ => None,
    })
}

/// The files of the crate whose root is `{src}/{root}`, found by following
/// its `mod` items from the root; named with `prefix`.
fn crate_sources(src: &Path, prefix: &str, root: &str) -> Vec<Source> {
    let mut out = Vec::new();
    load(&Tree { src, prefix }, &src.join(root), Vec::new(), false, true, &mut out);
    out
}

/// Where a crate's files are and how they are named.
struct Tree<'a> {
    src: &'a Path,
    prefix: &'a str,
}

impl Tree<'_> {
    fn name(&self, path: &Path) -> String {
        format!("{}{}", self.prefix, path.strip_prefix(self.src).unwrap().to_string_lossy())
    }
}

/// Reads the file of module `module` and, recursively, the files of the
/// modules it declares with `mod name;`. `mod_rs`: the file is a crate
/// root, a `mod.rs` or reached by `#[path]`, so its children sit next to
/// it rather than in a directory named after it.
fn load(tree: &Tree, path: &Path, module: Vec<String>, test: bool, mod_rs: bool, out: &mut Vec<Source>) {
    let file = tree.name(path);
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{file}: {e}"));
    let ast = parse(&file, &text);
    let here = path.parent().unwrap();
    let children = if mod_rs { here.to_path_buf() } else { here.join(path.file_stem().unwrap()) };
    for item in &ast.items {
        let syn::Item::Mod(m) = item else { continue };
        if m.content.is_some() {
            continue; // inline: its items are part of this file
        }
        let name = m.ident.to_string();
        let mut sub = module.clone();
        sub.push(name.clone());
        let test = test || is_test(&m.attrs);
        if let Some(p) = path_attribute(&m.attrs) {
            load(tree, &here.join(p), sub, test, true, out);
        } else if children.join(format!("{name}.rs")).is_file() {
            load(tree, &children.join(format!("{name}.rs")), sub, test, false, out);
        } else {
            load(tree, &children.join(&name).join("mod.rs"), sub, test, true, out);
        }
    }
    out.push(Source { file, module, test, lines: text.lines().count(), ast });
}

/// The files of every crate of the workspace (a package's library and
/// binary are two crates), by crate: `(package, crate root, files)`.
fn crates() -> Vec<(String, &'static str, Vec<Source>)> {
    let mut out = Vec::new();
    for (name, dir) in members() {
        let (src, prefix) = src_of(&dir);
        for root in ["lib.rs", "main.rs"] {
            if src.join(root).is_file() {
                out.push((name.clone(), root, crate_sources(&src, &prefix, root)));
            }
        }
    }
    out
}

/// The core library's files.
fn core_library<'a>(crates: &'a [(String, &'static str, Vec<Source>)]) -> &'a [Source] {
    &crates.iter().find(|(name, root, _)| name == CRATE_LAYERS[0] && *root == "lib.rs").unwrap().2
}

#[test]
fn every_source_file_is_in_the_module_tree() {
    fn files(tree: &Tree, dir: &Path, out: &mut BTreeSet<String>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                files(tree, &p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.insert(tree.name(&p));
            }
        }
    }
    let mut on_disk = BTreeSet::new();
    for (_, dir) in members() {
        let (src, prefix) = src_of(&dir);
        files(&Tree { src: &src, prefix: &prefix }, &src, &mut on_disk);
    }
    let crates = crates();
    let reached: BTreeSet<String> = crates.iter().flat_map(|c| &c.2).map(|s| s.file.clone()).collect();
    let orphans: Vec<&String> = on_disk.difference(&reached).collect();
    assert!(orphans.is_empty(), "files no `mod` item reaches: {orphans:?}");
    // every package's tree is read: the bridge's and the CLI's files too
    for file in ["crates/cufem-ccx/src/verify/field.rs", "crates/cufem-cli/src/cli/bench.rs"] {
        assert!(reached.contains(file), "{file} not reached");
    }
    let lib = core_library(&crates);
    // the tree is read as rustc reads it: a `#[path]` test file is a
    // submodule of the file that declares it
    let kinematic = lib.iter().find(|s| s.file == "materials/kinematic_tests.rs").unwrap();
    assert_eq!(kinematic.module, ["materials", "kinematic", "tests"]);
    assert!(kinematic.test);
    let schema = lib.iter().find(|s| s.file == "input/schema/section.rs").unwrap();
    assert_eq!(schema.module, ["input", "schema", "section"]);
}

// ---------------------------------------------------------------- layers

/// The workspace packages a manifest depends on (normal, build and dev
/// dependencies; `x.workspace = true` counts as `x`).
fn package_dependencies(manifest: &toml::Table, packages: &[&str]) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for kind in ["dependencies", "build-dependencies", "dev-dependencies"] {
        let Some(deps) = manifest.get(kind).and_then(|d| d.as_table()) else { continue };
        for (key, value) in deps {
            let name = value.get("package").and_then(|p| p.as_str()).unwrap_or(key);
            if packages.contains(&name) {
                out.insert(name.to_string());
            }
        }
    }
    out
}

/// `package → dependency` edges that go against [`CRATE_LAYERS`]-like `layers`
/// (lowest first), and packages not placed in it.
fn layer_violations(manifests: &[(String, toml::Table)], layers: &[&str]) -> Vec<String> {
    let mut problems = Vec::new();
    for (name, manifest) in manifests {
        let Some(level) = layers.iter().position(|l| l == name) else {
            problems.push(format!("{name} is a workspace member not placed in CRATE_LAYERS"));
            continue;
        };
        for dep in package_dependencies(manifest, layers) {
            if layers.iter().position(|l| *l == dep).is_some_and(|d| d >= level) {
                problems.push(format!("{name} depends on {dep}, a layer at or above its own"));
            }
        }
    }
    problems
}

/// The CalculiX bridge and the CLI depend on the core, never the reverse;
/// every package is placed in [`CRATE_LAYERS`].
#[test]
fn crates_depend_on_lower_layers_only() {
    let manifests: Vec<(String, toml::Table)> =
        members().into_iter().map(|(name, dir)| (name, manifest(&root().join(dir)))).collect();
    let problems = layer_violations(&manifests, CRATE_LAYERS);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // the check reads the real edges: the CLI uses both libraries
    let cli = &manifests.iter().find(|(n, _)| n == "cufem-cli").unwrap().1;
    assert_eq!(package_dependencies(cli, CRATE_LAYERS), BTreeSet::from(["cufem".to_string(), "cufem-ccx".to_string()]));
}

/// The core depending on the bridge (even as a renamed dev-dependency),
/// a package on itself and an unplaced package are each found.
#[test]
fn a_dependency_against_the_layers_is_caught() {
    let toml = |text: &str| -> toml::Table { text.parse().unwrap() };
    let manifests = [
        ("core".to_string(), toml("[dev-dependencies]\nbridge_alias = { package = \"bridge\", path = \"b\" }")),
        ("bridge".to_string(), toml("[dependencies]\ncore.workspace = true\nserde = \"1\"")),
        ("cli".to_string(), toml("[dependencies]\ncore = { path = \".\" }\ncli = { path = \".\" }")),
        ("extra".to_string(), toml("[dependencies]\ncore.workspace = true")),
    ];
    let problems = layer_violations(&manifests, &["core", "bridge", "cli"]);
    assert_eq!(
        problems,
        [
            "core depends on bridge, a layer at or above its own",
            "cli depends on cli, a layer at or above its own",
            "extra is a workspace member not placed in CRATE_LAYERS",
        ],
    );
    assert!(layer_violations(&manifests[1..2], &["core", "bridge"]).is_empty());
}

// ---------------------------------------------------------------- imports

/// The attributes of an item (those `#[cfg(test)]` is looked for in).
fn item_attributes(item: &syn::Item) -> &[syn::Attribute] {
    use syn::Item;
    match item {
        Item::Const(i) => &i.attrs,
        Item::Enum(i) => &i.attrs,
        Item::ExternCrate(i) => &i.attrs,
        Item::Fn(i) => &i.attrs,
        Item::ForeignMod(i) => &i.attrs,
        Item::Impl(i) => &i.attrs,
        Item::Macro(i) => &i.attrs,
        Item::Mod(i) => &i.attrs,
        Item::Static(i) => &i.attrs,
        Item::Struct(i) => &i.attrs,
        Item::Trait(i) => &i.attrs,
        Item::TraitAlias(i) => &i.attrs,
        Item::Type(i) => &i.attrs,
        Item::Union(i) => &i.attrs,
        Item::Use(i) => &i.attrs,
        _ => &[],
    }
}

/// The paths a file's code names, as written, with the module they are
/// written in; and the names its `use` items bring in.
#[derive(Default)]
struct Names {
    /// The module being read (the file's, then inline modules').
    module: Vec<String>,
    /// `(module, path as written)`.
    written: Vec<(Vec<String>, Vec<String>)>,
    /// Per module: a name brought in by `use` → the path it names, as written.
    aliases: BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>>,
    /// Inline (non-test) modules met.
    inline: Vec<Vec<String>>,
}

impl Names {
    fn of(source: &Source) -> Self {
        let mut names = Names { module: source.module.clone(), ..Names::default() };
        names.visit_file(&source.ast);
        names
    }

    /// Expands a `use` tree (`super::{a, b::{c as d, *}}`) below `prefix`.
    fn use_tree(&mut self, tree: &syn::UseTree, mut prefix: Vec<String>) {
        let (path, name) = match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                return self.use_tree(&p.tree, prefix);
            }
            syn::UseTree::Group(g) => {
                for t in &g.items {
                    self.use_tree(t, prefix.clone());
                }
                return;
            }
            syn::UseTree::Glob(_) => (prefix, None),
            syn::UseTree::Name(n) if n.ident == "self" => {
                let name = prefix.last().cloned();
                (prefix, name)
            }
            syn::UseTree::Name(n) => {
                prefix.push(n.ident.to_string());
                let name = prefix.last().cloned();
                (prefix, name)
            }
            syn::UseTree::Rename(r) => {
                if r.ident != "self" {
                    prefix.push(r.ident.to_string());
                }
                (prefix, Some(r.rename.to_string()).filter(|n| n != "_"))
            }
        };
        if let Some(name) = name {
            self.aliases.entry(self.module.clone()).or_default().insert(name, path.clone());
        }
        self.written.push((self.module.clone(), path));
    }

    /// Every `a::b::c` chain of identifiers in a macro call's tokens.
    fn tokens(&mut self, tokens: proc_macro2::TokenStream) {
        use proc_macro2::TokenTree;
        let tokens: Vec<TokenTree> = tokens.into_iter().collect();
        let colons = |i: usize| {
            matches!((tokens.get(i), tokens.get(i + 1)), (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
                if a.as_char() == ':' && b.as_char() == ':')
        };
        let mut i = 0;
        while i < tokens.len() {
            match &tokens[i] {
                TokenTree::Group(g) => self.tokens(g.stream()),
                TokenTree::Ident(first) if !(i >= 2 && colons(i - 2)) => {
                    let mut path = vec![first.to_string()];
                    while colons(i + 1) {
                        let Some(TokenTree::Ident(next)) = tokens.get(i + 3) else { break };
                        path.push(next.to_string());
                        i += 3;
                    }
                    self.written.push((self.module.clone(), path));
                }
                _ => {}
            }
            i += 1;
        }
    }
}

impl<'ast> Visit<'ast> for Names {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        if !is_test(item_attributes(item)) {
            visit::visit_item(self, item);
        }
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        if !is_test(&f.attrs) {
            visit::visit_impl_item_fn(self, f);
        }
    }

    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if m.content.is_some() {
            self.module.push(m.ident.to_string());
            self.inline.push(self.module.clone());
            visit::visit_item_mod(self, m);
            self.module.pop();
        }
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        if u.leading_colon.is_none() {
            self.use_tree(&u.tree, Vec::new());
        }
    }

    fn visit_path(&mut self, p: &'ast syn::Path) {
        if p.leading_colon.is_none() {
            let path = p.segments.iter().map(|s| s.ident.to_string()).collect();
            self.written.push((self.module.clone(), path));
        }
        visit::visit_path(self, p);
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        self.tokens(m.tokens.clone());
        visit::visit_macro(self, m);
    }
}

/// A path as written in module `module` made absolute
/// (`super::bounds::within` in `input::validate` → `[input, bounds, within]`);
/// `None` for a path that starts elsewhere (`std::…`, `Self::…`, a local).
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

/// `absolute`, with a first name a `use` item of the module brought in
/// replaced by what it names (`use super::bounds; bounds::within` →
/// `[input, bounds, within]`).
fn resolve(names: &Names, module: &[String], written: &[String], depth: usize) -> Option<Vec<String>> {
    if let Some(path) = absolute(module, written) {
        return Some(path);
    }
    let named = names.aliases.get(module)?.get(written.first()?)?;
    if depth > 8 || named.as_slice() == written {
        return None;
    }
    let mut path = resolve(names, module, named, depth + 1)?;
    path.extend(written[1..].iter().cloned());
    Some(path)
}

/// A directed graph between sibling modules.
type Graph = BTreeMap<String, BTreeSet<String>>;

/// For every module of a crate that has submodules (`crate` for the root,
/// `setup`, `analysis::structure`, …): `a → b` when the code of submodule
/// `a` names submodule `b` or something inside it.
fn import_graphs(sources: &[Source]) -> BTreeMap<String, Graph> {
    let names: Vec<Names> = sources.iter().filter(|s| !s.test).map(Names::of).collect();
    let mut modules: BTreeSet<Vec<String>> = sources.iter().map(|s| s.module.clone()).collect();
    modules.extend(names.iter().flat_map(|n| n.inline.iter().cloned()));
    let mut graphs: BTreeMap<String, Graph> = BTreeMap::new();
    for n in &names {
        for (module, written) in &n.written {
            let Some(target) = resolve(n, module, written, 0) else { continue };
            // the deepest module holding both the code and the target
            let common = module.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if common >= module.len() || common >= target.len() {
                continue; // the code names itself, one of its own submodules or an ancestor
            }
            if !modules.contains(&target[..=common]) {
                continue; // an item of the parent (e.g. `super::ModelError`), not a module
            }
            let parent = if common == 0 { "crate".to_string() } else { module[..common].join("::") };
            graphs.entry(parent).or_default().entry(module[common].clone()).or_default().insert(target[common].clone());
        }
    }
    graphs
}

/// Every cycle found by a depth-first search (one per back edge).
fn cycles(deps: &Graph) -> Vec<Vec<String>> {
    fn visit(m: &str, deps: &Graph, path: &mut Vec<String>, done: &mut BTreeSet<String>, found: &mut Vec<Vec<String>>) {
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

/// Every cycle of every graph, as `level: a → b → a`.
fn all_cycles(graphs: &BTreeMap<String, Graph>) -> Vec<String> {
    graphs
        .iter()
        .flat_map(|(level, deps)| cycles(deps).into_iter().map(move |c| format!("{level}: {}", c.join(" → "))))
        .collect()
}

#[test]
fn modules_and_files_form_no_import_cycle() {
    let crates = crates();
    let graphs = import_graphs(core_library(&crates));
    // the check reads what it should: the library's layers and setup's files
    let top = &graphs["crate"];
    assert!(top["analysis"].contains("setup") && top["setup"].contains("mesh"), "{top:?}");
    assert!(top["setup"].contains("input"), "setup reads input: {top:?}");
    let setup = &graphs["setup"];
    assert!(setup["bodies"].contains("sections") && setup["contacts"].contains("overlap"), "{setup:?}");
    // the layering ARCHITECTURE.md describes: input does not read the set-up
    // model, the set-up model does not read results
    let breaches = layer_breaches(top);
    assert!(breaches.is_empty(), "{}", breaches.join("\n"));
    let mut found = Vec::new();
    for (name, root, sources) in &crates {
        found.extend(all_cycles(&import_graphs(sources)).into_iter().map(|c| format!("{name} {root} {c}")));
    }
    assert!(found.is_empty(), "import cycles:\n{}", found.join("\n"));
}

/// The layering: `(lower, higher)`, the lower module never reads the higher.
const LAYERS: &[(&str, &str)] = &[
    ("input", "setup"),
    ("input", "analysis"),
    ("input", "post"),
    ("setup", "post"),
    ("setup", "analysis"),
    ("values", "elements"),
    ("solver", "analysis"),
];

/// The [`LAYERS`] rules the top-level graph `top` breaks.
fn layer_breaches(top: &Graph) -> Vec<String> {
    LAYERS
        .iter()
        .filter(|(low, high)| top.get(*low).is_some_and(|d| d.contains(*high)))
        .map(|(low, high)| format!("{low} depends on {high}"))
        .collect()
}

/// An `input` file naming `setup` (through an inline path) breaks the
/// layering; `setup` reading `input` does not.
#[test]
fn input_reading_setup_is_caught() {
    let sources = fake(&[
        ("lib.rs", &[], "pub mod input; pub mod setup;"),
        ("input/mod.rs", &["input"], "pub fn read() -> usize { crate::setup::Model::size() }"),
        ("setup/mod.rs", &["setup"], "use crate::input::read;\npub struct Model;"),
    ]);
    let graphs = import_graphs(&sources);
    assert_eq!(layer_breaches(&graphs["crate"]), ["input depends on setup"]);
    let fine = fake(&[
        ("lib.rs", &[], "pub mod input; pub mod setup;"),
        ("input/mod.rs", &["input"], "pub fn read() -> usize { 0 }"),
        ("setup/mod.rs", &["setup"], "use crate::input::read;\npub struct Model;"),
    ]);
    assert!(layer_breaches(&import_graphs(&fine)["crate"]).is_empty());
}

/// Sources written for a test: `(file, module path, text)`.
fn fake(files: &[(&str, &[&str], &str)]) -> Vec<Source> {
    files
        .iter()
        .map(|(file, module, text)| Source {
            file: file.to_string(),
            module: module.iter().map(|s| s.to_string()).collect(),
            test: false,
            lines: text.lines().count(),
            ast: parse(file, text),
        })
        .collect()
}

/// Two modules naming each other — through a `use` and through a path in
/// a macro call — are a cycle; a path is followed through a name a `use`
/// brought in; a test module's reading is not an edge.
#[test]
fn an_import_cycle_is_caught() {
    let sources = fake(&[
        ("lib.rs", &[], "pub mod a; pub mod b; pub mod c;"),
        ("a.rs", &["a"], "use crate::b::Thing;\npub fn f(_: Thing) {}"),
        ("b.rs", &["b"], "pub struct Thing;\npub fn g() { assert!(crate::a::ok()); }"),
        ("c/mod.rs", &["c"], "mod x; mod y;"),
        ("c/x.rs", &["c", "x"], "use crate::c;\npub fn h() -> usize { c::y::z::depth() }"),
        ("c/y/mod.rs", &["c", "y"], "pub mod z;\n#[cfg(test)]\nmod tests { use super::super::x; }"),
        ("c/y/z.rs", &["c", "y", "z"], "pub fn depth() -> usize { 0 }"),
    ]);
    let graphs = import_graphs(&sources);
    assert_eq!(graphs["crate"]["a"], BTreeSet::from(["b".to_string()]));
    assert_eq!(graphs["crate"]["b"], BTreeSet::from(["a".to_string()]));
    assert_eq!(all_cycles(&graphs), ["crate: a → b → a"]);
    // `c::y::z::depth` is followed through `use crate::c` to the file c/y/z.rs
    assert_eq!(graphs["c"]["x"], BTreeSet::from(["y".to_string()]));
    assert!(!graphs["c"].contains_key("y"), "the test module's `use` is not an edge: {:?}", graphs["c"]);
}

/// The path reader on the forms the sources use.
#[test]
fn paths_are_read_from_use_groups_inline_paths_and_macros() {
    let sources = fake(&[(
        "setup/bodies.rs",
        &["setup", "bodies"],
        "use super::{bounds, schema::*, validate::{count, division as div}};\n// use super::comment\n\
         fn f() { let s = \"super::string\"; let x = super::contacts::overlap(a); div(); }\n\
         use crate::setup::{\n    sections::check,\n};\nfn g() { println!(\"{}\", super::super::mesh::size()); }\n",
    )]);
    let names = Names::of(&sources[0]);
    let got: BTreeSet<String> =
        names.written.iter().filter_map(|(m, w)| resolve(&names, m, w, 0)).map(|p| p.join("::")).collect();
    let want = [
        "setup::bounds",
        "setup::schema",
        "setup::validate::count",
        "setup::validate::division", // the call `div()` too
        "setup::contacts::overlap",
        "setup::sections::check",
        "mesh::size", // in a macro call
    ];
    assert_eq!(got, want.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>());
}

// -------------------------------------------------------------- functions

/// Every function of a file (`fn` items, methods, associated and default
/// trait functions, nested ones): `(name, line of its `fn`, lines from
/// its `fn` keyword to its closing brace)`.
#[derive(Default)]
struct Functions(Vec<(String, usize, usize)>);

impl Functions {
    fn add(&mut self, sig: &syn::Signature, body: &syn::Block) {
        let first = sig.fn_token.span.start().line;
        let last = body.brace_token.span.close().end().line;
        self.0.push((sig.ident.to_string(), first, last - first + 1));
    }
}

impl<'ast> Visit<'ast> for Functions {
    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        self.add(&f.sig, &f.block);
        visit::visit_item_fn(self, f);
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.add(&f.sig, &f.block);
        visit::visit_impl_item_fn(self, f);
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if let Some(body) = &f.default {
            self.add(&f.sig, body);
        }
        visit::visit_trait_item_fn(self, f);
    }
}

/// Every function of `sources`: `(file:line name, lines)`.
fn function_lengths(sources: &[Source]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for s in sources {
        let mut fns = Functions::default();
        fns.visit_file(&s.ast);
        out.extend(fns.0.into_iter().map(|(name, line, n)| (format!("{}:{line} {name}", s.file), n)));
    }
    out
}

/// No function in `src/` is over 120 lines: a longer one does more than one
/// job. (No exception today; one would be listed here with its reason.)
#[test]
fn no_function_is_over_120_lines() {
    let all: Vec<(String, usize)> = crates().iter().flat_map(|c| function_lengths(&c.2)).collect();
    let long: Vec<&(String, usize)> = all.iter().filter(|(_, n)| *n > MAX_FN_LINES).collect();
    assert!(long.is_empty(), "split these by concept: {long:?}");
    // the measure itself: GMRES (about 100 lines, nested loops) is found
    // whole, and so is a function with an array type in its signature
    let find = |file: &str, name: &str| {
        all.iter().find(|(f, _)| f.starts_with(&format!("{file}:")) && f.ends_with(&format!(" {name}"))).map(|p| p.1)
    };
    let gmres = find("solver/krylov.rs", "gmres");
    assert!(gmres.is_some_and(|n| (80..=MAX_FN_LINES).contains(&n)), "{gmres:?} among {} functions", all.len());
    let overlaps = find("mesh/overlaps.rs", "first_overlap"); // `quads: &[[usize; 4]]`
    assert!(overlaps.is_some_and(|n| (30..=60).contains(&n)), "{overlaps:?}");
}

/// A 121-line function whose signature holds `[f64; 3]` is found with its
/// length, as a method, an associated function, a default trait method and
/// a nested function; 120 lines pass.
#[test]
fn a_long_function_is_caught() {
    let body = |n: usize| "    let _x = 1;\n".repeat(n - 3);
    let text = format!(
        "fn free(a: [f64; 3]) -> [f64; 3] {{\n{}    a\n}}\n\
         struct S;\nimpl S {{\n    fn method(&self, b: &[[usize; 4]]) {{\n{}    }}\n    fn assoc() -> [u8; 2] {{\n{}    [0; 2]\n}}\n}}\n\
         trait T {{\n    fn required(c: [f64; 3]);\n    fn provided(c: [f64; 3]) {{\n{}    }}\n}}\n\
         fn outer() {{\n    fn inner(d: [i32; 1]) {{\n{}    }}\n}}\n\
         fn fits(e: [f64; 3]) {{\n{}    let _e = e;\n}}\n",
        body(121),
        body(122),
        body(121),
        body(122),
        body(122),
        body(120),
    );
    let sources = fake(&[("fake.rs", &[], text.as_str())]);
    let found: BTreeMap<String, usize> =
        function_lengths(&sources).into_iter().map(|(f, n)| (f.rsplit(' ').next().unwrap().to_string(), n)).collect();
    let long: BTreeSet<&str> = found.iter().filter(|(_, n)| **n > MAX_FN_LINES).map(|(f, _)| f.as_str()).collect();
    assert_eq!(found["free"], 121);
    // `outer` holds the 121-line `inner`
    assert_eq!(long, BTreeSet::from(["free", "method", "assoc", "provided", "outer", "inner"]), "{found:?}");
    assert_eq!(found["fits"], 120);
    assert!(!found.contains_key("required"));
}

// ------------------------------------------------------------------ files

/// What is wrong with the long files: `files` are `(path, lines)`, `listed`
/// the reviewed outliers `(path, reason)`.
fn long_file_review(files: &[(String, usize)], listed: &[(&str, &str)]) -> Vec<String> {
    let mut problems = Vec::new();
    for (f, n) in files {
        if *n > LONG_FILE_LINES && !listed.iter().any(|(l, _)| l == f) {
            problems.push(format!(
                "{f} has {n} lines: split it by concept, or list it in LONG_FILES with why it is one idea"
            ));
        }
    }
    for (l, reason) in listed {
        match files.iter().find(|(f, _)| f == l) {
            None => problems.push(format!("{l} is listed in LONG_FILES but does not exist: remove it")),
            Some((_, n)) if *n <= LONG_FILE_LINES => {
                problems.push(format!("{l} has {n} lines, no longer over {LONG_FILE_LINES}: remove it from LONG_FILES"))
            }
            Some(_) if reason.trim().is_empty() => {
                problems.push(format!("{l} is listed in LONG_FILES without a reason"))
            }
            Some(_) => {}
        }
    }
    problems
}

#[test]
fn long_files_are_listed_with_a_reason() {
    let files: Vec<(String, usize)> = crates().iter().flat_map(|c| &c.2).map(|s| (s.file.clone(), s.lines)).collect();
    let problems = long_file_review(&files, LONG_FILES);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// An unlisted long file, a listed file that shrank, one that is gone and
/// one without a reason each fail; a listed long file passes.
#[test]
fn an_unreviewed_long_file_is_caught() {
    let files = [("a.rs".to_string(), 601), ("b.rs".to_string(), 600), ("c.rs".to_string(), 700), ("d.rs".into(), 650)];
    let listed = [("b.rs", "one idea"), ("c.rs", "one idea"), ("gone.rs", "one idea"), ("d.rs", " ")];
    let problems = long_file_review(&files, &listed);
    assert_eq!(problems.len(), 4, "{problems:#?}");
    for (p, file) in problems.iter().zip(["a.rs has 601", "b.rs has 600", "gone.rs", "d.rs"]) {
        assert!(p.starts_with(file), "{p}");
    }
    assert!(long_file_review(&files[2..3], &listed[1..2]).is_empty());
}

/// The modules of every crate that ARCHITECTURE.md does not name in a code
/// span: the map must show every room of the house.
fn unnamed_modules(crates: &[(String, &'static str, Vec<Source>)], map: &str) -> Vec<String> {
    let mut missing = BTreeSet::new();
    for (name, _, sources) in crates {
        for s in sources.iter().filter(|s| s.module.len() == 1 && !s.test) {
            if !map.contains(&format!("`{}`", s.module[0])) {
                missing.insert(format!("{name}: `{}`", s.module[0]));
            }
        }
    }
    missing.into_iter().collect()
}

#[test]
fn architecture_md_names_every_module() {
    let map = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let crates = crates();
    let missing = unnamed_modules(&crates, &map);
    assert!(missing.is_empty(), "ARCHITECTURE.md does not name: {}", missing.join(", "));
    // the check reads what it should: a map without the solver is caught
    let without = map.replace("`solver`", "solver");
    assert_eq!(unnamed_modules(&crates, &without), ["cufem: `solver`"]);
}

// ------------------------------------------------------------- structure

/// The most named fields `struct Structure` may have (issue 47: it holds
/// parts, not state of its own).
const MAX_STRUCTURE_FIELDS: usize = 10;

/// Every `struct name` of `sources` (test items included): `(file, its
/// named fields)`.
fn struct_fields(sources: &[Source], name: &str) -> Vec<(String, Vec<String>)> {
    struct Find<'n>(&'n str, Vec<Vec<String>>);
    impl<'ast> Visit<'ast> for Find<'_> {
        fn visit_item_struct(&mut self, s: &'ast syn::ItemStruct) {
            if s.ident == self.0 {
                self.1.push(s.fields.iter().filter_map(|f| f.ident.as_ref().map(|i| i.to_string())).collect());
            }
            visit::visit_item_struct(self, s);
        }
    }
    let mut out = Vec::new();
    for s in sources {
        let mut find = Find(name, Vec::new());
        find.visit_file(&s.ast);
        out.extend(find.1.into_iter().map(|fields| (s.file.clone(), fields)));
    }
    out
}

/// What is wrong with the `Structure`s found: none, several, or one with
/// more than [`MAX_STRUCTURE_FIELDS`] fields.
fn structure_review(found: &[(String, Vec<String>)]) -> Vec<String> {
    match found {
        [] => vec!["no `struct Structure` found".to_string()],
        [(file, fields)] if fields.len() > MAX_STRUCTURE_FIELDS => vec![format!(
            "{file}: Structure has {} fields (at most {MAX_STRUCTURE_FIELDS}): group them into parts: {fields:?}",
            fields.len()
        )],
        [_] => Vec::new(),
        several => vec![format!("several `struct Structure`: {:?}", several.iter().map(|f| &f.0).collect::<Vec<_>>())],
    }
}

#[test]
fn the_structure_holds_at_most_ten_fields() {
    let crates = crates();
    let found = struct_fields(core_library(&crates), "Structure");
    let problems = structure_review(&found);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // the check reads what it should: the analysis's structure, its parts named
    assert_eq!(found[0].0, "analysis/structure.rs");
    assert!(found[0].1.iter().any(|f| f == "parts"), "{found:?}");
}

/// A `Structure` of 11 named fields fails, one of 10 passes; a tuple
/// struct's fields and another struct's are not counted.
#[test]
fn an_eleventh_structure_field_is_caught() {
    let structure = |n: usize| {
        let fields: String = (0..n).map(|i| format!("    f{i}: usize,\n")).collect();
        format!("pub struct Structure {{\n{fields}}}\nstruct Other {{ a: u8, b: u8 }}\nstruct Pair(u8, u8);\n")
    };
    let eleven = fake(&[("analysis/structure.rs", &["analysis", "structure"], structure(11).as_str())]);
    let found = struct_fields(&eleven, "Structure");
    assert_eq!(found[0].1.len(), 11);
    let problems = structure_review(&found);
    assert!(problems.len() == 1 && problems[0].contains("Structure has 11 fields"), "{problems:?}");
    let ten = fake(&[("analysis/structure.rs", &["analysis", "structure"], structure(10).as_str())]);
    assert!(structure_review(&struct_fields(&ten, "Structure")).is_empty());
    assert_eq!(structure_review(&struct_fields(&ten, "Missing")), ["no `struct Structure` found"]);
}

// ---------------------------------------------------------- public surface

/// Top-level modules of the core that are `pub(crate)` as a whole: their
/// `pub` reaches no further than the crate.
const CRATE_PRIVATE_MODULES: &[&str] = &["assembly", "elements", "interfaces", "kinematics"];

/// `pub` items of the core no outside code names and no public signature
/// exposes, kept for a reason the word test cannot see: `(file, name, why)`.
const PUBLIC_BY_REVIEW: &[(&str, &str, &str)] = &[
    ("solver/newton.rs", "divergence_ratio", "struct update `..*settings` (tests) needs every field visible"),
    ("solver/newton.rs", "stagnation_iterations", "struct update `..*settings` (tests) needs every field visible"),
    ("solver/newton.rs", "line_search", "struct update `..*settings` (tests) needs every field visible"),
    ("damage/mod.rs", "to_array", "unused: src/damage is being reworked on another branch"),
    ("materials/damage.rs", "MODES", "the order `damage::Strengths::to_array` documents"),
];

/// A `pub` item (or field, or re-export) of the core: where, its name, and
/// the identifiers its public face names (a function's signature, a
/// field's type, an enum's or trait's whole body, a type's generics).
struct PubItem {
    file: String,
    name: String,
    face: BTreeSet<String>,
}

/// Every identifier under a syntax node.
#[derive(Default)]
struct Idents(BTreeSet<String>);

impl<'ast> Visit<'ast> for Idents {
    fn visit_ident(&mut self, i: &'ast proc_macro2::Ident) {
        self.0.insert(i.to_string());
    }
}

fn idents(visit: impl FnOnce(&mut Idents)) -> BTreeSet<String> {
    let mut found = Idents::default();
    visit(&mut found);
    found.0
}

/// The leaf names a `use` tree brings in (`a::{b, c as d}` → b, d); `*` → none.
fn use_leaves(tree: &syn::UseTree, out: &mut Vec<String>) {
    match tree {
        syn::UseTree::Path(p) => use_leaves(&p.tree, out),
        syn::UseTree::Name(n) => out.push(n.ident.to_string()),
        syn::UseTree::Rename(r) => out.push(r.rename.to_string()),
        syn::UseTree::Glob(_) => {}
        syn::UseTree::Group(g) => g.items.iter().for_each(|t| use_leaves(t, out)),
    }
}

/// Collects the plain-`pub` items of a list of items (inline modules and
/// `impl` blocks entered; `#[cfg(test)]` items skipped).
fn pub_items(file: &str, items: &[syn::Item], out: &mut Vec<PubItem>) {
    use syn::{Item, Visibility::Public};
    let mut found = Vec::new();
    let mut add = |name: String, face: BTreeSet<String>| found.push((name, face));
    let mut fields = Vec::new();
    for item in items.iter().filter(|i| !is_test(item_attributes(i))) {
        match item {
            Item::Fn(f) if matches!(f.vis, Public(_)) => {
                add(f.sig.ident.to_string(), idents(|v| v.visit_signature(&f.sig)))
            }
            Item::Struct(s) => {
                if matches!(s.vis, Public(_)) {
                    add(s.ident.to_string(), idents(|v| v.visit_generics(&s.generics)));
                }
                fields.extend(s.fields.iter().filter(|f| matches!(f.vis, Public(_))).cloned());
            }
            Item::Enum(e) if matches!(e.vis, Public(_)) => add(e.ident.to_string(), idents(|v| v.visit_item_enum(e))),
            Item::Trait(t) if matches!(t.vis, Public(_)) => add(t.ident.to_string(), idents(|v| v.visit_item_trait(t))),
            Item::Type(t) if matches!(t.vis, Public(_)) => add(t.ident.to_string(), idents(|v| v.visit_item_type(t))),
            Item::Const(c) if matches!(c.vis, Public(_)) => add(c.ident.to_string(), idents(|v| v.visit_type(&c.ty))),
            Item::Static(s) if matches!(s.vis, Public(_)) => add(s.ident.to_string(), idents(|v| v.visit_type(&s.ty))),
            Item::Mod(m) if matches!(m.vis, Public(_)) => add(m.ident.to_string(), BTreeSet::new()),
            Item::Use(u) if matches!(u.vis, Public(_)) => {
                let mut leaves = Vec::new();
                use_leaves(&u.tree, &mut leaves);
                // a re-export stands for what it names: public if one of them is
                for leaf in leaves {
                    add(leaf.clone(), BTreeSet::from([leaf]));
                }
            }
            Item::Impl(i) => {
                for it in &i.items {
                    match it {
                        syn::ImplItem::Fn(f) if matches!(f.vis, Public(_)) && !is_test(&f.attrs) => {
                            add(f.sig.ident.to_string(), idents(|v| v.visit_signature(&f.sig)))
                        }
                        syn::ImplItem::Const(c) if matches!(c.vis, Public(_)) => {
                            add(c.ident.to_string(), idents(|v| v.visit_type(&c.ty)))
                        }
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }
    for f in fields {
        // a public tuple field is its struct's face: listed with no name of its own
        found.push((f.ident.as_ref().map(|i| i.to_string()).unwrap_or_default(), idents(|v| v.visit_type(&f.ty))));
    }
    out.extend(found.into_iter().map(|(name, face)| PubItem { file: file.to_string(), name, face }));
    for item in items.iter().filter(|i| !is_test(item_attributes(i))) {
        if let syn::Item::Mod(m) = item
            && let Some((_, inner)) = &m.content
        {
            pub_items(file, inner, out);
        }
    }
}

/// Every identifier of the code outside the core — the other crates, their
/// tests, the integration tests, the Python package — and of the core's
/// doc-comment code blocks (the doc examples).
fn outside_words() -> BTreeSet<String> {
    fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                rust_files(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let words = |text: &str, out: &mut BTreeSet<String>| {
        out.extend(
            text.split(|c: char| !(c.is_alphanumeric() || c == '_')).filter(|w| !w.is_empty()).map(String::from),
        );
    };
    let mut files = Vec::new();
    for dir in ["tests", "python/src", "crates"] {
        rust_files(&root().join(dir), &mut files);
    }
    let mut out = BTreeSet::new();
    for f in &files {
        words(&std::fs::read_to_string(f).unwrap(), &mut out);
    }
    let mut core = Vec::new();
    rust_files(&root().join("src"), &mut core);
    for f in &core {
        let mut example = false;
        for line in std::fs::read_to_string(f).unwrap().lines() {
            let doc = line.trim_start().strip_prefix("///").or_else(|| line.trim_start().strip_prefix("//!"));
            match doc {
                Some(d) if d.trim_start().starts_with("```") => example = !example,
                Some(d) if example => words(d, &mut out),
                _ => {}
            }
        }
    }
    out
}

/// The `pub` items of `items` that nothing outside names (`outside`) and
/// no public face of a named item exposes, nor [`PUBLIC_BY_REVIEW`] lists:
/// `file: name`. Named items' faces are followed to a fixed point (a named
/// function returns a type, whose public fields name another…).
fn surface_candidates(items: &[PubItem], outside: &BTreeSet<String>) -> Vec<String> {
    let mut public = outside.clone();
    let mut grew = true;
    while grew {
        grew = false;
        for item in items {
            if item.name.is_empty() || public.contains(&item.name) {
                for word in &item.face {
                    grew |= public.insert(word.clone());
                }
            }
        }
    }
    let reviewed = |i: &PubItem| PUBLIC_BY_REVIEW.iter().any(|(f, n, _)| *f == i.file && *n == i.name);
    let mut out: Vec<String> = items
        .iter()
        .filter(|i| !i.name.is_empty() && !public.contains(&i.name) && !reviewed(i))
        .map(|i| format!("{}: {}", i.file, i.name))
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The `pub` items of the core's public modules (`#[cfg(test)]` files out).
fn core_pub_items(sources: &[Source]) -> Vec<PubItem> {
    let mut items = Vec::new();
    for s in sources.iter().filter(|s| !s.test) {
        if s.module.first().is_some_and(|m| CRATE_PRIVATE_MODULES.contains(&m.as_str())) {
            continue;
        }
        pub_items(&s.file, &s.ast.items, &mut items);
    }
    items
}

/// ARCHITECTURE.md: an item of the core is `pub` only if the other crates,
/// the Python package, the integration tests or the doc examples name it,
/// or a public face of such an item exposes it; the rest is `pub(crate)`.
/// The same check as `python3 bench/public_surface.py --check`.
#[test]
fn public_items_are_named_outside() {
    let crates = crates();
    let items = core_pub_items(core_library(&crates));
    let found = surface_candidates(&items, &outside_words());
    assert!(
        found.is_empty(),
        "pub items of the core that nothing outside names (make them pub(crate), or list them in \
         PUBLIC_BY_REVIEW with the reason):\n{}",
        found.join("\n")
    );
    // the check reads what it should: the root's nouns, a field and a method are seen
    for name in ["Model", "run", "write_results", "failure", "reaction"] {
        assert!(items.iter().any(|i| i.name == name), "{name} not found");
    }
}

/// An unnamed `pub fn`, field, method and re-export (and the item it
/// re-exports) are caught; a type a named function returns, the type of a
/// named public field, and items `pub(crate)` or in a test module are not.
#[test]
fn an_unnamed_pub_item_is_caught() {
    let sources = fake(&[(
        "a.rs",
        &["a"],
        "pub fn named() -> Out { Out { inner: Inner, hidden: 0 } }\n\
         pub struct Out { pub inner: Inner, pub hidden: u8 }\n\
         pub struct Inner;\n\
         pub fn unnamed() {}\n\
         pub(crate) fn quiet() {}\n\
         mod m { pub struct Kept; }\n\
         pub use m::Kept;\n\
         impl Out { pub fn method(&self) {} pub fn touched(&self) {} }\n\
         #[cfg(test)] mod tests { pub fn helper() {} }\n",
    )]);
    let outside = BTreeSet::from(["named", "touched", "inner"].map(String::from));
    let found = surface_candidates(&core_pub_items(&sources), &outside);
    assert_eq!(found, ["a.rs: Kept", "a.rs: hidden", "a.rs: method", "a.rs: unnamed"].map(String::from));
}
