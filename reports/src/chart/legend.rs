//! A chart's legend, in a box of its own below the plot: each entry a swatch
//! drawn as the plot draws it and its label; as many columns as the longest
//! label allows, and long labels wrapped (one column) rather than cut.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::canvas::{ChartError, FONT, FRAME, WIDTH, error};
use super::style::{Dash, LINE_WIDTH, Marker, mark, stroke};

/// What an entry shows before its label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Swatch {
    /// A stroke, with the series' marker at its middle when it has one.
    Line {
        colour: RGBColor,
        dash: Dash,
        marker: Option<Marker>,
    },
    /// A marker alone.
    Mark { colour: RGBColor, marker: Marker },
    /// A filled box (bars).
    Bar(RGBColor),
}

/// One entry of a legend.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Entry {
    pub(super) label: String,
    pub(super) swatch: Swatch,
}

/// Space around the box, pixels.
const MARGIN: i32 = 16;
/// Space inside the box, pixels.
const PADDING: i32 = 12;
/// Height of a line of the legend, pixels.
const LINE: i32 = 32;
/// Width of a swatch, and the gap after it, pixels.
const SWATCH: i32 = 56;
const GAP: i32 = 12;
/// Space between columns, pixels.
const GUTTER: i32 = 32;
/// The width of a character of the legend's type, as a share of [`FONT`]:
/// an estimate (the SVG is drawn without font metrics) on the generous side
/// (0.62 of the written `font-size`; sans-serif averages about 0.5), so a
/// label does not run into the next column.
const CHAR_EM: f64 = 0.5;

/// Where each entry goes, and how tall the legend is.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// Height of the legend below the plot, pixels (0 without entries).
    pub(super) height: u32,
    columns: usize,
    /// Per entry, its label's lines.
    lines: Vec<Vec<String>>,
}

/// The box's width inside its padding, pixels.
fn inner_width() -> i32 {
    WIDTH as i32 - 2 * MARGIN - 2 * PADDING
}

/// The width `label` takes in the chart's type, pixels (estimated).
pub(super) fn text_width(label: &str) -> i32 {
    (label.chars().count() as f64 * CHAR_EM * f64::from(FONT)).ceil() as i32
}

/// Lays `entries` out: the most columns in which every label fits on one
/// line, else one column with long labels wrapped between words.
pub(super) fn layout(entries: &[Entry]) -> Layout {
    if entries.is_empty() {
        return Layout {
            height: 0,
            columns: 1,
            lines: Vec::new(),
        };
    }
    let widest = entries.iter().map(|e| text_width(&e.label)).max().unwrap_or(0);
    let column = SWATCH + GAP + widest;
    let columns = ((inner_width() + GUTTER) / (column + GUTTER)).clamp(1, entries.len() as i32) as usize;
    let room = ((inner_width() - SWATCH - GAP) as f64 / (CHAR_EM * f64::from(FONT))).floor() as usize;
    let lines: Vec<Vec<String>> = entries.iter().map(|e| wrapped(&e.label, room.max(8))).collect();
    let rows = rows(&lines, columns);
    let height = rows.iter().sum::<i32>() * LINE + 2 * PADDING + 2 * MARGIN;
    Layout {
        height: height as u32,
        columns,
        lines,
    }
}

/// The height of each row, in lines: entries go down the columns in order.
fn rows(lines: &[Vec<String>], columns: usize) -> Vec<i32> {
    let count = lines.len().div_ceil(columns);
    (0..count)
        .map(|row| {
            (0..columns)
                .filter_map(|c| lines.get(c * count + row))
                .map(|l| l.len() as i32)
                .max()
                .unwrap_or(1)
        })
        .collect()
}

/// `label` in lines of at most `room` characters, broken after a comma or at
/// a space where it can be (a word longer than `room` stands alone).
fn wrapped(label: &str, room: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in label.split(' ') {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > room {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    lines.push(line);
    lines
}

/// The legend's box in `area`'s pixels: (left, top) and (right, bottom).
pub(super) fn frame(layout: &Layout) -> ((i32, i32), (i32, i32)) {
    ((MARGIN, MARGIN), (WIDTH as i32 - MARGIN, layout.height as i32 - MARGIN))
}

/// Draws `entries` laid out as `layout` into `area` (the strip below the plot).
pub(super) fn draw(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &[Entry],
    layout: &Layout,
) -> Result<(), ChartError> {
    if entries.is_empty() {
        return Ok(());
    }
    let (from, to) = frame(layout);
    area.draw(&Rectangle::new([from, to], FRAME.stroke_width(1)))
        .map_err(error)?;
    let count = entries.len().div_ceil(layout.columns);
    let heights = rows(&layout.lines, layout.columns);
    let column_width = (inner_width() + GUTTER) / layout.columns as i32;
    let style = TextStyle::from(("sans-serif", FONT).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, (entry, lines)) in entries.iter().zip(&layout.lines).enumerate() {
        let (column, row) = (i / count, i % count);
        let x = from.0 + PADDING + column as i32 * column_width;
        let y = from.1 + PADDING + heights[..row].iter().sum::<i32>() * LINE + LINE / 2;
        swatch(area, entry.swatch, (x, y))?;
        for (k, line) in lines.iter().enumerate() {
            area.draw_text(line, &style, (x + SWATCH + GAP, y + k as i32 * LINE))
                .map_err(error)?;
        }
    }
    Ok(())
}

/// Draws `swatch` with its left end at `(x, y)` (the middle of its line).
fn swatch(area: &DrawingArea<SVGBackend<'_>, Shift>, swatch: Swatch, (x, y): (i32, i32)) -> Result<(), ChartError> {
    let middle = (x + SWATCH / 2, y);
    match swatch {
        Swatch::Line { colour, dash, marker } => {
            let width = if dash == Dash::Threshold { 2 } else { LINE_WIDTH };
            stroke(area, vec![(x, y), (x + SWATCH, y)], colour, dash, width)?;
            if let Some(marker) = marker {
                mark(area, middle, marker, colour)?;
            }
            Ok(())
        }
        Swatch::Mark { colour, marker } => mark(area, middle, marker, colour),
        Swatch::Bar(colour) => area
            .draw(&Rectangle::new(
                [(x + 8, y - 10), (x + SWATCH - 8, y + 10)],
                colour.filled(),
            ))
            .map_err(error),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(label: &str) -> Entry {
        Entry {
            label: label.into(),
            swatch: Swatch::Bar(FRAME),
        }
    }

    #[test]
    fn short_labels_share_rows_and_long_ones_wrap() {
        assert_eq!(layout(&[]).height, 0);
        // Six short labels: three columns of 1 188 px hold them, two rows.
        let short: Vec<Entry> = ["median", "mean", "p95", "p05", "max", "min"].map(entry).to_vec();
        let l = layout(&short);
        assert!(l.columns >= 3, "{l:?}");
        assert_eq!(rows(&l.lines, l.columns).len(), 6usize.div_ceil(l.columns));
        // A label longer than the box wraps between words, in one column.
        let long = ["field.masses.error_model=dirichlet_mean"; 6].join(", ");
        let l = layout(&[entry(&long), entry("mean")]);
        assert_eq!(l.columns, 1);
        assert!(l.lines[0].len() >= 2, "{:?}", l.lines[0]);
        let room = ((inner_width() - SWATCH - GAP) as f64 / (CHAR_EM * f64::from(FONT))) as usize;
        assert!(l.lines[0].iter().all(|line| line.chars().count() <= room));
        assert_eq!(l.lines[0].join(" "), long);
        assert_eq!(
            l.height as i32,
            (l.lines[0].len() as i32 + 1) * LINE + 2 * PADDING + 2 * MARGIN
        );
    }
}
