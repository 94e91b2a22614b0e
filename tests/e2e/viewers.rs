//! Recordings the viewers load (issue 18, part 1), checked with the viewers'
//! own artefacts rather than look-alikes: every bundled scenario's run.mcap,
//! its channels and messages read with the MCAP library, is handed to
//! `ci/viewers/check-recording.js`, which checks with the npm packages
//! `ci/viewers/package-lock.json` pins that every `foxglove.*` schema equals the
//! one `@foxglove/schemas` publishes, that every schema is in the subset
//! Foxglove's and Lichtblick's parsers accept, and that every message validates
//! against its schema (ajv).
//!
//! `.ci/run` installs the packages (`npm ci`) and sets `SIGHTLINE_VIEWER_CHECKS`;
//! the test then fails rather than skips. Without it, it runs when `node` and
//! the installed packages are there, and says why it skips otherwise.
// See: issue 18, "Recordings the viewers load".

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use crate::bundled::every_run;
use crate::record::messages;
use crate::support::{RECORDING, arg, read, root, short_roundabout, sightline, temp_dir};

/// Set by `.ci/run` once `npm ci` has installed `ci/viewers/`: the check must run.
const CHECKS_VAR: &str = "SIGHTLINE_VIEWER_CHECKS";

/// The folder of the check script and its pinned packages.
fn viewers() -> PathBuf {
    root().join("ci/viewers")
}

/// Whether the check can run here; panics when `.ci/run` asked for it and it
/// cannot.
fn checks_available() -> bool {
    let node = Command::new("node")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    let installed =
        viewers().join("node_modules/@foxglove/schemas").is_dir() && viewers().join("node_modules/ajv").is_dir();
    let required = std::env::var_os(CHECKS_VAR).is_some() || std::env::var_os("CI").is_some();
    let why = match (node, installed) {
        (true, true) => return true,
        (false, _) => "node is not on PATH",
        (true, false) => "ci/viewers has no node_modules (run `npm ci --prefix ci/viewers`)",
    };
    assert!(
        !required,
        "{CHECKS_VAR} or CI is set but {why}: the viewers' checks cannot run"
    );
    eprintln!("skipped: {why}; .ci/run installs the viewers' packages and runs this check");
    false
}

/// One JSON line per schema, then one per message, as `check-recording.js` reads them.
fn dump(recording: &[u8], out: &Path) {
    let mut lines = std::io::BufWriter::new(std::fs::File::create(out).unwrap());
    let summary = mcap::Summary::read(recording)
        .expect("the recording has a valid summary")
        .expect("the recording has a summary");
    for schema in summary.schemas.values() {
        let line = serde_json::json!({
            "schema": schema.name,
            "encoding": schema.encoding,
            "data": String::from_utf8(schema.data.to_vec()).expect("a JSON Schema is UTF-8"),
        });
        writeln!(lines, "{line}").unwrap();
    }
    for message in mcap::MessageStream::new(recording).expect("the recording reads") {
        let message = message.expect("every message reads");
        let channel = &message.channel;
        let line = serde_json::json!({
            "topic": channel.topic,
            "schema": channel.schema.as_ref().map(|s| s.name.clone()),
            "encoding": channel.message_encoding,
            "data": String::from_utf8(message.data.to_vec()).expect("a JSON message is UTF-8"),
        });
        writeln!(lines, "{line}").unwrap();
    }
    lines.flush().unwrap();
}

/// Recordings of the topics the bundled ones leave out, by name: a short
/// roundabout with every vehicle cooperating and each one's own grid, its
/// clock set to 2026-03-01T08:00:00Z (`time.start`, written at +01:00), and the
/// urban junction with a d_min of 6 m (close approaches) and one run per point.
fn extra_recordings() -> &'static [(&'static str, Vec<u8>)] {
    static RECORDINGS: OnceLock<Vec<(&'static str, Vec<u8>)>> = OnceLock::new();
    RECORDINGS.get_or_init(|| {
        let roundabout = short_roundabout("3, start: 2026-03-01T09:00:00+01:00").replace("snapshot: 12", "snapshot: 2")
            + "record: { where: { perception.cooperating: 6 }, agent_grids: true }\n";
        let urban = read(&root().join("scenarios/urban-rsu-semantic.yaml"))
            .replace("duration: 120", "duration: 80")
            .replace("runs: 5 ", "runs: 1 ")
            .replace("d_min: 2", "d_min: 6")
            + "record: { point: 0 }\n";
        let tmp = temp_dir();
        [
            ("short roundabout, agent grids", roundabout),
            ("urban junction, d_min 6 m", urban),
        ]
        .into_iter()
        .enumerate()
        .map(|(i, (name, text))| {
            let scenario = tmp.path().join(format!("{i}.yaml"));
            std::fs::write(&scenario, text).unwrap();
            let out = tmp.path().join(i.to_string());
            let run = sightline(["run", arg(&scenario), "--out", arg(&out)]);
            assert!(matches!(run.code, Some(0 | 1)), "{run}");
            (name, std::fs::read(out.join(RECORDING)).unwrap())
        })
        .collect()
    })
}

/// A run of the bundled roundabout, 3 s long, recording every point and the
/// agents' grids (`record: { points: all, agent_grids: true }`): what it
/// printed, its exit code and its recording.
struct EveryPoint {
    stdout: String,
    code: i32,
    recording: Vec<u8>,
}

fn every_point() -> &'static EveryPoint {
    static RUN: OnceLock<EveryPoint> = OnceLock::new();
    RUN.get_or_init(|| {
        let text = short_roundabout("3").replace("snapshot: 12", "snapshot: 2")
            + "record: { points: all, agent_grids: true }\n";
        let tmp = temp_dir();
        let scenario = tmp.path().join("every-point.yaml");
        std::fs::write(&scenario, text).unwrap();
        let out = tmp.path().join("out");
        let run = sightline(["run", arg(&scenario), "--out", arg(&out)]);
        let code = run.code.expect("an exit code");
        assert!(matches!(code, 0 | 1), "{run}");
        EveryPoint {
            stdout: run.stdout.clone(),
            code,
            recording: std::fs::read(out.join(RECORDING)).unwrap(),
        }
    })
}

/// Every recording these tests read: the bundled scenarios', the extra ones
/// and the one of every point.
fn recordings() -> Vec<(&'static str, &'static [u8])> {
    let bundled = every_run()
        .into_iter()
        .map(|run| (run.scenario, run.recording.as_slice()));
    let extra = extra_recordings().iter().map(|(name, bytes)| (*name, bytes.as_slice()));
    let every = std::iter::once(("short roundabout, every point", every_point().recording.as_slice()));
    bundled.chain(extra).chain(every).collect()
}

/// Every point of the roundabout's 19 (`record.points: all`, issue 18), each
/// in its own minute: the scenario message lists them with their offsets, each
/// step's signals carry their point and lie within its minute, and a point's
/// agents and grids are cleared a second after its last step.
#[test]
fn every_point_is_recorded_a_minute_after_the_last() {
    let recording = &every_point().recording;
    let epoch = sightline_dsl::DEFAULT_START;
    let messages: Vec<mcap::Message> = mcap::MessageStream::new(recording)
        .unwrap()
        .map(|m| m.unwrap())
        .collect();
    let json = |m: &mcap::Message| -> serde_json::Value { serde_json::from_slice(&m.data).unwrap() };
    let on = |topic: &'static str| messages.iter().filter(move |m| m.channel.topic == topic);
    let scenario = json(on("/sightline/scenario").next().unwrap());
    let points = scenario["points"].as_array().unwrap();
    assert_eq!(points.len(), 19);
    for (k, point) in points.iter().enumerate() {
        assert_eq!(point["point"], k);
        assert_eq!(point["offset"], 60.0 * k as f64);
    }
    let minute = 60_000_000_000_u64;
    let mut steps = [0_u64; 19];
    for m in on("/sightline/signals") {
        let k = json(m)["point"].as_u64().unwrap();
        steps[k as usize] += 1;
        let start = epoch + k * minute;
        assert!(
            m.log_time >= start && m.log_time < start + 3_000_000_000,
            "point {k} at {}",
            m.log_time
        );
    }
    assert_eq!(steps, [30; 19]);
    // The last step of each point but the last is at 2.9 s; its agents go at 3.9 s.
    let cleared: Vec<u64> = on("/scene/agents")
        .filter(|m| json(m)["entities"].as_array().unwrap().is_empty())
        .map(|m| m.log_time)
        .collect();
    let expected: Vec<u64> = (0..18).map(|k| epoch + k * minute + 3_900_000_000).collect();
    assert_eq!(cleared, expected);
    // So are the grids: each grid topic a point showed (an agent's only where
    // it cooperates) gets a grid of no cell then (its fields kept; one cell's
    // row stride, so that a viewer counts 0 rows), and nothing else is
    // cell-less.
    let grid_topics: std::collections::BTreeSet<&str> = messages
        .iter()
        .map(|m| m.channel.topic.as_str())
        .filter(|t| *t == "/fusion/grid" || t.ends_with("/grid"))
        .collect();
    assert!(grid_topics.len() > 1, "{grid_topics:?}");
    for topic in grid_topics {
        let (empty, shown): (Vec<_>, Vec<_>) = messages
            .iter()
            .filter(|m| m.channel.topic == topic)
            .map(|m| (m.log_time, json(m)))
            .partition(|(_, grid)| grid["column_count"] == 0);
        let times: Vec<u64> = empty.iter().map(|(t, _)| *t).collect();
        let showing: Vec<u64> = expected
            .iter()
            .copied()
            .filter(|&at| shown.iter().any(|(t, _)| (at - 3_900_000_000..at).contains(t)))
            .collect();
        assert!(!showing.is_empty(), "{topic}");
        assert_eq!(times, showing, "{topic}");
        for (_, grid) in &empty {
            assert_eq!(
                (&grid["data"], &grid["row_stride"]),
                (&"".into(), &grid["cell_stride"]),
                "{topic}"
            );
            assert!(!grid["fields"].as_array().unwrap().is_empty(), "{topic}");
        }
    }
    // Until then /tf holds the point's last frames (written again at that
    // time), so that what is locked to them does not glide towards the next
    // point's first step.
    let tf: Vec<&mcap::Message> = on("/tf").collect();
    let frames = |m: &mcap::Message| -> Vec<serde_json::Value> {
        let mut transforms = json(m)["transforms"].as_array().unwrap().clone();
        for t in &mut transforms {
            assert_eq!(t["timestamp"], json(m)["transforms"][0]["timestamp"]);
            t.as_object_mut().unwrap().remove("timestamp");
        }
        transforms
    };
    for at in expected {
        let k = tf
            .iter()
            .position(|m| m.log_time == at)
            .expect("/tf when a point is cleared");
        assert_eq!(tf[k - 1].log_time, at - 1_000_000_000);
        assert_eq!(frames(tf[k]), frames(tf[k - 1]), "at {at}");
    }
    assert_eq!(on("/scene/map").count(), 19);
}

/// Every entity locked to a frame is drawn where `/tf` places that frame, and
/// the topics of such entities are written only when what they show changes:
/// in every recording, once all messages of a time at which `/tf` is written
/// are read, each entity of the latest message of every `foxglove.SceneUpdate`
/// topic that is `frame_locked` (kept until replaced) is in a frame that time's
/// `/tf` holds; at each step (a time with `/sightline/signals`), `/scene/agents`
/// shows exactly the agents `/tf` places in `map`, one entity per frame, and
/// `/scene/fields_of_view` exactly the sensor frames. Each message of those two
/// topics replaces the whole set, and differs from the one before it.
#[test]
fn locked_entities_follow_tf_and_are_written_when_they_change() {
    let locked_topics = ["/scene/agents", "/scene/fields_of_view"];
    let mut written_less = [false; 2];
    for (name, recording) in recordings() {
        // Per topic, the latest message's entities as (id, frame, locked).
        let mut shown: std::collections::BTreeMap<String, Vec<(String, String, bool)>> = Default::default();
        let mut writes = [0; 2];
        let mut steps = 0;
        // The time being read, its /tf frames (child → parent) and whether it is a step.
        let mut time = None;
        let mut frames: Option<std::collections::BTreeMap<String, String>> = None;
        let mut step = false;
        let check = |at: u64,
                     frames: &std::collections::BTreeMap<String, String>,
                     step: bool,
                     shown: &std::collections::BTreeMap<String, Vec<(String, String, bool)>>| {
            for (topic, entities) in shown {
                for (id, frame, locked) in entities {
                    assert!(
                        !locked || frames.contains_key(frame),
                        "{name}: {topic}'s {id} is locked to {frame}, which /tf lacks at {at}"
                    );
                }
            }
            if !step {
                return;
            }
            let of = |topic: &str| -> BTreeSet<String> {
                let entities = shown.get(topic).map(Vec::as_slice).unwrap_or_default();
                let set: BTreeSet<String> = entities.iter().map(|(_, frame, _)| frame.clone()).collect();
                assert_eq!(
                    set.len(),
                    entities.len(),
                    "{name}: one {topic} entity per frame at {at}"
                );
                set
            };
            let agents: BTreeSet<String> = frames
                .iter()
                .filter(|(_, p)| *p == "map")
                .map(|(c, _)| c.clone())
                .collect();
            let sensors: BTreeSet<String> = frames
                .iter()
                .filter(|(_, p)| *p != "map")
                .map(|(c, _)| c.clone())
                .collect();
            assert_eq!(of("/scene/agents"), agents, "{name} at {at}");
            assert_eq!(of("/scene/fields_of_view"), sensors, "{name} at {at}");
        };
        for m in mcap::MessageStream::new(recording).unwrap().map(|m| m.unwrap()) {
            if time != Some(m.log_time) {
                if let (Some(at), Some(frames)) = (time, frames.take()) {
                    check(at, &frames, step, &shown);
                }
                (time, step) = (Some(m.log_time), false);
            }
            let json: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
            let topic = m.channel.topic.as_str();
            match m.channel.schema.as_ref().map(|s| s.name.as_str()) {
                Some("foxglove.FrameTransforms") => {
                    steps += 1;
                    let transforms = json["transforms"].as_array().unwrap().iter();
                    frames = Some(
                        transforms
                            .map(|t| {
                                let child = t["child_frame_id"].as_str().unwrap().to_string();
                                (child, t["parent_frame_id"].as_str().unwrap().to_string())
                            })
                            .collect(),
                    );
                }
                Some("foxglove.SceneUpdate") => {
                    let entities: Vec<(String, String, bool)> = json["entities"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|e| {
                            let locked = e["frame_locked"] == true;
                            if locked {
                                assert_eq!(e["lifetime"], serde_json::json!({ "sec": 0, "nsec": 0 }), "{name}");
                            }
                            let text = |key: &str| e[key].as_str().unwrap().to_string();
                            (text("id"), text("frame_id"), locked)
                        })
                        .collect();
                    if let Some(k) = locked_topics.iter().position(|t| *t == topic) {
                        writes[k] += 1;
                        assert_eq!(json["deletions"][0]["type"], 1, "{name}: each message replaces all");
                        assert!(entities.iter().all(|(_, _, locked)| *locked), "{name}: {topic}");
                        assert_ne!(
                            shown.get(topic),
                            Some(&entities),
                            "{name}: {topic} written again unchanged at {}",
                            m.log_time
                        );
                    }
                    shown.insert(topic.to_string(), entities);
                }
                _ if topic == "/sightline/signals" => step = true,
                _ => {}
            }
        }
        if let (Some(at), Some(frames)) = (time, frames.take()) {
            check(at, &frames, step, &shown);
        }
        for (k, topic) in locked_topics.iter().enumerate() {
            assert!(writes[k] <= steps, "{name}: {topic} {} > {steps}", writes[k]);
            written_less[k] |= writes[k] > 0 && writes[k] < steps;
        }
    }
    assert_eq!(
        written_less, [true; 2],
        "some recording keeps its agents and its fields of view over several steps"
    );
}

/// `sightline replay` re-checks a recording of every point: the run's verdicts,
/// line for line, and its exit code, each point's steps added up against its
/// outcome.
#[test]
fn a_recording_of_every_point_replays_as_the_run() {
    let run = every_point();
    let tmp = temp_dir();
    let path = tmp.path().join(RECORDING);
    std::fs::write(&path, &run.recording).unwrap();
    let replay = sightline(["replay", arg(&path)]);
    replay.assert_exit(run.code);
    let lines = |stdout: &str| -> Vec<String> { stdout.lines().skip(1).map(str::to_string).collect() };
    assert_eq!(lines(&replay.stdout), lines(&run.stdout), "{replay}");
}

/// `time.start` places the recording at its date: the first step, the map and
/// every message's log time count from 2026-03-01T08:00:00Z, whatever offset
/// the file writes it with (the default epoch is checked with the bundled
/// roundabout, `record::bundled_roundabout_recording_has_foxglove_channels_and_the_steps`).
#[test]
fn time_start_places_the_recording_at_its_date() {
    let (_, recording) = &extra_recordings()[0];
    let start = 1_772_352_000_u64 * 1_000_000_000;
    let messages: Vec<mcap::Message> = mcap::MessageStream::new(recording)
        .unwrap()
        .map(|m| m.unwrap())
        .collect();
    let first = messages.iter().map(|m| m.log_time).min().unwrap();
    let last = messages.iter().map(|m| m.log_time).max().unwrap();
    assert_eq!(first, start);
    // Three seconds of 0.1 s steps: the last step at 2.9 s.
    assert_eq!(last, start + 2_900_000_000);
    let map = messages.iter().find(|m| m.channel.topic == "/scene/map").unwrap();
    let map: serde_json::Value = serde_json::from_slice(&map.data).unwrap();
    assert_eq!(
        map["entities"][0]["timestamp"],
        serde_json::json!({ "sec": 1_772_352_000, "nsec": 0 })
    );
}

/// A topic as the documentation names it: an agent's id as `<id>`.
fn documented_form(topic: &str) -> String {
    match topic.split('/').collect::<Vec<_>>()[..] {
        ["", "perception", _, what] => format!("/perception/<id>/{what}"),
        _ => topic.to_string(),
    }
}

/// The topics `docs/recording.md`'s channel table lists.
fn documented_topics() -> BTreeSet<String> {
    let docs = read(&root().join("docs/recording.md"));
    let table = docs
        .split("## Channels")
        .nth(1)
        .expect("docs/recording.md has a section Channels");
    table
        .lines()
        .filter_map(|line| line.strip_prefix("| `/"))
        .map(|rest| format!("/{}", &rest[..rest.find('`').expect("a topic in backquotes")]))
        .collect()
}

/// The documented topics are exactly the written ones: every topic of the
/// channel table is written by a real recording, and every topic a recording
/// writes is in the table; the layout shipped in `docs/` shows only written
/// topics.
#[test]
fn the_documented_topics_are_the_written_ones() {
    let documented = documented_topics();
    let mut written = BTreeSet::new();
    for (name, recording) in recordings() {
        let summary = mcap::Summary::read(recording).unwrap().unwrap();
        for channel in summary.channels.values() {
            let topic = documented_form(&channel.topic);
            assert!(
                documented.contains(&topic),
                "{name} writes {topic}, which docs/recording.md does not list"
            );
            written.insert(topic);
        }
    }
    let unwritten: Vec<&String> = documented.difference(&written).collect();
    assert!(
        unwritten.is_empty(),
        "docs/recording.md lists topics no recording writes: {unwritten:?}"
    );
    let layout: serde_json::Value = serde_json::from_str(&read(&root().join("docs/foxglove-layout.json"))).unwrap();
    let mut shown = Vec::new();
    collect_topics(&layout, &mut shown);
    assert!(shown.len() >= 5, "the layout shows the recording: {shown:?}");
    for topic in shown {
        assert!(
            written.contains(&documented_form(&topic)),
            "the layout shows {topic}, which no recording writes"
        );
    }
}

/// Every topic a layout names: keys and string values that start with `/`,
/// cut at the message path's first `.`.
fn collect_topics(node: &serde_json::Value, out: &mut Vec<String>) {
    fn add(text: &str, out: &mut Vec<String>) {
        if text.starts_with('/') {
            out.push(text.split('.').next().unwrap_or(text).to_string());
        }
    }
    match node {
        serde_json::Value::String(text) => add(text, out),
        serde_json::Value::Object(map) => {
            for (key, value) in map {
                add(key, out);
                collect_topics(value, out);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|item| collect_topics(item, out)),
        _ => {}
    }
}

/// Every series the layout plots finds numbers in some recording: its message
/// path (`/topic.field[0].field`, `field[:]{key=="value"}`, as the viewers
/// write them) resolved on the topic's messages.
#[test]
fn the_layouts_plots_find_numbers() {
    let layout: serde_json::Value = serde_json::from_str(&read(&root().join("docs/foxglove-layout.json"))).unwrap();
    let panels = layout["configById"].as_object().unwrap();
    let paths: Vec<&str> = (panels.iter())
        .filter(|(id, _)| id.starts_with("Plot!"))
        .flat_map(|(_, panel)| panel["paths"].as_array().unwrap())
        .map(|path| path["value"].as_str().unwrap())
        .collect();
    assert!(paths.len() >= 7, "the layout plots series: {paths:?}");
    let recorded = recordings();
    for path in paths {
        let (topic, fields) = path.split_once('.').unwrap();
        let found = recorded.iter().any(|(_, recording)| {
            (messages(recording, topic).iter()).any(|message| resolve(message, fields).iter().any(|v| v.is_number()))
        });
        assert!(found, "the layout plots {path}, which finds no number in any recording");
    }
}

/// The values a message path's fields (after the topic) reach in `value`:
/// `name`, `name[i]`, `name[:]` and `name[:]{key=="text"}`, joined by `.`.
fn resolve<'v>(value: &'v serde_json::Value, fields: &str) -> Vec<&'v serde_json::Value> {
    let mut reached = vec![value];
    for field in fields.split('.') {
        let (name, rest) = field.split_once('[').map_or((field, ""), |(n, r)| (n, r));
        reached = reached.into_iter().filter_map(|v| v.get(name)).collect();
        if rest.is_empty() {
            continue;
        }
        let (index, filter) = rest.split_once(']').unwrap();
        reached = (reached.into_iter())
            .filter_map(|v| v.as_array())
            .flat_map(|items| match index {
                ":" => items.iter().collect::<Vec<_>>(),
                i => items.get(i.parse::<usize>().unwrap()).into_iter().collect(),
            })
            .collect();
        if let Some(filter) = filter.strip_prefix('{').and_then(|f| f.strip_suffix('}')) {
            let (key, text) = filter.split_once("==").unwrap();
            let text = text.trim_matches('"');
            reached.retain(|v| v.get(key).and_then(|k| k.as_str()) == Some(text));
        }
    }
    reached
}

/// Every recording (the bundled scenarios' and the extra ones): Foxglove's
/// published schemas, the viewers' subset, and every message valid against its
/// schema.
#[test]
fn every_recording_matches_the_viewers_schemas() {
    if !checks_available() {
        return;
    }
    let tmp = temp_dir();
    for (i, (name, recording)) in recordings().into_iter().enumerate() {
        let path = tmp.path().join(format!("{i}.jsonl"));
        dump(recording, &path);
        let output = Command::new("node")
            .arg(viewers().join("check-recording.js"))
            .arg(&path)
            .output()
            .expect("node starts");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            output.status.success(),
            "{name}: the viewers' checks found problems:\n{stdout}{}",
            String::from_utf8_lossy(&output.stderr)
        );
        // The summary line: the check saw the schemas and messages.
        assert!(stdout.contains(": 0 problem(s)"), "{name}: {stdout}");
    }
}

/// The check is not a check that cannot fail: a look-alike of a Foxglove schema
/// (the one sightline wrote before issue 18, with `$defs` and `$ref`), a type
/// array and a message against its schema are each found.
#[test]
fn the_viewers_check_finds_what_the_viewers_refuse() {
    if !checks_available() {
        return;
    }
    let tmp = temp_dir();
    let path = tmp.path().join("bad.jsonl");
    let log = serde_json::json!({
        "title": "foxglove.Log", "type": "object",
        "$defs": { "Time": { "type": "object", "properties": { "sec": { "type": "integer" } } } },
        "properties": { "timestamp": { "$ref": "#/$defs/Time" }, "message": { "type": "string" } }
    });
    let signals = serde_json::json!({
        "title": "sightline.Signals", "type": "object",
        "properties": { "recall": { "type": ["number", "null"] }, "step": { "type": "integer" } },
        "required": ["step"]
    });
    let lines = [
        serde_json::json!({ "schema": "foxglove.Log", "encoding": "jsonschema", "data": log.to_string() }),
        serde_json::json!({ "schema": "sightline.Signals", "encoding": "jsonschema", "data": signals.to_string() }),
        serde_json::json!({ "topic": "/sightline/signals", "schema": "sightline.Signals", "encoding": "json", "data": r#"{"step":"one"}"# }),
    ];
    std::fs::write(&path, lines.map(|l| l.to_string()).join("\n")).unwrap();
    let output = Command::new("node")
        .arg(viewers().join("check-recording.js"))
        .arg(&path)
        .output()
        .expect("node starts");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    for expected in [
        "schema foxglove.Log: differs from the one @foxglove/schemas publishes",
        "schema foxglove.Log.timestamp: type undefined",
        "schema sightline.Signals.recall: type [\"number\",\"null\"]",
        "/sightline/signals: /step must be integer (sightline.Signals)",
    ] {
        assert!(stdout.contains(expected), "missing {expected:?} in:\n{stdout}");
    }
}
