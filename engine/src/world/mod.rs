//! Traffic scenes (seed 000): agents moving along roads, sensors limited by range,
//! field of view and line of sight, self-localization, and the collective
//! perception grid fused across cooperating agents.

mod calibration;
mod evidence;
mod fan;
mod following;
mod fuse;
mod layer;
mod localization;
mod measure;
mod memo;
mod message;
mod metrics;
mod motion;
mod observe;
mod radio;
mod raster;
mod received;
mod sight;
mod simulate;
mod state;
mod traced;
mod truth;

pub use calibration::{Calibration, RELIABILITY_BINS, ReliabilityBin};
pub(crate) use layer::StepLayer;
pub use metrics::{
    CellTally, DISTANCE_BIN, DISTANCE_BINS, DistanceBin, FusedCell, RecallByDistance, Snapshot, WorldMetrics,
    WorldOutcome,
};
pub use motion::Kinematics;
pub use observe::{Observation, Observed, Sighting, Sightings, in_view, mount_pose};
pub use radio::RadioStats;
pub use sight::{Bodies, Body, Occluders, Outline, Visibility, visibility};
pub use simulate::run;
pub use state::{AgentState, Restraint};

/// The step's pieces, for the engine's benches (feature `internals`).
#[cfg(feature = "internals")]
pub use {
    evidence::Evidence,
    fan::{View, view},
    fuse::CellFusion,
    observe::StepScene,
    raster::Raster,
};

pub(crate) use following::following_idealisations;
pub(crate) use localization::{filter_idealisations as localization_idealisations, odometry_idealisations};
pub(crate) use motion::ON_THEIR_WAY;
pub(crate) use sight::{ONE_RAY, OUTLINES, PLANAR, RSU_TRANSPARENT};
pub(crate) use simulate::SYNCHRONOUS;
pub(crate) use simulate::idealisations;
