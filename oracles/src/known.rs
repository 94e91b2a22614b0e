//! Known answers of the statistics, computed by hand, that `sightline selftest`
//! checks on the user's machine beside the engine's.

use sightline_engine::KnownAnswer;

use crate::check::seeds::{clopper_pearson_lower, mean_bound, wilson_lower};

/// Known answers of the confidence bounds of checks over seeds, computed by
/// hand, for `sightline selftest`.
pub fn known_answers() -> Vec<KnownAnswer> {
    let ten: Vec<f64> = (1..=10).map(f64::from).collect();
    vec![
        KnownAnswer::close(
            "STAT-01",
            "Clopper–Pearson lower 95 % bound, 30 of 30: 0.05^(1/30)",
            0.05f64.powf(1.0 / 30.0),
            clopper_pearson_lower(30, 30, 0.95),
        ),
        KnownAnswer::close(
            "STAT-02",
            "Wilson lower 95 % bound, 8 of 10",
            0.540792805687488,
            wilson_lower(8, 10, 0.95),
        ),
        KnownAnswer {
            id: "STAT-03",
            what: "Student-t lower 95 % bound of the mean of 1…10: 5.5 − 1.833113·√(55/60)",
            expected: 5.5 - 1.833113 * (55.0f64 / 60.0).sqrt(),
            got: mean_bound(&ten, 0.95, false).1,
            tolerance: 1e-5,
        },
    ]
}
