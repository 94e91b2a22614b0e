//! Traffic scenes (seed 000): agents moving along roads, sensors limited by range,
//! field of view and line of sight, self-localization, and the collective
//! perception grid fused across cooperating agents.

mod fuse;
mod localization;
mod metrics;
mod motion;
mod observe;
mod raster;
mod sight;
mod simulate;

pub use metrics::{CellTally, FusedCell, Snapshot, WorldMetrics, WorldOutcome};
pub use motion::{AgentState, Kinematics, Restraint};
pub use observe::{Observation, Observed, Sighting, Sightings, in_view, mount_pose};
pub use sight::{Bodies, Body, Occluders, Visibility, visibility};
pub use simulate::run;

/// The step's pieces, for the engine's benches (feature `internals`).
#[cfg(feature = "internals")]
pub use {fuse::CellFusion, observe::StepScene, raster::Raster};

pub(crate) use localization::filter_idealisations as localization_idealisations;
pub(crate) use motion::{ON_THEIR_WAY, following_idealisations};
pub(crate) use sight::{ONE_RAY, PLANAR, RSU_TRANSPARENT};
pub(crate) use simulate::idealisations;
