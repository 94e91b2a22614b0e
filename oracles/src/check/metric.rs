//! Metric thresholds.

use sightline_dsl::{Bound, Metric};

use super::short;
use crate::Status;

/// Compares the `value` of `metric` with `bound`: passes when the margin is ≥ 0.
/// `None` (or NaN) is an error: the metric is undefined at this point.
pub(crate) fn evaluate(metric: Metric, bound: Bound, value: Option<f64>) -> (Status, Option<f64>, Option<f64>, String) {
    let name = metric.name();
    let Some(value) = value.filter(|v| !v.is_nan()) else {
        return (
            Status::Error,
            None,
            None,
            format!("{name} is not defined at this point (nothing to measure it on)"),
        );
    };
    let margin = bound.margin(value);
    let (relation, holds) = match bound {
        Bound::AtLeast(_) if margin >= 0.0 => ("≥", true),
        Bound::AtLeast(_) => ("<", false),
        Bound::AtMost(_) if margin >= 0.0 => ("≤", true),
        Bound::AtMost(_) => (">", false),
    };
    let wanted = match bound {
        Bound::AtLeast(_) => "at least",
        Bound::AtMost(_) => "at most",
    };
    let status = if holds { Status::Pass } else { Status::Fail };
    let message = format!(
        "{name} = {} {relation} {threshold} (required {wanted} {threshold}; margin {})",
        short(value),
        short(margin),
        threshold = short(bound.threshold())
    );
    (status, Some(value), Some(margin), message)
}

#[cfg(test)]
mod tests {
    use sightline_engine::FieldMetrics;

    use super::*;

    fn metrics(false_alarms: u64) -> FieldMetrics {
        FieldMetrics {
            cells: 100,
            correct: 90,
            below_threshold: 10 - false_alarms,
            false_alarms,
            missed_detections: 0,
            decided_unknown: 0,
            unobserved: 0,
            mean_uncertainty: Some(0.1),
            conflict: None,
        }
    }

    #[test]
    fn at_most_passes_on_the_boundary_and_fails_beyond() {
        let (status, value, margin, _) = evaluate(
            Metric::FalseAlarms,
            Bound::AtMost(3.0),
            metrics(3).value(Metric::FalseAlarms),
        );
        assert_eq!((status, value, margin), (Status::Pass, Some(3.0), Some(0.0)));
        let (status, _, margin, message) = evaluate(
            Metric::FalseAlarms,
            Bound::AtMost(3.0),
            metrics(4).value(Metric::FalseAlarms),
        );
        assert_eq!((status, margin), (Status::Fail, Some(-1.0)));
        assert_eq!(message, "false_alarms = 4 > 3 (required at most 3; margin -1)");
    }

    #[test]
    fn at_least_compares_accuracy() {
        let (status, value, _, _) = evaluate(
            Metric::Accuracy,
            Bound::AtLeast(0.95),
            metrics(1).value(Metric::Accuracy),
        );
        assert_eq!((status, value), (Status::Fail, Some(0.9)));
    }

    #[test]
    fn undefined_metric_is_an_error_not_a_pass() {
        let (status, value, ..) = evaluate(
            Metric::MeanConflict,
            Bound::AtMost(1.0),
            metrics(0).value(Metric::MeanConflict),
        );
        assert_eq!((status, value), (Status::Error, None));
    }
}
