//! The semantic pipeline through the CLI on small scenes worked out by hand
//! (found by session 23's outside check of the semantic pipeline).

use crate::support::{arg, read_json, requirement, sightline, temp_dir, verdict};

/// The results.json of running `fixture` (a file of tests/fixtures/valid/),
/// which must exit with `exit`.
fn results(fixture: &str, exit: i32) -> serde_json::Value {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let scenario = format!("tests/fixtures/valid/{fixture}");
    sightline(["run", scenario.as_str(), "--out", arg(&out)]).assert_exit(exit);
    read_json(&out.join("results.json"))
}

/// The ego drives east at 10 m/s past an RSU at (110, 10) whose sensors see
/// six standing pedestrians for the whole run (14 s, 140 cycles). The ego is
/// within the RSU's 100 m in 129 cycles, but over the lossy link its first
/// plan reaches the RSU only after 38 of them (91 cycles with a plan, 546
/// object-cycles); the RSU sends 378 object-cycles in all (the outside
/// auditor's count from the recording). The 38 cycles before the first plan
/// count against the share: 378 / (129 × 6) = 0.488 (they were left out:
/// 378 / 546 = 0.692, a wrong PASS).
#[test]
fn shares_count_the_cycles_before_the_rsu_first_hears_the_ego() {
    let results = results("share-before-plan.yaml", 1);
    let (status, value, n) = verdict(&results, "SHARE");
    assert_eq!((status.as_str(), n), ("fail", Some(774)));
    assert!((value.unwrap() - 378.0 / 774.0).abs() < 1e-12, "{value:?}");
    assert_eq!(verdict(&results, "LSHARE"), ("pass".to_string(), Some(0.0), Some(774)));
}

/// `shares_over: all`: every one of the 140 cycles counts, 840 object-cycles
/// (it gave 546, the same as `ego_in_range`): 378 / 840 = 0.45.
#[test]
fn shares_over_all_count_every_cycle() {
    let results = results("share-all-cycles.yaml", 1);
    let (status, value, n) = verdict(&results, "SHARE");
    assert_eq!((status.as_str(), n), ("fail", Some(840)));
    assert!((value.unwrap() - 0.45).abs() < 1e-12, "{value:?}");
}

/// `shares_over: all` with the ego entering the scene at 4 s: the 40 cycles
/// before it (240 object-cycles of the six pedestrians) count too, against
/// the share, as the RSU tells an absent ego nothing: n = 140 × 6 = 840, of
/// which the RSU sent 189 once the ego was there (n was 600 without them, a
/// share of 0.315 instead of 0.225).
#[test]
fn shares_over_all_count_the_cycles_without_the_ego() {
    let results = results("share-all-ego-late.yaml", 1);
    let counts = &results["sweep"][0]["counts"];
    assert_eq!(
        (counts["perceived"].as_u64(), counts["transmitted"].as_u64()),
        (Some(840), Some(189))
    );
    let (status, value, n) = verdict(&results, "SHARE");
    assert_eq!((status.as_str(), n), ("fail", Some(840)));
    assert!((value.unwrap() - 189.0 / 840.0).abs() < 1e-12, "{value:?}");
}

/// A car (`hop`, from a SUMO trace) drives 1 m beside the ego's path within
/// d_min of it, leaves the scene at 2.1 s and comes back at 4.0 s, again within
/// d_min: two close approaches, neither flagged (the RSU sees nothing of it).
/// Back in the scene it kept the `close` of before it left, so the second
/// approach was not counted: missed_criticals 1, a PASS of "at most 1".
#[test]
fn a_road_user_back_in_the_scene_within_d_min_is_a_new_close_approach() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    sightline(["run", "tests/fixtures/valid/close-again.yaml", "--out", arg(&out)]).assert_exit(1);
    let results = read_json(&out.join("results.json"));
    assert_eq!(verdict(&results, "MISS"), ("fail".to_string(), Some(2.0), Some(2)));
    let (status, value, n) = verdict(&results, "WT");
    assert_eq!((status.as_str(), value, n), ("fail", None, Some(2)));
    // Both approaches listed, by road user and step, and named in the verdict.
    let approaches = &results["sweep"][0]["counts"]["approaches"];
    assert_eq!(
        approaches,
        &serde_json::json!([
            { "run": 0, "id": "hop", "at": 0.0, "flagged": null, "warning_time": null },
            { "run": 0, "id": "hop", "at": 4.0, "flagged": null, "warning_time": null },
        ])
    );
    let message = requirement(&results, "WT")["message"].as_str().unwrap();
    assert!(
        message.ends_with("(never flagged: hop at 0 s, hop at 4 s)"),
        "{message}"
    );
    // The report lists them too, under the counts.
    let report = std::fs::read_to_string(out.join("report.html")).unwrap();
    let table = report
        .split("Close approaches, the least warned first: 2 of 2 (2 in results.json)")
        .nth(1)
        .expect("a table of the close approaches");
    let rows = table.split("</tbody>").next().unwrap();
    let hop = r#"<td class="text">0</td><td class="text">hop</td>"#;
    assert_eq!(rows.matches(hop).count(), 2, "{rows}");
    assert!(
        rows.contains(r#"<td class="num">4</td><td class="num">—</td><td class="num">—</td>"#),
        "{rows}"
    );
}

/// PETs of whole steps (engine/tests/criticality.rs works the scene out): the
/// lead's 12 steps of 0.1 s are 1.2 s and the crossing car's 22 steps 2.2 s,
/// exactly the decimals, so each holds at equality either way. As a float
/// difference of step times the lead's was 1.1999999999999997 and
/// `at_least: 1.2` failed by 2.2e-16.
#[test]
fn durations_of_whole_steps_hold_at_equality() {
    let results = results("pet-whole-steps.yaml", 0);
    assert_eq!(verdict(&results, "PET-EQ").1, Some(1.2));
    assert_eq!(verdict(&results, "MINPET-EQ").1, Some(1.2));
    assert_eq!(verdict(&results, "PET-EQ-MAX").1, Some(2.2));
    assert_eq!(verdict(&results, "PET-EQ-MIN").1, Some(2.2));
}

/// Two pedestrians walk the crosswalk at x = 80 side by side in one spot
/// (twin_a and twin_b on the same path). Each contains the other's centre, so
/// the one ray to either ended inside the other and neither was ever seen
/// (both warned_never_seen: NEVER-SEEN failed on 2); 1 m apart (x = 81) they
/// were seen. A body that contains the target's centre no longer blocks the
/// ray to it: both are seen (at 5.1 s) and NEVER-SEEN holds.
#[test]
fn a_road_user_in_the_same_spot_does_not_hide_the_other() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    sightline(["run", "tests/fixtures/valid/twins-one-spot.yaml", "--out", arg(&out)]).assert_exit(0);
    let results = read_json(&out.join("results.json"));
    let records = results["sweep"][0]["objects"]["records"].as_array().unwrap();
    for twin in ["twin_a", "twin_b"] {
        let record = records
            .iter()
            .find(|r| r["id"] == twin)
            .unwrap_or_else(|| panic!("no {twin}"));
        assert!(record["first_seen"].as_f64().is_some(), "{twin} never seen: {record}");
    }
}
