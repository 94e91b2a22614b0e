//! Where a run came from: the tool and its build, the scenario file as named,
//! and the recording written beside the evidence. The CLI supplies these; how
//! the run ran is [`Execution`].

use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::Serialize;

use crate::execution::Execution;

/// Where a run came from, supplied by the CLI.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Provenance {
    /// The tool that produced the evidence.
    pub tool: Tool,
    /// The scenario file as the user named it.
    pub scenario_path: String,
    /// SHA-256 of the scenario file's bytes, lowercase hex.
    pub scenario_sha256: String,
    /// The scenario file's text, for the report's appendix.
    pub scenario_text: String,
    /// The recording written beside the evidence, when there is one.
    pub recording: Option<RecordingInfo>,
    /// The platform, the start and the duration of the run.
    pub execution: Execution,
}

/// The recording (`run.mcap`) written beside results.json.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct RecordingInfo {
    /// Its file name in the evidence directory.
    pub file: String,
    /// SHA-256 of its bytes, lowercase hex: `sightline replay` refuses a
    /// recording that does not match it.
    pub sha256: String,
    /// The recorded sweep point's index (with every point recorded, the first).
    pub point: usize,
    /// Its sweep label (empty without a sweep).
    pub label: String,
    /// Whether every sweep point is recorded (`record.points: all`), one
    /// after another on the recording's clock; left out when one is.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub every_point: bool,
    /// The ASAM OSI trace of the same point written beside it (`sightline run
    /// --osi`); left out without one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub osi_trace: Option<OsiTraceInfo>,
}

/// The OSI trace (`osi.mcap`) written beside the recording.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct OsiTraceInfo {
    /// Its file name in the evidence directory.
    pub file: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
}

/// The tool and its build. Its schema is also the recording's (see
/// [`mcap`](crate::mcap)), which stays open to new fields; results.json closes
/// it where it writes it.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize, JsonSchema)]
pub struct Tool {
    /// `sightline`.
    pub name: String,
    /// The crate version.
    pub version: String,
    /// `git describe` of the build (`unknown` outside a checkout); a build from a
    /// modified tree adds git's hash of the modifications (`…-dirty-<12 hex>`).
    pub git: String,
}

/// The schema of `T` with no key beyond its fields, for the types results.json
/// shares with formats whose schemas stay open ([`Tool`],
/// [`Execution`]).
pub(super) fn closed<T: JsonSchema>(generator: &mut SchemaGenerator) -> Schema {
    let mut schema = T::json_schema(generator);
    schema.insert("additionalProperties".into(), false.into());
    schema
}
