//! The page's view: the banner, the findings, the provenance rows and the
//! context of the argument, assembled from the sections' views and rendered with
//! the template set.

use serde::Serialize;

use sightline_dsl::{Scenario, display_value};

use super::document::{AppendixView, DocumentView, SelftestView, appendix, document, selftest};
use super::format::TableView;
use super::point::{point_body, samples_table};
use super::requirement::{Finding, RequirementView, finding, requirement_view};
use super::scope::scope;
use super::sweep::{ComparisonView, SweepView, comparisons, sweep_tables};
use crate::chart::Chart;
use crate::picture::Pictures;
use crate::results::{Results, Status, Summary};
use crate::template::{TemplateError, Templates};

/// What a run's page shows beyond its results.
#[derive(Debug, Clone, Copy)]
pub struct RunPage<'a> {
    /// The scenario as compiled (its scope and its `document` section).
    pub scenario: &'a Scenario,
    /// The scenario file's text, shown verbatim in the appendix.
    pub text: &'a str,
    /// The command that re-creates the run.
    pub reproduce: &'a str,
    /// The grid pictures of each point (world points only).
    pub pictures: &'a [Option<Pictures>],
    /// The charts of each point.
    pub charts: &'a [Vec<Chart>],
    /// The charts of each sweep.
    pub sweep_charts: &'a [Vec<Chart>],
}

/// Renders the report of `results` with `templates` (a
/// [`Page::Run`](crate::Page::Run) set).
pub fn html(results: &Results, page: &RunPage<'_>, templates: &Templates) -> Result<String, TemplateError> {
    let mut view = View::new(results, page.reproduce, page.pictures, page.charts);
    for (sweep, charts) in view.sweeps.iter_mut().zip(page.sweep_charts) {
        sweep.charts.clone_from(charts);
    }
    view.document = Some(document(results, page.scenario));
    view.scope = scope(page.scenario);
    view.selftest = Some(selftest());
    view.appendix = Some(appendix(results, page.text));
    templates.render(&view, results)
}

#[derive(Serialize)]
struct View<'a> {
    name: &'a str,
    description: &'a str,
    verdict: &'static str,
    /// `pass` or `fail`: what `sightline run` exits with.
    gate: &'static str,
    summary: Summary,
    /// Every requirement that fails the run, and every accepted not-exercised
    /// one, at its deciding point.
    findings: Vec<Finding>,
    provenance: Vec<(&'static str, String)>,
    /// The operational scenario as declared, for the argument's context.
    context: Vec<String>,
    requirements: Vec<RequirementView>,
    sweeps: Vec<SweepView>,
    comparisons: Vec<ComparisonView>,
    points: Vec<PointView>,
    /// Document control and the paper size.
    document: Option<DocumentView>,
    /// The scope and operational design domain, (aspect, value) rows.
    scope: Vec<(&'static str, String)>,
    /// The tool's self-test, run in this process.
    selftest: Option<SelftestView>,
    /// The scenario file verbatim.
    appendix: Option<AppendixView>,
}

#[derive(Serialize)]
struct PointView {
    label: String,
    summary: String,
    tables: Vec<TableView>,
    pictures: Option<Pictures>,
    charts: Vec<Chart>,
}

impl<'a> View<'a> {
    fn new(results: &'a Results, reproduce: &str, pictures: &[Option<Pictures>], charts: &[Vec<Chart>]) -> Self {
        View {
            name: &results.scenario.name,
            description: &results.scenario.description,
            verdict: results.verdict.name(),
            gate: results.gate.name(),
            summary: results.summary,
            findings: results
                .requirements
                .iter()
                .filter(|r| r.verdict != Status::Pass)
                .map(finding)
                .collect(),
            provenance: provenance(results, reproduce),
            context: context(results),
            requirements: results.requirements.iter().map(requirement_view).collect(),
            sweeps: sweep_tables(results),
            comparisons: comparisons(results),
            points: results
                .sweep
                .iter()
                .zip(pictures)
                .zip(charts)
                .map(|((point, pictures), charts)| {
                    let (summary, mut tables) = point_body(point);
                    tables.insert(0, samples_table(point));
                    PointView {
                        label: if point.label.is_empty() {
                            "the scenario".into()
                        } else {
                            point.label.clone()
                        },
                        summary,
                        tables,
                        pictures: pictures.clone(),
                        charts: charts.clone(),
                    }
                })
                .collect(),
            document: None,
            scope: Vec::new(),
            selftest: None,
            appendix: None,
        }
    }
}

/// The context of the argument: the scenario file and what it imports, its
/// seeds and the settings it sweeps.
fn context(results: &Results) -> Vec<String> {
    let mut context: Vec<String> = results
        .inputs
        .iter()
        .map(|input| format!("{} ({})", input.path, input.kind))
        .collect();
    context.push(match results.seed {
        Some(seed) => format!("seed {seed}"),
        None => "seeds as swept".into(),
    });
    for sweep in &results.sweeps {
        let axes: Vec<String> = sweep
            .axes
            .iter()
            .map(|a| {
                let values: Vec<String> = a.values.iter().map(display_value).collect();
                format!("{} ∈ {{{}}}", a.path, values.join(", "))
            })
            .collect();
        context.push(format!("swept: {}", axes.join(" × ")));
    }
    context
}

fn provenance(results: &Results, reproduce: &str) -> Vec<(&'static str, String)> {
    let tool = &results.tool;
    let execution = &results.execution;
    let mut rows = vec![
        ("Tool", format!("{} {} (git {})", tool.name, tool.version, tool.git)),
        ("Platform", execution.platform()),
        ("Started", execution.started.clone()),
        ("Duration", format!("{} s", execution.duration_seconds)),
        ("Scenario file", results.scenario.path.clone()),
        ("Scenario SHA-256", results.scenario.sha256.clone()),
    ];
    // The scenario is the first input; the rest are the files it imports.
    rows.extend(results.inputs.iter().skip(1).map(|input| {
        (
            "Imported file",
            format!("{} ({}), SHA-256 {}", input.path, input.kind, input.sha256),
        )
    }));
    rows.extend(results.recording.iter().map(|recording| {
        let point = if recording.every_point {
            format!("every point, {} of them, one after another", results.sweep.len())
        } else if recording.label.is_empty() {
            format!("point {}", recording.point)
        } else {
            format!("point {}: {}", recording.point, recording.label)
        };
        (
            "Recording",
            format!("{} ({point}), SHA-256 {}", recording.file, recording.sha256),
        )
    }));
    rows.extend(
        results
            .recording
            .iter()
            .filter_map(|recording| recording.osi_trace.as_ref())
            .map(|osi| {
                (
                    "OSI trace",
                    format!("{} (the same point), SHA-256 {}", osi.file, osi.sha256),
                )
            }),
    );
    rows.extend([
        (
            "Seed",
            results
                .seed
                .map_or_else(|| "swept (see the table)".into(), |s| s.to_string()),
        ),
        ("Sweep points", results.sweep.len().to_string()),
        ("Reproduce with", reproduce.to_string()),
    ]);
    rows
}
