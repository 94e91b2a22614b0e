//! Properties every object that came within d_min of the ego must meet.

use sightline_dsl::{Bound, ObjectProperty};

use super::short;
use crate::Evaluation;

/// Checks `property` of every close approach against `bound`: the smallest
/// margin decides; an object without the property (never flagged) fails with
/// no value. Fewer close approaches than `min_objects` (none, by default) is
/// not exercised: no object, nothing to judge.
pub(crate) fn evaluate(property: ObjectProperty, bound: Bound, values: &[Option<f64>], min_objects: u64) -> Evaluation {
    let name = property.name();
    let n = values.len() as u64;
    let measured = format!("smallest {name} of n = {n} objects that came within d_min of the ego");
    if n < min_objects {
        let message = if n == 0 {
            "nothing to judge: no object came within d_min of the ego".to_string()
        } else {
            format!(
                "nothing to judge: {n} objects came within d_min of the ego, fewer than the {min_objects} the check needs"
            )
        };
        return Evaluation::not_exercised(n, measured, message);
    }
    let missing = values.iter().filter(|v| v.is_none()).count();
    if missing > 0 {
        return Evaluation::failed(
            n,
            measured,
            format!("{missing} of {n} objects that came within d_min of the ego had no {name} (never flagged)"),
        );
    }
    let (margin, value) = values
        .iter()
        .flatten()
        .map(|&v| (bound.margin(v), v))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("values are present");
    let message = format!(
        "smallest {name} over {n} objects = {} (margin {}; n = {n})",
        short(value),
        short(margin)
    );
    Evaluation::judged(value, margin, n, measured, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Status;

    #[test]
    fn the_least_warned_object_decides() {
        let e = evaluate(
            ObjectProperty::WarningTime,
            Bound::AtLeast(1.0),
            &[Some(2.5), Some(1.2), Some(4.0)],
            1,
        );
        assert_eq!((e.status, e.value, e.n), (Status::Pass, Some(1.2), Some(3)));
        assert!((e.margin.unwrap() - 0.2).abs() < 1e-12);
        let e = evaluate(
            ObjectProperty::WarningTime,
            Bound::AtLeast(1.5),
            &[Some(2.5), Some(1.2)],
            1,
        );
        assert_eq!(e.status, Status::Fail);
    }

    #[test]
    fn an_unflagged_object_fails_and_no_object_is_not_exercised() {
        let e = evaluate(ObjectProperty::WarningTime, Bound::AtLeast(0.0), &[Some(3.0), None], 1);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, None, Some(2)));
        assert!(e.message.starts_with("1 of 2 objects"), "{}", e.message);
        let e = evaluate(ObjectProperty::WarningTime, Bound::AtLeast(1.0), &[], 1);
        assert_eq!((e.status, e.n), (Status::NotExercised, Some(0)));
        assert_eq!(e.message, "nothing to judge: no object came within d_min of the ego");
        let e = evaluate(ObjectProperty::WarningTime, Bound::AtLeast(1.0), &[Some(2.0)], 2);
        assert_eq!(e.status, Status::NotExercised);
    }
}
