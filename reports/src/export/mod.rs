//! A scenario's world as files other tools replay: an ASAM OpenSCENARIO 1.2
//! scenario and its ASAM OpenDRIVE 1.7 map (`sightline export`).
//!
//! The map (`map`, written by `opendrive`) is the world's declared roads:
//! polylines as line records, arcs and roundabouts as arc records, lanes of
//! their width, links and junctions where routes drive from one road into
//! another, occluders as buildings and crosswalks as crosswalk objects. The
//! scenario (`openscenario`) is one simulation of one sweep point
//! (`motion`): each agent, generated traffic included, an entity of its kind
//! and size, and each moving agent following the trajectory it was simulated
//! along, timed as simulated. What does not carry over is in docs/export.md.

mod map;
mod motion;
mod opendrive;
mod openscenario;
mod xml;

pub use opendrive::OPENDRIVE_VERSION;
pub use openscenario::OPENSCENARIO_VERSION;

use sightline_dsl::{Experiment, ImportKind, Scenario, World};

/// The two files of an export, in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The OpenSCENARIO document.
    pub openscenario: String,
    /// The OpenDRIVE document.
    pub opendrive: String,
    /// What the files leave out of this scenario, one sentence each.
    pub notes: Vec<String>,
    /// Roads in the map.
    pub roads: usize,
    /// Junctions in the map.
    pub junctions: usize,
    /// Entities in the scenario.
    pub entities: usize,
    /// Of those, the generated traffic's.
    pub generated: usize,
}

/// What to export, and how the files name each other and their author.
#[derive(Debug, Clone, Copy)]
pub struct ExportRequest<'a> {
    /// The compiled scenario.
    pub scenario: &'a Scenario,
    /// The sweep point simulated, an index into its points.
    pub point: usize,
    /// The OpenDRIVE file's name, as the OpenSCENARIO file refers to it.
    pub map_file: &'a str,
    /// The tool that writes the files (the file header's author).
    pub author: &'a str,
}

/// Why a scenario cannot be exported.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ExportError {
    /// A `field` experiment has no roads or agents.
    #[error("nothing to export: the scenario is a `field` experiment, with no roads and no agents")]
    Field,
    /// A world without roads has no map.
    #[error("nothing to export as a map: the scenario declares no roads (OpenDRIVE needs at least one)")]
    NoRoads,
    /// A name or id holds a character XML 1.0 does not allow.
    #[error("the value \"{value}\" holds U+{code:04X}, a character XML 1.0 does not allow: it cannot be exported")]
    Unwritable {
        /// The value, escaped as Rust's debug format escapes a string.
        value: String,
        /// The character's code point.
        code: u32,
    },
    /// Two entities of the scenario have one name.
    #[error("two entities are named \"{0}\": OpenSCENARIO knows an entity by its name")]
    DuplicateName(String),
}

impl From<xml::Unwritable> for ExportError {
    fn from(xml::Unwritable { value, code }: xml::Unwritable) -> Self {
        Self::Unwritable { value, code }
    }
}

/// Simulates the requested point once, at its seed, and writes its world as
/// OpenSCENARIO and OpenDRIVE.
pub fn export(request: &ExportRequest<'_>) -> Result<Export, ExportError> {
    let scenario = request.scenario;
    let point = &scenario.points[request.point];
    let Experiment::World(world) = &point.setup.experiment else {
        return Err(ExportError::Field);
    };
    let map = map::map(world).ok_or(ExportError::NoRoads)?;
    let mut motions = motion::Motions::default();
    sightline_engine::simulate_point(scenario, request.point, &mut motions);
    let mut notes = map.notes.clone();
    notes.extend(left_out(scenario, world));
    let absent: Vec<String> = motions
        .agents
        .iter()
        .zip(&motions.samples)
        .filter(|(_, samples)| samples.is_empty())
        .map(|(agent, _)| agent.id.escape_debug().to_string())
        .collect();
    if !absent.is_empty() {
        notes.push(format!(
            "{} agent(s) never in the scene during the run are left out: {}",
            absent.len(),
            absent.join(", ")
        ));
    }
    let label = point.label();
    let description = if label.is_empty() {
        format!("{} (seed {})", scenario.name, point.setup.seed)
    } else {
        format!("{} at {label} (seed {})", scenario.name, point.setup.seed)
    };
    let header = openscenario::Header {
        description: &description,
        author: request.author,
        map_file: request.map_file,
        duration: world.steps as f64 * world.step,
    };
    let (openscenario, entities) = openscenario::openscenario(&header, &motions)?;
    let declared = world.agents.len();
    let generated = motions.samples[declared.min(motions.samples.len())..]
        .iter()
        .filter(|samples| !samples.is_empty())
        .count();
    Ok(Export {
        opendrive: opendrive::opendrive(&map, &scenario.name)?,
        openscenario,
        notes,
        roads: map.roads.len(),
        junctions: map.junctions.len(),
        entities,
        generated,
    })
}

/// What the files leave out of `scenario` whatever the run: the links across
/// an imported network's junctions, an OpenDRIVE map's sidewalks, the system
/// under test.
fn left_out(scenario: &Scenario, world: &World) -> Vec<String> {
    let imported = |kind| scenario.imports.iter().any(|import| import.kind == kind);
    let mut notes = Vec::new();
    if world.roads.iter().any(|road| !road.links.is_empty()) {
        let network = if imported(ImportKind::OpenDrive) {
            "the OpenDRIVE map's"
        } else {
            "the SUMO network's"
        };
        notes.push(format!(
            "the connections across {network} junctions are not linked in the map (its roads and lanes are; the \
             agents' trajectories drive through the junctions)"
        ));
    }
    if imported(ImportKind::OpenDrive) {
        notes.push(
            "the OpenDRIVE map's sidewalks and other walking lanes are not in the map (its driving lanes are); the \
             pedestrians' trajectories follow them"
                .into(),
        );
    }
    if let Some(system) = &scenario.system_under_test {
        notes.push(format!(
            "the system under test (`{}`) is not exported: the files hold the world it is driven in",
            system.name().escape_debug()
        ));
    }
    notes
}
