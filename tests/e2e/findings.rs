//! The findings pages quote the bundled runs: every figure in their measured
//! tables is checked against a fresh run, so the docs cannot drift from what
//! sightline computes.

use crate::bundled::{roundabout, urban};
use crate::support::{in_sweep, read, root, setting as setting_of};

/// A markdown table of a findings document: its header cells, its body rows, and
/// the last bold line (`**…**`) before it.
pub struct Table {
    pub heading: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// The tables of the section `## {title}…` of the document at `path` (relative to
/// the repository root).
pub fn tables(path: &str, title: &str) -> Vec<Table> {
    let doc = read(&root().join(path));
    let section = doc
        .split("\n## ")
        .find(|s| s.starts_with(title))
        .unwrap_or_else(|| panic!("{path} has no section \"{title}\""));
    let mut tables: Vec<Table> = Vec::new();
    let mut heading = String::new();
    let mut in_table = false;
    for line in section.lines() {
        if !line.starts_with('|') {
            if line.starts_with("**") {
                heading = line.to_string();
            }
            in_table = false;
            continue;
        }
        let cells: Vec<String> = line
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect();
        if !in_table {
            tables.push(Table {
                heading: heading.clone(),
                header: cells,
                rows: Vec::new(),
            });
            in_table = true;
        } else if !cells[0].starts_with("---") {
            tables.last_mut().unwrap().rows.push(cells);
        }
    }
    tables
}

/// Whether `quoted` is `actual` rounded to the decimals it shows.
#[track_caller]
fn assert_quotes(quoted: &str, actual: f64, what: &str) {
    let decimals = quoted.split('.').nth(1).map_or(0, str::len) as i32;
    let value: f64 = quoted
        .parse()
        .unwrap_or_else(|_| panic!("{what}: not a number: {quoted}"));
    assert!(
        (actual - value).abs() <= 0.5 * 10f64.powi(-decimals) + 1e-12,
        "{what}: the findings quote {quoted}, the run gives {actual}"
    );
}

/// Checks every table of a section whose first columns (in backticks; at
/// least the first) are swept settings (a number or a name; `` `key` (sweep
/// K)``: among the points of sweep K only) and whose other columns are metrics
/// of the first point with those settings, else its counts, `n(…)`: a metric's
/// sample size, or `… (paper)`: the scenario's reference at that point (`—`
/// where there is none). Returns the number of cells checked.
fn check_swept_tables(results: &serde_json::Value, path: &str, section: &str) -> usize {
    let references = results["references"].as_array().unwrap();
    let mut checked = 0;
    for table in tables(path, section) {
        // The leading columns in backticks are settings; the point has them all.
        let axes = table.header.iter().take_while(|c| c.starts_with('`')).count().max(1);
        let mut sweep = None;
        let axis: Vec<&str> = table.header[..axes]
            .iter()
            .map(|c| match c.split_once(" (sweep ") {
                Some((axis, k)) => {
                    sweep = Some(k.trim_end_matches(')').parse::<u64>().unwrap());
                    axis.trim_matches('`')
                }
                None => c.trim_matches('`'),
            })
            .collect();
        let axis = &axis[..];
        let points: Vec<serde_json::Value> = results["sweep"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| sweep.is_none_or(|k| in_sweep(p, k)))
            .cloned()
            .collect();
        for cells in &table.rows {
            let setting = &cells[..axes];
            let point = point_with(&points, axis, setting)
                .unwrap_or_else(|| panic!("{path}: no point with {axis:?} = {setting:?}"));
            let index = point["index"].as_u64().unwrap();
            for (column, cell) in table.header.iter().zip(cells).skip(axes) {
                let actual = if let Some(metric) = column.strip_prefix("n(").and_then(|c| c.strip_suffix(')')) {
                    point["samples"][metric].as_f64()
                } else if let Some(metric) = column.strip_suffix(" (paper)") {
                    references
                        .iter()
                        .find(|r| {
                            r["metric"] == metric && r["points"].as_array().unwrap().iter().any(|p| p["point"] == index)
                        })
                        .map(|r| r["published"].as_f64().unwrap())
                } else {
                    point["metrics"][column.as_str()]
                        .as_f64()
                        .or_else(|| point["counts"][column.as_str()].as_f64())
                };
                let what = format!("{path}: {column} at {axis:?} = {setting:?}");
                match (cell.as_str(), actual) {
                    ("—", None) => {}
                    (quoted, Some(actual)) => assert_quotes(quoted, actual, &what),
                    (quoted, None) => panic!("{what}: the findings quote {quoted}, the run has none"),
                }
                checked += 1;
            }
        }
    }
    checked
}

/// The first point of `points` whose settings `axes` are `settings` (each a
/// number or a name).
fn point_with<'a>(
    points: &'a [serde_json::Value],
    axes: &[&str],
    settings: &[String],
) -> Option<&'a serde_json::Value> {
    points.iter().find(|p| {
        axes.iter().zip(settings).all(|(axis, setting)| {
            setting_of(p, axis).is_some_and(|value| {
                value.as_str() == Some(setting) || value.as_f64().is_some_and(|v| setting.parse() == Ok(v))
            })
        })
    })
}

/// Checks the tables of a section that list, for the point with a swept setting
/// (first column), the infrastructure contribution in one scene-density bin
/// (`bin`: its lower edge, then `–` and the upper): the steps in it, their
/// median and mean. Returns the number of rows checked.
fn check_density_tables(results: &serde_json::Value, path: &str, section: &str) -> usize {
    let points = results["sweep"].as_array().unwrap();
    let mut checked = 0;
    for table in tables(path, section) {
        assert_eq!(
            table.header[1..],
            ["bin", "steps", "median", "mean"],
            "{path}: {}",
            table.heading
        );
        let axis = table.header[0].trim_matches('`');
        for cells in &table.rows {
            let point = point_with(points, &[axis], &cells[..1])
                .unwrap_or_else(|| panic!("{path}: no point with {axis} = {}", cells[0]));
            let from: f64 = cells[1].split('–').next().unwrap().parse().unwrap();
            let row = point["contribution_by_density"]
                .as_array()
                .unwrap()
                .iter()
                .find(|row| row["from"].as_f64() == Some(from))
                .unwrap_or_else(|| panic!("{path}: no bin from {from} at {axis} = {}", cells[0]));
            for (column, cell) in ["steps", "median", "mean"].iter().zip(&cells[2..]) {
                let what = format!("{path}: {column} of bin {} at {axis} = {}", cells[1], cells[0]);
                assert_quotes(cell, row[*column].as_f64().unwrap(), &what);
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn seed_000_findings_quote_the_bundled_run() {
    let checked = check_swept_tables(roundabout(), "docs/findings/seed-000.md", "Measured beside the paper");
    // By penetration, at zero noise, by localization noise, by odometry, by
    // channel, latency and how long evidence is kept.
    assert_eq!(checked, 6 * 12 + 2 * 9 + 6 * 5 + 2 * 5 + 2 * 7 + 3 * 9 + 3 * 7);
}

#[test]
fn seed_002_findings_quote_the_bundled_run() {
    let path = "docs/findings/seed-002.md";
    let results = urban();
    let checked = check_swept_tables(results, path, "Measured beside the paper");
    // By density, per road user and their criticality, then by risk_for,
    // shares_over, labelled_by at each density, contribution_over, and the
    // ego waiting.
    assert_eq!(checked, 4 * 13 + 4 * 12 + 4 * 6 + 2 * 3 + 2 * 3 + 8 * 3 + 2 * 2 + 10);
    let bins = check_density_tables(results, path, "Extra objects by scene density");
    assert_eq!(bins, 7 + 5);

    // The paper pools anticipation over its densities: so does this table.
    let points = results["sweep"].as_array().unwrap();
    let mut pooled: Vec<f64> = points
        .iter()
        .filter(|p| in_sweep(p, 0))
        .flat_map(|p| p["counts"]["anticipation"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    pooled.sort_by(f64::total_cmp);
    let quantile = |q| sightline_engine::outcome::quantile(&pooled, q).expect("objects were anticipated");
    let table = tables(path, "Pooled over the densities").remove(0);
    assert_eq!(table.header, ["objects", "anticipation_median", "anticipation_p95"]);
    let row = &table.rows[0];
    assert_quotes(&row[0], pooled.len() as f64, "pooled objects");
    assert_quotes(&row[1], quantile(0.5), "pooled median");
    assert_quotes(&row[2], quantile(0.95), "pooled p95");
}
