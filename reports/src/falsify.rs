//! `falsify.json`: the wire format of a falsification (what `sightline falsify`
//! tried and found), and the [`Falsification`] both it and the falsification
//! report are drawn from.

use serde::Serialize;
use sightline_dsl::{Scenario, Vary};
use sightline_oracles::{Case, Outcome, Phase, Search, Status};

use crate::execution::Execution;
use crate::results::Tool;

/// A falsification as `sightline falsify` ran it: the scenario and its `vary`
/// space, the search and what it found, and how it ran.
#[derive(Debug, Clone, Copy)]
pub struct Falsification<'a> {
    /// The scenario searched (its `file` as the user named it).
    pub scenario: &'a Scenario,
    /// SHA-256 of the scenario file, lowercase hex.
    pub scenario_sha256: &'a str,
    /// The search's settings.
    pub search: &'a Search,
    /// The wall-clock budget, seconds, if the search had one.
    pub budget: Option<f64>,
    /// What it found.
    pub outcome: &'a Outcome,
    /// Distinct cases simulated (a case tried twice is simulated once).
    pub simulations: usize,
    /// The command that reproduces the search.
    pub command: &'a str,
    /// The command that reproduces the counterexample, when there is one.
    pub reproduce: Option<&'a str>,
    /// The tool.
    pub tool: &'a Tool,
    /// Where, when and how long the search ran.
    pub execution: &'a Execution,
}

/// `falsify.json` of `falsification`: the space, every case tried with its
/// values and worst requirement, and the counterexample. Only `execution`
/// holds timing, so the same search gives the same file but for it.
pub fn falsify_json(falsification: &Falsification<'_>) -> Result<String, serde_json::Error> {
    serde_json::to_string_pretty(&document(falsification)).map(|json| json + "\n")
}

/// The document.
#[derive(Serialize)]
pub(crate) struct Document<'a> {
    scenario: &'a str,
    command: &'a str,
    execution: &'a Execution,
    seed: u64,
    search: &'static str,
    vary: &'a [Vary],
    cases: Vec<CaseDocument<'a>>,
    first_counterexample: Option<usize>,
    counterexample: Option<CaseDocument<'a>>,
}

/// One case of [`Document`].
#[derive(Serialize)]
struct CaseDocument<'a> {
    phase: Phase,
    values: serde_json::Map<String, serde_json::Value>,
    requirement: Option<&'a str>,
    status: Status,
    margin: Option<f64>,
}

pub(crate) fn document<'a>(f: &Falsification<'a>) -> Document<'a> {
    let case = |case: &'a Case| CaseDocument {
        phase: case.phase,
        values: f
            .scenario
            .vary
            .iter()
            .zip(&case.indices)
            .map(|(v, &i)| (v.path.clone(), v.value(i)))
            .collect(),
        requirement: case.score.requirement.as_deref(),
        status: case.score.status,
        margin: case.score.margin,
    };
    Document {
        scenario: &f.scenario.file,
        command: f.command,
        execution: f.execution,
        seed: f.search.seed,
        search: search_name(f.search),
        vary: &f.scenario.vary,
        cases: f.outcome.cases.iter().map(case).collect(),
        first_counterexample: f.outcome.first_counterexample,
        counterexample: f.outcome.counterexample.map(|i| case(&f.outcome.cases[i])),
    }
}

/// `guided` or `random`.
pub(crate) fn search_name(search: &Search) -> &'static str {
    if search.guided { "guided" } else { "random" }
}
