//! Checks the sections share: ids unique in a list and distinct from imported
//! ones, points within the world, a length in whole steps, and the known names an error
//! about a dangling reference lists.

use std::collections::{HashMap, HashSet};

use super::context::{Context, locate};
use crate::de::closest;
use crate::error::{ErrorKind, Location};
use crate::path::Path;
use crate::raw::range;

/// The longest id of a declared thing: ids name topics, frames and entities in
/// the evidence, once per step.
pub(super) const MAX_ID_CHARS: usize = 64;

/// Whether `id` is one to 64 letters, digits, `-`, `_` or `.`: ids become
/// recording topics and frames (`/perception/ID/…`, where a `/` would nest),
/// XML names and terminal text.
pub(super) fn valid_id(id: &str) -> bool {
    (1..=MAX_ID_CHARS).contains(&id.chars().count())
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

/// Why `id` cannot name an agent, if it cannot: the recording's world frame
/// (`map`), or the form of a vehicle the semantic world's traffic generates
/// (`routeI-N`), which would make two road users of one id.
pub(super) fn reserved(id: &str) -> Option<&'static str> {
    let generated = id
        .strip_prefix("route")
        .and_then(|rest| rest.split_once('-'))
        .is_some_and(|(i, n)| {
            [i, n]
                .iter()
                .all(|part| !part.is_empty() && part.chars().all(|c| c.is_ascii_digit()))
        });
    match id {
        "map" => Some("the recording's world frame, the parent of every agent's"),
        _ if generated => Some("of the form `routeI-N` the traffic a semantic world generates is named by"),
        _ => None,
    }
}

/// Why imported object `id` (a traced vehicle or person, or a roadside unit) cannot
/// be an agent's, if it cannot: agents' ids follow the declared ones' rule
/// ([`valid_id`], not [`reserved`]), as they name the same frames and topics.
pub(super) fn imported_id_problem(id: &str) -> Option<String> {
    let why = if !valid_id(id) {
        id_rule(id)
    } else {
        format!("`{id}` is {}", reserved(id)?)
    };
    Some(format!(
        "an imported object's id names its agent, and {why}; rename it in the simulation"
    ))
}

/// Records an error for every id of a list that is not [`valid_id`] and a
/// duplicate-id error for every repeated one; returns whether all are valid
/// and unique.
pub(super) fn unique_ids<'a>(ctx: &mut Context<'_>, list: &Path, ids: impl Iterator<Item = &'a str>) -> bool {
    let mut first: HashMap<&str, Location> = HashMap::new();
    let mut ok = true;
    for (i, id) in ids.enumerate() {
        let path = list.index(i).key("id");
        if !valid_id(id) {
            ctx.error(&path, invalid_id(id));
            ok = false;
        } else if let Some(&location) = first.get(id) {
            ctx.error(
                &path,
                ErrorKind::DuplicateId {
                    id: id.to_string(),
                    first: location,
                },
            );
            ok = false;
        } else {
            first.insert(id, locate(ctx.tree, &path));
        }
    }
    ok
}

/// The error of an id that is not [`valid_id`].
pub(super) fn invalid_id(id: &str) -> ErrorKind {
    ErrorKind::Invalid(id_rule(id))
}

/// What an id is, and what `id` (not [`valid_id`], shown escaped and cut) is.
fn id_rule(id: &str) -> String {
    let shown: String = id.chars().take(MAX_ID_CHARS).collect();
    format!(
        "an id is 1 to {MAX_ID_CHARS} letters, digits, `-`, `_` or `.`; found \"{}{}\"",
        shown.escape_debug(),
        if shown.len() < id.len() { "…" } else { "" }
    )
}

/// Records an error at `list[i].id` for each declared id that something imported
/// (`what`: an edge of `traces.net`, …) also has; returns whether none does.
pub(super) fn distinct_from_imported<'a>(
    ctx: &mut Context<'_>,
    list: &Path,
    declared: impl Iterator<Item = &'a str>,
    imported: &HashSet<&str>,
    what: &str,
) -> bool {
    let mut ok = true;
    for (i, id) in declared.enumerate() {
        if imported.contains(id) {
            ctx.error(
                &list.index(i).key("id"),
                ErrorKind::Invalid(format!("`{id}` is also the id of {what}; choose another id")),
            );
            ok = false;
        }
    }
    ok
}

/// Checks that every coordinate of `points` lies in the world's range.
pub(super) fn coordinates(ctx: &mut Context<'_>, path: &Path, points: &[[f64; 2]]) -> bool {
    ctx.points_within(path, points, range::COORDINATE)
}

/// The number of whole `step`s in `length`, or `None` when it is not whole.
pub(super) fn whole_multiple(length: f64, step: f64) -> Option<f64> {
    let n = length / step;
    let rounded = n.round();
    ((n - rounded).abs() <= 1e-9 * rounded.max(1.0) && rounded >= 1.0).then_some(rounded)
}

/// "it has a, b" (or "it has none"), and the closest name when `name` looks like a typo of one.
/// Checks that every type of `types` (the list at `list`) is among `known`;
/// `missing` says what a type that is not means. Returns whether all are.
pub(super) fn types_among(
    ctx: &mut Context<'_>,
    list: &Path,
    types: &[String],
    known: &[&str],
    missing: impl Fn(&str) -> String,
) -> bool {
    let mut ok = true;
    for (i, kind) in types.iter().enumerate() {
        if !known.contains(&kind.as_str()) {
            ctx.error(
                &list.index(i),
                ErrorKind::DanglingReference(format!("{} ({})", missing(kind), known_names(kind, known))),
            );
            ok = false;
        }
    }
    ok
}

/// The distinct `types`, sorted.
pub(super) fn distinct<'a>(types: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let mut types: Vec<&str> = types.into_iter().collect();
    types.sort_unstable();
    types.dedup();
    types
}

pub(super) fn known_names(name: &str, known: &[&str]) -> String {
    let list = if known.is_empty() {
        "it has none".into()
    } else {
        format!("it has {}", known.join(", "))
    };
    match closest(name, known.iter().copied()) {
        Some(close) => format!("{list}; did you mean `{close}`?"),
        None => list,
    }
}
