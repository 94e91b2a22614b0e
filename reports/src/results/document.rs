//! The whole of results.json: the scenario, the files the run read, the
//! overall verdict and the requirement counts, and where each part lives.

use serde::Serialize;

use super::provenance::closed;
use super::{
    Assumption, MetricEntry, Ordered, PointResult, RecordingInfo, ReferenceResult, RequirementResult, Status, Sweep,
    Tool,
};
use crate::execution::Execution;

/// The format identifier written into every results.json.
pub const FORMAT: &str = "sightline-results/5";

/// The whole of results.json.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Results {
    /// The format and its version: `sightline-results/5`.
    #[schemars(schema_with = "format_schema")]
    pub format: &'static str,
    /// The tool.
    #[schemars(schema_with = "closed::<Tool>")]
    pub tool: Tool,
    /// Where, when and how long it ran (the fields that differ from run to run).
    #[schemars(schema_with = "closed::<Execution>")]
    pub execution: Execution,
    /// The scenario.
    pub scenario: ScenarioInfo,
    /// Every file the run read: the scenario, then the files it imports.
    pub inputs: Vec<InputInfo>,
    /// The recording beside results.json (absent when the run recorded none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<RecordingInfo>,
    /// The seed, when every point shares one (`null` when the seed is swept).
    pub seed: Option<u64>,
    /// The overall verdict: the worst requirement verdict (not exercised with
    /// no requirements: nothing was judged).
    pub verdict: Status,
    /// What a CI gate should do: `pass` when every requirement passes or is
    /// not exercised with an accepted reason and one passes (`sightline run`
    /// exits 0), `fail` otherwise: also with no requirements, or none judged
    /// (it exits 1).
    pub gate: Status,
    /// Requirement counts.
    pub summary: Summary,
    /// One entry per requirement, in file order.
    pub requirements: Vec<RequirementResult>,
    /// Metrics: numbers for a scenario without sweep, tables over the sweep otherwise.
    pub metrics: Ordered<MetricEntry>,
    /// The sweeps: their settings, values and the point of each row (empty
    /// without a sweep).
    pub sweeps: Vec<Sweep>,
    /// Every distinct configuration the sweeps simulate, once, with its labels
    /// and measurements (one point without a sweep).
    pub sweep: Vec<PointResult>,
    /// Published figures beside the measured values.
    pub references: Vec<ReferenceResult>,
    /// The modelling idealisations that applied to the run (`{id, text}`), each
    /// once: what the verdicts take as given ("Assumptions and limitations" in
    /// the report).
    pub assumptions: Vec<Assumption>,
    /// What the run leaves out or cannot vouch for though it runs (elements of
    /// imported files dropped, types read by their names, a trace that does
    /// not cover the run), as `sightline check` prints them on stderr.
    pub warnings: Vec<WarningInfo>,
}

/// A warning, located in the file it is about.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct WarningInfo {
    /// The file: the scenario's path as given, or an imported file's path
    /// resolved against the scenario's directory.
    pub file: String,
    /// The line, from 1.
    pub line: usize,
    /// The column in characters, from 1.
    pub column: usize,
    /// What, a lowercase fragment.
    pub message: String,
}

/// The schema of `format`: the string [`FORMAT`], and no other.
fn format_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({ "type": "string", "const": FORMAT })
}

/// The scenario file.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ScenarioInfo {
    /// The path as given.
    pub path: String,
    /// SHA-256 of its bytes.
    pub sha256: String,
    /// Its `name`.
    pub name: String,
    /// Its `description`.
    pub description: String,
}

/// A file a run read.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct InputInfo {
    /// `scenario`, or the kind of imported file (`sumo_fcd`, `sumo_net`,
    /// `sumo_poly`, `sumo_config`, `sumo_routes`, `opendrive`).
    pub kind: &'static str,
    /// The path: as given for the scenario, resolved against the scenario's
    /// directory for an imported file.
    pub path: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
}

/// Requirement counts by verdict.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Summary {
    /// All requirements.
    pub requirements: usize,
    /// Passed.
    pub passed: usize,
    /// Failed.
    pub failed: usize,
    /// Not exercised (nothing to judge), accepted or not.
    pub not_exercised: usize,
    /// Of those, not exercised with an accepted reason.
    pub accepted: usize,
    /// Could not be checked.
    pub errors: usize,
}

impl Results {
    /// The metrics that metric requirements and published references name, each
    /// once, in file order.
    pub fn cited_metrics(&self) -> Vec<&'static str> {
        let mut metrics: Vec<&'static str> = Vec::new();
        let named = self
            .requirements
            .iter()
            .filter(|r| r.check.kind == "metric")
            .map(|r| r.check.name)
            .chain(self.references.iter().map(|r| r.metric));
        for name in named {
            if !metrics.contains(&name) {
                metrics.push(name);
            }
        }
        metrics
    }
}
