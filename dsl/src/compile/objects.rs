//! The road users a per-object check judges, or the object-steps and
//! detections a system's metric (`sut_*`) is summed over (`check.objects`): ids, classes
//! and areas checked against what the scenario can produce at the
//! requirement's points, the window against the run. A selection that can
//! match nothing is an error here; one that matches nothing in a run is not
//! exercised there.

use std::collections::BTreeSet;

use super::checks::known_names;
use super::context::Context;
use crate::error::ErrorKind;
use crate::model::{AgentKind, Check, Experiment, Metric, ObjectProperty, ObjectSelection, Point, World};
use crate::path::Path;
use crate::raw::RawObjectSelection;
use crate::raw::range;

/// Compiles the selection of `check` at the `selected` points; `None` after
/// recording why.
pub(super) fn selection(
    ctx: &mut Context<'_>,
    raw: Option<&RawObjectSelection>,
    check: Check,
    (points, selected): (&[Point], &[usize]),
    path: &Path,
) -> Option<ObjectSelection> {
    let Some(raw) = raw else {
        return Some(ObjectSelection::default());
    };
    // An empty mapping selects as if it were absent: a key that changes nothing.
    let unset = raw.ids.is_empty()
        && raw.classes.is_empty()
        && raw.areas.is_empty()
        && raw.between.is_none()
        && raw.closer_than.is_none();
    if unset
        && ["ids", "classes", "areas", "between", "closer_than"]
            .iter()
            .all(|key| !ctx.has(&path.key(key)))
    {
        ctx.error(
            path,
            ErrorKind::Invalid(
                "an empty selection selects every road user, as no `objects` does; leave `objects` out, or select \
                 by `ids`, `classes`, `areas`, `between` or `closer_than`"
                    .into(),
            ),
        );
        return None;
    }
    match check {
        Check::Metric { metric, over_seeds, .. } if metric.of_system() => {
            if !of_system(ctx, raw, metric, over_seeds.is_some(), path) {
                return None;
            }
        }
        Check::Compare { metric, other, .. } if metric.of_system() || other.of_system() => {
            ctx.error(
                path,
                ErrorKind::Invalid(
                    "`objects` does not select within a comparison (`relative_to`); check each metric over \
                     the selection on its own"
                        .into(),
                ),
            );
            return None;
        }
        Check::PerObject { property, .. } if !property.of_record() => {
            // The grid's properties are offered only where a joint world has a grid.
            let joint = selected.iter().any(|&i| match &points[i].setup.experiment {
                Experiment::World(world) => world.is_joint(),
                Experiment::Field(_) => false,
            });
            let of_record: Vec<String> = ObjectProperty::ALL
                .iter()
                .filter(|p| p.of_record() && !p.of_system() && (joint || !p.needs_grid()))
                .map(|p| format!("`{}`", p.name()))
                .collect();
            ctx.error(
                path,
                ErrorKind::Invalid(format!(
                    "`{}` judges close approaches, which `objects` cannot select; judge the relevant road users' \
                     records instead ({})",
                    property.name(),
                    of_record.join(", ")
                )),
            );
            return None;
        }
        Check::PerObject { .. } => {}
        _ => {
            ctx.error(
                path,
                ErrorKind::Invalid(
                    "`objects` selects the road users of a `per_object` check, or what a system's metric \
                     (`sut_*`) is summed over"
                        .into(),
                ),
            );
            return None;
        }
    }
    let worlds: Vec<&World> = selected
        .iter()
        .filter_map(|&i| match &points[i].setup.experiment {
            Experiment::World(world) => Some(&**world),
            Experiment::Field(_) => None,
        })
        .collect();
    let mut ok = true;
    // An empty list would select nothing, though a missing one selects all.
    for (key, empty) in [
        ("ids", raw.ids.is_empty()),
        ("classes", raw.classes.is_empty()),
        ("areas", raw.areas.is_empty()),
    ] {
        if empty && ctx.has(&path.key(key)) {
            ctx.error(
                &path.key(key),
                ErrorKind::Invalid(format!(
                    "an empty list selects nothing; leave `{key}` out to select by the others"
                )),
            );
            ok = false;
        }
    }
    let road_users: BTreeSet<&str> = worlds.iter().flat_map(|w| road_users(w).map(|(_, id)| id)).collect();
    for (i, id) in raw.ids.iter().enumerate() {
        if !road_users.contains(id.as_str()) {
            let known: Vec<&str> = road_users.iter().copied().collect();
            ctx.error(
                &path.key("ids").index(i),
                ErrorKind::DanglingReference(format!(
                    "no road user `{id}` besides the ego and the roadside units ({}); generated road users are \
                     selected by `classes` and `areas`",
                    known_names(id, &known)
                )),
            );
            ok = false;
        }
    }
    // Precision and ghosts select detections by the class the system reports,
    // which may be one no road user of the scenario has (a ghost pedestrian).
    let by_reported_class = matches!(
        check,
        Check::Metric {
            metric: Metric::SutPrecision | Metric::SutGhosts,
            ..
        }
    );
    let classes: BTreeSet<&str> = worlds.iter().flat_map(|w| classes(w)).map(AgentKind::name).collect();
    for (i, class) in raw.classes.iter().enumerate() {
        if !by_reported_class && !classes.contains(class.name()) {
            let known: Vec<&str> = classes.iter().copied().collect();
            ctx.error(
                &path.key("classes").index(i),
                ErrorKind::DanglingReference(format!(
                    "no road user of class `{}` can occur in this scenario ({})",
                    class.name(),
                    known_names(class.name(), &known)
                )),
            );
            ok = false;
        }
    }
    let areas: BTreeSet<&str> = worlds.iter().flat_map(|w| area_ids(w)).collect();
    for (i, area) in raw.areas.iter().enumerate() {
        if !areas.contains(area.as_str()) {
            let known: Vec<&str> = areas.iter().copied().collect();
            ctx.error(
                &path.key("areas").index(i),
                ErrorKind::DanglingReference(format!(
                    "no crosswalk, interaction area or `areas` entry `{area}` ({})",
                    known_names(area, &known)
                )),
            );
            ok = false;
        }
    }
    if let Some([from, to]) = raw.between {
        let duration = worlds
            .iter()
            .map(|w| w.steps as f64 * w.step)
            .fold(f64::INFINITY, f64::min);
        // A window past the run's end holds moments no run covers: what it
        // selects would pass for a judgement of them.
        let valid = from.is_finite() && to.is_finite() && 0.0 <= from && from < to && to <= duration;
        if !valid {
            ctx.error(
                &path.key("between"),
                ErrorKind::Invalid(format!(
                    "a window [from, to] of seconds within the run, 0 ≤ from < to ≤ its end at {duration} s; \
                     found [{from}, {to}]"
                )),
            );
            ok = false;
        }
    }
    if let Some(distance) = raw.closer_than {
        ok &= ctx.within(&path.key("closer_than"), distance, range::EXTENT);
    }
    ok.then(|| ObjectSelection {
        ids: raw.ids.clone(),
        classes: raw.classes.clone(),
        areas: raw.areas.clone(),
        between: raw.between,
        closer_than: raw.closer_than,
    })
}

/// Errors where a selection of what `metric`, a system's, is summed over asks
/// for what the system's judge does not select by: a window or a distance to
/// an ego (a semantic pipeline's), or a check over seeds.
fn of_system(ctx: &mut Context<'_>, raw: &RawObjectSelection, metric: Metric, over_seeds: bool, path: &Path) -> bool {
    let name = metric.name();
    if over_seeds {
        ctx.error(
            path,
            ErrorKind::Invalid(
                "`objects` selects within the system's one run, and a check over `seeds` reads several: leave out \
                 `seeds` or `objects`"
                    .into(),
            ),
        );
        return false;
    }
    let unselected = [
        ("between", raw.between.is_some()),
        ("closer_than", raw.closer_than.is_some()),
    ];
    let by_detection = matches!(metric, Metric::SutPrecision | Metric::SutGhosts);
    if let Some((key, _)) = unselected.iter().find(|(_, given)| *given) {
        let keys = if by_detection {
            "`classes` and `areas`"
        } else {
            "`ids`, `classes` and `areas`"
        };
        ctx.error(
            &path.key(key),
            ErrorKind::Invalid(format!(
                "`{key}` selects road users by their closest approach to a semantic pipeline's ego; `{name}` \
                 selects what it is summed over by {keys} only"
            )),
        );
        return false;
    }
    // Ids keep only the detections that matched one of those road users: no
    // ghost is ever kept, whatever the system reports.
    if by_detection && !raw.ids.is_empty() {
        let outcome = if metric == Metric::SutPrecision { "1" } else { "0" };
        ctx.error(
            &path.key("ids"),
            ErrorKind::Invalid(format!(
                "`ids` keeps only the detections that matched one of those road users, so `{name}` would be \
                 {outcome} whatever the system reports; select detections by `classes` or `areas`"
            )),
        );
        return false;
    }
    true
}

/// The road users of `world` a record can be about: every agent but the ego
/// (the semantic pipeline's, or in a perception world the perception's) and
/// the roadside units, with its index.
fn road_users(world: &World) -> impl Iterator<Item = (usize, &str)> {
    let ego = (world.semantic.as_ref().map(|s| s.ego)).or(world.perception.as_ref().map(|p| p.ego));
    world
        .agents
        .iter()
        .enumerate()
        .filter(move |&(i, a)| Some(i) != ego && a.kind != AgentKind::Rsu)
        .map(|(i, a)| (i, a.id.as_str()))
}

/// The classes a road user of `world` can have: its declared and traced
/// agents', and its generated traffic's.
fn classes(world: &World) -> Vec<AgentKind> {
    let mut kinds: Vec<AgentKind> = road_users(world).map(|(i, _)| world.agents[i].kind).collect();
    if let Some(traffic) = &world.traffic {
        kinds.extend(
            traffic
                .vehicles
                .iter()
                .flat_map(|v| v.mix.iter().map(|&(kind, _)| kind)),
        );
        if traffic.pedestrians.is_some() {
            kinds.push(AgentKind::Pedestrian);
        }
    }
    kinds
}

/// The ids of every region of `world` a selection can name.
fn area_ids(world: &World) -> impl Iterator<Item = &str> {
    let crosswalks = world.crosswalks.iter().map(|c| c.id.as_str());
    let regions = world
        .interaction_areas
        .iter()
        .chain(&world.areas)
        .map(|a| a.id.as_str());
    crosswalks.chain(regions)
}
