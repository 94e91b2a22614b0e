//! The metrics a perception world's steps give, summed over them: the recorder
//! keeps the running sums for `/sightline/requirements`, and replay sums the
//! counts the recording holds to check them against the recorded outcome. Both
//! sum with the engine's own
//! [`WorldMetrics::add_step`](sightline_engine::outcome::WorldMetrics::add_step),
//! as the engine does.

use sightline_dsl::Metric;

/// The metrics the steps of a perception world give, summed over them.
pub(crate) const WORLD_STEP_METRICS: [Metric; 7] = [
    Metric::FovGain,
    Metric::OccupiedRecall,
    Metric::EgoOccupiedRecall,
    Metric::OccupiedPrecision,
    Metric::BlindRecall,
    Metric::OccupiedRecallWithSelfReport,
    Metric::SelfReportShare,
];
