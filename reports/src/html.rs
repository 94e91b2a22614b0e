//! report.html of a run: one self-contained page (inline CSS, no script, no
//! network) for an assessor, rendered from its template ([`Templates`]). Numbers
//! are formatted here so the template only lays them out.

use serde::Serialize;

use sightline_dsl::{Metric, RateBound, Statistic, display_value};
use sightline_oracles::Status;

use sightline_engine::outcome::{DELIVERY_BIN, DENSITY_BIN, DensityRow, SemanticMetrics, quantile};

use crate::chart::Chart;
use crate::picture::Pictures;
use crate::results::{CheckInfo, Detail, PointResult, RequirementResult, Results, Summary};
use crate::template::{TemplateError, Templates};

/// Metrics every sweep table shows; metrics that requirements or references use
/// are added after them.
const TABLE_METRICS: [&str; 11] = [
    "occupied_recall",
    "blind_recall",
    "occupied_precision",
    "fov_gain",
    "accuracy",
    "below_threshold",
    "false_alarms",
    "missed_detections",
    "confident_errors",
    "decided_unknown",
    "mean_conflict",
];

/// Renders the report with `templates` (a [`Page::Run`](crate::Page::Run)
/// set). `reproduce` is the command that re-creates the run; `pictures` holds
/// the grid pictures of each point (world points only), `charts` the charts of
/// each point, `sweep_charts` those of each sweep.
pub fn html(
    results: &Results,
    reproduce: &str,
    pictures: &[Option<Pictures>],
    charts: &[Vec<Chart>],
    sweep_charts: &[Vec<Chart>],
    templates: &Templates,
) -> Result<String, TemplateError> {
    let mut view = View::new(results, reproduce, pictures, charts);
    for (sweep, charts) in view.sweeps.iter_mut().zip(sweep_charts) {
        sweep.charts.clone_from(charts);
    }
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
}

/// A requirement that did not pass, as the banner names it.
#[derive(Serialize)]
struct Finding {
    id: String,
    anchor: String,
    verdict: &'static str,
    /// The verdict in words (`not exercised`).
    words: &'static str,
    /// Whether it fails the run (not an accepted not-exercised verdict).
    fails_run: bool,
    /// The reason a not-exercised verdict is accepted.
    accepted: Option<String>,
    /// The deciding point's label (empty without a sweep).
    label: String,
    measured: String,
    /// What the measured value holds, with its n.
    what: String,
    threshold: String,
    margin: String,
    n: String,
    message: String,
}

#[derive(Serialize)]
struct RequirementView {
    id: String,
    anchor: String,
    text: String,
    line: usize,
    check: String,
    measured: String,
    /// What `measured` holds, with its n.
    what: String,
    threshold: String,
    margin: String,
    verdict: &'static str,
    words: &'static str,
    accepted: Option<String>,
    message: String,
    points: Vec<EvaluationView>,
}

#[derive(Serialize)]
struct EvaluationView {
    label: String,
    verdict: &'static str,
    words: &'static str,
    measured: String,
    what: String,
    margin: String,
    message: String,
}

#[derive(Serialize)]
struct TableView {
    /// What the table shows; empty for none.
    caption: String,
    head: Vec<String>,
    rows: Vec<Vec<String>>,
    /// Leading columns that hold text (labels), not numbers.
    text_columns: usize,
}

#[derive(Serialize)]
struct SweepView {
    title: String,
    table: TableView,
    charts: Vec<Chart>,
}

#[derive(Serialize)]
struct ComparisonView {
    source: String,
    label: String,
    metric: &'static str,
    published: String,
    measured: String,
    ratio: String,
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
        }
    }
}

/// A measured value, or a dash where it is undefined.
pub(crate) fn or_dash(value: Option<f64>) -> String {
    value.map_or_else(|| "—".into(), number)
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
        let point = if recording.label.is_empty() {
            format!("point {}", recording.point)
        } else {
            format!("point {}: {}", recording.point, recording.label)
        };
        (
            "Recording",
            format!("{} ({point}), SHA-256 {}", recording.file, recording.sha256),
        )
    }));
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

fn finding(r: &RequirementResult) -> Finding {
    let decisive = r.points.iter().find(|p| p.point == r.point);
    Finding {
        id: r.id.clone(),
        anchor: format!("req-{}", r.id),
        verdict: r.verdict.name(),
        words: r.verdict.words(),
        fails_run: r.fails_run,
        accepted: r.accept_not_exercised.clone(),
        label: decisive.map(|p| p.label.clone()).unwrap_or_default(),
        measured: or_dash(r.value),
        what: r.measured.clone(),
        threshold: format!("{} {}", relation_sign(r.check.relation), number(r.threshold)),
        margin: or_dash(r.margin),
        n: r.n.map_or_else(|| "—".into(), |n| number(n as f64)),
        message: r.message.clone(),
    }
}

/// `≥`, `≤` or `tolerance`, for a check's relation.
fn relation_sign(relation: &str) -> &str {
    match relation {
        "at_least" => "≥",
        "at_most" => "≤",
        other => other,
    }
}

fn requirement_view(r: &RequirementResult) -> RequirementView {
    RequirementView {
        id: r.id.clone(),
        anchor: format!("req-{}", r.id),
        text: r.text.clone(),
        line: r.line,
        check: describe_check(&r.check),
        measured: or_dash(r.value),
        what: r.measured.clone(),
        threshold: number(r.threshold),
        margin: or_dash(r.margin),
        verdict: r.verdict.name(),
        words: r.verdict.words(),
        accepted: r.accept_not_exercised.clone(),
        message: r.message.clone(),
        points: r
            .points
            .iter()
            .map(|p| EvaluationView {
                label: if p.label.is_empty() {
                    "—".into()
                } else {
                    p.label.clone()
                },
                verdict: p.verdict.name(),
                words: p.verdict.words(),
                measured: or_dash(p.value),
                what: p.measured.clone(),
                margin: or_dash(p.margin),
                message: p.message.clone(),
            })
            .collect(),
    }
}

/// A row of a sweep table: the point and the sweep's values there.
type Row<'a> = (&'a PointResult, Vec<&'a serde_json::Value>);

/// One table per sweep, a point that sweeps share in each of their tables (one
/// table of the single point without a sweep).
fn sweep_tables(results: &Results) -> Vec<SweepView> {
    if results.sweeps.is_empty() {
        let all: Vec<Row<'_>> = results.sweep.iter().map(|point| (point, Vec::new())).collect();
        return vec![SweepView {
            title: "Results".into(),
            table: sweep_table(results, &[], &all),
            charts: Vec::new(),
        }];
    }
    results
        .sweeps
        .iter()
        .map(|sweep| {
            let paths: Vec<&str> = sweep.axes.iter().map(|a| a.path.as_str()).collect();
            let rows: Vec<Row<'_>> = sweep.rows().map(|(p, values)| (&results.sweep[p], values)).collect();
            SweepView {
                title: format!("Results over {}", paths.join(" × ")),
                table: sweep_table(results, &paths, &rows),
                charts: Vec::new(),
            }
        })
        .collect()
}

/// One row per combination: the axis values, then [`TABLE_METRICS`] and every
/// metric a requirement or reference uses, each followed by its published value
/// if any.
fn sweep_table(results: &Results, axes: &[&str], rows: &[Row<'_>]) -> TableView {
    let mut metrics: Vec<&str> = TABLE_METRICS.to_vec();
    for name in results.cited_metrics() {
        if !metrics.contains(&name) {
            metrics.push(name);
        }
    }
    metrics.retain(|m| rows.iter().any(|(p, _)| p.metrics.0.iter().any(|(k, _)| k == m)));
    let has_published = |metric: &str| results.references.iter().any(|r| r.metric == metric);

    let mut head: Vec<String> = axes.iter().map(|a| (*a).to_string()).collect();
    for metric in &metrics {
        head.push((*metric).to_string());
        if has_published(metric) {
            head.push(format!("{metric} (published)"));
        }
    }
    let rows = rows
        .iter()
        .map(|(point, values)| {
            let mut row: Vec<String> = values.iter().map(|v| display_value(v)).collect();
            for metric in &metrics {
                row.push(or_dash(point.metrics.get(metric)));
                if has_published(metric) {
                    let values: Vec<String> = results
                        .references
                        .iter()
                        .filter(|r| r.metric == *metric && r.points.iter().any(|p| p.point == point.index))
                        .map(|r| number(r.published))
                        .collect();
                    row.push(if values.is_empty() {
                        "—".into()
                    } else {
                        values.join(" / ")
                    });
                }
            }
            row
        })
        .collect();
    TableView {
        caption: String::new(),
        head,
        rows,
        text_columns: axes.len(),
    }
}

fn comparisons(results: &Results) -> Vec<ComparisonView> {
    results
        .references
        .iter()
        .flat_map(|r| {
            r.points.iter().map(move |p| ComparisonView {
                source: r.source.clone(),
                label: p.label.clone(),
                metric: r.metric,
                published: number(r.published),
                measured: or_dash(p.measured),
                ratio: p
                    .measured
                    .filter(|_| r.published != 0.0)
                    .map_or_else(|| "—".into(), |m| format!("{:.2}×", m / r.published)),
            })
        })
        .collect()
}

const BAND_COLUMNS: [&str; 7] = [
    "distance to nearest sensor",
    "cells",
    "accuracy",
    "below threshold",
    "false alarms",
    "missed detections",
    "mean conflict",
];

/// The summary line and the tables of a point's details.
/// Every metric the point measures, with its sample size and what it counts.
fn samples_table(p: &PointResult) -> TableView {
    let rows = p
        .samples
        .0
        .iter()
        .map(|(name, n)| {
            let population = Metric::ALL
                .iter()
                .find(|m| m.name() == name)
                .map_or("", |m| m.population());
            vec![
                name.clone(),
                population.to_string(),
                or_dash(p.metrics.get(name)),
                number(*n as f64),
            ]
        })
        .collect();
    TableView {
        caption: "Every metric with its sample size n (— where the population is empty)".into(),
        head: ["metric", "n counts", "value", "n"].map(String::from).to_vec(),
        rows,
        text_columns: 2,
    }
}

fn point_body(p: &PointResult) -> (String, Vec<TableView>) {
    match &p.detail {
        Detail::Field { bands, coverage: c } => (
            format!(
                "{} sensors; {}–{} observe each cell (mean {:.2})",
                c.sensors, c.min_sources, c.max_sources, c.mean_sources
            ),
            vec![TableView {
                caption: String::new(),
                text_columns: 1,
                head: BAND_COLUMNS.map(String::from).to_vec(),
                rows: bands
                    .iter()
                    .map(|b| {
                        vec![
                            match b.to {
                                Some(to) => format!("{} – {} m", number(b.from), number(to)),
                                None => format!("≥ {} m", number(b.from)),
                            },
                            number(b.cells as f64),
                            or_dash(b.accuracy),
                            number(b.below_threshold as f64),
                            number(b.false_alarms as f64),
                            number(b.missed_detections as f64),
                            or_dash(b.mean_conflict),
                        ]
                    })
                    .collect(),
            }],
        ),
        Detail::World { counts: c } => {
            let s = &c.sightings;
            let rows = [
                ("steps with the ego in the scene", c.steps as f64),
                ("occupied cell-steps", c.occupied as f64),
                ("… decided Occupy", c.detected as f64),
                ("free cell-steps decided Occupy", c.false_positives as f64),
                ("occupied cell-steps the ego did not observe", c.blind_occupied as f64),
                ("… decided Occupy", c.blind_detected as f64),
                ("cell-steps observed by the ego", c.ego_observed as f64),
                ("cell-steps observed by any cooperating agent", c.joint_observed as f64),
                ("targets in line of sight (sensor–target pairs)", s.los as f64),
                ("… hidden by an occluder", s.nlos_static as f64),
                ("… hidden by other agents", s.nlos_dynamic as f64),
                ("… detected", s.detected as f64),
            ];
            let mut rows: Vec<Vec<String>> = rows.iter().map(|(k, v)| vec![(*k).to_string(), number(*v)]).collect();
            rows.push(vec![
                "mean pose-estimate error, m".into(),
                or_dash(c.localization_error),
            ]);
            (format!("{} steps", c.steps), vec![counts_table(rows)])
        }
        Detail::Semantic {
            counts: c,
            contribution_by_density,
        } => (
            format!(
                "{} pooled run(s): {} steps with the ego, {} generated road users, {} anticipated objects",
                c.runs,
                c.steps,
                c.generated,
                c.anticipation.len()
            ),
            semantic_tables(c, contribution_by_density),
        ),
    }
}

fn counts_table(rows: Vec<Vec<String>>) -> TableView {
    TableView {
        caption: String::new(),
        text_columns: 1,
        head: vec!["count".into(), "value".into()],
        rows,
    }
}

/// The counts of a semantic run, its contribution by density and its packet
/// delivery by distance.
fn semantic_tables(c: &SemanticMetrics, density: &[DensityRow]) -> Vec<TableView> {
    let l = &c.labels;
    let counts = [
        ("steps with the ego in the scene", c.steps as f64),
        (
            "objects anticipated (learned of while hidden, later seen)",
            c.anticipation.len() as f64,
        ),
        ("objects learned of while hidden and never seen", c.never_seen as f64),
        (
            "object-cycles perceived by the RSUs (in the cycles the shares count)",
            c.perceived as f64,
        ),
        ("… sent to the ego", c.transmitted as f64),
        ("… with at least one label", c.labelled as f64),
        ("… labelled NLoS behind an occluder", l.nlos_static as f64),
        ("… labelled NLoS behind road users", l.nlos_dynamic as f64),
        ("… labelled relevant", l.relevant as f64),
        ("… labelled speeding", l.speeding as f64),
        ("… labelled with a predicted conflict", l.conflict as f64),
        ("object-cycles the ETSI baseline sends", c.baseline_objects as f64),
        ("bytes of semantic messages", c.bytes as f64),
        ("bytes of ETSI baseline messages", c.baseline_bytes as f64),
        ("messages sent to the ego", c.messages as f64),
        ("… received", c.delivered as f64),
        ("close approaches (within d_min of the ego)", c.close_approaches as f64),
        ("… with no conflict flagged beforehand", c.missed_criticals as f64),
        ("seconds the ego drove cautiously", c.cautious_time),
    ];
    let by_density = TableView {
        caption: "Objects the ego knows only through an RSU, by traffic density".into(),
        text_columns: 1,
        head: ["objects per km", "steps", "median", "mean"].map(String::from).to_vec(),
        rows: density
            .iter()
            .map(|r| {
                vec![
                    format!("{} – {}", number(r.from), number(r.from + DENSITY_BIN)),
                    number(r.steps as f64),
                    number(r.median),
                    number(r.mean),
                ]
            })
            .collect(),
    };
    let by_distance = TableView {
        caption: "Messages to the ego by RSU–ego distance".into(),
        text_columns: 1,
        head: ["distance", "sent", "received", "delivery ratio"]
            .map(String::from)
            .to_vec(),
        rows: c
            .delivery_by_distance
            .iter()
            .enumerate()
            .filter(|(_, b)| b.sent > 0)
            .map(|(i, b)| {
                let from = i as f64 * DELIVERY_BIN;
                vec![
                    format!("{} – {} m", number(from), number(from + DELIVERY_BIN)),
                    number(b.sent as f64),
                    number(b.received as f64),
                    number(b.received as f64 / b.sent as f64),
                ]
            })
            .collect(),
    };
    let quantiles = [0.0, 0.25, 0.5, 0.75, 0.95, 1.0];
    let anticipation = TableView {
        caption: "Anticipation time, seconds (type 7 quantiles over the pooled objects)".into(),
        text_columns: 0,
        head: ["objects", "min", "25 %", "median", "75 %", "95 %", "max"]
            .map(String::from)
            .to_vec(),
        rows: vec![
            std::iter::once(number(c.anticipation.len() as f64))
                .chain(quantiles.iter().map(|&q| or_dash(quantile(&c.anticipation, q))))
                .collect(),
        ],
    };
    vec![
        counts_table(counts.iter().map(|(k, v)| vec![(*k).to_string(), number(*v)]).collect()),
        anticipation,
        by_density,
        by_distance,
    ]
}

fn describe_check(check: &CheckInfo) -> String {
    let (name, threshold) = (check.name, number(check.threshold));
    let relation = match check.relation {
        "at_least" | "at_most" => format!("{name} {} {threshold}", relation_sign(check.relation)),
        _ => return format!("invariant {name} (tolerance {threshold})"),
    };
    match check.kind {
        "always" | "eventually" => {
            let window = check
                .within
                .map_or(String::new(), |w| format!(" within {} s", number(w)));
            return format!("{} {relation}{window}", check.kind);
        }
        "per_object" => return format!("every object within d_min: {relation}"),
        _ => {}
    }
    let Some(over) = check.over_seeds else {
        return relation;
    };
    let confidence = number(over.confidence * 100.0);
    match over.statistic {
        Statistic::Mean => format!(
            "mean over {} seeds: {relation} at {confidence} % confidence (Student t)",
            over.seeds
        ),
        Statistic::Share { share, method } => format!(
            "{relation} at ≥ {} % of {} seeds, at {confidence} % confidence ({})",
            number(share * 100.0),
            over.seeds,
            match method {
                RateBound::ClopperPearson => "Clopper–Pearson",
                RateBound::Wilson => "Wilson",
            }
        ),
    }
}

/// A number for people: counts with thousands separators, fractions to four
/// decimals, tiny values in scientific notation.
pub(crate) fn number(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    if value == value.trunc() && value.abs() < 1e15 {
        let digits = format!("{}", value.abs() as u64);
        let mut grouped = String::new();
        for (i, c) in digits.chars().enumerate() {
            if i > 0 && (digits.len() - i) % 3 == 0 {
                grouped.push(',');
            }
            grouped.push(c);
        }
        return if value < 0.0 { format!("-{grouped}") } else { grouped };
    }
    if value.abs() < 1e-3 {
        format!("{value:.2e}")
    } else if value.abs() < 10.0 {
        format!("{value:.4}")
    } else {
        format!("{value:.2}")
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::Metric;

    use super::*;

    #[test]
    fn numbers_read_like_the_paper() {
        assert_eq!(number(59862.0), "59,862");
        assert_eq!(number(-1425.0), "-1,425");
        assert_eq!(number(0.97871), "0.9787");
        assert_eq!(number(1e-9), "1.00e-9");
        assert_eq!(number(123.456), "123.46");
        assert_eq!(number(0.0), "0");
    }

    #[test]
    fn metric_list_is_known() {
        for name in TABLE_METRICS {
            assert!(Metric::ALL.iter().any(|m| m.name() == name), "{name}");
        }
    }
}
