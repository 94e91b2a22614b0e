//! The bundled roundabout (scenarios/roundabout-six-agents.yaml) with all six
//! vehicles cooperating: 30 s at 10 Hz over 600 × 600 cells (DESIGN.md target:
//! ≥ 20× faster than real time, ≤ 1.5 s on 2 cores), then one step (t = 12 s)
//! phase by phase: line of sight (a fan of rays over each target's outline),
//! observation (free-space carving and detections),
//! fusion. Run with `cargo bench -p sightline-engine --bench world`; figures are
//! recorded in docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;
use sightline_dsl::{Experiment, Scenario, World};
use sightline_engine::internals::{
    Bodies, CellFusion, Evidence, Kinematics, Observation, Occluders, Raster, StepScene, Visibility, view,
};
use sightline_engine::simulate;

/// The bundled scenario reduced to its nominal point (every connected vehicle
/// cooperating: six with the ego; nominal localization and radio), without
/// requirements.
fn six_agents() -> Scenario {
    let text = include_str!("../../scenarios/roundabout-six-agents.yaml");
    let mut scenario = sightline_dsl::compile("roundabout-six-agents.yaml", text, &Default::default())
        .expect("the bundled scenario is valid");
    let point = scenario
        .points
        .iter()
        .find(|p| p.label().starts_with("v2x.penetration=1 |"))
        .expect("the scenario sweeps the penetration, its nominal point among the studies")
        .clone();
    scenario.points = vec![sightline_dsl::Point {
        index: 0,
        labels: vec![sightline_dsl::Label {
            sweep: None,
            assignments: Vec::new(),
            ..point.labels[0].clone()
        }],
        ..point
    }];
    scenario.sweeps.clear();
    scenario.requirements.clear();
    scenario.references.clear();
    scenario
}

fn run(c: &mut Criterion) {
    let scenario = six_agents();
    let mut group = c.benchmark_group("roundabout");
    group.sample_size(10);
    group.bench_function("30s_at_10hz_six_cooperating", |b| b.iter(|| simulate(&scenario)));
    group.finish();
}

fn step(c: &mut Criterion) {
    let scenario = six_agents();
    let setup = &scenario.points[0].setup;
    let Experiment::World(world) = &setup.experiment else {
        panic!("a world scenario")
    };
    let World { agents, .. } = &**world;
    let perception = world
        .perception
        .as_ref()
        .expect("the roundabout measures collective perception");
    let occupancy = setup.occupancy.as_ref().expect("collective perception fuses a grid");
    let grid = occupancy.grid;
    let mut kinematics = Kinematics::new(agents, world.step, world.driving);
    let mut states = Vec::new();
    for k in 0..=120 {
        kinematics.advance(k, &mut states);
    }
    let mut bodies = Bodies::empty();
    bodies.update(agents, &states);
    let occluders = Occluders::new(&world.occluders);
    let mut raster = Raster::new(grid, &world.occluders);
    raster.set_bodies(bodies.all());
    let scene = StepScene {
        grid: &grid,
        occluders: &occluders,
        bodies: &bodies,
        raster: &raster,
    };
    let cooperating: Vec<usize> = perception
        .cooperating
        .iter()
        .copied()
        .filter(|&i| states[i].is_some())
        .collect();

    let mut group = c.benchmark_group("roundabout_step");
    group.bench_function("line_of_sight_every_sensor_target_pair", |b| {
        b.iter(|| {
            let mut visible = 0;
            for &i in &cooperating {
                let from = states[i].unwrap().position();
                for target in bodies.all().iter().filter(|t| t.agent != i) {
                    let sensor = &agents[i].sensors[0];
                    let in_range = (target.pose.translation - from).length() <= sensor.range;
                    visible += usize::from(
                        in_range
                            && view(&occluders, &bodies, from, i, target, sensor.ray_spacing).visibility
                                == Visibility::Los,
                    );
                }
            }
            visible
        })
    });
    let mut observations: Vec<Observation> = cooperating.iter().map(|_| Observation::new(grid.cells())).collect();
    group.bench_function("observation_carving_and_detections_six_agents", |b| {
        b.iter(|| {
            for (observation, &i) in observations.iter_mut().zip(&cooperating) {
                let pose = states[i].unwrap().pose;
                let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
                observation.observe(&scene, (i, &agents[i]), pose, pose, &mut rng);
            }
        })
    });
    // Fusion of every cell some agent observed, with the scenario's Bayesian rule.
    let mut cells: Vec<usize> = observations.iter().flat_map(|o| o.touched().to_vec()).collect();
    cells.sort_unstable();
    cells.dedup();
    let present: Vec<&dyn Evidence> = observations.iter().map(|o| o as &dyn Evidence).collect();
    let fusion = CellFusion {
        grid: &grid,
        rule: &occupancy.fusion.rule,
        observations: &present,
        occupied: perception.occupied,
        free: perception.free,
    };
    group.bench_function("fusion_of_the_observed_cells", |b| {
        let mut sources = Vec::new();
        b.iter(|| {
            cells
                .iter()
                .filter(|&&cell| fusion.estimate(cell, &mut sources).decision_mass().occupied > 0.5)
                .count()
        })
    });
    group.finish();
    eprintln!(
        "(one step: {} cooperating agents present, {} observed cells)",
        cooperating.len(),
        cells.len()
    );
}

criterion_group!(benches, run, step);
criterion_main!(benches);
