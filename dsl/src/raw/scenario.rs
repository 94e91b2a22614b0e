//! The scenario file's top level: every section, and the schema of `vary`.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::agents::RawAgent;
use super::document::RawDocument;
use super::field::RawField;
use super::fusion::{RawDecision, RawFusion, RawGrid};
use super::map::RawMap;
use super::perception::RawPerception;
use super::record::RawRecord;
use super::requirements::{RawReference, RawRequirement};
use super::semantic::{RawInteractionArea, RawSemantic};
use super::sensors::{RawLocalization, RawSensorModel};
use super::system::RawSystemUnderTest;
use super::traffic::{RawCrosswalk, RawDriving, RawTraffic};
use super::v2x::RawV2x;
use super::world::{RawOccluder, RawRoad, RawTime, RawTraces};

/// A sightline scenario: what to simulate, the requirements that must hold, and
/// optionally a sweep over settings.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, expecting = "a scenario mapping")]
#[schemars(title = "sightline scenario")]
#[schemars(rename = "Scenario")]
pub(crate) struct RawScenario {
    /// Language version; this release reads `1`.
    pub sightline: u32,
    /// Name shown in reports.
    pub name: String,
    /// What the scenario models and why; shown in reports.
    #[serde(default)]
    pub description: String,
    /// The report as a controlled document: version, author, reviewer,
    /// approver and paper size (they label the report only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub document: Option<RawDocument>,
    /// Seed of every random stream (0 to 2⁶⁴ − 1). The same file and seed give
    /// byte-identical results.
    #[serde(default)]
    pub seed: u64,
    /// The occupancy grid every method fuses into: required by the field
    /// experiment and by collective perception; a semantic world has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid: Option<RawGrid>,
    /// The static field experiment (seed 001): ground truth, fixed sensors, mass
    /// model. A scenario has either a `field` or a world (`time` … `perception`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<RawField>,
    /// World: simulated time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<RawTime>,
    /// World: agents' trajectories imported from the traffic simulator SUMO, and
    /// optionally its roads and buildings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traces: Option<RawTraces>,
    /// World: a road network from an OpenDRIVE file, its roads, sidewalks,
    /// junctions, crosswalks and buildings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub map: Option<RawMap>,
    /// World: directed roads with their lanes (besides those of `traces.net`
    /// and `map`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub roads: Vec<RawRoad>,
    /// World: buildings and walls that block sight (besides the polygons of
    /// `traces.poly` and the objects of `map`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub occluders: Vec<RawOccluder>,
    /// World: sensor models by id.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sensor_models: BTreeMap<String, RawSensorModel>,
    /// World: vehicles, pedestrians and roadside units (besides the objects of
    /// `traces.fcd`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub agents: Vec<RawAgent>,
    /// World: how connected agents localize themselves.
    #[serde(default)]
    pub localization: RawLocalization,
    /// World: who shares perception, and how observations become evidence.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub perception: Option<RawPerception>,
    /// World: background traffic generated on routes and crosswalks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traffic: Option<RawTraffic>,
    /// World: pedestrian crossings (besides the crosswalk objects of `map`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub crosswalks: Vec<RawCrosswalk>,
    /// World: regions around junctions, roundabout entries and crossings (besides
    /// the junctions of `traces.net` and `map`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub interaction_areas: Vec<RawInteractionArea>,
    /// World: regions named for requirements that select road users by area
    /// (`objects.areas`); they change nothing in the simulation.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<RawInteractionArea>,
    /// World: how vehicles keep their distance.
    #[serde(default)]
    pub driving: RawDriving,
    /// World: V2X assumptions; in collective perception, the radio the
    /// cooperating agents' grids go through (without it, they reach the ego
    /// whole and at once).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v2x: Option<RawV2x>,
    /// World: the roadside units' semantic pipeline for an assisted ego (seed 002).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<RawSemantic>,
    /// How sensor evidence is fused.
    #[serde(default)]
    pub fusion: RawFusion,
    /// How a fused cell becomes a decision.
    #[serde(default)]
    pub decision: RawDecision,
    /// The requirements that must hold.
    #[serde(default)]
    pub requirements: Vec<RawRequirement>,
    /// Settings to vary: a dotted path (`field.masses.gamma`; an agent by its id,
    /// `agents.<id>.speed.target`) and the list of values it takes. One run per
    /// combination, first key outermost.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sweep: BTreeMap<String, Vec<serde_json::Value>>,
    /// Independent sweeps, each like `sweep` and each reported as its own table
    /// (for example one over cooperating agents and one over localization noise).
    /// Use `sweep` or `sweeps`, not both.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sweeps: Vec<BTreeMap<String, Vec<serde_json::Value>>>,
    /// Published figures to show beside the measured ones.
    #[serde(default)]
    pub references: Vec<RawReference>,
    /// The space `sightline falsify` searches for a scenario that breaks a
    /// requirement: a dotted path (the sections a sweep may set) and either a
    /// range `[lo, hi]` (whole numbers when the setting is an integer) or
    /// `{ one_of: [ … ] }`. `sightline run` ignores it and runs the values
    /// written in the scenario.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    #[schemars(schema_with = "vary_schema")]
    pub vary: BTreeMap<String, serde_json::Value>,
    /// Record one sweep point, step by step, into `run.mcap` (Foxglove's
    /// formats) beside the other evidence; `sightline run --record` records
    /// with the defaults when this is absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub record: Option<RawRecord>,
    /// The user's own perception or fusion program, judged by the
    /// requirements on what it detects (docs/osi-sut.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system_under_test: Option<RawSystemUnderTest>,
}

/// The schema of `vary`: a range or a list of choices per dotted path.
fn vary_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "object",
        "additionalProperties": {
            "oneOf": [
                {
                    "description": "A range [lo, hi] (inclusive, lo ≤ hi).",
                    "type": "array",
                    "items": { "type": "number" },
                    "minItems": 2,
                    "maxItems": 2
                },
                {
                    "type": "object",
                    "properties": {
                        "one_of": {
                            "description": "The values the setting may take; a search shrinks toward the first.",
                            "type": "array",
                            "minItems": 1
                        }
                    },
                    "required": ["one_of"],
                    "additionalProperties": false
                }
            ]
        }
    })
}
