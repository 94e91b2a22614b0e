use std::collections::{BTreeMap, BTreeSet};

use super::*;
use crate::chart::canvas::PLOT_HEIGHT;
use crate::chart::style::{Dash, PALETTE};
use crate::chart::svg::{colour, decoded, elements, frames};

fn chart(lines: Vec<Line>, thresholds: Vec<Threshold>) -> LinesChart {
    LinesChart {
        caption: "recall".into(),
        x_desc: "cooperating vehicles".into(),
        y_desc: "occupied_recall".into(),
        lines,
        published: vec![(6.0, 0.94)],
        thresholds,
    }
}

fn line(i: usize, points: Vec<(f64, f64)>) -> Line {
    Line {
        name: format!("line {i}"),
        points,
    }
}

#[test]
fn nothing_to_draw_draws_nothing() {
    let mut empty = chart(Vec::new(), Vec::new());
    empty.published.clear();
    assert_eq!(empty.draw().unwrap(), Vec::new());
}

/// The threshold is drawn where the y axis puts its value: at the height of
/// the tick labelled 0.5, across the x values it applies at, and labelled.
#[test]
fn threshold_line_lies_at_its_value() {
    let threshold = Threshold {
        label: "R-1 ≥ 0.5".into(),
        value: 0.5,
        x: (2.0, 8.0),
    };
    let drawn = chart(vec![line(0, vec![(0.0, 0.0), (10.0, 1.0)])], vec![threshold])
        .draw()
        .unwrap();
    assert_eq!(drawn.len(), 1);
    let svg = decoded(&drawn[0]);
    let tick = elements(&svg, "text")
        .into_iter()
        .find(|t| t.text == "0.5" && t.get("text-anchor") == "end")
        .expect("a y tick labelled 0.5");
    let dashes: Vec<_> = elements(&svg, "polyline")
        .into_iter()
        .filter(|p| p.get("stroke") == colour(INK) && p.get("stroke-width") == "2")
        .filter(|p| p.points().iter().all(|&(_, y)| y < f64::from(PLOT_HEIGHT)))
        .collect();
    assert!(dashes.len() > 5, "a dashed line, in pieces: {}", dashes.len());
    for dash in &dashes {
        for (_, y) in dash.points() {
            assert!(
                (y - tick.number("y")).abs() <= 1.0,
                "{y} vs the tick's {}",
                tick.number("y")
            );
        }
    }
    // Across x = 2 to 8: the x ticks labelled 2 and 8 bound it.
    let x_of = |label: &str| {
        elements(&svg, "text")
            .into_iter()
            .find(|t| t.text == label && t.get("text-anchor") == "middle")
            .map(|t| t.number("x"))
            .expect("an x tick")
    };
    let xs: Vec<f64> = dashes.iter().flat_map(|d| d.points()).map(|p| p.0).collect();
    let (left, right) = (
        xs.iter().copied().fold(f64::MAX, f64::min),
        xs.iter().copied().fold(f64::MIN, f64::max),
    );
    assert!(
        (left - x_of("2")).abs() <= 1.0 && (right - x_of("8")).abs() <= 30.0,
        "{left}..{right}"
    );
    assert!(svg.contains("R-1 ≥ 0.5 (requirement)") && svg.matches("R-1 ≥ 0.5").count() == 2);
}

/// The legend sits in its own box below the plot, every entry inside it.
#[test]
fn legend_box_lies_below_the_plot() {
    let lines: Vec<Line> = (0..12)
        .map(|i| line(i, vec![(1.0, 0.1 * i as f64), (6.0, 0.05 * i as f64 + 0.3)]))
        .collect();
    let svg = decoded(&chart(lines, Vec::new()).draw().unwrap()[0]);
    let frames = frames(&svg);
    assert_eq!(frames.len(), 2, "{frames:?}");
    let (plot, legend) = (frames[0], frames[1]);
    assert!(
        legend.1 > plot.3 + 60.0,
        "the legend starts below the plot and its x labels: {frames:?}"
    );
    for text in elements(&svg, "text").iter().filter(|t| t.text.starts_with("line ")) {
        let (x, y) = (text.number("x"), text.number("y"));
        assert!(
            x > legend.0 && x < legend.2 && y > legend.1 && y < legend.3,
            "{text:?} outside {legend:?}"
        );
    }
}

/// With as many lines as there are looks, each (colour, dash) is drawn once;
/// one more line splits the chart in two on the same axes.
#[test]
fn no_two_lines_look_alike() {
    let lines: Vec<Line> = (0..DISTINCT)
        .map(|i| line(i, vec![(0.0, i as f64), (100.0, i as f64)]))
        .collect();
    let svg = decoded(&chart(lines.clone(), Vec::new()).draw().unwrap()[0]);
    // The plot's strokes by colour: unbroken lines are one long polyline,
    // dashes many short ones of their dash's length.
    let mut by_colour: BTreeMap<String, BTreeSet<&str>> = BTreeMap::new();
    for p in elements(&svg, "polyline")
        .iter()
        .filter(|p| p.get("stroke-width") == "3")
    {
        if p.points().iter().any(|&(_, y)| y >= f64::from(PLOT_HEIGHT)) {
            continue;
        }
        let length = p.length();
        let dash = match Dash::SERIES
            .iter()
            .find_map(|d| d.pattern().filter(|&(on, _)| (length - f64::from(on)).abs() <= 1.5))
        {
            Some((18, _)) => "long",
            Some(_) => "short",
            None if length > 200.0 => "solid",
            None => continue,
        };
        by_colour.entry(p.get("stroke").to_string()).or_default().insert(dash);
    }
    assert_eq!(by_colour.len(), PALETTE.len(), "{by_colour:?}");
    for (colour, dashes) in &by_colour {
        assert_eq!(dashes.len(), 3, "{colour}: {dashes:?}");
    }
    let mut more = lines;
    more.push(line(DISTINCT, vec![(0.0, 0.5), (100.0, 0.5)]));
    let parts = chart(more, Vec::new()).draw().unwrap();
    assert_eq!(parts.len(), 2);
    assert!(
        parts[0]
            .caption
            .ends_with("(part 1 of 2: lines 1 to 11 of 22, on the same axes)"),
        "{}",
        parts[0].caption
    );
    assert!(parts[1].caption.contains("lines 12 to 22 of 22"));
    // The same axes: the same y ticks in both.
    let ticks = |chart: &Chart| -> Vec<String> {
        elements(&decoded(chart), "text")
            .into_iter()
            .filter(|t| t.get("text-anchor") == "end")
            .map(|t| t.text)
            .collect()
    };
    assert_eq!(ticks(&parts[0]), ticks(&parts[1]));
}
