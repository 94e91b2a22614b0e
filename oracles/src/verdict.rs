//! Verdicts and how they are reached.

use serde::Serialize;
use sightline_dsl::{Check, Requirement, Scenario};

use crate::Measurements;
use crate::check::{invariant, metric};

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
            let (status, value, margin, message) = match requirement.check {
                Check::Metric { metric: m, bound } => metric::evaluate(m, bound, measurements.value(point, m)),
                Check::Invariant {
                    invariant: i,
                    tolerance,
                } => invariant::evaluate(i, tolerance, measurements.audit(point).as_ref()),
            };
            Evaluation {
                point,
                status,
                value,
                margin,
                message,
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
        Check::Metric { bound, .. } => bound.threshold(),
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
