//! junit.xml: one test suite per scenario, one test case per requirement and sweep
//! point. The counts on `<testsuites>` and `<testsuite>` come from quick-junit,
//! which derives them from the test cases it holds.

use crate::results::{Results, Status};
use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};

/// The JUnit report of one scenario's results.
pub fn junit(results: &Results) -> Report {
    let mut suite = TestSuite::new(results.scenario.name.as_str());
    suite.add_property(("scenario", results.scenario.path.as_str()));
    suite.add_property(("scenario_sha256", results.scenario.sha256.as_str()));
    if let Some(seed) = results.seed {
        suite.add_property(("seed", seed.to_string().as_str()));
    }
    suite.add_property((
        "tool",
        format!("{} {} ({})", results.tool.name, results.tool.version, results.tool.git).as_str(),
    ));
    for requirement in &results.requirements {
        let check = format!("{}:{}", requirement.check.kind, requirement.check.name);
        for point in &requirement.points {
            let name = if point.label.is_empty() {
                requirement.id.clone()
            } else {
                format!("{} [{}]", requirement.id, point.label)
            };
            let accepted = requirement.accept_not_exercised.as_deref();
            let mut status = match (point.verdict, accepted) {
                (Status::Pass, _) => TestCaseStatus::success(),
                (Status::NotExercised, Some(_)) => TestCaseStatus::skipped(),
                (Status::NotExercised | Status::Fail, _) => TestCaseStatus::non_success(NonSuccessKind::Failure),
                (Status::Error, _) => TestCaseStatus::non_success(NonSuccessKind::Error),
            };
            let value = point.value.map_or("none".to_string(), |v| format!("{v:?}"));
            let margin = point.margin.map_or("none".to_string(), |v| format!("{v:?}"));
            let n = point.n.map_or("unknown".to_string(), |n| n.to_string());
            let relation = format!("{} {:?}", requirement.check.relation, requirement.check.threshold);
            if point.verdict != Status::Pass {
                let mut message = format!(
                    "{} {}: measured {value} ({}); threshold {relation}; margin {margin}; n = {n}: {}",
                    point.verdict.words(),
                    name,
                    point.measured,
                    point.message
                );
                if let (Status::NotExercised, Some(reason)) = (point.verdict, accepted) {
                    message.push_str(&format!(" (accepted: {reason})"));
                }
                status
                    .set_type(point.verdict.name())
                    .set_message(message)
                    .set_description(format!(
                        "{}\ncheck: {check}\nmeasured: {value} ({})\nthreshold: {relation}\nmargin: {margin}\nn: {n}\n",
                        requirement.text, point.measured
                    ));
            }
            let mut case = TestCase::new(name, status);
            case.set_classname(results.scenario.path.as_str());
            case.add_property(("requirement", requirement.id.as_str()));
            case.add_property(("line", requirement.line.to_string().as_str()));
            case.add_property(("check", check.as_str()));
            case.add_property(("verdict", point.verdict.name()));
            case.add_property(("value", value.as_str()));
            case.add_property(("margin", margin.as_str()));
            case.add_property(("n", n.as_str()));
            suite.add_test_case(case);
        }
    }
    let mut report = Report::new("sightline");
    report.add_test_suite(suite);
    report
}
