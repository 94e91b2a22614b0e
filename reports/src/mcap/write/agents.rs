//! `/tf` and `/sightline/speeds` at every step, and `/scene/agents` when the
//! agents in the scene change, written straight into JSON: what does not
//! change from step to step (an agent's id, its sensors' mounts, its box and
//! label) is rendered once per recorded point, and each step writes only its
//! times, poses and speeds. The bytes are the ones serde_json gives
//! `FrameTransforms` (the test's message type), `SceneUpdate` and
//! [`SpeedsRecord`](crate::mcap::wire::SpeedsRecord) of the same agents (a test
//! compares them): encoding those field by field, every key escaped and every
//! constant number formatted again, was most of what recording a step cost.

use std::io::Write as _;

use sightline_dsl::Agent;
use sightline_engine::trace::{AgentState, Pose};

use crate::mcap::foxglove::{Entity, FRAME, Pose3, Time};

/// The frame of sensor `index` of agent `agent` (`<agent>/sensor<index>`).
pub(super) fn sensor_frame(agent: &str, index: usize) -> String {
    format!("{agent}/sensor{index}")
}

/// An agent's speed as `/sightline/speeds` holds it: m/s, rounded to the
/// centimetre per second.
pub(super) fn speed_mps(state: &AgentState) -> f64 {
    (state.speed * 100.0).round() / 100.0
}

/// What an agent's per-step messages hold that no step changes, as JSON.
pub(super) struct AgentJson {
    /// Its `/tf` transform after the timestamp, up to the translation.
    frame: Vec<u8>,
    /// Each sensor's `/tf` transform after the timestamp, to its end.
    sensors: Vec<Vec<u8>>,
    /// Its `/sightline/speeds` entry, up to the speed.
    speed: Vec<u8>,
    /// Its `/scene/agents` entity after the timestamp, to its end.
    entity: Vec<u8>,
}

impl AgentJson {
    /// The pieces of `agent`, whose sensors sit at `mounts` and whose
    /// `/scene/agents` entity is `entity` (at time 0).
    pub(super) fn new(agent: &Agent, mounts: impl IntoIterator<Item = Pose>, entity: &Entity) -> Self {
        let id = json(&agent.id);
        let sensors = mounts
            .into_iter()
            .enumerate()
            .map(|(k, mount)| {
                let pose = Pose3::planar(mount, 0.0);
                let mut out = format!(
                    r#","parent_frame_id":{id},"child_frame_id":{},"translation":"#,
                    json(&sensor_frame(&agent.id, k))
                )
                .into_bytes();
                pose.write_translation(&mut out);
                out.extend_from_slice(br#","rotation":"#);
                pose.write_rotation(&mut out);
                out.push(b'}');
                out
            })
            .collect();
        Self {
            frame: format!(r#","parent_frame_id":"{FRAME}","child_frame_id":{id},"translation":"#).into_bytes(),
            sensors,
            speed: format!(r#"{{"id":{id},"speed_mps":"#).into_bytes(),
            entity: json(entity)
                .strip_prefix(ENTITY_AT_0)
                .expect("an entity starts with its timestamp")
                .into(),
        }
    }
}

/// What an entity's JSON opens with at time 0, up to the end of its timestamp.
const ENTITY_AT_0: &str = r#"{"timestamp":{"sec":0,"nsec":0}"#;

/// Serde_json's encoding of `value`, which cannot fail for these types.
fn json(value: &(impl serde::Serialize + ?Sized)) -> String {
    serde_json::to_string(value).expect("a string encodes")
}

/// Each agent in the scene (its state in `states`, by agent) with its pieces.
fn in_scene<'a>(
    states: &'a [Option<AgentState>],
    pieces: &'a [AgentJson],
) -> impl Iterator<Item = (&'a AgentJson, &'a AgentState)> {
    pieces
        .iter()
        .zip(states)
        .filter_map(|(piece, state)| Some((piece, state.as_ref()?)))
}

/// Appends `foxglove.FrameTransforms` at `stamp` to `out`:
/// every agent in the scene (at `states`) in `map`, and each of its sensors in
/// it.
pub(super) fn write_transforms(out: &mut Vec<u8>, stamp: Time, states: &[Option<AgentState>], pieces: &[AgentJson]) {
    let mut timestamp = br#"{"timestamp":"#.to_vec();
    stamp.write_json(&mut timestamp);
    out.extend_from_slice(br#"{"transforms":["#);
    for (i, (piece, state)) in in_scene(states, pieces).enumerate() {
        if i > 0 {
            out.push(b',');
        }
        let pose = Pose3::planar(state.pose, 0.0);
        out.extend_from_slice(&timestamp);
        out.extend_from_slice(&piece.frame);
        pose.write_translation(out);
        out.extend_from_slice(br#","rotation":"#);
        pose.write_rotation(out);
        out.push(b'}');
        for sensor in &piece.sensors {
            out.push(b',');
            out.extend_from_slice(&timestamp);
            out.extend_from_slice(sensor);
        }
    }
    out.extend_from_slice(b"]}");
}

/// Appends `foxglove.SceneUpdate` at `stamp` to `out`: every
/// earlier entity deleted, and the entities of the agents `present` (indexes
/// into `pieces`).
pub(super) fn write_scene_agents(out: &mut Vec<u8>, stamp: Time, present: &[usize], pieces: &[AgentJson]) {
    let mut timestamp = br#"{"timestamp":"#.to_vec();
    stamp.write_json(&mut timestamp);
    out.extend_from_slice(br#"{"deletions":["#);
    out.extend_from_slice(&timestamp);
    out.extend_from_slice(br#","type":1,"id":""}],"entities":["#);
    for (i, &agent) in present.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(&timestamp);
        out.extend_from_slice(&pieces[agent].entity);
    }
    out.extend_from_slice(b"]}");
}

/// Appends step `step`'s `sightline.Speeds` of point `point` to `out`: every
/// agent in the scene (at `states`) with its speed.
pub(super) fn write_speeds(
    out: &mut Vec<u8>,
    point: usize,
    step: usize,
    states: &[Option<AgentState>],
    pieces: &[AgentJson],
) {
    // Writing into a Vec does not fail.
    let _ = write!(out, r#"{{"point":{point},"step":{step},"agents":["#);
    for (i, (piece, state)) in in_scene(states, pieces).enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(&piece.speed);
        let _ = serde_json::to_writer(&mut *out, &speed_mps(state));
        out.push(b'}');
    }
    out.extend_from_slice(b"]}");
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{Experiment, Options, compile};
    use sightline_engine::trace::{Vector, mount_pose};

    use super::super::scene::agent_entity;
    use super::*;
    use crate::mcap::foxglove::{Color, FrameTransform, FrameTransforms, SceneUpdate};
    use crate::mcap::wire::{AgentSpeed, SpeedsRecord};

    /// The agents of a bundled scenario's first point (cars, a bus, pedestrians,
    /// a roadside unit, sensors on several).
    fn agents(file: &str) -> Vec<Agent> {
        let text = std::fs::read_to_string(format!("{}/../scenarios/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let scenario = compile(file, &text, &Options::default()).unwrap_or_else(|e| panic!("{e}"));
        match &scenario.points[0].setup.experiment {
            Experiment::World(world) => world.agents.clone(),
            Experiment::Field(_) => panic!("{file} has a world"),
        }
    }

    /// The three messages, written directly, are byte for byte what
    /// serde_json gives the message types, for every agent of two bundled
    /// scenarios at poses in every quadrant (some out of the scene), odd
    /// speeds and times.
    #[test]
    fn written_json_is_serde_jsons() {
        for file in ["roundabout-six-agents.yaml", "urban-rsu-semantic.yaml"] {
            let agents = agents(file);
            assert!(agents.iter().any(|a| !a.sensors.is_empty()), "{file}");
            let colors = [Color::rgba(0.1, 0.2, 0.3, 0.4), Color::rgba(1.0, 0.5, 0.25, 1.0)];
            let pieces: Vec<AgentJson> = agents
                .iter()
                .enumerate()
                .map(|(i, a)| {
                    let entity = agent_entity(Time::from_nanos(0), a, colors[i % 2]);
                    AgentJson::new(a, a.sensors.iter().map(mount_pose), &entity)
                })
                .collect();
            for step in 0..7_u32 {
                let stamp = Time::from_nanos(946_684_800_000_000_000 + u64::from(step) * 123_456_789);
                let states: Vec<Option<AgentState>> = (0..agents.len())
                    .map(|i| {
                        let k = f64::from(step) + i as f64;
                        (!(i + step as usize).is_multiple_of(5)).then(|| AgentState {
                            pose: Pose::new(Vector::new(-50.0 + 17.3 * k, 40.0 - 9.87654321 * k), 0.7 * k - 3.0),
                            speed: 1.005 * k + 0.004_999,
                            offset: 0.0,
                            limit: f64::INFINITY,
                        })
                    })
                    .collect();
                let present = || states.iter().zip(&agents).filter_map(|(s, a)| Some((s.as_ref()?, a)));
                let mut out = Vec::new();
                write_transforms(&mut out, stamp, &states, &pieces);
                let transforms = present()
                    .flat_map(|(state, agent)| {
                        let own = FrameTransform::new(stamp, FRAME, agent.id.clone(), Pose3::planar(state.pose, 0.0));
                        let mounts = agent.sensors.iter().enumerate().map(move |(k, sensor)| {
                            let frame = super::sensor_frame(&agent.id, k);
                            FrameTransform::new(stamp, agent.id.clone(), frame, Pose3::planar(mount_pose(sensor), 0.0))
                        });
                        std::iter::once(own).chain(mounts)
                    })
                    .collect();
                let expected = serde_json::to_string(&FrameTransforms { transforms }).unwrap();
                assert_eq!(String::from_utf8(out.clone()).unwrap(), expected, "{file}, step {step}");
                let in_scene: Vec<usize> = (0..agents.len()).filter(|&i| states[i].is_some()).collect();
                out.clear();
                write_scene_agents(&mut out, stamp, &in_scene, &pieces);
                let entities = in_scene
                    .iter()
                    .map(|&i| agent_entity(stamp, &agents[i], colors[i % 2]))
                    .collect();
                let expected = serde_json::to_string(&SceneUpdate::replace(stamp, entities)).unwrap();
                assert_eq!(String::from_utf8(out.clone()).unwrap(), expected, "{file}, step {step}");
                out.clear();
                write_speeds(&mut out, 3, step as usize, &states, &pieces);
                let record = SpeedsRecord {
                    point: 3,
                    step: step as usize,
                    agents: present()
                        .map(|(state, agent)| AgentSpeed {
                            id: agent.id.clone(),
                            speed_mps: speed_mps(state),
                        })
                        .collect(),
                };
                let written: SpeedsRecord = serde_json::from_slice(&out).unwrap();
                assert_eq!(written, record, "{file}, step {step}");
                assert_eq!(String::from_utf8(out).unwrap(), serde_json::to_string(&record).unwrap());
            }
        }
    }

    /// Speeds are rounded to the centimetre per second, as written.
    #[test]
    fn speeds_are_rounded_to_the_centimetre_per_second() {
        let state = |speed| AgentState {
            pose: Pose::new(Vector::ZERO, 0.0),
            speed,
            offset: 0.0,
            limit: f64::INFINITY,
        };
        assert_eq!(speed_mps(&state(13.894_999)), 13.89);
        assert_eq!(speed_mps(&state(13.895_001)), 13.9);
        assert_eq!(speed_mps(&state(0.0)), 0.0);
    }
}
