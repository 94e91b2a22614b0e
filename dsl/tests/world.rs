//! World sections: what the compiler resolves, and the errors it reports.

use sightline_dsl::{Experiment, Motion, Options, World, compile};

/// A T junction: a main road and a roundabout joined by an arm.
const WORLD: &str = "sightline: 1
name: t
time: { duration: 10, step: 0.1 }
grid: { origin: [-50, -50], size: [100, 100], cell: 0.5 }
roads:
  - { id: ring, roundabout: { center: [0, 0], radius: 10 }, speed_limit: 6 }
  - { id: arm_in, polyline: [[-1.75, 45], [-1.75, 10.3]], speed_limit: 12 }
  - { id: arm_out, polyline: [[1.75, 10.3], [1.75, 45]], speed_limit: 12 }
  - { id: east_out, polyline: [[10.3, -1.75], [45, -1.75]], speed_limit: 12 }
sensor_models:
  lidar: { range: 40 }
agents:
  - { id: ego, kind: car, route: [arm_in, ring, east_out], speed: { target: 8 }, connected: true, sensors: [lidar] }
  - { id: cav, kind: car, route: [arm_in, ring, arm_out], start: { time: 2 }, speed: { target: 8 }, connected: true, sensors: [lidar] }
  - { id: rsu, kind: rsu, position: [15, 15], sensors: [lidar], connected: true }
  - { id: walker, kind: pedestrian, path: [[-8, 20], [8, 20]], speed: { target: 1.4 } }
perception: { ego: ego }
";

fn world(text: &str) -> World {
    let scenario = compile("w.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    let Experiment::World(world) = scenario.points[0].setup.experiment.clone() else {
        panic!("a world scenario")
    };
    *world
}

fn first_error(text: &str) -> String {
    compile("w.yaml", text, &Options::default())
        .expect_err("the file is invalid")
        .0[0]
        .to_string()
}

#[test]
fn routes_resolve_into_one_polyline_through_the_roundabout() {
    let world = world(WORLD);
    assert_eq!((world.steps, world.step), (100, 0.1));
    let Motion::Along { path, limits, .. } = &world.agents[0].motion else {
        panic!("the ego follows a route")
    };
    // From (−1.75, 45) down the arm (34.7 m), a quarter turn counter-clockwise
    // around the ring (r = 10) from about 100° to about 350°, then 34.7 m east.
    let turn = std::f64::consts::TAU * 10.0 * (250.0 / 360.0);
    assert!((path.length() - (34.7 + turn + 34.7)).abs() < 1.5, "{}", path.length());
    assert_eq!(path.start(), [-1.75, 45.0]);
    assert_eq!(path.end(), [45.0, -1.75]);
    assert_eq!(limits.iter().map(|l| l.1).collect::<Vec<_>>(), vec![12.0, 6.0, 12.0]);
    // The ego first, then the connected agents with sensors in file order.
    assert_eq!(world.perception.as_ref().unwrap().cooperating, vec![0, 1, 2]);
    assert_eq!(world.perception.as_ref().unwrap().snapshot_step, 50);
    assert!(matches!(world.agents[2].motion, Motion::Fixed { .. }));
}

/// `arm_in` ends at (−1.75, 10.3); the closest point of `east_out` is its start
/// (10.3, −1.75), 12.05·√2 = 17.04 m away. The error points at `east_out` in the route.
#[test]
fn a_route_that_does_not_connect_is_reported_at_its_road() {
    let text = WORLD.replace("route: [arm_in, ring, east_out]", "route: [arm_in, east_out]");
    assert_eq!(
        first_error(&text),
        "w.yaml:13:43: error: agents[0].route[1]: road `arm_in` does not connect to `east_out`: they are \
         17.04 m apart where one should join the other (at most the lane width, 3.5 m)"
    );
}

#[test]
fn unknown_roads_sensors_and_ego_are_dangling_references() {
    let road = first_error(&WORLD.replace("[arm_in, ring, east_out]", "[arm_in, ring, east]"));
    assert!(
        road.contains("agents[0].route[2]: no road `east` (it has ring, arm_in, arm_out, east_out)"),
        "{road}"
    );
    let sensor = first_error(&WORLD.replace(
        "sensors: [lidar], connected: true }",
        "sensors: [lidr], connected: true }",
    ));
    assert!(
        sensor.contains(
            "agents[2].sensors[0]: no sensor model `lidr` in `sensor_models` (it has lidar; did you mean `lidar`?)"
        ),
        "{sensor}"
    );
    let ego = first_error(&WORLD.replace("ego: ego", "ego: eog"));
    assert!(
        ego.contains("perception.ego: no agent `eog` (it has ego, cav, rsu, walker; did you mean `ego`?)"),
        "{ego}"
    );
}

#[test]
fn a_route_cannot_end_on_a_roundabout() {
    let text = WORLD.replace("[arm_in, ring, east_out]", "[arm_in, ring]");
    assert!(first_error(&text).contains("a route cannot end on a roundabout"));
}

#[test]
fn cooperating_counts_only_connected_agents_with_sensors() {
    let error = first_error(&WORLD.replace("perception: { ego: ego }", "perception: { ego: ego, cooperating: 4 }"));
    assert!(
        error.contains("expected from 1 to 3 (the ego and 2 connected agents with sensors), found 4"),
        "{error}"
    );
    let two = world(&WORLD.replace("perception: { ego: ego }", "perception: { ego: ego, cooperating: 2 }"));
    assert_eq!(two.perception.as_ref().unwrap().cooperating, vec![0, 1]);
}

#[test]
fn each_kind_moves_its_own_way() {
    let error = first_error(&WORLD.replace("kind: pedestrian, path:", "kind: car, path:"));
    assert!(
        error.ends_with("agents[3]: an agent of kind car moves by `route` or `trace`, not by `path`"),
        "{error}"
    );
    let error = first_error(&WORLD.replace("kind: rsu, position: [15, 15]", "kind: rsu"));
    assert!(
        error.ends_with("agents[2]: an agent of kind rsu moves by `position`"),
        "{error}"
    );
    let error = first_error(&WORLD.replace("kind: pedestrian, path:", "kind: pedestrian, trace: ped0, path:"));
    assert!(
        error.ends_with("agents[3]: an agent of kind pedestrian moves by `path` or `route` or `trace`, not by both"),
        "{error}"
    );
}

#[test]
fn a_field_and_a_world_do_not_mix() {
    let text = format!(
        "{WORLD}field:\n  truth: {{ occupied_fraction: 0.1 }}\n  sensors: {{ range: 10, layout: {{ regular: {{ rows: 1, cols: 1 }} }} }}\n  masses: {{ gamma: 5 }}\n"
    );
    let error = first_error(&text);
    assert!(
        error.contains("has no effect: it belongs to a world, and the scenario simulates the field experiment"),
        "{error}"
    );
}

#[test]
fn world_metrics_are_refused_in_the_field_and_field_metrics_in_worlds() {
    let text =
        format!("{WORLD}requirements:\n  - {{ id: A, text: x, check: {{ metric: accuracy, at_least: 0.9 }} }}\n");
    assert!(first_error(&text).contains("metric `accuracy` is not measured in a world scenario"));
}

fn compiled(text: &str, options: &Options<'_>) -> sightline_dsl::Scenario {
    compile("w.yaml", text, options).unwrap_or_else(|e| panic!("{e}"))
}

/// See: issue 6 §2. No `record` section and no `--record`: nothing is recorded.
#[test]
fn without_a_record_section_nothing_is_recorded() {
    assert_eq!(compiled(WORLD, &Options::default()).record, None);
}

/// `--record` without a section records the first point with a grid a second.
#[test]
fn the_record_flag_records_the_first_point_with_the_defaults() {
    let options = Options {
        record: true,
        ..Default::default()
    };
    let record = compiled(WORLD, &options).record.expect("recorded");
    assert_eq!((record.point, record.grid_rate, record.grid_every), (0, 1.0, Some(10)));
    assert!(!record.agent_grids);
    assert!(record.grids_at(0) && record.grids_at(20) && !record.grids_at(5));
}

/// `where` picks the first matching point; a rate of 0 records no grid.
#[test]
fn record_where_selects_the_first_matching_point() {
    let text = format!(
        "{WORLD}sweep: {{ perception.cooperating: [1, 2, 3] }}\nrecord: {{ where: {{ perception.cooperating: 2 }}, grid_rate: 0 }}\n"
    );
    let record = compiled(&text, &Options::default()).record.expect("recorded");
    assert_eq!((record.point, record.grid_every, record.agent_grids), (1, None, false));
    assert!(!record.grids_at(0));
}

/// With no grid recorded (`grid_rate: 0`), `agent_grids: true` would record
/// none either: refused at its key.
#[test]
fn agent_grids_without_grids_have_no_effect() {
    let text = format!("{WORLD}record: {{ grid_rate: 0, agent_grids: true }}\n");
    assert_eq!(
        first_error(&text),
        "w.yaml:18:25: error: record.agent_grids: has no effect: `grid_rate: 0` records no grid, so no agent's grid either"
    );
    let text = format!("{WORLD}record: {{ grid_rate: 0.5, agent_grids: true }}\n");
    assert!(compiled(&text, &Options::default()).record.unwrap().agent_grids);
}

/// Exact measurements (both σ 0) make every estimate the true pose: the
/// filter, its process noise and its odometry are refused at their keys, and
/// accepted again when a sweep makes the measurements noisy at some point.
#[test]
fn exact_localization_refuses_the_filter_keys() {
    for key in [
        "filter: none",
        "filter: kalman",
        "process_position_sigma: 5",
        "process_heading_sigma_deg: 5",
        "odometry: { speed_bias: 0.1, yaw_rate_bias_deg: 5, speed_sigma: 1 }",
    ] {
        let text = format!("{WORLD}localization: {{ position_sigma: 0, heading_sigma_deg: 0, {key} }}\n");
        let name = key.split(':').next().unwrap();
        assert_eq!(
            first_error(&text),
            format!(
                "w.yaml:18:58: error: localization.{name}: has no effect: `position_sigma` and \
                 `heading_sigma_deg` are 0: every estimate is the true pose, whatever the filter and its odometry"
            ),
        );
        let swept = format!("{text}sweep: {{ localization.heading_sigma_deg: [0, 1] }}\n")
            .replace("heading_sigma_deg: 0, ", "");
        compiled(&swept, &Options::default());
    }
    // Either σ alone makes the filter work.
    world(&format!(
        "{WORLD}localization: {{ position_sigma: 0.1, filter: none }}\n"
    ));
    world(&format!(
        "{WORLD}localization: {{ heading_sigma_deg: 0.1, filter: none }}\n"
    ));
}

#[test]
fn record_errors_are_located() {
    let text = format!("{WORLD}record: {{ point: 3 }}\n");
    assert_eq!(
        first_error(&text),
        "w.yaml:18:18: error: record.point: expected a point index below 1 (the scenario has 1 sweep point), found 3"
    );
    let text = format!("{WORLD}record: {{ grid_rate: 20 }}\n");
    assert_eq!(
        first_error(&text),
        "w.yaml:18:22: error: record.grid_rate: expected at most the step rate, 10 Hz (one grid per step), found 20"
    );
    let text = format!("{WORLD}record: {{ point: 0, where: {{ seed: 0 }} }}\n");
    assert!(first_error(&text).contains("give `point` (an index) or `where` (settings), not both"));
}

/// The `start_time` and `target_speed` of agent `id` at every sweep point.
fn motions(text: &str, id: &str) -> Vec<(f64, f64)> {
    let scenario = compile("w.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    scenario
        .points
        .iter()
        .map(|point| {
            let Experiment::World(world) = &point.setup.experiment else {
                panic!("a world scenario")
            };
            let agent = world.agents.iter().find(|a| a.id == id).expect("the agent");
            let Motion::Along {
                start_time,
                target_speed,
                ..
            } = agent.motion
            else {
                panic!("{id} moves along a path")
            };
            (start_time, target_speed)
        })
        .collect()
}

#[test]
fn a_sweep_sets_an_agent_named_by_its_id() {
    // The sweep gives cav's start and speed: the file leaves them out.
    let world = WORLD.replace("start: { time: 2 }, speed: { target: 8 }, connected", "connected");
    assert_ne!(world, WORLD);
    let text = format!("{world}sweep:\n  agents.cav.start.time: [0, 5]\n  agents.cav.speed.target: [4, 8]\n");
    assert_eq!(motions(&text, "cav"), [(0.0, 4.0), (0.0, 8.0), (5.0, 4.0), (5.0, 8.0)]);
    assert_eq!(
        motions(&text, "ego"),
        [(0.0, 8.0); 4],
        "the other agents keep their settings"
    );

    let filtered = format!(
        "{text}requirements:\n  - {{ id: R, text: t, where: {{ agents.cav.speed.target: 8 }}, check: {{ invariant: mass_function }} }}\n"
    );
    let scenario = compile("w.yaml", &filtered, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        scenario.requirements[0].points,
        [1, 3],
        "`where` names the agent as the sweep does"
    );
}

#[test]
fn vary_instantiates_an_agent_named_by_its_id() {
    use sightline_dsl::{Vary, instantiate};
    let text = format!(
        "{WORLD}vary:\n  agents.walker.start.time: [0, 4]\n  agents.walker.speed.target: {{ one_of: [1.4, 2.5] }}\n"
    );
    let scenario = compile("w.yaml", &text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scenario.vary[0].path, "agents.walker.start.time");
    let case = instantiate("w.yaml", &text, &Vary::settings(&scenario.vary, &[500, 1])).unwrap();
    assert_eq!(motions(&case, "walker"), [(2.0, 2.5)]);
    assert_eq!(motions(&case, "cav"), [(2.0, 8.0)]);
}

#[test]
fn an_agent_setting_must_name_an_agent_and_a_setting() {
    for (key, message) in [
        (
            "agents.kav.speed.target",
            "`agents.kav.speed.target` names no agent: `kav` is not the id of an entry of `agents` (did you mean `cav`?)",
        ),
        (
            "agents.cav",
            "`agents.cav` names an agent, not one of its settings (such as `agents.cav.speed.target`)",
        ),
        ("agents.cav.id", "an agent's id names it; it cannot be swept or varied"),
        (
            "agents.cav.speed.tar",
            "`agents.cav.speed` has `acceleration`, `initial`, `limit_factor`, `target`",
        ),
    ] {
        let error = first_error(&format!("{WORLD}sweep:\n  {key}: [1]\n"));
        assert!(error.contains(message), "{key}: {error}");
    }
}

/// See: issue 13 §6. The roundabout's first six studies meet where six
/// vehicles cooperate at the nominal noise (σ = 0.2 m) with noisy odometry
/// over the nominal radio (the file's values): 17 distinct configurations, not
/// 22, the shared one labelled by every sweep, and the requirements at that
/// configuration checked once. The seventh (zero noise) adds two of its own.
#[test]
fn the_roundabout_sweeps_meet_at_one_point() {
    let text = include_str!("../../scenarios/roundabout-six-agents.yaml");
    let scenario = compile("roundabout.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scenario.points.len(), 19);
    assert_eq!(scenario.sweeps[0].points, [0, 1, 2, 3, 4, 5]);
    assert_eq!(scenario.sweeps[1].points, [6, 7, 5, 8, 9, 10]);
    assert_eq!(scenario.sweeps[2].points, [11, 5]);
    assert_eq!(scenario.sweeps[3].points, [12, 5]);
    assert_eq!(scenario.sweeps[4].points, [5, 13, 14]);
    assert_eq!(scenario.sweeps[5].points, [15, 16, 5]);
    assert_eq!(scenario.sweeps[6].points, [17, 18]);
    assert_eq!(
        scenario.points[5].label(),
        "v2x.penetration=1 | localization.position_sigma=0.2 | localization.odometry.model=noisy | \
         v2x.channel.model=tr36885_urban | v2x.latency=0.02 | v2x.messages.max_age=1"
    );
    let nominal = scenario
        .requirements
        .iter()
        .find(|r| r.id == "RB-REC-06")
        .expect("RB-REC-06");
    assert_eq!(nominal.points, [5]);
    let noise = scenario
        .requirements
        .iter()
        .find(|r| r.id == "RB-NOISE-01")
        .expect("RB-NOISE-01");
    // Noisy odometry only: the exact-odometry point is a comparison.
    assert_eq!(noise.points, [5, 6, 7, 8, 9, 10]);
    let every = scenario
        .requirements
        .iter()
        .find(|r| r.id == "RB-PREC-01")
        .expect("RB-PREC-01");
    // Restated over the radio: the nominal point.
    assert_eq!(every.points, [5]);
}
