//! A world's frame and map: simulated time, the SUMO files it imports, roads
//! and the occluders that block sight.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::Direction;

/// Simulated time.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a time mapping with `duration` and `step`")]
#[schemars(rename = "Time")]
pub(crate) struct RawTime {
    /// Length of the run, seconds.
    #[schemars(transform = range::DURATION.schema())]
    pub duration: f64,
    /// Time between steps, seconds; the duration is a whole number of steps.
    #[schemars(transform = range::STEP.schema())]
    pub step: f64,
    /// When step 0 happens, as an ISO 8601 (RFC 3339) date and time with its UTC
    /// offset (`2026-03-01T08:00:00Z`; the offset within ±23:59, no leap
    /// second), from 1970 to before 2100 (Foxglove's timestamps end in 2106):
    /// the recording's clock (`run.mcap` timestamps). Default 2000-01-01T00:00:00Z, so that the
    /// same scenario and seed give the same recording.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("format" = "date-time"))]
    pub start: Option<String>,
}

/// Files written by the traffic simulator SUMO, in its network coordinates
/// (metres, x east, y north), which become the scenario's world frame. Paths are
/// relative to the scenario file's directory; the files a `sumocfg` names are
/// relative to its own, as SUMO reads them.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a traces mapping with `sumocfg` or `fcd`")]
#[schemars(rename = "Traces")]
pub(crate) struct RawTraces {
    /// A SUMO configuration (`.sumocfg`): the network (`net-file`), the route
    /// files (`route-files`, for their vehicle types), the additional files
    /// (`additional-files`: polygons, points of interest, vehicle types) and
    /// the FCD output (`fcd-output`) it names are read, unless the keys below
    /// name others instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sumocfg: Option<String>,
    /// SUMO floating car data (`sumo --fcd-output`); instead of the
    /// configuration's `fcd-output`, and needed without `sumocfg`. Every vehicle
    /// and person in it becomes an agent replaying its samples, unless a
    /// declared agent replays it (`trace:`); its type gives its kind and size
    /// (see the guide).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fcd: Option<String>,
    /// A SUMO network (`.net.xml`), instead of the configuration's `net-file`:
    /// its roads become `roads` (the lanes vehicles may use, with their widths
    /// and speed limits), its connections the roadside units' map, its
    /// junctions interaction areas, its crossings crosswalks, its walking areas
    /// named `areas`, and its lanes give traced vehicles their speed limits.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net: Option<String>,
    /// SUMO route files, instead of the configuration's `route-files`: their
    /// vehicle types (`<vType>`: `vClass`, `length`, `width`, `guiShape`)
    /// give the traced road users their kinds and sizes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub routes: Option<Vec<String>>,
    /// A SUMO additional file (`.poly.xml`), instead of the configuration's
    /// `additional-files`: polygons of a type in `occluder_types` become
    /// occluders, points of interest of type `rsus.poi_type` roadside units,
    /// and its vehicle types count as the route files' do.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poly: Option<String>,
    /// The polygon types that block sight; when given, each must be a type of
    /// a polygon of the imported files.
    #[serde(default = "default_occluder_types")]
    pub occluder_types: Vec<String>,
    /// With a network: every junction where paths from two roads meet or cross
    /// (roundabouts' too) becomes an interaction area with the junction's
    /// outline, named by its id.
    #[serde(default = "default_junction_areas")]
    pub junction_areas: bool,
    /// Points of interest that become roadside units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rsus: Option<RawPoiRsus>,
    /// The trace's time that becomes the scenario's time 0, seconds.
    #[serde(default)]
    #[schemars(transform = range::TRACE_TIME.schema())]
    pub begin: f64,
}

/// Roadside units from the points of interest of SUMO's additional files.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "an rsus mapping with `poi_type` and `sensors`")]
#[schemars(rename = "PoiRsus")]
pub(crate) struct RawPoiRsus {
    /// The `type` of the points of interest that are roadside units: each
    /// becomes one, named by its id, standing at its position, connected, with
    /// its antenna at its `<param key="height">` (metres; the channel's
    /// `rsu_antenna_m` without one).
    pub poi_type: String,
    /// Their sensors, ids of `sensor_models`; at least one.
    pub sensors: Vec<String>,
}

fn default_occluder_types() -> Vec<String> {
    vec!["building".into()]
}

fn default_junction_areas() -> bool {
    true
}

/// A directed road: one geometry, its lanes and its speed limit.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a road mapping with `id` and one geometry")]
#[schemars(rename = "Road")]
pub(crate) struct RawRoad {
    /// Unique id, used in routes.
    pub id: String,
    /// Centreline of lane 0 as points [[x, y], …], metres, in the direction of travel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::COORDINATE.schema())]
    pub polyline: Option<Vec<[f64; 2]>>,
    /// Centreline of lane 0 as a circular arc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arc: Option<RawArc>,
    /// A closed one-way ring: the circulating lane of a roundabout.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roundabout: Option<RawRoundabout>,
    /// Number of lanes; lane k lies k lane widths left of lane 0.
    #[serde(default = "default_lanes")]
    #[schemars(transform = range::LANES.schema())]
    pub lanes: u32,
    /// Lane width, metres.
    #[serde(default = "default_lane_width")]
    #[schemars(transform = range::BODY.schema())]
    pub lane_width: f64,
    /// Speed limit, m/s.
    #[schemars(transform = range::SPEED_POSITIVE.schema())]
    pub speed_limit: f64,
}

fn default_lanes() -> u32 {
    1
}

fn default_lane_width() -> f64 {
    3.5
}

/// A circular arc, counter-clockwise when `end_deg` > `start_deg`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "an arc mapping")]
#[schemars(rename = "Arc")]
pub(crate) struct RawArc {
    /// Centre [x, y], metres.
    #[schemars(transform = range::COORDINATE.schema())]
    pub center: [f64; 2],
    /// Radius, metres.
    #[schemars(transform = range::RADIUS.schema())]
    pub radius: f64,
    /// Angle of the first point, degrees counter-clockwise from +x.
    #[schemars(transform = range::ANGLE.schema())]
    pub start_deg: f64,
    /// Angle of the last point, degrees.
    #[schemars(transform = range::ARC_END.schema())]
    pub end_deg: f64,
}

/// A roundabout's circulating lane.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a roundabout mapping with `center` and `radius`")]
#[schemars(rename = "Roundabout")]
pub(crate) struct RawRoundabout {
    /// Centre [x, y], metres.
    #[schemars(transform = range::COORDINATE.schema())]
    pub center: [f64; 2],
    /// Radius of lane 0's centreline, metres.
    #[schemars(transform = range::RADIUS.schema())]
    pub radius: f64,
    /// Direction of travel: `ccw` (right-hand traffic) or `cw`.
    #[serde(default)]
    pub direction: Direction,
}

/// A static obstacle to sight: a building or a wall.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "an occluder mapping with `id` and `polygon`")]
#[schemars(rename = "Occluder")]
pub(crate) struct RawOccluder {
    /// Unique id.
    pub id: String,
    /// Outline [[x, y], …], metres, at least three corners (not repeated at the end).
    #[schemars(transform = range::COORDINATE.schema())]
    pub polygon: Vec<[f64; 2]>,
    /// Height, metres. Not modelled: sight and radio are computed in the plane,
    /// so `check` refuses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}
