//! A [`Map`] written as ASAM OpenDRIVE 1.7 XML.

use super::map::{Geometry, Link, Map, MapRoad, ObjectKind};
use super::xml::{Unwritable, Xml, num};

/// The OpenDRIVE version written: 1.7.
pub const OPENDRIVE_VERSION: (u32, u32) = (1, 7);

/// The map as an OpenDRIVE document named `name`.
pub(crate) fn opendrive(map: &Map, name: &str) -> Result<String, Unwritable> {
    let mut xml = Xml::new();
    xml.start("OpenDRIVE", &[]);
    let points = map
        .roads
        .iter()
        .flat_map(|road| road.geometry.iter().flat_map(|g| [g.at(0.0).0, g.at(g.length).0]));
    let (mut west, mut south, mut east, mut north) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for [x, y] in points {
        (west, east, south, north) = (west.min(x), east.max(x), south.min(y), north.max(y));
    }
    xml.empty(
        "header",
        &[
            ("revMajor", OPENDRIVE_VERSION.0.to_string()),
            ("revMinor", OPENDRIVE_VERSION.1.to_string()),
            ("name", name.into()),
            ("version", "1".into()),
            ("north", num(north)),
            ("south", num(south)),
            ("east", num(east)),
            ("west", num(west)),
            ("vendor", "sightline".into()),
        ],
    );
    for road in &map.roads {
        write_road(&mut xml, road, map);
    }
    for junction in &map.junctions {
        xml.start(
            "junction",
            &[
                ("id", junction.id.to_string()),
                ("name", format!("junction {}", junction.id)),
            ],
        );
        for (k, connection) in junction.connections.iter().enumerate() {
            xml.start(
                "connection",
                &[
                    ("id", k.to_string()),
                    ("incomingRoad", connection.incoming.to_string()),
                    ("connectingRoad", connection.connecting.to_string()),
                    ("contactPoint", "start".into()),
                ],
            );
            for &(from, to) in &connection.lanes {
                xml.empty("laneLink", &[("from", from.to_string()), ("to", to.to_string())]);
            }
            xml.end();
        }
        xml.end();
    }
    xml.finish()
}

fn write_road(xml: &mut Xml, road: &MapRoad, map: &Map) {
    xml.start(
        "road",
        &[
            ("name", road.name.clone()),
            ("length", num(road.length())),
            ("id", road.id.to_string()),
            ("junction", road.junction.map_or("-1".into(), |j| j.to_string())),
            ("rule", "RHT".into()),
        ],
    );
    if road.predecessor.is_some() || road.successor.is_some() {
        xml.start("link", &[]);
        for (tag, link) in [("predecessor", road.predecessor), ("successor", road.successor)] {
            match link {
                Some(Link::Road { id, start }) => xml.empty(
                    tag,
                    &[
                        ("elementType", "road".into()),
                        ("elementId", id.to_string()),
                        ("contactPoint", if start { "start" } else { "end" }.into()),
                    ],
                ),
                Some(Link::Junction(id)) => {
                    xml.empty(
                        tag,
                        &[("elementType", "junction".into()), ("elementId", id.to_string())],
                    );
                }
                None => {}
            }
        }
        xml.end();
    }
    xml.start("type", &[("s", "0".into()), ("type", "town".into())]);
    xml.empty("speed", &[("max", num(road.speed_limit)), ("unit", "m/s".into())]);
    xml.end();
    xml.start("planView", &[]);
    for g in &road.geometry {
        write_geometry(xml, g);
    }
    xml.end();
    xml.start("lanes", &[]);
    xml.empty(
        "laneOffset",
        &[
            ("s", "0".into()),
            ("a", num(road.lane_offset())),
            ("b", "0".into()),
            ("c", "0".into()),
            ("d", "0".into()),
        ],
    );
    xml.start("laneSection", &[("s", "0".into())]);
    xml.start("center", &[]);
    xml.start(
        "lane",
        &[("id", "0".into()), ("type", "none".into()), ("level", "false".into())],
    );
    xml.empty(
        "roadMark",
        &[
            ("sOffset", "0".into()),
            ("type", "solid".into()),
            ("color", "standard".into()),
        ],
    );
    xml.end();
    xml.end();
    xml.start("right", &[]);
    // Lane −1 (sightline's leftmost) first, lane −n (sightline's lane 0) last.
    for k in (0..road.lanes).rev() {
        xml.start(
            "lane",
            &[
                ("id", road.lane_id(k).to_string()),
                ("type", "driving".into()),
                ("level", "false".into()),
            ],
        );
        write_lane_link(xml, road, k, map);
        xml.empty(
            "width",
            &[
                ("sOffset", "0".into()),
                ("a", num(road.lane_width)),
                ("b", "0".into()),
                ("c", "0".into()),
                ("d", "0".into()),
            ],
        );
        let mark = if k == 0 { "solid" } else { "broken" };
        xml.empty(
            "roadMark",
            &[
                ("sOffset", "0".into()),
                ("type", mark.into()),
                ("color", "standard".into()),
            ],
        );
        xml.end();
    }
    xml.end();
    xml.end();
    xml.end();
    if !road.objects.is_empty() {
        xml.start("objects", &[]);
        for (i, object) in road.objects.iter().enumerate() {
            let kind = match object.kind {
                ObjectKind::Building => "building",
                ObjectKind::Crosswalk => "crosswalk",
            };
            let mut attributes = vec![
                ("id", format!("{}{:03}", road.id, i)),
                ("name", object.name.clone()),
                ("type", kind.to_string()),
                ("s", num(object.s)),
                ("t", num(object.t)),
                ("zOffset", "0".into()),
                ("hdg", "0".into()),
                ("orientation", "none".into()),
            ];
            if object.height > 0.0 {
                attributes.push(("height", num(object.height)));
            }
            xml.start("object", &attributes);
            xml.start("outlines", &[]);
            xml.start("outline", &[("id", "0".into()), ("closed", "true".into())]);
            for (k, [u, v]) in object.corners.iter().enumerate() {
                xml.empty(
                    "cornerLocal",
                    &[
                        ("u", num(*u)),
                        ("v", num(*v)),
                        ("z", "0".into()),
                        ("height", num(object.height)),
                        ("id", k.to_string()),
                    ],
                );
            }
            xml.end();
            xml.end();
            xml.end();
        }
        xml.end();
    }
    xml.end();
}

fn write_geometry(xml: &mut Xml, g: &Geometry) {
    xml.start(
        "geometry",
        &[
            ("s", num(g.s)),
            ("x", num(g.x)),
            ("y", num(g.y)),
            ("hdg", num(g.hdg)),
            ("length", num(g.length)),
        ],
    );
    if g.curvature == 0.0 {
        xml.empty("line", &[]);
    } else {
        xml.empty("arc", &[("curvature", num(g.curvature))]);
    }
    xml.end();
}

/// The lane's predecessor and successor on roads linked directly (a junction's
/// lanes are linked by its connections).
fn write_lane_link(xml: &mut Xml, road: &MapRoad, k: usize, map: &Map) {
    let other = |link: Option<Link>| match link {
        Some(Link::Road { id, .. }) => map.roads.get(id - 1).filter(|other| k < other.lanes),
        _ => None,
    };
    let (before, after) = (other(road.predecessor), other(road.successor));
    if before.is_none() && after.is_none() {
        return;
    }
    xml.start("link", &[]);
    if let Some(before) = before {
        xml.empty("predecessor", &[("id", before.lane_id(k).to_string())]);
    }
    if let Some(after) = after {
        xml.empty("successor", &[("id", after.lane_id(k).to_string())]);
    }
    xml.end();
}
