//! Command-line syntax (clap derive). Usage errors exit with status 2.

use std::path::PathBuf;
use std::time::Duration;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Verification toolkit for V2X collective perception: simulate a scenario, check
/// its requirements, write evidence.
#[derive(Debug, Parser)]
#[command(name = "sightline", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate scenarios, check their requirements and write results.json,
    /// junit.xml and report.html (and run.mcap when recording). Exit 0: all
    /// pass, 1: a requirement fails, 2: invalid input, 3: internal error.
    Run(RunArgs),
    /// Search a scenario's `vary` space for a case that breaks a requirement,
    /// shrink it and write counterexample.yaml, falsify.json and report.html. Exit 0: none
    /// found, 1: found, 2: invalid input, 3: internal error.
    Falsify(FalsifyArgs),
    /// Combine the shard files of `run --shard K/N` into the evidence one
    /// unsharded run writes (results.json, junit.xml, report.html, run.mcap).
    /// Exit codes as `run`; 2 also when a shard is missing, repeated, damaged,
    /// given twice, of another campaign or build, or its scenario file changed
    /// since; 3 when a measured value is outside its domain.
    Merge(MergeArgs),
    /// Re-check the requirements of a recording (run.mcap) from what it holds
    /// and print the verdicts as `run` does. Exit 0: all pass, 1: a requirement
    /// fails, 2: the recording is damaged, does not match the results.json beside
    /// it, or cannot be read, 3: internal error.
    Replay {
        /// The recording.
        file: PathBuf,
    },
    /// Validate scenario files without running them. Exit 0: all valid, 2: not.
    Check {
        /// Scenario files (`-`: standard input).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Judge the work of a run as `run --shard K/N` splits it over N
        /// processes (default: one process, as `run`): a campaign too large for
        /// one process is valid when sharded.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
        shards: Option<u32>,
    },
    /// Print the JSON Schema of the scenario language (for editors).
    Schema {
        /// Print the field reference as Markdown instead (docs/reference.md).
        #[arg(long)]
        markdown: bool,
    },
    /// Write a scenario's world (or a falsify counterexample's) as ASAM
    /// OpenSCENARIO 1.2 and its roads as an ASAM OpenDRIVE 1.7 map, for esmini
    /// or CARLA: DIR/scenario.xosc and DIR/scenario.xodr. Exit 0: written,
    /// 2: invalid input or nothing to export, 3: internal error.
    Export(ExportArgs),
    /// Check sightline against known answers computed by hand (fusion, line of
    /// sight, radio channel, confidence bounds); for tool qualification.
    Selftest,
}

#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scenario files (`-`: standard input, with --out).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Evidence directory. With one file the evidence goes here; with several,
    /// into DIR/STEM/ (STEM: the file name without its extension). Default: out/STEM/.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace every scenario's seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Worker threads, 1 to 256 (default: one per core). Results do not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=MAX_JOBS))]
    pub jobs: Option<u16>,
    /// Record into DIR/run.mcap even when a scenario has no `record:` section
    /// (with that section's defaults: the worst point of the first requirement
    /// that fails the run, or the first point when none does; a grid a second).
    #[arg(long)]
    pub record: bool,
    /// Also write DIR/osi.mcap, an ASAM OSI trace (osi3.GroundTruth and, per
    /// sensor of each cooperating agent, osi3.SensorView with sightline's
    /// visibility) of the recorded point; implies --record. See docs/osi.md.
    #[arg(long, conflicts_with = "shard")]
    pub osi: bool,
    /// Render report.html with the template set in DIR: its report.html (which
    /// may extend `sightline/report.html`) and what that includes or extends.
    /// Checked before anything runs; see docs/report-templates.md. Not with
    /// --shard, which writes no report: give it to `sightline merge`.
    #[arg(long, value_name = "DIR", conflicts_with = "shard")]
    pub template: Option<PathBuf>,
    /// Simulate only slice K of N of the scenarios' work (sweep points and
    /// seeds) and write DIR/shard-K-of-N.cbor instead of evidence; `sightline
    /// merge` combines the N shards. Exit 0 when the shard is written.
    #[arg(long, value_name = "K/N", value_parser = shard)]
    pub shard: Option<ShardSpec>,
}

#[derive(Debug, Args)]
pub struct ExportArgs {
    /// Scenario file, or a counterexample.yaml of `sightline falsify` (`-`:
    /// standard input, with --out).
    pub file: PathBuf,
    /// Output directory. Default: out/STEM/.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The sweep point to export, by its label as results.json and the report
    /// name it (`v2x.penetration=0.4`). Default: the first point.
    #[arg(long, value_name = "LABEL")]
    pub point: Option<String>,
    /// Replace the scenario's seed (which draws generated traffic and noise).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
}

/// Slice K of N (1 ≤ K ≤ N).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShardSpec {
    /// K, from 1.
    pub index: u32,
    /// N.
    pub count: u32,
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Shard files, or directories searched (with their subdirectories) for
    /// shard-K-of-N.cbor files.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Evidence directory, as for `run`: with one scenario the evidence goes
    /// here; with several, into DIR/STEM/. Default: out/STEM/.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Render report.html with the template set in DIR, as `run --template`.
    #[arg(long, value_name = "DIR")]
    pub template: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct FalsifyArgs {
    /// Scenario file with a `vary` section (`-`: standard input, with --out).
    pub file: PathBuf,
    /// The most cases to try before shrinking.
    #[arg(long, value_name = "N", default_value_t = 64, value_parser = clap::value_parser!(u64).range(1..))]
    pub cases: u64,
    /// Stop searching after this many seconds (the search is then no longer
    /// deterministic).
    #[arg(long, value_name = "SECONDS", value_parser = seconds)]
    pub budget: Option<Duration>,
    /// Seed of the search (default: the scenario's seed). Each case runs with
    /// the scenario's own seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// How cases are chosen.
    #[arg(long, value_enum, default_value_t = SearchMode::Guided)]
    pub search: SearchMode,
    /// Output directory. Default: out/STEM/.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Worker threads, 1 to 256 (default: one per core). Results do not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=MAX_JOBS))]
    pub jobs: Option<u16>,
    /// Render report.html with the template set in DIR: its falsify.html (which
    /// may extend `sightline/falsify.html`) and what that includes or extends.
    /// Checked before anything runs; see docs/report-templates.md.
    #[arg(long, value_name = "DIR")]
    pub template: Option<PathBuf>,
}

/// How `falsify` chooses cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SearchMode {
    /// Random cases, and after a few of them every other case a step toward a
    /// smaller margin from the case with the smallest so far.
    Guided,
    /// Random cases only (uniform over the grid of each setting).
    Random,
}

/// The most worker threads `--jobs` starts: more than any machine's cores,
/// and few enough to start under the 2 GB address-space cap the hostile-input
/// tests run with (thousands of threads fail there, some by aborting while a
/// thread starts, which no caller can catch).
const MAX_JOBS: i64 = 256;

/// `K/N` with 1 ≤ K ≤ N.
fn shard(text: &str) -> Result<ShardSpec, String> {
    let parsed = text
        .split_once('/')
        .and_then(|(k, n)| Some((k.parse::<u32>().ok()?, n.parse::<u32>().ok()?)));
    match parsed {
        Some((index, count)) if (1..=count).contains(&index) => Ok(ShardSpec { index, count }),
        _ => Err(format!("expected K/N with 1 ≤ K ≤ N (as in 2/8), found `{text}`")),
    }
}

/// A positive number of seconds.
fn seconds(text: &str) -> Result<Duration, String> {
    text.parse::<f64>()
        .ok()
        .filter(|s| *s > 0.0)
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .ok_or_else(|| format!("expected a positive number of seconds, found `{text}`"))
}
