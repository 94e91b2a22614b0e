//! Seed 002's road users beyond the declared agents: background traffic
//! generated on routes and crosswalks, the crossings, and how vehicles keep
//! their distance.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;
use crate::model::Following;

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
    #[schemars(transform = range::DENSITY.schema())]
    pub density_per_km: f64,
    /// The routes traffic drives, each a list of road ids like an agent's `route`.
    #[schemars(inner(length(max = crate::compile::MAX_ROUTE_ROADS)))]
    pub routes: Vec<Vec<String>>,
    /// Share of drivers who ignore speed limits (0–1); seed 002 uses 0.4.
    #[serde(default)]
    #[schemars(transform = range::PROBABILITY.schema())]
    pub non_compliant: f64,
    /// How much faster than the limit a non-compliant driver wants to go: its
    /// limit factor is drawn uniformly from this range [low, high].
    #[serde(default = "default_overspeed")]
    #[schemars(transform = range::OVERSPEED_FACTOR.schema())]
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
    #[schemars(transform = range::SHARE.schema())]
    pub car: f64,
    /// Trucks.
    #[serde(default)]
    #[schemars(transform = range::SHARE.schema())]
    pub truck: f64,
    /// Buses.
    #[serde(default)]
    #[schemars(transform = range::SHARE.schema())]
    pub bus: f64,
    /// Motorbikes.
    #[serde(default)]
    #[schemars(transform = range::SHARE.schema())]
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
    #[schemars(transform = range::ARRIVALS.schema())]
    pub per_minute: f64,
    /// Walking speed, m/s.
    #[serde(default = "default_walking_speed")]
    #[schemars(transform = range::SPEED_POSITIVE.schema())]
    pub speed: f64,
    /// How far before the crosswalk a pedestrian appears on the pavement, metres.
    #[serde(default = "default_approach")]
    #[schemars(transform = range::GAP.schema())]
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
    #[schemars(transform = range::COORDINATE.schema())]
    pub from: [f64; 2],
    /// The other kerb [x, y], metres.
    #[schemars(transform = range::COORDINATE.schema())]
    pub to: [f64; 2],
    /// Width across the walking direction, metres.
    #[serde(default = "default_crosswalk_width")]
    #[schemars(transform = range::BODY.schema())]
    pub width: f64,
}

fn default_crosswalk_width() -> f64 {
    4.0
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
    #[schemars(transform = range::REACTION.schema())]
    pub headway: f64,
    /// IDM gap kept when standing, metres.
    #[schemars(transform = range::GAP.schema())]
    pub min_gap: f64,
    /// IDM comfortable deceleration, m/s².
    #[schemars(transform = range::ACCELERATION.schema())]
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
