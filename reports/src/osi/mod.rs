//! ASAM OSI: sightline's world as OSI messages, and an OSI trace of a run.
//!
//! - `views`: one step of a world as `osi3.GroundTruth` (every road user and
//!   roadside unit in the scene) and, per sensor of each cooperating agent, as
//!   `osi3.SensorView`, which carries sightline's visibility result: each
//!   road user the sensor has in range and field of view is annotated with
//!   its visibility class and visible fraction (docs/osi.md says how);
//! - [`OsiTrace`]: a [`TraceSink`](sightline_engine::TraceSink) that writes
//!   those messages into an OSI multi-channel trace file (MCAP, as ASAM's trace
//!   file convention specifies), `sightline run --osi`'s `osi.mcap`.
//!
//! - `system`: the protocol that drives a system under test with those
//!   views and reads back its `osi3.SensorData` (docs/osi-sut.md), each
//!   detection's class read by `reported_class`.
//!
//! The messages are [`sightline_osi::osi3`]'s, compiled from ASAM's descriptors.

pub use trace::{OSI_TRACE, OsiTrace, TraceError};
pub use views::{AGENT_REFERENCE, VISIBILITY_REFERENCE};

mod answer;
mod reported_class;
pub mod system;
mod trace;
mod views;
