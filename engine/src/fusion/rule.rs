//! One entry point for every fusion rule: a cell's sources in, an estimate out.

use sightline_dsl::{FusionMethod, Rule, SwitchMeasure};

use super::bayes::{self, Occupancy};
use super::dempster::{Combination, Combiner};
use super::mass::Mass;
use super::weighted::{self, Distances};
use crate::idealisation::Idealisation;

/// The idealisations of a fusion method.
pub(crate) fn method_idealisations(method: FusionMethod) -> &'static [Idealisation] {
    match method {
        FusionMethod::Bayes => &[bayes::INDEPENDENT_MEASUREMENTS],
        FusionMethod::Dempster | FusionMethod::DistanceWeighted | FusionMethod::Hybrid => {
            &[super::dempster::INDEPENDENT_EVIDENCE]
        }
    }
}

/// One sensor's evidence about a cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Source {
    /// The sensor's mass vector.
    pub mass: Mass,
    /// Sensor–cell distance, metres (> 0).
    pub distance: f64,
}

/// A fused cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Estimate {
    /// The result of an evidential rule.
    Evidential {
        /// Fused mass and conflict.
        combination: Combination,
        /// Whether the distance-weighted rule was used for this cell.
        weighted: bool,
    },
    /// The result of Bayesian fusion.
    Occupancy(Occupancy),
}

impl Estimate {
    /// The masses the decision rule reads: the fused mass, or (1 − p, p, 0) for Bayes.
    pub fn decision_mass(&self) -> Mass {
        match self {
            Self::Evidential { combination, .. } => combination.mass,
            Self::Occupancy(o) => Mass::new(1.0 - o.probability, o.probability, 0.0),
        }
    }

    /// Per-cell uncertainty: the Unknown mass, or the entropy of a Bayesian cell.
    pub fn uncertainty(&self) -> f64 {
        match self {
            Self::Evidential { combination, .. } => combination.mass.unknown,
            Self::Occupancy(o) => o.uncertainty,
        }
    }
}

/// Fuses a cell's sources (at least one) with `rule`.
pub fn fuse(rule: &Rule, sources: &[Source]) -> Estimate {
    let pairs = sources.iter().map(|s| (s.mass, s.distance));
    match rule {
        Rule::Bayes => Estimate::Occupancy(bayes::fuse(sources.iter().map(|s| s.mass))),
        Rule::Dempster => standard(sources),
        Rule::DistanceWeighted(weighting) => Estimate::Evidential {
            combination: weighted::combine_all(pairs, *weighting),
            weighted: sources.len() > 1,
        },
        Rule::Hybrid { weighting, switch } => {
            let distances = Distances::of(sources.iter().map(|s| s.distance));
            let spread = match switch.measure {
                SwitchMeasure::Difference => distances.max - distances.min,
                SwitchMeasure::Ratio => distances.max / distances.min,
            };
            if sources.len() > 1 && spread > switch.threshold {
                Estimate::Evidential {
                    combination: weighted::combine_all_at(&distances, pairs, *weighting),
                    weighted: true,
                }
            } else {
                standard(sources)
            }
        }
    }
}

fn standard(sources: &[Source]) -> Estimate {
    let mut combiner = Combiner::new();
    for source in sources {
        combiner.add(source.mass);
    }
    Estimate::Evidential {
        combination: combiner.finish(),
        weighted: false,
    }
}
