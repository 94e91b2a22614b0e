//! `sightline run --shard K/N`: one deterministic slice of a campaign's work.
//!
//! The work of the scenario files given, in order, is their units (see
//! [`sightline_engine::Unit`]): per file, each group of sweep points that share
//! their sampled data, at each seed its checks need. Numbered across the files
//! from 0, unit u belongs to shard u mod N + 1, so every shard gets a similar
//! share of every sweep. The slice depends only on the files and N, never on the
//! machine or its thread count. Every shard file carries the campaign's id
//! ([`campaign_id`]), which every shard computes alike from the build, the
//! files and their hashes, `--seed`, `--record` and N.

use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use rayon::prelude::*;
use sightline_reports::{Execution, Shard, ShardInput, campaign_id, hex, sha256_hex, shard_bytes};

use crate::cli::ShardSpec;
use crate::evidence::{Request, tool};
use crate::exit::Exit;
use crate::input::Input;
use crate::output::{progress, say};
use crate::staging::Staging;

/// The name of shard `spec`'s file in a scenario's evidence directory.
pub fn shard_file_name(spec: ShardSpec) -> String {
    format!("shard-{}-of-{}.cbor", spec.index, spec.count)
}

/// Simulates shard `spec` of the units of `inputs` and writes each scenario's
/// part into its directory in `dirs` (a file for every scenario, so a merge can
/// tell a shard with no work for it from a missing one).
pub fn run_shard(
    pool: &rayon::ThreadPool,
    spec: ShardSpec,
    inputs: &[Input],
    dirs: &[PathBuf],
    request: Request,
) -> anyhow::Result<Exit> {
    let files: Vec<String> = inputs.iter().map(|i| i.name.clone()).collect();
    let all_inputs: Vec<Vec<ShardInput>> = inputs.iter().map(inputs_of).collect();
    let campaign = campaign_id(&tool(), &all_inputs, request.seed, request.record, spec.count);
    let mut first = 0;
    for (i, (input, dir)) in inputs.iter().zip(dirs).enumerate() {
        let all = sightline_engine::units(&input.scenario);
        let mine: Vec<_> = all
            .iter()
            .enumerate()
            .filter(|(u, _)| (first + u) % spec.count as usize == (spec.index - 1) as usize)
            .map(|(_, unit)| unit.clone())
            .collect();
        first += all.len();
        let path = input.name.clone();
        let (started, clock) = (SystemTime::now(), Instant::now());
        let bar = progress(mine.len(), &path);
        let units = pool.install(|| {
            mine.into_par_iter()
                .map(|unit| {
                    let outcomes = sightline_engine::simulate_unit(&input.scenario, &unit);
                    bar.inc(1);
                    (unit, outcomes)
                })
                .collect::<Vec<_>>()
        });
        bar.finish_and_clear();
        let simulated = units.len();
        let shard = Shard {
            campaign: campaign.clone(),
            tool: tool(),
            files: files.clone(),
            file: path.clone(),
            inputs: all_inputs[i].clone(),
            seed: request.seed,
            record: request.record,
            index: spec.index,
            count: spec.count,
            execution: Execution::on_this_machine(pool.current_num_threads(), started, clock.elapsed()),
            units,
        };
        let name = shard_file_name(spec);
        write_file(dir, &name, &shard_bytes(&shard))?;
        say(format_args!(
            "shard {}/{} of {path}: {simulated} of {} units -> {}",
            spec.index,
            spec.count,
            all.len(),
            dir.join(&name).display()
        ));
    }
    Ok(Exit::Pass)
}

/// The scenario file and the files it imports, with their hashes.
pub fn inputs_of(input: &Input) -> Vec<ShardInput> {
    let scenario = ShardInput {
        path: input.name.clone(),
        sha256: sha256_hex(&input.bytes),
    };
    let imports = input.scenario.imports.iter().map(|import| ShardInput {
        path: import.path.clone(),
        sha256: hex(&import.sha256),
    });
    std::iter::once(scenario).chain(imports).collect()
}

/// Writes `bytes` to `dir/name` as a set of one file, beside the other shards'.
fn write_file(dir: &Path, name: &str, bytes: &[u8]) -> anyhow::Result<()> {
    let mut staging = Staging::open(dir, &[])?;
    staging.write(name, bytes)?;
    staging.commit()
}
