//! The per-object record of a system under test in results.json: every road
//! user around the perception world's ego with when the system's served
//! sensors first had it in sight, when the system first detected it, when the
//! ego first saw it, its closest approach and the `sut_*` properties (the
//! engine's `system_objects` defines each).

use serde::Serialize;

use super::ClosestApproach;

/// What a point's system under test showed of each road user.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SystemDetail {
    /// Every road user in the scene with the ego at some step, other than
    /// the ego, the system's host and the roadside units.
    pub objects: SystemObjectList,
}

/// The road users a system under test is judged on, one by one.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SystemObjectList {
    /// Road users listed, in agent order (the n of a per-object check
    /// without a selection).
    pub listed: u64,
    /// The first 1000 records (`MAX_OBJECT_RECORDS`).
    pub records: Vec<SystemObjectResult>,
    /// Records past the first 1000, left out.
    pub omitted: u64,
}

/// One road user around the ego. Times are seconds from the start of the
/// run; `null`: it never happened.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SystemObjectResult {
    /// Its agent id.
    pub id: String,
    /// Its kind (`car`, `truck`, `bus`, `motorbike`, `pedestrian`).
    pub class: &'static str,
    /// When a sensor serving the system first had it in sight (in range and
    /// field of view, visible fraction above 0).
    pub first_in_sight: Option<f64>,
    /// When a judged detection of the system first matched it.
    pub first_detected: Option<f64>,
    /// When one of the ego's own sensors first had it in sight.
    pub first_seen_by_ego: Option<f64>,
    /// Its closest approach to the ego.
    pub closest: ClosestApproach,
    /// `sut_lead`: closest approach − first detected (`null`: never detected).
    pub lead: Option<f64>,
    /// `sut_anticipation`: first seen by the ego (or, never seen, closest
    /// approach) − first detected, at least 0 (`null`: never detected).
    pub anticipation: Option<f64>,
    /// `sut_delay`: first detected − first in sight, at least 0 (`null`:
    /// never detected, or never in sight).
    pub delay: Option<f64>,
    /// The ids of the crosswalks, interaction areas and declared `areas` its
    /// centre was in with the ego in the scene (left out: none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<String>,
}
