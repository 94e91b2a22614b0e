//! `traces`: a SUMO run (the fixture in `scenarios/sumo`) imported into a world,
//! and the errors of imported files, located in the scenario or in those files.

use std::io;
use std::path::Path;

use approx::assert_relative_eq;
use sightline_dsl::{
    AgentKind, Area, ErrorKind, Errors, Experiment, ImportKind, Location, Motion, Options, Scenario, World, compile,
};

/// A scenario file in `scenarios/`, so that `sumo/…` names the fixture. It need
/// not exist: only its directory matters.
const FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios/traces-test.yaml");

const BASE: &str = "sightline: 1
name: t
time: { duration: 60, step: 0.1 }
# no `grid`: a semantic world fuses none
traces:
  fcd: sumo/grid3x3.fcd.xml
  net: sumo/grid3x3.net.xml
  poly: sumo/grid3x3.poly.xml
sensor_models:
  front: { range: 80, fov_deg: 70 }
  around: { range: 100 }
agents:
  - { id: ego, kind: car, trace: veh7, connected: true, sensors: [front] }
  - { id: rsu, kind: rsu, position: [93.5, 93.5], sensors: [around] }
semantic: { ego: ego }
";

fn disk(path: &Path) -> io::Result<Vec<u8>> {
    std::fs::read(path)
}

/// Compiles `text` as [`FILE`], reading imports with `loader`.
fn compile_with(text: &str, loader: &dyn Fn(&Path) -> io::Result<Vec<u8>>) -> Result<Scenario, Errors> {
    let options = Options {
        loader: Some(&loader),
        ..Default::default()
    };
    compile(FILE, text, &options)
}

fn world(text: &str) -> World {
    let scenario = compile_with(text, &disk).unwrap_or_else(|e| panic!("{e}"));
    let Experiment::World(world) = scenario.points[0].setup.experiment.clone() else {
        panic!("a world scenario")
    };
    *world
}

/// The errors of `text`, each as `file:line:col: error: …` with [`FILE`]'s
/// directory cut to `…/`.
fn errors_with(text: &str, loader: &dyn Fn(&Path) -> io::Result<Vec<u8>>) -> Vec<String> {
    let directory = FILE.strip_suffix("traces-test.yaml").unwrap();
    compile_with(text, loader)
        .expect_err("the file is invalid")
        .0
        .iter()
        .map(|e| e.to_string().replace(directory, "…/"))
        .collect()
}

fn errors(text: &str) -> Vec<String> {
    errors_with(text, &disk)
}

#[test]
fn a_sumo_run_becomes_roads_buildings_areas_and_agents() {
    let scenario = compile_with(BASE, &disk).unwrap_or_else(|e| panic!("{e}"));
    let imports: Vec<(ImportKind, &str)> = scenario
        .imports
        .iter()
        .map(|i| (i.kind, i.path.rsplit('/').next().unwrap()))
        .collect();
    assert_eq!(
        imports,
        [
            (ImportKind::SumoFcd, "grid3x3.fcd.xml"),
            (ImportKind::SumoNet, "grid3x3.net.xml"),
            (ImportKind::SumoPoly, "grid3x3.poly.xml"),
        ]
    );
    for import in &scenario.imports {
        assert_eq!(import.bytes, std::fs::read(&import.path).unwrap(), "{}", import.path);
    }
    let Experiment::World(world) = &scenario.points[0].setup.experiment else {
        panic!("a world scenario")
    };
    // The 24 edges, one lane each, linked by the 44 connections.
    assert_eq!(world.roads.len(), 24);
    assert!(
        world
            .roads
            .iter()
            .all(|r| r.lanes.len() == 1 && r.lane_width == 3.2 && r.speed_limit == 13.89)
    );
    assert_eq!(world.roads.iter().map(|r| r.links.len()).sum::<usize>(), 44);
    // The eight buildings block sight, the park does not.
    assert_eq!(world.occluders.len(), 8);
    assert!(world.occluders.iter().all(|o| o.id.starts_with("b_")));
    // Junctions three or four roads enter; the corners have two.
    let areas: Vec<&str> = world.interaction_areas.iter().map(|a| a.id.as_str()).collect();
    assert_eq!(areas, ["A1", "B0", "B1", "B2", "C1"]);
    let Area::Polygon(b1) = &world.interaction_areas[2].shape else {
        panic!("a junction's outline")
    };
    assert!(
        b1.iter()
            .all(|p| (p[0] - 100.0).abs() <= 7.2 + 1e-9 && (p[1] - 100.0).abs() <= 7.2 + 1e-9)
    );
    // The ego and the RSU, then the 23 other objects of the trace.
    assert_eq!((world.agents.len(), world.imported), (25, 23));
    assert!(world.agents.iter().all(|a| a.id != "veh7"));
    assert!(world.agents[2..].iter().all(|a| !a.connected && a.sensors.is_empty()));
}

#[test]
fn undeclared_vehicle_types_map_to_kinds_by_name() {
    let world = world(BASE);
    let agent = |id: &str| world.agents.iter().find(|a| a.id == id).unwrap();
    let kind = |id: &str| {
        let agent = agent(id);
        assert_eq!((agent.length, agent.width), agent.kind.footprint(), "{id}");
        agent.kind
    };
    // SUMO types `car`, `motorcycle`, `truck`, `bus`, which no file declares.
    assert_eq!(kind("veh2"), AgentKind::Car);
    assert_eq!(kind("veh0"), AgentKind::Motorbike);
    assert_eq!(kind("veh13"), AgentKind::Truck);
    assert_eq!(kind("veh4"), AgentKind::Bus);
    // SUMO's built-in `DEFAULT_PEDTYPE`, with SUMO's default size.
    let ped = agent("ped0");
    assert_eq!((ped.kind, ped.length, ped.width), (AgentKind::Pedestrian, 0.215, 0.478));
}

/// veh7 first appears at 7 s with its front bumper at (1.60, 111.80), heading
/// north (SUMO's angle 0) on lane A1A2_0 (13.89 m/s): its centre is 2.25 m behind.
#[test]
fn a_traced_vehicle_is_placed_by_its_centre() {
    let world = world(BASE);
    let Motion::Trace { samples, path, max_gap } = &world.agents[0].motion else {
        panic!("the ego replays a trace")
    };
    let first = samples[0];
    assert_eq!(first.time, 7.0);
    assert_relative_eq!(first.position[0], 1.6);
    assert_relative_eq!(first.position[1], 111.8 - 2.25);
    assert_relative_eq!(first.heading, std::f64::consts::FRAC_PI_2);
    assert_eq!((first.speed, first.offset, first.limit), (12.26, 0.0, 13.89));
    assert_relative_eq!(samples[1].offset, 113.02 - 111.8, epsilon = 1e-9);
    let path = path.as_ref().expect("veh7 moves");
    assert_relative_eq!(path.length(), samples.last().unwrap().offset, epsilon = 1e-9);
    // The trace's period is 0.1 s.
    assert_relative_eq!(*max_gap, 0.15, epsilon = 1e-9);
    // A pedestrian's position is its centre.
    let walker = world.agents.iter().find(|a| a.id == "ped0").unwrap();
    let Motion::Trace { samples, .. } = &walker.motion else {
        panic!("a traced pedestrian")
    };
    assert_eq!(samples[0].limit, f64::INFINITY);
}

#[test]
fn begin_shifts_the_trace_and_drops_what_ends_before() {
    let world = world(
        &BASE
            .replace("  poly:", "  begin: 30\n  poly:")
            .replace("duration: 60", "duration: 20"),
    );
    let Motion::Trace { samples, .. } = &world.agents[0].motion else {
        panic!("the ego replays a trace")
    };
    assert_relative_eq!(samples[0].time, -23.0, epsilon = 1e-9);
    // veh3 leaves at 26.3 s, veh12 at 23.8 s: before the trace's 30 s.
    assert!(world.agents.iter().all(|a| a.id != "veh3" && a.id != "veh12"));
    assert_eq!(world.imported, 21);
    let late = BASE.replace("  poly:", "  begin: 54\n  poly:");
    assert_eq!(
        errors(&late),
        [
            "…/traces-test.yaml:14:34: error: agents[0].trace: `veh7` is not in the trace between the run's 0 and 60 s \
          (with `traces.begin`)"
        ]
    );
}

#[test]
fn ids_shared_with_the_trace_or_the_network_are_errors() {
    let text = BASE
        .replace(
            "semantic:",
            "  - { id: veh3, kind: rsu, position: [0, 0] }\n  - { id: again, kind: car, trace: veh7 }\nsemantic:",
        )
        .replace(
            "sensor_models:",
            "roads:\n  - { id: A0B0, polyline: [[0, 0], [1, 0]], speed_limit: 1 }\nsensor_models:",
        );
    assert_eq!(
        errors(&text),
        [
            "…/traces-test.yaml:10:11: error: roads[0].id: `A0B0` is also the id of an edge of `traces.net`; \
             choose another id",
            "…/traces-test.yaml:17:11: error: agents[2].id: `veh3` is also the id of an object of `traces.fcd`: \
             replay it with `trace: veh3`, or choose another id",
            "…/traces-test.yaml:18:36: error: agents[3].trace: agent `ego` replays `veh7` already",
        ]
    );
    // An agent named after the object it replays is fine.
    let world = world(
        &BASE
            .replace("id: ego, kind: car, trace: veh7", "id: veh7, kind: car, trace: veh7")
            .replace("ego: ego", "ego: veh7"),
    );
    assert_eq!(world.agents.iter().filter(|a| a.id == "veh7").count(), 1);
}

#[test]
fn trace_references_are_checked() {
    let unknown = errors(&BASE.replace("trace: veh7", "trace: veh77"));
    assert_eq!(unknown.len(), 1);
    assert!(
        unknown[0].starts_with("…/traces-test.yaml:13:34: error: agents[0].trace: no object `veh77` in `traces.fcd`"),
        "{unknown:?}"
    );
    assert!(unknown[0].ends_with("did you mean `veh7`?)"), "{unknown:?}");
    let without = BASE.replace(
        "traces:\n  fcd: sumo/grid3x3.fcd.xml\n  net: sumo/grid3x3.net.xml\n  poly: sumo/grid3x3.poly.xml\n",
        "",
    );
    assert_eq!(
        errors(&without)[0],
        "…/traces-test.yaml:9:34: error: agents[0].trace: no `traces` section to take `veh7` from"
    );
    let with_speed = BASE.replace("trace: veh7,", "trace: veh7, speed: { target: 5 }, lane: 0,");
    assert_eq!(
        errors(&with_speed),
        [
            "…/traces-test.yaml:13:40: error: agents[0].speed: an agent replaying a trace moves as recorded: \
             `speed` does not apply",
            "…/traces-test.yaml:13:62: error: agents[0].lane: an agent replaying a trace moves as recorded: \
             `lane` does not apply",
        ]
    );
}

#[test]
fn a_file_that_cannot_be_read_is_an_error_at_its_name() {
    let missing = errors(&BASE.replace("fcd: sumo/grid3x3.fcd.xml", "fcd: sumo/missing.fcd.xml"));
    assert_eq!(missing.len(), 1);
    assert!(
        missing[0].starts_with("…/traces-test.yaml:6:8: error: traces.fcd: failed to read …/sumo/missing.fcd.xml: "),
        "{missing:?}"
    );
    // Without a loader, the compiler reads nothing.
    let error = compile(FILE, BASE, &Options::default()).unwrap_err();
    assert_eq!(error.0.len(), 3, "{error}");
    assert_eq!(error.0[0].location, Location::new(6, 8));
    assert!(
        matches!(&error.0[0].kind, ErrorKind::Io { reason, .. } if reason == "this compilation was given no file loader")
    );
}

/// The fixture's files, except a replaced `.fcd.xml`.
fn with_fcd(fcd: &'static [u8]) -> impl Fn(&Path) -> io::Result<Vec<u8>> {
    move |path: &Path| {
        if path.to_string_lossy().ends_with(".fcd.xml") {
            Ok(fcd.to_vec())
        } else {
            disk(path)
        }
    }
}

#[test]
fn a_malformed_file_is_an_error_located_in_it() {
    let fcd = b"<fcd-export>\n  <timestep time=\"0.00\">\n    <vehicle id=\"veh7\" y=\"1\" angle=\"0\" speed=\"1\"/>\n  </timestep>\n</fcd-export>\n";
    assert_eq!(
        errors_with(BASE, &with_fcd(fcd)),
        ["…/sumo/grid3x3.fcd.xml:3:5: error: missing attribute `x` on <vehicle>"]
    );
    assert_eq!(
        errors_with(BASE, &with_fcd(b"<fcd-export>\n<timestep time=\"0\">\xff")),
        ["…/sumo/grid3x3.fcd.xml:2:20: error: the file is not UTF-8 text"]
    );
    // Problems of the scenario come first, then those of the files it imports.
    let text = BASE.replace("range: 80", "range: -80");
    assert_eq!(
        errors_with(&text, &with_fcd(b"<net/>")),
        [
            "…/traces-test.yaml:10:19: error: sensor_models.front.range: expected a number > 0, found -80",
            "…/sumo/grid3x3.fcd.xml:1:1: error: expected <fcd-export> as the root element, found <net>",
        ]
    );
}

#[test]
fn a_trace_on_lanes_the_network_lacks_is_an_error() {
    let fcd = b"<fcd-export>\n  <timestep time=\"0.00\">\n    <vehicle id=\"veh7\" x=\"1\" y=\"1\" angle=\"0\" speed=\"1\" lane=\"X_0\"/>\n  </timestep>\n</fcd-export>\n";
    assert_eq!(
        errors_with(BASE, &with_fcd(fcd)),
        [
            "…/traces-test.yaml:7:8: error: traces.net: the trace puts `veh7` at 0 s on lane `X_0`, which the network \
          does not have; are the trace and the network from the same simulation?"
        ]
    );
}

/// A route over two roads of the network crosses the junction between them on
/// SUMO's path: A1A2 ends at (1.6, 196.8), A2B2 starts at (3.2, 198.4), each
/// 89.6 m long; the right turn across the corner is 2.58 m.
#[test]
fn routes_cross_junctions_on_the_networks_paths() {
    let world = world(&BASE.replace(
        "semantic:",
        "  - { id: car, kind: car, route: [A1A2, A2B2], speed: { target: 10 } }\nsemantic:",
    ));
    let car = world.agents.iter().find(|a| a.id == "car").unwrap();
    let Motion::Along { path, limits, .. } = &car.motion else {
        panic!("a car on a route")
    };
    assert_eq!(path.start(), [1.6, 107.2]);
    assert_eq!(path.end(), [92.8, 198.4]);
    let passes = |[x, y]: [f64; 2]| path.points().iter().any(|p| (p[0] - x).hypot(p[1] - y) < 1e-9);
    assert!(passes([1.6, 196.8]) && passes([2.0, 198.0]) && passes([3.2, 198.4]));
    assert_relative_eq!(path.length(), 2.0 * 89.6 + 2.58, epsilon = 0.01);
    assert_eq!(limits.len(), 2);
    assert_relative_eq!(limits[0].0, 89.6, epsilon = 1e-9);
}

/// Reads the files from disk, with `from` replaced by `to` in the one whose
/// name ends with `suffix`.
fn edited(suffix: &'static str, from: &'static str, to: &'static str) -> impl Fn(&Path) -> io::Result<Vec<u8>> {
    move |path: &Path| {
        let bytes = disk(path)?;
        match path.to_string_lossy().ends_with(suffix) {
            true => Ok(String::from_utf8(bytes).unwrap().replace(from, to).into_bytes()),
            false => Ok(bytes),
        }
    }
}

/// Imported objects become agents, whose ids name recording frames and topics:
/// they follow the declared ids' rule, and are refused where they first appear.
#[test]
fn imported_ids_follow_the_rule_of_agent_ids() {
    let at = "…/sumo/grid3x3.fcd.xml:194:9: error: an imported object's id names its agent, and";
    assert_eq!(
        errors_with(BASE, &edited(".fcd.xml", "\"veh3\"", "\"map\"")),
        [format!(
            "{at} `map` is the recording's world frame, the parent of every agent's; rename it in the simulation"
        )]
    );
    assert_eq!(
        errors_with(BASE, &edited(".fcd.xml", "\"veh3\"", "\"rsu/sensor0\"")),
        [format!(
            "{at} an id is 1 to 64 letters, digits, `-`, `_` or `.`; found \"rsu/sensor0\"; rename it in the \
             simulation"
        )]
    );
    let rsus = BASE.replace(
        "sensor_models:",
        "  rsus: { poi_type: tree, sensors: [around] }\nsensor_models:",
    );
    assert_eq!(
        errors_with(&rsus, &edited(".poly.xml", "\"tree_0\"", "\"route1-2\"")),
        [
            "…/sumo/grid3x3.poly.xml:14:5: error: a roadside unit's point of interest: an imported object's id \
             names its agent, and `route1-2` is of the form `routeI-N` the traffic a semantic world generates is \
             named by; rename it in the simulation"
        ]
    );
    // The same files as they are compile.
    world(&rsus);
}
