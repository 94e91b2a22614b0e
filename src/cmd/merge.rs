//! `sightline merge PATH… [--out DIR]`: the evidence of a sharded campaign.
//!
//! Everything is checked before anything is written: every shard file is given
//! once and its seal holds (read_shard checks the payload's SHA-256 before
//! decoding it), each scenario has shards 1 to N exactly once, all of one
//! campaign (the same campaign id, the one this build and the files make), from
//! this build of sightline, and its input files are unchanged; the units then
//! make up the run ([`sightline_engine::assemble`]), and every measured value
//! lies in its domain ([`sightline_oracles::out_of_domain`]; outside, exit 3).
//! The recording, when the scenario asks for one, is made here: its point (a
//! pooled semantic point's first run) is simulated again, and must give the
//! outcome its shard gave.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use sightline_engine::{Run, Unit};
use sightline_oracles::Quantity;
use sightline_reports::{Execution, Page, Shard, ShardInput, campaign_id, read_shard};

use super::shard::inputs_of;
use crate::cli::MergeArgs;
use crate::evidence::{
    EVIDENCE_SET, Reporting, Request, creatable, evidence_dirs, recorded, recorded_point, resimulated, tool,
    write_evidence,
};
use crate::exit::Exit;
use crate::files::{DATA_LIMIT, read_regular};
use crate::input::{Input, load_all};
use crate::staging::Staging;
use crate::template::templates;
use crate::terminal::stderr;

/// One scenario of the campaign, ready to render.
struct Merged {
    input: Input,
    request: Request,
    run: Run,
    /// Its shards: each file, how it ran, and the units it held.
    shards: Vec<(PathBuf, Execution, Vec<Unit>)>,
}

/// Reads and checks every shard and the template set, then writes each
/// scenario's evidence.
pub fn merge(args: &MergeArgs) -> anyhow::Result<Exit> {
    let merged = collect(&args.paths)
        .and_then(assemble_all)
        .map_err(|message| (Exit::Invalid, message))
        .and_then(|merged| {
            in_domains(&merged)
                .map(|()| merged)
                .map_err(|message| (Exit::Internal, message))
        })
        .inspect_err(|(_, message)| stderr!("{message}"));
    let templates = templates(args.template.as_deref(), Page::Run);
    let merged = match merged {
        Ok(merged) => merged,
        Err((exit, _)) => return Ok(exit),
    };
    let Some(templates) = templates else {
        return Ok(Exit::Invalid);
    };
    let Some(dirs) = evidence_dirs(
        args.out.as_deref(),
        merged.iter().map(|m| &m.input),
        EVIDENCE_SET,
        args.template.as_deref(),
    ) else {
        return Ok(Exit::Invalid);
    };
    creatable(&dirs)?;
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
        let mut staging = Staging::open(dir, EVIDENCE_SET)?;
        let simulated = match scenario.record {
            None => {
                let verdicts = sightline_oracles::check(scenario, &run);
                (run, verdicts, None)
            }
            Some(record) => {
                let record = recorded_point(scenario, record, &sightline_oracles::check(scenario, &run));
                recorded(&input, &reporting, &mut staging, record, |recorder| {
                    resimulated(&input, record, run, recorder)
                })?
            }
        };
        let here = Execution::on_this_machine(rayon::current_num_threads(), started, clock.elapsed());
        let shards: Vec<Execution> = shards.into_iter().map(|(_, execution, _)| execution).collect();
        let execution = Execution::campaign(&shards, &here);
        exit = exit.max(write_evidence(&input, &reporting, staging, simulated, execution)?);
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
            find_shards(path, &mut HashSet::new(), &mut files)
                .map_err(|e| format!("{}: error: {e}", path.display()))?;
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
    refuse_repeats(&files)?;
    files.sort();
    files
        .into_iter()
        .map(|file| {
            let bytes = read_regular(&file, DATA_LIMIT)
                .map_err(|e| format!("{}: error: failed to read it: {e}", file.display()))?;
            let shard = read_shard(&bytes).map_err(|e| format!("{}: error: {e}", file.display()))?;
            Ok((file, shard))
        })
        .collect()
}

/// Refuses a shard file given twice, by the same path or by two paths that
/// lead to it (`./x` and `x`, a link): its units would count twice.
fn refuse_repeats(files: &[PathBuf]) -> Result<(), String> {
    let mut seen: HashMap<PathBuf, &PathBuf> = HashMap::new();
    for file in files {
        let real =
            std::fs::canonicalize(file).map_err(|e| format!("{}: error: failed to read it: {e}", file.display()))?;
        if let Some(first) = seen.insert(real, file) {
            // Spellings, not paths: `Path` equality ignores `.` components.
            return Err(if first.as_os_str() == file.as_os_str() {
                format!("{}: error: given twice (each shard file counts once)", file.display())
            } else {
                format!(
                    "{}: error: the same file as {}, given twice (each shard file counts once)",
                    file.display(),
                    first.display()
                )
            });
        }
    }
    Ok(())
}

/// Adds the shard files under `dir` to `files`, searching each directory once
/// (by its canonical path) however many links lead to it: a link to a
/// directory above led round for ever. `visited` holds the directories searched.
fn find_shards(dir: &Path, visited: &mut HashSet<PathBuf>, files: &mut Vec<PathBuf>) -> std::io::Result<()> {
    if !visited.insert(std::fs::canonicalize(dir)?) {
        return Ok(());
    }
    let mut entries = std::fs::read_dir(dir)?
        .map(|entry| entry.map(|e| e.path()))
        .collect::<std::io::Result<Vec<_>>>()?;
    // The spelling of a directory reached twice is the first in path order.
    entries.sort();
    for path in entries {
        if path.is_dir() {
            find_shards(&path, visited, files)?;
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
        if (&shard.campaign, &shard.files, shard.count, shard.seed, shard.record)
            != (&first.campaign, &first.files, first.count, first.seed, first.record)
        {
            return Err(format!(
                "{at}: error: from another campaign than {} (campaign {} and {}: the scenario files, their \
                 contents, N, --seed or --record differ)",
                first_path.display(),
                short(&shard.campaign),
                short(&first.campaign)
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
        osi: false,
    };
    let mut loaded = Vec::new();
    for file in &first.files {
        let parts = by_file.remove(file.as_str()).unwrap_or_default();
        if let Some(missing) = (1..=first.count).find(|k| !parts.contains_key(k)) {
            return Err(format!("{file}: error: shard {missing}/{} is missing", first.count));
        }
        let mut inputs = load_all(&[PathBuf::from(file)], request.seed, (request.record, false), None)
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
        loaded.push((input, now, parts));
    }
    let all_inputs: Vec<Vec<ShardInput>> = loaded.iter().map(|(_, now, _)| now.clone()).collect();
    let expected = campaign_id(&this, &all_inputs, first.seed, first.record, first.count);
    if first.campaign != expected {
        return Err(format!(
            "{}: error: its campaign id is {}, and this build, the files, N, --seed and --record make {}: \
             the shard was altered",
            first_path.display(),
            short(&first.campaign),
            short(&expected)
        ));
    }
    loaded
        .into_iter()
        .map(|(input, _, parts)| {
            let file = input.name.clone();
            let units = parts.values().flat_map(|(_, shard)| shard.units.iter().cloned());
            let run = sightline_engine::assemble(&input.scenario, units)
                .map_err(|e| format!("{file}: error: the shards do not make up its run: {e}"))?;
            let shards = parts
                .into_values()
                .map(|(path, shard)| {
                    let units = shard.units.iter().map(|(unit, _)| unit.clone()).collect();
                    (path.clone(), shard.execution.clone(), units)
                })
                .collect();
            Ok(Merged {
                input,
                request,
                run,
                shards,
            })
        })
        .collect()
}

/// The first 12 hex digits of a campaign id, as messages show it.
fn short(id: &str) -> &str {
    id.get(..12).unwrap_or(id)
}

/// Checks every measured value of every scenario against its domain: one line
/// per value outside, naming the shard that holds it.
fn in_domains(merged: &[Merged]) -> Result<(), String> {
    let mut lines = Vec::new();
    for merged in merged {
        for problem in sightline_oracles::out_of_domain(&merged.input.scenario, &merged.run) {
            let replicate = match problem.quantity {
                Quantity::Metric { replicate, .. } => replicate as u32,
                Quantity::Selected { .. } | Quantity::Signal { .. } | Quantity::Object { .. } => 0,
            };
            let (path, _, _) = merged
                .shards
                .iter()
                .find(|(_, _, units)| {
                    units
                        .iter()
                        .any(|u| u.replicate == replicate && u.group.contains(&problem.point))
                })
                .expect("every unit of the run comes from a shard");
            lines.push(format!(
                "{}: error: {}, {problem}: {OUT_OF_DOMAIN}",
                path.display(),
                merged.input.name
            ));
        }
    }
    if lines.is_empty() {
        Ok(())
    } else {
        Err(lines.join("\n"))
    }
}

/// What a value outside its domain means, for the messages of merge and replay.
pub const OUT_OF_DOMAIN: &str = "no simulation gives such a value (a defect in the sightline that measured it, \
                                 or a file altered and sealed again); nothing is judged";
