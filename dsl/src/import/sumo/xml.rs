//! What the three SUMO readers share: parsing within SUMO's limits, SUMO's
//! shapes and indices, and (from [`crate::import::xml`]) the located error and
//! typed attribute access that names the offending element.

use roxmltree::{Document, Node};

use crate::Location;
use crate::geometry::Xy;
pub(crate) use crate::import::xml::{
    Locator, attribute, children, element_error, error_at_pos, number, number_within, optional_number_within, string,
    tag, value_error,
};
use crate::import::xml::{XmlError, malformed, outside};
use crate::raw::range::COORDINATE;

/// A problem in a SUMO file, located by line and column.
pub type SumoError = XmlError;

/// The most elements one SUMO file may hold: the parser keeps every element
/// and attribute of a file at once, about 0.8 kB an element of FCD output with
/// what is read from it (`docs/limits.md`).
pub const MAX_ELEMENTS: usize = 1_000_000;

/// The most attributes (counted as `=` signs) one SUMO file may hold.
pub const MAX_ATTRIBUTES: usize = 10_000_000;

/// Parses `text` as XML; a file with more than [`MAX_ELEMENTS`] elements or
/// [`MAX_ATTRIBUTES`] attributes is refused before it is parsed, at the first
/// one past the limit, and a malformed file is an error at the parser's
/// position.
pub(crate) fn parse(text: &str) -> Result<Document<'_>, SumoError> {
    within_limits(text, MAX_ELEMENTS, MAX_ATTRIBUTES)?;
    Document::parse(text).map_err(|error| malformed(text, &error))
}

/// Counts the elements (`<` not opening an end tag, a comment or a
/// declaration) and attributes (`=`) of `text` against their limits.
fn within_limits(text: &str, max_elements: usize, max_attributes: usize) -> Result<(), SumoError> {
    let bytes = text.as_bytes();
    let (mut elements, mut attributes) = (0usize, 0usize);
    for (i, &byte) in bytes.iter().enumerate() {
        let (count, limit, what) = match byte {
            b'<' if !matches!(bytes.get(i + 1), Some(b'/' | b'!' | b'?')) => (&mut elements, max_elements, "elements"),
            b'=' => (&mut attributes, max_attributes, "attributes"),
            _ => continue,
        };
        *count += 1;
        if *count > limit {
            let before = &text[..i];
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().unwrap_or_default().chars().count() + 1;
            return Err(SumoError {
                location: Location::new(line, column),
                message: format!(
                    "the file has more than {limit} {what}, the most sightline reads from one file \
                     (docs/limits.md); simulate a shorter time or a smaller area, or write fewer samples \
                     (a longer --device.fcd.period)"
                ),
            });
        }
    }
    Ok(())
}

/// The root element, which must be named `name`.
pub(crate) fn root<'a, 'i>(doc: &'a Document<'i>, name: &str) -> Result<Node<'a, 'i>, SumoError> {
    let root = doc.root_element();
    if root.tag_name().name() == name {
        Ok(root)
    } else {
        Err(element_error(
            root,
            format!("expected <{name}> as the root element, found {}", tag(root)),
        ))
    }
}

/// A required non-negative integer, such as a lane index.
pub(crate) fn index(node: Node, name: &str) -> Result<u32, SumoError> {
    let attribute = attribute(node, name)?;
    attribute.value().parse().map_err(|_| {
        let message = format!(
            "attribute `{name}` of {} is not a non-negative integer: {:?}",
            tag(node),
            attribute.value()
        );
        value_error(node, &attribute, message)
    })
}

/// A required shape: points `x,y` (or `x,y,z`, the height dropped) separated by
/// spaces, each coordinate within the world's ([`COORDINATE`]). An empty shape
/// is an error; a bad point is located at that point, a coordinate out of range
/// at that coordinate.
pub(crate) fn shape(node: Node, name: &str) -> Result<Vec<Xy>, SumoError> {
    let attribute = attribute(node, name)?;
    let value = attribute.value();
    // Byte offsets into the value are exact in the file only when it holds no
    // entity references; otherwise point at the value's start.
    let raw = &node.document().input_text()[attribute.range_value()];
    let start = attribute.range_value().start;
    let mut points = Vec::new();
    for token in value.split_ascii_whitespace() {
        let offset = token.as_ptr() as usize - value.as_ptr() as usize;
        // The error at byte `within` of the point.
        let error = |within: usize, message: String| {
            let pos = if raw == value { start + offset + within } else { start };
            error_at_pos(node, pos, message)
        };
        let point = parse_point(token).ok_or_else(|| {
            let message = format!(
                "bad point {token:?} in attribute `{name}` of {}; expected \"x,y\" with finite numbers",
                tag(node)
            );
            error(0, message)
        })?;
        let y_at = token.find(',').map_or(0, |comma| comma + 1);
        for (axis, coordinate, within) in [("x", point[0], 0), ("y", point[1], y_at)] {
            if let Some(problem) = outside(COORDINATE, coordinate) {
                let message = format!(
                    "{axis} of point {token:?} in attribute `{name}` of {} {problem}",
                    tag(node)
                );
                return Err(error(within, message));
            }
        }
        points.push(point);
    }
    if points.is_empty() {
        return Err(value_error(
            node,
            &attribute,
            format!("attribute `{name}` of {} is empty", tag(node)),
        ));
    }
    Ok(points)
}

/// A required outline: a [`shape`] without a closing point equal to the first.
pub(crate) fn outline(node: Node, name: &str) -> Result<Vec<Xy>, SumoError> {
    let mut points = shape(node, name)?;
    if points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    Ok(points)
}

/// `x,y` or `x,y,z` as `[x, y]`.
fn parse_point(token: &str) -> Option<Xy> {
    let mut parts = token
        .split(',')
        .map(|part| part.parse::<f64>().ok().filter(|v| v.is_finite()));
    let x = parts.next()??;
    let y = parts.next()??;
    match (parts.next(), parts.next()) {
        (None, _) | (Some(Some(_)), None) => Some([x, y]),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_error<T>(text: &str, read: impl Fn(Node) -> Result<T, SumoError>) -> String {
        crate::import::xml::error_of_first_child(&parse(text).unwrap(), read)
    }

    #[test]
    fn malformed_xml_is_located_by_the_parser() {
        let error = parse("<net>\n  <edge id=\"a\">\n</net>\n").unwrap_err();
        assert_eq!(error.location, Location::new(3, 1));
        assert_eq!(error.to_string(), "3:1: malformed xml: expected 'edge' tag, not 'net'");
    }

    #[test]
    fn indices_are_non_negative_integers() {
        let text = "<net>\n  <lane index=\"-1\"/>\n</net>";
        assert_eq!(
            first_error(text, |n| index(n, "index")),
            "2:16: attribute `index` of <lane> is not a non-negative integer: \"-1\""
        );
    }

    #[test]
    fn shapes_read_points_and_drop_heights() {
        let doc = parse("<net><lane shape=\"0.00,1.60  100,1.6,4.5\n-3e1,2\"/></net>").unwrap();
        let lane = doc.root_element().first_element_child().unwrap();
        assert_eq!(
            shape(lane, "shape").unwrap(),
            vec![[0.0, 1.6], [100.0, 1.6], [-30.0, 2.0]]
        );
    }

    #[test]
    fn a_bad_shape_point_is_located_at_that_point() {
        let text = "<net>\n  <lane shape=\"0,0 1,x 2,2\"/>\n</net>";
        assert_eq!(
            first_error(text, |n| shape(n, "shape")),
            "2:20: bad point \"1,x\" in attribute `shape` of <lane>; expected \"x,y\" with finite numbers"
        );
        for bad in ["1", "1,2,3,4", "1,,2", "1,NaN"] {
            let text = format!("<net><lane shape=\"0,0 {bad}\"/></net>");
            assert!(
                first_error(&text, |n| shape(n, "shape")).starts_with("1:23: bad point"),
                "{bad}"
            );
        }
    }

    #[test]
    fn shape_coordinates_are_held_to_the_coordinate_range_at_the_coordinate() {
        let text = "<net>\n  <lane shape=\"0,0 1e6,-1e6,5e9 1,-1000000.1\"/>\n</net>";
        assert_eq!(
            first_error(text, |n| shape(n, "shape")),
            "2:35: y of point \"1,-1000000.1\" in attribute `shape` of <lane> must be a number from \
             -1000000 to 1000000 m, found -1000000.1"
        );
        let text = "<net><lane shape=\"0,0 1e6,-1e6,5e9\"/></net>";
        let doc = parse(text).unwrap();
        let lane = doc.root_element().first_element_child().unwrap();
        assert_eq!(shape(lane, "shape").unwrap(), [[0.0, 0.0], [1e6, -1e6]]);
        // Behind an entity reference, offsets into the value are not the file's.
        let text = "<net><lane shape=\"0&#44;0 2e6,0\"/></net>";
        assert!(first_error(text, |n| shape(n, "shape")).starts_with("1:19: x of point \"2e6,0\""));
    }

    #[test]
    fn an_empty_shape_is_an_error() {
        let text = "<net><lane shape=\" \"/></net>";
        assert_eq!(
            first_error(text, |n| shape(n, "shape")),
            "1:19: attribute `shape` of <lane> is empty"
        );
    }

    #[test]
    fn files_past_the_limits_are_refused_at_the_first_element_past_them() {
        let text = "<?xml version=\"1.0\"?>\n<a>\n  <!-- c --><b x=\"1\"/></a>";
        assert_eq!(within_limits(text, 2, 10), Ok(()));
        let error = within_limits(text, 1, 10).unwrap_err();
        assert_eq!(error.location, Location::new(3, 13));
        assert!(error.message.starts_with("the file has more than 1 elements"));
        let error = within_limits(text, 2, 1).unwrap_err();
        assert_eq!(error.location, Location::new(3, 17));
        assert!(
            error.message.starts_with("the file has more than 1 attributes"),
            "{}",
            error.message
        );
    }

    #[test]
    fn the_root_must_have_the_expected_name() {
        let doc = parse("<?xml version=\"1.0\"?>\n<additional/>").unwrap();
        let error = root(&doc, "net").unwrap_err();
        assert_eq!(
            error.to_string(),
            "2:1: expected <net> as the root element, found <additional>"
        );
    }
}
