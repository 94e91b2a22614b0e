//! The fuse phase of a world: the observations that reached the ego fused cell
//! by cell with each job's rule, over the counted cells they cover.
//!
//! Fusion runs in parallel over fixed-size chunks of the covered cells, each
//! fused as soon as the coverage has found it, while the coverage goes on. Each
//! chunk's fused estimates are tallied against the ground truth as they are
//! computed (the roundabout's grid has 360 000 cells: estimates are not kept),
//! and handed on chunk by chunk, so that the measure phase sums them in chunk
//! order whatever the thread count.

use std::sync::mpsc;

use sightline_dsl::{Decision, Grid, Perception, Rule};

use super::evidence::Evidence;
use super::memo::{Judged, Memo, judge};
use super::metrics::WorldTally;
use super::observe::Observed;
use super::raster::cell_center;
use super::truth::{OCCUPIED, SELF_REPORT, Truth};
use crate::fusion::{Estimate, Mass, Source, State, fuse};
use crate::idealisation::Idealisation;
use crate::math::Point;
use crate::run::Job;

/// The inverse sensor model is two constants.
pub(crate) const INVERSE_MODEL: Idealisation = Idealisation {
    id: "fuse.inverse-model",
    text: "An observation conveys fixed probabilities of occupancy (`perception.inverse_model`), whatever the \
           distance, the sensor or the visibility of the cell.",
};

/// Fuses, cell by cell, what a set of agents observed at one step with one rule.
///
/// Each observation becomes the least-committed mass whose pignistic probability
/// is the inverse sensor model's: free → (1 − 2f, 0, 2f), occupied →
/// (0, 2o − 1, 2 − 2o), discounted toward unknown by the evidence's weight
/// when it has aged over the radio. Bayes fuses their pignistic probabilities
/// (f and o back for fresh evidence); the weighted rules weigh each by the
/// distance from the agent's nearest sensor to the cell (floored at half a
/// cell).
pub struct CellFusion<'a> {
    /// The grid.
    pub grid: &'a Grid,
    /// The fusion rule.
    pub rule: &'a Rule,
    /// The evidence to fuse, the ego's own observation first.
    pub observations: &'a [&'a dyn Evidence],
    /// P(occupied) of a detected cell.
    pub occupied: f64,
    /// P(occupied) of a cell seen free.
    pub free: f64,
}

impl CellFusion<'_> {
    /// The fused estimate of `cell`, which at least one agent observed.
    /// `sources` is scratch space.
    pub fn estimate(&self, cell: usize, sources: &mut Vec<Source>) -> Estimate {
        sources.clear();
        // Only the distance-weighted rules read distances: spare the square roots.
        let distances = matches!(self.rule, Rule::DistanceWeighted(_) | Rule::Hybrid { .. });
        let center = cell_center(self.grid, cell);
        for observation in self.observations {
            let state = observation.get(cell);
            if state == Observed::Unknown {
                continue;
            }
            let distance = if distances {
                observation
                    .sensors(cell)
                    .iter()
                    .map(|p| (*p - center).length())
                    .fold(f64::INFINITY, f64::min)
            } else {
                0.0
            };
            sources.push(self.source(state, observation.weight(cell), distance));
        }
        fuse(self.rule, sources)
    }

    /// The memo of this rule's fused cells judged by `decision`, when the
    /// rule reads only masses.
    pub(super) fn memo(&self, decision: Decision) -> Option<Memo> {
        let fresh = [Observed::Free, Observed::Occupied].map(|state| self.source(state, 1.0, 0.0));
        Memo::new(self.rule, fresh, decision)
    }

    /// The source an observation of `state` (free or occupied) with `weight`
    /// from sensors `distance` away makes.
    pub(super) fn source(&self, state: Observed, weight: f64, distance: f64) -> Source {
        let mass = match state {
            Observed::Free => Mass::new(1.0 - 2.0 * self.free, 0.0, 2.0 * self.free),
            _ => Mass::new(0.0, 2.0 * self.occupied - 1.0, 2.0 - 2.0 * self.occupied),
        };
        Source {
            mass: if weight < 1.0 { mass.discounted(weight) } else { mass },
            distance: distance.max(self.grid.cell / 2.0),
        }
    }
}

/// Cells fused per parallel task.
const CHUNK: usize = 4096;

/// The counted cells the observations that reached the ego cover at one step:
/// the cells fused, and of those the ones a sensor observed (a cooperating
/// agent's self-reported footprint, [`Observed::Own`], is covered without
/// being observed).
#[derive(Debug, Clone)]
pub(super) struct Coverage {
    /// Per cell, whether it is covered.
    covered: Vec<bool>,
    /// Per covered cell, whether a sensor observed it.
    sensed: Vec<bool>,
    /// The covered cells, in the order first touched.
    cells: Vec<usize>,
    /// How many counted cells a sensor of the ego observed.
    ego: u64,
    /// How many counted cells a sensor of any cooperating agent observed.
    joint: u64,
}

impl Coverage {
    /// Nothing covered in a grid of `cells` cells.
    pub(super) fn new(cells: usize) -> Self {
        Self {
            covered: vec![false; cells],
            sensed: vec![false; cells],
            cells: Vec::new(),
            ego: 0,
            joint: 0,
        }
    }

    /// Covers every cell of `received` (the ego's observation first) that
    /// `counted` admits, handing `chunk` each [`CHUNK`] covered cells as they
    /// are found (the last ones however many), with its index.
    fn cover(
        &mut self,
        received: &[&dyn Evidence],
        counted: impl Fn(usize) -> bool,
        mut chunk: impl FnMut(usize, &[usize]),
    ) {
        for &cell in &self.cells {
            self.covered[cell] = false;
            self.sensed[cell] = false;
        }
        self.cells.clear();
        self.joint = 0;
        for (i, observation) in received.iter().enumerate() {
            for &cell in observation.touched() {
                if !self.covered[cell] && counted(cell) {
                    self.covered[cell] = true;
                    self.cells.push(cell);
                    if self.cells.len().is_multiple_of(CHUNK) {
                        let index = self.cells.len() / CHUNK - 1;
                        chunk(index, &self.cells[index * CHUNK..]);
                    }
                }
                if self.covered[cell] && !self.sensed[cell] && observation.get(cell) != Observed::Own {
                    self.sensed[cell] = true;
                    self.joint += 1;
                }
            }
            // The ego's observation comes first.
            if i == 0 {
                self.ego = self.joint;
            }
        }
        if !self.cells.len().is_multiple_of(CHUNK) {
            let index = self.cells.len() / CHUNK;
            chunk(index, &self.cells[index * CHUNK..]);
        }
    }

    /// The covered cells, in the order first touched.
    pub(super) fn cells(&self) -> &[usize] {
        &self.cells
    }

    /// Whether `cell` is covered.
    pub(super) fn covers(&self, cell: usize) -> bool {
        self.covered[cell]
    }

    /// How many counted cells a sensor of the ego observed.
    pub(super) fn ego(&self) -> u64 {
        self.ego
    }

    /// How many counted cells a sensor of any cooperating agent observed.
    pub(super) fn joint(&self) -> u64 {
        self.joint
    }
}

/// Fused values of the covered cells of one step, in cell order.
#[derive(Debug, Clone, Default)]
pub(super) struct CellValues {
    pub(super) probability: Vec<f32>,
    pub(super) uncertainty: Vec<f32>,
    pub(super) decision: Vec<Option<State>>,
}

/// The fuse phase's state: the fixed inputs of every step, and the coverage
/// and fused values, reused from step to step.
pub(super) struct Fusion<'a, 'j> {
    grid: &'a Grid,
    perception: &'a Perception,
    jobs: &'a [Job<'j>],
    coverage: Coverage,
    /// Per job: the fused values of the last pictured step.
    values: Vec<CellValues>,
    /// Per job: its fused cells by their sources' states, when its rule reads
    /// only masses.
    memos: Vec<Option<Memo>>,
}

/// What the fuse phase hands the measure phase: each job's fused grid of the
/// step, tallied against the truth.
pub(super) struct Fused<'a> {
    /// The counted cells covered.
    pub(super) coverage: &'a Coverage,
    /// Per job, in job order: the tallies of each chunk of covered cells, in
    /// chunk order.
    pub(super) chunks: Vec<Vec<WorldTally>>,
    /// Per job: the fused values of the covered cells, when the step is pictured.
    pub(super) values: Option<&'a [CellValues]>,
}

impl<'a, 'j> Fusion<'a, 'j> {
    /// Ready to fuse `jobs` on `grid` with `perception`'s inverse sensor model.
    pub(super) fn new(grid: &'a Grid, perception: &'a Perception, jobs: &'a [Job<'j>]) -> Self {
        let memos = jobs
            .iter()
            .map(|job| {
                let fusion = CellFusion {
                    grid,
                    rule: &job.fusion.rule,
                    observations: &[],
                    occupied: perception.occupied,
                    free: perception.free,
                };
                fusion.memo(job.decision)
            })
            .collect();
        Self {
            grid,
            perception,
            jobs,
            coverage: Coverage::new(grid.cells()),
            values: vec![CellValues::default(); jobs.len()],
            memos,
        }
    }

    /// Fuse: every job's grid over the counted cells (those `counted` admits)
    /// that `received` covers, the ego's observation first, tallied against
    /// `truth`; with `picture`, also the fused values of those cells; with
    /// `owners`, also whose footprint each cell decided Occupy is.
    pub(super) fn fuse(
        &mut self,
        received: &[&dyn Evidence],
        senders: &[Point],
        truth: &Truth,
        counted: impl Fn(usize) -> bool + Send,
        (picture, owners): (bool, bool),
    ) -> Fused<'_> {
        let fresh = received.iter().all(|o| o.fresh());
        let talliers: Vec<Tallier> = self
            .jobs
            .iter()
            .zip(&self.memos)
            .map(|(job, memo)| Tallier {
                fusion: CellFusion {
                    grid: self.grid,
                    rule: &job.fusion.rule,
                    observations: received,
                    occupied: self.perception.occupied,
                    free: self.perception.free,
                },
                decision: job.decision,
                truth: truth.cells(),
                owners: owners.then(|| truth.owners()),
                senders,
                memo: memo.as_ref().filter(|_| fresh),
            })
            .collect();
        // Each chunk of covered cells is fused and tallied by every job as
        // soon as the coverage has found it, while the coverage goes on; the
        // chunks are put back in order.
        let (done, tallied) = mpsc::channel();
        rayon::scope(|scope| {
            self.coverage.cover(received, counted, |index, cells| {
                let (cells, done, talliers) = (cells.to_vec(), done.clone(), &talliers);
                scope.spawn(move |_| {
                    let fused: Vec<(WorldTally, CellValues)> =
                        talliers.iter().map(|tallier| tallier.tally(&cells, picture)).collect();
                    done.send((index, fused)).expect("the fuse phase awaits every chunk");
                });
            });
        });
        drop(done);
        let mut fused: Vec<(usize, Vec<(WorldTally, CellValues)>)> = tallied.into_iter().collect();
        fused.sort_unstable_by_key(|&(index, _)| index);
        if picture {
            for (j, values) in self.values.iter_mut().enumerate() {
                values.probability.clear();
                values.uncertainty.clear();
                values.decision.clear();
                for (_, jobs) in &fused {
                    let chunk = &jobs[j].1;
                    values.probability.extend(&chunk.probability);
                    values.uncertainty.extend(&chunk.uncertainty);
                    values.decision.extend(&chunk.decision);
                }
            }
        }
        let mut chunks: Vec<Vec<WorldTally>> = vec![Vec::with_capacity(fused.len()); self.jobs.len()];
        for (_, jobs) in fused {
            for (j, (tally, _)) in jobs.into_iter().enumerate() {
                chunks[j].push(tally);
            }
        }
        Fused {
            coverage: &self.coverage,
            chunks,
            values: picture.then_some(self.values.as_slice()),
        }
    }
}

/// Tallies one method's fused grid of one step against the truth.
struct Tallier<'a> {
    fusion: CellFusion<'a>,
    decision: Decision,
    truth: &'a [u8],
    /// Per cell, whose footprint it is, when the owners of the cells decided
    /// Occupy are collected.
    owners: Option<&'a [u32]>,
    /// The true positions of the cooperating agents other than the ego in the
    /// scene, for recall by distance to the nearest.
    senders: &'a [Point],
    /// The job's memo, when every observation is fresh.
    memo: Option<&'a Memo>,
}

impl Tallier<'_> {
    /// Tallies a chunk of covered cells; with `picture`, also returns their fused
    /// values.
    fn tally(&self, cells: &[usize], picture: bool) -> (WorldTally, CellValues) {
        let mut tally = WorldTally::default();
        let mut values = CellValues::default();
        let mut sources = Vec::with_capacity(self.fusion.observations.len());
        let ego = self.fusion.observations[0];
        for &cell in cells {
            let judged = self.judged(self.fusion.observations, cell, &mut sources);
            let (estimate, probability, decision) = (judged.estimate, judged.probability, judged.decision);
            tally.estimates.record(&estimate);
            // Self-report is left out, as recall leaves it out: no sensor had to find it.
            if self.truth[cell] != SELF_REPORT {
                tally.calibration.record(probability, self.truth[cell] == OCCUPIED);
            }
            let decided = decision == Some(State::Occupied);
            // Whether a sensor found the cell occupied: a footprint a cooperating agent
            // reports (`Own`) is no sensor's finding, and one held over the radio is
            // where the agent was, which another road user may have driven into since.
            let sensed = || {
                self.fusion
                    .observations
                    .iter()
                    .any(|o| o.get(cell) == Observed::Occupied)
            };
            // A road user that does not cooperate is detected only where a sensor
            // found it; a cooperating agent's body is credited by its self-report too.
            let detected = match self.truth[cell] {
                OCCUPIED => decided && sensed(),
                SELF_REPORT => decided,
                _ => false,
            };
            if let Some(owners) = self.owners.filter(|_| detected) {
                tally.owners.push(owners[cell] as usize);
            }
            let counts = &mut tally.cells;
            match self.truth[cell] {
                OCCUPIED => {
                    counts.occupied += 1;
                    counts.detected += u64::from(detected);
                    counts.footprint_only += u64::from(decided && !detected);
                    // The ego alone, held to the same rule: its own sensor found the cell.
                    counts.ego_detected +=
                        u64::from(ego.get(cell) == Observed::Occupied && self.ego_decides_occupied(cell, &mut sources));
                    tally.by_distance.record(self.fusion.grid, self.senders, cell, detected);
                    if ego.get(cell) == Observed::Unknown {
                        counts.blind_occupied += 1;
                        counts.blind_detected += u64::from(detected);
                    }
                }
                SELF_REPORT => {
                    counts.self_report += 1;
                    counts.self_report_detected += u64::from(decided);
                    // Known only through self-report: no sensor found it occupied.
                    counts.self_report_only += u64::from(decided && !sensed());
                }
                _ => counts.false_positives += u64::from(decided),
            }
            if picture {
                values.probability.push(probability as f32);
                values.uncertainty.push(estimate.uncertainty() as f32);
                values.decision.push(decision);
            }
        }
        (tally, values)
    }

    /// Whether the ego's own observation alone, fused and judged as the job's
    /// grid is, decides `cell` Occupy: the ego-only baseline over the cells
    /// recall counts (`ego_occupied_recall`).
    fn ego_decides_occupied(&self, cell: usize, sources: &mut Vec<Source>) -> bool {
        let ego = &self.fusion.observations[..1];
        ego[0].get(cell) != Observed::Unknown && self.judged(ego, cell, sources).decision == Some(State::Occupied)
    }

    /// `cell` fused from `observations` (the job's, or a leading part of them)
    /// and judged by the job's rule: the memo's answer when it has one.
    fn judged(&self, observations: &[&dyn Evidence], cell: usize, sources: &mut Vec<Source>) -> Judged {
        if let Some(&judged) = self.memo.and_then(|memo| memo.get(observations, cell)) {
            return judged;
        }
        let fusion = CellFusion {
            observations,
            ..self.fusion
        };
        judge(fusion.estimate(cell, sources), self.decision)
    }
}
