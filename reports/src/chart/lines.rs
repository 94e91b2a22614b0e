//! Lines with markers over a shared x axis, published values as black
//! crosses, and a legend naming each line.

use plotters::prelude::*;

use super::canvas::{Chart, ChartError, PALETTE, SIZE, data_uri, error, frame};

/// A named line of (x, y) points.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Its legend entry.
    pub name: String,
    /// Its points, in x order.
    pub points: Vec<(f64, f64)>,
}

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

#[cfg(test)]
mod tests {
    use base64::Engine;
    use base64::engine::general_purpose::STANDARD;

    use super::*;

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
}
