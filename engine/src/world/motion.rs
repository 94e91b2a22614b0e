//! Kinematics: agents along their polylines, step by step.
//!
//! A moving agent appears at the first step at or after its start time, at its start
//! offset and initial speed. Each step its speed moves toward the target (capped by
//! the speed limit where it is) by at most acceleration · dt, then it advances by
//! speed · dt (semi-implicit Euler). It leaves the scene once it passes the end of
//! its way. Kinematics involves no randomness.

use sightline_dsl::{Agent, Motion};

use crate::math::{Point, Pose, Vector};

/// Where an agent is at a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AgentState {
    /// Position of the footprint's centre and heading, world frame.
    pub pose: Pose,
    /// Speed, m/s.
    pub speed: f64,
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

/// The moving part of an agent's state between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Progress {
    Waiting,
    Moving { offset: f64, speed: f64 },
    Gone,
}

/// Advances every agent of a world step by step.
#[derive(Debug, Clone)]
pub struct Kinematics<'a> {
    agents: &'a [Agent],
    step: f64,
    progress: Vec<Progress>,
}

impl<'a> Kinematics<'a> {
    /// Every agent before the first step.
    pub fn new(agents: &'a [Agent], step: f64) -> Self {
        Self {
            agents,
            step,
            progress: vec![Progress::Waiting; agents.len()],
        }
    }

    /// The states at step `k` (time k · step), advancing from step k − 1. Call for
    /// k = 0, 1, 2, … in order. `None`: the agent is not in the scene.
    pub fn advance(&mut self, k: usize, states: &mut Vec<Option<AgentState>>) {
        let time = k as f64 * self.step;
        states.clear();
        for (agent, progress) in self.agents.iter().zip(&mut self.progress) {
            states.push(match &agent.motion {
                Motion::Fixed { position, heading } => Some(AgentState {
                    pose: Pose::new(Vector::new(position[0], position[1]), *heading),
                    speed: 0.0,
                }),
                Motion::Along {
                    path,
                    limits,
                    start_time,
                    start_offset,
                    initial_speed,
                    target_speed,
                    acceleration,
                } => {
                    *progress = match *progress {
                        // A tolerance of a millionth of a step keeps `start: 0.3` with
                        // `step: 0.1` from waiting a step for 0.30000000000000004.
                        Progress::Waiting if time + 1e-6 * self.step >= *start_time => Progress::Moving {
                            offset: *start_offset,
                            speed: *initial_speed,
                        },
                        Progress::Moving { offset, speed } => {
                            let limit = limits
                                .iter()
                                .find(|&&(end, _)| offset < end)
                                .or(limits.last())
                                .map_or(f64::INFINITY, |&(_, limit)| limit);
                            let wanted = target_speed.min(limit);
                            let change = (wanted - speed).clamp(-acceleration * self.step, acceleration * self.step);
                            let speed = speed + change;
                            let offset = offset + speed * self.step;
                            if offset > path.length() {
                                Progress::Gone
                            } else {
                                Progress::Moving { offset, speed }
                            }
                        }
                        other => other,
                    };
                    match *progress {
                        Progress::Moving { offset, speed } => {
                            let [x, y] = path.point_at(offset);
                            Some(AgentState {
                                pose: Pose::new(Vector::new(x, y), path.heading_at(offset)),
                                speed,
                            })
                        }
                        Progress::Waiting | Progress::Gone => None,
                    }
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use sightline_dsl::AgentKind;
    use sightline_dsl::geometry::Polyline;

    use super::*;

    fn walker(start_time: f64, initial_speed: f64, limit: f64) -> Agent {
        Agent {
            id: "a".into(),
            kind: AgentKind::Car,
            length: 4.5,
            width: 1.8,
            motion: Motion::Along {
                path: Polyline::new([[0.0, 0.0], [100.0, 0.0]]).unwrap(),
                limits: vec![(50.0, limit), (100.0, 20.0)],
                start_time,
                start_offset: 10.0,
                initial_speed,
                target_speed: 10.0,
                acceleration: 2.0,
            },
            connected: false,
            sensors: Vec::new(),
        }
    }

    fn trajectory(agent: Agent, steps: usize) -> Vec<Option<AgentState>> {
        let agents = [agent];
        let mut kinematics = Kinematics::new(&agents, 0.5);
        let mut states = Vec::new();
        (0..steps)
            .map(|k| {
                kinematics.advance(k, &mut states);
                states[0]
            })
            .collect()
    }

    #[test]
    fn appears_at_its_start_time_and_offset() {
        let states = trajectory(walker(1.0, 10.0, 30.0), 4);
        assert!(states[0].is_none() && states[1].is_none());
        assert_eq!(states[2].unwrap().position(), Vector::new(10.0, 0.0));
        assert_relative_eq!(states[3].unwrap().position().x, 15.0);
    }

    /// From rest at 2 m/s² with dt = 0.5: speeds 1, 2, 3, …; offsets 10.5, 11.5, 13, …
    #[test]
    fn accelerates_toward_the_target() {
        let states = trajectory(walker(0.0, 0.0, 30.0), 4);
        let speeds: Vec<f64> = states.iter().map(|s| s.unwrap().speed).collect();
        assert_eq!(speeds, vec![0.0, 1.0, 2.0, 3.0]);
        assert_relative_eq!(states[3].unwrap().position().x, 13.0);
    }

    #[test]
    fn never_exceeds_the_speed_limit() {
        let states = trajectory(walker(0.0, 10.0, 4.0), 10);
        assert!(states[1..].iter().all(|s| s.unwrap().speed <= 10.0));
        // Brakes at 2 m/s² from 10 toward the 4 m/s limit: 9, 8, 7, …
        assert_eq!(states[1].unwrap().speed, 9.0);
        assert_eq!(states[6].unwrap().speed, 4.0);
    }

    #[test]
    fn leaves_after_the_end_of_its_way() {
        let states = trajectory(walker(0.0, 10.0, 30.0), 40);
        let last_seen = states.iter().rposition(Option::is_some).unwrap();
        assert!(states[last_seen + 1..].iter().all(Option::is_none));
        assert!(states[last_seen].unwrap().position().x <= 100.0);
    }
}
