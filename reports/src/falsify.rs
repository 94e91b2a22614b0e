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

/// junit.xml of a falsification: one case per requirement of the scenario.
/// The requirement the counterexample breaks is a failure (an error when it
/// could not be checked) naming `counterexample.yaml` and the command that
/// reproduces it; every other requirement passes the search: no case tried
/// broke it. Each case's `<system-out>` says how many cases were tried, in how
/// many the requirement had the smallest margin, and the smallest.
pub fn falsify_junit(f: &Falsification<'_>) -> quick_junit::Report {
    use quick_junit::{NonSuccessKind, TestCaseStatus};

    use crate::junit::{lines, new_case, new_suite};

    let scenario = f.scenario;
    let mut suite = new_suite(&scenario.name, &scenario.file, f.scenario_sha256);
    suite.add_property(("seed", f.search.seed.to_string().as_str()));
    suite.add_property(("search", search_name(f.search)));
    suite.add_property((
        "tool",
        format!("{} {} ({})", f.tool.name, f.tool.version, f.tool.git).as_str(),
    ));
    let found = f.outcome.counterexample.map(|i| &f.outcome.cases[i]);
    let duration = std::time::Duration::from_secs_f64(f.execution.duration_seconds.max(0.0));
    let tried = f.outcome.cases.len().to_string();
    for requirement in &scenario.requirements {
        let worst: Vec<&Case> = f
            .outcome
            .cases
            .iter()
            .filter(|c| c.score.requirement.as_deref() == Some(requirement.id.as_str()))
            .collect();
        let smallest = worst
            .iter()
            .filter_map(|c| c.score.margin)
            .min_by(f64::total_cmp)
            .map_or("none".to_string(), |m| format!("{m:?}"));
        let mut status = TestCaseStatus::success();
        let mut out = vec![
            ("requirement", requirement.id.clone()),
            ("text", requirement.text.clone()),
            ("cases", tried.clone()),
            ("cases_worst", worst.len().to_string()),
            ("smallest_margin", smallest),
        ];
        if let Some(case) = found.filter(|c| c.score.requirement.as_deref() == Some(requirement.id.as_str())) {
            let kind = match case.score.status {
                Status::Error => NonSuccessKind::Error,
                _ => NonSuccessKind::Failure,
            };
            let values: Vec<String> = scenario
                .vary
                .iter()
                .zip(&case.indices)
                .map(|(v, &i)| format!("{}={}", v.path, sightline_dsl::display_value(&v.value(i))))
                .collect();
            let margin = case.score.margin.map_or("none".to_string(), |m| format!("{m:?}"));
            status = TestCaseStatus::non_success(kind);
            status.set_type(case.score.status.name()).set_message(format!(
                "counterexample.yaml breaks {} ({}, margin {margin}) at {}; reproduce: {}",
                requirement.id,
                case.score.status.name(),
                values.join(", "),
                f.reproduce.unwrap_or("sightline run counterexample.yaml")
            ));
            out.extend([
                ("counterexample", "counterexample.yaml".to_string()),
                ("verdict", case.score.status.name().to_string()),
                ("margin", margin),
            ]);
        }
        let mut case = new_case(
            requirement.id.clone(),
            status,
            &scenario.name,
            &scenario.file,
            requirement.location.line,
        );
        case.set_time(duration / scenario.requirements.len().max(1) as u32);
        let out: Vec<(&str, &str)> = out.iter().map(|(k, v)| (*k, v.as_str())).collect();
        case.set_system_out(lines(&out));
        suite.add_test_case(case);
    }
    suite.set_time(duration);
    suite
        .extra
        .insert("timestamp".into(), f.execution.started.as_str().into());
    let mut report = quick_junit::Report::new("sightline falsify");
    report.add_test_suite(suite);
    report
}
