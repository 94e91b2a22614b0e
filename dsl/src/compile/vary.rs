//! `vary`: the space `sightline falsify` searches, read from the spanned tree
//! like the sweeps, and one concrete scenario per choice of values.
//!
//! Both ends of a range and every choice are checked as a sweep value is: set
//! into a copy of the tree and compiled, so a value out of the setting's range
//! is reported where it is written in `vary`.

use super::context::{Context, locate_key};
use super::kind;
use super::map::Mapped;
use super::setup::setup;
use super::sweep::{self, AxisNodes, is_prefix};
use super::traces::Imported;
use crate::de::from_node;
use crate::emit::emit;
use crate::error::{Error, ErrorKind, Errors, Location};
use crate::model::{Domain, MAX_WHOLE_END, Setup, Vary};
use crate::path::Path;
use crate::raw::RawScenario;
use crate::yaml::{self, Node, Value};

/// Reads and checks `vary`. With `base`, the scenario's own configuration,
/// every end and choice is compiled, and refused when it would leave a key of
/// the file without effect that `base` does not (every case falsify writes out
/// must be a scenario `check` accepts); the caller passes `None` when the
/// scenario is already invalid (the values would only repeat its errors).
pub(super) fn vary(
    ctx: &mut Context<'_>,
    sweeps: &[Vec<AxisNodes<'_>>],
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
    base: Option<&Setup>,
) -> Vec<Vary> {
    let tree = ctx.tree;
    let Some(Node {
        value: Value::Map(entries),
        ..
    }) = tree.get("vary")
    else {
        return Vec::new(); // absent, or serde has already rejected a non-mapping
    };
    let base_unused: Option<Vec<Path>> =
        base.map(|base| kind::unused(tree, base).into_iter().map(|(path, _)| path).collect());
    let mut varied: Vec<(Path, Vary)> = Vec::new();
    for (key, node) in entries {
        let here = Path::root().key("vary").key(&key.name);
        let Some((path, schema)) = sweep::setting(ctx, key, &here, ("vary", "`vary`")) else {
            continue;
        };
        if let Some((_, other)) = varied.iter().find(|(p, _)| is_prefix(p, &path) || is_prefix(&path, p)) {
            let message = format!("overlaps the vary key `{}`", other.path);
            ctx.error_at(key.location, &here, ErrorKind::Invalid(message));
            continue;
        }
        if let Some(axis) = sweeps
            .iter()
            .flatten()
            .find(|a| is_prefix(&a.path, &path) || is_prefix(&path, &a.path))
        {
            let message = format!(
                "`{}` is also swept (`{}`); a setting is swept or varied, not both",
                key.name, axis.here
            );
            ctx.error_at(key.location, &here, ErrorKind::Invalid(message));
            continue;
        }
        let Some((domain, values)) = domain(ctx, node, &here, is_integer(&schema)) else {
            continue;
        };
        if let Some(base_unused) = &base_unused
            && !values.iter().all(|value| {
                let setting = Setting {
                    here: &here,
                    path: &path,
                    key_location: key.location,
                };
                value_compiles(ctx, &setting, value, (imported, mapped), base_unused)
            })
        {
            continue;
        }
        varied.push((
            path,
            Vary {
                path: key.name.clone(),
                domain,
            },
        ));
    }
    varied.into_iter().map(|(_, vary)| vary).collect()
}

/// Whether a setting's schema says it takes whole numbers only.
fn is_integer(schema: &serde_json::Value) -> bool {
    match &schema["type"] {
        serde_json::Value::String(t) => t == "integer",
        serde_json::Value::Array(types) => types.iter().any(|t| t == "integer") && !types.iter().any(|t| t == "number"),
        _ => false,
    }
}

/// The domain of one `vary` entry and the value nodes to check (both ends, or
/// every choice).
fn domain<'a>(ctx: &mut Context<'_>, node: &'a Node, here: &Path, integer: bool) -> Option<(Domain, Vec<&'a Node>)> {
    let expected = "a range `[lo, hi]` of two numbers, or `{ one_of: [ … ] }`";
    let number = |node: &Node| match node.value {
        Value::Int(i) => Some(i as f64),
        Value::Float(f) if f.is_finite() => Some(f),
        _ => None,
    };
    match &node.value {
        Value::Seq(ends) if ends.len() == 2 => {
            let (Some(lo), Some(hi)) = (number(&ends[0]), number(&ends[1])) else {
                let bad = if number(&ends[0]).is_none() { 0 } else { 1 };
                ctx.error(
                    &here.index(bad),
                    ErrorKind::InvalidType {
                        expected: "a finite number".into(),
                        found: ends[bad].describe(),
                    },
                );
                return None;
            };
            if lo > hi {
                ctx.error(
                    &here.index(1),
                    ErrorKind::OutOfRange {
                        expected: format!("a high end ≥ the low end {lo}"),
                        found: hi.to_string(),
                    },
                );
                return None;
            }
            if integer && let Some(bad) = [lo, hi].iter().position(|end| end.abs() > MAX_WHOLE_END) {
                ctx.error(
                    &here.index(bad),
                    ErrorKind::OutOfRange {
                        expected: format!(
                            "an end from -{MAX_WHOLE_END} to {MAX_WHOLE_END} (2^53) for a range of whole numbers, \
                             whose values are held exactly only up to there; use `one_of` for larger values"
                        ),
                        found: ends[bad].describe(),
                    },
                );
                return None;
            }
            Some((Domain::Range { lo, hi, integer }, vec![&ends[0], &ends[1]]))
        }
        Value::Map(entries) if entries.len() == 1 && entries[0].0.name == "one_of" => {
            let choices_path = here.key("one_of");
            let Value::Seq(choices) = &entries[0].1.value else {
                ctx.error(
                    &choices_path,
                    ErrorKind::InvalidType {
                        expected: "a list of values".into(),
                        found: entries[0].1.describe(),
                    },
                );
                return None;
            };
            if choices.is_empty() {
                ctx.error(
                    &choices_path,
                    ErrorKind::Invalid("`one_of` needs at least one value".into()),
                );
                return None;
            }
            if let Some(i) = sweep::first_repeat(choices) {
                ctx.error(
                    &choices_path.index(i),
                    ErrorKind::Invalid("this value is listed twice".into()),
                );
                return None;
            }
            let domain = Domain::Choices(choices.iter().map(Node::to_json).collect());
            Some((domain, choices.iter().collect()))
        }
        _ => {
            ctx.error(
                here,
                ErrorKind::InvalidType {
                    expected: expected.into(),
                    found: node.describe(),
                },
            );
            None
        }
    }
}

/// A varied setting: where it is written in `vary`, its path in the tree, and
/// where its key is.
struct Setting<'a> {
    here: &'a Path,
    path: &'a Path,
    key_location: Location,
}

/// Compiles the scenario with `value` set at the setting; records its errors
/// (located at the value), and refuses the value when it leaves a key without
/// effect that is not in `base_unused`. Returns whether there were none.
fn value_compiles(
    ctx: &mut Context<'_>,
    setting: &Setting<'_>,
    value: &Node,
    (imported, mapped): (Option<&Imported>, Option<&Mapped>),
    base_unused: &[Path],
) -> bool {
    let mut probe = ctx.tree.clone();
    if let Err(message) = sweep::set(&mut probe, setting.path.segments(), value.clone(), setting.key_location) {
        ctx.error_at(value.location, setting.path, ErrorKind::Invalid(message));
        return false;
    }
    let mut probe_ctx = Context::new(ctx.file, &probe);
    match from_node::<RawScenario>(&probe, &Path::root()) {
        Ok(raw) => {
            let compiled = setup(&mut probe_ctx, &raw, imported, mapped);
            if let Some(compiled) = compiled.filter(|_| probe_ctx.errors.is_empty()) {
                for (unused, why) in kind::unused(&probe, &compiled) {
                    if !base_unused.contains(&unused) {
                        probe_ctx.error_at(
                            value.location,
                            setting.here,
                            ErrorKind::Invalid(format!(
                                "with this value, `{unused}` (line {}) would have no effect: {why}",
                                locate_key(&probe, &unused).line
                            )),
                        );
                    }
                }
            }
        }
        Err(e) => {
            let error = probe_ctx.de_error(e);
            probe_ctx.errors.push(error);
        }
    }
    let ok = probe_ctx.errors.is_empty();
    ctx.errors.extend(probe_ctx.errors);
    ok
}

/// The scenario file `source` (already compiled) without `vary` and with each
/// dotted path of `settings` set to its value (a case's values of the varied
/// settings, and any other setting the caller moves, such as the paths of
/// imported files), as YAML text: a concrete scenario that `sightline run` runs as
/// is. Comments and layout are not kept.
pub fn instantiate(file: &str, source: &str, settings: &[(String, serde_json::Value)]) -> Result<String, Errors> {
    let error = |location: Location, path: String, kind: ErrorKind| {
        Errors(vec![Error {
            file: file.to_string(),
            location,
            path,
            kind,
        }])
    };
    let mut tree = yaml::parse(source).map_err(|e| error(e.location, e.path.to_string(), e.kind))?;
    if let Value::Map(entries) = &mut tree.value {
        entries.retain(|(key, _)| key.name != "vary");
    }
    for (dotted, value) in settings {
        let location = Location::new(1, 1);
        let path = sweep::resolve(&tree, dotted).map_err(|kind| error(location, dotted.clone(), kind))?;
        sweep::set(&mut tree, path.segments(), Node::from_json(value, location), location)
            .map_err(|message| error(location, dotted.clone(), ErrorKind::Invalid(message)))?;
    }
    Ok(emit(&tree))
}
