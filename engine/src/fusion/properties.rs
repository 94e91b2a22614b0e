//! Algebraic properties of the fusion rules: Dempster's rule (seed 001, §II-B, eq. 1)
//! and the distance-weighted rule (§III-B) under every [`WeightScaling`] ×
//! [`SourceCombination`].
//!
//! Each test is named for the invariant it checks. Where an invariant holds it is a
//! property over generated inputs; where it does not, a unit test pins one concrete,
//! hand-checkable counterexample and asserts that the two sides differ by more than
//! [`DIFFERENT`]. `docs/findings/fusion-properties.md` tabulates every answer and names
//! the test that encodes it.
//!
//! # Determinism
//!
//! The properties run through the pinned runner (`crate::pinned`), not through the
//! `proptest!` macro, whose cases would depend on the `PROPTEST_*` variables.
//!
//! # Tolerances
//!
//! Masses are compared with `approx` at [`RELATIVE`] relative and [`ABSOLUTE`] absolute
//! error; conflicts at [`CONFLICT_ABSOLUTE`]. See the constants for why.

use super::dempster::{Combination, Combiner, combine};
use super::mass::{Mass, State};
use super::weighted::{combine_all, combine_two, discount};
use approx::relative_eq;
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::TestCaseResult;
use sightline_dsl::{SourceCombination, WeightScaling, Weighting};

// ---------------------------------------------------------------------------------------
// Configuration and tolerances
// ---------------------------------------------------------------------------------------

/// Relative tolerance on a mass component. Every mass component is built from sums and
/// products of non-negative numbers (conjunctive numerators, `powf`, normalisation), so
/// there is no cancellation and each operation adds a few ulps of *relative* error, even
/// under near-total conflict. A weight that should be 1 but is off by an ulp (MeanOne
/// rounds Σ 1/dⱼ) moves m^w by ε·|ln m| ≤ 2e-15 for grid masses ≥ 1/3000. Over 20,000
/// generated cases of the order, bracketing and reduction properties the largest
/// relative difference seen was 3.9e-15; 1e-12 leaves more than two orders of margin
/// and is still nine orders below the differences of the counterexamples.
const RELATIVE: f64 = 1e-12;

/// Absolute tolerance on a mass component, for components at or near zero, where a
/// relative comparison means nothing. Exact zeros stay exact (0·x = 0, 0^w = 0), so this
/// only has to absorb rounding of values that are tiny but non-zero.
const ABSOLUTE: f64 = 1e-15;

/// Absolute tolerance on a conflict. The combiners report K = 1 − Π(1 − kⱼ), a
/// difference close to 1 that cancels; its absolute error is a few ulps of 1 per source.
const CONFLICT_ABSOLUTE: f64 = 1e-12;

/// How far apart (max-norm over the three components) two results of a counterexample
/// must be for the property to count as failing. Every counterexample below differs by
/// at least 8e-3, and the holding properties agree to 1e-12, so the answer does not
/// depend on where between the two this threshold sits.
const DIFFERENT: f64 = 1e-3;

/// Tolerance on the six-significant-digit values quoted in comments and in the findings
/// document (rounding to six digits moves a value in [0, 1] by at most 5e-7).
const QUOTED: f64 = 1e-6;

/// Runs `property` on `strategy` with the pinned runner and panics with the shrunk
/// counterexample if it fails.
fn check<S: Strategy>(strategy: S, property: impl Fn(S::Value) -> TestCaseResult) {
    let mut runner = crate::pinned::runner(512, 0x5167_4711_0001);
    if let Err(failure) = runner.run(&strategy, property) {
        panic!("{failure}");
    }
}

// ---------------------------------------------------------------------------------------
// Strategies
// ---------------------------------------------------------------------------------------

/// Resolution of the integer grid masses are drawn on.
const GRID: u32 = 1000;

/// A mass function drawn on an integer grid: three counts in 0..=GRID, normalised.
/// Integers shrink towards small, readable counts where floats would not. A count is
/// zero with probability about 1/5 so that masses with one or two empty focal elements
/// (and so exact zeros and total conflict) are common; the all-zero draw, which is not
/// a mass function, becomes the vacuous mass instead of being rejected.
fn grid_mass() -> impl Strategy<Value = Mass> {
    let count = || prop_oneof![1 => Just(0u32), 4 => 0..=GRID];
    (count(), count(), count()).prop_map(|(empty, occupied, unknown)| {
        let total = empty + occupied + unknown;
        if total == 0 {
            return Mass::VACUOUS;
        }
        let total = f64::from(total);
        Mass::new(
            f64::from(empty) / total,
            f64::from(occupied) / total,
            f64::from(unknown) / total,
        )
    })
}

/// A mass function, degenerate (certain Empty, certain Occupy, vacuous) three times in
/// ten.
fn mass() -> impl Strategy<Value = Mass> {
    prop_oneof![
        1 => Just(Mass::certain(State::Empty)),
        1 => Just(Mass::certain(State::Occupied)),
        1 => Just(Mass::VACUOUS),
        7 => grid_mass(),
    ]
}

/// A sensor–cell distance in metres, drawn in decimetres from 0.1 m to 300 m.
fn distance() -> impl Strategy<Value = f64> {
    (1u32..=3000).prop_map(|decimetres| f64::from(decimetres) / 10.0)
}

/// One sensor's evidence about a cell: its mass and its distance in metres.
type Source = (Mass, f64);

/// One source: its mass and its distance, drawn together.
fn source() -> impl Strategy<Value = Source> {
    (mass(), distance())
}

/// The sources of one cell, one to six of them.
fn sources() -> impl Strategy<Value = Vec<Source>> {
    vec(source(), 1..=6)
}

/// The sources of one cell and the same sources in a shuffled order.
fn sources_and_permutation() -> impl Strategy<Value = (Vec<Source>, Vec<Source>)> {
    sources().prop_flat_map(|sources| (Just(sources.clone()), Just(sources).prop_shuffle()))
}

const SCALINGS: [WeightScaling; 3] = [
    WeightScaling::SumToOne,
    WeightScaling::MeanOne,
    WeightScaling::NearestOne,
];

/// Every scaling × source combination.
fn weightings() -> impl Iterator<Item = Weighting> {
    [SourceCombination::AllAtOnce, SourceCombination::Pairwise]
        .into_iter()
        .flat_map(|sources| SCALINGS.map(|scaling| Weighting { scaling, sources }))
}

// ---------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------

/// What the library returns under total conflict: a constant, so comparing it exactly
/// compares no computed float.
const TOTAL_CONFLICT: Combination = Combination {
    mass: Mass::VACUOUS,
    conflict: 1.0,
    total_conflict: true,
};

fn masses_close(a: Mass, b: Mass) -> bool {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .all(|(x, y)| relative_eq!(*x, y, epsilon = ABSOLUTE, max_relative = RELATIVE))
}

/// Both results agree on total conflict and, outside it, on mass and conflict.
fn assert_same_combination(left: Combination, right: Combination) -> TestCaseResult {
    prop_assert_eq!(left.total_conflict, right.total_conflict, "{:?} vs {:?}", left, right);
    prop_assert!(masses_close(left.mass, right.mass), "{:?} vs {:?}", left, right);
    prop_assert!(
        relative_eq!(left.conflict, right.conflict, epsilon = CONFLICT_ABSOLUTE),
        "{:?} vs {:?}",
        left,
        right
    );
    Ok(())
}

/// The largest componentwise difference of two masses.
fn distance_between(a: Mass, b: Mass) -> f64 {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Asserts that `actual` matches a mass quoted to six significant digits.
fn assert_quoted(actual: Mass, quoted: [f64; 3]) {
    for (a, q) in actual.to_array().iter().zip(quoted) {
        assert!((a - q).abs() <= QUOTED, "{actual:?} is not {quoted:?}");
    }
}

/// Asserts that a counterexample is one: the two results differ by more than [`DIFFERENT`].
fn assert_differ(left: Mass, right: Mass) {
    let difference = distance_between(left, right);
    assert!(
        difference > DIFFERENT,
        "{left:?} and {right:?} differ by only {difference:e}"
    );
}

/// The result of a combination with Dempster's rule over all `sources`, ignoring distances.
fn dempster_of(sources: impl IntoIterator<Item = Mass>) -> Combination {
    let mut combiner = Combiner::new();
    sources.into_iter().for_each(|m| combiner.add(m));
    combiner.finish()
}

/// Whether some source is certain of Empty and another certain of Occupy: the only way
/// the conjunctive combination of mass functions on {Empty, Occupy} loses all its mass.
/// (Unless a source is certain of Occupy, every source has mass on {Empty} or Θ, so the
/// combination keeps mass on {Empty} or Θ; symmetrically for Occupy. Conversely, with a
/// certain Empty and a certain Occupy every intersection of focal elements is empty.)
///
/// Total conflict is a matter of exact zeros, so this compares exactly: the strategies
/// produce exact zeros (0/n) and exact ones (n/n).
fn certain_empty_meets_certain_occupy(sources: &[Mass]) -> bool {
    let certain = |state| sources.iter().any(|&m| m == Mass::certain(state));
    certain(State::Empty) && certain(State::Occupied)
}

/// The distance at which the pairwise rule places a fused pair: 1/d = 1/d₁ + 1/d₂.
fn fused_distance(d1: f64, d2: f64) -> f64 {
    1.0 / (1.0 / d1 + 1.0 / d2)
}

/// The pairwise weighted rule's binary operator on (mass, distance) pairs.
fn pairwise_step(a: Source, b: Source, scaling: WeightScaling) -> (Combination, f64) {
    (combine_two(a.0, a.1, b.0, b.1, scaling), fused_distance(a.1, b.1))
}

// ---------------------------------------------------------------------------------------
// Dempster's rule
// ---------------------------------------------------------------------------------------

/// The result is a mass function (components in [0, 1], summing to 1), the conflict is
/// in [0, 1], and total conflict is reported as exactly the documented sentinel.
#[test]
fn dempster_returns_a_mass_function() {
    check((mass(), mass()), |(a, b)| {
        let c = combine(a, b);
        prop_assert!(c.mass.is_mass_function(1e-12), "{:?}", c);
        prop_assert!((0.0..=1.0).contains(&c.conflict), "{:?}", c);
        if c.total_conflict {
            prop_assert_eq!(c, TOTAL_CONFLICT);
        }
        Ok(())
    });
}

/// Eq. 1 written out as the double sum over pairs of focal elements B ∩ C = A, with the
/// intersection table of the frame, independently of the library's closed form.
#[test]
fn dempster_matches_equation_one() {
    fn intersection(b: State, c: State) -> Option<State> {
        match (b, c) {
            (State::Unknown, x) | (x, State::Unknown) => Some(x),
            (x, y) if x == y => Some(x),
            _ => None,
        }
    }
    check((mass(), mass()), |(m1, m2)| {
        let mut numerator = [0.0; 3];
        let mut conflict = 0.0;
        for b in State::ALL {
            for c in State::ALL {
                let product = m1[b] * m2[c];
                match intersection(b, c) {
                    Some(a) => numerator[a as usize] += product,
                    None => conflict += product,
                }
            }
        }
        let fused = combine(m1, m2);
        prop_assert!(relative_eq!(fused.conflict, conflict, epsilon = CONFLICT_ABSOLUTE));
        let agreement: f64 = numerator.iter().sum();
        if certain_empty_meets_certain_occupy(&[m1, m2]) {
            prop_assert_eq!(fused, TOTAL_CONFLICT);
        } else {
            let expected = Mass::new(
                numerator[0] / agreement,
                numerator[1] / agreement,
                numerator[2] / agreement,
            );
            prop_assert!(masses_close(fused.mass, expected), "{:?} vs {:?}", fused, expected);
        }
        Ok(())
    });
}

#[test]
fn dempster_is_commutative() {
    check((mass(), mass()), |(a, b)| {
        assert_same_combination(combine(a, b), combine(b, a))
    });
}

/// (a ⊕ b) ⊕ c = a ⊕ (b ⊕ c), stated with total conflict kept absorbing the way
/// [`Combiner`] keeps it: a bracketing stops at the first totally conflicting step.
///
/// What holds exactly: (1) whether total conflict occurs does not depend on the
/// bracketing (the unnormalised conjunctive product of the three is zero either way);
/// (2) otherwise the fused masses agree, and so does the accumulated conflict
/// K = 1 − (1 − k_inner)(1 − k_outer); (3) both equal the n-source [`Combiner`].
/// What does not: chaining the binary rule through `.mass` alone, see
/// [`binary_dempster_chained_through_total_conflict_is_not_associative`].
#[test]
fn dempster_is_associative() {
    fn accumulated(inner: Combination, outer: Combination) -> Combination {
        if inner.total_conflict {
            return inner;
        }
        Combination {
            conflict: 1.0 - (1.0 - inner.conflict) * (1.0 - outer.conflict),
            ..outer
        }
    }
    check((mass(), mass(), mass()), |(a, b, c)| {
        let ab = combine(a, b);
        let left = accumulated(ab, combine(ab.mass, c));
        let bc = combine(b, c);
        let right = accumulated(bc, combine(a, bc.mass));
        assert_same_combination(left, right)?;
        assert_same_combination(left, dempster_of([a, b, c]))?;
        prop_assert_eq!(left.total_conflict, certain_empty_meets_certain_occupy(&[a, b, c]));
        if left.total_conflict {
            prop_assert_eq!(left, TOTAL_CONFLICT);
        }
        Ok(())
    });
}

/// The vacuous mass is the identity on both sides, and inserting it anywhere among a
/// cell's sources changes nothing (not even the conflict).
#[test]
fn vacuous_is_the_identity_of_dempster() {
    check((mass(), sources(), any::<prop::sample::Index>()), |(m, sources, at)| {
        for fused in [combine(m, Mass::VACUOUS), combine(Mass::VACUOUS, m)] {
            prop_assert!(!fused.total_conflict);
            prop_assert!(masses_close(fused.mass, m), "{:?} vs {:?}", fused, m);
            prop_assert!(relative_eq!(fused.conflict, 0.0, epsilon = CONFLICT_ABSOLUTE));
        }
        let masses: Vec<Mass> = sources.iter().map(|&(m, _)| m).collect();
        let mut with_vacuous = masses.clone();
        with_vacuous.insert(at.index(masses.len() + 1), Mass::VACUOUS);
        assert_same_combination(dempster_of(masses), dempster_of(with_vacuous))
    });
}

/// Whether n sources are in total conflict is exactly whether one is certain of Empty
/// and another certain of Occupy.
#[test]
fn dempster_is_in_total_conflict_exactly_when_certain_empty_meets_certain_occupy() {
    check(sources(), |sources| {
        let masses: Vec<Mass> = sources.iter().map(|&(m, _)| m).collect();
        prop_assert_eq!(
            dempster_of(masses.iter().copied()).total_conflict,
            certain_empty_meets_certain_occupy(&masses)
        );
        Ok(())
    });
}

/// Under total conflict (k = 1) both the binary rule and the n-source combiner return
/// the vacuous mass with conflict 1, never NaN, and sources after it change nothing.
#[test]
fn total_conflict_never_yields_nan() {
    let conflicting = (
        prop_oneof![
            Just([Mass::certain(State::Empty), Mass::certain(State::Occupied)]),
            Just([Mass::certain(State::Occupied), Mass::certain(State::Empty)]),
        ],
        vec(mass(), 0..=4),
        any::<prop::sample::Index>(),
        any::<prop::sample::Index>(),
    );
    check(conflicting, |([x, y], others, at_x, at_y)| {
        prop_assert_eq!(combine(x, y), TOTAL_CONFLICT);
        // The conflicting pair anywhere among other sources: still total conflict.
        let mut masses = others;
        masses.insert(at_x.index(masses.len() + 1), x);
        masses.insert(at_y.index(masses.len() + 1), y);
        let fused = dempster_of(masses);
        prop_assert!(fused.mass.to_array().iter().all(|m| m.is_finite()));
        prop_assert!(fused.conflict.is_finite());
        prop_assert_eq!(fused, TOTAL_CONFLICT);
        Ok(())
    });
}

/// The n-source combination does not depend on the order sources are added in.
#[test]
fn dempster_combiner_is_independent_of_source_order() {
    check(sources_and_permutation(), |(sources, permuted)| {
        assert_same_combination(
            dempster_of(sources.iter().map(|&(m, _)| m)),
            dempster_of(permuted.iter().map(|&(m, _)| m)),
        )
    });
}

/// The vacuous sentinel is the identity of the rule, so chaining the binary rule through
/// `.mass` alone forgets a total conflict: (a ⊕ b) ⊕ c = Vacuous ⊕ c = c, while
/// a ⊕ (b ⊕ c) is in total conflict. Associativity holds only if the `total_conflict`
/// flag is carried, as [`Combiner`] and the pairwise weighted rule do.
///
/// a = (1, 0, 0), b = (0, 1, 0), c = (0.5, 0.2, 0.3):
/// left  = c = (0.5, 0.2, 0.3), conflict 0 (the total conflict of a ⊕ b is lost);
/// right = b ⊕ c = (0, 1, 0), then a ⊕ (0, 1, 0): total conflict, (0, 0, 1), k = 1.
#[test]
fn binary_dempster_chained_through_total_conflict_is_not_associative() {
    let (a, b, c) = (
        Mass::certain(State::Empty),
        Mass::certain(State::Occupied),
        Mass::new(0.5, 0.2, 0.3),
    );
    let left = combine(combine(a, b).mass, c);
    let right = combine(a, combine(b, c).mass);
    assert!(!left.total_conflict);
    assert_quoted(left.mass, [0.5, 0.2, 0.3]);
    assert_eq!(right, TOTAL_CONFLICT);
    assert_differ(left.mass, right.mass);
    // Carrying the flag restores associativity: the combiner agrees with the right side.
    assert_eq!(dempster_of([a, b, c]), TOTAL_CONFLICT);
}

// ---------------------------------------------------------------------------------------
// The distance-weighted rule: well-formedness
// ---------------------------------------------------------------------------------------

/// Every scaling × source combination returns a mass function and a conflict in [0, 1]
/// for one to six sources, and total conflict as the sentinel (so never NaN).
#[test]
fn weighted_rule_returns_a_mass_function() {
    check(sources(), |sources| {
        for weighting in weightings() {
            let c = combine_all(sources.iter().copied(), weighting);
            prop_assert!(c.mass.is_mass_function(1e-12), "{:?}: {:?}", weighting, c);
            prop_assert!((0.0..=1.0).contains(&c.conflict), "{:?}: {:?}", weighting, c);
            if c.total_conflict {
                prop_assert_eq!(c, TOTAL_CONFLICT);
            }
        }
        Ok(())
    });
}

/// The power transform keeps zero masses zero and positive masses positive, so the
/// weighted rule is in total conflict for exactly the same inputs as Dempster's rule.
#[test]
fn weighted_rule_is_in_total_conflict_exactly_when_dempster_is() {
    check(sources(), |sources| {
        let dempster = dempster_of(sources.iter().map(|&(m, _)| m));
        for weighting in weightings() {
            let weighted = combine_all(sources.iter().copied(), weighting);
            prop_assert_eq!(weighted.total_conflict, dempster.total_conflict, "{:?}", weighting);
        }
        Ok(())
    });
}

#[test]
fn weighted_rule_of_no_sources_is_vacuous() {
    for weighting in weightings() {
        let c = combine_all(std::iter::empty(), weighting);
        assert_eq!(c.mass, Mass::VACUOUS, "{weighting:?}");
        assert!(!c.total_conflict);
        assert!(c.conflict.abs() <= CONFLICT_ABSOLUTE);
    }
}

#[test]
fn weighted_two_source_rule_is_commutative() {
    check((source(), source()), |((a, da), (b, db))| {
        for scaling in SCALINGS {
            assert_same_combination(combine_two(a, da, b, db, scaling), combine_two(b, db, a, da, scaling))?;
        }
        Ok(())
    });
}

/// For two sources both ways of extending the rule are the paper's two-source rule, so
/// every two-source answer below holds for both.
#[test]
fn all_at_once_and_pairwise_agree_for_two_sources() {
    check((source(), source()), |(a, b)| {
        for scaling in SCALINGS {
            let two = combine_two(a.0, a.1, b.0, b.1, scaling);
            for sources in [SourceCombination::AllAtOnce, SourceCombination::Pairwise] {
                let all = combine_all([a, b].into_iter(), Weighting { scaling, sources });
                assert_same_combination(all, two)?;
            }
        }
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------
// Open question (a): associativity / source-order independence
// ---------------------------------------------------------------------------------------

/// AllAtOnce computes every weight from the whole set of distances, transforms each source
/// once and combines the results with the associative standard rule, so (unlike Pairwise)
/// the source order does not matter under any scaling.
#[test]
fn all_at_once_is_independent_of_source_order() {
    check(sources_and_permutation(), |(sources, permuted)| {
        for scaling in SCALINGS {
            let weighting = Weighting {
                scaling,
                sources: SourceCombination::AllAtOnce,
            };
            assert_same_combination(
                combine_all(sources.iter().copied(), weighting),
                combine_all(permuted.iter().copied(), weighting),
            )?;
        }
        Ok(())
    });
}

/// The shared counterexample to associativity of the pairwise rule: three sources at
/// 10 m, a = b = (0.64, 0, 0.36) and c = (0, 0.64, 0.36). Returns the two bracketings
/// (a ⊕ b) ⊕ c and a ⊕ (b ⊕ c), each with its accumulated conflict, after checking that
/// the library's pairwise fold of [a, b, c] and of [c, b, a] (= a ⊕ (b ⊕ c) by
/// commutativity) computes exactly these.
fn pairwise_bracketings(scaling: WeightScaling) -> (Combination, Combination) {
    let a = (Mass::new(0.64, 0.0, 0.36), 10.0);
    let b = a;
    let c = (Mass::new(0.0, 0.64, 0.36), 10.0);
    let (ab, d_ab) = pairwise_step(a, b, scaling);
    let (left, _) = pairwise_step((ab.mass, d_ab), c, scaling);
    let (bc, d_bc) = pairwise_step(b, c, scaling);
    let (right, _) = pairwise_step(a, (bc.mass, d_bc), scaling);
    let with_conflict = |inner: Combination, outer: Combination| Combination {
        conflict: 1.0 - (1.0 - inner.conflict) * (1.0 - outer.conflict),
        ..outer
    };
    let (left, right) = (with_conflict(ab, left), with_conflict(bc, right));
    let weighting = Weighting {
        scaling,
        sources: SourceCombination::Pairwise,
    };
    let forward = combine_all([a, b, c].into_iter(), weighting);
    let backward = combine_all([c, b, a].into_iter(), weighting);
    assert_same_combination(forward, left).unwrap();
    assert_same_combination(backward, right).unwrap();
    (left, right)
}

/// SumToOne, three sources at 10 m (see [`pairwise_bracketings`]): weights ½, ½ in the
/// first step and ⅔ (fused pair, 1/d = 0.2) vs ⅓ (single source) in the second.
///
/// (a ⊕ b) ⊕ c = (0.550033, 0.246492, 0.203475), K = 0.399874
/// a ⊕ (b ⊕ c) = (0.637578, 0.198535, 0.163887), K = 0.457102
#[test]
fn pairwise_sum_to_one_is_not_associative() {
    let (left, right) = pairwise_bracketings(WeightScaling::SumToOne);
    assert_quoted(left.mass, [0.550033, 0.246492, 0.203475]);
    assert_quoted(right.mass, [0.637578, 0.198535, 0.163887]);
    assert!((left.conflict - 0.399874).abs() <= QUOTED);
    assert!((right.conflict - 0.457102).abs() <= QUOTED);
    assert_differ(left.mass, right.mass);
}

/// MeanOne, three sources at 10 m (see [`pairwise_bracketings`]): weights 1, 1 in the
/// first step (the standard rule) and 4/3 (fused pair) vs 2/3 (single source) in the
/// second.
///
/// (a ⊕ b) ⊕ c = (0.837006, 0.0969382, 0.0660557), K = 0.551233
/// a ⊕ (b ⊕ c) = (0.682583, 0.216766, 0.100652), K = 0.552085
#[test]
fn pairwise_mean_one_is_not_associative() {
    let (left, right) = pairwise_bracketings(WeightScaling::MeanOne);
    assert_quoted(left.mass, [0.837006, 0.0969382, 0.0660557]);
    assert_quoted(right.mass, [0.682583, 0.216766, 0.100652]);
    assert!((left.conflict - 0.551233).abs() <= QUOTED);
    assert!((right.conflict - 0.552085).abs() <= QUOTED);
    assert_differ(left.mass, right.mass);
}

/// NearestOne, three sources at 10 m (see [`pairwise_bracketings`]): weights 1, 1 in the
/// first step and 1 (fused pair, at 5 m) vs ½ (single source) in the second. By hand:
///
/// a ⊕ b = (0.8704, 0, 0.1296); c^½ = (0, 4/7, 3/7);
/// (a ⊕ b) ⊕ c = (0.8704·3/7, 0.1296·4/7, 0.1296·3/7) / (1 − 0.8704·4/7)
///             = (0.742156, 0.147340, 0.110505)
/// b ⊕ c = (0.2304, 0.2304, 0.1296) / 0.5904; a^½ = (4/7, 0, 3/7);
/// a ⊕ (b ⊕ c) = (0.663677, 0.215247, 0.121076)
///
/// with accumulated conflicts K = 0.497371 and 0.541257.
#[test]
fn pairwise_nearest_one_is_not_associative() {
    let (left, right) = pairwise_bracketings(WeightScaling::NearestOne);
    let k = 0.8704 * 4.0 / 7.0;
    let by_hand = [0.8704 * 3.0 / 7.0, 0.1296 * 4.0 / 7.0, 0.1296 * 3.0 / 7.0].map(|m| m / (1.0 - k));
    assert_quoted(left.mass, by_hand);
    assert_quoted(left.mass, [0.742156, 0.147340, 0.110505]);
    assert_quoted(right.mass, [0.663677, 0.215247, 0.121076]);
    assert!((left.conflict - 0.497371).abs() <= QUOTED);
    assert!((right.conflict - 0.541257).abs() <= QUOTED);
    assert_differ(left.mass, right.mass);
}

// ---------------------------------------------------------------------------------------
// Open question (b): reduction to Dempster's rule at equal distances
// ---------------------------------------------------------------------------------------

/// n sources at one distance, n = 1..=6.
fn sources_at_one_distance() -> impl Strategy<Value = (Vec<Mass>, f64)> {
    (vec(mass(), 1..=6), distance())
}

/// MeanOne with AllAtOnce: every weight is n·(1/d)/(n/d) = 1, up to the rounding of
/// Σ 1/d, so each source keeps its mass and the rule is the standard rule.
#[test]
fn all_at_once_mean_one_reduces_to_dempster_at_equal_distances() {
    reduces_to_dempster(WeightScaling::MeanOne);
}

/// NearestOne with AllAtOnce: every weight is d_min/d = 1 exactly.
#[test]
fn all_at_once_nearest_one_reduces_to_dempster_at_equal_distances() {
    reduces_to_dempster(WeightScaling::NearestOne);
}

fn reduces_to_dempster(scaling: WeightScaling) {
    let weighting = Weighting {
        scaling,
        sources: SourceCombination::AllAtOnce,
    };
    check(sources_at_one_distance(), |(masses, d)| {
        let weighted = combine_all(masses.iter().map(|&m| (m, d)), weighting);
        assert_same_combination(weighted, dempster_of(masses))
    });
}

/// For two sources (the paper's setting, where Pairwise and AllAtOnce coincide) MeanOne
/// and NearestOne give both sources weight 1 at equal distances.
#[test]
fn two_source_rule_reduces_to_dempster_at_equal_distances_under_mean_one_and_nearest_one() {
    check((mass(), mass(), distance()), |(a, b, d)| {
        for scaling in [WeightScaling::MeanOne, WeightScaling::NearestOne] {
            assert_same_combination(combine_two(a, d, b, d, scaling), combine(a, b))?;
            let pairwise = Weighting {
                scaling,
                sources: SourceCombination::Pairwise,
            };
            assert_same_combination(combine_all([(a, d), (b, d)].into_iter(), pairwise), combine(a, b))?;
        }
        Ok(())
    });
}

/// What SumToOne does instead at equal distances: every weight is 1/n, so the result is
/// the standard rule applied to every source flattened by the power 1/n.
#[test]
fn sum_to_one_at_equal_distances_flattens_each_source_by_one_over_n() {
    let weighting = Weighting {
        scaling: WeightScaling::SumToOne,
        sources: SourceCombination::AllAtOnce,
    };
    check(sources_at_one_distance(), |(masses, d)| {
        let n = masses.len() as f64;
        let weighted = combine_all(masses.iter().map(|&m| (m, d)), weighting);
        let flattened = dempster_of(masses.iter().map(|&m| discount(m, 1.0 / n)));
        assert_same_combination(weighted, flattened)
    });
}

/// SumToOne, two sources a = b = (0.64, 0, 0.36) at 10 m, for the two-source rule and
/// both extensions (which coincide for two sources). w = ½, so each source becomes
/// (√0.64, 0, √0.36)/1.4 = (4/7, 0, 3/7) before combining:
///
/// weighted  = (1 − 9/49, 0, 9/49) = (0.816327, 0, 0.183673)
/// Dempster  = (1 − 0.36², 0, 0.36²) = (0.8704, 0, 0.1296)
///
/// The weighted rule is *less* sure than the standard one of what two agreeing sensors
/// at the same distance both report.
#[test]
fn sum_to_one_does_not_reduce_to_dempster_at_equal_distances() {
    let a = Mass::new(0.64, 0.0, 0.36);
    let dempster = combine(a, a);
    assert_quoted(dempster.mass, [0.8704, 0.0, 0.1296]);
    let two = combine_two(a, 10.0, a, 10.0, WeightScaling::SumToOne);
    assert_quoted(two.mass, [40.0 / 49.0, 0.0, 9.0 / 49.0]);
    assert_quoted(two.mass, [0.816327, 0.0, 0.183673]);
    assert_differ(two.mass, dempster.mass);
    for sources in [SourceCombination::AllAtOnce, SourceCombination::Pairwise] {
        let weighting = Weighting {
            scaling: WeightScaling::SumToOne,
            sources,
        };
        let all = combine_all([(a, 10.0), (a, 10.0)].into_iter(), weighting);
        assert_quoted(all.mass, [0.816327, 0.0, 0.183673]);
    }
    // Pairwise with three sources (see `pairwise_of_two_vacuous_then`): the second step
    // weighs the fused pair ⅔ and the third source ⅓, so c becomes c^⅓ normalised.
    let pairwise = pairwise_of_two_vacuous_then(a, WeightScaling::SumToOne);
    assert_quoted(pairwise, [0.547801, 0.0, 0.452199]);
    assert_differ(pairwise, a);
}

/// The pairwise fold of [Vacuous, Vacuous, c] with every source at 10 m, and the standard
/// rule's answer c. The first step fuses two ignorant sources into an ignorant one that
/// stands at 5 m (1/d = 0.2), so in the second step c (at 10 m) is outweighed.
fn pairwise_of_two_vacuous_then(c: Mass, scaling: WeightScaling) -> Mass {
    let weighting = Weighting {
        scaling,
        sources: SourceCombination::Pairwise,
    };
    let sources = [(Mass::VACUOUS, 10.0), (Mass::VACUOUS, 10.0), (c, 10.0)];
    let pairwise = combine_all(sources.into_iter(), weighting);
    let dempster = dempster_of(sources.map(|(m, _)| m));
    assert_quoted(dempster.mass, c.to_array());
    pairwise.mass
}

/// MeanOne with Pairwise, three sources at 10 m: the second step weighs the fused pair
/// 2·0.2/0.3 = 4/3 and the third source 2·0.1/0.3 = 2/3. With [Vacuous, Vacuous, c],
/// c = (0.64, 0, 0.36):
///
/// pairwise = c^⅔ normalised = (0.594735, 0, 0.405265)
/// Dempster = c              = (0.64, 0, 0.36)
#[test]
fn pairwise_mean_one_does_not_reduce_to_dempster_at_equal_distances() {
    let c = Mass::new(0.64, 0.0, 0.36);
    let pairwise = pairwise_of_two_vacuous_then(c, WeightScaling::MeanOne);
    assert_quoted(pairwise, [0.594735, 0.0, 0.405265]);
    assert_differ(pairwise, c);
}

/// NearestOne with Pairwise, three sources at 10 m: the second step weighs the fused
/// pair (at 5 m) 1 and the third source 5/10 = ½. With [Vacuous, Vacuous, c],
/// c = (0.64, 0, 0.36):
///
/// pairwise = (√0.64, 0, √0.36)/1.4 = (4/7, 0, 3/7) = (0.571429, 0, 0.428571)
/// Dempster = c                                      = (0.64, 0, 0.36)
///
/// The same sources in the order [c, Vacuous, Vacuous] give c. Nor is it about vacuous
/// sources: [c, c, c] gives (0.944457, 0, 0.0555429), Unknown 0.1296·3/7, instead of
/// (0.953344, 0, 0.046656), Unknown 0.36³.
#[test]
fn pairwise_nearest_one_does_not_reduce_to_dempster_at_equal_distances() {
    let c = Mass::new(0.64, 0.0, 0.36);
    let pairwise = pairwise_of_two_vacuous_then(c, WeightScaling::NearestOne);
    assert_quoted(pairwise, [4.0 / 7.0, 0.0, 3.0 / 7.0]);
    assert_quoted(pairwise, [0.571429, 0.0, 0.428571]);
    assert_differ(pairwise, c);

    let weighting = Weighting {
        scaling: WeightScaling::NearestOne,
        sources: SourceCombination::Pairwise,
    };
    // The same sources in the order [c, Vacuous, Vacuous] do give c: c enters with weight
    // 1, and the fused pair (at 5 m) keeps weight 1 against each later source.
    let c_first = [(c, 10.0), (Mass::VACUOUS, 10.0), (Mass::VACUOUS, 10.0)];
    assert_quoted(combine_all(c_first.into_iter(), weighting).mass, c.to_array());
    let three = combine_all([(c, 10.0); 3].into_iter(), weighting);
    let dempster = dempster_of([c; 3]);
    assert_quoted(three.mass, [0.944457, 0.0, 0.0555429]);
    assert_quoted(dempster.mass, [0.953344, 0.0, 0.046656]);
    assert_differ(three.mass, dempster.mass);
}

// ---------------------------------------------------------------------------------------
// A consequence: the vacuous mass is not neutral in the weighted rule
// ---------------------------------------------------------------------------------------

/// An ignorant source still takes weight, so a nearer vacuous source flattens the
/// informative one: a = (0.64, 0, 0.36) at 20 m with the vacuous mass at 10 m gives a's
/// weight as ⅓ (SumToOne), ⅔ (MeanOne), ½ (NearestOne) and the result a^w normalised:
///
/// SumToOne   (0.547801, 0, 0.452199)
/// MeanOne    (0.594735, 0, 0.405265)
/// NearestOne (0.571429, 0, 0.428571)
///
/// where Dempster's rule returns a. (Under NearestOne a vacuous source that is *not* the
/// nearest is neutral: see the next test.)
#[test]
fn vacuous_is_not_the_identity_of_the_weighted_rule() {
    let a = Mass::new(0.64, 0.0, 0.36);
    for (scaling, quoted) in [
        (WeightScaling::SumToOne, [0.547801, 0.0, 0.452199]),
        (WeightScaling::MeanOne, [0.594735, 0.0, 0.405265]),
        (WeightScaling::NearestOne, [0.571429, 0.0, 0.428571]),
    ] {
        let fused = combine_two(a, 20.0, Mass::VACUOUS, 10.0, scaling);
        assert_quoted(fused.mass, quoted);
        assert_differ(fused.mass, a);
    }
}

/// Under NearestOne with AllAtOnce a vacuous source no nearer than the nearest other
/// source gets weight ≤ 1 (and stays vacuous) and leaves every other weight d_min/dᵢ as
/// it was, so it changes nothing.
#[test]
fn nearest_one_all_at_once_ignores_a_vacuous_source_that_is_not_the_nearest() {
    let weighting = Weighting {
        scaling: WeightScaling::NearestOne,
        sources: SourceCombination::AllAtOnce,
    };
    let inputs = (sources(), 0u32..=3000, any::<prop::sample::Index>());
    check(inputs, |(sources, farther_decimetres, at)| {
        let nearest = sources.iter().map(|&(_, d)| d).fold(f64::INFINITY, f64::min);
        let vacuous = (Mass::VACUOUS, nearest + f64::from(farther_decimetres) / 10.0);
        let mut with_vacuous = sources.clone();
        with_vacuous.insert(at.index(sources.len() + 1), vacuous);
        assert_same_combination(
            combine_all(sources.into_iter(), weighting),
            combine_all(with_vacuous.into_iter(), weighting),
        )
    });
}

// ---------------------------------------------------------------------------------------
// Regressions
// ---------------------------------------------------------------------------------------

/// Regression (#2): `a` is a mass function (its masses sum to exactly 1.0 in f64)
/// whose Unknown mass is subnormal. Against certain Occupy the only agreeing product
/// is a.unknown·1 = 1e-310. `normalise` used to scale by 1/1e-310, which overflows to
/// +∞, and returned (NaN, +∞, NaN) with `total_conflict == false`; it now divides by
/// the agreement and returns (0, 1, 0).
#[test]
fn dempster_stays_finite_when_the_agreement_is_subnormal() {
    let a = Mass::new(1.0, 0.0, 1e-310);
    assert!(a.is_mass_function(0.0));
    let fused = combine(a, Mass::certain(State::Occupied));
    assert!(fused.mass.is_mass_function(1e-12), "{fused:?}");
    assert_eq!(fused.mass, Mass::certain(State::Occupied));
    assert!(!fused.total_conflict);
}
