//! Collective perception: the ego, who shares with it, the inverse sensor model
//! and the region the metrics count.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;

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
    #[schemars(transform = range::TIME.schema())]
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
    #[schemars(transform = range::COORDINATE.schema())]
    pub center: [f64; 2],
    /// Radius, metres.
    #[schemars(transform = range::EXTENT.schema())]
    pub radius: f64,
}

/// The inverse sensor model.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "an inverse model mapping")]
#[schemars(rename = "InverseModel")]
pub(crate) struct RawInverseModel {
    /// P(occupied) of a cell a detected object covers (0.5–1).
    #[schemars(transform = range::OCCUPIED.schema())]
    pub occupied: f64,
    /// P(occupied) of a cell seen free along a ray (0–0.5).
    #[schemars(transform = range::FREE.schema())]
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
