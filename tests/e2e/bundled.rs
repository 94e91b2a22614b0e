//! The bundled seed-001 scenario, end to end: 1000 × 1000 cells, 60 sweep points.
//! It takes a while, so it runs once and checks only the shape of the evidence.

use crate::support::{arg, assert_evidence_files, read_json, sightline, temp_dir};

#[test]
fn evidential_field_scenario_runs_end_to_end() {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    let scenario = "scenarios/evidential-field.yaml";
    let outcome = sightline(["run", scenario, "--out", arg(&out)]);
    outcome.assert_exit(0);
    assert_evidence_files(&out);
    let results = read_json(&out.join("results.json"));
    assert_eq!(results["format"], "sightline-results/1");
    assert_eq!(results["verdict"], "pass");
    assert_eq!(results["scenario"]["path"], scenario);
    assert_eq!(results["sweep"]["points"].as_array().map(Vec::len), Some(60));
    assert_eq!(results["references"].as_array().map(Vec::len), Some(10));
    for reference in results["references"].as_array().unwrap() {
        let points = reference["points"].as_array().unwrap();
        // Each Table III figure matches one γ and one method, under both error models.
        assert_eq!(points.len(), 2, "{reference:#}");
        assert!(points.iter().all(|p| p["measured"].is_number()), "{reference:#}");
    }
}
