//! A requirement's verdict and the check it judged, from the language's and
//! the oracles' types.

use sightline_dsl::{Bound, Check, Requirement, Temporal};
use sightline_oracles::Verdict;

use crate::results::{
    CheckInfo, OverSeeds, PointVerdict, RateBound, RequirementResult, SeedStatistics, Statistic, Status,
};

pub(super) fn requirement_result(requirement: &Requirement, verdict: &Verdict, labels: &[String]) -> RequirementResult {
    RequirementResult {
        id: requirement.id.clone(),
        text: requirement.text.clone(),
        line: requirement.location.line,
        check: check_info(&requirement.check),
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

fn check_info(check: &Check) -> CheckInfo {
    match *check {
        Check::Metric {
            metric,
            bound,
            over_seeds,
        } => CheckInfo {
            kind: "metric",
            name: metric.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds: over_seeds.map(self::over_seeds),
            within: None,
        },
        Check::Temporal {
            signal,
            operator,
            bound,
            within,
        } => CheckInfo {
            kind: match operator {
                Temporal::Always => "always",
                Temporal::Eventually => "eventually",
            },
            name: signal.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds: None,
            within,
        },
        Check::PerObject { property, bound } => CheckInfo {
            kind: "per_object",
            name: property.name(),
            relation: relation(bound),
            threshold: bound.threshold(),
            over_seeds: None,
            within: None,
        },
        Check::Invariant { invariant, tolerance } => CheckInfo {
            kind: "invariant",
            name: invariant.name(),
            relation: "tolerance",
            threshold: tolerance,
            over_seeds: None,
            within: None,
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
