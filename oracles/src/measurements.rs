//! What the oracles judge: each sweep point's metric values and mass audit, its
//! replicates' values for checks over seeds, its signals over time and its
//! per-object properties.

use sightline_dsl::{Metric, ObjectProperty, ObjectSelection, Signal};
use sightline_engine::outcome::MassAudit;
use sightline_engine::outcome::Series;
use sightline_engine::{RoadUserValue, Run, Sample};

/// The measurements of every sweep point of a run, as the oracles read them: a
/// fresh [`Run`], or the values a recording carries (`sightline replay`). The
/// oracles read nothing else, so the same measurements give the same verdicts.
pub trait Measurements {
    /// The value of `metric` and its sample size at point `point` in replicate
    /// `replicate` (0: the point's own run; 1, 2, …: the replicate seeds of
    /// checks over seeds); `None` where it is not measured.
    fn sample(&self, point: usize, replicate: usize, metric: Metric) -> Option<Sample>;

    /// The value of a system's `metric` and its sample size over the
    /// object-steps `selection` keeps at point `point` (see
    /// [`Outcome::selected_sample`](sightline_engine::Outcome::selected_sample));
    /// `None` where it is not measured over it.
    fn selected_sample(&self, point: usize, metric: Metric, selection: &ObjectSelection) -> Option<Sample>;

    /// The mass-function audit of point `point`; `None` where nothing is fused.
    fn audit(&self, point: usize) -> Option<MassAudit>;

    /// `signal` over each run of point `point`; `None` where it is not measured.
    fn series(&self, point: usize, signal: Signal) -> Option<Vec<Series>>;

    /// `property` of each road user `selection` keeps at point `point` (see
    /// [`Outcome::per_object`](sightline_engine::Outcome::per_object)); `None`
    /// where it is not measured.
    fn per_object(
        &self,
        point: usize,
        property: ObjectProperty,
        selection: &ObjectSelection,
    ) -> Option<Vec<RoadUserValue>>;
}

impl Measurements for Run {
    fn sample(&self, point: usize, replicate: usize, metric: Metric) -> Option<Sample> {
        match replicate {
            0 => self.points[point].sample(metric),
            r => self.replicates[point].get(r - 1)?.sample(metric),
        }
    }

    fn selected_sample(&self, point: usize, metric: Metric, selection: &ObjectSelection) -> Option<Sample> {
        self.points[point].selected_sample(metric, selection)
    }

    fn audit(&self, point: usize) -> Option<MassAudit> {
        self.points[point].audit().copied()
    }

    fn series(&self, point: usize, signal: Signal) -> Option<Vec<Series>> {
        self.points[point].series(signal)
    }

    fn per_object(
        &self,
        point: usize,
        property: ObjectProperty,
        selection: &ObjectSelection,
    ) -> Option<Vec<RoadUserValue>> {
        self.points[point].per_object(property, selection)
    }
}
