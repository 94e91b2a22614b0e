//! Car following: how a vehicle keeps its distance behind the road user ahead
//! in its lane, and when a vehicle due to enter finds its lane clear.
//!
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
//!
//! Tested through [`Kinematics`](super::Kinematics), in `world::motion`.

use std::collections::HashMap;

use foldhash::fast::FixedState;

use sightline_dsl::geometry::Polyline;
use sightline_dsl::{Agent, AgentKind, Driving, Following};

use super::state::{AgentState, Restraint};
use crate::idealisation::Idealisation;
use crate::math::{Point, Pose, Vector};

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

/// Car following over a world's agents: where road users were at the previous
/// step, and the driving parameters.
#[derive(Debug, Clone)]
pub(super) struct CarFollowing<'a> {
    agents: &'a [Agent],
    step: f64,
    driving: Driving,
    previous: Vec<Option<AgentState>>,
    /// The road users of the previous step by area.
    nearby: Nearby,
}

impl<'a> CarFollowing<'a> {
    /// No road user seen yet.
    pub(super) fn new(agents: &'a [Agent], step: f64, driving: Driving) -> Self {
        Self {
            agents,
            step,
            driving,
            previous: vec![None; agents.len()],
            nearby: Nearby::default(),
        }
    }

    /// Whether agent `i` follows a leader: car following is on and `i` is a vehicle.
    pub(super) fn applies(&self, i: usize) -> bool {
        self.driving.following != Following::None && self.agents[i].kind.is_vehicle()
    }

    /// Remembers the states of the step just computed, for the next one.
    pub(super) fn remember(&mut self, states: &[Option<AgentState>]) {
        self.previous.clone_from_slice(states);
        self.nearby.index(&self.previous);
    }

    /// The speed of following vehicle `i` one step after driving at `speed`
    /// (IDM), wanting `wanted` with its `acceleration`, under `restraint`.
    pub(super) fn next_speed(
        &self,
        i: usize,
        speed: f64,
        wanted: f64,
        acceleration: f64,
        restraint: Option<Restraint>,
    ) -> f64 {
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
        let accel = (acceleration * (free - interaction)).clamp(-MAX_BRAKING, acceleration);
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
    /// at this one (`entered`, placed as in `current`). Without car following, or
    /// for a pedestrian, always.
    pub(super) fn entry_clear(
        &self,
        i: usize,
        path: &Polyline,
        offset: f64,
        speed: f64,
        entered: &[usize],
        current: &[Option<AgentState>],
    ) -> bool {
        if !self.applies(i) {
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
        let entered = entered.iter().filter_map(|&j| Some((j, current[j]?)));
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
    // Inlined: the pair test runs for every pair of road users every step, and
    // left out of line it costs the urban junction some 6 % more instructions.
    #[inline]
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
/// lane looks at the 3 × 3 cells around a position, not at every agent. The
/// cells are hashed by foldhash with a fixed seed: the standard library's
/// SipHash was a tenth of the urban junction's time (issue 20), and nothing
/// depends on the map's order.
#[derive(Debug, Clone, Default)]
struct Nearby {
    cells: HashMap<(i64, i64), Vec<usize>, FixedState>,
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
