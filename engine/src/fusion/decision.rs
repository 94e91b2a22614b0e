//! The decision rule of seed 001, in both of the paper's statements.

use sightline_dsl::{Decision, DecisionRule};

use super::mass::{Mass, State};

/// How near the threshold a cell's margin or p_max must be to be at it
/// (1e-9): a mass that is θ's exactly in real arithmetic comes out of the
/// fusion a few ulps off it (0.7 − (1 − 0.7) is 0.3999999999999999), and
/// the boundary is the rule's own (`margin` decides at it, `exceeds` does
/// not), not whichever way the rounding went.
const AT_THRESHOLD: f64 = 1e-9;

/// Decides a cell: the state of the largest mass p_max when `decision`'s rule
/// holds (`margin`: p_max − p_others ≥ θ, p_others the sum of the other two;
/// `exceeds`: p_max > θ; a value within 1e-9 of θ is at it), `None` (below
/// threshold) otherwise. Ties for the largest mass go to the first of Empty,
/// Occupy, Unknown.
#[inline]
pub fn decide(mass: Mass, decision: Decision) -> Option<State> {
    let masses = mass.to_array();
    let (best, &p_max) = masses
        .iter()
        .enumerate()
        .fold((0, &masses[0]), |acc, (i, m)| if *m > *acc.1 { (i, m) } else { acc });
    let decided = match decision.rule {
        DecisionRule::Margin => p_max - (masses.iter().sum::<f64>() - p_max) >= decision.threshold - AT_THRESHOLD,
        DecisionRule::Exceeds => p_max > decision.threshold + AT_THRESHOLD,
    };
    decided.then_some(State::ALL[best])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn margin(threshold: f64) -> Decision {
        Decision {
            rule: DecisionRule::Margin,
            threshold,
        }
    }

    fn exceeds(threshold: f64) -> Decision {
        Decision {
            rule: DecisionRule::Exceeds,
            threshold,
        }
    }

    #[test]
    fn margin_decides_at_and_above_the_threshold() {
        // 0.9 − (0.05 + 0.05) = 0.8 ≥ 0.8: the boundary decides.
        assert_eq!(decide(Mass::new(0.9, 0.05, 0.05), margin(0.8)), Some(State::Empty));
        // 0.95 − 0.05 = 0.9.
        assert_eq!(decide(Mass::new(0.05, 0.95, 0.0), margin(0.8)), Some(State::Occupied));
        assert_eq!(decide(Mass::VACUOUS, margin(0.8)), Some(State::Unknown));
    }

    #[test]
    fn margin_stays_undecided_below_the_threshold() {
        // 0.85 − 0.15 = 0.7 < 0.8, though 0.85 exceeds 0.8.
        assert_eq!(decide(Mass::new(0.85, 0.1, 0.05), margin(0.8)), None);
        // 0.5 − 0.5 = 0 < 0.1.
        assert_eq!(decide(Mass::new(0.5, 0.5, 0.0), margin(0.1)), None);
    }

    #[test]
    fn exceeds_decides_strictly_above_the_threshold() {
        // 0.85 > 0.8, where the margin (0.7) does not reach 0.8.
        assert_eq!(decide(Mass::new(0.85, 0.1, 0.05), exceeds(0.8)), Some(State::Empty));
        // 0.81 > 0.8 on Occupy.
        assert_eq!(decide(Mass::new(0.04, 0.81, 0.15), exceeds(0.8)), Some(State::Occupied));
        // The boundary: 0.75 does not exceed 0.75 (0.75 and 0.25 are exact in binary).
        assert_eq!(decide(Mass::new(0.0, 0.25, 0.75), exceeds(0.75)), None);
        assert_eq!(decide(Mass::new(0.0, 0.25, 0.75), exceeds(0.5)), Some(State::Unknown));
        // (0.5, 0.3, 0.2): no component exceeds 0.8.
        assert_eq!(decide(Mass::new(0.5, 0.3, 0.2), exceeds(0.8)), None);
    }

    #[test]
    fn the_readings_agree_where_the_margin_threshold_is_twice_the_other_less_one() {
        // With masses summing to 1, p_max − p_others ≥ θ ⇔ p_max ≥ (1 + θ)/2:
        // margin at 0.5 and exceeds at 0.75 differ only at p_max = 0.75 exactly.
        for (mass, decided) in [
            (Mass::new(0.75, 0.25, 0.0), true), // 0.75 − 0.25 = 0.5 ≥ 0.5; 0.75 ≯ 0.75.
            (Mass::new(0.875, 0.125, 0.0), true),
            (Mass::new(0.625, 0.25, 0.125), false),
        ] {
            assert_eq!(decide(mass, margin(0.5)).is_some(), decided, "{mass:?}");
        }
        assert_eq!(decide(Mass::new(0.75, 0.25, 0.0), exceeds(0.75)), None);
        assert_eq!(decide(Mass::new(0.875, 0.125, 0.0), exceeds(0.75)), Some(State::Empty));
        assert_eq!(decide(Mass::new(0.625, 0.25, 0.125), exceeds(0.75)), None);
    }

    /// Masses that meet θ in real arithmetic and miss it by rounding, as the
    /// fusion computes them (the outside audit's cases), are at θ.
    #[test]
    fn a_mass_at_the_threshold_but_for_rounding_is_at_it() {
        use crate::fusion::{bayes, dempster};
        let bayes = |p: f64| {
            let fused = bayes::fuse(std::iter::once(Mass::new(1.0 - p, p, 0.0))).probability;
            Mass::new(1.0 - fused, fused, 0.0)
        };
        // Bayes, one detection of 0.7 at θ = 0.4: 0.7 − 0.3 = 0.4.
        let one = bayes(0.7);
        assert!(one.occupied - one.empty < 0.4, "the rounding this guards against");
        assert_eq!(decide(one, margin(0.4)), Some(State::Occupied));
        // Bayes, 0.9 at the default θ = 0.8: p_max ≥ (1 + θ)/2 = 0.9.
        let default = bayes(0.9);
        assert!(
            default.occupied - default.empty < 0.8,
            "the rounding this guards against"
        );
        assert_eq!(decide(default, margin(0.8)), Some(State::Occupied));
        // Two agreeing detections (0, 0.4, 0.6) under Dempster's rule:
        // (0, 0.64, 0.36), a margin of 0.28.
        let detection = Mass::new(0.0, 0.4, 0.6);
        let two = dempster::combine(detection, detection).mass;
        assert_eq!(decide(two, margin(0.28)), Some(State::Occupied));
        // `exceeds` is strict: p_max does not exceed its own value.
        assert_eq!(decide(default, exceeds(0.9)), None);
        assert_eq!(decide(bayes(0.7), exceeds(0.7)), None);
        // A margin clearly under θ stays undecided.
        assert_eq!(decide(one, margin(0.4 + 1e-6)), None);
    }

    #[test]
    fn ties_go_to_the_first_state_when_theta_allows() {
        assert_eq!(decide(Mass::new(0.5, 0.5, 0.0), margin(0.0)), Some(State::Empty));
        assert_eq!(
            decide(Mass::new(0.25, 0.375, 0.375), exceeds(0.3)),
            Some(State::Occupied)
        );
    }
}
