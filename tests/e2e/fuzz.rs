//! Structured mutation fuzzing under caps (issue 15): the real binary on
//! mutated scenarios, damaged recordings and damaged shard files, each run
//! under 2 GiB of address space and 20 s of wall-clock time
//! ([`sightline_capped`]).
//!
//! Scenarios: every bundled scenario and valid fixture, parsed with serde_yaml
//! (a parser independent of sightline's) and first *reduced* so that a valid
//! run is cheap in a debug build ([`reduced`]), then given one to three
//! [`Mutation`]s drawn by proptest strategies, written back as YAML text and
//! given to `check`, then to `run` when `check` accepts it. Recordings and
//! shards: bytes flipped, cut short or spliced ([`Damage`]), given to `replay`
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
use serde_yaml::{Mapping, Value};

use crate::support::{
    Outcome, RECORDING, caps_available, evidence_problem, files_under, root, sightline_capped, temp_dir,
};

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
/// report's grid pictures (`perception.snapshot`) dropped, every sweep axis to its
/// first value (and the requirements and references that select sweep points
/// with `where`, and the record section's point, dropped with them),
/// `semantic.runs` to 1 and checks over seeds to [`REDUCED_SEEDS`]. Imported
/// files are named by absolute path, so the text can be written anywhere.
pub fn reduced(path: &str) -> Value {
    let file = root().join(path);
    let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("failed to read {path}: {e}"));
    let mut tree: Value = serde_yaml::from_str(&text).unwrap_or_else(|e| panic!("{path} is not YAML: {e}"));
    let step = tree["time"]["step"].as_f64();
    if let (Some(step), Some(duration)) = (step, tree["time"]["duration"].as_f64()) {
        let kept = if tree.get("traces").is_some() {
            REDUCED_TRACE_SECONDS
        } else {
            step * REDUCED_STEPS
        };
        tree["time"]["duration"] = Value::from(duration.min(kept));
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
    }
    if let Some(record) = tree.get_mut("record").and_then(Value::as_mapping_mut) {
        record.remove("point");
        record.remove("where");
    }
    let directory = file.parent().expect("a file has a folder");
    for import in tree
        .get_mut("traces")
        .and_then(Value::as_mapping_mut)
        .into_iter()
        .flat_map(|t| t.values_mut())
    {
        if let Some(name) = import.as_str() {
            *import = Value::from(directory.join(name).to_string_lossy().into_owned());
        }
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

// ---------------------------------------------------------------------------
// Mutations of the YAML tree

/// One step of a path from the root of a YAML tree.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    Key(Value),
    Item(usize),
}

/// An edit of a scenario. Each `Index` picks among the nodes the edit applies
/// to (numbers, lists, keys, …) in the tree as it is when the edit is made; an
/// edit with nothing to apply to does nothing.
#[derive(Debug, Clone)]
enum Mutation {
    /// A number replaced by one of [`EXTREMES`].
    Extreme { at: Index, value: usize },
    /// A value replaced by one of another type, made from it.
    Retype { at: Index, to: Kind },
    /// A mapping's key deleted.
    DeleteKey { at: Index },
    /// A key written a second time in its mapping, with the same value.
    DuplicateKey { at: Index },
    /// A list's item repeated `times` more times.
    RepeatItem { at: Index, item: Index, times: usize },
    /// A list cut to its first `keep` items.
    Truncate { at: Index, keep: usize },
    /// A list of two numbers (a point) given a third.
    ThirdCoordinate { at: Index },
    /// Sweep axes over `axes` numeric settings with many values each (more
    /// than 10 000 points in all).
    WideSweep { at: Index, axes: usize, values: usize },
    /// A value replaced by lists (flow style) or mappings (block style, as a
    /// new top-level key) nested `depth` deep.
    DeepNesting { at: Index, depth: usize, block: bool },
    /// A value anchored and another replaced by an alias of it.
    Alias { anchor: Index, alias: Index },
    /// A value given a YAML tag.
    Tag { at: Index, tag: &'static str },
    /// An `id` renamed, so that what refers to it dangles.
    Dangle { at: Index },
}

/// The type a value is changed to.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Null,
    Number,
    String,
    List,
    Mapping,
}

/// Extreme numbers, as written in the file.
const EXTREMES: [&str; 13] = [
    "0",
    "-1",
    "1e-12",
    "1e-308",
    "1e12",
    "1e308",
    "-1e308",
    ".inf",
    "-.inf",
    ".nan",
    "9223372036854775808",
    "18446744073709551616",
    "123456789012345678901234567890123456789",
];

/// Tags a value is given.
const TAGS: [&str; 4] = ["!!float", "!!str", "!!int", "!custom"];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<Index>(), 0..EXTREMES.len()).prop_map(|(at, value)| Mutation::Extreme { at, value }),
        2 => (any::<Index>(), prop_oneof![
            Just(Kind::Null), Just(Kind::Number), Just(Kind::String), Just(Kind::List), Just(Kind::Mapping)
        ]).prop_map(|(at, to)| Mutation::Retype { at, to }),
        1 => any::<Index>().prop_map(|at| Mutation::DeleteKey { at }),
        1 => any::<Index>().prop_map(|at| Mutation::DuplicateKey { at }),
        1 => (any::<Index>(), any::<Index>(), prop::sample::select(vec![1, 9, 999]))
            .prop_map(|(at, item, times)| Mutation::RepeatItem { at, item, times }),
        1 => (any::<Index>(), 0..2usize).prop_map(|(at, keep)| Mutation::Truncate { at, keep }),
        1 => any::<Index>().prop_map(|at| Mutation::ThirdCoordinate { at }),
        1 => (any::<Index>(), 1..=3usize, prop::sample::select(vec![150, 1000]))
            .prop_map(|(at, axes, values)| Mutation::WideSweep { at, axes, values }),
        1 => (any::<Index>(), prop::sample::select(vec![64, 1000, 2500]), any::<bool>())
            .prop_map(|(at, depth, block)| Mutation::DeepNesting { at, depth, block }),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(anchor, alias)| Mutation::Alias { anchor, alias }),
        1 => (any::<Index>(), prop::sample::select(TAGS.to_vec())).prop_map(|(at, tag)| Mutation::Tag { at, tag }),
        1 => any::<Index>().prop_map(|at| Mutation::Dangle { at }),
    ]
}

/// A case: a base (by index into [`bases`]) and its mutations, in order.
#[derive(Debug, Clone)]
struct Case {
    base: Index,
    mutations: Vec<Mutation>,
}

fn case() -> impl Strategy<Value = Case> {
    (any::<Index>(), prop::collection::vec(mutation(), 1..=3)).prop_map(|(base, mutations)| Case { base, mutations })
}

/// A tree being mutated, and the text that replaces its placeholders once it
/// is written: what a serde_yaml tree cannot hold (a duplicate key, a tag on a
/// plain scalar, an anchor, an integer beyond 64 bits).
#[derive(Default)]
struct Draft {
    tree: Value,
    /// Placeholder strings in the tree and the text each stands for.
    raw: Vec<(String, String)>,
    /// Pairs of placeholders: the first written becomes `&name VALUE`, the
    /// other `*name`; each with the flow text of the value it replaced.
    aliases: Vec<[(String, String); 2]>,
    /// Text appended to the document.
    appendix: String,
}

impl Draft {
    /// A fresh placeholder standing for `text`.
    fn placeholder(&mut self, text: String) -> Value {
        // The closing `z` keeps one token from being the start of another.
        let token = format!("fuzz-raw-{}z", self.raw.len());
        self.raw.push((token.clone(), text));
        Value::from(token)
    }

    /// The YAML text of the mutated scenario.
    fn text(&self) -> String {
        let mut text = serde_yaml::to_string(&self.tree).expect("a tree is written");
        for (i, [(first, first_flow), (second, second_flow)]) in self.aliases.iter().enumerate() {
            let (anchor, alias, flow) = match (text.find(first), text.find(second)) {
                (Some(a), Some(b)) if b < a => (second, first, second_flow),
                _ => (first, second, first_flow),
            };
            text = text.replacen(anchor, &format!("&fuzz{i} {flow}"), 1);
            text = text.replace(alias, &format!("*fuzz{i}"));
        }
        // Later placeholders may sit inside the text of earlier ones.
        for (token, raw) in self.raw.iter().rev() {
            text = text.replace(token, raw);
        }
        text + &self.appendix
    }

    fn apply(&mut self, mutation: &Mutation) {
        match mutation {
            Mutation::Extreme { at, value } => {
                if let Some(path) = pick(&self.tree, at, |_, v| v.is_number()) {
                    *node_mut(&mut self.tree, &path) = self.placeholder(EXTREMES[*value].to_string());
                }
            }
            Mutation::Retype { at, to } => {
                if let Some(path) = pick(&self.tree, at, |_, _| true) {
                    let old = node_mut(&mut self.tree, &path);
                    *old = match to {
                        Kind::Null => Value::Null,
                        Kind::Number => Value::from(7),
                        Kind::String => Value::from(flow(old)),
                        Kind::List => Value::Sequence(vec![old.clone()]),
                        Kind::Mapping => Value::Mapping(Mapping::from_iter([(Value::from("value"), old.clone())])),
                    };
                }
            }
            Mutation::DeleteKey { at } => {
                if let Some((parent, key)) = pick_key(&self.tree, at) {
                    mapping_mut(&mut self.tree, &parent).remove(&key);
                }
            }
            Mutation::DuplicateKey { at } => {
                if let Some((parent, key)) = pick_key(&self.tree, at) {
                    let copy = self.placeholder(flow(&key));
                    let mapping = mapping_mut(&mut self.tree, &parent);
                    let value = mapping[&key].clone();
                    mapping.insert(copy, value);
                }
            }
            Mutation::RepeatItem { at, item, times } => {
                if let Some(path) = pick(&self.tree, at, |_, v| v.as_sequence().is_some_and(|s| !s.is_empty())) {
                    let list = sequence_mut(&mut self.tree, &path);
                    let i = item.index(list.len());
                    let copies = vec![list[i].clone(); *times];
                    list.splice(i..i, copies);
                }
            }
            Mutation::Truncate { at, keep } => {
                if let Some(path) = pick(&self.tree, at, |_, v| v.as_sequence().is_some_and(|s| s.len() > *keep)) {
                    sequence_mut(&mut self.tree, &path).truncate(*keep);
                }
            }
            Mutation::ThirdCoordinate { at } => {
                let point = |v: &Value| {
                    v.as_sequence()
                        .is_some_and(|s| s.len() == 2 && s.iter().all(Value::is_number))
                };
                if let Some(path) = pick(&self.tree, at, |_, v| point(v)) {
                    sequence_mut(&mut self.tree, &path).push(Value::from(1.5));
                }
            }
            Mutation::WideSweep { at, axes, values } => self.wide_sweep(at, *axes, *values),
            Mutation::DeepNesting { at, depth, block } => {
                if *block {
                    let nested: String = (1..=*depth).map(|d| format!("{}a:\n", " ".repeat(d))).collect();
                    self.appendix
                        .push_str(&format!("nested:\n{nested}{}1\n", " ".repeat(depth + 1)));
                } else if let Some(path) = pick(&self.tree, at, |_, _| true) {
                    let text = format!("{}1{}", "[".repeat(*depth), "]".repeat(*depth));
                    *node_mut(&mut self.tree, &path) = self.placeholder(text);
                }
            }
            Mutation::Alias { anchor, alias } => {
                let any = |_: &[Step], _: &Value| true;
                if let (Some(first), Some(second)) = (pick(&self.tree, anchor, any), pick(&self.tree, alias, any)) {
                    let i = self.aliases.len();
                    let tokens = [format!("fuzz-anchor-{i}z"), format!("fuzz-alias-{i}z")];
                    let flows = [
                        flow(node_mut(&mut self.tree, &first)),
                        flow(node_mut(&mut self.tree, &second)),
                    ];
                    // The second path may lie inside the first node: replace it first.
                    *node_mut(&mut self.tree, &second) = Value::from(tokens[1].clone());
                    if let Some(node) = node_mut_checked(&mut self.tree, &first) {
                        *node = Value::from(tokens[0].clone());
                    }
                    let [a, b] = tokens;
                    let [fa, fb] = flows;
                    self.aliases.push([(a, fa), (b, fb)]);
                }
            }
            Mutation::Tag { at, tag } => {
                if let Some(path) = pick(&self.tree, at, |_, _| true) {
                    let text = format!("{tag} {}", flow(node_mut(&mut self.tree, &path)));
                    *node_mut(&mut self.tree, &path) = self.placeholder(text);
                }
            }
            Mutation::Dangle { at } => {
                let is_id = |path: &[Step], v: &Value| v.is_string() && path.last() == Some(&Step::Key("id".into()));
                if let Some(path) = pick(&self.tree, at, is_id) {
                    let node = node_mut(&mut self.tree, &path);
                    *node = Value::from(format!("{}_gone", node.as_str().unwrap_or_default()));
                }
            }
        }
    }

    /// Sweeps `axes` numeric settings (or one, when there are fewer) with
    /// `values` values each, or 30 000 values for a single axis: more than
    /// 10 000 points either way, so a valid file would be refused by its size.
    fn wide_sweep(&mut self, at: &Index, axes: usize, values: usize) {
        let settings = numeric_settings(&self.tree);
        let (axes, values) = if axes > 1 && settings.len() >= axes {
            (axes, values)
        } else {
            (1, 30_000)
        };
        let chosen: Vec<(String, f64, bool)> = if settings.is_empty() {
            vec![("seed".into(), 1.0, true)]
        } else {
            let start = at.index(settings.len());
            settings.into_iter().cycle().skip(start).take(axes).collect()
        };
        let sweep = sweep_mut(&mut self.tree);
        for (setting, first, whole) in chosen {
            let list = (0..values)
                .map(|i| {
                    if whole {
                        Value::from(first as i64 + i as i64)
                    } else {
                        Value::from(first + i as f64 * 1e-6 * first.abs().max(1.0))
                    }
                })
                .collect();
            sweep.insert(Value::from(setting), Value::Sequence(list));
        }
    }
}

/// The mutated text of a case.
fn mutated(case: &Case) -> (String, String) {
    let (name, tree) = &bases()[case.base.index(bases().len())];
    let mut draft = Draft {
        tree: tree.clone(),
        ..Draft::default()
    };
    for mutation in &case.mutations {
        draft.apply(mutation);
    }
    (name.clone(), draft.text())
}

/// Every node but the root, in document order, with its path.
fn nodes(tree: &Value) -> Vec<(Vec<Step>, &Value)> {
    fn walk<'a>(value: &'a Value, path: &mut Vec<Step>, found: &mut Vec<(Vec<Step>, &'a Value)>) {
        let children: Vec<(Step, &Value)> = match value {
            Value::Sequence(items) => items.iter().enumerate().map(|(i, v)| (Step::Item(i), v)).collect(),
            Value::Mapping(m) => m.iter().map(|(k, v)| (Step::Key(k.clone()), v)).collect(),
            _ => Vec::new(),
        };
        for (step, child) in children {
            path.push(step);
            found.push((path.clone(), child));
            walk(child, path, found);
            path.pop();
        }
    }
    let mut found = Vec::new();
    walk(tree, &mut Vec::new(), &mut found);
    found
}

/// The path of one of the nodes `keep` accepts, chosen by `at`.
fn pick(tree: &Value, at: &Index, keep: impl Fn(&[Step], &Value) -> bool) -> Option<Vec<Step>> {
    let found: Vec<Vec<Step>> = nodes(tree)
        .into_iter()
        .filter(|(p, v)| keep(p, v))
        .map(|(p, _)| p)
        .collect();
    (!found.is_empty()).then(|| found[at.index(found.len())].clone())
}

/// One key of one mapping, chosen by `at`: the mapping's path and the key.
fn pick_key(tree: &Value, at: &Index) -> Option<(Vec<Step>, Value)> {
    let mut path = pick(tree, at, |p, _| matches!(p.last(), Some(Step::Key(_))))?;
    let Some(Step::Key(key)) = path.pop() else {
        unreachable!("picked by its last step")
    };
    Some((path, key))
}

fn node_mut_checked<'a>(tree: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    path.iter().try_fold(tree, |node, step| match (step, node) {
        (Step::Key(key), Value::Mapping(m)) => m.get_mut(key),
        (Step::Item(i), Value::Sequence(s)) => s.get_mut(*i),
        _ => None,
    })
}

#[track_caller]
fn node_mut<'a>(tree: &'a mut Value, path: &[Step]) -> &'a mut Value {
    node_mut_checked(tree, path).expect("the path was just found")
}

#[track_caller]
fn mapping_mut<'a>(tree: &'a mut Value, path: &[Step]) -> &'a mut Mapping {
    node_mut(tree, path).as_mapping_mut().expect("a mapping")
}

#[track_caller]
fn sequence_mut<'a>(tree: &'a mut Value, path: &[Step]) -> &'a mut Vec<Value> {
    node_mut(tree, path).as_sequence_mut().expect("a list")
}

/// The dotted paths of the numbers reached through mappings only (settings a
/// sweep may name), outside the sections that are not settings, with each
/// number and whether it is whole.
fn numeric_settings(tree: &Value) -> Vec<(String, f64, bool)> {
    const NOT_SETTINGS: [&str; 7] = [
        "sightline",
        "sweep",
        "sweeps",
        "requirements",
        "references",
        "vary",
        "record",
    ];
    nodes(tree)
        .into_iter()
        .filter_map(|(path, value)| {
            let keys: Vec<&str> = path
                .iter()
                .map(|step| match step {
                    Step::Key(Value::String(key)) => Some(key.as_str()),
                    _ => None,
                })
                .collect::<Option<_>>()?;
            let number = value.as_f64()?;
            (!NOT_SETTINGS.contains(&keys[0])).then(|| (keys.join("."), number, value.is_i64() || value.is_u64()))
        })
        .collect()
}

/// The sweep a new axis goes into: `sweep`, else the first of `sweeps`, else a
/// new `sweep`.
fn sweep_mut(tree: &mut Value) -> &mut Mapping {
    let root = tree.as_mapping_mut().expect("a scenario is a mapping");
    let in_sweeps = !root.contains_key("sweep")
        && root
            .get("sweeps")
            .and_then(Value::as_sequence)
            .is_some_and(|s| s.first().is_some_and(Value::is_mapping));
    if in_sweeps {
        return root["sweeps"][0].as_mapping_mut().expect("checked above");
    }
    let sweep = root
        .entry("sweep".into())
        .or_insert_with(|| Value::Mapping(Mapping::new()));
    if !sweep.is_mapping() {
        *sweep = Value::Mapping(Mapping::new());
    }
    sweep.as_mapping_mut().expect("made a mapping above")
}

/// A value as YAML flow text, on one line; placeholders left bare.
fn flow(value: &Value) -> String {
    match value {
        Value::Null => "null".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(_) => serde_yaml::to_string(value)
            .expect("a number is written")
            .trim_end()
            .into(),
        Value::String(s) if s.starts_with("fuzz-") || plain(s) => s.clone(),
        Value::String(s) => serde_json::to_string(s).expect("a string is written"),
        Value::Sequence(items) => format!("[{}]", items.iter().map(flow).collect::<Vec<_>>().join(", ")),
        Value::Mapping(m) => {
            let entries: Vec<String> = m.iter().map(|(k, v)| format!("{}: {}", flow(k), flow(v))).collect();
            format!("{{{}}}", entries.join(", "))
        }
        Value::Tagged(tagged) => format!("{} {}", tagged.tag, flow(&tagged.value)),
    }
}

/// Whether a string reads back as the same string when written without quotes.
fn plain(s: &str) -> bool {
    !s.is_empty()
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && serde_yaml::from_str::<Value>(s).is_ok_and(|v| v.as_str() == Some(s))
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

/// Runs `run` on every case, on as many threads as there are cores, and
/// panics listing the failures after saving each input with its report.
fn run_campaign<C: Sync>(name: &str, seed: u64, cases: &[C], run: impl Fn(&C) -> Option<Failure> + Sync) {
    let started = Instant::now();
    let next = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut failures: Vec<(usize, Failure)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut failed = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(case) = cases.get(i) else { break failed };
                        failed.extend(run(case).map(|f| (i, f)));
                    }
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a worker ran"))
            .collect()
    });
    // Shown with `--nocapture`: what the budget buys.
    eprintln!(
        "{} {name} cases from seed {seed} in {:.1?}",
        cases.len(),
        started.elapsed()
    );
    if failures.is_empty() {
        return;
    }
    failures.sort_by_key(|(i, _)| *i);
    let dir = failures_dir();
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("failed to create {}: {e}", dir.display()));
    let mut message = format!(
        "{} of {} {name} cases broke the contract (seed {seed}); inputs in {}\n",
        failures.len(),
        cases.len(),
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

/// Damage done to a file's bytes.
#[derive(Debug, Clone)]
enum Damage {
    /// Bytes at `at` xored with `mask` (never 0).
    Flip { at: Vec<Index>, mask: u8 },
    /// The file cut short at `at`.
    Truncate { at: Index },
    /// `len` bytes from `from` copied over those at `to`.
    Splice { from: Index, to: Index, len: usize },
    /// The file cut at `at` and continued from `from` of another good file.
    Graft { at: Index, other: Index, from: Index },
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        3 => (prop::collection::vec(any::<Index>(), 1..=4), 1..=255u8).prop_map(|(at, mask)| Damage::Flip { at, mask }),
        1 => any::<Index>().prop_map(|at| Damage::Truncate { at }),
        1 => (any::<Index>(), any::<Index>(), 1..4096usize).prop_map(|(from, to, len)| Damage::Splice { from, to, len }),
        1 => (any::<Index>(), any::<Index>(), any::<Index>()).prop_map(|(at, other, from)| Damage::Graft { at, other, from }),
    ]
}

/// `good[which]` with `damage` done to it, grafting from the others.
fn damaged(good: &[Vec<u8>], which: &Index, damage: &Damage) -> Vec<u8> {
    let mut bytes = good[which.index(good.len())].clone();
    let len = bytes.len();
    match damage {
        Damage::Flip { at, mask } => {
            for at in at {
                bytes[at.index(len)] ^= mask;
            }
        }
        Damage::Truncate { at } => bytes.truncate(at.index(len)),
        Damage::Splice { from, to, len: n } => {
            let (from, to) = (from.index(len), to.index(len));
            let n = (*n).min(len - from).min(len - to);
            bytes.copy_within(from..from + n, to);
        }
        Damage::Graft { at, other, from } => {
            let other = &good[other.index(good.len())];
            bytes.truncate(at.index(len));
            bytes.extend_from_slice(&other[from.index(other.len())..]);
        }
    }
    bytes
}

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
