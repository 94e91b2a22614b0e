//! Requirements, the checks they make (on a metric, a signal, every object or
//! an invariant), and published figures to compare with.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::metric::{Metric, ValueDomain};
use crate::Location;

/// A requirement with its check and the sweep points it applies to.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Requirement {
    /// Unique id (`FIELD-ERR-01`).
    pub id: String,
    /// The requirement in words.
    pub text: String,
    /// Where the requirement starts in the file, for traceability.
    pub location: Location,
    /// How it is checked.
    pub check: Check,
    /// Indices of the points it is checked at (never empty).
    pub points: Vec<usize>,
    /// The fewest samples (cells, steps, objects, times… as the check counts
    /// them) a point needs for the requirement to be exercised there.
    pub min_samples: u64,
    /// Why a not-exercised verdict is acceptable, when the scenario says so:
    /// the verdict stays `not_exercised`, and it does not fail the run.
    pub accept_not_exercised: Option<String>,
}

/// How a requirement is checked.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Check {
    /// A metric compared with a threshold.
    Metric {
        /// The metric.
        metric: Metric,
        /// The threshold.
        bound: Bound,
        /// Checked over independent seeds with a confidence bound instead of on
        /// the point's own run.
        over_seeds: Option<OverSeeds>,
    },
    /// A signal over time against a threshold, with a temporal operator.
    Temporal {
        /// The signal.
        signal: Signal,
        /// `always` or `eventually`.
        operator: Temporal,
        /// The threshold at each step.
        bound: Bound,
        /// Only the first this many seconds of the run (`None`: all of it).
        within: Option<f64>,
    },
    /// A property of every object that came within d_min of the ego.
    PerObject {
        /// The property.
        property: ObjectProperty,
        /// The threshold every object must meet.
        bound: Bound,
    },
    /// An invariant over every fused cell.
    Invariant {
        /// Which invariant.
        invariant: Invariant,
        /// Numerical tolerance.
        tolerance: f64,
    },
}

/// A metric check repeated over independent seeds: it passes only when a
/// one-sided confidence bound clears the threshold.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OverSeeds {
    /// Independent runs of the point: its own seed, then seeds derived from it.
    pub seeds: u32,
    /// Confidence level of the one-sided bound (0.5–1).
    pub confidence: f64,
    /// What is bounded.
    pub statistic: Statistic,
}

/// What a check over seeds bounds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// The metric's mean over the seeds: its lower (`at_least`) or upper
    /// (`at_most`) one-sided Student-t confidence bound must clear the threshold.
    Mean,
    /// The share of seeds at which the threshold holds: its lower one-sided
    /// confidence bound must be at least `share`.
    Share {
        /// The share of seeds required to hold (0–1).
        share: f64,
        /// The binomial confidence bound.
        method: RateBound,
    },
}

/// One-sided confidence bounds of a binomial proportion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RateBound {
    /// The exact Clopper–Pearson bound (from the Beta distribution): never below
    /// the stated confidence, often above.
    ClopperPearson,
    /// The Wilson score bound: closer to the stated confidence on average, below
    /// it for some sample sizes.
    Wilson,
}

/// Temporal operators over a signal's steps (signal temporal logic's G and F).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Temporal {
    /// At every step where the signal is defined; robustness is the smallest margin.
    Always,
    /// At some step where the signal is defined; robustness is the largest margin.
    Eventually,
}

/// Signals: a value per step, for temporal checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Signal {
    /// World: the step's `occupied_recall` (defined when a cell is truly occupied).
    OccupiedRecall,
    /// World: the step's `blind_recall` (defined when the ego misses an occupied cell).
    BlindRecall,
    /// World: the step's `occupied_precision` (defined when a cell is decided Occupy).
    OccupiedPrecision,
    /// Semantic: objects the ego knows only through an RSU, at each step with the ego.
    RsuOnlyObjects,
    /// Semantic: the shortest predicted time to conflict, seconds, in an RSU's
    /// message to the ego (defined at the cycles whose message flags a conflict).
    TimeToConflict,
}

impl Signal {
    /// Every signal in documentation order.
    pub const ALL: [Signal; 5] = [
        Self::OccupiedRecall,
        Self::BlindRecall,
        Self::OccupiedPrecision,
        Self::RsuOnlyObjects,
        Self::TimeToConflict,
    ];

    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::OccupiedRecall => "occupied_recall",
            Self::BlindRecall => "blind_recall",
            Self::OccupiedPrecision => "occupied_precision",
            Self::RsuOnlyObjects => "rsu_only_objects",
            Self::TimeToConflict => "time_to_conflict",
        }
    }

    /// Whether a world measuring collective perception has it.
    pub fn in_world(self) -> bool {
        matches!(self, Self::OccupiedRecall | Self::BlindRecall | Self::OccupiedPrecision)
    }

    /// Whether a world running the semantic pipeline has it.
    pub fn in_semantic(self) -> bool {
        !self.in_world()
    }

    /// The values it can take at a step.
    pub fn domain(self) -> ValueDomain {
        match self {
            Self::OccupiedRecall | Self::BlindRecall | Self::OccupiedPrecision => ValueDomain::Fraction,
            Self::RsuOnlyObjects => ValueDomain::Count,
            Self::TimeToConflict => ValueDomain::NonNegative,
        }
    }
}

/// Properties of the objects that came within d_min of the ego.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ObjectProperty {
    /// Seconds from the first RSU message flagging a conflict with the object to
    /// its close approach (an unflagged object has none, and fails).
    WarningTime,
}

impl ObjectProperty {
    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::WarningTime => "warning_time",
        }
    }

    /// The values an object's property can take (an object may also have none).
    pub fn domain(self) -> ValueDomain {
        match self {
            Self::WarningTime => ValueDomain::NonNegative,
        }
    }
}

/// A threshold and its direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    /// value ≥ threshold.
    AtLeast(f64),
    /// value ≤ threshold.
    AtMost(f64),
}

impl Bound {
    /// The threshold.
    pub fn threshold(self) -> f64 {
        match self {
            Self::AtLeast(t) | Self::AtMost(t) => t,
        }
    }

    /// Signed margin: positive when `value` satisfies the bound.
    pub fn margin(self, value: f64) -> f64 {
        match self {
            Self::AtLeast(t) => value - t,
            Self::AtMost(t) => t - value,
        }
    }
}

/// Invariants checked over every fused cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Invariant {
    /// Every fused cell holds a mass function: each mass finite and in [0, 1], the
    /// masses summing to 1 within the tolerance (for `bayes`: the occupancy
    /// probability is finite and in [0, 1]).
    MassFunction,
}

impl Invariant {
    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::MassFunction => "mass_function",
        }
    }
}

/// A published figure to show beside the measured one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reference {
    /// Where it is published.
    pub source: String,
    /// The metric it reports.
    pub metric: Metric,
    /// The published value.
    pub value: f64,
    /// Indices of the points it corresponds to (never empty).
    pub points: Vec<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The documented ranges: a metric "(0–1)" is a fraction, a count of cells
    /// a whole number.
    #[test]
    fn metrics_documented_as_shares_are_fractions_and_cell_counts_whole() {
        assert_eq!(Metric::Accuracy.domain(), ValueDomain::Fraction);
        assert_eq!(Metric::PacketDeliveryRatio.domain(), ValueDomain::Fraction);
        assert_eq!(Metric::FalseAlarms.domain(), ValueDomain::Count);
        assert_eq!(
            Metric::MissedCriticals.domain(),
            ValueDomain::NonNegative,
            "a mean over runs"
        );
        assert_eq!(Signal::RsuOnlyObjects.domain(), ValueDomain::Count);
        assert_eq!(ObjectProperty::WarningTime.domain(), ValueDomain::NonNegative);
    }
}
