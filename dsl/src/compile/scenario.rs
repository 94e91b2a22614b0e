//! The driver: text → tree → raw → imported files → setup per sweep combination
//! → distinct points → `vary` → requirements.

use std::collections::HashSet;
use std::{fmt, io};

use super::context::{Context, has, locate_key};
use super::kind::{self, Kind, ignored};
use super::record::record;
use super::requirements::{references, requirements};
use super::setup::setup;
use super::sweep::{self, AxisNodes, Configurations};
use super::traces::{self, Imported};
use super::vary;
use crate::de::from_node;
use crate::error::{Error, ErrorKind, Errors, Location};
use crate::model::{Assignment, Axis, Experiment, Label, Scenario, Setup, Sweep, display_value};
use crate::path::Path;
use crate::raw::RawScenario;
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
}

impl fmt::Debug for Options<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options")
            .field("seed", &self.seed)
            .field("loader", &self.loader.map(|_| "…"))
            .field("record", &self.record)
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
    let mut ctx = Context::new(file, &tree);
    check_version(&mut ctx);
    if !ctx.errors.is_empty() {
        return Err(ctx.errors);
    }
    let raw: RawScenario = from_node(&tree, &Path::root()).map_err(|e| vec![ctx.de_error(e)])?;
    // Imported files are read and parsed once: `traces` cannot be swept.
    let imported = traces::load(&mut ctx, raw.traces.as_ref(), options.loader);
    // Check the file as written before expanding the sweep, so that a problem
    // outside the swept keys is reported once, not once per point.
    let base = setup(&mut ctx, &raw, imported.as_ref());
    let sweeps = sweep::sweeps(&mut ctx);
    if let (Some(_), Some(axis)) = (options.seed, sweeps.iter().flatten().find(|a| a.dotted == "seed")) {
        ctx.error_at(
            axis.key_location,
            &axis.here,
            ErrorKind::Invalid("`--seed` cannot override a swept `seed`".into()),
        );
    }
    let base = base.filter(|_| ctx.errors.is_empty());
    let vary = vary::vary(&mut ctx, &sweeps, imported.as_ref(), base.as_ref());
    // Requirements are checked even when the setup is invalid (ids, texts and
    // check forms do not depend on the points), so one pass reports everything.
    let compiled = match base {
        Some(_) if ctx.errors.is_empty() => match points(file, &tree, &sweeps, options, imported.as_ref()) {
            Ok((compiled, combinations)) => {
                refuse_unused(&mut ctx, &combinations);
                Some(compiled)
            }
            Err(errors) => {
                ctx.errors.extend(errors);
                None
            }
        },
        _ => None,
    };
    let points = compiled.as_ref().map(Configurations::points);
    let requirements = requirements(&mut ctx, &raw.requirements, points);
    let references = references(&mut ctx, &raw.references, points);
    let record = record(&mut ctx, raw.record.as_ref(), options.record, points);
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
            imports: imported.map(|i| i.files).unwrap_or_default(),
            vary,
            record,
        }
    }))
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

/// One sweep combination: its setup and its tree (the file with its values in
/// place).
type Combination = (Setup, Node);

/// Compiles every combination of every sweep (the file as written without a
/// sweep) into the distinct configurations they give; also returns each
/// combination's setup with its tree (the file with its values in place).
fn points(
    file: &str,
    tree: &Node,
    sweeps: &[Vec<AxisNodes<'_>>],
    options: &Options<'_>,
    imported: Option<&Imported>,
) -> Result<(Configurations, Vec<Combination>), Vec<Error>> {
    let mut configurations = Configurations::new(sweeps.len());
    let mut combinations = Vec::new();
    let mut errors = Vec::new();
    let no_sweep: [Vec<AxisNodes<'_>>; 1] = [Vec::new()];
    let groups = if sweeps.is_empty() { &no_sweep[..] } else { sweeps };
    for (group, axes) in groups.iter().enumerate() {
        for choice in sweep::choices(axes) {
            let point_tree = sweep::substitute(tree, axes, &choice);
            let mut ctx = Context::new(file, &point_tree);
            let compiled = match from_node::<RawScenario>(&point_tree, &Path::root()) {
                Ok(raw) => setup(&mut ctx, &raw, imported).map(|setup| (raw, setup)),
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
                        settings: settings(&raw, &setup),
                    };
                    combinations.push((setup.clone(), point_tree));
                    configurations.add(label, setup);
                }
                Err(e) => errors.extend(e),
            }
        }
    }
    if errors.is_empty() {
        Ok((configurations, combinations))
    } else {
        Err(errors)
    }
}

/// Refuses each key that the settings around it leave without effect at every
/// sweep point that has it. A key is the node written at one place of the file:
/// one written outside the sweeps is in every point, one inside a swept value
/// only in the points that take that value. So `fusion.weights`, given once
/// and ignored by the `dempster` rule, is refused unless a sweep fuses with a
/// weighted rule at some point.
fn refuse_unused(ctx: &mut Context<'_>, combinations: &[Combination]) {
    let found: Vec<Vec<(Location, Path, String)>> = combinations
        .iter()
        .map(|(setup, tree)| {
            kind::unused(tree, setup)
                .into_iter()
                .map(|(path, why)| (locate_key(tree, &path), path, why))
                .collect()
        })
        .collect();
    let mut seen = HashSet::new();
    for (location, path, why) in found.iter().flatten() {
        if !seen.insert(*location) {
            continue;
        }
        let everywhere = combinations.iter().zip(&found).all(|((_, tree), unused)| {
            unused.iter().any(|(l, _, _)| l == location) || !(has(tree, path) && locate_key(tree, path) == *location)
        });
        if everywhere {
            ctx.error_at(*location, path, ErrorKind::NoEffect(why.clone()));
        }
    }
}

/// The effective settings of a combination as JSON, for `where` filters: the raw
/// sections with serde defaults filled in (agents keyed by id), plus what the
/// compiler resolves (the seed, the fusion label, the number of cooperating agents).
fn settings(raw: &RawScenario, setup: &crate::model::Setup) -> serde_json::Value {
    let mut json = serde_json::to_value(raw).expect("raw scenario types serialize to JSON");
    let object = json.as_object_mut().expect("a scenario serializes to an object");
    for key in [
        "sightline",
        "name",
        "description",
        "requirements",
        "sweep",
        "references",
        "vary",
        "record",
    ] {
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
    json
}
