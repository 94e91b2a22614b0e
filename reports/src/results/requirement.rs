//! A requirement's verdict and the evidence for it: the check as written, the
//! deciding point, every point it was checked at, and for a check over seeds
//! what the seeds gave.

use serde::Serialize;
use sightline_dsl::ObjectSelection;

/// A verdict as results.json writes it, from best to worst.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The requirement holds.
    Pass,
    /// Nothing to judge: the population is empty or smaller than the check's
    /// minimum sample size.
    NotExercised,
    /// The requirement is violated.
    Fail,
    /// The requirement could not be checked.
    Error,
}

impl Status {
    /// `pass`, `not_exercised`, `fail` or `error`, as results.json writes it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::NotExercised => "not_exercised",
            Self::Fail => "fail",
            Self::Error => "error",
        }
    }

    /// The verdict in words: `pass`, `not exercised`, `fail`, `error`.
    pub fn words(self) -> &'static str {
        match self {
            Self::NotExercised => "not exercised",
            other => other.name(),
        }
    }
}

/// One requirement's verdict and the evidence for it.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct RequirementResult {
    /// The id.
    pub id: String,
    /// The text.
    pub text: String,
    /// Line of the requirement in the scenario file.
    pub line: usize,
    /// The check as written.
    pub check: CheckInfo,
    /// The verdict.
    pub verdict: Status,
    /// Whether the verdict fails the run (a failure, an error, or not
    /// exercised without an accepted reason).
    pub fails_run: bool,
    /// Why a not-exercised verdict is acceptable, as the scenario says.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accept_not_exercised: Option<String>,
    /// The fewest samples a point needs to be judged.
    pub min_samples: u64,
    /// The deciding point's index.
    pub point: usize,
    /// The deciding measured value (worst status, then smallest margin).
    pub value: Option<f64>,
    /// The deciding value's sample size.
    pub n: Option<u64>,
    /// What the deciding value holds, with its n.
    pub measured: String,
    /// The threshold (for invariants: the tolerance).
    pub threshold: f64,
    /// The deciding margin (≥ 0 holds).
    pub margin: Option<f64>,
    /// The deciding check in words.
    pub message: String,
    /// Every point it was checked at.
    pub points: Vec<PointVerdict>,
}

impl RequirementResult {
    /// How the deciding value compares with `threshold`: `at_least`,
    /// `at_most` or `tolerance` as the check is written, but `at_least` for a
    /// share of seeds, whichever way its metric is bounded.
    pub fn relation(&self) -> &'static str {
        match self.check.over_seeds {
            Some(OverSeeds {
                statistic: Statistic::Share { .. },
                ..
            }) => "at_least",
            _ => self.check.relation,
        }
    }
}

/// A check in the form it was written.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CheckInfo {
    /// `metric`, `compare`, `always`, `eventually`, `per_object` or `invariant`.
    pub kind: &'static str,
    /// The metric, signal, property or invariant name.
    pub name: &'static str,
    /// `at_least`, `at_most` or `tolerance`.
    pub relation: &'static str,
    /// The threshold or tolerance.
    pub threshold: f64,
    /// The unit of the value compared with the threshold, and of the
    /// threshold and margin: `1` (dimensionless), `cells`, `s`, `m`, `B/s`,
    /// `objects` or `objects/run`.
    pub unit: &'static str,
    /// For a check over seeds: how many, at which confidence, bounding what.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub over_seeds: Option<OverSeeds>,
    /// For a temporal check: the window's length from the start, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub within: Option<f64>,
    /// For a comparison: the metric it is compared with.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub relative_to: Option<&'static str>,
    /// For a comparison: `ratio` or `difference`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub by: Option<&'static str>,
    /// For a per-object check: the road users it selects; for a system's
    /// metric (`sut_*`): the object-steps and detections it is summed over
    /// (left out: all).
    #[serde(skip_serializing_if = "ObjectSelection::is_all")]
    pub objects: ObjectSelection,
}

/// A metric check repeated over independent seeds, as written.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct OverSeeds {
    /// Independent runs of the point: its own seed, then seeds derived from it.
    pub seeds: u32,
    /// Confidence level of the one-sided bound.
    pub confidence: f64,
    /// What is bounded.
    pub statistic: Statistic,
}

/// What a check over seeds bounds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
#[schemars(deny_unknown_fields)]
pub enum Statistic {
    /// The metric's mean over the seeds (a Student-t bound).
    Mean,
    /// The share of seeds at which the threshold holds.
    Share {
        /// The share of seeds required to hold (0–1).
        share: f64,
        /// The binomial confidence bound.
        method: RateBound,
    },
}

/// A one-sided confidence bound of a binomial proportion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RateBound {
    /// The exact Clopper–Pearson bound.
    ClopperPearson,
    /// The Wilson score bound.
    Wilson,
}

/// A requirement checked at one point.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct PointVerdict {
    /// The point index.
    pub point: usize,
    /// The point's sweep label (empty without a sweep).
    pub label: String,
    /// The verdict at this point.
    pub verdict: Status,
    /// The measured value.
    pub value: Option<f64>,
    /// Its sample size.
    pub n: Option<u64>,
    /// What the value holds, with its n.
    pub measured: String,
    /// The margin.
    pub margin: Option<f64>,
    /// The check in words.
    pub message: String,
    /// For a check over seeds: the estimate and the bound compared.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seeds: Option<SeedStatistics>,
    /// For a temporal check: the time of the decisive step, seconds; when the
    /// point pools runs, in the run the message names (counted from 0; the
    /// recording's per-step topics show run 0 only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
}

/// What a check over seeds measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SeedStatistics {
    /// Seeds run.
    pub seeds: u32,
    /// Confidence level of the bound.
    pub confidence: f64,
    /// The bound's method: `student_t`, `clopper_pearson` or `wilson`.
    pub method: &'static str,
    /// The mean of the metric over the seeds, or the share of seeds judged to
    /// hold the threshold (a seed with fewer samples than `min_samples` is not
    /// counted as holding).
    pub estimate: f64,
    /// The one-sided confidence bound that is compared: of the estimate, or,
    /// for a share that fails with seeds not judged (too few samples), the
    /// bound at best, those seeds counted as holding.
    pub bound: f64,
}
