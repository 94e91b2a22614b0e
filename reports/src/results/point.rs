//! Everything measured at one point (a distinct configuration the sweeps
//! simulate): its labels, seed, fusion, metrics with their sample sizes, the
//! mass audit, and what only its kind of scenario measures.

use serde::Serialize;

use super::{Band, Coverage, DensityRow, MassAudit, ObjectList, Ordered, SemanticCounts, SystemDetail, WorldCounts};

/// Everything measured at one point.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct PointResult {
    /// The index.
    pub index: usize,
    /// Its labels joined with ` | ` (empty without a sweep).
    pub label: String,
    /// Each sweep combination the point stands for: one, or several where sweeps
    /// meet at the same configuration.
    pub labels: Vec<LabelResult>,
    /// The seed.
    pub seed: u64,
    /// The fusion method (absent where nothing is fused: a semantic world).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method: Option<&'static str>,
    /// The fusion label (absent where nothing is fused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fusion: Option<String>,
    /// Every defined metric.
    pub metrics: Ordered<f64>,
    /// The sample size of every metric the point measures, defined or not.
    pub samples: Ordered<u64>,
    /// The mass audit (absent where nothing is fused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub audit: Option<MassAudit>,
    /// What only this kind of scenario measures.
    #[serde(flatten)]
    pub detail: Detail,
}

/// One sweep combination a point stands for.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct LabelResult {
    /// The sweep (`null` without a sweep).
    pub sweep: Option<usize>,
    /// The combination as `path=value, …`.
    pub label: String,
    /// Each axis's value.
    pub settings: Ordered<serde_json::Value>,
}

/// Measurements particular to the kind of scenario.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(tag = "experiment", rename_all = "snake_case")]
pub enum Detail {
    /// The field experiment.
    Field {
        /// Metrics by distance to the nearest sensor.
        bands: Vec<Band>,
        /// Sensors per cell.
        coverage: Coverage,
    },
    /// A world's collective perception.
    World {
        /// The counts behind the metrics.
        counts: WorldCounts,
        /// In a joint world (collective perception and the semantic pipeline
        /// on one scene), what the pipeline measured, its road users' records
        /// with when each first came into this point's fused grid; absent in
        /// a perception world.
        // Boxed: a detail of every kind stays small.
        #[serde(skip_serializing_if = "Option::is_none")]
        semantic: Option<Box<SemanticDetail>>,
        /// With a system under test, what it showed of each road user around
        /// the ego; absent without one.
        #[serde(skip_serializing_if = "Option::is_none")]
        system: Option<Box<SystemDetail>>,
    },
    /// A world's semantic pipeline.
    Semantic {
        /// The counts and samples behind the metrics.
        counts: SemanticCounts,
        /// Objects known to the ego only through an RSU, by traffic density.
        contribution_by_density: Vec<DensityRow>,
        /// Every road user relevant to the ego, with its category.
        objects: ObjectList,
    },
}

/// What the semantic pipeline of a joint world measured (a semantic point
/// writes the same beside its `experiment`).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SemanticDetail {
    /// The counts and samples behind the metrics.
    pub counts: SemanticCounts,
    /// Objects known to the ego only through an RSU, by traffic density.
    pub contribution_by_density: Vec<DensityRow>,
    /// Every road user relevant to the ego, with its category and when it
    /// first came into the ego's fused grid.
    pub objects: ObjectList,
}
