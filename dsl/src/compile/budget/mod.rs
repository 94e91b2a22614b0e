//! The resource model (`docs/limits.md`): each quantity that sizes a point's
//! work or memory, computed as a product in f64 from the compiled setup before
//! anything is simulated or allocated, and refused with its numbers when it
//! exceeds its limit; then the work of the whole run, every point at the seeds
//! its checks need, per process ([`run_budget`]). Together with the ranges of
//! `raw::range` and the limits on grid cells, steps, sensors, sweep points,
//! runs and seeds, these bound every loop and allocation of a run.

use super::context::Context;
use crate::error::ErrorKind;
use crate::model::{
    Check, Experiment, Field, Grid, Layout, Point, Requirement, Semantic, Setup, Traffic, World, grid_every,
};
use crate::path::Path;

mod evidence;

pub(super) use evidence::{Evidence, evidence_budget};

/// The most agents in one run: declared, imported and the traffic expected to
/// be generated. The semantic pipeline compares every pair near the ego.
pub const MAX_AGENTS: f64 = 10_000.0;

/// The most agent-steps of a point: agents × steps × runs, the work of moving,
/// sensing and predicting every agent at every step.
pub const MAX_AGENT_STEPS: f64 = 1.0e8;

/// The most objects an OSI trace of a point holds (`--osi`): agents × steps ×
/// (1 + the cooperating agents' sensors), since each sensor's view repeats the
/// whole ground truth.
pub const MAX_OSI_OBJECTS: f64 = 1.0e8;

/// The most polyline points the roads' lanes and the agents' ways hold (each
/// generated vehicle keeps its route).
pub const MAX_PATH_POINTS: f64 = 1.0e7;

/// The longest total length of all lanes of all roads, metres.
pub const MAX_LANE_LENGTH: f64 = 1.0e7;

/// The most rays the cooperating agents cast in one step.
pub const MAX_RAYS_PER_STEP: f64 = 1.0e6;

/// The most grid cells the rays of a point may cross over the run (rays per
/// step × cells per ray × steps).
pub const MAX_RAY_CELLS: f64 = 1.0e10;

/// The most rays the cooperating agents' sensors may cast at objects over a
/// run, to see how much of each is in view (agents × sensors × the rays a fan
/// casts × steps). In a joint world the agents include the generated traffic,
/// which every cooperating sensor in range looks at.
pub const MAX_SIGHTING_RAYS: f64 = 1.0e9;

/// The most grid cells held at once: the grid's cells × (the cooperating
/// agents' observations + one for the truth and the fused grid + over the
/// radio, the ego's copy of what each other cooperating agent sent).
pub const MAX_CELLS_HELD: f64 = 1.0e8;

/// The most point-in-polygon edge tests that laying the occluders on the
/// grid takes at a point: every cell of an occluder's bounding box (within
/// the grid) against every edge of its outline, for each run.
pub const MAX_OCCLUDER_TESTS: f64 = 1.0e10;

/// The most mass vectors the field experiment draws at a point (sensors × the
/// cells within a sensor's range).
pub const MAX_FIELD_DRAWS: f64 = 1.0e9;

/// The most looks a semantic world's sensors take at a point: each sensor of
/// the ego and of the RSUs at each agent at each step of each run (a range and
/// field-of-view test, and at most one ray).
pub const MAX_SENSOR_LOOKS: f64 = 1.0e9;

/// The most samples of one predicted trajectory (`semantic.horizon` / `time.step`).
pub const MAX_PREDICTION_SAMPLES: f64 = 10_000.0;

/// The most agent-steps a recording holds: agents × steps, summed over the
/// recorded points (agents as the run counts them: declared, imported and the
/// traffic expected, so more than are in the scene at once). Each agent in the
/// scene is a frame and a speed at every step (`/tf`, `/sightline/speeds`),
/// and a box when the agents in the scene change (`/scene/agents`): some 36
/// bytes of the file each, measured at the bundled junction (docs/recording.md;
/// 80 before recording format 5), so at most about 0.4 GB.
pub const MAX_RECORDED_AGENT_STEPS: f64 = 1.0e7;

/// The most grid cells a recording holds: the grid's cells × the grids
/// recorded (the fused grid, and each cooperating agent's with
/// `agent_grids`), summed over the recorded points. Each grid is cropped to
/// the cells it holds, 8 bytes a cell before compression at most, so at most
/// 8 GB before compression; the bundled roundabout's every point holds 1.8e8.
pub const MAX_RECORDED_GRID_CELLS: f64 = 1.0e9;

/// Checks the size of a recording of `points` (every one of them with `all`,
/// else the largest, which the run may choose) at `grid_rate` grids a second;
/// returns whether it is within the limits.
pub(super) fn recording_budget(
    ctx: &mut Context<'_>,
    path: &Path,
    points: &[&Point],
    all: bool,
    grid_rate: f64,
    agent_grids: bool,
) -> bool {
    let sizes = points.iter().filter_map(|point| {
        let Experiment::World(world) = &point.setup.experiment else {
            return None;
        };
        let agent_steps = agent_count(world) * world.steps as f64;
        let grids = match (&point.setup.occupancy, &world.perception, grid_every(point, grid_rate)) {
            (Some(occupancy), Some(perception), Some(every)) => {
                let per_grid = if agent_grids {
                    1.0 + perception.cooperating.len() as f64
                } else {
                    1.0
                };
                occupancy.grid.cells() as f64 * (world.steps.div_ceil(every) as f64) * per_grid
            }
            _ => 0.0,
        };
        Some((agent_steps, grids))
    });
    let (agent_steps, cells) = if all {
        sizes.fold((0.0, 0.0), |(a, c), (x, y)| (a + x, c + y))
    } else {
        sizes.fold((0.0_f64, 0.0_f64), |(a, c), (x, y)| (a.max(x), c.max(y)))
    };
    let which = if all {
        "over the recorded points"
    } else {
        "at the recorded point"
    };
    limit(
        ctx,
        path,
        agent_steps,
        MAX_RECORDED_AGENT_STEPS,
        &format!("agent-steps recorded {which} (agents × steps)"),
        "record one point, a shorter run or less traffic",
    ) && limit(
        ctx,
        path,
        cells,
        MAX_RECORDED_GRID_CELLS,
        &format!("grid cells recorded {which} (cells × grids recorded)"),
        "record fewer grids (`grid_rate`, `agent_grids`), one point, or use larger cells",
    )
}

/// The most work one process may do, in points at the per-point work limits
/// (agent-steps, grid cells crossed by rays, rays cast at objects, looks at
/// objects, mass vectors drawn): the sum, over the sweep points and the seeds their checks
/// run them at, of each point's [`load`].
pub const MAX_RUN_LOAD: f64 = 100.0;

/// A point's work: its largest share of a per-point work limit (1 at the
/// limit). [`MAX_RUN_LOAD`] bounds their sum over what one process simulates.
pub fn load(setup: &Setup) -> f64 {
    let grid = setup.occupancy.as_ref().map(|o| &o.grid);
    match (&setup.experiment, grid) {
        (Experiment::Field(field), Some(grid)) => field_draws(field, grid) / MAX_FIELD_DRAWS,
        (Experiment::Field(_), None) => 0.0,
        (Experiment::World(world), grid) => {
            let (agents, steps) = (agent_count(world), world.steps as f64);
            let moving = agents * steps * runs(world) / MAX_AGENT_STEPS;
            let looks = (world.semantic.as_ref()).map_or(0.0, |s| sensor_looks(world, s, agents) / MAX_SENSOR_LOOKS);
            let rays = grid.and_then(|grid| ray_work(world, grid));
            rays.map_or(moving.max(looks), |rays| {
                moving
                    .max(looks)
                    .max(rays.cells * steps / MAX_RAY_CELLS)
                    .max(rays.fans * agents * steps / MAX_SIGHTING_RAYS)
            })
        }
    }
}

/// Checks the work of simulating `points`, each at its own seed and at the
/// seeds the checks over seeds among `requirements` that apply to it need,
/// split over `processes`: at most [`MAX_RUN_LOAD`] a process. Charged to
/// the check with the most seeds when there is one, else to `sweep` (the
/// sweep's key in the file).
pub(super) fn run_budget(
    ctx: &mut Context<'_>,
    points: &[Point],
    requirements: &[Requirement],
    (processes, sweep): (u32, &Path),
) -> bool {
    let seeds = |r: &Requirement| match &r.check {
        Check::Metric {
            over_seeds: Some(over), ..
        } => over.seeds,
        _ => 1,
    };
    let mut replicates = vec![1_u32; points.len()];
    for requirement in requirements {
        for &p in &requirement.points {
            replicates[p] = replicates[p].max(seeds(requirement));
        }
    }
    let total: f64 = (points.iter().zip(&replicates))
        .map(|(point, &n)| load(&point.setup) * f64::from(n))
        .sum();
    let most_seeds = (requirements.iter().enumerate()).max_by_key(|(_, r)| seeds(r));
    let at = match most_seeds {
        Some((i, r)) if seeds(r) > 1 => Path::root().key("requirements").index(i).key("check").key("seeds"),
        _ => sweep.clone(),
    };
    let processes = f64::from(processes.max(1));
    limit(
        ctx,
        &at,
        total / processes,
        MAX_RUN_LOAD,
        &format!(
            "points' worth of work in a process ({}, each at the seeds its checks need{}; a point at the per-point \
             work limits counts 1)",
            match points.len() {
                1 => "1 sweep point".to_string(),
                n => format!("{n} sweep points"),
            },
            if processes > 1.0 { ", shared by the shards" } else { "" }
        ),
        "sweep fewer points, check over fewer `seeds`, or split the run into shards (`sightline run --shard K/N`, \
         each held to the limit, then `sightline merge`)",
    )
}

/// Checks every product of the resource model of one point's setup; returns
/// whether all are within their limits.
pub(super) fn within_budget(ctx: &mut Context<'_>, setup: &Setup) -> bool {
    let grid = setup.occupancy.as_ref().map(|o| &o.grid);
    match (&setup.experiment, grid) {
        (Experiment::Field(field), Some(grid)) => field_budget(ctx, field, grid),
        (Experiment::World(world), grid) => world_budget(ctx, world, grid),
        (Experiment::Field(_), None) => true,
    }
}

fn field_budget(ctx: &mut Context<'_>, field: &Field, grid: &Grid) -> bool {
    limit(
        ctx,
        &Path::root().key("field").key("sensors"),
        field_draws(field, grid),
        MAX_FIELD_DRAWS,
        "mass vectors drawn at a point (sensors × cells within range)",
        "use fewer sensors, a shorter range or larger cells",
    )
}

fn world_budget(ctx: &mut Context<'_>, world: &World, grid: Option<&Grid>) -> bool {
    let root = Path::root();
    let runs = runs(world);
    let lanes = world.roads.iter().flat_map(|r| &r.lanes);
    let lane_points: f64 = lanes.clone().map(|l| l.points().len() as f64).sum();
    let lane_length: f64 = lanes.map(|l| l.length()).sum();
    let declared_points: f64 = world
        .agents
        .iter()
        .map(|a| a.motion.path().map_or(1.0, |p| p.points().len() as f64))
        .sum();
    let (vehicles, pedestrians, traffic_points) = generated_traffic(world);
    let agents = world.agents.len() as f64 + vehicles + pedestrians;
    // The agents are charged to what contributes most of them.
    let agents_at = if vehicles >= pedestrians.max(world.agents.len() as f64) {
        root.key("traffic").key("vehicles").key("density_per_km")
    } else if pedestrians >= world.agents.len() as f64 {
        root.key("traffic").key("pedestrians").key("per_minute")
    } else {
        root.key("agents")
    };
    let mut ok = limit(
        ctx,
        &root.key("roads"),
        lane_length,
        MAX_LANE_LENGTH,
        "metres of lanes",
        "model a smaller area",
    ) & limit(
        ctx,
        &agents_at,
        agents,
        MAX_AGENTS,
        "agents in a run (declared, imported and the traffic expected)",
        "lower the traffic or shorten the run",
    );
    ok = ok
        && limit(
            ctx,
            &agents_at,
            agents * world.steps as f64 * runs,
            MAX_AGENT_STEPS,
            "agent-steps at a point (agents × steps × runs)",
            "lower the traffic, shorten the run, take a longer step or fewer runs",
        ) & limit(
            ctx,
            &root.key("roads"),
            lane_points + declared_points + traffic_points,
            MAX_PATH_POINTS,
            "points on the lanes and the agents' ways",
            "use fewer lanes, larger arcs or less traffic",
        );
    if ctx.osi {
        let views = world.perception.as_ref().map_or(0, |perception| {
            let sensors = |&agent: &usize| world.agents.get(agent).map_or(0, |a| a.sensors.len());
            perception.cooperating.iter().map(sensors).sum::<usize>()
        });
        ok &= limit(
            ctx,
            &agents_at,
            agents * world.steps as f64 * (1.0 + views as f64),
            MAX_OSI_OBJECTS,
            "objects in the OSI trace of a point (agents × steps × (1 + the cooperating agents' sensors))",
            "run without --osi, or use fewer agents or cooperating sensors, or a shorter run",
        );
    }
    if let Some(semantic) = &world.semantic {
        ok &= limit(
            ctx,
            &root.key("semantic").key("horizon"),
            semantic.horizon / world.step,
            MAX_PREDICTION_SAMPLES,
            "samples in a predicted trajectory (horizon / step)",
            "use a shorter horizon or a longer step",
        );
        // Over the agents only when they are within their own limits.
        ok = ok
            && limit(
                ctx,
                &root.key("agents"),
                sensor_looks(world, semantic, agents),
                MAX_SENSOR_LOOKS,
                "looks at objects at a point (the ego's and the RSUs' sensors × agents × steps × runs)",
                "give the ego and the RSUs fewer sensors, lower the traffic, shorten the run or take fewer runs",
            );
    }
    if let (Some(perception), Some(grid)) = (&world.perception, grid) {
        let cooperating = perception.cooperating.len() as f64;
        let received = if perception.messages.is_some() {
            cooperating - 1.0
        } else {
            0.0
        };
        ok &= limit(
            ctx,
            &root.key("grid"),
            grid.cells() as f64 * (cooperating + 1.0 + received),
            MAX_CELLS_HELD,
            "grid cells held (cells × (cooperating agents + 1, + the grids received over the radio))",
            "use larger cells, a smaller grid or fewer cooperating agents",
        );
        ok &= rays_budget(ctx, world, grid, (agents, &agents_at));
    }
    if let Some(grid) = grid {
        ok &= limit(
            ctx,
            &root.key("occluders"),
            occluder_tests(world, grid) * runs,
            MAX_OCCLUDER_TESTS,
            "edge tests laying the occluders on the grid (each occluder's cells on the grid × its corners × runs)",
            "use fewer corners, smaller occluders or larger cells",
        );
    }
    ok
}

/// The edge tests that laying `world`'s occluders on `grid` takes once: the
/// cells of each one's bounding box within the grid × its corners.
fn occluder_tests(world: &World, grid: &Grid) -> f64 {
    // The cells from `lo` to `hi` along an axis starting at `origin`.
    let span = |lo: f64, hi: f64, origin: f64, count: usize| {
        let first = ((lo - origin) / grid.cell).floor().max(0.0);
        let last = ((hi - origin) / grid.cell).floor().min(count as f64 - 1.0);
        (last - first + 1.0).max(0.0)
    };
    world
        .occluders
        .iter()
        .map(|occluder| {
            let (lo, hi) = occluder
                .polygon
                .iter()
                .fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), &[x, y]| {
                    ([lo[0].min(x), lo[1].min(y)], [hi[0].max(x), hi[1].max(y)])
                });
            let cols = span(lo[0], hi[0], grid.origin[0], grid.cols);
            let rows = span(lo[1], hi[1], grid.origin[1], grid.rows);
            cols * rows * occluder.polygon.len() as f64
        })
        .sum()
}

/// The rays the cooperating agents cast per step, and the cells they cross
/// over the run, charged to the sensor model that casts the most; the rays
/// their fans cast at the `agents` of the run (charged where the agents are),
/// at most one fan per sensor and agent a step.
fn rays_budget(ctx: &mut Context<'_>, world: &World, grid: &Grid, (agents, agents_at): (f64, &Path)) -> bool {
    let Some(RayWork {
        rays,
        cells,
        fans,
        busiest: Some(model),
    }) = ray_work(world, grid)
    else {
        return true;
    };
    let at = Path::root().key("sensor_models").key(model).key("ray_spacing_deg");
    limit(
        ctx,
        &at,
        rays,
        MAX_RAYS_PER_STEP,
        "rays per step (cooperating agents' sensors × field of view / ray spacing)",
        "use a coarser `ray_spacing_deg`, a narrower `fov_deg` or fewer cooperating agents",
    ) && limit(
        ctx,
        &at,
        cells * world.steps as f64,
        MAX_RAY_CELLS,
        "grid cells crossed by rays over the run (rays per step × cells per ray × steps)",
        "use a coarser `ray_spacing_deg`, larger cells, a shorter range or fewer steps",
    ) && limit(
        ctx,
        agents_at,
        fans * agents * world.steps as f64,
        MAX_SIGHTING_RAYS,
        "rays cast at objects over the run (per cooperating sensor, its fan's rays × agents × steps)",
        "lower the traffic, shorten the run, use a coarser `ray_spacing_deg` or fewer cooperating agents",
    )
}

/// What the cooperating agents' sensors cast at each step of a world.
struct RayWork<'w> {
    /// Rays cast.
    rays: f64,
    /// Grid cells those rays cross.
    cells: f64,
    /// Rays cast at one object by every sensor's fan.
    fans: f64,
    /// The sensor model that casts the most rays (`None`: no cooperating sensor).
    busiest: Option<&'w str>,
}

/// The rays the cooperating agents of `world` cast per step over `grid`;
/// `None` when the world measures no collective perception.
fn ray_work<'w>(world: &'w World, grid: &Grid) -> Option<RayWork<'w>> {
    let perception = world.perception.as_ref()?;
    let diagonal = (grid.cols as f64).hypot(grid.rows as f64) * grid.cell;
    let mut work = RayWork {
        rays: 0.0,
        cells: 0.0,
        fans: 0.0,
        busiest: None,
    };
    let mut most = 0.0;
    for sensor in perception.cooperating.iter().flat_map(|&a| &world.agents[a].sensors) {
        let cast = (sensor.fov / sensor.ray_spacing).ceil().max(1.0);
        work.rays += cast;
        // A ray crosses about one cell per cell side along it, in both axes.
        work.cells += cast * 2.0 * sensor.range.min(diagonal) / grid.cell;
        // A fan spans an object's extent, less than a half turn.
        work.fans += (std::f64::consts::PI.min(sensor.fov) / sensor.ray_spacing)
            .ceil()
            .clamp(FAN_RAYS.0, FAN_RAYS.1);
        if work.busiest.is_none() || cast > most {
            (work.busiest, most) = (Some(sensor.model.as_str()), cast);
        }
    }
    Some(work)
}

/// The looks a semantic world's sensors take at a point: the ego's and the
/// RSUs' sensors × `agents` × steps × runs.
fn sensor_looks(world: &World, semantic: &Semantic, agents: f64) -> f64 {
    let sensors = |&agent: &usize| world.agents.get(agent).map_or(0, |a| a.sensors.len());
    let looking: usize = std::iter::once(&semantic.ego).chain(&semantic.rsus).map(sensors).sum();
    looking as f64 * agents * world.steps as f64 * runs(world)
}

/// The fewest and the most rays a fan casts at an object (the engine's
/// `world::fan`).
const FAN_RAYS: (f64, f64) = (10.0, 360.0);

/// The mass vectors the field experiment draws at a point: sensors × the
/// cells within a sensor's range.
fn field_draws(field: &Field, grid: &Grid) -> f64 {
    let sensors = match &field.layout {
        Layout::Positions(positions) => positions.len() as f64,
        Layout::Random { count } => *count as f64,
    };
    let in_range = (std::f64::consts::PI * (field.range / grid.cell).powi(2)).min(grid.cells() as f64);
    sensors * in_range
}

/// The runs a world's point pools (`semantic.runs`, else 1).
fn runs(world: &World) -> f64 {
    world.semantic.as_ref().map_or(1.0, |s| f64::from(s.runs))
}

/// The agents of a run of `world`: declared, imported and the traffic
/// expected.
fn agent_count(world: &World) -> f64 {
    let (vehicles, pedestrians, _) = generated_traffic(world);
    world.agents.len() as f64 + vehicles + pedestrians
}

/// The vehicles and pedestrians `world`'s traffic is expected to generate
/// over its run, and the path points they hold (see [`expected_traffic`]).
fn generated_traffic(world: &World) -> (f64, f64, f64) {
    let duration = world.step * world.steps as f64;
    (world.traffic.as_ref())
        .map(|t| expected_traffic(t, world, duration))
        .unwrap_or_default()
}

/// The vehicles and pedestrians the traffic is expected to generate over a
/// run, and the path points they hold: on each route its initial population
/// (density × length) and its inflow (density × entry speed × duration), at
/// each crosswalk its arrivals (rate × duration).
fn expected_traffic(traffic: &Traffic, world: &World, duration: f64) -> (f64, f64, f64) {
    let (mut vehicles, mut points) = (0.0, 0.0);
    if let Some(vehicle_traffic) = &traffic.vehicles {
        let per_m = vehicle_traffic.density_per_km / 1000.0;
        for route in &vehicle_traffic.routes {
            let entry_speed = route.limits.first().map_or(0.0, |&(_, limit)| limit);
            let count = per_m * (route.path.length() + entry_speed * duration);
            vehicles += count;
            points += count * route.path.points().len() as f64;
        }
    }
    let pedestrians = traffic
        .pedestrians
        .as_ref()
        .map_or(0.0, |p| p.per_minute / 60.0 * duration * world.crosswalks.len() as f64);
    (vehicles, pedestrians, points + 2.0 * pedestrians)
}

/// Records a [`ErrorKind::TooLarge`] at `path` unless `value` ≤ `max`; returns whether it is.
pub(super) fn limit(ctx: &mut Context<'_>, path: &Path, value: f64, max: f64, what: &str, remedy: &str) -> bool {
    if value <= max {
        return true;
    }
    ctx.error(
        path,
        ErrorKind::TooLarge(format!(
            "{} {what} exceed the limit of {}; {remedy}",
            figure(value),
            figure(max)
        )),
    );
    false
}

/// A count as people read it: whole below a million, else `3.6e9`.
fn figure(value: f64) -> String {
    if value < 1.0e6 {
        format!("{value:.0}")
    } else {
        format!("{value:.1e}").replace(".0e", "e")
    }
}

#[cfg(test)]
mod tests {
    use super::figure;

    #[test]
    fn figures_are_whole_or_scientific() {
        assert_eq!(figure(12_345.4), "12345");
        assert_eq!(figure(3.6e9), "3.6e9");
        assert_eq!(figure(1.0e8), "1e8");
    }
}
