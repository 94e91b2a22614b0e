//! The bundled SUMO town (`scenarios/sumo-town`), read whole from its
//! `.sumocfg` as netconvert and sumo wrote it: interaction areas at every
//! junction (the roundabout's four too), the crossings as crosswalks, roads
//! without their sidewalks, sizes from the vehicle types, and the roadside units
//! of the points of interest (issue 19).

use std::path::Path;

use sightline_dsl::{AgentKind, Experiment, ImportKind, Motion, Options, Scenario, World, compile};

const FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios/sumo-town-semantic.yaml");

fn scenario() -> Scenario {
    let text = std::fs::read_to_string(FILE).unwrap();
    let disk = |path: &Path| std::fs::read(path);
    let options = Options {
        loader: Some(&disk),
        ..Default::default()
    };
    compile(FILE, &text, &options).unwrap_or_else(|e| panic!("{e}"))
}

fn world(scenario: &Scenario) -> &World {
    let Experiment::World(world) = &scenario.points[0].setup.experiment else {
        panic!("a world scenario")
    };
    world
}

#[test]
fn the_configuration_names_every_file() {
    let scenario = scenario();
    let kinds: Vec<(ImportKind, bool)> = scenario.imports.iter().map(|i| (i.kind, i.named)).collect();
    assert_eq!(
        kinds,
        [
            (ImportKind::SumoConfig, true),
            (ImportKind::SumoFcd, false),
            (ImportKind::SumoNet, false),
            (ImportKind::SumoRoutes, false),
            (ImportKind::SumoPoly, false),
        ]
    );
    assert!(scenario.imports[1].path.ends_with("sumo-town/town.fcd.xml"));
}

#[test]
fn every_junction_where_paths_meet_is_an_interaction_area() {
    let scenario = scenario();
    let world = world(&scenario);
    // J, and the roundabout's four junctions, each entered by two roads (the
    // ring and an arm) whose paths merge; the arms' dead ends are none.
    let mut areas: Vec<&str> = world.interaction_areas.iter().map(|a| a.id.as_str()).collect();
    areas.sort_unstable();
    assert_eq!(areas, ["J", "RE", "RN", "RS", "RW"]);
}

#[test]
fn crossings_are_crosswalks_and_walking_areas_named_areas() {
    let scenario = scenario();
    let world = world(&scenario);
    let crosswalks: Vec<&str> = world.crosswalks.iter().map(|c| c.id.as_str()).collect();
    assert_eq!(crosswalks, [":J_c0", ":J_c1", ":J_c2", ":J_c3"]);
    for crosswalk in &world.crosswalks {
        // netconvert's crossings: 4 m wide, kerb to kerb across one lane each
        // way (and the bike lanes on the west arm).
        assert_eq!(crosswalk.width, 4.0, "{}", crosswalk.id);
        let length =
            ((crosswalk.to[0] - crosswalk.from[0]).powi(2) + (crosswalk.to[1] - crosswalk.from[1]).powi(2)).sqrt();
        assert!((6.0..=13.0).contains(&length), "{}: {length}", crosswalk.id);
    }
    let walking: Vec<&str> = world.areas.iter().map(|a| a.id.as_str()).collect();
    assert!(
        walking.starts_with(&[":J_w0", ":J_w1", ":J_w2", ":J_w3"]),
        "{walking:?}"
    );
}

#[test]
fn roads_leave_out_sidewalks_and_take_the_car_lane_s_width_and_speed() {
    let scenario = scenario();
    let world = world(&scenario);
    let road = |id: &str| world.roads.iter().find(|r| r.id == id).unwrap();
    // WJ: sidewalk (2 m), bike lane (1.5 m), car lane (3.2 m, the default).
    let wj = road("WJ");
    assert_eq!((wj.lanes.len(), wj.lane_width, wj.speed_limit), (2, 3.2, 13.89));
    let nj = road("NJ");
    assert_eq!((nj.lanes.len(), nj.lane_width, nj.speed_limit), (1, 3.2, 13.89));
    assert_eq!(road("ring_ws").speed_limit, 8.33);
    // Every road links on to another but at the dead ends.
    assert!(
        world
            .roads
            .iter()
            .filter(|r| r.links.is_empty())
            .all(|r| ["JW", "JN", "JS", "RE2", "RN2", "RS2"].contains(&r.id.as_str()))
    );
}

#[test]
fn vehicle_types_give_kinds_and_sizes() {
    let scenario = scenario();
    let world = world(&scenario);
    let body = |prefix: &str| {
        let agent = world.agents.iter().find(|a| a.id.starts_with(prefix)).unwrap();
        (agent.kind, agent.length, agent.width)
    };
    // `car`: its own size; `van` (delivery), `bus`, `bike` (bicycle) and
    // `walker` (pedestrian): SUMO's defaults for their classes.
    assert_eq!(body("car_ew"), (AgentKind::Car, 4.6, 1.8));
    assert_eq!(body("van_"), (AgentKind::Truck, 6.5, 2.16));
    assert_eq!(body("bus_"), (AgentKind::Bus, 12.0, 2.5));
    assert_eq!(body("bike_"), (AgentKind::Bicycle, 1.6, 0.65));
    assert_eq!(body("walk_"), (AgentKind::Pedestrian, 0.215, 0.478));
    // A bicycle's centre is 0.8 m behind SUMO's front position, not 2.25 m.
    let bike = world.agents.iter().find(|a| a.id.starts_with("bike_")).unwrap();
    let Motion::Trace { samples, .. } = &bike.motion else {
        panic!("a trace")
    };
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/sumo-town/town.fcd.xml"
    ))
    .unwrap();
    let needle = format!("<vehicle id=\"{}\" x=\"", bike.id);
    let at = text.find(&needle).unwrap() + needle.len();
    let x: f64 = text[at..].split('"').next().unwrap().parse().unwrap();
    let sample = &samples[0];
    assert!((x - sample.position[0] - 0.8 * sample.heading.cos()).abs() < 1e-9);
}

#[test]
fn points_of_interest_of_type_rsu_are_roadside_units_at_their_height() {
    let scenario = scenario();
    let world = world(&scenario);
    let rsus: Vec<_> = world
        .agents
        .iter()
        .filter(|a| a.kind == AgentKind::Rsu)
        .map(|a| {
            (
                a.id.as_str(),
                a.motion.clone(),
                a.antenna_m,
                a.connected,
                a.sensors.len(),
            )
        })
        .collect();
    let fixed = |x, y| Motion::Fixed {
        position: [x, y],
        heading: 0.0,
    };
    assert_eq!(
        rsus,
        [
            ("rsu_J", fixed(-12.0, -12.0), Some(6.0), true, 1),
            ("rsu_R", fixed(200.0, 0.0), Some(8.0), true, 1),
        ]
    );
    let semantic = world.semantic.as_ref().unwrap();
    assert_eq!(semantic.rsus, [1, 2]);
}

#[test]
fn the_run_is_covered_and_nothing_but_dead_end_walking_areas_is_left_out() {
    let scenario = scenario();
    assert_eq!(world(&scenario).uncovered, None);
    let warnings: Vec<String> = scenario.warnings.iter().map(|w| w.message.clone()).collect();
    assert_eq!(
        warnings,
        [
            "6 edges (`:E2_w0`, `:N_w0`, `:N2_w0`, `:S_w0`, `:S2_w0`, …) of the network (crossings or walking areas) \
          enclose no area, so no crosswalk or area"
        ]
    );
}
