//! `sightline run FILE… [--out DIR] [--seed N] [--jobs N] [--record] [--template DIR] [--shard K/N]`

use std::collections::HashSet;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use anyhow::Context;
use sightline_engine::Run;
use sightline_oracles::Verdict;
use sightline_reports::mcap::{Recorder, Source};
use sightline_reports::{Execution, Page, Provenance, RecordingInfo, Templates, Tool, render, sha256_hex};
use tempfile::NamedTempFile;

use crate::cli::RunArgs;
use crate::exit::Exit;
use crate::input::{Input, load_all};
use crate::output::{default_dir, progress, staging_file, stem, write_atomically};
use crate::summary::{print_verdicts, refuse_out_of_domain};
use crate::template::templates;

/// The recording's name in the evidence directory.
pub const RECORDING: &str = "run.mcap";

/// How a run was asked for, as its evidence and its recording say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    /// `--seed`.
    pub seed: Option<u64>,
    /// `--record`.
    pub record: bool,
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

/// Validates every file and the template set first (reporting every problem;
/// nothing is written if one is invalid), then runs each scenario (or, with
/// `--shard`, its slice) and writes its evidence.
pub fn run(args: &RunArgs) -> anyhow::Result<Exit> {
    let request = Request {
        seed: args.seed,
        record: args.record,
    };
    let inputs = load_all(&args.files, request.seed, request.record);
    let templates = templates(args.template.as_deref(), Page::Run);
    let (Some(inputs), Some(templates)) = (inputs, templates) else {
        return Ok(Exit::Invalid);
    };
    let Some(dirs) = evidence_dirs(args.out.as_deref(), &inputs) else {
        return Ok(Exit::Invalid);
    };
    let pool = worker_pool(args.jobs)?;
    if let Some(shard) = args.shard {
        return super::shard::run_shard(&pool, shard, &inputs, &dirs, request);
    }
    let reporting = Reporting {
        tool: tool(),
        request,
        templates: &templates,
    };
    let mut exit = Exit::Pass;
    for (input, dir) in inputs.iter().zip(&dirs) {
        let scenario = &input.scenario;
        let (started, clock) = (SystemTime::now(), Instant::now());
        let bar = progress(scenario.points.len(), &input.path.display().to_string());
        let mut done = |n: usize| bar.inc(n as u64);
        let simulated = match scenario.record {
            None => {
                let run = pool.install(|| sightline_engine::simulate_reporting(scenario, &mut done));
                let verdicts = sightline_oracles::check(scenario, &run);
                (run, verdicts, None)
            }
            Some(record) => recorded(input, &reporting, dir, |recorder| {
                Ok(pool.install(|| sightline_engine::simulate_traced(scenario, record.point, recorder, &mut done)))
            })?,
        };
        bar.finish_and_clear();
        // A value outside its domain is a defect of the engine: never judged.
        let why = "no correct simulation gives such a value, a defect in sightline; nothing is judged";
        if let Some(exit) = refuse_out_of_domain(&input.path.display(), scenario, &simulated.0, why) {
            return Ok(exit);
        }
        let execution = Execution::on_this_machine(pool.current_num_threads(), started, clock.elapsed());
        exit = exit.max(write_evidence(input, &reporting, dir, simulated, execution)?);
    }
    Ok(exit)
}

/// The worker threads: `jobs` of them, or one per core.
pub fn worker_pool(jobs: Option<u16>) -> anyhow::Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.map_or(0, usize::from))
        .build()
        .context("failed to start worker threads")
}

/// This build of sightline.
pub fn tool() -> Tool {
    Tool {
        name: "sightline".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        git: env!("SIGHTLINE_GIT").into(),
    }
}

/// A run, its verdicts, and its recording (staged in the evidence directory,
/// with what results.json says of it) when the scenario asks for one.
pub type Simulated = (Run, Vec<Verdict>, Option<(NamedTempFile, RecordingInfo)>);

/// Renders the evidence of a simulated `input` into `dir`, atomically, and
/// prints its verdicts; [`Exit::Pass`] when every requirement holds, and
/// [`Exit::Invalid`] (nothing written) when a custom template fails on the data.
pub fn write_evidence(
    input: &Input,
    reporting: &Reporting<'_>,
    dir: &Path,
    (run, verdicts, recording): Simulated,
    execution: Execution,
) -> anyhow::Result<Exit> {
    let scenario = &input.scenario;
    let path = input.path.display().to_string();
    let provenance = Provenance {
        tool: reporting.tool.clone(),
        scenario_path: path.clone(),
        scenario_sha256: sha256_hex(&input.bytes),
        recording: recording.as_ref().map(|(_, info)| info.clone()),
        execution,
    };
    let mut reproduce = match scenario.points.iter().map(|p| p.setup.seed).collect::<HashSet<_>>() {
        seeds if seeds.len() == 1 => format!("sightline run {path} --seed {}", scenario.points[0].setup.seed),
        _ => format!("sightline run {path}"),
    };
    if reporting.request.record {
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
    write_atomically(
        dir,
        &[
            ("results.json", &evidence.results_json),
            ("junit.xml", &evidence.junit_xml),
            ("report.html", &evidence.report_html),
        ],
        recording.map(|(file, _)| (file, RECORDING)).into_iter().collect(),
    )?;
    Ok(print_verdicts(
        &path,
        scenario,
        &verdicts,
        format_args!("-> {}", dir.display()),
    ))
}

/// Records `input`'s `record` point into a staging file in `dir` while
/// `simulate` runs the scenario with the recorder as its sink, then checks the
/// run and finishes the recording with its outcomes and verdicts.
pub fn recorded(
    input: &Input,
    reporting: &Reporting<'_>,
    dir: &Path,
    simulate: impl FnOnce(&mut Recorder<'_, BufWriter<&std::fs::File>>) -> anyhow::Result<Run>,
) -> anyhow::Result<Simulated> {
    let scenario = &input.scenario;
    let record = scenario.record.context("the scenario records nothing")?;
    let file = staging_file(dir)?;
    let failed = || format!("failed to write {}", dir.join(RECORDING).display());
    let text = std::str::from_utf8(&input.bytes).context("the scenario file is not UTF-8 text")?;
    let source = Source {
        tool: &reporting.tool,
        file: &input.path.display().to_string(),
        text,
        seed: reporting.request.seed,
        record_flag: reporting.request.record,
    };
    let mut recorder = Recorder::new(BufWriter::new(file.as_file()), scenario, record, &source).with_context(failed)?;
    let run = simulate(&mut recorder)?;
    let verdicts = sightline_oracles::check(scenario, &run);
    recorder
        .finish(&run, &verdicts)
        .with_context(failed)?
        .flush()
        .with_context(failed)?;
    // The hash is of the bytes on disk: the MCAP writer seeks back as it writes.
    let bytes = std::fs::read(file.path()).with_context(failed)?;
    let info = RecordingInfo {
        file: RECORDING.into(),
        sha256: sha256_hex(&bytes),
        point: record.point,
        label: scenario.points[record.point].label(),
    };
    Ok((run, verdicts, Some((file, info))))
}

/// Where each scenario's evidence goes (`out` with one scenario, `out/STEM/`
/// with several, `out/STEM/` under the working directory without `out`); `None`
/// (after printing why) when two scenarios would share a directory.
pub fn evidence_dirs<'a>(out: Option<&Path>, inputs: impl IntoIterator<Item = &'a Input>) -> Option<Vec<PathBuf>> {
    let files: Vec<&Path> = inputs.into_iter().map(|i| i.path.as_path()).collect();
    let dirs: Vec<PathBuf> = match (out, files.len()) {
        (Some(out), 1) => vec![out.to_path_buf()],
        (Some(out), _) => files.iter().map(|f| out.join(stem(f))).collect(),
        (None, _) => files.iter().map(|f| default_dir(f)).collect(),
    };
    let mut seen = HashSet::new();
    for (dir, file) in dirs.iter().zip(&files) {
        if !seen.insert(dir) {
            eprintln!(
                "{}: error: its evidence would overwrite another scenario's in {}; run the files separately with --out",
                file.display(),
                dir.display()
            );
            return None;
        }
    }
    Some(dirs)
}
