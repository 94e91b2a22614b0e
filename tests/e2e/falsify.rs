//! `falsify`: the bundled counterexample found and shrunk to its boundary, the
//! report of the search, the same search giving the same files, and the exit
//! codes of the contract (0 none found, 1 found, 2 invalid input).

use std::path::Path;

use quick_junit::{NonSuccessKind, TestCaseStatus};

use crate::support::{arg, normalise_execution, read, read_json, read_junit, sightline, temp_dir, unescape_html};

/// The bundled scenario whose `vary` space holds a counterexample.
const SCENARIO: &str = "scenarios/urban-falsify.yaml";

/// The varied receiver sensitivity, and one step of its grid (a 40 dB range in
/// 1000 steps).
const SENSITIVITY: &str = "v2x.channel.sensitivity_dbm";
const STEP_DB: f64 = 0.04;

/// The bundled scenario's requirements, in file order.
const REQUIREMENTS: [&str; 1] = ["FALS-PDR-01"];

/// Runs `falsify` on `file` into `out` with extra arguments.
fn falsify(file: &str, out: &Path, extra: &[&str]) -> crate::support::Outcome {
    let mut args = vec!["falsify", file, "--out", arg(out)];
    args.extend_from_slice(extra);
    sightline(args)
}

#[test]
fn run_ignores_vary_and_the_bundled_values_pass() {
    let out = temp_dir();
    sightline(["run", SCENARIO, "--out", arg(out.path())]).assert_exit(0);
}

#[test]
fn falsify_finds_the_bundled_counterexample_and_shrinks_it_to_the_boundary() {
    let out = temp_dir();
    let found = falsify(SCENARIO, out.path(), &[]);
    found.assert_exit(1);
    assert!(
        found
            .stdout
            .starts_with("FOUND scenarios/urban-falsify.yaml: FALS-PDR-01 fail"),
        "{found}"
    );
    let report = read_json(&out.path().join("falsify.json"));
    let counterexample = &report["counterexample"];
    assert_eq!(counterexample["requirement"], "FALS-PDR-01");
    assert!(counterexample["margin"].as_f64().unwrap() < 0.0);
    // Shrunk toward the first choice and the low end, but not past the boundary.
    assert_eq!(counterexample["values"]["traffic.pedestrians.per_minute"], 2);
    let sensitivity = counterexample["values"][SENSITIVITY].as_f64().unwrap();
    assert!(
        (-100.0..=-60.0).contains(&sensitivity) && sensitivity > -100.0,
        "{sensitivity}"
    );

    // junit.xml: one case per requirement; the broken one fails, naming the file.
    let junit = read_junit(&out.path().join("junit.xml"));
    let suite = &junit.test_suites[0];
    assert_eq!(
        suite.name.as_str(),
        "Urban junction, 10 s, falsify the RSU-to-ego link (scenarios/urban-falsify.yaml)"
    );
    let ids: Vec<&str> = suite.test_cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(ids, REQUIREMENTS);
    for case in &suite.test_cases {
        assert_eq!(
            case.classname.as_deref(),
            Some("sightline.urban_junction_10_s_falsify_the_rsu_to_ego_link")
        );
        assert_eq!(case.extra["file"].as_str(), SCENARIO);
        let broken = case.name.as_str() == "FALS-PDR-01";
        match &case.status {
            TestCaseStatus::NonSuccess { kind, message, .. } => {
                assert!(broken, "{} fails", case.name.as_str());
                assert_eq!(*kind, NonSuccessKind::Failure);
                let message = message.as_ref().unwrap().as_str();
                assert!(
                    message.starts_with("counterexample.yaml breaks FALS-PDR-01 (fail, margin -"),
                    "{message}"
                );
            }
            TestCaseStatus::Success { .. } => assert!(!broken, "FALS-PDR-01 passes"),
            other => panic!("{other:?}"),
        }
    }

    let file = out.path().join("counterexample.yaml");
    let text = read(&file);
    assert!(text.starts_with("# A counterexample to scenarios/urban-falsify.yaml, found by\n"));
    assert!(text.contains("# It breaks FALS-PDR-01 (fail, margin -"), "{text}");
    assert!(!text.contains("\nvary:"), "{text}");
    let failing = sightline(["run", arg(&file), "--out", arg(&out.path().join("failing"))]);
    failing.assert_exit(1);
    assert!(failing.stdout.contains("fail FALS-PDR-01"), "{failing}");

    // One grid step less extreme passes: the counterexample is at the boundary.
    let written = format!("sensitivity_dbm: {sensitivity:?}\n");
    assert!(text.contains(&written), "{written:?} not in\n{text}");
    let easier = text.replace(&written, &format!("sensitivity_dbm: {:.2}\n", sensitivity - STEP_DB));
    let easier_file = out.path().join("easier.yaml");
    std::fs::write(&easier_file, easier).unwrap();
    sightline(["run", arg(&easier_file), "--out", arg(&out.path().join("easier"))]).assert_exit(0);
}

/// The falsification report: the search's settings, every case tried with its
/// values and margin, the chart of margins, and the counterexample with its
/// shrunk values and the command that reproduces it.
#[test]
fn the_report_lists_the_search_the_cases_and_the_counterexample() {
    let out = temp_dir();
    falsify(SCENARIO, out.path(), &["--cases", "6"]).assert_exit(1);
    let json = read_json(&out.path().join("falsify.json"));
    let html = read(&out.path().join("report.html"));
    let text = unescape_html(&html);
    let section = |heading: &str| {
        let start = text
            .find(&format!("<h2>{heading}</h2>"))
            .unwrap_or_else(|| panic!("no {heading}"));
        let end = text[start + 4..].find("<h2>").map_or(text.len(), |e| start + 4 + e);
        text[start..end].to_string()
    };

    let search = section("Search");
    for row in [
        "<th scope=\"row\">Mode</th><td>guided: ".to_string(),
        format!("<th scope=\"row\">Seed</th><td>{}</td>", json["seed"]),
        "<th scope=\"row\">Cases</th><td>at most 6 before shrinking;".to_string(),
        "<th scope=\"row\">Budget</th><td>none".to_string(),
    ] {
        assert!(search.contains(&row), "{row} not in\n{search}");
    }
    assert!(search.contains(&format!(
        "<td class=\"mono\">{SENSITIVITY}</td><td>from -100 to -60 in 1000 equal steps</td>"
    )));
    assert!(
        text.contains(&format!("sightline falsify {SCENARIO} --cases 6 --seed 11")),
        "the command"
    );

    // One row per case, in order, with the values and margin falsify.json holds.
    let cases = json["cases"].as_array().unwrap();
    let table = section("Cases tried");
    let rows: Vec<&str> = table.split("<tr").skip(2).collect();
    assert_eq!(rows.len(), cases.len());
    for (i, (row, case)) in rows.iter().zip(cases).enumerate() {
        assert!(row.contains(&format!("<td class=\"num\">{}</td>", i + 1)), "{row}");
        assert!(row.contains(case["phase"].as_str().unwrap()), "{row}");
        let sensitivity = case["values"][SENSITIVITY].as_f64().unwrap();
        assert!(
            row.contains(&format!("<td class=\"num\">{sensitivity}</td>")),
            "{sensitivity} not in {row}"
        );
        assert!(row.contains(case["requirement"].as_str().unwrap()));
        let margin = case["margin"].as_f64().unwrap();
        // Four significant digits, as the page writes every number.
        let shown = row
            .split("<td class=\"num\">")
            .filter_map(|cell| cell.split("</td>").next()?.parse::<f64>().ok());
        assert!(
            shown
                .into_iter()
                .any(|v| (v - margin).abs() <= 5e-4 * margin.abs().max(1e-3)),
            "{margin} not in {row}"
        );
    }
    let shrunk = json["counterexample"]["values"][SENSITIVITY].as_f64().unwrap();
    let last = rows.last().unwrap();
    assert!(
        last.contains("(counterexample)") && last.contains(&format!("{shrunk}")),
        "{last}"
    );
    let first = json["first_counterexample"].as_u64().unwrap() as usize;
    assert!(rows[first - 1].contains("(first counterexample)"));

    assert!(
        text.contains("<figure class=\"chart\"><img src=\"data:image/svg+xml;base64,"),
        "the chart"
    );
    assert!(text.contains(&format!("The smallest margin of each of the {} cases", cases.len())));

    let counterexample = section("Counterexample");
    assert!(counterexample.contains(&format!("Case {}, shrunk from the first case", cases.len())));
    assert!(
        counterexample.contains(&format!("<td class=\"num\">{shrunk}</td>")),
        "{counterexample}"
    );
    let reproduce = format!("sightline run {}", out.path().join("counterexample.yaml").display());
    assert!(
        counterexample.contains(&format!("<code>{reproduce}</code>")),
        "{counterexample}"
    );
    assert!(text.contains("FOUND: case"), "the banner");
}

#[test]
fn the_same_seed_writes_the_same_files_whatever_the_thread_count() {
    let (a, b) = (temp_dir(), temp_dir());
    falsify(SCENARIO, a.path(), &["--seed", "5"]).assert_exit(1);
    falsify(SCENARIO, b.path(), &["--seed", "5", "--jobs", "1"]).assert_exit(1);
    for name in ["counterexample.yaml", "falsify.json", "report.html"] {
        let text = |dir: &Path| match unescape_html(&read(&dir.join(name))).replace(arg(dir), "OUT") {
            text if name == "counterexample.yaml" => text,
            text => normalise_execution(&text),
        };
        assert!(text(a.path()) == text(b.path()), "{name} differs");
    }
    let c = temp_dir();
    falsify(SCENARIO, c.path(), &["--seed", "6"]).assert_exit(1);
    assert_ne!(
        read_json(&a.path().join("falsify.json"))["cases"],
        read_json(&c.path().join("falsify.json"))["cases"]
    );
}

#[test]
fn a_space_that_cannot_break_a_requirement_exits_0() {
    let dir = temp_dir();
    let safe = read(Path::new(SCENARIO)).replace(
        "v2x.channel.sensitivity_dbm: [-100, -60]",
        "v2x.channel.sensitivity_dbm: [-100, -80]",
    );
    let file = dir.path().join("safe.yaml");
    std::fs::write(&file, safe).unwrap();
    // An earlier counterexample in the output directory is removed.
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("counterexample.yaml"), "stale").unwrap();
    let none = falsify(arg(&file), &out, &["--cases", "8", "--search", "random"]);
    none.assert_exit(0);
    assert!(none.stdout.starts_with("NONE "), "{none}");
    let report = read_json(&out.join("falsify.json"));
    assert_eq!(report["cases"].as_array().unwrap().len(), 8);
    assert!(report["counterexample"].is_null());
    assert!(!out.join("counterexample.yaml").exists());
    let html = unescape_html(&read(&out.join("report.html")));
    assert!(
        html.contains("NONE: no case of 8 breaks a requirement within the budget."),
        "the banner"
    );
    assert!(html.contains("None found within the budget: no case of 8 breaks a requirement."));
    assert!(html.contains("The smallest margin was "), "the closest case");
    assert!(html.contains("<th scope=\"row\">Mode</th><td>random: "));
    // A budget ends the search before its cases are used up.
    falsify(arg(&file), &out, &["--cases", "100000", "--budget", "0.5"]).assert_exit(0);
    let report = read_json(&out.join("falsify.json"));
    assert!(report["cases"].as_array().unwrap().len() < 100_000);
    let html = read(&out.join("report.html"));
    assert!(html.contains("<th scope=\"row\">Budget</th><td>0.5 s of wall-clock time</td>"));
}

/// junit.xml judges every requirement over every case tried: a second
/// requirement the counterexample also breaks fails too (not only its worst),
/// and a search that tried no case judged nothing.
#[test]
fn every_requirement_a_case_breaks_fails_and_a_search_without_cases_is_not_exercised() {
    let dir = temp_dir();
    let two = read(Path::new(SCENARIO)).replace(
        "requirements:\n",
        "requirements:\n  - id: TS-40\n    text: The RSU sends at most 40 % of what it perceives.\n    \
         check: { metric: transmitted_share, at_most: 0.4 }\n",
    );
    let file = dir.path().join("two.yaml");
    std::fs::write(&file, two).unwrap();
    let out = dir.path().join("out");
    let found = falsify(arg(&file), &out, &["--cases", "6"]);
    found.assert_exit(1);
    // Both requirements broke in some case; junit.xml fails both, each naming
    // the counterexample when it breaks it (as a run of it shows) and the
    // first case that broke it otherwise.
    let run = sightline([
        "run",
        arg(&out.join("counterexample.yaml")),
        "--out",
        arg(&dir.path().join("run")),
    ]);
    run.assert_exit(1);
    let text = read(&out.join("counterexample.yaml"));
    let junit = read_junit(&out.join("junit.xml"));
    for case in &junit.test_suites[0].test_cases {
        let id = case.name.as_str();
        let TestCaseStatus::NonSuccess { kind, message, .. } = &case.status else {
            panic!("{id} passes the search");
        };
        assert_eq!(*kind, NonSuccessKind::Failure);
        let message = message.as_ref().unwrap().as_str();
        if run.stdout.contains(&format!("fail {id}:")) {
            assert!(
                message.starts_with(&format!("counterexample.yaml breaks {id} (fail, margin -")),
                "{message}"
            );
            assert!(text.contains(&format!("{id} (fail, margin -")), "{text}");
        } else {
            assert!(
                message.contains(&format!(" cases broke {id}, first case ")),
                "{message}"
            );
            assert!(message.contains("counterexample.yaml does not break it"), "{message}");
        }
    }
    let html = unescape_html(&read(&out.join("report.html")));
    assert!(html.contains("<h2>Requirements over the search</h2>"), "the tally");

    // A budget spent before the first case: nothing judged, the gate fails.
    let none = falsify(arg(&file), &out, &["--budget", "0.000000001"]);
    none.assert_exit(1);
    assert!(none.stdout.starts_with("NOT EXERCISED "), "{none}");
    let junit = read_junit(&out.join("junit.xml"));
    for case in &junit.test_suites[0].test_cases {
        assert!(
            matches!(
                &case.status,
                TestCaseStatus::NonSuccess {
                    kind: NonSuccessKind::Failure,
                    ..
                }
            ),
            "{:?}",
            case.status
        );
    }
    assert!(!out.join("counterexample.yaml").exists());
    let html = unescape_html(&read(&out.join("report.html")));
    assert!(
        html.contains("NOT EXERCISED: no case was tried within the budget"),
        "the banner"
    );
}

#[test]
fn a_scenario_without_vary_or_with_an_invalid_one_exits_2_and_writes_nothing() {
    let out = temp_dir();
    let target = out.path().join("x");
    let none = falsify("tests/fixtures/valid/small-field.yaml", &target, &[]);
    none.assert_exit(2);
    assert!(
        none.stderr
            .contains("error: nothing to falsify: the scenario has no `vary` section"),
        "{none}"
    );
    let invalid = falsify("tests/fixtures/invalid/vary-errors.yaml", &target, &[]);
    invalid.assert_exit(2);
    assert!(invalid.stderr.contains("vary-errors.yaml:11:3: error:"), "{invalid}");
    // Without requirements there is nothing to break.
    let dir = temp_dir();
    let text = read(Path::new(SCENARIO));
    let without = dir.path().join("without.yaml");
    std::fs::write(&without, &text[..text.find("\nrequirements:").unwrap() + 1]).unwrap();
    let nothing = falsify(arg(&without), &target, &[]);
    nothing.assert_exit(2);
    assert!(
        nothing
            .stderr
            .contains("error: nothing to falsify: the scenario has no requirements"),
        "{nothing}"
    );
    // A case the language refuses names its keys, not lines of a file never written.
    let step = dir.path().join("step.yaml");
    std::fs::write(&step, text.replace("vary:\n", "vary:\n  time.step: [0.05, 0.1]\n")).unwrap();
    let refused = falsify(arg(&step), &target, &["--cases", "4"]);
    refused.assert_exit(2);
    assert!(
        refused
            .stderr
            .lines()
            .all(|line| line.contains("step.yaml: error: vary: the case time.step=")),
        "{refused}"
    );
    falsify(SCENARIO, &target, &["--budget", "-1"]).assert_exit(2);
    assert!(!target.exists());
}

#[test]
fn a_counterexample_reads_the_imported_files_from_its_own_directory() {
    // A copy of the SUMO grid scenario and its traces, without the checks over
    // 30 seeds (slow), with a receiver that cannot hear the RSU.
    let dir = temp_dir();
    std::fs::create_dir(dir.path().join("sumo")).unwrap();
    for ext in ["fcd", "net", "poly"] {
        let name = format!("grid3x3.{ext}.xml");
        std::fs::copy(
            Path::new("scenarios/sumo").join(&name),
            dir.path().join("sumo").join(&name),
        )
        .unwrap();
    }
    let text = read(Path::new("scenarios/sumo-grid-semantic.yaml"));
    let text = format!(
        "{}vary:\n  v2x.channel.sensitivity_dbm: {{ one_of: [-50] }}\n",
        &text[..text.find("  # Over 30 seeds").unwrap()]
    );
    let file = dir.path().join("grid.yaml");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out").join("grid");
    falsify(arg(&file), &out, &["--cases", "1"]).assert_exit(1);
    let counterexample = read(&out.join("counterexample.yaml"));
    assert!(
        counterexample.contains("  fcd: \"../../sumo/grid3x3.fcd.xml\"\n"),
        "{counterexample}"
    );
    let run = sightline([
        "run",
        arg(&out.join("counterexample.yaml")),
        "--out",
        arg(&dir.path().join("run")),
    ]);
    run.assert_exit(1);
    assert!(run.stdout.contains("fail GRID-PDR-01"), "{run}");
}

/// The search records no case: a `record:` section is said to be kept for
/// the counterexample, not silently dropped.
#[test]
fn a_record_section_is_kept_for_the_counterexample_with_a_note() {
    let dir = temp_dir();
    let file = dir.path().join("recorded.yaml");
    std::fs::write(&file, read(Path::new(SCENARIO)) + "record: {}\n").unwrap();
    let out = dir.path().join("out");
    let found = falsify(arg(&file), &out, &["--cases", "2"]);
    assert!(
        found.stderr.contains("note: record: no case of the search is recorded"),
        "{found}"
    );
    // The bundled space breaks at its first case.
    found.assert_exit(1);
    assert!(!out.join("run.mcap").exists());
    assert!(read(&out.join("counterexample.yaml")).contains("\nrecord:"));
}
