//! The mutations of the fuzz campaign: edits of a scenario's YAML tree
//! (serde_yaml), drawn by proptest strategies, and the text they write, with
//! what a tree cannot hold (a duplicate key, a tag, an anchor and its alias, an
//! integer beyond 64 bits, block-style nesting) put in as text.

use proptest::prelude::*;
use proptest::sample::Index;
use serde_yaml::{Mapping, Value};

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
pub(super) enum Mutation {
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
pub(super) enum Kind {
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

/// A case: a base (an index into the campaign's bases) and its mutations, in
/// order.
#[derive(Debug, Clone)]
pub(super) struct Case {
    pub(super) base: Index,
    pub(super) mutations: Vec<Mutation>,
}

impl Case {
    /// The YAML text of `base` with the case's mutations made to it.
    pub(super) fn text(&self, base: &Value) -> String {
        let mut draft = Draft {
            tree: base.clone(),
            ..Draft::default()
        };
        for mutation in &self.mutations {
            draft.apply(mutation);
        }
        draft.text()
    }
}

pub(super) fn case() -> impl Strategy<Value = Case> {
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
