//! An agent's state at a step, and a restraint on how it drives: what
//! kinematics, car following, trace replay and sensing share.

use crate::math::{Point, Pose};

/// Where an agent is at a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AgentState {
    /// Position of the footprint's centre and heading, world frame.
    pub pose: Pose,
    /// Speed, m/s.
    pub speed: f64,
    /// Distance along its way, metres (0 for a fixed agent).
    pub offset: f64,
    /// The speed limit where it is, m/s (infinite off roads).
    pub limit: f64,
}

impl AgentState {
    /// The centre of the footprint.
    pub fn position(&self) -> Point {
        self.pose.translation
    }

    /// The heading, radians.
    pub fn heading(&self) -> f64 {
        self.pose.rotation.angle()
    }
}

/// A temporary change of an agent's driving: a longer headway and a lower speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restraint {
    /// Time headway, seconds.
    pub headway: f64,
    /// Share of the wanted speed kept.
    pub speed_factor: f64,
}
