//! Requirements, the metrics they check, and published figures to compare with.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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

/// Metrics. Counts are numbers of cells. Some exist only in the field experiment,
/// some only in worlds (see [`Metric::in_field`], [`Metric::in_world`],
/// [`Metric::in_semantic`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Share of all cells whose decided state equals the ground truth (0–1).
    Accuracy,
    /// Cells with no decision (p_max − p_others < θ): seed 001's Table III.
    BelowThreshold,
    /// `below_threshold` as a share of all cells (0–1).
    BelowThresholdFraction,
    /// Cells decided Occupy that are truly empty.
    FalseAlarms,
    /// Cells decided Empty that are truly occupied.
    MissedDetections,
    /// `false_alarms` + `missed_detections`: confident wrong decisions.
    ConfidentErrors,
    /// `confident_errors` as a share of all cells (0–1).
    ConfidentErrorRate,
    /// Cells decided Unknown (the Unknown mass dominates).
    DecidedUnknown,
    /// Cells no sensor observes.
    Unobserved,
    /// Mean per-cell uncertainty over observed cells (0–1): the Unknown mass for
    /// evidential methods, the binary entropy of the occupancy probability (bits)
    /// for `bayes`.
    MeanUncertainty,
    /// Mean conflict K over observed cells (evidential methods only, 0–1).
    MeanConflict,
    /// Largest conflict K of any cell (evidential methods only, 0–1).
    MaxConflict,
    /// Cells whose sources are in total conflict, K = 1 (evidential methods only).
    TotalConflictCells,
    /// Cells fused with the distance-weighted rule (evidential methods only).
    WeightedCells,
    /// World: Σ cells observed by any cooperating agent / Σ cells observed by the
    /// ego, minus 1, over the run (seed 000 reports +260 %, that is 2.6).
    FovGain,
    /// World: share of the truly occupied cells the fused grid decides Occupy,
    /// over the run, the cooperating agents' own footprints (self-report) left
    /// out (0–1).
    OccupiedRecall,
    /// World: share of the cells the fused grid decides Occupy that are truly
    /// occupied, over the run (0–1).
    OccupiedPrecision,
    /// World: `occupied_recall` over the cells the ego does not observe itself (0–1).
    BlindRecall,
    /// World: `occupied_recall` with the cooperating agents' own footprints
    /// counted as well, as a grid that holds every road user is scored (0–1).
    OccupiedRecallWithSelfReport,
    /// World: share of the truly occupied cells the fused grid decides Occupy
    /// that only a cooperating agent's report of its own footprint marks
    /// occupied, no sensor (0–1).
    SelfReportShare,
    /// World: the Brier score of the fused occupancy probabilities, mean
    /// (p − o)² over the fused cell-steps (self-report left out), with p the
    /// pignistic probability for evidential methods (0 best, 1 worst).
    BrierScore,
    /// Semantic: median anticipation time by the paper's definition (seed 002,
    /// eq. 5), seconds, over objects the ego first learned of from an RSU while
    /// it could not see them and later saw itself.
    AnticipationMedian,
    /// Semantic: 95th percentile of the paper's anticipation time, seconds.
    AnticipationP95,
    /// Semantic: mean number of objects per step the ego knows only through an RSU.
    InfrastructureContribution,
    /// Semantic: share of the objects the RSUs perceive that they send (0–1), over
    /// the cycles `semantic.shares_over` selects.
    TransmittedShare,
    /// Semantic: share of the objects the RSUs perceive that they send with at
    /// least one label: NLoS, relevance, speed violation or conflict (0–1), over
    /// the cycles `semantic.shares_over` selects.
    LabelledShare,
    /// Semantic: bytes per second the RSUs' semantic messages put on the channel.
    ChannelLoad,
    /// Semantic: bytes per second an ETSI collective perception sender would put
    /// on the channel for the same objects.
    BaselineChannelLoad,
    /// Semantic: share of RSU messages to the ego that arrive (0–1).
    PacketDeliveryRatio,
    /// Semantic: objects per run that came within d_min of the ego without a
    /// conflict flagged in a message the ego received beforehand (the mean over
    /// `semantic.runs`).
    MissedCriticals,
    /// Semantic: median of our anticipation time, seconds, over the relevant
    /// objects a V2X message named before the ego saw them: first own sight −
    /// first V2X knowledge (`warned_before_seen`), or closest approach − first
    /// V2X knowledge, at least 0 (`warned_never_seen`).
    ObjectAnticipationMedian,
    /// Semantic: 95th percentile of our anticipation time, seconds.
    ObjectAnticipationP95,
    /// Semantic: relevant objects per run that a V2X message named before the
    /// ego saw them (category `warned_before_seen`; the mean over `semantic.runs`).
    ObjectsWarnedBeforeSeen,
    /// Semantic: relevant objects per run that a V2X message named and the ego
    /// never saw (`warned_never_seen`).
    ObjectsWarnedNeverSeen,
    /// Semantic: relevant objects per run the ego saw no later than a V2X
    /// message named them, or that no message named (`seen_first`).
    ObjectsSeenFirst,
    /// Semantic: relevant objects per run that no V2X message named and the ego
    /// never saw (`never_known`).
    ObjectsNeverKnown,
}

impl Metric {
    /// Every metric, in documentation order.
    pub const ALL: [Metric; 36] = [
        Self::Accuracy,
        Self::BelowThreshold,
        Self::BelowThresholdFraction,
        Self::FalseAlarms,
        Self::MissedDetections,
        Self::ConfidentErrors,
        Self::ConfidentErrorRate,
        Self::DecidedUnknown,
        Self::Unobserved,
        Self::MeanUncertainty,
        Self::MeanConflict,
        Self::MaxConflict,
        Self::TotalConflictCells,
        Self::WeightedCells,
        Self::FovGain,
        Self::OccupiedRecall,
        Self::OccupiedPrecision,
        Self::BlindRecall,
        Self::OccupiedRecallWithSelfReport,
        Self::SelfReportShare,
        Self::BrierScore,
        Self::AnticipationMedian,
        Self::AnticipationP95,
        Self::InfrastructureContribution,
        Self::TransmittedShare,
        Self::LabelledShare,
        Self::ChannelLoad,
        Self::BaselineChannelLoad,
        Self::PacketDeliveryRatio,
        Self::MissedCriticals,
        Self::ObjectAnticipationMedian,
        Self::ObjectAnticipationP95,
        Self::ObjectsWarnedBeforeSeen,
        Self::ObjectsWarnedNeverSeen,
        Self::ObjectsSeenFirst,
        Self::ObjectsNeverKnown,
    ];

    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Accuracy => "accuracy",
            Self::BelowThreshold => "below_threshold",
            Self::BelowThresholdFraction => "below_threshold_fraction",
            Self::FalseAlarms => "false_alarms",
            Self::MissedDetections => "missed_detections",
            Self::ConfidentErrors => "confident_errors",
            Self::ConfidentErrorRate => "confident_error_rate",
            Self::DecidedUnknown => "decided_unknown",
            Self::Unobserved => "unobserved",
            Self::MeanUncertainty => "mean_uncertainty",
            Self::MeanConflict => "mean_conflict",
            Self::MaxConflict => "max_conflict",
            Self::TotalConflictCells => "total_conflict_cells",
            Self::WeightedCells => "weighted_cells",
            Self::FovGain => "fov_gain",
            Self::OccupiedRecall => "occupied_recall",
            Self::OccupiedPrecision => "occupied_precision",
            Self::BlindRecall => "blind_recall",
            Self::OccupiedRecallWithSelfReport => "occupied_recall_with_self_report",
            Self::SelfReportShare => "self_report_share",
            Self::BrierScore => "brier_score",
            Self::AnticipationMedian => "anticipation_median",
            Self::AnticipationP95 => "anticipation_p95",
            Self::InfrastructureContribution => "infrastructure_contribution",
            Self::TransmittedShare => "transmitted_share",
            Self::LabelledShare => "labelled_share",
            Self::ChannelLoad => "channel_load",
            Self::BaselineChannelLoad => "baseline_channel_load",
            Self::PacketDeliveryRatio => "packet_delivery_ratio",
            Self::MissedCriticals => "missed_criticals",
            Self::ObjectAnticipationMedian => "object_anticipation_median",
            Self::ObjectAnticipationP95 => "object_anticipation_p95",
            Self::ObjectsWarnedBeforeSeen => "objects_warned_before_seen",
            Self::ObjectsWarnedNeverSeen => "objects_warned_never_seen",
            Self::ObjectsSeenFirst => "objects_seen_first",
            Self::ObjectsNeverKnown => "objects_never_known",
        }
    }

    /// Whether the field experiment measures it.
    pub fn in_field(self) -> bool {
        !self.in_semantic()
            && !matches!(
                self,
                Self::FovGain
                    | Self::OccupiedRecall
                    | Self::OccupiedPrecision
                    | Self::BlindRecall
                    | Self::OccupiedRecallWithSelfReport
                    | Self::SelfReportShare
                    | Self::BrierScore
            )
    }

    /// Whether worlds that measure collective perception measure it.
    pub fn in_world(self) -> bool {
        !self.in_semantic()
            && !matches!(
                self,
                Self::Accuracy
                    | Self::BelowThreshold
                    | Self::BelowThresholdFraction
                    | Self::FalseAlarms
                    | Self::MissedDetections
                    | Self::ConfidentErrors
                    | Self::ConfidentErrorRate
                    | Self::DecidedUnknown
                    | Self::Unobserved
            )
    }

    /// Whether worlds that measure the semantic pipeline measure it.
    pub fn in_semantic(self) -> bool {
        matches!(
            self,
            Self::AnticipationMedian
                | Self::AnticipationP95
                | Self::InfrastructureContribution
                | Self::TransmittedShare
                | Self::LabelledShare
                | Self::ChannelLoad
                | Self::BaselineChannelLoad
                | Self::PacketDeliveryRatio
                | Self::MissedCriticals
                | Self::ObjectAnticipationMedian
                | Self::ObjectAnticipationP95
                | Self::ObjectsWarnedBeforeSeen
                | Self::ObjectsWarnedNeverSeen
                | Self::ObjectsSeenFirst
                | Self::ObjectsNeverKnown
        )
    }

    /// What the metric's sample size n counts: the population it is computed
    /// over. An empty population leaves a requirement on it not exercised.
    pub fn population(self) -> &'static str {
        match self {
            Self::MeanUncertainty
            | Self::MeanConflict
            | Self::MaxConflict
            | Self::TotalConflictCells
            | Self::WeightedCells => "fused cells",
            Self::FovGain => "cell-steps the ego observes",
            Self::OccupiedRecall => "occupied cell-steps of non-cooperating road users",
            Self::OccupiedPrecision => "cell-steps decided occupied",
            Self::BlindRecall => "occupied cell-steps of non-cooperating road users the ego does not observe",
            Self::OccupiedRecallWithSelfReport => "truly occupied cell-steps",
            Self::SelfReportShare => "truly occupied cell-steps decided occupied",
            Self::BrierScore => "fused cell-steps, self-report left out",
            Self::AnticipationMedian | Self::AnticipationP95 => "anticipation times",
            Self::ObjectAnticipationMedian | Self::ObjectAnticipationP95 => {
                "relevant objects named by V2X before the ego saw them"
            }
            Self::ObjectsWarnedBeforeSeen
            | Self::ObjectsWarnedNeverSeen
            | Self::ObjectsSeenFirst
            | Self::ObjectsNeverKnown => "relevant objects",
            Self::InfrastructureContribution | Self::ChannelLoad | Self::BaselineChannelLoad => "steps with the ego",
            Self::TransmittedShare | Self::LabelledShare => "object-cycles the RSUs perceive",
            Self::PacketDeliveryRatio => "messages to the ego",
            Self::MissedCriticals => "close approaches",
            _ => "cells",
        }
    }

    /// The fewest samples a requirement on the metric needs by default; below
    /// it the requirement is not exercised. One for every metric but the
    /// quantiles, which need the smallest sample whose order statistics give a
    /// distribution-free two-sided 95 % confidence interval of the quantile
    /// (the sample's minimum and maximum cover the q quantile with probability
    /// 1 − qⁿ − (1 − q)ⁿ ≥ 0.95): 6 for the median, 59 for the 95th percentile.
    pub fn default_min_samples(self) -> u64 {
        match self {
            Self::AnticipationMedian | Self::ObjectAnticipationMedian => 6,
            Self::AnticipationP95 | Self::ObjectAnticipationP95 => 59,
            _ => 1,
        }
    }

    /// Whether the metric exists only for evidential (Dempster–Shafer) methods.
    pub fn is_evidential_only(self) -> bool {
        matches!(
            self,
            Self::MeanConflict | Self::MaxConflict | Self::TotalConflictCells | Self::WeightedCells
        )
    }

    /// The values it can take, as its documentation states them. A measured
    /// value outside is a defect (or damage), never something to judge.
    pub fn domain(self) -> ValueDomain {
        match self {
            Self::Accuracy
            | Self::BelowThresholdFraction
            | Self::ConfidentErrorRate
            | Self::MeanUncertainty
            | Self::MeanConflict
            | Self::MaxConflict
            | Self::OccupiedRecall
            | Self::OccupiedPrecision
            | Self::BlindRecall
            | Self::OccupiedRecallWithSelfReport
            | Self::SelfReportShare
            | Self::BrierScore
            | Self::TransmittedShare
            | Self::LabelledShare
            | Self::PacketDeliveryRatio => ValueDomain::Fraction,
            Self::BelowThreshold
            | Self::FalseAlarms
            | Self::MissedDetections
            | Self::ConfidentErrors
            | Self::DecidedUnknown
            | Self::Unobserved
            | Self::TotalConflictCells
            | Self::WeightedCells => ValueDomain::Count,
            // fov_gain: the joint field of view contains the ego's, so the gain
            // is never negative. Means over steps or runs (contribution, missed
            // criticals, objects per category) are not whole numbers.
            Self::FovGain
            | Self::AnticipationMedian
            | Self::AnticipationP95
            | Self::InfrastructureContribution
            | Self::ChannelLoad
            | Self::BaselineChannelLoad
            | Self::MissedCriticals
            | Self::ObjectAnticipationMedian
            | Self::ObjectAnticipationP95
            | Self::ObjectsWarnedBeforeSeen
            | Self::ObjectsWarnedNeverSeen
            | Self::ObjectsSeenFirst
            | Self::ObjectsNeverKnown => ValueDomain::NonNegative,
        }
    }
}

/// The values a measured quantity can take; every one of them is finite. (A
/// quantity that is not defined for a run is absent, not a value.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ValueDomain {
    /// A share, a rate or a probability: [0, 1].
    Fraction,
    /// A number of things: a whole number ≥ 0.
    Count,
    /// Seconds, bytes per second, a mean count or a gain: ≥ 0.
    NonNegative,
}

impl ValueDomain {
    /// Whether `value` lies in the domain (a NaN or an infinity never does).
    pub fn contains(self, value: f64) -> bool {
        value.is_finite()
            && value >= 0.0
            && match self {
                Self::Fraction => value <= 1.0,
                Self::Count => value.fract() == 0.0,
                Self::NonNegative => true,
            }
    }
}

impl std::fmt::Display for ValueDomain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Fraction => "[0, 1]",
            Self::Count => "whole numbers ≥ 0",
            Self::NonNegative => "finite numbers ≥ 0",
        })
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

    #[test]
    fn domains_hold_their_ends_and_refuse_what_lies_beyond() {
        use ValueDomain::*;
        for (domain, inside, outside) in [
            (Fraction, [0.0, 0.5, 1.0], [-1e-12, 1.0 + 1e-12, 1.11]),
            (Count, [0.0, 3.0, 1e15], [-1.0, 2.5, 1e-300]),
            (NonNegative, [0.0, 0.25, 1e300], [-0.25, -1e-300, -1.0]),
        ] {
            for value in inside {
                assert!(domain.contains(value), "{value} in {domain}");
            }
            for value in outside.into_iter().chain([f64::NAN, f64::INFINITY, f64::NEG_INFINITY]) {
                assert!(!domain.contains(value), "{value} not in {domain}");
            }
        }
    }

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
