//! World scenarios through the engine API: determinism, exact localization, and
//! what cooperation can and cannot change.

mod common;

use common::in_pool;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, RngSeed, TestRunner};
use sightline_dsl::{Metric, Scenario, Signal, compile};
use sightline_engine::outcome::WorldOutcome;
use sightline_engine::trace::WorldStep;
use sightline_engine::{Outcome, TraceSink, simulate, simulate_point};

/// A crossroads of 80 m arms with four buildings in the corners; five connected cars
/// and a non-connected truck, pedestrian and car. `{…}` fields are filled in.
const CROSSROADS: &str = r#"
sightline: 1
name: crossroads
seed: {seed}
time: { duration: 6, step: 0.2 }
grid: { origin: [-60, -60], size: [120, 120], cell: 0.5 }
roads:
  - { id: south_north, polyline: [[1.75, -60], [1.75, 60]], speed_limit: 14 }
  - { id: north_south, polyline: [[-1.75, 60], [-1.75, -60]], speed_limit: 14 }
  - { id: west_east, polyline: [[-60, -1.75], [60, -1.75]], speed_limit: 14 }
  - { id: east_west, polyline: [[60, 1.75], [-60, 1.75]], speed_limit: 14 }
occluders:
  - { id: ne, polygon: [[8, 8], [50, 8], [50, 50], [8, 50]] }
  - { id: nw, polygon: [[-50, 8], [-8, 8], [-8, 50], [-50, 50]] }
  - { id: sw, polygon: [[-50, -50], [-8, -50], [-8, -8], [-50, -8]] }
  - { id: se, polygon: [[8, -50], [50, -50], [50, -8], [8, -8]] }
sensor_models:
  lidar: { range: 50, detection_probability: 0.9, position_noise: { base: 0.05, per_m: 0.002 }, ray_spacing_deg: 1 }
agents:
  - { id: ego, kind: car, route: [south_north], start: { offset: {o0} }, speed: { target: 6 }, connected: true, sensors: [lidar] }
  - { id: a1, kind: car, route: [north_south], start: { offset: {o1} }, speed: { target: 6 }, connected: true, sensors: [lidar] }
  - { id: a2, kind: car, route: [west_east], start: { offset: {o2} }, speed: { target: 6 }, connected: true, sensors: [lidar] }
  - { id: a3, kind: car, route: [east_west], start: { offset: {o3} }, speed: { target: 6 }, connected: true, sensors: [lidar] }
  - { id: a4, kind: car, route: [west_east], start: { offset: {o4} }, speed: { target: 5 }, connected: true, sensors: [lidar] }
  - { id: truck, kind: truck, route: [east_west], start: { offset: 30 }, speed: { target: 5 } }
  - { id: walker, kind: pedestrian, path: [[-6, 20], [6, 20]], speed: { target: 1.4 } }
  - { id: car, kind: car, route: [north_south], start: { offset: 5 }, speed: { target: 7 } }
localization: { position_sigma: {sigma}, heading_sigma_deg: {heading}, filter: {filter} }
perception: { ego: ego }
fusion: { method: {method} }
decision: { threshold: 0 }
sweep:
  perception.cooperating: [1, 2, 3, 4, 5]
"#;

struct Setting {
    seed: u64,
    offsets: [u32; 5],
    sigma: f64,
    filter: &'static str,
    method: &'static str,
}

impl Setting {
    fn text(&self) -> String {
        let mut text = CROSSROADS
            .replace("{seed}", &self.seed.to_string())
            .replace("{sigma}", &self.sigma.to_string())
            .replace("{heading}", &(self.sigma * 5.0).to_string())
            // Exact localization takes no filter: `check` refuses one.
            .replace(
                ", filter: {filter}",
                &if self.sigma == 0.0 {
                    String::new()
                } else {
                    format!(", filter: {}", self.filter)
                },
            )
            .replace("{method}", self.method);
        for (i, offset) in self.offsets.iter().enumerate() {
            text = text.replace(&format!("{{o{i}}}"), &offset.to_string());
        }
        text
    }

    fn scenario(&self) -> Scenario {
        compile("crossroads.yaml", &self.text(), &Default::default()).unwrap_or_else(|e| panic!("{e}"))
    }
}

fn nominal(sigma: f64, filter: &'static str) -> Setting {
    Setting {
        seed: 3,
        offsets: [10, 15, 20, 30, 5],
        sigma,
        filter,
        method: "bayes",
    }
}

fn world(outcome: &Outcome) -> &WorldOutcome {
    match outcome {
        Outcome::World(world) => world,
        other => panic!("a perception world gives world outcomes, not {other:?}"),
    }
}

#[test]
fn world_results_do_not_depend_on_the_thread_count() {
    let scenario = nominal(0.3, "kalman").scenario();
    let one = in_pool(1, || simulate(&scenario));
    assert_eq!(one, in_pool(2, || simulate(&scenario)));
    assert_eq!(one, in_pool(4, || simulate(&scenario)));
}

/// Counts the world steps it is given and gives up after `limit` of them.
struct GivingUp {
    steps: usize,
    limit: usize,
}

impl TraceSink for GivingUp {
    fn world_step(&mut self, _step: &WorldStep<'_>) {
        self.steps += 1;
    }

    fn gave_up(&self) -> bool {
        self.steps >= self.limit
    }
}

/// A sink that gives up (a failed system under test) ends the world's run at
/// once: no step after it is simulated; one that never does sees all 30.
#[test]
fn a_world_stops_stepping_when_its_sink_gives_up() {
    let scenario = nominal(0.0, "none").scenario();
    for (limit, seen) in [(3, 3), (usize::MAX, 30)] {
        let mut sink = GivingUp { steps: 0, limit };
        simulate_point(&scenario, 0, &mut sink);
        assert_eq!(sink.steps, seen);
    }
}

/// With exact self-localization every agent's grid is drawn at its true pose,
/// whatever the filter: the outcome is that of ground-truth-aligned grids.
#[test]
fn zero_pose_noise_gives_ground_truth_aligned_grids() {
    let kalman = simulate(&nominal(0.0, "kalman").scenario());
    let raw = simulate(&nominal(0.0, "none").scenario());
    assert_eq!(kalman, raw);
    for outcome in kalman.points.iter().map(world) {
        assert_eq!(outcome.metrics.localization_error, Some(0.0));
    }
}

#[test]
fn pose_noise_shows_in_the_estimates_and_costs_precision() {
    let exact = simulate(&nominal(0.0, "kalman").scenario());
    let noisy = simulate(&nominal(0.5, "none").scenario());
    let (exact, noisy) = (world(&exact.points[4]), world(&noisy.points[4]));
    assert!(noisy.metrics.localization_error.unwrap() > 0.3);
    let precision = |o: &WorldOutcome| o.metrics.value(Metric::OccupiedPrecision).unwrap();
    assert!(
        precision(noisy) < precision(exact),
        "{} vs {}",
        precision(noisy),
        precision(exact)
    );
}

/// Adding a cooperating agent never shrinks the joint field of view, and with
/// exact localization it never lowers recall over every occupied cell, its own
/// footprint included: an agent's rays stop at the first obstacle, so it never
/// reports a truly occupied cell as free. (This property found agents reporting
/// their own footprint as free space.) The agent that joins moves its own cells
/// from the road users to find to self-report, so the population of
/// `occupied_recall` only shrinks, and the cells it leaves hold what was found
/// before.
#[test]
fn cooperation_never_loses_coverage_or_recall_with_exact_poses() {
    let config = Config {
        cases: 12,
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(20),
        ..Config::default()
    };
    let strategy = (0u64..1000, proptest::array::uniform5(0u32..60));
    TestRunner::new(config)
        .run(&strategy, |(seed, offsets)| {
            let setting = Setting {
                seed,
                offsets,
                sigma: 0.0,
                filter: "kalman",
                method: "bayes",
            };
            let run = simulate(&setting.scenario());
            let outcomes: Vec<&WorldOutcome> = run.points.iter().map(world).collect();
            for pair in outcomes.windows(2) {
                let (fewer, more) = (&pair[0].metrics, &pair[1].metrics);
                prop_assert!(more.joint_observed >= fewer.joint_observed);
                let (found, found_before) = (
                    more.detected + more.self_report_detected,
                    fewer.detected + fewer.self_report_detected,
                );
                prop_assert!(found >= found_before, "{found} < {found_before}");
                prop_assert_eq!(more.occupied + more.self_report, fewer.occupied + fewer.self_report);
                prop_assert!(more.occupied <= fewer.occupied);
                let moved = more.self_report - fewer.self_report;
                prop_assert!(more.detected + moved >= fewer.detected);
            }
            Ok(())
        })
        .unwrap();
}

/// On random small scenes (seed, start offsets, localization noise, fusion
/// method), every metric stays in its range, every fused cell holds a valid
/// mass function or probability, every step's signal stays in [0, 1], and the
/// steps' tallies add up to the run's.
#[test]
fn metrics_and_masses_stay_valid_on_random_scenes() {
    let config = Config {
        cases: 10,
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(21),
        ..Config::default()
    };
    let methods = ["bayes", "dempster", "distance_weighted"];
    let strategy = (
        0u64..1000,
        proptest::array::uniform5(0u32..60),
        0u32..=5,
        0usize..methods.len(),
    );
    TestRunner::new(config)
        .run(&strategy, |(seed, offsets, tenths, method)| {
            let setting = Setting {
                seed,
                offsets,
                sigma: f64::from(tenths) / 10.0,
                filter: "kalman",
                method: methods[method],
            };
            let run = simulate(&setting.scenario());
            for outcome in &run.points {
                let o = world(outcome);
                for metric in [
                    Metric::OccupiedRecall,
                    Metric::OccupiedPrecision,
                    Metric::BlindRecall,
                    Metric::OccupiedRecallWithSelfReport,
                    Metric::EgoOccupiedRecall,
                    Metric::SelfReportShare,
                ] {
                    if let Some(v) = o.metrics.value(metric) {
                        prop_assert!((0.0..=1.0).contains(&v), "{} = {v}", metric.name());
                    }
                }
                prop_assert!(o.metrics.value(Metric::FovGain).is_none_or(|g| g >= 0.0));
                prop_assert!(o.metrics.detected <= o.metrics.occupied);
                prop_assert!(o.metrics.ego_detected <= o.metrics.occupied);
                prop_assert!(o.metrics.blind_detected <= o.metrics.blind_occupied);
                prop_assert!(o.metrics.blind_occupied <= o.metrics.occupied);
                let m = &o.metrics;
                prop_assert!(m.self_report_only <= m.self_report_detected && m.self_report_detected <= m.self_report);
                let audit = &o.audit;
                prop_assert_eq!(audit.non_finite, 0);
                prop_assert!(audit.min_mass.is_none_or(|m| m >= -1e-12));
                prop_assert!(audit.max_mass.is_none_or(|m| m <= 1.0 + 1e-12));
                prop_assert!(audit.max_sum_error <= 1e-9, "Σm − 1 = {}", audit.max_sum_error);
                for signal in [Signal::OccupiedRecall, Signal::BlindRecall, Signal::OccupiedPrecision] {
                    for &(_, v) in &o.series(signal).expect("a world signal")[..] {
                        prop_assert!((0.0..=1.0).contains(&v), "{} = {v}", signal.name());
                    }
                }
                let (occupied, detected) = o
                    .by_step
                    .iter()
                    .fold((0, 0), |(n, d), (_, c)| (n + c.occupied, d + c.detected));
                prop_assert_eq!((occupied, detected), (o.metrics.occupied, o.metrics.detected));
            }
            Ok(())
        })
        .unwrap();
}
