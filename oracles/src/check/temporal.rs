//! Signals over time, with the robustness of signal temporal logic: `always`
//! holds with the smallest margin over the steps, `eventually` with the largest.
//!
//! Written here rather than taken from an STL crate: the checks are offline over
//! a finished run and use two operators on one signal (G and F, optionally on
//! [0, T]), whose robustness is a minimum or a maximum. The Rust STL monitors we
//! found (`mstlo` 0.1) are online monitors with a formula language and far more
//! than this needs; the tests below check these operators against hand-made
//! signals.

use sightline_dsl::{Bound, Signal, Temporal};
use sightline_engine::semantic::Series;

use super::short;
use crate::Status;

/// What a temporal check found: status, the signal's value and the margin at the
/// decisive step, that step's time, and a message.
pub(crate) struct Found {
    pub status: Status,
    pub value: Option<f64>,
    pub margin: Option<f64>,
    pub time: Option<f64>,
    pub message: String,
}

/// Checks `operator` (signal `bound`) over every run of a point, counting the
/// steps up to `within` seconds; each run must satisfy it, so the point's
/// robustness is the smallest over runs. A run without a defined step in the
/// window makes the check an error (an `always` over nothing would pass
/// vacuously).
pub(crate) fn evaluate(
    signal: Signal,
    operator: Temporal,
    bound: Bound,
    within: Option<f64>,
    runs: &[Series],
) -> Found {
    let name = signal.name();
    let mut worst: Option<(f64, f64, f64)> = None;
    for series in runs {
        let window = series.iter().filter(|(t, _)| within.is_none_or(|w| *t <= w + 1e-9));
        let margins = window.map(|&(t, v)| (bound.margin(v), t, v));
        let decisive = match operator {
            Temporal::Always => margins.min_by(|a, b| a.0.total_cmp(&b.0)),
            Temporal::Eventually => margins.max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1))),
        };
        let Some(decisive) = decisive else {
            let message = format!(
                "{name} is never defined{} in one of the {} runs: nothing to check",
                within.map_or(String::new(), |w| format!(" within {} s", short(w))),
                runs.len()
            );
            return Found {
                status: Status::Error,
                value: None,
                margin: None,
                time: None,
                message,
            };
        };
        if worst.is_none_or(|w| decisive.0 < w.0) {
            worst = Some(decisive);
        }
    }
    let Some((margin, time, value)) = worst else {
        return Found {
            status: Status::Error,
            value: None,
            margin: None,
            time: None,
            message: format!("{name} has no run to check"),
        };
    };
    let holds = margin >= 0.0;
    let relation = match bound {
        Bound::AtLeast(t) => format!("≥ {}", short(t)),
        Bound::AtMost(t) => format!("≤ {}", short(t)),
    };
    let what = match operator {
        Temporal::Always => "always",
        Temporal::Eventually => "eventually",
    };
    let window = within.map_or(String::new(), |w| format!(" within {} s", short(w)));
    let message = format!(
        "{what} {name} {relation}{window}: {} (robustness {}; {name} = {} at {} s)",
        if holds { "holds" } else { "fails" },
        short(margin),
        short(value),
        short(time)
    );
    Found {
        status: if holds { Status::Pass } else { Status::Fail },
        value: Some(value),
        margin: Some(margin),
        time: Some(time),
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(operator: Temporal, bound: Bound, within: Option<f64>, runs: &[Series]) -> Found {
        evaluate(Signal::BlindRecall, operator, bound, within, runs)
    }

    const SIGNAL: [(f64, f64); 5] = [(0.0, 0.9), (0.1, 0.7), (0.2, 0.95), (0.3, 0.6), (0.4, 0.85)];

    #[test]
    fn always_takes_the_smallest_margin_and_its_time() {
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[SIGNAL.to_vec()]);
        assert_eq!(found.status, Status::Pass);
        assert!((found.margin.unwrap() - 0.1).abs() < 1e-12);
        assert_eq!((found.value, found.time), (Some(0.6), Some(0.3)));
        let found = check(Temporal::Always, Bound::AtLeast(0.65), None, &[SIGNAL.to_vec()]);
        assert_eq!(found.status, Status::Fail);
        assert!((found.margin.unwrap() + 0.05).abs() < 1e-12);
    }

    #[test]
    fn within_cuts_the_window_on_its_boundary() {
        // Up to 0.2 s: 0.9, 0.7, 0.95; the 0.6 at 0.3 s is outside.
        let found = check(Temporal::Always, Bound::AtLeast(0.65), Some(0.2), &[SIGNAL.to_vec()]);
        assert_eq!((found.status, found.time), (Status::Pass, Some(0.1)));
    }

    #[test]
    fn eventually_takes_the_largest_margin_and_the_first_time_it_is_reached() {
        let found = check(Temporal::Eventually, Bound::AtLeast(0.95), None, &[SIGNAL.to_vec()]);
        assert_eq!(
            (found.status, found.margin, found.time),
            (Status::Pass, Some(0.0), Some(0.2))
        );
        let found = check(Temporal::Eventually, Bound::AtMost(0.5), Some(0.2), &[SIGNAL.to_vec()]);
        assert_eq!((found.status, found.time), (Status::Fail, Some(0.1)));
        assert!((found.margin.unwrap() + 0.2).abs() < 1e-12);
    }

    #[test]
    fn every_run_must_hold_and_the_worst_decides() {
        let good = vec![(0.0, 0.9), (0.1, 0.8)];
        let bad = vec![(0.0, 0.9), (0.1, 0.4)];
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[good, bad]);
        assert_eq!((found.status, found.value), (Status::Fail, Some(0.4)));
    }

    #[test]
    fn an_empty_signal_is_an_error_not_a_vacuous_pass() {
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[Vec::new()]);
        assert_eq!(found.status, Status::Error);
        let found = check(Temporal::Always, Bound::AtLeast(0.5), Some(0.05), &[vec![(0.1, 0.9)]]);
        assert_eq!(found.status, Status::Error);
        assert!(
            found.message.contains("never defined within 0.05 s"),
            "{}",
            found.message
        );
    }
}
