//! The per-object record of a semantic run (issue 17), on a scene built so that
//! each category occurs once and every time can be worked out by hand
//! (`tests/fixtures/valid/four-road-users.yaml`).
//!
//! The ego is at (0, −40.25 + 5 t); steps are 0.1 s apart; relevance is a
//! centre distance below 50 m (`semantic.proximity`), the ego's sensor sees
//! 30 m all round, the RSU at (27, 24) senses 20 m, and a message sent at a
//! cycle arrives 0.02 s later (the latency) plus the distance over the speed
//! of light (under 1 µs here).

use approx::assert_relative_eq;
use sightline_dsl::{AgentKind, Metric, Scenario};
use sightline_engine::outcome::{Category, SemanticMetrics};
use sightline_engine::{Outcome, simulate};

mod common;

use common::by_id;

fn scene() -> Scenario {
    let text = include_str!("../../tests/fixtures/valid/four-road-users.yaml");
    common::fixture("four-road-users.yaml", text)
}

fn metrics() -> SemanticMetrics {
    let run = simulate(&scene());
    match &run.points[0] {
        Outcome::Semantic(metrics) => metrics.clone(),
        other => panic!("a semantic world, not {other:?}"),
    }
}

/// Each message's arrival: its cycle plus the latency, within the light time.
fn assert_arrived(at: Option<f64>, cycle: f64) {
    assert_relative_eq!(at.expect("a message named it"), cycle + 0.02, epsilon = 1e-6);
}

#[test]
fn each_category_occurs_once_with_its_times_by_hand() {
    let metrics = metrics();
    // In order of becoming relevant; the ego and the RSU are not road users.
    let ids: Vec<&str> = metrics.objects.iter().map(|o| o.id.as_str()).collect();
    assert_eq!(ids, ["walker_c", "car_b", "walker_a", "walker_d"]);
    assert!(metrics.objects.iter().all(|o| o.run == 0 && o.first_warning.is_none()));

    // walker_c at (−1.5, 5.1), out of the RSU's 20 m (34 m away): relevant from
    // the start (45.4 m away); in the ego's 30 m once 5.1 − y < 29.96, y > −24.86,
    // t > 3.08: at 3.1. Closest where y is nearest 5.1: y = 5.25 at 9.1, 1.5075 m.
    // Its 0.6 m square spans x ∈ [−1.8, −1.2], the ego's 1.8 m width
    // x ∈ [−0.9, 0.9]: they never touch, so it has no time to collision, no
    // DRAC and, their footprints never sharing a spot, no PET.
    let c = by_id(&metrics, "walker_c");
    assert_eq!((c.class, c.category), (AgentKind::Pedestrian, Category::SeenFirst));
    assert_relative_eq!(c.first_relevant, 0.0);
    assert_relative_eq!(c.first_seen.unwrap(), 3.1, epsilon = 1e-9);
    assert_eq!(c.first_v2x, None);
    let closest = c.closest.unwrap();
    assert_relative_eq!(closest.time, 9.1, epsilon = 1e-9);
    assert_relative_eq!(
        closest.distance,
        (1.5f64.powi(2) + 0.15f64.powi(2)).sqrt(),
        epsilon = 1e-9
    );
    assert_eq!((c.min_ttc, c.max_drac, c.pet), (None, None, None));
    assert_eq!(c.anticipation(), None);

    // car_b parked at (30, 10.2), 14.1 m from the RSU: within 50 m of the ego
    // once |10.2 − y| < 40, y > −29.8, t > 2.09: named by the message of the
    // 2.1 cycle. Always 30 m or more from the ego: never seen. Closest at y =
    // 10.25 (t = 10.1). Ours: 10.1 − 2.12 = 7.98 s.
    let b = by_id(&metrics, "car_b");
    assert_eq!((b.class, b.category), (AgentKind::Car, Category::WarnedNeverSeen));
    assert_eq!((b.length, b.width), (4.5, 1.8));
    assert_relative_eq!(b.first_relevant, 2.1, epsilon = 1e-9);
    assert_arrived(b.first_v2x, 2.1);
    assert_eq!(b.first_seen, None);
    assert_relative_eq!(b.closest.unwrap().time, 10.1, epsilon = 1e-9);
    assert_relative_eq!(
        b.closest.unwrap().distance,
        (900.0f64 + 0.05 * 0.05).sqrt(),
        epsilon = 1e-9
    );
    assert_eq!(b.min_ttc, None, "it stands 30 m off the ego's way");
    assert_relative_eq!(b.anticipation().unwrap(), 10.1 - 2.12, epsilon = 1e-6);

    // walker_a at (15, 26.1), 12.2 m from the RSU: within 50 m once
    // |26.1 − y| < 47.70, y > −21.60, t > 3.73: the 3.8 cycle. The building's
    // corner (5, 20) hides it until the ray passes above it: y + (26.1 − y) / 3
    // ≥ 20, y ≥ 16.95, t ≥ 11.44: seen at 11.5. Ours and the paper's: 11.5 − 3.82.
    let a = by_id(&metrics, "walker_a");
    assert_eq!(a.category, Category::WarnedBeforeSeen);
    assert_relative_eq!(a.first_relevant, 3.8, epsilon = 1e-9);
    assert_arrived(a.first_v2x, 3.8);
    assert_relative_eq!(a.first_seen.unwrap(), 11.5, epsilon = 1e-9);
    assert_relative_eq!(a.closest.unwrap().time, 13.3, epsilon = 1e-9);
    assert_relative_eq!(a.anticipation().unwrap(), 11.5 - 3.82, epsilon = 1e-6);
    assert_relative_eq!(metrics.anticipation[..], [11.5 - 3.82][..], epsilon = 1e-6);

    // walker_d at (−35, 30.2), 62 m from the RSU and never within 30 m of the
    // ego: within 50 m once |30.2 − y| < 35.71, y > −5.51, t > 6.95: at 7.0.
    let d = by_id(&metrics, "walker_d");
    assert_eq!(d.category, Category::NeverKnown);
    assert_relative_eq!(d.first_relevant, 7.0, epsilon = 1e-9);
    assert_eq!((d.first_seen, d.first_v2x), (None, None));
    assert_relative_eq!(d.closest.unwrap().time, 14.1, epsilon = 1e-9);
    assert_eq!(d.closest.unwrap().position, [-35.0, 30.2]);
}

/// The paper's anticipation counts walker_a only; ours counts car_b too, which
/// the ego never saw. Each category is one road user per run, over four.
#[test]
fn our_anticipation_counts_the_never_seen_and_categories_are_metrics() {
    let metrics = metrics();
    assert_eq!(metrics.sample_size(Metric::AnticipationMedian), Some(1));
    assert_eq!(metrics.sample_size(Metric::ObjectAnticipationMedian), Some(2));
    // The median of 7.68 and 7.98.
    assert_relative_eq!(
        metrics.value(Metric::ObjectAnticipationMedian).unwrap(),
        (7.68 + 7.98) / 2.0,
        epsilon = 1e-6
    );
    for metric in [
        Metric::ObjectsWarnedBeforeSeen,
        Metric::ObjectsWarnedNeverSeen,
        Metric::ObjectsSeenFirst,
        Metric::ObjectsNeverKnown,
    ] {
        assert_eq!(metrics.value(metric), Some(1.0), "{}", metric.name());
        assert_eq!(metrics.sample_size(metric), Some(4), "{}", metric.name());
    }
}
