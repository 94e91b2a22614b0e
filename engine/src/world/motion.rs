//! Kinematics: agents along their polylines or replaying their traces, step by
//! step.
//!
//! A moving agent appears at the first step at or after its start time, at its start
//! offset and initial speed. Each step it picks an acceleration, then advances by
//! speed · dt (semi-implicit Euler); it leaves the scene once it passes the end of
//! its way. Kinematics involves no randomness.
//!
//! A traced agent replays its samples: it is in the scene from its first sample to
//! its last (to within a millionth of a step), except inside a gap between samples
//! longer than its `max_gap`. Between two samples its position, speed and offset
//! are linear in time and its heading turns the short way round; its speed limit
//! is that of the earlier sample's lane. Car following and restraint do not apply:
//! it drives as recorded, so a traced ego does not slow down when cautious.
//!
//! Its wanted speed is its target, capped by the speed limit where it is times its
//! limit factor (and by a caution factor while the ego is cautious). Without car
//! following, speed moves toward the wanted speed by at most acceleration · dt.
//! With `following: idm`, a vehicle applies the Intelligent Driver Model
//! (Treiber, Hennecke and Helbing, 2000) behind its leader: the closest vehicle
//! heading within `SAME_WAY` of its own, or pedestrian, whose centre lies ahead of
//! it within `LOOKAHEAD` and whose footprint overlaps its own across the heading,
//! as positioned at the previous step. The leader's speed counts along the
//! follower's heading (a pedestrian's as 0). There are no right-of-way rules:
//! crossing vehicles do not see each other, so a junction never locks up, and
//! they may meet in it — the conflicts the semantic pipeline is there to flag.
//! With car following, a vehicle whose start time has come enters only when its
//! lane is clear (every road user in it at least `min_gap` plus one headway of the
//! follower's speed away, ahead and behind); until then it waits, as SUMO delays
//! an insertion. Agents listed first enter first.

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use sightline_dsl::geometry::Polyline;
use sightline_dsl::{Agent, AgentKind, Driving, Following, Motion, TraceSample};

use crate::idealisation::Idealisation;
use crate::math::{Point, Pose, Vector};

/// Road users keep to their ways.
pub(crate) const ON_THEIR_WAY: Idealisation = Idealisation {
    id: "motion.on-their-way",
    text: "Road users follow their lane's centreline or their path exactly (no lateral motion, no lane \
           changes) and change speed by at most their acceleration; traced road users move straight at \
           constant speed between samples.",
};

/// Without car following, vehicles pass through each other.
pub(crate) const NO_FOLLOWING: Idealisation = Idealisation {
    id: "motion.no-following",
    text: "Vehicles ignore each other (`following: none`): they drive through one another rather than slow \
           down.",
};

/// Car following has no right of way.
pub(crate) const NO_RIGHT_OF_WAY: Idealisation = Idealisation {
    id: "motion.no-right-of-way",
    text: "Vehicles follow the one ahead in their lane (IDM) but obey no right-of-way rule: crossing vehicles \
           do not see each other and may meet in a junction.",
};

/// The idealisations of a car-following model.
pub(crate) fn following_idealisations(following: Following) -> &'static [Idealisation] {
    match following {
        Following::None => &[NO_FOLLOWING],
        Following::Idm => &[NO_RIGHT_OF_WAY],
    }
}

/// How far ahead a vehicle looks for a leader, metres.
const LOOKAHEAD: f64 = 100.0;

/// Largest heading difference of a vehicle followed, radians (60°).
const SAME_WAY: f64 = std::f64::consts::FRAC_PI_3;

/// The hardest braking IDM may ask for, m/s².
const MAX_BRAKING: f64 = 9.0;

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
    driving: Driving,
    progress: Vec<Progress>,
    restraints: Vec<Option<Restraint>>,
    previous: Vec<Option<AgentState>>,
    /// The road users of the previous step by area.
    nearby: Nearby,
    /// Agents that entered the scene at the step being computed.
    entered: Vec<usize>,
}

impl<'a> Kinematics<'a> {
    /// Every agent before the first step.
    pub fn new(agents: &'a [Agent], step: f64, driving: Driving) -> Self {
        Self {
            agents,
            step,
            driving,
            progress: vec![Progress::Waiting; agents.len()],
            restraints: vec![None; agents.len()],
            previous: vec![None; agents.len()],
            nearby: Nearby::default(),
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
        let time = k as f64 * self.step;
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
                    ..
                } => {
                    self.progress[i] = match self.progress[i] {
                        // A tolerance of a millionth of a step keeps `start: 0.3` with
                        // `step: 0.1` from waiting a step for 0.30000000000000004.
                        Progress::Waiting
                            if time + 1e-6 * self.step >= *start_time
                                && self.entry_clear(i, path, *start_offset, *initial_speed, states) =>
                        {
                            self.entered.push(i);
                            Progress::Moving {
                                offset: *start_offset,
                                speed: *initial_speed,
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
        self.previous.clone_from(states);
        self.nearby.index(&self.previous);
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
        if self.driving.following == Following::None || !agent.kind.is_vehicle() {
            return speed + (wanted - speed).clamp(-acceleration * self.step, acceleration * self.step);
        }
        let (gap, leader_speed) = self.leader(i).unwrap_or((f64::INFINITY, speed));
        let headway = restraint.map_or(self.driving.headway, |r| r.headway);
        let free = if wanted > 0.0 {
            1.0 - (speed / wanted).powi(4)
        } else {
            -1.0
        };
        let approach = speed * (speed - leader_speed) / (2.0 * (acceleration * self.driving.deceleration).sqrt());
        let desired_gap = self.driving.min_gap + (speed * headway + approach).max(0.0);
        let interaction = (desired_gap / gap.max(0.01)).powi(2);
        let accel = (acceleration * (free - interaction)).clamp(-MAX_BRAKING, *acceleration);
        (speed + accel * self.step).max(0.0)
    }

    /// The gap to agent `i`'s leader and the leader's speed along `i`'s heading.
    fn leader(&self, i: usize) -> Option<(f64, f64)> {
        let me = self.previous[i]?;
        self.nearby
            .around(me.position())
            .filter_map(|j| {
                let (ahead, along) = self.in_lane(i, &me, j, &self.previous[j]?)?;
                (ahead > 0.0).then(|| (ahead - (self.agents[i].length + self.agents[j].length) / 2.0, along))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Whether vehicle `i` may enter at `offset` along `path` at `speed`: with car
    /// following, every road user in its lane keeps at least the desired standing
    /// gap plus one headway of the follower's speed, ahead of it and behind it.
    /// Road users are placed as at the previous step, except those that entered
    /// at this one (`current`). Without car following, or for a pedestrian, always.
    fn entry_clear(&self, i: usize, path: &Polyline, offset: f64, speed: f64, current: &[Option<AgentState>]) -> bool {
        if self.driving.following == Following::None || !self.agents[i].kind.is_vehicle() {
            return true;
        }
        let [x, y] = path.point_at(offset);
        let me = AgentState {
            pose: Pose::new(Vector::new(x, y), path.heading_at(offset)),
            speed,
            offset,
            limit: f64::INFINITY,
        };
        let previous = self
            .nearby
            .around(me.position())
            .filter_map(|j| Some((j, self.previous[j]?)));
        let entered = self.entered.iter().filter_map(|&j| Some((j, current[j]?)));
        previous.chain(entered).all(|(j, other)| {
            let Some((ahead, _)) = self.in_lane(i, &me, j, &other) else {
                return true;
            };
            let gap = ahead.abs() - (self.agents[i].length + self.agents[j].length) / 2.0;
            let follower_speed = if ahead > 0.0 { speed } else { other.speed };
            gap >= self.driving.min_gap + follower_speed * self.driving.headway
        })
    }

    /// Where agent `j` in state `other` is for vehicle `i` in state `me`, if it is
    /// in `i`'s lane (footprints overlapping across `i`'s heading, within
    /// `LOOKAHEAD` either way, a vehicle heading within `SAME_WAY` or any
    /// pedestrian): how far its centre is ahead of `i`'s (negative behind) and its
    /// speed along `i`'s heading.
    fn in_lane(&self, i: usize, me: &AgentState, j: usize, other: &AgentState) -> Option<(f64, f64)> {
        let (agent, them) = (&self.agents[i], &self.agents[j]);
        if j == i || them.kind == AgentKind::Rsu {
            return None;
        }
        // Trigonometry-free: this runs for every pair of road users every step.
        let (cos, sin) = (me.pose.rotation.cos(), me.pose.rotation.sin());
        let d = other.position() - me.position();
        let ahead = d.x * cos + d.y * sin;
        let across = -d.x * sin + d.y * cos;
        let turn = cos * other.pose.rotation.cos() + sin * other.pose.rotation.sin();
        let followed = them.kind == AgentKind::Pedestrian || turn >= SAME_WAY.cos();
        let overlap = (agent.width + them.width) / 2.0;
        (followed && ahead.abs() <= LOOKAHEAD && across.abs() < overlap).then(|| {
            let along = if them.kind.is_vehicle() {
                other.speed * turn
            } else {
                0.0
            };
            (ahead, along.max(0.0))
        })
    }
}

/// Road users by square cells of `LOOKAHEAD` metres, so that finding who is in a
/// lane looks at the 3 × 3 cells around a position, not at every agent.
#[derive(Debug, Clone, Default)]
struct Nearby {
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl Nearby {
    /// Indexes every present agent of `states`.
    fn index(&mut self, states: &[Option<AgentState>]) {
        self.cells.values_mut().for_each(Vec::clear);
        for (i, state) in states.iter().enumerate() {
            if let Some(state) = state {
                self.cells.entry(Self::cell(state.position())).or_default().push(i);
            }
        }
    }

    /// Every agent within `LOOKAHEAD` of `position` (and some farther), in a
    /// fixed order.
    fn around(&self, position: Point) -> impl Iterator<Item = usize> + '_ {
        let (cx, cy) = Self::cell(position);
        (-1..=1)
            .flat_map(move |dx| (-1..=1).map(move |dy| (cx + dx, cy + dy)))
            .filter_map(|cell| self.cells.get(&cell))
            .flatten()
            .copied()
    }

    fn cell(position: Point) -> (i64, i64) {
        (
            (position.x / LOOKAHEAD).floor() as i64,
            (position.y / LOOKAHEAD).floor() as i64,
        )
    }
}

/// Where a traced agent is at `time`, `None` when it is out of the scene; times
/// within `tolerance` of a sample count as the sample's.
fn replay(samples: &[TraceSample], max_gap: f64, time: f64, tolerance: f64) -> Option<AgentState> {
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
            },
            connected: false,
            sensors: Vec::new(),
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
}
