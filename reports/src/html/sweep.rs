//! The results table of each sweep (its axis values, the metrics every table
//! shows and those the requirements and references cite, with published values
//! beside them) and the comparisons with published figures.

use serde::Serialize;

use sightline_dsl::display_value;

use super::format::{TableView, head, metric_unit, number, or_dash, with_unit};
use crate::chart::Chart;
use crate::results::{Axis, PointResult, Results};

/// Metrics every sweep table shows; metrics that requirements or references use
/// are added after them.
const TABLE_METRICS: [&str; 16] = [
    "occupied_recall",
    "ego_occupied_recall",
    "blind_recall",
    "self_report_share",
    "brier_score",
    "occupied_precision",
    "fov_gain",
    "packet_delivery_ratio",
    "message_age_mean",
    "accuracy",
    "below_threshold",
    "false_alarms",
    "missed_detections",
    "confident_errors",
    "decided_unknown",
    "mean_conflict",
];

/// The most value columns a sweep table holds beside its axes: a wider one is
/// split into several, each with the axes, so that it prints on A4 portrait.
const COLUMNS_PER_TABLE: usize = 6;

/// The most columns, axes and values, a part of a sweep table holds: a table of
/// many axes takes fewer values a part (each at least two), since a figure's n
/// beneath it (`n = 3,109,682`) breaks nowhere.
const COLUMNS_PER_PART: usize = 9;

#[derive(Serialize)]
pub(super) struct SweepView {
    title: String,
    /// The table, split into parts of at most [`COLUMNS_PER_TABLE`] value
    /// columns beside the axes (fewer beside many axes:
    /// [`COLUMNS_PER_PART`]), each with its figures' sample sizes.
    tables: Vec<SweepPart>,
    /// The first part (the whole table when it is narrow enough).
    table: TableView,
    pub(super) charts: Vec<Chart>,
}

/// A part of a sweep's table, and beneath each figure its n.
#[derive(Serialize)]
struct SweepPart {
    #[serde(flatten)]
    table: TableView,
    /// Per cell of `rows`, the sample size of its figure (`9,554`), empty where
    /// none is shown (the axes, published values, a metric whose n every row
    /// shares: its head gives it).
    ns: Vec<Vec<String>>,
}

/// A sweep's view: its table, and that table in parts narrow enough to print,
/// with the sample size `ns` of each cell.
fn sweep_view(title: String, table: TableView, ns: &[Vec<String>]) -> SweepView {
    let axes = table.text_columns;
    let values = table.head.len().saturating_sub(axes);
    let per_part = COLUMNS_PER_PART.saturating_sub(axes).clamp(2, COLUMNS_PER_TABLE);
    let parts = values.div_ceil(per_part).max(1);
    let part = |i: usize| {
        let columns: Vec<usize> = (0..axes)
            .chain(axes + i * per_part..(axes + (i + 1) * per_part).min(table.head.len()))
            .collect();
        let pick = |rows: &[Vec<String>]| -> Vec<Vec<String>> {
            rows.iter()
                .map(|row| columns.iter().map(|&c| row[c].clone()).collect())
                .collect()
        };
        SweepPart {
            table: TableView {
                caption: if parts > 1 {
                    format!("Part {} of {parts}", i + 1)
                } else {
                    String::new()
                },
                head: columns.iter().map(|&c| table.head[c].clone()).collect(),
                rows: pick(&table.rows),
                text_columns: axes,
            },
            ns: pick(ns),
        }
    };
    SweepView {
        title,
        tables: (0..parts).map(part).collect(),
        table,
        charts: Vec::new(),
    }
}

#[derive(Serialize)]
pub(super) struct ComparisonView {
    source: String,
    label: String,
    metric: &'static str,
    published: String,
    measured: String,
    n: String,
    ratio: String,
}

/// A row of a sweep table: the point and the sweep's values there.
type Row<'a> = (&'a PointResult, &'a [serde_json::Value]);

/// One table per sweep, a point that sweeps share in each of their tables (one
/// table of the single point without a sweep).
pub(super) fn sweep_tables(results: &Results) -> Vec<SweepView> {
    if results.sweeps.is_empty() {
        let all: Vec<Row<'_>> = results.sweep.iter().map(|point| (point, &[][..])).collect();
        let (table, ns) = sweep_table(results, &[], &all);
        return vec![sweep_view("Results".into(), table, &ns)];
    }
    results
        .sweeps
        .iter()
        .map(|sweep| {
            let paths: Vec<&str> = sweep.axes.iter().map(|a| a.path.as_str()).collect();
            let rows: Vec<Row<'_>> = sweep
                .rows
                .iter()
                .map(|row| (&results.sweep[row.point], &row.values[..]))
                .collect();
            let (table, ns) = sweep_table(results, &sweep.axes, &rows);
            sweep_view(format!("Results over {}", paths.join(" × ")), table, &ns)
        })
        .collect()
}

/// One row per combination: the axis values, then [`TABLE_METRICS`] and every
/// metric a requirement or reference uses, each followed by its published value
/// if any; and the sample size n of each figure (the points' populations
/// differ: more cooperating agents leave fewer cells unseen): in the column's
/// head when every row of the table shares it (the field's million cells),
/// else beneath each figure.
fn sweep_table(results: &Results, axes: &[Axis], rows: &[Row<'_>]) -> (TableView, Vec<Vec<String>>) {
    // A default column where some row has a value; a cited one where some row
    // measures it, its value or — (over nobody: n = 0).
    let mut metrics: Vec<&str> = TABLE_METRICS
        .into_iter()
        .filter(|m| rows.iter().any(|(p, _)| p.metrics.get(m).is_some()))
        .collect();
    for name in results.cited_metrics() {
        if !metrics.contains(&name) && rows.iter().any(|(p, _)| p.samples.get(name).is_some()) {
            metrics.push(name);
        }
    }
    let has_published = |metric: &str| results.references.iter().any(|r| r.metric == metric);

    let mut heads: Vec<String> = axes
        .iter()
        .map(|a| match &a.unit {
            Some(unit) => head(&a.path, unit),
            None => a.path.clone(),
        })
        .collect();
    // Each metric's n where it is the same in every row, for its head.
    let shared: Vec<Option<u64>> = metrics
        .iter()
        .map(|metric| {
            let first = rows.first().and_then(|(p, _)| p.samples.get(metric))?;
            rows.iter()
                .all(|(p, _)| p.samples.get(metric) == Some(first))
                .then_some(first)
        })
        .collect();
    for (metric, shared) in metrics.iter().zip(&shared) {
        heads.push(match shared {
            Some(n) => format!("{}, n = {}", head(metric, metric_unit(metric)), number(*n as f64)),
            None => head(metric, metric_unit(metric)),
        });
        if has_published(metric) {
            heads.push(head(&format!("{metric}, published"), metric_unit(metric)));
        }
    }
    // Each row's cells and, beside them, each cell's n (empty where none is shown).
    let (rows, ns) = rows
        .iter()
        .map(|(point, values)| {
            let mut row: Vec<String> = values.iter().map(display_value).collect();
            let mut ns = vec![String::new(); values.len()];
            for (metric, shared) in metrics.iter().zip(&shared) {
                row.push(or_dash(point.metrics.get(metric)));
                let n = point.samples.get(metric).filter(|_| shared.is_none());
                ns.push(n.map_or_else(String::new, |n| number(n as f64)));
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
                    ns.push(String::new());
                }
            }
            (row, ns)
        })
        .unzip();
    let table = TableView {
        caption: String::new(),
        head: heads,
        rows,
        text_columns: axes.len(),
    };
    (table, ns)
}

pub(super) fn comparisons(results: &Results) -> Vec<ComparisonView> {
    results
        .references
        .iter()
        .flat_map(|r| {
            let unit = metric_unit(r.metric);
            r.points.iter().map(move |p| ComparisonView {
                source: r.source.clone(),
                label: p.label.clone(),
                metric: r.metric,
                published: with_unit(Some(r.published), unit),
                measured: with_unit(p.measured, unit),
                n: p.n.map_or_else(|| "—".into(), |n| number(n as f64)),
                ratio: p
                    .measured
                    .filter(|_| r.published != 0.0)
                    .map_or_else(|| "—".into(), |m| format!("{}×", number(m / r.published))),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use sightline_dsl::Metric;

    use super::*;

    #[test]
    fn metric_list_is_known() {
        for name in TABLE_METRICS {
            assert!(Metric::ALL.iter().any(|m| m.name() == name), "{name}");
        }
    }
}
