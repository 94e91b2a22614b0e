//! results.json's published schema: `docs/results.schema.json` is the JSON
//! Schema that `sightline_reports::results_schema` generates from the wire
//! types, every bundled run's results.json and every golden one validate
//! against it (with a real validator, boon), and it refuses a document whose
//! keys the format does not define. Regenerate the schema with
//! `SIGHTLINE_BLESS=1 cargo test --test e2e results_schema::`.

use serde_json::{Value, json};
use sightline_reports::{FORMAT, results_schema};

use crate::support::{assert_matches_file, files_under, read_json, root};

const SCHEMA_FILE: &str = "docs/results.schema.json";

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
    other["format"] = json!("sightline-results/3");
    refusal(&other, "another format");
}
