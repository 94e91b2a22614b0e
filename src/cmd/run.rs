//! `sightline run FILE… [--out DIR] [--seed N] [--jobs N]`

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use anyhow::Context;
use sightline_oracles::Status;
use sightline_reports::{Provenance, Tool, render, sha256_hex};

use crate::cli::RunArgs;
use crate::exit::Exit;
use crate::input::{Input, load_all};
use crate::output::{say, write_atomically};

/// Validates every file first (nothing is written if one is invalid), then runs
/// each scenario and writes its evidence.
pub fn run(args: &RunArgs) -> anyhow::Result<Exit> {
    let Some(inputs) = load_all(&args.files, args.seed, args.record) else {
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
        let run = pool.install(|| sightline_engine::simulate(scenario));
        let verdicts = sightline_oracles::check(scenario, &run);
        let path = input.path.display().to_string();
        let provenance = Provenance {
            tool: Tool {
                name: "sightline".into(),
                version: env!("CARGO_PKG_VERSION").into(),
                git: env!("SIGHTLINE_GIT").into(),
            },
            scenario_path: path.clone(),
            scenario_sha256: sha256_hex(&input.bytes),
        };
        let reproduce = match scenario.points.iter().map(|p| p.setup.seed).collect::<HashSet<_>>() {
            seeds if seeds.len() == 1 => format!("sightline run {path} --seed {}", scenario.points[0].setup.seed),
            _ => format!("sightline run {path}"),
        };
        let evidence = render(scenario, &run, &verdicts, &provenance, &reproduce)?;
        write_atomically(
            dir,
            &[
                ("results.json", &evidence.results_json),
                ("junit.xml", &evidence.junit_xml),
                ("report.html", &evidence.report_html),
            ],
        )?;
        let summary = evidence.results.summary;
        let verdict = evidence.results.verdict.name().to_uppercase();
        say(format_args!(
            "{verdict} {path}: {} of {} requirements hold over {} sweep point{} -> {}",
            summary.passed,
            summary.requirements,
            scenario.points.len(),
            if scenario.points.len() == 1 { "" } else { "s" },
            dir.display()
        ));
        for requirement in evidence
            .results
            .requirements
            .iter()
            .filter(|r| r.verdict != Status::Pass)
        {
            say(format_args!(
                "  {} {}: {}",
                requirement.verdict.name(),
                requirement.id,
                requirement.message
            ));
        }
        if evidence.results.verdict != Status::Pass {
            exit = Exit::Fail;
        }
    }
    Ok(exit)
}

/// Where each scenario's evidence goes; `None` (after printing why) when two
/// scenarios would share a directory.
fn evidence_dirs(args: &RunArgs, inputs: &[Input]) -> Option<Vec<PathBuf>> {
    let stem = |path: &Path| path.file_stem().map_or_else(|| "scenario".into(), |s| s.to_os_string());
    let dirs: Vec<PathBuf> = match (&args.out, inputs.len()) {
        (Some(out), 1) => vec![out.clone()],
        (Some(out), _) => inputs.iter().map(|i| out.join(stem(&i.path))).collect(),
        (None, _) => inputs.iter().map(|i| Path::new("out").join(stem(&i.path))).collect(),
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
