//! The requirements that must hold, how each is checked, and the published
//! figures shown beside the measured ones.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::{AgentKind, Comparison, Invariant, Metric, ObjectProperty, RateBound, Signal};

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
    /// Compare the metric with another measured on the same run: `baseline`
    /// (the same metric over the ETSI baseline's messages, on the same traffic:
    /// `channel_load`, `anticipation_median`, `anticipation_p95`,
    /// `object_anticipation_median`, `object_anticipation_p95`) or another
    /// metric's name. `at_least` / `at_most` then bound their ratio (or, with
    /// `by: difference`, their difference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_to: Option<String>,
    /// How `relative_to` compares: `ratio` (metric / other, the default) or
    /// `difference` (metric − other).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub by: Option<Comparison>,
    /// An invariant over every fused cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub invariant: Option<Invariant>,
    /// Numerical tolerance of the invariant (≥ 0). Default 1e-9.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::TOLERANCE.schema())]
    pub tolerance: Option<f64>,
    /// Check the metric over this many independent seeds (at least 2): the
    /// point's own seed, then seeds derived from it. It passes only when a
    /// one-sided confidence bound clears the threshold: of the mean (Student t),
    /// or with `holds_in`, of the share of seeds at which the threshold holds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SEEDS.schema())]
    pub seeds: Option<u32>,
    /// Confidence level of the bound, above 0.5 and below 1. Default 0.95.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::CONFIDENCE.schema())]
    pub confidence: Option<f64>,
    /// The share of seeds (0–1, both excluded) at which the threshold must
    /// hold, bounded below at `confidence`. 1 is refused: the lower bound of a
    /// share is below 1 even with every seed holding, so it could never pass.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SHARE_OF_SEEDS.schema())]
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
    /// With `signal` only (a metric is one number per run): only the run's
    /// first this many seconds count (> 0), the steps at time t ≤ `within`,
    /// the step at t = `within` included.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SPAN.schema())]
    pub within: Option<f64>,
    /// A property every road user it judges must meet (`at_least` or
    /// `at_most`): `warning_time` of every object that came within d_min of
    /// the ego, or a property of every relevant road user's record (with a
    /// system under test, `sut_*`: of its record of every road user around
    /// the ego), optionally selected with `objects`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per_object: Option<ObjectProperty>,
    /// Which road users a `per_object` check judges (a record property's
    /// only), or what a system's metric (`sut_*`) is summed over: those
    /// matching every criterion given. Default: all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objects: Option<RawObjectSelection>,
    /// The fewest samples a point needs for the check to judge it (≥ 1): the
    /// metric's population (cells, steps, messages, anticipation times…), the
    /// signal's defined steps in each run, the objects of a per-object check,
    /// or the fused cells of an invariant. Below it the requirement is not
    /// exercised at that point. Default 1; 6 for the medians
    /// (`anticipation_median`, `object_anticipation_median`) and 59 for the 95th
    /// percentiles (the smallest samples whose extremes bound the quantile with
    /// 95 % confidence).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_samples: Option<u64>,
}

/// Which relevant road users a per-object check judges.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(
    deny_unknown_fields,
    expecting = "an objects mapping with `ids`, `classes`, `areas`, `closer_than` or `between`"
)]
#[schemars(rename = "ObjectSelection")]
pub(crate) struct RawObjectSelection {
    /// Ids of declared or traced agents (generated road users are selected by
    /// class and area). Each of these lists, when given, is not empty.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ids: Vec<String>,
    /// Classes a road user of the scenario can have.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub classes: Vec<AgentKind>,
    /// Ids of crosswalks, interaction areas or `areas`: the road user's centre
    /// was inside one of them at some step with the ego in the scene.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<String>,
    /// [from, to], seconds, ending by the run's end: its closest approach
    /// to the ego lies in this window.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::TIME.schema())]
    pub between: Option<[f64; 2]>,
    /// Metres (> 0): its closest approach to the ego, between centres, came
    /// nearer than this.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::EXTENT.schema())]
    pub closer_than: Option<f64>,
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
