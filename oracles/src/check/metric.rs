//! Metric thresholds.

use sightline_dsl::{Bound, Comparison, Metric, ObjectSelection, Trend};
use sightline_engine::Sample;

use super::{seen_among_too_few, short};
use crate::Evaluation;

/// Compares `metric`'s value over `selection` (a system's object-steps; all
/// where it selects nothing) with `bound`: passes when the margin is ≥ 0. A
/// sample smaller than `min_samples` (an empty population included) is not
/// exercised, unless the metric already misses in a way more samples cannot
/// mend ([`only_worsens`]): a failure; a metric the measurements lack, or one
/// undefined over a non-empty population, is an error.
pub(crate) fn evaluate(
    (metric, selection): (Metric, &ObjectSelection),
    bound: Bound,
    sample: Option<Sample>,
    min_samples: u64,
) -> Evaluation {
    let name = metric.name();
    let (population, label) = match selection.describe() {
        all if all.is_empty() => (metric.population().to_string(), name.to_string()),
        some => (format!("{} ({some})", metric.population()), format!("{name} ({some})")),
    };
    let Some(Sample { value, n }) = sample else {
        return Evaluation::error(format!("{label} is not measured at this point"));
    };
    let measured = describe(metric, n, &population);
    let short_of = n < min_samples;
    // Too few samples leave the check not exercised, unless the metric is one
    // that more samples can only worsen and it already misses: a violation seen.
    let seen_violation = |v: f64| only_worsens(metric, bound) && bound.margin(v) < 0.0;
    if short_of && !value.is_some_and(seen_violation) {
        return Evaluation::not_exercised(n, measured, too_few(name, n, min_samples, &population));
    }
    let Some(value) = value.filter(|v| !v.is_nan()) else {
        return Evaluation::error(format!("{name} is undefined over n = {n} {population}"));
    };
    let margin = bound.margin(value);
    let seen = seen_among_too_few(n, min_samples);
    let (relation, wanted) = match bound {
        Bound::AtLeast(_) => (if margin >= 0.0 { "≥" } else { "<" }, "at least"),
        Bound::AtMost(_) => (if margin >= 0.0 { "≤" } else { ">" }, "at most"),
    };
    let message = format!(
        "{label} = {} {relation} {threshold} (required {wanted} {threshold}; margin {}; n = {n}){seen}",
        short(value),
        short(margin),
        threshold = short(bound.threshold())
    );
    Evaluation::judged(value, margin, n, measured, message)
}

/// Whether more samples can only move `metric` further past `bound` once it
/// misses it: a count or a greatest value bounded above, a least value
/// bounded below ([`Metric::with_more_samples`]). Such a metric that misses
/// over too few samples is a violation seen; neither a share, a mean, a
/// quantile nor a comparison of two metrics is.
fn only_worsens(metric: Metric, bound: Bound) -> bool {
    matches!(
        (metric.with_more_samples(), bound),
        (Trend::OnlyUp, Bound::AtMost(_)) | (Trend::OnlyDown, Bound::AtLeast(_))
    )
}

/// Compares a metric with another measured on the same run, each with its
/// sample (`[(metric, sample), (other, sample)]`): their ratio or difference
/// against `bound`. Either sample smaller than `min_samples` is not exercised,
/// and so is a ratio to 0 (nothing to compare with), unless its numerator puts
/// it past the bound (x > 0 over 0 under `at_most`, x < 0 under `at_least`):
/// a violation seen, a failure with no value; a metric the
/// measurements lack, or one undefined over a non-empty population, is an
/// error. n is the smaller sample's.
pub(crate) fn compare(
    samples: [(Metric, Option<Sample>); 2],
    by: Comparison,
    bound: Bound,
    min_samples: u64,
) -> Evaluation {
    let mut values = [0.0; 2];
    let mut sizes = [0; 2];
    for (i, (metric, sample)) in samples.iter().enumerate() {
        let name = metric.name();
        let Some(Sample { value, n }) = *sample else {
            return Evaluation::error(format!("{name} is not measured at this point"));
        };
        if n < min_samples {
            return Evaluation::not_exercised(
                n,
                describe(*metric, n, metric.population()),
                too_few(name, n, min_samples, metric.population()),
            );
        }
        let Some(value) = value.filter(|v| !v.is_nan()) else {
            return Evaluation::error(format!("{name} is undefined over n = {n} {}", metric.population()));
        };
        (values[i], sizes[i]) = (value, n);
    }
    let [(metric, _), (other, _)] = samples;
    let operator = match by {
        Comparison::Ratio => "/",
        Comparison::Difference => "−",
    };
    let expression = format!("{} {operator} {}", metric.name(), other.name());
    let n = sizes[0].min(sizes[1]);
    let measured = format!(
        "{expression}: {} and {}",
        describe(metric, sizes[0], metric.population()),
        describe(other, sizes[1], other.population())
    );
    let Some(value) = by.of(values[0], values[1]) else {
        // x / 0 for x ≠ 0 is beyond every bound on its side: past an upper bound
        // when x > 0, below a lower one when x < 0. Any other ratio to 0 is undefined.
        let beyond = match bound {
            Bound::AtMost(_) => values[0] > 0.0,
            Bound::AtLeast(_) => values[0] < 0.0,
        };
        if beyond {
            let (side, wanted) = match bound {
                Bound::AtMost(t) => ("above", format!("at most {}", short(t))),
                Bound::AtLeast(t) => ("below", format!("at least {}", short(t))),
            };
            let message = format!(
                "{expression} = {} / 0, {side} every bound (required {wanted}; n = {n})",
                short(values[0])
            );
            return Evaluation::failed(n, measured, message);
        }
        return Evaluation::not_exercised(
            n,
            measured,
            format!(
                "nothing to compare with: {} = 0, so {expression} is undefined",
                other.name()
            ),
        );
    };
    let margin = bound.margin(value);
    let (relation, wanted) = match bound {
        Bound::AtLeast(_) => (if margin >= 0.0 { "≥" } else { "<" }, "at least"),
        Bound::AtMost(_) => (if margin >= 0.0 { "≤" } else { ">" }, "at most"),
    };
    let message = format!(
        "{expression} = {} {operator} {} = {} {relation} {threshold} (required {wanted} {threshold}; margin {}; n = {n})",
        short(values[0]),
        short(values[1]),
        short(value),
        short(margin),
        threshold = short(bound.threshold())
    );
    Evaluation::judged(value, margin, n, measured, message)
}

/// What a metric's value is, with its n and its `population` (the metric's,
/// or a selection of it): `median of n = 12 anticipation times`.
pub(crate) fn describe(metric: Metric, n: u64, population: &str) -> String {
    let what = match metric {
        Metric::AnticipationMedian
        | Metric::ObjectAnticipationMedian
        | Metric::BaselineAnticipationMedian
        | Metric::BaselineObjectAnticipationMedian => "median of",
        Metric::AnticipationP95
        | Metric::ObjectAnticipationP95
        | Metric::BaselineAnticipationP95
        | Metric::BaselineObjectAnticipationP95
        | Metric::MessageAgeP95 => "95th percentile of",
        _ => "value over",
    };
    format!("{what} n = {n} {population}")
}

/// The message of a check with too few samples.
pub(crate) fn too_few(name: &str, n: u64, min_samples: u64, population: &str) -> String {
    if n == 0 {
        format!("nothing to judge: no {population} to measure {name} on")
    } else {
        format!("nothing to judge: {name} over n = {n} {population}, fewer than the {min_samples} the check needs")
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::AgentKind;
    use sightline_engine::outcome::FieldMetrics;

    use super::*;

    const ALL: ObjectSelection = ObjectSelection::ALL;
    use crate::Status;

    fn metrics(false_alarms: u64) -> FieldMetrics {
        FieldMetrics {
            cells: 100,
            correct: 90,
            below_threshold: 10 - false_alarms,
            false_alarms,
            missed_detections: 0,
            decided_unknown: 0,
            unobserved: 0,
            mean_uncertainty: Some(0.1),
            conflict: None,
        }
    }

    fn sample(metrics: &FieldMetrics, metric: Metric) -> Option<Sample> {
        Some(Sample {
            value: metrics.value(metric),
            n: metrics.sample_size(metric)?,
        })
    }

    #[test]
    fn at_most_passes_on_the_boundary_and_fails_beyond() {
        let m = Metric::FalseAlarms;
        let e = evaluate((m, &ALL), Bound::AtMost(3.0), sample(&metrics(3), m), 1);
        assert_eq!(
            (e.status, e.value, e.margin, e.n),
            (Status::Pass, Some(3.0), Some(0.0), Some(100))
        );
        assert_eq!(e.measured, "value over n = 100 fused cells");
        let e = evaluate((m, &ALL), Bound::AtMost(3.0), sample(&metrics(4), m), 1);
        assert_eq!((e.status, e.margin), (Status::Fail, Some(-1.0)));
        assert_eq!(
            e.message,
            "false_alarms = 4 > 3 (required at most 3; margin -1; n = 100)"
        );
    }

    /// A grid no sensor observes decides no cell, so it raises no false
    /// alarm by judging nothing: not exercised, not a pass of "at most 0".
    /// Accuracy still counts its cells, none of them correct.
    #[test]
    fn errors_of_a_grid_no_sensor_observes_are_not_judged() {
        let blind = FieldMetrics {
            cells: 400,
            correct: 0,
            below_threshold: 0,
            false_alarms: 0,
            missed_detections: 0,
            decided_unknown: 0,
            unobserved: 400,
            mean_uncertainty: None,
            conflict: None,
        };
        for m in [Metric::FalseAlarms, Metric::ConfidentErrorRate, Metric::BelowThreshold] {
            let e = evaluate((m, &ALL), Bound::AtMost(0.0), sample(&blind, m), 1);
            assert_eq!((e.status, e.n), (Status::NotExercised, Some(0)), "{m:?}");
            assert_eq!(
                e.message,
                format!("nothing to judge: no fused cells to measure {} on", m.name())
            );
        }
        let e = evaluate(
            (Metric::Accuracy, &ALL),
            Bound::AtLeast(0.5),
            sample(&blind, Metric::Accuracy),
            1,
        );
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(0.0), Some(400)));
        // Half observed: the shares are over the observed half.
        let half = FieldMetrics {
            correct: 40,
            unobserved: 50,
            ..metrics(4)
        };
        let e = evaluate(
            (Metric::ConfidentErrorRate, &ALL),
            Bound::AtMost(0.1),
            sample(&half, Metric::ConfidentErrorRate),
            1,
        );
        assert_eq!((e.value, e.n), (Some(4.0 / 50.0), Some(50)));
    }

    #[test]
    fn at_least_compares_accuracy() {
        let e = evaluate(
            (Metric::Accuracy, &ALL),
            Bound::AtLeast(0.95),
            sample(&metrics(1), Metric::Accuracy),
            1,
        );
        assert_eq!((e.status, e.value), (Status::Fail, Some(0.9)));
    }

    /// 300 B/s against a baseline's 1000 B/s: a ratio of 0.3, a difference of −700.
    #[test]
    fn comparisons_bound_the_ratio_or_the_difference() {
        let load = |value: f64, n: u64| Some(Sample { value: Some(value), n });
        let pair = |ours, theirs| {
            [
                (Metric::ChannelLoad, load(ours, 50)),
                (Metric::BaselineChannelLoad, load(theirs, 40)),
            ]
        };
        let e = compare(pair(300.0, 1000.0), Comparison::Ratio, Bound::AtMost(0.5), 1);
        assert_eq!((e.status, e.value, e.n), (Status::Pass, Some(0.3), Some(40)));
        assert!((e.margin.unwrap() - 0.2).abs() < 1e-12);
        assert_eq!(
            e.message,
            "channel_load / baseline_channel_load = 300 / 1000 = 0.3 ≤ 0.5 (required at most 0.5; margin 0.2; n = 40)"
        );
        let e = compare(pair(600.0, 1000.0), Comparison::Ratio, Bound::AtMost(0.5), 1);
        assert_eq!(e.status, Status::Fail);
        let e = compare(pair(300.0, 1000.0), Comparison::Difference, Bound::AtLeast(0.0), 1);
        assert_eq!((e.status, e.value), (Status::Fail, Some(-700.0)));
        // Nothing sent by the baseline: no ratio. 300 B/s against nothing is past
        // any upper bound on the ratio, a violation seen; it meets every lower
        // bound only as an undefined quotient, so that is not exercised, and so is
        // 0 against nothing either way.
        let e = compare(pair(300.0, 0.0), Comparison::Ratio, Bound::AtMost(0.5), 1);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, None, Some(40)));
        assert_eq!(
            e.message,
            "channel_load / baseline_channel_load = 300 / 0, above every bound (required at most 0.5; n = 40)"
        );
        let e = compare(pair(300.0, 0.0), Comparison::Ratio, Bound::AtLeast(0.5), 1);
        assert_eq!(e.status, Status::NotExercised);
        let e = compare(pair(0.0, 0.0), Comparison::Ratio, Bound::AtMost(0.5), 1);
        assert_eq!(e.status, Status::NotExercised);
        // Either side too small a sample: not exercised; either side missing: an error.
        let e = compare(pair(300.0, 1000.0), Comparison::Ratio, Bound::AtMost(0.5), 45);
        assert_eq!((e.status, e.n), (Status::NotExercised, Some(40)));
        let e = compare(
            [(Metric::ChannelLoad, load(1.0, 5)), (Metric::BaselineChannelLoad, None)],
            Comparison::Ratio,
            Bound::AtMost(0.5),
            1,
        );
        assert_eq!(e.status, Status::Error);
    }

    #[test]
    fn an_empty_population_is_not_exercised_not_a_pass() {
        // The ratio is undefined over nothing; the check is not exercised.
        let empty = Some(Sample { value: None, n: 0 });
        let e = evaluate((Metric::OccupiedRecall, &ALL), Bound::AtLeast(0.9), empty, 1);
        assert_eq!(
            (e.status, e.value, e.margin, e.n),
            (Status::NotExercised, None, None, Some(0))
        );
        assert_eq!(
            e.message,
            "nothing to judge: no occupied cell-steps of non-cooperating road users to measure occupied_recall on"
        );
        // A count over nothing is 0 and would pass `at_most 0`: still not exercised.
        let none_close = Some(Sample { value: Some(0.0), n: 0 });
        let e = evaluate((Metric::MissedCriticals, &ALL), Bound::AtMost(0.0), none_close, 1);
        assert_eq!(e.status, Status::NotExercised);
    }

    /// A system's recall over its pedestrians: 6 of 11 object-steps matched.
    #[test]
    fn a_selection_names_its_population() {
        let pedestrians = ObjectSelection {
            classes: vec![AgentKind::Pedestrian],
            ..ObjectSelection::default()
        };
        let six_of_eleven = Some(Sample {
            value: Some(6.0 / 11.0),
            n: 11,
        });
        let e = evaluate((Metric::SutRecall, &pedestrians), Bound::AtLeast(0.9), six_of_eleven, 1);
        assert_eq!((e.status, e.n), (Status::Fail, Some(11)));
        assert_eq!(
            e.measured,
            "value over n = 11 object-steps in sight of a served sensor (of class pedestrian)"
        );
        assert_eq!(
            e.message,
            "sut_recall (of class pedestrian) = 0.545455 < 0.9 (required at least 0.9; margin -0.354545; n = 11)"
        );
        let none = Some(Sample { value: None, n: 0 });
        let e = evaluate((Metric::SutRecall, &pedestrians), Bound::AtLeast(0.9), none, 1);
        assert_eq!(e.status, Status::NotExercised);
        assert_eq!(
            e.message,
            "nothing to judge: no object-steps in sight of a served sensor (of class pedestrian) to measure \
             sut_recall on"
        );
    }

    #[test]
    fn a_quantile_of_too_few_samples_is_not_exercised() {
        let three = Some(Sample { value: Some(1.2), n: 3 });
        let m = Metric::AnticipationMedian;
        let e = evaluate((m, &ALL), Bound::AtLeast(1.0), three, m.default_min_samples());
        assert_eq!((e.status, e.value, e.n), (Status::NotExercised, None, Some(3)));
        assert_eq!(e.measured, "median of n = 3 anticipation times");
        assert!(e.message.contains("fewer than the 6 the check needs"), "{}", e.message);
        // The requirement may lower the minimum; then the value is judged.
        assert_eq!(evaluate((m, &ALL), Bound::AtLeast(1.0), three, 3).status, Status::Pass);
    }

    /// Too few samples, but a least TTC already under its bound or a count
    /// of false alarms already over it: more samples cannot mend either, a
    /// failure. A share that misses over too few samples may still be met:
    /// not exercised, and so is an extreme that holds.
    #[test]
    fn a_violation_seen_over_too_few_samples_fails_where_more_cannot_mend_it() {
        let ttc = |value: f64| {
            Some(Sample {
                value: Some(value),
                n: 2,
            })
        };
        let e = evaluate((Metric::MinTtc, &ALL), Bound::AtLeast(1.0), ttc(0.8), 3);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(0.8), Some(2)));
        assert_eq!(
            e.message,
            "min_ttc = 0.8 < 1 (required at least 1; margin -0.2; n = 2); a violation seen, judged though n = 2 \
             is fewer than the 3 the check needs"
        );
        let e = evaluate((Metric::MinTtc, &ALL), Bound::AtLeast(1.0), ttc(1.2), 3);
        assert_eq!((e.status, e.value), (Status::NotExercised, None));
        let m = Metric::FalseAlarms;
        let e = evaluate((m, &ALL), Bound::AtMost(3.0), sample(&metrics(4), m), 200);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(4.0), Some(100)));
        let e = evaluate((m, &ALL), Bound::AtMost(3.0), sample(&metrics(3), m), 200);
        assert_eq!(e.status, Status::NotExercised);
        let two_ghosts = Some(Sample { value: Some(2.0), n: 5 });
        let e = evaluate((Metric::SutGhosts, &ALL), Bound::AtMost(1.0), two_ghosts, 10);
        assert_eq!((e.status, e.value, e.n), (Status::Fail, Some(2.0), Some(5)));
        // Any count of cells only grows with more cells, not only the faults.
        let unobserved = Some(Sample {
            value: Some(7.0),
            n: 50,
        });
        let e = evaluate((Metric::Unobserved, &ALL), Bound::AtMost(5.0), unobserved, 100);
        assert_eq!((e.status, e.value), (Status::Fail, Some(7.0)));
        let m = Metric::Accuracy;
        let e = evaluate((m, &ALL), Bound::AtLeast(0.95), sample(&metrics(1), m), 200);
        assert_eq!((e.status, e.value), (Status::NotExercised, None));
    }

    #[test]
    fn unmeasured_or_undefined_over_samples_is_an_error() {
        let e = evaluate(
            (Metric::MeanConflict, &ALL),
            Bound::AtMost(1.0),
            sample(&metrics(0), Metric::MeanConflict),
            1,
        );
        assert_eq!((e.status, e.value), (Status::Error, None));
        let nan = Some(Sample {
            value: Some(f64::NAN),
            n: 10,
        });
        assert_eq!(
            evaluate((Metric::Accuracy, &ALL), Bound::AtLeast(0.5), nan, 1).status,
            Status::Error
        );
    }
}
