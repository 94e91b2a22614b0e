//! results.json: the versioned wire format of a run's evidence.
//!
//! Everything but `execution` (platform, worker threads, start time and
//! duration: see [`Execution`]) is deterministic: no output paths, nothing
//! that depends on the thread count, so the same scenario and seed give the
//! same file but for those fields.

use serde::{Serialize, Serializer};
use sightline_dsl::{Bound, Check, OverSeeds, Point, Requirement, Scenario, Temporal};
use sightline_engine::outcome::{BandMetrics, Coverage, DensityRow, MassAudit, SemanticMetrics, WorldMetrics};
use sightline_engine::{Idealisation, Outcome, Run};
use sightline_oracles::{SeedStatistics, Status, Verdict};

use crate::execution::Execution;

/// The format identifier written into every results.json.
pub const FORMAT: &str = "sightline-results/2";

/// Where a run came from, supplied by the CLI.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Provenance {
    /// The tool that produced the evidence.
    pub tool: Tool,
    /// The scenario file as the user named it.
    pub scenario_path: String,
    /// SHA-256 of the scenario file's bytes, lowercase hex.
    pub scenario_sha256: String,
    /// The recording written beside the evidence, when there is one.
    pub recording: Option<RecordingInfo>,
    /// The platform, the start and the duration of the run.
    pub execution: Execution,
}

/// The recording (`run.mcap`) written beside results.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordingInfo {
    /// Its file name in the evidence directory.
    pub file: String,
    /// SHA-256 of its bytes, lowercase hex: `sightline replay` refuses a
    /// recording that does not match it.
    pub sha256: String,
    /// The recorded sweep point's index.
    pub point: usize,
    /// Its sweep label (empty without a sweep).
    pub label: String,
}

/// The tool and its build.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Tool {
    /// `sightline`.
    pub name: String,
    /// The crate version.
    pub version: String,
    /// `git describe` of the build (`unknown` outside a checkout).
    pub git: String,
}

/// The whole of results.json.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Results {
    /// [`FORMAT`].
    pub format: &'static str,
    /// The tool.
    pub tool: Tool,
    /// Where, when and how long it ran (the fields that differ from run to run).
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
    /// The overall verdict: the worst requirement verdict (pass with no requirements).
    pub verdict: Status,
    /// What a CI gate should do: `pass` when every requirement passes or is
    /// not exercised with an accepted reason (`sightline run` exits 0),
    /// `fail` otherwise (it exits 1).
    pub gate: Status,
    /// Requirement counts.
    pub summary: Summary,
    /// One entry per requirement, in file order.
    pub requirements: Vec<RequirementResult>,
    /// Metrics: numbers for a scenario without sweep, tables over the sweep otherwise.
    pub metrics: Ordered<MetricEntry>,
    /// The sweeps: their settings, values and the point of each row (empty
    /// without a sweep).
    pub sweeps: Vec<sightline_dsl::Sweep>,
    /// Every distinct configuration the sweeps simulate, once, with its labels
    /// and measurements (one point without a sweep).
    pub sweep: Vec<PointResult>,
    /// Published figures beside the measured values.
    pub references: Vec<ReferenceResult>,
    /// The modelling idealisations that applied to the run (`{id, text}`), each
    /// once: what the verdicts take as given ("Assumptions and limitations" in
    /// the report).
    pub assumptions: Vec<Idealisation>,
}

/// The scenario file.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InputInfo {
    /// `scenario`, or the kind of imported file (`sumo_fcd`, `sumo_net`, `sumo_poly`).
    pub kind: &'static str,
    /// The path: as given for the scenario, resolved against the scenario's
    /// directory for an imported file.
    pub path: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
}

/// Requirement counts by verdict.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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

/// One requirement's verdict and the evidence for it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RequirementResult {
    /// The id.
    pub id: String,
    /// The text.
    pub text: String,
    /// Line of the requirement in the scenario file.
    pub line: usize,
    /// The check as written.
    pub check: CheckInfo,
    /// The verdict.
    pub verdict: Status,
    /// Whether the verdict fails the run (a failure, an error, or not
    /// exercised without an accepted reason).
    pub fails_run: bool,
    /// Why a not-exercised verdict is acceptable, as the scenario says.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accept_not_exercised: Option<String>,
    /// The fewest samples a point needs to be judged.
    pub min_samples: u64,
    /// The deciding point's index.
    pub point: usize,
    /// The deciding measured value (worst status, then smallest margin).
    pub value: Option<f64>,
    /// The deciding value's sample size.
    pub n: Option<u64>,
    /// What the deciding value holds, with its n.
    pub measured: String,
    /// The threshold (for invariants: the tolerance).
    pub threshold: f64,
    /// The deciding margin (≥ 0 holds).
    pub margin: Option<f64>,
    /// The deciding check in words.
    pub message: String,
    /// Every point it was checked at.
    pub points: Vec<PointVerdict>,
}

/// A check in the form it was written.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckInfo {
    /// `metric`, `always`, `eventually`, `per_object` or `invariant`.
    pub kind: &'static str,
    /// The metric, signal, property or invariant name.
    pub name: &'static str,
    /// `at_least`, `at_most` or `tolerance`.
    pub relation: &'static str,
    /// The threshold or tolerance.
    pub threshold: f64,
    /// For a check over seeds: how many, at which confidence, bounding what.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub over_seeds: Option<OverSeeds>,
    /// For a temporal check: the window's length from the start, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub within: Option<f64>,
}

/// A requirement checked at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointVerdict {
    /// The point index.
    pub point: usize,
    /// The point's sweep label (empty without a sweep).
    pub label: String,
    /// The verdict at this point.
    pub verdict: Status,
    /// The measured value.
    pub value: Option<f64>,
    /// Its sample size.
    pub n: Option<u64>,
    /// What the value holds, with its n.
    pub measured: String,
    /// The margin.
    pub margin: Option<f64>,
    /// The check in words.
    pub message: String,
    /// For a check over seeds: the estimate and the bound compared.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seeds: Option<SeedStatistics>,
    /// For a temporal check: the time of the decisive step, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
}

/// A metric in the top-level `metrics` map.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum MetricEntry {
    /// The value of a scenario without sweep, with its n.
    Measured(Measured),
    /// The values over each sweep, one table per sweep.
    Tables(Vec<Table>),
}

/// A metric's value and its sample size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measured {
    /// The value (`null` where it is undefined: an empty population).
    pub value: Option<f64>,
    /// The number of samples it is computed over.
    pub n: u64,
}

/// A metric over one sweep: one row per combination of its values, the axis
/// values, then the metric (`null` where it is undefined) and its n.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    /// Index of the sweep in `sweeps`.
    pub sweep: usize,
    /// The axis paths, then `value` and `n`.
    pub columns: Vec<String>,
    /// One row per combination (a point several sweeps share is a row of each).
    pub rows: Vec<Vec<serde_json::Value>>,
}

/// Everything measured at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointResult {
    /// The index.
    pub index: usize,
    /// Its labels joined with ` | ` (empty without a sweep).
    pub label: String,
    /// Each sweep combination the point stands for: one, or several where sweeps
    /// meet at the same configuration.
    pub labels: Vec<LabelResult>,
    /// The seed.
    pub seed: u64,
    /// The fusion method (absent where nothing is fused: a semantic world).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method: Option<&'static str>,
    /// The fusion label (absent where nothing is fused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fusion: Option<String>,
    /// Every defined metric.
    pub metrics: Ordered<f64>,
    /// The sample size of every metric the point measures, defined or not.
    pub samples: Ordered<u64>,
    /// The mass audit (absent where nothing is fused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub audit: Option<MassAudit>,
    /// What only this kind of scenario measures.
    #[serde(flatten)]
    pub detail: Detail,
}

/// One sweep combination a point stands for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LabelResult {
    /// The sweep (`null` without a sweep).
    pub sweep: Option<usize>,
    /// The combination as `path=value, …`.
    pub label: String,
    /// Each axis's value.
    pub settings: Ordered<serde_json::Value>,
}

/// Measurements particular to the kind of scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "experiment", rename_all = "snake_case")]
pub enum Detail {
    /// The field experiment.
    Field {
        /// Metrics by distance to the nearest sensor.
        bands: Vec<BandMetrics>,
        /// Sensors per cell.
        coverage: Coverage,
    },
    /// A world's collective perception.
    World {
        /// The counts behind the metrics.
        counts: WorldMetrics,
    },
    /// A world's semantic pipeline.
    Semantic {
        /// The counts and samples behind the metrics; the per-step series are
        /// left out (they are in run.mcap and in shard files).
        counts: SemanticMetrics,
        /// Objects known to the ego only through an RSU, by traffic density.
        contribution_by_density: Vec<DensityRow>,
    },
}

/// A published figure and the measured values it compares with.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceResult {
    /// Where it is published.
    pub source: String,
    /// The metric.
    pub metric: &'static str,
    /// The published value.
    pub published: f64,
    /// The measured value at each matching point.
    pub points: Vec<ReferencePoint>,
}

/// A measured value beside a published one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferencePoint {
    /// The point index.
    pub point: usize,
    /// The point's label.
    pub label: String,
    /// The measured value (`null` where undefined).
    pub measured: Option<f64>,
}

/// A map that serializes its entries in insertion order.
#[derive(Debug, Clone, PartialEq)]
pub struct Ordered<T>(pub Vec<(String, T)>);

impl<T: Copy> Ordered<T> {
    /// The value under `key`.
    pub fn get(&self, key: &str) -> Option<T> {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| *v)
    }
}

impl<T: Serialize> Serialize for Ordered<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(self.0.iter().map(|(k, v)| (k, v)))
    }
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

    /// Assembles the results of a run.
    pub fn new(scenario: &Scenario, run: &Run, verdicts: &[Verdict], provenance: &Provenance) -> Self {
        let labels: Vec<String> = scenario.points.iter().map(|p| p.label()).collect();
        let count = |status| verdicts.iter().filter(|v| v.status == status).count();
        let seeds: Vec<u64> = scenario.points.iter().map(|p| p.setup.seed).collect();
        Results {
            format: FORMAT,
            tool: provenance.tool.clone(),
            execution: provenance.execution.clone(),
            scenario: ScenarioInfo {
                path: provenance.scenario_path.clone(),
                sha256: provenance.scenario_sha256.clone(),
                name: scenario.name.clone(),
                description: scenario.description.clone(),
            },
            inputs: std::iter::once(InputInfo {
                kind: "scenario",
                path: provenance.scenario_path.clone(),
                sha256: provenance.scenario_sha256.clone(),
            })
            .chain(scenario.imports.iter().map(|import| InputInfo {
                kind: import.kind.name(),
                path: import.path.clone(),
                sha256: crate::sha256_hex(&import.bytes),
            }))
            .collect(),
            recording: provenance.recording.clone(),
            seed: seeds.iter().all(|&s| s == seeds[0]).then_some(seeds[0]),
            verdict: verdicts.iter().map(|v| v.status).max().unwrap_or(Status::Pass),
            gate: if verdicts.iter().any(Verdict::fails_run) {
                Status::Fail
            } else {
                Status::Pass
            },
            summary: Summary {
                requirements: verdicts.len(),
                passed: count(Status::Pass),
                failed: count(Status::Fail),
                not_exercised: count(Status::NotExercised),
                accepted: verdicts
                    .iter()
                    .filter(|v| v.status == Status::NotExercised && !v.fails_run())
                    .count(),
                errors: count(Status::Error),
            },
            requirements: scenario
                .requirements
                .iter()
                .zip(verdicts)
                .map(|(requirement, verdict)| requirement_result(requirement, verdict, &labels))
                .collect(),
            metrics: metrics(scenario, run),
            sweeps: scenario.sweeps.clone(),
            sweep: scenario.points.iter().zip(&run.points).map(point_result).collect(),
            references: scenario
                .references
                .iter()
                .map(|r| ReferenceResult {
                    source: r.source.clone(),
                    metric: r.metric.name(),
                    published: r.value,
                    points: r
                        .points
                        .iter()
                        .map(|&p| ReferencePoint {
                            point: p,
                            label: labels[p].clone(),
                            measured: run.points[p].value(r.metric),
                        })
                        .collect(),
                })
                .collect(),
            assumptions: sightline_engine::idealisations(scenario),
        }
    }
}

fn requirement_result(requirement: &Requirement, verdict: &Verdict, labels: &[String]) -> RequirementResult {
    RequirementResult {
        id: requirement.id.clone(),
        text: requirement.text.clone(),
        line: requirement.location.line,
        check: check_info(&requirement.check),
        verdict: verdict.status,
        fails_run: verdict.fails_run(),
        accept_not_exercised: verdict.accepted.clone(),
        min_samples: verdict.min_samples,
        point: verdict.decisive.point,
        value: verdict.decisive.value,
        n: verdict.decisive.n,
        measured: verdict.decisive.measured.clone(),
        threshold: verdict.threshold,
        margin: verdict.decisive.margin,
        message: verdict.decisive.message.clone(),
        points: verdict
            .evaluations
            .iter()
            .map(|e| PointVerdict {
                point: e.point,
                label: labels[e.point].clone(),
                verdict: e.status,
                value: e.value,
                n: e.n,
                measured: e.measured.clone(),
                margin: e.margin,
                message: e.message.clone(),
                seeds: e.seeds,
                time: e.time,
            })
            .collect(),
    }
}

fn point_result((point, outcome): (&Point, &Outcome)) -> PointResult {
    PointResult {
        index: point.index,
        label: point.label(),
        labels: point
            .labels
            .iter()
            .map(|label| LabelResult {
                sweep: label.sweep,
                label: label.text(),
                settings: Ordered(
                    label
                        .assignments
                        .iter()
                        .map(|a| (a.path.clone(), a.value.clone()))
                        .collect(),
                ),
            })
            .collect(),
        seed: point.setup.seed,
        method: point.setup.occupancy.as_ref().map(|o| o.fusion.rule.method().name()),
        fusion: point.setup.occupancy.as_ref().map(|o| o.fusion.label.clone()),
        metrics: Ordered(
            outcome
                .values()
                .into_iter()
                .map(|(m, v)| (m.name().to_string(), v))
                .collect(),
        ),
        samples: Ordered(
            outcome
                .samples()
                .into_iter()
                .map(|(m, s)| (m.name().to_string(), s.n))
                .collect(),
        ),
        audit: outcome.audit().copied(),
        detail: match outcome {
            Outcome::Field(o) => Detail::Field {
                bands: o.bands.clone(),
                coverage: o.coverage,
            },
            Outcome::World(o) => Detail::World {
                counts: o.metrics.clone(),
            },
            Outcome::Semantic(m) => Detail::Semantic {
                counts: SemanticMetrics {
                    contribution: Vec::new(),
                    rsu_only: Vec::new(),
                    time_to_conflict: Vec::new(),
                    ..m.clone()
                },
                contribution_by_density: m.contribution_by_density(),
            },
        },
    }
}

fn check_info(check: &Check) -> CheckInfo {
    match *check {
        Check::Metric {
            metric,
            bound,
            over_seeds,
        } => CheckInfo {
            kind: "metric",
            name: metric.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds,
            within: None,
        },
        Check::Temporal {
            signal,
            operator,
            bound,
            within,
        } => CheckInfo {
            kind: match operator {
                Temporal::Always => "always",
                Temporal::Eventually => "eventually",
            },
            name: signal.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds: None,
            within,
        },
        Check::PerObject { property, bound } => CheckInfo {
            kind: "per_object",
            name: property.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds: None,
            within: None,
        },
        Check::Invariant { invariant, tolerance } => CheckInfo {
            kind: "invariant",
            name: invariant.name(),
            relation: "tolerance",
            threshold: tolerance,
            over_seeds: None,
            within: None,
        },
    }
}

fn relation(bound: Bound) -> &'static str {
    match bound {
        Bound::AtLeast(_) => "at_least",
        Bound::AtMost(_) => "at_most",
    }
}

/// Top-level metrics: numbers without a sweep, one table per sweep with one.
fn metrics(scenario: &Scenario, run: &Run) -> Ordered<MetricEntry> {
    if scenario.sweeps.is_empty() {
        let samples = run.points[0].samples();
        return Ordered(
            samples
                .into_iter()
                .map(|(m, s)| {
                    let entry = MetricEntry::Measured(Measured { value: s.value, n: s.n });
                    (m.name().to_string(), entry)
                })
                .collect(),
        );
    }
    Ordered(
        sightline_dsl::Metric::ALL
            .iter()
            .filter(|&&m| run.points.iter().any(|o| o.sample(m).is_some()))
            .map(|&m| {
                let tables = scenario
                    .sweeps
                    .iter()
                    .enumerate()
                    .map(|(i, sweep)| {
                        let mut columns: Vec<String> = sweep.axes.iter().map(|a| a.path.clone()).collect();
                        columns.push("value".into());
                        columns.push("n".into());
                        let rows = sweep
                            .rows()
                            .map(|(p, values)| {
                                let mut row: Vec<serde_json::Value> = values.into_iter().cloned().collect();
                                let sample = run.points[p].sample(m);
                                row.push(
                                    sample
                                        .and_then(|s| s.value)
                                        .map_or(serde_json::Value::Null, serde_json::Value::from),
                                );
                                row.push(sample.map_or(serde_json::Value::Null, |s| s.n.into()));
                                row
                            })
                            .collect();
                        Table {
                            sweep: i,
                            columns,
                            rows,
                        }
                    })
                    .collect();
                (m.name().to_string(), MetricEntry::Tables(tables))
            })
            .collect(),
    )
}
