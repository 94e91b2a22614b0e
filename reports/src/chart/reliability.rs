//! A world point's reliability diagram: per bin of fused probability, the mean
//! probability against the observed frequency of occupancy, beside the
//! diagonal a calibrated grid would follow.

use plotters::prelude::*;

use super::canvas::{Axes, Chart, ChartError, FONT, data_uri, error};
use super::figure::figure;
use super::legend::{Entry, Swatch};
use super::style::{Dash, INK, LINE_WIDTH, Marker, PALETTE, mark, stroke};
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
    let colour = PALETTE[0];
    let legend = [
        Entry {
            label: "calibrated (the diagonal)".into(),
            swatch: Swatch::Line {
                colour: INK,
                dash: Dash::Long,
                marker: None,
            },
        },
        Entry {
            label: "fused grid, each bin labelled with its cell-steps".into(),
            swatch: Swatch::Line {
                colour,
                dash: Dash::Solid,
                marker: Some(Marker::Dot),
            },
        },
    ];
    let axes = Axes {
        x: 0.0..1.0,
        y: 0.0..1.05,
        x_desc: "mean fused probability of the bin (1)",
        y_desc: "observed frequency of occupied (1)",
        x_labels: None,
    };
    let svg = figure(&axes, &legend, |chart| {
        let area = chart.plotting_area();
        stroke(area, vec![(0.0, 0.0), (1.0, 1.0)], INK, Dash::Long, 2)?;
        stroke(
            area,
            points.iter().map(|&(p, o, _)| (p, o)).collect(),
            colour,
            Dash::Solid,
            LINE_WIDTH,
        )?;
        for &(p, o, n) in &points {
            mark(area, (p, o), Marker::Dot, colour)?;
            area.draw(
                &(EmptyElement::at((p, o)) + Text::new(format!("n={n}"), (8, -30), ("sans-serif", FONT).into_font())),
            )
            .map_err(error)?;
        }
        Ok(())
    })?;
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
