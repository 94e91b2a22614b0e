//! `sightline run FILE… [--out DIR] [--seed N] [--jobs N] [--record] [--template DIR]`

use std::collections::HashSet;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use anyhow::Context;
use sightline_engine::Run;
use sightline_oracles::Verdict;
use sightline_reports::mcap::{Recorder, Source};
use sightline_reports::{Execution, Page, Provenance, RecordingInfo, Tool, render, sha256_hex};
use tempfile::NamedTempFile;

use crate::cli::RunArgs;
use crate::exit::Exit;
use crate::input::{Input, load_all};
use crate::output::{default_dir, progress, staging_file, stem, write_atomically};
use crate::summary::print_verdicts;
use crate::template::templates;

/// The recording's name in the evidence directory.
pub const RECORDING: &str = "run.mcap";

/// Validates every file and the template set first (reporting every problem;
/// nothing is written if one is invalid), then runs each scenario and writes
/// its evidence.
pub fn run(args: &RunArgs) -> anyhow::Result<Exit> {
    let inputs = load_all(&args.files, args.seed, args.record);
    let templates = templates(args.template.as_deref(), Page::Run);
    let (Some(inputs), Some(templates)) = (inputs, templates) else {
        return Ok(Exit::Invalid);
    };
    let Some(dirs) = evidence_dirs(args, &inputs) else {
        return Ok(Exit::Invalid);
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.jobs.map_or(0, usize::from))
        .build()
        .context("failed to start worker threads")?;
    let mut exit = Exit::Pass;
    for (input, dir) in inputs.iter().zip(&dirs) {
        let scenario = &input.scenario;
        let path = input.path.display().to_string();
        let tool = Tool {
            name: "sightline".into(),
            version: env!("CARGO_PKG_VERSION").into(),
            git: env!("SIGHTLINE_GIT").into(),
        };
        let (started, clock) = (SystemTime::now(), Instant::now());
        let (run, verdicts, recording) = simulate(&pool, input, &tool, args, dir)?;
        let provenance = Provenance {
            tool,
            scenario_path: path.clone(),
            scenario_sha256: sha256_hex(&input.bytes),
            recording: recording.as_ref().map(|(_, info)| info.clone()),
            execution: Execution::on_this_machine(pool.current_num_threads(), started, clock.elapsed()),
        };
        let mut reproduce = match scenario.points.iter().map(|p| p.setup.seed).collect::<HashSet<_>>() {
            seeds if seeds.len() == 1 => format!("sightline run {path} --seed {}", scenario.points[0].setup.seed),
            _ => format!("sightline run {path}"),
        };
        if args.record {
            reproduce.push_str(" --record");
        }
        let evidence = match render(scenario, &run, &verdicts, &provenance, &reproduce, &templates) {
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
        if print_verdicts(&path, scenario, &verdicts, format_args!("-> {}", dir.display())) != Exit::Pass {
            exit = Exit::Fail;
        }
    }
    Ok(exit)
}

/// A run, its verdicts, and its recording (staged in `dir`, with what
/// results.json says of it) when the scenario asks for one.
type Simulated = (Run, Vec<Verdict>, Option<(NamedTempFile, RecordingInfo)>);

/// Simulates and checks `input`; records its `record` point into a staging file
/// in `dir` as the engine runs, when it has one.
fn simulate(
    pool: &rayon::ThreadPool,
    input: &Input,
    tool: &Tool,
    args: &RunArgs,
    dir: &Path,
) -> anyhow::Result<Simulated> {
    let scenario = &input.scenario;
    let bar = progress(scenario.points.len(), &input.path.display().to_string());
    let mut done = |n: usize| bar.inc(n as u64);
    let Some(record) = scenario.record else {
        let run = pool.install(|| sightline_engine::simulate_reporting(scenario, &mut done));
        bar.finish_and_clear();
        let verdicts = sightline_oracles::check(scenario, &run);
        return Ok((run, verdicts, None));
    };
    let file = staging_file(dir)?;
    let failed = || format!("failed to write {}", dir.join(RECORDING).display());
    let text = std::str::from_utf8(&input.bytes).context("the scenario file is not UTF-8 text")?;
    let source = Source {
        tool,
        file: &input.path.display().to_string(),
        text,
        seed: args.seed,
        record_flag: args.record,
    };
    let mut recorder = Recorder::new(BufWriter::new(file.as_file()), scenario, record, &source).with_context(failed)?;
    let run = pool.install(|| sightline_engine::simulate_traced(scenario, record.point, &mut recorder, &mut done));
    bar.finish_and_clear();
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

/// Where each scenario's evidence goes; `None` (after printing why) when two
/// scenarios would share a directory.
fn evidence_dirs(args: &RunArgs, inputs: &[Input]) -> Option<Vec<PathBuf>> {
    let dirs: Vec<PathBuf> = match (&args.out, inputs.len()) {
        (Some(out), 1) => vec![out.clone()],
        (Some(out), _) => inputs.iter().map(|i| out.join(stem(&i.path))).collect(),
        (None, _) => inputs.iter().map(|i| default_dir(&i.path)).collect(),
    };
    let mut seen = HashSet::new();
    for (dir, input) in dirs.iter().zip(inputs) {
        if !seen.insert(dir) {
            eprintln!(
                "{}: error: its evidence would overwrite another scenario's in {}; run the files separately with --out",
                input.path.display(),
                dir.display()
            );
            return None;
        }
    }
    Some(dirs)
}
