//! The model file of a mesh plan: the user's model-file text with each
//! body's divisions replaced by those of a [`MeshPlan`], everything else —
//! comments, order, every other key — kept as written.
//!
//! An adaptive run builds each refined model from this text
//! ([`super::Model::parse_planned`]) and writes the last one beside its
//! results (`adapted.toml`), so the model a user keeps, verifies or ships
//! is exactly the one that was solved.
//!
//! What is replaced, per body:
//!
//! * the axis: `lines` (the plan's element boundaries) instead of
//!   `from`/`to`/`elements`/`ratio`/`segments`;
//! * a `rectangle` section: `x` and `z` as `{ lines = […] }` (its `hole`
//!   as written);
//! * a parametric section: its in-plane counts multiplied by `2^n`, `n` the
//!   doublings of the whole section plus those of the count itself
//!   ([`SectionPlan::Doubled`]): a `tube`'s `around = 4 + 4k` (k per side),
//!   `along_x`, `along_z` (those written; the part `along`) and its
//!   `through` (the part `through` only; a tube given by `around` is then
//!   written with `along_x` and `along_z`); a profile's `along_flange`,
//!   `along_web`, a hat's `along_lip`; a `circular_tube`'s `around`; a
//!   `circle`'s `around` and `through`; a `laminate`'s `elements` of each
//!   ply. Defaults are written out when multiplied. A profile wall's `through` is kept;
//!   a profile's `junction_element` is set when the plan grades its walls.

use std::collections::BTreeMap;

use toml_edit::{Array, DocumentMut, InlineTable, Item, TableLike, Value};

use super::refine::{MeshPlan, SectionPlan};
use crate::input::{ModelError, defaults, invalid};
use crate::mesh::CrossSection;

/// `text` with the divisions of `plan` (module docs). `text` must be the
/// model file the plan was made from (a file with other bodies is refused).
pub(crate) fn planned_text(text: &str, plan: &MeshPlan) -> Result<String, ModelError> {
    Ok(planned_doc(text, plan)?.to_string())
}

/// The model file an adaptive run writes beside its results
/// (`adapted.toml`): [`planned_text`] with a header that says what it is
/// (`about`: the cycle, its DOF and estimate), the title marked as
/// adapted, and the `[adapt]` table left out — written in the header as
/// comments — so that `cufem run adapted.toml` solves this mesh again
/// instead of refining it further.
pub(crate) fn adapted_text(text: &str, plan: &MeshPlan, about: &str) -> Result<String, ModelError> {
    let mut doc = planned_doc(text, plan)?;
    // in place: the comments above the title (the file's first lines) are its key's
    if let Some(title) = doc.get_mut("title").and_then(Item::as_value_mut)
        && let Some(text) = title.as_str().map(str::to_owned)
    {
        let decor = title.decor().clone();
        *title = Value::from(format!("{text} (adapted mesh: {about})"));
        *title.decor_mut() = decor;
    }
    let mut header = format!(
        "# Written by `cufem run` with adaptive refinement: the run's model file with the divisions\n\
         # of its {about} written in, every other line as it was.\n"
    );
    match doc.remove("adapt") {
        Some(adapt) => {
            header.push_str(
                "# The [adapt] table is left out, so that `cufem run` on this file solves this mesh again;\n\
                 # to refine it further, remove the leading \"# \" of these lines:\n# [adapt]\n",
            );
            if let Some(t) = adapt.as_table_like() {
                for (key, value) in t.iter() {
                    let value = value.as_value().map_or_else(|| value.to_string(), |v| v.to_string());
                    header.push_str(&format!("# {key} = {}\n", value.trim()));
                }
            }
        }
        None => header.push_str("# The adaptive settings came from the command line (`--adapt`).\n"),
    }
    Ok(format!("{header}\n{doc}"))
}

/// The model file's document with the divisions of `plan` (module docs).
fn planned_doc(text: &str, plan: &MeshPlan) -> Result<DocumentMut, ModelError> {
    let mut doc: DocumentMut = text.parse().map_err(|e: toml_edit::TomlError| {
        invalid("(model file)", e.message().trim(), "a TOML model file (the one the mesh plan was made from)")
    })?;
    let mut bodies = bodies_mut(doc.as_item_mut());
    if bodies.len() != plan.bodies.len() {
        return Err(invalid(
            "bodies",
            format!("{} bodies", bodies.len()),
            format!("the {} bodies of the refined model's plan", plan.bodies.len()),
        ));
    }
    for (i, (body, p)) in bodies.iter_mut().zip(&plan.bodies).enumerate() {
        let axis = table(&mut **body, "axis", i)?;
        for k in ["from", "to", "elements", "ratio", "segments", "lines"] {
            axis.remove(k);
        }
        axis.insert("lines", Item::Value(numbers(&p.axis)));
        let section = table(&mut **body, "section", i)?;
        match &p.section {
            SectionPlan::Grid { x, z, .. } => {
                for (key, lines) in [("x", x), ("z", z)] {
                    let mut t = InlineTable::new();
                    t.insert("lines", numbers(lines));
                    section.insert(key, Item::Value(Value::InlineTable(t)));
                }
            }
            SectionPlan::Doubled { shape, times, parts, junction } => {
                double(section, shape, *times, parts);
                if let Some(a) = junction {
                    section.insert("junction_element", Item::Value(Value::from(*a)));
                    // the key added last: spacing as toml_edit writes it
                    section.fmt();
                }
            }
            SectionPlan::Fixed { .. } => {}
        }
    }
    Ok(doc)
}

/// Each body's table, `[[bodies]]` or `bodies = [{…}, …]`.
fn bodies_mut(root: &mut Item) -> Vec<&mut dyn TableLike> {
    tables_mut(root.get_mut("bodies"))
}

/// The tables of an array of tables (`[[key]]`) or of inline tables
/// (`key = [{…}, …]`); none for anything else.
fn tables_mut(item: Option<&mut Item>) -> Vec<&mut dyn TableLike> {
    match item {
        Some(Item::ArrayOfTables(a)) => a.iter_mut().map(|t| t as &mut dyn TableLike).collect(),
        Some(Item::Value(Value::Array(a))) => {
            a.iter_mut().filter_map(Value::as_inline_table_mut).map(|t| t as &mut dyn TableLike).collect()
        }
        _ => Vec::new(),
    }
}

/// Sub-table `key` of body `i` (a table or an inline table).
fn table<'a>(body: &'a mut dyn TableLike, key: &str, i: usize) -> Result<&'a mut dyn TableLike, ModelError> {
    body.get_mut(key)
        .and_then(Item::as_table_like_mut)
        .ok_or_else(|| invalid(format!("bodies[{i}].{key}"), "(not a table)", format!("a `{key}` table")))
}

/// A line's coordinates as written: each with the fewest significant
/// digits that keep it within `10⁻¹²` of the line's largest coordinate, so
/// that the round-off of their sums (`0.037500000000000006`) is not written
/// (a new user's review); the mesh moves by at most that, far below the
/// set-up's node-matching tolerance.
fn numbers(v: &[f64]) -> Value {
    let scale = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    Value::Array(v.iter().map(|&x| shortest(x, 1e-12 * scale)).collect::<Array>())
}

/// `x` with the fewest significant digits within `tolerance` of it.
fn shortest(x: f64, tolerance: f64) -> f64 {
    (0..17)
        .filter_map(|digits| format!("{x:.digits$e}").parse::<f64>().ok())
        .find(|y| (y - x).abs() <= tolerance)
        .unwrap_or(x)
}

/// The count `key` of `t` (its default when absent).
fn count(t: &dyn TableLike, key: &str, default: usize) -> usize {
    t.get(key).and_then(Item::as_integer).map_or(default, |n| usize::try_from(n).unwrap_or(0))
}

/// Sets count `key` to `n`, keeping the old value's spacing and trailing comment.
fn set(t: &mut dyn TableLike, key: &str, n: usize) {
    let mut v = Value::from(i64::try_from(n).unwrap_or(i64::MAX));
    if let Some(old) = t.get(key).and_then(Item::as_value) {
        *v.decor_mut() = old.decor().clone();
    }
    t.insert(key, Item::Value(v));
}

/// The factor `2^(times + parts[key])`.
fn factor(times: u32, parts: &BTreeMap<String, u32>, key: &str) -> usize {
    1usize.checked_shl(times + parts.get(key).copied().unwrap_or(0)).unwrap_or(usize::MAX)
}

/// The counts of a parametric section multiplied (module docs).
fn double(s: &mut dyn TableLike, shape: &str, times: u32, parts: &BTreeMap<String, u32>) {
    let f = |key: &str| factor(times, parts, key);
    let times_of = |s: &mut dyn TableLike, key: &str, default: usize| {
        let n = count(s, key, default).saturating_mul(f(key));
        set(s, key, n);
    };
    match shape {
        "tube" => {
            // `times` and the part `along` double the elements along the
            // walls, the part `through` those through them
            // (`crate::adapt::mark::through_walls`)
            let along = f(TUBE_ALONG);
            let through = factor(0, parts, TUBE_THROUGH);
            if s.contains_key("around") {
                // `around = 4 + 4k`: k elements per side, one through the wall
                let k = count(s, "around", 4).saturating_sub(4) / 4;
                if through > 1 {
                    // `around` allows one element through the wall only
                    s.remove("around");
                    set(s, "along_x", k.saturating_mul(along));
                    set(s, "along_z", k.saturating_mul(along));
                } else {
                    set(s, "around", 4 + 4 * k.saturating_mul(along));
                }
            } else {
                for key in ["along_x", "along_z"] {
                    let n = count(s, key, 1).saturating_mul(along);
                    set(s, key, n);
                }
            }
            if through > 1 {
                let n = count(s, "through", defaults::THROUGH).saturating_mul(through);
                set(s, "through", n);
            }
        }
        "i_beam" | "channel" | "z_section" | "angle" | "hat" | "box" => {
            times_of(s, "along_flange", defaults::ALONG_FLANGE);
            times_of(s, "along_web", defaults::ALONG_WEB);
            if shape == "hat" {
                times_of(s, "along_lip", defaults::ALONG_LIP);
            }
        }
        "circular_tube" => times_of(s, "around", defaults::AROUND),
        "circle" => {
            let around = count(s, "around", defaults::AROUND);
            let through = count(s, "through", (around / 8).max(1));
            set(s, "through", through.saturating_mul(f("through")));
            set(s, "around", around.saturating_mul(f("around")));
        }
        "laminate" => {
            for (k, p) in tables_mut(s.get_mut("plies")).into_iter().enumerate() {
                let n = count(p, "elements", defaults::THROUGH).saturating_mul(f(&ply_key(k)));
                set(p, "elements", n);
            }
        }
        _ => {}
    }
}

/// The named count of a `tube`'s elements through its wall in
/// [`SectionPlan::Doubled`]'s `parts` (`crate::adapt::mark::through_walls`).
pub(crate) const TUBE_THROUGH: &str = "through";
/// The named count of a `tube`'s elements along its walls (`around`, or
/// `along_x` and `along_z`) in [`SectionPlan::Doubled`]'s `parts`: doubled
/// beside `through` where the whole section was to be doubled.
pub(crate) const TUBE_ALONG: &str = "along";

/// The named count of each element of a section of `shape`
/// ([`SectionPlan::Doubled`]'s `parts`): a profile's wall count
/// ([`crate::mesh::profiles::along_key`]), a laminate's ply `plies[k]`;
/// `None` where the shape has no such count (tubes, circles) or the
/// element is in no region.
pub(crate) fn count_keys(shape: &str, section: &CrossSection) -> Vec<Option<String>> {
    let mut keys = vec![None; section.n_elements()];
    for r in &section.regions {
        let key = match shape {
            "laminate" => super::laminate::ply_of_region(&r.name).map(ply_key),
            "i_beam" | "channel" | "z_section" | "angle" | "hat" | "box" => {
                crate::mesh::profiles::along_key(&r.name).map(String::from)
            }
            _ => None,
        };
        for &e in &r.elements {
            if let Some(k) = keys.get_mut(e).filter(|k| k.is_none()) {
                *k = key.clone();
            }
        }
    }
    keys
}

/// The plan's key of a laminate's ply `k` (0-based) in
/// [`SectionPlan::Doubled`]'s `parts`: `plies[k]`.
pub(crate) fn ply_key(k: usize) -> String {
    format!("plies[{k}]")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::refine::BodyPlan;

    /// Tables written as `[bodies.axis]`, `[bodies.section]` and
    /// `[[bodies.section.plies]]` (not inline) are edited as the inline
    /// ones: the axis becomes `lines`, each ply's `elements` is multiplied
    /// by `2^(times + parts)` (a default written out), comments stay.
    #[test]
    fn tables_written_out_are_edited_in_place() {
        let text = r#"# a laminate
[[bodies]]
name = "plate"
[bodies.axis]
element = "B4"
from = 0.0
to = 1.0
elements = 2
[bodies.section]
shape = "laminate"
[[bodies.section.plies]]
thickness = 0.001
elements = 3 # bottom
[[bodies.section.plies]]
thickness = 0.001
"#;
        let parts = [(ply_key(1), 2)].into_iter().collect();
        let plan = MeshPlan {
            bodies: vec![BodyPlan {
                axis: vec![0.0, 0.25, 0.5, 1.0],
                section: SectionPlan::Doubled { shape: "laminate", times: 1, parts, junction: None },
            }],
        };
        let out = planned_text(text, &plan).unwrap();
        let t: toml::Table = out.parse().unwrap();
        let body = &t["bodies"].as_array().unwrap()[0];
        let axis = body["axis"].as_table().unwrap();
        assert_eq!(axis["lines"].as_array().unwrap().len(), 4);
        assert!(!axis.contains_key("from") && !axis.contains_key("elements"), "{out}");
        let plies = body["section"]["plies"].as_array().unwrap();
        // ply 0: 3 · 2¹; ply 1: the default 1 · 2^(1 + 2)
        assert_eq!((plies[0]["elements"].as_integer(), plies[1]["elements"].as_integer()), (Some(6), Some(8)));
        assert!(out.starts_with("# a laminate") && out.contains("# bottom"), "{out}");
        // a plan of another file (two bodies) is refused by key
        let two = MeshPlan { bodies: vec![plan.bodies[0].clone(), plan.bodies[0].clone()] };
        assert!(planned_text(text, &two).unwrap_err().to_string().contains("bodies"));
    }

    /// Written lines carry no round-off digits: `0.025 + 0.0125` is written
    /// `0.0375`, a third of `0.1` `0.033333333333` (beside a `1.0`); within `10⁻¹²` of the largest
    /// coordinate, and exact values kept.
    #[test]
    fn lines_are_written_without_round_off_digits() {
        let v = [0.0, 0.025 + 0.0125, 0.1 / 3.0, 0.1, -2.5e-3, 1.0 - 1e-16];
        assert_eq!(v[1].to_string(), "0.037500000000000006");
        let written = numbers(&v).to_string();
        assert_eq!(written.trim(), "[0.0, 0.0375, 0.033333333333, 0.1, -0.0025, 1.0]");
        let back: Vec<f64> = numbers(&v).as_array().unwrap().iter().map(|x| x.as_float().unwrap()).collect();
        for (a, b) in v.iter().zip(&back) {
            assert!((a - b).abs() <= 1e-12, "{a} {b}");
        }
    }

    /// A tube's counts: `times` and `along` double the elements along the
    /// walls, `through` those through them; a tube given by `around` (one
    /// element through the wall) is written with `along_x`/`along_z` once
    /// its `through` doubles, and the written file builds the tube asked for.
    #[test]
    fn a_tube_s_wall_count_is_doubled_apart_from_its_walls_lengths() {
        let text = |section: &str| {
            format!(
                "[[materials]]\nname = \"al\"\nyoung_modulus = 70e9\npoisson_ratio = 0.3\n[[bodies]]\nname = \"t\"\n\
                 material = \"al\"\nsection = {{ shape = \"tube\", element = \"L9\", width = 0.03, height = 0.03, \
                 thickness = 0.0015, {section} }}\naxis = {{ element = \"B4\", from = 0.0, to = 0.1, elements = 2 }}\n\
                 [[constraints]]\nname = \"root\"\nbody = \"t\"\nwhere = {{ y = 0.0 }}\nfix = [\"x\", \"y\", \"z\"]\n"
            )
        };
        let planned = |section: &str, times: u32, parts: &[(&str, u32)]| {
            let parts = parts.iter().map(|(k, n)| (k.to_string(), *n)).collect();
            let plan = MeshPlan {
                bodies: vec![BodyPlan {
                    axis: vec![0.0, 0.05, 0.1],
                    section: SectionPlan::Doubled { shape: "tube", times, parts, junction: None },
                }],
            };
            let out = planned_text(&text(section), &plan).unwrap();
            let t: toml::Table = out.parse().unwrap();
            let s = t["bodies"].as_array().unwrap()[0]["section"].as_table().unwrap().clone();
            let n = |k: &str| s.get(k).and_then(toml::Value::as_integer);
            let model = crate::setup::Model::parse_with(&out, crate::setup::Limits::none()).unwrap();
            ((n("around"), n("along_x"), n("along_z"), n("through")), model.mesh.bodies[0].section.n_elements())
        };
        // 28 around: 6 per side; corners 1 × 1
        assert_eq!(planned("around = 28", 1, &[]), ((Some(52), None, None, None), 52));
        assert_eq!(planned("around = 28", 0, &[(TUBE_ALONG, 1)]), ((Some(52), None, None, None), 52));
        // two through the wall: 4 corners of 2 × 2 and 4 walls of 6 × 2
        assert_eq!(planned("around = 28", 0, &[(TUBE_THROUGH, 1)]), ((None, Some(6), Some(6), Some(2)), 64));
        assert_eq!(
            planned("around = 28", 0, &[(TUBE_THROUGH, 1), (TUBE_ALONG, 1)]),
            ((None, Some(12), Some(12), Some(2)), 112)
        );
        assert_eq!(
            planned("through = 2, along_x = 3, along_z = 5", 1, &[(TUBE_THROUGH, 1)]),
            ((None, Some(6), Some(10), Some(4)), 4 * 16 + 2 * 4 * 6 + 2 * 4 * 10)
        );
    }
}
