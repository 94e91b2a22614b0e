//! The whole file (`<OpenDRIVE>`): header, roads and junctions, and the
//! references between them checked.

use std::collections::HashMap;

use roxmltree::Node;

use super::geometry::{CHAIN_TOLERANCE, Geometry, plan_view};
use super::junctions::{Contact, Junction, contact, junction};
use super::lanes::{LaneSection, Lanes, Speed, lanes, road_speeds};
use super::objects::{Object, objects};
use super::xml::{self, Locator, OpenDriveError};
use crate::Location;
use crate::import::xml::Number;

/// The longest road sightline reads, metres.
pub const MAX_ROAD_LENGTH: f64 = 100_000.0;

/// How far from the origin a map's points may lie, metres (the world's range
/// of coordinates).
pub const MAX_COORDINATE: f64 = 1.0e6;

/// An OpenDRIVE road network.
#[derive(Debug, Clone, PartialEq)]
pub struct Network {
    /// The minor revision of OpenDRIVE 1.x the header declares.
    pub rev_minor: u32,
    /// Its roads, in file order.
    pub roads: Vec<Road>,
    /// Its junctions, in file order.
    pub junctions: Vec<Junction>,
}

/// A road.
#[derive(Debug, Clone, PartialEq)]
pub struct Road {
    /// Its id.
    pub id: String,
    /// Its length along the reference line, metres.
    pub length: f64,
    /// The junction it belongs to (a connecting road), or `None` (`junction="-1"`).
    pub junction: Option<String>,
    /// Whether traffic keeps left (`rule="LHT"`): its left lanes then go along s.
    pub left_hand: bool,
    /// What precedes its start.
    pub predecessor: Option<RoadLink>,
    /// What follows its end.
    pub successor: Option<RoadLink>,
    /// Its reference line.
    pub reference: Vec<Geometry>,
    /// Its lanes.
    pub lanes: Lanes,
    /// Its speed limits by road type (`<type><speed>`), `s` along it.
    pub speeds: Vec<Speed>,
    /// Its objects.
    pub objects: Vec<Object>,
    /// Where it is written.
    pub at: Location,
}

/// What a road's end meets.
#[derive(Debug, Clone, PartialEq)]
pub struct RoadLink {
    /// A road (with the end of it that meets this one) or a junction.
    pub element: Element,
    /// Its id.
    pub id: String,
    /// Where it is written.
    pub at: Location,
}

/// The kind of element a road link names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// A road, met at its start or end.
    Road(Contact),
    /// A junction.
    Junction,
}

impl Road {
    /// The lane section holding the end `contact` of the road.
    pub fn section_at(&self, contact: Contact) -> &LaneSection {
        match contact {
            Contact::Start => &self.lanes.sections[0],
            Contact::End => self.lanes.sections.last().expect("a road has a lane section"),
        }
    }

    /// What meets the end `contact` of the road.
    pub fn link_at(&self, contact: Contact) -> Option<&RoadLink> {
        match contact {
            Contact::Start => self.predecessor.as_ref(),
            Contact::End => self.successor.as_ref(),
        }
    }
}

/// Reads an OpenDRIVE file (1.4 to 1.8) and checks its references: every road
/// and junction a link names exists, every lane a lane link names exists in
/// the lane section it meets, and every road's reference line chains and
/// covers its length.
///
/// What is read and what is left out is documented in `docs/opendrive.md`.
pub fn parse_opendrive(text: &str) -> Result<Network, OpenDriveError> {
    let doc = xml::parse(text)?;
    let root = doc.root_element();
    if root.tag_name().name() != "OpenDRIVE" {
        return Err(xml::element_error(
            root,
            format!("expected <OpenDRIVE> as the root element, found {}", xml::tag(root)),
        ));
    }
    xml::allowed_children(
        root,
        &["header", "road", "junction"],
        &["controller", "junctionGroup", "station"],
    )?;
    let Some(header) = xml::child(root, "header") else {
        return Err(xml::element_error(
            root,
            "an OpenDRIVE file starts with its <header>".into(),
        ));
    };
    let rev_minor = revision(header)?;
    let locator = Locator::new(text);
    let roads = xml::children(root, "road")
        .map(|r| road(r, &locator))
        .collect::<Result<Vec<_>, _>>()?;
    let junctions = xml::children(root, "junction")
        .map(|j| junction(j, &locator))
        .collect::<Result<Vec<_>, _>>()?;
    let network = Network {
        rev_minor,
        roads,
        junctions,
    };
    check_references(&network)?;
    Ok(network)
}

/// The header's minor revision, which must be of OpenDRIVE 1.4 to 1.8.
fn revision(header: Node) -> Result<u32, OpenDriveError> {
    let major = xml::integer(header, "revMajor")?;
    let minor = xml::integer(header, "revMinor")?;
    if major != 1 || !(4..=8).contains(&minor) {
        return Err(xml::element_error(
            header,
            format!("OpenDRIVE {major}.{minor} is not supported; sightline reads OpenDRIVE 1.4 to 1.8"),
        ));
    }
    Ok(minor as u32)
}

/// One `<road>`.
fn road(node: Node, locator: &Locator) -> Result<Road, OpenDriveError> {
    xml::allowed_children(
        node,
        &["link", "type", "planView", "lanes", "objects"],
        &["elevationProfile", "lateralProfile", "signals", "surface", "railroad"],
    )?;
    let id = xml::string(node, "id")?.to_owned();
    let length_attribute = xml::attribute(node, "length")?;
    let length = xml::non_negative(node, "length")?;
    if length <= 0.0 || length > MAX_ROAD_LENGTH {
        return Err(xml::value_error(
            node,
            &length_attribute,
            format!(
                "road {id}: a length of {} m is out of range; expected > 0 and ≤ {MAX_ROAD_LENGTH} m",
                Number(length)
            ),
        ));
    }
    let junction = Some(xml::string(node, "junction")?)
        .filter(|j| *j != "-1")
        .map(str::to_owned);
    let left_hand = xml::choice(node, "rule", &["RHT", "LHT"])? == Some("LHT");
    let (mut predecessor, mut successor) = (None, None);
    if let Some(link) = xml::child(node, "link") {
        xml::allowed_children(link, &["predecessor", "successor"], &[])?;
        predecessor = xml::child(link, "predecessor")
            .map(|l| road_link(l, locator))
            .transpose()?;
        successor = xml::child(link, "successor")
            .map(|l| road_link(l, locator))
            .transpose()?;
    }
    let Some(plan) = xml::child(node, "planView") else {
        return Err(xml::element_error(node, format!("road {id} has no <planView>")));
    };
    let reference = plan_view(plan, locator)?;
    check_extent(&id, &reference, length)?;
    let Some(lanes_node) = xml::child(node, "lanes") else {
        return Err(xml::element_error(node, format!("road {id} has no <lanes>")));
    };
    let lanes = lanes(lanes_node, length, locator)?;
    let objects = match xml::child(node, "objects") {
        Some(list) => objects(list, locator)?,
        None => Vec::new(),
    };
    Ok(Road {
        id,
        length,
        junction,
        left_hand,
        predecessor,
        successor,
        reference,
        lanes,
        speeds: road_speeds(node)?,
        objects,
        at: locator.at(node),
    })
}

/// Checks that the reference line starts at s = 0, ends at the road's length
/// and stays within the world's coordinates.
fn check_extent(id: &str, reference: &[Geometry], length: f64) -> Result<(), OpenDriveError> {
    let first = &reference[0];
    let last = reference.last().expect("a plan view has a record");
    let end = last.s + last.length;
    let tolerance = CHAIN_TOLERANCE.max(1e-6 * length);
    let problem = if first.s.abs() > tolerance {
        Some((
            first.at,
            format!("road {id}: its reference line starts at s = {}, not 0", first.s),
        ))
    } else if (end - length).abs() > tolerance {
        Some((
            last.at,
            format!(
                "road {id}: its reference line ends at s = {} (s + length of the last record), but the road's length is {}",
                Number(end),
                Number(length)
            ),
        ))
    } else {
        reference
            .iter()
            .find(|g| g.start.position.iter().any(|c| c.abs() > MAX_COORDINATE) || g.length > MAX_ROAD_LENGTH)
            .map(|g| {
                (
                    g.at,
                    format!(
                        "road {id}: the record at s = {} lies beyond the world's coordinates (±{MAX_COORDINATE} m) or is \
                         longer than {MAX_ROAD_LENGTH} m",
                        g.s
                    ),
                )
            })
    };
    match problem {
        Some((location, message)) => Err(OpenDriveError { location, message }),
        None => Ok(()),
    }
}

/// A road's `<predecessor>` or `<successor>`.
fn road_link(node: Node, locator: &Locator) -> Result<RoadLink, OpenDriveError> {
    let element = match xml::choice(node, "elementType", &["road", "junction"])? {
        Some("junction") => Element::Junction,
        Some(_) => match contact(node)? {
            Some(contact) => Element::Road(contact),
            None => {
                return Err(xml::element_error(
                    node,
                    format!(
                        "a link to a road names its `contactPoint` (start or end) on {}",
                        xml::tag(node)
                    ),
                ));
            }
        },
        None => {
            return Err(xml::element_error(
                node,
                format!("missing attribute `elementType` on {}", xml::tag(node)),
            ));
        }
    };
    Ok(RoadLink {
        element,
        id: xml::string(node, "elementId")?.to_owned(),
        at: locator.at(node),
    })
}

/// An error at `at`.
fn error(at: Location, message: String) -> OpenDriveError {
    OpenDriveError { location: at, message }
}

/// Checks every reference between roads, junctions and lanes.
fn check_references(network: &Network) -> Result<(), OpenDriveError> {
    let mut roads: HashMap<&str, &Road> = HashMap::new();
    for road in &network.roads {
        if let Some(first) = roads.insert(&road.id, road) {
            return Err(error(
                road.at,
                format!("road id {} is used twice (first at {})", road.id, first.at),
            ));
        }
    }
    let mut junctions: HashMap<&str, &Junction> = HashMap::new();
    for junction in &network.junctions {
        if let Some(first) = junctions.insert(&junction.id, junction) {
            return Err(error(
                junction.at,
                format!("junction id {} is used twice (first at {})", junction.id, first.at),
            ));
        }
    }
    let road_named = |id: &str, at: Location, what: &str| {
        roads
            .get(id)
            .copied()
            .ok_or_else(|| error(at, format!("{what} names road {id}, which the file does not have")))
    };
    for road in &network.roads {
        if let Some(junction) = &road.junction
            && !junctions.contains_key(junction.as_str())
        {
            return Err(error(
                road.at,
                format!(
                    "road {} belongs to junction {junction}, which the file does not have",
                    road.id
                ),
            ));
        }
        for end in [Contact::Start, Contact::End] {
            let Some(link) = road.link_at(end) else { continue };
            let what = format!(
                "road {}'s {}",
                road.id,
                if end == Contact::Start {
                    "predecessor"
                } else {
                    "successor"
                }
            );
            match link.element {
                Element::Junction => {
                    if !junctions.contains_key(link.id.as_str()) {
                        return Err(error(
                            link.at,
                            format!("{what} names junction {}, which the file does not have", link.id),
                        ));
                    }
                }
                Element::Road(contact) => {
                    let other = road_named(&link.id, link.at, &what)?;
                    check_lane_links(road, end, other.section_at(contact), &other.id)?;
                }
            }
        }
        check_section_links(road)?;
    }
    for junction in &network.junctions {
        for connection in &junction.connections {
            let what = format!("junction {}'s connection", junction.id);
            let incoming = road_named(&connection.incoming, connection.at, &what)?;
            let target = road_named(&connection.target, connection.at, &what)?;
            let Some(end) = [Contact::End, Contact::Start].into_iter().find(|&end| {
                incoming
                    .link_at(end)
                    .is_some_and(|l| l.element == Element::Junction && l.id == junction.id)
            }) else {
                return Err(error(
                    connection.at,
                    format!(
                        "{what} comes from road {}, which does not link to junction {}",
                        incoming.id, junction.id
                    ),
                ));
            };
            let (from_section, to_section) = (incoming.section_at(end), target.section_at(connection.contact));
            for &(from, to, at) in &connection.lane_links {
                for (lane, section, road) in [(from, from_section, incoming), (to, to_section, target)] {
                    if section.lane(lane).is_none() {
                        return Err(error(
                            at,
                            format!(
                                "the lane link names lane {lane} of road {}, which has no such lane where it meets junction {}",
                                road.id, junction.id
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Checks the lane links at a road's end `end` that meets `other_id`'s section
/// `other`: each lane's successor (or predecessor at the start) must exist there.
fn check_lane_links(road: &Road, end: Contact, other: &LaneSection, other_id: &str) -> Result<(), OpenDriveError> {
    for lane in road.section_at(end).lanes() {
        let links = if end == Contact::End {
            &lane.successors
        } else {
            &lane.predecessors
        };
        for &(id, at) in links {
            if other.lane(id).is_none() {
                return Err(error(
                    at,
                    format!(
                        "lane {} of road {} links to lane {id} of road {other_id}, which has no such lane where they meet",
                        lane.id, road.id
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Checks the lane links between a road's consecutive lane sections.
fn check_section_links(road: &Road) -> Result<(), OpenDriveError> {
    for pair in road.lanes.sections.windows(2) {
        let [before, after] = [&pair[0], &pair[1]];
        for (section, other, links) in [
            (before, after, (|l: &super::lanes::Lane| &l.successors) as fn(&_) -> &_),
            (after, before, |l: &super::lanes::Lane| &l.predecessors),
        ] {
            for lane in section.lanes() {
                for &(id, at) in links(lane) {
                    if other.lane(id).is_none() {
                        return Err(error(
                            at,
                            format!(
                                "lane {} of road {} links to lane {id} of the neighbouring lane section (at s = {}), which has no such lane",
                                lane.id, road.id, other.s
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}
