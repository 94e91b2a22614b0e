//! `falsify.json`: the wire format of a falsification (what `sightline falsify`
//! tried and found).

use serde::Serialize;
use sightline_dsl::{Scenario, Vary};
use sightline_oracles::{Case, Outcome, Phase, Search, Status};

/// `falsify.json` of a search over `scenario`'s `vary` space, reproduced by
/// `command`: the space, every case tried with its values and worst requirement,
/// and the counterexample. It holds no timing, so the same search gives the
/// same bytes.
pub fn falsify_json(
    scenario: &Scenario,
    outcome: &Outcome,
    search: &Search,
    command: &str,
) -> Result<String, serde_json::Error> {
    serde_json::to_string_pretty(&report(scenario, outcome, search, command)).map(|json| json + "\n")
}

/// The document.
#[derive(Serialize)]
struct Report<'a> {
    scenario: &'a str,
    command: &'a str,
    seed: u64,
    search: &'static str,
    vary: &'a [Vary],
    cases: Vec<CaseReport<'a>>,
    first_counterexample: Option<usize>,
    counterexample: Option<CaseReport<'a>>,
}

/// One case of [`Report`].
#[derive(Serialize)]
struct CaseReport<'a> {
    phase: Phase,
    values: serde_json::Map<String, serde_json::Value>,
    requirement: Option<&'a str>,
    status: Status,
    margin: Option<f64>,
}

fn report<'a>(scenario: &'a Scenario, outcome: &'a Outcome, search: &Search, command: &'a str) -> Report<'a> {
    let case = |case: &'a Case| CaseReport {
        phase: case.phase,
        values: scenario
            .vary
            .iter()
            .zip(&case.indices)
            .map(|(v, &i)| (v.path.clone(), v.value(i)))
            .collect(),
        requirement: case.score.requirement.as_deref(),
        status: case.score.status,
        margin: case.score.margin,
    };
    Report {
        scenario: &scenario.file,
        command,
        seed: search.seed,
        search: if search.guided { "guided" } else { "random" },
        vary: &scenario.vary,
        cases: outcome.cases.iter().map(case).collect(),
        first_counterexample: outcome.first_counterexample,
        counterexample: outcome.counterexample.map(|i| case(&outcome.cases[i])),
    }
}
