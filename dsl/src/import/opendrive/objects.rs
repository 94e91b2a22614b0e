//! A road's objects (`<objects><object>`): buildings, crosswalks and the
//! rest, each with its footprint as an outline, a box or a circle in road
//! coordinates. Every offset and size is held to the world's coordinate range
//! (±1e6 m) where it is written: beyond it, turning a corner into the map's
//! frame loses the object's own extent to rounding.

use roxmltree::Node;

use super::geometry::Pose;
use super::xml::{self, Locator, OpenDriveError};
use crate::Location;
use crate::geometry::Xy;
use crate::raw::range::COORDINATE;

/// A circular object's outline has this many corners.
const CIRCLE_CORNERS: usize = 16;

/// An object beside or on a road.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// Its id.
    pub id: String,
    /// Its `type` (`building`, `crosswalk`, …; `none` when absent).
    pub kind: String,
    /// Where along the road its origin lies, metres.
    pub s: f64,
    /// How far left of the reference line its origin lies, metres.
    pub t: f64,
    /// Its heading relative to the reference line's at `s`, radians.
    pub heading: f64,
    /// Its footprint.
    pub footprint: Footprint,
    /// Whether it is repeated along the road (`<repeat>`).
    pub repeated: bool,
    /// Where it is written.
    pub at: Location,
}

/// An object's footprint in the plane.
#[derive(Debug, Clone, PartialEq)]
pub enum Footprint {
    /// Its outlines (`<outline>`), each with whether it encloses an area
    /// (`closed`, default true) and its corners.
    Outlines(Vec<(bool, Corners)>),
    /// A box of `length` along its heading and `width` across, centred on its origin.
    Box {
        /// Along its heading, metres.
        length: f64,
        /// Across, metres.
        width: f64,
    },
    /// A circle about its origin.
    Circle {
        /// Radius, metres.
        radius: f64,
    },
    /// None given: a point.
    Point,
}

/// The corners of an outline.
#[derive(Debug, Clone, PartialEq)]
pub enum Corners {
    /// `<cornerLocal u v>`: in the object's frame (u along its heading).
    Local(Vec<Xy>),
    /// `<cornerRoad s t>`: in road coordinates.
    Road(Vec<Xy>),
}

/// Reads a road's `<objects>`.
pub(crate) fn objects(node: Node, locator: &Locator) -> Result<Vec<Object>, OpenDriveError> {
    xml::allowed_children(node, &["object"], &["objectReference", "tunnel", "bridge"])?;
    xml::children(node, "object").map(|o| object(o, locator)).collect()
}

/// One `<object>`.
fn object(node: Node, locator: &Locator) -> Result<Object, OpenDriveError> {
    xml::allowed_children(
        node,
        &["outline", "outlines", "repeat"],
        &[
            "material",
            "validity",
            "parkingSpace",
            "markings",
            "borders",
            "surface",
            "skeleton",
        ],
    )?;
    let mut outlines = Vec::new();
    let wrapped = xml::children(node, "outlines").flat_map(|o| xml::children(o, "outline"));
    for outline in xml::children(node, "outline").chain(wrapped) {
        outlines.push(read_outline(outline)?);
    }
    for wrapper in xml::children(node, "outlines") {
        xml::allowed_children(wrapper, &["outline"], &[])?;
    }
    let footprint = if !outlines.is_empty() {
        Footprint::Outlines(outlines)
    } else if let Some(radius) = xml::optional_number_within(node, "radius", COORDINATE)?.filter(|&r| r > 0.0) {
        Footprint::Circle { radius }
    } else {
        match (
            xml::optional_number_within(node, "length", COORDINATE)?,
            xml::optional_number_within(node, "width", COORDINATE)?,
        ) {
            (Some(length), Some(width)) if length > 0.0 && width > 0.0 => Footprint::Box { length, width },
            _ => Footprint::Point,
        }
    };
    Ok(Object {
        id: xml::string(node, "id")?.to_owned(),
        kind: node.attribute("type").unwrap_or("none").to_owned(),
        s: xml::non_negative(node, "s")?,
        t: xml::number_within(node, "t", COORDINATE)?,
        heading: xml::number_or(node, "hdg", 0.0)?,
        footprint,
        repeated: xml::child(node, "repeat").is_some(),
        at: locator.at(node),
    })
}

/// One `<outline>`: local or road corners, not both.
fn read_outline(node: Node) -> Result<(bool, Corners), OpenDriveError> {
    xml::allowed_children(node, &["cornerLocal", "cornerRoad"], &[])?;
    let closed = xml::choice(node, "closed", &["true", "false"])? != Some("false");
    let local: Vec<Xy> = xml::children(node, "cornerLocal")
        .map(|c| {
            Ok([
                xml::number_within(c, "u", COORDINATE)?,
                xml::number_within(c, "v", COORDINATE)?,
            ])
        })
        .collect::<Result<_, OpenDriveError>>()?;
    let road: Vec<Xy> = xml::children(node, "cornerRoad")
        .map(|c| Ok([xml::number(c, "s")?, xml::number_within(c, "t", COORDINATE)?]))
        .collect::<Result<_, OpenDriveError>>()?;
    match (local.is_empty(), road.is_empty()) {
        (false, true) => Ok((closed, Corners::Local(local))),
        (true, false) => Ok((closed, Corners::Road(road))),
        (true, true) => Err(xml::element_error(node, "an <outline> has no corners".into())),
        (false, false) => Err(xml::element_error(
            node,
            "an <outline> mixes <cornerLocal> and <cornerRoad>; OpenDRIVE allows one kind per outline".into(),
        )),
    }
}

impl Object {
    /// The areas it covers, in the map's frame, each a polygon of three
    /// corners or more: its closed outlines, or its box or circle. `origin`
    /// is the reference line's pose at its `s`, `pose` the reference line's
    /// pose at any s (for road corners). An open outline (`closed="false"`, a
    /// fence) or a point covers no area.
    pub fn areas(&self, origin: Pose, pose: impl Fn(f64) -> Pose) -> Vec<Vec<Xy>> {
        let centre = origin.left(self.t);
        let heading = origin.heading + self.heading;
        let (sin, cos) = heading.sin_cos();
        let local = |[u, v]: Xy| [centre[0] + u * cos - v * sin, centre[1] + u * sin + v * cos];
        match &self.footprint {
            Footprint::Outlines(outlines) => outlines
                .iter()
                .filter(|(closed, _)| *closed)
                .map(|(_, corners)| match corners {
                    Corners::Local(points) => points.iter().map(|&p| local(p)).collect(),
                    Corners::Road(points) => points.iter().map(|&[s, t]| pose(s).left(t)).collect(),
                })
                .filter(|polygon: &Vec<Xy>| polygon.len() >= 3)
                .collect(),
            Footprint::Box { length, width } => {
                let (l, w) = (length / 2.0, width / 2.0);
                vec![[[-l, -w], [l, -w], [l, w], [-l, w]].map(local).to_vec()]
            }
            Footprint::Circle { radius } => vec![
                (0..CIRCLE_CORNERS)
                    .map(|i| {
                        let angle = std::f64::consts::TAU * i as f64 / CIRCLE_CORNERS as f64;
                        local([radius * angle.cos(), radius * angle.sin()])
                    })
                    .collect(),
            ],
            Footprint::Point => Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn read(text: &str) -> Result<Vec<Object>, String> {
        let doc = xml::parse(text).unwrap();
        objects(doc.root_element(), &Locator::new(text)).map_err(|e| e.to_string())
    }

    /// A reference line along +x from the origin.
    fn along_x(s: f64) -> Pose {
        Pose {
            position: [s, 0.0],
            heading: 0.0,
        }
    }

    #[test]
    fn local_outlines_turn_with_the_object_and_road_corners_follow_the_road() {
        let objects = read(
            r#"<objects>
  <object id="b1" type="building" s="10" t="-8" hdg="1.5707963267948966" zOffset="0">
    <outlines><outline id="0"><cornerLocal u="0" v="0" z="0"/><cornerLocal u="4" v="0" z="0"/><cornerLocal u="4" v="2" z="0"/></outline></outlines>
  </object>
  <object id="c1" type="crosswalk" s="30" t="0"><outline><cornerRoad s="29" t="-3" dz="0"/><cornerRoad s="31" t="-3" dz="0"/><cornerRoad s="31" t="3" dz="0"/><cornerRoad s="29" t="3" dz="0"/></outline></object>
  <object id="f1" type="barrier" s="0" t="0"><outline closed="false"><cornerLocal u="0" v="0"/><cornerLocal u="1" v="0"/><cornerLocal u="1" v="1"/></outline></object>
  <object id="p1" type="pole" s="5" t="2" radius="1"/>
</objects>"#,
        )
        .unwrap();
        let building = objects[0].areas(along_x(10.0), along_x);
        // Turned a quarter left: u runs north, v west, from (10, −8).
        let expected = [[10.0, -8.0], [10.0, -4.0], [8.0, -4.0]];
        for (point, want) in building[0].iter().zip(expected) {
            assert_relative_eq!(point[0], want[0], epsilon = 1e-12);
            assert_relative_eq!(point[1], want[1], epsilon = 1e-12);
        }
        assert_eq!(
            objects[1].areas(along_x(30.0), along_x)[0],
            [[29.0, -3.0], [31.0, -3.0], [31.0, 3.0], [29.0, 3.0]]
        );
        assert!(
            objects[2].areas(along_x(0.0), along_x).is_empty(),
            "an open outline covers no area"
        );
        let pole = &objects[3].areas(along_x(5.0), along_x)[0];
        assert_eq!(pole.len(), CIRCLE_CORNERS);
        assert_relative_eq!(pole[0][0], 6.0);
        assert_relative_eq!(pole[4][1], 3.0, epsilon = 1e-12);
    }

    #[test]
    fn offsets_and_sizes_beyond_the_coordinate_range_are_refused_where_written() {
        let object = |attributes: &str, corner: &str| {
            read(&format!(
                r#"<objects><object id="x" s="0" t="0" {attributes}><outline>{corner}</outline></object></objects>"#
            ))
        };
        let corner = r#"<cornerLocal u="0" v="0"/>"#;
        assert_eq!(
            object("", r#"<cornerLocal u="1e100" v="-3.5"/>"#).unwrap_err(),
            "1:63: attribute `u` of <cornerLocal> must be a number from -1000000 to 1000000 m, found 1e100"
        );
        assert_eq!(
            object("", r#"<cornerRoad s="0" t="-2e6"/>"#).unwrap_err(),
            "1:68: attribute `t` of <cornerRoad> must be a number from -1000000 to 1000000 m, found -2000000"
        );
        assert_eq!(
            read(r#"<objects><object id="x" s="0" t="1e7"/></objects>"#).unwrap_err(),
            "1:34: attribute `t` of <object> must be a number from -1000000 to 1000000 m, found 10000000"
        );
        assert_eq!(
            read(r#"<objects><object id="x" s="0" t="0" radius="1e300"/></objects>"#).unwrap_err(),
            "1:45: attribute `radius` of <object> must be a number from -1000000 to 1000000 m, found 1e300"
        );
        assert!(object(r#"length="1e6" width="-1e6""#, corner).is_ok());
    }

    #[test]
    fn outlines_must_have_one_kind_of_corner() {
        assert_eq!(
            read(r#"<objects><object id="x" s="0" t="0"><outline><cornerLocal u="0" v="0"/><cornerRoad s="0" t="1"/></outline></object></objects>"#)
                .unwrap_err(),
            "1:37: an <outline> mixes <cornerLocal> and <cornerRoad>; OpenDRIVE allows one kind per outline"
        );
    }
}
