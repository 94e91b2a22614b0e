//! The end of a recording: every point's outcome with what its checks read
//! (`/sightline/outcome`), a semantic point's relevant road users
//! (`/semantic/objects`), and every verdict, structured (`/sightline/verdicts`)
//! and as a log line (`/log`), written once the run is over.

use std::io::Write;

use sightline_dsl::{Check, ObjectProperty, ObjectSelection, Signal};
use sightline_engine::{Outcome, Run};
use sightline_oracles::Verdict;

use super::channel::{LOG, OBJECT, OUTCOME, VERDICT};
use super::{Recorder, WriteError};
use crate::mcap::foxglove::{Level, Log, Time};
use crate::mcap::topic;
use crate::mcap::wire::{
    AuditRecord, MetricValue, ObjectRecord, ObjectValue, OutcomeRecord, PointVerdictRecord, Real, ReplicateRecord,
    RoadUserRecord, SeriesRecord, SeriesRun, SeriesSample, VerdictRecord,
};
use crate::results::{MAX_OBJECT_RECORDS, object_result};

impl<W: Write + Send + 'static> Recorder<'_, W> {
    /// Writes every point's outcome, every verdict (structured and as log lines)
    /// at the time of the last step, and closes the file; returns the output.
    pub fn finish(mut self, run: &Run, verdicts: &[Verdict]) -> Result<W, WriteError> {
        let end = self.last;
        let scenario = self.scenario;
        let metric_values = |outcome: &Outcome| -> Vec<MetricValue> {
            outcome
                .samples()
                .into_iter()
                .map(|(metric, sample)| MetricValue {
                    metric,
                    value: sample.value.map(Real),
                    n: sample.n,
                })
                .collect()
        };
        for (point, outcome) in scenario.points.iter().zip(&run.points) {
            // What this point's temporal and per-object checks read, each once.
            let mut signals: Vec<Signal> = Vec::new();
            let mut properties: Vec<(ObjectProperty, &ObjectSelection)> = Vec::new();
            for requirement in scenario.requirements.iter().filter(|r| r.points.contains(&point.index)) {
                match requirement.check {
                    Check::Temporal { signal, .. } if !signals.contains(&signal) => signals.push(signal),
                    Check::PerObject { property, .. } if !properties.contains(&(property, &requirement.objects)) => {
                        properties.push((property, &requirement.objects));
                    }
                    _ => {}
                }
            }
            let record = OutcomeRecord {
                point: point.index,
                label: point.label(),
                metrics: metric_values(outcome),
                audit: outcome.audit().copied().map(AuditRecord::from),
                replicates: run.replicates[point.index]
                    .iter()
                    .map(|outcome| ReplicateRecord {
                        metrics: metric_values(outcome),
                    })
                    .collect(),
                series: signals
                    .into_iter()
                    .filter_map(|signal| {
                        let runs = outcome.series(signal)?;
                        Some(SeriesRecord {
                            signal,
                            runs: runs
                                .iter()
                                .map(|series| SeriesRun {
                                    samples: series
                                        .iter()
                                        .map(|&(time, value)| SeriesSample {
                                            time: Real(time),
                                            value: Real(value),
                                        })
                                        .collect(),
                                })
                                .collect(),
                        })
                    })
                    .collect(),
                per_object: properties
                    .into_iter()
                    .filter_map(|(property, selection)| {
                        let values = outcome.per_object(property, selection)?;
                        Some(ObjectRecord {
                            property,
                            selection: selection.clone(),
                            values: (values.into_iter())
                                .map(|v| ObjectValue {
                                    who: v.who,
                                    value: v.value.map(Real),
                                })
                                .collect(),
                        })
                    })
                    .collect(),
            };
            self.publish(topic::OUTCOME, OUTCOME, end, &record);
            if let Some(metrics) = outcome.semantic() {
                // A joint world's records say when each road user came into the grid.
                let in_grid = matches!(outcome, Outcome::World(_));
                for object in metrics.objects.iter().take(MAX_OBJECT_RECORDS) {
                    let record = road_user_record(point.index, object, in_grid);
                    self.publish(topic::OBJECTS, OBJECT, end, &record);
                }
            }
        }
        for (requirement, verdict) in scenario.requirements.iter().zip(verdicts) {
            self.publish(topic::VERDICTS, VERDICT, end, &verdict_record(requirement, verdict));
            let level = match verdict.status {
                sightline_oracles::Status::Pass => Level::Info,
                sightline_oracles::Status::NotExercised if !verdict.fails_run() => Level::Warning,
                _ => Level::Error,
            };
            let log = Log::new(
                Time::from_nanos(end),
                level,
                format!(
                    "{} {}: {}",
                    verdict.status.words().to_uppercase(),
                    requirement.id,
                    verdict.decisive.message
                ),
                scenario.file.clone(),
                requirement.location.line,
            );
            self.publish(topic::LOG, LOG, end, &log);
        }
        self.out.finish()
    }
}

/// A relevant road user, flat, as results.json lists it (`in_grid`: with
/// its time in a joint world's fused grid).
fn road_user_record(point: usize, object: &sightline_engine::outcome::ObjectRecord, in_grid: bool) -> RoadUserRecord {
    let listed = object_result(object, in_grid);
    let closest = listed.closest;
    RoadUserRecord {
        point,
        run: listed.run,
        id: listed.id,
        class: listed.class.into(),
        length: listed.length,
        width: listed.width,
        first_relevant: listed.first_relevant,
        first_seen: listed.first_seen,
        first_v2x: listed.first_v2x,
        first_warning: listed.first_warning,
        first_in_grid: listed.first_in_grid.flatten(),
        closest_time: closest.map(|c| c.time),
        closest_distance: closest.map(|c| c.distance),
        closest_x: closest.map(|c| c.position[0]),
        closest_y: closest.map(|c| c.position[1]),
        min_ttc: listed.min_ttc,
        max_drac: listed.max_drac,
        pet: listed.pet,
        category: listed.category.name().into(),
        anticipation: listed.anticipation,
    }
}

fn verdict_record(requirement: &sightline_dsl::Requirement, verdict: &Verdict) -> VerdictRecord {
    VerdictRecord {
        id: requirement.id.clone(),
        text: requirement.text.clone(),
        verdict: verdict.status.name().into(),
        accepted: verdict.acceptance().map(str::to_owned),
        value: verdict.decisive.value.map(Real),
        threshold: Real(verdict.threshold),
        margin: verdict.decisive.margin.map(Real),
        message: verdict.decisive.message.clone(),
        points: verdict
            .evaluations
            .iter()
            .map(|e| PointVerdictRecord {
                point: e.point,
                verdict: e.status.name().into(),
                value: e.value.map(Real),
                n: e.n,
                measured: e.measured.clone(),
                margin: e.margin.map(Real),
                message: e.message.clone(),
            })
            .collect(),
    }
}
