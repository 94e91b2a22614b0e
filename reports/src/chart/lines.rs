//! Lines with markers over a shared x axis, published values as black
//! crosses, the thresholds of the requirements that bound the metric as
//! dashed black lines, and a legend below naming each. More lines than the
//! palette and line styles tell apart are drawn as small multiples on the same
//! axes, never with a repeated look.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use plotters::coord::types::RangedCoordf64;

use super::canvas::{Axes, Chart, ChartError, FONT, data_uri, error};
use super::figure::figure;
use super::legend::{Entry, Swatch, text_width};
use super::style::{DISTINCT, Dash, INK, LINE_WIDTH, Marker, mark, series, stroke};

/// A named line of (x, y) points.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Its legend entry.
    pub name: String,
    /// Its points, in x order.
    pub points: Vec<(f64, f64)>,
}

/// A bound a requirement sets on the charted value, drawn as a dashed black
/// line over the x values of the points it applies to.
#[derive(Debug, Clone, PartialEq)]
pub struct Threshold {
    /// What sets it, for the line's label and the legend: the requirements'
    /// ids and the bound (`RB-REC-06 ≥ 0.9`).
    pub label: String,
    /// The bound, in the charted value's unit.
    pub value: f64,
    /// The smallest and largest x it applies at (equal for one point: the line
    /// is then drawn a little either side of it).
    pub x: (f64, f64),
}

/// A chart of lines over a shared x axis.
#[derive(Debug, Clone, PartialEq)]
pub struct LinesChart {
    /// What it shows, for the caption.
    pub caption: String,
    /// The x axis's description, with its unit.
    pub x_desc: String,
    /// The y axis's description, with its unit.
    pub y_desc: String,
    /// The lines.
    pub lines: Vec<Line>,
    /// Published values, as black crosses.
    pub published: Vec<(f64, f64)>,
    /// The requirements' thresholds on the charted value.
    pub thresholds: Vec<Threshold>,
}

/// Share of the x range a threshold at one x spans, either side.
const ONE_POINT_SPAN: f64 = 0.05;

impl LinesChart {
    /// The chart: one, or several on the same axes when there are more lines
    /// than `style::DISTINCT` looks (each part's caption says which); none when
    /// there is nothing to draw.
    pub fn draw(&self) -> Result<Vec<Chart>, ChartError> {
        let Some((x, y)) = self.ranges() else {
            return Ok(Vec::new());
        };
        let parts = self.lines.len().div_ceil(DISTINCT).max(1);
        let per_part = self.lines.len().div_ceil(parts).max(1);
        let chunks: Vec<&[Line]> = if self.lines.is_empty() {
            vec![&[]]
        } else {
            self.lines.chunks(per_part).collect()
        };
        chunks
            .iter()
            .enumerate()
            .map(|(k, lines)| {
                let caption = if parts == 1 {
                    self.caption.clone()
                } else {
                    format!(
                        "{} (part {} of {parts}: lines {} to {} of {}, on the same axes)",
                        self.caption,
                        k + 1,
                        k * per_part + 1,
                        k * per_part + lines.len(),
                        self.lines.len()
                    )
                };
                let svg = self.svg(lines, x, y)?;
                Ok(Chart {
                    caption,
                    src: data_uri(&svg),
                })
            })
            .collect()
    }

    /// The x and y ranges every part shares: the data, the published values
    /// and the thresholds, padded by 5 % (y from 0 at most); `None` with
    /// nothing to draw.
    fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
        let points = self
            .lines
            .iter()
            .flat_map(|l| &l.points)
            .chain(&self.published)
            .copied()
            .chain(
                self.thresholds
                    .iter()
                    .flat_map(|t| [(t.x.0, t.value), (t.x.1, t.value)]),
            );
        let (x0, x1, y0, y1) = points.fold(None, |acc: Option<(f64, f64, f64, f64)>, (x, y)| {
            Some(acc.map_or((x, x, y, y), |(a, b, c, d)| (a.min(x), b.max(x), c.min(y), d.max(y))))
        })?;
        let pad = |lo: f64, hi: f64| {
            let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
            (lo - 0.05 * span, hi + 0.05 * span)
        };
        Some((pad(x0, x1), pad(y0.min(0.0), y1)))
    }

    /// One part's SVG: `lines` over the shared ranges.
    fn svg(&self, lines: &[Line], (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Result<String, ChartError> {
        let mut legend: Vec<Entry> = lines
            .iter()
            .enumerate()
            .map(|(i, line)| {
                let style = series(i).expect("a part holds at most DISTINCT lines");
                Entry {
                    label: line.name.clone(),
                    swatch: Swatch::Line {
                        colour: style.colour,
                        dash: style.dash,
                        marker: Some(style.marker),
                    },
                }
            })
            .collect();
        if !self.published.is_empty() {
            legend.push(Entry {
                label: "published".into(),
                swatch: Swatch::Mark {
                    colour: INK,
                    marker: Marker::Cross,
                },
            });
        }
        legend.extend(self.thresholds.iter().map(|t| Entry {
            label: format!("{} (requirement)", t.label),
            swatch: Swatch::Line {
                colour: INK,
                dash: Dash::Threshold,
                marker: None,
            },
        }));
        let axes = Axes {
            x: x0..x1,
            y: y0..y1,
            x_desc: &self.x_desc,
            y_desc: &self.y_desc,
            x_labels: None,
        };
        let half = ONE_POINT_SPAN * (x1 - x0);
        figure(&axes, &legend, |chart| {
            let area = chart.plotting_area();
            let spans: Vec<(f64, f64)> = self
                .thresholds
                .iter()
                .map(|t| {
                    if t.x.0 < t.x.1 {
                        t.x
                    } else {
                        (t.x.0 - half, t.x.1 + half)
                    }
                })
                .collect();
            for (t, &(from, to)) in self.thresholds.iter().zip(&spans) {
                stroke(area, vec![(from, t.value), (to, t.value)], INK, Dash::Threshold, 2)?;
            }
            for (i, line) in lines.iter().enumerate() {
                let style = series(i).expect("a part holds at most DISTINCT lines");
                stroke(area, line.points.clone(), style.colour, style.dash, LINE_WIDTH)?;
                for &p in &line.points {
                    mark(area, p, style.marker, style.colour)?;
                }
            }
            for &p in &self.published {
                mark(area, p, Marker::Cross, INK)?;
            }
            // Labels last, over the data: above the line's end farther from
            // the plot's edge.
            for (t, &(from, to)) in self.thresholds.iter().zip(&spans) {
                if (from - x0) > (x1 - to) {
                    label(area, &t.label, (to, t.value), HPos::Right)?;
                } else {
                    label(area, &t.label, (from, t.value), HPos::Left)?;
                }
            }
            Ok(())
        })
    }
}

/// Writes a threshold's `text` just above `at`, starting there (`HPos::Left`)
/// or ending there (`HPos::Right`), on a white ground so that lines under it
/// do not cross it.
fn label(
    area: &DrawingArea<SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    text: &str,
    at: (f64, f64),
    h: HPos,
) -> Result<(), ChartError> {
    let width = text_width(text);
    let (left, right) = match h {
        HPos::Right => (-width - 4, 4),
        _ => (-4, width + 4),
    };
    let height = FONT as i32;
    let style = TextStyle::from(("sans-serif", FONT).into_font()).pos(Pos::new(h, VPos::Bottom));
    area.draw(
        &(EmptyElement::at(at)
            + Rectangle::new([(left, -height - 6), (right, -4)], WHITE.mix(0.85).filled())
            + Text::new(text.to_string(), (0, -6), style)),
    )
    .map_err(error)
}

#[cfg(test)]
#[path = "lines_tests.rs"]
mod tests;
