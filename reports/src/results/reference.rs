//! What results.json sets beside the measurements: published figures to
//! compare them with, and the modelling assumptions the verdicts take as given.

use serde::Serialize;

/// A published figure and the measured values it compares with.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ReferenceResult {
    /// Where it is published.
    pub source: String,
    /// The metric.
    pub metric: &'static str,
    /// The published value.
    pub published: f64,
    /// The measured value at each matching point.
    pub points: Vec<ReferencePoint>,
}

/// A measured value beside a published one.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ReferencePoint {
    /// The point index.
    pub point: usize,
    /// The point's label.
    pub label: String,
    /// The measured value (`null` where undefined).
    pub measured: Option<f64>,
    /// What the measured value is computed over, its n (`null` where the
    /// point does not measure the metric).
    pub n: Option<u64>,
}

/// A modelling idealisation that applied to the run: what a model takes as
/// given that the real system does not guarantee.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Assumption {
    /// A stable id, `model.what` (`sight.one-ray`).
    pub id: String,
    /// The simplification and what it means for a verdict.
    pub text: String,
}
