//! Reading and compiling scenario files (or standard input, `-`), reporting
//! every problem on stderr.

use std::path::{Path, PathBuf};

use sightline_dsl::{Options, Scenario};

use crate::files::{DATA_LIMIT, TEXT_LIMIT, read_regular, read_stdin};
use crate::terminal::stderr;

/// The path that names standard input on the command line.
pub const STDIN: &str = "-";

/// How messages and evidence name standard input. The files a scenario read
/// from it imports are found from the working directory.
pub const STDIN_NAME: &str = "<stdin>";

/// A compiled scenario file and the bytes it was compiled from.
pub struct Input {
    /// The path as given (`-` for standard input).
    pub path: PathBuf,
    /// The name messages and evidence give it: the path, or `<stdin>`.
    pub name: String,
    /// The file's bytes (hashed into the evidence).
    pub bytes: Vec<u8>,
    /// The compiled scenario.
    pub scenario: Scenario,
}

impl Input {
    /// Whether it was read from standard input.
    pub fn is_stdin(&self) -> bool {
        self.path == Path::new(STDIN)
    }
}

/// Reads and compiles every file (`seed` overriding each one's, `record`
/// recording each one as `--record` does, `osi` bounding its OSI trace as
/// `--osi` does), the files it imports read from disk
/// too. Prints every error (as `file:line:col: error: …`) and returns `None` if
/// any file is invalid; prints the warnings of each valid file (as
/// `file:line:col: warning: …`).
pub fn load_all(
    paths: &[PathBuf],
    seed: Option<u64>,
    (record, osi): (bool, bool),
    processes: Option<u32>,
) -> Option<Vec<Input>> {
    let disk = |path: &Path| read_regular(path, DATA_LIMIT);
    let options = Options {
        seed,
        loader: Some(&disk),
        record,
        osi,
        processes,
    };
    let mut inputs = Vec::new();
    let mut valid = true;
    let is_stdin = |path: &&PathBuf| *path == Path::new(STDIN);
    if paths.iter().filter(is_stdin).count() > 1 {
        stderr!("{STDIN_NAME}: error: `-` is given more than once; standard input can be read only once");
        valid = false;
    }
    let mut stdin_read = false;
    for path in paths {
        if is_stdin(&path) && std::mem::replace(&mut stdin_read, true) {
            continue;
        }
        match load(path, &options) {
            Ok(input) => inputs.push(input),
            Err(message) => {
                stderr!("{message}");
                valid = false;
            }
        }
    }
    valid.then_some(inputs)
}

fn load(path: &Path, options: &Options<'_>) -> Result<Input, String> {
    let (name, bytes) = if path == Path::new(STDIN) {
        let bytes =
            read_stdin(TEXT_LIMIT).map_err(|e| format!("{STDIN_NAME}: error: failed to read standard input: {e}"))?;
        (STDIN_NAME.to_string(), bytes)
    } else {
        let name = path.display().to_string();
        let bytes =
            read_regular(path, TEXT_LIMIT).map_err(|e| format!("{name}: error: failed to read the file: {e}"))?;
        (name, bytes)
    };
    let text =
        sightline_dsl::utf8_text(&bytes).map_err(|at| format!("{name}:{at}: error: the file is not UTF-8 text"))?;
    let scenario = sightline_dsl::compile(&name, text, options).map_err(|errors| errors.to_string())?;
    if let Some(shards) = options.processes.filter(|&n| n > 1) {
        shard_budget(&name, &scenario, shards)?;
    }
    for warning in &scenario.warnings {
        stderr!("{warning}");
    }
    Ok(Input {
        path: path.to_path_buf(),
        name,
        bytes,
        scenario,
    })
}

/// Holds each of `shards` shards of `scenario` to the work limit of a process.
/// The language bounds the run's work divided by the shard count; `run --shard`
/// deals the units out in turn (see `cmd::shard`), so one shard can get the
/// heavy units of an uneven sweep. Whichever shard a scenario's first unit goes
/// to, the shards get the same sets of its units, so the check does not
/// depend on the other files of the run.
fn shard_budget(name: &str, scenario: &sightline_dsl::Scenario, shards: u32) -> Result<(), String> {
    let units = sightline_engine::units(scenario);
    // A shard beyond the units gets none: at most one load per unit (N is the user's).
    let mut loads = vec![0.0; units.len().min(shards as usize)];
    for (u, unit) in units.iter().enumerate() {
        let work: f64 = unit
            .group
            .iter()
            .map(|&point| sightline_dsl::point_load(&scenario.points[point].setup))
            .sum();
        loads[u % shards as usize] += work;
    }
    let most = loads.iter().copied().fold(0.0, f64::max);
    if most <= sightline_dsl::MAX_RUN_LOAD {
        return Ok(());
    }
    Err(format!(
        "{name}: error: one of {shards} shards would do {most:.0} points' worth of work (each at the seeds its \
         checks need; a point at the per-point work limits counts 1), more than the limit of {} a process: \
         `run --shard` deals the sweep's points and seeds out in turn, so shards get uneven shares of an \
         uneven sweep; split it into more shards, sweep fewer points or check over fewer `seeds`",
        sightline_dsl::MAX_RUN_LOAD
    ))
}
