//! A sweep's charts: each cited metric over the sweep's first numeric axis,
//! one line per combination of the other settings (named by what differs
//! between the lines; what they share goes into the caption), with the
//! thresholds of the requirements that bound the metric at the sweep's points.

use super::canvas::{Chart, ChartError, tick};
use super::lines::{Line, LinesChart, Threshold};
use crate::results::{Axis, PointResult, Results, Sweep, metric_unit};

/// Points of a line.
type Points = Vec<(f64, f64)>;

/// One chart per metric a requirement or reference cites, for each sweep with a
/// numeric axis: the metric over the first numeric axis, one line per
/// combination of the other settings, published values as crosses, and the
/// requirements' thresholds. One list per sweep, in sweep order.
pub(crate) fn sweep_charts(results: &Results) -> Result<Vec<Vec<Chart>>, ChartError> {
    let metrics = results.cited_metrics();
    results
        .sweeps
        .iter()
        .map(|sweep| {
            let Some(column) = sweep
                .axes
                .iter()
                .position(|a| a.values.iter().all(serde_json::Value::is_number))
            else {
                return Ok(Vec::new());
            };
            let mut charts = Vec::new();
            for &metric in &metrics {
                charts.extend(metric_chart(results, sweep, column, metric).draw()?);
            }
            Ok(charts)
        })
        .collect()
}

/// `metric` over axis `column` of `sweep`.
fn metric_chart(results: &Results, sweep: &Sweep, column: usize, metric: &'static str) -> LinesChart {
    let axis = &sweep.axes[column];
    let rows: Vec<(&PointResult, &[serde_json::Value])> = sweep
        .rows
        .iter()
        .map(|row| (&results.sweep[row.point], &row.values[..]))
        .collect();
    let x_at = |point: usize| {
        rows.iter()
            .find(|(p, _)| p.index == point)
            .and_then(|(_, values)| values[column].as_f64())
    };
    // Each line's name as its settings, each setting apart.
    let mut named: Vec<(Vec<String>, Points)> = Vec::new();
    for (point, values) in &rows {
        let (Some(x), Some(y)) = (values[column].as_f64(), point.metrics.get(metric)) else {
            continue;
        };
        let parts = others(point, &sweep.axes, values, column);
        match named.iter_mut().find(|(n, _)| *n == parts) {
            Some((_, points)) => points.push((x, y)),
            None => named.push((parts, vec![(x, y)])),
        }
    }
    let shared: Vec<String> = named.first().map_or_else(Vec::new, |(first, _)| {
        first
            .iter()
            .filter(|part| named.iter().all(|(n, _)| n.contains(part)))
            .cloned()
            .collect()
    });
    let lines: Vec<Line> = named
        .into_iter()
        .map(|(parts, mut points)| {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let own: Vec<String> = parts.into_iter().filter(|p| !shared.contains(p)).collect();
            Line {
                name: if own.is_empty() {
                    "measured".into()
                } else {
                    own.join(", ")
                },
                points,
            }
        })
        .collect();
    let published: Vec<(f64, f64)> = results
        .references
        .iter()
        .filter(|r| r.metric == metric)
        .flat_map(|r| r.points.iter().filter_map(|p| Some((x_at(p.point)?, r.published))))
        .collect();
    let unit = metric_unit(metric);
    let thresholds = thresholds(results, metric, x_at);
    let mut caption = format!("{metric} over {}", axis.path);
    if !shared.is_empty() {
        caption.push_str(&format!(" (every line: {})", shared.join(", ")));
    }
    if !thresholds.is_empty() {
        caption.push_str("; dashed black: the requirements' thresholds, over the points they apply to");
    }
    caption.push('.');
    LinesChart {
        caption,
        x_desc: axis_desc(axis),
        y_desc: format!("{metric} ({unit})"),
        lines,
        published,
        thresholds,
    }
}

/// A requirement's bound and the requirements that set it over the same points.
struct Bound<'a> {
    ids: Vec<&'a str>,
    /// `≥ 0.9`, `≤ 1.5 s`.
    text: String,
    value: f64,
    x: (f64, f64),
}

/// The thresholds of the metric requirements on `metric` at the points of the
/// chart (`x_at` places them), requirements with the same bound over the same
/// points on one line.
fn thresholds(results: &Results, metric: &str, x_at: impl Fn(usize) -> Option<f64>) -> Vec<Threshold> {
    let unit = metric_unit(metric);
    let mut bounds: Vec<Bound<'_>> = Vec::new();
    for r in results
        .requirements
        .iter()
        .filter(|r| r.check.kind == "metric" && r.check.name == metric && r.check.relative_to.is_none())
    {
        let xs = r.points.iter().filter_map(|p| x_at(p.point));
        let Some(x) = xs.fold(None, |acc: Option<(f64, f64)>, x| {
            Some(acc.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))))
        }) else {
            continue;
        };
        let sign = if r.check.relation == "at_most" { "≤" } else { "≥" };
        // The metric's own bound: a share of seeds compares its share with
        // `r.threshold`, the metric with this.
        let threshold = r.check.threshold;
        let text = match unit {
            "1" => format!("{sign} {}", tick(&threshold)),
            unit => format!("{sign} {} {unit}", tick(&threshold)),
        };
        match bounds.iter_mut().find(|b| b.text == text && b.x == x) {
            Some(bound) => bound.ids.push(&r.id),
            None => bounds.push(Bound {
                ids: vec![&r.id],
                text,
                value: threshold,
                x,
            }),
        }
    }
    bounds
        .into_iter()
        .map(|b| Threshold {
            label: format!("{} {}", b.ids.join(", "), b.text),
            value: b.value,
            x: b.x,
        })
        .collect()
}

/// An axis's description: its path and unit.
fn axis_desc(axis: &Axis) -> String {
    match axis.unit.as_deref() {
        Some(unit) => format!("{} ({unit})", axis.path),
        None => axis.path.clone(),
    }
}

/// A row's other swept settings (all but the charted `column`) and its method,
/// each a part of its line's name.
fn others(point: &PointResult, axes: &[Axis], values: &[serde_json::Value], column: usize) -> Vec<String> {
    let mut parts: Vec<String> = axes
        .iter()
        .zip(values)
        .enumerate()
        .filter(|&(i, _)| i != column)
        .map(|(_, (axis, v))| format!("{}={}", axis.path, sightline_dsl::display_value(v)))
        .collect();
    if let Some(fusion) = point
        .fusion
        .as_ref()
        .filter(|f| !f.is_empty() && !axes.iter().any(|a| a.path.starts_with("fusion")))
    {
        parts.push(fusion.clone());
    }
    parts
}
