//! The tests' reading of a chart's SVG: its polylines, rectangles and texts
//! with their attributes, so that a test checks what is drawn where.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

use super::canvas::Chart;

/// A chart's SVG, decoded from its `data:` URI.
pub(super) fn decoded(chart: &Chart) -> String {
    let base64 = chart
        .src
        .strip_prefix("data:image/svg+xml;base64,")
        .expect("an SVG data URI");
    String::from_utf8(STANDARD.decode(base64).expect("base64")).expect("UTF-8")
}

/// An element of the SVG: its attributes and its text.
#[derive(Debug, Clone)]
pub(super) struct Element {
    attributes: Vec<(String, String)>,
    pub(super) text: String,
}

impl Element {
    /// The attribute `name`; panics when there is none.
    pub(super) fn get(&self, name: &str) -> &str {
        self.attributes
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
            .unwrap_or_else(|| panic!("no {name} in {self:?}"))
    }

    /// The attribute `name` as a number.
    pub(super) fn number(&self, name: &str) -> f64 {
        self.get(name).parse().unwrap_or_else(|_| panic!("{name} of {self:?}"))
    }

    /// A polyline's points.
    pub(super) fn points(&self) -> Vec<(f64, f64)> {
        self.get("points")
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').expect("x,y");
                (x.parse().expect("x"), y.parse().expect("y"))
            })
            .collect()
    }

    /// A polyline's length, pixels.
    pub(super) fn length(&self) -> f64 {
        self.points()
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .sum()
    }
}

/// Every `<tag …>` element of `svg`, in order.
pub(super) fn elements(svg: &str, tag: &str) -> Vec<Element> {
    let open = format!("<{tag} ");
    svg.match_indices(&open)
        .map(|(at, _)| {
            let rest = &svg[at + open.len()..];
            let end = rest.find('>').expect("a closed tag");
            let head = rest[..end].trim_end_matches('/');
            let text = if rest[..end].ends_with('/') {
                String::new()
            } else {
                let body = &rest[end + 1..];
                body[..body.find('<').unwrap_or(body.len())].trim().to_string()
            };
            Element {
                attributes: attributes(head),
                text,
            }
        })
        .collect()
}

/// `name="value"` pairs of a tag's head.
fn attributes(head: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = head;
    while let Some(eq) = rest.find("=\"") {
        let name = rest[..eq].trim().to_string();
        let after = &rest[eq + 2..];
        let close = after.find('"').expect("a quoted value");
        out.push((name, after[..close].to_string()));
        rest = &after[close + 1..];
    }
    out
}

/// A colour as plotters writes it.
pub(super) fn colour(c: plotters::style::RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// The framed rectangles in the frame's colour: the plot's, then the
/// legend's when there is one, as (left, top, right, bottom).
pub(super) fn frames(svg: &str) -> Vec<(f64, f64, f64, f64)> {
    elements(svg, "rect")
        .into_iter()
        .filter(|r| r.get("fill") == "none" && r.get("stroke") == colour(super::canvas::FRAME))
        .map(|r| {
            let (x, y) = (r.number("x"), r.number("y"));
            (x, y, x + r.number("width"), y + r.number("height"))
        })
        .collect()
}
