//! A scenario's evidence, shared by `run`, `run --shard` and `merge`: how the run
//! was asked for, this build, the recording staged with the evidence, and the
//! evidence set committed into its directory as a whole (see `staging`).

use std::collections::HashSet;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::Context;
use sightline_dsl::{Record, RecordedPoints, Scenario};
use sightline_engine::Run;
use sightline_engine::TraceSink;
use sightline_engine::trace::{SemanticStep, WorldStep};
use sightline_oracles::Verdict;
use sightline_reports::mcap::{Recorder, Source};
use sightline_reports::osi::{OSI_TRACE, OsiTrace};
use sightline_reports::{
    Execution, OsiTraceInfo, Provenance, RecordingInfo, Sha256Writer, Templates, Tool, render, sha256_hex,
};

use crate::exit::Exit;
use crate::input::Input;
use crate::output::{default_dir, shell_word, stem};
use crate::staging::Staging;
use crate::summary::print_verdicts;
use crate::terminal::stderr;

/// The recording's name in the evidence directory.
pub const RECORDING: &str = "run.mcap";

/// Every file of a scenario's evidence set, `run`'s, `merge`'s and `falsify`'s
/// alike: a new set replaces all of them, so that no file of an earlier set (a
/// `run.mcap` when the new run records nothing, `falsify`'s files after a `run`,
/// a `counterexample.yaml` after a search that found none) stays beside it.
pub const EVIDENCE_SET: &[&str] = &[
    "results.json",
    "junit.xml",
    "report.html",
    RECORDING,
    OSI_TRACE,
    "falsify.json",
    "counterexample.yaml",
];

/// How a run was asked for, as its evidence and its recording say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    /// `--seed`.
    pub seed: Option<u64>,
    /// `--record` (or `--osi`, which implies it).
    pub record: bool,
    /// `--osi`.
    pub osi: bool,
}

/// What the evidence of every scenario of a command shares.
pub struct Reporting<'t> {
    /// This build of sightline.
    pub tool: Tool,
    /// How the run was asked for.
    pub request: Request,
    /// The page templates.
    pub templates: &'t Templates,
}

/// This build of sightline.
pub fn tool() -> Tool {
    Tool {
        name: "sightline".into(),
        version: env!("CARGO_PKG_VERSION").into(),
        git: env!("SIGHTLINE_GIT").into(),
    }
}

/// A run, its verdicts, and what results.json says of its recording (staged
/// with the evidence) when the scenario asks for one.
pub type Simulated = (Run, Vec<Verdict>, Option<RecordingInfo>);

/// Renders the evidence of a simulated `input` into `staging` and commits it,
/// then prints its verdicts; [`Exit::Pass`] when every requirement holds, and
/// [`Exit::Invalid`] (nothing written) when a custom template fails on the data.
pub fn write_evidence(
    input: &Input,
    reporting: &Reporting<'_>,
    mut staging: Staging,
    (run, verdicts, recording): Simulated,
    execution: Execution,
) -> anyhow::Result<Exit> {
    let scenario = &input.scenario;
    let path = &input.name;
    let provenance = Provenance {
        tool: reporting.tool.clone(),
        scenario_path: path.clone(),
        scenario_sha256: sha256_hex(&input.bytes),
        scenario_text: String::from_utf8_lossy(&input.bytes).into_owned(),
        recording,
        execution,
    };
    // The command as typed: `-` for standard input.
    let given = shell_word(&input.path);
    let mut reproduce = match scenario.points.iter().map(|p| p.setup.seed).collect::<HashSet<_>>() {
        seeds if seeds.len() == 1 => format!("sightline run {given} --seed {}", scenario.points[0].setup.seed),
        _ => format!("sightline run {given}"),
    };
    if reporting.request.osi {
        reproduce.push_str(" --osi");
    } else if reporting.request.record {
        reproduce.push_str(" --record");
    }
    // A scenario on standard input names no evidence directory of its own.
    if input.is_stdin() {
        reproduce.push_str(&format!(" --out {}", shell_word(staging.dir())));
    }
    let templates = reporting.templates;
    let evidence = match render(scenario, &run, &verdicts, &provenance, &reproduce, templates) {
        Ok(evidence) => evidence,
        // A custom template that fails on the data is the input's fault.
        Err(sightline_reports::Error::Template(error)) if templates.is_custom() => {
            stderr!("{error}");
            return Ok(Exit::Invalid);
        }
        Err(error) => return Err(error.into()),
    };
    staging.write("results.json", evidence.results_json.as_bytes())?;
    staging.write("junit.xml", evidence.junit_xml.as_bytes())?;
    staging.write("report.html", evidence.report_html.as_bytes())?;
    let dir = staging.dir().to_path_buf();
    staging.commit()?;
    Ok(print_verdicts(
        path,
        scenario,
        &verdicts,
        format_args!("-> {}", dir.display()),
    ))
}

/// The recording of `record`'s point, when the file names it (or the scenario
/// has one point); otherwise of the decisive point of the first requirement
/// that fails the run judged `verdicts` (a failure, an error, or a
/// not-exercised verdict the scenario does not accept), or of the first point
/// when none does.
pub fn recorded_point(scenario: &Scenario, record: Record, verdicts: &[Verdict]) -> Record {
    if record.named || record.points == RecordedPoints::All {
        return record;
    }
    let worst = verdicts.iter().find(|v| v.fails_run()).map(|v| v.decisive.point);
    record.at_point(&scenario.points, worst.unwrap_or(record.point))
}

/// Simulates what `record` records of `input`'s scenario again (one point, or
/// only its first run where it pools several runs of the semantic pipeline;
/// every point), reporting its steps to `recorder`, and returns `run` once
/// what it holds of them is found the same, bit for bit.
pub fn resimulated(input: &Input, record: Record, run: Run, recorder: &mut impl TraceSink) -> anyhow::Result<Run> {
    let same = match record.points {
        RecordedPoints::One => run.points[record.point].holds_recorded(&sightline_engine::simulate_recorded(
            &input.scenario,
            record.point,
            recorder,
        )),
        RecordedPoints::All => sightline_engine::simulate_traced_all(&input.scenario, recorder, &mut |_| {}) == run,
    };
    if !same {
        anyhow::bail!(
            "{}: the recorded points, simulated again, differ from the run's outcomes: \
             sightline is not deterministic here; please report it with the scenario",
            input.name
        );
    }
    Ok(run)
}

/// What a recorded point's steps are written to: the recording, and the OSI
/// trace with `--osi`, each a staged file of the evidence set.
pub struct Sinks<'s> {
    /// The recording, hashed as it is written.
    recorder: Recorder<'s, Sha256Writer<BufWriter<File>>>,
    /// The recording's staged name.
    name: String,
    /// The OSI trace, hashed as it is written, and its staged name.
    osi: Option<(OsiTrace<Sha256Writer<BufWriter<File>>>, String)>,
}

impl<'s> Sinks<'s> {
    /// Starts recording the points `record` names of `input`'s scenario (and,
    /// with `--osi`, tracing its one point) into files staged as `run.mcap`
    /// and `osi.mcap` behind `prefix`.
    fn open(
        input: &'s Input,
        reporting: &Reporting<'_>,
        staging: &mut Staging,
        record: Record,
        prefix: &str,
    ) -> anyhow::Result<Self> {
        let name = format!("{prefix}{RECORDING}");
        let file = staging.create(&name)?;
        let osi_file = match reporting.request.osi {
            true => {
                let name = format!("{prefix}{OSI_TRACE}");
                Some((staging.create(&name)?, name))
            }
            false => None,
        };
        let text = std::str::from_utf8(&input.bytes).context("the scenario file is not UTF-8 text")?;
        let source = Source {
            tool: &reporting.tool,
            file: &input.name,
            text,
            seed: reporting.request.seed,
            record_flag: reporting.request.record,
        };
        let recorder = Recorder::new(
            Sha256Writer::new(BufWriter::new(file)),
            &input.scenario,
            record,
            &source,
        )
        .with_context(|| failed(staging, RECORDING))?;
        let osi = match osi_file {
            Some((osi_file, name)) => Some((
                OsiTrace::new(
                    Sha256Writer::new(BufWriter::new(osi_file)),
                    &input.scenario,
                    record,
                    &input.name,
                )
                .with_context(|| failed(staging, OSI_TRACE))?,
                name,
            )),
            None => None,
        };
        Ok(Self { recorder, name, osi })
    }

    /// Ends the recording of `record`'s points with the `run` and its
    /// `verdicts`, and the OSI trace, and stages them as `run.mcap` and
    /// `osi.mcap`; what results.json says of them.
    fn keep(
        self,
        staging: &mut Staging,
        scenario: &Scenario,
        record: Record,
        (run, verdicts): (&Run, &[Verdict]),
    ) -> anyhow::Result<RecordingInfo> {
        let Self { recorder, name, osi } = self;
        let (mut file, sha256) = recorder
            .finish(run, verdicts)
            .with_context(|| failed(staging, RECORDING))?
            .finish();
        file.flush().with_context(|| failed(staging, RECORDING))?;
        let osi_trace = match osi {
            Some((osi, osi_name)) => {
                let (mut osi_file, sha256) = osi.finish().with_context(|| failed(staging, OSI_TRACE))?.finish();
                osi_file.flush().with_context(|| failed(staging, OSI_TRACE))?;
                stage_as(staging, &osi_name, OSI_TRACE)?;
                Some(OsiTraceInfo {
                    file: OSI_TRACE.into(),
                    sha256,
                })
            }
            None => None,
        };
        stage_as(staging, &name, RECORDING)?;
        Ok(RecordingInfo {
            file: RECORDING.into(),
            sha256,
            point: record.point,
            label: scenario.points[record.point].label(),
            every_point: record.points == RecordedPoints::All,
            osi_trace,
        })
    }

    /// Drops the recording and the OSI trace unfinished, and their files.
    fn discard(self, staging: &mut Staging) -> anyhow::Result<()> {
        let Self { recorder, name, osi } = self;
        drop(recorder);
        staging.remove(&name)?;
        match osi {
            Some((osi, name)) => {
                drop(osi);
                staging.remove(&name)
            }
            None => Ok(()),
        }
    }
}

impl TraceSink for Sinks<'_> {
    fn point(&mut self, point: usize) {
        // `--osi` with every point recorded is refused before the run.
        self.recorder.point(point);
    }

    fn start(&mut self, agents: &[sightline_dsl::Agent]) {
        self.recorder.start(agents);
        if let Some((osi, _)) = &mut self.osi {
            osi.start(agents);
        }
    }

    fn wants_grids(&self, step: usize) -> bool {
        self.recorder.wants_grids(step)
    }

    fn world_step(&mut self, step: &WorldStep<'_>) {
        self.recorder.world_step(step);
        if let Some((osi, _)) = &mut self.osi {
            osi.world_step(step);
        }
    }

    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.recorder.semantic_step(step);
        if let Some((osi, _)) = &mut self.osi {
            osi.semantic_step(step);
        }
    }
}

/// Records the points `record` names of `input`'s scenario into `staging`
/// (and, with `--osi`, the one point's OSI trace) while `simulate` runs the scenario with them
/// as its sink, then checks the run and finishes the recording with its
/// outcomes and verdicts.
pub fn recorded(
    input: &Input,
    reporting: &Reporting<'_>,
    staging: &mut Staging,
    record: Record,
    simulate: impl FnOnce(&mut Sinks<'_>) -> anyhow::Result<Run>,
) -> anyhow::Result<Simulated> {
    let mut sinks = Sinks::open(input, reporting, staging, record, "")?;
    let run = simulate(&mut sinks)?;
    let verdicts = sightline_oracles::check(&input.scenario, &run);
    let info = sinks.keep(staging, &input.scenario, record, (&run, &verdicts))?;
    Ok((run, verdicts, Some(info)))
}

/// The most points `run --record` records in the first pass ([`records_each`]):
/// at the joint junction a point's recording costs about 75 ms of CPU and
/// simulating the point again alone about 180 ms (docs/performance.md), so
/// recording a fourth point would cost more than simulating the chosen one
/// again.
const FIRST_PASS_POINTS: usize = 3;

/// Whether `run --record` records each point of `scenario` in the first pass
/// ([`recorded_each`]) when the point to keep is chosen once the run is
/// judged: where every point shares one simulation, which simulating the
/// chosen point again would repeat almost whole, and the points are few.
pub fn records_each(scenario: &Scenario) -> bool {
    scenario.points.len() <= FIRST_PASS_POINTS && sightline_engine::shares_one_simulation(scenario)
}

/// Records every point of `input`'s scenario, each into files of its own
/// (`point-N.run.mcap`, and `point-N.osi.mcap` with `--osi`), while
/// `simulate` runs the scenario with them as its sinks, one per point; once
/// the run is judged, keeps the recording of the point [`recorded_point`]
/// picks, finished as [`recorded`] finishes it, and removes the others.
pub fn recorded_each(
    input: &Input,
    reporting: &Reporting<'_>,
    staging: &mut Staging,
    record: Record,
    simulate: impl FnOnce(&mut [Sinks<'_>]) -> anyhow::Result<Run>,
) -> anyhow::Result<Simulated> {
    let scenario = &input.scenario;
    let mut sinks = Vec::with_capacity(scenario.points.len());
    for point in 0..scenario.points.len() {
        let at_point = record.at_point(&scenario.points, point);
        sinks.push(Sinks::open(
            input,
            reporting,
            staging,
            at_point,
            &format!("point-{point}."),
        )?);
    }
    let run = simulate(&mut sinks)?;
    let verdicts = sightline_oracles::check(scenario, &run);
    let record = recorded_point(scenario, record, &verdicts);
    let kept = sinks.swap_remove(record.point);
    for other in sinks {
        other.discard(staging)?;
    }
    let info = kept.keep(staging, scenario, record, (&run, &verdicts))?;
    Ok((run, verdicts, Some(info)))
}

/// Stages the staged file `name` as `as_name`.
fn stage_as(staging: &mut Staging, name: &str, as_name: &str) -> anyhow::Result<()> {
    match name == as_name {
        true => Ok(()),
        false => staging.rename(name, as_name),
    }
}

/// What a failure to write the evidence file `name` says.
fn failed(staging: &Staging, name: &str) -> String {
    format!("failed to write {}", staging.dir().join(name).display())
}

/// Fails when a file, or a symbolic link to nothing, stands where one of
/// `dirs`, or a directory above it, is to be created: found before anything
/// runs (a shard or a second scenario would otherwise simulate first), it
/// fails as creating the directory would (evidence that cannot be written:
/// exit 3).
pub fn creatable(dirs: &[PathBuf]) -> anyhow::Result<()> {
    for dir in dirs {
        let Some(found) = dir.ancestors().find(|a| a.symlink_metadata().is_ok()) else {
            continue;
        };
        if !found.is_dir() {
            let what = match found.exists() {
                true => "is not a directory",
                false => "is a symbolic link to nothing",
            };
            anyhow::bail!("failed to create {}: {} {what}", dir.display(), found.display());
        }
    }
    Ok(())
}

/// Where each scenario's evidence goes (`out` with one scenario, `out/STEM/`
/// with several, `out/STEM/` under the working directory without `out`); `None`
/// (after printing why) when two scenarios would share a directory, one read
/// from standard input has no `out`, one's name leaves no directory name
/// (`...yaml`: `..`), or the set written there, whose files are
/// `replaces`, would replace or remove a file the command reads (a
/// `counterexample.yaml` run with `--out` its own folder, the `--template`
/// set's `report.html` run with `--out` the set's folder).
pub fn evidence_dirs<'a>(
    out: Option<&Path>,
    inputs: impl IntoIterator<Item = &'a Input>,
    replaces: &[&str],
    template: Option<&Path>,
) -> Option<Vec<PathBuf>> {
    let inputs: Vec<&Input> = inputs.into_iter().collect();
    if out.is_none()
        && let Some(input) = inputs.iter().find(|i| i.is_stdin())
    {
        stderr!(
            "{}: error: a scenario read from standard input has no file name to name its evidence directory after; give --out DIR",
            input.name
        );
        return None;
    }
    let named = |input: &Input| {
        let dir = match out {
            Some(out) => stem(&input.path).map(|stem| out.join(stem)),
            None => default_dir(&input.path),
        };
        if dir.is_none() {
            stderr!(
                "{}: error: its name without the extension is `.` or `..`, which cannot name its evidence \
                 directory; rename the file{}",
                input.name,
                if out.is_none() { " or give --out DIR" } else { "" }
            );
        }
        dir
    };
    let dirs: Vec<PathBuf> = match (out, inputs.len()) {
        (Some(out), 1) => vec![out.to_path_buf()],
        _ => inputs.iter().map(|i| named(i)).collect::<Option<_>>()?,
    };
    let mut seen = HashSet::new();
    for (dir, input) in dirs.iter().zip(&inputs) {
        if !seen.insert(dir) {
            stderr!(
                "{}: error: its evidence would overwrite another scenario's in {}; run the files separately with --out",
                input.name,
                dir.display()
            );
            return None;
        }
        let replaced = replaced_input(dir, input, replaces).or_else(|| replaced_template(dir, template?, replaces));
        if let Some(read) = replaced {
            stderr!(
                "{}: error: the evidence written into {} would replace this file, which the command reads; give \
                 another --out",
                read.display(),
                dir.display()
            );
            return None;
        }
    }
    Some(dirs)
}

/// The first file `input` reads (the scenario file, then its imports) that a
/// set of `replaces` written into `dir` would replace, if any.
fn replaced_input(dir: &Path, input: &Input, replaces: &[&str]) -> Option<PathBuf> {
    // Where a file is, with its folder resolved (links, `..`); `None` when the
    // folder does not exist, so that nothing in it can be replaced.
    let resolved = |file: &Path| {
        let folder = file
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        Some(std::fs::canonicalize(folder).ok()?.join(file.file_name()?))
    };
    let dir = std::fs::canonicalize(dir).ok()?;
    let scenario = (!input.is_stdin()).then(|| input.path.clone());
    let imports = input.scenario.imports.iter().map(|import| PathBuf::from(&import.path));
    scenario.into_iter().chain(imports).find(|file| {
        replaces
            .iter()
            .any(|name| resolved(file.as_path()) == Some(dir.join(name)))
    })
}

/// The first file of the template set in `template` that a set of `replaces`
/// written into `dir` would replace, if any: one there when `dir` is the set's
/// folder or a folder in it.
fn replaced_template(dir: &Path, template: &Path, replaces: &[&str]) -> Option<PathBuf> {
    let within = std::fs::canonicalize(dir)
        .ok()?
        .strip_prefix(std::fs::canonicalize(template).ok()?)
        .ok()?
        .to_path_buf();
    replaces
        .iter()
        .map(|name| template.join(&within).join(name))
        .find(|file| file.symlink_metadata().is_ok())
}

#[cfg(test)]
mod tests {
    use sightline_reports::Page;

    use super::*;

    /// The bundled joint junction, 8 s long, with the blind recall asked of
    /// Dempster's rule (point 1) rather than Bayes', at 0.99: it fails there
    /// only, so the recording kept is point 1's.
    fn junction() -> Input {
        let text = include_str!("../scenarios/junction-joint.yaml")
            .replace("duration: 20", "duration: 8")
            .replace(
                "where: { fusion.method: bayes }\n    check: { metric: blind_recall, at_least: 0.5 }",
                "where: { fusion.method: dempster }\n    check: { metric: blind_recall, at_least: 0.99 }",
            );
        let options = sightline_dsl::Options {
            record: true,
            osi: true,
            ..Default::default()
        };
        let scenario = sightline_dsl::compile("junction.yaml", &text, &options).unwrap_or_else(|e| panic!("{e}"));
        Input {
            path: "junction.yaml".into(),
            name: "junction.yaml".into(),
            bytes: text.into_bytes(),
            scenario,
        }
    }

    /// The staged files of the set: name and bytes, by name.
    fn staged(staging: &Staging) -> Vec<(String, Vec<u8>)> {
        let folder = staging.path(RECORDING).parent().unwrap().to_path_buf();
        let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(folder)
            .unwrap()
            .map(|entry| entry.unwrap())
            .filter(|entry| entry.file_name() != "manifest")
            .map(|entry| {
                (
                    entry.file_name().into_string().unwrap(),
                    std::fs::read(entry.path()).unwrap(),
                )
            })
            .collect();
        files.sort();
        files
    }

    /// Recording each point of a shared simulation in its first pass keeps the
    /// judged point's recording and OSI trace byte for byte as simulating that
    /// point again alone writes them, and stages nothing else.
    #[test]
    fn recording_each_point_keeps_what_simulating_the_kept_point_again_writes() {
        let input = junction();
        let scenario = &input.scenario;
        assert!(records_each(scenario));
        let templates = Templates::bundled(Page::Run);
        let reporting = Reporting {
            tool: tool(),
            request: Request {
                seed: None,
                record: true,
                osi: true,
            },
            templates: &templates,
        };
        let record = scenario.record.expect("--record");
        let dir = tempfile::tempdir().unwrap();
        let mut each = Staging::open(&dir.path().join("each"), EVIDENCE_SET).unwrap();
        let (run, verdicts, info) = recorded_each(&input, &reporting, &mut each, record, |sinks| {
            Ok(sightline_engine::simulate_traced_each(scenario, sinks, &mut |_| {}))
        })
        .unwrap();
        let info = info.expect("a recording");
        assert_eq!(info.point, 1, "the blind recall fails at Dempster's rule only");

        let first = sightline_engine::simulate(scenario);
        let again = recorded_point(scenario, record, &sightline_oracles::check(scenario, &first));
        let mut alone = Staging::open(&dir.path().join("alone"), EVIDENCE_SET).unwrap();
        let (run_alone, verdicts_alone, info_alone) = recorded(&input, &reporting, &mut alone, again, |sinks| {
            resimulated(&input, again, first, sinks)
        })
        .unwrap();
        assert_eq!((run, verdicts, Some(info)), (run_alone, verdicts_alone, info_alone));
        let (each, alone) = (staged(&each), staged(&alone));
        let names: Vec<&str> = each.iter().map(|(name, _)| name.as_str()).collect();
        assert_eq!(names, [OSI_TRACE, RECORDING]);
        assert!(each == alone, "the recordings differ");
    }

    /// Up to three points sharing one simulation are recorded in the first
    /// pass; a fourth, or points of separate simulations, are simulated again.
    #[test]
    fn the_first_pass_records_at_most_three_points_of_one_simulation() {
        let records = |fusion: &str, sweep: &str| {
            let text = include_str!("../scenarios/junction-joint.yaml")
                .replace("decision: {", &format!("{fusion}\ndecision: {{"))
                .replace("sweep: { fusion.method: [bayes, dempster] }", sweep);
            let scenario =
                sightline_dsl::compile("j.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
            records_each(&scenario)
        };
        // The sweeps give the method; the file only the hybrid rule's switch.
        let hybrid = "fusion: { switch: { threshold: 10 } }";
        assert!(records(hybrid, "sweep: { fusion.method: [bayes, dempster, hybrid] }"));
        assert!(!records(
            hybrid,
            "sweep: { fusion.method: [bayes, dempster, hybrid, distance_weighted] }"
        ));
        let sigma = "sweeps: [{ fusion.method: [bayes] }, { localization.position_sigma: [0.1, 0.2] }]";
        assert!(!records("fusion: { method: bayes }", sigma), "two simulations");
    }
}
