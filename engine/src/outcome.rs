//! What a run measured: the outcome of each kind of world and the metric types
//! it is made of. These are the engine's results as data; results.json, the
//! report and the oracles read them, and the reports crate owns how they are
//! written down.
//!
//! - The field experiment (seed 001): [`FieldOutcome`], whole-grid
//!   [`FieldMetrics`], the same by distance band ([`BandMetrics`]), sensor
//!   [`Coverage`] and the [`MassAudit`] of every fused cell.
//! - A perception world (seed 000): [`WorldOutcome`], its [`WorldMetrics`]
//!   (summed from each step's [`CellTally`]), [`Sightings`] by visibility,
//!   recall by distance to the nearest sender ([`RecallByDistance`]), what
//!   went over the radio ([`RadioStats`]), and the grids of one step ([`Snapshot`] of [`FusedCell`]s with their decided
//!   [`State`]).
//! - A system under test in a perception world: its [`SystemMetrics`], summed
//!   by a [`SystemJudge`] from its [`Detection`]s at each step, with the
//!   record of every road user around the ego ([`SystemObject`]).
//! - A semantic world (seed 002): [`SemanticMetrics`] with its density rows
//!   ([`DensityRow`]), delivery bins ([`DeliveryBin`]), label counts
//!   ([`LabelCounts`]), per-step [`Series`], and the per-object
//!   [`ObjectRecord`]s with their [`Category`] and [`Closest`] approach, and
//!   every [`CloseApproach`].

pub use crate::fusion::State;
pub use crate::metrics::{
    BandMetrics, ConflictMetrics, Coverage, FieldMetrics, FieldOutcome, MassAudit, Series, quantile,
};
pub use crate::semantic::{
    Category, CloseApproach, Closest, DELIVERY_BIN, DENSITY_BIN, DeliveryBin, DensityRow, LabelCounts, ObjectRecord,
    SemanticMetrics,
};
pub use crate::system::{Detection, SystemJudge, SystemMetrics};
pub use crate::system_objects::SystemObject;
pub use crate::world::{
    Calibration, CellTally, DISTANCE_BIN, DISTANCE_BINS, DistanceBin, FusedCell, RELIABILITY_BINS, RadioStats,
    RecallByDistance, ReliabilityBin, Sightings, Snapshot, WorldMetrics, WorldOutcome,
};
