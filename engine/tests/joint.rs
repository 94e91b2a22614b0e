//! One world (issue 17, part 4): collective perception and the semantic
//! pipeline on one scene, on a scene built so that when each road user first
//! comes into the ego's fused grid can be worked out by hand
//! (`tests/fixtures/valid/joint-two-walkers.yaml`).
//!
//! The ego is at (0, −40.25 + 5 t); steps are 0.1 s apart; its sensor sees
//! 30 m all round, the roadside unit at (27, 24) 20 m all round, both with
//! detection probability 1 and no noise; grids are exchanged whole (no
//! `v2x`), and the inverse sensor model gives an occupied observation
//! P(occupied) = 0.7, the mass (0, 0.4, 0.6) on (Empty, Occupy, Unknown).

use approx::assert_relative_eq;
use sightline_dsl::{Metric, ObjectProperty, ObjectSelection, Scenario};
use sightline_engine::outcome::{SemanticMetrics, WorldOutcome};
use sightline_engine::{Outcome, simulate, simulate_point};

mod common;

use common::by_id;

fn scene() -> Scenario {
    let text = include_str!("../../tests/fixtures/valid/joint-two-walkers.yaml");
    common::fixture("joint-two-walkers.yaml", text)
}

/// The world outcome of each point: Bayes, then Dempster.
fn outcomes(scenario: &Scenario) -> Vec<WorldOutcome> {
    simulate(scenario)
        .points
        .into_iter()
        .map(|outcome| match outcome {
            Outcome::World(world) => world,
            other => panic!("a joint world's outcome is a world's, not {other:?}"),
        })
        .collect()
}

fn pipeline(outcome: &WorldOutcome) -> &SemanticMetrics {
    outcome
        .semantic
        .as_deref()
        .expect("a joint world measures its pipeline")
}

/// walker_a steps out at (15, 26.1) at 1.2 s. The unit, 12.2 m away with
/// nothing between, detects it at once and marks its footprint occupied;
/// the ego, 62 m away, is out of range, and for the whole run (until 9.9 s,
/// y = 9.25) the building hides it (the ego would see past the building's
/// corner (5, 20) only from y ≈ 17). So the fused grid holds the unit's
/// observation alone: Bayes gives 0.7 > 0.5 and decides it occupied at 1.2
/// s; Dempster's rule keeps (0, 0.4, 0.6), where Unknown outweighs Occupy,
/// and never decides it occupied. walker_b, 35 m west of the lane, is out of
/// every sensor's range: in neither grid. The points share one simulation,
/// so everything else the pipeline measured is the same at both.
#[test]
fn each_fused_grid_gives_its_own_first_time_in_the_grid() {
    let scenario = scene();
    let [bayes, dempster] = <[WorldOutcome; 2]>::try_from(outcomes(&scenario)).expect("two points");
    let (a, b) = (by_id(pipeline(&bayes), "walker_a"), by_id(pipeline(&bayes), "walker_b"));
    assert_relative_eq!(a.first_in_grid.expect("in the Bayesian grid"), 1.2, epsilon = 1e-9);
    assert_eq!(a.first_seen, None, "the building hides walker_a from the ego");
    assert_eq!(b.first_in_grid, None);
    assert_eq!((b.first_seen, b.first_v2x), (None, None), "nobody perceives walker_b");
    for id in ["walker_a", "walker_b"] {
        assert_eq!(by_id(pipeline(&dempster), id).first_in_grid, None, "{id}");
    }
    // The same pipeline run, its records but for the grid's times.
    let without_grid = |metrics: &SemanticMetrics| {
        let mut metrics = metrics.clone();
        for record in &mut metrics.objects {
            record.first_in_grid = None;
        }
        metrics
    };
    assert_eq!(without_grid(pipeline(&bayes)), without_grid(pipeline(&dempster)));
    // Closest at the last step, 9.9 s: walker_a's grid lead is 9.9 − 1.2.
    assert_relative_eq!(a.closest.unwrap().time, 9.9, epsilon = 1e-9);
    assert_relative_eq!(a.property(ObjectProperty::GridLead).unwrap(), 8.7, epsilon = 1e-9);
    assert_relative_eq!(
        a.property(ObjectProperty::GridOrWarningLead).unwrap(),
        8.7,
        epsilon = 1e-9
    );
    assert_eq!(b.property(ObjectProperty::GridOrWarningLead), None);
}

/// A joint world's outcome answers both models' metrics, signals and
/// per-object properties; `packet_delivery_ratio` it splits in two.
#[test]
fn a_joint_outcome_answers_both_models() {
    let scenario = scene();
    let run = simulate(&scenario);
    let outcome = &run.points[0];
    let Outcome::World(world) = outcome else {
        panic!("a world's outcome")
    };
    let semantic = pipeline(world);
    assert_eq!(
        outcome.value(Metric::OccupiedRecall),
        world.metrics.value(Metric::OccupiedRecall)
    );
    assert_eq!(
        outcome.sample(Metric::ObjectsNeverKnown).map(|s| (s.value, s.n)),
        Some((Some(1.0), 2)),
        "walker_b, of the two relevant road users"
    );
    assert_eq!(
        outcome.value(Metric::SemanticPacketDeliveryRatio),
        semantic.value(Metric::PacketDeliveryRatio)
    );
    assert!(semantic.messages > 0, "the unit sends the ego messages");
    // No radio carries the grids here: the grid's half of the ratio is not
    // measured, and the ambiguous whole is not defined.
    assert_eq!(outcome.sample(Metric::GridPacketDeliveryRatio), None);
    assert_eq!(outcome.sample(Metric::PacketDeliveryRatio), None);
    assert!(outcome.series(sightline_dsl::Signal::OccupiedRecall).is_some());
    assert!(outcome.series(sightline_dsl::Signal::RsuOnlyObjects).is_some());
    let everyone = ObjectSelection::default();
    let leads = outcome
        .per_object(ObjectProperty::GridLead, &everyone)
        .expect("a joint world has a grid");
    assert_eq!(leads.len(), 2);
    assert_eq!(leads.iter().filter(|l| l.value.is_some()).count(), 1);
}

/// Recording a joint point changes nothing, and the outcome does not depend
/// on the thread count.
#[test]
fn a_joint_world_is_deterministic() {
    let scenario = scene();
    let alone = simulate_point(&scenario, 1, &mut sightline_engine::NoTrace);
    let one = common::in_pool(1, || simulate(&scenario));
    let three = common::in_pool(3, || simulate(&scenario));
    assert_eq!(one, three);
    assert_eq!(one.points[1], alone);
}
