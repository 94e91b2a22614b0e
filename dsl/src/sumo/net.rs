//! SUMO road networks (`.net.xml`): edges, their lanes, and the connections
//! between them.

use std::collections::{HashMap, HashSet};

use roxmltree::Node;

use super::xml::{self, SumoError};
use crate::geometry::Xy;

/// SUMO's default lane width, metres, for lanes that give none.
pub const DEFAULT_LANE_WIDTH: f64 = 3.2;

/// A road network read from a `.net.xml` file.
///
/// Internal edges (`function="internal"`, the paths across junctions) and the
/// connections through them are left out: what remains are the roads between
/// junctions and which lane continues into which. Crossings and walking areas,
/// when the network has them, are kept as edges.
#[derive(Debug, Clone, PartialEq)]
pub struct Network {
    /// Edges other than internal ones, in file order.
    pub edges: Vec<Edge>,
    /// Connections between those edges, in file order.
    pub connections: Vec<Connection>,
}

/// A road in one direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    /// Its SUMO id.
    pub id: String,
    /// Its lanes, in file order (SUMO writes lane 0, the rightmost, first).
    pub lanes: Vec<Lane>,
}

/// One lane of an edge.
#[derive(Debug, Clone, PartialEq)]
pub struct Lane {
    /// Its SUMO id.
    pub id: String,
    /// Its index within the edge, 0 the rightmost.
    pub index: u32,
    /// Speed limit, m/s.
    pub speed: f64,
    /// Width, metres; [`DEFAULT_LANE_WIDTH`] when the file gives none.
    pub width: f64,
    /// Centreline in network coordinates, metres, in the direction of travel;
    /// at least two points.
    pub shape: Vec<Xy>,
}

/// A lane of one edge continuing into a lane of the next.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Connection {
    /// The incoming edge's id.
    pub from: String,
    /// The outgoing edge's id.
    pub to: String,
    /// The lane index on `from`.
    pub from_lane: u32,
    /// The lane index on `to`.
    pub to_lane: u32,
}

/// Reads a SUMO network (`<net><edge><lane …/></edge>…<connection …/></net>`).
///
/// A lane needs `id`, `index`, `speed` and `shape` (`x,y x,y …`, at least two
/// points; a height `x,y,z` is dropped); `width` is optional. A connection needs
/// `from`, `to`, `fromLane` and `toLane`. Junctions, the location and other
/// elements and attributes are ignored.
///
/// Errors: malformed XML, a missing or bad attribute, and a connection to an
/// edge or lane the network does not have.
pub fn parse_net(text: &str) -> Result<Network, SumoError> {
    let doc = xml::parse(text)?;
    let root = xml::root(&doc, "net")?;
    let mut edges = Vec::new();
    let mut internal = HashSet::new();
    for node in xml::children(root, "edge") {
        let id = xml::string(node, "id")?;
        if node.attribute("function") == Some("internal") {
            internal.insert(id);
            continue;
        }
        let lanes = xml::children(node, "lane").map(lane).collect::<Result<_, _>>()?;
        edges.push(Edge {
            id: id.to_owned(),
            lanes,
        });
    }
    let by_id: HashMap<&str, &Edge> = edges.iter().map(|edge| (edge.id.as_str(), edge)).collect();
    let mut connections = Vec::new();
    for node in xml::children(root, "connection") {
        let from = xml::string(node, "from")?;
        let to = xml::string(node, "to")?;
        if internal.contains(from) || internal.contains(to) {
            continue;
        }
        let connection = Connection {
            from: from.to_owned(),
            to: to.to_owned(),
            from_lane: xml::index(node, "fromLane")?,
            to_lane: xml::index(node, "toLane")?,
        };
        for (edge, lane) in [(from, connection.from_lane), (to, connection.to_lane)] {
            let message = match by_id.get(edge) {
                None => format!("connection to unknown edge `{edge}`"),
                Some(found) if !found.lanes.iter().any(|l| l.index == lane) => {
                    format!("connection to lane {lane} of edge `{edge}`, which has no such lane")
                }
                Some(_) => continue,
            };
            return Err(xml::element_error(node, message));
        }
        connections.push(connection);
    }
    Ok(Network { edges, connections })
}

/// One `<lane>`.
fn lane(node: Node) -> Result<Lane, SumoError> {
    let lane = Lane {
        id: xml::string(node, "id")?.to_owned(),
        index: xml::index(node, "index")?,
        speed: xml::number(node, "speed")?,
        width: xml::number_or(node, "width", DEFAULT_LANE_WIDTH)?,
        shape: xml::shape(node, "shape")?,
    };
    if lane.shape.len() < 2 {
        let attribute = xml::attribute(node, "shape")?;
        let message = "attribute `shape` of <lane> has one point; a lane needs at least two".to_owned();
        return Err(xml::value_error(node, &attribute, message));
    }
    Ok(lane)
}

#[cfg(test)]
mod tests {
    use super::*;

    const NET: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<net version="1.20" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
    <location netOffset="0.00,0.00" convBoundary="0.00,0.00,100.00,0.00" projParameter="!"/>
    <edge id=":B_0" function="internal">
        <lane id=":B_0_0" index="0" speed="13.89" length="5.00" shape="98.40,-1.60 103.20,-1.60"/>
    </edge>
    <edge id="AB" from="A" to="B" priority="-1">
        <lane id="AB_0" index="0" speed="13.89" length="96.80" shape="0.00,-1.60 98.40,-1.60"/>
        <lane id="AB_1" index="1" speed="13.89" length="96.80" width="3.50" shape="0.00,1.75,0.00 98.40,1.75,0.00"/>
    </edge>
    <edge id="BC" from="B" to="C" priority="-1">
        <lane id="BC_0" index="0" speed="8.33" length="96.80" shape="103.20,-1.60 200.00,-1.60"/>
    </edge>
    <junction id="B" type="priority" x="100.00" y="0.00" incLanes="AB_0 AB_1" intLanes=":B_0_0" shape="100,0"/>
    <connection from="AB" to="BC" fromLane="0" toLane="0" via=":B_0_0" dir="s" state="M"/>
    <connection from=":B_0" to="BC" fromLane="0" toLane="0" dir="s" state="M"/>
</net>
"#;

    fn error(text: &str) -> String {
        parse_net(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_edges_lanes_and_connections_without_internal_ones() {
        let net = parse_net(NET).unwrap();
        let ids: Vec<_> = net.edges.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids, ["AB", "BC"]);
        let ab = &net.edges[0];
        assert_eq!(
            ab.lanes[0],
            Lane {
                id: "AB_0".into(),
                index: 0,
                speed: 13.89,
                width: DEFAULT_LANE_WIDTH,
                shape: vec![[0.0, -1.6], [98.4, -1.6]],
            }
        );
        assert_eq!(ab.lanes[1].width, 3.5);
        assert_eq!(ab.lanes[1].shape, [[0.0, 1.75], [98.4, 1.75]]);
        assert_eq!(
            net.connections,
            [Connection {
                from: "AB".into(),
                to: "BC".into(),
                from_lane: 0,
                to_lane: 0
            }]
        );
    }

    #[test]
    fn lane_errors_are_located() {
        let text = NET.replace(r#"speed="8.33""#, r#"speed="8,33""#);
        assert_eq!(
            error(&text),
            "12:42: attribute `speed` of <lane> is not a number: \"8,33\""
        );
        let text = NET.replace(r#"index="1" "#, "");
        assert_eq!(error(&text), "9:9: missing attribute `index` on <lane>");
        let text = NET.replace("103.20,-1.60 200.00,-1.60", "103.20,-1.60 200.00;-1.60");
        assert_eq!(
            error(&text),
            "12:83: bad point \"200.00;-1.60\" in attribute `shape` of <lane>; expected \"x,y\" with finite numbers"
        );
        let text = NET.replace("103.20,-1.60 200.00,-1.60", "103.20,-1.60");
        assert_eq!(
            error(&text),
            "12:70: attribute `shape` of <lane> has one point; a lane needs at least two"
        );
    }

    #[test]
    fn connections_must_join_existing_lanes() {
        let text = NET.replace(
            r#"to="BC" fromLane="0" toLane="0" via"#,
            r#"to="CD" fromLane="0" toLane="0" via"#,
        );
        assert_eq!(error(&text), "15:5: connection to unknown edge `CD`");
        let text = NET.replace(r#"toLane="0" via"#, r#"toLane="2" via"#);
        assert_eq!(
            error(&text),
            "15:5: connection to lane 2 of edge `BC`, which has no such lane"
        );
        let text = NET.replace(r#"fromLane="0" toLane="0" via"#, r#"fromLane="one" toLane="0" via"#);
        assert_eq!(
            error(&text),
            "15:45: attribute `fromLane` of <connection> is not a non-negative integer: \"one\""
        );
    }

    #[test]
    fn malformed_xml_is_an_error() {
        assert_eq!(
            error("<net>\n<edge id=\"a\"></net>"),
            "2:14: malformed xml: expected 'edge' tag, not 'net'"
        );
    }
}
