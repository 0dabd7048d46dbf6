//! Tables in which one key chooses the variant (`shape = "flat"`,
//! `method = "surface"`), each variant with exactly its own keys beside keys
//! that every variant shares.
//!
//! serde's internally tagged enums say everything a user needs when a
//! variant is misspelt (`unknown variant `flt`, expected one of `flat`,
//! `cylinder`, `sphere``) or a key belongs to another variant (`unknown
//! field `radius`, expected one of …`, listing the keys of the chosen
//! variant, shared ones included), and the TOML reader adds the line. Three
//! things they cannot do are done here: keep the shared keys in one place
//! (a serde `flatten` of them would lose the list of allowed keys from
//! the message), give the choosing key a default (`method` may be left
//! out), and name the key of a bad value (serde reads a tagged table into a
//! buffer first, and what it reads from there carries no key names).

use serde::Deserialize;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};

/// Declares `$vis struct $name { shared keys…, $vis $tag_field: $enum }` and
/// `$vis enum $enum { Variant { own keys… }, … }` (`$vis` the struct's
/// visibility, for its fields and the enum too), read from one flat table
/// in which the key `$tag` names the variant (`= "name"` after each
/// variant), optionally with a default variant.
///
/// The table is read through a private mirror enum (module `$mirror`) whose
/// variants hold the shared keys and their own, each denying unknown keys,
/// so that serde's messages list exactly the keys the chosen variant
/// accepts; its JSON Schema is the mirror's (one branch per variant, the
/// keys' doc comments as descriptions). Field attributes are doc comments;
/// `=> transform` after a field's type writes its range into the schema
/// (`=> ranges::FRICTION.schema()`).
macro_rules! tagged_table {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident $shared:tt
        $(#[$emeta:meta])*
        pub $tag_field:ident: enum $enum:ident by $tag:literal $(or $default:literal)? {
            $( $(#[$vmeta:meta])* $variant:ident = $vname:literal $own:tt )*
        }
        mirror $mirror:ident;
    ) => {
        $crate::input::schema::tagged::tagged_table!(@struct [$(#[$meta])*] $vis $name $tag_field $enum $shared);

        $crate::input::schema::tagged::tagged_table!(@enum [$(#[$emeta])*] $vis $enum { $( [$(#[$vmeta])*] $variant $own )* });

        #[doc = concat!("The flat table that [`", stringify!($name), "`] is read from.")]
        mod $mirror {
            #[allow(unused_imports)]
            use super::*;
            $( $crate::input::schema::tagged::tagged_table!(@mirror $variant $shared $own); )*

            $(#[$meta])*
            #[derive(serde::Deserialize, schemars::JsonSchema)]
            #[serde(tag = $tag)]
            pub(crate) enum Tagged {
                $( $(#[$vmeta])* #[serde(rename = $vname)] $variant($variant), )*
            }

            /// The variants' names, as the model file writes them.
            pub(crate) const NAMES: &[&str] = &[$($vname),*];
        }

        impl schemars::JsonSchema for $name {
            fn schema_name() -> std::borrow::Cow<'static, str> {
                stringify!($name).into()
            }

            fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
                #[allow(unused_mut)]
                let mut schema = <$mirror::Tagged as schemars::JsonSchema>::json_schema(generator);
                $( $crate::input::schema::tagged::optional_tag(&mut schema, $tag, $default); )?
                schema
            }
        }

        impl<'de> serde::Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let default: Option<&'static str> = None $(.or(Some($default)))?;
                let tagged: $mirror::Tagged =
                    $crate::input::schema::tagged::read_tagged(d, ($tag, $mirror::NAMES), default, Some($mirror::NAMES))?;
                Ok(match tagged {
                    $( $mirror::Tagged::$variant(m) => $crate::input::schema::tagged::tagged_table!(
                        @convert m $name $tag_field $enum $variant $shared $own
                    ), )*
                })
            }
        }
    };
    (@enum [$($emeta:tt)*] $vis:vis $enum:ident {
        $( [$($vmeta:tt)*] $variant:ident { $( $(#[$ometa:meta])* $ofield:ident: $oty:ty $(=> $otf:expr)?, )* } )*
    }) => {
        $($emeta)*
        #[derive(Debug)]
        $vis enum $enum {
            $( $($vmeta)* $variant { $( $(#[$ometa])* $ofield: $oty, )* }, )*
        }
    };
    (@struct [$($meta:tt)*] $vis:vis $name:ident $tag_field:ident $enum:ident
        { $( $(#[$fmeta:meta])* $field:ident: $fty:ty $(=> $ftf:expr)?, )* }
    ) => {
        $($meta)*
        #[derive(Debug)]
        $vis struct $name {
            $( $(#[$fmeta])* $vis $field: $fty, )*
            #[doc = concat!("The variant and its own keys ([`", stringify!($enum), "`]).")]
            $vis $tag_field: $enum,
        }
    };
    (@mirror $variant:ident
        { $( $(#[$smeta:meta])* $sfield:ident: $sty:ty $(=> $stf:expr)?, )* }
        { $( $(#[$ometa:meta])* $ofield:ident: $oty:ty $(=> $otf:expr)?, )* }
    ) => {
        #[derive(serde::Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct $variant {
            $( $(#[$smeta])* $(#[schemars(transform = $stf)])? pub $sfield: $sty, )*
            $( $(#[$ometa])* $(#[schemars(transform = $otf)])? pub $ofield: $oty, )*
        }
    };
    (@convert $m:ident $name:ident $tag_field:ident $enum:ident $variant:ident
        { $( $(#[$smeta:meta])* $sfield:ident: $sty:ty $(=> $stf:expr)?, )* }
        { $( $(#[$ometa:meta])* $ofield:ident: $oty:ty $(=> $otf:expr)?, )* }
    ) => {
        $name {
            $( $sfield: $m.$sfield, )*
            $tag_field: $enum::$variant { $( $ofield: $m.$ofield, )* },
        }
    };
}

pub(crate) use tagged_table;

/// Makes the tag `tag` optional, with `default` its default, in the branch
/// of a tagged table's schema whose tag is `default` (a contact's `method`
/// may be left out).
pub(crate) fn optional_tag(schema: &mut schemars::Schema, tag: &str, default: &str) {
    let Some(serde_json::Value::Array(branches)) = schema.get_mut("oneOf") else { return };
    for branch in branches {
        if branch.pointer(&format!("/properties/{tag}/const")).and_then(|v| v.as_str()) != Some(default) {
            continue;
        }
        if let Some(serde_json::Value::Object(property)) = branch.pointer_mut(&format!("/properties/{tag}")) {
            property.insert("default".into(), default.into());
        }
        if let Some(serde_json::Value::Array(required)) = branch.get_mut("required") {
            required.retain(|r| r != tag);
        }
    }
}

/// Reads `T` (a serde enum tagged by `tag`) from `d`; when the table has no
/// `tag` key and a `default` is given, as if it said `tag = default`.
///
/// The table is first read as a whole (as serde buffers any internally
/// tagged table): the tag's value is checked against `names` (if given)
/// where it stands, so a misspelt variant is reported at its own line and
/// column; an error in another key is reported at the table's line, with
/// the key named ([`culprit`]: serde's buffered tables lose key names).
pub(crate) fn read_tagged<'de, D, T>(
    d: D,
    (tag, variants): (&'static str, &'static [&'static str]),
    default: Option<&'static str>,
    names: Option<&'static [&'static str]>,
) -> Result<T, D::Error>
where
    D: Deserializer<'de>,
    T: de::DeserializeOwned,
{
    let mut table = d.deserialize_map(TableVisitor { tag, names })?;
    if let Some(default) = default {
        table.entry(tag).or_insert_with(|| toml::Value::String(default.to_string()));
    }
    T::deserialize(toml::Value::Table(table.clone())).map_err(|e| {
        let message = culprit::<T>(&table, tag, &e);
        de::Error::custom(match owners::<T>(&table, (tag, variants), &message) {
            Some(owners) => format!("{message} ({owners})"),
            None => message,
        })
    })
}

/// For an unknown key of one variant, the other variants that have it
/// (`a key of shape = "laminate"`): a new user wrote a laminate's
/// `interfaces` in a rectangle and was told only the rectangle's keys.
fn owners<T: de::DeserializeOwned>(
    table: &toml::Table,
    (tag, variants): (&str, &[&str]),
    message: &str,
) -> Option<String> {
    let field = message.strip_prefix("unknown field `")?.split('`').next()?;
    let given = table.get(tag).and_then(toml::Value::as_str);
    let value = table.get(field)?;
    let owners: Vec<String> = variants
        .iter()
        .filter(|&&v| Some(v) != given)
        .filter(|&&v| {
            // the key alone with the tag: an unknown key is refused as it
            // is read, missing ones after
            let mut other = toml::Table::new();
            other.insert(tag.to_string(), toml::Value::String(v.to_string()));
            other.insert(field.to_string(), value.clone());
            match T::deserialize(toml::Value::Table(other)) {
                Ok(_) => true,
                Err(e) => !e.message().contains(&format!("unknown field `{field}`")),
            }
        })
        .map(|v| format!("{tag} = {v:?}"))
        .collect();
    (!owners.is_empty()).then(|| format!("a key of {}", owners.join(", ")))
}

/// The message of `error`, read from `table`, prefixed with the key whose
/// value caused it: the first key without which the error goes away or
/// changes. Unknown and missing keys name themselves already.
fn culprit<T: de::DeserializeOwned>(table: &toml::Table, tag: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim_end().to_string();
    if message.starts_with("unknown field") || message.starts_with("missing field") {
        return message;
    }
    for key in table.keys().filter(|k| *k != tag) {
        let mut without = table.clone();
        without.remove(key);
        let changed = match T::deserialize(toml::Value::Table(without)) {
            Ok(_) => true,
            Err(e) => e.message().trim_end() != message,
        };
        if changed {
            return format!("`{key}`: {message}");
        }
    }
    message
}

/// A table whose `tag` key must be one of `names` (if given).
struct TableVisitor {
    tag: &'static str,
    names: Option<&'static [&'static str]>,
}

impl<'de> Visitor<'de> for TableVisitor {
    type Value = toml::Table;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a table")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<toml::Table, A::Error> {
        let mut table = toml::Table::new();
        while let Some(key) = map.next_key::<String>()? {
            let value = if let (true, Some(names)) = (key == self.tag, self.names) {
                toml::Value::String(map.next_value_seed(OneOf(names))?)
            } else {
                map.next_value::<toml::Value>()?
            };
            table.insert(key, value);
        }
        Ok(table)
    }
}

/// A string that must be one of the given names.
struct OneOf(&'static [&'static str]);

impl<'de> DeserializeSeed<'de> for OneOf {
    type Value = String;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<String, D::Error> {
        let s = String::deserialize(d)?;
        if self.0.contains(&s.as_str()) { Ok(s) } else { Err(de::Error::unknown_variant(&s, self.0)) }
    }
}
