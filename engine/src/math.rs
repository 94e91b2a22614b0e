//! The geometry vocabulary of the engine: parry's types (glam underneath), so that
//! positions go to parry's ray casts and BVH without conversion. Signatures use
//! these names, never glam's or nalgebra's.

pub use parry2d_f64::math::{Pose, Vector};

/// A position in the world frame, metres: a vector from the world origin (glam has
/// no separate point type).
pub type Point = Vector;

/// The time of step `k` of `step` seconds, to the nanosecond: k · step as a
/// float product misses the decimal by ~1e-16 (3 × 0.1 s gives
/// 0.30000000000000004), so that every time the evidence prints reads as the
/// decimal it is (0.3) and a time written in a scenario compares equal to it.
pub fn step_time(k: usize, step: f64) -> f64 {
    to_ns(k as f64 * step)
}

/// `seconds` rounded to the nanosecond: a time computed as a quotient or a
/// product of decimals (a TTC of 5.8 m at 5 m/s) reads as the decimal it is,
/// 1.16, not 1.1599999999999995, and a threshold written as that decimal
/// holds at equality.
pub fn to_ns(seconds: f64) -> f64 {
    (seconds * 1e9).round() / 1e9
}

/// The time from `earlier` to `later`, seconds, to the nanosecond. Step times
/// are k·dt, so the time between two of them is a whole number of steps, which
/// a float subtraction misses by ~1e-16 (12 steps of 0.1 s give
/// 1.1999999999999997, and `at_least: 1.2` failed); rounded to whole
/// nanoseconds it is the double nearest the decimal (1.2) for any step that is
/// a whole number of nanoseconds. A time that is not a step time (a message's
/// arrival) moves by less than half a nanosecond.
pub fn elapsed(later: f64, earlier: f64) -> f64 {
    to_ns(later - earlier)
}

#[cfg(test)]
mod elapsed_tests {
    use super::elapsed;

    #[test]
    fn step_times_are_the_decimal() {
        assert_eq!(3.0 * 0.1, 0.30000000000000004);
        assert_eq!(super::step_time(3, 0.1), 0.3);
        assert_eq!(super::step_time(51, 0.1), 5.1);
        assert_eq!(super::step_time(604, 0.1), 60.4);
        assert_eq!(super::step_time(7, 0.05), 0.35);
    }

    #[test]
    fn whole_steps_give_the_decimal() {
        assert_eq!(elapsed(2.2, 1.0), 1.2);
        assert_eq!(elapsed(22.0 * 0.1, 10.0 * 0.1), 1.2);
        assert_eq!(elapsed(3.8 + 0.1, 0.1), 3.8);
        assert_eq!(elapsed(1.0, 1.0 + 4e-7), -4e-7);
    }
}
