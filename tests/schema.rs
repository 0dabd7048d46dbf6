//! The model schema is typed: a misspelt word (a hardening law, a section
//! shape, a contact method, an indenter shape or method, a small setting)
//! or a key that the chosen variant does not have is refused by the TOML
//! reader, and the message `cufem` prints keeps the model file's line and
//! the list of what is allowed there.

use std::path::PathBuf;

use cufem::setup::{Limits, Model, ModelError};

fn example(name: &str) -> String {
    std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).unwrap()
}

/// `text` with the first `from` replaced by `to` (which must be there).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the example");
    text.replacen(from, to, 1)
}

/// The 1-based line of the first occurrence of `marker` in `text`.
fn line_of(text: &str, marker: &str) -> usize {
    let at = text.find(marker).unwrap_or_else(|| panic!("{marker:?} is not in the text"));
    text[..at].matches('\n').count() + 1
}

/// The model is refused by the reader at line `line`, with all of `needles`
/// in the message; returns the message as `cufem` prints it.
fn refused(text: &str, line: usize, needles: &[&str]) -> String {
    let Err(e) = Model::parse_with(text, Limits::none()) else { panic!("the model was accepted") };
    assert!(matches!(e, ModelError::Parse(_)), "not a parser error: {e}");
    let printed = e.to_string();
    assert!(printed.starts_with(&format!("model file: TOML parse error at line {line}, column ")), "{printed}");
    for n in needles {
        assert!(printed.contains(n), "{n:?} not in:\n{printed}");
    }
    printed
}

#[test]
fn a_misspelt_hardening_law_is_refused_with_its_line_and_the_laws() {
    let text = edit(&example("cantilevers_contact.toml"), "hardening = \"perfect\"", "hardening = \"perfekt\"");
    refused(
        &text,
        line_of(&text, "perfekt"),
        &["unknown variant `perfekt`, expected one of `perfect`, `linear`, `table`, `voce`"],
    );
    // a key of another law: the keys of the law given are listed
    let text = edit(
        &example("cantilevers_contact.toml"),
        "hardening = \"perfect\" }",
        "hardening = \"perfect\", hardening_modulus = 1e9 }",
    );
    refused(
        &text,
        line_of(&text, "plasticity ="),
        &["unknown field `hardening_modulus`, expected `yield_stress` or `kinematic`"],
    );
    let text = edit(&example("bending_compact_4L9.toml"), "hardening = \"table\"", "hardening = \"voce\"");
    refused(&text, line_of(&text, "[materials.plasticity]"), &["unknown field `table`, expected one of"]);
    // a bad row of the table is reported with the key
    let text = edit(&example("bending_compact_4L9.toml"), "[0.002, 44.7e6]", "[0.002, 44.7e6, 7.0]");
    refused(
        &text,
        line_of(&text, "[materials.plasticity]"),
        &["materials[0].plasticity.table: invalid length 3, expected an array of length 2"],
    );
}

#[test]
fn a_misspelt_section_shape_is_refused_with_its_line_and_the_shapes() {
    let text = edit(&example("cantilevers_contact.toml"), "shape = \"rectangle\"", "shape = \"rectangel\"");
    refused(
        &text,
        line_of(&text, "rectangel"),
        &["unknown variant `rectangel`, expected one of `rectangle`, `tube`, `quads`, `i_beam`, `channel`, \
           `z_section`, `angle`, `hat`, `box`, `circular_tube`, `circle`, `gmsh`"],
    );
    // a key of another shape: the keys of this one are listed
    let text = edit(&example("bending_tube_20L9.toml"), "around = 20 }", "around = 20, web_thickness = 0.002 }");
    refused(
        &text,
        line_of(&text, "section ="),
        &["unknown field `web_thickness`, expected one of `element`, `origin`, `width`, `height`, `thickness`, \
           `around`, `along_x`, `along_z`, `through`"],
    );
    // and the shapes that have it (a new user wrote a laminate's
    // `interfaces` in a rectangle and was told the rectangle's keys alone)
    refused(
        &text,
        line_of(&text, "section ="),
        &["(a key of shape = \"i_beam\", shape = \"channel\", shape = \"z_section\", shape = \"angle\", \
           shape = \"hat\", shape = \"box\")"],
    );
    // a bad value in a shape's own key is reported with the key
    let text = edit(&example("bending_tube_20L9.toml"), "around = 20 }", "around = \"twenty\" }");
    refused(
        &text,
        line_of(&text, "section ="),
        &["bodies[0].section.around: invalid type: text \"twenty\", expected a whole number, 0 or more"],
    );
    // the element is a word too
    let text = edit(&example("bending_tube_20L9.toml"), "element = \"L9\"", "element = \"Q9\"");
    refused(&text, line_of(&text, "section ="), &["unknown variant `Q9`, expected one of `L4`, `L9`, `L16`"]);
}

#[test]
fn a_misspelt_contact_method_is_refused_with_its_line_and_the_methods() {
    let base = example("cantilevers_contact.toml");
    let slave = "slave = { body = \"upper\", where = { z = 0.0254 } }\n";
    let text = edit(&base, slave, &format!("{slave}method = \"surfce\"\n"));
    refused(
        &text,
        line_of(&text, "method = \"surfce\""),
        &["unknown variant `surfce`, expected `node_to_node` or `surface`"],
    );
    // each method has its own keys: search_distance belongs to "surface",
    // tolerance and pairs to "node_to_node" (the default)
    let text = edit(&base, slave, &format!("{slave}search_distance = 0.01\n"));
    refused(
        &text,
        line_of(&text, "[[contacts]]"),
        &[
            "unknown field `search_distance`, expected one of `name`, `master`, `slave`",
            "`tolerance`, `pairs`",
            "(a key of method = \"surface\")",
        ],
    );
    let text = edit(&base, slave, &format!("{slave}method = \"surface\"\ntolerance = 1e-6\n"));
    refused(&text, line_of(&text, "[[contacts]]"), &["unknown field `tolerance`", "`search_distance`"]);
    // another key's mistake in a contact is still reported, at the table,
    // with its key (serde's buffered tables alone lose the key's name)
    let text = edit(&base, slave, &format!("{slave}penalty_factor = \"high\"\n"));
    refused(
        &text,
        line_of(&text, "[[contacts]]"),
        &["contacts[0].penalty_factor: invalid type: text \"high\", expected a number"],
    );
    // no method: node-to-node, as before
    let model = Model::parse_with(&base, Limits::none()).unwrap();
    assert!(model.contacts[0].surface.is_none() && !model.contacts[0].pairs.is_empty());
    let surface = edit(&base, slave, &format!("{slave}method = \"surface\"\n"));
    assert!(Model::parse_with(&surface, Limits::none()).unwrap().contacts[0].surface.is_some());
}

#[test]
fn a_misspelt_indenter_shape_or_method_is_refused_with_its_line_and_the_choices() {
    let base = example("cantilevers_contact.toml");
    let text = edit(&base, "shape = \"cylinder\"", "shape = \"cilinder\"");
    refused(
        &text,
        line_of(&text, "cilinder"),
        &["unknown variant `cilinder`, expected one of `flat`, `cylinder`, `sphere`"],
    );
    // a key of another shape: the keys of a cylinder are listed
    let text = edit(&base, "axis = \"x\"\n", "axis = \"x\"\nnormal = \"-z\"\n");
    refused(
        &text,
        line_of(&text, "[[indenters]]"),
        &["unknown field `normal`, expected one of `name`, `body`", "`axis`, `center`, `radius`, `length`"],
    );
    let text = edit(&base, "axis = \"x\"\n", "axis = \"x\"\nmethod = \"surfac\"\n");
    refused(
        &text,
        line_of(&text, "[[indenters]]"),
        &["unknown variant `surfac`, expected `node_to_node` or `surface`"],
    );
    let text = edit(&base, "axis = \"x\"\n", "axis = \"w\"\n");
    refused(
        &text,
        line_of(&text, "[[indenters]]"),
        &["indenters[0].axis: unknown variant `w`, expected one of `x`, `y`, `z`"],
    );
    let text = edit(&example("block_indentation.toml"), "normal = \"-z\"", "normal = \"z-\"");
    refused(
        &text,
        line_of(&text, "[[indenters]]"),
        &["unknown variant `z-`, expected one of `+x`, `-x`, `+y`, `-y`, `+z`, `-z`"],
    );
}

#[test]
fn small_settings_are_words_from_a_list() {
    let base = example("cantilever_timoshenko.toml");
    let cases = [
        ("[solver]\nfactor_precision = \"half\"\n", "half", "unknown variant `half`, expected `single` or `double`"),
        ("[output]\nrecovery = \"nodal\"\n", "nodal", "unknown variant `nodal`, expected `projection` or `element`"),
    ];
    for (table, word, expected) in cases {
        let text = format!("{table}{base}");
        refused(&text, line_of(&text, word), &[expected]);
    }
    let text = edit(&base, "material = \"aluminium\"\n", "material = \"aluminium\"\nformulation = \"mixed\"\n");
    refused(
        &text,
        line_of(&text, "mixed"),
        &["unknown variant `mixed`, expected one of `standard`, `bbar`, `assumed_shear`"],
    );
    let text =
        format!("{base}\n[[references]]\nprobe = \"tip\"\nquantity = \"sigma_yy\"\nvalue = 1.0\nsource = \"x\"\n");
    refused(
        &text,
        line_of(&text, "sigma_yy"),
        &["references[1].quantity: invalid value: text \"sigma_yy\", expected one of u_x, u_y"],
    );
}

/// The printed message keeps the whole list of allowed keys, however long
/// the misspelt key (only the quoted source line is cut).
#[test]
fn the_list_of_allowed_keys_is_never_cut() {
    let long = "a".repeat(300);
    let text = edit(&example("cantilevers_contact.toml"), "axis = \"x\"\n", &format!("axis = \"x\"\n{long} = 1\n"));
    let printed = refused(&text, line_of(&text, "[[indenters]]"), &["`penetration_tolerance`", "`length`"]);
    assert!(printed.len() < 2000, "{printed}");
}
