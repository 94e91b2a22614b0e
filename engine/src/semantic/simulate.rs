//! The step loop of a semantic world: kinematics with generated traffic, each
//! RSU's perception into its LDM, the pipeline, the V2X link both ways, the ego's
//! caution, and the metrics.
//!
//! Our choices where seed 002 is silent:
//! - An RSU perceives every object in its sensors' range (or, with
//!   `rsu_sight: line_of_sight`, in view and line of sight), each with its sensor's
//!   detection probability; each measurement adds Gaussian noise with
//!   σ(d) = base + per_m · d to x, y, speed, length and width (eq. 1).
//! - Each cycle the ego sends its state and plan (uplink); the RSU plans with the
//!   last one it received. An RSU sends a message only when it selects an object.
//! - The ego knows an object through an RSU for `KNOWN_FOR` seconds after a
//!   message naming it arrives; it sees an object when the object's centre is in
//!   range and field of view of one of its sensors with a clear line of sight.
//! - Connected vehicles (v2x.penetration) send the ego their own state each
//!   cycle; the ego then knows them without an RSU. Vehicles imported from a
//!   trace are drawn connected as generated ones are.
//! - The transmitted and labelled shares count, by default, the cycles in which
//!   the ego is within range of one of the RSU's sensors (`shares_over:
//!   ego_in_range`): seed 002 places RSUs along the ego's way, so its ego is
//!   always served. `shares_over: all` counts every cycle.
//! - Density is the number of vehicles and pedestrians in the scene per km of
//!   road (lane 0 of every road, those of a SUMO network too); without roads it
//!   is undefined, and the contribution is not binned by density.
//! - The RSU's map: with a road network (roads linked across junctions, from
//!   `traces.net`), every lane continued through its links far enough for the
//!   fastest prediction over the horizon (`lane_routes`), since the network
//!   says where vehicles can go; without one, the ways the scenario gives:
//!   declared routes, traffic routes and the paths of traced vehicles. With a
//!   network, traced paths are left out: they would tell the RSU where each
//!   vehicle is going to turn. Declared and traffic routes are in both.
//! - A traced ego's plan is its traced path at its current speed, so the RSU
//!   knows where it is going as it knows a declared ego's route. It replays its
//!   trace, so caution cannot slow it down; `cautious_time` still counts the time
//!   it would have been cautious.

use std::collections::VecDeque;

use rand::RngExt;
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use sightline_dsl::geometry::Polyline;
use sightline_dsl::{Agent, AgentKind, Motion, RsuSight, Semantic, ShareCycles, World};

use super::ldm::{self, Ldm, Measurement};
use super::message::{self, EtsiSender, Item, baseline_bytes, semantic_bytes};
use super::metrics::{DELIVERY_BIN, SemanticMetrics, Series};
use super::pipeline::{EgoPlan, Pipeline};
use super::relevance::Areas;
use super::risk::{MapRoute, RouteMap, lane_routes};
use super::traffic;
use crate::idealisation::Idealisation;
use crate::math::{Pose, Vector};
use crate::rng::{Derived, Purpose, derived_seed, stream};
use crate::sink::{NoTrace, TraceSink};
use crate::trace::{Approach, Arrival, Packet, PacketKind, SemanticLog};
use crate::v2x::{self, Link, transmit};
use crate::world::{
    self, AgentState, Bodies, Body, Kinematics, Occluders, Restraint, Visibility, in_view, mount_pose, visibility,
};

/// The ego's own sight is perfect.
pub(crate) const EGO_SIGHT: Idealisation = Idealisation {
    id: "semantic.ego-sight",
    text: "The ego sees an object at once and exactly when its centre is in range, in field of view and in line \
           of sight of one of its sensors: its own sensors miss nothing and add no error.",
};

/// Roadside units measure with white noise.
pub(crate) const RSU_MEASUREMENTS: Idealisation = Idealisation {
    id: "semantic.rsu-measurements",
    text: "A roadside unit measures each object it perceives with its sensor's detection probability and \
           independent Gaussian errors of position, speed, length and width; headings are exact and no object \
           is reported that is not there.",
};

/// Roadside units perceive through buildings.
pub(crate) const RSU_RANGE: Idealisation = Idealisation {
    id: "semantic.rsu-range",
    text: "A roadside unit perceives every object within its sensors' range, through buildings and road users \
           (`rsu_sight: range`, seed 002's circular region).",
};

/// Nobody localizes.
pub(crate) const EXACT_POSES: Idealisation = Idealisation {
    id: "semantic.exact-poses",
    text: "The ego and the roadside units know their own poses exactly: a semantic world does not model \
           self-localization.",
};

/// The RSU knows the ego's plan.
pub(crate) const EGO_PLAN: Idealisation = Idealisation {
    id: "semantic.ego-plan",
    text: "A roadside unit predicts the ego along its route at the speed the ego last sent, without error.",
};

/// Direct messages carry exact states.
pub(crate) const DIRECT_STATES: Idealisation = Idealisation {
    id: "semantic.direct-states",
    text: "A connected road user's message carries its exact state.",
};

/// What a message makes known.
pub(crate) const KNOWN_FOR_A_WHILE: Idealisation = Idealisation {
    id: "semantic.known-for",
    text: "An object named in a message counts as known to the ego for 0.5 s after the message arrives.",
};

/// The idealisation of what a roadside unit perceives.
pub(crate) fn rsu_sight_idealisations(sight: RsuSight) -> &'static [Idealisation] {
    match sight {
        RsuSight::Range => &[RSU_RANGE],
        RsuSight::LineOfSight => &[world::ONE_RAY],
    }
}

/// The idealisations of a world running the semantic pipeline, besides those
/// of its options (RSU sight, path-loss model, car following).
pub(crate) fn idealisations(world: &World, semantic: &Semantic) -> Vec<Idealisation> {
    let mut listed = vec![world::PLANAR, world::ON_THEIR_WAY];
    if world.traffic.is_some() {
        listed.push(traffic::GENERATED);
    }
    listed.extend([
        EXACT_POSES,
        world::ONE_RAY,
        EGO_SIGHT,
        RSU_MEASUREMENTS,
        world::RSU_TRANSPARENT,
        ldm::ASSOCIATION,
        EGO_PLAN,
        message::SIZED,
        v2x::NO_CONTENTION,
        KNOWN_FOR_A_WHILE,
    ]);
    let road_users = world
        .agents
        .iter()
        .enumerate()
        .filter(|&(i, a)| i != semantic.ego && a.kind != AgentKind::Rsu);
    if world.v2x.penetration > 0.0 || road_users.clone().any(|(_, a)| a.connected) {
        listed.push(DIRECT_STATES);
    }
    listed
}

/// How long a message keeps an object known to the ego, seconds.
pub const KNOWN_FOR: f64 = 0.5;

/// A network's map routes reach this many times the fastest speed limit × the
/// horizon past the lane a vehicle is on: a non-compliant driver at 1.5 × the
/// limit under the 1.1 hypothesis still stays on the map.
const REACH_FACTOR: f64 = 2.0;

/// Speed of light, m/s, for propagation delay.
const LIGHT: f64 = 299_792_458.0;

/// What the run tracks per agent.
#[derive(Debug, Clone, Copy, Default)]
struct Knowledge {
    /// When a message naming it last arrived.
    last_received: Option<f64>,
    /// When a message naming it first arrived, and whether the ego had seen it before.
    first_received: Option<(f64, bool)>,
    /// When the ego first saw it.
    first_seen: Option<f64>,
    /// When its own V2X message last arrived.
    last_direct: Option<f64>,
    /// When a message flagging a conflict with it first reached the ego.
    flagged: Option<f64>,
    /// Whether it is within d_min of the ego now.
    close: bool,
}

/// An RSU's state across cycles.
struct Rsu {
    agent: usize,
    /// Its longest sensor range, metres.
    range: f64,
    ldm: Ldm,
    baseline: EtsiSender,
    plan: Option<EgoPlan>,
    detections: ChaCha8Rng,
    channel: ChaCha8Rng,
}

/// Runs a world's semantic pipeline `semantic.runs` times, each run with its own
/// seed (run 0 with `seed` itself), and pools the measurements in run order.
/// Run 0 reports each step to `sink`; the others run in parallel afterwards and
/// report nothing. The result does not depend on the thread count.
pub fn run(seed: u64, world: &World, semantic: &Semantic, sink: &mut impl TraceSink) -> SemanticMetrics {
    let mut pooled = run_once(seed, world, semantic, sink);
    let others: Vec<SemanticMetrics> = (1..semantic.runs)
        .into_par_iter()
        .map(|r| run_once(derived_seed(seed, Derived::Run, r), world, semantic, &mut NoTrace))
        .collect();
    for metrics in others {
        pooled.pool(metrics);
    }
    pooled
}

/// One run of a world's semantic pipeline, reporting each step to `sink`.
fn run_once(seed: u64, world: &World, semantic: &Semantic, sink: &mut impl TraceSink) -> SemanticMetrics {
    let agents = traffic::scene(seed, world);
    let dt = world.step;
    let occluders = Occluders::new(&world.occluders);
    let map = route_map(world, semantic);
    let ego_route = agents[semantic.ego]
        .motion
        .path()
        .expect("the compiler checks that the ego follows a route or a moving trace");
    let pipeline = Pipeline {
        semantic,
        areas: Areas::of(world),
        occluders: &occluders,
        map: &map,
        ego_route,
        dt,
    };
    let channel = &world.v2x.channel;
    let network_km = world.roads.iter().map(|r| r.lanes[0].length()).sum::<f64>() / 1000.0;
    let density = |present: u32| (network_km > 0.0).then(|| f64::from(present) / network_km);
    let mut rsus: Vec<Rsu> = semantic
        .rsus
        .iter()
        .map(|&agent| Rsu {
            agent,
            range: agents[agent].sensors.iter().map(|s| s.range).fold(0.0, f64::max),
            ldm: Ldm::default(),
            baseline: EtsiSender::new(semantic.baseline),
            plan: None,
            detections: stream(seed, Purpose::Detections, agent as u64),
            channel: stream(seed, Purpose::Channel, agent as u64),
        })
        .collect();
    let mut ego_channel = stream(seed, Purpose::Channel, semantic.ego as u64);
    let mut cam_channel = stream(seed, Purpose::Channel, agents.len() as u64);
    let mut kinematics = Kinematics::new(&agents, dt, world.driving);
    let mut knowledge = vec![Knowledge::default(); agents.len()];
    let mut in_flight: VecDeque<(f64, Vec<Item>)> = VecDeque::new();
    let mut metrics = SemanticMetrics {
        runs: 1,
        generated: (agents.len() - world.agents.len()) as u64,
        ..Default::default()
    };
    let mut cautious_until = f64::NEG_INFINITY;
    let (mut rsu_only, mut time_to_conflict): (Series, Series) = (Vec::new(), Vec::new());
    let mut states = Vec::new();
    let mut log = SemanticLog::default();
    sink.start(&agents);

    for k in 0..world.steps {
        let time = k as f64 * dt;
        kinematics.advance(k, &mut states);
        let bodies = Bodies::of_scene(&agents, &states);
        let ego = states[semantic.ego];

        // Messages arriving by now.
        while in_flight.front().is_some_and(|&(at, _)| at <= time + 1e-9) {
            let (at, items) = in_flight.pop_front().expect("checked non-empty");
            for item in &items {
                let known = &mut knowledge[item.agent];
                known.last_received = Some(at);
                if known.first_received.is_none() {
                    known.first_received = Some((at, known.first_seen.is_some()));
                }
                if item.labels.conflict.is_some() {
                    known.flagged.get_or_insert(at);
                    cautious_until = cautious_until.max(at + semantic.caution.hold);
                }
            }
            log.arrivals.push(Arrival { at, items });
        }

        if let Some(ego) = ego {
            metrics.steps += 1;
            metrics.duration += dt;
            let cautious = time < cautious_until;
            if cautious {
                metrics.cautious_time += dt;
            }
            kinematics.restrain(
                semantic.ego,
                cautious.then_some(Restraint {
                    headway: semantic.caution.headway,
                    speed_factor: semantic.caution.speed_factor,
                }),
            );
            let mut present = 0u32;
            let mut through_rsu = 0u32;
            for body in bodies.all().iter().filter(|b| b.agent != semantic.ego) {
                present += 1;
                let known = &mut knowledge[body.agent];
                let seen = sees(&agents[semantic.ego], ego.pose, &occluders, &bodies, semantic.ego, body);
                if seen && known.first_seen.is_none() {
                    known.first_seen = Some(time);
                }
                let fresh = |at: Option<f64>| at.is_some_and(|at| time - at <= KNOWN_FOR + 1e-9);
                if !seen && fresh(known.last_received) && !fresh(known.last_direct) {
                    through_rsu += 1;
                }
                let close = (body.pose.translation - ego.position()).length() <= semantic.d_min;
                if close && !known.close {
                    metrics.close_approaches += 1;
                    metrics.missed_criticals += u64::from(known.flagged.is_none());
                    metrics.warnings.push(known.flagged.map(|at| time - at));
                    log.approaches.push(Approach {
                        agent: body.agent,
                        flagged: known.flagged.is_some(),
                    });
                }
                known.close = close;
            }
            metrics.contribution.push((density(present), through_rsu));
            rsu_only.push((time, f64::from(through_rsu)));
        }

        // RSUs run their cycle, and connected road users send, at the V2X rate.
        let cycle = k % semantic.period_steps == 0;
        for rsu in rsus.iter_mut().filter(|_| cycle) {
            let Some(station) = states[rsu.agent] else { continue };
            perceive(rsu, &agents, &states, &occluders, &bodies, semantic, time);
            let Some(ego) = ego else { continue };
            let uplink = Link {
                distance_m: (ego.position() - station.position()).length(),
                los: !occluders.block(station.position(), ego.position()),
                tx_antenna_m: channel.vehicle_antenna_m,
                rx_antenna_m: channel.rsu_antenna_m,
            };
            let reception = transmit(channel, &uplink, &mut ego_channel);
            log.packets.push(Packet {
                from: semantic.ego,
                to: rsu.agent,
                kind: PacketKind::Uplink,
                link: uplink,
                reception,
            });
            if reception.received {
                rsu.plan = Some(EgoPlan {
                    time,
                    offset: ego.offset,
                    speed: ego.speed,
                });
            }
            let Some(plan) = rsu.plan else { continue };
            let perceived: Vec<(usize, &Measurement)> = rsu
                .ldm
                .current(time)
                .filter(|&(agent, _)| agent != semantic.ego)
                .map(|(agent, track)| (agent, track.latest()))
                .collect();
            // Whether this cycle counts toward the transmitted and labelled shares.
            let shared = match semantic.shares_over {
                ShareCycles::All => true,
                ShareCycles::EgoInRange => uplink.distance_m <= rsu.range,
            };
            if shared {
                metrics.perceived += perceived.len() as u64;
            }
            let baseline = rsu.baseline.select(perceived);
            if baseline > 0 {
                metrics.baseline_objects += baseline as u64;
                metrics.baseline_bytes += baseline_bytes(baseline) as u64;
            }
            let items = pipeline.run(&rsu.ldm, time, &plan);
            if items.is_empty() {
                continue;
            }
            if shared {
                count_labels(&mut metrics, &items);
            }
            let soonest = items
                .iter()
                .filter_map(|item| item.labels.conflict)
                .map(|conflict| conflict.time)
                .reduce(f64::min);
            if let Some(soonest) = soonest {
                time_to_conflict.push((time, soonest));
            }
            let bytes = semantic_bytes(items.len());
            metrics.bytes += bytes as u64;
            metrics.messages += 1;
            let downlink = Link {
                tx_antenna_m: channel.rsu_antenna_m,
                rx_antenna_m: channel.vehicle_antenna_m,
                ..uplink
            };
            let bin = (downlink.distance_m / DELIVERY_BIN) as usize;
            if metrics.delivery_by_distance.len() <= bin {
                metrics.delivery_by_distance.resize(bin + 1, Default::default());
            }
            metrics.delivery_by_distance[bin].sent += 1;
            let reception = transmit(channel, &downlink, &mut rsu.channel);
            log.packets.push(Packet {
                from: rsu.agent,
                to: semantic.ego,
                kind: PacketKind::Downlink {
                    items: items.clone(),
                    bytes,
                },
                link: downlink,
                reception,
            });
            if reception.received {
                metrics.delivered += 1;
                metrics.delivery_by_distance[bin].received += 1;
                let arrival = time + world.v2x.latency + downlink.distance_m / LIGHT;
                let at = in_flight.partition_point(|&(t, _)| t <= arrival);
                in_flight.insert(at, (arrival, items));
            }
        }
        // Connected road users tell the ego about themselves.
        if let Some(ego) = ego.filter(|_| cycle) {
            for (i, state) in states.iter().enumerate() {
                let Some(state) = state else { continue };
                if i == semantic.ego || !agents[i].connected || agents[i].kind == AgentKind::Rsu {
                    continue;
                }
                let distance = (state.position() - ego.position()).length();
                let link = Link {
                    distance_m: distance,
                    los: !occluders.block(state.position(), ego.position()),
                    tx_antenna_m: channel.vehicle_antenna_m,
                    rx_antenna_m: channel.vehicle_antenna_m,
                };
                let reception = transmit(channel, &link, &mut cam_channel);
                log.packets.push(Packet {
                    from: i,
                    to: semantic.ego,
                    kind: PacketKind::Direct,
                    link,
                    reception,
                });
                if reception.received {
                    knowledge[i].last_direct = Some(time + world.v2x.latency + distance / LIGHT);
                }
            }
        }
        sink.semantic_step(&log.step(k, time, &states));
        log.clear();
    }

    for known in &knowledge {
        if let Some((received, false)) = known.first_received {
            match known.first_seen {
                Some(seen) => metrics.anticipation.push(seen - received),
                None => metrics.never_seen += 1,
            }
        }
    }
    metrics.anticipation.sort_by(f64::total_cmp);
    metrics.rsu_only = vec![rsu_only];
    metrics.time_to_conflict = vec![time_to_conflict];
    metrics
}

/// The RSU's map of `world` (see the module docs): with a network, its lanes
/// continued; then the way of every vehicle of the world (a traced one's only
/// without a network) and every traffic route, each once.
pub fn route_map(world: &World, semantic: &Semantic) -> RouteMap {
    let network = world.roads.iter().any(|road| !road.links.is_empty());
    let mut routes = if network {
        let fastest = world.roads.iter().map(|road| road.speed_limit).fold(0.0, f64::max);
        lane_routes(&world.roads, semantic.horizon * REACH_FACTOR * fastest)
    } else {
        Vec::new()
    };
    let mut ways: Vec<&Polyline> = Vec::new();
    let declared = world
        .agents
        .iter()
        .filter(|a| a.kind.is_vehicle())
        .filter(|a| !network || !matches!(a.motion, Motion::Trace { .. }))
        .filter_map(|a| a.motion.path());
    let generated = world
        .traffic
        .iter()
        .flat_map(|t| t.vehicles.iter())
        .flat_map(|v| v.routes.iter().map(|r| &r.path));
    for path in declared.chain(generated) {
        if !ways.contains(&path) {
            ways.push(path);
        }
    }
    routes.extend(ways.into_iter().cloned().map(MapRoute::whole));
    RouteMap::new(routes)
}

/// Whether the ego at `pose` could see `target` with one of its sensors.
fn sees(ego: &Agent, pose: Pose, occluders: &Occluders, bodies: &Bodies, ego_index: usize, target: &Body) -> bool {
    ego.sensors.iter().any(|sensor| {
        let mount = pose * mount_pose(sensor);
        in_view(sensor, mount, target.pose.translation).is_some()
            && visibility(occluders, bodies, mount.translation, ego_index, target) == Visibility::Los
    })
}

/// One RSU cycle of perception: noisy measurements into the LDM (eq. 1).
fn perceive(
    rsu: &mut Rsu,
    agents: &[Agent],
    states: &[Option<AgentState>],
    occluders: &Occluders,
    bodies: &Bodies,
    semantic: &Semantic,
    time: f64,
) {
    let station = &agents[rsu.agent];
    let Some(pose) = states[rsu.agent].map(|s| s.pose) else {
        return;
    };
    for target in bodies.all() {
        let state = states[target.agent].expect("bodies are of present agents");
        let spec = &agents[target.agent];
        let sensor = station.sensors.iter().find(|sensor| {
            let mount = pose * mount_pose(sensor);
            match semantic.rsu_sight {
                RsuSight::Range => (state.position() - mount.translation).length() <= sensor.range,
                RsuSight::LineOfSight => {
                    in_view(sensor, mount, state.position()).is_some()
                        && visibility(occluders, bodies, mount.translation, rsu.agent, target) == Visibility::Los
                }
            }
        });
        let Some(sensor) = sensor else { continue };
        if rsu.detections.random::<f64>() >= sensor.detection_probability {
            continue;
        }
        let distance = (state.position() - pose.translation).length();
        let mut noise = |base: f64, per_m: f64| {
            let sigma = base + per_m * distance;
            if sigma > 0.0 {
                Normal::new(0.0, sigma)
                    .expect("σ is finite and positive")
                    .sample(&mut rsu.detections)
            } else {
                0.0
            }
        };
        let position = state.position()
            + Vector::new(
                noise(sensor.noise_base, sensor.noise_per_m),
                noise(sensor.noise_base, sensor.noise_per_m),
            );
        let measurement = Measurement {
            time,
            position,
            speed: (state.speed + noise(sensor.velocity_noise_base, sensor.velocity_noise_per_m)).max(0.0),
            heading: state.heading(),
            length: (spec.length + noise(sensor.size_noise_base, sensor.size_noise_per_m)).max(0.1),
            width: (spec.width + noise(sensor.size_noise_base, sensor.size_noise_per_m)).max(0.1),
            limit: state.limit,
        };
        rsu.ldm.record(target.agent, spec.kind, measurement);
    }
    rsu.ldm.forget(time, semantic.history);
}

fn count_labels(metrics: &mut SemanticMetrics, items: &[Item]) {
    metrics.transmitted += items.len() as u64;
    for item in items {
        let labels = &item.labels;
        metrics.labelled += u64::from(labels.any());
        metrics.labels.nlos_static += u64::from(labels.nlos == Some(Visibility::NlosStatic));
        metrics.labels.nlos_dynamic += u64::from(labels.nlos == Some(Visibility::NlosDynamic));
        metrics.labels.relevant += u64::from(labels.relevant);
        metrics.labels.speeding += u64::from(labels.speeding);
        metrics.labels.conflict += u64::from(labels.conflict.is_some());
    }
}
