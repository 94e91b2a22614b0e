//! The distance-weighted Dempster rule of seed 001 (§III-B) and its variants.
//!
//! As written, for two sources at distances d₁, d₂ from the cell:
//!
//! ```text
//! wᵢ   = (1/dᵢ) / (1/d₁ + 1/d₂)                     (weights sum to 1)
//! m'ᵢₛ = mᵢₛ^wᵢ / Σₜ mᵢₜ^wᵢ                         (s, t ∈ {E, O, Θ})
//! m̃    = Dempster(m'₁, m'₂)                         (eqs. 2–3, conflict k)
//! ```
//!
//! The paper leaves open how weights are scaled when it matters (see
//! [`WeightScaling`]) and how more than two sources combine (see
//! [`SourceCombination`]); both are scenario options.
//!
//! Note what the power transform does: w < 1 pulls a mass vector toward the
//! uniform (⅓, ⅓, ⅓), not toward ignorance (0, 0, 1), so a weakly weighted source
//! still puts mass on both Empty and Occupy and so adds conflict.

use sightline_dsl::{SourceCombination, WeightScaling, Weighting};

use super::dempster::{Combination, Combiner, combine};
use super::mass::Mass;
use crate::elementary::pow;

/// The power transform m'ₛ = mₛ^w / Σₜ mₜ^w of a mass vector by weight `w` > 0.
///
/// Computed as (mₛ/m_max)^w / Σₜ (mₜ/m_max)^w, which is the same quantity: the
/// largest term is exactly 1, so the sum lies in [1, 3] and cannot underflow
/// however large w is, and the largest mass needs no power at all.
#[inline]
pub fn discount(mass: Mass, weight: f64) -> Mass {
    if weight == 1.0 {
        return mass;
    }
    let terms = transform_terms(mass, weight);
    let total = terms.total();
    Mass::new(terms.empty / total, terms.occupied / total, terms.unknown / total)
}

/// The power transform before its normalisation: terms proportional to
/// [`discount`]'s masses, the largest 1. Dempster's rule does not depend on
/// the scale of a source (the [`Combiner`] divides once, by the scale of the
/// whole combination), so the weighted rule combines these as they are.
#[inline]
pub(super) fn transform_terms(mass: Mass, weight: f64) -> Mass {
    if weight == 1.0 {
        return mass;
    }
    let (largest, ratios) = Ratios::of(mass);
    largest.terms(ratios.map(|ratio| pow(ratio, weight)))
}

/// Which state holds the largest mass: the power transform leaves its term
/// at 1 and raises the other two ratios, in state order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Ratios(u8);

impl Ratios {
    /// The largest state of `mass` and the other two masses over it (1 for
    /// a tie, so that tied states stay equal).
    #[inline]
    pub(super) fn of(mass: Mass) -> (Self, [f64; 2]) {
        let m = mass.to_array();
        let largest = if m[0] >= m[1] && m[0] >= m[2] {
            0
        } else if m[1] >= m[2] {
            1
        } else {
            2
        };
        let max = m[largest];
        let ratio = |other: usize| if m[other] == max { 1.0 } else { m[other] / max };
        let [a, b] = Self::others(largest);
        (Self(largest as u8), [ratio(a), ratio(b)])
    }

    /// The transform's terms from the two ratios raised to the weight: the
    /// largest state's is 1.
    #[inline]
    pub(super) fn terms(self, powers: [f64; 2]) -> Mass {
        let mut terms = [1.0; 3];
        let [a, b] = Self::others(usize::from(self.0));
        (terms[a], terms[b]) = (powers[0], powers[1]);
        Mass::new(terms[0], terms[1], terms[2])
    }

    /// The two states other than `largest`, in state order.
    #[inline]
    fn others(largest: usize) -> [usize; 2] {
        match largest {
            0 => [1, 2],
            1 => [0, 2],
            _ => [0, 1],
        }
    }
}

/// What the weights of one cell's sources depend on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distances {
    /// Number of sources.
    pub count: usize,
    /// Σⱼ 1/dⱼ.
    pub inverse_sum: f64,
    /// min dⱼ.
    pub min: f64,
    /// max dⱼ.
    pub max: f64,
}

impl Distances {
    /// Summarises the distances of a cell's sources (all > 0).
    pub fn of(distances: impl IntoIterator<Item = f64>) -> Self {
        distances.into_iter().fold(
            Self {
                count: 0,
                inverse_sum: 0.0,
                min: f64::INFINITY,
                max: 0.0,
            },
            |acc, d| Self {
                count: acc.count + 1,
                inverse_sum: acc.inverse_sum + 1.0 / d,
                min: acc.min.min(d),
                max: acc.max.max(d),
            },
        )
    }

    /// The weight of a source at `distance` under `scaling`.
    #[inline]
    pub fn weight(&self, distance: f64, scaling: WeightScaling) -> f64 {
        match scaling {
            WeightScaling::SumToOne => 1.0 / (distance * self.inverse_sum),
            WeightScaling::MeanOne => self.count as f64 / (distance * self.inverse_sum),
            WeightScaling::NearestOne => self.min / distance,
        }
    }
}

/// The paper's two-source rule, with `scaling` applied to the weights.
pub fn combine_two(a: Mass, distance_a: f64, b: Mass, distance_b: f64, scaling: WeightScaling) -> Combination {
    let distances = Distances::of([distance_a, distance_b]);
    combine(
        discount(a, distances.weight(distance_a, scaling)),
        discount(b, distances.weight(distance_b, scaling)),
    )
}

/// Combines a cell's sources (mass, distance) with the weighted rule.
pub fn combine_all(sources: impl Iterator<Item = (Mass, f64)> + Clone, weighting: Weighting) -> Combination {
    combine_all_at(&Distances::of(sources.clone().map(|(_, d)| d)), sources, weighting)
}

/// [`combine_all`] when the caller already has the sources' [`Distances`].
pub fn combine_all_at(
    distances: &Distances,
    sources: impl Iterator<Item = (Mass, f64)>,
    weighting: Weighting,
) -> Combination {
    match weighting.sources {
        SourceCombination::AllAtOnce => {
            let mut combiner = Combiner::new();
            for (mass, distance) in sources {
                combiner.add(transform_terms(mass, distances.weight(distance, weighting.scaling)));
            }
            combiner.finish()
        }
        SourceCombination::Pairwise => pairwise(sources, weighting.scaling),
    }
}

/// Folds sources pairwise with [`combine_two`]; a fused result stands at the
/// distance whose inverse is the sum of its inputs' inverse distances.
fn pairwise(mut sources: impl Iterator<Item = (Mass, f64)>, scaling: WeightScaling) -> Combination {
    let Some((first, first_distance)) = sources.next() else {
        return Combiner::new().finish();
    };
    let mut mass = first;
    let mut distance = first_distance;
    let mut agreement = 1.0;
    for (next, next_distance) in sources {
        let step = combine_two(mass, distance, next, next_distance, scaling);
        if step.total_conflict {
            return step;
        }
        mass = step.mass;
        agreement *= 1.0 - step.conflict;
        distance = 1.0 / (1.0 / distance + 1.0 / next_distance);
    }
    Combination {
        mass,
        conflict: (1.0 - agreement).clamp(0.0, 1.0),
        total_conflict: false,
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// By hand: m = (0.81, 0.09, 0.10) with w = 0.5 → (0.9, 0.3, √0.1) / Σ.
    #[test]
    fn discount_is_a_normalised_power() {
        let d = discount(Mass::new(0.81, 0.09, 0.10), 0.5);
        let total = 0.9 + 0.3 + 0.1f64.sqrt();
        assert_relative_eq!(d.empty, 0.9 / total, epsilon = 1e-12);
        assert_relative_eq!(d.occupied, 0.3 / total, epsilon = 1e-12);
        assert_relative_eq!(d.unknown, 0.1f64.sqrt() / total, epsilon = 1e-12);
    }

    #[test]
    fn discount_toward_zero_weight_tends_to_uniform_not_vacuous() {
        let d = discount(Mass::new(0.98, 0.01, 0.01), 1e-9);
        for m in d.to_array() {
            assert_relative_eq!(m, 1.0 / 3.0, epsilon = 1e-6);
        }
    }

    /// The paper's weights for d = (50, 150): w = (0.75, 0.25).
    #[test]
    fn paper_weights_sum_to_one() {
        let distances = Distances::of([50.0, 150.0]);
        assert_relative_eq!(distances.weight(50.0, WeightScaling::SumToOne), 0.75, epsilon = 1e-12);
        assert_relative_eq!(distances.weight(150.0, WeightScaling::SumToOne), 0.25, epsilon = 1e-12);
        assert_relative_eq!(distances.weight(50.0, WeightScaling::MeanOne), 1.5, epsilon = 1e-12);
        assert_relative_eq!(
            distances.weight(150.0, WeightScaling::NearestOne),
            1.0 / 3.0,
            epsilon = 1e-12
        );
    }

    /// Worked by hand: m₁ = (0.81, 0.09, 0.10) at 50 m, m₂ = (0.25, 0.64, 0.11) at
    /// 50 m. Equal distances give w = ½ each, so m'ᵢ = √mᵢ / Σ√mᵢ:
    /// m'₁ = (0.9, 0.3, 0.31623)/1.51623, m'₂ = (0.5, 0.8, 0.33166)/1.63166,
    /// then eqs. 2–3.
    #[test]
    fn two_sources_as_written_by_hand() {
        let s1 = 0.9 + 0.3 + 0.1f64.sqrt();
        let s2 = 0.5 + 0.8 + 0.11f64.sqrt();
        let (e1, o1, u1) = (0.9 / s1, 0.3 / s1, 0.1f64.sqrt() / s1);
        let (e2, o2, u2) = (0.5 / s2, 0.8 / s2, 0.11f64.sqrt() / s2);
        let k = e1 * o2 + o1 * e2;
        let alpha = 1.0 / (1.0 - k);
        let expected = [
            alpha * (e1 * e2 + e1 * u2 + e2 * u1),
            alpha * (o1 * o2 + o1 * u2 + o2 * u1),
            alpha * (u1 * u2),
        ];
        let c = combine_two(
            Mass::new(0.81, 0.09, 0.10),
            50.0,
            Mass::new(0.25, 0.64, 0.11),
            50.0,
            WeightScaling::SumToOne,
        );
        assert_relative_eq!(c.conflict, k, epsilon = 1e-12);
        for (a, e) in c.mass.to_array().iter().zip(expected) {
            assert_relative_eq!(*a, e, epsilon = 1e-12);
        }
    }

    /// Worked by hand with unequal weights (§III-B): m₁ = (0.7, 0.2, 0.1) at 20 m,
    /// m₂ = (0.1, 0.8, 0.1) at 60 m. w₁ = (1/20)/(1/20 + 1/60) = 0.75, w₂ = 0.25.
    /// m₁^0.75 = (0.765286, 0.299070, 0.177828), sum 1.242183, so
    /// m'₁ = (0.616081, 0.240761, 0.143158); m₂^0.25 = (0.562341, 0.945742,
    /// 0.562341), sum 2.070424, so m'₂ = (0.271607, 0.456786, 0.271607).
    /// k = 0.616081·0.456786 + 0.240761·0.271607 = 0.346810, α = 1.530948;
    /// m̃_e = α(0.616081·0.271607 + 0.616081·0.271607 + 0.271607·0.143158) = 0.571880,
    /// m̃_o = α(0.240761·0.456786 + 0.240761·0.271607 + 0.456786·0.143158) = 0.368593,
    /// m̃_u = α·0.143158·0.271607 = 0.059527. The nearer source's Empty wins,
    /// where Dempster's rule (equal say) would favour Occupy.
    #[test]
    fn two_sources_with_unequal_weights_by_hand() {
        let c = combine_two(
            Mass::new(0.7, 0.2, 0.1),
            20.0,
            Mass::new(0.1, 0.8, 0.1),
            60.0,
            WeightScaling::SumToOne,
        );
        assert_relative_eq!(c.conflict, 0.346810, epsilon = 1e-6);
        for (a, e) in c.mass.to_array().iter().zip([0.571880, 0.368593, 0.059527]) {
            assert_relative_eq!(*a, e, epsilon = 1e-6);
        }
        // The order of the sources does not matter.
        let swapped = combine_two(
            Mass::new(0.1, 0.8, 0.1),
            60.0,
            Mass::new(0.7, 0.2, 0.1),
            20.0,
            WeightScaling::SumToOne,
        );
        for (a, b) in c.mass.to_array().iter().zip(swapped.mass.to_array()) {
            assert_relative_eq!(*a, b, epsilon = 1e-12);
        }
    }

    /// The mechanism table of docs/findings/seed-001.md: n agreeing sensors, each
    /// reporting the mean vector at d = 0 of the paper's experiment, (0.9375,
    /// 0.03125, 0.03125), at equal distances. As written, their fused
    /// p_max − p_others falls below θ = 0.8 from n = 4 on, and falls further as n
    /// grows (p_max = (1 + margin)/2 stays above 0.8: 0.9110, 0.8853, 0.8739);
    /// Dempster's rule goes to 1.
    #[test]
    fn as_written_agreeing_sources_fall_below_the_paper_threshold() {
        let p_max = |m: Mass| m.empty.max(m.occupied).max(m.unknown);
        let margin = |m: Mass| p_max(m) - (m.total() - p_max(m));
        let ideal = Mass::new(0.9375, 0.03125, 0.03125);
        let as_written = Weighting {
            scaling: WeightScaling::SumToOne,
            sources: SourceCombination::AllAtOnce,
        };
        for (n, dempster, weighted) in [(2, 0.9917, 0.8220), (4, 1.0, 0.7706), (6, 1.0, 0.7479)] {
            let sources = vec![(ideal, 100.0); n];
            let mut standard = Combiner::new();
            sources.iter().for_each(|&(m, _)| standard.add(m));
            assert_relative_eq!(margin(standard.finish().mass), dempster, epsilon = 5e-5);
            let fused = combine_all(sources.iter().copied(), as_written);
            assert_relative_eq!(margin(fused.mass), weighted, epsilon = 5e-5);
            assert_relative_eq!(p_max(fused.mass), (1.0 + weighted) / 2.0, epsilon = 5e-5);
        }
    }

    #[test]
    fn all_at_once_equals_the_paper_for_two_sources() {
        let a = (Mass::new(0.7, 0.2, 0.1), 40.0);
        let b = (Mass::new(0.3, 0.5, 0.2), 120.0);
        for scaling in [
            WeightScaling::SumToOne,
            WeightScaling::MeanOne,
            WeightScaling::NearestOne,
        ] {
            for sources in [SourceCombination::AllAtOnce, SourceCombination::Pairwise] {
                let n = combine_all([a, b].into_iter(), Weighting { scaling, sources });
                let two = combine_two(a.0, a.1, b.0, b.1, scaling);
                for (x, y) in n.mass.to_array().iter().zip(two.mass.to_array()) {
                    assert_relative_eq!(*x, y, epsilon = 1e-12);
                }
                assert_relative_eq!(n.conflict, two.conflict, epsilon = 1e-12);
            }
        }
    }
}
