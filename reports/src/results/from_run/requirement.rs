//! A requirement's verdict and the check it judged, from the language's and
//! the oracles' types.

use sightline_dsl::{Bound, Check, ObjectSelection, Requirement, Temporal};
use sightline_oracles::Verdict;

use crate::results::{
    CheckInfo, OverSeeds, PointVerdict, RateBound, RequirementResult, SeedStatistics, Statistic, Status,
};

pub(super) fn requirement_result(requirement: &Requirement, verdict: &Verdict, labels: &[String]) -> RequirementResult {
    RequirementResult {
        id: requirement.id.clone(),
        text: requirement.text.clone(),
        line: requirement.location.line,
        check: check_info(requirement),
        verdict: verdict.status.into(),
        fails_run: verdict.fails_run(),
        accept_not_exercised: verdict.accepted.clone(),
        min_samples: verdict.min_samples,
        point: verdict.decisive.point,
        value: verdict.decisive.value,
        n: verdict.decisive.n,
        measured: verdict.decisive.measured.clone(),
        threshold: verdict.threshold,
        margin: verdict.decisive.margin,
        message: verdict.decisive.message.clone(),
        points: verdict
            .evaluations
            .iter()
            .map(|e| PointVerdict {
                point: e.point,
                label: labels[e.point].clone(),
                verdict: e.status.into(),
                value: e.value,
                n: e.n,
                measured: e.measured.clone(),
                margin: e.margin,
                message: e.message.clone(),
                seeds: e.seeds.map(seed_statistics),
                time: e.time,
            })
            .collect(),
    }
}

fn check_info(requirement: &Requirement) -> CheckInfo {
    let plain = |kind, name, bound: Bound| CheckInfo {
        kind,
        name,
        relation: relation(bound),
        threshold: bound.threshold(),
        unit: requirement.check.unit().symbol(),
        over_seeds: None,
        within: None,
        relative_to: None,
        by: None,
        objects: ObjectSelection::default(),
    };
    match requirement.check {
        Check::Metric {
            metric,
            bound,
            over_seeds,
        } => CheckInfo {
            over_seeds: over_seeds.map(self::over_seeds),
            objects: requirement.objects.clone(),
            ..plain("metric", metric.name(), bound)
        },
        Check::Compare {
            metric,
            other,
            by,
            bound,
        } => CheckInfo {
            relative_to: Some(other.name()),
            by: Some(by.name()),
            ..plain("compare", metric.name(), bound)
        },
        Check::Temporal {
            signal,
            operator,
            bound,
            within,
        } => {
            let kind = match operator {
                Temporal::Always => "always",
                Temporal::Eventually => "eventually",
            };
            CheckInfo {
                within,
                ..plain(kind, signal.name(), bound)
            }
        }
        Check::PerObject { property, bound } => CheckInfo {
            objects: requirement.objects.clone(),
            ..plain("per_object", property.name(), bound)
        },
        Check::Invariant { invariant, tolerance } => CheckInfo {
            relation: "tolerance",
            threshold: tolerance,
            ..plain("invariant", invariant.name(), Bound::AtMost(tolerance))
        },
    }
}

fn relation(bound: Bound) -> &'static str {
    match bound {
        Bound::AtLeast(_) => "at_least",
        Bound::AtMost(_) => "at_most",
    }
}

fn over_seeds(over: sightline_dsl::OverSeeds) -> OverSeeds {
    let sightline_dsl::OverSeeds {
        seeds,
        confidence,
        statistic,
    } = over;
    OverSeeds {
        seeds,
        confidence,
        statistic: match statistic {
            sightline_dsl::Statistic::Mean => Statistic::Mean,
            sightline_dsl::Statistic::Share { share, method } => Statistic::Share {
                share,
                method: match method {
                    sightline_dsl::RateBound::ClopperPearson => RateBound::ClopperPearson,
                    sightline_dsl::RateBound::Wilson => RateBound::Wilson,
                },
            },
        },
    }
}

fn seed_statistics(statistics: sightline_oracles::SeedStatistics) -> SeedStatistics {
    let sightline_oracles::SeedStatistics {
        seeds,
        confidence,
        method,
        estimate,
        bound,
    } = statistics;
    SeedStatistics {
        seeds,
        confidence,
        method,
        estimate,
        bound,
    }
}

impl From<sightline_oracles::Status> for Status {
    fn from(status: sightline_oracles::Status) -> Self {
        match status {
            sightline_oracles::Status::Pass => Self::Pass,
            sightline_oracles::Status::NotExercised => Self::NotExercised,
            sightline_oracles::Status::Fail => Self::Fail,
            sightline_oracles::Status::Error => Self::Error,
        }
    }
}
