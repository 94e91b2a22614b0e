//! The same file and seed give byte-identical evidence (but for when, where and
//! how long it ran), whatever the number of worker threads; `--seed` replaces the scenario's seed, unless the seed is swept.

use std::path::Path;

use crate::support::{
    FAILING, SEED_SWEEP, SMALL_FIELD, arg, files_under, normalise_execution, normalise_junit_times, read, read_json,
    root, sightline, temp_dir, unescape_html,
};

/// The bundled seed 002 junction.
const URBAN: &str = "scenarios/urban-rsu-semantic.yaml";

/// Runs `scenario` into `dir` with extra arguments; panics unless it exits `code`.
fn run_into(scenario: &str, dir: &Path, extra: &[&str], code: i32) {
    let mut args = vec!["run", scenario, "--out", arg(dir)];
    args.extend_from_slice(extra);
    sightline(args).assert_exit(code);
}

/// Panics unless the evidence in `a` and `b` is the same: junit.xml byte for
/// byte, results.json and report.html but for the execution (platform, threads,
/// start, duration).
#[track_caller]
fn assert_same_evidence(a: &Path, b: &Path) {
    for name in ["results.json", "junit.xml", "report.html"] {
        let text = |dir: &Path| match read(&dir.join(name)) {
            text if name == "junit.xml" => normalise_junit_times(&text),
            text => normalise_execution(&text),
        };
        assert!(
            text(a) == text(b),
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn same_scenario_twice_gives_byte_identical_evidence() {
    let tmp = temp_dir();
    for scenario in [SMALL_FIELD, FAILING] {
        let code = if scenario == FAILING { 1 } else { 0 };
        let (first, second) = (tmp.path().join("first"), tmp.path().join("second"));
        run_into(scenario, &first, &[], code);
        run_into(scenario, &second, &[], code);
        assert_same_evidence(&first, &second);
        std::fs::remove_dir_all(&first).unwrap();
        std::fs::remove_dir_all(&second).unwrap();
    }
}

#[test]
fn thread_count_does_not_change_evidence() {
    let tmp = temp_dir();
    let (one, two, three) = (
        tmp.path().join("jobs-1"),
        tmp.path().join("jobs-2"),
        tmp.path().join("jobs-3"),
    );
    run_into(SMALL_FIELD, &one, &["--jobs", "1"], 0);
    run_into(SMALL_FIELD, &two, &["--jobs", "2"], 0);
    run_into(SMALL_FIELD, &three, &["--jobs", "3"], 0);
    assert_same_evidence(&one, &two);
    assert_same_evidence(&one, &three);
}

/// The semantic pipeline (generated traffic, packet drops) is as deterministic.
#[test]
fn thread_count_does_not_change_semantic_evidence() {
    // The junction pools runs; the SUMO grid also checks requirements over 30 seeds.
    for (scenario, code) in [(URBAN, 1), ("scenarios/sumo-grid-semantic.yaml", 0)] {
        let tmp = temp_dir();
        let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
        run_into(scenario, &one, &["--jobs", "1"], code);
        run_into(scenario, &two, &["--jobs", "2"], code);
        assert_same_evidence(&one, &two);
    }
}

/// A joint world (generated traffic, the grid's fusion in parallel chunks,
/// the owners of its cells merged in chunk order, both radios) is as
/// deterministic.
// See: issue 17, "One world".
#[test]
fn thread_count_does_not_change_joint_evidence() {
    let tmp = temp_dir();
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    run_into("scenarios/junction-joint.yaml", &one, &["--jobs", "1"], 0);
    run_into("scenarios/junction-joint.yaml", &two, &["--jobs", "2"], 0);
    assert_same_evidence(&one, &two);
}

/// Noisy odometry draws from one stream per agent, a block per step: swept
/// over its noise, a perception world's evidence is the same at any thread
/// count.
// See: issue 16, "Odometry with noise".
#[test]
fn thread_count_does_not_change_noisy_odometry_evidence() {
    let scenario = "tests/fixtures/valid/noisy-odometry.yaml";
    let tmp = temp_dir();
    let (one, two, three) = (tmp.path().join("one"), tmp.path().join("two"), tmp.path().join("three"));
    run_into(scenario, &one, &["--jobs", "1"], 0);
    run_into(scenario, &two, &["--jobs", "2"], 0);
    run_into(scenario, &three, &["--jobs", "3"], 0);
    assert_same_evidence(&one, &two);
    assert_same_evidence(&one, &three);
    // The odometry's noise is drawn: each level estimates poses differently.
    let results = read_json(&one.join("results.json"));
    let errors: Vec<f64> = results["sweep"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["counts"]["localization_error"].as_f64().unwrap())
        .collect();
    assert!(errors[0] != errors[1] && errors[1] != errors[2], "{errors:?}");
}

#[test]
fn seed_flag_replaces_the_seed_and_changes_the_results() {
    let tmp = temp_dir();
    let (file_seed, same_seed, other_seed) = (
        tmp.path().join("file-seed"),
        tmp.path().join("same-seed"),
        tmp.path().join("other-seed"),
    );
    run_into(SMALL_FIELD, &file_seed, &[], 0);
    // The fixture's own seed is 42: `--seed 42` is the same run.
    run_into(SMALL_FIELD, &same_seed, &["--seed", "42"], 0);
    run_into(SMALL_FIELD, &other_seed, &["--seed", "7"], 0);
    assert_same_evidence(&file_seed, &same_seed);

    let before = read_json(&file_seed.join("results.json"));
    let after = read_json(&other_seed.join("results.json"));
    assert_eq!(before["seed"], 42);
    assert_eq!(after["seed"], 7);
    let points = |results: &serde_json::Value| results["sweep"].as_array().unwrap().clone();
    for point in points(&after) {
        assert_eq!(point["seed"], 7, "every point takes the flag's seed");
    }
    let metrics =
        |results: &serde_json::Value| points(results).iter().map(|p| p["metrics"].clone()).collect::<Vec<_>>();
    assert_ne!(metrics(&before), metrics(&after), "another seed draws another field");
    assert!(read(&other_seed.join("junit.xml")).contains("<property name=\"seed\" value=\"7\"/>"));
    let report = unescape_html(&read(&other_seed.join("report.html")));
    assert!(
        report.contains(&format!("sightline run {SMALL_FIELD} --seed 7")),
        "reproduce command"
    );
}

#[test]
fn seed_flag_is_refused_when_the_scenario_sweeps_the_seed() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let outcome = sightline(["run", SEED_SWEEP, "--out", arg(&out), "--seed", "5"]);
    outcome.assert_exit(2);
    assert_eq!(
        outcome.stderr,
        format!("{SEED_SWEEP}:12:3: error: sweep.seed: `--seed` cannot override a swept `seed`\n")
    );
    assert!(files_under(tmp.path()).is_empty(), "nothing is written");
    // The line and column above name the `seed:` key of the sweep.
    let line = read(&root().join(SEED_SWEEP)).lines().nth(11).unwrap().to_string();
    assert_eq!(&line[2..], "seed: [1, 2, 3]");

    // Without the flag the scenario is valid; with a swept seed there is no single seed.
    run_into(SEED_SWEEP, &out, &[], 0);
    let results = read_json(&out.join("results.json"));
    assert_eq!(results["seed"], serde_json::Value::Null);
    let seeds: Vec<_> = results["sweep"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["seed"].clone())
        .collect();
    assert_eq!(seeds, [1, 2, 3]);
}
