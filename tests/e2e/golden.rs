//! Golden evidence: the fixtures' results.json and junit.xml, redacted of the tool
//! version and git revision, against `tests/golden/<scenario>/`. Any other change
//! to the evidence shows up here for review. Refresh with `SIGHTLINE_BLESS=1
//! cargo test --test e2e golden::`, never by hand.

use crate::support::{
    FAILING, SHARED_POINT, SMALL_FIELD, arg, assert_matches_file, read, redact_junit, redact_results_json, sightline,
    temp_dir,
};

/// Runs `scenario` and compares its redacted evidence with `tests/golden/<golden>/`.
fn assert_golden(scenario: &str, golden: &str, code: i32) {
    let tmp = temp_dir();
    let out = tmp.path().join("out");
    sightline(["run", scenario, "--out", arg(&out)]).assert_exit(code);
    assert_matches_file(
        &format!("tests/golden/{golden}/results.json"),
        &redact_results_json(&read(&out.join("results.json"))),
    );
    assert_matches_file(
        &format!("tests/golden/{golden}/junit.xml"),
        &redact_junit(&read(&out.join("junit.xml"))),
    );
}

#[test]
fn small_field_evidence_matches_golden() {
    assert_golden(SMALL_FIELD, "small-field", 0);
}

#[test]
fn failing_evidence_matches_golden() {
    assert_golden(FAILING, "accuracy-under-noise", 1);
}

#[test]
fn shared_point_evidence_matches_golden() {
    assert_golden(SHARED_POINT, "shared-point", 0);
}
