//! `/tf` and `/scene/agents` at every step, written straight into JSON: what
//! does not change from step to step (an agent's id, kind, size, colour and
//! label, its sensors' mounts) is rendered once per recorded point, and each
//! step writes only its times, poses and speeds, each pose's numbers formatted
//! once for the three places they appear (the agent's transform, its box and
//! its label) and each time once per message. The bytes are the ones
//! serde_json gives [`FrameTransforms`](crate::mcap::foxglove::FrameTransforms)
//! and [`SceneUpdate`] of the same entities (a test compares them): encoding
//! those field by field, every key escaped and every constant number formatted
//! again, was most of what recording a step cost.

use sightline_dsl::Agent;
use sightline_engine::trace::{AgentState, Pose};

use crate::mcap::foxglove::{Color, FRAME, Pose3, Text, Time, Vector3};

/// The colour of an agent's label.
const LABEL: Color = Color::rgba(1.0, 1.0, 1.0, 1.0);

/// The frame of sensor `index` of agent `agent` (`<agent>/sensor<index>`).
pub(super) fn sensor_frame(agent: &str, index: usize) -> String {
    format!("{agent}/sensor{index}")
}

/// What an agent's messages hold that no step changes, as JSON.
pub(super) struct AgentJson {
    /// Its `/tf` transform after the timestamp, up to the translation's x.
    frame: Vec<u8>,
    /// Each sensor's `/tf` transform after the timestamp, to its end.
    sensors: Vec<Vec<u8>>,
    /// Its entity after the timestamp, up to the speed's digits.
    head: Vec<u8>,
    /// Its box's z, up to the box's orientation.
    cube_z: Vec<u8>,
    /// After the box's orientation, up to the label's x.
    cube: Vec<u8>,
    /// Its label's z, up to the label's orientation.
    label_z: Vec<u8>,
    /// After the label's orientation, to the entity's end.
    label: Vec<u8>,
}

/// A transform in `map` after its x and y, up to its rotation (agents move in
/// the plane z = 0).
const TRANSFORM_Z: &[u8] = br#","z":0.0},"rotation":"#;

/// An entity after its speed's digits, up to its box's x.
const SPEED_TO_CUBE: &[u8] = br#""}],"arrows":[],"cubes":[{"pose":{"position":{"#;

impl AgentJson {
    /// The pieces of `agent`, drawn in `color`, whose sensors sit at `mounts`.
    pub(super) fn new(agent: &Agent, color: Color, mounts: impl IntoIterator<Item = Pose>) -> Self {
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
        let height = agent.kind.height();
        let size = json(&Vector3 {
            x: agent.length,
            y: agent.width,
            z: height,
        });
        let z_up_to_orientation = |z: f64| {
            let mut out = vec![b','];
            Pose3::at(0.0, 0.0, z, 0.0).write_z(&mut out);
            out.extend_from_slice(br#"},"orientation":"#);
            out
        };
        let label = json(&Text::label(Pose3::identity(), agent.id.clone(), LABEL));
        // The label's fields after its pose: `{"pose":{…},` cut off.
        let label_tail = &label[label.find(r#","billboard""#).expect("a label has billboard")..];
        Self {
            frame: format!(r#","parent_frame_id":"{FRAME}","child_frame_id":{id},"translation":{{"#).into_bytes(),
            sensors,
            head: format!(
                r#","frame_id":"{FRAME}","id":{id},"lifetime":{{"sec":0,"nsec":0}},"frame_locked":false,"metadata":[{{"key":"kind","value":{}}},{{"key":"speed_mps","value":""#,
                json(agent.kind.name())
            )
            .into_bytes(),
            cube_z: z_up_to_orientation(height / 2.0),
            cube: format!(
                r#"}},"size":{size},"color":{}}}],"spheres":[],"cylinders":[],"lines":[],"triangles":[],"texts":[{{"pose":{{"position":{{"#,
                json(&color)
            )
            .into_bytes(),
            label_z: z_up_to_orientation(height + 1.0),
            label: format!(r#"}}{label_tail}],"models":[]}}"#).into_bytes(),
        }
    }
}

/// Serde_json's encoding of `value`, which cannot fail for these types.
fn json(value: &(impl serde::Serialize + ?Sized)) -> String {
    serde_json::to_string(value).expect("a string, a vector, a colour or a label encodes")
}

/// Every agent's pose at one step as the JSON its transform, its box and its
/// label repeat: the position's `"x":…,"y":…` and the orientation, each
/// number formatted once.
#[derive(Default)]
pub(super) struct StepPoses {
    json: Vec<u8>,
    /// Per agent, where its x and y start, where its orientation starts and
    /// where it ends in `json`; `None` when it is not in the scene.
    spans: Vec<Option<[usize; 3]>>,
}

impl StepPoses {
    /// Holds the poses of `states` (by agent), replacing the previous step's.
    pub(super) fn write(&mut self, states: &[Option<AgentState>]) {
        self.json.clear();
        self.spans.clear();
        for state in states {
            let span = state.as_ref().map(|state| {
                let pose = Pose3::planar(state.pose, 0.0);
                let start = self.json.len();
                pose.write_xy(&mut self.json);
                let xy = self.json.len();
                pose.write_rotation(&mut self.json);
                [start, xy, self.json.len()]
            });
            self.spans.push(span);
        }
    }

    /// Per agent, its x and y and its orientation if it is in the scene.
    fn iter(&self) -> impl Iterator<Item = Option<(&[u8], &[u8])>> {
        self.spans
            .iter()
            .map(|span| span.map(|[start, xy, end]| (&self.json[start..xy], &self.json[xy..end])))
    }
}

/// Writes step `stamp`'s `foxglove.FrameTransforms` into `out` (cleared
/// first): every agent in the scene (at `poses`) in `map`, and each of its
/// sensors in it.
pub(super) fn write_transforms(out: &mut Vec<u8>, stamp: Time, poses: &StepPoses, pieces: &[AgentJson]) {
    let mut timestamp = br#"{"timestamp":"#.to_vec();
    stamp.write_json(&mut timestamp);
    out.clear();
    out.extend_from_slice(br#"{"transforms":["#);
    let mut first = true;
    for (piece, (xy, rotation)) in pieces.iter().zip(poses.iter()).filter_map(|(p, pose)| Some((p, pose?))) {
        for sensor in std::iter::once(None).chain(piece.sensors.iter().map(Some)) {
            if !std::mem::take(&mut first) {
                out.push(b',');
            }
            out.extend_from_slice(&timestamp);
            match sensor {
                Some(sensor) => out.extend_from_slice(sensor),
                None => {
                    out.extend_from_slice(&piece.frame);
                    out.extend_from_slice(xy);
                    out.extend_from_slice(TRANSFORM_Z);
                    out.extend_from_slice(rotation);
                    out.push(b'}');
                }
            }
        }
    }
    out.extend_from_slice(b"]}");
}

/// Writes step `stamp`'s `foxglove.SceneUpdate` of `/scene/agents` into `out`
/// (cleared first): a delete-all, then every agent in the scene (at `poses`,
/// moving at `states`' speeds) as a box with its id, kind and speed.
pub(super) fn write_agents(
    out: &mut Vec<u8>,
    stamp: Time,
    poses: &StepPoses,
    states: &[Option<AgentState>],
    pieces: &[AgentJson],
) {
    use std::io::Write as _;
    let mut timestamp = Vec::new();
    stamp.write_json(&mut timestamp);
    out.clear();
    out.extend_from_slice(br#"{"deletions":[{"timestamp":"#);
    out.extend_from_slice(&timestamp);
    out.extend_from_slice(br#","type":1,"id":""}],"entities":["#);
    let mut first = true;
    for ((state, piece), pose) in states.iter().zip(pieces).zip(poses.iter()) {
        let (Some(state), Some((xy, rotation))) = (state, pose) else {
            continue;
        };
        if !std::mem::take(&mut first) {
            out.push(b',');
        }
        out.extend_from_slice(br#"{"timestamp":"#);
        out.extend_from_slice(&timestamp);
        out.extend_from_slice(&piece.head);
        let _ = write!(out, "{:.2}", state.speed);
        out.extend_from_slice(SPEED_TO_CUBE);
        for (z, after) in [(&piece.cube_z, &piece.cube), (&piece.label_z, &piece.label)] {
            out.extend_from_slice(xy);
            out.extend_from_slice(z);
            out.extend_from_slice(rotation);
            out.extend_from_slice(after);
        }
    }
    out.extend_from_slice(b"]}");
}

#[cfg(test)]
mod tests {
    use sightline_dsl::{Experiment, Options, compile};
    use sightline_engine::trace::{Vector, mount_pose};

    use super::*;
    use crate::mcap::foxglove::{Cube, Entity, FrameTransform, FrameTransforms, SceneUpdate, Vector3};

    /// The entity [`write_agents`] writes for `agent` at `state`, built from
    /// the message types.
    fn entity(stamp: Time, agent: &Agent, state: &AgentState, color: Color) -> Entity {
        let height = agent.kind.height();
        Entity::new(stamp, agent.id.clone())
            .meta("kind", agent.kind.name())
            .meta("speed_mps", format!("{:.2}", state.speed))
            .cube(Cube {
                pose: Pose3::planar(state.pose, height / 2.0),
                size: Vector3 {
                    x: agent.length,
                    y: agent.width,
                    z: height,
                },
                color,
            })
            .text(Text::label(
                Pose3::planar(state.pose, height + 1.0),
                agent.id.clone(),
                LABEL,
            ))
    }

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

    /// Both messages, written directly, are byte for byte what serde_json gives
    /// the message types, for every agent of two bundled scenarios at poses in
    /// every quadrant (some out of the scene), odd speeds and times.
    #[test]
    fn written_json_is_serde_jsons() {
        let colors = [Color::rgba(0.1, 0.75, 0.3, 0.9), Color::rgba(0.6, 0.3, 0.85, 0.9)];
        for file in ["roundabout-six-agents.yaml", "urban-rsu-semantic.yaml"] {
            let agents = agents(file);
            assert!(agents.iter().any(|a| !a.sensors.is_empty()), "{file}");
            let color = |i: usize| colors[i % 2];
            let pieces: Vec<AgentJson> = agents
                .iter()
                .enumerate()
                .map(|(i, a)| AgentJson::new(a, color(i), a.sensors.iter().map(mount_pose)))
                .collect();
            let mut poses = StepPoses::default();
            for step in 0..7_u32 {
                let stamp = Time::from_nanos(946_684_800_000_000_000 + u64::from(step) * 123_456_789);
                let states: Vec<Option<AgentState>> = (0..agents.len())
                    .map(|i| {
                        let k = f64::from(step) + i as f64;
                        (!(i + step as usize).is_multiple_of(5)).then(|| AgentState {
                            pose: Pose::new(Vector::new(-50.0 + 17.3 * k, 40.0 - 9.87654321 * k), 0.7 * k - 3.0),
                            speed: 1.005 * k,
                            offset: 0.0,
                            limit: f64::INFINITY,
                        })
                    })
                    .collect();
                poses.write(&states);
                let mut out = Vec::new();
                write_agents(&mut out, stamp, &poses, &states, &pieces);
                let entities = states
                    .iter()
                    .enumerate()
                    .filter_map(|(i, s)| Some(entity(stamp, &agents[i], s.as_ref()?, color(i))))
                    .collect();
                let expected = serde_json::to_string(&SceneUpdate::replace(stamp, entities)).unwrap();
                assert_eq!(String::from_utf8(out.clone()).unwrap(), expected, "{file}, step {step}");
                write_transforms(&mut out, stamp, &poses, &pieces);
                let transforms = states
                    .iter()
                    .zip(&agents)
                    .filter_map(|(s, a)| Some((s.as_ref()?, a)))
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
                assert_eq!(String::from_utf8(out).unwrap(), expected, "{file}, step {step}");
            }
        }
    }
}
