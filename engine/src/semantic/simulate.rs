//! The step loop of a semantic world: **move** (agents, generated traffic
//! among them, advance), then the pipeline's [`Layer`] of phases:
//! **communicate** (the semantic messages that reached the ego by now),
//! **sense** (the ego's own sight and what it was told; each RSU's perception
//! into its LDM at its cycle), **measure** (the ego's step), then at each V2X
//! cycle, RSU by RSU, **communicate** (the ego's plan up) → **fuse** (the
//! pipeline over the LDM) → **communicate** (the message down), and connected
//! road users' own messages, and last **measure** (the step's record to the
//! sink). State carried from step to step lives in the [`Kinematics`] and the
//! layer: the [`Ego`], the [`Rsu`]s, the [`Radio`] and the [`Measures`].
//!
//! A joint world runs the same layer on the perception world's scene
//! ([`world::StepLayer`]): one move for both models, the ego's caution
//! restraining the ego there, and each fusion job's grid telling the layer
//! which road users it decided occupied, the first time of which each road
//! user's record keeps (`first_in_grid`). The layer then draws from random
//! streams of its own ([`Derived::Pipeline`]), so that a roadside unit that
//! also cooperates in the grid draws its pipeline's detections and packet
//! losses apart from its grid's.
//!
//! Our choices where seed 002 is silent:
//! - An RSU perceives every object in its sensors' range (or, with
//!   `rsu_sight: line_of_sight`, the default of a joint world, in view and line
//!   of sight past the map's occluders and the road users' bodies), each with
//!   its sensor's detection probability; each measurement adds Gaussian noise
//!   with σ(d) = base + per_m · d to x, y, speed, length and width (eq. 1).
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
//!   always served. `shares_over: all` counts every cycle. Likewise the
//!   infrastructure contribution counts the steps with the ego within range of
//!   one of an RSU's sensors (`contribution_over: ego_in_range`), or every step
//!   with the ego (`all`).
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

use rayon::prelude::*;
use sightline_dsl::{Agent, AgentKind, Motion, Semantic, ShareCycles, World};

use super::criticality;
use super::ego::{self, Ego};
use super::ldm;
use super::map::route_map;
use super::measure::Measures;
use super::message;
use super::metrics::SemanticMetrics;
use super::pipeline::Pipeline;
use super::radio::{self, Radio};
use super::relevance::Areas;
use super::risk::RouteMap;
use super::rsu::{self, Rsu};
use super::traffic;
use crate::idealisation::Idealisation;
use crate::math::step_time;
use crate::rng::{Derived, derived_seed};
use crate::sink::{NoTrace, TraceSink};
use crate::v2x;
use crate::world::{self, AgentState, Bodies, Kinematics, Occluders, StepLayer};

/// Nobody localizes.
pub(crate) const EXACT_POSES: Idealisation = Idealisation {
    id: "semantic.exact-poses",
    text: "The ego and the roadside units know their own poses exactly: a semantic world does not model \
           self-localization.",
};

/// The pipeline of a joint world uses true poses.
pub(crate) const PIPELINE_EXACT_POSES: Idealisation = Idealisation {
    id: "joint.pipeline-exact-poses",
    text: "In the semantic pipeline the ego and the roadside units know their own poses exactly (the ego's \
           plan and sight, the roadside units' measurements); only the grid's cooperating agents localize.",
};

/// A traced ego does not react.
pub(crate) const EGO_REPLAYS: Idealisation = Idealisation {
    id: "semantic.ego-replays",
    text: "The ego replays its trace: it cannot slow down when a roadside unit flags a conflict, so its \
           trajectory, and every close approach, is the trace's whatever it is told; `cautious_time` counts \
           the time it would have been cautious.",
};

/// Each model of a joint world senses on its own.
pub(crate) const TWO_SENSOR_MODELS: Idealisation = Idealisation {
    id: "joint.two-sensor-models",
    text: "In a joint world a sensor feeds each model as that model sees it: a cooperating agent's grid (a fan \
           of rays per object, free space carved) and the semantic pipeline's object sightings (the ego's and \
           the roadside units', one ray to an object's centre) draw their detections independently, so a \
           roadside unit may detect an object in its grid and miss it in its object list at the same step.",
};

/// The idealisations of a world running the semantic pipeline (alone or in a
/// joint world), besides those of its options (RSU sight, path-loss model,
/// car following).
pub(crate) fn idealisations(world: &World, semantic: &Semantic) -> Vec<Idealisation> {
    let mut listed = vec![world::PLANAR, world::ON_THEIR_WAY];
    if world.traffic.is_some() {
        listed.push(traffic::GENERATED);
    }
    listed.extend([
        if world.is_joint() {
            PIPELINE_EXACT_POSES
        } else {
            EXACT_POSES
        },
        world::ONE_RAY,
        world::OUTLINES,
        world::SYNCHRONOUS,
        ego::EGO_SIGHT,
        rsu::RSU_MEASUREMENTS,
        world::RSU_TRANSPARENT,
        ldm::ASSOCIATION,
        rsu::EGO_PLAN,
        message::SIZED,
        v2x::NO_CONTENTION,
        ego::KNOWN_FOR_A_WHILE,
        radio::BASELINE_REPLAY,
        criticality::BOXES,
    ]);
    let road_users = world
        .agents
        .iter()
        .enumerate()
        .filter(|&(i, a)| i != semantic.ego && a.kind != AgentKind::Rsu);
    if world.v2x.penetration > 0.0 || road_users.clone().any(|(_, a)| a.connected) {
        listed.push(radio::DIRECT_STATES);
    }
    if world.is_joint() {
        listed.push(TWO_SENSOR_MODELS);
    }
    if matches!(world.agents[semantic.ego].motion, Motion::Trace { .. }) {
        listed.push(EGO_REPLAYS);
    }
    listed
}

/// Runs a world's semantic pipeline `semantic.runs` times, each run with its own
/// seed (run 0 with `seed` itself), and pools the measurements in run order,
/// keeping run 0's own as [`SemanticMetrics::first_run`] when there are several.
/// Run 0 reports each step to `sink`; the others run in parallel afterwards and
/// report nothing. The result does not depend on the thread count.
pub fn run(seed: u64, world: &World, semantic: &Semantic, sink: &mut impl TraceSink) -> SemanticMetrics {
    let first = first_run(seed, world, semantic, sink);
    if semantic.runs <= 1 {
        return first;
    }
    let others: Vec<SemanticMetrics> = (1..semantic.runs)
        .into_par_iter()
        .map(|r| run_once((derived_seed(seed, Derived::Run, r), r), world, semantic, &mut NoTrace))
        .collect();
    let mut pooled = first.clone();
    for metrics in others {
        pooled.pool(metrics);
    }
    pooled.first_run = Some(Box::new(first));
    pooled
}

/// Run 0 of [`run`] alone, reporting each step to `sink`: what a recording of
/// a semantic point records, its measurements [`run`]'s
/// [`first_run`](SemanticMetrics::first_run) (or, with one run, [`run`]'s own).
pub fn first_run(seed: u64, world: &World, semantic: &Semantic, sink: &mut impl TraceSink) -> SemanticMetrics {
    run_once((seed, 0), world, semantic, sink)
}

/// Pooled run `run` of a world's semantic pipeline, with its `seed`, reporting
/// each step to `sink`: the move, then the layer.
fn run_once((seed, run): (u64, u32), world: &World, semantic: &Semantic, sink: &mut impl TraceSink) -> SemanticMetrics {
    let agents = traffic::scene(seed, world);
    let ground = Ground::new(world, semantic);
    let mut layer = Layer::new(seed, (world, semantic), &agents, &ground, 0);
    let mut kinematics = Kinematics::new(&agents, world.step, world.driving);
    let mut states = Vec::new();
    let mut bodies = Bodies::empty();
    sink.start(&agents);
    for k in 0..world.steps {
        kinematics.advance(k, &mut states);
        bodies.update(&agents, &states);
        layer.step(k, &states, &bodies, &mut kinematics);
        layer.record(k, &states, sink);
    }
    let mut metrics = layer.finish(run);
    metrics.pop().expect("a run without grids measures once")
}

/// What stays fixed over a run of the pipeline: the map's occluders and the
/// ways the RSUs predict vehicles along.
pub(crate) struct Ground {
    occluders: Occluders,
    map: RouteMap,
}

impl Ground {
    /// The ground of `world` for `semantic`'s RSUs.
    pub(crate) fn new(world: &World, semantic: &Semantic) -> Self {
        Self {
            occluders: Occluders::new(&world.occluders),
            map: route_map(world, semantic),
        }
    }
}

/// The semantic pipeline over a run, step by step: the ego, the RSUs, the
/// radio between them and what is measured, on a scene another loop moves.
pub(crate) struct Layer<'a> {
    semantic: &'a Semantic,
    agents: &'a [Agent],
    occluders: &'a Occluders,
    pipeline: Pipeline<'a>,
    rsus: Vec<Rsu>,
    radio: Radio<'a>,
    ego: Ego,
    measures: Measures,
    /// Per fused grid (fusion job) of a joint world, per agent: when a cell of
    /// its footprint was first decided occupied.
    in_grid: Vec<Vec<Option<f64>>>,
}

impl<'a> Layer<'a> {
    /// The pipeline of `semantic` in `world` before the first step, on the
    /// scene of `agents` over `ground`, drawing from the streams of `seed`;
    /// `grids`: the fused grids whose road users it follows (0 outside a
    /// joint world).
    pub(crate) fn new(
        seed: u64,
        (world, semantic): (&'a World, &'a Semantic),
        agents: &'a [Agent],
        ground: &'a Ground,
        grids: usize,
    ) -> Self {
        let ego_route = agents[semantic.ego]
            .motion
            .path()
            .expect("the compiler checks that the ego follows a route or a moving trace");
        Self {
            semantic,
            agents,
            occluders: &ground.occluders,
            pipeline: Pipeline {
                semantic,
                areas: Areas::of(world),
                occluders: &ground.occluders,
                map: &ground.map,
                ego_route,
                dt: world.step,
            },
            rsus: semantic
                .rsus
                .iter()
                .map(|&agent| Rsu::new(seed, agent, agents, semantic))
                .collect(),
            radio: Radio::new(seed, &world.v2x, semantic.ego, agents.len()),
            ego: Ego::new(semantic.ego, agents.len()),
            measures: Measures::new(world, semantic, agents.len()),
            in_grid: vec![vec![None; agents.len()]; grids],
        }
    }

    /// The run's metrics, its road users' records labelled with pooled run
    /// `run`: one per fused grid it followed, each record holding when the
    /// road user first came into that grid, or one when it followed none.
    pub(crate) fn finish(self, run: u32) -> Vec<SemanticMetrics> {
        self.measures.finish(&self.ego, self.agents, run, &self.in_grid)
    }
}

impl StepLayer for Layer<'_> {
    fn step(&mut self, k: usize, states: &[Option<AgentState>], bodies: &Bodies, kinematics: &mut Kinematics<'_>) {
        let semantic = self.semantic;
        let dt = self.pipeline.dt;
        let time = step_time(k, dt);
        // RSUs run their cycle, and connected road users send, at the V2X rate.
        let cycle = k.is_multiple_of(semantic.period_steps);
        let ego_state = states[semantic.ego];
        // Communicate: the semantic messages that reached the ego by now.
        let arrivals = self.radio.arrivals(time);
        self.ego.receive(&arrivals, semantic.caution.hold);
        self.measures.arrivals(arrivals);
        self.ego.receive_baseline(&self.radio.baseline_arrivals(time));
        // Sense: the ego's view of the scene, measured, and the caution it
        // drives with from the next step on; the RSUs' perception.
        if let Some(ego_now) = ego_state {
            let view = self.ego.sense(
                time,
                &self.agents[semantic.ego],
                ego_now.pose,
                self.occluders,
                bodies,
                semantic.d_min,
            );
            kinematics.restrain(semantic.ego, self.ego.restraint(time, semantic));
            let served = self.rsus.iter().any(|rsu| {
                states[rsu.agent].is_some_and(|s| (s.position() - ego_now.position()).length() <= rsu.range)
            });
            let counted = match semantic.contribution_over {
                ShareCycles::All => true,
                ShareCycles::EgoInRange => served,
            };
            let cautious = self.ego.cautious(time);
            self.measures
                .ego_step((time, dt), ego_now, states, (cautious, counted), view);
        }
        for rsu in self.rsus.iter_mut().filter(|_| cycle) {
            rsu.perceive(self.agents, states, self.occluders, bodies, semantic, time);
        }
        // Communicate and fuse, RSU by RSU; connected road users' own messages.
        if let Some(ego_state) = ego_state.filter(|_| cycle) {
            let cycle = Cycle {
                semantic,
                pipeline: &self.pipeline,
                occluders: self.occluders,
                states,
                ego: ego_state,
                time,
            };
            for rsu in &mut self.rsus {
                cycle.exchange(rsu, &mut self.radio, &mut self.measures);
            }
            let direct = self
                .radio
                .direct(self.agents, states, ego_state, self.occluders, time, &mut self.ego);
            for packet in direct {
                self.measures.packet(packet);
            }
        } else if cycle && semantic.shares_over == ShareCycles::All {
            // `shares_over: all` counts every cycle: with the ego out of the
            // scene an RSU in it tells the ego nothing of what it perceives.
            for rsu in &self.rsus {
                if states[rsu.agent].is_some() {
                    self.measures.unsent(rsu.perceived(&self.pipeline, time));
                }
            }
        }
    }

    fn reads_grid(&self) -> bool {
        !self.in_grid.is_empty()
    }

    fn in_grid(&mut self, job: usize, time: f64, owners: &[usize]) {
        let first = &mut self.in_grid[job];
        for &agent in owners {
            first[agent].get_or_insert(time);
        }
    }

    fn record(&mut self, k: usize, states: &[Option<AgentState>], sink: &mut impl TraceSink) {
        let time = step_time(k, self.pipeline.dt);
        self.measures.record(k, time, states, sink);
    }
}

/// A V2X cycle with the ego in the scene: what the RSUs and the ego exchange.
struct Cycle<'a> {
    semantic: &'a Semantic,
    pipeline: &'a Pipeline<'a>,
    occluders: &'a Occluders,
    states: &'a [Option<AgentState>],
    /// The ego's state.
    ego: AgentState,
    /// The cycle's time, seconds.
    time: f64,
}

impl Cycle<'_> {
    /// One RSU's part, if it is in the scene: communicate (the ego's plan up),
    /// fuse (its pipeline over its LDM with the last plan it received),
    /// communicate (its message down, if it selected anything), each measured.
    fn exchange(&self, rsu: &mut Rsu, radio: &mut Radio<'_>, measures: &mut Measures) {
        let Some(station) = self.states[rsu.agent] else { return };
        let uplink = radio.uplink(rsu, station, self.ego, self.occluders, self.time);
        let link = uplink.link;
        measures.packet(uplink);
        // Whether this cycle counts toward the transmitted and labelled shares.
        let shared = match self.semantic.shares_over {
            ShareCycles::All => true,
            ShareCycles::EgoInRange => link.distance_m <= rsu.range,
        };
        let Some(plan) = rsu.plan else {
            // No plan received yet: the RSU tells the ego nothing of what it
            // perceives, which counts against the shares.
            if shared {
                measures.unsent(rsu.perceived(self.pipeline, self.time));
            }
            return;
        };
        let selection = rsu.select(self.pipeline, self.time, &plan);
        measures.selection(self.time, &selection, shared);
        if !selection.baseline.is_empty() {
            radio.baseline_downlink(rsu, &link, selection.baseline, self.time);
        }
        if selection.items.is_empty() {
            return;
        }
        let downlink = radio.downlink(rsu, &link, selection.items, self.time);
        measures.packet(downlink);
    }
}
