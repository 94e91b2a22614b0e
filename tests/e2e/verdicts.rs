//! Verdicts that cannot pass for the wrong reason (issue #13): a requirement
//! with nothing to judge is not exercised, fails the run unless the scenario
//! accepts it with a reason, and the summary, junit.xml and report.html name
//! every requirement that did not pass with its point, value, threshold,
//! margin and n.
//! See: https://github.com/sightline/sightline/issues/13

use quick_junit::{NonSuccessKind, TestCaseStatus};

use crate::support::{
    FAILING, arg, case_output, read, read_json, read_junit, requirement, sightline, temp_dir, unescape_html, verdict,
};

/// The bundled urban junction for one run, with d_min of 1 cm: no road user
/// comes that close, and six anticipation times are measured.
const IDLE: &str = "tests/fixtures/not-exercised/junction-idle.yaml";

/// A scenario without requirements judges nothing, so it does not pass: not
/// exercised, and the gate fails.
#[test]
fn a_scenario_without_requirements_is_not_exercised() {
    let tmp = temp_dir();
    let text = read(&crate::support::root().join(crate::support::SMALL_FIELD));
    let (head, tail) = text.split_once("requirements:\n").unwrap();
    let references = &tail[tail.find("references:").unwrap()..];
    let file = tmp.path().join("unjudged.yaml");
    std::fs::write(&file, format!("{head}{references}")).unwrap();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", arg(&file), "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert!(
        outcome.stdout.starts_with(&format!(
            "NOT EXERCISED {}: 0 of 0 requirements hold over 3 sweep points (no requirements: nothing to judge)",
            file.display()
        )),
        "{outcome}"
    );
    let results = read_json(&out.join("results.json"));
    assert_eq!(
        (&results["verdict"], &results["gate"]),
        (&"not_exercised".into(), &"fail".into())
    );
}

/// A temporal check's window covers the run up to its end, its last step's
/// time plus a step (each step's state holds until the next): `within` the
/// run's duration is judged over every step; a window reaching past the end
/// is not exercised.
#[test]
fn a_window_of_the_runs_duration_is_judged_and_one_past_it_is_not() {
    let tmp = temp_dir();
    let text = std::fs::read_to_string(crate::support::root().join(IDLE)).unwrap();
    for (within, verdict) in [("120", "pass"), ("120.05", "not_exercised")] {
        let file = tmp.path().join(format!("within-{within}.yaml"));
        std::fs::write(&file, text.replace("within: 200 }", &format!("within: {within} }}"))).unwrap();
        let out = tmp.path().join(within);
        sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);
        let results = read_json(&out.join("results.json"));
        let window = requirement(&results, "IDLE-RSU-T");
        assert_eq!(window["verdict"], verdict, "within {within}: {window}");
        assert_eq!(window["n"], 1200, "within {within}: {window}");
    }
}

/// Two requirements, each not exercised for an accepted reason: the run
/// judged nothing, so it passes nothing.
#[test]
fn a_run_with_every_requirement_accepted_not_exercised_does_not_pass() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let scenario = "tests/fixtures/not-exercised/all-accepted.yaml";
    let outcome = sightline(["run", scenario, "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert!(
        outcome.stdout.starts_with(&format!(
            "NOT EXERCISED {scenario}: 0 of 2 requirements hold over 1 sweep point \
             (not exercised: MISS-01, TTC-01 (2 accepted)) -> "
        )),
        "{outcome}"
    );
    let results = read_json(&out.join("results.json"));
    assert_eq!(
        (&results["verdict"], &results["gate"]),
        (&"not_exercised".into(), &"fail".into())
    );
}

/// A cooperating bus whose one sensor reaches 0.2 m, inside its own body,
/// adds no field of view: the ego's disc of 3 m is 44 cells, 440 cell-steps
/// over the run, and the bus's reported footprint is no cell a sensor
/// observed. fov_gain = 440 / 440 − 1 = 0, a FAIL of "at least 0.5".
#[test]
fn fov_gain_counts_no_self_reported_body() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline([
        "run",
        "tests/fixtures/failing/fov-gain-self-report.yaml",
        "--out",
        arg(&out),
    ])
    .assert_exit(1);
    let results = read_json(&out.join("results.json"));
    assert_eq!(verdict(&results, "FOV-01"), ("fail".to_string(), Some(0.0), Some(440)));
    let counts = &results["sweep"][0]["counts"];
    assert_eq!(
        (&counts["ego_observed"], &counts["joint_observed"]),
        (&440.into(), &440.into())
    );
}

/// A field no sensor observes: its errors are over no fused cell.
#[test]
fn a_field_no_sensor_observes_judges_no_error() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let scenario = "tests/fixtures/not-exercised/field-unobserved.yaml";
    sightline(["run", scenario, "--out", arg(&out)]).assert_exit(1);
    let results = read_json(&out.join("results.json"));
    assert_eq!(results["sweep"][0]["metrics"]["unobserved"], 400.0);
    for id in ["FA-01", "CER-01", "BT-01"] {
        assert_eq!(
            verdict(&results, id),
            ("not_exercised".to_string(), None, Some(0)),
            "{id}"
        );
    }
}

#[test]
fn requirements_with_nothing_to_judge_are_not_exercised_and_fail_the_run() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", IDLE, "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert!(
        outcome.stdout.starts_with(&format!(
            "NOT EXERCISED {IDLE}: 1 of 6 requirements hold over 1 sweep point \
             (not exercised: IDLE-WARN, IDLE-MISS, IDLE-ANT-P95, IDLE-RSU-T, IDLE-MISS-ACCEPTED (1 accepted)) -> "
        )),
        "{outcome}"
    );
    for line in [
        "  not exercised IDLE-WARN: measured none (smallest warning_time of n = 0 objects that came within d_min \
         of the ego), threshold 1.5, margin none, n = 0: nothing to judge: no objects that came within d_min of the ego",
        "  not exercised IDLE-ANT-P95: measured none (95th percentile of n = 6 anticipation times), threshold 10.0, \
         margin none, n = 6: nothing to judge: anticipation_p95 over n = 6 anticipation times, fewer than the 59 \
         the check needs",
        "  not exercised IDLE-RSU-T: measured none (rsu_only_objects at the decisive step of n = 1200 defined steps \
         (1 run)), threshold 1.0, margin none, n = 1200: nothing to judge: the window of 200 s reaches past the \
         run's end at 120 s",
    ] {
        assert!(outcome.stdout.contains(&format!("{line}\n")), "{line}\n{outcome}");
    }

    let results = read_json(&out.join("results.json"));
    assert_eq!(
        (&results["verdict"], &results["gate"]),
        (&"not_exercised".into(), &"fail".into())
    );
    let summary = &results["summary"];
    let counts = ["passed", "not_exercised", "accepted", "failed"].map(|key| summary[key].as_u64());
    assert_eq!(counts, [Some(1), Some(5), Some(1), Some(0)]);
    // A count over no close approach is 0 and would pass `at_most: 0`.
    let miss = requirement(&results, "IDLE-MISS");
    assert_eq!(
        (&miss["verdict"], &miss["n"], &miss["value"], &miss["fails_run"]),
        (
            &"not_exercised".into(),
            &0.into(),
            &serde_json::Value::Null,
            &true.into()
        )
    );
    // Over no close approach there is no figure: left out, not 0.
    assert_eq!(results["sweep"][0]["metrics"].get("missed_criticals"), None);
    assert_eq!(results["sweep"][0]["samples"]["missed_criticals"], 0);
    // The report's table of every metric shows it as not measured.
    let report = unescape_html(&read(&out.join("report.html")));
    assert!(
        report.contains(
            r#"<td class="text">missed_<wbr>criticals</td><td class="text">close approaches</td><td class="text">objects/run</td><td class="num">—</td><td class="num">0</td>"#
        ),
        "missed_criticals over no close approach is shown as —"
    );
    // The median has the six samples it needs by default, and is judged.
    let median = requirement(&results, "IDLE-ANT-MEDIAN");
    assert_eq!(
        (&median["verdict"], &median["n"], &median["min_samples"]),
        (&"pass".into(), &6.into(), &6.into())
    );
    assert_eq!(median["measured"], "median of n = 6 anticipation times");
    assert_eq!(requirement(&results, "IDLE-ANT-P95")["min_samples"], 59);
    let accepted = requirement(&results, "IDLE-MISS-ACCEPTED");
    assert_eq!(
        (&accepted["verdict"], &accepted["fails_run"]),
        (&"not_exercised".into(), &false.into())
    );

    // junit.xml: not exercised is a failure of its own type; accepted, a skip.
    let junit = read_junit(&out.join("junit.xml"));
    let suite = &junit.test_suites[0];
    assert_eq!((suite.tests, suite.failures, suite.errors), (6, 4, 0));
    for case in &suite.test_cases {
        let verdict = case_output(case)["verdict"].clone();
        match (case.name.as_str(), &case.status) {
            ("IDLE-ANT-MEDIAN", TestCaseStatus::Success { .. }) => {}
            ("IDLE-MISS-ACCEPTED", TestCaseStatus::Skipped { message, .. }) => {
                let message = message.as_ref().expect("the skip says why");
                assert!(
                    message.ends_with("(accepted: d_min is 1 cm in this fixture, so no close approach is expected.)")
                );
            }
            (
                name,
                TestCaseStatus::NonSuccess {
                    kind: NonSuccessKind::Failure,
                    ty,
                    message,
                    ..
                },
            ) => {
                assert_eq!(ty.as_ref().map(|t| t.as_str()), Some("not_exercised"), "{name}");
                let message = message.as_ref().unwrap().as_str();
                assert!(
                    message.starts_with(&format!("not exercised {name}: measured none (")),
                    "{message}"
                );
                assert!(message.contains("; n = "), "{message}");
                assert_eq!(verdict, "not_exercised");
            }
            (name, status) => panic!("{name}: {status:?}"),
        }
    }

    // report.html: the banner names each, with what was measured and its n;
    // the accepted one carries its reason.
    let html = unescape_html(&read(&out.join("report.html")));
    assert!(html.contains(r#"data-verdict="not_exercised" data-gate="fail""#));
    assert!(html.contains("NOT EXERCISED:\n  1 of 6 requirements pass, 5 not exercised (1 accepted)."));
    assert!(html.contains(
        r##"<li data-requirement="IDLE-WARN" data-verdict="not_exercised"><a href="#req-IDLE-WARN" class="id">IDLE-WARN</a> not exercised: measured — (smallest warning_time of n = 0 objects that came within d_min of the ego), threshold ≥ 1.5 s, margin —, n = 0.</li>"##
    ));
    assert!(html.contains("accepted: d_min is 1 cm in this fixture, so no close approach is expected."));
}

#[test]
fn an_accepted_not_exercised_verdict_lets_the_run_pass() {
    let tmp = temp_dir();
    let scenario = tmp.path().join("accepted.yaml");
    // Only the requirements that pass or are accepted.
    let text = read(std::path::Path::new(IDLE));
    let kept = text
        .split("  - id: ")
        .enumerate()
        .filter(|(i, part)| *i == 0 || part.starts_with("IDLE-ANT-MEDIAN") || part.starts_with("IDLE-MISS-ACCEPTED"));
    let text = kept.map(|(_, part)| part).collect::<Vec<_>>().join("  - id: ");
    std::fs::write(&scenario, text.replace("../../../docs", "docs")).unwrap();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", arg(&scenario), "--out", arg(&out)]);
    outcome.assert_exit(0);
    assert!(outcome.stdout.starts_with("PASS "), "{outcome}");
    assert!(
        outcome
            .stdout
            .contains("(not exercised: IDLE-MISS-ACCEPTED (1 accepted))"),
        "{outcome}"
    );
    let results = read_json(&out.join("results.json"));
    assert_eq!(
        (&results["verdict"], &results["gate"]),
        (&"not_exercised".into(), &"pass".into())
    );
}

#[test]
fn the_measured_column_says_what_it_holds() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline(["run", FAILING, "--out", arg(&out)]).assert_exit(1);
    let html = unescape_html(&read(&out.join("report.html")));
    // The failing requirement in the banner, at its point, with its numbers.
    assert!(html.contains(
        r##"<a href="#req-NOISE-ACC-01" class="id">NOISE-ACC-01</a> fail at field.masses.gamma=30: measured 0.9812 (value over n = 1600 cells), threshold ≥ 0.995, margin -0.01375, n = 1600.</li>"##
    ), "{html}");
    assert!(html.contains(r#"<td class="num">0.9812<div class="what">value over n = 1600 cells</div></td>"#));
    // Each point's details list every metric with its n.
    assert!(html.contains(
        r#"<tr><td class="text">accuracy</td><td class="text">cells</td><td class="text">1</td><td class="num">0.9812</td><td class="num">1,600</td></tr>"#
    ));
}

/// A scenario replaying the SUMO grid's trace `fcd` for `duration` seconds,
/// with one requirement that passes wherever the trace has road users.
fn replaying(fcd: &str, duration: u32) -> String {
    format!(
        "sightline: 1\nname: uncovered\ntime: {{ duration: {duration}, step: 0.1 }}\n\
         traces: {{ fcd: {fcd}, net: {root}/scenarios/sumo/grid3x3.net.xml }}\n\
         sensor_models: {{ front: {{ range: 80, fov_deg: 70 }}, around: {{ range: 100 }} }}\n\
         agents:\n  - {{ id: ego, kind: car, trace: veh7, connected: true, sensors: [front] }}\n\
         \x20 - {{ id: rsu, kind: rsu, position: [93.5, 93.5], sensors: [around] }}\n\
         semantic: {{ ego: ego }}\n\
         requirements:\n  - {{ id: PDR, text: Delivered., check: {{ metric: packet_delivery_ratio, at_least: 0 }} }}\n",
        root = crate::support::root().display()
    )
}

/// Runs `scenario` (text) and asserts that it fails, warning `warning` on
/// stderr and in results.json, its requirement not exercised.
fn assert_uncovered(scenario: &str, warning: &str) {
    let tmp = temp_dir();
    let file = tmp.path().join("uncovered.yaml");
    std::fs::write(&file, scenario).unwrap();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", arg(&file), "--out", arg(&out)]);
    outcome.assert_exit(1);
    assert!(outcome.stderr.contains(warning), "{outcome}");
    let results = read_json(&out.join("results.json"));
    let pdr = &results["requirements"][0];
    assert_eq!(pdr["verdict"], "not_exercised", "{pdr}");
    let warnings = results["warnings"].as_array().unwrap();
    let (_, message) = warning.split_once("warning: ").unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w["message"].as_str().unwrap().starts_with(message)),
        "{warnings:?}"
    );
}

/// A trace that does not cover the run (the grid's minute of SUMO run in a
/// run of 80 s) is a warning on stderr and in results.json, and a requirement
/// that would pass is not exercised, so the run fails (issue 19).
#[test]
fn a_pass_on_a_run_the_trace_does_not_cover_is_not_exercised() {
    let fcd = format!("{}/scenarios/sumo/grid3x3.fcd.xml", crate::support::root().display());
    assert_uncovered(
        &replaying(&fcd, 80),
        "grid3x3.fcd.xml:1:1: warning: the trace does not cover the run: it has road users from 0 s to 59.9 s \
         only of the run's 0 s to 80 s",
    );
}

/// A trace with a hole (the grid's minute with its timesteps from 10 s to
/// 49.9 s taken out) does not cover the run either, though road users are
/// traced at its start and end: the requirement that held on the 20 s left is
/// not exercised.
#[test]
fn a_pass_on_a_run_with_a_hole_in_its_trace_is_not_exercised() {
    let tmp = temp_dir();
    let text = read(&crate::support::root().join("scenarios/sumo/grid3x3.fcd.xml"));
    let mut parts = text.split("    <timestep ");
    let mut holed = parts.next().unwrap().to_owned();
    for part in parts {
        let time: f64 = part["time=\"".len()..].split('"').next().unwrap().parse().unwrap();
        if !(10.0..50.0).contains(&time) {
            holed.push_str("    <timestep ");
            holed.push_str(part);
        }
    }
    let line = holed[..holed.find("<timestep time=\"50.00\"").unwrap()].lines().count();
    let fcd = tmp.path().join("holed.fcd.xml");
    std::fs::write(&fcd, holed).unwrap();
    assert_uncovered(
        &replaying(&fcd.display().to_string(), 60),
        &format!(
            "holed.fcd.xml:{line}:5: warning: the trace does not cover the run: it has no timestep from 9.9 s to 50 s \
             of the run's 0 s to 60 s"
        ),
    );
}

/// Only a not-exercised verdict is accepted: a requirement that passes
/// everywhere although it gives a reason (P-01) is not called accepted by the
/// summary, the report or the recording. And a run that fails only through a
/// requirement not exercised at one point records that point by default.
#[test]
fn a_pass_is_not_called_accepted_and_the_recording_is_of_the_point_that_fails_the_run() {
    const FILE: &str = "tests/fixtures/not-exercised/field-pass-with-reason.yaml";
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let outcome = sightline(["run", FILE, "--out", arg(&out), "--record"]);
    outcome.assert_exit(1);
    assert!(!outcome.stdout.contains("accepted"), "{outcome}");
    let results = read_json(&out.join("results.json"));
    let ne = requirement(&results, "NE-01");
    assert_eq!((&ne["verdict"], &ne["point"]), (&"not_exercised".into(), &3.into()));
    assert_eq!(requirement(&results, "P-01")["verdict"], "pass");
    assert_eq!(results["recording"]["point"], 3, "NE-01's point, not the first");
    let html = unescape_html(&read(&out.join("report.html")));
    for claim in [
        "accepted: a reason",
        "accepted by the scenario: a reason",
        "Accepted: a reason",
    ] {
        assert!(!html.contains(claim), "the report says `{claim}`");
    }
    let recording = sightline_reports::mcap::read(&std::fs::read(out.join("run.mcap")).unwrap()).unwrap();
    let accepted: Vec<_> = recording
        .verdicts
        .iter()
        .map(|v| (v.id.as_str(), v.accepted.as_deref()))
        .collect();
    assert_eq!(accepted, [("P-01", None), ("NE-01", None)]);
}

/// The estimate of a share over seeds is the share judged to hold: at one of
/// six seeds no road user comes within d_min of the ego (too few samples, not
/// judged), and `missed_criticals ≤ 0` holds at four of the other five. The
/// estimate is 4/6; the bound compared is the one at best, the seed not judged
/// counted as holding: Clopper–Pearson's lower 95 % bound of 5 of 6, the 5 %
/// quantile of Beta(5, 2), where 6x⁵ − 5x⁶ = 0.05: 0.41820.
#[test]
fn a_share_over_seeds_estimates_the_seeds_judged_to_hold() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let scenario = "tests/fixtures/failing/seeds-share-estimate.yaml";
    sightline(["run", scenario, "--out", arg(&out)]).assert_exit(1);
    let results = read_json(&out.join("results.json"));
    let share = requirement(&results, "S-MISS");
    assert_eq!(share["verdict"], "fail", "{share}");
    let seeds = &share["points"][0]["seeds"];
    assert_eq!(
        (&seeds["seeds"], &seeds["method"]),
        (&6.into(), &"clopper_pearson".into())
    );
    assert!(
        (seeds["estimate"].as_f64().unwrap() - 4.0 / 6.0).abs() < 1e-12,
        "{seeds}"
    );
    let bound = seeds["bound"].as_f64().unwrap();
    assert!((bound - 0.418_197).abs() < 1e-6, "{seeds}");
    assert!(
        (6.0 * bound.powi(5) - 5.0 * bound.powi(6) - 0.05).abs() < 1e-9,
        "{seeds}"
    );
    assert!(
        share["message"]
            .as_str()
            .unwrap()
            .starts_with("missed_criticals ≤ 0 at 4 seeds; with the 1 not judged holding too"),
        "{share}"
    );
}
