//! Verdicts and how they are reached.

use serde::Serialize;
use sightline_dsl::{Check, OverSeeds, Requirement, Scenario, Statistic};

use crate::Measurements;
use crate::check::seeds::SeedStatistics;
use crate::check::{invariant, metric, object, seeds, temporal};

/// The outcome of a check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The requirement holds.
    Pass,
    /// The requirement is violated.
    Fail,
    /// The requirement could not be checked (a metric undefined at a point).
    Error,
}

impl Status {
    /// `pass`, `fail` or `error`, as written in results.json.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::Fail => "fail",
            Self::Error => "error",
        }
    }
}

/// A requirement checked at one sweep point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// Index of the sweep point.
    pub point: usize,
    /// The outcome.
    pub status: Status,
    /// The measured value (`None` when it could not be measured).
    pub value: Option<f64>,
    /// Signed margin: ≥ 0 holds, < 0 fails (`None` on error).
    pub margin: Option<f64>,
    /// The check in words, with the numbers.
    pub message: String,
    /// For a check over seeds: what the seeds measured and the bound compared.
    pub seeds: Option<SeedStatistics>,
    /// For a temporal check: the time of the decisive step, seconds.
    pub time: Option<f64>,
}

/// A requirement checked at every point it applies to.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// The requirement's id.
    pub id: String,
    /// The worst status over the points.
    pub status: Status,
    /// The threshold (for invariants: the tolerance).
    pub threshold: f64,
    /// The evaluation with the smallest margin (errors first): the value that decides.
    pub decisive: Evaluation,
    /// One evaluation per point, in point order.
    pub evaluations: Vec<Evaluation>,
}

/// Checks every requirement of `scenario` against the measurements of a run
/// (a [`Run`](sightline_engine::Run), or a recording's), in requirement order.
pub fn check(scenario: &Scenario, measurements: &(impl Measurements + ?Sized)) -> Vec<Verdict> {
    scenario
        .requirements
        .iter()
        .map(|requirement| verdict(requirement, measurements))
        .collect()
}

fn verdict(requirement: &Requirement, measurements: &(impl Measurements + ?Sized)) -> Verdict {
    let evaluations: Vec<Evaluation> = requirement
        .points
        .iter()
        .map(|&point| {
            let mut time = None;
            let (status, value, margin, message, seeds) = match requirement.check {
                Check::Metric {
                    metric: m,
                    bound,
                    over_seeds: None,
                } => {
                    let (status, value, margin, message) = metric::evaluate(m, bound, measurements.value(point, 0, m));
                    (status, value, margin, message, None)
                }
                Check::Metric {
                    metric: m,
                    bound,
                    over_seeds: Some(over),
                } => {
                    let values: Vec<Option<f64>> = (0..over.seeds as usize)
                        .map(|r| measurements.value(point, r, m))
                        .collect();
                    seeds::evaluate(m, bound, over, &values)
                }
                Check::Temporal {
                    signal,
                    operator,
                    bound,
                    within,
                } => {
                    let runs = measurements.series(point, signal).unwrap_or_default();
                    let found = temporal::evaluate(signal, operator, bound, within, &runs);
                    time = found.time;
                    (found.status, found.value, found.margin, found.message, None)
                }
                Check::PerObject { property, bound } => {
                    let values = measurements.per_object(point, property).unwrap_or_default();
                    let (status, value, margin, message) = object::evaluate(property, bound, &values);
                    (status, value, margin, message, None)
                }
                Check::Invariant {
                    invariant: i,
                    tolerance,
                } => {
                    let (status, value, margin, message) =
                        invariant::evaluate(i, tolerance, measurements.audit(point).as_ref());
                    (status, value, margin, message, None)
                }
            };
            Evaluation {
                point,
                status,
                value,
                margin,
                message,
                seeds,
                time,
            }
        })
        .collect();
    let decisive = evaluations
        .iter()
        .min_by(|a, b| {
            b.status.cmp(&a.status).then(
                a.margin
                    .unwrap_or(f64::NEG_INFINITY)
                    .total_cmp(&b.margin.unwrap_or(f64::NEG_INFINITY)),
            )
        })
        .expect("the dsl gives every requirement at least one point")
        .clone();
    let threshold = match requirement.check {
        Check::Metric {
            over_seeds:
                Some(OverSeeds {
                    statistic: Statistic::Share { share, .. },
                    ..
                }),
            ..
        } => share,
        Check::Metric { bound, .. } | Check::Temporal { bound, .. } | Check::PerObject { bound, .. } => {
            bound.threshold()
        }
        Check::Invariant { tolerance, .. } => tolerance,
    };
    Verdict {
        id: requirement.id.clone(),
        status: decisive.status,
        threshold,
        decisive,
        evaluations,
    }
}
