//! The `system_under_test` section: the program, the agent and sensors it
//! serves, its limits; and what a scenario with one must not ask for (several
//! sweep points, `vary`, a recording, checks over seeds), since the system is
//! run once, on one point, as sightline's own models are not.

use super::context::{Context, locate};
use crate::error::ErrorKind;
use crate::model::{Check, Experiment, Point, Requirement, SystemUnderTest};
use crate::path::Path;
use crate::raw::range;
use crate::raw::{RawScenario, RawSystemUnderTest};

/// Arguments a command may have, its program included.
const MAX_ARGUMENTS: usize = 256;
/// Bytes an argument may have.
const MAX_ARGUMENT_BYTES: usize = 4096;
/// Wall-clock seconds a step may take when the file does not say.
const DEFAULT_STEP_TIMEOUT: f64 = 5.0;
/// Matching gate when the file does not say, metres.
const DEFAULT_GATE: f64 = 2.0;
/// Least existence probability judged when the file does not say.
const DEFAULT_MIN_EXISTENCE: f64 = 0.5;

/// Compiles `system_under_test` against the compiled points and requirements;
/// refuses a metric of the system's in a scenario without one.
pub(super) fn system_under_test(
    ctx: &mut Context<'_>,
    raw: &RawScenario,
    points: Option<&[Point]>,
    requirements: &[Requirement],
) -> Option<SystemUnderTest> {
    let Some(system) = raw.system_under_test.as_ref() else {
        refuse_system_metrics(ctx, &checks(ctx, raw, requirements));
        return None;
    };
    let path = Path::root().key("system_under_test");
    let command_ok = command(ctx, &system.command, &path.key("command"));
    let step_timeout = system.step_timeout.unwrap_or(DEFAULT_STEP_TIMEOUT);
    let gate = system.gate.unwrap_or(DEFAULT_GATE);
    let min_existence = system.min_existence.unwrap_or(DEFAULT_MIN_EXISTENCE);
    let limits_ok = ctx.within(&path.key("step_timeout"), step_timeout, range::SUT_TIMEOUT)
        & ctx.within(&path.key("gate"), gate, range::SUT_GATE)
        & ctx.within(&path.key("min_existence"), min_existence, range::PROBABILITY);
    let alone_ok = runs_once(ctx, raw, &checks(ctx, raw, requirements));
    let (agent, sensors) = served(ctx, system, points?, &path)?;
    let host_ok = host_unselected(ctx, raw, &system.agent);
    (command_ok && limits_ok && alone_ok && host_ok).then(|| SystemUnderTest {
        command: system.command.clone(),
        agent,
        agent_id: system.agent.clone(),
        sensors,
        step_timeout,
        gate,
        min_existence,
    })
}

fn command(ctx: &mut Context<'_>, command: &[String], path: &Path) -> bool {
    let problem = if command.is_empty() {
        Some("a command names its program: give at least one element".to_string())
    } else if command.len() > MAX_ARGUMENTS {
        Some(format!(
            "a command has at most {MAX_ARGUMENTS} elements; found {}",
            command.len()
        ))
    } else if command[0].is_empty() {
        Some("the program's name is empty".to_string())
    } else {
        command
            .iter()
            .find(|a| a.len() > MAX_ARGUMENT_BYTES || a.contains('\0'))
            .map(|_| format!("an argument has at most {MAX_ARGUMENT_BYTES} bytes and no NUL character"))
    };
    if let Some(problem) = &problem {
        ctx.error(path, ErrorKind::Invalid(problem.clone()));
    }
    problem.is_none()
}

/// Errors where the scenario asks the run to be repeated or searched, which a
/// system under test is not.
fn runs_once(ctx: &mut Context<'_>, raw: &RawScenario, requirements: &[(Path, &Requirement)]) -> bool {
    let mut ok = true;
    let mut refuse = |ctx: &mut Context<'_>, at: &Path, why: &str| {
        ctx.error(at, ErrorKind::Invalid(why.into()));
        ok = false;
    };
    if !raw.vary.is_empty() {
        refuse(
            ctx,
            &Path::root().key("vary"),
            "`sightline falsify` does not drive a system under test: leave out `vary` or `system_under_test`",
        );
    }
    if raw.record.is_some() {
        refuse(
            ctx,
            &Path::root().key("record"),
            "a run with a system under test is not recorded: leave out `record` or `system_under_test`",
        );
    }
    for (check, requirement) in requirements {
        if matches!(
            requirement.check,
            Check::Metric {
                over_seeds: Some(_),
                ..
            }
        ) {
            refuse(
                ctx,
                &check.key("seeds"),
                "a system under test is run once, at the scenario's seed: a check over seeds needs it run at \
                 each, which sightline does not do",
            );
        }
    }
    ok
}

/// The agent and sensors the system serves, in the scenario's one point,
/// which must be a perception world.
fn served(
    ctx: &mut Context<'_>,
    system: &RawSystemUnderTest,
    points: &[Point],
    path: &Path,
) -> Option<(usize, Vec<usize>)> {
    let world = match points {
        [point] => match &point.setup.experiment {
            Experiment::World(world) if world.perception.is_some() && world.semantic.is_none() => world,
            _ => {
                ctx.error(
                    path,
                    ErrorKind::Invalid(
                        "a system under test is driven in a perception world (`perception`, no `semantic`): \
                         its views carry the sensors' sightings with their occlusion"
                            .into(),
                    ),
                );
                return None;
            }
        },
        _ => {
            ctx.error(
                path,
                ErrorKind::Invalid(format!(
                    "a system under test is run once, on one point, and the sweep has {} points: leave out the \
                     sweep, or run one scenario per setting",
                    points.len()
                )),
            );
            return None;
        }
    };
    let perception = world.perception.as_ref()?;
    let agent = world.agents.iter().position(|a| a.id == system.agent);
    let Some(agent) = agent.filter(|i| perception.cooperating.contains(i)) else {
        let why = match agent {
            Some(_) => format!(
                "agent `{}` does not cooperate: only a cooperating agent's sensors are simulated",
                system.agent
            ),
            None => format!("no agent `{}` in the world", system.agent),
        };
        ctx.error(&path.key("agent"), ErrorKind::Invalid(why));
        return None;
    };
    let count = world.agents[agent].sensors.len();
    let sensors: Vec<usize> = match &system.sensors {
        None => (0..count).collect(),
        Some(list) => {
            let mut sensors = Vec::with_capacity(list.len().min(count));
            for (i, &index) in list.iter().enumerate() {
                if !ctx.within(&path.key("sensors").index(i), index as f64, range::SENSOR_INDEX) {
                    return None;
                }
                match usize::try_from(index).ok().filter(|&s| s < count) {
                    Some(s) if !sensors.contains(&s) => sensors.push(s),
                    Some(s) => {
                        ctx.error(
                            &path.key("sensors").index(i),
                            ErrorKind::Invalid(format!("sensor {s} is listed twice")),
                        );
                        return None;
                    }
                    None => {
                        ctx.error(
                            &path.key("sensors").index(i),
                            ErrorKind::OutOfRange {
                                expected: format!(
                                    "a sensor index below {count} (agent `{}` has {count})",
                                    system.agent
                                ),
                                found: index.to_string(),
                            },
                        );
                        return None;
                    }
                }
            }
            sensors.sort_unstable();
            sensors
        }
    };
    if sensors.is_empty() {
        ctx.error(
            &path.key("sensors"),
            ErrorKind::Invalid(format!("agent `{}` serves the system no sensor", system.agent)),
        );
        return None;
    }
    Some((agent, sensors))
}

/// Errors where an `objects` selection names the agent the system serves,
/// which is no road user it is judged on (a host that is the ego has its
/// error where selections are compiled: the ego is no road user of a record).
fn host_unselected(ctx: &mut Context<'_>, raw: &RawScenario, host: &str) -> bool {
    if raw.perception.as_ref().is_some_and(|p| p.ego == host) {
        return true;
    }
    let mut ok = true;
    for (i, requirement) in raw.requirements.iter().enumerate() {
        let ids = requirement.check.objects.iter().flat_map(|o| &o.ids);
        for (j, _) in ids.enumerate().filter(|(_, id)| *id == host) {
            let at = Path::root().key("requirements").index(i).key("check");
            ctx.error(
                &at.key("objects").key("ids").index(j),
                ErrorKind::Invalid(format!(
                    "`{host}` is the agent the system under test serves, not a road user it is judged on"
                )),
            );
            ok = false;
        }
    }
    ok
}

/// Errors at each requirement that checks a metric of the system under test
/// in a scenario that declares none.
fn refuse_system_metrics(ctx: &mut Context<'_>, requirements: &[(Path, &Requirement)]) {
    for (check, requirement) in requirements {
        let (metrics, at) = match &requirement.check {
            Check::Metric { metric, .. } => (vec![*metric], check.key("metric")),
            Check::Compare { metric, other, .. } => (vec![*metric, *other], check.clone()),
            Check::PerObject { property, .. } if property.of_system() => {
                ctx.error(
                    &check.key("per_object"),
                    ErrorKind::Invalid(format!(
                        "`{}` judges a system under test, and the scenario declares no `system_under_test`",
                        property.name()
                    )),
                );
                continue;
            }
            _ => continue,
        };
        if let Some(metric) = metrics.iter().find(|m| m.of_system()) {
            ctx.error(
                &at,
                ErrorKind::Invalid(format!(
                    "metric `{}` judges a system under test, and the scenario declares no `system_under_test`",
                    metric.name()
                )),
            );
        }
    }
}

/// Each compiled requirement with the path of its check in the file. A
/// requirement that did not compile leaves a gap in the compiled list, so
/// each is found by where it starts.
fn checks<'r>(ctx: &Context<'_>, raw: &RawScenario, requirements: &'r [Requirement]) -> Vec<(Path, &'r Requirement)> {
    let list = Path::root().key("requirements");
    let mut at = 0..raw.requirements.len();
    requirements
        .iter()
        .filter_map(|requirement| {
            let i = at.find(|&i| locate(ctx.tree, &list.index(i)) == requirement.location)?;
            Some((list.index(i).key("check"), requirement))
        })
        .collect()
}
