//! Requirements and references: ids, checks, and `where` filters resolved to points.

use std::collections::{BTreeMap, HashMap};

use super::checks::{invalid_id, valid_id};
use super::compare;
use super::context::{Context, locate};
use super::objects;
use super::sweep::json_eq;
use crate::de::closest;
use crate::error::{ErrorKind, Location};
use crate::model::display_value;
use crate::model::{
    Bound, Check, Experiment, Metric, OverSeeds, Point, RateBound, Reference, Requirement, Settings, Statistic,
    Temporal,
};
use crate::path::Path;
use crate::raw::range;
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
            ctx.error(&id_path, invalid_id(&requirement.id));
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
        let min_samples = requirement.check.min_samples;
        if min_samples == Some(0) {
            ctx.error(
                &path.key("check").key("min_samples"),
                ErrorKind::Invalid("a check needs at least one sample: give 1 or more".into()),
            );
        }
        let accepted = requirement.accept_not_exercised.as_deref().map(str::trim);
        if accepted.is_some_and(str::is_empty) {
            ctx.error(
                &path.key("accept_not_exercised"),
                ErrorKind::Invalid("give the reason a not-exercised verdict is acceptable".into()),
            );
        }
        let Some(points) = points else {
            continue;
        };
        let selected = select(ctx, &requirement.filter, points, &path.key("where"));
        if let (Some(check), Some(selected)) = (check, selected) {
            let metrics = match check {
                Check::Metric { metric, .. } => vec![(metric, "metric")],
                Check::Compare { metric, other, .. } => vec![(metric, "metric"), (other, "relative_to")],
                _ => Vec::new(),
            };
            if !metrics
                .into_iter()
                .all(|(metric, key)| defined_everywhere(ctx, metric, &selected, points, &path.key("check").key(key)))
            {
                continue;
            }
            let semantic_at =
                |i: usize| matches!(&points[i].setup.experiment, Experiment::World(w) if w.semantic.is_some());
            let world_at =
                |i: usize| matches!(&points[i].setup.experiment, Experiment::World(w) if w.perception.is_some());
            let unmeasured = match check {
                Check::Temporal { signal, .. } => selected
                    .iter()
                    .find(|&&i| {
                        if signal.in_world() {
                            !world_at(i)
                        } else {
                            !semantic_at(i)
                        }
                    })
                    .map(|_| {
                        let kind = if signal.in_world() {
                            "collective perception"
                        } else {
                            "semantic"
                        };
                        (
                            "signal",
                            format!("signal `{}` is measured in {kind} worlds only", signal.name()),
                        )
                    }),
                Check::PerObject { property, .. } if property.needs_grid() => {
                    selected.iter().find(|&&i| !(semantic_at(i) && world_at(i))).map(|_| {
                        (
                            "per_object",
                            format!(
                                "`{}` reads the ego's fused grid, which only a joint world (`perception` and \
                                 `semantic`) has",
                                property.name()
                            ),
                        )
                    })
                }
                Check::PerObject { property, .. } if property.of_system() => {
                    selected.iter().find(|&&i| semantic_at(i) || !world_at(i)).map(|_| {
                        (
                            "per_object",
                            format!(
                                "`{}` judges a system under test, which runs in a perception world (`perception`, \
                                 no `semantic`) only",
                                property.name()
                            ),
                        )
                    })
                }
                Check::PerObject { property, .. } => selected.iter().find(|&&i| !semantic_at(i)).map(|_| {
                    (
                        "per_object",
                        format!(
                            "`{}` is measured in worlds with a semantic pipeline only",
                            property.name()
                        ),
                    )
                }),
                _ => None,
            };
            if let Some((key, message)) = unmeasured {
                ctx.error(&path.key("check").key(key), ErrorKind::Invalid(message));
                continue;
            }
            if let Check::Invariant { invariant, .. } = check
                && selected.iter().any(|&i| semantic_at(i) && !world_at(i))
            {
                ctx.error(
                    &path.key("check").key("invariant"),
                    ErrorKind::Invalid(format!(
                        "invariant `{}` checks fused grid cells, and a semantic world fuses none",
                        invariant.name()
                    )),
                );
                continue;
            }
            let objects = objects::selection(
                ctx,
                requirement.check.objects.as_ref(),
                check,
                (points, &selected),
                &path.key("check").key("objects"),
            );
            let Some(objects) = objects else { continue };
            let default_min = match check {
                Check::Metric { metric, .. } => metric.default_min_samples(),
                Check::Compare { metric, other, .. } => metric.default_min_samples().max(other.default_min_samples()),
                _ => 1,
            };
            compiled.push(Requirement {
                id: requirement.id.clone(),
                text: requirement.text.clone(),
                location: locate(ctx.tree, &path),
                check,
                points: selected,
                min_samples: min_samples.unwrap_or(default_min).max(1),
                accept_not_exercised: accepted.map(str::to_string),
                objects,
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

fn check(ctx: &mut Context<'_>, raw: &RawCheck, path: &Path) -> Option<Check> {
    let kinds = [
        raw.metric.is_some(),
        raw.signal.is_some(),
        raw.per_object.is_some(),
        raw.invariant.is_some(),
    ];
    if kinds.iter().filter(|&&k| k).count() != 1 {
        ctx.error(
            path,
            ErrorKind::Invalid(
                "a check names one of a `metric` (with `at_least` or `at_most`), a `signal` (with `always` or \
                 `eventually`), a `per_object` property or an `invariant`"
                    .into(),
            ),
        );
        return None;
    }
    if raw.signal.is_none() {
        let temporal = [
            ("always", raw.always.is_some()),
            ("eventually", raw.eventually.is_some()),
            ("within", raw.within.is_some()),
        ];
        if let Some((key, _)) = temporal.iter().find(|(_, given)| *given) {
            ctx.error(
                &path.key(key),
                ErrorKind::Invalid(format!(
                    "`{key}` applies to a `signal` over time, not to a single value"
                )),
            );
            return None;
        }
    }
    if raw.metric.is_none() {
        if !compare::refuse_without_metric(ctx, raw, path) {
            return None;
        }
        let statistical = [
            ("seeds", raw.seeds.is_some()),
            ("confidence", raw.confidence.is_some()),
            ("holds_in", raw.holds_in.is_some()),
            ("method", raw.method.is_some()),
        ];
        if let Some((key, _)) = statistical.iter().find(|(_, given)| *given) {
            ctx.error(
                &path.key(key),
                ErrorKind::Invalid(format!("`{key}` belongs to metric checks over seeds")),
            );
            return None;
        }
    }
    if raw.invariant.is_none() && raw.tolerance.is_some() {
        ctx.error(
            &path.key("tolerance"),
            ErrorKind::Invalid("`tolerance` belongs to invariant checks".into()),
        );
        return None;
    }
    if let Some(invariant) = raw.invariant {
        if raw.at_least.is_some() || raw.at_most.is_some() {
            ctx.error(
                path,
                ErrorKind::Invalid("an invariant check takes no `at_least` or `at_most`".into()),
            );
            return None;
        }
        let tolerance = raw.tolerance.unwrap_or(DEFAULT_TOLERANCE);
        return ctx
            .within(&path.key("tolerance"), tolerance, range::TOLERANCE)
            .then_some(Check::Invariant { invariant, tolerance });
    }
    if let Some(signal) = raw.signal {
        if raw.at_least.is_some() || raw.at_most.is_some() {
            ctx.error(
                path,
                ErrorKind::Invalid("a signal's threshold goes under `always` or `eventually`".into()),
            );
            return None;
        }
        let (operator, threshold, key) = match (&raw.always, &raw.eventually) {
            (Some(t), None) => (Temporal::Always, t, "always"),
            (None, Some(t)) => (Temporal::Eventually, t, "eventually"),
            _ => {
                ctx.error(
                    path,
                    ErrorKind::Invalid("a signal check gives exactly one of `always`, `eventually`".into()),
                );
                return None;
            }
        };
        let bound = bound(ctx, threshold.at_least, threshold.at_most, &path.key(key))?;
        let within_ok = raw
            .within
            .is_none_or(|w| ctx.within(&path.key("within"), w, range::SPAN));
        return within_ok.then_some(Check::Temporal {
            signal,
            operator,
            bound,
            within: raw.within,
        });
    }
    let bound = bound(ctx, raw.at_least, raw.at_most, path)?;
    if let Some(property) = raw.per_object {
        return Some(Check::PerObject { property, bound });
    }
    let metric = raw.metric.expect("one kind of check is named");
    let over_seeds = over_seeds(ctx, raw, path)?;
    compare::metric_check(ctx, raw, (metric, bound, over_seeds), path)
}

/// Exactly one of `at_least`, `at_most`, finite, under `path`.
fn bound(ctx: &mut Context<'_>, at_least: Option<f64>, at_most: Option<f64>, path: &Path) -> Option<Bound> {
    let (bound, key) = match (at_least, at_most) {
        (Some(t), None) => (Bound::AtLeast(t), "at_least"),
        (None, Some(t)) => (Bound::AtMost(t), "at_most"),
        _ => {
            ctx.error(
                path,
                ErrorKind::Invalid("give exactly one of `at_least`, `at_most`".into()),
            );
            return None;
        }
    };
    ctx.finite(&path.key(key), bound.threshold()).then_some(bound)
}

/// Default confidence of a check over seeds.
const DEFAULT_CONFIDENCE: f64 = 0.95;

/// The check over seeds, if any: `Some(None)` for a check on the point's own run,
/// `None` after an error.
fn over_seeds(ctx: &mut Context<'_>, raw: &RawCheck, path: &Path) -> Option<Option<OverSeeds>> {
    let Some(seeds) = raw.seeds else {
        let stray = [
            ("confidence", raw.confidence.is_some()),
            ("holds_in", raw.holds_in.is_some()),
            ("method", raw.method.is_some()),
        ];
        if let Some((key, _)) = stray.iter().find(|(_, given)| *given) {
            ctx.error(
                &path.key(key),
                ErrorKind::Invalid(format!("`{key}` belongs to checks over `seeds`")),
            );
            return None;
        }
        return Some(None);
    };
    if raw.method.is_some() && raw.holds_in.is_none() {
        ctx.error(
            &path.key("method"),
            ErrorKind::Invalid("`method` bounds the share of `holds_in`; a mean takes none".into()),
        );
        return None;
    }
    let confidence = raw.confidence.unwrap_or(DEFAULT_CONFIDENCE);
    let ok = ctx.expect(
        range::SEEDS.contains(f64::from(seeds)),
        &path.key("seeds"),
        &format!("a whole number from 2 to {}", range::SEEDS.max),
        f64::from(seeds),
    ) & ctx.expect(
        range::CONFIDENCE.contains(confidence),
        &path.key("confidence"),
        "a level above 0.5 and below 1",
        confidence,
    ) & raw.holds_in.is_none_or(|share| {
        if share == 1.0 {
            // Every seed holding bounds the share below 1: it could never pass.
            ctx.error(
                &path.key("holds_in"),
                ErrorKind::Invalid(
                    "`holds_in: 1` can never pass: a share's lower confidence bound is below 1 even with every \
                     seed holding ((1 − c)^(1/n) by Clopper–Pearson, n / (n + z²) by Wilson); require a share \
                     below 1"
                        .into(),
                ),
            );
            return false;
        }
        ctx.expect(
            range::SHARE_OF_SEEDS.contains(share),
            &path.key("holds_in"),
            "a share above 0 and below 1",
            share,
        )
    });
    let statistic = match raw.holds_in {
        None => Statistic::Mean,
        Some(share) => Statistic::Share {
            share,
            method: raw.method.unwrap_or(RateBound::ClopperPearson),
        },
    };
    ok.then_some(Some(OverSeeds {
        seeds,
        confidence,
        statistic,
    }))
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
            Experiment::World(world) if world.is_joint() => (metric.in_joint(), "a joint world"),
            Experiment::World(world) if world.semantic.is_some() => {
                (metric.in_semantic(), "a world with a semantic pipeline")
            }
            Experiment::World(_) => (metric.in_world(), "a world scenario"),
        };
        if !measured {
            let name = metric.name();
            let message = match metric {
                Metric::PacketDeliveryRatio => format!(
                    "metric `{name}` would not say which radio in a joint world, which has two: name \
                     `grid_packet_delivery_ratio` (the cooperating agents' messages to the ego) or \
                     `semantic_packet_delivery_ratio` (the roadside units' messages to the ego)"
                ),
                _ if metric.joint_only() => format!(
                    "metric `{name}` names one of the two radios of a joint world (`perception` and \
                     `semantic`), and {kind} has one: its `packet_delivery_ratio`"
                ),
                _ => format!("metric `{name}` is not measured in {kind}"),
            };
            ctx.error(path, ErrorKind::Invalid(message));
            return false;
        }
        let radio = match &point.setup.experiment {
            Experiment::World(world) => world.perception.as_ref().map(|p| p.messages.is_some()),
            Experiment::Field(_) => None,
        };
        if metric.needs_radio() && radio == Some(false) {
            ctx.error(
                path,
                ErrorKind::Invalid(format!(
                    "metric `{}` is measured over the radio, and the scenario declares no `v2x`: every grid reaches \
                     the ego whole and at once",
                    metric.name()
                )),
            );
            return false;
        }
        let fusion = point.setup.occupancy.as_ref().map(|o| &o.fusion.rule);
        if let Some(rule) = fusion.filter(|rule| metric.is_evidential_only() && !rule.is_evidential()) {
            let method = rule.method().name();
            let label = point.label();
            let advice = if label.is_empty() {
                format!("the scenario fuses with `{method}`")
            } else {
                format!("sweep point {label} fuses with `{method}`; restrict the check with `where`")
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

/// The points with a label whose settings match every entry of a `where`
/// filter (a point that several sweeps reach matches as each of them); `None`
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
        let found = settings(points).any(|s| s.get(key).is_some());
        if !found {
            let hint = suggest(&points[0].labels[0].settings, key)
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
            p.labels.iter().any(|label| {
                filter
                    .iter()
                    .all(|(key, want)| label.settings.get(key).is_some_and(|have| json_eq(have, want)))
            })
        })
        .map(|p| p.index)
        .collect();
    if selected.is_empty() {
        let seen: Vec<String> = filter
            .keys()
            .map(|key| {
                let mut values: Vec<String> = Vec::new();
                for settings in settings(points) {
                    if let Some(v) = settings.get(key).map(display_value)
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

/// The effective settings of every label of every point.
fn settings(points: &[Point]) -> impl Iterator<Item = &Settings> {
    points.iter().flat_map(|p| &p.labels).map(|label| &label.settings)
}

/// The setting closest to a dotted path that names none.
fn suggest(settings: &Settings, dotted: &str) -> Option<String> {
    let (prefix, last) = match dotted.rsplit_once('.') {
        Some((prefix, last)) => (Some(prefix), last),
        None => (None, dotted),
    };
    let best = match prefix {
        Some(prefix) => closest(last, settings.get(prefix)?.as_object()?.keys().map(String::as_str))?,
        None => closest(last, settings.sections())?,
    };
    Some(prefix.map_or_else(|| best.clone(), |prefix| format!("{prefix}.{best}")))
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
