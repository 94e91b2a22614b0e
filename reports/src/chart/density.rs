//! The distribution of anticipation times: a histogram scaled to a density
//! under a Gaussian kernel density estimate (Silverman's bandwidth).

use plotters::prelude::*;

use super::canvas::{Axes, Chart, ChartError, data_uri, error};
use super::figure::figure;
use super::legend::{Entry, Swatch};
use super::style::{Dash, LINE_WIDTH, PALETTE, stroke};

/// The histogram's bars: the palette's sky blue.
const BARS: RGBColor = PALETTE[4];
/// The density estimate: the palette's vermillion.
const CURVE: RGBColor = PALETTE[5];

/// Points at which a density estimate is drawn.
const CURVE_POINTS: usize = 200;

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

    let mut legend = vec![Entry {
        label: "histogram, as a density".into(),
        swatch: Swatch::Bar(BARS),
    }];
    if !curve.is_empty() {
        legend.push(Entry {
            label: "kernel density estimate".into(),
            swatch: Swatch::Line {
                colour: CURVE,
                dash: Dash::Solid,
                marker: None,
            },
        });
    }
    let axes = Axes {
        x: x0..x1,
        y: 0.0..top.max(1e-9),
        x_desc: "anticipation time (s)",
        y_desc: "density (1/s)",
        x_labels: None,
    };
    let svg = figure(&axes, &legend, |chart| {
        chart
            .draw_series(
                bars.iter()
                    .map(|&(a, b, h)| Rectangle::new([(a, 0.0), (b, h)], BARS.filled())),
            )
            .map_err(error)?;
        if !curve.is_empty() {
            stroke(chart.plotting_area(), curve, CURVE, Dash::Solid, LINE_WIDTH)?;
        }
        Ok(())
    })?;
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

#[cfg(test)]
mod tests {
    use base64::Engine;
    use base64::engine::general_purpose::STANDARD;

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
