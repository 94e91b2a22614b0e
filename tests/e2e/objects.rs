//! The per-object record (issue 17, part 1) through the CLI: the hand-built
//! scene with one road user per category (its times are worked out in
//! `engine/tests/objects.rs`), judged on the counts by category, and the
//! bundled urban junction's road users counted by category.
// See: issue 17, "A per-object record".

use crate::bundled::{urban, urban_run};
use crate::support::{arg, read, read_json, requirement, sightline, temp_dir, unescape_html};

const FOUR: &str = "tests/fixtures/valid/four-road-users.yaml";

#[test]
fn each_category_is_listed_counted_and_judged() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    // walker_d goes unknown: OBJ-NEVER-01 (at most 0) fails on 1 of 4.
    sightline(["run", FOUR, "--out", arg(&out)]).assert_exit(1);
    let results = read_json(&out.join("results.json"));
    let never = requirement(&results, "OBJ-NEVER-01");
    assert_eq!(
        (&never["verdict"], &never["value"], &never["n"]),
        (&"fail".into(), &1.0.into(), &4.into())
    );
    let objects = &results["sweep"][0]["objects"];
    assert_eq!((&objects["relevant"], &objects["omitted"]), (&4.into(), &0.into()));
    for category in ["warned_before_seen", "warned_never_seen", "seen_first", "never_known"] {
        assert_eq!(objects["categories"][category], 1, "{category}");
    }
    let listed: Vec<(&str, &str)> = objects["records"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| (o["id"].as_str().unwrap(), o["category"].as_str().unwrap()))
        .collect();
    assert_eq!(
        listed,
        [
            ("walker_c", "seen_first"),
            ("car_b", "warned_never_seen"),
            ("walker_a", "warned_before_seen"),
            ("walker_d", "never_known"),
        ]
    );
    let metrics = &results["sweep"][0]["metrics"];
    assert_eq!(metrics["objects_seen_first"], 1.0);
    assert_eq!(results["sweep"][0]["samples"]["object_anticipation_median"], 2);
    assert_eq!(results["sweep"][0]["samples"]["anticipation_median"], 1);

    let report = unescape_html(&read(&out.join("report.html")));
    assert!(report.contains("Relevant road users by how the ego came to know them (n = 4 over the pooled runs)"));
    // Never known first in the report's table.
    let row = |id: &str| {
        report
            .find(&format!(">{id}<"))
            .unwrap_or_else(|| panic!("{id} in the report"))
    };
    assert!(row("walker_d") < row("car_b") && row("car_b") < row("walker_a") && row("walker_a") < row("walker_c"));
}

/// The category a record's own times give it, as the engine defines it.
fn category_of(record: &serde_json::Value) -> &'static str {
    match (record["first_v2x"].as_f64(), record["first_seen"].as_f64()) {
        (Some(told), Some(seen)) if told < seen => "warned_before_seen",
        (Some(_), None) => "warned_never_seen",
        (_, Some(_)) => "seen_first",
        (None, None) => "never_known",
    }
}

/// Every point of the bundled junction lists every relevant road user, never
/// seen ones included, each in the category its times give; the counts are
/// the metrics (per run, over five) with n the relevant road users, and ours
/// counts the never-seen road users the paper's anticipation leaves out.
#[test]
fn the_urban_junction_counts_its_road_users_by_category() {
    let results = urban();
    for point in results["sweep"].as_array().unwrap() {
        let objects = &point["objects"];
        let relevant = objects["relevant"].as_u64().unwrap();
        let records = objects["records"].as_array().unwrap();
        assert_eq!(objects["omitted"], 0, "the junction lists every relevant road user");
        assert_eq!(records.len() as u64, relevant);
        let count = |category: &str| records.iter().filter(|r| category_of(r) == category).count() as u64;
        for category in ["warned_before_seen", "warned_never_seen", "seen_first", "never_known"] {
            assert_eq!(
                objects["categories"][category].as_u64(),
                Some(count(category)),
                "{category}"
            );
            let metric = format!("objects_{category}");
            assert_eq!(point["metrics"][&metric].as_f64(), Some(count(category) as f64 / 5.0));
            assert_eq!(point["samples"][&metric].as_u64(), Some(relevant));
        }
        assert!(records.iter().all(|r| r["category"] == category_of(r)));
        assert!(
            count("warned_never_seen") > 0,
            "{}: never-seen road users are listed",
            point["label"]
        );
        let ours = point["samples"]["object_anticipation_median"].as_u64().unwrap();
        assert_eq!(ours, count("warned_before_seen") + count("warned_never_seen"));
        // No road user is connected (penetration 0), so only RSUs name them:
        // the paper's population is `warned_before_seen`, and its never-seen
        // count `warned_never_seen`.
        assert_eq!(
            point["samples"]["anticipation_median"].as_u64(),
            Some(count("warned_before_seen"))
        );
        assert_eq!(point["counts"]["never_seen"].as_u64(), Some(count("warned_never_seen")));
    }
    let html = unescape_html(&urban_run().report);
    assert!(html.contains("Relevant road users by how the ego came to know them"));
}
