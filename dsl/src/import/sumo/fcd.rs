//! SUMO floating car data (`sumo --fcd-output`): every vehicle's and person's
//! position, heading and speed at every time step.

use std::collections::HashMap;

use roxmltree::{Document, Node};

use super::xml::{self, Locator, SumoError};
use crate::Location;
use crate::geometry::Xy;
use crate::raw::range;

/// A trace read from SUMO FCD output.
#[derive(Debug, Clone, PartialEq)]
pub struct Fcd {
    /// Every vehicle and person, in order of first appearance.
    pub objects: Vec<FcdObject>,
    /// Every `<timestep>`, empty ones too, in time order: what times the trace
    /// covers, with road users or without.
    pub timesteps: Vec<Timestep>,
}

/// A `<timestep>` of the trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timestep {
    /// Simulation time, seconds.
    pub time: f64,
    /// Where it is in the file.
    pub location: Location,
}

/// One vehicle or person and its samples.
#[derive(Debug, Clone, PartialEq)]
pub struct FcdObject {
    /// Its SUMO id.
    pub id: String,
    /// Whether it is a `<person>` (else a `<vehicle>`).
    pub is_person: bool,
    /// The SUMO type id at its first sample (`type`), empty when the file has none.
    pub vtype: String,
    /// Its samples, in time order.
    pub samples: Vec<FcdSample>,
    /// Where its first sample is in the file.
    pub location: Location,
}

/// Where an object was at one time step.
#[derive(Debug, Clone, PartialEq)]
pub struct FcdSample {
    /// Simulation time, seconds.
    pub time: f64,
    /// Position in network coordinates, metres: for a vehicle, the centre of
    /// its front bumper.
    pub position: Xy,
    /// Heading, radians counter-clockwise from +x, in (−π, π].
    pub heading: f64,
    /// Speed, m/s.
    pub speed: f64,
    /// The lane it is on (vehicles only, when the file has `lane`).
    pub lane: Option<String>,
}

/// Reads SUMO FCD output (`<fcd-export><timestep time=…><vehicle …/><person …/>`).
///
/// Each `<vehicle>` and `<person>` needs `id`, `x`, `y`, `angle` and `speed`;
/// `type` and `lane` are optional and other attributes and elements
/// (`<container>`, for one) are ignored. SUMO's `angle` (degrees, 0 = north,
/// clockwise) becomes a heading in radians, counter-clockwise from +x.
///
/// A person riding a vehicle is inside it, so such a sample is skipped when the
/// file says so: with `vehicle` among `--fcd-output.attributes`, SUMO writes the
/// vehicle's id for riders and `vehicle=""` for people on foot. SUMO's default
/// attributes leave it out, and a rider then reads as a pedestrian at its
/// vehicle's position.
///
/// Errors: malformed XML, a missing or non-finite attribute, an `x` or `y`
/// beyond the world's coordinates (±1e6 m), a `speed` outside a scenario's
/// speed range (0 to 150 m/s), timesteps out of time order or two
/// at one time, an id twice in one timestep or used by both a vehicle and a
/// person, and geographic
/// coordinates: `lon`/`lat` attributes, or a file whose header records
/// `--fcd-output.geo` or `--fcd-output.utm` (x and y are then not network
/// coordinates). Without SUMO's header, such coordinates go undetected.
pub fn parse_fcd(text: &str) -> Result<Fcd, SumoError> {
    let doc = xml::parse(text)?;
    reject_projected_output(&doc)?;
    let root = xml::root(&doc, "fcd-export")?;
    let locator = Locator::new(text);
    let mut objects: Vec<FcdObject> = Vec::new();
    // Each id's index in `objects`, and whether it was a <person>.
    let mut seen: HashMap<&str, (usize, bool)> = HashMap::new();
    let mut timesteps: Vec<Timestep> = Vec::new();
    for step in xml::children(root, "timestep") {
        let time = xml::number(step, "time")?;
        if let Some(previous) = timesteps.last().map(|t| t.time).filter(|&previous| time <= previous) {
            let attribute = xml::attribute(step, "time")?;
            let message = match time < previous {
                true => format!("time {time} is earlier than the previous timestep's {previous}"),
                false => format!("time {time} is the previous timestep's too; each timestep is at its own time"),
            };
            return Err(xml::value_error(step, &attribute, message));
        }
        timesteps.push(Timestep {
            time,
            location: locator.at(step),
        });
        for node in step.children().filter(Node::is_element) {
            let is_person = match node.tag_name().name() {
                "vehicle" => false,
                "person" => true,
                _ => continue,
            };
            let id = xml::string(node, "id")?;
            if node.has_attribute("lon") || node.has_attribute("lat") {
                let message = format!(
                    "{} has geo coordinates (`lon`, `lat`), which are not supported; rerun sumo without --fcd-output.geo",
                    xml::tag(node)
                );
                return Err(xml::element_error(node, message));
            }
            if is_person && node.attribute("vehicle").is_some_and(|vehicle| !vehicle.is_empty()) {
                continue;
            }
            let sample = sample(node, time)?;
            match seen.get(id) {
                Some(&(index, was_person)) if was_person == is_person => {
                    let samples = &mut objects[index].samples;
                    if samples.last().is_some_and(|last| last.time == time) {
                        let message = format!("`{id}` appears twice in the timestep at time {time}");
                        return Err(xml::element_error(node, message));
                    }
                    samples.push(sample);
                }
                Some(_) => {
                    let message = format!("`{id}` appears as both a <vehicle> and a <person>");
                    return Err(xml::element_error(node, message));
                }
                None => {
                    let vtype = node.attribute("type").unwrap_or_default();
                    seen.insert(id, (objects.len(), is_person));
                    objects.push(FcdObject {
                        id: id.to_owned(),
                        is_person,
                        vtype: vtype.to_owned(),
                        samples: vec![sample],
                        location: locator.at(node),
                    });
                }
            }
        }
    }
    Ok(Fcd { objects, timesteps })
}

/// One `<vehicle>` or `<person>` at `time`.
fn sample(node: Node, time: f64) -> Result<FcdSample, SumoError> {
    Ok(FcdSample {
        time,
        position: [
            xml::number_within(node, "x", range::COORDINATE)?,
            xml::number_within(node, "y", range::COORDINATE)?,
        ],
        heading: heading(xml::number(node, "angle")?),
        speed: xml::number_within(node, "speed", range::SPEED)?,
        lane: node.attribute("lane").map(str::to_owned),
    })
}

/// SUMO's angle (degrees, 0 = north, clockwise) as a heading (radians,
/// counter-clockwise from +x) in (−π, π].
fn heading(angle: f64) -> f64 {
    // Normalise in degrees, where the quarter turns are exact.
    let degrees = 180.0 - (180.0 - (90.0 - angle)).rem_euclid(360.0);
    degrees.to_radians()
}

/// SUMO records its options in a comment before the root element; reject output
/// whose x and y are not network coordinates.
fn reject_projected_output(doc: &Document) -> Result<(), SumoError> {
    const OPTIONS: [(&str, &str); 2] = [
        ("fcd-output.geo", "longitude and latitude"),
        ("fcd-output.utm", "unshifted UTM coordinates"),
    ];
    for comment in doc.root().children().filter(Node::is_comment) {
        let text = comment.text().unwrap_or_default();
        for (option, meaning) in OPTIONS {
            if let Some(offset) = text.find(&format!("<{option} value=\"true\"/>")) {
                let message = format!(
                    "the file was written with --{option}, so x and y are {meaning}, which are not supported; \
                     rerun sumo without --{option}"
                );
                // The comment's text starts after its "<!--".
                return Err(xml::error_at_pos(comment, comment.range().start + 4 + offset, message));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI};

    use approx::assert_relative_eq;

    use super::*;

    const TRACE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fcd-export xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
    <timestep time="0.00">
        <vehicle id="v0" x="10.00" y="1.60" angle="90.00" type="truck" speed="12.50" pos="3.0" lane="A0B0_0" slope="0.00"/>
        <person id="p0" x="2.00" y="5.00" angle="0.00" type="DEFAULT_PEDTYPE" speed="1.20" edge="A0A1"/>
    </timestep>
    <timestep time="0.10">
        <vehicle id="v0" x="11.25" y="1.60" angle="90.00" type="truck" speed="12.50" lane="A0B0_0"/>
        <vehicle id="v1" x="50.00" y="-1.60" angle="270.00" speed="8.00"/>
        <person id="p0" x="2.00" y="5.12" angle="0.00" type="DEFAULT_PEDTYPE" speed="1.20" vehicle=""/>
        <container id="c0" x="0" y="0" angle="0" speed="0"/>
    </timestep>
    <timestep time="0.20">
        <person id="p0" x="11.25" y="1.60" angle="90.00" speed="12.50" vehicle="v0"/>
    </timestep>
</fcd-export>
"#;

    fn error(text: &str) -> String {
        parse_fcd(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_vehicles_and_people_in_order_of_first_appearance() {
        let fcd = parse_fcd(TRACE).unwrap();
        let summary: Vec<_> = fcd
            .objects
            .iter()
            .map(|o| (o.id.as_str(), o.is_person, o.vtype.as_str(), o.samples.len()))
            .collect();
        assert_eq!(
            summary,
            [
                ("v0", false, "truck", 2),
                ("p0", true, "DEFAULT_PEDTYPE", 2),
                ("v1", false, "", 1),
            ]
        );
        let second = &fcd.objects[0].samples[1];
        assert_eq!(second.time, 0.1);
        assert_eq!(second.position, [11.25, 1.6]);
        assert_relative_eq!(second.heading, 0.0);
        assert_eq!(second.speed, 12.5);
        assert_eq!(second.lane.as_deref(), Some("A0B0_0"));
        let walker = &fcd.objects[1].samples[0];
        assert_relative_eq!(walker.heading, FRAC_PI_2);
        assert_eq!(walker.lane, None);
    }

    #[test]
    fn a_person_riding_a_vehicle_has_no_sample() {
        let fcd = parse_fcd(TRACE).unwrap();
        let times: Vec<f64> = fcd.objects[1].samples.iter().map(|s| s.time).collect();
        assert_eq!(times, [0.0, 0.1]);
    }

    #[test]
    fn sumo_angles_become_counter_clockwise_headings_from_x() {
        assert_relative_eq!(heading(0.0), FRAC_PI_2);
        assert_relative_eq!(heading(90.0), 0.0);
        assert_relative_eq!(heading(180.0), -FRAC_PI_2);
        assert_relative_eq!(heading(270.0), PI);
        assert_relative_eq!(heading(-90.0), PI);
        assert_relative_eq!(heading(45.0), PI / 4.0);
        assert_relative_eq!(heading(315.0), 3.0 * PI / 4.0);
        assert_relative_eq!(heading(450.0), 0.0);
    }

    #[test]
    fn a_missing_attribute_is_an_error_at_the_element() {
        let text = TRACE.replace(r#"<vehicle id="v1" x="50.00" "#, r#"<vehicle id="v1" "#);
        assert_eq!(error(&text), "9:9: missing attribute `x` on <vehicle>");
        let text = TRACE.replace(r#" angle="270.00""#, "");
        assert_eq!(error(&text), "9:9: missing attribute `angle` on <vehicle>");
    }

    #[test]
    fn a_bad_number_is_an_error_at_the_value() {
        let text = TRACE.replace(r#"speed="8.00""#, r#"speed="abc""#);
        assert_eq!(
            error(&text),
            "9:68: attribute `speed` of <vehicle> is not a number: \"abc\""
        );
        let text = TRACE.replace(r#"y="-1.60""#, r#"y="NaN""#);
        assert_eq!(
            error(&text),
            "9:39: attribute `y` of <vehicle> is not a finite number: \"NaN\""
        );
    }

    #[test]
    fn time_must_not_go_back() {
        let text = TRACE.replace(r#"time="0.20""#, r#"time="0.05""#);
        assert_eq!(
            error(&text),
            "13:21: time 0.05 is earlier than the previous timestep's 0.1"
        );
    }

    #[test]
    fn geo_coordinates_are_rejected() {
        let text = TRACE.replace(r#"x="50.00" y="-1.60""#, r#"lon="9.0026" lat="48.7530""#);
        assert_eq!(
            error(&text),
            "9:9: <vehicle> has geo coordinates (`lon`, `lat`), which are not supported; \
             rerun sumo without --fcd-output.geo"
        );
    }

    #[test]
    fn a_header_recording_fcd_output_geo_is_rejected() {
        let header = "<!-- generated by Eclipse SUMO sumo 1.28.0\n<sumoConfiguration>\n    <output>\n        \
                      <fcd-output.geo value=\"true\"/>\n    </output>\n</sumoConfiguration>\n-->\n";
        let text = TRACE.replace("<fcd-export", &format!("{header}<fcd-export"));
        assert_eq!(
            error(&text),
            "5:9: the file was written with --fcd-output.geo, so x and y are longitude and latitude, \
             which are not supported; rerun sumo without --fcd-output.geo"
        );
    }

    /// Each of these changed verdicts: a road user twice in one timestep, or
    /// one timestep twice, held two positions at one time; a speed of −5 or
    /// 1e300 m/s was taken as measured.
    #[test]
    fn a_road_user_twice_at_one_time_and_speeds_out_of_range_are_errors() {
        let text = TRACE.replace(
            r#"<vehicle id="v1" x="50.00""#,
            r#"<vehicle id="v0" x="12.00" y="1.60" angle="90.00" speed="12.50"/>
        <vehicle id="v1" x="50.00""#,
        );
        assert_eq!(error(&text), "9:9: `v0` appears twice in the timestep at time 0.1");
        let text = TRACE.replace(r#"time="0.20""#, r#"time="0.10""#);
        assert_eq!(
            error(&text),
            "13:21: time 0.1 is the previous timestep's too; each timestep is at its own time"
        );
        for (speed, found) in [("-5", "-5"), ("150.01", "150.01"), ("1e300", "1e300")] {
            let text = TRACE.replace(r#"speed="8.00""#, &format!(r#"speed="{speed}""#));
            assert_eq!(
                error(&text),
                format!("9:68: attribute `speed` of <vehicle> must be a number from 0 to 150 m/s, found {found}")
            );
        }
    }

    /// A road user at `x="1e300"` was taken as far away, and the scenario
    /// passed without it.
    #[test]
    fn positions_beyond_the_coordinate_range_are_errors_at_the_value() {
        for (x, y, at, found) in [
            ("1e300", "-1.60", "9:29 attribute `x`", "1e300"),
            ("-1000000.5", "-1.60", "9:29 attribute `x`", "-1000000.5"),
            ("50.00", "2e6", "9:39 attribute `y`", "2000000"),
        ] {
            let text = TRACE.replace(r#"x="50.00" y="-1.60""#, &format!(r#"x="{x}" y="{y}""#));
            let (position, attribute) = at.split_once(' ').unwrap();
            assert_eq!(
                error(&text),
                format!(
                    "{position}: {attribute} of <vehicle> must be a number from -1000000 to 1000000 m, found {found}"
                )
            );
        }
        let text = TRACE.replace(r#"x="50.00" y="-1.60""#, r#"x="-1e6" y="1e6""#);
        assert_eq!(parse_fcd(&text).unwrap().objects[2].samples[0].position, [-1e6, 1e6]);
    }

    #[test]
    fn an_id_cannot_be_both_vehicle_and_person() {
        let text = TRACE.replace(r#"<vehicle id="v1""#, r#"<vehicle id="p0""#);
        assert_eq!(error(&text), "9:9: `p0` appears as both a <vehicle> and a <person>");
    }

    #[test]
    fn malformed_xml_and_other_files_are_errors() {
        let text = TRACE.replace(
            "</timestep>\n    <timestep time=\"0.10\">",
            "\n    <timestep time=\"0.10\">",
        );
        assert_eq!(
            error(&text),
            "16:1: malformed xml: expected 'timestep' tag, not 'fcd-export'"
        );
        assert_eq!(
            error("<net/>"),
            "1:1: expected <fcd-export> as the root element, found <net>"
        );
    }
}
