//! run.mcap written into memory and read back (issue 6): replay's measurements
//! are the run's, bit for bit; the step records add up; damage is caught.

mod common;

use std::io::Cursor;

use sightline_dsl::{Metric, Options, RecordedPoints, Scenario, compile};
use sightline_engine::{Run, simulate_traced, simulate_traced_all};
use sightline_oracles::{Measurements, check};
use sightline_reports::Tool;
use sightline_reports::mcap::{ReadError, Recorder, Recording, Source, read, topic};

use common::WORLD;

fn scenario() -> Scenario {
    compile("t.yaml", WORLD, &Options::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The scenario recording every point.
fn every_point() -> Scenario {
    let text = WORLD.replace("record: { point: 1,", "record: { points: all,");
    compile("t.yaml", &text, &Options::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs the scenario, recording into memory; returns the run and the bytes.
fn recorded(scenario: &Scenario) -> (Run, Vec<u8>) {
    let record = scenario.record.expect("the scenario records");
    let tool = Tool {
        name: "sightline".into(),
        version: "test".into(),
        git: "test".into(),
    };
    let source = Source {
        tool: &tool,
        file: "t.yaml",
        text: WORLD,
        seed: None,
        record_flag: false,
    };
    let mut recorder = Recorder::new(Cursor::new(Vec::new()), scenario, record, &source).unwrap();
    let run = match record.points {
        RecordedPoints::One => simulate_traced(scenario, record.point, &mut recorder, &mut |_| {}),
        RecordedPoints::All => simulate_traced_all(scenario, &mut recorder, &mut |_| {}),
    };
    let verdicts = check(scenario, &run);
    let bytes = recorder.finish(&run, &verdicts).unwrap().into_inner();
    (run, bytes)
}

#[test]
fn a_recording_reads_back_to_the_runs_measurements_and_verdicts() {
    let scenario = scenario();
    let (run, bytes) = recorded(&scenario);
    let recording: Recording = read(&bytes).unwrap();
    assert_eq!(recording.scenario.text, WORLD);
    let recorded: Vec<(usize, &str, f64)> = recording
        .scenario
        .points
        .iter()
        .map(|p| (p.point, p.label.as_str(), p.offset))
        .collect();
    assert_eq!(recorded, [(1, "fusion={method=dempster}", 0.0)]);
    let measurements = recording.measurements(scenario.points.len()).unwrap();
    for point in 0..scenario.points.len() {
        for metric in Metric::ALL {
            let (original, replayed) = (run.sample(point, 0, metric), measurements.sample(point, 0, metric));
            assert_eq!(
                original.map(|s| (s.value.map(f64::to_bits), s.n)),
                replayed.map(|s| (s.value.map(f64::to_bits), s.n)),
                "{} at point {point}",
                metric.name()
            );
        }
        assert_eq!(run.audit(point), measurements.audit(point));
    }
    assert_eq!(check(&scenario, &run), check(&scenario, &measurements));
    assert_eq!(recording.verdicts.len(), 2);
    // 60 steps; grids every 5 steps; the ego, the car and the RSU cooperate.
    let counts = &recording.counts;
    assert_eq!(counts[topic::SPEEDS], 60);
    // The four agents stay in the scene: their boxes are written once.
    assert_eq!(counts[topic::AGENTS], 1);
    assert_eq!(counts[topic::SIGNALS], 60);
    assert_eq!(counts[topic::FUSED_GRID], 12);
    assert_eq!(counts[&topic::agent_grid("rsu")], 12);
    assert_eq!(counts[&topic::detections("ego")], 60);
    assert_eq!(counts[topic::OUTCOME], 2);
    let steps = recording
        .step_counts
        .get(&1)
        .expect("a perception world's steps carry cells");
    assert_eq!(steps.steps, 60);
    assert_eq!(recording.step_counts.len(), 1);
}

/// Every point (`record.points: all`, issue 18): each in its own minute, its
/// steps marked with it and adding up to its own outcome; replay's
/// measurements and verdicts are the run's.
#[test]
fn every_point_is_recorded_in_its_own_span_of_time() {
    let scenario = every_point();
    let (run, bytes) = recorded(&scenario);
    let recording = read(&bytes).unwrap();
    let recorded: Vec<(usize, f64)> = recording.scenario.points.iter().map(|p| (p.point, p.offset)).collect();
    // 6 s and a second, rounded up to a minute.
    assert_eq!(recorded, [(0, 0.0), (1, 60.0)]);
    assert_eq!(recording.counts[topic::SIGNALS], 120);
    // Twelve grids a point, and the empty grid that clears the first point's
    // a second after its last step.
    assert_eq!(recording.counts[topic::FUSED_GRID], 25);
    assert_eq!(recording.step_counts.len(), 2);
    for (point, steps) in &recording.step_counts {
        assert_eq!(steps.steps, 60, "point {point}");
    }
    let measurements = recording.measurements(scenario.points.len()).unwrap();
    assert_eq!(check(&scenario, &run), check(&scenario, &measurements));
    // Point 1's steps lie a minute after point 0's: its first signal is at the
    // epoch plus 60 s, every signal of point 0 before it.
    let times = signal_times(&bytes);
    let epoch = sightline_dsl::DEFAULT_START;
    let first_of = |point: u64| times.iter().find(|t| t.0 == point).map(|t| t.1);
    assert_eq!(first_of(0), Some(epoch));
    assert_eq!(first_of(1), Some(epoch + 60_000_000_000));
    assert!(times.windows(2).all(|w| w[0].1 <= w[1].1));
    assert!(times.iter().filter(|t| t.0 == 0).all(|t| t.1 < epoch + 6_000_000_000));
}

/// The point and log time of every `/sightline/signals` message, in file order.
fn signal_times(bytes: &[u8]) -> Vec<(u64, u64)> {
    let summary = mcap::Summary::read(bytes).unwrap().expect("a summary");
    let channel = summary
        .channels
        .values()
        .find(|c| c.topic == topic::SIGNALS)
        .expect("the signals channel")
        .id;
    mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| m.channel.id == channel)
        .map(|m| {
            let json: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
            (json["point"].as_u64().unwrap(), m.log_time)
        })
        .collect()
}

#[test]
fn the_same_run_gives_the_same_bytes() {
    let scenario = scenario();
    assert!(recorded(&scenario).1 == recorded(&scenario).1);
}

#[test]
fn a_truncated_or_damaged_recording_is_refused() {
    let (_, bytes) = recorded(&scenario());
    for cut in [0, 7, bytes.len() / 3, bytes.len() - 1] {
        assert!(matches!(read(&bytes[..cut]), Err(ReadError::Mcap(_))), "cut at {cut}");
    }
    // Any flipped byte breaks a CRC, the magic, or a record's structure.
    for at in (0..bytes.len()).step_by(bytes.len() / 97 + 1) {
        let mut damaged = bytes.clone();
        damaged[at] ^= 0x20;
        assert!(read(&damaged).is_err(), "a flipped byte at {at} went unnoticed");
    }
}

/// A recording whose outcome no longer matches its steps is inconsistent.
#[test]
fn steps_that_do_not_add_up_to_the_outcome_are_refused() {
    let scenario = scenario();
    let (_, bytes) = recorded(&scenario);
    let mut recording = read(&bytes).unwrap();
    let outcome = &mut recording.outcomes[1];
    let recall = outcome
        .metrics
        .iter_mut()
        .find(|m| m.metric == Metric::OccupiedRecall)
        .expect("recall is recorded");
    recall.value.as_mut().expect("recall is defined").0 += 1e-9;
    let error = recording.measurements(scenario.points.len()).unwrap_err();
    assert!(error.to_string().contains("occupied_recall"), "{error}");
    assert!(
        recording.measurements(3).is_err(),
        "a point count that differs is refused"
    );
}

/// A cooperating agent that leaves the scene mid-point observes nothing
/// more: its grid is cleared at the first step it holds no cell, not left on
/// screen for the rest of the point (session 20's outside check).
#[test]
fn a_grid_that_holds_nothing_is_cleared() {
    // The car reaches the end of its 34.7 m road after about 4.3 s of the 6.
    let text = WORLD.replace(
        "route: [arm_in, ring, east_out], start: { offset: 20 }",
        "route: [east_out], start: { offset: 0 }",
    );
    let scenario = compile("t.yaml", &text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    let (_, bytes) = recorded(&scenario);
    let summary = mcap::Summary::read(&bytes).unwrap().expect("a summary");
    let channel = summary
        .channels
        .values()
        .find(|c| c.topic == topic::agent_grid("cav"))
        .expect("the car's grid")
        .id;
    let widths: Vec<u64> = mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| m.channel.id == channel)
        .map(|m| {
            let grid: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
            grid["column_count"].as_u64().unwrap()
        })
        .collect();
    // Grids while it drives, then one of no cell; nothing after it.
    let (last, shown) = widths.split_last().expect("grids of the car");
    assert!(!shown.is_empty() && shown.iter().all(|&w| w > 0), "{widths:?}");
    assert_eq!(*last, 0, "{widths:?}");
}
