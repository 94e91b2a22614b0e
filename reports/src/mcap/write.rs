//! The recording writer: a [`TraceSink`] that streams one sweep point's steps
//! into an MCAP file as the engine runs, then every point's outcome and every
//! verdict.
//!
//! The recorder takes each message as the engine hands it a step; a thread
//! of its own compresses and writes them ([`container`]), concurrently with
//! the simulation. The messages of every step that cost most to encode (the
//! frames, speeds, detections and grids) are encoded on that thread too: the
//! recorder hands it what they hold, the simulation goes on.
//!
//! Memory stays bounded: each message is built, handed to the writer thread
//! in a batch and dropped once written into the current chunk (the MCAP
//! writer keeps one chunk and the indexes; a few batches wait for it at most);
//! no grid is kept after its step.
//!
//! This module holds the recorder and its state from step to step: how a
//! recording starts, and the running values of the requirements its steps
//! signal. Its children write the rest: the channels and their schemas
//! ([`channel`]), the file ([`container`]), the scene ([`scene`]), a perception world's steps ([`world`]),
//! a semantic world's ([`semantic`]) and the end ([`outcomes`]). A joint
//! world's step is both: the grid's part, then the pipeline's, in one step's
//! scene and signals.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::sync::Arc;

use mcap::{Compression, WriteOptions};
use sightline_dsl::{Agent, Check, Experiment, Grid as CellGrid, JointPart, Metric, Record, RecordedPoints, Scenario};
use sightline_engine::TraceSink;
use sightline_engine::outcome::{SemanticMetrics, WorldMetrics};
use sightline_engine::trace::{AgentState, Pose, SemanticStep, Vector, WorldStep, mount_pose};

use super::counts::WORLD_STEP_METRICS;
use super::foxglove::{LineType, SceneUpdate, Time};
use super::topic;
use super::wire::{
    CellSignals, ImportRecord, RECORDING_FORMAT, RecordedPointRecord, RequirementSignal, RequirementSignals,
    ScenarioRecord,
};
use crate::{Tool, sha256_hex};
use channel::{REQUIREMENTS, SCENARIO, SCENE};
use container::Container;
use scene::{field_of_view, map_entities};

mod agents;
mod channel;
mod container;
mod outcomes;
mod records;
mod scene;
mod semantic;
mod world;

/// Why a recording could not be written (the output failed; never the input).
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The MCAP writer or the output failed.
    #[error("failed to write the recording: {0}")]
    Mcap(#[from] mcap::McapError),
    /// A message did not encode.
    #[error("failed to encode a recorded message: {0}")]
    Json(#[from] serde_json::Error),
    /// The thread that writes the file did not start.
    #[error("failed to start the recording's writer thread: {0}")]
    Thread(std::io::Error),
    /// The thread that writes the file panicked.
    #[error("the recording's writer thread panicked: {0}")]
    Panicked(String),
}

/// Where a recording comes from, as the CLI knows it.
#[derive(Debug, Clone, Copy)]
pub struct Source<'a> {
    /// The tool that records.
    pub tool: &'a Tool,
    /// The scenario file as the user named it.
    pub file: &'a str,
    /// The scenario's text, as compiled.
    pub text: &'a str,
    /// The seed `--seed` imposed, if any.
    pub seed: Option<u64>,
    /// Whether `--record` was given.
    pub record_flag: bool,
}

/// How long after a point's last step its agents and detections are cleared
/// when another point follows, nanoseconds (points are at least a second
/// apart).
const CLEARED_AFTER: u64 = 1_000_000_000;

/// The metrics the steps of a semantic world's recorded run give.
const SEMANTIC_STEP_METRICS: [Metric; 2] = [Metric::PacketDeliveryRatio, Metric::MissedCriticals];

/// What the steps have summed so far, for `/sightline/requirements`: a
/// perception world's cell counts, a semantic world's message and approach
/// counts, a joint world's both.
struct Running {
    world: Option<WorldMetrics>,
    semantic: Option<SemanticMetrics>,
}

impl Running {
    /// `metric` over the steps so far; `None` where they do not give it.
    fn value(&self, metric: Metric) -> Option<f64> {
        match (&self.world, &self.semantic) {
            (Some(world), Some(semantic)) => match metric.joint_part() {
                _ if !metric.in_joint() => None,
                (JointPart::Grid, metric) => world.value(metric),
                (JointPart::Semantic, metric) => semantic.value(metric),
            },
            (Some(world), None) => world.value(metric),
            (None, Some(semantic)) => semantic.value(metric),
            (None, None) => None,
        }
    }

    /// Whether the steps give `metric`.
    fn gives(&self, metric: Metric) -> bool {
        let (world, semantic) = (self.world.is_some(), self.semantic.is_some());
        match (world, semantic) {
            (true, true) => {
                metric.in_joint()
                    && match metric.joint_part() {
                        (JointPart::Grid, metric) => WORLD_STEP_METRICS.contains(&metric),
                        (JointPart::Semantic, metric) => SEMANTIC_STEP_METRICS.contains(&metric),
                    }
            }
            (true, false) => WORLD_STEP_METRICS.contains(&metric),
            (false, true) => SEMANTIC_STEP_METRICS.contains(&metric),
            (false, false) => false,
        }
    }
}

/// Streams a run's record into an MCAP file (see `docs/recording.md` for the
/// channels): create it before the run, hand it to
/// [`simulate_traced`](sightline_engine::simulate_traced) as the sink, then
/// [`finish`](Self::finish) it with the run and its verdicts.
///
/// The output is written on a thread the recorder starts, in order and
/// without seeking back: wrapped in a [`Sha256Writer`](crate::Sha256Writer),
/// it gives the file's hash as it is written.
///
/// The bytes depend only on the scenario, the seed and the tool's own version
/// (the MCAP header names the library `sightline`, without a version): the same
/// run gives the same file whatever the thread count.
pub struct Recorder<'s, W> {
    /// The file, written on a thread of its own.
    out: Container<W>,
    scenario: &'s Scenario,
    record: Record,
    /// The occupancy grid; `None` in a semantic world, which fuses none.
    grid: Option<CellGrid>,
    /// Log time of the latest step, nanoseconds since 1970 (the recording's
    /// clock starts at `record.start`).
    last: u64,
    /// When the recorded point's step 0 is, nanoseconds since 1970.
    base: u64,
    /// Whether a point's steps are being recorded (a next point clears its scene).
    open: bool,
    agents: Vec<Agent>,
    /// Per agent, its sensors' field-of-view outlines in the sensor frame.
    fields_of_view: Vec<Vec<(Pose, LineType, Vec<Vector>)>>,
    ego: Option<usize>,
    cooperating: BTreeSet<usize>,
    /// Cooperating agents whose detections were shown at the previous step.
    shown: BTreeSet<usize>,
    /// Agents whose fields of view `/scene/fields_of_view` shows, in order.
    fields_shown: Vec<usize>,
    /// Agents `/scene/agents` shows, in order.
    agents_shown: Vec<usize>,
    /// The grid topics the point has shown, with their fields.
    grids_shown: BTreeMap<String, world::GridFields>,
    /// Per agent, what its `/tf` and `/sightline/speeds` JSON holds at every step.
    /// Shared with the writer thread, which encodes those messages.
    agent_json: Arc<[agents::AgentJson]>,
    /// Each agent's id as a JSON string, for the semantic records.
    ids: records::Ids,
    /// Every agent's state at the latest step (`None`: not in the scene).
    last_states: Arc<[Option<AgentState>]>,
    /// Requirements at the recorded point whose metric the steps give.
    signalled: Vec<(String, Metric, sightline_dsl::Bound)>,
    running: Running,
    /// In a joint world, the grid's signals of the step being recorded,
    /// published with the pipeline's.
    pending_cells: Option<CellSignals>,
}

impl<'s, W: Write + Send + 'static> Recorder<'s, W> {
    /// Starts the recording of `scenario` into `out`: the MCAP header,
    /// `/sightline/scenario`, the imported files as attachments, and (one point
    /// recorded) point `record.point`'s static scene. With every point recorded
    /// (`record.points: all`), each point starts when the run calls
    /// [`TraceSink::point`].
    pub fn new(out: W, scenario: &'s Scenario, record: Record, source: &Source<'_>) -> Result<Self, WriteError> {
        let options = WriteOptions::new()
            .compression(Some(Compression::Lz4))
            .library("sightline");
        let mut recorder = Self {
            out: Container::start(out, options)?,
            scenario,
            record,
            grid: None,
            last: record.start,
            base: record.start,
            open: false,
            agents: Vec::new(),
            fields_of_view: Vec::new(),
            ego: None,
            cooperating: BTreeSet::new(),
            shown: BTreeSet::new(),
            fields_shown: Vec::new(),
            agents_shown: Vec::new(),
            grids_shown: BTreeMap::new(),
            agent_json: Arc::new([]),
            ids: records::Ids::default(),
            last_states: Arc::new([]),
            signalled: Vec::new(),
            running: Running {
                world: None,
                semantic: None,
            },
            pending_cells: None,
        };
        let points = record
            .recorded(scenario.points.len())
            .map(|point| RecordedPointRecord {
                point,
                label: scenario.points[point].label(),
                offset: (record.start_of(point) - record.start) as f64 / 1e9,
            })
            .collect();
        recorder.publish(
            topic::SCENARIO,
            SCENARIO,
            record.start,
            &ScenarioRecord {
                format: RECORDING_FORMAT.into(),
                tool: source.tool.clone(),
                file: source.file.into(),
                text: source.text.into(),
                sha256: sha256_hex(source.text.as_bytes()),
                seed: source.seed,
                record_flag: source.record_flag,
                points,
                imports: scenario
                    .imports
                    .iter()
                    .map(|import| ImportRecord {
                        kind: import.kind.name().into(),
                        path: import.path.clone(),
                        sha256: crate::hex(&import.sha256),
                    })
                    .collect(),
            },
        );
        for import in &scenario.imports {
            recorder
                .out
                .attach(&import.path, "application/xml", record.start, &import.bytes);
        }
        if record.points == RecordedPoints::One {
            recorder.begin(record.point);
        }
        recorder.out.take_failure()?;
        Ok(recorder)
    }
}

impl<W> Recorder<'_, W> {
    /// Whether the recorded point is a joint world, whose steps each model
    /// reports in turn.
    fn joint(&self) -> bool {
        self.running.world.is_some() && self.running.semantic.is_some()
    }

    /// Starts recording point `point` at its place on the clock: what its
    /// steps show and signal, and its map (`/scene/map`, replacing the previous
    /// point's); the previous point's agents and detections are cleared a
    /// second after its last step.
    fn begin(&mut self, point: usize) {
        if std::mem::replace(&mut self.open, true) {
            self.clear_scene(self.last.saturating_add(CLEARED_AFTER));
        }
        let scenario = self.scenario;
        self.record = self.record.at_point(&scenario.points, point);
        self.base = self.record.start_of(point);
        self.last = self.base;
        let setup = &scenario.points[point].setup;
        let world = match &setup.experiment {
            Experiment::World(world) => Some(world.as_ref()),
            Experiment::Field(_) => None,
        };
        self.running = Running {
            world: world
                .filter(|w| w.perception.is_some())
                .map(|_| WorldMetrics::default()),
            semantic: world.filter(|w| w.semantic.is_some()).map(|_| SemanticMetrics {
                runs: 1,
                ..SemanticMetrics::default()
            }),
        };
        self.pending_cells = None;
        let running = &self.running;
        self.signalled = scenario
            .requirements
            .iter()
            .filter(|r| r.points.contains(&point))
            .filter_map(|r| match r.check {
                // A metric checked on the run itself: its running value over the steps.
                Check::Metric {
                    metric,
                    bound,
                    over_seeds: None,
                } if running.gives(metric) => Some((r.id.clone(), metric, bound)),
                _ => None,
            })
            .collect();
        self.grid = setup.occupancy.as_ref().map(|o| o.grid);
        self.ego = world.and_then(|w| {
            w.semantic
                .as_ref()
                .map(|s| s.ego)
                .or_else(|| w.perception.as_ref().map(|p| p.ego))
        });
        self.cooperating = world
            .and_then(|w| w.perception.as_ref())
            .map(|p| p.cooperating.iter().copied().collect())
            .unwrap_or_default();
        self.shown.clear();
        self.fields_shown.clear();
        self.agents_shown.clear();
        self.agent_json = Arc::new([]);
        self.ids = records::Ids::default();
        self.last_states = Arc::new([]);
        self.agents.clear();
        self.fields_of_view.clear();
        if let Some(world) = world {
            let map = map_entities(world, self.grid.as_ref(), self.base);
            let stamp = Time::from_nanos(self.base);
            self.publish(topic::MAP, SCENE, self.base, &SceneUpdate::replace(stamp, map));
        }
    }

    /// `/sightline/requirements`: each signalled requirement over the steps so far.
    fn publish_requirement_signals(&mut self, step: usize, time: u64) {
        if self.signalled.is_empty() {
            return;
        }
        let requirements = self
            .signalled
            .iter()
            .map(|(id, metric, bound)| {
                let value = self.running.value(*metric);
                RequirementSignal {
                    id: id.clone(),
                    metric: *metric,
                    value,
                    threshold: bound.threshold(),
                    margin: value.map(|v| bound.margin(v)),
                }
            })
            .collect();
        let message = RequirementSignals {
            point: self.record.point,
            step,
            requirements,
        };
        self.publish(topic::REQUIREMENTS, REQUIREMENTS, time, &message);
    }

    /// The recording's time `seconds` of simulated time after the recorded
    /// point's step 0, nanoseconds since 1970.
    fn at(&self, seconds: f64) -> u64 {
        self.base.saturating_add(nanos(seconds))
    }

    fn agent_id(&self, index: usize) -> String {
        self.agents
            .get(index)
            .map_or_else(|| format!("agent{index}"), |a| a.id.clone())
    }
}

impl<W> TraceSink for Recorder<'_, W> {
    fn point(&mut self, point: usize) {
        self.begin(point);
    }

    fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.to_vec();
        self.ids = records::Ids::new(agents.iter().map(|a| a.id.as_str()));
        self.fields_of_view = agents
            .iter()
            .map(|agent| {
                agent
                    .sensors
                    .iter()
                    .map(|sensor| {
                        let (kind, outline) = field_of_view(sensor.range, sensor.fov);
                        (mount_pose(sensor), kind, outline)
                    })
                    .collect()
            })
            .collect();
        self.render_agents();
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.record.grids_at(step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.publish_world_step(step);
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.publish_semantic_step(step);
    }
}

/// Seconds of simulated time as nanoseconds (negative and NaN as 0).
fn nanos(seconds: f64) -> u64 {
    (seconds * 1e9).round() as u64
}
