//! The JSON Schema of the scenario language (draft-07, which yaml-language-server
//! reads) and the field reference generated from it.

use std::fmt::Write;
use std::sync::OnceLock;

use schemars::generate::SchemaSettings;
use serde_json::{Map, Value};

use crate::raw::RawScenario;

/// The JSON Schema of a scenario file.
pub fn schema() -> Value {
    SchemaSettings::draft07()
        .into_generator()
        .into_root_schema_for::<RawScenario>()
        .to_value()
}

/// Why a dotted path names no setting: the deepest valid prefix, the keys allowed
/// under it (empty when it is not a mapping), and the first unknown segment.
pub(crate) struct NoSetting {
    pub(crate) parent: String,
    pub(crate) allowed: Vec<String>,
    pub(crate) unknown: String,
}

/// The list whose entries a dotted path names by id (`agents.ego.speed.target`).
pub(crate) const AGENTS: &str = "agents";

/// Checks that a dotted key path (`field.masses.gamma`, `agents.<id>.start.time`)
/// names a setting of the language, by walking the properties of the schema;
/// returns the setting's schema (references resolved). The id of an agent is not
/// checked here.
pub(crate) fn check_setting(segments: &[&str]) -> Result<Value, NoSetting> {
    static SCHEMA: OnceLock<Value> = OnceLock::new();
    let schema = SCHEMA.get_or_init(schema);
    let mut node = schema;
    for (depth, segment) in segments.iter().enumerate() {
        let resolved = reference(node).map_or(node, |name| &schema["definitions"][name.as_str()]);
        if depth == 1 && segments[0] == AGENTS {
            // `agents.<id>`: the segment names an entry of the list.
            node = &resolved["items"];
            continue;
        }
        let properties = resolved["properties"].as_object();
        // A map with keys of the user's choosing (`sensor_models.<id>`).
        let entries = resolved["additionalProperties"]
            .as_object()
            .map(|_| &resolved["additionalProperties"]);
        match properties.and_then(|p| p.get(*segment)).or(entries) {
            Some(child) => node = child,
            None => {
                return Err(NoSetting {
                    parent: segments[..depth].join("."),
                    allowed: properties.map(|p| p.keys().cloned().collect()).unwrap_or_default(),
                    unknown: (*segment).to_string(),
                });
            }
        }
    }
    Ok(reference(node)
        .map_or(node, |name| &schema["definitions"][name.as_str()])
        .clone())
}

/// The unit of the setting a dotted path names (`v2x.latency` → `s`,
/// `agents.<id>.start.offset` → `m`), as the schema writes it on the number
/// (`unit`, from the quantity's range); `None` for a setting without one (a
/// name, a count, a quantity whose unit its context sets) or a path that names
/// no setting.
pub fn setting_unit(dotted: &str) -> Option<String> {
    let segments: Vec<&str> = dotted.split('.').collect();
    let node = check_setting(&segments).ok()?;
    let unit = node
        .get("unit")
        .or_else(|| node.get("items").and_then(|items| items.get("unit")));
    unit.and_then(Value::as_str).map(str::to_string)
}

/// The field-by-field reference of the language as Markdown, generated from
/// [`schema`]: one table per mapping (named by its YAML path), then the allowed
/// values of every enumeration.
pub fn reference_markdown() -> String {
    let schema = schema();
    let definitions = schema["definitions"].as_object().cloned().unwrap_or_default();
    let mut out = String::from(
        "# Scenario language reference\n\n\
         Generated from the JSON Schema by `sightline schema --markdown`; do not edit by hand.\n\
         Units are SI (metres, seconds) unless a field says otherwise; a number's unit follows its range.\n",
    );
    let mut enums = Vec::new();
    let mut queue = vec![("(top level)".to_string(), schema.clone())];
    while !queue.is_empty() {
        let (path, object) = queue.remove(0);
        let _ = write!(out, "\n## `{path}`\n\n");
        if let Some(description) = object["description"].as_str() {
            let _ = writeln!(out, "{}\n", one_line(description));
        }
        out.push_str("| key | type | default | description |\n|---|---|---|---|\n");
        let required: Vec<&str> = object["required"]
            .as_array()
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        for (key, property) in object["properties"].as_object().into_iter().flatten() {
            let (mut type_text, target) = describe_type(property, &definitions);
            if let Some(range) = range_text(property) {
                type_text = format!("{type_text} in {range}");
            }
            let default = if required.contains(&key.as_str()) {
                "required".to_string()
            } else {
                property
                    .get("default")
                    .map(|d| format!("`{d}`"))
                    .unwrap_or_else(|| "—".into())
            };
            let description = property["description"].as_str().map(one_line).unwrap_or_default();
            let _ = writeln!(out, "| `{key}` | {type_text} | {default} | {description} |");
            match target {
                Some(Target::Object(name, suffix)) => {
                    let child = if path == "(top level)" {
                        format!("{key}{suffix}")
                    } else {
                        format!("{path}.{key}{suffix}")
                    };
                    queue.push((child, definitions[&name].clone()));
                }
                Some(Target::Enum(name)) if !enums.contains(&name) => enums.push(name),
                _ => {}
            }
        }
    }
    out.push_str("\n# Values\n");
    for name in enums {
        let definition = &definitions[&name];
        let _ = write!(out, "\n## {name}\n\n");
        if let Some(description) = definition["description"].as_str() {
            let _ = writeln!(out, "{}\n", one_line(description));
        }
        out.push_str("| value | meaning |\n|---|---|\n");
        for variant in definition["oneOf"].as_array().into_iter().flatten() {
            let _ = writeln!(
                out,
                "| `{}` | {} |",
                variant["const"].as_str().unwrap_or_default(),
                variant["description"].as_str().map(one_line).unwrap_or_default()
            );
        }
    }
    out
}

/// A definition a property leads to.
enum Target {
    /// A mapping, and the suffix its path takes (`[]` for a list of mappings,
    /// `.<id>` for the values of a map).
    Object(String, &'static str),
    /// An enumeration.
    Enum(String),
}

/// The type of a property in words, and the definition it leads to.
fn describe_type(property: &Value, definitions: &Map<String, Value>) -> (String, Option<Target>) {
    if let Some(name) = reference(property) {
        let definition = &definitions[&name];
        if definition.get("oneOf").is_some() {
            let values: Vec<String> = definition["oneOf"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|v| v["const"].as_str().map(|c| format!("`{c}`")))
                .collect();
            let anchor = name.to_lowercase();
            return (
                format!("[{name}](#{anchor}): {}", values.join(", ")),
                Some(Target::Enum(name)),
            );
        }
        return ("mapping".into(), Some(Target::Object(name, "")));
    }
    match property["type"].as_str().or_else(|| {
        // `Option<T>` becomes `["T", "null"]`.
        property["type"]
            .as_array()?
            .iter()
            .filter_map(Value::as_str)
            .find(|t| *t != "null")
    }) {
        Some("array") => {
            let items = &property["items"];
            if let Some(name) = reference(items) {
                return ("list of mappings".into(), Some(Target::Object(name, "[]")));
            }
            let (item_type, _) = describe_type(items, definitions);
            match (property["minItems"].as_u64(), property["maxItems"].as_u64()) {
                (Some(2), Some(2)) => (format!("[{item_type}, {item_type}]"), None),
                _ => (format!("list of {item_type}"), None),
            }
        }
        Some("object") => match reference(&property["additionalProperties"]) {
            // A map whose keys the user names (`sensor_models.<id>`).
            Some(name) => ("mapping of id → mapping".into(), Some(Target::Object(name, ".<id>"))),
            None => ("mapping of dotted path → value".into(), None),
        },
        Some("integer") => ("whole number".into(), None),
        Some(other) => (other.into(), None),
        None => ("any".into(), None),
    }
}

/// The range of a number, or of the numbers of a list or a point, in
/// interval notation (`(0, 100]`), when the schema bounds it.
fn range_text(property: &Value) -> Option<String> {
    let mut node = property;
    while node.get("items").is_some() {
        node = &node["items"];
    }
    let bound = |key: &str| node.get(key).map(Value::to_string);
    let (low, open_low) = match (bound("minimum"), bound("exclusiveMinimum")) {
        (Some(min), _) => (min, "["),
        (None, Some(min)) => (min, "("),
        _ => return None,
    };
    let (high, open_high) = match (bound("maximum"), bound("exclusiveMaximum")) {
        (Some(max), _) => (max, "]"),
        (None, Some(max)) => (max, ")"),
        _ => return None,
    };
    let unit = match node.get("unit").and_then(Value::as_str) {
        Some(unit) if unit != "1" => format!(" {unit}"),
        _ => String::new(),
    };
    Some(format!("{open_low}{low}, {high}{open_high}{unit}"))
}

/// The definition name a property points at, through `$ref`, `allOf` or a nullable `anyOf`.
fn reference(property: &Value) -> Option<String> {
    if let Some(r) = property["$ref"].as_str() {
        return r.strip_prefix("#/definitions/").map(str::to_string);
    }
    ["allOf", "anyOf"]
        .iter()
        .filter_map(|k| property[*k].as_array())
        .flatten()
        .find_map(reference)
}

fn one_line(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schema_is_draft_07_and_closed() {
        let schema = schema();
        assert_eq!(schema["$schema"], "http://json-schema.org/draft-07/schema#");
        assert_eq!(schema["additionalProperties"], false);
        assert_eq!(schema["definitions"]["Masses"]["additionalProperties"], false);
    }

    #[test]
    fn reference_names_sections_by_yaml_path() {
        let markdown = reference_markdown();
        for section in [
            "## `field.masses`",
            "## `requirements[].check`",
            "## `fusion.switch`",
            "## `sensor_models.<id>`",
            "## `sensor_models.<id>.mount`",
            "## FusionMethod",
        ] {
            assert!(markdown.contains(section), "missing {section}");
        }
        assert!(markdown.contains("| `gamma` | number in [0, 100) % | required |"));
        assert!(markdown.contains("| `latency` | number in [0, 60] s |"), "{markdown}");
    }

    /// A swept setting's unit, as the report writes it beside the values.
    #[test]
    fn settings_have_the_unit_of_their_range() {
        for (path, unit) in [
            ("v2x.latency", Some("s")),
            ("localization.position_sigma", Some("m")),
            ("localization.odometry.speed_sigma", Some("m/s")),
            ("localization.odometry.yaw_rate_sigma_deg", Some("°/s")),
            ("traffic.vehicles.density_per_km", Some("veh/km")),
            ("agents.ego.start.offset", Some("m")),
            ("sensor_models.lidar.range", Some("m")),
            ("grid.origin", Some("m")),
            ("v2x.penetration", Some("1")),
            // A count, a name, a σ whose unit its context sets, no setting.
            ("perception.cooperating", None),
            ("fusion.method", None),
            ("sensor_models.lidar.position_noise.base", None),
            ("v2x.no_such_key", None),
        ] {
            assert_eq!(setting_unit(path).as_deref(), unit, "{path}");
        }
    }
}
