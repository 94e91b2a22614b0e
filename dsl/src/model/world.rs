//! A traffic scene: roads resolved into lane polylines, occluders, agents with
//! their motion, sensors and localization, and who shares perception.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{Crosswalk, Driving, InteractionArea, Messages, Semantic, Traffic, V2x};
use crate::geometry::{Arc, Polyline, Xy};

/// A simulated traffic scene (language sections `time` … `semantic`). It measures
/// collective perception (`perception`), the semantic pipeline (`semantic`), or both.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct World {
    /// Time between steps, seconds.
    pub step: f64,
    /// Number of steps; step k is at time k · step.
    pub steps: usize,
    /// Roads, for pictures: id and lane centrelines.
    pub roads: Vec<Road>,
    /// The pairs of roads (indices into `roads`) that a declared route (an
    /// agent's or generated traffic's) drives from the first into the second,
    /// sorted and without repeats. The engine follows the routes' paths; maps
    /// written for other tools (`sightline export`) link the roads with these.
    pub connections: Vec<(usize, usize)>,
    /// Static obstacles to sight.
    pub occluders: Vec<Occluder>,
    /// Every agent: the declared ones in file order, the roadside units of
    /// `traces.rsus`, then the objects of `traces` that no declared agent
    /// replays, in order of first appearance.
    pub agents: Vec<Agent>,
    /// How many agents, at the end of `agents`, are objects imported from
    /// `traces`; each is connected as generated traffic is (`v2x.penetration`).
    pub imported: usize,
    /// Self-localization of connected agents.
    pub localization: Localization,
    /// Collective perception, when measured.
    pub perception: Option<Perception>,
    /// Background traffic.
    pub traffic: Option<Traffic>,
    /// Pedestrian crossings.
    pub crosswalks: Vec<Crosswalk>,
    /// Regions around conflict zones.
    pub interaction_areas: Vec<InteractionArea>,
    /// Regions named for requirements that select road users by area; they
    /// change nothing in the simulation.
    pub areas: Vec<InteractionArea>,
    /// How vehicles keep their distance.
    pub driving: Driving,
    /// V2X assumptions.
    pub v2x: V2x,
    /// The roadside units' semantic pipeline, when measured.
    pub semantic: Option<Semantic>,
    /// Why the run is not all covered by the trace of `traces` (it has no
    /// road user at its start or end), when it is not: a requirement that
    /// would pass here is not exercised.
    pub uncovered: Option<String>,
}

impl World {
    /// Whether it runs collective perception and the semantic pipeline
    /// together, on one scene (a joint world).
    pub fn is_joint(&self) -> bool {
        self.perception.is_some() && self.semantic.is_some()
    }

    /// Whether a vehicle drives by the car-following model (`driving`): a
    /// declared vehicle on its way at a speed above 0 (its target or its
    /// initial one), or generated vehicle traffic; not when every vehicle
    /// replays a trace or stands still.
    pub fn drives_vehicles(&self) -> bool {
        let drives = |a: &Agent| match a.motion {
            Motion::Along {
                target_speed,
                initial_speed,
                ..
            } => a.kind.is_vehicle() && (target_speed > 0.0 || initial_speed > 0.0),
            _ => false,
        };
        self.traffic.as_ref().is_some_and(|t| t.vehicles.is_some()) || self.agents.iter().any(drives)
    }
}

/// A road's lanes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Road {
    /// Its id.
    pub id: String,
    /// Lane centrelines, lane 0 first.
    pub lanes: Vec<Polyline>,
    /// Lane width, metres.
    pub lane_width: f64,
    /// Speed limit, m/s.
    pub speed_limit: f64,
    /// Where its lanes continue across junctions (roads of a SUMO network;
    /// empty for declared roads).
    pub links: Vec<LaneLink>,
    /// The circle lane 0 follows when it is declared as an `arc` or a
    /// `roundabout` (`lanes` hold its chords); `None` for a polyline.
    pub arc: Option<Arc>,
}

/// A lane of one road continuing into a lane of another across a junction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LaneLink {
    /// The lane it leaves, an index into the road's `lanes`.
    pub from_lane: usize,
    /// The road it enters, an index into [`World::roads`].
    pub to_road: usize,
    /// The lane it enters, an index into that road's `lanes`.
    pub to_lane: usize,
    /// The centreline across the junction, from the end of one lane to the start
    /// of the other; empty when the network gives none (a straight join).
    pub via: Vec<Xy>,
}

/// A static obstacle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Occluder {
    /// Its id.
    pub id: String,
    /// Outline, counter-clockwise, first corner not repeated.
    pub polygon: Vec<Xy>,
}

/// Kinds of agent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum AgentKind {
    /// A passenger car (4.5 × 1.8 m).
    Car,
    /// A truck (10 × 2.5 m).
    Truck,
    /// A bus (12 × 2.55 m).
    Bus,
    /// A motorbike (2.2 × 0.8 m).
    Motorbike,
    /// A bicycle and its rider (1.6 × 0.65 m, SUMO's default): a vehicle on
    /// the roads' lanes, as slow and small as a vulnerable road user.
    Bicycle,
    /// A pedestrian (0.6 × 0.6 m).
    Pedestrian,
    /// A roadside unit (0.5 × 0.5 m): fixed, never part of the ground truth.
    Rsu,
}

impl AgentKind {
    /// The default footprint (length, width), metres.
    pub fn footprint(self) -> (f64, f64) {
        match self {
            Self::Car => (4.5, 1.8),
            Self::Truck => (10.0, 2.5),
            Self::Bus => (12.0, 2.55),
            Self::Motorbike => (2.2, 0.8),
            Self::Bicycle => (1.6, 0.65),
            Self::Pedestrian => (0.6, 0.6),
            Self::Rsu => (0.5, 0.5),
        }
    }

    /// A typical height, metres: for what is drawn or exported in 3-D (the
    /// recording's boxes, OpenSCENARIO's bounding boxes); the world is planar,
    /// so nothing is computed with it.
    pub fn height(self) -> f64 {
        match self {
            Self::Car => 1.5,
            Self::Truck => 3.5,
            Self::Bus => 3.2,
            Self::Motorbike => 1.4,
            Self::Bicycle => 1.7,
            Self::Pedestrian => 1.8,
            Self::Rsu => 5.0,
        }
    }

    /// The name as scenario files write it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Car => "car",
            Self::Truck => "truck",
            Self::Bus => "bus",
            Self::Motorbike => "motorbike",
            Self::Bicycle => "bicycle",
            Self::Pedestrian => "pedestrian",
            Self::Rsu => "rsu",
        }
    }

    /// Whether it drives along roads.
    pub fn is_vehicle(self) -> bool {
        matches!(
            self,
            Self::Car | Self::Truck | Self::Bus | Self::Motorbike | Self::Bicycle
        )
    }
}

/// Direction of travel on a roundabout.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Counter-clockwise (right-hand traffic).
    #[default]
    Ccw,
    /// Clockwise (left-hand traffic).
    Cw,
}

/// How an agent estimates its own pose.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PoseFilter {
    /// A Kalman filter on (x, y, θ): prediction from its own motion, update with
    /// each self-reported measurement (seed 000).
    #[default]
    Kalman,
    /// The raw measurement, unfiltered.
    None,
}

/// An agent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Agent {
    /// Its id.
    pub id: String,
    /// What it is.
    pub kind: AgentKind,
    /// Footprint length, metres.
    pub length: f64,
    /// Footprint width, metres.
    pub width: f64,
    /// How it moves.
    pub motion: Motion,
    /// Whether it shares its perception.
    pub connected: bool,
    /// Its sensors.
    pub sensors: Vec<Sensor>,
    /// Its antenna's height, metres, when it is its own (a roadside unit
    /// imported from a SUMO point of interest with a height); `None`: the
    /// channel's height for its kind (`v2x.channel`).
    pub antenna_m: Option<f64>,
}

/// When an agent that follows a path enters the scene, with car following
/// (without it, every agent enters at its start time).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Entry {
    /// At its start time, or as soon after as its place is clear: a declared
    /// agent, or a vehicle arriving at the start of its way, queues.
    Queue,
    /// At its start time or never: a vehicle placed along its way as the run
    /// starts, whose place another road user holds, is not in the scene (it
    /// would otherwise appear there later, out of nowhere).
    OnTime,
}

/// How an agent moves.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// It stands still.
    Fixed {
        /// Position, metres.
        position: Xy,
        /// Heading, radians.
        heading: f64,
    },
    /// It follows a polyline (a vehicle's resolved route, a pedestrian's path).
    Along {
        /// The path.
        path: Polyline,
        /// Speed limits along it: (arc length where the limit ends, limit m/s), in
        /// order; the last entry covers the end. Unlimited for pedestrians.
        limits: Vec<(f64, f64)>,
        /// When it appears, seconds.
        start_time: f64,
        /// Where it appears, metres along the path.
        start_offset: f64,
        /// Speed when it appears, m/s.
        initial_speed: f64,
        /// Desired speed, m/s.
        target_speed: f64,
        /// It never exceeds the speed limit times this factor (1: compliant).
        limit_factor: f64,
        /// Largest change of speed, m/s².
        acceleration: f64,
        /// Whether it may enter later than `start_time` when its place is taken.
        entry: Entry,
    },
    /// It replays recorded samples (a SUMO trace): in the scene from its first
    /// sample to its last, interpolated between them.
    Trace {
        /// The samples, in time order; at least one.
        samples: Vec<TraceSample>,
        /// The polyline through the samples' positions, along which their
        /// offsets are measured; `None` when it never moves.
        path: Option<Polyline>,
        /// The longest time between two samples it is interpolated across,
        /// seconds; across a longer gap it is out of the scene.
        max_gap: f64,
    },
}

impl Motion {
    /// The polyline it moves along: a route's or path's, a trace's; `None` for a
    /// fixed agent or a trace that never moves.
    pub fn path(&self) -> Option<&Polyline> {
        match self {
            Self::Fixed { .. } => None,
            Self::Along { path, .. } => Some(path),
            Self::Trace { path, .. } => path.as_ref(),
        }
    }
}

/// Where a traced agent was at one time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TraceSample {
    /// Scenario time, seconds.
    pub time: f64,
    /// Position of the footprint's centre, metres.
    pub position: Xy,
    /// Heading, radians counter-clockwise from +x.
    pub heading: f64,
    /// Speed, m/s.
    pub speed: f64,
    /// Distance travelled along its path since its first sample, metres.
    pub offset: f64,
    /// The speed limit of the lane it is on, m/s (infinite when not known).
    pub limit: f64,
}

/// A sensor on an agent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensor {
    /// The sensor model's id.
    pub model: String,
    /// Range, metres.
    pub range: f64,
    /// Horizontal field of view, radians (≤ 2π).
    pub fov: f64,
    /// Mount forward of the agent's centre, metres.
    pub mount_x: f64,
    /// Mount left of the agent's centre, metres.
    pub mount_y: f64,
    /// Mount yaw relative to the agent's heading, radians.
    pub mount_yaw: f64,
    /// Detection probability of a visible object in range.
    pub detection_probability: f64,
    /// σ of position error at distance 0, metres.
    pub noise_base: f64,
    /// Growth of σ per metre.
    pub noise_per_m: f64,
    /// σ of length and width error at distance 0, metres.
    pub size_noise_base: f64,
    /// Growth of the size σ per metre.
    pub size_noise_per_m: f64,
    /// σ of speed error at distance 0, m/s.
    pub velocity_noise_base: f64,
    /// Growth of the speed σ per metre.
    pub velocity_noise_per_m: f64,
    /// Angle between carving rays, radians.
    pub ray_spacing: f64,
}

/// Self-localization.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Localization {
    /// σ of each x and y measurement, metres.
    pub position_sigma: f64,
    /// σ of each heading measurement, radians.
    pub heading_sigma: f64,
    /// The estimator.
    pub filter: PoseFilter,
    /// Process noise of the Kalman filter on x and y, metres per √s.
    pub process_position_sigma: f64,
    /// Process noise on the heading, radians per √s.
    pub process_heading_sigma: f64,
    /// What the Kalman filter's prediction knows of the agent's motion.
    pub odometry: Odometry,
}

impl Localization {
    /// Whether the measurements are exact (both σ are 0): every estimate is
    /// then the true pose, whatever the filter and its odometry.
    pub fn is_exact(&self) -> bool {
        self.position_sigma == 0.0 && self.heading_sigma == 0.0
    }
}

/// The odometry models the pose filter can predict with (`localization.odometry.model`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OdometryModel {
    /// The agent's exact motion since the last step (an idealisation).
    Exact,
    /// Speed and yaw rate read with white noise and a constant bias.
    #[default]
    Noisy,
}

/// What the Kalman filter's prediction knows of the agent's motion between two
/// steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Odometry {
    /// The exact motion.
    Exact,
    /// The motion re-integrated from a speed and a yaw rate read with noise.
    Noisy(OdometryNoise),
}

impl Odometry {
    /// The model chosen.
    pub fn model(&self) -> OdometryModel {
        match self {
            Self::Exact => OdometryModel::Exact,
            Self::Noisy(_) => OdometryModel::Noisy,
        }
    }
}

/// The errors of a speed and a yaw-rate reading, one of each per step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OdometryNoise {
    /// σ of each step's speed reading, m/s.
    pub speed_sigma: f64,
    /// Scale error of the speed reading, a fraction of the true speed (0.01:
    /// it reads 1 % fast).
    pub speed_bias: f64,
    /// σ of each step's yaw-rate reading, radians per second.
    pub yaw_rate_sigma: f64,
    /// Offset of the yaw-rate reading, radians per second.
    pub yaw_rate_bias: f64,
}

impl Default for OdometryNoise {
    /// Typical wheel-speed and yaw-rate sensors of a production car; the sources
    /// are in docs/scenario-language.md ("Odometry"): a speed σ of 0.1 m/s per
    /// 0.1 s reading (a 48-tooth tone wheel counted over a step), tyres worn
    /// half-way (+1 %), a yaw-rate σ of 0.1 °/s and the largest in-run bias of
    /// a rate-grade gyroscope, 1000 °/h ≈ 0.28 °/s.
    fn default() -> Self {
        Self {
            speed_sigma: 0.1,
            speed_bias: 0.01,
            yaw_rate_sigma: 0.1_f64.to_radians(),
            yaw_rate_bias: 0.28_f64.to_radians(),
        }
    }
}

/// Collective perception.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Perception {
    /// Index of the ego in [`World::agents`].
    pub ego: usize,
    /// Indices of the agents whose grids are fused, the ego first.
    pub cooperating: Vec<usize>,
    /// P(occupied) of a detected cell.
    pub occupied: f64,
    /// P(occupied) of a cell seen free.
    pub free: f64,
    /// Step whose grids the report pictures.
    pub snapshot_step: usize,
    /// The circle (centre, radius in metres) the metrics count; `None`: the whole grid.
    pub region: Option<(Xy, f64)>,
    /// The messages that carry cooperating agents' grids over the radio
    /// ([`World::v2x`]) when the scenario declares `v2x`; `None`: every grid
    /// reaches the ego whole at the step it is observed.
    pub messages: Option<Messages>,
}
