//! Measured values against their domains, checked before anything is judged.
//!
//! A fraction outside [0, 1], a negative or fractional count, a NaN or an
//! infinity where the metric documents none: each is a defect in what produced
//! the measurements (or a file altered behind its checksum), and a verdict
//! reached from it would mean nothing. `sightline merge` and `sightline replay`
//! refuse such measurements as an internal error.

use std::fmt;

use sightline_dsl::{Check, Metric, ObjectProperty, Scenario, Signal, ValueDomain};

use crate::Measurements;

/// A measured value outside its domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutOfDomain {
    /// The sweep point, an index into [`Scenario::points`].
    pub point: usize,
    /// What was measured, and where in the point's runs.
    pub quantity: Quantity,
    /// The value.
    pub value: f64,
}

/// A measured quantity of a sweep point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// A metric of one of the point's runs.
    Metric {
        /// The metric.
        metric: Metric,
        /// 0: the point's own run; r ≥ 1: the r-th replicate of checks over seeds.
        replicate: usize,
    },
    /// A signal at one step.
    Signal {
        /// The signal.
        signal: Signal,
        /// The step's time, seconds.
        time: f64,
    },
    /// A system's metric over the selection (`objects`) of one requirement.
    Selected {
        /// The metric.
        metric: Metric,
        /// The requirement, an index into [`Scenario::requirements`].
        requirement: usize,
    },
    /// A property of one of the road users a per-object check judges.
    Object {
        /// The property.
        property: ObjectProperty,
        /// The road user's position in the list the check judges, from 0.
        object: usize,
    },
}

impl Quantity {
    /// The values the quantity can take.
    pub fn domain(self) -> ValueDomain {
        match self {
            Self::Metric { metric, .. } | Self::Selected { metric, .. } => metric.domain(),
            Self::Signal { signal, .. } => signal.domain(),
            Self::Object { property, .. } => property.domain(),
        }
    }
}

impl fmt::Display for OutOfDomain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (point, value, domain) = (self.point, self.value, self.quantity.domain());
        match self.quantity {
            Quantity::Metric { metric, replicate: 0 } => write!(f, "point {point}: {} = {value}", metric.name()),
            Quantity::Metric { metric, replicate } => {
                write!(f, "point {point}, replicate {replicate}: {} = {value}", metric.name())
            }
            Quantity::Selected { metric, requirement } => write!(
                f,
                "point {point}: {} over requirements[{requirement}]'s `objects` = {value}",
                metric.name()
            ),
            Quantity::Signal { signal, time } => write!(f, "point {point}: {} = {value} at {time} s", signal.name()),
            Quantity::Object { property, object } => {
                write!(f, "point {point}: {} = {value} of object {object}", property.name())
            }
        }?;
        write!(f, ", outside its domain ({domain})")
    }
}

/// Every value in `measurements` outside its domain, point by point: each
/// metric of each of the point's runs (its own and the replicates its checks
/// over seeds need), each signal at each step, each system metric over a
/// requirement's selection, each property of each road user a per-object
/// check judges. Empty when all are in their domains.
pub fn out_of_domain(scenario: &Scenario, measurements: &(impl Measurements + ?Sized)) -> Vec<OutOfDomain> {
    let mut runs = vec![0; scenario.points.len()];
    for unit in sightline_engine::units(scenario) {
        for &point in &unit.group {
            runs[point] = runs[point].max(unit.replicate as usize + 1);
        }
    }
    let mut found = Vec::new();
    let mut check = |point: usize, quantity: Quantity, value: f64| {
        if !quantity.domain().contains(value) {
            found.push(OutOfDomain { point, quantity, value });
        }
    };
    for (point, &runs) in runs.iter().enumerate() {
        for replicate in 0..runs {
            for metric in Metric::ALL {
                if let Some(value) = measurements.sample(point, replicate, metric).and_then(|s| s.value) {
                    check(point, Quantity::Metric { metric, replicate }, value);
                }
            }
        }
        for signal in Signal::ALL {
            for &(time, value) in measurements.series(point, signal).iter().flatten().flatten() {
                check(point, Quantity::Signal { signal, time }, value);
            }
        }
        let judged = scenario.requirements.iter().enumerate();
        for (index, requirement) in judged.filter(|(_, r)| r.points.contains(&point)) {
            let selection = &requirement.objects;
            match requirement.check {
                Check::Metric { metric, .. } if !selection.is_all() => {
                    if let Some(value) = measurements
                        .selected_sample(point, metric, selection)
                        .and_then(|s| s.value)
                    {
                        check(
                            point,
                            Quantity::Selected {
                                metric,
                                requirement: index,
                            },
                            value,
                        );
                    }
                }
                Check::PerObject { property, .. } => {
                    let values = measurements.per_object(point, property, selection);
                    for (object, value) in values.iter().flatten().enumerate() {
                        if let Some(value) = value.value {
                            check(point, Quantity::Object { property, object }, value);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{ObjectSelection, Options, compile};
    use sightline_engine::outcome::{MassAudit, Series};
    use sightline_engine::{Outcome, RoadUserValue, Sample, simulate};

    use super::*;

    /// Two points of the field experiment, the second checked over three seeds.
    const FIELD: &str = r#"
sightline: 1
name: domains
seed: 3
grid: { size: [20, 20], cell: 1 }
field:
  truth: { occupied_fraction: 0.2 }
  sensors: { range: 15, layout: { regular: { rows: 1, cols: 2 } } }
  masses: {}
sweep:
  field.masses.gamma: [4, 30]
requirements:
  - { id: ACC, text: accurate, check: { metric: accuracy, at_least: 0.5 } }
  - id: SEEDS
    text: accurate over seeds
    where: { field.masses.gamma: 30 }
    check: { metric: accuracy, at_least: 0.5, seeds: 3 }
"#;

    #[test]
    fn a_run_in_its_domains_passes_and_a_share_above_one_is_named() {
        let scenario = compile("t.yaml", FIELD, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
        let mut run = simulate(&scenario);
        assert_eq!(out_of_domain(&scenario, &run), []);
        assert_eq!(run.replicates[1].len(), 2, "two replicates of point 1");

        // Accuracy 1.11 on replicate 2 of point 1: correct cells beyond all cells.
        let Outcome::Field(field) = &mut run.replicates[1][1] else {
            panic!("a field outcome")
        };
        field.metrics.correct = field.metrics.cells * 111 / 100;
        let accuracy = field.metrics.correct as f64 / field.metrics.cells as f64;
        // A NaN uncertainty on point 0: not finite, so outside [0, 1] too.
        let Outcome::Field(first) = &mut run.points[0] else {
            panic!("a field outcome")
        };
        first.metrics.mean_uncertainty = Some(f64::NAN);
        let found = out_of_domain(&scenario, &run);
        let metrics: Vec<_> = found
            .iter()
            .map(|o| match o.quantity {
                Quantity::Metric { metric, replicate } => (o.point, replicate, metric),
                other => panic!("only metrics are damaged, found {other:?}"),
            })
            .collect();
        assert_eq!(
            metrics,
            [(0, 0, Metric::MeanUncertainty), (1, 2, Metric::Accuracy)],
            "{found:?}"
        );
        assert_eq!(
            found[1].to_string(),
            format!("point 1, replicate 2: accuracy = {accuracy}, outside its domain ([0, 1])")
        );
    }

    /// A system's precision over one requirement's selection, and nothing else.
    struct SelectedPrecision(f64);

    impl Measurements for SelectedPrecision {
        fn sample(&self, _: usize, _: usize, _: Metric) -> Option<Sample> {
            None
        }
        fn selected_sample(&self, _: usize, metric: Metric, _: &ObjectSelection) -> Option<Sample> {
            (metric == Metric::SutPrecision).then_some(Sample {
                value: Some(self.0),
                n: 2,
            })
        }
        fn audit(&self, _: usize) -> Option<MassAudit> {
            None
        }
        fn series(&self, _: usize, _: Signal) -> Option<Vec<Series>> {
            None
        }
        fn per_object(&self, _: usize, _: ObjectProperty, _: &ObjectSelection) -> Option<Vec<RoadUserValue>> {
            None
        }
    }

    #[test]
    fn a_system_metric_over_a_selection_is_checked_too() {
        let text = r#"
sightline: 1
name: a selection's domain
time: { duration: 0.1, step: 0.1 }
grid: { origin: [-30, -30], size: [60, 60], cell: 1 }
roads: [{ id: ns, polyline: [[0, -30], [0, 30]], speed_limit: 10 }]
sensor_models: { lidar: { range: 40 } }
agents:
  - { id: ego, kind: car, route: [ns], start: { offset: 20 }, speed: { target: 0 }, connected: true, sensors: [lidar] }
  - { id: car, kind: car, route: [ns], start: { offset: 40 }, speed: { target: 0 } }
perception: { ego: ego }
fusion: { method: bayes }
system_under_test: { command: [sh, -c, "exit 0"], agent: ego }
requirements:
  - { id: ALL, text: all, check: { metric: sut_precision, at_least: 0.5 } }
  - { id: CARS, text: cars, check: { metric: sut_precision, at_least: 0.5, objects: { classes: [car] } } }
"#;
        let scenario = compile("t.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(out_of_domain(&scenario, &SelectedPrecision(1.0)), []);
        let found = out_of_domain(&scenario, &SelectedPrecision(1.5));
        let selected = Quantity::Selected {
            metric: Metric::SutPrecision,
            requirement: 1,
        };
        assert_eq!(
            found,
            [OutOfDomain {
                point: 0,
                quantity: selected,
                value: 1.5
            }]
        );
        assert_eq!(
            found[0].to_string(),
            "point 0: sut_precision over requirements[1]'s `objects` = 1.5, outside its domain ([0, 1])"
        );
    }
}
