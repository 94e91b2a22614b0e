//! SUMO road networks (`.net.xml`): edges, their lanes, the connections between
//! them with their paths across junctions, and the junctions.

use std::collections::{HashMap, HashSet};

use roxmltree::Node;

use super::vclass::CLASSES;
use super::xml::{self, SumoError};
use crate::geometry::Xy;
use crate::raw::range;

/// SUMO's default lane width, metres, for lanes that give none.
pub const DEFAULT_LANE_WIDTH: f64 = 3.2;

/// A road network read from a `.net.xml` file.
///
/// Internal edges (`function="internal"`, the paths across junctions) are not
/// among the edges: their lanes are listed apart, and each connection carries
/// the path across its junction. What remains as edges are the roads between
/// junctions. Crossings and walking areas, when the network has them, are kept
/// as edges with their `function`.
#[derive(Debug, Clone, PartialEq)]
pub struct Network {
    /// Edges other than internal ones, in file order.
    pub edges: Vec<Edge>,
    /// The lanes of internal edges, in file order: where a vehicle crossing a
    /// junction is (SUMO's lane ids starting with `:`).
    pub internal_lanes: Vec<Lane>,
    /// Connections between those edges, in file order.
    pub connections: Vec<Connection>,
    /// Junctions other than internal ones, in file order.
    pub junctions: Vec<Junction>,
}

/// A road in one direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    /// Its SUMO id.
    pub id: String,
    /// Its `function`: empty for a road, `crossing`, `walkingarea` or `connector`.
    pub function: String,
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
    /// The vehicle classes it permits (`allow`, `disallow`; all when it gives
    /// neither), one bit per entry of [`CLASSES`].
    pub permitted: u64,
}

impl Lane {
    /// Whether it permits the vehicle class named `name`.
    pub fn permits(&self, name: &str) -> bool {
        CLASSES
            .iter()
            .position(|class| class.name == name)
            .is_some_and(|i| self.permitted & (1 << i) != 0)
    }

    /// Whether it permits a class other than people on foot: a lane for
    /// vehicles, not a sidewalk.
    pub fn is_for_vehicles(&self) -> bool {
        CLASSES
            .iter()
            .enumerate()
            .any(|(i, class)| self.permitted & (1 << i) != 0 && !matches!(class.name, "pedestrian" | "wheelchair"))
    }
}

/// Every class.
const ALL_CLASSES: u64 = (1 << CLASSES.len()) - 1;

/// A lane of one edge continuing into a lane of the next.
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// The incoming edge's id.
    pub from: String,
    /// The outgoing edge's id.
    pub to: String,
    /// The lane index on `from`.
    pub from_lane: u32,
    /// The lane index on `to`.
    pub to_lane: u32,
    /// The centreline across the junction, from the end of the `from` lane to
    /// the start of the `to` lane: the shapes of the internal lanes SUMO routes
    /// the connection through (`via`, followed lane by lane), joined. Empty when
    /// the network has none (one written with `--no-internal-links`).
    pub via: Vec<Xy>,
}

/// A junction where edges meet.
#[derive(Debug, Clone, PartialEq)]
pub struct Junction {
    /// Its SUMO id.
    pub id: String,
    /// Its `type` (`priority`, `traffic_light`, `dead_end`, …).
    pub kind: String,
    /// The lanes that enter it (`incLanes`), in file order.
    pub incoming: Vec<String>,
    /// Its outline in network coordinates, metres, without a closing point equal
    /// to the first; empty when the file gives none.
    pub shape: Vec<Xy>,
}

/// A lane by its edge's id and its index.
type LaneOf<'a> = (&'a str, u32);

/// Reads a SUMO network (`<net><edge><lane …/></edge>…<junction …/>…<connection …/></net>`).
///
/// A lane needs `id`, `index`, `speed` (m/s, in the range of a scenario's
/// speed limits: above 0, at most 150) and `shape` (`x,y x,y …`, at least two
/// points; a height `x,y,z` is dropped); `width` is optional. A connection needs
/// `from`, `to`, `fromLane` and `toLane`; `via` is optional. A junction needs
/// `id`; `type`, `incLanes` and `shape` are optional. The location, roundabouts,
/// traffic-light programs and other elements and attributes are ignored.
///
/// Errors: malformed XML, a missing or bad attribute, a point of a lane's or a
/// junction's shape beyond the world's coordinates (±1e6 m), a connection to an
/// edge or lane the network does not have, and a `via` naming an internal lane
/// it does not have.
pub fn parse_net(text: &str) -> Result<Network, SumoError> {
    let doc = xml::parse(text)?;
    let root = xml::root(&doc, "net")?;
    let mut edges = Vec::new();
    // Each internal lane's edge id, and its index in `internal_lanes`.
    let mut internal: HashMap<String, (&str, usize)> = HashMap::new();
    let mut internal_edges = HashSet::new();
    let mut internal_lanes = Vec::new();
    for node in xml::children(root, "edge") {
        let id = xml::string(node, "id")?;
        let lanes: Vec<Lane> = xml::children(node, "lane").map(lane).collect::<Result<_, _>>()?;
        let function = node.attribute("function").unwrap_or_default();
        if function == "internal" {
            internal_edges.insert(id);
            for lane in lanes {
                internal.insert(lane.id.clone(), (id, internal_lanes.len()));
                internal_lanes.push(lane);
            }
            continue;
        }
        edges.push(Edge {
            id: id.to_owned(),
            function: function.to_owned(),
            lanes,
        });
    }
    let by_id: HashMap<&str, &Edge> = edges.iter().map(|edge| (edge.id.as_str(), edge)).collect();
    // Every connection with a `via`, internal ones too, by its (from, to) lanes,
    // for following a path across a junction lane by lane.
    let mut vias: HashMap<(LaneOf, LaneOf), Node> = HashMap::new();
    let mut normal = Vec::new();
    for node in xml::children(root, "connection") {
        let from = xml::string(node, "from")?;
        let to = xml::string(node, "to")?;
        let from_lane = xml::index(node, "fromLane")?;
        let to_lane = xml::index(node, "toLane")?;
        if node.has_attribute("via") {
            vias.insert(((from, from_lane), (to, to_lane)), node);
        }
        if internal_edges.contains(from) || internal_edges.contains(to) {
            continue;
        }
        for (edge, lane) in [(from, from_lane), (to, to_lane)] {
            let message = match by_id.get(edge) {
                None => format!("connection to unknown edge `{edge}`"),
                Some(found) if !found.lanes.iter().any(|l| l.index == lane) => {
                    format!("connection to lane {lane} of edge `{edge}`, which has no such lane")
                }
                Some(_) => continue,
            };
            return Err(xml::element_error(node, message));
        }
        normal.push((from, from_lane, to, to_lane));
    }
    let mut connections = Vec::new();
    for (from, from_lane, to, to_lane) in normal {
        let mut via: Vec<Xy> = Vec::new();
        let mut next = vias.get(&((from, from_lane), (to, to_lane))).copied();
        // Each step moves to another internal lane; a cycle would revisit one.
        let mut visited = HashSet::new();
        while let Some(at) = next {
            let lane_id = xml::string(at, "via")?;
            let problem = match internal.get(lane_id) {
                None => ", which is not an internal lane of the network",
                Some(_) if !visited.insert(lane_id) => " again: the path across the junction loops",
                Some(_) => "",
            };
            if !problem.is_empty() {
                let attribute = xml::attribute(at, "via")?;
                let message = format!("`via` names `{lane_id}`{problem}");
                return Err(xml::value_error(at, &attribute, message));
            }
            let (edge, index) = internal[lane_id];
            let lane = &internal_lanes[index];
            let skip = usize::from(via.last() == lane.shape.first());
            via.extend(&lane.shape[skip..]);
            next = vias.get(&((edge, lane.index), (to, to_lane))).copied();
        }
        connections.push(Connection {
            from: from.to_owned(),
            to: to.to_owned(),
            from_lane,
            to_lane,
            via,
        });
    }
    let junctions = xml::children(root, "junction")
        .filter(|node| node.attribute("type") != Some("internal"))
        .map(junction)
        .collect::<Result<_, _>>()?;
    Ok(Network {
        edges,
        internal_lanes,
        connections,
        junctions,
    })
}

/// One `<junction>`.
fn junction(node: Node) -> Result<Junction, SumoError> {
    let shape = match node.attribute("shape") {
        Some(_) => xml::outline(node, "shape")?,
        None => Vec::new(),
    };
    Ok(Junction {
        id: xml::string(node, "id")?.to_owned(),
        kind: node.attribute("type").unwrap_or_default().to_owned(),
        incoming: node
            .attribute("incLanes")
            .unwrap_or_default()
            .split_ascii_whitespace()
            .map(str::to_owned)
            .collect(),
        shape,
    })
}

/// One `<lane>`.
fn lane(node: Node) -> Result<Lane, SumoError> {
    let permitted = match (node.attribute_node("allow"), node.attribute_node("disallow")) {
        (Some(allow), _) => classes(node, &allow)?,
        (None, Some(disallow)) => ALL_CLASSES & !classes(node, &disallow)?,
        (None, None) => ALL_CLASSES,
    };
    let lane = Lane {
        id: xml::string(node, "id")?.to_owned(),
        index: xml::index(node, "index")?,
        speed: xml::number_within(node, "speed", range::SPEED_POSITIVE)?,
        width: xml::optional_number_within(node, "width", range::BODY)?.unwrap_or(DEFAULT_LANE_WIDTH),
        shape: xml::shape(node, "shape")?,
        permitted,
    };
    if lane.shape.len() < 2 {
        let attribute = xml::attribute(node, "shape")?;
        let message = "attribute `shape` of <lane> has one point; a lane needs at least two".to_owned();
        return Err(xml::value_error(node, &attribute, message));
    }
    Ok(lane)
}

/// The classes a list of `allow` or `disallow` names, as bits of [`CLASSES`].
fn classes(node: Node, attribute: &roxmltree::Attribute) -> Result<u64, SumoError> {
    let mut bits = 0;
    for name in attribute.value().split_ascii_whitespace() {
        if name == "all" {
            bits = ALL_CLASSES;
            continue;
        }
        let Some(i) = CLASSES.iter().position(|class| class.name == name) else {
            let message = format!(
                "attribute `{}` of {} names vehicle class {name:?}, which SUMO does not know",
                attribute.name(),
                xml::tag(node)
            );
            return Err(xml::value_error(node, attribute, message));
        };
        bits |= 1 << i;
    }
    Ok(bits)
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
    <edge id=":B_1" function="internal">
        <lane id=":B_1_0" index="0" speed="6.51" length="4.00" shape="98.40,1.75 100.00,3.00"/>
    </edge>
    <edge id=":B_2" function="internal">
        <lane id=":B_2_0" index="0" speed="6.51" length="4.00" shape="100.00,3.00 101.60,5.00"/>
    </edge>
    <edge id="BD" from="B" to="D" priority="-1">
        <lane id="BD_0" index="0" speed="13.89" length="95.00" shape="101.60,5.00 101.60,100.00"/>
    </edge>
    <edge id=":B_w0" function="walkingarea">
        <lane id=":B_w0_0" index="0" speed="1.00" length="1.00" width="2.00" shape="95,-5 96,-5"/>
    </edge>
    <junction id="B" type="priority" x="100.00" y="0.00" incLanes="AB_0 AB_1" intLanes=":B_0_0" shape="95,-5 105,-5 105,5 95,5 95,-5"/>
    <junction id=":B_2_0" type="internal" x="100.00" y="3.00" incLanes=":B_1_0" intLanes=""/>
    <junction id="D" type="dead_end" x="101.60" y="100.00"/>
    <connection from="AB" to="BC" fromLane="0" toLane="0" via=":B_0_0" dir="s" state="M"/>
    <connection from="AB" to="BD" fromLane="1" toLane="0" via=":B_1_0" dir="l" state="m"/>
    <connection from=":B_0" to="BC" fromLane="0" toLane="0" dir="s" state="M"/>
    <connection from=":B_1" to="BD" fromLane="0" toLane="0" via=":B_2_0" dir="l" state="m"/>
    <connection from=":B_2" to="BD" fromLane="0" toLane="0" dir="l" state="M"/>
</net>
"#;

    fn error(text: &str) -> String {
        parse_net(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_edges_lanes_and_connections_without_internal_ones() {
        let net = parse_net(NET).unwrap();
        let ids: Vec<_> = net.edges.iter().map(|e| (e.id.as_str(), e.function.as_str())).collect();
        assert_eq!(ids, [("AB", ""), ("BC", ""), ("BD", ""), (":B_w0", "walkingarea")]);
        let internal: Vec<_> = net.internal_lanes.iter().map(|l| (l.id.as_str(), l.speed)).collect();
        assert_eq!(internal, [(":B_0_0", 13.89), (":B_1_0", 6.51), (":B_2_0", 6.51)]);
        let ab = &net.edges[0];
        assert_eq!(
            ab.lanes[0],
            Lane {
                id: "AB_0".into(),
                index: 0,
                speed: 13.89,
                width: DEFAULT_LANE_WIDTH,
                shape: vec![[0.0, -1.6], [98.4, -1.6]],
                permitted: ALL_CLASSES,
            }
        );
        assert_eq!(ab.lanes[1].width, 3.5);
        assert_eq!(ab.lanes[1].shape, [[0.0, 1.75], [98.4, 1.75]]);
        assert_eq!(
            net.connections[0],
            Connection {
                from: "AB".into(),
                to: "BC".into(),
                from_lane: 0,
                to_lane: 0,
                via: vec![[98.4, -1.6], [103.2, -1.6]],
            }
        );
    }

    #[test]
    fn a_path_across_a_junction_follows_its_internal_lanes() {
        let net = parse_net(NET).unwrap();
        assert_eq!(net.connections.len(), 2);
        let left = &net.connections[1];
        assert_eq!((left.from.as_str(), left.from_lane, left.to.as_str()), ("AB", 1, "BD"));
        // :B_1_0 then :B_2_0, their shared point once.
        assert_eq!(left.via, [[98.4, 1.75], [100.0, 3.0], [101.6, 5.0]]);
        let text = NET.replace(
            r#"from=":B_1" to="BD" fromLane="0" toLane="0" via=":B_2_0""#,
            r#"from=":B_1" to="BD" fromLane="0" toLane="0" via=":B_9_0""#,
        );
        assert_eq!(
            error(&text),
            "32:66: `via` names `:B_9_0`, which is not an internal lane of the network"
        );
        let text = NET.replace(
            r#"from=":B_2" to="BD" fromLane="0" toLane="0""#,
            r#"from=":B_2" to="BD" fromLane="0" toLane="0" via=":B_1_0""#,
        );
        assert_eq!(
            error(&text),
            "33:66: `via` names `:B_1_0` again: the path across the junction loops"
        );
        let text = NET.replace(" via=\":B_0_0\"", "");
        assert_eq!(parse_net(&text).unwrap().connections[0].via, Vec::<Xy>::new());
    }

    #[test]
    fn junctions_other_than_internal_ones_are_read() {
        let net = parse_net(NET).unwrap();
        let b = &net.junctions[0];
        assert_eq!((b.id.as_str(), b.kind.as_str()), ("B", "priority"));
        assert_eq!(b.incoming, ["AB_0", "AB_1"]);
        assert_eq!(b.shape, [[95.0, -5.0], [105.0, -5.0], [105.0, 5.0], [95.0, 5.0]]);
        let d = &net.junctions[1];
        assert_eq!((d.id.as_str(), d.kind.as_str(), d.shape.len()), ("D", "dead_end", 0));
        assert_eq!(net.junctions.len(), 2);
    }

    #[test]
    fn lane_errors_are_located() {
        let text = NET.replace(r#"speed="8.33""#, r#"speed="8,33""#);
        assert_eq!(
            error(&text),
            "12:42: attribute `speed` of <lane> is not a number: \"8,33\""
        );
        for (speed, found) in [("0", "0"), ("-5", "-5"), ("150.5", "150.5"), ("1e300", "1e300")] {
            let text = NET.replace(r#"speed="8.33""#, &format!(r#"speed="{speed}""#));
            assert_eq!(
                error(&text),
                format!("12:42: attribute `speed` of <lane> must be a number > 0 and ≤ 150 m/s, found {found}")
            );
        }
        // A lane's width is a body's, as a road's `lane_width`.
        let text = NET.replace(r#"width="3.50""#, r#"width="1e300""#);
        assert_eq!(
            error(&text),
            "9:71: attribute `width` of <lane> must be a number > 0 and ≤ 100 m, found 1e300"
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

    /// A walking area's lane at 1e300 m was read, and the scenario passed.
    #[test]
    fn shape_points_beyond_the_coordinate_range_are_errors_at_the_coordinate() {
        let text = NET.replace(r#"shape="95,-5 96,-5""#, r#"shape="1e300,-5 96,-5""#);
        assert_eq!(
            error(&text),
            "24:85: x of point \"1e300,-5\" in attribute `shape` of <lane> must be a number from \
             -1000000 to 1000000 m, found 1e300"
        );
        let text = NET.replace("105,-5 105,5", "105,-5 105,-1000001");
        assert_eq!(
            error(&text),
            "26:121: y of point \"105,-1000001\" in attribute `shape` of <junction> must be a number from \
             -1000000 to 1000000 m, found -1000001"
        );
    }

    #[test]
    fn connections_must_join_existing_lanes() {
        let text = NET.replace(
            r#"to="BC" fromLane="0" toLane="0" via"#,
            r#"to="CD" fromLane="0" toLane="0" via"#,
        );
        assert_eq!(error(&text), "29:5: connection to unknown edge `CD`");
        let text = NET.replace(r#"toLane="0" via"#, r#"toLane="2" via"#);
        assert_eq!(
            error(&text),
            "29:5: connection to lane 2 of edge `BC`, which has no such lane"
        );
        let text = NET.replace(r#"fromLane="0" toLane="0" via"#, r#"fromLane="one" toLane="0" via"#);
        assert_eq!(
            error(&text),
            "29:45: attribute `fromLane` of <connection> is not a non-negative integer: \"one\""
        );
    }

    #[test]
    fn lanes_permit_what_allow_and_disallow_say() {
        let text = NET
            .replace(
                r#"<lane id="AB_0" index="0""#,
                r#"<lane id="AB_0" index="0" allow="pedestrian""#,
            )
            .replace(
                r#"<lane id="AB_1" index="1""#,
                r#"<lane id="AB_1" index="1" disallow="pedestrian bicycle""#,
            )
            .replace(
                r#"<lane id="BC_0" index="0""#,
                r#"<lane id="BC_0" index="0" allow="bicycle""#,
            );
        let net = parse_net(&text).unwrap();
        let [sidewalk, road] = [&net.edges[0].lanes[0], &net.edges[0].lanes[1]];
        assert!(sidewalk.permits("pedestrian") && !sidewalk.permits("passenger") && !sidewalk.is_for_vehicles());
        assert!(!road.permits("pedestrian") && !road.permits("bicycle") && road.permits("passenger"));
        assert!(road.is_for_vehicles());
        let bike_lane = &net.edges[1].lanes[0];
        assert!(bike_lane.is_for_vehicles() && !bike_lane.permits("passenger"));
        let text = NET.replace(
            r#"<lane id="AB_0" index="0""#,
            r#"<lane id="AB_0" index="0" allow="hovercraft""#,
        );
        assert_eq!(
            error(&text),
            "8:42: attribute `allow` of <lane> names vehicle class \"hovercraft\", which SUMO does not know"
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
