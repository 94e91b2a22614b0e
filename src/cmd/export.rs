//! `sightline export FILE [--out DIR] [--point LABEL] [--seed N]`
//!
//! Compiles the scenario, has `sightline_reports::export` simulate one sweep
//! point and render it as OpenSCENARIO and OpenDRIVE, and writes the two files
//! into `DIR` as a set (see `staging`): both, or neither.

use sightline_reports::{ExportRequest, OPENDRIVE_VERSION, OPENSCENARIO_VERSION};

use crate::cli::ExportArgs;
use crate::evidence::{evidence_dirs, tool};
use crate::exit::Exit;
use crate::input::load_all;
use crate::output::say;
use crate::staging::Staging;
use crate::terminal::stderr;

/// The scenario's file name in the output directory.
pub const SCENARIO_FILE: &str = "scenario.xosc";

/// The map's file name, beside the scenario, which refers to it by this name.
pub const MAP_FILE: &str = "scenario.xodr";

/// The files of an export: a new export replaces both.
const EXPORT_SET: &[&str] = &[SCENARIO_FILE, MAP_FILE];

/// Exports the requested point of the scenario; [`Exit::Invalid`] (nothing
/// written) when it cannot be exported.
pub fn export(args: &ExportArgs) -> anyhow::Result<Exit> {
    let Some(input) = load_all(std::slice::from_ref(&args.file), args.seed, (false, false), None)
        .and_then(|inputs| inputs.into_iter().next())
    else {
        return Ok(Exit::Invalid);
    };
    let path = &input.name;
    let scenario = &input.scenario;
    let point = match &args.point {
        None => 0,
        Some(label) => match scenario.points.iter().position(|p| &p.label() == label) {
            Some(point) => point,
            None => {
                let labels: Vec<String> = scenario.points.iter().map(|p| format!("`{}`", p.label())).collect();
                stderr!(
                    "{path}: error: --point: no sweep point is labelled `{label}` (the points: {})",
                    labels.join(", ")
                );
                return Ok(Exit::Invalid);
            }
        },
    };
    let tool = tool();
    let author = format!("{} {}", tool.name, tool.version);
    let request = ExportRequest {
        scenario,
        point,
        map_file: MAP_FILE,
        author: &author,
    };
    let exported = match sightline_reports::export(&request) {
        Ok(exported) => exported,
        Err(error) => {
            stderr!("{path}: error: {error}");
            return Ok(Exit::Invalid);
        }
    };
    let Some(dir) =
        evidence_dirs(args.out.as_deref(), [&input], EXPORT_SET, None).and_then(|dirs| dirs.into_iter().next())
    else {
        return Ok(Exit::Invalid);
    };
    let mut staging = Staging::open(&dir, EXPORT_SET)?;
    staging.write(SCENARIO_FILE, exported.openscenario.as_bytes())?;
    staging.write(MAP_FILE, exported.opendrive.as_bytes())?;
    staging.commit()?;
    for note in &exported.notes {
        stderr!("{path}: note: {note}");
    }
    let label = scenario.points[point].label();
    let at = if label.is_empty() {
        String::new()
    } else {
        format!(" at {label}")
    };
    say(format_args!(
        "EXPORTED {path}{at} (seed {}): OpenSCENARIO {}.{} with {} entities ({} generated), OpenDRIVE {}.{} with {} roads and {} junctions -> {}",
        scenario.points[point].setup.seed,
        OPENSCENARIO_VERSION.0,
        OPENSCENARIO_VERSION.1,
        exported.entities,
        exported.generated,
        OPENDRIVE_VERSION.0,
        OPENDRIVE_VERSION.1,
        exported.roads,
        exported.junctions,
        dir.display()
    ));
    Ok(Exit::Pass)
}
