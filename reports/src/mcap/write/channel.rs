//! The channels a recording writes: each message type's schema, and how a
//! message is encoded for its topic (the container registers the topic's
//! channel and schema on first use).

use serde::Serialize;

use super::Recorder;
use crate::mcap::flat::flat_schema_of as schema_of;
use crate::mcap::foxglove::{FRAME_TRANSFORMS_SCHEMA, GRID_SCHEMA, LOG_SCHEMA, SCENE_UPDATE_SCHEMA};
use crate::mcap::wire::{
    ApproachRecord, ArrivalRecord, MessageRecord, OutcomeRecord, PacketRecord, RequirementSignals, RoadUserRecord,
    ScenarioRecord, SignalsRecord, SpeedsRecord, VerdictRecord,
};

/// A channel's schema: its name and its JSON Schema.
#[derive(Clone, Copy)]
pub(super) struct SchemaSpec {
    pub(super) name: &'static str,
    pub(super) data: fn() -> Vec<u8>,
}

impl SchemaSpec {
    const fn new(name: &'static str, data: fn() -> Vec<u8>) -> Self {
        Self { name, data }
    }
}

// Foxglove's schemas as published (`schemas/`); sightline's derived from the
// record types (each named by its `title`) and made flat.
pub(super) const SCENE: SchemaSpec =
    SchemaSpec::new("foxglove.SceneUpdate", || SCENE_UPDATE_SCHEMA.as_bytes().to_vec());
pub(super) const GRID: SchemaSpec = SchemaSpec::new("foxglove.Grid", || GRID_SCHEMA.as_bytes().to_vec());
pub(super) const TRANSFORMS: SchemaSpec = SchemaSpec::new("foxglove.FrameTransforms", || {
    FRAME_TRANSFORMS_SCHEMA.as_bytes().to_vec()
});
pub(super) const LOG: SchemaSpec = SchemaSpec::new("foxglove.Log", || LOG_SCHEMA.as_bytes().to_vec());
pub(super) const SCENARIO: SchemaSpec = SchemaSpec::new("sightline.Scenario", schema_of::<ScenarioRecord>);
pub(super) const OUTCOME: SchemaSpec = SchemaSpec::new("sightline.Outcome", schema_of::<OutcomeRecord>);
pub(super) const VERDICT: SchemaSpec = SchemaSpec::new("sightline.Verdict", schema_of::<VerdictRecord>);
pub(super) const SIGNALS: SchemaSpec = SchemaSpec::new("sightline.Signals", schema_of::<SignalsRecord>);
pub(super) const REQUIREMENTS: SchemaSpec =
    SchemaSpec::new("sightline.RequirementSignals", schema_of::<RequirementSignals>);
pub(super) const SPEEDS: SchemaSpec = SchemaSpec::new("sightline.Speeds", schema_of::<SpeedsRecord>);
pub(super) const PACKET: SchemaSpec = SchemaSpec::new("sightline.Packet", schema_of::<PacketRecord>);
pub(super) const MESSAGE: SchemaSpec = SchemaSpec::new("sightline.SemanticMessage", schema_of::<MessageRecord>);
pub(super) const ARRIVAL: SchemaSpec = SchemaSpec::new("sightline.Arrival", schema_of::<ArrivalRecord>);
pub(super) const APPROACH: SchemaSpec = SchemaSpec::new("sightline.Approach", schema_of::<ApproachRecord>);
pub(super) const OBJECT: SchemaSpec = SchemaSpec::new("sightline.Object", schema_of::<RoadUserRecord>);

impl<W> Recorder<'_, W> {
    /// Writes `message` on `topic` (created with `schema` on first use) at
    /// `log_time` nanoseconds; the first failure is kept for
    /// [`finish`](Self::finish) and stops all further writing.
    pub(super) fn publish(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, message: &impl Serialize) {
        self.out
            .message(topic, schema, log_time, |out| serde_json::to_writer(out, message));
    }

    /// [`publish`](Self::publish) of a message the writer thread encodes
    /// (holding about `held` bytes): encoding off the simulation's thread.
    pub(super) fn publish_deferred(
        &mut self,
        topic: &str,
        schema: SchemaSpec,
        log_time: u64,
        held: usize,
        message: impl Serialize + Send + 'static,
    ) {
        self.out.deferred(topic, schema, log_time, held, move |out| {
            serde_json::to_writer(out, &message)
        });
    }
}
