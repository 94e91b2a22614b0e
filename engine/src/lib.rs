//! sightline's simulation engine: sampling, fusion and metrics.
//!
//! The engine owns everything between a compiled [`Scenario`](sightline_dsl::Scenario)
//! and its measurements: seeded random streams, the fusion rules (Dempster,
//! distance-weighted, hybrid, Bayesian), the decision rule, the V2X radio channel, and
//! the metrics of each sweep point. It returns data ([`Run`], [`FieldOutcome`]); it
//! does not print, write files or judge requirements (that is `sightline-oracles`).
//!
//! [`simulate_point`] runs one sweep point and hands a [`TraceSink`] a record of
//! every step as it goes ([`trace`]): agent states, detections, packets, signals,
//! and fused grids at the steps the sink asks for; [`simulate_traced`] runs every
//! point and records one of them that way. The engine keeps none of it, so
//! memory stays bounded; the MCAP writer and the temporal oracles are sinks.
//!
//! Every model states what it idealises, beside its code, as an
//! [`Idealisation`]; [`idealisations`] lists those a scenario's run assumed (its
//! kinds of model and the options it chooses), which the report prints under
//! "Assumptions and limitations".
//!
//! Results are deterministic: the same scenario and seed give bit-identical
//! outcomes and records whatever the number of rayon threads, and recording does
//! not change an outcome.
//!
//! ```
//! use sightline_engine::fusion::{combine, Mass};
//!
//! let fused = combine(Mass::new(0.6, 0.3, 0.1), Mass::new(0.5, 0.2, 0.3));
//! assert!((fused.conflict - 0.27).abs() < 1e-12);
//! assert!(fused.mass.is_mass_function(1e-12));
//! ```
#![warn(missing_docs)]

pub use idealisation::{Idealisation, ModelOption, idealisations};
pub use metrics::{BandMetrics, ConflictMetrics, Coverage, FieldMetrics, FieldOutcome, MassAudit};
pub use run::{
    AssembleError, Job, Outcome, Run, Sample, Unit, assemble, simulate, simulate_point, simulate_reporting,
    simulate_traced, simulate_unit, units,
};
pub use sink::{NoTrace, TraceSink};

pub mod field;
pub mod fusion;
mod idealisation;
pub mod math;
mod metrics;
mod rng;
mod run;
pub mod semantic;
mod sink;
pub mod trace;
pub mod v2x;
pub mod world;
