//! SUMO additional and route files: polygons (buildings, parks), points of
//! interest and vehicle types.

use roxmltree::Node;

use super::vclass::vehicle_class;
use super::xml::{self, Locator, SumoError};
use crate::Location;
use crate::geometry::Xy;
use crate::raw::range::{BODY, COORDINATE, VEHICLE_LENGTH};

/// What an additional or route file holds that sightline reads.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Additional {
    /// The `<poly>` shapes, in file order.
    pub polygons: Vec<Polygon>,
    /// The points of interest (`<poi>`), in file order.
    pub pois: Vec<Poi>,
    /// The vehicle types (`<vType>`, in a `<vTypeDistribution>` too), in file order.
    pub vtypes: Vec<VType>,
    /// The top-level elements of an additional file sightline does not read
    /// (`<busStop>`, detectors, …): each name, how many, and where the first is.
    pub ignored: Vec<(String, usize, Location)>,
}

/// A `<poly>` shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    /// Its SUMO id.
    pub id: String,
    /// Its `type` (`building`, `park`, …), empty when absent.
    pub kind: String,
    /// Outline in network coordinates, metres, in file order, without a closing
    /// point equal to the first. SUMO also draws unfilled polygons as open lines,
    /// so it may have fewer than three points.
    pub shape: Vec<Xy>,
    /// Where the element starts.
    pub location: Location,
}

/// A point of interest (`<poi>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Poi {
    /// Its SUMO id.
    pub id: String,
    /// Its `type`, empty when absent.
    pub kind: String,
    /// Where it is.
    pub at: PoiAt,
    /// Its height above the ground, metres: the `<param key="height">` it
    /// carries (SUMO's own `height` attribute is the size of its image).
    pub height: Option<f64>,
    /// Where the element starts.
    pub location: Location,
}

/// Where a point of interest is.
#[derive(Debug, Clone, PartialEq)]
pub enum PoiAt {
    /// At `x`, `y`, network coordinates, metres.
    Point(Xy),
    /// On lane `lane`, `pos` metres from its start (negative: from its end) and
    /// `pos_lat` metres to its left.
    Lane {
        /// The lane's id.
        lane: String,
        /// Metres along the lane.
        pos: f64,
        /// Metres to the lane's left (SUMO's `posLat`).
        pos_lat: f64,
    },
}

/// A vehicle or person type (`<vType>`).
#[derive(Debug, Clone, PartialEq)]
pub struct VType {
    /// Its id, as FCD output names it.
    pub id: String,
    /// Its vehicle class, one SUMO knows; `None` when absent (SUMO then takes
    /// `passenger`).
    pub vclass: Option<&'static str>,
    /// Its length, metres, when given.
    pub length: Option<f64>,
    /// Its width, metres, when given.
    pub width: Option<f64>,
    /// Its `guiShape`, when given.
    pub gui_shape: Option<String>,
    /// Where the element starts.
    pub location: Location,
}

/// The top-level elements of an additional file that sightline reads or that
/// only hold what it reads.
const READ: [&str; 5] = ["poly", "poi", "vType", "vTypeDistribution", "location"];

/// Reads the polygons, points of interest and vehicle types of a SUMO
/// additional file (`<additional>`) or route file (`<routes>`).
///
/// A polygon needs `id` and `shape` (`x,y x,y …`; a height `x,y,z` is dropped);
/// a point of interest `id` and either `x` and `y` or `lane` and `pos`; a type
/// `id`, and its `vClass`, `length` and `width` are read when given. The
/// routes, vehicles and persons of a route file are not read (the FCD output
/// holds where they went); other elements of an additional file are listed in
/// [`Additional::ignored`].
///
/// Errors: malformed XML, another root element, a missing or bad attribute, a
/// polygon's point, a point of interest's `x` or `y` or its `posLat` beyond the
/// world's coordinates (±1e6 m), a vehicle class SUMO does not know, a type's
/// length outside (0, 10 000] m or width outside (0, 100] m, and shapes or
/// points in geographic coordinates (`geo="true"`, `lon`/`lat`): convert them
/// to network coordinates first, for example with SUMO's polyconvert.
pub fn parse_additional(text: &str) -> Result<Additional, SumoError> {
    let doc = xml::parse(text)?;
    let root = doc.root_element();
    let is_routes = match root.tag_name().name() {
        "additional" => false,
        "routes" => true,
        _ => {
            return Err(xml::element_error(
                root,
                format!(
                    "expected <additional> or <routes> as the root element, found {}",
                    xml::tag(root)
                ),
            ));
        }
    };
    let locator = Locator::new(text);
    let mut additional = Additional::default();
    for node in root.children().filter(Node::is_element) {
        match node.tag_name().name() {
            "poly" => additional.polygons.push(polygon(node, &locator)?),
            "poi" => additional.pois.push(poi(node, &locator)?),
            "vType" => additional.vtypes.push(vtype(node, &locator)?),
            "vTypeDistribution" => {
                for node in xml::children(node, "vType") {
                    additional.vtypes.push(vtype(node, &locator)?);
                }
            }
            name if is_routes || READ.contains(&name) => {}
            name => match additional.ignored.iter_mut().find(|(n, _, _)| n == name) {
                Some((_, count, _)) => *count += 1,
                None => additional.ignored.push((name.to_owned(), 1, locator.at(node))),
            },
        }
    }
    Ok(additional)
}

/// Whether a `geo` attribute says the coordinates are longitude and latitude.
fn is_geo<'a, 'i>(node: Node<'a, 'i>) -> Option<roxmltree::Attribute<'a, 'i>> {
    node.attribute_node("geo")
        .filter(|geo| matches!(geo.value(), "true" | "True" | "yes" | "on" | "1" | "x"))
}

/// One `<poly>`.
fn polygon(node: Node, locator: &Locator) -> Result<Polygon, SumoError> {
    let id = xml::string(node, "id")?;
    if let Some(geo) = is_geo(node) {
        let message = format!(
            "polygon `{id}` is in geo coordinates (longitude, latitude), which are not supported; \
             convert it to network coordinates"
        );
        return Err(xml::value_error(node, &geo, message));
    }
    let shape = xml::outline(node, "shape")?;
    Ok(Polygon {
        id: id.to_owned(),
        kind: node.attribute("type").unwrap_or_default().to_owned(),
        shape,
        location: locator.at(node),
    })
}

/// One `<poi>`.
fn poi(node: Node, locator: &Locator) -> Result<Poi, SumoError> {
    let id = xml::string(node, "id")?;
    if is_geo(node).is_some() || node.has_attribute("lon") || node.has_attribute("lat") {
        let message = format!(
            "point of interest `{id}` is in geo coordinates (longitude, latitude), which are not supported; \
             convert it to network coordinates"
        );
        return Err(xml::element_error(node, message));
    }
    let at = match node.attribute("lane") {
        Some(lane) => PoiAt::Lane {
            lane: lane.to_owned(),
            pos: xml::number(node, "pos")?,
            pos_lat: xml::optional_number_within(node, "posLat", COORDINATE)?.unwrap_or(0.0),
        },
        None => PoiAt::Point([
            xml::number_within(node, "x", COORDINATE)?,
            xml::number_within(node, "y", COORDINATE)?,
        ]),
    };
    let mut height = None;
    for param in xml::children(node, "param").filter(|p| p.attribute("key") == Some("height")) {
        let value = xml::number(param, "value")?;
        if value <= 0.0 {
            let attribute = xml::attribute(param, "value")?;
            let message = format!("the height of point of interest `{id}` is not positive: {value}");
            return Err(xml::value_error(param, &attribute, message));
        }
        height = Some(value);
    }
    Ok(Poi {
        id: id.to_owned(),
        kind: node.attribute("type").unwrap_or_default().to_owned(),
        at,
        height,
        location: locator.at(node),
    })
}

/// One `<vType>`.
fn vtype(node: Node, locator: &Locator) -> Result<VType, SumoError> {
    let id = xml::string(node, "id")?;
    let vclass = match node.attribute_node("vClass") {
        Some(attribute) => Some(vehicle_class(attribute.value()).map(|c| c.name).ok_or_else(|| {
            let message = format!(
                "type `{id}` has vehicle class {:?}, which SUMO does not know",
                attribute.value()
            );
            xml::value_error(node, &attribute, message)
        })?),
        None => None,
    };
    Ok(VType {
        id: id.to_owned(),
        vclass,
        length: xml::optional_number_within(node, "length", VEHICLE_LENGTH)?,
        width: xml::optional_number_within(node, "width", BODY)?,
        gui_shape: node.attribute("guiShape").map(str::to_owned),
        location: locator.at(node),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const POLYS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<additional>
    <poly id="b0" type="building" color="red" fill="1" layer="-1" shape="10,10 40,10 40,30 10,30 10,10"/>
    <poi id="tree" type="tree" x="50" y="50"/>
    <poly id="fence" geo="false" shape="0,0 5,0,1.5"/>
    <busStop id="s0" lane="a_0" startPos="0" endPos="10"/>
    <poi id="rsu_1" type="rsu" lane="a_0" pos="-5" posLat="3.5">
        <param key="height" value="6.5"/>
    </poi>
    <busStop id="s1" lane="a_0" startPos="20" endPos="30"/>
    <vTypeDistribution id="mix">
        <vType id="van" vClass="delivery" guiShape="delivery"/>
    </vTypeDistribution>
    <vType id="bike" vClass="bicycle" length="1.8" width="0.7"/>
</additional>
"#;

    fn error(text: &str) -> String {
        parse_additional(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_polygons_and_drops_the_closing_point() {
        let polygons = parse_additional(POLYS).unwrap().polygons;
        assert_eq!(
            polygons,
            [
                Polygon {
                    id: "b0".into(),
                    kind: "building".into(),
                    shape: vec![[10.0, 10.0], [40.0, 10.0], [40.0, 30.0], [10.0, 30.0]],
                    location: Location::new(3, 5),
                },
                Polygon {
                    id: "fence".into(),
                    kind: String::new(),
                    shape: vec![[0.0, 0.0], [5.0, 0.0]],
                    location: Location::new(5, 5),
                },
            ]
        );
    }

    #[test]
    fn reads_points_of_interest_with_their_height() {
        let pois = parse_additional(POLYS).unwrap().pois;
        assert_eq!(pois[0].at, PoiAt::Point([50.0, 50.0]));
        assert_eq!((pois[0].kind.as_str(), pois[0].height), ("tree", None));
        assert_eq!(
            pois[1].at,
            PoiAt::Lane {
                lane: "a_0".into(),
                pos: -5.0,
                pos_lat: 3.5
            }
        );
        assert_eq!((pois[1].id.as_str(), pois[1].height), ("rsu_1", Some(6.5)));
    }

    #[test]
    fn reads_vehicle_types_in_and_out_of_distributions() {
        let vtypes = parse_additional(POLYS).unwrap().vtypes;
        let summary: Vec<_> = vtypes
            .iter()
            .map(|t| (t.id.as_str(), t.vclass, t.length, t.width, t.gui_shape.as_deref()))
            .collect();
        assert_eq!(
            summary,
            [
                ("van", Some("delivery"), None, None, Some("delivery")),
                ("bike", Some("bicycle"), Some(1.8), Some(0.7), None),
            ]
        );
    }

    #[test]
    fn lists_the_elements_it_does_not_read() {
        let ignored = parse_additional(POLYS).unwrap().ignored;
        assert_eq!(ignored, [("busStop".to_string(), 2, Location::new(6, 5))]);
        let routes = "<routes><vType id=\"a\"/><vehicle id=\"v\" depart=\"0\"/></routes>";
        assert_eq!(parse_additional(routes).unwrap().ignored, []);
    }

    /// A building at 1e300 m was refused as enclosing no area; a point of
    /// interest there was read.
    #[test]
    fn positions_beyond_the_coordinate_range_are_errors_where_written() {
        let text = POLYS.replace("40,30 10,30", "40,30 1e300,30");
        assert_eq!(
            error(&text),
            "3:92: x of point \"1e300,30\" in attribute `shape` of <poly> must be a number from \
             -1000000 to 1000000 m, found 1e300"
        );
        let text = POLYS.replace(r#"x="50" y="50""#, r#"x="50" y="-2e6""#);
        assert_eq!(
            error(&text),
            "4:42: attribute `y` of <poi> must be a number from -1000000 to 1000000 m, found -2000000"
        );
        let text = POLYS.replace(r#"posLat="3.5""#, r#"posLat="1e300""#);
        assert_eq!(
            error(&text),
            "7:60: attribute `posLat` of <poi> must be a number from -1000000 to 1000000 m, found 1e300"
        );
    }

    #[test]
    fn errors_are_located() {
        let text = POLYS.replace(r#"<poly id="fence" "#, "<poly ");
        assert_eq!(error(&text), "5:5: missing attribute `id` on <poly>");
        let text = POLYS.replace("40,30 10,30", "40,30 10 30");
        assert_eq!(
            error(&text),
            "3:92: bad point \"10\" in attribute `shape` of <poly>; expected \"x,y\" with finite numbers"
        );
        let text = POLYS.replace(r#"geo="false""#, r#"geo="true""#);
        assert_eq!(
            error(&text),
            "5:27: polygon `fence` is in geo coordinates (longitude, latitude), which are not supported; \
             convert it to network coordinates"
        );
        assert_eq!(
            error("<additional>\n<poly id=\"a\" shape=\"1,1\">"),
            "2:26: malformed xml: the root node was opened but never closed"
        );
        let text = POLYS.replace(r#"vClass="bicycle""#, r#"vClass="e_bike""#);
        assert_eq!(
            error(&text),
            "14:30: type `bike` has vehicle class \"e_bike\", which SUMO does not know"
        );
        // A type's width is a body's, more than 0 and at most 100 m; its
        // length at most 10 km, as trains are long (a car 1e300 m long was
        // read, and the scenario passed).
        for (size, found) in [("0", "0"), ("100.5", "100.5"), ("1e300", "1e300")] {
            let text = POLYS.replace(r#"width="0.7""#, &format!(r#"width="{size}""#));
            assert_eq!(
                error(&text),
                format!("14:59: attribute `width` of <vType> must be a number > 0 and ≤ 100 m, found {found}")
            );
        }
        let text = POLYS.replace(r#"length="1.8""#, r#"length="1e9""#);
        assert_eq!(
            error(&text),
            "14:47: attribute `length` of <vType> must be a number > 0 and ≤ 10000 m, found 1000000000"
        );
        let text = POLYS.replace(r#"length="1.8""#, r#"length="200""#);
        assert_eq!(parse_additional(&text).unwrap().vtypes[1].length, Some(200.0));
        let text = POLYS.replace(r#"value="6.5""#, r#"value="high""#);
        assert_eq!(
            error(&text),
            "8:36: attribute `value` of <param> is not a number: \"high\""
        );
        let text = POLYS.replace(r#"x="50" y="50""#, r#"lon="9.1" lat="48.7""#);
        assert_eq!(
            error(&text),
            "4:5: point of interest `tree` is in geo coordinates (longitude, latitude), which are not \
             supported; convert it to network coordinates"
        );
        assert_eq!(
            error("<net/>"),
            "1:1: expected <additional> or <routes> as the root element, found <net>"
        );
    }
}
