//! Bayesian occupancy fusion in log-odds, the comparison method (seed 000's grid).
//!
//! Each source's mass vector becomes an occupancy probability by the pignistic
//! transform p = m(O) + m(Θ)/2 (Smets), clamped to [ε, 1 − ε] with
//! ε = [`PROBABILITY_CLAMP`] so a certain source cannot make the log-odds
//! infinite. Sources are independent measurements with a uniform prior, so the
//! fused log-odds is their sum. The cell's uncertainty is the binary entropy of
//! the fused probability in bits (0 certain, 1 at p = ½).

use super::mass::Mass;
use crate::idealisation::Idealisation;

/// Bayes multiplies independent likelihoods.
pub(crate) const INDEPENDENT_MEASUREMENTS: Idealisation = Idealisation {
    id: "fusion.bayes-independent",
    text: "Bayesian fusion treats the sources as independent measurements with a uniform prior (fused log-odds \
           are their sum): sources that share an error corroborate each other.",
};

/// Per-source probabilities are clamped to [ε, 1 − ε] with this ε.
pub const PROBABILITY_CLAMP: f64 = 1e-6;

/// A fused Bayesian cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Occupancy {
    /// P(occupied).
    pub probability: f64,
    /// Binary entropy of `probability`, bits (0–1).
    pub uncertainty: f64,
}

/// The pignistic occupancy probability of a mass vector.
#[inline]
pub fn pignistic(mass: Mass) -> f64 {
    mass.occupied + 0.5 * mass.unknown
}

/// ln(p / (1 − p)) of a clamped probability.
#[inline]
fn log_odds(probability: f64) -> f64 {
    let p = probability.clamp(PROBABILITY_CLAMP, 1.0 - PROBABILITY_CLAMP);
    (p / (1.0 - p)).ln()
}

/// Fuses sources by summing their log-odds.
pub fn fuse(sources: impl Iterator<Item = Mass>) -> Occupancy {
    let log_odds: f64 = sources.map(|m| log_odds(pignistic(m))).sum();
    let probability = 1.0 / (1.0 + (-log_odds).exp());
    Occupancy {
        probability,
        uncertainty: entropy(probability),
    }
}

/// Binary entropy in bits, with 0·log 0 = 0.
fn entropy(p: f64) -> f64 {
    let term = |q: f64| if q > 0.0 { -q * q.log2() } else { 0.0 };
    term(p) + term(1.0 - p)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// Two sources at p = 0.8 each: log-odds ln 4 + ln 4 = ln 16, p = 16/17.
    #[test]
    fn log_odds_add() {
        let m = Mass::new(0.2, 0.8, 0.0);
        let fused = fuse([m, m].into_iter());
        assert_relative_eq!(fused.probability, 16.0 / 17.0, epsilon = 1e-12);
    }

    #[test]
    fn unknown_mass_counts_half() {
        assert_relative_eq!(pignistic(Mass::new(0.2, 0.3, 0.5)), 0.55, epsilon = 1e-15);
        let fused = fuse([Mass::VACUOUS].into_iter());
        assert_relative_eq!(fused.probability, 0.5, epsilon = 1e-15);
        assert_relative_eq!(fused.uncertainty, 1.0, epsilon = 1e-15);
    }

    #[test]
    fn certain_sources_stay_finite() {
        // Three clamped sources give log-odds 3·ln(10⁶) ≈ 41; σ(41) rounds to 1.
        let fused = fuse([Mass::new(0.0, 1.0, 0.0); 3].into_iter());
        assert!(fused.probability.is_finite() && (0.0..=1.0).contains(&fused.probability));
        assert!(fused.uncertainty.is_finite() && fused.uncertainty >= 0.0);
    }
}
