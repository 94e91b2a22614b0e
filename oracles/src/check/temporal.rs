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
use sightline_engine::outcome::Series;

use super::short;
use crate::Evaluation;

/// The steps a temporal check counts.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Window {
    /// Only the first this many seconds (`None`: the whole run).
    pub within: Option<f64>,
    /// When the run ends, seconds (its last step's time plus a step: each
    /// step's state holds until the next): a window reaching past it is not
    /// covered, one ending there is (`None`: unknown, taken as covered).
    pub covered: Option<f64>,
    /// The fewest defined steps each run needs in the window.
    pub min_steps: u64,
}

/// Checks `operator` (signal `bound`) over every run of a point, counting the
/// steps in `window`; each run must satisfy it, so the point's robustness is
/// the smallest over runs. A window the run does not cover, or a run with
/// fewer defined steps in it than the window's minimum, leaves the check not
/// exercised (an `always` over nothing would pass vacuously), unless a run
/// already breaks an `always` on the steps there are: a violation seen is a
/// failure whatever the steps not seen hold. No run at all is an error.
pub(crate) fn evaluate(
    signal: Signal,
    operator: Temporal,
    bound: Bound,
    window: Window,
    runs: &[Series],
) -> Evaluation {
    let name = signal.name();
    let in_window = |t: f64| window.within.is_none_or(|w| t <= w + 1e-9);
    let steps: u64 = runs
        .iter()
        .map(|series| series.iter().filter(|(t, _)| in_window(*t)).count() as u64)
        .sum();
    let plural = if runs.len() == 1 { "" } else { "s" };
    let measured = format!(
        "{name} at the decisive step of n = {steps} defined steps ({} run{plural})",
        runs.len()
    );
    let span = window
        .within
        .map_or(String::new(), |w| format!(" within {} s", short(w)));
    let uncovered = match (window.within, window.covered) {
        (Some(within), Some(end)) if end + 1e-9 < within => Some(format!(
            "the window of {} s reaches past the run's end at {} s",
            short(within),
            short(end)
        )),
        _ => None,
    };
    // Why every run is incomplete (the window is not covered), else why the
    // first incomplete run is.
    let mut incomplete = uncovered.clone();
    let mut worst: Option<(f64, f64, f64)> = None;
    let mut worst_run = 0;
    for (run, series) in runs.iter().enumerate() {
        let defined = series.iter().filter(|(t, _)| in_window(*t));
        let count = defined.clone().count() as u64;
        let margins = defined.map(|&(t, v)| (bound.margin(v), t, v));
        let decisive = match operator {
            Temporal::Always => margins.min_by(|a, b| a.0.total_cmp(&b.0)),
            Temporal::Eventually => margins.max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1))),
        };
        let short_of_steps = count < window.min_steps;
        if short_of_steps && incomplete.is_none() {
            incomplete = Some(if count == 0 {
                format!("{name} is never defined{span} in one of the {} runs", runs.len())
            } else {
                format!(
                    "{name} is defined at {count} steps{span} in one of the {} runs, fewer than the {} the check needs",
                    runs.len(),
                    window.min_steps
                )
            });
        }
        // A run's margin counts when its window is complete, or when it
        // already breaks an `always`, which more steps cannot mend.
        let complete = !short_of_steps && uncovered.is_none();
        if let Some(decisive) = decisive.filter(|d| complete || (operator == Temporal::Always && d.0 < 0.0))
            && worst.is_none_or(|w| decisive.0 < w.0)
        {
            worst = Some(decisive);
            worst_run = run;
        }
    }
    if let Some(why) = &incomplete
        && worst.is_none_or(|(margin, ..)| margin >= 0.0)
    {
        return Evaluation::not_exercised(steps, measured, format!("nothing to judge: {why}"));
    }
    let Some((margin, time, value)) = worst else {
        return Evaluation::error(format!("{name} is not measured at this point (no run to check)"));
    };
    let relation = match bound {
        Bound::AtLeast(t) => format!("≥ {}", short(t)),
        Bound::AtMost(t) => format!("≤ {}", short(t)),
    };
    let what = match operator {
        Temporal::Always => "always",
        Temporal::Eventually => "eventually",
    };
    // Pooled runs: the decisive step's run, counted from 0 (the recording
    // holds run 0 only).
    let of_run = if runs.len() > 1 {
        format!(" of run {worst_run} (runs 0–{} pooled)", runs.len() - 1)
    } else {
        String::new()
    };
    let message = format!(
        "{what} {name} {relation}{span}: {} (robustness {}; {name} = {} at {} s{of_run}; n = {steps} steps)",
        if margin >= 0.0 { "holds" } else { "fails" },
        short(margin),
        short(value),
        short(time)
    );
    Evaluation {
        time: Some(time),
        ..Evaluation::judged(value, margin, steps, measured, message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Status;

    fn check(operator: Temporal, bound: Bound, within: Option<f64>, runs: &[Series]) -> Evaluation {
        let window = Window {
            within,
            covered: Some(10.0),
            min_steps: 1,
        };
        evaluate(Signal::BlindRecall, operator, bound, window, runs)
    }

    const SIGNAL: [(f64, f64); 5] = [(0.0, 0.9), (0.1, 0.7), (0.2, 0.95), (0.3, 0.6), (0.4, 0.85)];

    #[test]
    fn always_takes_the_smallest_margin_and_its_time() {
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[SIGNAL.to_vec()]);
        assert_eq!((found.status, found.n), (Status::Pass, Some(5)));
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
        assert_eq!((found.status, found.time, found.n), (Status::Pass, Some(0.1), Some(3)));
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
        let found = check(
            Temporal::Always,
            Bound::AtLeast(0.5),
            None,
            &[good.clone(), bad.clone()],
        );
        assert_eq!((found.status, found.value, found.n), (Status::Fail, Some(0.4), Some(4)));
        // The message names the pooled run the decisive step is in, from 0.
        assert_eq!(
            found.message,
            "always blind_recall ≥ 0.5: fails (robustness -0.1; blind_recall = 0.4 at 0.1 s of run 1 (runs 0–1 \
             pooled); n = 4 steps)"
        );
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[bad, good]);
        assert!(
            found.message.contains("at 0.1 s of run 0 (runs 0–1 pooled)"),
            "{}",
            found.message
        );
    }

    #[test]
    fn an_empty_signal_is_not_exercised_not_a_vacuous_pass() {
        let found = check(Temporal::Always, Bound::AtLeast(0.5), None, &[Vec::new()]);
        assert_eq!((found.status, found.n), (Status::NotExercised, Some(0)));
        let found = check(Temporal::Always, Bound::AtLeast(0.5), Some(0.05), &[vec![(0.1, 0.9)]]);
        assert_eq!(found.status, Status::NotExercised);
        assert!(
            found.message.contains("never defined within 0.05 s"),
            "{}",
            found.message
        );
        assert_eq!(
            check(Temporal::Always, Bound::AtLeast(0.5), None, &[]).status,
            Status::Error
        );
    }

    #[test]
    fn a_violation_seen_fails_an_always_whatever_the_steps_not_seen() {
        // The 0.6 at 0.3 s breaks `always ≥ 0.65` in a window past the run's
        // end, and in a run pooled with one never defined: a failure either way.
        let found = check(Temporal::Always, Bound::AtLeast(0.65), Some(12.0), &[SIGNAL.to_vec()]);
        assert_eq!(
            (found.status, found.value, found.time),
            (Status::Fail, Some(0.6), Some(0.3))
        );
        let found = check(
            Temporal::Always,
            Bound::AtLeast(0.65),
            None,
            &[Vec::new(), SIGNAL.to_vec()],
        );
        assert_eq!((found.status, found.value, found.n), (Status::Fail, Some(0.6), Some(5)));
        // Held on the steps seen, it stays unjudged; so does an `eventually`
        // met or missed on them (the steps not seen would decide a miss, and
        // a pass on part of a window is not earned).
        let found = check(
            Temporal::Always,
            Bound::AtLeast(0.5),
            None,
            &[Vec::new(), SIGNAL.to_vec()],
        );
        assert_eq!(found.status, Status::NotExercised);
        assert_eq!(
            found.message,
            "nothing to judge: blind_recall is never defined in one of the 2 runs"
        );
        for bound in [Bound::AtLeast(0.9), Bound::AtLeast(0.99)] {
            let found = check(Temporal::Eventually, bound, Some(12.0), &[SIGNAL.to_vec()]);
            assert_eq!(found.status, Status::NotExercised, "{bound:?}");
        }
    }

    #[test]
    fn a_window_past_the_run_is_not_exercised() {
        // The run ends at 10 s; a 12 s window, or one a millisecond longer,
        // is not covered, even though every defined step holds; one of 10 s,
        // the whole run, is.
        for within in [12.0, 10.001] {
            let found = check(Temporal::Always, Bound::AtLeast(0.5), Some(within), &[SIGNAL.to_vec()]);
            assert_eq!(found.status, Status::NotExercised, "{within}");
            assert_eq!(
                found.message,
                format!("nothing to judge: the window of {within} s reaches past the run's end at 10 s")
            );
        }
        assert_eq!(
            check(Temporal::Always, Bound::AtLeast(0.5), Some(10.0), &[SIGNAL.to_vec()]).status,
            Status::Pass
        );
    }

    #[test]
    fn too_few_defined_steps_are_not_exercised() {
        let window = Window {
            within: None,
            covered: None,
            min_steps: 6,
        };
        let found = evaluate(
            Signal::BlindRecall,
            Temporal::Always,
            Bound::AtLeast(0.5),
            window,
            &[SIGNAL.to_vec()],
        );
        assert_eq!((found.status, found.n), (Status::NotExercised, Some(5)));
        assert!(found.message.contains("defined at 5 steps"), "{}", found.message);
    }
}
