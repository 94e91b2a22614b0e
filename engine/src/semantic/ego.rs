//! The ego of a semantic world: what it knows of each road user (its own sight,
//! the RSUs' messages, connected road users' own messages) and the caution a
//! flagged conflict puts it in.

use sightline_dsl::{Agent, Semantic};

use crate::idealisation::Idealisation;
use crate::math::Pose;
use crate::trace::Arrival;
use crate::world::{Bodies, Body, Occluders, Restraint, Visibility, in_view, mount_pose, visibility};

/// The ego's own sight is perfect.
pub(crate) const EGO_SIGHT: Idealisation = Idealisation {
    id: "semantic.ego-sight",
    text: "The ego sees an object at once and exactly when its centre is in range, in field of view and in line \
           of sight of one of its sensors: its own sensors miss nothing and add no error.",
};

/// What a message makes known.
pub(crate) const KNOWN_FOR_A_WHILE: Idealisation = Idealisation {
    id: "semantic.known-for",
    text: "An object named in a message counts as known to the ego for 0.5 s after the message arrives.",
};

/// How long a message keeps an object known to the ego, seconds.
pub const KNOWN_FOR: f64 = 0.5;

/// What the ego knows of one road user, over a run.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Knowledge {
    /// When a message naming it last arrived.
    last_received: Option<f64>,
    /// When a message naming it first arrived, and whether the ego had seen it before.
    pub(super) first_received: Option<(f64, bool)>,
    /// When the ego first saw it.
    pub(super) first_seen: Option<f64>,
    /// When its own V2X message last arrived.
    last_direct: Option<f64>,
    /// When its own V2X message first arrived.
    pub(super) first_direct: Option<f64>,
    /// When a message flagging a conflict with it first reached the ego.
    pub(super) flagged: Option<f64>,
    /// When the ETSI baseline's message naming it would first have reached
    /// the ego, and whether the ego had seen it before.
    pub(super) baseline_received: Option<(f64, bool)>,
    /// Whether it is within d_min of the ego now.
    close: bool,
}

/// The ego's state across steps.
#[derive(Debug, Clone)]
pub(super) struct Ego {
    /// Its agent index.
    agent: usize,
    /// Per agent, by agent index.
    knowledge: Vec<Knowledge>,
    /// Until when it drives cautiously, seconds.
    cautious_until: f64,
}

/// What the ego perceives of the scene at one step, with its own sensors and
/// through what V2X has told it.
#[derive(Debug, Clone, Default)]
pub(super) struct EgoView {
    /// Road users in the scene besides the ego.
    pub(super) present: u32,
    /// Of those, the ones it knows only through an RSU: not in sight, named by a
    /// fresh RSU message, and no fresh message of their own.
    pub(super) through_rsu: u32,
    /// The road users that came within d_min of it at this step, in scene
    /// order, each with when a conflict with it was first flagged to the ego.
    pub(super) approaches: Vec<(usize, Option<f64>)>,
}

impl Ego {
    /// Agent `agent` knowing nothing of the `agents` agents of the scene.
    pub(super) fn new(agent: usize, agents: usize) -> Self {
        Self {
            agent,
            knowledge: vec![Knowledge::default(); agents],
            cautious_until: f64::NEG_INFINITY,
        }
    }

    /// Takes in the semantic messages that arrived, in order of arrival: the
    /// objects they name become known, and a flagged conflict makes the ego
    /// cautious for `hold` seconds.
    pub(super) fn receive(&mut self, arrivals: &[Arrival], hold: f64) {
        for Arrival { at, items } in arrivals {
            for item in items {
                let known = &mut self.knowledge[item.agent];
                known.last_received = Some(*at);
                if known.first_received.is_none() {
                    known.first_received = Some((*at, known.first_seen.is_some()));
                }
                if item.labels.conflict.is_some() {
                    known.flagged.get_or_insert(*at);
                    self.cautious_until = self.cautious_until.max(at + hold);
                }
            }
        }
    }

    /// Takes in the ETSI baseline's messages that arrived (when, and the agents
    /// each names), in order of arrival: what the ego would have known of
    /// them instead of the semantic messages. They change nothing else.
    pub(super) fn receive_baseline(&mut self, arrivals: &[(f64, Vec<usize>)]) {
        for (at, agents) in arrivals {
            for &agent in agents {
                let known = &mut self.knowledge[agent];
                if known.baseline_received.is_none() {
                    known.baseline_received = Some((*at, known.first_seen.is_some()));
                }
            }
        }
    }

    /// Takes in road user `agent`'s own message, arrived at `at`.
    pub(super) fn hear(&mut self, agent: usize, at: f64) {
        let known = &mut self.knowledge[agent];
        known.last_direct = Some(at);
        known.first_direct.get_or_insert(at);
    }

    /// Whether the ego drives cautiously at `time`.
    pub(super) fn cautious(&self, time: f64) -> bool {
        time < self.cautious_until
    }

    /// How the ego's caution at `time` restrains its driving.
    pub(super) fn restraint(&self, time: f64, semantic: &Semantic) -> Option<Restraint> {
        self.cautious(time).then_some(Restraint {
            headway: semantic.caution.headway,
            speed_factor: semantic.caution.speed_factor,
        })
    }

    /// Sense: what the ego (`spec`, at `pose`) perceives of every other road user
    /// in `bodies` at `time`, with its own sensors past `occluders` and through
    /// what it was told; notes when it first saw each and which are within
    /// `d_min` of it.
    pub(super) fn sense(
        &mut self,
        time: f64,
        spec: &Agent,
        pose: Pose,
        occluders: &Occluders,
        bodies: &Bodies,
        d_min: f64,
    ) -> EgoView {
        let mut view = EgoView::default();
        // A road user out of the scene is not close: back within d_min, it
        // makes a new close approach.
        let mut present = vec![false; self.knowledge.len()];
        for body in bodies.all() {
            present[body.agent] = true;
        }
        for (known, _) in self.knowledge.iter_mut().zip(&present).filter(|&(_, &p)| !p) {
            known.close = false;
        }
        for body in bodies.all().iter().filter(|b| b.agent != self.agent) {
            view.present += 1;
            let known = &mut self.knowledge[body.agent];
            let seen = sees(spec, pose, occluders, bodies, self.agent, body);
            if seen && known.first_seen.is_none() {
                known.first_seen = Some(time);
            }
            let fresh = |at: Option<f64>| at.is_some_and(|at| time - at <= KNOWN_FOR + 1e-9);
            if !seen && fresh(known.last_received) && !fresh(known.last_direct) {
                view.through_rsu += 1;
            }
            let close = (body.pose.translation - pose.translation).length() <= d_min;
            if close && !known.close {
                view.approaches.push((body.agent, known.flagged));
            }
            known.close = close;
        }
        view
    }

    /// What it knows of each agent, by agent index.
    pub(super) fn knowledge(&self) -> &[Knowledge] {
        &self.knowledge
    }
}

/// Whether the ego at `pose` could see `target` with one of its sensors.
fn sees(ego: &Agent, pose: Pose, occluders: &Occluders, bodies: &Bodies, ego_index: usize, target: &Body) -> bool {
    ego.sensors.iter().any(|sensor| {
        let mount = pose * mount_pose(sensor);
        in_view(sensor, mount, target.pose.translation).is_some()
            && visibility(occluders, bodies, mount.translation, ego_index, target) == Visibility::Los
    })
}
