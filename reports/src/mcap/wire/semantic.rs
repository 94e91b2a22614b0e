//! A semantic world's own channels in a recording: its packets, semantic
//! messages, arrivals, close approaches and road users.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// `/v2x/packets` (one message per packet, at the step it is sent).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Packet")]
pub struct PacketRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step.
    pub step: usize,
    /// The sending agent's id.
    pub from: String,
    /// The receiving agent's id.
    pub to: String,
    /// `uplink` (the ego's state to an RSU), `downlink` (an RSU's semantic
    /// message to the ego) or `direct` (a connected road user's state to the ego).
    pub kind: String,
    /// A downlink's size on the channel, bytes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bytes: Option<u64>,
    /// Distance between the antennas, metres.
    pub distance_m: f64,
    /// Whether the direct path is free of buildings.
    pub los: bool,
    /// Received power, dBm (left out when not finite).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rssi_dbm: Option<f64>,
    /// Whether it reached the receiver's sensitivity.
    pub received: bool,
}

/// `/semantic/messages` (one per semantic message an RSU sends the ego, at
/// the step it is sent).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.SemanticMessage")]
pub struct MessageRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step.
    pub step: usize,
    /// The sending RSU's id.
    pub from: String,
    /// Whether the ego received it.
    pub received: bool,
    /// Its size on the channel, bytes.
    pub bytes: u64,
    /// The objects it names, with their labels.
    pub items: Vec<ItemRecord>,
}

/// `/semantic/arrivals` (one per semantic message reaching the ego, at the time
/// it arrives).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Arrival")]
pub struct ArrivalRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// When it arrived, seconds.
    pub at: f64,
    /// The objects it names, with their labels.
    pub items: Vec<ItemRecord>,
}

/// An object of a semantic message and its labels.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ItemRecord {
    /// The object's agent id.
    pub agent: String,
    /// Occluded from the ego: `static` (by a building) or `dynamic` (by road
    /// users only); left out in line of sight.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nlos: Option<String>,
    /// Interaction relevance.
    pub relevant: bool,
    /// A dangerous driver (speed violation).
    pub speeding: bool,
    /// A predicted conflict with the ego's plan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conflict: Option<ConflictRecord>,
}

/// A predicted conflict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ConflictRecord {
    /// Time until the centres first come within d_min, seconds.
    pub time: f64,
    /// Smallest predicted distance between the centres, metres.
    pub separation: f64,
}

/// `/semantic/approaches` (one per object coming within d_min of the ego).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Approach")]
pub struct ApproachRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step.
    pub step: usize,
    /// The object's agent id.
    pub agent: String,
    /// Whether a conflict with it had reached the ego before: `false` is a
    /// missed critical.
    pub flagged: bool,
}

/// `/semantic/objects` (after the last step, one per relevant road user of
/// each semantic point, at most `MAX_OBJECT_RECORDS` per point): its record as
/// results.json lists it, flat. Times are seconds; left out: never happened.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Object")]
pub struct RoadUserRecord {
    /// The point's index.
    pub point: usize,
    /// The pooled run.
    pub run: u32,
    /// The road user's agent id.
    pub id: String,
    /// Its kind.
    pub class: String,
    /// Its length, metres.
    pub length: f64,
    /// Its width, metres.
    pub width: f64,
    /// When it became relevant.
    pub first_relevant: f64,
    /// When the ego first saw it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_seen: Option<f64>,
    /// When the first V2X message naming it reached the ego.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_v2x: Option<f64>,
    /// When the first message flagging a conflict with it reached the ego.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_warning: Option<f64>,
    /// In a joint world, when a cell of its footprint was first decided
    /// occupied in the ego's fused grid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_in_grid: Option<f64>,
    /// When it came closest to the ego.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closest_time: Option<f64>,
    /// How close, between the centres, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closest_distance: Option<f64>,
    /// Where it was then, x, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closest_x: Option<f64>,
    /// Where it was then, y, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closest_y: Option<f64>,
    /// Its least time to collision with the ego while within
    /// `semantic.proximity` of it, seconds (oriented boxes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_ttc: Option<f64>,
    /// Its greatest deceleration rate to avoid a crash then, m/s².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_drac: Option<f64>,
    /// Its post-encroachment time with the ego then, seconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pet: Option<f64>,
    /// `warned_before_seen`, `warned_never_seen`, `seen_first` or `never_known`.
    pub category: String,
    /// Our anticipation time, seconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anticipation: Option<f64>,
}
