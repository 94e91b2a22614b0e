//! What every chart shares: its size, the line palette, the plotting frame
//! (white, axes named, a light mesh), and the SVG as a `data:` URI.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use serde::Serialize;

/// Size of a chart, pixels.
pub(super) const SIZE: (u32, u32) = (640, 300);

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

/// Line colours, in order (a colour-blind-safe palette, Okabe and Ito).
pub(super) const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(213, 94, 0),
    RGBColor(240, 228, 66),
];

/// A plotting area of `root`, filled white, over `x` × `y` with its axes named
/// and a light mesh.
pub(super) fn frame<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    x: Range<f64>,
    y: Range<f64>,
    descriptions: (&str, &str),
) -> Result<Plot<'a, 'b>, ChartError> {
    framed(root, x, y, descriptions, None)
}

/// A plotting area as [`frame`] draws it, the x labels written by `x_labels`
/// when given.
pub(super) fn framed<'a, 'b>(
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
pub(super) type Plot<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// An SVG as a `data:` URI.
pub(super) fn data_uri(svg: &str) -> String {
    format!("data:image/svg+xml;base64,{}", STANDARD.encode(svg))
}

pub(super) fn error(e: impl std::fmt::Display) -> ChartError {
    ChartError(e.to_string())
}
