//! Charts for the report, drawn by plotters to SVG and embedded as `data:` URIs
//! (the page stays self-contained, and nothing in an SVG is interpolated into the
//! HTML unescaped).

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use serde::Serialize;

use sightline_engine::outcome::{DELIVERY_BIN, DENSITY_BIN, SemanticMetrics};
use sightline_oracles::{Case, Phase};

use crate::results::{PointResult, Results};

/// Size of a chart, pixels.
const SIZE: (u32, u32) = (640, 300);

/// Points at which a density estimate is drawn.
const CURVE_POINTS: usize = 200;

/// A chart ready for the page.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Chart {
    /// What it shows, for the caption.
    pub caption: String,
    /// The SVG as a `data:` URI.
    pub src: String,
}

/// A chart that could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("failed to draw a chart: {0}")]
pub struct ChartError(String);

/// Silverman's rule-of-thumb bandwidth for a Gaussian kernel,
/// 0.9 · min(σ, IQR / 1.34) · n^(−1/5) (σ with n − 1); `None` for fewer than two
/// samples or no spread.
pub fn silverman_bandwidth(sorted: &[f64]) -> Option<f64> {
    let n = sorted.len();
    if n < 2 {
        return None;
    }
    let mean = sorted.iter().sum::<f64>() / n as f64;
    let sd = (sorted.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    let quantile = |q| sightline_engine::outcome::quantile(sorted, q).expect("n ≥ 2");
    let iqr = quantile(0.75) - quantile(0.25);
    let spread = if iqr > 0.0 { sd.min(iqr / 1.34) } else { sd };
    (spread > 0.0).then(|| 0.9 * spread * (n as f64).powf(-0.2))
}

/// The Gaussian kernel density estimate of `samples` with bandwidth `h` at `x`.
pub fn kde(samples: &[f64], h: f64, x: f64) -> f64 {
    let norm = 1.0 / (samples.len() as f64 * h * (2.0 * std::f64::consts::PI).sqrt());
    norm * samples
        .iter()
        .map(|s| (-0.5 * ((x - s) / h).powi(2)).exp())
        .sum::<f64>()
}

/// The distribution of anticipation times: a histogram scaled to a density, with
/// the kernel density estimate over it when the samples have a spread. `None`
/// without samples.
pub fn anticipation(sorted: &[f64]) -> Result<Option<Chart>, ChartError> {
    let (Some(&first), Some(&last)) = (sorted.first(), sorted.last()) else {
        return Ok(None);
    };
    let bandwidth = silverman_bandwidth(sorted);
    let pad = bandwidth.map_or(0.5, |h| 3.0 * h);
    // Anticipation times are never negative: the estimate is reflected at 0
    // (Silverman 1986, §2.10) so that no density leaks below it.
    let reflect = first >= 0.0;
    let (x0, x1) = (if reflect { 0.0 } else { first - pad }, last + pad);
    let bins = ((sorted.len() as f64).sqrt().ceil() as usize).clamp(5, 40);
    let width = (last - first).max(1e-9) / bins as f64;
    let mut counts = vec![0usize; bins];
    for &x in sorted {
        counts[(((x - first) / width) as usize).min(bins - 1)] += 1;
    }
    let scale = 1.0 / (sorted.len() as f64 * width);
    let bars: Vec<(f64, f64, f64)> = counts
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            (
                first + i as f64 * width,
                first + (i + 1) as f64 * width,
                c as f64 * scale,
            )
        })
        .collect();
    let curve: Vec<(f64, f64)> = bandwidth
        .map(|h| {
            (0..=CURVE_POINTS)
                .map(|i| {
                    let x = x0 + (x1 - x0) * i as f64 / CURVE_POINTS as f64;
                    let mirrored = if reflect { kde(sorted, h, -x) } else { 0.0 };
                    (x, kde(sorted, h, x) + mirrored)
                })
                .collect()
        })
        .unwrap_or_default();
    let top = bars
        .iter()
        .map(|b| b.2)
        .chain(curve.iter().map(|p| p.1))
        .fold(0.0, f64::max)
        * 1.1;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let mut chart = frame(
            &root,
            x0..x1,
            0.0..top.max(1e-9),
            ("anticipation time (s)", "density (1/s)"),
        )?;
        chart
            .draw_series(
                bars.iter()
                    .map(|&(a, b, h)| Rectangle::new([(a, 0.0), (b, h)], RGBColor(150, 170, 200).filled())),
            )
            .map_err(error)?;
        if !curve.is_empty() {
            chart
                .draw_series(LineSeries::new(curve, RGBColor(180, 30, 30).stroke_width(2)))
                .map_err(error)?;
        }
        root.present().map_err(error)?;
    }
    let src = data_uri(&svg);
    let caption = match bandwidth {
        Some(h) => format!(
            "Anticipation times of {} objects: histogram as a density, and a Gaussian kernel density estimate (Silverman bandwidth {h:.2} s, reflected at 0).",
            sorted.len()
        ),
        None => format!(
            "Anticipation times of {} objects (too few or too alike for a density estimate).",
            sorted.len()
        ),
    };
    Ok(Some(Chart { caption, src }))
}

/// A semantic point's charts: its anticipation times, the objects the ego knows
/// only through an RSU by traffic density (median and mean per bin), and the
/// delivery ratio of the RSU's messages by distance.
pub(crate) fn semantic_charts(m: &SemanticMetrics) -> Result<Vec<Chart>, ChartError> {
    let rows = m.contribution_by_density();
    let centre = |from: f64| from + DENSITY_BIN / 2.0;
    let by_density = [
        Line {
            name: "median".into(),
            points: rows.iter().map(|r| (centre(r.from), r.median)).collect(),
        },
        Line {
            name: "mean".into(),
            points: rows.iter().map(|r| (centre(r.from), r.mean)).collect(),
        },
    ];
    let delivery = [Line {
        name: "delivered / sent".into(),
        points: m
            .delivery_by_distance
            .iter()
            .enumerate()
            .filter(|(_, b)| b.sent > 0)
            .map(|(i, b)| ((i as f64 + 0.5) * DELIVERY_BIN, b.received as f64 / b.sent as f64))
            .collect(),
    }];
    let charts = [
        anticipation(&m.anticipation)?,
        lines_chart(
            format!(
                "Objects the ego knows only through an RSU, by the scene's density ({} objects/km bins, at their centres).",
                DENSITY_BIN
            ),
            ("objects per km", "objects known only through an RSU"),
            &by_density,
            &[],
        )?,
        lines_chart(
            format!("Share of the RSU's messages that reach the ego, by distance ({DELIVERY_BIN} m bins)."),
            ("RSU–ego distance (m)", "delivery ratio"),
            &delivery,
            &[],
        )?,
    ];
    Ok(charts.into_iter().flatten().collect())
}

/// A named line of (x, y) points.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Its legend entry.
    pub name: String,
    /// Its points, in x order.
    pub points: Vec<(f64, f64)>,
}

/// Line colours, in order (a colour-blind-safe palette, Okabe and Ito).
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(213, 94, 0),
    RGBColor(240, 228, 66),
];

/// Lines with markers over a shared x axis, and published values as black
/// crosses; a legend names each line. `None` when there is nothing to draw.
pub fn lines_chart(
    caption: String,
    (x_desc, y_desc): (&str, &str),
    lines: &[Line],
    published: &[(f64, f64)],
) -> Result<Option<Chart>, ChartError> {
    let all = || lines.iter().flat_map(|l| &l.points).chain(published);
    let Some((x0, x1, y0, y1)) = all().fold(None, |acc: Option<(f64, f64, f64, f64)>, &(x, y)| {
        Some(acc.map_or((x, x, y, y), |(a, b, c, d)| (a.min(x), b.max(x), c.min(y), d.max(y))))
    }) else {
        return Ok(None);
    };
    let pad = |lo: f64, hi: f64| {
        let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
        (lo - 0.05 * span, hi + 0.05 * span)
    };
    let ((x0, x1), (y0, y1)) = (pad(x0, x1), pad(y0.min(0.0), y1));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let mut chart = frame(&root, x0..x1, y0..y1, (x_desc, y_desc))?;
        for (i, line) in lines.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(line.points.iter().copied(), colour.stroke_width(2)))
                .map_err(error)?
                .label(line.name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2)));
            chart
                .draw_series(line.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(error)?;
        }
        if !published.is_empty() {
            chart
                .draw_series(published.iter().map(|&p| Cross::new(p, 5, BLACK.stroke_width(2))))
                .map_err(error)?
                .label("published")
                .legend(|(x, y)| Cross::new((x + 8, y), 4, BLACK.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .position(SeriesLabelPosition::LowerRight)
            .draw()
            .map_err(error)?;
        root.present().map_err(error)?;
    }
    let src = data_uri(&svg);
    Ok(Some(Chart { caption, src }))
}

/// The smallest margin of every case of a falsification in the order tried:
/// a colour per phase (in the legend when it has cases), the smallest margin
/// so far as a line, zero (below it a
/// requirement breaks) dashed, the counterexample ringed. Cases whose worst
/// requirement could not be checked have no margin and are left out. `None`
/// when no case has a margin.
pub(crate) fn margin_chart(cases: &[Case], counterexample: Option<usize>) -> Result<Option<Chart>, ChartError> {
    let points: Vec<(f64, f64, Phase)> = cases
        .iter()
        .enumerate()
        .filter_map(|(i, case)| Some(((i + 1) as f64, case.score.margin?, case.phase)))
        .collect();
    if points.is_empty() {
        return Ok(None);
    }
    let (lo, hi) = points
        .iter()
        .fold((0.0_f64, 0.0_f64), |(lo, hi), &(_, m, _)| (lo.min(m), hi.max(m)));
    let span = (hi - lo).max(1e-9);
    // Room above the points for the legend in the upper right.
    let (y0, y1) = (lo - 0.08 * span, hi + 0.7 * span);
    let (x0, x1) = (0.5, cases.len() as f64 + 0.5);
    let mut lowest = f64::INFINITY;
    let so_far: Vec<(f64, f64)> = points
        .iter()
        .map(|&(x, m, _)| {
            lowest = lowest.min(m);
            (x, lowest)
        })
        .collect();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        // Cases are counted: whole numbers only on the x axis.
        let whole = |x: &f64| {
            if x.fract() == 0.0 {
                format!("{x:.0}")
            } else {
                String::new()
            }
        };
        let mut chart = framed(
            &root,
            x0..x1,
            y0..y1,
            ("case, in the order tried", "smallest margin"),
            Some(&whole),
        )?;
        chart
            .draw_series(DashedLineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                6,
                4,
                BLACK.stroke_width(1),
            ))
            .map_err(error)?
            .label("0: below it a requirement breaks")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(1)));
        let grey = RGBColor(150, 150, 150);
        chart
            .draw_series(LineSeries::new(so_far, grey.stroke_width(2)))
            .map_err(error)?
            .label("smallest so far")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], grey.stroke_width(2)));
        for (i, phase) in [Phase::Random, Phase::Guided, Phase::Shrink].into_iter().enumerate() {
            let colour = PALETTE[i];
            let name = match phase {
                Phase::Random => "random case",
                Phase::Guided => "guided step",
                Phase::Shrink => "shrinking",
            };
            let of_phase: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.2 == phase)
                .map(|&(x, m, _)| (x, m))
                .collect();
            if of_phase.is_empty() {
                continue;
            }
            chart
                .draw_series(of_phase.into_iter().map(|p| Circle::new(p, 3, colour.filled())))
                .map_err(error)?
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 8, y), 3, colour.filled()));
        }
        if let Some(&(x, m, _)) = counterexample.and_then(|i| points.iter().find(|p| p.0 == (i + 1) as f64)) {
            chart
                .draw_series([Circle::new((x, m), 7, BLACK.stroke_width(2))])
                .map_err(error)?
                .label("counterexample")
                .legend(|(x, y)| Circle::new((x + 8, y), 5, BLACK.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(error)?;
        root.present().map_err(error)?;
    }
    let unchecked = cases.len() - points.len();
    let mut caption = format!(
        "The smallest margin of each of the {} cases, in the order tried; a requirement breaks below 0.",
        cases.len()
    );
    if unchecked > 0 {
        caption.push_str(&format!(
            " Not drawn: {unchecked} of them, whose worst requirement could not be checked (no margin)."
        ));
    }
    Ok(Some(Chart {
        caption,
        src: data_uri(&svg),
    }))
}

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
            let rows: Vec<(&PointResult, Vec<&serde_json::Value>)> =
                sweep.rows().map(|(p, values)| (&results.sweep[p], values)).collect();
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
fn others(point: &PointResult, axes: &[sightline_dsl::Axis], values: &[&serde_json::Value], column: usize) -> String {
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

/// A plotting area of `root`, filled white, over `x` × `y` with its axes named
/// and a light mesh.
fn frame<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    x: Range<f64>,
    y: Range<f64>,
    descriptions: (&str, &str),
) -> Result<Plot<'a, 'b>, ChartError> {
    framed(root, x, y, descriptions, None)
}

/// A plotting area as [`frame`] draws it, the x labels written by `x_labels`
/// when given.
fn framed<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    x: Range<f64>,
    y: Range<f64>,
    (x_desc, y_desc): (&str, &str),
    x_labels: Option<&dyn Fn(&f64) -> String>,
) -> Result<Plot<'a, 'b>, ChartError> {
    root.fill(&WHITE).map_err(error)?;
    let mut chart = ChartBuilder::on(root)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(x, y)
        .map_err(error)?;
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x_desc).y_desc(y_desc).light_line_style(WHITE);
    if let Some(x_labels) = x_labels {
        mesh.x_label_formatter(x_labels);
    }
    mesh.draw().map_err(error)?;
    Ok(chart)
}

/// A chart's plotting area.
type Plot<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// An SVG as a `data:` URI.
fn data_uri(svg: &str) -> String {
    format!("data:image/svg+xml;base64,{}", STANDARD.encode(svg))
}

fn error(e: impl std::fmt::Display) -> ChartError {
    ChartError(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn silverman_bandwidth_by_hand() {
        // Mean 3, sample σ = √2.5 = 1.5811; IQR = 4 − 2 = 2, 2 / 1.34 = 1.4925 is smaller.
        let h = silverman_bandwidth(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert!((h - 0.9 * (2.0 / 1.34) * 5f64.powf(-0.2)).abs() < 1e-12);
        assert_eq!(silverman_bandwidth(&[2.0]), None);
        assert_eq!(silverman_bandwidth(&[2.0, 2.0, 2.0]), None);
    }

    #[test]
    fn density_estimate_integrates_to_one() {
        let samples = [0.2, 0.9, 1.1, 1.4, 3.0, 7.5];
        let h = silverman_bandwidth(&samples).unwrap();
        let (a, b, n) = (-10.0, 20.0, 30_000);
        let dx = (b - a) / n as f64;
        let area: f64 = (0..n).map(|i| kde(&samples, h, a + (i as f64 + 0.5) * dx) * dx).sum();
        assert!((area - 1.0).abs() < 1e-6, "{area}");
        // Symmetric samples give a symmetric estimate.
        let symmetric = [-1.0, 1.0];
        assert!((kde(&symmetric, 0.5, 0.3) - kde(&symmetric, 0.5, -0.3)).abs() < 1e-15);
    }

    #[test]
    fn lines_draw_every_line_in_the_legend() {
        assert_eq!(lines_chart("none".into(), ("x", "y"), &[], &[]).unwrap(), None);
        let chart = lines_chart(
            "recall".into(),
            ("cooperating vehicles", "occupied_recall"),
            &[Line {
                name: "bayes".into(),
                points: vec![(1.0, 0.43), (6.0, 0.92)],
            }],
            &[(6.0, 0.94)],
        )
        .unwrap()
        .unwrap();
        let svg = String::from_utf8(
            STANDARD
                .decode(chart.src.strip_prefix("data:image/svg+xml;base64,").unwrap())
                .unwrap(),
        )
        .unwrap();
        assert!(svg.contains("bayes") && svg.contains("published") && svg.contains("cooperating vehicles"));
    }

    /// The SVG of a chart.
    fn svg(chart: &Chart) -> String {
        String::from_utf8(
            STANDARD
                .decode(chart.src.strip_prefix("data:image/svg+xml;base64,").unwrap())
                .unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn margin_chart_draws_each_phase_and_rings_the_counterexample() {
        use sightline_oracles::{Score, Status};
        let case = |phase, margin: Option<f64>| Case {
            phase,
            indices: vec![0],
            score: Score {
                requirement: Some("R-1".into()),
                status: match margin {
                    Some(m) if m >= 0.0 => Status::Pass,
                    Some(_) => Status::Fail,
                    None => Status::Error,
                },
                margin,
                breaks: margin.is_none_or(|m| m < 0.0),
            },
        };
        assert_eq!(margin_chart(&[case(Phase::Random, None)], None).unwrap(), None);
        let cases = [
            case(Phase::Random, Some(0.4)),
            case(Phase::Guided, Some(-0.2)),
            case(Phase::Random, None),
            case(Phase::Shrink, Some(-0.1)),
        ];
        let random_only = margin_chart(&cases[..1], None).unwrap().unwrap();
        assert!(svg(&random_only).contains("random case") && !svg(&random_only).contains("guided step"));
        let chart = margin_chart(&cases, Some(3)).unwrap().unwrap();
        let drawn = svg(&chart);
        for label in [
            "random case",
            "guided step",
            "shrinking",
            "counterexample",
            "smallest so far",
        ] {
            assert!(drawn.contains(label), "{label}");
        }
        assert!(
            chart.caption.contains("4 cases") && chart.caption.contains("Not drawn: 1 "),
            "{}",
            chart.caption
        );
        let without = margin_chart(&cases, None).unwrap().unwrap();
        assert!(!svg(&without).contains("counterexample"));
    }

    #[test]
    fn anticipation_chart_is_an_svg_data_uri() {
        assert_eq!(anticipation(&[]).unwrap(), None);
        let chart = anticipation(&[0.5, 1.0, 1.2, 2.0, 4.5]).unwrap().unwrap();
        let svg = String::from_utf8(
            STANDARD
                .decode(chart.src.strip_prefix("data:image/svg+xml;base64,").unwrap())
                .unwrap(),
        )
        .unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("anticipation time (s)"),
            "{svg}"
        );
        assert!(chart.caption.contains("5 objects"));
        let single = anticipation(&[2.0]).unwrap().unwrap();
        assert!(single.caption.contains("too few"));
    }
}
