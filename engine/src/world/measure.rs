//! The measure phase of a world: each measured step added to every fusion job's
//! metrics (with [`WorldMetrics::add_step`], as replay sums a recording), its
//! per-step tallies and the snapshot, and every step's record handed to the
//! trace sink.
//!
//! Floating-point sums run in a fixed order (cooperating agents in cooperation
//! order, chunks of fused cells in chunk order), so that the results do not
//! depend on the thread count.

use sightline_dsl::Grid;

use super::calibration::Calibration;
use super::fuse::{CellValues, Fused};
use super::metrics::{CellTally, FusedCell, RecallByDistance, Snapshot, WorldMetrics, WorldOutcome};
use super::observe::{Observation, Observed, Sightings};
use super::radio::RadioStats;
use super::raster::Raster;
use super::state::AgentState;
use super::truth::{EXCLUDED, OCCUPIED, SELF_REPORT, Truth};
use crate::math::Point;
use crate::metrics::EstimateTally;
use crate::run::Job;
use crate::sink::TraceSink;
use crate::trace::{CooperatorStep, FusedGrid, FusedStep, Measured, WorldStep};

/// What a run has measured so far.
pub(super) struct Measures {
    /// Per fusion job, in job order.
    jobs: Vec<JobMeasures>,
    /// The cooperating agents' sightings over the measured steps.
    sightings: Sightings,
    /// The cooperating agents' position errors over the measured steps: their
    /// sum, metres, and their number.
    error_sum: f64,
    error_count: u64,
}

/// What one fusion job has measured so far.
#[derive(Debug, Default)]
struct JobMeasures {
    /// The counts; the statistics are filled in at the end.
    metrics: WorldMetrics,
    estimates: EstimateTally,
    calibration: Calibration,
    by_distance: RecallByDistance,
    snapshot: Option<Snapshot>,
    by_step: Vec<(f64, CellTally)>,
}

/// A measured step (the ego in the scene), as the earlier phases leave it.
pub(super) struct MeasuredStep<'a> {
    /// The step.
    pub(super) step: usize,
    /// Its time, seconds.
    pub(super) time: f64,
    /// Every agent's true state.
    pub(super) states: &'a [Option<AgentState>],
    /// The scene's raster, for the snapshot's occluders.
    pub(super) raster: &'a Raster,
    /// What the cooperating agents in the scene sensed, the ego first.
    pub(super) sensed: &'a [CooperatorStep<'a>],
    /// The step's ground truth.
    pub(super) truth: &'a Truth,
    /// The grid.
    pub(super) grid: &'a Grid,
    /// The true positions of the cooperating agents other than the ego in the scene.
    pub(super) senders: &'a [Point],
    /// Every job's fused grid.
    pub(super) fused: Fused<'a>,
    /// Whether it is the snapshot step.
    pub(super) snapshot: bool,
    /// Whether the sink wants its fused grids.
    pub(super) grids: bool,
}

impl Measures {
    /// Nothing measured yet, for `jobs` fusion jobs.
    pub(super) fn new(jobs: usize) -> Self {
        Self {
            jobs: (0..jobs).map(|_| JobMeasures::default()).collect(),
            sightings: Sightings::default(),
            error_sum: 0.0,
            error_count: 0,
        }
    }

    /// Measure: adds a measured step to every job's measurements and reports
    /// it to `sink`.
    pub(super) fn measure(&mut self, step: MeasuredStep<'_>, sink: &mut impl TraceSink) {
        for c in step.sensed {
            self.sightings.add(c.observation.sightings);
            let truth = step.states[c.agent].expect("a present cooperator is in the scene").pose;
            self.error_sum += (c.estimate.translation - truth.translation).length();
            self.error_count += 1;
        }
        let coverage = step.fused.coverage;
        let truth = step.truth.cells();
        let (ego_observed, joint_observed) = (coverage.ego(), coverage.joint());
        // Occupied cells nobody observed count as missed (and as blind: the ego did
        // not observe them either); so do a cooperating agent's own cells that
        // nobody, not even it, observed (its estimated footprint missed them).
        let unseen = |kind: u8| {
            step.truth
                .marked()
                .iter()
                .filter(|&&c| truth[c] == kind && !coverage.covers(c))
                .count() as u64
        };
        let (unseen, unseen_own) = (unseen(OCCUPIED), unseen(SELF_REPORT));
        // The same occupied cells, missed, by distance to the nearest sender.
        let mut unseen_by_distance = RecallByDistance::default();
        for &cell in step.truth.marked() {
            if truth[cell] == OCCUPIED && !coverage.covers(cell) {
                unseen_by_distance.record(step.grid, step.senders, cell, false);
            }
        }
        let mut fused = Vec::with_capacity(self.jobs.len());
        for (j, (job, chunks)) in self.jobs.iter_mut().zip(&step.fused.chunks).enumerate() {
            let mut cells = CellTally {
                occupied: unseen,
                blind_occupied: unseen,
                self_report: unseen_own,
                ..CellTally::default()
            };
            // Chunk by chunk, so that the floating-point sums do not depend on
            // the thread count.
            job.by_distance.merge(&unseen_by_distance);
            for chunk in chunks {
                cells.add(&chunk.cells);
                job.estimates.merge(&chunk.estimates);
                job.calibration.merge(&chunk.calibration);
                job.by_distance.merge(&chunk.by_distance);
            }
            job.metrics.add_step(ego_observed, joint_observed, &cells);
            let values = step.fused.values.map(|values| &values[j]);
            if step.snapshot {
                let values = values.expect("the snapshot step is pictured");
                let ego = step.sensed[0].observation;
                job.snapshot = Some(picture(step.step, truth, step.raster, ego, coverage.cells(), values));
            }
            job.by_step.push((step.time, cells));
            fused.push(FusedStep {
                cells,
                grid: values.filter(|_| step.grids).map(|values| FusedGrid {
                    cells: coverage.cells(),
                    probability: &values.probability,
                    uncertainty: &values.uncertainty,
                }),
            });
        }
        sink.world_step(&WorldStep {
            step: step.step,
            time: step.time,
            agents: step.states,
            cooperators: step.sensed,
            measured: Some(Measured {
                ego_observed,
                joint_observed,
                fused: &fused,
            }),
        });
    }

    /// Every job's outcome, with what went over the radio (`None` without one).
    pub(super) fn finish(self, jobs: &[Job<'_>], radio: Option<RadioStats>) -> Vec<WorldOutcome> {
        let localization_error = (self.error_count > 0).then(|| self.error_sum / self.error_count as f64);
        self.jobs
            .into_iter()
            .zip(jobs)
            .map(|(measured, job)| {
                let (mean_uncertainty, conflict, audit) = measured.estimates.finish(job.fusion.rule.is_evidential());
                WorldOutcome {
                    metrics: WorldMetrics {
                        sightings: self.sightings,
                        localization_error,
                        mean_uncertainty,
                        conflict,
                        calibration: measured.calibration,
                        recall_by_distance: measured.by_distance,
                        radio: radio.clone().map(Box::new),
                        ..measured.metrics
                    },
                    audit,
                    snapshot: measured.snapshot,
                    by_step: measured.by_step,
                    semantic: None,
                    system: None,
                }
            })
            .collect()
    }
}

/// Reports a step the ego is not in: it counts in no metric.
pub(super) fn unmeasured(
    step: usize,
    time: f64,
    states: &[Option<AgentState>],
    sensed: &[CooperatorStep<'_>],
    sink: &mut impl TraceSink,
) {
    sink.world_step(&WorldStep {
        step,
        time,
        agents: states,
        cooperators: sensed,
        measured: None,
    });
}

/// The grids of the snapshot step.
fn picture(
    step: usize,
    truth: &[u8],
    raster: &Raster,
    ego: &Observation,
    observed_cells: &[usize],
    values: &CellValues,
) -> Snapshot {
    let truth_picture = (0..truth.len())
        .map(|cell| match (raster.is_occluder(cell), truth[cell]) {
            (true, _) => 2,
            (false, OCCUPIED | SELF_REPORT) => 1,
            // Occluders are handled above: what else is excluded is the ego.
            (false, EXCLUDED) => 3,
            _ => 0,
        })
        .collect();
    let ego_picture = (0..truth.len())
        .map(|cell| match ego.get(cell) {
            Observed::Unknown => 0,
            Observed::Free => 1,
            Observed::Occupied | Observed::Own => 2,
        })
        .collect();
    let mut fused = vec![None; truth.len()];
    for (i, &cell) in observed_cells.iter().enumerate() {
        fused[cell] = Some(FusedCell {
            probability: values.probability[i],
            uncertainty: values.uncertainty[i],
            decision: values.decision[i],
        });
    }
    Snapshot {
        step,
        truth: truth_picture,
        ego: ego_picture,
        fused,
    }
}
