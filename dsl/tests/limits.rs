//! Limits (issue 15): every number within its physical range, every product of
//! the resource model checked before work, and errors that point at the cause.
//! See: docs/limits.md.

use proptest::prelude::*;
use sightline_dsl::{ErrorKind, Errors, Options, compile, schema};

const URBAN: &str = include_str!("../../scenarios/urban-rsu-semantic.yaml");
const ROUNDABOUT: &str = include_str!("../../scenarios/roundabout-six-agents.yaml");
const FIELD: &str = include_str!("../../scenarios/evidential-field.yaml");

/// `text` with `from` replaced once by `to` (which must be there).
fn with(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "the scenario has `{from}`");
    text.replacen(from, to, 1)
}

fn errors(text: &str) -> Errors {
    compile("s.yaml", text, &Options::default()).expect_err("the scenario is refused")
}

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("the needle is there")
        + 1
}

/// Each hostile value of the fuzzing trial is refused at the key that gives it.
#[test]
fn issue_15_hostile_values_are_refused_where_they_are_written() {
    let cases = [
        (
            with(
                URBAN,
                "size_noise: { base: 0.05, per_m: 0.001 }",
                "size_noise: { base: 0.05, per_m: 1e308 }",
            ),
            "size_noise",
            "sensor_models.rsu_sensing.size_noise.per_m: expected a number ≤ 1, found 1e308",
        ),
        (
            with(URBAN, "per_minute: 2,", "per_minute: 1e12,"),
            "per_minute: 1e12",
            "traffic.pedestrians.per_minute: expected a number ≤ 600, found 1000000000000",
        ),
        (
            with(URBAN, "[[-1.75, 500], [-1.75, 8]]", "[[-1.75, 1e308], [-1.75, 8]]"),
            "1e308",
            "roads[0].polyline[0][1]: expected a number ≤ 1000000, found 1e308",
        ),
        (
            with(URBAN, "[[-1.75, 500], [-1.75, 8]]", "[[-1.75, 10000000], [-1.75, 8]]"),
            "10000000",
            "roads[0].polyline[0][1]: expected a number ≤ 1000000, found 10000000",
        ),
        (
            with(ROUNDABOUT, "ray_spacing_deg: 0.5", "ray_spacing_deg: 1e-6"),
            "ray_spacing_deg",
            "sensor_models.lidar.ray_spacing_deg: expected a number ≥ 0.01, found 1e-6",
        ),
        (
            // Found after the trial: a process noise whose square underflows to
            // 0 left the pose filter a singular matrix (a panic).
            with(
                ROUNDABOUT,
                "  filter: kalman\n",
                "  filter: kalman\n  process_position_sigma: 1e-200\n",
            ),
            "process_position_sigma",
            "localization.process_position_sigma: expected a number ≥ 0.000001, found 1e-200",
        ),
        (
            with(FIELD, "concentration: 32", "concentration: 1e-8"),
            "concentration",
            "field.masses.concentration: expected a number ≥ 1, found 1e-8",
        ),
    ];
    for (text, needle, message) in cases {
        let errors = errors(&text);
        assert_eq!(errors.0.len(), 1, "{errors}");
        let error = &errors.0[0];
        assert!(matches!(error.kind, ErrorKind::OutOfRange { .. }), "{error}");
        assert_eq!(error.location.line, line_of(&text, needle), "{error}");
        assert!(error.to_string().ends_with(message), "{error}");
    }
}

/// A road whose arc cannot be drawn is the one error: the routes of the ego
/// and of the traffic that drive on it, or on roads after it, are not
/// reported as naming a missing road.
#[test]
fn issue_15_a_failed_road_is_reported_once_not_at_the_routes_that_name_it() {
    let text = with(URBAN, "radius: 6.25, start_deg: 0", "radius: 1e-12, start_deg: 0");
    let errors = errors(&text);
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert_eq!(errors.0[0].path, "roads[12].arc.radius");
    assert_eq!(errors.0[0].location.line, line_of(&text, "1e-12"));
}

/// A sensor model out of range is the one error, not each agent that names it.
#[test]
fn a_failed_sensor_model_is_reported_once_not_at_the_agents_that_name_it() {
    let text = with(ROUNDABOUT, "range: 80", "range: -80");
    let errors = errors(&text);
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert_eq!(errors.0[0].path, "sensor_models.lidar.range");
}

/// A name no declaration has is still a dangling reference.
#[test]
fn a_route_naming_no_road_is_still_refused() {
    let text = with(
        URBAN,
        "route: [south_in, s_n, north_out]",
        "route: [south_in, s_n, nowhere]",
    );
    let errors = errors(&text);
    assert!(
        errors
            .0
            .iter()
            .any(|e| matches!(&e.kind, ErrorKind::DanglingReference(m) if m.starts_with("no road `nowhere`"))),
        "{errors}"
    );
}

/// A route of more roads than any scene names is refused at the route, an
/// agent's or the traffic's (1 001 roads of one lane compiled in quadratic time:
/// 200 000 never finished).
#[test]
fn a_route_of_too_many_roads_is_refused_where_it_is_written() {
    let long = |road: &str| format!("[{}]", vec![road; 1_001].join(", "));
    let cases = [
        ("route: [south_in, s_n, north_out]", "route: ", "agents[0].route"),
        ("- [north_in, n_s, south_out]", "- ", "traffic.vehicles.routes[0]"),
    ];
    for (from, key, at) in cases {
        let text = with(URBAN, from, &format!("{key}{}", long("south_in")));
        let errors = errors(&text);
        assert_eq!(errors.0.len(), 1, "{errors}");
        assert_eq!(errors.0[0].path, at);
        assert_eq!(errors.0[0].location.line, line_of(&text, "south_in, south_in"));
        assert_eq!(
            errors.0[0].kind,
            ErrorKind::TooLarge(
                "1001 roads in a route exceed the limit of 1000; name each road of the way once".into()
            )
        );
    }
    // The same way with its last road named again up to the limit is a route.
    let at_the_limit = format!("route: [south_in, s_n{}]", ", north_out".repeat(998));
    let text = with(URBAN, "route: [south_in, s_n, north_out]", &at_the_limit);
    compile("s.yaml", &text, &Options::default()).expect("1 000 roads are a route");
}

/// Products within each range are still checked: many fine rays over many
/// steps exceed the rays per step, with the numbers.
#[test]
fn rays_per_step_are_checked_as_a_product() {
    let text = with(ROUNDABOUT, "ray_spacing_deg: 0.5", "ray_spacing_deg: 0.01");
    let text = text.replace("[lidar]", "[lidar, lidar, lidar, lidar, lidar, lidar]");
    let errors = errors(&text);
    let too_large: Vec<_> = errors
        .0
        .iter()
        .filter(|e| matches!(e.kind, ErrorKind::TooLarge(_)))
        .collect();
    assert!(!too_large.is_empty(), "{errors}");
    assert_eq!(too_large[0].path, "sensor_models.lidar.ray_spacing_deg");
    assert!(
        too_large[0].to_string().contains(
            "1.3e6 rays per step (cooperating agents' sensors × field of view / ray spacing) exceed the limit of 1e6"
        ),
        "{}",
        too_large[0]
    );
}

/// Traffic is counted before it is generated: a dense crowd at every crosswalk
/// over a long run exceeds the agents of a run.
#[test]
fn expected_traffic_is_checked_before_it_is_generated() {
    let text = with(URBAN, "per_minute: 2,", "per_minute: 600,");
    let text = with(&text, "duration: 120", "duration: 600");
    let errors = errors(&text);
    assert!(
        errors.0.iter().any(|e| e.path == "traffic.pedestrians.per_minute"
            && e.to_string()
                .contains("agents in a run (declared, imported and the traffic expected) exceed the limit of 10000")),
        "{errors}"
    );
}

/// Every number the schema admits has a lower and an upper bound, but for the
/// few that only compare or count (`docs/limits.md` says why).
#[test]
fn every_number_in_the_schema_has_a_range() {
    const UNBOUNDED: [&str; 12] = [
        "Scenario.sightline",
        "Scenario.seed",
        "Agent.lane",
        "Perception.cooperating",
        "Record.point",
        "Check.at_least",
        "Check.at_most",
        "Check.min_samples",
        "Reference.value",
        "Threshold.at_least",
        "Threshold.at_most",
        "Occluder.height",
    ];
    let schema = schema();
    let mut unbounded = Vec::new();
    let mut definitions: Vec<(String, &serde_json::Value)> = vec![("Scenario".into(), &schema)];
    for (name, definition) in schema["definitions"].as_object().unwrap() {
        definitions.push((name.clone(), definition));
    }
    for (name, definition) in definitions {
        for (key, property) in definition["properties"].as_object().into_iter().flatten() {
            let mut node = property;
            while node.get("items").is_some() {
                node = &node["items"];
            }
            let numeric = ["number", "integer"]
                .iter()
                .any(|t| node["type"] == *t || node["type"].as_array().is_some_and(|a| a.iter().any(|x| x == *t)));
            let bounded = |side: &str, exclusive: &str| node.get(side).or(node.get(exclusive)).is_some();
            if numeric && !(bounded("minimum", "exclusiveMinimum") && bounded("maximum", "exclusiveMaximum")) {
                unbounded.push(format!("{name}.{key}"));
            }
        }
    }
    unbounded.retain(|k| !UNBOUNDED.contains(&k.as_str()));
    assert!(
        unbounded.is_empty(),
        "numbers without a range in the schema: {unbounded:?}"
    );
}

/// Keys of the bundled scenarios, each with the line that gives it, the
/// value there, and its documented range.
const KEYS: [(&str, &str, f64, f64, bool); 6] = [
    // (scenario, the text to replace, lowest allowed, highest allowed, lowest excluded)
    ("urban", "per_m: 0.001", 0.0, 1.0, false),
    ("urban", "per_minute: 2,", 0.0, 600.0, false),
    ("urban", "d_min: 2", 0.0, 100.0, true),
    ("roundabout", "ray_spacing_deg: 0.5", 0.01, 10.0, false),
    ("roundabout", "range: 80", 0.0, 1.0e4, true),
    ("field", "concentration: 32", 1.0, 1.0e12, false),
];

fn key_text(case: usize, value: f64) -> (String, String) {
    let (scenario, written, ..) = KEYS[case];
    let base = match scenario {
        "urban" => URBAN,
        "roundabout" => ROUNDABOUT,
        _ => FIELD,
    };
    let key = written.split(':').next().unwrap();
    let separator = if written.ends_with(',') { "," } else { "" };
    (
        with(base, written, &format!("{key}: {value:e}{separator}")),
        key.to_string(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// A finite value within a key's documented range compiles, or fails for
    /// another reason than its range (a grid rate that no longer divides, a
    /// budget), never with a panic and never at the key as out of range.
    #[test]
    fn values_within_the_range_are_not_refused_as_out_of_range(case in 0..KEYS.len(), t in 0.0..=1.0f64) {
        let (_, _, low, high, open) = KEYS[case];
        let value = low + (high - low) * t;
        prop_assume!(!(open && value == low));
        let (text, key) = key_text(case, value);
        if let Err(errors) = compile("s.yaml", &text, &Options::default()) {
            for error in &errors.0 {
                prop_assert!(
                    !(error.path.ends_with(&key) && matches!(error.kind, ErrorKind::OutOfRange { .. })),
                    "{value} refused: {error}"
                );
            }
        }
    }

    /// A value outside a key's documented range is refused at the line that
    /// gives it.
    #[test]
    fn values_outside_the_range_are_refused_where_written(
        case in 0..KEYS.len(),
        above in any::<bool>(),
        factor in 1.0f64..1.0e290,
    ) {
        let (_, _, low, high, _) = KEYS[case];
        let value = if above { high * (1.0 + factor) } else { low - factor };
        let (text, key) = key_text(case, value);
        let errors = compile("s.yaml", &text, &Options::default()).expect_err("refused");
        let error = errors.0.iter().find(|e| e.path.ends_with(&key)).expect("an error at the key");
        prop_assert!(matches!(error.kind, ErrorKind::OutOfRange { .. }), "{error}");
        prop_assert_eq!(error.location.line, line_of(&text, &format!("{key}: {value:e}")));
    }
}

/// A check over seeds multiplies its points' work: the urban junction's twelve
/// points at 10 000 seeds would take days in one process, so `run` (one
/// process) refuses it at the check's `seeds`, a run split into enough shards
/// takes it, and a compilation that simulates nothing (a merge, a replay) does
/// not judge it.
#[test]
fn the_work_of_a_run_counts_its_seeds_and_is_split_by_shards() {
    let text = with(
        URBAN,
        "check: { metric: packet_delivery_ratio, at_least: 0.95 }",
        "check: { metric: packet_delivery_ratio, at_least: 0.95, seeds: 10000 }",
    );
    let processes = |processes| Options {
        processes,
        ..Default::default()
    };
    let refused = compile("s.yaml", &text, &processes(Some(1))).expect_err("too much for one process");
    let [error] = &refused.0[..] else {
        panic!("one error: {refused}")
    };
    assert!(matches!(error.kind, ErrorKind::TooLarge(_)), "{error}");
    assert_eq!(error.path, "requirements[4].check.seeds");
    assert_eq!(error.location.line, line_of(&text, "seeds: 10000"));
    let message = error.to_string();
    assert!(
        message.contains("12 sweep points, each at the seeds") && message.contains("--shard K/N"),
        "{message}"
    );
    assert!(compile("s.yaml", &text, &processes(Some(100))).is_ok());
    assert!(compile("s.yaml", &text, &processes(None)).is_ok());
    // The file as bundled: well within one process.
    assert!(compile("s.yaml", URBAN, &processes(Some(1))).is_ok());
}

/// Laying an occluder on the grid tests each cell of its bounding box against
/// each of its edges: an outline of 30 000 corners over the whole grid is
/// refused before anything is laid (it took minutes).
#[test]
fn an_occluder_of_many_corners_over_the_grid_is_refused() {
    let teeth = 15_000;
    let mut corners: Vec<String> = (0..teeth)
        .flat_map(|i| {
            let x = -150.0 + 300.0 * f64::from(i) / f64::from(teeth);
            [format!("[{x}, -150]"), format!("[{}, -149]", x + 0.01)]
        })
        .collect();
    corners.extend(["[150, 150]".to_string(), "[-150, 150]".to_string()]);
    let comb = format!("  - {{ id: comb, polygon: [{}] }}\n", corners.join(", "));
    let text = with(
        ROUNDABOUT,
        "occluders:                       # ours: four corner blocks clear of the ring\n",
        &format!("occluders:\n{comb}"),
    );
    let errors = errors(&text);
    assert!(
        errors.0.iter().any(|e| e.path == "occluders"
            && e.to_string().contains(
                "1.1e10 edge tests laying the occluders on the grid (each occluder's cells on the grid × its corners \
                 × runs) exceed the limit of 1e10"
            )),
        "{errors}"
    );
}

/// Every requirement is a verdict at each point it applies to, each written
/// to the evidence with its text: too many verdicts, or text repeated into
/// too many bytes, are refused (a thousand requirements over a thousand
/// points ran out of memory).
#[test]
fn verdicts_and_the_text_they_repeat_are_bounded() {
    let many: String = (0..2000)
        .map(|i| format!("  - {{ id: R{i}, text: t, check: {{ invariant: mass_function }} }}\n"))
        .collect();
    let long = format!(
        "  - {{ id: LONG, text: {}, check: {{ invariant: mass_function }} }}\n",
        "t".repeat(1_000_000)
    );
    let text_limit = " bytes of text in the evidence (each point's label; per verdict its requirement's text, its \
                      point's label and the scenario's name; per reference row its source and label) exceed the \
                      limit of 5e7";
    let requirements = |added: &str| with(FIELD, "requirements:\n", &format!("requirements:\n{added}"));
    // A name of 400 kB in each of the field's 600 verdicts (the fuzz trial's
    // 6 MB name over 400 points wrote a 386 MB junit.xml, then ran out of memory).
    let name = format!("name: {}\n", "n".repeat(400_000));
    let named = with(
        FIELD,
        "name: \"Evidential field: distance-weighted Dempster rule (seed 001)\"\n",
        &name,
    );
    for (text, message) in [
        (
            requirements(&many),
            " verdicts (requirements × the sweep points each applies to) exceed the limit of 100000",
        ),
        (requirements(&long), text_limit),
        (named, text_limit),
    ] {
        let errors = errors(&text);
        assert!(
            errors
                .0
                .iter()
                .any(|e| e.path == "requirements" && e.to_string().contains(message)),
            "{errors}"
        );
    }
}

/// Reference figures and a field's distance bands are written at every point
/// they apply to: 1 000 of either over the field's 120 points is refused
/// where they are written (the fuzz trial's 3 900 bands over 500 points wrote
/// 459 MB of results.json from a 37 kB file).
#[test]
fn rows_of_results_are_bounded() {
    let rows = " rows of results beside the verdicts (reference figures × the points each applies to, and a \
                field's distance bands × the points) exceed the limit of 100000";
    let references: String = (0..1000)
        .map(|i| format!("  - {{ source: paper, metric: accuracy, value: {i} }}\n"))
        .collect();
    let bands: Vec<String> = (1..=1000).map(|i| format!("{}", i as f64 / 10.0)).collect();
    let bands = format!("field:\n  distance_bands: [{}]\n", bands.join(", "));
    for (text, path) in [
        (
            with(FIELD, "references:\n", &format!("references:\n{references}")),
            "references",
        ),
        (with(FIELD, "field:\n", &bands), "field.distance_bands"),
    ] {
        let errors = errors(&text);
        assert!(
            errors.0.iter().any(|e| e.path == path && e.to_string().contains(rows)),
            "{errors}"
        );
    }
}

/// The ego's and the RSUs' sensors each look at every agent at every step: a
/// list of 2 000 sensors on the ego (the fuzz trial's 100 000 never ended) is
/// refused at the agents.
#[test]
fn a_semantic_world_s_sensor_looks_are_bounded() {
    let sensors = vec!["ego_front"; 2000].join(", ");
    let text = with(URBAN, "sensors: [ego_front]", &format!("sensors: [{sensors}]"));
    let errors = errors(&text);
    assert!(
        errors.0.iter().any(|e| e.path == "agents"
            && e.to_string().contains(
                " looks at objects at a point (the ego's and the RSUs' sensors × agents × steps × runs) exceed the \
                 limit of 1e9"
            )),
        "{errors}"
    );
}
