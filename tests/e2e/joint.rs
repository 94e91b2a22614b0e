//! One world (issue 17, part 4): collective perception and the semantic
//! pipeline run together, end to end. A hand-built scene judged road user by
//! road user (pass, fail, not exercised), the bundled junction with both
//! models (its evidence, its recording with both models' steps, its
//! pedestrian requirement failing without the shared grids), the same
//! evidence from shards and at any thread count.
// See: issue 17, "One world".

use std::path::Path;
use std::sync::OnceLock;

use crate::bundled::{Bundled, run_bundled};
use crate::record::{channels, messages};
use crate::support::{
    arg, files_under, normalise_execution, normalise_junit_times, read, read_json, requirement, root, sightline,
    temp_dir, unescape_html, verdict,
};

/// Two walkers, one in the Bayesian grid from 1.2 s, one never
/// (`engine/tests/joint.rs` works them out).
const WALKERS: &str = "tests/fixtures/valid/joint-two-walkers.yaml";

/// The bundled junction with both models.
const JUNCTION: &str = "scenarios/junction-joint.yaml";

/// The bundled joint junction, run once with `--record`; every requirement
/// holds.
pub fn junction_run() -> &'static Bundled {
    static RUN: OnceLock<Bundled> = OnceLock::new();
    RUN.get_or_init(|| run_bundled(JUNCTION, 0))
}

/// Each requirement of the hand-built scene has the verdict its road users
/// give: walker_a in the grid 8.7 s before its closest approach (pass),
/// walker_b never in it (fail, no value), nobody within 5 m (not exercised).
#[test]
fn a_joint_world_judges_each_road_user_by_the_grid_and_the_warnings() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", WALKERS, "--out", arg(&out)]);
    run.assert_exit(1);
    let results = read_json(&out.join("results.json"));
    let (status, lead, n) = verdict(&results, "JOINT-A-01");
    assert_eq!((status.as_str(), n), ("pass", Some(1)));
    assert!((lead.unwrap() - 8.7).abs() < 1e-9, "{lead:?}");
    assert_eq!(verdict(&results, "JOINT-B-01"), ("fail".into(), None, Some(1)));
    assert!(
        run.stdout
            .contains("had no grid_lead (never in the ego's fused grid: walker_b)"),
        "{run}"
    );
    assert_eq!(
        verdict(&results, "JOINT-NEAR-01"),
        ("not_exercised".into(), None, Some(0))
    );
    // The points share one simulation: their pipelines differ only in the
    // grid's times, null where a road user never came into the grid.
    let in_grid = |point: usize| -> Vec<(String, serde_json::Value)> {
        results["sweep"][point]["semantic"]["objects"]["records"]
            .as_array()
            .unwrap()
            .iter()
            .map(|o| (o["id"].as_str().unwrap().to_string(), o["first_in_grid"].clone()))
            .collect()
    };
    let rounded = |v: &serde_json::Value| v.as_f64().map(|t| (t * 10.0).round() / 10.0);
    let bayes = in_grid(0);
    assert_eq!(bayes[0].0, "walker_a");
    assert_eq!(rounded(&bayes[0].1), Some(1.2));
    assert_eq!(
        (bayes[1].0.as_str(), &bayes[1].1),
        ("walker_b", &serde_json::Value::Null)
    );
    assert!(
        in_grid(1).iter().all(|(_, t)| t.is_null()),
        "Dempster's grid never decides them"
    );
    for point in 0..2 {
        let sweep = &results["sweep"][point];
        assert_eq!(sweep["experiment"], "world");
        assert!(sweep["counts"]["steps"].as_u64().unwrap() > 0);
        assert_eq!(sweep["semantic"]["objects"]["relevant"], 2);
        assert!(sweep["metrics"]["occupied_recall"].is_number());
        assert!(sweep["metrics"]["objects_never_known"].is_number());
        assert!(sweep["metrics"].get("packet_delivery_ratio").is_none());
        assert!(sweep["metrics"]["semantic_packet_delivery_ratio"].is_number());
    }
    // The report lists the road users with their time in the grid.
    let html = unescape_html(&read(&out.join("report.html")));
    assert!(
        html.contains("in grid (s)"),
        "the report's object table has the grid's times"
    );
    assert!(html.contains("Relevant road users by how the ego came to know them"));
    assert!(html.contains("Occupied-cell recall by distance"));
}

/// A car no sensor sees, following a cooperator over a perfect radio
/// (`footprint-trail.yaml` in a joint world): the cooperator's old footprints
/// are not held, and the newest, up to a message period behind it, is
/// credited to the cooperator alone, so the car never comes into the ego's
/// fused grid and has no grid_lead, at any message rate; the cooperator,
/// which reports itself, does.
#[test]
fn a_car_in_a_cooperator_s_wake_never_comes_into_the_grid() {
    let fixture = read(&root().join("tests/fixtures/valid/joint-footprint-trail.yaml"));
    let radio = "v2x: { latency: 0.02, channel: { model: ideal } }";
    assert!(fixture.contains(radio));
    for rate in [10, 1] {
        let tmp = temp_dir();
        let (file, out) = (tmp.path().join("trail.yaml"), tmp.path().join("out"));
        let messages =
            format!("v2x: {{ latency: 0.02, channel: {{ model: ideal }}, messages: {{ rate_hz: {rate} }} }}");
        std::fs::write(&file, fixture.replace(radio, &messages)).unwrap();
        let run = sightline(["run", arg(&file), "--out", arg(&out)]);
        run.assert_exit(1);
        let results = read_json(&out.join("results.json"));
        let records = results["sweep"][0]["semantic"]["objects"]["records"]
            .as_array()
            .unwrap();
        let first_in_grid = |id: &str| &records.iter().find(|o| o["id"] == id).unwrap()["first_in_grid"];
        assert_eq!(first_in_grid("car1"), &serde_json::Value::Null, "{rate} Hz");
        assert!(first_in_grid("cav1").is_number(), "{rate} Hz");
        assert_eq!(verdict(&results, "GRID-LEAD").0, "fail", "{rate} Hz");
        assert!(
            run.stdout
                .contains("had no grid_lead (never in the ego's fused grid: car1)"),
            "{rate} Hz: {run}"
        );
    }
}

/// The bundled junction runs the fused grid and the semantic pipeline in one
/// world: the pedestrians near the ego are judged by either, and the
/// recording holds both models' steps, one record of signals a step.
#[test]
fn the_bundled_joint_junction_runs_both_models_in_one_world() {
    let run = junction_run();
    let results = &run.results;
    assert_eq!(results["verdict"], "pass");
    let pedestrians = requirement(results, "JNT-PED-01");
    assert!(pedestrians["n"].as_u64().unwrap() >= 2, "{pedestrians}");
    for point in results["sweep"].as_array().unwrap() {
        let semantic = &point["semantic"];
        assert!(
            semantic["counts"]["generated"].as_u64().unwrap() > 0,
            "generated traffic"
        );
        let records = semantic["objects"]["records"].as_array().unwrap();
        assert!(records.iter().any(|o| o["first_in_grid"].is_number()));
        assert!(records.iter().all(|o| o.get("first_in_grid").is_some()));
        for metric in [
            "blind_recall",
            "grid_packet_delivery_ratio",
            "semantic_packet_delivery_ratio",
        ] {
            assert!(point["metrics"][metric].is_number(), "{metric}");
        }
    }
    let html = unescape_html(&run.report);
    for shown in [
        "Messages to the ego by RSU–ego distance",
        "in grid (s)",
        "Fused occupancy",
    ] {
        assert!(html.contains(shown), "the report lacks {shown:?}");
    }
    let channels = channels(&run.recording);
    let steps = 200;
    for topic in ["/sightline/speeds", "/sightline/signals"] {
        assert_eq!(channels[topic].count, steps, "{topic}: one per step");
    }
    for topic in [
        "/fusion/grid",
        "/semantic/messages",
        "/v2x/packets",
        "/semantic/objects",
    ] {
        assert!(channels.contains_key(topic), "the recording lacks {topic}");
    }
    let signals = messages(&run.recording, "/sightline/signals");
    assert!(signals.iter().all(|s| s["semantic"].is_object()));
    // The recorded point's steps add up to its grid's counts and its messages.
    let point = &results["sweep"][results["recording"]["point"].as_u64().unwrap() as usize];
    let summed = |part: &str, count: &str| -> u64 { signals.iter().filter_map(|s| s[part][count].as_u64()).sum() };
    assert_eq!(Some(summed("cells", "occupied")), point["counts"]["occupied"].as_u64());
    assert_eq!(
        Some(summed("semantic", "messages")),
        point["semantic"]["counts"]["messages"].as_u64()
    );
}

/// The pedestrian requirement of the bundled junction can fail, and the
/// RSU's and the cooperating car's grids are what hold it: with the ego's
/// sensor cut to 12 m, the Bayesian grid knows each pedestrian before the ego
/// sees it (their shared grids) and the requirement holds at that point; with
/// the radio dead (a receiver no packet reaches), each pedestrian comes into
/// the grid when the ego sees it, too late, and the requirement fails.
#[test]
fn the_pedestrian_requirement_fails_without_the_shared_grids() {
    let tmp = temp_dir();
    let bundled = read(Path::new(JUNCTION));
    let short_sighted = bundled.replacen("    range: 80\n    fov_deg: 70", "    range: 12\n    fov_deg: 70", 1);
    let dead = short_sighted.replacen("sensitivity_dbm: -90", "sensitivity_dbm: 0", 1);
    assert!(
        short_sighted != bundled && dead != short_sighted,
        "the variants change the scenario"
    );
    let run = |name: &str, text: &str| {
        let (file, out) = (tmp.path().join(format!("{name}.yaml")), tmp.path().join(name));
        std::fs::write(&file, text).unwrap();
        sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);
        read_json(&out.join("results.json"))
    };
    let (radio, no_radio) = (run("radio", &short_sighted), run("dead", &dead));
    let bayes = |results: &serde_json::Value| {
        let point = requirement(results, "JNT-PED-01")["points"][0].clone();
        assert_eq!(point["label"], "fusion.method=bayes");
        assert_eq!(point["n"], 2, "both declared pedestrians are judged");
        (
            point["verdict"].as_str().unwrap().to_string(),
            point["value"].as_f64().unwrap(),
        )
    };
    let ((with, lead_with), (without, lead_without)) = (bayes(&radio), bayes(&no_radio));
    assert_eq!((with.as_str(), without.as_str()), ("pass", "fail"));
    assert!(lead_without < lead_with, "{lead_without} < {lead_with}");
    assert_eq!(requirement(&no_radio, "JNT-PED-01")["verdict"], "fail");
    assert_eq!(requirement(&no_radio, "JNT-GPDR-01")["value"], 0.0, "no grid arrives");
    // Road user by road user: in the grid before the ego's own first sight
    // with the radio, at it without.
    let times = |results: &serde_json::Value| -> Vec<(f64, f64)> {
        results["sweep"][0]["semantic"]["objects"]["records"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|o| o["id"] == "ped_south" || o["id"] == "ped_north")
            .map(|o| (o["first_in_grid"].as_f64().unwrap(), o["first_seen"].as_f64().unwrap()))
            .collect()
    };
    let (shared, own) = (times(&radio), times(&no_radio));
    assert_eq!((shared.len(), own.len()), (2, 2));
    assert!(shared.iter().all(|(grid, seen)| grid < seen), "{shared:?}");
    assert!(own.iter().all(|(grid, seen)| (grid - seen).abs() < 1e-9), "{own:?}");
}

/// Shards of a joint world (its two points share one simulation) merge into
/// the unsharded evidence.
#[test]
fn a_joint_world_merges_from_its_shards() {
    let tmp = temp_dir();
    let normalised = |dir: &Path, file: &Path| {
        let text = read(&dir.join(file));
        match file.extension().and_then(|e| e.to_str()) {
            Some("json" | "html") => normalise_execution(&text),
            Some("xml") => normalise_junit_times(&text),
            _ => text,
        }
    };
    let same = |a: &Path, b: &Path| {
        assert_eq!(files_under(a), files_under(b));
        for file in files_under(a) {
            assert!(
                normalised(a, &file) == normalised(b, &file),
                "{} differs",
                file.display()
            );
        }
    };
    let whole = tmp.path().join("whole");
    sightline(["run", WALKERS, "--out", arg(&whole)]).assert_exit(1);
    let parts: Vec<_> = (1..=2)
        .map(|k| {
            let dir = tmp.path().join(format!("shard-{k}"));
            let shard = format!("{k}/2");
            sightline(["run", WALKERS, "--shard", &shard, "--out", arg(&dir)]).assert_exit(0);
            dir
        })
        .collect();
    let merged = tmp.path().join("merged");
    sightline(["merge", "--out", arg(&merged), arg(&parts[0]), arg(&parts[1])]).assert_exit(1);
    same(&whole, &merged);
}
