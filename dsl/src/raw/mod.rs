//! The YAML as written: a serde mirror of the scenario file, nothing resolved,
//! one module per group of sections.
//!
//! Doc comments here become the JSON Schema's descriptions (what editors show on
//! hover) and the generated reference in `docs/reference.md`, so each states its
//! unit and default. Every struct denies unknown keys. A struct whose keys are
//! all optional takes its defaults from one `Default` impl (a container
//! `#[serde(default)]`); a struct with a required key keeps a default function
//! per defaulted key, since serde has no container default that leaves a key
//! required. Each number names its physical range (`range`), which the schema carries
//! and `compile` checks; ids and references are checked in `compile`.

mod agents;
mod document;
mod field;
mod fusion;
mod map;
mod perception;
pub(crate) mod range;
mod record;
mod requirements;
mod scenario;
mod semantic;
mod sensors;
mod system;
mod traffic;
mod v2x;
mod world;

pub(crate) use agents::RawAgent;
pub(crate) use document::{RawDocument, RawPaper};
pub(crate) use field::{RawField, RawLayout, RawMasses, RawTruth};
pub(crate) use fusion::{RawDecision, RawFusion, RawGrid};
pub(crate) use map::RawMap;
pub(crate) use perception::RawPerception;
pub(crate) use record::{RawRecord, RawRecordedPoints};
pub(crate) use requirements::{RawCheck, RawObjectSelection, RawReference, RawRequirement};
pub(crate) use scenario::RawScenario;
pub(crate) use semantic::{RawInteractionArea, RawSemantic};
pub(crate) use sensors::{RawNoise, RawOdometry, RawSensorModel};
pub(crate) use system::RawSystemUnderTest;
pub(crate) use traffic::{RawCrosswalk, RawDriving, RawTraffic};
pub(crate) use v2x::{RawMessages, RawV2x};
pub(crate) use world::{RawOccluder, RawPoiRsus, RawRoad, RawTime, RawTraces};
