//! A falsification's margins: the smallest margin of every case in the order
//! tried, coloured by phase, with the counterexample ringed.

use plotters::prelude::*;
use sightline_oracles::{Case, Phase};

use super::canvas::{Chart, ChartError, PALETTE, SIZE, data_uri, error, framed};

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
