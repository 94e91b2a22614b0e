//! A perception world's cell counts summed over its steps: the recorder keeps
//! the running sums for `/sightline/requirements`, and replay sums the counts
//! the recording holds to check them against the recorded outcome. Both sum
//! here, the same way.

use sightline_dsl::Metric;
use sightline_engine::outcome::{CellTally, Sightings, WorldMetrics};

/// The metrics the steps of a perception world give, summed over them.
pub(crate) const WORLD_STEP_METRICS: [Metric; 4] = [
    Metric::FovGain,
    Metric::OccupiedRecall,
    Metric::OccupiedPrecision,
    Metric::BlindRecall,
];

/// World metrics with every count zero.
pub(crate) fn zero_world_metrics() -> WorldMetrics {
    WorldMetrics {
        steps: 0,
        occupied: 0,
        detected: 0,
        false_positives: 0,
        blind_occupied: 0,
        blind_detected: 0,
        ego_observed: 0,
        joint_observed: 0,
        sightings: Sightings::default(),
        localization_error: None,
        mean_uncertainty: None,
        conflict: None,
    }
}

/// Adds one step's counts (cells observed by the ego and jointly, and the fused
/// grid's tallies) to `metrics`. Saturating: replay sums counts read from a file,
/// and a forged count must give a mismatch, not an overflow.
pub(crate) fn add_counts(metrics: &mut WorldMetrics, ego_observed: u64, joint_observed: u64, cells: &CellTally) {
    let add = |total: &mut u64, count: u64| *total = total.saturating_add(count);
    add(&mut metrics.steps, 1);
    add(&mut metrics.ego_observed, ego_observed);
    add(&mut metrics.joint_observed, joint_observed);
    add(&mut metrics.occupied, cells.occupied);
    add(&mut metrics.detected, cells.detected);
    add(&mut metrics.false_positives, cells.false_positives);
    add(&mut metrics.blind_occupied, cells.blind_occupied);
    add(&mut metrics.blind_detected, cells.blind_detected);
}
