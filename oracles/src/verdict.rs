//! Verdicts and how they are reached.

use serde::Serialize;
use sightline_dsl::{Check, Experiment, OverSeeds, Requirement, Scenario, Statistic};

use crate::Measurements;
use crate::check::seeds::SeedStatistics;
use crate::check::{invariant, metric, object, seeds, temporal};

/// The outcome of a check, from best to worst.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The requirement holds.
    Pass,
    /// Nothing to judge: the population is empty (no object came close, no
    /// sample, a window the run does not cover) or smaller than the check's
    /// minimum sample size. Neither a pass nor a failure; it fails the run
    /// unless the requirement accepts it with a reason.
    NotExercised,
    /// The requirement is violated.
    Fail,
    /// The requirement could not be checked: the measurements are inconsistent
    /// with the scenario (a metric missing from a recording, say).
    Error,
}

impl Status {
    /// `pass`, `not_exercised`, `fail` or `error`, as written in results.json.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::NotExercised => "not_exercised",
            Self::Fail => "fail",
            Self::Error => "error",
        }
    }

    /// The status in words: `pass`, `not exercised`, `fail`, `error`.
    pub fn words(self) -> &'static str {
        match self {
            Self::NotExercised => "not exercised",
            other => other.name(),
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
    /// The measured value (`None` when there is nothing to measure).
    pub value: Option<f64>,
    /// Signed margin: ≥ 0 holds, < 0 fails (`None` unless judged).
    pub margin: Option<f64>,
    /// The sample size behind `value`, in the units `measured` names (`None`
    /// when not even that is known).
    pub n: Option<u64>,
    /// What `value` holds, with its n: `value over n = 512 truly occupied
    /// cell-steps`, `median of n = 12 anticipation times`, `lower 95 % bound of
    /// the mean over 30 seeds`.
    pub measured: String,
    /// The check in words, with the numbers.
    pub message: String,
    /// For a check over seeds: what the seeds measured and the bound compared.
    pub seeds: Option<SeedStatistics>,
    /// For a temporal check: the time of the decisive step, seconds (in the
    /// run its message names when the point pools runs).
    pub time: Option<f64>,
}

impl Evaluation {
    /// A judged value: pass or fail by the sign of `margin`.
    pub(crate) fn judged(value: f64, margin: f64, n: u64, measured: String, message: String) -> Self {
        Self {
            status: if margin >= 0.0 { Status::Pass } else { Status::Fail },
            value: Some(value),
            margin: Some(margin),
            n: Some(n),
            ..Self::unjudged(Status::Pass, measured, message)
        }
    }

    /// Not exercised: `n` samples where the check needs more.
    pub(crate) fn not_exercised(n: u64, measured: String, message: String) -> Self {
        Self {
            n: Some(n),
            ..Self::unjudged(Status::NotExercised, measured, message)
        }
    }

    /// A failure with no value to show: some of the `n` samples cannot meet
    /// the requirement at all (an object never flagged, a NaN mass).
    pub(crate) fn failed(n: u64, measured: String, message: String) -> Self {
        Self {
            n: Some(n),
            ..Self::unjudged(Status::Fail, measured, message)
        }
    }

    /// An error: the measurements cannot be judged.
    pub(crate) fn error(message: String) -> Self {
        Self::unjudged(Status::Error, "nothing".into(), message)
    }

    fn unjudged(status: Status, measured: String, message: String) -> Self {
        Self {
            point: 0,
            status,
            value: None,
            margin: None,
            n: None,
            measured,
            message,
            seeds: None,
            time: None,
        }
    }
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
    /// The fewest samples a point needs to be judged.
    pub min_samples: u64,
    /// Why a not-exercised verdict is acceptable, when the scenario says so.
    pub accepted: Option<String>,
    /// The evaluation with the worst status and, among those, the smallest
    /// margin: the value that decides.
    pub decisive: Evaluation,
    /// One evaluation per point, in point order.
    pub evaluations: Vec<Evaluation>,
}

impl Verdict {
    /// The scenario's reason for accepting this verdict: only a not-exercised
    /// verdict is accepted, so a pass or a failure has none.
    pub fn acceptance(&self) -> Option<&str> {
        match self.status {
            Status::NotExercised => self.accepted.as_deref(),
            Status::Pass | Status::Fail | Status::Error => None,
        }
    }

    /// Whether the verdict fails the run: a failure, an error, or a
    /// not-exercised verdict the requirement does not accept.
    pub fn fails_run(&self) -> bool {
        match self.status {
            Status::Pass => false,
            Status::NotExercised => self.acceptance().is_none(),
            Status::Fail | Status::Error => true,
        }
    }
}

/// What a run's verdicts tell a CI gate: the worst status that fails the run,
/// `Pass` when none does and one requirement passes, and `NotExercised` when
/// none passes (no requirement at all, or each not exercised for an accepted
/// reason: nothing was judged, so nothing was passed).
pub fn headline(verdicts: &[Verdict]) -> Status {
    let failing = verdicts.iter().filter(|v| v.fails_run()).map(|v| v.status).max();
    match failing {
        Some(status) => status,
        None if verdicts.iter().any(|v| v.status == Status::Pass) => Status::Pass,
        None => Status::NotExercised,
    }
}

/// Checks every requirement of `scenario` against the measurements of a run
/// (a [`Run`](sightline_engine::Run), or a recording's), in requirement order.
pub fn check(scenario: &Scenario, measurements: &(impl Measurements + ?Sized)) -> Vec<Verdict> {
    scenario
        .requirements
        .iter()
        .map(|requirement| verdict(scenario, requirement, measurements))
        .collect()
}

fn verdict(scenario: &Scenario, requirement: &Requirement, measurements: &(impl Measurements + ?Sized)) -> Verdict {
    let min = requirement.min_samples;
    let evaluations: Vec<Evaluation> = requirement
        .points
        .iter()
        .map(|&point| {
            let evaluation = match requirement.check {
                Check::Metric {
                    metric: m,
                    bound,
                    over_seeds: None,
                } => {
                    let selection = &requirement.objects;
                    let sample = if selection.is_all() {
                        measurements.sample(point, 0, m)
                    } else {
                        measurements.selected_sample(point, m, selection)
                    };
                    metric::evaluate((m, selection), bound, sample, min)
                }
                Check::Metric {
                    metric: m,
                    bound,
                    over_seeds: Some(over),
                } => {
                    let samples: Vec<_> = (0..over.seeds as usize)
                        .map(|r| measurements.sample(point, r, m))
                        .collect();
                    seeds::evaluate(m, bound, over, &samples, min)
                }
                Check::Compare {
                    metric: m,
                    other,
                    by,
                    bound,
                } => {
                    let samples = [m, other].map(|metric| (metric, measurements.sample(point, 0, metric)));
                    metric::compare(samples, by, bound, min)
                }
                Check::Temporal {
                    signal,
                    operator,
                    bound,
                    within,
                } => {
                    let runs = measurements.series(point, signal).unwrap_or_default();
                    let window = temporal::Window {
                        within,
                        covered: run_end(scenario, point),
                        min_steps: min,
                    };
                    temporal::evaluate(signal, operator, bound, window, &runs)
                }
                Check::PerObject { property, bound } => {
                    let selection = &requirement.objects;
                    let values = measurements.per_object(point, property, selection).unwrap_or_default();
                    object::evaluate((property, selection), bound, &values, min)
                }
                Check::Invariant {
                    invariant: i,
                    tolerance,
                } => invariant::evaluate(i, tolerance, measurements.audit(point).as_ref(), min),
            };
            uncovered(scenario, point, Evaluation { point, ..evaluation })
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
        Check::Metric { bound, .. }
        | Check::Compare { bound, .. }
        | Check::Temporal { bound, .. }
        | Check::PerObject { bound, .. } => bound.threshold(),
        Check::Invariant { tolerance, .. } => tolerance,
    };
    Verdict {
        id: requirement.id.clone(),
        status: decisive.status,
        threshold,
        min_samples: min,
        accepted: requirement.accept_not_exercised.clone(),
        decisive,
        evaluations,
    }
}

/// A pass at a point whose run the imported trace does not cover is not
/// exercised: part of the run has no traced road users to judge.
fn uncovered(scenario: &Scenario, point: usize, evaluation: Evaluation) -> Evaluation {
    match &scenario.points[point].setup.experiment {
        Experiment::World(world) if evaluation.status == Status::Pass => match &world.uncovered {
            Some(why) => Evaluation {
                status: Status::NotExercised,
                message: format!("{}; not exercised: {why}", evaluation.message),
                ..evaluation
            },
            None => evaluation,
        },
        _ => evaluation,
    }
}

/// When a world point's run ends, seconds: its last step's time plus a step,
/// each step's state holding until the next (`None` for the field
/// experiment, which has no time).
fn run_end(scenario: &Scenario, point: usize) -> Option<f64> {
    match &scenario.points[point].setup.experiment {
        Experiment::World(world) => Some(world.steps as f64 * world.step),
        Experiment::Field(_) => None,
    }
}
