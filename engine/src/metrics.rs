//! What a field run measures, and the tallies it is computed from; the metric
//! types every world shares (conflict, the mass audit, a signal over time).
//!
//! Every cell falls in exactly one outcome: decided correctly, false alarm
//! (decided Occupy, truly empty), missed detection (decided Empty, truly
//! occupied), decided Unknown, below threshold (no decision), or unobserved (no
//! sensor in range). Tallies are kept per grid row and merged in row order, so
//! sums of floating-point values do not depend on the thread count.

use serde::{Deserialize, Serialize};
use sightline_dsl::{Decision, Metric};

use crate::fusion::{Estimate, State, decide};

/// A signal over a run: (time in seconds, value) at the steps it is defined,
/// in time order (a world's per-step recall, a semantic world's time to
/// conflict).
pub type Series = Vec<(f64, f64)>;

/// Everything measured at one sweep point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldOutcome {
    /// Whole-grid metrics.
    pub metrics: FieldMetrics,
    /// The same decisions split by distance to the nearest sensor.
    pub bands: Vec<BandMetrics>,
    /// The mass-function audit of every fused cell.
    pub audit: MassAudit,
    /// How many sensors observe each cell.
    pub coverage: Coverage,
}

/// Whole-grid metrics of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldMetrics {
    /// Cells in the grid.
    pub cells: u64,
    /// Cells decided correctly.
    pub correct: u64,
    /// Cells with no decision.
    pub below_threshold: u64,
    /// Cells decided Occupy that are truly empty.
    pub false_alarms: u64,
    /// Cells decided Empty that are truly occupied.
    pub missed_detections: u64,
    /// Cells decided Unknown.
    pub decided_unknown: u64,
    /// Cells no sensor observes.
    pub unobserved: u64,
    /// Mean uncertainty over observed cells (`None` when no cell is observed).
    pub mean_uncertainty: Option<f64>,
    /// Conflict statistics (`None` for non-evidential methods).
    pub conflict: Option<ConflictMetrics>,
}

/// The conflict signal of an evidential run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConflictMetrics {
    /// Mean conflict K over observed cells (`None` when no cell is observed).
    pub mean: Option<f64>,
    /// Largest conflict K of any cell.
    pub max: f64,
    /// Cells in total conflict (K = 1).
    pub total_conflict_cells: u64,
    /// Cells fused with the distance-weighted rule.
    pub weighted_cells: u64,
}

impl ConflictMetrics {
    /// The value of a conflict `metric`; `None` for another metric and where
    /// no cell was fused (the maximum and the counts over no cell are no
    /// figures, not 0).
    pub fn value(&self, metric: Metric) -> Option<f64> {
        let mean = self.mean?;
        match metric {
            Metric::MeanConflict => Some(mean),
            Metric::MaxConflict => Some(self.max),
            Metric::TotalConflictCells => Some(self.total_conflict_cells as f64),
            Metric::WeightedCells => Some(self.weighted_cells as f64),
            _ => None,
        }
    }
}

impl FieldMetrics {
    /// The value of `metric`, or `None` where it is not defined for this run
    /// (its population, [`Self::sample_size`], empty included).
    pub fn value(&self, metric: Metric) -> Option<f64> {
        if self.sample_size(metric)? == 0 {
            return None;
        }
        let observed = (self.cells - self.unobserved) as f64;
        let confident_errors = (self.false_alarms + self.missed_detections) as f64;
        Some(match metric {
            Metric::Accuracy => self.correct as f64 / self.cells as f64,
            Metric::BelowThreshold => self.below_threshold as f64,
            Metric::BelowThresholdFraction => self.below_threshold as f64 / observed,
            Metric::FalseAlarms => self.false_alarms as f64,
            Metric::MissedDetections => self.missed_detections as f64,
            Metric::ConfidentErrors => confident_errors,
            Metric::ConfidentErrorRate => confident_errors / observed,
            Metric::DecidedUnknown => self.decided_unknown as f64,
            Metric::Unobserved => self.unobserved as f64,
            Metric::MeanUncertainty => self.mean_uncertainty?,
            Metric::MeanConflict | Metric::MaxConflict | Metric::TotalConflictCells | Metric::WeightedCells => {
                self.conflict.as_ref()?.value(metric)?
            }
            _ => return None,
        })
    }

    /// The number of cells `metric` is computed over ([`Metric::population`]),
    /// or `None` where this run does not measure it. A decision's errors are
    /// over the observed cells: an unobserved cell is not decided, so it can
    /// be no error, and a grid no sensor observes judges nothing.
    pub fn sample_size(&self, metric: Metric) -> Option<u64> {
        let observed = self.cells - self.unobserved;
        match metric {
            Metric::MeanConflict | Metric::MaxConflict | Metric::TotalConflictCells | Metric::WeightedCells => {
                self.conflict.as_ref().map(|_| observed)
            }
            m if m.over_fused_cells() => Some(observed),
            m if m.in_field() => Some(self.cells),
            _ => None,
        }
    }
}

/// Decisions among the cells whose nearest sensor lies in [`from`, `to`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BandMetrics {
    /// Lower edge, metres.
    pub from: f64,
    /// Upper edge, metres (`None`: unbounded).
    pub to: Option<f64>,
    /// Cells in the band.
    pub cells: u64,
    /// Share decided correctly (`None` for an empty band).
    pub accuracy: Option<f64>,
    /// Cells with no decision.
    pub below_threshold: u64,
    /// False alarms.
    pub false_alarms: u64,
    /// Missed detections.
    pub missed_detections: u64,
    /// Mean conflict K over the band's observed cells (evidential methods only).
    pub mean_conflict: Option<f64>,
}

/// Extremes of the fused masses, for the mass-function invariant. For `bayes`
/// the audited vector is (1 − p, p, 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MassAudit {
    /// Fused cells audited.
    pub cells: u64,
    /// Cells with a NaN or infinite mass.
    pub non_finite: u64,
    /// Smallest finite mass of any cell (`None` when no cell was fused).
    pub min_mass: Option<f64>,
    /// Largest finite mass of any cell.
    pub max_mass: Option<f64>,
    /// Largest |Σ masses − 1| of any finite cell.
    pub max_sum_error: f64,
}

/// Sensors per cell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Coverage {
    /// Number of sensors.
    pub sensors: usize,
    /// Fewest sensors observing a cell.
    pub min_sources: usize,
    /// Most sensors observing a cell.
    pub max_sources: usize,
    /// Mean sensors per cell.
    pub mean_sources: f64,
}

/// Counts for one band.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct BandTally {
    cells: u64,
    observed: u64,
    conflict_sum: f64,
    correct: u64,
    below: u64,
    false_alarms: u64,
    missed: u64,
}

/// Running statistics of fused estimates: uncertainty, conflict, and the
/// mass-function audit. Shared by the field and world tallies.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EstimateTally {
    fused: u64,
    uncertainty_sum: f64,
    conflict_sum: f64,
    conflict_max: f64,
    total_conflict: u64,
    weighted: u64,
    non_finite: u64,
    min_mass: f64,
    max_mass: f64,
    max_sum_error: f64,
}

impl Default for EstimateTally {
    fn default() -> Self {
        Self {
            fused: 0,
            uncertainty_sum: 0.0,
            conflict_sum: 0.0,
            conflict_max: 0.0,
            total_conflict: 0,
            weighted: 0,
            non_finite: 0,
            min_mass: f64::INFINITY,
            max_mass: f64::NEG_INFINITY,
            max_sum_error: 0.0,
        }
    }
}

impl EstimateTally {
    /// Records one fused estimate.
    #[inline]
    pub(crate) fn record(&mut self, estimate: &Estimate) {
        self.fused += 1;
        self.uncertainty_sum += estimate.uncertainty();
        if let Estimate::Evidential { combination, weighted } = estimate {
            self.conflict_sum += combination.conflict;
            self.conflict_max = self.conflict_max.max(combination.conflict);
            self.total_conflict += u64::from(combination.total_conflict);
            self.weighted += u64::from(*weighted);
        }
        let mass = estimate.decision_mass();
        let masses = mass.to_array();
        if masses.iter().all(|m| m.is_finite()) {
            for m in masses {
                self.min_mass = self.min_mass.min(m);
                self.max_mass = self.max_mass.max(m);
            }
            self.max_sum_error = self.max_sum_error.max((mass.total() - 1.0).abs());
        } else {
            self.non_finite += 1;
        }
    }

    /// Adds `other`'s statistics; call in a fixed order for reproducible sums.
    pub(crate) fn merge(&mut self, other: &EstimateTally) {
        self.fused += other.fused;
        self.uncertainty_sum += other.uncertainty_sum;
        self.conflict_sum += other.conflict_sum;
        self.conflict_max = self.conflict_max.max(other.conflict_max);
        self.total_conflict += other.total_conflict;
        self.weighted += other.weighted;
        self.non_finite += other.non_finite;
        self.min_mass = self.min_mass.min(other.min_mass);
        self.max_mass = self.max_mass.max(other.max_mass);
        self.max_sum_error = self.max_sum_error.max(other.max_sum_error);
    }

    /// Mean uncertainty, conflict statistics (for evidential methods) and the audit.
    pub(crate) fn finish(&self, evidential: bool) -> (Option<f64>, Option<ConflictMetrics>, MassAudit) {
        let mean = |sum: f64| (self.fused > 0).then(|| sum / self.fused as f64);
        let fused = self.fused > 0;
        (
            mean(self.uncertainty_sum),
            evidential.then(|| ConflictMetrics {
                mean: mean(self.conflict_sum),
                max: self.conflict_max,
                total_conflict_cells: self.total_conflict,
                weighted_cells: self.weighted,
            }),
            MassAudit {
                cells: self.fused,
                non_finite: self.non_finite,
                min_mass: (fused && self.min_mass.is_finite()).then_some(self.min_mass),
                max_mass: (fused && self.max_mass.is_finite()).then_some(self.max_mass),
                max_sum_error: self.max_sum_error,
            },
        )
    }
}

/// Running counts of one method over part of the grid.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tally {
    cells: u64,
    correct: u64,
    below: u64,
    false_alarms: u64,
    missed: u64,
    unknown: u64,
    unobserved: u64,
    estimates: EstimateTally,
    bands: Vec<BandTally>,
}

impl Tally {
    pub(crate) fn new(bands: usize) -> Self {
        Self {
            cells: 0,
            correct: 0,
            below: 0,
            false_alarms: 0,
            missed: 0,
            unknown: 0,
            unobserved: 0,
            estimates: EstimateTally::default(),
            bands: vec![BandTally::default(); bands],
        }
    }

    /// Records one cell: its band, its truth, and its estimate (`None`:
    /// unobserved), decided by `decision`.
    #[inline]
    pub(crate) fn record(&mut self, band: usize, occupied: bool, estimate: Option<&Estimate>, decision: Decision) {
        self.cells += 1;
        self.bands[band].cells += 1;
        let Some(estimate) = estimate else {
            self.unobserved += 1;
            return;
        };
        self.estimates.record(estimate);
        let band = &mut self.bands[band];
        band.observed += 1;
        if let Estimate::Evidential { combination, .. } = estimate {
            band.conflict_sum += combination.conflict;
        }
        match (decide(estimate.decision_mass(), decision), occupied) {
            (None, _) => {
                self.below += 1;
                band.below += 1;
            }
            (Some(State::Unknown), _) => self.unknown += 1,
            (Some(State::Occupied), true) | (Some(State::Empty), false) => {
                self.correct += 1;
                band.correct += 1;
            }
            (Some(State::Occupied), false) => {
                self.false_alarms += 1;
                band.false_alarms += 1;
            }
            (Some(State::Empty), true) => {
                self.missed += 1;
                band.missed += 1;
            }
        }
    }

    /// Adds `other`'s counts; call in a fixed order for reproducible sums.
    pub(crate) fn merge(&mut self, other: &Tally) {
        self.cells += other.cells;
        self.correct += other.correct;
        self.below += other.below;
        self.false_alarms += other.false_alarms;
        self.missed += other.missed;
        self.unknown += other.unknown;
        self.unobserved += other.unobserved;
        self.estimates.merge(&other.estimates);
        for (band, o) in self.bands.iter_mut().zip(&other.bands) {
            band.cells += o.cells;
            band.observed += o.observed;
            band.conflict_sum += o.conflict_sum;
            band.correct += o.correct;
            band.below += o.below;
            band.false_alarms += o.false_alarms;
            band.missed += o.missed;
        }
    }

    /// The metrics of the tallied cells; `edges` are the band edges, `evidential`
    /// whether the method has a conflict signal.
    pub(crate) fn finish(&self, edges: &[f64], evidential: bool, coverage: Coverage) -> FieldOutcome {
        let (mean_uncertainty, conflict, audit) = self.estimates.finish(evidential);
        FieldOutcome {
            metrics: FieldMetrics {
                cells: self.cells,
                correct: self.correct,
                below_threshold: self.below,
                false_alarms: self.false_alarms,
                missed_detections: self.missed,
                decided_unknown: self.unknown,
                unobserved: self.unobserved,
                mean_uncertainty,
                conflict,
            },
            bands: self
                .bands
                .iter()
                .enumerate()
                .map(|(i, b)| BandMetrics {
                    from: if i == 0 { 0.0 } else { edges[i - 1] },
                    to: edges.get(i).copied(),
                    cells: b.cells,
                    accuracy: (b.cells > 0).then(|| b.correct as f64 / b.cells as f64),
                    below_threshold: b.below,
                    false_alarms: b.false_alarms,
                    missed_detections: b.missed,
                    mean_conflict: (evidential && b.observed > 0).then(|| b.conflict_sum / b.observed as f64),
                })
                .collect(),
            audit,
            coverage,
        }
    }
}

/// The `q` quantile of ascending `sorted` values, linear between order statistics
/// (Hyndman and Fan's type 7, the default of R and NumPy); `None` when empty.
pub fn quantile(sorted: &[f64], q: f64) -> Option<f64> {
    let last = sorted.len().checked_sub(1)?;
    let position = q * last as f64;
    let below = position.floor() as usize;
    let above = (below + 1).min(last);
    Some(sorted[below] + (sorted[above] - sorted[below]) * (position - below as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let values = [1.0, 2.0, 3.0, 4.0, 10.0];
        assert_eq!(quantile(&values, 0.5), Some(3.0));
        // Position 0.95 × 4 = 3.8: 4 + 0.8 × (10 − 4) = 8.8.
        assert!((quantile(&values, 0.95).unwrap() - 8.8).abs() < 1e-12);
        assert_eq!(quantile(&[], 0.5), None);
    }

    #[test]
    fn conflict_over_no_fused_cell_has_no_value() {
        let conflict = |mean| ConflictMetrics {
            mean,
            max: 0.0,
            total_conflict_cells: 0,
            weighted_cells: 0,
        };
        let conflicts = [
            Metric::MeanConflict,
            Metric::MaxConflict,
            Metric::TotalConflictCells,
            Metric::WeightedCells,
        ];
        for metric in conflicts {
            assert_eq!(conflict(None).value(metric), None, "{metric:?}");
        }
        let values: Vec<_> = conflicts.iter().map(|&m| conflict(Some(0.0)).value(m)).collect();
        assert_eq!(values, [Some(0.0); 4]);
        assert_eq!(conflict(Some(0.0)).value(Metric::Accuracy), None);
    }
}
