//! The decision rule of seed 001 (§IV-C).

use super::mass::{Mass, State};

/// Decides a cell: the state of the largest mass p_max when p_max − p_others ≥ θ
/// (p_others the sum of the other two), `None` (below threshold) otherwise.
/// Ties for the largest mass go to the first of Empty, Occupy, Unknown; they can
/// only decide when θ ≤ 0.
#[inline]
pub fn decide(mass: Mass, threshold: f64) -> Option<State> {
    let masses = mass.to_array();
    let (best, &p_max) = masses
        .iter()
        .enumerate()
        .fold((0, &masses[0]), |acc, (i, m)| if *m > *acc.1 { (i, m) } else { acc });
    let p_others: f64 = masses.iter().sum::<f64>() - p_max;
    (p_max - p_others >= threshold).then_some(State::ALL[best])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decides_at_and_above_the_threshold() {
        // 0.9 − 0.1 = 0.8 ≥ 0.8.
        assert_eq!(decide(Mass::new(0.9, 0.05, 0.05), 0.8), Some(State::Empty));
        assert_eq!(decide(Mass::new(0.05, 0.95, 0.0), 0.8), Some(State::Occupied));
        assert_eq!(decide(Mass::VACUOUS, 0.8), Some(State::Unknown));
    }

    #[test]
    fn stays_undecided_below_the_threshold() {
        // 0.85 − 0.15 = 0.7 < 0.8.
        assert_eq!(decide(Mass::new(0.85, 0.1, 0.05), 0.8), None);
        assert_eq!(decide(Mass::new(0.5, 0.5, 0.0), 0.1), None);
    }

    #[test]
    fn ties_go_to_the_first_state_when_theta_allows() {
        assert_eq!(decide(Mass::new(0.5, 0.5, 0.0), 0.0), Some(State::Empty));
    }
}
