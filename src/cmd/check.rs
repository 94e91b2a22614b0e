//! `sightline check FILE…`

use std::path::PathBuf;

use crate::exit::Exit;
use crate::input::load_all;
use crate::output::say;

/// Validates every file, its run's work judged as split over `shards`
/// processes; prints one line per valid file, every error otherwise.
pub fn check(files: &[PathBuf], shards: u32) -> Exit {
    let Some(inputs) = load_all(files, None, (false, false), Some(shards)) else {
        return Exit::Invalid;
    };
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    for input in inputs {
        let scenario = &input.scenario;
        let (points, requirements) = (scenario.points.len(), scenario.requirements.len());
        let sharded = match shards {
            1 => String::new(),
            n => format!(", run as {n} shards"),
        };
        say(format_args!(
            "{}: ok ({points} sweep point{}, {requirements} requirement{}{sharded})",
            input.name,
            plural(points),
            plural(requirements),
        ));
    }
    Exit::Pass
}
