//! One step of a world as OSI messages: the ground truth, and what each sensor
//! of a cooperating agent has in view.
//!
//! The conventions (docs/osi.md):
//! - a road user's OSI id is its agent index plus one (agents numbered as the
//!   engine's `start` lists them: the scenario's, then generated traffic), so
//!   that no road user has the id 0 an unset field reads as; its sightline id
//!   is in a `source_reference` of type [`AGENT_REFERENCE`];
//! - a roadside unit is no road user: it is a stationary object (of type
//!   `TYPE_OTHER`, numbered and referenced the same way), and its sensors'
//!   views have no host vehicle (`host_vehicle_id` unset), their mounting
//!   positions in the unit's frame;
//! - timestamps are simulated time since step 0 (`zero_time` in an OSI trace's
//!   metadata places that on the calendar);
//! - the world is planar: a bounding box stands on the ground (its centre at
//!   half its height), every roll and pitch is 0, and a vehicle's reference
//!   point (OSI's rear axle, which sightline does not model) is its footprint's
//!   centre on the ground (`bbcenter_to_rear` (0, 0, −height/2)), the origin of
//!   the vehicle coordinates a sensor's mounting position is given in;
//! - a sensor's id is its index on its agent; a `SensorView` holds the whole
//!   ground truth, as OSI requires, and each road user its sensor has in range
//!   and field of view carries a `source_reference` of type
//!   [`VISIBILITY_REFERENCE`] whose identifiers are its visibility class (`los`,
//!   `nlos_static`, `nlos_dynamic`) and its visible fraction (the share of its
//!   angular extent in line of sight, 0 to 1, as a decimal).

use sightline_dsl::{Agent, AgentKind, Sensor};
use sightline_engine::trace::{AgentState, Sighting, Visibility, WorldStep};
use sightline_osi::osi3;
use sightline_osi::osi3::moving_object::{Type as ObjectType, VehicleClassification, vehicle_classification};

/// The `source_reference` type naming a road user's sightline id.
pub const AGENT_REFERENCE: &str = "sightline.agent";

/// The `source_reference` type carrying what a sensor sees of a road user.
pub const VISIBILITY_REFERENCE: &str = "sightline.visibility";

/// The OSI id of agent `index`.
fn object_id(index: usize) -> u64 {
    index as u64 + 1
}

fn identifier(value: u64) -> osi3::Identifier {
    osi3::Identifier { value: Some(value) }
}

/// `seconds` of simulated time (never negative) as an OSI timestamp.
pub(super) fn timestamp(seconds: f64) -> osi3::Timestamp {
    let nanos = (seconds.max(0.0) * 1e9).round() as u64;
    osi3::Timestamp {
        seconds: Some((nanos / 1_000_000_000) as i64),
        nanos: Some((nanos % 1_000_000_000) as u32),
    }
}

/// The ground truth of one step at `time`: every agent in the scene
/// (`states` by agent index), in agent order, the road users as moving
/// objects and the roadside units as stationary ones; `host` names the host
/// vehicle.
pub(super) fn ground_truth(
    agents: &[Agent],
    states: &[Option<AgentState>],
    time: f64,
    host: Option<usize>,
) -> osi3::GroundTruth {
    let present = || {
        agents
            .iter()
            .zip(states)
            .enumerate()
            .filter_map(|(index, (agent, state))| state.as_ref().map(|state| (index, agent, state)))
    };
    let moving_object = present()
        .filter(|(_, agent, _)| agent.kind != AgentKind::Rsu)
        .map(|(index, agent, state)| moving_object(index, agent, state))
        .collect();
    let stationary_object = present()
        .filter(|(_, agent, _)| agent.kind == AgentKind::Rsu)
        .map(|(index, agent, state)| roadside_unit(index, agent, state))
        .collect();
    osi3::GroundTruth {
        version: Some(sightline_osi::interface_version()),
        timestamp: Some(timestamp(time)),
        host_vehicle_id: host.map(|host| identifier(object_id(host))),
        moving_object,
        stationary_object,
        ..Default::default()
    }
}

/// Roadside unit `index` at `state` as a stationary object.
fn roadside_unit(index: usize, agent: &Agent, state: &AgentState) -> osi3::StationaryObject {
    let height = agent.kind.height();
    let position = state.position();
    osi3::StationaryObject {
        id: Some(identifier(object_id(index))),
        base: Some(osi3::BaseStationary {
            dimension: Some(osi3::Dimension3d {
                length: Some(agent.length),
                width: Some(agent.width),
                height: Some(height),
            }),
            position: Some(vector(position.x, position.y, height / 2.0)),
            orientation: Some(yaw(state.heading())),
            ..Default::default()
        }),
        classification: Some(osi3::stationary_object::Classification {
            r#type: Some(osi3::stationary_object::classification::Type::Other as i32),
            ..Default::default()
        }),
        source_reference: vec![agent_reference(agent)],
        ..Default::default()
    }
}

/// The `source_reference` naming `agent`'s sightline id.
fn agent_reference(agent: &Agent) -> osi3::ExternalReference {
    osi3::ExternalReference {
        r#type: Some(AGENT_REFERENCE.into()),
        identifier: vec![agent.id.clone()],
        ..Default::default()
    }
}

/// Agent `index` at `state` as a moving object.
fn moving_object(index: usize, agent: &Agent, state: &AgentState) -> osi3::MovingObject {
    let height = agent.kind.height();
    let heading = state.heading();
    let position = state.position();
    let vehicle = match agent.kind {
        AgentKind::Car => Some(vehicle_classification::Type::Car),
        AgentKind::Truck => Some(vehicle_classification::Type::HeavyTruck),
        AgentKind::Bus => Some(vehicle_classification::Type::Bus),
        AgentKind::Motorbike => Some(vehicle_classification::Type::Motorbike),
        AgentKind::Bicycle => Some(vehicle_classification::Type::Bicycle),
        AgentKind::Pedestrian | AgentKind::Rsu => None,
    };
    let kind = match vehicle {
        Some(_) => ObjectType::Vehicle,
        None => ObjectType::Pedestrian,
    };
    osi3::MovingObject {
        id: Some(identifier(object_id(index))),
        base: Some(osi3::BaseMoving {
            dimension: Some(osi3::Dimension3d {
                length: Some(agent.length),
                width: Some(agent.width),
                height: Some(height),
            }),
            position: Some(vector(position.x, position.y, height / 2.0)),
            orientation: Some(yaw(heading)),
            velocity: Some(vector(state.speed * heading.cos(), state.speed * heading.sin(), 0.0)),
            ..Default::default()
        }),
        r#type: Some(kind as i32),
        vehicle_attributes: vehicle.map(|_| osi3::moving_object::VehicleAttributes {
            bbcenter_to_rear: Some(vector(0.0, 0.0, -height / 2.0)),
            ..Default::default()
        }),
        vehicle_classification: vehicle.map(|class| VehicleClassification {
            r#type: Some(class as i32),
            ..Default::default()
        }),
        source_reference: vec![agent_reference(agent)],
        ..Default::default()
    }
}

fn vector(x: f64, y: f64, z: f64) -> osi3::Vector3d {
    osi3::Vector3d {
        x: Some(x),
        y: Some(y),
        z: Some(z),
    }
}

fn yaw(yaw: f64) -> osi3::Orientation3d {
    osi3::Orientation3d {
        roll: Some(0.0),
        pitch: Some(0.0),
        yaw: Some(yaw),
    }
}

/// A sensor's mounting position in its agent's frame: the vehicle
/// coordinates, or a roadside unit's own.
fn mounting(sensor: &Sensor) -> osi3::MountingPosition {
    osi3::MountingPosition {
        position: Some(vector(sensor.mount_x, sensor.mount_y, 0.0)),
        orientation: Some(yaw(sensor.mount_yaw)),
    }
}

/// What sensor `index` (`sensor`) of agent `host` has in view at a step with
/// ground truth `truth`: the ground truth with `host` its host vehicle (none
/// when `host` is a roadside unit, `vehicle` false) and the sensor's
/// `sightings` of the step annotated on the road users they name.
pub(super) fn sensor_view(
    truth: &osi3::GroundTruth,
    (host, vehicle): (usize, bool),
    (index, sensor): (usize, &Sensor),
    sightings: &[Sighting],
) -> osi3::SensorView {
    let mut truth = truth.clone();
    let host_vehicle_id = vehicle.then(|| identifier(object_id(host)));
    truth.host_vehicle_id = host_vehicle_id;
    for sighting in sightings.iter().filter(|s| s.sensor == index) {
        let id = object_id(sighting.target);
        if let Some(object) = truth
            .moving_object
            .iter_mut()
            .find(|o| o.id.and_then(|i| i.value) == Some(id))
        {
            object.source_reference.push(visibility(sighting));
        }
    }
    let sensor_id = identifier(index as u64);
    osi3::SensorView {
        version: Some(sightline_osi::interface_version()),
        timestamp: truth.timestamp,
        sensor_id: Some(sensor_id),
        mounting_position: Some(mounting(sensor)),
        host_vehicle_id,
        generic_sensor_view: vec![osi3::GenericSensorView {
            view_configuration: Some(osi3::GenericSensorViewConfiguration {
                sensor_id: Some(sensor_id),
                mounting_position: Some(mounting(sensor)),
                field_of_view_horizontal: Some(sensor.fov),
                ..Default::default()
            }),
        }],
        global_ground_truth: Some(truth),
        ..Default::default()
    }
}

/// A sighting as a `source_reference`: its class and visible fraction.
fn visibility(sighting: &Sighting) -> osi3::ExternalReference {
    let class = match sighting.visibility {
        Visibility::Los => "los",
        Visibility::NlosStatic => "nlos_static",
        Visibility::NlosDynamic => "nlos_dynamic",
    };
    osi3::ExternalReference {
        r#type: Some(VISIBILITY_REFERENCE.into()),
        identifier: vec![class.into(), sighting.visible_fraction.to_string()],
        ..Default::default()
    }
}

/// One step of a perception world as OSI messages.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StepViews {
    /// The ground truth, the ego its host vehicle.
    pub(super) ground_truth: osi3::GroundTruth,
    /// Per cooperating agent in the scene (the ego first) and sensor of it, in
    /// order: the agent, the sensor's index and what it has in view.
    pub(super) sensor_views: Vec<(usize, usize, osi3::SensorView)>,
}

impl StepViews {
    /// `step` of a world of `agents` whose ego is `ego`.
    pub(super) fn of(agents: &[Agent], step: &WorldStep<'_>, ego: Option<usize>) -> Self {
        let ground_truth = ground_truth(agents, step.agents, step.time, ego);
        let sensor_views = step
            .cooperators
            .iter()
            .flat_map(|c| {
                let host = agents.get(c.agent);
                let sensors = host.map_or(&[][..], |a| a.sensors.as_slice());
                let vehicle = host.is_some_and(|a| a.kind != AgentKind::Rsu);
                let truth = &ground_truth;
                sensors.iter().enumerate().map(move |sensor| {
                    let view = sensor_view(truth, (c.agent, vehicle), sensor, c.observation.sighted());
                    (c.agent, sensor.0, view)
                })
            })
            .collect();
        Self {
            ground_truth,
            sensor_views,
        }
    }
}
