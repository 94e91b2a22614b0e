//! V2X assumptions: penetration, latency and the radio channel.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::PathLossModel;

/// V2X assumptions.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields, expecting = "a v2x mapping")]
#[schemars(rename = "V2x")]
pub(crate) struct RawV2x {
    /// Share of generated vehicles that are connected (0–1); seed 002 uses 0.
    #[schemars(transform = range::PROBABILITY.schema())]
    pub penetration: f64,
    /// Delay from sending to delivery, seconds, besides propagation.
    #[schemars(transform = range::LATENCY.schema())]
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
