//! Requirements and references: ids, checks, and `where` filters resolved to points.

use std::collections::{BTreeMap, HashMap};

use super::context::{Context, locate};
use super::sweep::json_eq;
use crate::de::closest;
use crate::error::{ErrorKind, Location};
use crate::model::display_value;
use crate::model::{Bound, Check, Experiment, Metric, Point, Reference, Requirement};
use crate::path::Path;
use crate::raw::{RawCheck, RawReference, RawRequirement};

/// Tolerance of an invariant check when the file gives none.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Compiles the requirements against the compiled points. Without points (the
/// setup is invalid) only what does not depend on them is checked.
pub(super) fn requirements(
    ctx: &mut Context<'_>,
    raw: &[RawRequirement],
    points: Option<&[Point]>,
) -> Vec<Requirement> {
    let list = Path::root().key("requirements");
    let mut first_seen: HashMap<&str, Location> = HashMap::new();
    let mut compiled = Vec::new();
    for (i, requirement) in raw.iter().enumerate() {
        let path = list.index(i);
        let id_path = path.key("id");
        let id_ok = valid_id(&requirement.id);
        if !id_ok {
            ctx.error(
                &id_path,
                ErrorKind::Invalid(format!(
                    "an id is one or more letters, digits, `-`, `_` or `.`; found \"{}\"",
                    requirement.id
                )),
            );
        } else if let Some(&first) = first_seen.get(requirement.id.as_str()) {
            ctx.error(
                &id_path,
                ErrorKind::DuplicateId {
                    id: requirement.id.clone(),
                    first,
                },
            );
        } else {
            first_seen.insert(&requirement.id, locate(ctx.tree, &id_path));
        }
        if requirement.text.trim().is_empty() {
            ctx.error(
                &path.key("text"),
                ErrorKind::Invalid("a requirement needs its text".into()),
            );
        }
        let check = check(ctx, &requirement.check, &path.key("check"));
        let Some(points) = points else {
            continue;
        };
        let selected = select(ctx, &requirement.filter, points, &path.key("where"));
        if let (Some(check), Some(selected)) = (check, selected) {
            if let Check::Metric { metric, .. } = check
                && !defined_everywhere(ctx, metric, &selected, points, &path.key("check").key("metric"))
            {
                continue;
            }
            if let Check::Invariant { invariant, .. } = check
                && selected
                    .iter()
                    .any(|&i| matches!(&points[i].setup.experiment, Experiment::World(w) if w.semantic.is_some()))
            {
                ctx.error(
                    &path.key("check").key("invariant"),
                    ErrorKind::Invalid(format!(
                        "invariant `{}` checks fused grid cells, and a world with a semantic pipeline fuses none",
                        invariant.name()
                    )),
                );
                continue;
            }
            compiled.push(Requirement {
                id: requirement.id.clone(),
                text: requirement.text.clone(),
                location: locate(ctx.tree, &path),
                check,
                points: selected,
            });
        }
    }
    compiled
}

/// Compiles the published figures against the compiled points (when there are any).
pub(super) fn references(ctx: &mut Context<'_>, raw: &[RawReference], points: Option<&[Point]>) -> Vec<Reference> {
    let list = Path::root().key("references");
    let mut compiled = Vec::new();
    for (i, reference) in raw.iter().enumerate() {
        let path = list.index(i);
        if reference.source.trim().is_empty() {
            ctx.error(
                &path.key("source"),
                ErrorKind::Invalid("name the source of the figure".into()),
            );
        }
        let value_ok = ctx.finite(&path.key("value"), reference.value);
        let Some(points) = points else {
            continue;
        };
        let Some(selected) = select(ctx, &reference.filter, points, &path.key("where")) else {
            continue;
        };
        if value_ok && defined_everywhere(ctx, reference.metric, &selected, points, &path.key("metric")) {
            compiled.push(Reference {
                source: reference.source.clone(),
                metric: reference.metric,
                value: reference.value,
                points: selected,
            });
        }
    }
    compiled
}

fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

fn check(ctx: &mut Context<'_>, raw: &RawCheck, path: &Path) -> Option<Check> {
    match (raw.metric, raw.invariant) {
        (Some(metric), None) => {
            if raw.tolerance.is_some() {
                ctx.error(
                    &path.key("tolerance"),
                    ErrorKind::Invalid("`tolerance` belongs to invariant checks".into()),
                );
                return None;
            }
            let bound = match (raw.at_least, raw.at_most) {
                (Some(t), None) => Bound::AtLeast(t),
                (None, Some(t)) => Bound::AtMost(t),
                _ => {
                    ctx.error(
                        path,
                        ErrorKind::Invalid("a metric check gives exactly one of `at_least`, `at_most`".into()),
                    );
                    return None;
                }
            };
            let key = if raw.at_least.is_some() { "at_least" } else { "at_most" };
            ctx.finite(&path.key(key), bound.threshold())
                .then_some(Check::Metric { metric, bound })
        }
        (None, Some(invariant)) => {
            if raw.at_least.is_some() || raw.at_most.is_some() {
                ctx.error(
                    path,
                    ErrorKind::Invalid("an invariant check takes no `at_least` or `at_most`".into()),
                );
                return None;
            }
            let tolerance = raw.tolerance.unwrap_or(DEFAULT_TOLERANCE);
            ctx.non_negative(&path.key("tolerance"), tolerance)
                .then_some(Check::Invariant { invariant, tolerance })
        }
        _ => {
            ctx.error(
                path,
                ErrorKind::Invalid(
                    "a check names either a `metric` (with `at_least` or `at_most`) or an `invariant`".into(),
                ),
            );
            None
        }
    }
}

/// Errors unless `metric` is produced at every selected point: by its kind of
/// scenario, and by its fusion method (conflict metrics need an evidential rule).
fn defined_everywhere(
    ctx: &mut Context<'_>,
    metric: Metric,
    selected: &[usize],
    points: &[Point],
    path: &Path,
) -> bool {
    for &i in selected {
        let point = &points[i];
        let (measured, kind) = match &point.setup.experiment {
            Experiment::Field(_) => (metric.in_field(), "the field experiment"),
            Experiment::World(world) if world.semantic.is_some() => {
                (metric.in_semantic(), "a world with a semantic pipeline")
            }
            Experiment::World(_) => (metric.in_world(), "a world scenario"),
        };
        if !measured {
            ctx.error(
                path,
                ErrorKind::Invalid(format!("metric `{}` is not measured in {kind}", metric.name())),
            );
            return false;
        }
        if metric.is_evidential_only() && !point.setup.fusion.rule.is_evidential() {
            let method = point.setup.fusion.rule.method().name();
            let advice = if point.assignments.is_empty() {
                format!("the scenario fuses with `{method}`")
            } else {
                format!(
                    "sweep point {} fuses with `{method}`; restrict the check with `where`",
                    point.label()
                )
            };
            ctx.error(
                path,
                ErrorKind::Invalid(format!(
                    "metric `{}` exists only for evidential fusion methods, and {advice}",
                    metric.name()
                )),
            );
            return false;
        }
    }
    true
}

/// The points whose settings match every entry of a `where` filter; `None`
/// (after recording why) when a key names no setting or nothing matches.
pub(super) fn select(
    ctx: &mut Context<'_>,
    filter: &BTreeMap<String, serde_json::Value>,
    points: &[Point],
    path: &Path,
) -> Option<Vec<usize>> {
    let mut ok = true;
    for key in filter.keys() {
        let key_path = path.key(key);
        let found = points.iter().any(|p| lookup(&p.settings, key).is_some());
        if !found {
            let hint = suggest(&points[0].settings, key)
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            ctx.error_at_key(
                &key_path,
                ErrorKind::DanglingReference(format!("`{key}` names no setting of this scenario{hint}")),
            );
            ok = false;
        }
    }
    if !ok {
        return None;
    }
    let selected: Vec<usize> = points
        .iter()
        .filter(|p| {
            filter
                .iter()
                .all(|(key, want)| lookup(&p.settings, key).is_some_and(|have| json_eq(have, want)))
        })
        .map(|p| p.index)
        .collect();
    if selected.is_empty() {
        let seen: Vec<String> = filter
            .keys()
            .map(|key| {
                let mut values: Vec<String> = Vec::new();
                for p in points {
                    if let Some(v) = lookup(&p.settings, key).map(display_value)
                        && !values.contains(&v)
                    {
                        values.push(v);
                    }
                }
                format!("`{key}` takes {}", values.join(", "))
            })
            .collect();
        ctx.error(
            path,
            ErrorKind::DanglingReference(format!("matches no sweep point ({})", seen.join("; "))),
        );
        return None;
    }
    Some(selected)
}

/// The setting at a dotted path.
fn lookup<'a>(settings: &'a serde_json::Value, dotted: &str) -> Option<&'a serde_json::Value> {
    dotted.split('.').try_fold(settings, |node, key| node.get(key))
}

/// The closest existing dotted path to a mistyped one.
fn suggest(settings: &serde_json::Value, dotted: &str) -> Option<String> {
    let (parent, last) = match dotted.rsplit_once('.') {
        Some((parent, last)) => (lookup(settings, parent)?, last),
        None => (settings, dotted),
    };
    let keys: Vec<&str> = parent.as_object()?.keys().map(String::as_str).collect();
    let best = closest(last, keys.iter().copied())?;
    Some(match dotted.rsplit_once('.') {
        Some((prefix, _)) => format!("{prefix}.{best}"),
        None => best,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_plain_names() {
        assert!(valid_id("FIELD-ERR-01"));
        assert!(valid_id("a.b_c"));
        assert!(!valid_id(""));
        assert!(!valid_id("has space"));
        assert!(!valid_id("<script>"));
    }
}
