//! `sightline check FILE…`

use std::path::PathBuf;

use crate::exit::Exit;
use crate::input::load_all;
use crate::output::say;

/// Validates every file; prints one line per valid file, every error otherwise.
pub fn check(files: &[PathBuf]) -> Exit {
    let Some(inputs) = load_all(files, None, (false, false), Some(1)) else {
        return Exit::Invalid;
    };
    for input in inputs {
        let scenario = &input.scenario;
        say(format_args!(
            "{}: ok ({} sweep point{}, {} requirement{})",
            input.name,
            scenario.points.len(),
            if scenario.points.len() == 1 { "" } else { "s" },
            scenario.requirements.len(),
            if scenario.requirements.len() == 1 { "" } else { "s" },
        ));
    }
    Exit::Pass
}
