//! Worlds replaying the SUMO run in `scenarios/sumo`: collective perception
//! between two traced vehicles, and who is connected in a semantic run.

use std::path::Path;

use sightline_dsl::{AgentKind, Experiment, Metric, Options, Scenario, World, compile};
use sightline_engine::{Outcome, simulate};

/// A scenario file in `scenarios/`, so that `sumo/…` names the fixture.
const FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios/traces-engine-test.yaml");

fn scenario(text: &str) -> Scenario {
    let disk = |path: &Path| std::fs::read(path);
    let options = Options {
        loader: Some(&disk),
        ..Default::default()
    };
    compile(FILE, text, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// From the trace's 30 s: the ego (SUMO's veh7) drives south towards junction B1
/// at (100, 100), which the bus (veh4) crosses at about 32 s.
const PERCEPTION: &str = "sightline: 1
name: traced perception
time: { duration: 8, step: 0.2 }
grid: { origin: [40, 40], size: [120, 120], cell: 1 }
traces: { fcd: sumo/grid3x3.fcd.xml, net: sumo/grid3x3.net.xml, poly: sumo/grid3x3.poly.xml, begin: 30 }
sensor_models:
  lidar: { range: 60 }
agents:
  - { id: ego, kind: car, trace: veh7, connected: true, sensors: [lidar] }
  - { id: bus, kind: bus, trace: veh4, connected: true, sensors: [lidar] }
perception: { ego: ego }
fusion: { method: bayes }
decision: { threshold: 0 }
";

#[test]
fn traced_vehicles_share_perception_of_traced_traffic() {
    let run = simulate(&scenario(PERCEPTION));
    let Outcome::World(outcome) = &run.points[0] else {
        panic!("a perception world")
    };
    let metrics = &outcome.metrics;
    // The ego is in the scene at every step of the 8 s.
    assert_eq!(metrics.steps, 40);
    assert!(metrics.occupied > 0, "traced traffic occupies cells");
    assert!(metrics.value(Metric::OccupiedRecall).unwrap() > 0.5);
    assert!(metrics.blind_detected > 0, "the bus shows the ego what it cannot see");
    assert!(metrics.value(Metric::FovGain).unwrap() > 0.0);
    assert_eq!(metrics.localization_error, Some(0.0));
}

const SEMANTIC: &str = "sightline: 1
name: traced semantic
time: { duration: 60, step: 0.1 }
traces: { fcd: sumo/grid3x3.fcd.xml, net: sumo/grid3x3.net.xml }
sensor_models:
  front: { range: 80, fov_deg: 70 }
agents:
  - { id: ego, kind: car, trace: veh7, connected: true, sensors: [front] }
  - { id: rsu, kind: rsu, position: [93.5, 93.5], sensors: [front] }
v2x: { penetration: {p} }
semantic: { ego: ego }
";

fn world(penetration: f64) -> World {
    let scenario = scenario(&SEMANTIC.replace("{p}", &penetration.to_string()));
    let Experiment::World(world) = &scenario.points[0].setup.experiment else {
        panic!("a world")
    };
    (**world).clone()
}

/// Imported vehicles are connected with probability `v2x.penetration`, imported
/// pedestrians never; declared agents keep what they declare.
#[test]
fn imported_vehicles_are_connected_at_the_penetration_rate() {
    let connected = |penetration: f64| {
        let world = world(penetration);
        let agents = sightline_engine::semantic::scene(7, &world);
        assert_eq!(
            agents.len(),
            world.agents.len(),
            "no traffic section, nothing generated"
        );
        assert!(
            agents[0].connected && !agents[1].connected,
            "declared agents keep what they declare"
        );
        agents[2..]
            .iter()
            .map(|a| (a.kind == AgentKind::Pedestrian, a.connected))
            .collect::<Vec<_>>()
    };
    let none = connected(0.0);
    assert_eq!(none.len(), 23);
    assert!(none.iter().all(|&(_, connected)| !connected));
    assert!(
        connected(1.0)
            .iter()
            .all(|&(pedestrian, connected)| connected != pedestrian)
    );
    let half = connected(0.5);
    let vehicles = half.iter().filter(|&&(pedestrian, _)| !pedestrian).count();
    let drawn = half.iter().filter(|&&(_, connected)| connected).count();
    assert!(0 < drawn && drawn < vehicles, "{drawn} of {vehicles}");
    assert_eq!(half, connected(0.5), "the draw is seeded");
}
