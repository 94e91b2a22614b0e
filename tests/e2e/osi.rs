//! `sightline run --osi` (issue 21, parts 1 and 4): osi.mcap follows ASAM's
//! OSI multi-channel trace convention (read with the MCAP library and decoded
//! with the prost types), its SensorViews carry the visibility of a scene
//! counted by hand, its bytes do not depend on the thread count, a field
//! experiment is refused, and, when `SIGHTLINE_OSI_PYTHON` names a Python with
//! ASAM's tools (ci/tools.sh sets it; with `CI` set the tests fail rather than
//! skip without it), ASAM's trace reader and the official bindings read the
//! trace and the vendored descriptors are the bindings' own.
// See: issue 21, "OSI out".

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use prost::Message;
use serde_json::json;
use sightline_osi::osi3;

use crate::support::{SMALL_FIELD, arg, root, sightline, temp_dir, tool};

/// Names a Python with osi-python and asam-osi-utilities.
const PYTHON_VAR: &str = "SIGHTLINE_OSI_PYTHON";

const TRACE: &str = "osi.mcap";

/// The hand-counted scene of tests/e2e/visibility.rs: `cav` (agent 1, OSI id
/// 2) at (0, 20) facing east sees `near` (id 3) wholly, `far` (id 4) not at
/// all (behind `near`) and `walker` (id 5) half; the ego (id 1), 30 m south
/// behind a wall, sees nothing. One step of 0.1 s, at time 0.
const SCENE: &str = include_str!("../fixtures/templates/wall-and-cooperator.yaml.in");

const OTHERS: &str = "  - { id: near, kind: car, route: [we], start: { offset: 35 }, speed: { target: 0 } }
  - { id: far, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 } }
  - { id: walker, kind: pedestrian, path: [[11, 23.6], [12, 23.6]], speed: { target: 0 } }";

const REQUIREMENTS: &str = "requirements:
  - { id: VIS-HALF, text: Half of what is in view shows., check: { metric: mean_visible_fraction, at_least: 0.45 } }
";

/// The Python with ASAM's OSI tools (see [`tool`]).
fn python() -> Option<PathBuf> {
    tool(PYTHON_VAR, "a Python with osi-python and asam-osi-utilities")
}

/// Runs the hand-counted scene with `--osi` into `dir` and returns the trace.
fn scene_trace(dir: &Path) -> Vec<u8> {
    let (file, out) = (dir.join("scene.yaml"), dir.join("evidence"));
    std::fs::write(&file, SCENE.replace("{others}", OTHERS).replace("{rest}", REQUIREMENTS)).unwrap();
    sightline(["run", arg(&file), "--out", arg(&out), "--osi"]).assert_exit(0);
    assert!(out.join("run.mcap").is_file(), "--osi implies --record");
    let report = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        report.contains(" --seed 1 --osi</"),
        "the report's command to reproduce the run asks for the trace"
    );
    let trace = std::fs::read(out.join(TRACE)).expect("osi.mcap is written");
    // results.json and the report name the trace by its hash, as the recording.
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let sha = crate::support::sha256_hex(&trace);
    assert_eq!(
        results["recording"]["osi_trace"],
        json!({ "file": TRACE, "sha256": sha })
    );
    assert!(
        report.contains(&format!("{TRACE} (the same point), SHA-256 {sha}")),
        "the report lacks the trace's hash"
    );
    trace
}

/// Every message of `topic`, in the order written: its publish and log
/// times and its bytes.
fn messages(trace: &[u8], topic: &str) -> Vec<(u64, u64, Vec<u8>)> {
    mcap::MessageStream::new(trace)
        .expect("the trace starts with the MCAP magic")
        .map(|m| m.expect("every message reads"))
        .filter(|m| m.channel.topic == topic)
        .map(|m| (m.publish_time, m.log_time, m.data.into_owned()))
        .collect()
}

fn nanos(stamp: Option<osi3::Timestamp>) -> u64 {
    let stamp = stamp.expect("a timestamp");
    stamp.seconds.unwrap() as u64 * 1_000_000_000 + u64::from(stamp.nanos.unwrap())
}

/// The file as OSI's convention requires: an indexed MCAP file with lz4
/// chunks, the `net.asam.osi.trace` metadata, a `protobuf` schema per
/// message type holding the descriptor set, `protobuf` channels with their
/// versions, publish time = log time = the message's timestamp.
#[test]
fn the_trace_follows_asams_multi_channel_convention() {
    let tmp = temp_dir();
    let trace = scene_trace(tmp.path());
    let summary = mcap::Summary::read(&trace).unwrap().expect("a summary section");
    assert!(!summary.chunk_indexes.is_empty(), "an indexed file");
    for chunk in &summary.chunk_indexes {
        assert_eq!(chunk.compression, "lz4");
    }
    let descriptors = std::fs::read(root().join("osi/proto/osi3.fds")).unwrap();
    let mut schemas: Vec<&str> = summary.schemas.values().map(|s| &*s.name).collect();
    schemas.sort_unstable();
    assert_eq!(schemas, ["osi3.GroundTruth", "osi3.SensorView"]);
    for schema in summary.schemas.values() {
        assert_eq!(schema.encoding, "protobuf");
        assert!(
            *schema.data == descriptors[..],
            "{}: the vendored descriptor set",
            schema.name
        );
    }
    let channels: BTreeMap<&str, (&str, u64)> = summary
        .channels
        .values()
        .map(|c| {
            assert_eq!(c.message_encoding, "protobuf", "{}", c.topic);
            for key in ["osi_version", "protobuf_version"] {
                let key = format!("net.asam.osi.trace.channel.{key}");
                assert!(c.metadata.contains_key(&key), "{}: {key}", c.topic);
            }
            assert_eq!(c.metadata["net.asam.osi.trace.channel.osi_version"], "3.8.0");
            let count = summary.stats.as_ref().unwrap().channel_message_counts[&c.id];
            (&*c.topic, (&*c.schema.as_ref().unwrap().name, count))
        })
        .collect();
    assert_eq!(
        channels,
        BTreeMap::from([
            ("GroundTruth", ("osi3.GroundTruth", 1)),
            ("ego.SensorView[0]", ("osi3.SensorView", 1)),
            ("cav.SensorView[0]", ("osi3.SensorView", 1)),
        ])
    );
    let metadata: Vec<_> = mcap::read::LinearReader::new(&trace)
        .unwrap()
        .filter_map(|record| match record.unwrap() {
            mcap::records::Record::Metadata(m) => Some(m),
            _ => None,
        })
        .collect();
    assert_eq!(metadata.len(), 1, "exactly one metadata record");
    assert_eq!(metadata[0].name, "net.asam.osi.trace");
    let data = &metadata[0].metadata;
    for (key, value) in [
        ("version", "3.8.0"),
        ("min_osi_version", "3.8.0"),
        ("max_osi_version", "3.8.0"),
    ] {
        assert_eq!(data[key], value, "{key}");
    }
    assert!(data.contains_key("min_protobuf_version") && data.contains_key("max_protobuf_version"));
    // No time.start: step 0 is the recording clock's default, 2000-01-01.
    assert_eq!(data["zero_time"], "2000-01-01T00:00:00Z");
    for (publish, log, bytes) in messages(&trace, "GroundTruth") {
        let truth = osi3::GroundTruth::decode(bytes.as_slice()).unwrap();
        assert_eq!((publish, log), (nanos(truth.timestamp), nanos(truth.timestamp)));
    }
    let times: Vec<u64> = messages(&trace, "cav.SensorView[0]").iter().map(|m| m.0).collect();
    assert_eq!(times, [0]);
}

/// The ground truth places each road user as the scene does, and cav's
/// SensorView carries the visibility counted by hand; the ego's, none.
#[test]
fn a_sensor_view_carries_the_visibility_counted_by_hand() {
    let tmp = temp_dir();
    let trace = scene_trace(tmp.path());
    let (_, _, bytes) = &messages(&trace, "GroundTruth")[0];
    let truth = osi3::GroundTruth::decode(bytes.as_slice()).unwrap();
    assert_eq!(truth.host_vehicle_id.unwrap().value, Some(1), "the ego is the host");
    let near = &truth.moving_object[2];
    assert_eq!(near.id.unwrap().value, Some(3));
    assert_eq!(near.source_reference[0].identifier, ["near"]);
    let base = near.base.as_ref().unwrap();
    let position = base.position.unwrap();
    // Offset 35 m along `we` from (-30, 20); a car is 1.5 m high, its box on the ground.
    assert_eq!(
        (position.x, position.y, position.z),
        (Some(5.0), Some(20.0), Some(0.75))
    );
    assert_eq!(base.orientation.unwrap().yaw, Some(0.0));
    assert_eq!(near.r#type, Some(osi3::moving_object::Type::Vehicle as i32));
    let walker = &truth.moving_object[4];
    assert_eq!(walker.r#type, Some(osi3::moving_object::Type::Pedestrian as i32));

    let visibility = |topic: &str| -> BTreeMap<u64, Vec<Vec<String>>> {
        let (_, _, bytes) = &messages(&trace, topic)[0];
        let view = osi3::SensorView::decode(bytes.as_slice()).unwrap();
        assert_eq!(view.sensor_id.unwrap().value, Some(0));
        let truth = view.global_ground_truth.unwrap();
        assert_eq!(truth.moving_object.len(), 5, "{topic}: the whole ground truth");
        assert_eq!(truth.host_vehicle_id, view.host_vehicle_id);
        truth
            .moving_object
            .iter()
            .map(|o| {
                let seen = o
                    .source_reference
                    .iter()
                    .filter(|r| r.r#type.as_deref() == Some("sightline.visibility"));
                (
                    o.id.unwrap().value.unwrap(),
                    seen.map(|r| r.identifier.clone()).collect(),
                )
            })
            .collect()
    };
    let none: Vec<Vec<String>> = Vec::new();
    let seen = |class: &str, fraction: &str| vec![vec![class.to_string(), fraction.to_string()]];
    assert_eq!(
        visibility("cav.SensorView[0]"),
        BTreeMap::from([
            (1, none.clone()),
            (2, none.clone()),
            (3, seen("los", "1")),
            (4, seen("nlos_dynamic", "0")),
            (5, seen("los", "0.5")),
        ])
    );
    assert!(visibility("ego.SensorView[0]").values().all(Vec::is_empty));
}

/// The same scenario and seed give the same trace whatever the thread count.
#[test]
fn the_trace_is_the_same_whatever_the_thread_count() {
    let tmp = temp_dir();
    let traces: Vec<Vec<u8>> = ["1", "3"]
        .iter()
        .map(|jobs| {
            let out = tmp.path().join(jobs);
            let scenario = "tests/fixtures/valid/small-junction.yaml";
            sightline(["run", scenario, "--out", arg(&out), "--osi", "--jobs", jobs]).assert_exit(0);
            std::fs::read(out.join(TRACE)).unwrap()
        })
        .collect();
    assert!(messages(&traces[0], "GroundTruth").len() > 1);
    assert!(traces[0] == traces[1], "osi.mcap differs between --jobs 1 and --jobs 3");
}

/// A roadside unit is a stationary object, and its sensor's view has no
/// host vehicle (small-junction: ego, cav, rsu, walker; the rsu OSI id 3).
#[test]
fn a_roadside_unit_is_a_stationary_object_without_a_host_vehicle() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline([
        "run",
        "tests/fixtures/valid/small-junction.yaml",
        "--out",
        arg(&out),
        "--osi",
    ])
    .assert_exit(0);
    let trace = std::fs::read(out.join(TRACE)).unwrap();
    let (_, _, bytes) = &messages(&trace, "GroundTruth")[0];
    let truth = osi3::GroundTruth::decode(bytes.as_slice()).unwrap();
    let ids = |objects: Vec<Option<osi3::Identifier>>| -> Vec<u64> {
        objects.into_iter().map(|id| id.unwrap().value.unwrap()).collect()
    };
    assert_eq!(ids(truth.moving_object.iter().map(|o| o.id).collect()), [1, 2, 4]);
    assert_eq!(ids(truth.stationary_object.iter().map(|o| o.id).collect()), [3]);
    let rsu = &truth.stationary_object[0];
    assert_eq!(rsu.source_reference[0].identifier, ["rsu"]);
    let position = rsu.base.as_ref().unwrap().position.unwrap();
    assert_eq!(
        (position.x, position.y, position.z),
        (Some(12.0), Some(12.0), Some(2.5))
    );
    let (_, _, bytes) = &messages(&trace, "rsu.SensorView[0]")[0];
    let view = osi3::SensorView::decode(bytes.as_slice()).unwrap();
    assert_eq!(view.host_vehicle_id, None);
    assert_eq!(view.global_ground_truth.unwrap().host_vehicle_id, None);
    let (_, _, bytes) = &messages(&trace, "cav.SensorView[0]")[0];
    let view = osi3::SensorView::decode(bytes.as_slice()).unwrap();
    assert_eq!(view.host_vehicle_id.unwrap().value, Some(2));
}

/// A semantic world reports no sightings: its trace is the ground truth of
/// each of its 80 steps (8 s of 0.1 s), and a road user that leaves the scene
/// leaves it (tests/fixtures/valid/criticality.yaml: ego, rsu, lead, crossing,
/// walker; `lead` leaves its road, which ends at x = 50.3, at 4.05 s).
#[test]
fn a_semantic_world_traces_its_ground_truth() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    sightline([
        "run",
        "tests/fixtures/valid/criticality.yaml",
        "--out",
        arg(&out),
        "--osi",
    ])
    .assert_exit(0);
    let trace = std::fs::read(out.join(TRACE)).unwrap();
    let summary = mcap::Summary::read(&trace).unwrap().unwrap();
    let topics: Vec<&str> = summary.channels.values().map(|c| &*c.topic).collect();
    assert_eq!(topics, ["GroundTruth"]);
    let steps = messages(&trace, "GroundTruth");
    assert_eq!(steps.len(), 80);
    let ids_at = |step: usize| -> (Vec<u64>, Vec<u64>) {
        let truth = osi3::GroundTruth::decode(steps[step].2.as_slice()).unwrap();
        assert_eq!(nanos(truth.timestamp), step as u64 * 100_000_000);
        assert_eq!(truth.host_vehicle_id.unwrap().value, Some(1));
        let ids = |ids: Vec<Option<osi3::Identifier>>| ids.into_iter().map(|id| id.unwrap().value.unwrap()).collect();
        (
            ids(truth.moving_object.iter().map(|o| o.id).collect()),
            ids(truth.stationary_object.iter().map(|o| o.id).collect()),
        )
    };
    assert_eq!(ids_at(40), (vec![1, 3, 4, 5], vec![2]), "at 4.0 s");
    assert_eq!(ids_at(41), (vec![1, 4, 5], vec![2]), "at 4.1 s, lead has left");
    assert_eq!(ids_at(79), (vec![1, 4, 5], vec![2]));
}

/// A world of 100 cooperating cars, one sensor each, for 20 000 steps: each
/// of the 101 views of a step repeats the 100 cars, 2.02e8 objects (printed
/// to one decimal, 2e8), over the resource model's limit of 1e8 for an OSI
/// trace. Valid without `--osi`;
/// with it, refused at the agents before anything runs.
#[test]
fn a_trace_over_the_resource_model_is_refused_before_the_run() {
    // 600 parked cars and the ego, whose one sensor cooperates, over 100 000
    // steps: 6.01e7 agent-steps, 1.2e8 objects in the trace (each agent-step
    // in the ground truth and in the one sensor's view), within every other
    // limit (the fans the sensor casts at the agents: 6.01e8 rays).
    let cars: String = (1..601)
        .map(|i| {
            format!("  - {{ id: c{i}, kind: car, route: [we], start: {{ offset: {i} }}, speed: {{ target: 0 }} }}\n")
        })
        .collect();
    let scenario = format!(
        "sightline: 1
name: Many parked cars
seed: 1
time: {{ duration: 10000, step: 0.1 }}
grid: {{ origin: [-10, -10], size: [1020, 20], cell: 1 }}
roads:
  - {{ id: we, polyline: [[0, 0], [1000, 0]], speed_limit: 10 }}
sensor_models: {{ lidar: {{ range: 5, fov_deg: 10, ray_spacing_deg: 1 }} }}
agents:
  - {{ id: ego, kind: car, route: [we], speed: {{ target: 0 }}, connected: true, sensors: [lidar] }}
{cars}perception: {{ ego: ego }}
fusion: {{ method: bayes }}
requirements:
  - {{ id: REC, text: Recall., check: {{ metric: occupied_recall, at_least: 0.5 }} }}
"
    );
    let tmp = temp_dir();
    let (file, out) = (tmp.path().join("many.yaml"), tmp.path().join("evidence"));
    std::fs::write(&file, scenario).unwrap();
    sightline(["check", arg(&file)]).assert_exit(0);
    let run = sightline(["run", arg(&file), "--out", arg(&out), "--osi"]);
    run.assert_exit(2);
    assert_eq!(
        run.stderr,
        format!(
            "{}:10:3: error: agents: 1.2e8 objects in the OSI trace of a point (agents × steps × (1 + the \
             cooperating agents' sensors)) exceed the limit of 1e8; run without --osi, or use fewer agents or \
             cooperating sensors, or a shorter run\n",
            file.display()
        )
    );
    assert!(!out.exists());
}

/// A field experiment has no road users to trace: refused before anything
/// runs, nothing written.
#[test]
fn a_field_experiment_has_no_osi_trace() {
    let tmp = temp_dir();
    let out = tmp.path().join("evidence");
    let run = sightline(["run", SMALL_FIELD, "--out", arg(&out), "--osi"]);
    run.assert_exit(2);
    assert_eq!(
        run.stderr,
        format!(
            "{SMALL_FIELD}: error: --osi traces road users, and a field experiment has none: only a world (agents) has an OSI trace\n"
        )
    );
    assert!(!out.exists());
}

/// A trace is one point's timeline: `--osi` with every point recorded is
/// refused before anything runs, nothing written.
#[test]
fn every_point_recorded_has_no_osi_trace() {
    let tmp = temp_dir();
    let (file, out) = (tmp.path().join("scene.yaml"), tmp.path().join("evidence"));
    let rest = format!("{REQUIREMENTS}record: {{ points: all }}\n");
    std::fs::write(&file, SCENE.replace("{others}", OTHERS).replace("{rest}", &rest)).unwrap();
    let run = sightline(["run", arg(&file), "--out", arg(&out), "--osi"]);
    run.assert_exit(2);
    assert!(
        run.stderr
            .contains("error: --osi traces one sweep point, and `record.points: all` records every point"),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
}

/// The trace is part of the evidence set: a later run without `--osi` into
/// the same folder leaves no trace of an earlier point behind.
#[test]
fn a_later_run_without_osi_leaves_no_stale_trace() {
    let tmp = temp_dir();
    scene_trace(tmp.path());
    let (file, out) = (tmp.path().join("scene.yaml"), tmp.path().join("evidence"));
    sightline(["run", arg(&file), "--out", arg(&out), "--record"]).assert_exit(0);
    assert!(out.join("run.mcap").is_file());
    assert!(!out.join(TRACE).exists(), "osi.mcap of the earlier run is left");
    let results = std::fs::read_to_string(out.join("results.json")).unwrap();
    assert!(!results.contains("osi_trace"), "results.json names a trace not written");
}

/// What tests/python/read_osi.py, run by `python`, reads of the trace at `path`.
#[track_caller]
fn read_with_asams_tools(python: &Path, path: &Path) -> serde_json::Value {
    let output = Command::new(python)
        .arg(root().join("tests/python/read_osi.py"))
        .arg(path)
        .output()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", python.display()));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "read_osi.py failed on {}:\n{stderr}",
        path.display()
    );
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("read_osi.py printed no JSON ({e}):\n{stderr}"))
}

/// ASAM's trace reader reads every message, decoding with the official
/// bindings and with the schema the trace embeds; the bindings serialize
/// every message back to sightline's bytes; they read the visibility the
/// Rust types do. The same for a junction with a roadside unit, 60 steps.
#[test]
fn asams_tools_read_the_trace() {
    let Some(python) = python() else { return };
    let tmp = temp_dir();
    scene_trace(tmp.path());
    let read = read_with_asams_tools(&python, &tmp.path().join("evidence").join(TRACE));
    let counts = json!({
        "GroundTruth GroundTruth": 1,
        "cav.SensorView[0] SensorView": 1,
        "ego.SensorView[0] SensorView": 1,
    });
    assert_eq!(read["readers"]["precompiled"], counts);
    assert_eq!(read["readers"]["mcap-contained"], counts);
    assert_eq!(read["round_trip"], json!({ "checked": 3, "problems": [] }));
    assert_eq!(read["chunks"]["compressions"], json!(["lz4"]));
    assert_eq!(read["metadata"][0]["name"], "net.asam.osi.trace");
    let descriptors = std::fs::read(root().join("osi/proto/osi3.fds")).unwrap();
    let hex: String = descriptors.iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(read["schemas"]["osi3.SensorView"]["data"], hex.as_str());
    assert_eq!(
        read["visibility"]["cav.SensorView[0]"],
        json!({ "1": [], "2": [], "3": [["los", "1"]], "4": [["nlos_dynamic", "0"]], "5": [["los", "0.5"]] })
    );

    let out = tmp.path().join("junction");
    sightline([
        "run",
        "tests/fixtures/valid/small-junction.yaml",
        "--out",
        arg(&out),
        "--osi",
    ])
    .assert_exit(0);
    let read = read_with_asams_tools(&python, &out.join(TRACE));
    let counts: serde_json::Value = [
        "GroundTruth GroundTruth",
        "ego.SensorView[0] SensorView",
        "cav.SensorView[0] SensorView",
        "rsu.SensorView[0] SensorView",
    ]
    .into_iter()
    .map(|key| (key.to_string(), json!(60)))
    .collect::<serde_json::Map<_, _>>()
    .into();
    assert_eq!(read["readers"]["precompiled"], counts);
    assert_eq!(read["readers"]["mcap-contained"], counts);
    assert_eq!(read["round_trip"], json!({ "checked": 240, "problems": [] }));
}

/// The vendored descriptor set is the one the official bindings embed
/// (osi/proto/extract.py gathers it from them).
#[test]
fn the_descriptors_are_the_official_bindings() {
    let Some(python) = python() else { return };
    let output = Command::new(&python)
        .arg(root().join("osi/proto/extract.py"))
        .output()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", python.display()));
    assert!(
        output.status.success(),
        "extract.py failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let vendored = std::fs::read(root().join("osi/proto/osi3.fds")).unwrap();
    assert!(
        output.stdout == vendored,
        "osi/proto/osi3.fds is not what osi-python embeds; see osi/proto/README.md"
    );
}
