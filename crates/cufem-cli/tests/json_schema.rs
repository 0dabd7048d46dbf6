//! `cufem schema` prints the model file's JSON Schema (draft 7), derived
//! from the reader's own types: every shipped model file is valid against
//! it as printed, checked with an independent validator (the `jsonschema`
//! crate, on the TOML read into JSON as an editor's TOML plug-in does),
//! and a file that the reader refuses for a misspelt key, a wrong type, a
//! key of another variant or a number out of its range is refused by the
//! schema too.

use std::path::{Path, PathBuf};
use std::process::Command;

use cufem::setup::{Limits, Model};
use serde_json::Value;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The schema as `cufem schema` prints it.
fn printed_schema() -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_cufem")).arg("schema").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("cufem schema prints JSON")
}

fn validator() -> jsonschema::Validator {
    jsonschema::validator_for(&printed_schema()).expect("the printed schema compiles")
}

/// A model file's TOML as JSON.
fn json(text: &str) -> Value {
    let value: toml::Value = toml::from_str(text).unwrap();
    serde_json::to_value(value).unwrap()
}

/// The schema's complaints about `text`, one line each (location: message).
fn complaints(validator: &jsonschema::Validator, text: &str) -> Vec<String> {
    let instance = json(text);
    validator.iter_errors(&instance).map(|e| format!("{}: {e}", e.instance_path())).collect()
}

/// The shipped model files: examples/*.toml and bench/*.toml.
fn shipped() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["examples", "bench"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn the_printed_schema_is_a_draft_7_schema() {
    let schema = printed_schema();
    assert_eq!(schema["$schema"], "http://json-schema.org/draft-07/schema#");
    assert!(jsonschema::meta::is_valid(&schema), "not a valid draft-07 schema");
    // the reader refuses unknown keys: so does the schema, at the top and in every table
    assert_eq!(schema["additionalProperties"], false);
    assert_eq!(schema["definitions"]["SolverFile"]["additionalProperties"], false);
    // descriptions are the keys' doc comments
    let description = schema["definitions"]["MaterialFile"]["properties"]["young_modulus"]["description"].as_str();
    assert_eq!(description, Some("Isotropic: Young's modulus E (Pa)."));
}

#[test]
fn every_shipped_model_file_is_valid_against_the_printed_schema() {
    let validator = validator();
    let files = shipped();
    assert!(files.len() >= 38, "{} model files found", files.len());
    let mut bad = Vec::new();
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        for c in complaints(&validator, &text) {
            bad.push(format!("{}: {c}", path.strip_prefix(root()).unwrap().display()));
        }
    }
    assert!(bad.is_empty(), "{} complaints:\n{}", bad.len(), bad.join("\n"));
}

/// `text` with the first `from` replaced by `to` (which must be there).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the model");
    text.replacen(from, to, 1)
}

#[test]
fn a_file_the_reader_refuses_is_refused_by_the_schema() {
    let validator = validator();
    let block = std::fs::read_to_string(root().join("examples/block_indentation.toml")).unwrap();
    let contact = std::fs::read_to_string(root().join("examples/cantilevers_contact.toml")).unwrap();
    // (model, what the reader's message names, what the schema's names)
    let cases = [
        // a misspelt key, in a table and at the top
        (edit(&block, "young_modulus", "youngs_modulus"), "youngs_modulus", "youngs_modulus"),
        (edit(&block, "[solver]", "[solvers]"), "solvers", "solvers"),
        // a wrong type: a number written as a string, a point with two coordinates
        (edit(&block, "young_modulus = 70e9", "young_modulus = \"70e9\""), "young_modulus", "/young_modulus"),
        (edit(&block, "point = [0.2, 0.05, 0.3]", "point = [0.2, 0.05]"), "length 2", "/point"),
        // a word outside its list
        (edit(&block, "normal = \"-z\"", "normal = \"down\""), "down", "/indenters/0"),
        // a key of another variant: a radius on a flat punch
        (edit(&block, "position = 0.3", "position = 0.3\nradius = 0.1"), "radius", "/indenters/0"),
        // a required key left out
        (edit(&block, "name = \"alloy\"\n", ""), "name", "/materials/0"),
        // numbers out of the ranges the reader checks (src/input/ranges.rs)
        (edit(&block, "poisson_ratio = 0.3", "poisson_ratio = 0.5"), "poisson_ratio", "/poisson_ratio"),
        (edit(&block, "young_modulus = 70e9", "young_modulus = 70.0"), "young_modulus", "/young_modulus"),
        (edit(&block, "increments = 20", "increments = 0"), "solver.increments", "/solver/increments"),
        (edit(&block, "increments = 20", "increments = 20\ncutback_factor = 1.0"), "cutback_factor", "/cutback_factor"),
        // (inside a table of variants the validator names the table whose branches all fail)
        (edit(&block, "elements = 6, ratio = 0.3 }", "elements = 6, ratio = 2e4 }"), "ratio", "/bodies/0/section"),
        (edit(&block, "points = 201", "points = 1"), "points", "/lines/0/points"),
        (edit(&contact, "[[contacts]]", "[[contacts]]\nfriction = 11.0"), "friction", "/contacts/0"),
    ];
    for (text, reader_names, schema_names) in cases {
        let Err(refused) = Model::parse_with(&text, Limits::none()) else {
            panic!("the reader accepted what its message should name: {reader_names:?}")
        };
        let refused = refused.to_string();
        assert!(refused.contains(reader_names), "the reader's message does not name {reader_names:?}: {refused}");
        let said = complaints(&validator, &text);
        assert!(!said.is_empty(), "the schema accepted what the reader refused ({refused})");
        assert!(said.iter().any(|c| c.contains(schema_names)), "{schema_names:?} not in {said:?}");
    }
}

#[test]
fn the_variant_chosen_and_the_defaulted_tag_are_followed() {
    let validator = validator();
    let contact = std::fs::read_to_string(root().join("examples/cantilevers_contact.toml")).unwrap();
    // a contact without `method` is node-to-node, which takes `tolerance`
    assert!(!contact.contains("method"));
    let text = edit(&contact, "[[contacts]]", "[[contacts]]\ntolerance = 1e-6");
    assert!(complaints(&validator, &text).is_empty());
    Model::parse_with(&text, Limits::none()).unwrap();
    // …and not `search_distance`, which is the surface method's
    let text = edit(&contact, "[[contacts]]", "[[contacts]]\nsearch_distance = 1e-3");
    assert!(!complaints(&validator, &text).is_empty());
    assert!(Model::parse_with(&text, Limits::none()).is_err());
    let text = edit(&contact, "[[contacts]]", "[[contacts]]\nmethod = \"surface\"\nsearch_distance = 1e-3");
    assert!(complaints(&validator, &text).is_empty(), "{:?}", complaints(&validator, &text));
}
