//! The lines `run` and `replay` print for a scenario's verdicts, and the exit
//! status they earn: both commands print them the same way, so a replay can be
//! compared with its run line for line.

use std::fmt::Display;

use sightline_dsl::Scenario;
use sightline_oracles::{Status, Verdict};

use crate::exit::Exit;
use crate::output::say;

/// Prints `PASS|FAIL|ERROR path: N of M requirements hold over K sweep points`
/// followed by `tail`, then one line per requirement that does not hold;
/// returns [`Exit::Pass`] when every requirement holds, [`Exit::Fail`] otherwise.
pub fn print_verdicts(path: &str, scenario: &Scenario, verdicts: &[Verdict], tail: impl Display) -> Exit {
    let overall = verdicts.iter().map(|v| v.status).max().unwrap_or(Status::Pass);
    let passed = verdicts.iter().filter(|v| v.status == Status::Pass).count();
    let points = scenario.points.len();
    say(format_args!(
        "{} {path}: {passed} of {} requirements hold over {points} sweep point{} {tail}",
        overall.name().to_uppercase(),
        verdicts.len(),
        if points == 1 { "" } else { "s" },
    ));
    for (requirement, verdict) in scenario.requirements.iter().zip(verdicts) {
        if verdict.status != Status::Pass {
            say(format_args!(
                "  {} {}: {}",
                verdict.status.name(),
                requirement.id,
                verdict.decisive.message
            ));
        }
    }
    if overall == Status::Pass {
        Exit::Pass
    } else {
        Exit::Fail
    }
}
