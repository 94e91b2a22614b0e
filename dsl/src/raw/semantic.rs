//! The sections of seed 002's infrastructure-assisted ego: generated traffic,
//! crosswalks and interaction areas, driving behaviour, the V2X link and the
//! roadside unit's semantic pipeline.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::RawRegion;
use crate::model::{Following, PathLossModel, RiskScope, RsuSight, ShareCycles};

/// Background traffic generated on declared routes and crosswalks, deterministic
/// for the scenario's seed.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a traffic mapping")]
#[schemars(rename = "Traffic")]
pub(crate) struct RawTraffic {
    /// Vehicles on routes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vehicles: Option<RawVehicleTraffic>,
    /// Pedestrians crossing at every crosswalk.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pedestrians: Option<RawPedestrianTraffic>,
}

/// Vehicles generated on routes.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(
    deny_unknown_fields,
    expecting = "a vehicle traffic mapping with `density_per_km` and `routes`"
)]
#[schemars(rename = "VehicleTraffic")]
pub(crate) struct RawVehicleTraffic {
    /// Mean number of vehicles per km of each route, kept by inflow at its start.
    pub density_per_km: f64,
    /// The routes traffic drives, each a list of road ids like an agent's `route`.
    pub routes: Vec<Vec<String>>,
    /// Share of drivers who ignore speed limits (0–1); seed 002 uses 0.4.
    #[serde(default)]
    pub non_compliant: f64,
    /// How much faster than the limit a non-compliant driver wants to go: its
    /// limit factor is drawn uniformly from this range [low, high].
    #[serde(default = "default_overspeed")]
    pub overspeed_factor: [f64; 2],
    /// Share of each kind among generated vehicles; need not sum to 1.
    #[serde(default)]
    pub mix: RawMix,
}

fn default_overspeed() -> [f64; 2] {
    [1.2, 1.5]
}

/// Relative frequencies of vehicle kinds.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a mix mapping")]
#[schemars(rename = "Mix")]
pub(crate) struct RawMix {
    /// Passenger cars.
    #[serde(default)]
    pub car: f64,
    /// Trucks.
    #[serde(default)]
    pub truck: f64,
    /// Buses.
    #[serde(default)]
    pub bus: f64,
    /// Motorbikes.
    #[serde(default)]
    pub motorbike: f64,
}

// Only for an absent `mix`: a key left out of a written `mix` is 0, not its
// share here, so this struct takes no container `#[serde(default)]`.
impl Default for RawMix {
    fn default() -> Self {
        Self {
            car: 1.0,
            truck: 0.0,
            bus: 0.0,
            motorbike: 0.0,
        }
    }
}

/// Pedestrians crossing at crosswalks.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a pedestrian traffic mapping with `per_minute`")]
#[schemars(rename = "PedestrianTraffic")]
pub(crate) struct RawPedestrianTraffic {
    /// Mean arrivals per minute at each crosswalk (a Poisson process).
    pub per_minute: f64,
    /// Walking speed, m/s.
    #[serde(default = "default_walking_speed")]
    pub speed: f64,
    /// How far before the crosswalk a pedestrian appears on the pavement, metres.
    #[serde(default = "default_approach")]
    pub approach: f64,
}

fn default_walking_speed() -> f64 {
    1.3
}

fn default_approach() -> f64 {
    5.0
}

/// A pedestrian crossing: a straight walk from one kerb to the other.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a crosswalk mapping with `id`, `from` and `to`")]
#[schemars(rename = "Crosswalk")]
pub(crate) struct RawCrosswalk {
    /// Unique id.
    pub id: String,
    /// One kerb [x, y], metres.
    pub from: [f64; 2],
    /// The other kerb [x, y], metres.
    pub to: [f64; 2],
    /// Width across the walking direction, metres.
    #[serde(default = "default_crosswalk_width")]
    pub width: f64,
}

fn default_crosswalk_width() -> f64 {
    4.0
}

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
    pub polygon: Option<Vec<[f64; 2]>>,
    /// A disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub circle: Option<RawRegion>,
}

/// How vehicles keep their distance.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a driving mapping")]
#[schemars(rename = "Driving")]
pub(crate) struct RawDriving {
    /// `none`: vehicles ignore each other; `idm`: the Intelligent Driver Model
    /// behind the closest vehicle ahead in the lane.
    pub following: Following,
    /// IDM desired time headway, seconds.
    pub headway: f64,
    /// IDM gap kept when standing, metres.
    pub min_gap: f64,
    /// IDM comfortable deceleration, m/s².
    pub deceleration: f64,
}

impl Default for RawDriving {
    fn default() -> Self {
        Self {
            following: Following::default(),
            headway: 1.5,
            min_gap: 2.0,
            deceleration: 3.0,
        }
    }
}

/// V2X assumptions.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a v2x mapping")]
#[schemars(rename = "V2x")]
pub(crate) struct RawV2x {
    /// Share of generated vehicles that are connected (0–1); seed 002 uses 0.
    pub penetration: f64,
    /// Delay from sending to delivery, seconds, besides propagation.
    pub latency: f64,
    /// The radio channel.
    pub channel: RawChannel,
}

/// The radio channel (defaults: seed 002 and 3GPP TR 36.885).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a channel mapping")]
#[schemars(rename = "Channel")]
pub(crate) struct RawChannel {
    /// Path-loss model.
    pub model: PathLossModel,
    /// Transmit power, dBm.
    pub tx_power_dbm: f64,
    /// σ of the log-normal shadowing on a line-of-sight link, dB.
    pub shadowing_sigma_db: f64,
    /// σ of the shadowing on a link an occluder blocks, dB.
    pub nlos_shadowing_sigma_db: f64,
    /// Fixed implementation losses, dB.
    pub device_loss_db: f64,
    /// Receiver sensitivity, dBm.
    pub sensitivity_dbm: f64,
    /// Carrier frequency, GHz.
    pub carrier_ghz: f64,
    /// Antenna height of vehicles and pedestrians, metres.
    pub vehicle_antenna_m: f64,
    /// Antenna height of roadside units, metres.
    pub rsu_antenna_m: f64,
}

impl Default for RawChannel {
    /// The model's defaults, kept in one place (`model::Channel`).
    fn default() -> Self {
        let channel = crate::model::Channel::default();
        Self {
            model: channel.model,
            tx_power_dbm: channel.tx_power_dbm,
            shadowing_sigma_db: channel.shadowing_sigma_db,
            nlos_shadowing_sigma_db: channel.nlos_shadowing_sigma_db,
            device_loss_db: channel.device_loss_db,
            sensitivity_dbm: channel.sensitivity_dbm,
            carrier_ghz: channel.carrier_ghz,
            vehicle_antenna_m: channel.vehicle_antenna_m,
            rsu_antenna_m: channel.rsu_antenna_m,
        }
    }
}

/// The roadside units' semantic pipeline (seed 002, section III).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a semantic mapping with `ego`")]
#[schemars(rename = "Semantic")]
pub(crate) struct RawSemantic {
    /// Id of the assisted vehicle (connected, with sensors).
    pub ego: String,
    /// Ids of the roadside units that assist it. Default: every RSU with sensors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rsus: Option<Vec<String>>,
    /// Proximity filter: objects farther from the ego are not sent, metres.
    #[serde(default = "default_proximity")]
    pub proximity: f64,
    /// Prediction horizon T_p, seconds.
    #[serde(default = "default_horizon")]
    pub horizon: f64,
    /// Conflict distance d_min between predicted centres, metres.
    #[serde(default = "default_d_min")]
    pub d_min: f64,
    /// Dangerous-driver classification.
    #[serde(default)]
    pub overspeed: RawOverspeed,
    /// Speed hypotheses of a compliant vehicle, as factors of its measured speed.
    #[serde(default = "default_hypotheses")]
    pub hypotheses: Vec<f64>,
    /// How often each RSU runs the pipeline and sends its message, Hz; the
    /// simulation step must divide its period.
    #[serde(default = "default_rate")]
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
    /// Independent runs pooled into each point's measurements (traffic, detections
    /// and packet losses drawn anew; run 0 uses the scenario's seed).
    #[serde(default = "default_runs")]
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
    pub window: f64,
    /// Threshold δ_min on the mean violation, m/s.
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
    pub headway: f64,
    /// Share of its desired speed the ego keeps while cautious (0–1).
    pub speed_factor: f64,
    /// How long the ego stays cautious after the last flagged conflict, seconds.
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
    pub distance: f64,
    /// … or whose speed changed by more than this, m/s.
    pub speed: f64,
    /// … or whose heading changed by more than this, degrees.
    pub heading_deg: f64,
    /// … or that was last sent at least this long ago, seconds.
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
