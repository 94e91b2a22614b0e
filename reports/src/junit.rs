//! junit.xml: one test suite per scenario, one test case per requirement and sweep
//! point. The counts on `<testsuites>` and `<testsuite>` come from quick-junit,
//! which derives them from the test cases it holds.

use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
use sightline_oracles::Status;

use crate::results::Results;

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
        for point in &requirement.points {
            let name = if point.label.is_empty() {
                requirement.id.clone()
            } else {
                format!("{} [{}]", requirement.id, point.label)
            };
            let mut status = match point.verdict {
                Status::Pass => TestCaseStatus::success(),
                Status::Fail => TestCaseStatus::non_success(NonSuccessKind::Failure),
                Status::Error => TestCaseStatus::non_success(NonSuccessKind::Error),
            };
            status
                .set_type(format!("{}:{}", requirement.check.kind, requirement.check.name))
                .set_message(point.message.as_str())
                .set_description(format!(
                    "{}\nmeasured: {}\nthreshold: {} ({})\n",
                    requirement.text,
                    point.value.map_or("undefined".to_string(), |v| v.to_string()),
                    requirement.check.threshold,
                    requirement.check.relation
                ));
            let mut case = TestCase::new(name, status);
            case.set_classname(results.scenario.path.as_str());
            case.add_property(("requirement", requirement.id.as_str()));
            case.add_property(("line", requirement.line.to_string().as_str()));
            suite.add_test_case(case);
        }
    }
    let mut report = Report::new("sightline");
    report.add_test_suite(suite);
    report
}
