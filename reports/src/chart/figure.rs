//! A chart as SVG: the plot, framed, and its legend in a box of its own below
//! it.

use plotters::prelude::*;

use super::canvas::{Axes, ChartError, FRAME, PLOT_HEIGHT, Plot, WIDTH, error, framed};
use super::legend::{self, Entry};

/// Draws a chart as SVG: the plot over `axes`, framed, with `draw` drawing
/// its content, and `legend` in a box of its own below the plot (never over
/// the data).
pub(super) fn figure(
    axes: &Axes<'_>,
    legend: &[Entry],
    draw: impl FnOnce(&mut Plot<'_, '_>) -> Result<(), ChartError>,
) -> Result<String, ChartError> {
    let layout = legend::layout(legend);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, PLOT_HEIGHT + layout.height)).into_drawing_area();
        root.fill(&WHITE).map_err(error)?;
        let (top, bottom) = root.split_vertically(PLOT_HEIGHT);
        let mut chart = framed(&top, axes)?;
        draw(&mut chart)?;
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        root.draw(&Rectangle::new(
            [(xs.start, ys.start), (xs.end - 1, ys.end - 1)],
            FRAME.stroke_width(1),
        ))
        .map_err(error)?;
        legend::draw(&bottom, legend, &layout)?;
        root.present().map_err(error)?;
    }
    Ok(svg)
}
