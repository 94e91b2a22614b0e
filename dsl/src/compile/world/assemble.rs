//! A world assembled from its sections, each compiled once and in the order
//! they depend on each other, and the run's number of steps.

use super::agents::{Scene, agents};
use super::joint::joint;
use super::occluders::occluders;
use super::perception::perception_of;
use super::roads::roads;
use super::routes::RoadIndex;
use super::semantic::{areas, crosswalks, driving, interaction_areas, own_antennas, semantic_of, traffic, v2x};
use super::sensors::{localization, sensor_models};
use crate::compile::checks::whole_multiple;
use crate::compile::context::Context;
use crate::compile::map::Mapped;
use crate::compile::traces::Imported;
use crate::error::ErrorKind;
use std::collections::BTreeSet;

use crate::model::World;
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawScenario, RawTime, RawV2x};

/// The most steps a run may have.
pub const MAX_STEPS: usize = 100_000;

/// Compiles the world sections of a scenario that has no `field`, with what its
/// `traces` and `map` import (`None` when it has none).
pub(crate) fn world(
    ctx: &mut Context<'_>,
    raw: &RawScenario,
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> Option<World> {
    let root = Path::root();
    let Some(time) = &raw.time else {
        ctx.error(
            &root,
            ErrorKind::Invalid(
                "a scenario simulates a `field` or a world; a world needs `time: { duration, step }`".into(),
            ),
        );
        return None;
    };
    let steps = time_steps(ctx, time, &root.key("time"));
    let (sensors, sensors_ok) = sensor_models(ctx, raw);
    let localization = localization(ctx, raw);
    let driving = driving(ctx, &raw.driving);
    let v2x = v2x(ctx, raw.v2x.as_ref().unwrap_or(&RawV2x::default()));
    if raw.traces.is_some() && imported.is_none() || raw.map.is_some() && mapped.is_none() {
        // A file of `traces` or `map` failed to load, and its errors are recorded: what
        // the sections that depend on it would say without it would mislead.
        return None;
    }
    let (roads, roads_ok) = roads(ctx, &raw.roads, imported, mapped);
    let occluders = occluders(ctx, &raw.occluders, imported, mapped);
    let road_index = RoadIndex::new(&roads);
    let walkways = RoadIndex::new(mapped.map_or(&[], |m| &m.walkways));
    let scene = Scene {
        roads: &road_index,
        walkways: &walkways,
        sensors: &sensors,
        imported,
        duration: time.duration,
    };
    let agents = agents(ctx, &raw.agents, &scene).filter(|(agents, _)| match &v2x {
        Some(v2x) => own_antennas(ctx, v2x, agents),
        None => true,
    });
    // A joint world gives both; its `v2x.penetration` is refused below.
    let is_joint = raw.perception.is_some() && raw.semantic.is_some();
    let perception = match (&raw.perception, &agents, steps) {
        (Some(perception), Some((agents, _)), Some(steps)) => {
            perception_of(ctx, perception, (raw.v2x.as_ref(), is_joint), agents, time.step, steps).map(Some)
        }
        (None, _, _) => Some(None),
        _ => None,
    };
    let crosswalks = crosswalks(ctx, &raw.crosswalks, imported, mapped);
    let interaction_areas = interaction_areas(ctx, &raw.interaction_areas, imported, mapped);
    let areas = match (&crosswalks, &interaction_areas) {
        (Some(crosswalks), Some(interaction)) => areas(ctx, &raw.areas, crosswalks, interaction, imported),
        _ => None,
    };
    let traffic = raw
        .traffic
        .as_ref()
        .map(|t| traffic(ctx, t, &road_index, crosswalks.as_deref()));
    let semantic = match (&raw.semantic, &agents) {
        (Some(semantic), Some((agents, _))) => semantic_of(ctx, semantic, agents, time.step, is_joint).map(Some),
        (None, _) => Some(None),
        _ => None,
    };
    let joint_ok = match (is_joint, &agents) {
        (true, Some((agents, _))) => joint(
            ctx,
            raw,
            agents,
            (
                perception.as_ref().and_then(Option::as_ref),
                semantic.as_ref().and_then(Option::as_ref),
            ),
        ),
        _ => true,
    };
    if raw.perception.is_none() && raw.semantic.is_none() {
        ctx.error(
            &root,
            ErrorKind::Invalid(
                "a world measures collective perception (`perception: { ego: … }`) or the semantic pipeline \
                 (`semantic: { ego: … }`)"
                    .into(),
            ),
        );
        return None;
    }
    let connections = connections(raw, &road_index);
    if !joint_ok {
        return None;
    }
    Some(World {
        step: time.step,
        steps: steps?,
        connections,
        roads: roads_ok.then_some(roads)?,
        occluders: occluders?,
        imported: agents.as_ref().map_or(0, |(_, imported)| *imported),
        agents: sensors_ok.then_some(agents?.0)?,
        localization: localization?,
        perception: perception?,
        traffic: traffic.map_or(Some(None), |t| t.map(Some))?,
        crosswalks: crosswalks?,
        interaction_areas: interaction_areas?,
        areas: areas?,
        driving: driving?,
        v2x: v2x?,
        semantic: semantic?,
        uncovered: imported
            .and_then(|i| i.coverage(time.duration, time.step))
            .map(|w| w.message),
    })
}

/// The pairs of roads, by index, that a declared route drives from one into
/// the other (an agent's `route`, a route of `traffic.vehicles`), sorted. The
/// routes themselves are checked where they are resolved (`routes`).
fn connections(raw: &RawScenario, roads: &RoadIndex<'_>) -> Vec<(usize, usize)> {
    let index = |id: &String| roads.position(id);
    let agent_routes = raw.agents.iter().filter_map(|agent| agent.route.as_ref());
    let traffic_routes = raw
        .traffic
        .iter()
        .filter_map(|traffic| traffic.vehicles.as_ref())
        .flat_map(|vehicles| &vehicles.routes);
    let pairs: BTreeSet<(usize, usize)> = agent_routes
        .chain(traffic_routes)
        .flat_map(|route| route.windows(2))
        .filter_map(|pair| Some((index(&pair[0])?, index(&pair[1])?)))
        .collect();
    pairs.into_iter().collect()
}

fn time_steps(ctx: &mut Context<'_>, time: &RawTime, path: &Path) -> Option<usize> {
    let ok = ctx.within(&path.key("duration"), time.duration, range::DURATION)
        & ctx.within(&path.key("step"), time.step, range::STEP);
    if !ok {
        return None;
    }
    match whole_multiple(time.duration, time.step) {
        Some(n) if n <= MAX_STEPS as f64 => Some(n as usize),
        Some(n) => {
            ctx.error(
                path,
                ErrorKind::TooLarge(format!("{n:.0} steps exceed the limit of {MAX_STEPS}")),
            );
            None
        }
        None => {
            ctx.error(
                &path.key("duration"),
                ErrorKind::OutOfRange {
                    expected: format!("a whole number of {} s steps", time.step),
                    found: time.duration.to_string(),
                },
            );
            None
        }
    }
}
