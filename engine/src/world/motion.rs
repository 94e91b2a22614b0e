//! Kinematics: agents along their polylines or replaying their traces, step by
//! step.
//!
//! A moving agent appears at the first step at or after its start time, at its start
//! offset and initial speed. Each step it picks an acceleration, then advances by
//! speed · dt (semi-implicit Euler); it leaves the scene once it passes the end of
//! its way. Kinematics involves no randomness.
//!
//! Its wanted speed is its target, capped by the speed limit where it is times its
//! limit factor (and by a caution factor while the ego is cautious). Without car
//! following, speed moves toward the wanted speed by at most acceleration · dt;
//! with it, a vehicle follows the road user ahead and enters only a clear lane
//! (`world::following`). A traced agent replays its samples (`world::traced`).

use sightline_dsl::{Agent, Driving, Entry, Motion};

use super::following::CarFollowing;
use super::state::{AgentState, Restraint};
use super::traced::replay;
use crate::idealisation::Idealisation;
use crate::math::{Pose, Vector, step_time};

/// Road users keep to their ways.
pub(crate) const ON_THEIR_WAY: Idealisation = Idealisation {
    id: "motion.on-their-way",
    text: "Road users follow their lane's centreline or their path exactly (no lateral motion, no lane \
           changes) and change speed by at most their acceleration; traced road users move straight at \
           constant speed between samples.",
};

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
    restraints: Vec<Option<Restraint>>,
    /// Car following, which remembers where road users were at the previous step.
    following: CarFollowing<'a>,
    /// Agents that entered the scene at the step being computed.
    entered: Vec<usize>,
}

impl<'a> Kinematics<'a> {
    /// Every agent before the first step.
    pub fn new(agents: &'a [Agent], step: f64, driving: Driving) -> Self {
        Self {
            agents,
            step,
            progress: vec![Progress::Waiting; agents.len()],
            restraints: vec![None; agents.len()],
            following: CarFollowing::new(agents, step, driving),
            entered: Vec::new(),
        }
    }

    /// Restrains agent `agent` from the next step on (`None`: drives normally). A
    /// traced agent ignores it.
    pub fn restrain(&mut self, agent: usize, restraint: Option<Restraint>) {
        self.restraints[agent] = restraint;
    }

    /// The states at step `k` (time k · step), advancing from step k − 1. Call for
    /// k = 0, 1, 2, … in order. `None`: the agent is not in the scene.
    pub fn advance(&mut self, k: usize, states: &mut Vec<Option<AgentState>>) {
        let time = step_time(k, self.step);
        states.clear();
        self.entered.clear();
        for i in 0..self.agents.len() {
            let agent = &self.agents[i];
            states.push(match &agent.motion {
                Motion::Fixed { position, heading } => Some(AgentState {
                    pose: Pose::new(Vector::new(position[0], position[1]), *heading),
                    speed: 0.0,
                    offset: 0.0,
                    limit: f64::INFINITY,
                }),
                Motion::Along {
                    path,
                    limits,
                    start_time,
                    start_offset,
                    initial_speed,
                    entry,
                    ..
                } => {
                    self.progress[i] = match self.progress[i] {
                        // A tolerance of a millionth of a step keeps `start: 0.3` with
                        // `step: 0.1` from waiting a step for 0.30000000000000004.
                        Progress::Waiting if time + 1e-6 * self.step >= *start_time => {
                            if self
                                .following
                                .entry_clear(i, path, *start_offset, *initial_speed, &self.entered, states)
                            {
                                self.entered.push(i);
                                Progress::Moving {
                                    offset: *start_offset,
                                    speed: *initial_speed,
                                }
                            } else if *entry == Entry::OnTime {
                                Progress::Gone
                            } else {
                                Progress::Waiting
                            }
                        }
                        Progress::Moving { offset, speed } => {
                            let speed = self.next_speed(i, offset, speed);
                            let offset = offset + speed * self.step;
                            if offset > path.length() {
                                Progress::Gone
                            } else {
                                Progress::Moving { offset, speed }
                            }
                        }
                        other => other,
                    };
                    match self.progress[i] {
                        Progress::Moving { offset, speed } => {
                            let [x, y] = path.point_at(offset);
                            Some(AgentState {
                                pose: Pose::new(Vector::new(x, y), path.heading_at(offset)),
                                speed,
                                offset,
                                limit: limit_at(limits, offset),
                            })
                        }
                        Progress::Waiting | Progress::Gone => None,
                    }
                }
                Motion::Trace { samples, max_gap, .. } => replay(samples, *max_gap, time, 1e-6 * self.step),
            });
        }
        self.following.remember(states);
    }

    /// The speed of moving agent `i` one step after being at `offset` at `speed`.
    fn next_speed(&self, i: usize, offset: f64, speed: f64) -> f64 {
        let agent = &self.agents[i];
        let Motion::Along {
            limits,
            target_speed,
            limit_factor,
            acceleration,
            ..
        } = &agent.motion
        else {
            return 0.0;
        };
        let restraint = self.restraints[i];
        let wanted =
            target_speed.min(limit_at(limits, offset) * limit_factor) * restraint.map_or(1.0, |r| r.speed_factor);
        if !self.following.applies(i) {
            return speed + (wanted - speed).clamp(-acceleration * self.step, acceleration * self.step);
        }
        self.following.next_speed(i, speed, wanted, *acceleration, restraint)
    }
}

/// The limit in force at `offset`: the first entry that ends after it, else the last.
fn limit_at(limits: &[(f64, f64)], offset: f64) -> f64 {
    limits
        .iter()
        .find(|&&(end, _)| offset < end)
        .or(limits.last())
        .map_or(f64::INFINITY, |&(_, limit)| limit)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use sightline_dsl::geometry::Polyline;
    use sightline_dsl::{AgentKind, Following, TraceSample};

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
                limit_factor: 1.0,
                acceleration: 2.0,
                entry: Entry::Queue,
            },
            connected: false,
            sensors: Vec::new(),
            antenna_m: None,
        }
    }

    fn driving(following: Following) -> Driving {
        Driving {
            following,
            headway: 1.5,
            min_gap: 2.0,
            deceleration: 3.0,
        }
    }

    fn trajectory(agent: Agent, steps: usize) -> Vec<Option<AgentState>> {
        trajectory_with(agent, 0.5, steps)
    }

    fn trajectory_with(agent: Agent, step: f64, steps: usize) -> Vec<Option<AgentState>> {
        let agents = [agent];
        let mut kinematics = Kinematics::new(&agents, step, driving(Following::None));
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

    fn with(mut agent: Agent, edit: impl FnOnce(&mut f64, &mut f64, &mut f64, &mut f64)) -> Agent {
        if let Motion::Along {
            start_offset,
            initial_speed,
            target_speed,
            limit_factor,
            ..
        } = &mut agent.motion
        {
            edit(start_offset, initial_speed, target_speed, limit_factor);
        }
        agent
    }

    #[test]
    fn a_non_compliant_driver_exceeds_the_limit_by_its_factor() {
        let fast = with(walker(0.0, 4.0, 4.0), |_, _, target, factor| {
            *target = 50.0;
            *factor = 1.5;
        });
        let states = trajectory(fast, 12);
        // Limit 4 m/s on the first 50 m, times 1.5: it settles at 6 m/s.
        assert_eq!(states[2].unwrap().speed, 6.0);
        assert_eq!(states[2].unwrap().limit, 4.0);
    }

    /// Agent 0 of `agents` after `steps` steps of 0.5 s with IDM, restrained from
    /// the start to a 2.5 s headway and half its wanted speed.
    fn restrained(agents: &[Agent], steps: usize) -> AgentState {
        let mut kinematics = Kinematics::new(agents, 0.5, driving(Following::Idm));
        kinematics.restrain(
            0,
            Some(Restraint {
                headway: 2.5,
                speed_factor: 0.5,
            }),
        );
        let mut states = Vec::new();
        for k in 0..steps {
            kinematics.advance(k, &mut states);
        }
        states[0].expect("the agent is in the scene")
    }

    #[test]
    fn restraint_lowers_the_wanted_speed() {
        let speed = restrained(&[walker(0.0, 10.0, 30.0)], 20).speed;
        assert!((4.95..=5.05).contains(&speed), "speed {speed}");
    }

    // Car following (`world::following`).

    /// A car at 10 m/s closes on a car standing 60 m ahead: IDM brakes it to a stop
    /// behind the other, at least the minimum gap away, and never through it.
    #[test]
    fn idm_stops_behind_a_standing_vehicle() {
        let follower = with(walker(0.0, 10.0, 30.0), |offset, _, _, _| *offset = 0.0);
        let standing = with(walker(0.0, 0.0, 30.0), |offset, initial, target, _| {
            *offset = 60.0;
            *initial = 0.0;
            *target = 0.0;
        });
        let agents = [follower, standing];
        let mut kinematics = Kinematics::new(&agents, 0.1, driving(Following::Idm));
        let mut states = Vec::new();
        let mut gaps = Vec::new();
        for k in 0..400 {
            kinematics.advance(k, &mut states);
            let [a, b] = [states[0].unwrap(), states[1].unwrap()];
            gaps.push(b.offset - a.offset - 4.5);
        }
        assert!(
            gaps.iter().all(|&g| g > 0.5),
            "closest gap {:?}",
            gaps.iter().copied().reduce(f64::min)
        );
        let last = *gaps.last().unwrap();
        assert!((1.5..=3.0).contains(&last), "final gap {last}");
        assert!(states[0].unwrap().speed < 0.05);
    }

    /// A car due at offset 0 while another drives away from offset 5 waits until
    /// the gap is at least min_gap + speed · headway = 2 + 10 · 1.5 = 17 m.
    #[test]
    fn idm_delays_an_entry_until_the_lane_is_clear() {
        let leader = with(walker(0.0, 10.0, 30.0), |offset, _, _, _| *offset = 5.0);
        let follower = with(walker(0.0, 10.0, 30.0), |offset, _, _, _| *offset = 0.0);
        let agents = [leader, follower];
        let mut kinematics = Kinematics::new(&agents, 0.1, driving(Following::Idm));
        let mut states = Vec::new();
        let mut entered = None;
        for k in 0..40 {
            kinematics.advance(k, &mut states);
            if entered.is_none()
                && let Some(follower) = states[1]
            {
                entered = Some((k, states[0].unwrap().offset - follower.offset - 4.5));
            }
        }
        let (k, gap) = entered.expect("the follower enters once the leader is far enough");
        // The leader's gap grows by 1 m a step from 0.5 m: 17.5 m at k = 17, which
        // the follower sees at k = 18 (entries look at the previous step).
        assert_eq!(k, 18, "gap {gap}");
        assert!(gap >= 17.0 - 1e-9);
        // Without car following, both enter at once.
        let mut kinematics = Kinematics::new(&agents, 0.1, driving(Following::None));
        kinematics.advance(0, &mut states);
        assert!(states.iter().all(Option::is_some));
    }

    /// A car placed at offset 0 as the run starts, whose place a car ahead at
    /// offset 5 holds, is left out when it may only enter on time; queueing, it
    /// appears there 18 steps later (above).
    #[test]
    fn an_entry_on_time_whose_place_is_taken_never_enters() {
        let leader = with(walker(0.0, 10.0, 30.0), |offset, _, _, _| *offset = 5.0);
        let mut late = with(walker(0.0, 10.0, 30.0), |offset, _, _, _| *offset = 0.0);
        if let Motion::Along { entry, .. } = &mut late.motion {
            *entry = Entry::OnTime;
        }
        let agents = [leader, late];
        let mut kinematics = Kinematics::new(&agents, 0.1, driving(Following::Idm));
        let mut states = Vec::new();
        for k in 0..40 {
            kinematics.advance(k, &mut states);
            assert!(states[0].is_some() && states[1].is_none(), "step {k}");
        }
    }

    // Trace replay (`world::traced`).

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
