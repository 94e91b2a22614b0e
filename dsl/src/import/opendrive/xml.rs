//! Reading OpenDRIVE's XML: parsing within the size limits, OpenDRIVE's
//! number and choice types, and the check of an element's children against
//! those OpenDRIVE allows there; the located error and typed attribute access
//! come from [`crate::import::xml`].

use roxmltree::{Document, Node, ParsingOptions};

use crate::Location;
use crate::de::closest;
pub(crate) use crate::import::xml::{
    Locator, attribute, children, element_error, number, number_or, number_within, optional_number_within, string, tag,
    value_error,
};
use crate::import::xml::{Number, XmlError, malformed};

/// The most bytes an OpenDRIVE file may hold: about 25 times a dense 1 km²
/// city network, and what the parsed tree of such a file keeps within a few
/// hundred megabytes.
pub const MAX_BYTES: usize = 64 << 20;

/// The most XML nodes (elements, attributes' owners, text) an OpenDRIVE file
/// may hold; the parser stops at the limit instead of allocating more.
pub const MAX_NODES: u32 = 2_000_000;

/// A problem in an OpenDRIVE file, located by line and column.
pub type OpenDriveError = XmlError;

/// Parses `text` as XML within [`MAX_BYTES`] and [`MAX_NODES`]; a malformed
/// file is an error at the parser's position.
pub(crate) fn parse(text: &str) -> Result<Document<'_>, OpenDriveError> {
    if text.len() > MAX_BYTES {
        return Err(OpenDriveError {
            location: Location::new(1, 1),
            message: format!(
                "the file holds {} MiB, more than the limit of {} MiB for an OpenDRIVE map",
                text.len() >> 20,
                MAX_BYTES >> 20
            ),
        });
    }
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
        ..ParsingOptions::default()
    };
    Document::parse_with_options(text, options).map_err(|error| match error {
        roxmltree::Error::NodesLimitReached => OpenDriveError {
            location: Location::new(error.pos().row as usize, error.pos().col as usize),
            message: format!("the file holds more than {MAX_NODES} XML nodes, the limit for an OpenDRIVE map"),
        },
        _ => malformed(text, &error),
    })
}

/// The first element child of `node` named `name`.
pub(crate) fn child<'a, 'i>(node: Node<'a, 'i>, name: &'static str) -> Option<Node<'a, 'i>> {
    children(node, name).next()
}

/// Elements OpenDRIVE allows anywhere, which carry nothing sightline reads.
const ANYWHERE: [&str; 2] = ["userData", "dataQuality"];

/// Checks that every element child of `node` is one OpenDRIVE allows there:
/// those sightline reads (`read`) and those it ignores (`ignored`), besides
/// `<userData>` and `<dataQuality>`. An element the standard does not define
/// there is an error naming the closest allowed name; `<include>`, which
/// would need another file, is refused as not supported.
pub(crate) fn allowed_children(node: Node, read: &[&str], ignored: &[&str]) -> Result<(), OpenDriveError> {
    for child in node.children().filter(Node::is_element) {
        let name = child.tag_name().name();
        if read.contains(&name) || ignored.contains(&name) || ANYWHERE.contains(&name) {
            continue;
        }
        let message = if name == "include" {
            format!(
                "<include> in {} is not supported: sightline reads one file; put the included elements in it",
                tag(node)
            )
        } else {
            let known = read.iter().chain(ignored).copied();
            let suggestion = closest(name, known)
                .map(|close| format!("; did you mean <{close}>?"))
                .unwrap_or_default();
            format!(
                "unknown element <{name}> in {}: OpenDRIVE 1.8 defines no such element there{suggestion}",
                tag(node)
            )
        };
        return Err(element_error(child, message));
    }
    Ok(())
}

/// A required number ≥ 0 (OpenDRIVE's `t_grEqZero`).
pub(crate) fn non_negative(node: Node, name: &str) -> Result<f64, OpenDriveError> {
    let value = number(node, name)?;
    if value < 0.0 {
        let attribute = attribute(node, name)?;
        let message = format!(
            "attribute `{name}` of {} must be ≥ 0, found {}",
            tag(node),
            Number(value)
        );
        return Err(value_error(node, &attribute, message));
    }
    Ok(value)
}

/// A required whole number, such as a lane id.
pub(crate) fn integer(node: Node, name: &str) -> Result<i32, OpenDriveError> {
    let attribute = attribute(node, name)?;
    attribute.value().trim().parse().map_err(|_| {
        let message = format!(
            "attribute `{name}` of {} is not a whole number: {:?}",
            tag(node),
            attribute.value()
        );
        value_error(node, &attribute, message)
    })
}

/// An optional attribute that must be one of `allowed`; `None` when absent.
pub(crate) fn choice<'a>(node: Node<'a, '_>, name: &str, allowed: &[&str]) -> Result<Option<&'a str>, OpenDriveError> {
    let Some(attribute) = node.attribute_node(name) else {
        return Ok(None);
    };
    let value = attribute.value();
    if allowed.contains(&value) {
        return Ok(Some(value));
    }
    let expected = allowed.iter().map(|a| format!("`{a}`")).collect::<Vec<_>>().join(", ");
    let suggestion = closest(value, allowed.iter().copied())
        .map(|close| format!("; did you mean `{close}`?"))
        .unwrap_or_default();
    let message = format!(
        "attribute `{name}` of {} is {value:?}; expected one of {expected}{suggestion}",
        tag(node)
    );
    Err(value_error(node, &attribute, message))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_child_error<T>(text: &str, read: impl Fn(Node) -> Result<T, OpenDriveError>) -> String {
        crate::import::xml::error_of_first_child(&parse(text).unwrap(), read)
    }

    #[test]
    fn malformed_xml_is_located_by_the_parser() {
        let error = parse("<OpenDRIVE>\n  <road id=\"1\">\n</OpenDRIVE>\n").unwrap_err();
        assert_eq!(
            error.to_string(),
            "3:1: malformed xml: expected 'road' tag, not 'OpenDRIVE'"
        );
        let error = parse("<OpenDRIVE>\n  <road").unwrap_err();
        assert_eq!(error.location, Location::new(2, 8));
    }

    #[test]
    fn a_document_type_definition_is_refused() {
        // Entity expansion ("billion laughs") needs a DTD; none is read.
        let text = "<!DOCTYPE r [<!ENTITY a \"aaaa\">]>\n<OpenDRIVE>&a;</OpenDRIVE>";
        assert!(parse(text).unwrap_err().message.starts_with("malformed xml: "));
    }

    #[test]
    fn too_many_nodes_stop_the_parser() {
        let text = format!("<OpenDRIVE>{}</OpenDRIVE>", "<a/>".repeat(MAX_NODES as usize));
        let error = parse(&text).unwrap_err();
        assert_eq!(
            error.message,
            format!("the file holds more than {MAX_NODES} XML nodes, the limit for an OpenDRIVE map")
        );
    }

    #[test]
    fn numbers_are_checked_where_they_are_written() {
        let text = "<OpenDRIVE>\n  <geometry s=\"x\" length=\"-1\" hdg=\"inf\"/>\n</OpenDRIVE>";
        assert_eq!(
            first_child_error(text, |n| number(n, "s")),
            "2:16: attribute `s` of <geometry> is not a number: \"x\""
        );
        assert_eq!(
            first_child_error(text, |n| non_negative(n, "length")),
            "2:27: attribute `length` of <geometry> must be ≥ 0, found -1"
        );
        assert_eq!(
            first_child_error(text, |n| number(n, "hdg")),
            "2:36: attribute `hdg` of <geometry> is not a finite number: \"inf\""
        );
        assert_eq!(
            first_child_error(text, |n| number(n, "x")),
            "2:3: missing attribute `x` on <geometry>"
        );
    }

    #[test]
    fn choices_suggest_the_closest_value() {
        let text = "<OpenDRIVE><road rule=\"RTH\"/></OpenDRIVE>";
        assert_eq!(
            first_child_error(text, |n| choice(n, "rule", &["RHT", "LHT"]).map(|c| c.map(str::len))),
            "1:24: attribute `rule` of <road> is \"RTH\"; expected one of `RHT`, `LHT`; did you mean `RHT`?"
        );
    }

    #[test]
    fn unknown_children_are_refused_and_known_ones_pass() {
        let text = "<OpenDRIVE><planView><geomtry/></planView></OpenDRIVE>";
        assert_eq!(
            first_child_error(text, |n| allowed_children(n, &["geometry"], &[])),
            "1:22: unknown element <geomtry> in <planView>: OpenDRIVE 1.8 defines no such element there; \
             did you mean <geometry>?"
        );
        let text = "<OpenDRIVE><road><userData/><signals/><include file=\"x\"/></road></OpenDRIVE>";
        assert_eq!(
            first_child_error(text, |n| allowed_children(n, &[], &["signals"])),
            "1:39: <include> in <road> is not supported: sightline reads one file; put the included elements in it"
        );
    }
}
