//! Declared traffic participants and roadside units: how each moves, its
//! footprint and its sensors.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::AgentKind;

/// A traffic participant or a roadside unit.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "an agent mapping with `id` and `kind`")]
#[schemars(rename = "Agent")]
pub(crate) struct RawAgent {
    /// Unique id.
    pub id: String,
    /// What it is; sets the default footprint.
    pub kind: AgentKind,
    /// Vehicles: the road ids it drives along, in order (`road R lane L` for
    /// a lane of `map`). Pedestrians: the sidewalks of `map` it walks along.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(length(max = crate::compile::MAX_ROUTE_ROADS))]
    pub route: Option<Vec<String>>,
    /// Vehicles: the lane it keeps (0: lane 0 of every road).
    #[serde(default)]
    pub lane: u32,
    /// Pedestrians: the points [[x, y], …] it walks through, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::COORDINATE.schema())]
    pub path: Option<Vec<[f64; 2]>>,
    /// Vehicles and pedestrians: the id of the object in `traces.fcd` whose
    /// samples it replays, instead of a route or a path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
    /// Roadside units: where it stands [x, y], metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::COORDINATE.schema())]
    pub position: Option<[f64; 2]>,
    /// Roadside units: heading, degrees counter-clockwise from +x.
    #[serde(default)]
    #[schemars(transform = range::ANGLE.schema())]
    pub heading_deg: f64,
    /// When and where a moving agent appears.
    #[serde(default)]
    pub start: RawStart,
    /// Speed profile of a moving agent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<RawSpeed>,
    /// Footprint; the kind's default when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<RawSize>,
    /// Whether it shares its perception over V2X.
    #[serde(default)]
    pub connected: bool,
    /// Ids of its sensor models.
    #[serde(default)]
    pub sensors: Vec<String>,
}

/// When and where a moving agent appears.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a start mapping")]
#[schemars(rename = "Start")]
pub(crate) struct RawStart {
    /// Time it appears, seconds.
    #[schemars(transform = range::TIME.schema())]
    pub time: f64,
    /// Distance along its route or path where it appears, metres.
    #[schemars(transform = range::OFFSET.schema())]
    pub offset: f64,
}

/// A speed profile: from `initial`, toward `target` at `acceleration`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a speed mapping with `target`")]
#[schemars(rename = "Speed")]
pub(crate) struct RawSpeed {
    /// Desired speed, m/s (vehicles never exceed the road's limit times `limit_factor`).
    #[schemars(transform = range::SPEED.schema())]
    pub target: f64,
    /// Speed when it appears, m/s; the target when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SPEED.schema())]
    pub initial: Option<f64>,
    /// Largest change of speed, m/s².
    #[serde(default = "default_acceleration")]
    #[schemars(transform = range::ACCELERATION.schema())]
    pub acceleration: f64,
    /// Vehicles: it never exceeds the road's speed limit times this factor
    /// (above 1: a non-compliant driver).
    #[serde(default = "default_limit_factor")]
    #[schemars(transform = range::SPEED_FACTOR.schema())]
    pub limit_factor: f64,
}

fn default_limit_factor() -> f64 {
    1.0
}

fn default_acceleration() -> f64 {
    2.0
}

/// A footprint.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a size mapping with `length` and `width`")]
#[schemars(rename = "Size")]
pub(crate) struct RawSize {
    /// Along the heading, metres.
    #[schemars(transform = range::BODY.schema())]
    pub length: f64,
    /// Across the heading, metres.
    #[schemars(transform = range::BODY.schema())]
    pub width: f64,
}
