//! The step loop of a world, as a sequence of phases: **move** (agents advance
//! and their footprints are drawn), **sense** (each cooperating agent estimates
//! its pose and observes; a sender due over the radio encodes what it sensed
//! in the same task), **communicate** (what reaches the ego: over the
//! [`Radio`] when the scenario declares `v2x`, else every grid whole and at
//! once), **fuse** (every
//! job's grid over the cells covered, tallied against the ground truth) and
//! **measure** (the step added to each job's metrics and reported to the sink).
//! State carried from step to step lives in [`Scene`], the [`Cooperator`]s, the
//! [`Truth`], the [`Fusion`] buffers and the [`Measures`].
//!
//! A joint world runs the semantic pipeline on the same scene as a
//! [`StepLayer`]: after the move, its own phases (with the ego's caution
//! restraining the ego from the next step on); after the fuse, which road
//! users each job's grid decided occupied; after the measure, its record.
//!
//! Observations run in parallel across agents (each draws from its own random
//! streams); fusion runs in parallel over fixed-size chunks of the observed cells,
//! merged in chunk order. Results do not depend on the thread count.

use rand::rngs::ChaCha8Rng;
use rayon::prelude::*;
use sightline_dsl::{Agent, AgentKind, Grid, Motion, Perception, World};

use super::evidence::Evidence;
use super::fan;
use super::fuse::{self, Fusion};
use super::layer::StepLayer;
use super::localization::{self, PoseEstimator};
use super::measure::{MeasuredStep, Measures, unmeasured};
use super::message::Message;
use super::metrics::WorldOutcome;
use super::motion::{self, Kinematics};
use super::observe::{self, Observation, StepScene};
use super::radio::{self, Radio};
use super::raster::{Raster, cell_center};
use super::sight::{self, Bodies, Occluders};
use super::state::AgentState;
use super::truth::{EXCLUDED, Truth};
use crate::idealisation::Idealisation;
use crate::math::{Point, Pose, Vector, step_time};
use crate::rng::{Purpose, stream};
use crate::run::Job;
use crate::sink::TraceSink;
use crate::trace::CooperatorStep;

/// Each step's grids stand alone.
pub(crate) const MEMORYLESS: Idealisation = Idealisation {
    id: "world.memoryless",
    text: "Each step's grids hold that step's observations only: no agent accumulates evidence over time or \
           tracks objects.",
};

/// Grids are exchanged without a radio.
pub(crate) const LOSSLESS_EXCHANGE: Idealisation = Idealisation {
    id: "world.lossless-exchange",
    text: "Every cooperating agent's grid reaches the ego at the step it is observed, complete: the scenario \
           declares no `v2x`, so the grids' exchange models no radio (loss, delay, size limits).",
};

/// Agents sense together.
pub(crate) const SYNCHRONOUS: Idealisation = Idealisation {
    id: "world.synchronous",
    text: "Every agent senses at the same instants, the simulation steps, and processes what it senses without \
           delay.",
};

/// A cooperating roadside unit knows where it stands.
pub(crate) const SURVEYED: Idealisation = Idealisation {
    id: "world.surveyed-rsu",
    text: "A cooperating roadside unit places its grid with its true, surveyed pose.",
};

/// The idealisations of a world measuring collective perception, besides those
/// of its options (pose filter, car following, fusion method).
pub(crate) fn idealisations(world: &World, perception: &Perception) -> Vec<Idealisation> {
    let mut listed = vec![
        sight::PLANAR,
        motion::ON_THEIR_WAY,
        SYNCHRONOUS,
        sight::OUTLINES,
        fan::FAN,
        observe::DETECTIONS,
        observe::NOISE,
        observe::FREE_SPACE,
        observe::SELF_REPORT,
    ];
    let cooperators = || perception.cooperating.iter().map(|&i| &world.agents[i]);
    if cooperators().any(|a| matches!(a.motion, Motion::Fixed { .. })) {
        listed.push(SURVEYED);
    }
    if cooperators().any(|a| !matches!(a.motion, Motion::Fixed { .. })) {
        listed.push(if world.localization.is_exact() {
            localization::EXACT
        } else {
            localization::WHITE_NOISE
        });
    }
    if world.agents.iter().any(|a| a.kind == AgentKind::Rsu) {
        listed.push(sight::RSU_TRANSPARENT);
    }
    listed.push(MEMORYLESS);
    match perception.messages {
        None => listed.push(LOSSLESS_EXCHANGE),
        Some(_) => {
            listed.extend([
                radio::GRID_MESSAGES,
                radio::FIXED_RATE,
                radio::STEP_DELIVERY,
                crate::v2x::NO_CONTENTION,
            ]);
            listed.extend_from_slice(crate::v2x::path_loss_idealisations(world.v2x.channel.model));
        }
    }
    listed.push(fuse::INVERSE_MODEL);
    listed
}

/// What stays fixed over a run of a world.
struct Setting<'a> {
    grid: &'a Grid,
    world: &'a World,
    /// Every agent of the scene: the world's, then any generated traffic.
    agents: &'a [Agent],
    occluders: Occluders,
    /// Per cell: whether it lies in the region of interest.
    in_region: Vec<bool>,
}

impl<'a> Setting<'a> {
    fn new(grid: &'a Grid, (world, agents): (&'a World, &'a [Agent]), perception: &'a Perception) -> Self {
        let cells = grid.cells();
        let in_region = match perception.region {
            None => vec![true; cells],
            Some(([x, y], radius)) => (0..cells)
                .map(|cell| (cell_center(grid, cell) - Vector::new(x, y)).length() <= radius)
                .collect(),
        };
        Self {
            grid,
            world,
            agents,
            occluders: Occluders::new(&world.occluders),
            in_region,
        }
    }

    /// Whether the metrics count `cell`: in the region of interest, neither an
    /// occluder nor the ego's footprint.
    fn counted(&self, raster: &Raster, truth: &Truth, cell: usize) -> bool {
        self.in_region[cell] && !raster.is_occluder(cell) && truth.cells()[cell] != EXCLUDED
    }
}

/// The moving scene: every agent's state, their bodies, and the raster they are
/// drawn on, carried from step to step.
struct Scene<'a> {
    kinematics: Kinematics<'a>,
    states: Vec<Option<AgentState>>,
    bodies: Bodies,
    raster: Raster,
}

impl<'a> Scene<'a> {
    /// The scene of `agents` before the first step.
    fn new(grid: &Grid, world: &World, agents: &'a [Agent]) -> Self {
        Self {
            kinematics: Kinematics::new(agents, world.step, world.driving),
            states: Vec::new(),
            bodies: Bodies::empty(),
            raster: Raster::new(*grid, &world.occluders),
        }
    }

    /// Move: every agent advances to step `k`, and the bodies of those in the
    /// scene are drawn on the raster.
    fn advance(&mut self, k: usize, agents: &[Agent]) {
        self.kinematics.advance(k, &mut self.states);
        self.bodies.update(agents, &self.states);
        self.raster.set_bodies(self.bodies.all());
    }
}

/// A cooperating agent's state across steps.
struct Cooperator {
    agent: usize,
    observation: Observation,
    estimator: PoseEstimator,
    localization: ChaCha8Rng,
    odometry: ChaCha8Rng,
    detections: ChaCha8Rng,
    present: bool,
    /// The pose it placed its observation with.
    estimate: Pose,
}

impl Cooperator {
    /// Cooperating agent `agent` before the first step, with its random streams.
    fn new(seed: u64, agent: usize, cells: usize, world: &World) -> Self {
        Self {
            agent,
            observation: Observation::new(cells),
            estimator: PoseEstimator::new(world.localization),
            localization: stream(seed, Purpose::Localization, agent as u64),
            odometry: stream(seed, Purpose::Odometry, agent as u64),
            detections: stream(seed, Purpose::Detections, agent as u64),
            present: false,
            estimate: Pose::IDENTITY,
        }
    }
}

/// Runs a world's collective perception once on the scene of `agents` (the
/// world's, then any generated traffic) and evaluates every job on the same
/// observations, with `layer` running on the same scene, reporting each step
/// to `sink`.
pub fn run(
    seed: u64,
    grid: &Grid,
    (world, agents): (&World, &[Agent]),
    perception: &Perception,
    jobs: &[Job<'_>],
    layer: &mut impl StepLayer,
    sink: &mut impl TraceSink,
) -> Vec<WorldOutcome> {
    let setting = Setting::new(grid, (world, agents), perception);
    let mut scene = Scene::new(grid, world, agents);
    let mut cooperators: Vec<Cooperator> = perception
        .cooperating
        .iter()
        .map(|&agent| Cooperator::new(seed, agent, grid.cells(), world))
        .collect();
    let mut radio = perception
        .messages
        .as_ref()
        .map(|messages| Radio::new(seed, (&world.v2x, messages), grid, world.step, &perception.cooperating));
    let mut truth = Truth::new(grid.cells());
    let mut fusion = Fusion::new(grid, perception, jobs);
    let mut measures = Measures::new(jobs.len());
    sink.start(agents);

    for k in 0..world.steps {
        if sink.gave_up() {
            break;
        }
        let time = step_time(k, world.step);
        scene.advance(k, agents);
        layer.step(k, &scene.states, &scene.bodies, &mut scene.kinematics);
        let ego_in_scene = scene.states[perception.ego].is_some();
        let due = match &mut radio {
            Some(radio) if ego_in_scene => radio.generate(time, &scene.states),
            _ => Vec::new(),
        };
        let (sensed, encoded) = sense(&setting, k, &scene, &mut cooperators, (radio.as_ref(), &due));
        if !ego_in_scene {
            unmeasured(k, time, &scene.states, &sensed, sink);
            layer.record(k, &scene.states, sink);
            continue;
        }
        if let Some(radio) = &mut radio {
            let sent = encoded
                .into_iter()
                .map(|(agent, messages)| {
                    let sensed = sensed.iter().find(|c| c.agent == agent);
                    (sensed.expect("a sender encodes what it sensed"), messages)
                })
                .collect();
            radio.communicate(time, sent, (agents, &scene.states), &setting.occluders);
        }
        let (received, reporting) = communicate(&sensed, radio.as_ref());
        let senders: Vec<Point> = sensed[1..]
            .iter()
            .filter_map(|c| scene.states[c.agent].map(|s| s.position()))
            .collect();
        truth.mark(
            grid,
            &scene.raster,
            &setting.in_region,
            &scene.bodies,
            perception.ego,
            &reporting,
        );
        let snapshot = k == perception.snapshot_step;
        let grids = sink.wants_grids(k);
        let fused = fusion.fuse(
            &received,
            &senders,
            &truth,
            |cell| setting.counted(&scene.raster, &truth, cell),
            (snapshot || grids, layer.reads_grid()),
        );
        if layer.reads_grid() {
            for (job, chunks) in fused.chunks.iter().enumerate() {
                for chunk in chunks {
                    layer.in_grid(job, time, &chunk.owners);
                }
            }
        }
        let step = MeasuredStep {
            step: k,
            time,
            states: &scene.states,
            raster: &scene.raster,
            sensed: &sensed,
            truth: &truth,
            grid,
            senders: &senders,
            fused,
            snapshot,
            grids,
        };
        measures.measure(step, sink);
        layer.record(k, &scene.states, sink);
    }
    measures.finish(jobs, radio.map(Radio::finish))
}

/// Sense: every cooperating agent in the scene estimates its pose at step `k`
/// (a roadside unit knows its surveyed one) and observes with it; those `due`
/// to send over the `radio` encode what they sensed, as they sense. Agents
/// update their pose estimates whether or not the ego is there. Returns what
/// those in the scene sensed, and the messages of those due with their agent
/// index, both in cooperation order.
fn sense<'c>(
    setting: &Setting<'_>,
    k: usize,
    scene: &Scene<'_>,
    cooperators: &'c mut [Cooperator],
    (radio, due): (Option<&Radio<'_>>, &[usize]),
) -> (Vec<CooperatorStep<'c>>, Vec<(usize, Vec<Message>)>) {
    let world = setting.world;
    let agents = setting.agents;
    let step_scene = StepScene {
        grid: setting.grid,
        occluders: &setting.occluders,
        bodies: &scene.bodies,
        raster: &scene.raster,
    };
    let encoded: Vec<Option<(usize, Vec<Message>)>> = cooperators
        .par_iter_mut()
        .map(|c| {
            c.present = false;
            let state = scene.states[c.agent]?;
            let agent = &agents[c.agent];
            let estimate = match agent.motion {
                // A roadside unit's position is surveyed.
                Motion::Fixed { .. } => state.pose,
                Motion::Along { .. } | Motion::Trace { .. } => {
                    // Step k's odometry draws are block k of the agent's stream.
                    c.odometry.set_block_pos(k as u64);
                    c.estimator
                        .estimate(state.pose, world.step, &mut c.localization, &mut c.odometry)
                }
            };
            c.estimate = estimate;
            c.observation
                .observe(&step_scene, (c.agent, agent), state.pose, estimate, &mut c.detections);
            c.present = true;
            let radio = radio.filter(|_| due.contains(&c.agent))?;
            Some((c.agent, radio.encode(&c.observation, state.position())))
        })
        .collect();
    let sensed = cooperators
        .iter()
        .filter(|c| c.present)
        .map(|c| CooperatorStep {
            agent: c.agent,
            estimate: c.estimate,
            observation: &c.observation,
        })
        .collect();
    (sensed, encoded.into_iter().flatten().collect())
}

/// Communicate: the evidence the ego fuses, its own observation first, and
/// the cooperating agents that report their own footprints to it (the ground
/// truth counts those as self-report). Without a radio every cooperating
/// agent's observation arrives whole at the step it is made
/// ([`LOSSLESS_EXCHANGE`]); over one, what the ego holds of each sender.
fn communicate<'c>(sensed: &[CooperatorStep<'c>], radio: Option<&'c Radio<'_>>) -> (Vec<&'c dyn Evidence>, Vec<usize>) {
    let ego = &sensed[0];
    match radio {
        None => (
            sensed.iter().map(|c| c.observation as &dyn Evidence).collect(),
            sensed.iter().map(|c| c.agent).collect(),
        ),
        Some(radio) => (
            std::iter::once(ego.observation as &dyn Evidence)
                .chain(radio.received())
                .collect(),
            std::iter::once(ego.agent).chain(radio.reporting()).collect(),
        ),
    }
}
