//! What a finished point says: its metrics' values and samples, its
//! signals, and its road users' per-object properties.

use serde::{Deserialize, Serialize};
use sightline_dsl::{JointPart, Metric, ObjectProperty, ObjectSelection, Signal};

use super::Outcome;
use crate::metrics::{MassAudit, Series};
use crate::semantic::SemanticMetrics;
use crate::world::WorldOutcome;

impl Outcome {
    /// The value of `metric`, or `None` where it is not defined for this run.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        match self {
            Self::Field(o) => o.metrics.value(metric),
            Self::World(o) if metric.of_system() => o.system.as_ref()?.value(metric),
            Self::World(o) => match o.joint_part(metric) {
                Some((JointPart::Semantic, s, metric)) => s.value(metric),
                Some((JointPart::Grid, _, metric)) => o.metrics.value(metric),
                None if o.semantic.is_some() => None,
                None => o.metrics.value(metric),
            },
            Self::Semantic(m) => m.value(metric),
        }
    }

    /// Every defined metric in documentation order.
    pub fn values(&self) -> Vec<(Metric, f64)> {
        Metric::ALL
            .iter()
            .filter_map(|&m| self.value(m).map(|v| (m, v)))
            .collect()
    }

    /// `metric`'s value and the number of samples it is computed over; `None`
    /// where this kind of run does not measure it.
    pub fn sample(&self, metric: Metric) -> Option<Sample> {
        let n = match self {
            Self::Field(o) => o.metrics.sample_size(metric),
            Self::World(o) if metric.of_system() => o.system.as_ref()?.sample_size(metric),
            Self::World(o) => match o.joint_part(metric) {
                Some((JointPart::Semantic, s, metric)) => s.sample_size(metric),
                Some((JointPart::Grid, _, metric)) => o.metrics.sample_size(metric, o.audit.cells),
                None if o.semantic.is_some() => None,
                None => o.metrics.sample_size(metric, o.audit.cells),
            },
            Self::Semantic(m) => m.sample_size(metric),
        }?;
        Some(Sample {
            value: self.value(metric),
            n,
        })
    }

    /// [`Outcome::sample`] of a system's `metric` over the object-steps
    /// `selection` keeps; `None` where it is not measured over it.
    pub fn selected_sample(&self, metric: Metric, selection: &ObjectSelection) -> Option<Sample> {
        let Self::World(o) = self else { return None };
        let (value, n) = o.system.as_ref()?.selected_sample(metric, selection)?;
        Some(Sample { value, n })
    }

    /// [`Outcome::sample`] of every metric this kind of run measures, in
    /// documentation order.
    pub fn samples(&self) -> Vec<(Metric, Sample)> {
        Metric::ALL
            .iter()
            .filter_map(|&m| self.sample(m).map(|s| (m, s)))
            .collect()
    }

    /// `signal` over each run of this point (one series for a world, one per
    /// pooled run for a semantic point); `None` where it is not measured.
    pub fn series(&self, signal: Signal) -> Option<Vec<Series>> {
        if let Self::World(o) = self
            && signal.in_world()
        {
            return o.series(signal).map(|series| vec![series]);
        }
        let m = self.semantic()?;
        match signal {
            Signal::RsuOnlyObjects => Some(m.rsu_only.clone()),
            Signal::TimeToConflict => Some(m.time_to_conflict.clone()),
            Signal::OccupiedRecall | Signal::BlindRecall | Signal::OccupiedPrecision => None,
        }
    }

    /// `property` of every road user `selection` keeps, in order (`None` for
    /// one without the property): of every object that came within d_min of
    /// the ego for `warning_time` (which selects nothing), of every relevant
    /// road user's record for the others, of the system under test's record
    /// for its properties (`sut_delay`: of those that came into a served
    /// sensor's sight); `None` where it is not measured (a property of the
    /// fused grid outside a joint world, of a system without one).
    pub fn per_object(&self, property: ObjectProperty, selection: &ObjectSelection) -> Option<Vec<RoadUserValue>> {
        if property.of_system() {
            let Self::World(o) = self else { return None };
            let objects = &o.system.as_ref()?.objects;
            return Some(
                (objects.iter())
                    .filter(|object| object.selected_by(selection) && object.judged_on(property))
                    .map(|object| RoadUserValue {
                        who: object.id.clone(),
                        value: object.property(property),
                    })
                    .collect(),
            );
        }
        let m = self.semantic()?;
        if property.needs_grid() && !matches!(self, Self::World(_)) {
            return None;
        }
        // A road user's id, with its run where the point pools runs.
        let who = |id: &str, run: u32| {
            if m.runs > 1 {
                format!("{id} of run {run}")
            } else {
                id.to_string()
            }
        };
        Some(if property.of_record() {
            (m.objects.iter())
                .filter(|record| record.selected_by(selection))
                .map(|record| RoadUserValue {
                    who: who(&record.id, record.run),
                    value: record.property(property),
                })
                .collect()
        } else {
            (m.approaches.iter())
                .map(|approach| RoadUserValue {
                    who: format!("{} at {} s", who(&approach.id, approach.run), approach.at),
                    value: approach.warning_time(),
                })
                .collect()
        })
    }

    /// What the semantic pipeline measured: a semantic point's metrics, a
    /// joint world's pipeline's; `None` where it does not run.
    pub fn semantic(&self) -> Option<&SemanticMetrics> {
        match self {
            Self::Semantic(m) => Some(m),
            Self::World(o) => o.semantic.as_deref(),
            Self::Field(_) => None,
        }
    }

    /// The mass-function audit of every fused cell; `None` where nothing is fused.
    pub fn audit(&self) -> Option<&MassAudit> {
        match self {
            Self::Field(o) => Some(&o.audit),
            Self::World(o) => Some(&o.audit),
            Self::Semantic(_) => None,
        }
    }
}

impl WorldOutcome {
    /// In a joint world, which model measures `metric`, that model's
    /// metrics (the pipeline's, for [`JointPart::Semantic`]) and the metric
    /// it measures it as; `None` outside a joint world, and for a metric a
    /// joint world does not measure.
    fn joint_part(&self, metric: Metric) -> Option<(JointPart, &SemanticMetrics, Metric)> {
        let semantic = self.semantic.as_deref()?;
        metric.in_joint().then(|| {
            let (part, as_metric) = metric.joint_part();
            (part, semantic, as_metric)
        })
    }
}

/// One road user's value of a per-object property, and who it is.
#[derive(Debug, Clone, PartialEq)]
pub struct RoadUserValue {
    /// Its id, with its run where the point pools several (`ped_3 of run 2`);
    /// for `warning_time`, the road user with when it came within d_min of the
    /// ego (`ped_3 at 12.4 s`).
    pub who: String,
    /// Its value (`None`: it has none).
    pub value: Option<f64>,
}

/// A metric as measured: its value (`None` where it is undefined, an empty
/// population) and its sample size n, counted in [`Metric::population`] units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// The value.
    pub value: Option<f64>,
    /// How many samples it is computed over.
    pub n: u64,
}
