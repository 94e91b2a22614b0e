//! The scope and operational design domain of the scenario, as declared:
//! what kind of experiment, where and how long, who and what is in it, how
//! they sense, communicate and fuse, and what is swept.

use sightline_dsl::{AgentKind, Experiment, Scenario, Setup, SystemUnderTest, World};

use super::format::number;

/// The scope and operational design domain of the scenario, as declared: what
/// kind of experiment, where and how long, who and what is in it, how they
/// sense, communicate and fuse, and what is swept. One (aspect, value) row
/// each, from the first point (the sweep rows say what changes).
pub(super) fn scope(scenario: &Scenario) -> Vec<(&'static str, String)> {
    let Some(point) = scenario.points.first() else {
        return Vec::new();
    };
    let setup: &Setup = &point.setup;
    let mut rows = Vec::new();
    if let Some(occupancy) = &setup.occupancy {
        let g = &occupancy.grid;
        rows.push((
            "Area",
            format!(
                "{} m × {} m from ({}, {}) m, cells of {} m",
                number(g.cols as f64 * g.cell),
                number(g.rows as f64 * g.cell),
                number(g.origin[0]),
                number(g.origin[1]),
                number(g.cell)
            ),
        ));
        rows.push(("Fusion", occupancy.fusion.label.clone()));
    }
    match &setup.experiment {
        Experiment::Field(field) => {
            rows.push((
                "Experiment",
                "static evidential field (seed 001): fixed sensors over a generated ground truth".into(),
            ));
            let sensors = match &field.layout {
                sightline_dsl::Layout::Positions(positions) => positions.len(),
                sightline_dsl::Layout::Random { count } => *count,
            };
            rows.push(("Sensors", format!("{sensors} fixed, range {} m", number(field.range))));
        }
        Experiment::World(world) => world_scope(world, scenario.system_under_test.as_ref(), &mut rows),
    }
    rows.push((
        "Sweep",
        if scenario.sweeps.is_empty() {
            "none: one configuration".into()
        } else {
            scenario
                .sweeps
                .iter()
                .map(|s| s.axes.iter().map(|a| a.path.clone()).collect::<Vec<_>>().join(" × "))
                .collect::<Vec<_>>()
                .join("; ")
        },
    ));
    rows.push(("Configurations", scenario.points.len().to_string()));
    rows
}

/// The scope rows of a world: what it runs (collective perception, the
/// semantic pipeline or both, a system under test), its time, roads and road
/// users, who shares a grid, which units run the pipeline, and the radio of
/// each.
fn world_scope(world: &World, system: Option<&SystemUnderTest>, rows: &mut Vec<(&'static str, String)>) {
    let ids = |agents: &[usize]| -> Vec<&str> { agents.iter().map(|&a| world.agents[a].id.as_str()).collect() };
    let experiment = match (&world.perception, &world.semantic) {
        (Some(_), Some(_)) => {
            "joint world: collective perception (seed 000: the ego's grid fused from its own and the cooperating \
             agents' grids) and the roadside units' semantic pipeline (seed 002), on one scene, for one ego"
        }
        (Some(_), None) => {
            "collective perception (seed 000): the ego's grid fused from its own and the cooperating agents' grids"
        }
        _ => "roadside units' semantic pipeline for an assisted ego (seed 002)",
    };
    rows.push(("Experiment", experiment.into()));
    let ego = world
        .perception
        .as_ref()
        .map(|p| p.ego)
        .or(world.semantic.as_ref().map(|s| s.ego));
    if let Some(ego) = ego {
        rows.push(("Ego", world.agents[ego].id.clone()));
    }
    if let Some(system) = system {
        rows.push((
            "System under test",
            format!(
                "`{}` over ASAM OSI, on sensors {} (by index) of {}, matching gate {} m",
                system.name(),
                system
                    .sensors
                    .iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", "),
                system.agent_id,
                number(system.gate)
            ),
        ));
    }
    rows.push((
        "Time",
        format!(
            "{} s in steps of {} s",
            number(world.steps as f64 * world.step),
            number(world.step)
        ),
    ));
    rows.push((
        "Road network",
        format!("{} roads, {} occluders", world.roads.len(), world.occluders.len()),
    ));
    rows.push(("Road users and units", road_users(world)));
    if let Some(traffic) = &world.traffic {
        let vehicles = traffic
            .vehicles
            .as_ref()
            .map(|v| format!("vehicles {} per km", number(v.density_per_km)));
        let pedestrians = traffic
            .pedestrians
            .as_ref()
            .map(|p| format!("pedestrians {} per minute", number(p.per_minute)));
        let parts: Vec<String> = vehicles.into_iter().chain(pedestrians).collect();
        rows.push(("Generated traffic", parts.join(", ")));
    }
    if let Some(perception) = &world.perception {
        let others = ids(&perception.cooperating[1..]);
        rows.push((
            "Grids fused",
            if others.is_empty() {
                "the ego's own only: no other agent cooperates".into()
            } else {
                let whose = if others.len() == 1 { "agent's" } else { "agents'" };
                format!(
                    "the ego's and {} cooperating {whose}: {}",
                    others.len(),
                    others.join(", ")
                )
            },
        ));
        rows.push((
            "V2X, grids",
            match &perception.messages {
                Some(m) => format!(
                    "over the radio: {}, {} Hz messages of at most {} bytes, evidence dropped after {} s",
                    channel(world),
                    number(m.rate_hz),
                    m.max_bytes,
                    number(m.max_age)
                ),
                None => "no radio: cooperating agents' grids reach the ego whole and at once".into(),
            },
        ));
    }
    if let Some(semantic) = &world.semantic {
        rows.push((
            "Semantic pipeline",
            format!("run by {}", ids(&semantic.rsus).join(", ")),
        ));
        let connected = if world.perception.is_some() {
            "; generated and imported road users are not connected".to_string()
        } else if world.traffic.as_ref().is_some_and(|t| t.vehicles.is_some()) || world.imported > 0 {
            format!(
                "; penetration {} (the share of generated and imported vehicles connected)",
                number(world.v2x.penetration)
            )
        } else {
            String::new()
        };
        rows.push(("V2X, pipeline", format!("{}{connected}", channel(world))));
    }
}

/// A world's radio channel in words: its path-loss model and latency.
fn channel(world: &World) -> String {
    let model = serde_json::to_value(world.v2x.channel.model)
        .ok()
        .and_then(|m| m.as_str().map(str::to_string))
        .unwrap_or_default();
    format!("channel {model}, latency {} s", number(world.v2x.latency))
}

/// The road users and units of a world by kind, in order of first
/// appearance (`3 cars, 1 roadside unit`), and how many replay a trace.
fn road_users(world: &World) -> String {
    let mut kinds: Vec<(AgentKind, usize)> = Vec::new();
    for agent in &world.agents {
        match kinds.iter_mut().find(|(k, _)| *k == agent.kind) {
            Some((_, n)) => *n += 1,
            None => kinds.push((agent.kind, 1)),
        }
    }
    let mut words = kinds
        .iter()
        .map(|&(kind, n)| format!("{n} {}", kind_words(kind, n)))
        .collect::<Vec<_>>()
        .join(", ");
    if world.imported > 0 {
        words.push_str(&format!(" ({} of them imported from traces)", world.imported));
    }
    words
}

/// A kind of road user or unit as a count of `n` of them says it.
fn kind_words(kind: AgentKind, n: usize) -> String {
    let one = match kind {
        AgentKind::Rsu => "roadside unit",
        other => other.name(),
    };
    match (n, kind) {
        (1, _) => one.into(),
        (_, AgentKind::Bus) => "buses".into(),
        _ => format!("{one}s"),
    }
}
