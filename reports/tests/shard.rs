//! Shard files (issue 5 §3): outcomes of every kind come back from CBOR bit for
//! bit, the read-back units make up the run, and damage is caught.

mod common;

use sightline_dsl::{Options, Scenario, compile};
use sightline_engine::{Outcome, assemble, simulate, simulate_unit, units};
use std::time::{Duration, UNIX_EPOCH};

use sightline_reports::{Execution, SHARD_FORMAT, Shard, ShardError, ShardInput, Tool, read_shard, shard_bytes};

use common::WORLD;

fn compiled(text: &str) -> Scenario {
    compile("t.yaml", text, &Options::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The shard holding `units` of `scenario`, simulated.
fn shard(scenario: &Scenario, units: Vec<sightline_engine::Unit>) -> Shard {
    Shard {
        format: SHARD_FORMAT.into(),
        tool: Tool {
            name: "sightline".into(),
            version: "test".into(),
            git: "test".into(),
        },
        files: vec!["t.yaml".into()],
        file: "t.yaml".into(),
        inputs: vec![ShardInput {
            path: "t.yaml".into(),
            sha256: "0".repeat(64),
        }],
        seed: None,
        record: false,
        index: 1,
        count: 1,
        execution: Execution::on_this_machine(2, UNIX_EPOCH, Duration::from_millis(1500)),
        units: units
            .into_iter()
            .map(|unit| {
                let outcomes = simulate_unit(scenario, &unit);
                (unit, outcomes)
            })
            .collect(),
    }
}

/// The small junction with a check over three seeds: world outcomes with their
/// snapshot and per-step tallies, and replicates.
#[test]
fn a_world_run_read_back_from_shards_is_the_run() {
    let text = format!(
        "{WORLD}  - {{ id: SEEDS, text: recall over seeds, check: {{ metric: occupied_recall, at_least: 0.1, seeds: 3 }} }}\n"
    )
    .replace("record: { point: 1, grid_rate: 2, agent_grids: true }\n", "");
    let scenario = compiled(&text);
    let all = units(&scenario);
    assert_eq!(all.len(), 3, "one group at three seeds");
    let (first, rest) = all.split_at(1);
    let parts = [shard(&scenario, first.to_vec()), shard(&scenario, rest.to_vec())];
    let read: Vec<Shard> = parts.iter().map(|s| read_shard(&shard_bytes(s)).unwrap()).collect();
    assert_eq!(read, parts);
    let Outcome::World(world) = &read[0].units[0].1[0] else {
        panic!("a world outcome");
    };
    assert!(world.snapshot.is_some() && !world.by_step.is_empty());
    let run = assemble(&scenario, read.into_iter().flat_map(|s| s.units)).unwrap();
    assert_eq!(run, simulate(&scenario));
}

/// The bundled urban junction, 20 s long, two pooled runs per point: semantic
/// outcomes with their per-step series.
#[test]
fn semantic_outcomes_and_their_series_come_back() {
    let text = include_str!("../../scenarios/urban-rsu-semantic.yaml")
        .replace("duration: 120", "duration: 20")
        .replace("runs: 5 ", "runs: 2 ");
    let scenario = compiled(&text);
    let written = shard(&scenario, units(&scenario)[..1].to_vec());
    let Outcome::Semantic(metrics) = &written.units[0].1[0] else {
        panic!("a semantic outcome");
    };
    assert_eq!(metrics.rsu_only.len(), 2, "one series per pooled run");
    assert!(!metrics.contribution.is_empty());
    assert_eq!(read_shard(&shard_bytes(&written)).unwrap(), written);
}

#[test]
fn infinities_and_nan_come_back() {
    let scenario = compiled(include_str!("../../tests/fixtures/valid/seed-sweep.yaml"));
    let mut written = shard(&scenario, units(&scenario)[..1].to_vec());
    let Outcome::Field(field) = &mut written.units[0].1[0] else {
        panic!("a field outcome");
    };
    field.metrics.mean_uncertainty = Some(f64::NAN);
    field.coverage.mean_sources = f64::INFINITY;
    let Outcome::Field(read) = &read_shard(&shard_bytes(&written)).unwrap().units[0].1[0] else {
        panic!("a field outcome");
    };
    assert!(read.metrics.mean_uncertainty.is_some_and(f64::is_nan));
    assert_eq!(read.coverage.mean_sources, f64::INFINITY);
}

#[test]
fn a_damaged_or_foreign_shard_is_refused() {
    let scenario = compiled(include_str!("../../tests/fixtures/valid/seed-sweep.yaml"));
    let mut written = shard(&scenario, units(&scenario));
    let bytes = shard_bytes(&written);
    let truncated = read_shard(&bytes[..bytes.len() - 10]);
    assert!(matches!(truncated, Err(ShardError::Damaged(_))), "{truncated:?}");
    assert!(matches!(read_shard(b"{\"format\": 1}"), Err(ShardError::Damaged(_))));
    written.format = "sightline-shard/0".into();
    let foreign = read_shard(&shard_bytes(&written)).map(|_| ()).unwrap_err();
    assert_eq!(
        foreign.to_string(),
        "written as `sightline-shard/0`; this sightline reads `sightline-shard/1` (merge with the sightline that wrote it)"
    );
}
