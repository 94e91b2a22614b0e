//! What every chart shares: its size and type sizes, the plotting frame
//! (white, axes named, tick labels without spurious digits), and the SVG as a
//! `data:` URI.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use serde::Serialize;

/// Width of a chart, pixels: the page shows it at most 1 200 px wide, and A4
/// prints it 186 mm wide, where the type sizes below come out at 8.5 to 9 pt.
pub(super) const WIDTH: u32 = 1280;
/// Height of a chart's plot (axes and their labels), pixels; its legend
/// adds rows below.
pub(super) const PLOT_HEIGHT: u32 = 600;
/// Type size of tick labels, legend entries and labels in the plot, as
/// plotters takes it (its SVG writes `font-size` 1.24 times smaller: 21 px).
pub(super) const FONT: u32 = 26;
/// Type size of the axes' descriptions, as plotters takes it (22.6 px).
const DESC_FONT: u32 = 28;
/// The plot's frame.
pub(super) const FRAME: RGBColor = RGBColor(89, 99, 110);

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

/// What a chart plots: its ranges, the axes' descriptions, and how the x
/// axis's ticks are labelled when not as numbers.
pub(super) struct Axes<'a> {
    pub(super) x: Range<f64>,
    pub(super) y: Range<f64>,
    pub(super) x_desc: &'a str,
    pub(super) y_desc: &'a str,
    pub(super) x_labels: Option<&'a dyn Fn(&f64) -> String>,
}

/// A chart's plotting area.
pub(super) type Plot<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The plotting area of `area`, filled white, over the axes' ranges with
/// their descriptions and a light mesh.
pub(super) fn framed<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    axes: &Axes<'_>,
) -> Result<Plot<'a, 'b>, ChartError> {
    let mut chart = ChartBuilder::on(area)
        .margin_top(20)
        .margin_right(36)
        .margin_left(16)
        .x_label_area_size(84)
        .y_label_area_size(118)
        .build_cartesian_2d(axes.x.clone(), axes.y.clone())
        .map_err(error)?;
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(axes.x_desc)
        .y_desc(axes.y_desc)
        .light_line_style(WHITE)
        .label_style(("sans-serif", FONT))
        .axis_desc_style(("sans-serif", DESC_FONT))
        .set_all_tick_mark_size(6)
        .y_label_formatter(&tick);
    match axes.x_labels {
        Some(labels) => mesh.x_label_formatter(labels),
        None => mesh.x_label_formatter(&tick),
    };
    mesh.draw().map_err(error)?;
    Ok(chart)
}

/// A tick's value as a reader writes it: without the digits binary rounding
/// adds (`0.3`, not `0.30000000000000004`) and without a bare `.0` (`6`).
pub(super) fn tick(value: &f64) -> String {
    let rounded: f64 = format!("{value:.9e}").parse().unwrap_or(*value);
    if rounded == 0.0 {
        "0".into()
    } else {
        rounded.to_string()
    }
}

/// An SVG as a `data:` URI.
pub(super) fn data_uri(svg: &str) -> String {
    format!("data:image/svg+xml;base64,{}", STANDARD.encode(svg))
}

pub(super) fn error(e: impl std::fmt::Display) -> ChartError {
    ChartError(e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_read_as_written() {
        assert_eq!(tick(&0.30000000000000004), "0.3");
        assert_eq!(tick(&6.0), "6");
        assert_eq!(tick(&-0.0), "0");
        assert_eq!(tick(&1.0e-12), "0.000000000001");
        assert_eq!(tick(&2500.0), "2500");
        assert_eq!(tick(&0.025), "0.025");
    }
}
