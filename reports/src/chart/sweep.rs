//! A sweep's charts: each cited metric over the sweep's first numeric axis,
//! one line per combination of the other settings.

use super::canvas::{Chart, ChartError};
use super::lines::{Line, lines_chart};
use crate::results::{Axis, PointResult, Results};

/// One chart per metric a requirement or reference cites, for each sweep with a
/// numeric axis: the metric over the first numeric axis, one line per
/// combination of the other settings, published values as crosses. One list per
/// sweep, in sweep order.
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
            let axis = &sweep.axes[column];
            let rows: Vec<(&PointResult, &[serde_json::Value])> = sweep
                .rows
                .iter()
                .map(|row| (&results.sweep[row.point], &row.values[..]))
                .collect();
            let mut charts = Vec::new();
            for &metric in &metrics {
                let mut lines: Vec<Line> = Vec::new();
                for (point, values) in &rows {
                    let (Some(x), Some(y)) = (values[column].as_f64(), point.metrics.get(metric)) else {
                        continue;
                    };
                    let name = others(point, &sweep.axes, values, column);
                    match lines.iter_mut().find(|l| l.name == name) {
                        Some(line) => line.points.push((x, y)),
                        None => lines.push(Line {
                            name,
                            points: vec![(x, y)],
                        }),
                    }
                }
                for line in &mut lines {
                    line.points.sort_by(|a, b| a.0.total_cmp(&b.0));
                }
                let published: Vec<(f64, f64)> = results
                    .references
                    .iter()
                    .filter(|r| r.metric == metric)
                    .flat_map(|r| r.points.iter().map(move |p| (p.point, r.published)))
                    .flat_map(|(p, value)| {
                        rows.iter()
                            .filter(move |(point, _)| point.index == p)
                            .filter_map(move |(_, values)| Some((values[column].as_f64()?, value)))
                    })
                    .collect();
                let caption = format!("{metric} over {}", axis.path);
                charts.extend(lines_chart(caption, (&axis.path, metric), &lines, &published)?);
            }
            Ok(charts)
        })
        .collect()
}

/// A row's other swept settings (all but the charted `column`) and its method,
/// as a legend entry.
fn others(point: &PointResult, axes: &[Axis], values: &[serde_json::Value], column: usize) -> String {
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
    if parts.is_empty() {
        "measured".into()
    } else {
        parts.join(", ")
    }
}
