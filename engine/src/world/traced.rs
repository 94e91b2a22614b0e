//! Trace replay: where an agent that replays a recorded trace is at a time.
//!
//! A traced agent replays its samples: it is in the scene from its first sample to
//! its last (to within a millionth of a step), except inside a gap between samples
//! longer than its `max_gap`. Between two samples its position, speed and offset
//! are linear in time and its heading turns the short way round; its speed limit
//! is that of the earlier sample's lane. Car following and restraint do not apply:
//! it drives as recorded, so a traced ego does not slow down when cautious.
//!
//! Tested through [`Kinematics`](super::Kinematics), in `world::motion`.

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
