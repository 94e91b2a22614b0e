//! What the oracles judge: each sweep point's metric values and mass audit.

use sightline_dsl::Metric;
use sightline_engine::{MassAudit, Run};

/// The measurements of every sweep point of a run, as the oracles read them: a
/// fresh [`Run`], or the values a recording carries (`sightline replay`). The
/// oracles read nothing else, so the same measurements give the same verdicts.
pub trait Measurements {
    /// The value of `metric` at point `point`; `None` where it is not defined.
    fn value(&self, point: usize, metric: Metric) -> Option<f64>;

    /// The mass-function audit of point `point`; `None` where nothing is fused.
    fn audit(&self, point: usize) -> Option<MassAudit>;
}

impl Measurements for Run {
    fn value(&self, point: usize, metric: Metric) -> Option<f64> {
        self.points[point].value(metric)
    }

    fn audit(&self, point: usize) -> Option<MassAudit> {
        self.points[point].audit().copied()
    }
}
