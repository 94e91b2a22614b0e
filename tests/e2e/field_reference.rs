//! The bundled field experiment (seed 001) against an independent
//! implementation: `bench/numpy_s1.py`, vectorised numpy written from the
//! docs, with numpy's own random stream. The two cannot agree to the cell, so
//! every count and mean of every point the reference computes must agree
//! within sampling error (docs/findings/seed-001.md, "An independent
//! implementation").

use std::path::Path;
use std::process::{Child, Command, Stdio};

use serde_json::Value;

use crate::bundled::field;
use crate::support::{root, setting, tool};

/// The Python with numpy (bench/requirements.txt); `.ci/run` sets it.
const PYTHON_VAR: &str = "SIGHTLINE_NUMPY_PYTHON";

/// The bundled scenario's γ, readings, rules and the methods the reference
/// computes (all but the pairwise fold).
const GAMMAS: [&str; 5] = ["6", "8", "10", "12", "14"];
const ERROR_MODELS: [&str; 2] = ["dirichlet_mean", "wrong_label"];
const RULES: [&str; 2] = ["margin", "exceeds"];
const METHODS: [&str; 5] = [
    "Baseline",
    "Proposed",
    "Proposed, mean-one weights",
    "Proposed, nearest-one weights",
    "Bayes",
];

/// The largest difference accepted, in standard errors of the difference.
/// The standard errors are upper bounds (below), and both streams are fixed,
/// so the test is deterministic: a change of either stream redraws it, and
/// with 680 such comparisons the chance that one then passes 5 is about 4 in 10 000.
const Z_MAX: f64 = 5.0;

/// The counts each point's decisions are compared on.
const COUNTS: [&str; 5] = [
    "below_threshold",
    "correct",
    "false_alarms",
    "missed_detections",
    "decided_unknown",
];

/// Every point the reference computes: counts within [`Z_MAX`] binomial
/// standard errors of the difference, √(2 n p̄(1 − p̄)) with p̄ the two counts'
/// mean share of the n cells (cells are independent, and a sum of independent
/// Bernoulli trials of unequal p varies less than that); means within
/// [`Z_MAX`] standard errors from the reference's standard deviation over
/// cells, √2 · sd / √n (an upper bound too: it includes how the cells' own
/// means differ); the weighted cells, which depend on the geometry alone,
/// equal. 100 points: 680 figures within sampling error, 60 equal.
///
/// Skipped locally unless `SIGHTLINE_NUMPY_PYTHON` names a Python with numpy;
/// with `CI` set a missing one fails the test.
#[test]
fn the_bundled_field_experiment_agrees_with_an_independent_numpy_implementation() {
    let Some(python) = tool(PYTHON_VAR, "a Python with numpy (bench/requirements.txt)") else {
        return;
    };
    // Both readings at once, while the bundled run (shared with other tests) runs.
    let references: Vec<(&str, Child)> = ERROR_MODELS
        .iter()
        .map(|&model| (model, reference(Path::new(&python), model)))
        .collect();
    let results = &field().results;
    let mut compared = 0;
    let mut points = 0;
    for (model, child) in references {
        let output = child.wait_with_output().expect("numpy_s1.py ran");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            output.status.success(),
            "numpy_s1.py --error-model {model} failed:\n{stderr}"
        );
        let lines = String::from_utf8(output.stdout).expect("numpy_s1.py prints UTF-8");
        for line in lines.lines() {
            let numpy: Value = serde_json::from_str(line).expect("numpy_s1.py prints JSON lines");
            for point in results["sweep"].as_array().expect("a sweep") {
                let of = |path| setting(point, path).unwrap_or_else(|| panic!("{}: no {path}", point["label"]));
                let fusion = point["fusion"].as_str().expect("a fusion label");
                if of("field.masses.error_model").as_str() != Some(model)
                    || of("field.masses.gamma").as_f64() != numpy["gamma"].as_f64()
                    || !METHODS.contains(&fusion)
                {
                    continue;
                }
                let rule = of("decision.rule").as_str().expect("a rule");
                compared += compare(point, &numpy[fusion], rule, &numpy);
                points += 1;
            }
        }
    }
    let sets = GAMMAS.len() * ERROR_MODELS.len() * RULES.len();
    assert_eq!(points, sets * METHODS.len(), "points compared");
    // Five counts a point; two means of each of the four Dempster methods,
    // one of Bayes (no conflict); the weighted cells of the three hybrid ones.
    assert_eq!(
        compared,
        sets * (METHODS.len() * COUNTS.len() + 4 * 2 + 1 + 3),
        "figures compared"
    );
}

/// `bench/numpy_s1.py` on every γ of the bundled scenario under one reading,
/// started.
fn reference(python: &Path, error_model: &str) -> Child {
    Command::new(python)
        .arg(root().join("bench/numpy_s1.py"))
        .args(["--seed", "2", "--error-model", error_model, "--gamma"])
        .args(GAMMAS)
        .arg("--methods")
        .args(METHODS)
        .arg("--rules")
        .args(RULES)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("failed to start {}: {e}", python.display()))
}

/// Compares one point of results.json with the reference's method `numpy`
/// under `rule` (`run` is the reference's whole line, for the weighted cells);
/// returns how many figures it compared.
fn compare(point: &Value, numpy: &Value, rule: &str, run: &Value) -> usize {
    let label = point["label"].as_str().expect("a label");
    let metric = |name: &str| {
        point["metrics"][name]
            .as_f64()
            .unwrap_or_else(|| panic!("{label}: no {name}"))
    };
    let cells = point["samples"]["accuracy"].as_f64().expect("the accuracy's n");
    assert_eq!(cells, 1e6, "{label}: every cell observed");
    let mut compared = 0;
    for count in COUNTS {
        let ours = if count == "correct" {
            (metric("accuracy") * cells).round()
        } else {
            metric(count)
        };
        let theirs = numpy[rule][count]
            .as_f64()
            .unwrap_or_else(|| panic!("numpy: no {rule}.{count}"));
        let share = (ours + theirs) / (2.0 * cells);
        let error = (2.0 * cells * share * (1.0 - share)).sqrt();
        assert!(
            ours == theirs || (ours - theirs).abs() <= Z_MAX * error,
            "{label}: {count} {ours} against numpy's {theirs}, {:.1} standard errors apart",
            (ours - theirs) / error
        );
        compared += 1;
    }
    for (mean, spread) in [("mean_conflict", "sd_conflict"), ("mean_uncertainty", "sd_uncertainty")] {
        let Some(theirs) = numpy[mean].as_f64() else {
            continue;
        };
        let ours = metric(mean);
        let error = numpy[spread].as_f64().expect("a spread beside each mean") * (2.0 / cells).sqrt();
        assert!(
            (ours - theirs).abs() <= Z_MAX * error,
            "{label}: {mean} {ours} against numpy's {theirs}, {:.1} standard errors apart",
            (ours - theirs) / error
        );
        compared += 1;
    }
    if point["method"] == "hybrid" {
        assert_eq!(
            metric("weighted_cells"),
            run["weighted_cells"].as_f64().unwrap(),
            "{label}"
        );
        compared += 1;
    }
    compared
}
