//! A world replaying the SUMO run in `scenarios/sumo`: collective perception
//! between two traced vehicles (who is connected in a semantic run is tested
//! beside the traffic model, engine/src/semantic/traffic.rs).

use std::path::Path;

use sightline_dsl::{Metric, Options, Scenario, compile};
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
