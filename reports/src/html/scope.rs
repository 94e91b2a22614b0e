//! The scope and operational design domain of the scenario, as declared:
//! what kind of experiment, where and how long, who and what is in it, how
//! they sense, communicate and fuse, and what is swept.
//!
//! Each row speaks of every configuration, not the first: a part a sweep
//! changes shows the set of values it takes, and its row says it is swept
//! and by which keys, so that no row states one configuration's value as the
//! scenario's.

use std::collections::{HashMap, HashSet};

use sightline_dsl::{AgentKind, Experiment, Field, Messages, Perception, Scenario, Setup, SystemUnderTest, World};

use super::format::number;

/// One row of the scope: (aspect, value).
type Row = (&'static str, String);

/// The scope and operational design domain of the scenario: one (aspect,
/// value) row each, over every configuration. A row whose value differs
/// between configurations starts `swept by` and the keys that change it
/// (`` swept by `fusion.method` (see Sweep): {bayes, dempster} ``);
/// the sweep rows say what is swept and how many configurations there are.
pub(super) fn scope(scenario: &Scenario) -> Vec<Row> {
    let setups: Vec<&Setup> = scenario.points.iter().map(|p| &p.setup).collect();
    if setups.is_empty() {
        return Vec::new();
    }
    let system = scenario.system_under_test.as_ref();
    let at_each: Vec<Vec<Row>> = setups.iter().map(|s| rows(std::slice::from_ref(s), system)).collect();
    let mut rows = rows(&setups, system);
    for (aspect, value) in &mut rows {
        let at = |point: usize| {
            at_each[point]
                .iter()
                .find(|(a, _)| a == aspect)
                .map(|(_, v)| v.as_str())
        };
        if (1..setups.len()).any(|point| at(point) != at(0)) {
            let keys: Vec<String> = swept_by(scenario, at).iter().map(|key| format!("`{key}`")).collect();
            *value = match keys.as_slice() {
                [] => format!("swept (see Sweep): {value}"),
                keys => format!("swept by {} (see Sweep): {value}", keys.join(", ")),
            };
        }
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

/// The sweep keys that change a row whose value at each point is `at`: an
/// axis changes it where two rows of its sweep that agree on every other axis
/// show it differently. In sweep and axis order, each key once. A row that
/// differs only between sweeps (each fixing a key to another value) names
/// none.
fn swept_by<'a>(scenario: &'a Scenario, at: impl Fn(usize) -> Option<&'a str>) -> Vec<&'a str> {
    let mut keys: Vec<&str> = Vec::new();
    for sweep in &scenario.sweeps {
        let rows: Vec<(usize, Vec<&serde_json::Value>)> = sweep.rows().collect();
        for (i, axis) in sweep.axes.iter().enumerate() {
            let mut seen: HashMap<String, Option<&str>> = HashMap::new();
            let changes = rows.iter().any(|(point, values)| {
                let others: Vec<&serde_json::Value> = (values.iter().enumerate())
                    .filter(|&(j, _)| j != i)
                    .map(|(_, v)| *v)
                    .collect();
                let others = serde_json::to_string(&others).expect("sweep values serialize");
                *seen.entry(others).or_insert_with(|| at(*point)) != at(*point)
            });
            if changes && !keys.contains(&axis.path.as_str()) {
                keys.push(&axis.path);
            }
        }
    }
    keys
}

/// The values `part` takes over `items`, each once in first-seen order: one
/// as it is, several as a [`set`].
fn each<T: ?Sized>(items: &[&T], part: impl Fn(&T) -> String) -> String {
    set(items.iter().map(|item| part(item)))
}

/// The numbers `part` takes over `items` as the page writes them, each once
/// and in ascending order: one as it is, several as a [`set`].
fn each_number<T: ?Sized>(items: &[&T], part: impl Fn(&T) -> f64) -> String {
    let mut values: Vec<f64> = items.iter().map(|item| part(item)).collect();
    values.sort_by(f64::total_cmp);
    set(values.into_iter().map(number))
}

/// `values` each once, in order: one as it is, several as a set `{a, b}`
/// (`{a; b}` where a value holds a comma).
fn set(values: impl Iterator<Item = String>) -> String {
    // A set beside the list: a sweep of 10 000 points may give as many values.
    let mut seen: HashSet<String> = HashSet::new();
    let distinct: Vec<String> = values.filter(|value| seen.insert(value.clone())).collect();
    match distinct.as_slice() {
        [one] => one.clone(),
        _ => {
            let separator = if distinct.iter().any(|v| v.contains(',')) {
                "; "
            } else {
                ", "
            };
            format!("{{{}}}", distinct.join(separator))
        }
    }
}

/// The scope rows of `setups` (the configurations, at least one), each part
/// the set of values it takes over them; `Sweep` and `Configurations` are the
/// caller's.
fn rows(setups: &[&Setup], system: Option<&SystemUnderTest>) -> Vec<Row> {
    let mut rows = Vec::new();
    let occupancy: Vec<_> = setups.iter().filter_map(|s| s.occupancy.as_ref()).collect();
    if !occupancy.is_empty() {
        rows.push((
            "Area",
            format!(
                "{} m × {} m from {} m, cells of {} m",
                each_number(&occupancy, |o| o.grid.cols as f64 * o.grid.cell),
                each_number(&occupancy, |o| o.grid.rows as f64 * o.grid.cell),
                each(&occupancy, |o| format!(
                    "({}, {})",
                    number(o.grid.origin[0]),
                    number(o.grid.origin[1])
                )),
                each_number(&occupancy, |o| o.grid.cell)
            ),
        ));
        rows.push(("Fusion", each(&occupancy, |o| o.fusion.label.clone())));
    }
    let fields: Vec<&Field> = (setups.iter())
        .filter_map(|s| match &s.experiment {
            Experiment::Field(field) => Some(field),
            Experiment::World(_) => None,
        })
        .collect();
    let worlds: Vec<&World> = (setups.iter())
        .filter_map(|s| match &s.experiment {
            Experiment::World(world) => Some(&**world),
            Experiment::Field(_) => None,
        })
        .collect();
    if !fields.is_empty() {
        rows.push((
            "Experiment",
            "static evidential field (seed 001): fixed sensors over a generated ground truth".into(),
        ));
        let sensors = |field: &Field| match &field.layout {
            sightline_dsl::Layout::Positions(positions) => positions.len(),
            sightline_dsl::Layout::Random { count } => *count,
        };
        rows.push((
            "Sensors",
            format!(
                "{} fixed, range {} m",
                each(&fields, |f| sensors(f).to_string()),
                each_number(&fields, |f| f.range)
            ),
        ));
    }
    if !worlds.is_empty() {
        world_scope(&worlds, system, &mut rows);
    }
    rows
}

/// The scope rows of the worlds of the configurations: what they run
/// (collective perception, the semantic pipeline or both, a system under
/// test), their time, roads and road users, who shares a grid, which units
/// run the pipeline, and the radio of each.
fn world_scope(worlds: &[&World], system: Option<&SystemUnderTest>, rows: &mut Vec<Row>) {
    rows.push(("Experiment", each(worlds, |w| experiment(w).into())));
    let egos: Vec<&World> = (worlds.iter().copied())
        .filter(|w| w.perception.is_some() || w.semantic.is_some())
        .collect();
    if !egos.is_empty() {
        rows.push(("Ego", each(&egos, |w| w.agents[ego(w)].id.clone())));
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
            each_number(worlds, |w| w.steps as f64 * w.step),
            each_number(worlds, |w| w.step)
        ),
    ));
    rows.push((
        "Road network",
        format!(
            "{} roads, {} occluders",
            each(worlds, |w| w.roads.len().to_string()),
            each(worlds, |w| w.occluders.len().to_string())
        ),
    ));
    rows.push(("Road users and units", each(worlds, road_users)));
    let traffic: Vec<_> = worlds.iter().filter_map(|w| w.traffic.as_ref()).collect();
    if !traffic.is_empty() {
        let vehicles: Vec<_> = traffic.iter().filter_map(|t| t.vehicles.as_ref()).collect();
        let pedestrians: Vec<_> = traffic.iter().filter_map(|t| t.pedestrians.as_ref()).collect();
        let parts: Vec<String> = [
            (!vehicles.is_empty()).then(|| format!("vehicles {} per km", each_number(&vehicles, |v| v.density_per_km))),
            (!pedestrians.is_empty())
                .then(|| format!("pedestrians {} per minute", each_number(&pedestrians, |p| p.per_minute))),
        ]
        .into_iter()
        .flatten()
        .collect();
        rows.push(("Generated traffic", parts.join(", ")));
    }
    let perception: Vec<(&World, &Perception)> = (worlds.iter())
        .filter_map(|&w| w.perception.as_ref().map(|p| (w, p)))
        .collect();
    if !perception.is_empty() {
        let perception: Vec<&(&World, &Perception)> = perception.iter().collect();
        rows.push(("Grids fused", each(&perception, |&(w, p)| grids_fused(w, p))));
        let radio: Vec<(&World, &Messages)> = (perception.iter())
            .filter_map(|&&(w, p)| p.messages.as_ref().map(|m| (w, m)))
            .collect();
        let radio: Vec<&(&World, &Messages)> = radio.iter().collect();
        rows.push((
            "V2X, grids",
            each(&perception, |&(_, p)| match p.messages {
                Some(_) => format!(
                    "over the radio: {}, {} Hz messages of at most {} bytes, evidence dropped after {} s",
                    channel(&radio.iter().map(|&&(w, _)| w).collect::<Vec<_>>()),
                    each_number(&radio, |&(_, m)| m.rate_hz),
                    each(&radio, |&(_, m)| m.max_bytes.to_string()),
                    each_number(&radio, |&(_, m)| m.max_age)
                ),
                None => "no radio: cooperating agents' grids reach the ego whole and at once".into(),
            }),
        ));
    }
    let semantic: Vec<&World> = worlds.iter().copied().filter(|w| w.semantic.is_some()).collect();
    if !semantic.is_empty() {
        rows.push((
            "Semantic pipeline",
            each(&semantic, |w| {
                let rsus = &w.semantic.as_ref().expect("a semantic world").rsus;
                format!("run by {}", ids(w, rsus).join(", "))
            }),
        ));
        let penetration = each_number(&semantic, |w| w.v2x.penetration);
        rows.push((
            "V2X, pipeline",
            format!(
                "{}{}",
                channel(&semantic),
                each(&semantic, |w| connected(w, &penetration))
            ),
        ));
    }
}

/// The ids of `agents` (indices into the world's agents).
fn ids<'a>(world: &'a World, agents: &[usize]) -> Vec<&'a str> {
    agents.iter().map(|&a| world.agents[a].id.as_str()).collect()
}

/// What a world runs, in words.
fn experiment(world: &World) -> &'static str {
    match (&world.perception, &world.semantic) {
        (Some(_), Some(_)) => {
            "joint world: collective perception (seed 000: the ego's grid fused from its own and the cooperating \
             agents' grids) and the roadside units' semantic pipeline (seed 002), on one scene, for one ego"
        }
        (Some(_), None) => {
            "collective perception (seed 000): the ego's grid fused from its own and the cooperating agents' grids"
        }
        _ => "roadside units' semantic pipeline for an assisted ego (seed 002)",
    }
}

/// The ego of a world that perceives or runs the pipeline.
fn ego(world: &World) -> usize {
    (world.perception.as_ref().map(|p| p.ego))
        .or(world.semantic.as_ref().map(|s| s.ego))
        .expect("a world with an ego")
}

/// Whose grids the ego fuses, in words.
fn grids_fused(world: &World, perception: &Perception) -> String {
    let others = ids(world, &perception.cooperating[1..]);
    if others.is_empty() {
        "the ego's own only: no other agent cooperates".into()
    } else {
        let whose = if others.len() == 1 { "agent's" } else { "agents'" };
        format!(
            "the ego's and {} cooperating {whose}: {}",
            others.len(),
            others.join(", ")
        )
    }
}

/// Which road users the pipeline's radio reaches, after its channel: none in
/// a joint world, the share `penetration` where there are generated or
/// imported vehicles, and nothing to say otherwise.
fn connected(world: &World, penetration: &str) -> String {
    if world.perception.is_some() {
        "; generated and imported road users are not connected".to_string()
    } else if world.traffic.as_ref().is_some_and(|t| t.vehicles.is_some()) || world.imported > 0 {
        format!("; penetration {penetration} (the share of generated and imported vehicles connected)")
    } else {
        String::new()
    }
}

/// The worlds' radio channel in words: its path-loss model and latency.
fn channel(worlds: &[&World]) -> String {
    let model = |world: &World| {
        serde_json::to_value(world.v2x.channel.model)
            .ok()
            .and_then(|m| m.as_str().map(str::to_string))
            .unwrap_or_default()
    };
    format!(
        "channel {}, latency {} s",
        each(worlds, model),
        each_number(worlds, |w| w.v2x.latency)
    )
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The scope of a field of four sensors, 20 m × 10 m, with `rest` (the
    /// settings the test gives or sweeps: seed, fusion, sensor range, masses).
    fn field(rest: &str) -> Vec<Row> {
        let text = format!(
            "sightline: 1\nname: t\ngrid: {{ size: [20, 10], cell: 1 }}\n\
             requirements:\n  - {{ id: R, text: t, check: {{ invariant: mass_function }} }}\n{rest}"
        );
        scope(&sightline_dsl::compile("t.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}")))
    }

    /// A field's truth and sensor layout, with its sensors' `range` (empty
    /// where a sweep sets it) and its `masses`.
    fn sensors(range: &str, masses: &str) -> String {
        format!(
            "field:\n  truth: {{ occupied_fraction: 0.1 }}\n  masses: {masses}\n  \
             sensors: {{ {range} layout: {{ regular: {{ rows: 2, cols: 2 }} }} }}\n"
        )
    }

    fn row(rows: &[Row], aspect: &str) -> String {
        let found = rows.iter().find(|(a, _)| *a == aspect);
        found.unwrap_or_else(|| panic!("no {aspect} in {rows:?}")).1.clone()
    }

    /// A swept row gives every value with the key that sweeps it; in a
    /// product of sweeps an axis is named only where it changes the row
    /// (`field.masses.gamma` changes none); a row no sweep changes is as
    /// one configuration gives it.
    #[test]
    fn a_row_a_sweep_changes_gives_its_values_and_keys() {
        let rows = field(&format!(
            "seed: 1\n{}sweep:\n  field.masses.gamma: [6, 8]\n  field.sensors.range: [30, 5]\n  fusion:\n    \
             - {{ label: Baseline, method: dempster }}\n    - {{ label: \"Bayes, plain\", method: bayes }}\n",
            sensors("", "{ error_model: dirichlet_mean }")
        ));
        assert_eq!(
            row(&rows, "Fusion"),
            "swept by `fusion` (see Sweep): {Baseline; Bayes, plain}"
        );
        assert_eq!(
            row(&rows, "Sensors"),
            "swept by `field.sensors.range` (see Sweep): 4 fixed, range {5, 30} m"
        );
        assert_eq!(row(&rows, "Area"), "20 m × 10 m from (0, 0) m, cells of 1 m");
        assert_eq!(row(&rows, "Configurations"), "8");
    }

    /// A sweep of keys no row shows (the seed, γ) leaves every row as one
    /// configuration gives it.
    #[test]
    fn a_sweep_of_keys_no_row_shows_changes_no_row() {
        let swept = field(&format!(
            "{}sweep:\n  seed: [1, 2]\n  field.masses.gamma: [6, 8]\n",
            sensors("range: 5,", "{ error_model: dirichlet_mean }")
        ));
        let single = field(&format!("seed: 1\n{}", sensors("range: 5,", "{ gamma: 6 }")));
        let unswept = |rows: &[Row]| -> Vec<Row> {
            (rows.iter())
                .filter(|(a, _)| !["Sweep", "Configurations"].contains(a))
                .cloned()
                .collect()
        };
        assert_eq!(unswept(&swept), unswept(&single));
        assert!(swept.iter().all(|(_, v)| !v.starts_with("swept")), "{swept:?}");
        assert_eq!(row(&swept, "Sensors"), "4 fixed, range 5 m");
    }

    /// A row that differs only between sweeps, each fixing a key to another
    /// value, is said to be swept with no key named: no axis changes it
    /// within its sweep.
    #[test]
    fn a_row_that_differs_between_sweeps_is_swept() {
        let rows = field(&format!(
            "seed: 1\n{}sweeps:\n  - {{ field.sensors.range: [30] }}\n  - {{ field.sensors.range: [5] }}\n",
            sensors("", "{ gamma: 6 }")
        ));
        assert_eq!(row(&rows, "Sensors"), "swept (see Sweep): 4 fixed, range {5, 30} m");
        assert_eq!(row(&rows, "Area"), "20 m × 10 m from (0, 0) m, cells of 1 m");
    }

    #[test]
    fn values_are_each_given_once() {
        let text = |values: &[&str]| set(values.iter().map(|v| v.to_string()));
        assert_eq!(text(&["a", "a"]), "a");
        assert_eq!(text(&["b", "a", "b"]), "{b, a}");
        assert_eq!(text(&["a, b", "c"]), "{a, b; c}");
        let numbers = [&0.3, &0.02, &1.0, &0.02];
        assert_eq!(each_number(&numbers, |v: &f64| *v), "{0.02, 0.3, 1}");
        assert_eq!(each_number(&[&1500.0, &2.0], |v: &f64| *v), "{2; 1,500}");
    }
}
