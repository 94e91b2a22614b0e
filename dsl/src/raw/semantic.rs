//! The roadside units' semantic pipeline for an assisted ego (seed 002): the
//! interaction areas it watches, its layers' settings, the ego's caution and the
//! ETSI baseline it is compared with.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::perception::RawRegion;
use super::range;
use crate::model::{LabelledBy, RiskScope, RsuSight, ShareCycles};

/// A region around a conflict zone (junction, roundabout entry, crossing).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(
    deny_unknown_fields,
    expecting = "an interaction area mapping with `id` and a `polygon` or `circle`"
)]
#[schemars(rename = "InteractionArea")]
pub(crate) struct RawInteractionArea {
    /// Unique id.
    pub id: String,
    /// Outline [[x, y], …], metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::COORDINATE.schema())]
    pub polygon: Option<Vec<[f64; 2]>>,
    /// A disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub circle: Option<RawRegion>,
}

/// The roadside units' semantic pipeline (seed 002, section III).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a semantic mapping with `ego`")]
#[schemars(rename = "Semantic")]
pub(crate) struct RawSemantic {
    /// Id of the assisted vehicle (connected, with sensors).
    pub ego: String,
    /// Ids of the roadside units that assist it, each once. Default: every RSU
    /// with sensors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rsus: Option<Vec<String>>,
    /// Proximity filter: objects farther from the ego are not sent, metres.
    #[serde(default = "default_proximity")]
    #[schemars(transform = range::EXTENT.schema())]
    pub proximity: f64,
    /// Prediction horizon T_p, seconds: at least one step. Also how far ahead
    /// the relevance layer looks for a path entering an area.
    #[serde(default = "default_horizon")]
    #[schemars(transform = range::REACTION.schema())]
    pub horizon: f64,
    /// Conflict distance d_min between predicted centres, metres.
    #[serde(default = "default_d_min")]
    #[schemars(transform = range::BODY.schema())]
    pub d_min: f64,
    /// Dangerous-driver classification.
    #[serde(default)]
    pub overspeed: RawOverspeed,
    /// Speed hypotheses of a compliant vehicle, as factors of its measured speed.
    #[serde(default = "default_hypotheses")]
    #[schemars(transform = range::SPEED_FACTOR.schema())]
    pub hypotheses: Vec<f64>,
    /// How often each RSU runs the pipeline and sends its message, Hz; the
    /// simulation step must divide its period.
    #[serde(default = "default_rate")]
    #[schemars(transform = range::RATE.schema())]
    pub rate: f64,
    /// Which objects the risk layer predicts: `relevant` (those the interaction
    /// layer labelled, as seed 002 writes) or `all` proximate vehicles and crossing
    /// pedestrians.
    #[serde(default)]
    pub risk_for: RiskScope,
    /// What an RSU perceives: `range` (everything within its sensors' range, as
    /// seed 002's circular region) or `line_of_sight` (its sensors' field of view
    /// and occlusion, like a vehicle's).
    #[serde(default)]
    pub rsu_sight: RsuSight,
    /// How long the LDM keeps an object's history, seconds (at least the overspeed
    /// window).
    #[serde(default = "default_history")]
    #[schemars(transform = range::SPAN.schema())]
    pub history: f64,
    /// How the ego reacts to a flagged conflict.
    #[serde(default)]
    pub caution: RawCaution,
    /// The ETSI collective perception baseline the semantic selection is compared with.
    #[serde(default)]
    pub baseline: RawBaseline,
    /// Which RSU cycles the transmitted and labelled shares count: `ego_in_range`
    /// (the ego within range of one of the RSU's sensors) or `all`.
    #[serde(default)]
    pub shares_over: ShareCycles,
    /// Which labels make an object labelled for the labelled share: `any`
    /// (ours: the NLoS flag too) or `critical` (relevance, speeding or a
    /// predicted conflict).
    #[serde(default)]
    pub labelled_by: LabelledBy,
    /// Which steps the infrastructure contribution (objects the ego knows only
    /// through an RSU) counts: `ego_in_range` (the ego within range of one of
    /// an RSU's sensors: seed 002's ego, always served) or `all`.
    #[serde(default)]
    pub contribution_over: ShareCycles,
    /// Independent runs pooled into each point's measurements (traffic, detections
    /// and packet losses drawn anew; run 0 uses the scenario's seed).
    #[serde(default = "default_runs")]
    #[schemars(transform = range::RUNS.schema())]
    pub runs: u32,
}

fn default_proximity() -> f64 {
    50.0
}

fn default_horizon() -> f64 {
    3.0
}

fn default_d_min() -> f64 {
    2.0
}

fn default_hypotheses() -> Vec<f64> {
    vec![0.7, 1.0, 1.1]
}

fn default_rate() -> f64 {
    10.0
}

fn default_history() -> f64 {
    5.0
}

fn default_runs() -> u32 {
    1
}

/// The dangerous-driver window (seed 002, eq. 2).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "an overspeed mapping")]
#[schemars(rename = "Overspeed")]
pub(crate) struct RawOverspeed {
    /// Window T_w, seconds.
    #[schemars(transform = range::SPAN.schema())]
    pub window: f64,
    /// Threshold δ_min on the mean violation, m/s.
    #[schemars(transform = range::SPEED.schema())]
    pub threshold: f64,
}

impl Default for RawOverspeed {
    fn default() -> Self {
        Self {
            window: 5.0,
            threshold: 2.0,
        }
    }
}

/// The ego's reaction to an emergency.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a caution mapping")]
#[schemars(rename = "Caution")]
pub(crate) struct RawCaution {
    /// Time headway the ego keeps while cautious, seconds (with `driving.following: idm`).
    #[schemars(transform = range::REACTION.schema())]
    pub headway: f64,
    /// Share of its desired speed the ego keeps while cautious (0–1).
    #[schemars(transform = range::PROBABILITY_POSITIVE.schema())]
    pub speed_factor: f64,
    /// How long the ego stays cautious after the last flagged conflict, seconds.
    #[schemars(transform = range::TIME.schema())]
    pub hold: f64,
}

impl Default for RawCaution {
    fn default() -> Self {
        Self {
            headway: 2.5,
            speed_factor: 0.8,
            hold: 3.0,
        }
    }
}

/// ETSI TS 103 324 object inclusion rules for the baseline sender.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a baseline mapping")]
#[schemars(rename = "Baseline")]
pub(crate) struct RawBaseline {
    /// Include an object that moved more than this since it was last sent, metres.
    #[schemars(transform = range::EXTENT.schema())]
    pub distance: f64,
    /// … or whose speed changed by more than this, m/s.
    #[schemars(transform = range::SPEED_POSITIVE.schema())]
    pub speed: f64,
    /// … or whose heading changed by more than this, degrees.
    #[schemars(transform = range::HEADING_CHANGE.schema())]
    pub heading_deg: f64,
    /// … or that was last sent at least this long ago, seconds.
    #[schemars(transform = range::SPAN.schema())]
    pub interval: f64,
}

impl Default for RawBaseline {
    fn default() -> Self {
        Self {
            distance: 4.0,
            speed: 0.5,
            heading_deg: 4.0,
            interval: 1.0,
        }
    }
}
