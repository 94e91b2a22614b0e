//! Groups that share one pass over the grid: field points that differ only in
//! their mass model (`field.masses`, such as γ) share the grid, the truth and
//! the sensors, so one pass finds every row's sources once and samples them
//! with each group's model ([`field::run`]). Every outcome is the one its group
//! gives alone, bit for bit: a pass only saves the work the groups share.

use sightline_dsl::{Experiment, Field, Scenario, Setup};

use super::{Job, Outcome, Unit, simulate_unit};
use crate::field::{self, Sampling};

/// `groups` (with the seeds each needs) gathered into passes, in order of
/// first appearance: a field group joins the first pass whose groups differ
/// from it only in their mass model; any other group is a pass of its own.
pub(super) fn passes(scenario: &Scenario, groups: Vec<(Vec<usize>, u32)>) -> Vec<Vec<(Vec<usize>, u32)>> {
    let setup = |group: &[usize]| &scenario.points[group[0]].setup;
    let mut passes: Vec<Vec<(Vec<usize>, u32)>> = Vec::new();
    for group in groups {
        match passes
            .iter_mut()
            .find(|pass| same_pass(setup(&pass[0].0), setup(&group.0)))
        {
            Some(pass) => pass.push(group),
            None => passes.push(vec![group]),
        }
    }
    passes
}

/// Whether `a` and `b` are field points with the same seed, grid and field
/// but for the mass model.
fn same_pass(a: &Setup, b: &Setup) -> bool {
    let grid = |setup: &Setup| setup.occupancy.as_ref().map(|o| o.grid);
    match (&a.experiment, &b.experiment) {
        (Experiment::Field(x), Experiment::Field(y)) => {
            a.seed == b.seed
                && grid(a) == grid(b)
                && Field {
                    masses: y.masses,
                    ..x.clone()
                } == *y
        }
        _ => false,
    }
}

/// Simulates `units`, groups of one pass at one replicate, together: one
/// outcome per point of each unit's group, bit for bit what [`simulate_unit`]
/// gives each.
pub(super) fn simulate_pass(scenario: &Scenario, units: &[Unit]) -> Vec<Vec<Outcome>> {
    match units {
        [unit] => vec![simulate_unit(scenario, unit)],
        _ => {
            let groups: Vec<&[usize]> = units.iter().map(|unit| unit.group.as_slice()).collect();
            simulate_fields(scenario, &groups, units[0].seed(scenario))
        }
    }
}

/// Simulates field `groups` that [`passes`] puts in one pass, with `seed`:
/// one outcome per point of each group, in order.
pub(super) fn simulate_fields(scenario: &Scenario, groups: &[&[usize]], seed: u64) -> Vec<Vec<Outcome>> {
    let setup = |point: usize| &scenario.points[point].setup;
    let field = |point: usize| match &setup(point).experiment {
        Experiment::Field(field) => field,
        Experiment::World(_) => unreachable!("a pass shares a field"),
    };
    let grid = |point: usize| {
        &setup(point)
            .occupancy
            .as_ref()
            .expect("the compiler gives the field experiment a grid")
            .grid
    };
    let jobs: Vec<Vec<Job<'_>>> = groups
        .iter()
        .map(|group| {
            group
                .iter()
                .filter_map(|&point| setup(point).occupancy.as_ref())
                .map(|occupancy| Job {
                    fusion: &occupancy.fusion,
                    decision: occupancy.decision,
                })
                .collect()
        })
        .collect();
    let samplings: Vec<Sampling<'_>> = groups
        .iter()
        .zip(&jobs)
        .map(|(group, jobs)| Sampling {
            masses: field(group[0]).masses,
            jobs,
        })
        .collect();
    let first = groups[0][0];
    field::run(seed, grid(first), field(first), &samplings)
        .into_iter()
        .map(|outcomes| outcomes.into_iter().map(Outcome::Field).collect())
        .collect()
}
