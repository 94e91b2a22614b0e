//! The lines `run` and `replay` print for a scenario's verdicts, and the exit
//! status they earn: both commands print them the same way, so a replay can be
//! compared with its run line for line.

use std::fmt::Display;

use sightline_dsl::Scenario;
use sightline_oracles::{Measurements, Status, Verdict, headline};

use crate::exit::Exit;
use crate::output::say;
use crate::terminal::stderr;

/// Prints `PASS|FAIL|NOT EXERCISED|ERROR path: N of M requirements hold over K
/// sweep points (fail: A; not exercised: B)` followed by `tail`, then one line
/// per requirement that does not pass, naming its deciding point, measured
/// value, threshold, margin and n; returns [`Exit::Pass`] when no verdict fails
/// the run (every requirement passes, or is not exercised for an accepted
/// reason), [`Exit::Fail`] otherwise and when there is no requirement.
pub fn print_verdicts(path: &str, scenario: &Scenario, verdicts: &[Verdict], tail: impl Display) -> Exit {
    let headline = headline(verdicts);
    let passed = verdicts.iter().filter(|v| v.status == Status::Pass).count();
    let points = scenario.points.len();
    let named: Vec<String> = [Status::Error, Status::Fail, Status::NotExercised]
        .into_iter()
        .filter_map(|status| {
            let ids: Vec<&str> = verdicts
                .iter()
                .filter(|v| v.status == status)
                .map(|v| v.id.as_str())
                .collect();
            let accepted = verdicts.iter().filter(|v| v.status == status && !v.fails_run()).count();
            let note = if accepted > 0 {
                format!(" ({accepted} accepted)")
            } else {
                String::new()
            };
            (!ids.is_empty()).then(|| format!("{}: {}{note}", status.words(), ids.join(", ")))
        })
        .collect();
    let named = if verdicts.is_empty() {
        " (no requirements: nothing to judge)".to_owned()
    } else if named.is_empty() {
        String::new()
    } else {
        format!(" ({})", named.join("; "))
    };
    say(format_args!(
        "{} {path}: {passed} of {} requirements hold over {points} sweep point{}{named} {tail}",
        headline.words().to_uppercase(),
        verdicts.len(),
        if points == 1 { "" } else { "s" },
    ));
    for (requirement, verdict) in scenario.requirements.iter().zip(verdicts) {
        if verdict.status != Status::Pass {
            let decisive = &verdict.decisive;
            let label = scenario.points[decisive.point].label();
            let at = if label.is_empty() {
                String::new()
            } else {
                format!(" at [{label}]")
            };
            let shown = |v: Option<f64>| v.map_or_else(|| "none".to_string(), |v| format!("{v:?}"));
            let accepted = verdict
                .acceptance()
                .map_or(String::new(), |reason| format!(" (accepted: {reason})"));
            say(format_args!(
                "  {} {}{at}{accepted}: measured {} ({}), threshold {}, margin {}, n = {}: {}",
                verdict.status.words(),
                requirement.id,
                shown(decisive.value),
                decisive.measured,
                shown(Some(verdict.threshold)),
                shown(decisive.margin),
                decisive.n.map_or_else(|| "unknown".to_string(), |n| n.to_string()),
                decisive.message
            ));
        }
    }
    if headline == Status::Pass {
        Exit::Pass
    } else {
        Exit::Fail
    }
}

/// Prints one line per measured value of `measurements` outside its domain,
/// each naming `file` and `why` no correct run gives it; returns
/// [`Exit::Internal`] when there is one, so that nothing is judged.
pub fn refuse_out_of_domain(
    file: &impl Display,
    scenario: &Scenario,
    measurements: &(impl Measurements + ?Sized),
    why: &str,
) -> Option<Exit> {
    let outside = sightline_oracles::out_of_domain(scenario, measurements);
    for problem in &outside {
        stderr!("{file}: error: {problem}: {why}");
    }
    (!outside.is_empty()).then_some(Exit::Internal)
}
