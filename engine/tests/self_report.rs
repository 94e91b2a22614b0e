//! Self-report counted apart (issue 16, part 2), on scenes small enough to count
//! by hand: a cooperating agent's own footprint is not a road user that
//! cooperation revealed, so recall leaves it out and `self_report_share` counts
//! it.
// See: issue 16, "Honest recall".

use approx::assert_relative_eq;
use sightline_dsl::{Metric, compile};
use sightline_engine::outcome::{WorldMetrics, WorldOutcome};
use sightline_engine::{Outcome, simulate};

/// One 0.1 s step on a 1 m grid. A wall from x = −30 to 30 between y = 5 and 6
/// hides the north from the ego, which stands at (0, −10) facing north; `cav`,
/// connected, stands at (0, 20) facing east. Both carry a 25 m lidar without
/// noise and localize exactly. A car's 4.5 × 1.8 m footprint centred on
/// (x, 20) covers the 4 × 2 cells whose centres lie within 2.25 m and 0.9 m of
/// it: 8 cells (tests/fixtures/templates/wall-and-cooperator.yaml.in).
const SCENE: &str = include_str!("../../tests/fixtures/templates/wall-and-cooperator.yaml.in");

/// A car that does not cooperate, 10 m east of `cav`, hidden from the ego.
const HIDDEN_CAR: &str = "  - { id: car, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 } }";

fn outcomes(others: &str, sweep: &str) -> Vec<WorldOutcome> {
    let text = SCENE.replace("{others}", others).replace("{rest}", sweep);
    let scenario = compile("self-report.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    simulate(&scenario)
        .points
        .into_iter()
        .map(|outcome| match outcome {
            Outcome::World(world) => world,
            other => panic!("a perception world gives world outcomes, not {other:?}"),
        })
        .collect()
}

fn run(others: &str, sweep: &str) -> Vec<WorldMetrics> {
    outcomes(others, sweep).into_iter().map(|o| o.metrics).collect()
}

/// `metric`'s value and n.
fn measured(metrics: &WorldMetrics, metric: Metric) -> (Option<f64>, Option<u64>) {
    (metrics.value(metric), metrics.sample_size(metric, 0))
}

/// The only occupied cells are `cav`'s own, which it reports and no sensor
/// sees: all it contributes is self-report, and recall over the other cells
/// has nothing to count (n = 0, no value), not a perfect 1.
#[test]
fn a_cooperator_whose_own_body_is_all_it_reports_adds_only_self_report() {
    let metrics = run("", "").remove(0);
    assert_eq!(metrics.steps, 1);
    assert_eq!(
        (
            metrics.self_report,
            metrics.self_report_detected,
            metrics.self_report_only
        ),
        (8, 8, 8)
    );
    assert_eq!((metrics.occupied, metrics.detected, metrics.false_positives), (0, 0, 0));
    assert_eq!(measured(&metrics, Metric::OccupiedRecall), (None, Some(0)));
    assert_eq!(measured(&metrics, Metric::BlindRecall), (None, Some(0)));
    assert_eq!(measured(&metrics, Metric::SelfReportShare), (Some(1.0), Some(8)));
    assert_eq!(
        measured(&metrics, Metric::OccupiedRecallWithSelfReport),
        (Some(1.0), Some(8))
    );
    assert_eq!(measured(&metrics, Metric::OccupiedPrecision), (Some(1.0), Some(8)));
}

/// A car the ego cannot see and `cav` detects. With the ego alone, both cars
/// are road users to find (16 cells) and none is found. With `cav`
/// cooperating, its own 8 cells are self-report, and the hidden car's 8 are
/// revealed: recall and blind recall 1 over 8 cells, half of the 16 cells
/// known being self-report.
#[test]
fn a_hidden_road_user_revealed_by_a_cooperator_counts_in_recall() {
    let points = run(HIDDEN_CAR, "sweep: { perception.cooperating: [1, 2] }");
    let (alone, together) = (&points[0], &points[1]);

    assert_eq!((alone.occupied, alone.detected, alone.blind_occupied), (16, 0, 16));
    assert_eq!(alone.self_report, 0);
    assert_eq!(measured(alone, Metric::OccupiedRecall), (Some(0.0), Some(16)));
    assert_eq!(measured(alone, Metric::SelfReportShare), (None, Some(0)));

    assert_eq!((together.occupied, together.detected), (8, 8));
    assert_eq!((together.blind_occupied, together.blind_detected), (8, 8));
    assert_eq!(
        (
            together.self_report,
            together.self_report_detected,
            together.self_report_only
        ),
        (8, 8, 8)
    );
    assert_eq!(measured(together, Metric::OccupiedRecall), (Some(1.0), Some(8)));
    assert_eq!(measured(together, Metric::BlindRecall), (Some(1.0), Some(8)));
    assert_eq!(measured(together, Metric::SelfReportShare), (Some(0.5), Some(16)));
    assert_eq!(
        measured(together, Metric::OccupiedRecallWithSelfReport),
        (Some(1.0), Some(16))
    );
}

/// The ego-only baseline over the same cells (`ego_occupied_recall`): a car
/// 10 m in front of the ego, on its road, which it sees whole (8 cells), and
/// the hidden car. With the ego alone, three cars are road users to find (24
/// cells) and the ego finds the 8 in front: 8/24, as `occupied_recall`. With
/// `cav` cooperating, its 8 cells leave the population as self-report: the
/// ego alone now finds 8 of 16 (0.5) while the fused grid finds all 16. Of the
/// gain from 1/3 to 1, 1/6 is the population shrinking and 1/2 what
/// cooperation reveals.
#[test]
fn the_ego_alone_is_scored_over_the_same_cells_as_the_fused_grid() {
    let seen = "  - { id: seen, kind: car, route: [ns], start: { offset: 30 }, speed: { target: 0 } }";
    let points = run(
        &format!("{HIDDEN_CAR}\n{seen}"),
        "sweep: { perception.cooperating: [1, 2] }",
    );
    let (alone, together) = (&points[0], &points[1]);
    assert_eq!((alone.occupied, alone.detected, alone.ego_detected), (24, 8, 8));
    assert_eq!(measured(alone, Metric::EgoOccupiedRecall), (Some(8.0 / 24.0), Some(24)));
    assert_eq!(
        measured(alone, Metric::EgoOccupiedRecall),
        measured(alone, Metric::OccupiedRecall)
    );
    assert_eq!(
        (together.occupied, together.detected, together.ego_detected),
        (16, 16, 8)
    );
    assert_eq!(measured(together, Metric::EgoOccupiedRecall), (Some(0.5), Some(16)));
    assert_eq!(measured(together, Metric::OccupiedRecall), (Some(1.0), Some(16)));
}

/// A cooperator's own cells that another cooperator's sensor also finds
/// occupied are self-report, but not known *only* through it: `car2`, a
/// second connected car 10 m east of `cav`, and `cav` each see the other.
#[test]
fn a_cooperator_seen_by_another_is_not_known_only_through_self_report() {
    let second = "  - { id: cav2, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 }, connected: true, sensors: [lidar] }";
    let metrics = run(second, "").remove(0);
    assert_eq!(
        (
            metrics.self_report,
            metrics.self_report_detected,
            metrics.self_report_only
        ),
        (16, 16, 0)
    );
    assert_eq!(measured(&metrics, Metric::SelfReportShare), (Some(0.0), Some(16)));
    assert_eq!(measured(&metrics, Metric::OccupiedRecall), (None, Some(0)));
}

/// Calibration (issue 16, part 5) on the scene of the hidden car. Every fused
/// cell is seen by one agent only (the wall parts their views), so its p is the
/// inverse model's: 0.3 where seen free, 0.7 where detected; both err by 0.3,
/// and the Brier score is 0.09. Cells nobody observed are not judged (the
/// hidden car's with the ego alone), nor is `cav`'s own body when it
/// cooperates: n is the fused cells less its 8.
#[test]
fn brier_score_judges_the_fused_cells_self_report_aside() {
    let points = outcomes(HIDDEN_CAR, "sweep: { perception.cooperating: [1, 2] }");
    let (alone, together) = (&points[0], &points[1]);
    let brier = |o: &WorldOutcome| measured(&o.metrics, Metric::BrierScore);

    let (value, n) = brier(alone);
    assert_relative_eq!(value.unwrap(), 0.09, epsilon = 1e-9);
    assert_eq!(n, Some(alone.audit.cells));
    let bins = &alone.metrics.calibration.bins;
    assert_eq!(bins[3].cells, alone.audit.cells);
    assert_eq!(bins[3].observed_frequency(), Some(0.0));

    let (value, n) = brier(together);
    assert_relative_eq!(value.unwrap(), 0.09, epsilon = 1e-9);
    assert_eq!(n, Some(together.audit.cells - 8));
    let bins = &together.metrics.calibration.bins;
    assert_eq!((bins[7].cells, bins[7].observed_frequency()), (8, Some(1.0)));
    assert_relative_eq!(bins[7].mean_probability().unwrap(), 0.7, epsilon = 1e-9);
    assert_eq!(bins[3].cells, together.audit.cells - 16);
    assert_eq!(bins[3].observed_frequency(), Some(0.0));
}
