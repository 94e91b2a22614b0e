//! Metric checks over independent seeds: a one-sided confidence bound of the mean
//! (Student t) or of the share of seeds at which the threshold holds
//! (Clopper–Pearson or Wilson) must clear the requirement.

use serde::Serialize;
use sightline_dsl::{Bound, Metric, OverSeeds, RateBound, Statistic};
use statrs::distribution::{Beta, ContinuousCDF, Normal, StudentsT};

use sightline_engine::Sample;

use super::short;
use crate::Evaluation;

/// What a check over seeds measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SeedStatistics {
    /// Seeds run.
    pub seeds: u32,
    /// Confidence level of the bound.
    pub confidence: f64,
    /// The bound's method: `student_t`, `clopper_pearson` or `wilson`.
    pub method: &'static str,
    /// The mean of the metric, or the share of seeds judged to hold the
    /// threshold (a seed with fewer samples than the check needs is not
    /// counted as holding).
    pub estimate: f64,
    /// The one-sided confidence bound that is compared: of the estimate, or,
    /// when a share fails with seeds not judged, the bound at best, those
    /// seeds counted as holding.
    pub bound: f64,
}

/// Checks `metric` against `bound` over the samples of every seed (the point's
/// own first). The compared value is the bound; its margin is against the
/// threshold for a mean, against `share` for a share, and its n is the number
/// of seeds. A seed with fewer than `min_samples` samples leaves the check not
/// exercised, unless a share misses even with every such seed counted as
/// holding (a failure whatever they hold); a seed where the metric is missing
/// or undefined over samples is an error.
pub(crate) fn evaluate(
    metric: Metric,
    bound: Bound,
    over: OverSeeds,
    samples: &[Option<Sample>],
    min_samples: u64,
) -> Evaluation {
    let name = metric.name();
    let seeds = samples.len();
    let Some(samples) = samples.iter().copied().collect::<Option<Vec<Sample>>>() else {
        return Evaluation::error(format!("{name} is not measured at one of the {seeds} seeds"));
    };
    let short_of = samples.iter().filter(|s| s.n < min_samples).count();
    let fewest = samples.iter().map(|s| s.n).min().unwrap_or(0);
    if short_of > 0 {
        let unjudged = format!(
            "{short_of} of {seeds} seeds: {name} over as few as n = {fewest} {}, fewer than the {min_samples} the check needs",
            metric.population()
        );
        let judged_defined = (samples.iter())
            .filter(|s| s.n >= min_samples)
            .all(|s| s.value.is_some_and(|v| !v.is_nan()));
        if let (Statistic::Share { share, method }, true) = (over.statistic, judged_defined) {
            // A share that misses even with every seed not judged counted as
            // holding fails whatever those seeds hold.
            let holding = samples
                .iter()
                .filter(|s| s.n >= min_samples && s.value.is_some_and(|v| bound.margin(v) >= 0.0))
                .count();
            let n = seeds as u32;
            // The bound at best, the seeds not judged counted as holding; the
            // estimate is the share judged to hold.
            let statistics = SeedStatistics {
                estimate: holding as f64 / f64::from(n),
                ..share_statistics(method, (holding + short_of) as u32, n, over.confidence)
            };
            let limit = statistics.bound;
            if limit < share {
                let measured = format!(
                    "lower {} % {} bound of the share of n = {n} seeds that hold, at best",
                    short(over.confidence * 100.0),
                    method_title(method)
                );
                let message = format!(
                    "{} at {holding} seeds; with the {short_of} not judged holding too, the share's lower {}% \
                     bound {} ({}) misses {} (margin {}); not judged: {unjudged}",
                    relation(name, bound),
                    short(over.confidence * 100.0),
                    short(limit),
                    statistics.method,
                    short(share),
                    short(limit - share)
                );
                return Evaluation {
                    seeds: Some(statistics),
                    ..Evaluation::judged(limit, limit - share, u64::from(n), measured, message)
                };
            }
        }
        let message = format!(
            "nothing to judge at {unjudged}{}",
            judged_range(name, &samples, min_samples)
        );
        return Evaluation::not_exercised(fewest, format!("{name} at each of {seeds} seeds"), message);
    }
    let Some(values) = samples
        .iter()
        .map(|s| s.value.filter(|v| !v.is_nan()))
        .collect::<Option<Vec<f64>>>()
    else {
        let message = format!("{name} is undefined at one of the {seeds} seeds");
        return Evaluation::error(message);
    };
    let n = values.len() as u32;
    let confidence = short(over.confidence * 100.0);
    let (statistics, threshold, margin, description, measured) = match over.statistic {
        Statistic::Mean => {
            let upper = matches!(bound, Bound::AtMost(_));
            let (mean, limit) = mean_bound(&values, over.confidence, upper);
            let statistics = SeedStatistics {
                seeds: n,
                confidence: over.confidence,
                method: "student_t",
                estimate: mean,
                bound: limit,
            };
            let side = if upper { "upper" } else { "lower" };
            let description = format!(
                "mean {name} over {n} seeds = {}, its {side} {confidence}% bound {}",
                short(mean),
                short(limit)
            );
            let measured = format!("{side} {confidence} % Student-t bound of the mean over n = {n} seeds");
            (
                statistics,
                bound.threshold(),
                bound.margin(limit),
                description,
                measured,
            )
        }
        Statistic::Share { share, method } => {
            let holding = values.iter().filter(|&&v| bound.margin(v) >= 0.0).count() as u32;
            let statistics = share_statistics(method, holding, n, over.confidence);
            let limit = statistics.bound;
            let description = format!(
                "{} at {holding} of {n} seeds, the share's lower {confidence}% bound {} ({})",
                relation(name, bound),
                short(limit),
                statistics.method
            );
            let measured = format!(
                "lower {confidence} % {} bound of the share of n = {n} seeds that hold",
                method_title(method)
            );
            (statistics, share, limit - share, description, measured)
        }
    };
    // Seeds that all give the same value are one sample repeated: nothing the
    // seed draws changes the metric here, however many seeds ran.
    let repeated = if n > 1 && values.iter().all(|v| v.to_bits() == values[0].to_bits()) {
        format!(
            "; the {n} seeds gave identical values: nothing drawn at random changes {name} at this point, \
             so they are one sample repeated, not {n} independent ones"
        )
    } else {
        String::new()
    };
    let message = format!(
        "{description} {} {} (margin {}){repeated}",
        if margin >= 0.0 { "clears" } else { "misses" },
        short(threshold),
        short(margin)
    );
    Evaluation {
        seeds: Some(statistics),
        ..Evaluation::judged(statistics.bound, margin, u64::from(n), measured, message)
    }
}

/// What the seeds that could be judged gave, for the message of a check left
/// not exercised by the others (`; the 4 seeds judged gave min_ttc from 0 to
/// 2.1`), so that a value past the bound at one of them (a collision) shows
/// in the verdict; empty when none could be judged.
fn judged_range(name: &str, samples: &[Sample], min_samples: u64) -> String {
    let judged: Vec<f64> = samples
        .iter()
        .filter(|s| s.n >= min_samples)
        .filter_map(|s| s.value.filter(|v| !v.is_nan()))
        .collect();
    let (low, high) = judged
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &v| {
            (low.min(v), high.max(v))
        });
    match judged.len() {
        0 => String::new(),
        1 => format!("; the one seed judged gave {name} {}", short(low)),
        k => format!(
            "; the {k} seeds judged gave {name} from {} to {}",
            short(low),
            short(high)
        ),
    }
}

/// `name ≥ t` or `name ≤ t`.
fn relation(name: &str, bound: Bound) -> String {
    match bound {
        Bound::AtLeast(t) => format!("{name} ≥ {}", short(t)),
        Bound::AtMost(t) => format!("{name} ≤ {}", short(t)),
    }
}

/// A share of `k` seeds holding of `n`, with its one-sided lower bound at
/// `confidence` by `method`.
fn share_statistics(method: RateBound, k: u32, n: u32, confidence: f64) -> SeedStatistics {
    let (name, bound) = match method {
        RateBound::ClopperPearson => ("clopper_pearson", clopper_pearson_lower(k, n, confidence)),
        RateBound::Wilson => ("wilson", wilson_lower(k, n, confidence)),
    };
    SeedStatistics {
        seeds: n,
        confidence,
        method: name,
        estimate: f64::from(k) / f64::from(n),
        bound,
    }
}

/// `method` in words.
fn method_title(method: RateBound) -> &'static str {
    match method {
        RateBound::ClopperPearson => "Clopper–Pearson",
        RateBound::Wilson => "Wilson",
    }
}

/// The mean of `values` and its one-sided Student-t bound at `confidence`:
/// mean ∓ t(confidence, n − 1) · s / √n (upper with `upper`). It assumes the
/// seeds' values are roughly normal; with no spread the bound is the mean.
/// Needs at least two values.
pub fn mean_bound(values: &[f64], confidence: f64, upper: bool) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let t = StudentsT::new(0.0, 1.0, n - 1.0)
        .expect("at least two seeds")
        .inverse_cdf(confidence);
    let half = t * (variance / n).sqrt();
    (mean, if upper { mean + half } else { mean - half })
}

/// The exact one-sided lower bound of a binomial share with `k` successes in
/// `n` trials: the 1 − confidence quantile of Beta(k, n − k + 1); 0 when k = 0.
pub fn clopper_pearson_lower(k: u32, n: u32, confidence: f64) -> f64 {
    if k == 0 {
        return 0.0;
    }
    Beta::new(f64::from(k), f64::from(n - k + 1))
        .expect("positive shape parameters")
        .inverse_cdf(1.0 - confidence)
}

/// The Wilson score one-sided lower bound of a binomial share with `k`
/// successes in `n` trials.
pub fn wilson_lower(k: u32, n: u32, confidence: f64) -> f64 {
    let z = Normal::standard().inverse_cdf(confidence);
    let (n, p) = (f64::from(n), f64::from(k) / f64::from(n));
    let centre = p + z * z / (2.0 * n);
    let spread = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    ((centre - spread) / (1.0 + z * z / n)).max(0.0)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;
    use crate::Status;

    #[test]
    fn clopper_pearson_with_every_seed_holding_is_alpha_to_the_one_over_n() {
        // k = n: the bound solves p^n = α.
        assert_relative_eq!(
            clopper_pearson_lower(30, 30, 0.95),
            0.05f64.powf(1.0 / 30.0),
            epsilon = 1e-9
        );
        assert_eq!(clopper_pearson_lower(0, 30, 0.95), 0.0);
        // k = 1 of n: 1 − (1 − α)^(1/n).
        assert_relative_eq!(
            clopper_pearson_lower(1, 10, 0.9),
            1.0 - 0.9f64.powf(0.1),
            epsilon = 1e-9
        );
    }

    #[test]
    fn wilson_bound_by_hand() {
        // 8 of 10 at 95 %, z = 1.644854: (0.8 + z²/20 − z·√(0.016 + z²/400)) / (1 + z²/10).
        assert_relative_eq!(wilson_lower(8, 10, 0.95), 0.540792805687488, epsilon = 1e-6);
        // Wilson sits above the exact bound here.
        assert!(wilson_lower(8, 10, 0.95) > clopper_pearson_lower(8, 10, 0.95));
    }

    #[test]
    fn student_t_bound_by_hand() {
        // Ten values with mean 5.5 and s = √(55/6); t(0.95, 9) = 1.833113.
        let values: Vec<f64> = (1..=10).map(f64::from).collect();
        let (mean, lower) = mean_bound(&values, 0.95, false);
        assert_eq!(mean, 5.5);
        assert_relative_eq!(lower, 5.5 - 1.833113 * (55.0f64 / 6.0 / 10.0).sqrt(), epsilon = 1e-5);
        let (_, upper) = mean_bound(&values, 0.95, true);
        assert_relative_eq!(upper - mean, mean - lower, epsilon = 1e-12);
        // No spread: the bound is the mean.
        assert_eq!(mean_bound(&[2.0, 2.0, 2.0], 0.95, false), (2.0, 2.0));
    }

    fn over(statistic: Statistic) -> OverSeeds {
        OverSeeds {
            seeds: 10,
            confidence: 0.95,
            statistic,
        }
    }

    /// Ten seeds measuring 1, 2, …, 10, each over 50 samples.
    fn one_to_ten() -> Vec<Option<Sample>> {
        (1..=10)
            .map(|v| {
                Some(Sample {
                    value: Some(f64::from(v)),
                    n: 50,
                })
            })
            .collect()
    }

    #[test]
    fn a_mean_above_the_threshold_can_still_fail_its_bound() {
        let values = one_to_ten();
        // Mean 5.5 ≥ 5, but the lower bound 3.745 is not.
        let e = evaluate(
            Metric::OccupiedRecall,
            Bound::AtLeast(5.0),
            over(Statistic::Mean),
            &values,
            1,
        );
        assert_eq!((e.status, e.n), (Status::Fail, Some(10)));
        assert_relative_eq!(e.value.unwrap(), 3.745, epsilon = 1e-3);
        assert_relative_eq!(e.margin.unwrap(), 3.745 - 5.0, epsilon = 1e-3);
        assert_eq!(e.seeds.unwrap().estimate, 5.5);
        assert_eq!(e.measured, "lower 95 % Student-t bound of the mean over n = 10 seeds");
        assert!(
            e.message.starts_with("mean occupied_recall over 10 seeds = 5.5"),
            "{}",
            e.message
        );
        let e = evaluate(
            Metric::OccupiedRecall,
            Bound::AtLeast(3.7),
            over(Statistic::Mean),
            &values,
            1,
        );
        assert_eq!(e.status, Status::Pass);
    }

    /// Two of six seeds with no road user on a collision course leave a mean
    /// of min_ttc not exercised; the four judged, one of them a collision
    /// (0 s), are named in the message (an outside audit: the collision was
    /// nowhere in the verdict).
    #[test]
    fn a_check_left_not_exercised_names_what_the_judged_seeds_gave() {
        let sample = |value: Option<f64>, n| Some(Sample { value, n });
        let samples = [
            sample(Some(0.0), 1),
            sample(None, 0),
            sample(Some(2.1), 2),
            sample(Some(1.3), 1),
            sample(None, 0),
            sample(Some(1.7), 1),
        ];
        let message = |samples: &[Option<Sample>]| {
            let e = evaluate(Metric::MinTtc, Bound::AtLeast(1.0), over(Statistic::Mean), samples, 1);
            assert_eq!(e.status, Status::NotExercised);
            e.message
        };
        let all = message(&samples);
        assert!(
            all.ends_with("; the 4 seeds judged gave min_ttc from 0 to 2.1"),
            "{all}"
        );
        let one = message(&samples[..2]);
        assert!(one.ends_with("; the one seed judged gave min_ttc 0"), "{one}");
        let none = message(&samples[1..2]);
        assert!(none.ends_with("the check needs"), "{none}");
    }

    /// Seven seeds of a world that draws nothing: seven equal values. The
    /// verdict stands (the value is exact), and its message says they are one
    /// sample repeated; ten different values say nothing of the kind.
    #[test]
    fn identical_seeds_are_called_one_sample_repeated() {
        let same = vec![
            Some(Sample {
                value: Some(0.93),
                n: 40
            });
            7
        ];
        let e = evaluate(
            Metric::OccupiedRecall,
            Bound::AtLeast(0.9),
            over(Statistic::Mean),
            &same,
            1,
        );
        assert_eq!((e.status, e.n), (Status::Pass, Some(7)));
        assert!(
            e.message.ends_with(
                "; the 7 seeds gave identical values: nothing drawn at random changes occupied_recall at this \
                 point, so they are one sample repeated, not 7 independent ones"
            ),
            "{}",
            e.message
        );
        let e = evaluate(
            Metric::OccupiedRecall,
            Bound::AtLeast(3.7),
            over(Statistic::Mean),
            &one_to_ten(),
            1,
        );
        assert!(!e.message.contains("identical"), "{}", e.message);
    }

    #[test]
    fn a_share_counts_the_seeds_that_hold() {
        let values = one_to_ten();
        let share = |share, method| Statistic::Share { share, method };
        // at_most 8 holds at 8 of 10 seeds; Wilson's lower 95 % bound is 0.5408.
        let e = evaluate(
            Metric::MissedCriticals,
            Bound::AtMost(8.0),
            over(share(0.5, RateBound::Wilson)),
            &values,
            1,
        );
        assert_eq!(e.status, Status::Pass);
        assert_relative_eq!(e.value.unwrap(), 0.540792805687488, epsilon = 1e-6);
        assert_relative_eq!(e.margin.unwrap(), 0.040792805687488, epsilon = 1e-6);
        assert_eq!(
            e.measured,
            "lower 95 % Wilson bound of the share of n = 10 seeds that hold"
        );
        let e = evaluate(
            Metric::MissedCriticals,
            Bound::AtMost(8.0),
            over(share(0.6, RateBound::Wilson)),
            &values,
            1,
        );
        assert_eq!(e.status, Status::Fail);
    }

    #[test]
    fn a_seed_with_too_few_samples_leaves_the_check_not_exercised() {
        let mut values = one_to_ten();
        values[3] = Some(Sample { value: None, n: 0 });
        let e = evaluate(
            Metric::OccupiedRecall,
            Bound::AtLeast(0.0),
            over(Statistic::Mean),
            &values,
            1,
        );
        assert_eq!((e.status, e.value, e.n), (Status::NotExercised, None, Some(0)));
        assert!(
            e.message.starts_with("nothing to judge at 1 of 10 seeds"),
            "{}",
            e.message
        );
    }

    #[test]
    fn a_share_that_misses_even_if_the_seeds_not_judged_held_fails() {
        // at_most 2 holds at 2 of the 9 seeds judged (1 and 2); the tenth has
        // too few samples. Even if it held, 3 of 10 clears no share of 0.5.
        let mut values = one_to_ten();
        values[9] = Some(Sample { value: None, n: 0 });
        let share = |share| {
            over(Statistic::Share {
                share,
                method: RateBound::Wilson,
            })
        };
        let e = evaluate(Metric::MissedCriticals, Bound::AtMost(2.0), share(0.5), &values, 1);
        assert_eq!((e.status, e.n), (Status::Fail, Some(10)));
        assert_relative_eq!(e.value.unwrap(), wilson_lower(3, 10, 0.95), epsilon = 1e-12);
        // The estimate is the share judged to hold, 2 of 10; the bound, at
        // best, counts the tenth as holding (3 of 10).
        let statistics = e.seeds.unwrap();
        assert_eq!((statistics.estimate, statistics.seeds), (0.2, 10));
        assert_relative_eq!(statistics.bound, wilson_lower(3, 10, 0.95), epsilon = 1e-12);
        assert!(
            e.message
                .starts_with("missed_criticals ≤ 2 at 2 seeds; with the 1 not judged holding too"),
            "{}",
            e.message
        );
        // A share of 0.1 it could clear with the tenth: not exercised.
        let e = evaluate(Metric::MissedCriticals, Bound::AtMost(2.0), share(0.1), &values, 1);
        assert_eq!(e.status, Status::NotExercised);
    }

    #[test]
    fn an_unmeasured_or_undefined_seed_is_an_error() {
        let mut values = one_to_ten();
        values[1] = None;
        let e = evaluate(
            Metric::AnticipationMedian,
            Bound::AtMost(3.0),
            over(Statistic::Mean),
            &values,
            1,
        );
        assert_eq!((e.status, e.value), (Status::Error, None));
        values[1] = Some(Sample { value: None, n: 50 });
        let e = evaluate(
            Metric::AnticipationMedian,
            Bound::AtMost(3.0),
            over(Statistic::Mean),
            &values,
            1,
        );
        assert_eq!(e.status, Status::Error);
    }
}
