//! The user's own system under test, driven over ASAM OSI (docs/osi-sut.md).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::range;

/// An external perception or fusion program judged by the scenario's
/// requirements: sightline starts it, hands it at each step what the served
/// sensors of one cooperating agent see (`osi3.SensorView`, occlusion
/// included) and reads back what it detected (`osi3.SensorData`), over the
/// protocol of docs/osi-sut.md. A perception world with one sweep point only.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a system_under_test mapping")]
#[schemars(rename = "SystemUnderTest")]
pub(crate) struct RawSystemUnderTest {
    /// The program and its arguments, run without a shell (`[python3,
    /// tracker.py]`); a relative program path is looked up on `PATH`, relative
    /// arguments are the program's business (it runs in sightline's working
    /// directory).
    pub command: Vec<String>,
    /// The cooperating agent whose sensors it serves: the host vehicle (or
    /// roadside unit) of its views, the frame of its detections.
    pub agent: String,
    /// The agent's sensors it serves, by index on the agent (0: its first);
    /// default every one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SENSOR_INDEX.schema())]
    pub sensors: Option<Vec<u64>>,
    /// Wall-clock seconds the system may take to answer one step (and to
    /// announce its protocol, and to exit after the last step). Default 5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SUT_TIMEOUT.schema())]
    pub step_timeout: Option<f64>,
    /// Matching gate, metres: a detection matches a road user whose centre is
    /// within this distance of it (one to one, nearest pairs first). Default 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::SUT_GATE.schema())]
    pub gate: Option<f64>,
    /// Detections whose existence probability is below this are not judged
    /// (neither matched nor ghosts). Default 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = range::PROBABILITY.schema())]
    pub min_existence: Option<f64>,
}
