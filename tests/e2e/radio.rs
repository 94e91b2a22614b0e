//! Collective perception over the radio (issue 16, part 1) through the CLI: a
//! dead radio leaves the ego alone, and a perfect one delivers a step late,
//! counted by hand on a static scene.
// See: issue 16, "The radio in the perception world".

use serde_json::Value;

use crate::support::{arg, read, read_json, requirement, sightline, temp_dir};

/// The wall scene of the self-report tests, run for 1 s (ten steps): `cav`,
/// behind the wall, sees a car 10 m east of it that the ego cannot.
fn scene(perception: &str, rest: &str) -> String {
    include_str!("../fixtures/templates/wall-and-cooperator.yaml.in")
        .replace("time: { duration: 0.1, step: 0.1 }", "time: { duration: 1, step: 0.1 }")
        .replace("perception: { ego: ego }", perception)
        .replace(
            "{others}",
            "  - { id: car, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 } }",
        )
        .replace("{rest}", rest)
}

/// Runs `text`, which has no requirements (so it exits 1: nothing judged),
/// and returns its single point's results.
fn point(text: &str) -> Value {
    let tmp = temp_dir();
    let (file, out) = (tmp.path().join("radio.yaml"), tmp.path().join("evidence"));
    std::fs::write(&file, text).unwrap();
    sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);
    let results = read_json(&out.join("results.json"));
    let mut point = results["sweep"][0].clone();
    point["report"] = read(&out.join("report.html")).into();
    point["assumptions"] = results["assumptions"].clone();
    point
}

const NO_REQUIREMENT: &str = "requirements: []";

#[test]
fn a_dead_radio_leaves_the_ego_alone() {
    let alone = point(&scene("perception: { ego: ego, cooperating: 1 }", NO_REQUIREMENT));
    // 23 dBm less 123 dBm: no shadowing draw reaches −90 dBm.
    let dead = point(&scene(
        "perception: { ego: ego }\nv2x: { channel: { tx_power_dbm: -100 } }",
        NO_REQUIREMENT,
    ));
    for metric in [
        "occupied_recall",
        "blind_recall",
        "occupied_precision",
        "occupied_recall_with_self_report",
        "fov_gain",
        "brier_score",
    ] {
        assert_eq!(
            (&dead["metrics"][metric], &dead["samples"][metric]),
            (&alone["metrics"][metric], &alone["samples"][metric]),
            "{metric}"
        );
    }
    // The ego alone misses the car and the cooperator behind the wall.
    assert_eq!(alone["metrics"]["occupied_recall"], 0.0);
    assert_eq!(alone["samples"]["occupied_recall"], 160);
    let radio = &dead["counts"]["radio"];
    assert_eq!((&radio["sent"], &radio["received"]), (&10.into(), &0.into()));
    assert_eq!(dead["metrics"]["packet_delivery_ratio"], 0.0);
    assert_eq!(dead["samples"]["packet_delivery_ratio"], 10);
    // Nothing fused: no message age, n = 0.
    assert_eq!(dead["metrics"].get("message_age_mean"), None);
    assert_eq!(dead["samples"]["message_age_mean"], 0);
    assert_eq!(alone["counts"]["radio"], Value::Null);
}

/// A perfect radio (`model: ideal`, no latency) on a static scene: `cav`'s
/// grid of step k is fused at step k + 1. At step 0 the ego holds nothing of
/// it: the car (8 cells) is missed and `cav`'s own body (8 cells), unreported,
/// is a road user to find, and missed too. From step 1 on the car is known and
/// `cav`'s body is self-report: recall is 9 × 8 / (16 + 9 × 8) = 72 / 88.
#[test]
fn a_perfect_radio_delivers_a_step_late() {
    let lossless = point(&scene("perception: { ego: ego }", NO_REQUIREMENT));
    assert_eq!(lossless["metrics"]["occupied_recall"], 1.0);
    assert_eq!(lossless["samples"]["occupied_recall"], 80);
    let ideal = point(&scene(
        "perception: { ego: ego }\nv2x: { channel: { model: ideal } }",
        NO_REQUIREMENT,
    ));
    assert_eq!(ideal["metrics"]["occupied_recall"], 72.0 / 88.0);
    assert_eq!(ideal["samples"]["occupied_recall"], 88);
    let radio = &ideal["counts"]["radio"];
    let sent = radio["sent"].as_u64().unwrap();
    // Every step's grid goes out whole, in the same number of 1100-byte messages.
    assert!(sent >= 10 && sent.is_multiple_of(10), "{sent}");
    assert_eq!(radio["received"], sent);
    assert!(radio["bytes"].as_u64().unwrap() <= sent * 1100);
    // The last step's messages are on their way when the run ends.
    assert_eq!(
        radio["ages"],
        serde_json::json!([{ "age": 0.1, "messages": sent - sent / 10 }])
    );
    assert_eq!(ideal["metrics"]["message_age_mean"], 0.1);
    assert_eq!(ideal["metrics"]["packet_delivery_ratio"], 1.0);
    // One sender in the scene for ten 0.1 s steps.
    let bytes = radio["bytes"].as_f64().unwrap();
    assert_eq!(ideal["metrics"]["bytes_per_second_per_agent"], bytes / 1.0);
    assert_eq!(radio["sender_steps"], 10);
    // The car sits 10 m from `cav`, and `cav`'s own body at step 0 on it:
    // every occupied cell-step is in the first band.
    let near = &ideal["counts"]["recall_by_distance"][0];
    assert_eq!((&near["occupied"], &near["detected"]), (&88.into(), &72.into()));
    let ids: Vec<&str> = ideal["assumptions"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|a| a["id"].as_str())
        .collect();
    for id in ["radio.grid-messages", "radio.step-delivery", "v2x.ideal"] {
        assert!(ids.contains(&id), "{id} in {ids:?}");
    }
    assert!(!ids.contains(&"world.lossless-exchange"));
    assert!(
        ideal["report"]
            .as_str()
            .unwrap()
            .contains("Occupied-cell recall by distance to the nearest cooperating agent")
    );
}

/// Selecting sends one message a step, no larger than the limit, the
/// sender's own body and its detections first: with room for little more than
/// them, the car is still known, from step 1 on.
#[test]
fn selecting_sends_one_message_with_the_detections_first() {
    let selected = point(&scene(
        "perception: { ego: ego }\nv2x: { channel: { model: ideal }, messages: { oversize: select, max_bytes: 250 } }",
        NO_REQUIREMENT,
    ));
    let radio = &selected["counts"]["radio"];
    assert_eq!(radio["sent"], 10);
    assert!(radio["bytes"].as_u64().unwrap() <= 2500);
    assert_eq!(selected["metrics"]["occupied_recall"], 72.0 / 88.0);
}

/// A cooperator's footprint says where it is: a newer one replaces the older.
/// Held until `max_age`, the footprints of a moving cooperator left a trail
/// that fusion read as occupied and credited to the car following in it,
/// which no sensor sees (`blind_recall` 0.94, a wrong PASS). Only the newest
/// is held; and even the newest, at one message a second, lies up to about
/// 1.1 s (9 m) behind the cooperator, on the car: a reported footprint detects no
/// one but its sender (`blind_recall` was 0.51 at 1 Hz, a wrong PASS of a
/// half-recall requirement). The car is never known, at any message rate.
#[test]
fn a_car_in_a_cooperator_s_wake_is_not_credited_with_its_old_footprints() {
    let fixture = read(&crate::support::root().join("tests/fixtures/valid/footprint-trail.yaml"));
    let radio = "v2x: { latency: 0.02, channel: { model: ideal } }";
    assert!(fixture.contains(radio));
    for rate in [10, 2, 1] {
        let tmp = temp_dir();
        let (file, out) = (tmp.path().join("trail.yaml"), tmp.path().join("out"));
        let messages =
            format!("v2x: {{ latency: 0.02, channel: {{ model: ideal }}, messages: {{ rate_hz: {rate} }} }}");
        std::fs::write(&file, fixture.replace(radio, &messages)).unwrap();
        sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);
        let results = read_json(&out.join("results.json"));
        let point = &results["sweep"][0];
        // car1 is the only road user that does not cooperate, and the ego never sees it.
        let occupied = point["samples"]["occupied_recall"].as_u64().unwrap();
        assert!(occupied > 0);
        assert_eq!(point["samples"]["blind_recall"], occupied, "{rate} Hz");
        assert_eq!(point["metrics"]["blind_recall"], 0.0, "{rate} Hz");
        assert_eq!(point["metrics"]["occupied_recall"], 0.0, "{rate} Hz");
        // cav1's grids do arrive, its own body in them.
        assert_eq!(point["metrics"]["packet_delivery_ratio"], 1.0);
        assert!(point["metrics"]["occupied_recall_with_self_report"].as_f64().unwrap() > 0.0);
        let status = &requirement(&results, "HIDDEN")["verdict"];
        assert_eq!(status, "fail", "{rate} Hz");
    }
}

/// A message older than `max_age` when it arrives is dropped at once: it is
/// never fused, so it is no sample of the fused messages' age. Over a perfect
/// radio with a latency of `max_age`, every grid arrives 1.1 s after it was
/// sensed and the ego fuses none: the age metrics have nothing to judge
/// (they were 1.1 s over n = 69 messages, a wrong PASS of "at most 1.2 s"),
/// while every message still counts as delivered.
#[test]
fn messages_past_their_age_on_arrival_are_not_among_the_fused() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let run = sightline(["run", "tests/fixtures/valid/late-grids.yaml", "--out", arg(&out)]);
    run.assert_exit(1);
    let results = read_json(&out.join("results.json"));
    let point = &results["sweep"][0];
    assert_eq!(point["samples"]["message_age_mean"], 0);
    assert_eq!(point["metrics"]["message_age_mean"], Value::Null);
    assert_eq!(point["metrics"]["fov_gain"], 0.0);
    assert_eq!(point["metrics"]["packet_delivery_ratio"], 1.0);
    for id in ["AGE-MEAN", "AGE-P95"] {
        assert_eq!(requirement(&results, id)["verdict"], "not_exercised", "{id}");
    }
    assert_eq!(requirement(&results, "PDR")["verdict"], "pass");
}
