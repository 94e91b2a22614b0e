//! Properties every object that came within d_min of the ego must meet.

use sightline_dsl::{Bound, ObjectProperty};

use super::short;
use crate::Status;

/// Checks `property` of every close approach against `bound`: the smallest
/// margin decides; an object without the property (never flagged) fails with
/// no value. No close approach: it holds.
pub(crate) fn evaluate(
    property: ObjectProperty,
    bound: Bound,
    values: &[Option<f64>],
) -> (Status, Option<f64>, Option<f64>, String) {
    let name = property.name();
    if values.is_empty() {
        return (
            Status::Pass,
            None,
            None,
            "no object came within d_min of the ego".into(),
        );
    }
    let missing = values.iter().filter(|v| v.is_none()).count();
    if missing > 0 {
        return (
            Status::Fail,
            None,
            None,
            format!(
                "{missing} of {} objects that came within d_min of the ego had no {name} (never flagged)",
                values.len()
            ),
        );
    }
    let (margin, value) = values
        .iter()
        .flatten()
        .map(|&v| (bound.margin(v), v))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("values are present");
    let status = if margin >= 0.0 { Status::Pass } else { Status::Fail };
    let message = format!(
        "smallest {name} over {} objects = {} (margin {})",
        values.len(),
        short(value),
        short(margin)
    );
    (status, Some(value), Some(margin), message)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_least_warned_object_decides() {
        let (status, value, margin, _) = evaluate(
            ObjectProperty::WarningTime,
            Bound::AtLeast(1.0),
            &[Some(2.5), Some(1.2), Some(4.0)],
        );
        assert_eq!((status, value), (Status::Pass, Some(1.2)));
        assert!((margin.unwrap() - 0.2).abs() < 1e-12);
        let (status, ..) = evaluate(
            ObjectProperty::WarningTime,
            Bound::AtLeast(1.5),
            &[Some(2.5), Some(1.2)],
        );
        assert_eq!(status, Status::Fail);
    }

    #[test]
    fn an_unflagged_object_fails_and_none_passes() {
        let (status, value, _, message) =
            evaluate(ObjectProperty::WarningTime, Bound::AtLeast(0.0), &[Some(3.0), None]);
        assert_eq!((status, value), (Status::Fail, None));
        assert!(message.starts_with("1 of 2 objects"), "{message}");
        let (status, ..) = evaluate(ObjectProperty::WarningTime, Bound::AtLeast(1.0), &[]);
        assert_eq!(status, Status::Pass);
    }
}
