//! The recording writer: a [`TraceSink`] that streams one sweep point's steps
//! into an MCAP file as the engine runs, then every point's outcome and every
//! verdict.
//!
//! Memory stays bounded: each message is built, written into the current chunk
//! and dropped (the MCAP writer keeps one chunk and the indexes); no grid is kept
//! after its step.

use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::{PI, TAU};
use std::io::{Seek, Write};

use mcap::records::MessageHeader;
use mcap::{Attachment, Compression, WriteOptions, Writer};
use serde::Serialize;
use sightline_dsl::{
    Agent, AgentKind, Area, Check, Experiment, Grid as CellGrid, Metric, ObjectProperty, Record, Scenario, Signal,
    World,
};
use sightline_engine::outcome::{CellTally, SemanticMetrics, Sightings, WorldMetrics};
use sightline_engine::trace::{
    AgentState, Body, CooperatorStep, FusedGrid, Item, Measured, Observed, PacketKind, Pose, SemanticStep, Vector,
    Visibility, WorldStep, mount_pose,
};
use sightline_engine::{Outcome, Run, TraceSink};
use sightline_oracles::Verdict;

use super::foxglove::{
    Color, Cube, Entity, GRID_SCHEMA, Grid, LOG_SCHEMA, Level, Line, LineType, Log, Numeric, Pose3,
    SCENE_UPDATE_SCHEMA, SceneUpdate, Text, Time, Vector3,
};
use super::topic;
use super::wire::{
    ApproachRecord, ArrivalRecord, AuditRecord, CellSignals, ConflictRecord, ImportRecord, ItemRecord, MessageRecord,
    MetricValue, ObjectRecord, OutcomeRecord, PacketRecord, PointVerdictRecord, RECORDING_FORMAT, Real,
    RequirementSignal, RequirementSignals, ScenarioRecord, SemanticSignals, SeriesRecord, SignalsRecord, VerdictRecord,
    schema_of,
};
use crate::{Tool, sha256_hex};

/// Why a recording could not be written (the output failed; never the input).
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The MCAP writer or the output failed.
    #[error("failed to write the recording: {0}")]
    Mcap(#[from] mcap::McapError),
    /// A message did not encode.
    #[error("failed to encode a recorded message: {0}")]
    Json(#[from] serde_json::Error),
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

/// A channel's schema: its name and its JSON Schema.
#[derive(Clone, Copy)]
struct SchemaSpec {
    name: &'static str,
    data: fn() -> Vec<u8>,
}

impl SchemaSpec {
    const fn new(name: &'static str, data: fn() -> Vec<u8>) -> Self {
        Self { name, data }
    }
}

// Foxglove's schemas as written in `schemas/`; sightline's derived from the record
// types (each named by its `title`).
const SCENE: SchemaSpec = SchemaSpec::new("foxglove.SceneUpdate", || SCENE_UPDATE_SCHEMA.as_bytes().to_vec());
const GRID: SchemaSpec = SchemaSpec::new("foxglove.Grid", || GRID_SCHEMA.as_bytes().to_vec());
const LOG: SchemaSpec = SchemaSpec::new("foxglove.Log", || LOG_SCHEMA.as_bytes().to_vec());
const SCENARIO: SchemaSpec = SchemaSpec::new("sightline.Scenario", schema_of::<ScenarioRecord>);
const OUTCOME: SchemaSpec = SchemaSpec::new("sightline.Outcome", schema_of::<OutcomeRecord>);
const VERDICT: SchemaSpec = SchemaSpec::new("sightline.Verdict", schema_of::<VerdictRecord>);
const SIGNALS: SchemaSpec = SchemaSpec::new("sightline.Signals", schema_of::<SignalsRecord>);
const REQUIREMENTS: SchemaSpec = SchemaSpec::new("sightline.RequirementSignals", schema_of::<RequirementSignals>);
const PACKET: SchemaSpec = SchemaSpec::new("sightline.Packet", schema_of::<PacketRecord>);
const MESSAGE: SchemaSpec = SchemaSpec::new("sightline.SemanticMessage", schema_of::<MessageRecord>);
const ARRIVAL: SchemaSpec = SchemaSpec::new("sightline.Arrival", schema_of::<ArrivalRecord>);
const APPROACH: SchemaSpec = SchemaSpec::new("sightline.Approach", schema_of::<ApproachRecord>);

/// The metrics the steps of a perception world give, summed over them.
pub(crate) const WORLD_STEP_METRICS: [Metric; 4] = [
    Metric::FovGain,
    Metric::OccupiedRecall,
    Metric::OccupiedPrecision,
    Metric::BlindRecall,
];

/// The metrics the steps of a semantic world's recorded run give.
const SEMANTIC_STEP_METRICS: [Metric; 2] = [Metric::PacketDeliveryRatio, Metric::MissedCriticals];

/// Segments of a full circle (a 360° sensor's range, a region).
const CIRCLE_SEGMENTS: usize = 72;

/// The largest angle between two points of a field-of-view arc, radians.
const ARC_STEP: f64 = 5.0 * PI / 180.0;

const EGO: Color = Color::rgba(0.1, 0.75, 0.3, 0.9);
const CONNECTED: Color = Color::rgba(0.2, 0.45, 0.95, 0.9);
const VEHICLE: Color = Color::rgba(0.55, 0.55, 0.6, 0.9);
const PEDESTRIAN: Color = Color::rgba(0.95, 0.55, 0.1, 0.9);
const RSU: Color = Color::rgba(0.6, 0.3, 0.85, 0.9);
const LABEL: Color = Color::rgba(1.0, 1.0, 1.0, 1.0);
const FOV: Color = Color::rgba(0.3, 0.8, 1.0, 0.35);
const ROAD: Color = Color::rgba(0.7, 0.7, 0.7, 0.8);
const OCCLUDER: Color = Color::rgba(0.85, 0.3, 0.25, 1.0);
const AREA: Color = Color::rgba(1.0, 0.85, 0.2, 0.7);
const OUTLINE: Color = Color::rgba(0.4, 0.4, 0.4, 0.6);
const DETECTION: Color = Color::rgba(1.0, 0.2, 0.6, 0.7);
const ESTIMATE: Color = Color::rgba(0.1, 0.9, 0.9, 0.9);

/// What the steps have summed so far, for `/sightline/requirements`.
enum Running {
    World(WorldMetrics),
    Semantic(SemanticMetrics),
    Nothing,
}

/// Streams a run's record into an MCAP file (see `docs/recording.md` for the
/// channels): create it before the run, hand it to
/// [`simulate_traced`](sightline_engine::simulate_traced) as the sink, then
/// [`finish`](Self::finish) it with the run and its verdicts.
///
/// The bytes depend only on the scenario, the seed and the tool's own version
/// (the MCAP header names the library `sightline`, without a version): the same
/// run gives the same file whatever the thread count.
pub struct Recorder<'s, W: Write + Seek> {
    out: Writer<W>,
    scenario: &'s Scenario,
    record: Record,
    /// The occupancy grid; `None` in a semantic world, which fuses none.
    grid: Option<CellGrid>,
    /// Topic → channel id, created on first use.
    channels: BTreeMap<String, u16>,
    /// Schema name → schema id.
    schemas: BTreeMap<&'static str, u16>,
    sequence: u32,
    /// The first write error; once set, nothing more is written.
    failure: Option<WriteError>,
    /// Log time of the latest step, nanoseconds.
    last: u64,
    agents: Vec<Agent>,
    /// Per agent, its sensors' field-of-view outlines in the sensor frame.
    fields_of_view: Vec<Vec<(Pose, LineType, Vec<Vector>)>>,
    ego: Option<usize>,
    cooperating: BTreeSet<usize>,
    /// Cooperating agents whose detections were shown at the previous step.
    shown: BTreeSet<usize>,
    /// Requirements at the recorded point whose metric the steps give.
    signalled: Vec<(String, Metric, sightline_dsl::Bound)>,
    running: Running,
}

impl<'s, W: Write + Seek> Recorder<'s, W> {
    /// Starts the recording of point `record.point` of `scenario` into `out`:
    /// the MCAP header, `/sightline/scenario`, the imported files as attachments
    /// and the static scene.
    pub fn new(out: W, scenario: &'s Scenario, record: Record, source: &Source<'_>) -> Result<Self, WriteError> {
        let options = WriteOptions::new()
            .compression(Some(Compression::Lz4))
            .library("sightline");
        let point = &scenario.points[record.point];
        let world = match &point.setup.experiment {
            Experiment::World(world) => Some(world.as_ref()),
            Experiment::Field(_) => None,
        };
        let requirement_metrics: &[Metric] = match world {
            Some(w) if w.semantic.is_some() => &SEMANTIC_STEP_METRICS,
            Some(_) => &WORLD_STEP_METRICS,
            None => &[],
        };
        let signalled = scenario
            .requirements
            .iter()
            .filter(|r| r.points.contains(&record.point))
            .filter_map(|r| match r.check {
                // A metric checked on the run itself: its running value over the steps.
                Check::Metric {
                    metric,
                    bound,
                    over_seeds: None,
                } if requirement_metrics.contains(&metric) => Some((r.id.clone(), metric, bound)),
                _ => None,
            })
            .collect();
        let running = match world {
            Some(w) if w.semantic.is_some() => Running::Semantic(SemanticMetrics {
                runs: 1,
                ..SemanticMetrics::default()
            }),
            Some(_) => Running::World(zero_world_metrics()),
            None => Running::Nothing,
        };
        let mut recorder = Self {
            out: options.create(out)?,
            scenario,
            record,
            grid: point.setup.occupancy.as_ref().map(|o| o.grid),
            channels: BTreeMap::new(),
            schemas: BTreeMap::new(),
            sequence: 0,
            failure: None,
            last: 0,
            agents: Vec::new(),
            fields_of_view: Vec::new(),
            ego: world.and_then(|w| {
                w.semantic
                    .as_ref()
                    .map(|s| s.ego)
                    .or_else(|| w.perception.as_ref().map(|p| p.ego))
            }),
            cooperating: world
                .and_then(|w| w.perception.as_ref())
                .map(|p| p.cooperating.iter().copied().collect())
                .unwrap_or_default(),
            shown: BTreeSet::new(),
            signalled,
            running,
        };
        recorder.publish(
            topic::SCENARIO,
            SCENARIO,
            0,
            &ScenarioRecord {
                format: RECORDING_FORMAT.into(),
                tool: source.tool.clone(),
                file: source.file.into(),
                text: source.text.into(),
                sha256: sha256_hex(source.text.as_bytes()),
                seed: source.seed,
                record_flag: source.record_flag,
                point: record.point,
                label: point.label(),
                imports: scenario
                    .imports
                    .iter()
                    .map(|import| ImportRecord {
                        kind: import.kind.name().into(),
                        path: import.path.clone(),
                        sha256: sha256_hex(&import.bytes),
                    })
                    .collect(),
            },
        );
        for import in &scenario.imports {
            recorder.out.attach(&Attachment {
                log_time: 0,
                create_time: 0,
                name: import.path.clone(),
                media_type: "application/xml".into(),
                data: std::borrow::Cow::Borrowed(&import.bytes),
            })?;
        }
        if let Some(world) = world {
            let map = map_entities(world, recorder.grid.as_ref());
            recorder.publish(topic::MAP, SCENE, 0, &SceneUpdate::add(map));
        }
        recorder.take_failure()?;
        Ok(recorder)
    }

    /// Writes every point's outcome, every verdict (structured and as log lines)
    /// at the time of the last step, and closes the file; returns the output.
    pub fn finish(mut self, run: &Run, verdicts: &[Verdict]) -> Result<W, WriteError> {
        let end = self.last;
        let scenario = self.scenario;
        let metric_values = |outcome: &Outcome| -> Vec<MetricValue> {
            outcome
                .samples()
                .into_iter()
                .map(|(metric, sample)| MetricValue {
                    metric,
                    value: sample.value.map(Real),
                    n: sample.n,
                })
                .collect()
        };
        for (point, outcome) in scenario.points.iter().zip(&run.points) {
            // What this point's temporal and per-object checks read, each once.
            let mut signals: Vec<Signal> = Vec::new();
            let mut properties: Vec<ObjectProperty> = Vec::new();
            for requirement in scenario.requirements.iter().filter(|r| r.points.contains(&point.index)) {
                match requirement.check {
                    Check::Temporal { signal, .. } if !signals.contains(&signal) => signals.push(signal),
                    Check::PerObject { property, .. } if !properties.contains(&property) => properties.push(property),
                    _ => {}
                }
            }
            let record = OutcomeRecord {
                point: point.index,
                label: point.label(),
                metrics: metric_values(outcome),
                audit: outcome.audit().copied().map(AuditRecord::from),
                replicates: run.replicates[point.index].iter().map(metric_values).collect(),
                series: signals
                    .into_iter()
                    .filter_map(|signal| {
                        let runs = outcome.series(signal)?;
                        Some(SeriesRecord {
                            signal,
                            runs: runs
                                .iter()
                                .map(|series| series.iter().map(|&(t, v)| (Real(t), Real(v))).collect())
                                .collect(),
                        })
                    })
                    .collect(),
                per_object: properties
                    .into_iter()
                    .filter_map(|property| {
                        let values = outcome.per_object(property)?;
                        Some(ObjectRecord {
                            property,
                            values: values.iter().map(|v| v.map(Real)).collect(),
                        })
                    })
                    .collect(),
            };
            self.publish(topic::OUTCOME, OUTCOME, end, &record);
        }
        for (requirement, verdict) in scenario.requirements.iter().zip(verdicts) {
            self.publish(topic::VERDICTS, VERDICT, end, &verdict_record(requirement, verdict));
            let level = match verdict.status {
                sightline_oracles::Status::Pass => Level::Info,
                sightline_oracles::Status::NotExercised if !verdict.fails_run() => Level::Warning,
                _ => Level::Error,
            };
            let log = Log::new(
                Time::from_nanos(end),
                level,
                format!(
                    "{} {}: {}",
                    verdict.status.words().to_uppercase(),
                    requirement.id,
                    verdict.decisive.message
                ),
                scenario.file.clone(),
                requirement.location.line,
            );
            self.publish(topic::LOG, LOG, end, &log);
        }
        self.take_failure()?;
        self.out.finish()?;
        Ok(self.out.into_inner())
    }

    fn take_failure(&mut self) -> Result<(), WriteError> {
        self.failure.take().map_or(Ok(()), Err)
    }

    /// Writes `message` on `topic` (created with `schema` on first use) at
    /// `log_time` nanoseconds; the first failure is kept for
    /// [`finish`](Self::finish) and stops all further writing.
    fn publish(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, message: &impl Serialize) {
        if self.failure.is_some() {
            return;
        }
        if let Err(error) = self.try_publish(topic, schema, log_time, message) {
            self.failure = Some(error);
        }
    }

    fn try_publish(
        &mut self,
        topic: &str,
        schema: SchemaSpec,
        log_time: u64,
        message: &impl Serialize,
    ) -> Result<(), WriteError> {
        let channel_id = match self.channels.get(topic) {
            Some(&id) => id,
            None => {
                let schema_id = match self.schemas.get(schema.name) {
                    Some(&id) => id,
                    None => {
                        let id = self.out.add_schema(schema.name, "jsonschema", &(schema.data)())?;
                        self.schemas.insert(schema.name, id);
                        id
                    }
                };
                let id = self.out.add_channel(schema_id, topic, "json", &BTreeMap::new())?;
                self.channels.insert(topic.to_string(), id);
                id
            }
        };
        let data = serde_json::to_vec(message)?;
        self.sequence += 1;
        self.out.write_to_known_channel(
            &MessageHeader {
                channel_id,
                sequence: self.sequence,
                log_time,
                publish_time: log_time,
            },
            &data,
        )?;
        Ok(())
    }

    /// `/scene/agents`: every agent in the scene as a box with its id, and its
    /// sensors' fields of view.
    fn publish_agents(&mut self, time: u64, states: &[Option<AgentState>]) {
        let stamp = Time::from_nanos(time);
        let entities = states
            .iter()
            .enumerate()
            .filter_map(|(i, state)| Some((i, (*state)?, self.agents.get(i)?)))
            .map(|(i, state, agent)| {
                let height = height(agent.kind);
                let mut entity = Entity::new(stamp, agent.id.clone())
                    .meta("kind", kind_name(agent.kind))
                    .meta("speed_mps", format!("{:.2}", state.speed))
                    .cube(Cube {
                        pose: Pose3::planar(state.pose, height / 2.0),
                        size: Vector3 {
                            x: agent.length,
                            y: agent.width,
                            z: height,
                        },
                        color: self.color(i, agent),
                    })
                    .text(Text::label(
                        Pose3::planar(state.pose, height + 1.0),
                        agent.id.clone(),
                        LABEL,
                    ));
                for (mount, kind, outline) in self.fields_of_view.get(i).into_iter().flatten() {
                    entity = entity.line(Line::new(
                        *kind,
                        Pose3::planar(state.pose * *mount, 0.05),
                        outline.iter().copied(),
                        0.1,
                        FOV,
                    ));
                }
                entity
            })
            .collect();
        self.publish(topic::AGENTS, SCENE, time, &SceneUpdate::replace(stamp, entities));
    }

    fn color(&self, index: usize, agent: &Agent) -> Color {
        match agent.kind {
            _ if Some(index) == self.ego => EGO,
            AgentKind::Rsu => RSU,
            AgentKind::Pedestrian => PEDESTRIAN,
            _ if agent.connected || self.cooperating.contains(&index) => CONNECTED,
            _ => VEHICLE,
        }
    }

    /// `/perception/<id>/detections`: where each cooperating agent placed what it
    /// detected, and where it believes it is; emptied when it leaves the scene.
    fn publish_detections(&mut self, time: u64, cooperators: &[CooperatorStep<'_>]) {
        let stamp = Time::from_nanos(time);
        let now: BTreeSet<usize> = cooperators.iter().map(|c| c.agent).collect();
        for c in cooperators {
            let Some(agent) = self.agents.get(c.agent) else {
                continue;
            };
            let mut entities = vec![Entity::new(stamp, "estimate").line(Line::new(
                LineType::Loop,
                Pose3::identity(),
                Body::of(c.agent, agent, c.estimate).corners(),
                0.15,
                ESTIMATE,
            ))];
            for sighting in c.observation.sighted() {
                let Some(body) = sighting.detected else { continue };
                let name = self.agent_id(sighting.target);
                let height = self.agents.get(sighting.target).map_or(1.5, |a| height(a.kind));
                entities.push(
                    Entity::new(stamp, format!("{name}#{}", sighting.sensor))
                        .meta("target", &name)
                        .meta("sensor", sighting.sensor)
                        .cube(Cube {
                            pose: Pose3::planar(body.pose, height / 2.0),
                            size: Vector3 {
                                x: body.half_extents.x * 2.0,
                                y: body.half_extents.y * 2.0,
                                z: height,
                            },
                            color: DETECTION,
                        }),
                );
            }
            let topic = topic::detections(&agent.id);
            self.publish(&topic, SCENE, time, &SceneUpdate::replace(stamp, entities));
        }
        for gone in self.shown.difference(&now).copied().collect::<Vec<_>>() {
            let topic = topic::detections(&self.agent_id(gone));
            self.publish(&topic, SCENE, time, &SceneUpdate::replace(stamp, Vec::new()));
        }
        self.shown = now;
    }

    /// `/fusion/grid`: the fused grid cropped to the cells it holds.
    fn publish_fused_grid(&mut self, time: u64, fused: &FusedGrid<'_>) {
        let Some(grid) = self.grid else { return };
        let Some(crop) = Crop::around(&grid, fused.cells.iter().copied()) else {
            return;
        };
        let mut values = vec![f32::NAN; crop.cells() * 2];
        for ((&cell, &p), &u) in fused.cells.iter().zip(fused.probability).zip(fused.uncertainty) {
            let at = crop.index(&grid, cell) * 2;
            values[at] = p;
            values[at + 1] = u;
        }
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let grid = crop.grid(&grid, time, &["probability", "uncertainty"], Numeric::Float32, &data);
        self.publish(topic::FUSED_GRID, GRID, time, &grid);
    }

    /// `/perception/<id>/grid`: each cooperating agent's own grid, cropped to
    /// the cells it observed.
    fn publish_agent_grids(&mut self, time: u64, cooperators: &[CooperatorStep<'_>]) {
        let Some(grid) = self.grid else { return };
        for c in cooperators {
            let observation = c.observation;
            let Some(crop) = Crop::around(&grid, observation.touched().iter().copied()) else {
                continue;
            };
            let mut data = vec![0u8; crop.cells()];
            for &cell in observation.touched() {
                data[crop.index(&grid, cell)] = match observation.get(cell) {
                    Observed::Unknown => 0,
                    Observed::Free => 1,
                    Observed::Occupied => 2,
                };
            }
            let grid = crop.grid(&grid, time, &["state"], Numeric::Uint8, &data);
            let topic = topic::agent_grid(&self.agent_id(c.agent));
            self.publish(&topic, GRID, time, &grid);
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
                let value = match &self.running {
                    Running::World(m) => m.value(*metric),
                    Running::Semantic(m) => m.value(*metric),
                    Running::Nothing => None,
                };
                RequirementSignal {
                    id: id.clone(),
                    metric: *metric,
                    value,
                    threshold: bound.threshold(),
                    margin: value.map(|v| bound.margin(v)),
                }
            })
            .collect();
        let message = RequirementSignals { step, requirements };
        self.publish(topic::REQUIREMENTS, REQUIREMENTS, time, &message);
    }

    fn agent_id(&self, index: usize) -> String {
        self.agents
            .get(index)
            .map_or_else(|| format!("agent{index}"), |a| a.id.clone())
    }

    fn items(&self, items: &[Item]) -> Vec<ItemRecord> {
        items
            .iter()
            .map(|item| ItemRecord {
                agent: self.agent_id(item.agent),
                nlos: item.labels.nlos.map(|v| {
                    match v {
                        Visibility::NlosStatic => "static",
                        Visibility::NlosDynamic => "dynamic",
                        Visibility::Los => "los",
                    }
                    .to_string()
                }),
                relevant: item.labels.relevant,
                speeding: item.labels.speeding,
                conflict: item.labels.conflict.map(|c| ConflictRecord {
                    time: c.time,
                    separation: c.separation,
                }),
            })
            .collect()
    }
}

impl<W: Write + Seek> TraceSink for Recorder<'_, W> {
    fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.to_vec();
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
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.record.grids_at(step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        let time = nanos(step.time);
        self.last = time;
        self.publish_agents(time, step.agents);
        self.publish_detections(time, step.cooperators);
        let cells = step.measured.and_then(|measured| {
            let fused = measured.fused.first()?;
            if let Some(grid) = &fused.grid {
                self.publish_fused_grid(time, grid);
            }
            Some(self.cell_signals(&measured, &fused.cells))
        });
        if self.record.agent_grids && self.record.grids_at(step.step) {
            self.publish_agent_grids(time, step.cooperators);
        }
        let signals = SignalsRecord {
            step: step.step,
            cells,
            semantic: None,
        };
        self.publish(topic::SIGNALS, SIGNALS, time, &signals);
        self.publish_requirement_signals(step.step, time);
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        let time = nanos(step.time);
        self.last = time;
        for arrival in step.arrivals {
            let record = ArrivalRecord {
                at: arrival.at,
                items: self.items(&arrival.items),
            };
            self.publish(topic::ARRIVALS, ARRIVAL, nanos(arrival.at), &record);
        }
        self.publish_agents(time, step.agents);
        let mut signals = SemanticSignals {
            packets: 0,
            received: 0,
            messages: 0,
            messages_received: 0,
            arrivals: step.arrivals.len() as u64,
            approaches: step.approaches.len() as u64,
            missed: step.approaches.iter().filter(|a| !a.flagged).count() as u64,
            min_time_to_conflict: step.min_time_to_conflict(),
        };
        for packet in step.packets {
            let received = packet.reception.received;
            signals.packets += 1;
            signals.received += u64::from(received);
            let (kind, bytes) = match &packet.kind {
                PacketKind::Uplink => ("uplink", None),
                PacketKind::Downlink { bytes, .. } => ("downlink", Some(*bytes as u64)),
                PacketKind::Direct => ("direct", None),
            };
            let record = PacketRecord {
                step: step.step,
                from: self.agent_id(packet.from),
                to: self.agent_id(packet.to),
                kind: kind.into(),
                bytes,
                distance_m: packet.link.distance_m,
                los: packet.link.los,
                rssi_dbm: Some(packet.reception.rssi_dbm).filter(|r| r.is_finite()),
                received,
            };
            self.publish(topic::PACKETS, PACKET, time, &record);
            if let PacketKind::Downlink { items, bytes } = &packet.kind {
                signals.messages += 1;
                signals.messages_received += u64::from(received);
                let record = MessageRecord {
                    step: step.step,
                    from: self.agent_id(packet.from),
                    received,
                    bytes: *bytes as u64,
                    items: self.items(items),
                };
                self.publish(topic::MESSAGES, MESSAGE, time, &record);
            }
        }
        for approach in step.approaches {
            let record = ApproachRecord {
                step: step.step,
                agent: self.agent_id(approach.agent),
                flagged: approach.flagged,
            };
            self.publish(topic::APPROACHES, APPROACH, time, &record);
        }
        if let Running::Semantic(running) = &mut self.running {
            running.messages += signals.messages;
            running.delivered += signals.messages_received;
            running.close_approaches += signals.approaches;
            running.missed_criticals += signals.missed;
        }
        let record = SignalsRecord {
            step: step.step,
            cells: None,
            semantic: Some(signals),
        };
        self.publish(topic::SIGNALS, SIGNALS, time, &record);
        self.publish_requirement_signals(step.step, time);
    }
}

impl<W: Write + Seek> Recorder<'_, W> {
    /// The step's cell signals; adds the step to the running counts.
    fn cell_signals(&mut self, measured: &Measured<'_>, cells: &CellTally) -> CellSignals {
        let mut step = zero_world_metrics();
        add_counts(&mut step, measured.ego_observed, measured.joint_observed, cells);
        if let Running::World(running) = &mut self.running {
            add_counts(running, measured.ego_observed, measured.joint_observed, cells);
        }
        CellSignals {
            ego_observed: measured.ego_observed,
            joint_observed: measured.joint_observed,
            occupied: cells.occupied,
            detected: cells.detected,
            false_positives: cells.false_positives,
            blind_occupied: cells.blind_occupied,
            blind_detected: cells.blind_detected,
            recall: step.value(Metric::OccupiedRecall),
            precision: step.value(Metric::OccupiedPrecision),
            blind_recall: step.value(Metric::BlindRecall),
            fov_gain: step.value(Metric::FovGain),
        }
    }
}

/// World metrics with every count zero.
pub(crate) fn zero_world_metrics() -> WorldMetrics {
    WorldMetrics {
        steps: 0,
        occupied: 0,
        detected: 0,
        false_positives: 0,
        blind_occupied: 0,
        blind_detected: 0,
        ego_observed: 0,
        joint_observed: 0,
        sightings: Sightings::default(),
        localization_error: None,
        mean_uncertainty: None,
        conflict: None,
    }
}

/// Adds one step's counts (cells observed by the ego and jointly, and the fused
/// grid's tallies) to `metrics`. Saturating: replay sums counts read from a file,
/// and a forged count must give a mismatch, not an overflow.
pub(crate) fn add_counts(metrics: &mut WorldMetrics, ego_observed: u64, joint_observed: u64, cells: &CellTally) {
    let add = |total: &mut u64, count: u64| *total = total.saturating_add(count);
    add(&mut metrics.steps, 1);
    add(&mut metrics.ego_observed, ego_observed);
    add(&mut metrics.joint_observed, joint_observed);
    add(&mut metrics.occupied, cells.occupied);
    add(&mut metrics.detected, cells.detected);
    add(&mut metrics.false_positives, cells.false_positives);
    add(&mut metrics.blind_occupied, cells.blind_occupied);
    add(&mut metrics.blind_detected, cells.blind_detected);
}

fn verdict_record(requirement: &sightline_dsl::Requirement, verdict: &Verdict) -> VerdictRecord {
    VerdictRecord {
        id: requirement.id.clone(),
        text: requirement.text.clone(),
        verdict: verdict.status.name().into(),
        accepted: verdict.accepted.clone(),
        value: verdict.decisive.value.map(Real),
        threshold: Real(verdict.threshold),
        margin: verdict.decisive.margin.map(Real),
        message: verdict.decisive.message.clone(),
        points: verdict
            .evaluations
            .iter()
            .map(|e| PointVerdictRecord {
                point: e.point,
                verdict: e.status.name().into(),
                value: e.value.map(Real),
                n: e.n,
                measured: e.measured.clone(),
                margin: e.margin.map(Real),
                message: e.message.clone(),
            })
            .collect(),
    }
}

/// Seconds of simulated time as nanoseconds (negative and NaN as 0).
pub(crate) fn nanos(seconds: f64) -> u64 {
    (seconds * 1e9).round() as u64
}

/// The rectangle of grid cells holding every given cell.
struct Crop {
    col: usize,
    row: usize,
    cols: usize,
    rows: usize,
}

impl Crop {
    /// The bounding box of `cells`; `None` when there are none.
    fn around(grid: &CellGrid, cells: impl Iterator<Item = usize>) -> Option<Self> {
        let mut bounds: Option<[usize; 4]> = None;
        for cell in cells {
            let (col, row) = (cell % grid.cols, cell / grid.cols);
            bounds = Some(match bounds {
                None => [col, row, col, row],
                Some([c0, r0, c1, r1]) => [c0.min(col), r0.min(row), c1.max(col), r1.max(row)],
            });
        }
        bounds.map(|[c0, r0, c1, r1]| Self {
            col: c0,
            row: r0,
            cols: c1 - c0 + 1,
            rows: r1 - r0 + 1,
        })
    }

    fn cells(&self) -> usize {
        self.cols * self.rows
    }

    /// The position of grid cell `cell` (inside the crop) in the crop's data.
    fn index(&self, grid: &CellGrid, cell: usize) -> usize {
        (cell / grid.cols - self.row) * self.cols + (cell % grid.cols - self.col)
    }

    fn grid(&self, grid: &CellGrid, time: u64, names: &[&'static str], kind: Numeric, data: &[u8]) -> Grid {
        let corner = [
            grid.origin[0] + self.col as f64 * grid.cell,
            grid.origin[1] + self.row as f64 * grid.cell,
        ];
        Grid::new(
            Time::from_nanos(time),
            corner,
            grid.cell,
            u32::try_from(self.cols).unwrap_or(u32::MAX),
            names,
            kind,
            data,
        )
    }
}

/// A sensor's field of view in its own frame: a circle of its range when it
/// sees all around, else the sector from the sensor out to its range.
fn field_of_view(range: f64, fov: f64) -> (LineType, Vec<Vector>) {
    let at = |angle: f64| Vector::new(angle.cos(), angle.sin()) * range;
    if fov >= TAU - 1e-9 {
        let points = (0..CIRCLE_SEGMENTS)
            .map(|i| at(i as f64 * TAU / CIRCLE_SEGMENTS as f64))
            .collect();
        return (LineType::Loop, points);
    }
    let segments = (fov / ARC_STEP).ceil().max(1.0) as usize;
    let points = std::iter::once(Vector::ZERO)
        .chain((0..=segments).map(|i| at(-fov / 2.0 + fov * i as f64 / segments as f64)))
        .collect();
    (LineType::Loop, points)
}

/// `/scene/map`: the grid's outline (where there is a grid), roads, occluders,
/// interaction areas, crosswalks and the perception region.
fn map_entities(world: &World, grid: Option<&CellGrid>) -> Vec<Entity> {
    let stamp = Time::from_nanos(0);
    let flat = |points: &[[f64; 2]]| points.iter().map(|&[x, y]| Vector::new(x, y)).collect::<Vec<_>>();
    let loop_line =
        |points: Vec<Vector>, thickness, color| Line::new(LineType::Loop, Pose3::identity(), points, thickness, color);
    let circle = |[x, y]: [f64; 2], radius: f64| {
        (0..CIRCLE_SEGMENTS)
            .map(|i| {
                let angle = i as f64 * TAU / CIRCLE_SEGMENTS as f64;
                Vector::new(x + radius * angle.cos(), y + radius * angle.sin())
            })
            .collect::<Vec<_>>()
    };
    let mut entities: Vec<Entity> = grid
        .map(|grid| {
            let [x0, y0] = grid.origin;
            let (x1, y1) = (x0 + grid.cols as f64 * grid.cell, y0 + grid.rows as f64 * grid.cell);
            Entity::new(stamp, "grid").line(loop_line(flat(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]), 0.2, OUTLINE))
        })
        .into_iter()
        .collect();
    for road in &world.roads {
        let mut entity = Entity::new(stamp, format!("road/{}", road.id)).meta("speed_limit_mps", road.speed_limit);
        for lane in &road.lanes {
            entity = entity.line(Line::new(
                LineType::Strip,
                Pose3::identity(),
                flat(lane.points()),
                0.15,
                ROAD,
            ));
        }
        entities.push(entity);
    }
    for occluder in &world.occluders {
        entities.push(Entity::new(stamp, format!("occluder/{}", occluder.id)).line(loop_line(
            flat(&occluder.polygon),
            0.3,
            OCCLUDER,
        )));
    }
    for area in &world.interaction_areas {
        let outline = match &area.shape {
            Area::Polygon(points) => flat(points),
            Area::Circle { center, radius } => circle(*center, *radius),
        };
        entities.push(Entity::new(stamp, format!("area/{}", area.id)).line(loop_line(outline, 0.2, AREA)));
    }
    for crosswalk in &world.crosswalks {
        let (from, to) = (Vector::from(crosswalk.from), Vector::from(crosswalk.to));
        let across = (to - from).normalize_or_zero();
        let half = Vector::new(-across.y, across.x) * (crosswalk.width / 2.0);
        let corners = vec![from + half, to + half, to - half, from - half];
        entities.push(Entity::new(stamp, format!("crosswalk/{}", crosswalk.id)).line(loop_line(corners, 0.15, AREA)));
    }
    if let Some((center, radius)) = world.perception.as_ref().and_then(|p| p.region) {
        entities.push(Entity::new(stamp, "region").line(loop_line(circle(center, radius), 0.2, AREA)));
    }
    entities
}

/// A box's height for an agent of `kind`, metres (pictures only).
fn height(kind: AgentKind) -> f64 {
    match kind {
        AgentKind::Car => 1.5,
        AgentKind::Truck => 3.5,
        AgentKind::Bus => 3.2,
        AgentKind::Motorbike => 1.4,
        AgentKind::Pedestrian => 1.8,
        AgentKind::Rsu => 5.0,
    }
}

fn kind_name(kind: AgentKind) -> &'static str {
    match kind {
        AgentKind::Car => "car",
        AgentKind::Truck => "truck",
        AgentKind::Bus => "bus",
        AgentKind::Motorbike => "motorbike",
        AgentKind::Pedestrian => "pedestrian",
        AgentKind::Rsu => "rsu",
    }
}
