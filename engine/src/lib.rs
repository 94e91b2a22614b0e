//! sightline's simulation engine: sampling, fusion and metrics.
//!
//! The engine owns everything between a compiled [`Scenario`](sightline_dsl::Scenario)
//! and its measurements: seeded random streams, the fusion rules (Dempster,
//! distance-weighted, hybrid, Bayesian), the decision rule, the V2X radio channel, and
//! the metrics of each sweep point. It does not print, write files or judge
//! requirements (that is `sightline-oracles`).
//!
//! Its interface is closed: a compiled scenario goes in, and out come
//!
//! - outcomes: a [`Run`] of one [`Outcome`] per sweep point ([`simulate`]), made
//!   of the types in [`outcome`], each metric with its sample size ([`Sample`]);
//! - trace events: [`simulate_point`] hands a [`TraceSink`] a record of every step
//!   as it goes ([`trace`]): agent states, detections, packets, signals, and fused
//!   grids at the steps the sink asks for; [`simulate_traced`] runs every point
//!   and records one of them that way, [`simulate_traced_each`] each to its own
//!   sink. The engine keeps none of it, so memory
//!   stays bounded; the MCAP writer and the temporal oracles are sinks;
//! - the campaign split: [`units`] of work, [`simulate_unit`] and [`assemble`];
//! - what a run takes as given ([`idealisations`]) and the engine's
//!   [`known_answers`] for `sightline selftest`.
//!
//! The worlds (the field experiment, the perception world, the semantic world)
//! and the shared models (fusion, the radio channel, geometry) are private
//! modules; docs/architecture.md maps them.
//!
//! Every model states what it idealises, beside its code, as an
//! [`Idealisation`]; [`idealisations`] lists those a scenario's run assumed (its
//! kinds of model and the options it chooses), which the report prints under
//! "Assumptions and limitations".
//!
//! Results are deterministic: the same scenario and seed give bit-identical
//! outcomes and records whatever the number of rayon threads, and recording does
//! not change an outcome.
#![warn(missing_docs)]

pub use idealisation::{Idealisation, ModelOption, idealisations};
pub use known::{KnownAnswer, known_answers};
pub use recorded::simulate_recorded;
pub use run::{
    AssembleError, Job, Outcome, RoadUserValue, Run, Sample, Unit, assemble, shares_one_simulation, simulate,
    simulate_point, simulate_reporting, simulate_traced, simulate_traced_all, simulate_traced_each, simulate_unit,
    units,
};
pub use sink::{NoTrace, TraceSink};

pub mod outcome;
pub mod trace;

mod elementary;
mod field;
mod fusion;
mod idealisation;
mod known;
mod math;
mod metrics;
#[cfg(test)]
mod pinned;
mod recorded;
mod rng;
mod run;
mod semantic;
mod sink;
mod system;
mod system_objects;
mod v2x;
mod world;

/// The engine's components, for its own tests and benches only: not part of
/// its interface, and nothing outside `engine/` may enable the `internals`
/// feature.
#[cfg(feature = "internals")]
#[doc(hidden)]
pub mod internals {
    pub use crate::semantic::{Areas, EgoPlan, Ldm, Measurement, Pipeline, route_map, run as run_semantic};
    pub use crate::world::{
        Bodies, CellFusion, Evidence, Kinematics, Observation, Occluders, Raster, StepScene, View, Visibility, in_view,
        view, visibility,
    };
}
