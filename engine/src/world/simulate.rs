//! The step loop of a world: kinematics, footprints, each cooperating agent's
//! observation, and the fused grid of every method, tallied against ground truth.
//!
//! Observations run in parallel across agents (each draws from its own random
//! streams); fusion runs in parallel over fixed-size chunks of the observed cells,
//! merged in chunk order. Results do not depend on the thread count.

use rand::rngs::ChaCha8Rng;
use rayon::prelude::*;
use sightline_dsl::{AgentKind, Grid, Motion, Perception, World};

use super::fuse::{self, CellFusion};
use super::localization::{self, PoseEstimator};
use super::metrics::{CellTally, FusedCell, Snapshot, WorldMetrics, WorldOutcome, WorldTally};
use super::motion::{self, Kinematics};
use super::observe::{self, Observation, Observed, Sightings, StepScene};
use super::raster::{Raster, box_cells, cell_center};
use super::sight::{self, Bodies, Body, Occluders};
use crate::fusion::{Estimate, State, decide, pignistic};
use crate::idealisation::Idealisation;
use crate::math::{Pose, Vector};
use crate::rng::{Purpose, stream};
use crate::run::Job;
use crate::sink::TraceSink;
use crate::trace::{CooperatorStep, FusedGrid, FusedStep, Measured, WorldStep};

/// Each step's grids stand alone.
pub(crate) const MEMORYLESS: Idealisation = Idealisation {
    id: "world.memoryless",
    text: "Each step's grids hold that step's observations only: no agent accumulates evidence over time or \
           tracks objects.",
};

/// Grids are exchanged without a radio.
pub(crate) const LOSSLESS_EXCHANGE: Idealisation = Idealisation {
    id: "world.lossless-exchange",
    text: "Every cooperating agent's grid reaches the ego at the step it is observed, complete: collective \
           perception does not model the radio (loss, delay, bandwidth), and `check` refuses `v2x` in it \
           (issue 16).",
};

/// Agents sense together.
pub(crate) const SYNCHRONOUS: Idealisation = Idealisation {
    id: "world.synchronous",
    text: "Every agent senses at the same instants, the simulation steps, and processes what it senses without \
           delay.",
};

/// A cooperating roadside unit knows where it stands.
pub(crate) const SURVEYED: Idealisation = Idealisation {
    id: "world.surveyed-rsu",
    text: "A cooperating roadside unit places its grid with its true, surveyed pose.",
};

/// The idealisations of a world measuring collective perception, besides those
/// of its options (pose filter, car following, fusion method).
pub(crate) fn idealisations(world: &World, perception: &Perception) -> Vec<Idealisation> {
    let mut listed = vec![
        sight::PLANAR,
        motion::ON_THEIR_WAY,
        SYNCHRONOUS,
        sight::ONE_RAY,
        observe::DETECTIONS,
        observe::NOISE,
        observe::FREE_SPACE,
        observe::SELF_REPORT,
    ];
    let cooperators = || perception.cooperating.iter().map(|&i| &world.agents[i]);
    if cooperators().any(|a| matches!(a.motion, Motion::Fixed { .. })) {
        listed.push(SURVEYED);
    }
    if cooperators().any(|a| !matches!(a.motion, Motion::Fixed { .. })) {
        let noise = &world.localization;
        listed.push(if noise.position_sigma == 0.0 && noise.heading_sigma == 0.0 {
            localization::EXACT
        } else {
            localization::WHITE_NOISE
        });
    }
    if world.agents.iter().any(|a| a.kind == AgentKind::Rsu) {
        listed.push(sight::RSU_TRANSPARENT);
    }
    listed.extend([MEMORYLESS, LOSSLESS_EXCHANGE, fuse::INVERSE_MODEL]);
    listed
}

/// Cells fused per parallel task.
const CHUNK: usize = 4096;

/// Ground truth of a cell.
const FREE: u8 = 0;
const OCCUPIED: u8 = 1;
const EXCLUDED: u8 = 2;

/// A cooperating agent's state across steps.
struct Cooperator {
    agent: usize,
    observation: Observation,
    estimator: PoseEstimator,
    localization: ChaCha8Rng,
    detections: ChaCha8Rng,
    present: bool,
    /// The pose it placed its observation with.
    estimate: Pose,
}

/// Fused values of the observed cells of one step, in cell order.
#[derive(Debug, Clone, Default)]
struct CellValues {
    probability: Vec<f32>,
    uncertainty: Vec<f32>,
    decision: Vec<Option<State>>,
}

/// Runs a world's collective perception once and evaluates every job on the same
/// observations, reporting each step to `sink`.
pub fn run(
    seed: u64,
    grid: &Grid,
    world: &World,
    perception: &Perception,
    jobs: &[Job<'_>],
    sink: &mut impl TraceSink,
) -> Vec<WorldOutcome> {
    let cells = grid.cells();
    let occluders = Occluders::new(&world.occluders);
    let mut raster = Raster::new(*grid, &world.occluders);
    let mut kinematics = Kinematics::new(&world.agents, world.step, world.driving);
    let mut cooperators: Vec<Cooperator> = perception
        .cooperating
        .iter()
        .map(|&agent| Cooperator {
            agent,
            observation: Observation::new(cells),
            estimator: PoseEstimator::new(world.localization),
            localization: stream(seed, Purpose::Localization, agent as u64),
            detections: stream(seed, Purpose::Detections, agent as u64),
            present: false,
            estimate: Pose::IDENTITY,
        })
        .collect();
    let mut states = Vec::new();
    // Per cell: 0 free, 1 truly occupied, 2 excluded from the metrics (occluders
    // and the ego's own footprint).
    let mut truth = vec![FREE; cells];
    let mut truth_cells: Vec<usize> = Vec::new();
    let mut observed = vec![false; cells];
    let mut observed_cells: Vec<usize> = Vec::new();
    let in_region: Vec<bool> = match perception.region {
        None => vec![true; cells],
        Some(([x, y], radius)) => (0..cells)
            .map(|cell| (cell_center(grid, cell) - Vector::new(x, y)).length() <= radius)
            .collect(),
    };
    let mut tallies = vec![WorldTally::default(); jobs.len()];
    let mut snapshots: Vec<Option<Snapshot>> = vec![None; jobs.len()];
    let mut by_step: Vec<Vec<(f64, CellTally)>> = vec![Vec::new(); jobs.len()];
    // The fused values of a pictured step, per job; kept for one step only.
    let mut values = vec![CellValues::default(); jobs.len()];
    sink.start(&world.agents);
    let (mut steps, mut ego_observed, mut joint_observed) = (0u64, 0u64, 0u64);
    let mut sightings = Sightings::default();
    let (mut error_sum, mut error_count) = (0.0, 0u64);

    for k in 0..world.steps {
        kinematics.advance(k, &mut states);
        let bodies = Bodies::of_scene(&world.agents, &states);
        raster.set_bodies(bodies.all());
        // Agents update their pose estimates whether or not the ego is there.
        let scene = StepScene {
            grid,
            occluders: &occluders,
            bodies: &bodies,
            raster: &raster,
        };
        cooperators.par_iter_mut().for_each(|c| {
            c.present = false;
            let Some(state) = states[c.agent] else { return };
            let agent = &world.agents[c.agent];
            let estimate = match agent.motion {
                // A roadside unit's position is surveyed.
                Motion::Fixed { .. } => state.pose,
                Motion::Along { .. } | Motion::Trace { .. } => {
                    c.estimator.estimate(state.pose, world.step, &mut c.localization)
                }
            };
            c.estimate = estimate;
            c.observation
                .observe(&scene, (c.agent, agent), state.pose, estimate, &mut c.detections);
            c.present = true;
        });
        let time = k as f64 * world.step;
        if states[perception.ego].is_none() {
            sink.world_step(&WorldStep {
                step: k,
                time,
                agents: &states,
                cooperators: &cooperation(&cooperators),
                measured: None,
            });
            continue;
        }
        steps += 1;
        for c in cooperators.iter().filter(|c| c.present) {
            sightings.add(c.observation.sightings);
            let truth = states[c.agent].expect("a present cooperator is in the scene").pose;
            error_sum += (c.estimate.translation - truth.translation).length();
            error_count += 1;
        }

        for &cell in &truth_cells {
            truth[cell] = FREE;
        }
        truth_cells.clear();
        // The ego's footprint first, so that no other body claims its cells.
        let mut footprints: Vec<&Body> = bodies.all().iter().collect();
        footprints.sort_by_key(|b| b.agent != perception.ego);
        for body in footprints {
            for cell in box_cells(grid, body) {
                if in_region[cell] && !raster.is_occluder(cell) && truth[cell] == FREE {
                    truth[cell] = if body.agent == perception.ego {
                        EXCLUDED
                    } else {
                        OCCUPIED
                    };
                    truth_cells.push(cell);
                }
            }
        }
        for &cell in &observed_cells {
            observed[cell] = false;
        }
        observed_cells.clear();
        let present: Vec<&Observation> = cooperators
            .iter()
            .filter(|c| c.present)
            .map(|c| &c.observation)
            .collect();
        let counted = |cell: usize| in_region[cell] && !raster.is_occluder(cell) && truth[cell] != EXCLUDED;
        for observation in &present {
            for &cell in observation.touched() {
                if counted(cell) && !observed[cell] {
                    observed[cell] = true;
                    observed_cells.push(cell);
                }
            }
        }
        let ego = &cooperators[0].observation;
        let ego_step = ego.touched().iter().filter(|&&c| counted(c)).count() as u64;
        ego_observed += ego_step;
        joint_observed += observed_cells.len() as u64;
        // Occupied cells nobody observed count as missed (and as blind: the ego did
        // not observe them either).
        let unseen = truth_cells
            .iter()
            .filter(|&&c| truth[c] == OCCUPIED && !observed[c])
            .count() as u64;

        let snapshot = k == perception.snapshot_step;
        let wants_grids = sink.wants_grids(k);
        let mut step_cells = Vec::with_capacity(jobs.len());
        for (j, job) in jobs.iter().enumerate() {
            let tallier = Tallier {
                fusion: CellFusion {
                    grid,
                    rule: &job.fusion.rule,
                    observations: &present,
                    occupied: perception.occupied,
                    free: perception.free,
                },
                threshold: job.decision.threshold,
                truth: &truth,
            };
            let chunks: Vec<(WorldTally, CellValues)> = observed_cells
                .par_chunks(CHUNK)
                .map(|chunk| tallier.tally(chunk, snapshot || wants_grids))
                .collect();
            let mut cells = CellTally {
                occupied: unseen,
                blind_occupied: unseen,
                ..CellTally::default()
            };
            // Chunk by chunk, so that the floating-point sums do not depend on
            // the thread count.
            for (chunk, _) in &chunks {
                cells.add(&chunk.cells);
                tallies[j].estimates.merge(&chunk.estimates);
            }
            tallies[j].cells.add(&cells);
            if snapshot || wants_grids {
                let values = &mut values[j];
                values.probability.clear();
                values.uncertainty.clear();
                values.decision.clear();
                for (_, chunk) in &chunks {
                    values.probability.extend(&chunk.probability);
                    values.uncertainty.extend(&chunk.uncertainty);
                    values.decision.extend(&chunk.decision);
                }
            }
            if snapshot {
                snapshots[j] = Some(picture(k, &truth, &raster, ego, &observed_cells, &values[j]));
            }
            by_step[j].push((time, cells));
            step_cells.push(cells);
        }
        let fused: Vec<FusedStep<'_>> = step_cells
            .into_iter()
            .zip(&values)
            .map(|(cells, values)| FusedStep {
                cells,
                grid: wants_grids.then(|| FusedGrid {
                    cells: &observed_cells,
                    probability: &values.probability,
                    uncertainty: &values.uncertainty,
                }),
            })
            .collect();
        sink.world_step(&WorldStep {
            step: k,
            time,
            agents: &states,
            cooperators: &cooperation(&cooperators),
            measured: Some(Measured {
                ego_observed: ego_step,
                joint_observed: observed_cells.len() as u64,
                fused: &fused,
            }),
        });
    }

    tallies
        .iter()
        .zip(jobs)
        .zip(snapshots)
        .zip(by_step)
        .map(|(((tally, job), snapshot), by_step)| {
            let (mean_uncertainty, conflict, audit) = tally.estimates.finish(job.fusion.rule.is_evidential());
            WorldOutcome {
                metrics: WorldMetrics {
                    steps,
                    occupied: tally.cells.occupied,
                    detected: tally.cells.detected,
                    false_positives: tally.cells.false_positives,
                    blind_occupied: tally.cells.blind_occupied,
                    blind_detected: tally.cells.blind_detected,
                    ego_observed,
                    joint_observed,
                    sightings,
                    localization_error: (error_count > 0).then(|| error_sum / error_count as f64),
                    mean_uncertainty,
                    conflict,
                },
                audit,
                snapshot,
                by_step,
            }
        })
        .collect()
}

/// The cooperating agents in the scene, for the step record.
fn cooperation(cooperators: &[Cooperator]) -> Vec<CooperatorStep<'_>> {
    cooperators
        .iter()
        .filter(|c| c.present)
        .map(|c| CooperatorStep {
            agent: c.agent,
            estimate: c.estimate,
            observation: &c.observation,
        })
        .collect()
}

/// Tallies one method's fused grid of one step against the truth.
struct Tallier<'a> {
    fusion: CellFusion<'a>,
    threshold: f64,
    truth: &'a [u8],
}

impl Tallier<'_> {
    /// Tallies a chunk of observed cells; with `picture`, also returns their fused
    /// values.
    fn tally(&self, cells: &[usize], picture: bool) -> (WorldTally, CellValues) {
        let mut tally = WorldTally::default();
        let mut values = CellValues::default();
        let mut sources = Vec::with_capacity(self.fusion.observations.len());
        let ego = self.fusion.observations[0];
        for &cell in cells {
            let estimate = self.fusion.estimate(cell, &mut sources);
            tally.estimates.record(&estimate);
            let decision = decide(estimate.decision_mass(), self.threshold);
            let decided = decision == Some(State::Occupied);
            let blind = ego.get(cell) == Observed::Unknown;
            let counts = &mut tally.cells;
            if self.truth[cell] == OCCUPIED {
                counts.occupied += 1;
                counts.detected += u64::from(decided);
                if blind {
                    counts.blind_occupied += 1;
                    counts.blind_detected += u64::from(decided);
                }
            } else if decided {
                counts.false_positives += 1;
            }
            if picture {
                values.probability.push(match estimate {
                    Estimate::Occupancy(o) => o.probability as f32,
                    Estimate::Evidential { combination, .. } => pignistic(combination.mass) as f32,
                });
                values.uncertainty.push(estimate.uncertainty() as f32);
                values.decision.push(decision);
            }
        }
        (tally, values)
    }
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
            (false, OCCUPIED) => 1,
            // Occluders are handled above: what else is excluded is the ego.
            (false, EXCLUDED) => 3,
            _ => 0,
        })
        .collect();
    let ego_picture = (0..truth.len())
        .map(|cell| match ego.get(cell) {
            Observed::Unknown => 0,
            Observed::Free => 1,
            Observed::Occupied => 2,
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
