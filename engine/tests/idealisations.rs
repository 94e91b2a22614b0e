//! Idealisations stated (issue 13): every model option of the language maps to
//! the idealisations it adds, or explicitly to none, and a run lists those its
//! settings assumed.
// See: issue 13, "Idealisations stated".

use std::collections::BTreeMap;

use serde::de::DeserializeOwned;
use serde_json::Value;
use sightline_dsl::{Options, compile};
use sightline_engine::{Idealisation, ModelOption, idealisations};

/// `value` of one of the language's enumerations.
fn parse<T: DeserializeOwned>(value: &str) -> T {
    serde_json::from_value(Value::String(value.into())).unwrap_or_else(|e| panic!("`{value}`: {e}"))
}

/// The model option that the value `value` of the language's enumeration
/// `name` selects; `None` when `name` selects no model.
fn option(name: &str, value: &str) -> Option<ModelOption> {
    Some(match name {
        "PoseFilter" => ModelOption::PoseFilter(parse(value)),
        "OdometryModel" => ModelOption::OdometryModel(parse(value)),
        "FusionMethod" => ModelOption::FusionMethod(parse(value)),
        "WeightScaling" => ModelOption::WeightScaling(parse(value)),
        "SourceCombination" => ModelOption::SourceCombination(parse(value)),
        "SwitchMeasure" => ModelOption::SwitchMeasure(parse(value)),
        "ErrorModel" => ModelOption::ErrorModel(parse(value)),
        "PathLossModel" => ModelOption::PathLossModel(parse(value)),
        "Following" => ModelOption::Following(parse(value)),
        "RiskScope" => ModelOption::RiskScope(parse(value)),
        "RsuSight" => ModelOption::RsuSight(parse(value)),
        "ShareCycles" => ModelOption::ShareCycles(parse(value)),
        "LabelledBy" => ModelOption::LabelledBy(parse(value)),
        _ => return None,
    })
}

/// The enumerations of the language that select no model, and why.
const NOT_OPTIONS: &[(&str, &str)] = &[
    ("Metric", "what a requirement measures"),
    ("Signal", "what a requirement follows over time"),
    (
        "ObjectProperty",
        "what a requirement asks of every road user it selects",
    ),
    ("Comparison", "how a requirement compares two metrics"),
    ("Invariant", "what a requirement asks of every fused cell"),
    ("RateBound", "how a check over seeds bounds a share"),
    (
        "AgentKind",
        "what an agent is (its footprint and role), not how it is modelled",
    ),
    ("Direction", "a roundabout's geometry"),
    (
        "Oversize",
        "how a sender fits its grid into messages: behaviour the radio models, neither way idealised",
    ),
    ("Paper", "the paper the report is laid out for"),
    (
        "DecisionRule",
        "how a fused cell is judged: which statement of seed 001's metric, not a model of the world",
    ),
    ("RecordedPoints", "which sweep points the recording holds step by step"),
];

/// The option values that add no idealisation to their model's own, each
/// explicitly.
const NONE: &[(&str, &str)] = &[
    ("PoseFilter", "kalman"),
    ("PoseFilter", "none"),
    ("WeightScaling", "sum_to_one"),
    ("WeightScaling", "mean_one"),
    ("WeightScaling", "nearest_one"),
    ("SourceCombination", "all_at_once"),
    ("SourceCombination", "pairwise"),
    ("SwitchMeasure", "difference"),
    ("SwitchMeasure", "ratio"),
    ("RiskScope", "relevant"),
    ("RiskScope", "all"),
    ("ShareCycles", "ego_in_range"),
    ("ShareCycles", "all"),
    ("LabelledBy", "any"),
    ("LabelledBy", "critical"),
];

/// Every enumeration of the language's JSON Schema, with its values.
fn enumerations() -> BTreeMap<String, Vec<String>> {
    let schema = sightline_dsl::schema();
    schema["definitions"]
        .as_object()
        .expect("the schema has definitions")
        .iter()
        .filter_map(|(name, definition)| {
            let values: Vec<String> = definition["oneOf"]
                .as_array()?
                .iter()
                .map(|v| v["const"].as_str().map(str::to_owned))
                .collect::<Option<_>>()?;
            Some((name.clone(), values))
        })
        .collect()
}

#[test]
fn every_model_option_states_its_idealisations_or_none() {
    let enumerations = enumerations();
    assert!(
        enumerations.contains_key("PoseFilter"),
        "the schema's enumerations are found"
    );
    for (name, values) in &enumerations {
        let not_option = NOT_OPTIONS.iter().any(|(n, _)| n == name);
        for value in values {
            match option(name, value) {
                Some(_) if not_option => panic!("{name} is listed as selecting no model, but selects one"),
                None if !not_option => panic!(
                    "the language's enumeration {name} is neither a model option (map it to a ModelOption, whose \
                     idealisations it must state) nor listed in NOT_OPTIONS"
                ),
                None => {}
                Some(option) => {
                    let stated = option.idealisations();
                    let none = NONE.contains(&(name.as_str(), value.as_str()));
                    assert!(
                        stated.is_empty() == none,
                        "{name} `{value}`: {} but {}",
                        if none {
                            "listed as adding none"
                        } else {
                            "not listed as adding none"
                        },
                        if stated.is_empty() { "adds none" } else { "adds some" }
                    );
                }
            }
        }
    }
    for (name, value) in NONE {
        assert!(
            enumerations
                .get(*name)
                .is_some_and(|values| values.iter().any(|v| v == value)),
            "NONE lists {name} `{value}`, which the language does not have"
        );
    }
}

/// The idealisations of the one-point scenario `text`, by id.
fn ids(text: &str) -> Vec<&'static str> {
    let scenario = compile("t.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
    idealisations(&scenario).iter().map(|i| i.id).collect()
}

const WORLD: &str = "sightline: 1
name: w
time: { duration: 1, step: 0.1 }
grid: { origin: [-20, -20], size: [40, 40], cell: 1 }
roads: [{ id: r, polyline: [[0, -20], [0, 20]], speed_limit: 10 }]
sensor_models: { s: { range: 10 } }
agents:
  - { id: ego, kind: car, route: [r], speed: { target: 5 }, connected: true, sensors: [s] }
  - { id: cav, kind: car, route: [r], start: { offset: 10 }, speed: { target: 5 }, connected: true, sensors: [s] }
localization: { position_sigma: 0.2, filter: kalman }
perception: { ego: ego }
fusion: { method: bayes }
";

#[test]
fn a_run_lists_what_its_options_assume() {
    let kalman = ids(WORLD);
    for id in [
        "sight.planar",
        "sight.outlines",
        "sight.fan",
        "world.lossless-exchange",
        "localization.white-noise",
    ] {
        assert!(kalman.contains(&id), "{id} missing from {kalman:?}");
    }
    // Noisy odometry by default: what it still idealises, never exact odometry.
    assert!(kalman.contains(&"localization.noisy-odometry") && !kalman.contains(&"localization.exact-odometry"));
    let exact_odometry = ids(&WORLD.replace("filter: kalman", "filter: kalman, odometry: { model: exact }"));
    assert!(
        exact_odometry.contains(&"localization.exact-odometry")
            && !exact_odometry.contains(&"localization.noisy-odometry")
    );
    assert!(kalman.contains(&"fusion.bayes-independent"));
    assert!(kalman.contains(&"motion.no-following"));
    // No roadside unit, so none is transparent or surveyed.
    assert!(!kalman.contains(&"sight.rsu-transparent") && !kalman.contains(&"world.surveyed-rsu"));
    // Partial visibility (issue 16, part 4): the fan replaces the one-ray rule.
    assert!(!kalman.contains(&"sight.one-ray"));

    let unfiltered = ids(&WORLD.replace("filter: kalman", "filter: none"));
    assert!(
        !unfiltered.iter().any(|id| id.ends_with("-odometry")),
        "the raw measurement reads no odometry: {unfiltered:?}"
    );
    // Exact measurements make every estimate the true pose: no filter or
    // odometry is in effect (the defaults are a Kalman filter with noisy odometry).
    let exact = ids(&WORLD.replace("{ position_sigma: 0.2, filter: kalman }", "{ position_sigma: 0 }"));
    assert!(exact.contains(&"localization.exact") && !exact.contains(&"localization.white-noise"));
    assert!(
        !exact.iter().any(|id| id.ends_with("-odometry")),
        "exact localization reads no odometry: {exact:?}"
    );
    let dempster = ids(&WORLD.replace("method: bayes", "method: dempster"));
    assert!(dempster.contains(&"fusion.dempster-independent") && !dempster.contains(&"fusion.bayes-independent"));
}

const SEMANTIC: &str = "sightline: 1
name: s
time: { duration: 1, step: 0.1 }
roads: [{ id: r, polyline: [[0, -20], [0, 20]], speed_limit: 10 }]
sensor_models: { front: { range: 10 }, ring: { range: 30 } }
agents:
  - { id: ego, kind: car, route: [r], speed: { target: 5 }, connected: true, sensors: [front] }
  - { id: rsu, kind: rsu, position: [5, 0], sensors: [ring] }
v2x: { channel: { model: tr36885_urban } }
semantic: { ego: ego }
";

#[test]
fn a_semantic_run_lists_its_radio_and_its_roadside_units_sight() {
    let urban = ids(SEMANTIC);
    for id in [
        "semantic.ego-sight",
        "v2x.no-contention",
        "v2x.nlos-corner",
        "semantic.rsu-range",
        "ldm.association",
        "world.synchronous",
        "v2x.road-users-transparent",
    ] {
        assert!(urban.contains(&id), "{id} missing from {urban:?}");
    }
    // Nothing is generated and no road user but the ego is connected.
    assert!(!urban.contains(&"traffic.generated") && !urban.contains(&"semantic.direct-states"));
    let ideal = ids(&SEMANTIC.replace("tr36885_urban", "ideal"));
    assert!(
        ideal.contains(&"v2x.ideal") && !ideal.contains(&"v2x.independent-shadowing"),
        "{ideal:?}"
    );
    let sighted = ids(&SEMANTIC.replace(
        "semantic: { ego: ego }",
        "semantic: { ego: ego, rsu_sight: line_of_sight }",
    ));
    assert!(!sighted.contains(&"semantic.rsu-range"));
}

#[test]
fn a_sweep_lists_what_any_of_its_points_assumes_once() {
    // The sweep gives the method: the file's would be refused.
    let world = WORLD.replace("fusion: { method: bayes }\n", "");
    let swept = ids(&format!("{world}sweep: {{ fusion.method: [bayes, dempster] }}\n"));
    assert_eq!(
        swept.iter().filter(|&&id| id == "fusion.bayes-independent").count(),
        1,
        "{swept:?}"
    );
    assert!(swept.contains(&"fusion.dempster-independent"));
}

#[test]
fn idealisation_ids_are_unique_and_texts_are_sentences() {
    let mut all: Vec<Idealisation> = Vec::new();
    for (name, values) in enumerations() {
        for value in values {
            if let Some(option) = option(&name, &value) {
                all.extend_from_slice(option.idealisations());
            }
        }
    }
    for text in [
        WORLD.to_string(),
        WORLD.replace("{ position_sigma: 0.2, filter: kalman }", "{ position_sigma: 0 }"),
    ] {
        let scenario = compile("t.yaml", &text, &Options::default()).unwrap();
        all.extend(idealisations(&scenario));
    }
    let mut by_id: BTreeMap<&str, &str> = BTreeMap::new();
    for idealisation in &all {
        let text = by_id.entry(idealisation.id).or_insert(idealisation.text);
        assert_eq!(
            *text, idealisation.text,
            "two idealisations share the id {}",
            idealisation.id
        );
        assert!(
            idealisation.text.ends_with('.') && idealisation.text.starts_with(char::is_uppercase),
            "{}: not a sentence",
            idealisation.id
        );
        assert!(idealisation.id.contains('.'), "{}: not `model.what`", idealisation.id);
    }
}
