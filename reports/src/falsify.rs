//! `falsify.json`: the wire format of a falsification (what `sightline falsify`
//! tried and found), and the [`Falsification`] both it and the falsification
//! report are drawn from.

use serde::Serialize;
use sightline_dsl::{Scenario, Vary};
use sightline_oracles::{Case, Judged, Outcome, Phase, Search, Status};

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

/// `path=value, …` of the case at `indices` of the `vary` space.
pub fn case_values(vary: &[Vary], indices: &[u64]) -> String {
    vary.iter()
        .zip(indices)
        .map(|(v, &i)| format!("{}={}", v.path, sightline_dsl::display_value(&v.value(i))))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `guided` or `random`.
pub(crate) fn search_name(search: &Search) -> &'static str {
    if search.guided { "guided" } else { "random" }
}

/// What a search found for one requirement, over every case tried.
#[derive(Debug)]
pub(crate) struct Tally<'a> {
    /// Cases tried.
    pub cases: usize,
    /// Cases in which it was judged (not "not exercised").
    pub exercised: usize,
    /// Cases in which it failed a `sightline run` of the case.
    pub broken: usize,
    /// The first case that broke it (index in the outcome's cases) and its judgement.
    pub first_broken: Option<(usize, &'a Judged)>,
    /// Its smallest margin over every case.
    pub smallest: Option<f64>,
    /// The counterexample's judgement of it, when the counterexample breaks it.
    pub by_counterexample: Option<&'a Judged>,
}

impl<'a> Tally<'a> {
    /// The tally of requirement `id` over the cases of `outcome`.
    pub(crate) fn of(outcome: &'a Outcome, id: &str) -> Self {
        let judged = |case: &'a Case| case.score.each.iter().find(|j| j.id == id);
        let mut tally = Tally {
            cases: outcome.cases.len(),
            exercised: 0,
            broken: 0,
            first_broken: None,
            smallest: None,
            by_counterexample: outcome
                .counterexample
                .and_then(|i| judged(&outcome.cases[i]))
                .filter(|j| j.breaks),
        };
        for (i, judged) in outcome
            .cases
            .iter()
            .enumerate()
            .filter_map(|(i, c)| Some((i, judged(c)?)))
        {
            tally.exercised += usize::from(judged.status != Status::NotExercised);
            if judged.breaks {
                tally.broken += 1;
                tally.first_broken.get_or_insert((i, judged));
            }
            if let Some(margin) = judged.margin {
                tally.smallest = Some(tally.smallest.map_or(margin, |m: f64| m.min(margin)));
            }
        }
        tally
    }
}

/// junit.xml of a falsification: one case per requirement of the scenario.
/// A requirement the counterexample breaks is a failure (an error when it
/// could not be checked) naming `counterexample.yaml` and the command that
/// reproduces it; one that another case broke is a failure naming that case's
/// values; one that no case judged is skipped (its not being exercised is
/// accepted), or a failure when no case was tried at all; the rest pass the
/// search. Each case's `<system-out>` says how
/// many cases were tried, judged it and broke it, and its smallest margin.
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
    let duration = std::time::Duration::from_secs_f64(f.execution.duration_seconds.max(0.0));
    let shown = |margin: Option<f64>| margin.map_or("none".to_string(), |m| format!("{m:?}"));
    let values = |case: &Case| case_values(&scenario.vary, &case.indices);
    let kind = |judged: &Judged| match judged.status {
        Status::Error => NonSuccessKind::Error,
        _ => NonSuccessKind::Failure,
    };
    for requirement in &scenario.requirements {
        let id = requirement.id.as_str();
        let tally = Tally::of(f.outcome, id);
        let mut out = vec![
            ("requirement", requirement.id.clone()),
            ("text", requirement.text.clone()),
            ("cases", tally.cases.to_string()),
            ("cases_exercised", tally.exercised.to_string()),
            ("cases_broken", tally.broken.to_string()),
            ("smallest_margin", shown(tally.smallest)),
        ];
        let status = if let (Some(judged), Some(i)) = (tally.by_counterexample, f.outcome.counterexample) {
            let margin = shown(judged.margin);
            let mut status = TestCaseStatus::non_success(kind(judged));
            status.set_type(judged.status.name()).set_message(format!(
                "counterexample.yaml breaks {id} ({}, margin {margin}) at {}; reproduce: {}",
                judged.status.name(),
                values(&f.outcome.cases[i]),
                f.reproduce.unwrap_or("sightline run counterexample.yaml")
            ));
            out.extend([
                ("counterexample", "counterexample.yaml".to_string()),
                ("verdict", judged.status.name().to_string()),
                ("margin", margin),
            ]);
            status
        } else if let Some((i, judged)) = tally.first_broken {
            let mut status = TestCaseStatus::non_success(kind(judged));
            status.set_type(judged.status.name()).set_message(format!(
                "{} of {} cases broke {id}, first case {} ({}, margin {}) at {}; counterexample.yaml does not \
                 break it: set those values to reproduce it",
                tally.broken,
                tally.cases,
                i + 1,
                judged.status.name(),
                shown(judged.margin),
                values(&f.outcome.cases[i]),
            ));
            status
        } else if tally.cases == 0 {
            // Like a run without samples: nothing was judged, and the search fails the gate.
            let mut status = TestCaseStatus::non_success(NonSuccessKind::Failure);
            status.set_type(Status::NotExercised.name()).set_message(format!(
                "not exercised: no case was tried within the budget, so nothing judged {id}"
            ));
            status
        } else if tally.exercised == 0 {
            // Not exercised in every case, and accepted (else every case broke it).
            let mut status = TestCaseStatus::skipped();
            status.set_type(Status::NotExercised.name()).set_message(format!(
                "not exercised in any of the {} cases tried (accepted)",
                tally.cases
            ));
            status
        } else {
            TestCaseStatus::success()
        };
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
