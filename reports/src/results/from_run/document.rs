//! The document: [`Results::new`] assembles results.json from a scenario, its
//! run and its verdicts; the sweeps and the top-level metrics.

use sightline_dsl::Scenario;
use sightline_engine::{Idealisation, Run};
use sightline_oracles::Verdict;

use super::point::point_result;
use super::requirement::requirement_result;
use crate::results::{
    Assumption, Axis, FORMAT, InputInfo, Measured, MetricEntry, Ordered, Provenance, ReferencePoint, ReferenceResult,
    Results, ScenarioInfo, Status, Summary, Sweep, SweepRow, Table, WarningInfo,
};

impl Results {
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
                sha256: crate::hex(&import.sha256),
            }))
            .collect(),
            recording: provenance.recording.clone(),
            seed: seeds.iter().all(|&s| s == seeds[0]).then_some(seeds[0]),
            verdict: verdicts
                .iter()
                .map(|v| v.status)
                .max()
                .map_or(Status::NotExercised, Status::from),
            gate: match sightline_oracles::headline(verdicts) {
                sightline_oracles::Status::Pass => Status::Pass,
                _ => Status::Fail,
            },
            summary: Summary {
                requirements: verdicts.len(),
                passed: count(sightline_oracles::Status::Pass),
                failed: count(sightline_oracles::Status::Fail),
                not_exercised: count(sightline_oracles::Status::NotExercised),
                accepted: verdicts
                    .iter()
                    .filter(|v| v.status == sightline_oracles::Status::NotExercised && !v.fails_run())
                    .count(),
                errors: count(sightline_oracles::Status::Error),
            },
            requirements: scenario
                .requirements
                .iter()
                .zip(verdicts)
                .map(|(requirement, verdict)| requirement_result(requirement, verdict, &labels))
                .collect(),
            metrics: metrics(scenario, run),
            sweeps: scenario.sweeps.iter().map(sweep).collect(),
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
                            n: run.points[p].sample(r.metric).map(|s| s.n),
                        })
                        .collect(),
                })
                .collect(),
            assumptions: sightline_engine::idealisations(scenario)
                .into_iter()
                .map(|Idealisation { id, text }| Assumption {
                    id: id.into(),
                    text: text.into(),
                })
                .collect(),
            warnings: scenario
                .warnings
                .iter()
                .map(|w| WarningInfo {
                    file: w.file.clone(),
                    line: w.location.line,
                    column: w.location.column,
                    message: w.message.clone(),
                })
                .collect(),
        }
    }
}

/// A sweep with its rows spelled out.
fn sweep(sweep: &sightline_dsl::Sweep) -> Sweep {
    Sweep {
        axes: sweep
            .axes
            .iter()
            .map(|axis| Axis {
                path: axis.path.clone(),
                values: axis.values.clone(),
                unit: sightline_dsl::setting_unit(&axis.path),
            })
            .collect(),
        points: sweep.points.clone(),
        rows: sweep
            .rows()
            .map(|(point, values)| SweepRow {
                point,
                values: values.into_iter().cloned().collect(),
            })
            .collect(),
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
