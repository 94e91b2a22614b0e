//! What a world run measures: occupied-cell recall and precision of the fused grid,
//! recall in the ego's blind area, the field of view gained by cooperation, how
//! much of what the fused grid knows is self-report, and what sensors saw and
//! missed (how many sensor–target pairs were in line of sight, and the mean
//! visible fraction of the targets, `mean_visible_fraction`).
//!
//! Counts are over cell-steps: a cell occupied at 300 steps counts 300 times.
//! Only cells in the region of interest are counted, never occluder cells or the
//! ego's own footprint, and only at steps at which the ego is in the scene.
//!
//! The cells a cooperating agent's own body covers (its true footprint) are
//! self-report: the agent marks them itself, so no sensor had to find them.
//! Recall (`occupied_recall`, `blind_recall`) counts the other occupied cells,
//! each detected when decided Occupy where a sensor found it occupied (a
//! reported footprint, held over the radio where its agent was, detects no
//! one who drove into it since), which answers "does cooperation reveal the
//! road users the ego cannot see?";
//! the self-report cells are counted apart (`self_report_share`), and with them
//! (`occupied_recall_with_self_report`) as a grid holding every road user is
//! scored. Precision counts every cell decided Occupy. How well the fused
//! probabilities are calibrated (`brier_score` and its reliability table) is
//! judged in [`super::calibration`].

use serde::{Deserialize, Serialize};
use sightline_dsl::{Grid, Metric, Signal};

use super::calibration::Calibration;
use super::observe::Sightings;
use super::radio::RadioStats;
use super::raster::cell_center;
use crate::fusion::State;
use crate::math::Point;
use crate::metrics::Series;
use crate::metrics::quantile;
use crate::metrics::{ConflictMetrics, EstimateTally, MassAudit};
use crate::semantic::SemanticMetrics;

/// Everything measured at one sweep point of a world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WorldOutcome {
    /// The metrics.
    pub metrics: WorldMetrics,
    /// The mass-function audit of every fused cell.
    pub audit: MassAudit,
    /// The grids at the snapshot step, for pictures.
    pub snapshot: Option<Snapshot>,
    /// Each measured step's time and cell tallies, for temporal checks.
    pub by_step: Vec<(f64, CellTally)>,
    /// In a joint world, what the semantic pipeline measured on the same
    /// scene, its road users' records holding when each first came into this
    /// job's fused grid; `None` in a perception world. Boxed: an outcome of
    /// every kind stays small.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<Box<SemanticMetrics>>,
    /// What the scenario's system under test achieved, once it is judged
    /// (the CLI drives the system and fills this in); `None` without one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system: Option<crate::system::SystemMetrics>,
}

impl WorldOutcome {
    /// `signal` at every measured step where it is defined (recall needs occupied
    /// cells, precision cells decided Occupy); `None` for a semantic signal.
    pub fn series(&self, signal: Signal) -> Option<Series> {
        let ratio = |num: u64, den: u64| (den > 0).then(|| num as f64 / den as f64);
        let value = |c: &CellTally| match signal {
            Signal::OccupiedRecall => ratio(c.detected, c.occupied),
            Signal::BlindRecall => ratio(c.blind_detected, c.blind_occupied),
            Signal::OccupiedPrecision => {
                let decided = c.detected + c.footprint_only + c.self_report_detected;
                ratio(decided, decided + c.false_positives)
            }
            Signal::RsuOnlyObjects | Signal::TimeToConflict => None,
        };
        signal.in_world().then(|| {
            self.by_step
                .iter()
                .filter_map(|(time, cells)| value(cells).map(|v| (*time, v)))
                .collect()
        })
    }
}

/// World metrics of one run. The default has every count zero and every
/// statistic `None`: the metrics of a run before its first step.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct WorldMetrics {
    /// Steps counted (the ego in the scene).
    pub steps: u64,
    /// Cell-steps truly occupied by a road user that does not cooperate (not
    /// the ego, an RSU or a cooperating agent reporting its own footprint).
    pub occupied: u64,
    /// Of those, decided Occupy by the fused grid where a sensor found them
    /// occupied (not a reported footprint alone).
    pub detected: u64,
    /// Of the `occupied` cell-steps, those the ego's own observation alone
    /// decides Occupy (fused and decided by the same rule).
    pub ego_detected: u64,
    /// Cell-steps decided Occupy that are truly free.
    pub false_positives: u64,
    /// Of the `occupied` cell-steps, those the ego did not observe itself.
    pub blind_occupied: u64,
    /// Of those, detected as `detected` counts.
    pub blind_detected: u64,
    /// Of the `occupied` cell-steps, those decided Occupy where no sensor
    /// found them occupied: only another agent's reported footprint (where
    /// that agent was) covers them. A correct decision (`occupied_precision`
    /// counts it), no detection (`detected` does not).
    pub footprint_only: u64,
    /// Cell-steps truly occupied by a cooperating agent other than the ego
    /// (its own footprint, which it reports).
    pub self_report: u64,
    /// Of those, decided Occupy by the fused grid.
    pub self_report_detected: u64,
    /// Of those, the cell-steps no sensor observed occupied: known only
    /// through self-report.
    pub self_report_only: u64,
    /// Cell-steps a sensor of the ego observed.
    pub ego_observed: u64,
    /// Cell-steps a sensor of any cooperating agent observed (a self-reported
    /// footprint is not observed).
    pub joint_observed: u64,
    /// Sensor–target pairs in range and field of view, by visibility, over the run.
    pub sightings: Sightings,
    /// Mean position error of the cooperating agents' pose estimates, metres.
    pub localization_error: Option<f64>,
    /// Mean uncertainty of the fused cells.
    pub mean_uncertainty: Option<f64>,
    /// Conflict statistics (evidential methods only).
    pub conflict: Option<ConflictMetrics>,
    /// How well the fused probabilities are calibrated.
    pub calibration: Calibration,
    /// Recall by distance to the nearest cooperating agent other than the ego.
    pub recall_by_distance: RecallByDistance,
    /// What went over the radio; `None` without one (no `v2x`). Boxed: an
    /// outcome of every kind stays small.
    pub radio: Option<Box<RadioStats>>,
}

impl WorldMetrics {
    /// Adds one measured step's counts: the counted cells the ego observed and
    /// that any cooperating agent observed, and one fusion job's cell tallies.
    /// Saturating: replay sums counts read from a file with it, and a forged
    /// count must give a mismatch, not an overflow.
    pub fn add_step(&mut self, ego_observed: u64, joint_observed: u64, cells: &CellTally) {
        let add = |total: &mut u64, count: u64| *total = total.saturating_add(count);
        add(&mut self.steps, 1);
        add(&mut self.ego_observed, ego_observed);
        add(&mut self.joint_observed, joint_observed);
        add(&mut self.occupied, cells.occupied);
        add(&mut self.detected, cells.detected);
        add(&mut self.ego_detected, cells.ego_detected);
        add(&mut self.false_positives, cells.false_positives);
        add(&mut self.blind_occupied, cells.blind_occupied);
        add(&mut self.blind_detected, cells.blind_detected);
        add(&mut self.footprint_only, cells.footprint_only);
        add(&mut self.self_report, cells.self_report);
        add(&mut self.self_report_detected, cells.self_report_detected);
        add(&mut self.self_report_only, cells.self_report_only);
    }

    /// Truly occupied cell-steps detected, self-report included.
    fn correct(&self) -> u64 {
        self.detected.saturating_add(self.self_report_detected)
    }

    /// Truly occupied cell-steps decided Occupy: the detected ones and those
    /// only another agent's footprint covers.
    fn decided_occupied(&self) -> u64 {
        self.correct().saturating_add(self.footprint_only)
    }

    /// The value of `metric`, or `None` where it is not defined for this run.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        let ratio = |num: u64, den: u64| (den > 0).then(|| num as f64 / den as f64);
        match metric {
            Metric::FovGain => ratio(self.joint_observed, self.ego_observed).map(|r| r - 1.0),
            Metric::OccupiedRecall => ratio(self.detected, self.occupied),
            Metric::EgoOccupiedRecall => ratio(self.ego_detected, self.occupied),
            Metric::OccupiedPrecision => ratio(
                self.decided_occupied(),
                self.decided_occupied().saturating_add(self.false_positives),
            ),
            Metric::BlindRecall => ratio(self.blind_detected, self.blind_occupied),
            Metric::OccupiedRecallWithSelfReport => {
                ratio(self.correct(), self.occupied.saturating_add(self.self_report))
            }
            Metric::SelfReportShare => ratio(self.self_report_only, self.correct()),
            Metric::BrierScore => self.calibration.brier_score(),
            Metric::PacketDeliveryRatio => {
                let radio = self.radio.as_ref()?;
                ratio(radio.received, radio.sent)
            }
            Metric::MessageAgeMean => self.radio.as_ref()?.mean_age(),
            Metric::MessageAgeP95 => quantile(&self.radio.as_ref()?.sorted_ages(), 0.95),
            Metric::BytesPerSecondPerAgent => {
                let radio = self.radio.as_ref()?;
                (radio.sender_steps > 0).then(|| radio.bytes as f64 / (radio.sender_steps as f64 * radio.step))
            }
            Metric::MeanVisibleFraction => {
                let pairs = self.sightings.total();
                (pairs > 0).then(|| self.sightings.visible / pairs as f64)
            }
            Metric::MeanUncertainty => self.mean_uncertainty,
            Metric::MeanConflict | Metric::MaxConflict | Metric::TotalConflictCells | Metric::WeightedCells => {
                self.conflict.as_ref()?.value(metric)
            }
            _ => None,
        }
    }

    /// The number of cell-steps `metric` is computed over
    /// ([`Metric::population`]), given the `fused` cell-steps of the run's
    /// audit; `None` where a world does not measure it.
    pub fn sample_size(&self, metric: Metric, fused: u64) -> Option<u64> {
        match metric {
            Metric::FovGain => Some(self.ego_observed),
            Metric::OccupiedRecall | Metric::EgoOccupiedRecall => Some(self.occupied),
            Metric::OccupiedPrecision => Some(self.decided_occupied().saturating_add(self.false_positives)),
            Metric::BlindRecall => Some(self.blind_occupied),
            Metric::OccupiedRecallWithSelfReport => Some(self.occupied.saturating_add(self.self_report)),
            Metric::SelfReportShare => Some(self.correct()),
            Metric::BrierScore => Some(self.calibration.cells),
            Metric::PacketDeliveryRatio => self.radio.as_ref().map(|r| r.sent),
            Metric::MessageAgeMean | Metric::MessageAgeP95 => self.radio.as_ref().map(|r| r.fused()),
            Metric::BytesPerSecondPerAgent => self.radio.as_ref().map(|r| r.sender_steps),
            Metric::MeanVisibleFraction => Some(self.sightings.total()),
            Metric::MeanUncertainty => Some(fused),
            Metric::MeanConflict | Metric::MaxConflict | Metric::TotalConflictCells | Metric::WeightedCells => {
                self.conflict.as_ref().map(|_| fused)
            }
            _ => None,
        }
    }
}

/// The grids of one step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The step.
    pub step: usize,
    /// Per cell: 0 free, 1 occupied by an agent (a cooperating agent's own
    /// footprint, which the metrics count apart as self-report, included), 2
    /// occluder, 3 the ego (whose footprint no metric counts). Cells outside the
    /// region of interest are free.
    pub truth: Vec<u8>,
    /// Per cell, the ego's own grid: 0 unknown, 1 free, 2 occupied.
    pub ego: Vec<u8>,
    /// Per cell, the fused grid; `None` where no cooperating agent observed the
    /// cell (or the cell is not counted: outside the region, an occluder, the ego).
    pub fused: Vec<Option<FusedCell>>,
}

/// A fused cell of a [`Snapshot`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FusedCell {
    /// Occupancy probability (pignistic for evidential methods).
    pub probability: f32,
    /// Uncertainty (the fused estimate's):
    /// the mass on Unknown, m(Θ), for evidential methods; the binary entropy of
    /// the probability in bits for Bayes. Both run from 0 (certain) to 1.
    pub uncertainty: f32,
    /// The decision rule's state for the cell; `None` below the threshold.
    pub decision: Option<State>,
}

/// Cell-steps of one method by outcome: one step's or, summed with
/// [`CellTally::add`], a run's (the counts of [`WorldMetrics`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CellTally {
    /// Truly occupied by a road user that does not cooperate.
    pub occupied: u64,
    /// Of those, decided Occupy by the fused grid where a sensor found them
    /// occupied.
    pub detected: u64,
    /// Of the `occupied`, decided Occupy by the ego's own observation alone.
    pub ego_detected: u64,
    /// Decided Occupy but truly free.
    pub false_positives: u64,
    /// Of the `occupied`, those not observed by the ego itself.
    pub blind_occupied: u64,
    /// Of those, detected as `detected` counts.
    pub blind_detected: u64,
    /// Of the `occupied`, decided Occupy where only another agent's reported
    /// footprint, no sensor, marks them occupied.
    pub footprint_only: u64,
    /// Truly occupied by a cooperating agent other than the ego (self-report).
    pub self_report: u64,
    /// Of those, decided Occupy by the fused grid.
    pub self_report_detected: u64,
    /// Of those, observed occupied by no sensor: known only through self-report.
    pub self_report_only: u64,
}

impl CellTally {
    /// Adds `other`'s counts.
    pub fn add(&mut self, other: &CellTally) {
        self.occupied += other.occupied;
        self.detected += other.detected;
        self.ego_detected += other.ego_detected;
        self.false_positives += other.false_positives;
        self.blind_occupied += other.blind_occupied;
        self.blind_detected += other.blind_detected;
        self.footprint_only += other.footprint_only;
        self.self_report += other.self_report;
        self.self_report_detected += other.self_report_detected;
        self.self_report_only += other.self_report_only;
    }
}

/// Width of a bin of [`RecallByDistance`], metres.
pub const DISTANCE_BIN: f64 = 25.0;
/// Bins of [`RecallByDistance`]: four of [`DISTANCE_BIN`], then everything farther.
pub const DISTANCE_BINS: usize = 5;

/// Occupied-cell recall (self-report left out, as `occupied_recall`) by the
/// distance from the cell to the nearest cooperating agent other than the ego
/// in the scene: bin i holds distances in [25 i, 25 (i + 1)) m, the last bin
/// 100 m and beyond. Cell-steps with no such agent in the scene are not
/// counted.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RecallByDistance {
    /// The bins, nearest first. Boxed: an outcome of every kind stays small.
    pub bins: Box<[DistanceBin; DISTANCE_BINS]>,
}

/// The occupied cell-steps of one bin of [`RecallByDistance`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct DistanceBin {
    /// Occupied cell-steps of road users that do not cooperate.
    pub occupied: u64,
    /// Of them, decided Occupy by the fused grid.
    pub detected: u64,
}

impl RecallByDistance {
    /// Counts the occupied `cell` of `grid` by its distance to the nearest of
    /// `senders`; nothing when there is none.
    pub(crate) fn record(&mut self, grid: &Grid, senders: &[Point], cell: usize, detected: bool) {
        let center = cell_center(grid, cell);
        let Some(distance) = senders.iter().map(|s| (*s - center).length()).reduce(f64::min) else {
            return;
        };
        let bin = ((distance / DISTANCE_BIN) as usize).min(DISTANCE_BINS - 1);
        self.bins[bin].occupied += 1;
        self.bins[bin].detected += u64::from(detected);
    }

    /// Adds `other`'s counts.
    pub(crate) fn merge(&mut self, other: &RecallByDistance) {
        for (bin, other) in self.bins.iter_mut().zip(other.bins.iter()) {
            bin.occupied += other.occupied;
            bin.detected += other.detected;
        }
    }
}

/// One method's tallies over a chunk of fused cells of one step.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct WorldTally {
    pub(crate) cells: CellTally,
    pub(crate) estimates: EstimateTally,
    pub(crate) calibration: Calibration,
    pub(crate) by_distance: RecallByDistance,
    /// The agents whose footprint holds a cell of the chunk decided Occupy,
    /// once per such cell, in cell order; collected only when asked for.
    pub(crate) owners: Vec<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two steps add up field by field, one step each; the default counts nothing.
    #[test]
    fn add_step_sums_a_step_s_counts() {
        let mut metrics = WorldMetrics::default();
        assert_eq!(metrics.steps, 0);
        assert_eq!(metrics.value(Metric::OccupiedRecall), None);
        // Nothing judged: no Brier score, n = 0 (a requirement on it is not exercised).
        assert_eq!(
            (
                metrics.value(Metric::BrierScore),
                metrics.sample_size(Metric::BrierScore, 0)
            ),
            (None, Some(0))
        );
        let cells = CellTally {
            occupied: 10,
            detected: 8,
            ego_detected: 3,
            false_positives: 1,
            blind_occupied: 4,
            blind_detected: 2,
            footprint_only: 1,
            self_report: 6,
            self_report_detected: 5,
            self_report_only: 3,
        };
        metrics.add_step(100, 150, &cells);
        metrics.add_step(50, 50, &cells);
        assert_eq!(metrics.steps, 2);
        assert_eq!((metrics.ego_observed, metrics.joint_observed), (150, 200));
        assert_eq!(
            (metrics.occupied, metrics.detected, metrics.false_positives),
            (20, 16, 2)
        );
        assert_eq!((metrics.blind_occupied, metrics.blind_detected), (8, 4));
        assert_eq!(
            (
                metrics.self_report,
                metrics.self_report_detected,
                metrics.self_report_only
            ),
            (12, 10, 6)
        );
        assert_eq!(metrics.value(Metric::OccupiedRecall), Some(0.8));
        // The ego alone, over the same 20 cell-steps.
        assert_eq!(metrics.ego_detected, 6);
        assert_eq!(metrics.value(Metric::EgoOccupiedRecall), Some(0.3));
        assert_eq!(metrics.sample_size(Metric::EgoOccupiedRecall, 0), Some(20));
        // (16 + 10) / (20 + 12), over 32 cell-steps; 6 of the 26 correct ones are self-report only.
        assert_eq!(metrics.value(Metric::OccupiedRecallWithSelfReport), Some(26.0 / 32.0));
        assert_eq!(metrics.sample_size(Metric::OccupiedRecallWithSelfReport, 0), Some(32));
        assert_eq!(metrics.value(Metric::SelfReportShare), Some(6.0 / 26.0));
        assert_eq!(metrics.sample_size(Metric::SelfReportShare, 0), Some(26));
        // Precision counts the 2 cell-steps only another agent's footprint covers as
        // correct decisions, which no recall counts as detected: (16 + 2 + 10) / (28 + 2).
        assert_eq!(metrics.footprint_only, 2);
        assert_eq!(metrics.value(Metric::OccupiedPrecision), Some(28.0 / 30.0));
        assert_eq!(metrics.sample_size(Metric::OccupiedPrecision, 0), Some(30));
    }

    /// Four sensor–target pairs: one wholly seen, two half seen, one hidden:
    /// (1 + 0.5 + 0.5 + 0) / 4 = 0.5, n = 4; no pair, no value and n = 0.
    #[test]
    fn the_mean_visible_fraction_counts_hidden_targets_as_zero() {
        let mut metrics = WorldMetrics::default();
        assert_eq!(
            (
                metrics.value(Metric::MeanVisibleFraction),
                metrics.sample_size(Metric::MeanVisibleFraction, 0)
            ),
            (None, Some(0))
        );
        metrics.sightings = Sightings {
            los: 3,
            nlos_static: 1,
            nlos_dynamic: 0,
            detected: 3,
            visible: 1.0 + 0.5 + 0.5,
        };
        assert_eq!(metrics.value(Metric::MeanVisibleFraction), Some(0.5));
        assert_eq!(metrics.sample_size(Metric::MeanVisibleFraction, 0), Some(4));
    }

    /// A forged count from a recording saturates rather than overflowing.
    #[test]
    fn add_step_saturates() {
        let mut metrics = WorldMetrics::default();
        let cells = CellTally {
            occupied: u64::MAX,
            ..CellTally::default()
        };
        metrics.add_step(u64::MAX, 1, &cells);
        metrics.add_step(1, 1, &cells);
        assert_eq!(
            (metrics.occupied, metrics.ego_observed, metrics.joint_observed),
            (u64::MAX, u64::MAX, 2)
        );
    }
}
