//! The world sections: ids, ranges, geometry resolved into lane polylines, routes
//! checked for connectivity and resolved into one path per vehicle.

use std::collections::{HashMap, HashSet};

use super::context::{Context, locate};
use super::semantic::{crosswalks, driving, interaction_areas, semantic_of, traffic, v2x};
use super::setup::whole_multiple;
use super::traces::{Imported, imported_agents, trace_motion};
use crate::de::closest;
use crate::error::{ErrorKind, Location};
use crate::geometry::{MAX_CHORD_ERROR, Polyline, Xy, arc, distance};
use crate::model::{
    Agent, AgentKind, Direction, LaneLink, Localization, Motion, Occluder, Perception, Road, Sensor, World,
};
use crate::path::Path;
use crate::raw::{RawAgent, RawOccluder, RawPerception, RawRoad, RawScenario, RawSensorModel, RawTime};

/// The most steps a run may have.
pub const MAX_STEPS: usize = 100_000;

/// Compiles the world sections of a scenario that has no `field`, with what its
/// `traces` import (`None` when it has none).
pub(super) fn world(ctx: &mut Context<'_>, raw: &RawScenario, imported: Option<&Imported>) -> Option<World> {
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
    let sensors = sensor_models(ctx, raw);
    let localization = localization(ctx, raw);
    let driving = driving(ctx, &raw.driving);
    let v2x = v2x(ctx, &raw.v2x);
    if raw.traces.is_some() && imported.is_none() {
        // A file of `traces` failed to load, and its errors are recorded: what
        // the sections that depend on it would say without it would mislead.
        return None;
    }
    let roads = roads(ctx, &raw.roads, imported);
    let occluders = occluders(ctx, &raw.occluders, imported);
    let scene = Scene {
        roads: roads.as_deref().unwrap_or_default(),
        sensors: &sensors?,
        imported,
        duration: time.duration,
    };
    let agents = agents(ctx, &raw.agents, &scene);
    let perception = match (&raw.perception, &agents, steps) {
        (Some(perception), Some((agents, _)), Some(steps)) => {
            perception_of(ctx, perception, agents, time.step, steps).map(Some)
        }
        (None, _, _) => Some(None),
        _ => None,
    };
    let roads_known = roads.as_deref().unwrap_or_default();
    let crosswalks = crosswalks(ctx, &raw.crosswalks);
    let interaction_areas = interaction_areas(ctx, &raw.interaction_areas, imported);
    let traffic = raw
        .traffic
        .as_ref()
        .map(|t| traffic(ctx, t, roads_known, crosswalks.as_deref().unwrap_or_default()));
    // A world measuring collective perception refuses `semantic` (see `kind`).
    let semantic = match (&raw.semantic, &agents) {
        (Some(_), _) if raw.perception.is_some() => Some(None),
        (Some(semantic), Some((agents, _))) => semantic_of(ctx, semantic, agents, time.step).map(Some),
        (None, _) => Some(None),
        _ => None,
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
    Some(World {
        step: time.step,
        steps: steps?,
        roads: roads?,
        occluders: occluders?,
        imported: agents.as_ref().map_or(0, |(_, imported)| *imported),
        agents: agents?.0,
        localization: localization?,
        perception: perception?,
        traffic: traffic.map_or(Some(None), |t| t.map(Some))?,
        crosswalks: crosswalks?,
        interaction_areas: interaction_areas?,
        driving: driving?,
        v2x: v2x?,
        semantic: semantic?,
    })
}

fn time_steps(ctx: &mut Context<'_>, time: &RawTime, path: &Path) -> Option<usize> {
    let ok = ctx.positive(&path.key("duration"), time.duration) & ctx.positive(&path.key("step"), time.step);
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

/// Records a duplicate-id error for every repeated id of a list; returns whether all are unique.
pub(super) fn unique_ids<'a>(ctx: &mut Context<'_>, list: &Path, ids: impl Iterator<Item = &'a str>) -> bool {
    let mut first: HashMap<&str, Location> = HashMap::new();
    let mut ok = true;
    for (i, id) in ids.enumerate() {
        let path = list.index(i).key("id");
        if let Some(&location) = first.get(id) {
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

pub(super) fn finite_points(ctx: &mut Context<'_>, path: &Path, points: &[[f64; 2]]) -> bool {
    let mut ok = true;
    for (i, point) in points.iter().enumerate() {
        for (axis, &v) in point.iter().enumerate() {
            ok &= ctx.finite(&path.index(i).index(axis), v);
        }
    }
    ok
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

/// The declared roads, then those of `traces.net`.
fn roads(ctx: &mut Context<'_>, raw: &[RawRoad], imported: Option<&Imported>) -> Option<Vec<Road>> {
    let list = Path::root().key("roads");
    let net_roads = imported.map_or(&[][..], |i| &i.roads);
    let net_ids: HashSet<&str> = net_roads.iter().map(|r| r.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|r| r.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|r| r.id.as_str()),
            &net_ids,
            "an edge of `traces.net`",
        );
    let mut roads = Vec::new();
    for (i, road) in raw.iter().enumerate() {
        let path = list.index(i);
        let shape_ok = ctx.expect(road.lanes >= 1, &path.key("lanes"), "at least 1", road.lanes.into())
            & ctx.positive(&path.key("lane_width"), road.lane_width)
            & ctx.positive(&path.key("speed_limit"), road.speed_limit);
        match (shape_ok, reference_line(ctx, road, &path)) {
            (true, Some(reference)) => {
                let lanes = (0..road.lanes)
                    .map(|k| reference.offset_left(f64::from(k) * road.lane_width))
                    .collect();
                roads.push(Road {
                    id: road.id.clone(),
                    lanes,
                    lane_width: road.lane_width,
                    speed_limit: road.speed_limit,
                    links: Vec::new(),
                });
            }
            _ => ok = false,
        }
    }
    // The network's links index its own roads, which follow the declared ones.
    let first = roads.len();
    roads.extend(net_roads.iter().map(|road| {
        Road {
            links: road
                .links
                .iter()
                .map(|link| LaneLink {
                    to_road: first + link.to_road,
                    ..link.clone()
                })
                .collect(),
            ..road.clone()
        }
    }));
    ok.then_some(roads)
}

/// Lane 0's centreline of a road.
fn reference_line(ctx: &mut Context<'_>, road: &RawRoad, path: &Path) -> Option<Polyline> {
    let given = [road.polyline.is_some(), road.arc.is_some(), road.roundabout.is_some()];
    if given.iter().filter(|&&g| g).count() != 1 {
        ctx.error(
            path,
            ErrorKind::Invalid("give exactly one of `polyline`, `arc`, `roundabout`".into()),
        );
        return None;
    }
    if let Some(points) = &road.polyline {
        let line_path = path.key("polyline");
        if !finite_points(ctx, &line_path, points) {
            return None;
        }
        let line = Polyline::new(points.iter().copied());
        if line.is_none() {
            ctx.error(
                &line_path,
                ErrorKind::Invalid("a polyline needs two distinct points".into()),
            );
        }
        return line;
    }
    if let Some(a) = &road.arc {
        let arc_path = path.key("arc");
        let ok = finite_points(ctx, &arc_path.key("center"), &[a.center])
            & ctx.positive(&arc_path.key("radius"), a.radius)
            & ctx.finite(&arc_path.key("start_deg"), a.start_deg)
            & ctx.expect(
                a.end_deg.is_finite() && a.end_deg != a.start_deg && (a.end_deg - a.start_deg).abs() <= 360.0,
                &arc_path.key("end_deg"),
                "an angle other than start_deg, within 360° of it",
                a.end_deg,
            );
        return ok
            .then(|| {
                Polyline::new(arc(
                    a.center,
                    a.radius,
                    a.start_deg.to_radians(),
                    a.end_deg.to_radians(),
                ))
            })
            .flatten();
    }
    let ring = road.roundabout.as_ref()?;
    let ring_path = path.key("roundabout");
    let inner = ring.radius - f64::from(road.lanes - 1) * road.lane_width;
    let ok = finite_points(ctx, &ring_path.key("center"), &[ring.center])
        & ctx.expect(
            ring.radius.is_finite() && inner > MAX_CHORD_ERROR,
            &ring_path.key("radius"),
            "a radius larger than the inner lanes take",
            ring.radius,
        );
    let sweep = match ring.direction {
        Direction::Ccw => std::f64::consts::TAU,
        Direction::Cw => -std::f64::consts::TAU,
    };
    ok.then(|| Polyline::new(arc(ring.center, ring.radius, 0.0, sweep)))
        .flatten()
}

/// The declared occluders, then the polygons of `traces.poly` that block sight.
fn occluders(ctx: &mut Context<'_>, raw: &[RawOccluder], imported: Option<&Imported>) -> Option<Vec<Occluder>> {
    let list = Path::root().key("occluders");
    let polygons = imported.map_or(&[][..], |i| &i.occluders);
    let polygon_ids: HashSet<&str> = polygons.iter().map(|o| o.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|o| o.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|o| o.id.as_str()),
            &polygon_ids,
            "a polygon of `traces.poly`",
        );
    let mut occluders = Vec::new();
    for (i, occluder) in raw.iter().enumerate() {
        let path = list.index(i);
        let polygon_path = path.key("polygon");
        if !finite_points(ctx, &polygon_path, &occluder.polygon) {
            ok = false;
            continue;
        }
        let Some(polygon) = counter_clockwise(&occluder.polygon) else {
            ctx.error(
                &polygon_path,
                ErrorKind::Invalid("an occluder needs at least three corners enclosing an area".into()),
            );
            ok = false;
            continue;
        };
        occluders.push(Occluder {
            id: occluder.id.clone(),
            polygon,
        });
    }
    occluders.extend_from_slice(polygons);
    ok.then_some(occluders)
}

/// `polygon` counter-clockwise, or `None` when it has fewer than three corners or
/// encloses no area.
pub(super) fn counter_clockwise(polygon: &[Xy]) -> Option<Vec<Xy>> {
    let area = signed_area(polygon);
    if polygon.len() < 3 || area.abs() < 1e-9 {
        return None;
    }
    let mut polygon = polygon.to_vec();
    if area < 0.0 {
        polygon.reverse();
    }
    Some(polygon)
}

/// The signed area of a polygon, positive when counter-clockwise (shoelace formula).
fn signed_area(polygon: &[Xy]) -> f64 {
    let n = polygon.len();
    (0..n)
        .map(|i| {
            let [a, b] = [polygon[i], polygon[(i + 1) % n]];
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

fn sensor_models(ctx: &mut Context<'_>, raw: &RawScenario) -> Option<HashMap<String, Sensor>> {
    let map = Path::root().key("sensor_models");
    let mut ok = true;
    let mut sensors = HashMap::new();
    for (name, model) in &raw.sensor_models {
        let path = map.key(name);
        match sensor(ctx, name, model, &path) {
            Some(sensor) => {
                sensors.insert(name.clone(), sensor);
            }
            None => ok = false,
        }
    }
    ok.then_some(sensors)
}

fn sensor(ctx: &mut Context<'_>, name: &str, raw: &RawSensorModel, path: &Path) -> Option<Sensor> {
    let ok = ctx.positive(&path.key("range"), raw.range)
        & ctx.expect(
            raw.fov_deg > 0.0 && raw.fov_deg <= 360.0,
            &path.key("fov_deg"),
            "an angle above 0 and at most 360",
            raw.fov_deg,
        )
        & ctx.probability(&path.key("detection_probability"), raw.detection_probability)
        & ctx.non_negative(&path.key("position_noise").key("base"), raw.position_noise.base)
        & ctx.non_negative(&path.key("position_noise").key("per_m"), raw.position_noise.per_m)
        & ctx.non_negative(&path.key("size_noise").key("base"), raw.size_noise.base)
        & ctx.non_negative(&path.key("size_noise").key("per_m"), raw.size_noise.per_m)
        & ctx.non_negative(&path.key("velocity_noise").key("base"), raw.velocity_noise.base)
        & ctx.non_negative(&path.key("velocity_noise").key("per_m"), raw.velocity_noise.per_m)
        & ctx.expect(
            raw.ray_spacing_deg > 0.0 && raw.ray_spacing_deg <= 10.0,
            &path.key("ray_spacing_deg"),
            "an angle above 0 and at most 10",
            raw.ray_spacing_deg,
        )
        & ctx.finite(&path.key("mount").key("x"), raw.mount.x)
        & ctx.finite(&path.key("mount").key("y"), raw.mount.y)
        & ctx.finite(&path.key("mount").key("yaw_deg"), raw.mount.yaw_deg);
    ok.then(|| Sensor {
        model: name.to_string(),
        range: raw.range,
        fov: raw.fov_deg.to_radians(),
        mount_x: raw.mount.x,
        mount_y: raw.mount.y,
        mount_yaw: raw.mount.yaw_deg.to_radians(),
        detection_probability: raw.detection_probability,
        noise_base: raw.position_noise.base,
        noise_per_m: raw.position_noise.per_m,
        size_noise_base: raw.size_noise.base,
        size_noise_per_m: raw.size_noise.per_m,
        velocity_noise_base: raw.velocity_noise.base,
        velocity_noise_per_m: raw.velocity_noise.per_m,
        ray_spacing: raw.ray_spacing_deg.to_radians(),
    })
}

/// What agents are resolved against.
struct Scene<'a> {
    /// Every road, declared and imported.
    roads: &'a [Road],
    /// The sensor models by id.
    sensors: &'a HashMap<String, Sensor>,
    /// What `traces` imports.
    imported: Option<&'a Imported>,
    /// Length of the run, seconds.
    duration: f64,
}

/// The declared agents, then the objects of the trace none of them replays; and
/// how many of those there are.
fn agents(ctx: &mut Context<'_>, raw: &[RawAgent], scene: &Scene<'_>) -> Option<(Vec<Agent>, usize)> {
    let list = Path::root().key("agents");
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|a| a.id.as_str()));
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
    let imported = scene.imported.map_or_else(Vec::new, |imported| {
        let declared = raw.iter().map(|a| a.id.as_str()).chain(replayed.into_keys()).collect();
        imported_agents(imported, &declared, scene.duration)
    });
    let count = imported.len();
    agents.extend(imported);
    ok.then_some((agents, count))
}

fn agent_of(ctx: &mut Context<'_>, raw: &RawAgent, path: &Path, scene: &Scene<'_>) -> Option<Agent> {
    let (default_length, default_width) = raw.kind.footprint();
    let (length, width) = match &raw.size {
        Some(size) => {
            let ok = ctx.positive(&path.key("size").key("length"), size.length)
                & ctx.positive(&path.key("size").key("width"), size.width);
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
        match scene.sensors.get(name) {
            Some(sensor) => resolved.push(sensor.clone()),
            None => {
                let mut known: Vec<&str> = scene.sensors.keys().map(String::as_str).collect();
                known.sort_unstable();
                ctx.error(
                    &path.key("sensors").index(i),
                    ErrorKind::DanglingReference(format!(
                        "no sensor model `{name}` in `sensor_models` ({})",
                        known_names(name, &known)
                    )),
                );
                sensors_ok = false;
            }
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
    })
}

/// How an agent moves: roadside units stand, vehicles follow their route,
/// pedestrians their path, and either may replay a trace instead.
fn motion(ctx: &mut Context<'_>, raw: &RawAgent, path: &Path, scene: &Scene<'_>, length: f64) -> Option<Motion> {
    let allowed: &[&str] = match raw.kind {
        AgentKind::Rsu => &["position"],
        AgentKind::Pedestrian => &["path", "trace"],
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
        let ok = finite_points(ctx, &path.key("position"), &[position])
            & ctx.finite(&path.key("heading_deg"), raw.heading_deg);
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
    let ok = ctx.non_negative(&speed_path.key("target"), speed.target)
        & ctx.non_negative(&speed_path.key("initial"), initial)
        & ctx.positive(&speed_path.key("acceleration"), speed.acceleration)
        & ctx.positive(&speed_path.key("limit_factor"), speed.limit_factor)
        & ctx.non_negative(&path.key("start").key("time"), raw.start.time)
        & ctx.non_negative(&path.key("start").key("offset"), raw.start.offset);
    let (along, limits) = match (&raw.route, &raw.path) {
        (Some(route), _) => route_path(ctx, route, raw.lane, &path.key("route"), scene.roads)?,
        (None, Some(points)) => {
            let path_path = path.key("path");
            if !finite_points(ctx, &path_path, points) {
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
    })
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

/// Resolves a route into one polyline on lane `lane` of each road, with the speed
/// limit of each part. Road a connects to road b across a junction when a links
/// that lane to b's (roads of a SUMO network), or else when a's last point lies
/// within one lane width of b (a ring is left where b's first point projects onto
/// it).
pub(super) fn route_path(
    ctx: &mut Context<'_>,
    route: &[String],
    lane: u32,
    path: &Path,
    roads: &[Road],
) -> Option<(Polyline, Vec<(f64, f64)>)> {
    if route.is_empty() {
        ctx.error(path, ErrorKind::Invalid("a route names at least one road".into()));
        return None;
    }
    let mut parts: Vec<(&Road, &Polyline)> = Vec::new();
    for (i, id) in route.iter().enumerate() {
        let Some(road) = roads.iter().find(|r| &r.id == id) else {
            let known: Vec<&str> = roads.iter().map(|r| r.id.as_str()).collect();
            ctx.error(
                &path.index(i),
                ErrorKind::DanglingReference(format!("no road `{id}` ({})", known_names(id, &known))),
            );
            return None;
        };
        let Some(centreline) = road.lanes.get(lane as usize) else {
            ctx.error(
                &path.index(i),
                ErrorKind::Invalid(format!("road `{id}` has no lane {lane} (it has {})", road.lanes.len())),
            );
            return None;
        };
        parts.push((road, centreline));
    }
    if parts.last().is_some_and(|(_, line)| line.is_closed()) {
        ctx.error(
            &path.index(route.len() - 1),
            ErrorKind::Invalid("a route cannot end on a roundabout: name the road that leaves it".into()),
        );
        return None;
    }
    let mut points: Vec<Xy> = Vec::new();
    let mut limits = Vec::new();
    let mut entry = 0.0;
    for (i, &(road, line)) in parts.iter().enumerate() {
        // Where this road is left, and where the next one is entered: a ring is
        // left where the next road starts; any other road at its end, onto the
        // closest point of the next.
        let link = parts.get(i + 1).and_then(|&(next_road, _)| {
            road.links.iter().find(|link| {
                link.from_lane == lane as usize
                    && link.to_lane == lane as usize
                    && roads[link.to_road].id == next_road.id
            })
        });
        let (exit, next_entry) = match parts.get(i + 1) {
            None => (line.length(), 0.0),
            Some(_) if link.is_some() => (line.length(), 0.0),
            Some(&(next_road, next)) => {
                let (exit, gap, next_entry) = if line.is_closed() {
                    let at = line.project(next.start());
                    (at.offset, at.distance, 0.0)
                } else {
                    let at = next.project(line.end());
                    (line.length(), at.distance, at.offset)
                };
                let tolerance = road.lane_width.max(next_road.lane_width);
                if gap > tolerance {
                    ctx.error(
                        &path.index(i + 1),
                        ErrorKind::DanglingReference(format!(
                            "road `{}` does not connect to `{}`: they are {gap:.2} m apart where one should \
                             join the other (at most the lane width, {tolerance} m)",
                            road.id, next_road.id
                        )),
                    );
                    return None;
                }
                (exit, next_entry)
            }
        };
        if line.is_closed() && exit < entry {
            points.extend(line.slice(entry, line.length()));
            points.extend(line.slice(0.0, exit));
        } else {
            points.extend(line.slice(entry, exit));
        }
        limits.push((length_of(&points), road.speed_limit));
        // The path across the junction drives at the next road's limit.
        points.extend(link.iter().flat_map(|link| &link.via));
        entry = next_entry;
    }
    let Some(polyline) = Polyline::new(points) else {
        ctx.error(path, ErrorKind::Invalid("the route has no length".into()));
        return None;
    };
    Some((polyline, limits))
}

/// "it has a, b" (or "it has none"), and the closest name when `name` looks like a typo of one.
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

fn length_of(points: &[Xy]) -> f64 {
    points.windows(2).map(|p| distance(p[0], p[1])).sum()
}

fn localization(ctx: &mut Context<'_>, raw: &RawScenario) -> Option<Localization> {
    let path = Path::root().key("localization");
    let l = &raw.localization;
    let ok = ctx.non_negative(&path.key("position_sigma"), l.position_sigma)
        & ctx.non_negative(&path.key("heading_sigma_deg"), l.heading_sigma_deg)
        & ctx.positive(&path.key("process_position_sigma"), l.process_position_sigma)
        & ctx.positive(&path.key("process_heading_sigma_deg"), l.process_heading_sigma_deg);
    ok.then_some(Localization {
        position_sigma: l.position_sigma,
        heading_sigma: l.heading_sigma_deg.to_radians(),
        filter: l.filter,
        process_position_sigma: l.process_position_sigma,
        process_heading_sigma: l.process_heading_sigma_deg.to_radians(),
    })
}

fn perception_of(
    ctx: &mut Context<'_>,
    raw: &RawPerception,
    agents: &[Agent],
    step: f64,
    steps: usize,
) -> Option<Perception> {
    let path = Path::root().key("perception");
    let Some(ego) = agents.iter().position(|a| a.id == raw.ego) else {
        let known: Vec<&str> = agents.iter().map(|a| a.id.as_str()).collect();
        ctx.error(
            &path.key("ego"),
            ErrorKind::DanglingReference(format!("no agent `{}` ({})", raw.ego, known_names(&raw.ego, &known))),
        );
        return None;
    };
    if agents[ego].sensors.is_empty() {
        ctx.error(
            &path.key("ego"),
            ErrorKind::Invalid(format!("the ego `{}` has no sensors", raw.ego)),
        );
        return None;
    }
    let others = agents
        .iter()
        .enumerate()
        .filter(|&(i, a)| i != ego && a.connected && !a.sensors.is_empty())
        .map(|(i, _)| i);
    let available = 1 + others.clone().count();
    let count = raw.cooperating.map_or(available, |c| c as usize);
    if !(1..=available).contains(&count) {
        ctx.error(
            &path.key("cooperating"),
            ErrorKind::OutOfRange {
                expected: format!(
                    "from 1 to {available} (the ego and {} connected agents with sensors)",
                    available - 1
                ),
                found: count.to_string(),
            },
        );
        return None;
    }
    if count > 1 && !agents[ego].connected {
        ctx.error(
            &path.key("ego"),
            ErrorKind::Invalid(format!(
                "the ego `{}` receives the grids of {} cooperating agents, so it must be `connected: true`",
                raw.ego,
                count - 1
            )),
        );
        return None;
    }
    let model = &raw.inverse_model;
    let model_path = path.key("inverse_model");
    let ok = ctx.expect(
        model.occupied > 0.5 && model.occupied < 1.0,
        &model_path.key("occupied"),
        "a probability above 0.5 and below 1",
        model.occupied,
    ) & ctx.expect(
        model.free > 0.0 && model.free < 0.5,
        &model_path.key("free"),
        "a probability above 0 and below 0.5",
        model.free,
    );
    let duration = step * steps as f64;
    let snapshot = raw.snapshot.unwrap_or(duration / 2.0);
    let snapshot_ok = ctx.expect(
        (0.0..=duration).contains(&snapshot),
        &path.key("snapshot"),
        &format!("a time from 0 to {duration} s"),
        snapshot,
    );
    let region_ok = raw.region.as_ref().is_none_or(|r| {
        finite_points(ctx, &path.key("region").key("center"), &[r.center])
            & ctx.positive(&path.key("region").key("radius"), r.radius)
    });
    (ok && snapshot_ok && region_ok).then(|| Perception {
        ego,
        cooperating: std::iter::once(ego).chain(others.take(count - 1)).collect(),
        occupied: model.occupied,
        free: model.free,
        snapshot_step: ((snapshot / step).round() as usize).min(steps),
        region: raw.region.as_ref().map(|r| (r.center, r.radius)),
    })
}
