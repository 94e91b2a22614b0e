//! The channels a recording writes: each message type's schema, and how a
//! message is written on its topic, the topic's channel and schema registered
//! on first use.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use mcap::McapError;
use mcap::records::MessageHeader;
use serde::Serialize;

use super::{Recorder, WriteError};
use crate::mcap::flat::flat_schema_of as schema_of;
use crate::mcap::foxglove::{FRAME_TRANSFORMS_SCHEMA, GRID_SCHEMA, LOG_SCHEMA, SCENE_UPDATE_SCHEMA};
use crate::mcap::wire::{
    ApproachRecord, ArrivalRecord, MessageRecord, OutcomeRecord, PacketRecord, RequirementSignals, RoadUserRecord,
    ScenarioRecord, SignalsRecord, SpeedsRecord, VerdictRecord,
};

/// A channel's schema: its name and its JSON Schema.
#[derive(Clone, Copy)]
pub(super) struct SchemaSpec {
    name: &'static str,
    data: fn() -> Vec<u8>,
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

impl<W: Write + Seek> Recorder<'_, W> {
    /// Writes `message` on `topic` (created with `schema` on first use) at
    /// `log_time` nanoseconds; the first failure is kept for
    /// [`finish`](Self::finish) and stops all further writing.
    pub(super) fn publish(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, message: &impl Serialize) {
        if self.failure.is_some() {
            return;
        }
        if let Err(error) = self.try_publish(topic, schema, log_time, message) {
            self.failure = Some(error);
        }
    }

    /// [`publish`](Self::publish) of a message already encoded, `json`.
    pub(super) fn publish_json(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, json: &[u8]) {
        if self.failure.is_some() {
            return;
        }
        if let Err(error) = self.try_write(topic, schema, log_time, json) {
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
        let data = serde_json::to_vec(message)?;
        self.try_write(topic, schema, log_time, &data)
    }

    fn try_write(&mut self, topic: &str, schema: SchemaSpec, log_time: u64, data: &[u8]) -> Result<(), WriteError> {
        let (out, schemas) = (&mut self.out, &mut self.schemas);
        let channel_id = registered(&mut self.channels, topic, || {
            let schema_id = registered(schemas, schema.name, || {
                out.add_schema(schema.name, "jsonschema", &(schema.data)())
            })?;
            out.add_channel(schema_id, topic, "json", &BTreeMap::new())
        })?;
        self.sequence += 1;
        self.out.write_to_known_channel(
            &MessageHeader {
                channel_id,
                sequence: self.sequence,
                log_time,
                publish_time: log_time,
            },
            data,
        )?;
        Ok(())
    }
}

/// The id `table` holds for `name`, or else the one `register` gives it, which
/// the table then keeps.
fn registered(
    table: &mut BTreeMap<String, u16>,
    name: &str,
    register: impl FnOnce() -> Result<u16, McapError>,
) -> Result<u16, McapError> {
    if let Some(&id) = table.get(name) {
        return Ok(id);
    }
    let id = register()?;
    table.insert(name.to_string(), id);
    Ok(id)
}
