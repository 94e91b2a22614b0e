//! A world point's reliability diagram: per bin of fused probability, the mean
//! probability against the observed frequency of occupancy, beside the
//! diagonal a calibrated grid would follow.

use plotters::prelude::*;

use super::canvas::{Chart, ChartError, PALETTE, SIZE, data_uri, error, frame};
use crate::results::Calibration;

/// The reliability diagram of `calibration`: each bin with cell-steps as a
/// marker at (mean p, observed frequency) labelled with its n, empty bins left
/// out, and the diagonal. `None` when no cell-step was judged.
pub(crate) fn reliability_chart(calibration: &Calibration) -> Result<Option<Chart>, ChartError> {
    let points: Vec<(f64, f64, u64)> = calibration
        .bins
        .iter()
        .filter_map(|b| Some((b.mean_probability?, b.observed_frequency?, b.cells)))
        .collect();
    let Some(brier) = calibration.brier_score.filter(|_| !points.is_empty()) else {
        return Ok(None);
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let mut chart = frame(
            &root,
            0.0..1.0,
            0.0..1.05,
            ("mean fused probability of the bin", "observed frequency of occupied"),
        )?;
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, 0.0), (1.0, 1.0)],
                6,
                4,
                BLACK.stroke_width(1),
            ))
            .map_err(error)?
            .label("calibrated")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(1)));
        let colour = PALETTE[0];
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|&(p, o, _)| (p, o)),
                colour.stroke_width(2),
            ))
            .map_err(error)?
            .label("fused grid")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2)));
        chart
            .draw_series(points.iter().map(|&(p, o, n)| {
                EmptyElement::at((p, o))
                    + Circle::new((0, 0), 3, colour.filled())
                    + Text::new(format!("n={n}"), (4, -14), ("sans-serif", 11).into_font())
            }))
            .map_err(error)?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(error)?;
        root.present().map_err(error)?;
    }
    let caption = format!(
        "Reliability of the fused occupancy probabilities (pignistic for evidential methods): {} equal bins, \
         empty ones left out, each labelled with its cell-steps. Brier score {brier:.4}, n = {} cell-steps \
         (self-report left out).",
        calibration.bins.len(),
        calibration.cells
    );
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
    use crate::results::ReliabilityBin;

    fn bin(i: usize, cells: u64, mean: f64, frequency: f64) -> ReliabilityBin {
        ReliabilityBin {
            from: i as f64 / 10.0,
            to: (i + 1) as f64 / 10.0,
            cells,
            mean_probability: (cells > 0).then_some(mean),
            observed_frequency: (cells > 0).then_some(frequency),
        }
    }

    /// The hand-computed four cells: three filled bins, each labelled with its
    /// n; the empty bins are not drawn.
    #[test]
    fn reliability_chart_labels_filled_bins_only() {
        let mut bins: Vec<ReliabilityBin> = (0..10).map(|i| bin(i, 0, 0.0, 0.0)).collect();
        bins[1] = bin(1, 1, 0.1, 0.0);
        bins[6] = bin(6, 1, 0.6, 1.0);
        bins[9] = bin(9, 2, 0.9, 0.5);
        let calibration = Calibration {
            cells: 4,
            brier_score: Some(0.2475),
            bins,
        };
        let chart = reliability_chart(&calibration).unwrap().unwrap();
        let svg = String::from_utf8(
            STANDARD
                .decode(chart.src.strip_prefix("data:image/svg+xml;base64,").unwrap())
                .unwrap(),
        )
        .unwrap();
        assert_eq!(svg.matches("\nn=1\n").count(), 2, "{svg}");
        assert_eq!(svg.matches("\nn=2\n").count(), 1);
        assert_eq!(svg.matches("\nn=0\n").count(), 0);
        assert!(svg.contains("calibrated") && svg.contains("observed frequency of occupied"));
        assert!(chart.caption.contains("Brier score 0.2475, n = 4 cell-steps"));
    }

    /// Nothing judged: no chart.
    #[test]
    fn nothing_judged_draws_nothing() {
        let calibration = Calibration {
            cells: 0,
            brier_score: None,
            bins: (0..10).map(|i| bin(i, 0, 0.0, 0.0)).collect(),
        };
        assert_eq!(reliability_chart(&calibration).unwrap(), None);
    }
}
