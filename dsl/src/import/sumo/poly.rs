//! SUMO polygons (`.poly.xml` and other additional files): buildings, parks and
//! other shapes beside the roads.

use roxmltree::Node;

use super::xml::{self, SumoError};
use crate::geometry::Xy;

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
}

/// Reads the `<poly>` elements of a SUMO additional file
/// (`<additional><poly id type shape="x,y …"/>…</additional>`).
///
/// A polygon needs `id` and `shape` (`x,y x,y …`; a height `x,y,z` is dropped).
/// Points of interest (`<poi>`), other elements and other attributes are ignored.
///
/// Errors: malformed XML, a missing or bad attribute, and a polygon in
/// geographic coordinates (`geo="true"`): convert it to network coordinates
/// first, for example with SUMO's polyconvert.
pub fn parse_poly(text: &str) -> Result<Vec<Polygon>, SumoError> {
    let doc = xml::parse(text)?;
    let root = xml::root(&doc, "additional")?;
    xml::children(root, "poly").map(polygon).collect()
}

/// One `<poly>`.
fn polygon(node: Node) -> Result<Polygon, SumoError> {
    let id = xml::string(node, "id")?;
    if let Some(geo) = node.attribute_node("geo")
        && matches!(geo.value(), "true" | "True" | "yes" | "on" | "1" | "x")
    {
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
</additional>
"#;

    fn error(text: &str) -> String {
        parse_poly(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_polygons_and_drops_the_closing_point() {
        let polygons = parse_poly(POLYS).unwrap();
        assert_eq!(
            polygons,
            [
                Polygon {
                    id: "b0".into(),
                    kind: "building".into(),
                    shape: vec![[10.0, 10.0], [40.0, 10.0], [40.0, 30.0], [10.0, 30.0]],
                },
                Polygon {
                    id: "fence".into(),
                    kind: String::new(),
                    shape: vec![[0.0, 0.0], [5.0, 0.0]],
                },
            ]
        );
    }

    #[test]
    fn polygon_errors_are_located() {
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
    }
}
