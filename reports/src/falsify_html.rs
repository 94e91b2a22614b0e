//! The falsification report (`report.html` of `sightline falsify`): the search's
//! settings, every case tried, a chart of the margins and the counterexample.
//! Numbers are formatted here so the template only lays them out.

use serde::Serialize;
use sightline_dsl::{Domain, Vary, display_value};
use sightline_oracles::{Case, Phase, Status};

use crate::Error;
use crate::chart::{Chart, margin_chart};
use crate::falsify::{Falsification, Tally, document};
use crate::html::{DocumentView, content_id, control, number, or_dash};
use crate::template::Templates;

/// Renders the falsification report of `falsification` with `templates` (a
/// [`Page::Falsify`](crate::Page::Falsify) set).
pub fn falsify_html(falsification: &Falsification<'_>, templates: &Templates) -> Result<String, Error> {
    let view = View::new(falsification)?;
    Ok(templates.render(&view, &document(falsification))?)
}

#[derive(Serialize)]
struct View<'a> {
    document: DocumentView,
    name: &'a str,
    provenance: Vec<(&'static str, String)>,
    settings: Vec<(&'static str, String)>,
    space: Vec<SettingView>,
    /// Cases tried before shrinking, and in all.
    tried: usize,
    columns: Vec<&'a str>,
    cases: Vec<CaseView>,
    chart: Option<Chart>,
    counterexample: Option<CounterexampleView>,
    /// Without a counterexample: the smallest margin seen.
    closest: Option<ClosestView>,
    /// Every requirement over every case tried, as junit.xml judges it.
    requirements: Vec<RequirementView>,
}

#[derive(Serialize)]
struct RequirementView {
    id: String,
    /// `fail` (a case broke it), `error`, `not_exercised` (no case judged it)
    /// or `pass` (every case that judged it held).
    verdict: &'static str,
    exercised: usize,
    broken: usize,
    /// The first case that broke it, 1-based.
    first_broken: Option<usize>,
    smallest: String,
}

#[derive(Serialize)]
struct SettingView {
    path: String,
    values: String,
}

#[derive(Serialize)]
struct CaseView {
    /// 1-based, in the order tried.
    number: usize,
    phase: &'static str,
    values: Vec<String>,
    requirement: String,
    status: &'static str,
    margin: String,
    /// `first counterexample` or `counterexample` (shrunk), or empty.
    mark: &'static str,
}

#[derive(Serialize)]
struct CounterexampleView {
    case: usize,
    first: usize,
    requirement: String,
    /// The other requirements it breaks.
    also: Vec<String>,
    status: &'static str,
    margin: String,
    values: Vec<(String, String)>,
    reproduce: String,
}

#[derive(Serialize)]
struct ClosestView {
    case: usize,
    requirement: String,
    margin: String,
}

impl<'a> View<'a> {
    fn new(f: &Falsification<'a>) -> Result<Self, Error> {
        let outcome = f.outcome;
        let vary = &f.scenario.vary;
        let tried = outcome.cases.iter().filter(|c| c.phase != Phase::Shrink).count();
        let requirement = |case: &Case| case.score.requirement.clone().unwrap_or_else(|| "—".into());
        let counterexample = outcome.counterexample.map(|i| {
            let case = &outcome.cases[i];
            CounterexampleView {
                case: i + 1,
                first: outcome.first_counterexample.unwrap_or(i + 1),
                requirement: requirement(case),
                also: case
                    .score
                    .each
                    .iter()
                    .filter(|j| j.breaks && Some(&j.id) != case.score.requirement.as_ref())
                    .map(|j| j.id.clone())
                    .collect(),
                status: case.score.status.name(),
                margin: or_dash(case.score.margin),
                values: vary
                    .iter()
                    .zip(&case.indices)
                    .map(|(v, &index)| (v.path.clone(), display_value(&v.value(index))))
                    .collect(),
                reproduce: f.reproduce.unwrap_or_default().to_string(),
            }
        });
        let closest = outcome
            .cases
            .iter()
            .enumerate()
            .filter_map(|(i, c)| Some((i, c, c.score.margin?)))
            .min_by(|a, b| a.2.total_cmp(&b.2))
            .map(|(i, case, margin)| ClosestView {
                case: i + 1,
                requirement: requirement(case),
                margin: number(margin),
            })
            .filter(|_| counterexample.is_none());
        Ok(View {
            document: document_control(f),
            name: &f.scenario.name,
            provenance: provenance(f),
            settings: settings(f, tried),
            space: vary.iter().map(setting_view).collect(),
            tried,
            columns: vary.iter().map(|v| v.path.as_str()).collect(),
            cases: outcome
                .cases
                .iter()
                .enumerate()
                .map(|(i, case)| CaseView {
                    number: i + 1,
                    phase: phase_name(case.phase),
                    values: vary
                        .iter()
                        .zip(&case.indices)
                        .map(|(v, &index)| display_value(&v.value(index)))
                        .collect(),
                    requirement: requirement(case),
                    status: case.score.status.name(),
                    margin: or_dash(case.score.margin),
                    mark: if outcome.counterexample == Some(i) {
                        "counterexample"
                    } else if outcome.first_counterexample == Some(i + 1) {
                        "first counterexample"
                    } else {
                        ""
                    },
                })
                .collect(),
            chart: margin_chart(&outcome.cases, outcome.counterexample)?,
            counterexample,
            closest,
            requirements: f
                .scenario
                .requirements
                .iter()
                .map(|requirement| {
                    let tally = Tally::of(outcome, &requirement.id);
                    let first = tally.by_counterexample.or(tally.first_broken.map(|(_, j)| j));
                    RequirementView {
                        id: requirement.id.clone(),
                        verdict: match first {
                            Some(judged) => judged.status.name(),
                            None if tally.exercised == 0 => Status::NotExercised.name(),
                            None => Status::Pass.name(),
                        },
                        exercised: tally.exercised,
                        broken: tally.broken,
                        first_broken: tally.first_broken.map(|(i, _)| i + 1),
                        smallest: or_dash(tally.smallest),
                    }
                })
                .collect(),
        })
    }
}

/// The falsification report's document control: its id is [`content_id`] of
/// falsify.json without the scenario's path and the command (which spell the
/// path as typed), with what they stood for by content instead: the tool, the
/// hashes of the scenario and of the files it imports, and the search's
/// limits. So the same search of the same files gives the same id however the
/// file was named, and another tool, file or limit gives another.
fn document_control(f: &Falsification<'_>) -> DocumentView {
    let mut content = serde_json::to_value(document(f)).expect("falsify.json serializes");
    if let Some(object) = content.as_object_mut() {
        object.remove("scenario");
        object.remove("command");
        object.insert(
            "tool".into(),
            serde_json::to_value(f.tool).expect("the tool serializes"),
        );
        object.insert("scenario_sha256".into(), f.scenario_sha256.into());
        let imports: Vec<String> = f.scenario.imports.iter().map(|i| crate::hex(&i.sha256)).collect();
        object.insert("imports_sha256".into(), imports.into());
        object.insert(
            "limits".into(),
            serde_json::json!({
                "cases": f.search.cases,
                "shrink_cases": f.search.shrink_cases,
                "budget": f.budget,
            }),
        );
    }
    control(content_id(content), &f.execution.started, &f.scenario.document)
}

fn phase_name(phase: Phase) -> &'static str {
    match phase {
        Phase::Random => "random",
        Phase::Guided => "guided",
        Phase::Shrink => "shrink",
    }
}

fn provenance(f: &Falsification<'_>) -> Vec<(&'static str, String)> {
    let (tool, execution) = (f.tool, f.execution);
    vec![
        ("Tool", format!("{} {} (git {})", tool.name, tool.version, tool.git)),
        ("Platform", execution.platform()),
        ("Started", execution.started.clone()),
        ("Duration", format!("{} s", execution.duration_seconds)),
        ("Scenario file", f.scenario.file.clone()),
        ("Scenario SHA-256", f.scenario_sha256.to_string()),
        ("Reproduce with", f.command.to_string()),
    ]
}

fn settings(f: &Falsification<'_>, tried: usize) -> Vec<(&'static str, String)> {
    let search = f.search;
    let all = f.outcome.cases.len();
    vec![
        (
            "Mode",
            if search.guided {
                "guided: random cases and, after the first few, every other case a step from the case with the smallest margin so far"
            } else {
                "random: cases drawn uniformly from the space"
            }
            .into(),
        ),
        ("Seed", search.seed.to_string()),
        ("Cases", format!("at most {} before shrinking; {tried} tried", search.cases)),
        (
            "Budget",
            f.budget
                .map_or_else(|| "none (the cases above)".into(), |s| format!("{s} s of wall-clock time")),
        ),
        (
            "Shrinking",
            format!("at most {} cases; {} tried", search.shrink_cases, all - tried),
        ),
        ("Simulations", format!("{} (each distinct case once)", f.simulations)),
    ]
}

fn setting_view(vary: &Vary) -> SettingView {
    let values = match &vary.domain {
        Domain::Range { lo, hi, integer: true } => {
            format!("whole numbers from {} to {}", number(*lo), number(*hi))
        }
        Domain::Range { lo, hi, .. } => format!(
            "from {} to {} in {} equal steps",
            number(*lo),
            number(*hi),
            vary.count().saturating_sub(1)
        ),
        Domain::Choices(values) => {
            let values: Vec<String> = values.iter().map(display_value).collect();
            format!("one of {}", values.join(", "))
        }
    };
    SettingView {
        path: vary.path.clone(),
        values,
    }
}
