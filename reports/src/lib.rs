//! sightline's evidence: `results.json`, `junit.xml`, `report.html` and
//! `run.mcap` of a run, `falsify.json` and `report.html` of a falsification, and
//! the shard files of a run split across machines.
//!
//! This crate maps a compiled scenario, its run and its verdicts to bytes. It owns
//! the wire formats (see [`Results`] and [`mcap`]) and the page templates (see
//! [`Templates`]: the bundled ones, or an organisation's set, checked before
//! anything runs); it does not open files (the CLI hands it a writer, or a
//! [`Loader`] for a template set, and renames what it wrote into place
//! atomically) and it does not judge (that is `sightline-oracles`).
//!
//! results.json is written from types defined here, not from the engine's, the
//! language's or the oracles' structs: [`Results`] and the types it is made of
//! (requirements and their [`Status`], points and their [`Detail`], the counts
//! behind the metrics, provenance) are filled from a run in one module
//! (`results::from_run`), so renaming a field elsewhere cannot change the
//! evidence. Its format is versioned ([`FORMAT`]) and its JSON Schema,
//! generated from these types by [`results_schema`], is published as
//! `docs/results.schema.json`.
//!
//! `sightline export` writes a scenario's world for other simulators:
//! [`export()`] simulates one sweep point and returns an ASAM OpenSCENARIO
//! scenario and its ASAM OpenDRIVE map (written formats belong here, beside
//! the evidence; the language owns only the compiled model they are made from).
//!
//! The recording is written as the engine runs: [`mcap::Recorder`] is a
//! [`TraceSink`](sightline_engine::TraceSink), and [`mcap::read`] reads it back
//! for `sightline replay`.
#![warn(missing_docs)]

pub use chart::{Chart, ChartError, Line, LinesChart, Threshold, anticipation, kde, silverman_bandwidth};
pub use execution::{Execution, rfc3339};
pub use export::{Export, ExportError, ExportRequest, OPENDRIVE_VERSION, OPENSCENARIO_VERSION, export};
pub use falsify::{Falsification, case_values, falsify_json, falsify_junit};
pub use falsify_html::falsify_html;
pub use html::{RunPage, html};
pub use junit::{junit, junit_xml};
pub use picture::{Legend, Picture, Pictures, Scale, Swatch, pictures};
pub use results::{
    Assumption, Axis, Band, CheckInfo, Conflict, Coverage, DeliveryBin, DensityRow, Detail, FORMAT, InputInfo,
    LabelCounts, LabelResult, MassAudit, Measured, MetricEntry, Ordered, OsiTraceInfo, OverSeeds, PointResult,
    PointVerdict, Provenance, RateBound, RecordingInfo, ReferencePoint, ReferenceResult, RequirementResult, Results,
    ScenarioInfo, SeedStatistics, SemanticCounts, Sightings, Statistic, Status, Summary, Sweep, SweepRow, Table, Tool,
    WorldCounts, results_schema,
};
pub use shard::{SHARD_FORMAT, Shard, ShardError, ShardInput, campaign_id, read_shard, shard_bytes};
pub use template::{Callee, Loader, Location, Page, TemplateError, TemplateErrorKind, Templates};

mod chart;
mod execution;
mod export;
mod falsify;
mod falsify_html;
mod html;
mod junit;
pub mod mcap;
pub mod osi;
mod picture;
mod results;
mod shard;
mod template;

use sha2::{Digest, Sha256};
use sightline_dsl::{Experiment, Scenario};
use sightline_engine::{Outcome, Run};
use sightline_oracles::Verdict;

/// The three evidence files of one scenario, rendered in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Evidence {
    /// The assembled results.
    pub results: Results,
    /// `results.json`.
    pub results_json: String,
    /// `junit.xml`.
    pub junit_xml: String,
    /// `report.html`.
    pub report_html: String,
}

/// Why evidence could not be rendered: a defect in sightline, or a custom
/// template that fails on the data.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The report template failed: a defect in sightline for the bundled
    /// templates, in the input for a custom set ([`Templates::is_custom`]).
    #[error(transparent)]
    Template(#[from] TemplateError),
    /// The JUnit serializer failed.
    #[error("failed to render junit.xml: {0}")]
    Junit(#[from] quick_junit::SerializeError),
    /// The JSON serializer failed.
    #[error("failed to render results.json: {0}")]
    Json(#[from] serde_json::Error),
    /// A grid picture could not be encoded.
    #[error("failed to draw a grid picture: {0}")]
    Picture(#[from] png::EncodingError),
    /// A chart could not be drawn.
    #[error(transparent)]
    Chart(#[from] ChartError),
}

/// Renders all evidence of a run, its report with `templates`. `reproduce` is
/// the command that re-creates it.
pub fn render(
    scenario: &Scenario,
    run: &Run,
    verdicts: &[Verdict],
    provenance: &Provenance,
    reproduce: &str,
    templates: &Templates,
) -> Result<Evidence, Error> {
    let results = Results::new(scenario, run, verdicts, provenance);
    let mut results_json = serde_json::to_string_pretty(&results)?;
    results_json.push('\n');
    let junit_xml = junit_xml(&junit(&results))?;
    let pictures = scenario
        .points
        .iter()
        .zip(&run.points)
        .map(
            |(point, outcome)| match (outcome, &point.setup.experiment, &point.setup.occupancy) {
                (Outcome::World(o), Experiment::World(world), Some(occupancy)) => o
                    .snapshot
                    .as_ref()
                    .map(|s| {
                        picture::pictures(
                            &occupancy.grid,
                            world.step,
                            s,
                            world.perception.as_ref().and_then(|p| p.region),
                            occupancy.fusion.rule.is_evidential(),
                        )
                    })
                    .transpose(),
                _ => Ok(None),
            },
        )
        .collect::<Result<Vec<_>, _>>()?;
    let charts = results
        .sweep
        .iter()
        .map(|point| match &point.detail {
            Detail::Semantic {
                counts,
                contribution_by_density,
                objects: _,
            } => chart::semantic_charts(counts, contribution_by_density),
            Detail::World { counts, semantic, .. } => {
                let mut charts: Vec<Chart> = chart::reliability_chart(&counts.calibration)?.into_iter().collect();
                if let Some(s) = semantic {
                    charts.extend(chart::semantic_charts(&s.counts, &s.contribution_by_density)?);
                }
                Ok(charts)
            }
            Detail::Field { .. } => Ok(Vec::new()),
        })
        .collect::<Result<Vec<Vec<Chart>>, ChartError>>()?;
    let sweep_charts = chart::sweep_charts(&results)?;
    let page = RunPage {
        scenario,
        text: &provenance.scenario_text,
        reproduce,
        pictures: &pictures,
        charts: &charts,
        sweep_charts: &sweep_charts,
    };
    let report_html = html(&results, &page, templates)?;
    Ok(Evidence {
        results,
        results_json,
        junit_xml,
        report_html,
    })
}

/// SHA-256 of `bytes` as lowercase hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

/// A writer that hashes what passes through it: a file's SHA-256 as it is
/// written, for an output written in order (as the recording's
/// [`Recorder`](mcap::Recorder) and the [`OsiTrace`](osi::OsiTrace) write
/// it), without reading the file back.
pub struct Sha256Writer<W> {
    inner: W,
    hasher: Sha256,
}

impl<W> Sha256Writer<W> {
    /// Hashes what is written into `inner`.
    pub fn new(inner: W) -> Self {
        Self {
            inner,
            hasher: Sha256::new(),
        }
    }

    /// The output, and [`sha256_hex`] of every byte it accepted.
    pub fn finish(self) -> (W, String) {
        (self.inner, hex(&self.hasher.finalize()))
    }
}

impl<W: std::io::Write> std::io::Write for Sha256Writer<W> {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        let written = self.inner.write(bytes)?;
        self.hasher.update(&bytes[..written]);
        Ok(written)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// `digest` as lowercase hex (an import's [`sha256`](sightline_dsl::Import::sha256), as the evidence names it).
pub fn hex(digest: &[u8]) -> String {
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Takes at most 5 bytes a write.
    struct Narrow(Vec<u8>);

    impl std::io::Write for Narrow {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            let n = buf.len().min(5);
            self.0.extend_from_slice(&buf[..n]);
            Ok(n)
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// What the output accepted, a few bytes at a time, is what is hashed.
    #[test]
    fn a_written_hash_is_the_hash_of_the_bytes_written() {
        use std::io::Write as _;
        let bytes: Vec<u8> = (0..70_001_u32).map(|i| (i * 17 % 253) as u8).collect();
        let mut out = Sha256Writer::new(Narrow(Vec::new()));
        out.write_all(b"abc").unwrap();
        out.write_all(&bytes).unwrap();
        let (Narrow(written), hash) = out.finish();
        assert_eq!(written, [&b"abc"[..], &bytes].concat());
        assert_eq!(hash, sha256_hex(&written));
        let (_, abc) = {
            let mut out = Sha256Writer::new(Vec::new());
            out.write_all(b"abc").unwrap();
            out.finish()
        };
        assert_eq!(abc, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }
}
