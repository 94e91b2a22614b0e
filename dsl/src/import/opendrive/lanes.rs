//! A road's lanes (`<lanes>`): the lane offset, the lane sections with each
//! lane's type, width polynomials, links and speed limits, and the road's own
//! speed limits (`<type><speed>`).

use roxmltree::Node;

use super::xml::{self, Locator, OpenDriveError};
use crate::Location;
use crate::import::xml::Number;
use crate::raw::range;

/// A cubic in s: a + b·ds + c·ds² + d·ds³ with ds = s − `s`, valid from `s` to
/// the next record's `s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Poly3 {
    /// Where the record starts, metres (along the road for a lane offset,
    /// from the lane section's start for a width).
    pub s: f64,
    /// a, b, c, d.
    pub k: [f64; 4],
}

/// The value at `s` of the records valid there (the first one before it).
pub(crate) fn value_at(records: &[Poly3], s: f64) -> f64 {
    let i = records.partition_point(|r| r.s <= s).max(1) - 1;
    records.get(i).map_or(0.0, |r| {
        let ds = s - r.s;
        r.k[0] + ds * (r.k[1] + ds * (r.k[2] + ds * r.k[3]))
    })
}

/// Whether the records are linear in s (no c or d term): evaluating them at a
/// segment's ends then gives the straight line between.
pub(crate) fn linear(records: &[Poly3]) -> bool {
    records.iter().all(|r| r.k[2] == 0.0 && r.k[3] == 0.0)
}

/// What road users a lane carries, by its `type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaneUse {
    /// Vehicles: `driving`, ramps, `entry`, `exit`, `bidirectional`,
    /// `slipLane`, `bus`, `taxi`, `HOV`, `mwyEntry`, `mwyExit`.
    Drive,
    /// Pedestrians: `sidewalk`, `walking`.
    Walk,
    /// Neither (`shoulder`, `border`, `parking`, `biking`, `median`, …): the
    /// lane takes its width but no road user travels along it.
    Other,
}

/// The lane types of OpenDRIVE 1.8, with what each carries.
const LANE_TYPES: [(&str, LaneUse); 31] = [
    ("driving", LaneUse::Drive),
    ("entry", LaneUse::Drive),
    ("exit", LaneUse::Drive),
    ("onRamp", LaneUse::Drive),
    ("offRamp", LaneUse::Drive),
    ("connectingRamp", LaneUse::Drive),
    ("bidirectional", LaneUse::Drive),
    ("slipLane", LaneUse::Drive),
    ("bus", LaneUse::Drive),
    ("taxi", LaneUse::Drive),
    ("HOV", LaneUse::Drive),
    ("mwyEntry", LaneUse::Drive),
    ("mwyExit", LaneUse::Drive),
    ("sidewalk", LaneUse::Walk),
    ("walking", LaneUse::Walk),
    ("shoulder", LaneUse::Other),
    ("border", LaneUse::Other),
    ("stop", LaneUse::Other),
    ("none", LaneUse::Other),
    ("restricted", LaneUse::Other),
    ("parking", LaneUse::Other),
    ("median", LaneUse::Other),
    ("biking", LaneUse::Other),
    ("curb", LaneUse::Other),
    ("special1", LaneUse::Other),
    ("special2", LaneUse::Other),
    ("special3", LaneUse::Other),
    ("roadWorks", LaneUse::Other),
    ("tram", LaneUse::Other),
    ("rail", LaneUse::Other),
    ("shared", LaneUse::Other),
];

/// Which way a lane's traffic goes relative to its side's (`direction`, 1.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaneDirection {
    /// Its side's: along s on the right in right-hand traffic.
    Standard,
    /// Against its side's.
    Reversed,
    /// Both ways.
    Both,
}

/// A road's lanes.
#[derive(Debug, Clone, PartialEq)]
pub struct Lanes {
    /// The lane offset records (`<laneOffset>`): how far left of the reference
    /// line the centre lane lies, metres.
    pub offsets: Vec<Poly3>,
    /// The lane sections, in order of s; the first starts at 0.
    pub sections: Vec<LaneSection>,
}

/// A stretch of road with one set of lanes.
#[derive(Debug, Clone, PartialEq)]
pub struct LaneSection {
    /// Where it starts along the road, metres.
    pub s: f64,
    /// Its left lanes, ids 1, 2, … from the centre out.
    pub left: Vec<Lane>,
    /// Its right lanes, ids −1, −2, … from the centre out.
    pub right: Vec<Lane>,
    /// Where it is written.
    pub at: Location,
}

impl LaneSection {
    /// The lane with id `id` (not the centre lane).
    pub fn lane(&self, id: i32) -> Option<&Lane> {
        let side = if id > 0 { &self.left } else { &self.right };
        side.get(id.unsigned_abs().checked_sub(1)? as usize)
    }

    /// Its lanes, left then right.
    pub fn lanes(&self) -> impl Iterator<Item = &Lane> {
        self.left.iter().chain(&self.right)
    }
}

/// One lane of a lane section.
#[derive(Debug, Clone, PartialEq)]
pub struct Lane {
    /// Its id: positive on the left, negative on the right.
    pub id: i32,
    /// Its `type`.
    pub kind: String,
    /// What it carries, by its type.
    pub carries: LaneUse,
    /// Which way its traffic goes.
    pub direction: LaneDirection,
    /// Its width records, `s` from the section's start.
    pub widths: Vec<Poly3>,
    /// The lanes it continues from (`<predecessor id>`), with where each is written.
    pub predecessors: Vec<(i32, Location)>,
    /// The lanes it continues into (`<successor id>`).
    pub successors: Vec<(i32, Location)>,
    /// Its speed limits (`<speed>`), `s` from the section's start.
    pub speeds: Vec<Speed>,
    /// Where it is written.
    pub at: Location,
}

/// A speed limit from `s` on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Speed {
    /// Where it starts, metres.
    pub s: f64,
    /// The limit, m/s; `None` for `no limit` and `undefined`.
    pub limit: Option<f64>,
}

/// Reads `<lanes>`: lane offsets and lane sections, in order, within the
/// road's `length`.
pub(crate) fn lanes(node: Node, length: f64, locator: &Locator) -> Result<Lanes, OpenDriveError> {
    xml::allowed_children(node, &["laneOffset", "laneSection"], &[])?;
    let offsets = records(node, "laneOffset", "s")?;
    let mut sections: Vec<LaneSection> = Vec::new();
    for child in xml::children(node, "laneSection") {
        let section = section(child, locator)?;
        let problem = match sections.last() {
            None if section.s > 1e-6 => Some("the first lane section starts after s = 0"),
            Some(previous) if section.s < previous.s => Some("lane sections are not in order of s"),
            _ if section.s >= length && section.s > 0.0 => Some("the lane section starts at or after the road's end"),
            _ => None,
        };
        if let Some(problem) = problem {
            return Err(xml::element_error(
                child,
                format!("{problem} (s = {})", Number(section.s)),
            ));
        }
        sections.push(section);
    }
    if sections.is_empty() {
        return Err(xml::element_error(node, "<lanes> holds no <laneSection>".into()));
    }
    Ok(Lanes { offsets, sections })
}

/// The `name` records of `node` (`<laneOffset>`, `<width>`), their start
/// attribute `start`, checked to be in order.
fn records(node: Node, name: &'static str, start: &str) -> Result<Vec<Poly3>, OpenDriveError> {
    let mut records: Vec<Poly3> = Vec::new();
    for child in xml::children(node, name) {
        let record = Poly3 {
            s: xml::non_negative(child, start)?,
            k: [
                xml::number(child, "a")?,
                xml::number(child, "b")?,
                xml::number(child, "c")?,
                xml::number(child, "d")?,
            ],
        };
        if records.last().is_some_and(|last| record.s < last.s) {
            return Err(xml::element_error(
                child,
                format!(
                    "<{name}> records are not in order of `{start}` ({} after {})",
                    Number(record.s),
                    Number(records[records.len() - 1].s)
                ),
            ));
        }
        records.push(record);
    }
    Ok(records)
}

/// One `<laneSection>`.
fn section(node: Node, locator: &Locator) -> Result<LaneSection, OpenDriveError> {
    xml::allowed_children(node, &["left", "center", "right"], &[])?;
    let s = xml::non_negative(node, "s")?;
    if let Some(single) = node.attribute_node("singleSide")
        && single.value() == "true"
    {
        return Err(xml::value_error(
            node,
            &single,
            "lane sections valid for one side only (`singleSide=\"true\"`) are not supported".into(),
        ));
    }
    if xml::child(node, "center").is_none() {
        return Err(xml::element_error(
            node,
            "a <laneSection> needs its <center> lane".into(),
        ));
    }
    let left = match xml::child(node, "left") {
        Some(side) => side_lanes(side, 1, locator)?,
        None => Vec::new(),
    };
    let right = match xml::child(node, "right") {
        Some(side) => side_lanes(side, -1, locator)?,
        None => Vec::new(),
    };
    for centre in xml::child(node, "center")
        .into_iter()
        .flat_map(|c| xml::children(c, "lane"))
    {
        if xml::integer(centre, "id")? != 0 {
            return Err(xml::element_error(centre, "the centre lane's id is 0".into()));
        }
    }
    Ok(LaneSection {
        s,
        left,
        right,
        at: locator.at(node),
    })
}

/// The lanes of `<left>` (`sign` 1) or `<right>` (−1), ordered from the centre
/// out; their ids must be 1, 2, … (or −1, −2, …) without gaps.
fn side_lanes(node: Node, sign: i32, locator: &Locator) -> Result<Vec<Lane>, OpenDriveError> {
    xml::allowed_children(node, &["lane"], &[])?;
    let mut lanes = xml::children(node, "lane")
        .map(|l| lane(l, locator))
        .collect::<Result<Vec<_>, _>>()?;
    lanes.sort_by_key(|lane| lane.id.abs());
    let nodes: Vec<Node> = xml::children(node, "lane").collect();
    for (i, lane) in lanes.iter().enumerate() {
        let expected = sign * (i as i32 + 1);
        if lane.id != expected {
            let at = nodes
                .iter()
                .find(|n| locator.at(**n) == lane.at)
                .copied()
                .unwrap_or(node);
            let side = if sign > 0 { "<left>" } else { "<right>" };
            return Err(xml::element_error(
                at,
                format!(
                    "lane {} in {side}: the lanes of a side are numbered {}, {}, … from the centre out, and lane \
                     {expected} is missing or repeated",
                    lane.id,
                    sign,
                    2 * sign
                ),
            ));
        }
    }
    Ok(lanes)
}

/// One `<lane>` of a side.
fn lane(node: Node, locator: &Locator) -> Result<Lane, OpenDriveError> {
    xml::allowed_children(
        node,
        &["link", "width", "speed", "border"],
        &["roadMark", "material", "visibility", "access", "height", "rule"],
    )?;
    let id = xml::integer(node, "id")?;
    let kind = xml::string(node, "type")?;
    let names: Vec<&str> = LANE_TYPES.iter().map(|(name, _)| *name).collect();
    xml::choice(node, "type", &names)?;
    let carries = LANE_TYPES
        .iter()
        .find(|(name, _)| *name == kind)
        .map_or(LaneUse::Other, |(_, use_)| *use_);
    let direction = match xml::choice(node, "direction", &["standard", "reversed", "both"])? {
        Some("reversed") => LaneDirection::Reversed,
        Some("both") => LaneDirection::Both,
        _ => LaneDirection::Standard,
    };
    if let Some(border) = xml::child(node, "border") {
        return Err(xml::element_error(
            border,
            format!("lane {id}: lane borders (<border>) are not supported; give the lane's <width> instead"),
        ));
    }
    let widths = records(node, "width", "sOffset")?;
    if widths.is_empty() {
        return Err(xml::element_error(node, format!("lane {id} has no <width>")));
    }
    // A width may reach 0 where a lane opens or closes, but not start below
    // it; and a lane that carries road users has some width somewhere.
    for (record, width) in xml::children(node, "width").zip(&widths) {
        if width.k[0] < 0.0 {
            let message = format!(
                "lane {id}: a <width> starts at a negative width, {} m; give the lane's width (≥ 0) where the record \
                 starts",
                Number(width.k[0])
            );
            return Err(xml::value_error(record, &xml::attribute(record, "a")?, message));
        }
    }
    if carries != LaneUse::Other && widths.iter().all(|w| w.k == [0.0; 4]) {
        return Err(xml::element_error(
            node,
            format!(
                "lane {id} ({kind}) has no width anywhere: every <width> is 0; leave the lane out or give its width"
            ),
        ));
    }
    let (mut predecessors, mut successors) = (Vec::new(), Vec::new());
    if let Some(link) = xml::child(node, "link") {
        xml::allowed_children(link, &["predecessor", "successor"], &[])?;
        for (name, list) in [("predecessor", &mut predecessors), ("successor", &mut successors)] {
            for end in xml::children(link, name) {
                list.push((xml::integer(end, "id")?, locator.at(end)));
            }
        }
    }
    let mut speeds: Vec<Speed> = Vec::new();
    for speed in xml::children(node, "speed") {
        let s = xml::non_negative(speed, "sOffset")?;
        if speeds.last().is_some_and(|last| s < last.s) {
            return Err(xml::element_error(
                speed,
                "<speed> records are not in order of `sOffset`".into(),
            ));
        }
        speeds.push(Speed {
            s,
            limit: Some(
                max_speed(speed)?
                    .ok_or_else(|| xml::element_error(speed, "a lane's <speed> gives its `max` as a number".into()))?,
            ),
        });
    }
    Ok(Lane {
        id,
        kind: kind.to_owned(),
        carries,
        direction,
        widths,
        predecessors,
        successors,
        speeds,
        at: locator.at(node),
    })
}

/// The speed limits of a road's `<type>` records, `s` along the road.
pub(crate) fn road_speeds(road: Node) -> Result<Vec<Speed>, OpenDriveError> {
    let mut speeds: Vec<Speed> = Vec::new();
    for kind in xml::children(road, "type") {
        xml::allowed_children(kind, &["speed"], &[])?;
        let s = xml::non_negative(kind, "s")?;
        if speeds.last().is_some_and(|last| s < last.s) {
            return Err(xml::element_error(
                kind,
                "<type> records are not in order of `s`".into(),
            ));
        }
        let limit = match xml::child(kind, "speed") {
            Some(speed) => max_speed(speed)?,
            None => None,
        };
        speeds.push(Speed { s, limit });
    }
    Ok(speeds)
}

/// A `<speed>`'s `max` in m/s by its `unit` (default m/s); `None` for
/// `no limit` and `undefined`.
fn max_speed(node: Node) -> Result<Option<f64>, OpenDriveError> {
    let max = xml::attribute(node, "max")?;
    if matches!(max.value(), "no limit" | "undefined") {
        return Ok(None);
    }
    let value = xml::non_negative(node, "max")?;
    let unit = xml::choice(node, "unit", &["m/s", "km/h", "mph"])?;
    let factor = match unit {
        Some("km/h") => 1.0 / 3.6,
        Some("mph") => 0.447_04,
        _ => 1.0,
    };
    if value == 0.0 {
        return Err(xml::value_error(
            node,
            &max,
            "a speed limit of 0 stops all traffic; give a positive `max`".into(),
        ));
    }
    let limit = value * factor;
    if !range::SPEED_POSITIVE.contains(limit) {
        let message = format!(
            "a speed limit of {} {} is above {} m/s, a scenario's largest speed limit",
            Number(value),
            unit.unwrap_or("m/s"),
            range::SPEED_POSITIVE.max
        );
        return Err(xml::value_error(node, &max, message));
    }
    Ok(Some(limit))
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    const LANES: &str = r#"<lanes>
  <laneOffset s="0" a="0.5" b="0" c="0" d="0"/>
  <laneSection s="0">
    <left>
      <lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><speed sOffset="0" max="50" unit="km/h"/></lane>
    </left>
    <center><lane id="0" type="none"/></center>
    <right>
      <lane id="-2" type="sidewalk"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane>
      <lane id="-1" type="driving"><link><successor id="-1"/></link><width sOffset="0" a="3" b="0.1" c="0" d="0"/><roadMark sOffset="0" type="solid"/></lane>
    </right>
  </laneSection>
  <laneSection s="40">
    <center><lane id="0" type="none"/></center>
    <right><lane id="-1" type="biking" direction="both"><width sOffset="0" a="1.5" b="0" c="0" d="0"/></lane></right>
  </laneSection>
</lanes>"#;

    fn read(text: &str) -> Result<Lanes, String> {
        let doc = xml::parse(text).unwrap();
        lanes(doc.root_element(), 100.0, &Locator::new(text)).map_err(|e| e.to_string())
    }

    #[test]
    fn reads_sections_lanes_widths_links_and_speeds() {
        let lanes = read(LANES).unwrap();
        assert_eq!(
            lanes.offsets,
            [Poly3 {
                s: 0.0,
                k: [0.5, 0.0, 0.0, 0.0]
            }]
        );
        let first = &lanes.sections[0];
        assert_eq!(first.left.len(), 1);
        let right: Vec<(i32, LaneUse)> = first.right.iter().map(|l| (l.id, l.carries)).collect();
        assert_eq!(right, [(-1, LaneUse::Drive), (-2, LaneUse::Walk)]);
        let lane = first.lane(-1).unwrap();
        assert_eq!(lane.successors.iter().map(|s| s.0).collect::<Vec<_>>(), [-1]);
        assert_relative_eq!(value_at(&lane.widths, 10.0), 4.0);
        assert_relative_eq!(first.lane(1).unwrap().speeds[0].limit.unwrap(), 50.0 / 3.6);
        let second = &lanes.sections[1];
        assert_eq!(
            (second.s, second.right[0].carries, second.right[0].direction),
            (40.0, LaneUse::Other, LaneDirection::Both)
        );
        assert!(second.lane(1).is_none() && second.lane(-2).is_none());
    }

    #[test]
    fn lane_errors_are_located() {
        assert_eq!(
            read(&LANES.replace(r#"id="-2""#, r#"id="-3""#)).unwrap_err(),
            "9:7: lane -3 in <right>: the lanes of a side are numbered -1, -2, … from the centre out, and lane -2 \
             is missing or repeated"
        );
        assert_eq!(
            read(&LANES.replace(r#"type="sidewalk""#, r#"type="sidewlak""#)).unwrap_err(),
            "9:27: attribute `type` of <lane> is \"sidewlak\"; expected one of `driving`, `entry`, `exit`, \
             `onRamp`, `offRamp`, `connectingRamp`, `bidirectional`, `slipLane`, `bus`, `taxi`, `HOV`, `mwyEntry`, \
             `mwyExit`, `sidewalk`, `walking`, `shoulder`, `border`, `stop`, `none`, `restricted`, `parking`, \
             `median`, `biking`, `curb`, `special1`, `special2`, `special3`, `roadWorks`, `tram`, `rail`, `shared`; \
             did you mean `sidewalk`?"
        );
        assert_eq!(
            read(&LANES.replace(r#"<laneSection s="40">"#, r#"<laneSection s="140">"#)).unwrap_err(),
            "13:3: the lane section starts at or after the road's end (s = 140)"
        );
        assert_eq!(
            read(&LANES.replace(r#"max="50""#, r#"max="fast""#)).unwrap_err(),
            "5:105: attribute `max` of <speed> is not a number: \"fast\""
        );
        assert_eq!(
            read(&LANES.replace(
                "<roadMark",
                "<border sOffset=\"0\" a=\"1\" b=\"0\" c=\"0\" d=\"0\"/><roadMark"
            ))
            .unwrap_err(),
            "10:115: lane -1: lane borders (<border>) are not supported; give the lane's <width> instead"
        );
    }

    /// A width that starts below 0, and a lane carrying road users that has no
    /// width anywhere, are refused; a width that starts at 0 and grows (a lane
    /// opening), and a zero-width lane that carries no one, are read.
    #[test]
    fn a_negative_width_and_a_lane_of_no_width_are_refused() {
        let sidewalk = r#"<width sOffset="0" a="2" b="0" c="0" d="0"/>"#;
        let with = |width: &str| LANES.replace(sidewalk, width);
        assert_eq!(
            read(&with(r#"<width sOffset="0" a="-3.5" b="0" c="0" d="0"/>"#)).unwrap_err(),
            "9:59: lane -2: a <width> starts at a negative width, -3.5 m; give the lane's width (≥ 0) where the \
             record starts"
        );
        assert_eq!(
            read(&with(
                r#"<width sOffset="0" a="2" b="0" c="0" d="0"/><width sOffset="5" a="-1" b="1" c="0" d="0"/>"#
            ))
            .unwrap_err(),
            "9:103: lane -2: a <width> starts at a negative width, -1 m; give the lane's width (≥ 0) where the \
             record starts"
        );
        assert_eq!(
            read(&with(r#"<width sOffset="0" a="0" b="0" c="0" d="0"/>"#)).unwrap_err(),
            "9:7: lane -2 (sidewalk) has no width anywhere: every <width> is 0; leave the lane out or give its width"
        );
        let opening = read(&with(r#"<width sOffset="0" a="0" b="0.1" c="0" d="0"/>"#)).unwrap();
        assert_relative_eq!(value_at(&opening.sections[0].lane(-2).unwrap().widths, 10.0), 1.0);
        let shoulder = with(r#"<width sOffset="0" a="0" b="0" c="0" d="0"/>"#).replace("sidewalk", "shoulder");
        assert!(read(&shoulder).is_ok());
    }

    /// A limit above 150 m/s (the largest a scenario's own speed limits take)
    /// is refused in the unit the file gives; 540 km/h is 150 m/s.
    #[test]
    fn a_speed_limit_above_150_m_s_is_refused() {
        assert_eq!(
            read(&LANES.replace(r#"max="50""#, r#"max="541""#)).unwrap_err(),
            "5:105: a speed limit of 541 km/h is above 150 m/s, a scenario's largest speed limit"
        );
        let doc = xml::parse(r#"<road><type s="0" type="town"><speed max="1e6"/></type></road>"#).unwrap();
        assert_eq!(
            road_speeds(doc.root_element()).unwrap_err().to_string(),
            "1:43: a speed limit of 1000000 m/s is above 150 m/s, a scenario's largest speed limit"
        );
        assert!(read(&LANES.replace(r#"max="50""#, r#"max="540""#)).is_ok());
    }

    #[test]
    fn road_speeds_convert_units_and_read_no_limit() {
        let doc = xml::parse(
            r#"<road><type s="0" type="town"><speed max="30" unit="mph"/></type><type s="50" type="motorway"><speed max="no limit"/></type><type s="60" type="rural"/></road>"#,
        )
        .unwrap();
        let speeds = road_speeds(doc.root_element()).unwrap();
        assert_relative_eq!(speeds[0].limit.unwrap(), 13.4112);
        assert_eq!((speeds[1].s, speeds[1].limit), (50.0, None));
        assert_eq!((speeds[2].s, speeds[2].limit), (60.0, None));
    }
}
