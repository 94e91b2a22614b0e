//! `sightline run FILE… [--out DIR] [--seed N] [--jobs N] [--record] [--osi] [--template DIR] [--shard K/N]`

use std::time::{Instant, SystemTime};

use sightline_dsl::{Experiment, RecordedPoints, Scenario};
use sightline_reports::{Execution, Page};

use crate::cli::RunArgs;
use crate::evidence::{
    EVIDENCE_SET, Reporting, Request, creatable, evidence_dirs, recorded, recorded_each, recorded_point, records_each,
    resimulated, tool, write_evidence,
};
use crate::exit::Exit;
use crate::input::load_all;
use crate::output::{PointClock, progress};
use crate::staging::Staging;
use crate::summary::refuse_out_of_domain;
use crate::template::templates;
use crate::terminal::stderr;

/// Validates every file and the template set first (reporting every problem;
/// nothing is written if one is invalid), then runs each scenario (or, with
/// `--shard`, its slice) and writes its evidence.
pub fn run(args: &RunArgs) -> anyhow::Result<Exit> {
    let request = Request {
        seed: args.seed,
        record: args.record || args.osi,
        osi: args.osi,
    };
    let inputs = load_all(
        &args.files,
        request.seed,
        (request.record, request.osi),
        Some(args.shard.map_or(1, |shard| shard.count)),
    );
    let templates = templates(args.template.as_deref(), Page::Run);
    let (Some(inputs), Some(templates)) = (inputs, templates) else {
        return Ok(Exit::Invalid);
    };
    // A shard writes only its shard file.
    let replaces = if args.shard.is_some() { &[][..] } else { EVIDENCE_SET };
    let Some(dirs) = evidence_dirs(args.out.as_deref(), &inputs, replaces, args.template.as_deref()) else {
        return Ok(Exit::Invalid);
    };
    if let Some(input) = inputs.iter().find(|i| args.osi && !has_road_users(&i.scenario)) {
        stderr!(
            "{}: error: --osi traces road users, and a field experiment has none: only a world (agents) has an OSI trace",
            input.name
        );
        return Ok(Exit::Invalid);
    }
    let every_point = |scenario: &Scenario| scenario.record.is_some_and(|r| r.points == RecordedPoints::All);
    if let Some(input) = inputs.iter().find(|i| args.osi && every_point(&i.scenario)) {
        stderr!(
            "{}: error: --osi traces one sweep point, and `record.points: all` records every point: \
             name the point to trace (`record: {{ point: N }}`) or leave --osi out",
            input.name
        );
        return Ok(Exit::Invalid);
    }
    let driven = |i: &&crate::input::Input| i.scenario.system_under_test.is_some();
    if let Some(input) = inputs
        .iter()
        .find(|i| driven(i) && (args.record || args.osi || args.shard.is_some()))
    {
        stderr!(
            "{}: error: a run with a system under test is neither recorded nor sharded: leave out --record, --osi \
             and --shard",
            input.name
        );
        return Ok(Exit::Invalid);
    }
    if let Some(input) = inputs.iter().find(|i| i.is_stdin() && args.shard.is_some()) {
        stderr!(
            "{}: error: a shard's scenario must be a file: `sightline merge` reads it again",
            input.name
        );
        return Ok(Exit::Invalid);
    }
    creatable(&dirs)?;
    let pool = worker_pool(args.jobs)?;
    if let Some(shard) = args.shard {
        return super::shard::run_shard(&pool, shard, &inputs, &dirs, request);
    }
    let reporting = Reporting {
        tool: tool(),
        request,
        templates: &templates,
    };
    let mut exit = Exit::Pass;
    for (input, dir) in inputs.iter().zip(&dirs) {
        let scenario = &input.scenario;
        // Opened before the simulation: an unwritable directory is found at once.
        let mut staging = Staging::open(dir, EVIDENCE_SET)?;
        let (started, elapsed) = (SystemTime::now(), Instant::now());
        let bar = progress(scenario.points.len(), &input.name);
        let mut clock = PointClock::new(scenario.points.len());
        let mut done = |points: &[usize]| {
            bar.inc(points.len() as u64);
            clock.done(points);
        };
        let simulated = match (&scenario.system_under_test, scenario.record) {
            // The system is run on the scenario's one point, and judged.
            (Some(system), _) => match crate::system::run(scenario, system, &pool) {
                Ok(run) => {
                    done(&[0]);
                    let verdicts = sightline_oracles::check(scenario, &run);
                    (run, verdicts, None)
                }
                // Its failure is the run's: no verdict but `error`, nothing written.
                Err(error) => {
                    bar.finish_and_clear();
                    stderr!("{}: error: {error}; no requirement is judged", input.name);
                    return Ok(Exit::Internal);
                }
            },
            (None, None) => {
                let run = pool.install(|| sightline_engine::simulate_reporting(scenario, &mut done));
                let verdicts = sightline_oracles::check(scenario, &run);
                (run, verdicts, None)
            }
            // Every point, each recorded as it runs.
            (None, Some(record)) if record.points == RecordedPoints::All => {
                recorded(input, &reporting, &mut staging, record, |recorder| {
                    Ok(pool.install(|| sightline_engine::simulate_traced_all(scenario, recorder, &mut done)))
                })?
            }
            // The point to record is known before the run: recorded as it runs.
            (None, Some(record)) if record.named || scenario.points.len() == 1 => {
                recorded(input, &reporting, &mut staging, record, |recorder| {
                    Ok(pool.install(|| sightline_engine::simulate_traced(scenario, record.point, recorder, &mut done)))
                })?
            }
            // A few points sharing one simulation, which simulating the point to
            // keep again would repeat whole: each point recorded as it runs, the
            // one to keep chosen once the run is judged.
            (None, Some(record)) if records_each(scenario) => {
                recorded_each(input, &reporting, &mut staging, record, |sinks| {
                    Ok(pool.install(|| sightline_engine::simulate_traced_each(scenario, sinks, &mut done)))
                })?
            }
            // The worst point of the first requirement that fails the run: known once the
            // run is judged, then simulated again as it is recorded.
            (None, Some(record)) => {
                let run = pool.install(|| sightline_engine::simulate_reporting(scenario, &mut done));
                let record = recorded_point(scenario, record, &sightline_oracles::check(scenario, &run));
                recorded(input, &reporting, &mut staging, record, |recorder| {
                    pool.install(|| resimulated(input, record, run, recorder))
                })?
            }
        };
        bar.finish_and_clear();
        // A value outside its domain is a defect of the engine: never judged.
        let why = "no correct simulation gives such a value, a defect in sightline; nothing is judged";
        if let Some(exit) = refuse_out_of_domain(&input.name, scenario, &simulated.0, why) {
            return Ok(exit);
        }
        let execution = Execution::on_this_machine(pool.current_num_threads(), started, elapsed.elapsed())
            .with_points(clock.seconds());
        exit = exit.max(write_evidence(input, &reporting, staging, simulated, execution)?);
    }
    Ok(exit)
}

/// Whether every point of `scenario` is a world, whose road users an OSI
/// trace holds (a field experiment has none, and an OSI trace needs a channel).
fn has_road_users(scenario: &Scenario) -> bool {
    scenario
        .points
        .iter()
        .all(|point| matches!(point.setup.experiment, Experiment::World(_)))
}

/// The worker threads: `jobs` of them, or one per core.
pub fn worker_pool(jobs: Option<u16>) -> anyhow::Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.map_or(0, usize::from))
        .build()
        // Its message already ends with the system's reason (its source).
        .map_err(|error| anyhow::anyhow!("failed to start worker threads: {error}"))
}
