//! The metrics a requirement checks: their names, which kinds of scenario
//! measure them, what their sample size n counts, and the values they take
//! ([`ValueDomain`](super::ValueDomain), shared with signals and object
//! properties) and their units ([`Unit`](super::Unit)), in `metric_values`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::ObjectProperty;

/// Metrics. Counts are numbers of cells. Some exist only in the field experiment,
/// some only in worlds (see [`Metric::in_field`], [`Metric::in_world`],
/// [`Metric::in_semantic`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Share of all cells whose decided state equals the ground truth (0–1;
    /// an unobserved cell is not decided, so not correct).
    Accuracy,
    /// Observed cells with no decision (p_max − p_others < θ): seed 001's
    /// Table III.
    BelowThreshold,
    /// `below_threshold` as a share of the observed cells (0–1).
    BelowThresholdFraction,
    /// Observed cells decided Occupy that are truly empty.
    FalseAlarms,
    /// Observed cells decided Empty that are truly occupied.
    MissedDetections,
    /// `false_alarms` + `missed_detections`: confident wrong decisions.
    ConfidentErrors,
    /// `confident_errors` as a share of the observed cells (0–1).
    ConfidentErrorRate,
    /// Observed cells decided Unknown (the Unknown mass dominates).
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
    /// World: Σ cells a sensor of any cooperating agent observed / Σ cells a
    /// sensor of the ego observed, minus 1, over the run (seed 000 reports
    /// +260 %, that is 2.6). A self-reported footprint is not observed.
    FovGain,
    /// World: share of the truly occupied cells the fused grid decides Occupy
    /// where a sensor found them occupied, over the run, the cooperating
    /// agents' own footprints (self-report) left out (0–1). A cell that only a
    /// reported footprint marks occupied (held over the radio, where its agent
    /// was) is no detection of whoever is there now.
    OccupiedRecall,
    /// World: share of the cells the fused grid decides Occupy that are truly
    /// occupied, over the run (0–1).
    OccupiedPrecision,
    /// World: `occupied_recall` over the cells the ego does not observe itself (0–1).
    BlindRecall,
    /// World: `occupied_recall` with the cooperating agents' own footprints
    /// counted as well, each credited when decided Occupy, reported or sensed,
    /// as a grid that holds every road user is scored (0–1).
    OccupiedRecallWithSelfReport,
    /// World: `occupied_recall` of the ego's own observation alone, over the
    /// same cells (fused and decided by the same rule): the ego-only baseline
    /// at the same population, so that cooperation's gain is
    /// `occupied_recall` − `ego_occupied_recall` at one point (0–1).
    EgoOccupiedRecall,
    /// World: of the truly occupied cells the fused grid decides Occupy and
    /// counts detected (a sensor found them occupied, or they are a
    /// cooperating agent's body, which it reports), the share only that
    /// self-report marks occupied, no sensor (0–1). Cells decided Occupy on a
    /// held footprint alone (`footprint_only`) are in neither.
    SelfReportShare,
    /// World: the Brier score of the fused occupancy probabilities, mean
    /// (p − o)² over the fused cell-steps (self-report left out), with p the
    /// pignistic probability for evidential methods (0 best, 1 worst).
    BrierScore,
    /// World: the mean share of an object's outline (its angular extent) in
    /// line of sight of a cooperating agent's sensor, over the sensor–target
    /// pairs in range and field of view, a hidden object counting 0 (0–1).
    MeanVisibleFraction,
    /// World over the radio: mean age of the messages the ego fuses, seconds from
    /// sensing to the first step the ego fuses the message.
    MessageAgeMean,
    /// World over the radio: 95th percentile of the message age, seconds.
    MessageAgeP95,
    /// World over the radio: bytes per second each cooperating agent other than
    /// the ego sends, over the steps it is in the scene with the ego.
    BytesPerSecondPerAgent,
    /// Semantic: median anticipation time by the paper's definition (seed 002,
    /// eq. 5), seconds, over objects the ego first learned of from an RSU while
    /// it could not see them and later saw itself.
    AnticipationMedian,
    /// Semantic: 95th percentile of the paper's anticipation time, seconds.
    AnticipationP95,
    /// Semantic: mean number of objects per step the ego knows only through an
    /// RSU, over the steps `semantic.contribution_over` selects.
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
    /// Semantic: share of RSU messages to the ego that arrive (0–1). World over
    /// the radio: share of the cooperating agents' messages to the ego that
    /// arrive (0–1).
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
    /// Semantic: `anticipation_median` had the RSUs sent the ETSI baseline's
    /// collective perception messages instead of the semantic ones: the same
    /// traffic and ego trajectory, the same links with their own loss draws.
    BaselineAnticipationMedian,
    /// Semantic: `anticipation_p95` over the ETSI baseline's messages.
    BaselineAnticipationP95,
    /// Semantic: `object_anticipation_median` over the ETSI baseline's
    /// messages, for the same relevant objects.
    BaselineObjectAnticipationMedian,
    /// Semantic: `object_anticipation_p95` over the ETSI baseline's messages.
    BaselineObjectAnticipationP95,
    /// Semantic: the least time to collision of any relevant road user with
    /// the ego (the least of the records' `min_ttc`), seconds, over the road
    /// users on a collision course with it.
    MinTtc,
    /// Semantic: the least post-encroachment time of any relevant road user
    /// with the ego (the least of the records' `pet`), seconds, over the road
    /// users whose footprints covered a spot the ego's covered.
    MinPet,
    /// Semantic: the greatest deceleration rate to avoid a crash the ego
    /// needed for any relevant road user (the greatest of the records'
    /// `max_drac`), m/s², over the road users its braking could have avoided.
    MaxDrac,
    /// Joint world: `packet_delivery_ratio` of collective perception, the
    /// share of the cooperating agents' messages to the ego that arrive (0–1),
    /// where a world has both radios and `packet_delivery_ratio` would not say
    /// which.
    GridPacketDeliveryRatio,
    /// Joint world: `packet_delivery_ratio` of the semantic pipeline, the
    /// share of the RSUs' messages to the ego that arrive (0–1).
    SemanticPacketDeliveryRatio,
    /// System under test: share of the object-steps a served sensor has at
    /// least partly in sight (visible fraction above 0) that a detection of
    /// the system matches (0–1; docs/osi-sut.md gives the matching rule).
    SutRecall,
    /// System under test: share of its judged detections that match a road
    /// user (0–1).
    SutPrecision,
    /// System under test: mean distance, metres, from a matched detection to
    /// the centre of the road user it matches.
    SutPositionError,
    /// System under test: share of its matched detections whose reported
    /// class (its most probable candidate's) is the kind of the road user
    /// they match (0–1).
    SutClassAccuracy,
    /// System under test: mean latency, seconds, over the road users it
    /// detected after a served sensor first had them in sight: first matched
    /// − first in sight, at least 0.
    SutLatency,
    /// System under test: judged detections that match no road user within
    /// the gate (ghost objects), summed over the steps.
    SutGhosts,
}

impl Metric {
    /// Every metric, in documentation order.
    pub const ALL: [Metric; 56] = [
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
        Self::EgoOccupiedRecall,
        Self::SelfReportShare,
        Self::BrierScore,
        Self::MeanVisibleFraction,
        Self::MessageAgeMean,
        Self::MessageAgeP95,
        Self::BytesPerSecondPerAgent,
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
        Self::BaselineAnticipationMedian,
        Self::BaselineAnticipationP95,
        Self::BaselineObjectAnticipationMedian,
        Self::BaselineObjectAnticipationP95,
        Self::MinTtc,
        Self::MinPet,
        Self::MaxDrac,
        Self::GridPacketDeliveryRatio,
        Self::SemanticPacketDeliveryRatio,
        Self::SutRecall,
        Self::SutPrecision,
        Self::SutPositionError,
        Self::SutClassAccuracy,
        Self::SutLatency,
        Self::SutGhosts,
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
            Self::EgoOccupiedRecall => "ego_occupied_recall",
            Self::SelfReportShare => "self_report_share",
            Self::BrierScore => "brier_score",
            Self::MeanVisibleFraction => "mean_visible_fraction",
            Self::MessageAgeMean => "message_age_mean",
            Self::MessageAgeP95 => "message_age_p95",
            Self::BytesPerSecondPerAgent => "bytes_per_second_per_agent",
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
            Self::BaselineAnticipationMedian => "baseline_anticipation_median",
            Self::BaselineAnticipationP95 => "baseline_anticipation_p95",
            Self::BaselineObjectAnticipationMedian => "baseline_object_anticipation_median",
            Self::BaselineObjectAnticipationP95 => "baseline_object_anticipation_p95",
            Self::MinTtc => "min_ttc",
            Self::MinPet => "min_pet",
            Self::MaxDrac => "max_drac",
            Self::GridPacketDeliveryRatio => "grid_packet_delivery_ratio",
            Self::SemanticPacketDeliveryRatio => "semantic_packet_delivery_ratio",
            Self::SutRecall => "sut_recall",
            Self::SutPrecision => "sut_precision",
            Self::SutPositionError => "sut_position_error",
            Self::SutClassAccuracy => "sut_class_accuracy",
            Self::SutLatency => "sut_latency",
            Self::SutGhosts => "sut_ghosts",
        }
    }

    /// The same quantity measured over the ETSI baseline's messages on the
    /// same traffic (`relative_to: baseline`), where there is one.
    pub fn baseline(self) -> Option<Metric> {
        Some(match self {
            Self::ChannelLoad => Self::BaselineChannelLoad,
            Self::AnticipationMedian => Self::BaselineAnticipationMedian,
            Self::AnticipationP95 => Self::BaselineAnticipationP95,
            Self::ObjectAnticipationMedian => Self::BaselineObjectAnticipationMedian,
            Self::ObjectAnticipationP95 => Self::BaselineObjectAnticipationP95,
            _ => return None,
        })
    }

    /// Whether the field experiment measures it.
    pub fn in_field(self) -> bool {
        !self.in_semantic()
            && !self.joint_only()
            && !matches!(
                self,
                Self::FovGain
                    | Self::OccupiedRecall
                    | Self::OccupiedPrecision
                    | Self::BlindRecall
                    | Self::OccupiedRecallWithSelfReport
                    | Self::EgoOccupiedRecall
                    | Self::SelfReportShare
                    | Self::BrierScore
                    | Self::MeanVisibleFraction
                    | Self::MessageAgeMean
                    | Self::MessageAgeP95
                    | Self::BytesPerSecondPerAgent
            )
            && !self.of_system()
    }

    /// Whether worlds that measure collective perception measure it (some only
    /// over the radio: [`Metric::needs_radio`]).
    pub fn in_world(self) -> bool {
        (!self.in_semantic() || self == Self::PacketDeliveryRatio)
            && !self.joint_only()
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
                | Self::BaselineAnticipationMedian
                | Self::BaselineAnticipationP95
                | Self::BaselineObjectAnticipationMedian
                | Self::BaselineObjectAnticipationP95
                | Self::MinTtc
                | Self::MinPet
                | Self::MaxDrac
        )
    }

    /// Whether worlds that run collective perception and the semantic
    /// pipeline together (joint worlds) measure it: every metric of either,
    /// but `packet_delivery_ratio`, which each defines over its own radio and
    /// a joint world splits in two (`grid_packet_delivery_ratio`,
    /// `semantic_packet_delivery_ratio`).
    pub fn in_joint(self) -> bool {
        match self {
            Self::PacketDeliveryRatio => false,
            _ => self.joint_only() || self.in_world() || self.in_semantic(),
        }
    }

    /// Whether it judges a system under test (`system_under_test`): measured
    /// in a perception world that declares one, and only there. A check on it
    /// takes an `objects` selection, summed over what the selection keeps.
    pub fn of_system(self) -> bool {
        matches!(
            self,
            Self::SutRecall
                | Self::SutPrecision
                | Self::SutPositionError
                | Self::SutClassAccuracy
                | Self::SutLatency
                | Self::SutGhosts
        )
    }

    /// Whether only joint worlds measure it: the two halves of
    /// `packet_delivery_ratio`.
    pub fn joint_only(self) -> bool {
        matches!(self, Self::GridPacketDeliveryRatio | Self::SemanticPacketDeliveryRatio)
    }

    /// In a joint world, which of its two models measures it, and as which
    /// of that model's own metrics (each half of `packet_delivery_ratio` is
    /// its model's `packet_delivery_ratio`). Meaningful where
    /// [`Metric::in_joint`] holds.
    pub fn joint_part(self) -> (JointPart, Metric) {
        match self {
            Self::GridPacketDeliveryRatio => (JointPart::Grid, Self::PacketDeliveryRatio),
            Self::SemanticPacketDeliveryRatio => (JointPart::Semantic, Self::PacketDeliveryRatio),
            metric if metric.in_semantic() => (JointPart::Semantic, metric),
            metric => (JointPart::Grid, metric),
        }
    }

    /// Whether a collective-perception world measures it only over the radio
    /// (when it declares `v2x`).
    pub fn needs_radio(self) -> bool {
        matches!(
            self,
            Self::PacketDeliveryRatio
                | Self::GridPacketDeliveryRatio
                | Self::MessageAgeMean
                | Self::MessageAgeP95
                | Self::BytesPerSecondPerAgent
        )
    }

    /// What the metric's sample size n counts: the population it is computed
    /// over. An empty population leaves a requirement on it not exercised.
    pub fn population(self) -> &'static str {
        match self {
            m if m.over_fused_cells() => "fused cells",
            Self::FovGain => "cell-steps the ego observes",
            Self::OccupiedRecall | Self::EgoOccupiedRecall => "occupied cell-steps of non-cooperating road users",
            Self::OccupiedPrecision => "cell-steps decided occupied",
            Self::BlindRecall => "occupied cell-steps of non-cooperating road users the ego does not observe",
            Self::OccupiedRecallWithSelfReport => "truly occupied cell-steps",
            Self::SelfReportShare => "truly occupied cell-steps decided occupied",
            Self::BrierScore => "fused cell-steps, self-report left out",
            Self::MeanVisibleFraction => "sensor–target pairs in range and field of view, per step",
            Self::MessageAgeMean | Self::MessageAgeP95 => "messages the ego fuses",
            Self::BytesPerSecondPerAgent => "steps of cooperating agents with the ego",
            Self::AnticipationMedian | Self::AnticipationP95 => "anticipation times",
            Self::BaselineAnticipationMedian | Self::BaselineAnticipationP95 => {
                "anticipation times over the ETSI baseline's messages"
            }
            Self::BaselineObjectAnticipationMedian | Self::BaselineObjectAnticipationP95 => {
                "relevant objects named by the ETSI baseline before the ego saw them"
            }
            Self::InfrastructureContribution => "steps with the ego that `contribution_over` counts",
            Self::ChannelLoad | Self::BaselineChannelLoad => "steps with the ego",
            Self::TransmittedShare | Self::LabelledShare => "object-cycles the RSUs perceive",
            Self::PacketDeliveryRatio => "messages to the ego",
            Self::GridPacketDeliveryRatio => "cooperating agents' messages to the ego",
            Self::SemanticPacketDeliveryRatio => "RSU messages to the ego",
            Self::MissedCriticals => "close approaches",
            Self::ObjectAnticipationMedian | Self::ObjectAnticipationP95 => {
                "relevant objects named by V2X before the ego saw them"
            }
            Self::ObjectsWarnedBeforeSeen
            | Self::ObjectsWarnedNeverSeen
            | Self::ObjectsSeenFirst
            | Self::ObjectsNeverKnown => "relevant objects",
            Self::MinTtc => ObjectProperty::MinTtc.population(),
            Self::MinPet => ObjectProperty::Pet.population(),
            Self::MaxDrac => ObjectProperty::MaxDrac.population(),
            Self::SutRecall => "object-steps in sight of a served sensor",
            Self::SutPrecision | Self::SutGhosts => "judged detections",
            Self::SutPositionError | Self::SutClassAccuracy => "matched detections",
            Self::SutLatency => "road users detected after first in sight",
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
            Self::AnticipationMedian
            | Self::ObjectAnticipationMedian
            | Self::BaselineAnticipationMedian
            | Self::BaselineObjectAnticipationMedian => 6,
            Self::AnticipationP95
            | Self::MessageAgeP95
            | Self::ObjectAnticipationP95
            | Self::BaselineAnticipationP95
            | Self::BaselineObjectAnticipationP95 => 59,
            _ => 1,
        }
    }

    /// Whether a field measures it over the fused (observed) cells only: a
    /// decision's errors, which an unobserved cell, never decided, cannot
    /// make, and the fused masses' statistics.
    pub fn over_fused_cells(self) -> bool {
        matches!(
            self,
            Self::BelowThreshold
                | Self::BelowThresholdFraction
                | Self::FalseAlarms
                | Self::MissedDetections
                | Self::ConfidentErrors
                | Self::ConfidentErrorRate
                | Self::DecidedUnknown
                | Self::MeanUncertainty
                | Self::MeanConflict
                | Self::MaxConflict
                | Self::TotalConflictCells
                | Self::WeightedCells
        )
    }

    /// Whether the metric exists only for evidential (Dempster–Shafer) methods.
    pub fn is_evidential_only(self) -> bool {
        matches!(
            self,
            Self::MeanConflict | Self::MaxConflict | Self::TotalConflictCells | Self::WeightedCells
        )
    }
}

/// The two models a joint world runs, each measuring its own metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum JointPart {
    /// Collective perception: the ego's fused grid.
    Grid,
    /// The roadside units' semantic pipeline.
    Semantic,
}
