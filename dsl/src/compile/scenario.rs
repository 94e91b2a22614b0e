//! The driver: text → tree → raw → imported files → setup per sweep combination
//! → distinct points → `vary` → requirements.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::sync::Arc;
use std::{fmt, io};

use super::budget::{Evidence, evidence_budget, run_budget};
use super::context::{Context, has, locate_key};
use super::ignored::ignored;
use super::kind::{self, Kind};
use super::map::{self, Mapped};
use super::record::{record, start};
use super::requirements::{references, requirements};
use super::setup::setup;
use super::sweep::{self, AxisNodes, Configurations, MAX_SETTINGS_BYTES};
use super::system::system_under_test;
use super::traces::{self, Imported};
use super::vary;
use crate::de::from_node;
use crate::error::{Error, ErrorKind, Errors, Location};
use crate::model::{Assignment, Axis, Document, Experiment, Label, Paper, Scenario, Settings, Sweep, display_value};
use crate::path::Path;
use crate::raw::{RawDocument, RawPaper, RawScenario};
use crate::schema::AGENTS;
use crate::yaml::{self, Node, Value};

/// The language version this release reads.
pub const LANGUAGE_VERSION: i128 = 1;

/// Settings of one compilation that the file does not give.
#[derive(Clone, Copy, Default)]
pub struct Options<'a> {
    /// Replace the scenario's `seed` (the CLI's `--seed`). An error when `seed` is swept.
    pub seed: Option<u64>,
    /// Reads the files the scenario imports (`traces`). Without one, a scenario
    /// that imports files fails to read them: the compiler never touches the file
    /// system itself.
    pub loader: Option<&'a dyn Loader>,
    /// Record a point into `run.mcap` even when the file has no `record`
    /// section (the CLI's `--record`), with that section's defaults.
    pub record: bool,
    /// The recorded point is also written as an OSI trace (the CLI's
    /// `--osi`): the resource model then bounds the trace's objects too.
    pub osi: bool,
    /// The scenario is to be simulated by this many processes (`run`: 1,
    /// `run --shard K/N`: N): the resource model then bounds the work of each
    /// (`budget::MAX_RUN_LOAD`). `None` where nothing is simulated (a merge,
    /// a replay) or only one point (an export).
    pub processes: Option<u32>,
}

impl fmt::Debug for Options<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options")
            .field("seed", &self.seed)
            .field("loader", &self.loader.map(|_| "…"))
            .field("record", &self.record)
            .field("osi", &self.osi)
            .field("processes", &self.processes)
            .finish()
    }
}

/// Reads the files a scenario imports, for [`compile`]. A closure is one:
///
/// ```
/// use std::path::Path;
/// let disk = |path: &Path| std::fs::read(path);
/// let options = sightline_dsl::Options { loader: Some(&disk), ..Default::default() };
/// # let _ = options;
/// ```
pub trait Loader {
    /// The bytes of the file at `path` (the scenario file's directory joined with
    /// the path the scenario gives).
    fn load(&self, path: &std::path::Path) -> io::Result<Vec<u8>>;
}

impl<F: Fn(&std::path::Path) -> io::Result<Vec<u8>>> Loader for F {
    fn load(&self, path: &std::path::Path) -> io::Result<Vec<u8>> {
        self(path)
    }
}

/// Compiles the text of one scenario file. `file` names it in errors and
/// locates the files it imports (relative to its directory).
///
/// Returns every problem found, those of the scenario file first in source
/// order, then those of the files it imports; no problem means the scenario can
/// run.
pub fn compile(file: &str, source: &str, options: &Options<'_>) -> Result<Scenario, Errors> {
    compile_inner(file, source, options).map_err(|mut errors| {
        errors.sort_by(|a, b| (a.file != file, &a.file, a.location).cmp(&(b.file != file, &b.file, b.location)));
        errors.dedup();
        Errors(errors)
    })
}

fn compile_inner(file: &str, source: &str, options: &Options<'_>) -> Result<Scenario, Vec<Error>> {
    let tree = yaml::parse(source).map_err(|e| {
        vec![Error {
            file: file.to_string(),
            location: e.location,
            path: e.path.to_string(),
            kind: e.kind,
        }]
    })?;
    // The file as written is checked with the keys every sweep gives filled in.
    let given = sweep::completed(&tree);
    let mut ctx = Context::new(file, &given);
    ctx.driven = tree.get("system_under_test").is_some();
    check_version(&mut ctx);
    if !ctx.errors.is_empty() {
        return Err(ctx.errors);
    }
    let raw: RawScenario = from_node(&given, &Path::root()).map_err(|e| vec![ctx.de_error(e)])?;
    // Imported files are read and parsed once: `traces` and `map` cannot be swept.
    let imported = traces::load(&mut ctx, raw.traces.as_ref(), options.loader);
    let mapped = map::load(&mut ctx, raw.map.as_ref(), options.loader);
    // Check the file as written before expanding the sweep, so that a problem
    // outside the swept keys is reported once, not once per point.
    let base = setup(&mut ctx, &raw, imported.as_ref(), mapped.as_ref());
    let setup_tree = without_read_once(&tree);
    let sweeps = sweep::sweeps(&mut ctx, setup_tree.size());
    if let (Some(_), Some(axis)) = (options.seed, sweeps.iter().flatten().find(|a| a.dotted == "seed")) {
        ctx.error_at(
            axis.key_location,
            &axis.here,
            ErrorKind::Invalid("`--seed` cannot override a swept `seed`".into()),
        );
    }
    let base = base.filter(|_| ctx.errors.is_empty());
    let vary = vary::vary(&mut ctx, &sweeps, imported.as_ref(), mapped.as_ref(), base.as_ref());
    // Requirements are checked even when the setup is invalid (ids, texts and
    // check forms do not depend on the points), so one pass reports everything.
    let compiled = match base {
        Some(_) if ctx.errors.is_empty() => match points(
            file,
            &setup_tree,
            &sweeps,
            (options, ctx.driven),
            (imported.as_ref(), mapped.as_ref()),
        ) {
            Ok((compiled, unused)) => {
                refuse_unused(&mut ctx, &setup_tree, &sweeps, &unused);
                Some(compiled)
            }
            Err(errors) => {
                ctx.errors.extend(errors);
                None
            }
        },
        _ => None,
    };
    // After the points, so that a file also refused for what its settings
    // leave without effect is told both in one pass.
    sweep::refuse_replaced(&mut ctx, &tree, &sweeps);
    let points = compiled.as_ref().map(Configurations::points);
    let requirements = requirements(&mut ctx, &raw.requirements, points);
    let references = references(&mut ctx, &raw.references, points);
    let evidence = Evidence {
        name: &raw.name,
        points,
        requirements: &requirements,
        references: &references,
    };
    evidence_budget(&mut ctx, &evidence);
    if let (Some(points), Some(processes)) = (points, options.processes) {
        let sweep = Path::root().key(if raw.sweeps.is_empty() { "sweep" } else { "sweeps" });
        run_budget(&mut ctx, points, &requirements, (processes, &sweep));
    }
    let start = start(&mut ctx, raw.time.as_ref());
    let record = record(&mut ctx, raw.record.as_ref(), options.record, points, start);
    let system_under_test = system_under_test(&mut ctx, &raw, points, &requirements);
    let warnings = imported.as_ref().map_or_else(Vec::new, |imported| {
        let mut warnings = imported.warnings.clone();
        warnings.extend(
            raw.time
                .as_ref()
                .and_then(|time| imported.coverage(time.duration, time.step)),
        );
        warnings
    });
    ctx.finish(compiled.map(Configurations::into_parts).map(|(points, rows)| {
        Scenario {
            file: file.to_string(),
            name: raw.name,
            description: raw.description,
            sweeps: sweeps
                .iter()
                .zip(rows)
                .map(|(axes, points)| Sweep {
                    axes: axes
                        .iter()
                        .map(|a| Axis {
                            path: a.dotted.clone(),
                            values: a.values.iter().map(Node::to_json).collect(),
                        })
                        .collect(),
                    points,
                })
                .collect(),
            points,
            requirements,
            references,
            imports: imported
                .map(|i| i.files)
                .into_iter()
                .chain(mapped.map(|m| m.files))
                .flatten()
                .collect(),
            vary,
            record,
            system_under_test,
            document: document(raw.document),
            warnings,
        }
    }))
}

/// The `document` section: it only labels the report, so nothing is checked
/// beyond its form.
fn document(raw: Option<RawDocument>) -> Document {
    let raw = raw.unwrap_or_default();
    Document {
        version: raw.version,
        author: raw.author,
        reviewer: raw.reviewer,
        approver: raw.approver,
        paper: match raw.paper {
            Some(RawPaper::Letter) => Paper::Letter,
            Some(RawPaper::A4) | None => Paper::A4,
        },
    }
}

fn check_version(ctx: &mut Context<'_>) {
    let root = Path::root();
    match ctx.tree.get("sightline").map(|n| &n.value) {
        Some(Value::Int(LANGUAGE_VERSION)) => {}
        Some(Value::Int(other)) => ctx.error(
            &root.key("sightline"),
            ErrorKind::Invalid(format!(
                "language version {other} is not supported; this sightline reads version {LANGUAGE_VERSION}"
            )),
        ),
        Some(_) => ctx.error(
            &root.key("sightline"),
            ErrorKind::InvalidType {
                expected: format!("the language version `{LANGUAGE_VERSION}`"),
                found: ctx.tree.get("sightline").map(Node::describe).unwrap_or_default(),
            },
        ),
        None if matches!(ctx.tree.value, Value::Map(_)) => {
            ctx.error_at(Location::new(1, 1), &root, ErrorKind::MissingKey("sightline".into()))
        }
        None => ctx.error(
            &root,
            ErrorKind::InvalidType {
                expected: "a scenario mapping starting with `sightline: 1`".into(),
                found: ctx.tree.describe(),
            },
        ),
    }
}

/// Top-level sections read once for the whole scenario, not per sweep
/// combination: a combination is compiled from the file without them, so that a
/// long sweep axis is not copied and read again at every point.
const READ_ONCE: [&str; 8] = [
    "sweep",
    "sweeps",
    "vary",
    "requirements",
    "references",
    "record",
    "system_under_test",
    "document",
];

/// The file without its [`READ_ONCE`] sections.
fn without_read_once(tree: &Node) -> Node {
    let value = match &tree.value {
        Value::Map(entries) => Value::Map(
            entries
                .iter()
                .filter(|(key, _)| !READ_ONCE.contains(&key.name.as_str()))
                .cloned()
                .collect(),
        ),
        other => other.clone(),
    };
    Node::new(value, tree.location)
}

/// The keys the combinations' settings leave without effect.
#[derive(Default)]
struct Unused {
    /// Each key unused at some combination, by where it is written: its path and
    /// why, as first found.
    keys: BTreeMap<Location, (Path, String)>,
    /// Per combination, in the order of [`combinations`], where its unused keys
    /// are written.
    at: Vec<HashSet<Location>>,
}

/// Every combination of every sweep (the file as written without a sweep), in
/// order: its sweep, its axes, the value chosen on each, and its tree (`tree`
/// with those values in place). Each tree is made when it is reached, so one is
/// held at a time.
fn combinations<'s, 'a>(
    tree: &'s Node,
    sweeps: &'s [Vec<AxisNodes<'a>>],
) -> impl Iterator<Item = (usize, &'s [AxisNodes<'a>], Vec<usize>, Node)> + 's {
    let groups: Vec<&'s [AxisNodes<'a>]> = if sweeps.is_empty() {
        vec![&[]]
    } else {
        sweeps.iter().map(Vec::as_slice).collect()
    };
    groups.into_iter().enumerate().flat_map(move |(group, axes)| {
        sweep::choices(axes).into_iter().map(move |choice| {
            let point_tree = sweep::substitute(tree, axes, &choice);
            (group, axes, choice, point_tree)
        })
    })
}

/// Compiles every combination of every sweep into the distinct configurations
/// they give; also returns, per combination, the keys its settings leave without
/// effect.
fn points(
    file: &str,
    tree: &Node,
    sweeps: &[Vec<AxisNodes<'_>>],
    (options, driven): (&Options<'_>, bool),
    (imported, mapped): (Option<&Imported>, Option<&Mapped>),
) -> Result<(Configurations, Unused), Vec<Error>> {
    let mut configurations = Configurations::new(sweeps.len());
    let mut sections = Sections::default();
    let mut unused = Unused::default();
    let mut errors = Vec::new();
    // Each label as tables, messages and JUnit show it, and its point.
    let mut named: HashMap<String, usize> = HashMap::new();
    for (group, axes, choice, point_tree) in combinations(tree, sweeps) {
        let mut ctx = Context::new(file, &point_tree);
        ctx.osi = options.osi;
        ctx.driven = driven;
        let compiled = match from_node::<RawScenario>(&point_tree, &Path::root()) {
            Ok(raw) => setup(&mut ctx, &raw, imported, mapped).map(|setup| (raw, setup)),
            Err(e) => {
                ctx.errors.push(ctx.de_error(e));
                None
            }
        };
        match ctx.finish(compiled) {
            Ok((raw, mut setup)) => {
                if let Some(seed) = options.seed {
                    setup.seed = seed;
                }
                let label = Label {
                    sweep: (!sweeps.is_empty()).then_some(group),
                    assignments: axes
                        .iter()
                        .zip(&choice)
                        .map(|(axis, &i)| {
                            let value = axis.values[i].to_json();
                            Assignment {
                                path: axis.dotted.clone(),
                                display: display_value(&value),
                                value,
                            }
                        })
                        .collect(),
                    settings: settings(&raw, &setup, &mut sections),
                };
                let mut here = HashSet::new();
                for (path, why) in kind::unused(&point_tree, &setup) {
                    let location = locate_key(&point_tree, &path);
                    unused.keys.entry(location).or_insert((path, why));
                    here.insert(location);
                }
                unused.at.push(here);
                let text = label.text();
                let index = configurations.add(label, setup);
                if let Some(first) = axes.first()
                    && *named.entry(text.clone()).or_insert(index) != index
                {
                    let value = first.here.index(choice[0]);
                    errors.push(Error {
                        file: file.to_string(),
                        location: first.values[choice[0]].location,
                        path: value.to_string(),
                        kind: ErrorKind::Invalid(format!(
                            "the sweep point `{text}` names two different configurations; \
                             give the values distinct labels (`label:` in a mapping)"
                        )),
                    });
                }
                if configurations.bytes().saturating_add(sections.bytes) > MAX_SETTINGS_BYTES {
                    errors.push(Error {
                        file: file.to_string(),
                        location: tree.location,
                        path: String::new(),
                        kind: ErrorKind::TooLarge(format!(
                            "the settings of the first {} sweep points already take more than {} MiB; \
                             sweep fewer values or split the scenario",
                            configurations.points().len(),
                            MAX_SETTINGS_BYTES >> 20
                        )),
                    });
                    break;
                }
            }
            Err(e) => errors.extend(e),
        }
    }
    if errors.is_empty() {
        Ok((configurations, unused))
    } else {
        Err(errors)
    }
}

/// Refuses each key that the settings around it leave without effect at every
/// sweep point that has it. A key is the node written at one place of the file:
/// one written outside the sweeps is in every point, one inside a swept value
/// only in the points that take that value. So `fusion.weights`, given once
/// and ignored by the `dempster` rule, is refused unless a sweep fuses with a
/// weighted rule at some point. The combinations' trees are made again only
/// when some key is unused somewhere.
fn refuse_unused(ctx: &mut Context<'_>, tree: &Node, sweeps: &[Vec<AxisNodes<'_>>], unused: &Unused) {
    if unused.keys.is_empty() {
        return;
    }
    let mut everywhere = vec![true; unused.keys.len()];
    for ((_, _, _, point_tree), here) in combinations(tree, sweeps).zip(&unused.at) {
        for (refuse, (location, (path, _))) in everywhere.iter_mut().zip(&unused.keys) {
            *refuse &=
                here.contains(location) || !(has(&point_tree, path) && locate_key(&point_tree, path) == *location);
        }
    }
    for (refuse, (location, (path, why))) in everywhere.into_iter().zip(&unused.keys) {
        if refuse {
            ctx.error_at(*location, path, ErrorKind::NoEffect(why.clone()));
        }
    }
}

/// The effective settings of a combination as JSON, for `where` filters: the raw
/// sections with serde defaults filled in (agents keyed by id), plus what the
/// compiler resolves (the seed, the fusion label, the number of cooperating agents).
fn settings(raw: &RawScenario, setup: &crate::model::Setup, shared: &mut Sections) -> Settings {
    let mut json = serde_json::to_value(raw).expect("raw scenario types serialize to JSON");
    let object = json.as_object_mut().expect("a scenario serializes to an object");
    // What names and describes the file, and the sections read once, are no
    // settings of a point.
    for key in ["sightline", "name", "description"].into_iter().chain(READ_ONCE) {
        object.remove(key);
    }
    // Sections the scenario's kind ignores are no settings of its points.
    let kind = Kind::of_setup(setup);
    object.retain(|key, _| ignored(kind, &Path::root().key(key)).is_none());
    object.insert("seed".into(), setup.seed.into());
    // Agents by id, as a sweep names them: `agents.<id>.speed.target`.
    if let Some(agents) = object.get_mut(AGENTS)
        && let Some(list) = agents.as_array_mut()
    {
        let by_id = list
            .drain(..)
            .filter_map(|agent| Some((agent.get("id")?.as_str()?.to_string(), agent)))
            .collect();
        *agents = serde_json::Value::Object(by_id);
    }
    if let (Some(fusion), Some(occupancy)) = (
        object.get_mut("fusion").and_then(|f| f.as_object_mut()),
        &setup.occupancy,
    ) {
        fusion.insert("label".into(), occupancy.fusion.label.clone().into());
    }
    if let (Experiment::World(world), Some(perception)) = (
        &setup.experiment,
        object.get_mut("perception").and_then(|p| p.as_object_mut()),
    ) && let Some(compiled) = &world.perception
    {
        perception.insert("cooperating".into(), compiled.cooperating.len().into());
    }
    let serde_json::Value::Object(sections) = json else {
        unreachable!("a scenario serializes to an object")
    };
    Settings::new(
        sections
            .into_iter()
            .map(|(name, section)| {
                let shared = shared.intern(&name, section);
                (name, shared)
            })
            .collect(),
    )
}

/// The distinct settings sections of a scenario's combinations, each held once.
#[derive(Default)]
struct Sections {
    /// Each distinct section by its name and serialization.
    by_text: HashMap<(String, String), Arc<serde_json::Value>>,
    /// The bytes of those serializations.
    bytes: usize,
}

impl Sections {
    /// The section `name` equal to `section`, shared when one was seen before.
    fn intern(&mut self, name: &str, section: serde_json::Value) -> Arc<serde_json::Value> {
        let text = section.to_string();
        let bytes = &mut self.bytes;
        self.by_text
            .entry((name.to_string(), text))
            .or_insert_with_key(|(_, text)| {
                *bytes = bytes.saturating_add(text.len());
                Arc::new(section)
            })
            .clone()
    }
}
