//! junit.xml: one test suite per scenario, one test case per requirement and
//! sweep point (`sightline run`) or per requirement (`sightline falsify`). The
//! counts on `<testsuites>` and `<testsuite>` come from quick-junit, which
//! derives them from the test cases it holds.
//!
//! What a CI server shows: a case's `classname` is the scenario's name as a
//! dotted identifier (`sightline.roundabout_six_cooperating_vehicles`), its
//! `file` and `line` the requirement's place in the scenario file, its `time`
//! the time simulating its point took, shared among the point's cases (a
//! share of the run's wall-clock time when the points were not timed). No published JUnit schema allows
//! `<properties>` in a `<testcase>` (Jenkins' junit-10.xsd, Ant's, JUnit 5's),
//! so each case's oracle (the check in words), measured value, threshold,
//! margin, n and message are `name: value`
//! lines of its `<system-out>`, which CI servers show beside the case, passing
//! cases too (each value on one line: a line feed in a requirement's text is
//! written `\n`, a backslash `\\`); the suite's `<properties>` name the scenario, its hash, the seed
//! and the tool. A suite is named by the scenario's name and its file, so two
//! scenarios of the same name are two suites.

use std::time::Duration;

use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};

use crate::Execution;
use crate::html::describe_check;
use crate::results::{Results, Status};

/// The JUnit report of one scenario's results.
pub fn junit(results: &Results) -> Report {
    let scenario = &results.scenario;
    let mut suite = new_suite(&scenario.name, &scenario.path, &scenario.sha256);
    if let Some(seed) = results.seed {
        suite.add_property(("seed", seed.to_string().as_str()));
    }
    let tool = &results.tool;
    suite.add_property((
        "tool",
        format!("{} {} ({})", tool.name, tool.version, tool.git).as_str(),
    ));
    let duration = Duration::from_secs_f64(results.execution.duration_seconds.max(0.0));
    let cases = results
        .requirements
        .iter()
        .flat_map(|r| r.points.iter().map(|p| p.point));
    let time = case_times(results.sweep.len(), cases, &results.execution);
    for requirement in &results.requirements {
        let check = format!("{}:{}", requirement.check.kind, requirement.check.name);
        // What the value and threshold below mean: for a share of seeds, the
        // per-seed bound and the share (the threshold is the share's).
        let oracle = describe_check(&requirement.check);
        let unit = requirement.check.unit;
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
            let shown = |v: Option<f64>| v.map_or("none".to_string(), |v| format!("{v:?}"));
            let (value, margin) = (shown(point.value), shown(point.margin));
            let n = point.n.map_or("unknown".to_string(), |n| n.to_string());
            let relation = format!("{} {:?}", requirement.relation(), requirement.threshold);
            if point.verdict != Status::Pass {
                let mut message = format!(
                    "{} {}: measured {value}{} ({}); threshold {relation}; margin {margin}; n = {n}: {}",
                    point.verdict.words(),
                    name,
                    if unit == "1" || point.value.is_none() {
                        String::new()
                    } else {
                        format!(" {unit}")
                    },
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
                        "{}\ncheck: {check}\noracle: {oracle}\nmeasured: {value} ({})\nthreshold: {relation}\nmargin: \
                         {margin}\nn: {n}\n",
                        one_line(&requirement.text),
                        point.measured
                    ));
            }
            let mut case = new_case(name, status, &scenario.name, &scenario.path, requirement.line);
            case.set_time(time(point.point));
            case.set_system_out(lines(&[
                ("requirement", requirement.id.as_str()),
                ("text", requirement.text.as_str()),
                ("check", check.as_str()),
                ("oracle", oracle.as_str()),
                ("verdict", point.verdict.name()),
                ("value", value.as_str()),
                ("unit", unit),
                ("threshold", relation.as_str()),
                ("margin", margin.as_str()),
                ("n", n.as_str()),
                ("measured", point.measured.as_str()),
                ("message", point.message.as_str()),
            ]));
            suite.add_test_case(case);
        }
    }
    let mut report = Report::new("sightline");
    suite.set_time(duration);
    suite
        .extra
        .insert("timestamp".into(), results.execution.started.as_str().into());
    report.add_test_suite(suite);
    report
}

/// The time of a case at each of `points` sweep points, given the point of
/// every case: the seconds simulating the point took, shared among the
/// point's cases, when the run measured each point's (`execution.points`);
/// else the run's wall-clock time shared among all cases (a merged campaign
/// measured none).
fn case_times(
    points: usize,
    cases: impl Iterator<Item = usize>,
    execution: &Execution,
) -> impl Fn(usize) -> Duration + '_ {
    let mut at_point = vec![0u32; points];
    for point in cases {
        if let Some(count) = at_point.get_mut(point) {
            *count += 1;
        }
    }
    let cases: u32 = at_point.iter().sum();
    let measured = execution.points.len() == points;
    let whole = Duration::from_secs_f64(execution.duration_seconds.max(0.0));
    move |point| match (measured, execution.points.get(point), at_point.get(point)) {
        (true, Some(&seconds), Some(&count)) => Duration::from_secs_f64(seconds.max(0.0)) / count.max(1),
        _ => whole / cases.max(1),
    }
}

/// The text of a JUnit report. quick-junit writes a `skipped` count on the
/// root `<testsuites>`, which no published Jenkins schema allows there; it is
/// dropped (each `<testsuite>` keeps its own), so that the file validates
/// against Jenkins' junit-10.xsd. quick-junit drops the control characters
/// XML 1.0 does not allow, but not its two other excluded characters, U+FFFE
/// and U+FFFF (a scenario's name or a requirement's text may hold them):
/// each becomes U+FFFD, so that the file stays well-formed.
pub fn junit_xml(report: &Report) -> Result<String, quick_junit::SerializeError> {
    const NOT_XML: [char; 2] = ['\u{FFFE}', '\u{FFFF}'];
    let mut text = report.to_string()?;
    if text.contains(NOT_XML) {
        text = text.replace(NOT_XML, "\u{FFFD}");
    }
    let root = text
        .find("<testsuites ")
        .map(|at| (at, at + text[at..].find('>').unwrap_or(0)));
    let skipped = root.and_then(|(at, end)| {
        let from = at + text[at..end].find(" skipped=\"")?;
        let to = from + " skipped=\"".len() + text[from + " skipped=\"".len()..].find('"')? + 1;
        Some((from, to))
    });
    Ok(match skipped {
        Some((from, to)) => format!("{}{}", &text[..from], &text[to..]),
        None => text,
    })
}

/// The suite of scenario `name` in file `path` (a suite per file, so two
/// scenarios of one name do not collide), its hash a property.
pub(crate) fn new_suite(name: &str, path: &str, sha256: &str) -> TestSuite {
    let mut suite = TestSuite::new(format!("{name} ({path})"));
    suite.extra.insert("file".into(), path.into());
    suite.add_property(("scenario", path));
    suite.add_property(("scenario_name", name));
    suite.add_property(("scenario_sha256", sha256));
    suite
}

/// A test case of a requirement at `line` of the scenario `name` in `path`.
pub(crate) fn new_case(name: String, status: TestCaseStatus, scenario: &str, path: &str, line: usize) -> TestCase {
    let mut case = TestCase::new(name, status);
    case.set_classname(classname(scenario));
    case.extra.insert("file".into(), path.into());
    case.extra.insert("line".into(), line.to_string().into());
    case
}

/// `name: value` lines, for a case's `<system-out>`: one line each, whatever
/// the value holds ([`one_line`]).
pub(crate) fn lines(pairs: &[(&str, &str)]) -> String {
    pairs
        .iter()
        .map(|(name, value)| format!("{name}: {}\n", one_line(value)))
        .collect()
}

/// `text` on one line: a line feed written `\n`, a backslash `\\`, so a
/// requirement's text of several lines cannot add a `name: value` line
/// (`verdict: pass`) of its own.
fn one_line(text: &str) -> String {
    text.replace('\\', "\\\\").replace('\n', "\\n")
}

/// A scenario's name as a dotted identifier under `sightline.`: lowercase
/// letters, digits and underscores (`Roundabout, six cooperating vehicles` →
/// `sightline.roundabout_six_cooperating_vehicles`); `sightline.scenario` for
/// a name with no letter or digit.
pub(crate) fn classname(name: &str) -> String {
    let words: Vec<String> = name
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect();
    let mut identifier = words.join("_");
    if identifier.is_empty() {
        identifier = "scenario".into();
    } else if identifier.starts_with(|c: char| c.is_numeric()) {
        identifier.insert(0, '_');
    }
    format!("sightline.{identifier}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// XML 1.0's characters: #x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD]
    /// | [#x10000-#x10FFFF].
    fn is_xml_char(c: char) -> bool {
        matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
    }

    /// A suite and a case named with U+FFFE, U+FFFF and control characters
    /// give a file of XML 1.0's characters only, the two non-characters as
    /// U+FFFD.
    #[test]
    fn characters_xml_does_not_allow_are_not_written() {
        let mut suite = new_suite("a\u{FFFE}b\u{1}", "x\u{FFFF}.yaml", "00");
        let mut case = new_case("R\u{FFFF}1".into(), TestCaseStatus::success(), "s\u{FFFE}", "p", 3);
        case.set_system_out("text \u{FFFE}\u{FFFF} \u{7}end");
        suite.add_test_case(case);
        let mut report = Report::new("sightline");
        report.add_test_suite(suite);
        let text = junit_xml(&report).unwrap();
        assert_eq!(text.chars().find(|&c| !is_xml_char(c)), None, "{text}");
        assert!(text.contains("a\u{FFFD}b"), "{text}");
        assert!(text.contains("R\u{FFFD}1"), "{text}");
        assert!(text.contains("text \u{FFFD}\u{FFFD} end"), "{text}");
    }

    /// A text of several lines stays one `text:` line: its own
    /// `verdict: pass` cannot be read as the case's.
    #[test]
    fn a_value_of_several_lines_is_one_line() {
        assert_eq!(
            lines(&[("text", "Low.\nverdict: pass\\n"), ("verdict", "fail")]),
            "text: Low.\\nverdict: pass\\\\n\nverdict: fail\n"
        );
    }

    #[test]
    fn classnames_are_dotted_identifiers_of_the_name() {
        assert_eq!(
            classname("Roundabout, six cooperating vehicles"),
            "sightline.roundabout_six_cooperating_vehicles"
        );
        assert_eq!(
            classname("SUMO grid / RSU (seed 002)"),
            "sightline.sumo_grid_rsu_seed_002"
        );
        assert_eq!(classname("3 vans"), "sightline._3_vans");
        assert_eq!(classname(" <> "), "sightline.scenario");
        assert_eq!(classname("Straße"), "sightline.straße");
    }

    /// Two points timed 2 s and 4 s, with two cases at point 0 and one at
    /// point 1: 1 s, 1 s and 4 s. Without the points' times (a merged
    /// campaign), the run's 6 s shared among the three cases: 2 s each.
    #[test]
    fn a_case_takes_a_share_of_its_points_time() {
        let execution = Execution {
            os: "linux".into(),
            arch: "x86_64".into(),
            threads: 1,
            started: "2026-01-01T00:00:00Z".into(),
            duration_seconds: 6.0,
            points: vec![2.0, 4.0],
        };
        let time = case_times(2, [0, 1, 0].into_iter(), &execution);
        assert_eq!([time(0), time(1)], [Duration::from_secs(1), Duration::from_secs(4)]);
        let merged = Execution {
            points: Vec::new(),
            ..execution.clone()
        };
        let time = case_times(2, [0, 1, 0].into_iter(), &merged);
        assert_eq!([time(0), time(1)], [Duration::from_secs(2); 2]);
    }
}
