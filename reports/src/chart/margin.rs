//! A falsification's margins: the smallest margin of every case in the order
//! tried, coloured by phase, with the counterexample ringed.

use plotters::prelude::*;
use sightline_oracles::{Case, Phase};

use super::canvas::{Axes, Chart, ChartError, data_uri};
use super::figure::figure;
use super::legend::{Entry, Swatch};
use super::style::{Dash, INK, LINE_WIDTH, Marker, PALETTE, mark, stroke};

/// A phase's name, colour and cases (x, margin).
type Phased<'a> = (&'a str, RGBColor, Vec<(f64, f64)>);

/// The smallest margin so far.
const GREY: RGBColor = RGBColor(120, 120, 120);

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
    let (y0, y1) = (lo - 0.08 * span, hi + 0.08 * span);
    let (x0, x1) = (0.5, cases.len() as f64 + 0.5);
    let mut lowest = f64::INFINITY;
    let so_far: Vec<(f64, f64)> = points
        .iter()
        .map(|&(x, m, _)| {
            lowest = lowest.min(m);
            (x, lowest)
        })
        .collect();
    let phases: Vec<Phased<'_>> = [Phase::Random, Phase::Guided, Phase::Shrink]
        .into_iter()
        .zip(PALETTE)
        .map(|(phase, colour)| {
            let name = match phase {
                Phase::Random => "random case",
                Phase::Guided => "guided step",
                Phase::Shrink => "shrinking",
            };
            let of_phase = points
                .iter()
                .filter(|p| p.2 == phase)
                .map(|&(x, m, _)| (x, m))
                .collect();
            (name, colour, of_phase)
        })
        .filter(|(_, _, of_phase): &(_, _, Vec<_>)| !of_phase.is_empty())
        .collect();
    let ringed = counterexample.and_then(|i| points.iter().find(|p| p.0 == (i + 1) as f64));
    let mut legend = vec![
        Entry {
            label: "0: below it a requirement breaks".into(),
            swatch: Swatch::Line {
                colour: INK,
                dash: Dash::Threshold,
                marker: None,
            },
        },
        Entry {
            label: "smallest so far".into(),
            swatch: Swatch::Line {
                colour: GREY,
                dash: Dash::Solid,
                marker: None,
            },
        },
    ];
    legend.extend(phases.iter().map(|&(name, colour, _)| Entry {
        label: name.into(),
        swatch: Swatch::Mark {
            colour,
            marker: Marker::Dot,
        },
    }));
    if ringed.is_some() {
        legend.push(Entry {
            label: "counterexample".into(),
            swatch: Swatch::Mark {
                colour: INK,
                marker: Marker::Ring,
            },
        });
    }
    // Cases are counted: whole numbers only on the x axis.
    let whole = |x: &f64| {
        if x.fract() == 0.0 {
            format!("{x:.0}")
        } else {
            String::new()
        }
    };
    let axes = Axes {
        x: x0..x1,
        y: y0..y1,
        x_desc: "case, in the order tried",
        y_desc: "smallest margin (its requirement's unit)",
        x_labels: Some(&whole),
    };
    let svg = figure(&axes, &legend, |chart| {
        let area = chart.plotting_area();
        stroke(area, vec![(x0, 0.0), (x1, 0.0)], INK, Dash::Threshold, 2)?;
        stroke(area, so_far, GREY, Dash::Solid, LINE_WIDTH)?;
        for (_, colour, of_phase) in &phases {
            for &p in of_phase {
                mark(area, p, Marker::Dot, *colour)?;
            }
        }
        if let Some(&(x, m, _)) = ringed {
            mark(area, (x, m), Marker::Ring, INK)?;
        }
        Ok(())
    })?;
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

#[cfg(test)]
mod tests {
    use base64::Engine;
    use base64::engine::general_purpose::STANDARD;

    use super::*;

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
                each: Vec::new(),
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
}
