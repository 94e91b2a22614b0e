//! Reading a recording back for `sightline replay`: the whole file checked
//! (magic at both ends, every chunk's, attachment's and section's CRC), then
//! what replay needs kept: the scenario, the imported files, every point's
//! outcome, the verdicts, and each recorded point's cell counts summed over its
//! steps. Messages on other channels are checked and dropped, so memory stays
//! bounded by one chunk.

use std::collections::BTreeMap;

use mcap::records::Record;
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use serde::de::DeserializeOwned;
use sightline_dsl::{Metric, ObjectProperty, ObjectSelection, Signal};
use sightline_engine::outcome::{CellTally, MassAudit, Series, WorldMetrics};
use sightline_engine::{RoadUserValue, Sample};
use sightline_oracles::Measurements;

use super::counts::WORLD_STEP_METRICS;
use super::lengths;
use super::topic;
use super::wire::{MetricValue, OutcomeRecord, RECORDING_FORMAT, ScenarioRecord, SignalsRecord, VerdictRecord};
use crate::sha256_hex;

/// The largest record (or message inside a chunk) a recording may hold, bytes.
/// A damaged length field is an error, not an allocation.
const RECORD_LIMIT: usize = 1 << 28;

/// Why a file is not a sightline recording that replay can trust.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The MCAP container is damaged: truncated, a bad CRC, a bad record.
    #[error("it is not a complete, intact MCAP file ({0}); it may be truncated or damaged")]
    Mcap(#[from] mcap::McapError),
    /// A record's length field overruns the record.
    #[error("it is not a complete, intact MCAP file ({0}); it may be truncated or damaged")]
    Damaged(String),
    /// A valid MCAP file that sightline did not write (or not this version).
    #[error("it is not a sightline recording: {0}")]
    NotSightline(String),
    /// A message on a sightline channel does not decode.
    #[error("message {index} on {topic} is malformed: {error}")]
    Message {
        /// The topic.
        topic: &'static str,
        /// Its position on the topic, from 1.
        index: usize,
        /// What is wrong with it.
        error: serde_json::Error,
    },
    /// The parts of the recording disagree with each other.
    #[error("its content is inconsistent: {0}")]
    Inconsistent(String),
}

/// What replay reads from a recording.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// How the scenario was run, with its text.
    pub scenario: ScenarioRecord,
    /// The imported files, by path (their hashes checked against
    /// [`ScenarioRecord::imports`]).
    pub imports: BTreeMap<String, Vec<u8>>,
    /// Every point's outcome, in point order.
    pub outcomes: Vec<OutcomeRecord>,
    /// The verdicts as the run reached them, in requirement order.
    pub verdicts: Vec<VerdictRecord>,
    /// Messages per topic.
    pub counts: BTreeMap<String, u64>,
    /// Each recorded point of a perception world that has measured steps: its
    /// cell counts summed over them, by point.
    pub step_counts: BTreeMap<usize, WorldMetrics>,
}

/// Reads and checks a whole recording.
pub fn read(bytes: &[u8]) -> Result<Recording, ReadError> {
    let mut reader = LinearReader::new_with_options(
        LinearReaderOptions::default()
            .with_validate_chunk_crcs(true)
            .with_validate_data_section_crc(true)
            .with_validate_summary_section_crc(true)
            .with_check_finishes_after_end_magic(true)
            .with_record_length_limit(RECORD_LIMIT),
    );
    let mut topics: BTreeMap<u16, String> = BTreeMap::new();
    let mut scenarios: Vec<ScenarioRecord> = Vec::new();
    let mut outcomes: Vec<OutcomeRecord> = Vec::new();
    let mut verdicts: Vec<VerdictRecord> = Vec::new();
    let mut counts: BTreeMap<String, u64> = BTreeMap::new();
    let mut attachments: BTreeMap<String, Vec<u8>> = BTreeMap::new();
    let mut step_counts: BTreeMap<usize, WorldMetrics> = BTreeMap::new();
    let mut malformed: Option<ReadError> = None;
    let mut offset = 0;
    while let Some(event) = reader.next_event() {
        match event? {
            LinearReadEvent::ReadRequest(wanted) => {
                let take = wanted.min(bytes.len() - offset);
                reader.insert(take).copy_from_slice(&bytes[offset..offset + take]);
                offset += take;
                reader.notify_read(take);
            }
            LinearReadEvent::Record { opcode, data } => {
                lengths::check(opcode, data).map_err(ReadError::Damaged)?;
                match mcap::parse_record(opcode, data)? {
                    Record::Channel(channel) => {
                        topics.insert(channel.id, channel.topic);
                    }
                    Record::Attachment { header, data, .. } => {
                        attachments.insert(header.name, data.into_owned());
                    }
                    Record::Message { header, data } => {
                        let Some(name) = topics.get(&header.channel_id) else {
                            return Err(ReadError::Mcap(mcap::McapError::UnknownChannel(
                                header.sequence,
                                header.channel_id,
                            )));
                        };
                        let count = counts.entry(name.clone()).or_default();
                        *count += 1;
                        let index = *count as usize;
                        // A chunk's CRC is checked once the chunk is read, after its
                        // messages: a message that does not decode is reported only
                        // when the container around it is intact (a damaged byte is
                        // damage, not a malformed message).
                        let first = &mut malformed;
                        match name.as_str() {
                            topic::SCENARIO => scenarios.extend(kept(decode(topic::SCENARIO, index, &data), first)),
                            topic::OUTCOME => outcomes.extend(kept(decode(topic::OUTCOME, index, &data), first)),
                            topic::VERDICTS => verdicts.extend(kept(decode(topic::VERDICTS, index, &data), first)),
                            topic::SIGNALS => {
                                let decoded = kept(decode::<SignalsRecord>(topic::SIGNALS, index, &data), first);
                                let Some(signals) = decoded else { continue };
                                if let Some(cells) = signals.cells {
                                    let tally = CellTally {
                                        occupied: cells.occupied,
                                        detected: cells.detected,
                                        ego_detected: cells.ego_detected,
                                        false_positives: cells.false_positives,
                                        blind_occupied: cells.blind_occupied,
                                        blind_detected: cells.blind_detected,
                                        footprint_only: cells.footprint_only,
                                        self_report: cells.self_report,
                                        self_report_detected: cells.self_report_detected,
                                        self_report_only: cells.self_report_only,
                                    };
                                    step_counts.entry(signals.point).or_default().add_step(
                                        cells.ego_observed,
                                        cells.joint_observed,
                                        &tally,
                                    );
                                }
                            }
                            _ => {}
                        }
                    }
                    _ => {}
                }
            }
        }
    }
    if let Some(error) = malformed {
        return Err(error);
    }
    let scenario = match <[ScenarioRecord; 1]>::try_from(scenarios) {
        Ok([scenario]) => scenario,
        Err(found) => {
            return Err(ReadError::NotSightline(format!(
                "expected one message on {}, found {}",
                topic::SCENARIO,
                found.len()
            )));
        }
    };
    if scenario.format != RECORDING_FORMAT {
        return Err(ReadError::NotSightline(format!(
            "its format is `{}`; this sightline reads `{RECORDING_FORMAT}`",
            scenario.format
        )));
    }
    if sha256_hex(scenario.text.as_bytes()) != scenario.sha256 {
        return Err(ReadError::Inconsistent(format!(
            "the scenario text does not match its SHA-256 {}",
            scenario.sha256
        )));
    }
    let mut imports = BTreeMap::new();
    for import in &scenario.imports {
        let Some(bytes) = attachments.remove(&import.path) else {
            return Err(ReadError::Inconsistent(format!(
                "the imported file {} is not attached",
                import.path
            )));
        };
        if sha256_hex(&bytes) != import.sha256 {
            return Err(ReadError::Inconsistent(format!(
                "the attached {} does not match its SHA-256 {}",
                import.path, import.sha256
            )));
        }
        imports.insert(import.path.clone(), bytes);
    }
    if let Some(point) = step_counts
        .keys()
        .find(|&&point| !scenario.points.iter().any(|p| p.point == point))
    {
        return Err(ReadError::Inconsistent(format!(
            "it holds steps of point {point}, which it does not list as recorded"
        )));
    }
    outcomes.sort_by_key(|o| o.point);
    if let Some((i, outcome)) = outcomes.iter().enumerate().find(|(i, o)| o.point != *i) {
        return Err(ReadError::Inconsistent(format!(
            "the outcome of point {i} is missing or repeated (found point {} in its place)",
            outcome.point
        )));
    }
    Ok(Recording {
        scenario,
        imports,
        outcomes,
        verdicts,
        counts,
        step_counts,
    })
}

fn decode<T: DeserializeOwned>(topic: &'static str, index: usize, data: &[u8]) -> Result<T, ReadError> {
    serde_json::from_slice(data).map_err(|error| ReadError::Message { topic, index, error })
}

/// The decoded message, or `None` with its error kept in `first` (the first one
/// only).
fn kept<T>(message: Result<T, ReadError>, first: &mut Option<ReadError>) -> Option<T> {
    message.map_err(|error| first.get_or_insert(error)).ok()
}

/// The recorded measurements of every point, for the oracles.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordedRun {
    points: Vec<RecordedPoint>,
}

/// One point's recorded measurements.
#[derive(Debug, Clone, PartialEq)]
struct RecordedPoint {
    /// Per run: the point's own, then each replicate's metrics.
    metrics: Vec<Vec<(Metric, Sample)>>,
    audit: Option<MassAudit>,
    series: Vec<(Signal, Vec<Series>)>,
    per_object: Vec<(ObjectProperty, ObjectSelection, Vec<RoadUserValue>)>,
}

impl Measurements for RecordedRun {
    fn sample(&self, point: usize, replicate: usize, metric: Metric) -> Option<Sample> {
        let metrics = self.points.get(point)?.metrics.get(replicate)?;
        metrics.iter().find(|(m, _)| *m == metric).map(|&(_, s)| s)
    }

    /// Nothing: a run with a system under test, the only one whose metrics
    /// select object-steps, is never recorded (`run` refuses `--record`).
    fn selected_sample(&self, _: usize, _: Metric, _: &ObjectSelection) -> Option<Sample> {
        None
    }

    fn audit(&self, point: usize) -> Option<MassAudit> {
        self.points.get(point)?.audit
    }

    fn series(&self, point: usize, signal: Signal) -> Option<Vec<Series>> {
        let point = self.points.get(point)?;
        point
            .series
            .iter()
            .find(|(s, _)| *s == signal)
            .map(|(_, runs)| runs.clone())
    }

    fn per_object(
        &self,
        point: usize,
        property: ObjectProperty,
        selection: &ObjectSelection,
    ) -> Option<Vec<RoadUserValue>> {
        let point = self.points.get(point)?;
        point
            .per_object
            .iter()
            .find(|(p, s, _)| *p == property && s == selection)
            .map(|(_, _, v)| v.clone())
    }
}

impl Recording {
    /// The recorded measurements of a scenario of `points` sweep points, once
    /// the recording is checked against itself: one outcome per point, and, for
    /// a perception world, each recorded point's steps adding up to the metrics
    /// its outcome holds.
    pub fn measurements(&self, points: usize) -> Result<RecordedRun, ReadError> {
        if self.outcomes.len() != points {
            return Err(ReadError::Inconsistent(format!(
                "it holds the outcomes of {} points, and its scenario has {points}",
                self.outcomes.len()
            )));
        }
        let run = RecordedRun {
            points: self
                .outcomes
                .iter()
                .map(|o| {
                    let metrics = |values: &[MetricValue]| {
                        values
                            .iter()
                            .map(|m| {
                                let sample = Sample {
                                    value: m.value.map(|r| r.0),
                                    n: m.n,
                                };
                                (m.metric, sample)
                            })
                            .collect()
                    };
                    RecordedPoint {
                        metrics: std::iter::once(&o.metrics)
                            .chain(o.replicates.iter().map(|r| &r.metrics))
                            .map(|values| metrics(values))
                            .collect(),
                        audit: o.audit.map(MassAudit::from),
                        series: o
                            .series
                            .iter()
                            .map(|s| {
                                let runs = s
                                    .runs
                                    .iter()
                                    .map(|run| run.samples.iter().map(|s| (s.time.0, s.value.0)).collect())
                                    .collect();
                                (s.signal, runs)
                            })
                            .collect(),
                        per_object: o
                            .per_object
                            .iter()
                            .map(|p| {
                                let values = (p.values.iter())
                                    .map(|v| RoadUserValue {
                                        who: v.who.clone(),
                                        value: v.value.map(|r| r.0),
                                    })
                                    .collect();
                                (p.property, p.selection.clone(), values)
                            })
                            .collect(),
                    }
                })
                .collect(),
        };
        for (&point, steps) in &self.step_counts {
            for metric in WORLD_STEP_METRICS {
                let (summed, recorded) = (steps.value(metric), run.sample(point, 0, metric).and_then(|s| s.value));
                if summed.map(f64::to_bits) != recorded.map(f64::to_bits) {
                    return Err(ReadError::Inconsistent(format!(
                        "the steps of point {point} give {} = {}, and its outcome holds {}",
                        metric.name(),
                        shown(summed),
                        shown(recorded)
                    )));
                }
            }
        }
        Ok(run)
    }
}

fn shown(value: Option<f64>) -> String {
    value.map_or_else(|| "nothing".into(), |v| v.to_string())
}
