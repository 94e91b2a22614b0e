//! Calibration of the fused grid (issue 16, part 5) through the CLI: a
//! requirement on `brier_score` is judged with its n, results.json carries the
//! reliability table, and the report draws the diagram.
// See: issue 16, "Calibration".

use crate::support::{arg, read, read_json, requirement, sightline, temp_dir};

/// One 0.1 s step on a 1 m grid: a wall hides the north from the ego; `cav`,
/// connected, sees a car 10 m east of it that the ego cannot. Each fused cell
/// is seen by one agent only, so its p is the inverse model's (0.3 free, 0.7
/// detected) and errs by 0.3: the Brier score is 0.09.
const SCENE: &str = include_str!("../fixtures/templates/wall-and-cooperator.yaml.in");

/// The car 10 m east of `cav`, hidden from the ego.
const HIDDEN_CAR: &str = "  - { id: car, kind: car, route: [we], start: { offset: 40 }, speed: { target: 0 } }";

const REQUIREMENTS: &str = "requirements:
  - { id: CAL-OK, text: Calibrated enough., check: { metric: brier_score, at_most: 0.1 } }
  - { id: CAL-TIGHT, text: Better calibrated., check: { metric: brier_score, at_most: 0.05 } }
";

#[test]
fn a_brier_score_requirement_is_judged_with_its_n_and_the_report_draws_the_diagram() {
    let tmp = temp_dir();
    let (file, out) = (tmp.path().join("calibration.yaml"), tmp.path().join("evidence"));
    std::fs::write(
        &file,
        SCENE.replace("{others}", HIDDEN_CAR).replace("{rest}", REQUIREMENTS),
    )
    .unwrap();
    sightline(["run", arg(&file), "--out", arg(&out)]).assert_exit(1);

    let results = read_json(&out.join("results.json"));
    let calibration = &results["sweep"][0]["counts"]["calibration"];
    let n = calibration["cells"].as_u64().unwrap();
    // The fused cells less the cooperator's own 8 (self-report).
    assert_eq!(n, results["sweep"][0]["audit"]["cells"].as_u64().unwrap() - 8);
    let brier = calibration["brier_score"].as_f64().unwrap();
    assert!((brier - 0.09).abs() < 1e-9, "{brier}");
    let bins = calibration["bins"].as_array().unwrap();
    assert_eq!(bins.len(), 10);
    assert_eq!(
        (&bins[7]["cells"], &bins[7]["observed_frequency"]),
        (&8.into(), &1.0.into())
    );
    assert_eq!(bins[3]["cells"].as_u64().unwrap(), n - 8);
    assert_eq!(bins[5]["mean_probability"], serde_json::Value::Null);

    for (id, verdict) in [("CAL-OK", "pass"), ("CAL-TIGHT", "fail")] {
        let r = requirement(&results, id);
        assert_eq!((&r["verdict"], &r["n"]), (&verdict.into(), &n.into()), "{id}");
    }
    let report = read(&out.join("report.html"));
    assert!(
        report.contains(&format!("Brier score 0.0900, n = {n} cell-steps")),
        "the reliability diagram's caption"
    );
}
