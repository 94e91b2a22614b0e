//! The published JSON Schema of results.json (`docs/results.schema.json`),
//! generated from the wire types: draft 2020-12, describing what sightline
//! writes (every field it always writes is required, and no object takes a key
//! the format does not define).

use schemars::generate::SchemaSettings;

use super::Results;

/// The JSON Schema of results.json in the format [`FORMAT`](super::FORMAT).
pub fn results_schema() -> serde_json::Value {
    SchemaSettings::draft2020_12()
        .for_serialize()
        .into_generator()
        .into_root_schema_for::<Results>()
        .to_value()
}
