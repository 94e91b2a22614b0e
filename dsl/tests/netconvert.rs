//! The SUMO importer on what SUMO itself writes (issue 19): a signalised
//! junction and a three-arm roundabout built from plain XML by `netconvert`
//! (sidewalks and crossings guessed), simulated by `sumo` from a `.sumocfg`,
//! and imported through it.
//!
//! Runs Eclipse SUMO from the venv of the Python that `SIGHTLINE_SUMO_PYTHON`
//! names (`python3 -m venv v && v/bin/pip install eclipse-sumo==1.28.0`, as
//! `.ci/run` does). Skipped without it, unless `CI` is set: then it fails.

use std::path::{Path, PathBuf};
use std::process::Command;

use sightline_dsl::{AgentKind, Experiment, Motion, Options, Scenario, World, compile};

const PYTHON_VAR: &str = "SIGHTLINE_SUMO_PYTHON";

const NODES: &str = r#"<nodes>
    <node id="T" x="0" y="0" type="traffic_light"/>
    <node id="W" x="-100" y="0"/>
    <node id="N" x="0" y="100"/>
    <node id="S" x="0" y="-100"/>
    <node id="R0" x="135" y="0" type="priority"/>
    <node id="R1" x="157.5" y="-12.99" type="priority"/>
    <node id="R2" x="157.5" y="12.99" type="priority"/>
    <node id="SE" x="200" y="-80"/>
    <node id="NE" x="200" y="80"/>
</nodes>"#;

const EDGES: &str = r#"<edges>
    <edge id="WT" from="W" to="T" numLanes="1" speed="13.89"/>
    <edge id="TW" from="T" to="W" numLanes="1" speed="13.89"/>
    <edge id="NT" from="N" to="T" numLanes="1" speed="13.89"/>
    <edge id="TN" from="T" to="N" numLanes="1" speed="13.89"/>
    <edge id="ST" from="S" to="T" numLanes="1" speed="13.89"/>
    <edge id="TS" from="T" to="S" numLanes="1" speed="13.89"/>
    <edge id="RT" from="R0" to="T" numLanes="1" speed="13.89"/>
    <edge id="TR" from="T" to="R0" numLanes="1" speed="13.89"/>
    <edge id="r01" from="R0" to="R1" numLanes="1" speed="8.33"/>
    <edge id="r12" from="R1" to="R2" numLanes="1" speed="8.33"/>
    <edge id="r20" from="R2" to="R0" numLanes="1" speed="8.33"/>
    <edge id="R1SE" from="R1" to="SE" numLanes="1" speed="13.89"/>
    <edge id="SER1" from="SE" to="R1" numLanes="1" speed="13.89"/>
    <edge id="R2NE" from="R2" to="NE" numLanes="1" speed="13.89"/>
    <edge id="NER2" from="NE" to="R2" numLanes="1" speed="13.89"/>
    <roundabout nodes="R0 R1 R2" edges="r01 r12 r20"/>
</edges>"#;

const ROUTES: &str = r#"<routes>
    <vType id="van" vClass="delivery" guiShape="delivery"/>
    <vType id="bike" vClass="bicycle"/>
    <vType id="coach" vClass="coach" length="13.5"/>
    <vType id="walker" vClass="pedestrian"/>
    <flow id="vans" type="van" begin="0" end="40" period="5" from="WT" to="R1SE"/>
    <personFlow id="walkers" type="walker" begin="0" end="40" period="4" departPos="70">
        <walk from="WT" to="TS"/>
    </personFlow>
    <flow id="bikes" type="bike" begin="1" end="40" period="6" from="NT" to="TW"/>
    <flow id="coaches" type="coach" begin="2" end="40" period="20" from="NER2" to="TS"/>
</routes>"#;

const ADDITIONAL: &str = r#"<additional>
    <poi id="rsu_T" type="rsu" x="-9" y="-9"><param key="height" value="6.5"/></poi>
    <poi id="rsu_lane" type="rsu" lane="TR_1" pos="-10" posLat="-5"/>
    <poi id="bench" type="bench" x="20" y="20"/>
</additional>"#;

const CONFIG: &str = r#"<configuration>
    <input>
        <net-file value="net/n.net.xml"/>
        <route-files value="n.rou.xml"/>
        <additional-files value="n.add.xml"/>
    </input>
    <time><begin value="0"/><end value="40"/><step-length value="0.1"/></time>
    <output>
        <fcd-output value="out/n.fcd.xml"/>
        <fcd-output.attributes value="x,y,angle,type,speed,lane,vehicle"/>
    </output>
    <random_number><seed value="7"/></random_number>
    <report><no-step-log value="true"/></report>
</configuration>"#;

const SCENARIO: &str = "sightline: 1
name: netconvert
time: { duration: 30, step: 0.1 }
traces:
  sumocfg: sim/n.sumocfg
  begin: 5
  rsus: { poi_type: rsu, sensors: [around] }
sensor_models:
  front: { range: 80, fov_deg: 70 }
  around: { range: 100 }
agents:
  - { id: ego, kind: car, trace: vans.0, connected: true, sensors: [front] }
semantic: { ego: ego }
";

/// The directory of SUMO's programs, or `None` (skipped) without
/// `SIGHTLINE_SUMO_PYTHON` outside CI.
fn sumo_bin() -> Option<PathBuf> {
    let Some(python) = std::env::var_os(PYTHON_VAR) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "{PYTHON_VAR} is not set in CI; .ci/run sets it to a Python with eclipse-sumo==1.28.0"
        );
        eprintln!(
            "skipped: {PYTHON_VAR} is not set; set it to a Python with Eclipse SUMO \
             (python3 -m venv v && v/bin/pip install eclipse-sumo==1.28.0), as .ci/run does"
        );
        return None;
    };
    Some(
        Path::new(&python)
            .parent()
            .expect("a python in a venv's bin")
            .to_path_buf(),
    )
}

fn run(bin: &Path, program: &str, dir: &Path, args: &[&str]) {
    let output = Command::new(bin.join(program))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {program}: {e}"));
    assert!(
        output.status.success(),
        "{program} failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Builds the network and runs the simulation in a fresh directory, and
/// compiles the scenario beside it.
fn simulate(bin: &Path) -> Scenario {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("netconvert");
    let _ = std::fs::remove_dir_all(&dir);
    let sim = dir.join("sim");
    for sub in ["net", "out"] {
        std::fs::create_dir_all(sim.join(sub)).unwrap();
    }
    for (name, text) in [
        ("n.nod.xml", NODES),
        ("n.edg.xml", EDGES),
        ("n.rou.xml", ROUTES),
        ("n.add.xml", ADDITIONAL),
        ("n.sumocfg", CONFIG),
    ] {
        std::fs::write(sim.join(name), text).unwrap();
    }
    run(
        bin,
        "netconvert",
        &sim,
        &[
            "-n",
            "n.nod.xml",
            "-e",
            "n.edg.xml",
            "--sidewalks.guess",
            "--crossings.guess",
            "--no-turnarounds",
            "--offset.disable-normalization",
            "-o",
            "net/n.net.xml",
        ],
    );
    run(bin, "sumo", &sim, &["-c", "n.sumocfg"]);
    let file = dir.join("s.yaml");
    let disk = |path: &Path| std::fs::read(path);
    let options = Options {
        loader: Some(&disk),
        ..Default::default()
    };
    compile(&file.display().to_string(), SCENARIO, &options).unwrap_or_else(|e| panic!("{e}"))
}

fn world(scenario: &Scenario) -> &World {
    let Experiment::World(world) = &scenario.points[0].setup.experiment else {
        panic!("a world scenario")
    };
    world
}

#[test]
fn a_netconvert_network_and_a_sumo_run_import_whole() {
    let Some(bin) = sumo_bin() else { return };
    let scenario = simulate(&bin);
    let world = world(&scenario);

    // Every junction where paths meet: the signalised one and the three of the
    // roundabout, each entered by the ring and one arm.
    let mut areas: Vec<&str> = world.interaction_areas.iter().map(|a| a.id.as_str()).collect();
    areas.sort_unstable();
    assert_eq!(areas, ["R0", "R1", "R2", "T"]);

    // Four crossings at T, one on each roundabout arm.
    let mut crosswalks: Vec<&str> = world.crosswalks.iter().map(|c| c.id.as_str()).collect();
    crosswalks.sort_unstable();
    assert_eq!(
        crosswalks,
        [":R0_c0", ":R1_c0", ":R2_c0", ":T_c0", ":T_c1", ":T_c2", ":T_c3"]
    );

    // The guessed sidewalks (lane 0) are no lanes of the roads.
    for road in &world.roads {
        assert_eq!((road.lanes.len(), road.lane_width), (1, 3.2), "{}", road.id);
    }

    // Sizes from the types, SUMO's class defaults where a type gives none.
    let body = |prefix: &str| {
        let agent = world.agents.iter().find(|a| a.id.starts_with(prefix)).unwrap();
        (agent.kind, agent.length, agent.width)
    };
    assert_eq!(body("vans."), (AgentKind::Truck, 6.5, 2.16));
    assert_eq!(body("bikes."), (AgentKind::Bicycle, 1.6, 0.65));
    assert_eq!(body("coaches."), (AgentKind::Bus, 13.5, 2.6));
    assert_eq!(body("walkers."), (AgentKind::Pedestrian, 0.215, 0.478));

    // The points of interest of type `rsu`: one at x, y with its height, one
    // 10 m before the end of lane TR_1 and 5 m to its right (TR runs east at
    // y = -1.6, so at y = -6.6), at the channel's height.
    let rsus: Vec<_> = world
        .agents
        .iter()
        .filter(|a| a.kind == AgentKind::Rsu)
        .map(|a| (a.id.as_str(), a.motion.clone(), a.antenna_m))
        .collect();
    assert_eq!(rsus.len(), 2);
    assert_eq!(
        rsus[0],
        (
            "rsu_T",
            Motion::Fixed {
                position: [-9.0, -9.0],
                heading: 0.0
            },
            Some(6.5)
        )
    );
    let Motion::Fixed { position, .. } = rsus[1].1 else {
        panic!("standing")
    };
    assert_eq!((rsus[1].0, rsus[1].2), ("rsu_lane", None));
    assert!(
        (position[1] + 6.6).abs() < 1e-6 && (100.0..135.0).contains(&position[0]),
        "{position:?}"
    );

    // What is left out is said: the bench, and the walking areas at the dead ends.
    let warnings: Vec<&str> = scenario.warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(
        warnings
            .iter()
            .any(|w| w.starts_with("1 point of interest of type `bench`")),
        "{warnings:?}"
    );
    assert!(world.uncovered.is_none(), "{warnings:?}");
}
