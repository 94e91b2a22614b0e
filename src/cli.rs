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
        /// Scenario files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Print the JSON Schema of the scenario language (for editors).
    Schema {
        /// Print the field reference as Markdown instead (docs/reference.md).
        #[arg(long)]
        markdown: bool,
    },
    /// Check sightline against known answers computed by hand (fusion, line of
    /// sight, radio channel, confidence bounds); for tool qualification.
    Selftest,
}

#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scenario files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Evidence directory. With one file the evidence goes here; with several,
    /// into DIR/STEM/ (STEM: the file name without its extension). Default: out/STEM/.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace every scenario's seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Worker threads, at least 1 (default: one per core). Results do not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,
    /// Record into DIR/run.mcap even when a scenario has no `record:` section
    /// (with that section's defaults: the first sweep point, a grid a second).
    #[arg(long)]
    pub record: bool,
    /// Render report.html with the template set in DIR: its report.html (which
    /// may extend `sightline/report.html`) and what that includes or extends.
    /// Checked before anything runs; see docs/report-templates.md.
    #[arg(long, value_name = "DIR")]
    pub template: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct FalsifyArgs {
    /// Scenario file with a `vary` section.
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
    /// Worker threads, at least 1 (default: one per core). Results do not depend on it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
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

/// A positive number of seconds.
fn seconds(text: &str) -> Result<Duration, String> {
    text.parse::<f64>()
        .ok()
        .filter(|s| *s > 0.0)
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .ok_or_else(|| format!("expected a positive number of seconds, found `{text}`"))
}
