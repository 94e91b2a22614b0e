//! What one agent's sensors observe at one step, as an occupancy grid in the world
//! frame placed with the agent's *estimated* pose.
//!
//! For each sensor: rays every `ray_spacing` over the field of view are measured in
//! the true world (how far each runs before an obstacle) and drawn from the
//! estimated sensor pose, marking the cells they cross free. Every other agent
//! whose centre is in range and field of view is looked at with a fan of rays
//! over its outline ([`super::fan`]): its visibility class and visible fraction.
//! One in line of sight (any part of it) is detected with the sensor's detection
//! probability, at its true position plus Gaussian noise σ(d) = base + per_m · d
//! on each axis and with its length and width each off by Gaussian noise of the
//! size σ(d) (never below 10 cm; a pedestrian's circle keeps its diameter's
//! draw). Only the seen part of that measured footprint (placed from the
//! estimated pose) is marked occupied: a cell of the footprint is marked when
//! the fan's ray nearest to its centre's bearing (from the estimated sensor,
//! relative to the bearing of the measured centre) was clear, the rays at the
//! fan's ends standing for everything beyond them. Bearings are taken relative
//! to the object's centre so that the seen side stays on the object when noise
//! moves it. Occupied wins over free where two observations of the agent meet. Finally the agent reports its own
//! footprint at its estimated pose ([`Observed::Own`], occupied to fusion): it
//! knows where it is (up to its localization error), as a V2X sender reports its
//! own state, and its rays, which pass through its own footprint, must not report
//! it as free space. The mark is kept apart from a detection's, so that the
//! metrics can tell self-report from perception.

use rand::RngExt;
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use sightline_dsl::{Agent, Grid, Sensor};

use super::fan::{View, view};
use super::raster::{Raster, box_cells, cell_center, traverse};
use super::sight::{Bodies, Body, Occluders, Outline, Visibility};
use crate::idealisation::Idealisation;
use crate::math::{Point, Pose, Vector};

/// Detections are independent draws.
pub(crate) const DETECTIONS: Idealisation = Idealisation {
    id: "observe.detections",
    text: "A visible object in range and field of view is detected with the sensor's fixed probability, \
           independently at every step and by every sensor, whatever its distance or how much of it shows; \
           no sensor reports an object that is not there.",
};

/// Measurement errors are white and Gaussian.
pub(crate) const NOISE: Idealisation = Idealisation {
    id: "observe.noise",
    text: "A detection's errors of position and size are Gaussian, unbiased and independent from step to \
           step; its heading is exact.",
};

/// Free space is carved on the grid.
pub(crate) const FREE_SPACE: Idealisation = Idealisation {
    id: "observe.free-space",
    text: "Free space is carved along rays `ray_spacing_deg` apart, cell by cell, up to the first building or \
           road user of the true world; a cell belongs to a footprint or a building when its centre lies inside \
           it, and a footprint always holds the cell under its own centre (a body smaller than a cell takes \
           one).",
};

/// Cooperators report their own bodies.
pub(crate) const SELF_REPORT: Idealisation = Idealisation {
    id: "observe.self-report",
    text: "Each cooperating agent marks its own footprint occupied at its estimated pose, as a V2X sender \
           reports its own state. Its true footprint is not counted in `occupied_recall` or `blind_recall` \
           (no sensor had to find it): `self_report_share` and `occupied_recall_with_self_report` count it.",
};

/// What an agent knows of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Observed {
    /// Nothing.
    Unknown,
    /// Seen free along a ray.
    Free,
    /// Covered by a detected object.
    Occupied,
    /// Covered by the observer's own footprint, as it reports it (occupied to
    /// fusion, but no sensor's finding).
    Own,
}

impl Observed {
    /// Whether the cell is reported occupied, by a detection or by self-report.
    pub fn is_occupied(self) -> bool {
        matches!(self, Self::Occupied | Self::Own)
    }
}

/// One agent's observation grid, reused from step to step.
#[derive(Debug)]
pub struct Observation {
    cells: Vec<Observed>,
    touched: Vec<usize>,
    /// Estimated positions of the agent's sensors this step.
    pub sensor_positions: Vec<Point>,
    /// Counts of targets in range and field of view, by visibility, and detections.
    pub sightings: Sightings,
    sighted: Vec<Sighting>,
}

/// One target in range and field of view of one of an agent's sensors at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sighting {
    /// Index of the sensor on the observing agent.
    pub sensor: usize,
    /// Index of the target agent.
    pub target: usize,
    /// Whether the target was in line of sight (any part of it), and what hid
    /// it if not.
    pub visibility: Visibility,
    /// The share of the target's angular extent in line of sight, in [0, 1]:
    /// 0 when hidden, 1 when wholly seen.
    pub visible_fraction: f64,
    /// Where the observer placed the target when it detected it: the measured
    /// footprint in the world frame, seen from the observer's estimated pose (its
    /// `agent` is the target). `None` when hidden or missed.
    pub detected: Option<Body>,
}

/// Targets in range and field of view, by what hides them, over a run or a step.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sightings {
    /// In line of sight, wholly or in part.
    pub los: u64,
    /// Hidden by an occluder.
    pub nlos_static: u64,
    /// Hidden by other agents only.
    pub nlos_dynamic: u64,
    /// Visible targets that were detected.
    pub detected: u64,
    /// The sum of every target's visible fraction (hidden ones add 0).
    pub visible: f64,
}

impl Sightings {
    /// Adds `other`'s counts.
    pub fn add(&mut self, other: Sightings) {
        self.los += other.los;
        self.nlos_static += other.nlos_static;
        self.nlos_dynamic += other.nlos_dynamic;
        self.detected += other.detected;
        self.visible += other.visible;
    }

    /// Targets in range and field of view, whatever hid them.
    pub fn total(&self) -> u64 {
        self.los + self.nlos_static + self.nlos_dynamic
    }
}

/// The distance to `point` when it lies within the range and field of view of a
/// sensor at `pose` (both edges included), `None` otherwise.
pub fn in_view(sensor: &Sensor, pose: Pose, point: Point) -> Option<f64> {
    let offset = point - pose.translation;
    let distance = offset.length();
    let bearing = offset.y.atan2(offset.x) - pose.rotation.angle();
    let off_axis = bearing.sin().atan2(bearing.cos()).abs();
    (distance <= sensor.range && off_axis <= sensor.fov / 2.0).then_some(distance)
}

/// A sensor's pose in its agent's frame.
pub fn mount_pose(sensor: &Sensor) -> Pose {
    Pose::new(Vector::new(sensor.mount_x, sensor.mount_y), sensor.mount_yaw)
}

/// Everything an observation reads from the step.
pub struct StepScene<'a> {
    /// The grid.
    pub grid: &'a Grid,
    /// Occluders for line of sight.
    pub occluders: &'a Occluders,
    /// Footprints of the step.
    pub bodies: &'a Bodies,
    /// Obstacles on the grid.
    pub raster: &'a Raster,
}

impl Observation {
    /// An empty observation of a grid of `cells` cells.
    pub fn new(cells: usize) -> Self {
        Self {
            cells: vec![Observed::Unknown; cells],
            touched: Vec::new(),
            sensor_positions: Vec::new(),
            sightings: Sightings::default(),
            sighted: Vec::new(),
        }
    }

    /// What the agent knows of `cell`.
    pub fn get(&self, cell: usize) -> Observed {
        self.cells[cell]
    }

    /// What the agent knows of the cells `range`, in order.
    pub(super) fn cells(&self, range: std::ops::Range<usize>) -> &[Observed] {
        &self.cells[range]
    }

    /// The cells observed this step (free or occupied), each once.
    pub fn touched(&self) -> &[usize] {
        &self.touched
    }

    /// Every target in range and field of view of a sensor this step, sensor by
    /// sensor: what [`Self::sightings`] counts.
    pub fn sighted(&self) -> &[Sighting] {
        &self.sighted
    }

    /// Marks `cell`: free < own footprint < detected occupied, the stronger mark kept.
    pub(super) fn mark(&mut self, cell: usize, observed: Observed) {
        match (self.cells[cell], observed) {
            (Observed::Unknown, _) => {
                self.cells[cell] = observed;
                self.touched.push(cell);
            }
            (Observed::Free, Observed::Occupied | Observed::Own) | (Observed::Own, Observed::Occupied) => {
                self.cells[cell] = observed;
            }
            _ => {}
        }
    }

    fn clear(&mut self) {
        for &cell in &self.touched {
            self.cells[cell] = Observed::Unknown;
        }
        self.touched.clear();
        self.sensor_positions.clear();
        self.sightings = Sightings::default();
        self.sighted.clear();
    }

    /// Observes the step as agent `index`, truly at `truth`, believing itself at
    /// `estimate`; draws detections from `rng`.
    pub fn observe(
        &mut self,
        scene: &StepScene<'_>,
        (index, agent): (usize, &Agent),
        truth: Pose,
        estimate: Pose,
        rng: &mut ChaCha8Rng,
    ) {
        self.clear();
        for (s, sensor) in agent.sensors.iter().enumerate() {
            let mount = mount_pose(sensor);
            let (true_sensor, estimated_sensor) = (truth * mount, estimate * mount);
            self.sensor_positions.push(estimated_sensor.translation);
            self.carve(scene, index, sensor, true_sensor, estimated_sensor);
            self.detect(scene, index, (s, sensor), true_sensor, estimated_sensor, rng);
        }
        let own = Body::of(index, agent, estimate);
        for cell in box_cells(scene.grid, &own) {
            self.mark(cell, Observed::Own);
        }
    }

    /// Marks free the cells along each ray, as long as it runs in the true world.
    fn carve(&mut self, scene: &StepScene<'_>, index: usize, sensor: &Sensor, truth: Pose, estimate: Pose) {
        let rays = (sensor.fov / sensor.ray_spacing).ceil().max(1.0) as usize;
        let first = -sensor.fov / 2.0 + sensor.ray_spacing / 2.0;
        let (true_heading, estimated_heading) = (truth.rotation.angle(), estimate.rotation.angle());
        // Marking free changes only unknown cells: borrowed apart, the walk
        // keeps the grid's address in a register.
        let (cells, touched) = (&mut self.cells[..], &mut self.touched);
        for i in 0..rays {
            let bearing = first + i as f64 * sensor.ray_spacing;
            let length = scene
                .raster
                .free_length(truth.translation, true_heading + bearing, sensor.range, index);
            let angle = estimated_heading + bearing;
            traverse(
                scene.grid,
                estimate.translation,
                Vector::new(angle.cos(), angle.sin()),
                length,
                |cell, _| {
                    if cells[cell] == Observed::Unknown {
                        cells[cell] = Observed::Free;
                        touched.push(cell);
                    }
                    true
                },
            );
        }
    }

    /// Classifies every other agent in range and field of view of sensor `s` and
    /// marks the footprints of those detected.
    fn detect(
        &mut self,
        scene: &StepScene<'_>,
        index: usize,
        (s, sensor): (usize, &Sensor),
        truth: Pose,
        estimate: Pose,
        rng: &mut ChaCha8Rng,
    ) {
        for target in scene.bodies.all().iter().filter(|b| b.agent != index) {
            let Some(distance) = in_view(sensor, truth, target.pose.translation) else {
                continue;
            };
            let seen = view(
                scene.occluders,
                scene.bodies,
                truth.translation,
                index,
                target,
                sensor.ray_spacing,
            );
            let detected = match seen.visibility {
                Visibility::NlosStatic => {
                    self.sightings.nlos_static += 1;
                    None
                }
                Visibility::NlosDynamic => {
                    self.sightings.nlos_dynamic += 1;
                    None
                }
                Visibility::Los => {
                    self.sightings.los += 1;
                    self.measure(scene.grid, sensor, (truth, estimate), (target, &seen), distance, rng)
                }
            };
            let visible_fraction = seen.fraction();
            self.sightings.visible += visible_fraction;
            self.sighted.push(Sighting {
                sensor: s,
                target: target.agent,
                visibility: seen.visibility,
                visible_fraction,
                detected,
            });
        }
    }

    /// Detects a visible `target` at `distance` with the sensor's probability and
    /// marks the part of its measured footprint that `seen` shows; returns the
    /// whole measured footprint, or `None` when missed.
    fn measure(
        &mut self,
        grid: &Grid,
        sensor: &Sensor,
        (truth, estimate): (Pose, Pose),
        (target, seen): (&Body, &View),
        distance: f64,
        rng: &mut ChaCha8Rng,
    ) -> Option<Body> {
        if rng.random::<f64>() >= sensor.detection_probability {
            return None;
        }
        self.sightings.detected += 1;
        let sigma = sensor.noise_base + sensor.noise_per_m * distance;
        let size_sigma = sensor.size_noise_base + sensor.size_noise_per_m * distance;
        let mut noise = || -> f64 { StandardNormal.sample(&mut *rng) };
        let measured = target.pose.translation + Vector::new(noise(), noise()) * sigma;
        let mut size = (target.half_extents * 2.0 + Vector::new(noise(), noise()) * size_sigma).max(Vector::splat(0.1));
        if target.outline == Outline::Circle {
            size.y = size.x;
        }
        // Where the sensor believes the object is: the measurement seen from the
        // estimated pose instead of the true one.
        let at = estimate * (truth.inverse() * measured);
        let heading = target.pose.rotation.angle() + estimate.rotation.angle() - truth.rotation.angle();
        let placed = Body {
            pose: Pose::new(at, heading),
            half_extents: size / 2.0,
            ..*target
        };
        let bearing = |point: Point| {
            let offset = point - estimate.translation;
            offset.y.atan2(offset.x)
        };
        let centre = bearing(at);
        for cell in box_cells(grid, &placed) {
            if seen.sees(bearing(cell_center(grid, cell)) - centre) {
                self.mark(cell, Observed::Occupied);
            }
        }
        Some(placed)
    }
}

/// An observation holding only `sighted`, for the tests of what reads it.
#[cfg(test)]
impl Observation {
    pub(crate) fn with_sighted(sighted: Vec<Sighting>) -> Self {
        Self {
            sighted,
            ..Self::new(0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sensor at the origin looking along +y, 50 m range, 90° field of view.
    fn sensor(fov_deg: f64) -> (Sensor, Pose) {
        let sensor = Sensor {
            model: "s".into(),
            range: 50.0,
            fov: fov_deg.to_radians(),
            mount_x: 0.0,
            mount_y: 0.0,
            mount_yaw: 0.0,
            detection_probability: 1.0,
            noise_base: 0.0,
            noise_per_m: 0.0,
            size_noise_base: 0.0,
            size_noise_per_m: 0.0,
            velocity_noise_base: 0.0,
            velocity_noise_per_m: 0.0,
            ray_spacing: 0.01,
        };
        (sensor, Pose::new(Vector::ZERO, std::f64::consts::FRAC_PI_2))
    }

    fn at(distance: f64, degrees_off_axis: f64) -> Point {
        let angle = (90.0 + degrees_off_axis).to_radians();
        Vector::new(angle.cos(), angle.sin()) * distance
    }

    #[test]
    fn the_range_edge_is_included() {
        let (sensor, pose) = sensor(90.0);
        assert_eq!(in_view(&sensor, pose, Vector::new(0.0, 50.0)), Some(50.0));
        assert_eq!(in_view(&sensor, pose, Vector::new(0.0, 50.001)), None);
    }

    #[test]
    fn the_field_of_view_ends_at_half_its_angle_on_either_side() {
        let (sensor, pose) = sensor(90.0);
        assert!(in_view(&sensor, pose, at(30.0, 44.9)).is_some());
        assert!(in_view(&sensor, pose, at(30.0, -44.9)).is_some());
        assert!(in_view(&sensor, pose, at(30.0, 45.1)).is_none());
        assert!(in_view(&sensor, pose, at(30.0, -45.1)).is_none());
        assert!(in_view(&sensor, pose, at(30.0, 180.0)).is_none());
    }

    /// A car 20 m north of a car with an all-round sensor, across its line of
    /// sight (x from −2.25 to 2.25, y from 19.1 to 20.9), behind the corner of a
    /// building that covers x < 0, 5 ≤ y ≤ 15 (the fan's case in
    /// [`super::super::fan`]): half of it is seen, and on the 0.5 m grid the
    /// detection marks occupied exactly the 16 cells of its footprint whose
    /// centre lies east of x = 0 (4 columns × 4 rows: its ends lie on cell
    /// centres, and the footprint holds the west one, x = −2.25, not the east
    /// one, x = 2.25), none of the 20 west of it.
    #[test]
    fn only_the_seen_side_of_a_car_half_behind_a_corner_is_marked_occupied() {
        use sightline_dsl::{AgentKind, Motion, Occluder};

        let grid = Grid {
            origin: [-10.0, 0.0],
            cell: 0.5,
            cols: 40,
            rows: 60,
        };
        let building = [Occluder {
            id: "b".into(),
            polygon: vec![[-10.0, 5.0], [0.0, 5.0], [0.0, 15.0], [-10.0, 15.0]],
        }];
        let (mut all_round, heading_north) = sensor(360.0);
        all_round.ray_spacing = 1.0_f64.to_radians();
        let observer = Agent {
            id: "ego".into(),
            kind: AgentKind::Car,
            length: 4.5,
            width: 1.8,
            motion: Motion::Fixed {
                position: [0.0, 0.0],
                heading: heading_north.rotation.angle(),
            },
            connected: true,
            sensors: vec![all_round],
            antenna_m: None,
        };
        let target = Body::of(1, &observer, Pose::new(Vector::new(0.0, 20.0), 0.0));
        let bodies = Bodies::new(vec![Body::of(0, &observer, heading_north), target]);
        let mut raster = Raster::new(grid, &building);
        raster.set_bodies(bodies.all());
        let scene = StepScene {
            grid: &grid,
            occluders: &Occluders::new(&building),
            bodies: &bodies,
            raster: &raster,
        };
        let mut observation = Observation::new(grid.cells());
        let mut rng = <ChaCha8Rng as rand::SeedableRng>::seed_from_u64(0);
        observation.observe(&scene, (0, &observer), heading_north, heading_north, &mut rng);

        let [sighting] = observation.sighted() else {
            panic!("one target in view: {:?}", observation.sighted());
        };
        assert_eq!(sighting.visibility, Visibility::Los);
        approx::assert_relative_eq!(sighting.visible_fraction, 0.5, epsilon = 1e-9);
        let footprint = box_cells(&grid, &target);
        assert_eq!(footprint.len(), 36);
        let (east, west): (Vec<usize>, Vec<usize>) = footprint
            .into_iter()
            .partition(|&cell| cell_center(&grid, cell).x > 0.0);
        assert_eq!((east.len(), west.len()), (16, 20));
        assert!(east.iter().all(|&cell| observation.get(cell) == Observed::Occupied));
        assert!(west.iter().all(|&cell| observation.get(cell) != Observed::Occupied));
    }

    #[test]
    fn an_all_round_sensor_sees_behind_itself() {
        let (sensor, pose) = sensor(360.0);
        for degrees in [0.0, 90.0, 179.9, 180.0, -135.0] {
            assert!(in_view(&sensor, pose, at(30.0, degrees)).is_some(), "{degrees}°");
        }
    }
}
