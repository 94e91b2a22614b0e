//! No silent assumptions (issue 13): every key of the language, in each kind of
//! scenario (the field experiment, a world measuring collective perception, a
//! world running the semantic pipeline, a joint world running both), either
//! changes what is simulated or measured, or `check` refuses it at
//! `file:line:col` with a reason.
//!
//! The keys are the leaves of the JSON Schema (`sightline schema`). [`KEYS`]
//! classifies each in each kind (a joint world as a semantic one, on a base
//! that is the semantic one's with a grid and cooperating agents, unless
//! [`JOINT`] says otherwise): how to change it (its effect is shown by
//! comparing outcomes, results.json, the recording's settings and the space
//! falsify searches), how to write it so that `check` refuses it, or that it
//! only labels. A key added to the schema without an entry fails the test.
//!
//! The scenarios are small and compiled, simulated and checked in process; they
//! are written as JSON, which is YAML.
// See: issue 13, "No silent assumptions".

use std::collections::{BTreeMap, BTreeSet, HashMap};

use serde_json::Value;
use sightline_dsl::{Error, ErrorKind, Options, compile};
use sightline_reports::{Execution, Provenance, Results, Tool};

use super::support::root;

/// A scenario file in `scenarios/`, so that `sumo/…` names the bundled SUMO
/// run. It need not exist: only its directory matters.
const FILE: &str = "scenarios/keys-test.yaml";

/// The kinds of scenario, in the order of [`Key`]'s classes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Field,
    Perception,
    Semantic,
    Joint,
}

const KINDS: [Kind; 4] = [Kind::Field, Kind::Perception, Kind::Semantic, Kind::Joint];

/// The small scenario of each kind that every change starts from.
fn base(kind: Kind) -> Value {
    let text = match kind {
        Kind::Field => FIELD,
        Kind::Perception => PERCEPTION,
        Kind::Semantic => SEMANTIC,
        Kind::Joint => JOINT,
    };
    serde_json::from_str(text).expect("a base scenario is JSON")
}

const FIELD: &str = r#"{
  "sightline": 1, "name": "keys: field", "seed": 1,
  "grid": { "size": [20, 20], "cell": 1 },
  "field": {
    "truth": { "occupied_fraction": 0.3 },
    "sensors": { "range": 15, "layout": { "regular": { "rows": 1, "cols": 2 } } },
    "masses": { "gamma": 10 }
  },
  "requirements": [ { "id": "R1", "text": "Accurate.", "check": { "metric": "accuracy", "at_least": 0.5 } } ]
}"#;

const PERCEPTION: &str = r#"{
  "sightline": 1, "name": "keys: collective perception", "seed": 3,
  "time": { "duration": 1, "step": 0.1 },
  "grid": { "origin": [-30, -30], "size": [60, 60], "cell": 1 },
  "roads": [
    { "id": "ns", "polyline": [[0, -30], [0, 30]], "speed_limit": 10 },
    { "id": "we", "polyline": [[-30, 2], [30, 2]], "speed_limit": 10 }
  ],
  "occluders": [ { "id": "block", "polygon": [[5, 5], [15, 5], [15, 15], [5, 15]] } ],
  "sensor_models": { "lidar": { "range": 25 }, "cone": { "range": 25, "fov_deg": 120 } },
  "agents": [
    { "id": "ego", "kind": "car", "route": ["ns"], "start": { "offset": 20 }, "speed": { "target": 8 }, "connected": true, "sensors": ["lidar"] },
    { "id": "cav", "kind": "car", "route": ["we"], "start": { "offset": 20 }, "speed": { "target": 8 }, "connected": true, "sensors": ["lidar"] },
    { "id": "car", "kind": "car", "route": ["we"], "start": { "offset": 35 }, "speed": { "target": 6 } },
    { "id": "ped", "kind": "pedestrian", "path": [[10, -10], [10, 10]], "speed": { "target": 1.4 } },
    { "id": "rsu", "kind": "rsu", "position": [-8, -8], "connected": true, "sensors": ["cone"] }
  ],
  "localization": { "position_sigma": 0.1, "heading_sigma_deg": 0.5 },
  "perception": { "ego": "ego" },
  "fusion": { "method": "bayes" },
  "decision": { "threshold": 0 },
  "requirements": [ { "id": "R1", "text": "Recall.", "check": { "metric": "occupied_recall", "at_least": 0.5 } } ]
}"#;

const SEMANTIC: &str = r#"{
  "sightline": 1, "name": "keys: semantic pipeline", "seed": 5,
  "time": { "duration": 6, "step": 0.1 },
  "roads": [
    { "id": "ns", "polyline": [[-1.75, 80], [-1.75, -80]], "speed_limit": 10 },
    { "id": "sn", "polyline": [[1.75, -80], [1.75, 80]], "speed_limit": 10 },
    { "id": "we", "polyline": [[-80, -1.75], [80, -1.75]], "speed_limit": 10 },
    { "id": "ew", "polyline": [[80, 1.75], [-80, 1.75]], "speed_limit": 10 }
  ],
  "occluders": [ { "id": "block", "polygon": [[6, 6], [40, 6], [40, 40], [6, 40]] } ],
  "crosswalks": [ { "id": "cw", "from": [-6, -9], "to": [6, -9] } ],
  "interaction_areas": [ { "id": "junction", "polygon": [[-12, -12], [12, -12], [12, 12], [-12, 12]] } ],
  "sensor_models": { "front": { "range": 50, "fov_deg": 90 }, "ring": { "range": 60, "position_noise": { "base": 0.1 } } },
  "agents": [
    { "id": "ego", "kind": "car", "route": ["sn"], "start": { "offset": 45 }, "speed": { "target": 8 }, "connected": true, "sensors": ["front"] },
    { "id": "rsu", "kind": "rsu", "position": [-8, -8], "sensors": ["ring"] },
    { "id": "car", "kind": "car", "route": ["ew"], "start": { "offset": 45 }, "speed": { "target": 9 } },
    { "id": "ped", "kind": "pedestrian", "path": [[-6, -9], [6, -9]], "speed": { "target": 1.4 } }
  ],
  "traffic": {
    "vehicles": { "density_per_km": 30, "routes": [["we"], ["ew"], ["ns"]], "non_compliant": 0.5 },
    "pedestrians": { "per_minute": 20 }
  },
  "v2x": { "penetration": 0.5, "latency": 0.01 },
  "semantic": { "ego": "ego" },
  "requirements": [ { "id": "R1", "text": "Delivered.", "check": { "metric": "packet_delivery_ratio", "at_least": 0.5 } } ]
}"#;

/// The semantic base run together with collective perception: its agents in
/// the same order (the roadside unit now shares its grid), a cooperating car
/// after them, a grid, and its radio without `penetration`, which a joint
/// world refuses.
const JOINT: &str = r#"{
  "sightline": 1, "name": "keys: joint world", "seed": 5,
  "time": { "duration": 6, "step": 0.1 },
  "grid": { "origin": [-40, -40], "size": [80, 80], "cell": 1 },
  "roads": [
    { "id": "ns", "polyline": [[-1.75, 80], [-1.75, -80]], "speed_limit": 10 },
    { "id": "sn", "polyline": [[1.75, -80], [1.75, 80]], "speed_limit": 10 },
    { "id": "we", "polyline": [[-80, -1.75], [80, -1.75]], "speed_limit": 10 },
    { "id": "ew", "polyline": [[80, 1.75], [-80, 1.75]], "speed_limit": 10 }
  ],
  "occluders": [ { "id": "block", "polygon": [[6, 6], [40, 6], [40, 40], [6, 40]] } ],
  "crosswalks": [ { "id": "cw", "from": [-6, -9], "to": [6, -9] } ],
  "interaction_areas": [ { "id": "junction", "polygon": [[-12, -12], [12, -12], [12, 12], [-12, 12]] } ],
  "sensor_models": { "front": { "range": 50, "fov_deg": 90 }, "ring": { "range": 60, "position_noise": { "base": 0.1 } } },
  "agents": [
    { "id": "ego", "kind": "car", "route": ["sn"], "start": { "offset": 45 }, "speed": { "target": 8 }, "connected": true, "sensors": ["front"] },
    { "id": "rsu", "kind": "rsu", "position": [-8, -8], "connected": true, "sensors": ["ring"] },
    { "id": "car", "kind": "car", "route": ["ew"], "start": { "offset": 45 }, "speed": { "target": 9 } },
    { "id": "ped", "kind": "pedestrian", "path": [[-6, -9], [6, -9]], "speed": { "target": 1.4 } },
    { "id": "cav", "kind": "car", "route": ["we"], "start": { "offset": 50 }, "speed": { "target": 8 }, "connected": true, "sensors": ["front"] }
  ],
  "traffic": {
    "vehicles": { "density_per_km": 30, "routes": [["we"], ["ew"], ["ns"]], "non_compliant": 0.5 },
    "pedestrians": { "per_minute": 20 }
  },
  "localization": { "position_sigma": 0.1, "heading_sigma_deg": 0.5 },
  "perception": { "ego": "ego" },
  "fusion": { "method": "bayes" },
  "decision": { "threshold": 0 },
  "v2x": { "latency": 0.01 },
  "semantic": { "ego": "ego" },
  "requirements": [ { "id": "R1", "text": "Delivered.", "check": { "metric": "semantic_packet_delivery_ratio", "at_least": 0.5 } } ]
}"#;

/// A setting: a dotted path (a number is a list index) and its value as JSON.
type Set = (&'static str, &'static str);

/// What a key does in one kind of scenario.
#[derive(Debug, Clone, Copy)]
enum Class {
    /// Changing it changes the outcome: the base with `with` applied, against
    /// the same with `change` applied as well.
    Effective {
        with: &'static [Set],
        change: &'static [Set],
    },
    /// Writing it (`set` on the base) makes `check` refuse the scenario with an
    /// error at the key (or at `at`, the key that conflicts with it).
    Refused {
        set: &'static [Set],
        at: Option<&'static str>,
    },
    /// Refused as part of its top-level section, written whole ([`SECTIONS`]).
    Section,
    /// Its section is the other model's: writing it makes a perception or a
    /// semantic world a joint one ([`joining`]), whose outcome differs; what
    /// the key itself does is checked in the joint world.
    MakesJoint,
    /// It only labels (an id, a name, a text, a source).
    Descriptive,
    /// It is the system under test's: nothing simulated in process runs the
    /// system, so its effect is shown by the named test of
    /// `tests/e2e/system.rs`, which has the CLI drive one (the test must exist).
    Driven(&'static str),
}

const fn change(change: &'static [Set]) -> Class {
    Class::Effective { with: &[], change }
}

const fn with(with: &'static [Set], change: &'static [Set]) -> Class {
    Class::Effective { with, change }
}

const fn refused(set: &'static [Set]) -> Class {
    Class::Refused { set, at: None }
}

const fn refused_at(set: &'static [Set], at: &'static str) -> Class {
    Class::Refused { set, at: Some(at) }
}

use Class::{Descriptive, Driven, MakesJoint, Section};

/// A key of the schema and what it does in the field experiment, in
/// collective perception and in the semantic pipeline.
struct Key {
    path: &'static str,
    field: Class,
    perception: Class,
    semantic: Class,
}

impl Key {
    fn class(&self, kind: Kind) -> Class {
        match kind {
            Kind::Field => self.field,
            Kind::Perception => self.perception,
            Kind::Semantic => self.semantic,
            Kind::Joint => JOINT_KEYS
                .iter()
                .find(|(path, _)| *path == self.path)
                .map_or(self.semantic, |&(_, class)| class),
        }
    }
}

/// What writing the other model's section takes to make a world of `kind`
/// a joint one: a semantic world also needs a grid, and drops its
/// `v2x.penetration` and its requirement's `packet_delivery_ratio`, which a
/// joint world refuses.
fn joining(kind: Kind) -> &'static [Set] {
    match kind {
        Kind::Perception => &[("semantic", r#"{ "ego": "ego" }"#)],
        Kind::Semantic => &[
            ("perception", r#"{ "ego": "ego" }"#),
            ("grid", r#"{ "origin": [-40, -40], "size": [80, 80], "cell": 1 }"#),
            ("v2x.penetration", "null"),
            ("requirements.0.check.metric", r#""semantic_packet_delivery_ratio""#),
        ],
        Kind::Field | Kind::Joint => panic!("only a perception or a semantic world becomes a joint one"),
    }
}

/// Every top-level section some kind refuses, written whole with every key it
/// can hold, and where the refusal is reported when it is not at the section
/// itself (a `field` makes a world's sections the refused ones).
const SECTIONS: &[(&str, &str)] = &[
    (
        "time",
        r#"{ "duration": 1, "step": 0.1, "start": "2026-03-01T08:00:00Z" }"#,
    ),
    (
        "traces",
        r#"{ "sumocfg": "sumo-town/town.sumocfg", "fcd": "sumo/grid3x3.fcd.xml", "net": "sumo/grid3x3.net.xml",
             "routes": ["sumo-town/town.rou.xml"], "poly": "sumo/grid3x3.poly.xml",
             "occluder_types": ["building"], "junction_areas": true, "rsus": { "poi_type": "rsu", "sensors": ["lidar"] },
             "begin": 1 }"#,
    ),
    (
        "map",
        r#"{ "opendrive": "../dsl/tests/opendrive/straight.xodr", "occluder_types": ["building"], "junction_areas": true,
             "speed_limit": 5 }"#,
    ),
    (
        "roads",
        r#"[ { "id": "a", "polyline": [[0, 0], [10, 0]], "lanes": 2, "lane_width": 3, "speed_limit": 10 },
             { "id": "b", "arc": { "center": [0, 0], "radius": 10, "start_deg": 0, "end_deg": 90 }, "speed_limit": 10 },
             { "id": "c", "roundabout": { "center": [0, 0], "radius": 10, "direction": "cw" }, "speed_limit": 10 } ]"#,
    ),
    (
        "occluders",
        r#"[ { "id": "o", "polygon": [[0, 0], [1, 0], [1, 1]], "height": 3 } ]"#,
    ),
    (
        "sensor_models",
        r#"{ "s": { "range": 10, "fov_deg": 90, "mount": { "x": 1, "y": 0, "yaw_deg": 0 }, "detection_probability": 1,
                    "position_noise": { "base": 0, "per_m": 0 }, "size_noise": { "base": 0, "per_m": 0 },
                    "velocity_noise": { "base": 0, "per_m": 0 }, "ray_spacing_deg": 1 } }"#,
    ),
    (
        "agents",
        r#"[ { "id": "x", "kind": "car", "route": ["a"], "lane": 0, "path": [[0, 0], [1, 0]], "trace": "veh0",
               "position": [0, 0], "heading_deg": 0, "start": { "time": 0, "offset": 0 },
               "speed": { "target": 1, "initial": 1, "acceleration": 1, "limit_factor": 1 },
               "size": { "length": 4, "width": 2 }, "connected": true, "sensors": ["s"] } ]"#,
    ),
    (
        "localization",
        r#"{ "position_sigma": 0.1, "heading_sigma_deg": 1, "filter": "kalman", "process_position_sigma": 0.1,
             "process_heading_sigma_deg": 0.5,
             "odometry": { "model": "noisy", "speed_sigma": 0.1, "speed_bias": 0.01, "yaw_rate_sigma_deg": 0.1,
                           "yaw_rate_bias_deg": 0.2 } }"#,
    ),
    (
        "perception",
        r#"{ "ego": "ego", "cooperating": 1, "inverse_model": { "occupied": 0.7, "free": 0.3 }, "snapshot": 0,
             "region": { "center": [0, 0], "radius": 10 } }"#,
    ),
    (
        "traffic",
        r#"{ "vehicles": { "density_per_km": 10, "routes": [["a"]], "non_compliant": 0.1, "overspeed_factor": [1.2, 1.5],
                           "mix": { "car": 1, "truck": 0, "bus": 0, "motorbike": 0 } },
             "pedestrians": { "per_minute": 1, "speed": 1.3, "approach": 5 } }"#,
    ),
    (
        "crosswalks",
        r#"[ { "id": "c", "from": [0, 0], "to": [1, 0], "width": 3 } ]"#,
    ),
    (
        "interaction_areas",
        r#"[ { "id": "i", "polygon": [[0, 0], [1, 0], [1, 1]], "circle": { "center": [0, 0], "radius": 1 } } ]"#,
    ),
    (
        "areas",
        r#"[ { "id": "a", "polygon": [[0, 0], [1, 0], [1, 1]], "circle": { "center": [0, 0], "radius": 1 } } ]"#,
    ),
    (
        "driving",
        r#"{ "following": "idm", "headway": 1.5, "min_gap": 2, "deceleration": 3 }"#,
    ),
    (
        "v2x",
        r#"{ "penetration": 0.5, "latency": 0.01,
             "channel": { "model": "tr36885_urban", "tx_power_dbm": 23, "shadowing_sigma_db": 3, "nlos_shadowing_sigma_db": 4,
                          "device_loss_db": 3, "sensitivity_dbm": -90, "carrier_ghz": 5.9, "vehicle_antenna_m": 1.5,
                          "rsu_antenna_m": 5 },
             "messages": { "rate_hz": 10, "max_bytes": 1100, "oversize": "split", "max_age": 1, "decay": 0.5 } }"#,
    ),
    (
        "semantic",
        r#"{ "ego": "ego", "rsus": ["rsu"], "proximity": 50, "horizon": 3, "d_min": 2,
             "overspeed": { "window": 5, "threshold": 2 }, "hypotheses": [0.7, 1, 1.1], "rate": 10, "risk_for": "all",
             "rsu_sight": "range", "history": 5, "caution": { "headway": 2.5, "speed_factor": 0.8, "hold": 3 },
             "baseline": { "distance": 4, "speed": 0.5, "heading_deg": 4, "interval": 1 }, "shares_over": "all",
             "contribution_over": "all", "labelled_by": "critical", "runs": 1 }"#,
    ),
    (
        "field",
        r#"{ "truth": { "occupied_fraction": 0.2, "blob": 1 },
             "sensors": { "range": 5, "layout": { "regular": { "rows": 1, "cols": 1 }, "positions": [[0, 0]], "random": { "count": 1 } } },
             "masses": { "concentration": 32, "epsilon0": 0.0625, "gamma": 10, "error_model": "wrong_label" },
             "distance_bands": [5] }"#,
    ),
    ("grid", r#"{ "origin": [0, 0], "size": [10, 10], "cell": 1 }"#),
    (
        "fusion",
        r#"{ "label": "L", "method": "hybrid", "weights": "mean_one", "sources": "pairwise",
             "switch": { "measure": "ratio", "threshold": 2 } }"#,
    ),
    ("decision", r#"{ "rule": "exceeds", "threshold": 0.5 }"#),
    (
        "system_under_test",
        r#"{ "command": ["true"], "agent": "ego", "sensors": [0], "step_timeout": 1, "gate": 2, "min_existence": 0.5 }"#,
    ),
];

/// Where `kind` reports a refused `section` when not at the section: a
/// `field` turns a world into the field experiment, whose refusals are at the
/// world's sections (`time` first).
fn section_refused_at(kind: Kind, section: &str) -> &'static str {
    match (kind, section) {
        (Kind::Perception | Kind::Semantic | Kind::Joint, "field") => "time",
        _ => SECTIONS
            .iter()
            .find(|(name, _)| *name == section)
            .map(|(name, _)| *name)
            .unwrap_or_else(|| panic!("no full value of section `{section}` in SECTIONS")),
    }
}

/// A sweep over fusion methods, for the keys that select points.
const FUSION_SWEEP: Set = ("sweep", r#"{ "fusion.method": ["dempster", "bayes"] }"#);
/// A sweep over cooperating agents, for the keys that select points.
const COOPERATING_SWEEP: Set = ("sweep", r#"{ "perception.cooperating": [1, 3] }"#);
/// A sweep over the semantic pipeline's rate.
const RATE_SWEEP: Set = ("sweep", r#"{ "semantic.rate": [10, 5] }"#);
/// A requirement on a signal over time (worlds).
const SIGNAL: Set = (
    "requirements.0.check",
    r#"{ "signal": "occupied_recall", "always": { "at_least": 0.1 } }"#,
);
/// Where a signal check is refused in the field experiment: at its signal.
const SIGNAL_AT: &str = "requirements[0].check.signal";
/// Noisy speeds, for the keys that read speeds over time.
const NOISY_SPEEDS: &[Set] = &[("sensor_models.ring.velocity_noise", r#"{ "base": 2 }"#)];
/// A receiver at the edge of reception and a building between the roadside
/// unit and the ego's way, for the channel's keys.
const MARGINAL_RADIO: &[Set] = &[
    ("v2x.channel.sensitivity_dbm", "-62"),
    (
        "occluders.+",
        r#"{ "id": "wall", "polygon": [[-6, -22], [-3, -22], [-3, -12], [-6, -12]] }"#,
    ),
];
/// A radio for collective perception: its keys are compared over it.
const RADIO: &[Set] = &[("v2x.latency", "0.01")];
/// The same with messages too small for a grid, for the keys that fit one.
const SMALL_MESSAGES: &[Set] = &[("v2x.latency", "0.01"), ("v2x.messages.max_bytes", "300")];
/// The same with a wall between the roadside unit and the ego's way and a
/// receiver at the edge of reception, for the keys of blocked links.
const BLOCKED_RADIO: &[Set] = &[
    ("v2x.latency", "0.01"),
    ("v2x.channel.sensitivity_dbm", "-48"),
    (
        "occluders.+",
        r#"{ "id": "wall", "polygon": [[-5, -12], [-4, -12], [-4, -4], [-5, -4]] }"#,
    ),
];
/// The same for a semantic world.
/// A per-object check on every relevant road user's record, for the keys
/// that select among them.
const PER_OBJECT: Set = (
    "requirements.0.check",
    r#"{ "per_object": "closest_distance", "at_least": 0 }"#,
);
/// Where a selection outside a per-object check is refused.
const OBJECTS_AT: &str = "requirements[0].check.objects";
/// A comparison with the ETSI baseline, for `by`.
const COMPARISON: Set = (
    "requirements.0.check",
    r#"{ "metric": "channel_load", "at_most": 1000000, "relative_to": "baseline" }"#,
);
const SEMANTIC_SIGNAL: Set = (
    "requirements.0.check",
    r#"{ "signal": "rsu_only_objects", "always": { "at_least": 0 } }"#,
);
/// The SUMO run around the centre junction of the bundled 3 × 3 grid, for the
/// semantic pipeline's `traces` keys.
const SUMO_SEMANTIC: &[Set] = &[
    ("time", r#"{ "duration": 40, "step": 0.1 }"#),
    ("roads", "[]"),
    ("occluders", "[]"),
    ("crosswalks", "[]"),
    ("interaction_areas", "[]"),
    ("traffic", "null"),
    (
        "agents",
        r#"[ { "id": "ego", "kind": "car", "trace": "veh7", "connected": true, "sensors": ["front"] },
             { "id": "rsu", "kind": "rsu", "position": [93.5, 93.5], "sensors": ["ring"] } ]"#,
    ),
    (
        "traces",
        r#"{ "fcd": "sumo/grid3x3.fcd.xml", "net": "sumo/grid3x3.net.xml", "poly": "sumo/grid3x3.poly.xml" }"#,
    ),
];

/// The bundled SUMO town's trace from 20 s, without its types (issue 19).
const TOWN_FCD: Set = ("traces", r#"{ "fcd": "sumo-town/town.fcd.xml", "begin": 20 }"#);
/// The town's trace and its points of interest, no roadside units yet.
const TOWN_POIS: Set = (
    "traces",
    r#"{ "fcd": "sumo-town/town.fcd.xml", "poly": "sumo-town/town.poly.xml", "begin": 20 }"#,
);
/// The town's points of interest of type `rsu` as roadside units, with a
/// sensor model of the perception base, and of the semantic base.
const TOWN_RSUS_LIDAR: Set = ("traces.rsus", r#"{ "poi_type": "rsu", "sensors": ["lidar"] }"#);
const TOWN_RSUS_RING: Set = ("traces.rsus", r#"{ "poi_type": "rsu", "sensors": ["ring"] }"#);

/// The bundled OpenDRIVE crossroads (`scenarios/opendrive`), for the
/// semantic pipeline's `map` keys: the ego from the west straight through the
/// junction, a car from the north turning right across its way, the roadside
/// unit on the south-west corner.
const MAP_SEMANTIC: &[Set] = &[
    ("time", r#"{ "duration": 12, "step": 0.1 }"#),
    ("roads", "[]"),
    ("occluders", "[]"),
    ("crosswalks", "[]"),
    ("interaction_areas", "[]"),
    (
        "traffic",
        r#"{ "vehicles": { "density_per_km": 30, "routes": [["road 2 lane -1", "road 106 lane -1", "road 4 lane 1"]], "non_compliant": 0.5 },
             "pedestrians": { "per_minute": 20 } }"#,
    ),
    ("map", r#"{ "opendrive": "opendrive/crossroads.xodr" }"#),
    (
        "agents",
        r#"[ { "id": "ego", "kind": "car", "route": ["road 1 lane -1", "road 102 lane -1", "road 3 lane 1"], "start": { "offset": 100 }, "speed": { "target": 10 }, "connected": true, "sensors": ["front"] },
             { "id": "rsu", "kind": "rsu", "position": [157, 19], "sensors": ["ring"] },
             { "id": "car", "kind": "car", "route": ["road 4 lane -1", "road 110 lane -1", "road 1 lane 1"], "start": { "offset": 40 }, "speed": { "target": 10 } },
             { "id": "ped", "kind": "pedestrian", "route": ["road 4 lane -2"], "start": { "offset": 40 }, "speed": { "target": 1.4 } } ]"#,
    ),
];

/// A straight road without speed limits through the collective-perception
/// base's grid (`dsl/tests/opendrive/straight.xodr`), for `map.speed_limit`.
const MAP_STRAIGHT: &[Set] = &[
    (
        "map",
        r#"{ "opendrive": "../dsl/tests/opendrive/straight.xodr", "speed_limit": 5 }"#,
    ),
    ("agents.2.route", r#"["road 1 lane -1"]"#),
    ("agents.2.start.offset", "5"),
    ("agents.2.speed.target", "8"),
];

/// Every key of the language: how to change it, or how `check` refuses it, in
/// each kind of scenario. One entry per line where it fits: a table, not code.
#[rustfmt::skip]
const KEYS: &[Key] = &[
    // The scenario as a whole.
    Key { path: "sightline", field: refused(&[("sightline", "2")]), perception: refused(&[("sightline", "2")]), semantic: refused(&[("sightline", "2")]) },
    Key { path: "name", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "description", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    // The report as a controlled document (issue 18): its control table and
    // its page size, nothing simulated, measured or judged.
    Key { path: "document.version", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "document.author", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "document.reviewer", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "document.approver", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "document.paper", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "seed", field: change(&[("seed", "2")]), perception: change(&[("seed", "4")]), semantic: change(&[("seed", "6")]) },
    // grid, fusion, decision: what fuses.
    Key {
        path: "grid.origin",
        field: with(&[("field.sensors.layout", r#"{ "positions": [[5, 5], [15, 15]] }"#)], &[("grid.origin", "[3, 0]")]),
        perception: change(&[("grid.origin", "[-31, -30]")]),
        semantic: Section,
    },
    Key { path: "grid.size", field: change(&[("grid.size", "[20, 10]")]), perception: change(&[("grid.size", "[50, 60]")]), semantic: Section },
    Key { path: "grid.cell", field: change(&[("grid.cell", "0.5")]), perception: change(&[("grid.cell", "0.5")]), semantic: Section },
    Key { path: "fusion.label", field: change(&[("fusion.label", r#""Baseline""#)]), perception: change(&[("fusion.label", r#""Baseline""#)]), semantic: Section },
    Key { path: "fusion.method", field: change(&[("fusion.method", r#""bayes""#)]), perception: change(&[("fusion.method", r#""dempster""#)]), semantic: Section },
    Key {
        path: "fusion.weights",
        field: with(&[("fusion.method", r#""distance_weighted""#), ("field.sensors.layout.regular.cols", "3")], &[("fusion.weights", r#""mean_one""#)]),
        perception: with(&[("fusion.method", r#""distance_weighted""#)], &[("fusion.weights", r#""mean_one""#)]),
        semantic: Section,
    },
    Key {
        path: "fusion.sources",
        field: with(&[("fusion.method", r#""distance_weighted""#), ("fusion.weights", r#""mean_one""#), ("field.sensors.layout.regular.cols", "3")], &[("fusion.sources", r#""pairwise""#)]),
        perception: with(&[("fusion.method", r#""distance_weighted""#), ("fusion.weights", r#""mean_one""#)], &[("fusion.sources", r#""pairwise""#)]),
        semantic: Section,
    },
    Key {
        path: "fusion.switch.measure",
        field: with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "measure": "difference", "threshold": 2 }"#)], &[("fusion.switch.measure", r#""ratio""#)]),
        perception: with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "measure": "difference", "threshold": 2 }"#)], &[("fusion.switch.measure", r#""ratio""#)]),
        semantic: Section,
    },
    Key {
        path: "fusion.switch.threshold",
        field: with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "threshold": 2 }"#)], &[("fusion.switch.threshold", "8")]),
        perception: with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "threshold": 2 }"#)], &[("fusion.switch.threshold", "20")]),
        semantic: Section,
    },
    Key { path: "decision.threshold", field: change(&[("decision.threshold", "0.5")]), perception: change(&[("decision.threshold", "0.5")]), semantic: Section },
    // At θ = 0 both rules decide every cell; at 0.5, margin asks p_max ≥ 0.75, exceeds p_max > 0.5.
    Key { path: "decision.rule", field: change(&[("decision.rule", r#""exceeds""#)]), perception: with(&[("decision.threshold", "0.5")], &[("decision.rule", r#""exceeds""#)]), semantic: Section },
    // The field experiment.
    Key { path: "field.truth.occupied_fraction", field: change(&[("field.truth.occupied_fraction", "0.5")]), perception: Section, semantic: Section },
    Key { path: "field.truth.blob", field: change(&[("field.truth.blob", "2")]), perception: Section, semantic: Section },
    Key { path: "field.sensors.range", field: change(&[("field.sensors.range", "10")]), perception: Section, semantic: Section },
    Key { path: "field.sensors.layout.regular.rows", field: change(&[("field.sensors.layout.regular.rows", "2")]), perception: Section, semantic: Section },
    Key { path: "field.sensors.layout.regular.cols", field: change(&[("field.sensors.layout.regular.cols", "3")]), perception: Section, semantic: Section },
    Key { path: "field.sensors.layout.positions", field: change(&[("field.sensors.layout", r#"{ "positions": [[2, 2], [18, 18]] }"#)]), perception: Section, semantic: Section },
    Key {
        path: "field.sensors.layout.random.count",
        field: with(&[("field.sensors.layout", r#"{ "random": { "count": 2 } }"#)], &[("field.sensors.layout.random.count", "3")]),
        perception: Section,
        semantic: Section,
    },
    Key { path: "field.masses.concentration", field: change(&[("field.masses.concentration", "10")]), perception: Section, semantic: Section },
    Key { path: "field.masses.epsilon0", field: change(&[("field.masses.epsilon0", "0.1")]), perception: Section, semantic: Section },
    Key { path: "field.masses.gamma", field: change(&[("field.masses.gamma", "20")]), perception: Section, semantic: Section },
    Key { path: "field.masses.error_model", field: change(&[("field.masses.error_model", r#""wrong_label""#)]), perception: Section, semantic: Section },
    Key { path: "field.distance_bands", field: change(&[("field.distance_bands", "[5, 10]")]), perception: Section, semantic: Section },
    // Worlds: time, imported traces, roads, buildings.
    Key { path: "time.duration", field: Section, perception: change(&[("time.duration", "0.5")]), semantic: change(&[("time.duration", "5")]) },
    Key { path: "time.step", field: Section, perception: change(&[("time.step", "0.05")]), semantic: change(&[("time.step", "0.05")]) },
    // The recording's clock: its timestamps (issue 18).
    Key { path: "time.start", field: Section, perception: with(&[("record", "{}")], &[("time.start", r#""2026-03-01T08:00:00Z""#)]), semantic: with(&[("record", "{}")], &[("time.start", r#""2026-03-01T09:00:00+01:00""#)]) },
    Key { path: "traces.fcd", field: Section, perception: change(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#)]), semantic: change(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#)]) },
    Key {
        path: "traces.net",
        field: Section,
        perception: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#)], &[("traces.net", r#""sumo/grid3x3.net.xml""#), ("agents.2.route", r#"["A0A1"]"#)]),
        semantic: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#)], &[("traces.net", r#""sumo/grid3x3.net.xml""#)]),
    },
    Key {
        path: "traces.poly",
        field: Section,
        perception: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#), ("grid", r#"{ "origin": [-30, -30], "size": [60, 60], "cell": 1 }"#), ("agents.0.start.offset", "40")], &[("traces.poly", r#""sumo/grid3x3.poly.xml""#)]),
        semantic: with(SUMO_SEMANTIC, &[("traces.poly", "null")]),
    },
    Key {
        path: "traces.occluder_types",
        field: Section,
        perception: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml", "poly": "sumo/grid3x3.poly.xml" }"#), ("agents.0.start.offset", "40")], &[("traces.occluder_types", r#"["park"]"#)]),
        semantic: with(SUMO_SEMANTIC, &[("traces.occluder_types", r#"["park"]"#)]),
    },
    Key {
        path: "traces.junction_areas",
        field: Section,
        perception: refused(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml", "net": "sumo/grid3x3.net.xml", "junction_areas": false }"#)]),
        semantic: with(SUMO_SEMANTIC, &[("traces.junction_areas", "false")]),
    },
    // issue 19: a SUMO configuration, vehicle types, points of interest as RSUs.
    Key { path: "traces.sumocfg", field: Section, perception: change(&[("traces", r#"{ "sumocfg": "sumo-town/town.sumocfg", "begin": 20 }"#)]), semantic: change(&[("traces", r#"{ "sumocfg": "sumo-town/town.sumocfg", "begin": 20 }"#)]) },
    Key { path: "traces.routes", field: Section, perception: with(&[TOWN_FCD], &[("traces.routes", r#"["sumo-town/town.rou.xml"]"#)]), semantic: with(&[TOWN_FCD], &[("traces.routes", r#"["sumo-town/town.rou.xml"]"#)]) },
    Key { path: "traces.rsus.poi_type", field: Section, perception: with(&[TOWN_POIS], &[TOWN_RSUS_LIDAR]), semantic: with(&[TOWN_POIS], &[TOWN_RSUS_RING]) },
    Key { path: "traces.rsus.sensors", field: Section, perception: with(&[TOWN_POIS, TOWN_RSUS_LIDAR], &[("traces.rsus.sensors", r#"["cone"]"#)]), semantic: with(&[TOWN_POIS, TOWN_RSUS_RING], &[("traces.rsus.sensors", r#"["front"]"#)]) },
    Key {
        path: "traces.begin",
        field: Section,
        perception: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#)], &[("traces.begin", "5")]),
        semantic: with(SUMO_SEMANTIC, &[("traces.begin", "2")]),
    },
    // A map from OpenDRIVE (issue 19).
    Key {
        path: "map.opendrive",
        field: Section,
        perception: change(&[("map", r#"{ "opendrive": "../dsl/tests/opendrive/straight.xodr", "speed_limit": 5 }"#), ("agents.2.route", r#"["road 1 lane -1"]"#), ("agents.2.start.offset", "5")]),
        semantic: change(MAP_SEMANTIC),
    },
    Key {
        path: "map.occluder_types",
        field: Section,
        perception: with(&[("map", r#"{ "opendrive": "opendrive/crossroads.xodr" }"#), ("grid", r#"{ "origin": [120, -30], "size": [90, 120], "cell": 1 }"#), ("agents.0.route", r#"["road 2 lane -1", "road 106 lane -1", "road 4 lane 1"]"#), ("agents.0.start.offset", "60"), ("agents.1.route", r#"["road 3 lane -1", "road 107 lane -1", "road 1 lane 1"]"#), ("agents.1.start.offset", "60"), ("agents.2.route", r#"["road 1 lane -1"]"#), ("agents.3.path", "[[150, 60], [150, 50]]"), ("agents.4.position", "[157, 19]")], &[("map.occluder_types", "[]")]),
        semantic: with(MAP_SEMANTIC, &[("map.occluder_types", "[]")]),
    },
    Key {
        path: "map.junction_areas",
        field: Section,
        perception: refused(&[("map", r#"{ "opendrive": "opendrive/crossroads.xodr", "junction_areas": false }"#)]),
        semantic: with(MAP_SEMANTIC, &[("map.junction_areas", "false")]),
    },
    Key {
        path: "map.speed_limit",
        field: Section,
        perception: with(MAP_STRAIGHT, &[("map.speed_limit", "8")]),
        semantic: refused(&[("map", r#"{ "opendrive": "opendrive/crossroads.xodr", "speed_limit": 10 }"#)]),
    },
    Key { path: "roads[].id", field: Section, perception: Descriptive, semantic: Descriptive },
    Key { path: "roads[].polyline", field: Section, perception: change(&[("roads.1.polyline", "[[-30, 3], [30, 3]]")]), semantic: change(&[("roads.3.polyline", "[[80, 3], [-80, 3]]")]) },
    Key {
        path: "roads[].arc.center",
        field: Section,
        perception: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.2.arc.center", "[1, 0]")]),
        semantic: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.4.arc.center", "[1, 0]")]),
    },
    Key {
        path: "roads[].arc.radius",
        field: Section,
        perception: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.2.arc.radius", "15")]),
        semantic: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.4.arc.radius", "15")]),
    },
    Key {
        path: "roads[].arc.start_deg",
        field: Section,
        perception: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.2.arc.start_deg", "-30")]),
        semantic: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.4.arc.start_deg", "-30")]),
    },
    Key {
        path: "roads[].arc.end_deg",
        field: Section,
        perception: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0"), ("time.duration", "3")], &[("roads.2.arc.end_deg", "30")]),
        semantic: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0")], &[("roads.4.arc.end_deg", "30")]),
    },
    Key {
        path: "roads[].roundabout.center",
        field: Section,
        perception: with(RING, &[("roads.2.roundabout.center", "[1, 0]")]),
        semantic: with(SEMANTIC_RING, &[("roads.4.roundabout.center", "[1, 0]")]),
    },
    Key { path: "roads[].roundabout.radius", field: Section, perception: with(RING, &[("roads.2.roundabout.radius", "14")]), semantic: with(SEMANTIC_RING, &[("roads.4.roundabout.radius", "14")]) },
    Key {
        path: "roads[].roundabout.direction",
        field: Section,
        perception: with(RING, &[("roads.2.roundabout.direction", r#""cw""#)]),
        semantic: with(SEMANTIC_RING, &[("roads.4.roundabout.direction", r#""cw""#)]),
    },
    Key {
        path: "roads[].lanes",
        field: Section,
        perception: with(&[("roads.1.lanes", "2"), ("agents.2.lane", "1")], &[("roads.1.lanes", "3"), ("agents.2.lane", "2")]),
        semantic: with(&[("roads.3.lanes", "2"), ("agents.2.lane", "1")], &[("roads.3.lanes", "3"), ("agents.2.lane", "2")]),
    },
    Key {
        path: "roads[].lane_width",
        field: Section,
        perception: with(&[("roads.1.lanes", "2"), ("agents.2.lane", "1")], &[("roads.1.lane_width", "5")]),
        semantic: with(&[("roads.3.lanes", "2"), ("agents.2.lane", "1")], &[("roads.3.lane_width", "5")]),
    },
    Key { path: "roads[].speed_limit", field: Section, perception: change(&[("roads.1.speed_limit", "5")]), semantic: change(&[("roads.3.speed_limit", "5")]) },
    Key { path: "occluders[].id", field: Section, perception: Descriptive, semantic: Descriptive },
    Key {
        path: "occluders[].polygon",
        field: Section,
        perception: change(&[("occluders.0.polygon", "[[-5, 5], [-15, 5], [-15, 15]]")]),
        semantic: change(&[("occluders.0.polygon", "[[-6, -6], [-40, -6], [-40, -40], [-6, -40]]")]),
    },
    Key { path: "occluders[].height", field: Section, perception: refused(&[("occluders.0.height", "10")]), semantic: refused(&[("occluders.0.height", "10")]) },
    // Sensors.
    Key { path: "sensor_models.<id>.range", field: Section, perception: change(&[("sensor_models.lidar.range", "15")]), semantic: change(&[("sensor_models.ring.range", "20")]) },
    Key { path: "sensor_models.<id>.fov_deg", field: Section, perception: change(&[("sensor_models.lidar.fov_deg", "90")]), semantic: change(&[("sensor_models.front.fov_deg", "30")]) },
    Key {
        path: "sensor_models.<id>.mount.x",
        field: Section,
        perception: change(&[("sensor_models.lidar.mount", r#"{ "x": 3 }"#)]),
        semantic: change(&[("sensor_models.front.mount", r#"{ "x": -20 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.mount.y",
        field: Section,
        perception: change(&[("sensor_models.lidar.mount", r#"{ "y": 3 }"#)]),
        semantic: change(&[("sensor_models.front.mount", r#"{ "y": 20 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.mount.yaw_deg",
        field: Section,
        perception: change(&[("sensor_models.cone.mount", r#"{ "yaw_deg": 90 }"#)]),
        semantic: change(&[("sensor_models.front.mount", r#"{ "yaw_deg": 90 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.detection_probability",
        field: Section,
        perception: change(&[("sensor_models.lidar.detection_probability", "0.5")]),
        semantic: change(&[("sensor_models.ring.detection_probability", "0.5")]),
    },
    Key {
        path: "sensor_models.<id>.position_noise.base",
        field: Section,
        perception: change(&[("sensor_models.lidar.position_noise", r#"{ "base": 1 }"#)]),
        semantic: change(&[("sensor_models.ring.position_noise.base", "3")]),
    },
    Key {
        path: "sensor_models.<id>.position_noise.per_m",
        field: Section,
        perception: change(&[("sensor_models.lidar.position_noise", r#"{ "per_m": 0.05 }"#)]),
        semantic: change(&[("sensor_models.ring.position_noise", r#"{ "per_m": 0.1 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.size_noise.base",
        field: Section,
        perception: change(&[("sensor_models.lidar.size_noise", r#"{ "base": 1 }"#)]),
        semantic: change(&[("sensor_models.ring.size_noise", r#"{ "base": 2 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.size_noise.per_m",
        field: Section,
        perception: change(&[("sensor_models.lidar.size_noise", r#"{ "per_m": 0.05 }"#)]),
        semantic: change(&[("sensor_models.ring.size_noise", r#"{ "per_m": 0.1 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.velocity_noise.base",
        field: Section,
        perception: refused(&[("sensor_models.lidar.velocity_noise", r#"{ "base": 1 }"#)]),
        semantic: change(&[("sensor_models.ring.velocity_noise", r#"{ "base": 3 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.velocity_noise.per_m",
        field: Section,
        perception: refused(&[("sensor_models.lidar.velocity_noise", r#"{ "per_m": 0.05 }"#)]),
        semantic: change(&[("sensor_models.ring.velocity_noise", r#"{ "per_m": 0.1 }"#)]),
    },
    Key {
        path: "sensor_models.<id>.ray_spacing_deg",
        field: Section,
        perception: change(&[("sensor_models.lidar.ray_spacing_deg", "3")]),
        semantic: refused(&[("sensor_models.front.ray_spacing_deg", "3")]),
    },
    // Agents.
    Key { path: "agents[].id", field: Section, perception: Descriptive, semantic: Descriptive },
    Key { path: "agents[].kind", field: Section, perception: change(&[("agents.2.kind", r#""truck""#)]), semantic: change(&[("agents.2.kind", r#""truck""#)]) },
    Key { path: "agents[].route", field: Section, perception: change(&[("agents.2.route", r#"["ns"]"#)]), semantic: change(&[("agents.2.route", r#"["we"]"#)]) },
    Key { path: "agents[].lane", field: Section, perception: with(&[("roads.1.lanes", "2")], &[("agents.2.lane", "1")]), semantic: with(&[("roads.3.lanes", "2")], &[("agents.2.lane", "1")]) },
    Key { path: "agents[].path", field: Section, perception: change(&[("agents.3.path", "[[-10, -10], [-10, 10]]")]), semantic: change(&[("agents.3.path", "[[-6, 9], [6, 9]]")]) },
    Key {
        path: "agents[].trace",
        field: Section,
        perception: with(&[("traces", r#"{ "fcd": "sumo/grid3x3.fcd.xml" }"#), ("agents.5", r#"{ "id": "t", "kind": "pedestrian", "trace": "ped0", "connected": true, "sensors": ["lidar"] }"#)], &[("agents.5.trace", r#""veh0""#)]),
        semantic: with(SUMO_SEMANTIC, &[("agents.0.trace", r#""veh6""#)]),
    },
    Key { path: "agents[].position", field: Section, perception: change(&[("agents.4.position", "[-8, 8]")]), semantic: change(&[("agents.1.position", "[20, -20]")]) },
    Key {
        path: "agents[].heading_deg",
        field: Section,
        perception: change(&[("agents.4.heading_deg", "180")]),
        semantic: with(&[("semantic.rsu_sight", r#""line_of_sight""#), ("sensor_models.ring.fov_deg", "90")], &[("agents.1.heading_deg", "180")]),
    },
    Key { path: "agents[].start.time", field: Section, perception: change(&[("agents.2.start.time", "0.5")]), semantic: change(&[("agents.2.start.time", "2")]) },
    Key { path: "agents[].start.offset", field: Section, perception: change(&[("agents.2.start.offset", "10")]), semantic: change(&[("agents.2.start.offset", "30")]) },
    Key { path: "agents[].speed.target", field: Section, perception: change(&[("agents.2.speed.target", "9")]), semantic: change(&[("agents.2.speed.target", "4")]) },
    Key { path: "agents[].speed.initial", field: Section, perception: change(&[("agents.2.speed.initial", "0")]), semantic: change(&[("agents.2.speed.initial", "0")]) },
    Key {
        path: "agents[].speed.acceleration",
        field: Section,
        perception: with(&[("agents.2.speed.initial", "0")], &[("agents.2.speed.acceleration", "4")]),
        semantic: with(&[("agents.2.speed.initial", "0")], &[("agents.2.speed.acceleration", "4")]),
    },
    Key {
        path: "agents[].speed.limit_factor",
        field: Section,
        perception: with(&[("agents.2.speed.target", "15")], &[("agents.2.speed.limit_factor", "1.4")]),
        semantic: with(&[("agents.2.speed.target", "15")], &[("agents.2.speed.limit_factor", "1.4")]),
    },
    Key {
        path: "agents[].size.length",
        field: Section,
        perception: change(&[("agents.2.size", r#"{ "length": 8, "width": 1.8 }"#)]),
        semantic: change(&[("agents.2.size", r#"{ "length": 12, "width": 1.8 }"#)]),
    },
    Key {
        path: "agents[].size.width",
        field: Section,
        perception: change(&[("agents.2.size", r#"{ "length": 4.5, "width": 3 }"#)]),
        semantic: change(&[("agents.2.size", r#"{ "length": 4.5, "width": 3 }"#)]),
    },
    Key { path: "agents[].connected", field: Section, perception: change(&[("agents.1.connected", "false"), ("agents.1.sensors", "[]")]), semantic: change(&[("agents.2.connected", "true")]) },
    Key { path: "agents[].sensors", field: Section, perception: change(&[("agents.1.sensors", r#"["cone"]"#)]), semantic: change(&[("agents.0.sensors", r#"["front", "ring"]"#)]) },
    // Collective perception.
    Key { path: "localization.position_sigma", field: Section, perception: change(&[("localization.position_sigma", "0.5")]), semantic: Section },
    Key { path: "localization.heading_sigma_deg", field: Section, perception: change(&[("localization.heading_sigma_deg", "3")]), semantic: Section },
    Key { path: "localization.filter", field: Section, perception: change(&[("localization.filter", r#""none""#)]), semantic: Section },
    Key { path: "localization.process_position_sigma", field: Section, perception: change(&[("localization.process_position_sigma", "1")]), semantic: Section },
    Key { path: "localization.process_heading_sigma_deg", field: Section, perception: change(&[("localization.process_heading_sigma_deg", "5")]), semantic: Section },
    Key { path: "localization.odometry.model", field: Section, perception: change(&[("localization.odometry.model", r#""exact""#)]), semantic: Section },
    Key { path: "localization.odometry.speed_sigma", field: Section, perception: change(&[("localization.odometry.speed_sigma", "1")]), semantic: Section },
    Key { path: "localization.odometry.speed_bias", field: Section, perception: change(&[("localization.odometry.speed_bias", "0.08")]), semantic: Section },
    Key { path: "localization.odometry.yaw_rate_sigma_deg", field: Section, perception: change(&[("localization.odometry.yaw_rate_sigma_deg", "3")]), semantic: Section },
    Key { path: "localization.odometry.yaw_rate_bias_deg", field: Section, perception: change(&[("localization.odometry.yaw_rate_bias_deg", "4")]), semantic: Section },
    Key { path: "perception.ego", field: Section, perception: change(&[("perception.ego", r#""cav""#)]), semantic: MakesJoint },
    Key { path: "perception.cooperating", field: Section, perception: change(&[("perception.cooperating", "2")]), semantic: MakesJoint },
    Key { path: "perception.inverse_model.occupied", field: Section, perception: change(&[("perception.inverse_model", r#"{ "occupied": 0.9 }"#)]), semantic: MakesJoint },
    Key { path: "perception.inverse_model.free", field: Section, perception: change(&[("perception.inverse_model", r#"{ "free": 0.1 }"#)]), semantic: MakesJoint },
    Key { path: "perception.snapshot", field: Section, perception: change(&[("perception.snapshot", "0.2")]), semantic: MakesJoint },
    Key {
        path: "perception.region.center",
        field: Section,
        perception: with(&[("perception.region", r#"{ "center": [0, 0], "radius": 15 }"#)], &[("perception.region.center", "[5, 0]")]),
        semantic: MakesJoint,
    },
    Key {
        path: "perception.region.radius",
        field: Section,
        perception: with(&[("perception.region", r#"{ "center": [0, 0], "radius": 15 }"#)], &[("perception.region.radius", "10")]),
        semantic: MakesJoint,
    },
    // The semantic pipeline's world.
    Key { path: "traffic.vehicles.density_per_km", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.density_per_km", "10")]) },
    Key { path: "traffic.vehicles.routes", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.routes", r#"[["we"]]"#)]) },
    Key { path: "traffic.vehicles.non_compliant", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.non_compliant", "0")]) },
    Key { path: "traffic.vehicles.overspeed_factor", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.overspeed_factor", "[1.5, 2]")]) },
    Key { path: "traffic.vehicles.mix.car", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.mix", r#"{ "car": 1, "truck": 1 }"#)]) },
    Key { path: "traffic.vehicles.mix.truck", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.mix", r#"{ "truck": 1 }"#)]) },
    Key { path: "traffic.vehicles.mix.bus", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.mix", r#"{ "bus": 1 }"#)]) },
    Key { path: "traffic.vehicles.mix.motorbike", field: Section, perception: Section, semantic: change(&[("traffic.vehicles.mix", r#"{ "motorbike": 1 }"#)]) },
    Key { path: "traffic.pedestrians.per_minute", field: Section, perception: Section, semantic: change(&[("traffic.pedestrians.per_minute", "5")]) },
    Key { path: "traffic.pedestrians.speed", field: Section, perception: Section, semantic: change(&[("traffic.pedestrians.speed", "2")]) },
    Key { path: "traffic.pedestrians.approach", field: Section, perception: Section, semantic: change(&[("traffic.pedestrians.approach", "0")]) },
    Key { path: "crosswalks[].id", field: Section, perception: Section, semantic: Descriptive },
    Key { path: "crosswalks[].from", field: Section, perception: Section, semantic: change(&[("crosswalks.0.from", "[-6, -20]")]) },
    Key { path: "crosswalks[].to", field: Section, perception: Section, semantic: change(&[("crosswalks.0.to", "[6, -20]")]) },
    Key { path: "crosswalks[].width", field: Section, perception: Section, semantic: change(&[("crosswalks.0.width", "20")]) },
    Key { path: "interaction_areas[].id", field: Section, perception: Section, semantic: Descriptive },
    Key { path: "interaction_areas[].polygon", field: Section, perception: Section, semantic: change(&[("interaction_areas.0.polygon", "[[-40, -40], [40, -40], [40, 40], [-40, 40]]")]) },
    Key {
        path: "interaction_areas[].circle.center",
        field: Section,
        perception: Section,
        semantic: with(&[("interaction_areas.0", r#"{ "id": "junction", "circle": { "center": [0, 0], "radius": 12 } }"#)], &[("interaction_areas.0.circle.center", "[0, 30]")]),
    },
    Key {
        path: "interaction_areas[].circle.radius",
        field: Section,
        perception: Section,
        semantic: with(&[("interaction_areas.0", r#"{ "id": "junction", "circle": { "center": [0, 0], "radius": 12 } }"#)], &[("interaction_areas.0.circle.radius", "40")]),
    },
    // A declared area names road users' records (results.json `objects`).
    Key { path: "areas[].id", field: Section, perception: Section, semantic: Descriptive },
    Key {
        path: "areas[].polygon",
        field: Section,
        perception: Section,
        semantic: with(&[("areas", r#"[ { "id": "zone", "polygon": [[-40, -40], [40, -40], [40, 40], [-40, 40]] } ]"#)], &[("areas.0.polygon", "[[100, 100], [110, 100], [110, 110]]")]),
    },
    Key {
        path: "areas[].circle.center",
        field: Section,
        perception: Section,
        semantic: with(&[("areas", r#"[ { "id": "zone", "circle": { "center": [0, 0], "radius": 30 } } ]"#)], &[("areas.0.circle.center", "[200, 200]")]),
    },
    Key {
        path: "areas[].circle.radius",
        field: Section,
        perception: Section,
        semantic: with(&[("areas", r#"[ { "id": "zone", "circle": { "center": [0, 0], "radius": 30 } } ]"#)], &[("areas.0.circle.radius", "1")]),
    },
    Key { path: "driving.following", field: Section, perception: change(&[("driving.following", r#""idm""#)]), semantic: change(&[("driving.following", r#""idm""#)]) },
    Key {
        path: "driving.headway",
        field: Section,
        perception: with(&[("driving.following", r#""idm""#)], &[("driving.headway", "3")]),
        semantic: with(&[("driving.following", r#""idm""#)], &[("driving.headway", "3")]),
    },
    Key {
        path: "driving.min_gap",
        field: Section,
        perception: with(&[("driving.following", r#""idm""#)], &[("driving.min_gap", "8")]),
        semantic: with(&[("driving.following", r#""idm""#)], &[("driving.min_gap", "8")]),
    },
    Key {
        path: "driving.deceleration",
        field: Section,
        perception: with(&[("driving.following", r#""idm""#)], &[("driving.deceleration", "1")]),
        semantic: with(&[("driving.following", r#""idm""#)], &[("driving.deceleration", "1")]),
    },
    Key { path: "v2x.penetration", field: Section, perception: with(RADIO, &[("v2x.penetration", "0")]), semantic: change(&[("v2x.penetration", "0")]) },
    Key { path: "v2x.latency", field: Section, perception: with(RADIO, &[("v2x.latency", "0.3")]), semantic: change(&[("v2x.latency", "0.3")]) },
    Key { path: "v2x.channel.model", field: Section, perception: with(RADIO, &[("v2x.channel.model", r#""ideal""#)]), semantic: change(&[("v2x.channel.model", r#""ideal""#)]) },
    Key { path: "v2x.channel.tx_power_dbm", field: Section, perception: with(RADIO, &[("v2x.channel.tx_power_dbm", "-20")]), semantic: change(&[("v2x.channel.tx_power_dbm", "-20")]) },
    Key { path: "v2x.channel.shadowing_sigma_db", field: Section, perception: with(MARGINAL_RADIO, &[("v2x.channel.shadowing_sigma_db", "12")]), semantic: with(MARGINAL_RADIO, &[("v2x.channel.shadowing_sigma_db", "12")]) },
    Key { path: "v2x.channel.nlos_shadowing_sigma_db", field: Section, perception: with(BLOCKED_RADIO, &[("v2x.channel.nlos_shadowing_sigma_db", "12")]), semantic: with(MARGINAL_RADIO, &[("v2x.channel.nlos_shadowing_sigma_db", "12")]) },
    Key { path: "v2x.channel.device_loss_db", field: Section, perception: with(RADIO, &[("v2x.channel.device_loss_db", "40")]), semantic: change(&[("v2x.channel.device_loss_db", "40")]) },
    Key { path: "v2x.channel.sensitivity_dbm", field: Section, perception: with(RADIO, &[("v2x.channel.sensitivity_dbm", "-30")]), semantic: change(&[("v2x.channel.sensitivity_dbm", "-60")]) },
    Key { path: "v2x.channel.carrier_ghz", field: Section, perception: with(MARGINAL_RADIO, &[("v2x.channel.carrier_ghz", "60")]), semantic: with(MARGINAL_RADIO, &[("v2x.channel.carrier_ghz", "60")]) },
    Key { path: "v2x.channel.vehicle_antenna_m", field: Section, perception: with(MARGINAL_RADIO, &[("v2x.channel.vehicle_antenna_m", "1.1")]), semantic: change(&[("v2x.channel.vehicle_antenna_m", "1.1")]) },
    Key { path: "v2x.channel.rsu_antenna_m", field: Section, perception: with(BLOCKED_RADIO, &[("v2x.channel.rsu_antenna_m", "1.1")]), semantic: with(MARGINAL_RADIO, &[("v2x.channel.rsu_antenna_m", "1.1")]) },
    Key { path: "v2x.messages.rate_hz", field: Section, perception: with(RADIO, &[("v2x.messages.rate_hz", "2")]), semantic: refused_at(&[("v2x.messages.rate_hz", "5")], "v2x.messages") },
    Key { path: "v2x.messages.max_bytes", field: Section, perception: with(RADIO, &[("v2x.messages.max_bytes", "300")]), semantic: refused_at(&[("v2x.messages.max_bytes", "300")], "v2x.messages") },
    Key { path: "v2x.messages.oversize", field: Section, perception: with(SMALL_MESSAGES, &[("v2x.messages.oversize", r#""select""#)]), semantic: refused_at(&[("v2x.messages.oversize", r#""select""#)], "v2x.messages") },
    Key { path: "v2x.messages.max_age", field: Section, perception: with(RADIO, &[("v2x.messages.max_age", "0.1")]), semantic: refused_at(&[("v2x.messages.max_age", "0.1")], "v2x.messages") },
    Key { path: "v2x.messages.decay", field: Section, perception: with(RADIO, &[("v2x.messages.decay", "0.2")]), semantic: refused_at(&[("v2x.messages.decay", "0.2")], "v2x.messages") },
    Key {
        path: "semantic.ego",
        field: Section,
        perception: MakesJoint,
        semantic: with(&[("agents.2.connected", "true")], &[("agents.2.sensors", r#"["front"]"#), ("agents.0.sensors", "[]"), ("semantic.ego", r#""car""#)]),
    },
    Key {
        path: "semantic.rsus",
        field: Section,
        perception: MakesJoint,
        semantic: with(&[("agents.4", r#"{ "id": "rsu2", "kind": "rsu", "position": [20, -20], "sensors": ["ring"] }"#), ("sweep", r#"{ "semantic.rsus": [["rsu", "rsu2"], ["rsu2"]] }"#)], &[("sweep", r#"{ "semantic.rsus": [["rsu", "rsu2"], ["rsu"]] }"#)]),
    },
    Key { path: "semantic.proximity", field: Section, perception: MakesJoint, semantic: change(&[("semantic.proximity", "15")]) },
    Key { path: "semantic.horizon", field: Section, perception: MakesJoint, semantic: change(&[("semantic.horizon", "1")]) },
    Key { path: "semantic.d_min", field: Section, perception: MakesJoint, semantic: change(&[("semantic.d_min", "6")]) },
    Key { path: "semantic.overspeed.window", field: Section, perception: MakesJoint, semantic: with(NOISY_SPEEDS, &[("semantic.overspeed.window", "1")]) },
    Key { path: "semantic.overspeed.threshold", field: Section, perception: MakesJoint, semantic: with(NOISY_SPEEDS, &[("semantic.overspeed.threshold", "0.5")]) },
    Key { path: "semantic.hypotheses", field: Section, perception: MakesJoint, semantic: change(&[("semantic.hypotheses", "[1.5]")]) },
    Key { path: "semantic.rate", field: Section, perception: MakesJoint, semantic: change(&[("semantic.rate", "5")]) },
    Key { path: "semantic.risk_for", field: Section, perception: MakesJoint, semantic: change(&[("semantic.risk_for", r#""all""#)]) },
    Key { path: "semantic.rsu_sight", field: Section, perception: MakesJoint, semantic: change(&[("semantic.rsu_sight", r#""line_of_sight""#)]) },
    Key {
        path: "semantic.history",
        field: Section,
        perception: MakesJoint,
        semantic: with(&[("semantic.overspeed", r#"{ "window": 0.3 }"#), ("semantic.history", "0.3"), ("sensor_models.ring.position_noise.base", "1")], &[("semantic.history", "1")]),
    },
    Key {
        path: "semantic.caution.headway",
        field: Section,
        perception: MakesJoint,
        semantic: with(&[("driving.following", r#""idm""#), ("semantic.risk_for", r#""all""#), ("traffic.vehicles.routes.+", r#"["sn"]"#)], &[("semantic.caution", r#"{ "headway": 6 }"#)]),
    },
    Key { path: "semantic.caution.speed_factor", field: Section, perception: MakesJoint, semantic: with(&[("semantic.risk_for", r#""all""#)], &[("semantic.caution", r#"{ "speed_factor": 0.2 }"#)]) },
    Key { path: "semantic.caution.hold", field: Section, perception: MakesJoint, semantic: with(&[("semantic.risk_for", r#""all""#)], &[("semantic.caution", r#"{ "hold": 0 }"#)]) },
    Key { path: "semantic.baseline.distance", field: Section, perception: MakesJoint, semantic: change(&[("semantic.baseline", r#"{ "distance": 0.5 }"#)]) },
    Key { path: "semantic.baseline.speed", field: Section, perception: MakesJoint, semantic: with(NOISY_SPEEDS, &[("semantic.baseline", r#"{ "speed": 3 }"#)]) },
    Key {
        path: "semantic.baseline.heading_deg",
        field: Section,
        perception: MakesJoint,
        semantic: with(&[ARC_ROAD, ("agents.2.route", r#"["bend"]"#), ("agents.2.start.offset", "0"), ("semantic.baseline", r#"{ "distance": 100, "speed": 100, "interval": 100 }"#)], &[("semantic.baseline.heading_deg", "0.5")]),
    },
    Key { path: "semantic.baseline.interval", field: Section, perception: MakesJoint, semantic: change(&[("semantic.baseline", r#"{ "interval": 0.1 }"#)]) },
    Key { path: "semantic.shares_over", field: Section, perception: MakesJoint, semantic: with(&[("agents.0.start.offset", "0")], &[("semantic.shares_over", r#""all""#)]) },
    Key { path: "semantic.contribution_over", field: Section, perception: MakesJoint, semantic: with(&[("agents.0.start.offset", "0")], &[("semantic.contribution_over", r#""all""#)]) },
    Key { path: "semantic.labelled_by", field: Section, perception: MakesJoint, semantic: change(&[("semantic.labelled_by", r#""critical""#)]) },
    Key { path: "semantic.runs", field: Section, perception: MakesJoint, semantic: change(&[("semantic.runs", "2")]) },
    // Requirements and published figures: what is judged and shown.
    Key { path: "requirements[].id", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key { path: "requirements[].text", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key {
        path: "requirements[].where",
        field: with(&[FUSION_SWEEP], &[("requirements.0.where", r#"{ "fusion.method": "bayes" }"#)]),
        perception: with(&[COOPERATING_SWEEP], &[("requirements.0.where", r#"{ "perception.cooperating": 3 }"#)]),
        semantic: with(&[RATE_SWEEP], &[("requirements.0.where", r#"{ "semantic.rate": 5 }"#)]),
    },
    Key {
        path: "requirements[].check.metric",
        field: change(&[("requirements.0.check.metric", r#""below_threshold_fraction""#)]),
        perception: change(&[("requirements.0.check.metric", r#""blind_recall""#)]),
        semantic: change(&[("requirements.0.check.metric", r#""transmitted_share""#)]),
    },
    Key {
        path: "requirements[].check.at_least",
        field: change(&[("requirements.0.check.at_least", "0.99")]),
        perception: change(&[("requirements.0.check.at_least", "0.99")]),
        semantic: change(&[("requirements.0.check.at_least", "0.99")]),
    },
    Key {
        path: "requirements[].check.at_most",
        field: change(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_most": 0.5 }"#)]),
        perception: change(&[("requirements.0.check", r#"{ "metric": "occupied_recall", "at_most": 0.5 }"#)]),
        semantic: change(&[("requirements.0.check", r#"{ "metric": "packet_delivery_ratio", "at_most": 0.5 }"#)]),
    },
    Key {
        path: "requirements[].check.seeds",
        field: change(&[("requirements.0.check.seeds", "3")]),
        perception: change(&[("requirements.0.check.seeds", "3")]),
        semantic: change(&[("requirements.0.check.seeds", "3")]),
    },
    Key {
        path: "requirements[].check.confidence",
        field: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.confidence", "0.6")]),
        perception: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.confidence", "0.6")]),
        semantic: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.confidence", "0.6")]),
    },
    Key {
        path: "requirements[].check.holds_in",
        field: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.holds_in", "0.5")]),
        perception: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.holds_in", "0.5")]),
        semantic: with(&[("requirements.0.check.seeds", "3")], &[("requirements.0.check.holds_in", "0.5")]),
    },
    Key {
        path: "requirements[].check.method",
        field: with(&[("requirements.0.check.seeds", "3"), ("requirements.0.check.holds_in", "0.5")], &[("requirements.0.check.method", r#""wilson""#)]),
        perception: with(&[("requirements.0.check.seeds", "3"), ("requirements.0.check.holds_in", "0.5")], &[("requirements.0.check.method", r#""wilson""#)]),
        semantic: with(&[("requirements.0.check.seeds", "3"), ("requirements.0.check.holds_in", "0.5")], &[("requirements.0.check.method", r#""wilson""#)]),
    },
    Key {
        path: "requirements[].check.invariant",
        field: change(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)]),
        perception: change(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)]),
        semantic: refused(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)]),
    },
    Key {
        path: "requirements[].check.tolerance",
        field: with(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)], &[("requirements.0.check.tolerance", "0.5")]),
        perception: with(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)], &[("requirements.0.check.tolerance", "0.5")]),
        semantic: Class::Refused { set: &[("requirements.0.check", r#"{ "invariant": "mass_function", "tolerance": 0.5 }"#)], at: Some("requirements[0].check.invariant") },
    },
    Key { path: "requirements[].check.signal", field: refused(&[SIGNAL]), perception: change(&[SIGNAL]), semantic: change(&[SEMANTIC_SIGNAL]) },
    Key {
        path: "requirements[].check.always.at_least",
        field: refused_at(&[SIGNAL], SIGNAL_AT),
        perception: with(&[SIGNAL], &[("requirements.0.check.always.at_least", "0.9")]),
        semantic: with(&[SEMANTIC_SIGNAL], &[("requirements.0.check.always.at_least", "3")]),
    },
    Key {
        path: "requirements[].check.always.at_most",
        field: refused_at(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "always": { "at_most": 0.1 } }"#)], SIGNAL_AT),
        perception: change(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "always": { "at_most": 0.9 } }"#)]),
        semantic: change(&[("requirements.0.check", r#"{ "signal": "rsu_only_objects", "always": { "at_most": 0 } }"#)]),
    },
    Key {
        path: "requirements[].check.eventually.at_least",
        field: refused_at(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "eventually": { "at_least": 0.1 } }"#)], SIGNAL_AT),
        perception: change(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "eventually": { "at_least": 0.9 } }"#)]),
        semantic: change(&[("requirements.0.check", r#"{ "signal": "rsu_only_objects", "eventually": { "at_least": 3 } }"#)]),
    },
    Key {
        path: "requirements[].check.eventually.at_most",
        field: refused_at(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "eventually": { "at_most": 0.1 } }"#)], SIGNAL_AT),
        perception: change(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "eventually": { "at_most": 0.9 } }"#)]),
        semantic: change(&[("requirements.0.check", r#"{ "signal": "rsu_only_objects", "eventually": { "at_most": 0 } }"#)]),
    },
    Key {
        path: "requirements[].check.within",
        field: refused_at(&[("requirements.0.check", r#"{ "signal": "occupied_recall", "always": { "at_least": 0.1 }, "within": 0.5 }"#)], SIGNAL_AT),
        perception: with(&[SIGNAL], &[("requirements.0.check.within", "0.3")]),
        semantic: with(&[SEMANTIC_SIGNAL], &[("requirements.0.check.within", "1")]),
    },
    Key {
        path: "requirements[].check.per_object",
        field: refused(&[("requirements.0.check", r#"{ "per_object": "warning_time", "at_least": 1 }"#)]),
        perception: refused(&[("requirements.0.check", r#"{ "per_object": "warning_time", "at_least": 1 }"#)]),
        semantic: change(&[("requirements.0.check", r#"{ "per_object": "warning_time", "at_least": 1 }"#)]),
    },
    Key {
        path: "requirements[].check.relative_to",
        field: refused(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "relative_to": "baseline" }"#)]),
        perception: refused(&[("requirements.0.check", r#"{ "metric": "occupied_recall", "at_least": 0.5, "relative_to": "baseline" }"#)]),
        semantic: with(&[("requirements.0.check", r#"{ "metric": "channel_load", "at_most": 1000000 }"#)], &[("requirements.0.check.relative_to", r#""baseline""#)]),
    },
    Key {
        path: "requirements[].check.by",
        field: refused(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "by": "difference" }"#)]),
        perception: refused(&[("requirements.0.check", r#"{ "metric": "occupied_recall", "at_least": 0.5, "by": "difference" }"#)]),
        semantic: with(&[COMPARISON], &[("requirements.0.check.by", r#""difference""#)]),
    },
    Key {
        path: "requirements[].check.objects.ids",
        field: refused_at(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "objects": { "ids": ["x"] } }"#)], OBJECTS_AT),
        perception: Driven("objects_select_a_systems_object_steps_and_detections_by_id_class_and_area"),
        semantic: with(&[PER_OBJECT], &[("requirements.0.check.objects", r#"{ "ids": ["car"] }"#)]),
    },
    Key {
        path: "requirements[].check.objects.classes",
        field: refused_at(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "objects": { "classes": ["car"] } }"#)], OBJECTS_AT),
        perception: Driven("objects_select_a_systems_object_steps_and_detections_by_id_class_and_area"),
        semantic: with(&[PER_OBJECT], &[("requirements.0.check.objects", r#"{ "classes": ["pedestrian"] }"#)]),
    },
    Key {
        path: "requirements[].check.objects.areas",
        field: refused_at(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "objects": { "areas": ["a"] } }"#)], OBJECTS_AT),
        perception: Driven("objects_select_a_systems_object_steps_and_detections_by_id_class_and_area"),
        semantic: with(&[PER_OBJECT], &[("requirements.0.check.objects", r#"{ "areas": ["cw"] }"#)]),
    },
    Key {
        path: "requirements[].check.objects.closer_than",
        field: refused_at(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "objects": { "closer_than": 5 } }"#)], OBJECTS_AT),
        perception: refused_at(&[("requirements.0.check", r#"{ "metric": "occupied_recall", "at_least": 0.5, "objects": { "closer_than": 5 } }"#)], OBJECTS_AT),
        semantic: with(&[PER_OBJECT], &[("requirements.0.check.objects", r#"{ "closer_than": 20 }"#)]),
    },
    Key {
        path: "requirements[].check.objects.between",
        field: refused_at(&[("requirements.0.check", r#"{ "metric": "accuracy", "at_least": 0.5, "objects": { "between": [0, 1] } }"#)], OBJECTS_AT),
        perception: refused_at(&[("requirements.0.check", r#"{ "metric": "occupied_recall", "at_least": 0.5, "objects": { "between": [0, 1] } }"#)], OBJECTS_AT),
        semantic: with(&[PER_OBJECT], &[("requirements.0.check.objects", r#"{ "between": [3, 6] }"#)]),
    },
    // More samples than any run has: the verdict turns not exercised.
    Key {
        path: "requirements[].check.min_samples",
        field: change(&[("requirements.0.check.min_samples", "1000000000")]),
        perception: change(&[("requirements.0.check.min_samples", "1000000000")]),
        semantic: change(&[("requirements.0.check.min_samples", "1000000000")]),
    },
    // A not-exercised verdict accepted: the run's gate passes.
    Key {
        path: "requirements[].accept_not_exercised",
        field: with(&[("requirements.0.check.min_samples", "1000000000")], &[("requirements.0.accept_not_exercised", r#""no sample expected""#)]),
        perception: with(&[("requirements.0.check.min_samples", "1000000000")], &[("requirements.0.accept_not_exercised", r#""no sample expected""#)]),
        semantic: with(&[("requirements.0.check.min_samples", "1000000000")], &[("requirements.0.accept_not_exercised", r#""no sample expected""#)]),
    },
    Key { path: "references[].source", field: Descriptive, perception: Descriptive, semantic: Descriptive },
    Key {
        path: "references[].metric",
        field: with(&[("references", r#"[ { "source": "S", "metric": "accuracy", "value": 0.9 } ]"#)], &[("references.0.metric", r#""below_threshold_fraction""#)]),
        perception: with(&[("references", r#"[ { "source": "S", "metric": "occupied_recall", "value": 0.9 } ]"#)], &[("references.0.metric", r#""blind_recall""#)]),
        semantic: with(&[("references", r#"[ { "source": "S", "metric": "packet_delivery_ratio", "value": 0.9 } ]"#)], &[("references.0.metric", r#""transmitted_share""#)]),
    },
    Key {
        path: "references[].value",
        field: with(&[("references", r#"[ { "source": "S", "metric": "accuracy", "value": 0.9 } ]"#)], &[("references.0.value", "0.8")]),
        perception: with(&[("references", r#"[ { "source": "S", "metric": "occupied_recall", "value": 0.9 } ]"#)], &[("references.0.value", "0.8")]),
        semantic: with(&[("references", r#"[ { "source": "S", "metric": "packet_delivery_ratio", "value": 0.9 } ]"#)], &[("references.0.value", "0.8")]),
    },
    Key {
        path: "references[].where",
        field: with(&[FUSION_SWEEP, ("references", r#"[ { "source": "S", "metric": "accuracy", "value": 0.9 } ]"#)], &[("references.0.where", r#"{ "fusion.method": "bayes" }"#)]),
        perception: with(&[COOPERATING_SWEEP, ("references", r#"[ { "source": "S", "metric": "occupied_recall", "value": 0.9 } ]"#)], &[("references.0.where", r#"{ "perception.cooperating": 3 }"#)]),
        semantic: with(&[RATE_SWEEP, ("references", r#"[ { "source": "S", "metric": "packet_delivery_ratio", "value": 0.9 } ]"#)], &[("references.0.where", r#"{ "semantic.rate": 5 }"#)]),
    },
    // Sweeps, the space falsify searches, the recording.
    Key { path: "sweep", field: change(&[FUSION_SWEEP]), perception: change(&[COOPERATING_SWEEP]), semantic: change(&[RATE_SWEEP]) },
    // The second sweep leaves the file's seed as written: a value every sweep
    // point replaced would be refused.
    Key {
        path: "sweeps",
        field: change(&[("sweeps", r#"[ { "seed": [1, 2] }, { "fusion.method": ["bayes"] } ]"#)]),
        perception: change(&[("sweeps", r#"[ { "seed": [3, 4] }, { "perception.cooperating": [1] } ]"#)]),
        semantic: change(&[("sweeps", r#"[ { "seed": [5, 6] }, { "semantic.rate": [5] } ]"#)]),
    },
    Key {
        path: "vary",
        field: change(&[("vary", r#"{ "field.masses.gamma": [5, 15] }"#)]),
        perception: change(&[("vary", r#"{ "localization.position_sigma": [0, 0.5] }"#)]),
        semantic: change(&[("vary", r#"{ "v2x.channel.sensitivity_dbm": [-100, -60] }"#)]),
    },
    Key {
        path: "record.point",
        field: with(&[FUSION_SWEEP, ("record", "{}")], &[("record.point", "1")]),
        perception: with(&[COOPERATING_SWEEP, ("record", "{}")], &[("record.point", "1")]),
        semantic: with(&[RATE_SWEEP, ("record", "{}")], &[("record.point", "1")]),
    },
    Key {
        path: "record.where",
        field: with(&[FUSION_SWEEP, ("record", "{}")], &[("record.where", r#"{ "fusion.method": "bayes" }"#)]),
        perception: with(&[COOPERATING_SWEEP, ("record", "{}")], &[("record.where", r#"{ "perception.cooperating": 3 }"#)]),
        semantic: with(&[RATE_SWEEP, ("record", "{}")], &[("record.where", r#"{ "semantic.rate": 5 }"#)]),
    },
    Key {
        path: "record.points",
        field: refused(&[("record", r#"{ "points": "all" }"#)]),
        perception: with(&[COOPERATING_SWEEP, ("record", "{}")], &[("record.points", r#""all""#)]),
        semantic: with(&[RATE_SWEEP, ("record", "{}")], &[("record.points", r#""all""#)]),
    },
    Key {
        path: "record.grid_rate",
        field: refused(&[("record", r#"{ "grid_rate": 2 }"#)]),
        perception: with(&[("record", "{}")], &[("record.grid_rate", "5")]),
        semantic: refused(&[("record", r#"{ "grid_rate": 2 }"#)]),
    },
    Key {
        path: "record.agent_grids",
        field: refused(&[("record", r#"{ "agent_grids": true }"#)]),
        perception: with(&[("record", "{}")], &[("record.agent_grids", "true")]),
        semantic: refused(&[("record", r#"{ "agent_grids": true }"#)]),
    },
    // A system under test runs in a perception world only; what each key does
    // shows when the CLI drives a system (tests/e2e/system.rs).
    Key { path: "system_under_test.command", field: Section, perception: Driven("each_key_of_system_under_test_changes_the_judgement"), semantic: Section },
    Key { path: "system_under_test.agent", field: Section, perception: Driven("each_key_of_system_under_test_changes_the_judgement"), semantic: Section },
    Key { path: "system_under_test.sensors", field: Section, perception: Driven("each_key_of_system_under_test_changes_the_judgement"), semantic: Section },
    Key { path: "system_under_test.gate", field: Section, perception: Driven("each_key_of_system_under_test_changes_the_judgement"), semantic: Section },
    Key { path: "system_under_test.min_existence", field: Section, perception: Driven("each_key_of_system_under_test_changes_the_judgement"), semantic: Section },
    Key { path: "system_under_test.step_timeout", field: Section, perception: Driven("step_timeout_bounds_a_slow_system"), semantic: Section },
];

/// The keys a joint world ([`JOINT`]) does not treat as a semantic world
/// does: those of the grid, the fusion, self-localization and the messages
/// that carry grids, which it reads; the egos, which it changes together;
/// what it refuses (`v2x.penetration`, pooled runs); `rsu_sight`, whose
/// default there is `line_of_sight`; and `packet_delivery_ratio`, which it
/// splits in two. Every other key is checked in the joint world as the
/// semantic column says.
#[rustfmt::skip]
const JOINT_KEYS: &[(&str, Class)] = &[
    ("grid.origin", change(&[("grid.origin", "[-41, -40]")])),
    ("grid.size", change(&[("grid.size", "[70, 80]")])),
    ("grid.cell", change(&[("grid.cell", "0.5")])),
    ("fusion.label", change(&[("fusion.label", r#""Baseline""#)])),
    ("fusion.method", change(&[("fusion.method", r#""dempster""#)])),
    ("fusion.weights", with(&[("fusion.method", r#""distance_weighted""#)], &[("fusion.weights", r#""mean_one""#)])),
    ("fusion.sources", with(&[("fusion.method", r#""distance_weighted""#), ("fusion.weights", r#""mean_one""#)], &[("fusion.sources", r#""pairwise""#)])),
    ("fusion.switch.measure", with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "measure": "difference", "threshold": 2 }"#)], &[("fusion.switch.measure", r#""ratio""#)])),
    ("fusion.switch.threshold", with(&[("fusion.method", r#""hybrid""#), ("fusion.switch", r#"{ "threshold": 2 }"#)], &[("fusion.switch.threshold", "20")])),
    ("decision.threshold", change(&[("decision.threshold", "0.5")])),
    ("decision.rule", with(&[("decision.threshold", "0.5")], &[("decision.rule", r#""exceeds""#)])),
    ("sensor_models.<id>.ray_spacing_deg", change(&[("sensor_models.front.ray_spacing_deg", "3")])),
    ("localization.position_sigma", change(&[("localization.position_sigma", "0.5")])),
    ("localization.heading_sigma_deg", change(&[("localization.heading_sigma_deg", "3")])),
    ("localization.filter", change(&[("localization.filter", r#""none""#)])),
    ("localization.process_position_sigma", change(&[("localization.process_position_sigma", "1")])),
    ("localization.process_heading_sigma_deg", change(&[("localization.process_heading_sigma_deg", "5")])),
    ("localization.odometry.model", change(&[("localization.odometry.model", r#""exact""#)])),
    ("localization.odometry.speed_sigma", change(&[("localization.odometry.speed_sigma", "1")])),
    ("localization.odometry.speed_bias", change(&[("localization.odometry.speed_bias", "0.08")])),
    ("localization.odometry.yaw_rate_sigma_deg", change(&[("localization.odometry.yaw_rate_sigma_deg", "3")])),
    ("localization.odometry.yaw_rate_bias_deg", change(&[("localization.odometry.yaw_rate_bias_deg", "4")])),
    // One ego for both models: the two keys change together (apart, `check`
    // refuses them: tests/fixtures/invalid/joint-ambiguous-settings.yaml).
    ("perception.ego", change(&[("perception.ego", r#""cav""#), ("semantic.ego", r#""cav""#)])),
    ("semantic.ego", change(&[("semantic.ego", r#""cav""#), ("perception.ego", r#""cav""#)])),
    ("perception.cooperating", change(&[("perception.cooperating", "2")])),
    ("perception.inverse_model.occupied", change(&[("perception.inverse_model", r#"{ "occupied": 0.9 }"#)])),
    ("perception.inverse_model.free", change(&[("perception.inverse_model", r#"{ "free": 0.1 }"#)])),
    ("perception.snapshot", change(&[("perception.snapshot", "0.2")])),
    ("perception.region.center", with(&[("perception.region", r#"{ "center": [0, 0], "radius": 15 }"#)], &[("perception.region.center", "[5, 0]")])),
    ("perception.region.radius", with(&[("perception.region", r#"{ "center": [0, 0], "radius": 15 }"#)], &[("perception.region.radius", "10")])),
    ("semantic.rsus", with(&[("agents.5", r#"{ "id": "rsu2", "kind": "rsu", "position": [20, -20], "sensors": ["ring"] }"#), ("sweep", r#"{ "semantic.rsus": [["rsu", "rsu2"], ["rsu2"]] }"#)], &[("sweep", r#"{ "semantic.rsus": [["rsu", "rsu2"], ["rsu"]] }"#)])),
    ("semantic.rsu_sight", change(&[("semantic.rsu_sight", r#""range""#)])),
    ("semantic.runs", refused(&[("semantic.runs", "2")])),
    ("v2x.penetration", refused(&[("v2x.penetration", "0.5")])),
    ("v2x.messages.rate_hz", change(&[("v2x.messages.rate_hz", "2")])),
    ("v2x.messages.max_bytes", change(&[("v2x.messages.max_bytes", "300")])),
    ("v2x.messages.oversize", with(&[("v2x.messages.max_bytes", "300")], &[("v2x.messages.oversize", r#""select""#)])),
    ("v2x.messages.max_age", change(&[("v2x.messages.max_age", "0.1")])),
    ("v2x.messages.decay", change(&[("v2x.messages.decay", "0.2")])),
    ("record.grid_rate", with(&[("record", "{}")], &[("record.grid_rate", "5")])),
    ("record.agent_grids", with(&[("record", "{}")], &[("record.agent_grids", "true")])),
    ("requirements[].check.invariant", change(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)])),
    ("requirements[].check.tolerance", with(&[("requirements.0.check", r#"{ "invariant": "mass_function" }"#)], &[("requirements.0.check.tolerance", "0.5")])),
    ("requirements[].check.at_most", change(&[("requirements.0.check", r#"{ "metric": "semantic_packet_delivery_ratio", "at_most": 0.5 }"#)])),
    ("references[].metric", with(&[("references", r#"[ { "source": "S", "metric": "semantic_packet_delivery_ratio", "value": 0.9 } ]"#)], &[("references.0.metric", r#""occupied_recall""#)])),
    ("references[].value", with(&[("references", r#"[ { "source": "S", "metric": "occupied_recall", "value": 0.9 } ]"#)], &[("references.0.value", "0.8")])),
    ("references[].where", with(&[RATE_SWEEP, ("references", r#"[ { "source": "S", "metric": "occupied_recall", "value": 0.9 } ]"#)], &[("references.0.where", r#"{ "semantic.rate": 5 }"#)])),
];

/// A road with an arc in either world (the third of a perception world, the
/// fifth of a semantic one).
const ARC_ROAD: Set = (
    "roads.+",
    r#"{ "id": "bend", "arc": { "center": [0, 0], "radius": 20, "start_deg": -60, "end_deg": 90 }, "speed_limit": 10 }"#,
);

/// A roundabout and the road that leaves it, with the car on them.
const RING: &[Set] = &[
    (
        "roads.2",
        r#"{ "id": "ring", "roundabout": { "center": [0, 0], "radius": 15 }, "speed_limit": 10 }"#,
    ),
    (
        "roads.3",
        r#"{ "id": "out", "polyline": [[0, 15], [0, 30]], "speed_limit": 10 }"#,
    ),
    ("agents.2.route", r#"["ring", "out"]"#),
    ("agents.2.start.offset", "0"),
];

/// The same in a semantic world.
const SEMANTIC_RING: &[Set] = &[
    (
        "roads.4",
        r#"{ "id": "ring", "roundabout": { "center": [0, 0], "radius": 15 }, "speed_limit": 10 }"#,
    ),
    (
        "roads.5",
        r#"{ "id": "out", "polyline": [[0, 15], [0, 30]], "speed_limit": 10 }"#,
    ),
    ("agents.2.route", r#"["ring", "out"]"#),
    ("agents.2.start.offset", "0"),
];

/// Sets `path` (dotted; a number indexes a list, `+` appends to it) in `doc`
/// to `value`, creating mappings on the way.
fn set(doc: &mut Value, path: &str, value: Value) {
    let mut node = doc;
    let segments: Vec<&str> = path.split('.').collect();
    for (i, segment) in segments.iter().enumerate() {
        let last = i + 1 == segments.len();
        node = match node {
            Value::Array(items) => {
                let index = if *segment == "+" {
                    items.len()
                } else {
                    segment
                        .parse::<usize>()
                        .unwrap_or_else(|_| panic!("`{segment}` of `{path}` is not an index"))
                };
                if index == items.len() {
                    items.push(Value::Null);
                }
                &mut items[index]
            }
            Value::Null => {
                *node = Value::Object(Default::default());
                node.as_object_mut().unwrap().entry(*segment).or_insert(Value::Null)
            }
            Value::Object(map) => map.entry(*segment).or_insert(Value::Null),
            other => panic!("cannot set `{path}`: `{segment}` is under {other}"),
        };
        if last {
            *node = value;
            return;
        }
    }
}

/// The base of `kind` with `settings` applied.
fn document(kind: Kind, settings: &[&[Set]]) -> Value {
    let mut doc = base(kind);
    for &(path, value) in settings.iter().copied().flatten() {
        let value: Value = serde_json::from_str(value).unwrap_or_else(|e| panic!("`{path}`: {value} is not JSON: {e}"));
        if value.is_null() {
            // `null` removes the setting.
            let (parent, key) = path.rsplit_once('.').unwrap_or(("", path));
            let mut node = &mut doc;
            for segment in parent.split('.').filter(|s| !s.is_empty()) {
                node = &mut node[segment];
            }
            node.as_object_mut().unwrap().remove(key);
        } else {
            set(&mut doc, path, value);
        }
    }
    doc
}

/// What a scenario's evidence shows: the outcome of every point (pictures
/// and signals included), results.json but for where and when it ran, the
/// recording's settings and the space falsify searches.
fn evidence(text: &str) -> Result<String, Vec<Error>> {
    let disk = |path: &std::path::Path| std::fs::read(root().join(path));
    let options = Options {
        loader: Some(&disk),
        ..Default::default()
    };
    let scenario = compile(FILE, text, &options).map_err(|errors| errors.0)?;
    let run = sightline_engine::simulate(&scenario);
    let verdicts = sightline_oracles::check(&scenario, &run);
    let provenance = Provenance {
        tool: Tool {
            name: "sightline".into(),
            version: "test".into(),
            git: "test".into(),
        },
        scenario_path: FILE.into(),
        scenario_sha256: "0".repeat(64),
        scenario_text: String::new(),
        recording: None,
        execution: Execution {
            os: "test".into(),
            arch: "test".into(),
            threads: 1,
            started: "2026-01-01T00:00:00Z".into(),
            duration_seconds: 0.0,
            points: Vec::new(),
        },
    };
    let results =
        serde_json::to_string(&Results::new(&scenario, &run, &verdicts, &provenance)).expect("results serialize");
    // Debug, not PartialEq: an undefined metric is NaN in both.
    Ok(format!(
        "{:?}\n{results}\n{:?}\n{:?}",
        run, scenario.record, scenario.vary
    ))
}

/// The JSON Schema of the language with its references resolved on demand.
struct Schema {
    root: Value,
}

impl Schema {
    fn new() -> Self {
        Self {
            root: sightline_dsl::schema(),
        }
    }

    /// `node` with a `$ref`, `allOf` or nullable `anyOf` to a definition followed.
    fn resolve<'a>(&'a self, node: &'a Value) -> &'a Value {
        if let Some(name) = node["$ref"].as_str().and_then(|r| r.strip_prefix("#/definitions/")) {
            return self.resolve(&self.root["definitions"][name]);
        }
        for key in ["allOf", "anyOf"] {
            if let Some(found) = node[key]
                .as_array()
                .into_iter()
                .flatten()
                .find(|n| n.get("$ref").is_some())
            {
                return self.resolve(found);
            }
        }
        node
    }

    /// How a node's children are named: its properties, its list's entries
    /// (`[]`), or the values of a map keyed by id (`.<id>`); `None` for a leaf.
    fn children<'a>(&'a self, node: &'a Value) -> Option<Children<'a>> {
        let node = self.resolve(node);
        if let Some(properties) = node["properties"].as_object() {
            return Some(Children::Properties(properties));
        }
        let items = self.resolve(&node["items"]);
        if items["properties"].is_object() {
            return Some(Children::Entries(items));
        }
        let values = self.resolve(&node["additionalProperties"]);
        if values["properties"].is_object() {
            return Some(Children::Values(values));
        }
        None
    }

    /// Every leaf key path: `agents[].speed.target`, `sensor_models.<id>.range`.
    fn leaves(&self) -> Vec<String> {
        let mut leaves = Vec::new();
        self.walk(&self.root, String::new(), &mut leaves);
        leaves
    }

    fn walk(&self, node: &Value, path: String, leaves: &mut Vec<String>) {
        match self.children(node) {
            None => leaves.push(path),
            Some(Children::Properties(properties)) => {
                for (key, child) in properties {
                    let child_path = if path.is_empty() {
                        key.clone()
                    } else {
                        format!("{path}.{key}")
                    };
                    self.walk(child, child_path, leaves);
                }
            }
            Some(Children::Entries(items)) => self.walk(items, format!("{path}[]"), leaves),
            Some(Children::Values(values)) => self.walk(values, format!("{path}.<id>"), leaves),
        }
    }

    /// The leaf key paths at which two scenarios differ.
    fn differences(&self, a: &Value, b: &Value) -> BTreeSet<String> {
        let mut found = BTreeSet::new();
        self.diff(&self.root, String::new(), a, b, &mut found);
        found
    }

    fn diff(&self, node: &Value, path: String, a: &Value, b: &Value, found: &mut BTreeSet<String>) {
        if a == b {
            return;
        }
        let join = |key: &str| {
            if path.is_empty() {
                key.to_string()
            } else {
                format!("{path}.{key}")
            }
        };
        match self.children(node) {
            None => {
                // A sweep or `vary` axis sets the key it names.
                if matches!(path.as_str(), "sweep" | "sweeps[]" | "vary") {
                    let keys: BTreeSet<&String> = [a, b]
                        .iter()
                        .filter_map(|v| v.as_object())
                        .flat_map(|m| m.keys())
                        .collect();
                    for key in keys.into_iter().filter(|k| a[k.as_str()] != b[k.as_str()]) {
                        found.insert(schema_path(key));
                    }
                }
                found.insert(path);
            }
            Some(Children::Properties(properties)) => {
                for (key, child) in properties {
                    self.diff(child, join(key), &a[key.as_str()], &b[key.as_str()], found);
                }
            }
            Some(Children::Entries(items)) => {
                let length = |v: &Value| v.as_array().map_or(0, Vec::len);
                for i in 0..length(a).max(length(b)) {
                    self.diff(items, format!("{path}[]"), &a[i], &b[i], found);
                }
            }
            Some(Children::Values(values)) => {
                let keys: BTreeSet<&String> = [a, b]
                    .iter()
                    .filter_map(|v| v.as_object())
                    .flat_map(|m| m.keys())
                    .collect();
                for key in keys {
                    self.diff(
                        values,
                        format!("{path}.<id>"),
                        &a[key.as_str()],
                        &b[key.as_str()],
                        found,
                    );
                }
            }
        }
    }
}

/// The key path of a dotted setting: `agents.ego.speed.target` →
/// `agents[].speed.target`, `sensor_models.lidar.range` →
/// `sensor_models.<id>.range`.
fn schema_path(dotted: &str) -> String {
    match dotted.split_once('.') {
        Some(("agents", rest)) => format!("agents[]{}", &rest[rest.find('.').unwrap_or(rest.len())..]),
        Some(("sensor_models", rest)) => format!("sensor_models.<id>{}", &rest[rest.find('.').unwrap_or(rest.len())..]),
        _ => dotted.to_string(),
    }
}

enum Children<'a> {
    Properties(&'a serde_json::Map<String, Value>),
    Entries(&'a Value),
    Values(&'a Value),
}

/// Whether `error`'s location points, in `text`, at the key that ends its path
/// or at that key's value (a list entry: at the entry).
fn points_at_key(text: &str, error: &Error) -> bool {
    let Some(line) = text.lines().nth(error.location.line - 1) else {
        return false;
    };
    let before: String = line.chars().take(error.location.column - 1).collect();
    let here: String = line.chars().skip(error.location.column - 1).collect();
    let last = error.path.rsplit('.').next().unwrap_or_default();
    match last.split_once('[') {
        // A list entry is located at the entry.
        Some(_) => here.starts_with('{'),
        // A key that has no effect is located at the key, a value the check
        // refuses at the value.
        None => here.starts_with(&format!("\"{last}\"")) || before.ends_with(&format!("\"{last}\": ")),
    }
}

/// A refused scenario: its text and its errors.
type Refusal = (String, Vec<Error>);

/// Checks one key in one kind of scenario; `Err` says what is wrong.
fn check(
    schema: &Schema,
    cache: &mut HashMap<String, Result<String, Vec<Error>>>,
    key: &Key,
    kind: Kind,
) -> Result<(), String> {
    let mut evaluate = |doc: &Value| {
        let text = serde_json::to_string_pretty(doc).unwrap();
        cache
            .entry(text.clone())
            .or_insert_with(|| evidence(&text))
            .clone()
            .map_err(|errors| (text, errors))
    };
    let touches = |before: &Value, after: &Value| {
        let touched = schema.differences(before, after);
        if touched.contains(key.path) {
            Ok(())
        } else {
            Err(format!("its settings touch {touched:?}, not the key"))
        }
    };
    match key.class(kind) {
        Descriptive => Ok(()),
        Class::Driven(test) => {
            let tests = include_str!("system.rs");
            if tests.contains(&format!("fn {test}() {{")) {
                Ok(())
            } else {
                Err(format!("tests/e2e/system.rs has no test `{test}` to show its effect"))
            }
        }
        MakesJoint => {
            let (before, after) = (base(kind), document(kind, &[joining(kind)]));
            let show = |(_, errors): (String, Vec<Error>)| {
                errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
            };
            let a = evaluate(&before).map_err(|e| format!("the base is refused: {}", show(e)))?;
            let b = evaluate(&after).map_err(|e| format!("the joint world is refused: {}", show(e)))?;
            if a == b {
                return Err("the joint world measures what the base measures".into());
            }
            Ok(())
        }
        Class::Effective { with, change } => {
            let before = document(kind, &[with]);
            let after = document(kind, &[with, change]);
            touches(&before, &after)?;
            let show = |(_, errors): (String, Vec<Error>)| {
                errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
            };
            let a = evaluate(&before).map_err(|e| format!("the scenario before the change is refused: {}", show(e)))?;
            let b = evaluate(&after).map_err(|e| format!("the changed scenario is refused: {}", show(e)))?;
            if a == b {
                return Err("changing it changes nothing".into());
            }
            Ok(())
        }
        Class::Refused { set, at } => refusal(&base(kind), &document(kind, &[set]), at, &touches, &mut evaluate),
        Section => {
            let section = key.path.split(['.', '[']).next().unwrap();
            let full = SECTIONS
                .iter()
                .find(|(name, _)| *name == section)
                .unwrap_or_else(|| panic!("no full value of section `{section}` in SECTIONS"));
            let after = document(kind, &[&[*full]]);
            refusal(
                &base(kind),
                &after,
                Some(section_refused_at(kind, section)),
                &touches,
                &mut evaluate,
            )
        }
    }
}

/// Checks that `after` (which writes the key) is refused at the key, or at `at`.
fn refusal(
    before: &Value,
    after: &Value,
    at: Option<&str>,
    touches: &dyn Fn(&Value, &Value) -> Result<(), String>,
    evaluate: &mut dyn FnMut(&Value) -> Result<String, Refusal>,
) -> Result<(), String> {
    touches(before, after)?;
    let Err((text, errors)) = evaluate(after) else {
        return Err("`check` accepts it".into());
    };
    let located = errors.iter().any(|error| {
        let on_key = match at {
            Some(at) => error.path == at,
            None => schema_prefix(&error.path, before, after),
        };
        on_key && points_at_key(&text, error)
    });
    if located {
        Ok(())
    } else {
        Err(format!(
            "refused, but not at the key: {}",
            errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
        ))
    }
}

/// Whether the error path `path` (`agents[1].connected`) names a node the
/// change from `before` to `after` wrote: the node differs between them.
fn schema_prefix(path: &str, before: &Value, after: &Value) -> bool {
    let pointer: String = path
        .replace('[', ".")
        .replace(']', "")
        .split('.')
        .map(|segment| format!("/{segment}"))
        .collect();
    after.pointer(&pointer).is_some() && before.pointer(&pointer) != after.pointer(&pointer)
}

#[test]
fn every_key_is_effective_or_refused_in_every_kind_of_scenario() {
    let schema = Schema::new();
    let leaves: BTreeSet<String> = schema.leaves().into_iter().collect();
    let table: BTreeMap<&str, &Key> = KEYS.iter().map(|key| (key.path, key)).collect();
    assert_eq!(table.len(), KEYS.len(), "a key is listed twice in KEYS");
    let unclassified: Vec<&String> = leaves
        .iter()
        .filter(|leaf| !table.contains_key(leaf.as_str()))
        .collect();
    assert!(
        unclassified.is_empty(),
        "keys of the schema without an entry in KEYS (say how to change each in each kind of scenario, or that \
         `check` refuses it): {unclassified:?}"
    );
    let stale: Vec<&&str> = table
        .keys()
        .chain(JOINT_KEYS.iter().map(|(path, _)| path))
        .filter(|path| !leaves.contains(**path))
        .collect();
    assert!(
        stale.is_empty(),
        "entries of KEYS or JOINT_KEYS that are not keys of the schema: {stale:?}"
    );
    let mut cache = HashMap::new();
    let mut failures = Vec::new();
    for key in KEYS {
        for kind in KINDS {
            if let Err(why) = check(&schema, &mut cache, key, kind) {
                failures.push(format!("{kind:?} {}: {why}", key.path));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} keys fail:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A sweep or `vary` axis that sets a key the scenario's kind ignores is
/// refused at the axis, by the command line too (exit 2, `file:line:col`).
#[test]
fn an_axis_that_sets_an_ignored_key_is_refused_where_it_is_written() {
    for (kind, dotted, value) in [
        (Kind::Semantic, "v2x.messages.rate_hz", "5"),
        (Kind::Perception, "traffic.pedestrians.per_minute", "3"),
        (Kind::Semantic, "grid.cell", "0.5"),
        (Kind::Semantic, "fusion.method", r#""bayes""#),
        (Kind::Semantic, "localization.position_sigma", "0.3"),
        (Kind::Field, "time.step", "0.1"),
        (Kind::Field, "v2x.latency", "0.1"),
    ] {
        for section in ["sweep", "vary"] {
            let axis = if section == "sweep" {
                format!("[{value}]")
            } else {
                format!(r#"{{ "one_of": [{value}] }}"#)
            };
            let mut doc = base(kind);
            doc[section] = serde_json::json!({ dotted: serde_json::from_str::<Value>(&axis).unwrap() });
            let text = serde_json::to_string_pretty(&doc).unwrap();
            let errors = evidence(&text).expect_err("an ignored key is refused");
            let here = format!("{section}.{dotted}");
            let at_axis = |e: &Error| {
                let line = text.lines().nth(e.location.line - 1).unwrap_or_default();
                let here: String = line.chars().skip(e.location.column - 1).collect();
                here.starts_with(&format!("\"{dotted}\""))
            };
            assert!(
                errors
                    .iter()
                    .any(|e| e.path == here && matches!(e.kind, ErrorKind::NoEffect(_)) && at_axis(e)),
                "{kind:?}: `{here}` is not refused at the axis: {errors:?}"
            );
        }
    }
}
