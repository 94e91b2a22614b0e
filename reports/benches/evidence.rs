//! What the report adds to a bundled run (issues 6 and 18: the report and the
//! recording together add at most 20 % to a bundled run's time): rendering
//! results.json, junit.xml and report.html from each bundled scenario's
//! simulated and checked run, as `sightline run` does (less writing the three
//! files). The whole run, with and without `--record`, is timed as a process;
//! docs/performance.md gives both and how they combine. Each render is timed
//! twice: by the process's CPU time (every thread, user and system), steady on
//! a shared machine, and by wall time, what a user waits. Run with
//! `cargo bench -p sightline-reports --bench evidence` (Linux).

use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, SystemTime};

use criterion::{Criterion, criterion_group, criterion_main};
use sightline_dsl::{Options, Scenario};
use sightline_engine::{Run, simulate};
use sightline_oracles::{Verdict, check};
use sightline_reports::{Evidence, Execution, Page, Provenance, Templates, Tool, render, sha256_hex};

/// The bundled scenarios, by their paths from the workspace's root.
const BUNDLED: [&str; 8] = [
    "scenarios/evidential-field.yaml",
    "scenarios/roundabout-six-agents.yaml",
    "scenarios/urban-rsu-semantic.yaml",
    "scenarios/sumo-grid-semantic.yaml",
    "scenarios/urban-falsify.yaml",
    "scenarios/junction-joint.yaml",
    "scenarios/opendrive-crossroads-semantic.yaml",
    "scenarios/sumo-town-semantic.yaml",
];

/// A bundled scenario, simulated and checked.
struct Bundled {
    file: &'static str,
    text: String,
    scenario: Scenario,
    run: Run,
    verdicts: Vec<Verdict>,
}

impl Bundled {
    fn new(file: &'static str) -> Self {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(file);
        let text = std::fs::read_to_string(&path).expect("the bundled scenario is readable");
        let loader = |path: &Path| std::fs::read(path);
        let options = Options {
            loader: Some(&loader),
            ..Options::default()
        };
        let name = path.to_string_lossy().into_owned();
        let scenario = sightline_dsl::compile(&name, &text, &options).expect("the bundled scenario is valid");
        let run = simulate(&scenario);
        let verdicts = check(&scenario, &run);
        Self {
            file,
            text,
            scenario,
            run,
            verdicts,
        }
    }

    /// results.json, junit.xml and report.html, as the CLI renders them.
    fn rendered(&self) -> Evidence {
        let provenance = Provenance {
            tool: Tool {
                name: "sightline".into(),
                version: env!("CARGO_PKG_VERSION").into(),
                git: "bench".into(),
            },
            scenario_path: self.file.into(),
            scenario_sha256: sha256_hex(self.text.as_bytes()),
            scenario_text: self.text.clone(),
            recording: None,
            execution: Execution::on_this_machine(1, SystemTime::now(), Duration::ZERO),
        };
        let reproduce = format!("sightline run {}", self.file);
        let templates = Templates::bundled(Page::Run);
        render(
            &self.scenario,
            &self.run,
            &self.verdicts,
            &provenance,
            &reproduce,
            &templates,
        )
        .expect("the evidence renders")
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
    for file in BUNDLED {
        let bundled = Bundled::new(file);
        let name = file.trim_start_matches("scenarios/").trim_end_matches(".yaml");
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        for clock in [Clock::Cpu, Clock::Wall] {
            group.bench_function(format!("{}/render", clock.name()), |b| {
                clock.time(b, || bundled.rendered())
            });
        }
        group.finish();
    }
}

criterion_group!(benches, evidence);
criterion_main!(benches);
