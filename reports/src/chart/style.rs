//! How a chart tells its series apart: a colour-blind-safe palette (Okabe and
//! Ito) crossed with three line styles, each style with its own marker, so no
//! two series of a chart share a colour and a dash; requirement thresholds in
//! black with a dash of their own. The strokes and markers are drawn the same
//! way in the plot and in the legend.

use plotters::coord::CoordTranslate;
use plotters::element::{Circle, Cross, DashedPathElement, EmptyElement, PathElement, TriangleMarker};
use plotters::prelude::*;

use super::canvas::{ChartError, error};

/// Series colours, in order: Okabe and Ito's palette (2008) without its
/// black, which thresholds and published values keep.
pub(super) const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(213, 94, 0),
    RGBColor(240, 228, 66),
];

/// Thresholds and published values.
pub(super) const INK: RGBColor = RGBColor(0, 0, 0);

/// How a line is stroked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Dash {
    /// Unbroken.
    Solid,
    /// Long dashes.
    Long,
    /// Short dashes, nearly dots.
    Short,
    /// A requirement's threshold: long dashes with wide gaps, in black.
    Threshold,
}

impl Dash {
    /// The styles series take, in order.
    pub(super) const SERIES: [Dash; 3] = [Dash::Solid, Dash::Long, Dash::Short];

    /// Dash and gap lengths, pixels; `None` for an unbroken line.
    pub(super) fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Self::Solid => None,
            Self::Long => Some((18, 8)),
            Self::Short => Some((5, 6)),
            Self::Threshold => Some((24, 12)),
        }
    }
}

/// What marks a data point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Marker {
    /// A filled disc.
    Dot,
    /// A filled triangle.
    Triangle,
    /// A filled square.
    Square,
    /// A diagonal cross (published values).
    Cross,
    /// An open circle (the counterexample).
    Ring,
}

/// A series' look: colour, dash and the marker of its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) struct Style {
    pub(super) colour: RGBColor,
    pub(super) dash: Dash,
    pub(super) marker: Marker,
}

/// How many series one chart tells apart: each colour once per line style.
pub(super) const DISTINCT: usize = PALETTE.len() * Dash::SERIES.len();

/// The look of series `i` of a chart (every colour unbroken first, then
/// dashed, then short-dashed); `None` from [`DISTINCT`] on, where the chart
/// must split (small multiples) rather than repeat a look.
pub(super) fn series(i: usize) -> Option<Style> {
    let dash = *Dash::SERIES.get(i / PALETTE.len())?;
    let marker = match dash {
        Dash::Solid => Marker::Dot,
        Dash::Long => Marker::Triangle,
        _ => Marker::Square,
    };
    Some(Style {
        colour: PALETTE[i % PALETTE.len()],
        dash,
        marker,
    })
}

/// Line width of a series, pixels.
pub(super) const LINE_WIDTH: u32 = 3;
/// Half the size of a marker, pixels.
pub(super) const MARKER_SIZE: i32 = 6;

/// Strokes `points` on `area` in `colour` with `dash`.
pub(super) fn stroke<CT>(
    area: &DrawingArea<SVGBackend<'_>, CT>,
    points: Vec<CT::From>,
    colour: RGBColor,
    dash: Dash,
    width: u32,
) -> Result<(), ChartError>
where
    CT: CoordTranslate,
    CT::From: Clone,
{
    let style = colour.stroke_width(width);
    match dash.pattern() {
        None => area.draw(&PathElement::new(points, style)),
        Some((on, off)) => area.draw(&DashedPathElement::new(points, on, off, style)),
    }
    .map_err(error)
}

/// Draws `marker` at `at` on `area` in `colour`.
pub(super) fn mark<CT>(
    area: &DrawingArea<SVGBackend<'_>, CT>,
    at: CT::From,
    marker: Marker,
    colour: RGBColor,
) -> Result<(), ChartError>
where
    CT: CoordTranslate,
    CT::From: Clone,
{
    let s = MARKER_SIZE;
    match marker {
        Marker::Dot => area.draw(&Circle::new(at, s, colour.filled())),
        Marker::Triangle => area.draw(&TriangleMarker::new(at, s + 2, colour.filled())),
        Marker::Square => area.draw(&(EmptyElement::at(at) + Rectangle::new([(-s, -s), (s, s)], colour.filled()))),
        Marker::Cross => area.draw(&Cross::new(at, s + 2, colour.stroke_width(3))),
        Marker::Ring => area.draw(&Circle::new(at, 2 * s, colour.stroke_width(3))),
    }
    .map_err(error)
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::*;

    /// No two series of a chart look alike: every (colour, dash) pair once,
    /// and nothing past the pairs there are.
    #[test]
    fn series_styles_never_repeat_a_colour_and_dash() {
        let styles: Vec<Style> = (0..DISTINCT).map(|i| series(i).expect("within DISTINCT")).collect();
        let pairs: HashSet<(RGBColor, Dash)> = styles.iter().map(|s| (s.colour, s.dash)).collect();
        assert_eq!(pairs.len(), DISTINCT);
        assert_eq!(DISTINCT, 21);
        assert_eq!(series(DISTINCT), None);
        // Neither black (thresholds, published values) nor the threshold's dash.
        assert!(styles.iter().all(|s| s.colour != INK && s.dash != Dash::Threshold));
        // The first seven are the palette, unbroken.
        assert!(
            styles[..7]
                .iter()
                .all(|s| s.dash == Dash::Solid && s.marker == Marker::Dot)
        );
    }
}
