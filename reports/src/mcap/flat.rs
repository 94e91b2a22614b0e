//! sightline's channel schemas made flat: the JSON Schema subset the viewers'
//! parsers accept.
//!
//! Foxglove and Lichtblick turn a channel's JSON Schema into message
//! definitions with `parseJsonSchema` (`packages/mcap-support/src/parseJsonSchema.ts`
//! in Lichtblick and in Foxglove Studio's last public source). It reads an
//! object's `properties` only, and each property by its `type` alone: `boolean`,
//! `string` (with `contentEncoding` absent or `base64`), `number`, `integer`,
//! `object` (read the same way) or `array` whose `items` have one of those types
//! (not an array); a property with `oneOf` is accepted only when every
//! alternative is a numeric `const`. Anything else is refused with an error and
//! the channel shows nothing: `$ref`, a type array such as `["number", "null"]`,
//! `anyOf`, a property without `type`, an array of arrays.
//!
//! schemars writes a type's schema with `$defs` and `$ref`, nullable fields as
//! type arrays or `anyOf` with `null`, and documented string enums as `oneOf`
//! of string constants. [`flat_schema_of`] rewrites that into the subset: each
//! `$ref` inlined, each nullable field given its one type and left out of
//! `required` (the wire types leave a `None` out of the message: see
//! [`wire`](super::wire)), string constants as `enum`, and the Rust-only
//! `format`s (`uint64`, `double`, …) dropped.

use schemars::JsonSchema;
use serde_json::{Map, Value};

/// The flat JSON Schema of `T`, as a recording registers it.
pub(crate) fn flat_schema_of<T: JsonSchema>() -> Vec<u8> {
    let schema = serde_json::to_value(schemars::schema_for!(T)).expect("a JSON Schema converts to JSON");
    let defs = schema.get("$defs").cloned().unwrap_or_default();
    let mut flat = flatten(&schema, &defs);
    if let Value::Object(root) = &mut flat {
        root.remove("$schema");
    }
    serde_json::to_vec(&flat).expect("a JSON value serializes")
}

/// `node` without `$ref`, nullable types, string `oneOf` or `format`, its
/// references resolved in `defs`.
fn flatten(node: &Value, defs: &Value) -> Value {
    let Value::Object(map) = node else {
        return node.clone();
    };
    let mut out = Map::new();
    if let Some(name) = map.get("$ref").and_then(Value::as_str) {
        let target = name.strip_prefix("#/$defs/").and_then(|name| defs.get(name));
        if let Some(Value::Object(target)) = target.map(|t| flatten(t, defs)) {
            out.extend(target);
        }
    }
    // A nullable field is its one non-null alternative.
    for key in ["anyOf", "oneOf"] {
        if let Some(Value::Array(alternatives)) = map.get(key)
            && alternatives.iter().any(is_null)
        {
            let rest: Vec<&Value> = alternatives.iter().filter(|a| !is_null(a)).collect();
            if let [only] = rest[..]
                && let Value::Object(only) = flatten(only, defs)
            {
                out.extend(only);
            }
        }
    }
    for (key, value) in map {
        match key.as_str() {
            "$ref" | "$defs" | "format" => {}
            "anyOf" | "oneOf" if value.as_array().is_some_and(|a| a.iter().any(is_null)) => {}
            "oneOf" if string_constants(value).is_some() => {
                out.insert("type".into(), "string".into());
                out.insert("enum".into(), string_constants(value).unwrap_or_default().into());
            }
            "type" => {
                let types: Vec<&Value> = match value {
                    Value::Array(types) => types.iter().filter(|t| t.as_str() != Some("null")).collect(),
                    other => vec![other],
                };
                if let [only] = types[..] {
                    out.insert(key.clone(), only.clone());
                }
            }
            "properties" => {
                let properties = value.as_object().into_iter().flatten();
                let flat: Map<String, Value> = properties.map(|(k, v)| (k.clone(), flatten(v, defs))).collect();
                out.insert(key.clone(), flat.into());
            }
            "required" => {
                let nullable = |name: &str| map.get("properties").and_then(|p| p.get(name)).is_some_and(nullable);
                let required: Vec<Value> = value
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter(|name| !name.as_str().is_some_and(nullable))
                    .cloned()
                    .collect();
                out.insert(key.clone(), required.into());
            }
            "items" => {
                out.insert(key.clone(), flatten(value, defs));
            }
            _ => {
                out.insert(key.clone(), value.clone());
            }
        }
    }
    out.into()
}

fn is_null(schema: &Value) -> bool {
    schema.get("type").and_then(Value::as_str) == Some("null")
}

/// Whether a property's schema admits `null`.
fn nullable(schema: &Value) -> bool {
    let type_null = schema
        .get("type")
        .and_then(Value::as_array)
        .is_some_and(|types| types.iter().any(|t| t.as_str() == Some("null")));
    let alternative_null = ["anyOf", "oneOf"].iter().any(|key| {
        schema
            .get(key)
            .and_then(Value::as_array)
            .is_some_and(|a| a.iter().any(is_null))
    });
    type_null || alternative_null
}

/// The constants of a `oneOf` whose every alternative is a string `const`.
fn string_constants(one_of: &Value) -> Option<Vec<Value>> {
    one_of
        .as_array()?
        .iter()
        .map(|alternative| alternative.get("const").filter(|c| c.is_string()).cloned())
        .collect()
}

#[cfg(test)]
mod tests {
    use schemars::JsonSchema;
    use serde_json::{Value, json};

    use super::flat_schema_of;

    /// A string enum with documented variants: schemars writes `oneOf` of
    /// string constants.
    #[derive(JsonSchema)]
    #[expect(dead_code, reason = "only its schema is read")]
    enum Kind {
        /// The first.
        First,
        /// The second.
        Second,
    }

    #[derive(JsonSchema)]
    #[expect(dead_code, reason = "only its schema is read")]
    struct Inner {
        /// A count.
        count: u64,
    }

    #[derive(JsonSchema)]
    #[schemars(title = "test.Outer")]
    #[expect(dead_code, reason = "only its schema is read")]
    struct Outer {
        /// A number that may be absent.
        value: Option<f64>,
        /// A nested object that may be absent.
        inner: Option<Inner>,
        /// A list of nested objects.
        items: Vec<Inner>,
        /// A kind.
        kind: Kind,
    }

    /// Written out by hand: references inlined, each nullable field given its
    /// one type and left out of `required`, the enum a string with `enum`, no
    /// `format`, `$defs` or `$schema`.
    #[test]
    fn a_schema_is_made_flat_as_written_out_by_hand() {
        let flat: Value = serde_json::from_slice(&flat_schema_of::<Outer>()).unwrap();
        assert_eq!(flat["title"], "test.Outer");
        assert_eq!(flat["type"], "object");
        assert_eq!(flat["required"], json!(["items", "kind"]));
        assert_eq!(
            flat["properties"]["value"],
            json!({ "type": "number", "description": "A number that may be absent." })
        );
        assert_eq!(flat["properties"]["inner"]["type"], "object");
        assert_eq!(flat["properties"]["inner"]["properties"]["count"]["type"], "integer");
        assert_eq!(flat["properties"]["items"]["type"], "array");
        assert_eq!(flat["properties"]["items"]["items"]["required"], json!(["count"]));
        assert_eq!(flat["properties"]["kind"]["type"], "string");
        assert_eq!(flat["properties"]["kind"]["enum"], json!(["First", "Second"]));
        let text = flat.to_string();
        for refused in ["$ref", "$defs", "$schema", "anyOf", "oneOf", "null", "format"] {
            assert!(!text.contains(refused), "{refused} in {text}");
        }
    }
}
