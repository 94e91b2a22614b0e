//! The scene a recording shows in Foxglove's 3D panel: the map (`/scene/map`),
//! the frame tree (`/tf`: `map` → each agent → its sensors), the agents with
//! their ids (`/scene/agents`), their sensors' fields of view
//! (`/scene/fields_of_view`) and what each cooperating agent detected (`/perception/<id>/detections`), with the shapes and colours they
//! are drawn in.

use std::collections::BTreeSet;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use sightline_dsl::{Agent, AgentKind, Area, Grid as CellGrid, World};
use sightline_engine::trace::{AgentState, Body, CooperatorStep, Vector};

use super::Recorder;
use super::agents::{AgentJson, sensor_frame, write_scene_agents, write_speeds, write_transforms};
use super::channel::{SCENE, SPEEDS, TRANSFORMS};
use crate::mcap::foxglove::{Color, Cube, Entity, Line, LineType, Pose3, SceneUpdate, Text, Time, Vector3};
use crate::mcap::topic;

/// Segments of a full circle (a 360° sensor's range, a region).
const CIRCLE_SEGMENTS: usize = 72;

/// The largest angle between two points of a field-of-view arc, radians.
const ARC_STEP: f64 = 5.0 * PI / 180.0;

const EGO: Color = Color::rgba(0.1, 0.75, 0.3, 0.9);
const CONNECTED: Color = Color::rgba(0.2, 0.45, 0.95, 0.9);
const VEHICLE: Color = Color::rgba(0.55, 0.55, 0.6, 0.9);
const PEDESTRIAN: Color = Color::rgba(0.95, 0.55, 0.1, 0.9);
const RSU: Color = Color::rgba(0.6, 0.3, 0.85, 0.9);
const FOV: Color = Color::rgba(0.3, 0.8, 1.0, 0.35);
const ROAD: Color = Color::rgba(0.7, 0.7, 0.7, 0.8);
const OCCLUDER: Color = Color::rgba(0.85, 0.3, 0.25, 1.0);
const AREA: Color = Color::rgba(1.0, 0.85, 0.2, 0.7);
const OUTLINE: Color = Color::rgba(0.4, 0.4, 0.4, 0.6);
const DETECTION: Color = Color::rgba(1.0, 0.2, 0.6, 0.7);
const ESTIMATE: Color = Color::rgba(0.1, 0.9, 0.9, 0.9);
const LABEL: Color = Color::rgba(1.0, 1.0, 1.0, 1.0);

impl<W> Recorder<'_, W> {
    /// A step's scene: `/tf` (every agent in the scene as a frame, its sensors
    /// as frames under it), and when they change, the fields of view
    /// (`/scene/fields_of_view`) and the agents' boxes (`/scene/agents`), each
    /// locked to its frame; then every agent's speed (`/sightline/speeds`).
    pub(super) fn publish_agents(&mut self, time: u64, step: usize, states: &[Option<AgentState>]) {
        let states: Arc<[Option<AgentState>]> = states.into();
        self.publish_transforms(time, &states);
        let present: Vec<usize> = (0..states.len()).filter(|&i| states[i].is_some()).collect();
        self.publish_fields_of_view(time, &present);
        self.publish_scene_agents(time, present);
        let (point, pieces, held) = (self.record.point, Arc::clone(&self.agent_json), size_of_val(&*states));
        let speeds = Arc::clone(&states);
        self.out.deferred(topic::SPEEDS, SPEEDS, time, held, move |out| {
            write_speeds(out, point, step, &speeds, &pieces);
            Ok(())
        });
        self.last_states = states;
    }

    /// `/tf` of the agents at `states`, encoded by the writer thread.
    fn publish_transforms(&mut self, time: u64, states: &Arc<[Option<AgentState>]>) {
        let (states, pieces, held) = (Arc::clone(states), Arc::clone(&self.agent_json), size_of_val(&**states));
        self.out
            .deferred(topic::TRANSFORMS, TRANSFORMS, time, held, move |out| {
                write_transforms(out, Time::from_nanos(time), &states, &pieces);
                Ok(())
            });
    }

    /// What [`publish_agents`](Self::publish_agents) writes of each agent at
    /// every step and no step changes: rendered once the point's agents are
    /// known.
    pub(super) fn render_agents(&mut self) {
        self.agent_json = self
            .agents
            .iter()
            .zip(&self.fields_of_view)
            .enumerate()
            .map(|(i, (agent, sensors))| {
                let entity = agent_entity(Time::from_nanos(0), agent, self.color(i, agent));
                AgentJson::new(agent, sensors.iter().map(|(mount, _, _)| *mount), &entity)
            })
            .collect();
    }

    /// `/scene/agents`: every agent in the scene as its
    /// [`agent_entity`], locked to the agent's frame (the viewer moves it with
    /// the agent's `/tf`); written only when the agents in the scene change,
    /// each message the whole set, as the fields of view are.
    fn publish_scene_agents(&mut self, time: u64, present: Vec<usize>) {
        if present == self.agents_shown {
            return;
        }
        let pieces = &self.agent_json;
        self.out.written(topic::AGENTS, SCENE, time, |out| {
            write_scene_agents(out, Time::from_nanos(time), &present, pieces);
        });
        self.agents_shown = present;
    }

    /// `/scene/fields_of_view`: each sensor's field of view of every agent in
    /// the scene, locked to the sensor's frame (so the viewer moves it with the
    /// agent's `/tf`); written only when the agents with sensors in the scene
    /// change, each message the whole set (a viewer that seeks reads the
    /// latest message of each topic, so none may depend on an earlier one).
    fn publish_fields_of_view(&mut self, time: u64, in_scene: &[usize]) {
        let present: Vec<usize> = in_scene
            .iter()
            .copied()
            .filter(|&i| !self.fields_of_view[i].is_empty())
            .collect();
        if present == self.fields_shown {
            return;
        }
        let stamp = Time::from_nanos(time);
        let entities = present
            .iter()
            .flat_map(|&i| {
                let agent = &self.agents[i];
                self.fields_of_view[i]
                    .iter()
                    .enumerate()
                    .map(move |(k, (_, kind, outline))| {
                        let frame = sensor_frame(&agent.id, k);
                        Entity::locked(stamp, frame.clone(), frame).line(Line::new(
                            *kind,
                            Pose3::at(0.0, 0.0, 0.05, 0.0),
                            outline.iter().copied(),
                            0.1,
                            FOV,
                        ))
                    })
            })
            .collect();
        self.publish(
            topic::FIELDS_OF_VIEW,
            SCENE,
            time,
            &SceneUpdate::replace(stamp, entities),
        );
        self.fields_shown = present;
    }

    fn color(&self, index: usize, agent: &Agent) -> Color {
        match agent.kind {
            _ if Some(index) == self.ego => EGO,
            AgentKind::Rsu => RSU,
            AgentKind::Pedestrian => PEDESTRIAN,
            _ if agent.connected || self.cooperating.contains(&index) => CONNECTED,
            _ => VEHICLE,
        }
    }

    /// `/perception/<id>/detections`: where each cooperating agent placed what it
    /// detected (with the share of it in line of sight), and where it believes
    /// it is; emptied when it leaves the scene.
    pub(super) fn publish_detections(&mut self, time: u64, cooperators: &[CooperatorStep<'_>]) {
        let stamp = Time::from_nanos(time);
        let now: BTreeSet<usize> = cooperators.iter().map(|c| c.agent).collect();
        for c in cooperators {
            let Some(agent) = self.agents.get(c.agent) else {
                continue;
            };
            let mut entities = vec![Entity::new(stamp, "estimate").line(Line::new(
                LineType::Loop,
                Pose3::identity(),
                Body::of(c.agent, agent, c.estimate).corners(),
                0.15,
                ESTIMATE,
            ))];
            for sighting in c.observation.sighted() {
                let Some(body) = sighting.detected else { continue };
                let name = self.agent_id(sighting.target);
                let height = self.agents.get(sighting.target).map_or(1.5, |a| a.kind.height());
                entities.push(
                    Entity::new(stamp, format!("{name}#{}", sighting.sensor))
                        .meta("target", &name)
                        .meta("sensor", sighting.sensor)
                        .meta("visible_fraction", sighting.visible_fraction)
                        .cube(Cube {
                            pose: Pose3::planar(body.pose, height / 2.0),
                            size: Vector3 {
                                x: body.half_extents.x * 2.0,
                                y: body.half_extents.y * 2.0,
                                z: height,
                            },
                            color: DETECTION,
                        }),
                );
            }
            let topic = topic::detections(&agent.id);
            let held = size_of_val(entities.as_slice());
            self.publish_deferred(&topic, SCENE, time, held, SceneUpdate::replace(stamp, entities));
        }
        for gone in self.shown.difference(&now).copied().collect::<Vec<_>>() {
            let topic = topic::detections(&self.agent_id(gone));
            self.publish(&topic, SCENE, time, &SceneUpdate::replace(stamp, Vec::new()));
        }
        self.shown = now;
    }

    /// Clears the agents (`/scene/agents`), their fields of view, every
    /// cooperating agent's detections and the grids (`/fusion/grid`,
    /// `/perception/<id>/grid`) at `time`: the end of a point when
    /// another follows. `/tf` holds the last step's frames until then, so
    /// that what is locked to them stays where it was rather than gliding
    /// towards the next point's first step.
    pub(super) fn clear_scene(&mut self, time: u64) {
        let stamp = Time::from_nanos(time);
        if self.last_states.iter().any(Option::is_some) {
            self.publish_transforms(time, &self.last_states.clone());
        }
        let agents = !std::mem::take(&mut self.agents_shown).is_empty();
        let fields = !std::mem::take(&mut self.fields_shown).is_empty();
        for (topic, shown) in [(topic::AGENTS, agents), (topic::FIELDS_OF_VIEW, fields)] {
            if shown {
                self.publish(topic, SCENE, time, &SceneUpdate::replace(stamp, Vec::new()));
            }
        }
        for gone in std::mem::take(&mut self.shown) {
            let topic = topic::detections(&self.agent_id(gone));
            self.publish(&topic, SCENE, time, &SceneUpdate::replace(stamp, Vec::new()));
        }
        self.clear_grids(time);
    }
}

/// An agent's `/scene/agents` entity at `stamp`: a box of its footprint in
/// `color` with its id as a label and its kind as metadata, in the agent's
/// frame, locked to it.
pub(super) fn agent_entity(stamp: Time, agent: &Agent, color: Color) -> Entity {
    let height = agent.kind.height();
    Entity::locked(stamp, agent.id.clone(), agent.id.clone())
        .meta("kind", agent.kind.name())
        .cube(Cube {
            pose: Pose3::at(0.0, 0.0, height / 2.0, 0.0),
            size: Vector3 {
                x: agent.length,
                y: agent.width,
                z: height,
            },
            color,
        })
        .text(Text::label(
            Pose3::at(0.0, 0.0, height + 1.0, 0.0),
            agent.id.clone(),
            LABEL,
        ))
}

/// A sensor's field of view in its own frame: a circle of its range when it
/// sees all around, else the sector from the sensor out to its range.
pub(super) fn field_of_view(range: f64, fov: f64) -> (LineType, Vec<Vector>) {
    let at = |angle: f64| Vector::new(angle.cos(), angle.sin()) * range;
    if fov >= TAU - 1e-9 {
        let points = (0..CIRCLE_SEGMENTS)
            .map(|i| at(i as f64 * TAU / CIRCLE_SEGMENTS as f64))
            .collect();
        return (LineType::Loop, points);
    }
    let segments = (fov / ARC_STEP).ceil().max(1.0) as usize;
    let points = std::iter::once(Vector::ZERO)
        .chain((0..=segments).map(|i| at(-fov / 2.0 + fov * i as f64 / segments as f64)))
        .collect();
    (LineType::Loop, points)
}

/// `/scene/map`: the grid's outline (where there is a grid), roads, occluders,
/// interaction areas, crosswalks and the perception region, stamped `start`.
pub(super) fn map_entities(world: &World, grid: Option<&CellGrid>, start: u64) -> Vec<Entity> {
    let stamp = Time::from_nanos(start);
    let flat = |points: &[[f64; 2]]| points.iter().map(|&[x, y]| Vector::new(x, y)).collect::<Vec<_>>();
    let loop_line =
        |points: Vec<Vector>, thickness, color| Line::new(LineType::Loop, Pose3::identity(), points, thickness, color);
    let circle = |[x, y]: [f64; 2], radius: f64| {
        (0..CIRCLE_SEGMENTS)
            .map(|i| {
                let angle = i as f64 * TAU / CIRCLE_SEGMENTS as f64;
                Vector::new(x + radius * angle.cos(), y + radius * angle.sin())
            })
            .collect::<Vec<_>>()
    };
    let mut entities: Vec<Entity> = grid
        .map(|grid| {
            let [x0, y0] = grid.origin;
            let (x1, y1) = (x0 + grid.cols as f64 * grid.cell, y0 + grid.rows as f64 * grid.cell);
            Entity::new(stamp, "grid").line(loop_line(flat(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]), 0.2, OUTLINE))
        })
        .into_iter()
        .collect();
    for road in &world.roads {
        let mut entity = Entity::new(stamp, format!("road/{}", road.id)).meta("speed_limit_mps", road.speed_limit);
        for lane in &road.lanes {
            entity = entity.line(Line::new(
                LineType::Strip,
                Pose3::identity(),
                flat(lane.points()),
                0.15,
                ROAD,
            ));
        }
        entities.push(entity);
    }
    for occluder in &world.occluders {
        entities.push(Entity::new(stamp, format!("occluder/{}", occluder.id)).line(loop_line(
            flat(&occluder.polygon),
            0.3,
            OCCLUDER,
        )));
    }
    for area in &world.interaction_areas {
        let outline = match &area.shape {
            Area::Polygon(points) => flat(points),
            Area::Circle { center, radius } => circle(*center, *radius),
        };
        entities.push(Entity::new(stamp, format!("area/{}", area.id)).line(loop_line(outline, 0.2, AREA)));
    }
    for crosswalk in &world.crosswalks {
        let (from, to) = (Vector::from(crosswalk.from), Vector::from(crosswalk.to));
        let across = (to - from).normalize_or_zero();
        let half = Vector::new(-across.y, across.x) * (crosswalk.width / 2.0);
        let corners = vec![from + half, to + half, to - half, from - half];
        entities.push(Entity::new(stamp, format!("crosswalk/{}", crosswalk.id)).line(loop_line(corners, 0.15, AREA)));
    }
    if let Some((center, radius)) = world.perception.as_ref().and_then(|p| p.region) {
        entities.push(Entity::new(stamp, "region").line(loop_line(circle(center, radius), 0.2, AREA)));
    }
    entities
}
