//! results.json's published schema: `docs/results.schema.json` is the JSON
//! Schema that `sightline_reports::results_schema` generates from the wire
//! types, every bundled run's results.json and every golden one validate
//! against it (with a real validator, boon), and it refuses a document whose
//! keys the format does not define. Regenerate the schema with
//! `SIGHTLINE_BLESS=1 cargo test --test e2e results_schema::`.

use serde_json::{Value, json};
use sightline_reports::{FORMAT, results_schema};

use crate::support::{assert_matches_file, files_under, read_json, root, sha256_hex};

const SCHEMA_FILE: &str = "docs/results.schema.json";

/// The format and the SHA-256 of its schema's shape ([`shape`]): a schema
/// that accepts or refuses other documents is another format, so a reader
/// that pinned one schema by its format string is not handed documents it
/// refuses. When the shape changes, bump [`FORMAT`]
/// (`reports/src/results/document.rs`, and the docs that name it) and record
/// the new pair here.
const FORMAT_SHAPE: (&str, &str) = (
    "sightline-results/5",
    "f510e3b1dc6268bd86590b36ed9e1072a72aed296d26438715a6c39f46f5e0f0",
);

/// Why `results` does not validate against the schema, or `Ok`.
fn validate(results: &Value) -> Result<(), String> {
    let location = "urn:sightline:results.schema.json";
    let mut compiler = boon::Compiler::new();
    compiler
        .add_resource(location, results_schema())
        .expect("the schema is a JSON document");
    let mut schemas = boon::Schemas::new();
    let index = compiler
        .compile(location, &mut schemas)
        .unwrap_or_else(|e| panic!("the schema compiles: {e:#}"));
    schemas.validate(results, index).map_err(|e| format!("{e}"))
}

#[track_caller]
fn assert_valid(results: &Value, what: &str) {
    if let Err(error) = validate(results) {
        panic!("{what} does not validate against {SCHEMA_FILE}: {error}");
    }
}

/// Why `results` is refused; panics if it validates.
#[track_caller]
fn refusal(results: &Value, what: &str) -> String {
    validate(results).expect_err(&format!("{SCHEMA_FILE} accepts {what}"))
}

/// A golden results.json with its execution placeholders (`"[THREADS]"`,
/// `"[DURATION_SECONDS]"`, …) put back as values of their type, as a run
/// writes them.
fn golden(name: &str) -> Value {
    let mut results = read_json(&root().join("tests/golden").join(name).join("results.json"));
    let execution = results["execution"].as_object_mut().expect("execution is an object");
    for (key, value) in execution.iter_mut() {
        assert!(
            value.as_str().is_some_and(|v| v.starts_with('[')),
            "{name}: execution.{key} is redacted"
        );
        *value = match key.as_str() {
            "threads" => json!(2),
            "duration_seconds" => json!(1.5),
            "started" => json!("2026-05-01T09:30:00Z"),
            _ => json!("redacted"),
        };
    }
    results
}

/// The golden evidence's directories (`small-field`, …).
fn goldens() -> Vec<String> {
    let mut names: Vec<String> = files_under(&root().join("tests/golden"))
        .into_iter()
        .filter(|p| p.file_name().is_some_and(|f| f == "results.json"))
        .filter_map(|p| Some(p.parent()?.to_str()?.to_string()))
        .collect();
    names.sort();
    names
}

#[test]
fn results_schema_json_is_generated_from_the_wire_types() {
    let schema = results_schema();
    assert_eq!(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
    assert_eq!(schema["properties"]["format"]["const"], FORMAT);
    let mut text = serde_json::to_string_pretty(&schema).expect("the schema serializes");
    text.push('\n');
    assert_matches_file(SCHEMA_FILE, &text);
}

/// The schema without its prose (`description`, `title`, `examples`,
/// `$comment`): what decides which documents it accepts. The names of
/// properties and definitions are kept, whatever they are called.
fn shape(schema: &Value) -> Value {
    const PROSE: [&str; 4] = ["description", "title", "examples", "$comment"];
    const NAMED: [&str; 4] = ["properties", "$defs", "patternProperties", "dependentSchemas"];
    match schema {
        Value::Object(object) => Value::Object(
            object
                .iter()
                .filter(|(key, _)| !PROSE.contains(&key.as_str()))
                .map(|(key, value)| {
                    let value = match value {
                        Value::Object(named) if NAMED.contains(&key.as_str()) => Value::Object(
                            named
                                .iter()
                                .map(|(name, schema)| (name.clone(), shape(schema)))
                                .collect(),
                        ),
                        _ => shape(value),
                    };
                    (key.clone(), value)
                })
                .collect(),
        ),
        Value::Array(items) => Value::Array(items.iter().map(shape).collect()),
        other => other.clone(),
    }
}

#[test]
fn the_format_names_the_shape_of_its_schema() {
    let schema = results_schema();
    let shape = sha256_hex(shape(&schema).to_string().as_bytes());
    let (format, recorded) = FORMAT_SHAPE;
    assert_eq!(
        FORMAT, format,
        "FORMAT changed: record its shape in FORMAT_SHAPE: (\"{FORMAT}\", \"{shape}\")"
    );
    assert_eq!(
        shape, recorded,
        "results.json's schema changed shape since {format}: bump FORMAT, then record the new pair in FORMAT_SHAPE"
    );
}

#[test]
fn the_shape_ignores_prose_but_not_property_names() {
    let schema = json!({
        "description": "prose",
        "properties": { "description": { "type": "string", "description": "prose" } },
        "$defs": { "title": { "title": "prose", "const": 1 } }
    });
    assert_eq!(
        shape(&schema),
        json!({
            "properties": { "description": { "type": "string" } },
            "$defs": { "title": { "const": 1 } }
        })
    );
}

#[test]
fn every_bundled_run_validates() {
    for run in crate::bundled::every_run() {
        assert_valid(&run.results, run.scenario);
    }
}

#[test]
fn every_golden_results_json_validates() {
    let names = goldens();
    assert!(names.len() >= 3, "goldens: {names:?}");
    for name in &names {
        assert_valid(&golden(name), &format!("tests/golden/{name}/results.json"));
    }
}

/// A field renamed anywhere (top level, in a requirement, in the counts of a
/// flattened point detail, in the execution) is refused, and so are a missing
/// field and another format.
#[test]
fn a_renamed_key_is_refused() {
    let valid = golden("small-field");
    assert_valid(&valid, "small-field");
    let renamed = |path: &[&str], from: &str, to: &str| {
        let mut results = valid.clone();
        let mut object = &mut results;
        for segment in path {
            object = match segment.parse::<usize>() {
                Ok(index) => &mut object[index],
                Err(_) => &mut object[*segment],
            };
        }
        let object = object.as_object_mut().expect("an object");
        let value = object.remove(from).unwrap_or_else(|| panic!("no key {from}"));
        object.insert(to.into(), value);
        results
    };
    for (path, from, to) in [
        (&[][..], "assumptions", "idealisations"),
        (&["requirements", "0"][..], "margin", "signed_margin"),
        (&["requirements", "0", "points", "0"][..], "measured", "measure"),
        (&["sweep", "0"][..], "coverage", "sensor_coverage"),
        (&["sweep", "0", "bands", "0"][..], "accuracy", "accurate"),
        (&["sweep", "0", "audit"][..], "max_sum_error", "sum_error"),
        (&["execution"][..], "threads", "workers"),
        (&["tool"][..], "git", "revision"),
    ] {
        let error = refusal(
            &renamed(path, from, to),
            &format!("{}.{from} renamed {to}", path.join(".")),
        );
        assert!(error.contains(to) || error.contains(from), "{from} → {to}: {error}");
    }
    let mut missing = valid.clone();
    missing["sweep"][0]["coverage"]
        .as_object_mut()
        .unwrap()
        .remove("mean_sources");
    refusal(&missing, "a coverage without mean_sources");
    let mut other = valid;
    other["format"] = json!("sightline-results/2");
    refusal(&other, "an earlier format");
}
