//! The YAML as written: a serde mirror of the scenario file, nothing resolved.
//!
//! Doc comments here become the JSON Schema's descriptions (what editors show on
//! hover) and the generated reference in `docs/reference.md`, so each states its
//! unit and default. Every struct denies unknown keys. Ranges, ids and references
//! are checked in `compile.rs`.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::model::{ErrorModel, FusionMethod, Invariant, Metric, SourceCombination, SwitchMeasure, WeightScaling};

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
    /// The occupancy grid every method fuses into.
    pub grid: RawGrid,
    /// The static field experiment (seed 001): ground truth, fixed sensors, mass model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<RawField>,
    /// How sensor evidence is fused.
    #[serde(default)]
    pub fusion: RawFusion,
    /// How a fused cell becomes a decision.
    #[serde(default)]
    pub decision: RawDecision,
    /// The requirements that must hold.
    #[serde(default)]
    pub requirements: Vec<RawRequirement>,
    /// Settings to vary: a dotted path (`field.masses.gamma`) and the list of values
    /// it takes. One run per combination, first key outermost.
    #[serde(default)]
    pub sweep: BTreeMap<String, Vec<serde_json::Value>>,
    /// Published figures to show beside the measured ones.
    #[serde(default)]
    pub references: Vec<RawReference>,
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
    #[serde(default = "default_error_model")]
    pub error_model: ErrorModel,
}

fn default_concentration() -> f64 {
    32.0
}

fn default_epsilon0() -> f64 {
    0.0625
}

fn default_error_model() -> ErrorModel {
    ErrorModel::DirichletMean
}

/// How sensor evidence is fused in each cell.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a fusion mapping")]
#[schemars(rename = "Fusion")]
pub(crate) struct RawFusion {
    /// Name shown in tables (`Baseline`, `Proposed`). Default: the method name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// The fusion rule.
    #[serde(default = "default_method")]
    pub method: FusionMethod,
    /// Scaling of the distance weights (`distance_weighted`, `hybrid`); the default
    /// is the paper's.
    #[serde(default = "default_weights")]
    pub weights: WeightScaling,
    /// How more than two sources combine (`distance_weighted`, `hybrid`).
    #[serde(default = "default_sources")]
    pub sources: SourceCombination,
    /// When `hybrid` switches to the weighted rule. Required for `hybrid`: the
    /// paper gives no threshold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub switch: Option<RawSwitch>,
}

impl Default for RawFusion {
    fn default() -> Self {
        Self {
            label: None,
            method: default_method(),
            weights: default_weights(),
            sources: default_sources(),
            switch: None,
        }
    }
}

fn default_method() -> FusionMethod {
    FusionMethod::Dempster
}

fn default_weights() -> WeightScaling {
    WeightScaling::SumToOne
}

fn default_sources() -> SourceCombination {
    SourceCombination::AllAtOnce
}

/// The hybrid switch: the weighted rule is used where the sources' distances
/// differ by more than `threshold`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a switch mapping with `threshold`")]
#[schemars(rename = "Switch")]
pub(crate) struct RawSwitch {
    /// How distances are compared.
    #[serde(default = "default_measure")]
    pub measure: SwitchMeasure,
    /// Metres for `difference` (≥ 0); a ratio ≥ 1 for `ratio`.
    pub threshold: f64,
}

fn default_measure() -> SwitchMeasure {
    SwitchMeasure::Difference
}

/// The decision rule: a cell takes the state of its largest mass when
/// p_max − p_others ≥ θ.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a decision mapping")]
#[schemars(rename = "Decision")]
pub(crate) struct RawDecision {
    /// θ (0–1; the paper's 0.8).
    #[serde(default = "default_threshold")]
    pub threshold: f64,
}

impl Default for RawDecision {
    fn default() -> Self {
        Self {
            threshold: default_threshold(),
        }
    }
}

fn default_threshold() -> f64 {
    0.8
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
}

/// A check: a `metric` with `at_least` or `at_most`, or an `invariant`.
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
