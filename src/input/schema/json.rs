//! The model file's JSON Schema (`cufem schema`), for editors that check
//! and complete TOML as it is typed (VS Code's Even Better TOML, taplo).
//!
//! It is generated from the types the reader deserializes into (`JsonSchema`
//! derived beside `Deserialize`, serde's `rename`, `tag` and
//! `deny_unknown_fields` honoured), so a key the reader accepts is a key of
//! the schema and an unknown key is refused by both; the keys' doc comments
//! are its descriptions and the plain ranges of [`crate::input::ranges`]
//! its `minimum`/`maximum`. Draft 7, which taplo reads; TOML has no null,
//! so the `null` that serde's `Option` would allow is left out.

use std::borrow::Cow;

use schemars::generate::SchemaSettings;
use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde_json::{Map, Value};

use super::{Exact, ModelFile};

/// An array of exactly `N` items.
impl<T: JsonSchema, const N: usize> JsonSchema for Exact<T, N> {
    fn inline_schema() -> bool {
        true
    }

    fn schema_name() -> Cow<'static, str> {
        format!("Array_size_{N}_of_{}", T::schema_name()).into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        schemars::json_schema!({
            "type": "array",
            "items": generator.subschema_for::<T>(),
            "minItems": N,
            "maxItems": N,
        })
    }
}

/// The JSON Schema (draft 7) of a model file, as `cufem schema` prints it.
pub fn json_schema() -> Value {
    let schema = SchemaSettings::draft07().into_generator().into_root_schema_for::<ModelFile>();
    let mut value = schema.to_value();
    without_null(&mut value);
    if let Value::Object(root) = &mut value {
        root.insert("title".into(), "cufem model file".into());
    }
    value
}

/// `v` with every `null` alternative removed: from `type` lists, from
/// `enum` lists and from `anyOf` (a lone remaining alternative replaces it).
fn without_null(v: &mut Value) {
    match v {
        Value::Array(items) => items.iter_mut().for_each(without_null),
        Value::Object(obj) => {
            obj.values_mut().for_each(without_null);
            if let Some(Value::Array(types)) = obj.get_mut("type") {
                types.retain(|t| t != "null");
                if let [only] = &types[..] {
                    let only = only.clone();
                    obj.insert("type".into(), only);
                }
            }
            if let Some(Value::Array(values)) = obj.get_mut("enum") {
                values.retain(|v| !v.is_null());
            }
            if let Some(Value::Array(alternatives)) = obj.get_mut("anyOf") {
                alternatives.retain(|a| a.get("type").and_then(Value::as_str) != Some("null"));
                if alternatives.len() == 1 {
                    let only = alternatives.pop().unwrap_or_default();
                    obj.remove("anyOf");
                    merge(obj, only);
                }
            }
        }
        _ => {}
    }
}

/// Puts the lone alternative `only` in place of an `anyOf`: its keys join
/// `obj`'s, except a `$ref`, which keeps `obj`'s other keys (a description)
/// apart in an `allOf` (draft 7 ignores the siblings of a `$ref`).
fn merge(obj: &mut Map<String, Value>, only: Value) {
    let Value::Object(only) = only else { return };
    if obj.is_empty() {
        obj.extend(only);
    } else if only.contains_key("$ref") {
        obj.insert("allOf".into(), Value::Array(vec![Value::Object(only)]));
    } else {
        for (k, v) in only {
            obj.entry(k).or_insert(v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_alternatives_are_left_out() {
        let mut v = serde_json::json!({
            "properties": {
                "a": { "type": ["number", "null"], "minimum": 1 },
                "b": { "anyOf": [{ "$ref": "#/definitions/B" }, { "type": "null" }], "description": "d" },
                "c": { "anyOf": [{ "$ref": "#/definitions/C" }, { "type": "null" }] },
                "d": { "enum": ["x", null] }
            }
        });
        without_null(&mut v);
        assert_eq!(
            v,
            serde_json::json!({
                "properties": {
                    "a": { "type": "number", "minimum": 1 },
                    "b": { "allOf": [{ "$ref": "#/definitions/B" }], "description": "d" },
                    "c": { "$ref": "#/definitions/C" },
                    "d": { "enum": ["x"] }
                }
            })
        );
    }
}
