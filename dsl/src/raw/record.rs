//! What `sightline run` records into `run.mcap`.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;

/// What `sightline run` records into `run.mcap`: one sweep point, step by
/// step (the scene, detections, fused grids, V2X packets, semantic messages),
/// or every point (`points: all`), and every point's metrics and verdicts.
/// Give `point` or `where`, not both; neither records the worst point of the
/// first requirement that fails the run (a failure, an error, or a
/// not-exercised verdict not accepted; the first point when none does).
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
    #[schemars(transform = range::RATE_OR_ZERO.schema())]
    pub grid_rate: Option<f64>,
    /// Also record each cooperating agent's own grid, at `grid_rate` (refused with `grid_rate: 0`, which records no grid).
    pub agent_grids: bool,
    /// `one` (the default): the point `point` or `where` names, or the worst
    /// point of the first requirement that fails the run; `all`: every sweep point, one
    /// after another on the recording's clock (docs/recording.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub points: Option<RawRecordedPoints>,
}

/// Which points a recording holds step by step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
#[schemars(rename = "RecordedPoints")]
pub(crate) enum RawRecordedPoints {
    /// One point.
    One,
    /// Every sweep point.
    All,
}
