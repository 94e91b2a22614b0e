//! The user's own system under test (`system_under_test`, docs/osi-sut.md):
//! `child` runs its process within time limits and reaps it on every path;
//! `driver` is the sink that feeds it each step's views over the protocol of
//! `sightline_reports::osi::system` and has the engine judge its answers.

mod child;
mod driver;

use anyhow::anyhow;
use sightline_dsl::{Check, Experiment, ObjectSelection, Scenario, SystemUnderTest};
use sightline_engine::outcome::SystemJudge;
use sightline_engine::{Outcome, Run};
use sightline_reports::osi::system::{PROTOCOL, PROTOCOL_ENV, VIEWS_ENV};

use driver::{Driver, Failure};

/// Runs `scenario`'s one point with `system` driven and judged at every
/// step; an error names the system, the step and what went wrong.
pub fn run(scenario: &Scenario, system: &SystemUnderTest, pool: &rayon::ThreadPool) -> anyhow::Result<Run> {
    let name = system.name();
    let failed = |failure: Failure| anyhow!("system `{name}` {}: {}", failure.when, failure.error);
    let env = [
        (PROTOCOL_ENV, PROTOCOL.to_string()),
        (VIEWS_ENV, system.sensors.len().to_string()),
    ];
    let Some(Experiment::World(world)) = scenario.points.first().map(|p| &p.setup.experiment) else {
        return Err(anyhow!("a system under test runs in a perception world only"));
    };
    let judge = SystemJudge::new(
        world,
        (system.agent, system.sensors.clone()),
        system.gate,
        selections(scenario),
    );
    let mut driver = Driver::start(system, judge, &env).map_err(failed)?;
    let mut outcome = pool.install(|| sightline_engine::simulate_point(scenario, 0, &mut driver));
    let metrics = driver.finish().map_err(failed)?;
    match &mut outcome {
        Outcome::World(world) => world.system = Some(metrics),
        _ => return Err(anyhow!("a system under test runs in a perception world only")),
    }
    Ok(Run {
        points: vec![outcome],
        replicates: vec![Vec::new()],
    })
}

/// The selections of `scenario`'s checks on the system's metrics (`sut_*`),
/// each once.
fn selections(scenario: &Scenario) -> Vec<ObjectSelection> {
    let mut selections: Vec<ObjectSelection> = Vec::new();
    for requirement in &scenario.requirements {
        let of_system = matches!(requirement.check, Check::Metric { metric, .. } if metric.of_system());
        if of_system && !requirement.objects.is_all() && !selections.contains(&requirement.objects) {
            selections.push(requirement.objects.clone());
        }
    }
    selections
}
