//! What the evidence adds to a bundled run (issue 6: writing the report and the
//! recording adds at most 20 % to a bundled run's time). The bundled roundabout
//! and urban junction, every sweep point, each measured twice: simulated and
//! checked alone, then as `sightline run --record` does it, the recorded point
//! streamed into run.mcap (in memory) as the engine runs, and results.json,
//! junit.xml and report.html rendered. Each is timed twice: by the process's CPU
//! time (every thread, user and system), steady on a shared machine, and by wall
//! time, what a user waits, which scatters by tens of per cent while other jobs
//! share the 2 cores. Run with
//! `cargo bench -p sightline-reports --bench evidence` (Linux); figures are
//! recorded in docs/performance.md.

use std::hint::black_box;
use std::io::Cursor;
use std::time::{Duration, SystemTime};

use criterion::{Criterion, criterion_group, criterion_main};
use sightline_dsl::{Options, Scenario};
use sightline_engine::{Run, simulate, simulate_traced};
use sightline_oracles::{Verdict, check};
use sightline_reports::mcap::{Recorder, Source};
use sightline_reports::{Evidence, Execution, Page, Provenance, RecordingInfo, Templates, Tool, render, sha256_hex};

/// A bundled scenario as `sightline run --record` compiles it.
struct Bundled {
    file: &'static str,
    text: &'static str,
    scenario: Scenario,
}

impl Bundled {
    fn new(file: &'static str, text: &'static str) -> Self {
        let options = Options {
            record: true,
            ..Options::default()
        };
        let scenario = sightline_dsl::compile(file, text, &options).expect("the bundled scenario is valid");
        Self { file, text, scenario }
    }

    /// The run and its verdicts: no evidence.
    fn checked(&self) -> (Run, Vec<Verdict>) {
        let run = simulate(&self.scenario);
        let verdicts = check(&self.scenario, &run);
        (run, verdicts)
    }

    /// The run recorded and checked, and its evidence rendered, as the CLI
    /// does (less writing the files).
    fn with_evidence(&self) -> (Evidence, Vec<u8>) {
        let scenario = &self.scenario;
        let record = scenario.record.expect("--record records a point");
        let tool = Tool {
            name: "sightline".into(),
            version: env!("CARGO_PKG_VERSION").into(),
            git: "bench".into(),
        };
        let source = Source {
            tool: &tool,
            file: self.file,
            text: self.text,
            seed: None,
            record_flag: true,
        };
        let mut recorder =
            Recorder::new(Cursor::new(Vec::new()), scenario, record, &source).expect("the recording starts");
        let run = simulate_traced(scenario, record.point, &mut recorder, &mut |_| {});
        let verdicts = check(scenario, &run);
        let recording = recorder
            .finish(&run, &verdicts)
            .expect("the recording ends")
            .into_inner();
        let provenance = Provenance {
            tool,
            scenario_path: self.file.into(),
            scenario_sha256: sha256_hex(self.text.as_bytes()),
            scenario_text: self.text.into(),
            recording: Some(RecordingInfo {
                file: "run.mcap".into(),
                sha256: sha256_hex(&recording),
                point: record.point,
                label: scenario.points[record.point].label(),
            }),
            execution: Execution::on_this_machine(1, SystemTime::now(), Duration::ZERO),
        };
        let reproduce = format!("sightline run {} --record", self.file);
        let templates = Templates::bundled(Page::Run);
        let evidence =
            render(scenario, &run, &verdicts, &provenance, &reproduce, &templates).expect("the evidence renders");
        (evidence, recording)
    }
}

/// CPU time this process has used so far, user and system, every thread: from
/// `/proc/self/stat`, in clock ticks of 10 ms (Linux's USER_HZ is 100).
fn cpu_time() -> Duration {
    let stat = std::fs::read_to_string("/proc/self/stat").expect("/proc/self/stat is readable (Linux)");
    // The fields after the command name, which is in parentheses: utime and
    // stime are the 14th and 15th fields of the line.
    let fields: Vec<&str> = stat[stat.rfind(')').expect("the command name closes") + 2..]
        .split(' ')
        .collect();
    let ticks: u64 = fields[11..13]
        .iter()
        .map(|f| f.parse::<u64>().expect("a tick count"))
        .sum();
    Duration::from_millis(ticks * 10)
}

/// What a measurement counts.
#[derive(Clone, Copy)]
enum Clock {
    /// CPU time, every thread: steady whatever else the machine runs.
    Cpu,
    /// Wall time: what a user waits, on a quiet machine.
    Wall,
}

impl Clock {
    fn name(self) -> &'static str {
        match self {
            Clock::Cpu => "cpu",
            Clock::Wall => "wall",
        }
    }

    /// Times `routine` by this clock.
    fn time<T>(self, b: &mut criterion::Bencher<'_>, routine: impl Fn() -> T) {
        match self {
            Clock::Cpu => b.iter_custom(|iterations| {
                let start = cpu_time();
                for _ in 0..iterations {
                    black_box(routine());
                }
                cpu_time() - start
            }),
            Clock::Wall => b.iter(|| black_box(routine())),
        }
    }
}

fn evidence(c: &mut Criterion) {
    let scenarios = [
        Bundled::new(
            "scenarios/roundabout-six-agents.yaml",
            include_str!("../../scenarios/roundabout-six-agents.yaml"),
        ),
        Bundled::new(
            "scenarios/urban-rsu-semantic.yaml",
            include_str!("../../scenarios/urban-rsu-semantic.yaml"),
        ),
    ];
    for bundled in &scenarios {
        let name = bundled.file.trim_start_matches("scenarios/").trim_end_matches(".yaml");
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        for clock in [Clock::Cpu, Clock::Wall] {
            let id = |what: &str| format!("{}/{what}", clock.name());
            group.bench_function(id("simulate_and_check"), |b| clock.time(b, || bundled.checked()));
            group.bench_function(id("with_recording_and_report"), |b| {
                clock.time(b, || bundled.with_evidence())
            });
        }
        group.finish();
    }
}

criterion_group!(benches, evidence);
criterion_main!(benches);
