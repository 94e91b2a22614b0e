//! How more samples can move each metric's value: what lets an oracle judge
//! a violation seen over too few samples.

use super::Metric;

/// How more samples can move a metric's value ([`Metric::with_more_samples`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trend {
    /// Only up: a count, a greatest value.
    OnlyUp,
    /// Only down: a least value.
    OnlyDown,
    /// Either way: a share, a mean, a quantile, a ratio.
    Either,
}

impl Metric {
    /// How more samples can move the metric's value: only up (a count, a
    /// greatest value), only down (a least value) or either way (a share, a
    /// mean, a quantile, a ratio, a count per run: a mean over runs). Every
    /// metric is named here, so a new one must say.
    pub fn with_more_samples(self) -> Trend {
        match self {
            Self::BelowThreshold
            | Self::FalseAlarms
            | Self::MissedDetections
            | Self::ConfidentErrors
            | Self::DecidedUnknown
            | Self::Unobserved
            | Self::MaxConflict
            | Self::TotalConflictCells
            | Self::WeightedCells
            | Self::MaxDrac
            | Self::SutGhosts => Trend::OnlyUp,
            Self::MinTtc | Self::MinPet => Trend::OnlyDown,
            Self::Accuracy
            | Self::BelowThresholdFraction
            | Self::ConfidentErrorRate
            | Self::MeanUncertainty
            | Self::MeanConflict
            | Self::FovGain
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
            | Self::AnticipationMedian
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
            | Self::GridPacketDeliveryRatio
            | Self::SemanticPacketDeliveryRatio
            | Self::SutRecall
            | Self::SutPrecision
            | Self::SutPositionError
            | Self::SutClassAccuracy
            | Self::SutLatency => Trend::Either,
        }
    }
}
