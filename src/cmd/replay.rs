//! `sightline replay RUN.mcap`

use std::io;
use std::path::Path;

use sightline_dsl::Options;
use sightline_reports::mcap::{Recording, read};
use sightline_reports::sha256_hex;

use super::merge::OUT_OF_DOMAIN;
use crate::exit::Exit;
use crate::files::{DATA_LIMIT, read_regular};
use crate::summary::{print_verdicts, refuse_out_of_domain};
use crate::terminal::stderr;

/// Re-checks the requirements of a recording from what it holds: the file is
/// checked whole (and against the results.json beside it, if any), the recorded
/// scenario is compiled again, every recorded value is checked against its
/// domain, and the oracles judge the recorded measurements. Prints the verdicts
/// as `run` does; every refusal is exit 2 but a value outside its domain, which
/// no run gives: exit 3.
pub fn replay(file: &Path) -> Exit {
    let name = file.display();
    let bytes = match read_regular(file, DATA_LIMIT) {
        Ok(bytes) => bytes,
        Err(error) => {
            stderr!("{name}: error: failed to read the recording: {error}");
            return Exit::Invalid;
        }
    };
    if let Err(problem) = matches_results(file, &bytes) {
        stderr!("{name}: error: {problem}");
        return Exit::Invalid;
    }
    let recording = match read(&bytes) {
        Ok(recording) => recording,
        Err(error) => {
            stderr!("{name}: error: failed to read the recording: {error}");
            return Exit::Invalid;
        }
    };
    let loader = |path: &Path| {
        recording
            .imports
            .get(&path.display().to_string())
            .cloned()
            .ok_or_else(|| io::Error::new(io::ErrorKind::NotFound, "the recording does not carry this file"))
    };
    let options = Options {
        seed: recording.scenario.seed,
        loader: Some(&loader),
        record: recording.scenario.record_flag,
        osi: false,
        processes: None,
    };
    let scenario = match sightline_dsl::compile(&recording.scenario.file, &recording.scenario.text, &options) {
        Ok(scenario) => scenario,
        Err(errors) => {
            stderr!("{name}: error: the recorded scenario does not compile with this sightline:");
            stderr!("{errors}");
            return Exit::Invalid;
        }
    };
    let measurements = match recording.measurements(scenario.points.len()) {
        Ok(measurements) => measurements,
        Err(error) => {
            stderr!("{name}: error: failed to read the recording: {error}");
            return Exit::Invalid;
        }
    };
    if let Some(exit) = refuse_out_of_domain(&name, &scenario, &measurements, OUT_OF_DOMAIN) {
        return exit;
    }
    let verdicts = sightline_oracles::check(&scenario, &measurements);
    warn_divergence(&name.to_string(), &recording, &verdicts);
    print_verdicts(
        &recording.scenario.file,
        &scenario,
        &verdicts,
        format_args!("(replayed from {name})"),
    )
}

/// Checks `bytes` against the recording's SHA-256 in the results.json beside
/// `file`, when there is one.
fn matches_results(file: &Path, bytes: &[u8]) -> Result<(), String> {
    let results = file.with_file_name("results.json");
    let text = match read_regular(&results, DATA_LIMIT).map(String::from_utf8) {
        Ok(Ok(text)) => text,
        Ok(Err(_)) => return Err(format!("{} beside it is not UTF-8 text", results.display())),
        Err(error) if error.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(error) => return Err(format!("failed to read {} beside it: {error}", results.display())),
    };
    let json: serde_json::Value = serde_json::from_str(&text).map_err(|error| {
        format!(
            "{} beside it is not JSON ({error}), so the recording cannot be checked against it",
            results.display()
        )
    })?;
    let Some(expected) = json["recording"]["sha256"].as_str() else {
        return Err(format!(
            "{} beside it records no recording: this file is not the one that run wrote",
            results.display()
        ));
    };
    let actual = sha256_hex(bytes);
    if actual != expected {
        return Err(format!(
            "its SHA-256 is {actual}, and {} beside it records {expected}: the recording was changed or is not the one that run wrote",
            results.display()
        ));
    }
    Ok(())
}

/// Warns where this sightline's verdicts differ from those the recording
/// holds (a different version judging the same measurements differently).
fn warn_divergence(name: &str, recording: &Recording, verdicts: &[sightline_oracles::Verdict]) {
    if recording.verdicts.len() != verdicts.len() {
        stderr!(
            "{name}: warning: the recording holds {} verdicts; replay reaches {}",
            recording.verdicts.len(),
            verdicts.len()
        );
    }
    for (recorded, verdict) in recording.verdicts.iter().zip(verdicts) {
        if recorded.id != verdict.id
            || recorded.verdict != verdict.status.name()
            || recorded.message != verdict.decisive.message
        {
            stderr!(
                "{name}: warning: {}: the recording holds `{} {}: {}`; replay gives `{} {}: {}`",
                verdict.id,
                recorded.verdict,
                recorded.id,
                recorded.message,
                verdict.status.name(),
                verdict.id,
                verdict.decisive.message
            );
        }
    }
}
