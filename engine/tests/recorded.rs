//! What a recording of a point chosen after the run is checked against (issue
//! 18's speed target): a semantic point pooling several runs records its first
//! run only, so only that run is simulated again, and it must give, bit for
//! bit, the measurements the pooled outcome kept of it.

use sightline_dsl::{Scenario, compile};
use sightline_engine::outcome::{ObjectRecord, SemanticMetrics};
use sightline_engine::trace::SemanticStep;
use sightline_engine::{Outcome, TraceSink, simulate, simulate_point, simulate_recorded};

/// The bundled urban junction, 30 s long, pooling two runs at two densities.
fn pooled() -> Scenario {
    let text = include_str!("../../scenarios/urban-rsu-semantic.yaml");
    let head = &text[..text.find("\nsweeps:").expect("the junction has sweeps")];
    let text = head
        .replace("duration: 120", "duration: 30")
        .replace("runs: 5 ", "runs: 2 ")
        // The sweep gives the density: the file's would be refused.
        .replace("    density_per_km: 10 ", "    # density_per_km ")
        + "\nsweep: { traffic.vehicles.density_per_km: [5, 15] }\n";
    compile("urban.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Every semantic step a sink is given, as its debug text.
#[derive(Default)]
struct Steps(Vec<String>);

impl TraceSink for Steps {
    fn semantic_step(&mut self, step: &SemanticStep<'_>) {
        self.0.push(format!("{step:?}"));
    }
}

fn metrics(outcome: &Outcome) -> &SemanticMetrics {
    match outcome {
        Outcome::Semantic(metrics) => metrics,
        other => panic!("a semantic world gives semantic metrics, not {other:?}"),
    }
}

#[test]
fn a_pooled_point_is_recorded_and_checked_by_its_first_run_alone() {
    let scenario = pooled();
    let run = simulate(&scenario);
    for point in 0..2 {
        let kept = &run.points[point];
        let pooled = metrics(kept);
        assert_eq!(pooled.runs, 2);
        let first = pooled.first_run.as_deref().expect("a pooled point keeps its first run");
        assert_eq!((first.runs, first.first_run.is_none()), (1, true));
        let run_0: Vec<&ObjectRecord> = pooled.objects.iter().filter(|o| o.run == 0).collect();
        assert_eq!(first.objects.iter().collect::<Vec<_>>(), run_0);
        // Simulated again alone, the first run reports the steps the whole
        // point reports (the other runs report none) and gives what was kept.
        let (mut alone, mut whole) = (Steps::default(), Steps::default());
        let again = simulate_recorded(&scenario, point, &mut alone);
        assert_eq!(simulate_point(&scenario, point, &mut whole), *kept);
        assert!(!alone.0.is_empty() && alone.0 == whole.0, "point {point}");
        assert_eq!(metrics(&again), first);
        assert!(kept.holds_recorded(&again));
        // One count off in the first run is told apart, and so is the whole
        // pooled point given for its first run.
        let mut forged = again.clone();
        let Outcome::Semantic(m) = &mut forged else {
            unreachable!()
        };
        m.bytes += 1;
        assert!(!kept.holds_recorded(&forged));
        assert!(!kept.holds_recorded(kept));
    }
}

/// A point that pools nothing (one run, or a world) is checked whole.
#[test]
fn a_point_of_one_run_is_checked_whole() {
    let text = include_str!("../../scenarios/urban-rsu-semantic.yaml");
    let head = &text[..text.find("\nsweeps:").expect("the junction has sweeps")];
    let text = head
        .replace("duration: 120", "duration: 20")
        .replace("runs: 5 ", "runs: 1 ");
    let scenario = compile("urban.yaml", &text, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let run = simulate(&scenario);
    assert!(metrics(&run.points[0]).first_run.is_none(), "one run is its own first");
    let again = simulate_recorded(&scenario, 0, &mut Steps::default());
    assert_eq!(again, run.points[0]);
    assert!(run.points[0].holds_recorded(&again));
}
