//! The OpenDRIVE reader on whole maps: the bundled crossroads
//! (`scenarios/opendrive`, written by scenariogeneration) and a hand-written
//! map of every kind of reference line record, lane offsets, widths that vary
//! and two lane sections (`tests/opendrive/curves.xodr`). Checked against
//! values computed independently (mpmath at 30 digits, by quadrature where
//! there is no closed form) and against SUMO's own conversion of the same
//! files (`netconvert --opendrive-files`).
// See: issue 19, part 2.

use std::path::{Path, PathBuf};
use std::process::Command;

use approx::assert_relative_eq;
use sightline_dsl::geometry::{Polyline, Xy};
use sightline_dsl::import::opendrive::{LaneUse, Map, MapLane, Network, build, parse_opendrive};

const CROSSROADS: &str = include_str!("../../scenarios/opendrive/crossroads.xodr");
const CURVES: &str = include_str!("opendrive/curves.xodr");

fn map(text: &str) -> Map {
    build(&parse_opendrive(text).unwrap_or_else(|e| panic!("{e}"))).unwrap_or_else(|e| panic!("{e}"))
}

fn lane<'m>(map: &'m Map, name: &str) -> &'m MapLane {
    map.lanes
        .iter()
        .find(|lane| lane.name == name)
        .unwrap_or_else(|| panic!("no lane `{name}`"))
}

#[test]
fn every_record_of_the_hand_written_map_ends_where_mpmath_puts_it() {
    let map = map(CURVES);
    // Road 20 is a poly3 v(u) = 0.004u² − 0.00005u³, 60 m of arc from
    // (83.0348712466435, 77.5303152428357) heading 1.61666512371394 rad (the
    // end of road 10's line, spiral, arc and paramPoly3, by mpmath); its
    // lane −1 ends 1.75 m right of the poly3's end, at u = 59.835039631386.
    let end = *lane(&map, "road 20 lane -1").centre.last().unwrap();
    assert_relative_eq!(end[0], 78.435_172_222_35, epsilon = 1e-6);
    assert_relative_eq!(end[1], 137.115_169_966_7, epsilon = 1e-6);
    // Road 10's lane 1 (3.5 m left of the reference line, which starts at the
    // origin heading 0.1 rad) ends at its start, travelled against s.
    let start = *lane(&map, "road 10 lane 1").centre.last().unwrap();
    assert_relative_eq!(start[0], -1.75 * 0.1_f64.sin(), epsilon = 1e-12);
    assert_relative_eq!(start[1], 1.75 * 0.1_f64.cos(), epsilon = 1e-12);
}

#[test]
fn lanes_follow_their_links_through_sections_and_into_the_next_road() {
    let map = map(CURVES);
    let names: Vec<(&str, LaneUse)> = map.lanes.iter().map(|l| (l.name.as_str(), l.carries)).collect();
    assert_eq!(
        names,
        [
            ("road 10 lane -1", LaneUse::Drive),
            ("road 10 lane 1", LaneUse::Drive),
            // A lane that appears mid-road is named with its lane section.
            ("road 10 section 1 lane -2", LaneUse::Drive),
            ("road 20 lane 1", LaneUse::Drive),
            ("road 20 lane -1", LaneUse::Drive),
            ("road 20 lane -2", LaneUse::Walk),
            ("road 20 lane -2 reversed", LaneUse::Walk),
        ]
    );
    let through = lane(&map, "road 10 lane -1");
    assert_eq!(map.lanes[through.next[0]].name, "road 20 lane -1");
    assert_eq!(through.next.len(), 1);
    // 60 km/h from the road's <type><speed unit="km/h">.
    assert_relative_eq!(through.speed.unwrap(), 60.0 / 3.6);
    // Lane −1 is 3.25 m wide at s = 0 and widens, then 3.5 m from s = 80.
    assert!(through.width > 3.25 && through.width < 3.6, "{}", through.width);
}

#[test]
fn the_crossroads_has_its_turns_buildings_crosswalk_and_junction() {
    let map = map(CROSSROADS);
    let drivable = map.lanes.iter().filter(|l| l.carries == LaneUse::Drive).count();
    // Two lanes on each of four arms, and twelve one-lane connecting roads.
    assert_eq!(drivable, 8 + 12);
    let west_in = lane(&map, "road 1 lane -1");
    let turns: Vec<&str> = west_in.next.iter().map(|&i| map.lanes[i].name.as_str()).collect();
    assert_eq!(turns, ["road 101 lane -1", "road 102 lane -1", "road 103 lane -1"]);
    // The S-bend turns left then right by as much: the arm ends heading east,
    // 14 m (twice the bend's lateral shift) … as the generator lays it out.
    let points = &west_in.centre;
    let [a, b] = [points[points.len() - 2], points[points.len() - 1]];
    assert_relative_eq!((b[1] - a[1]).atan2(b[0] - a[0]), 0.0, epsilon = 1e-9);
    let kinds: Vec<&str> = map.objects.iter().map(|o| o.kind.as_str()).collect();
    assert_eq!(kinds.iter().filter(|&&k| k == "building").count(), 4);
    assert_eq!(kinds.iter().filter(|&&k| k == "crosswalk").count(), 1);
    assert_eq!(map.junctions.len(), 1);
    assert_eq!(map.junctions[0].id, "100");
}

/// SUMO's netconvert next to the Python that `SIGHTLINE_SUMO_PYTHON` names
/// (a venv with `eclipse-sumo==1.28.0`); `None` (the test skips) when it is
/// unset, and a failure when `CI` is set without it.
fn netconvert() -> Option<PathBuf> {
    const VAR: &str = "SIGHTLINE_SUMO_PYTHON";
    let Some(python) = std::env::var_os(VAR) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI is set but {VAR} is not: .ci/run installs eclipse-sumo and sets it"
        );
        eprintln!("skipped: {VAR} is not set; set it to a Python with eclipse-sumo==1.28.0, as .ci/run does");
        return None;
    };
    let tool = Path::new(&python).with_file_name("netconvert");
    assert!(tool.is_file(), "{VAR} is set but there is no {}", tool.display());
    Some(tool)
}

/// The normal lanes of SUMO's conversion of `xodr`: (road id, lane id) from
/// their `origId`, and their centrelines in the map's frame (`netOffset` undone).
fn converted(tool: &Path, xodr: &str) -> Vec<((String, i32), Vec<Xy>)> {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("map.xodr");
    std::fs::write(&input, xodr).unwrap();
    let output = dir.path().join("map.net.xml");
    let run = Command::new(tool)
        .arg("--opendrive-files")
        .arg(&input)
        .arg("--output.original-names")
        .arg("true")
        .arg("-o")
        .arg(&output)
        .output()
        .unwrap_or_else(|e| panic!("failed to run {}: {e}", tool.display()));
    assert!(
        run.status.success(),
        "netconvert failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&output).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let offset: Vec<f64> = doc
        .descendants()
        .find(|n| n.has_tag_name("location"))
        .and_then(|n| n.attribute("netOffset"))
        .unwrap()
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    doc.descendants()
        .filter(|n| n.has_tag_name("lane") && !n.attribute("id").unwrap().starts_with(':'))
        .map(|lane| {
            let orig = lane
                .children()
                .find(|p| p.attribute("key") == Some("origId"))
                .and_then(|p| p.attribute("value"))
                .unwrap();
            let (road, id) = orig.rsplit_once('_').unwrap();
            let shape = lane
                .attribute("shape")
                .unwrap()
                .split(' ')
                .map(|point| {
                    let xy: Vec<f64> = point.split(',').map(|c| c.parse().unwrap()).collect();
                    [xy[0] - offset[0], xy[1] - offset[1]]
                })
                .collect();
            ((road.to_owned(), id.parse().unwrap()), shape)
        })
        .collect()
}

/// How far SUMO's lane centrelines may lie from sightline's, metres.
/// netconvert samples curves every 2 m (`--opendrive.curve-resolution`) and
/// offsets its own polyline of the reference line, so its points stray from
/// the true lane centre by that sampling's chord error (2² / (8R): 5 mm at
/// the crossroads' 10 m turns; measured, at most 9 mm there), and it
/// interpolates a changing lane offset between its own points (up to 9.5 cm
/// on `curves.xodr`, whose offset ramps at 2 cm/m and then by a cubic).
const TOLERANCE: f64 = 0.1;

/// Whether lane `id` of road `road` keeps one width through each lane
/// section: SUMO gives a lane one width per edge (at least one edge per lane
/// section), so where the width changes along a lane
/// (lane −2 of road 10 in `curves.xodr` widens from 0 to 3.5 m) netconvert's
/// centreline is off by up to half the change (0.78 m there), and such lanes
/// are not compared.
fn constant_width(network: &Network, road: &str, id: i32) -> bool {
    let road = network.roads.iter().find(|r| r.id == road).unwrap();
    road.lanes
        .sections
        .iter()
        .filter_map(|section| section.lane(id))
        .all(|lane| {
            let first = lane.widths[0].k[0];
            lane.widths.iter().all(|w| w.k[1..] == [0.0; 3] && w.k[0] == first)
        })
}

/// Every lane SUMO converts lies on sightline's lane of the same road and id
/// (any of its lane sections, in either direction) within [`TOLERANCE`], and
/// every lane sightline finds on a road SUMO converts is among SUMO's.
fn assert_same_lanes(xodr: &str, tool: &Path) {
    let map = map(xodr);
    // Connecting roads become SUMO's internal lanes, which carry no origId.
    let network = parse_opendrive(xodr).unwrap();
    let connecting: Vec<&str> = network
        .roads
        .iter()
        .filter(|road| road.junction.is_some())
        .map(|road| road.id.as_str())
        .collect();
    let sumo = converted(tool, xodr);
    assert!(!sumo.is_empty());
    let ours = |road: &str, id: i32| -> Vec<Polyline> {
        map.lanes
            .iter()
            .filter(|lane| {
                let name = lane.name.strip_suffix(" reversed").unwrap_or(&lane.name);
                let prefix = format!("road {road} ");
                name.starts_with(&prefix) && name.ends_with(&format!(" lane {id}"))
            })
            .map(|lane| Polyline::new(lane.centre.iter().copied()).unwrap())
            .collect()
    };
    let mut worst = 0.0_f64;
    let mut compared = 0;
    for ((road, id), shape) in sumo
        .iter()
        .filter(|((road, id), _)| constant_width(&network, road, *id))
    {
        compared += 1;
        let candidates = ours(road, *id);
        assert!(
            !candidates.is_empty(),
            "SUMO has lane {id} of road {road}; sightline does not"
        );
        for &point in shape {
            let distance = candidates
                .iter()
                .map(|line| line.project(point).distance)
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(distance);
            assert!(
                distance <= TOLERANCE,
                "SUMO's lane {id} of road {road} passes {point:?}, {distance:.3} m from sightline's"
            );
        }
    }
    assert!(compared * 2 > sumo.len(), "most of SUMO's lanes are compared");
    eprintln!(
        "{compared} of {} SUMO lanes compared, the farthest point {worst:.4} m from sightline's lane",
        sumo.len()
    );
    for lane in map.lanes.iter().filter(|lane| lane.carries == LaneUse::Drive) {
        let road = lane.name.split(' ').nth(1).unwrap();
        let id: i32 = lane.name.split(' ').rev().find_map(|w| w.parse().ok()).unwrap();
        assert!(
            connecting.contains(&road) || sumo.iter().any(|((r, i), _)| r == road && *i == id),
            "sightline has {}; SUMO does not",
            lane.name
        );
    }
}

#[test]
fn lanes_lie_on_netconverts_conversion_of_the_same_maps() {
    let Some(tool) = netconvert() else { return };
    assert_same_lanes(CROSSROADS, &tool);
    assert_same_lanes(CURVES, &tool);
}
