//! The user's own system under test (issue 21): `system_under_test` driven over
//! ASAM OSI and judged. Tiny shell systems speak the protocol's framing by hand
//! (a 4-byte little-endian length, then the message) to break it in every way
//! a system can: each failure is the run's `error` (exit 3), named by the
//! system and the step, with nothing written and nothing left running. With
//! `SIGHTLINE_OSI_PYTHON` naming a Python with osi-python (ci/tools.sh; with
//! `CI` set the tests fail rather than skip without it), the example systems
//! of `examples/osi-sut` run through their scenarios: the tracker passes, the
//! one that drops partly occluded road users fails on recall, and each key of
//! `system_under_test` shows its effect.
// See: issue 21, "Test the user's own system".

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::support::{Outcome, arg, read_json, redact_results_json, requirement, root, temp_dir, tool, verdict};

const PYTHON_VAR: &str = "SIGHTLINE_OSI_PYTHON";

/// One step (t = 0) of a small perception world: the ego's all-round lidar
/// has a car in sight. `{system}` is the `system_under_test` section.
const ONE_STEP: &str = r#"sightline: 1
name: one step of a system under test
seed: 1
time: { duration: 0.1, step: 0.1 }
grid: { origin: [-30, -30], size: [60, 60], cell: 1 }
roads:
  - { id: ns, polyline: [[0, -30], [0, 30]], speed_limit: 10 }
  - { id: we, polyline: [[-30, 20], [30, 20]], speed_limit: 10 }
sensor_models: { lidar: { range: 40 } }
agents:
  - { id: ego, kind: car, route: [ns], start: { offset: 20 }, speed: { target: 0 }, connected: true, sensors: [lidar] }
  - { id: car, kind: car, route: [we], start: { offset: 30 }, speed: { target: 0 } }
localization: { position_sigma: 0 }
perception: { ego: ego }
fusion: { method: bayes }
system_under_test: {system}
requirements:
  - { id: SUT-REC, text: The system detects what is in sight., check: { metric: sut_recall, at_least: 0.9 } }
  - { id: SUT-GHOST, text: No ghost., check: { metric: sut_ghosts, at_most: 0 } }
"#;

/// The version announcement, framed, as `printf` writes it.
const HELLO: &str = r"printf '\023\000\000\000sightline-osi-sut/1'";

/// An `osi3.SensorData` answering step 0 with nothing detected: its timestamp
/// (field 2) of 0 s and 0 ns, framed.
const EMPTY_ANSWER: &str = r"printf '\006\000\000\000\022\004\010\000\020\000'";

/// An `osi3.SensorData` answering step 0 with one detection, encoded by hand
/// from OSI's field numbers: existence probability 1 (header, field 1, its
/// field 3), 30 m straight ahead of the host (base, field 2; position, its
/// field 2; x and y, fields 1 and 2), and one candidate (field 8) of
/// probability 1 (field 1) and type 3, `TYPE_PEDESTRIAN` (field 2); framed.
const PEDESTRIAN_ANSWER: &str = r"printf '\066\000\000\000\022\004\010\000\020\000\152\056\012\011\031\000\000\000\000\000\000\360\077\022\024\022\022\011\000\000\000\000\000\000\076\100\021\000\000\000\000\000\000\000\000\102\013\011\000\000\000\000\000\000\360\077\020\003'";

/// Writes ONE_STEP with `system` into a fresh folder and runs it there.
fn run_system(system: &str) -> (Outcome, tempfile::TempDir, Duration) {
    run_with(system, "")
}

/// [`run_system`] with `requirements` (YAML list items) added.
fn run_with(system: &str, requirements: &str) -> (Outcome, tempfile::TempDir, Duration) {
    let dir = temp_dir();
    let file = dir.path().join("sut.yaml");
    std::fs::write(&file, ONE_STEP.replace("{system}", system) + requirements).unwrap();
    let started = Instant::now();
    let outcome = super::support::sightline(["run", arg(&file), "--out", arg(&dir.path().join("out"))]);
    (outcome, dir, started.elapsed())
}

/// A shell one-liner as a system serving the ego.
fn shell(script: &str, step_timeout: f64) -> String {
    let script = script.replace('\\', r"\\").replace('"', r#"\""#);
    format!(r#"{{ command: [sh, -c, "{script}"], agent: ego, step_timeout: {step_timeout} }}"#)
}

/// Asserts that the run ended in `error` naming the system and `when`, with
/// `what` in the message, and wrote nothing.
#[track_caller]
fn assert_error(outcome: &Outcome, dir: &Path, when: &str, what: &str) {
    outcome.assert_exit(3);
    let line = outcome
        .stderr
        .lines()
        .find(|l| l.contains("error: system `"))
        .unwrap_or_else(|| {
            panic!("no error naming the system\n{outcome}");
        });
    assert!(
        line.contains(when) && line.contains(what),
        "expected `{when}` and `{what}` in\n{outcome}"
    );
    assert!(line.ends_with("no requirement is judged"), "{line}");
    assert!(
        !dir.join("out").join("results.json").exists(),
        "evidence written\n{outcome}"
    );
}

#[test]
fn a_missing_executable_is_an_error_before_step_0() {
    let (outcome, dir, _) = run_system("{ command: [./no-such-system, --fast], agent: ego }");
    assert_error(
        &outcome,
        dir.path(),
        "system `./no-such-system --fast` before step 0",
        "failed to start it",
    );
}

#[test]
fn a_system_that_prints_garbage_is_an_error() {
    // "garb" read as a length is far above the limit: refused before any allocation.
    let (outcome, dir, _) = run_system(&shell("printf garbage; exec cat >/dev/null", 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "before step 0",
        "above the protocol's limit of 16777216 bytes",
    );
    // After a correct announcement, bytes that are no SensorData.
    let script = format!(r"{HELLO}; printf '\004\000\000\000\377\377\377\377'; exec cat >/dev/null");
    let (outcome, dir, _) = run_system(&shell(&script, 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "at step 0 (t = 0 s)",
        "its message is not an osi3.SensorData",
    );
}

#[test]
fn a_length_over_the_limit_is_an_error_at_its_step() {
    let script = format!(r"{HELLO}; printf '\001\000\000\001'; exec cat >/dev/null");
    let (outcome, dir, _) = run_system(&shell(&script, 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "at step 0",
        "a message of 16777217 bytes announced",
    );
}

#[test]
fn another_protocol_version_is_refused_by_name() {
    let script = r"printf '\023\000\000\000sightline-osi-sut/9'; exec cat >/dev/null";
    let (outcome, dir, _) = run_system(&shell(script, 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "before step 0",
        "it announced `sightline-osi-sut/9`, and sightline speaks `sightline-osi-sut/1`",
    );
}

#[test]
fn an_answer_out_of_protocol_is_an_error() {
    // An empty SensorData: no timestamp, so it answers no step.
    let script = format!(r"{HELLO}; printf '\000\000\000\000'; exec cat >/dev/null");
    let (outcome, dir, _) = run_system(&shell(&script, 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "at step 0",
        "has the timestamp none, and answers the step at 0.000000000 s",
    );
}

#[test]
fn a_system_that_exits_or_closes_its_output_mid_run_is_an_error() {
    let (outcome, dir, _) = run_system(&shell(&format!("{HELLO}; exit 4"), 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "at step 0",
        "its output ended (it exited with status 4)",
    );
    let (outcome, dir, _) = run_system(&shell(&format!("{HELLO}; exec 1>&-; exec cat >/dev/null"), 5.0));
    assert_error(&outcome, dir.path(), "at step 0", "its output ended");
}

#[test]
fn a_system_that_fails_after_the_last_step_is_an_error() {
    let (outcome, dir, _) = run_system(&shell(&format!("{HELLO}; {EMPTY_ANSWER}; cat >/dev/null; exit 5"), 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "after the last step",
        "it exited with status 5 after the last step",
    );
}

/// An answer to step 0 of `objects` empty moving objects (field 13, two
/// bytes each), framed, in a file of `dir`; the shell command that writes it.
fn empty_objects_answer(dir: &Path, objects: usize) -> String {
    let mut message = b"\x12\x04\x08\x00\x10\x00".to_vec();
    message.extend([0x6a, 0].repeat(objects));
    let mut framed = (message.len() as u32).to_le_bytes().to_vec();
    framed.extend(message);
    let file = dir.join("answer.bin");
    std::fs::write(&file, framed).unwrap();
    format!("cat '{}'", file.display())
}

/// An answer within the message limit holding more moving objects than the
/// protocol's bound is refused by count, before its objects are decoded: 16 MB
/// of empty objects took 5.6 GB to decode (session 19's outside check).
#[test]
fn an_answer_of_too_many_moving_objects_is_refused_by_count() {
    let answers = temp_dir();
    for (objects, what) in [
        (
            10_001,
            "holds 10001 moving objects, above the protocol's limit of 10000",
        ),
        (8_000_000, "holds 8000000 moving objects"),
    ] {
        let answer = empty_objects_answer(answers.path(), objects);
        let (outcome, dir, _) = run_system(&shell(&format!("{HELLO}; {answer}; exec cat >/dev/null"), 20.0));
        assert_error(&outcome, dir.path(), "at step 0 (t = 0 s)", what);
    }
}

/// Anything the system writes after its last answer is an error: another
/// answer, or a flood of them, which sightline reads no further than its
/// first message (it used to read on, in memory, until the step timeout).
#[test]
fn output_after_the_last_answer_is_an_error() {
    for script in [
        format!("{HELLO}; {EMPTY_ANSWER}; cat >/dev/null; {EMPTY_ANSWER}"),
        format!("{HELLO}; {EMPTY_ANSWER}; cat >/dev/null; while :; do {EMPTY_ANSWER} || exit; done"),
        format!("{HELLO}; while :; do {EMPTY_ANSWER} || exit; done"),
    ] {
        let (outcome, dir, elapsed) = run_system(&shell(&script, 20.0));
        assert_error(
            &outcome,
            dir.path(),
            "after the last step",
            "it wrote 10 bytes after the last step",
        );
        assert!(elapsed < Duration::from_secs(15), "took {elapsed:?}");
    }
    // Bytes that are no message: the four of a length over the limit.
    let script = format!("{HELLO}; {EMPTY_ANSWER}; cat >/dev/null; yes");
    let (outcome, dir, _) = run_system(&shell(&script, 20.0));
    assert_error(
        &outcome,
        dir.path(),
        "after the last step",
        "it wrote 4 bytes after the last step",
    );
}

/// A wrong announcement is shown escaped and bounded, on the error's one
/// line: no control character or terminal escape of the system's reaches
/// sightline's standard error.
#[test]
fn a_wrong_announcement_is_shown_escaped() {
    let script = r"printf '\030\000\000\000sightline-osi-sut/1\n\033[2J'; exec cat >/dev/null";
    let (outcome, dir, _) = run_system(&shell(script, 5.0));
    assert_error(
        &outcome,
        dir.path(),
        "before step 0",
        r"it announced `sightline-osi-sut/1\n\u{1b}[2J`, and sightline speaks",
    );
    assert!(!outcome.stderr.contains('\x1b'), "{outcome}");
}

/// Whether a process whose command line holds `marker` runs (read from
/// `/proc`, as `pgrep -f` does).
fn running(marker: &str) -> bool {
    let processes = std::fs::read_dir("/proc").expect("/proc lists the processes");
    processes.flatten().any(|entry| {
        std::fs::read(entry.path().join("cmdline")).is_ok_and(|line| {
            let line: Vec<u8> = line.iter().map(|&b| if b == 0 { b' ' } else { b }).collect();
            String::from_utf8_lossy(&line).contains(marker)
        })
    })
}

/// Runs the system `script` (a shell script) with a step timeout of 0.5 s,
/// which it outlasts at step 0: an error, within 20 s.
fn run_past_its_timeout(script: &str) {
    let (outcome, dir, elapsed) = run_system(&shell(script, 0.5));
    assert_error(
        &outcome,
        dir.path(),
        "at step 0",
        "it did not answer within 0.5 s (its step_timeout)",
    );
    assert!(elapsed < Duration::from_secs(20), "took {elapsed:?}");
}

#[test]
fn a_system_past_its_step_timeout_is_an_error_and_is_killed() {
    // A sleep no other test starts, to find it.
    let marker = "sleep 31.25";
    run_past_its_timeout(&format!("{HELLO}; exec {marker}"));
    assert!(!running(marker), "the system was left running");
}

/// What the system started goes with it: a helper it left running (holding
/// sightline's standard error, so a pipeline reading it, as this test's, would
/// wait for the helper) is killed with the system.
// See: session 17's outside check.
#[test]
fn a_helper_the_system_started_is_killed_with_it() {
    let (system, helper) = ("sleep 33.5", "sleep 34.25");
    run_past_its_timeout(&format!("{HELLO}; {helper} & exec {system}"));
    assert!(
        !running(system) && !running(helper),
        "the system or its helper was left running"
    );
}

/// A system that exits 0 after its last answer while a helper it started
/// holds its output open is done when it exits: the helper is killed, and the
/// run is judged, not held up to the step timeout (60 s here).
// See: session 20's outside check.
#[test]
fn a_helper_holding_the_output_open_does_not_hold_up_the_run() {
    let helper = "sleep 35.75";
    let script = format!("{HELLO}; {EMPTY_ANSWER}; {helper} & cat >/dev/null; exit 0");
    let (outcome, _dir, elapsed) = run_system(&shell(&script, 60.0));
    outcome.assert_exit(1);
    assert!(outcome.stdout.contains("fail: SUT-REC"), "{outcome}");
    assert!(elapsed < Duration::from_secs(20), "took {elapsed:?}");
    assert!(!running(helper), "the helper was left running");
}

#[test]
fn an_interrupted_run_reaps_its_system() {
    let marker = "sleep 32.75";
    let dir = temp_dir();
    let file = dir.path().join("sut.yaml");
    let system = shell(&format!("{HELLO}; exec {marker}"), 60.0);
    std::fs::write(&file, ONE_STEP.replace("{system}", &system)).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["run", arg(&file), "--out", arg(&dir.path().join("out"))])
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(20);
    while !running(marker) {
        assert!(Instant::now() < deadline, "the system never started");
        std::thread::sleep(Duration::from_millis(20));
    }
    let sent = Command::new("kill")
        .args(["-s", "INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status}");
    assert!(!running(marker), "the system was left running");
    assert!(!dir.path().join("out").join("results.json").exists());
}

#[test]
fn a_system_that_detects_nothing_is_judged_and_fails_on_recall() {
    let (outcome, dir, _) = run_system(&shell(&format!("{HELLO}; {EMPTY_ANSWER}; exec cat >/dev/null"), 5.0));
    outcome.assert_exit(1);
    let results = read_json(&dir.path().join("out").join("results.json"));
    // The car is in the lidar's sight at the one step, and nothing matched it.
    assert_eq!(verdict(&results, "SUT-REC"), ("fail".into(), Some(0.0), Some(1)));
    // No detection: nothing to judge a ghost on.
    assert_eq!(verdict(&results, "SUT-GHOST").0, "not_exercised");
}

/// The one car in sight, reported exactly where it is (the ego at (0, −10)
/// facing north, the car at (0, 20)) as a pedestrian: matched, so no ghost,
/// and of the wrong class, so the class accuracy is 0 over 1 matched
/// detection. By class, the detections reported as cars are none; the
/// matched detections of cars are the one.
/// Precision and ghosts select by the reported class, so `pedestrian` is
/// accepted there though no pedestrian can occur: the one detection, matched.
#[test]
fn a_system_reporting_the_wrong_class_is_judged_by_class() {
    let requirements = r#"  - { id: CLS, text: c, check: { metric: sut_class_accuracy, at_least: 0.5 } }
  - { id: PRE-CARS, text: p, check: { metric: sut_precision, at_least: 0.5, objects: { classes: [car] } } }
  - { id: POS-CARS, text: e, check: { metric: sut_position_error, at_most: 0.5, objects: { classes: [car] } } }
  - { id: PRE-PED, text: p, check: { metric: sut_precision, at_least: 0.5, objects: { classes: [pedestrian] } } }
  - { id: GHOST-BIKE, text: g, check: { metric: sut_ghosts, at_most: 0, objects: { classes: [bicycle] } } }
"#;
    let system = shell(&format!("{HELLO}; {PEDESTRIAN_ANSWER}; exec cat >/dev/null"), 5.0);
    let (outcome, dir, _) = run_with(&system, requirements);
    outcome.assert_exit(1);
    let results = read_json(&dir.path().join("out").join("results.json"));
    assert_eq!(verdict(&results, "SUT-REC"), ("pass".into(), Some(1.0), Some(1)));
    assert_eq!(verdict(&results, "SUT-GHOST"), ("pass".into(), Some(0.0), Some(1)));
    assert_eq!(verdict(&results, "CLS"), ("fail".into(), Some(0.0), Some(1)));
    assert_eq!(metric(&results, "sut_class_accuracy"), (Some(0.0), 1));
    assert_eq!(verdict(&results, "PRE-CARS"), ("not_exercised".into(), None, Some(0)));
    let (status, error, n) = verdict(&results, "POS-CARS");
    assert_eq!((status.as_str(), n), ("pass", Some(1)));
    assert!(error.unwrap() < 1e-9, "{error:?}");
    assert_eq!(verdict(&results, "PRE-PED"), ("pass".into(), Some(1.0), Some(1)));
    assert_eq!(verdict(&results, "GHOST-BIKE"), ("not_exercised".into(), None, Some(0)));
}

#[test]
fn a_scenario_with_a_system_is_neither_recorded_nor_sharded() {
    let dir = temp_dir();
    let file = dir.path().join("sut.yaml");
    std::fs::write(&file, ONE_STEP.replace("{system}", &shell("exit 0", 1.0))).unwrap();
    let out = dir.path().join("out");
    for flag in [["--record", ""], ["--osi", ""], ["--shard", "1/2"]] {
        let mut args = vec!["run", arg(&file), "--out", arg(&out), flag[0]];
        args.extend(Some(flag[1]).filter(|f| !f.is_empty()));
        let outcome = super::support::sightline(&args);
        outcome.assert_exit(2);
        assert!(outcome.stderr.contains("neither recorded nor sharded"), "{outcome}");
    }
}

/// The Python with osi-python (see [`tool`]).
fn python() -> Option<PathBuf> {
    tool(PYTHON_VAR, "a Python with osi-python")
}

/// Runs scenario `text` (an example's, changed) with the example systems'
/// Python first on PATH, `jobs` threads; its exit code and results.json.
fn run_example(python: &Path, text: &str, jobs: &str) -> (Option<i32>, serde_json::Value) {
    let dir = temp_dir();
    let file = dir.path().join("example.yaml");
    std::fs::write(&file, text).unwrap();
    run_file(python, &file, &dir.path().join("out"), jobs)
}

/// Runs scenario `file` into `out` with the example systems' Python first on
/// PATH, `jobs` threads; its exit code and results.json.
fn run_file(python: &Path, file: &Path, out: &Path, jobs: &str) -> (Option<i32>, serde_json::Value) {
    let bin = python.parent().expect("the Python is in a folder");
    let path = std::env::join_paths(
        std::iter::once(bin.to_path_buf()).chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
    )
    .unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["run", arg(file), "--out", arg(out), "--jobs", jobs])
        .current_dir(root())
        .env("PATH", path)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let results = out.join("results.json");
    assert!(
        results.exists(),
        "no evidence\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    (output.status.code(), read_json(&results))
}

fn example(name: &str) -> String {
    std::fs::read_to_string(root().join("examples/osi-sut").join(name)).unwrap()
}

/// `metric`'s value and n in results.json.
fn metric(results: &serde_json::Value, metric: &str) -> (Option<f64>, u64) {
    let entry = &results["metrics"][metric];
    (entry["value"].as_f64(), entry["n"].as_u64().expect("an n"))
}

#[test]
fn the_example_tracker_passes_and_the_flawed_one_fails_on_recall() {
    let Some(python) = python() else { return };
    let (code, results) = run_example(&python, &example("tracker.yaml"), "2");
    assert_eq!(code, Some(0), "{results:#}");
    let (code, flawed) = run_example(&python, &example("flawed_tracker.yaml"), "2");
    assert_eq!(code, Some(1));
    let failing = crate::support::failing(&flawed);
    assert_eq!(failing, ["SUT-REC-01", "SUT-REC-PED", "SUT-DELAY-01"]);
    // The same road users in sight: the flaw is in what it reports of them.
    assert_eq!(
        metric(&results, "sut_recall"),
        (Some(1.0), metric(&flawed, "sut_recall").1)
    );
    let (recall, n) = metric(&flawed, "sut_recall");
    assert!(recall.unwrap() < 0.95 && n > 50, "{recall:?} over {n}");
    // Road user by road user: the good tracker detects each as it comes into
    // sight; the flawed one detects the two partly hidden on their way in
    // (car_east behind the building's corner, walker_b behind walker_a) later,
    // so warns of them later, and walker_a, hidden all along, by neither.
    let good = records(&results);
    let bad = records(&flawed);
    let ids = |records: &[serde_json::Value]| records.iter().map(|r| r["id"].clone()).collect::<Vec<_>>();
    assert_eq!(ids(&good), ["car_east", "car_west", "walker_a", "walker_b"]);
    assert_eq!(ids(&bad), ids(&good));
    for (good, bad) in good.iter().zip(&bad) {
        let id = &good["id"];
        assert_eq!(good["first_in_sight"], bad["first_in_sight"], "{id}");
        assert_eq!(good["first_detected"], good["first_in_sight"], "{id}");
        assert_eq!(
            good["delay"].as_f64(),
            good["first_in_sight"].as_f64().map(|_| 0.0),
            "{id}"
        );
        if let (Some(sight), Some(detected)) = (bad["first_in_sight"].as_f64(), bad["first_detected"].as_f64()) {
            assert!(
                (bad["delay"].as_f64().unwrap() - (detected - sight)).abs() < 1e-9,
                "{id}"
            );
            let lead = |r: &serde_json::Value| r["lead"].as_f64().unwrap();
            assert!((lead(good) - lead(bad) - (detected - sight)).abs() < 1e-9, "{id}");
        }
    }
    let late: Vec<_> = bad
        .iter()
        .filter(|r| r["delay"].as_f64() > Some(0.0))
        .map(|r| r["id"].clone())
        .collect();
    assert_eq!(late, ["car_east", "walker_b"]);
    assert!(bad[2]["first_in_sight"].is_null() && bad[2]["lead"].is_null());
}

/// The records of the system's road users in results.json.
fn records(results: &serde_json::Value) -> Vec<serde_json::Value> {
    let list = &results["sweep"][0]["system"]["objects"];
    assert_eq!(list["omitted"], 0);
    list["records"].as_array().expect("a list of records").clone()
}

/// A system on another agent than the ego (a connected car north of the
/// building) has the pedestrians in sight long before the ego does: its
/// anticipation is first seen by the ego − first detected, or for walker_a,
/// whom the ego never sees, closest approach − first detected; neither the
/// ego nor the host is listed. Served by the ego's own lidar, the system
/// anticipates nothing, and the same requirement fails.
#[test]
fn a_system_serving_another_agent_anticipates_what_the_ego_cannot_see() {
    let Some(python) = python() else { return };
    let requirement = "requirements:\n  - id: SUT-ANT-01\n    text: The system knows of each pedestrian 1 s before \
                       the ego sees it.\n    check: { per_object: sut_anticipation, at_least: 1, objects: { classes: \
                       [pedestrian] } }\n";
    let base = example("tracker.yaml");
    let base = format!("{}{requirement}", &base[..base.find("requirements:").unwrap()]);
    let car_west = base
        .replace(
            "speed: { target: 8 } }",
            "speed: { target: 8 }, connected: true, sensors: [lidar] }",
        )
        .replace("agent: ego", "agent: car_west");
    let (code, results) = run_example(&python, &car_west, "2");
    assert_eq!(code, Some(0), "{results:#}");
    let records = records(&results);
    let ids: Vec<_> = records.iter().map(|r| r["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["car_east", "walker_a", "walker_b"]);
    for record in &records[1..] {
        let detected = record["first_detected"].as_f64().unwrap();
        let ego_knows = record["first_seen_by_ego"]
            .as_f64()
            .unwrap_or(record["closest"]["time"].as_f64().unwrap());
        let anticipation = record["anticipation"].as_f64().unwrap();
        assert!((anticipation - (ego_knows - detected)).abs() < 1e-9, "{record}");
        assert!(anticipation > 5.0, "{record}");
    }
    assert!(records[1]["first_seen_by_ego"].is_null());
    assert_eq!(results["requirements"][0]["n"], 2, "{results:#}");
    let (code, ego) = run_example(&python, &base, "2");
    assert_eq!((code, crate::support::failing(&ego)), (Some(1), vec!["SUT-ANT-01"]));
}

/// `objects` on the system's metrics, on the examples' scene. The
/// figures are counted independently of the judge, from the same scene's OSI
/// trace (`run --osi` without the system): the lidar has the cars in sight at
/// 101 object-steps and the pedestrians at 11, fully in sight (what the
/// flawed tracker keeps, coasting 0.3 s) at 89 and 6 of them. The tracker
/// matches all; the `walkway` strip holds the pedestrians' paths and neither
/// road; the circle `far` is out of the lidar's range. Both trackers report
/// each road user's class from the ground truth.
#[test]
fn objects_select_a_systems_object_steps_and_detections_by_id_class_and_area() {
    let Some(python) = python() else { return };
    let selections = r#"areas:
  - { id: walkway, polygon: [[-30, -2], [30, -2], [30, 2], [-30, 2]] }
  - { id: far, circle: { center: [45, -45], radius: 3 } }
system_under_test:"#;
    let extra = r#"
  - { id: CARS, text: c, check: { metric: sut_recall, at_least: 0.9, objects: { classes: [car] } } }
  - { id: CAR-IDS, text: c, check: { metric: sut_recall, at_least: 0.9, objects: { ids: [car_east, car_west] } } }
  - { id: WALKWAY, text: w, check: { metric: sut_recall, at_least: 0.9, objects: { areas: [walkway] } } }
  - { id: FAR, text: f, check: { metric: sut_latency, at_most: 1, objects: { areas: [far] } } }
  - { id: CAR-LAT, text: l, check: { metric: sut_latency, at_most: 1, objects: { classes: [car] } } }
  - { id: PRE-CARS, text: p, check: { metric: sut_precision, at_least: 0.9, objects: { classes: [car] } } }
  - { id: CLS-CARS, text: k, check: { metric: sut_class_accuracy, at_least: 0.9, objects: { classes: [car] } } }
  - { id: POS-FAR, text: e, check: { metric: sut_position_error, at_most: 1, objects: { areas: [far] } } }
  - { id: GHOST-PED, text: g, check: { metric: sut_ghosts, at_most: 0, objects: { classes: [pedestrian] } } }
"#;
    let scenario = |name: &str| example(name).replacen("system_under_test:", selections, 1) + extra;
    let (_, good) = run_example(&python, &scenario("tracker.yaml"), "2");
    let (_, flawed) = run_example(&python, &scenario("flawed_tracker.yaml"), "2");
    let recall = |verdict: &str, matched: f64, n: u64| (verdict.to_string(), Some(matched / n as f64), Some(n));
    for id in ["CARS", "CAR-IDS"] {
        assert_eq!(verdict(&good, id), recall("pass", 101.0, 101));
        assert_eq!(verdict(&flawed, id), recall("fail", 89.0, 101));
    }
    for id in ["SUT-REC-PED", "WALKWAY"] {
        assert_eq!(verdict(&good, id), recall("pass", 11.0, 11));
        assert_eq!(verdict(&flawed, id), recall("fail", 6.0, 11));
    }
    // The classes partition the whole: 101 + 11 object-steps, 89 + 6 matched.
    assert_eq!(metric(&flawed, "sut_recall"), (Some(95.0 / 112.0), 112));
    // Each class's latency is over its own road users: the two cars.
    for results in [&good, &flawed] {
        assert_eq!(verdict(results, "CAR-LAT").2, Some(2));
        let objects = &requirement(results, "CAR-LAT")["check"]["objects"];
        assert_eq!(objects, &serde_json::json!({ "classes": ["car"] }));
    }
    // Detections by the class they report: the pedestrians' are the matched
    // pedestrians in sight (11 and 6), the cars' the rest; every one matched
    // a road user of its class.
    for (results, pedestrians) in [(&good, 11), (&flawed, 6)] {
        let (_, all) = metric(results, "sut_precision");
        assert_eq!(
            verdict(results, "SUT-PRE-PED"),
            ("pass".into(), Some(1.0), Some(pedestrians))
        );
        assert_eq!(
            verdict(results, "PRE-CARS"),
            ("pass".into(), Some(1.0), Some(all - pedestrians))
        );
        assert_eq!(
            verdict(results, "CLS-CARS"),
            ("pass".into(), Some(1.0), Some(all - pedestrians))
        );
        assert_eq!(metric(results, "sut_class_accuracy"), (Some(1.0), all));
        assert_eq!(
            verdict(results, "GHOST-PED"),
            ("pass".into(), Some(0.0), Some(pedestrians))
        );
        assert_eq!(verdict(results, "POS-FAR"), ("not_exercised".into(), None, Some(0)));
    }
    // Nothing in the selection: not exercised, naming what it looked for.
    assert_eq!(verdict(&good, "FAR"), ("not_exercised".to_string(), None, Some(0)));
    assert_eq!(
        requirement(&good, "FAR")["message"],
        "nothing to judge: no road users detected after first in sight (in far) to measure sut_latency on"
    );
}

#[test]
fn a_deterministic_system_gives_the_same_results_whatever_the_thread_count() {
    let Some(python) = python() else { return };
    let (file, dir) = (Path::new("examples/osi-sut/tracker.yaml"), temp_dir());
    let (_, one) = run_file(&python, file, &dir.path().join("one"), "1");
    let (_, three) = run_file(&python, file, &dir.path().join("three"), "3");
    let redact = |results: &serde_json::Value| redact_results_json(&serde_json::to_string_pretty(results).unwrap());
    assert_eq!(redact(&one), redact(&three));
}

#[test]
fn each_key_of_system_under_test_changes_the_judgement() {
    let Some(python) = python() else { return };
    let base = example("tracker.yaml");
    let (_, before) = run_example(&python, &base, "2");
    let judged = |text: String| run_example(&python, &text, "2").1;
    // gate: below the tracker's 0.5 m cells, most detections match nothing.
    let tight = judged(base.replace("gate: 2", "gate: 0.05"));
    assert!(
        metric(&tight, "sut_ghosts").0 > Some(0.0),
        "{:?}",
        metric(&tight, "sut_ghosts")
    );
    // min_existence: coasting tracks (0.7) are no longer judged.
    let strict = judged(base.replace("gate: 2", "gate: 2\n  min_existence: 0.8"));
    assert!(metric(&strict, "sut_precision").1 < metric(&before, "sut_precision").1);
    // command: the flawed tracker detects less.
    let flawed = judged(base.replace("tracker.py]", "flawed_tracker.py]"));
    assert!(metric(&flawed, "sut_recall").0 < metric(&before, "sut_recall").0);
    // sensors and agent: a second, forward-only sensor on the ego, and a
    // connected car, each sees other road users.
    let two = base.replace("sensors: [lidar] }", "sensors: [lidar, front] }").replace(
        "lidar: { range: 40, fov_deg: 360 }",
        "lidar: { range: 40, fov_deg: 360 }\n  front: { range: 15, fov_deg: 30 }",
    );
    let (_, all) = run_example(&python, &two, "2");
    let front = judged(two.replace("agent: ego", "agent: ego\n  sensors: [1]"));
    assert!(metric(&front, "sut_recall").1 < metric(&all, "sut_recall").1);
    let cooperating = base.replace(
        "speed: { target: 9 } }",
        "speed: { target: 9 }, connected: true, sensors: [lidar] }",
    );
    let (_, ego) = run_example(&python, &cooperating, "2");
    let car = judged(cooperating.replace("agent: ego", "agent: car_east"));
    assert_ne!(metric(&car, "sut_recall").1, metric(&ego, "sut_recall").1);
}

#[test]
fn step_timeout_bounds_a_slow_system() {
    let Some(python) = python() else { return };
    // The tracker takes some milliseconds a step: a microsecond is too short.
    let dir = temp_dir();
    let file = dir.path().join("slow.yaml");
    std::fs::write(
        &file,
        example("tracker.yaml").replace("step_timeout: 5", "step_timeout: 0.001"),
    )
    .unwrap();
    let bin = python.parent().unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let output = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["run", arg(&file), "--out", arg(&dir.path().join("out"))])
        .current_dir(root())
        .env("PATH", path)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("did not answer within 0.001 s"), "{stderr}");
}
