//! Command-line syntax (clap derive). Usage errors exit with status 2.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

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
}
