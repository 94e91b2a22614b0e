//! Properties every road user a per-object check judges must meet.

use sightline_dsl::{Bound, ObjectProperty, ObjectSelection};
use sightline_engine::RoadUserValue;

use super::{seen_among_too_few, short};
use crate::Evaluation;

/// Checks `property` of every road user `selection` kept against `bound`: the
/// smallest margin decides. A road user without the property fails with no
/// value, except for a property only conflicts have
/// ([`ObjectProperty::defined_only`]): one without a conflict is not judged.
/// Fewer judged road users than `min_objects` (none, by default) is not
/// exercised (nothing to judge), unless one of them already violates the
/// bound (no value, or a failing one): a violation seen is a failure whatever
/// the road users not seen would hold. Messages name the road user that
/// decides, and those without the property.
pub(crate) fn evaluate(
    (property, selection): (ObjectProperty, &ObjectSelection),
    bound: Bound,
    values: &[RoadUserValue],
    min_objects: u64,
) -> Evaluation {
    let name = property.name();
    let selected = values.len();
    let values: Vec<&RoadUserValue> = values
        .iter()
        .filter(|v| !property.defined_only() || v.value.is_some())
        .collect();
    let n = values.len() as u64;
    // Those judged among those selected: "… with the ego (of class
    // pedestrian; 3 selected)", the selection after the qualifier.
    let population = match (selection.describe(), property.defined_only()) {
        (all, true) if all.is_empty() => format!("{} (of {selected} selected)", property.population()),
        (some, true) => format!("{} ({some}; {selected} selected)", property.population()),
        (all, false) if all.is_empty() => property.population().to_string(),
        (some, false) => format!("{} {some}", property.population()),
    };
    let extreme = match bound {
        Bound::AtLeast(_) => "smallest",
        Bound::AtMost(_) => "largest",
    };
    let measured = format!("{extreme} {name} of n = {n} {population}");
    // Too few road users to judge leaves the check not exercised, unless one
    // already violates the bound: a violation seen is judged all the same.
    let too_few = (n < min_objects).then(|| {
        if n == 0 {
            format!("no {population}")
        } else {
            format!("{n} {population}, fewer than the {min_objects} the check needs")
        }
    });
    let missing: Vec<&str> = (values.iter())
        .filter(|v| v.value.is_none())
        .map(|v| v.who.as_str())
        .collect();
    if !missing.is_empty() {
        let why = match property {
            ObjectProperty::WarningTime | ObjectProperty::WarningLead => "never flagged",
            ObjectProperty::GridLead => "never in the ego's fused grid",
            ObjectProperty::GridOrWarningLead => "never in the ego's fused grid, never flagged",
            ObjectProperty::SutLead | ObjectProperty::SutAnticipation | ObjectProperty::SutDelay => {
                "never detected by the system"
            }
            _ => "never known to the ego",
        };
        let seen = seen_among_too_few(n, min_objects);
        return Evaluation::failed(
            n,
            measured,
            format!(
                "{} of {n} {population} had no {name} ({why}: {}){seen}",
                missing.len(),
                some_of(&missing)
            ),
        );
    }
    let Some((margin, value, who)) = (values.iter())
        .filter_map(|v| v.value.map(|value| (bound.margin(value), value, &v.who)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
    else {
        let few = too_few.unwrap_or_else(|| format!("no {population}"));
        return Evaluation::not_exercised(n, measured, format!("nothing to judge: {few}"));
    };
    if let Some(few) = too_few.filter(|_| margin >= 0.0) {
        return Evaluation::not_exercised(n, measured, format!("nothing to judge: {few}"));
    }
    let seen = seen_among_too_few(n, min_objects);
    let message = format!(
        "{extreme} {name} over {n} {population} = {}, of {who} (margin {}; n = {n}){seen}",
        short(value),
        short(margin)
    );
    Evaluation::judged(value, margin, n, measured, message)
}

/// The first few of `names`, then how many more: `a, b, c and 4 more`.
fn some_of(names: &[&str]) -> String {
    const SHOWN: usize = 3;
    match names.len() {
        n if n <= SHOWN => names.join(", "),
        n => format!("{} and {} more", names[..SHOWN].join(", "), n - SHOWN),
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::AgentKind;

    use super::*;
    use crate::Status;

    const WARNING_TIME: (ObjectProperty, &ObjectSelection) = (ObjectProperty::WarningTime, &ALL);
    const ALL: ObjectSelection = ObjectSelection::ALL;

    /// [`evaluate`] over road users `u1`, `u2`, … with `values`.
    fn check(
        what: (ObjectProperty, &ObjectSelection),
        bound: Bound,
        values: &[Option<f64>],
        min_objects: u64,
    ) -> Evaluation {
        let users: Vec<RoadUserValue> = (values.iter().enumerate())
            .map(|(i, &value)| RoadUserValue {
                who: format!("u{}", i + 1),
                value,
            })
            .collect();
        evaluate(what, bound, &users, min_objects)
    }

    #[test]
    fn the_least_warned_object_decides() {
        let e = check(WARNING_TIME, Bound::AtLeast(1.0), &[Some(2.5), Some(1.2), Some(4.0)], 1);
        assert_eq!((e.status, e.value, e.n), (Status::Pass, Some(1.2), Some(3)));
        assert!((e.margin.unwrap() - 0.2).abs() < 1e-12);
        let e = check(WARNING_TIME, Bound::AtLeast(1.5), &[Some(2.5), Some(1.2)], 1);
        assert_eq!(e.status, Status::Fail);
    }

    #[test]
    fn an_unflagged_object_fails_and_no_object_is_not_exercised() {
        let e = check(WARNING_TIME, Bound::AtLeast(0.0), &[Some(3.0), None], 1);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, None, Some(2)));
        assert!(e.message.starts_with("1 of 2 objects"), "{}", e.message);
        let e = check(WARNING_TIME, Bound::AtLeast(1.0), &[], 1);
        assert_eq!((e.status, e.n), (Status::NotExercised, Some(0)));
        assert_eq!(
            e.message,
            "nothing to judge: no objects that came within d_min of the ego"
        );
        let e = check(WARNING_TIME, Bound::AtLeast(1.0), &[Some(2.0)], 2);
        assert_eq!(e.status, Status::NotExercised);
    }

    /// Too few road users to judge, but one already breaks the bound: a
    /// failure, as an `always` broken on too few steps is. Held by all of
    /// them, the check stays not exercised.
    #[test]
    fn a_violation_seen_among_too_few_road_users_fails() {
        // PET 1.2 s and 2.2 s against ≥ 1.5 s, three needed: 1.2 fails by 0.3.
        let pet = (ObjectProperty::Pet, &ALL);
        let e = check(pet, Bound::AtLeast(1.5), &[Some(2.2), Some(1.2)], 3);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(1.2), Some(2)));
        assert!((e.margin.unwrap() + 0.3).abs() < 1e-12);
        assert!(
            e.message.ends_with(
                "= 1.2, of u2 (margin -0.3; n = 2); a violation seen, judged though n = 2 is fewer than the 3 the check needs"
            ),
            "{}",
            e.message
        );
        // A road user never flagged cannot meet a lead of 1 s at all.
        let e = check(WARNING_TIME, Bound::AtLeast(1.0), &[Some(3.0), None], 5);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, None, Some(2)));
        assert!(e.message.starts_with("1 of 2 objects"), "{}", e.message);
        // Both hold: too few to pass, not exercised.
        let e = check(pet, Bound::AtLeast(1.0), &[Some(2.2), Some(1.2)], 3);
        assert_eq!((e.status, e.value, e.n), (Status::NotExercised, None, Some(2)));
        assert!(e.message.starts_with("nothing to judge: 2 "), "{}", e.message);
    }

    /// A selection that keeps no road user in a run is not exercised there,
    /// and says which road users it looked for.
    #[test]
    fn an_empty_selection_is_not_exercised_and_named() {
        let pedestrians = ObjectSelection {
            classes: vec![AgentKind::Pedestrian],
            areas: vec!["cw_north".into()],
            ..Default::default()
        };
        let e = check((ObjectProperty::WarningLead, &pedestrians), Bound::AtLeast(2.0), &[], 1);
        assert_eq!(e.status, Status::NotExercised);
        assert_eq!(
            e.message,
            "nothing to judge: no relevant road users of class pedestrian, in cw_north"
        );
        let e = check(
            (ObjectProperty::KnowledgeLead, &pedestrians),
            Bound::AtLeast(2.0),
            &[Some(2.5), None],
            1,
        );
        assert_eq!(e.status, Status::Fail);
        assert!(
            e.message
                .ends_with("had no knowledge_lead (never known to the ego: u2)"),
            "{}",
            e.message
        );
    }

    /// A road user never on a collision course has no TTC and is left out;
    /// the least TTC of the others decides, and when no selected road user
    /// had one the check is not exercised, never passed.
    #[test]
    fn road_users_without_a_conflict_are_not_judged() {
        let all = ObjectSelection::default();
        let e = check(
            (ObjectProperty::MinTtc, &all),
            Bound::AtLeast(1.5),
            &[None, Some(2.0), None, Some(1.7)],
            1,
        );
        assert_eq!((e.status, e.value, e.n), (Status::Pass, Some(1.7), Some(2)));
        assert_eq!(
            e.measured,
            "smallest min_ttc of n = 2 relevant road users on a collision course with the ego (of 4 selected)"
        );
        let e = check((ObjectProperty::MinTtc, &all), Bound::AtLeast(1.5), &[None, None], 1);
        assert_eq!((e.status, e.n), (Status::NotExercised, Some(0)));
        assert_eq!(
            e.message,
            "nothing to judge: no relevant road users on a collision course with the ego (of 2 selected)"
        );
        // An upper bound: the greatest DRAC decides.
        let e = check(
            (ObjectProperty::MaxDrac, &all),
            Bound::AtMost(3.0),
            &[Some(1.0), None, Some(3.4)],
            1,
        );
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(3.4), Some(2)));
        assert!(e.message.starts_with("largest max_drac over 2"), "{}", e.message);
        let e = check((ObjectProperty::Pet, &all), Bound::AtLeast(1.0), &[Some(0.0)], 1);
        assert_eq!((e.status, e.value), (Status::Fail, Some(0.0)));
    }

    /// The road user that decides is named, and so are those without the
    /// property: the first three, then how many more.
    #[test]
    fn messages_name_the_road_users_that_decide() {
        let e = check(WARNING_TIME, Bound::AtLeast(1.0), &[Some(2.5), Some(1.2), Some(4.0)], 1);
        assert!(e.message.contains("= 1.2, of u2 (margin 0.2;"), "{}", e.message);
        let unflagged = [Some(3.0), None, None, Some(1.0), None, None, None];
        let e = check(WARNING_TIME, Bound::AtLeast(0.0), &unflagged, 1);
        assert!(
            e.message
                .ends_with("had no warning_time (never flagged: u2, u3, u5 and 2 more)"),
            "{}",
            e.message
        );
    }
}
