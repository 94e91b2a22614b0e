//! run.mcap and `sightline replay` (issue 6 §2, §3, §5): the recording's
//! channels, schemas and message counts (read with the MCAP library, and with
//! the official Python reader when `SIGHTLINE_MCAP_PYTHON` names one), its size,
//! its bytes whatever the thread count, replay's verdicts on every bundled
//! scenario, and damaged or mismatched recordings refused with exit 2.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use crate::bundled::{Bundled, every_run, roundabout_run, sumo_grid_run};
use crate::support::{
    FAILING, RECORDING, arg, files_under, normalise_execution, read, read_json, root, short_roundabout, sightline,
    temp_dir, tool,
};

/// Names a Python that has the official `mcap` package; `.ci/run` sets it.
const PYTHON_VAR: &str = "SIGHTLINE_MCAP_PYTHON";

/// The bundled roundabout's recording at default settings must stay under this.
const SIZE_LIMIT: usize = 20 * 1024 * 1024;

/// A channel as the MCAP library reads it: its schema's name and its messages.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Channel {
    pub(crate) schema: String,
    pub(crate) count: u64,
}

/// Every channel of a recording by topic, read from its summary by the MCAP
/// library (not by sightline's reader).
#[track_caller]
pub(crate) fn channels(recording: &[u8]) -> BTreeMap<String, Channel> {
    let summary = mcap::Summary::read(recording)
        .expect("the recording has a valid summary")
        .expect("the recording has a summary");
    let counts = summary
        .stats
        .expect("the summary has statistics")
        .channel_message_counts;
    summary
        .channels
        .values()
        .map(|channel| {
            let schema = channel.schema.as_ref().expect("every channel has a schema");
            assert_eq!(schema.encoding, "jsonschema", "{}", channel.topic);
            assert_eq!(channel.message_encoding, "json", "{}", channel.topic);
            let count = counts.get(&channel.id).copied().unwrap_or(0);
            (
                channel.topic.clone(),
                Channel {
                    schema: schema.name.to_string(),
                    count,
                },
            )
        })
        .collect()
}

/// Every message on `topic`, decoded as JSON, in the order written.
pub(crate) fn messages(recording: &[u8], topic: &str) -> Vec<serde_json::Value> {
    mcap::MessageStream::new(recording)
        .expect("the recording starts with the MCAP magic")
        .map(|m| m.expect("every message reads"))
        .filter(|m| m.channel.topic == topic)
        .map(|m| serde_json::from_slice(&m.data).expect("every message is JSON"))
        .collect()
}

/// The expected channels: (topic, schema, count).
#[track_caller]
fn assert_channels(actual: BTreeMap<String, Channel>, expected: &[(&str, &str, u64)]) {
    let expected: BTreeMap<String, Channel> = expected
        .iter()
        .map(|&(topic, schema, count)| {
            (
                topic.to_string(),
                Channel {
                    schema: schema.into(),
                    count,
                },
            )
        })
        .collect();
    assert_eq!(actual, expected);
}

/// The bundled roundabout at default settings records the worst point of its
/// first failing requirement (#18) for 30 s at 10 Hz, a fused grid a second,
/// the frame tree and each cooperating vehicle's detections; far under 20 MB.
#[test]
fn bundled_roundabout_recording_has_foxglove_channels_and_the_steps() {
    let run = roundabout_run();
    let first_failing = run.results["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["fails_run"] == true)
        .expect("the roundabout fails a requirement");
    // Its decisive point: the failing one with the smallest margin.
    let index = first_failing["point"].as_u64().unwrap() as usize;
    assert_eq!(run.results["recording"]["point"].as_u64(), Some(index as u64));
    let point = &run.results["sweep"][index];
    assert_eq!(run.results["recording"]["label"], point["label"]);
    // The ego is in the scene at every one of the 300 steps, so each is measured.
    assert_eq!(point["counts"]["steps"], 300);
    let recording = &run.recording;
    assert!(
        recording.len() < SIZE_LIMIT,
        "the recording is {} bytes",
        recording.len()
    );
    let requirements = run.results["requirements"].as_array().unwrap().len() as u64;
    // One outcome per distinct configuration: the first six sweeps' 22 rows
    // share one; the seventh adds two.
    let points = 19;
    let mut channels = channels(recording);
    // Each cooperating vehicle's detections, at the steps it is in the scene.
    let detections: Vec<String> = channels
        .keys()
        .filter(|t| t.starts_with("/perception/") && t.ends_with("/detections"))
        .cloned()
        .collect();
    assert!(
        detections.len() > 1,
        "the failing point has cooperating vehicles: {detections:?}"
    );
    for topic in detections {
        let channel = channels.remove(&topic).unwrap();
        assert_eq!(channel.schema, "foxglove.SceneUpdate");
        assert!((1..=300).contains(&channel.count), "{topic}: {}", channel.count);
    }
    assert_channels(
        channels,
        &[
            ("/sightline/scenario", "sightline.Scenario", 1),
            ("/scene/map", "foxglove.SceneUpdate", 1),
            ("/tf", "foxglove.FrameTransforms", 300),
            ("/sightline/speeds", "sightline.Speeds", 300),
            // At the first step, then each time a vehicle enters or leaves.
            ("/scene/agents", "foxglove.SceneUpdate", 11),
            // At the first step, then each time a vehicle with sensors enters or leaves.
            ("/scene/fields_of_view", "foxglove.SceneUpdate", 5),
            // Steps 0, 10, …, 290.
            ("/fusion/grid", "foxglove.Grid", 30),
            ("/sightline/signals", "sightline.Signals", 300),
            // The requirements at the point whose metrics sum over the steps.
            ("/sightline/requirements", "sightline.RequirementSignals", 300),
            ("/sightline/outcome", "sightline.Outcome", points),
            ("/sightline/verdicts", "sightline.Verdict", requirements),
            ("/log", "foxglove.Log", requirements),
        ],
    );
    // Timestamps count from the default epoch, 2000-01-01T00:00:00Z: the map at
    // the epoch, step k at epoch + k · 0.1 s.
    let epoch = 946_684_800_000_000_000_u64;
    let times: Vec<u64> = mcap::MessageStream::new(recording)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| m.channel.topic == "/tf")
        .map(|m| m.log_time)
        .collect();
    assert_eq!(times.first(), Some(&epoch));
    assert_eq!(times.get(10), Some(&(epoch + 1_000_000_000)));
    let tf = &messages(recording, "/tf")[0]["transforms"];
    assert_eq!(tf[0]["parent_frame_id"], "map");
    assert_eq!(tf[0]["child_frame_id"], "ego");
    assert_eq!(tf[0]["timestamp"]["sec"], 946_684_800);
    assert!(
        tf.as_array()
            .unwrap()
            .iter()
            .any(|t| t["parent_frame_id"] == "ego" && t["child_frame_id"] == "ego/sensor0"),
        "the ego's sensor frames hang under the ego: {tf}"
    );
    // The steps' cell counts add up to the point's.
    let signals = messages(recording, "/sightline/signals");
    for count in [
        "occupied",
        "detected",
        "false_positives",
        "ego_observed",
        "joint_observed",
    ] {
        let summed: u64 = signals.iter().map(|s| s["cells"][count].as_u64().unwrap()).sum();
        assert_eq!(Some(summed), point["counts"][count].as_u64(), "{count}");
    }
    // The requirement recorded for is signalled step by step: its last value is
    // the point's.
    let last = messages(recording, "/sightline/requirements").pop().unwrap();
    let signal = last["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["id"] == first_failing["id"])
        .expect("the first failing requirement is signalled");
    let metric = signal["metric"].as_str().unwrap();
    assert_eq!(signal["value"], point["metrics"][metric]);
    assert!(signal["margin"].as_f64().unwrap() < 0.0, "{signal}");
    // results.json and the report name the recording by its hash.
    let sha = crate::support::sha256_hex(recording);
    assert_eq!(run.results["recording"]["sha256"], sha.as_str());
    assert_eq!(run.results["recording"]["file"], RECORDING);
    assert!(run.report.contains(&sha), "the report lacks the recording's hash");
}

/// `run --help` says which point `--record` records: the one the bundled
/// roundabout's recording shows (the worst of its first requirement that fails the run), not
/// the first sweep point.
#[test]
fn run_help_names_the_point_record_records() {
    let help = sightline(["run", "--help"]);
    assert_eq!(help.code, Some(0), "{help}");
    let text = help.stdout.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        text.contains(
            "the worst point of the first requirement that fails the run, or the first point when none does; a grid a second"
        ),
        "{text}"
    );
    assert!(!text.contains("the first sweep point"), "{text}");
}

/// The bundled SUMO grid: no road user comes within d_min of the ego, so
/// missed criticals are over nobody at every step; `/sightline/requirements`
/// signals no value and no margin for them, never 0 (the verdict is not
/// exercised).
#[test]
fn a_requirement_over_nobody_is_signalled_without_a_value() {
    let run = sumo_grid_run();
    let signals = messages(&run.recording, "/sightline/requirements");
    assert!(!signals.is_empty());
    for message in &signals {
        let miss = message["requirements"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["id"] == "GRID-MISS-01")
            .expect("GRID-MISS-01 is signalled");
        assert_eq!((miss.get("value"), miss.get("margin")), (None, None), "{miss}");
    }
}

/// The urban junction shortened to 80 s (the ego reaches the junction after
/// 60 s) with one run per point, half the road users connected (direct packets)
/// and a d_min of 6 m (close approaches): the recording's messages are the
/// record's, counted as results.json counts them, and its relevant road users
/// are results.json's (issue 17).
#[test]
fn urban_recording_counts_the_packets_messages_and_approaches() {
    let text = read(&root().join("scenarios/urban-rsu-semantic.yaml"))
        .replace("duration: 120", "duration: 80")
        .replace("runs: 5 ", "runs: 1 ")
        .replace("penetration: 0 ", "penetration: 0.5 ")
        .replace("d_min: 2", "d_min: 6");
    let tmp = temp_dir();
    let scenario = tmp.path().join("urban.yaml");
    std::fs::write(&scenario, text).unwrap();
    let out = tmp.path().join("out");
    let run = sightline(["run", arg(&scenario), "--out", arg(&out), "--record"]);
    let results = read_json(&out.join("results.json"));
    run.assert_exit(if results["verdict"] == "pass" { 0 } else { 1 });
    // The recorded point: the worst of the first requirement that fails the run, if any.
    let recorded = results["recording"]["point"].as_u64().unwrap() as usize;
    let counts = &results["sweep"][recorded]["counts"];
    assert_eq!(counts["runs"], 1);
    let recording = std::fs::read(out.join(RECORDING)).unwrap();
    let channels = channels(&recording);
    for (topic, schema) in [
        ("/sightline/speeds", "sightline.Speeds"),
        ("/sightline/signals", "sightline.Signals"),
    ] {
        assert_eq!(channels[topic].schema, schema);
        assert_eq!(channels[topic].count, 800, "{topic}: one per step");
    }
    assert!(!channels.contains_key("/fusion/grid"), "a semantic world fuses no grid");
    let sent = messages(&recording, "/semantic/messages");
    let received = sent.iter().filter(|m| m["received"] == true).count() as u64;
    assert_eq!(Some(sent.len() as u64), counts["messages"].as_u64());
    assert_eq!(Some(received), counts["delivered"].as_u64());
    let approaches = messages(&recording, "/semantic/approaches");
    assert!(!approaches.is_empty(), "a d_min of 6 m gives close approaches");
    let missed = approaches.iter().filter(|a| a["flagged"] == false).count() as u64;
    assert_eq!(Some(approaches.len() as u64), counts["close_approaches"].as_u64());
    assert_eq!(Some(missed), counts["missed_criticals"].as_u64());
    let packets = messages(&recording, "/v2x/packets");
    let kinds = |kind: &str| packets.iter().filter(|p| p["kind"] == kind).count() as u64;
    assert_eq!(kinds("downlink"), sent.len() as u64);
    assert!(
        kinds("uplink") > 0 && kinds("direct") > 0,
        "uplinks and direct packets are recorded"
    );
    assert!(channels["/semantic/arrivals"].count <= received);
    assert_eq!(channels["/v2x/packets"].schema, "sightline.Packet");
    assert_eq!(channels["/semantic/objects"].schema, "sightline.Object");
    // Every point's road users; the first point's are results.json's first.
    let objects: Vec<serde_json::Value> = messages(&recording, "/semantic/objects")
        .into_iter()
        .filter(|o| o["point"] == 0)
        .collect();
    let listed = results["sweep"][0]["objects"]["records"].as_array().unwrap();
    assert!(!listed.is_empty());
    assert_eq!(objects.len(), listed.len());
    for (recorded, listed) in objects.iter().zip(listed) {
        for field in [
            "id",
            "class",
            "first_relevant",
            "first_seen",
            "first_v2x",
            "category",
            "min_ttc",
            "max_drac",
            "pet",
        ] {
            assert_eq!(recorded[field], listed[field], "{field}");
        }
        assert_eq!(recorded["closest_time"], listed["closest"]["time"]);
    }
}

/// The lines `run` or `replay` printed, with the first line's destination (`->
/// DIR` or `(replayed from FILE)`) cut off.
fn verdict_lines(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .enumerate()
        .map(
            |(i, line)| match (i, line.rfind(" -> "), line.rfind(" (replayed from ")) {
                (0, Some(at), _) | (0, None, Some(at)) => line[..at].to_string(),
                _ => line.to_string(),
            },
        )
        .collect()
}

/// Writes a bundled run's recording and results.json into `dir`; returns the
/// recording's path.
fn lay_out(run: &Bundled, dir: &Path) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("results.json"), &run.results_json).unwrap();
    let path = dir.join(RECORDING);
    std::fs::write(&path, &run.recording).unwrap();
    path
}

/// Replay prints the verdicts of the run, line for line, and exits as it did,
/// on every bundled scenario.
#[test]
fn replay_gives_the_run_verdicts_on_every_bundled_scenario() {
    let tmp = temp_dir();
    for (i, run) in every_run().into_iter().enumerate() {
        let recording = lay_out(run, &tmp.path().join(i.to_string()));
        let replay = sightline(["replay", arg(&recording)]);
        // The roundabout fails (issue 16), and replays as failing.
        replay.assert_exit(if run.results["gate"] == "pass" { 0 } else { 1 });
        assert_eq!(replay.stderr, "", "{replay}");
        assert_eq!(
            verdict_lines(&replay.stdout),
            verdict_lines(&run.stdout),
            "{}",
            run.scenario
        );
        assert!(
            replay
                .stdout
                .contains(&format!("(replayed from {})", recording.display()))
        );
    }
}

/// A failing run replays as failing: the field fixture whose requirement fails
/// at one of its points.
#[test]
fn replay_of_a_failing_run_fails_with_the_same_lines() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", crate::support::FAILING, "--out", arg(&out), "--record"]);
    run.assert_exit(1);
    let replay = sightline(["replay", arg(&out.join(RECORDING))]);
    replay.assert_exit(1);
    assert_eq!(verdict_lines(&replay.stdout), verdict_lines(&run.stdout));
}

/// A truncated recording is refused, whether or not results.json is beside it.
#[test]
fn replay_refuses_a_truncated_recording() {
    let run = roundabout_run();
    let tmp = temp_dir();
    let alone = tmp.path().join("alone.mcap");
    std::fs::write(&alone, &run.recording[..run.recording.len() - 1000]).unwrap();
    let replay = sightline(["replay", arg(&alone)]);
    replay.assert_exit(2);
    assert_eq!(replay.stdout, "");
    assert!(
        replay.stderr.starts_with(&format!(
            "{}: error: failed to read the recording: it is not a complete, intact MCAP file",
            alone.display()
        )),
        "{replay}"
    );
    assert!(replay.stderr.contains("truncated or damaged"), "{replay}");

    let beside = lay_out(run, &tmp.path().join("beside"));
    std::fs::write(&beside, &run.recording[..run.recording.len() / 2]).unwrap();
    let replay = sightline(["replay", arg(&beside)]);
    replay.assert_exit(2);
    assert!(replay.stderr.contains("results.json beside it records"), "{replay}");
}

/// A channel record of the summary section whose topic claims 2.6 GB is
/// refused before anything is allocated: the `mcap` crate allocates a string by
/// its declared length (a fuzz case of issue 15 aborted so under a 2 GiB cap).
#[test]
fn replay_refuses_a_length_field_past_its_record_within_the_caps() {
    let run = roundabout_run();
    let topic = b"/sightline/verdicts";
    let mut prefixed = (topic.len() as u32).to_le_bytes().to_vec();
    prefixed.extend_from_slice(topic);
    // The last copy is the summary's channel record, read after the data's CRC.
    let at = run
        .recording
        .windows(prefixed.len())
        .rposition(|w| w == prefixed.as_slice())
        .expect("the summary repeats the channel");
    let mut damaged = run.recording.clone();
    damaged[at..at + 4].copy_from_slice(&2_667_577_362u32.to_le_bytes());
    let tmp = temp_dir();
    std::fs::write(tmp.path().join("run.mcap"), &damaged).unwrap();
    let replay = crate::support::sightline_capped(tmp.path(), ["replay", "run.mcap"]);
    if let Some(broken) = replay.broken_contract() {
        panic!("{broken}\n{replay}");
    }
    replay.assert_exit(2);
    assert!(replay.stderr.contains("overruns the record"), "{replay}");
}

/// A recording whose bytes are not those results.json hashed is refused; a
/// damaged byte is caught by the CRCs when no results.json is beside it.
#[test]
fn replay_refuses_a_recording_that_does_not_match_its_results() {
    let run = sumo_grid_run();
    let tmp = temp_dir();
    let mut damaged = run.recording.clone();
    let middle = damaged.len() / 2;
    damaged[middle] ^= 0x55;

    let beside = lay_out(run, &tmp.path().join("beside"));
    std::fs::write(&beside, &damaged).unwrap();
    let replay = sightline(["replay", arg(&beside)]);
    replay.assert_exit(2);
    let sha = crate::support::sha256_hex(&damaged);
    let expected = crate::support::sha256_hex(&run.recording);
    assert_eq!(
        replay.stderr,
        format!(
            "{}: error: its SHA-256 is {sha}, and {} beside it records {expected}: the recording was changed or is not the one that run wrote\n",
            beside.display(),
            beside.with_file_name("results.json").display()
        )
    );

    let alone = tmp.path().join("alone.mcap");
    std::fs::write(&alone, &damaged).unwrap();
    let replay = sightline(["replay", arg(&alone)]);
    replay.assert_exit(2);
    assert!(replay.stderr.contains("truncated or damaged"), "{replay}");
}

/// `recording` written anew with each message on `topic` edited by `edit`:
/// the CRCs are made for the new bytes, so only what replay checks beyond the
/// container can catch the change.
fn rewritten(recording: &[u8], topic: &str, edit: impl Fn(&mut serde_json::Value)) -> Vec<u8> {
    let mut writer = mcap::Writer::new(std::io::Cursor::new(Vec::new())).unwrap();
    for message in mcap::MessageStream::new(recording).unwrap() {
        let mut message = message.unwrap();
        if message.channel.topic == topic {
            let mut json: serde_json::Value = serde_json::from_slice(&message.data).unwrap();
            edit(&mut json);
            message.data = serde_json::to_vec(&json).unwrap().into();
        }
        writer.write(&message).unwrap();
    }
    writer.finish().unwrap();
    writer.into_inner().into_inner()
}

/// A recording whose outcome says accuracy = 1.11 (the failing γ = 30 point),
/// in an intact container: replay refuses to judge it (it would have turned
/// the FAIL into a PASS), exit 3 (issue 13).
#[test]
fn replay_of_a_value_outside_its_domain_is_an_internal_error() {
    let tmp = temp_dir();
    let out = tmp.path().join("run");
    sightline(["run", FAILING, "--record", "--out", arg(&out)]).assert_exit(1);
    let recording = std::fs::read(out.join(RECORDING)).unwrap();
    let forged = rewritten(&recording, "/sightline/outcome", |outcome| {
        if outcome["point"] == 1 {
            let metrics = outcome["metrics"].as_array_mut().unwrap();
            let accuracy = metrics.iter_mut().find(|m| m["metric"] == "accuracy").unwrap();
            accuracy["value"] = 1.11.into();
        }
    });
    let alone = tmp.path().join("alone.mcap");
    std::fs::write(&alone, &forged).unwrap();
    let replay = sightline(["replay", arg(&alone)]);
    replay.assert_exit(3);
    assert_eq!(replay.stdout, "", "no verdict");
    assert_eq!(
        replay.stderr,
        format!(
            "{}: error: point 1: accuracy = 1.11, outside its domain ([0, 1]): no simulation gives such a value \
             (a defect in the sightline that measured it, or a file altered and sealed again); nothing is judged\n",
            alone.display()
        )
    );
}

/// Steps of a point the recording does not list as recorded are refused, in
/// an intact container: the bundled roundabout's steps, said to be of a point
/// it did not record (issue 18).
#[test]
fn replay_refuses_steps_of_a_point_it_did_not_record() {
    let run = roundabout_run();
    let recorded = run.results["recording"]["point"].as_u64().unwrap();
    let other = (recorded + 1) % 19;
    let forged = rewritten(&run.recording, "/sightline/signals", |signals| {
        signals["point"] = other.into();
    });
    let tmp = temp_dir();
    let alone = tmp.path().join("alone.mcap");
    std::fs::write(&alone, &forged).unwrap();
    let replay = sightline(["replay", arg(&alone)]);
    replay.assert_exit(2);
    assert!(
        replay.stderr.contains(&format!(
            "it holds steps of point {other}, which it does not list as recorded"
        )),
        "{replay}"
    );
}

/// Usage errors: a missing file, and a file that is not MCAP.
#[test]
fn replay_refuses_what_is_not_a_recording() {
    let tmp = temp_dir();
    let missing = tmp.path().join("missing.mcap");
    let replay = sightline(["replay", arg(&missing)]);
    replay.assert_exit(2);
    assert!(
        replay
            .stderr
            .starts_with(&format!("{}: error: failed to read the recording: ", missing.display()))
    );
    let replay = sightline(["replay", crate::support::SMALL_FIELD]);
    replay.assert_exit(2);
    assert!(replay.stderr.contains("not a complete, intact MCAP file"), "{replay}");
}

/// The same scenario and seed give a byte-identical recording whatever the
/// number of worker threads: a short roundabout recording every topic (all
/// agents cooperating, a grid every step, each agent's own grid), a short
/// junction, and a short joint junction whose two points share one simulation,
/// each recorded as it runs (issue 18), of which the failing second point's is
/// kept and nothing else of the other stays in the evidence set.
#[test]
fn recording_is_byte_identical_whatever_the_thread_count() {
    let tmp = temp_dir();
    let roundabout = short_roundabout("4").replace("snapshot: 12", "snapshot: 2")
        + "record: { where: { perception.cooperating: 6 }, grid_rate: 10, agent_grids: true }\n";
    let urban = read(&root().join("scenarios/urban-rsu-semantic.yaml"))
        .replace("duration: 120", "duration: 70")
        .replace("runs: 5 ", "runs: 2 ")
        + "record: { point: 1 }\n";
    let joint = read(&root().join("scenarios/junction-joint.yaml"))
        .replace("duration: 20", "duration: 8")
        .replace("where: { fusion.method: bayes }", "where: { fusion.method: dempster }")
        .replace("blind_recall, at_least: 0.5", "blind_recall, at_least: 0.99")
        + "record: { grid_rate: 2, agent_grids: true }\n";
    for (name, text) in [("roundabout", roundabout), ("urban", urban), ("joint", joint)] {
        let scenario = tmp.path().join(format!("{name}.yaml"));
        std::fs::write(&scenario, text).unwrap();
        let evidence: Vec<(Vec<u8>, String)> = ["1", "3"]
            .iter()
            .map(|jobs| {
                let out = tmp.path().join(format!("{name}-{jobs}"));
                let run = sightline(["run", arg(&scenario), "--out", arg(&out), "--jobs", jobs]);
                assert!(matches!(run.code, Some(0 | 1)), "{run}");
                if name == "joint" {
                    let results = read_json(&out.join("results.json"));
                    assert_eq!(results["recording"]["point"].as_u64(), Some(1), "{run}");
                    let mut files = files_under(&out);
                    files.sort();
                    assert_eq!(
                        files,
                        ["junit.xml", "report.html", "results.json", RECORDING].map(Path::new)
                    );
                }
                (
                    std::fs::read(out.join(RECORDING)).unwrap(),
                    normalise_execution(&read(&out.join("results.json"))),
                )
            })
            .collect();
        assert!(evidence[0].0.len() > 1000, "{name}: a recording was written");
        for other in &evidence[1..] {
            assert!(other.0 == evidence[0].0, "{name}: run.mcap depends on the thread count");
            assert_eq!(
                other.1, evidence[0].1,
                "{name}: results.json depends on the thread count"
            );
        }
    }
}

/// The official Python reader (`pip install mcap`) reads every bundled
/// scenario's recording: the same channels, schemas and counts as the MCAP
/// library, lz4 chunks, and the imported files attached.
/// Skipped (with a message) only when `SIGHTLINE_MCAP_PYTHON` is unset; `.ci/run`
/// sets it, and then any failure of the reader fails the test.
#[test]
fn the_python_mcap_reader_reads_the_recordings() {
    let Some(python) = tool(PYTHON_VAR, "a Python with the official reader (mcap 1.6.0)") else {
        return;
    };
    let tmp = temp_dir();
    for (i, run) in every_run().into_iter().enumerate() {
        let recording = lay_out(run, &tmp.path().join(i.to_string()));
        let output = Command::new(&python)
            .arg(root().join("tests/python/read_recording.py"))
            .arg(&recording)
            .output()
            .unwrap_or_else(|e| panic!("failed to start {}: {e}", Path::new(&python).display()));
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            output.status.success(),
            "the Python reader failed on {}:\n{stderr}",
            run.scenario
        );
        let read: serde_json::Value = serde_json::from_slice(&output.stdout)
            .unwrap_or_else(|e| panic!("the Python reader printed no JSON ({e}):\n{stderr}"));
        assert_eq!(read["library"], "sightline");
        assert_eq!(read["compression"], serde_json::json!(["lz4"]));
        assert_eq!(read["problems"], serde_json::json!([]), "{}", run.scenario);
        let python_channels: BTreeMap<String, Channel> = read["channels"]
            .as_object()
            .unwrap()
            .iter()
            .map(|(topic, c)| {
                assert_eq!(c["schema_encoding"], "jsonschema");
                assert_eq!(c["message_encoding"], "json");
                let channel = Channel {
                    schema: c["schema"].as_str().unwrap().into(),
                    count: c["count"].as_u64().unwrap(),
                };
                (topic.clone(), channel)
            })
            .collect();
        assert_eq!(python_channels, channels(&run.recording), "{}", run.scenario);
        // The reader lists the attachments by name.
        let mut imports: Vec<&str> = run.results["inputs"]
            .as_array()
            .unwrap()
            .iter()
            .skip(1)
            .map(|input| input["path"].as_str().unwrap())
            .collect();
        imports.sort_unstable();
        assert_eq!(read["attachments"], serde_json::json!(imports), "{}", run.scenario);
    }
}
