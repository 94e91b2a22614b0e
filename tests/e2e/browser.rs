//! report.html in a real browser: headless Chromium opens the report of every
//! bundled scenario, of a failing fixture and of one whose text carries markup,
//! through `tests/python/check_report.py` (Playwright driving Debian's
//! Chromium). Each page loads offline with no console error and requests
//! nothing but itself; its banner, title and traceability table say what
//! results.json says; it runs no script. Each is also printed to PDF as
//! Chromium prints it (A4 by default): every column head of every table is in
//! the PDF's text (read with pypdf) and no table is wider than the page.
//! Reports, full-page screenshots and PDFs are kept in
//! `target/tmp/browser/<scenario>/`; each page count is printed.
//!
//! Skipped (with a message) only when `SIGHTLINE_BROWSER_PYTHON` is unset;
//! `.ci/run` sets it, and then any failure fails the test.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::bundled::{Bundled, every_run};
use crate::support::{FAILING, arg, read, read_json, root, sha256_hex, sightline, tool};

/// Names a Python with Playwright; `.ci/run` sets it.
const PYTHON_VAR: &str = "SIGHTLINE_BROWSER_PYTHON";

/// A valid fixture whose name, description and requirement text carry markup
/// that sets the global `sightlineInjected` and the title if it ever runs.
const HOSTILE: &str = "tests/fixtures/valid/script-in-text.yaml";

/// The Python to drive the browser with, or `None` (with a message) to skip.
fn python() -> Option<PathBuf> {
    tool(PYTHON_VAR, "a Python with Playwright, beside Debian's chromium")
}

/// Where the report of `scenario` is opened and its screenshot kept.
fn page_dir(scenario: &str) -> PathBuf {
    let stem = Path::new(scenario).file_stem().expect("a scenario file has a name");
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("browser").join(stem)
}

/// Opens `dir/report.html` in Chromium, saves `dir/screenshot.png`, prints it
/// to `dir/report.pdf` and returns what the page showed; panics with the
/// checker's reasons when it fails.
fn open(python: &Path, dir: &Path) -> serde_json::Value {
    open_page(python, dir, &[])
}

/// [`open`] with the checker's extra arguments (`--falsify`).
fn open_page(python: &Path, dir: &Path, extra: &[&str]) -> serde_json::Value {
    let output = Command::new(python)
        .arg(root().join("tests/python/check_report.py"))
        .arg(dir.join("report.html"))
        .arg(dir.join("screenshot.png"))
        .arg("--pdf")
        .arg(dir.join("report.pdf"))
        .args(extra)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", Path::new(python).display()));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "the report failed in the browser:\n{stderr}");
    serde_json::from_slice(&output.stdout)
        .unwrap_or_else(|e| panic!("the browser check printed no JSON ({e}):\n{stderr}"))
}

/// Runs `scenario` into its page directory; returns its results.json.
fn run(scenario: &str) -> serde_json::Value {
    let dir = page_dir(scenario);
    let outcome = sightline(["run", scenario, "--out", arg(&dir)]);
    assert!(matches!(outcome.code, Some(0 | 1)), "{outcome}");
    let results = read_json(&dir.join("results.json"));
    assert_eq!(outcome.code == Some(0), results["gate"] == "pass", "{outcome}");
    results
}

/// Writes the report of a run kept by `bundled.rs` into its page directory.
fn lay_out(run: &Bundled) {
    let dir = page_dir(run.scenario);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("failed to create {}: {e}", dir.display()));
    std::fs::write(dir.join("report.html"), &run.report).expect("the report is written");
}

/// The page says what `results` says: the verdict in the banner, the scenario's
/// name in the title and heading, one traceability row per requirement with its
/// id, text and verdict; and it holds and ran no script.
#[track_caller]
fn assert_page_shows(page: &serde_json::Value, results: &serde_json::Value) {
    let scenario = results["scenario"]["path"].as_str().unwrap();
    let verdict = results["verdict"].as_str().unwrap();
    let name = results["scenario"]["name"].as_str().unwrap();
    assert_eq!(page["verdict"], verdict, "{scenario}");
    let banner = page["banner"].as_str().unwrap();
    assert!(
        banner.starts_with(&format!("{}:", shown(verdict))),
        "{scenario}: banner {banner:?}"
    );
    // The banner names every requirement that did not pass.
    for r in results["requirements"].as_array().unwrap() {
        let id = r["id"].as_str().unwrap();
        assert_eq!(
            banner.contains(id),
            r["verdict"] != "pass",
            "{scenario}: banner {banner:?} and {id}"
        );
    }
    assert_eq!(page["title"], format!("sightline report: {name}"), "{scenario}");
    // Printed on A4 (no scenario asks for Letter), every column head in the
    // PDF (the checker fails otherwise).
    assert_eq!(page["pdf"]["paper"], "A4", "{scenario}");
    assert!(page["pdf"]["pages"].as_u64().is_some_and(|n| n >= 1), "{scenario}");
    eprintln!("{scenario}: {} pages on A4", page["pdf"]["pages"]);
    assert_eq!(page["heading"], name, "{scenario}");
    let rows: Vec<[&str; 3]> = page["traceability"]
        .as_array()
        .unwrap()
        .iter()
        .map(|row| [0, 1, 6].map(|column| first_line(row[column].as_str().unwrap())))
        .collect();
    let verdicts: Vec<String> = results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| shown(r["verdict"].as_str().unwrap()))
        .collect();
    let expected: Vec<[&str; 3]> = results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .zip(&verdicts)
        .map(|(r, verdict)| [r["id"].as_str().unwrap(), r["text"].as_str().unwrap(), verdict])
        .collect();
    assert_eq!(rows, expected, "{scenario}: traceability");
    for (what, none) in [
        ("scripts", 0.into()),
        ("handlers", 0.into()),
        ("globals", serde_json::json!([])),
    ] {
        assert_eq!(page[what], none, "{scenario}: {what}");
    }
}

/// A verdict as the page shows it: in words, which the style writes in capitals.
fn shown(verdict: &str) -> String {
    verdict.replace('_', " ").to_uppercase()
}

/// The first line of a cell: a measured value or a verdict, without the note
/// beneath it.
fn first_line(text: &str) -> &str {
    text.lines().next().unwrap_or_default()
}

/// Opens the report in the page directory of `scenario` and checks it against
/// `results`.
#[track_caller]
fn assert_report_works(python: &Path, scenario: &str, results: &serde_json::Value) {
    assert_page_shows(&open(python, &page_dir(scenario)), results);
}

/// Runs `scenario` and checks its report in the browser; returns results.json.
#[track_caller]
fn run_and_open(python: &Path, scenario: &str) -> serde_json::Value {
    let results = run(scenario);
    assert_report_works(python, scenario, &results);
    results
}

/// Every file in `scenarios/` (the runs are shared with `bundled.rs`).
#[test]
fn every_bundled_report_works_offline_in_a_browser() {
    let Some(python) = python() else { return };
    for run in every_run() {
        lay_out(run);
        assert_report_works(&python, run.scenario, &run.results);
    }
}

/// A failing run's report says so in its banner and its table.
#[test]
fn a_failing_report_shows_the_failure_in_a_browser() {
    let Some(python) = python() else { return };
    let results = run_and_open(&python, FAILING);
    assert_eq!(results["verdict"], "fail");
}

/// A run with nothing to judge says so: its banner reads NOT EXERCISED and
/// names each such requirement (#13).
#[test]
fn a_not_exercised_report_names_each_requirement_in_a_browser() {
    let Some(python) = python() else { return };
    let results = run_and_open(&python, "tests/fixtures/not-exercised/junction-idle.yaml");
    assert_eq!(
        (&results["verdict"], &results["gate"]),
        (&"not_exercised".into(), &"fail".into())
    );
}

/// Markup in the scenario's text is shown as text: the title, heading and
/// table hold it to the letter, and none of it ran (no script element, no
/// event handler, no global set, the title unchanged).
#[test]
fn markup_in_the_scenario_text_is_shown_as_text() {
    let Some(python) = python() else { return };
    let results = run_and_open(&python, HOSTILE);
    let name = results["scenario"]["name"].as_str().unwrap();
    let text = results["requirements"][0]["text"].as_str().unwrap();
    assert!(
        name.contains("<script>") && text.contains("</td><script>"),
        "{name} / {text}"
    );
    let html = read(&page_dir(HOSTILE).join("report.html"));
    assert!(!html.contains("<script>"), "the report holds a script element");
}

/// A requirement text holding a 127-character URL, a token with no place to
/// break, still prints on A4: the traceability table's cells break it
/// anywhere rather than widen the table past the page (the checker fails a
/// table wider than the printed page).
#[test]
fn a_long_url_in_a_requirement_breaks_within_a4() {
    let Some(python) = python() else { return };
    let url = "https://example.org/standards/iso-26262/part-8/clause-11/requirements/tool-qualification/confidence-level/TCL3/section-11.4.5.2";
    assert_eq!(url.len(), 127);
    let map = root().join("scenarios/opendrive/crossroads.xodr");
    let text = read(&root().join("scenarios/opendrive-crossroads-semantic.yaml"))
        .replace(
            "opendrive: opendrive/crossroads.xodr",
            &format!("opendrive: {}", map.display()),
        )
        .replace(
            "text: At least 90 % of the RSU's messages reach the ego.",
            &format!("text: \"See {url}. At least 90 % of the RSU's messages reach the ego.\""),
        );
    assert!(text.contains(url));
    // The scenario beside its output directory, `page_dir("long-url")`.
    let dir = page_dir("long-url-scenario");
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = dir.join("long-url.yaml");
    std::fs::write(&scenario, text).unwrap();
    let results = run_and_open(&python, scenario.to_str().unwrap());
    assert!(results["requirements"].to_string().contains(url));
}

/// The appendix is the scenario file to the character as the browser parses
/// the page: a file that starts with blank lines (a `<pre>` drops the newline
/// right after its tag), one with CR LF line ends and one with CR alone (the
/// HTML parser turns a written CR into LF) each come back from the
/// appendix's text content exactly, the file whose SHA-256 the report gives.
#[test]
fn the_appendix_is_the_scenario_file_character_for_character() {
    let Some(python) = python() else { return };
    let text = read(&root().join("tests/fixtures/valid/small-field.yaml"));
    assert!(text.ends_with('\n') && !text.contains('\r'));
    let dir = page_dir("appendix-scenarios");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, file) in [
        ("appendix-blank-lines", format!("\n\n{text}")),
        ("appendix-crlf", text.replace('\n', "\r\n")),
        ("appendix-cr", text.replace('\n', "\r")),
    ] {
        let scenario = dir.join(format!("{name}.yaml"));
        std::fs::write(&scenario, &file).unwrap();
        let results = run(scenario.to_str().unwrap());
        assert_eq!(results["scenario"]["sha256"], sha256_hex(file.as_bytes()), "{name}");
        let page = open(&python, &page_dir(name));
        assert_eq!(page["appendix"].as_str(), Some(file.as_str()), "{name}");
    }
}

/// The report of `sightline falsify` (#18): it opens offline, carries its
/// document control (an id of its own, the scenario's `document` fields) and
/// its verdict, and prints on A4 with every column of its tables.
#[test]
fn the_falsify_report_prints_on_a4_with_its_document_control() {
    let Some(python) = python() else { return };
    let scenario = "scenarios/urban-falsify.yaml";
    let dir = page_dir("urban-falsify-search");
    let search = sightline(["falsify", scenario, "--cases", "4", "--out", arg(&dir)]);
    search.assert_exit(1);
    let page = open_page(&python, &dir, &["--falsify"]);
    assert_eq!(page["verdict"], "fail");
    assert_eq!(page["pdf"]["paper"], "A4");
    eprintln!("{scenario} (falsify): {} pages on A4", page["pdf"]["pages"]);
    let control = page["control"].as_array().unwrap();
    let row = |name: &str| {
        control
            .iter()
            .find(|r| r[0] == name)
            .and_then(|r| r[1].as_str())
            .unwrap_or_else(|| panic!("no {name} row: {control:?}"))
            .to_string()
    };
    assert!(
        row("Document id").starts_with("SL-") && row("Document id").len() == 19,
        "{control:?}"
    );
    assert_eq!(row("Paper"), "A4");
}
