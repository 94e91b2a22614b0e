//! The compiled model: what a valid file becomes, and how problems are reported.

use sightline_dsl::{
    Bound, Check, DecisionRule, ErrorKind, ErrorModel, Errors, Experiment, Layout, Location, Metric, Options,
    OverSeeds, Point, RateBound, Rule, Scenario, SourceCombination, Statistic, Switch, SwitchMeasure, WeightScaling,
    Weighting, compile,
};

const BASE: &str = "sightline: 1
name: t
grid: { size: [20, 10], cell: 0.5 }
field:
  truth: { occupied_fraction: 0.2 }
  sensors: { range: 15, layout: { regular: { rows: 1, cols: 2 } } }
  masses: { gamma: 10 }
";

/// [`BASE`] without γ, for sweeps that set it at every point: a value of the
/// file that every point replaces is refused.
fn base_without_gamma() -> String {
    BASE.replace("masses: { gamma: 10 }", "masses: {}")
}

fn ok(text: &str) -> Scenario {
    compile("t.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn errors(text: &str) -> Errors {
    compile("t.yaml", text, &Options::default()).expect_err("the file is invalid")
}

#[test]
fn defaults_follow_the_paper() {
    let scenario = ok(BASE);
    let setup = &scenario.points[0].setup;
    assert_eq!(setup.seed, 0);
    let occupancy = setup.occupancy.as_ref().unwrap();
    assert_eq!(occupancy.decision.threshold, 0.8);
    assert_eq!(occupancy.decision.rule, DecisionRule::Margin);
    assert_eq!(occupancy.fusion.rule, Rule::Dempster);
    assert_eq!(occupancy.fusion.label, "dempster");
    assert_eq!((occupancy.grid.cols, occupancy.grid.rows), (40, 20));
    let Experiment::Field(field) = &setup.experiment else {
        panic!("a field scenario")
    };
    assert_eq!(field.masses.concentration, 32.0);
    assert_eq!(field.masses.epsilon0, 0.0625);
    assert_eq!(field.truth.blob_cells, 1);
    assert_eq!(field.distance_bands, vec![50.0, 100.0, 150.0, 200.0]);
    // A regular 1 × 2 layout sits at the centres of two 10 × 10 m tiles.
    assert_eq!(field.layout, Layout::Positions(vec![[5.0, 5.0], [15.0, 5.0]]));
}

#[test]
fn sweep_expands_first_axis_outermost() {
    let scenario = ok(&format!(
        "{}sweep:\n  field.masses.gamma: [6, 14]\n  fusion:\n    - {{ label: B, method: dempster }}\n    - {{ label: P, method: hybrid, weights: mean_one, sources: pairwise, switch: {{ measure: ratio, threshold: 2 }} }}\n",
        base_without_gamma()
    ));
    let labels: Vec<String> = scenario.points.iter().map(|p| p.label()).collect();
    assert_eq!(
        labels,
        [
            "field.masses.gamma=6, fusion=B",
            "field.masses.gamma=6, fusion=P",
            "field.masses.gamma=14, fusion=B",
            "field.masses.gamma=14, fusion=P"
        ]
    );
    assert_eq!(
        scenario.points[3].setup.occupancy.as_ref().unwrap().fusion.rule,
        Rule::Hybrid {
            weighting: Weighting {
                scaling: WeightScaling::MeanOne,
                sources: SourceCombination::Pairwise
            },
            switch: Switch {
                measure: SwitchMeasure::Ratio,
                threshold: 2.0
            }
        }
    );
    let Experiment::Field(field) = &scenario.points[2].setup.experiment else {
        panic!("a field scenario")
    };
    assert_eq!(field.masses.gamma, 14.0);
}

#[test]
fn where_selects_points_by_effective_settings() {
    let scenario = ok(&format!(
        "{}sweep:\n  field.masses.gamma: [6, 14]\n  fusion.method: [dempster, bayes]\nrequirements:\n  - id: R1\n    text: conflict stays low\n    where: {{ fusion.label: dempster, field.masses.gamma: 14.0 }}\n    check: {{ metric: mean_conflict, at_most: 0.5 }}\n",
        base_without_gamma()
    ));
    let requirement = &scenario.requirements[0];
    assert_eq!(requirement.points, vec![2]);
    assert_eq!(requirement.location, Location::new(12, 5));
    assert_eq!(
        requirement.check,
        Check::Metric {
            metric: Metric::MeanConflict,
            bound: Bound::AtMost(0.5),
            over_seeds: None,
        }
    );
}

#[test]
fn checks_over_seeds_take_their_defaults_and_bounds() {
    let scenario = ok(&format!(
        "{BASE}requirements:\n  - id: R1\n    text: accurate over seeds\n    check: {{ metric: accuracy, at_least: 0.5, seeds: 12 }}\n  - id: R2\n    text: mostly accurate\n    check: {{ metric: accuracy, at_least: 0.5, seeds: 30, confidence: 0.9, holds_in: 0.8, method: wilson }}\n"
    ));
    let over = |i: usize| match scenario.requirements[i].check {
        Check::Metric { over_seeds, .. } => over_seeds.unwrap(),
        _ => panic!("a metric check"),
    };
    assert_eq!(
        over(0),
        OverSeeds {
            seeds: 12,
            confidence: 0.95,
            statistic: Statistic::Mean
        }
    );
    assert_eq!(
        over(1).statistic,
        Statistic::Share {
            share: 0.8,
            method: RateBound::Wilson
        }
    );
    assert_eq!(over(1).confidence, 0.9);
}

#[test]
fn seed_spans_the_whole_u64_range() {
    let scenario = ok(&format!("{BASE}seed: 18446744073709551615\n"));
    assert_eq!(scenario.points[0].setup.seed, u64::MAX);
}

#[test]
fn seed_option_replaces_the_file_seed() {
    let scenario = compile(
        "t.yaml",
        BASE,
        &Options {
            seed: Some(99),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(scenario.points[0].setup.seed, 99);
    let swept = format!("{BASE}sweep:\n  seed: [1, 2]\n");
    let error = compile(
        "t.yaml",
        &swept,
        &Options {
            seed: Some(99),
            ..Default::default()
        },
    )
    .unwrap_err();
    assert_eq!(error.0[0].path, "sweep.seed");
}

#[test]
fn compile_errors_are_reported_together_in_source_order() {
    let text = format!(
        "{BASE}decision: {{ threshold: 1.5 }}\nrequirements:\n  - {{ id: A, text: x, check: {{ metric: accuracy, at_least: 0.9 }} }}\n  - {{ id: A, text: y, check: {{ metric: accuracy }} }}\n"
    )
    .replace("occupied_fraction: 0.2", "occupied_fraction: -0.2");
    let errors = errors(&text);
    let paths: Vec<&str> = errors.0.iter().map(|e| e.path.as_str()).collect();
    assert_eq!(
        paths,
        [
            "field.truth.occupied_fraction",
            "decision.threshold",
            "requirements[1].id",
            "requirements[1].check"
        ]
    );
    assert!(matches!(errors.0[2].kind, ErrorKind::DuplicateId { .. }));
}

#[test]
fn a_bad_swept_value_is_reported_at_the_value() {
    let errors = errors(&format!("{BASE}sweep:\n  decision.threshold: [0.5, 2]\n"));
    assert_eq!(errors.0.len(), 1);
    assert_eq!(errors.0[0].location, Location::new(9, 29));
    assert_eq!(errors.0[0].path, "decision.threshold");
}

#[test]
fn the_decision_rule_is_read_and_an_unknown_one_refused_where_written() {
    for (written, rule) in [("margin", DecisionRule::Margin), ("exceeds", DecisionRule::Exceeds)] {
        let scenario = ok(&format!("{BASE}decision: {{ rule: {written}, threshold: 0.6 }}\n"));
        let decision = scenario.points[0].setup.occupancy.as_ref().unwrap().decision;
        assert_eq!((decision.rule, decision.threshold), (rule, 0.6), "{written}");
    }
    // Swept, each reading is its own point.
    let swept = ok(&format!("{BASE}sweep:\n  decision.rule: [margin, exceeds]\n"));
    let rules: Vec<DecisionRule> = swept
        .points
        .iter()
        .map(|point| point.setup.occupancy.as_ref().unwrap().decision.rule)
        .collect();
    assert_eq!(rules, [DecisionRule::Margin, DecisionRule::Exceeds]);
    // Line 8, the value after `decision: { rule: `.
    let refused = errors(&format!("{BASE}decision: {{ rule: exceed }}\n"));
    assert_eq!(refused.0.len(), 1);
    assert_eq!(refused.0[0].path, "decision.rule");
    assert_eq!(refused.0[0].location, Location::new(8, 19));
    let message = refused.to_string();
    assert!(message.starts_with("t.yaml:8:19: error:"), "{message}");
    assert!(message.contains("exceeds"), "the closest rule is suggested: {message}");
    let swept = errors(&format!("{BASE}sweep:\n  decision.rule: [margin, p_max]\n"));
    assert_eq!(swept.0[0].location, Location::new(9, 27));
}

/// The error model of the field's masses.
fn error_model(point: &Point) -> ErrorModel {
    match &point.setup.experiment {
        Experiment::Field(field) => field.masses.error_model,
        other => panic!("a field scenario, not {other:?}"),
    }
}

#[test]
fn the_error_model_is_read_and_an_unknown_one_refused_where_written() {
    for (written, model) in [
        ("dirichlet_mean", ErrorModel::DirichletMean),
        ("wrong_label", ErrorModel::WrongLabel),
        ("dirichlet_toward_empty", ErrorModel::DirichletTowardEmpty),
    ] {
        let scenario = ok(&BASE.replace(
            "masses: { gamma: 10 }",
            &format!("masses: {{ gamma: 10, error_model: {written} }}"),
        ));
        assert_eq!(error_model(&scenario.points[0]), model, "{written}");
    }
    // Swept, each reading is its own point.
    let swept = ok(&format!(
        "{BASE}sweep:\n  field.masses.error_model: [dirichlet_mean, wrong_label, dirichlet_toward_empty]\n"
    ));
    let models: Vec<ErrorModel> = swept.points.iter().map(error_model).collect();
    assert_eq!(
        models,
        [
            ErrorModel::DirichletMean,
            ErrorModel::WrongLabel,
            ErrorModel::DirichletTowardEmpty
        ]
    );
    // Line 7, the value after `masses: { gamma: 10, error_model: `.
    let refused = errors(&BASE.replace(
        "masses: { gamma: 10 }",
        "masses: { gamma: 10, error_model: dirichlet_toward_emty }",
    ));
    assert_eq!(refused.0.len(), 1);
    assert_eq!(refused.0[0].path, "field.masses.error_model");
    assert_eq!(refused.0[0].location, Location::new(7, 37));
    let message = refused.to_string();
    assert!(message.starts_with("t.yaml:7:37: error:"), "{message}");
    assert!(
        message.contains("(did you mean `dirichlet_toward_empty`?)"),
        "{message}"
    );
    let swept = errors(&format!(
        "{BASE}sweep:\n  field.masses.error_model: [wrong_label, dirichlet_text]\n"
    ));
    assert_eq!(swept.0[0].path, "field.masses.error_model");
    assert_eq!(swept.0[0].location, Location::new(9, 43));
}

#[test]
fn a_requirement_that_checks_nothing_is_an_error() {
    let errors = errors(&format!(
        "{BASE}sweep:\n  fusion.method: [dempster, bayes]\nrequirements:\n  - {{ id: A, text: x, where: {{ fusion.method: hybrid }}, check: {{ metric: accuracy, at_least: 0.9 }} }}\n"
    ));
    assert!(matches!(errors.0[0].kind, ErrorKind::DanglingReference(ref m) if m.starts_with("matches no sweep point")));
}

#[test]
fn evidential_metrics_are_refused_at_bayes_points() {
    let errors = errors(&format!(
        "{BASE}fusion: {{ method: bayes }}\nrequirements:\n  - {{ id: A, text: x, check: {{ metric: max_conflict, at_most: 0.9 }} }}\n"
    ));
    assert_eq!(errors.0[0].path, "requirements[0].check.metric");
}

#[test]
fn misdetection_must_stay_below_one_at_the_range() {
    let errors = errors(&BASE.replace("gamma: 10", "gamma: 95"));
    assert_eq!(errors.0[0].path, "field.masses.gamma");
    assert!(errors.0[0].to_string().contains("γ < 93.75"));
}

#[test]
fn overlapping_and_unsweepable_keys_are_refused() {
    let overlap = errors(&format!(
        "{BASE}sweep:\n  fusion: [{{ method: bayes }}]\n  fusion.method: [dempster]\n"
    ));
    assert!(overlap.0[0].to_string().contains("overlaps the sweep key `fusion`"));
    let name = errors(&format!("{BASE}sweep:\n  name: [a, b]\n"));
    assert!(name.0[0].to_string().contains("cannot sweep `name`"));
}

#[test]
fn independent_sweeps_run_one_after_the_other() {
    let scenario = ok(&format!(
        "{BASE}sweeps:\n  - {{ field.masses.gamma: [6, 14] }}\n  - {{ decision.threshold: [0.7, 0.8, 0.9] }}\n"
    ));
    assert_eq!(scenario.sweeps.len(), 2);
    assert_eq!(scenario.sweeps[0].points, vec![0, 1]);
    assert_eq!(scenario.sweeps[1].points, vec![2, 3, 4]);
    let labels: Vec<String> = scenario.points.iter().map(|p| p.label()).collect();
    assert_eq!(labels[1], "field.masses.gamma=14");
    assert_eq!(labels[4], "decision.threshold=0.9");
    assert_eq!(scenario.points[3].labels[0].sweep, Some(1));
    // The second sweep leaves γ as the file has it.
    let Experiment::Field(field) = &scenario.points[3].setup.experiment else {
        panic!("a field scenario")
    };
    assert_eq!(field.masses.gamma, 10.0);
}

#[test]
fn sweep_and_sweeps_do_not_mix() {
    let errors = errors(&format!(
        "{BASE}sweep:\n  seed: [1, 2]\nsweeps:\n  - {{ decision.threshold: [0.7] }}\n"
    ));
    assert!(
        errors.0[0]
            .to_string()
            .contains("give `sweep` (one sweep) or `sweeps` (several), not both")
    );
}

#[test]
fn vary_keeps_integer_settings_whole_and_instantiates_a_concrete_scenario() {
    use sightline_dsl::{Domain, RANGE_STEPS, Vary, instantiate};
    let text = format!(
        "{BASE}vary:\n  field.sensors.layout.regular.rows: [1, 3]\n  field.masses.gamma: [0, 20]\n  fusion.method: {{ one_of: [dempster, bayes] }}\n"
    );
    let scenario = ok(&text);
    // `run` runs the values written in the file.
    let Experiment::Field(field) = &scenario.points[0].setup.experiment else {
        panic!("a field scenario")
    };
    assert_eq!(field.masses.gamma, 10.0);
    let domains: Vec<&Domain> = scenario.vary.iter().map(|v| &v.domain).collect();
    assert_eq!(
        domains,
        [
            &Domain::Range {
                lo: 1.0,
                hi: 3.0,
                integer: true
            },
            &Domain::Range {
                lo: 0.0,
                hi: 20.0,
                integer: false
            },
            &Domain::Choices(vec!["dempster".into(), "bayes".into()]),
        ]
    );
    let counts: Vec<u64> = scenario.vary.iter().map(|v| v.count()).collect();
    assert_eq!(counts, [3, RANGE_STEPS + 1, 2]);

    let case = instantiate("t.yaml", &text, &Vary::settings(&scenario.vary, &[1, 250, 1])).unwrap();
    assert!(!case.contains("vary"), "{case}");
    let concrete = ok(&case);
    assert!(concrete.vary.is_empty());
    let setup = &concrete.points[0].setup;
    assert_eq!(setup.occupancy.as_ref().unwrap().fusion.rule, Rule::Bayes);
    let Experiment::Field(field) = &setup.experiment else {
        panic!("a field scenario")
    };
    assert_eq!(field.masses.gamma, 5.0);
    assert!(case.contains("rows: 2,") || case.contains("rows: 2\n"), "{case}");
    let Layout::Positions(positions) = &field.layout else {
        panic!("a regular layout becomes positions")
    };
    assert_eq!(positions.len(), 4);
}

/// See: issue 13 §6. A combination of one sweep that is the same configuration as
/// one of another (γ = 10 at the default threshold 0.8, the threshold 0.8 at the
/// file's γ = 10) is one point carrying both labels, which `where` reaches by
/// either.
#[test]
fn sweeps_that_meet_share_one_point() {
    let scenario = ok(&format!(
        "{BASE}sweeps:\n  - {{ field.masses.gamma: [6, 10] }}\n  - {{ decision.threshold: [0.7, 0.8, 0.9] }}\nrequirements:\n  - {{ id: R1, text: t, where: {{ decision.threshold: 0.8 }}, check: {{ metric: accuracy, at_least: 0.5 }} }}\n  - {{ id: R2, text: t, where: {{ field.masses.gamma: 10 }}, check: {{ metric: accuracy, at_least: 0.5 }} }}\n"
    ));
    let labels: Vec<String> = scenario.points.iter().map(|p| p.label()).collect();
    assert_eq!(
        labels,
        [
            "field.masses.gamma=6",
            "field.masses.gamma=10 | decision.threshold=0.8",
            "decision.threshold=0.7",
            "decision.threshold=0.9"
        ]
    );
    assert_eq!(scenario.sweeps[0].points, [0, 1]);
    assert_eq!(scenario.sweeps[1].points, [2, 1, 3]);
    let shared = &scenario.points[1];
    let sweeps: Vec<Option<usize>> = shared.labels.iter().map(|l| l.sweep).collect();
    assert_eq!(sweeps, [Some(0), Some(1)]);
    // Every sweep keeps all its rows, each with its own values.
    let rows: Vec<(usize, Vec<serde_json::Value>)> = scenario.sweeps[1]
        .rows()
        .map(|(point, values)| (point, values.into_iter().cloned().collect()))
        .collect();
    assert_eq!(
        rows,
        [
            (2, vec![serde_json::json!(0.7)]),
            (1, vec![serde_json::json!(0.8)]),
            (3, vec![serde_json::json!(0.9)])
        ]
    );
    assert_eq!(scenario.requirements[0].points, [0, 1], "γ = 6 and the shared point");
    assert_eq!(
        scenario.requirements[1].points,
        [1, 2, 3],
        "every point of the second sweep"
    );
}

/// Two combinations of one sweep that compile to the same setup (a label equal to
/// the default one) are one point too, listed twice by its sweep.
#[test]
fn one_sweep_lists_a_point_once_per_row() {
    let scenario = ok(&format!(
        "{BASE}sweep:\n  fusion: [{{ method: bayes }}, {{ method: bayes, label: bayes }}, {{ method: dempster }}]\n"
    ));
    assert_eq!(scenario.points.len(), 2);
    assert_eq!(scenario.sweeps[0].points, [0, 0, 1]);
    assert_eq!(scenario.points[0].label(), "fusion={method=bayes} | fusion=bayes");
}

/// Two points that would show under one label (tables, messages and JUnit name
/// points by it) are refused, within a sweep and across sweeps.
#[test]
fn two_points_under_one_label_are_refused() {
    for (sweeps, location) in [
        (
            "sweep:\n  fusion: [{ label: A, method: bayes }, { label: A, method: dempster }]\n",
            Location::new(9, 41),
        ),
        (
            "sweeps:\n  - fusion: [{ label: A, method: bayes }]\n  - fusion: [{ label: A, method: dempster }]\n",
            Location::new(10, 14),
        ),
    ] {
        let refused = errors(&format!("{BASE}{sweeps}"));
        assert_eq!(refused.0.len(), 1, "{refused}");
        assert_eq!(refused.0[0].location, location, "{refused}");
        assert!(
            matches!(refused.0[0].kind, ErrorKind::Invalid(ref m) if m.contains("`fusion=A` names two different")),
            "{refused}"
        );
    }
}

/// Equal setups are the test, to the bit: 0 and −0 stay two points.
#[test]
fn zero_and_negative_zero_stay_apart() {
    let scenario = ok(&format!(
        "{}sweeps:\n  - {{ field.masses.gamma: [0] }}\n  - {{ field.masses.gamma: [-0.0] }}\n  - {{ field.masses.gamma: [0.0] }}\n",
        base_without_gamma()
    ));
    assert_eq!(scenario.points.len(), 2);
    assert_eq!(scenario.sweeps[2].points, [0]);
}

#[test]
fn sweep_sizes_are_checked_before_the_points_are_made() {
    let values = |n: usize| (0..n).map(|i| i.to_string()).collect::<Vec<_>>().join(", ");
    // Three axes of 30 values make 27 000 combinations: refused at the sweep.
    let text = format!(
        "{}sweep:\n  seed: [{}]\n  field.masses.gamma: [{}]\n  field.masses.concentration: [{}]\n",
        base_without_gamma(),
        values(30),
        (1..=30).map(|g| format!("{g}.5")).collect::<Vec<_>>().join(", "),
        (1..=30).map(|r| format!("{r}.25")).collect::<Vec<_>>().join(", "),
    );
    let refused = errors(&text);
    assert_eq!(refused.0.len(), 1, "{refused}");
    assert_eq!(
        (refused.0[0].path.as_str(), refused.0[0].location),
        ("sweep", Location::new(8, 1))
    );
    assert!(matches!(refused.0[0].kind, ErrorKind::TooLarge(ref m) if m.contains("more than 10000 points")));

    // Each combination compiles its own copy of the file: 9 000 copies of a file
    // of a few hundred nodes are refused, 1 000 are compiled.
    let occluders: String = (0..60)
        .map(|i| format!("  - {{ id: o{i}, polygon: [[{i}, 0], [{i}.5, 0], [{i}.5, 1]] }}\n"))
        .collect();
    let world = |seeds: usize| {
        format!(
            "sightline: 1\nname: t\ngrid: {{ size: [100, 10], cell: 1 }}\ntime: {{ duration: 1, step: 0.1 }}\nroads:\n  - {{ id: r, polyline: [[0, 0], [100, 0]], speed_limit: 10 }}\n\
             occluders:\n{occluders}sensor_models:\n  s: {{ range: 10 }}\n\
             agents:\n  - {{ id: a, kind: car, route: [r], speed: {{ target: 5 }}, sensors: [s] }}\n\
             perception: {{ ego: a }}\nsweep:\n  seed: [{}]\n",
            values(seeds)
        )
    };
    let refused = errors(&world(9000));
    assert!(
        matches!(refused.0[0].kind, ErrorKind::TooLarge(ref m) if m.contains("each compile a copy")),
        "{refused}"
    );
    assert_eq!(ok(&world(1000)).points.len(), 1000);
}

#[test]
fn a_file_value_every_sweep_point_replaces_is_refused_where_it_is_written() {
    // The file's γ (line 7) and method (line 8) are replaced at every point.
    let text = format!(
        "{BASE}fusion: {{ method: bayes, label: F }}\nsweep:\n  field.masses.gamma: [6, 14]\n  fusion.method: [dempster, bayes]\n"
    );
    let refused = errors(&text);
    let found: Vec<(&str, Location)> = refused.0.iter().map(|e| (e.path.as_str(), e.location)).collect();
    assert_eq!(
        found,
        [
            ("field.masses.gamma", Location::new(7, 13)),
            ("fusion.method", Location::new(8, 11))
        ],
        "{refused}"
    );
    assert!(matches!(&refused.0[1].kind, ErrorKind::NoEffect(why)
        if why == "`sweep.fusion.method` replaces it at every sweep point; leave it out of the file"));

    // A swept section replaces every key of it the file writes.
    let refused = errors(&format!(
        "{BASE}fusion: {{ method: bayes }}\nsweep:\n  fusion: [{{ method: dempster }}, {{ method: bayes }}]\n"
    ));
    assert_eq!(
        (refused.0[0].path.as_str(), refused.0[0].location),
        ("fusion", Location::new(8, 1))
    );

    // Replaced in every sweep, each named; kept when one sweep leaves it as written.
    let refused = errors(&format!(
        "{BASE}sweeps:\n  - {{ field.masses.gamma: [6] }}\n  - {{ field: [{{ truth: {{ occupied_fraction: 0.2 }}, sensors: {{ range: 15, layout: {{ regular: {{ rows: 1, cols: 2 }} }} }}, masses: {{ gamma: 8 }} }}] }}\n"
    ));
    assert!(
        refused.0.iter().any(|e| e.path == "field.masses.gamma"
            && e.to_string()
                .contains("`sweeps[0].field.masses.gamma` and `sweeps[1].field` replace it")),
        "{refused}"
    );
    ok(&format!(
        "{BASE}sweeps:\n  - {{ field.masses.gamma: [6, 14] }}\n  - {{ decision.threshold: [0.7] }}\n"
    ));
}

#[test]
fn a_key_every_sweep_point_sets_counts_as_given() {
    // γ is required; the sweep gives it at every point.
    let scenario = ok(&format!(
        "{}sweep:\n  field.masses.gamma: [6, 14]\n",
        base_without_gamma()
    ));
    let gammas: Vec<f64> = scenario
        .points
        .iter()
        .map(|p| match &p.setup.experiment {
            Experiment::Field(field) => field.masses.gamma,
            _ => panic!("a field scenario"),
        })
        .collect();
    assert_eq!(gammas, [6.0, 14.0]);
    // A bad swept value is still reported at the value, once.
    let refused = errors(&format!(
        "{}sweep:\n  field.masses.gamma: [-2, 6]\n",
        base_without_gamma()
    ));
    assert_eq!(refused.0.len(), 1, "{refused}");
    assert_eq!(refused.0[0].location, Location::new(9, 24));
    // A sweep that leaves it out leaves it missing.
    let refused = errors(&format!(
        "{}sweeps:\n  - {{ field.masses.gamma: [6] }}\n  - {{ decision.threshold: [0.7] }}\n",
        base_without_gamma()
    ));
    assert!(refused.to_string().contains("missing key `gamma`"), "{refused}");
}

#[test]
fn the_field_refuses_an_origin_its_layout_moves_with() {
    let moved = BASE.replace("grid: { size", "grid: { origin: [5, 0], size");
    for layout in ["regular: { rows: 1, cols: 2 }", "random: { count: 3 }"] {
        let refused = errors(&moved.replace("regular: { rows: 1, cols: 2 }", layout));
        assert_eq!(
            (refused.0[0].path.as_str(), refused.0[0].location),
            ("grid.origin", Location::new(3, 9)),
            "{refused}"
        );
        assert!(matches!(&refused.0[0].kind, ErrorKind::NoEffect(why) if why.contains("no distance changes")));
    }
    // Told in one pass with a value every sweep point replaces.
    let both = errors(&format!("{moved}sweep:\n  field.masses.gamma: [6, 14]\n"));
    let paths: Vec<&str> = both.0.iter().map(|e| e.path.as_str()).collect();
    assert_eq!(paths, ["grid.origin", "field.masses.gamma"], "{both}");
    // Given positions, the grid's origin decides which cells they see.
    ok(&moved.replace("regular: { rows: 1, cols: 2 }", "positions: [[5, 5], [15, 5]]"));
}
