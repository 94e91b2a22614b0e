//! Agents: the declared ones with their footprint, sensors and motion (standing,
//! along a route or a path, or replaying a trace), then the traced objects none
//! of them replays.

use std::collections::{HashMap, HashSet};

use super::routes::{RoadIndex, route_path};
use crate::compile::checks::{coordinates, known_names, reserved, unique_ids};
use crate::compile::context::{Context, Declaration};
use crate::compile::traces::{Imported, imported_agents, trace_motion};
use crate::error::ErrorKind;
use crate::geometry::Polyline;
use crate::model::{Agent, AgentKind, Entry, Motion, Sensor};
use crate::path::Path;
use crate::raw::RawAgent;
use crate::raw::range;

/// What agents are resolved against.
pub(super) struct Scene<'a> {
    /// Every road, declared and imported.
    pub(super) roads: &'a RoadIndex<'a>,
    /// The sidewalks of `map`, which pedestrians' routes name.
    pub(super) walkways: &'a RoadIndex<'a>,
    /// The sensor models by id.
    pub(super) sensors: &'a HashMap<String, Sensor>,
    /// What `traces` imports.
    pub(super) imported: Option<&'a Imported>,
    /// Length of the run, seconds.
    pub(super) duration: f64,
}

/// The declared agents, then the objects of the trace none of them replays; and
/// how many of those there are.
pub(super) fn agents(ctx: &mut Context<'_>, raw: &[RawAgent], scene: &Scene<'_>) -> Option<(Vec<Agent>, usize)> {
    let list = Path::root().key("agents");
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|a| a.id.as_str()));
    for (i, agent) in raw.iter().enumerate() {
        if let Some(why) = reserved(&agent.id) {
            ctx.error(
                &list.index(i).key("id"),
                ErrorKind::Invalid(format!("`{}` is {why}; choose another id", agent.id)),
            );
            ok = false;
        }
    }
    if let Some(imported) = scene.imported {
        let objects: HashSet<&str> = imported.ids().collect();
        for (i, agent) in raw.iter().enumerate() {
            if objects.contains(agent.id.as_str()) && agent.trace.as_ref() != Some(&agent.id) {
                ctx.error(
                    &list.index(i).key("id"),
                    ErrorKind::Invalid(format!(
                        "`{0}` is also the id of an object of `traces.fcd`: replay it with `trace: {0}`, or \
                         choose another id",
                        agent.id
                    )),
                );
                ok = false;
            }
        }
    }
    // Each traced object, by the first agent that replays it.
    let mut replayed: HashMap<&str, usize> = HashMap::new();
    let mut agents = Vec::new();
    for (i, agent) in raw.iter().enumerate() {
        if let Some(trace) = &agent.trace {
            if let Some(&first) = replayed.get(trace.as_str()) {
                ctx.error(
                    &list.index(i).key("trace"),
                    ErrorKind::Invalid(format!("agent `{}` replays `{trace}` already", raw[first].id)),
                );
                ok = false;
            } else {
                replayed.insert(trace, i);
            }
        }
        match agent_of(ctx, agent, &list.index(i), scene) {
            Some(agent) => agents.push(agent),
            None => ok = false,
        }
    }
    if let Some(imported) = scene.imported {
        match poi_rsus(ctx, raw, imported, scene) {
            Some(rsus) => agents.extend(rsus),
            None => ok = false,
        }
    }
    let imported = scene.imported.map_or_else(Vec::new, |imported| {
        let declared = raw.iter().map(|a| a.id.as_str()).chain(replayed.into_keys()).collect();
        imported_agents(imported, &declared, scene.duration)
    });
    let count = imported.len();
    agents.extend(imported);
    ok.then_some((agents, count))
}

/// The roadside units of `traces.rsus`: standing, connected, with their
/// sensors; ids distinct from the declared agents' and the trace's objects'.
fn poi_rsus(ctx: &mut Context<'_>, raw: &[RawAgent], imported: &Imported, scene: &Scene<'_>) -> Option<Vec<Agent>> {
    let at = Path::root().key("traces").key("rsus");
    let mut ok = true;
    let mut sensors = Vec::new();
    for (i, name) in imported.rsu_sensors.iter().enumerate() {
        match resolve_sensor(ctx, name, &at.key("sensors").index(i), scene) {
            Some(sensor) => sensors.push(sensor),
            None => ok = false,
        }
    }
    let objects: HashSet<&str> = imported.ids().collect();
    for rsu in &imported.rsus {
        let clash = if raw.iter().any(|a| a.id == rsu.id) {
            Some("a declared agent")
        } else if objects.contains(rsu.id.as_str()) {
            Some("an object of the trace")
        } else {
            None
        };
        if let Some(clash) = clash {
            ctx.error(
                &at.key("poi_type"),
                ErrorKind::Invalid(format!(
                    "point of interest `{}` would be a roadside unit with the id of {clash}",
                    rsu.id
                )),
            );
            ok = false;
        }
    }
    let (length, width) = AgentKind::Rsu.footprint();
    ok.then(|| {
        imported
            .rsus
            .iter()
            .map(|rsu| Agent {
                id: rsu.id.clone(),
                kind: AgentKind::Rsu,
                length,
                width,
                motion: Motion::Fixed {
                    position: rsu.position,
                    heading: 0.0,
                },
                connected: true,
                sensors: sensors.clone(),
                antenna_m: rsu.antenna_m,
            })
            .collect()
    })
}

/// The sensor model `name`, or an error at `path` (unless the model's own
/// errors say why).
fn resolve_sensor(ctx: &mut Context<'_>, name: &str, path: &Path, scene: &Scene<'_>) -> Option<Sensor> {
    if let Some(sensor) = scene.sensors.get(name) {
        return Some(sensor.clone());
    }
    if !ctx.is_failed(Declaration::SensorModel, name) {
        let mut known: Vec<&str> = scene.sensors.keys().map(String::as_str).collect();
        known.sort_unstable();
        ctx.error(
            path,
            ErrorKind::DanglingReference(format!(
                "no sensor model `{name}` in `sensor_models` ({})",
                known_names(name, &known)
            )),
        );
    }
    None
}

fn agent_of(ctx: &mut Context<'_>, raw: &RawAgent, path: &Path, scene: &Scene<'_>) -> Option<Agent> {
    let (default_length, default_width) = raw.kind.footprint();
    let (length, width) = match &raw.size {
        Some(size) => {
            let ok = ctx.within(&path.key("size").key("length"), size.length, range::BODY)
                & ctx.within(&path.key("size").key("width"), size.width, range::BODY);
            if !ok {
                return None;
            }
            (size.length, size.width)
        }
        None => (default_length, default_width),
    };
    let mut resolved = Vec::new();
    let mut sensors_ok = true;
    for (i, name) in raw.sensors.iter().enumerate() {
        match resolve_sensor(ctx, name, &path.key("sensors").index(i), scene) {
            Some(sensor) => resolved.push(sensor),
            None => sensors_ok = false,
        }
    }
    let motion = motion(ctx, raw, path, scene, length);
    Some(Agent {
        id: raw.id.clone(),
        kind: raw.kind,
        length,
        width,
        motion: motion?,
        connected: raw.connected,
        sensors: sensors_ok.then_some(resolved)?,
        antenna_m: None,
    })
}

/// How an agent moves: roadside units stand, vehicles follow their route,
/// pedestrians their path, and either may replay a trace instead.
fn motion(ctx: &mut Context<'_>, raw: &RawAgent, path: &Path, scene: &Scene<'_>, length: f64) -> Option<Motion> {
    let allowed: &[&str] = match raw.kind {
        AgentKind::Rsu => &["position"],
        AgentKind::Pedestrian => &["path", "route", "trace"],
        _ => &["route", "trace"],
    };
    let given: Vec<&str> = [
        ("route", raw.route.is_some()),
        ("path", raw.path.is_some()),
        ("position", raw.position.is_some()),
        ("trace", raw.trace.is_some()),
    ]
    .into_iter()
    .filter_map(|(key, given)| given.then_some(key))
    .collect();
    let ways = allowed
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(" or ");
    let problem = match (given.iter().find(|key| !allowed.contains(key)), given.len()) {
        (Some(key), _) => Some(format!(", not by `{key}`")),
        (None, 0) => Some(String::new()),
        (None, 1) => None,
        (None, _) => Some(", not by both".into()),
    };
    if let Some(problem) = problem {
        let kind = serde_json::to_value(raw.kind)
            .ok()
            .and_then(|v| v.as_str().map(str::to_owned))
            .unwrap_or_default();
        ctx.error(
            path,
            ErrorKind::Invalid(format!("an agent of kind {kind} moves by {ways}{problem}")),
        );
        return None;
    }
    if let Some(position) = raw.position {
        let ok = coordinates(ctx, &path.key("position"), &[position])
            & ctx.within(&path.key("heading_deg"), raw.heading_deg, range::ANGLE);
        return ok.then_some(Motion::Fixed {
            position,
            heading: raw.heading_deg.to_radians(),
        });
    }
    if let Some(id) = &raw.trace {
        return trace(ctx, id, path, scene, raw.kind, length);
    }
    let Some(speed) = &raw.speed else {
        ctx.error(
            path,
            ErrorKind::Invalid("a moving agent needs `speed: { target: … }`".into()),
        );
        return None;
    };
    let speed_path = path.key("speed");
    let initial = speed.initial.unwrap_or(speed.target);
    let ok = ctx.within(&speed_path.key("target"), speed.target, range::SPEED)
        & ctx.within(&speed_path.key("initial"), initial, range::SPEED)
        & ctx.within(&speed_path.key("acceleration"), speed.acceleration, range::ACCELERATION)
        & ctx.within(&speed_path.key("limit_factor"), speed.limit_factor, range::SPEED_FACTOR)
        & ctx.within(&path.key("start").key("time"), raw.start.time, range::TIME)
        & ctx.within(&path.key("start").key("offset"), raw.start.offset, range::OFFSET);
    let (along, limits) = match (&raw.route, &raw.path) {
        (Some(route), _) if raw.kind == AgentKind::Pedestrian => walk(ctx, route, raw.lane, &path.key("route"), scene)?,
        (Some(route), _) => route_path(ctx, route, raw.lane, &path.key("route"), scene.roads)?,
        (None, Some(points)) => {
            let path_path = path.key("path");
            if !coordinates(ctx, &path_path, points) {
                return None;
            }
            let Some(line) = Polyline::new(points.iter().copied()) else {
                ctx.error(
                    &path_path,
                    ErrorKind::Invalid("a path needs two distinct points".into()),
                );
                return None;
            };
            let length = line.length();
            (line, vec![(length, f64::INFINITY)])
        }
        (None, None) => unreachable!("checked above: a moving agent not replaying a trace has a route or a path"),
    };
    if !ok {
        return None;
    }
    if raw.start.offset >= along.length() {
        ctx.error(
            &path.key("start").key("offset"),
            ErrorKind::OutOfRange {
                expected: format!("less than the length of its way, {:.1} m", along.length()),
                found: raw.start.offset.to_string(),
            },
        );
        return None;
    }
    Some(Motion::Along {
        path: along,
        limits,
        start_time: raw.start.time,
        start_offset: raw.start.offset,
        initial_speed: initial,
        target_speed: speed.target,
        limit_factor: speed.limit_factor,
        acceleration: speed.acceleration,
        entry: Entry::Queue,
    })
}

/// A pedestrian's route along sidewalks of `map`, unlimited in speed.
fn walk(
    ctx: &mut Context<'_>,
    route: &[String],
    lane: u32,
    path: &Path,
    scene: &Scene<'_>,
) -> Option<(Polyline, Vec<(f64, f64)>)> {
    if scene.walkways.is_empty() {
        ctx.error(
            path,
            ErrorKind::Invalid(
                "a pedestrian's `route` names sidewalks of `map` (`road R lane L`), and there are none; give its \
                 `path`"
                    .into(),
            ),
        );
        return None;
    }
    let (line, _) = route_path(ctx, route, lane, path, scene.walkways)?;
    let length = line.length();
    Some((line, vec![(length, f64::INFINITY)]))
}

/// The motion of an agent replaying object `id` of the trace.
fn trace(
    ctx: &mut Context<'_>,
    id: &str,
    path: &Path,
    scene: &Scene<'_>,
    kind: AgentKind,
    length: f64,
) -> Option<Motion> {
    let mut ok = true;
    for key in ["speed", "start", "lane"] {
        if ctx.has(&path.key(key)) {
            ctx.error_at_key(
                &path.key(key),
                ErrorKind::Invalid(format!(
                    "an agent replaying a trace moves as recorded: `{key}` does not apply"
                )),
            );
            ok = false;
        }
    }
    let at = path.key("trace");
    let Some(imported) = scene.imported else {
        ctx.error(
            &at,
            ErrorKind::DanglingReference(format!("no `traces` section to take `{id}` from")),
        );
        return None;
    };
    let Some(object) = imported.object(id) else {
        let known: Vec<&str> = imported.ids().collect();
        ctx.error(
            &at,
            ErrorKind::DanglingReference(format!(
                "no object `{id}` in `traces.fcd` ({})",
                known_names(id, &known)
            )),
        );
        return None;
    };
    if !imported.overlaps(object, scene.duration) {
        ctx.error(
            &at,
            ErrorKind::Invalid(format!(
                "`{id}` is not in the trace between the run's 0 and {} s (with `traces.begin`)",
                scene.duration
            )),
        );
        return None;
    }
    ok.then(|| trace_motion(imported, object, kind, length))
}
