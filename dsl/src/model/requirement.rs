//! Requirements, what they check (metrics in [`super::metric`]), and published
//! figures to compare with.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{AgentKind, Metric, Unit, ValueDomain};
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
    /// The road users a per-object check judges (every one for other checks).
    pub objects: ObjectSelection,
}

/// Which relevant road users a per-object check judges, or which object-steps
/// and detections a system's metric (`sut_*`) is summed over: those matching
/// every criterion given (an empty list or no window matches all).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ObjectSelection {
    /// Agent ids.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ids: Vec<String>,
    /// Classes (of a system's detection: the class it reports).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub classes: Vec<AgentKind>,
    /// Ids of crosswalks, interaction areas or declared `areas`: the road
    /// user's centre was inside one of them at some step with the ego in the
    /// scene (for a system's object-step: at that step; for its detection:
    /// the detection's position at its step).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<String>,
    /// [from, to], seconds: its closest approach to the ego lies in it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub between: Option<[f64; 2]>,
    /// Metres: its closest approach to the ego (between centres) came nearer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub closer_than: Option<f64>,
}

impl ObjectSelection {
    /// The selection of every road user (the default, as a constant).
    pub const ALL: Self = Self {
        ids: Vec::new(),
        classes: Vec::new(),
        areas: Vec::new(),
        between: None,
        closer_than: None,
    };

    /// Whether it selects every road user.
    pub fn is_all(&self) -> bool {
        *self == Self::ALL
    }

    /// What it selects, in words (`pedestrians in cw_north`), for messages.
    pub fn describe(&self) -> String {
        let mut words = Vec::new();
        if !self.classes.is_empty() {
            let classes: Vec<&str> = self.classes.iter().map(|c| c.name()).collect();
            words.push(format!("of class {}", classes.join(" or ")));
        }
        if !self.ids.is_empty() {
            words.push(format!("with id {}", self.ids.join(" or ")));
        }
        if !self.areas.is_empty() {
            words.push(format!("in {}", self.areas.join(" or ")));
        }
        if let Some(distance) = self.closer_than {
            words.push(format!("closer than {distance} m to the ego"));
        }
        if let Some([from, to]) = self.between {
            words.push(format!("closest to the ego between {from} s and {to} s"));
        }
        words.join(", ")
    }
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
    /// A metric compared with another measured on the same run (the same
    /// traffic): their ratio or difference against the threshold.
    Compare {
        /// The metric.
        metric: Metric,
        /// What it is compared with: another metric, or its twin over the ETSI
        /// baseline's messages ([`Metric::baseline`]).
        other: Metric,
        /// Ratio or difference.
        by: Comparison,
        /// The threshold of metric / other, or of metric − other.
        bound: Bound,
    },
    /// A property of every road user the requirement's `objects` select.
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

impl Check {
    /// The unit of the value it compares with its threshold: the metric's,
    /// signal's or property's; 1 for a ratio of two metrics, a share of seeds
    /// and an invariant's tolerance.
    pub fn unit(&self) -> Unit {
        match *self {
            Self::Metric {
                over_seeds:
                    Some(OverSeeds {
                        statistic: Statistic::Share { .. },
                        ..
                    }),
                ..
            }
            | Self::Compare {
                by: Comparison::Ratio, ..
            }
            | Self::Invariant { .. } => Unit::One,
            Self::Metric { metric, .. } | Self::Compare { metric, .. } => metric.unit(),
            Self::Temporal { signal, .. } => signal.unit(),
            Self::PerObject { property, .. } => property.unit(),
        }
    }
}

/// How a comparison combines a metric with the other.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// metric / other (undefined when other is 0).
    #[default]
    Ratio,
    /// metric − other.
    Difference,
}

impl Comparison {
    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ratio => "ratio",
            Self::Difference => "difference",
        }
    }

    /// The compared value of `value` against `other` (`None`: a ratio to 0).
    pub fn of(self, value: f64, other: f64) -> Option<f64> {
        match self {
            Self::Ratio => (other != 0.0).then(|| value / other),
            Self::Difference => Some(value - other),
        }
    }
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

    /// The unit of its values.
    pub fn unit(self) -> Unit {
        match self {
            Self::OccupiedRecall | Self::BlindRecall | Self::OccupiedPrecision => Unit::One,
            Self::RsuOnlyObjects => Unit::Objects,
            Self::TimeToConflict => Unit::Seconds,
        }
    }
}

/// Properties of road users a per-object check bounds: of the close approaches
/// (`warning_time`), of the per-object record of every relevant road user, or
/// of a system under test's record of every road user in the scene with the
/// ego (`sut_*`; [`ObjectProperty::of_record`], [`ObjectProperty::of_system`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ObjectProperty {
    /// Each object that came within d_min of the ego: seconds from the first
    /// RSU message flagging a conflict with it to the step it came within d_min
    /// (the close approach's start, not its closest point, which its record's
    /// `closest.time` gives; an unflagged object has none, and fails).
    WarningTime,
    /// Each relevant road user: seconds from the first RSU message flagging a
    /// conflict with it to its closest approach to the ego, negative when the
    /// warning came after (one never flagged has none, and fails).
    WarningLead,
    /// Each relevant road user: seconds from when the ego first knew of it, by
    /// its own sight or a V2X message, to its closest approach, negative when
    /// it learned of it after (one never known has none, and fails).
    KnowledgeLead,
    /// Each relevant road user: seconds V2X told the ego of it before the ego
    /// could see it (our per-object anticipation: first own sight, or for one
    /// never seen its closest approach, minus first V2X knowledge); 0 for one
    /// the ego saw first; one never known has none, and fails.
    Anticipation,
    /// Each relevant road user: its closest approach to the ego, metres
    /// between centres.
    ClosestDistance,
    /// Each relevant road user on a collision course with the ego: its least
    /// time to collision, seconds (oriented boxes at constant velocity, over
    /// the steps within `semantic.proximity`; 0: they touched). One never on
    /// such a course has none and is not judged.
    MinTtc,
    /// Each relevant road user whose footprint covered a spot the ego's
    /// covered: its post-encroachment time, seconds (0: they touched). One
    /// without such a spot has none and is not judged.
    Pet,
    /// Each relevant road user on a collision course that the ego's braking
    /// could avoid: the greatest deceleration rate to avoid the crash the ego
    /// needed, m/s². One braking never could avoid (head on, from behind, or
    /// heading for an ego that stands) has none and is not judged.
    MaxDrac,
    /// Joint world, each relevant road user: seconds from when a cell of its
    /// footprint was first decided occupied in the ego's fused grid to its
    /// closest approach, negative when that came after (one never in the grid
    /// has none, and fails).
    GridLead,
    /// Joint world, each relevant road user: seconds from the earlier of its
    /// first time in the ego's fused grid and its first warning (an RSU
    /// message flagging a conflict with it) to its closest approach (one with
    /// neither has none, and fails).
    GridOrWarningLead,
    /// System under test, each road user: seconds from when a judged
    /// detection of the system first matched it to its closest approach to
    /// the ego, negative when that came after (the system's warning; one
    /// never detected has none, and fails).
    SutLead,
    /// System under test, each road user: seconds the system detected it
    /// before the ego's own sensors had it in sight (first in the ego's
    /// sight, or for one never in it its closest approach, minus first
    /// detected, at least 0); 0 for one the ego saw no later; one never
    /// detected has none, and fails.
    SutAnticipation,
    /// System under test, each road user that came into a served sensor's
    /// sight: seconds from then to the system's first detection of it, at
    /// least 0 (one never in sight is not judged; one in sight and never
    /// detected has none, and fails).
    SutDelay,
}

impl ObjectProperty {
    /// Every property in documentation order.
    pub const ALL: [ObjectProperty; 13] = [
        Self::WarningTime,
        Self::WarningLead,
        Self::KnowledgeLead,
        Self::Anticipation,
        Self::ClosestDistance,
        Self::MinTtc,
        Self::Pet,
        Self::MaxDrac,
        Self::GridLead,
        Self::GridOrWarningLead,
        Self::SutLead,
        Self::SutAnticipation,
        Self::SutDelay,
    ];

    /// The name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Self::WarningTime => "warning_time",
            Self::WarningLead => "warning_lead",
            Self::KnowledgeLead => "knowledge_lead",
            Self::Anticipation => "anticipation",
            Self::ClosestDistance => "closest_distance",
            Self::MinTtc => "min_ttc",
            Self::Pet => "pet",
            Self::MaxDrac => "max_drac",
            Self::GridLead => "grid_lead",
            Self::GridOrWarningLead => "grid_or_warning_lead",
            Self::SutLead => "sut_lead",
            Self::SutAnticipation => "sut_anticipation",
            Self::SutDelay => "sut_delay",
        }
    }

    /// Whether it reads the ego's fused grid, which only a joint world (one
    /// with `perception` and `semantic`) has.
    pub fn needs_grid(self) -> bool {
        matches!(self, Self::GridLead | Self::GridOrWarningLead)
    }

    /// Whether it judges a system under test (`system_under_test`): read
    /// from the system's per-object record, in a perception world that
    /// declares one, and only there.
    pub fn of_system(self) -> bool {
        matches!(self, Self::SutLead | Self::SutAnticipation | Self::SutDelay)
    }

    /// Whether it is read from the per-object record of every relevant road
    /// user (so that `objects` can select among them), rather than from the
    /// close approaches.
    pub fn of_record(self) -> bool {
        self != Self::WarningTime
    }

    /// Whether a check judges only the road users that have it: a
    /// criticality measure exists only for a road user in conflict with the
    /// ego, and one without a conflict is left out of the population rather
    /// than failed (an empty population is not exercised, never a pass).
    /// For the others, a road user without the property fails.
    pub fn defined_only(self) -> bool {
        matches!(self, Self::MinTtc | Self::Pet | Self::MaxDrac)
    }

    /// The road users it is measured over, in words.
    pub fn population(self) -> &'static str {
        match self {
            Self::WarningTime => "objects that came within d_min of the ego",
            Self::MinTtc => "relevant road users on a collision course with the ego",
            Self::Pet => "relevant road users that covered a spot the ego covered",
            Self::MaxDrac => "relevant road users on a collision course the ego's braking could avoid",
            Self::WarningLead
            | Self::KnowledgeLead
            | Self::Anticipation
            | Self::ClosestDistance
            | Self::GridLead
            | Self::GridOrWarningLead => "relevant road users",
            Self::SutLead | Self::SutAnticipation => "road users in the scene with the ego",
            Self::SutDelay => "road users in a served sensor's sight",
        }
    }

    /// The values an object's property can take (an object may also have none).
    pub fn domain(self) -> ValueDomain {
        match self {
            Self::WarningTime
            | Self::Anticipation
            | Self::ClosestDistance
            | Self::MinTtc
            | Self::Pet
            | Self::MaxDrac
            | Self::SutAnticipation
            | Self::SutDelay => ValueDomain::NonNegative,
            Self::WarningLead | Self::KnowledgeLead | Self::GridLead | Self::GridOrWarningLead | Self::SutLead => {
                ValueDomain::Real
            }
        }
    }

    /// The unit of its values.
    pub fn unit(self) -> Unit {
        match self {
            Self::ClosestDistance => Unit::Metres,
            Self::MaxDrac => Unit::MetresPerSecondSquared,
            _ => Unit::Seconds,
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
