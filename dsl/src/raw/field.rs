//! The static field experiment of seed 001: ground truth, fixed sensors and
//! their mass model.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::ErrorModel;

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
    #[schemars(transform = range::EXTENT.schema())]
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
    #[schemars(transform = range::PROBABILITY.schema())]
    pub occupied_fraction: f64,
    /// Side of a square blob, metres; a whole number of cells. Default: one cell,
    /// so every cell is drawn independently.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::EXTENT.schema())]
    pub blob: Option<f64>,
}

/// Fixed sensors, each observing every cell whose centre lies within its range.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a sensors mapping")]
#[schemars(rename = "Sensors")]
pub(crate) struct RawSensors {
    /// Sensing radius R, metres.
    #[schemars(transform = range::SENSOR_RANGE.schema())]
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
    #[schemars(transform = range::COORDINATE.schema())]
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
    #[schemars(transform = range::SENSOR_COUNT.schema())]
    pub rows: u32,
    /// Number of sensor columns (along x).
    #[schemars(transform = range::SENSOR_COUNT.schema())]
    pub cols: u32,
}

/// A random layout.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a mapping with `count`")]
#[schemars(rename = "Random")]
pub(crate) struct RawRandom {
    /// Number of sensors.
    #[schemars(transform = range::SENSOR_COUNT.schema())]
    pub count: u32,
}

/// The sensor mass model: misdetection ε(d; γ) = ε0 + γ/100 · d/R (seed 001, §IV-A).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a masses mapping")]
#[schemars(rename = "Masses")]
pub(crate) struct RawMasses {
    /// Sum of the three Dirichlet parameters (the paper's 30 + 1 + 1 = 32).
    #[serde(default = "default_concentration")]
    #[schemars(transform = range::CONCENTRATION.schema())]
    pub concentration: f64,
    /// ε0, the misdetection at distance 0 (0–1, exclusive; the paper's 0.0625).
    #[serde(default = "default_epsilon0")]
    #[schemars(transform = range::PROBABILITY_OPEN.schema())]
    pub epsilon0: f64,
    /// γ, the growth of misdetection with distance: ε rises by γ/100 from the sensor
    /// to its range (≥ 0; ε at the range must stay below 1).
    #[schemars(transform = range::GAMMA.schema())]
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
