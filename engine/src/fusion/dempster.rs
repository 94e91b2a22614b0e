//! Dempster's rule of combination (seed 001, eq. 1) on the frame {Empty, Occupy}.
//!
//! For two sources the conflict is k = e₁o₂ + o₁e₂ and
//!
//! ```text
//! m(E) = (e₁e₂ + e₁u₂ + u₁e₂) / (1 − k)
//! m(O) = (o₁o₂ + o₁u₂ + u₁o₂) / (1 − k)
//! m(Θ) = u₁u₂ / (1 − k)
//! ```
//!
//! We divide by the sum of the three numerators rather than by 1 − k: the two
//! are equal for mass functions, but the sum keeps the result normalised to the
//! last bit when the inputs carry rounding error.
//!
//! **Total conflict** (k = 1: all numerators zero, e.g. {Empty} certain against
//! {Occupy} certain) leaves the rule undefined. We return the vacuous mass
//! (complete ignorance) with conflict 1, never NaN, and the n-source
//! [`Combiner`] keeps it absorbing: once the sources are in total conflict no
//! further source changes that, so the result does not depend on source order.

use super::mass::Mass;
use crate::idealisation::Idealisation;

/// Dempster's rule combines distinct evidence.
pub(crate) const INDEPENDENT_EVIDENCE: Idealisation = Idealisation {
    id: "fusion.dempster-independent",
    text: "Dempster's rule treats the sources as independent bodies of evidence: sources that share an error \
           corroborate each other.",
};

/// The result of a combination: the fused mass and the conflict it discarded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Combination {
    /// The normalised fused mass (vacuous under total conflict).
    pub mass: Mass,
    /// The conflict k ∈ [0, 1].
    pub conflict: f64,
    /// Whether the sources are in total conflict (no agreeing product at all).
    pub total_conflict: bool,
}

/// The unnormalised conjunctive combination: the three numerators of eq. 1.
#[inline]
fn conjunctive(a: Mass, b: Mass) -> Mass {
    Mass::new(
        a.empty * b.empty + a.empty * b.unknown + a.unknown * b.empty,
        a.occupied * b.occupied + a.occupied * b.unknown + a.unknown * b.occupied,
        a.unknown * b.unknown,
    )
}

/// The mass e₁o₂ + o₁e₂ the conjunctive combination of `a` and `b` puts on ∅.
#[inline]
fn pair_conflict(a: Mass, b: Mass) -> f64 {
    a.empty * b.occupied + a.occupied * b.empty
}

/// The conflict k = e₁o₂ + o₁e₂ of two mass functions, at most 1.
#[inline]
fn conflict(a: Mass, b: Mass) -> f64 {
    pair_conflict(a, b).min(1.0)
}

/// Scales a conjunctive result to sum to 1, or `None` under total conflict.
/// Divides rather than multiplying by 1/agreement: the reciprocal of a subnormal
/// agreement overflows to infinity.
#[inline]
fn normalise(raw: Mass) -> Option<Mass> {
    let agreement = raw.total();
    (agreement > 0.0).then(|| Mass::new(raw.empty / agreement, raw.occupied / agreement, raw.unknown / agreement))
}

const TOTAL_CONFLICT: Combination = Combination {
    mass: Mass::VACUOUS,
    conflict: 1.0,
    total_conflict: true,
};

/// Combines two masses with Dempster's rule.
///
/// Under total conflict the returned mass is the vacuous one, which is also the
/// rule's identity: a caller that chains `.mass` into a further combination
/// without checking [`Combination::total_conflict`] loses the conflict. Use a
/// [`Combiner`] for more than two sources.
#[inline]
pub fn combine(a: Mass, b: Mass) -> Combination {
    match normalise(conjunctive(a, b)) {
        Some(mass) => Combination {
            mass,
            conflict: conflict(a, b),
            total_conflict: false,
        },
        None => TOTAL_CONFLICT,
    }
}

/// Combines any number of sources with Dempster's rule, one at a time.
///
/// The rule is associative and commutative, so the order of [`add`](Self::add)
/// calls does not matter (up to rounding). The accumulated conflict is the
/// conflict of the n-source combination, K = 1 − Πⱼ(1 − kⱼ), with each kⱼ
/// computed as in eq. 1.
///
/// The combiner keeps the conjunctive combination unnormalised and divides by
/// its sum once, in [`finish`](Self::finish): normalising after every source
/// is the same up to rounding, but puts three divisions on the chain from one
/// source to the next, which made fusion a third of the seed 001 experiment.
/// Beside it, it keeps the mass the combination gave to conflicting pairs, so
/// that K is that mass over all the mass (exactly 0 when no pair conflicts,
/// and no cancellation in 1 − Π). Both are rescaled by 2⁶⁰⁰ when the
/// combination falls below 2⁻⁶⁰⁰, so that a long chain of conflicting
/// sources does not underflow: only a true total conflict (every numerator
/// zero) reaches zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Combiner {
    /// The unnormalised conjunctive combination so far (times a power of two).
    raw: Mass,
    /// The mass given to conflicting pairs so far, on the same scale.
    conflict: f64,
    total_conflict: bool,
}

impl Default for Combiner {
    fn default() -> Self {
        Self::new()
    }
}

/// Below this sum the combination is rescaled (2⁻⁶⁰⁰).
const RESCALE_BELOW: f64 = 2.409_919_865_102_884_6e-181;
/// The rescaling factor, 2⁶⁰⁰.
const RESCALE_BY: f64 = 4.149_515_568_880_993e180;
/// Conflict beyond this (2⁷⁰⁰) is kept there when rescaled: against an
/// agreement below 2⁻⁶⁰⁰ · 2⁶⁰⁰ it is K = 1 to the last bit, and capping it
/// keeps it finite.
const CONFLICT_CAP: f64 = 5.260_135_901_548_374e210;

impl Combiner {
    /// A combiner holding the vacuous mass (no evidence yet).
    pub const fn new() -> Self {
        Self {
            raw: Mass::VACUOUS,
            conflict: 0.0,
            total_conflict: false,
        }
    }

    /// Combines one more source into the result.
    #[inline]
    pub fn add(&mut self, source: Mass) {
        if self.total_conflict {
            return;
        }
        let (raw, mut conflict) = (
            conjunctive(self.raw, source),
            self.conflict * source.total() + pair_conflict(self.raw, source),
        );
        let agreement = raw.total();
        if agreement > RESCALE_BELOW {
            self.raw = raw;
            self.conflict = conflict;
        } else if agreement > 0.0 {
            conflict = (conflict * RESCALE_BY).min(CONFLICT_CAP);
            self.raw = Mass::new(
                raw.empty * RESCALE_BY,
                raw.occupied * RESCALE_BY,
                raw.unknown * RESCALE_BY,
            );
            self.conflict = conflict;
        } else {
            self.total_conflict = true;
        }
    }

    /// The fused mass and the total conflict K.
    pub fn finish(&self) -> Combination {
        if self.total_conflict {
            return TOTAL_CONFLICT;
        }
        let agreement = self.raw.total();
        Combination {
            mass: Mass::new(
                self.raw.empty / agreement,
                self.raw.occupied / agreement,
                self.raw.unknown / agreement,
            ),
            conflict: (self.conflict / (self.conflict + agreement)).clamp(0.0, 1.0),
            total_conflict: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;
    use crate::fusion::mass::State;

    fn assert_mass(actual: Mass, expected: [f64; 3]) {
        for (a, e) in actual.to_array().iter().zip(expected) {
            assert_relative_eq!(*a, e, epsilon = 1e-12);
        }
    }

    /// Worked by hand from eq. 1: m₁ = (0.6, 0.3, 0.1), m₂ = (0.5, 0.2, 0.3).
    /// k = 0.6·0.2 + 0.3·0.5 = 0.27, 1 − k = 0.73;
    /// E: 0.30 + 0.18 + 0.05 = 0.53; O: 0.06 + 0.09 + 0.02 = 0.17; Θ: 0.03.
    #[test]
    fn two_sources_by_hand() {
        let c = combine(Mass::new(0.6, 0.3, 0.1), Mass::new(0.5, 0.2, 0.3));
        assert_relative_eq!(c.conflict, 0.27, epsilon = 1e-12);
        assert_mass(c.mass, [0.53 / 0.73, 0.17 / 0.73, 0.03 / 0.73]);
    }

    /// Two confident, agreeing sensors as in the paper's experiment:
    /// (0.9375, 0.03125, 0.03125) twice: k = 2·0.9375·0.03125 = 0.05859375;
    /// E: 0.87890625 + 2·0.029296875 = 0.9375; O: 0.0029296875; Θ: 0.0009765625.
    #[test]
    fn agreeing_sources_sharpen() {
        let m = Mass::new(0.9375, 0.03125, 0.03125);
        let c = combine(m, m);
        assert_relative_eq!(c.conflict, 0.05859375, epsilon = 1e-15);
        let norm = 1.0 - 0.05859375;
        assert_mass(c.mass, [0.9375 / norm, 0.0029296875 / norm, 0.0009765625 / norm]);
    }

    #[test]
    fn total_conflict_is_vacuous_with_k_one() {
        let c = combine(Mass::certain(State::Empty), Mass::certain(State::Occupied));
        assert_eq!(c.mass, Mass::VACUOUS);
        assert_eq!(c.conflict, 1.0);
        assert!(c.total_conflict);
    }

    #[test]
    fn total_conflict_absorbs_later_sources() {
        let mut combiner = Combiner::new();
        combiner.add(Mass::certain(State::Empty));
        combiner.add(Mass::certain(State::Occupied));
        combiner.add(Mass::new(0.5, 0.0, 0.5));
        assert_eq!(combiner.finish(), TOTAL_CONFLICT);
    }

    /// Three sources: K = 1 − (1 − k₁)(1 − k₂) equals the conflict of the
    /// unnormalised conjunctive combination, computed here directly.
    #[test]
    fn combiner_conflict_is_the_n_source_conflict() {
        let sources = [
            Mass::new(0.6, 0.3, 0.1),
            Mass::new(0.5, 0.2, 0.3),
            Mass::new(0.1, 0.7, 0.2),
        ];
        let mut combiner = Combiner::new();
        sources.iter().for_each(|&m| combiner.add(m));
        // Unnormalised conjunctive combination of the three.
        let (mut e, mut o, mut u) = (1.0, 0.0, 0.0);
        let mut first = true;
        for m in sources {
            if first {
                (e, o, u) = (m.empty, m.occupied, m.unknown);
                first = false;
            } else {
                (e, o, u) = (
                    e * m.empty + e * m.unknown + u * m.empty,
                    o * m.occupied + o * m.unknown + u * m.occupied,
                    u * m.unknown,
                );
            }
        }
        let fused = combiner.finish();
        assert_relative_eq!(fused.conflict, 1.0 - (e + o + u), epsilon = 1e-12);
        assert_mass(fused.mass, [e / (e + o + u), o / (e + o + u), u / (e + o + u)]);
    }

    /// Issue 20: the combiner normalises once, at the end. A chain of 3000
    /// sources that each conflict with the combination (agreement about
    /// 0.6 a step, 10⁻⁶⁶⁶ in all) rescales instead of underflowing: the
    /// result is what normalising at every step gives, the conflict 1 to the
    /// last bit, and the sources are not taken for a total conflict.
    #[test]
    fn a_long_conflicting_chain_rescales_instead_of_underflowing() {
        let sources = [Mass::new(0.6, 0.3, 0.1), Mass::new(0.3, 0.6, 0.1)];
        let mut combiner = Combiner::new();
        let mut stepwise = Mass::VACUOUS;
        for i in 0..3000 {
            combiner.add(sources[i % 2]);
            stepwise = normalise(conjunctive(stepwise, sources[i % 2])).expect("no total conflict");
        }
        let fused = combiner.finish();
        assert!(!fused.total_conflict);
        assert_eq!(fused.conflict, 1.0);
        for (a, e) in fused.mass.to_array().iter().zip(stepwise.to_array()) {
            assert_relative_eq!(*a, e, max_relative = 1e-9);
        }
    }

    /// A source that conflicts with nothing adds exactly no conflict.
    #[test]
    fn agreeing_sources_have_exactly_no_conflict() {
        let mut combiner = Combiner::new();
        combiner.add(Mass::new(0.4, 0.0, 0.6));
        combiner.add(Mass::new(0.7, 0.0, 0.3));
        assert_eq!(combiner.finish().conflict, 0.0);
        let mut one = Combiner::new();
        one.add(Mass::new(0.2, 0.5, 0.3));
        assert_eq!(one.finish().conflict, 0.0);
    }

    #[test]
    fn vacuous_is_the_identity() {
        let m = Mass::new(0.2, 0.5, 0.3);
        let c = combine(m, Mass::VACUOUS);
        assert_mass(c.mass, m.to_array());
        assert_eq!(c.conflict, 0.0);
    }
}
