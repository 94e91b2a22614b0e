//! A scenario's evidence, shared by `run`, `run --shard` and `merge`: how the run
//! was asked for, this build, the recording staged with the evidence, and the
//! evidence set committed into its directory as a whole (see `staging`).

use std::collections::HashSet;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::Context;
use sightline_dsl::{Record, RecordedPoints, Scenario};
use sightline_engine::Run;
use sightline_engine::TraceSink;
use sightline_engine::trace::{SemanticStep, WorldStep};
use sightline_oracles::{Status, Verdict};
use sightline_reports::mcap::{Recorder, Source};
use sightline_reports::osi::{OSI_TRACE, OsiTrace};
use sightline_reports::{
    Execution, OsiTraceInfo, Provenance, RecordingInfo, Templates, Tool, render, sha256_hex, sha256_hex_of,
};

use crate::exit::Exit;
use crate::input::Input;
use crate::output::{default_dir, stem};
use crate::staging::Staging;
use crate::summary::print_verdicts;

/// The recording's name in the evidence directory.
pub const RECORDING: &str = "run.mcap";

/// Every file of a scenario's evidence set, `run`'s, `merge`'s and `falsify`'s
/// alike: a new set replaces all of them, so that no file of an earlier set (a
/// `run.mcap` when the new run records nothing, `falsify`'s files after a `run`,
/// a `counterexample.yaml` after a search that found none) stays beside it.
pub const EVIDENCE_SET: &[&str] = &[
    "results.json",
    "junit.xml",
    "report.html",
    RECORDING,
    OSI_TRACE,
    "falsify.json",
    "counterexample.yaml",
];

/// How a run was asked for, as its evidence and its recording say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    /// `--seed`.
    pub seed: Option<u64>,
    /// `--record` (or `--osi`, which implies it).
    pub record: bool,
    /// `--osi`.
    pub osi: bool,
}

/// What the evidence of every scenario of a command shares.
pub struct Reporting<'t> {
    /// This build of sightline.
    pub tool: Tool,
    /// How the run was asked for.
    pub request: Request,
    /// The page templates.
    pub templates: &'t Templates,
}

/// This build of sightline.
pub fn tool() -> Tool {
    Tool {
        name: "sightline".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        git: env!("SIGHTLINE_GIT").into(),
    }
}

/// A run, its verdicts, and what results.json says of its recording (staged
/// with the evidence) when the scenario asks for one.
pub type Simulated = (Run, Vec<Verdict>, Option<RecordingInfo>);

/// Renders the evidence of a simulated `input` into `staging` and commits it,
/// then prints its verdicts; [`Exit::Pass`] when every requirement holds, and
/// [`Exit::Invalid`] (nothing written) when a custom template fails on the data.
pub fn write_evidence(
    input: &Input,
    reporting: &Reporting<'_>,
    mut staging: Staging,
    (run, verdicts, recording): Simulated,
    execution: Execution,
) -> anyhow::Result<Exit> {
    let scenario = &input.scenario;
    let path = &input.name;
    let provenance = Provenance {
        tool: reporting.tool.clone(),
        scenario_path: path.clone(),
        scenario_sha256: sha256_hex(&input.bytes),
        scenario_text: String::from_utf8_lossy(&input.bytes).into_owned(),
        recording,
        execution,
    };
    // The command as typed: `-` for standard input.
    let given = input.path.display();
    let mut reproduce = match scenario.points.iter().map(|p| p.setup.seed).collect::<HashSet<_>>() {
        seeds if seeds.len() == 1 => format!("sightline run {given} --seed {}", scenario.points[0].setup.seed),
        _ => format!("sightline run {given}"),
    };
    if reporting.request.osi {
        reproduce.push_str(" --osi");
    } else if reporting.request.record {
        reproduce.push_str(" --record");
    }
    let templates = reporting.templates;
    let evidence = match render(scenario, &run, &verdicts, &provenance, &reproduce, templates) {
        Ok(evidence) => evidence,
        // A custom template that fails on the data is the input's fault.
        Err(sightline_reports::Error::Template(error)) if templates.is_custom() => {
            eprintln!("{error}");
            return Ok(Exit::Invalid);
        }
        Err(error) => return Err(error.into()),
    };
    staging.write("results.json", evidence.results_json.as_bytes())?;
    staging.write("junit.xml", evidence.junit_xml.as_bytes())?;
    staging.write("report.html", evidence.report_html.as_bytes())?;
    let dir = staging.dir().to_path_buf();
    staging.commit()?;
    Ok(print_verdicts(
        path,
        scenario,
        &verdicts,
        format_args!("-> {}", dir.display()),
    ))
}

/// The recording of `record`'s point, when the file names it (or the scenario
/// has one point); otherwise of the worst point of the first failing
/// requirement of a run judged `verdicts`, or of the first point when none
/// fails.
pub fn recorded_point(scenario: &Scenario, record: Record, verdicts: &[Verdict]) -> Record {
    if record.named || record.points == RecordedPoints::All {
        return record;
    }
    let worst = verdicts
        .iter()
        .find(|v| v.status == Status::Fail)
        .map(|v| v.decisive.point);
    record.at_point(&scenario.points, worst.unwrap_or(record.point))
}

/// Simulates what `record` records of `input`'s scenario again (one point, or
/// only its first run where it pools several runs of the semantic pipeline;
/// every point), reporting its steps to `recorder`, and returns `run` once
/// what it holds of them is found the same, bit for bit.
pub fn resimulated(input: &Input, record: Record, run: Run, recorder: &mut impl TraceSink) -> anyhow::Result<Run> {
    let same = match record.points {
        RecordedPoints::One => run.points[record.point].holds_recorded(&sightline_engine::simulate_recorded(
            &input.scenario,
            record.point,
            recorder,
        )),
        RecordedPoints::All => sightline_engine::simulate_traced_all(&input.scenario, recorder, &mut |_| {}) == run,
    };
    if !same {
        anyhow::bail!(
            "{}: the recorded points, simulated again, differ from the run's outcomes: \
             sightline is not deterministic here; please report it with the scenario",
            input.name
        );
    }
    Ok(run)
}

/// What a recorded point's steps are written to: the recording, and the OSI
/// trace with `--osi`.
pub struct Sinks<'s, 'f> {
    recorder: Recorder<'s, BufWriter<&'f std::fs::File>>,
    osi: Option<OsiTrace<BufWriter<&'f std::fs::File>>>,
}

impl TraceSink for Sinks<'_, '_> {
    fn point(&mut self, point: usize) {
        // `--osi` with every point recorded is refused before the run.
        self.recorder.point(point);
    }

    fn start(&mut self, agents: &[sightline_dsl::Agent]) {
        self.recorder.start(agents);
        if let Some(osi) = &mut self.osi {
            osi.start(agents);
        }
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.recorder.wants_grids(step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.recorder.world_step(step);
        if let Some(osi) = &mut self.osi {
            osi.world_step(step);
        }
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.recorder.semantic_step(step);
        if let Some(osi) = &mut self.osi {
            osi.semantic_step(step);
        }
    }
}

/// Records the points `record` names of `input`'s scenario into `staging`
/// (and, with `--osi`, the one point's OSI trace) while `simulate` runs the scenario with them
/// as its sink, then checks the run and finishes the recording with its
/// outcomes and verdicts.
pub fn recorded(
    input: &Input,
    reporting: &Reporting<'_>,
    staging: &mut Staging,
    record: Record,
    simulate: impl FnOnce(&mut Sinks<'_, '_>) -> anyhow::Result<Run>,
) -> anyhow::Result<Simulated> {
    let scenario = &input.scenario;
    let file = staging.create(RECORDING)?;
    let osi_file = match reporting.request.osi {
        true => Some(staging.create(OSI_TRACE)?),
        false => None,
    };
    let failed = |name: &str| format!("failed to write {}", staging.dir().join(name).display());
    let text = std::str::from_utf8(&input.bytes).context("the scenario file is not UTF-8 text")?;
    let source = Source {
        tool: &reporting.tool,
        file: &input.name,
        text,
        seed: reporting.request.seed,
        record_flag: reporting.request.record,
    };
    let recorder =
        Recorder::new(BufWriter::new(&file), scenario, record, &source).with_context(|| failed(RECORDING))?;
    let osi = match &osi_file {
        Some(osi_file) => Some(
            OsiTrace::new(BufWriter::new(osi_file), scenario, record, &input.name)
                .with_context(|| failed(OSI_TRACE))?,
        ),
        None => None,
    };
    let mut sinks = Sinks { recorder, osi };
    let run = simulate(&mut sinks)?;
    let verdicts = sightline_oracles::check(scenario, &run);
    let Sinks { recorder, osi } = sinks;
    recorder
        .finish(&run, &verdicts)
        .with_context(|| failed(RECORDING))?
        .flush()
        .with_context(|| failed(RECORDING))?;
    let osi_trace = match osi {
        Some(osi) => {
            osi.finish()
                .with_context(|| failed(OSI_TRACE))?
                .flush()
                .with_context(|| failed(OSI_TRACE))?;
            Some(OsiTraceInfo {
                file: OSI_TRACE.into(),
                sha256: staged_sha256(staging, OSI_TRACE).with_context(|| failed(OSI_TRACE))?,
            })
        }
        None => None,
    };
    let info = RecordingInfo {
        file: RECORDING.into(),
        sha256: staged_sha256(staging, RECORDING).with_context(|| failed(RECORDING))?,
        point: record.point,
        label: scenario.points[record.point].label(),
        every_point: record.points == RecordedPoints::All,
        osi_trace,
    };
    Ok((run, verdicts, Some(info)))
}

/// SHA-256 of the staged file `name` as it is on disk (MCAP writers seek back
/// as they write), lowercase hex.
fn staged_sha256(staging: &Staging, name: &str) -> std::io::Result<String> {
    sha256_hex_of(std::fs::File::open(staging.path(name))?)
}

/// Where each scenario's evidence goes (`out` with one scenario, `out/STEM/`
/// with several, `out/STEM/` under the working directory without `out`); `None`
/// (after printing why) when two scenarios would share a directory, or one read
/// from standard input has no `out`.
pub fn evidence_dirs<'a>(out: Option<&Path>, inputs: impl IntoIterator<Item = &'a Input>) -> Option<Vec<PathBuf>> {
    let inputs: Vec<&Input> = inputs.into_iter().collect();
    if out.is_none()
        && let Some(input) = inputs.iter().find(|i| i.is_stdin())
    {
        eprintln!(
            "{}: error: a scenario read from standard input has no file name to name its evidence directory after; give --out DIR",
            input.name
        );
        return None;
    }
    let dirs: Vec<PathBuf> = match (out, inputs.len()) {
        (Some(out), 1) => vec![out.to_path_buf()],
        (Some(out), _) => inputs.iter().map(|i| out.join(stem(&i.path))).collect(),
        (None, _) => inputs.iter().map(|i| default_dir(&i.path)).collect(),
    };
    let mut seen = HashSet::new();
    for (dir, input) in dirs.iter().zip(&inputs) {
        if !seen.insert(dir) {
            eprintln!(
                "{}: error: its evidence would overwrite another scenario's in {}; run the files separately with --out",
                input.name,
                dir.display()
            );
            return None;
        }
    }
    Some(dirs)
}
