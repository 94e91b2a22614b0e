//! Structured mutation fuzzing under caps (issue 15): the real binary on
//! mutated scenarios, damaged recordings and damaged shard files, each run
//! under 2 GiB of address space and 20 s of wall-clock time
//! ([`sightline_capped`]).
//!
//! Scenarios: every bundled scenario and valid fixture, parsed with serde_yaml
//! (a parser independent of sightline's) and first *reduced* so that a valid
//! run is cheap in a debug build ([`reduced`]), then given one to three
//! [`mutation::Mutation`]s drawn by proptest strategies, written back as YAML text and
//! given to `check`, then to `run` when `check` accepts it. Recordings and
//! shards: bytes flipped, cut short or spliced ([`damage::Damage`]), given to `replay`
//! and `merge`.
//!
//! A case fails when the run ends by a signal (an abort, a crash, SIGKILL at the
//! time cap), exits with another code than 0, 1 or 2, panics, refuses without a
//! location, or leaves an evidence folder holding anything but a whole set. Every
//! failing input is saved under `target/tmp/fuzz/` with the command and what
//! went wrong, and the first few are printed.
//!
//! The case count and seed are fixed, so CI is reproducible; to search longer:
//!
//! ```text
//! SIGHTLINE_FUZZ_CASES=5000 SIGHTLINE_FUZZ_SEED=7 cargo test --test e2e fuzz::
//! ```

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use proptest::prelude::*;
use proptest::sample::Index;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_yaml::Value;

use damage::{damage, damaged};
use mutation::{Case, case};

use crate::support::{
    Outcome, RECORDING, caps_available, evidence_problem, files_under, root, sightline_capped, temp_dir,
};

// The edits of a scenario's YAML tree.
#[path = "fuzz/mutation.rs"]
mod mutation;

// The damage done to recordings and shard files.
#[path = "fuzz/damage.rs"]
mod damage;

/// Cases per campaign (scenarios, recordings, shards); default [`CASES`].
const CASES_VAR: &str = "SIGHTLINE_FUZZ_CASES";

/// The seed of the cases; default [`SEED`].
const SEED_VAR: &str = "SIGHTLINE_FUZZ_SEED";

/// Mutated scenarios per CI run: about 70 s on two cores in a debug build
/// (docs/qualification.md).
const CASES: usize = 1500;

/// Damaged recordings and shard files per CI run, each: a few seconds in all.
const DAMAGED_CASES: usize = 300;

/// The seed of the CI run.
const SEED: u64 = 15;

/// Where the failing inputs are kept, for CI logs and for re-testing.
fn failures_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz")
}

/// The folders whose `*.yaml` files are the campaign's bases.
const BASE_DIRS: [&str; 2] = ["scenarios", "tests/fixtures/valid"];

/// The steps a reduced scenario simulates.
const REDUCED_STEPS: f64 = 5.0;

/// The seconds a reduced scenario that replays traces simulates: the bundled
/// SUMO scenario's ego enters its trace at 7 s.
const REDUCED_TRACE_SECONDS: f64 = 8.0;

/// The seeds a reduced check over seeds asks for.
const REDUCED_SEEDS: u64 = 2;

/// A scenario made cheap to run in a debug build, keeping every section:
/// `time.duration` cut to [`REDUCED_STEPS`] steps (or
/// [`REDUCED_TRACE_SECONDS`] when it replays traces) and the time of the
/// report's grid pictures (`perception.snapshot`) dropped, windows of road
/// users (`between`) ending with it, agents that would start after it
/// starting at once, every sweep axis to its
/// first value (and the requirements and references that select sweep points
/// with `where`, and the record section's point, dropped with them),
/// `semantic.runs` to 1 and checks over seeds to [`REDUCED_SEEDS`]. Imported
/// files (`traces`, `map`) are named by absolute path, so the text can be
/// written anywhere.
pub fn reduced(path: &str) -> Value {
    let file = root().join(path);
    let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("failed to read {path}: {e}"));
    let mut tree: Value = serde_yaml::from_str(&text).unwrap_or_else(|e| panic!("{path} is not YAML: {e}"));
    let step = tree["time"]["step"].as_f64();
    let mut end = None;
    if let (Some(step), Some(duration)) = (step, tree["time"]["duration"].as_f64()) {
        let kept = if tree.get("traces").is_some() {
            REDUCED_TRACE_SECONDS
        } else {
            step * REDUCED_STEPS
        };
        end = Some(duration.min(kept));
        tree["time"]["duration"] = Value::from(duration.min(kept));
    }
    // An agent starts by the shorter run's last step, or it would never enter.
    if let (Some(step), Some(end)) = (step, end) {
        for agent in tree
            .get_mut("agents")
            .and_then(Value::as_sequence_mut)
            .into_iter()
            .flatten()
        {
            let start = agent.get_mut("start").and_then(|s| s.get_mut("time"));
            if let Some(time) = start.filter(|t| t.as_f64().is_some_and(|t| t > end - step)) {
                *time = Value::from(0.0);
            }
        }
    }
    if let Some(perception) = tree.get_mut("perception").and_then(Value::as_mapping_mut) {
        perception.remove("snapshot");
    }
    if let Some(sweep) = tree.get_mut("sweep") {
        first_values(sweep);
    }
    for sweep in tree
        .get_mut("sweeps")
        .and_then(Value::as_sequence_mut)
        .into_iter()
        .flatten()
    {
        first_values(sweep);
    }
    if let Some(runs) = tree.get_mut("semantic").and_then(|s| s.get_mut("runs")) {
        *runs = Value::from(1);
    }
    for list in ["requirements", "references"] {
        if let Some(items) = tree.get_mut(list).and_then(Value::as_sequence_mut) {
            items.retain(|item| item.get("where").is_none());
        }
    }
    for requirement in tree
        .get_mut("requirements")
        .and_then(Value::as_sequence_mut)
        .into_iter()
        .flatten()
    {
        if let Some(seeds) = requirement.get_mut("check").and_then(|c| c.get_mut("seeds")) {
            *seeds = Value::from(REDUCED_SEEDS);
        }
        // A window of road users ends by the shorter run's end.
        let window = requirement
            .get_mut("check")
            .and_then(|c| c.get_mut("objects"))
            .and_then(|o| o.get_mut("between"))
            .and_then(Value::as_sequence_mut);
        if let (Some(window), Some(end)) = (window, end) {
            let from = window[0].as_f64().unwrap_or(0.0).min(end / 2.0);
            *window = vec![Value::from(from), Value::from(end)];
        }
    }
    if let Some(record) = tree.get_mut("record").and_then(Value::as_mapping_mut) {
        record.remove("point");
        record.remove("where");
    }
    let directory = file.parent().expect("a file has a folder");
    let absolute = |import: &mut Value| {
        if let Some(name) = import.as_str() {
            *import = Value::from(directory.join(name).to_string_lossy().into_owned());
        }
    };
    for import in tree
        .get_mut("traces")
        .and_then(Value::as_mapping_mut)
        .into_iter()
        .flat_map(|t| t.values_mut())
    {
        absolute(import);
    }
    if let Some(map) = tree.get_mut("map").and_then(|m| m.get_mut("opendrive")) {
        absolute(map);
    }
    tree
}

/// Keeps the first value of every axis of a sweep.
fn first_values(sweep: &mut Value) {
    for values in sweep.as_mapping_mut().into_iter().flat_map(|m| m.values_mut()) {
        if let Some(list) = values.as_sequence_mut() {
            list.truncate(1);
        }
    }
}

/// The campaign's bases: every bundled scenario and valid fixture, reduced.
fn bases() -> &'static [(String, Value)] {
    static BASES: OnceLock<Vec<(String, Value)>> = OnceLock::new();
    BASES.get_or_init(|| {
        let mut paths: Vec<String> = BASE_DIRS
            .iter()
            .flat_map(|dir| {
                files_under(&root().join(dir))
                    .into_iter()
                    .filter(|p| p.parent() == Some(Path::new("")) && p.extension().is_some_and(|e| e == "yaml"))
                    .map(move |p| format!("{dir}/{}", p.display()))
            })
            .collect();
        paths.sort();
        paths.into_iter().map(|path| (path.clone(), reduced(&path))).collect()
    })
}

/// The seed and case count of this run.
fn campaign(default_cases: usize) -> (u64, usize) {
    let number = |var: &str| {
        std::env::var(var)
            .ok()
            .map(|v| v.parse().unwrap_or_else(|e| panic!("{var}={v}: {e}")))
    };
    let seed = number(SEED_VAR).unwrap_or(SEED);
    let cases = number(CASES_VAR).map_or(default_cases, |n| n as usize);
    (seed, cases)
}

/// `count` values of `strategy`, drawn from `seed` alone.
fn draw<S: Strategy>(strategy: S, seed: u64, count: usize) -> Vec<S::Value> {
    let mut bytes = [0; 32];
    for chunk in bytes.chunks_mut(8) {
        chunk.copy_from_slice(&seed.to_le_bytes());
    }
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    (0..count)
        .map(|_| strategy.new_tree(&mut runner).expect("the strategy draws").current())
        .collect()
}

/// The base a case mutates, and its mutated text.
fn mutated(case: &Case) -> (&'static str, String) {
    let (name, tree) = &bases()[case.base.index(bases().len())];
    (name, case.text(tree))
}

// ---------------------------------------------------------------------------
// Running cases

/// A case that broke the contract.
struct Failure {
    /// What the input was made from and how.
    what: String,
    /// The input.
    input: Vec<u8>,
    /// The input's file name in the case's folder.
    file: &'static str,
    /// The command and what went wrong.
    report: String,
}

/// The failing cases after which a campaign stops: enough to show the
/// defects, without spending the time cap on each of hundreds more.
const MAX_FAILURES: usize = 20;

/// Runs `run` on every case (or until [`MAX_FAILURES`] have failed), on as
/// many threads as there are cores, and panics listing the failures after
/// saving each input with its report.
fn run_campaign<C: Sync>(name: &str, seed: u64, cases: &[C], run: impl Fn(&C) -> Option<Failure> + Sync) {
    let started = Instant::now();
    let next = AtomicUsize::new(0);
    let failed = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut failures: Vec<(usize, Failure)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut found = Vec::new();
                    while failed.load(Ordering::Relaxed) < MAX_FAILURES {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(case) = cases.get(i) else { break };
                        if let Some(failure) = run(case) {
                            failed.fetch_add(1, Ordering::Relaxed);
                            found.push((i, failure));
                        }
                    }
                    found
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a worker ran"))
            .collect()
    });
    // Shown with `--nocapture`: what the budget buys.
    let ran = next.load(Ordering::Relaxed).min(cases.len());
    eprintln!("{ran} {name} cases from seed {seed} in {:.1?}", started.elapsed());
    if failures.is_empty() {
        return;
    }
    failures.sort_by_key(|(i, _)| *i);
    let dir = failures_dir();
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("failed to create {}: {e}", dir.display()));
    let stopped = if ran < cases.len() { " (stopped there)" } else { "" };
    let mut message = format!(
        "{} of {ran} {name} cases broke the contract{stopped} (seed {seed}); inputs in {}\n",
        failures.len(),
        dir.display()
    );
    for (shown, (i, failure)) in failures.iter().enumerate() {
        let extension = failure.file.rsplit('.').next().unwrap_or("bin");
        let saved = dir.join(format!("{name}-{seed}-{i}.{extension}"));
        let report = format!(
            "{}\n(run in a folder holding the input as {})\n{}",
            failure.what, failure.file, failure.report
        );
        std::fs::write(&saved, &failure.input).expect("the failing input is saved");
        std::fs::write(saved.with_extension("txt"), &report).expect("the report is saved");
        message.push_str(&format!("\n=== case {i}: {}\n", saved.display()));
        if shown < 5 {
            if let Ok(text) = std::str::from_utf8(&failure.input) {
                message.push_str(&format!("--- {}\n{}\n", failure.file, cut(text, 3000)));
            }
            message.push_str(&format!("{report}\n"));
        } else {
            message.push_str(&format!("{}\n", failure.report.lines().next().unwrap_or_default()));
        }
    }
    panic!("{message}");
}

/// At most `limit` bytes of `text` (at a character boundary), marked when cut.
fn cut(text: &str, limit: usize) -> String {
    match text.char_indices().nth(limit) {
        Some((end, _)) => format!("{}\n[… {} more bytes]", &text[..end], text.len() - end),
        None => text.to_string(),
    }
}

/// Why the run of `args` in `dir` broke the contract, if it did.
fn judge(dir: &Path, args: &[&str]) -> Result<Outcome, String> {
    let outcome = sightline_capped(dir, args);
    match outcome.broken_contract() {
        Some(why) => Err(format!("{why}\n{outcome}")),
        None => Ok(outcome),
    }
}

/// Checks a scenario text, and runs it when `check` accepts it.
fn scenario_case(what: String, text: String) -> Option<Failure> {
    let tmp = temp_dir();
    let dir = tmp.path();
    std::fs::write(dir.join("case.yaml"), &text).expect("the case is written");
    let fail = |report: String| {
        Some(Failure {
            what: what.clone(),
            input: text.clone().into_bytes(),
            file: "case.yaml",
            report,
        })
    };
    let check = match judge(dir, &["check", "case.yaml"]) {
        Ok(check) => check,
        Err(report) => return fail(report),
    };
    if check.code != Some(0) {
        return None;
    }
    let run = match judge(dir, &["run", "case.yaml", "--out", "out"]) {
        Ok(run) => run,
        Err(report) => return fail(report),
    };
    evidence_problem(&dir.join("out"), run.code).and_then(|problem| fail(format!("{problem}\n{run}")))
}

/// Mutated bundled scenarios and fixtures are refused with a location or run
/// to a whole evidence set, within 20 s and 2 GiB. See: issue 15.
#[test]
fn mutated_scenarios_are_refused_or_run_within_the_caps() {
    if !caps_available() {
        return;
    }
    let (seed, count) = campaign(CASES);
    let cases = draw(case(), seed, count);
    run_campaign("scenario", seed, &cases, |case| {
        let (base, text) = mutated(case);
        scenario_case(format!("{base} with {:?}", case.mutations), text)
    });
}

/// The reduced bases are valid and run to a whole evidence set within the
/// caps: otherwise the campaign would test refusals only.
#[test]
fn the_reduced_bases_run() {
    if !caps_available() {
        return;
    }
    for (name, tree) in bases() {
        let text = serde_yaml::to_string(tree).expect("a tree is written");
        let tmp = temp_dir();
        std::fs::write(tmp.path().join("case.yaml"), &text).unwrap();
        let check = sightline_capped(tmp.path(), ["check", "case.yaml"]);
        assert_eq!(check.code, Some(0), "{name} reduced is refused\n{check}\n{text}");
        let run = sightline_capped(tmp.path(), ["run", "case.yaml", "--out", "out"]);
        assert!(matches!(run.code, Some(0 | 1)), "{name} reduced\n{run}");
        assert_eq!(evidence_problem(&tmp.path().join("out"), run.code), None, "{name}");
    }
}

// ---------------------------------------------------------------------------
// Damaged recordings and shard files

/// The reduced bundled scenarios whose recordings are damaged: a collective
/// perception world and a semantic world.
const RECORDED: [&str; 2] = [
    "scenarios/roundabout-six-agents.yaml",
    "scenarios/urban-rsu-semantic.yaml",
];

/// `run --record` of each of [`RECORDED`], reduced: the recordings' bytes.
fn recordings() -> Vec<Vec<u8>> {
    RECORDED
        .iter()
        .map(|path| {
            let tmp = temp_dir();
            let text = serde_yaml::to_string(&reduced(path)).expect("a tree is written");
            std::fs::write(tmp.path().join("case.yaml"), text).unwrap();
            let run = sightline_capped(tmp.path(), ["run", "case.yaml", "--record", "--out", "out"]);
            assert!(matches!(run.code, Some(0 | 1)), "{path}\n{run}");
            std::fs::read(tmp.path().join("out").join(RECORDING)).expect("the run recorded")
        })
        .collect()
}

/// Damaged recordings of the bundled scenarios are refused (or re-checked)
/// by `replay` within the caps, never crash it. See: issue 15.
#[test]
fn damaged_recordings_are_refused_within_the_caps() {
    if !caps_available() {
        return;
    }
    let good = recordings();
    let (seed, count) = campaign(DAMAGED_CASES);
    let cases = draw((any::<Index>(), damage()), seed, count);
    run_campaign("recording", seed, &cases, |(which, damage)| {
        let bytes = damaged(&good, which, damage);
        let tmp = temp_dir();
        std::fs::write(tmp.path().join(RECORDING), &bytes).unwrap();
        let what = format!("{} recorded, with {damage:?}", RECORDED[which.index(good.len())]);
        judge(tmp.path(), &["replay", RECORDING]).err().map(|report| Failure {
            what,
            input: bytes,
            file: RECORDING,
            report,
        })
    });
}

/// The bundled scenario whose shards are damaged, reduced: three sweep points.
const SHARDED: &str = "scenarios/urban-rsu-semantic.yaml";

/// The scenario text of [`SHARDED`] and its two shard files, made in `dir`
/// (the shards name the scenario by its path there, `scenario.yaml`).
fn shard_campaign(dir: &Path) -> (String, [Vec<u8>; 2]) {
    let text = serde_yaml::to_string(&reduced(SHARDED)).expect("a tree is written");
    std::fs::write(dir.join("scenario.yaml"), &text).unwrap();
    let shards = [1, 2].map(|k| {
        let spec = format!("{k}/2");
        let run = sightline_capped(dir, ["run", "scenario.yaml", "--shard", &spec, "--out", "shards"]);
        assert_eq!(run.code, Some(0), "{run}");
        std::fs::read(dir.join(format!("shards/shard-{k}-of-2.cbor"))).expect("the shard is written")
    });
    (text, shards)
}

/// A damaged shard file is refused by `merge` within the caps, and nothing is
/// written. See: issue 15.
#[test]
fn damaged_shards_are_refused_within_the_caps() {
    if !caps_available() {
        return;
    }
    let setup = temp_dir();
    let (scenario, good) = shard_campaign(setup.path());
    let (seed, count) = campaign(DAMAGED_CASES);
    let cases = draw((any::<Index>(), damage()), seed, count);
    run_campaign("shard", seed, &cases, |(which, damage)| {
        let k = which.index(good.len());
        let bytes = damaged(&good, which, damage);
        let tmp = temp_dir();
        let dir = tmp.path();
        std::fs::write(dir.join("scenario.yaml"), &scenario).unwrap();
        std::fs::write(dir.join("damaged.cbor"), &bytes).unwrap();
        std::fs::write(dir.join("good.cbor"), &good[1 - k]).unwrap();
        let what = format!("shard {} of 2 of {SHARDED} reduced, with {damage:?}", k + 1);
        let fail = |report: String| {
            Some(Failure {
                what: what.clone(),
                input: bytes.clone(),
                file: "damaged.cbor",
                report,
            })
        };
        let merge = match judge(dir, &["merge", "good.cbor", "damaged.cbor", "--out", "out"]) {
            Ok(merge) => merge,
            Err(report) => return fail(report),
        };
        evidence_problem(&dir.join("out"), merge.code).and_then(|problem| fail(format!("{problem}\n{merge}")))
    });
}
