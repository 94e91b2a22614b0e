//! The V2X link between connected agents and roadside units: who is connected,
//! how often and how late messages go, and the radio channel that drops them.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// V2X assumptions of a world.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct V2x {
    /// Share of generated traffic that is connected (0–1).
    pub penetration: f64,
    /// Time from sending to delivery of a received packet, seconds (processing and
    /// access delay; propagation at the speed of light is added per packet).
    pub latency: f64,
    /// The radio channel.
    pub channel: Channel,
}

/// Bytes of a message besides its cells: the ITS PDU header, management
/// container and station data (121 bytes), and one sensor information
/// container per sensor (35 bytes each), as ETSI TR 103 562 (Table 3) measures
/// the mandatory fields of a CPM.
pub const MESSAGE_HEADER_BYTES: u32 = 121;
/// Bytes of one sensor information container (ETSI TR 103 562, Table 3).
pub const SENSOR_INFORMATION_BYTES: u32 = 35;
/// Bytes of the smallest grid payload: one row (3 bytes) holding one run (4 bytes).
pub const SMALLEST_PAYLOAD_BYTES: u32 = 7;

/// The messages cooperating agents send the ego in a collective-perception
/// world that declares `v2x`: how often, how large, and how long what arrives
/// stays evidence.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Messages {
    /// Messages each cooperating agent generates per second (a fixed rate; the
    /// first at its first step in the scene).
    pub rate_hz: f64,
    /// Largest message, bytes (the CPM size limit, ETSI TS 103 324 MTU_CPM).
    pub max_bytes: u32,
    /// What a grid that does not fit in one message becomes.
    pub oversize: Oversize,
    /// Received evidence older than this is dropped, seconds since it was sensed.
    pub max_age: f64,
    /// Time constant of the decay of received evidence toward unknown, seconds;
    /// `None`: evidence keeps its weight until `max_age`.
    pub decay: Option<f64>,
}

impl Default for Messages {
    /// 10 Hz (TS 103 324's shortest vehicle interval, T_GenCpmMin = 100 ms),
    /// 1100 bytes (the segmentation threshold of ETSI TR 103 562's simulations),
    /// split, dropped after 1 s (ours: T_GenCpmMax), no decay.
    fn default() -> Self {
        Self {
            rate_hz: 10.0,
            max_bytes: 1100,
            oversize: Oversize::Split,
            max_age: 1.0,
            decay: None,
        }
    }
}

/// What a sender does with a grid larger than one message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Oversize {
    /// Sends it in as many messages as it needs, rows in order, each on its own
    /// over the channel.
    Split,
    /// Sends one message: the runs of cells in order of priority (its own
    /// footprint, occupied cells, then free cells nearest the sender first),
    /// as many as fit; the rest is not sent.
    Select,
}

/// Path-loss models of 3GPP TR 36.885 (V14.0.0), Annex A.1.4, and of TR 37.885
/// (NR V2X, V15), Table 6.2.1-1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PathLossModel {
    /// Urban case: WINNER+ B1 (Manhattan grid) for LOS; NLOS where an occluder
    /// blocks the direct link.
    Tr36885Urban,
    /// Freeway case: LOS only (PL = 32.4 + 20 log10 d + 20 log10 fc). TR 37.885's
    /// highway line is the same.
    Tr36885Highway,
    /// NR V2X urban grid (TR 37.885, V2V): LOS PL = 38.77 + 16.7 log10 d +
    /// 18.2 log10 fc; NLOS (an occluder blocks the link) PL = 36.85 + 30 log10 d
    /// + 18.9 log10 fc.
    Tr37885Urban,
    /// Every packet arrives (no path loss, no shadowing).
    Ideal,
}

/// The radio channel of every V2X link: received power
/// RSSI = P_tx − L_path(d) − L_shadow − L_device; a packet is received when
/// RSSI ≥ the receiver's sensitivity (seed 002, eq. 4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Channel {
    /// Path-loss model.
    pub model: PathLossModel,
    /// Transmit power P_tx, dBm.
    pub tx_power_dbm: f64,
    /// σ of the zero-mean log-normal shadowing on a line-of-sight link, dB.
    pub shadowing_sigma_db: f64,
    /// σ of the shadowing on a non-line-of-sight link, dB.
    pub nlos_shadowing_sigma_db: f64,
    /// Fixed implementation losses L_device, dB.
    pub device_loss_db: f64,
    /// Receiver sensitivity RSSI_TH, dBm.
    pub sensitivity_dbm: f64,
    /// Carrier frequency, GHz.
    pub carrier_ghz: f64,
    /// Antenna height of vehicles and pedestrians, metres.
    pub vehicle_antenna_m: f64,
    /// Antenna height of roadside units, metres.
    pub rsu_antenna_m: f64,
}

impl Default for Channel {
    /// Seed 002's values: 23 dBm, σ = 3 dB, 3 dB device loss, −90 dBm sensitivity,
    /// 5.9 GHz, urban model; TR 36.885's 4 dB NLOS shadowing and 1.5 m antennas,
    /// and a 5 m roadside unit mast.
    fn default() -> Self {
        Self {
            model: PathLossModel::Tr36885Urban,
            tx_power_dbm: 23.0,
            shadowing_sigma_db: 3.0,
            nlos_shadowing_sigma_db: 4.0,
            device_loss_db: 3.0,
            sensitivity_dbm: -90.0,
            carrier_ghz: 5.9,
            vehicle_antenna_m: 1.5,
            rsu_antenna_m: 5.0,
        }
    }
}
