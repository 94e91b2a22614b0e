//! How well the fused occupancy probabilities are calibrated: the Brier score
//! and a reliability table of the fused cells a world judges.
//!
//! The judged probability p is the one the report pictures: Bayes's fused
//! probability, and for the evidential rules the pignistic probability
//! BetP(occupied) = m(O) + m(Θ)/2 of the fused mass. It is compared with the
//! truth o (1 for a cell occupied by a road user that does not cooperate, 0 for
//! a free cell) at every measured step, over the cells the fused grid holds: the
//! counted cells some received observation covers. Cells no one observed carry
//! no fused probability and are left out, as are the cooperating agents' own
//! footprints (self-report: no sensor had to find them, as recall leaves them
//! out).

use serde::{Deserialize, Serialize};

/// Equal bins of probability in the reliability table.
pub const RELIABILITY_BINS: usize = 10;

/// How close below a bin's lower edge a probability may fall and still count
/// in the bin. The inverse sensor model's probabilities sit on edges (0.3,
/// 0.7, and 0.5 where two observations disagree), and the fused value comes
/// out a rounding error either side of them: without it one probability would
/// split between two bins by the order of its sums (measured on the
/// roundabout: 431 cell-steps at p = 0.3 − 3·10⁻¹⁶ in the bin below the rest).
const EDGE_TOLERANCE: f64 = 1e-9;

/// The calibration tallies of a run (or of a chunk of fused cells): sums, in
/// the order the cells are recorded and merged.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Calibration {
    /// Cell-steps judged.
    pub cells: u64,
    /// Σ (p − o)² over them.
    pub squared_error_sum: f64,
    /// The reliability table: bin i holds p in [i/10, (i+1)/10) (its lower
    /// edge less 10⁻⁹, for rounding errors), the last bin p = 1 as well.
    /// Boxed: an outcome of every kind stays small.
    pub bins: Box<[ReliabilityBin; RELIABILITY_BINS]>,
}

/// The fused cell-steps whose probability falls in one bin.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ReliabilityBin {
    /// Cell-steps in the bin.
    pub cells: u64,
    /// Σ p over them.
    pub probability_sum: f64,
    /// Of them, truly occupied (o = 1).
    pub occupied: u64,
}

impl ReliabilityBin {
    /// The mean fused probability; `None` for an empty bin.
    pub fn mean_probability(&self) -> Option<f64> {
        (self.cells > 0).then(|| self.probability_sum / self.cells as f64)
    }

    /// The observed frequency of o = 1; `None` for an empty bin.
    pub fn observed_frequency(&self) -> Option<f64> {
        (self.cells > 0).then(|| self.occupied as f64 / self.cells as f64)
    }
}

impl Calibration {
    /// Records one fused cell: its probability `p` (0–1) and its truth.
    #[inline]
    pub(crate) fn record(&mut self, p: f64, occupied: bool) {
        let o = if occupied { 1.0 } else { 0.0 };
        self.cells += 1;
        self.squared_error_sum += (p - o) * (p - o);
        // A NaN probability lands in the first bin (`as` saturates); the audit
        // reports non-finite masses apart.
        let bin = ((p * RELIABILITY_BINS as f64 + EDGE_TOLERANCE) as usize).min(RELIABILITY_BINS - 1);
        let bin = &mut self.bins[bin];
        bin.cells += 1;
        bin.probability_sum += p;
        bin.occupied += u64::from(occupied);
    }

    /// Adds `other`'s tallies; call in a fixed order for reproducible sums.
    pub(crate) fn merge(&mut self, other: &Calibration) {
        self.cells += other.cells;
        self.squared_error_sum += other.squared_error_sum;
        for (bin, other) in self.bins.iter_mut().zip(other.bins.iter()) {
            bin.cells += other.cells;
            bin.probability_sum += other.probability_sum;
            bin.occupied += other.occupied;
        }
    }

    /// The Brier score, mean (p − o)² (0 best, 1 worst); `None` when no cell
    /// was judged.
    pub fn brier_score(&self) -> Option<f64> {
        (self.cells > 0).then(|| self.squared_error_sum / self.cells as f64)
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// Four cells by hand: p = 0.9, 0.9, 0.1, 0.6 against o = 1, 0, 0, 1.
    #[test]
    fn brier_score_and_bins_by_hand() {
        let mut calibration = Calibration::default();
        for (p, o) in [(0.9, true), (0.9, false), (0.1, false), (0.6, true)] {
            calibration.record(p, o);
        }
        assert_eq!(calibration.cells, 4);
        // (0.01 + 0.81 + 0.01 + 0.16) / 4.
        assert_relative_eq!(calibration.brier_score().unwrap(), 0.2475, epsilon = 1e-12);
        let filled: Vec<(usize, u64, f64, f64)> = calibration
            .bins
            .iter()
            .enumerate()
            .filter(|(_, b)| b.cells > 0)
            .map(|(i, b)| {
                (
                    i,
                    b.cells,
                    b.mean_probability().unwrap(),
                    b.observed_frequency().unwrap(),
                )
            })
            .collect();
        assert_eq!(filled.len(), 3);
        assert_eq!((filled[0].0, filled[0].1), (1, 1));
        assert_relative_eq!(filled[0].2, 0.1);
        assert_relative_eq!(filled[0].3, 0.0);
        assert_eq!((filled[1].0, filled[1].1), (6, 1));
        assert_relative_eq!(filled[1].2, 0.6);
        assert_relative_eq!(filled[1].3, 1.0);
        assert_eq!((filled[2].0, filled[2].1), (9, 2));
        assert_relative_eq!(filled[2].2, 0.9);
        assert_relative_eq!(filled[2].3, 0.5);
    }

    /// Nothing judged: no score, n = 0, every bin empty.
    #[test]
    fn empty_population_has_no_value() {
        let calibration = Calibration::default();
        assert_eq!((calibration.brier_score(), calibration.cells), (None, 0));
        assert!(calibration.bins.iter().all(|b| b.mean_probability().is_none()));
    }

    /// A probability a rounding error below an edge counts in the bin above it,
    /// as the edge itself does.
    #[test]
    fn a_rounding_error_below_an_edge_stays_in_the_edge_s_bin() {
        let mut calibration = Calibration::default();
        calibration.record(0.3, false);
        calibration.record(0.299_999_999_999_999_66, false);
        calibration.record(0.299, false);
        assert_eq!((calibration.bins[2].cells, calibration.bins[3].cells), (1, 2));
    }

    /// p = 1 falls in the last bin, p = 0 in the first; merging two halves gives
    /// the whole.
    #[test]
    fn bin_edges_and_merge() {
        let (mut a, mut b, mut whole) = (Calibration::default(), Calibration::default(), Calibration::default());
        a.record(1.0, true);
        b.record(0.0, false);
        whole.record(1.0, true);
        whole.record(0.0, false);
        assert_eq!((a.bins[9].cells, b.bins[0].cells), (1, 1));
        a.merge(&b);
        assert_eq!(a, whole);
        assert_eq!(a.brier_score(), Some(0.0));
    }
}
