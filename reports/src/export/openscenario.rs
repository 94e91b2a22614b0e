//! One simulation of a world written as ASAM OpenSCENARIO 1.2 XML: every
//! agent an entity of its kind and size, placed and set to its speed at the
//! start, and every moving agent following the trajectory it was simulated
//! along, timed as simulated, from when it appeared.

use sightline_dsl::{Agent, AgentKind, Motion};

use super::ExportError;
use super::motion::{Motions, Sample, thinned};
use super::xml::{Xml, num};

/// The OpenSCENARIO version written: 1.2.
pub const OPENSCENARIO_VERSION: (u32, u32) = (1, 2);

/// The file header's date: fixed, so that the same scenario and seed give the
/// same bytes (the recording's default clock, `time.start`).
const DATE: &str = "2000-01-01T00:00:00";

/// What the scenario file says of itself.
pub(crate) struct Header<'a> {
    /// The file header's description.
    pub description: &'a str,
    /// The file header's author: the tool that wrote it.
    pub author: &'a str,
    /// The OpenDRIVE file, relative to this one.
    pub map_file: &'a str,
    /// When the storyboard stops, seconds.
    pub duration: f64,
}

/// The entities and storyboard of `motions`; agents never in the scene are
/// left out. Returns the document and how many entities it has; an error
/// when two have one name or a value cannot be written.
pub(crate) fn openscenario(header: &Header<'_>, motions: &Motions) -> Result<(String, usize), ExportError> {
    let present: Vec<(&Agent, &[Sample])> = motions
        .agents
        .iter()
        .zip(&motions.samples)
        .filter(|(_, samples)| !samples.is_empty())
        .map(|(agent, samples)| (agent, samples.as_slice()))
        .collect();
    let mut names = std::collections::HashSet::new();
    if let Some((agent, _)) = present.iter().find(|(agent, _)| !names.insert(agent.id.as_str())) {
        return Err(ExportError::DuplicateName(agent.id.escape_debug().to_string()));
    }
    let mut xml = Xml::new();
    xml.start("OpenSCENARIO", &[]);
    xml.empty(
        "FileHeader",
        &[
            ("revMajor", OPENSCENARIO_VERSION.0.to_string()),
            ("revMinor", OPENSCENARIO_VERSION.1.to_string()),
            ("date", DATE.into()),
            ("description", header.description.into()),
            ("author", header.author.into()),
        ],
    );
    xml.empty("ParameterDeclarations", &[]);
    xml.empty("CatalogLocations", &[]);
    xml.start("RoadNetwork", &[]);
    xml.empty("LogicFile", &[("filepath", header.map_file.into())]);
    xml.end();
    xml.start("Entities", &[]);
    for (agent, _) in &present {
        write_entity(&mut xml, agent);
    }
    xml.end();
    xml.start("Storyboard", &[]);
    xml.start("Init", &[]);
    xml.start("Actions", &[]);
    for (agent, samples) in &present {
        write_init(&mut xml, agent, samples[0]);
    }
    xml.end();
    xml.end();
    xml.start("Story", &[("name", "sightline".into())]);
    xml.start("Act", &[("name", "simulated".into())]);
    let moving: Vec<(&Agent, Vec<Sample>)> = present
        .iter()
        .filter(|(agent, _)| !matches!(agent.motion, Motion::Fixed { .. }))
        .map(|(agent, samples)| (*agent, thinned(samples)))
        .filter(|(_, vertices)| vertices.len() >= 2)
        .collect();
    for (agent, vertices) in &moving {
        write_maneuver_group(&mut xml, agent, vertices);
    }
    if moving.is_empty() {
        // An act needs a maneuver group; one with no maneuver does nothing.
        xml.start(
            "ManeuverGroup",
            &[("maximumExecutionCount", "1".into()), ("name", "none".into())],
        );
        xml.empty("Actors", &[("selectTriggeringEntities", "false".into())]);
        xml.end();
    }
    write_time_trigger(&mut xml, "StartTrigger", "start", 0.0);
    xml.end();
    xml.end();
    write_time_trigger(&mut xml, "StopTrigger", "end", header.duration);
    Ok((xml.finish()?, present.len()))
}

fn write_entity(xml: &mut Xml, agent: &Agent) {
    xml.start("ScenarioObject", &[("name", agent.id.clone())]);
    let z = agent.kind.height();
    match agent.kind {
        AgentKind::Car | AgentKind::Truck | AgentKind::Bus | AgentKind::Motorbike | AgentKind::Bicycle => {
            xml.start(
                "Vehicle",
                &[
                    ("name", agent.id.clone()),
                    ("vehicleCategory", agent.kind.name().into()),
                ],
            );
            write_bounding_box(xml, agent, z);
            // Generous limits: the trajectory's timing, not the vehicle, sets its speed.
            xml.empty(
                "Performance",
                &[
                    ("maxSpeed", "70".into()),
                    ("maxAcceleration", "10".into()),
                    ("maxDeceleration", "10".into()),
                ],
            );
            let wheel: f64 = if matches!(agent.kind, AgentKind::Truck | AgentKind::Bus) {
                1.0
            } else {
                0.6
            };
            xml.start("Axles", &[]);
            for (tag, x, steering) in [("FrontAxle", 0.3, 0.5), ("RearAxle", -0.3, 0.0)] {
                xml.empty(
                    tag,
                    &[
                        ("maxSteering", num(steering)),
                        ("wheelDiameter", num(wheel)),
                        ("trackWidth", num(0.85 * agent.width)),
                        ("positionX", num(x * agent.length)),
                        ("positionZ", num(wheel / 2.0)),
                    ],
                );
            }
            xml.end();
        }
        AgentKind::Pedestrian => {
            xml.start(
                "Pedestrian",
                &[
                    ("name", agent.id.clone()),
                    ("mass", "75".into()),
                    ("pedestrianCategory", "pedestrian".into()),
                ],
            );
            write_bounding_box(xml, agent, z);
        }
        AgentKind::Rsu => {
            xml.start(
                "MiscObject",
                &[
                    ("name", agent.id.clone()),
                    ("mass", "100".into()),
                    ("miscObjectCategory", "pole".into()),
                ],
            );
            write_bounding_box(xml, agent, z);
        }
    }
    xml.start("Properties", &[]);
    xml.empty(
        "Property",
        &[("name", "sightline.kind".into()), ("value", agent.kind.name().into())],
    );
    xml.empty(
        "Property",
        &[
            ("name", "sightline.connected".into()),
            ("value", agent.connected.to_string()),
        ],
    );
    xml.end();
    xml.end();
    xml.end();
}

/// The footprint as a box whose centre is the entity's reference point.
fn write_bounding_box(xml: &mut Xml, agent: &Agent, height: f64) {
    xml.start("BoundingBox", &[]);
    xml.empty(
        "Center",
        &[("x", "0".into()), ("y", "0".into()), ("z", num(height / 2.0))],
    );
    xml.empty(
        "Dimensions",
        &[
            ("width", num(agent.width)),
            ("length", num(agent.length)),
            ("height", num(height)),
        ],
    );
    xml.end();
}

fn write_position(xml: &mut Xml, sample: &Sample) {
    xml.start("Position", &[]);
    xml.empty(
        "WorldPosition",
        &[
            ("x", num(sample.position[0])),
            ("y", num(sample.position[1])),
            ("z", "0".into()),
            ("h", num(sample.heading)),
        ],
    );
    xml.end();
}

/// Where the agent first is, and its speed there.
fn write_init(xml: &mut Xml, agent: &Agent, first: Sample) {
    xml.start("Private", &[("entityRef", agent.id.clone())]);
    xml.start("PrivateAction", &[]);
    xml.start("TeleportAction", &[]);
    write_position(xml, &first);
    xml.end();
    xml.end();
    if !matches!(agent.motion, Motion::Fixed { .. }) {
        xml.start("PrivateAction", &[]);
        xml.start("LongitudinalAction", &[]);
        xml.start("SpeedAction", &[]);
        xml.empty(
            "SpeedActionDynamics",
            &[
                ("dynamicsShape", "step".into()),
                ("value", "0".into()),
                ("dynamicsDimension", "time".into()),
            ],
        );
        xml.start("SpeedActionTarget", &[]);
        xml.empty("AbsoluteTargetSpeed", &[("value", num(first.speed))]);
        xml.end();
        xml.end();
        xml.end();
        xml.end();
    }
    xml.end();
}

/// The agent follows its timed trajectory from the time it appears.
fn write_maneuver_group(xml: &mut Xml, agent: &Agent, vertices: &[Sample]) {
    let id = &agent.id;
    xml.start(
        "ManeuverGroup",
        &[("maximumExecutionCount", "1".into()), ("name", id.clone())],
    );
    xml.start("Actors", &[("selectTriggeringEntities", "false".into())]);
    xml.empty("EntityRef", &[("entityRef", id.clone())]);
    xml.end();
    xml.start("Maneuver", &[("name", id.clone())]);
    xml.start("Event", &[("name", id.clone()), ("priority", "override".into())]);
    xml.start("Action", &[("name", id.clone())]);
    xml.start("PrivateAction", &[]);
    xml.start("RoutingAction", &[]);
    xml.start("FollowTrajectoryAction", &[]);
    xml.start("TrajectoryRef", &[]);
    xml.start("Trajectory", &[("name", id.clone()), ("closed", "false".into())]);
    xml.start("Shape", &[]);
    xml.start("Polyline", &[]);
    for vertex in vertices {
        xml.start("Vertex", &[("time", num(vertex.time))]);
        write_position(xml, vertex);
        xml.end();
    }
    xml.end();
    xml.end();
    xml.end();
    xml.end();
    xml.start("TimeReference", &[]);
    xml.empty(
        "Timing",
        &[
            ("domainAbsoluteRelative", "absolute".into()),
            ("scale", "1".into()),
            ("offset", "0".into()),
        ],
    );
    xml.end();
    xml.empty("TrajectoryFollowingMode", &[("followingMode", "position".into())]);
    xml.end();
    xml.end();
    xml.end();
    xml.end();
    write_time_trigger(xml, "StartTrigger", "appears", vertices[0].time);
    xml.end();
    xml.end();
    xml.end();
}

/// A trigger that fires once the simulation time reaches `time`.
fn write_time_trigger(xml: &mut Xml, tag: &'static str, name: &str, time: f64) {
    xml.start(tag, &[]);
    xml.start("ConditionGroup", &[]);
    xml.start(
        "Condition",
        &[
            ("name", name.into()),
            ("delay", "0".into()),
            ("conditionEdge", "none".into()),
        ],
    );
    xml.start("ByValueCondition", &[]);
    xml.empty(
        "SimulationTimeCondition",
        &[("value", num(time)), ("rule", "greaterOrEqual".into())],
    );
    xml.end();
    xml.end();
    xml.end();
    xml.end();
}
