//! Each requirement as the page shows it: its check in words, its deciding
//! value, threshold and margin, and its verdict at every point; the findings
//! of the banner.

use serde::Serialize;
use sightline_dsl::ObjectProperty;

use super::format::{exact_with_unit, number, with_unit};
use crate::results::{CheckInfo, RateBound, RequirementResult, Statistic, Status};

/// A requirement that did not pass, as the banner names it.
#[derive(Serialize)]
pub(super) struct Finding {
    id: String,
    anchor: String,
    verdict: &'static str,
    /// The verdict in words (`not exercised`).
    words: &'static str,
    /// Whether it fails the run (not an accepted not-exercised verdict).
    fails_run: bool,
    /// The reason a not-exercised verdict is accepted (none for another
    /// verdict).
    accepted: Option<String>,
    /// The deciding point's label (empty without a sweep).
    label: String,
    measured: String,
    /// What the measured value holds, with its n.
    what: String,
    threshold: String,
    margin: String,
    n: String,
    message: String,
}

#[derive(Serialize)]
pub(super) struct RequirementView {
    id: String,
    anchor: String,
    text: String,
    line: usize,
    check: String,
    /// The unit of the measured value, threshold and margin (`1`: dimensionless).
    unit: &'static str,
    measured: String,
    /// What `measured` holds, with its n.
    what: String,
    threshold: String,
    margin: String,
    verdict: &'static str,
    words: &'static str,
    accepted: Option<String>,
    message: String,
    points: Vec<EvaluationView>,
}

#[derive(Serialize)]
struct EvaluationView {
    label: String,
    verdict: &'static str,
    words: &'static str,
    /// Whether the point is not exercised and the scenario accepts that.
    accepted: bool,
    measured: String,
    what: String,
    margin: String,
    message: String,
}

/// The scenario's reason for accepting `verdict`: only a not-exercised verdict
/// is accepted, so a pass or a failure has none.
fn acceptance(verdict: Status, reason: Option<&String>) -> Option<String> {
    (verdict == Status::NotExercised).then(|| reason.cloned()).flatten()
}

pub(super) fn finding(r: &RequirementResult) -> Finding {
    let decisive = r.points.iter().find(|p| p.point == r.point);
    let unit = r.check.unit;
    Finding {
        id: r.id.clone(),
        anchor: format!("req-{}", r.id),
        verdict: r.verdict.name(),
        words: r.verdict.words(),
        fails_run: r.fails_run,
        accepted: acceptance(r.verdict, r.accept_not_exercised.as_ref()),
        label: decisive.map(|p| p.label.clone()).unwrap_or_default(),
        measured: with_unit(r.value, unit),
        what: r.measured.clone(),
        threshold: format!("{} {}", relation_sign(r.relation()), exact_with_unit(r.threshold, unit)),
        margin: with_unit(r.margin, unit),
        // As the `what` beside it writes it (`n = 28529`), not `28,529`.
        n: r.n.map_or_else(|| "—".into(), |n| n.to_string()),
        message: r.message.clone(),
    }
}

/// `≥`, `≤` or `tolerance`, for a check's relation.
fn relation_sign(relation: &str) -> &str {
    match relation {
        "at_least" => "≥",
        "at_most" => "≤",
        other => other,
    }
}

pub(super) fn requirement_view(r: &RequirementResult) -> RequirementView {
    let unit = r.check.unit;
    RequirementView {
        id: r.id.clone(),
        anchor: format!("req-{}", r.id),
        text: r.text.clone(),
        line: r.line,
        check: describe_check(&r.check),
        unit,
        measured: with_unit(r.value, unit),
        what: r.measured.clone(),
        threshold: exact_with_unit(r.threshold, unit),
        margin: with_unit(r.margin, unit),
        verdict: r.verdict.name(),
        words: r.verdict.words(),
        accepted: acceptance(r.verdict, r.accept_not_exercised.as_ref()),
        message: r.message.clone(),
        points: r
            .points
            .iter()
            .map(|p| EvaluationView {
                label: if p.label.is_empty() {
                    "—".into()
                } else {
                    p.label.clone()
                },
                verdict: p.verdict.name(),
                words: p.verdict.words(),
                accepted: acceptance(p.verdict, r.accept_not_exercised.as_ref()).is_some(),
                measured: with_unit(p.value, unit),
                what: p.measured.clone(),
                margin: with_unit(p.margin, unit),
                message: p.message.clone(),
            })
            .collect(),
    }
}

/// The check in words, as the report's Oracle column and junit.xml give it
/// (`occupied_recall ≥ 0.5 at ≥ 90 % of 30 seeds, at 95 % confidence
/// (Clopper–Pearson)`).
pub(crate) fn describe_check(check: &CheckInfo) -> String {
    let (name, threshold) = (check.name, exact_with_unit(check.threshold, check.unit));
    let relation = match check.relation {
        "at_least" | "at_most" => format!("{name} {} {threshold}", relation_sign(check.relation)),
        _ => return format!("invariant {name} (tolerance {threshold})"),
    };
    match check.kind {
        "always" | "eventually" => {
            let window = check
                .within
                .map_or(String::new(), |w| format!(" within {} s", number(w)));
            return format!("{} {relation}{window}", check.kind);
        }
        "per_object" if check.name == "warning_time" => return format!("every object within d_min: {relation}"),
        "per_object" => {
            // The criticality measures judge only the road users in conflict.
            let property = ObjectProperty::ALL.into_iter().find(|p| p.name() == name);
            let conflicts = property.is_some_and(ObjectProperty::defined_only);
            let users = match property {
                _ if conflicts => "every road user in conflict with the ego",
                Some(ObjectProperty::SutDelay) => "every road user in a served sensor's sight",
                Some(p) if p.of_system() => "every road user in the scene with the ego",
                _ => "every relevant road user",
            };
            let selected = check.objects.describe();
            return match (conflicts, selected.is_empty()) {
                (_, true) => format!("{users}: {relation}"),
                (true, false) => format!("{users} ({selected}): {relation}"),
                (false, false) => format!("{users} {selected}: {relation}"),
            };
        }
        "metric" if !check.objects.is_all() => {
            // A system's metric over the object-steps it selects (never over seeds).
            let sign = relation_sign(check.relation);
            return format!("{name} ({}) {sign} {threshold}", check.objects.describe());
        }
        "compare" => {
            let other = check.relative_to.unwrap_or_default();
            let (operator, sign) = (
                if check.by == Some("difference") { "−" } else { "/" },
                relation_sign(check.relation),
            );
            return format!("{name} {operator} {other} {sign} {threshold}");
        }
        _ => {}
    }
    let Some(over) = check.over_seeds else {
        return relation;
    };
    let confidence = number(over.confidence * 100.0);
    match over.statistic {
        Statistic::Mean => format!(
            "mean over {} seeds: {relation} at {confidence} % confidence (Student t)",
            over.seeds
        ),
        Statistic::Share { share, method } => format!(
            "{relation} at ≥ {} % of {} seeds, at {confidence} % confidence ({})",
            number(share * 100.0),
            over.seeds,
            match method {
                RateBound::ClopperPearson => "Clopper–Pearson",
                RateBound::Wilson => "Wilson",
            }
        ),
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{AgentKind, ObjectSelection};

    use super::*;

    #[test]
    fn a_systems_metric_over_a_selection_names_it() {
        let check = |objects| CheckInfo {
            kind: "metric",
            name: "sut_recall",
            relation: "at_least",
            threshold: 0.9,
            unit: "1",
            over_seeds: None,
            within: None,
            relative_to: None,
            by: None,
            objects,
        };
        let pedestrians = ObjectSelection {
            classes: vec![AgentKind::Pedestrian],
            areas: vec!["walkway".into()],
            ..ObjectSelection::default()
        };
        assert_eq!(describe_check(&check(ObjectSelection::default())), "sut_recall ≥ 0.9");
        assert_eq!(
            describe_check(&check(pedestrians)),
            "sut_recall (of class pedestrian, in walkway) ≥ 0.9"
        );
    }
}
