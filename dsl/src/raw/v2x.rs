//! V2X assumptions: penetration, latency, the radio channel, and the messages
//! of collective perception.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::{Messages, Oversize, PathLossModel};

/// V2X assumptions.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a v2x mapping")]
#[schemars(rename = "V2x")]
pub(crate) struct RawV2x {
    /// Semantic worlds: share of generated and imported vehicles that are
    /// connected (0–1; default 0, as seed 002). Collective perception: share of
    /// the connected agents with sensors, besides the ego, that cooperate (the
    /// first in file order; default all), instead of `perception.cooperating`.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::PROBABILITY.schema())]
    pub penetration: Option<f64>,
    /// Delay from sending to delivery, seconds, besides propagation.
    #[schemars(transform = range::LATENCY.schema())]
    pub latency: f64,
    /// The radio channel.
    pub channel: RawChannel,
    /// Collective perception: the messages that carry the cooperating agents'
    /// grids to the ego.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub messages: Option<RawMessages>,
}

/// The messages of collective perception (defaults: `model::Messages`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a messages mapping")]
#[schemars(rename = "Messages")]
pub(crate) struct RawMessages {
    /// Messages each cooperating agent generates per second, Hz (ETSI TS 103 324
    /// allows 1 to 10 for a vehicle, up to 20 for a roadside unit).
    #[schemars(transform = range::MESSAGE_RATE.schema())]
    pub rate_hz: f64,
    /// Largest message, bytes (TS 103 324's MTU_CPM; default 1100, the
    /// segmentation threshold of ETSI TR 103 562's simulations).
    #[schemars(transform = range::MESSAGE_BYTES.schema())]
    pub max_bytes: u32,
    /// What a grid larger than one message becomes: `split` (several messages)
    /// or `select` (one message, the most important cells first).
    pub oversize: Oversize,
    /// Received evidence older than this (since it was sensed) is dropped,
    /// seconds; at least one step.
    #[schemars(transform = range::REACTION.schema())]
    pub max_age: f64,
    /// Time constant of the decay of received evidence toward unknown, seconds
    /// (its mass is discounted by exp(−age / decay)). Default: no decay.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::REACTION.schema())]
    pub decay: Option<f64>,
}

impl Default for RawMessages {
    /// The model's defaults, kept in one place (`model::Messages`).
    fn default() -> Self {
        let messages = Messages::default();
        Self {
            rate_hz: messages.rate_hz,
            max_bytes: messages.max_bytes,
            oversize: messages.oversize,
            max_age: messages.max_age,
            decay: messages.decay,
        }
    }
}

/// The radio channel (defaults: seed 002 and 3GPP TR 36.885).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a channel mapping")]
#[schemars(rename = "Channel")]
pub(crate) struct RawChannel {
    /// Path-loss model.
    pub model: PathLossModel,
    /// Transmit power, dBm.
    #[schemars(transform = range::POWER.schema())]
    pub tx_power_dbm: f64,
    /// σ of the log-normal shadowing on a line-of-sight link, dB.
    #[schemars(transform = range::DECIBELS.schema())]
    pub shadowing_sigma_db: f64,
    /// σ of the shadowing on a link an occluder blocks, dB.
    #[schemars(transform = range::DECIBELS.schema())]
    pub nlos_shadowing_sigma_db: f64,
    /// Fixed implementation losses, dB.
    #[schemars(transform = range::DECIBELS.schema())]
    pub device_loss_db: f64,
    /// Receiver sensitivity, dBm.
    #[schemars(transform = range::SENSITIVITY.schema())]
    pub sensitivity_dbm: f64,
    /// Carrier frequency, GHz.
    #[schemars(transform = range::CARRIER.schema())]
    pub carrier_ghz: f64,
    /// Antenna height of vehicles and pedestrians, metres.
    #[schemars(transform = range::ANTENNA.schema())]
    pub vehicle_antenna_m: f64,
    /// Antenna height of roadside units, metres.
    #[schemars(transform = range::ANTENNA.schema())]
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
