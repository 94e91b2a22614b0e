//! An OSI multi-channel trace file: ASAM's MCAP convention for OSI messages
//! (OSI 3.8's "OSI trace file formats"), written as the engine runs.
//!
//! The file is an indexed MCAP file with lz4-compressed chunks; it holds the
//! `net.asam.osi.trace` metadata record (the OSI and protobuf versions, the
//! calendar time of time 0, a description, the data source), one schema
//! record per OSI message type (encoding `protobuf`, named by the message's
//! full name, its data the descriptor set the messages are compiled from) and
//! the channels:
//!
//! | topic | message | what |
//! |---|---|---|
//! | `GroundTruth` | `osi3.GroundTruth` | every road user and roadside unit in the scene, each step |
//! | `AGENT.SensorView[K]` | `osi3.SensorView` | sensor K (from 0) of cooperating agent AGENT (a roadside unit too), each step it is in the scene |
//!
//! Each message's log and publish times are its OSI timestamp in nanoseconds
//! (simulated time since step 0). A semantic world reports no sightings:
//! its trace holds the ground truth only. The bytes depend only on the
//! scenario, the seed and the recorded point: the MCAP header names the
//! library `sightline` without a version, and the metadata no wall-clock time
//! (OSI's recommended `creation_time` is left out for that reason).
//!
//! The trace is written in order, without seeking back (each chunk is built
//! in memory and written whole), so a writer can hash it as it passes
//! ([`Sha256Writer`](crate::Sha256Writer)).

use std::collections::BTreeMap;
use std::io::Write;

use mcap::records::{MessageHeader, Metadata};
use mcap::write::NoSeek;
use mcap::{Compression, WriteOptions, Writer};
use prost::Message;
use sightline_dsl::{Agent, Experiment, Record, Scenario};
use sightline_engine::TraceSink;
use sightline_engine::trace::{SemanticStep, WorldStep};

use super::views::{StepViews, ground_truth};

/// The trace's name in the evidence directory.
pub const OSI_TRACE: &str = "osi.mcap";

/// Why a trace could not be written (the output failed; never the input).
#[derive(Debug, thiserror::Error)]
#[error("failed to write the OSI trace: {0}")]
pub struct TraceError(#[from] mcap::McapError);

/// Streams one sweep point's steps into an OSI trace: create it before the
/// run, hand it to the engine as a sink, then [`finish`](Self::finish) it.
pub struct OsiTrace<W: Write> {
    out: Writer<NoSeek<W>>,
    agents: Vec<Agent>,
    ego: Option<usize>,
    /// Schema name → schema id.
    schemas: BTreeMap<&'static str, u16>,
    /// Topic → channel id.
    channels: BTreeMap<String, u16>,
    /// The first write error; once set, nothing more is written.
    failure: Option<mcap::McapError>,
}

impl<W: Write> OsiTrace<W> {
    /// Starts the trace of point `record.point` of `scenario` (read from
    /// `file`) into `out`: the MCAP header and the OSI metadata.
    pub fn new(out: W, scenario: &Scenario, record: Record, file: &str) -> Result<Self, TraceError> {
        let options = WriteOptions::new()
            .compression(Some(Compression::Lz4))
            .library("sightline")
            .disable_seeking(true);
        let mut out = options.create(NoSeek::new(out))?;
        let version = sightline_osi::osi_version();
        let protobuf = sightline_osi::PROTOBUF_VERSION.to_string();
        let point = &scenario.points[record.point];
        let metadata = BTreeMap::from([
            ("version".to_string(), version.clone()),
            ("min_osi_version".to_string(), version.clone()),
            ("max_osi_version".to_string(), version),
            ("min_protobuf_version".to_string(), protobuf.clone()),
            ("max_protobuf_version".to_string(), protobuf),
            ("zero_time".to_string(), zero_time(record.start)),
            (
                "description".to_string(),
                format!("{}, point {}, simulated by sightline", scenario.name, point.label()),
            ),
            ("data_sources".to_string(), format!("sightline scenario {file}")),
        ]);
        out.write_metadata(&Metadata {
            name: "net.asam.osi.trace".into(),
            metadata,
        })?;
        let ego = match &point.setup.experiment {
            Experiment::World(world) => world
                .perception
                .as_ref()
                .map(|p| p.ego)
                .or_else(|| world.semantic.as_ref().map(|s| s.ego)),
            Experiment::Field(_) => None,
        };
        Ok(Self {
            out,
            agents: Vec::new(),
            ego,
            schemas: BTreeMap::new(),
            channels: BTreeMap::new(),
            failure: None,
        })
    }

    /// Ends the trace (its summary and index) and hands back the output.
    pub fn finish(mut self) -> Result<W, TraceError> {
        if let Some(error) = self.failure.take() {
            return Err(error.into());
        }
        self.out.finish()?;
        Ok(self.out.into_inner().into_inner())
    }

    /// Writes `message` of OSI type `schema` on `topic` (described by
    /// `description`), stamped `time` nanoseconds.
    fn publish(&mut self, (topic, description): (&str, &str), schema: &'static str, time: u64, message: &impl Message) {
        if self.failure.is_some() {
            return;
        }
        if let Err(error) = self.try_publish((topic, description), schema, time, message) {
            self.failure = Some(error);
        }
    }

    fn try_publish(
        &mut self,
        (topic, description): (&str, &str),
        schema: &'static str,
        time: u64,
        message: &impl Message,
    ) -> Result<(), mcap::McapError> {
        let channel_id = match self.channels.get(topic) {
            Some(&id) => id,
            None => {
                let schema_id = match self.schemas.get(schema) {
                    Some(&id) => id,
                    None => {
                        let id = self
                            .out
                            .add_schema(schema, "protobuf", sightline_osi::FILE_DESCRIPTOR_SET)?;
                        self.schemas.insert(schema, id);
                        id
                    }
                };
                let metadata = BTreeMap::from([
                    (
                        "net.asam.osi.trace.channel.osi_version".to_string(),
                        sightline_osi::osi_version(),
                    ),
                    (
                        "net.asam.osi.trace.channel.protobuf_version".to_string(),
                        sightline_osi::PROTOBUF_VERSION.to_string(),
                    ),
                    (
                        "net.asam.osi.trace.channel.description".to_string(),
                        description.to_string(),
                    ),
                ]);
                let id = self.out.add_channel(schema_id, topic, "protobuf", &metadata)?;
                self.channels.insert(topic.to_string(), id);
                id
            }
        };
        self.out.write_to_known_channel(
            &MessageHeader {
                channel_id,
                // No packaging layer numbers the messages: 0, as the convention asks.
                sequence: 0,
                log_time: time,
                publish_time: time,
            },
            &message.encode_to_vec(),
        )
    }
}

impl<W: Write> TraceSink for OsiTrace<W> {
    fn start(&mut self, agents: &[Agent]) {
        self.agents = agents.to_vec();
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        let views = StepViews::of(&self.agents, step, self.ego);
        let time = nanos(step.time);
        self.publish(
            ("GroundTruth", GROUND_TRUTH),
            "osi3.GroundTruth",
            time,
            &views.ground_truth,
        );
        for (agent, sensor, view) in &views.sensor_views {
            let agent = &self.agents[*agent];
            let topic = format!("{}.SensorView[{sensor}]", agent.id);
            let description = format!(
                "what sensor {sensor} ({}) of {} has in view, with sightline's visibility of each road user",
                agent.sensors[*sensor].model, agent.id
            );
            self.publish((&topic, &description), "osi3.SensorView", time, view);
        }
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        let truth = ground_truth(&self.agents, step.agents, step.time, self.ego);
        self.publish(
            ("GroundTruth", GROUND_TRUTH),
            "osi3.GroundTruth",
            nanos(step.time),
            &truth,
        );
    }
}

/// Simulated seconds as the nanoseconds of the messages' timestamps.
fn nanos(seconds: f64) -> u64 {
    let stamp = super::views::timestamp(seconds);
    stamp.seconds.unwrap_or(0) as u64 * 1_000_000_000 + u64::from(stamp.nanos.unwrap_or(0))
}

/// Step 0's calendar time, `start` nanoseconds since 1970-01-01T00:00:00Z, in
/// UTC as the convention's `zero_time` asks (ISO 8601 with its zone; a
/// fraction of a second only when there is one).
fn zero_time(start: u64) -> String {
    jiff::Timestamp::from_nanosecond(i128::from(start))
        .expect("u64 nanoseconds since 1970 lie within jiff's range")
        .to_string()
}

const GROUND_TRUTH: &str = "every road user (moving objects) and roadside unit (stationary objects) in the scene";

#[cfg(test)]
mod tests {
    use super::*;

    /// `date -u -d @946684800` is 2000-01-01T00:00:00Z.
    #[test]
    fn zero_time_is_utc_with_a_fraction_only_when_there_is_one() {
        assert_eq!(zero_time(946_684_800_000_000_000), "2000-01-01T00:00:00Z");
        assert_eq!(zero_time(946_684_800_500_000_000), "2000-01-01T00:00:00.5Z");
        assert_eq!(zero_time(0), "1970-01-01T00:00:00Z");
    }

    #[test]
    fn a_step_time_is_its_timestamp_in_nanoseconds() {
        assert_eq!(nanos(0.0), 0);
        assert_eq!(nanos(0.1), 100_000_000);
        assert_eq!(nanos(12.3), 12_300_000_000);
    }
}
