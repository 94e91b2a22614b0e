//! Running a whole scenario: every sweep point, sharing sampled data where it can.

use serde::Serialize;
use sightline_dsl::{Agent, Decision, Experiment, Fusion, Metric, Scenario, Setup};

use crate::field;
use crate::metrics::{FieldOutcome, MassAudit};
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
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "experiment", rename_all = "snake_case")]
pub enum Outcome {
    /// The field experiment.
    Field(FieldOutcome),
    /// A world's collective perception.
    World(WorldOutcome),
    /// A world's semantic pipeline.
    Semantic(SemanticMetrics),
}

impl Outcome {
    /// The value of `metric`, or `None` where it is not defined for this run.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        match self {
            Self::Field(o) => o.metrics.value(metric),
            Self::World(o) => o.metrics.value(metric),
            Self::Semantic(m) => m.value(metric),
        }
    }

    /// Every defined metric in documentation order.
    pub fn values(&self) -> Vec<(Metric, f64)> {
        Metric::ALL
            .iter()
            .filter_map(|&m| self.value(m).map(|v| (m, v)))
            .collect()
    }

    /// The mass-function audit of every fused cell; `None` where nothing is fused.
    pub fn audit(&self) -> Option<&MassAudit> {
        match self {
            Self::Field(o) => Some(&o.audit),
            Self::World(o) => Some(&o.audit),
            Self::Semantic(_) => None,
        }
    }
}

/// The outcome of every sweep point of a scenario, in point order.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// One outcome per [`Scenario::points`] entry.
    pub points: Vec<Outcome>,
}

/// Simulates every point of `scenario`.
///
/// Points that differ only in fusion or decision settings share one simulation:
/// the same ground truth and the same sampled observations, fused by each method.
/// Comparisons between methods at a sweep point are therefore paired, not subject
/// to sampling noise.
pub fn simulate(scenario: &Scenario) -> Run {
    simulate_all(scenario, None, &mut NoTrace)
}

/// Simulates every point of `scenario` as [`simulate`] does, reporting the steps
/// of point `point` to `sink` (see [`trace`](crate::trace)): what `sightline run`
/// records. The run is the one [`simulate`] gives, bit for bit, and the record is
/// the one [`simulate_point`] gives: where the point shares its sampled data with
/// others, the sink sees only the point's own fused grid.
///
/// # Panics
///
/// If `point` is not an index of [`Scenario::points`].
pub fn simulate_traced(scenario: &Scenario, point: usize, sink: &mut impl TraceSink) -> Run {
    assert!(
        point < scenario.points.len(),
        "point {point} is not a point of the scenario"
    );
    simulate_all(scenario, Some(point), sink)
}

/// Every point, group by group; the group holding point `traced` reports to `sink`.
fn simulate_all(scenario: &Scenario, traced: Option<usize>, sink: &mut impl TraceSink) -> Run {
    let mut outcomes: Vec<Option<Outcome>> = vec![None; scenario.points.len()];
    for group in shared_data_groups(scenario) {
        let results = match traced.and_then(|point| group.iter().position(|&i| i == point)) {
            Some(job) => simulate_group(scenario, &group, &mut OneJob { sink: &mut *sink, job }),
            None => simulate_group(scenario, &group, &mut NoTrace),
        };
        for (&i, outcome) in group.iter().zip(results) {
            outcomes[i] = Some(outcome);
        }
    }
    Run {
        points: outcomes
            .into_iter()
            .map(|o| o.expect("every point belongs to one group"))
            .collect(),
    }
}

/// Passes a group's record on to a sink that wants one job's: each step's fused
/// grids cut down to that job's.
struct OneJob<'s, S> {
    sink: &'s mut S,
    job: usize,
}

impl<S: TraceSink> TraceSink for OneJob<'_, S> {
    fn start(&mut self, agents: &[Agent]) {
        self.sink.start(agents);
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.sink.wants_grids(step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        let measured = step.measured.map(|m| Measured {
            fused: &m.fused[self.job..=self.job],
            ..m
        });
        self.sink.world_step(&WorldStep { measured, ..*step });
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.sink.semantic_step(step);
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
    let mut outcomes = simulate_group(scenario, &[point], sink);
    outcomes.pop().expect("one outcome per point")
}

/// Simulates the points of `group`, which share their sampled data, once; one
/// outcome per point, in group order.
fn simulate_group(scenario: &Scenario, group: &[usize], sink: &mut impl TraceSink) -> Vec<Outcome> {
    let first = &scenario.points[group[0]].setup;
    let jobs: Vec<Job<'_>> = group
        .iter()
        .map(|&i| Job {
            fusion: &scenario.points[i].setup.fusion,
            decision: scenario.points[i].setup.decision,
        })
        .collect();
    match &first.experiment {
        // The field experiment has no steps: it reports nothing to the sink.
        Experiment::Field(f) => field::run(first.seed, &first.grid, f, &jobs)
            .into_iter()
            .map(Outcome::Field)
            .collect(),
        Experiment::World(w) => match (&w.perception, &w.semantic) {
            (Some(perception), _) => world::run(first.seed, &first.grid, w, perception, &jobs, sink)
                .into_iter()
                .map(Outcome::World)
                .collect(),
            // Fusion settings do not touch the semantic pipeline: one run serves all.
            (None, Some(s)) => vec![Outcome::Semantic(semantic::run(first.seed, w, s, sink)); jobs.len()],
            (None, None) => unreachable!("the compiler requires `perception` or `semantic`"),
        },
    }
}

/// Point indices grouped by identical sampled data (seed, grid, experiment), in
/// order of first appearance.
fn shared_data_groups(scenario: &Scenario) -> Vec<Vec<usize>> {
    let same_data = |a: &Setup, b: &Setup| a.seed == b.seed && a.grid == b.grid && a.experiment == b.experiment;
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
