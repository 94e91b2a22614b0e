//! `sightline merge PATH… [--out DIR]`: the evidence of a sharded campaign.
//!
//! Everything is checked before anything is written: every shard file reads,
//! each scenario has shards 1 to N exactly once, from this build of sightline,
//! with the same `--seed` and `--record`, and its input files are unchanged;
//! the units then make up the run ([`sightline_engine::assemble`]). The
//! recording, when the scenario asks for one, is made here: its point is
//! simulated again, and must give the outcome its shard gave.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use anyhow::bail;
use sightline_engine::Run;
use sightline_reports::{Execution, Page, Shard, read_shard};

use super::run::{Reporting, Request, evidence_dirs, recorded, tool, write_evidence};
use super::shard::inputs_of;
use crate::cli::MergeArgs;
use crate::exit::Exit;
use crate::input::{Input, load_all};
use crate::template::templates;

/// One scenario of the campaign, ready to render.
struct Merged {
    input: Input,
    request: Request,
    run: Run,
    /// How each of its shards ran.
    shards: Vec<Execution>,
}

/// Reads and checks every shard and the template set, then writes each
/// scenario's evidence.
pub fn merge(args: &MergeArgs) -> anyhow::Result<Exit> {
    let merged = collect(&args.paths)
        .and_then(assemble_all)
        .inspect_err(|message| eprintln!("{message}"));
    let templates = templates(args.template.as_deref(), Page::Run);
    let (Ok(merged), Some(templates)) = (merged, templates) else {
        return Ok(Exit::Invalid);
    };
    let Some(dirs) = evidence_dirs(args.out.as_deref(), merged.iter().map(|m| &m.input)) else {
        return Ok(Exit::Invalid);
    };
    let mut exit = Exit::Pass;
    for (merged, dir) in merged.into_iter().zip(&dirs) {
        let (started, clock) = (SystemTime::now(), Instant::now());
        let Merged {
            input,
            request,
            run,
            shards,
        } = merged;
        let reporting = Reporting {
            tool: tool(),
            request,
            templates: &templates,
        };
        let scenario = &input.scenario;
        let simulated = match scenario.record {
            None => {
                let verdicts = sightline_oracles::check(scenario, &run);
                (run, verdicts, None)
            }
            Some(record) => recorded(&input, &reporting, dir, |recorder| {
                let outcome = sightline_engine::simulate_point(scenario, record.point, recorder);
                if outcome != run.points[record.point] {
                    bail!(
                        "{}: the recorded point, simulated again, differs from its shard's outcome: \
                         sightline is not deterministic here; please report it with the scenario",
                        input.path.display()
                    );
                }
                Ok(run)
            })?,
        };
        let here = Execution::on_this_machine(rayon::current_num_threads(), started, clock.elapsed());
        let execution = Execution::campaign(&shards, &here);
        exit = exit.max(write_evidence(&input, &reporting, dir, simulated, execution)?);
    }
    Ok(exit)
}

/// Every shard file in `paths` (files as given; directories searched with their
/// subdirectories for `shard-K-of-N.cbor`), read, in path order.
fn collect(paths: &[PathBuf]) -> Result<Vec<(PathBuf, Shard)>, String> {
    let mut files = Vec::new();
    for path in paths {
        if path.is_dir() {
            let before = files.len();
            find_shards(path, &mut files).map_err(|e| format!("{}: error: {e}", path.display()))?;
            if files.len() == before {
                return Err(format!(
                    "{}: error: no shard files (shard-K-of-N.cbor, written by `sightline run --shard K/N`) in it",
                    path.display()
                ));
            }
        } else {
            files.push(path.clone());
        }
    }
    files.sort();
    files.dedup();
    files
        .into_iter()
        .map(|file| {
            let bytes =
                std::fs::read(&file).map_err(|e| format!("{}: error: failed to read it: {e}", file.display()))?;
            let shard = read_shard(&bytes).map_err(|e| format!("{}: error: {e}", file.display()))?;
            Ok((file, shard))
        })
        .collect()
}

/// Adds the shard files under `dir` to `files`.
fn find_shards(dir: &Path, files: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            find_shards(&path, files)?;
        } else if is_shard_name(&path) {
            files.push(path);
        }
    }
    Ok(())
}

/// `shard-K-of-N.cbor`.
fn is_shard_name(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .and_then(|n| n.strip_prefix("shard-")?.strip_suffix(".cbor")?.split_once("-of-"))
        .is_some_and(|(k, n)| k.parse::<u32>().is_ok() && n.parse::<u32>().is_ok())
}

/// Checks that the shards make up whole runs of one campaign, and assembles them.
fn assemble_all(shards: Vec<(PathBuf, Shard)>) -> Result<Vec<Merged>, String> {
    let (first_path, first) = shards.first().ok_or("error: no shard files given")?;
    let this = tool();
    let mut by_file: BTreeMap<&str, BTreeMap<u32, &(PathBuf, Shard)>> = BTreeMap::new();
    for entry @ (path, shard) in &shards {
        let at = path.display();
        if shard.tool != this {
            return Err(format!(
                "{at}: error: simulated by sightline {} ({}); this is {} ({}): merge with the build that simulated it",
                shard.tool.version, shard.tool.git, this.version, this.git
            ));
        }
        if (&shard.files, shard.count, shard.seed, shard.record)
            != (&first.files, first.count, first.seed, first.record)
        {
            return Err(format!(
                "{at}: error: from another campaign than {} (the scenario files, N, --seed or --record differ)",
                first_path.display()
            ));
        }
        if let Some((other, _)) = by_file.entry(&shard.file).or_default().insert(shard.index, entry) {
            return Err(format!(
                "{at}: error: shard {}/{} of {} is also in {}",
                shard.index,
                shard.count,
                shard.file,
                other.display()
            ));
        }
    }
    let request = Request {
        seed: first.seed,
        record: first.record,
    };
    first
        .files
        .iter()
        .map(|file| {
            let parts = by_file.remove(file.as_str()).unwrap_or_default();
            if let Some(missing) = (1..=first.count).find(|k| !parts.contains_key(k)) {
                return Err(format!("{file}: error: shard {missing}/{} is missing", first.count));
            }
            let mut inputs = load_all(&[PathBuf::from(file)], request.seed, request.record)
                .ok_or_else(|| format!("{file}: error: the scenario no longer compiles (see above)"))?;
            let input = inputs.pop().expect("one input per file");
            let now = inputs_of(&input);
            for (path, shard) in parts.values() {
                if shard.inputs != now {
                    return Err(format!(
                        "{}: error: {file} or a file it imports changed since this shard was simulated",
                        path.display()
                    ));
                }
            }
            let shards = parts.values().map(|(_, shard)| shard.execution.clone()).collect();
            let units = parts.into_values().flat_map(|(_, shard)| shard.units.iter().cloned());
            let run = sightline_engine::assemble(&input.scenario, units)
                .map_err(|e| format!("{file}: error: the shards do not make up its run: {e}"))?;
            Ok(Merged {
                input,
                request,
                run,
                shards,
            })
        })
        .collect()
}
