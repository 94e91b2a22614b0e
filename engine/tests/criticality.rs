//! TTC, PET and DRAC in the per-object record (issue 17, part 3), on a scene
//! whose every value can be worked out by hand
//! (`tests/fixtures/valid/criticality.yaml`).
//!
//! Cars are 4.5 m × 1.8 m, steps 0.1 s. The ego drives east along y = 0 at
//! 10 m/s from x = −0.25: its front is at x = 2 + 10 t, its rear at
//! −2.5 + 10 t, one metre further each step.

use approx::assert_relative_eq;
use sightline_dsl::{Metric, ObjectProperty, ObjectSelection, Scenario};
use sightline_engine::outcome::SemanticMetrics;
use sightline_engine::{Outcome, simulate};

mod common;

use common::by_id;

fn scene() -> Scenario {
    let text = include_str!("../../tests/fixtures/valid/criticality.yaml");
    common::fixture("criticality.yaml", text)
}

fn outcome() -> Outcome {
    simulate(&scene()).points.swap_remove(0)
}

fn metrics(outcome: &Outcome) -> &SemanticMetrics {
    match outcome {
        Outcome::Semantic(metrics) => metrics,
        other => panic!("a semantic world, not {other:?}"),
    }
}

#[test]
fn each_measure_by_hand() {
    let outcome = outcome();
    let metrics = metrics(&outcome);

    // lead: centre at x = 30.05 + 5 t, its rear at 27.8 + 5 t, until its road
    // ends at 50.3 (t = 4.05: last at 4.0). The ego closes at 5 m/s on a gap
    // of 27.8 + 5 t − (2 + 10 t) = 25.8 − 5 t: TTC 5.16 − t, least at the
    // last step, 1.16 s; DRAC 5 / (2 TTC), greatest then: 5 / 2.32.
    let lead = by_id(metrics, "lead");
    assert_relative_eq!(lead.min_ttc.unwrap(), 1.16, epsilon = 1e-9);
    assert_relative_eq!(lead.max_drac.unwrap(), 5.0 / 2.32, epsilon = 1e-9);
    // PET: the ego at step i (centre −0.25 + i) covers a spot the lead's
    // footprint at step j (30.05 + 0.5 j) covered when the centres are within
    // 4.5 m: i − 0.5 j ≥ 25.8, with i ≤ 40 (the lead's last step). The least
    // i − j is at j = 28, i = 40: 12 steps, 1.2 s (the continuous motion's
    // 1.16 s, within two steps).
    assert_relative_eq!(lead.pet.unwrap(), 1.2, epsilon = 1e-9);

    // crossing: north along x = 20 at 5 m/s from y = −25.25, its front at
    // −23 + 5 t. It never meets the ego, so at no step does the constant
    // velocity course touch: no TTC, no DRAC. The conflict area is
    // x ∈ [19.1, 20.9], y ∈ [−0.9, 0.9]: the ego covers it from 2 + 10 t =
    // 19.1 (1.71 s) until −2.5 + 10 t = 20.9 (2.34 s), last at the 2.3 step;
    // crossing's front reaches y = −0.9 at 4.42 s, first at the 4.5 step.
    let crossing = by_id(metrics, "crossing");
    assert_eq!((crossing.min_ttc, crossing.max_drac), (None, None));
    assert_relative_eq!(crossing.pet.unwrap(), 2.2, epsilon = 1e-9);

    // walker: a 0.6 m square at (30, 30), within 50 m of the ego but 30 m off
    // its road: no conflict of any kind.
    let walker = by_id(metrics, "walker");
    assert_eq!((walker.min_ttc, walker.pet, walker.max_drac), (None, None, None));

    // The run's metrics: the least TTC and PET, the greatest DRAC, each over
    // the road users that have one.
    for (metric, value, n) in [
        (Metric::MinTtc, 1.16, 1),
        (Metric::MinPet, 1.2, 2),
        (Metric::MaxDrac, 5.0 / 2.32, 1),
    ] {
        assert_relative_eq!(metrics.value(metric).unwrap(), value, epsilon = 1e-9);
        assert_eq!(metrics.sample_size(metric), Some(n), "{}", metric.name());
    }
}

/// A per-object check reads every selected road user's value, conflicts or
/// not; the oracle leaves out those without one.
#[test]
fn per_object_values_list_every_selected_road_user() {
    let outcome = outcome();
    let all = ObjectSelection::default();
    let values = outcome.per_object(ObjectProperty::Pet, &all).unwrap();
    assert_eq!(values.len(), 3);
    assert_eq!(values.iter().filter(|v| v.value.is_some()).count(), 2);
}
