//! TTC, PET and DRAC (issue 17, part 3) through the CLI: the hand-computed
//! scene judged, listed, recorded and replayed, and the same measures checked
//! against CommonRoad's criticality package (commonroad-crime, pinned in
//! `.ci/run`) on two-road-user scenes where the definitions match, with the
//! documented differences asserted where they do not
//! (`docs/qualification.md`, "Metric definitions").
// See: issue 17, "Criticality metrics assessors know".

use std::path::Path;
use std::process::Command;

use serde_json::{Value, json};

use crate::support::{
    RECORDING, arg, read, read_json, requirement, root, sightline, temp_dir, tool, unescape_html, verdict,
};

const SCENE: &str = "tests/fixtures/valid/criticality.yaml";

/// The Python with commonroad-crime; `.ci/run` sets it.
const PYTHON_VAR: &str = "SIGHTLINE_CRIME_PYTHON";

/// The scene's values, worked out in `engine/tests/criticality.rs`, judged as
/// the requirements say; the pedestrian, never in conflict, leaves its check
/// not exercised (accepted); the report lists PET and DRAC; the recording
/// replays to the same verdicts.
#[test]
fn criticality_is_judged_listed_and_replayed() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", SCENE, "--out", arg(&out), "--record"]);
    run.assert_exit(0);
    let results = read_json(&out.join("results.json"));
    for (id, value, n) in [
        ("CRIT-TTC-01", 1.16, 1),
        ("CRIT-PET-01", 1.2, 2),
        ("CRIT-DRAC-01", 5.0 / 2.32, 1),
        ("CRIT-MIN-01", 1.16, 1),
        // At equality: TTC is to the nanosecond (it was 1.1599999999999995).
        ("CRIT-TTC-EQ", 1.16, 1),
    ] {
        let (status, measured, count) = verdict(&results, id);
        assert_eq!((status.as_str(), count), ("pass", Some(n)), "{id}");
        assert!((measured.unwrap() - value).abs() < 1e-9, "{id}: {measured:?}");
    }
    let pedestrian = requirement(&results, "CRIT-PED-01");
    assert_eq!(
        (&pedestrian["verdict"], &pedestrian["n"]),
        (&"not_exercised".into(), &0.into())
    );
    let records = results["sweep"][0]["objects"]["records"].as_array().unwrap();
    let lead = records.iter().find(|o| o["id"] == "lead").unwrap();
    assert!((lead["pet"].as_f64().unwrap() - 1.2).abs() < 1e-9);
    let walker = records.iter().find(|o| o["id"] == "walker").unwrap();
    assert_eq!(
        (&walker["min_ttc"], &walker["pet"], &walker["max_drac"]),
        (&Value::Null, &Value::Null, &Value::Null)
    );
    let assumptions = results["assumptions"].to_string();
    assert!(assumptions.contains("criticality.boxes"), "{assumptions}");
    let report = unescape_html(&read(&out.join("report.html")));
    assert!(report.contains(">PET (s)<") && report.contains(">max DRAC (m/s²)<"));

    let replay = sightline(["replay", arg(&out.join(RECORDING))]);
    replay.assert_exit(0);
    let lines = |stdout: &str| stdout.lines().skip(1).map(String::from).collect::<Vec<_>>();
    assert_eq!(lines(&replay.stdout), lines(&run.stdout));
}

/// Fewer road users than a per-object check needs, one of them already
/// breaking it, is a failure, not a not-exercised verdict the scenario may
/// accept: the lead's PET of 1.2 s misses 1.5 s though three crossings are
/// needed and two were seen; no road user is ever flagged (no message reaches
/// the ego), so none can lead by 1 s though five are needed and three were
/// seen. A check all of whose two road users hold (PET ≥ 1 s) stays not
/// exercised.
#[test]
fn a_violation_seen_among_too_few_road_users_fails() {
    let tmp = temp_dir();
    let text = read(&root().join(SCENE));
    let (head, _) = text.split_once("requirements:\n").unwrap();
    let file = tmp.path().join("too-few.yaml");
    let accept = "    accept_not_exercised: Too few road users in this short scene.\n";
    let requirements = [
        ("PET-MIN3", "{ per_object: pet, at_least: 1.5, min_samples: 3 }"),
        ("LEAD-MIN5", "{ per_object: warning_lead, at_least: 1, min_samples: 5 }"),
        ("PET-HOLDS", "{ per_object: pet, at_least: 1, min_samples: 3 }"),
    ]
    .map(|(id, check)| format!("  - id: {id}\n    text: Judged.\n    check: {check}\n{accept}"))
    .concat();
    std::fs::write(&file, format!("{head}requirements:\n{requirements}")).unwrap();
    let out = tmp.path().join("out");
    let run = sightline(["run", arg(&file), "--out", arg(&out)]);
    run.assert_exit(1);
    assert!(
        run.stdout.starts_with(&format!(
            "FAIL {}: 0 of 3 requirements hold over 1 sweep point (fail: PET-MIN3, LEAD-MIN5; not exercised: \
             PET-HOLDS (1 accepted))",
            file.display()
        )),
        "{run}"
    );
    let results = read_json(&out.join("results.json"));
    let (status, value, n) = verdict(&results, "PET-MIN3");
    assert_eq!((status.as_str(), n), ("fail", Some(2)));
    assert!((value.unwrap() - 1.2).abs() < 1e-9, "{value:?}");
    assert_eq!(verdict(&results, "LEAD-MIN5"), ("fail".into(), None, Some(3)));
    assert!(
        requirement(&results, "LEAD-MIN5")["message"]
            .as_str()
            .unwrap()
            .starts_with("3 of 3 relevant road users had no warning_lead (never flagged: lead, crossing, walker); a violation seen"),
        "{results}"
    );
    assert_eq!(verdict(&results, "PET-HOLDS"), ("not_exercised".into(), None, Some(2)));
}

/// A road user moving in a straight line at constant speed.
#[derive(Clone, Copy)]
struct User {
    kind: &'static str,
    at: [f64; 2],
    heading_deg: f64,
    speed: f64,
}

impl User {
    fn car(at: [f64; 2], heading_deg: f64, speed: f64) -> Self {
        Self {
            kind: "car",
            at,
            heading_deg,
            speed,
        }
    }

    /// Its size, the defaults of its kind.
    fn size(self) -> [f64; 2] {
        if self.kind == "pedestrian" {
            [0.6, 0.6]
        } else {
            [4.5, 1.8]
        }
    }

    /// The case's description of it.
    fn json(self) -> Value {
        let [length, width] = self.size();
        json!({
            "x": self.at[0], "y": self.at[1], "heading_deg": self.heading_deg,
            "speed": self.speed, "length": length, "width": width,
        })
    }

    /// A straight way 400 m long from where it starts, along its heading.
    fn way(self) -> String {
        let rad = self.heading_deg.to_radians();
        let end = [self.at[0] + 400.0 * rad.cos(), self.at[1] + 400.0 * rad.sin()];
        format!("[[{}, {}], [{}, {}]]", self.at[0], self.at[1], end[0], end[1])
    }
}

/// Steps of 0.1 s.
const DT: f64 = 0.1;

/// A two-road-user scene: `steps` steps of the ego and `other`, and the
/// CRIME measures to run on it.
struct Case {
    name: &'static str,
    ego: User,
    other: User,
    steps: u32,
    measures: &'static [&'static str],
}

impl Case {
    /// The scene as a sightline scenario: each on its own straight way at its
    /// speed from the start, vehicles ignoring each other, and a roadside unit
    /// that senses nothing, so that no message slows the ego down.
    fn scenario(&self) -> String {
        let speed_limit = self.ego.speed.max(self.other.speed) + 1.0;
        let other = match self.other.kind {
            "pedestrian" => format!(
                "{{ id: other, kind: pedestrian, path: {}, speed: {{ target: {} }} }}",
                self.other.way(),
                self.other.speed
            ),
            kind => format!(
                "{{ id: other, kind: {kind}, route: [theirs], speed: {{ target: {} }} }}",
                self.other.speed
            ),
        };
        format!(
            "sightline: 1\n\
             name: {name}\n\
             seed: 1\n\
             time: {{ duration: {duration}, step: {DT} }}\n\
             roads:\n  \
               - {{ id: mine, polyline: {mine}, speed_limit: {speed_limit} }}\n  \
               - {{ id: theirs, polyline: {theirs}, speed_limit: {speed_limit} }}\n\
             sensor_models:\n  eye: {{ range: 30 }}\n  rsu_eye: {{ range: 1 }}\n\
             agents:\n  \
               - {{ id: ego, kind: car, route: [mine], speed: {{ target: {ego_speed} }}, connected: true, sensors: [eye] }}\n  \
               - {{ id: rsu, kind: rsu, position: [-500, -500], sensors: [rsu_eye] }}\n  \
               - {other}\n\
             v2x: {{ channel: {{ model: ideal }} }}\n\
             semantic: {{ ego: ego }}\n\
             requirements:\n  \
               - {{ id: R1, text: Anything., check: {{ metric: objects_never_known, at_least: 0 }} }}\n",
            name = self.name,
            duration = f64::from(self.steps) * DT,
            mine = self.ego.way(),
            theirs = self.other.way(),
            ego_speed = self.ego.speed,
        )
    }

    /// The case as `tests/python/crime_case.py` reads it.
    fn json(&self) -> Value {
        json!({
            "dt": DT, "steps": self.steps, "proximity": 50,
            "ego": self.ego.json(), "other": self.other.json(), "measures": self.measures,
        })
    }

    /// The other road user's record in sightline's results.json.
    fn sightline(&self, dir: &Path) -> Value {
        let file = dir.join(format!("{}.yaml", self.name));
        std::fs::write(&file, self.scenario()).unwrap();
        let out = dir.join(self.name);
        sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(0);
        let results = read_json(&out.join("results.json"));
        let records = results["sweep"][0]["objects"]["records"].as_array().unwrap().clone();
        records
            .into_iter()
            .find(|o| o["id"] == "other")
            .unwrap_or_else(|| panic!("{}: the other road user is relevant", self.name))
    }

    /// CRIME's values on the same scene.
    fn crime(&self, python: &Path, dir: &Path) -> Value {
        let file = dir.join(format!("{}.json", self.name));
        std::fs::write(&file, self.json().to_string()).unwrap();
        let output = Command::new(python)
            .arg(root().join("tests/python/crime_case.py"))
            .arg(&file)
            .output()
            .unwrap_or_else(|e| panic!("failed to start {}: {e}", python.display()));
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            output.status.success(),
            "{}: crime_case.py failed:\n{stderr}",
            self.name
        );
        serde_json::from_slice(&output.stdout)
            .unwrap_or_else(|e| panic!("{}: crime_case.py printed no JSON ({e}):\n{stderr}", self.name))
    }
}

/// The cases, with what each compares (see the assertions below).
fn cases() -> Vec<Case> {
    // Slightly off +x: CRIME 0.4.5's a_long_req reads a lanelet heading
    // exactly +x (orientation 0) as "no projection" and returns 0.
    let east = 0.001;
    vec![
        Case {
            name: "rear-end",
            ego: User::car([0.0, 0.0], east, 12.0),
            other: User::car([30.05, 0.0], east, 8.0),
            steps: 12,
            measures: &["ttc", "ttc_star", "a_long_req"],
        },
        Case {
            name: "pulling-away",
            ego: User::car([0.0, 0.0], east, 8.0),
            other: User::car([30.05, 0.0], east, 12.0),
            steps: 5,
            measures: &["ttc", "a_long_req"],
        },
        Case {
            name: "head-on",
            ego: User::car([0.0, 0.0], 0.0, 10.0),
            other: User::car([60.05, 0.0], 180.0, 5.0),
            steps: 10,
            measures: &["ttc", "ttc_star"],
        },
        Case {
            name: "right-angles",
            ego: User::car([-0.25, 0.0], 0.0, 10.0),
            other: User::car([20.0, -12.05], 90.0, 5.0),
            steps: 8,
            measures: &["ttc_star", "a_long_req"],
        },
        Case {
            name: "corner-first",
            ego: User::car([0.0, 0.0], 0.0, 8.0),
            other: User::car([40.0, 6.0], 200.0, 6.0),
            steps: 10,
            measures: &["ttc_star"],
        },
        Case {
            name: "pet-crossing",
            ego: User::car([-0.25, 0.0], 0.0, 10.0),
            other: User::car([20.0, -25.25], 90.0, 5.0),
            steps: 80,
            measures: &["pet"],
        },
        Case {
            name: "pet-pedestrian",
            ego: User::car([-0.25, 0.0], 0.0, 10.0),
            other: User {
                kind: "pedestrian",
                at: [30.0, -1.1],
                heading_deg: 90.0,
                speed: 1.5,
            },
            steps: 60,
            measures: &["pet"],
        },
    ]
}

/// CRIME's rounding: TTC and a_long_req to 0.01, PET to 0.0001.
const HUNDREDTH: f64 = 0.005 + 1e-9;

/// sightline against commonroad-crime, case by case:
/// - TTC*: CRIME's first colliding time step of the two boxes along their
///   trajectories, so our exact TTC ≤ TTC* < TTC + one step;
/// - CRIME's lane-based TTC (headway along the lanelet over the speed
///   difference) equals ours behind a slower car, to its rounding; head on it
///   takes the oncoming car's speed as if it drove the ego's way (the speed
///   times the cosine of the lane's orientation), so it is (10 + 5) / (10 − 5)
///   = 3 times ours;
/// - a_long_req, the review's DRAC, is −DRAC behind a slower car; for a
///   road user off the ego's lanelet CRIME gives 0, ours the deceleration
///   that stops the ego short of the contact; behind a faster car, pulling
///   away, CRIME still gives −v_rel² / (2 gap), ours none (no collision);
/// - PET: CRIME takes the entry one step early and the exit at the first
///   step out, so on the same sampled footprints its PET is ours − 2 steps.
///
/// Skipped locally unless `SIGHTLINE_CRIME_PYTHON` names a Python with
/// commonroad-crime; with `CI` set a missing one fails the test.
#[test]
fn commonroad_crime_agrees_where_the_definitions_match() {
    let Some(python) = tool(PYTHON_VAR, "a Python with commonroad-crime 0.4.5") else {
        return;
    };
    let python = python.as_path();
    let tmp = temp_dir();
    for case in cases() {
        let ours = case.sightline(tmp.path());
        let crime = case.crime(python, tmp.path());
        let name = case.name;
        let value = |v: &Value, key: &str| v[key].as_f64();
        let ttc = value(&ours, "min_ttc");
        if let Some(star) = value(&crime, "ttc_star") {
            let ttc = ttc.unwrap_or_else(|| panic!("{name}: CRIME's TTC* is {star} s, ours none"));
            assert!(
                ttc <= star + 1e-9 && star < ttc + DT + 1e-9,
                "{name}: TTC {ttc} s, CRIME's TTC* {star} s"
            );
        } else if case.measures.contains(&"ttc_star") {
            assert_eq!(ttc, None, "{name}: CRIME finds no collision");
        }
        match (name, value(&crime, "ttc")) {
            ("head-on", Some(lane)) => {
                let ttc = ttc.unwrap();
                assert!((lane - 3.0 * ttc).abs() < HUNDREDTH, "{name}: {lane} vs 3 × {ttc}");
            }
            (_, Some(lane)) => assert!((lane - ttc.unwrap()).abs() < HUNDREDTH, "{name}: {lane} vs {ttc:?}"),
            (_, None) if case.measures.contains(&"ttc") => {
                assert_eq!(ttc, None, "{name}: CRIME's TTC is infinite");
            }
            (_, None) => {}
        }
        if let Some(a_req) = value(&crime, "a_long_req") {
            let drac = value(&ours, "max_drac");
            let expected = match name {
                "right-angles" => 0.0,
                // v_rel² / (2 gap) at the first step, the gap 30.05 − 4.5 m.
                "pulling-away" => {
                    assert_eq!(drac, None, "{name}: the ego does not close");
                    16.0 / (2.0 * 25.55)
                }
                _ => drac.unwrap_or_else(|| panic!("{name}: no DRAC")),
            };
            assert!(
                (a_req + expected).abs() < HUNDREDTH,
                "{name}: a_long_req {a_req}, DRAC {drac:?}"
            );
        }
        if case.measures.contains(&"pet") {
            let pet = value(&ours, "pet").unwrap_or_else(|| panic!("{name}: no PET"));
            let theirs = value(&crime, "pet").unwrap_or_else(|| panic!("{name}: CRIME's PET is infinite"));
            assert!(
                (theirs - (pet - 2.0 * DT)).abs() < 1e-4 + 1e-9,
                "{name}: PET {pet}, CRIME's {theirs}"
            );
            assert_eq!(ttc, None, "{name}: a PET case never collides");
        }
    }
}
