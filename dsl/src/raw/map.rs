//! A world's map from another tool: an ASAM OpenDRIVE road network.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;

/// A road network in ASAM OpenDRIVE (`.xodr`, 1.4 to 1.8), in its inertial
/// coordinates (metres, x east, y north), which become the scenario's world
/// frame. Its drivable lanes become roads named `road R lane L` (routes name
/// them), its sidewalks ways pedestrians may take, its junctions interaction
/// areas, its crosswalk objects crosswalks and its objects of `occluder_types`
/// occluders. What is read and what is not: `docs/opendrive.md`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a map mapping with `opendrive`")]
#[schemars(rename = "Map")]
pub(crate) struct RawMap {
    /// The OpenDRIVE file, relative to the scenario file's directory.
    pub opendrive: String,
    /// The object types (`type` of `<object>`) whose outlines block sight;
    /// when given, each must be a type of an object of the map.
    #[serde(default = "default_occluder_types")]
    pub occluder_types: Vec<String>,
    /// Every junction with connecting roads becomes an interaction area,
    /// `junction J`, the outline of its connecting roads' drivable lanes.
    #[serde(default = "default_junction_areas")]
    pub junction_areas: bool,
    /// The speed limit of drivable lanes the map gives none (no `<speed>` of
    /// the lane, no `<type><speed>` of its road, or `no limit`), m/s. Required
    /// when the map has such a lane; refused when it has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SPEED_POSITIVE.schema())]
    pub speed_limit: Option<f64>,
}

fn default_occluder_types() -> Vec<String> {
    vec!["building".into()]
}

fn default_junction_areas() -> bool {
    true
}
