//! sightline's simulation engine: sampling, fusion and metrics.
//!
//! The engine owns everything between a compiled [`Scenario`](sightline_dsl::Scenario)
//! and its measurements: seeded random streams, the fusion rules (Dempster,
//! distance-weighted, hybrid, Bayesian), the decision rule, the V2X radio channel, and
//! the metrics of each sweep point. It returns data ([`Run`], [`FieldOutcome`]); it
//! does not print, write files or judge requirements (that is `sightline-oracles`).
//!
//! Results are deterministic: the same scenario and seed give bit-identical
//! outcomes whatever the number of rayon threads.
//!
//! ```
//! use sightline_engine::fusion::{combine, Mass};
//!
//! let fused = combine(Mass::new(0.6, 0.3, 0.1), Mass::new(0.5, 0.2, 0.3));
//! assert!((fused.conflict - 0.27).abs() < 1e-12);
//! assert!(fused.mass.is_mass_function(1e-12));
//! ```
#![warn(missing_docs)]

pub use metrics::{BandMetrics, ConflictMetrics, Coverage, FieldMetrics, FieldOutcome, MassAudit};
pub use run::{Job, Outcome, Run, simulate};

pub mod field;
pub mod fusion;
pub mod math;
mod metrics;
mod rng;
mod run;
pub mod semantic;
pub mod v2x;
pub mod world;
