//! The YAML as written: a serde mirror of the scenario file, nothing resolved.
//!
//! Doc comments here become the JSON Schema's descriptions (what editors show on
//! hover) and the generated reference in `docs/reference.md`, so each states its
//! unit and default. Every struct denies unknown keys. Ranges, ids and references
//! are checked in `compile.rs`.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

mod semantic;

pub(crate) use semantic::*;

use crate::model::{
    AgentKind, Direction, ErrorModel, FusionMethod, Invariant, Metric, ObjectProperty, PoseFilter, RateBound, Signal,
    SourceCombination, SwitchMeasure, WeightScaling,
};

/// A sightline scenario: what to simulate, the requirements that must hold, and
/// optionally a sweep over settings.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a scenario mapping")]
#[schemars(title = "sightline scenario")]
#[schemars(rename = "Scenario")]
pub(crate) struct RawScenario {
    /// Language version; this release reads `1`.
    pub sightline: u32,
    /// Name shown in reports.
    pub name: String,
    /// What the scenario models and why; shown in reports.
    #[serde(default)]
    pub description: String,
    /// Seed of every random stream (0 to 2⁶⁴ − 1). The same file and seed give
    /// byte-identical results.
    #[serde(default)]
    pub seed: u64,
    /// The occupancy grid every method fuses into: required by the field
    /// experiment and by collective perception; a semantic world has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid: Option<RawGrid>,
    /// The static field experiment (seed 001): ground truth, fixed sensors, mass
    /// model. A scenario has either a `field` or a world (`time` … `perception`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<RawField>,
    /// World: simulated time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<RawTime>,
    /// World: agents' trajectories imported from the traffic simulator SUMO, and
    /// optionally its roads and buildings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traces: Option<RawTraces>,
    /// World: directed roads with their lanes (besides those of `traces.net`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub roads: Vec<RawRoad>,
    /// World: buildings and walls that block sight (besides the polygons of
    /// `traces.poly`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub occluders: Vec<RawOccluder>,
    /// World: sensor models by id.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sensor_models: BTreeMap<String, RawSensorModel>,
    /// World: vehicles, pedestrians and roadside units (besides the objects of
    /// `traces.fcd`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub agents: Vec<RawAgent>,
    /// World: how connected agents localize themselves.
    #[serde(default)]
    pub localization: RawLocalization,
    /// World: who shares perception, and how observations become evidence.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub perception: Option<RawPerception>,
    /// World: background traffic generated on routes and crosswalks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traffic: Option<RawTraffic>,
    /// World: pedestrian crossings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub crosswalks: Vec<RawCrosswalk>,
    /// World: regions around junctions, roundabout entries and crossings (besides
    /// the junctions of `traces.net`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub interaction_areas: Vec<RawInteractionArea>,
    /// World: how vehicles keep their distance.
    #[serde(default)]
    pub driving: RawDriving,
    /// World: V2X assumptions.
    #[serde(default)]
    pub v2x: RawV2x,
    /// World: the roadside units' semantic pipeline for an assisted ego (seed 002).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<RawSemantic>,
    /// How sensor evidence is fused.
    #[serde(default)]
    pub fusion: RawFusion,
    /// How a fused cell becomes a decision.
    #[serde(default)]
    pub decision: RawDecision,
    /// The requirements that must hold.
    #[serde(default)]
    pub requirements: Vec<RawRequirement>,
    /// Settings to vary: a dotted path (`field.masses.gamma`; an agent by its id,
    /// `agents.<id>.speed.target`) and the list of values it takes. One run per
    /// combination, first key outermost.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sweep: BTreeMap<String, Vec<serde_json::Value>>,
    /// Independent sweeps, each like `sweep` and each reported as its own table
    /// (for example one over cooperating agents and one over localization noise).
    /// Use `sweep` or `sweeps`, not both.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sweeps: Vec<BTreeMap<String, Vec<serde_json::Value>>>,
    /// Published figures to show beside the measured ones.
    #[serde(default)]
    pub references: Vec<RawReference>,
    /// The space `sightline falsify` searches for a scenario that breaks a
    /// requirement: a dotted path (the sections a sweep may set) and either a
    /// range `[lo, hi]` (whole numbers when the setting is an integer) or
    /// `{ one_of: [ … ] }`. `sightline run` ignores it and runs the values
    /// written in the scenario.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    #[schemars(schema_with = "vary_schema")]
    pub vary: BTreeMap<String, serde_json::Value>,
    /// Record one sweep point, step by step, into `run.mcap` (Foxglove's
    /// formats) beside the other evidence; `sightline run --record` records
    /// with the defaults when this is absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub record: Option<RawRecord>,
}

/// The schema of `vary`: a range or a list of choices per dotted path.
fn vary_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "object",
        "additionalProperties": {
            "oneOf": [
                {
                    "description": "A range [lo, hi] (inclusive, lo ≤ hi).",
                    "type": "array",
                    "items": { "type": "number" },
                    "minItems": 2,
                    "maxItems": 2
                },
                {
                    "type": "object",
                    "properties": {
                        "one_of": {
                            "description": "The values the setting may take; a search shrinks toward the first.",
                            "type": "array",
                            "minItems": 1
                        }
                    },
                    "required": ["one_of"],
                    "additionalProperties": false
                }
            ]
        }
    })
}

/// A regular grid of square cells, axis-aligned in the world frame.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a grid mapping with `size` and `cell`")]
#[schemars(rename = "Grid")]
pub(crate) struct RawGrid {
    /// World position of the lower-left corner [x, y], metres.
    #[serde(default)]
    pub origin: [f64; 2],
    /// Width and height [x, y], metres; each a whole number of cells.
    pub size: [f64; 2],
    /// Side of a square cell, metres.
    pub cell: f64,
}

/// The static field experiment of seed 001.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a field mapping")]
#[schemars(rename = "Field")]
pub(crate) struct RawField {
    /// Ground-truth generator.
    pub truth: RawTruth,
    /// The fixed sensors.
    pub sensors: RawSensors,
    /// How each sensor's mass vector (Empty, Occupy, Unknown) is drawn.
    pub masses: RawMasses,
    /// Upper edges of the distance bands (to the nearest sensor) that metrics are
    /// split by, metres, increasing. A last band holds everything beyond.
    ///
    #[serde(default = "default_distance_bands")]
    pub distance_bands: Vec<f64>,
}

fn default_distance_bands() -> Vec<f64> {
    vec![50.0, 100.0, 150.0, 200.0]
}

/// Ground truth: square blobs of cells, each occupied with a fixed probability.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a truth mapping")]
#[schemars(rename = "Truth")]
pub(crate) struct RawTruth {
    /// Probability that a blob is occupied (0–1); the expected occupied share of cells.
    pub occupied_fraction: f64,
    /// Side of a square blob, metres; a whole number of cells. Default: one cell,
    /// so every cell is drawn independently.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blob: Option<f64>,
}

/// Fixed sensors, each observing every cell whose centre lies within its range.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a sensors mapping")]
#[schemars(rename = "Sensors")]
pub(crate) struct RawSensors {
    /// Sensing radius R, metres.
    pub range: f64,
    /// Where the sensors are: exactly one of `regular`, `positions`, `random`.
    pub layout: RawLayout,
}

/// Sensor positions: give exactly one key.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a layout mapping")]
#[schemars(rename = "Layout")]
pub(crate) struct RawLayout {
    /// `rows` × `cols` sensors at the centres of equal tiles of the grid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub regular: Option<RawRegular>,
    /// Explicit positions [[x, y], …] in the world frame, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<Vec<[f64; 2]>>,
    /// Positions drawn uniformly over the grid from the scenario seed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub random: Option<RawRandom>,
}

/// A regular layout.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a mapping with `rows` and `cols`")]
#[schemars(rename = "Regular")]
pub(crate) struct RawRegular {
    /// Number of sensor rows (along y).
    pub rows: u32,
    /// Number of sensor columns (along x).
    pub cols: u32,
}

/// A random layout.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a mapping with `count`")]
#[schemars(rename = "Random")]
pub(crate) struct RawRandom {
    /// Number of sensors.
    pub count: u32,
}

/// The sensor mass model: misdetection ε(d; γ) = ε0 + γ/100 · d/R (seed 001, §IV-A).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a masses mapping")]
#[schemars(rename = "Masses")]
pub(crate) struct RawMasses {
    /// Sum of the three Dirichlet parameters (the paper's 30 + 1 + 1 = 32).
    #[serde(default = "default_concentration")]
    pub concentration: f64,
    /// ε0, the misdetection at distance 0 (0–1, exclusive; the paper's 0.0625).
    #[serde(default = "default_epsilon0")]
    pub epsilon0: f64,
    /// γ, the growth of misdetection with distance: ε rises by γ/100 from the sensor
    /// to its range (≥ 0; ε at the range must stay below 1).
    pub gamma: f64,
    /// How misdetection shapes the mass vector.
    #[serde(default)]
    pub error_model: ErrorModel,
}

fn default_concentration() -> f64 {
    32.0
}

fn default_epsilon0() -> f64 {
    0.0625
}

/// How sensor evidence is fused in each cell.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a fusion mapping")]
#[schemars(rename = "Fusion")]
pub(crate) struct RawFusion {
    /// Name shown in tables (`Baseline`, `Proposed`). Default: the method name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// The fusion rule.
    pub method: FusionMethod,
    /// Scaling of the distance weights (`distance_weighted`, `hybrid`); the default
    /// is the paper's.
    pub weights: WeightScaling,
    /// How more than two sources combine (`distance_weighted`, `hybrid`).
    pub sources: SourceCombination,
    /// When `hybrid` switches to the weighted rule. Required for `hybrid`: the
    /// paper gives no threshold.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub switch: Option<RawSwitch>,
}

/// The hybrid switch: the weighted rule is used where the sources' distances
/// differ by more than `threshold`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a switch mapping with `threshold`")]
#[schemars(rename = "Switch")]
pub(crate) struct RawSwitch {
    /// How distances are compared.
    #[serde(default)]
    pub measure: SwitchMeasure,
    /// Metres for `difference` (≥ 0); a ratio ≥ 1 for `ratio`.
    pub threshold: f64,
}

/// The decision rule: a cell takes the state of its largest mass when
/// p_max − p_others ≥ θ.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a decision mapping")]
#[schemars(rename = "Decision")]
pub(crate) struct RawDecision {
    /// θ (0–1; the paper's 0.8).
    pub threshold: f64,
}

impl Default for RawDecision {
    fn default() -> Self {
        Self { threshold: 0.8 }
    }
}

/// A requirement: an id, its text, and how it is checked.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(
    deny_unknown_fields,
    expecting = "a requirement mapping with `id`, `text` and `check`"
)]
#[schemars(rename = "Requirement")]
pub(crate) struct RawRequirement {
    /// Unique id: letters, digits, `-`, `_`, `.`.
    pub id: String,
    /// The requirement in words.
    pub text: String,
    /// How it is checked.
    pub check: RawCheck,
    /// Check only at sweep points whose settings match: dotted path → value
    /// (`fusion.label: Proposed`). Default: every point.
    #[serde(default, rename = "where")]
    pub filter: BTreeMap<String, serde_json::Value>,
    /// Accept a not-exercised verdict (nothing to judge at a point: no object,
    /// no sample, an uncovered window, fewer samples than `min_samples`) for
    /// the reason given: the verdict stays `not_exercised` and the report
    /// prints the reason, but it does not fail the run. Without it a
    /// not-exercised requirement fails the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accept_not_exercised: Option<String>,
}

/// A check: a `metric` with `at_least` or `at_most` (optionally over `seeds`), a
/// `signal` with `always` or `eventually`, a `per_object` property, or an
/// `invariant`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a check mapping")]
#[schemars(rename = "Check")]
pub(crate) struct RawCheck {
    /// The metric compared with the threshold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metric: Option<Metric>,
    /// Passes when the metric is at least this value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_least: Option<f64>,
    /// Passes when the metric is at most this value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_most: Option<f64>,
    /// An invariant over every fused cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub invariant: Option<Invariant>,
    /// Numerical tolerance of the invariant (≥ 0). Default 1e-9.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Check the metric over this many independent seeds (at least 2): the
    /// point's own seed, then seeds derived from it. It passes only when a
    /// one-sided confidence bound clears the threshold: of the mean (Student t),
    /// or with `holds_in`, of the share of seeds at which the threshold holds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seeds: Option<u32>,
    /// Confidence level of the bound, above 0.5 and below 1. Default 0.95.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub confidence: Option<f64>,
    /// The share of seeds (0–1] at which the threshold must hold, bounded below
    /// at `confidence`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub holds_in: Option<f64>,
    /// The bound of that share: `clopper_pearson` (exact, the default) or `wilson`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<RateBound>,
    /// A signal over time, checked with `always` or `eventually`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub signal: Option<Signal>,
    /// The signal meets the threshold at every step where it is defined.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub always: Option<RawThreshold>,
    /// The signal meets the threshold at some step where it is defined.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eventually: Option<RawThreshold>,
    /// Only the run's first this many seconds count (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub within: Option<f64>,
    /// A property every object that came within d_min of the ego must meet
    /// (`at_least` or `at_most`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per_object: Option<ObjectProperty>,
    /// The fewest samples a point needs for the check to judge it (≥ 1): the
    /// metric's population (cells, steps, messages, anticipation times…), the
    /// signal's defined steps in each run, the objects of a per-object check,
    /// or the fused cells of an invariant. Below it the requirement is not
    /// exercised at that point. Default 1; 6 for `anticipation_median` and 59
    /// for `anticipation_p95` (the smallest samples whose extremes bound the
    /// quantile with 95 % confidence).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_samples: Option<u64>,
}

/// A threshold at each step of a signal: `at_least` or `at_most`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a threshold mapping with `at_least` or `at_most`")]
#[schemars(rename = "Threshold")]
pub(crate) struct RawThreshold {
    /// The signal is at least this value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_least: Option<f64>,
    /// The signal is at most this value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_most: Option<f64>,
}

/// A published figure, shown beside the measured value at the matching sweep points.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a reference mapping")]
#[schemars(rename = "Reference")]
pub(crate) struct RawReference {
    /// Where the figure is published (`Miyata et al., Table III`).
    pub source: String,
    /// The metric it reports.
    pub metric: Metric,
    /// The sweep points it corresponds to: dotted path → value. Default: every point.
    #[serde(default, rename = "where")]
    pub filter: BTreeMap<String, serde_json::Value>,
    /// The published value.
    pub value: f64,
}

/// What `sightline run` records into `run.mcap`: one sweep point, step by
/// step (the scene, detections, fused grids, V2X packets, semantic messages),
/// and every point's metrics and verdicts. Give `point` or `where`, not both;
/// neither records the first point.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a record mapping")]
#[schemars(rename = "Record")]
pub(crate) struct RawRecord {
    /// The recorded sweep point by index (0: the first point, in the order of
    /// results.json's `sweep`, which lists each distinct configuration once).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<u64>,
    /// The recorded sweep point by its settings: dotted path → value
    /// (`perception.cooperating: 6`); the first point that matches.
    #[serde(rename = "where", skip_serializing_if = "BTreeMap::is_empty")]
    pub filter: BTreeMap<String, serde_json::Value>,
    /// Fused grids (probability and uncertainty) recorded per simulated second,
    /// Hz: every `round(1 / (grid_rate · time.step))` steps, at most every step;
    /// 0 records none. Default 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid_rate: Option<f64>,
    /// Also record each cooperating agent's own grid, at `grid_rate`.
    pub agent_grids: bool,
}

/// Simulated time.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a time mapping with `duration` and `step`")]
#[schemars(rename = "Time")]
pub(crate) struct RawTime {
    /// Length of the run, seconds.
    pub duration: f64,
    /// Time between steps, seconds; the duration is a whole number of steps.
    pub step: f64,
}

/// Files written by the traffic simulator SUMO, in its network coordinates
/// (metres, x east, y north), which become the scenario's world frame. Paths are
/// relative to the scenario file's directory.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a traces mapping with `fcd`")]
#[schemars(rename = "Traces")]
pub(crate) struct RawTraces {
    /// SUMO floating car data (`sumo --fcd-output`). Every vehicle and person in
    /// it becomes an agent replaying its samples, unless a declared agent replays
    /// it (`trace:`); a vehicle type maps to a kind by its name (see the guide).
    pub fcd: String,
    /// A SUMO network (`.net.xml`): its roads become `roads` (lane centrelines
    /// and speed limits), its connections the roadside units' map, and its
    /// lanes give traced vehicles their speed limits.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net: Option<String>,
    /// SUMO polygons (`.poly.xml`): those of a type in `occluder_types` become
    /// occluders.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poly: Option<String>,
    /// The polygon types that block sight.
    #[serde(default = "default_occluder_types")]
    pub occluder_types: Vec<String>,
    /// With `net`: every junction at least three roads enter becomes an
    /// interaction area with the junction's outline, named by its id.
    #[serde(default = "default_junction_areas")]
    pub junction_areas: bool,
    /// The trace's time that becomes the scenario's time 0, seconds.
    #[serde(default)]
    pub begin: f64,
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
    pub polyline: Option<Vec<[f64; 2]>>,
    /// Centreline of lane 0 as a circular arc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arc: Option<RawArc>,
    /// A closed one-way ring: the circulating lane of a roundabout.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roundabout: Option<RawRoundabout>,
    /// Number of lanes; lane k lies k lane widths left of lane 0.
    #[serde(default = "default_lanes")]
    pub lanes: u32,
    /// Lane width, metres.
    #[serde(default = "default_lane_width")]
    pub lane_width: f64,
    /// Speed limit, m/s.
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
    pub center: [f64; 2],
    /// Radius, metres.
    pub radius: f64,
    /// Angle of the first point, degrees counter-clockwise from +x.
    pub start_deg: f64,
    /// Angle of the last point, degrees.
    pub end_deg: f64,
}

/// A roundabout's circulating lane.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a roundabout mapping with `center` and `radius`")]
#[schemars(rename = "Roundabout")]
pub(crate) struct RawRoundabout {
    /// Centre [x, y], metres.
    pub center: [f64; 2],
    /// Radius of lane 0's centreline, metres.
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
    pub polygon: Vec<[f64; 2]>,
    /// Height, metres. Not modelled: sight and radio are computed in the plane,
    /// so `check` refuses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}

/// A sensor model, referred to by agents.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a sensor model mapping")]
#[schemars(rename = "SensorModel")]
pub(crate) struct RawSensorModel {
    /// Range, metres.
    pub range: f64,
    /// Horizontal field of view, degrees (360: all around).
    #[serde(default = "default_fov")]
    pub fov_deg: f64,
    /// Mounting pose in the agent frame (x forward, y left).
    #[serde(default)]
    pub mount: RawMount,
    /// Probability that a visible object in range is detected (0–1).
    #[serde(default = "default_detection_probability")]
    pub detection_probability: f64,
    /// Standard deviation of a detection's position error, σ(d) = base + per_m · d
    /// (seed 002, eq. 1, with a linear σ(d)).
    #[serde(default)]
    pub position_noise: RawNoise,
    /// Standard deviation of the error of a detection's length and width,
    /// σ(d) = base + per_m · d, metres.
    #[serde(default)]
    pub size_noise: RawNoise,
    /// Standard deviation of a detection's speed error, σ(d) = base + per_m · d, m/s.
    #[serde(default)]
    pub velocity_noise: RawNoise,
    /// Angle between the rays that carve free space, degrees.
    #[serde(default = "default_ray_spacing")]
    pub ray_spacing_deg: f64,
}

fn default_fov() -> f64 {
    360.0
}

fn default_detection_probability() -> f64 {
    1.0
}

fn default_ray_spacing() -> f64 {
    0.5
}

/// A mounting pose in the agent frame.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a mount mapping")]
#[schemars(rename = "Mount")]
pub(crate) struct RawMount {
    /// Forward of the agent's centre, metres.
    pub x: f64,
    /// Left of the agent's centre, metres.
    pub y: f64,
    /// Yaw relative to the agent's heading, degrees.
    pub yaw_deg: f64,
}

/// A distance-dependent standard deviation σ(d) = base + per_m · d.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a noise mapping with `base` and `per_m`")]
#[schemars(rename = "Noise")]
pub(crate) struct RawNoise {
    /// σ at distance 0, metres.
    pub base: f64,
    /// Growth of σ per metre of distance.
    pub per_m: f64,
}

/// A traffic participant or a roadside unit.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "an agent mapping with `id` and `kind`")]
#[schemars(rename = "Agent")]
pub(crate) struct RawAgent {
    /// Unique id.
    pub id: String,
    /// What it is; sets the default footprint.
    pub kind: AgentKind,
    /// Vehicles: the road ids it drives along, in order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub route: Option<Vec<String>>,
    /// Vehicles: the lane it keeps (0: lane 0 of every road).
    #[serde(default)]
    pub lane: u32,
    /// Pedestrians: the points [[x, y], …] it walks through, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<Vec<[f64; 2]>>,
    /// Vehicles and pedestrians: the id of the object in `traces.fcd` whose
    /// samples it replays, instead of a route or a path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
    /// Roadside units: where it stands [x, y], metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 2]>,
    /// Roadside units: heading, degrees counter-clockwise from +x.
    #[serde(default)]
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
    pub time: f64,
    /// Distance along its route or path where it appears, metres.
    pub offset: f64,
}

/// A speed profile: from `initial`, toward `target` at `acceleration`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a speed mapping with `target`")]
#[schemars(rename = "Speed")]
pub(crate) struct RawSpeed {
    /// Desired speed, m/s (vehicles never exceed the road's limit times `limit_factor`).
    pub target: f64,
    /// Speed when it appears, m/s; the target when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<f64>,
    /// Largest change of speed, m/s².
    #[serde(default = "default_acceleration")]
    pub acceleration: f64,
    /// Vehicles: it never exceeds the road's speed limit times this factor
    /// (above 1: a non-compliant driver).
    #[serde(default = "default_limit_factor")]
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
    pub length: f64,
    /// Across the heading, metres.
    pub width: f64,
}

/// Self-localization of connected agents.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a localization mapping")]
#[schemars(rename = "Localization")]
pub(crate) struct RawLocalization {
    /// σ of each self-reported x and y measurement, metres.
    pub position_sigma: f64,
    /// σ of each self-reported heading measurement, degrees.
    pub heading_sigma_deg: f64,
    /// How an agent estimates its pose from its measurements.
    pub filter: PoseFilter,
    /// Kalman filter: uncertainty the motion model adds to x and y, metres per √s.
    pub process_position_sigma: f64,
    /// Kalman filter: uncertainty the motion model adds to the heading, degrees per √s.
    pub process_heading_sigma_deg: f64,
}

impl Default for RawLocalization {
    fn default() -> Self {
        Self {
            position_sigma: 0.0,
            heading_sigma_deg: 0.0,
            filter: PoseFilter::default(),
            process_position_sigma: 0.1,
            process_heading_sigma_deg: 0.5,
        }
    }
}

/// Collective perception: who shares, and how an observation becomes evidence.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a perception mapping with `ego`")]
#[schemars(rename = "Perception")]
pub(crate) struct RawPerception {
    /// Id of the ego agent (connected, with sensors).
    pub ego: String,
    /// Agents whose grids are fused, the ego included: the ego and the first
    /// `cooperating` − 1 other connected agents with sensors, in file order.
    /// Default: all connected agents with sensors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cooperating: Option<u32>,
    /// Probabilities of occupancy an observation conveys.
    #[serde(default)]
    pub inverse_model: RawInverseModel,
    /// Time of the grids pictured in the report, seconds. Default: the middle of the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot: Option<f64>,
    /// The area the metrics count: cells whose centre lies in this circle. Default:
    /// the whole grid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<RawRegion>,
}

/// A circular region of interest.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a region mapping with `center` and `radius`")]
#[schemars(rename = "Region")]
pub(crate) struct RawRegion {
    /// Centre [x, y], metres.
    pub center: [f64; 2],
    /// Radius, metres.
    pub radius: f64,
}

/// The inverse sensor model.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "an inverse model mapping")]
#[schemars(rename = "InverseModel")]
pub(crate) struct RawInverseModel {
    /// P(occupied) of a cell a detected object covers (0.5–1).
    pub occupied: f64,
    /// P(occupied) of a cell seen free along a ray (0–0.5).
    pub free: f64,
}

impl Default for RawInverseModel {
    fn default() -> Self {
        Self {
            occupied: 0.7,
            free: 0.3,
        }
    }
}
