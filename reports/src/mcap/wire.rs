//! sightline's own channels in a recording: their JSON wire types, whose JSON
//! Schemas (generated from these types and made flat by [`flat`](super::flat))
//! the recording registers. Those `sightline replay` reads back also
//! deserialize.
//!
//! The viewers' schema parsers read one type per field, so a `None` is left out
//! of its message (never `null`), and a list holds objects or plain values,
//! never lists or `null`s.
//!
//! A semantic world's own records (packets, messages, arrivals, approaches,
//! road users) are in [`semantic`].

use std::borrow::Cow;
use std::fmt;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use sightline_dsl::{Metric, ObjectProperty, ObjectSelection, Signal};
use sightline_engine::outcome::MassAudit;

use crate::Tool;

mod semantic;

pub use semantic::{
    ApproachRecord, ArrivalRecord, ConflictRecord, ItemRecord, MessageRecord, PacketRecord, RoadUserRecord,
};

/// The format of sightline's recordings, written in `/sightline/scenario`;
/// replay reads this version only.
pub const RECORDING_FORMAT: &str = "sightline-recording/8";

/// A number that survives JSON exactly: finite values as JSON numbers (read back
/// bit for bit). JSON has no number for NaN and the infinities, and the viewers'
/// schema parsers no type but one per field, so the schema says `number`: no
/// simulation gives a non-finite value, and should a defect give one, it is
/// written as the string `NaN`, `inf` or `-inf`, read back as such, and refused
/// by replay's domain check (that message then breaks its schema, as it should).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

impl Serialize for Real {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            v if v.is_finite() => serializer.serialize_f64(v),
            v if v.is_nan() => serializer.serialize_str("NaN"),
            v if v > 0.0 => serializer.serialize_str("inf"),
            _ => serializer.serialize_str("-inf"),
        }
    }
}

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct RealVisitor;
        impl Visitor<'_> for RealVisitor {
            type Value = Real;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number, `NaN`, `inf` or `-inf`")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Real, E> {
                Ok(Real(v))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Real, E> {
                match v {
                    "NaN" => Ok(Real(f64::NAN)),
                    "inf" => Ok(Real(f64::INFINITY)),
                    "-inf" => Ok(Real(f64::NEG_INFINITY)),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
        }
        deserializer.deserialize_any(RealVisitor)
    }
}

impl JsonSchema for Real {
    fn schema_name() -> Cow<'static, str> {
        "Real".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "type": "number",
            "description": "A finite number, read back bit for bit"
        })
    }
}

/// `/sightline/scenario` (once, at time 0): what was run and how, enough for
/// `sightline replay` to compile the scenario again.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Scenario")]
pub struct ScenarioRecord {
    /// [`RECORDING_FORMAT`].
    pub format: String,
    /// The tool that recorded it.
    pub tool: Tool,
    /// The scenario file as the user named it.
    pub file: String,
    /// Its text, as compiled.
    pub text: String,
    /// SHA-256 of the text, lowercase hex.
    pub sha256: String,
    /// The seed `--seed` imposed (left out: the file's own).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Whether `--record` asked for the recording (the file may have no `record`).
    pub record_flag: bool,
    /// The points recorded step by step, in the order recorded: one, or every
    /// sweep point (`record.points: all`), each in its own span of time.
    pub points: Vec<RecordedPointRecord>,
    /// The files the scenario imports; each is attached to the recording
    /// (attachment name: the path).
    pub imports: Vec<ImportRecord>,
}

/// A point recorded step by step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RecordedPointRecord {
    /// Its index in results.json's `sweep`.
    pub point: usize,
    /// Its sweep label (empty without a sweep).
    pub label: String,
    /// When its step 0 is, seconds after the scenario's epoch (`time.start`):
    /// 0 for the one recorded point; with every point recorded, point k's is
    /// k times the slot (the longest point's duration and a second, rounded up
    /// to a whole minute).
    pub offset: f64,
}

/// A file the scenario imports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ImportRecord {
    /// `sumo_fcd`, `sumo_net`, `sumo_poly` or `opendrive`.
    pub kind: String,
    /// Its path, as the scenario resolved it (the attachment's name).
    pub path: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
}

/// `/sightline/outcome` (once per sweep point, at the end): what the point
/// measured, exactly, for the oracles of `sightline replay`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Outcome")]
pub struct OutcomeRecord {
    /// The point's index.
    pub point: usize,
    /// Its sweep label.
    pub label: String,
    /// Every metric the point measures, in documentation order.
    pub metrics: Vec<MetricValue>,
    /// The mass-function audit of its fused cells (left out where nothing is fused).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub audit: Option<AuditRecord>,
    /// Each replicate seed its checks over seeds ran (replicate 1, 2, …; empty
    /// without such a check).
    pub replicates: Vec<ReplicateRecord>,
    /// The signals its temporal checks read, over each run.
    pub series: Vec<SeriesRecord>,
    /// The per-object properties its checks read.
    pub per_object: Vec<ObjectRecord>,
}

/// A signal of one point: one list of (time s, value) per run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SeriesRecord {
    /// The signal's name, as in scenario files.
    pub signal: Signal,
    /// Per run, its defined steps.
    pub runs: Vec<SeriesRun>,
}

/// A signal over one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SeriesRun {
    /// Its defined steps, in time order.
    pub samples: Vec<SeriesSample>,
}

/// A signal's value at one step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SeriesSample {
    /// The step's time, seconds.
    pub time: Real,
    /// The signal's value.
    pub value: Real,
}

/// A per-object property of one point, of the road users a check selects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ObjectRecord {
    /// The property's name, as in scenario files.
    pub property: ObjectProperty,
    /// The road users it is of (left out: all).
    #[serde(default, skip_serializing_if = "ObjectSelection::is_all")]
    pub selection: ObjectSelection,
    /// Per road user, in order.
    pub values: Vec<ObjectValue>,
}

/// A per-object property of one road user.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ObjectValue {
    /// Who it is: its id, with its run where the point pools runs (`ped_3 of
    /// run 2`); for `warning_time`, also when it came within d_min of the ego
    /// (`ped_3 at 12.4 s`).
    pub who: String,
    /// Its value (left out: the object has none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Real>,
}

/// Every metric of one replicate seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ReplicateRecord {
    /// Every metric it measures, in documentation order.
    pub metrics: Vec<MetricValue>,
}

/// One metric's value and sample size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MetricValue {
    /// The metric's name, as in scenario files.
    pub metric: Metric,
    /// Its value (left out where it is undefined: an empty population).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Real>,
    /// The number of samples it is computed over (see the metric's population
    /// in the language reference).
    pub n: u64,
}

/// [`MassAudit`] on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AuditRecord {
    /// Fused cells audited.
    pub cells: u64,
    /// Cells with a NaN or infinite mass.
    pub non_finite: u64,
    /// Smallest finite mass of any cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_mass: Option<Real>,
    /// Largest finite mass of any cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_mass: Option<Real>,
    /// Largest |Σ masses − 1| of any finite cell.
    pub max_sum_error: Real,
}

impl From<MassAudit> for AuditRecord {
    fn from(audit: MassAudit) -> Self {
        Self {
            cells: audit.cells,
            non_finite: audit.non_finite,
            min_mass: audit.min_mass.map(Real),
            max_mass: audit.max_mass.map(Real),
            max_sum_error: Real(audit.max_sum_error),
        }
    }
}

impl From<AuditRecord> for MassAudit {
    fn from(audit: AuditRecord) -> Self {
        Self {
            cells: audit.cells,
            non_finite: audit.non_finite,
            min_mass: audit.min_mass.map(|r| r.0),
            max_mass: audit.max_mass.map(|r| r.0),
            max_sum_error: audit.max_sum_error.0,
        }
    }
}

/// `/sightline/verdicts` (once per requirement, at the end): the verdict as the
/// run reached it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Verdict")]
pub struct VerdictRecord {
    /// The requirement's id.
    pub id: String,
    /// Its text.
    pub text: String,
    /// `pass`, `not_exercised`, `fail` or `error`.
    pub verdict: String,
    /// Why a not-exercised verdict is acceptable, when the scenario says so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accepted: Option<String>,
    /// The deciding measured value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Real>,
    /// The threshold (for invariants: the tolerance).
    pub threshold: Real,
    /// The deciding signed margin (≥ 0 holds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<Real>,
    /// The deciding check in words.
    pub message: String,
    /// Every point it was checked at.
    pub points: Vec<PointVerdictRecord>,
}

/// A requirement checked at one point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PointVerdictRecord {
    /// The point's index.
    pub point: usize,
    /// `pass`, `not_exercised`, `fail` or `error`.
    pub verdict: String,
    /// The measured value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Real>,
    /// Its sample size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<u64>,
    /// What the value holds.
    pub measured: String,
    /// The signed margin.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<Real>,
    /// The check in words.
    pub message: String,
}

/// `/sightline/signals` (every step): what the step measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Signals")]
pub struct SignalsRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step; step k is at time k · `time.step`.
    pub step: usize,
    /// A perception world's fused grid at this step (left out in a semantic world,
    /// or when the ego is not in the scene: such steps count in no metric).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cells: Option<CellSignals>,
    /// A semantic world's traffic at this step (left out in a perception world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<SemanticSignals>,
}

/// The fused grid of one step against the truth, counted over the cells the
/// metrics count (the region of interest, occluders and the ego's footprint left
/// out). Ratios are left out where undefined.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CellSignals {
    /// Cells a sensor of the ego observed.
    pub ego_observed: u64,
    /// Cells a sensor of any cooperating agent observed (the cells fused,
    /// less those only a self-reported footprint covers).
    pub joint_observed: u64,
    /// Cells truly occupied by a road user that does not cooperate.
    pub occupied: u64,
    /// Of those, decided occupied where a sensor found them occupied.
    pub detected: u64,
    /// Of the `occupied` cells, those the ego's own observation alone decides
    /// occupied.
    pub ego_detected: u64,
    /// Cells decided occupied that are truly free.
    pub false_positives: u64,
    /// Of the `occupied` cells, those the ego did not observe itself.
    pub blind_occupied: u64,
    /// Of those, decided occupied where a sensor found them occupied.
    pub blind_detected: u64,
    /// Of the `occupied` cells, decided occupied where only another agent's
    /// reported footprint, no sensor, marks them occupied.
    pub footprint_only: u64,
    /// Cells of a cooperating agent's own body (other than the ego's): self-report.
    pub self_report: u64,
    /// Of those, decided occupied.
    pub self_report_detected: u64,
    /// Of those, observed occupied by no sensor.
    pub self_report_only: u64,
    /// This step's `occupied_recall`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recall: Option<f64>,
    /// This step's `occupied_precision`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<f64>,
    /// This step's `blind_recall`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blind_recall: Option<f64>,
    /// This step's `self_report_share`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_report_share: Option<f64>,
    /// This step's `fov_gain`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_gain: Option<f64>,
}

/// A semantic world's step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SemanticSignals {
    /// Packets sent (every kind).
    pub packets: u64,
    /// Of those, received.
    pub received: u64,
    /// Semantic messages the RSUs sent the ego.
    pub messages: u64,
    /// Of those, received.
    pub messages_received: u64,
    /// Semantic messages that reached the ego since the previous step.
    pub arrivals: u64,
    /// Objects that came within d_min of the ego.
    pub approaches: u64,
    /// Of those, without a conflict flagged to the ego beforehand.
    pub missed: u64,
    /// The shortest time to conflict the RSUs predicted, seconds (left out: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_time_to_conflict: Option<f64>,
}

/// `/sightline/requirements` (every step): each requirement that applies to the
/// recorded point and whose metric the steps give, over the steps so far.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.RequirementSignals")]
pub struct RequirementSignals {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step.
    pub step: usize,
    /// One entry per requirement, in file order.
    pub requirements: Vec<RequirementSignal>,
}

/// A requirement's metric over the steps so far.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RequirementSignal {
    /// The requirement's id.
    pub id: String,
    /// Its metric.
    pub metric: Metric,
    /// The metric over the steps so far (left out while undefined). A semantic
    /// point's metric is over its first run only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// The threshold.
    pub threshold: f64,
    /// The signed margin so far (≥ 0 holds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<f64>,
}

/// `/sightline/speeds` (every step of a world): what changes from step to
/// step of the agents `/scene/agents` draws, for a Plot panel
/// (`/sightline/speeds.agents[:]{id=="ego"}.speed_mps`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[schemars(title = "sightline.Speeds")]
pub struct SpeedsRecord {
    /// The sweep point: its index in results.json's `sweep`.
    pub point: usize,
    /// The step.
    pub step: usize,
    /// Every agent in the scene at the step, in agent order.
    pub agents: Vec<AgentSpeed>,
}

/// An agent's speed at one step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AgentSpeed {
    /// The agent's id (its `/tf` frame and its `/scene/agents` entity).
    pub id: String,
    /// Its speed, m/s, rounded to the centimetre per second.
    pub speed_mps: f64,
}

#[cfg(test)]
mod tests {
    use super::Real;

    /// Replay judges the recorded values: every f64 reads back bit for bit.
    #[test]
    fn real_survives_json_exactly() {
        for value in [
            0.1 + 0.2,
            1.0 / 3.0,
            5e-324,
            f64::MAX,
            -0.0,
            0.9438271028037383,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let text = serde_json::to_string(&Real(value)).unwrap();
            let back: Real = serde_json::from_str(&text).unwrap();
            assert_eq!(back.0.to_bits(), value.to_bits(), "{value} as {text}");
        }
        let nan: Real = serde_json::from_str(&serde_json::to_string(&Real(f64::NAN)).unwrap()).unwrap();
        assert!(nan.0.is_nan());
        assert!(serde_json::from_str::<Real>("\"many\"").is_err());
    }
}
