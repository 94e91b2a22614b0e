//! What the XML readers ([`sumo`](super::sumo), [`opendrive`](super::opendrive))
//! share: the located [`XmlError`] and typed attribute access that names the
//! offending element. Each format keeps its own size limits and its own
//! vocabulary (shapes, lane ids, allowed children) in its `xml` module.

use roxmltree::{Attribute, Node};

use crate::Location;
use crate::error::end_of;
use crate::raw::range::Range;

/// A problem in an XML file, located by line and column.
///
/// Displays as `line:col: message`; the caller prefixes the file name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{location}: {message}")]
pub struct XmlError {
    /// Where in the file: an element's `<`, an attribute value's first
    /// character, a point of a shape that does not parse, or the parser's
    /// position in malformed XML.
    pub location: Location,
    /// What is wrong, a lowercase fragment such as
    /// ``attribute `x` of <vehicle> is not a number: "abc"``.
    pub message: String,
}

/// A number read from a file, as a message shows it: as Rust writes it
/// (`12`, `0.25`; `{:.3}` keeps its precision), or in exponent form when that
/// would run past 15 digits (`-1e308`, not 309 of them).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Number(pub f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let value = self.0;
        let plain = value == 0.0 || (1e-6..1e15).contains(&value.abs());
        match (plain, f.precision()) {
            (true, None) => write!(f, "{value}"),
            (true, Some(digits)) => write!(f, "{value:.digits$}"),
            (false, None) => write!(f, "{value:e}"),
            (false, Some(digits)) => write!(f, "{value:.digits$e}"),
        }
    }
}

/// The message of a roxmltree parse error as `malformed xml: …`, and where it
/// is: roxmltree appends " at row:col" (dropped here, the location says it) and
/// says 1:1 for a text that ends too early (located at its end instead).
pub(crate) fn malformed(text: &str, error: &roxmltree::Error) -> XmlError {
    let pos = error.pos();
    let message = error.to_string();
    let message = message.strip_suffix(&format!(" at {pos}")).unwrap_or(&message);
    let location = match error {
        roxmltree::Error::UnexpectedEndOfStream | roxmltree::Error::UnclosedRootNode => end_of(text),
        _ => Location::new(pos.row as usize, pos.col as usize),
    };
    XmlError {
        location,
        message: format!("malformed xml: {message}"),
    }
}

/// An error at byte `pos` of the document that holds `node`.
pub(crate) fn error_at_pos(node: Node, pos: usize, message: String) -> XmlError {
    let pos = node.document().text_pos_at(pos);
    XmlError {
        location: Location::new(pos.row as usize, pos.col as usize),
        message,
    }
}

/// An error at the start (the `<`) of element `node`.
pub(crate) fn element_error(node: Node, message: String) -> XmlError {
    error_at_pos(node, node.range().start, message)
}

/// Locates elements by line and column in one pass over the text: roxmltree's
/// own `text_pos_at` counts lines from the start at every call, which over
/// every element of a large file is quadratic (6 % of the SUMO town's run,
/// locating each of its FCD's road users); an error, located once, uses
/// roxmltree's (`error_at_pos`).
pub(crate) struct Locator {
    /// The byte offset where each line starts.
    starts: Vec<usize>,
}

impl Locator {
    /// The locator of `text`.
    pub(crate) fn new(text: &str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Self { starts }
    }

    /// Where element `node` starts (its `<`).
    pub(crate) fn at(&self, node: Node) -> Location {
        let pos = node.range().start;
        let line = self.starts.partition_point(|&start| start <= pos);
        let start = self.starts[line - 1];
        let column = node.document().input_text()[start..pos].chars().count() + 1;
        Location::new(line, column)
    }
}

/// An error at the first character of `attribute`'s value.
pub(crate) fn value_error(node: Node, attribute: &Attribute, message: String) -> XmlError {
    error_at_pos(node, attribute.range_value().start, message)
}

/// The element's name, as `<name>`, for messages.
pub(crate) fn tag(node: Node) -> String {
    format!("<{}>", node.tag_name().name())
}

/// The element children of `node` named `name`, in file order.
pub(crate) fn children<'a, 'i>(node: Node<'a, 'i>, name: &str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |child| child.has_tag_name(name))
}

/// A required attribute.
pub(crate) fn attribute<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Result<Attribute<'a, 'i>, XmlError> {
    node.attribute_node(name)
        .ok_or_else(|| element_error(node, format!("missing attribute `{name}` on {}", tag(node))))
}

/// A required string attribute.
pub(crate) fn string<'a>(node: Node<'a, '_>, name: &str) -> Result<&'a str, XmlError> {
    Ok(attribute(node, name)?.value())
}

/// A required finite number.
pub(crate) fn number(node: Node, name: &str) -> Result<f64, XmlError> {
    finite(node, &attribute(node, name)?)
}

/// A required number within `range`: a speed a file gives, for one, within the
/// range the scenario's own speeds have.
pub(crate) fn number_within(node: Node, name: &str, range: Range) -> Result<f64, XmlError> {
    let value = number(node, name)?;
    match outside(range, value) {
        None => Ok(value),
        Some(problem) => {
            let message = format!("attribute `{name}` of {} {problem}", tag(node));
            Err(value_error(node, &attribute(node, name)?, message))
        }
    }
}

/// What is wrong with `value` when it lies outside `range`, as the end of a
/// message (`must be a number from -1000000 to 1000000 m, found 1e300`);
/// `None` when it lies within.
pub(crate) fn outside(range: Range, value: f64) -> Option<String> {
    if range.contains(value) {
        return None;
    }
    let unit = if range.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", range.unit)
    };
    Some(format!("must be {}{unit}, found {}", range.words(), Number(value)))
}

/// An optional number within `range`, as [`number_within`]; `None` when absent.
pub(crate) fn optional_number_within(node: Node, name: &str, range: Range) -> Result<Option<f64>, XmlError> {
    node.attribute_node(name)
        .map(|_| number_within(node, name, range))
        .transpose()
}

/// An optional finite number, `default` when absent.
pub(crate) fn number_or(node: Node, name: &str, default: f64) -> Result<f64, XmlError> {
    Ok(optional_number(node, name)?.unwrap_or(default))
}

/// An optional finite number.
pub(crate) fn optional_number(node: Node, name: &str) -> Result<Option<f64>, XmlError> {
    node.attribute_node(name).map(|a| finite(node, &a)).transpose()
}

/// The value of `attribute` as a finite number (surrounding white space, which
/// XML schemas collapse in numbers, allowed).
fn finite(node: Node, attribute: &Attribute) -> Result<f64, XmlError> {
    let value = attribute.value();
    let describe = |what: &str| {
        let message = format!(
            "attribute `{}` of {} is not {what}: {value:?}",
            attribute.name(),
            tag(node)
        );
        value_error(node, attribute, message)
    };
    match value.trim().parse::<f64>() {
        Ok(number) if number.is_finite() => Ok(number),
        Ok(_) => Err(describe("a finite number")),
        Err(_) => Err(describe("a number")),
    }
}

/// The error `read` gives on the first child of `doc`'s root, displayed
/// (the importers' tests: a reader that succeeds there fails the test).
#[cfg(test)]
pub(crate) fn error_of_first_child<T>(doc: &roxmltree::Document, read: impl Fn(Node) -> Result<T, XmlError>) -> String {
    match read(doc.root_element().first_element_child().unwrap()) {
        Ok(_) => panic!("expected an error"),
        Err(error) => error.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_child_error<T>(text: &str, read: impl Fn(Node) -> Result<T, XmlError>) -> String {
        error_of_first_child(&roxmltree::Document::parse(text).unwrap(), read)
    }

    /// Numbers in messages read as written, in exponent form only past 15
    /// digits, with or without a precision.
    #[test]
    fn numbers_in_messages_stay_short() {
        let shown = |v: f64| (format!("{}", Number(v)), format!("{:.3}", Number(v)));
        assert_eq!(shown(12.0), ("12".into(), "12.000".into()));
        assert_eq!(shown(-0.25), ("-0.25".into(), "-0.250".into()));
        assert_eq!(shown(0.0), ("0".into(), "0.000".into()));
        assert_eq!(shown(-1e308), ("-1e308".into(), "-1.000e308".into()));
        assert_eq!(shown(2.5e15), ("2.5e15".into(), "2.500e15".into()));
        assert_eq!(shown(1e-9), ("1e-9".into(), "1.000e-9".into()));
    }

    /// The one-pass locator places every element where roxmltree's own
    /// `text_pos_at` does, across lines, CRLF endings and multi-byte text.
    #[test]
    fn the_locator_agrees_with_the_parser() {
        let text = "<net>\r\n  <edge id=\"ä\"/><edge id=\"b\"/>\n\n\t<lane>größer</lane>\r\n  <x/>\n</net>";
        let doc = roxmltree::Document::parse(text).unwrap();
        let locator = Locator::new(text);
        let elements: Vec<Node> = doc.descendants().filter(Node::is_element).collect();
        assert_eq!(elements.len(), 5);
        for node in elements {
            let pos = doc.text_pos_at(node.range().start);
            assert_eq!(locator.at(node), Location::new(pos.row as usize, pos.col as usize));
        }
    }

    #[test]
    fn malformed_xml_is_located_by_the_parser() {
        let text = "<net>\n  <edge id=\"a\">\n</net>\n";
        let error = malformed(text, &roxmltree::Document::parse(text).unwrap_err());
        assert_eq!(error.to_string(), "3:1: malformed xml: expected 'edge' tag, not 'net'");
        let text = "<net>\n  <edge";
        let error = malformed(text, &roxmltree::Document::parse(text).unwrap_err());
        assert_eq!(error.location, Location::new(2, 8));
    }

    #[test]
    fn a_missing_attribute_points_at_the_element() {
        let text = "<net>\n    <lane id=\"a\"/>\n</net>";
        assert_eq!(
            first_child_error(text, |n| number(n, "speed")),
            "2:5: missing attribute `speed` on <lane>"
        );
    }

    #[test]
    fn bad_numbers_point_at_the_value() {
        let text = "<net>\n  <lane speed=\"fast\" length=\"inf\"/>\n</net>";
        assert_eq!(
            first_child_error(text, |n| number(n, "speed")),
            "2:16: attribute `speed` of <lane> is not a number: \"fast\""
        );
        assert_eq!(
            first_child_error(text, |n| number(n, "length")),
            "2:30: attribute `length` of <lane> is not a finite number: \"inf\""
        );
    }

    #[test]
    fn optional_numbers_default_only_when_absent() {
        let doc = roxmltree::Document::parse("<net><lane width=\" 2.5\"/><lane/></net>").unwrap();
        let lanes: Vec<_> = children(doc.root_element(), "lane").collect();
        assert_eq!(number_or(lanes[0], "width", 3.2).unwrap(), 2.5);
        assert_eq!(number_or(lanes[1], "width", 3.2).unwrap(), 3.2);
        assert_eq!(optional_number(lanes[1], "width").unwrap(), None);
    }
}
