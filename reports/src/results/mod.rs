//! results.json: the versioned wire format of a run's evidence, owned here.
//!
//! Every type written into results.json is defined in this module tree, apart
//! from the engine's, the language's and the oracles' types, so that renaming a
//! field there cannot change the evidence silently: `from_run` is the one
//! place that maps them to these types, and `docs/results.schema.json` (the
//! JSON Schema of [`Results`], see [`results_schema`]) publishes the format
//! named by [`FORMAT`].
//!
//! - `document`: the whole file ([`Results`]), the scenario, its inputs and
//!   the requirement counts.
//! - `provenance`: where a run came from ([`Provenance`], [`Tool`], the
//!   [`RecordingInfo`]); how it ran is [`Execution`](crate::Execution).
//! - `requirement`: each requirement's verdict ([`Status`]) at its deciding
//!   point and at every point, and the check as written.
//! - `point` and `sweep`: every configuration simulated, with its labels,
//!   metrics and what only its kind of scenario measures ([`Detail`]), and the
//!   sweeps that reach them.
//! - `counts`: the counts behind the metrics (distance bands, coverage, the
//!   mass audit, a world's and a semantic run's counts).
//! - `objects`: a semantic point's per-object record ([`ObjectList`]), at most
//!   [`MAX_OBJECT_RECORDS`] listed.
//! - `metrics`: the top-level metrics (a value, or one table per sweep) and
//!   the insertion-ordered map ([`Ordered`]) they are written as.
//! - `reference`: published figures beside measured values, and the
//!   modelling assumptions.
//!
//! Everything but `execution` (platform, worker threads, start time and
//! duration) is deterministic: no output paths, nothing that depends on the
//! thread count, so the same scenario and seed give the same file but for those
//! fields.

pub use counts::{
    AgeCount, Band, Calibration, CloseApproach, Conflict, Coverage, DeliveryBin, DensityRow, DistanceRow, LabelCounts,
    MassAudit, Radio, ReliabilityBin, SemanticCounts, Sightings, WorldCounts,
};
pub use document::{FORMAT, InputInfo, Results, ScenarioInfo, Summary, WarningInfo};
pub(crate) use from_run::object_result;
pub(crate) use metrics::metric_unit;
pub use metrics::{Measured, MetricEntry, Ordered, Table};
pub use objects::{CategoryCounts, ClosestApproach, MAX_OBJECT_RECORDS, ObjectCategory, ObjectList, ObjectResult};
pub use point::{Detail, LabelResult, PointResult, SemanticDetail};
pub use provenance::{OsiTraceInfo, Provenance, RecordingInfo, Tool};
pub use reference::{Assumption, ReferencePoint, ReferenceResult};
pub use requirement::{
    CheckInfo, OverSeeds, PointVerdict, RateBound, RequirementResult, SeedStatistics, Statistic, Status,
};
pub use schema::results_schema;
pub use sweep::{Axis, Sweep, SweepRow};
pub use system::{SystemDetail, SystemObjectList, SystemObjectResult};

mod counts;
mod document;
mod from_run;
mod metrics;
mod objects;
mod point;
mod provenance;
mod reference;
mod requirement;
mod schema;
mod sweep;
mod system;
