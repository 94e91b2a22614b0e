//! The occupancy grid every method fuses into, how evidence is fused in each
//! cell, and how a fused cell becomes a decision.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::{DecisionRule, FusionMethod, SourceCombination, SwitchMeasure, WeightScaling};

/// A regular grid of square cells, axis-aligned in the world frame.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a grid mapping with `size` and `cell`")]
#[schemars(rename = "Grid")]
pub(crate) struct RawGrid {
    /// World position of the lower-left corner [x, y], metres.
    #[serde(default)]
    #[schemars(transform = range::COORDINATE.schema())]
    pub origin: [f64; 2],
    /// Width and height [x, y], metres; each a whole number of cells.
    #[schemars(transform = range::EXTENT.schema())]
    pub size: [f64; 2],
    /// Side of a square cell, metres.
    #[schemars(transform = range::CELL.schema())]
    pub cell: f64,
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
    #[schemars(transform = range::SWITCH.schema())]
    pub threshold: f64,
}

/// The decision rule: a cell takes the state of its largest mass p_max when
/// p_max − p_others ≥ θ (`rule: margin`, seed 001 §IV-C) or p_max > θ
/// (`rule: exceeds`, seed 001 §IV-A and §IV-E).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a decision mapping")]
#[schemars(rename = "Decision")]
pub(crate) struct RawDecision {
    /// Which of seed 001's statements of the rule; the default is §IV-C's formula.
    pub rule: DecisionRule,
    /// θ (0–1; the paper's 0.8).
    #[schemars(transform = range::PROBABILITY.schema())]
    pub threshold: f64,
}

impl Default for RawDecision {
    fn default() -> Self {
        Self {
            rule: DecisionRule::default(),
            threshold: 0.8,
        }
    }
}
