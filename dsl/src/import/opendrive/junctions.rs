//! Junctions (`<junction>`): which roads meet, and which lane of an incoming
//! road continues into which lane of a connecting road.

use roxmltree::Node;

use super::xml::{self, Locator, OpenDriveError};
use crate::Location;

/// A junction.
#[derive(Debug, Clone, PartialEq)]
pub struct Junction {
    /// Its id.
    pub id: String,
    /// Its `type`: `default`, `virtual`, `direct` or `crossing`.
    pub kind: String,
    /// Its connections, in file order.
    pub connections: Vec<Connection>,
    /// Where it is written.
    pub at: Location,
}

/// Which end of a road meets a junction or another road.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    /// Its start (s = 0).
    Start,
    /// Its end (s = length).
    End,
}

/// A connection: traffic from an incoming road into a connecting road (or, in
/// a direct junction, straight into a linked road).
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// The incoming road's id.
    pub incoming: String,
    /// The connecting road's id (`connectingRoad`), or the linked road's in a
    /// direct junction (`linkedRoad`).
    pub target: String,
    /// The end of the target road where traffic enters it.
    pub contact: Contact,
    /// (lane of the incoming road, lane of the target road, where written).
    pub lane_links: Vec<(i32, i32, Location)>,
    /// Where it is written.
    pub at: Location,
}

/// The junction types of OpenDRIVE 1.8 (1.4–1.6 know `default` and `virtual`).
const KINDS: [&str; 4] = ["default", "virtual", "direct", "crossing"];

/// Reads one `<junction>`.
pub(crate) fn junction(node: Node, locator: &Locator) -> Result<Junction, OpenDriveError> {
    xml::allowed_children(
        node,
        &["connection"],
        &[
            "priority",
            "controller",
            "surface",
            "boundary",
            "elevationGrid",
            "planView",
            "objects",
            "signals",
            "crossPath",
            "roadSection",
        ],
    )?;
    let kind = xml::choice(node, "type", &KINDS)?.unwrap_or("default");
    let connections = xml::children(node, "connection")
        .map(|c| connection(c, locator))
        .collect::<Result<_, _>>()?;
    Ok(Junction {
        id: xml::string(node, "id")?.to_owned(),
        kind: kind.to_owned(),
        connections,
        at: locator.at(node),
    })
}

/// One `<connection>`.
fn connection(node: Node, locator: &Locator) -> Result<Connection, OpenDriveError> {
    xml::allowed_children(node, &["laneLink"], &["predecessor", "successor"])?;
    let target = match (node.attribute("connectingRoad"), node.attribute("linkedRoad")) {
        (Some(road), None) | (None, Some(road)) => road,
        _ => {
            return Err(xml::element_error(
                node,
                "a <connection> names its `connectingRoad` (or, in a direct junction, its `linkedRoad`)".into(),
            ));
        }
    };
    let contact = match xml::choice(node, "contactPoint", &["start", "end"])? {
        Some("end") => Contact::End,
        Some(_) => Contact::Start,
        None => {
            return Err(xml::element_error(
                node,
                "missing attribute `contactPoint` on <connection>".into(),
            ));
        }
    };
    let lane_links = xml::children(node, "laneLink")
        .map(|link| Ok((xml::integer(link, "from")?, xml::integer(link, "to")?, locator.at(link))))
        .collect::<Result<_, OpenDriveError>>()?;
    Ok(Connection {
        incoming: xml::string(node, "incomingRoad")?.to_owned(),
        target: target.to_owned(),
        contact,
        lane_links,
        at: locator.at(node),
    })
}

/// Reads a `contactPoint` attribute (`start` or `end`), when given.
pub(crate) fn contact(node: Node) -> Result<Option<Contact>, OpenDriveError> {
    Ok(match xml::choice(node, "contactPoint", &["start", "end"])? {
        Some("start") => Some(Contact::Start),
        Some(_) => Some(Contact::End),
        None => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Junction, String> {
        let doc = xml::parse(text).unwrap();
        junction(doc.root_element(), &Locator::new(text)).map_err(|e| e.to_string())
    }

    #[test]
    fn reads_connections_and_lane_links() {
        let j = read(
            r#"<junction id="7" name="x"><connection id="0" incomingRoad="1" connectingRoad="100" contactPoint="start"><laneLink from="-1" to="-1"/></connection><priority high="1" low="2"/></junction>"#,
        )
        .unwrap();
        assert_eq!((j.id.as_str(), j.kind.as_str()), ("7", "default"));
        let c = &j.connections[0];
        assert_eq!(
            (c.incoming.as_str(), c.target.as_str(), c.contact),
            ("1", "100", Contact::Start)
        );
        assert_eq!(c.lane_links[0].0..c.lane_links[0].1, -1..-1);
    }

    #[test]
    fn a_connection_needs_its_target_and_contact_point() {
        assert_eq!(
            read(r#"<junction id="7"><connection id="0" incomingRoad="1" contactPoint="start"/></junction>"#)
                .unwrap_err(),
            "1:18: a <connection> names its `connectingRoad` (or, in a direct junction, its `linkedRoad`)"
        );
        assert_eq!(
            read(r#"<junction id="7"><connection id="0" incomingRoad="1" connectingRoad="2"/></junction>"#)
                .unwrap_err(),
            "1:18: missing attribute `contactPoint` on <connection>"
        );
        assert_eq!(
            read(r#"<junction id="7" type="roundabout"/>"#).unwrap_err(),
            "1:24: attribute `type` of <junction> is \"roundabout\"; expected one of `default`, `virtual`, `direct`, \
             `crossing`"
        );
    }
}
