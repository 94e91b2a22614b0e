//! Running a whole scenario: every sweep point, sharing sampled data where it can.

use sightline_dsl::{Experiment, Scenario, Setup};

use crate::field::{self, Job};
use crate::metrics::FieldOutcome;

/// The outcome of every sweep point of a scenario, in point order.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// One outcome per [`Scenario::points`] entry.
    pub points: Vec<FieldOutcome>,
}

/// Simulates every point of `scenario`.
///
/// Points that differ only in fusion or decision settings share one pass over the
/// grid: the ground truth and every sensor's masses are sampled once, and each
/// method fuses the very same samples. Comparisons between methods at a sweep
/// point are therefore paired, not subject to sampling noise.
pub fn simulate(scenario: &Scenario) -> Run {
    let mut outcomes: Vec<Option<FieldOutcome>> = vec![None; scenario.points.len()];
    for group in shared_data_groups(scenario) {
        let first = &scenario.points[group[0]].setup;
        let Experiment::Field(field) = &first.experiment;
        let jobs: Vec<Job<'_>> = group
            .iter()
            .map(|&i| Job {
                fusion: &scenario.points[i].setup.fusion,
                decision: scenario.points[i].setup.decision,
            })
            .collect();
        for (&i, outcome) in group.iter().zip(field::run(first.seed, &first.grid, field, &jobs)) {
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
