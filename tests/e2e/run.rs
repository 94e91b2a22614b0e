//! `sightline run` on valid scenarios: the exit code says whether every
//! requirement holds, and the three evidence files say why.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use quick_junit::{NonSuccessKind, TestCaseStatus};

use crate::support::{
    FAILING, SEED_SWEEP, SHARED_POINT, SMALL_FIELD, arg, assert_evidence_files, case_output, files_under, read,
    read_json, read_junit, root, sha256_hex, sightline, sightline_in, temp_dir, unescape_html,
};

/// The requirement ids of a fixture, in file order, read from its `- id:` lines.
fn requirement_ids(scenario: &str) -> Vec<String> {
    read(&root().join(scenario))
        .lines()
        .filter_map(|line| line.trim_start().strip_prefix("- id:"))
        .map(|id| id.trim().to_string())
        .collect()
}

/// The top-level `name:` of a fixture.
fn scenario_name(scenario: &str) -> String {
    read(&root().join(scenario))
        .lines()
        .find_map(|line| line.strip_prefix("name:"))
        .map(|name| name.trim().to_string())
        .expect("the fixture has a top-level name")
}

#[test]
fn valid_scenario_passes_and_writes_three_evidence_files() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", SMALL_FIELD, "--out", arg(&out)]);
    outcome.assert_exit(0);
    assert!(
        outcome.stdout.starts_with(&format!(
            "PASS {SMALL_FIELD}: 3 of 3 requirements hold over 3 sweep points"
        )),
        "{outcome}"
    );
    assert_eq!(outcome.stderr, "", "{outcome}");
    assert_evidence_files(&out);

    let results = read_json(&out.join("results.json"));
    assert_eq!(results["format"], "sightline-results/5");
    assert_eq!(results["verdict"], "pass");
    assert_eq!(results["tool"]["name"], "sightline");
    assert_eq!(results["tool"]["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(results["scenario"]["path"], SMALL_FIELD);
    assert_eq!(results["scenario"]["name"], scenario_name(SMALL_FIELD).as_str());
    let bytes = std::fs::read(root().join(SMALL_FIELD)).unwrap();
    assert_eq!(results["scenario"]["sha256"], sha256_hex(&bytes).as_str());
    assert_eq!(results["seed"], 42);

    let requirements = results["requirements"].as_array().expect("requirements is a list");
    let ids: Vec<&str> = requirements.iter().map(|r| r["id"].as_str().unwrap()).collect();
    assert_eq!(ids, requirement_ids(SMALL_FIELD));
    let summary = &results["summary"];
    assert_eq!(
        (
            &summary["requirements"],
            &summary["passed"],
            &summary["failed"],
            &summary["errors"]
        ),
        (&3.into(), &3.into(), &0.into(), &0.into())
    );
    for requirement in requirements {
        assert_eq!(requirement["verdict"], "pass", "{requirement:#}");
        // The verdict must agree with the measured value and the threshold it reports.
        let value = requirement["value"]
            .as_f64()
            .expect("a passing requirement has a value");
        let threshold = requirement["threshold"].as_f64().unwrap();
        match requirement["check"]["relation"].as_str().unwrap() {
            "at_least" => assert!(value >= threshold, "{requirement:#}"),
            "at_most" | "tolerance" => assert!(value <= threshold, "{requirement:#}"),
            other => panic!("unknown relation {other}"),
        }
    }

    let points = results["sweep"].as_array().expect("sweep is a list");
    let labels: Vec<&str> = points.iter().map(|p| p["label"].as_str().unwrap()).collect();
    assert_eq!(labels, ["fusion=Baseline", "fusion=Proposed", "fusion=Bayes"]);
    let methods: Vec<&str> = points.iter().map(|p| p["method"].as_str().unwrap()).collect();
    assert_eq!(methods, ["dempster", "hybrid", "bayes"]);
    // One sweep: one table per metric.
    assert_eq!(results["sweeps"].as_array().map(Vec::len), Some(1));
    let accuracy = &results["metrics"]["accuracy"][0];
    assert_eq!(accuracy["sweep"], 0);
    assert_eq!(accuracy["columns"], serde_json::json!(["fusion", "value", "n"]));
    assert_eq!(accuracy["rows"].as_array().map(Vec::len), Some(3));
    // Each row ends in the metric's sample size: every cell of the 60 m × 60 m grid.
    assert_eq!(accuracy["rows"][0][2], 3600);
    // The reference's `where` selects the Baseline point only.
    let references = results["references"].as_array().unwrap();
    assert_eq!(references.len(), 1);
    assert_eq!(references[0]["points"][0]["label"], "fusion=Baseline");
    assert_eq!(references[0]["points"].as_array().map(Vec::len), Some(1));
}

/// See: issue 13 §6. Sweeps that meet at one configuration simulate it once and
/// count each requirement there once in JUnit, while both sweeps' tables keep it
/// as a row.
#[test]
fn a_configuration_two_sweeps_reach_is_simulated_and_counted_once() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", SHARED_POINT, "--out", arg(&out)]);
    outcome.assert_exit(0);
    assert!(
        outcome.stdout.starts_with(&format!(
            "PASS {SHARED_POINT}: 2 of 2 requirements hold over 3 sweep points"
        )),
        "{outcome}"
    );

    let results = read_json(&out.join("results.json"));
    let labels: Vec<&str> = results["sweep"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["label"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            "field.masses.gamma=4",
            "field.masses.gamma=8 | decision.threshold=0.8",
            "decision.threshold=0.9"
        ]
    );
    assert_eq!(results["sweeps"][1]["points"], serde_json::json!([1, 2]));
    let accuracy = &results["metrics"]["accuracy"];
    assert_eq!(
        accuracy[0]["rows"][1][1], accuracy[1]["rows"][0][1],
        "one run, in both tables"
    );

    // SHARED-MASS-01 at 3 points, SHARED-ACC-01 at the 2 with threshold 0.8:
    // 5 cases, where counting each sweep's rows would give 4 + 3.
    let junit = read_junit(&out.join("junit.xml"));
    assert_eq!(junit.tests, 5);
    assert_eq!(junit.test_suites[0].tests, 5);
    let names: Vec<&str> = junit.test_suites[0]
        .test_cases
        .iter()
        .map(|c| c.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "SHARED-MASS-01 [field.masses.gamma=4]",
            "SHARED-MASS-01 [field.masses.gamma=8 | decision.threshold=0.8]",
            "SHARED-MASS-01 [decision.threshold=0.9]",
            "SHARED-ACC-01 [field.masses.gamma=4]",
            "SHARED-ACC-01 [field.masses.gamma=8 | decision.threshold=0.8]",
        ]
    );

    let html = unescape_html(&read(&out.join("report.html")));
    assert!(html.contains("<th scope=\"row\">Sweep points</th><td class=\"mono\">3</td>"));
    for row in ["4", "8", "0.8", "0.9"] {
        assert!(
            html.contains(&format!("<tr><td class=\"text\">{row}</td>")),
            "a table row at {row}"
        );
    }
}

#[test]
fn report_is_self_contained_and_traces_every_requirement() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", SMALL_FIELD, "--out", arg(&out)]).assert_exit(0);
    let html = read(&out.join("report.html"));
    let text = unescape_html(&html);

    assert!(
        text.contains(&scenario_name(SMALL_FIELD)),
        "the report names the scenario"
    );
    for id in requirement_ids(SMALL_FIELD) {
        assert!(text.contains(&id), "the report lacks requirement {id}");
    }
    let bytes = std::fs::read(root().join(SMALL_FIELD)).unwrap();
    assert!(text.contains(&sha256_hex(&bytes)), "the report lacks the input hash");
    assert!(
        text.contains(&format!("sightline run {SMALL_FIELD} --seed 42")),
        "the report lacks the command that reproduces it"
    );

    // Self-contained: every link stays inside the page and resolves there; nothing
    // is fetched from the network or a neighbouring file.
    let lower = html.to_ascii_lowercase();
    assert!(
        !lower.contains("<script src") && !lower.contains("<link"),
        "external resource"
    );
    assert!(
        !lower.contains("@import") && !lower.contains("url("),
        "CSS loads a resource"
    );
    for attribute in ["src=", "href="] {
        for (at, _) in lower.match_indices(attribute) {
            let value = attribute_value(&html[at + attribute.len()..]);
            assert!(
                !value.contains("http://") && !value.contains("https://") && !value.starts_with("//"),
                "{attribute}{value:?} reaches the network"
            );
            let anchor = value
                .strip_prefix('#')
                .unwrap_or_else(|| panic!("{attribute}{value:?} leaves the page"));
            assert!(
                html.contains(&format!("id=\"{anchor}\"")),
                "link to a missing anchor #{anchor}"
            );
        }
    }
}

/// The value of an HTML attribute, given the text after its `=`.
fn attribute_value(text: &str) -> &str {
    match text.chars().next() {
        Some(quote @ ('"' | '\'')) => {
            let rest = &text[1..];
            &rest[..rest.find(quote).expect("the attribute value is closed")]
        }
        _ => &text[..text.find(|c: char| c.is_whitespace() || c == '>').unwrap_or(text.len())],
    }
}

#[test]
fn failing_requirement_exits_1_and_junit_carries_value_and_threshold() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", FAILING, "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert!(
        outcome.stdout.starts_with(&format!("FAIL {FAILING}: 1 of 2")),
        "{outcome}"
    );
    // The summary names the failing requirement, and its line gives the point,
    // the measured value and what it is, the threshold, the margin and n.
    assert!(
        outcome.stdout.contains("sweep points (fail: NOISE-ACC-01) -> "),
        "{outcome}"
    );
    assert!(
        outcome.stdout.contains(
            "\n  fail NOISE-ACC-01 at [field.masses.gamma=30]: measured 0.98125 (value over n = 1600 cells), \
             threshold 0.995, margin -0.01375000000000004, n = 1600: "
        ),
        "{outcome}"
    );
    assert!(
        !outcome.stdout.contains("NOISE-MASS-01"),
        "a passing requirement is listed\n{outcome}"
    );
    assert_evidence_files(&out);

    let results = read_json(&out.join("results.json"));
    assert_eq!(results["verdict"], "fail");
    assert_eq!(results["summary"]["failed"], 1);
    let requirement = results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["id"] == "NOISE-ACC-01")
        .expect("NOISE-ACC-01 in results.json");
    assert_eq!(requirement["verdict"], "fail");
    let threshold = requirement["threshold"].as_f64().unwrap();
    assert_eq!(threshold, 0.995);
    let failing_points: Vec<&serde_json::Value> = results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r["points"].as_array().unwrap())
        .filter(|p| p["verdict"] == "fail")
        .collect();
    assert_eq!(failing_points.len(), 1, "one failing point: γ = 30");
    let failing = failing_points[0];
    assert_eq!(failing["label"], "field.masses.gamma=30");
    let measured = failing["value"].as_f64().unwrap();
    assert!(measured < threshold);

    let junit = read_junit(&out.join("junit.xml"));
    let suites = &junit.test_suites;
    assert_eq!(suites.len(), 1);
    let count = |suite: &quick_junit::TestSuite, wanted: NonSuccessKind| {
        suite
            .test_cases
            .iter()
            .filter(|c| matches!(&c.status, TestCaseStatus::NonSuccess { kind, .. } if *kind == wanted))
            .count()
    };
    let suite = &suites[0];
    assert_eq!(suite.test_cases.len(), 4, "one case per requirement and sweep point");
    assert_eq!(
        (suite.tests, suite.failures, suite.errors),
        (
            suite.test_cases.len(),
            count(suite, NonSuccessKind::Failure),
            count(suite, NonSuccessKind::Error)
        ),
        "<testsuite> counts"
    );
    assert_eq!(
        (junit.tests, junit.failures, junit.errors),
        (suite.tests, suite.failures, suite.errors),
        "<testsuites> counts"
    );
    assert_eq!(suite.failures, failing_points.len());

    let case = suite
        .test_cases
        .iter()
        .find(|c| c.name.as_str() == "NOISE-ACC-01 [field.masses.gamma=30]")
        .expect("a test case for the failing point");
    let TestCaseStatus::NonSuccess {
        kind: NonSuccessKind::Failure,
        message,
        description,
        ..
    } = &case.status
    else {
        panic!("the failing point is not a <failure>: {:?}", case.status);
    };
    let message = message.as_ref().expect("the failure has a message");
    // Messages round to six significant digits; the description keeps full precision.
    let numbers = numbers_in(message);
    assert!(
        numbers.iter().any(|&n| (n - measured).abs() <= 1e-5 * measured.abs())
            && numbers.iter().any(|&n| (n - threshold).abs() <= 1e-5 * threshold.abs()),
        "the failure message {message:?} lacks the measured {measured} or the threshold {threshold}"
    );
    let description = description.as_ref().expect("the failure has a description");
    assert!(
        message.starts_with("fail NOISE-ACC-01 [field.masses.gamma=30]: measured "),
        "{message:?}"
    );
    assert!(message.contains("n = 1600"), "{message:?}");
    let lines: Vec<&str> = description.lines().collect();
    assert!(
        lines.contains(&format!("measured: {measured} (value over n = 1600 cells)").as_str()),
        "{description:?}"
    );
    assert!(
        lines.contains(&format!("threshold: at_least {threshold}").as_str()),
        "{description:?}"
    );
    assert!(lines.contains(&"n: 1600"), "{description:?}");
    assert_eq!(case_output(case)["requirement"], "NOISE-ACC-01");

    let passing = suite
        .test_cases
        .iter()
        .find(|c| c.name.as_str() == "NOISE-ACC-01 [field.masses.gamma=4]")
        .expect("a test case for the passing point");
    assert!(
        matches!(passing.status, TestCaseStatus::Success { .. }),
        "{:?}",
        passing.status
    );
    // Passing cases carry their values too, and every case names the scenario
    // (not its path), its file and the requirement's line, and takes a time.
    let output = case_output(passing);
    assert_eq!(output["verdict"], "pass");
    assert_eq!(output["threshold"], format!("at_least {threshold:?}"));
    assert_eq!(output["n"], "1600");
    assert!(
        output["value"].parse::<f64>().is_ok_and(|v| v >= threshold),
        "{output:?}"
    );
    assert!(output["margin"].parse::<f64>().is_ok_and(|m| m >= 0.0), "{output:?}");
    let name = results["scenario"]["name"].as_str().unwrap();
    assert_eq!(suite.name.as_str(), format!("{name} ({FAILING})"));
    let line = requirement["line"].as_u64().unwrap().to_string();
    for case in &suite.test_cases {
        assert_eq!(
            case.classname.as_deref(),
            Some("sightline.small_field_under_heavy_noise")
        );
        assert_eq!(case.extra["file"].as_str(), FAILING);
        assert!(case.time.is_some(), "{} has a time", case.name.as_str());
        if case.name.starts_with("NOISE-ACC-01") {
            assert_eq!(case.extra["line"].as_str(), line);
        }
    }
}

/// Every decimal number written in `text`.
fn numbers_in(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | 'e')))
        .filter_map(|token| token.trim_end_matches('.').parse().ok())
        .collect()
}

#[test]
fn several_files_write_one_directory_per_file_stem() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", SMALL_FIELD, SEED_SWEEP, "--out", arg(&out)]);
    outcome.assert_exit(0);
    assert_eq!(
        outcome.stdout.lines().filter(|l| l.starts_with("PASS ")).count(),
        2,
        "{outcome}"
    );
    for (stem, scenario) in [("small-field", SMALL_FIELD), ("seed-sweep", SEED_SWEEP)] {
        assert_evidence_files(&out.join(stem));
        assert_eq!(
            read_json(&out.join(stem).join("results.json"))["scenario"]["path"],
            scenario
        );
    }
    assert_eq!(files_under(&out).len(), 6, "nothing beside the two directories");
}

#[test]
fn one_failing_file_among_several_exits_1_and_all_evidence_is_written() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", FAILING, SMALL_FIELD, "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert_evidence_files(&out.join("accuracy-under-noise"));
    assert_evidence_files(&out.join("small-field"));
    assert_eq!(
        read_json(&out.join("small-field").join("results.json"))["verdict"],
        "pass"
    );
}

#[test]
fn one_invalid_file_among_several_writes_nothing() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let invalid = "tests/fixtures/invalid/unknown-key.yaml";
    let outcome = sightline(["run", SMALL_FIELD, invalid, "--out", arg(&out)]);
    outcome.assert_exit(2);
    // Exactly the problems `check` finds in the invalid file alone.
    assert_eq!(outcome.stderr, sightline(["check", invalid]).stderr);
    assert_eq!(outcome.stdout, "", "{outcome}");
    assert!(!out.exists(), "{} was created", out.display());
    assert_eq!(files_under(tmp.path()), Vec::<std::path::PathBuf>::new());
}

#[test]
fn files_sharing_a_stem_are_refused_before_anything_is_written() {
    let tmp = temp_dir();
    let copy = tmp.path().join("copy");
    std::fs::create_dir(&copy).unwrap();
    let other = copy.join("small-field.yaml");
    std::fs::copy(root().join(SMALL_FIELD), &other).unwrap();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", SMALL_FIELD, arg(&other), "--out", arg(&out)]);
    outcome.assert_exit(2);
    assert_eq!(
        outcome.stderr,
        format!(
            "{}: error: its evidence would overwrite another scenario's in {}; run the files separately with --out\n",
            other.display(),
            out.join("small-field").display()
        )
    );
    assert!(!out.exists(), "{} was created", out.display());
}

/// A file named `...yaml` (stem `..`) or `..yaml` (stem `.`) names no evidence
/// directory: with another file and `--out`, or alone without it, the set went
/// into the folder above (replacing or removing files there). Refused with
/// exit 2 before anything is written, the folder above untouched.
// See: session 19's hostile-input check.
#[test]
fn a_file_whose_stem_is_dot_or_dot_dot_is_refused() {
    for name in ["...yaml", "..yaml"] {
        let tmp = temp_dir();
        let campaign = tmp.path().join("campaign");
        std::fs::create_dir(&campaign).unwrap();
        std::fs::write(campaign.join("report.html"), "precious").unwrap();
        let dotted = campaign.join(name);
        std::fs::copy(root().join(SMALL_FIELD), &dotted).unwrap();
        let out = campaign.join("evidence");
        let with_out = sightline(["run", SMALL_FIELD, arg(&dotted), "--out", arg(&out)]);
        let alone = sightline_in(&campaign, ["run", name]);
        for outcome in [with_out, alone] {
            outcome.assert_exit(2);
            assert!(
                outcome
                    .stderr
                    .contains(&format!("{name}: error: its name without the extension is `.` or `..`")),
                "{outcome}"
            );
            assert_eq!(outcome.stdout, "", "{outcome}");
        }
        assert_eq!(
            files_under(&campaign),
            [PathBuf::from(name), PathBuf::from("report.html")],
            "{name}"
        );
        assert_eq!(read(&campaign.join("report.html")), "precious");
    }
}

#[test]
fn default_evidence_dir_is_out_slash_file_stem() {
    let tmp = temp_dir();
    std::fs::copy(root().join(SMALL_FIELD), tmp.path().join("small-field.yaml")).unwrap();
    let outcome = sightline_in(tmp.path(), ["run", "small-field.yaml"]);
    outcome.assert_exit(0);
    assert_evidence_files(&tmp.path().join("out").join("small-field"));
    assert_eq!(
        files_under(tmp.path()).len(),
        4,
        "the scenario and three evidence files"
    );
}

#[test]
fn check_accepts_valid_files_and_writes_nothing() {
    let tmp = temp_dir();
    let files = [SMALL_FIELD, SEED_SWEEP, FAILING].map(|f| root().join(f));
    let outcome = sightline_in(tmp.path(), std::iter::once("check").chain(files.iter().map(|f| arg(f))));
    outcome.assert_exit(0);
    let expected = format!(
        "{}: ok (3 sweep points, 3 requirements)\n{}: ok (3 sweep points, 1 requirement)\n{}: ok (2 sweep points, 2 requirements)\n",
        files[0].display(),
        files[1].display(),
        files[2].display()
    );
    assert_eq!(outcome.stdout, expected);
    assert_eq!(outcome.stderr, "");
    assert_eq!(
        files_under(tmp.path()),
        Vec::<std::path::PathBuf>::new(),
        "check wrote files"
    );
}

#[test]
fn unwritable_evidence_dir_is_an_internal_error() {
    let tmp = temp_dir();
    let blocker = tmp.path().join("evidence");
    std::fs::write(&blocker, "a file where the directory should go").unwrap();
    let refused = format!("error: failed to create {}", blocker.display());
    for shard in [&[][..], &["--shard", "1/2"]] {
        let outcome = sightline(["run", SMALL_FIELD, "--out", arg(&blocker)].iter().chain(shard));
        outcome.assert_exit(3);
        assert!(outcome.stderr.starts_with(&refused), "{outcome}");
    }
    // Found before anything runs: the first scenario's evidence is not
    // written when the second's directory cannot be.
    let out = tmp.path().join("two");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("seed-sweep"), "a file where the directory should go").unwrap();
    let outcome = sightline(["run", SMALL_FIELD, SEED_SWEEP, "--out", arg(&out)]);
    outcome.assert_exit(3);
    assert_eq!(
        outcome.stderr,
        format!(
            "error: failed to create {0}: {0} is not a directory\n",
            out.join("seed-sweep").display()
        )
    );
    assert!(!out.join("small-field").exists(), "{outcome}");
    // A symbolic link to nothing where the directory goes is found as early.
    #[cfg(unix)]
    {
        let dangling = tmp.path().join("dangling");
        std::os::unix::fs::symlink(tmp.path().join("nowhere"), &dangling).unwrap();
        for shard in [&[][..], &["--shard", "1/2"]] {
            let outcome = sightline(["run", SMALL_FIELD, "--out", arg(&dangling)].iter().chain(shard));
            outcome.assert_exit(3);
            assert_eq!(
                outcome.stderr,
                format!(
                    "error: failed to create {0}: {0} is a symbolic link to nothing\n",
                    dangling.display()
                ),
            );
        }
    }
}

/// `sightline run … | head -1` closes stdout while sightline still prints its
/// summary; that is the reader's choice, not a defect in sightline, so the run
/// exits with the status it earned (0: the fixture passes).
#[test]
fn closed_stdout_is_not_an_internal_error() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let (reader, writer) = std::io::pipe().expect("failed to create a pipe");
    drop(reader);
    let output = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["run", SMALL_FIELD, "--out", arg(&out)])
        .current_dir(root())
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .expect("failed to start sightline");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert_evidence_files(Path::new(&out));
}

/// Text from the scenario reaches the report escaped: a name or requirement that
/// contains markup is shown as text, never interpreted.
#[test]
fn markup_in_scenario_text_is_escaped_in_the_report() {
    let tmp = temp_dir();
    let fixture = read(&root().join(SMALL_FIELD))
        .replace(
            "name: Small field, three fusion methods",
            "name: \"<script>alert('name')</script> & co\"",
        )
        .replace(
            "text: Every fused cell holds a mass function.",
            "text: \"<img src=x onerror=alert(1)> holds\"",
        );
    assert!(
        fixture.contains("<script>") && fixture.contains("<img"),
        "the fixture changed"
    );
    std::fs::write(tmp.path().join("markup.yaml"), fixture).unwrap();
    sightline_in(tmp.path(), ["run", "markup.yaml", "--out", "out"]).assert_exit(0);
    let html = read(&tmp.path().join("out/report.html"));
    assert!(!html.contains("<script"), "raw <script> in the report");
    assert!(!html.contains("<img"), "raw <img> in the report");
    assert!(
        html.contains("&lt;script&gt;alert(&#x27;name&#x27;)&lt;&#x2f;script&gt; &amp; co"),
        "escaped name missing"
    );
    assert!(
        html.contains("&lt;img src=x onerror=alert(1)&gt; holds"),
        "escaped requirement text missing"
    );
}

/// `selftest` reproduces every hand-computed known answer and says so.
#[test]
fn selftest_reproduces_its_known_answers() {
    let outcome = sightline(["selftest"]);
    outcome.assert_exit(0);
    let lines: Vec<&str> = outcome.stdout.lines().collect();
    let cases = lines.iter().filter(|l| l.starts_with("PASS ")).count();
    assert!(cases >= 14, "{outcome}");
    assert!(!outcome.stdout.contains("FAIL "), "{outcome}");
    let summary = lines.last().unwrap();
    assert!(
        summary.ends_with(&format!("selftest: {cases} of {cases} known answers hold")),
        "{summary}"
    );
}
