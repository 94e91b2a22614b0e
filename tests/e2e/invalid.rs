//! Invalid inputs and usage errors: exit 2, every problem on stderr, nothing
//! written.
//!
//! Data-driven: each `tests/fixtures/invalid/NAME.yaml` has a `NAME.stderr`
//! holding the exact expected stderr, one `file:line:col: error: yaml.path:
//! message` line per problem. `check` and `run` must both print exactly that.
//! The SUMO files some of them import are in `tests/fixtures/invalid/sumo/`; a
//! problem in such a file is located in it.
//!
//! To (re)write the `.stderr` files from the actual output, run
//!
//! ```text
//! SIGHTLINE_BLESS=1 cargo test --test e2e invalid::
//! ```
//!
//! then read every changed file: the line and column must point at the offending
//! key or value, and the message must say what was expected and what was found.
//! A new fixture needs a line in `invalid_inputs!` below.

use std::path::PathBuf;

use crate::support::{arg, assert_matches_file, blessing, files_under, root, sightline, sightline_in, temp_dir};

const FIXTURES: &str = "tests/fixtures/invalid";

/// The directories in [`FIXTURES`] that hold the SUMO and OpenDRIVE files
/// fixtures import.
const IMPORTED: [&str; 2] = ["sumo", "opendrive"];

/// Panics unless every line of `stderr` has the form `file:line:col: error: …`
/// with 1-based numbers, `file` the scenario or a SUMO file it imports, so that a
/// blessed file cannot hold a malformed message.
#[track_caller]
fn assert_located(file: &str, stderr: &str) {
    assert!(!stderr.is_empty(), "no error printed for {file}");
    assert!(stderr.ends_with('\n'), "stderr does not end in a newline: {stderr:?}");
    for line in stderr.lines() {
        let rest = line
            .strip_prefix(file)
            .or_else(|| {
                IMPORTED.iter().find_map(|dir| {
                    let imported = format!("{FIXTURES}/{dir}/");
                    let rest = line.strip_prefix(&imported)?;
                    let name = &rest[..rest.find(':')?];
                    root().join(&imported).join(name).is_file().then(|| &rest[name.len()..])
                })
            })
            .and_then(|r| r.strip_prefix(':'))
            .unwrap_or_else(|| panic!("{line:?} does not start with `{file}:` or the path of a file it imports"));
        let mut parts = rest.splitn(3, ':');
        for what in ["line", "column"] {
            let number: usize = parts
                .next()
                .and_then(|n| n.parse().ok())
                .unwrap_or_else(|| panic!("{line:?} has no {what} number"));
            assert!(number >= 1, "{line:?}: {what} numbers start at 1");
        }
        let message = parts.next().unwrap_or_default();
        assert!(message.starts_with(" error: "), "{line:?} is not an error line");
    }
}

/// Runs `check` and `run` on one invalid fixture and compares with its `.stderr`.
#[track_caller]
fn assert_rejected(name: &str) {
    let scenario = format!("{FIXTURES}/{name}.yaml");
    let check = sightline(["check", &scenario]);
    check.assert_exit(2);
    assert_eq!(check.stdout, "", "check printed on stdout\n{check}");
    assert_located(&scenario, &check.stderr);
    assert_matches_file(&format!("{FIXTURES}/{name}.stderr"), &check.stderr);

    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", &scenario, "--out", arg(&out)]);
    run.assert_exit(2);
    assert_eq!(run.stdout, "", "run printed on stdout\n{run}");
    assert_eq!(run.stderr, check.stderr, "run and check disagree on {scenario}");
    assert!(!out.exists(), "run created {} for an invalid scenario", out.display());
    assert_eq!(files_under(tmp.path()), Vec::<PathBuf>::new(), "run wrote files");
}

macro_rules! invalid_inputs {
    ($($test:ident => $name:literal,)*) => {
        /// Every fixture the tests below cover.
        const NAMES: &[&str] = &[$($name),*];
        $(
            #[test]
            fn $test() {
                assert_rejected($name);
            }
        )*
    };
}

invalid_inputs! {
    a_character_yaml_does_not_allow_is_refused => "unprintable-character",
    a_control_character_written_as_an_escape_is_refused => "control-character-escape",
    a_bidirectional_override_is_refused => "bidi-override",
    agent_ids_that_would_nest_or_clash_are_refused => "agent-ids-refused",
    a_section_written_as_a_list_is_refused => "section-as-list",
    the_channels_rsu_antenna_where_every_rsu_has_its_own_is_refused => "traces-rsu-antenna-all-own",
    car_following_where_every_vehicle_replays_a_trace_is_refused => "traces-driving-without-driven-vehicles",
    occluder_types_name_what_the_imported_files_have => "traces-occluder-type-absent",
    map_occluder_types_name_what_the_map_has => "opendrive-occluder-type-absent",
    a_roadside_unit_listed_twice_and_a_sub_step_horizon_are_refused => "semantic-rsus-and-horizon",
    system_under_test_is_validated => "system-under-test-errors",
    system_under_test_sensors_are_on_its_agent => "system-under-test-sensors",
    system_under_test_runs_once => "system-under-test-run-once",
    system_metrics_need_a_system => "system-metric-without-system",
    system_checks_select_by_id_class_and_area_only => "system-under-test-objects",
    system_object_properties_are_validated => "system-object-properties",
    semantic_ego_must_be_connected => "semantic-ego-not-connected",
    semantic_rate_must_fit_the_step => "semantic-rate-off-step",
    semantic_runs_must_be_at_least_one => "semantic-runs-zero",
    checks_over_seeds_are_validated => "check-over-seeds-errors",
    a_share_of_every_seed_that_can_never_pass_is_refused => "holds-in-one",
    temporal_and_per_object_checks_are_validated => "temporal-check-errors",
    interaction_area_has_one_shape => "interaction-area-two-shapes",
    object_selections_and_comparisons_are_validated => "object-selection-errors",
    an_empty_object_selection_is_refused => "object-selection-empty",
    declared_areas_take_their_own_ids => "area-id-taken",
    semantic_traffic_errors_are_all_reported => "semantic-traffic-errors",
    malformed_yaml_is_a_syntax_error => "syntax-unclosed-flow",
    empty_file_is_refused => "empty",
    non_utf8_file_is_refused => "not-utf8",
    unsupported_language_version_is_refused => "unsupported-version",
    unknown_key_suggests_the_closest_key => "unknown-key",
    unknown_value_suggests_the_closest_value => "unknown-fusion-method",
    an_unknown_error_model_suggests_the_closest_reading => "unknown-error-model",
    missing_required_key_is_named => "missing-key",
    wrong_type_is_refused => "wrong-type",
    probability_above_one_is_out_of_range => "probability-above-one",
    negative_grid_size_is_out_of_range => "non-positive-size",
    zero_cell_size_is_out_of_range => "zero-cell",
    grid_size_not_a_whole_number_of_cells_is_refused => "size-not-multiple-of-cell",
    oversize_grid_is_refused_before_allocating => "oversize-grid",
    numbers_beyond_their_physical_range_are_refused => "numbers-beyond-physical-range",
    a_failed_road_is_the_one_error_not_the_routes_over_it => "arc-radius-too-small",
    ray_spacing_finer_than_any_lidar_is_refused => "ray-spacing-too-fine",
    rays_per_step_are_refused_as_a_product => "too-many-rays",
    a_vanishing_concentration_is_refused => "concentration-too-small",
    traffic_beyond_a_run_is_refused_before_it_is_generated => "traffic-too-dense",
    duplicate_key_is_refused => "duplicate-key",
    duplicate_requirement_id_is_refused => "duplicate-requirement-id",
    where_naming_no_setting_is_a_dangling_reference => "where-unknown-setting",
    where_matching_no_sweep_point_is_a_dangling_reference => "where-matches-no-point",
    metric_undefined_for_the_fusion_method_is_refused => "metric-undefined-for-method",
    metric_undefined_at_one_sweep_point_is_refused => "metric-undefined-at-sweep-point",
    hybrid_without_switch_is_refused => "hybrid-without-switch",
    sweep_over_an_unsweepable_section_is_refused => "sweep-unsweepable-section",
    sweep_over_the_recordings_clock_is_refused => "sweep-time-start",
    sweep_key_with_an_empty_segment_is_refused => "sweep-empty-segment",
    sweep_key_naming_no_setting_is_refused => "sweep-unknown-key",
    out_of_range_sweep_value_is_located_in_the_sweep => "sweep-value-out-of-range",
    vary_errors_are_all_reported => "vary-errors",
    out_of_range_vary_value_is_located_in_vary => "vary-value-out-of-range",
    a_whole_number_vary_range_beyond_2_53_is_refused_at_its_end => "vary-integer-range-beyond-2-53",
    vary_over_a_misnamed_agent_setting_is_refused => "vary-agent-errors",
    every_problem_of_a_file_is_reported_in_source_order => "several-errors",
    seed_beyond_64_bits_is_out_of_range => "seed-beyond-64-bits",
    route_that_does_not_connect_is_located_at_its_road => "route-not-connected",
    missing_trace_file_is_located_at_its_name => "traces-missing-file",
    malformed_trace_file_is_located_in_it => "traces-malformed-fcd",
    // issue 19: SUMO configurations, types, points of interest, networks.
    sumocfg_naming_a_missing_file_is_located_at_its_value => "traces-sumocfg-missing-net",
    sumocfg_without_fcd_output_is_located_at_its_key => "traces-sumocfg-no-fcd",
    malformed_sumocfg_is_located_in_it => "traces-sumocfg-malformed",
    unknown_vehicle_class_is_located_in_its_route_file => "traces-unknown-vclass",
    point_of_interest_on_a_missing_lane_is_located_at_it => "traces-poi-missing-lane",
    vehicle_type_declared_twice_names_the_first => "traces-duplicate-vtype",
    connection_to_a_missing_edge_is_located_at_it => "traces-net-missing-edge",
    rsus_without_sensors_and_a_wrong_file_kind_are_both_reported => "traces-rsus-without-sensors",
    rsus_of_a_type_no_point_of_interest_has_are_refused => "traces-rsus-unknown-type",
    rsu_antenna_below_the_urban_channel_is_refused => "traces-rsu-antenna-too-low",
    a_trace_position_beyond_the_coordinate_range_is_refused_at_the_attribute => "traces-fcd-position-beyond-range",
    a_lane_shape_beyond_the_coordinate_range_is_refused_at_the_coordinate => "traces-net-shape-beyond-range",
    a_polygon_shape_beyond_the_coordinate_range_is_refused_at_the_coordinate => "traces-poly-shape-beyond-range",
    unknown_sensor_model_is_a_dangling_reference => "unknown-sensor-model",
    record_point_beyond_the_sweep_is_out_of_range => "record-point-out-of-range",
    record_point_and_where_are_exclusive => "record-point-and-where",
    record_grid_rate_above_the_step_rate_is_refused => "record-grid-rate-above-step-rate",
    record_unknown_key_lists_the_keys => "record-unknown-key",
    record_where_matching_no_point_and_a_negative_rate_are_reported => "record-where-matches-no-point",
    record_every_point_or_one_not_both => "record-all-points-and-point",
    record_every_point_of_a_field_is_refused => "record-all-points-of-a-field",
    record_over_its_size_budget_is_refused => "record-too-large",
    // See: issue 13, case 1 ("no silent assumptions").
    grid_fusion_and_localization_in_a_semantic_world_are_refused => "semantic-fusion-keys",
    world_sections_in_the_field_experiment_are_refused => "field-with-world-sections",
    keys_their_settings_leave_without_effect_are_refused => "keys-without-effect",
    semantic_keys_their_settings_leave_without_effect_are_refused => "semantic-keys-without-effect",
    semantic_speed_keys_without_a_vehicle_are_refused => "semantic-speed-keys-without-vehicles",
    semantic_prediction_keys_without_a_conflict_to_predict_are_refused => "semantic-prediction-keys-without-conflicts",
    an_agent_starting_after_the_run_is_refused => "agent-starts-after-the-run",
    nlos_shadowing_without_a_building_is_refused => "radio-nlos-sigma-without-buildings",
    car_following_where_every_vehicle_is_parked_is_refused => "driving-with-parked-vehicles-only",
    vary_value_leaving_a_key_without_effect_is_refused => "vary-leaves-a-key-without-effect",
    // See: issue 15 (hostile input).
    aliases_that_multiply_are_refused_at_a_million_nodes => "alias-bomb",
    a_third_coordinate_is_refused_not_dropped => "point-with-a-third-coordinate",
    yaml_tags_are_refused => "tagged-value",
    nesting_is_refused_past_its_limit => "nesting-too-deep",
    // See: issue 16 (odometry with noise).
    odometry_out_of_physical_range_is_refused => "odometry-out-of-range",
    noise_beside_exact_odometry_is_refused => "odometry-exact-with-noise",
    // See: issue 16, "Bad input" (the radio in collective perception).
    radio_parameters_out_of_physical_range_are_refused => "radio-out-of-range",
    radio_the_step_cannot_serve_and_two_counts_of_cooperators_are_refused => "radio-limits-of-the-step",
    a_radio_metric_without_a_radio_is_refused => "radio-metric-without-v2x",
    // See: issue 17, part 4 (one world).
    a_joint_world_refuses_what_would_be_ambiguous => "joint-ambiguous-settings",
    a_joint_world_refuses_the_ambiguous_delivery_ratio => "joint-packet-delivery-ratio",
    what_only_a_joint_world_measures_is_refused_elsewhere => "grid-properties-outside-joint",
    joint_keys_their_settings_leave_without_effect_are_refused => "joint-keys-without-effect",
    // See: issue 18 (the recording's clock).
    time_start_without_its_offset_is_refused => "time-start-not-a-date",
    time_start_before_1970_is_out_of_range => "time-start-out-of-range",
    time_start_an_offset_of_a_day_is_refused => "time-start-offset-a-day",
    time_start_a_leap_second_is_refused => "time-start-leap-second",
    time_start_past_foxglove_timestamps_is_out_of_range => "time-start-after-2100",
    // See: issue 19, part 4 (bad OpenDRIVE maps).
    malformed_opendrive_is_located_in_the_map => "opendrive-malformed-xml",
    unknown_opendrive_element_suggests_the_closest => "opendrive-unknown-element",
    reference_line_that_does_not_close_is_located_at_its_record => "opendrive-geometry-gap",
    reference_line_whose_s_does_not_chain_is_located_at_its_record => "opendrive-geometry-s-gap",
    link_to_a_missing_road_is_located_at_the_link => "opendrive-missing-road",
    lane_link_to_a_missing_lane_is_located_at_the_link => "opendrive-missing-lane",
    map_beyond_the_point_limit_is_refused_before_sampling => "opendrive-points-beyond-limit",
    a_map_object_corner_beyond_the_coordinate_range_is_refused_at_the_attribute => "opendrive-object-corner-beyond-range",
    crosswalk_ends_closer_than_its_least_length_are_refused => "crosswalk-ends-too-close",
    a_run_beyond_the_work_of_one_process_is_refused => "run-work-beyond-limit",
    route_naming_a_missing_lane_suggests_the_closest => "opendrive-unknown-lane",
    lanes_without_a_speed_limit_need_map_speed_limit => "opendrive-speed-limit-missing",
    unknown_occluder_type_suggests_the_closest => "opendrive-occluder-type-unknown",
}

#[test]
fn every_invalid_fixture_is_tested_and_has_its_stderr() {
    let dir = root().join(FIXTURES);
    let mut yaml = Vec::new();
    let mut stderr = Vec::new();
    for path in files_under(&dir) {
        if IMPORTED.iter().any(|dir| path.starts_with(dir)) {
            continue;
        }
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        match path.extension().and_then(|e| e.to_str()) {
            Some("yaml") => yaml.push(name),
            Some("stderr") => stderr.push(name),
            _ => panic!("unexpected file {} in {FIXTURES}", path.display()),
        }
    }
    let mut listed: Vec<String> = NAMES.iter().map(|n| n.to_string()).collect();
    listed.sort();
    assert_eq!(
        yaml, listed,
        "every NAME.yaml is listed in invalid_inputs!, and only those"
    );
    if !blessing() {
        assert_eq!(
            stderr, listed,
            "every NAME.yaml has its NAME.stderr, and no .stderr is orphaned"
        );
    }
}

#[test]
fn invalid_file_makes_check_of_several_files_fail_without_ok_lines() {
    let valid = "tests/fixtures/valid/small-field.yaml";
    let invalid = format!("{FIXTURES}/duplicate-key.yaml");
    let outcome = sightline(["check", valid, &invalid]);
    outcome.assert_exit(2);
    assert_eq!(outcome.stdout, "", "{outcome}");
    assert_eq!(outcome.stderr, sightline(["check", &invalid]).stderr);
}

#[test]
fn missing_file_exits_2_and_writes_nothing() {
    let missing = "tests/fixtures/does-not-exist.yaml";
    let check = sightline(["check", missing]);
    check.assert_exit(2);
    assert!(
        check
            .stderr
            .starts_with(&format!("{missing}: error: failed to read the file: ")),
        "{check}"
    );
    assert_eq!(check.stderr.lines().count(), 1, "{check}");

    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", missing, "--out", arg(&out)]);
    run.assert_exit(2);
    assert_eq!(run.stderr, check.stderr);
    assert_eq!(files_under(tmp.path()), Vec::<PathBuf>::new());
}

#[test]
fn directory_given_as_scenario_exits_2() {
    let outcome = sightline(["check", "tests/fixtures"]);
    outcome.assert_exit(2);
    assert_eq!(
        outcome.stderr, "tests/fixtures: error: failed to read the file: a directory, not a regular file\n",
        "{outcome}"
    );
}

/// A FIFO would block `check` forever and `/dev/zero` would be read until
/// memory runs out: both are refused before a byte is read.
#[cfg(unix)]
#[test]
fn fifos_and_devices_are_refused_at_once() {
    let tmp = temp_dir();
    let fifo = tmp.path().join("scenario.yaml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success(), "mkfifo {}", fifo.display());
    for (file, what) in [(arg(&fifo), "a FIFO"), ("/dev/zero", "a device")] {
        let outcome = sightline(["check", file]);
        outcome.assert_exit(2);
        assert_eq!(
            outcome.stderr,
            format!("{file}: error: failed to read the file: {what}, not a regular file\n"),
            "{outcome}"
        );
    }
}

/// A symbolic link loop given as the scenario is named for what it is, not
/// left to the system's "too many levels of symbolic links" (#15).
#[cfg(unix)]
#[test]
fn a_symbolic_link_loop_is_refused() {
    let tmp = temp_dir();
    let (first, second) = (tmp.path().join("a.yaml"), tmp.path().join("b.yaml"));
    std::os::unix::fs::symlink(&second, &first).unwrap();
    std::os::unix::fs::symlink(&first, &second).unwrap();
    let outcome = sightline(["check", arg(&first)]);
    outcome.assert_exit(2);
    assert_eq!(
        outcome.stderr,
        format!(
            "{}: error: failed to read the file: a symbolic link loop, not a regular file\n",
            arg(&first)
        ),
        "{outcome}"
    );
}

/// A scenario file over 16 MiB is refused without being compiled.
#[test]
fn an_oversized_scenario_is_refused() {
    let tmp = temp_dir();
    let big = tmp.path().join("big.yaml");
    std::fs::write(&big, vec![b'#'; (16 << 20) + 1]).expect("the file is written");
    let outcome = sightline(["check", arg(&big)]);
    outcome.assert_exit(2);
    assert_eq!(
        outcome.stderr,
        format!(
            "{}: error: failed to read the file: larger than the limit of 16 MiB\n",
            arg(&big)
        ),
        "{outcome}"
    );
}

#[test]
fn usage_errors_exit_2_and_write_nothing() {
    let scenario = root().join("tests/fixtures/valid/small-field.yaml");
    let scenario = arg(&scenario);
    let cases: [&[&str]; 10] = [
        &[],
        &["frobnicate"],
        &["run"],
        &["check"],
        &["run", scenario, "--frobnicate"],
        &["run", scenario, "--jobs", "0"],
        &["run", scenario, "--jobs", "two"],
        &["run", scenario, "--seed", "-1"],
        &["run", scenario, "--seed", "18446744073709551616"],
        &["run", scenario, "--out"],
    ];
    for args in cases {
        // Run in an empty directory: the default evidence directory (out/) must
        // not appear either.
        let tmp = temp_dir();
        let outcome = sightline_in(tmp.path(), args);
        outcome.assert_exit(2);
        assert_eq!(outcome.stdout, "", "{outcome}");
        assert!(
            outcome.stderr.starts_with("error: ") || outcome.stderr.contains("\nUsage: "),
            "no usage error printed\n{outcome}"
        );
        assert_eq!(files_under(tmp.path()), Vec::<PathBuf>::new(), "{outcome}");
    }
}
