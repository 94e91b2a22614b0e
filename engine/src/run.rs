//! Running a whole scenario: every sweep point, sharing sampled data where it can.

mod passes;
mod reading;

pub use reading::{RoadUserValue, Sample};

use std::collections::HashMap;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use sightline_dsl::{Agent, Check, Decision, Experiment, Fusion, Scenario, Setup, World};

use crate::metrics::FieldOutcome;
use crate::rng::{Derived, derived_seed};
use crate::semantic::{self, SemanticMetrics};
use crate::sink::{NoTrace, TraceSink};
use crate::trace::{Measured, SemanticStep, WorldStep};
use crate::world::{self, WorldOutcome};

/// One method to evaluate on shared data.
#[derive(Debug, Clone, Copy)]
pub struct Job<'a> {
    /// The fusion rule.
    pub fusion: &'a Fusion,
    /// The decision rule.
    pub decision: Decision,
}

/// What one sweep point measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "experiment", rename_all = "snake_case")]
pub enum Outcome {
    /// The field experiment.
    Field(FieldOutcome),
    /// A world's collective perception, with its semantic pipeline's
    /// measurements in a joint world ([`WorldOutcome::semantic`]).
    World(WorldOutcome),
    /// A world's semantic pipeline.
    Semantic(SemanticMetrics),
}

/// The outcome of every sweep point of a scenario, in point order.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// One outcome per [`Scenario::points`] entry.
    pub points: Vec<Outcome>,
    /// Per point, the outcomes of the replicates its checks over seeds need
    /// (replicate 1, 2, …; replicate 0 is the point's own outcome), empty when
    /// no check asks for any.
    pub replicates: Vec<Vec<Outcome>>,
}

/// Simulates every point of `scenario`.
///
/// Points that differ only in fusion or decision settings share one simulation:
/// the same ground truth and the same sampled observations, fused by each method.
/// Comparisons between methods at a sweep point are therefore paired, not subject
/// to sampling noise. Field groups that differ only in their mass model share
/// one pass over the grid (the rows' sensors and distances), each sampled as
/// it would be alone.
///
/// A point that a check over seeds (`seeds: n`) applies to is also simulated at
/// n − 1 replicate seeds derived from its own, in parallel; replicates of points
/// that share data share them too.
pub fn simulate(scenario: &Scenario) -> Run {
    simulate_all::<NoTrace>(scenario, &mut [], &mut |_| {})
}

/// [`simulate`], calling `done(points)` each time the `points` (with their
/// replicates) are simulated, for a progress display and the time each point
/// takes. The run is the same.
pub fn simulate_reporting(scenario: &Scenario, done: &mut dyn FnMut(&[usize])) -> Run {
    simulate_all::<NoTrace>(scenario, &mut [], done)
}

/// Simulates every point of `scenario` as [`simulate_reporting`] does, reporting
/// the steps of point `point` to `sink` (see [`trace`](crate::trace)): what
/// `sightline run` records. The run is the one [`simulate`] gives, bit for bit,
/// and the record is the one [`simulate_point`] gives: where the point shares its
/// sampled data with others, the sink sees only the point's own fused grid.
/// Replicates of checks over seeds are not recorded.
///
/// # Panics
///
/// If `point` is not an index of [`Scenario::points`].
pub fn simulate_traced(
    scenario: &Scenario,
    point: usize,
    sink: &mut impl TraceSink,
    done: &mut dyn FnMut(&[usize]),
) -> Run {
    assert!(
        point < scenario.points.len(),
        "point {point} is not a point of the scenario"
    );
    simulate_all(scenario, &mut [(point, sink)], done)
}

/// Simulates every point of `scenario` as [`simulate_reporting`] does, reporting
/// the steps of each point to its own sink, `sinks[point]`, as
/// [`simulate_traced`] reports one point's: points that share their sampled
/// data are simulated together once, each sink seeing only its own point's
/// fused grid. What `sightline run` records when the point to keep is known
/// only once the run is judged and every point shares one simulation
/// ([`shares_one_simulation`]). The run is the one [`simulate`] gives, bit for
/// bit, and each record the one [`simulate_point`] gives its point.
///
/// # Panics
///
/// If `sinks` does not hold one sink per point of [`Scenario::points`].
pub fn simulate_traced_each<S: TraceSink>(scenario: &Scenario, sinks: &mut [S], done: &mut dyn FnMut(&[usize])) -> Run {
    assert_eq!(sinks.len(), scenario.points.len(), "one sink per point of the scenario");
    let mut traced: Vec<(usize, &mut S)> = sinks.iter_mut().enumerate().collect();
    simulate_all(scenario, &mut traced, done)
}

/// Whether every point of `scenario` shares one simulation: the points differ
/// only in their fusion or decision settings, so that one pass simulates the
/// sampled data of all (and replicates of checks over seeds).
pub fn shares_one_simulation(scenario: &Scenario) -> bool {
    shared_data_groups(scenario).len() == 1
}

/// Simulates every point of `scenario`, reporting the steps of each to `sink`,
/// point after point in order ([`TraceSink::point`] before each): what
/// `sightline run` records with `record.points: all`. The run is the one
/// [`simulate`] gives, bit for bit: each point is simulated alone, as
/// [`simulate_point`] does (so points that share their sampled data are
/// simulated once each rather than once together), then the replicates of
/// checks over seeds, in parallel, unrecorded. `done(&[point])` after each
/// point; its replicates' time counts toward the last point's.
pub fn simulate_traced_all(scenario: &Scenario, sink: &mut impl TraceSink, done: &mut dyn FnMut(&[usize])) -> Run {
    let mut own: Vec<Option<Outcome>> = Vec::with_capacity(scenario.points.len());
    for point in 0..scenario.points.len() {
        sink.point(point);
        own.push(Some(simulate_point(scenario, point, sink)));
        if point + 1 < scenario.points.len() {
            done(&[point]);
        }
    }
    let (groups, replicates): (Vec<Unit>, Vec<Unit>) = units(scenario).into_iter().partition(|u| u.replicate == 0);
    let mut pieces: Vec<(Unit, Vec<Outcome>)> = groups
        .into_iter()
        .map(|unit| {
            let outcomes = unit
                .group
                .iter()
                .map(|&i| own[i].take().expect("each point belongs to one group"))
                .collect();
            (unit, outcomes)
        })
        .collect();
    pieces.par_extend(replicates.into_par_iter().map(|unit| {
        let outcomes = simulate_unit(scenario, &unit);
        (unit, outcomes)
    }));
    if let Some(last) = scenario.points.len().checked_sub(1) {
        done(&[last]);
    }
    assemble(scenario, pieces).expect("the pieces of every group, each once")
}

/// Every point, pass by pass (see [`passes`]), with the replicates checks over
/// seeds need; each `(point, sink)` of `traced` has the point's steps reported
/// to the sink; `done` after each pass.
fn simulate_all<S: TraceSink>(
    scenario: &Scenario,
    traced: &mut [(usize, &mut S)],
    done: &mut dyn FnMut(&[usize]),
) -> Run {
    let mut pieces = Vec::new();
    for pass in passes::passes(scenario, groups(scenario)) {
        let unit = |group: &[usize], replicate| Unit {
            group: group.to_vec(),
            replicate,
        };
        match &pass[..] {
            [(group, _)] => {
                let seed = unit(group, 0).seed(scenario);
                let sinks: Vec<(usize, &mut S)> = traced
                    .iter_mut()
                    .filter_map(|(point, sink)| {
                        let job = group.iter().position(|i| i == point)?;
                        Some((job, &mut **sink))
                    })
                    .collect();
                let outcomes = match sinks.is_empty() {
                    true => simulate_group(scenario, group, seed, &mut NoTrace),
                    false => simulate_group(scenario, group, seed, &mut JobSinks(sinks)),
                };
                pieces.push((unit(group, 0), outcomes));
            }
            // Fields, which report nothing to a sink.
            _ => {
                let own: Vec<Unit> = pass.iter().map(|(group, _)| unit(group, 0)).collect();
                let outcomes = passes::simulate_pass(scenario, &own);
                pieces.extend(own.into_iter().zip(outcomes));
            }
        }
        let most = pass.iter().map(|&(_, seeds)| seeds).max().unwrap_or(1);
        let replicates: Vec<Vec<Unit>> = (1..most)
            .map(|replicate| {
                pass.iter()
                    .filter(|&&(_, seeds)| replicate < seeds)
                    .map(|(group, _)| unit(group, replicate))
                    .collect()
            })
            .collect();
        pieces.par_extend(replicates.into_par_iter().flat_map_iter(|units| {
            let outcomes = passes::simulate_pass(scenario, &units);
            units.into_iter().zip(outcomes)
        }));
        let points: Vec<usize> = pass.iter().flat_map(|(group, _)| group.iter().copied()).collect();
        done(&points);
    }
    assemble(scenario, pieces).expect("the pieces of every group, each once")
}

/// A piece of a run that can be simulated on its own, on another machine: a
/// group of points that share their sampled data, at one of the seeds the
/// scenario needs. `sightline run --shard` simulates some of a scenario's units,
/// `sightline merge` [`assemble`]s them.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Unit {
    /// The points, indices into [`Scenario::points`], in order.
    pub group: Vec<usize>,
    /// 0 for the points' own seed, r ≥ 1 for the r-th replicate of checks over seeds.
    pub replicate: u32,
}

impl Unit {
    /// The seed the unit is simulated with.
    fn seed(&self, scenario: &Scenario) -> u64 {
        let seed = scenario.points[self.group[0]].setup.seed;
        match self.replicate {
            0 => seed,
            r => derived_seed(seed, Derived::Replicate, r),
        }
    }
}

/// Every unit of `scenario`, in the order [`simulate`] simulates them: group by
/// group, the group's own seed first, then its replicates.
pub fn units(scenario: &Scenario) -> Vec<Unit> {
    groups(scenario)
        .into_iter()
        .flat_map(|(group, seeds)| {
            (0..seeds).map(move |replicate| Unit {
                group: group.clone(),
                replicate,
            })
        })
        .collect()
}

/// Simulates `unit` of `scenario`: one outcome per point of its group, in
/// order, bit for bit those [`simulate`] gives.
///
/// # Panics
///
/// If `unit` is not one of [`units`]`(scenario)`.
pub fn simulate_unit(scenario: &Scenario, unit: &Unit) -> Vec<Outcome> {
    simulate_group(scenario, &unit.group, unit.seed(scenario), &mut NoTrace)
}

/// Why simulated units do not make up a run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AssembleError {
    /// A unit of the scenario is not among them.
    #[error("the outcomes of points {:?} at replicate {} are missing", .0.group, .0.replicate)]
    Missing(Unit),
    /// A unit appears twice, or is not a unit of the scenario.
    #[error("the outcomes of points {:?} at replicate {} are not expected (twice, or not of this scenario)", .0.group, .0.replicate)]
    Unexpected(Unit),
    /// A unit's outcomes do not match its points.
    #[error("the outcomes of points {:?} at replicate {} do not match the points", .0.group, .0.replicate)]
    Mismatched(Unit),
}

/// The run that every unit of `scenario`, each simulated once (in any order, by
/// any machine), makes up: equal to [`simulate`]`(scenario)`.
pub fn assemble(
    scenario: &Scenario,
    pieces: impl IntoIterator<Item = (Unit, Vec<Outcome>)>,
) -> Result<Run, AssembleError> {
    let mut expected: HashMap<Unit, Option<Vec<Outcome>>> = units(scenario).into_iter().map(|u| (u, None)).collect();
    for (unit, outcomes) in pieces {
        // A unit of the scenario names only its points, so it is looked up
        // before its points are.
        let Some(slot @ None) = expected.get_mut(&unit) else {
            return Err(AssembleError::Unexpected(unit));
        };
        let fits = outcomes.len() == unit.group.len()
            && unit
                .group
                .iter()
                .zip(&outcomes)
                .all(|(&i, outcome)| measures(&scenario.points[i].setup.experiment, outcome));
        if !fits {
            return Err(AssembleError::Mismatched(unit));
        }
        *slot = Some(outcomes);
    }
    let mut points: Vec<Option<Outcome>> = vec![None; scenario.points.len()];
    let mut replicates: Vec<Vec<Outcome>> = vec![Vec::new(); scenario.points.len()];
    for unit in units(scenario) {
        let outcomes = expected
            .remove(&unit)
            .flatten()
            .ok_or_else(|| AssembleError::Missing(unit.clone()))?;
        for (&i, outcome) in unit.group.iter().zip(outcomes) {
            match unit.replicate {
                0 => points[i] = Some(outcome),
                _ => replicates[i].push(outcome),
            }
        }
    }
    Ok(Run {
        points: points
            .into_iter()
            .map(|o| o.expect("every point belongs to one group"))
            .collect(),
        replicates,
    })
}

/// Whether `outcome` is what a point of `experiment` measures.
fn measures(experiment: &Experiment, outcome: &Outcome) -> bool {
    match (experiment, outcome) {
        (Experiment::Field(_), Outcome::Field(_)) => true,
        (Experiment::World(w), Outcome::World(o)) => w.perception.is_some() && w.is_joint() == o.semantic.is_some(),
        (Experiment::World(w), Outcome::Semantic(_)) => w.perception.is_none(),
        _ => false,
    }
}

/// The groups of points that share sampled data, each with the seeds its checks
/// over seeds need (the most any of its points needs; 1: its own only).
fn groups(scenario: &Scenario) -> Vec<(Vec<usize>, u32)> {
    let seeds = seeds_needed(scenario);
    shared_data_groups(scenario)
        .into_iter()
        .map(|group| {
            let most = group.iter().map(|&i| seeds[i]).max().unwrap_or(1);
            (group, most)
        })
        .collect()
}

/// Per point, the most seeds a check over seeds applying to it asks for (1: none).
fn seeds_needed(scenario: &Scenario) -> Vec<u32> {
    let mut seeds = vec![1; scenario.points.len()];
    for requirement in &scenario.requirements {
        if let Check::Metric {
            over_seeds: Some(over), ..
        } = requirement.check
        {
            for &point in &requirement.points {
                seeds[point] = seeds[point].max(over.seeds);
            }
        }
    }
    seeds
}

/// Passes a group's record on to sinks that each want one job's, `(job,
/// sink)`: each step's fused grids cut down to that job's.
struct JobSinks<'s, S>(Vec<(usize, &'s mut S)>);

impl<S: TraceSink> TraceSink for JobSinks<'_, S> {
    fn point(&mut self, point: usize) {
        for (_, sink) in &mut self.0 {
            sink.point(point);
        }
    }

    fn start(&mut self, agents: &[Agent]) {
        for (_, sink) in &mut self.0 {
            sink.start(agents);
        }
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.0.iter().any(|(_, sink)| sink.wants_grids(step))
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        for (job, sink) in &mut self.0 {
            let measured = step.measured.map(|m| Measured {
                fused: &m.fused[*job..=*job],
                ..m
            });
            sink.world_step(&WorldStep { measured, ..*step });
        }
    }

    /// Only once every sink has: the others want the rest of the run.
    fn gave_up(&self) -> bool {
        self.0.iter().all(|(_, sink)| sink.gave_up())
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        for (_, sink) in &mut self.0 {
            sink.semantic_step(step);
        }
    }
}

/// Simulates point `point` of `scenario` alone, reporting each step to `sink`
/// (see [`trace`](crate::trace)). The outcome is the one [`simulate`] gives the
/// point, bit for bit: a point's sampled data do not depend on the points it
/// shares them with, and a sink only observes.
///
/// # Panics
///
/// If `point` is not an index of [`Scenario::points`].
pub fn simulate_point(scenario: &Scenario, point: usize, sink: &mut impl TraceSink) -> Outcome {
    let mut outcomes = simulate_group(scenario, &[point], scenario.points[point].setup.seed, sink);
    outcomes.pop().expect("one outcome per point")
}

/// Simulates the points of `group`, which share their sampled data, once with
/// `seed`; one outcome per point, in group order.
fn simulate_group(scenario: &Scenario, group: &[usize], seed: u64, sink: &mut impl TraceSink) -> Vec<Outcome> {
    let first = &scenario.points[group[0]].setup;
    // Every point of a group shares its grid; each has its own fusion.
    let jobs: Vec<Job<'_>> = group
        .iter()
        .filter_map(|&i| scenario.points[i].setup.occupancy.as_ref())
        .map(|occupancy| Job {
            fusion: &occupancy.fusion,
            decision: occupancy.decision,
        })
        .collect();
    match (&first.experiment, &first.occupancy) {
        // The field experiment has no steps: it reports nothing to the sink.
        (Experiment::Field(_), Some(_)) => passes::simulate_fields(scenario, &[group], seed)
            .pop()
            .expect("one group's outcomes"),
        (Experiment::World(w), occupancy) => match (&w.perception, &w.semantic, occupancy) {
            (Some(perception), None, Some(occupancy)) => {
                world::run(seed, &occupancy.grid, (w, &w.agents), perception, &jobs, &mut (), sink)
                    .into_iter()
                    .map(Outcome::World)
                    .collect()
            }
            (Some(perception), Some(s), Some(occupancy)) => {
                joint(seed, (w, perception, s), &occupancy.grid, &jobs, sink)
            }
            // The points of a semantic group are the same configuration: one run serves all.
            (None, Some(s), None) => vec![Outcome::Semantic(semantic::run(seed, w, s, sink)); group.len()],
            _ => unreachable!("the compiler gives collective perception a grid, and the semantic pipeline none"),
        },
        (Experiment::Field(_), None) => unreachable!("the compiler gives the field experiment a grid"),
    }
}

/// A joint world's group at `seed`: collective perception with every job on
/// the scene of the world's agents and its generated traffic, the semantic
/// pipeline running on it; one outcome per job, each with the pipeline's
/// measurements and its road users' times in that job's grid.
fn joint(
    seed: u64,
    (w, perception, s): (&World, &sightline_dsl::Perception, &sightline_dsl::Semantic),
    grid: &sightline_dsl::Grid,
    jobs: &[Job<'_>],
    sink: &mut impl TraceSink,
) -> Vec<Outcome> {
    let agents = semantic::scene(seed, w);
    let ground = semantic::Ground::new(w, s);
    // The pipeline's random streams are those of a seed derived from the
    // point's, apart from the grid's.
    let pipeline_seed = derived_seed(seed, Derived::Pipeline, 1);
    let mut layer = semantic::Layer::new(pipeline_seed, (w, s), &agents, &ground, jobs.len());
    let outcomes = world::run(seed, grid, (w, &agents), perception, jobs, &mut layer, sink);
    outcomes
        .into_iter()
        .zip(layer.finish(0))
        .map(|(outcome, metrics)| {
            Outcome::World(WorldOutcome {
                semantic: Some(Box::new(metrics)),
                ..outcome
            })
        })
        .collect()
}

/// Point indices grouped by identical sampled data (seed, grid, experiment), in
/// order of first appearance: points that differ only in fusion or decision.
fn shared_data_groups(scenario: &Scenario) -> Vec<Vec<usize>> {
    let grid = |setup: &Setup| setup.occupancy.as_ref().map(|o| o.grid);
    let same_data = |a: &Setup, b: &Setup| a.seed == b.seed && grid(a) == grid(b) && a.experiment == b.experiment;
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, point) in scenario.points.iter().enumerate() {
        match groups
            .iter_mut()
            .find(|g| same_data(&scenario.points[g[0]].setup, &point.setup))
        {
            Some(group) => group.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}
