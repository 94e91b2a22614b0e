//! The bundled seed 002 junction (scenarios/urban-rsu-semantic.yaml): one run of
//! 120 s at 10 Hz with dense traffic (issue target: ≥ 100× faster than real time,
//! ≤ 1.2 s, on 2 cores), and one RSU cycle of the four-layer pipeline over 100
//! tracked objects (target < 1 ms). Run with
//! `cargo bench -p sightline-engine --bench semantic`; figures are recorded in
//! docs/performance.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use sightline_dsl::{AgentKind, Experiment, RiskScope, Scenario, Semantic, World};
use sightline_engine::NoTrace;
use sightline_engine::internals::{Areas, EgoPlan, Ldm, Measurement, Occluders, Pipeline, route_map, run_semantic};
use sightline_engine::trace::Point;

/// Route density of the whole-run bench, vehicles per km of each route; the bench
/// prints the scene density it gives.
const DENSITY: f64 = 45.0;

/// Objects in the LDM of the per-cycle bench.
const OBJECTS: usize = 100;

/// The bundled scenario's world and pipeline settings: one run, no sweep.
fn junction() -> (World, Semantic) {
    let text = include_str!("../../scenarios/urban-rsu-semantic.yaml");
    let scenario: Scenario = sightline_dsl::compile("urban-rsu-semantic.yaml", text, &Default::default())
        .expect("the bundled scenario is valid");
    let Experiment::World(world) = &scenario.points[0].setup.experiment else {
        panic!("a world scenario")
    };
    let semantic = world.semantic.clone().expect("the junction runs the semantic pipeline");
    ((**world).clone(), Semantic { runs: 1, ..semantic })
}

fn whole_run(c: &mut Criterion) {
    let (mut world, semantic) = junction();
    if let Some(vehicles) = world.traffic.as_mut().and_then(|t| t.vehicles.as_mut()) {
        vehicles.density_per_km = DENSITY;
    }
    let metrics = run_semantic(11, &world, &semantic, &mut NoTrace);
    let density = metrics.contribution.iter().filter_map(|&(d, _)| d).sum::<f64>() / metrics.contribution.len() as f64;
    println!(
        "route density {DENSITY}/km: mean scene density {density:.1} objects/km, {} road users generated",
        metrics.generated
    );
    let mut group = c.benchmark_group("junction");
    group.sample_size(10);
    group.bench_function("120s_at_10hz_one_run", |b| {
        b.iter(|| run_semantic(11, &world, &semantic, &mut NoTrace))
    });
    group.finish();
}

/// 100 objects within 50 m of the junction, 5 s of history each: vehicles on the
/// scenario's traffic routes, one in ten a pedestrian near a crosswalk. Every
/// vehicle is predicted (`risk_for: all`), the pipeline's worst case.
fn one_cycle(c: &mut Criterion) {
    let (world, semantic) = junction();
    let semantic = Semantic {
        risk_for: RiskScope::All,
        ..semantic
    };
    let routes: Vec<_> = world
        .traffic
        .iter()
        .flat_map(|t| t.vehicles.iter())
        .flat_map(|v| v.routes.iter().map(|r| r.path.clone()))
        .collect();
    let ego_route = world.agents[semantic.ego]
        .motion
        .path()
        .expect("the ego follows a route");
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let now = 60.0;
    let mut ldm = Ldm::default();
    for object in 0..OBJECTS {
        let pedestrian = object % 10 == 9;
        let route = &routes[object % routes.len()];
        // Routes run 500 m in, through the junction, and out: keep to ±45 m of it.
        let centre = route.length() / 2.0;
        let offset = centre + rng.random_range(-45.0..45.0);
        let speed = if pedestrian { 1.3 } else { rng.random_range(3.0..15.0) };
        for k in 0..50 {
            let time = now - f64::from(49 - k) * world.step;
            let at = offset - speed * (now - time);
            let [x, y] = route.point_at(at.max(0.0));
            let position = Point::new(x, y) + if pedestrian { Point::new(3.5, 0.0) } else { Point::ZERO };
            let measurement = Measurement {
                time,
                position,
                speed,
                heading: route.heading_at(at.max(0.0)),
                length: if pedestrian { 0.5 } else { 4.5 },
                width: if pedestrian { 0.5 } else { 1.8 },
                limit: 13.9,
            };
            let kind = if pedestrian {
                AgentKind::Pedestrian
            } else {
                AgentKind::Car
            };
            ldm.record(object + 2, kind, measurement);
        }
    }
    let occluders = Occluders::new(&world.occluders);
    let map = route_map(&world, &semantic);
    let pipeline = Pipeline {
        semantic: &semantic,
        areas: Areas::of(&world),
        occluders: &occluders,
        map: &map,
        ego_route,
        dt: world.step,
    };
    // The ego 20 m before the junction at 8.3 m/s.
    let plan = EgoPlan {
        time: now,
        offset: ego_route.length() / 2.0 - 20.0,
        speed: 8.3,
    };
    let items = pipeline.run(&ldm, now, &plan);
    println!(
        "{OBJECTS} objects in the LDM: {} sent, {} with a predicted conflict",
        items.len(),
        items.iter().filter(|i| i.labels.conflict.is_some()).count()
    );
    let mut group = c.benchmark_group("rsu_cycle");
    group.bench_function("pipeline_100_objects", |b| {
        b.iter(|| pipeline.run(black_box(&ldm), now, &plan))
    });
    group.finish();
}

criterion_group!(benches, whole_run, one_cycle);
criterion_main!(benches);
