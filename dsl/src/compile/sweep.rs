//! Sweeps: axes read from the spanned tree in file order, one tree per
//! combination with the swept values substituted, so a bad value is reported
//! where it is written, and the distinct configurations the combinations give.

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasher, Hasher};
use std::io;

use foldhash::fast::{FixedState, FoldHasher};

use super::context::{Context, has, locate_key};
use super::ignored::ignored;
use super::kind::Kind;
use crate::de::{closest, one_of};
use crate::error::{ErrorKind, Location};
use crate::model::{Label, Point, Setup};
use crate::path::{Path, Segment};
use crate::schema::{AGENTS, check_setting};
use crate::yaml::{Key, Node, Value};

/// The most sweep combinations one scenario may have, all sweeps together.
pub const MAX_POINTS: usize = 10_000;

/// The most nodes all combinations may copy together (combinations × nodes of
/// the file): each combination is compiled from its own copy of the file.
pub const MAX_COPIED_NODES: usize = 2_000_000;

/// The most bytes the distinct points' compiled settings may take together,
/// measured as JSON while they are compiled.
pub const MAX_SETTINGS_BYTES: usize = 512 << 20;

/// Top-level sections a sweep may set.
const SWEEPABLE: [&str; 14] = [
    "seed",
    "grid",
    "field",
    "fusion",
    "decision",
    "time",
    "sensor_models",
    "localization",
    "perception",
    "traffic",
    "driving",
    "v2x",
    "semantic",
    AGENTS,
];

/// One axis as written: the path it sets and its value nodes.
pub(super) struct AxisNodes<'a> {
    /// Where the axis is written (`sweep.fusion`, `sweeps[1].seed`).
    pub(super) here: Path,
    pub(super) path: Path,
    pub(super) dotted: String,
    pub(super) key_location: Location,
    pub(super) values: &'a [Node],
}

/// Reads and checks the sweeps: the `sweep` mapping, or each mapping of `sweeps`,
/// whose combinations each copy a tree of `copied` nodes.
pub(super) fn sweeps<'a>(ctx: &mut Context<'a>, copied: usize) -> Vec<Vec<AxisNodes<'a>>> {
    let tree = ctx.tree;
    let root = Path::root();
    if tree.get("sweep").is_some() && tree.get("sweeps").is_some() {
        ctx.error(
            &root.key("sweeps"),
            ErrorKind::Invalid("give `sweep` (one sweep) or `sweeps` (several), not both".into()),
        );
        return Vec::new();
    }
    let one = tree.get("sweep").is_some();
    let sweeps: Vec<Vec<AxisNodes<'a>>> = sweep_mappings(tree)
        .into_iter()
        .enumerate()
        .map(|(i, sweep)| {
            let at = if one {
                root.key("sweep")
            } else {
                root.key("sweeps").index(i)
            };
            axes(ctx, sweep, &at)
        })
        .collect();
    let section = root.key(if tree.get("sweep").is_some() { "sweep" } else { "sweeps" });
    let count = sweeps.iter().try_fold(0usize, |total, axes| {
        axes.iter()
            .try_fold(1usize, |n, a| n.checked_mul(a.values.len()))
            .and_then(|n| total.checked_add(n))
    });
    match count {
        Some(n) if n <= MAX_POINTS => {
            if n.saturating_mul(copied) > MAX_COPIED_NODES {
                ctx.error_at_key(
                    &section,
                    ErrorKind::TooLarge(format!(
                        "the sweeps' {n} combinations each compile a copy of the scenario's {copied} nodes, \
                         more than {MAX_COPIED_NODES} nodes in all; sweep fewer values or split the scenario"
                    )),
                );
            }
        }
        _ => ctx.error_at_key(
            &section,
            ErrorKind::TooLarge(format!("the sweeps have more than {MAX_POINTS} points")),
        ),
    }
    sweeps
}

/// The file with each setting it omits that every sweep sets, given the first
/// value a sweep sets it to: a key every point takes from a sweep counts as
/// given, so the file need not write a value the sweeps replace. The file as
/// written is checked on this tree; a key a sweep may not set adds nothing
/// (its errors are [`sweeps`]'s to report).
pub(super) fn completed(tree: &Node) -> Node {
    let written: Vec<Vec<(Path, &Node)>> = sweep_mappings(tree)
        .into_iter()
        .map(|sweep| match &sweep.value {
            Value::Map(entries) => entries
                .iter()
                .filter_map(|(key, node)| match &node.value {
                    Value::Seq(values) => {
                        let (path, _) = settable(tree, &key.name, ("sweep", "a sweep")).ok()?;
                        Some((path, values.first()?))
                    }
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        })
        .collect();
    let mut completed = tree.clone();
    for (path, first) in written.iter().flatten() {
        let everywhere = written.iter().all(|axes| axes.iter().any(|(p, _)| is_prefix(p, path)));
        if everywhere && !has(&completed, path) {
            // A path that cannot be set is refused where the sweep writes it.
            let _ = set(&mut completed, path.segments(), (*first).clone(), first.location);
        }
    }
    completed
}

/// The sweep mappings as written: `sweep`, or each entry of `sweeps` (none when
/// the file gives both, an error [`sweeps`] reports).
fn sweep_mappings(tree: &Node) -> Vec<&Node> {
    match (tree.get("sweep"), tree.get("sweeps")) {
        (Some(sweep), None) => vec![sweep],
        (
            None,
            Some(Node {
                value: Value::Seq(items),
                ..
            }),
        ) => items.iter().collect(),
        _ => Vec::new(),
    }
}

/// Refuses each value the file writes that every sweep point replaces: every
/// sweep has an axis that sets it or a section around it. The error is at the
/// key in `file` and names the axes that replace it.
pub(super) fn refuse_replaced(ctx: &mut Context<'_>, file: &Node, sweeps: &[Vec<AxisNodes<'_>>]) {
    let mut refused: Vec<&Path> = Vec::new();
    for axis in sweeps.iter().flatten() {
        if refused.contains(&&axis.path) || !has(file, &axis.path) {
            continue;
        }
        let replacing: Option<Vec<&AxisNodes<'_>>> = sweeps
            .iter()
            .map(|axes| axes.iter().find(|a| is_prefix(&a.path, &axis.path)))
            .collect();
        let Some(replacing) = replacing else {
            continue;
        };
        let names: Vec<String> = replacing.iter().map(|a| format!("`{}`", a.here)).collect();
        let verb = if names.len() == 1 { "replaces" } else { "replace" };
        ctx.error_at(
            locate_key(file, &axis.path),
            &axis.path,
            ErrorKind::NoEffect(format!(
                "{} {verb} it at every sweep point; leave it out of the file",
                names.join(" and ")
            )),
        );
        refused.push(&axis.path);
    }
}

/// Reads and checks the axes of one sweep mapping, at `prefix` in the file.
fn axes<'a>(ctx: &mut Context<'a>, sweep: &'a Node, prefix: &Path) -> Vec<AxisNodes<'a>> {
    let tree = ctx.tree;
    let Value::Map(entries) = &sweep.value else {
        return Vec::new(); // serde has already rejected anything but a mapping
    };
    let mut axes: Vec<AxisNodes<'a>> = Vec::new();
    for (key, node) in entries {
        let here = prefix.key(&key.name);
        let Some((path, _)) = setting(ctx, key, &here, ("sweep", "a sweep")) else {
            continue;
        };
        let Value::Seq(values) = &node.value else {
            continue; // serde has already rejected a non-list
        };
        if values.is_empty() {
            ctx.error(
                &here,
                ErrorKind::Invalid("a sweep axis needs at least one value".into()),
            );
            continue;
        }
        if let Some(i) = first_repeat(values) {
            ctx.error(&here.index(i), ErrorKind::Invalid("this value is listed twice".into()));
            continue;
        }
        if let Some(other) = axes
            .iter()
            .find(|a| is_prefix(&a.path, &path) || is_prefix(&path, &a.path))
        {
            ctx.error_at(
                key.location,
                &here,
                ErrorKind::Invalid(format!("overlaps the sweep key `{}`", other.dotted)),
            );
            continue;
        }
        let mut probe = tree.clone();
        if let Err(message) = set(&mut probe, path.segments(), values[0].clone(), key.location) {
            ctx.error_at(key.location, &here, ErrorKind::Invalid(message));
            continue;
        }
        axes.push(AxisNodes {
            here,
            path,
            dotted: key.name.clone(),
            key_location: key.location,
            values,
        });
    }
    axes
}

/// Checks that the key `key` (written at `here`) names a setting that a sweep
/// or `vary` may set (`words`: the verb and the noun of messages); returns its
/// path in the tree and its JSON Schema.
pub(super) fn setting(
    ctx: &mut Context<'_>,
    key: &Key,
    here: &Path,
    words: (&str, &str),
) -> Option<(Path, serde_json::Value)> {
    settable(ctx.tree, &key.name, words)
        .map_err(|kind| ctx.error_at(key.location, here, kind))
        .ok()
}

/// The path in `tree` and the JSON Schema of the setting `name` names, if a
/// sweep or `vary` (`words`) may set it; else why not.
fn settable(tree: &Node, name: &str, (verb, noun): (&str, &str)) -> Result<(Path, serde_json::Value), ErrorKind> {
    let path = resolve(tree, name)?;
    let Some(Segment::Key(section)) = path.segments().first() else {
        return Err(ErrorKind::Invalid(
            "expected a dotted path such as `fusion.method`".into(),
        ));
    };
    if !SWEEPABLE.contains(&section.as_str()) {
        return Err(ErrorKind::Invalid(format!(
            "cannot {verb} `{section}`; {noun} sets the simulation: {}",
            SWEEPABLE.map(|s| format!("`{s}`")).join(", ")
        )));
    }
    if name == "time.start" {
        return Err(ErrorKind::Invalid(format!(
            "cannot {verb} `time.start`: it sets the recording's clock once for the whole run, not a \
             simulation setting of a point"
        )));
    }
    let names: Vec<&str> = name.split('.').collect();
    match check_setting(&names) {
        Ok(schema) => match Kind::of(tree).and_then(|kind| ignored(kind, &path)) {
            Some(why) => Err(ErrorKind::NoEffect(why.into())),
            None => Ok((path, schema)),
        },
        Err(no) => {
            let message = if no.allowed.is_empty() {
                format!("`{name}` names no setting: `{}` is not a mapping", no.parent)
            } else {
                let allowed: Vec<&str> = no.allowed.iter().map(String::as_str).collect();
                let hint = closest(&no.unknown, allowed.iter().copied())
                    .map(|c| format!(" (did you mean `{}.{c}`?)", no.parent))
                    .unwrap_or_default();
                format!(
                    "`{name}` names no setting: `{}` has {}{hint}",
                    no.parent,
                    one_of(allowed.iter())
                )
            };
            Err(ErrorKind::DanglingReference(message))
        }
    }
}

/// The path in `tree` of a dotted setting: its keys, except that in
/// `agents.<id>.…` the id names the entry of `agents` with that `id`.
pub(super) fn resolve(tree: &Node, dotted: &str) -> Result<Path, ErrorKind> {
    let Some(path) = Path::parse_dotted(dotted) else {
        return Err(ErrorKind::Invalid(
            "expected a dotted path such as `fusion.method`".into(),
        ));
    };
    let [Segment::Key(section), Segment::Key(id), rest @ ..] = path.segments() else {
        return Ok(path);
    };
    if section != AGENTS {
        return Ok(path);
    }
    let ids: Vec<&str> = match tree.get(AGENTS) {
        Some(Node {
            value: Value::Seq(agents),
            ..
        }) => agents
            .iter()
            .map(|agent| match agent.get("id").map(|id| &id.value) {
                Some(Value::Str(id)) => id.as_str(),
                _ => "",
            })
            .collect(),
        _ => Vec::new(),
    };
    let Some(index) = ids.iter().position(|i| i == id) else {
        let hint = closest(id, ids.iter().copied())
            .map(|c| format!(" (did you mean `{c}`?)"))
            .unwrap_or_default();
        return Err(ErrorKind::DanglingReference(format!(
            "`{dotted}` names no agent: `{id}` is not the id of an entry of `agents`{hint}"
        )));
    };
    match rest.first() {
        None => Err(ErrorKind::Invalid(format!(
            "`{dotted}` names an agent, not one of its settings (such as `{dotted}.speed.target`)"
        ))),
        Some(Segment::Key(key)) if key == "id" => Err(ErrorKind::Invalid(
            "an agent's id names it; it cannot be swept or varied".into(),
        )),
        Some(_) => Ok(rest
            .iter()
            .cloned()
            .fold(Path::root().key(AGENTS).index(index), Path::push)),
    }
}

/// Every choice of one value per axis, first axis outermost.
pub(super) fn choices(axes: &[AxisNodes<'_>]) -> Vec<Vec<usize>> {
    axes.iter().fold(vec![Vec::new()], |acc, axis| {
        acc.iter()
            .flat_map(|prefix| {
                (0..axis.values.len()).map(move |i| {
                    let mut choice = prefix.clone();
                    choice.push(i);
                    choice
                })
            })
            .collect()
    })
}

/// A copy of `tree` with each axis set to its chosen value.
pub(super) fn substitute(tree: &Node, axes: &[AxisNodes<'_>], choice: &[usize]) -> Node {
    let mut point = tree.clone();
    for (axis, &i) in axes.iter().zip(choice) {
        set(
            &mut point,
            axis.path.segments(),
            axis.values[i].clone(),
            axis.key_location,
        )
        .expect("axes() checked that every path can be set");
    }
    point
}

/// Sets the node at `segments`, creating missing mappings on the way (a list
/// entry must exist).
pub(super) fn set(node: &mut Node, segments: &[Segment], value: Node, key_location: Location) -> Result<(), String> {
    let Some((first, rest)) = segments.split_first() else {
        *node = value;
        return Ok(());
    };
    let child = match (first, &mut node.value) {
        (Segment::Index(i), Value::Seq(items)) => items.get_mut(*i).ok_or("no such list entry")?,
        (Segment::Index(_), _) => return Err("cannot set a list entry: its parent is not a list".into()),
        (Segment::Key(first), Value::Map(entries)) => {
            let index = match entries.iter().position(|(k, _)| &k.name == first) {
                Some(index) => index,
                None => {
                    let empty = Node::new(Value::Map(Vec::new()), key_location);
                    let key = Key {
                        name: first.clone(),
                        location: key_location,
                    };
                    entries.push((key, empty));
                    entries.len() - 1
                }
            };
            &mut entries[index].1
        }
        (Segment::Key(first), _) => return Err(format!("cannot set `{first}`: its parent is not a mapping")),
    };
    set(child, rest, value, key_location)
}

pub(super) fn is_prefix(prefix: &Path, path: &Path) -> bool {
    path.segments().starts_with(prefix.segments())
}

/// JSON equality with numbers compared by value (`6` equals `6.0`).
pub(super) fn json_eq(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    canonical(a) == canonical(b)
}

/// The index of the first value in `values` equal (by [`json_eq`]) to an earlier
/// one, found in linear time.
pub(super) fn first_repeat(values: &[Node]) -> Option<usize> {
    let mut seen = HashSet::new();
    values.iter().position(|v| !seen.insert(canonical(&v.to_json())))
}

/// A text equal for two values exactly when [`json_eq`] holds: numbers as
/// `f64` (`-0` as `0`), mapping keys sorted.
fn canonical(value: &serde_json::Value) -> String {
    use serde_json::Value as J;
    match value {
        J::Number(n) => format!("{:?}", n.as_f64().map(|x| x + 0.0)),
        J::Array(items) => format!("[{}]", items.iter().map(canonical).collect::<Vec<_>>().join(",")),
        J::Object(entries) => {
            let mut entries: Vec<String> = entries
                .iter()
                .map(|(k, v)| format!("{}:{}", J::String(k.clone()), canonical(v)))
                .collect();
            entries.sort_unstable();
            format!("{{{}}}", entries.join(","))
        }
        other => other.to_string(),
    }
}

/// The distinct configurations of the sweeps' combinations, in order of first
/// appearance: a combination whose setup equals an earlier one's joins its point
/// (see [`Point`] for what "equal" means).
pub(super) struct Configurations {
    points: Vec<Point>,
    /// Per sweep, the point of each row added so far.
    rows: Vec<Vec<usize>>,
    /// Point indices by the hash of their setup's serialization.
    by_hash: HashMap<u64, Vec<usize>>,
    /// The bytes of the distinct setups' serializations.
    bytes: usize,
}

impl Configurations {
    /// None yet, for `sweeps` sweeps.
    pub(super) fn new(sweeps: usize) -> Self {
        Self {
            points: Vec::new(),
            rows: vec![Vec::new(); sweeps],
            by_hash: HashMap::new(),
            bytes: 0,
        }
    }

    /// Adds a combination, the next row of its sweep, and returns the index
    /// of its point.
    pub(super) fn add(&mut self, label: Label, setup: Setup) -> usize {
        let sweep = label.sweep;
        let (hash, bytes) = fingerprint(&setup);
        let candidates = self.by_hash.entry(hash).or_default();
        let same = candidates.iter().copied().find(|&i| {
            let other = &self.points[i].setup;
            *other == setup && serialized(other) == serialized(&setup)
        });
        let index = match same {
            Some(index) => {
                self.points[index].labels.push(label);
                index
            }
            None => {
                let index = self.points.len();
                candidates.push(index);
                self.bytes = self.bytes.saturating_add(bytes);
                self.points.push(Point {
                    index,
                    labels: vec![label],
                    setup,
                });
                index
            }
        };
        if let Some(rows) = sweep.and_then(|s| self.rows.get_mut(s)) {
            rows.push(index);
        }
        index
    }

    /// The bytes of the distinct points' setups serialized as JSON: a measure
    /// of the memory they hold.
    pub(super) fn bytes(&self) -> usize {
        self.bytes
    }

    /// The points, each configuration once.
    pub(super) fn points(&self) -> &[Point] {
        &self.points
    }

    /// The points, and per sweep the point of each row.
    pub(super) fn into_parts(self) -> (Vec<Point>, Vec<Vec<usize>>) {
        (self.points, self.rows)
    }
}

/// A hash of the JSON serialization of `value`, streamed, and its length in
/// bytes. foldhash, with its fixed seed: SipHash over an imported trace's
/// many small writes was 4 % of the SUMO town's run; a collision costs only
/// the comparison of the setups.
fn fingerprint(value: &impl serde::Serialize) -> (u64, usize) {
    /// Hashes what is written, counting its bytes.
    struct Hashing(FoldHasher<'static>, usize);
    impl io::Write for Hashing {
        fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
            self.0.write(bytes);
            self.1 += bytes.len();
            Ok(bytes.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }
    let mut hashing = Hashing(FixedState::default().build_hasher(), 0);
    serde_json::to_writer(&mut hashing, value).expect("settings serialize to JSON");
    (hashing.0.finish(), hashing.1)
}

/// The setup's JSON serialization: every float written exactly.
fn serialized(setup: &Setup) -> Vec<u8> {
    serde_json::to_vec(setup).expect("a setup serializes to JSON")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::yaml::parse;

    fn list(source: &str) -> Vec<Node> {
        match parse(source).expect("valid YAML").value {
            Value::Seq(items) => items,
            _ => panic!("a list"),
        }
    }

    #[test]
    fn repeats_are_found_by_value() {
        assert_eq!(first_repeat(&list("[1, 2, 1.0]")), Some(2));
        assert_eq!(first_repeat(&list("[-0.0, 0]")), Some(1));
        assert_eq!(first_repeat(&list("[{a: 1, b: [2]}, {b: [2.0], a: 1}]")), Some(1));
        assert_eq!(first_repeat(&list("[1, \"1\", [1], {a: 1}, null]")), None);
        assert_eq!(first_repeat(&list("[{a: 1}, {a: 1, b: 2}]")), None);
    }

    #[test]
    fn a_long_axis_is_checked_in_linear_time() {
        let values: Vec<Node> = (0..300_000)
            .map(|i| Node::new(Value::Int(i), Location::new(1, 1)))
            .collect();
        assert_eq!(first_repeat(&values), None);
    }
}
