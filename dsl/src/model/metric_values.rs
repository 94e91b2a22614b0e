//! The values a metric takes: its domain and its unit.

use super::Metric;
use super::unit::{Unit, ValueDomain};

impl Metric {
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
            | Self::EgoOccupiedRecall
            | Self::SelfReportShare
            | Self::BrierScore
            | Self::MeanVisibleFraction
            | Self::TransmittedShare
            | Self::LabelledShare
            | Self::PacketDeliveryRatio
            | Self::GridPacketDeliveryRatio
            | Self::SemanticPacketDeliveryRatio
            | Self::SutRecall
            | Self::SutPrecision
            | Self::SutClassAccuracy => ValueDomain::Fraction,
            Self::BelowThreshold
            | Self::FalseAlarms
            | Self::MissedDetections
            | Self::ConfidentErrors
            | Self::DecidedUnknown
            | Self::Unobserved
            | Self::TotalConflictCells
            | Self::WeightedCells
            | Self::SutGhosts => ValueDomain::Count,
            // fov_gain: the joint field of view contains the ego's, so the gain
            // is never negative. Means over steps or runs (contribution, missed
            // criticals, objects per category) are not whole numbers.
            Self::FovGain
            | Self::MessageAgeMean
            | Self::MessageAgeP95
            | Self::BytesPerSecondPerAgent
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
            | Self::ObjectsNeverKnown
            | Self::BaselineAnticipationMedian
            | Self::BaselineAnticipationP95
            | Self::BaselineObjectAnticipationMedian
            | Self::BaselineObjectAnticipationP95
            | Self::MinTtc
            | Self::MinPet
            | Self::MaxDrac
            | Self::SutPositionError
            | Self::SutLatency => ValueDomain::NonNegative,
        }
    }

    /// The unit its values are in (the report writes it beside every value).
    pub fn unit(self) -> Unit {
        match self {
            Self::BelowThreshold
            | Self::FalseAlarms
            | Self::MissedDetections
            | Self::ConfidentErrors
            | Self::DecidedUnknown
            | Self::Unobserved
            | Self::TotalConflictCells
            | Self::WeightedCells => Unit::Cells,
            Self::MessageAgeMean
            | Self::MessageAgeP95
            | Self::AnticipationMedian
            | Self::AnticipationP95
            | Self::ObjectAnticipationMedian
            | Self::ObjectAnticipationP95
            | Self::BaselineAnticipationMedian
            | Self::BaselineAnticipationP95
            | Self::BaselineObjectAnticipationMedian
            | Self::BaselineObjectAnticipationP95
            | Self::MinTtc
            | Self::MinPet
            | Self::SutLatency => Unit::Seconds,
            Self::SutPositionError => Unit::Metres,
            Self::SutGhosts => Unit::Objects,
            Self::MaxDrac => Unit::MetresPerSecondSquared,
            Self::BytesPerSecondPerAgent | Self::ChannelLoad | Self::BaselineChannelLoad => Unit::BytesPerSecond,
            Self::InfrastructureContribution => Unit::Objects,
            Self::MissedCriticals
            | Self::ObjectsWarnedBeforeSeen
            | Self::ObjectsWarnedNeverSeen
            | Self::ObjectsSeenFirst
            | Self::ObjectsNeverKnown => Unit::ObjectsPerRun,
            // Shares, rates, probabilities, a relative gain, a mean mass or
            // entropy bounded by 1, a Brier score.
            _ => Unit::One,
        }
    }
}
