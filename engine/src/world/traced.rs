//! Trace replay: where an agent that replays a recorded trace is at a time.
//!
//! A traced agent replays its samples: it is in the scene from its first sample to
//! its last (to within a millionth of a step), except inside a gap between samples
//! longer than its `max_gap`. Between two samples its position, speed and offset
//! are linear in time and its heading turns the short way round; its speed limit
//! is that of the earlier sample's lane. Car following and restraint do not apply:
//! it drives as recorded, so a traced ego does not slow down when cautious.

use std::f64::consts::{PI, TAU};

use sightline_dsl::TraceSample;

use super::state::AgentState;
use crate::math::{Pose, Vector};

/// Where a traced agent is at `time`, `None` when it is out of the scene; times
/// within `tolerance` of a sample count as the sample's.
pub(super) fn replay(samples: &[TraceSample], max_gap: f64, time: f64, tolerance: f64) -> Option<AgentState> {
    let (first, last) = (samples.first()?, samples.last()?);
    if time < first.time - tolerance || time > last.time + tolerance {
        return None;
    }
    let next = samples.partition_point(|s| s.time <= time);
    let (a, b) = match next {
        0 => (first, first),
        n if n == samples.len() => (last, last),
        n => (&samples[n - 1], &samples[n]),
    };
    let (a, b) = if b.time - a.time <= max_gap {
        (a, b)
    } else if time - a.time <= tolerance {
        (a, a)
    } else if b.time - time <= tolerance {
        (b, b)
    } else {
        return None;
    };
    let u = if b.time > a.time {
        ((time - a.time) / (b.time - a.time)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let lerp = |from: f64, to: f64| from + (to - from) * u;
    let turn = (b.heading - a.heading + PI).rem_euclid(TAU) - PI;
    Some(AgentState {
        pose: Pose::new(
            Vector::new(lerp(a.position[0], b.position[0]), lerp(a.position[1], b.position[1])),
            a.heading + turn * u,
        ),
        speed: lerp(a.speed, b.speed),
        offset: lerp(a.offset, b.offset),
        limit: a.limit,
    })
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use sightline_dsl::geometry::Polyline;
    use sightline_dsl::{Agent, Motion};

    use super::super::motion::tests::{restrained, trajectory_with, walker};
    use super::*;

    fn sample(time: f64, x: f64, heading: f64, speed: f64) -> TraceSample {
        TraceSample {
            time,
            position: [x, 0.0],
            heading,
            speed,
            offset: x,
            limit: 13.9,
        }
    }

    fn replayed(samples: Vec<TraceSample>, max_gap: f64, step: f64, steps: usize) -> Vec<Option<AgentState>> {
        trajectory_with(
            Agent {
                motion: Motion::Trace {
                    path: Polyline::new(samples.iter().map(|s| s.position)),
                    samples,
                    max_gap,
                },
                ..walker(0.0, 0.0, 30.0)
            },
            step,
            steps,
        )
    }

    /// Samples at 1 s (x = 10 m, 8 m/s) and 2 s (x = 20 m, 12 m/s); at 1.25 s,
    /// a quarter of the way: x = 12.5 m, 9 m/s, offset 12.5 m.
    #[test]
    fn a_trace_is_linear_between_two_samples() {
        let states = replayed(
            vec![sample(1.0, 10.0, 0.0, 8.0), sample(2.0, 20.0, 0.0, 12.0)],
            1.0,
            0.25,
            10,
        );
        let at = states[5].unwrap();
        assert_relative_eq!(at.position().x, 12.5);
        assert_relative_eq!(at.position().y, 0.0);
        assert_relative_eq!(at.speed, 9.0);
        assert_relative_eq!(at.offset, 12.5);
        assert_eq!(at.limit, 13.9);
    }

    /// In the scene from the first sample (step 4 at 0.25 s) to the last (step 8),
    /// both included; not before, not after.
    #[test]
    fn a_trace_is_present_from_its_first_to_its_last_sample() {
        let states = replayed(
            vec![sample(1.0, 10.0, 0.0, 8.0), sample(2.0, 20.0, 0.0, 12.0)],
            1.0,
            0.25,
            12,
        );
        let present: Vec<usize> = (0..12).filter(|&k| states[k].is_some()).collect();
        assert_eq!(present, [4, 5, 6, 7, 8]);
        // Sample times that are not exact multiples of the step still count:
        // 0.3 is step 3 of 0.1 s, though 3 × 0.1 = 0.30000000000000004.
        let states = replayed(
            vec![sample(0.2, 0.0, 0.0, 1.0), sample(0.3, 0.1, 0.0, 1.0)],
            1.0,
            0.1,
            5,
        );
        assert!(states[2].is_some() && states[3].is_some() && states[4].is_none());
    }

    /// From 170° to −170° the heading turns 20° through ±180°, not 340° back
    /// through 0: halfway it points at 180°.
    #[test]
    fn a_trace_turns_the_short_way_across_the_wrap() {
        let [from, to] = [170f64.to_radians(), (-170f64).to_radians()];
        let states = replayed(
            vec![sample(0.0, 0.0, from, 5.0), sample(1.0, 5.0, to, 5.0)],
            1.0,
            0.25,
            5,
        );
        let halfway = states[2].unwrap().heading();
        assert_relative_eq!(halfway.abs(), std::f64::consts::PI, epsilon = 1e-9);
        let quarter = states[1].unwrap().heading();
        assert_relative_eq!(quarter, 175f64.to_radians(), epsilon = 1e-9);
        let three_quarters = states[3].unwrap().heading();
        assert_relative_eq!(three_quarters, (-175f64).to_radians(), epsilon = 1e-9);
    }

    /// Samples 3 s apart with a 1.5 s gap allowed: present at both samples, out of
    /// the scene between them.
    #[test]
    fn a_trace_is_absent_inside_a_long_gap() {
        let states = replayed(
            vec![sample(0.0, 0.0, 0.0, 5.0), sample(3.0, 15.0, 0.0, 5.0)],
            1.5,
            1.0,
            5,
        );
        let present: Vec<bool> = states.iter().map(Option::is_some).collect();
        assert_eq!(present, [true, false, false, true, false]);
    }

    /// A traced agent drives as recorded: restraint does not slow it down.
    #[test]
    fn a_trace_ignores_restraint() {
        let agents = [Agent {
            motion: Motion::Trace {
                samples: vec![sample(0.0, 0.0, 0.0, 10.0), sample(10.0, 100.0, 0.0, 10.0)],
                path: Polyline::new([[0.0, 0.0], [100.0, 0.0]]),
                max_gap: 10.0,
            },
            ..walker(0.0, 0.0, 30.0)
        }];
        let state = restrained(&agents, 5);
        assert_relative_eq!(state.speed, 10.0);
        assert_relative_eq!(state.position().x, 20.0);
    }
}
