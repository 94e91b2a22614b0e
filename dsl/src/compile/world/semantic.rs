//! The sections of seed 002's assisted ego: traffic, crosswalks, interaction
//! areas, driving, V2X and the semantic pipeline.

use std::collections::HashSet;

use super::routes::{RoadIndex, route_path};
use crate::compile::checks::{coordinates, distinct_from_imported, known_names, unique_ids, whole_multiple};
use crate::compile::context::Context;
use crate::compile::map::Mapped;
use crate::compile::traces::Imported;
use crate::error::ErrorKind;
use crate::geometry::{counter_clockwise, distance};
use crate::model::{
    Agent, AgentKind, Area, Baseline, Caution, Channel, Crosswalk, Driving, InteractionArea, PathLossModel,
    PedestrianTraffic, RsuSight, Semantic, Traffic, TrafficRoute, V2x, VehicleTraffic,
};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawCrosswalk, RawDriving, RawInteractionArea, RawSemantic, RawTraffic, RawV2x};

/// The declared crosswalks, then the crossings of `traces.net` and the
/// crosswalk objects of `map`.
pub(super) fn crosswalks(
    ctx: &mut Context<'_>,
    raw: &[RawCrosswalk],
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> Option<Vec<Crosswalk>> {
    let list = Path::root().key("crosswalks");
    let crossings = imported.map_or(&[][..], |i| &i.crosswalks);
    let objects = mapped.map_or(&[][..], |m| &m.crosswalks);
    let crossing_ids: HashSet<&str> = crossings.iter().map(|c| c.id.as_str()).collect();
    let object_ids: HashSet<&str> = objects.iter().map(|c| c.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|c| c.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|c| c.id.as_str()),
            &crossing_ids,
            "a crossing of `traces.net`",
        )
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|c| c.id.as_str()),
            &object_ids,
            "an object of `map`",
        );
    for (i, crosswalk) in raw.iter().enumerate() {
        let path = list.index(i);
        let ends_ok =
            coordinates(ctx, &path.key("from"), &[crosswalk.from]) & coordinates(ctx, &path.key("to"), &[crosswalk.to]);
        ok &= ends_ok & ctx.within(&path.key("width"), crosswalk.width, range::BODY);
        if ends_ok && distance(crosswalk.from, crosswalk.to) <= Crosswalk::MIN_LENGTH {
            ctx.error(
                &path.key("to"),
                ErrorKind::Invalid(format!(
                    "a crosswalk's ends must lie more than {} m apart",
                    Crosswalk::MIN_LENGTH
                )),
            );
            ok = false;
        }
    }
    ok.then(|| {
        raw.iter()
            .map(|c| Crosswalk {
                id: c.id.clone(),
                from: c.from,
                to: c.to,
                width: c.width,
            })
            .chain(crossings.iter().cloned())
            .chain(objects.iter().cloned())
            .collect()
    })
}

/// The declared interaction areas, then the junctions of `traces.net` and `map`.
pub(super) fn interaction_areas(
    ctx: &mut Context<'_>,
    raw: &[RawInteractionArea],
    imported: Option<&Imported>,
    mapped: Option<&Mapped>,
) -> Option<Vec<InteractionArea>> {
    let list = Path::root().key("interaction_areas");
    let junctions = imported.map_or(&[][..], |i| &i.areas);
    let junction_ids: HashSet<&str> = junctions.iter().map(|a| a.id.as_str()).collect();
    let mut ok = unique_ids(ctx, &list, raw.iter().map(|a| a.id.as_str()))
        & distinct_from_imported(
            ctx,
            &list,
            raw.iter().map(|a| a.id.as_str()),
            &junction_ids,
            "a junction of `traces.net` (`traces.junction_areas`)",
        );
    let map_junctions = mapped.map_or(&[][..], |m| &m.areas);
    let map_ids: HashSet<&str> = map_junctions.iter().map(|a| a.id.as_str()).collect();
    ok &= distinct_from_imported(
        ctx,
        &list,
        raw.iter().map(|a| a.id.as_str()),
        &map_ids,
        "a junction of `map` (`map.junction_areas`)",
    );
    let (mut areas, shapes_ok) = named_areas(ctx, &list, raw);
    ok &= shapes_ok;
    areas.extend_from_slice(junctions);
    areas.extend_from_slice(map_junctions);
    ok.then_some(areas)
}

/// The regions `areas` names for requirements, then the walking areas of
/// `traces.net`: ids unique among themselves and distinct from every crosswalk
/// and interaction area, so that an id selects one kind of region.
pub(super) fn areas(
    ctx: &mut Context<'_>,
    raw: &[RawInteractionArea],
    crosswalks: &[Crosswalk],
    interaction: &[InteractionArea],
    imported: Option<&Imported>,
) -> Option<Vec<InteractionArea>> {
    let list = Path::root().key("areas");
    let walking = imported.map_or(&[][..], |i| &i.walking_areas);
    let walking_ids: HashSet<&str> = walking.iter().map(|a| a.id.as_str()).collect();
    let crosswalk_ids: HashSet<&str> = crosswalks.iter().map(|c| c.id.as_str()).collect();
    let interaction_ids: HashSet<&str> = interaction.iter().map(|a| a.id.as_str()).collect();
    let ids = || raw.iter().map(|a| a.id.as_str());
    let ok = unique_ids(ctx, &list, ids())
        & distinct_from_imported(ctx, &list, ids(), &crosswalk_ids, "a crosswalk")
        & distinct_from_imported(ctx, &list, ids(), &interaction_ids, "an interaction area")
        & distinct_from_imported(ctx, &list, ids(), &walking_ids, "a walking area of `traces.net`");
    let (mut areas, shapes_ok) = named_areas(ctx, &list, raw);
    areas.extend_from_slice(walking);
    (ok && shapes_ok).then_some(areas)
}

/// The regions of `list`, each a `polygon` or a `circle`; whether all are valid.
fn named_areas(ctx: &mut Context<'_>, list: &Path, raw: &[RawInteractionArea]) -> (Vec<InteractionArea>, bool) {
    let mut ok = true;
    let mut areas = Vec::new();
    for (i, area) in raw.iter().enumerate() {
        let path = list.index(i);
        let shape = match (&area.polygon, &area.circle) {
            (Some(polygon), None) => {
                let polygon_path = path.key("polygon");
                if !coordinates(ctx, &polygon_path, polygon) {
                    None
                } else if let Some(outline) = counter_clockwise(polygon) {
                    Some(Area::Polygon(outline))
                } else {
                    ctx.error(
                        &polygon_path,
                        ErrorKind::Invalid("an area needs at least three corners enclosing an area".into()),
                    );
                    None
                }
            }
            (None, Some(circle)) => {
                let circle_path = path.key("circle");
                let circle_ok = coordinates(ctx, &circle_path.key("center"), &[circle.center])
                    & ctx.within(&circle_path.key("radius"), circle.radius, range::EXTENT);
                circle_ok.then_some(Area::Circle {
                    center: circle.center,
                    radius: circle.radius,
                })
            }
            _ => {
                ctx.error(
                    &path,
                    ErrorKind::Invalid("an area is a `polygon` or a `circle`, exactly one".into()),
                );
                None
            }
        };
        match shape {
            Some(shape) => areas.push(InteractionArea {
                id: area.id.clone(),
                shape,
            }),
            None => ok = false,
        }
    }
    (areas, ok)
}

pub(super) fn traffic(
    ctx: &mut Context<'_>,
    raw: &RawTraffic,
    roads: &RoadIndex<'_>,
    crosswalks: Option<&[Crosswalk]>,
) -> Option<Traffic> {
    let path = Path::root().key("traffic");
    let mut ok = true;
    let vehicles = raw.vehicles.as_ref().and_then(|v| {
        let path = path.key("vehicles");
        let [low, high] = v.overspeed_factor;
        let mix = [
            (AgentKind::Car, v.mix.car, "car"),
            (AgentKind::Truck, v.mix.truck, "truck"),
            (AgentKind::Bus, v.mix.bus, "bus"),
            (AgentKind::Motorbike, v.mix.motorbike, "motorbike"),
        ];
        let factor_path = path.key("overspeed_factor");
        let mut fields_ok = ctx.within(&path.key("density_per_km"), v.density_per_km, range::DENSITY)
            & ctx.probability(&path.key("non_compliant"), v.non_compliant)
            & ((ctx.within(&factor_path.index(0), low, range::OVERSPEED_FACTOR)
                & ctx.within(&factor_path.index(1), high, range::OVERSPEED_FACTOR))
                && ctx.expect(
                    low <= high,
                    &factor_path.index(1),
                    &format!("a high end ≥ the low end {low}"),
                    high,
                ));
        for &(_, share, name) in &mix {
            fields_ok &= ctx.within(&path.key("mix").key(name), share, range::SHARE);
        }
        let total: f64 = mix.iter().map(|&(_, share, _)| share).sum();
        if fields_ok && total <= 0.0 {
            ctx.error(
                &path.key("mix"),
                ErrorKind::Invalid("the mix needs at least one kind with a share above 0".into()),
            );
            fields_ok = false;
        }
        if v.routes.is_empty() {
            ctx.error(
                &path.key("routes"),
                ErrorKind::Invalid("traffic needs at least one route".into()),
            );
            fields_ok = false;
        }
        let mut routes = Vec::new();
        for (i, route) in v.routes.iter().enumerate() {
            match route_path(ctx, route, 0, &path.key("routes").index(i), roads) {
                Some((path, limits)) => routes.push(TrafficRoute { path, limits }),
                None => fields_ok = false,
            }
        }
        ok &= fields_ok;
        fields_ok.then(|| VehicleTraffic {
            density_per_km: v.density_per_km,
            routes,
            non_compliant: v.non_compliant,
            overspeed_factor: v.overspeed_factor,
            mix: mix
                .iter()
                .filter(|&&(_, share, _)| share > 0.0)
                .map(|&(kind, share, _)| (kind, share / total))
                .collect(),
        })
    });
    let pedestrians = raw.pedestrians.as_ref().and_then(|p| {
        let path = path.key("pedestrians");
        let mut fields_ok = ctx.within(&path.key("per_minute"), p.per_minute, range::ARRIVALS)
            & ctx.within(&path.key("speed"), p.speed, range::SPEED_POSITIVE)
            & ctx.within(&path.key("approach"), p.approach, range::GAP);
        // Crosswalks that failed to compile have their own errors.
        if crosswalks.is_some_and(<[Crosswalk]>::is_empty) {
            ctx.error(
                &path,
                ErrorKind::Invalid("pedestrian traffic crosses at `crosswalks`, and there are none".into()),
            );
            fields_ok = false;
        }
        ok &= fields_ok;
        fields_ok.then_some(PedestrianTraffic {
            per_minute: p.per_minute,
            speed: p.speed,
            approach: p.approach,
        })
    });
    ok.then_some(Traffic { vehicles, pedestrians })
}

pub(super) fn driving(ctx: &mut Context<'_>, raw: &RawDriving) -> Option<Driving> {
    let path = Path::root().key("driving");
    let ok = ctx.within(&path.key("headway"), raw.headway, range::REACTION)
        & ctx.within(&path.key("min_gap"), raw.min_gap, range::GAP)
        & ctx.within(&path.key("deceleration"), raw.deceleration, range::ACCELERATION);
    ok.then_some(Driving {
        following: raw.following,
        headway: raw.headway,
        min_gap: raw.min_gap,
        deceleration: raw.deceleration,
    })
}

/// The height an antenna must be above, metres: WINNER+ B1 (TR 36.885 urban)
/// uses effective antenna heights h − 1 m, which must stay above 0.
fn lowest_antenna(model: PathLossModel) -> f64 {
    if model == PathLossModel::Tr36885Urban { 1.0 } else { 0.0 }
}

/// Checks the antennas agents have of their own (roadside units of points of
/// interest with a `height`) against the channel, at `traces.rsus.poi_type`.
pub(super) fn own_antennas(ctx: &mut Context<'_>, v2x: &V2x, agents: &[Agent]) -> bool {
    let lowest = lowest_antenna(v2x.channel.model);
    let mut ok = true;
    for agent in agents {
        let Some(height) = agent.antenna_m else { continue };
        if height <= lowest || !range::ANTENNA.contains(height) {
            ctx.error(
                &Path::root().key("traces").key("rsus").key("poi_type"),
                ErrorKind::Invalid(format!(
                    "point of interest `{}` puts its antenna at {height} m (its `height` parameter); \
                     the channel needs a height above {lowest} m and at most {} m",
                    agent.id,
                    range::ANTENNA.max
                )),
            );
            ok = false;
        }
    }
    ok
}

pub(super) fn v2x(ctx: &mut Context<'_>, raw: &RawV2x) -> Option<V2x> {
    let path = Path::root().key("v2x");
    let c = &raw.channel;
    let channel_path = path.key("channel");
    let lowest = lowest_antenna(c.model);
    let penetration = raw.penetration.unwrap_or(0.0);
    let mut ok = ctx.probability(&path.key("penetration"), penetration)
        & ctx.within(&path.key("latency"), raw.latency, range::LATENCY)
        & ctx.within(&channel_path.key("tx_power_dbm"), c.tx_power_dbm, range::POWER)
        & ctx.within(
            &channel_path.key("shadowing_sigma_db"),
            c.shadowing_sigma_db,
            range::DECIBELS,
        )
        & ctx.within(
            &channel_path.key("nlos_shadowing_sigma_db"),
            c.nlos_shadowing_sigma_db,
            range::DECIBELS,
        )
        & ctx.within(&channel_path.key("device_loss_db"), c.device_loss_db, range::DECIBELS)
        & ctx.within(
            &channel_path.key("sensitivity_dbm"),
            c.sensitivity_dbm,
            range::SENSITIVITY,
        )
        & ctx.within(&channel_path.key("carrier_ghz"), c.carrier_ghz, range::CARRIER);
    for (key, height) in [
        ("vehicle_antenna_m", c.vehicle_antenna_m),
        ("rsu_antenna_m", c.rsu_antenna_m),
    ] {
        ok &= ctx.expect(
            height > lowest,
            &channel_path.key(key),
            &format!("a height above {lowest} m"),
            height,
        ) && ctx.within(&channel_path.key(key), height, range::ANTENNA);
    }
    ok.then_some(V2x {
        penetration,
        latency: raw.latency,
        channel: Channel {
            model: c.model,
            tx_power_dbm: c.tx_power_dbm,
            shadowing_sigma_db: c.shadowing_sigma_db,
            nlos_shadowing_sigma_db: c.nlos_shadowing_sigma_db,
            device_loss_db: c.device_loss_db,
            sensitivity_dbm: c.sensitivity_dbm,
            carrier_ghz: c.carrier_ghz,
            vehicle_antenna_m: c.vehicle_antenna_m,
            rsu_antenna_m: c.rsu_antenna_m,
        },
    })
}

/// The semantic pipeline, in a joint world (`joint`) or a semantic one.
pub(super) fn semantic_of(
    ctx: &mut Context<'_>,
    raw: &RawSemantic,
    agents: &[Agent],
    step: f64,
    joint: bool,
) -> Option<Semantic> {
    let path = Path::root().key("semantic");
    // In a joint world the roadside units perceive through their modelled
    // sensors and the map's occluders unless the file says otherwise.
    let rsu_sight = if joint && !ctx.has(&path.key("rsu_sight")) {
        RsuSight::LineOfSight
    } else {
        raw.rsu_sight
    };
    let find = |ctx: &mut Context<'_>, id: &str, at: &Path| {
        let found = agents.iter().position(|a| a.id == id);
        if found.is_none() {
            let known: Vec<&str> = agents.iter().map(|a| a.id.as_str()).collect();
            ctx.error(
                at,
                ErrorKind::DanglingReference(format!("no agent `{id}` ({})", known_names(id, &known))),
            );
        }
        found
    };
    let ego = find(ctx, &raw.ego, &path.key("ego")).and_then(|ego| {
        let agent = &agents[ego];
        let problem = if agent.motion.path().is_none() || !agent.kind.is_vehicle() {
            Some("is not a vehicle on a route or a trace that moves")
        } else if !agent.connected {
            Some("is not `connected: true`")
        } else if agent.sensors.is_empty() {
            Some("has no sensors")
        } else {
            None
        };
        if let Some(problem) = problem {
            ctx.error(
                &path.key("ego"),
                ErrorKind::Invalid(format!("the ego `{}` {problem}", raw.ego)),
            );
            return None;
        }
        Some(ego)
    });
    let rsus: Option<Vec<usize>> = match &raw.rsus {
        Some(ids) => {
            let mut found = Vec::new();
            for (i, id) in ids.iter().enumerate() {
                let at = path.key("rsus").index(i);
                let Some(index) = find(ctx, id, &at) else { continue };
                if found.contains(&index) {
                    ctx.error(&at, ErrorKind::Invalid(format!("`{id}` is listed twice")));
                    continue;
                }
                if agents[index].kind != AgentKind::Rsu || agents[index].sensors.is_empty() {
                    ctx.error(
                        &at,
                        ErrorKind::Invalid(format!("`{id}` is not a roadside unit (`kind: rsu`) with sensors")),
                    );
                    continue;
                }
                found.push(index);
            }
            (found.len() == ids.len()).then_some(found)
        }
        None => Some(
            agents
                .iter()
                .enumerate()
                .filter(|(_, a)| a.kind == AgentKind::Rsu && !a.sensors.is_empty())
                .map(|(i, _)| i)
                .collect(),
        ),
    };
    let rsus = rsus.filter(|r| {
        if r.is_empty() {
            ctx.error(
                &path,
                ErrorKind::Invalid("the semantic pipeline needs a roadside unit (`kind: rsu`) with sensors".into()),
            );
        }
        !r.is_empty()
    });
    let mut ok = ctx.within(&path.key("proximity"), raw.proximity, range::EXTENT)
        & ctx.within(&path.key("horizon"), raw.horizon, range::REACTION)
        & ctx.within(&path.key("d_min"), raw.d_min, range::BODY)
        & ctx.within(&path.key("overspeed").key("window"), raw.overspeed.window, range::SPAN)
        & ctx.within(
            &path.key("overspeed").key("threshold"),
            raw.overspeed.threshold,
            range::SPEED,
        )
        & ctx.within(&path.key("rate"), raw.rate, range::RATE)
        & ctx.within(
            &path.key("caution").key("headway"),
            raw.caution.headway,
            range::REACTION,
        )
        & ctx.expect(
            range::PROBABILITY_POSITIVE.contains(raw.caution.speed_factor),
            &path.key("caution").key("speed_factor"),
            "a number above 0 and at most 1",
            raw.caution.speed_factor,
        )
        & ctx.within(&path.key("caution").key("hold"), raw.caution.hold, range::TIME)
        & ctx.within(
            &path.key("baseline").key("distance"),
            raw.baseline.distance,
            range::EXTENT,
        )
        & ctx.within(
            &path.key("baseline").key("speed"),
            raw.baseline.speed,
            range::SPEED_POSITIVE,
        )
        & ctx.within(
            &path.key("baseline").key("heading_deg"),
            raw.baseline.heading_deg,
            range::HEADING_CHANGE,
        )
        & ctx.within(
            &path.key("baseline").key("interval"),
            raw.baseline.interval,
            range::SPAN,
        );
    if ok && raw.horizon < step {
        // A prediction of less than a step has no segment to test.
        ctx.error(
            &path.key("horizon"),
            ErrorKind::OutOfRange {
                expected: format!("at least one {step} s step"),
                found: raw.horizon.to_string(),
            },
        );
        ok = false;
    }
    ok &= ctx.expect(
        range::RUNS.contains(f64::from(raw.runs)),
        &path.key("runs"),
        &format!("a whole number from 1 to {}", range::RUNS.max),
        f64::from(raw.runs),
    );
    if raw.hypotheses.is_empty() {
        ctx.error(
            &path.key("hypotheses"),
            ErrorKind::Invalid("give at least one speed hypothesis".into()),
        );
        ok = false;
    }
    for (i, &factor) in raw.hypotheses.iter().enumerate() {
        ok &= ctx.within(&path.key("hypotheses").index(i), factor, range::SPEED_FACTOR);
    }
    ok &= ctx.expect(
        range::SPAN.contains(raw.history) && raw.history >= raw.overspeed.window,
        &path.key("history"),
        &format!("at least the overspeed window, {} s", raw.overspeed.window),
        raw.history,
    );
    let period_steps = (ok && raw.rate > 0.0)
        .then(|| whole_multiple(1.0 / raw.rate, step))
        .flatten();
    if ok && period_steps.is_none() {
        ctx.error(
            &path.key("rate"),
            ErrorKind::OutOfRange {
                expected: format!("a rate whose period is a whole number of {step} s steps"),
                found: raw.rate.to_string(),
            },
        );
        ok = false;
    }
    if !ok {
        return None;
    }
    Some(Semantic {
        ego: ego?,
        rsus: rsus?,
        proximity: raw.proximity,
        horizon: raw.horizon,
        d_min: raw.d_min,
        overspeed_window: raw.overspeed.window,
        overspeed_threshold: raw.overspeed.threshold,
        hypotheses: raw.hypotheses.clone(),
        period_steps: period_steps? as usize,
        risk_for: raw.risk_for,
        rsu_sight,
        history: raw.history,
        caution: Caution {
            headway: raw.caution.headway,
            speed_factor: raw.caution.speed_factor,
            hold: raw.caution.hold,
        },
        baseline: Baseline {
            distance: raw.baseline.distance,
            speed: raw.baseline.speed,
            heading: raw.baseline.heading_deg.to_radians(),
            interval: raw.baseline.interval,
        },
        shares_over: raw.shares_over,
        labelled_by: raw.labelled_by,
        contribution_over: raw.contribution_over,
        runs: raw.runs,
    })
}
