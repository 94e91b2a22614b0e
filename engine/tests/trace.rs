//! The per-step run record (issue 3): recording changes nothing, the steps add up
//! to the run's metrics, grids come only when asked for, and the recorded states
//! are the simulated ones.

mod common;

use std::collections::BTreeSet;

use approx::assert_relative_eq;
use common::in_pool;
use sightline_dsl::{Agent, AgentKind, Experiment, Motion, Scenario, World, compile};
use sightline_engine::internals::{Kinematics, in_view};
use sightline_engine::outcome::{CellTally, SemanticMetrics, Sightings, State, WorldOutcome};
use sightline_engine::trace::Visibility::{Los, NlosDynamic, NlosStatic};
use sightline_engine::trace::{
    AgentState, Approach, Arrival, Item, Packet, PacketKind, Pose, SemanticStep, Sighting, WorldStep, mount_pose,
};
use sightline_engine::{
    Outcome, TraceSink, shares_one_simulation, simulate, simulate_point, simulate_traced, simulate_traced_all,
    simulate_traced_each,
};

/// The bundled roundabout, 14 s long (the snapshot stays at 12 s), all six
/// vehicles cooperating, fused by Bayes (point 0) and Dempster (point 1): one
/// shared-data group of two jobs.
fn roundabout() -> Scenario {
    let text = include_str!("../../scenarios/roundabout-six-agents.yaml");
    let head = &text[..text.find("\nsweeps:").expect("the roundabout has sweeps")];
    // The sweep gives the fusion: the file's would be refused.
    let text = head
        .replace("duration: 30", "duration: 14")
        .replace("\nfusion: { method: bayes }\n", "\n")
        + "\nsweep:\n  fusion:\n    - { method: bayes }\n    - { method: dempster }\n";
    compile("roundabout.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The bundled urban junction, 80 s long (the ego reaches the junction after
/// 60 s), with half the generated road users connected so that direct packets are
/// sent too, and a receiver sensitivity of −70 dBm instead of −90 so that packets
/// from 100 m away are lost; one run, its shares over every cycle (so that every
/// message sent counts), and a d_min of 6 m so that close approaches happen.
fn urban() -> Scenario {
    let text = include_str!("../../scenarios/urban-rsu-semantic.yaml")
        .replace("duration: 120", "duration: 80")
        .replace("penetration: 0 ", "penetration: 0.5 ")
        .replace("sensitivity_dbm: -90", "sensitivity_dbm: -70")
        .replace("runs: 5 ", "runs: 1\n  shares_over: all ")
        .replace("d_min: 2", "d_min: 6");
    compile("urban.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn world_of(scenario: &Scenario) -> &World {
    match &scenario.points[0].setup.experiment {
        Experiment::World(world) => world,
        Experiment::Field(_) => panic!("a world scenario"),
    }
}

/// One cooperating agent's part of a recorded world step.
#[derive(Debug, Clone, PartialEq)]
struct CooperatorRecord {
    agent: usize,
    estimate: Pose,
    sighted: Vec<Sighting>,
    sightings: Sightings,
}

/// A fused grid as recorded: (cells, probabilities, uncertainties).
type GridRecord = (Vec<usize>, Vec<f32>, Vec<f32>);

/// What a world step measured, owned.
#[derive(Debug, Clone, PartialEq)]
struct MeasuredRecord {
    ego_observed: u64,
    joint_observed: u64,
    /// Per job: the step's tallies and the grid when asked for.
    fused: Vec<(CellTally, Option<GridRecord>)>,
}

/// A world step, owned.
#[derive(Debug, Clone, PartialEq)]
struct WorldRecord {
    step: usize,
    time: f64,
    agents: Vec<Option<AgentState>>,
    cooperators: Vec<CooperatorRecord>,
    measured: Option<MeasuredRecord>,
}

/// A semantic step, owned.
#[derive(Debug, Clone, PartialEq)]
struct SemanticRecord {
    step: usize,
    time: f64,
    agents: Vec<Option<AgentState>>,
    packets: Vec<Packet>,
    arrivals: Vec<Arrival>,
    approaches: Vec<Approach>,
    min_time_to_conflict: Option<f64>,
}

/// Keeps every step, and grids at `grid_steps`.
#[derive(Debug, Default, PartialEq)]
struct Recorder {
    grid_steps: BTreeSet<usize>,
    asked: Vec<usize>,
    agents: Vec<Agent>,
    world: Vec<WorldRecord>,
    semantic: Vec<SemanticRecord>,
}

impl Recorder {
    fn asking_grids_at(steps: &[usize]) -> Self {
        Self {
            grid_steps: steps.iter().copied().collect(),
            ..Self::default()
        }
    }
}

impl TraceSink for Recorder {
    fn start(&mut self, agents: &[Agent]) {
        assert!(self.agents.is_empty(), "start is called once");
        self.agents = agents.to_vec();
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.grid_steps.contains(&step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.world.push(WorldRecord {
            step: step.step,
            time: step.time,
            agents: step.agents.to_vec(),
            cooperators: step
                .cooperators
                .iter()
                .map(|c| CooperatorRecord {
                    agent: c.agent,
                    estimate: c.estimate,
                    sighted: c.observation.sighted().to_vec(),
                    sightings: c.observation.sightings,
                })
                .collect(),
            measured: step.measured.map(|m| MeasuredRecord {
                ego_observed: m.ego_observed,
                joint_observed: m.joint_observed,
                fused: m
                    .fused
                    .iter()
                    .map(|f| {
                        let grid = f
                            .grid
                            .map(|g| (g.cells.to_vec(), g.probability.to_vec(), g.uncertainty.to_vec()));
                        (f.cells, grid)
                    })
                    .collect(),
            }),
        });
        if step.measured.is_some() {
            self.asked.push(step.step);
        }
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.semantic.push(SemanticRecord {
            step: step.step,
            time: step.time,
            agents: step.agents.to_vec(),
            packets: step.packets.to_vec(),
            arrivals: step.arrivals.to_vec(),
            approaches: step.approaches.to_vec(),
            min_time_to_conflict: step.min_time_to_conflict(),
        });
    }
}

fn world_outcome(outcome: &Outcome) -> &WorldOutcome {
    match outcome {
        Outcome::World(world) => world,
        other => panic!("a perception world gives world outcomes, not {other:?}"),
    }
}

fn semantic_metrics(outcome: &Outcome) -> &SemanticMetrics {
    match outcome {
        Outcome::Semantic(metrics) => metrics,
        other => panic!("a semantic world gives semantic metrics, not {other:?}"),
    }
}

/// Each point of a shared-data group, run alone with a recording sink, gives the
/// outcome `simulate` gives it within the group; the record does not depend on the
/// thread count.
#[test]
fn recording_a_world_point_changes_neither_its_outcome_nor_with_threads() {
    let scenario = roundabout();
    let run = simulate(&scenario);
    for point in 0..2 {
        let recorded = |threads| {
            in_pool(threads, || {
                let mut recorder = Recorder::asking_grids_at(&[40]);
                (simulate_point(&scenario, point, &mut recorder), recorder)
            })
        };
        let (outcome, record) = recorded(1);
        assert_eq!(outcome, run.points[point], "point {point}");
        let (outcome_2, record_2) = recorded(2);
        assert_eq!(outcome_2, outcome);
        assert!(
            record_2 == record,
            "the record of point {point} depends on the thread count"
        );
    }
}

#[test]
fn recording_a_semantic_point_changes_nothing() {
    let scenario = urban();
    let run = simulate(&scenario);
    let mut recorder = Recorder::default();
    assert_eq!(simulate_point(&scenario, 1, &mut recorder), run.points[1]);
    assert!(!recorder.semantic.is_empty());
}

/// Recording one point of a whole run (what `sightline run` records, issue 6)
/// gives `simulate`'s run and the point's own record, even when the point shares
/// its data with another: the sink sees only its own fused grid.
#[test]
fn tracing_one_point_of_a_run_gives_the_run_and_that_points_record() {
    let scenario = roundabout();
    let run = simulate(&scenario);
    for point in 0..2 {
        let mut alone = Recorder::asking_grids_at(&[40]);
        simulate_point(&scenario, point, &mut alone);
        let mut traced = Recorder::asking_grids_at(&[40]);
        assert_eq!(
            simulate_traced(&scenario, point, &mut traced, &mut |_| {}),
            run,
            "point {point}"
        );
        assert!(traced == alone, "the record of point {point} differs within the run");
    }
}

/// Recording each point of a run to its own sink (what `sightline run` records
/// when every point shares one simulation, issue 18) gives `simulate`'s run,
/// simulated once, and each sink its point's own record, at one thread and at
/// three.
#[test]
fn tracing_each_point_of_a_shared_simulation_gives_the_run_and_each_points_record() {
    let scenario = roundabout();
    assert!(shares_one_simulation(&scenario));
    assert!(!shares_one_simulation(&urban()));
    let run = simulate(&scenario);
    let alone: Vec<Recorder> = (0..2)
        .map(|point| {
            let mut alone = Recorder::asking_grids_at(&[40]);
            simulate_point(&scenario, point, &mut alone);
            alone
        })
        .collect();
    assert!(alone[0] != alone[1], "the two fusion rules' grids differ");
    for threads in [1, 3] {
        let mut sinks = vec![Recorder::asking_grids_at(&[40]), Recorder::asking_grids_at(&[40])];
        let mut passes = 0;
        let traced = in_pool(threads, || {
            simulate_traced_each(&scenario, &mut sinks, &mut |points| {
                assert_eq!(points, [0, 1]);
                passes += 1;
            })
        });
        assert_eq!(traced, run, "{threads} threads");
        assert_eq!(passes, 1, "one simulation for both points");
        assert!(
            sinks == alone,
            "a point's record differs within the run, {threads} threads"
        );
    }
}

/// Each point's own record, as a run that records every point hands them over.
#[derive(Default)]
struct EveryPoint(Vec<(usize, Recorder)>);

impl EveryPoint {
    fn current(&mut self) -> &mut Recorder {
        &mut self.0.last_mut().expect("`point` comes before the steps").1
    }
}

impl TraceSink for EveryPoint {
    fn point(&mut self, point: usize) {
        self.0.push((point, Recorder::asking_grids_at(&[40])));
    }

    fn start(&mut self, agents: &[Agent]) {
        self.current().start(agents);
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.0.last().is_some_and(|(_, r)| r.wants_grids(step))
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.current().world_step(step);
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.current().semantic_step(step);
    }
}

/// Recording every point (`record.points: all`, issue 18) gives `simulate`'s
/// run, and point after point in order each point's own record, also for two
/// points that share their data.
#[test]
fn tracing_every_point_gives_the_run_and_each_points_record() {
    let scenario = roundabout();
    let mut every = EveryPoint::default();
    let mut done = 0;
    assert_eq!(
        simulate_traced_all(&scenario, &mut every, &mut |points| done += points.len()),
        simulate(&scenario)
    );
    assert_eq!(done, 2);
    assert_eq!(every.0.iter().map(|(p, _)| *p).collect::<Vec<_>>(), [0, 1]);
    for (point, record) in &every.0 {
        let mut alone = Recorder::asking_grids_at(&[40]);
        simulate_point(&scenario, *point, &mut alone);
        assert!(*record == alone, "the record of point {point} differs");
    }
}

/// Over the measured steps, the step records add up to the run's counts.
#[test]
fn world_steps_add_up_to_the_metrics() {
    let scenario = roundabout();
    let world = world_of(&scenario);
    for point in 0..2 {
        let mut recorder = Recorder::default();
        let outcome = simulate_point(&scenario, point, &mut recorder);
        let metrics = &world_outcome(&outcome).metrics;
        assert_eq!(recorder.world.len(), world.steps);
        let measured: Vec<&WorldRecord> = recorder.world.iter().filter(|r| r.measured.is_some()).collect();
        assert_eq!(measured.len() as u64, metrics.steps);

        let (mut cells, mut ego, mut joint, mut sightings) = (CellTally::default(), 0, 0, Sightings::default());
        for record in &measured {
            let measured = record.measured.as_ref().unwrap();
            assert_eq!(measured.fused.len(), 1, "one job per point");
            cells.add(&measured.fused[0].0);
            ego += measured.ego_observed;
            joint += measured.joint_observed;
            for cooperator in &record.cooperators {
                // The list and the counts say the same.
                let count = |v| cooperator.sighted.iter().filter(|s| s.visibility == v).count() as u64;
                let detected = cooperator.sighted.iter().filter(|s| s.detected.is_some()).count() as u64;
                assert_eq!(
                    (count(Los), count(NlosStatic), count(NlosDynamic), detected),
                    (
                        cooperator.sightings.los,
                        cooperator.sightings.nlos_static,
                        cooperator.sightings.nlos_dynamic,
                        cooperator.sightings.detected
                    )
                );
                sightings.add(cooperator.sightings);
            }
        }
        assert!(cells.occupied > 0 && cells.detected > 0 && cells.blind_occupied > 0 && cells.self_report > 0);
        let expected = CellTally {
            occupied: metrics.occupied,
            detected: metrics.detected,
            ego_detected: metrics.ego_detected,
            false_positives: metrics.false_positives,
            blind_occupied: metrics.blind_occupied,
            blind_detected: metrics.blind_detected,
            footprint_only: metrics.footprint_only,
            self_report: metrics.self_report,
            self_report_detected: metrics.self_report_detected,
            self_report_only: metrics.self_report_only,
        };
        assert_eq!(cells, expected, "point {point}");
        assert_eq!((ego, joint), (metrics.ego_observed, metrics.joint_observed));
        assert_eq!(sightings, metrics.sightings);
        assert!(sightings.detected > 0 && sightings.nlos_static > 0);
    }
}

/// Grids come at the steps asked for and nowhere else, one value per observed
/// cell; at the snapshot step they are the snapshot's.
#[test]
fn fused_grids_come_only_at_the_steps_asked_for() {
    let scenario = roundabout();
    let world = world_of(&scenario);
    let perception = world.perception.as_ref().unwrap();
    let cells = scenario.points[0].setup.occupancy.as_ref().unwrap().grid.cells();
    let asked = [0, 37, perception.snapshot_step];
    let mut recorder = Recorder::asking_grids_at(&asked);
    let outcome = simulate_point(&scenario, 0, &mut recorder);
    assert_eq!(
        recorder.asked,
        (0..world.steps).collect::<Vec<_>>(),
        "asked once per measured step"
    );

    let mut handed = Vec::new();
    for record in &recorder.world {
        let measured = record.measured.as_ref().unwrap();
        let Some((observed, probability, uncertainty)) = &measured.fused[0].1 else {
            continue;
        };
        handed.push(record.step);
        // The fused cells: those a sensor observed, and the self-reported
        // footprints no sensor did.
        assert!(observed.len() as u64 >= measured.joint_observed);
        assert_eq!(probability.len(), observed.len());
        assert_eq!(uncertainty.len(), observed.len());
        assert!(observed.iter().all(|&c| c < cells));
        assert!(probability.iter().chain(uncertainty).all(|v| (0.0..=1.0).contains(v)));
    }
    assert_eq!(handed, asked);

    let snapshot = world_outcome(&outcome).snapshot.as_ref().unwrap();
    let record = &recorder.world[perception.snapshot_step];
    let (observed, probability, uncertainty) = record.measured.as_ref().unwrap().fused[0].1.as_ref().unwrap();
    let mut expected = vec![None; cells];
    for ((&cell, &p), &u) in observed.iter().zip(probability).zip(uncertainty) {
        expected[cell] = Some((p, u));
    }
    let pictured: Vec<Option<(f32, f32)>> = snapshot
        .fused
        .iter()
        .map(|c| c.map(|c| (c.probability, c.uncertainty)))
        .collect();
    assert!(pictured == expected, "the grid at the snapshot step is the snapshot's");

    // The snapshot's decisions are those the step's metrics count.
    let time = perception.snapshot_step as f64 * world.step;
    let (_, tally) = world_outcome(&outcome)
        .by_step
        .iter()
        .find(|(t, _)| *t == time)
        .expect("the ego is in the scene at the snapshot");
    let decided_occupied = |truth: u8| {
        let cells = snapshot.truth.iter().zip(&snapshot.fused);
        cells
            .filter(|(t, c)| **t == truth && c.is_some_and(|c| c.decision == Some(State::Occupied)))
            .count() as u64
    };
    // The picture shows every road user alike, cooperating agents' own bodies
    // (self-report, counted apart) included.
    assert_eq!(tally.detected + tally.self_report_detected, decided_occupied(1));
    assert_eq!(tally.false_positives, decided_occupied(0));
    assert_eq!(
        tally.occupied + tally.self_report,
        snapshot.truth.iter().filter(|&&t| t == 1).count() as u64
    );
    assert!(
        tally.detected > 0 && snapshot.truth.contains(&3),
        "the ego and detections are pictured"
    );
}

/// The recorded states are the kinematics' (a perception world restrains no one);
/// each cooperator's estimate is the one its localization error is measured on;
/// each sighting is of a target in view of its sensor, and each detection lies
/// near the target.
#[test]
fn recorded_world_states_are_the_simulated_ones() {
    let scenario = roundabout();
    let world = world_of(&scenario);
    let mut recorder = Recorder::default();
    let outcome = simulate_point(&scenario, 0, &mut recorder);
    assert_eq!(recorder.agents, world.agents);

    let mut kinematics = Kinematics::new(&world.agents, world.step, world.driving);
    let mut states = Vec::new();
    let (mut error_sum, mut errors) = (0.0, 0);
    for (k, record) in recorder.world.iter().enumerate() {
        kinematics.advance(k, &mut states);
        assert_eq!((record.step, record.time), (k, nanosecond(k as f64 * world.step)));
        assert_eq!(record.agents, states, "step {k}");
        for cooperator in &record.cooperators {
            let truth = states[cooperator.agent]
                .expect("a recorded cooperator is in the scene")
                .pose;
            error_sum += (cooperator.estimate.translation - truth.translation).length();
            errors += 1;
            let agent = &world.agents[cooperator.agent];
            for sighting in &cooperator.sighted {
                let target = states[sighting.target].unwrap().position();
                let sensor = &agent.sensors[sighting.sensor];
                assert!(in_view(sensor, truth * mount_pose(sensor), target).is_some());
                if let Some(body) = sighting.detected {
                    assert_eq!(body.agent, sighting.target);
                    assert!(
                        (body.pose.translation - target).length() < 3.0,
                        "{body:?} vs {target:?}"
                    );
                }
            }
        }
    }
    let metrics = &world_outcome(&outcome).metrics;
    assert_relative_eq!(
        error_sum / f64::from(errors),
        metrics.localization_error.unwrap(),
        max_relative = 1e-9
    );
    assert!(metrics.localization_error.unwrap() > 0.0);
}

/// Messages, deliveries, bytes, labels and close approaches add up to the
/// metrics; a flagged approach follows a conflict that reached the ego.
#[test]
fn semantic_steps_add_up_to_the_metrics() {
    let scenario = urban();
    let world = world_of(&scenario);
    let semantic = world.semantic.as_ref().unwrap();
    let mut recorder = Recorder::default();
    // Density 15 per km: three close approaches, one of them flagged.
    let outcome = simulate_point(&scenario, 2, &mut recorder);
    let metrics = semantic_metrics(&outcome);
    assert_eq!(recorder.semantic.len(), world.steps);

    let messages: Vec<(&Packet, &Vec<Item>, usize)> = recorder
        .semantic
        .iter()
        .flat_map(|r| &r.packets)
        .filter_map(|p| match &p.kind {
            PacketKind::Downlink { items, bytes } => Some((p, items, *bytes)),
            PacketKind::Uplink | PacketKind::Direct => None,
        })
        .collect();
    assert_eq!(messages.len() as u64, metrics.messages);
    let delivered = messages.iter().filter(|(p, ..)| p.reception.received).count() as u64;
    assert_eq!(delivered, metrics.delivered);
    assert!(
        0 < delivered && delivered < metrics.messages,
        "some messages are dropped"
    );
    assert_eq!(messages.iter().map(|m| m.2 as u64).sum::<u64>(), metrics.bytes);
    let items = || messages.iter().flat_map(|m| m.1.iter());
    assert_eq!(items().count() as u64, metrics.transmitted);
    let conflicts = items().filter(|i| i.labels.conflict.is_some()).count() as u64;
    assert_eq!(conflicts, metrics.labels.conflict);
    assert!(conflicts > 0);

    let approaches: Vec<(usize, &Approach)> = recorder
        .semantic
        .iter()
        .flat_map(|r| r.approaches.iter().map(move |a| (r.step, a)))
        .collect();
    assert_eq!(approaches.len() as u64, metrics.close_approaches);
    let missed = approaches.iter().filter(|(_, a)| !a.flagged).count() as u64;
    assert_eq!(missed, metrics.missed_criticals);
    assert!(approaches.len() as u64 > missed, "some approaches were flagged");
    for (step, approach) in &approaches {
        let warned = recorder.semantic[..=*step].iter().flat_map(|r| &r.arrivals).any(|a| {
            a.items
                .iter()
                .any(|i| i.agent == approach.agent && i.labels.conflict.is_some())
        });
        assert_eq!(warned, approach.flagged, "{approach:?} at step {step}");
    }

    // Arrivals are the delivered messages, less those still in flight at the end.
    let arrivals: Vec<&Arrival> = recorder.semantic.iter().flat_map(|r| &r.arrivals).collect();
    assert!(arrivals.len() as u64 <= delivered && arrivals.len() as u64 + 2 >= delivered);
    for record in &recorder.semantic {
        for arrival in &record.arrivals {
            assert!(arrival.at <= record.time + 1e-9 && arrival.at > record.time - world.step);
        }
        let sent_conflict = record.packets.iter().any(|p| {
            matches!(&p.kind, PacketKind::Downlink { items, .. } if items.iter().any(|i| i.labels.conflict.is_some()))
        });
        assert_eq!(record.min_time_to_conflict.is_some(), sent_conflict);
        if let Some(time) = record.min_time_to_conflict {
            assert!((0.0..=semantic.horizon).contains(&time), "{time}");
        }
    }

    // Every packet: received exactly when its RSSI reaches the sensitivity, on the
    // link its kind says.
    let channel = &world.v2x.channel;
    let rsu = 1;
    assert_eq!(recorder.agents[rsu].kind, AgentKind::Rsu);
    let mut kinds = [0; 3];
    for packet in recorder.semantic.iter().flat_map(|r| &r.packets) {
        assert_eq!(
            packet.reception.received,
            packet.reception.rssi_dbm >= channel.sensitivity_dbm
        );
        let (from, to) = (&recorder.agents[packet.from], &recorder.agents[packet.to]);
        match packet.kind {
            PacketKind::Uplink => {
                kinds[0] += 1;
                assert_eq!((packet.from, packet.to), (semantic.ego, rsu));
            }
            PacketKind::Downlink { .. } => {
                kinds[1] += 1;
                assert_eq!((packet.from, packet.to), (rsu, semantic.ego));
            }
            PacketKind::Direct => {
                kinds[2] += 1;
                assert!(from.connected && from.kind != AgentKind::Rsu && packet.from != semantic.ego);
                assert_eq!(packet.to, semantic.ego);
                assert!(to.connected);
            }
        }
    }
    assert!(kinds.iter().all(|&n| n > 0), "every kind of packet is sent: {kinds:?}");
}

/// The record names every agent of the run, generated traffic included, and the
/// fixed RSU stands where the scenario puts it at every step.
#[test]
fn recorded_semantic_states_are_the_simulated_ones() {
    let scenario = urban();
    let world = world_of(&scenario);
    let mut recorder = Recorder::default();
    let outcome = simulate_point(&scenario, 0, &mut recorder);
    let metrics = semantic_metrics(&outcome);
    assert_eq!(
        recorder.agents.len() as u64,
        world.agents.len() as u64 + metrics.generated
    );
    assert_eq!(recorder.agents[..world.agents.len()], world.agents[..]);

    let rsu = world.agents.iter().position(|a| a.kind == AgentKind::Rsu).unwrap();
    let Motion::Fixed { position, .. } = world.agents[rsu].motion else {
        panic!("an RSU stands still")
    };
    for (k, record) in recorder.semantic.iter().enumerate() {
        assert_eq!((record.step, record.time), (k, nanosecond(k as f64 * world.step)));
        assert_eq!(record.agents.len(), recorder.agents.len());
        let state = record.agents[rsu].expect("the RSU is always there");
        assert_eq!([state.position().x, state.position().y], position);
    }
    let present = |k: usize| recorder.semantic[k].agents.iter().filter(|s| s.is_some()).count();
    assert!(present(world.steps - 1) > present(0), "traffic enters the scene");
}

/// Step k's time as the engine states it: k · step to the nanosecond.
fn nanosecond(seconds: f64) -> f64 {
    (seconds * 1e9).round() / 1e9
}
